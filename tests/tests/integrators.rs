//! Integrator semantics that Mitsuba's scenes rely on beyond what the reference images show:
//! `hide_emitters` lets camera rays pass through area emitters, on both integrators.
use caustic::backend::BackendChoice;
use caustic_tests::*;
use std::path::PathBuf;

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

fn render(xml: &str, tag: &str) -> caustic::film::Film {
    let dir: PathBuf = std::env::temp_dir().join(format!("caustic-integrators-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.xml");
    std::fs::write(&path, xml).unwrap();
    let scene = caustic::load_scene(&path, &[]);
    std::fs::remove_dir_all(&dir).ok();
    render_scene(&scene.expect("scene loads"), BackendChoice::Cpu, 8, 1)
}

fn centre(film: &caustic::film::Film) -> [f32; 3] {
    film.rgb[(film.height / 2 * film.width + film.width / 2) as usize]
}

#[test]
fn hidden_emitters_let_camera_rays_through() {
    for integrator in ["path", "direct"] {
        let hidden = render(&wall_scene(integrator, true, 2.0), &format!("{integrator}-hidden"));
        let without = render(&wall_scene(integrator, true, 6.0), &format!("{integrator}-without"));
        let shown = render(&wall_scene(integrator, false, 2.0), &format!("{integrator}-shown"));
        // The same camera rays reach the same wall points with the same random numbers.
        let max_diff = hidden.rgb.iter().zip(&without.rgb).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs())).fold(0.0f32, f32::max);
        println!("{integrator}: centre hidden {:?}, emitter behind the camera {:?}, shown {:?}; max |hidden - without| {max_diff:e}", centre(&hidden), centre(&without), centre(&shown));
        assert!(centre(&without)[0] > 0.01, "{integrator}: the wall is not lit");
        assert!(max_diff <= 1e-5 * (1.0 + centre(&without)[0]), "{integrator}: hidden emitter changes the image by {max_diff}");
        assert!(centre(&shown)[0] >= 5.0, "{integrator}: the visible emitter's radiance is missing ({:?})", centre(&shown));
    }
}
