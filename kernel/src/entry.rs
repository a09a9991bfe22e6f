//! GPU compute entry points (SPIR-V only). They do nothing but fetch the buffers and call the same
//! functions the CPU runner calls. Binding numbers and the workgroup size are the literals rust-gpu's
//! attributes need; their names live in `layout` (`binding::*`, `TILE`), which the host uses.
use crate::film_splat::{gather, resolved as film_resolved, WordCells};
use crate::integrator::{
    accumulated, render_pixel, splat_bdpt_samples, splat_camera_paths, splats_camera_paths,
    trace_light_paths, SceneView,
};
use crate::layout::{
    square_scale, BvhNode, FrameParams, Light, Material, PixelAccum, Primitive, Texture, TriangleAttributes,
};
use crate::splat::{resolved, GpuWords, SPLAT_STRIDE};
use spirv_std::glam::UVec3;
use spirv_std::spirv;

/// Camera paths: one invocation per pixel; it adds `params.sample_count` samples to the pixel's
/// accumulator (IBPT: splats them into the pixel's sums).
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
#[allow(clippy::too_many_arguments)]
pub fn render(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams, // PARAMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],    // NODES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] prims: &[Primitive],  // PRIMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] attributes: &[TriangleAttributes], // ATTRIBUTES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] materials: &[Material], // MATERIALS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] lights: &[Light],     // LIGHTS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] tables: &[f32],       // TABLES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] accum: &mut [PixelAccum], // ACCUM
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] textures: &[Texture], // TEXTURES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] splat: &mut [u32],    // SPLAT
    // The scene's `features` mask, fixed when the pipeline is created (default: everything);
    // layout::SPEC_FEATURES.
    #[spirv(spec_constant(id = 0, default = 4294967295))] features: u32,
    // The path tracer's loop (layout::SPEC_REGENERATE; default: regenerating).
    #[spirv(spec_constant(id = 1, default = 1))] regenerate: u32,
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let scene = SceneView {
        nodes,
        prims,
        attributes,
        materials,
        lights,
        textures,
        tables,
        features,
        wide_bvh: false,
    };
    let pixel = id.y * params.width + id.x;
    if splats_camera_paths(&scene, params) {
        splat_camera_paths(&scene, params, pixel, &mut GpuWords(splat));
        return;
    }
    // The splatting film's cells (untouched under filter importance sampling): `resolve` gathers
    // them into the accumulator.
    let mut cells = WordCells(splat);
    let sums = render_pixel(&scene, params, pixel, regenerate != 0, &mut cells);
    if params.film_reach == 0 {
        accum[pixel as usize] = accumulated(accum[pixel as usize], &sums, params.sample_count);
    }
}

/// Light paths (`ptracer`, IBPT's light half): one invocation per path index, laid out like the pixels
/// (so dispatch sizes stay within limits as `render`'s do), each splatting wherever its paths reach. A
/// separate entry point from `render`, so that neither carries the other's registers.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
#[allow(clippy::too_many_arguments)]
pub fn light(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams, // PARAMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],    // NODES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] prims: &[Primitive],  // PRIMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] attributes: &[TriangleAttributes], // ATTRIBUTES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] materials: &[Material], // MATERIALS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] lights: &[Light],     // LIGHTS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] tables: &[f32],       // TABLES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] textures: &[Texture], // TEXTURES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] splat: &mut [u32],    // SPLAT
    #[spirv(spec_constant(id = 0, default = 4294967295))] features: u32,
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let scene = SceneView {
        nodes,
        prims,
        attributes,
        materials,
        lights,
        textures,
        tables,
        features,
        wide_bvh: false,
    };
    let pixel = id.y * params.width + id.x;
    trace_light_paths(&scene, params, pixel, &mut GpuWords(splat));
}

/// Bidirectional path tracing (`integrator::bdpt`): one invocation per pixel, each sample's light path
/// and camera path, splatting wherever they reach. Its own entry point, so that `render` does not
/// carry it.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
#[allow(clippy::too_many_arguments)]
pub fn bdpt(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams, // PARAMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],    // NODES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] prims: &[Primitive],  // PRIMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] attributes: &[TriangleAttributes], // ATTRIBUTES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] materials: &[Material], // MATERIALS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] lights: &[Light],     // LIGHTS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] tables: &[f32],       // TABLES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] textures: &[Texture], // TEXTURES
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] splat: &mut [u32],    // SPLAT
    #[spirv(spec_constant(id = 0, default = 4294967295))] features: u32,
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let scene = SceneView {
        nodes,
        prims,
        attributes,
        materials,
        lights,
        textures,
        tables,
        features,
        wide_bvh: false,
    };
    let pixel = id.y * params.width + id.x;
    splat_bdpt_samples(&scene, params, pixel, &mut GpuWords(splat));
}

/// After a splatting pass: folds each pixel's splat words into its accumulator and clears them, so
/// that no pass needs its words read back; for the splatting film, gathers each pixel's sums from
/// the cells of its neighbourhood (`film_splat`) into its accumulator.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
pub fn resolve(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams, // PARAMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] accum: &mut [PixelAccum], // ACCUM
    #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] splat: &mut [u32],    // SPLAT
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    if params.film_reach != 0 {
        let pixel = (id.y * params.width + id.x) as usize;
        let cells = WordCells(splat);
        let gathered = gather(&cells, params, id.x, id.y);
        accum[pixel] = film_resolved(accum[pixel], &gathered, square_scale(params));
        return;
    }
    let pixel = (id.y * params.width + id.x) as usize;
    let base = pixel * SPLAT_STRIDE as usize;
    let mut words = [0u32; SPLAT_STRIDE as usize];
    let mut i = 0;
    while i < SPLAT_STRIDE as usize {
        words[i] = splat[base + i];
        splat[base + i] = 0;
        i += 1;
    }
    accum[pixel] = resolved(accum[pixel], words, params.sample_count, square_scale(params));
}
