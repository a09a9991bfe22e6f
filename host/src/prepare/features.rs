//! `SceneBuffers::features`: the kernel paths a scene can reach, which the GPU's pipelines are
//! specialized to (`caustic_kernel::features`), and the flags that say how its buffers are laid out.
use crate::scene::Scene;
use caustic_kernel::camera::CAMERA_IRRADIANCE_METER;
use caustic_kernel::features;
use caustic_kernel::layout::*;

/// `SceneBuffers::features`: the kernel paths the scene can reach (`scene_features`), and how its
/// buffers are laid out.
pub(super) fn features_of(
    scene: &Scene,
    materials: &[Material],
    lights: &[Light],
    textures: bool,
    params: &FrameParams,
    instanced: bool,
) -> u32 {
    let integrator_kind = params.integrator;
    let mut features = scene_features(materials, lights, textures, integrator_kind);
    if crate::prepare::attribute_buffers::used(scene) {
        features |= features::MESH_ATTRIBUTES;
    }
    if params.camera.kind == CAMERA_IRRADIANCE_METER {
        features |= features::IRRADIANCE_METER;
    }
    // Not paths to specialize but how the buffers are laid out, which per-pixel loop runs and how
    // shading frames are oriented: set exactly when they are two-level, when the integrator is
    // `direct` and when the scene has maps or anisotropic roughness (also under
    // `CAUSTIC_SPECIALIZE=0`).
    features = every_path(features, materials);
    if instanced {
        features |= features::INSTANCING;
    }
    if integrator_kind == INTEGRATOR_DIRECT {
        features |= features::DIRECT_INTEGRATOR;
    }
    features
}

/// The bits that say how the buffers are laid out, which loop runs and how frames are oriented.
const CONVENTIONS: u32 = features::INSTANCING | features::DIRECT_INTEGRATOR | features::TANGENT_FRAMES;

/// Every kernel path, with the conventions of the scene whose own mask is `specialised`: the mask a
/// scene renders the same image with as with its own (the tests compare the two).
pub fn all_paths_as(specialised: u32) -> u32 {
    (features::ALL & !CONVENTIONS) | (specialised & CONVENTIONS)
}

/// `features` with the bits that are conventions rather than paths set as the scene needs them:
/// `INSTANCING` and `DIRECT_INTEGRATOR` cleared (the caller sets them), `TANGENT_FRAMES` exactly
/// where `materials` have a normal or bump map or anisotropic roughness. With it set, every shading
/// frame's tangent follows dp/du, which turns isotropic models' samples about the normal: the same
/// image in expectation, other noise. So `features::ALL` (every path) with this gives the image the
/// scene's own mask gives (`CAUSTIC_SPECIALIZE=0`, and the tests that compare the two).
pub fn every_path(features: u32, materials: &[Material]) -> u32 {
    let mut f = features & !CONVENTIONS;
    if materials.iter().any(|m| m.perturb != 0 || anisotropic(m)) {
        f |= features::TANGENT_FRAMES;
    }
    f
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
    if materials.iter().any(|m| m.flags & MATERIAL_MASK != 0 || m.kind == BSDF_THIN_DIELECTRIC) {
        f |= features::MASK;
    }
    f
}

/// Whether `m`'s microfacet roughness differs along dp/du and dp/dv (numbers that differ, or a texture
/// on either that is not the other's): its shading frame must then follow dp/du, as Mitsuba's.
/// The principled models' `anisotropic` weight is their `alpha_v` (0: isotropic).
fn anisotropic(m: &Material) -> bool {
    match m.kind {
        BSDF_ROUGH_CONDUCTOR | BSDF_ROUGH_DIELECTRIC | BSDF_PPLASTIC => {
            m.alpha_u != m.alpha_v || m.alpha_u_texture != m.alpha_v_texture
        }
        BSDF_PRINCIPLED | BSDF_PRINCIPLED_THIN => m.alpha_v != 0.0 || m.alpha_v_texture != NONE,
        _ => false,
    }
}
