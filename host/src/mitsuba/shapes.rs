//! Shape plugins: `obj`, `sphere` (analytic), `rectangle`, `cube`; each with `to_world`,
//! `flip_normals`, `face_normals`, a nested or referenced BSDF and an optional area emitter.
use super::props::Props;
use super::Loader;
use crate::mesh::{self, Mesh};
use crate::scene::{Geometry, Shape};
use anyhow::{bail, Result};
use caustic_kernel::scene::{Material, BSDF_DIFFUSE};
use glam::{Mat4, Vec3};

/// Mitsuba's `rectangle`: [-1, 1]² in the z = 0 plane, facing +z.
fn rectangle() -> Mesh {
    Mesh {
        positions: vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0)],
        indices: vec![0, 1, 2, 2, 3, 0],
        corner_normals: None,
        triangle_materials: vec![None; 2],
    }
}

/// Mitsuba's `cube`: [-1, 1]³ with outward faces.
fn cube() -> Mesh {
    let mut m = Mesh::default();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let n = Vec3::from_array(std::array::from_fn(|i| if i == axis { sign } else { 0.0 }));
            let u = Vec3::from_array(std::array::from_fn(|i| if i == (axis + 1) % 3 { 1.0 } else { 0.0 }));
            let v = n.cross(u);
            let base = m.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                m.positions.push(n + u * a + v * b);
            }
            m.indices.extend([base, base + 1, base + 2, base + 2, base + 3, base]);
        }
    }
    m.triangle_materials = vec![None; 12];
    m
}

impl Loader {
    pub(crate) fn load_shape(&mut self, props: &Props) -> Result<()> {
        let to_world = props.transform("to_world")?;
        let flip_normals = props.boolean("flip_normals", false)?;
        let face_normals = props.boolean("face_normals", false)?;
        let geometry = match props.kind.as_str() {
            "obj" => {
                let Some(name) = props.string("filename")? else { bail!("{}: obj shape needs a 'filename'", props.loc) };
                let path = self.resolve(&name, &props.loc)?;
                let (mesh, _) = mesh::load_obj(&path, false).map_err(|e| anyhow::anyhow!("{}: {e:#}", props.loc))?;
                mesh_geometry(mesh, to_world, face_normals)
            }
            "rectangle" => mesh_geometry(rectangle(), to_world, true),
            "cube" => mesh_geometry(cube(), to_world, true),
            "sphere" => {
                let center = props.point("center", Vec3::ZERO)?;
                let radius = props.float("radius", 1.0)?;
                // Like Mitsuba, fold a uniform scale and translation of to_world into centre and radius.
                let (scale, _, _) = to_world.to_scale_rotation_translation();
                if (scale.x - scale.y).abs() > 1e-4 * scale.x.abs() || (scale.x - scale.z).abs() > 1e-4 * scale.x.abs() {
                    bail!("{}: a sphere's to_world may only scale uniformly", props.loc);
                }
                let center = to_world.transform_point3(center);
                let radius = radius * scale.x.abs();
                if !(radius > 0.0 && radius.is_finite() && center.is_finite()) {
                    bail!("{}: sphere needs a finite positive radius and centre", props.loc);
                }
                Geometry::Sphere { center, radius }
            }
            other => {
                self.warn(&format!("{}: shape type '{other}' is not supported yet; ignored", props.loc));
                props.mark_all_used();
                return Ok(());
            }
        };
        if let Geometry::Triangles { triangles, .. } = &geometry {
            if triangles.is_empty() {
                self.warn(&format!("{}: shape has no non-degenerate triangles; ignored", props.loc));
                props.mark_all_used();
                return Ok(());
            }
        }
        let material = self.shape_material(props)?;
        let mut emission = None;
        for e in props.nested("emitter") {
            let ep = self.props(&props.path, props.doc, e.node)?;
            emission = self.load_shape_emitter(&ep)?;
        }
        self.warn_unused(props);
        self.shapes.push(Shape { origin: props.loc.to_string(), geometry, material, emission, flip_normals });
        Ok(())
    }

    /// The shape's nested `<bsdf>` or `<ref>`; Mitsuba's default is a diffuse BSDF.
    fn shape_material(&mut self, props: &Props) -> Result<u32> {
        let mut entries = props.nested("bsdf");
        entries.extend(props.nested("ref"));
        match entries.first() {
            Some(e) => {
                let p = self.props(&props.path, props.doc, e.node)?;
                self.load_bsdf(&p)
            }
            None => {
                self.materials.push(Material { kind: BSDF_DIFFUSE, diffuse: [0.5, 0.5, 0.5, 0.0], ..Default::default() });
                Ok(self.materials.len() as u32 - 1)
            }
        }
    }
}

fn mesh_geometry(mut mesh: Mesh, to_world: Mat4, face_normals: bool) -> Geometry {
    if face_normals {
        mesh.corner_normals = None;
    } else {
        mesh.ensure_normals();
    }
    let (triangles, normals) = mesh.transformed(to_world);
    Geometry::Triangles { triangles, normals }
}
