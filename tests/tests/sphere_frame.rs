//! A sphere's texture coordinates turn with the rotation in its `to_world`, as Mitsuba's
//! (`caustic_kernel::shape::sphere::Orientation`): checkerboarded spheres rotated, scaled and
//! mirrored, and a sphere light with a checkerboard radiance, against Mitsuba 3.9.1's render on
//! both backends, with the frames dropped as the negative control (what caustic rendered before);
//! the frame the loader keeps, through instances too.
use caustic::backend::BackendChoice;
use caustic::scene::{Geometry, Scene};
use caustic_tests::*;
use glam::{Mat3, Vec3};

const REFERENCE_SPP: f64 = 16384.0;

fn check(scene: &Scene, choice: BackendChoice, spp: u32, label: &str) -> (f64, f64) {
    scene_against_reference(scene, "sphere_frame.exr", REFERENCE_SPP, choice, spp, 3, label)
}

fn frames(scene: &Scene) -> Vec<Mat3> {
    let spheres = scene.shapes.iter().filter_map(|s| match s.geometry {
        Geometry::Sphere { frame, .. } => Some(frame),
        _ => None,
    });
    spheres.collect()
}

#[test]
fn sphere_uv_turns_with_to_world() {
    let scene = caustic::load::load_scene(&test_data("sphere_frame.xml"), &[]).expect("loads");
    for (choice, spp) in [(BackendChoice::Cpu, 512), (BackendChoice::Gpu, 128)] {
        let (pass, z) = check(&scene, choice, spp, &format!("rotated spheres, {choice:?}"));
        assert_agrees_with_reference((pass, z), &format!("rotated spheres, {choice:?}"));
    }
    // Negative control: every sphere upright again.
    let mut upright = scene.clone();
    for shape in &mut upright.shapes {
        if let Geometry::Sphere { frame, .. } = &mut shape.geometry {
            *frame = Mat3::IDENTITY;
        }
    }
    let (pass, z) = check(&upright, BackendChoice::Cpu, 512, "upright spheres");
    assert_disagrees_with_reference((pass, z), "spheres without their frames");
}

/// The frames the loader keeps: orthonormal rotations of `to_world` (a scale taken out), the mirrored
/// one with a negative determinant and its normals flipped, as Mitsuba's inward-facing ones.
#[test]
fn the_loader_keeps_the_rotation() {
    let scene = caustic::load::load_scene(&test_data("sphere_frame.xml"), &[]).expect("loads");
    let f = frames(&scene);
    assert_eq!(f.len(), 4);
    let about_x = Mat3::from_rotation_x(125.7f32.to_radians());
    assert!(f[0].abs_diff_eq(about_x, 1e-5), "{:?}", f[0]);
    let slanted = Mat3::from_axis_angle(Vec3::new(0.6, 0.8, 0.0), 40f32.to_radians());
    assert!(f[1].abs_diff_eq(slanted, 1e-5), "{:?}", f[1]);
    let mirrored = Mat3::from_rotation_z(30f32.to_radians()) * Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
    assert!(f[2].abs_diff_eq(mirrored, 1e-5), "{:?}", f[2]);
    let flips: Vec<bool> = scene
        .shapes
        .iter()
        .filter(|s| matches!(s.geometry, Geometry::Sphere { .. }))
        .map(|s| s.flip_normals)
        .collect();
    assert_eq!(flips, [false, false, true, false]);
}

/// A sphere in a shapegroup is placed as a sphere of its own by each instance (the loader does it),
/// its frame the instance's rotation times its own.
#[test]
fn instances_turn_their_spheres() {
    let group = r#"<shape type="shapegroup" id="g"><shape type="sphere">
            <transform name="to_world"><rotate x="1" angle="50"/></transform></shape></shape>"#;
    let instance = |rotation: &str| {
        format!(
            r#"<shape type="instance"><ref id="g"/>
            <transform name="to_world">{rotation}<translate x="3"/></transform></shape>"#
        )
    };
    let (a, b) = (instance(r#"<rotate z="1" angle="20"/>"#), instance(r#"<rotate y="1" angle="90"/>"#));
    let scene = load_xml(&format!("<scene version=\"3.0.0\">{group}{a}{b}</scene>"), "sphere-instances");
    let own = Mat3::from_rotation_x(50f32.to_radians());
    let expected =
        [Mat3::from_rotation_z(20f32.to_radians()) * own, Mat3::from_rotation_y(90f32.to_radians()) * own];
    let f = frames(&scene);
    assert!(f.len() == 2 && f.iter().zip(&expected).all(|(f, e)| f.abs_diff_eq(*e, 1e-5)), "{f:?}");
}
