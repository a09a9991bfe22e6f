//! Consistency of each model with itself, across the `Bxdf` interface: sampling weights equal
//! `eval / pdf` at the sampled direction.
mod common;
use caustic_kernel::bsdf::TransportMode;
use caustic_kernel::rng::Sampler;
use common::models::*;

#[test]
fn sample_weights_equal_eval_over_pdf() {
    let wos = random_dirs(40, 11);
    for (name, m) in smooth_models() {
        let base = Model::new(&m, false);
        for adjoint in [false, true] {
            let mut b = base;
            b.mode = if adjoint { TransportMode::Importance } else { TransportMode::Radiance };
            let mut rng = Sampler::new(3, 3, 3);
            let mut checked = 0;
            for wo in &wos {
                for _ in 0..50 {
                    let ul = rng.next_1d();
                    let s = b.sample(*wo, ul, rng.next_2d());
                    if s.pdf <= 0.0 || s.delta {
                        continue;
                    }
                    let (f, pdf) = (b.eval(*wo, s.wi), b.pdf(*wo, s.wi));
                    assert!(
                        close(s.pdf, pdf, 2e-3, 1e-6),
                        "{name} wo={wo} wi={}: sample pdf {} vs pdf {pdf}",
                        s.wi,
                        s.pdf
                    );
                    assert!(
                        close3(s.weight, f / pdf, 2e-3, 1e-6),
                        "{name} wo={wo} wi={}: weight {} vs eval/pdf {}",
                        s.wi,
                        s.weight,
                        f / pdf
                    );
                    checked += 1;
                }
            }
            assert!(checked > 500, "{name}: only {checked} samples");
        }
    }
}
