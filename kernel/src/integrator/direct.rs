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
use crate::instancing::surface_point;
use crate::layout::{FrameParams, SceneView, NONE};
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
    let found = if hidden {
        first_hit_past_emitters(scene, &accel, &camera_ray)
    } else {
        accel.trace(&camera_ray, false, NONE)
    };
    let hit = match found {
        Some(h) => h,
        None if hidden => return Rgb::ZERO,
        None => return environment(scene, params, camera_ray.dir, &camera, counts),
    };
    let prim = scene.prims[hit.prim as usize];
    let sp = surface_point(scene, &prim, &hit, &camera_ray);
    let mut emitted = Rgb::ZERO;
    if prim.light != NONE {
        emitted = area_emission(scene, &prim, &sp, camera_ray.dir, &camera, counts);
    }

    let mut material = scene.materials[prim.material as usize];
    let mut lambda = NO_WAVELENGTH;
    let dispersion = disperse(scene, params, &mut material, &mut lambda, sampler, DIM_WAVELENGTH);
    let mut result = Rgb::ZERO;
    let shading = shading_frame(scene, &material, &prim, &hit, &sp, camera_ray.dir);
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
        i += 1;
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Radiance);
        if bs.pdf <= 0.0 {
            continue;
        }
        let wi = frame.to_world(bs.wi);
        let ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        let from = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta, lt: 0.0 };
        let le = match accel.trace(&ray, false, NONE) {
            None => environment(scene, params, wi, &from, counts),
            Some(h) => {
                let lit = scene.prims[h.prim as usize];
                if lit.light == NONE {
                    continue;
                }
                area_emission(scene, &lit, &surface_point(scene, &lit, &h, &ray), wi, &from, counts)
            }
        };
        result += bs.weight * le / counts.bsdf;
    }
    emitted + dispersion * result
}
