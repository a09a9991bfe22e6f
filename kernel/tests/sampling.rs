//! χ² tests of every sampling routine against its density.
//!
//! kernel/tests holds the kernel's math, run on the CPU without a scene or the host: sampling
//! routines, BSDFs, lights (README.md there maps the files). Loading and the command line are tested in
//! host/tests, rendered images in tests/tests.
mod common;
use caustic_kernel::bsdf::phong::Phong;
use caustic_kernel::bsdf::Bxdf;
use caustic_kernel::frame::Frame;
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::*;
use caustic_kernel::light;
use caustic_kernel::rng::Sampler;
use caustic_kernel::sampling::*;
use common::*;

const RADIANCE: caustic_kernel::bsdf::TransportMode = caustic_kernel::bsdf::TransportMode::Radiance;

#[test]
fn cosine_hemisphere() {
    chi2_directions(
        "cosine hemisphere",
        |_, u| Some(square_to_cosine_hemisphere(u)),
        |d| cosine_hemisphere_pdf(d.z) as f64,
    );
}

#[test]
fn uniform_sphere() {
    chi2_directions(
        "uniform sphere",
        |_, u| Some(square_to_uniform_sphere(u)),
        |_| 1.0 / (4.0 * std::f64::consts::PI),
    );
}

#[test]
fn uniform_cone_wide_and_narrow() {
    for cos_max in [0.2f32, 0.9, 0.95] {
        let omc = 1.0 - cos_max;
        chi2_directions(
            &format!("cone cosθmax={cos_max}"),
            |_, u| Some(square_to_uniform_cone(u, omc)),
            |d| if d.z >= cos_max { uniform_cone_pdf(omc) as f64 } else { 0.0 },
        );
    }
}

#[test]
fn phong_lobe_and_mixture() {
    for (kd, ks, n) in [(0.0, 1.0, 10.0), (0.0, 0.9, 200.0), (0.5, 0.5, 30.0), (0.8, 0.1, 1.0)] {
        let bsdf = Phong::new(Vec3::splat(kd), Vec3::splat(ks), n);
        for wo in [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.6, 0.2, 0.3).normalize(),
            Vec3::new(0.99, 0.0, 0.05).normalize(),
        ] {
            chi2_directions(
                &format!("phong kd={kd} ks={ks} n={n} wo={wo:?}"),
                |ul, u| {
                    let s = bsdf.sample(wo, ul, u, RADIANCE);
                    (s.pdf > 0.0).then_some(s.wi)
                },
                |wi| bsdf.pdf(wo, wi, RADIANCE) as f64,
            );
        }
    }
}

/// The sphere light seen from outside: directions must be uniform inside the subtended cone, which in
/// the cone's own coordinates ((1 - cos θ)/(1 - cos θmax), φ) is the uniform square — this works for
/// near, far and tiny spheres alike. The reported pdf must be the cone's, and `pdf()` must agree.
#[test]
fn sphere_light_directions() {
    for (center, radius) in [
        (Vec3::new(0.0, 0.0, 3.0), 1.0f32),
        (Vec3::new(1.0, 2.0, 50.0), 1.0),
        (Vec3::new(0.0, 0.0, 1000.0), 0.5),
        (Vec3::new(3e4, -2e4, 1e4), 1e-2),
    ] {
        let prim = Primitive {
            p0: center.to_array(),
            kind: PRIM_SPHERE,
            p1: [radius, 0.0, 0.0],
            ..Default::default()
        };
        let l = Light { kind: LIGHT_SPHERE, prim: 0, pmf: 1.0, radiance: [1.0; 4], ..Default::default() };
        let d2 = center.length_squared();
        let omc = one_minus_cos_from_sin2(radius * radius / d2);
        let axis = Frame::from_normal(center.normalize());
        const N: usize = 16;
        let mut observed = vec![0.0; N * N];
        let mut rng = Sampler::new(7, 7, center.x as u32);
        for _ in 0..SAMPLES / 2 {
            let s = light::sphere::sample(&l, &prim, Vec3::ZERO, rng.next_2d());
            assert!(s.pdf > 0.0 && s.dist > 0.0 && s.radiance.x > 0.0);
            let rel = (s.pdf as f64 / uniform_cone_pdf(omc) as f64 - 1.0).abs();
            assert!(rel < 1e-4, "sample pdf {} is not the cone's", s.pdf);
            // The sampled point lies on the sphere.
            let q = s.wi * s.dist;
            // Up to the rounding of single-precision coordinates of that magnitude (a few ulps).
            assert!(
                ((q - center).length() - radius).abs()
                    <= 1e-3 * radius + 4.0 * f32::EPSILON * center.length(),
                "point off the sphere"
            );
            let local = axis.to_local(s.wi);
            let u = (((1.0 - local.z as f64) / omc as f64) * N as f64) as usize;
            let mut phi = (local.y as f64).atan2(local.x as f64);
            if phi < 0.0 {
                phi += 2.0 * std::f64::consts::PI;
            }
            let v = (phi / (2.0 * std::f64::consts::PI) * N as f64) as usize;
            observed[u.min(N - 1) * N + v.min(N - 1)] += 1.0;
            let pdf_again = light::sphere::pdf(&prim, Vec3::ZERO, q, (q - center).normalize());
            assert!((pdf_again / s.pdf - 1.0).abs() < 1e-4);
        }
        let expected = vec![(SAMPLES / 2) as f64 / (N * N) as f64; N * N];
        let p = chi2_p_value(&observed, &expected);
        println!("sphere light c={center:?} r={radius}: p = {p:.4}");
        // For cones narrower than ~1e-4 sr, single-precision unit vectors quantise (1 - cos θ) into a few
        // levels; there only the pdf and on-sphere checks apply (narrow cones are tested at 1e-4 above).
        if omc > 1e-4 {
            assert!(p > ALPHA, "sphere light c={center:?}: not uniform in its cone (p = {p:.2e})");
        }
    }
}

/// From inside a (flipped) sphere light, directions follow the area-sampling density.
#[test]
fn sphere_light_from_inside() {
    let center = Vec3::new(0.3, 0.0, 0.2);
    let prim = Primitive {
        p0: center.to_array(),
        kind: PRIM_SPHERE,
        p1: [2.0, 0.0, 0.0],
        flags: PRIM_FLAG_FLIP,
        ..Default::default()
    };
    let l = Light { kind: LIGHT_SPHERE, prim: 0, pmf: 1.0, radiance: [1.0; 4], ..Default::default() };
    chi2_directions(
        "sphere light from inside",
        |_, u| {
            let s = light::sphere::sample(&l, &prim, Vec3::ZERO, u);
            (s.pdf > 0.0).then_some(s.wi)
        },
        |wi| {
            let ray =
                caustic_kernel::camera::Ray { origin: Vec3::ZERO, dir: wi, t_min: 0.0, t_max: f32::MAX };
            let (t, _) = caustic_kernel::shape::sphere::intersect(center, 2.0, &ray, f32::MAX).unwrap();
            let q = wi * t;
            light::sphere::pdf(&prim, Vec3::ZERO, q, -(q - center).normalize()) as f64
        },
    );
}

/// χ² of area sampling on `prim` (emitting towards the origin along `normal`), seen as directions
/// from the origin: the area density converted to solid angle is the expected one.
fn area_light_chi2(name: &str, prim: Primitive, normal: Vec3) {
    let l = Light { kind: LIGHT_AREA, prim: 0, pmf: 1.0, radiance: [1.0; 4], ..Default::default() };
    let frame = Frame::from_normal(Vec3::Z);
    chi2_directions(
        name,
        |_, u| {
            let s = light::area::sample(&l, &prim, Vec3::ZERO, u);
            (s.pdf > 0.0).then_some(frame.to_local(s.wi))
        },
        |wi| {
            let ray =
                caustic_kernel::camera::Ray { origin: Vec3::ZERO, dir: wi, t_min: 0.0, t_max: f32::MAX };
            match caustic_kernel::shape::intersect(
                &prim,
                &ray,
                &caustic_kernel::shape::triangle::RayShear::of(&ray),
                f32::MAX,
            ) {
                Some((t, _)) => light::area::pdf(&prim, Vec3::ZERO, wi * t, normal) as f64,
                None => 0.0,
            }
        },
    );
}

#[test]
fn triangle_light_directions() {
    let (p0, p1, p2) = (Vec3::new(-1.0, -0.5, 2.0), Vec3::new(1.5, -0.2, 1.0), Vec3::new(0.2, 1.5, 1.5));
    // Winding chosen so that the emitting side faces the origin.
    let prim = Primitive {
        p0: p0.to_array(),
        p1: p2.to_array(),
        p2: p1.to_array(),
        kind: PRIM_TRIANGLE,
        ..Default::default()
    };
    area_light_chi2("triangle light", prim, (p2 - p0).cross(p1 - p0).normalize());
}

/// A tilted ellipse: an uneven affine image of the unit disk.
#[test]
fn disk_light_directions() {
    let (c, u, v) = (Vec3::new(0.3, -0.2, 2.0), Vec3::new(1.2, 0.0, 0.4), Vec3::new(0.1, 0.6, -0.2));
    // u × v points away from the origin; the flag turns the emitting side towards it.
    assert!(u.cross(v).dot(c) > 0.0);
    let prim = Primitive {
        p0: c.to_array(),
        p1: u.to_array(),
        p2: v.to_array(),
        kind: PRIM_DISK,
        flags: PRIM_FLAG_FLIP,
        ..Default::default()
    };
    area_light_chi2("disk light", prim, -u.cross(v).normalize());
}

/// Uniform barycentrics: χ² over a grid of the (b1, b2) unit triangle.
#[test]
fn triangle_barycentrics_are_uniform() {
    const N: usize = 20;
    let mut observed = vec![0.0; N * N];
    let mut rng = Sampler::new(1, 2, 3);
    for _ in 0..SAMPLES {
        let b = square_to_uniform_triangle(rng.next_2d());
        assert!(b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 + 1e-6);
        observed[((b.x * N as f32) as usize).min(N - 1) * N + ((b.y * N as f32) as usize).min(N - 1)] += 1.0;
    }
    // Expected: the area of each grid cell inside the triangle, times the density 2.
    let mut expected = vec![0.0; N * N];
    const SUB: usize = 16;
    for i in 0..N * SUB {
        for j in 0..N * SUB {
            let (x, y) = ((i as f64 + 0.5) / (N * SUB) as f64, (j as f64 + 0.5) / (N * SUB) as f64);
            if x + y <= 1.0 {
                expected[(i / SUB) * N + j / SUB] += 2.0 / ((N * SUB) as f64).powi(2) * SAMPLES as f64;
            }
        }
    }
    let p = chi2_p_value(&observed, &expected);
    println!("triangle barycentrics: p = {p:.4}");
    assert!(p > ALPHA);
}

/// Power-proportional light selection from the tabulated CDF.
#[test]
fn light_selection_follows_the_pmf() {
    let weights = [5.0f32, 0.0, 1.0, 3.0, 0.5, 10.0, 0.0, 2.5];
    let total: f32 = weights.iter().sum();
    let mut cdf = Vec::new();
    let mut run = 0.0;
    for w in weights {
        run += w / total;
        cdf.push(run);
    }
    *cdf.last_mut().unwrap() = 1.0;
    // An offset in front checks that tables are addressed relative to their start.
    let mut tables = vec![9.0f32; 3];
    tables.extend(&cdf);
    let mut observed = vec![0.0; weights.len()];
    let mut rng = Sampler::new(4, 5, 6);
    for _ in 0..SAMPLES {
        let s = sample_cdf(&tables, 3, weights.len() as u32, rng.next_1d());
        assert!((0.0..1.0).contains(&s.remapped));
        observed[s.index as usize] += 1.0;
    }
    assert_eq!(observed[1], 0.0, "a zero-power light was chosen");
    assert_eq!(observed[6], 0.0, "a zero-power light was chosen");
    let expected: Vec<f64> = weights.iter().map(|w| (*w / total) as f64 * SAMPLES as f64).collect();
    let p = chi2_p_value(&observed, &expected);
    println!("light selection: p = {p:.4}");
    assert!(p > ALPHA);
}

/// A point of [0, 1] with linear density (`sample_linear`, inside an envmap's cells) against
/// `linear_pdf`, whose integral over each bin is the CDF's difference; with either end at zero, both
/// at zero (uniform) and ends a hundredfold apart.
#[test]
fn linear_segment() {
    const BINS: usize = 64;
    for (a, b) in [(1.0f32, 1.0f32), (0.0, 1.0), (1.0, 0.0), (0.2, 3.0), (5.0, 0.05), (0.0, 0.0)] {
        let cdf = |x: f64| {
            let (a, b) = (a as f64, b as f64);
            if a + b > 0.0 {
                ((2.0 - x) * a * x + b * x * x) / (a + b)
            } else {
                x
            }
        };
        let mut observed = vec![0.0; BINS];
        let mut rng = Sampler::new(7, (a * 10.0) as u32, (b * 10.0) as u32);
        for _ in 0..SAMPLES {
            let x = sample_linear(rng.next_1d(), a, b);
            assert!((0.0..1.0).contains(&x), "{x} outside [0, 1) for ({a}, {b})");
            observed[(x * BINS as f32) as usize] += 1.0;
        }
        let expected: Vec<f64> = (0..BINS)
            .map(|i| (cdf((i + 1) as f64 / BINS as f64) - cdf(i as f64 / BINS as f64)) * SAMPLES as f64)
            .collect();
        let p = chi2_p_value(&observed, &expected);
        println!("linear ({a}, {b}): p = {p:.4}");
        assert!(p > ALPHA, "linear ({a}, {b}): samples do not follow the density (p = {p:.2e})");
        // The density it reports is the CDF's derivative.
        for x in [0.0f32, 0.3, 0.7, 0.999] {
            let h = 1e-4;
            let slope = (cdf(x as f64 + h) - cdf(x as f64 - h)) / (2.0 * h);
            assert!((linear_pdf(x, a, b) as f64 - slope).abs() < 1e-3, "pdf at {x} for ({a}, {b})");
        }
    }
}

#[test]
fn power_heuristic_is_stable() {
    assert_eq!(power_heuristic(1.0, 0.0), 1.0);
    assert_eq!(power_heuristic(0.0, 1.0), 0.0);
    assert!((power_heuristic(1e30, 1e30) - 0.5).abs() < 1e-6);
    assert!((power_heuristic(1e-30, 1e-30) - 0.5).abs() < 1e-6);
    assert_eq!(power_heuristic(1.0, f32::INFINITY), 0.0);
    let w = power_heuristic(2.0, 1.0) + power_heuristic(1.0, 2.0);
    assert!((w - 1.0).abs() < 1e-6);
}

/// `1 - cos θmax` for tiny or far spheres: the naive form cancels to 0, ours keeps precision.
#[test]
fn cone_of_a_tiny_sphere_keeps_its_solid_angle() {
    let (r, d) = (1e-3f32, 1e3f32);
    let sin2 = (r / d) * (r / d);
    let omc = one_minus_cos_from_sin2(sin2);
    let exact = sin2 as f64 / 2.0; // small-angle expansion, relative error ~sin²/4
    assert!(((omc as f64 - exact) / exact).abs() < 1e-5, "{omc} vs {exact}");
    assert_eq!(1.0 - (1.0 - sin2).sqrt(), 0.0, "(the naive form really does cancel here)");
}

/// A projector's emission directions (`light::projector::direction`, uniform over the image) against
/// the density it reports, `1 / (area · cos³θ)` inside the image's pyramid, for a square image, a wide
/// one and a narrow one.
#[test]
fn projector_directions() {
    for (tan_x, tan_y) in [(0.5f32, 0.5f32), (0.7, 0.35), (0.1, 0.15)] {
        let area = 4.0 * tan_x * tan_y;
        let rows = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
        let l = Light {
            kind: LIGHT_PROJECTOR,
            pmf: 1.0,
            params: [tan_x, tan_y, 0.0, area],
            to_local: rows,
            ..Default::default()
        };
        chi2_directions(
            &format!("projector tan {tan_x}×{tan_y}"),
            |_, u| {
                let (d, density) = light::projector::direction(&l, u);
                let expected = light::projector::density(d.z, area);
                assert!(
                    (density - expected).abs() <= 1e-4 * expected,
                    "reported density {density} for {expected}"
                );
                Some(d)
            },
            |d| {
                let inside = d.z > 0.0 && (d.x / d.z).abs() <= tan_x && (d.y / d.z).abs() <= tan_y;
                if inside {
                    1.0 / (area as f64 * (d.z as f64).powi(3))
                } else {
                    0.0
                }
            },
        );
    }
}
