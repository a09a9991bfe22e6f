//! The GPU's limits against a scene's needs, checked before any GPU buffer exists: wgpu panics (in
//! `create_buffer` or `create_bind_group`) on a buffer over `max_buffer_size` or a binding over
//! `max_storage_buffer_binding_size`, which a 2049×2048 film (its 32-byte accumulator per pixel) or a
//! 3M-triangle mesh reaches on lavapipe and with wgpu's default limits. The device is opened with the
//! adapter's own limits (the H100 binds 4 GiB, 32 times the default), so these are what this GPU allows.
use crate::prepare::buffers::SceneBuffers;
use anyhow::Result;
use caustic_kernel::layout::{PixelAccum, TILE};

/// Every storage buffer the GPU backend binds, by name, with its size in bytes.
pub fn buffer_sizes(buffers: &SceneBuffers) -> Vec<(&'static str, u64)> {
    fn bytes<T>(v: &[T]) -> u64 {
        std::mem::size_of_val(v) as u64
    }
    let pixels = buffers.params.width as u64 * buffers.params.height as u64;
    // (A placeholder word where nothing splats: a binding cannot be empty.)
    let splat = (pixels * caustic_kernel::film_splat::words_per_pixel(&buffers.params) as u64).max(1);
    vec![
        ("frame parameters", std::mem::size_of_val(&buffers.params) as u64),
        ("BVH nodes", bytes(&buffers.nodes)),
        ("primitives", bytes(&buffers.prims)),
        ("triangle attributes", bytes(&buffers.attributes)),
        ("materials", bytes(&buffers.materials)),
        ("lights", bytes(&buffers.lights)),
        ("tables (texels, sampling tables)", bytes(&buffers.tables)),
        ("textures", bytes(&buffers.textures)),
        ("film accumulator", pixels * std::mem::size_of::<PixelAccum>() as u64),
        ("splats", splat * 4),
        ("light vertex cache", cache_bytes(buffers)),
        ("merging grid", grid_bytes(buffers)),
    ]
}

/// BDPT's and VCM's light vertex cache (`caustic_kernel::integrator::bdpt::LightVertex`, eight slots a
/// pixel); a placeholder vertex for the other integrators.
pub fn cache_bytes(buffers: &SceneBuffers) -> u64 {
    use caustic_kernel::integrator::{bdpt::LightVertex, traces_cached, vcm_grid};
    let slots =
        if traces_cached(buffers.params.integrator) { vcm_grid::slots(&buffers.params) as u64 } else { 1 };
    slots * std::mem::size_of::<LightVertex>() as u64
}

/// VCM's hash grid (`caustic_kernel::integrator::vcm_grid`); a placeholder word for the others.
pub fn grid_bytes(buffers: &SceneBuffers) -> u64 {
    use caustic_kernel::integrator::{merges, vcm_grid::Grid};
    let words = if merges(buffers.params.integrator) { Grid::of(&buffers.params).words() as u64 } else { 1 };
    words * 4
}

/// A scene this GPU cannot hold (the automatic backend choice then renders on the CPU, saying why).
#[derive(Debug)]
pub struct OverLimit(pub String);

impl std::fmt::Display for OverLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for OverLimit {}

macro_rules! over {
    ($($t:tt)*) => {
        return Err(OverLimit(format!($($t)*)).into())
    };
}

/// Refuses a scene that this GPU cannot hold, naming the buffer, the limit, its value and the need.
pub fn check(buffers: &SceneBuffers, limits: &wgpu::Limits, adapter: &str) -> Result<()> {
    let advice = "render a smaller film or scene, or use --backend cpu";
    for (what, size) in buffer_sizes(buffers) {
        for (limit, value) in [
            ("max_storage_buffer_binding_size", limits.max_storage_buffer_binding_size),
            ("max_buffer_size", limits.max_buffer_size),
        ] {
            if size > value {
                over!(
                    "{adapter} cannot hold this scene's {what}: {size} bytes ({}) needed, its {limit} is \
                     {value} bytes ({}); {advice}",
                    mib(size),
                    mib(value)
                );
            }
        }
    }
    let (width, height) = (buffers.params.width, buffers.params.height);
    let groups = width.div_ceil(TILE).max(height.div_ceil(TILE));
    if groups > limits.max_compute_workgroups_per_dimension {
        over!(
            "a {width}×{height} film needs {groups} workgroups of {TILE}×{TILE} pixels along a side, over \
             {adapter}'s max_compute_workgroups_per_dimension of {}; {advice}",
            limits.max_compute_workgroups_per_dimension
        );
    }
    Ok(())
}

fn mib(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64)
}
