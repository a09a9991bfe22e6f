//! A renderer-neutral description of a scene, produced by the loaders (Mitsuba XML, OBJ) and turned
//! into kernel buffers by `buffers`.
use caustic_kernel::scene::Material;
use glam::{Mat4, Vec3};

/// Reconstruction filter of the film (Mitsuba's `rfilter`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    Box { radius: f32 },
    Tent { radius: f32 },
    Gaussian { stddev: f32, radius: f32 },
}

impl Filter {
    pub fn radius(&self) -> f32 {
        match *self {
            Filter::Box { radius } | Filter::Tent { radius } | Filter::Gaussian { radius, .. } => radius,
        }
    }

    /// The 1D filter weight at offset `x` (the 2D filter is the product of two).
    pub fn weight(&self, x: f32) -> f32 {
        match *self {
            Filter::Box { radius } => {
                if x >= -radius && x < radius {
                    1.0
                } else {
                    0.0
                }
            }
            Filter::Tent { radius } => (1.0 - x.abs() / radius).max(0.0),
            Filter::Gaussian { stddev, radius } => {
                let alpha = -1.0 / (2.0 * stddev * stddev);
                ((alpha * x * x).exp() - (alpha * radius * radius).exp()).max(0.0)
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    Independent,
    Stratified,
}

#[derive(Clone, Debug)]
pub struct Sensor {
    /// Camera-to-world transform (no scale): local +z looks forward, +x to the image's left.
    pub to_world: Mat4,
    /// Horizontal field of view in degrees.
    pub fov_x: f32,
    pub near_clip: f32,
    pub far_clip: f32,
    pub width: u32,
    pub height: u32,
    pub filter: Filter,
    pub sampler: SamplerKind,
    pub spp: u32,
}

#[derive(Clone, Debug)]
pub struct Integrator {
    /// Mitsuba `max_depth`; -1 = unbounded.
    pub max_depth: i32,
    pub rr_depth: u32,
    pub hide_emitters: bool,
}

impl Default for Integrator {
    fn default() -> Self {
        Integrator { max_depth: -1, rr_depth: 5, hide_emitters: false }
    }
}

#[derive(Clone, Debug)]
pub enum Geometry {
    /// World-space triangles, with optional per-corner shading normals.
    Triangles { triangles: Vec<[Vec3; 3]>, normals: Option<Vec<[Vec3; 3]>> },
    Sphere { center: Vec3, radius: f32 },
}

#[derive(Clone, Debug)]
pub struct Shape {
    /// Where the shape came from, for messages (file:line or a name).
    pub origin: String,
    pub geometry: Geometry,
    /// Index into `Scene::materials`.
    pub material: u32,
    /// Uniform emitted radiance (linear sRGB) of an area emitter on this shape.
    pub emission: Option<[f32; 3]>,
    pub flip_normals: bool,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub sensor: Sensor,
    pub integrator: Integrator,
    pub materials: Vec<Material>,
    pub shapes: Vec<Shape>,
    /// Non-fatal problems found while loading (unsupported elements, clamped values), already printed.
    pub warnings: Vec<String>,
}

/// Look-at transform with Mitsuba's conventions (columns: left, up, forward, origin).
pub fn look_at(origin: Vec3, target: Vec3, up: Vec3) -> Option<Mat4> {
    let dir = (target - origin).normalize_or_zero();
    let left = up.cross(dir).normalize_or_zero();
    if dir == Vec3::ZERO || left == Vec3::ZERO {
        return None;
    }
    let new_up = dir.cross(left);
    Some(Mat4::from_cols(left.extend(0.0), new_up.extend(0.0), dir.extend(0.0), origin.extend(1.0)))
}
