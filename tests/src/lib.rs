//! Helpers shared by the integration tests: where the reference data live, and rendering a scene to
//! a film on a chosen backend.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::{self, BackendChoice};
use caustic::output::film::Film;
use caustic::prepare::buffers;
use caustic::render::passes;
use caustic::scene::Scene;
use std::path::PathBuf;

pub mod corner;
pub mod replicas;

/// `../shared` beside the repository (override with CAUSTIC_SHARED), whether it is there or not.
/// (`CARGO_MANIFEST_DIR` is this crate's folder, one below the repository root.)
fn shared_path() -> PathBuf {
    match std::env::var_os("CAUSTIC_SHARED") {
        Some(p) => PathBuf::from(p),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared"),
    }
}

/// xorshift64*: a deterministic stream per seed, for tests that draw their own inputs (the loader
/// fuzzer's mutations, the wide BVH's rays).
pub struct Xorshift(pub u64);

impl Xorshift {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `0..n` (0 for `n == 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// Uniform in [0, 1), from the top 24 bits.
    pub fn uniform(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The shared data, for tests that need them: panics if the references are absent.
pub fn shared_dir() -> PathBuf {
    let dir = shared_path();
    assert!(
        dir.join("refs/mitsuba").is_dir(),
        "reference data not found at {} (set CAUSTIC_SHARED)",
        dir.display()
    );
    dir
}

/// The shared data, for tests that skip without them: None, with a notice, if the Mitsuba scenes
/// are absent.
pub fn shared_dir_if_present() -> Option<PathBuf> {
    let dir = shared_path();
    if dir.join("scenes/mitsuba").is_dir() {
        Some(dir)
    } else {
        eprintln!("notice: {} not found (set CAUSTIC_SHARED); test skipped", dir.display());
        None
    }
}

pub fn mitsuba_scene(relative: &str) -> PathBuf {
    shared_dir().join("scenes/mitsuba").join(relative)
}

pub fn mitsuba_reference(name: &str) -> PathBuf {
    shared_dir().join("refs/mitsuba").join(format!("{name}.exr"))
}

pub fn defines(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
}

/// Loads a Mitsuba scene given as text (written to a temporary `scene.xml` in a folder named after
/// `tag`, then removed) with `defines` (`-D`); the loader's result, errors naming that file.
pub fn try_load_xml(xml: &str, tag: &str, defines_: &[(&str, &str)]) -> anyhow::Result<Scene> {
    load_xml_file(xml, tag, |path| caustic::load::load_scene(path, &defines(defines_)))
}

/// `try_load_xml` under `--strict` (without defines): a substitution is an error.
pub fn try_load_xml_strict(xml: &str, tag: &str) -> anyhow::Result<Scene> {
    load_xml_file(xml, tag, |path| {
        caustic::load::load_scene_with(path, &[], caustic::load::LoadOptions { strict: true })
    })
}

/// Writes `xml` to a temporary `scene.xml` (in a folder named after `tag`), loads it with `load`,
/// removes it.
fn load_xml_file(
    xml: &str,
    tag: &str,
    load: impl FnOnce(&std::path::Path) -> anyhow::Result<Scene>,
) -> anyhow::Result<Scene> {
    let dir = std::env::temp_dir().join(format!("caustic-test-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let path = dir.join("scene.xml");
    std::fs::write(&path, xml).expect("scene written");
    let scene = load(&path);
    std::fs::remove_dir_all(&dir).ok();
    scene
}

/// `try_load_xml` without defines; panics with the error if the scene does not load.
pub fn load_xml(xml: &str, tag: &str) -> Scene {
    try_load_xml(xml, tag, &[]).unwrap_or_else(|e| panic!("{tag}: the scene does not load: {e:#}"))
}

/// Renders `scene` with `spp` samples and `seed` on `choice`; panics with the error if it fails.
pub fn render_scene(scene: &Scene, choice: BackendChoice, spp: u32, seed: u32) -> Film {
    render_buffers(&buffers::build(scene).expect("scene builds"), choice, spp, seed)
}

/// `render_scene` for scene buffers built (and perhaps altered) by the caller.
pub fn render_buffers(buffers: &buffers::SceneBuffers, choice: BackendChoice, spp: u32, seed: u32) -> Film {
    let buffers = buffers.clone();
    let mut backend = backend::create(choice, &buffers)
        .expect("backend starts (for the GPU: is a Vulkan driver such as lavapipe installed?)");
    let (film, stats) =
        passes::render(backend.as_mut(), &buffers, spp, seed, |_| {}).expect("render succeeds");
    eprintln!("rendered on {} in {:.2} s", backend.describe(), stats.seconds);
    assert!(film.rgb.iter().flatten().all(|c| c.is_finite()), "non-finite pixel");
    film
}

/// Renders the window `crop` of `scene` (whose own crop it replaces) as a part of the whole image:
/// the window with a margin of the filter's radius around it (within the image) is rendered and cut
/// back to `crop`, so that its edge pixels take the samples beyond its edge that they take in the
/// whole image (a crop's own edge stops them, in caustic's film as in Mitsuba's) and compare exactly
/// with a reference of the whole image cut to `crop`.
pub fn render_window(
    scene: &Scene,
    crop: caustic::scene::Crop,
    choice: BackendChoice,
    spp: u32,
    seed: u32,
) -> Film {
    let (w, h) = (scene.sensor.width, scene.sensor.height);
    let margin = scene.sensor.filter.radius().ceil() as u32;
    let (x0, y0) = (crop.x.saturating_sub(margin), crop.y.saturating_sub(margin));
    let (x1, y1) = ((crop.x + crop.width + margin).min(w), (crop.y + crop.height + margin).min(h));
    let mut s = scene.clone();
    s.sensor.crop = Some(caustic::scene::Crop { x: x0, y: y0, width: x1 - x0, height: y1 - y0 });
    render_scene(&s, choice, spp, seed).crop(crop.x - x0, crop.y - y0, crop.width, crop.height)
}

/// The largest per-channel |difference| between two images of one size (GPU against CPU, one image
/// against another of the same seed).
pub fn max_abs_difference(a: &Film, b: &Film) -> f32 {
    a.rgb
        .iter()
        .zip(&b.rgb)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
        .fold(0.0f32, f32::max)
}

/// How many pixels of `a` differ from `b`'s in some channel by more than `relative · (1 + |a|)`.
pub fn pixels_differing(a: &Film, b: &Film, relative: f32) -> usize {
    a.rgb
        .iter()
        .zip(&b.rgb)
        .filter(|(p, q)| (0..3).any(|c| (p[c] - q[c]).abs() > relative * (1.0 + p[c].abs())))
        .count()
}

/// A file of `tests/data` (small scenes and the Mitsuba references their scripts write).
pub fn test_data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data").join(name)
}

/// Asserts that no case of a table checked against Mitsuba 3.9.1 failed: `failures` lists each
/// failing case's message, of `total` cases.
pub fn assert_cases_match_mitsuba(failures: &[String], total: usize) {
    assert!(
        failures.is_empty(),
        "{} of {total} cases differ from Mitsuba 3.9.1:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Asserts that an image agrees with its reference, from `against_mitsuba_reference`'s (fraction of
/// pixels passing the z-test, mean-luminance z-score): at least 99% of the pixels and |z| < 4.
pub fn assert_agrees_with_reference((pass, z): (f64, f64), what: &str) {
    assert!(pass >= 0.99, "{what}: only {:.2}% of pixels agree with Mitsuba", pass * 100.0);
    assert!(z.abs() < 4.0, "{what}: mean luminance differs from Mitsuba by {z:.2} standard errors");
}

/// The negative control's side of `assert_agrees_with_reference`: a change the comparison must catch
/// (fewer than 99% of the pixels passing, or |z| ≥ 4); `what` names the change.
pub fn assert_disagrees_with_reference((pass, z): (f64, f64), what: &str) {
    assert!(pass < 0.99 || z.abs() >= 4.0, "{what} went unnoticed (pass {pass:.4}, z {z:+.2})");
}

/// Renders `tests/data/{scene}` with `defines` on `choice` and compares it with the Mitsuba reference
/// `tests/data/{reference}` (rendered at `reference_spp`); prints `label` with the figures and returns
/// (fraction of pixels passing the z-test, mean-luminance z-score).
#[allow(clippy::too_many_arguments)]
pub fn against_mitsuba_reference(
    scene: &str,
    defines_: &[(&str, &str)],
    reference: &str,
    reference_spp: f64,
    choice: BackendChoice,
    spp: u32,
    seed: u32,
    label: &str,
) -> (f64, f64) {
    let loaded = caustic::load::load_scene(&test_data(scene), &defines(defines_)).expect("loads");
    scene_against_reference(&loaded, reference, reference_spp, choice, spp, seed, label)
}

/// `against_mitsuba_reference` for a scene already loaded (and perhaps changed by the test).
pub fn scene_against_reference(
    loaded: &Scene,
    reference: &str,
    reference_spp: f64,
    choice: BackendChoice,
    spp: u32,
    seed: u32,
    label: &str,
) -> (f64, f64) {
    let film = render_scene(loaded, choice, spp, seed);
    let reference = Film::load_exr(&test_data(reference)).expect("reference loads");
    let c =
        caustic::output::compare::compare(&film, &reference, spp as f64 / reference_spp).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!(
        "{label}, {choice:?} {spp} spp: RMSE {:.5}, luminance ratio {:.4}, z {z:+.2}, pass {pass:.4}",
        c.rmse, c.luminance_ratio
    );
    (pass, z)
}
