//! Lambert and modified Phong (the models of OBJ/MTL scenes): reciprocity, energy conservation
//! (albedo ≤ 1, also for a very narrow lobe, and sampling weights that estimate the same albedo), and
//! a black back side. The checks are those of the other models (`common::bsdf_checks`); Phong's
//! sampling is χ²-tested in `sampling.rs`.
mod common;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::rng::Sampler;
use common::bsdf_checks::{albedo, check_energy, check_reciprocity, mirror_albedo_grid};
use common::models::{diffuse_and_phong, Model};

fn name(m: &caustic_kernel::layout::Material) -> String {
    format!("kind {} exponent {}", m.kind, m.eta)
}

#[test]
fn reciprocity() {
    let dirs = {
        // The pairs this test has always used (not `random_dirs`, whose sampler is seeded otherwise).
        let mut rng = Sampler::new(9, 9, 9);
        (0..400)
            .map(|_| caustic_kernel::sampling::square_to_uniform_sphere(rng.next_2d()))
            .collect::<Vec<_>>()
    };
    for m in diffuse_and_phong() {
        check_reciprocity(
            &name(&m),
            &Model::new(&m, false),
            &dirs,
            // f itself must be symmetric (eval includes |cos θi|), to 1e-4 of max(f, 1).
            |a, b| (a - b).abs().max_element() <= 1e-4 * a.abs().max_element().max(1.0),
            |_, _| false,
        );
    }
}

/// Albedo by quadrature on a grid crowded around the mirror direction (the exponent-1000 lobe is
/// ~0.03 rad wide), and the mean sampling weight against it.
#[test]
fn energy_is_conserved_and_sampling_weights_agree() {
    for m in diffuse_and_phong() {
        let b = Model::new(&m, false);
        for wo in [Vec3::Z, Vec3::new(0.5, 0.0, 0.5).normalize(), Vec3::new(0.99, 0.1, 0.02).normalize()] {
            let a = albedo(&b, wo, &mirror_albedo_grid(wo));
            let rng = Sampler::new(1, m.kind, (wo.x * 1000.0) as u32);
            check_energy(&name(&m), &b, wo, a, 0.0, 200_000, rng);
        }
    }
}

#[test]
fn back_side_is_black_for_one_sided_models() {
    for m in diffuse_and_phong() {
        let b = Model::new(&m, false);
        let below = Vec3::new(0.2, 0.1, -0.9).normalize();
        let above = Vec3::new(0.1, -0.3, 0.8).normalize();
        assert_eq!(b.eval(below, above), Vec3::ZERO);
        assert_eq!(b.eval(above, below), Vec3::ZERO);
        assert_eq!(b.pdf(above, below), 0.0);
        assert_eq!(b.sample(below, 0.3, Vec2::new(0.4, 0.6)).pdf, 0.0);
    }
}
