//! Mesh files (OBJ, PLY, serialized) and built-in shapes load with Mitsuba 3's semantics: counts,
//! normals, texture coordinates, `flip_normals`/`face_normals`, and clean errors for bad files.
//!
//! host/tests holds the host's own behaviour: loading scenes, meshes and images, and the command
//! line. Kernel math (sampling, BSDFs, lights) is tested in kernel/tests; rendered images as a whole in
//! tests/tests.
use caustic::load::mesh::{self, primitives};
use caustic::scene::mesh::Mesh;
use caustic::scene::{Geometry, Scene, Shape};
use caustic_tests::shared_dir_if_present;
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

fn shared_mesh(name: &str) -> Option<PathBuf> {
    shared_dir_if_present().map(|d| d.join("scenes/mitsuba/common/meshes").join(name))
}

/// A fresh directory for one test's files.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("caustic-shapes-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes a scene whose body is `shapes` and loads it.
fn load_scene_with(dir: &Path, shapes: &str) -> anyhow::Result<Scene> {
    let path = dir.join("scene.xml");
    std::fs::write(&path, format!("<scene version=\"3.0.0\">\n{shapes}\n</scene>\n")).unwrap();
    caustic::load::mitsuba::load(&path, &[])
}

fn load_error(dir: &Path, shapes: &str) -> String {
    match load_scene_with(dir, shapes) {
        Ok(_) => panic!("the scene loaded but should not:\n{shapes}"),
        Err(e) => format!("{e:#}"),
    }
}

struct Soup<'a> {
    triangles: &'a [[Vec3; 3]],
    normals: Option<&'a [[Vec3; 3]]>,
    uvs: Option<&'a [[Vec2; 3]]>,
}

fn soup(shape: &Shape) -> Soup<'_> {
    match &shape.geometry {
        Geometry::Triangles { triangles, normals, uvs, .. } => {
            Soup { triangles, normals: normals.as_deref(), uvs: uvs.as_deref() }
        }
        other => panic!("expected triangles, got {other:?}"),
    }
}

fn area(triangles: &[[Vec3; 3]]) -> f64 {
    triangles.iter().map(|t| 0.5 * f64::from((t[1] - t[0]).cross(t[2] - t[0]).length())).sum()
}

fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    points.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), &p| (lo.min(p), hi.max(p)))
}

fn assert_unit_normals(mesh: &Mesh) {
    let normals = mesh.normals.as_ref().expect("normals");
    assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4), "a normal is not unit length");
}

// ---------------------------------------------------------------- serialized

/// Vertex and triangle counts of the three meshes in matpreview.serialized, decoded independently
/// (a few lines of Python's zlib and struct).
const MATPREVIEW: [(u32, usize, usize); 3] = [(0, 289, 512), (1, 2078, 3936), (2, 29439, 57152)];

#[test]
fn serialized_matpreview_meshes_have_their_counts_normals_and_uvs() {
    let Some(path) = shared_mesh("matpreview.serialized") else { return };
    let mut extents = Vec::new();
    for (index, vertices, triangles) in MATPREVIEW {
        let mesh = mesh::load_serialized(&path, index).unwrap();
        assert_eq!(mesh.positions.len(), vertices, "shape_index {index}");
        assert_eq!(mesh.triangle_count(), triangles, "shape_index {index}");
        assert_unit_normals(&mesh);
        let uvs = mesh.uvs.as_ref().expect("matpreview meshes carry uvs");
        assert!(uvs.iter().all(|uv| uv.is_finite()));
        let (lo, hi) = bounds(&mesh.positions);
        let extent = hi - lo;
        assert!(
            lo.is_finite() && hi.is_finite() && extent.max_element() > 0.1 && extent.max_element() < 100.0,
            "shape_index {index}: bounds {lo}..{hi}"
        );
        // Every vertex is used by some triangle: a sign that the index array was read in step.
        let mut used = vec![false; vertices];
        mesh.indices.iter().for_each(|&i| used[i as usize] = true);
        assert!(used.iter().all(|&u| u), "shape_index {index}: unused vertices");
        extents.push(extent);
    }
    // Three different meshes, not one read three times.
    assert!(extents[0] != extents[1] && extents[1] != extents[2], "extents {extents:?}");
}

#[test]
fn serialized_shape_index_out_of_range_is_an_error() {
    let Some(path) = shared_mesh("matpreview.serialized") else { return };
    let e = format!("{:#}", mesh::load_serialized(&path, 3).unwrap_err());
    assert!(e.contains("matpreview.serialized") && e.contains("out of range"), "{e}");
}

#[test]
fn damaged_serialized_files_are_errors_naming_the_file() {
    let Some(path) = shared_mesh("matpreview.serialized") else { return };
    let bytes = std::fs::read(&path).unwrap();
    let dir = temp_dir("serialized");
    let cases: [(&str, Vec<u8>, u32); 5] = [
        ("truncated.serialized", bytes[..3000].to_vec(), 0),
        ("truncated-header.serialized", bytes[..20].to_vec(), 0),
        ("truncated-table.serialized", bytes[..bytes.len() - 6].to_vec(), 2),
        ("not-a-mesh.serialized", b"definitely not a mesh".to_vec(), 0),
        (
            "damaged.serialized",
            {
                // Flip bits in the middle of the third mesh's compressed data.
                let mut b = bytes.clone();
                for k in 0..64 {
                    b[600_000 + 97 * k] ^= 0x5a;
                }
                b
            },
            2,
        ),
    ];
    for (name, data, index) in cases {
        let file = dir.join(name);
        std::fs::write(&file, data).unwrap();
        let Err(e) = mesh::load_serialized(&file, index) else { panic!("{name} loaded") };
        let e = format!("{e:#}");
        assert!(e.contains(name), "{e}");
    }
    let e = format!("{:#}", mesh::load_serialized(&dir.join("absent.serialized"), 0).unwrap_err());
    assert!(e.contains("absent.serialized"), "{e}");
}

// ---------------------------------------------------------------- PLY

/// `element NAME COUNT` from a PLY header.
fn header_count(path: &Path, element: &str) -> usize {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes.windows(10).position(|w| w == b"end_header").unwrap();
    let header = String::from_utf8_lossy(&bytes[..end]).to_string();
    let prefix = format!("element {element} ");
    header.lines().find_map(|l| l.strip_prefix(&prefix)).unwrap().trim().parse().unwrap()
}

#[test]
fn ply_bunny_matches_its_header() {
    let Some(path) = shared_mesh("bunny.ply") else { return };
    let mesh = mesh::load_ply(&path).unwrap().0;
    assert_eq!(mesh.positions.len(), header_count(&path, "vertex"));
    // Every face of the bunny is a triangle.
    assert_eq!(mesh.triangle_count(), header_count(&path, "face"));
    assert!(mesh.normals.is_none() && mesh.uvs.is_none());
    let (lo, hi) = bounds(&mesh.positions);
    assert!((hi - lo).max_element() > 0.1 && (hi - lo).max_element() < 0.3, "bunny bounds {lo}..{hi}");
}

#[test]
fn ascii_ply_meshes_load() {
    for name in ["sphere.ply", "teapot.ply"] {
        let Some(path) = shared_mesh(name) else { return };
        let mesh = mesh::load_ply(&path).unwrap().0;
        assert_eq!(mesh.positions.len(), header_count(&path, "vertex"), "{name}");
        assert_eq!(mesh.triangle_count(), header_count(&path, "face"), "{name}");
    }
}

/// A small mesh in every PLY encoding: a quad and a triangle, with normals, `s t` texture
/// coordinates, properties to ignore, mixed scalar types and an element after the faces.
struct SyntheticPly;

impl SyntheticPly {
    const POSITIONS: [[f32; 3]; 5] =
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.25], [0.0, 1.0, 0.0], [2.0, 0.5, -0.5]];
    const NORMALS: [[f32; 3]; 5] =
        [[0.0, 0.0, 2.0], [0.0, 0.0, 1.0], [0.0, 0.6, 0.8], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
    const UVS: [[f32; 2]; 5] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.125]];
    const FACES: [&'static [i32]; 2] = [&[0, 1, 2, 3], &[1, 4, 2]];

    fn header(format: &str) -> String {
        format!(
            "ply\nformat {format} 1.0\ncomment synthetic\nelement vertex 5\nproperty float x\nproperty float y\nproperty double z\n\
             property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n\
             element face 2\nproperty list uchar int vertex_indices\nproperty short flags\n\
             element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
        )
    }

    fn ascii() -> Vec<u8> {
        let mut text = Self::header("ascii");
        for k in 0..5 {
            let (p, n, uv) = (Self::POSITIONS[k], Self::NORMALS[k], Self::UVS[k]);
            text +=
                &format!("{} {} {} 200 {} {} {} {} {}\n", p[0], p[1], p[2], n[0], n[1], n[2], uv[0], uv[1]);
        }
        for face in Self::FACES {
            text += &format!(
                "{} {} -3\n",
                face.len(),
                face.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(" ")
            );
        }
        text += "0 2\n";
        text.into_bytes()
    }

    fn binary(big_endian: bool) -> Vec<u8> {
        let mut out =
            Self::header(if big_endian { "binary_big_endian" } else { "binary_little_endian" }).into_bytes();
        let f32b = |v: f32| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
        let i32b = |v: i32| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
        for k in 0..5 {
            let (p, n, uv) = (Self::POSITIONS[k], Self::NORMALS[k], Self::UVS[k]);
            out.extend(f32b(p[0]));
            out.extend(f32b(p[1]));
            out.extend(if big_endian {
                f64::from(p[2]).to_be_bytes()
            } else {
                f64::from(p[2]).to_le_bytes()
            });
            out.push(200);
            for v in [n[0], n[1], n[2], uv[0], uv[1]] {
                out.extend(f32b(v));
            }
        }
        for face in Self::FACES {
            out.push(face.len() as u8);
            face.iter().for_each(|&i| out.extend(i32b(i)));
            out.extend(if big_endian { (-3i16).to_be_bytes() } else { (-3i16).to_le_bytes() });
        }
        out.extend(i32b(0));
        out.extend(i32b(2));
        out
    }
}

fn assert_same_mesh(a: &Mesh, b: &Mesh, what: &str) {
    assert_eq!(a.positions, b.positions, "{what}: positions");
    assert_eq!(a.indices, b.indices, "{what}: indices");
    assert_eq!(a.normals, b.normals, "{what}: normals");
    assert_eq!(a.uvs, b.uvs, "{what}: uvs");
}

#[test]
fn ascii_and_binary_ply_give_identical_meshes() {
    let dir = temp_dir("ply-encodings");
    let mut meshes = Vec::new();
    for (name, bytes) in [
        ("ascii.ply", SyntheticPly::ascii()),
        ("little.ply", SyntheticPly::binary(false)),
        ("big.ply", SyntheticPly::binary(true)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        meshes.push((name, mesh::load_ply(&path).unwrap_or_else(|e| panic!("{e:#}")).0));
    }
    let (_, ascii) = &meshes[0];
    assert_eq!(ascii.positions.len(), 5);
    // The quad fans from its first corner.
    assert_eq!(ascii.indices, vec![0, 1, 2, 0, 2, 3, 1, 4, 2]);
    assert_eq!(ascii.normals.as_ref().unwrap()[0], Vec3::Z, "normals are normalized");
    assert_eq!(ascii.uvs.as_ref().unwrap()[4], Vec2::new(0.5, 0.125), "s t are texture coordinates");
    for (name, mesh) in &meshes[1..] {
        assert_same_mesh(ascii, mesh, name);
    }
}

#[test]
fn broken_ply_files_are_errors_naming_the_file() {
    let dir = temp_dir("ply-broken");
    let good = SyntheticPly::binary(false);
    let ascii = String::from_utf8(SyntheticPly::ascii()).unwrap();
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("truncated.ply", good[..good.len() - 20].to_vec()),
        ("bad-index.ply", ascii.replace("3 1 4 2 -3", "3 1 9 2 -3").into_bytes()),
        ("negative-index.ply", ascii.replace("3 1 4 2 -3", "3 1 -4 2 -3").into_bytes()),
        ("bad-number.ply", ascii.replace("200", "abc").into_bytes()),
        ("no-faces.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n".to_vec()),
        ("not-ply.ply", b"solid cube\nfacet normal 0 0 1\n".to_vec()),
        ("empty.ply", Vec::new()),
    ];
    for (name, bytes) in cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let Err(e) = mesh::load_ply(&path) else { panic!("{name} loaded") };
        let e = format!("{e:#}");
        assert!(e.contains(name), "{e}");
    }
    if let Some(bunny) = shared_mesh("bunny.ply") {
        let bytes = std::fs::read(bunny).unwrap();
        let path = dir.join("half-bunny.ply");
        std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
        let e = format!("{:#}", mesh::load_ply(&path).unwrap_err());
        assert!(e.contains("half-bunny.ply"), "{e}");
    }
}

// ---------------------------------------------------------------- OBJ

#[test]
fn obj_uvs_are_flipped_like_mitsubas_and_agree_with_the_rectangle() {
    let Some(path) = shared_mesh("rectangle.obj") else { return };
    let (mesh, _) = mesh::load_obj(&path, false).unwrap();
    let uvs = mesh.uvs.as_ref().expect("rectangle.obj has vt");
    // After the flip, uv = xy / 2 + 1/2 at every corner, exactly Mitsuba's rectangle parameterization.
    for (p, uv) in mesh.positions.iter().zip(uvs) {
        assert_eq!(*uv, p.truncate() * 0.5 + 0.5, "corner {p}");
    }
    let dir = temp_dir("obj-flip");
    let filename = path.display();
    let scene = load_scene_with(&dir, &format!(
        "<shape type=\"obj\"><string name=\"filename\" value=\"{filename}\"/></shape>\n\
         <shape type=\"obj\"><string name=\"filename\" value=\"{filename}\"/><boolean name=\"flip_tex_coords\" value=\"false\"/></shape>"
    ))
    .unwrap();
    let (flipped, raw) = (soup(&scene.shapes[0]), soup(&scene.shapes[1]));
    for (t, (a, b)) in flipped.triangles.iter().zip(flipped.uvs.unwrap().iter().zip(raw.uvs.unwrap())) {
        for k in 0..3 {
            assert_eq!(a[k], t[k].truncate() * 0.5 + 0.5);
            assert_eq!(b[k], Vec2::new(a[k].x, 1.0 - a[k].y));
        }
    }
}

// ---------------------------------------------------------------- built-in shapes

#[test]
fn disk_and_cylinder_areas_match_the_analytic_shapes() {
    let dir = temp_dir("areas");
    let scene = load_scene_with(&dir, concat!(
        "<shape type=\"disk\"><transform name=\"to_world\"><scale value=\"2\"/><translate z=\"1\"/></transform></shape>\n",
        "<shape type=\"cylinder\"><float name=\"radius\" value=\"0.5\"/><point name=\"p0\" x=\"1\" y=\"0\" z=\"0\"/>",
        "<point name=\"p1\" x=\"1\" y=\"2\" z=\"0\"/></shape>\n",
    ))
    .unwrap();
    // The disk is analytic; the cylinder's inscribed polygon falls short of the true area by less
    // than 1e-5 (see load::mesh::primitives).
    let Geometry::Disk { center, u, v } = scene.shapes[0].geometry else { panic!("the disk is analytic") };
    assert_eq!((center, u, v), (Vec3::Z, Vec3::X * 2.0, Vec3::Y * 2.0));
    assert!((caustic_kernel::shape::disk::area(u, v) as f64 - 4.0 * std::f64::consts::PI).abs() < 1e-5);
    let cylinder = area(soup(&scene.shapes[1]).triangles);
    let true_cylinder = 2.0 * std::f64::consts::PI * 0.5 * 2.0;
    assert!(
        cylinder < true_cylinder && cylinder > true_cylinder * (1.0 - 1e-5),
        "cylinder area {cylinder}, expected {true_cylinder}"
    );
    const { assert!(primitives::SEGMENTS >= 512) };
}

/// Geometric and shading normals of a cylinder from (1, 0, 0) to (1, 2, 0), radius 0.5: unit,
/// perpendicular to the axis, pointing away from it.
fn assert_cylinder_faces_outward(shape: &Shape) {
    let s = soup(shape);
    let axis_point = |p: Vec3| Vec3::new(1.0, p.y, 0.0);
    let normals = s.normals.expect("a cylinder has smooth normals");
    for (t, n) in s.triangles.iter().zip(normals) {
        let centre = (t[0] + t[1] + t[2]) / 3.0;
        let outward = (centre - axis_point(centre)).normalize();
        let geometric = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
        assert!(geometric.dot(outward) > 0.999, "facet at {centre} faces {geometric}");
        for k in 0..3 {
            let radial = (t[k] - axis_point(t[k])).normalize();
            assert!(
                n[k].dot(radial) > 0.99999 && (n[k].length() - 1.0).abs() < 1e-5,
                "normal {} at {}",
                n[k],
                t[k]
            );
        }
    }
}

#[test]
fn cylinder_normals_and_uvs_follow_mitsuba() {
    let dir = temp_dir("cylinder");
    let cylinder = "<float name=\"radius\" value=\"0.5\"/><point name=\"p0\" x=\"1\" y=\"0\" z=\"0\"/><point name=\"p1\" x=\"1\" y=\"2\" z=\"0\"/>";
    let scene = load_scene_with(&dir, &format!(
        "<shape type=\"cylinder\">{cylinder}</shape>\n\
         <shape type=\"cylinder\">{cylinder}<boolean name=\"flip_normals\" value=\"true\"/></shape>\n\
         <shape type=\"cylinder\">{cylinder}<transform name=\"to_world\"><scale z=\"-1\"/></transform></shape>"
    ))
    .unwrap();
    assert_cylinder_faces_outward(&scene.shapes[0]);
    // flip_normals is the kernel's business: the geometry stays, the shape carries the flag.
    assert!(!scene.shapes[0].flip_normals && scene.shapes[1].flip_normals);
    assert_eq!(soup(&scene.shapes[0]).triangles, soup(&scene.shapes[1]).triangles);
    // A mirroring to_world (z ↦ −z leaves this cylinder in place) must not turn it inside out.
    assert_cylinder_faces_outward(&scene.shapes[2]);

    // uv = (φ/2π, t) with t along the axis from p0 and φ measured from the first vector of
    // Mitsuba's basis around the axis (Duff et al.).
    let s = soup(&scene.shapes[0]);
    let (first, second) = primitives::orthonormal_basis(Vec3::Y);
    for (t, uv) in s.triangles.iter().zip(s.uvs.expect("a cylinder has uvs")) {
        // No triangle spans the seam: each covers one segment's worth of u.
        let (u_min, u_max) = (uv[0].x.min(uv[1].x).min(uv[2].x), uv[0].x.max(uv[1].x).max(uv[2].x));
        assert!(
            u_max - u_min < 1.5 / primitives::SEGMENTS as f32,
            "triangle at {} spans u {u_min}..{u_max}",
            t[0]
        );
        for k in 0..3 {
            let d = t[k] - Vec3::new(1.0, t[k].y, 0.0);
            let u =
                d.dot(second).atan2(d.dot(first)).rem_euclid(std::f32::consts::TAU) / std::f32::consts::TAU;
            // u = 0 and u = 1 are the same place on the seam.
            let distance = (uv[k].x - u).abs();
            assert!(distance.min(1.0 - distance) < 1e-4, "u {} at {}, expected {u}", uv[k].x, t[k]);
            assert!((uv[k].y - t[k].y / 2.0).abs() < 1e-6, "v {} at {}", uv[k].y, t[k]);
        }
    }
}

/// Rays straight down onto disks: the hit lies on the circle's interior only, its uv is Mitsuba's
/// (r, φ/2π) in the disk's own coordinates, and the disk faces +z — mirrored too, since Mitsuba's
/// normal is the inverse transpose of +z.
#[test]
fn disk_hits_uvs_and_normals_follow_mitsuba() {
    use caustic_kernel::camera::Ray;
    use caustic_kernel::shape::{intersect, surface_point, triangle::RayShear, Hit};
    let dir = temp_dir("disk");
    let scene = load_scene_with(&dir, "<shape type=\"disk\"/>\n<shape type=\"disk\"><transform name=\"to_world\"><scale x=\"-1\"/><translate z=\"-3\"/></transform></shape>").unwrap();
    let buffers = caustic::prepare::buffers::build(&scene).unwrap();
    for (k, z) in [(0usize, 0.0f32), (1, -3.0)] {
        let prim =
            buffers.prims.iter().find(|p| (p.p0[2] - z).abs() < 1e-6).expect("both disks are primitives");
        let mirror = if k == 1 { -1.0 } else { 1.0 };
        for (x, y) in [(0.5f32, 0.0f32), (0.0, 0.7), (-0.3, -0.4), (0.99, 0.1), (1.01, 0.0), (0.8, 0.8)] {
            let ray = Ray { origin: Vec3::new(x, y, z + 1.0), dir: -Vec3::Z, t_min: 0.0, t_max: f32::MAX };
            let hit = intersect(prim, &ray, &RayShear::of(&ray), f32::MAX);
            let r = (x * x + y * y).sqrt();
            assert_eq!(hit.is_some(), r <= 1.0, "disk {k}: ({x}, {y}) at r = {r}");
            let Some((t, ab)) = hit else { continue };
            assert!((t - 1.0).abs() < 1e-6);
            let sp = surface_point(
                prim,
                &buffers.attributes,
                &Hit { t, prim: 0, uv: ab, instance: caustic_kernel::layout::NONE },
                &ray,
            );
            assert!((sp.p - Vec3::new(x, y, z)).length() < 1e-6, "hit point {}", sp.p);
            assert!((sp.ng - Vec3::Z).length() < 1e-6, "disk {k} faces {}", sp.ng);
            // φ runs from the disk's local x axis, which the mirror sends to −x.
            let phi = y.atan2(mirror * x).rem_euclid(std::f32::consts::TAU) / std::f32::consts::TAU;
            assert!(
                (sp.uv.x - r).abs() < 1e-6 && (sp.uv.y - phi).abs() < 1e-5,
                "disk {k}: uv {} at ({x}, {y}), expected ({r}, {phi})",
                sp.uv
            );
        }
    }
}

#[test]
fn rectangle_and_cube_carry_mitsubas_uvs() {
    let dir = temp_dir("flat");
    let scene = load_scene_with(&dir, "<shape type=\"rectangle\"/>\n<shape type=\"cube\"/>").unwrap();
    let rectangle = soup(&scene.shapes[0]);
    assert_eq!(rectangle.triangles.len(), 2);
    assert!(rectangle.normals.is_none());
    for (t, uv) in rectangle.triangles.iter().zip(rectangle.uvs.unwrap()) {
        assert!((t[1] - t[0]).cross(t[2] - t[0]).z > 0.0, "the rectangle faces +z");
        for k in 0..3 {
            assert_eq!(uv[k], t[k].truncate() * 0.5 + 0.5);
        }
    }
    let cube = soup(&scene.shapes[1]);
    assert_eq!(cube.triangles.len(), 12);
    assert!((area(cube.triangles) - 24.0).abs() < 1e-6);
    for (t, uv) in cube.triangles.iter().zip(cube.uvs.unwrap()) {
        let outward = (t[0] + t[1] + t[2]) / 3.0;
        assert!((t[1] - t[0]).cross(t[2] - t[0]).dot(outward) > 0.0, "cube faces point outward");
        assert!(uv.iter().all(|uv| (uv.x == 0.0 || uv.x == 1.0) && (uv.y == 0.0 || uv.y == 1.0)));
    }
}

// ---------------------------------------------------------------- shape options and scenes

#[test]
fn face_normals_drop_and_default_generates_smooth_normals() {
    let Some(path) = shared_mesh("sphere.ply") else { return };
    let dir = temp_dir("face-normals");
    let filename = path.display();
    let scene = load_scene_with(&dir, &format!(
        "<shape type=\"ply\"><string name=\"filename\" value=\"{filename}\"/></shape>\n\
         <shape type=\"ply\"><string name=\"filename\" value=\"{filename}\"/><boolean name=\"face_normals\" value=\"true\"/></shape>"
    ))
    .unwrap();
    let smooth = soup(&scene.shapes[0]);
    let normals = smooth.normals.expect("generated normals");
    // sphere.ply is a sphere about the origin: generated normals point nearly radially.
    for (t, n) in smooth.triangles.iter().zip(normals) {
        for k in 0..3 {
            assert!(n[k].dot(t[k].normalize()) > 0.98, "normal {} at {}", n[k], t[k]);
        }
    }
    assert!(soup(&scene.shapes[1]).normals.is_none());
}

#[test]
fn generated_normals_are_right_under_a_non_uniform_to_world() {
    // A sphere stretched 4× along x: generated normals follow the ellipsoid, n ∝ (x/16, y, z).
    let Some(path) = shared_mesh("sphere.ply") else { return };
    let dir = temp_dir("non-uniform");
    let scene = load_scene_with(&dir, &format!(
        "<shape type=\"ply\"><string name=\"filename\" value=\"{}\"/><transform name=\"to_world\"><scale x=\"4\" y=\"1\" z=\"1\"/></transform></shape>",
        path.display()
    ))
    .unwrap();
    let s = soup(&scene.shapes[0]);
    let mut worst = 1.0f32;
    for (t, n) in s.triangles.iter().zip(s.normals.unwrap()) {
        for k in 0..3 {
            let analytic = (t[k] / Vec3::new(16.0, 1.0, 1.0)).normalize();
            worst = worst.min(n[k].dot(analytic));
        }
    }
    assert!(worst > 0.95, "worst agreement {worst}");
}

#[test]
fn bad_mesh_files_in_a_scene_name_the_scene_line_and_the_file() {
    let dir = temp_dir("scene-errors");
    std::fs::write(dir.join("broken.ply"), b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n").unwrap();
    let e =
        load_error(&dir, "\n<shape type=\"ply\"><string name=\"filename\" value=\"broken.ply\"/></shape>");
    assert!(e.contains("scene.xml:3") && e.contains("broken.ply"), "{e}");
    let e = load_error(
        &dir,
        "<shape type=\"serialized\"><string name=\"filename\" value=\"missing.serialized\"/></shape>",
    );
    assert!(e.contains("scene.xml:2") && e.contains("missing.serialized"), "{e}");
    let e = load_error(&dir, "<shape type=\"cylinder\"><point name=\"p1\" x=\"0\" y=\"0\" z=\"0\"/></shape>");
    assert!(e.contains("scene.xml:2"), "{e}");
    if let Some(path) = shared_mesh("matpreview.serialized") {
        let shape = format!("<shape type=\"serialized\"><string name=\"filename\" value=\"{}\"/><integer name=\"shape_index\" value=\"3\"/></shape>", path.display());
        let e = load_error(&dir, &shape);
        assert!(
            e.contains("scene.xml:2") && e.contains("matpreview.serialized") && e.contains("out of range"),
            "{e}"
        );
        let e = load_error(&dir, &shape.replace("value=\"3\"", "value=\"-1\""));
        assert!(e.contains("scene.xml:2") && e.contains("shape_index"), "{e}");
    }
}

#[test]
fn shared_shape_scenes_load() {
    let Some(shared) = shared_dir_if_present() else { return };
    let scenes = shared.join("scenes/mitsuba/docs/scenes");
    let disk =
        caustic::load::mitsuba::load(&scenes.join("shape_disk.xml"), &[]).expect("shape_disk.xml loads");
    assert!(matches!(disk.shapes[0].geometry, Geometry::Disk { .. }), "the disk is analytic");
    for (file, kind_count) in
        [("shape_ply_bunny.xml", 69451), ("shape_cylinder_twosided.xml", 2 * primitives::SEGMENTS as usize)]
    {
        let scene =
            caustic::load::mitsuba::load(&scenes.join(file), &[]).unwrap_or_else(|e| panic!("{file}: {e:#}"));
        // The first shape is the one the scene is about; the included stage follows.
        let s = soup(&scene.shapes[0]);
        assert_eq!(s.triangles.len(), kind_count, "{file}");
        assert!(s.triangles.iter().flatten().all(|p| p.is_finite()), "{file}");
    }
}
