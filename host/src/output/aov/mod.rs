//! Mitsuba's `aov` and `depth` integrators: what a scene asks for (`AovSpec`, read from the `aovs`
//! string `name:type,…`), the EXR channel names Mitsuba 3.9.1 gives them, and developing them into
//! the film's extra channels (`pass` renders them).
//!
//! Channel names, read from EXR files Mitsuba 3.9.1 (scalar_rgb) wrote: the image is `R`, `G`, `B`
//! (the nested integrator's; black without one); the nested integrator's image again as
//! `<its name>.R/.G/.B/.A` (`_arg_<i>` when the element has no `name`), `A` being the fraction of
//! samples whose camera ray met something; then each AOV: `depth` → `<name>.T`, `position`,
//! `geo_normal`, `sh_normal`, `dp_du`, `dp_dv` → `.X .Y .Z`, `uv` → `.U .V`, `albedo` → `.R .G .B`,
//! `prim_index`, `shape_index` → `.I`. A camera ray that meets nothing gives 0 in every AOV channel
//! (Mitsuba zeroes the surface record). The `depth` integrator writes the distance as R = G = B.
pub mod exr;
pub mod pass;

use crate::output::film::{AovChannel, Film};
use anyhow::{bail, Result};

/// One AOV type of Mitsuba's `aov` integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AovKind {
    /// `eval_diffuse_reflectance` of the surface's BSDF (`pass::albedo` says what each model gives).
    Albedo,
    /// Distance along the camera ray from the near clip plane (where Mitsuba's rays start) to the hit.
    Depth,
    Position,
    Uv,
    GeoNormal,
    ShNormal,
    DpDu,
    DpDv,
    /// The triangle's index in its mesh (0 for analytic shapes).
    PrimIndex,
    /// The shape's index in Mitsuba's shape list, from 1 (`pass::shape_indices`).
    ShapeIndex,
}

impl AovKind {
    /// The type named `name` in an `aovs` string; `None` for an unknown one.
    pub fn parse(name: &str) -> Option<AovKind> {
        Some(match name {
            "albedo" => AovKind::Albedo,
            "depth" => AovKind::Depth,
            "position" => AovKind::Position,
            "uv" => AovKind::Uv,
            "geo_normal" => AovKind::GeoNormal,
            "sh_normal" => AovKind::ShNormal,
            "dp_du" => AovKind::DpDu,
            "dp_dv" => AovKind::DpDv,
            "prim_index" => AovKind::PrimIndex,
            "shape_index" => AovKind::ShapeIndex,
            _ => return None,
        })
    }

    /// The suffixes of its channels, in the order its values come.
    pub fn suffixes(self) -> &'static [&'static str] {
        match self {
            AovKind::Albedo => &["R", "G", "B"],
            AovKind::Depth => &["T"],
            AovKind::Uv => &["U", "V"],
            AovKind::PrimIndex | AovKind::ShapeIndex => &["I"],
            _ => &["X", "Y", "Z"],
        }
    }
}

/// One entry `name:type` of the `aovs` string.
#[derive(Clone, Debug, PartialEq)]
pub struct Aov {
    pub name: String,
    pub kind: AovKind,
}

/// What an `aov` or `depth` integrator adds to the render.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct AovSpec {
    /// The channel prefix of the nested integrator's image copy (its `name`, or `_arg_<i>`); `None`
    /// without a nested integrator, whose image is then black.
    pub nested: Option<String>,
    pub aovs: Vec<Aov>,
    /// Mitsuba's `depth` integrator: the image itself is the depth (R = G = B), no extra channels.
    pub depth_image: bool,
}

/// Mitsuba's `depth` integrator's spec.
pub fn depth_integrator() -> AovSpec {
    AovSpec { nested: None, aovs: vec![Aov { name: String::new(), kind: AovKind::Depth }], depth_image: true }
}

/// AOV types Mitsuba has and caustic does not compute (screen-space uv derivatives need ray
/// differentials, which caustic's camera rays do not carry).
pub const UNSUPPORTED: [&str; 2] = ["duv_dx", "duv_dy"];

/// Parses Mitsuba's `aovs` string: entries separated by commas or spaces, each `name:type`. Returns
/// the AOVs and the entries of a type in `UNSUPPORTED` (left out, for the caller to report); an
/// entry that is not `name:type` or names an unknown type is an error.
pub fn parse_aovs(text: &str) -> Result<(Vec<Aov>, Vec<String>)> {
    let mut aovs = Vec::new();
    let mut skipped = Vec::new();
    for token in text.split([',', ' ']).filter(|t| !t.is_empty()) {
        let parts: Vec<&str> = token.split(':').collect();
        let [name, kind] = parts[..] else { bail!("AOV '{token}' is not a <name>:<type> pair") };
        if name.is_empty() || kind.is_empty() {
            bail!("AOV '{token}' is not a <name>:<type> pair");
        }
        match AovKind::parse(kind) {
            Some(kind) => aovs.push(Aov { name: name.to_string(), kind }),
            None if UNSUPPORTED.contains(&kind) => skipped.push(token.to_string()),
            None => bail!(
                "AOV '{token}': unknown type '{kind}' (known: albedo, depth, position, uv, geo_normal, \
                 sh_normal, dp_du, dp_dv, prim_index, shape_index)"
            ),
        }
    }
    Ok((aovs, skipped))
}

impl AovSpec {
    /// The extra channels' names, in the order `pass` computes their values: the nested image's
    /// alpha first (its `.R .G .B` are copied from the image), then each AOV's components.
    pub fn computed_channels(&self) -> Vec<String> {
        let mut names = Vec::new();
        if let Some(n) = &self.nested {
            names.push(format!("{n}.A"));
        }
        for a in &self.aovs {
            names.extend(a.kind.suffixes().iter().map(|s| format!("{}.{s}", a.name)));
        }
        names
    }

    /// A channel name the image and its AOVs would share (the EXR can hold one of each), if any.
    pub fn duplicate_channel(&self) -> Option<String> {
        let mut names: Vec<String> = ["R", "G", "B"].map(String::from).to_vec();
        if let Some(n) = &self.nested {
            names.extend(["R", "G", "B"].map(|c| format!("{n}.{c}")));
        }
        names.extend(self.computed_channels());
        let mut seen = std::collections::HashSet::new();
        names.into_iter().find(|n| !seen.insert(n.clone()))
    }

    /// Puts the rendered AOVs (`computed`: `computed_channels`' order, per pixel; their variances of
    /// the mean in `variance`) into `film`: the depth integrator's replace the image; otherwise
    /// they become its extra channels, after the nested image's copy, and without a nested
    /// integrator the image is black.
    pub fn develop(&self, film: &mut Film, computed: Vec<Vec<f32>>, variance: Vec<Vec<f64>>) {
        if self.depth_image {
            film.rgb = computed[0].iter().map(|&d| [d; 3]).collect();
            film.variance = Some(variance[0].iter().map(|&v| [v; 3]).collect());
            return;
        }
        let mut channels = Vec::new();
        match &self.nested {
            Some(n) => {
                for (c, suffix) in ["R", "G", "B"].iter().enumerate() {
                    channels.push(AovChannel {
                        name: format!("{n}.{suffix}"),
                        values: film.rgb.iter().map(|p| p[c]).collect(),
                        variance: film.variance.as_ref().map(|v| v.iter().map(|p| p[c]).collect()),
                    });
                }
            }
            None => {
                film.rgb.iter_mut().for_each(|p| *p = [0.0; 3]);
                if let Some(v) = film.variance.as_mut() {
                    v.iter_mut().for_each(|p| *p = [0.0; 3]);
                }
            }
        }
        let computed = self.computed_channels().into_iter().zip(computed).zip(variance);
        for ((name, values), variance) in computed {
            channels.push(AovChannel { name, values, variance: Some(variance) });
        }
        film.aovs = channels;
    }
}

/// Renders the scene's AOVs, if it has any, over samples `[0, spp)` with `seed` (the image's) and
/// puts them into `film` (`AovSpec::develop`). A scene without AOVs costs nothing here.
pub fn add_to(film: &mut Film, buffers: &crate::prepare::buffers::SceneBuffers, spp: u32, seed: u32) {
    if let Some(spec) = &buffers.aovs {
        if spec.computed_channels().is_empty() {
            // An `aov` with neither AOVs nor a nested integrator: a black image, nothing to trace.
            spec.develop(film, Vec::new(), Vec::new());
            return;
        }
        let (values, variance) = pass::render(buffers, spec, spp, seed);
        spec.develop(film, values, variance);
    }
}
