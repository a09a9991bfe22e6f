//! Mitsuba's `mesh_attribute` texture on PLY attributes against Mitsuba 3.9.1
//! (`tests/data/mesh_attribute*.xml`; `mesh_attribute.py` writes the meshes and the references):
//! vertex colours interpolated by the hit's barycentrics, one- and three-channel face attributes,
//! `scale`, a blend weight and a roughness read as one number, and the same grid in a shapegroup
//! placed twice (stored once), one placement mirrored. Per-pixel z-test and mean-luminance z-score,
//! on the CPU and the GPU backend, with a negative control each (every attribute replaced by its
//! mean must fail). Also: the specialization bit and the attribute data exist only in scenes that
//! read attributes, and bad input is refused with file and line.
use caustic::backend::BackendChoice;
use caustic::scene::Geometry;
use caustic_kernel::features;
use caustic_tests::*;

const REFERENCE_SPP: f64 = 2048.0;
const MEAN_MESH: (&str, &str) = ("mesh", "mesh_attribute_mean.ply");

fn check(scene: &str, defines_: &[(&str, &str)], choice: BackendChoice, spp: u32, label: &str) -> (f64, f64) {
    let reference = scene.replace(".xml", ".exr");
    against_mitsuba_reference(scene, defines_, &reference, REFERENCE_SPP, choice, spp, 3, label)
}

fn assert_matches(scene: &str, choice: BackendChoice, spp: u32) {
    let (pass, z) = check(scene, &[], choice, spp, scene);
    assert_agrees_with_reference((pass, z), &format!("{scene} {choice:?}"));
}

fn assert_caught(scene: &str) {
    let label = format!("{scene} (negative control: attributes replaced by their means)");
    let (pass, z) = check(scene, &[MEAN_MESH], BackendChoice::Cpu, 512, &label);
    assert_disagrees_with_reference((pass, z), &label);
}

#[test]
fn mesh_attributes_match_mitsuba() {
    let scene = "mesh_attribute.xml";
    assert_matches(scene, BackendChoice::Cpu, 512);
    assert_matches(scene, BackendChoice::Gpu, 128);
    assert_caught(scene);
}

/// The group's triangles are stored once: a hit in either placement reads its own triangle's values.
#[test]
fn instanced_mesh_attributes_match_mitsuba() {
    let scene = "mesh_attribute_instanced.xml";
    let loaded = caustic::load::load_scene(&test_data(scene), &[]).unwrap();
    let built = caustic::prepare::buffers::build(&loaded).unwrap();
    assert!(features::has(built.features, features::INSTANCING), "the grid is not stored once");
    assert_matches(scene, BackendChoice::Cpu, 512);
    assert_matches(scene, BackendChoice::Gpu, 128);
    assert_caught(scene);
}

/// Only scenes with `mesh_attribute` textures compile the lookup in and keep attribute values; a
/// shape keeps only the attributes its textures read.
#[test]
fn attributes_are_kept_only_where_read() {
    let ply = test_data("mesh_attribute.ply");
    let scene = |reflectance: &str| {
        format!(
            r#"<scene version="3.0.0"><shape type="ply"><string name="filename" value="{}"/>
            <bsdf type="diffuse">{reflectance}</bsdf></shape></scene>"#,
            ply.display()
        )
    };
    let plain = load_xml(&scene(r#"<rgb name="reflectance" value="0.5"/>"#), "attr-plain");
    let Geometry::Triangles { attributes, .. } = &plain.shapes[0].geometry else { panic!("a mesh") };
    assert!(attributes.is_empty(), "a scene reading no attribute keeps {attributes:?}");
    let plain_buffers = caustic::prepare::buffers::build(&plain).unwrap();
    assert!(!features::has(plain_buffers.features, features::MESH_ATTRIBUTES));
    let read = load_xml(
        &scene(
            r#"<texture type="mesh_attribute" name="reflectance"><string name="name" value="face_wear"/></texture>"#,
        ),
        "attr-read",
    );
    let Geometry::Triangles { attributes, .. } = &read.shapes[0].geometry else { panic!("a mesh") };
    let names: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["face_wear"]);
    let read_buffers = caustic::prepare::buffers::build(&read).unwrap();
    assert!(features::has(read_buffers.features, features::MESH_ATTRIBUTES));
    // Nine floats (three corners, RGB) per triangle of the grid's 18, and nothing more.
    assert_eq!(read_buffers.tables.len() - plain_buffers.tables.len(), 18 * 9);

    // A principled weight beyond the record's slots reads it too (`textured_weights`).
    let sheen = load_xml(
        &scene(r#"<rgb name="reflectance" value="0.5"/>"#).replace(
            r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>"#,
            r#"<bsdf type="principled"><texture type="mesh_attribute" name="sheen"><string name="name" value="face_wear"/></texture></bsdf>"#,
        ),
        "attr-sheen",
    );
    let Geometry::Triangles { attributes, .. } = &sheen.shapes[0].geometry else { panic!("a mesh") };
    assert_eq!(attributes.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(), ["face_wear"]);
}

/// A missing attribute (on a mesh, on a rectangle), a three-channel attribute read as one number, a
/// four-channel colour, a name without `vertex_`/`face_`, and an attribute on a mask's opacity or
/// on a parameter caustic replaces by a mean are refused with the texture's file and line.
#[test]
fn bad_mesh_attributes_are_refused_with_file_and_line() {
    let dir = std::env::temp_dir().join(format!("caustic-test-{}-attr-rgba", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rgba = dir.join("rgba.ply");
    std::fs::write(
        &rgba,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
         property float r\nproperty float g\nproperty float b\nproperty float a\nelement face 1\n\
         property list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n",
    )
    .unwrap();
    let ply = test_data("mesh_attribute.ply");
    let texture = |name: &str, param: &str| {
        format!(
            r#"<texture type="mesh_attribute" name="{param}"><string name="name" value="{name}"/></texture>"#
        )
    };
    let mesh = |file: &std::path::Path, bsdf: &str| {
        format!(
            r#"<scene version="3.0.0">
<shape type="ply"><string name="filename" value="{}"/>
{bsdf}
</shape></scene>"#,
            file.display()
        )
    };
    let diffuse = |t: String| format!(r#"<bsdf type="diffuse">{t}</bsdf>"#);
    let cases = [
        (mesh(&ply, &diffuse(texture("vertex_missing", "reflectance"))), "'vertex_missing'", "no such attribute"),
        (
            r#"<scene version="3.0.0">
<shape type="rectangle">
<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/></texture></bsdf>
</shape></scene>"#
                .to_string(),
            "'vertex_color'",
            "(it has: none)",
        ),
        (
            mesh(&ply, &format!(r#"<bsdf type="roughconductor">{}</bsdf>"#, texture("face_tint_color", "alpha"))),
            "'face_tint_color'",
            "3 channels where one number",
        ),
        (mesh(&rgba, &diffuse(texture("vertex_color", "reflectance"))), "'vertex_color'", "4 channels"),
        (mesh(&ply, &diffuse(texture("color", "reflectance"))), "'color'", "'vertex_' or 'face_'"),
        (
            mesh(&ply, &format!(r#"<bsdf type="mask">{}<bsdf type="diffuse"/></bsdf>"#, texture("face_wear", "opacity"))),
            "'face_wear'",
            "not by masks",
        ),
        (
            mesh(&ply, &format!(r#"<bsdf type="principled">{}</bsdf>"#, texture("face_tint_color", "clearcoat"))),
            "'face_tint_color'",
            "3 channels where one number",
        ),
        (
            mesh(&ply, &format!(r#"<bsdf type="roughplastic">{}</bsdf>"#, texture("face_wear", "alpha"))),
            "'face_wear'",
            "replaces by a mean",
        ),
    ];
    for (k, (xml, name, reason)) in cases.iter().enumerate() {
        let Err(e) = try_load_xml(xml, &format!("attr-bad-{k}"), &[]) else { panic!("case {k} loaded") };
        let message = format!("{e:#}");
        // The texture's line: the third of each scene.
        assert!(
            message.contains("scene.xml:3") && message.contains(name) && message.contains(reason),
            "case {k}: {message}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
