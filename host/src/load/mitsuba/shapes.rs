//! Shape plugins: `obj`, `ply`, `serialized` (meshes from files), `rectangle`, `cube`, `disk`,
//! `cylinder` (tessellated; see `load::mesh::primitives`) and `sphere` (analytic); each with `to_world`,
//! `flip_normals`, `face_normals`, a nested or referenced BSDF and an optional area emitter.
//! `shapegroup` and `instance` (stored once: `crate::scene::instancing`) and `merge` hold other shapes.
//! `flip_normals` travels to the kernel as a flag of the shape, which turns both the geometric and
//! the shading normal around, as Mitsuba does.
use super::loader::AreaEmission;
use super::loader::Loader;
use super::props::Props;
use super::xml::Loc;
use crate::load::mesh::{self, primitives};
use crate::scene::instancing::{self, Instance};
use crate::scene::mesh::{Mesh, Triangles};
use crate::scene::{Geometry, Shape};
use anyhow::{anyhow, bail, Result};
use caustic_kernel::layout::{Material, BSDF_DIFFUSE};
use glam::{Mat3, Mat4, Vec3};

impl Loader {
    pub(crate) fn load_shape(&mut self, props: &Props) -> Result<()> {
        match props.kind.as_str() {
            "shapegroup" => return self.load_shape_group(props),
            "instance" => return self.load_instance(props),
            "merge" => return self.load_merge(props),
            _ => {}
        }
        let to_world = props.transform("to_world")?;
        let mut flip_normals = props.boolean("flip_normals", false)?;
        let face_normals = props.boolean("face_normals", false)?;
        let mut geometry = match props.kind.as_str() {
            "obj" | "ply" | "serialized" => {
                mesh_geometry(self.load_mesh_file(props)?, to_world, face_normals)
            }
            // Mitsuba's rectangle and cube are flat, whatever face_normals says.
            "rectangle" => flat_geometry(primitives::rectangle(), to_world),
            "cube" => flat_geometry(primitives::cube(), to_world),
            "disk" => {
                flip_normals ^= Mat3::from_mat4(to_world).determinant() < 0.0;
                disk_geometry(to_world, props)?
            }
            "cylinder" => {
                let radius = props.float("radius", 1.0)?;
                let (p0, p1) = (props.point("p0", Vec3::ZERO)?, props.point("p1", Vec3::Z)?);
                let Some(placement) = primitives::cylinder_placement(radius, p0, p1) else {
                    bail!("{}: a cylinder needs distinct end points p0 and p1", props.loc);
                };
                tessellated_geometry(primitives::unit_cylinder(), to_world * placement)
            }
            "sphere" => {
                let center = props.point("center", Vec3::ZERO)?;
                let radius = props.float("radius", 1.0)?;
                // Like Mitsuba, fold a uniform scale and translation of to_world into centre and radius.
                // A mirror keeps a sphere a sphere: compare the scales' magnitudes.
                let scale = to_world.to_scale_rotation_translation().0.abs();
                if (scale.x - scale.y).abs() > 1e-4 * scale.x || (scale.x - scale.z).abs() > 1e-4 * scale.x {
                    bail!("{}: a sphere's to_world may only scale uniformly", props.loc);
                }
                let center = to_world.transform_point3(center);
                let frame = Mat3::from_mat4(to_world) * (1.0 / scale.x);
                // Mitsuba's sphere keeps a mirror's sign in its radius: its normals face inwards.
                flip_normals ^= frame.determinant() < 0.0;
                let radius = radius * scale.x;
                if !(radius > 0.0 && radius.is_finite() && center.is_finite()) {
                    bail!("{}: sphere needs a finite positive radius and centre", props.loc);
                }
                Geometry::Sphere { center, radius, frame }
            }
            other => {
                refuse_lost_sensor(props)?;
                let message = format!("{}: shape type '{other}' is not supported yet; ignored", props.loc);
                self.substituted(format!("shape '{other}'"), &props.loc, message);
                props.mark_all_used();
                return Ok(());
            }
        };
        if let Geometry::Triangles { triangles, .. } = &geometry {
            if triangles.is_empty() {
                refuse_lost_sensor(props)?;
                self.warn(&format!("{}: shape has no non-degenerate triangles; ignored", props.loc));
                props.mark_all_used();
                return Ok(());
            }
        }
        let (material, emission) = self.shape_bsdf_and_emitter(props)?;
        // A mesh keeps only the attributes its textures read: most scenes store and upload none.
        self.keep_read_attributes(props, &mut geometry, material)?;
        let sensors = props.nested("sensor");
        if let Some(second) = sensors.get(1) {
            bail!("{}: a shape takes one sensor; the first is at {}", second.loc, sensors[0].loc);
        }
        for e in sensors {
            let sensor_props = self.props(props.src, e.node)?;
            let sensor = self.load_shape_sensor(&sensor_props, self.shapes.len())?;
            self.set_sensor(sensor, &e.loc);
        }
        self.warn_unused(props);
        let emission_directional = emission.is_some_and(|e| e.directional);
        let (emission, emission_texture) = (emission.map(|e| e.radiance), emission.and_then(|e| e.texture));
        let origin = props.loc.to_string();
        self.shapes.push(Shape {
            origin,
            geometry,
            material,
            emission,
            emission_texture,
            emission_directional,
            flip_normals,
        });
        Ok(())
    }

    /// The shapes nested in `props` (a `shapegroup` or a `merge`), loaded and taken off the scene's
    /// list. Groups do not nest, as in Mitsuba.
    fn nested_shapes(&mut self, props: &Props) -> Result<Vec<Shape>> {
        let start = self.shapes.len();
        for e in props.nested("shape") {
            let child = self.props(props.src, e.node)?;
            if matches!(child.kind.as_str(), "shapegroup" | "instance") {
                bail!("{}: a {} cannot hold a {} (Mitsuba refuses it too)", e.loc, props.kind, child.kind);
            }
            self.load_shape(&child)?;
        }
        if let Some(loc) = self.meter_shape.as_ref().filter(|(shape, _)| *shape >= start).map(|(_, loc)| loc)
        {
            bail!(
                "{loc}: an irradiancemeter inside a {} is not supported (attach it to a shape of the scene)",
                props.kind
            );
        }
        Ok(self.shapes.drain(start..).collect())
    }

    /// Mitsuba's `shapegroup`: shapes kept aside under the group's id, rendered only where an
    /// `instance` places them. Emitters cannot be instanced (Mitsuba refuses them as well).
    fn load_shape_group(&mut self, props: &Props) -> Result<()> {
        let Some(id) = props.id.clone() else { bail!("{}: a shapegroup needs an 'id'", props.loc) };
        let group = self.nested_shapes(props)?;
        if let Some(s) = group.iter().find(|s| s.emission.is_some()) {
            bail!("{}: an emitter in a shapegroup cannot be instanced (Mitsuba refuses it too)", s.origin);
        }
        if group.is_empty() {
            self.warn(&format!("{}: shapegroup '{id}' holds no shape", props.loc));
        }
        self.warn_unused(props);
        // Spheres are placed as spheres (`load_instance`); the rest is stored once.
        let (spheres, rest) = group.into_iter().partition(|s| matches!(s.geometry, Geometry::Sphere { .. }));
        self.shape_groups.insert(id, self.instancing.groups.len());
        self.instancing.groups.push(rest);
        self.group_spheres.push(spheres);
        Ok(())
    }

    /// Mitsuba's `instance`: the shapes of the `shapegroup` it names by `<ref>`, placed by its
    /// `to_world`. Its triangles and disks stay in the group, stored once (`crate::scene::instancing`; the
    /// loader flattens groups placed only once at the end); its spheres are placed as spheres (one
    /// primitive each, no larger than an instance), and so is everything under a singular `to_world`.
    fn load_instance(&mut self, props: &Props) -> Result<()> {
        let to_world = props.transform("to_world")?;
        let refs = props.nested("ref");
        let [r] = refs.as_slice() else {
            bail!("{}: an instance names one shapegroup, by <ref id=\"...\"/>", props.loc)
        };
        let id = self.props(props.src, r.node)?.doc_attr_id()?;
        let Some(&group) = self.shape_groups.get(&id) else {
            bail!("{}: no shapegroup '{id}' is defined before this instance", r.loc)
        };
        let origin = props.loc.to_string();
        let mut placed = Vec::new();
        for shape in &self.group_spheres[group] {
            placed.push(instancing::placed(shape, to_world, &origin)?);
        }
        if instancing::invertible(to_world) {
            self.instancing.instances.push(Instance { group, to_world, origin });
        } else {
            for shape in &self.instancing.groups[group] {
                placed.push(instancing::placed(shape, to_world, &origin)?);
            }
        }
        self.shapes.extend(placed);
        self.warn_unused(props);
        Ok(())
    }

    /// Mitsuba's `merge`: its shapes, merged into one mesh there for speed; here simply loaded.
    fn load_merge(&mut self, props: &Props) -> Result<()> {
        let shapes = self.nested_shapes(props)?;
        self.shapes.extend(shapes);
        self.warn_unused(props);
        Ok(())
    }

    /// The mesh of an `obj`, `ply` or `serialized` shape in object space, with Mitsuba's
    /// `flip_tex_coords` (default true for OBJ, false for PLY; serialized files have no such option).
    fn load_mesh_file(&mut self, props: &Props) -> Result<Mesh> {
        let Some(name) = props.string("filename")? else {
            bail!("{}: a {} shape needs a 'filename'", props.loc, props.kind)
        };
        let path = self.resolve(&name, &props.loc)?;
        // load_obj has already flipped v, as Mitsuba's default for OBJ asks.
        let flip_tex_coords = match props.kind.as_str() {
            "obj" => !props.boolean("flip_tex_coords", true)?,
            "ply" => props.boolean("flip_tex_coords", false)?,
            _ => false,
        };
        let loaded = match props.kind.as_str() {
            "obj" => mesh::load_obj(&path, false).map(|(mesh, _)| mesh),
            "ply" => mesh::load_ply(&path).map(|(mesh, warnings)| {
                for w in warnings {
                    self.warn(&format!("{}: {w}", props.loc));
                }
                mesh
            }),
            _ => {
                let index = props.integer("shape_index", 0)?;
                let Ok(index) = u32::try_from(index) else {
                    bail!("{}: shape_index must be a non-negative integer, not {index}", props.loc)
                };
                mesh::load_serialized(&path, index)
            }
        };
        let mut mesh = loaded.map_err(|e| anyhow!("{}: {e:#}", props.loc))?;
        if flip_tex_coords {
            mesh.flip_tex_coords();
        }
        Ok(mesh)
    }

    /// The shape's BSDF and area emission, nested or referenced (`<ref>` may name either). Mitsuba's
    /// default BSDF is diffuse: grey for ordinary shapes, black for emitters. As in Mitsuba, a shape
    /// takes one BSDF and one area emitter: a second of either is an error, not a silent choice.
    fn shape_bsdf_and_emitter(&mut self, props: &Props) -> Result<(u32, Option<AreaEmission>)> {
        let mut material: Option<(u32, Loc)> = None;
        let mut emission: Option<(AreaEmission, Loc)> = None;
        // Marks them used; they are then taken in document order, so that the second is the one named.
        let (bsdfs, emitters, refs) = (props.nested("bsdf"), props.nested("emitter"), props.nested("ref"));
        let mut children: Vec<_> = bsdfs.iter().chain(&emitters).chain(&refs).collect();
        children.sort_by_key(|e| e.node.range().start);
        for e in children {
            // `<ref name="interior|exterior" id="…"/>` binds a participating medium, which caustic
            // does not render (its top-level `<medium>` is already reported as ignored).
            if e.tag == "ref" && matches!(e.name.as_deref(), Some("interior" | "exterior")) {
                let (side, id) =
                    (e.name.as_deref().unwrap_or_default(), e.node.attribute("id").unwrap_or("?"));
                let message = format!(
                    "{}: the {side} medium '{id}' is not supported (no participating media); ignored",
                    e.loc
                );
                self.ignored(
                    format!("<ref name=\"{side}\"> (a medium) of shape '{}'", props.kind),
                    &e.loc,
                    message,
                );
                continue;
            }
            let p = self.props(props.src, e.node)?;
            let named_emitter = match e.tag.as_str() {
                "ref" => self.named_area_emitters.get(&p.doc_attr_id()?).copied(),
                _ => None,
            };
            if e.tag == "emitter" || named_emitter.is_some() {
                if let Some((_, first)) = &emission {
                    bail!("{}: a shape takes one area emitter; the first is at {first}", e.loc);
                }
                let radiance = match named_emitter {
                    Some(radiance) => Some(radiance),
                    None => self.load_shape_emitter(&p)?,
                };
                emission = radiance.map(|r| (r, e.loc.clone()));
            } else {
                if let Some((_, first)) = &material {
                    bail!("{}: a shape takes one BSDF; the first is at {first}", e.loc);
                }
                material = Some((self.load_bsdf(&p)?, e.loc.clone()));
            }
        }
        let (material, emission) = (material.map(|(m, _)| m), emission.map(|(r, _)| r));
        let material = match material {
            Some(m) => m,
            None => {
                let grey = if emission.is_some() { 0.0 } else { 0.5 };
                self.materials.push(Material {
                    kind: BSDF_DIFFUSE,
                    reflectance: [grey, grey, grey, 0.0],
                    ..Default::default()
                });
                self.materials.len() as u32 - 1
            }
        };
        Ok((material, emission))
    }
}

/// A mesh read from a file. Mitsuba applies `to_world` before it generates missing normals (which
/// matters under non-uniform scaling), so this transforms first.
fn mesh_geometry(mut mesh: Mesh, to_world: Mat4, face_normals: bool) -> Geometry {
    mesh.transform(to_world);
    if face_normals {
        mesh.normals = None;
    } else {
        mesh.ensure_normals();
    }
    triangle_geometry(mesh.triangles())
}

fn flat_geometry(mesh: Mesh, to_world: Mat4) -> Geometry {
    triangle_geometry(mesh.transformed(to_world))
}

/// Mitsuba's disk, intersected analytically: the images of the local centre and x, y axes. Its
/// normal is the local +z through the inverse transpose of `to_world`, i.e. `u × v` flipped when
/// `to_world` mirrors (the caller folds that into the shape's `flip_normals`), so that the disk's uv
/// keep running from `u` towards `v` as Mitsuba's do.
fn disk_geometry(to_world: Mat4, props: &Props) -> Result<Geometry> {
    let center = to_world.transform_point3(Vec3::ZERO);
    let (u, v) = (to_world.transform_vector3(Vec3::X), to_world.transform_vector3(Vec3::Y));
    let area = u.cross(v).length();
    if !(area.is_finite() && area > 0.0 && center.is_finite()) {
        bail!("{}: the disk's to_world collapses or is not finite", props.loc);
    }
    Ok(Geometry::Disk { center, u, v })
}

/// A tessellated analytic shape. Mitsuba's disk and cylinder take their normal from the local one
/// through the inverse transpose of `to_world`, whatever the handedness of `to_world`; a mirroring
/// transform would turn the tessellation's winding (and so its geometric normal) inside out, so the
/// winding is reversed to match.
fn tessellated_geometry(mut mesh: Mesh, to_world: Mat4) -> Geometry {
    if Mat3::from_mat4(to_world).determinant() < 0.0 {
        mesh.reverse_winding();
    }
    triangle_geometry(mesh.transformed(to_world))
}

fn triangle_geometry(t: Triangles) -> Geometry {
    Geometry::Triangles { triangles: t.triangles, normals: t.normals, uvs: t.uvs, attributes: t.attributes }
}

/// A sensor in a shape that is left out (an unsupported type, no triangles) would measure nothing:
/// refused rather than dropped.
fn refuse_lost_sensor(props: &Props) -> Result<()> {
    if let Some(e) = props.nested("sensor").first() {
        bail!("{}: this sensor's shape ({}) is left out, so it cannot measure anything", e.loc, props.loc);
    }
    Ok(())
}
