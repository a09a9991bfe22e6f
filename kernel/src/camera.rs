//! Cameras with Mitsuba's sensor conventions: `perspective` (pinhole), `thinlens` and `orthographic`.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use crate::glam::{Vec2, Vec3};
use crate::math::vec3;
use crate::sampling::square_to_concentric_disk;

pub const CAMERA_PERSPECTIVE: u32 = 0;
pub const CAMERA_THIN_LENS: u32 = 1;
pub const CAMERA_ORTHOGRAPHIC: u32 = 2;
/// Mitsuba's `irradiancemeter`: rays leave the points of a shape (`crate::irradiance_meter`, which
/// reads the shape from `Camera::meter_table`); the other fields are unused.
pub const CAMERA_IRRADIANCE_METER: u32 = 3;

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
    /// Irradiance meter: where its shape's primitives start in `tables` (`crate::irradiance_meter`).
    pub meter_table: u32,
    /// Mitsuba's `principal_point_offset_x/y` (perspective only; zero otherwise): the image window's
    /// centre moves by this much of the full film's width and height, towards larger film coordinates
    /// (Mitsuba adds it to the film sample before projecting, so a positive x shows more of the image's
    /// right).
    pub principal_offset: [f32; 2],
    pub _pad: [u32; 2],
}

/// A connection from a scene point to the camera (`Camera::connect`).
#[derive(Clone, Copy)]
pub struct CameraConnection {
    /// Film position (fractions of the full image's width and height, origin top-left).
    pub film: Vec2,
    /// Unit direction from the point towards the camera.
    pub dir: Vec3,
    pub dist: f32,
    /// How much of the segment, at the camera's end, lies closer than the near clip plane: camera
    /// rays start at that plane, so whatever is there hides nothing from them, and a connection's
    /// shadow ray stops there too (0 without a near clip).
    pub clipped: f32,
    /// `We·cos θc / d²`: what the connection contributes per unit of `f·cos` arriving at the camera.
    pub importance: f32,
    /// The point of the camera the connection reaches (the pinhole, or a point of the aperture).
    pub point: Vec3,
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
        let x = (1.0 - 2.0 * (film.x + self.principal_offset[0])) * self.tan_half_x;
        let y = (1.0 - 2.0 * (film.y + self.principal_offset[1])) * self.tan_half_y;
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

    /// Whether light tracing can connect to this camera (pinhole and thin lens; not orthographic).
    #[inline]
    pub fn connectable(&self) -> bool {
        self.kind == CAMERA_PERSPECTIVE || self.kind == CAMERA_THIN_LENS
    }

    /// The camera seen from a world point `p`, for light tracing: `u_lens` picks the point of a thin
    /// lens's aperture the connection reaches (uniformly, as camera rays pick it; ignored by the
    /// pinhole). `None` when `p` is behind the camera, outside the film or the clip range.
    #[inline]
    pub fn connect(&self, p: Vec3, u_lens: Vec2) -> Option<CameraConnection> {
        let lens = if self.kind == CAMERA_THIN_LENS {
            square_to_concentric_disk(u_lens) * self.aperture_radius
        } else {
            Vec2::ZERO
        };
        self.connect_through(p, lens)
    }

    /// `connect` through the aperture point `lens` (local x, y; the origin for the pinhole): where `p`
    /// lands on the film (fractions of width and height) and the importance `We·cos θc / d²` of the
    /// connection, with `We = 1 / (A·cos⁴θc)` normalised over the whole film (`A`: the image plane's
    /// area at unit distance; θc and d measured from the aperture point), so that a pixel of a `W×H`
    /// film receives `1/(W·H)` of it in expectation. For a thin lens the density `1/(π r²)` of the
    /// aperture point cancels the lens's share of `We`, and a fixed aperture point maps directions to
    /// the focus plane as a pinhole there does: the same expression holds.
    pub fn connect_through(&self, p: Vec3, lens: Vec2) -> Option<CameraConnection> {
        if !self.connectable() {
            return None;
        }
        let d = p - vec3(self.origin);
        let local = Vec3::new(d.dot(vec3(self.axis_x)), d.dot(vec3(self.axis_y)), d.dot(vec3(self.axis_z)));
        if !(local.z > 0.0) || local.z < self.near_clip || local.z > self.far_clip {
            return None;
        }
        let aperture = Vec3::new(lens.x, lens.y, 0.0);
        let v = local - aperture;
        // Where the ray from the aperture point through `p` crosses the focus plane, in units of the
        // focus distance (the pinhole's image plane at unit distance when the aperture is the origin).
        let (mut x, mut y) = (v.x / v.z, v.y / v.z);
        if self.kind == CAMERA_THIN_LENS {
            x += lens.x / self.focus_distance;
            y += lens.y / self.focus_distance;
        }
        let film = Vec2::new(
            0.5 * (1.0 - x / self.tan_half_x) - self.principal_offset[0],
            0.5 * (1.0 - y / self.tan_half_y) - self.principal_offset[1],
        );
        if !(film.x >= 0.0 && film.x < 1.0 && film.y >= 0.0 && film.y < 1.0) {
            return None;
        }
        let dist2 = v.length_squared();
        let dist = dist2.sqrt();
        let cos_theta = v.z / dist;
        let area = 4.0 * self.tan_half_x * self.tan_half_y;
        let importance = 1.0 / (area * cos_theta * cos_theta * cos_theta * dist2);
        let point = self.to_world_point(aperture);
        // Camera rays start where they cross the plane z = near_clip (`generate_ray`): that part of
        // the segment, a share near_clip / v.z of it, is the camera's own.
        let clipped = dist * (self.near_clip / v.z);
        Some(CameraConnection { film, dir: (point - p) / dist, dist, clipped, importance, point })
    }

    /// The aperture point (local x, y) of a camera ray starting at world point `origin`.
    #[inline]
    pub fn lens_point_of(&self, origin: Vec3) -> Vec2 {
        let d = origin - vec3(self.origin);
        Vec2::new(d.dot(vec3(self.axis_x)), d.dot(vec3(self.axis_y)))
    }

    #[inline]
    #[allow(clippy::wrong_self_convention)] // a 112-byte camera: by reference, like the other methods
    fn to_world_vector(&self, v: Vec3) -> Vec3 {
        vec3(self.axis_x) * v.x + vec3(self.axis_y) * v.y + vec3(self.axis_z) * v.z
    }

    #[inline]
    #[allow(clippy::wrong_self_convention)] // a 112-byte camera: by reference, like the other methods
    fn to_world_point(&self, p: Vec3) -> Vec3 {
        vec3(self.origin) + self.to_world_vector(p)
    }
}
