//! Mitsuba's `projector`: an image (its `irradiance` texture, times `scale`, in `radiance`) projected
//! from a point through a pinhole along local +z, the image filling the rectangle
//! `[−tan(fov_x/2), tan(fov_x/2)] × [−tan(fov_y/2), tan(fov_y/2)]` of the plane z = 1 (u decreasing
//! with x and v with y, as Mitsuba's perspective projection maps them). Normalised as Mitsuba's: the
//! intensity towards a direction at angle θ from the axis is `π · value(uv) / cos³θ`, so that a plane
//! facing the projector at z = 1 receives `π · value` where the image falls.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{textured, to_local, to_world, LightSample};
use crate::glam::{Vec2, Vec3};
use crate::layout::{Light, SceneView, NONE};
use crate::math::{vec3, PI};
use crate::spectrum::Rgb;

/// The image coordinates of a direction `local` in the projector's frame, or `None` outside the
/// image (or behind the projector).
#[inline]
fn image_uv(light: &Light, local: Vec3) -> Option<Vec2> {
    if !(local.z > 0.0) {
        return None;
    }
    let (tan_x, tan_y) = (light.params[0], light.params[1]);
    let uv = Vec2::new(0.5 - 0.5 * local.x / (local.z * tan_x), 0.5 - 0.5 * local.y / (local.z * tan_y));
    if uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0 {
        Some(uv)
    } else {
        None
    }
}

/// The intensity sent towards the unit world direction `dir`.
pub fn intensity(scene: &SceneView, light: &Light, dir: Vec3) -> Rgb {
    let local = to_local(light, dir);
    match image_uv(light, local) {
        Some(uv) => textured::value(scene, light, uv) * (PI / (local.z * local.z * local.z)),
        None => Rgb::ZERO,
    }
}

/// The direction (world, unit) through image point `uv`, and the solid-angle density of directions
/// drawn so with `uv` uniform on the image: `1 / (area · cos³θ)`.
pub fn direction(light: &Light, uv: Vec2) -> (Vec3, f32) {
    let (tan_x, tan_y, area) = (light.params[0], light.params[1], light.params[3]);
    let local = Vec3::new((1.0 - 2.0 * uv.x) * tan_x, (1.0 - 2.0 * uv.y) * tan_y, 1.0).normalize();
    (to_world(light, local), density(local.z, area))
}

/// `1 / (area · cos³θ)`: the density of directions drawn uniformly over the image.
#[inline]
pub fn density(cos_theta: f32, area: f32) -> f32 {
    if cos_theta > 0.0 && area > 0.0 {
        1.0 / (area * cos_theta * cos_theta * cos_theta)
    } else {
        0.0
    }
}

pub fn sample(scene: &SceneView, light: &Light, p: Vec3) -> LightSample {
    let d = vec3([light.position[0], light.position[1], light.position[2]]) - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return LightSample::none();
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    LightSample {
        wi,
        dist,
        radiance: intensity(scene, light, -wi) / dist2,
        pdf: 1.0,
        delta: true,
        prim: NONE,
        light: NONE,
    }
}
