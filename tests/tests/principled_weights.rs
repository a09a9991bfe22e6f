//! Every weight of Mitsuba's `principled` and `principledthin` as a texture: those beyond the
//! record's own slots are read through `caustic_kernel::bsdf::textured_weights`. Whole images
//! against Mitsuba 3.9.1's render on both backends; the negative control is the substitution caustic
//! made before, each such texture replaced by its mean.
use caustic::backend::BackendChoice;
use caustic_kernel::bsdf::textured_weights::{SLOTS, SLOT_ETA};
use caustic_kernel::layout::*;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 32768.0;

fn check(scene: &caustic::scene::Scene, choice: BackendChoice, spp: u32, what: &str) -> (f64, f64) {
    let label = format!("textured principled weights, {what}");
    scene_against_reference(scene, "principled_weights.exr", REFERENCE_SPP, choice, spp, 5, &label)
}

#[test]
fn textured_weights_match_mitsuba() {
    let scene = caustic::load::load_scene(&test_data("principled_weights.xml"), &[]).expect("loads");
    assert!(scene.warnings.is_empty(), "nothing is substituted: {:?}", scene.warnings);
    // Both records list their textured weights: the principled sphere seven, the thin sheet six,
    // `eta` among them.
    let listed = |kind: u32| {
        let m = scene.materials.iter().find(|m| m.kind == kind).expect("the model's record");
        scene.weight_tables[m.table as usize]
    };
    let count = |t: [f32; SLOTS]| t.iter().filter(|&&i| i >= 0.0).count();
    assert_eq!(count(listed(BSDF_PRINCIPLED)), 7);
    let thin = listed(BSDF_PRINCIPLED_THIN);
    assert!(count(thin) == 6 && thin[SLOT_ETA] >= 0.0, "{thin:?}");

    // Lavapipe is several times slower than the CPU backend: fewer samples there.
    for (choice, spp) in [(BackendChoice::Cpu, 1024), (BackendChoice::Gpu, 256)] {
        assert_agrees_with_reference(check(&scene, choice, spp, "textures"), &format!("{choice:?}"));
    }
    // Negative control: each texture's mean instead of the texture, as before.
    let mut means = scene.clone();
    for m in &mut means.materials {
        if matches!(m.kind, BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN) {
            m.table = NONE;
        }
    }
    let (pass, z) = check(&means, BackendChoice::Cpu, 1024, "the textures' means");
    assert_disagrees_with_reference((pass, z), "the means");
}
