//! Light tracing (Mitsuba's `ptracer`): paths start on an emitter chosen with the pmf that next-event
//! estimation uses; the emitter point and every vertex with a non-delta BSDF are connected to the
//! camera by a shadow ray and splatted into the pixel they project to. Importance transport: BSDFs are
//! evaluated and sampled in `TransportMode::Importance`, with Veach's correction for shading normals.
//!
//! Normalisation: one light path per pixel and sample, so `spp × pixels` paths; a path's splat is its
//! contribution times `full image pixels / rendered pixels` (crop windows), and the host divides each
//! pixel's sum by the samples per pixel, as for camera paths. Reconstruction is a box filter over the
//! pixel. `max_depth` counts segments as in `path`: a vertex `d` segments from the emitter is connected
//! only if `d + 1 ≤ max_depth`; `hide_emitters` drops the emitter-to-camera connection.
use super::path::{DIMS_PER_BOUNCE, DIM_FIRST_BOUNCE};
use super::shading_frame;
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::{CameraConnection, Ray};
use crate::glam::Vec3;
use crate::layout::{FrameParams, SceneView, NONE};
use crate::light::emission;
use crate::math::{max_component, vec3};
use crate::rng::Sampler;
use crate::shape::{offset_origin, surface_point};
use crate::spectrum::Rgb;
use crate::splat::{splat, AtomicWords};

const IMPORTANCE: TransportMode = TransportMode::Importance;
/// Shadow rays to the camera stop this fraction short of it.
const SHADOW_EPSILON: f32 = 1.0e-4;

/// Veach's correction for shading normals in importance transport, `|wo·ns| |wi·ng| / (|wo·ng| |wi·ns|)`
/// (`wo` towards the previous vertex, `wi` towards the next): with it the adjoint BSDF is the true
/// adjoint of the shading-normal BSDF that camera paths see.
#[inline]
fn shading_normal_correction(wo: Vec3, wi: Vec3, ns: Vec3, ng: Vec3) -> f32 {
    let denom = wo.dot(ng).abs() * wi.dot(ns).abs();
    if denom > 0.0 {
        wo.dot(ns).abs() * wi.dot(ng).abs() / denom
    } else {
        0.0
    }
}

/// The rendered pixel that a camera connection lands in, if it lies inside the crop window.
#[inline]
fn pixel_of(params: &FrameParams, c: &CameraConnection) -> u32 {
    let x = (c.film.x * params.full_width as f32) as u32;
    let y = (c.film.y * params.full_height as f32) as u32;
    if x < params.crop_x || y < params.crop_y {
        return NONE;
    }
    let (px, py) = (x - params.crop_x, y - params.crop_y);
    if px >= params.width || py >= params.height {
        return NONE;
    }
    py * params.width + px
}

/// Connects the point `origin` (already moved off its surface) to the camera through `c` and adds
/// `value · importance` to the pixel it lands in, unless something blocks the way. `skip`: a primitive
/// the shadow ray ignores (the emitter it starts on).
#[allow(clippy::too_many_arguments)]
fn splat_to_camera<W: AtomicWords>(
    params: &FrameParams,
    accel: &Accel,
    words: &mut W,
    origin: Vec3,
    c: &CameraConnection,
    value: Rgb,
    skip: u32,
    u: f32,
) {
    let pixel = pixel_of(params, c);
    if pixel == NONE || max_component(value) <= 0.0 {
        return;
    }
    let d = vec3(params.camera.origin) - origin;
    let dist = d.length();
    let shadow = Ray { origin, dir: d / dist, t_min: 0.0, t_max: dist * (1.0 - SHADOW_EPSILON) };
    if accel.occluded(&shadow, skip) {
        return;
    }
    let film_scale = (params.full_width * params.full_height) as f32 / (params.width * params.height) as f32;
    splat(words, pixel, value * (c.importance * film_scale), u);
}

/// Traces the light path of (`path_index`, sample) and splats its camera connections.
pub fn trace<W: AtomicWords>(scene: &SceneView, params: &FrameParams, sampler: &mut Sampler, words: &mut W) {
    let accel = Accel { nodes: scene.nodes, prims: scene.prims };
    let camera = params.camera;
    let u_select = sampler.next_1d();
    let u_pos = sampler.next_2d();
    let u_dir = sampler.next_2d();
    let u_round = sampler.next_1d();
    let es = emission::sample(scene, params, u_select, u_pos, u_dir);
    if es.light == NONE || max_component(es.weight) <= 0.0 {
        return;
    }
    let max_depth = params.max_depth;
    if !es.delta_position && params.hide_emitters == 0 && max_depth != 0 {
        if let Some(c) = camera.connect(es.origin) {
            let le = emission::emitted_towards(scene, &es, c.dir);
            splat_to_camera(params, &accel, words, es.origin, &c, le, es.prim, u_round);
        }
    }
    let mut beta = es.weight;
    let mut ray = Ray { origin: es.origin, dir: es.dir, t_min: 0.0, t_max: f32::MAX };
    // Segments from the emitter to the vertex about to be found.
    let mut depth = 1u32;
    while max_depth == NONE || depth < max_depth {
        sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
        let hit = match accel.trace(&ray, false, NONE) {
            Some(h) => h,
            None => break,
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(&prim, scene.attributes, &hit, &ray);
        let material = scene.materials[prim.material as usize];
        let bsdf = Bsdf::new(&material, scene.textures, scene.tables, sp.uv, scene.features);
        let (frame, ng, wo) = shading_frame(bsdf.two_sided(), &sp, ray.dir);
        let wo_world = -ray.dir;
        let u_round = sampler.next_1d();

        // This vertex is `depth` segments from the emitter: connecting it makes `depth + 1`.
        if bsdf.flags().has_smooth() {
            if let Some(c) = camera.connect(sp.p) {
                let f = bsdf.eval(wo, frame.to_local(c.dir), IMPORTANCE);
                let corr = shading_normal_correction(wo_world, c.dir, frame.n, ng);
                let origin = offset_origin(&sp, ng, c.dir);
                splat_to_camera(params, &accel, words, origin, &c, beta * f * corr, NONE, u_round);
            }
        }
        if max_depth != NONE && depth + 1 >= max_depth {
            break;
        }

        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let bs = bsdf.sample(wo, u_lobe, u_dir, IMPORTANCE);
        if bs.pdf <= 0.0 {
            break;
        }
        let wi = frame.to_world(bs.wi);
        beta *= bs.weight * shading_normal_correction(wo_world, wi, frame.n, ng);
        ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        depth += 1;

        let u_rr = sampler.next_1d();
        if depth >= params.rr_depth {
            let q = max_component(beta).min(0.95);
            if u_rr >= q {
                break;
            }
            beta /= q;
        }
        if max_component(beta) <= 0.0 {
            break;
        }
    }
}
