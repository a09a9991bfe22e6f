//! Host memory a render will allocate, for `system::memory::check` to hold against what the
//! machine has before anything is allocated.
use crate::prepare::buffers::SceneBuffers;
use caustic_kernel::layout::PixelAccum;

/// Host bytes a render of `buffers` needs at its peak: the scene, and per pixel the device's f32
/// sums (the CPU's own, or the GPU's read-back staging and the copy collected from it), three f64
/// totals (the backend's, the copy read back and one summing several devices), the finished image's
/// means and variances, and a pass's splat words for light tracing.
pub fn render_need(buffers: &SceneBuffers) -> u64 {
    let pixels = buffers.params.width as u64 * buffers.params.height as u64;
    let accum = std::mem::size_of::<PixelAccum>() as u64;
    let total = std::mem::size_of::<super::accumulation::PixelTotal>() as u64;
    let image = 3 * 4 + 3 * 8;
    let splat = caustic_kernel::film_splat::words_per_pixel(&buffers.params) as u64 * 4;
    scene_bytes(buffers) + pixels * (2 * accum + 3 * total + image + splat)
}

/// Bytes of the scene's own buffers (geometry, BVH, materials, lights, tables), without the film's.
pub fn scene_bytes(buffers: &SceneBuffers) -> u64 {
    super::limits::buffer_sizes(buffers)
        .into_iter()
        .filter(|(what, _)| !matches!(*what, "film accumulator" | "splats"))
        .map(|(_, size)| size)
        .sum()
}
