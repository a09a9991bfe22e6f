//! Mitsuba's `blendbsdf` (`kernel/src/bsdf/blend.rs`): eval, pdf and sample against Mitsuba 3.9.1's
//! own values (`data/blend_values.json`, written by `data/blend_values.py`), the one documented
//! divergence (Dirac samples), χ² of its sampling against its pdf, reciprocity, and energy in a
//! white furnace.
mod common;
use caustic_kernel::bsdf::{blend, TransportMode};
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use common::bsdf_checks::{albedo, check_energy, check_reciprocity, chi2_model, sphere_grid};
use common::mitsuba::{reference_material, references_in};
use common::models::*;
use common::Grid;
use serde_json::Value;

const VALUES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/blend_values.json");

/// A child as the script names it: one of `mitsuba_bsdf_values.py`'s materials, or its `DIFFUSE`.
fn child(name: &str) -> Material {
    match name {
        "diffuse" => Material { reflectance: c4(0.2, 0.6, 0.4), ..material(BSDF_DIFFUSE) },
        _ => reference_material(name),
    }
}

/// The blend `name` of the values file: its children and weight.
fn blend_of(name: &str) -> (Material, Material, f32) {
    let text = std::fs::read_to_string(VALUES).unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    let b = &v["blends"][name];
    (
        child(b["first"].as_str().unwrap()),
        child(b["second"].as_str().unwrap()),
        b["weight"].as_f64().unwrap() as f32,
    )
}

fn model(name: &str, adjoint: bool) -> Model {
    let (a, b, w) = blend_of(name);
    Model::blend(&a, &b, w, adjoint)
}

#[test]
fn eval_and_pdf_match_mitsuba() {
    let refs = references_in(VALUES).eval;
    let mut nonzero = 0;
    for r in &refs {
        let b = model(&r.model, r.adjoint);
        let (f, pdf) = (b.eval(r.wo, r.wi), b.pdf(r.wo, r.wi));
        let ctx = format!("{} adjoint={} wo={} wi={}", r.model, r.adjoint, r.wo, r.wi);
        assert!(close3(f, r.f, 2e-3, 1e-6), "{ctx}: eval {f}, Mitsuba {}", r.f);
        assert!(close(pdf, r.pdf, 2e-3, 1e-6), "{ctx}: pdf {pdf}, Mitsuba {}", r.pdf);
        let ep = b.eval_pdf(r.wo, r.wi);
        assert!(close3(ep.f, f, 1e-6, 0.0) && close(ep.pdf, pdf, 1e-6, 0.0), "{ctx}: eval_pdf");
        nonzero += (r.pdf > 0.0) as u32;
    }
    assert!(refs.len() >= 80 && nonzero >= 40, "{} rows, {nonzero} non-zero", refs.len());
}

/// Samples of smooth lobes: Mitsuba's direction, mixture weight, mixture pdf and eta.
#[test]
fn smooth_samples_match_mitsuba() {
    let refs = references_in(VALUES).sample;
    let mut valid = 0;
    for r in &refs {
        let b = model(&r.model, r.adjoint);
        let s = b.sample(r.wo, r.u_lobe, Vec2::from(r.u));
        let ctx = format!("{} adjoint={} wo={} u=({}, {:?})", r.model, r.adjoint, r.wo, r.u_lobe, r.u);
        if s.delta {
            continue;
        }
        if r.pdf == 0.0 || r.weight == Vec3::ZERO {
            assert!(s.pdf == 0.0 || s.weight == Vec3::ZERO, "{ctx}: Mitsuba's is void, ours {}", s.wi);
            continue;
        }
        valid += 1;
        assert!(close3(s.wi, r.wi, 1e-3, 1e-4), "{ctx}: wi {} vs Mitsuba {}", s.wi, r.wi);
        assert!(close3(s.weight, r.weight, 3e-3, 1e-5), "{ctx}: weight {} vs Mitsuba {}", s.weight, r.weight);
        assert!(close(s.pdf, r.pdf, 3e-3, 1e-6), "{ctx}: pdf {} vs Mitsuba {}", s.pdf, r.pdf);
        assert_eq!(s.eta, r.eta, "{ctx}: eta");
    }
    assert!(valid >= 80, "only {valid} valid smooth samples");
}

/// The divergence `blend.rs` documents: where the chosen child samples a Dirac lobe, Mitsuba's weight
/// is `(p·v + (1−p)·f_o) / (p·P + (1−p)·pdf_o)` (`v`, `P`: the child's weight·probability and
/// discrete probability; `f_o`, `pdf_o`: the other child's value and density there, `p` the choice's
/// probability), which adds a density to a probability. caustic keeps the child's weight, which is
/// unbiased (`white_furnace` below). Both rules are checked against the values: the same direction,
/// Mitsuba's weight reproduced by its formula from caustic's children, and caustic's the child's.
#[test]
fn dirac_samples_diverge_as_documented() {
    let refs = references_in(VALUES).sample;
    let (mut dirac, mut apart) = (0, 0);
    for r in &refs {
        let b = model(&r.model, r.adjoint);
        let s = b.sample(r.wo, r.u_lobe, Vec2::from(r.u));
        if !s.delta {
            continue;
        }
        let ctx = format!("{} adjoint={} wo={} u=({}, {:?})", r.model, r.adjoint, r.wo, r.u_lobe, r.u);
        let (first, second, w) = blend_of(&r.model);
        let mode = if r.adjoint { TransportMode::Importance } else { TransportMode::Radiance };
        let (chosen, other, p) = if r.u_lobe <= w { (second, first, w) } else { (first, second, 1.0 - w) };
        let (chosen, other) = (Model::new(&chosen, r.adjoint).in_mode(mode), Model::new(&other, r.adjoint));
        let u_child = if r.u_lobe <= w { r.u_lobe / w } else { (r.u_lobe - w) / (1.0 - w) };
        let c = chosen.sample(r.wo, u_child, Vec2::from(r.u));
        assert!(close3(s.wi, r.wi, 1e-4, 1e-5) && s.eta == r.eta, "{ctx}: wi {} vs Mitsuba {}", s.wi, r.wi);
        assert!(
            close3(s.weight, c.weight, 1e-6, 0.0),
            "{ctx}: weight {} vs the child's {}",
            s.weight,
            c.weight
        );
        assert!(close(s.pdf, p * c.pdf, 1e-6, 0.0), "{ctx}: pdf {} vs {p}·{}", s.pdf, c.pdf);
        let o = other.eval_pdf(r.wo, c.wi);
        let mitsuba = (c.weight * (p * c.pdf) + o.f * (1.0 - p)) / (p * c.pdf + (1.0 - p) * o.pdf);
        assert!(close3(mitsuba, r.weight, 3e-3, 1e-5), "{ctx}: Mitsuba's {} vs its rule {mitsuba}", r.weight);
        dirac += 1;
        apart += ((s.weight - r.weight).abs().max_element() > 0.01 * r.weight.max_element()) as u32;
    }
    assert!(dirac >= 20 && apart >= 5, "{dirac} Dirac samples, {apart} of them apart from Mitsuba's");
}

/// Blends of smooth and of Dirac children, from above and (transmissive) below, in both modes.
#[test]
fn chi2_of_blends() {
    let ggx = rough(BSDF_ROUGH_CONDUCTOR, 0.2, 0.4, false);
    let glass = rough(BSDF_ROUGH_DIELECTRIC, 0.3, 0.3, false);
    let diffuse = material(BSDF_DIFFUSE);
    let cases = [
        ("diffuse+ggx", diffuse, copper(ggx), 0.3),
        ("principled+glass", principled(0.4), glass, 0.5),
        ("diffuse+mirror", diffuse, copper(material(BSDF_CONDUCTOR)), 0.6),
        ("glass+diffuse", glass, diffuse, 0.9),
    ];
    for (k, (name, a, b, w)) in cases.iter().enumerate() {
        for (j, cos) in [0.8f32, 0.2, -0.5].iter().enumerate() {
            let m = Model::blend(a, b, *w, false);
            if *cos < 0.0 && !m.bsdf.flags().has_transmission() {
                continue;
            }
            let wo = polar(*cos, 0.4);
            for adjoint in [false, true] {
                let m = Model::blend(a, b, *w, adjoint);
                let label = format!("blend {name} wo={wo} adjoint={adjoint}");
                chi2_model(&label, &m, wo, &sphere_grid(), (k * 8 + j * 2 + adjoint as usize) as u32);
            }
        }
    }
}

#[test]
fn reciprocity() {
    let dirs = random_dirs(4000, 5);
    let cases = [
        ("diffuse+ggx", material(BSDF_DIFFUSE), copper(rough(BSDF_ROUGH_CONDUCTOR, 0.2, 0.4, false)), 0.3),
        ("principled+glass", principled(0.4), rough(BSDF_ROUGH_DIELECTRIC, 0.3, 0.3, false), 0.5),
    ];
    for (name, a, b, w) in cases {
        let m = Model::blend(&a, &b, w, false);
        let checked = check_reciprocity(
            name,
            &m,
            &dirs,
            |x, y| close3(x, y, 2e-3, 1e-6),
            |wo, wi| wo.z * wi.z < 0.0 && (wo.z.abs() < 0.05 || wi.z.abs() < 0.05),
        );
        assert!(checked > 100, "{name}: too few non-zero pairs ({checked})");
    }
}

/// White furnace: a white diffuse and a white mirror (a conductor with k = 1, eta = 0), blended half
/// and half, reflect everything: albedo 1 at every angle, which caustic's sampling weights average to.
/// Mitsuba's rule for Dirac samples (`dirac_samples_diverge_as_documented`) would make the mirror's
/// weight `(0.5 + 0.5·cos/π)/(0.5 + 0.5·cos/π) = 1` here but less than 1 for any diffuse below white:
/// the second case, a 0.5 diffuse, must average `0.5·0.5 + 0.5 = 0.75`.
#[test]
fn white_furnace() {
    let mirror = material(BSDF_CONDUCTOR);
    for (k, grey) in [1.0f32, 0.5].iter().enumerate() {
        let diffuse = Material { reflectance: c4(*grey, *grey, *grey), ..material(BSDF_DIFFUSE) };
        let m = Model::blend(&diffuse, &mirror, 0.5, false);
        for cos in [1.0f32, 0.5, 0.1] {
            let wo = polar(cos, 0.3);
            // The mirror's half is a Dirac lobe, outside the quadrature.
            let a = albedo(&m, wo, &Grid::coarse(Vec3::Z)) + Vec3::splat(0.5);
            let expected = 0.5 * grey + 0.5;
            assert!(
                (a - Vec3::splat(expected)).abs().max_element() < 2e-3,
                "grey {grey} cos {cos}: albedo {a}"
            );
            check_energy("diffuse+mirror", &m, wo, a, 0.0, 50_000, Sampler::new(k as u32, 26, 1));
        }
    }
}

/// A blend of each model (`every_model`: every kind, Dirac ones too) with a smooth one, either way
/// round: smooth samples weigh `eval / pdf` of the blend at their direction with the blend's `pdf`,
/// Dirac ones keep a finite weight and a scaled probability, `eval_pdf` is `eval` and `pdf`, and the
/// flags are the union of the children's.
#[test]
fn every_model_blends_consistently() {
    let smooth = copper(rough(BSDF_ROUGH_CONDUCTOR, 0.3, 0.2, false));
    let wos = random_dirs(12, 21);
    let mut rng = Sampler::new(7, 7, 7);
    for (name, m) in every_model() {
        for (first, second, w) in [(m, smooth, 0.4f32), (smooth, m, 0.7)] {
            for adjoint in [false, true] {
                let b = Model::blend(&first, &second, w, adjoint);
                let (fa, fb) =
                    (Model::new(&first, adjoint).bsdf.flags(), Model::new(&second, adjoint).bsdf.flags());
                assert_eq!(b.bsdf.flags().0, fa.0 | fb.0, "{name}: flags");
                let (mut smooth_samples, mut dirac) = (0, 0);
                for wo in &wos {
                    for _ in 0..20 {
                        let s = b.sample(*wo, rng.next_1d(), rng.next_2d());
                        if s.pdf.is_nan() || s.pdf <= 0.0 {
                            continue;
                        }
                        assert!(
                            s.weight.is_finite() && s.weight.min_element() >= 0.0,
                            "{name}: weight {}",
                            s.weight
                        );
                        if s.delta {
                            dirac += 1;
                            continue;
                        }
                        let (f, pdf) = (b.eval(*wo, s.wi), b.pdf(*wo, s.wi));
                        let e = b.eval_pdf(*wo, s.wi);
                        assert!(
                            close3(e.f, f, 1e-6, 0.0) && close(e.pdf, pdf, 1e-6, 0.0),
                            "{name}: eval_pdf"
                        );
                        let ctx = format!("{name} w={w} wo={wo} wi={}", s.wi);
                        assert!(close(s.pdf, pdf, 2e-3, 1e-6), "{ctx}: sample pdf {} vs pdf {pdf}", s.pdf);
                        assert!(
                            close3(s.weight, f / pdf, 2e-3, 1e-6),
                            "{ctx}: weight {} vs {}",
                            s.weight,
                            f / pdf
                        );
                        smooth_samples += 1;
                    }
                }
                assert!(
                    smooth_samples + dirac > 50,
                    "{name}: {smooth_samples} smooth and {dirac} Dirac samples"
                );
            }
        }
    }
}

/// A tree of blends as the host writes it: `blend(w1, blend(w2, a, b), c)` and
/// `blend(w1, blend(w2, a, b), blend(w3, c, d))` (material list `a, b, c, d`, then the inner blends).
fn trees(a: Material, b: Material, c: Material, d: Material) -> Vec<(&'static str, Model, Vec<f32>)> {
    let (w1, w2, w3) = (0.35f32, 0.6f32, 0.25f32);
    let mut list = vec![a, b, c, d, blend::record(0, 1, w2, NONE), blend::record(2, 3, w3, NONE)];
    list.push(blend::record(4, 2, w1, NONE));
    let three = Model::tree(&blend::record(4, 2, w1, NONE), &list, false);
    let four = Model::tree(&blend::record(4, 5, w1, NONE), &list, false);
    // Each leaf's weight in the order a, b, c, d.
    let three_weights = vec![(1.0 - w1) * (1.0 - w2), (1.0 - w1) * w2, w1, 0.0];
    let four_weights = vec![(1.0 - w1) * (1.0 - w2), (1.0 - w1) * w2, w1 * (1.0 - w3), w1 * w3];
    vec![("three leaves", three, three_weights), ("four leaves", four, four_weights)]
}

/// A tree of blends scatters as its leaves' weighted sum (the weights the products of the blend
/// weights down the tree): eval, pdf and flags against the leaves' own.
#[test]
fn nested_blends_mix_their_leaves() {
    let leaves = [
        Material { reflectance: c4(0.8, 0.2, 0.1), ..material(BSDF_DIFFUSE) },
        copper(rough(BSDF_ROUGH_CONDUCTOR, 0.3, 0.3, false)),
        rough(BSDF_ROUGH_DIELECTRIC, 0.2, 0.2, false),
        principled(0.0),
    ];
    let dirs = random_dirs(300, 31);
    for (name, tree, weights) in trees(leaves[0], leaves[1], leaves[2], leaves[3]) {
        let models: Vec<Model> = leaves.iter().map(|m| Model::new(m, false)).collect();
        let used = weights.iter().zip(&models).filter(|(w, _)| **w > 0.0);
        let flags = used.fold(0, |f, (_, m)| f | m.bsdf.flags().0);
        assert_eq!(tree.bsdf.flags().0, flags, "{name}: flags");
        let mut nonzero = 0;
        for (k, wo) in dirs.iter().enumerate() {
            let wi = dirs[(k * 7 + 3) % dirs.len()];
            let (mut f, mut pdf) = (Vec3::ZERO, 0.0);
            for (w, m) in weights.iter().zip(&models) {
                f += m.eval(*wo, wi) * *w;
                pdf += m.pdf(*wo, wi) * *w;
            }
            let ctx = format!("{name} wo={wo} wi={wi}");
            assert!(close3(tree.eval(*wo, wi), f, 1e-5, 1e-7), "{ctx}: eval {} vs {f}", tree.eval(*wo, wi));
            assert!(close(tree.pdf(*wo, wi), pdf, 1e-5, 1e-7), "{ctx}: pdf {} vs {pdf}", tree.pdf(*wo, wi));
            nonzero += (pdf > 0.0) as u32;
        }
        assert!(nonzero > 50, "{name}: only {nonzero} non-zero pairs");
    }
}

/// A tree picks the leaf Mitsuba's choices down it pick: at each blend `bsdf_1` where `u_lobe ≤ w`,
/// `u_lobe` rescaled into the child. The leaf's own sample with the rescaled `u_lobe` has the tree's
/// direction (the weights of smooth samples are the mixture's: `every_model_blends_consistently`).
#[test]
fn nested_blends_choose_as_mitsuba_descends() {
    let leaves = [
        Material { reflectance: c4(0.8, 0.2, 0.1), ..material(BSDF_DIFFUSE) },
        copper(rough(BSDF_ROUGH_CONDUCTOR, 0.3, 0.3, false)),
        copper(rough(BSDF_ROUGH_CONDUCTOR, 0.05, 0.4, false)),
        rough(BSDF_ROUGH_PLASTIC, 0.2, 0.2, false),
    ];
    let (w1, w2, w3) = (0.35f32, 0.6f32, 0.25f32);
    let mut rng = Sampler::new(3, 5, 8);
    for (name, tree, _) in trees(leaves[0], leaves[1], leaves[2], leaves[3]) {
        let four = name == "four leaves";
        let mut checked = 0;
        for _ in 0..2000 {
            let (wo, ul, u) =
                (polar(0.2 + 0.8 * rng.next_1d(), 6.0 * rng.next_1d()), rng.next_1d(), rng.next_2d());
            // Mitsuba's descent: (leaf, u_lobe for it).
            let (leaf, ul_leaf) = if ul <= w1 {
                let v = ul / w1;
                if !four {
                    (2, v)
                } else if v <= w3 {
                    (3, v / w3)
                } else {
                    (2, (v - w3) / (1.0 - w3))
                }
            } else {
                let v = (ul - w1) / (1.0 - w1);
                if v <= w2 {
                    (1, v / w2)
                } else {
                    (0, (v - w2) / (1.0 - w2))
                }
            };
            let s = tree.sample(wo, ul, u);
            let own = Model::new(&leaves[leaf], false).sample(wo, ul_leaf.min(0.99999994), u);
            if own.pdf.is_nan() || s.pdf.is_nan() || own.pdf <= 0.0 || s.pdf <= 0.0 {
                continue;
            }
            assert!(
                close3(s.wi, own.wi, 1e-4, 1e-5),
                "{name} u_lobe {ul}: wi {} vs leaf {leaf}'s {}",
                s.wi,
                own.wi
            );
            checked += 1;
        }
        assert!(checked > 1500, "{name}: {checked} samples checked");
    }
}

/// χ² of the trees' sampling against their pdf, in both transport modes, from above and below.
#[test]
fn chi2_of_nested_blends() {
    let leaves = [
        material(BSDF_DIFFUSE),
        copper(rough(BSDF_ROUGH_CONDUCTOR, 0.2, 0.4, false)),
        rough(BSDF_ROUGH_DIELECTRIC, 0.3, 0.3, false),
        principled(0.4),
    ];
    for (k, (name, tree, _)) in trees(leaves[0], leaves[1], leaves[2], leaves[3]).into_iter().enumerate() {
        for (j, cos) in [0.7f32, -0.4].iter().enumerate() {
            for adjoint in [false, true] {
                let m =
                    tree.in_mode(if adjoint { TransportMode::Importance } else { TransportMode::Radiance });
                let wo = polar(*cos, 0.9);
                let label = format!("{name} wo={wo} adjoint={adjoint}");
                chi2_model(&label, &m, wo, &sphere_grid(), (100 + k * 8 + j * 2 + adjoint as usize) as u32);
            }
        }
    }
}
