//! Mitsuba's `irradiancemeter` on the host: which primitives carry the meter and the table the
//! kernel samples them from (`caustic_kernel::irradiance_meter`: their count, the CDF of their areas,
//! their indices in the primitive buffer).
use super::lights::cdf_of;
use crate::scene::{Geometry, Projection, Scene};
use anyhow::{bail, Result};
use caustic_kernel::layout::Primitive;
use std::f64::consts::PI;

/// The meter's primitives, by their index in scene order (as `primitives::primitives` pushes them), with
/// their areas; `None` when the sensor is not an irradiance meter.
pub(crate) fn scene_order_primitives(scene: &Scene) -> Option<Vec<(u32, f64)>> {
    let Projection::IrradianceMeter { shape } = scene.sensor.projection else { return None };
    let first: usize = scene.shapes[..shape].iter().map(|s| primitive_count(&s.geometry)).sum();
    let areas: Vec<f64> = match &scene.shapes[shape].geometry {
        Geometry::Triangles { triangles, .. } => {
            triangles.iter().map(|t| crate::scene::mesh::triangle_area(*t)).collect()
        }
        Geometry::Sphere { radius, .. } => vec![4.0 * PI * (*radius as f64).powi(2)],
        Geometry::Disk { u, v, .. } => vec![PI * u.as_dvec3().cross(v.as_dvec3()).length()],
    };
    Some(areas.into_iter().zip(first as u32..).map(|(a, i)| (i, a)).collect())
}

fn primitive_count(geometry: &Geometry) -> usize {
    match geometry {
        Geometry::Triangles { triangles, .. } => triangles.len(),
        Geometry::Sphere { .. } | Geometry::Disk { .. } => 1,
    }
}

/// Appends the meter's table to `tables` and returns where it starts: the count, the inclusive CDF
/// of the areas, the primitives' indices after the BVH's reordering (`new_index`, by scene-order
/// index); counts and indices as the bits of `u32`s.
pub(crate) fn place_table(
    meter: &[(u32, f64)],
    new_index: &[u32],
    prims: &[Primitive],
    tables: &mut Vec<f32>,
) -> Result<u32> {
    let total: f64 = meter.iter().map(|&(_, a)| a).sum();
    if !(total > 0.0 && total.is_finite()) {
        bail!("the irradiancemeter's shape has no area to measure over (total {total})");
    }
    let start = tables.len() as u32;
    tables.push(f32::from_bits(meter.len() as u32));
    tables.extend(cdf_of(&meter.iter().map(|&(_, a)| a).collect::<Vec<_>>()));
    for &(i, _) in meter {
        let index = new_index[i as usize];
        debug_assert!((index as usize) < prims.len());
        tables.push(f32::from_bits(index));
    }
    Ok(start)
}
