//! Rendering an OBJ/MTL file directly: MTL `Kd`/`Ks`/`Ns` become the modified Phong BRDF (`Kd` alone:
//! Lambert), `Ke` an area emitter; an automatic camera frames the model and a sphere light lights it.
use crate::scene::mesh;
use crate::scene::rgba;
use crate::scene::{
    look_at, warn, FilmMode, Filter, Geometry, Integrator, Projection, SamplerKind, Scene, Sensor, Shape,
};
use anyhow::{bail, Result};
use caustic_kernel::layout::{Material, BSDF_DIFFUSE, BSDF_PHONG};
use glam::Vec3;
use std::path::Path;

/// Refuses an MTL entry with a NaN, infinite or negative `Kd`, `Ks`, `Ke` or `Ns` (`Ke nan`
/// rendered black, a negative `Kd` negative pixels), naming the MTL file and line.
fn check_material(m: &tobj::Material, obj: &Path) -> Result<()> {
    for (key, values) in [
        ("Kd", m.diffuse.map(Vec::from)),
        ("Ks", m.specular.map(Vec::from)),
        ("Ke", m.emissive.map(Vec::from)),
        ("Ns", m.shininess.map(|n| vec![n])),
    ] {
        if let Some(v) = values.filter(|v| v.iter().any(|c| !c.is_finite() || *c < 0.0)) {
            bail!(
                "{}: material '{}': {key} must be finite and non-negative, got {v:?}",
                mtl_location(obj, &m.name, key),
                m.name
            );
        }
    }
    Ok(())
}

/// `file.mtl:line` of `key` in material `name` of the OBJ's material libraries (tobj keeps no
/// lines), or the OBJ's path when it cannot be found.
fn mtl_location(obj: &Path, name: &str, key: &str) -> String {
    let dir = obj.parent().unwrap_or(Path::new(""));
    let text = crate::system::files::read_to_string(obj, "OBJ file").unwrap_or_default();
    let libraries =
        text.lines().filter_map(|l| l.trim().strip_prefix("mtllib ")).flat_map(str::split_whitespace);
    for library in libraries {
        let path = dir.join(library);
        let Ok(mtl) = crate::system::files::read_to_string(&path, "material library") else { continue };
        let mut current = false;
        for (i, line) in mtl.lines().enumerate() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("newmtl") => current = words.next() == Some(name),
                Some(k) if current && k == key => return format!("{}:{}", path.display(), i + 1),
                _ => {}
            }
        }
    }
    obj.display().to_string()
}

/// The caustic material and emission of an MTL entry.
fn convert_material(
    m: &tobj::Material,
    path: &Path,
    warnings: &mut Vec<String>,
) -> (Material, Option<[f32; 3]>) {
    let kd = m.diffuse.unwrap_or([0.5; 3]);
    let ks = m.specular.unwrap_or([0.0; 3]);
    let mut material = if ks.iter().any(|&c| c > 0.0) {
        Material {
            kind: BSDF_PHONG,
            eta: m.shininess.unwrap_or(30.0).clamp(0.0, 1.0e6),
            reflectance: rgba(kd),
            specular_reflectance: rgba(ks),
            ..Default::default()
        }
    } else {
        Material { kind: BSDF_DIFFUSE, reflectance: rgba(kd), ..Default::default() }
    };
    // Energy conservation needs kd + ks ≤ 1 per channel; scale both down where an MTL exceeds it.
    for c in 0..3 {
        let sum = material.reflectance[c] + material.specular_reflectance[c];
        if sum > 1.0 {
            let name = &m.name;
            warn(
                warnings,
                format!("{}: material '{name}': Kd + Ks > 1, scaled down to conserve energy", path.display()),
            );
            material.reflectance[c] /= sum;
            material.specular_reflectance[c] /= sum;
        }
    }
    let emission = m.emissive.filter(|e| e.iter().any(|&c| c > 0.0));
    (material, emission)
}

/// The largest model radius framed: the light sits about 5 radii from the model, and squared
/// distances must stay below f32's 3.4e38 (the square root of which is 1.8e19) with room to spare.
const MAX_RADIUS: f64 = 1e18;

/// Loads an OBJ file as a scene; `strict` refuses it when its material library does not load
/// (which otherwise gives every triangle the default grey).
pub fn load(path: &Path, strict: bool) -> Result<Scene> {
    let mut warnings = Vec::new();
    let (mesh, mtl) = super::mesh::load_obj(path, true)?;
    let mtl = match mtl {
        Ok(mtl) => mtl,
        Err(message) if strict => anyhow::bail!("{message} (--strict)"),
        Err(message) => {
            warn(&mut warnings, message);
            Vec::new()
        }
    };
    let mut materials =
        vec![Material { kind: BSDF_DIFFUSE, reflectance: [0.5, 0.5, 0.5, 0.0], ..Default::default() }];
    let mut emissions = vec![None];
    for m in &mtl {
        check_material(m, path)?;
        let (material, emission) = convert_material(m, path, &mut warnings);
        materials.push(material);
        emissions.push(emission);
    }
    let mut with_normals = mesh.clone();
    with_normals.ensure_normals();
    let mesh::Triangles { triangles, normals, uvs, .. } = with_normals.transformed(glam::Mat4::IDENTITY);
    // One shape per material, so that emission stays per shape.
    let mut shapes = Vec::new();
    // The triangles `transformed` keeps, by the same test, to index its output.
    let kept: Vec<usize> = (0..mesh.indices.len() / 3)
        .filter(|&t| {
            mesh::face_normal([0, 1, 2].map(|k| mesh.positions[mesh.indices[3 * t + k] as usize])).is_some()
        })
        .collect();
    for (slot, emission) in emissions.iter().enumerate() {
        let select: Vec<usize> = (0..kept.len())
            .filter(|&i| mesh.triangle_materials[kept[i]].map_or(0, |m| m + 1) == slot)
            .collect();
        if select.is_empty() {
            continue;
        }
        shapes.push(Shape {
            origin: format!("{} (material {slot})", path.display()),
            geometry: Geometry::Triangles {
                triangles: select.iter().map(|&i| triangles[i]).collect(),
                normals: normals.as_ref().map(|n| select.iter().map(|&i| n[i]).collect()),
                uvs: uvs.as_ref().map(|u| select.iter().map(|&i| u[i]).collect()),
                attributes: Vec::new(),
            },
            material: slot as u32,
            emission: *emission,
            emission_texture: None,
            emission_directional: false,
            flip_normals: false,
        });
    }

    // Frame the model: look at its bounding box from the front (+z), slightly above.
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    // In f64, and refused where single precision cannot hold the result: the camera setup of a
    // model with coordinates near 1e19 overflowed (a panic in look_at).
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-3);
    if radius > MAX_RADIUS {
        bail!(
            "{}: the model spans {:.3e} units (from {lo} to {hi}); caustic squares distances in single \
             precision, so a model over {MAX_RADIUS:.0e} units across cannot be framed: scale it down",
            path.display(),
            2.0 * radius
        );
    }
    let fov_x = 40.0f32;
    let distance = radius / ((fov_x as f64).to_radians() * 0.5).sin() * 1.1;
    let eye = center + glam::DVec3::new(0.0, 0.35, 1.0).normalize() * distance;
    let to_world = look_at(eye.as_vec3(), center.as_vec3(), Vec3::Y)
        .expect("the view direction is never parallel to +y");
    // A sphere light above and to the right, sized and scaled for an irradiance of ≈3 at the model.
    let light_pos = center + glam::DVec3::new(0.8, 1.6, 1.2).normalize() * distance * 1.5;
    let light_radius = radius * 0.15;
    let d2 = (light_pos - center).length_squared();
    let radiance = (3.0 * d2 / (std::f64::consts::PI * light_radius * light_radius)) as f32;
    let (light_pos, light_radius, distance) = (light_pos.as_vec3(), light_radius as f32, distance as f32);
    materials.push(Material { kind: BSDF_DIFFUSE, ..Default::default() });
    shapes.push(Shape {
        origin: "automatic sphere light".into(),
        geometry: Geometry::Sphere { center: light_pos, radius: light_radius, frame: glam::Mat3::IDENTITY },
        material: materials.len() as u32 - 1,
        emission: Some([radiance; 3]),
        emission_texture: None,
        emission_directional: false,
        flip_normals: false,
    });
    Ok(Scene {
        sensor: Sensor {
            projection: Projection::Perspective,
            crop: None,
            to_world,
            fov_x,
            near_clip: distance * 1e-3,
            far_clip: distance * 1e3,
            principal_point_offset: [0.0; 2],
            width: 512,
            height: 512,
            filter: Filter::Gaussian { stddev: 0.5, radius: 2.0 },
            sampler: SamplerKind::Stratified,
            spp: 64,
            film: FilmMode::Splat,
        },
        integrator: Integrator::default(),
        materials,
        shapes,
        instancing: Default::default(),
        emitters: vec![],
        textures: vec![],
        weight_tables: vec![],
        aovs: None,
        warnings,
    })
}
