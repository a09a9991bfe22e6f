//! A renderer-neutral description of a scene, produced by the loaders (`load`: Mitsuba XML, OBJ)
//! and turned into kernel buffers by `prepare`: its shapes (`shape`) and meshes (`mesh`), instances
//! (`instancing`), sensor, emitters, materials and integrator, the AOVs it asks for, the warnings
//! its loading gave (`warn`) and where f32 precision ends for it (`precision`).
//!
//! Uses no other folder.
pub mod aov;
pub mod instancing;
pub mod mesh;
pub mod precision;
pub mod shape;

pub use shape::{Geometry, Shape};

use anyhow::Result;
use caustic_kernel::layout::{Material, Texture};
use glam::{Mat3, Mat4, Vec3};

/// Reconstruction filter of the film (Mitsuba's `rfilter`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    Box {
        radius: f32,
    },
    Tent {
        radius: f32,
    },
    Gaussian {
        stddev: f32,
        radius: f32,
    },
    /// Mitchell and Netravali's piecewise cubic with parameters `b` and `c`, radius 2 (Mitsuba's
    /// `mitchell`; its `catmullrom` is this with b = 0, c = 1/2). Negative between |x| ≈ 1 and 2.
    Mitchell {
        b: f32,
        c: f32,
    },
    /// A sinc windowed by a wider sinc, `lobes` lobes on each side and as many pixels of radius
    /// (Mitsuba's `lanczos`). Negative on every other lobe.
    Lanczos {
        lobes: u32,
    },
}

impl Filter {
    pub fn radius(&self) -> f32 {
        match *self {
            Filter::Box { radius } | Filter::Tent { radius } | Filter::Gaussian { radius, .. } => radius,
            Filter::Mitchell { .. } => 2.0,
            Filter::Lanczos { lobes } => lobes as f32,
        }
    }

    /// The 1D filter weight at offset `x` (the 2D filter is the product of two). Negative for the
    /// negative lobes of `Mitchell` and `Lanczos`.
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
            Filter::Mitchell { b, c } => mitchell_netravali(b, c, x.abs()),
            Filter::Lanczos { lobes } => {
                let l = lobes as f32;
                if x.abs() >= l {
                    0.0
                } else {
                    sinc(x) * sinc(x / l)
                }
            }
        }
    }
}

/// Mitchell and Netravali's cubic at `t` = |x| ≥ 0: 1 at 0 for b = 0, C¹ everywhere, zero from 2.
fn mitchell_netravali(b: f32, c: f32, t: f32) -> f32 {
    let (t2, t3) = (t * t, t * t * t);
    let k = if t < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * t3 + (-18.0 + 12.0 * b + 6.0 * c) * t2 + (6.0 - 2.0 * b)
    } else if t < 2.0 {
        (-b - 6.0 * c) * t3 + (6.0 * b + 30.0 * c) * t2 - (12.0 * b + 48.0 * c) * t + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    k / 6.0
}

/// sin(πx)/(πx), 1 at 0.
fn sinc(x: f32) -> f32 {
    let px = std::f32::consts::PI * x;
    if px.abs() < 1e-6 {
        1.0
    } else {
        px.sin() / px
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    Independent,
    Stratified,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    Perspective,
    ThinLens {
        aperture_radius: f32,
        focus_distance: f32,
    },
    /// Half extents of the view volume along local x and y.
    Orthographic {
        half_width: f32,
        half_height: f32,
    },
    /// Mitsuba's `radiancemeter`: the radiance along one ray, from the origin along local +z (a
    /// perspective camera whose field of view is zero: every film position gives that ray).
    RadianceMeter,
    /// Mitsuba's `irradiancemeter`: the irradiance averaged over shape `shape` (index into
    /// `Scene::shapes`), measured by rays leaving it (`crate::prepare::irradiance_meter`).
    IrradianceMeter {
        shape: usize,
    },
}

/// The part of the full image that is rendered (Mitsuba's `crop_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

#[derive(Clone, Debug)]
pub struct Sensor {
    pub projection: Projection,
    /// Camera-to-world transform (no scale): local +z looks forward, +x to the image's left.
    pub to_world: Mat4,
    /// Horizontal field of view in degrees.
    pub fov_x: f32,
    pub near_clip: f32,
    pub far_clip: f32,
    /// Mitsuba's `principal_point_offset_x/y` (perspective only): fractions of the film's width and
    /// height by which the image window's centre moves.
    pub principal_point_offset: [f32; 2],
    /// Size of the full image; `crop` selects what is rendered.
    pub width: u32,
    pub height: u32,
    pub crop: Option<Crop>,
    pub filter: Filter,
    pub sampler: SamplerKind,
    pub spp: u32,
    /// How camera samples reach the film (`--film`).
    pub film: FilmMode,
}

/// How camera samples reach the film (`caustic_kernel::film`): splatted into every pixel the filter
/// covers, as Mitsuba's `hdrfilm` does (the default), or each to its own pixel with its offset drawn
/// from the filter, whose noise is uncorrelated between pixels (a denoiser's input) at a higher
/// error per sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum FilmMode {
    #[default]
    Splat,
    /// Filter importance sampling.
    Fis,
}

#[derive(Clone, Debug)]
pub struct Integrator {
    pub kind: IntegratorKind,
    /// Mitsuba `max_depth`; -1 = unbounded.
    pub max_depth: i32,
    pub rr_depth: u32,
    pub hide_emitters: bool,
    /// Vertex merging's radius and its shrinking (`vcm`; read, unused, by the others).
    pub merging: MergeSettings,
    /// `bdpt`'s and `vcm`'s `connection_share`: 0 joins each camera vertex to every vertex of its
    /// light path; `c` in (0, 1] to one of them drawn uniformly, counted `c` in the MIS weights
    /// (`FrameParams::connection_share`); `DEFAULT_CONNECTION_SHARE` where a scene does not say.
    pub connection_share: f32,
    /// `ibpt`'s, `bdpt`'s and `vcm`'s `light_tracing_share`, in (0, 1]: the share of light paths
    /// connected to the camera (`FrameParams::light_tracing_share`); 1 (every one) by default.
    pub light_tracing_share: f32,
    /// `bdpt`'s and `vcm`'s `connection_rate`, in (0, 1]: the share of camera vertices that join
    /// their light path (`FrameParams::connection_rate`); 1 (every one) by default.
    pub connection_rate: f32,
    /// Run `ibpt`'s, `bdpt`'s or `vcm`'s own kernel even in a scene where no light path can start
    /// (every emitter at infinity), where by default `path`'s kernel renders their estimator
    /// (`prepare::buffers::kernel_kind`); `--own-kernel`.
    pub own_kernel: bool,
}

/// `connection_share` where a scene does not give one. Measured on one lent H200 (BENCHMARKS.md,
/// "One light vertex per camera vertex"): at 0.5 `bdpt` and `vcm` ran the Cornell box 1.48-1.55x
/// faster than joining every vertex (0), the seed's scenes and the caustics seen through glass and
/// water 1.0-1.16x, each at the same error to within 2%; 0.25 ran as fast with errors no lower.
pub const DEFAULT_CONNECTION_SHARE: f32 = 0.5;

impl Default for Integrator {
    fn default() -> Self {
        Integrator {
            kind: IntegratorKind::Path,
            max_depth: -1,
            rr_depth: 5,
            hide_emitters: false,
            merging: MergeSettings::default(),
            connection_share: DEFAULT_CONNECTION_SHARE,
            light_tracing_share: 1.0,
            connection_rate: 1.0,
            own_kernel: false,
        }
    }
}

/// `vcm`'s merging radius: the first pass's, absolute (`radius`) or as a fraction of the scene's
/// bounding sphere's radius (`radius_factor`); later passes shrink it by Knaus and Zwicker's
/// progressive rule with `alpha`.
#[derive(Clone, Copy, Debug)]
pub struct MergeSettings {
    pub radius: Option<f32>,
    pub radius_factor: f32,
    pub alpha: f32,
}

impl Default for MergeSettings {
    /// SmallVCM's defaults: 0.3% of the scene's radius, `alpha` 0.75.
    fn default() -> Self {
        MergeSettings { radius: None, radius_factor: 0.003, alpha: 0.75 }
    }
}

/// An integrator chosen on the command line (`--integrator`), overriding the scene's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum IntegratorChoice {
    /// Path tracing with next-event estimation.
    Path,
    /// Direct illumination, one light and one BSDF sample per shading point.
    Direct,
    /// Light tracing (Mitsuba's `ptracer`).
    Ptracer,
    /// Path tracing and light tracing combined by MIS (instant bidirectional path tracing).
    Ibpt,
    /// Bidirectional path tracing: every connection of a light path and a camera path, by MIS.
    Bdpt,
    /// Vertex connection and merging: bidirectional path tracing and photon mapping, by MIS.
    Vcm,
}

impl Integrator {
    /// The scene's integrator with its kind replaced by `choice`; `max_depth`, `rr_depth` and
    /// `hide_emitters` carry over (`direct` has its own depth of 2).
    pub fn overridden(self, choice: IntegratorChoice) -> Integrator {
        match choice {
            IntegratorChoice::Path => Integrator { kind: IntegratorKind::Path, ..self },
            IntegratorChoice::Ptracer => Integrator { kind: IntegratorKind::Ptracer, ..self },
            IntegratorChoice::Ibpt => Integrator { kind: IntegratorKind::Ibpt, ..self },
            IntegratorChoice::Bdpt => Integrator { kind: IntegratorKind::Bdpt, ..self },
            IntegratorChoice::Vcm => Integrator { kind: IntegratorKind::Vcm, ..self },
            IntegratorChoice::Direct => Integrator {
                kind: IntegratorKind::Direct { emitter_samples: 1, bsdf_samples: 1 },
                max_depth: 2,
                ..self
            },
        }
    }

    /// The kind a render with `--integrator choice` (none: the scene's own) runs.
    pub fn kind_under(&self, choice: Option<IntegratorChoice>) -> IntegratorKind {
        choice.map_or(self.kind, |c| self.clone().overridden(c).kind)
    }
}

/// Which estimator renders the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    Path,
    /// Direct illumination with this many light and BSDF samples per shading point.
    Direct {
        emitter_samples: u32,
        bsdf_samples: u32,
    },
    /// Light tracing (Mitsuba's `ptracer`).
    Ptracer,
    /// Instant bidirectional path tracing: path tracing and light tracing combined by MIS.
    Ibpt,
    /// Bidirectional path tracing (`caustic_kernel::integrator::bdpt`).
    Bdpt,
    /// Vertex connection and merging (`caustic_kernel::integrator::vcm_grid`, `Integrator::merging`).
    Vcm,
}

/// An emitter not attached to a shape.
#[derive(Clone, Debug)]
pub enum Emitter {
    Point {
        position: Vec3,
        intensity: [f32; 3],
    },
    /// `to_world` maps the beam axis to local +z; angles in degrees.
    Spot {
        to_world: Mat4,
        intensity: [f32; 3],
        cutoff_angle: f32,
        beam_width: f32,
        /// Mitsuba's `texture`: an image spread over the cone, multiplying the intensity.
        texture: Option<u32>,
    },
    /// Mitsuba's `projector`: `to_world` maps the projection axis to local +z; `irradiance` times
    /// `scale` (and the texture, if any); `fov_x` in degrees, `aspect` the image's width / height.
    Projector {
        to_world: Mat4,
        irradiance: [f32; 3],
        texture: Option<u32>,
        fov_x: f32,
        aspect: f32,
    },
    /// `direction` the light travels in.
    Directional {
        direction: Vec3,
        irradiance: [f32; 3],
    },
    Constant {
        radiance: [f32; 3],
    },
    /// A lat-long image (`texture` indexes `Scene::textures`), rotated by `to_world`.
    Envmap {
        texture: u32,
        to_world: Mat3,
        scale: f32,
        /// Mitsuba's `mis_compensation`: sample in proportion to the luminance above the map's mean
        /// (Karlík et al. 2019), leaving the dim directions to BSDF sampling.
        mis_compensation: bool,
    },
}

/// A texture record with its texels (linear RGB, row-major from the top; empty for procedural
/// textures); `buffers` places the texels in the table buffer and sets the record's offset.
#[derive(Clone, Debug)]
pub struct SceneTexture {
    pub record: Texture,
    pub texels: Vec<f32>,
    /// A `mesh_attribute` texture's attribute name and where it was defined.
    pub mesh_attribute: Option<MeshAttributeRef>,
}

/// What a `mesh_attribute` texture reads: the attribute `name` of the shape it is on; `origin` is
/// the texture's file and line.
#[derive(Clone, Debug)]
pub struct MeshAttributeRef {
    pub name: String,
    pub origin: String,
}

impl SceneTexture {
    /// The mean colour (a checkerboard's: of its two colours). A mesh attribute's values are the
    /// shape's, unknown to the texture: its `scale` times a grey ½ stands in, which only sets sampling
    /// weights (the loader refuses it wherever a mean would replace the texture).
    pub fn mean(&self) -> [f32; 3] {
        let r = &self.record;
        if self.mesh_attribute.is_some() {
            return [0.5 * r.color0[0]; 3];
        }
        if r.kind == caustic_kernel::layout::TEXTURE_CHECKERBOARD {
            return [0, 1, 2].map(|c| 0.5 * (r.color0[c] + r.color1[c]));
        }
        let n = (self.texels.len() / 3).max(1) as f64;
        [0, 1, 2].map(|c| (self.texels.iter().skip(c).step_by(3).map(|&v| v as f64).sum::<f64>() / n) as f32)
    }
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub sensor: Sensor,
    pub integrator: Integrator,
    pub materials: Vec<Material>,
    pub shapes: Vec<Shape>,
    /// Shapegroups stored once and the instances placing them (besides `shapes`).
    pub instancing: crate::scene::instancing::Instancing,
    pub emitters: Vec<Emitter>,
    pub textures: Vec<SceneTexture>,
    /// The textured weights of `principled` and `principledthin` records beyond the record's own
    /// slots (`caustic_kernel::bsdf::textured_weights`): such a record's `table` indexes this list
    /// here, and `buffers::build` moves the entry into the table buffer.
    pub weight_tables: Vec<[f32; caustic_kernel::bsdf::textured_weights::SLOTS]>,
    /// Mitsuba's `aov` or `depth` integrator: what is rendered beside (or instead of) the image.
    pub aovs: Option<aov::AovSpec>,
    /// Non-fatal problems found while loading (unsupported elements, clamped values), already printed.
    pub warnings: Vec<String>,
}

impl Scene {
    /// Moves the instances of groups placed fewer than `min_placements` times into `shapes`,
    /// transformed (all of them with `usize::MAX`: the flattened scene, which renders the same image).
    pub fn flatten_instances(&mut self, min_placements: usize) -> Result<()> {
        let mut count = vec![0usize; self.instancing.groups.len()];
        for i in &self.instancing.instances {
            count[i.group] += 1;
        }
        let mut kept = Vec::new();
        for i in std::mem::take(&mut self.instancing.instances) {
            if count[i.group] >= min_placements {
                kept.push(i);
                continue;
            }
            for shape in &self.instancing.groups[i.group] {
                self.shapes.push(instancing::placed(shape, i.to_world, &i.origin)?);
            }
        }
        self.instancing.instances = kept;
        Ok(())
    }
}

/// Prints a loading warning and records it in `warnings` (which becomes `Scene::warnings`). Every
/// loader warns through this, so that what stderr shows and what the scene lists agree.
pub(crate) fn warn(warnings: &mut Vec<String>, message: String) {
    eprintln!("warning: {message}");
    warnings.push(message);
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

/// An RGB colour as the kernel's layout stores it: four floats, the fourth unused. The scene's
/// materials hold it (the loaders build them), and so do the buffers `prepare` builds.
pub(crate) fn rgba(c: [f32; 3]) -> [f32; 4] {
    [c[0], c[1], c[2], 0.0]
}
