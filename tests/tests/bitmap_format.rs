//! Mitsuba's `bitmap` storage precision (`format`: auto, variant, float16/fp16, uint8; with and
//! without `raw`) on 8-bit, 16-bit and float images: the texels caustic loads against the values
//! Mitsuba 3.9.1's texture returns at each texel (`tests/data/bitmap_format.json`, written with the
//! images by `bitmap_format.py`), with a negative control; `accel` accepted; an unknown format and a
//! value half precision cannot hold refused, naming the file and line.
use caustic_tests::*;

fn texture_xml(file: &str, format: &str, raw: bool) -> String {
    let path = test_data(file);
    format!(
        r#"<scene version="3.0.0">
    <shape type="sphere"><bsdf type="diffuse">
        <texture name="reflectance" type="bitmap">
            <string name="filename" value="{}"/><string name="format" value="{format}"/>
            <boolean name="raw" value="{raw}"/><boolean name="accel" value="false"/>
            <string name="filter_type" value="nearest"/></texture></bsdf></shape>
</scene>"#,
        path.display()
    )
}

/// The loaded texels of `file` under `format` and `raw`.
fn texels(file: &str, format: &str, raw: bool) -> anyhow::Result<Vec<f32>> {
    let scene = try_load_xml(&texture_xml(file, format, raw), &format!("bitmap-{format}-{raw}"), &[])?;
    Ok(scene.textures[0].texels.clone())
}

/// The largest difference between `got` and Mitsuba's `texels`, relative to the value (1e-30
/// below it: absolute).
fn worst(got: &[f32], want: &serde_json::Value) -> f64 {
    let want: Vec<f64> = want
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|t| t.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()))
        .collect();
    assert_eq!(got.len(), want.len());
    got.iter().zip(&want).map(|(&g, &w)| (g as f64 - w).abs() / w.abs().max(1e-30)).fold(0.0, f64::max)
}

/// The largest difference between `got` and Mitsuba's `texels` in steps of 1/255, of the values
/// sRGB-encoded if `encoded`.
fn worst_steps(got: &[f32], want: &serde_json::Value, encoded: bool) -> f64 {
    let want = want
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|t| t.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()));
    let encode = |v: f32| if encoded { caustic::load::image_io::linear_to_srgb(v) } else { v };
    got.iter()
        .zip(want)
        .map(|(&g, w)| (encode(g) as f64 - encode(w as f32) as f64).abs() * 255.0)
        .fold(0.0, f64::max)
}

#[test]
fn bitmap_storage_formats_match_mitsuba() {
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(test_data("bitmap_format.json")).unwrap()).unwrap();
    let cases = data["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 30);
    for case in cases {
        let (file, format, raw) = (
            case["file"].as_str().unwrap(),
            case["format"].as_str().unwrap(),
            case["raw"].as_bool().unwrap(),
        );
        let got = texels(file, format, raw).unwrap_or_else(|e| panic!("{file} {format}: {e:#}"));
        if format == "uint8" && file != "bitmap_format_8.png" {
            // Mitsuba's conversion of 16-bit and float samples to 8 bits is not always the nearest
            // step, and not by position-independent rules (0.5 became 127/255 and 0.75 192/255 in
            // one image; 16-bit 33333/65535 (129.7 steps) 129, 60000 (233.46) 234): it looks
            // dithered. caustic rounds to the nearest step: within one step of Mitsuba's (in the
            // encoded values for sRGB-encoded files).
            let steps = worst_steps(&got, &case["texels"], file.ends_with(".png") && !raw);
            println!("{file}, format {format}, raw {raw}: largest difference {steps:.3} steps of 1/255");
            assert!(steps < 1.001, "{file}, format {format}, raw {raw}: {steps} steps of 1/255 from Mitsuba");
            continue;
        }
        let error = worst(&got, &case["texels"]);
        println!("{file}, format {format}, raw {raw}: largest relative difference {error:.1e}");
        // f32 rounding of the sRGB curve: Mitsuba's and caustic's differ in the last bits.
        assert!(error < 2e-6, "{file}, format {format}, raw {raw}: {error:.1e} from Mitsuba");
    }
    // Negative control: f32 storage where Mitsuba rounds (a 16-bit file's default half precision,
    // a float file in 8 bits) is caught.
    for (file, format, stored_as) in
        [("bitmap_format_16.png", "auto", "variant"), ("bitmap_format.exr", "uint8", "variant")]
    {
        let case =
            cases.iter().find(|c| c["file"] == file && c["format"] == format && c["raw"] == false).unwrap();
        let error = worst(&texels(file, stored_as, false).unwrap(), &case["texels"]);
        assert!(error > 1e-4, "{file}: {stored_as} storage passes for {format} ({error:.1e})");
    }
}

#[test]
fn bitmap_format_refusals_name_file_and_line() {
    let error = format!("{:#}", texels("bitmap_format.exr", "half", false).unwrap_err());
    println!("{error}");
    assert!(error.contains("scene.xml:3: ") && error.contains("not 'half'"), "{error}");
    // A texel of 70000 overflows half precision (Mitsuba would store infinity).
    let dir = std::env::temp_dir().join(format!("caustic-bitmap-overflow-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exr = dir.join("big.exr");
    let film = caustic::output::film::Film {
        width: 2,
        height: 1,
        rgb: vec![[0.5, 70000.0, 1.0], [0.1, 0.2, 0.3]],
        variance: None,
        invalid_samples: 0,
        comment: None,
        sum_variance_factor: 1.0,
        aovs: Vec::new(),
    };
    film.save(&exr).unwrap();
    let xml = texture_xml("x", "float16", false)
        .replace(&test_data("x").display().to_string(), &exr.display().to_string());
    let error = format!("{:#}", try_load_xml(&xml, "bitmap-overflow", &[]).unwrap_err());
    std::fs::remove_dir_all(&dir).ok();
    println!("{error}");
    assert!(error.contains("scene.xml:3: ") && error.contains("texel (0, 0) holds 70000"), "{error}");
}
