//! Unidirectional path tracing with next-event estimation, combined with BSDF sampling by the power
//! heuristic; Mitsuba's `path` semantics for `max_depth`, `rr_depth` and `hide_emitters`.
use crate::bsdf::Bsdf;
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::frame::Frame;
use crate::glam::{Vec2, Vec3};
use crate::light::{self, infinite};
use crate::math::max_component;
use crate::rng::Sampler;
use crate::sampling::power_heuristic;
use crate::scene::{FrameParams, SceneView, NONE};
use crate::shape::{offset_origin, surface_point, SurfacePoint};
use crate::spectrum::Rgb;

/// Random dimensions: the camera uses the first few; bounce `k` starts at a fixed offset so that all
/// paths use the same dimension for the same decision.
pub const DIM_FIRST_BOUNCE: u32 = 4;
pub const DIMS_PER_BOUNCE: u32 = 8;

/// Shadow rays stop this fraction short of the light so that the emitter itself does not occlude.
const SHADOW_EPSILON: f32 = 1.0e-4;

/// Where the path came from: what weighting an emitter it hits needs.
#[derive(Clone, Copy)]
struct PreviousVertex {
    p: Vec3,
    /// Solid-angle density of the BSDF sample that left it.
    pdf: f32,
    /// The camera, or a Dirac-delta BSDF lobe: emitters hit are not weighted against light sampling.
    delta: bool,
}

/// Radiance arriving along `ray`.
pub fn li(scene: &SceneView, params: &FrameParams, camera_ray: Ray, sampler: &mut Sampler) -> Rgb {
    let accel = Accel { nodes: scene.nodes, prims: scene.prims };
    let mut ray = camera_ray;
    let mut throughput = Rgb::ONE;
    let mut result = Rgb::ZERO;
    let mut eta_scale = 1.0f32;
    let mut depth = 0u32;
    let mut prev = PreviousVertex { p: ray.origin, pdf: 0.0, delta: true };

    loop {
        sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
        let visible_emitter = !(depth == 0 && params.hide_emitters != 0);
        let hit = match accel.trace(&ray, false, NONE) {
            Some(h) => h,
            None => {
                if visible_emitter {
                    result += throughput * environment(scene, params, ray.dir, &prev);
                }
                break;
            }
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(&prim, scene.attributes, &hit, &ray);

        if prim.light != NONE && visible_emitter {
            let emitter = scene.lights[prim.light as usize];
            let le = light::emitted(&emitter, sp.ns, -ray.dir);
            let weight = if prev.delta { 1.0 } else { power_heuristic(prev.pdf, light::pdf(&emitter, &prim, prev.p, sp.p, sp.ng)) };
            result += throughput * le * weight;
        }

        if params.max_depth != NONE && depth + 1 >= params.max_depth {
            break;
        }

        let material = scene.materials[prim.material as usize];
        let bsdf = Bsdf::new(&material, scene.textures, scene.tables, sp.uv);
        let (mut ns, mut ng) = (sp.ns, sp.ng);
        if bsdf.two_sided() && ng.dot(ray.dir) > 0.0 {
            ns = -ns;
            ng = -ng;
        }
        let frame = Frame::from_normal(ns);
        let wo = frame.to_local(-ray.dir);

        let u_select = sampler.next_1d();
        let u_light = sampler.next_2d();
        if bsdf.has_smooth_component() {
            result += throughput * next_event(scene, params, &accel, &bsdf, &frame, &sp, ng, wo, u_select, u_light);
        }

        // BSDF sampling.
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let bs = bsdf.sample(wo, u_lobe, u_dir);
        if bs.pdf <= 0.0 {
            break;
        }
        // No test of `wi` against the geometric normal: Mitsuba's integrators have none, and the
        // images must agree (the ray offset below still starts on the side `wi` leaves by).
        let wi = frame.to_world(bs.wi);
        throughput *= bs.weight;
        eta_scale *= bs.eta * bs.eta;
        prev = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta };
        ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        depth += 1;

        let u_rr = sampler.next_1d();
        if depth >= params.rr_depth {
            let q = (max_component(throughput) * eta_scale).min(0.95);
            if u_rr >= q {
                break;
            }
            throughput /= q;
        }
        if max_component(throughput) <= 0.0 {
            break;
        }
    }
    result
}

/// Light sampling at a surface point, weighted against BSDF sampling by the power heuristic (delta
/// emitters, which BSDF sampling cannot hit, take the full weight).
#[allow(clippy::too_many_arguments)]
fn next_event(scene: &SceneView, params: &FrameParams, accel: &Accel, bsdf: &Bsdf, frame: &Frame, sp: &SurfacePoint, ng: Vec3, wo: Vec3, u_select: f32, u_light: Vec2) -> Rgb {
    let ls = light::sample(scene, params, sp.p, u_select, u_light);
    if ls.pdf <= 0.0 || max_component(ls.radiance) <= 0.0 {
        return Rgb::ZERO;
    }
    let wi = frame.to_local(ls.wi);
    let f = bsdf.eval(wo, wi);
    if max_component(f) <= 0.0 {
        return Rgb::ZERO;
    }
    let shadow = Ray { origin: offset_origin(sp, ng, ls.wi), dir: ls.wi, t_min: 0.0, t_max: ls.dist * (1.0 - SHADOW_EPSILON) };
    if accel.occluded(&shadow, ls.prim) {
        return Rgb::ZERO;
    }
    let weight = if ls.delta { 1.0 } else { power_heuristic(ls.pdf, bsdf.pdf(wo, wi)) };
    f * ls.radiance * (weight / ls.pdf)
}

/// Radiance of the environment emitter (if any) along an escaping ray, MIS-weighted.
fn environment(scene: &SceneView, params: &FrameParams, dir: Vec3, prev: &PreviousVertex) -> Rgb {
    if params.env_light == NONE {
        return Rgb::ZERO;
    }
    let env = scene.lights[params.env_light as usize];
    let le = infinite::eval(&env, scene, dir);
    let weight = if prev.delta { 1.0 } else { power_heuristic(prev.pdf, infinite::pdf(&env, scene, dir) * env.pmf) };
    le * weight
}
