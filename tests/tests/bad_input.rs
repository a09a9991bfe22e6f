//! Bad input gives clear errors naming file and line (never a panic); unsupported elements give
//! warnings naming element and line, and the rest of the scene still loads.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use std::path::PathBuf;

fn write_scene(name: &str, body: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("caustic-bad-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, body).unwrap();
    path
}

fn load_err(name: &str, body: &str) -> String {
    let path = write_scene(name, body);
    match caustic::load::load_scene(&path, &[]) {
        Ok(_) => panic!("{name} loaded but should not"),
        Err(e) => format!("{e:#}"),
    }
}

const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;

#[test]
fn malformed_xml_names_file_and_line() {
    let e = load_err(
        "malformed.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n  </shap>\n</scene>\n",
    );
    assert!(e.contains("malformed.xml:3"), "{e}");
}

#[test]
fn missing_mesh_names_file_line_and_mesh() {
    let e = load_err("missing.xml", "<scene version=\"3.0.0\">\n\n  <shape type=\"obj\"><string name=\"filename\" value=\"nope.obj\"/></shape>\n</scene>\n");
    assert!(e.contains("missing.xml:3") && e.contains("nope.obj"), "{e}");
}

#[test]
fn broken_mesh_is_an_error_not_a_panic() {
    write_scene("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    let e = load_err("uses-broken.xml", "<scene version=\"3.0.0\">\n  <shape type=\"obj\"><string name=\"filename\" value=\"broken.obj\"/></shape>\n</scene>\n");
    assert!(e.contains("uses-broken.xml:2"), "{e}");
}

#[test]
fn absurd_parameters_are_rejected() {
    for (what, body) in [
        ("fov", r#"<sensor type="perspective"><float name="fov" value="0"/></sensor>"#),
        ("radius", r#"<shape type="sphere"><float name="radius" value="-1"/></shape>"#),
        (
            "film",
            r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="0"/></film></sensor>"#,
        ),
        ("number", r#"<sensor type="perspective"><float name="fov" value="wide"/></sensor>"#),
        ("nan", r#"<sensor type="perspective"><float name="fov" value="nan"/></sensor>"#),
        ("max_depth", r#"<integrator type="path"><integer name="max_depth" value="-7"/></integrator>"#),
        ("reflectance", r#"<bsdf type="diffuse"><rgb name="reflectance" value="1, -2, 3"/></bsdf>"#),
        (
            "direct",
            r#"<integrator type="direct"><integer name="emitter_samples" value="0"/><integer name="bsdf_samples" value="0"/></integrator>"#,
        ),
        (
            "direct_negative",
            r#"<integrator type="direct"><integer name="bsdf_samples" value="-1"/></integrator>"#,
        ),
        ("fuzz", r#"<bsdf type="fuzzymetal"><float name="fuzz" value="1.5"/></bsdf>"#),
    ] {
        let e = load_err(
            &format!("absurd-{what}.xml"),
            &format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n"),
        );
        assert!(e.contains(&format!("absurd-{what}.xml:2")), "{what}: {e}");
    }
}

#[test]
fn undefined_parameter_is_named() {
    let e = load_err("undefined.xml", "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"$zoom\"/></sensor>\n</scene>\n");
    assert!(e.contains("$zoom") && e.contains("undefined.xml:2"), "{e}");
}

#[test]
fn unsupported_elements_warn_and_the_rest_loads() {
    let path = write_scene(
        "unsupported.xml",
        &format!("<scene version=\"3.0.0\">\n{SENSOR}\n<emitter type=\"sunsky\"/>\n<shape type=\"sphere\"><float name=\"wobble\" value=\"2\"/></shape>\n<shape type=\"teapot\"/>\n</scene>\n"),
    );
    let scene = caustic::load::load_scene(&path, &[]).expect("loads with warnings");
    assert_eq!(scene.shapes.len(), 1, "the supported sphere is kept");
    let w = scene.warnings.join("\n");
    assert!(w.contains("unsupported.xml:3") && w.contains("emitter"), "{w}");
    assert!(w.contains("unsupported.xml:4") && w.contains("wobble"), "{w}");
    assert!(w.contains("unsupported.xml:5") && w.contains("teapot"), "{w}");
}

/// Without `--strict`, a scene with deviations (unsupported plugins substituted or left out,
/// properties not read) still loads, with one warning per kind of deviation however many instances
/// (saying how many more and where the last is) and one summary line counting them. With
/// `--strict` the same scene is refused, every deviation named with its file and line.
#[test]
fn deviations_warn_once_per_kind_and_strict_refuses_them() {
    let hair = "<shape type=\"sphere\"><bsdf type=\"hair\"/></shape>";
    let path = write_scene(
        "deviations.xml",
        &format!(
            "<scene version=\"3.0.0\">\n{SENSOR}\n{hair}\n{hair}\n{hair}\n<shape type=\"sphere\"><float name=\"wobble\" value=\"2\"/></shape>\n<emitter type=\"sunsky\"/>\n</scene>\n"
        ),
    );
    let scene = caustic::load::load_scene(&path, &[]).expect("loads without --strict");
    assert_eq!(scene.shapes.len(), 4, "the substituted BSDFs' shapes are kept");
    let about_hair: Vec<&String> = scene.warnings.iter().filter(|w| w.contains("'hair'")).collect();
    assert_eq!(about_hair.len(), 1, "one warning for three hair BSDFs: {:?}", scene.warnings);
    assert!(
        about_hair[0].contains("deviations.xml:3")
            && about_hair[0].contains("2 more like it, the last at")
            && about_hair[0].contains("deviations.xml:5"),
        "{}",
        about_hair[0]
    );
    let summary = scene.warnings.last().expect("a summary line");
    assert!(
        summary.contains("4 elements substituted")
            && summary.contains("1 property ignored")
            && summary.contains("3 kinds of deviation")
            && summary.contains("--strict"),
        "{summary}"
    );
    assert_eq!(scene.warnings.len(), 4, "hair, wobble, sunsky and the summary: {:?}", scene.warnings);

    let strict = caustic::load::LoadOptions { strict: true };
    let e =
        format!("{:#}", caustic::load::load_scene_with(&path, &[], strict).expect_err("--strict refuses it"));
    for needle in [
        "deviations.xml:3",
        "hair",
        "deviations.xml:5",
        "deviations.xml:6",
        "wobble",
        "deviations.xml:7",
        "sunsky",
    ] {
        assert!(e.contains(needle), "{needle} not in: {e}");
    }

    // A scene caustic reads as written loads under --strict, and without a summary line.
    let clean = write_scene(
        "clean.xml",
        &format!("<scene version=\"3.0.0\">\n{SENSOR}\n<shape type=\"sphere\"/>\n</scene>\n"),
    );
    let scene = caustic::load::load_scene_with(&clean, &[], strict).expect("a clean scene loads strictly");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

/// Every scene shipped in scenes/ and every shared Mitsuba scene the conformance test renders is read
/// as written: each loads under `--strict`.
#[test]
fn shipped_and_reference_scenes_load_strictly() {
    let strict = caustic::load::LoadOptions { strict: true };
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    if let Some(shared) = caustic_tests::shared_dir_if_present() {
        let dir = shared.join("scenes/mitsuba");
        let list = std::fs::read_to_string(dir.join("SCENES.txt")).unwrap();
        scenes.extend(list.lines().filter(|l| !l.trim().is_empty()).map(|l| dir.join(l.trim())));
    }
    assert!(scenes.len() >= 6, "{scenes:?}");
    for path in &scenes {
        // As the conformance test (and Mitsuba's reference renders): some scenes use $spp undefined.
        if let Err(e) =
            caustic::load::load_scene_with(path, &caustic_tests::defines(&[("spp", "16")]), strict)
        {
            panic!("{} does not load under --strict: {e:#}", path.display());
        }
    }
}

#[test]
fn defaults_and_overrides() {
    let path = write_scene("defaults.xml", "<scene version=\"3.0.0\">\n<default name=\"res\" value=\"8\"/>\n<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"$res\"/><integer name=\"height\" value=\"$res\"/></film></sensor>\n</scene>\n");
    let scene = caustic::load::load_scene(&path, &[]).unwrap();
    assert_eq!(scene.sensor.width, 8);
    let scene = caustic::load::load_scene(&path, &[("res".into(), "12".into())]).unwrap();
    assert_eq!((scene.sensor.width, scene.sensor.height), (12, 12));
}

#[test]
fn moment_renders_its_nested_integrator() {
    let path = write_scene(
        "moment.xml",
        &format!("<scene version=\"3.0.0\">\n{SENSOR}\n<integrator type=\"moment\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/></integrator></integrator>\n</scene>\n"),
    );
    let scene = caustic::load::load_scene(&path, &[]).expect("loads");
    assert_eq!(scene.integrator.max_depth, 3, "the nested path integrator's settings apply");
    let bad = write_scene(
        "moment_empty.xml",
        &format!("<scene version=\"3.0.0\">\n{SENSOR}\n<integrator type=\"moment\"/>\n</scene>\n"),
    );
    let e = format!("{:#}", caustic::load::load_scene(&bad, &[]).unwrap_err());
    assert!(e.contains("moment_empty.xml:3") && e.contains("nested"), "{e}");
}

/// Loading is linear in the number of elements: 20,000 spheres load (the time is printed; each
/// element's line used to be found by scanning the file from its start), and the line named for the
/// last of them is still right.
#[test]
fn twenty_thousand_spheres_load() {
    const SPHERES: usize = 20_000;
    let mut body = format!("<scene version=\"3.0.0\">\n{SENSOR}\n");
    for i in 0..SPHERES {
        body.push_str(&format!(
            "<shape type=\"sphere\"><point name=\"center\" x=\"{i}\" y=\"0\" z=\"0\"/><float name=\"radius\" value=\"0.4\"/></shape>\n"
        ));
    }
    // Line SPHERES + 3: a parameter nobody reads, to check the line named in its warning.
    body.push_str("<shape type=\"sphere\"><float name=\"wobble\" value=\"2\"/></shape>\n</scene>\n");
    let path = write_scene("spheres.xml", &body);
    let start = std::time::Instant::now();
    let scene = caustic::load::load_scene(&path, &[]).expect("loads");
    println!("{} spheres loaded in {:.3} s", SPHERES + 1, start.elapsed().as_secs_f64());
    assert_eq!(scene.shapes.len(), SPHERES + 1);
    let w = scene.warnings.join("\n");
    assert!(w.contains(&format!("spheres.xml:{}", SPHERES + 3)) && w.contains("wobble"), "{w}");
}

/// What Mitsuba refuses is an error here too, naming file and line, rather than a silent choice: an
/// `id` given twice, two BSDFs (or two area emitters) in one shape, two integrators.
#[test]
fn what_mitsuba_refuses_is_an_error() {
    for (what, body, needle) in [
        (
            "duplicate-id",
            "<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"conductor\" id=\"a\"/>",
            "duplicate id",
        ),
        (
            "duplicate-id-kinds",
            "<texture type=\"checkerboard\" id=\"a\"/>\n<shape type=\"sphere\" id=\"a\"/>",
            "duplicate id",
        ),
        (
            "two-bsdfs",
            "<bsdf type=\"diffuse\" id=\"grey\"/>\n<shape type=\"sphere\"><bsdf type=\"diffuse\"/><ref id=\"grey\"/></shape>",
            "BSDF",
        ),
        (
            "two-nested-bsdfs",
            "<shape type=\"sphere\"><bsdf type=\"diffuse\"/>\n<bsdf type=\"conductor\"/></shape>",
            "BSDF",
        ),
        (
            "two-emitters",
            "<shape type=\"sphere\"><emitter type=\"area\"/>\n<emitter type=\"area\"/></shape>",
            "emitter",
        ),
        (
            "two-integrators",
            "<integrator type=\"path\"/>\n<integrator type=\"direct\"/>",
            "integrator",
        ),
    ] {
        // The second definition is on line 4 (the scene's sensor takes line 2).
        let e = load_err(
            &format!("refused-{what}.xml"),
            &format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>\n"),
        );
        assert!(e.contains(&format!("refused-{what}.xml:4")) && e.contains(needle), "{what}: {e}");
    }
}

/// Elements nested 10,000 deep are a clean error naming file and line, not a stack overflow (of the
/// XML parser, or of the loader recursing through `twosided` and `moment`); 256 levels still load.
#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    const DEPTH: usize = 10_000;
    let shape = |inner: &str| format!("<shape type=\"sphere\">\n{inner}</shape>\n");
    let nest = |open: &str, innermost: &str, close: &str| {
        format!("{}{innermost}{}", open.repeat(DEPTH), close.repeat(DEPTH))
    };
    for (what, nested) in [
        ("bsdfs", shape(&nest("<bsdf type=\"twosided\">\n", "<bsdf type=\"diffuse\"/>", "</bsdf>"))),
        ("moments", nest("<integrator type=\"moment\">\n", "<integrator type=\"path\"/>", "</integrator>")),
        ("elements", shape(&nest("<x>\n", "", "</x>"))),
    ] {
        let body = format!("<scene version=\"3.0.0\">\n{nested}</scene>\n");
        let e = load_err(&format!("deep-{what}.xml"), &body);
        assert!(e.contains(&format!("deep-{what}.xml:")) && e.contains("nested"), "{what}: {e}");
    }
    // Just inside the limit (256 levels: scene, shape, 253 BSDFs), on a test thread's small stack.
    let inner = format!(
        "{}<bsdf type=\"diffuse\"/>{}",
        "<bsdf type=\"twosided\">".repeat(252),
        "</bsdf>".repeat(252)
    );
    let path = write_scene("deep-enough.xml", &format!("<scene version=\"3.0.0\">{}</scene>", shape(&inner)));
    assert_eq!(caustic::load::load_scene(&path, &[]).expect("loads").shapes.len(), 1);
}

/// Files that each include the next one twice, 26 deep, ask for 2^26 loads within the depth limit:
/// the total is bounded, and the error comes at once, naming the file and line.
#[test]
fn an_include_explosion_is_bounded() {
    const LEVELS: usize = 26;
    let mut top = PathBuf::new();
    for level in (0..LEVELS).rev() {
        let body = if level + 1 < LEVELS {
            let next = format!("<include filename=\"explode-{}.xml\"/>\n", level + 1);
            format!("<scene version=\"3.0.0\">\n{next}{next}</scene>\n")
        } else {
            "<scene version=\"3.0.0\"/>\n".to_string()
        };
        top = write_scene(&format!("explode-{level}.xml"), &body);
    }
    let start = std::time::Instant::now();
    let e = match caustic::load::load_scene(&top, &[]) {
        Ok(_) => panic!("2^26 includes loaded"),
        Err(e) => format!("{e:#}"),
    };
    assert!(e.contains("more than 10000 files") && e.contains("explode-"), "{e}");
    assert!(start.elapsed().as_secs() < 30, "took {:?}", start.elapsed());
}

/// A scene with nothing to hit renders black on both backends (it panicked the CPU runner: the empty
/// BVH's root was traversed as an inner node).
#[test]
fn a_scene_without_shapes_renders_black() {
    for xml in [
        r#"<scene version="3.0.0"/>"#,
        r#"<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor><emitter type="point"><point name="position" value="0, 0, 1"/></emitter></scene>"#,
    ] {
        let scene = caustic_tests::load_xml(xml, "empty");
        for choice in [caustic::backend::BackendChoice::Cpu, caustic::backend::BackendChoice::Gpu] {
            let mut small = scene.clone();
            small.sensor.width = small.sensor.width.min(8);
            small.sensor.height = small.sensor.height.min(8);
            let film = caustic_tests::render_scene(&small, choice, 2, 1);
            assert!(
                film.rgb.iter().flatten().all(|&c| c == 0.0),
                "{choice:?}: a scene without shapes is not black"
            );
        }
    }
}

/// A film whose accumulator exceeds what this GPU binds is refused before any GPU buffer exists,
/// naming the buffer, the limit, its value and the need (wgpu panicked in `create_bind_group`: on
/// lavapipe, whose binding limit is 128 MiB, any film over 2048×2048).
#[test]
fn a_film_over_the_gpu_binding_limit_is_refused() {
    let adapter = caustic::backend::gpu::adapters().into_iter().next().expect("a Vulkan adapter (lavapipe)");
    let limits = adapter.limits();
    let limit = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    // 32-byte accumulator per pixel: one row more than fits.
    let width = 8192u32;
    let height = (limit / 32 / width as u64 + 1) as u32;
    let mut scene = caustic_tests::load_xml(&format!("<scene version=\"3.0.0\">{SENSOR}</scene>"), "limits");
    (scene.sensor.width, scene.sensor.height) = (width, height);
    let buffers = caustic::prepare::buffers::build(&scene).expect("builds");
    let need = caustic::backend::memory::render_need(&buffers);
    if caustic::system::memory::available().is_some_and(|have| need > have) {
        eprintln!("notice: a {width}×{height} film needs more memory than this machine has; test skipped");
        return;
    }
    let e = match caustic::backend::create(caustic::backend::BackendChoice::Gpu, &buffers) {
        Ok(_) => panic!("a {width}×{height} film was accepted by a GPU binding {limit} bytes"),
        Err(e) => format!("{e:#}"),
    };
    let bytes = (width as u64 * height as u64 * 32).to_string();
    assert!(e.contains("film accumulator") && e.contains("max_") && e.contains(&limit.to_string()), "{e}");
    assert!(e.contains(&bytes), "the need ({bytes} bytes) is not named: {e}");
}

/// A 32768×32768 film (about 120 GiB of host memory) is refused before allocation where the machine
/// has less available (it aborted: "memory allocation failed"); the estimate against a given
/// `MemAvailable` is checked everywhere.
#[test]
fn a_film_larger_than_memory_is_refused() {
    let mut scene = caustic_tests::load_xml(&format!("<scene version=\"3.0.0\">{SENSOR}</scene>"), "memory");
    (scene.sensor.width, scene.sensor.height) = (32768, 32768);
    let buffers = caustic::prepare::buffers::build(&scene).expect("builds");
    let need = caustic::backend::memory::render_need(&buffers);
    assert!(need > 100 << 30, "a 32768² film needs {need} bytes?");
    let e =
        caustic::system::memory::check(need, Some(64 << 30), "a 32768×32768 render").unwrap_err().to_string();
    assert!(e.contains("32768×32768") && e.contains("64.0 GiB available"), "{e}");
    assert_eq!(
        caustic::system::memory::parse_mem_available("MemTotal: 9 kB\nMemAvailable:    2048 kB\n"),
        Some(2 << 20)
    );
    match caustic::system::memory::available() {
        Some(have) if have < need => {
            let e = match caustic::backend::create(caustic::backend::BackendChoice::Cpu, &buffers) {
                Ok(_) => panic!("a render needing {need} bytes started with {have} available"),
                Err(e) => format!("{e:#}"),
            };
            assert!(e.contains("GiB") && e.contains("32768×32768"), "{e}");
        }
        _ => eprintln!("notice: this machine has memory for a 32768² film; only the estimate was checked"),
    }
}

/// Numbers entering a scene from files other than the XML (whose values `Props` checks) are
/// validated where they enter: texels of envmaps and bitmaps (one Inf texel made 60% of the samples
/// NaN, counted as black), MTL colours (`Ke nan` rendered black, a negative `Kd` negative pixels),
/// OBJ coordinates near 1e19 (a panic framing the model), an orthographic camera of scale 0 (a black
/// image); each is refused naming file and position or line.
#[test]
fn hostile_numbers_in_files_are_refused_naming_where() {
    let texels = |name: &str, at: usize, value: f32| {
        let mut rgb = vec![[0.5f32; 3]; 4 * 3];
        rgb[at][1] = value;
        let film = caustic::output::film::Film::from_rgb(4, 3, rgb);
        film.save(&write_scene(name, "").with_file_name(name)).unwrap();
    };
    texels("inf.exr", 4 + 2, f32::INFINITY);
    texels("nan.exr", 2 * 4 + 1, f32::NAN);
    texels("negative.exr", 3, -1.0);
    for (file, element, pixel) in [
        ("inf.exr", "<emitter type=\"envmap\"><string name=\"filename\" value=\"inf.exr\"/></emitter>", "(2, 1)"),
        ("negative.exr", "<emitter type=\"envmap\"><string name=\"filename\" value=\"negative.exr\"/></emitter>", "(3, 0)"),
        (
            "nan.exr",
            "<shape type=\"sphere\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"nan.exr\"/></texture></bsdf></shape>",
            "(1, 2)",
        ),
    ] {
        let e = load_err(&format!("texels-{file}.xml"), &format!("<scene version=\"3.0.0\">\n{element}\n</scene>\n"));
        assert!(e.contains(&format!("texels-{file}.xml:2")) && e.contains(file) && e.contains(pixel), "{file}: {e}");
    }

    let obj = "mtllib hostile.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
    for (what, mtl, needle) in [
        ("ke-nan", "newmtl a\nKd 0.5 0.5 0.5\nnewmtl m\nKd 0.5 0.5 0.5\nKe nan 1 1\n", "hostile.mtl:5"),
        ("kd-negative", "newmtl m\n\nKd 0.5 -0.5 0.5\n", "hostile.mtl:3"),
    ] {
        write_scene("hostile.mtl", mtl);
        let e = load_err(&format!("{what}.obj"), obj);
        assert!(e.contains(needle) && e.contains("'m'"), "{what}: {e}");
    }
    write_scene("hostile.mtl", "newmtl m\nKd 0.5 0.5 0.5\n");
    let e = load_err("huge.obj", "mtllib hostile.mtl\nv -2e19 0 0\nv 2e19 0 0\nv 0 2e19 0\nf 1 2 3\n");
    assert!(e.contains("huge.obj") && e.contains("scale it down"), "{e}");

    let e = load_err(
        "ortho-zero.xml",
        "<scene version=\"3.0.0\">\n<sensor type=\"orthographic\"><transform name=\"to_world\"><scale value=\"0\"/></transform></sensor>\n</scene>\n",
    );
    assert!(e.contains("ortho-zero.xml:2") && e.contains("orthographic"), "{e}");
}

/// A rectangle scaled by 1e10 is a rectangle (its squared area overflows f32, and it was dropped as
/// degenerate), and as an emitter its power is finite and positive.
#[test]
fn a_huge_rectangle_is_kept() {
    let scene = caustic_tests::load_xml(
        &format!("<scene version=\"3.0.0\">{SENSOR}<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"1e10\"/></transform><emitter type=\"area\"/></shape></scene>"),
        "huge-rectangle",
    );
    match &scene.shapes[0].geometry {
        caustic::scene::Geometry::Triangles { triangles, .. } => {
            assert_eq!(triangles.len(), 2, "triangles kept")
        }
        _ => panic!("a rectangle is triangles"),
    }
    let buffers = caustic::prepare::buffers::build(&scene).expect("builds");
    // Two triangles of equal area: half the light-selection probability each (a power overflowing
    // f32 would be zero and leave only the uniform half of the mixture).
    let pmf: Vec<f32> = buffers.lights.iter().map(|l| l.pmf).collect();
    assert!(pmf.len() == 2 && pmf.iter().all(|p| (p - 0.5).abs() < 1e-6), "{pmf:?}");
}

/// Two AOVs of one name are refused when the scene loads, naming its line (they were found only
/// when the EXR was written, after the render).
#[test]
fn a_duplicate_aov_channel_is_refused_at_load() {
    let e = load_err(
        "aov-twice.xml",
        &format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"aov\">\n<string name=\"aovs\" value=\"d:depth,d:depth\"/>\n</integrator>\n{SENSOR}</scene>"
        ),
    );
    assert!(e.contains("aov-twice.xml:2") && e.contains("'d.T'"), "{e}");
}

/// Texture coordinates and normals that are not finite, or uvs past the addressable range, are
/// refused naming the mesh file and vertex, as positions are.
#[test]
fn non_finite_mesh_attributes_are_refused() {
    for (name, line) in [("uv-nan", "vt nan 0.5"), ("uv-huge", "vt 1e30 0.5")] {
        let obj = write_scene(
            &format!("{name}.obj"),
            &format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{line}\nvt 0 0\nvt 1 1\nf 1/1 2/2 3/3\n"),
        );
        let e = load_err(
            &format!("{name}.xml"),
            &format!(
                "<scene version=\"3.0.0\">{SENSOR}<shape type=\"obj\"><string name=\"filename\" value=\"{}\"/></shape></scene>",
                obj.display()
            ),
        );
        assert!(
            e.contains(&format!("{name}.obj")) && e.contains("vertex 0") && e.contains("texture coordinates"),
            "{name}: {e}"
        );
    }
}

/// A crop window whose offset plus size overflows is refused (it panicked in release on the CPU,
/// and on the GPU a window outside the film was accepted); a mesh or material library that is a
/// link to a device (`/dev/zero`) is refused by name instead of read until memory runs out.
#[test]
fn overflowing_crops_and_endless_streams_are_refused() {
    let film = |crop: &str| {
        format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>{crop}</film></sensor></scene>"
        )
    };
    let e = load_err(
        "crop-overflow.xml",
        &film("<integer name=\"crop_offset_x\" value=\"9223372036854775807\"/><integer name=\"crop_width\" value=\"1\"/>"),
    );
    assert!(e.contains("crop-overflow.xml") && e.contains("crop window"), "{e}");
    let zero = write_scene("zero-link.ply", "");
    std::fs::remove_file(&zero).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let e = load_err(
        "zero-mesh.xml",
        &format!(
            "<scene version=\"3.0.0\">{SENSOR}<shape type=\"ply\"><string name=\"filename\" value=\"{}\"/></shape></scene>",
            zero.display()
        ),
    );
    assert!(e.contains("zero-link.ply") && e.contains("not a regular file"), "{e}");
}
