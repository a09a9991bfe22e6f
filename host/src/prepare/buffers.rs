//! Scene description → the kernel's buffers: primitives in BVH order, BVH2 nodes (built by `obvhs`),
//! per-triangle attributes, materials, textures, lights with power-proportional selection, and the
//! table buffer (sampling distributions, texels, precomputed BSDF tables).
use crate::scene::{rgba, Emitter, Geometry, IntegratorKind, Projection, SamplerKind, Scene, Shape};
use anyhow::{bail, Result};
use caustic_kernel::bvh::STACK_SIZE;
use caustic_kernel::camera::{
    Camera, CAMERA_IRRADIANCE_METER, CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE, CAMERA_THIN_LENS,
};
use caustic_kernel::features;
use caustic_kernel::layout::*;
use caustic_kernel::spectrum::luminance;
use glam::{Mat3, Vec2, Vec3, Vec3A};
use obvhs::aabb::Aabb;
use std::f32::consts::PI;

/// Bins of the tabulated reconstruction filter.
pub const FILTER_BINS: u32 = 64;

/// Everything the kernel reads, ready to upload (GPU) or borrow (CPU). Every list has at least one
/// element because GPU buffers cannot be empty; unused placeholders are never read.
#[derive(Clone, Debug)]
pub struct SceneBuffers {
    pub nodes: Vec<BvhNode>,
    pub prims: Vec<Primitive>,
    pub attributes: Vec<TriangleAttributes>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub textures: Vec<Texture>,
    pub tables: Vec<f32>,
    /// `FrameParams` with everything but the per-dispatch fields filled in.
    pub params: FrameParams,
    /// What the scene uses (`caustic_kernel::features`); the kernel skips, and on the GPU compiles
    /// out, everything else.
    pub features: u32,
    /// The scene's `aov` or `depth` integrator (`crate::scene::aov`), rendered beside the image.
    pub aovs: Option<crate::scene::aov::AovSpec>,
    /// Host only, for AOVs (empty without): per primitive (BVH order), Mitsuba's shape index
    /// (`shape_indices`) and its index within the shape.
    pub prim_origins: Vec<[u32; 2]>,
    /// Primitives the scene's instances place, each group's counted once per instance (stored once
    /// each, in `prims`; `crate::scene::instancing`). 0 without instances.
    pub placed_prims: u64,
}

impl SceneBuffers {
    pub fn view(&self) -> SceneView<'_> {
        SceneView {
            nodes: &self.nodes,
            prims: &self.prims,
            attributes: &self.attributes,
            materials: &self.materials,
            lights: &self.lights,
            textures: &self.textures,
            tables: &self.tables,
            features: self.features,
            wide_bvh: false,
        }
    }
}

fn arr(v: Vec3) -> [f32; 3] {
    v.to_array()
}

/// Lights with their power and the emitter (shape or emitter element) each belongs to, for selection.
#[derive(Default)]
pub(crate) struct LightList {
    pub(crate) lights: Vec<Light>,
    powers: Vec<f32>,
    emitters: Vec<u32>,
    emitter_count: u32,
}

/// Light tracing's share of the selection probability spread evenly over emitters; the rest follows
/// power. Light paths are started where the power is, but power alone starves an emitter that is weak
/// overall and dominant somewhere (a spot light beside a sky, a small lamp beside a large one:
/// Veach's MIS scene) of samples, and that region's noise explodes.
const LIGHT_TRACING_UNIFORM_SHARE: f64 = 0.5;

impl LightList {
    /// Starts a new emitter: the lights pushed until the next call belong to it.
    fn begin_emitter(&mut self) {
        self.emitter_count += 1;
    }

    fn push(&mut self, light: Light, power: f32) -> u32 {
        self.lights.push(light);
        self.powers.push(if power.is_finite() { power.max(0.0) } else { 0.0 });
        self.emitters.push(self.emitter_count - 1);
        self.lights.len() as u32 - 1
    }

    /// Selection weights: a mixture of power-proportional selection and a uniform choice of emitter
    /// followed by power-proportional selection among its lights (the triangles of a mesh emitter),
    /// `uniform_share` of the latter.
    ///
    /// Next-event estimation takes `uniform_share` 1, as Mitsuba's `path` and `direct` do (every
    /// emitter equally likely): the half-and-half mixture light tracing uses gave
    /// `emitter_spot_no_texture` (two spot lights beside a sky) 2.3x Mitsuba's MSE at equal spp, each
    /// spot being chosen a sixth of the time instead of a third (BENCHMARKS.md, "The 23 shared scenes").
    fn selection_weights(&self, uniform_share: f64) -> Vec<f64> {
        let total: f64 = self.powers.iter().map(|&p| p as f64).sum();
        let mut per_emitter = vec![0.0f64; self.emitter_count as usize];
        let mut lights_per_emitter = vec![0u32; self.emitter_count as usize];
        for (&p, &e) in self.powers.iter().zip(&self.emitters) {
            per_emitter[e as usize] += p as f64;
            lights_per_emitter[e as usize] += 1;
        }
        let n = self.emitter_count.max(1) as f64;
        self.powers
            .iter()
            .zip(&self.emitters)
            .map(|(&p, &e)| {
                let by_power = if total > 0.0 { p as f64 / total } else { 0.0 };
                let group = per_emitter[e as usize];
                let within =
                    if group > 0.0 { p as f64 / group } else { 1.0 / lights_per_emitter[e as usize] as f64 };
                (1.0 - uniform_share) * by_power + uniform_share * within / n
            })
            .collect()
    }
}

/// Mitsuba's barycentric texture coordinates for meshes without any.
const DEFAULT_UVS: [Vec2; 3] = [Vec2::ZERO, Vec2::X, Vec2::Y];

/// Primitive records and their attributes in scene order, and the area lights on them.
pub(crate) fn primitives(
    shapes: &[Shape],
    light_tracing: bool,
    lights: &mut LightList,
    blocks: &mut crate::prepare::attribute_buffers::AttributeBlocks,
) -> (Vec<Primitive>, Vec<TriangleAttributes>) {
    let mut prims = Vec::new();
    let mut attributes = Vec::new();
    for shape in shapes {
        // Mitsuba's `directionalarea` lights nothing that path tracing finds (its `eval` and light
        // samples are zero): outside light tracing its shape is an ordinary (black) surface.
        let emission = shape.emission.filter(|_| !shape.emission_directional || light_tracing);
        if emission.is_some() {
            lights.begin_emitter();
        }
        let flags_base = if shape.flip_normals { PRIM_FLAG_FLIP } else { 0 };
        let mut push = |mut prim: Primitive, attr: TriangleAttributes, area: f32, light_kind: u32| {
            prim.light = NONE;
            if let Some(radiance) = emission {
                // A textured emitter's radiance is the texture's (the kernel multiplies by 1); its
                // power, the mean's.
                let light = Light {
                    kind: light_kind,
                    prim: prims.len() as u32,
                    table: NONE,
                    radiance: if shape.emission_texture.is_some() { [1.0; 4] } else { rgba(radiance) },
                    texture: shape.emission_texture.unwrap_or(NONE),
                    flags: if shape.emission_directional { LIGHT_FLAG_DIRECTIONAL_AREA } else { 0 },
                    ..Default::default()
                };
                // Power: π·A·L, or A·L along the normal alone.
                let lobe = if shape.emission_directional { 1.0 } else { PI };
                prim.light = lights.push(light, lobe * area * luminance(Vec3::from(radiance)));
            }
            prims.push(prim);
            attributes.push(attr);
        };
        match &shape.geometry {
            Geometry::Triangles { triangles, normals, uvs, attributes: corner_attributes } => {
                for (i, t) in triangles.iter().enumerate() {
                    // In f64: squaring an f32 cross product overflows for edges over about 1e9.5.
                    let area = crate::scene::mesh::triangle_area(*t) as f32;
                    let mut flags = flags_base;
                    let uv = uvs.as_ref().map_or(DEFAULT_UVS, |u| u[i]);
                    let mut attr = TriangleAttributes {
                        uv0: uv[0].to_array(),
                        uv1: uv[1].to_array(),
                        uv2: uv[2].to_array(),
                        mesh_attributes: blocks.push_triangle(corner_attributes, i),
                        ..Default::default()
                    };
                    if let Some(c) = normals {
                        let gn = crate::scene::mesh::face_normal(*t).unwrap_or(Vec3::Z);
                        // Flat triangles skip interpolation: a scene pays nothing for normals it does not need.
                        if c[i].iter().any(|n| n.dot(gn) < 1.0 - 1e-6) {
                            flags |= PRIM_FLAG_SMOOTH;
                            (attr.n0, attr.n1, attr.n2) = (arr(c[i][0]), arr(c[i][1]), arr(c[i][2]));
                        }
                    }
                    let prim = Primitive {
                        p0: arr(t[0]),
                        kind: PRIM_TRIANGLE,
                        p1: arr(t[1]),
                        material: shape.material,
                        p2: arr(t[2]),
                        light: NONE,
                        flags,
                        offset_floor: 0.0,
                        _pad: [0; 2],
                    };
                    push(prim, attr, area, LIGHT_AREA);
                }
            }
            Geometry::Sphere { center, radius, frame } => {
                let (tilt, p2) = sphere_orientation(frame);
                let prim = Primitive {
                    p0: arr(*center),
                    kind: PRIM_SPHERE,
                    p1: [*radius, tilt[0], tilt[1]],
                    material: shape.material,
                    p2,
                    light: NONE,
                    flags: flags_base,
                    offset_floor: 0.0,
                    _pad: [0; 2],
                };
                push(prim, TriangleAttributes::default(), 4.0 * PI * radius * radius, LIGHT_SPHERE);
            }
            Geometry::Disk { center, u, v } => {
                let prim = Primitive {
                    p0: arr(*center),
                    kind: PRIM_DISK,
                    p1: arr(*u),
                    material: shape.material,
                    p2: arr(*v),
                    light: NONE,
                    flags: flags_base,
                    offset_floor: 0.0,
                    _pad: [0; 2],
                };
                push(prim, TriangleAttributes::default(), PI * u.cross(*v).length(), LIGHT_AREA);
            }
        }
    }
    (prims, attributes)
}

/// The record's words for a sphere's frame (`caustic_kernel::shape::sphere::Orientation`): a
/// mirrored frame is stored as the rotation of its x-negated self, the quaternion with w ≥ 0 (its
/// `w − 1` is then small near the identity).
fn sphere_orientation(frame: &Mat3) -> ([f32; 2], [f32; 3]) {
    let mirrored = frame.determinant() < 0.0;
    let rotation = if mirrored { *frame * Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0)) } else { *frame };
    let mut q = glam::Quat::from_mat3(&rotation).normalize();
    if q.w < 0.0 {
        q = -q;
    }
    caustic_kernel::shape::sphere::Orientation::words(q.x, q.y, q.z, q.w, mirrored)
}

fn bounds(p: &Primitive) -> Aabb {
    if p.kind == PRIM_INSTANCE {
        Aabb::new(Vec3A::from(p.p0), Vec3A::from(p.p2))
    } else if p.kind == PRIM_SPHERE {
        let c = Vec3A::from(p.p0);
        let r = Vec3A::splat(p.p1[0]);
        Aabb::new(c - r, c + r)
    } else if p.kind == PRIM_DISK {
        // The ellipse c + a·u + b·v reaches ±sqrt(u_i² + v_i²) along each axis.
        let (c, u, v) = (Vec3A::from(p.p0), Vec3A::from(p.p1), Vec3A::from(p.p2));
        let r = (u * u + v * v).sqrt();
        Aabb::new(c - r, c + r)
    } else {
        let (a, b, c) = (Vec3A::from(p.p0), Vec3A::from(p.p1), Vec3A::from(p.p2));
        Aabb::new(a.min(b).min(c), a.max(b).max(c))
    }
}

/// obvhs's medium preset with more reinsertion work and a collapse cost that keeps leaves small.
/// Measured on the H100 (2026-11-22) against the plain preset: cbox 175 → 239 Msamples/s, material
/// previews +20% (glass 59 → 72, diffuse 113 → 136), the PLY bunny 131 → 165; the build of a
/// 62k-triangle mesh takes ~0.1 s. One H100 call on 2026-11-27 (each setting interleaved) moved the
/// collapse cost from 1 to 0.5 and the reinsertion ratio from 0.2 to 0.6: glass +6.0%, the diamond
/// +5.8%, cbox +4.1%, copper +4.1%, diffuse +2.5%, the bunny +1.6%; the build takes about twice as
/// long, so scenes past `MORE_REINSERTION_UP_TO` primitives keep 0.2. obvhs builds on rayon's threads
/// (its `parallel` feature, same tree): on the H100 machine's 16 cores a 10M-triangle scene's
/// buffers and BVH took 41.4 s single-threaded and 7.6 s so (BENCHMARKS.md, "Large scenes").
fn bvh_build_params(primitives: usize) -> obvhs::BvhBuildParams {
    obvhs::BvhBuildParams {
        reinsertion_batch_ratio: if primitives <= MORE_REINSERTION_UP_TO { 0.6 } else { 0.2 },
        collapse_traversal_cost: 0.5,
        ..obvhs::BvhBuildParams::medium_build()
    }
}

/// The largest scene (in primitives) whose BVH gets the costlier reinsertion: about 1 s of build on
/// the H100 machine's 16 cores, where the 10M-triangle scene's 7.6 s would double.
const MORE_REINSERTION_UP_TO: usize = 1 << 20;

/// Builds the BVH and reorders primitives (and what refers to them) into leaf order.
pub(crate) fn build_bvh(
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    origins: &mut Vec<[u32; 2]>,
    lights: &mut [Light],
) -> Result<Vec<BvhNode>> {
    build_bvh_reordering(prims, attributes, origins, lights).map(|(nodes, _)| nodes)
}

/// `build_bvh`, also returning each primitive's new index (by its index before).
fn build_bvh_reordering(
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    origins: &mut Vec<[u32; 2]>,
    lights: &mut [Light],
) -> Result<(Vec<BvhNode>, Vec<u32>)> {
    let aabbs: Vec<Aabb> = prims.iter().map(bounds).collect();
    let mut build_time = std::time::Duration::ZERO;
    let bvh = obvhs::bvh2::builder::build_bvh2(&aabbs, bvh_build_params(aabbs.len()), &mut build_time);
    let (nodes, order) = if bvh.nodes.is_empty() || bvh.depth(0) < STACK_SIZE {
        let nodes = bvh.nodes.iter().map(|n| node_of(&n.aabb, n.prim_count, n.first_index)).collect();
        (nodes, bvh.primitive_indices.clone())
    } else {
        within_depth(&bvh, STACK_SIZE - 1)
    };
    let order = &order;
    let mut new_index = vec![0u32; prims.len()];
    for (new, &old) in order.iter().enumerate() {
        new_index[old as usize] = new as u32;
    }
    *prims = order.iter().map(|&i| prims[i as usize]).collect();
    *attributes = order.iter().map(|&i| attributes[i as usize]).collect();
    if !origins.is_empty() {
        *origins = order.iter().map(|&i| origins[i as usize]).collect();
    }
    for l in lights.iter_mut().filter(|l| matches!(l.kind, LIGHT_AREA | LIGHT_SPHERE)) {
        l.prim = new_index[l.prim as usize];
    }
    inside_buffers(&nodes, prims.len())?;
    Ok((nodes, new_index))
}

/// Checks that every child index and leaf range of `nodes` lies inside the node and primitive
/// buffers: the kernel's traversal reads them without bounds checks (`Accel::trace`).
fn inside_buffers(nodes: &[BvhNode], prims: usize) -> Result<()> {
    for (i, n) in nodes.iter().enumerate() {
        let (first, count) = (n.first as usize, n.prim_count as usize);
        let inside = if count > 0 { first + count <= prims } else { first + 1 < nodes.len() };
        anyhow::ensure!(inside, "internal error: BVH node {i} points past the buffers ({first}, {count})");
    }
    Ok(())
}

fn node_of(aabb: &Aabb, prim_count: u32, first: u32) -> BvhNode {
    BvhNode { min: aabb.min.to_array(), prim_count, max: aabb.max.to_array(), first }
}

/// The BVH laid out again, depth first, with every subtree that reaches `levels` deep collapsed
/// into one leaf of all its primitives, and the primitive order that goes with it. Triangles that
/// coincide cannot be told apart by any split: 100 copies of one triangle made obvhs a chain 93
/// levels deep, past the kernel's traversal stack (`STACK_SIZE`); a leaf of them is what such input
/// deserves. Trees within the stack keep obvhs's layout untouched.
fn within_depth(bvh: &obvhs::bvh2::Bvh2, levels: usize) -> (Vec<BvhNode>, Vec<u32>) {
    let mut nodes = vec![BvhNode::default()];
    let mut order = Vec::with_capacity(bvh.primitive_indices.len());
    let mut stack = vec![(0usize, 0usize, 1usize)]; // (node in bvh, node in `nodes`, its level)
    while let Some((old, new, level)) = stack.pop() {
        let n = &bvh.nodes[old];
        if n.is_leaf() || level == levels {
            let first = order.len() as u32;
            let mut subtree = vec![old];
            while let Some(i) = subtree.pop() {
                let m = &bvh.nodes[i];
                if m.is_leaf() {
                    let range = m.first_index as usize..(m.first_index + m.prim_count) as usize;
                    order.extend_from_slice(&bvh.primitive_indices[range]);
                } else {
                    subtree.extend([m.first_index as usize + 1, m.first_index as usize]);
                }
            }
            nodes[new] = node_of(&n.aabb, order.len() as u32 - first, first);
        } else {
            let children = nodes.len();
            nodes.extend([BvhNode::default(); 2]);
            nodes[new] = node_of(&n.aabb, 0, children as u32);
            stack.push((n.first_index as usize + 1, children + 1, level + 1));
            stack.push((n.first_index as usize, children, level + 1));
        }
    }
    (nodes, order)
}

/// The scene's bounding sphere (centre, radius), slightly enlarged as Mitsuba does for emitters at
/// infinity; a unit sphere for an empty scene.
fn bounding_sphere(nodes: &[BvhNode], has_prims: bool) -> (Vec3, f32) {
    if !has_prims {
        return (Vec3::ZERO, 1.0);
    }
    let (lo, hi) = (Vec3::from(nodes[0].min), Vec3::from(nodes[0].max));
    let centre = 0.5 * (lo + hi);
    (centre, (0.5 * (hi - lo).length() * (1.0 + 1e-4)).max(1e-4))
}

/// Normalised inclusive CDF of non-negative weights (uniform when they sum to zero).
pub(crate) fn cdf_of(weights: &[f64]) -> Vec<f32> {
    let total: f64 = weights.iter().sum();
    let n = weights.len() as f64;
    let mut running = 0.0f64;
    let mut cdf: Vec<f32> = weights
        .iter()
        .map(|&w| {
            running += if total > 0.0 { w / total } else { 1.0 / n };
            running as f32
        })
        .collect();
    if let Some(last) = cdf.last_mut() {
        *last = 1.0;
    }
    cdf
}

fn rows_of(m: Mat3) -> [[f32; 4]; 3] {
    [0, 1, 2].map(|r| m.row(r).extend(0.0).to_array())
}

/// A bitmap texture's texels (RGB) where `place_textures` put them in the table buffer.
fn texels<'a>(t: &Texture, tables: &'a [f32]) -> &'a [f32] {
    &tables[t.offset as usize..(t.offset + 3 * t.width * t.height) as usize]
}

/// An envmap's sampling tables (marginal CDF over the `height - 1` cell rows, then one conditional
/// CDF of `width` cells per row; see `light::infinite`) and its power per unit scale and area. With
/// `compensate`, the tables follow the luminance above the texels' mean (`mis_compensation`).
fn envmap_distribution(t: &Texture, texels: &[f32], compensate: bool) -> (Vec<f32>, f32) {
    let (w, h) = (t.width as usize, t.height as usize);
    let luminances: Vec<f64> =
        texels.chunks_exact(3).map(|c| luminance(Vec3::from_slice(c)).max(0.0) as f64).collect();
    let offset = if compensate { compensation_offset(&luminances) } else { 0.0 };
    let lum = |x: usize, y: usize| luminances[y * w + x];
    let sin_theta = |y: usize| (PI as f64 * y as f64 / (h - 1) as f64).sin();
    // Each cell's mean over its four corners, weighted by sin θ (dω = sin θ dθ dφ), less `offset`.
    let cell = |c: usize, r: usize, offset: f64| {
        let c1 = (c + 1) % w;
        let at = |x: usize, y: usize| (lum(x, y) - offset).max(0.0) * sin_theta(y);
        0.25 * (at(c, r) + at(c1, r) + at(c, r + 1) + at(c1, r + 1))
    };
    let mut marginal = Vec::with_capacity(h - 1);
    let mut conditional = Vec::with_capacity((h - 1) * w);
    let mut power = 0.0f64;
    for r in 0..h - 1 {
        let cells: Vec<f64> = (0..w).map(|c| cell(c, r, offset)).collect();
        power += (0..w).map(|c| cell(c, r, 0.0)).sum::<f64>();
        marginal.push(cells.iter().sum::<f64>());
        conditional.extend(cdf_of(&cells));
    }
    // ∫ luminance dω over the sphere, by the cells' mean values: the power light selection uses,
    // compensated or not.
    let cell_solid_angle = (2.0 * PI as f64 / w as f64) * (PI as f64 / (h - 1) as f64);
    let mut table = cdf_of(&marginal);
    table.extend(conditional);
    (table, (power * cell_solid_angle) as f32)
}

/// What MIS compensation subtracts from each texel's luminance: the mean over the texels, or
/// nothing when the map is nearly constant (mean − minimum within 1% of the mean), where it would
/// leave almost no direction to sample. Mitsuba's rule (`src/emitters/envmap.cpp`).
fn compensation_offset(luminances: &[f64]) -> f64 {
    let mean = luminances.iter().sum::<f64>() / luminances.len().max(1) as f64;
    let min = luminances.iter().copied().fold(f64::INFINITY, f64::min);
    if mean - min <= 0.01 * mean {
        0.0
    } else {
        mean
    }
}

/// Light records of the emitters that are not shapes; returns the environment light's index.
fn emitter_lights(
    scene: &Scene,
    textures: &[Texture],
    tables: &mut Vec<f32>,
    lights: &mut LightList,
    (centre, radius): (Vec3, f32),
) -> u32 {
    let mut env_light = NONE;
    let disk_area = PI * radius * radius;
    let bsphere = [centre.x, centre.y, centre.z, radius];
    for e in &scene.emitters {
        let mut light = Light { prim: NONE, table: NONE, position: bsphere, ..Default::default() };
        let power = match e {
            Emitter::Point { position, intensity } => {
                light.kind = LIGHT_POINT;
                light.radiance = rgba(*intensity);
                light.position = position.extend(0.0).to_array();
                4.0 * PI * luminance(Vec3::from(*intensity))
            }
            Emitter::Spot { to_world, intensity, cutoff_angle, beam_width, texture } => {
                let (cutoff, beam) =
                    (cutoff_angle.to_radians(), beam_width.to_radians().min(cutoff_angle.to_radians()));
                light.kind = LIGHT_SPOT;
                light.radiance = rgba(*intensity);
                light.position = to_world.w_axis.truncate().extend(0.0).to_array();
                let inv_transition = if cutoff > beam { 1.0 / (cutoff - beam) } else { 0.0 };
                light.params = [cutoff.cos(), beam.cos(), cutoff, inv_transition];
                light.to_local = rows_of(orthonormal(Mat3::from_mat4(*to_world)).transpose());
                light.texture = texture.unwrap_or(NONE);
                let mean = texture.map_or(1.0, |t| luminance(Vec3::from(scene.textures[t as usize].mean())));
                // Solid angle of the cone out to the middle of the falloff ramp.
                2.0 * PI * (1.0 - (0.5 * (cutoff + beam)).cos()) * luminance(Vec3::from(*intensity)) * mean
            }
            Emitter::Projector { to_world, irradiance, texture, fov_x, aspect } => {
                let tan_x = (0.5 * fov_x.to_radians()).tan();
                let tan_y = tan_x / aspect;
                let image_area = 4.0 * tan_x * tan_y;
                light.kind = LIGHT_PROJECTOR;
                light.radiance = rgba(*irradiance);
                light.texture = texture.unwrap_or(NONE);
                light.position = to_world.w_axis.truncate().extend(0.0).to_array();
                light.params = [tan_x, tan_y, 0.0, image_area];
                light.to_local = rows_of(orthonormal(Mat3::from_mat4(*to_world)).transpose());
                let mean = texture.map_or(1.0, |t| luminance(Vec3::from(scene.textures[t as usize].mean())));
                // Power: π · value · image area (`light::projector`).
                PI * image_area * luminance(Vec3::from(*irradiance)) * mean
            }
            Emitter::Directional { direction, irradiance } => {
                light.kind = LIGHT_DIRECTIONAL;
                light.radiance = rgba(*irradiance);
                light.to_local = rows_of(frame_with_z(direction.normalize()).transpose());
                disk_area * luminance(Vec3::from(*irradiance))
            }
            Emitter::Constant { radiance } => {
                light.kind = LIGHT_CONSTANT;
                light.radiance = rgba(*radiance);
                disk_area * 4.0 * PI * luminance(Vec3::from(*radiance))
            }
            Emitter::Envmap { texture, to_world, scale, mis_compensation } => {
                let t = &textures[*texture as usize];
                let texels = texels(t, tables);
                // Light tracing draws emission from these tables alone, with nothing to cover the
                // directions compensation leaves out: compensation is for NEE beside BSDF sampling.
                let compensate = *mis_compensation
                    && matches!(scene.integrator.kind, IntegratorKind::Path | IntegratorKind::Direct { .. });
                let (table, integral) = envmap_distribution(t, texels, compensate);
                light.kind = LIGHT_ENVMAP;
                light.prim = *texture;
                light.radiance = [*scale; 4];
                light.table = tables.len() as u32;
                light.to_local = rows_of(to_world.inverse());
                tables.extend(table);
                disk_area * scale * integral
            }
        };
        lights.begin_emitter();
        let index = lights.push(light, power);
        if matches!(e, Emitter::Constant { .. } | Emitter::Envmap { .. }) {
            env_light = index;
        }
    }
    env_light
}

/// Gram-Schmidt on the columns: rotations from transforms that may carry scale.
fn orthonormal(m: Mat3) -> Mat3 {
    let z = m.z_axis.normalize();
    let x = (m.x_axis - z * m.x_axis.dot(z)).normalize();
    Mat3::from_cols(x, z.cross(x), z)
}

/// A rotation whose third column is `z`.
fn frame_with_z(z: Vec3) -> Mat3 {
    let (x, y) = z.any_orthonormal_pair();
    Mat3::from_cols(x, y, z)
}

/// The kernel's camera for a sensor.
pub fn camera(scene: &Scene) -> Camera {
    let s = &scene.sensor;
    let tan_half_x = (s.fov_x.to_radians() * 0.5).tan();
    let mut camera = Camera {
        origin: s.to_world.w_axis.truncate().to_array(),
        near_clip: s.near_clip,
        axis_x: s.to_world.x_axis.truncate().to_array(),
        tan_half_x,
        axis_y: s.to_world.y_axis.truncate().to_array(),
        tan_half_y: tan_half_x * s.height as f32 / s.width as f32,
        axis_z: s.to_world.z_axis.truncate().to_array(),
        far_clip: s.far_clip,
        kind: CAMERA_PERSPECTIVE,
        ..Default::default()
    };
    match s.projection {
        Projection::Perspective => camera.principal_offset = s.principal_point_offset,
        Projection::ThinLens { aperture_radius, focus_distance } => {
            camera.kind = CAMERA_THIN_LENS;
            camera.aperture_radius = aperture_radius;
            camera.focus_distance = focus_distance;
        }
        Projection::Orthographic { half_width, half_height } => {
            camera.kind = CAMERA_ORTHOGRAPHIC;
            camera.tan_half_x = half_width;
            camera.tan_half_y = half_height;
        }
        Projection::RadianceMeter => {
            camera.tan_half_x = 0.0;
            camera.tan_half_y = 0.0;
        }
        // Its primitives' table is placed by `build`.
        Projection::IrradianceMeter { .. } => camera.kind = CAMERA_IRRADIANCE_METER,
    }
    camera
}

/// Places each texture's texels in the table buffer.
fn place_textures(
    scene: &Scene,
    tables: &mut Vec<f32>,
    blocks: &crate::prepare::attribute_buffers::AttributeBlocks,
) -> Vec<Texture> {
    scene
        .textures
        .iter()
        .map(|t| {
            let mut record = t.record;
            record.offset = match &t.mesh_attribute {
                Some(a) => blocks.slot_offset(&a.name),
                None => tables.len() as u32,
            };
            tables.extend_from_slice(&t.texels);
            record
        })
        .collect()
}

pub fn build(scene: &Scene) -> Result<SceneBuffers> {
    let mut light_list = LightList::default();
    let light_tracing = scene.integrator.kind == IntegratorKind::Ptracer;
    let mut blocks = crate::prepare::attribute_buffers::AttributeBlocks::of(scene);
    let (mut prims, mut attributes) = primitives(&scene.shapes, light_tracing, &mut light_list, &mut blocks);
    let mut prim_origins = if scene.aovs.is_some() { prim_origins(scene) } else { Vec::new() };
    let has_prims = !prims.is_empty();
    // The irradiance meter's primitives, by their index in scene order (`primitives` pushes them).
    let meter_prims = crate::prepare::irradiance_meter::scene_order_primitives(scene);
    let mut new_index = Vec::new();
    let mut nodes = if has_prims {
        let (nodes, order) =
            build_bvh_reordering(&mut prims, &mut attributes, &mut prim_origins, &mut light_list.lights)?;
        new_index = order;
        nodes
    } else {
        // A leaf holding only the placeholder primitive pushed below (a triangle of zero area that no
        // ray hits). Not an inner node with an inverted box: the slab test swaps min and max, so such a
        // box is [-1, 1]³ to it, and traversal read children that do not exist (CPU panic, GPU garbage).
        vec![BvhNode { min: [0.0; 3], prim_count: 1, max: [0.0; 3], first: 0 }]
    };
    // With instances, that BVH becomes one group under a BVH over the instances
    // (`crate::prepare::instance_buffers`).
    let instanced = crate::prepare::instance_buffers::two_level(
        &mut nodes,
        &mut prims,
        &mut attributes,
        scene,
        &mut blocks,
    )?;
    let has_prims = !prims.is_empty();
    // The ray offset's absolute part (`caustic_kernel::shape::offset_origin`): Mitsuba's 1, or the
    // scene's half-diagonal where smaller, so that a scene scaled down keeps its image.
    let offset_floor = if has_prims {
        (0.5 * (Vec3::from(nodes[0].max) - Vec3::from(nodes[0].min)).length()).min(1.0)
    } else {
        1.0
    };
    for p in &mut prims {
        p.offset_floor = offset_floor;
    }
    let (mut tables, filter_signed) =
        crate::prepare::filter_table::filter_tables(&scene.sensor.filter, FILTER_BINS)?;
    let filter_cdf_offset = 0;
    crate::prepare::instance_buffers::place_transforms(&mut prims, &mut tables, &scene.instancing);
    let mut textures = place_textures(scene, &mut tables, &blocks);
    blocks.place(&mut tables, &mut attributes);
    let env_light =
        emitter_lights(scene, &textures, &mut tables, &mut light_list, bounding_sphere(&nodes, has_prims));

    let uniform_share = match scene.integrator.kind {
        IntegratorKind::Ptracer | IntegratorKind::Ibpt => LIGHT_TRACING_UNIFORM_SHARE,
        IntegratorKind::Path | IntegratorKind::Direct { .. } => 1.0,
    };
    let light_cdf = cdf_of(&light_list.selection_weights(uniform_share));
    let mut lights = light_list.lights;
    for (l, i) in lights.iter_mut().zip(0..) {
        l.pmf = light_cdf[i] - if i == 0 { 0.0 } else { light_cdf[i - 1] };
    }
    let light_cdf_offset = tables.len() as u32;
    tables.extend(light_cdf);
    let mut camera = camera(scene);
    if let Some(meter) = meter_prims {
        camera.meter_table =
            crate::prepare::irradiance_meter::place_table(&meter, &new_index, &prims, &mut tables)?;
    }

    let mut materials = scene.materials.clone();
    for m in &mut materials {
        if let Some(table) = caustic_kernel::bsdf::precompute(m) {
            m.table = tables.len() as u32;
            tables.extend(table);
        } else if matches!(m.kind, BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN) && m.table != NONE {
            // From its index into the scene's list to its place in the table buffer.
            let weights = scene.weight_tables[m.table as usize];
            m.table = tables.len() as u32;
            tables.extend(weights);
        }
    }

    // Dispersive materials: the wavelengths their paths draw (`caustic_kernel::wavelength`).
    let mut wavelength_table = 0;
    if materials.iter().any(caustic_kernel::wavelength::disperses) {
        use crate::load::mitsuba::spectrum::{cie_xyz_table, XYZ_TO_SRGB};
        wavelength_table = tables.len() as u32;
        tables.extend(caustic_kernel::wavelength::build_table(&cie_xyz_table(), XYZ_TO_SRGB));
    }

    let s = &scene.sensor;
    let crop = s.crop.unwrap_or(crate::scene::Crop { x: 0, y: 0, width: s.width, height: s.height });
    let (integrator_kind, emitter_samples, bsdf_samples) = match scene.integrator.kind {
        IntegratorKind::Path => (INTEGRATOR_PATH, 1, 1),
        IntegratorKind::Direct { emitter_samples, bsdf_samples } => {
            (INTEGRATOR_DIRECT, emitter_samples, bsdf_samples)
        }
        IntegratorKind::Ptracer => {
            check_light_tracing(scene, "ptracer")?;
            (INTEGRATOR_PTRACER, 1, 1)
        }
        IntegratorKind::Ibpt => {
            check_light_tracing(scene, "ibpt")?;
            if let Some(s) = scene.shapes.iter().find(|s| s.emission.is_some() && s.emission_directional) {
                bail!(
                    "{}: a directionalarea emitter is rendered by ptracer (which alone sees it in Mitsuba) \
                     and by path and direct (as black), not by ibpt",
                    s.origin
                );
            }
            (INTEGRATOR_IBPT, 1, 1)
        }
    };
    let params = FrameParams {
        width: crop.width,
        height: crop.height,
        max_depth: if scene.integrator.max_depth < 0 { NONE } else { scene.integrator.max_depth as u32 },
        rr_depth: scene.integrator.rr_depth,
        sampler: if s.sampler == SamplerKind::Stratified { SAMPLER_STRATIFIED } else { SAMPLER_INDEPENDENT },
        spp_total: s.spp,
        light_count: lights.len() as u32,
        light_cdf_offset,
        filter_cdf_offset,
        filter_bins: FILTER_BINS,
        filter_radius: s.filter.radius(),
        filter_signed: filter_signed as u32,
        hide_emitters: scene.integrator.hide_emitters as u32,
        env_light,
        crop_x: crop.x,
        crop_y: crop.y,
        full_width: s.width,
        full_height: s.height,
        integrator: integrator_kind,
        emitter_samples,
        bsdf_samples,
        wavelength_table,
        square_scale_log2: square_scale_log2(&lights, &textures, &tables),
        film_reach: film_reach(s, integrator_kind),
        camera,
        ..Default::default()
    };
    let mut features = scene_features(&materials, &lights, !textures.is_empty(), integrator_kind);
    if crate::prepare::attribute_buffers::used(scene) {
        features |= features::MESH_ATTRIBUTES;
    }
    if camera.kind == CAMERA_IRRADIANCE_METER {
        features |= features::IRRADIANCE_METER;
    }
    // Not paths to specialize but how the buffers are laid out and which per-pixel loop runs: set
    // exactly when they are two-level and when the integrator is `direct` (also under
    // `CAUSTIC_SPECIALIZE=0`).
    features &= !(features::INSTANCING | features::DIRECT_INTEGRATOR);
    if instanced {
        features |= features::INSTANCING;
    }
    if integrator_kind == INTEGRATOR_DIRECT {
        features |= features::DIRECT_INTEGRATOR;
    }
    if materials.is_empty() {
        materials.push(Material::default());
    }
    if prims.is_empty() {
        prims.push(Primitive { light: NONE, ..Primitive::default() });
        attributes.push(TriangleAttributes::default());
        prim_origins.push([0, 0]);
    }
    if lights.is_empty() {
        lights.push(Light::default());
    }
    if textures.is_empty() {
        textures.push(Texture::default());
    }
    let aovs = scene.aovs.clone();
    let placed_prims = crate::prepare::instance_buffers::placed_primitives(&scene.instancing);
    Ok(SceneBuffers {
        nodes,
        prims,
        attributes,
        materials,
        lights,
        textures,
        tables,
        params,
        features,
        aovs,
        prim_origins,
        placed_prims,
    })
}

/// Per primitive in scene order (as `primitives` pushes them): Mitsuba's shape index and the
/// primitive's index within its shape (a triangle's in its mesh; 0 for analytic shapes).
fn prim_origins(scene: &Scene) -> Vec<[u32; 2]> {
    let is_mesh: Vec<bool> =
        scene.shapes.iter().map(|s| matches!(s.geometry, Geometry::Triangles { .. })).collect();
    let shape_index = shape_indices(&is_mesh);
    let mut origins = Vec::new();
    for (shape, &index) in scene.shapes.iter().zip(&shape_index) {
        let count = match &shape.geometry {
            Geometry::Triangles { triangles, .. } => triangles.len() as u32,
            Geometry::Sphere { .. } | Geometry::Disk { .. } => 1,
        };
        origins.extend((0..count).map(|i| [index, i]));
    }
    origins
}

/// Mitsuba's numbering of the shapes (`shape_index`, from 1), measured on Mitsuba 3.9.1: its parser
/// merges the meshes into one list after the other shapes, so the analytic shapes (sphere, disk)
/// come first in file order, then the meshes (every triangle shape: rectangle, cube, OBJ, PLY, …)
/// in reverse file order (the order of Mitsuba's hash table of meshes, seen with four to twelve
/// shapes). Meshes that share a BSDF and emitter Mitsuba merges into one shape; caustic does not.
pub fn shape_indices(is_mesh: &[bool]) -> Vec<u32> {
    let mut index = vec![0u32; is_mesh.len()];
    let mut next = 1;
    for (i, _) in is_mesh.iter().enumerate().filter(|(_, m)| !**m) {
        index[i] = next;
        next += 1;
    }
    for (i, _) in is_mesh.iter().enumerate().rev().filter(|(_, m)| **m) {
        index[i] = next;
        next += 1;
    }
    index
}

/// `FrameParams::square_scale_log2`: the power of two that brings the scene's brightest emission
/// (radiance, intensity or irradiance; an envmap's scale times its largest texel) to about 1, so
/// that samples up to ~1e19 times it square within f32's range (and samples down to 1e-19 of it
/// do not underflow). Radiance 1e30 squared in f32 was +Inf; 0 where nothing emits.
fn square_scale_log2(lights: &[Light], textures: &[Texture], tables: &[f32]) -> i32 {
    let brightest = lights
        .iter()
        .map(|l| {
            let mut m = l.radiance[..3].iter().fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            let texture = if l.kind == LIGHT_ENVMAP { l.prim } else { l.texture };
            if texture != NONE && textures[texture as usize].kind == TEXTURE_CHECKERBOARD {
                let t = &textures[texture as usize];
                m *= t.color0[..3].iter().chain(&t.color1[..3]).fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            } else if texture != NONE {
                m *= texels(&textures[texture as usize], tables)
                    .iter()
                    .fold(0.0f64, |m, &c| m.max(c.abs() as f64));
            }
            m
        })
        .filter(|m| m.is_finite() && *m > 0.0)
        .fold(0.0f64, f64::max);
    if brightest > 0.0 {
        (-brightest.log2().round()).clamp(-100.0, 100.0) as i32
    } else {
        0
    }
}

/// The kernel paths a scene can reach: its BSDF models, emitter kinds, textures and integrator.
/// `CAUSTIC_SPECIALIZE=0` keeps every path (for A/B timings of the specialization itself).
fn scene_features(materials: &[Material], lights: &[Light], textures: bool, integrator: u32) -> u32 {
    if std::env::var("CAUSTIC_SPECIALIZE").is_ok_and(|v| v == "0") {
        return features::ALL;
    }
    // Lambert is also the fallback of the dispatch, so its path is always there.
    let mut f = features::bsdf(BSDF_DIFFUSE);
    for m in materials {
        f |= features::material(m.kind);
    }
    for l in lights {
        f |= features::light(l.kind);
        if l.texture != NONE {
            f |= features::TEXTURED_EMISSION;
        }
    }
    if textures {
        f |= features::TEXTURES;
    }
    if caustic_kernel::integrator::splats(integrator) {
        f |= features::LIGHT_TRACER;
    }
    if materials.iter().any(caustic_kernel::wavelength::disperses) {
        f |= features::DISPERSION;
    }
    if materials.iter().any(|m| m.flags & MATERIAL_MASK != 0) {
        f |= features::MASK;
    }
    if materials.iter().any(|m| m.perturb != 0) {
        f |= features::NORMAL_MAPPING;
    }
    f
}

/// How far the splatting film spreads a camera sample (`FrameParams::film_reach`), or 0 for filter
/// importance sampling: asked for (`--film fis`), where light tracing's MIS weighs camera samples by
/// the filter's density (ptracer, ibpt), for the irradiance and radiance meters (one value, no
/// neighbours), where splatting is the same (a box of radius ½), and for a filter wider than
/// `film_splat::MAX_REACH` pixels, with a warning.
fn film_reach(sensor: &crate::scene::Sensor, integrator: u32) -> u32 {
    use caustic_kernel::film_splat::{reach_for_radius, MAX_REACH};
    let meter = matches!(sensor.projection, Projection::RadianceMeter | Projection::IrradianceMeter { .. });
    if sensor.film != crate::scene::FilmMode::Splat
        || meter
        || integrator == INTEGRATOR_PTRACER
        || integrator == INTEGRATOR_IBPT
    {
        return 0;
    }
    let reach = reach_for_radius(sensor.filter.radius());
    if reach > MAX_REACH {
        eprintln!(
            "warning: the reconstruction filter's radius {} reaches {reach} pixels, past the splatting \
             film's {MAX_REACH}: its samples are drawn from the filter instead (as --film fis)",
            sensor.filter.radius()
        );
        return 0;
    }
    reach
}

/// What light tracing does not cover yet is refused, never rendered without it: the orthographic
/// camera (light tracing connects to the pinhole and to points of a thin lens's aperture) and the
/// radiance meter (a single ray, which no light path can reach by a connection).
fn check_light_tracing(scene: &Scene, name: &str) -> Result<()> {
    let integrator = name;
    if matches!(scene.sensor.projection, Projection::RadianceMeter) {
        bail!("{integrator}: the radiancemeter sensor measures a single ray, which light tracing cannot connect to (render this scene with path)");
    }
    if matches!(scene.sensor.projection, Projection::IrradianceMeter { .. }) {
        bail!("{integrator}: the irradiancemeter sensor is not supported by light tracing yet (render this scene with path)");
    }
    if !camera(scene).connectable() {
        bail!(
            "{integrator}: the orthographic sensor is not supported, only perspective and thinlens (render \
             this scene with path)"
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaf(first: u32, count: u32) -> BvhNode {
        BvhNode { prim_count: count, first, ..Default::default() }
    }

    #[test]
    fn trees_that_point_past_their_buffers_are_refused() {
        // A root over two leaves of two primitives each.
        let good = [leaf(1, 0), leaf(0, 2), leaf(2, 2)];
        assert!(inside_buffers(&good, 4).is_ok());
        assert!(inside_buffers(&good, 3).is_err(), "a leaf past the primitives");
        let far_child = [leaf(2, 0), leaf(0, 2), leaf(2, 2)];
        assert!(inside_buffers(&far_child, 4).is_err(), "a child past the nodes");
        assert!(inside_buffers(&[], 0).is_ok());
    }

    #[test]
    fn built_trees_lie_inside_their_buffers() {
        // Coincident triangles, whose tree `within_depth` lays out again, and a row of distinct ones.
        for coincident in [true, false] {
            let mut prims: Vec<Primitive> = (0..300)
                .map(|i| {
                    let x = if coincident { 0.0 } else { i as f32 };
                    Primitive {
                        p0: [x, 0.0, 0.0],
                        p1: [x + 1.0, 0.0, 0.0],
                        p2: [x, 1.0, 0.0],
                        ..Default::default()
                    }
                })
                .collect();
            let mut attributes = vec![TriangleAttributes::default(); prims.len()];
            let nodes = build_bvh(&mut prims, &mut attributes, &mut Vec::new(), &mut []).unwrap();
            assert!(inside_buffers(&nodes, prims.len()).is_ok());
        }
    }
}
