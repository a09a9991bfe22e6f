//! The path tracer's two per-pixel loops (`caustic::backend::path_loop`): one path after the other,
//! or one loop of bounces that regenerates finished paths. They draw the same random numbers per
//! sample and add the sums in the same order, so each backend's images agree to rounding whichever
//! loop runs, and the GPU's measured choice (which splits its first passes between the two) too.
//!
//! One test in this binary: it sets `CAUSTIC_PATH_LOOP` and `CAUSTIC_WORKGROUP`, which every backend
//! reads when created.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic_tests::*;

/// A glass sphere (total internal reflection: paths of very different lengths) and a diffuse one in
/// a diffuse box under an area lamp, `max_depth` -1.
const SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="-1"/></integrator>
    <sensor type="perspective"><float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, -3.5, 1" target="0, 0, 0.8" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="90"/><translate y="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.6, 0.7"/></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.5"/><point name="center" x="-0.5" y="0" z="0.5"/>
        <bsdf type="dielectric"/></shape>
    <shape type="sphere"><float name="radius" value="0.4"/><point name="center" x="0.7" y="0.3" z="0.4"/>
        <bsdf type="roughplastic"><float name="alpha" value="0.2"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="180"/><translate z="2.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>
</scene>"#;

#[test]
fn both_loops_and_the_measured_choice_render_the_same_image() {
    let scene = load_xml(SCENE, "path-loop");
    let mut films: Vec<(String, Film)> = Vec::new();
    for choice in [BackendChoice::Cpu, BackendChoice::Gpu] {
        // (`measure` with two workgroup sizes: four pipelines timed against each other, the first of
        // them, which runs alone first, in 16×5 workgroups that overhang the 24×24 image:
        // `backend::variant`.)
        for (request, sizes) in [("plain", ""), ("regenerate", ""), ("measure", ""), ("measure", "16x5,8x8")]
        {
            if choice == BackendChoice::Cpu && request == "measure" {
                continue; // (the CPU has nothing to measure: it runs the plain loop)
            }
            std::env::set_var("CAUSTIC_PATH_LOOP", request);
            if !sizes.is_empty() {
                std::env::set_var("CAUSTIC_WORKGROUP", sizes);
            }
            let film = render_scene(&scene, choice, 96, 3);
            std::env::remove_var("CAUSTIC_WORKGROUP");
            assert_eq!(film.invalid_samples, 0, "{choice:?} {request} {sizes}: invalid samples");
            films.push((format!("{choice:?} {request} {sizes}"), film));
        }
    }
    // A render long enough for the trial to begin (its long passes add up to `FIRST_ALONE`): the
    // other candidates build on a thread while the first renders on, then take passes in turn.
    std::env::set_var("CAUSTIC_PATH_LOOP", "measure");
    std::env::set_var("CAUSTIC_WORKGROUP", "16x5,8x8");
    let long = render_scene(&scene, BackendChoice::Gpu, 1536, 3);
    std::env::remove_var("CAUSTIC_WORKGROUP");
    std::env::set_var("CAUSTIC_PATH_LOOP", "plain");
    let long_cpu = render_scene(&scene, BackendChoice::Cpu, 1536, 3);
    let diff = max_abs_difference(&long_cpu, &long);
    println!("1536 spp, a trial of four pipelines against the CPU: largest difference {diff:.2e}");
    assert!(diff < 1e-3, "the trial's render differs from the CPU's by {diff}");
    std::env::remove_var("CAUSTIC_PATH_LOOP");
    let (first, reference) = &films[0];
    for (name, film) in &films[1..] {
        let diff = max_abs_difference(reference, film);
        println!("{name} against {first}: largest difference {diff:.2e}");
        // The same samples, summed in the same order: only rounding may differ between backends (the
        // GPU's compiler may fuse or reorder float operations the CPU's does not).
        assert!(diff < 1e-3, "{name} differs from {first} by {diff}");
    }
    // A negative control: another seed's image is not the same one.
    std::env::set_var("CAUSTIC_PATH_LOOP", "plain");
    let other = render_scene(&scene, BackendChoice::Cpu, 96, 4);
    std::env::remove_var("CAUSTIC_PATH_LOOP");
    assert!(max_abs_difference(reference, &other) > 1e-2, "the comparison cannot tell two seeds apart");
}
