//! Integrator plugins: `path` (and Mitsuba's differentiable `prb`, `prb_basic`, `prb_projective`,
//! whose images are the path tracer's), `direct`, `ptracer` (light tracing), `ibpt` (caustic's own: path and
//! light tracing combined by MIS), `bdpt` (caustic's: bidirectional path tracing) and `moment` (its nested integrator; caustic always tracks
//! the variance), and Mitsuba's `aov` and `depth` (`crate::scene::aov`: outputs rendered beside the image).
use super::loader::Loader;
use super::props::Props;
use crate::scene::{Integrator, IntegratorKind, DEFAULT_CONNECTION_SHARE};
use anyhow::{bail, Result};

impl Loader {
    pub(crate) fn load_integrator(&mut self, props: &Props) -> Result<Integrator> {
        let integrator = match props.kind.as_str() {
            // Mitsuba's differentiable path tracers (Python plugins of its llvm and cuda variants)
            // render the path tracer's image: the same estimator up to their Russian roulette
            // (throughput alone, no η²), with max_depth 6 by default (`tests/tests/integrators.rs`
            // against Mitsuba 3.9.1's prb); Blender's exporter writes `prb`.
            "path" | "prb" | "prb_basic" | "prb_projective" => {
                let default_depth = if props.kind == "path" { -1 } else { 6 };
                let (max_depth, rr_depth) = depths(props, default_depth)?;
                if props.kind == "prb_projective" {
                    // Its visibility-gradient settings do not change the image.
                    for name in ["sppc", "sppp", "sppi", "guiding", "guiding_proj", "guiding_rounds"] {
                        props.mark_used(name);
                    }
                }
                Integrator {
                    kind: IntegratorKind::Path,
                    max_depth,
                    rr_depth,
                    hide_emitters: props.boolean("hide_emitters", false)?,
                    ..Default::default()
                }
            }
            "ptracer" | "ibpt" | "bdpt" | "vcm" => {
                let (max_depth, rr_depth) = depths(props, -1)?;
                // Mitsuba's `samples_per_pass` only splits its own work; the image does not depend on it.
                props.integer("samples_per_pass", -1)?;
                let kind = match props.kind.as_str() {
                    "ibpt" => IntegratorKind::Ibpt,
                    "bdpt" => IntegratorKind::Bdpt,
                    "vcm" => IntegratorKind::Vcm,
                    _ => IntegratorKind::Ptracer,
                };
                let merging =
                    if kind == IntegratorKind::Vcm { merge_settings(props)? } else { Default::default() };
                let bidirectional = matches!(kind, IntegratorKind::Bdpt | IntegratorKind::Vcm);
                let connection_share =
                    if bidirectional { connection_share(props)? } else { DEFAULT_CONNECTION_SHARE };
                let light_tracing_share =
                    if kind == IntegratorKind::Ptracer { 1.0 } else { share(props, "light_tracing_share")? };
                let connection_rate = if bidirectional { share(props, "connection_rate")? } else { 1.0 };
                Integrator {
                    kind,
                    max_depth,
                    rr_depth,
                    hide_emitters: props.boolean("hide_emitters", false)?,
                    merging,
                    connection_share,
                    light_tracing_share,
                    connection_rate,
                    ..Default::default()
                }
            }
            "direct" => {
                // As in Mitsuba, `shading_samples` is the default of both counts.
                let shading = props.integer("shading_samples", 1)?;
                let emitter_samples = props.integer("emitter_samples", shading)?;
                let bsdf_samples = props.integer("bsdf_samples", shading)?;
                for (name, n) in [("emitter_samples", emitter_samples), ("bsdf_samples", bsdf_samples)] {
                    if !(0..=1024).contains(&n) {
                        bail!("{}: {name} must be in [0, 1024], got {n}", props.loc);
                    }
                }
                if emitter_samples + bsdf_samples == 0 {
                    bail!("{}: direct needs at least one emitter or BSDF sample", props.loc);
                }
                let kind = IntegratorKind::Direct {
                    emitter_samples: emitter_samples as u32,
                    bsdf_samples: bsdf_samples as u32,
                };
                Integrator {
                    kind,
                    max_depth: 2,
                    rr_depth: 5,
                    hide_emitters: props.boolean("hide_emitters", false)?,
                    ..Default::default()
                }
            }
            "moment" => {
                // Mitsuba's moment integrator renders its nested integrator and adds the second moment
                // as an extra output; caustic always tracks it (`render --variance` writes it).
                let nested = props.nested("integrator");
                let Some(inner) = nested.first() else {
                    bail!("{}: moment needs a nested <integrator>", props.loc)
                };
                if nested.len() > 1 {
                    let message = format!(
                        "{}: moment with several nested integrators renders only the first",
                        props.loc
                    );
                    self.ignored("moment's second integrator".to_string(), &props.loc, message);
                }
                let inner = self.props(props.src, inner.node)?;
                self.load_integrator(&inner)?
            }
            "aov" => self.load_aov(props)?,
            "depth" => {
                self.aovs = Some(crate::scene::aov::depth_integrator());
                // The image is the depth (`aov`): the cheapest image integrator renders beside it.
                Integrator { kind: IntegratorKind::Path, max_depth: 1, ..Default::default() }
            }
            other => {
                let message = format!("{}: integrator '{other}' is not supported yet; using path", props.loc);
                self.substituted(format!("integrator '{other}'"), &props.loc, message);
                props.mark_all_used();
                Integrator::default()
            }
        };
        self.warn_unused(props);
        Ok(integrator)
    }
}

impl Loader {
    /// Mitsuba's `aov`: the `aovs` list and the nested integrator that renders the image (the
    /// first; a second is left out with a warning; none gives a black image).
    fn load_aov(&mut self, props: &Props) -> Result<Integrator> {
        if self.aovs.is_some() {
            bail!("{}: an aov integrator inside another aov or depth integrator", props.loc);
        }
        let text = props.string("aovs")?.unwrap_or_default();
        let (aovs, skipped) =
            crate::scene::aov::parse_aovs(&text).map_err(|e| anyhow::anyhow!("{}: {e}", props.loc))?;
        for token in skipped {
            let message =
                format!("{}: AOV '{token}' is not supported (no ray differentials); left out", props.loc);
            self.ignored(format!("AOV '{token}'"), &props.loc, message);
        }
        let nested = props.nested("integrator");
        let (name, integrator) = match nested.first() {
            Some(entry) => {
                // Mitsuba names the first unnamed child object `_arg_0` (measured: an unnamed nested
                // `path` writes `_arg_0.R` …).
                let name = entry.name.clone().unwrap_or_else(|| "_arg_0".to_string());
                let inner = self.props(props.src, entry.node)?;
                if inner.kind == "aov" || inner.kind == "depth" {
                    bail!("{}: an aov or depth integrator nested in aov is not supported", inner.loc);
                }
                (Some(name), self.load_integrator(&inner)?)
            }
            None => (None, Integrator { kind: IntegratorKind::Path, max_depth: 1, ..Default::default() }),
        };
        if nested.len() > 1 {
            let message =
                format!("{}: aov with several nested integrators renders only the first", props.loc);
            self.ignored("aov's second integrator".to_string(), &props.loc, message);
        }
        let spec = crate::scene::aov::AovSpec { nested: name, aovs, depth_image: false };
        // Found here, not when the EXR is written after the render.
        if let Some(channel) = spec.duplicate_channel() {
            bail!("{}: two output channels would be named '{channel}'", props.loc);
        }
        self.aovs = Some(spec);
        Ok(integrator)
    }
}

/// `max_depth` (-1: unbounded; `default_depth` where absent: -1 for Mitsuba's C++ integrators, 6
/// for its Python ones) and `rr_depth` (default 5), as Mitsuba reads them.
fn depths(props: &Props, default_depth: i64) -> Result<(i32, u32)> {
    let max_depth = props.integer("max_depth", default_depth)?;
    let rr_depth = props.integer("rr_depth", 5)?;
    if !(-1..=1_000_000).contains(&max_depth) {
        bail!("{}: max_depth must be -1 (unbounded) or in [0, 1000000], got {max_depth}", props.loc);
    }
    if !(1..=1_000_000).contains(&rr_depth) {
        bail!("{}: rr_depth must be in [1, 1000000], got {rr_depth}", props.loc);
    }
    Ok((max_depth as i32, rr_depth as u32))
}

/// `bdpt`'s and `vcm`'s `connection_share` (`scene::Integrator::connection_share`), checked.
fn connection_share(props: &Props) -> Result<f32> {
    let c = props.float("connection_share", DEFAULT_CONNECTION_SHARE)?;
    if !(0.0..=1.0).contains(&c) {
        bail!("{}: connection_share must be from 0 to 1, got {c}", props.loc);
    }
    Ok(c)
}

/// A share in (0, 1], 1 by default: `light_tracing_share` (`ibpt`, `bdpt`, `vcm`) or
/// `connection_rate` (`bdpt`, `vcm`), checked.
fn share(props: &Props, name: &str) -> Result<f32> {
    let q = props.float(name, 1.0)?;
    if !(q > 0.0 && q <= 1.0) {
        bail!("{}: {name} must be above 0 and at most 1, got {q}", props.loc);
    }
    Ok(q)
}

/// `vcm`'s merging radius (`radius`, absolute; or `radius_factor` of the scene's bounding sphere's
/// radius, 0.003 by default) and `alpha` (0.75: each pass's radius squared shrinks by `(i + α)/(i + 1)`
/// on average), checked.
fn merge_settings(props: &Props) -> Result<crate::scene::MergeSettings> {
    let defaults = crate::scene::MergeSettings::default();
    let radius = if props.has("radius") { Some(props.float("radius", 0.0)?) } else { None };
    let radius_factor = props.float("radius_factor", defaults.radius_factor)?;
    let alpha = props.float("alpha", defaults.alpha)?;
    if let Some(r) = radius {
        if !(r > 0.0 && r.is_finite()) {
            bail!("{}: vcm's radius must be positive and finite, got {r}", props.loc);
        }
    }
    if !(radius_factor > 0.0 && radius_factor.is_finite()) {
        bail!("{}: vcm's radius_factor must be positive and finite, got {radius_factor}", props.loc);
    }
    if !(alpha > 0.0 && alpha <= 1.0) {
        bail!("{}: vcm's alpha must be in (0, 1], got {alpha}", props.loc);
    }
    Ok(crate::scene::MergeSettings { radius, radius_factor, alpha })
}
