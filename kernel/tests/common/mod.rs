//! Helpers shared by the kernel's test files (kernel/tests: the kernel's math on the CPU, see its
//! README.md); each file declares `mod common;` and uses what it needs (so the rest is dead code there,
//! hence the `allow`).
//!
//! - `chi2`: χ² goodness-of-fit of a sampler against its density, and quadrature over the sphere;
//! - `models`: test materials and `Model` (a BSDF in a transport mode, built as the host builds it);
//! - `bsdf_checks`: checks more than one file runs on BSDFs (reciprocity, albedo, χ² of a model);
//! - `mitsuba`: Mitsuba 3.9.1's BSDF values (`data/`) and the materials that produced them.
#![allow(dead_code)]
pub mod bsdf_checks;
pub mod chi2;
pub mod mitsuba;
pub mod models;

// The χ² helpers by their bare names, as `sampling.rs` has always used them.
#[allow(unused_imports)]
pub use chi2::*;
