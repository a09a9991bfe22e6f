//! Emitters: selection proportional to power, direction sampling and densities for next-event
//! estimation and multiple importance sampling.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

pub mod area;
pub mod directional;
pub mod emission;
pub mod infinite;
pub mod point;
pub mod projector;
pub mod sphere;
pub mod textured;

use crate::features;
use crate::glam::{Vec2, Vec3};
use crate::layout::{
    FrameParams, Light, Primitive, SceneView, LIGHT_AREA, LIGHT_CONSTANT, LIGHT_DIRECTIONAL, LIGHT_ENVMAP,
    LIGHT_POINT, LIGHT_PROJECTOR, LIGHT_SPHERE, LIGHT_SPOT, NONE,
};
use crate::math::max_component;
use crate::math::vec3;
use crate::sampling::sample_cdf;
use crate::spectrum::Rgb;

/// A direction towards a point on an emitter, with what arrives along it.
#[derive(Clone, Copy)]
pub struct LightSample {
    /// Unit direction from the shading point towards the emitter.
    pub wi: Vec3,
    /// Distance to the sampled emitter point (beyond the scene for infinite emitters).
    pub dist: f32,
    /// Radiance arriving at the shading point (for delta emitters: intensity / distance²).
    pub radiance: Rgb,
    /// Solid-angle density at the shading point, including the selection probability; for delta
    /// emitters the selection probability alone.
    pub pdf: f32,
    /// Point, spot and directional emitters: BSDF sampling cannot hit them, so no MIS weight.
    pub delta: bool,
    /// The emitting primitive (which shadow rays ignore), or `NONE`.
    pub prim: u32,
    /// The emitter's index in the light list (set by `sample`).
    pub light: u32,
}

impl LightSample {
    pub fn none() -> Self {
        LightSample {
            wi: Vec3::Z,
            dist: 0.0,
            radiance: Rgb::ZERO,
            pdf: 0.0,
            delta: false,
            prim: NONE,
            light: NONE,
        }
    }
}

/// The emitter's uniform radiance (or intensity, irradiance, envmap scale).
#[inline]
pub fn radiance(light: &Light) -> Rgb {
    vec3([light.radiance[0], light.radiance[1], light.radiance[2]])
}

/// Radiance leaving an emitting surface with normal `n` in direction `w`: area emitters are one-sided.
#[inline]
pub fn emitted(light: &Light, n: Vec3, w: Vec3) -> Rgb {
    if n.dot(w) > 0.0 {
        radiance(light)
    } else {
        Rgb::ZERO
    }
}

/// Radiance leaving the surface point of texture coordinates `uv` (normal `n`) of area emitter
/// `light` in direction `w` (one-sided; textured where the emitter is).
#[inline]
pub fn emitted_at(scene: &SceneView, light: &Light, n: Vec3, w: Vec3, uv: Vec2) -> Rgb {
    if n.dot(w) > 0.0 {
        textured::value(scene, light, uv)
    } else {
        Rgb::ZERO
    }
}

/// `light.to_local` applied to a world vector.
#[inline]
pub(crate) fn to_local(light: &Light, v: Vec3) -> Vec3 {
    let r = light.to_local;
    Vec3::new(
        r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z,
        r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
        r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z,
    )
}

/// The inverse of `to_local` (a rotation, so its transpose).
#[inline]
pub(crate) fn to_world(light: &Light, v: Vec3) -> Vec3 {
    let r = light.to_local;
    Vec3::new(
        r[0][0] * v.x + r[1][0] * v.y + r[2][0] * v.z,
        r[0][1] * v.x + r[1][1] * v.y + r[2][1] * v.z,
        r[0][2] * v.x + r[1][2] * v.y + r[2][2] * v.z,
    )
}

/// How far a shadow ray towards an infinite emitter must reach from `p`: past the scene's bounding
/// sphere (centre and radius in `light.position`).
#[inline]
pub(crate) fn beyond_scene(light: &Light, p: Vec3) -> f32 {
    let centre = vec3([light.position[0], light.position[1], light.position[2]]);
    2.0 * light.position[3].max((p - centre).length())
}

/// Converts the density `1/area` of a point seen at squared distance `dist2` under `cos_light` into
/// a solid-angle density.
#[inline]
fn area_to_solid_angle(area: f32, dist2: f32, cos_light: f32) -> f32 {
    if cos_light <= 0.0 || area <= 0.0 {
        0.0
    } else {
        dist2 / (cos_light * area)
    }
}

/// The light sample for a point `q` (normal `n`) drawn uniformly from an emitting surface of area
/// `area`, as seen from `p`.
pub(crate) fn from_area_sample(light: &Light, p: Vec3, q: Vec3, n: Vec3, area: f32) -> LightSample {
    let d = q - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return LightSample::none();
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let pdf = area_to_solid_angle(area, dist2, n.dot(wi).abs());
    if pdf <= 0.0 {
        return LightSample::none();
    }
    LightSample {
        wi,
        dist,
        radiance: emitted(light, n, -wi),
        pdf,
        delta: false,
        prim: light.prim,
        light: NONE,
    }
}

/// Solid-angle density at `p` of uniform area sampling that produced `hit_p` (normal `hit_n`).
pub(crate) fn area_sample_pdf(area: f32, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let d = hit_p - p;
    let dist2 = d.length_squared();
    if dist2 <= 0.0 {
        return 0.0;
    }
    area_to_solid_angle(area, dist2, hit_n.dot(d).abs() / dist2.sqrt())
}

/// Picks an emitter with probability proportional to its power and samples a direction towards it.
pub fn sample(scene: &SceneView, params: &FrameParams, p: Vec3, u_select: f32, u: Vec2) -> LightSample {
    if params.light_count == 0 {
        return LightSample::none();
    }
    let chosen = sample_cdf(scene.tables, params.light_cdf_offset, params.light_count, u_select);
    let light = scene.lights[chosen.index as usize];
    // Feature tests inside the arms, not as guards: measured faster here (BENCHMARKS.md).
    let uses = |kind: u32| features::has(scene.features, features::light(kind));
    let mut s = match light.kind {
        LIGHT_AREA => {
            if uses(LIGHT_AREA) {
                area::sample(&light, &scene.prims[light.prim as usize], p, u)
            } else {
                LightSample::none()
            }
        }
        LIGHT_SPHERE => {
            if uses(LIGHT_SPHERE) {
                sphere::sample(&light, &scene.prims[light.prim as usize], p, u)
            } else {
                LightSample::none()
            }
        }
        LIGHT_POINT | LIGHT_SPOT => {
            if uses(LIGHT_POINT) || uses(LIGHT_SPOT) {
                point::sample(scene, &light, p)
            } else {
                LightSample::none()
            }
        }
        LIGHT_DIRECTIONAL => {
            if uses(LIGHT_DIRECTIONAL) {
                directional::sample(&light, p)
            } else {
                LightSample::none()
            }
        }
        LIGHT_CONSTANT => {
            if uses(LIGHT_CONSTANT) {
                infinite::sample_constant(&light, p, u)
            } else {
                LightSample::none()
            }
        }
        LIGHT_ENVMAP => {
            if uses(LIGHT_ENVMAP) {
                infinite::sample_envmap(&light, scene, p, u)
            } else {
                LightSample::none()
            }
        }
        LIGHT_PROJECTOR => {
            if uses(LIGHT_PROJECTOR) {
                projector::sample(scene, &light, p)
            } else {
                LightSample::none()
            }
        }
        _ => LightSample::none(),
    };
    // A textured area emitter: the texture at the sampled point (sampling stays uniform by area).
    if (light.kind == LIGHT_AREA || light.kind == LIGHT_SPHERE)
        && textured::is_textured(scene, &light)
        && max_component(s.radiance) > 0.0
    {
        s.radiance = textured::at_surface_point(scene, &light, light.prim, p + s.wi * s.dist);
    }
    s.pdf *= light.pmf;
    s.light = chosen.index;
    s
}

/// Solid-angle density with which `sample` would have produced the direction from `p` to the point
/// `hit_p` (normal `hit_n`) on the emitting primitive of `light`, including the selection probability.
pub fn pdf(light: &Light, prim: &Primitive, p: Vec3, hit_p: Vec3, hit_n: Vec3) -> f32 {
    let pdf = if light.kind == LIGHT_SPHERE {
        sphere::pdf(prim, p, hit_p, hit_n)
    } else {
        area::pdf(prim, p, hit_p, hit_n)
    };
    pdf * light.pmf
}
