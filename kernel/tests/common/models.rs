//! Test fixtures for the BSDF models: `Model` (a material's BSDF in one transport mode, built as the
//! host builds it), the materials the tests run on, directions, and float comparisons.
use caustic_kernel::bsdf::{Bsdf, BsdfSample, Bxdf, EvalPdf, TransportMode};
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::*;
use caustic_kernel::rng::Sampler;
use caustic_kernel::sampling::square_to_uniform_sphere;

/// A model as the integrators see it: `Bsdf` (the one dispatch) in a transport mode.
#[derive(Clone, Copy)]
pub struct Model {
    pub bsdf: Bsdf<'static>,
    pub mode: TransportMode,
}

impl Model {
    /// Builds the model of `m` as the host would: precomputes what it needs, evaluates no textures.
    pub fn new(m: &Material, adjoint: bool) -> Model {
        Model::in_list(m, &[], adjoint)
    }

    /// Mitsuba's `blendbsdf` of `first` and `second` with weight `weight` (of `second`), built as the
    /// host builds it: the blend record names the children's places in the material list.
    pub fn blend(first: &Material, second: &Material, weight: f32, adjoint: bool) -> Model {
        let blend = caustic_kernel::bsdf::blend::record(0, 1, weight, NONE);
        Model::in_list(&blend, &[*first, *second], adjoint)
    }

    /// A tree of blends: `root` (a blend record) over the material list `materials`, where its
    /// children and their children are.
    pub fn tree(root: &Material, materials: &[Material], adjoint: bool) -> Model {
        Model::in_list(root, materials, adjoint)
    }

    /// The model of `m` in a scene whose material list is `materials` (precomputed here, and leaked
    /// with the tables: the BSDF keeps both: a test builds a few hundred models at most, and `Model` stays `Copy`).
    fn in_list(m: &Material, materials: &[Material], adjoint: bool) -> Model {
        let mut m = *m;
        let mut materials = materials.to_vec();
        // Behind some unrelated data, as in the host's table buffer: a model that reads its table at
        // the wrong offset reads these.
        let mut tables = vec![7.0f32; 5];
        for m in std::iter::once(&mut m).chain(materials.iter_mut()) {
            if let Some(table) = caustic_kernel::bsdf::precompute(m) {
                m.table = tables.len() as u32;
                tables.extend(table);
            }
        }
        let tables: &'static [f32] = Box::leak(tables.into_boxed_slice());
        let materials: &'static [Material] = Box::leak(materials.into_boxed_slice());
        let mode = if adjoint { TransportMode::Importance } else { TransportMode::Radiance };
        Model { bsdf: Bsdf::from_material(&m, materials, tables), mode }
    }

    /// The same model in transport mode `mode`.
    pub fn in_mode(self, mode: TransportMode) -> Model {
        Model { mode, ..self }
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.bsdf.eval(wo, wi, self.mode)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.bsdf.pdf(wo, wi, self.mode)
    }

    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> EvalPdf {
        self.bsdf.eval_pdf(wo, wi, self.mode)
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> BsdfSample {
        self.bsdf.sample(wo, u_lobe, u, self.mode)
    }

    /// The model's kind (`BSDF_BLEND` for a blend).
    pub fn kind(&self) -> u32 {
        if self.bsdf.blended {
            return BSDF_BLEND;
        }
        self.bsdf.first.material.kind
    }

    /// The concrete model, for tests that look inside it.
    pub fn concrete<M: Bxdf<'static>>(&self) -> M {
        let c = &self.bsdf.first;
        M::from_material(&c.material, c.reflectance, c.specular, self.bsdf.tables)
    }
}

pub const MODES: [TransportMode; 2] = [TransportMode::Radiance, TransportMode::Importance];

pub fn rgb(c: [f32; 4]) -> Vec3 {
    Vec3::new(c[0], c[1], c[2])
}

pub fn c4(r: f32, g: f32, b: f32) -> [f32; 4] {
    [r, g, b, 0.0]
}

/// A material of `kind` with Mitsuba's defaults where the host would fill them in: unit specular
/// reflectance and transmittance, a perfect-mirror conductor (eta 0, k 1), diffuse 0.5, IOR 1.5.
pub fn material(kind: u32) -> Material {
    Material {
        kind,
        eta: 1.5,
        alpha_u: 0.1,
        alpha_v: 0.1,
        reflectance: c4(0.5, 0.5, 0.5),
        specular_reflectance: c4(1.0, 1.0, 1.0),
        specular_transmittance: c4(1.0, 1.0, 1.0),
        conductor_eta: c4(0.0, 0.0, 0.0),
        conductor_k: c4(1.0, 1.0, 1.0),
        ..Default::default()
    }
}

pub fn rough(kind: u32, alpha_u: f32, alpha_v: f32, beckmann: bool) -> Material {
    Material { alpha_u, alpha_v, flags: if beckmann { MATERIAL_BECKMANN } else { 0 }, ..material(kind) }
}

/// Ray Tracing in One Weekend's metal with fuzz `fuzz` (stored in `alpha_u`).
pub fn fuzzy(fuzz: f32) -> Material {
    Material { alpha_u: fuzz, reflectance: c4(0.9, 0.6, 0.3), ..material(BSDF_FUZZY_METAL) }
}

/// A copper-like conductor's complex index (RGB): every channel differs, so a swapped one shows.
pub fn copper(m: Material) -> Material {
    Material { conductor_eta: c4(0.2, 0.9, 1.1), conductor_k: c4(3.9, 2.4, 2.2), ..m }
}

/// Lambert and modified Phong (kd, ks, exponent in `eta`) from a perfect Phong mirror-ish lobe to a
/// very narrow one and a diffuse-only mixture.
pub fn diffuse_and_phong() -> Vec<Material> {
    let mut v =
        vec![Material { kind: BSDF_DIFFUSE, reflectance: [1.0, 0.5, 0.2, 0.0], ..Default::default() }];
    for (kd, ks, n) in
        [(0.0, 1.0, 1.0), (0.0, 1.0, 50.0), (0.5, 0.5, 10.0), (0.3, 0.7, 1000.0), (0.9, 0.1, 0.0)]
    {
        v.push(Material {
            kind: BSDF_PHONG,
            eta: n,
            reflectance: [kd; 4],
            specular_reflectance: [ks; 4],
            ..Default::default()
        });
    }
    v
}

/// Models with smooth lobes over a range of parameters.
pub fn smooth_models() -> Vec<(String, Material)> {
    let mut v = Vec::new();
    for beckmann in [false, true] {
        let d = if beckmann { "beckmann" } else { "ggx" };
        for (au, av) in [(0.05f32, 0.05f32), (0.3, 0.3), (1.0, 1.0), (0.1, 0.5)] {
            v.push((
                format!("roughconductor {d} {au}/{av}"),
                copper(rough(BSDF_ROUGH_CONDUCTOR, au, av, beckmann)),
            ));
            for eta in [1.5f32, 2.42] {
                v.push((
                    format!("roughdielectric {d} {au}/{av} η={eta}"),
                    Material { eta, ..rough(BSDF_ROUGH_DIELECTRIC, au, av, beckmann) },
                ));
            }
        }
        for alpha in [0.05f32, 0.4, 1.0] {
            v.push((
                format!("roughplastic {d} {alpha}"),
                Material {
                    reflectance: c4(0.3, 0.5, 0.7),
                    ..rough(BSDF_ROUGH_PLASTIC, alpha, alpha, beckmann)
                },
            ));
        }
    }
    v.push(("plastic".into(), Material { reflectance: c4(0.3, 0.5, 0.7), ..material(BSDF_PLASTIC) }));
    v.push((
        "plastic nonlinear".into(),
        Material {
            flags: MATERIAL_NONLINEAR,
            eta: 2.0,
            reflectance: c4(0.9, 0.5, 0.1),
            ..material(BSDF_PLASTIC)
        },
    ));
    // Lobes wide enough for random direction pairs to land in them; narrow ones are fitted by χ².
    for fuzz in [0.3f32, 0.6, 1.0] {
        v.push((format!("fuzzymetal {fuzz}"), fuzzy(fuzz)));
    }
    v
}

/// At least one material of every model kind, named: the smooth models, Lambert and Phong, the
/// Dirac-delta models, narrow and fuzz-0 fuzzy metal.
pub fn every_model() -> Vec<(String, Material)> {
    let mut v = smooth_models();
    for m in diffuse_and_phong() {
        let name = match m.kind {
            BSDF_PHONG => {
                format!("phong kd={} ks={} n={}", m.reflectance[0], m.specular_reflectance[0], m.eta)
            }
            _ => "diffuse".to_string(),
        };
        v.push((name, m));
    }
    v.push(("conductor".into(), copper(material(BSDF_CONDUCTOR))));
    v.push(("conductor (perfect mirror)".into(), material(BSDF_CONDUCTOR)));
    for eta in [1.5f32, 2.42] {
        v.push((format!("dielectric η={eta}"), Material { eta, ..material(BSDF_DIELECTRIC) }));
        v.push((format!("thindielectric η={eta}"), Material { eta, ..material(BSDF_THIN_DIELECTRIC) }));
    }
    for fuzz in [0.0f32, 0.05] {
        v.push((format!("fuzzymetal {fuzz}"), fuzzy(fuzz)));
    }
    for spec_trans in [0.0f32, 0.6] {
        v.push((format!("principled spec_trans={spec_trans}"), principled(spec_trans)));
    }
    for (spec_trans, diff_trans) in [(0.0f32, 0.0f32), (0.5, 0.8)] {
        let name = format!("principledthin spec_trans={spec_trans} diff_trans={diff_trans}");
        v.push((name, principled_thin(spec_trans, diff_trans)));
    }
    for beckmann in [false, true] {
        v.push((format!("pplastic beckmann={beckmann}"), pplastic(beckmann)));
    }
    v
}

/// Mitsuba's `principledthin` with sheen, flatness and tint (transmission weights as given).
pub fn principled_thin(spec_trans: f32, diff_trans: f32) -> Material {
    let mut m = Material {
        kind: BSDF_PRINCIPLED_THIN,
        eta: 1.4,
        alpha_u: 0.4,
        alpha_v: 0.3,
        reflectance: c4(0.8, 0.4, 0.2),
        ..Default::default()
    };
    caustic_kernel::bsdf::principled_thin::ThinParams {
        spec_trans,
        spec_tint: 0.3,
        sheen: 0.5,
        sheen_tint: 0.5,
        flatness: 0.2,
        diff_trans,
        spec_refl_rate: 1.0,
        spec_trans_rate: 1.0,
        diff_refl_rate: 1.0,
        diff_trans_rate: 1.0,
    }
    .pack(&mut m);
    m
}

/// Mitsuba's `pplastic` (unpolarized), anisotropic, with a coloured base and coat.
pub fn pplastic(beckmann: bool) -> Material {
    let mut m = Material {
        reflectance: c4(0.3, 0.5, 0.7),
        specular_reflectance: c4(0.9, 0.8, 0.7),
        ..rough(BSDF_PPLASTIC, 0.2, 0.4, beckmann)
    };
    m.params[caustic_kernel::bsdf::pplastic::PARAM_SPECULAR_WEIGHT] = 0.6;
    m
}

/// Mitsuba's `principled` with every lobe on (refraction with weight `spec_trans`).
pub fn principled(spec_trans: f32) -> Material {
    let mut m = Material {
        kind: BSDF_PRINCIPLED,
        eta: 1.4,
        alpha_u: 0.4,
        alpha_v: 0.3,
        reflectance: c4(0.8, 0.4, 0.2),
        specular_reflectance: c4(0.3, 0.3, 0.3),
        ..Default::default()
    };
    caustic_kernel::bsdf::principled::PrincipledParams {
        spec_trans,
        spec_tint: 0.3,
        sheen: 0.5,
        sheen_tint: 0.5,
        clearcoat: 0.6,
        clearcoat_gloss: 0.5,
        flatness: 0.2,
        spec_rate: 1.0,
        clearcoat_rate: 1.0,
        diffuse_rate: 1.0,
    }
    .pack(&mut m);
    m
}

pub fn dir(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z).normalize()
}

/// A unit direction with cosine `cos_theta` and azimuth `phi`.
pub fn polar(cos_theta: f32, phi: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta)
}

/// `n` directions uniform on the sphere (deterministic in `seed`).
pub fn random_dirs(n: usize, seed: u32) -> Vec<Vec3> {
    let mut rng = Sampler::new(seed, 3, 4);
    (0..n).map(|_| square_to_uniform_sphere(rng.next_2d())).collect()
}

/// `|a - b| ≤ abs + rel·max(|a|, |b|)`.
pub fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= abs + rel * a.abs().max(b.abs())
}

/// `close` in every channel.
pub fn close3(a: Vec3, b: Vec3, rel: f32, abs: f32) -> bool {
    close(a.x, b.x, rel, abs) && close(a.y, b.y, rel, abs) && close(a.z, b.z, rel, abs)
}
