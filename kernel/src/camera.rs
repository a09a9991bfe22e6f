//! Pinhole perspective camera with Mitsuba's `perspective` sensor conventions.
use crate::math::vec3;
use crate::glam::{Vec2, Vec3};

/// A perspective camera in world space. The axes are the sensor's `to_world` image of the local x, y, z
/// axes: local +z looks into the scene and local +x points to the image's left, so film coordinates
/// increase opposite to x and y (Mitsuba's convention).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Camera {
    pub origin: [f32; 3],
    pub near_clip: f32,
    pub axis_x: [f32; 3],
    /// tan of half the horizontal field of view.
    pub tan_half_x: f32,
    pub axis_y: [f32; 3],
    /// tan of half the vertical field of view.
    pub tan_half_y: f32,
    pub axis_z: [f32; 3],
    pub far_clip: f32,
}

/// A ray with its valid parameter interval.
#[derive(Clone, Copy)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub t_min: f32,
    pub t_max: f32,
}

impl Camera {
    /// The primary ray through `film` (fractions of the image width and height, origin top-left).
    pub fn generate_ray(&self, film: Vec2) -> Ray {
        let x = (1.0 - 2.0 * film.x) * self.tan_half_x;
        let y = (1.0 - 2.0 * film.y) * self.tan_half_y;
        let local = Vec3::new(x, y, 1.0);
        let dir_unnormalized = vec3(self.axis_x) * local.x + vec3(self.axis_y) * local.y + vec3(self.axis_z);
        // Clip planes are perpendicular to the view axis: a depth z lies at distance z·|local| on this ray.
        let len = local.length();
        Ray {
            origin: vec3(self.origin),
            dir: dir_unnormalized.normalize(),
            t_min: self.near_clip * len,
            t_max: self.far_clip * len,
        }
    }
}
