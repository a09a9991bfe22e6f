//! GPU compute entry points (SPIR-V only). They do nothing but fetch the buffers and call the same
//! functions the CPU runner calls. Binding numbers and the workgroup size are the literals rust-gpu's
//! attributes need; their names live in `layout` (`binding::*`, `TILE`), which the host uses.
use crate::film_splat::{gather, resolved as film_resolved, resolved_splats, WordCells};
use crate::integrator::bdpt::{CacheSlots, LightVertex, MAX_LIGHT_VERTICES};
use crate::integrator::{
    accumulated, render_pixel, splat_cached_camera_path, splat_camera_paths, splats_camera_paths,
    trace_cached_light_path, trace_light_paths, vcm_grid, SceneView,
};
use crate::layout::{
    splats, square_scale, BvhNode, FrameParams, Light, Material, PixelAccum, Primitive, Texture,
    TriangleAttributes,
};
use crate::splat::GpuWords;
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

/// BDPT's and VCM's light paths (`integrator::bdpt`): one invocation per pixel, its light path's
/// camera connections splatted, its vertices into its slots of the light vertex cache.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
#[allow(clippy::too_many_arguments)]
pub fn cache_light(
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
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] cache: &mut [LightVertex], // CACHE
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
    let mut slots = CacheSlots { cache, base: pixel * MAX_LIGHT_VERTICES };
    trace_cached_light_path(&scene, params, pixel, &mut slots, &mut GpuWords(splat));
}

/// VCM's grid (`integrator::vcm_grid`): each pixel's light path's vertices linked into their
/// buckets' lists.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
pub fn grid_link(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams, // PARAMS
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] cache: &[LightVertex], // CACHE
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] grid: &mut [u32],    // GRID
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let g = vcm_grid::Grid::of(params);
    let first = (id.y * params.width + id.x) * MAX_LIGHT_VERTICES;
    let mut words = GpuWords(grid);
    let mut k = 0;
    while k < MAX_LIGHT_VERTICES {
        vcm_grid::link(cache, &g, first + k, &mut words);
        k += 1;
    }
}

/// BDPT's and VCM's camera paths: one invocation per pixel, connected to its light path's vertices in
/// the cache and (VCM) merged through the grid, splatted into the pixel's sums.
#[spirv(compute(threads(8, 8, 1)))] // layout::TILE
#[allow(clippy::too_many_arguments)]
pub fn cache_camera(
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
    #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] cache: &[LightVertex], // CACHE
    #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] grid: &[u32],        // GRID
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
    splat_cached_camera_path(&scene, params, pixel, cache, grid, &mut GpuWords(splat));
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
    // (The splatting integrators' camera samples, splatted film or not, go to the splat words.)
    if params.film_reach != 0 && !splats(params.integrator) {
        let pixel = (id.y * params.width + id.x) as usize;
        let cells = WordCells(splat);
        let gathered = gather(&cells, params, id.x, id.y);
        accum[pixel] = film_resolved(accum[pixel], &gathered, square_scale(params));
        return;
    }
    let pixel = (id.y * params.width + id.x) as usize;
    let q = square_scale(params);
    accum[pixel] = resolved_splats(accum[pixel], &mut GpuWords(splat), params, id.x, id.y, q);
}
