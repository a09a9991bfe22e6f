//! Mitsuba's `aov` and `depth` integrators: what a scene asks for (`AovSpec`, read from the `aovs`
//! string `name:type,…`) and the EXR channel names Mitsuba 3.9.1 gives them. `output::aov` renders
//! them and develops them into the film's extra channels.
//!
//! Channel names, read from EXR files Mitsuba 3.9.1 (scalar_rgb) wrote: the image is `R`, `G`, `B`
//! (the nested integrator's; black without one); the nested integrator's image again as
//! `<its name>.R/.G/.B/.A` (`_arg_<i>` when the element has no `name`), `A` being the fraction of
//! samples whose camera ray met something; then each AOV: `depth` → `<name>.T`, `position`,
//! `geo_normal`, `sh_normal`, `dp_du`, `dp_dv` → `.X .Y .Z`, `uv` → `.U .V`, `albedo` → `.R .G .B`,
//! `prim_index`, `shape_index` → `.I`. A camera ray that meets nothing gives 0 in every AOV channel
//! (Mitsuba zeroes the surface record). The `depth` integrator writes the distance as R = G = B.
use anyhow::{bail, Result};

/// One AOV type of Mitsuba's `aov` integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AovKind {
    /// `eval_diffuse_reflectance` of the surface's BSDF (`output::aov::pass` says what each model
    /// gives).
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
    /// The shape's index in Mitsuba's shape list, from 1 (`prepare::primitives::shape_indices`).
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
    /// The extra channels' names, in the order `output::aov::pass` computes their values: the nested
    /// image's alpha first (its `.R .G .B` are copied from the image), then each AOV's components.
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
}
