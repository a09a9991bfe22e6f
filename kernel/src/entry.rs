//! GPU compute entry points (SPIR-V only). They do nothing but fetch the buffers and call the same
//! functions the CPU runner calls.
use crate::integrator::{accumulate, render_pixel, SceneView};
use crate::layout::{BvhNode, FrameParams, Light, Material, Primitive, Texture, TriangleAttributes};
use spirv_std::glam::UVec3;
use spirv_std::spirv;

/// Workgroup edge: 8×8 pixels, so neighbouring rays (coherent traversal) run together.
pub const TILE: u32 = 8;

/// One invocation per pixel; it adds `params.sample_count` samples to the pixel's accumulator.
#[spirv(compute(threads(8, 8, 1)))]
pub fn render(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &FrameParams,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] nodes: &[BvhNode],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] prims: &[Primitive],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] attributes: &[TriangleAttributes],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] materials: &[Material],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] lights: &[Light],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 6)] tables: &[f32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 7)] accum: &mut [f32],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] textures: &[Texture],
    // The scene's `features` mask, fixed when the pipeline is created (default: everything).
    #[spirv(spec_constant(id = 0, default = 4294967295))] features: u32,
) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let scene = SceneView { nodes, prims, attributes, materials, lights, textures, tables, features };
    let pixel = id.y * params.width + id.x;
    let sums = render_pixel(&scene, params, pixel);
    accumulate(accum, pixel, &sums, params.sample_count);
}
