//! BSDF checks: reciprocity, energy conservation (numerical albedo ≤ 1), and agreement between the
//! sampling weights and eval/pdf.
use caustic_kernel::bsdf::Bsdf;
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use caustic_kernel::sampling::square_to_uniform_sphere;

const RADIANCE: caustic_kernel::bsdf::TransportMode = caustic_kernel::bsdf::TransportMode::Radiance;

fn materials() -> Vec<Material> {
    let mut v =
        vec![Material { kind: BSDF_DIFFUSE, reflectance: [1.0, 0.5, 0.2, 0.0], ..Default::default() }];
    for (kd, ks, n) in
        [(0.0, 1.0, 1.0), (0.0, 1.0, 50.0), (0.5, 0.5, 10.0), (0.3, 0.7, 1000.0), (0.9, 0.1, 0.0)]
    {
        v.push(Material {
            kind: BSDF_PHONG,
            eta: n,
            reflectance: [kd; 4],
            specular_reflectance: [ks; 4],
            ..Default::default()
        });
    }
    v
}

fn directions(n: usize) -> Vec<Vec3> {
    let mut rng = Sampler::new(9, 9, 9);
    (0..n).map(|_| square_to_uniform_sphere(rng.next_2d())).collect()
}

#[test]
fn reciprocity() {
    let dirs = directions(400);
    for m in materials() {
        let b = Bsdf::from_material(&m, &[]);
        for pair in dirs.chunks(2) {
            let (wo, wi) = (pair[0], pair[1]);
            // eval includes |cos θi|; f itself must be symmetric.
            let f1 = b.eval(wo, wi, RADIANCE) / wi.z.abs().max(1e-8);
            let f2 = b.eval(wi, wo, RADIANCE) / wo.z.abs().max(1e-8);
            assert!(
                (f1 - f2).abs().max_element() <= 1e-4 * f1.abs().max_element().max(1.0),
                "kind {} not reciprocal: {f1} vs {f2}",
                m.kind
            );
        }
    }
}

/// Directional albedo ∫ f cos dωi by quadrature over the whole sphere, in coordinates around the
/// mirror direction with `cos α = 1 - 2s²` so that narrow lobes (exponent 1000) are resolved.
fn albedo(b: &Bsdf, wo: Vec3) -> Vec3 {
    const N: usize = 600;
    let frame = caustic_kernel::frame::Frame::from_normal(Vec3::new(-wo.x, -wo.y, wo.z));
    let mut sum = Vec3::ZERO;
    for i in 0..N {
        let s = (i as f64 + 0.5) / N as f64;
        let cos_a = 1.0 - 2.0 * s * s;
        let d_cos = 4.0 * s / N as f64;
        let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
        for j in 0..N {
            let phi = (j as f64 + 0.5) / N as f64 * 2.0 * std::f64::consts::PI;
            let local = Vec3::new((sin_a * phi.cos()) as f32, (sin_a * phi.sin()) as f32, cos_a as f32);
            sum += b.eval(wo, frame.to_world(local), RADIANCE)
                * (d_cos * 2.0 * std::f64::consts::PI / N as f64) as f32;
        }
    }
    sum
}

#[test]
fn energy_is_conserved_and_sampling_weights_agree() {
    for m in materials() {
        let b = Bsdf::from_material(&m, &[]);
        for wo in [Vec3::Z, Vec3::new(0.5, 0.0, 0.5).normalize(), Vec3::new(0.99, 0.1, 0.02).normalize()] {
            let a = albedo(&b, wo);
            assert!(
                a.max_element() <= 1.0 + 2e-3,
                "kind {} exponent {} reflects {a} > 1 at wo {wo}",
                m.kind,
                m.eta
            );
            // The mean sampling weight estimates the same albedo.
            let mut rng = Sampler::new(1, m.kind, (wo.x * 1000.0) as u32);
            let n = 200_000;
            let mut mean = Vec3::ZERO;
            let mut sq = Vec3::ZERO;
            for _ in 0..n {
                let ul = rng.next_1d();
                let s = b.sample(wo, ul, rng.next_2d(), RADIANCE);
                if s.pdf > 0.0 {
                    assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0);
                    mean += s.weight;
                    sq += s.weight * s.weight;
                }
            }
            mean /= n as f32;
            let se = ((sq / n as f32 - mean * mean) / n as f32).max(Vec3::ZERO);
            let tol = se.x.sqrt().max(se.y.sqrt()).max(se.z.sqrt()) * 5.0 + 2e-3;
            assert!(
                (mean - a).abs().max_element() <= tol,
                "kind {} n {} wo {wo}: sampled albedo {mean} vs quadrature {a}",
                m.kind,
                m.eta
            );
        }
    }
}

#[test]
fn back_side_is_black_for_one_sided_models() {
    for m in materials() {
        let b = Bsdf::from_material(&m, &[]);
        let below = Vec3::new(0.2, 0.1, -0.9).normalize();
        let above = Vec3::new(0.1, -0.3, 0.8).normalize();
        assert_eq!(b.eval(below, above, RADIANCE), Vec3::ZERO);
        assert_eq!(b.eval(above, below, RADIANCE), Vec3::ZERO);
        assert_eq!(b.pdf(above, below, RADIANCE), 0.0);
        assert_eq!(b.sample(below, 0.3, caustic_kernel::glam::Vec2::new(0.4, 0.6), RADIANCE).pdf, 0.0);
    }
}
