//! Agreement with Mitsuba 3.9.1: every model's `eval`, `pdf` and `sample` against Mitsuba's own values
//! for the same materials, directions and random numbers, in radiance and importance (`adjoint`)
//! transport. The values live in `data/mitsuba_bsdf_values.json`; `data/mitsuba_bsdf_values.py`
//! wrote them with Mitsuba's Python bindings (`pip install mitsuba==3.9.1`, variant `scalar_rgb`) and
//! says how to regenerate them; `common::mitsuba::reference_material` mirrors its dictionaries.
mod common;
use caustic_kernel::glam::{Vec2, Vec3};
use common::mitsuba::{reference_model, references, REFERENCE_MODELS};
use common::models::{close, close3};

#[test]
fn eval_and_pdf_match_mitsuba() {
    let refs = references().eval;
    let mut worst = 0.0f32;
    for r in &refs {
        let b = reference_model(&r.model, r.adjoint);
        let (wo, wi) = (r.wo, r.wi);
        let f = b.eval(wo, wi);
        let pdf = b.pdf(wo, wi);
        let want = r.f;
        let scale = want.max_element().max(1e-3);
        worst = worst.max((f - want).abs().max_element() / scale);
        assert!(
            close3(f, want, 2e-3, 1e-6),
            "{} adjoint={}: eval({wo}, {wi}) = {f}, Mitsuba {want}",
            r.model,
            r.adjoint
        );
        assert!(
            close(pdf, r.pdf, 2e-3, 1e-6),
            "{} adjoint={}: pdf({wo}, {wi}) = {pdf}, Mitsuba {}",
            r.model,
            r.adjoint,
            r.pdf
        );
    }
    let nonzero = refs.iter().filter(|r| r.pdf > 0.0).count();
    println!(
        "{} references ({nonzero} with pdf > 0), largest relative eval difference {worst:.2e}",
        refs.len()
    );
}

#[test]
fn samples_match_mitsuba() {
    let refs = references().sample;
    for r in &refs {
        let b = reference_model(&r.model, r.adjoint);
        let wo = r.wo;
        let s = b.sample(wo, r.u_lobe, Vec2::from(r.u));
        let want_w = r.weight;
        // Mitsuba returns zero-weight samples where caustic reports none (pdf 0): both end the path.
        if r.pdf == 0.0 || want_w == Vec3::ZERO {
            assert!(
                s.pdf == 0.0 || s.weight == Vec3::ZERO,
                "{}: Mitsuba's sample is void, ours {} {}",
                r.model,
                s.wi,
                s.weight
            );
            continue;
        }
        let ctx = format!("{} adjoint={} wo={wo} u=({}, {:?})", r.model, r.adjoint, r.u_lobe, r.u);
        assert!(close3(s.wi, r.wi, 1e-3, 1e-4), "{ctx}: wi {} vs Mitsuba {}", s.wi, r.wi);
        assert!(close3(s.weight, want_w, 3e-3, 1e-5), "{ctx}: weight {} vs Mitsuba {want_w}", s.weight);
        assert!(close(s.pdf, r.pdf, 3e-3, 1e-6), "{ctx}: pdf {} vs Mitsuba {}", s.pdf, r.pdf);
        assert_eq!(s.eta, r.eta, "{ctx}: eta");
    }
}

/// Every reference model and mode has rows of each kind it should: a model dropped from the file (or
/// misspelt in it) would otherwise go untested without a failure.
#[test]
fn every_reference_model_has_values() {
    let refs = references();
    let count = |model: &str, adjoint: bool, eval: bool| {
        if eval {
            refs.eval.iter().filter(|r| r.model == model && r.adjoint == adjoint).count()
        } else {
            refs.sample.iter().filter(|r| r.model == model && r.adjoint == adjoint).count()
        }
    };
    let delta = ["conductor", "dielectric", "thin_dielectric"];
    let refracting =
        ["dielectric", "thin_dielectric", "rough_dielectric_ggx", "rough_dielectric_beckmann_aniso"];
    let models = REFERENCE_MODELS;
    for model in models {
        // Building it checks that the name is one `reference_material` knows.
        reference_model(model, false);
        for adjoint in [false, true] {
            if adjoint && !refracting.contains(&model) {
                continue;
            }
            assert!(count(model, adjoint, false) >= 12, "{model} adjoint={adjoint}: too few sample rows");
            if !delta.contains(&model) {
                assert!(count(model, adjoint, true) >= 12, "{model} adjoint={adjoint}: too few eval rows");
            }
        }
    }
    for r in &refs.eval {
        assert!(models.contains(&r.model.as_str()), "unknown model {} in the eval rows", r.model);
    }
    for r in &refs.sample {
        assert!(models.contains(&r.model.as_str()), "unknown model {} in the sample rows", r.model);
    }
}
