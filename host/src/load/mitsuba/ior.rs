//! Indices of refraction as Mitsuba 3 names them: the table of dielectric IORs that `int_ior` /
//! `ext_ior` strings refer to, and the measured complex IORs (η, k) of conductors that a
//! `material` string loads from `ior/<material>.eta.spd` and `ior/<material>.k.spd`.
//!
//! Mitsuba's rgb variants turn the measured spectra into linear sRGB with `bounded = false` and
//! `d65 = false`: the spectrum is integrated against the CIE 1931 curves without a D65 weight and
//! only negative channels are clamped. That is exactly the conversion `spectrum.rs` applies to
//! emission spectra, so it is reused here.
use super::props::Props;
use super::spectrum::{read_spd, spectrum_to_rgb, SpectrumUse};
use super::xml::Loc;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

/// Mitsuba's named dielectric IORs (≈589 nm, 0–20 °C), with its spelling (lower case).
pub const NAMED_DIELECTRIC_IORS: [(&str, f32); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// An optical glass of caustic's dispersion extension (`glass`): Sellmeier's coefficients of its index,
/// `n² = 1 + Σ Bᵢλ²/(λ² − Cᵢ)` with λ in µm, as the Schott (and, for fused silica, Malitson's)
/// catalogue lists them.
pub struct Glass {
    pub name: &'static str,
    pub b: [f32; 3],
    pub c: [f32; 3],
}

// The catalogue's digits, kept as published (f32 rounds them).
#[allow(clippy::excessive_precision)]
pub const NAMED_GLASSES: [Glass; 5] = [
    Glass {
        name: "bk7",
        b: [1.03961212, 0.231792344, 1.01046945],
        c: [0.00600069867, 0.0200179144, 103.560653],
    },
    Glass {
        name: "fused silica",
        b: [0.6961663, 0.4079426, 0.8974794],
        c: [0.00467914826, 0.0135120631, 97.9340025],
    },
    Glass {
        name: "f2",
        b: [1.34533359, 0.209073176, 0.937357162],
        c: [0.00997743871, 0.0470450767, 111.886764],
    },
    Glass {
        name: "sf11",
        b: [1.73759695, 0.313747346, 1.89878101],
        c: [0.013188707, 0.0623068142, 155.23629],
    },
    Glass {
        name: "sf66",
        b: [2.0245976, 0.470187196, 2.59970433],
        c: [0.0147053225, 0.0692998276, 161.817601],
    },
];

/// A named glass (case ignored).
pub fn named_glass(name: &str) -> Option<&'static Glass> {
    let name = name.to_lowercase();
    NAMED_GLASSES.iter().find(|g| g.name == name)
}

/// The names `named_glass` knows, for messages.
pub fn glass_names() -> String {
    NAMED_GLASSES.iter().map(|g| format!("'{}'", g.name)).collect::<Vec<_>>().join(", ")
}

/// The conductor `material` that stands for a perfect mirror (η = 0, k = 1) and needs no data.
pub const PERFECT_MIRROR: &str = "none";

/// Set to a folder holding `ior/*.spd` to find conductor data outside the scene's folders.
pub const DATA_DIR_VARIABLE: &str = "CAUSTIC_DATA_DIR";

/// Looks a dielectric up by name; case is ignored (Mitsuba lower-cases the name first).
pub fn named_dielectric_ior(name: &str) -> Option<f32> {
    let name = name.to_lowercase();
    NAMED_DIELECTRIC_IORS.iter().find(|(n, _)| *n == name).map(|&(_, ior)| ior)
}

/// The names `named_dielectric_ior` knows, for messages.
pub fn dielectric_ior_names() -> String {
    NAMED_DIELECTRIC_IORS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
}

/// An `int_ior` / `ext_ior`-style property as Mitsuba reads it: a `<float>` is the IOR itself, a
/// `<string>` names an entry of the table, any other tag is an error; absent, the named `default`.
/// The sign is not checked here (Mitsuba's BSDFs reject negative IORs themselves).
pub(crate) fn ior_property(props: &Props, name: &str, default: &str) -> Result<f32> {
    let Some(entry) = props.entries.iter().find(|e| e.name.as_deref() == Some(name)) else {
        return named_dielectric_ior(default)
            .with_context(|| format!("{}: default IOR '{default}' is not a known name", props.loc));
    };
    // Mark the property used through the typed accessors, then interpret it by its tag.
    let value = match entry.tag.as_str() {
        "float" => return props.float(name, 0.0),
        _ => props.string(name)?.unwrap_or_default(),
    };
    ior_from_tagged_value(&entry.tag, name, &value, &entry.loc)
}

/// The non-`<float>` half of `ior_property`, separate so that it can be tested without a scene.
fn ior_from_tagged_value(tag: &str, name: &str, value: &str, loc: &Loc) -> Result<f32> {
    if tag != "string" {
        bail!("{loc}: '{name}' must be a <float> or a <string> naming a material, not <{tag}>");
    }
    named_dielectric_ior(value).with_context(|| {
        format!(
            "{loc}: no IOR is known by the name '{value}' for '{name}' (give a <float>, or one of: {})",
            dielectric_ior_names()
        )
    })
}

/// The measured complex IOR of a conductor `material` (e.g. `Au`) as linear sRGB `(η, k)`.
///
/// Looks for `ior/<material>.eta.spd` (and its `.k.spd` sibling) in each of `search_dirs` in order,
/// then in `$CAUSTIC_DATA_DIR/ior/`, then among Mitsuba's own (`conductor_table`). The name is
/// case-sensitive, as the file names are.
pub fn conductor_eta_k(material: &str, search_dirs: &[PathBuf]) -> Result<([f32; 3], [f32; 3])> {
    if material == PERFECT_MIRROR {
        return Ok(([0.0; 3], [1.0; 3]));
    }
    if material.is_empty() || material.contains(['/', '\\']) {
        bail!("conductor material '{material}' is not a material name");
    }
    let ior_dirs = ior_data_dirs(search_dirs);
    let eta_name = format!("{material}.eta.spd");
    let Some(dir) = ior_dirs.iter().find(|d| d.join(&eta_name).is_file()) else {
        return super::conductor_table::built_in(material)
            .with_context(|| missing_material_message(material, &ior_dirs));
    };
    let eta = spd_file_to_rgb(&dir.join(eta_name))?;
    let k = spd_file_to_rgb(&dir.join(format!("{material}.k.spd")))?;
    Ok((eta, k))
}

/// The `ior/` folders `conductor_eta_k` tries, in order (existing or not).
pub fn ior_data_dirs(search_dirs: &[PathBuf]) -> Vec<PathBuf> {
    let env_dir = std::env::var_os(DATA_DIR_VARIABLE).filter(|v| !v.is_empty()).map(PathBuf::from);
    let mut dirs: Vec<PathBuf> = Vec::new();
    for dir in search_dirs.iter().chain(env_dir.iter()) {
        let ior = dir.join("ior");
        if !dirs.contains(&ior) {
            dirs.push(ior);
        }
    }
    dirs
}

/// `dirs`, followed by every ancestor of each (absolute where the folder exists), without repeats:
/// scenes often keep shared data such as `ior/` a few levels above their own folder.
pub fn with_ancestors(dirs: &[PathBuf]) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = dirs.to_vec();
    for dir in dirs {
        let absolute = dir.canonicalize().unwrap_or_else(|_| dir.clone());
        for ancestor in absolute.ancestors().skip(1) {
            let ancestor = ancestor.to_path_buf();
            if !ancestor.as_os_str().is_empty() && !out.contains(&ancestor) {
                out.push(ancestor);
            }
        }
    }
    out
}

/// The conductor materials found in the `ior/` folders (those with both spectra) and built in,
/// plus `none`.
pub fn conductor_materials(search_dirs: &[PathBuf]) -> Vec<String> {
    let mut names = vec![PERFECT_MIRROR.to_string()];
    names.extend(super::conductor_table::BUILT_IN.iter().map(|e| e.0.to_string()));
    for dir in ior_data_dirs(search_dirs) {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for entry in entries.flatten() {
            let file_name = entry.file_name();
            let Some(material) = file_name.to_str().and_then(|n| n.strip_suffix(".eta.spd")) else {
                continue;
            };
            if dir.join(format!("{material}.k.spd")).is_file() && !names.iter().any(|n| n == material) {
                names.push(material.to_string());
            }
        }
    }
    names[1..].sort();
    names
}

fn missing_material_message(material: &str, ior_dirs: &[PathBuf]) -> String {
    let searched = ior_dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ");
    let parents: Vec<PathBuf> = ior_dirs.iter().filter_map(|d| d.parent().map(Path::to_path_buf)).collect();
    let available = conductor_materials(&parents);
    let mut message = format!("conductor material '{material}': no {material}.eta.spd in any of: {searched}");
    if let Some(near) = available.iter().find(|n| n.eq_ignore_ascii_case(material)) {
        message.push_str(&format!(" (names are case-sensitive: did you mean '{near}'?)"));
    }
    message.push_str(&format!("; nor is it one of Mitsuba's, built in; available: {}", available.join(", ")));
    message
}

/// Reads a spectrum file and converts it as Mitsuba's rgb variants convert IOR spectra.
pub fn spd_file_to_rgb(path: &Path) -> Result<[f32; 3]> {
    let (wavelengths, values) = read_spd(path)?;
    // SpectrumUse::Emission is the unweighted (no D65), lower-clamped-only conversion.
    Ok(spectrum_to_rgb(&wavelengths, &values, SpectrumUse::Emission))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Mitsuba scene data beside the repository (`../shared`), if present.
    fn shared_mitsuba_dir() -> Option<PathBuf> {
        let dir = match std::env::var_os("CAUSTIC_SHARED") {
            Some(p) => PathBuf::from(p),
            None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared"),
        }
        .join("scenes/mitsuba");
        if dir.join("ior").is_dir() {
            Some(dir)
        } else {
            eprintln!("notice: {} has no ior/ folder; skipping the measured-conductor checks", dir.display());
            None
        }
    }

    /// A fresh, empty folder for one test.
    fn scratch_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("caustic-ior-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("ior")).unwrap();
        dir
    }

    fn assert_close(got: [f32; 3], want: [f32; 3], what: &str) {
        for (g, w) in got.iter().zip(want) {
            // The references are printed to 7 significant digits; the agreement is at f32 precision.
            assert!((g - w).abs() <= 2e-6 * w.abs(), "{what}: got {got:?}, Mitsuba gives {want:?}");
        }
    }

    #[test]
    fn named_iors_are_mitsubas() {
        assert_eq!(named_dielectric_ior("water"), Some(1.3330));
        assert_eq!(named_dielectric_ior("bk7"), Some(1.5046));
        assert_eq!(named_dielectric_ior("BK7"), Some(1.5046));
        assert_eq!(named_dielectric_ior("diamond"), Some(2.419));
        assert_eq!(named_dielectric_ior("air"), Some(1.000277));
        assert_eq!(named_dielectric_ior("Carbon Dioxide"), Some(1.00045));
        assert_eq!(named_dielectric_ior("polypropylene"), Some(1.49));
        assert_eq!(named_dielectric_ior("amber"), Some(1.55));
        assert_eq!(named_dielectric_ior("glass"), None);
        assert_eq!(named_dielectric_ior(" water"), None);
    }

    #[test]
    fn ior_strings_name_table_entries_and_other_tags_are_refused() {
        let loc = Loc { file: PathBuf::from("scene.xml"), line: 7 };
        assert_eq!(ior_from_tagged_value("string", "int_ior", "Diamond", &loc).unwrap(), 2.419);
        let unknown = ior_from_tagged_value("string", "int_ior", "1.5", &loc).unwrap_err().to_string();
        assert!(
            unknown.contains("scene.xml:7") && unknown.contains("'1.5'") && unknown.contains("bk7"),
            "{unknown}"
        );
        let wrong_tag = ior_from_tagged_value("integer", "int_ior", "2", &loc).unwrap_err().to_string();
        assert!(wrong_tag.contains("<integer>"), "{wrong_tag}");
    }

    #[test]
    fn perfect_mirror_needs_no_data() {
        assert_eq!(conductor_eta_k("none", &[]).unwrap(), ([0.0; 3], [1.0; 3]));
    }

    /// Mitsuba's named conductors need no data beside the scene (its package ships them; caustic
    /// carries them built in); an unknown name still fails, listing what exists.
    #[test]
    fn named_conductors_need_no_data() {
        let scratch = scratch_dir("no-data");
        let (eta, k) = conductor_eta_k("Au", std::slice::from_ref(&scratch)).unwrap();
        assert_close(eta, [0.143036, 0.3753071, 1.442045], "built-in Au eta");
        assert_close(k, [3.982997, 2.385556, 1.603359], "built-in Au k");
        let message = conductor_eta_k("Unobtainium", &[scratch]).unwrap_err().to_string();
        assert!(message.contains("'Unobtainium'") && message.contains("Cu_palik"), "{message}");
    }

    // Reference values: Mitsuba 3.9.1, variant scalar_rgb, `conductor` with `material` set,
    // read back through `mi.traverse(bsdf)['eta.value']` / `['k.value']`.
    #[test]
    fn measured_conductors_match_mitsuba() {
        let Some(dir) = shared_mitsuba_dir() else { return };
        let cases: [(&str, [f32; 3], [f32; 3]); 5] = [
            ("Au", [0.143036, 0.3753071, 1.442045], [3.982997, 2.385556, 1.603359]),
            ("Cu", [0.2010055, 0.9237495, 1.102215], [3.913262, 2.453045, 2.14209]),
            ("Al", [1.657501, 0.8804047, 0.5212445], [9.223811, 6.269502, 4.837004]),
            ("Ag", [0.1552762, 0.116728, 0.1383876], [4.828354, 3.122222, 2.146901]),
            ("Cr", [4.369668, 2.916505, 1.654905], [5.206547, 4.231306, 3.754699]),
        ];
        for (material, eta, k) in cases {
            let (got_eta, got_k) = conductor_eta_k(material, std::slice::from_ref(&dir)).unwrap();
            assert_close(got_eta, eta, &format!("{material} eta"));
            assert_close(got_k, k, &format!("{material} k"));
        }
        // Every material shipped beside the scenes parses and converts to something sensible.
        for material in conductor_materials(std::slice::from_ref(&dir)) {
            let (eta, k) = conductor_eta_k(&material, std::slice::from_ref(&dir)).unwrap();
            assert!(eta.iter().chain(&k).all(|c| c.is_finite() && *c >= 0.0), "{material}: {eta:?} {k:?}");
        }
    }

    /// Every spectrum pair beside the scenes gives the built-in entry of its name, bit for bit, and
    /// the table lists no other material.
    #[test]
    fn built_in_conductors_are_the_spectra() {
        let Some(dir) = shared_mitsuba_dir() else { return };
        let ior = dir.join("ior");
        let mut names: Vec<String> = conductor_materials(std::slice::from_ref(&dir));
        names.retain(|n| n != PERFECT_MIRROR && ior.join(format!("{n}.eta.spd")).is_file());
        let table: Vec<&str> = super::super::conductor_table::BUILT_IN.iter().map(|e| e.0).collect();
        assert_eq!(table, names, "the table lists exactly the shared spectra");
        for name in &names {
            // The files come first: this reads them.
            let from_files = conductor_eta_k(name, std::slice::from_ref(&dir)).unwrap();
            assert_eq!(super::super::conductor_table::built_in(name), Some(from_files), "{name}");
        }
    }

    /// Writes `conductor_table.rs` from the shared spectra (run by hand, `--ignored`).
    #[test]
    #[ignore]
    fn write_conductor_table() {
        let dir = shared_mitsuba_dir().expect("../shared's scenes/mitsuba/ior");
        let ior = dir.join("ior");
        let mut names: Vec<String> = std::fs::read_dir(&ior)
            .unwrap()
            .flatten()
            .filter_map(|e| e.file_name().to_str()?.strip_suffix(".eta.spd").map(str::to_string))
            .collect();
        names.sort();
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src/mitsuba/conductor_table.rs");
        let text = std::fs::read_to_string(&path).unwrap();
        let start = text.find("pub const BUILT_IN").unwrap();
        let end = start + text[start..].find("];").unwrap() + 2;
        let mut table = String::from("pub const BUILT_IN: &[(&str, [f32; 3], [f32; 3])] = &[\n");
        for name in names {
            let (eta, k) = conductor_eta_k(&name, std::slice::from_ref(&dir)).unwrap();
            table.push_str(&format!("    (\"{name}\", {eta:?}, {k:?}),\n"));
        }
        table.push_str("];");
        std::fs::write(&path, format!("{}{table}{}", &text[..start], &text[end..])).unwrap();
    }

    #[test]
    fn ancestors_reach_the_shared_ior_folder() {
        let Some(dir) = shared_mitsuba_dir() else { return };
        let scene_dir = dir.join("docs/scenes");
        let (eta, _) = conductor_eta_k("Au", &with_ancestors(&[scene_dir])).unwrap();
        assert!(eta[0] > 0.1 && eta[0] < 0.2, "{eta:?}");
    }

    #[test]
    fn missing_material_names_where_it_looked_and_what_exists() {
        let Some(dir) = shared_mitsuba_dir() else { return };
        let message = conductor_eta_k("au", std::slice::from_ref(&dir)).unwrap_err().to_string();
        assert!(
            message.contains("'au'") && message.contains(&dir.join("ior").display().to_string()),
            "{message}"
        );
        assert!(message.contains("did you mean 'Au'"), "{message}");
        assert!(message.contains("Cu") && message.contains("none"), "{message}");
        let names = conductor_materials(&[dir]);
        assert!(names.iter().any(|n| n == "Al") && names[0] == "none", "{names:?}");
    }

    #[test]
    fn malformed_spd_names_file_and_line() {
        let dir = scratch_dir("malformed");
        let eta = dir.join("ior/Bad.eta.spd");
        std::fs::write(&eta, "# comment\n400 1.0\n500 abc\n").unwrap();
        std::fs::write(dir.join("ior/Bad.k.spd"), "400 1\n500 1\n").unwrap();
        let message = format!("{:#}", conductor_eta_k("Bad", std::slice::from_ref(&dir)).unwrap_err());
        assert!(message.contains(&format!("{}:3", eta.display())) && message.contains("abc"), "{message}");

        std::fs::write(&eta, "400 1.0 2.0\n").unwrap();
        let message = format!("{:#}", conductor_eta_k("Bad", std::slice::from_ref(&dir)).unwrap_err());
        assert!(message.contains(&format!("{}:1", eta.display())), "{message}");

        std::fs::write(&eta, "500 1.0\n400 1.0\n").unwrap();
        let message = format!("{:#}", conductor_eta_k("Bad", std::slice::from_ref(&dir)).unwrap_err());
        assert!(
            message.contains(&format!("{}:2", eta.display())) && message.contains("increase"),
            "{message}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn missing_k_file_is_named() {
        let dir = scratch_dir("missing-k");
        std::fs::write(dir.join("ior/Half.eta.spd"), "400 1\n700 1\n").unwrap();
        let message = format!("{:#}", conductor_eta_k("Half", std::slice::from_ref(&dir)).unwrap_err());
        assert!(message.contains("Half.k.spd"), "{message}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A constant spectrum converts like an equal-energy emitter: no D65 weight, no upper clamp.
    #[test]
    fn constant_spectrum_is_unweighted() {
        let dir = scratch_dir("constant");
        std::fs::write(dir.join("ior/Flat.eta.spd"), "# flat\n360 2\n\n830 2 # end\n").unwrap();
        std::fs::write(dir.join("ior/Flat.k.spd"), "360 1\n830 1\n").unwrap();
        let (eta, k) = conductor_eta_k("Flat", std::slice::from_ref(&dir)).unwrap();
        let white = super::super::spectrum::xyz_to_srgb([1.0, 1.0, 1.0]).map(|c| c as f32);
        for c in 0..3 {
            assert!(
                (k[c] - white[c]).abs() < 2e-3 && (eta[c] - 2.0 * white[c]).abs() < 4e-3,
                "{eta:?} {k:?} {white:?}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
