//! χ² tests of the irradiance meter's rays (`caustic_kernel::irradiance_meter`): over triangles of
//! different areas and normals, how often each is chosen (by area; a negative control chooses
//! uniformly) and the directions about each normal (cosine-weighted); on a sphere, the starting
//! points (uniform by area, just off the surface on the normal's side) and the directions.
mod common;
use caustic_kernel::frame::Frame;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::irradiance_meter::generate_ray;
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use caustic_kernel::sampling::cosine_hemisphere_pdf;
use common::*;
use std::f64::consts::PI;

/// A scene view over `prims` whose meter lists `meter` (indices into `prims`) with `cdf`.
fn with_meter<R>(prims: &[Primitive], meter: &[u32], cdf: &[f32], f: impl FnOnce(&SceneView) -> R) -> R {
    let mut tables = vec![f32::from_bits(meter.len() as u32)];
    tables.extend_from_slice(cdf);
    tables.extend(meter.iter().map(|&i| f32::from_bits(i)));
    let scene = SceneView {
        nodes: &[],
        prims,
        attributes: &[],
        materials: &[],
        lights: &[],
        textures: &[],
        tables: &tables,
        features: 0,
        wide_bvh: false,
    };
    f(&scene)
}

fn triangle(p0: Vec3, p1: Vec3, p2: Vec3, flags: u32) -> Primitive {
    Primitive {
        p0: p0.to_array(),
        kind: PRIM_TRIANGLE,
        p1: p1.to_array(),
        p2: p2.to_array(),
        light: NONE,
        flags,
        offset_floor: 1.0,
        ..Default::default()
    }
}

/// Four triangles far apart (so that a ray's origin tells which it left): area 1.5 facing −x near
/// x = 5, area 0.5 facing +z near the origin, area 1 facing −y (its normal flipped) near y = −5, and
/// one the meter leaves out (area 12.5, facing −z).
fn mesh() -> Vec<Primitive> {
    let (a, b) = (Vec3::new(5.0, 0.0, 0.0), Vec3::new(0.0, -5.0, 0.0));
    vec![
        triangle(a + Vec3::new(0.0, 1.5, 0.0), a, a + Vec3::new(0.0, 0.0, 2.0), 0),
        triangle(Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), 0),
        triangle(b + Vec3::new(1.0, 0.0, 0.0), b, b + Vec3::new(0.0, 0.0, 2.0), PRIM_FLAG_FLIP),
        triangle(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.0, 5.0, 3.0), Vec3::new(5.0, 0.0, 3.0), 0),
    ]
}

/// Which of the meter's triangles (0, 1, 2: primitives 1, 0, 2 of `mesh()`) a ray left, and its
/// normal.
fn source(origin: Vec3) -> (usize, Vec3) {
    if origin.x > 4.0 {
        (1, Vec3::NEG_X)
    } else if origin.y < -4.0 {
        (2, Vec3::NEG_Y)
    } else {
        (0, Vec3::Z)
    }
}

/// A meter whose CDF is `cdf` over primitives 1, 0, 2 of `mesh()` (areas 0.5, 1.5, 1): the χ² p-value
/// of how often it left each triangle, against their shares of the area; its directions, in the
/// frame of the normal of the triangle each left, against the cosine-weighted density.
fn mesh_meter(name: &str, cdf: &[f32]) -> f64 {
    let prims = mesh();
    with_meter(&prims, &[1, 0, 2], cdf, |scene| {
        let mut counts = [0.0f64; 3];
        let mut extra = Sampler::new(7, 1, 0);
        chi2_directions(
            &format!("{name}: directions"),
            |ul, u| {
                let ray = generate_ray(scene, 0, Vec2::new(ul, extra.next_1d()), u);
                let (i, n) = source(ray.origin);
                counts[i] += 1.0;
                Some(Frame::from_normal(n).to_local(ray.dir))
            },
            |d| cosine_hemisphere_pdf(d.z).max(0.0) as f64,
        );
        let total: f64 = counts.iter().sum();
        let expected = [0.5 / 3.0, 1.5 / 3.0, 1.0 / 3.0].map(|share| share * total);
        let p = chi2_p_value(&counts, &expected);
        println!("{name}: triangles left {counts:?} for {expected:.0?}, χ² p-value {p:.4}");
        p
    })
}

#[test]
fn meter_rays_follow_area_and_cosine() {
    let p = mesh_meter("meter over three triangles", &[0.5 / 3.0, 2.0 / 3.0, 1.0]);
    assert!(p > ALPHA, "the triangles are not chosen by area (p = {p:.2e})");
}

/// Negative control: had the meter chosen its triangles uniformly rather than by area, the χ² test
/// of the counts rejects it.
#[test]
fn meter_test_catches_a_uniform_choice() {
    let p = mesh_meter("uniform choice", &[1.0 / 3.0, 2.0 / 3.0, 1.0]);
    assert!(p < ALPHA, "choosing triangles uniformly went unnoticed (p = {p:.2e})");
}

/// On a sphere (centre c, radius r): starting points uniform over it, each ray leaving on the normal's
/// side by the ray offset, with cosine-weighted directions about the normal (and about the inward
/// normal when the sphere's normals are flipped).
#[test]
fn meter_on_a_sphere() {
    let (c, r) = (Vec3::new(0.3, -2.0, 1.0), 0.7f32);
    for flags in [0, PRIM_FLAG_FLIP] {
        let prims = [Primitive {
            p0: c.to_array(),
            kind: PRIM_SPHERE,
            p1: [r, 0.0, 0.0],
            light: NONE,
            flags,
            offset_floor: 1.0,
            ..Default::default()
        }];
        let side = if flags != 0 { -1.0 } else { 1.0 };
        with_meter(&prims, &[0], &[1.0], |scene| {
            let mut extra = Sampler::new(9, 2, 0);
            chi2_directions(
                &format!("meter points on a sphere (flags {flags})"),
                |ul, u| {
                    let ray = generate_ray(scene, 0, u, Vec2::new(ul, extra.next_1d()));
                    let out = (ray.origin - c).length() - r;
                    assert!(
                        out * side > 0.0 && out.abs() < 1e-3,
                        "origin {:?} off the sphere by {out}",
                        ray.origin
                    );
                    Some((ray.origin - c).normalize())
                },
                |_| 1.0 / (4.0 * PI),
            );
            chi2_directions(
                &format!("meter directions on a sphere (flags {flags})"),
                |ul, u| {
                    let ray = generate_ray(scene, 0, Vec2::new(ul, extra.next_1d()), u);
                    let n = (ray.origin - c).normalize() * side;
                    Some(Frame::from_normal(n).to_local(ray.dir))
                },
                |d| cosine_hemisphere_pdf(d.z).max(0.0) as f64,
            );
        });
    }
}
