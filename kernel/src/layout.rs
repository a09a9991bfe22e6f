//! The one definition of every buffer the host and the kernel share (kajiya's `rust-shaders-shared`):
//! `#[repr(C)]` structs of 32-bit scalars with explicit padding, uploaded as storage buffers by the GPU
//! backend and borrowed as slices by the CPU runner. (The host's `scene` module is something else: the
//! renderer-neutral description the loaders produce, which the host's `prepare` folder packs into these.)
//! Polymorphic records are tagged structs (a `kind` word), since rust-gpu lays out data-carrying enums
//! in buffers differently from Rust.

/// Marks "none" in index fields.
pub const NONE: u32 = u32::MAX;

/// One BVH2 node (32 bytes). Inner nodes (`prim_count == 0`) have children at `first` and `first + 1`;
/// leaves cover primitives `first .. first + prim_count` (primitives are stored in BVH order).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct BvhNode {
    pub min: [f32; 3],
    pub prim_count: u32,
    pub max: [f32; 3],
    pub first: u32,
}

pub const PRIM_TRIANGLE: u32 = 0;
pub const PRIM_SPHERE: u32 = 1;
/// An analytic disk: centre `p0`, axes `p1` (u) and `p2` (v); it faces `u × v` (flipped by `PRIM_FLAG_FLIP`).
pub const PRIM_DISK: u32 = 2;
/// An instance of a shapegroup (`instancing`; only with `features::INSTANCING`): `p0` and `p2` are
/// its world bounds' min and max (for the host), `material` the root of the group's BVH in the node
/// buffer, `flags` where its transforms start in `tables` (`instancing::INSTANCE_FLOATS` floats), or
/// `NONE` for the scene's own shapes, which need none.
pub const PRIM_INSTANCE: u32 = 3;

/// Primitive flag: interpolate the per-vertex normals in `ShadingNormals`.
pub const PRIM_FLAG_SMOOTH: u32 = 1;
/// Primitive flag: the shape's normals are flipped (`flip_normals`).
pub const PRIM_FLAG_FLIP: u32 = 2;

/// A triangle (`p0, p1, p2`) or an analytic sphere (centre `p0`, radius `p1[0]`), 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Primitive {
    pub p0: [f32; 3],
    pub kind: u32,
    pub p1: [f32; 3],
    pub material: u32,
    pub p2: [f32; 3],
    /// Index into the light list when the primitive emits, else `NONE`.
    pub light: u32,
    pub flags: u32,
    /// The absolute part of the ray offset from this primitive (`shape::offset_origin`): the scene's
    /// size up to 1, the same for every primitive of a scene (kept here, where every offset finds it).
    pub offset_floor: f32,
    pub _pad: [u32; 2],
}

/// Per-triangle vertex attributes, indexed like `Primitive`: shading normals (used when the primitive
/// has `PRIM_FLAG_SMOOTH`) and texture coordinates (Mitsuba's barycentric default `(0,0), (1,0), (0,1)`
/// when the mesh has none).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct TriangleAttributes {
    pub n0: [f32; 3],
    pub _p0: f32,
    pub n1: [f32; 3],
    pub _p1: f32,
    pub n2: [f32; 3],
    pub _p2: f32,
    pub uv0: [f32; 2],
    pub uv1: [f32; 2],
    pub uv2: [f32; 2],
    /// Where the triangle's mesh attributes start in `tables` (`MESH_ATTRIBUTE_FLOATS` per attribute
    /// the scene's `mesh_attribute` textures read), `NONE` where it has none; read only with
    /// `features::MESH_ATTRIBUTES`.
    pub mesh_attributes: u32,
    pub _p3: u32,
}

/// Floats of one mesh attribute of one triangle in `tables`: linear RGB at corners 0, 1, 2 (a
/// one-channel attribute repeated as a grey; a face attribute the same at all three).
pub const MESH_ATTRIBUTE_FLOATS: u32 = 9;

pub const BSDF_DIFFUSE: u32 = 0;
pub const BSDF_PHONG: u32 = 1;
pub const BSDF_CONDUCTOR: u32 = 2;
pub const BSDF_ROUGH_CONDUCTOR: u32 = 3;
pub const BSDF_DIELECTRIC: u32 = 4;
pub const BSDF_THIN_DIELECTRIC: u32 = 5;
pub const BSDF_ROUGH_DIELECTRIC: u32 = 6;
pub const BSDF_PLASTIC: u32 = 7;
pub const BSDF_ROUGH_PLASTIC: u32 = 8;
/// "Ray Tracing in One Weekend"'s fuzzy metal; `alpha_u` holds the fuzz.
pub const BSDF_FUZZY_METAL: u32 = 9;
/// Mitsuba's `principled` (Disney BSDF); its parameters' fields: `bsdf::principled::PrincipledParams`.
pub const BSDF_PRINCIPLED: u32 = 10;
/// Mitsuba's `principledthin` (a thin Disney sheet); its parameters' fields:
/// `bsdf::principled_thin::ThinParams`.
pub const BSDF_PRINCIPLED_THIN: u32 = 11;
/// Mitsuba's `blendbsdf`: not a model but a weighted pair of other records (`bsdf::blend`). Its kind
/// lies outside the models' feature bits 0–11: its path has its own bit, `features::BLEND`.
pub const BSDF_BLEND: u32 = 12;
/// Mitsuba's `pplastic` (unpolarized): the models' feature bits are all taken, so its path has its own
/// bit, `features::PPLASTIC`.
pub const BSDF_PPLASTIC: u32 = 13;

/// Material flag: both sides of the surface scatter (Mitsuba's `twosided`).
pub const MATERIAL_TWO_SIDED: u32 = 1;
/// Material flag: the microfacet distribution is Beckmann (GGX otherwise).
pub const MATERIAL_BECKMANN: u32 = 2;
/// Material flag: plastic's `nonlinear` (colour shift from internal scattering).
pub const MATERIAL_NONLINEAR: u32 = 4;
/// Material flag: a dielectric whose index of refraction depends on the wavelength (`wavelength`).
pub const MATERIAL_DISPERSIVE: u32 = 8;
/// Material flag: the dispersion follows Sellmeier's law (else Cauchy's; `wavelength`).
pub const MATERIAL_SELLMEIER: u32 = 16;
/// Mitsuba's `mask`: the surface is there with probability `opacity` (or `opacity_texture`'s
/// luminance) and otherwise lets the path through unchanged (`crate::mask`).
pub const MATERIAL_MASK: u32 = 32;
/// Flags above this bit: where a `twosided` of two BSDFs keeps its back's record, its index in the
/// material list plus one (0: none; `two_sided`). The record has no spare word; the flags' low byte
/// is enough for the flag bits.
pub const MATERIAL_BACK_SHIFT: u32 = 8;

/// `Material::perturb`: the kind of perturbation in the low two bits (0: none).
pub const PERTURB_KIND: u32 = 3;
/// Mitsuba's `normalmap`: the texture's RGB, `2c − 1`, is the normal in the shading frame.
pub const PERTURB_NORMAL_MAP: u32 = 1;
/// Mitsuba's `bumpmap`: the texture's luminance (times `bump_scale`) displaces the surface.
pub const PERTURB_BUMP_MAP: u32 = 2;
/// `flip_invalid_normals`: a perturbed normal facing away from the viewer is mirrored about the normal.
pub const PERTURB_FLIP_INVALID: u32 = 4;
/// `use_shadowing_function`: Estevez et al.'s microfacet shadowing of the bump terminator.
pub const PERTURB_SHADOWING: u32 = 8;
/// The perturbation wraps a `twosided` BSDF (else `twosided`, if any, wraps the perturbation).
pub const PERTURB_TWO_SIDED_INSIDE: u32 = 16;

/// A BSDF record (160 bytes). Which fields a model reads is documented by the model's `from_material`;
/// colours are linear RGB with an unused fourth lane. `Default` is a black diffuse without textures.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Material {
    pub kind: u32,
    pub flags: u32,
    /// Microfacet roughness along the shading frame's tangent and bitangent; the fuzz of
    /// `BSDF_FUZZY_METAL`.
    pub alpha_u: f32,
    pub alpha_v: f32,
    /// Relative index of refraction (interior over exterior) of dielectrics and plastics; the Phong
    /// exponent for `BSDF_PHONG`.
    pub eta: f32,
    /// Texture replacing `reflectance` (index into the texture list), or `NONE`; conductors'
    /// `conductor_k`.
    pub reflectance_texture: u32,
    /// Texture replacing `specular_reflectance`, or `NONE`.
    pub specular_texture: u32,
    /// Start of a model's precomputed table in `tables` (rough plastic's transmittance), or `NONE`.
    pub table: u32,
    /// `MATERIAL_MASK`: the probability that a path meets the surface (1: opaque).
    pub opacity: f32,
    /// Texture whose luminance replaces `opacity`, or `NONE`.
    pub opacity_texture: u32,
    /// Rough conductors and dielectrics: textures whose luminance replaces `alpha_u` and `alpha_v`
    /// (Mitsuba's textured `alpha`, `alpha_u`, `alpha_v`), or `NONE`. (Also keep the arrays below at
    /// 16-byte offsets.)
    pub alpha_u_texture: u32,
    pub alpha_v_texture: u32,
    /// Diffuse reflectance (diffuse, Phong `kd`, plastic).
    pub reflectance: [f32; 4],
    /// Specular reflectance (Phong `ks`, conductors, dielectrics, plastics).
    pub specular_reflectance: [f32; 4],
    /// Specular transmittance of dielectrics (`param_texture` may replace it).
    pub specular_transmittance: [f32; 4],
    /// Conductors: real part of the relative complex index of refraction, per channel (`param_texture`
    /// may replace it).
    pub conductor_eta: [f32; 4],
    /// Conductors: imaginary part (absorption), per channel (`reflectance_texture` may replace it).
    pub conductor_k: [f32; 4],
    /// Model-specific precomputed scalars (see the model's `precompute`).
    pub params: [f32; 4],
    /// Normal or bump mapping around this BSDF (Mitsuba's `normalmap`, `bumpmap`; `bsdf::perturb`):
    /// `PERTURB_*` bits, 0 for none; the normal map or height texture; the bump map's `scale`.
    pub perturb: u32,
    pub perturb_texture: u32,
    pub bump_scale: f32,
    /// Texture replacing the one parameter of a model that the slots above do not cover, or `NONE`
    /// (`bsdf::Component::new`): the `specular_transmittance` of dielectrics, the `conductor_eta` of
    /// conductors (which keep a textured `conductor_k` in `reflectance_texture`: they have no diffuse
    /// reflectance). It takes the perturbation group's spare word, so the record does not grow.
    pub param_texture: u32,
}

// The host and both backends share this layout; a field added must find a spare word first.
#[cfg(not(target_arch = "spirv"))]
const _: () = assert!(core::mem::size_of::<Material>() == 160);

impl Default for Material {
    fn default() -> Self {
        Material {
            kind: BSDF_DIFFUSE,
            flags: 0,
            alpha_u: 0.0,
            alpha_v: 0.0,
            eta: 1.0,
            reflectance_texture: NONE,
            specular_texture: NONE,
            table: NONE,
            opacity: 1.0,
            opacity_texture: NONE,
            alpha_u_texture: NONE,
            alpha_v_texture: NONE,
            reflectance: [0.0; 4],
            specular_reflectance: [0.0; 4],
            specular_transmittance: [0.0; 4],
            conductor_eta: [0.0; 4],
            conductor_k: [0.0; 4],
            params: [0.0; 4],
            perturb: 0,
            perturb_texture: NONE,
            bump_scale: 1.0,
            param_texture: NONE,
        }
    }
}

/// An area emitter on a flat primitive (triangle or disk), sampled uniformly by area.
pub const LIGHT_AREA: u32 = 0;
pub const LIGHT_SPHERE: u32 = 1;
pub const LIGHT_POINT: u32 = 2;
pub const LIGHT_SPOT: u32 = 3;
pub const LIGHT_DIRECTIONAL: u32 = 4;
pub const LIGHT_CONSTANT: u32 = 5;
pub const LIGHT_ENVMAP: u32 = 6;
/// Light flag of an area emitter: Mitsuba's `directionalarea`, which emits along its surface's normal
/// only (a Dirac delta in direction): light tracing alone starts paths there (`light::emission`).
pub const LIGHT_FLAG_DIRECTIONAL_AREA: u32 = 1;
/// Mitsuba's `projector`: an image projected from a point through a pinhole (`light::projector`).
pub const LIGHT_PROJECTOR: u32 = 7;

/// An emitter (128 bytes), chosen for next-event estimation with probability `pmf` (proportional to
/// its power). `Default` has no texture.
#[repr(C)]
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Light {
    pub kind: u32,
    /// The emitting primitive of area lights; the texture of an envmap; else `NONE`.
    pub prim: u32,
    pub pmf: f32,
    /// Start of the light's sampling distribution in `tables` (envmap), else `NONE`.
    pub table: u32,
    /// Radiance (area, constant, envmap scale), intensity (point, spot) or irradiance (directional).
    pub radiance: [f32; 4],
    /// Position (point, spot); the scene's bounding-sphere centre and radius in `w` (directional,
    /// constant, envmap).
    pub position: [f32; 4],
    /// Spot: `cos cutoff, cos beam_width, cutoff (radians), 1 / (cutoff - beam_width)`; projector:
    /// `tan(fov_x / 2), tan(fov_y / 2)`, unused, the image's area on the plane z = 1; envmap: the
    /// luminance its sampling leaves out of every texel (MIS compensation's offset, else 0).
    pub params: [f32; 4],
    /// Rows of the world-to-local rotation (spot: local +z is the beam axis; directional: local +z is
    /// the direction of travel; envmap: Mitsuba's lat-long frame; projector: local +z is the axis).
    pub to_local: [[f32; 4]; 3],
    /// The texture that multiplies `radiance` (`light::textured`, under `features::TEXTURED_EMISSION`):
    /// an area emitter's radiance over its surface's uv, a spot's image over its cone, a projector's
    /// irradiance; `NONE` for uniform emission. (An envmap's texture is in `prim`.)
    pub texture: u32,
    /// `LIGHT_FLAG_*` bits.
    pub flags: u32,
    pub _pad: [u32; 2],
}

impl Default for Light {
    fn default() -> Self {
        Light {
            kind: 0,
            prim: 0,
            pmf: 0.0,
            table: 0,
            radiance: [0.0; 4],
            position: [0.0; 4],
            params: [0.0; 4],
            to_local: [[0.0; 4]; 3],
            texture: NONE,
            flags: 0,
            _pad: [0; 2],
        }
    }
}

pub const TEXTURE_BITMAP: u32 = 0;
pub const TEXTURE_CHECKERBOARD: u32 = 1;
/// Mitsuba's `mesh_attribute`: the hit triangle's attribute, interpolated by the hit's barycentrics;
/// `offset` is the attribute's place in each triangle's block (`TriangleAttributes::mesh_attributes`),
/// `color0` the `scale`.
pub const TEXTURE_MESH_ATTRIBUTE: u32 = 2;

/// Texture flag: nearest-neighbour lookups (bilinear otherwise).
pub const TEXTURE_NEAREST: u32 = 1;
/// Texture flags: wrap mode in bits 1..2 (`TEXTURE_WRAP_*` shifted by 1).
pub const TEXTURE_WRAP_SHIFT: u32 = 1;
pub const TEXTURE_WRAP_REPEAT: u32 = 0;
pub const TEXTURE_WRAP_MIRROR: u32 = 1;
pub const TEXTURE_WRAP_CLAMP: u32 = 2;

/// A texture (96 bytes). Bitmaps keep their linear RGB texels in `tables` (three floats per texel,
/// row-major from the top row).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct Texture {
    pub kind: u32,
    pub width: u32,
    pub height: u32,
    /// Where the texels start in `tables`.
    pub offset: u32,
    pub flags: u32,
    pub _pad: [u32; 3],
    /// Rows of the affine `to_uv` transform: `u' = r0·(u, v, 1)`, `v' = r1·(u, v, 1)`.
    pub to_uv: [[f32; 4]; 2],
    /// Checkerboard colours.
    pub color0: [f32; 4],
    pub color1: [f32; 4],
}

/// One pixel's running sums in the accumulation buffer (32 bytes): what every pass adds to
/// (`integrator::accumulated`) and what the host folds into its f64 totals every few thousand
/// samples (the host's `backend::accumulation::Accumulation::fold`), then clears.
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug, PartialEq))]
pub struct PixelAccum {
    /// Sum of the samples' RGB estimates.
    pub sum: [f32; 3],
    /// Samples taken (a float, summed like the rest).
    pub count: f32,
    /// Sum of the squared estimates, per channel, each scaled by `square_scale` before squaring
    /// (the host divides that back out when it folds these into its f64 totals).
    pub sum_sq: [f32; 3],
    /// Samples whose estimate was NaN or infinite: counted as black and reported.
    pub invalid: f32,
}

/// `2^params.square_scale_log2` (exact: built from the exponent bits; `e` within ±126).
#[inline]
pub fn square_scale(params: &FrameParams) -> f32 {
    f32::from_bits(((127 + params.square_scale_log2) as u32) << 23)
}

/// The GPU entry point's workgroup edge (`threads(8, 8, 1)` in `entry.rs`, which needs a literal):
/// 8×8 pixels, so neighbouring rays (coherent traversal) run together. The host dispatches by it.
pub const TILE: u32 = 8;

/// Specialization constant ids of the camera entry point (`entry.rs` spells them as literals): the
/// scene's feature mask (`features`), and whether the path tracer runs its regenerating loop (1) or
/// its plain one (0; `integrator::render_pixel`).
pub const SPEC_FEATURES: u32 = 0;
pub const SPEC_REGENERATE: u32 = 1;

/// Binding numbers of the entry point's buffers (descriptor set 0), named for the host's bind group;
/// `entry.rs` spells the same numbers as the literals rust-gpu's attributes need.
pub mod binding {
    pub const PARAMS: u32 = 0;
    pub const NODES: u32 = 1;
    pub const PRIMS: u32 = 2;
    pub const ATTRIBUTES: u32 = 3;
    pub const MATERIALS: u32 = 4;
    pub const LIGHTS: u32 = 5;
    pub const TABLES: u32 = 6;
    pub const ACCUM: u32 = 7;
    pub const TEXTURES: u32 = 8;
    /// Light tracing's fixed-point splat sums (`splat`); a placeholder word for the other integrators.
    pub const SPLAT: u32 = 9;
    /// BDPT's and VCM's light vertex cache (`integrator::bdpt::LightVertex`, `MAX_LIGHT_VERTICES` a
    /// pixel).
    pub const CACHE: u32 = 10;
    /// VCM's hash grid over the cache (`integrator::vcm_grid`).
    pub const GRID: u32 = 11;
}

pub const INTEGRATOR_PATH: u32 = 0;
pub const INTEGRATOR_DIRECT: u32 = 1;
/// Light tracing (Mitsuba's `ptracer`): splats into the `SPLAT` buffer instead of accumulating.
pub const INTEGRATOR_PTRACER: u32 = 2;
/// Instant bidirectional path tracing: a camera path (with NEE) and a light path (connected to the
/// camera) per pixel sample, combined by the power heuristic; splats like `INTEGRATOR_PTRACER`.
pub const INTEGRATOR_IBPT: u32 = 3;
/// Bidirectional path tracing (`integrator::bdpt`): per pixel sample a light path and a camera path
/// joined in every way, combined by the power heuristic; splats like `INTEGRATOR_IBPT`, in the camera
/// entry point alone.
pub const INTEGRATOR_BDPT: u32 = 4;
/// Vertex connection and merging (`integrator::vcm`): each pass traces a light path per pixel into
/// the light vertex cache, builds the hash grid over it, then traces a camera path per pixel that
/// connects to its own light path's vertices and merges with every light vertex within
/// `merge_radius`; splats like `INTEGRATOR_BDPT`.
pub const INTEGRATOR_VCM: u32 = 5;

/// Whether integrator `kind` splats into the `SPLAT` words (resolved by the host after each pass).
#[inline]
pub fn splats(kind: u32) -> bool {
    kind == INTEGRATOR_PTRACER || kind == INTEGRATOR_IBPT || kind == INTEGRATOR_BDPT || kind == INTEGRATOR_VCM
}

pub const SAMPLER_INDEPENDENT: u32 = 0;
pub const SAMPLER_STRATIFIED: u32 = 1;

/// Per-dispatch parameters (a uniform buffer: only 4-byte scalars and 16-byte groups).
#[repr(C)]
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(target_arch = "spirv"), derive(bytemuck::Pod, bytemuck::Zeroable, Debug))]
pub struct FrameParams {
    pub width: u32,
    pub height: u32,
    /// Index of the first sample this dispatch adds to each pixel.
    pub sample_base: u32,
    /// Samples per pixel this dispatch adds.
    pub sample_count: u32,

    pub seed: u32,
    /// Mitsuba's `max_depth`: longest path in segments, `u32::MAX` for unbounded (-1).
    pub max_depth: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    pub sampler: u32,

    /// Total samples per pixel of the whole render (the stratified sampler's strata come from it).
    pub spp_total: u32,
    pub light_count: u32,
    /// Where the light-selection CDF starts in the table buffer.
    pub light_cdf_offset: u32,
    /// Where the reconstruction filter's CDF starts in the table buffer, and its bin count.
    pub filter_cdf_offset: u32,

    pub filter_bins: u32,
    pub filter_radius: f32,
    pub hide_emitters: u32,
    /// The environment emitter (constant or envmap) in the light list, or `NONE`.
    pub env_light: u32,

    /// The rendered pixels (`width` × `height`) start at (`crop_x`, `crop_y`) of the full image.
    pub crop_x: u32,
    pub crop_y: u32,
    pub full_width: u32,
    pub full_height: u32,

    /// `INTEGRATOR_PATH`, `INTEGRATOR_DIRECT`, `INTEGRATOR_PTRACER`, `INTEGRATOR_IBPT`,
    /// `INTEGRATOR_BDPT` or `INTEGRATOR_VCM`.
    pub integrator: u32,
    /// Light and BSDF samples per shading point of the direct integrator.
    pub emitter_samples: u32,
    pub bsdf_samples: u32,
    /// Where the wavelength table starts in the table buffer (`wavelength`; scenes with dispersion).
    pub wavelength_table: u32,

    /// 1 when the filter has negative lobes (`mitchell`, `lanczos`): its signed running sum follows
    /// its CDF in the table buffer and camera samples carry signed weights (`film`); 0 otherwise.
    pub filter_signed: u32,
    /// The sums of squares add `(2^e · l)²` for a sample `l` (`square_scale`; `e` here, chosen by the
    /// host from the scene's brightest emitter): a lamp of radiance 1e30 gave squares of 1e60, +Inf
    /// in f32, and every variance infinite. A power of two, so the scaling itself is exact; 0 (the
    /// default) is no scaling.
    pub square_scale_log2: i32,
    /// The film (`film_splat`): 0 gives each camera sample to its own pixel, its offset drawn from
    /// the filter (filter importance sampling); `r` > 0 splats it, drawn uniformly in its pixel, into
    /// the (2r+1)² pixels around it with the filter's weight, as Mitsuba's `hdrfilm` does.
    pub film_reach: u32,
    /// Vertex merging's radius in this pass (`INTEGRATOR_VCM`; 0 otherwise), in scene units.
    pub merge_radius: f32,

    /// BDPT's and VCM's connections (`bdpt_mis::Connections`): 0 joins each camera vertex to every
    /// vertex of its light path; `c` > 0 to one of them drawn uniformly, the connection strategies
    /// counting `c` against the other strategies' 1 in the weights.
    pub connection_share: f32,
    /// The share of light paths connected to the camera (`ibpt`, `bdpt`, `vcm`; the host passes 1
    /// for `ptracer`, whose light tracing is its only strategy), decided for each 8×8 tile of path
    /// indices and sample (`ptracer::connects_to_camera`);
    /// their splats count `1 / share` (`ptracer::film_scale`) and the weights count light tracing
    /// `share` times. 0 (or 1 and above): every light path.
    pub light_tracing_share: f32,
    /// BDPT's and VCM's share of camera vertices that join their light path
    /// (`bdpt::connection_rate`), decided for each 8×8 tile of pixels, sample and depth; a joined
    /// vertex counts `1 / rate` and the weights count connections `rate` times as often. 0 (or 1 and
    /// above): every camera vertex with a non-Dirac lobe.
    pub connection_rate: f32,
    /// The filter's untruncated masses along an axis, of its |w| table and of its signed one
    /// (`film::whole_masses`; equal where it has no negative lobes): the mass `film` divides by for a
    /// pixel whose filter lies inside the rendered window, written once a frame by the host instead
    /// of summed from the tables for every column of every splat.
    pub filter_abs_mass: f32,
    pub filter_mass: f32,
    pub _pad: [u32; 3],

    pub camera: crate::camera::Camera,
}

/// The scene as the kernel sees it: borrowed buffers.
#[derive(Clone, Copy)]
pub struct SceneView<'a> {
    pub nodes: &'a [BvhNode],
    pub prims: &'a [Primitive],
    pub attributes: &'a [TriangleAttributes],
    pub materials: &'a [Material],
    pub lights: &'a [Light],
    pub textures: &'a [Texture],
    /// Concatenated tables: 1D distributions (light selection CDF, filter CDF, envmap CDFs), bitmap
    /// texels, precomputed BSDF tables; located by `FrameParams`, `Texture`, `Light` and `Material`.
    pub tables: &'a [f32],
    /// What the scene uses (`features`): unused paths are skipped (on the GPU, compiled out).
    pub features: u32,
    /// `nodes` holds a 4-wide BVH (`wide_bvh`) rather than BVH2: the CPU backend's choice.
    pub wide_bvh: bool,
}
