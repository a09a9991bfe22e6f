//! Integrator semantics that Mitsuba's scenes rely on beyond what the reference images show:
//! `hide_emitters` lets camera rays pass through area emitters, on both integrators; Mitsuba's `prb`
//! renders as `path` with its own default depth.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::BackendChoice;
use caustic_tests::*;

/// A wall lit by a point light, and a rectangle emitting towards +z only: at `emitter_z` 2 it sits
/// between the camera (z = 5) and the wall, lighting nothing the camera sees; at 6 it is behind the
/// camera. Either way the emitters, and so the light-selection probabilities, are the same.
fn wall_scene(integrator: &str, hide: bool, emitter_z: f32) -> String {
    let emitter = format!(
        r#"<shape type="rectangle"><transform name="to_world"><scale value="0.5"/><translate z="{emitter_z}"/></transform>
               <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>"#
    );
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><boolean name="hide_emitters" value="{hide}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="4"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8"/></bsdf></shape>
    <emitter type="point"><point name="position" value="0, 0, 1"/><rgb name="intensity" value="3"/></emitter>
    {emitter}
</scene>"#
    )
}

fn render(xml: &str, tag: &str) -> caustic::output::film::Film {
    render_scene(&load_xml(xml, tag), BackendChoice::Cpu, 8, 1)
}

fn centre(film: &caustic::output::film::Film) -> [f32; 3] {
    film.rgb[(film.height / 2 * film.width + film.width / 2) as usize]
}

#[test]
fn hidden_emitters_let_camera_rays_through() {
    for integrator in ["path", "direct"] {
        let hidden = render(&wall_scene(integrator, true, 2.0), &format!("{integrator}-hidden"));
        let without = render(&wall_scene(integrator, true, 6.0), &format!("{integrator}-without"));
        let shown = render(&wall_scene(integrator, false, 2.0), &format!("{integrator}-shown"));
        // The same camera rays reach the same wall points with the same random numbers.
        let max_diff = hidden
            .rgb
            .iter()
            .zip(&without.rgb)
            .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
            .fold(0.0f32, f32::max);
        println!("{integrator}: centre hidden {:?}, emitter behind the camera {:?}, shown {:?}; max |hidden - without| {max_diff:e}", centre(&hidden), centre(&without), centre(&shown));
        assert!(centre(&without)[0] > 0.01, "{integrator}: the wall is not lit");
        assert!(
            max_diff <= 1e-5 * (1.0 + centre(&without)[0]),
            "{integrator}: hidden emitter changes the image by {max_diff}"
        );
        assert!(
            centre(&shown)[0] >= 5.0,
            "{integrator}: the visible emitter's radiance is missing ({:?})",
            centre(&shown)
        );
    }
}

/// A diffuse floor lit by one area emitter of each flat or curved kind, rendered by light sampling
/// alone and by BSDF sampling alone (Mitsuba's `direct` with 3 + 0 and 0 + 3 samples): the two
/// estimate the same image only if each emitter's sampling density is what its `pdf` says.
#[test]
fn light_and_bsdf_sampling_agree_on_every_emitter_shape() {
    let emitters = [
        (
            "rectangle",
            r#"<shape type="rectangle"><transform name="to_world"><scale value="0.4"/><rotate x="1" angle="180"/><translate z="1.2"/></transform>"#,
        ),
        (
            "disk",
            r#"<shape type="disk"><transform name="to_world"><scale x="0.5" y="0.3"/><rotate x="1" angle="150"/><translate z="1.2"/></transform>"#,
        ),
        (
            "sphere",
            r#"<shape type="sphere"><float name="radius" value="0.3"/><point name="center" x="0.2" y="0" z="1.2"/>"#,
        ),
    ];
    for (name, shape) in emitters {
        let render_with = |emitter_samples: u32, bsdf_samples: u32| {
            let xml = format!(
                r#"<scene version="3.0.0">
    <integrator type="direct"><integer name="emitter_samples" value="{emitter_samples}"/><integer name="bsdf_samples" value="{bsdf_samples}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, -2.5, 2.5" target="0, 0, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    {shape}<emitter type="area"><rgb name="radiance" value="4"/></emitter></shape>
</scene>"#
            );
            let scene = load_xml(&xml, &format!("{name}-{emitter_samples}-{bsdf_samples}"));
            render_scene(&scene, BackendChoice::Cpu, 2048, 7 + emitter_samples)
        };
        let light_only = render_with(3, 0);
        let bsdf_only = render_with(0, 3);
        // The two estimators' variances differ widely: the z-scores use both, each pooled over the
        // pixel's neighbours (a pixel whose few BSDF samples all missed the light has a zero estimate).
        let pooled = |f: &caustic::output::film::Film| {
            caustic::output::compare::pooled_variance(f.variance.as_ref().unwrap(), f.width, f.height)
        };
        let (va, vb) = (pooled(&light_only), pooled(&bsdf_only));
        let (mut diff, mut var, mut worst) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..light_only.rgb.len() {
            let d = light_only.rgb[i][1] as f64 - bsdf_only.rgb[i][1] as f64;
            let v = va[i][1] + vb[i][1];
            diff += d;
            var += v;
            worst = worst.max(d.abs() / (v.sqrt() + 1e-6));
        }
        let z = diff / var.sqrt();
        println!("{name}: light vs BSDF sampling: image mean z {z:+.2}, worst pixel |z| {worst:.2}");
        // 1024 pixels: |z| ≤ 4.9 is the Šidák-corrected 0.1% two-sided bound per pixel.
        assert!(
            z.abs() < 4.0 && worst < 4.9,
            "{name}: light and BSDF sampling disagree (z {z:+.2}, worst {worst:.2})"
        );
    }
}

/// Mitsuba's `prb` (`tests/data/prb.xml`: a closed box of bright walls, the camera inside) renders as
/// caustic's path tracer with prb's default `max_depth` of 6, against Mitsuba 3.9.1's own prb
/// render (`prb.py`, llvm_ad_rgb, 65536 spp); and with `path`'s unbounded depth it would not, which
/// is what the box is for.
#[test]
fn prb_renders_as_mitsubas_prb() {
    let scene = caustic::load::load_scene(&test_data("prb.xml"), &[]).expect("loads");
    assert_eq!((scene.integrator.max_depth, scene.integrator.rr_depth), (6, 5));
    let label = "prb.xml (prb: path, max_depth 6)";
    let result = scene_against_reference(&scene, "prb.exr", 65536.0, BackendChoice::Cpu, 1024, 3, label);
    assert_agrees_with_reference(result, label);
    let mut unbounded = scene;
    unbounded.integrator.max_depth = -1;
    let label = "prb.xml with path's unbounded depth";
    let result = scene_against_reference(&unbounded, "prb.exr", 65536.0, BackendChoice::Cpu, 1024, 3, label);
    assert_disagrees_with_reference(result, label);
}

/// Next-event estimation picks each emitter equally often, as Mitsuba's `path` and `direct` do
/// (within a mesh emitter, its triangles by power); light tracing starts half its paths by power.
#[test]
fn emitters_are_chosen_as_mitsuba_chooses_them_for_next_event_estimation() {
    // The wall scene's point light (intensity 3: power 4π·3) and rectangle (two triangles, radiance
    // 5 on area 1: power 5π).
    let pmfs = |integrator: &str| -> Vec<f32> {
        let scene = load_xml(&wall_scene(integrator, false, 2.0), &format!("selection-{integrator}"));
        caustic::prepare::buffers::build(&scene).expect("builds").lights.iter().map(|l| l.pmf).collect()
    };
    for integrator in ["path", "direct"] {
        let pmf = pmfs(integrator);
        // Scene order: the rectangle's two triangles, then the point light.
        let expected = [0.25, 0.25, 0.5];
        assert!(
            pmf.len() == 3 && pmf.iter().zip(expected).all(|(p, e)| (p - e).abs() < 1e-6),
            "{integrator}: {pmf:?}"
        );
    }
    let pmf = pmfs("ptracer");
    let (rectangle, point) = (5.0 * std::f32::consts::PI, 12.0 * std::f32::consts::PI);
    let point_share = 0.5 * point / (rectangle + point) + 0.25;
    assert!(pmf.len() == 3 && (pmf[2] - point_share).abs() < 1e-5, "ptracer: {pmf:?}");
}
