//! Direct illumination (Mitsuba's `direct`): emission seen by the camera plus light arriving at the
//! first surface straight from an emitter, estimated with `emitter_samples` light samples and
//! `bsdf_samples` BSDF samples per pixel sample, combined by the power heuristic.
use super::nee::{
    area_emission, environment, first_hit_past_emitters, next_event, LightTracingMis, PreviousVertex,
    StrategyCounts,
};
use super::path::DIM_FIRST_BOUNCE;
use super::{disperse, shading_frame, NO_WAVELENGTH};
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::features;
use crate::instancing::surface_point;
use crate::layout::{FrameParams, SceneView, NONE};
use crate::mask;
use crate::math::max_component;
use crate::rng::Sampler;
use crate::shape::offset_origin;
use crate::spectrum::Rgb;

/// The dimension from which a dispersive surface draws its wavelength (past any sample's).
const DIM_WAVELENGTH: u32 = u32::MAX - 2;

/// Radiance arriving along `camera_ray` after at most one bounce.
pub fn li(scene: &SceneView, params: &FrameParams, camera_ray: Ray, sampler: &mut Sampler) -> Rgb {
    let accel = Accel::of(scene);
    let counts = StrategyCounts { light: params.emitter_samples as f32, bsdf: params.bsdf_samples as f32 };
    let camera = PreviousVertex::camera(camera_ray.origin);
    sampler.set_dimension(DIM_FIRST_BOUNCE);

    let hidden = params.hide_emitters != 0;
    let masks = features::has(scene.features, features::MASK);
    let trace_camera = |ray: &Ray| {
        if hidden {
            first_hit_past_emitters(scene, &accel, ray)
        } else {
            accel.trace(ray, false, NONE)
        }
    };
    let mut ray = camera_ray;
    let mut emitted = Rgb::ZERO;
    let mut passes = 0;
    // What crossed null interfaces lets through, and whether the last met a pane (`mask::Crossing`).
    let mut through = Rgb::ONE;
    let mut reflect_only = false;
    let (hit, prim, sp) = if !masks {
        // One trace, no loop, where the scene has no null interfaces (the frozen constant leaves this
        // branch alone in the pruned kernel).
        let hit = match trace_camera(&ray) {
            Some(h) => h,
            None if hidden => return emitted,
            None => return environment(scene, params, ray.dir, &camera, counts),
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        if prim.light != NONE {
            emitted = area_emission(scene, &prim, &sp, ray.dir, &camera, counts);
        }
        (hit, prim, sp)
    } else {
        // The camera ray crosses null interfaces as `path`'s does (`mask`): straight on, emitters it
        // meets on the way counted as seen directly.
        loop {
            let hit = match trace_camera(&ray) {
                Some(h) => h,
                None if hidden => return emitted,
                None => return emitted + through * environment(scene, params, ray.dir, &camera, counts),
            };
            let prim = scene.prims[hit.prim as usize];
            let sp = surface_point(scene, &prim, &hit, &ray);
            if prim.light != NONE {
                emitted += through * area_emission(scene, &prim, &sp, ray.dir, &camera, counts);
            }
            let material = &scene.materials[prim.material as usize];
            let crossing = mask::crossing(scene, material, &sp, ray.dir, sampler, &mut passes);
            if !crossing.through {
                reflect_only = crossing.reflect_only;
                break (hit, prim, sp);
            }
            through *= crossing.weight;
            if passes >= mask::MAX_PASSES || max_component(through) <= 0.0 {
                return emitted;
            }
            ray = mask::onward(&sp, ray.dir);
        }
    };

    let mut material = scene.materials[crate::two_sided::seen(scene, prim.material, &sp, ray.dir) as usize];
    let mut lambda = NO_WAVELENGTH;
    let dispersion = disperse(scene, params, &mut material, &mut lambda, sampler, DIM_WAVELENGTH);
    let mut result = Rgb::ZERO;
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

    if bsdf.flags().has_smooth() {
        let mut i = 0;
        while i < params.emitter_samples {
            let u_select = sampler.next_1d();
            let u_light = sampler.next_2d();
            result += next_event(
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
                counts,
                LightTracingMis::OFF,
            ) / counts.light;
            i += 1;
        }
    }

    let mut i = 0;
    while i < params.bsdf_samples {
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        // At a pane the crossing has chosen reflection already (`mask::Crossing::reflect_only`).
        let u_lobe = if reflect_only { 0.0 } else { u_lobe };
        i += 1;
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Radiance);
        if bs.pdf <= 0.0 {
            continue;
        }
        let wi = frame.to_world(bs.wi);
        let mut ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        let from = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta, lt: 0.0 };
        let le = if !masks {
            match accel.trace(&ray, false, NONE) {
                None => environment(scene, params, wi, &from, counts),
                Some(h) => {
                    let lit = scene.prims[h.prim as usize];
                    if lit.light == NONE {
                        continue;
                    }
                    area_emission(scene, &lit, &surface_point(scene, &lit, &h, &ray), wi, &from, counts)
                }
            }
        } else {
            // On across null interfaces as the camera ray (emitters met on the way count, weighted
            // from `sp`).
            let mut le = Rgb::ZERO;
            let mut crossed = Rgb::ONE;
            loop {
                let Some(h) = accel.trace(&ray, false, NONE) else {
                    le += crossed * environment(scene, params, ray.dir, &from, counts);
                    break;
                };
                let lit = scene.prims[h.prim as usize];
                let lit_material = scene.materials[lit.material as usize];
                if lit.light == NONE && !mask::is_null(scene, &lit_material) {
                    break;
                }
                let lit_sp = surface_point(scene, &lit, &h, &ray);
                if lit.light != NONE {
                    le += crossed * area_emission(scene, &lit, &lit_sp, ray.dir, &from, counts);
                }
                let crossing = mask::crossing(scene, &lit_material, &lit_sp, ray.dir, sampler, &mut passes);
                if !crossing.through {
                    break;
                }
                crossed *= crossing.weight;
                if passes >= mask::MAX_PASSES || max_component(crossed) <= 0.0 {
                    break;
                }
                ray = mask::onward(&lit_sp, ray.dir);
            }
            le
        };
        result += bs.weight * le / counts.bsdf;
    }
    emitted + through * dispersion * result
}
