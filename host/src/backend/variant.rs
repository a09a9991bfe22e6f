//! Which build of the camera pipeline runs: its path loop (`path_loop`) and its workgroup size,
//! chosen per scene by timing the candidates on the render's own first passes.
//!
//! Why the workgroup size: NVIDIA's Vulkan compiler budgets registers by it. The same pruned kernel
//! gets 128 registers per thread (162–168 with microfacets) in 8×8 workgroups, 128 in 16×16 and 32×16,
//! 96 in 32×20, 80 in 32×24 and 64 in 32×32 (`caustic kernel-stats`), trading spills for occupancy,
//! and the warps take other pixels (8×4 against 32×1). No size is best everywhere (H200,
//! 2026-11-27, BENCHMARKS.md, "Registers and workgroup sizes"): `integrator_direct_both` ran 1.19×
//! faster in 32×16 workgroups, glass 1.08× in 32×24, rough plastic 1.13× in 32×32, while the
//! Cornell box lost 22% in 32×24 and the sphere light 34% in 32×32. So, as for the path loop, the
//! backend builds the candidates and measures (the first at once, the others when the trial begins:
//! `backend::gpu`).
//!
//! The trial: the first candidate alone until its long passes (`LONG_PASS`) add up to `FIRST_ALONE`
//! (a short render cannot pay for a trial), then whole passes in turn, each to the candidate measured
//! least so far, until each has run `DECIDE_AFTER` in long passes; the fastest per sample wins.
//! Whole passes, not shares of one: a share is a short dispatch, and a dispatch waits for its
//! longest path, which weighs the candidates differently. On the H100 (2026-11-28), the diamond's
//! regenerating loop in 8×8 measured 56 ms per sample per pixel in shares of three samples and 41
//! in whole renders, its plain loop 63 against 58; glass's regenerating loop in 32×24 7.39 against
//! 6.86 and its plain loop in 8×8 7.28 against 7.06, so the shares chose plain loops for glass,
//! 3–4% slower than the best.
//! Every candidate computes the same image to the bit (the loops and the sizes only change which
//! thread runs which sample when), so the trial changes the speed alone. The choice is kept on disk
//! (`Decisions`) for the next render of the same scene setup on the same adapter, which then builds
//! that pipeline alone; a render that ends before the trial does keeps its measurements there, and
//! the next one resumes them.
use super::path_loop::{self, PathLoop, Request};
use anyhow::{bail, Result};
use caustic_kernel::layout::TILE;
use std::path::PathBuf;
use std::time::Duration;

/// One build of the camera pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    pub path_loop: PathLoop,
    /// Width and height of a workgroup, in pixels.
    pub workgroup: [u32; 2],
}

/// The kernel's own workgroup (`entry.rs`).
pub const DEFAULT_WORKGROUP: [u32; 2] = [TILE, TILE];

/// The sizes a hardware adapter tries unless `CAUSTIC_WORKGROUP` says otherwise.
pub const TRIED_WORKGROUPS: [[u32; 2]; 3] = [DEFAULT_WORKGROUP, [32, 16], [32, 24]];

/// Whether the candidates are the backend's own (neither `CAUSTIC_PATH_LOOP` nor `CAUSTIC_WORKGROUP`
/// set): only then does a kept decision replace the trial (`measure` asks for one).
pub fn unrequested() -> bool {
    std::env::var_os("CAUSTIC_PATH_LOOP").is_none() && std::env::var_os("CAUSTIC_WORKGROUP").is_none()
}

/// `CAUSTIC_WORKGROUP`: unset (the backend's choice), or sizes `WxH[,WxH…]` to try (one: that size
/// alone), each at most 1024 invocations.
pub fn requested_workgroups() -> Result<Option<Vec<[u32; 2]>>> {
    match std::env::var("CAUSTIC_WORKGROUP") {
        Ok(text) => parse_workgroups(&text).map(Some),
        Err(_) => Ok(None),
    }
}

/// Sizes `WxH[,WxH…]`, each of at most 1024 invocations.
fn parse_workgroups(text: &str) -> Result<Vec<[u32; 2]>> {
    let parse = |s: &str| -> Option<[u32; 2]> {
        let (w, h) = s.trim().split_once('x')?;
        let size = [w.parse().ok()?, h.parse().ok()?];
        (size[0] > 0 && size[1] > 0 && size[0] * size[1] <= 1024).then_some(size)
    };
    match text.split(',').map(parse).collect::<Option<Vec<_>>>() {
        Some(sizes) if !sizes.is_empty() => Ok(sizes),
        _ => bail!("CAUSTIC_WORKGROUP must be sizes WxH (W·H ≤ 1024), comma-separated, not {text:?}"),
    }
}

/// The camera pipelines to build: every path loop the request and the integrator allow (both for the
/// path tracer on a hardware adapter), times every workgroup size (`TRIED_WORKGROUPS` there). A
/// software adapter (the tests' lavapipe) builds the regenerating loop in the kernel's own size alone:
/// one compile instead of six. The first candidate is the plain loop at the kernel's size.
pub fn candidates(path_tracer: bool, software: bool) -> Result<Vec<Variant>> {
    let loops: Vec<PathLoop> = match path_loop::requested()? {
        Request::Fixed(choice) => vec![choice],
        Request::Measure if path_tracer => PathLoop::BOTH.to_vec(),
        Request::Default if path_tracer && !software => PathLoop::BOTH.to_vec(),
        _ => vec![PathLoop::Regenerate],
    };
    let sizes = match requested_workgroups()? {
        Some(sizes) => sizes,
        None if software => vec![DEFAULT_WORKGROUP],
        None => TRIED_WORKGROUPS.to_vec(),
    };
    Ok(sizes
        .iter()
        .flat_map(|&workgroup| loops.iter().map(move |&path_loop| Variant { path_loop, workgroup }))
        .collect())
}

/// The user's cache directory: `$XDG_CACHE_HOME` where absolute, else `~/.cache`.
pub(crate) fn cache_base() -> Option<PathBuf> {
    std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .filter(|p| p.is_absolute())
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache")))
}

/// Trial outcomes kept between renders: one small file per setup key (`$XDG_CACHE_HOME/caustic/variants`,
/// else `~/.cache/caustic/variants`), naming the loop and the size. A missing or unreadable one only
/// means the trial runs again.
pub struct Decisions {
    pub dir: Option<PathBuf>,
}

impl Decisions {
    pub fn in_cache() -> Self {
        Decisions { dir: cache_base().map(|b| b.join("caustic").join("variants")) }
    }

    /// The key of a setup: the kernel, the scene (`scene_fingerprint`), the adapter and the
    /// candidates (another set, another trial).
    pub fn key(kernel: &[u32], scene: u64, adapter: &str, candidates: &[Variant]) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::hash::DefaultHasher::new();
        (kernel, scene, adapter, format!("{candidates:?}")).hash(&mut h);
        h.finish()
    }

    pub fn load(&self, key: u64) -> Option<Variant> {
        let text = self.read(key, "txt")?;
        let (kind, size) = text.trim().split_once(' ')?;
        let path_loop = PathLoop::named(kind)?;
        let (w, h) = size.split_once('x')?;
        let workgroup: [u32; 2] = [w.parse().ok()?, h.parse().ok()?];
        (workgroup[0] > 0 && workgroup[1] > 0 && workgroup[0] * workgroup[1] <= 1024)
            .then_some(Variant { path_loop, workgroup })
    }

    pub fn store(&self, key: u64, v: Variant) {
        self.write(key, "txt", &format!("{} {}x{}\n", v.path_loop.name(), v.workgroup[0], v.workgroup[1]));
        if let Some(path) = self.path(key, "trial") {
            let _ = std::fs::remove_file(path);
        }
    }

    /// The measurements of an undecided trial of `count` candidates that earlier renders of this
    /// setup ran (`store_partial`): renders too short to finish a trial (`integrator_direct_both`'s
    /// 256 spp take 0.1 s on the H100) add up to one.
    pub fn load_partial(&self, key: u64, count: usize) -> Option<Trial> {
        Trial::from_text(&self.read(key, "trial")?, count)
    }

    pub fn store_partial(&self, key: u64, trial: &Trial) {
        self.write(key, "trial", &trial.to_text());
    }

    /// Setup `key`'s file of kind `extension` (`txt`: the choice; `trial`: an unfinished trial).
    fn path(&self, key: u64, extension: &str) -> Option<PathBuf> {
        Some(self.dir.as_ref()?.join(format!("{key:016x}.{extension}")))
    }

    fn read(&self, key: u64, extension: &str) -> Option<String> {
        std::fs::read_to_string(self.path(key, extension)?).ok()
    }

    fn write(&self, key: u64, extension: &str, text: &str) {
        let (Some(dir), Some(path)) = (&self.dir, self.path(key, extension)) else { return };
        if std::fs::create_dir_all(dir).is_ok() {
            let _ = std::fs::write(path, text);
        }
    }
}

/// What tells one scene setup from another for a kept choice: its feature mask, its settings (the
/// frame parameters, image size and camera included, less what changes from pass to pass and the
/// seed), its materials and lights, and the size and bounds of its geometry. Two scenes that share a
/// feature mask and an image size (the shared set's diffuse scenes, say) keep a choice each: in
/// c6f7d47's 22-scene table of 2026-11-27 they shared one (BENCHMARKS.md, "Registers and workgroup
/// sizes").
pub fn scene_fingerprint(buffers: &crate::prepare::buffers::SceneBuffers) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut params = buffers.params;
    (params.sample_base, params.sample_count, params.seed, params.spp_total) = (0, 0, 0, 0);
    let mut h = std::hash::DefaultHasher::new();
    buffers.features.hash(&mut h);
    bytemuck::bytes_of(&params).hash(&mut h);
    bytemuck::cast_slice::<_, u8>(&buffers.materials).hash(&mut h);
    bytemuck::cast_slice::<_, u8>(&buffers.lights).hash(&mut h);
    (buffers.prims.len(), buffers.nodes.len(), buffers.textures.len(), buffers.tables.len()).hash(&mut h);
    buffers.nodes.first().map(bytemuck::bytes_of).hash(&mut h);
    h.finish()
}

/// The first candidate runs alone until its long passes add up to this: a short render (the sphere
/// light's 256 spp take 80 ms on the H100) is over before a trial could pay for itself.
const FIRST_ALONE: Duration = Duration::from_millis(100);
/// A pass long enough to measure a candidate by: this long, or this many samples per pixel. The
/// render grows its passes from one sample towards a second (`render::TARGET_PASS`); the first
/// ones are dominated by their longest paths.
const LONG_PASS: (Duration, u32) = (Duration::from_millis(250), 64);
/// Then each candidate runs whole passes until it has run this long in long ones.
const DECIDE_AFTER: Duration = Duration::from_millis(200);

/// The trial of `count` candidates (indices into `candidates`' list) over a render's first passes.
#[derive(Clone, Debug)]
pub struct Trial {
    count: usize,
    /// Time in long passes of the first candidate before the trial.
    first_alone: Duration,
    /// Per candidate: time and samples per pixel measured in its passes of the trial (after the
    /// first, which may carry the other pipelines' builds: the GPU idles meanwhile).
    time: Vec<Duration>,
    samples: Vec<u64>,
    warm: bool,
    decided: Option<usize>,
}

impl Trial {
    /// A trial of `count` candidates; with one, decided from the start.
    pub fn new(count: usize) -> Self {
        Trial {
            count,
            first_alone: Duration::ZERO,
            time: vec![Duration::ZERO; count],
            samples: vec![0; count],
            warm: false,
            decided: (count <= 1).then_some(0),
        }
    }

    /// The candidate chosen, once it is.
    pub fn decided(&self) -> Option<usize> {
        self.decided
    }

    /// Whether the trial has begun: the candidates take passes in turn (and all must be built).
    pub fn running(&self) -> bool {
        self.decided.is_none() && self.first_alone >= FIRST_ALONE
    }

    /// The candidate that runs the next pass: the chosen one, the first before the trial, else the
    /// one measured least so far (the first of those).
    pub fn next(&self) -> usize {
        match self.decided {
            Some(choice) => choice,
            None if !self.running() => 0,
            None => (0..self.count).min_by_key(|&i| self.time[i]).unwrap_or(0),
        }
    }

    /// Records that candidate `choice` (`next`'s) ran a pass of `samples` per pixel in `elapsed`, and
    /// decides once every candidate has been measured long enough.
    pub fn record(&mut self, choice: usize, samples: u32, elapsed: Duration) {
        if self.decided.is_some() {
            return;
        }
        let long = elapsed >= LONG_PASS.0 || samples >= LONG_PASS.1;
        if !self.running() {
            if long {
                self.first_alone += elapsed;
            }
            return;
        }
        // (Each render starts again from one-sample passes: those measure no candidate either.)
        if !std::mem::replace(&mut self.warm, true) || !long {
            return;
        }
        self.time[choice] += elapsed;
        self.samples[choice] += samples as u64;
        if self.time.iter().all(|&t| t >= DECIDE_AFTER) {
            let per_sample = self.per_sample();
            let best = (0..self.count).min_by(|&a, &b| per_sample[a].total_cmp(&per_sample[b]));
            self.decided = best;
        }
    }

    /// The measurements so far, as one line: nanoseconds alone, then nanoseconds and samples per
    /// candidate. Not whether the first pass of the trial was dropped: a new process builds its
    /// pipelines again, and its first pass of the trial again follows that.
    pub fn to_text(&self) -> String {
        let mut words = vec![self.first_alone.as_nanos().to_string()];
        for (t, s) in self.time.iter().zip(&self.samples) {
            words.push(t.as_nanos().to_string());
            words.push(s.to_string());
        }
        words.join(" ") + "\n"
    }

    /// A trial of `count` candidates resumed from `to_text`'s line (`None` if it is not one of
    /// `count` candidates).
    pub fn from_text(text: &str, count: usize) -> Option<Trial> {
        let words: Vec<u64> = text.split_whitespace().map(|w| w.parse().ok()).collect::<Option<_>>()?;
        if count <= 1 || words.len() != 1 + 2 * count {
            return None;
        }
        let mut t = Trial::new(count);
        t.first_alone = Duration::from_nanos(words[0]);
        for i in 0..count {
            (t.time[i], t.samples[i]) = (Duration::from_nanos(words[1 + 2 * i]), words[2 + 2 * i]);
        }
        Some(t)
    }

    /// The figures behind the choice, for the log: seconds per sample per pixel of each candidate.
    pub fn per_sample(&self) -> Vec<f64> {
        (0..self.count).map(|i| self.time[i].as_secs_f64() / self.samples[i].max(1) as f64).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(v: u64) -> Duration {
        Duration::from_millis(v)
    }

    /// Runs passes of `count` samples with the given ms per sample per candidate until the trial
    /// decides; returns it and the passes it took.
    fn trial(cost_ms: &[u64], count: u32) -> (Trial, u32) {
        let mut t = Trial::new(cost_ms.len());
        for pass in 1..100 {
            if t.decided().is_some() {
                return (t, pass);
            }
            let i = t.next();
            t.record(i, count, ms(cost_ms[i] * count as u64));
        }
        panic!("no decision");
    }

    #[test]
    fn the_first_runs_alone_then_the_fastest_per_sample_wins() {
        let t = Trial::new(2);
        assert_eq!(t.next(), 0, "the first candidate alone first");
        // One pass alone (360 ms: long, and ≥ 100), one unmeasured pass of the trial, then one each
        // (360 and 300 ms ≥ 200): decided in the fourth.
        let (t, passes) = trial(&[12, 10], 30);
        assert_eq!(t.decided(), Some(1));
        assert_eq!(passes, 5);
        assert_eq!(t.next(), 1);
        assert_eq!(trial(&[10, 12], 30).0.decided(), Some(0));
        // Six candidates (two loops by three sizes): every one is timed, the cheapest wins.
        assert_eq!(trial(&[10, 12, 9, 11, 7, 8], 40).0.decided(), Some(4));
    }

    #[test]
    fn short_passes_neither_start_the_trial_nor_measure() {
        let mut t = Trial::new(3);
        // A render's first passes: short in time and in samples.
        for n in [1, 2, 4, 8, 16, 32] {
            t.record(0, n, ms(3 * n as u64));
        }
        assert!(!t.running(), "passes under {LONG_PASS:?} do not count");
        assert_eq!(t.next(), 0);
        t.record(0, 64, ms(5)); // (64 samples per pixel: long in samples)
        assert!(!t.running());
        t.record(0, 20, ms(250)); // (long in time)
        assert!(t.running());
        t.record(t.next(), 40, ms(500)); // (the first pass of the trial is not measured)
        t.record(t.next(), 2, ms(10)); // (nor a short one)
        assert_eq!(t.per_sample(), vec![0.0; 3]);
        // The least measured runs next: the second after the first.
        t.record(t.next(), 40, ms(500));
        assert_eq!(t.next(), 1);
    }

    /// Renders too short to decide add up: each resumes the last one's measurements, drops its own
    /// first pass of the trial (its pipelines are new) and decides as one long render would.
    #[test]
    fn short_renders_resume_the_trial() {
        let dir = std::env::temp_dir().join(format!("caustic-partial-test-{}", std::process::id()));
        let decisions = Decisions { dir: Some(dir.clone()) };
        let cost_ms = [12u64, 10];
        let mut renders = 0;
        let decided = loop {
            renders += 1;
            assert!(renders < 50, "never decided");
            let mut t = decisions.load_partial(3, 2).unwrap_or_else(|| Trial::new(2));
            for _ in 0..2 {
                let i = t.next();
                t.record(i, 64, ms(cost_ms[i] * 64));
            }
            if let Some(choice) = t.decided() {
                decisions.store(3, Variant { path_loop: PathLoop::Plain, workgroup: [8, 8] });
                break choice;
            }
            decisions.store_partial(3, &t);
        };
        assert_eq!(decided, 1);
        assert!(renders > 2, "decided in {renders} renders of two passes");
        assert!(decisions.load_partial(3, 2).is_none(), "a decision ends the kept trial");
        assert!(Trial::from_text("1 2 3", 2).is_none() && Trial::from_text("1 2 x 4 5", 2).is_none());
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn one_candidate_is_decided_from_the_start() {
        let t = Trial::new(1);
        assert_eq!(t.decided(), Some(0));
        assert_eq!(t.next(), 0);
        assert!(!t.running());
    }

    #[test]
    fn workgroup_requests_are_sizes_of_at_most_1024_invocations() {
        assert_eq!(parse_workgroups("32x16").unwrap(), vec![[32, 16]]);
        assert_eq!(parse_workgroups("8x8, 32x32").unwrap(), vec![[8, 8], [32, 32]]);
        for bad in ["", "32", "32x", "0x8", "64x32", "8x8,", "8X8", "-8x8"] {
            let e = parse_workgroups(bad).unwrap_err().to_string();
            assert!(e.contains("CAUSTIC_WORKGROUP"), "{bad:?}: {e}");
        }
    }

    #[test]
    fn the_kernels_own_size_is_tried_first_and_every_size_fits_a_workgroup() {
        assert_eq!(TRIED_WORKGROUPS[0], DEFAULT_WORKGROUP);
        assert!(TRIED_WORKGROUPS.iter().all(|[w, h]| w * h <= 1024));
    }

    #[test]
    fn a_decision_is_kept_per_setup() {
        let dir = std::env::temp_dir().join(format!("caustic-variants-test-{}", std::process::id()));
        let decisions = Decisions { dir: Some(dir.clone()) };
        let v = Variant { path_loop: PathLoop::Regenerate, workgroup: [32, 16] };
        assert_eq!(decisions.load(7), None);
        decisions.store(7, v);
        assert_eq!(decisions.load(7), Some(v));
        assert_eq!(decisions.load(8), None, "another setup's key");
        std::fs::write(dir.join(format!("{:016x}.txt", 9u64)), "plain 32x9999").unwrap();
        assert_eq!(decisions.load(9), None, "a size over 1024 invocations is not read back");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_scene_setup_has_its_own_fingerprint() {
        let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cornell-box.xml"));
        let build = |res: &str| {
            let scene = crate::load::load_scene(path, &[("res".to_string(), res.to_string())]).unwrap();
            crate::prepare::buffers::build(&scene).unwrap()
        };
        let a = build("16");
        assert_eq!(scene_fingerprint(&a), scene_fingerprint(&build("16")));
        let mut pass = a.clone();
        (pass.params.seed, pass.params.sample_base, pass.params.sample_count) = (7, 64, 16);
        assert_eq!(scene_fingerprint(&a), scene_fingerprint(&pass), "a pass's fields are not the setup");
        assert_ne!(scene_fingerprint(&a), scene_fingerprint(&build("32")), "another image size");
        let mut other = a.clone();
        other.materials[0].alpha_u += 0.25;
        assert_ne!(scene_fingerprint(&a), scene_fingerprint(&other), "another material, same mask");
    }
}
