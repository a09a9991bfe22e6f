//! The CPU backend: the kernel's per-pixel function, called natively on every core.
use caustic_kernel::integrator::{accumulate, render_pixel, SceneView, ACCUM_STRIDE};
use caustic_kernel::layout::FrameParams;
use rayon::prelude::*;

/// Adds `params.sample_count` samples to every pixel of `accum` (`ACCUM_STRIDE` floats per pixel),
/// exactly as one GPU dispatch does.
pub fn render_pass(scene: &SceneView, params: &FrameParams, accum: &mut [f32]) {
    let pixels = (params.width * params.height) as usize;
    assert_eq!(accum.len(), pixels * ACCUM_STRIDE, "accumulation buffer does not match the image size");
    // Rows as work items: large enough to amortise scheduling, small enough to balance load.
    let row = params.width as usize * ACCUM_STRIDE;
    accum.par_chunks_mut(row).enumerate().for_each(|(y, row_accum)| {
        for x in 0..params.width {
            let pixel = y as u32 * params.width + x;
            let sums = render_pixel(scene, params, pixel);
            // The row slice starts at this row's first pixel.
            accumulate(row_accum, x, &sums, params.sample_count);
        }
    });
}
