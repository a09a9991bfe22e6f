//! Directional light (Mitsuba `directional`): irradiance arriving from one direction everywhere.
use super::{beyond_scene, radiance, to_world, LightSample};
use crate::glam::Vec3;
use crate::layout::{Light, NONE};

pub fn sample(light: &Light, p: Vec3) -> LightSample {
    // Local +z is the direction the light travels.
    let wi = -to_world(light, Vec3::Z).normalize();
    LightSample {
        wi,
        dist: beyond_scene(light, p),
        radiance: radiance(light),
        pdf: 1.0,
        delta: true,
        prim: NONE,
        light: NONE,
    }
}
