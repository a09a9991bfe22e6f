//! Direct lighting shared by the integrators: next-event estimation (light sampling with a shadow
//! ray) and the weight of emitters that BSDF sampling finds, combined by the power heuristic.
//!
//! With `n_l` light samples and `n_b` BSDF samples per vertex (Mitsuba's `direct` takes several; the
//! path tracer one each) the heuristic compares `n_l·p_light` with `n_b·p_bsdf`, and each strategy's
//! sum is divided by its own count by the caller.
use super::bdpt_mis::{self, SubpathMis};
use super::mis;
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::layout::{FrameParams, Primitive, SceneView, NONE};
use crate::light::{self, emission, infinite};
use crate::math::max_component;
use crate::sampling::power_heuristic;
use crate::shape::{offset_origin, Hit, SurfacePoint};
use crate::spectrum::Rgb;

/// Shadow rays stop this fraction short of the light so that the emitter itself does not occlude.
const SHADOW_EPSILON: f32 = 1.0e-4;

/// Samples each strategy takes per shading point.
#[derive(Clone, Copy)]
pub struct StrategyCounts {
    pub light: f32,
    pub bsdf: f32,
}

impl StrategyCounts {
    pub const ONE_EACH: StrategyCounts = StrategyCounts { light: 1.0, bsdf: 1.0 };
}

/// Where a ray came from: what weighting an emitter it hits needs.
#[derive(Clone, Copy)]
pub struct PreviousVertex {
    pub p: Vec3,
    /// Solid-angle density of the BSDF sample that left it.
    pub pdf: f32,
    /// The camera, or a Dirac-delta BSDF lobe: emitters hit are not weighted against light sampling.
    pub delta: bool,
    /// IBPT: the camera path's light-tracing scalar for the vertex this ray finds (`LightTracingMis`),
    /// 0 when light tracing cannot make the path (or is not running).
    pub lt: f32,
}

impl PreviousVertex {
    pub fn camera(p: Vec3) -> Self {
        PreviousVertex { p, pdf: 0.0, delta: true, lt: 0.0 }
    }
}

/// IBPT's state on a camera path (`docs/ibpt.md`): `scale` is the ratio of the light-tracing density
/// of the path so far to its camera-tracing density, without the terms of the current vertex
/// (`1 / (We·cos/d² · film scale)` at the first vertex, then `· ρ_rev / ρ_fwd` per bounce); zero when
/// light tracing cannot make the path. `first_vertex`: the current vertex is the camera's first, which
/// light tracing connects to the camera rather than samples (no reverse density there).
///
/// Under BDPT (`bdpt` set) the camera path's recursive state `state` (`bdpt_mis`) weighs the light
/// sample against every bidirectional strategy instead.
#[derive(Clone, Copy)]
pub struct LightTracingMis {
    pub scale: f32,
    pub first_vertex: bool,
    /// 1 under BDPT.
    pub bdpt: u32,
    pub state: SubpathMis,
}

impl LightTracingMis {
    pub const OFF: LightTracingMis =
        LightTracingMis { scale: 0.0, first_vertex: false, bdpt: 0, state: SubpathMis::ZERO };

    /// IBPT's camera scalar at a vertex (the first one, or a later one).
    #[inline]
    pub fn ibpt(scale: f32, first_vertex: bool) -> Self {
        LightTracingMis { scale, first_vertex, ..Self::OFF }
    }

    /// BDPT's camera state, where the light sample makes a path whose every strategy exists
    /// (`bidirectional`); else the plain weighting against BSDF sampling.
    #[inline]
    pub fn bdpt(state: SubpathMis, bidirectional: bool) -> Self {
        LightTracingMis { bdpt: bidirectional as u32, state, ..Self::OFF }
    }
}

/// One light sample at a surface point, weighted against BSDF sampling (delta emitters, which BSDF
/// sampling cannot hit, take the full weight). Not divided by `counts.light`.
#[allow(clippy::too_many_arguments)]
pub fn next_event(
    scene: &SceneView,
    params: &FrameParams,
    accel: &Accel,
    bsdf: &Bsdf,
    frame: &Frame,
    sp: &SurfacePoint,
    ng: Vec3,
    wo: Vec3,
    u_select: f32,
    u_light: Vec2,
    counts: StrategyCounts,
    lt: LightTracingMis,
) -> Rgb {
    let ls = light::sample(scene, params, sp.p, u_select, u_light);
    if ls.pdf <= 0.0 || max_component(ls.radiance) <= 0.0 {
        return Rgb::ZERO;
    }
    let wi = frame.to_local(ls.wi);
    // One dispatch for both: the density is needed only if the shadow ray is clear, but computing it
    // with the value shares the model's construction and work (half vector, D, Fresnel).
    let ep = bsdf.eval_pdf(wo, wi, TransportMode::Radiance);
    if max_component(ep.f) <= 0.0 {
        return Rgb::ZERO;
    }
    // From the offset origin to the light point itself, as Mitsuba's `spawn_ray_to` does: keeping the
    // direction and distance from the surface point would end the ray the offset (then 8.9e-5·(1 + |p|))
    // past the light, behind whatever lies closer to it than that (measured: a lamp 2e-6 under a
    // ceiling in a box scaled by 1e-4 rendered 22% dark).
    let origin = offset_origin(sp, ng, ls.wi);
    let to_light = sp.p + ls.wi * ls.dist - origin;
    let dist = to_light.length();
    let shadow = Ray { origin, dir: to_light / dist, t_min: 0.0, t_max: dist * (1.0 - SHADOW_EPSILON) };
    let transmittance = crate::mask::transmittance(scene, accel, &shadow, ls.prim);
    if max_component(transmittance) <= 0.0 {
        return Rgb::ZERO;
    }
    let weight = if lt.bdpt != 0 {
        let r_hit = if ls.delta { 0.0 } else { ep.pdf / ls.pdf };
        let reverse = bsdf.pdf(wi, wo, TransportMode::Importance);
        let cos = ng.dot(ls.wi).abs();
        let (m, c) = (bdpt_mis::Merging::of(params), bdpt_mis::Connections::of(params));
        bdpt_mis::nee_weight(lt.state, r_hit, emission::nee_ratio(scene, &ls), cos, reverse, m, c)
    } else if lt.scale > 0.0 {
        // IBPT: against BSDF sampling and against the light path that connects this point to the camera.
        let r_hit = if ls.delta { 0.0 } else { ep.pdf / ls.pdf };
        let reverse = if lt.first_vertex { 1.0 } else { bsdf.pdf(wi, wo, TransportMode::Importance) };
        mis::nee_weight(r_hit, lt.scale, lt.first_vertex, reverse, emission::nee_ratio(scene, &ls))
    } else if ls.delta {
        1.0
    } else {
        power_heuristic(counts.light * ls.pdf, counts.bsdf * ep.pdf)
    };
    ep.f * ls.radiance * transmittance * (weight / ls.pdf)
}

/// Radiance of the area emitter on `prim` seen along `dir` at `sp`, weighted against light sampling
/// from `prev`.
pub fn area_emission(
    scene: &SceneView,
    prim: &Primitive,
    sp: &SurfacePoint,
    dir: Vec3,
    prev: &PreviousVertex,
    counts: StrategyCounts,
) -> Rgb {
    seen_area_emission(scene, prim, sp, dir, prev, counts, 0.0)
}

/// `area_emission`, where under IBPT the camera sees the emitter at its first vertex: weighted
/// against the emitter point's splats of `light_paths` light paths a camera sample
/// (`mis::seen_scale`); 0 at every other vertex.
pub fn seen_area_emission(
    scene: &SceneView,
    prim: &Primitive,
    sp: &SurfacePoint,
    dir: Vec3,
    prev: &PreviousVertex,
    counts: StrategyCounts,
    light_paths: f32,
) -> Rgb {
    let emitter = scene.lights[prim.light as usize];
    let le = light::emitted_at(scene, &emitter, sp.ns, -dir, sp.uv);
    let weight = if prev.lt > 0.0 {
        // IBPT: against light sampling and against the light path that starts at this point.
        let r_nee = if prev.delta { 0.0 } else { light::pdf(&emitter, prim, prev.p, sp.p, sp.ng) / prev.pdf };
        let e = emission::hit_density(scene, prim.light);
        let lt = if light_paths > 0.0 { mis::seen_scale(prev.lt, e, light_paths) } else { prev.lt };
        mis::hit_weight(r_nee, lt, e)
    } else if prev.delta {
        1.0
    } else {
        power_heuristic(
            counts.bsdf * prev.pdf,
            counts.light * light::pdf(&emitter, prim, prev.p, sp.p, sp.ng),
        )
    };
    le * weight
}

/// Radiance of the environment emitter (if any) along an escaping ray, weighted likewise.
pub fn environment(
    scene: &SceneView,
    params: &FrameParams,
    dir: Vec3,
    prev: &PreviousVertex,
    counts: StrategyCounts,
) -> Rgb {
    if params.env_light == NONE {
        return Rgb::ZERO;
    }
    let env = scene.lights[params.env_light as usize];
    let le = infinite::eval(&env, scene, dir);
    let weight = if prev.delta {
        1.0
    } else {
        power_heuristic(counts.bsdf * prev.pdf, counts.light * infinite::pdf(&env, scene, dir) * env.pmf)
    };
    le * weight
}

/// The first surface along a camera ray when directly visible emitters are hidden: Mitsuba's
/// `hide_emitters` lets camera rays pass through area emitters to what lies behind them.
pub fn first_hit_past_emitters(scene: &SceneView, accel: &Accel, ray: &Ray) -> Option<Hit> {
    // Advancing `t_min` (strictly excluded) past each emitter keeps `t` relative to the camera ray;
    // bounded so that a stack of coincident emitters cannot loop forever.
    let mut r = *ray;
    let mut skip = NONE;
    let mut steps = 0;
    while steps < 64 {
        let hit = accel.trace(&r, false, skip)?;
        if scene.prims[hit.prim as usize].light == NONE {
            return Some(hit);
        }
        r.t_min = hit.t;
        skip = hit.prim;
        steps += 1;
    }
    None
}
