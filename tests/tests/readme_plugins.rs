//! docs/mitsuba.md's table of Mitsuba 3 plugins against the loader: the table names every plugin of Mitsuba
//! 3.9.1 (`tests/data/mitsuba_plugins.txt`) exactly once; each plugin it calls not supported is
//! refused by `--strict` in a one-element scene (naming file and line); each it calls supported or
//! partial loads under `--strict` in a one-element scene of its defaults (plugins that need a file
//! are left to the tests of their loaders).
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn readme_rows() -> Vec<(String, String, String)> {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/mitsuba.md")).unwrap();
    readme
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            // "| family | `plugin` | status | notes |" splits into 6 cells, empty at both ends.
            let [_, family, plugin, status, _, _] = cells.as_slice() else { return None };
            let plugin = plugin.strip_prefix('`')?.strip_suffix('`')?;
            matches!(*status, "supported" | "partial" | "not supported")
                .then(|| (family.to_string(), plugin.to_string(), status.to_string()))
        })
        .collect()
}

/// A one-element scene using `plugin` of `family` with its defaults, where one can be written
/// without files.
fn scene_using(family: &str, plugin: &str) -> Option<String> {
    Some(match (family, plugin) {
        // (`mesh_attribute` reads a mesh file's attributes: `mesh_attribute.rs`.)
        (_, "obj" | "ply" | "serialized" | "envmap" | "bitmap" | "mesh_attribute") => return None,
        ("bsdf", "mask") => {
            r#"<shape type="sphere"><bsdf type="mask"><bsdf type="diffuse"/></bsdf></shape>"#.into()
        }
        // A bump map needs a bitmap (Mitsuba's checkerboard has no gradient): left to normalmap.rs.
        ("bsdf", "bumpmap") => return None,
        ("bsdf", "normalmap") => r#"<shape type="sphere"><bsdf type="normalmap"><texture name="normalmap" type="checkerboard"/><bsdf type="diffuse"/></bsdf></shape>"#.into(),
        // Mitsuba requires the weight and two BSDFs.
        ("bsdf", "blendbsdf") => r#"<shape type="sphere"><bsdf type="blendbsdf"><float name="weight" value="0.5"/><bsdf type="diffuse"/><bsdf type="roughconductor"/></bsdf></shape>"#.into(),
        ("bsdf", "twosided") => {
            r#"<shape type="sphere"><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>"#.into()
        }
        ("bsdf", _) => format!(r#"<shape type="sphere"><bsdf type="{plugin}"/></shape>"#),
        ("emitter", "area" | "directionalarea") => {
            format!(r#"<shape type="sphere"><emitter type="{plugin}"/></shape>"#)
        }
        ("emitter", _) => format!(r#"<emitter type="{plugin}"/>"#),
        ("film", _) => format!(r#"<sensor type="perspective"><film type="{plugin}"/></sensor>"#),
        ("integrator", "moment") => {
            r#"<integrator type="moment"><integrator type="path"/></integrator>"#.into()
        }
        ("integrator", _) => format!(r#"<integrator type="{plugin}"/>"#),
        ("medium", _) => format!(r#"<medium type="{plugin}"/>"#),
        ("phase", _) => format!(r#"<medium type="homogeneous"><phase type="{plugin}"/></medium>"#),
        ("volume", _) => {
            format!(r#"<medium type="heterogeneous"><volume name="sigma_t" type="{plugin}"/></medium>"#)
        }
        ("rfilter", _) => {
            format!(
                r#"<sensor type="perspective"><film type="hdrfilm"><rfilter type="{plugin}"/></film></sensor>"#
            )
        }
        ("sampler", _) => format!(r#"<sensor type="perspective"><sampler type="{plugin}"/></sensor>"#),
        ("sensor", "thinlens") => {
            r#"<sensor type="thinlens"><float name="aperture_radius" value="0.1"/></sensor>"#.into()
        }
        // Mitsuba refuses the default film (768×576) for a radiance meter, as caustic does.
        ("sensor", "radiancemeter") => r#"<sensor type="radiancemeter"><film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film></sensor>"#.into(),
        // The irradiance meter lives in a shape, as in Mitsuba.
        ("sensor", "irradiancemeter") => r#"<shape type="sphere"><sensor type="irradiancemeter"/></shape>"#.into(),
        ("sensor", _) => format!(r#"<sensor type="{plugin}"/>"#),
        // Mitsuba requires a group's id and an instance's group, as caustic does.
        ("shape", "shapegroup") => r#"<shape type="shapegroup" id="g"><shape type="sphere"/></shape>"#.into(),
        ("shape", "instance") => {
            r#"<shape type="shapegroup" id="g"><shape type="sphere"/></shape><shape type="instance"><ref id="g"/></shape>"#.into()
        }
        ("shape", _) => format!(r#"<shape type="{plugin}"/>"#),
        // Mitsuba requires each spectrum's own values (d65 has defaults).
        ("spectrum", _) => {
            let values = match plugin {
                "srgb" => r#"<rgb name="color" value="0.5"/>"#,
                "uniform" | "rawconstant" => r#"<float name="value" value="2"/>"#,
                "regular" => r#"<float name="wavelength_min" value="400"/><float name="wavelength_max" value="700"/><string name="values" value="1, 2"/>"#,
                "irregular" => r#"<string name="wavelengths" value="400, 700"/><string name="values" value="1, 2"/>"#,
                "blackbody" => r#"<float name="temperature" value="3000"/>"#,
                _ => "",
            };
            format!(
                r#"<shape type="sphere"><emitter type="area"><spectrum name="radiance" type="{plugin}">{values}</spectrum></emitter></shape>"#
            )
        }
        ("texture", _) => format!(
            r#"<shape type="sphere"><bsdf type="diffuse"><texture name="reflectance" type="{plugin}"/></bsdf></shape>"#
        ),
        other => panic!("no scene template for {other:?}"),
    })
}

fn load_strict(dir: &Path, name: &str, element: &str) -> Result<caustic::scene::Scene, String> {
    let path = dir.join(format!("{name}.xml"));
    std::fs::write(&path, format!("<scene version=\"3.0.0\">\n{element}\n</scene>\n")).unwrap();
    caustic::load::load_scene_with(&path, &[], caustic::load::LoadOptions { strict: true })
        .map_err(|e| format!("{e:#}"))
}

#[test]
fn readme_lists_every_mitsuba_plugin_and_strict_agrees() {
    let data =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/data/mitsuba_plugins.txt")).unwrap();
    let mitsuba: BTreeSet<(String, String)> = data
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let (family, plugin) = l.split_once(' ').unwrap();
            (family.to_string(), plugin.to_string())
        })
        .collect();
    assert_eq!(
        mitsuba.len(),
        106,
        "the list holds Mitsuba 3.9.1's 106 plugins (100 in C++, 6 Python integrators)"
    );
    let rows = readme_rows();
    let listed: BTreeSet<(String, String)> = rows.iter().map(|(f, p, _)| (f.clone(), p.clone())).collect();
    assert_eq!(listed.len(), rows.len(), "a plugin is listed twice");
    let missing: Vec<_> = mitsuba.difference(&listed).collect();
    let extra: Vec<_> = listed.difference(&mitsuba).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "docs/mitsuba.md lacks {missing:?}; lists unknown {extra:?}"
    );

    let dir: PathBuf = std::env::temp_dir().join(format!("caustic-readme-plugins-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut failures = Vec::new();
    for (family, plugin, status) in &rows {
        let Some(element) = scene_using(family, plugin) else { continue };
        let name = format!("{family}-{plugin}");
        match (status.as_str(), load_strict(&dir, &name, &element)) {
            ("not supported", Ok(_)) => {
                failures.push(format!("{name}: not supported, yet loads under --strict"))
            }
            ("not supported", Err(e)) if !e.contains(&format!("{name}.xml:2")) => {
                failures.push(format!("{name}: refused without naming file and line: {e}"))
            }
            ("supported" | "partial", Err(e)) => {
                failures.push(format!("{name}: {status}, yet refused under --strict: {e}"))
            }
            _ => {}
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        failures.is_empty(),
        "docs/mitsuba.md's plugin table disagrees with the loader:\n{}",
        failures.join("\n")
    );
}
