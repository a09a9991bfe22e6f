//! Cameras with Mitsuba's sensor conventions: `perspective` (pinhole), `thinlens` and `orthographic`.
use crate::glam::{Vec2, Vec3};
use crate::math::vec3;
use crate::sampling::square_to_concentric_disk;

pub const CAMERA_PERSPECTIVE: u32 = 0;
pub const CAMERA_THIN_LENS: u32 = 1;
pub const CAMERA_ORTHOGRAPHIC: u32 = 2;

/// A camera in world space. The axes are the sensor's `to_world` image of the local x, y, z axes: local
/// +z looks into the scene and local +x points to the image's left, so film coordinates increase
/// opposite to x and y (Mitsuba's convention).
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
    pub kind: u32,
    /// Thin lens: radius of the aperture disk in local units.
    pub aperture_radius: f32,
    /// Thin lens: distance of the plane in focus along local +z.
    pub focus_distance: f32,
    pub _pad: u32,
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
    /// The primary ray through `film` (fractions of the image width and height, origin top-left);
    /// `u_lens` picks the point on a thin lens's aperture.
    pub fn generate_ray(&self, film: Vec2, u_lens: Vec2) -> Ray {
        let x = (1.0 - 2.0 * film.x) * self.tan_half_x;
        let y = (1.0 - 2.0 * film.y) * self.tan_half_y;
        let (local_origin, local_dir) = if self.kind == CAMERA_ORTHOGRAPHIC {
            // tan_half_* hold the half extents of the view volume.
            (Vec3::new(x, y, 0.0), Vec3::Z)
        } else if self.kind == CAMERA_THIN_LENS {
            let lens = square_to_concentric_disk(u_lens) * self.aperture_radius;
            let aperture = Vec3::new(lens.x, lens.y, 0.0);
            let focus = Vec3::new(x, y, 1.0) * self.focus_distance;
            (aperture, (focus - aperture).normalize())
        } else {
            (Vec3::ZERO, Vec3::new(x, y, 1.0).normalize())
        };
        // Clip planes are perpendicular to the view axis: depth z lies at distance z / dir.z.
        let inv_z = 1.0 / local_dir.z;
        Ray {
            origin: self.to_world_point(local_origin),
            dir: self.to_world_vector(local_dir).normalize(),
            t_min: self.near_clip * inv_z,
            t_max: self.far_clip * inv_z,
        }
    }

    #[inline]
    fn to_world_vector(&self, v: Vec3) -> Vec3 {
        vec3(self.axis_x) * v.x + vec3(self.axis_y) * v.y + vec3(self.axis_z) * v.z
    }

    #[inline]
    fn to_world_point(&self, p: Vec3) -> Vec3 {
        vec3(self.origin) + self.to_world_vector(p)
    }
}
