//! Unidirectional path tracing with next-event estimation, combined with BSDF sampling by the power
//! heuristic; Mitsuba's `path` semantics for `max_depth`, `rr_depth` and `hide_emitters`.
use super::SceneView;
use crate::bsdf::Bsdf;
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::frame::Frame;
use crate::light;
use crate::math::max_component;
use crate::rng::Sampler;
use crate::sampling::power_heuristic;
use crate::scene::{FrameParams, NONE};
use crate::shape::{offset_origin, surface_point};
use crate::spectrum::Rgb;

/// Random dimensions: the camera uses the first few; bounce `k` starts at a fixed offset so that all
/// paths use the same dimension for the same decision.
pub const DIM_FIRST_BOUNCE: u32 = 4;
pub const DIMS_PER_BOUNCE: u32 = 8;

/// Shadow rays stop this fraction short of the light so that the emitter itself does not occlude.
const SHADOW_EPSILON: f32 = 1.0e-4;

/// Radiance arriving along `ray`.
pub fn li(scene: &SceneView, params: &FrameParams, camera_ray: Ray, sampler: &mut Sampler) -> Rgb {
    let accel = Accel { nodes: scene.nodes, prims: scene.prims };
    let mut ray = camera_ray;
    let mut throughput = Rgb::ONE;
    let mut result = Rgb::ZERO;
    let mut eta_scale = 1.0f32;
    let mut depth = 0u32;
    // The previous scattering vertex, for weighting emitters hit by BSDF sampling.
    let mut prev_p = ray.origin;
    let mut prev_pdf = 0.0f32;
    let mut prev_delta = true;

    loop {
        sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
        let hit = match accel.trace(&ray, false) {
            Some(h) => h,
            None => break,
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(&prim, scene.normals, &hit, &ray);

        if prim.light != NONE && !(depth == 0 && params.hide_emitters != 0) {
            let emitter = scene.lights[prim.light as usize];
            let le = light::emitted(&emitter, sp.ns, -ray.dir);
            let weight = if prev_delta {
                1.0
            } else {
                power_heuristic(prev_pdf, light::pdf(&emitter, &prim, prev_p, sp.p, sp.ng))
            };
            result += throughput * le * weight;
        }

        if params.max_depth != NONE && depth + 1 >= params.max_depth {
            break;
        }

        let material = scene.materials[prim.material as usize];
        let bsdf = Bsdf::from_material(&material);
        let (mut ns, mut ng) = (sp.ns, sp.ng);
        if material.two_sided != 0 && ng.dot(ray.dir) > 0.0 {
            ns = -ns;
            ng = -ng;
        }
        let frame = Frame::from_normal(ns);
        let wo = frame.to_local(-ray.dir);

        // Next-event estimation.
        let u_select = sampler.next_1d();
        let u_light = sampler.next_2d();
        if bsdf.has_smooth_component() {
            let ls = light::sample(scene.lights, scene.prims, scene.tables, params.light_count, params.light_cdf_offset, sp.p, u_select, u_light);
            if ls.pdf > 0.0 && max_component(ls.radiance) > 0.0 {
                let wi = frame.to_local(ls.wi);
                let f = bsdf.eval(wo, wi);
                if max_component(f) > 0.0 {
                    let shadow = Ray {
                        origin: offset_origin(&sp, ng, ls.wi),
                        dir: ls.wi,
                        t_min: 0.0,
                        t_max: ls.dist * (1.0 - SHADOW_EPSILON),
                    };
                    if !accel.occluded(&shadow) {
                        let weight = power_heuristic(ls.pdf, bsdf.pdf(wo, wi));
                        result += throughput * f * ls.radiance * (weight / ls.pdf);
                    }
                }
            }
        }

        // BSDF sampling.
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let bs = bsdf.sample(wo, u_lobe, u_dir);
        if bs.pdf <= 0.0 {
            break;
        }
        let wi = frame.to_world(bs.wi);
        // A direction the shading normal calls "above" but the geometric normal "below" would leak
        // light through the surface.
        if wi.dot(ng) * bs.wi.z <= 0.0 {
            break;
        }
        throughput *= bs.weight;
        eta_scale *= bs.eta * bs.eta;
        prev_p = sp.p;
        prev_pdf = bs.pdf;
        prev_delta = false;
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
