//! Mitsuba conformance: every scene listed in `../shared/scenes/mitsuba/SCENES.txt` is loaded unmodified,
//! rendered, and compared with Mitsuba 3.9.1's reference by the per-pixel z-test and the mean-luminance
//! z-score of `caustic compare`. CI renders the central quarter of each image (the same pixels of the
//! reference) at a fixed sample budget; all scenes on the CPU, a representative subset on the GPU
//! backend (lavapipe in CI). Set CAUSTIC_CONFORMANCE_BUDGET (samples per scene) for longer runs and
//! CAUSTIC_CONFORMANCE_ONLY=name,name to select scenes.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::BackendChoice;
use caustic::output::compare::compare;
use caustic::output::film::Film;
use caustic::scene::Crop;
use caustic_tests::*;
use std::time::Instant;

/// One listed scene with its reference's sample count.
struct Listed {
    name: String,
    file: String,
    reference_spp: u32,
}

fn listed_scenes() -> Vec<Listed> {
    let text =
        std::fs::read_to_string(shared_dir().join("refs/mitsuba/refs.json")).expect("refs.json readable");
    let json: serde_json::Value = serde_json::from_str(&text).expect("refs.json is JSON");
    let listed = std::fs::read_to_string(mitsuba_scene("SCENES.txt")).expect("SCENES.txt readable");
    let scenes = json["scenes"].as_object().expect("refs.json has scenes");
    let wanted: Option<Vec<String>> =
        std::env::var("CAUSTIC_CONFORMANCE_ONLY").ok().map(|s| s.split(',').map(str::to_string).collect());
    listed
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(|file| {
            let (name, entry) = scenes
                .iter()
                .find(|(_, v)| v["file"] == file)
                .unwrap_or_else(|| panic!("{file} has no reference in refs.json"));
            Listed {
                name: name.clone(),
                file: file.to_string(),
                reference_spp: entry["spp"].as_u64().unwrap_or(2048) as u32,
            }
        })
        .filter(|s| wanted.as_ref().is_none_or(|w| w.contains(&s.name)))
        .collect()
}

struct Outcome {
    name: String,
    spp: u32,
    pixels: u32,
    seconds: f64,
    rmse: f64,
    pass: f64,
    z: f64,
}

impl Outcome {
    fn ok(&self) -> bool {
        self.pass >= 0.99 && self.z.abs() < 4.0
    }
}

/// Renders the central `fraction` × `fraction` window of a scene with about `budget` samples.
fn check(scene: &Listed, choice: BackendChoice, fraction: f32, budget: u64) -> Outcome {
    check_edited(scene, choice, fraction, budget, |_| {})
}

/// `check`, with the loaded scene changed by `edit` first (to a variant with the same expectation).
fn check_edited(
    scene: &Listed,
    choice: BackendChoice,
    fraction: f32,
    budget: u64,
    edit: impl Fn(&mut caustic::scene::Scene),
) -> Outcome {
    // Like Mitsuba's own reference renders, pass the sample count (some scenes use $spp before their
    // includes give it a default); the render below sets the budget's count anyway.
    let mut s = caustic::load::load_scene(&mitsuba_scene(&scene.file), &defines(&[("spp", "16")]))
        .unwrap_or_else(|e| panic!("{} does not load: {e:#}", scene.name));
    let (w, h) = (s.sensor.width, s.sensor.height);
    let (cw, ch) = (((w as f32 * fraction) as u32).max(1), ((h as f32 * fraction) as u32).max(1));
    let crop = Crop { x: (w - cw) / 2, y: (h - ch) / 2, width: cw, height: ch };
    edit(&mut s);
    let pixels = cw * ch;
    let spp = (budget / pixels as u64).clamp(4, 4096) as u32;
    let start = Instant::now();
    let film = render_window(&s, crop, choice, spp, 11);
    let seconds = start.elapsed().as_secs_f64();
    let reference = Film::load_exr(&mitsuba_reference(&scene.name))
        .expect("reference loads")
        .crop(crop.x, crop.y, cw, ch);
    let c = compare(&film, &reference, spp as f64 / scene.reference_spp as f64).expect("same size");
    Outcome {
        name: scene.name.clone(),
        spp,
        pixels,
        seconds,
        rmse: c.rmse,
        pass: c.pass_fraction.unwrap_or(0.0),
        z: c.luminance_z.unwrap_or(f64::INFINITY),
    }
}

fn budget(default: u64) -> u64 {
    std::env::var("CAUSTIC_CONFORMANCE_BUDGET").ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn run(label: &str, scenes: &[Listed], choice: BackendChoice, fraction: f32, budget: u64) {
    let outcomes: Vec<Outcome> = scenes.iter().map(|s| check(s, choice, fraction, budget)).collect();
    println!(
        "\n{label}: central {:.0}% of each image, ~{budget} samples per scene",
        fraction * fraction * 100.0
    );
    println!(
        "{:<32} {:>6} {:>8} {:>8} {:>9} {:>7} {:>7}  result",
        "scene", "spp", "pixels", "seconds", "RMSE", "pass", "lum z"
    );
    for o in &outcomes {
        println!(
            "{:<32} {:>6} {:>8} {:>8.2} {:>9.5} {:>7.4} {:>+7.2}  {}",
            o.name,
            o.spp,
            o.pixels,
            o.seconds,
            o.rmse,
            o.pass,
            o.z,
            if o.ok() { "ok" } else { "FAIL" }
        );
    }
    let failed: Vec<&str> = outcomes.iter().filter(|o| !o.ok()).map(|o| o.name.as_str()).collect();
    assert!(
        failed.is_empty(),
        "{label}: {} of {} scenes differ from Mitsuba: {}",
        failed.len(),
        outcomes.len(),
        failed.join(", ")
    );
}

#[test]
fn every_listed_scene_matches_mitsuba_on_the_cpu() {
    let scenes = listed_scenes();
    run("CPU", &scenes, BackendChoice::Cpu, 0.5, budget(3_000_000));
}

/// A subset covering every feature family: meshes and area lights, envmap + microfacets +
/// checkerboard, smooth dielectrics, bitmap textures, spot + constant emitters, thin lens, conductors,
/// analytic sphere lights.
const GPU_SUBSET: [&str; 8] = [
    "cbox",
    "bsdf_roughplastic_ggx",
    "bsdf_dielectric_glass",
    "bsdf_diffuse_textured",
    "emitter_spot_no_texture",
    "sensor_thinlens",
    "bsdf_conductor_gold",
    "shape_sphere_light_analytic",
];

#[test]
fn a_representative_subset_matches_mitsuba_on_the_gpu() {
    let scenes: Vec<Listed> =
        listed_scenes().into_iter().filter(|s| GPU_SUBSET.contains(&s.name.as_str())).collect();
    run("GPU", &scenes, BackendChoice::Gpu, 0.25, budget(400_000));
}

/// Mitsuba's `direct` weights `emitter_samples` light samples against `bsdf_samples` BSDF samples;
/// the counts change the variance, never the expectation, so every split must match the reference
/// rendered with one of each.
#[test]
fn direct_sample_counts_keep_the_expectation() {
    use caustic::scene::IntegratorKind;
    let Some(scene) = listed_scenes().into_iter().find(|s| s.name == "integrator_direct_both") else {
        return;
    };
    let outcomes: Vec<(u32, u32, Outcome)> = [(4u32, 1u32), (1, 3), (3, 0)]
        .into_iter()
        .map(|(emitter_samples, bsdf_samples)| {
            let o = check_edited(&scene, BackendChoice::Cpu, 0.25, budget(1_500_000), |s| {
                assert!(matches!(s.integrator.kind, IntegratorKind::Direct { .. }), "the scene uses direct");
                s.integrator.kind = IntegratorKind::Direct { emitter_samples, bsdf_samples };
            });
            (emitter_samples, bsdf_samples, o)
        })
        .collect();
    for (e, b, o) in &outcomes {
        println!(
            "direct emitter_samples={e} bsdf_samples={b}: spp {} RMSE {:.5} pass {:.4} lum z {:+.2}",
            o.spp, o.rmse, o.pass, o.z
        );
    }
    assert!(outcomes.iter().all(|(_, _, o)| o.ok()), "a sample split changed the direct integrator's image");
}
