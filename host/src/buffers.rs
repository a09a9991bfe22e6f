//! Scene description → the kernel's buffers: primitives in BVH order, BVH2 nodes (built by `obvhs`),
//! shading normals, materials, lights with power-proportional selection, and the sampling tables.
use crate::scene::{Filter, Geometry, SamplerKind, Scene};
use anyhow::{bail, Result};
use caustic_kernel::bvh::STACK_SIZE;
use caustic_kernel::camera::Camera;
use caustic_kernel::scene::*;
use caustic_kernel::spectrum::luminance;
use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;

/// Bins of the tabulated reconstruction filter.
pub const FILTER_BINS: u32 = 64;

/// Everything the kernel reads, ready to upload (GPU) or borrow (CPU). Every list has at least one
/// element because GPU buffers cannot be empty; unused placeholders are never read.
#[derive(Clone, Debug)]
pub struct SceneBuffers {
    pub nodes: Vec<BvhNode>,
    pub prims: Vec<Primitive>,
    pub normals: Vec<ShadingNormals>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub tables: Vec<f32>,
    /// `FrameParams` with everything but the per-dispatch fields filled in.
    pub params: FrameParams,
}

impl SceneBuffers {
    pub fn view(&self) -> caustic_kernel::integrator::SceneView<'_> {
        caustic_kernel::integrator::SceneView {
            nodes: &self.nodes,
            prims: &self.prims,
            normals: &self.normals,
            materials: &self.materials,
            lights: &self.lights,
            tables: &self.tables,
        }
    }
}

fn arr(v: Vec3) -> [f32; 3] {
    v.to_array()
}

/// Primitive records and their shading normals, in scene order.
fn primitives(scene: &Scene) -> (Vec<Primitive>, Vec<ShadingNormals>, Vec<Light>, Vec<f32>) {
    let mut prims = Vec::new();
    let mut normals = Vec::new();
    let mut lights = Vec::new();
    let mut powers = Vec::new();
    for shape in &scene.shapes {
        let flags_base = if shape.flip_normals { PRIM_FLAG_FLIP } else { 0 };
        let mut push = |prim: Primitive, n: ShadingNormals, area: f32, light_kind: u32| {
            let mut prim = prim;
            prim.light = NONE;
            if let Some(radiance) = shape.emission {
                prim.light = lights.len() as u32;
                lights.push(Light { kind: light_kind, prim: prims.len() as u32, pmf: 0.0, _pad: 0, radiance: [radiance[0], radiance[1], radiance[2], 0.0] });
                powers.push(luminance(Vec3::from(radiance)) * area);
            }
            prims.push(prim);
            normals.push(n);
        };
        match &shape.geometry {
            Geometry::Triangles { triangles, normals: corner } => {
                for (i, t) in triangles.iter().enumerate() {
                    let geometric = (t[1] - t[0]).cross(t[2] - t[0]);
                    let area = 0.5 * geometric.length();
                    let mut flags = flags_base;
                    let mut sn = ShadingNormals::default();
                    if let Some(c) = corner {
                        let gn = geometric.normalize();
                        // Flat triangles skip interpolation: a scene pays nothing for normals it does not need.
                        if c[i].iter().any(|n| n.dot(gn) < 1.0 - 1e-6) {
                            flags |= PRIM_FLAG_SMOOTH;
                            sn = ShadingNormals { n0: arr(c[i][0]), n1: arr(c[i][1]), n2: arr(c[i][2]), ..Default::default() };
                        }
                    }
                    let prim = Primitive { p0: arr(t[0]), kind: PRIM_TRIANGLE, p1: arr(t[1]), material: shape.material, p2: arr(t[2]), light: NONE, flags, _pad: [0; 3] };
                    push(prim, sn, area, LIGHT_TRIANGLE);
                }
            }
            Geometry::Sphere { center, radius } => {
                let prim = Primitive { p0: arr(*center), kind: PRIM_SPHERE, p1: [*radius, 0.0, 0.0], material: shape.material, p2: [0.0; 3], light: NONE, flags: flags_base, _pad: [0; 3] };
                push(prim, ShadingNormals::default(), 4.0 * std::f32::consts::PI * radius * radius, LIGHT_SPHERE);
            }
        }
    }
    (prims, normals, lights, powers)
}

fn bounds(p: &Primitive) -> Aabb {
    if p.kind == PRIM_SPHERE {
        let c = Vec3A::from(p.p0);
        let r = Vec3A::splat(p.p1[0]);
        Aabb::new(c - r, c + r)
    } else {
        let (a, b, c) = (Vec3A::from(p.p0), Vec3A::from(p.p1), Vec3A::from(p.p2));
        Aabb::new(a.min(b).min(c), a.max(b).max(c))
    }
}

/// Builds the BVH and reorders primitives (and what refers to them) into leaf order.
fn build_bvh(prims: &mut Vec<Primitive>, normals: &mut Vec<ShadingNormals>, lights: &mut [Light]) -> Result<Vec<BvhNode>> {
    let aabbs: Vec<Aabb> = prims.iter().map(bounds).collect();
    let mut build_time = std::time::Duration::ZERO;
    let bvh = obvhs::bvh2::builder::build_bvh2(&aabbs, obvhs::BvhBuildParams::medium_build(), &mut build_time);
    let order = &bvh.primitive_indices;
    let mut new_index = vec![0u32; prims.len()];
    for (new, &old) in order.iter().enumerate() {
        new_index[old as usize] = new as u32;
    }
    *prims = order.iter().map(|&i| prims[i as usize]).collect();
    *normals = order.iter().map(|&i| normals[i as usize]).collect();
    for l in lights.iter_mut() {
        l.prim = new_index[l.prim as usize];
    }
    let nodes: Vec<BvhNode> = bvh
        .nodes
        .iter()
        .map(|n| BvhNode { min: n.aabb.min.to_array(), prim_count: n.prim_count, max: n.aabb.max.to_array(), first: n.first_index })
        .collect();
    let depth = bvh.depth(0);
    if depth >= STACK_SIZE {
        bail!("the BVH is {depth} levels deep; the kernel's traversal stack holds {STACK_SIZE}");
    }
    Ok(nodes)
}

/// Inclusive CDF of a filter's 1D weight over [-radius, radius].
fn filter_cdf(filter: &Filter) -> Vec<f32> {
    const SUB: usize = 32;
    let r = filter.radius();
    let width = 2.0 * r / FILTER_BINS as f32;
    let mut cdf = Vec::with_capacity(FILTER_BINS as usize);
    let mut total = 0.0f64;
    for b in 0..FILTER_BINS {
        let mut mass = 0.0f64;
        for s in 0..SUB {
            let x = -r + (b as f32 + (s as f32 + 0.5) / SUB as f32) * width;
            mass += filter.weight(x) as f64;
        }
        total += mass;
        cdf.push(total);
    }
    cdf.iter().map(|&c| (c / total) as f32).collect()
}

/// The kernel's camera for a sensor.
pub fn camera(scene: &Scene) -> Camera {
    let s = &scene.sensor;
    let tan_half_x = (s.fov_x.to_radians() * 0.5).tan();
    Camera {
        origin: s.to_world.w_axis.truncate().to_array(),
        near_clip: s.near_clip,
        axis_x: s.to_world.x_axis.truncate().to_array(),
        tan_half_x,
        axis_y: s.to_world.y_axis.truncate().to_array(),
        tan_half_y: tan_half_x * s.height as f32 / s.width as f32,
        axis_z: s.to_world.z_axis.truncate().to_array(),
        far_clip: s.far_clip,
    }
}

pub fn build(scene: &Scene) -> Result<SceneBuffers> {
    let (mut prims, mut normals, mut lights, powers) = primitives(scene);
    let nodes = if prims.is_empty() {
        // An empty box (min > max) that no ray enters.
        vec![BvhNode { min: [1.0; 3], prim_count: 0, max: [-1.0; 3], first: 0 }]
    } else {
        build_bvh(&mut prims, &mut normals, &mut lights)?
    };
    let total_power: f32 = powers.iter().sum();
    let mut tables = Vec::new();
    let mut running = 0.0f32;
    for (l, p) in lights.iter_mut().zip(&powers) {
        l.pmf = if total_power > 0.0 { p / total_power } else { 1.0 / powers.len() as f32 };
        running += l.pmf;
        tables.push(running);
    }
    if let Some(last) = tables.last_mut() {
        *last = 1.0;
    }
    let light_cdf_offset = 0;
    let filter_cdf_offset = tables.len() as u32;
    tables.extend(filter_cdf(&scene.sensor.filter));

    let s = &scene.sensor;
    let params = FrameParams {
        width: s.width,
        height: s.height,
        max_depth: if scene.integrator.max_depth < 0 { NONE } else { scene.integrator.max_depth as u32 },
        rr_depth: scene.integrator.rr_depth,
        sampler: if s.sampler == SamplerKind::Stratified { SAMPLER_STRATIFIED } else { SAMPLER_INDEPENDENT },
        spp_total: s.spp,
        light_count: lights.len() as u32,
        light_cdf_offset,
        filter_cdf_offset,
        filter_bins: FILTER_BINS,
        filter_radius: s.filter.radius(),
        hide_emitters: scene.integrator.hide_emitters as u32,
        camera: camera(scene),
        ..Default::default()
    };
    let mut materials = scene.materials.clone();
    if materials.is_empty() {
        materials.push(Material::default());
    }
    if prims.is_empty() {
        prims.push(Primitive::default());
        normals.push(ShadingNormals::default());
    }
    if lights.is_empty() {
        lights.push(Light::default());
    }
    Ok(SceneBuffers { nodes, prims, normals, materials, lights, tables, params })
}
