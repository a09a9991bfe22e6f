//! Point and spot lights (Mitsuba `point`, `spot`): radiant intensity from one point, falling off with
//! the squared distance; the spot's intensity ramps linearly in angle from the beam width to the cutoff,
//! times its image (`texture`) where it has one (`textured::spot_uv`).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::{radiance, textured, to_local, LightSample};
use crate::glam::Vec3;
use crate::layout::{Light, SceneView, LIGHT_SPOT, NONE};
use crate::math::vec3;
use crate::spectrum::Rgb;

/// Mitsuba's spot profile for a unit direction in the light's frame (beam along +z).
pub fn spot_falloff(light: &Light, local: Vec3) -> f32 {
    let [cos_cutoff, cos_beam, cutoff, inv_transition] = light.params;
    let cos_theta = local.z;
    if cos_theta <= cos_cutoff {
        0.0
    } else if cos_theta >= cos_beam {
        1.0
    } else {
        ((cutoff - cos_theta.clamp(-1.0, 1.0).acos()) * inv_transition).clamp(0.0, 1.0)
    }
}

/// A spot's intensity towards `local` (unit, in its frame): intensity · falloff · image, the image
/// looked up only inside the cone (where its coordinates are finite).
pub fn spot_intensity(scene: &SceneView, light: &Light, local: Vec3) -> Rgb {
    let falloff = spot_falloff(light, local);
    if falloff <= 0.0 {
        return Rgb::ZERO;
    }
    textured::value(scene, light, textured::spot_uv(light, local)) * falloff
}

pub fn sample(scene: &SceneView, light: &Light, p: Vec3) -> LightSample {
    let d = vec3([light.position[0], light.position[1], light.position[2]]) - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return LightSample::none();
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let intensity = if light.kind == LIGHT_SPOT {
        spot_intensity(scene, light, to_local(light, -wi))
    } else {
        radiance(light)
    };
    LightSample { wi, dist, radiance: intensity / dist2, pdf: 1.0, delta: true, prim: NONE, light: NONE }
}
