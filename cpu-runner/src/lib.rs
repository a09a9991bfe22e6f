//! The CPU backend: the kernel's per-pixel function, called natively on every core.
use caustic_kernel::integrator::{accumulated, render_pixel, SceneView};
use caustic_kernel::layout::{FrameParams, PixelAccum};
use rayon::prelude::*;

/// Adds `params.sample_count` samples to every pixel of `accum` (one `PixelAccum` per pixel), exactly
/// as one GPU dispatch does.
pub fn render_pass(scene: &SceneView, params: &FrameParams, accum: &mut [PixelAccum]) {
    let pixels = (params.width * params.height) as usize;
    assert_eq!(accum.len(), pixels, "accumulation buffer does not match the image size");
    // Rows as work items: large enough to amortise scheduling, small enough to balance load.
    accum.par_chunks_mut(params.width as usize).enumerate().for_each(|(y, row)| {
        for (x, slot) in row.iter_mut().enumerate() {
            let pixel = y as u32 * params.width + x as u32;
            *slot = accumulated(*slot, &render_pixel(scene, params, pixel), params.sample_count);
        }
    });
}
