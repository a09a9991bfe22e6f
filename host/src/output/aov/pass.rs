//! Rendering the AOVs: each pixel's camera rays (the image's own: same seed, pixel and sample index,
//! so the same film positions and lens points) to their first hit, averaged as the image is. The
//! film sample is drawn from the reconstruction filter (`caustic_kernel::film`), so the mean of the
//! samples' values converges to Mitsuba's filter-weighted average over the pixel; with negative
//! lobes each value carries the sample's signed weight, as the image's do.
//!
//! It runs on the CPU for either backend, with the kernel's own code linked natively (intersection,
//! surface points, tangents, textures, BSDFs): first hits only, so it is cheap beside the image, and
//! a scene without AOVs never runs it (the kernel is unchanged). Measured on the shared 2-core
//! machine: `tests/data/aov.xml` at 1024×768, 16 spp (12.6M camera rays, all ten AOV types) took
//! about 4 CPU-seconds here against 11.7 for its image (path, max_depth 4, CPU backend). It grows
//! with pixels × spp whatever the backend renders the image on: a GPU entry point is the way to
//! make it scale with the GPU.
use crate::prepare::buffers::SceneBuffers;
use crate::scene::aov::{AovKind, AovSpec};
use caustic_kernel::bsdf::{Bsdf, TransportMode};
use caustic_kernel::bvh::Accel;
use caustic_kernel::features;
use caustic_kernel::film::sample_position;
use caustic_kernel::glam::Vec3;
use caustic_kernel::integrator::shading_frame;
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use caustic_kernel::shape::{surface_point, tangents, Hit};
use caustic_kernel::spectrum::Rgb;
use rayon::prelude::*;

/// Means and variances of the means of `spec.computed_channels()`, one `Vec` per channel, over
/// samples `[0, spp)` of every pixel with `seed`.
pub fn render(buffers: &SceneBuffers, spec: &AovSpec, spp: u32, seed: u32) -> (Vec<Vec<f32>>, Vec<Vec<f64>>) {
    let channels = spec.computed_channels().len().max(1);
    let mut params = buffers.params;
    params.spp_total = spp;
    let (width, height) = (params.width as usize, params.height as usize);
    let stats: Vec<(Vec<f64>, Vec<f64>)> = (0..width * height)
        .into_par_iter()
        .map(|pixel| {
            let mut sum = vec![0.0f64; channels];
            let mut sum_sq = vec![0.0f64; channels];
            let mut values = vec![0.0f32; channels];
            for s in 0..spp {
                let weight = sample(buffers, spec, &params, pixel as u32, s, seed, &mut values);
                for c in 0..channels {
                    // A non-finite value (a degenerate triangle's normal) counts as 0, as the image
                    // counts a non-finite sample as black.
                    let v = values[c] * weight;
                    let v = if v.is_finite() { v as f64 } else { 0.0 };
                    sum[c] += v;
                    sum_sq[c] += v * v;
                }
            }
            (sum, sum_sq)
        })
        .collect();
    let n = spp.max(1) as f64;
    let mut means = vec![Vec::with_capacity(width * height); channels];
    let mut variances = vec![Vec::with_capacity(width * height); channels];
    for (sum, sum_sq) in &stats {
        for c in 0..channels {
            let mean = sum[c] / n;
            means[c].push(mean as f32);
            variances[c].push((sum_sq[c] - n * mean * mean).max(0.0) / (n * (n - 1.0).max(1.0)));
        }
    }
    (means, variances)
}

/// One camera sample's values (`values`, in `computed_channels` order) and its filter weight.
#[allow(clippy::too_many_arguments)]
fn sample(
    buffers: &SceneBuffers,
    spec: &AovSpec,
    params: &FrameParams,
    pixel: u32,
    sample_index: u32,
    seed: u32,
    values: &mut [f32],
) -> f32 {
    let scene = buffers.view();
    let (px, py) = (pixel % params.width, pixel / params.width);
    // As `integrator::camera_sample` draws the image's ray, by filter importance sampling: the AOVs
    // are accumulated per pixel (the same filtered values in expectation as the splatting film's).
    let mut sampler = Sampler::new(seed, pixel, sample_index);
    let fis = FrameParams { film_reach: 0, ..*params };
    let film = sample_position(&fis, scene.tables, px, py, sample_index, &mut sampler);
    let u_lens = sampler.next_2d();
    let ray = params.camera.generate_ray(film.pos, u_lens);
    let weight = if params.filter_signed != 0 { film.weight } else { 1.0 };
    let accel = Accel::of(&scene);
    values.fill(0.0);
    let found = accel.trace(&ray, false, NONE);
    let mut i = 0;
    if spec.nested.is_some() {
        values[0] = alpha(params, found.map(|h| &scene.prims[h.prim as usize]));
        i = 1;
    }
    let Some(hit) = found else { return weight };
    let prim = scene.prims[hit.prim as usize];
    let sp = surface_point(&prim, scene.attributes, &hit, &ray);
    for aov in &spec.aovs {
        let v: [f32; 3] = match aov.kind {
            // Mitsuba's camera rays start on the near clip plane, caustic's at the camera with that
            // plane as `t_min` (measured: Mitsuba's depth was caustic's t less 0.01, the default
            // near_clip, at the image's centre).
            AovKind::Depth => [hit.t - ray.t_min, 0.0, 0.0],
            AovKind::Position => sp.p.to_array(),
            AovKind::Uv => [sp.uv.x, sp.uv.y, 0.0],
            AovKind::GeoNormal => sp.ng.to_array(),
            AovKind::ShNormal => shading_normal(buffers, &prim, &hit, &sp, ray.dir).to_array(),
            AovKind::DpDu => tangents(&prim, scene.attributes, &hit, &sp).0.to_array(),
            AovKind::DpDv => tangents(&prim, scene.attributes, &hit, &sp).1.to_array(),
            AovKind::PrimIndex => [buffers.prim_origins[hit.prim as usize][1] as f32, 0.0, 0.0],
            AovKind::ShapeIndex => [buffers.prim_origins[hit.prim as usize][0] as f32, 0.0, 0.0],
            AovKind::Albedo => albedo(buffers, &prim, &hit, &sp, ray.dir).to_array(),
        };
        let n = aov.kind.suffixes().len();
        values[i..i + n].copy_from_slice(&v[..n]);
        i += n;
    }
    weight
}

/// The nested image's alpha for a camera ray that first meets `hit` (or nothing), as Mitsuba's
/// integrators mark a sample valid: `direct` where the ray meets a surface; `path` (and caustic's
/// other integrators) also where it leaves to a visible environment emitter, and at `max_depth` 1
/// only where it meets an emitter (0 at `max_depth` 0). (Mitsuba's `path` also skips surfaces whose
/// BSDF has a null lobe, such as `mask`; here every surface counts.)
fn alpha(params: &FrameParams, hit: Option<&Primitive>) -> f32 {
    let visible_env = params.env_light != NONE && params.hide_emitters == 0;
    let valid = match hit {
        _ if params.max_depth == 0 => false,
        Some(_) if params.integrator == INTEGRATOR_DIRECT => true,
        None => visible_env && params.integrator != INTEGRATOR_DIRECT,
        Some(p) if params.max_depth == 1 => p.light != NONE && params.hide_emitters == 0,
        Some(_) => true,
    };
    if valid {
        1.0
    } else {
        0.0
    }
}

/// The shading normal, on the shape's side (Mitsuba's `sh_frame.n`, which is not turned towards the
/// viewer). Under a normal or bump map, Mitsuba's map gives its tilted normal in world space (in the
/// unmirrored shading frame, `flip_invalid_normals` applied), but a `twosided` wrapping the map has
/// no `sh_frame` of its own and gives the untilted one (measured on `normalmap.xml`: the sphere,
/// the disk in `twosided(normalmap)` and the rectangle in `normalmap(twosided)` then agree).
fn shading_normal(
    buffers: &SceneBuffers,
    prim: &Primitive,
    hit: &Hit,
    sp: &caustic_kernel::shape::SurfacePoint,
    dir: Vec3,
) -> Vec3 {
    let material = &buffers.materials[prim.material as usize];
    let mapped = features::has(buffers.features, features::TANGENT_FRAMES) && material.perturb != 0;
    let twosided_outside =
        material.flags & MATERIAL_TWO_SIDED != 0 && material.perturb & PERTURB_TWO_SIDED_INSIDE == 0;
    if !mapped || twosided_outside {
        return sp.ns;
    }
    // Without a `twosided` outside the map, the frame `shading_frame` tilts is the unmirrored one.
    let shading = shading_frame(&buffers.view(), material, prim, hit, sp, dir);
    shading.frame().to_world(shading.tilt.n)
}

/// Mitsuba's `eval_diffuse_reflectance`: the textured diffuse reflectance of `diffuse`, `plastic`,
/// `roughplastic`, and the base colour of `principled` and `principledthin`; a blend's leaves
/// weighted as the blend weighs them; every other model Mitsuba's default, π·f(viewer, normal)
/// (the BSDF evaluated towards the shading normal: 0 for smooth conductors and dielectrics, which
/// are Dirac lobes). `twosided` is the material's flag: seen from behind, the back is the front, or the back's record
/// where it has two (`caustic_kernel::two_sided::seen`).
fn albedo(
    buffers: &SceneBuffers,
    prim: &Primitive,
    hit: &Hit,
    sp: &caustic_kernel::shape::SurfacePoint,
    dir: Vec3,
) -> Rgb {
    let scene = buffers.view();
    let material = &scene.materials[caustic_kernel::two_sided::seen(&scene, prim.material, sp, dir) as usize];
    let bsdf = Bsdf::new(
        material,
        scene.materials,
        scene.textures,
        scene.tables,
        sp.lookup(),
        scene.features,
        caustic_kernel::bsdf::perturb::Perturbation::NONE,
    );
    let mut plain = *material;
    plain.perturb = 0;
    let wo = shading_frame(&scene, &plain, prim, hit, sp, dir).wo;
    let mut albedo = Rgb::ZERO;
    for i in 0..bsdf.leaf_count() {
        let c = bsdf.leaf(i);
        let value = match c.material.kind {
            BSDF_DIFFUSE | BSDF_PLASTIC | BSDF_ROUGH_PLASTIC | BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN => {
                c.reflectance
            }
            _ => bsdf.only(i).eval(wo, Vec3::Z, TransportMode::Radiance) * std::f32::consts::PI,
        };
        albedo += value * bsdf.leaf_weight(i);
    }
    albedo
}
