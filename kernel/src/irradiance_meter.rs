//! Mitsuba's `irradiancemeter` sensor: rays leave points drawn uniformly by area on the shape the
//! meter is attached to, along cosine-weighted directions about its normal, each carrying the weight
//! π (`WEIGHT`). The expectation is `(1/A)·∫ ∫ L cos θ dω dA`: the irradiance averaged over the
//! shape, what Mitsuba 3.9.1 writes to the meter's one-pixel film.
//!
//! The shape's primitives are listed in `tables` from `Camera::meter_table`: their count (the bits of
//! a `u32`), the inclusive CDF of their areas, then their indices (bits of `u32`s).
use crate::camera::Ray;
use crate::frame::Frame;
use crate::glam::Vec2;
use crate::layout::SceneView;
use crate::light::area::sample_position;
use crate::sampling::{sample_cdf, square_to_cosine_hemisphere};
use crate::shape::{offset_scale, RAY_EPSILON};

/// What every meter ray carries: the cosine-weighted density `cos θ/π` leaves π of `L cos θ / pdf`
/// (the density of the point, 1/A, is not divided out: the mean over the area is measured).
pub const WEIGHT: f32 = core::f32::consts::PI;

/// The ray of the meter whose primitives start at `table`: `u_pos` chooses the primitive (by area)
/// and the point on it, `u_dir` the direction.
pub fn generate_ray(scene: &SceneView, table: u32, u_pos: Vec2, u_dir: Vec2) -> Ray {
    let count = scene.tables[table as usize].to_bits();
    let chosen = sample_cdf(scene.tables, table + 1, count, u_pos.x);
    let prim_index = scene.tables[(table + 1 + count + chosen.index) as usize].to_bits();
    let prim = scene.prims[prim_index as usize];
    let ps = sample_position(&prim, Vec2::new(chosen.remapped, u_pos.y));
    let dir = Frame::from_normal(ps.n).to_world(square_to_cosine_hemisphere(u_dir));
    // Off the surface along the normal, as rays leaving a surface start (`shape::offset_origin`).
    let origin = ps.p + ps.n * (offset_scale(ps.p, ps.error_scale, prim.offset_floor) * RAY_EPSILON);
    Ray { origin, dir, t_min: 0.0, t_max: f32::MAX }
}
