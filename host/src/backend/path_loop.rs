//! Which per-pixel loop the path tracer's kernel runs, chosen per scene by measuring both.
//!
//! `caustic_kernel::integrator::render_pixel` has two loops over a pixel's samples that compute the
//! same image to the bit (each sample draws the same random numbers either way): one path after the
//! other, or one loop of bounces in which a lane whose path ended starts its next sample at once
//! (path regeneration). Which is faster depends on the scene: on the H100 regeneration ran the
//! diamond 1.42× faster (total internal reflection keeps a few paths bouncing for hundreds of
//! vertices while their warps idle) and cost the fast scenes 8–19% (the sphere light 0.81×: there
//! the regeneration branch runs the camera-sample code at almost every bounce; session 9). No rule
//! read off the scene separated the two groups (rough plastic gained in one scene and lost in
//! another), so the GPU backend builds both and times them on the render's own first passes: after
//! `PLAIN_FIRST` of the plain loop alone, each pass runs half its samples with each loop, and the
//! faster per sample wins once both have run for `DECIDE_AFTER`.
use std::time::Duration;

/// The loops, as spec constant 1 of the kernel (`caustic_kernel::layout::SPEC_REGENERATE`) says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathLoop {
    /// One path after the other.
    Plain,
    /// One loop of bounces over all the samples (path regeneration).
    Regenerate,
}

impl PathLoop {
    pub const BOTH: [PathLoop; 2] = [PathLoop::Plain, PathLoop::Regenerate];

    /// The value of the kernel's spec constant 1.
    pub fn spec_value(self) -> u32 {
        match self {
            PathLoop::Plain => 0,
            PathLoop::Regenerate => 1,
        }
    }
}

/// What `CAUSTIC_PATH_LOOP` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Request {
    /// Unset: the backend's own choice (the GPU measures on a hardware adapter).
    Default,
    /// `measure`: time both loops wherever the path tracer runs (on a software adapter too).
    Measure,
    /// `plain` or `regenerate`: that loop alone (measurements; the tests that check the two agree).
    Fixed(PathLoop),
}

pub fn requested() -> anyhow::Result<Request> {
    match std::env::var("CAUSTIC_PATH_LOOP").as_deref() {
        Err(_) => Ok(Request::Default),
        Ok("measure") => Ok(Request::Measure),
        Ok("plain") => Ok(Request::Fixed(PathLoop::Plain)),
        Ok("regenerate") => Ok(Request::Fixed(PathLoop::Regenerate)),
        Ok(other) => anyhow::bail!("CAUSTIC_PATH_LOOP must be plain, regenerate or measure, not {other:?}"),
    }
}

/// The plain loop alone runs this long first: a short render (the sphere light's 256 spp take 80 ms
/// on the H100, where the plain loop ran 2915 Msamples/s and regeneration 2300) is over before a
/// trial could pay for itself, and the plain loop is the better guess (8 of the 10 scenes timed in
/// session 10 ran it as fast or faster).
const PLAIN_FIRST: Duration = Duration::from_millis(100);
/// Then passes are split between the loops until each has run this long in split passes; the faster
/// per sample wins.
const DECIDE_AFTER: Duration = Duration::from_millis(50);

/// The trial of the two loops over a render's first passes.
#[derive(Clone, Debug, Default)]
pub struct Trial {
    /// Time in whole passes of the plain loop before the trial.
    plain_first: Duration,
    /// Per loop: time and samples per pixel measured in split passes (after the first split pass,
    /// which may carry the regenerating pipeline's first-use costs).
    time: [Duration; 2],
    samples: [u64; 2],
    warm: bool,
    decided: Option<PathLoop>,
}

impl Trial {
    /// A trial whose outcome is fixed (one loop built, or `CAUSTIC_PATH_LOOP` set).
    pub fn fixed(choice: PathLoop) -> Self {
        Trial { decided: Some(choice), ..Default::default() }
    }

    /// The loop chosen, once it is.
    pub fn decided(&self) -> Option<PathLoop> {
        self.decided
    }

    /// How to run a pass of `count` samples per pixel: (loop, samples) dispatches in order.
    pub fn plan(&self, count: u32) -> Vec<(PathLoop, u32)> {
        match self.decided {
            Some(choice) => vec![(choice, count)],
            None if self.plain_first < PLAIN_FIRST || count < 2 => vec![(PathLoop::Plain, count)],
            None => vec![(PathLoop::Plain, count / 2), (PathLoop::Regenerate, count - count / 2)],
        }
    }

    /// Records how long the dispatches of a pass's `plan` took, and decides once both loops have been
    /// measured long enough.
    pub fn record(&mut self, dispatches: &[(PathLoop, u32, Duration)]) {
        if self.decided.is_some() {
            return;
        }
        if let [(PathLoop::Plain, _, elapsed)] = dispatches {
            self.plain_first += *elapsed;
            return;
        }
        if !std::mem::replace(&mut self.warm, true) {
            return;
        }
        for &(choice, count, elapsed) in dispatches {
            let i = choice.spec_value() as usize;
            self.time[i] += elapsed;
            self.samples[i] += count as u64;
        }
        if self.time.iter().all(|&t| t >= DECIDE_AFTER) {
            let [plain, regenerate] = self.per_sample();
            self.decided = Some(if regenerate < plain { PathLoop::Regenerate } else { PathLoop::Plain });
        }
    }

    /// The figures behind the choice, for the log: seconds per sample per pixel of each loop.
    pub fn per_sample(&self) -> [f64; 2] {
        std::array::from_fn(|i| self.time[i].as_secs_f64() / self.samples[i].max(1) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use PathLoop::{Plain, Regenerate};

    fn ms(v: u64) -> Duration {
        Duration::from_millis(v)
    }

    /// Runs passes of `count` samples with the given ms per sample per loop until the trial decides.
    fn trial(plain_ms: u64, regenerate_ms: u64, count: u32) -> (Trial, u32) {
        let mut t = Trial::default();
        for pass in 1..100 {
            if t.decided().is_some() {
                return (t, pass);
            }
            let plan = t.plan(count);
            let cost = |l: PathLoop| if l == Plain { plain_ms } else { regenerate_ms };
            let timed: Vec<_> = plan.iter().map(|&(l, n)| (l, n, ms(cost(l) * n as u64))).collect();
            t.record(&timed);
        }
        panic!("no decision");
    }

    #[test]
    fn the_plain_loop_runs_alone_first_then_the_faster_per_sample_wins() {
        let t = Trial::default();
        assert_eq!(t.plan(8), vec![(Plain, 8)], "the plain loop first");
        // Three plain passes (144 ms ≥ 100), one unmeasured split pass, then three split passes (72
        // and 60 ms ≥ 50): decided before the eighth.
        let (t, passes) = trial(12, 10, 4);
        assert_eq!(t.decided(), Some(Regenerate));
        assert_eq!(passes, 8);
        assert_eq!(t.plan(8), vec![(Regenerate, 8)]);
        assert_eq!(trial(10, 12, 4).0.decided(), Some(Plain));
        // A one-sample pass cannot be split: it runs the plain loop and measures nothing.
        let mut t = Trial { plain_first: PLAIN_FIRST, ..Default::default() };
        assert_eq!(t.plan(1), vec![(Plain, 1)]);
        t.record(&[(Plain, 1, ms(5))]);
        assert_eq!(t.plan(5), vec![(Plain, 2), (Regenerate, 3)]);
    }

    #[test]
    fn a_fixed_trial_never_splits() {
        let t = Trial::fixed(Plain);
        assert_eq!(t.plan(64), vec![(Plain, 64)]);
    }
}
