//! Mitsuba's `pplastic` in its unpolarized form (`kernel/src/bsdf/pplastic.rs`): eval, pdf and sample
//! against Mitsuba 3.9.1's own values (`data/pplastic_values.json`, written by
//! `data/pplastic_values.py`), χ² of its sampling against its pdf, reciprocity, and energy.
mod common;
use caustic_kernel::bsdf::pplastic::PARAM_SPECULAR_WEIGHT;
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use common::bsdf_checks::{albedo, check_energy, check_reciprocity, chi2_model, sphere_grid};
use common::mitsuba::references_in;
use common::models::*;
use common::Grid;
use serde_json::Value;

const VALUES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pplastic_values.json");

/// A pplastic material from Mitsuba's dictionary `d`, with Mitsuba's defaults (Beckmann, α 0.1,
/// polypropylene 1.49 over air 1.000277), stored as the host stores it.
fn pplastic_material(d: &Value) -> Material {
    let num = |k: &str, default: f32| d.get(k).map(|v| v.as_f64().unwrap() as f32).unwrap_or(default);
    let colour = |k: &str, default: f32| {
        d.get(k).map_or([default; 3], |c| {
            let v = c["value"].as_array().unwrap();
            [0, 1, 2].map(|i| v[i].as_f64().unwrap() as f32)
        })
    };
    let (diffuse, specular) = (colour("diffuse_reflectance", 0.5), colour("specular_reflectance", 1.0));
    let mean = |c: [f32; 3]| (c[0] + c[1] + c[2]) / 3.0;
    let eta = if d.get("eta").is_some() {
        num("eta", 0.0)
    } else {
        num("int_ior", 1.49) / num("ext_ior", 1.000277)
    };
    let alpha = num("alpha", 0.1);
    let ggx = d.get("distribution").is_some_and(|v| v == "ggx");
    let mut m = Material {
        kind: BSDF_PPLASTIC,
        flags: if ggx { 0 } else { MATERIAL_BECKMANN },
        eta,
        alpha_u: num("alpha_u", alpha),
        alpha_v: num("alpha_v", alpha),
        reflectance: c4(diffuse[0], diffuse[1], diffuse[2]),
        specular_reflectance: c4(specular[0], specular[1], specular[2]),
        ..Default::default()
    };
    m.params[PARAM_SPECULAR_WEIGHT] = mean(specular) / (mean(diffuse) + mean(specular));
    m
}

fn materials() -> Vec<(String, Material)> {
    let text = std::fs::read_to_string(VALUES).unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    v["materials"].as_object().unwrap().iter().map(|(k, d)| (k.clone(), pplastic_material(d))).collect()
}

fn model(name: &str) -> Model {
    let (_, m) = materials().into_iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no {name}"));
    Model::new(&m, false)
}

#[test]
fn eval_and_pdf_match_mitsuba() {
    let refs = references_in(VALUES).eval;
    let mut nonzero = 0;
    for r in &refs {
        let b = model(&r.model);
        let (f, pdf) = (b.eval(r.wo, r.wi), b.pdf(r.wo, r.wi));
        let ctx = format!("{} wo={} wi={}", r.model, r.wo, r.wi);
        assert!(close3(f, r.f, 2e-3, 1e-6), "{ctx}: eval {f}, Mitsuba {}", r.f);
        assert!(close(pdf, r.pdf, 2e-3, 1e-6), "{ctx}: pdf {pdf}, Mitsuba {}", r.pdf);
        nonzero += (r.pdf > 0.0) as u32;
    }
    assert!(refs.len() >= 40 && nonzero >= 20, "{} rows, {nonzero} non-zero", refs.len());
}

#[test]
fn samples_match_mitsuba() {
    let refs = references_in(VALUES).sample;
    let mut valid = 0;
    for r in &refs {
        let b = model(&r.model);
        let s = b.sample(r.wo, r.u_lobe, Vec2::from(r.u));
        let ctx = format!("{} wo={} u=({}, {:?})", r.model, r.wo, r.u_lobe, r.u);
        if r.pdf == 0.0 || r.weight == Vec3::ZERO {
            assert!(s.pdf == 0.0 || s.weight == Vec3::ZERO, "{ctx}: Mitsuba's is void, ours {}", s.wi);
            continue;
        }
        valid += 1;
        assert!(close3(s.wi, r.wi, 1e-3, 1e-4), "{ctx}: wi {} vs Mitsuba {}", s.wi, r.wi);
        assert!(close3(s.weight, r.weight, 3e-3, 1e-5), "{ctx}: weight {} vs Mitsuba {}", s.weight, r.weight);
        assert!(close(s.pdf, r.pdf, 3e-3, 1e-6), "{ctx}: pdf {} vs Mitsuba {}", s.pdf, r.pdf);
    }
    assert!(valid >= 40, "only {valid} valid samples");
}

#[test]
fn chi2_of_every_material() {
    for (k, (name, m)) in materials().iter().enumerate() {
        for (j, cos) in [0.9f32, 0.4, 0.05].iter().enumerate() {
            let wo = polar(*cos, 0.7);
            let label = format!("pplastic {name} wo={wo}");
            chi2_model(&label, &Model::new(m, false), wo, &sphere_grid(), (k * 8 + j) as u32);
        }
    }
}

#[test]
fn reciprocity() {
    let dirs = random_dirs(4000, 4);
    for (name, m) in materials() {
        let checked = check_reciprocity(
            &name,
            &Model::new(&m, false),
            &dirs,
            |a, b| close3(a, b, 2e-3, 1e-6),
            |_, _| false,
        );
        assert!(checked > 100, "{name}: too few non-zero pairs ({checked})");
    }
}

/// White base and coating: the glossy lobe reflects F and the base what the coating lets through
/// twice, without the internal reflections `roughplastic` keeps, so the albedo stays below 1; the
/// mean sampling weight reproduces it.
#[test]
fn energy() {
    let white = serde_json::json!({"type": "pplastic", "diffuse_reflectance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}, "alpha": 0.3, "distribution": "ggx"});
    let b = Model::new(&pplastic_material(&white), false);
    for (k, cos) in [1.0f32, 0.5, 0.1].iter().enumerate() {
        let wo = polar(*cos, 0.2);
        let a = albedo(&b, wo, &Grid::coarse(Vec3::Z));
        println!("cos θo={cos}: albedo {a:.4}");
        check_energy("white pplastic", &b, wo, a, 0.0, 50_000, Sampler::new(k as u32, 17, 1));
    }
}
