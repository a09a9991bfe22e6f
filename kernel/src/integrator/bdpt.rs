//! Bidirectional path tracing and vertex connection and merging: for each pixel sample a light path
//! and a camera path, and every way of joining them: the camera path hitting an emitter, next-event
//! estimation from each camera vertex, each camera vertex connected to each vertex of its light path
//! by a shadow ray, each light vertex connected to the camera (light tracing, splatted wherever it
//! lands) and, under VCM, each camera vertex merged with every light vertex of the pass within the
//! merging radius (`vcm_grid`). The strategies are weighted by the power heuristic through the
//! recursive quantities of `bdpt_mis`, so that paths light tracing and IBPT cannot make, a caustic
//! seen in a mirror or through glass (light → specular → diffuse → specular → camera), are found.
//!
//! A pass traces every pixel's light path first, keeping its vertices in the pass's light vertex
//! cache (`CacheSlots`: `MAX_LIGHT_VERTICES` slots of `LightVertex` a path, so memory is bounded per
//! path and per pass), then every pixel's camera path, which connects to its own light path's
//! vertices (`CacheView`) and merges with all of them (`vcm_grid::GridView`). A path whose vertices
//! with a non-Dirac lobe number at most `MAX_LIGHT_VERTICES`, within `MAX_LIGHT_SEGMENTS + 1`
//! segments, is weighted over every strategy (`bidirectional`): a light path stops before a vertex it
//! could not keep, so every light sub-path of such a path is one a light path can be. Other paths
//! (where `max_depth` allows them) are made by the camera path alone, hitting an emitter or by
//! next-event estimation, weighted between those two as `path` weighs them. Each path therefore has a
//! set of strategies that all exist, and the weights sum to one over it. (Counting segments alone, a
//! chain of Dirac vertices in glass used up the light path's reach: the prism seen through itself
//! took a camera path of ten segments through the glass to the lamp at full weight: one sample of
//! 15,868 in a pixel of 0.006.)
//!
//! Light paths and camera paths follow `ptracer` and `path`: Mitsuba's `max_depth` (segments),
//! `rr_depth` and `hide_emitters`, null interfaces crossed without a vertex (`mask`), importance
//! transport with Veach's shading-normal correction on the light side. As under IBPT, no light path
//! starts on an emitter at infinity (camera paths alone carry their light), and a light path's emitter
//! point is connected to the camera and weighed against the camera path that sees it there.
//! Dispersive glass refracts every path of a pass at the pass's one wavelength (`pass_wavelength`), so
//! that light and camera vertices of any two paths can be joined; a light vertex records whether its
//! path dispersed (`LightVertex::dispersed`). The host refuses the radiance and irradiance meters, the
//! orthographic camera and `directionalarea` emitters under `bdpt` and `vcm`.
#[cfg(target_arch = "spirv")]
use spirv_std::num_traits::Float;

use super::bdpt_mis::{self, Connections, Merging, SubpathMis};
use super::nee::{
    environment, first_hit_past_emitters, next_event, LightTracingMis, PreviousVertex, StrategyCounts,
};
use super::pass_wavelength::PassWavelength;
use super::path::{DIMS_PER_BOUNCE, DIM_FIRST_BOUNCE, DIM_MASK};
use super::ptracer::{
    film_scale, inv_nee_ratio_sq, lens_sample, light_paths, shading_normal_correction, splat_emitter_point,
    splat_to_camera, ConnectionMis, DIM_LENS_AT_EMITTER, DIM_LENS_IN_BOUNCE,
};
use super::shading_frame;
use super::vcm_grid::GridView;
use crate::bsdf::perturb::{Perturbation, Shading};
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::glam::{Vec2, Vec3};
use crate::instancing::surface_point;
use crate::layout::{FrameParams, SceneView, NONE};
use crate::light::{self, emission};
use crate::mask;
use crate::math::max_component;
use crate::rng::{hash2, Sampler};
use crate::sampling::power_heuristic;
use crate::shape::{offset_origin, SurfacePoint};
use crate::spectrum::Rgb;
use crate::splat::AtomicWords;

/// The light path's vertices kept for connections (those with a non-Dirac lobe): paths with more are
/// weighted between the camera path's two strategies. Each vertex takes 208 bytes of the light vertex
/// cache (`kernel/tests/bdpt_mis.rs`).
pub const MAX_LIGHT_VERTICES: u32 = 8;
/// The light path's longest length in segments, Dirac vertices included: paths up to one segment
/// longer are weighted over all strategies where their non-Dirac vertices fit the cache.
pub const MAX_LIGHT_SEGMENTS: u32 = 32;
const SHADOW_EPSILON: f32 = 1.0e-4;
/// The dimension (plus the camera path's depth) from which a camera vertex draws the light vertex it
/// joins (`Connections`), beside the bounce's own (`DIMS_PER_BOUNCE`, all taken).
const DIM_CONNECT: u32 = 1 << 25;
const ONE_EACH: StrategyCounts = StrategyCounts::ONE_EACH;

/// A vertex of the light path with a non-Dirac lobe, as the light vertex cache holds it: where it is,
/// how it is shaded, the light path's throughput arriving there (`Le·…/p`, before its BSDF) and its
/// MIS state. Flat, `repr(C)`, of scalars and 3-arrays in 16-byte groups, so that Rust and the GPU
/// lay the storage buffer out alike (naga rounds a `Vec3` member up to 16 bytes: `perturb::Perturbation`).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct LightVertex {
    pub p: [f32; 3],
    pub error_scale: f32,
    /// The surface's geometric normal (`SurfacePoint::ng`).
    pub ng: [f32; 3],
    pub offset_floor: f32,
    pub ns: [f32; 3],
    /// The material seen there (a two-sided pair's side chosen).
    pub material: u32,
    pub uv: [f32; 2],
    pub bary: [f32; 2],
    pub beta: [f32; 3],
    pub mesh_attributes: u32,
    /// The shading frame (`Shading`): `s`, `t`, `n`, the geometric normal on its side and the
    /// direction back along the light path in it.
    pub s: [f32; 3],
    pub vcm: f32,
    pub t: [f32; 3],
    pub vc: f32,
    pub n: [f32; 3],
    /// Segments from the emitter (0 for an empty slot), with `DISPERSED` set where the light path
    /// met a dispersive material up to and including this vertex.
    pub depth: u32,
    pub shading_ng: [f32; 3],
    pub vm: f32,
    pub wo: [f32; 3],
    /// A normal or bump map's tilt (`Perturbation`): its flags, then its frame and tilted normal.
    pub tilt_flags: u32,
    pub tilt_s: [f32; 3],
    pub tilt_t: [f32; 3],
    pub tilt_nt: [f32; 3],
    pub tilt_n: [f32; 3],
}

#[inline]
fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

#[inline]
fn a3(v: Vec3) -> [f32; 3] {
    [v.x, v.y, v.z]
}

/// `LightVertex::depth`'s flag of a path that dispersed (`pass_wavelength`).
pub const DISPERSED: u32 = 1 << 31;

impl LightVertex {
    pub const EMPTY: LightVertex = LightVertex {
        p: [0.0; 3],
        error_scale: 0.0,
        ng: [0.0, 0.0, 1.0],
        offset_floor: 0.0,
        ns: [0.0, 0.0, 1.0],
        material: 0,
        uv: [0.0; 2],
        bary: [0.0; 2],
        beta: [0.0; 3],
        mesh_attributes: NONE,
        s: [1.0, 0.0, 0.0],
        vcm: 0.0,
        t: [0.0, 1.0, 0.0],
        vc: 0.0,
        n: [0.0, 0.0, 1.0],
        depth: 0,
        shading_ng: [0.0, 0.0, 1.0],
        vm: 0.0,
        wo: [0.0, 0.0, 1.0],
        tilt_flags: 0,
        tilt_s: [1.0, 0.0, 0.0],
        tilt_t: [0.0, 1.0, 0.0],
        tilt_nt: [0.0, 0.0, 1.0],
        tilt_n: [0.0, 0.0, 1.0],
    };

    #[inline]
    fn new(
        sp: &SurfacePoint,
        shading: &Shading,
        material: u32,
        beta: Rgb,
        mis: SubpathMis,
        depth: u32,
    ) -> Self {
        LightVertex {
            p: a3(sp.p),
            error_scale: sp.error_scale,
            ng: a3(sp.ng),
            offset_floor: sp.offset_floor,
            ns: a3(sp.ns),
            material,
            uv: [sp.uv.x, sp.uv.y],
            bary: [sp.bary.x, sp.bary.y],
            beta: a3(beta),
            mesh_attributes: sp.mesh_attributes,
            s: a3(shading.s),
            vcm: mis.vcm,
            t: a3(shading.t),
            vc: mis.vc,
            n: a3(shading.n),
            depth,
            shading_ng: a3(shading.ng),
            vm: mis.vm,
            wo: a3(shading.wo),
            tilt_flags: shading.tilt.flags,
            tilt_s: a3(shading.tilt.s),
            tilt_t: a3(shading.tilt.t),
            tilt_nt: a3(shading.tilt.nt),
            tilt_n: a3(shading.tilt.n),
        }
    }

    /// Segments from the emitter (0 for an empty slot).
    #[inline]
    pub fn segments(&self) -> u32 {
        self.depth & !DISPERSED
    }

    /// Whether the light path dispersed on its way here (this vertex included).
    #[inline]
    pub fn dispersed(&self) -> bool {
        self.depth & DISPERSED != 0
    }

    #[inline]
    pub fn position(&self) -> Vec3 {
        v3(self.p)
    }

    #[inline]
    pub fn throughput(&self) -> Rgb {
        v3(self.beta)
    }

    #[inline]
    fn surface_point(&self) -> SurfacePoint {
        SurfacePoint {
            p: v3(self.p),
            ng: v3(self.ng),
            ns: v3(self.ns),
            error_scale: self.error_scale,
            offset_floor: self.offset_floor,
            uv: Vec2::new(self.uv[0], self.uv[1]),
            mesh_attributes: self.mesh_attributes,
            bary: Vec2::new(self.bary[0], self.bary[1]),
        }
    }

    #[inline]
    pub fn mis(&self) -> SubpathMis {
        SubpathMis { vcm: self.vcm, vc: self.vc, vm: self.vm }
    }

    #[inline]
    pub fn shading(&self) -> Shading {
        let tilt = Perturbation {
            s: v3(self.tilt_s),
            t: v3(self.tilt_t),
            nt: v3(self.tilt_nt),
            n: v3(self.tilt_n),
            flags: self.tilt_flags,
            _pad: [0; 3],
        };
        Shading {
            s: v3(self.s),
            t: v3(self.t),
            n: v3(self.n),
            ng: v3(self.shading_ng),
            wo: v3(self.wo),
            tilt,
        }
    }
}

/// One light path's `MAX_LIGHT_VERTICES` slots of the light vertex cache, from `base`.
pub struct CacheSlots<'a> {
    pub cache: &'a mut [LightVertex],
    pub base: u32,
}

impl CacheSlots<'_> {
    #[inline]
    fn put(&mut self, k: u32, v: LightVertex) {
        self.cache[(self.base + k) as usize] = v;
    }

    /// After the path's `count` vertices: the slots past them are marked empty (they hold the last
    /// pass's). Their depth alone, which is all that anything reads of an empty slot (`CacheView::count`,
    /// `vcm_grid::link`): emptying the whole 208 bytes took a third of the light pass's cache writes on
    /// the Cornell box, whose light paths keep five vertices of eight.
    #[inline]
    fn finish(&mut self, count: u32) {
        let mut k = count;
        while k < MAX_LIGHT_VERTICES {
            self.cache[(self.base + k) as usize].depth = 0;
            k += 1;
        }
    }
}

/// One light path's slots of the light vertex cache, read by its camera path.
pub struct CacheView<'a> {
    pub cache: &'a [LightVertex],
    pub base: u32,
}

impl CacheView<'_> {
    #[inline]
    fn vertex(&self, k: u32) -> LightVertex {
        self.cache[(self.base + k) as usize]
    }

    /// Segments from the emitter to vertex `k` (its depth alone read).
    #[inline]
    fn segments(&self, k: u32) -> u32 {
        self.cache[(self.base + k) as usize].depth & !DISPERSED
    }

    /// The path's vertices: those before the first empty slot (their depth alone read).
    #[inline]
    pub fn count(&self) -> u32 {
        let mut count = 0;
        while count < MAX_LIGHT_VERTICES && self.cache[(self.base + count) as usize].depth > 0 {
            count += 1;
        }
        count
    }
}

/// A camera vertex's path state, as the strategies that join it to light vertices see it: its MIS
/// state, its `segments` from the camera, its vertices with a non-Dirac lobe (`smooth`, this one
/// included) and whether its path `dispersed` on the way (this vertex included), with the pass's
/// `wavelength`. Its BSDF, shading and point travel beside it as separate
/// references: a struct of pointers to function-local values is a type naga rejects in the SPIR-V
/// rust-gpu emits ("Type [68] '' is invalid", on every entry point), where plain values pass.
#[derive(Clone, Copy)]
pub struct CameraVertex {
    pub mis: SubpathMis,
    pub segments: u32,
    pub smooth: u32,
    pub dispersed: bool,
    pub wavelength: PassWavelength,
}

/// Whether a path of `segments`, `smooth` of whose vertices between its ends have a non-Dirac lobe,
/// is weighted over every strategy: whether each of its light sub-paths is within a light path's reach.
#[inline]
pub fn bidirectional(segments: u32, smooth: u32) -> bool {
    segments <= MAX_LIGHT_SEGMENTS + 1 && smooth <= MAX_LIGHT_VERTICES
}

/// Whether light paths connect their emitter points to the camera: where a camera path may see an
/// emitter (not with `hide_emitters`; not where `max_depth` 0 allows no segment).
#[inline]
fn sees_emitter_points(params: &FrameParams) -> bool {
    params.hide_emitters == 0 && params.max_depth != 0
}

/// Whether `max_depth` (`NONE`: unbounded) allows a path of `segments`.
#[inline]
pub fn within(max_depth: u32, segments: u32) -> bool {
    max_depth == NONE || segments <= max_depth
}

/// Traces a light path, splats each of its vertices' connections to the camera where `to_camera`
/// (`ptracer::connects_to_camera`) and keeps the vertices a camera path can connect to; returns how
/// many it kept.
pub fn trace_light_path<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    sampler: &mut Sampler,
    words: &mut W,
    vertices: &mut CacheSlots,
    to_camera: bool,
) -> u32 {
    let count = light_path_vertices(scene, params, sampler, words, vertices, to_camera);
    vertices.finish(count);
    count
}

fn light_path_vertices<W: AtomicWords>(
    scene: &SceneView,
    params: &FrameParams,
    sampler: &mut Sampler,
    words: &mut W,
    vertices: &mut CacheSlots,
    to_camera: bool,
) -> u32 {
    let accel = Accel::of(scene);
    let camera = params.camera;
    let merging = Merging::of(params);
    let connections = Connections::of(params);
    let wavelength = PassWavelength::of(scene, params);
    let mut dispersed = false;
    // The emitter sample's dimensions as `ptracer` draws them.
    let u_select = sampler.next_1d();
    let u_pos = sampler.next_2d();
    let u_dir = sampler.next_2d();
    let es = emission::sample(scene, params, u_select, u_pos, u_dir);
    if es.light == NONE || max_component(es.weight) <= 0.0 {
        return 0;
    }
    let max_depth = params.max_depth;
    let hit_density = if es.delta_position { 0.0 } else { emission::hit_density(scene, es.light) };
    let inv_hit_sq = if hit_density > 0.0 { 1.0 / (hit_density * hit_density) } else { 0.0 };
    if to_camera && sees_emitter_points(params) && !es.delta_position && !es.infinite {
        // The emitter point itself to the camera: against the camera path that sees it (`camera_path`).
        let u_round = sampler.next_1d();
        let u_lens = lens_sample(sampler, DIM_LENS_AT_EMITTER);
        let weighting = ConnectionMis::emitter_point(inv_hit_sq, light_paths(params));
        splat_emitter_point(scene, params, &accel, words, &es, u_lens, u_round, weighting);
    }
    let mut mis = SubpathMis::ZERO;
    let mut beta = es.weight;
    let mut ray = Ray { origin: es.origin, dir: es.dir, t_min: 0.0, t_max: f32::MAX };
    let mut previous = es.p;
    let mut depth = 1u32;
    let mut count = 0u32;
    let mut mask_passes = 0u32;
    while depth <= MAX_LIGHT_SEGMENTS && (max_depth == NONE || depth < max_depth) {
        let bounce_dims = DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE;
        sampler.set_dimension(bounce_dims);
        let hit = match accel.trace(&ray, false, NONE) {
            Some(h) => h,
            None => break,
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        let crossing = mask::crossing(
            scene,
            &scene.materials[prim.material as usize],
            &sp,
            ray.dir,
            sampler,
            &mut mask_passes,
        );
        if crossing.through {
            beta *= crossing.weight;
            if mask_passes >= mask::MAX_PASSES || max_component(beta) <= 0.0 {
                break;
            }
            ray = mask::onward(&sp, ray.dir);
            continue;
        }
        let material_index = crate::two_sided::seen(scene, prim.material, &sp, ray.dir);
        let mut material = scene.materials[material_index as usize];
        dispersed |= wavelength.disperse(&mut material);
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
        let cos_in = sp.ng.dot(ray.dir).abs();
        mis = if depth == 1 {
            let inv_nee_sq = if smooth { inv_nee_ratio_sq(scene, &es, sp.p) } else { 0.0 };
            SubpathMis::light_first_vertex(inv_nee_sq, inv_hit_sq, cos_in, merging, connections)
        } else {
            mis.arrive((sp.p - previous).length_squared(), cos_in)
        };

        if smooth {
            // A path through more such vertices than the cache keeps is the camera path's alone. Each
            // one is kept (a camera vertex connecting to it makes a path of `depth + 1` segments, which
            // the loop's bound keeps within `max_depth`), so its slot says how many came before it.
            if count >= MAX_LIGHT_VERTICES {
                break;
            }
            let flagged = if dispersed { depth | DISPERSED } else { depth };
            vertices.put(count, LightVertex::new(&sp, &shading, material_index, beta, mis, flagged));
            count += 1;
            let c = if to_camera {
                camera.connect(sp.p, lens_sample(sampler, bounce_dims + DIM_LENS_IN_BOUNCE))
            } else {
                None
            };
            if let Some(c) = c {
                let to_camera = frame.to_local(c.dir);
                let f = bsdf.eval(wo, to_camera, TransportMode::Importance);
                let corr = shading_normal_correction(wo_world, c.dir, frame.n, ng);
                let origin = offset_origin(&sp, ng, c.dir);
                // The camera path's density of leaving here back along the light path.
                let rev = bsdf.pdf(to_camera, wo, TransportMode::Radiance);
                let weighting = ConnectionMis::bdpt(mis, sp.ng.dot(c.dir).abs(), rev, merging, connections);
                splat_to_camera(
                    scene,
                    params,
                    &accel,
                    words,
                    origin,
                    &c,
                    beta * f * corr * wavelength.factor(dispersed),
                    NONE,
                    u_round,
                    weighting,
                );
            }
        }
        if depth >= MAX_LIGHT_SEGMENTS || (max_depth != NONE && depth + 1 >= max_depth) {
            break;
        }

        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let u_lobe = if crossing.reflect_only { 0.0 } else { u_lobe };
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Importance);
        if bs.pdf <= 0.0 {
            break;
        }
        let wi = frame.to_world(bs.wi);
        let rev = if bs.delta { bs.pdf } else { bsdf.pdf(bs.wi, wo, TransportMode::Radiance) };
        mis = mis.scatter(bs.delta, bs.pdf, rev, sp.ng.dot(wi).abs(), merging);
        beta *= bs.weight * shading_normal_correction(wo_world, wi, frame.n, ng);
        previous = sp.p;
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
    count
}

/// `FrameParams::connection_rate` in (0, 1] (`super::share_in_unit`).
#[inline]
pub fn connection_rate(params: &FrameParams) -> f32 {
    super::share_in_unit(params.connection_rate)
}

/// The stream of the camera vertices' draws of whether they join (`connection_rate`), apart from
/// every path's.
const RATE_STREAM: u32 = 0x3c6e_f372;

/// The camera path of one pixel sample (of `pixel`) with its strategies: emitters hit, next-event
/// estimation, connections to its light path's `vertices` and, under VCM, merges with the pass's
/// light vertices (`grid`; under BDPT `Merging::OFF` leaves it unread).
#[allow(clippy::too_many_arguments)]
pub fn camera_path(
    scene: &SceneView,
    params: &FrameParams,
    pixel: u32,
    camera_ray: Ray,
    sampler: &mut Sampler,
    pixel_density: f32,
    vertices: &CacheView,
    grid: &GridView,
) -> Rgb {
    let count = vertices.count();
    let accel = Accel::of(scene);
    let max_depth = params.max_depth;
    let merging = Merging::of(params);
    let connections = Connections::of(params);
    let draws_one = params.connection_share > 0.0;
    let rate = connection_rate(params);
    let wavelength = PassWavelength::of(scene, params);
    let mut dispersed = false;
    let lens = params.camera.lens_point_of(camera_ray.origin);
    let mut ray = camera_ray;
    let mut throughput = Rgb::ONE;
    let mut result = Rgb::ZERO;
    let mut eta_scale = 1.0f32;
    let mut mis = SubpathMis::ZERO;
    // The path's vertices with a non-Dirac lobe so far (`bidirectional`).
    let mut smooth = 0u32;
    let mut prev = PreviousVertex::camera(camera_ray.origin);
    // Segments to the vertex about to be found, less one.
    let mut depth = 0u32;
    let mut mask_passes = 0u32;
    loop {
        sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
        let visible_emitter = !(depth == 0 && params.hide_emitters != 0);
        let found = if visible_emitter {
            accel.trace(&ray, false, NONE)
        } else {
            first_hit_past_emitters(scene, &accel, &ray)
        };
        let hit = match found {
            Some(h) => h,
            None => {
                if visible_emitter {
                    // Environments start no light path: weighed against next-event estimation alone.
                    let le = environment(scene, params, ray.dir, &prev, ONE_EACH);
                    result += throughput * le * wavelength.factor(dispersed);
                }
                break;
            }
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        let segments = depth + 1;
        let cos_in = sp.ng.dot(ray.dir).abs();
        let dist_sq = (sp.p - prev.p).length_squared();
        let arrived = if depth == 0 {
            // Light tracing reaches the first vertex by connecting it to the camera, through the
            // aperture point this ray left from.
            let a = match params.camera.connect_through(sp.p, lens) {
                Some(c) => c.importance * pixel_density * film_scale(params) * cos_in,
                None => 0.0,
            };
            SubpathMis::camera_first_vertex(a, connections)
        } else {
            mis.arrive(dist_sq, cos_in)
        };

        if prim.light != NONE {
            let emitter = scene.lights[prim.light as usize];
            let le = light::emitted_at(scene, &emitter, sp.ns, -ray.dir, sp.uv);
            let weight = if depth == 0 {
                // Seen by the camera: the light path's emitter point connected to the camera is the
                // other strategy (`light_path_vertices`), at light tracing's density of that point.
                let point = if sees_emitter_points(params) {
                    emission::hit_density(scene, prim.light) * cos_in
                } else {
                    0.0
                };
                bdpt_mis::seen_weight(arrived, point, light_paths(params), connections)
            } else if prev.delta {
                // Through Dirac lobes alone: the recursion's terms decide.
                if !bidirectional(segments, smooth) {
                    1.0
                } else {
                    let emission = emission::hit_density(scene, prim.light) * cos_in;
                    bdpt_mis::hit_weight(arrived, 0.0, emission, connections)
                }
            } else {
                let direct = light::pdf(&emitter, &prim, prev.p, sp.p, sp.ng);
                if bidirectional(segments, smooth) {
                    let direct_area = bdpt_mis::to_area(direct, dist_sq, cos_in);
                    let emission = emission::hit_density(scene, prim.light) * cos_in;
                    bdpt_mis::hit_weight(arrived, direct_area, emission, connections)
                } else {
                    power_heuristic(prev.pdf, direct)
                }
            };
            result += throughput * le * (weight * wavelength.factor(dispersed));
        }

        let mut material =
            scene.materials[crate::two_sided::seen(scene, prim.material, &sp, ray.dir) as usize];
        let mut reflect_only = false;
        if mask::is_null(scene, &material) {
            sampler.set_dimension(DIM_MASK + mask_passes);
            let u_mask = sampler.next_1d();
            sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
            mask_passes += 1;
            let crossing = mask::cross(scene, &material, &sp, ray.dir, u_mask);
            if crossing.through {
                throughput *= crossing.weight;
                if mask_passes >= mask::MAX_PASSES || max_component(throughput) <= 0.0 {
                    break;
                }
                ray = mask::onward(&sp, ray.dir);
                continue;
            }
            reflect_only = crossing.reflect_only;
        }
        if max_depth != NONE && segments >= max_depth {
            break;
        }
        dispersed |= wavelength.disperse(&mut material);
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
        mis = arrived;

        // The light vertex this vertex joins where it joins one (`Connections`): a dimension of its
        // own, so that joining every vertex draws what it drew before.
        let u_connect = if draws_one {
            sampler.set_dimension(DIM_CONNECT + depth);
            let u = sampler.next_1d();
            sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
            u
        } else {
            0.0
        };
        let u_select = sampler.next_1d();
        let u_light = sampler.next_2d();
        if bsdf.flags().has_smooth() {
            smooth += 1;
            let weighting = LightTracingMis::bdpt(mis, bidirectional(segments + 1, smooth));
            let nee = next_event(
                scene, params, &accel, &bsdf, &frame, &sp, ng, wo, u_select, u_light, ONE_EACH, weighting,
            );
            result += throughput * nee * wavelength.factor(dispersed);
            let vertex = CameraVertex { mis, segments, smooth, dispersed, wavelength };
            result += throughput * grid.merge(&bsdf, &shading, &sp, vertex, max_depth, merging);
            // Every vertex of the light path, or one drawn uniformly and counted `count` times; at this
            // vertex with probability `rate` (the same for the tile's vertices at this depth), counted
            // `1 / rate` times.
            let joins = rate >= 1.0
                || super::tile_draw(params, pixel, params.sample_base, hash2(RATE_STREAM, depth)) < rate;
            let (mut k, end, scale) = if !joins {
                (0, 0, 0.0)
            } else if draws_one {
                let k = ((u_connect * count as f32) as u32).min(count.max(1) - 1);
                (k, (k + 1).min(count), count as f32 / rate)
            } else {
                (0, count, 1.0 / rate)
            };
            while k < end {
                // Its depth first, its 208 bytes only for a connection made.
                let length = segments + vertices.segments(k) + 1;
                if within(max_depth, length) && bidirectional(length, smooth + k + 1) {
                    let v = vertices.vertex(k);
                    let joined = connect(scene, &accel, &bsdf, &shading, &sp, vertex, &v, merging);
                    result += throughput * joined * scale;
                }
                k += 1;
            }
        }

        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let u_lobe = if reflect_only { 0.0 } else { u_lobe };
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Radiance);
        if bs.pdf <= 0.0 {
            break;
        }
        let wi = frame.to_world(bs.wi);
        throughput *= bs.weight;
        eta_scale *= bs.eta * bs.eta;
        let rev = if bs.delta { bs.pdf } else { bsdf.pdf(bs.wi, wo, TransportMode::Importance) };
        mis = mis.scatter(bs.delta, bs.pdf, rev, sp.ng.dot(wi).abs(), merging);
        prev = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta, lt: 0.0 };
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

/// Camera vertex `camera` connected to light vertex `v` by a shadow ray: both BSDFs (the light
/// vertex's material refracting at the pass's wavelength), the geometry between them, the light path's
/// throughput and the weight.
#[allow(clippy::too_many_arguments)]
fn connect(
    scene: &SceneView,
    accel: &Accel,
    bsdf: &Bsdf,
    shading: &Shading,
    sp: &SurfacePoint,
    camera: CameraVertex,
    v: &LightVertex,
    merging: Merging,
) -> Rgb {
    let d = v.position() - sp.p;
    let dist_sq = d.length_squared();
    if !(dist_sq > 0.0) {
        return Rgb::ZERO;
    }
    let dist = dist_sq.sqrt();
    let dir = d / dist;
    let frame = shading.frame();
    let wi = frame.to_local(dir);
    let ep = bsdf.eval_pdf(shading.wo, wi, TransportMode::Radiance);
    if max_component(ep.f) <= 0.0 {
        return Rgb::ZERO;
    }
    let light_shading = v.shading();
    let light_frame = light_shading.frame();
    let light_sp = v.surface_point();
    let mut light_material = scene.materials[v.material as usize];
    camera.wavelength.disperse(&mut light_material);
    let light_bsdf = Bsdf::new(
        &light_material,
        scene.materials,
        scene.textures,
        scene.tables,
        light_sp.lookup(),
        scene.features,
        light_shading.tilt,
    );
    let to_camera = light_frame.to_local(-dir);
    let light_ep = light_bsdf.eval_pdf(light_shading.wo, to_camera, TransportMode::Importance);
    if max_component(light_ep.f) <= 0.0 {
        return Rgb::ZERO;
    }
    let corr = shading_normal_correction(
        light_frame.to_world(light_shading.wo),
        -dir,
        light_frame.n,
        light_shading.ng,
    );
    // Each side's density of sampling the other's vertex, and of leaving its own back along its path.
    let camera_rev = bsdf.pdf(wi, shading.wo, TransportMode::Importance);
    let light_rev = light_bsdf.pdf(to_camera, light_shading.wo, TransportMode::Radiance);
    let light_side =
        v.mis().others(bdpt_mis::to_area(ep.pdf, dist_sq, v3(v.ng).dot(dir).abs()), light_rev, merging);
    let camera_side = camera.mis.others(
        bdpt_mis::to_area(light_ep.pdf, dist_sq, sp.ng.dot(dir).abs()),
        camera_rev,
        merging,
    );
    let weight = bdpt_mis::weight(light_side, camera_side);
    let value = ep.f * light_ep.f * v.throughput() * (corr * weight / dist_sq);
    if max_component(value) <= 0.0 {
        return Rgb::ZERO;
    }
    let origin = offset_origin(sp, shading.ng, dir);
    let target = offset_origin(&light_sp, light_shading.ng, -dir);
    let to_target = target - origin;
    let length = to_target.length();
    let shadow = Ray { origin, dir: to_target / length, t_min: 0.0, t_max: length * (1.0 - SHADOW_EPSILON) };
    let factor = camera.wavelength.factor(camera.dispersed || v.dispersed());
    value * factor * mask::transmittance(scene, accel, &shadow, NONE)
}
