//! Spectrum plugins written out as objects (`<spectrum type="srgb|uniform|d65|rawconstant|regular|
//! irregular|blackbody">`): caustic's colour for each against what Mitsuba 3.9.1 renders
//! (`tests/data/spectrum_plugins.json`, written by `spectrum_plugins.py`: `scalar_rgb` for the
//! constant ones, `scalar_spectral` for the spectra, which Mitsuba's rgb variants refuse to render),
//! and the scenes Mitsuba refuses refused with file and line.
use serde_json::Value;
use std::path::PathBuf;

/// caustic's colour for the case (the emitter's radiance or the BSDF's reflectance), or its error.
fn load(case: &Value, dir: &std::path::Path) -> Result<[f32; 3], String> {
    let spectrum = case["spectrum"].as_str().unwrap();
    let emission = case["usage"] == "emission";
    let body = if emission {
        format!(r#"<shape type="rectangle"><emitter type="area">{spectrum}</emitter></shape>"#)
    } else {
        format!(r#"<shape type="rectangle"><bsdf type="diffuse">{spectrum}</bsdf></shape>"#)
    };
    let path = dir.join(format!("{}.xml", case["name"].as_str().unwrap()));
    std::fs::write(&path, format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")).unwrap();
    let scene = caustic::load::mitsuba::load(&path, &[]).map_err(|e| format!("{e:#}"))?;
    let shape = &scene.shapes[0];
    Ok(if emission {
        shape.emission.expect("an area emitter")
    } else {
        let r = scene.materials[shape.material as usize].reflectance;
        [r[0], r[1], r[2]]
    })
}

#[test]
fn spectrum_plugins_match_mitsuba() {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/spectrum_plugins.json");
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&data).unwrap()).unwrap();
    let dir = std::env::temp_dir().join(format!("caustic-spectrum-plugins-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = doc["cases"].as_array().unwrap();
    let mut failures = Vec::new();
    for case in cases {
        let name = case["name"].as_str().unwrap();
        match (case.get("error"), load(case, &dir)) {
            (Some(_), Ok(rgb)) => {
                failures.push(format!("{name}: Mitsuba refuses it, caustic loads it as {rgb:?}"))
            }
            (Some(_), Err(e)) if !e.contains(&format!("{name}.xml:")) => {
                failures.push(format!("{name}: refused without naming file and line: {e}"))
            }
            (Some(_), Err(_)) => {}
            (None, Err(e)) => failures.push(format!("{name}: Mitsuba renders it, caustic refuses it: {e}")),
            (None, Ok(rgb)) => {
                let tolerance = case["tolerance"].as_f64().unwrap();
                let mitsuba: Vec<f64> =
                    case["mitsuba"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
                let off = (0..3)
                    .any(|c| (rgb[c] as f64 - mitsuba[c]).abs() > tolerance * mitsuba[c].abs().max(1e-3));
                if off {
                    failures.push(format!(
                        "{name}: Mitsuba {mitsuba:?}, caustic {rgb:?} (tolerance {tolerance})"
                    ));
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    caustic_tests::assert_cases_match_mitsuba(&failures, cases.len());
}

/// The negative control: a blackbody 1% hotter (3030 K for 3000 K: red about 8% brighter) falls
/// outside the tolerance the test above allows the spectral cases.
#[test]
fn the_blackbody_tolerance_resolves_a_wrong_temperature() {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/spectrum_plugins.json");
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&data).unwrap()).unwrap();
    let case = doc["cases"].as_array().unwrap().iter().find(|c| c["name"] == "blackbody_3000").unwrap();
    let dir = std::env::temp_dir().join(format!("caustic-spectrum-control-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut wrong = case.clone();
    wrong["spectrum"] = Value::from(case["spectrum"].as_str().unwrap().replace("3000", "3030"));
    let rgb = load(&wrong, &dir).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let mitsuba: Vec<f64> = case["mitsuba"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let worst = (0..3).map(|c| (rgb[c] as f64 / mitsuba[c] - 1.0).abs()).fold(0.0, f64::max);
    let tolerance = case["tolerance"].as_f64().unwrap();
    assert!(worst > tolerance, "1% hotter is within the tolerance: {rgb:?} against {mitsuba:?}");
}
