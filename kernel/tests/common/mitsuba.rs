//! Mitsuba 3.9.1's own BSDF values (`kernel/tests/data/mitsuba_bsdf_values.json`, written by
//! `mitsuba_bsdf_values.py` beside it) and the caustic materials that mirror the Mitsuba dictionaries
//! which produced them.
use super::models::{c4, copper, material, rough, Model};
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::*;
use serde_json::Value;

/// `bsdf.eval` and `bsdf.pdf` of Mitsuba for one direction pair (caustic's `wo` is Mitsuba's `si.wi`).
pub struct EvalRef {
    pub model: String,
    pub adjoint: bool,
    pub wo: Vec3,
    pub wi: Vec3,
    pub f: Vec3,
    pub pdf: f32,
}

/// `bsdf.sample` of Mitsuba for one `wo` and pair of random numbers.
pub struct SampleRef {
    pub model: String,
    pub adjoint: bool,
    pub wo: Vec3,
    pub u_lobe: f32,
    pub u: [f32; 2],
    pub wi: Vec3,
    pub weight: Vec3,
    pub pdf: f32,
    pub eta: f32,
}

pub struct References {
    pub eval: Vec<EvalRef>,
    pub sample: Vec<SampleRef>,
}

const PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/mitsuba_bsdf_values.json");

/// Reads the reference file. (Values go through f64 to f32: the file's 9-digit decimals read back as
/// the float32s Mitsuba computed.)
pub fn references() -> References {
    references_in(PATH)
}

/// Reads a file of reference rows in the format of `mitsuba_bsdf_values.json`.
pub fn references_in(path: &str) -> References {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let v: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
    let num =
        |r: &Value, k: &str| r[k].as_f64().unwrap_or_else(|| panic!("{path}: no number {k} in {r}")) as f32;
    let vec3 = |r: &Value, k: &str| {
        let a = r[k].as_array().filter(|a| a.len() == 3).unwrap_or_else(|| panic!("{path}: {k} in {r}"));
        Vec3::from_array([0, 1, 2].map(|i| a[i].as_f64().unwrap() as f32))
    };
    let model = |r: &Value| r["model"].as_str().unwrap().to_string();
    let adjoint = |r: &Value| r["adjoint"].as_bool().unwrap();
    let rows = |k: &str| v[k].as_array().unwrap_or_else(|| panic!("{path}: no {k} rows")).clone();
    let eval = rows("eval")
        .iter()
        .map(|r| EvalRef {
            model: model(r),
            adjoint: adjoint(r),
            wo: vec3(r, "wo"),
            wi: vec3(r, "wi"),
            f: vec3(r, "f"),
            pdf: num(r, "pdf"),
        })
        .collect();
    let sample = rows("sample")
        .iter()
        .map(|r| {
            let u = r["u"].as_array().unwrap();
            SampleRef {
                model: model(r),
                adjoint: adjoint(r),
                wo: vec3(r, "wo"),
                u_lobe: num(r, "u_lobe"),
                u: [u[0].as_f64().unwrap() as f32, u[1].as_f64().unwrap() as f32],
                wi: vec3(r, "wi"),
                weight: vec3(r, "weight"),
                pdf: num(r, "pdf"),
                eta: num(r, "eta"),
            }
        })
        .collect();
    References { eval, sample }
}

/// Every material `reference_material` knows: the models Mitsuba's values cover.
pub const REFERENCE_MODELS: [&str; 11] = [
    "conductor",
    "rough_conductor_ggx_aniso",
    "rough_conductor_beckmann",
    "dielectric",
    "thin_dielectric",
    "rough_dielectric_ggx",
    "rough_dielectric_beckmann_aniso",
    "plastic",
    "plastic_nonlinear",
    "rough_plastic_beckmann",
    "rough_plastic_ggx_nonlinear",
];

/// The materials of the reference values: the same parameters as the Mitsuba dictionaries
/// (`MATERIALS` in the script), whose `ext_ior` is 1.
pub fn reference_material(name: &str) -> Material {
    let (sr, st) = (c4(0.9, 0.8, 0.7), c4(0.6, 0.7, 0.8));
    match name {
        "conductor" => {
            Material { specular_reflectance: c4(1.0, 0.8, 0.6), ..copper(material(BSDF_CONDUCTOR)) }
        }
        "rough_conductor_ggx_aniso" => Material {
            specular_reflectance: c4(1.0, 0.8, 0.6),
            ..copper(rough(BSDF_ROUGH_CONDUCTOR, 0.1, 0.4, false))
        },
        "rough_conductor_beckmann" => copper(rough(BSDF_ROUGH_CONDUCTOR, 0.3, 0.3, true)),
        "dielectric" => {
            Material { specular_reflectance: sr, specular_transmittance: st, ..material(BSDF_DIELECTRIC) }
        }
        "thin_dielectric" => Material {
            specular_reflectance: sr,
            specular_transmittance: st,
            ..material(BSDF_THIN_DIELECTRIC)
        },
        "rough_dielectric_ggx" => Material {
            specular_reflectance: sr,
            specular_transmittance: st,
            ..rough(BSDF_ROUGH_DIELECTRIC, 0.2, 0.2, false)
        },
        "rough_dielectric_beckmann_aniso" => {
            Material { eta: 2.42, ..rough(BSDF_ROUGH_DIELECTRIC, 0.05, 0.3, true) }
        }
        "plastic" => Material { reflectance: c4(0.3, 0.5, 0.7), ..material(BSDF_PLASTIC) },
        "plastic_nonlinear" => Material {
            eta: 1.9,
            flags: MATERIAL_NONLINEAR,
            reflectance: c4(0.8, 0.4, 0.1),
            specular_reflectance: c4(0.9, 0.7, 0.9),
            ..material(BSDF_PLASTIC)
        },
        "rough_plastic_beckmann" => {
            Material { reflectance: c4(0.3, 0.5, 0.7), ..rough(BSDF_ROUGH_PLASTIC, 0.1, 0.1, true) }
        }
        "rough_plastic_ggx_nonlinear" => Material {
            eta: 1.9,
            flags: MATERIAL_NONLINEAR,
            reflectance: c4(0.8, 0.4, 0.1),
            specular_reflectance: c4(0.9, 0.7, 0.9),
            ..rough(BSDF_ROUGH_PLASTIC, 0.4, 0.4, false)
        },
        _ => panic!("unknown reference model {name}"),
    }
}

/// The reference models, built once (rough plastic's precomputation is not free).
pub fn reference_model(name: &str, adjoint: bool) -> Model {
    use std::collections::HashMap;
    use std::sync::Mutex;
    static CACHE: Mutex<Option<HashMap<(String, bool), Model>>> = Mutex::new(None);
    let mut cache = CACHE.lock().unwrap();
    *cache
        .get_or_insert_with(HashMap::new)
        .entry((name.to_string(), adjoint))
        .or_insert_with(|| Model::new(&reference_material(name), adjoint))
}
