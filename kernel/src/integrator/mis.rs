//! IBPT's multiple-importance arithmetic (`docs/ibpt.md`), as pure functions of densities so that the
//! camera half (`path`, `nee`) and the light half (`ptracer`) use one definition each and a test can
//! walk explicit paths through both (`kernel/tests/ibpt_mis.rs`: the three weights sum to one).
//!
//! Camera path: one scalar `s`, the light-tracing density of the path so far over its camera-tracing
//! density, without the current vertex's reverse term. Light path: one scalar `d`, the sum over the
//! camera strategies of their squared density ratios to light tracing, without the current vertex's
//! camera-side density and the camera connection's importance.

/// The power heuristic's weight of a strategy from the other strategies' density ratios to its own.
#[inline]
pub fn weight_from_ratios(r1: f32, r2: f32) -> f32 {
    1.0 / (1.0 + r1 * r1 + r2 * r2)
}

/// Camera path, first vertex: light tracing reaches it by a connection carrying `importance`
/// (`We·cos/d²`) with `film_scale` (full film pixels over rendered ones); 0 if it cannot.
#[inline]
pub fn camera_scale_at_first_vertex(importance: f32, film_scale: f32) -> f32 {
    if importance > 0.0 {
        1.0 / (importance * film_scale)
    } else {
        0.0
    }
}

/// Camera path, leaving a vertex by a direction of density `fwd`; `rev` is light tracing's density of
/// sampling the way back (unused at the first vertex, which light tracing connects instead). A Dirac
/// lobe has the same probability both ways, except that at the first vertex it leaves light tracing
/// nothing to connect.
#[inline]
pub fn camera_scale_after(scale: f32, first_vertex: bool, delta: bool, fwd: f32, rev: f32) -> f32 {
    if delta {
        if first_vertex {
            0.0
        } else {
            scale
        }
    } else if first_vertex {
        scale / fwd
    } else {
        scale * rev / fwd
    }
}

/// Camera path hitting an emitter: `r_nee` (light sampling's density over BSDF sampling's, 0 after a
/// Dirac lobe), `scale` the camera scalar there and `hit_density` the emitter's `emission::hit_density`.
#[inline]
pub fn hit_weight(r_nee: f32, scale: f32, hit_density: f32) -> f32 {
    weight_from_ratios(r_nee, scale * hit_density)
}

/// Next-event estimation from a camera vertex: `r_hit` (BSDF sampling's density over the light
/// sample's, 0 for delta lights), the camera scalar, light tracing's reverse density at this vertex
/// (unused at the first vertex) and the light sample's `emission::nee_ratio`.
#[inline]
pub fn nee_weight(r_hit: f32, scale: f32, first_vertex: bool, rev: f32, nee_ratio: f32) -> f32 {
    let reverse = if first_vertex { 1.0 } else { rev };
    weight_from_ratios(r_hit, scale * reverse * nee_ratio)
}

/// Light path, the emitter point connected to the camera: `x = We·cos/d²·film_scale`,
/// `inv_hit_sq = 1/E²` (0 for point and spot lights).
#[inline]
pub fn emitter_connection_weight(x: f32, inv_hit_sq: f32) -> f32 {
    1.0 / (1.0 + x * x * inv_hit_sq)
}

/// Light path, its first vertex connected to the camera: `rho` the camera path's density of sampling
/// the direction to the emitter point from there, `inv_nee_sq = 1/e²` of next-event estimation from it
/// (0 if it has no smooth lobe).
#[inline]
pub fn first_vertex_connection_weight(x: f32, rho: f32, inv_hit_sq: f32, inv_nee_sq: f32) -> f32 {
    1.0 / (1.0 + x * x * (rho * rho * inv_hit_sq + inv_nee_sq))
}

/// Light path, a later vertex connected to the camera: `rho` the camera path's density of the
/// direction back along the light path, `d` the light scalar.
#[inline]
pub fn connection_weight(x: f32, rho: f32, d: f32) -> f32 {
    let y = x * rho;
    1.0 / (1.0 + y * y * d)
}

/// Light path, leaving a vertex by a direction of density `fwd` (light tracing's) whose reverse the
/// camera path samples with `rho`. At the first vertex `d` starts from the emitter terms (a Dirac lobe
/// there rules out next-event estimation from it); later a Dirac lobe leaves `d` unchanged.
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn light_scalar_after(
    d: f32,
    first_vertex: bool,
    delta: bool,
    inv_hit_sq: f32,
    inv_nee_sq: f32,
    rho: f32,
    fwd: f32,
) -> f32 {
    if delta {
        return if first_vertex { inv_hit_sq } else { d };
    }
    let ratio = rho / fwd;
    if first_vertex {
        inv_hit_sq * ratio * ratio + inv_nee_sq / (fwd * fwd)
    } else {
        d * ratio * ratio
    }
}
