//! The box corner the light-tracing and bidirectional integrators' tests render
//! (`tests/tests/ptracer.rs`, `bdpt.rs`, `vcm.rs`): a diffuse floor, back wall and red side wall
//! around a sphere, under each emitter kind; and the statistical agreement of an integrator with
//! `path` on it.
use crate::replicas::*;
use crate::*;
use caustic::backend::BackendChoice;
use caustic::output::film::Film;

/// A diffuse box corner (floor, back wall, a red side wall) with a sphere of `sphere_bsdf`, lit by
/// `emitter`, `max_depth` `depth`, 24×24 pixels seen through a box filter.
pub fn corner(integrator: &str, emitter: &str, depth: &str, sphere_bsdf: &str) -> String {
    corner_sized(integrator, emitter, depth, 24, sphere_bsdf)
}

/// `corner` at `res`×`res` pixels.
pub fn corner_sized(integrator: &str, emitter: &str, depth: &str, res: u32, sphere_bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="{integrator}"><integer name="max_depth" value="{depth}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, -3, 1.6" target="0, 0, 0.5" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="90"/><translate y="1.5" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate y="1" angle="90"/><translate x="-1.5" z="1"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.2"/></bsdf></bsdf></shape>
    <shape type="sphere"><float name="radius" value="0.4"/><point name="center" x="0.3" y="0.2" z="0.4"/>
        {sphere_bsdf}</shape>
    {emitter}
</scene>"#
    )
}

pub const ROUGH_PLASTIC: &str = r#"<bsdf type="roughplastic"><float name="alpha" value="0.2"/><rgb name="diffuse_reflectance" value="0.3, 0.4, 0.6"/></bsdf>"#;
pub const GLASS: &str = r#"<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>"#;

pub const EMITTERS: [(&str, &str); 4] = [
    (
        "area",
        r#"<shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate z="1.9"/></transform>
            <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>"#,
    ),
    (
        "sphere",
        r#"<shape type="sphere"><float name="radius" value="0.15"/><point name="center" x="-0.5" y="-0.3" z="1.4"/>
            <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>"#,
    ),
    (
        "point",
        r#"<emitter type="point"><point name="position" value="0.4, -0.6, 1.5"/><rgb name="intensity" value="4"/></emitter>"#,
    ),
    (
        "spot",
        r#"<emitter type="spot"><transform name="to_world"><lookat origin="-0.6, -1, 1.8" target="0.2, 0.3, 0"/></transform>
            <rgb name="intensity" value="8"/><float name="cutoff_angle" value="35"/></emitter>"#,
    ),
];

/// `integrator` (`spp` replicated, seed `seed`) against `path` (`path_spp`, seed `seed + 1`) on
/// `xml(kind)`; returns the two images.
pub fn agrees_with_path(
    integrator: &str,
    what: &str,
    xml: impl Fn(&str) -> String,
    spp: u32,
    path_spp: u32,
    seed: u32,
) -> (Replicated, Film) {
    let path = render_scene(
        &load_xml(&xml("path"), &format!("{what}-path")),
        BackendChoice::Cpu,
        path_spp,
        seed + 1,
    );
    let result = render_replicated(&load_xml(&xml(integrator), &format!("{what}-{integrator}")), spp, seed);
    assert_agrees(integrator, what, &result, &path);
    (result, path)
}

/// Asserts that `result` (of `integrator`, replicated) and the path-traced `path` estimate one image:
/// whole-image z and worst pixel |z| (`agreement`), no invalid sample, a scene that is not dark.
pub fn assert_agrees(integrator: &str, what: &str, result: &Replicated, path: &Film) {
    let (z, worst) = agreement(result, path);
    println!(
        "{what}: {integrator} mean {:.5}, path {:.5}: image z {z:+.2}, worst pixel |z| {worst:.2}",
        result.mean,
        image_mean(path)
    );
    assert!(image_mean(path) > 1e-3, "{what}: the scene is dark");
    assert_eq!(result.film.invalid_samples, 0, "{what}: {integrator} gave NaN or infinite samples");
    // 24×24×3 values: |z| ≤ 5.0 is the Šidák-corrected 0.1% two-sided bound per value.
    assert!(
        z.abs() < 4.5 && worst < 5.0,
        "{what}: {integrator} and path disagree (z {z:+.2}, worst {worst:.2})"
    );
}
