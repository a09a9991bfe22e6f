//! Consistency of each model with itself, across the `Bxdf` interface: sampling weights equal
//! `eval / pdf` at the sampled direction, the fused `eval_pdf` computes bit for bit what `eval` and
//! `pdf` compute apart, and the `flags()` a model declares match what it does (integrators trust the
//! flags to skip light sampling and connections).
mod common;
use caustic_kernel::bsdf::fresnel::reflect;
use caustic_kernel::bsdf::{BsdfFlags, TransportMode};
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::Material;
use caustic_kernel::rng::Sampler;
use common::mitsuba::{reference_material, REFERENCE_MODELS};
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

/// Every model kind: `every_model` and the materials of the Mitsuba references.
fn all_models() -> Vec<(String, Material)> {
    let mut v = every_model();
    for name in REFERENCE_MODELS {
        v.push((format!("mitsuba reference {name}"), reference_material(name)));
    }
    v
}

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

/// The fused `eval_pdf` (which models override to share the half vector, `D` and Fresnel between the
/// two) must compute exactly what `eval` and `pdf` compute apart: bitwise on the CPU, so that next-event
/// estimation (which calls `eval_pdf`) and BSDF sampling's MIS weights (which call `pdf`) agree on
/// every path. On random direction pairs, on both sides of the surface, and on sampled directions,
/// where the lobes are.
#[test]
fn eval_pdf_is_eval_and_pdf_bitwise() {
    let dirs = random_dirs(2000, 31);
    for (name, m) in all_models() {
        let base = Model::new(&m, false);
        for mode in MODES {
            let b = base.in_mode(mode);
            let mut rng = Sampler::new(5, 5, 5);
            let mut nonzero = 0;
            for pair in dirs.chunks(2) {
                let wo = pair[0];
                let ul = rng.next_1d();
                let sampled = b.sample(wo, ul, rng.next_2d()).wi;
                for wi in [pair[1], sampled, reflect(wo), -wo] {
                    let fused = b.eval_pdf(wo, wi);
                    let (f, pdf) = (b.eval(wo, wi), b.pdf(wo, wi));
                    assert!(
                        bits(fused.f) == bits(f) && fused.pdf.to_bits() == pdf.to_bits(),
                        "{name} {mode:?} wo={wo} wi={wi}: eval_pdf gives ({}, {}), eval and pdf ({f}, {pdf})",
                        fused.f,
                        fused.pdf
                    );
                    nonzero += (pdf > 0.0) as u32;
                }
            }
            // A model with smooth lobes must have been compared where it is non-zero.
            if b.bsdf.flags().has_smooth() {
                assert!(nonzero > 200, "{name} {mode:?}: only {nonzero} pairs with pdf > 0");
            }
        }
    }
}

/// Each model's `flags()` against its behaviour, from both sides of the surface in both modes:
/// - without DIFFUSE or GLOSSY, `eval` and `pdf` are zero everywhere (also at the mirror and straight
///   through) and every sample is a Dirac delta; with them, `eval` is positive somewhere and some
///   samples are not deltas;
/// - SPECULAR models produce delta samples, the others never do;
/// - TRANSMISSION models produce samples across the surface (`wi.z · wo.z < 0`), the others never do;
///   REFLECTION models produce samples on the side of `wo`, the others never do.
#[test]
fn flags_agree_with_behaviour() {
    let dirs = random_dirs(400, 41);
    for (name, m) in all_models() {
        let base = Model::new(&m, false);
        for mode in MODES {
            let b = base.in_mode(mode);
            let flags = b.bsdf.flags();
            let mut rng = Sampler::new(8, 8, 8);
            let mut max_eval = 0.0f32;
            let (mut delta, mut non_delta, mut across, mut same_side) = (0, 0, 0, 0);
            for (i, &wo) in dirs.iter().enumerate() {
                let mut wis = vec![dirs[(i + 1) % dirs.len()], reflect(wo), -wo];
                for _ in 0..8 {
                    let ul = rng.next_1d();
                    let s = b.sample(wo, ul, rng.next_2d());
                    if s.pdf <= 0.0 {
                        continue;
                    }
                    if s.delta {
                        delta += 1;
                    } else {
                        non_delta += 1;
                    }
                    if s.wi.z * wo.z < 0.0 {
                        across += 1;
                    } else if s.wi.z * wo.z > 0.0 {
                        same_side += 1;
                    }
                    wis.push(s.wi);
                }
                for wi in wis {
                    let (f, pdf) = (b.eval(wo, wi), b.pdf(wo, wi));
                    if !flags.has_smooth() {
                        assert!(
                            f == Vec3::ZERO && pdf == 0.0,
                            "{name} {mode:?}: no smooth lobe flagged, but eval({wo}, {wi}) = {f}, pdf {pdf}"
                        );
                    }
                    max_eval = max_eval.max(f.max_element());
                }
            }
            let ctx = format!(
                "{name} {mode:?} flags {:#b}: {delta} delta and {non_delta} other samples, {across} across \
                 the surface, {same_side} on the side of wo, largest eval {max_eval}",
                flags.0
            );
            if flags.has_smooth() {
                assert!(max_eval > 0.0 && non_delta > 0, "{ctx}: a smooth lobe is flagged but never seen");
            } else {
                assert_eq!(non_delta, 0, "{ctx}: only Dirac lobes are flagged");
            }
            assert_eq!(flags.has_specular(), delta > 0, "{ctx}: SPECULAR flag vs delta samples");
            assert_eq!(flags.has_transmission(), across > 0, "{ctx}: TRANSMISSION flag vs samples");
            assert_eq!(
                flags.0 & BsdfFlags::REFLECTION != 0,
                same_side > 0,
                "{ctx}: REFLECTION flag vs samples"
            );
        }
    }
}
