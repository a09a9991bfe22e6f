//! Mitsuba's `aov` and `depth` integrators (`caustic::output::aov`): every channel of a render of
//! `tests/data/aov.xml` (the image, the nested integrator's copy with its alpha, and each AOV type)
//! against Mitsuba 3.9.1's EXR (`aov.py`), on the CPU and on the GPU backend (lavapipe), with the
//! channel names read from both files; the `depth` integrator against Mitsuba's; a negative control
//! (the scene's Gaussian filter replaced by a box must be caught); never a non-finite value; and
//! bad `aovs` strings refused with file and line.
//!
//! What the comparison catches (CPU, 256 spp, measured): the depth measured from the camera instead
//! of the near clip plane (Mitsuba's ray origin) 76% of the depth channel's pixels agreeing; the
//! facet normal given as `sh_normal` on the smooth OBJ 97% (`nn.X`); a box filter in place of the
//! scene's Gaussian, every channel (84–97%).
use caustic::backend::BackendChoice;
use caustic::output::aov::exr::read_channels;
use caustic::output::film::Film;
use caustic::prepare::buffers;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 4096.0;
/// Per-pixel |z| above which a value disagrees (about 1% of 3072 pixels by chance, Šidák).
const Z_LIMIT: f64 = 4.5;

/// Renders `aov.xml` (with `defines_`) at `spp` on `choice` and adds its AOVs, as `caustic render`
/// does; the film and its EXR file's channels.
fn render(choice: BackendChoice, spp: u32, defines_: &[(&str, &str)]) -> (Film, Vec<(String, Vec<f32>)>) {
    let scene = caustic::load::load_scene(&test_data("aov.xml"), &defines(defines_)).expect("loads");
    let built = buffers::build(&scene).expect("builds");
    let seed = 3;
    let mut film = render_buffers(&built, choice, spp, seed);
    caustic::output::aov::add_to(&mut film, &built, spp, seed);
    let path = std::env::temp_dir().join(format!("caustic-aov-{}-{choice:?}.exr", std::process::id()));
    film.save(&path).expect("EXR written");
    let (w, h, channels) = read_channels(&path).expect("EXR read back");
    std::fs::remove_file(&path).ok();
    assert_eq!((w, h), (film.width, film.height));
    for (name, values) in &channels {
        assert!(values.iter().all(|v| v.is_finite()), "{choice:?}: channel {name} has a non-finite value");
    }
    (film, channels)
}

/// Per channel (`film`'s image and AOVs against the reference's channel of that name): the fraction
/// of pixels agreeing, a pixel agreeing where its difference is within `Z_LIMIT` standard errors
/// (the render's variance of the mean, and the reference's, scaled from it by the sample counts) or
/// below 1e-3·(1 + |reference|) (a value constant over the pixel has no variance: normals of a flat
/// face, the index of one shape); the RMSE for the record. An AOV jumps where the filter's footprint
/// crosses an edge, and a footprint whose tail (the Gaussian's beyond 1.5 pixels holds 0.3% of it
/// per axis) reaches another surface with a probability below 1/spp shows no variance in `spp`
/// samples (measured: 1.3% of the depth channel's pixels failed on that alone, the render 0 where
/// Mitsuba had 0.003, or 6.064 ± 0.0009 against 6.046); so an AOV's standard error is at least the
/// channel's largest |value| over `spp`, the value of one sample in `spp` landing elsewhere.
fn agreement(film: &Film, spp: u32, reference: &[(String, Vec<f32>)]) -> Vec<(String, f64, f64)> {
    agreement_at(film, spp, reference, REFERENCE_SPP)
}

/// `agreement` with a reference of `reference_spp` samples.
fn agreement_at(
    film: &Film,
    spp: u32,
    reference: &[(String, Vec<f32>)],
    reference_spp: f64,
) -> Vec<(String, f64, f64)> {
    let mut ours: Vec<(String, Vec<f32>, Vec<f64>)> = Vec::new();
    let variance = film.variance.as_ref().expect("the image's variance");
    for (c, name) in ["R", "G", "B"].iter().enumerate() {
        ours.push((
            name.to_string(),
            film.rgb.iter().map(|p| p[c]).collect(),
            variance.iter().map(|p| p[c]).collect(),
        ));
    }
    for a in &film.aovs {
        ours.push((a.name.clone(), a.values.clone(), a.variance.clone().expect("an AOV's variance")));
    }
    let ratio = spp as f64 / reference_spp;
    let image =
        |name: &str| ["R", "G", "B"].iter().any(|c| name == *c || name.ends_with(&format!("image.{c}")));
    ours.iter()
        .map(|(name, values, var)| {
            let (_, r) = reference.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no {name}"));
            let largest = r.iter().fold(0.0f64, |m, v| m.max(v.abs() as f64));
            let floor = if image(name) && !film.aovs.is_empty() { 0.0 } else { largest / spp as f64 };
            let mut pass = 0usize;
            let mut sq = 0.0;
            for i in 0..values.len() {
                let d = (values[i] - r[i]) as f64;
                sq += d * d;
                let sigma = (var[i] * (1.0 + ratio)).sqrt().max(floor);
                if d.abs() <= Z_LIMIT * sigma || d.abs() <= 1e-3 * (1.0 + r[i].abs() as f64) {
                    pass += 1;
                }
            }
            (name.clone(), pass as f64 / values.len() as f64, (sq / values.len() as f64).sqrt())
        })
        .collect()
}

fn names(channels: &[(String, Vec<f32>)]) -> Vec<String> {
    channels.iter().map(|(n, _)| n.clone()).collect()
}

#[test]
fn every_aov_matches_mitsuba() {
    let (_, _, reference) = read_channels(&test_data("aov.exr")).expect("reference loads");
    for (choice, spp) in [(BackendChoice::Cpu, 256), (BackendChoice::Gpu, 128)] {
        let (film, channels) = render(choice, spp, &[]);
        assert_eq!(names(&channels), names(&reference), "{choice:?}: channel names differ from Mitsuba's");
        for (name, pass, rmse) in agreement(&film, spp, &reference) {
            println!("{choice:?} {spp} spp: {name:<12} pass {pass:.4}, RMSE {rmse:.5}");
            assert!(pass >= 0.99, "{choice:?}: channel {name}: only {:.2}% of pixels agree", pass * 100.0);
        }
    }
}

/// The AOVs are averaged through the reconstruction filter: the same scene with a box filter
/// instead of the Gaussian must disagree with Mitsuba's Gaussian-filtered channels at the edges.
#[test]
fn a_box_filter_is_caught() {
    let (_, _, reference) = read_channels(&test_data("aov.exr")).expect("reference loads");
    let spp = 256;
    let (film, _) = render(BackendChoice::Cpu, spp, &[("filter", "box")]);
    let failing: Vec<String> = agreement(&film, spp, &reference)
        .into_iter()
        .filter(|(_, pass, _)| *pass < 0.99)
        .map(|(name, pass, _)| format!("{name} {pass:.3}"))
        .collect();
    println!("box filter (negative control): channels caught: {failing:?}");
    assert!(failing.len() >= 10, "a box filter went unnoticed in most channels: {failing:?}");
}

/// Mitsuba's `depth` integrator: the distance as R = G = B, 0 where the ray meets nothing.
#[test]
fn depth_integrator_matches_mitsuba() {
    let xml = std::fs::read_to_string(test_data("aov.xml")).expect("scene");
    let start = xml.find("<integrator type=\"aov\">").expect("aov integrator");
    let end = xml.find("<sensor").expect("sensor");
    let depth_xml = format!("{}<integrator type=\"depth\"/>\n    {}", &xml[..start], &xml[end..]);
    // Loaded from a temporary folder: the mesh by its full path.
    let mesh = test_data("aov_mesh.obj");
    let depth_xml = depth_xml.replace("\"aov_mesh.obj\"", &format!("\"{}\"", mesh.display()));
    let scene = try_load_xml(&depth_xml, "depth", &[]).expect("loads");
    let built = buffers::build(&scene).expect("builds");
    let spp = 256;
    let mut film = render_buffers(&built, BackendChoice::Cpu, spp, 5);
    caustic::output::aov::add_to(&mut film, &built, spp, 5);
    assert!(film.aovs.is_empty(), "the depth integrator writes no extra channels");
    let (_, _, reference) = read_channels(&test_data("aov_depth.exr")).expect("reference loads");
    assert_eq!(names(&reference), ["B", "G", "R"], "Mitsuba's depth image is RGB");
    for (name, pass, rmse) in agreement(&film, spp, &reference) {
        println!("depth {name}: pass {pass:.4}, RMSE {rmse:.5}");
        assert!(pass >= 0.99, "depth {name}: only {:.2}% of pixels agree", pass * 100.0);
    }
    assert!(film.rgb.iter().all(|p| p[0] == p[1] && p[1] == p[2]), "R, G and B differ");
    assert_eq!(film.rgb[0], [0.0; 3], "the top-left corner is background: depth 0");
}

/// Bad `aovs` strings and unsupported types are refused with the file and line.
#[test]
fn bad_aov_lists_are_refused_with_file_and_line() {
    let scene = |aovs: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"aov\">\n<string name=\"aovs\" value=\"{aovs}\"/>\n\
             </integrator>\n<shape type=\"sphere\"/>\n</scene>"
        )
    };
    for (aovs, expected) in [
        ("dd:depth,nn:normals", "unknown type 'normals'"),
        ("dd", "not a <name>:<type> pair"),
        (":depth", "not a <name>:<type> pair"),
        ("a:b:depth", "not a <name>:<type> pair"),
    ] {
        let message = format!("{:#}", try_load_xml(&scene(aovs), "bad-aovs", &[]).expect_err(aovs));
        assert!(message.contains("scene.xml:2"), "{aovs}: no file and line in: {message}");
        assert!(message.contains(expected), "{aovs}: {message}");
    }
    // Screen-space uv derivatives are left out with a warning (an error under --strict).
    let loaded = try_load_xml(&scene("dd:depth,d:duv_dx"), "duv", &[]).expect("loads");
    assert_eq!(loaded.aovs.expect("aovs").aovs.len(), 1);
    assert!(loaded.warnings.iter().any(|w| w.contains("duv_dx")), "{:?}", loaded.warnings);
}

/// Without a nested integrator the image is black and only the AOV channels follow it (Mitsuba
/// 3.9.1 wrote `R G B dd.y.T nn.X nn.Y nn.Z` for `dd.y:depth,nn:sh_normal` alone); with neither
/// AOVs nor a nested integrator, a black image and no extra channel.
#[test]
fn an_aov_integrator_without_nested_integrator_renders_black() {
    let scene = |aovs: &str| {
        format!(
            "<scene version=\"3.0.0\"><integrator type=\"aov\"><string name=\"aovs\" value=\"{aovs}\"/>\
             </integrator><shape type=\"sphere\"/><emitter type=\"constant\"/></scene>"
        )
    };
    for (aovs, names) in [("dd.y:depth,nn:sh_normal", vec!["dd.y.T", "nn.X", "nn.Y", "nn.Z"]), ("", vec![])] {
        let loaded = try_load_xml(&scene(aovs), "no-nested", &[]).expect("loads");
        let built = buffers::build(&loaded).expect("builds");
        let mut film = render_buffers(&built, BackendChoice::Cpu, 4, 1);
        caustic::output::aov::add_to(&mut film, &built, 4, 1);
        assert!(film.rgb.iter().all(|p| *p == [0.0; 3]), "{aovs:?}: the image is not black");
        assert_eq!(film.aovs.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(), names, "{aovs:?}");
        if let Some(depth) = film.aovs.first() {
            assert!(depth.values.iter().any(|&d| d > 0.0), "the sphere is not in the depth channel");
        }
    }
}

/// Shading normals (and albedo, shape indices) under normal and bump maps, against Mitsuba: the
/// map's tilted normal in world space, except inside a `twosided` that wraps the map, which gives
/// the untilted one. Measured before that rule was written (the tilted normal in the shading
/// frame's coordinates, as the kernel keeps it): the mapped sphere, disk and rectangle off by a mean
/// |difference| of 0.3 to 1.0 per component; after it, 0.002 to 0.008.
#[test]
fn shading_normals_under_normal_and_bump_maps_match_mitsuba() {
    let loaded = caustic::load::load_scene(&test_data("aov_normalmap.xml"), &[]).expect("loads");
    let built = buffers::build(&loaded).expect("builds");
    let spp = 256;
    let mut film = render_buffers(&built, BackendChoice::Cpu, spp, 7);
    caustic::output::aov::add_to(&mut film, &built, spp, 7);
    let (_, _, reference) = read_channels(&test_data("aov_normalmap.exr")).expect("reference loads");
    for (name, pass, rmse) in agreement_at(&film, spp, &reference, 1024.0) {
        println!("normal maps {name:<8} pass {pass:.4}, RMSE {rmse:.5}");
        assert!(pass >= 0.99, "normal maps: channel {name}: only {:.2}% of pixels agree", pass * 100.0);
    }
}
