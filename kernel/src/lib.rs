//! caustic's rendering kernel.
//!
//! Everything that decides what a pixel looks like lives here, once: random numbers, sampling, camera,
//! BVH traversal and intersection, BSDFs, lights and the integrators. rust-gpu compiles this crate to
//! SPIR-V for the wgpu backend (`entry`), and the CPU runner links the very same functions natively.
//!
//! The dialect is the subset rust-gpu 0.11 accepts: no recursion, no trait objects, no slice iterator
//! adaptors, no `.get()`, no sub-slices, no 64-bit types. Buffer data are `#[repr(C)]` plain structs
//! (`layout`) shared with the host.
#![cfg_attr(target_arch = "spirv", no_std)]
// `!(x > 0.0)` is how the kernel rejects NaN along with non-positive values, on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bsdf;
pub mod bvh;
pub mod camera;
pub mod features;
pub mod film;
pub mod film_splat;
pub mod frame;
pub mod instancing;
pub mod integrator;
pub mod irradiance_meter;
pub mod layout;
pub mod light;
pub mod mask;
pub mod math;
pub mod rng;
pub mod sampling;
pub mod shape;
pub mod spectrum;
pub mod splat;
pub mod texture;
pub mod traverse;
pub mod two_sided;
pub mod wavelength;
pub mod wide_bvh;

#[cfg(target_arch = "spirv")]
pub mod entry;

pub use spirv_std::glam;
