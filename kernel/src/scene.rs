//! Plain data shared between the host and the kernel: `#[repr(C)]` structs of 32-bit scalars with
//! explicit padding, uploaded as storage buffers by the GPU backend and borrowed as slices by the CPU
//! runner. Polymorphic records are tagged structs (a `kind` word), since rust-gpu lays out data-carrying
//! enums in buffers differently from Rust.

/// Marks "none" in index fields.
pub const NONE: u32 = u32::MAX;

/// One BVH2 node (32 bytes). Inner nodes (`prim_count == 0`) have children at `first` and `first + 1`;
/// leaves cover primitives `first .. first + prim_count` (primitives are stored in BVH order).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct BvhNode {
    pub min: [f32; 3],
    pub prim_count: u32,
    pub max: [f32; 3],
    pub first: u32,
}

pub const PRIM_TRIANGLE: u32 = 0;
pub const PRIM_SPHERE: u32 = 1;

/// Primitive flag: interpolate the per-vertex normals in `ShadingNormals`.
pub const PRIM_FLAG_SMOOTH: u32 = 1;
/// Primitive flag: the shape's normals are flipped (`flip_normals`).
pub const PRIM_FLAG_FLIP: u32 = 2;

/// A triangle (`p0, p1, p2`) or an analytic sphere (centre `p0`, radius `p1[0]`), 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Primitive {
    pub p0: [f32; 3],
    pub kind: u32,
    pub p1: [f32; 3],
    pub material: u32,
    pub p2: [f32; 3],
    /// Index into the light list when the primitive emits, else `NONE`.
    pub light: u32,
    pub flags: u32,
    pub _pad: [u32; 3],
}

/// Per-vertex shading normals of a smooth triangle, indexed like `Primitive`.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct ShadingNormals {
    pub n0: [f32; 3],
    pub _p0: f32,
    pub n1: [f32; 3],
    pub _p1: f32,
    pub n2: [f32; 3],
    pub _p2: f32,
}

pub const BSDF_DIFFUSE: u32 = 0;
pub const BSDF_PHONG: u32 = 1;

/// A BSDF record. `diffuse` is the diffuse reflectance (Lambert) or `kd` (Phong); `specular` is `ks`.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Material {
    pub kind: u32,
    pub exponent: f32,
    /// 1 when both sides of the surface scatter (Mitsuba's `twosided`), else 0.
    pub two_sided: u32,
    pub _pad: u32,
    pub diffuse: [f32; 4],
    pub specular: [f32; 4],
}

pub const LIGHT_TRIANGLE: u32 = 0;
pub const LIGHT_SPHERE: u32 = 1;

/// An emitter: an emissive primitive (`prim`) with uniform radiance, chosen for next-event estimation
/// with probability `pmf` (proportional to its power).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Light {
    pub kind: u32,
    pub prim: u32,
    pub pmf: f32,
    pub _pad: u32,
    pub radiance: [f32; 4],
}

pub const SAMPLER_INDEPENDENT: u32 = 0;
pub const SAMPLER_STRATIFIED: u32 = 1;

/// Per-dispatch parameters (a uniform buffer: only 4-byte scalars and 16-byte groups).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct FrameParams {
    pub width: u32,
    pub height: u32,
    /// Index of the first sample this dispatch adds to each pixel.
    pub sample_base: u32,
    /// Samples per pixel this dispatch adds.
    pub sample_count: u32,

    pub seed: u32,
    /// Mitsuba's `max_depth`: longest path in segments, `u32::MAX` for unbounded (-1).
    pub max_depth: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    pub sampler: u32,

    /// Total samples per pixel of the whole render (the stratified sampler's strata come from it).
    pub spp_total: u32,
    pub light_count: u32,
    /// Where the light-selection CDF starts in the table buffer.
    pub light_cdf_offset: u32,
    /// Where the reconstruction filter's CDF starts in the table buffer, and its bin count.
    pub filter_cdf_offset: u32,

    pub filter_bins: u32,
    pub filter_radius: f32,
    pub hide_emitters: u32,
    pub _pad0: u32,

    pub camera: crate::camera::Camera,
}
