//! Rendering an OBJ/MTL file directly: MTL `Kd`/`Ks`/`Ns` become the modified Phong BRDF (`Kd` alone:
//! Lambert), `Ke` an area emitter; an automatic camera frames the model and a sphere light lights it.
use crate::buffers::rgba;
use crate::mesh;
use crate::scene::{
    look_at, warn, Filter, Geometry, Integrator, Projection, SamplerKind, Scene, Sensor, Shape,
};
use anyhow::Result;
use caustic_kernel::layout::{Material, BSDF_DIFFUSE, BSDF_PHONG};
use glam::Vec3;
use std::path::Path;

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

/// Loads an OBJ file as a scene; `strict` refuses it when its material library does not load
/// (which otherwise gives every triangle the default grey).
pub fn load(path: &Path, strict: bool) -> Result<Scene> {
    let mut warnings = Vec::new();
    let (mesh, mtl) = mesh::load_obj(path, true)?;
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
        let (material, emission) = convert_material(m, path, &mut warnings);
        materials.push(material);
        emissions.push(emission);
    }
    let mut with_normals = mesh.clone();
    with_normals.ensure_normals();
    let mesh::Triangles { triangles, normals, uvs } = with_normals.transformed(glam::Mat4::IDENTITY);
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
            },
            material: slot as u32,
            emission: *emission,
            flip_normals: false,
        });
    }

    // Frame the model: look at its bounding box from the front (+z), slightly above.
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-3);
    let fov_x = 40.0f32;
    let distance = radius / (fov_x.to_radians() * 0.5).sin() * 1.1;
    let eye = center + Vec3::new(0.0, 0.35, 1.0).normalize() * distance;
    let to_world = look_at(eye, center, Vec3::Y).expect("the view direction is never parallel to +y");
    // A sphere light above and to the right, sized and scaled for an irradiance of ≈3 at the model.
    let light_pos = center + Vec3::new(0.8, 1.6, 1.2).normalize() * distance * 1.5;
    let light_radius = radius * 0.15;
    let d2 = (light_pos - center).length_squared();
    let radiance = 3.0 * d2 / (std::f32::consts::PI * light_radius * light_radius);
    materials.push(Material { kind: BSDF_DIFFUSE, ..Default::default() });
    shapes.push(Shape {
        origin: "automatic sphere light".into(),
        geometry: Geometry::Sphere { center: light_pos, radius: light_radius },
        material: materials.len() as u32 - 1,
        emission: Some([radiance; 3]),
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
            width: 512,
            height: 512,
            filter: Filter::Gaussian { stddev: 0.5, radius: 2.0 },
            sampler: SamplerKind::Stratified,
            spp: 64,
        },
        integrator: Integrator::default(),
        materials,
        shapes,
        emitters: vec![],
        textures: vec![],
        warnings,
    })
}
