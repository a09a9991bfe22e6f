//! Direct OBJ/MTL input: MTL Kd/Ks/Ns → modified Phong (Kd alone → Lambert), Ke → area emitter, an
//! automatic camera and sphere light; the result renders to a finite, lit image.
//!
//! tests/tests holds end-to-end tests: whole scenes through the `caustic` crate, mostly rendered and
//! judged by statistics over whole images (against Mitsuba's references, the other backend or an exact
//! answer). Kernel math (sampling, BSDFs, lights) belongs in kernel/tests; the host's loading of single
//! files and its command line in host/tests.
use caustic::backend::BackendChoice;
use caustic::scene::Geometry;
use caustic_kernel::layout::{BSDF_DIFFUSE, BSDF_PHONG};
use caustic_tests::render_scene;

#[test]
fn obj_with_mtl_renders() {
    let dir = std::env::temp_dir().join(format!("caustic-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl shiny\nKd 0.4 0.4 0.4\nKs 0.5 0.5 0.5\nNs 40\nnewmtl matte\nKd 0.7 0.2 0.2\nnewmtl lamp\nKd 0 0 0\nKe 5 5 5\n").unwrap();
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1 0\nv 0.2 1 0\nv 0 1 0.2\nusemtl shiny\nf 1 3 2\nf 1 4 3\nusemtl matte\nf 1 2 5\nusemtl lamp\nf 5 6 7\n",
    )
    .unwrap();
    let scene = caustic::load::load_scene(&dir.join("model.obj"), &[]).expect("OBJ loads");
    assert!(scene.materials.iter().any(|m| m.kind == BSDF_PHONG && (m.eta - 40.0).abs() < 1e-6));
    assert!(scene.materials.iter().any(|m| m.kind == BSDF_DIFFUSE && (m.reflectance[0] - 0.7).abs() < 1e-6));
    let emissive: Vec<_> = scene.shapes.iter().filter(|s| s.emission.is_some()).collect();
    assert_eq!(emissive.len(), 2, "the Ke triangle and the automatic sphere light emit");
    assert!(emissive.iter().any(|s| matches!(s.geometry, Geometry::Sphere { .. })));
    let mut small = scene.clone();
    small.sensor.width = 32;
    small.sensor.height = 32;
    let film = render_scene(&small, BackendChoice::Cpu, 8, 1);
    let mean = film.rgb.iter().map(|p| p[0] as f64).sum::<f64>() / film.rgb.len() as f64;
    assert!(mean > 0.0, "the model is unlit");
}
