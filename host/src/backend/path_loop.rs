//! Which per-pixel loop the path tracer's kernel runs, chosen per scene by measuring both.
//!
//! `caustic_kernel::integrator::render_pixel` has two loops over a pixel's samples that compute the
//! same image to the bit (each sample draws the same random numbers either way): one path after the
//! other, or one loop of bounces in which a lane whose path ended starts its next sample at once
//! (path regeneration). Which is faster depends on the scene: on the H100 regeneration ran the
//! diamond 1.42× faster (total internal reflection keeps a few paths bouncing for hundreds of
//! vertices while their warps idle) and cost the fast scenes 8–19% (the sphere light 0.81×: there
//! the regeneration branch runs the camera-sample code at almost every bounce; 2026-11-24). No rule
//! read off the scene separated the two groups (rough plastic gained in one scene and lost in
//! another), so the GPU backend builds both and times them on the render's own first passes: after
//! a first stretch of the plain loop alone, each pass runs part of its samples with each loop, and
//! the fastest per sample wins (`variant`, which times the workgroup sizes with them).

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

    /// How logs and the kept choices (`variant::Decisions`) name it.
    pub fn name(self) -> &'static str {
        match self {
            PathLoop::Plain => "plain",
            PathLoop::Regenerate => "regenerating",
        }
    }

    /// The loop `name` names.
    pub fn named(name: &str) -> Option<PathLoop> {
        PathLoop::BOTH.into_iter().find(|l| l.name() == name)
    }

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
