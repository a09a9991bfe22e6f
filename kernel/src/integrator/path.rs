//! Unidirectional path tracing with next-event estimation, combined with BSDF sampling by the power
//! heuristic; Mitsuba's `path` semantics for `max_depth`, `rr_depth` and `hide_emitters`. As IBPT's
//! camera half it also weighs against light tracing (`LightTracingMis`, `docs/ibpt.md`).
use super::mis;
use super::nee::{
    environment, first_hit_past_emitters, next_event, seen_area_emission, LightTracingMis, PreviousVertex,
    StrategyCounts,
};
use super::ptracer::{film_scale, light_paths};
use super::{disperse, shading_frame, NO_WAVELENGTH};
use crate::bsdf::{Bsdf, TransportMode};
use crate::bvh::Accel;
use crate::camera::Ray;
use crate::features;
use crate::glam::Vec3;
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
/// camera samples land where this ray crosses the film (`film::camera_density`; unused otherwise).
pub fn li(
    scene: &SceneView,
    params: &FrameParams,
    camera_ray: Ray,
    sampler: &mut Sampler,
    pixel_density: f32,
) -> Rgb {
    let mut path = CameraPath::new(camera_ray, pixel_density);
    while path.bounce(scene, params, sampler) {}
    path.result
}

/// A camera path in flight: what one vertex hands the next. `li` follows one to its end;
/// `render_pixel` may run a pixel's samples as one loop of bounces, so that on the GPU a lane whose
/// path ended starts its next sample at once instead of idling until the longest path of its warp
/// ends (path regeneration).
#[derive(Clone, Copy)]
pub struct CameraPath {
    ray: Ray,
    /// Where the camera ray left the lens (IBPT connects the first vertex through it).
    lens_origin: Vec3,
    pixel_density: f32,
    throughput: Rgb,
    /// The radiance gathered so far: the path's estimate once `bounce` returns false.
    pub result: Rgb,
    eta_scale: f32,
    depth: u32,
    prev: PreviousVertex,
    /// IBPT: MIS against the light path that connects to the camera (`LightTracingMis`).
    lt_scale: f32,
    lambda: f32,
    mask_passes: u32,
}

impl CameraPath {
    pub fn new(camera_ray: Ray, pixel_density: f32) -> Self {
        CameraPath {
            ray: camera_ray,
            lens_origin: camera_ray.origin,
            pixel_density,
            throughput: Rgb::ONE,
            result: Rgb::ZERO,
            eta_scale: 1.0,
            depth: 0,
            prev: PreviousVertex::camera(camera_ray.origin),
            lt_scale: 0.0,
            lambda: NO_WAVELENGTH,
            mask_passes: 0,
        }
    }

    /// Follows the path to its next vertex and scatters there; false once the path has ended.
    pub fn bounce(&mut self, scene: &SceneView, params: &FrameParams, sampler: &mut Sampler) -> bool {
        let accel = Accel::of(scene);
        let ibpt =
            params.integrator == INTEGRATOR_IBPT && features::has(scene.features, features::LIGHT_TRACER);
        // Throughputs only turn negative in a channel in scenes with dispersion (`wavelength`); the
        // others keep the plain maximum: they run the instructions they ran before dispersion existed.
        let dispersion = features::has(scene.features, features::DISPERSION);
        let magnitude = |t: Rgb| if dispersion { max_abs_component(t) } else { max_component(t) };
        let depth = self.depth;
        let ray = self.ray;

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
                    self.result +=
                        self.throughput * environment(scene, params, ray.dir, &self.prev, ONE_EACH);
                }
                return false;
            }
        };
        let prim = scene.prims[hit.prim as usize];
        let sp = surface_point(scene, &prim, &hit, &ray);
        if ibpt && depth == 0 {
            // Light tracing reaches the first vertex by connecting it to the camera.
            // Through the aperture point this camera ray left from (thin lens).
            let lens = params.camera.lens_point_of(self.lens_origin);
            self.lt_scale = match params.camera.connect_through(sp.p, lens) {
                Some(c) => {
                    mis::camera_scale_at_first_vertex(c.importance * self.pixel_density, film_scale(params))
                }
                None => 0.0,
            };
            self.prev.lt = self.lt_scale;
        }

        if prim.light != NONE {
            // Seen by the camera under IBPT: against the emitter point's splat (`mis::seen_ratio_sq`).
            let seen = if ibpt && depth == 0 { light_paths(params) } else { 0.0 };
            self.result +=
                self.throughput * seen_area_emission(scene, &prim, &sp, ray.dir, &self.prev, ONE_EACH, seen);
        }

        // A null interface (a mask, a thin dielectric's transmission) lets the path through: straight
        // on, no bounce (`mask`).
        let mut material =
            scene.materials[crate::two_sided::seen(scene, prim.material, &sp, ray.dir) as usize];
        let mut reflect_only = false;
        if mask::is_null(scene, &material) {
            sampler.set_dimension(DIM_MASK + self.mask_passes);
            let u_mask = sampler.next_1d();
            sampler.set_dimension(DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE);
            self.mask_passes += 1;
            let crossing = mask::cross(scene, &material, &sp, ray.dir, u_mask);
            if crossing.through {
                self.throughput *= crossing.weight;
                if self.mask_passes >= mask::MAX_PASSES || magnitude(self.throughput) <= 0.0 {
                    return false;
                }
                self.ray = mask::onward(&sp, ray.dir);
                return true;
            }
            reflect_only = crossing.reflect_only;
        }

        if params.max_depth != NONE && depth + 1 >= params.max_depth {
            return false;
        }

        let dim_wavelength = DIM_FIRST_BOUNCE + depth * DIMS_PER_BOUNCE + DIM_WAVELENGTH;
        self.throughput *= disperse(scene, params, &mut material, &mut self.lambda, sampler, dim_wavelength);
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
            self.result += self.throughput
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
                    LightTracingMis::ibpt(self.lt_scale, depth == 0),
                );
        }

        // BSDF sampling.
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        // At a pane the crossing has chosen reflection already (`mask::Crossing::reflect_only`).
        let u_lobe = if reflect_only { 0.0 } else { u_lobe };
        let bs = bsdf.sample(wo, u_lobe, u_dir, TransportMode::Radiance);
        if bs.pdf <= 0.0 {
            return false;
        }
        // No test of `wi` against the geometric normal: Mitsuba's integrators have none, and the
        // images must agree (the ray offset below still starts on the side `wi` leaves by).
        let wi = frame.to_world(bs.wi);
        self.throughput *= bs.weight;
        self.eta_scale *= bs.eta * bs.eta;
        if ibpt {
            // Light tracing samples this vertex's direction back towards the camera (not at the first
            // vertex, which it connects); a Dirac lobe has the same probability both ways, and at the
            // first vertex it leaves light tracing nothing to connect.
            let first = depth == 0;
            let reverse =
                if bs.delta || first { 1.0 } else { bsdf.pdf(bs.wi, wo, TransportMode::Importance) };
            self.lt_scale = mis::camera_scale_after(self.lt_scale, first, bs.delta, bs.pdf, reverse);
        }
        self.prev = PreviousVertex { p: sp.p, pdf: bs.pdf, delta: bs.delta, lt: self.lt_scale };
        self.ray = Ray { origin: offset_origin(&sp, ng, wi), dir: wi, t_min: 0.0, t_max: f32::MAX };
        self.depth = depth + 1;

        let u_rr = sampler.next_1d();
        if self.depth >= params.rr_depth {
            let q = (magnitude(self.throughput) * self.eta_scale).min(0.95);
            if u_rr >= q {
                return false;
            }
            self.throughput /= q;
        }
        // (Not `> 0.0`: a NaN throughput goes on, as it always has, and is counted invalid at the end.)
        if magnitude(self.throughput) <= 0.0 {
            return false;
        }
        true
    }
}
