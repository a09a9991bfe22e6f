//! Sampling where light leaves the emitters, for light tracing: an emitter chosen with the same pmf
//! that next-event estimation uses, a point on it and a direction of emission, with the weight
//! `Le·|cos| / (pmf · p(point) · p(direction))` that the light path starts with.
//!
//! Supported: area emitters on triangles, disks and spheres (uniform by area, cosine-weighted
//! directions; a textured one's texture weights the point it draws; a `directionalarea` emits along
//! the normal alone), point lights (uniform
//! directions), spots (uniform inside the cutoff cone) and projectors (uniform over the image); for
//! plain light tracing also the infinite emitters (directional, constant, envmap), as Mitsuba's
//! `ptracer` traces them: a direction drawn as next-event estimation draws it towards the emitter, and
//! a start uniformly on the disk of the scene's bounding sphere that faces it. (Under IBPT the camera
//! paths alone carry infinite emitters' light: no light path starts there.)
use super::{area, directional, infinite, point, projector, radiance, textured, to_world, LightSample};
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::layout::{
    FrameParams, Light, SceneView, INTEGRATOR_PTRACER, LIGHT_AREA, LIGHT_CONSTANT, LIGHT_DIRECTIONAL,
    LIGHT_ENVMAP, LIGHT_FLAG_DIRECTIONAL_AREA, LIGHT_POINT, LIGHT_PROJECTOR, LIGHT_SPHERE, LIGHT_SPOT, NONE,
};
use crate::math::{vec3, PI};
use crate::sampling::{
    sample_cdf, square_to_concentric_disk, square_to_cosine_hemisphere, square_to_uniform_cone,
    square_to_uniform_sphere,
};
use crate::shape::{offset_scale, RAY_EPSILON};
use crate::spectrum::Rgb;

/// The start of a light path.
#[derive(Clone, Copy)]
pub struct EmissionSample {
    /// Where the light leaves (on the emitter's surface, or the point light's position).
    pub p: Vec3,
    /// Where rays leaving the emitter start: `p` moved off the surface to the emitting side by
    /// `shape::offset_origin`'s offset, so that they do not re-hit it.
    pub origin: Vec3,
    /// The emitting surface's normal (zero for point and spot lights).
    pub n: Vec3,
    /// Direction of emission (unit).
    pub dir: Vec3,
    /// `Le·|cos θ| / (pmf · p(point) · p(direction))`.
    pub weight: Rgb,
    /// `Le` toward any direction is `radiance · area / pmf` per unit `cos`: what connecting the emitter
    /// point itself to the camera carries, `position_weight · Le(ω)·cos θ` (area emitters only).
    pub position_weight: f32,
    /// The emitter is a point (point, spot, projector), at infinity, or emits along one direction
    /// (`directionalarea`): the camera cannot see the sampled point.
    pub delta_position: bool,
    /// The emitter is at infinity (directional, constant, envmap; `visible_infinite` shows it).
    pub infinite: bool,
    /// The emitting primitive (which a ray leaving it must not re-hit), or `NONE`.
    pub prim: u32,
    /// The emitter's index in the light list (`NONE`: nothing was sampled).
    pub light: u32,
}

impl EmissionSample {
    pub fn none() -> Self {
        EmissionSample {
            p: Vec3::ZERO,
            origin: Vec3::ZERO,
            n: Vec3::ZERO,
            dir: Vec3::Z,
            weight: Rgb::ZERO,
            position_weight: 0.0,
            delta_position: false,
            infinite: false,
            prim: NONE,
            light: NONE,
        }
    }
}

/// Whether `kind` is an emitter at infinity.
#[inline]
pub fn is_infinite(kind: u32) -> bool {
    kind == LIGHT_DIRECTIONAL || kind == LIGHT_CONSTANT || kind == LIGHT_ENVMAP
}

/// A direction towards infinite emitter `light` as seen from `p`, as next-event estimation draws it
/// (without the selection probability); none for the kinds the scene does not use.
fn infinite_direction(scene: &SceneView, light: &Light, p: Vec3, u: Vec2) -> LightSample {
    let uses = |kind: u32| crate::features::has(scene.features, crate::features::light(kind));
    match light.kind {
        LIGHT_DIRECTIONAL if uses(LIGHT_DIRECTIONAL) => directional::sample(light, p),
        LIGHT_CONSTANT if uses(LIGHT_CONSTANT) => infinite::sample_constant(light, p, u),
        LIGHT_ENVMAP if uses(LIGHT_ENVMAP) => infinite::sample_envmap(light, scene, p, u),
        _ => LightSample::none(),
    }
}

/// For plain light tracing: the infinite emitter of `s` seen directly by a camera at `eye`, as
/// Mitsuba's `ptracer` shows it: a direction drawn from the eye towards the emitter and a point that
/// far along it (`far`: past the scene, within the camera's clip range), with the radiance that point
/// sends to the eye over the densities, in the area measure of the point (`Le·dist² / pdf(ω)`).
/// Directional lights (a Dirac delta of direction) are never seen.
pub fn visible_infinite(scene: &SceneView, s: &EmissionSample, eye: Vec3, far: f32, u: Vec2) -> (Vec3, Rgb) {
    let light = scene.lights[s.light as usize];
    if light.kind == LIGHT_DIRECTIONAL {
        return (eye, Rgb::ZERO);
    }
    let ls = infinite_direction(scene, &light, eye, u);
    let pdf = ls.pdf * light.pmf;
    if !(pdf > 0.0) {
        return (eye, Rgb::ZERO);
    }
    let dist = ls.dist.min(far);
    (eye + ls.wi * dist, ls.radiance * (dist * dist / pdf))
}

/// Chooses an emitter by `u_select` and samples a point (`u_pos`) and a direction (`u_dir`) on it.
pub fn sample(
    scene: &SceneView,
    params: &FrameParams,
    u_select: f32,
    u_pos: Vec2,
    u_dir: Vec2,
) -> EmissionSample {
    if params.light_count == 0 {
        return EmissionSample::none();
    }
    let chosen = sample_cdf(scene.tables, params.light_cdf_offset, params.light_count, u_select);
    let light = scene.lights[chosen.index as usize];
    if !(light.pmf > 0.0) {
        return EmissionSample::none();
    }
    let mut s = EmissionSample::none();
    s.light = chosen.index;
    if light.kind == LIGHT_AREA || light.kind == LIGHT_SPHERE {
        let prim = scene.prims[light.prim as usize];
        let area::PositionSample { p, n, area, error_scale: scale } = area::sample_position(&prim, u_pos);
        if light.flags & LIGHT_FLAG_DIRECTIONAL_AREA != 0 {
            // Mitsuba's `directionalarea`: along the normal, Le·A / pmf; no camera ray can meet that
            // direction, so the point itself is not connected to the camera.
            if !(area > 0.0) {
                return EmissionSample::none();
            }
            s.p = p;
            s.origin = p + n * (offset_scale(p, scale, prim.offset_floor) * RAY_EPSILON);
            s.n = n;
            s.dir = n;
            s.weight = textured::at_surface_point(scene, &light, light.prim, p) * (area / light.pmf);
            s.delta_position = true;
            s.prim = light.prim;
            return s;
        }
        // Cosine-weighted about the emitting side: Le·cos / (pmf · (1/A) · cos/π) = Le·A·π / pmf.
        let local = square_to_cosine_hemisphere(u_dir);
        if !(local.z > 0.0) || !(area > 0.0) {
            return EmissionSample::none();
        }
        let le = textured::at_surface_point(scene, &light, light.prim, p);
        s.p = p;
        s.origin = p + n * (offset_scale(p, scale, prim.offset_floor) * RAY_EPSILON);
        s.n = n;
        s.dir = Frame::from_normal(n).to_world(local);
        s.position_weight = area / light.pmf;
        s.weight = le * (s.position_weight * PI);
        s.prim = light.prim;
        return s;
    }
    if is_infinite(light.kind) {
        if params.integrator != INTEGRATOR_PTRACER {
            return EmissionSample::none();
        }
        // The scene's bounding sphere (centre, radius) is in `position`.
        let centre = vec3([light.position[0], light.position[1], light.position[2]]);
        let r = light.position[3];
        let ls = infinite_direction(scene, &light, centre, u_dir);
        if !(ls.pdf > 0.0) || !(r > 0.0) {
            return EmissionSample::none();
        }
        // A start on the disk of radius r tangent to the sphere on the emitter's side (density
        // 1/(π r²)), travelling away from the emitter.
        let d = square_to_concentric_disk(u_pos) * r;
        s.origin = centre + ls.wi * r + Frame::from_normal(ls.wi).to_world(Vec3::new(d.x, d.y, 0.0));
        s.p = s.origin;
        s.dir = -ls.wi;
        s.weight = ls.radiance * (PI * r * r / (ls.pdf * light.pmf));
        s.delta_position = true;
        s.infinite = true;
        return s;
    }
    if light.kind == LIGHT_POINT || light.kind == LIGHT_SPOT || light.kind == LIGHT_PROJECTOR {
        s.p = vec3([light.position[0], light.position[1], light.position[2]]);
        s.origin = s.p;
        s.delta_position = true;
        if light.kind == LIGHT_POINT {
            s.dir = square_to_uniform_sphere(u_dir);
            s.weight = radiance(&light) * (4.0 * PI / light.pmf);
        } else if light.kind == LIGHT_SPOT {
            // Uniform inside the cutoff cone, weighted by the spot's profile (and image).
            let one_minus_cos_max = 1.0 - light.params[0];
            let local = square_to_uniform_cone(u_dir, one_minus_cos_max);
            s.dir = to_world(&light, local);
            s.weight =
                point::spot_intensity(scene, &light, local) * (2.0 * PI * one_minus_cos_max / light.pmf);
        } else {
            // Uniform over the image: I(ω) / p(ω) = π·value(uv)·area.
            let (dir, density) = projector::direction(&light, u_dir);
            s.dir = dir;
            s.weight = if density > 0.0 {
                projector::intensity(scene, &light, dir) / (density * light.pmf)
            } else {
                Rgb::ZERO
            };
        }
        return s;
    }
    EmissionSample::none()
}

/// What the emitter of `s` sends towards `dir` from its sampled point, per unit of the connection's
/// geometry: `Le(dir)·|cos θ| / (pmf · p(point))` for area emitters (one-sided), `I(dir) / pmf` for
/// point, spot and projector lights.
pub fn emitted_towards(scene: &SceneView, s: &EmissionSample, dir: Vec3) -> Rgb {
    let light = scene.lights[s.light as usize];
    if light.kind == LIGHT_POINT {
        return radiance(&light) / light.pmf;
    }
    if light.kind == LIGHT_SPOT {
        return point::spot_intensity(scene, &light, super::to_local(&light, dir)) / light.pmf;
    }
    if light.kind == LIGHT_PROJECTOR {
        return projector::intensity(scene, &light, dir) / light.pmf;
    }
    let cos = s.n.dot(dir);
    if cos <= 0.0 {
        return Rgb::ZERO;
    }
    textured::at_surface_point(scene, &light, light.prim, s.p) * (s.position_weight * cos)
}

/// The area of an emitting primitive (what emission samples uniformly).
fn emitter_area(scene: &SceneView, light: &Light) -> f32 {
    let prim = scene.prims[light.prim as usize];
    if light.kind == LIGHT_SPHERE {
        4.0 * PI * prim.p1[0] * prim.p1[0]
    } else {
        area::normal_and_area(&prim).1
    }
}

/// For MIS against light tracing: `p_E(x)·p_E(ω|x) / |cos θ|` of emission that starts at a point `x` of
/// area emitter `light` (index) and leaves in any direction: `pmf / (A·π)` for cosine-weighted emission
/// from uniformly chosen points. Zero for emitters light tracing does not start from.
pub fn hit_density(scene: &SceneView, light: u32) -> f32 {
    let l = scene.lights[light as usize];
    if l.kind != LIGHT_AREA && l.kind != LIGHT_SPHERE {
        return 0.0;
    }
    let area = emitter_area(scene, &l);
    if area > 0.0 {
        l.pmf / (area * PI)
    } else {
        0.0
    }
}

/// For MIS against light tracing at a light sample `ls` taken from `p` for next-event estimation: the
/// emission density of the sampled point and of the direction towards `p`, over the light sample's own
/// density, with the geometry of the connection: `p_E(x) p_E(ω) / (p_L(ω)·|cos θx|)` for area emitters
/// (`p_L` in solid angle), `p_E(ω) / d²` for point, spot and projector lights (their choice and
/// position cancel).
pub fn nee_ratio(scene: &SceneView, ls: &LightSample) -> f32 {
    let l = scene.lights[ls.light as usize];
    if l.kind == LIGHT_POINT {
        return 1.0 / (4.0 * PI * ls.dist * ls.dist);
    }
    if l.kind == LIGHT_SPOT {
        return 1.0 / (2.0 * PI * (1.0 - l.params[0]) * ls.dist * ls.dist);
    }
    if l.kind == LIGHT_PROJECTOR {
        let cos = super::to_local(&l, -ls.wi).z;
        return projector::density(cos, l.params[3]) / (ls.dist * ls.dist);
    }
    // Cosine-weighted emission: p_E(ω) / |cos θx| = 1/π whatever the direction.
    let density = hit_density(scene, ls.light);
    if density > 0.0 && ls.pdf > 0.0 {
        density / ls.pdf
    } else {
        0.0
    }
}
