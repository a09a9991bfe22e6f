//! Scene description → the kernel's buffers (`SceneBuffers`), assembled by `build` from the stages
//! beside it: primitives and their attributes (`primitives`, `attribute_buffers`), the BVH in whose
//! leaf order they are stored (`bvh`, two-level with instances: `instance_buffers`), materials and
//! textures (`materials`), lights with power-proportional selection (`lights`), the camera and
//! film (`camera`, `filter_table`, `irradiance_meter`), the kernel paths the scene reaches
//! (`features`), and the table buffer all of them append to (sampling distributions, texels,
//! precomputed BSDF tables).
use super::bvh::{bounding_sphere, build_bvh_reordering};
use super::camera::{camera, film_reach};
use super::features::features_of;
use super::lights::{cdf_of, emitter_lights, square_scale_log2, LightList, LIGHT_TRACING_UNIFORM_SHARE};
use super::materials::{place_materials, place_textures, place_wavelengths};
use super::primitives::{prim_origins, primitives};
use crate::scene::{Emitter, IntegratorKind, Projection, SamplerKind, Scene};
use anyhow::{bail, Result};
use caustic_kernel::layout::*;
use glam::Vec3;

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
    /// `vcm`: how the merging radius shrinks from pass to pass (`merge_radius`), 0 otherwise.
    pub merge_alpha: f32,
}

/// `vcm`'s radius in iteration `i` (the pass's sample index): the first pass's, `first`, times
/// `(i + 1)^((α − 1)/2)`, so that its square shrinks as Knaus and Zwicker's progressive photon
/// mapping shrinks it on average and the estimate converges. 0 where `first` is (the other integrators).
pub fn merge_radius(first: f32, alpha: f32, iteration: u32) -> f32 {
    first * ((iteration + 1) as f32).powf(0.5 * (alpha - 1.0))
}

impl SceneBuffers {
    /// `vcm`'s radius in iteration `iteration` (`merge_radius`).
    pub fn merge_radius(&self, iteration: u32) -> f32 {
        merge_radius(self.params.merge_radius, self.merge_alpha, iteration)
    }
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

/// The kernel that renders `scene`'s integrator: its own, except that `ibpt`, `bdpt` and `vcm` in a
/// scene where no light path can start (every emitter at infinity, where their light paths do not
/// start, or none) are `path`'s estimator, every strategy beyond the camera path's two contributing
/// nothing, so `path`'s kernel renders them (unless `Integrator::own_kernel`). `path`'s kernel does the
/// same work without the light pass, the light vertex cache and the MIS state (on the H200 a `bdpt`
/// sample cost 2.1-2.9 `path` samples on such scenes: BENCHMARKS.md, "BDPT against path on the shared
/// scenes"). The scene is checked as the integrator asked for would check it, so a scene it refuses
/// stays refused whatever its emitters.
pub fn kernel_kind(scene: &Scene) -> Result<IntegratorKind> {
    let kind = scene.integrator.kind;
    let name = match kind {
        IntegratorKind::Ibpt => "ibpt",
        IntegratorKind::Bdpt => "bdpt",
        IntegratorKind::Vcm => "vcm",
        _ => return Ok(kind),
    };
    check_bidirectional(scene, name)?;
    let finite_emitter = scene.shapes.iter().any(|s| s.emission.is_some())
        || scene.emitters.iter().any(|e| match e {
            Emitter::Point { .. } | Emitter::Spot { .. } | Emitter::Projector { .. } => true,
            Emitter::Directional { .. } | Emitter::Constant { .. } | Emitter::Envmap { .. } => false,
        });
    if finite_emitter || scene.integrator.own_kernel {
        return Ok(kind);
    }
    eprintln!(
        "note: {name}: no light path can start in this scene (its emitters are all at infinity), so \
         {name} is path tracing here and path's kernel renders it (--own-kernel runs {name}'s)"
    );
    Ok(IntegratorKind::Path)
}

pub fn build(scene: &Scene) -> Result<SceneBuffers> {
    let kind = kernel_kind(scene)?;
    let mut light_list = LightList::default();
    let light_tracing = kind == IntegratorKind::Ptracer;
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
    if instanced {
        // The groups' leaves too are read without bounds checks (`bvh::intersect_leaf`).
        super::bvh::inside_buffers(&nodes, prims.len())?;
    }
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
    let scene_sphere = bounding_sphere(&nodes, has_prims);
    let env_light = emitter_lights(scene, kind, &textures, &mut tables, &mut light_list, scene_sphere);

    let uniform_share = match kind {
        IntegratorKind::Ptracer | IntegratorKind::Ibpt | IntegratorKind::Bdpt | IntegratorKind::Vcm => {
            LIGHT_TRACING_UNIFORM_SHARE
        }
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

    let mut materials = place_materials(scene, &mut tables);
    let wavelength_table = place_wavelengths(&materials, &mut tables);

    let s = &scene.sensor;
    let crop = s.crop.unwrap_or(crate::scene::Crop { x: 0, y: 0, width: s.width, height: s.height });
    let (integrator_kind, emitter_samples, bsdf_samples) = match kind {
        IntegratorKind::Path => (INTEGRATOR_PATH, 1, 1),
        IntegratorKind::Direct { emitter_samples, bsdf_samples } => {
            (INTEGRATOR_DIRECT, emitter_samples, bsdf_samples)
        }
        IntegratorKind::Ptracer => {
            check_light_tracing(scene, "ptracer")?;
            (INTEGRATOR_PTRACER, 1, 1)
        }
        // `kernel_kind` checked the scene.
        IntegratorKind::Ibpt => (INTEGRATOR_IBPT, 1, 1),
        IntegratorKind::Bdpt => (INTEGRATOR_BDPT, 1, 1),
        IntegratorKind::Vcm => (INTEGRATOR_VCM, 1, 1),
    };
    let merge_radius = match kind {
        IntegratorKind::Vcm => {
            let m = scene.integrator.merging;
            m.radius.unwrap_or(m.radius_factor * scene_sphere.1)
        }
        _ => 0.0,
    };
    let bidirectional = matches!(kind, IntegratorKind::Bdpt | IntegratorKind::Vcm);
    let connection_share = if bidirectional {
        share_or_override(scene.integrator.connection_share, "CAUSTIC_CONNECTION_SHARE", true)?
    } else {
        0.0
    };
    let light_tracing_share = match kind {
        IntegratorKind::Ibpt | IntegratorKind::Bdpt | IntegratorKind::Vcm => {
            share_or_override(scene.integrator.light_tracing_share, "CAUSTIC_LIGHT_TRACING_SHARE", false)?
        }
        _ => 1.0,
    };
    let connection_rate = if bidirectional {
        share_or_override(scene.integrator.connection_rate, "CAUSTIC_CONNECTION_RATE", false)?
    } else {
        1.0
    };
    let mut params = FrameParams {
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
        merge_radius,
        connection_share,
        light_tracing_share,
        connection_rate,
        camera,
        ..Default::default()
    };
    (params.filter_abs_mass, params.filter_mass) = caustic_kernel::film::whole_masses(&tables, &params);
    let features = features_of(scene, &materials, &lights, !textures.is_empty(), &params, instanced);
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
        merge_alpha: if kind == IntegratorKind::Vcm { scene.integrator.merging.alpha } else { 0.0 },
    })
}

/// What light tracing does not cover yet is refused, never rendered without it: the orthographic
/// camera (light tracing connects to the pinhole and to points of a thin lens's aperture) and the
/// radiance meter (a single ray, which no light path can reach by a connection).
/// What IBPT and BDPT refuse besides what light tracing does: `directionalarea` emitters, which
/// only light paths reach (their weights would count strategies that cannot happen).
/// The scene's share (`connection_share`, `light_tracing_share`, `connection_rate`), or environment
/// variable `var`'s where it is set (for measuring one scene at several shares): a number up to 1,
/// above 0 (or 0 where `zero` allows it).
fn share_or_override(scene: f32, var: &str, zero: bool) -> Result<f32> {
    let Ok(text) = std::env::var(var) else {
        return Ok(scene);
    };
    match text.trim().parse::<f32>() {
        Ok(c) if c <= 1.0 && (c > 0.0 || (zero && c == 0.0)) => Ok(c),
        _ if zero => bail!("{var}: expected a number from 0 to 1, got {text:?}"),
        _ => bail!("{var}: expected a number above 0 and at most 1, got {text:?}"),
    }
}

fn check_bidirectional(scene: &Scene, name: &str) -> Result<()> {
    check_light_tracing(scene, name)?;
    if let Some(s) = scene.shapes.iter().find(|s| s.emission.is_some() && s.emission_directional) {
        bail!(
            "{}: a directionalarea emitter is rendered by ptracer (which alone sees it in Mitsuba) \
             and by path and direct (as black), not by {name}",
            s.origin
        );
    }
    Ok(())
}

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
