//! Light tracing (Mitsuba's `ptracer`): paths start on an emitter chosen with the pmf that next-event
//! estimation uses; the emitter point and every vertex with a non-delta BSDF are connected to the
//! camera by a shadow ray and splatted into the pixel they project to. Importance transport: BSDFs are
//! evaluated and sampled in `TransportMode::Importance`, with Veach's correction for shading normals.
//!
//! Normalisation: one light path per pixel and sample, so `spp × pixels` paths; a path's splat is its
//! contribution times `full image pixels / rendered pixels` (crop windows), and the host divides each
//! pixel's sum by the samples per pixel, as for camera paths. Each connection is splatted into every
//! pixel whose reconstruction filter covers it, weighted as that pixel's camera samples are.
//! `max_depth` counts segments as in `path`: a vertex `d` segments from the emitter is connected
//! only if `d + 1 ≤ max_depth`; `hide_emitters` drops the emitter-to-camera connection. Masks: light
//! paths pass through them as camera paths do, and connections are attenuated by them (`mask`).
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::bdpt_mis::{self, SubpathMis};
use super::mis;
use super::nee::first_hit_past_emitters;
use super::path::{DIMS_PER_BOUNCE, DIM_FIRST_BOUNCE, DIM_WAVELENGTH};
use super::{axis_weights, disperse, shading_frame, splat_footprint, tile_draw, NO_WAVELENGTH, SPAN};
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::{CameraConnection, Ray};
use crate::features;
use crate::film;
use crate::glam::{Vec2, Vec3};
use crate::instancing::surface_point;
use crate::layout::{FrameParams, SceneView, INTEGRATOR_IBPT, NONE};
use crate::light::emission;
use crate::math::{max_abs_component, max_component, vec3};
use crate::rng::Sampler;
use crate::shape::offset_origin;
use crate::spectrum::Rgb;
use crate::splat::{splat, AtomicWords};

const IMPORTANCE: TransportMode = TransportMode::Importance;
/// Shadow rays to the camera stop this fraction short of it.
const SHADOW_EPSILON: f32 = 1.0e-4;

/// Veach's correction for shading normals in importance transport, `|wo·ns| |wi·ng| / (|wo·ng| |wi·ns|)`
/// (`wo` towards the previous vertex, `wi` towards the next): with it the adjoint BSDF is the true
/// adjoint of the shading-normal BSDF that camera paths see.
#[inline]
pub(super) fn shading_normal_correction(wo: Vec3, wi: Vec3, ns: Vec3, ng: Vec3) -> f32 {
    let denom = wo.dot(ng).abs() * wi.dot(ns).abs();
    if denom > 0.0 {
        wo.dot(ns).abs() * wi.dot(ng).abs() / denom
    } else {
        0.0
    }
}

/// Rendered pixels per light path's reach: light paths (one per rendered pixel and sample) land
/// anywhere on the full film, so a crop window's pixels see `rendered / full` of them, and of those
/// the share connected to the camera (`light_tracing_share`). Everything that weighs light tracing
/// against the camera strategies takes its density through this one factor, as through a crop
/// window's, so the weights stay a partition of unity at any share.
#[inline]
pub fn film_scale(params: &FrameParams) -> f32 {
    (params.full_width * params.full_height) as f32
        / (params.width * params.height) as f32
        / light_tracing_share(params)
}

/// The light paths a pass traces: one per pixel of the window.
#[inline]
pub fn light_paths(params: &FrameParams) -> f32 {
    (params.width * params.height) as f32
}

/// `FrameParams::light_tracing_share` in (0, 1] (`super::share_in_unit`).
#[inline]
pub fn light_tracing_share(params: &FrameParams) -> f32 {
    super::share_in_unit(params.light_tracing_share)
}

/// Whether light path `index` (laid out like the pixels) of sample `sample` connects to the camera:
/// with probability `light_tracing_share` (`super::tile_draw`).
#[inline]
pub fn connects_to_camera(params: &FrameParams, index: u32, sample: u32) -> bool {
    let q = light_tracing_share(params);
    q >= 1.0 || tile_draw(params, index, sample, SHARE_STREAM) < q
}

/// The stream of `connects_to_camera`'s draws, apart from every path's.
const SHARE_STREAM: u32 = 0x5a3c_96e1;

/// How a camera connection is weighted against the camera strategies under IBPT (`mis`): not at all
/// (plain light tracing), or as the emitter point, the first vertex or a later vertex of a light path.
/// Under BDPT and VCM (`MIS_BDPT`): `d` and `vc` hold the light path's `bdpt_mis::SubpathMis` at the
/// vertex, `rho` the camera path's density of leaving it back along the light path, `cos` the cosine
/// there towards the camera, `eta_sq` vertex merging's factor (`bdpt_mis::Merging`). Under
/// `MIS_EMITTER`, `d` holds the pass's light paths (`mis::seen_ratio_sq`).
#[derive(Clone, Copy)]
pub(super) struct ConnectionMis {
    kind: u32,
    rho: f32,
    inv_hit_sq: f32,
    inv_nee_sq: f32,
    d: f32,
    vc: f32,
    cos: f32,
    eta_sq: f32,
    /// The connections' count, squared (`bdpt_mis::Connections`).
    connections_sq: f32,
}

const MIS_NONE: u32 = 0;
const NO_MIS: ConnectionMis = ConnectionMis {
    kind: MIS_NONE,
    rho: 0.0,
    inv_hit_sq: 0.0,
    inv_nee_sq: 0.0,
    d: 0.0,
    vc: 0.0,
    cos: 0.0,
    eta_sq: 0.0,
    connections_sq: 0.0,
};
const MIS_EMITTER: u32 = 1;
const MIS_FIRST_VERTEX: u32 = 2;
const MIS_LATER_VERTEX: u32 = 3;
const MIS_BDPT: u32 = 4;

impl ConnectionMis {
    /// A light vertex of BDPT with state `state`, `cos` towards the camera, `rev` the camera path's
    /// density of leaving it back along the light path.
    #[inline]
    pub(super) fn bdpt(
        state: SubpathMis,
        cos: f32,
        rev: f32,
        m: bdpt_mis::Merging,
        c: bdpt_mis::Connections,
    ) -> Self {
        ConnectionMis {
            kind: MIS_BDPT,
            rho: rev,
            d: state.vcm,
            vc: state.vc,
            cos,
            eta_sq: m.eta_sq,
            connections_sq: c.sq,
            ..NO_MIS
        }
    }

    /// The emitter point itself, against the camera path that sees it there (`inv_hit_sq`: `1/E²` of
    /// `emission::hit_density`): the only two strategies of a one-segment path, under IBPT and BDPT
    /// alike, weighed as `mis::seen_ratio_sq` says with the pass's `light_paths`.
    #[inline]
    pub(super) fn emitter_point(inv_hit_sq: f32, light_paths: f32) -> Self {
        ConnectionMis { kind: MIS_EMITTER, inv_hit_sq, d: light_paths, ..NO_MIS }
    }

    /// The weight of a splat whose camera strategies carry `importance` (`We·cos/d²`, the film scale and
    /// the pixel's filter density at the point: the camera path's density of landing there).
    #[inline]
    fn weight(&self, importance: f32) -> f32 {
        match self.kind {
            MIS_EMITTER => mis::emitter_connection_weight(importance, self.inv_hit_sq, self.d),
            MIS_FIRST_VERTEX => {
                mis::first_vertex_connection_weight(importance, self.rho, self.inv_hit_sq, self.inv_nee_sq)
            }
            MIS_LATER_VERTEX => mis::connection_weight(importance, self.rho, self.d),
            MIS_BDPT => {
                let state = SubpathMis { vcm: self.d, vc: self.vc, vm: 0.0 };
                // Light tracing is not a connection: the others' terms times c² (`bdpt_mis`).
                let m = bdpt_mis::Merging { eta_sq: self.eta_sq, inv_eta_sq: 0.0, inv_eta: 0.0 };
                bdpt_mis::weight(self.connections_sq * state.others(importance * self.cos, self.rho, m), 0.0)
            }
            _ => 1.0,
        }
    }
}

/// Connects the point `origin` (already moved off its surface) to the camera through `c` and, unless
/// something blocks the way, splats `value · importance` into every rendered pixel whose
/// reconstruction filter covers the point, weighted by the filter as the pixel's camera samples are
/// (`film::pixel_weight`; one pixel for the box). `skip`: a primitive the shadow ray ignores (the
/// emitter it starts on).
#[allow(clippy::too_many_arguments)]
pub(super) fn splat_to_camera<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    accel: &Accel,
    words: &mut W,
    origin: Vec3,
    c: &CameraConnection,
    value: Rgb,
    skip: u32,
    u: f32,
    weighting: ConnectionMis,
) {
    if max_abs_component(value) <= 0.0 {
        return;
    }
    // The footprint of the filter around the point, in pixels of the full image, within the crop.
    let pos = Vec2::new(c.film.x * params.full_width as f32, c.film.y * params.full_height as f32);
    let r = params.filter_radius;
    let x0 = ((pos.x - r).floor().max(params.crop_x as f32)) as u32;
    let y0 = ((pos.y - r).floor().max(params.crop_y as f32)) as u32;
    let x1 = ((pos.x + r).floor() as u32).min(params.crop_x + params.width - 1);
    let y1 = ((pos.y + r).floor() as u32).min(params.crop_y + params.height - 1);
    if (pos.x + r) < params.crop_x as f32 || (pos.y + r) < params.crop_y as f32 || x0 > x1 || y0 > y1 {
        return;
    }
    let d = c.point - origin;
    let dist = d.length();
    // Up to the near clip plane, as the camera ray that would see the point runs (a surface between
    // the plane and the lens hides nothing: Mitsuba's `path` sees past it, and its `ptracer`, which
    // tests the whole segment, does not).
    let reach = (dist - c.clipped) * (1.0 - SHADOW_EPSILON);
    let shadow = Ray { origin, dir: d / dist, t_min: 0.0, t_max: reach };
    let transmittance = to_camera(scene, params, accel, &shadow, skip);
    if max_component(transmittance) <= 0.0 {
        return;
    }
    let value = value * transmittance;
    let importance = c.importance * film_scale(params);
    let (columns, rows) = (x1 - x0 + 1, y1 - y0 + 1);
    if params.film_reach != 0 && columns as usize <= SPAN && rows as usize <= SPAN {
        // The splatting film: the camera's density is one wherever the point lands in the window
        // (`film::camera_density`), and `film::pixel_weight` is taken separably, each column's and
        // row's filter and mass once (per pixel, the filter's table lookups took 29% of an `ibpt`
        // render of the Cornell box on the CPU, `perf`), the same weights to the bit.
        if film::camera_density(scene.tables, params, pos, x0, y0) <= 0.0 {
            return;
        }
        let weight = weighting.weight(importance);
        let first = ((x0 - params.crop_x) as i32, (y0 - params.crop_y) as i32);
        let along_x = axis_weights(scene, params, pos.x, first.0, columns, true);
        let along_y = axis_weights(scene, params, pos.y, first.1, rows, false);
        let value = value * (importance * weight);
        splat_footprint(words, params.width, first, &along_x, &along_y, (columns, rows), value, u);
        return;
    }
    let mut y = y0;
    while y <= y1 {
        let mut x = x0;
        while x <= x1 {
            let density = film::camera_density(scene.tables, params, pos, x, y);
            // The filter itself (negative on a negative lobe) where the MIS weight takes the camera
            // samples' density; the two are one under filter importance sampling without lobes.
            let filter = if params.filter_signed != 0 || params.film_reach != 0 {
                film::pixel_weight(scene.tables, params, pos, x, y)
            } else {
                density
            };
            if density > 0.0 && filter != 0.0 {
                let pixel = (y - params.crop_y) * params.width + (x - params.crop_x);
                let weight = weighting.weight(importance * density);
                splat(words, pixel, value * (importance * filter * weight), u);
            }
            x += 1;
        }
        y += 1;
    }
}

/// Connects the emitter point of `es` (an emitter the camera can see: not a point, spot or projector,
/// not at infinity) to the camera through the aperture point `u_lens` and splats what it emits
/// towards the camera.
#[allow(clippy::too_many_arguments)]
pub(super) fn splat_emitter_point<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    accel: &Accel,
    words: &mut W,
    es: &emission::EmissionSample,
    u_lens: Vec2,
    u_round: f32,
    weighting: ConnectionMis,
) {
    if let Some(c) = params.camera.connect(es.origin, u_lens) {
        let le = emission::emitted_towards(scene, es, c.dir);
        splat_to_camera(scene, params, accel, words, es.origin, &c, le, es.prim, u_round, weighting);
    }
}

/// The light that crosses `shadow`, a segment from a light vertex to the camera (ignoring primitive
/// `skip`): blocked by any surface, attenuated at each null interface (`mask::transmittance`). With
/// `hide_emitters` camera rays pass through emitters (`path`), so the segment does too: otherwise
/// IBPT's weights would count a light-tracing strategy that cannot happen.
fn to_camera(scene: &SceneView, params: &FrameParams, accel: &Accel, shadow: &Ray, skip: u32) -> Rgb {
    if params.hide_emitters == 0 {
        return crate::mask::transmittance(scene, accel, shadow, skip);
    }
    if !features::has(scene.features, features::MASK) {
        return if first_hit_past_emitters(scene, accel, shadow).is_some() { Rgb::ZERO } else { Rgb::ONE };
    }
    // Surface by surface, nearest first, as the camera ray would meet them: emitters skipped, null
    // interfaces attenuating, anything else blocking.
    let mut r = *shadow;
    let mut t = Rgb::ONE;
    let mut steps = 0;
    while steps < crate::mask::MAX_PASSES {
        let Some(hit) = accel.trace(&r, false, skip) else { return t };
        let prim = scene.prims[hit.prim as usize];
        if prim.light == NONE {
            let m = scene.materials[prim.material as usize];
            if !crate::mask::is_null(scene, &m) {
                return Rgb::ZERO;
            }
            let sp = surface_point(scene, &prim, &hit, &r);
            t *= crate::mask::null_transmission(scene, &m, &sp, r.dir);
            if max_component(t) <= 0.0 {
                return Rgb::ZERO;
            }
        }
        r.t_min = hit.t;
        steps += 1;
    }
    Rgb::ZERO
}

/// The aperture point of a thin lens that the emitter's connections reach: a dimension past the
/// emitter sample's, before the first bounce's.
pub(super) const DIM_LENS_AT_EMITTER: u32 = 6;
/// Within a bounce's dimensions (`path::DIMS_PER_BOUNCE`), the two after Russian roulette's.
pub(super) const DIM_LENS_IN_BOUNCE: u32 = 5;

/// The 2D sample that picks a thin lens's aperture point for a connection, from dimensions `dim` and
/// `dim + 1`, which no other decision uses.
#[inline]
pub(super) fn lens_sample(sampler: &Sampler, dim: u32) -> Vec2 {
    let mut s = *sampler;
    s.set_dimension(dim);
    s.next_2d()
}

/// Traces the light path of (`path_index`, sample) and splats its camera connections (weighted against
/// the camera strategies under IBPT).
pub fn trace<W: AtomicWords>(scene: &SceneView, params: &FrameParams, sampler: &mut Sampler, words: &mut W) {
    let ibpt = params.integrator == INTEGRATOR_IBPT;
    let accel = Accel::of(scene);
    let camera = params.camera;
    let u_select = sampler.next_1d();
    let u_pos = sampler.next_2d();
    let u_dir = sampler.next_2d();
    let u_round = sampler.next_1d();
    let u_lens_at_emitter = lens_sample(sampler, DIM_LENS_AT_EMITTER);
    let es = emission::sample(scene, params, u_select, u_pos, u_dir);
    if es.light == NONE || max_component(es.weight) <= 0.0 {
        return;
    }
    let max_depth = params.max_depth;
    // IBPT: `1/E²` for the camera path that hits this emitter point (none for point and spot lights),
    // with E = p(point)·p(direction)/|cos| of the emission.
    let hit_density = if es.delta_position { 0.0 } else { emission::hit_density(scene, es.light) };
    let inv_hit_sq = if hit_density > 0.0 { 1.0 / (hit_density * hit_density) } else { 0.0 };
    if es.infinite && params.hide_emitters == 0 && max_depth != 0 {
        // The emitter seen directly: a point past the scene, closer than the far clip plane (where
        // camera rays stop and see the environment).
        let eye = vec3(camera.origin);
        let (far_point, value) = emission::visible_infinite(scene, &es, eye, 0.999 * camera.far_clip, u_pos);
        if let Some(c) = camera.connect(far_point, u_lens_at_emitter) {
            splat_to_camera(scene, params, &accel, words, far_point, &c, value, NONE, u_round, NO_MIS);
        }
    }
    if !es.delta_position && params.hide_emitters == 0 && max_depth != 0 {
        let weighting =
            if ibpt { ConnectionMis::emitter_point(inv_hit_sq, light_paths(params)) } else { NO_MIS };
        splat_emitter_point(scene, params, &accel, words, &es, u_lens_at_emitter, u_round, weighting);
    }
    // IBPT's scalar `d` (after the first vertex): Σ over the camera strategies of their squared density
    // ratios to light tracing, without the current vertex's reverse density.
    let mut mis_d = 0.0f32;
    // At the first vertex: `1/er²` for next-event estimation from it (`emission::nee_ratio`).
    let mut inv_nee_sq = 0.0f32;
    let mut beta = es.weight;
    let mut ray = Ray { origin: es.origin, dir: es.dir, t_min: 0.0, t_max: f32::MAX };
    // Segments from the emitter to the vertex about to be found.
    let mut depth = 1u32;
    let mut lambda = NO_WAVELENGTH;
    let mut mask_passes = 0u32;
    // As in `path`: the cheaper maximum where no channel can turn negative.
    let dispersion = crate::features::has(scene.features, crate::features::DISPERSION);
    let magnitude = |t: Rgb| if dispersion { max_abs_component(t) } else { max_component(t) };
    while max_depth == NONE || depth < max_depth {
        let bounce_dims = DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE;
        sampler.set_dimension(bounce_dims);
        let hit = match accel.trace(&ray, false, NONE) {
            Some(h) => h,
            None => break,
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        // Across a null interface as camera paths go (`mask`): no vertex, so depth and MIS state stay
        // as they are.
        let crossing = crate::mask::crossing(
            scene,
            &scene.materials[prim.material as usize],
            &sp,
            ray.dir,
            sampler,
            &mut mask_passes,
        );
        if crossing.through {
            beta *= crossing.weight;
            if mask_passes >= crate::mask::MAX_PASSES || magnitude(beta) <= 0.0 {
                break;
            }
            ray = crate::mask::onward(&sp, ray.dir);
            continue;
        }
        let mut material =
            scene.materials[crate::two_sided::seen(scene, prim.material, &sp, ray.dir) as usize];
        let dim_wavelength = bounce_dims + DIM_WAVELENGTH;
        beta *= disperse(scene, params, &mut material, &mut lambda, sampler, dim_wavelength);
        let shading = shading_frame(scene, &material, &prim, &hit, &sp, ray.dir);
        let (frame, ng, wo) = (shading.frame(), shading.ng, shading.wo);
        let bsdf = Bsdf::new(
            &material,
            scene.materials,
            scene.textures,
            scene.tables,
            sp.lookup(),
            scene.features,
            shading.tilt,
        );
        let wo_world = -ray.dir;
        let u_round = sampler.next_1d();
        let smooth = bsdf.flags().has_smooth();
        if ibpt && depth == 1 {
            // Next-event estimation from this vertex could have sampled the emitter point.
            inv_nee_sq = if smooth { inv_nee_ratio_sq(scene, &es, sp.p) } else { 0.0 };
        }

        // This vertex is `depth` segments from the emitter: connecting it makes `depth + 1`.
        if smooth {
            if let Some(c) = camera.connect(sp.p, lens_sample(sampler, bounce_dims + DIM_LENS_IN_BOUNCE)) {
                let to_camera = frame.to_local(c.dir);
                let f = bsdf.eval(wo, to_camera, IMPORTANCE);
                let corr = shading_normal_correction(wo_world, c.dir, frame.n, ng);
                let origin = offset_origin(&sp, ng, c.dir);
                let weighting = if ibpt {
                    // The camera path's density of the direction back along the light path from here.
                    let rho = bsdf.pdf(to_camera, wo, TransportMode::Radiance);
                    let kind = if depth == 1 { MIS_FIRST_VERTEX } else { MIS_LATER_VERTEX };
                    ConnectionMis { kind, rho, inv_hit_sq, inv_nee_sq, d: mis_d, ..NO_MIS }
                } else {
                    NO_MIS
                };
                let value = beta * f * corr;
                splat_to_camera(scene, params, &accel, words, origin, &c, value, NONE, u_round, weighting);
            }
        }
        if max_depth != NONE && depth + 1 >= max_depth {
            break;
        }

        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        // At a pane the crossing has chosen reflection already (`mask::Crossing::reflect_only`).
        let u_lobe = if crossing.reflect_only { 0.0 } else { u_lobe };
        let bs = bsdf.sample(wo, u_lobe, u_dir, IMPORTANCE);
        if bs.pdf <= 0.0 {
            break;
        }
        let wi = frame.to_world(bs.wi);
        if ibpt {
            // The camera path samples this vertex's direction back towards the light (`rho`) where light
            // tracing sampled `bs.pdf`; a Dirac lobe has the same probability both ways (and rules out
            // next-event estimation from the first vertex).
            let rho = if bs.delta { 1.0 } else { bsdf.pdf(bs.wi, wo, TransportMode::Radiance) };
            mis_d = mis::light_scalar_after(mis_d, depth == 1, bs.delta, inv_hit_sq, inv_nee_sq, rho, bs.pdf);
        }
        beta *= bs.weight * shading_normal_correction(wo_world, wi, frame.n, ng);
        ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        depth += 1;

        let u_rr = sampler.next_1d();
        if depth >= params.rr_depth {
            let q = magnitude(beta).min(0.95);
            if u_rr >= q {
                break;
            }
            beta /= q;
        }
        if magnitude(beta) <= 0.0 {
            break;
        }
    }
}

/// `1/er²` for next-event estimation from the first vertex `p` towards the emitter point of `es`:
/// the density ratio `emission::nee_ratio` of that light sample.
pub(super) fn inv_nee_ratio_sq(scene: &SceneView, es: &emission::EmissionSample, p: Vec3) -> f32 {
    let d = es.p - p;
    let dist2 = d.length_squared();
    if !(dist2 > 0.0) {
        return 0.0;
    }
    let dist = dist2.sqrt();
    let light = scene.lights[es.light as usize];
    // The light sample next-event estimation would have drawn for this point (its solid-angle density).
    let pdf = if es.delta_position {
        1.0
    } else {
        crate::light::pdf(&light, &scene.prims[light.prim as usize], p, es.p, es.n)
    };
    let ls = crate::light::LightSample {
        wi: d / dist,
        dist,
        radiance: Rgb::ZERO,
        pdf,
        delta: es.delta_position,
        prim: es.prim,
        light: es.light,
    };
    let r = emission::nee_ratio(scene, &ls);
    if r > 0.0 {
        1.0 / (r * r)
    } else {
        0.0
    }
}
