//! The CPU backend: the kernel's per-pixel function, called natively on every core.
use caustic_kernel::integrator::{
    accumulated, render_pixel, splat_camera_paths, splats_camera_paths, trace_light_paths, SceneView,
};
use caustic_kernel::layout::{FrameParams, PixelAccum};
use caustic_kernel::splat::{AtomicWords, SPLAT_STRIDE};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// Adds `params.sample_count` samples to every pixel of `accum` (one `PixelAccum` per pixel), exactly
/// as one GPU dispatch does; the path tracer by its regenerating loop or its plain one (the same
/// image either way: `render_pixel`).
pub fn render_pass(scene: &SceneView, params: &FrameParams, accum: &mut [PixelAccum], regenerate: bool) {
    let pixels = (params.width * params.height) as usize;
    assert_eq!(accum.len(), pixels, "accumulation buffer does not match the image size");
    // Bands of TILE rows as work items, each walked in TILE × TILE tiles: neighbouring pixels' rays
    // one after the other, as the GPU's workgroups run them.
    let (width, tile) = (params.width as usize, caustic_kernel::layout::TILE as usize);
    accum.par_chunks_mut(width * tile).enumerate().for_each(|(band, rows)| {
        let height = rows.len() / width;
        for x0 in (0..width).step_by(tile) {
            for dy in 0..height {
                for x in x0..(x0 + tile).min(width) {
                    let slot = &mut rows[dy * width + x];
                    let pixel = ((band * tile + dy) * width + x) as u32;
                    *slot = accumulated(
                        *slot,
                        &render_pixel(scene, params, pixel, regenerate),
                        params.sample_count,
                    );
                }
            }
        }
    });
}

/// The CPU's splat words: `u32` atomics shared by every thread.
struct CpuWords<'a>(&'a [AtomicU32]);

impl AtomicWords for CpuWords<'_> {
    #[inline]
    fn fetch_add(&mut self, index: u32, value: u32) -> u32 {
        // Relaxed: the sums are read only after the pass has joined every thread.
        self.0[index as usize].fetch_add(value, Ordering::Relaxed)
    }
}

/// Traces `params.sample_count` light paths per pixel (IBPT: and camera paths), exactly as the GPU's
/// dispatches do, and returns the splat words (`caustic_kernel::splat` layout) for the host to resolve.
pub fn light_pass(scene: &SceneView, params: &FrameParams) -> Vec<u32> {
    let pixels = params.width * params.height;
    let words: Vec<AtomicU32> = (0..pixels * SPLAT_STRIDE).map(|_| AtomicU32::new(0)).collect();
    let camera_half = splats_camera_paths(scene, params);
    (0..pixels).into_par_iter().for_each(|pixel| {
        let mut words = CpuWords(&words);
        if camera_half {
            splat_camera_paths(scene, params, pixel, &mut words);
        }
        trace_light_paths(scene, params, pixel, &mut words);
    });
    words.into_iter().map(AtomicU32::into_inner).collect()
}
