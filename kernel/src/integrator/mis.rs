//! IBPT's multiple-importance arithmetic (`docs/ibpt.md`), as pure functions of densities so that the
//! camera half (`path`, `nee`) and the light half (`ptracer`) use one definition each and a test can
//! walk explicit paths through both (`kernel/tests/ibpt_mis.rs`: the three weights sum to one).
//!
//! Camera path: one scalar `s`, the light-tracing density of the path so far over its camera-tracing
//! density, without the current vertex's reverse term. Light path: one scalar `d`, the sum over the
//! camera strategies of their squared density ratios to light tracing, without the current vertex's
//! camera-side density and the camera connection's importance.

use crate::math::safe_sqrt;

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

/// The camera seeing an emitter, a path of one segment, has two strategies: the camera ray hitting
/// the point and light tracing's emitter point splatted to the camera. `r_sq` is light tracing's
/// density of the point over the camera's, squared (`r²`), as the power heuristic takes it; this is
/// the ratio both weights use instead, `r² · min(1, SEEN_HIT_GAIN · r / light_paths)`.
///
/// The heuristic reads a strategy's variance from its density, which holds for the splats (Poisson
/// over each pixel's footprint) but not for the hit: with the splatting film's control variate
/// (`film_splat::control_variate`) a camera ray that lands on an emitter spanning many pixels returns
/// its radiance without noise, except on the pixels its outline crosses. Over an emitter of `n`
/// pixels, with `N = light_paths` emitter points a pass, the splats leave a squared relative error of
/// about `n² / N` and the hit about `1.4 √n` (a coverage variance of 0.2 on `6.8 √n` outline pixels,
/// the Cornell box light's 151 for its 490). For a lambertian area light `r` is `N / (π² n)`
/// (measured: 13.5 for the Cornell box light at 256², 0.6 for the sphere light of
/// `shape_sphere_light_analytic` at 960×720), so the ratio of the two errors grows as `r^1.5 / √N`
/// and crosses 1 at `r = (N / SEEN_HIT_GAIN)^(1/3)`: 3.3 at 256², 7.2 at 960×720. The splats keep a
/// light of a few hundred pixels and any smaller lamp (`r` past the crossing, unchanged above
/// `N / SEEN_HIT_GAIN`), the hit takes a light filling much of the view. Any function of the path
/// that both sides evaluate alike keeps the two weights summing to one.
#[inline]
pub fn seen_ratio_sq(r_sq: f32, light_paths: f32) -> f32 {
    r_sq * (SEEN_HIT_GAIN * safe_sqrt(r_sq) / light_paths).min(1.0)
}

/// `seen_ratio_sq`'s constant: `1.36² · π⁶` (1.85 · 961.389), the two errors' ratio `k √n / (n² / N)`
/// at `n = N / (π² r)`, squared over `r³ / N`, for the hit's coefficient `k` = 1.36 (about 1.4 above).
pub const SEEN_HIT_GAIN: f32 = 1.85 * 961.389;

/// Light path, the emitter point connected to the camera: `x = We·cos/d²·film_scale`,
/// `inv_hit_sq = 1/E²` (0 for point and spot lights), against the camera ray seeing the point
/// (`seen_ratio_sq`, written here for the camera's density over light tracing's, `t = x²/E² = 1/r²`:
/// `t · max(1, light_paths · √t / SEEN_HIT_GAIN)`).
#[inline]
pub fn emitter_connection_weight(x: f32, inv_hit_sq: f32, light_paths: f32) -> f32 {
    let t = x * x * inv_hit_sq;
    1.0 / (1.0 + t * (light_paths * safe_sqrt(t) / SEEN_HIT_GAIN).max(1.0))
}

/// Camera path, an emitter seen at its first vertex under IBPT: the camera scalar there (`scale`,
/// light tracing's density over the camera's per unit of `hit_density`) tempered as
/// `seen_ratio_sq` says, for `hit_weight`.
#[inline]
pub fn seen_scale(scale: f32, hit_density: f32, light_paths: f32) -> f32 {
    scale * safe_sqrt((SEEN_HIT_GAIN * scale * hit_density / light_paths).min(1.0))
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
