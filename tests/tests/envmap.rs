//! The `envmap` emitter's `mis_compensation` (Karlík et al. 2019, as Mitsuba reads it): light
//! sampling follows the luminance above the map's mean, BSDF sampling covers the rest, and the image
//! is the one without compensation.
use caustic::backend::BackendChoice;
use caustic::prepare::buffers;
use caustic_kernel::layout::LIGHT_ENVMAP;
use caustic_tests::replicas::*;
use caustic_tests::*;

/// A glossy sphere on a diffuse floor under the shared museum environment.
fn scene(integrator: &str, compensate: bool) -> String {
    let museum = shared_dir().join("scenes/mitsuba/common/textures/museum.exr");
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, -3, 1.2" target="0, 0, 0.4" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.5"/><point name="center" x="0" y="0" z="0.5"/>
        <bsdf type="roughconductor"><float name="alpha" value="0.25"/></bsdf></shape>
    <emitter type="envmap"><string name="filename" value="{}"/>
        <boolean name="mis_compensation" value="{compensate}"/>
        <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
</scene>"#,
        museum.display()
    )
}

/// The envmap's conditional CDFs (`light::infinite`'s layout) and how many of their cells have
/// probability zero.
fn zero_cells(b: &buffers::SceneBuffers) -> usize {
    let env = b.lights.iter().find(|l| l.kind == LIGHT_ENVMAP).expect("an envmap light");
    let t = &b.textures[env.prim as usize];
    let (w, h) = (t.width as usize, t.height as usize);
    let conditional = &b.tables[env.table as usize + (h - 1)..env.table as usize + (h - 1) + (h - 1) * w];
    conditional
        .chunks_exact(w)
        .map(|row| (0..w).filter(|&c| row[c] == if c == 0 { 0.0 } else { row[c - 1] }).count())
        .sum()
}

#[test]
fn compensation_leaves_the_dim_directions_to_bsdf_sampling() {
    let plain = buffers::build(&load_xml(&scene("path", false), "env-plain")).unwrap();
    let compensated = buffers::build(&load_xml(&scene("path", true), "env-comp")).unwrap();
    let (a, b) = (zero_cells(&plain), zero_cells(&compensated));
    let cells = {
        let t = compensated.textures.iter().find(|t| t.width > 1).unwrap();
        t.width as usize * (t.height as usize - 1)
    };
    println!("cells of probability zero: {a} without compensation, {b} with, of {cells}");
    assert!(b > a + cells / 10, "compensation left the distribution as it was ({a} → {b} of {cells})");
    assert!(b < cells, "compensation left nothing to sample");
    // Light tracing draws emission from the tables alone: there compensation is not applied.
    let pt = buffers::build(&load_xml(&scene("ptracer", true), "env-pt")).unwrap();
    assert_eq!(
        zero_cells(&pt),
        zero_cells(&buffers::build(&load_xml(&scene("ptracer", false), "env-pt2")).unwrap())
    );
}

#[test]
fn compensation_renders_the_same_image() {
    for integrator in ["path", "direct"] {
        let plain = render_replicated(&load_xml(&scene(integrator, false), "env-plain-r"), 256, 7);
        let compensated =
            render_scene(&load_xml(&scene(integrator, true), "env-comp-r"), BackendChoice::Cpu, 256, 8);
        let (z, worst) = agreement(&plain, &compensated);
        println!(
            "{integrator}: plain mean {:.5}, compensated mean {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
            plain.mean,
            image_mean(&compensated)
        );
        assert!(plain.mean > 1e-2, "the scene is dark");
        assert!(
            z.abs() < 4.5 && worst < 5.0,
            "{integrator}: compensation changed the image (z {z:+.2}, worst {worst:.2})"
        );
    }
}
