//! Unidirectional path tracing with next-event estimation, combined with BSDF sampling by the power
//! heuristic; Mitsuba's `path` semantics for `max_depth`, `rr_depth` and `hide_emitters`. As IBPT's
//! camera half it also weighs against light tracing (`LightTracingMis`, `docs/ibpt.md`).
use super::mis;
use super::nee::{
    area_emission, environment, first_hit_past_emitters, next_event, LightTracingMis, PreviousVertex,
    StrategyCounts,
};
use super::ptracer::film_scale;
use super::{disperse, shading_frame, NO_WAVELENGTH};
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::features;
use crate::instancing::surface_point;
use crate::layout::{FrameParams, SceneView, INTEGRATOR_IBPT, NONE};
use crate::mask;
use crate::math::{max_abs_component, max_component};
use crate::rng::Sampler;
use crate::shape::offset_origin;
use crate::spectrum::Rgb;

const ONE_EACH: StrategyCounts = StrategyCounts::ONE_EACH;

/// Random dimensions: the camera uses the first few; bounce `k` starts at a fixed offset so that all
/// paths use the same dimension for the same decision.
pub const DIM_FIRST_BOUNCE: u32 = 4;
pub const DIMS_PER_BOUNCE: u32 = 8;
/// The last of a bounce's dimensions: the wavelength a dispersive vertex draws (`disperse`).
pub const DIM_WAVELENGTH: u32 = DIMS_PER_BOUNCE - 1;
/// Pass `k` through a mask draws dimension `DIM_MASK + k`: pass-throughs leave the depth (and so
/// the bounce's dimensions) unchanged, so they draw from a range of their own.
pub const DIM_MASK: u32 = 1 << 24;

/// Radiance arriving along `ray`. `pixel_density`: under IBPT, the density with which the pixel's
/// camera samples land where this ray crosses the film (`film::pixel_density`; unused otherwise).
pub fn li(
    scene: &SceneView,
    params: &FrameParams,
    camera_ray: Ray,
    sampler: &mut Sampler,
    pixel_density: f32,
) -> Rgb {
    let accel = Accel::of(scene);
    let mut ray = camera_ray;
    let mut throughput = Rgb::ONE;
    let mut result = Rgb::ZERO;
    let mut eta_scale = 1.0f32;
    let mut depth = 0u32;
    let mut prev = PreviousVertex::camera(ray.origin);
    // IBPT: MIS against the light path that connects to the camera (`LightTracingMis`).
    let ibpt = params.integrator == INTEGRATOR_IBPT && features::has(scene.features, features::LIGHT_TRACER);
    let mut lt_scale = 0.0f32;
    let mut lambda = NO_WAVELENGTH;
    // Throughputs only turn negative in a channel in scenes with dispersion (`wavelength`); the others
    // keep the plain maximum: they run the instructions they ran before dispersion existed.
    let dispersion = features::has(scene.features, features::DISPERSION);
    let magnitude = |t: Rgb| if dispersion { max_abs_component(t) } else { max_component(t) };
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
                    result += throughput * environment(scene, params, ray.dir, &prev, ONE_EACH);
                }
                break;
            }
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        if ibpt && depth == 0 {
            // Light tracing reaches the first vertex by connecting it to the camera.
            // Through the aperture point this camera ray left from (thin lens).
            let lens = params.camera.lens_point_of(camera_ray.origin);
            lt_scale = match params.camera.connect_through(sp.p, lens) {
                Some(c) => {
                    mis::camera_scale_at_first_vertex(c.importance * pixel_density, film_scale(params))
                }
                None => 0.0,
            };
            prev.lt = lt_scale;
        }

        if prim.light != NONE {
            result += throughput * area_emission(scene, &prim, &sp, ray.dir, &prev, ONE_EACH);
        }

        // A mask lets the path through with probability 1 − opacity: straight on, no bounce (`mask`).
        let mut material = scene.materials[prim.material as usize];
        if mask::is_mask(scene, &material) {
            sampler.set_dimension(DIM_MASK + mask_passes);
            let u_mask = sampler.next_1d();
            sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
            mask_passes += 1;
            if u_mask >= mask::opacity(scene, &material, sp.uv) {
                if mask_passes >= mask::MAX_PASSES {
                    break;
                }
                let origin = offset_origin(&sp, sp.ng, ray.dir);
                ray = Ray { origin, dir: ray.dir, t_min: 0.0, t_max: f32::MAX };
                continue;
            }
        }

        if params.max_depth != NONE && depth + 1 >= params.max_depth {
            break;
        }

        let dim_wavelength = DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE + DIM_WAVELENGTH;
        throughput *= disperse(scene, params, &mut material, &mut lambda, sampler, dim_wavelength);
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

        let u_select = sampler.next_1d();
        let u_light = sampler.next_2d();
        if bsdf.flags().has_smooth() {
            result += throughput
                * next_event(
                    scene,
                    params,
                    &accel,
                    &bsdf,
                    &frame,
                    &sp,
                    ng,
                    wo,
                    u_select,
                    u_light,
                    ONE_EACH,
                    LightTracingMis { scale: lt_scale, first_vertex: depth == 0 },
                );
        }

        // BSDF sampling.
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Radiance);
        if bs.pdf <= 0.0 {
            break;
        }
        // No test of `wi` against the geometric normal: Mitsuba's integrators have none, and the
        // images must agree (the ray offset below still starts on the side `wi` leaves by).
        let wi = frame.to_world(bs.wi);
        throughput *= bs.weight;
        eta_scale *= bs.eta * bs.eta;
        if ibpt {
            // Light tracing samples this vertex's direction back towards the camera (not at the first
            // vertex, which it connects); a Dirac lobe has the same probability both ways, and at the
            // first vertex it leaves light tracing nothing to connect.
            let first = depth == 0;
            let reverse =
                if bs.delta || first { 1.0 } else { bsdf.pdf(bs.wi, wo, TransportMode::Importance) };
            lt_scale = mis::camera_scale_after(lt_scale, first, bs.delta, bs.pdf, reverse);
        }
        prev = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta, lt: lt_scale };
        ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        depth += 1;

        let u_rr = sampler.next_1d();
        if depth >= params.rr_depth {
            let q = (magnitude(throughput) * eta_scale).min(0.95);
            if u_rr >= q {
                break;
            }
            throughput /= q;
        }
        if magnitude(throughput) <= 0.0 {
            break;
        }
    }
    result
}
