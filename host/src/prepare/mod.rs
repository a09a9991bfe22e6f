//! A `scene::Scene` into the kernel's buffers (`buffers::SceneBuffers`): primitives in BVH order,
//! the BVH (two-level with instances), per-triangle attributes, materials, textures, lights, the
//! film's filter tables, the irradiance meter's table, and the wide BVH the CPU walks.
//!
//! Uses `scene` and `load` (the CIE tables of `load::mitsuba::spectrum`).
mod attribute_buffers;
pub mod buffers;
mod bvh;
pub mod camera;
pub mod features;
pub mod filter_table;
pub mod instance_buffers;
pub mod irradiance_meter;
mod lights;
mod materials;
mod primitives;
pub mod wide_bvh;
