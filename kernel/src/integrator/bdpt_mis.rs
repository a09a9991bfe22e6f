//! Bidirectional path tracing's and vertex connection and merging's multiple-importance arithmetic:
//! the recursion of Georgiev et al. 2012 ("Implementing Vertex Connection and Merging"), with the
//! power heuristic. Every quantity is kept squared (the heuristic's exponent 2), as pure functions of
//! densities so that the camera half and the light half use one definition each and a test can walk
//! explicit paths through both (`kernel/tests/bdpt_mis.rs`: every path's weights sum to one over the
//! strategies that can make it, merges included).
//!
//! A sub-path carries three scalars at its current vertex `v` (`SubpathMis`):
//! - `vcm`: the density ratio, squared, of the strategy whose *other* sub-path reaches `v` (the other
//!   side samples `v` by connecting to, or hitting, the vertex before it) to the strategy that made
//!   `v` here, without `v`'s own reverse density;
//! - `vc`: the sum of those ratios, squared, for the strategies whose other sub-path reaches further
//!   along this one (connections, and merges at the vertices before `v`), without the reverse density
//!   at `v`;
//! - `vm`: the same sum relative to merging at `v` instead of connecting there.
//!
//! Merging enters through one factor (`Merging`): `eta = π r² · L`, the ratio of a merge's density to
//! a connection's at the same vertex, with `r` the merging radius and `L` the light paths a camera
//! vertex merges with per camera sample. BDPT is the case `eta = 0` (`Merging::OFF`): no merge, and
//! `vm` unused.
//!
//! A camera vertex may join one vertex of its light path drawn at random instead of every one
//! (`Connections`): the connection strategies (a camera vertex joined to a light vertex past the
//! emitter) then count `c` against the other strategies' 1 (hitting the emitter, next-event
//! estimation, light tracing's connection to the camera). The state is kept in connections' units:
//! the terms that stand for the other strategies are divided by `c²` where they enter (at each
//! sub-path's first vertex), merges count `eta / c`, and a weight whose own strategy is not a
//! connection multiplies the others' terms by `c²`. `c = 1` is the recursion above.
//!
//! Densities are in solid angle at the vertex they leave; the cosines that turn them into area
//! densities are taken with the geometric normal, on both sides alike.
//!
//! Conventions of caustic's camera (`mis::camera_scale_at_first_vertex`): the camera strategy's density
//! of a first vertex `x`, relative to light tracing's paths per camera sample, is `importance ·
//! pixel density · film scale · |cos θx|` (`Camera::connect_through`'s importance), written `a` here.

use crate::layout::{FrameParams, INTEGRATOR_VCM};
use crate::math::is_finite;

/// How a camera vertex joins its light path's vertices: every one (`EVERY`), or one drawn uniformly
/// with the connection strategies counting `c` in the weights (`sq` = c², `inv_sq` = 1/c²).
#[derive(Clone, Copy)]
pub struct Connections {
    pub sq: f32,
    pub inv_sq: f32,
}

impl Connections {
    pub const EVERY: Connections = Connections { sq: 1.0, inv_sq: 1.0 };

    /// The connections of `FrameParams::connection_share` `share` (0, or not a positive finite
    /// number: `EVERY`).
    #[inline]
    pub fn new(share: f32) -> Self {
        let sq = share * share;
        if !(sq > 0.0) || !is_finite(1.0 / sq) || !is_finite(sq) {
            return Connections::EVERY;
        }
        Connections { sq, inv_sq: 1.0 / sq }
    }

    /// A pass's connections: `connection_share`, and as often as camera vertices join their light
    /// paths (`bdpt::connection_rate`; every vertex joined counts 1).
    #[inline]
    pub fn of(params: &FrameParams) -> Self {
        let rate = super::bdpt::connection_rate(params);
        let c = params.connection_share;
        Connections::new(if c > 0.0 { c * rate } else { rate })
    }
}

/// Vertex merging's weight factor in connections' units (`eta / c`), squared, and its inverse, and
/// the merge estimator's `1 / eta` (all 0 without merging).
#[derive(Clone, Copy)]
pub struct Merging {
    pub eta_sq: f32,
    pub inv_eta_sq: f32,
    pub inv_eta: f32,
}

impl Merging {
    pub const OFF: Merging = Merging { eta_sq: 0.0, inv_eta_sq: 0.0, inv_eta: 0.0 };

    /// Merging within `radius` among the vertices of `light_paths` light paths per camera sample,
    /// beside `connections`.
    #[inline]
    pub fn new(radius: f32, light_paths: f32, connections: Connections) -> Self {
        let eta = core::f32::consts::PI * radius * radius * light_paths;
        let eta_sq = eta * eta * connections.inv_sq;
        if !(eta > 0.0) || !is_finite(eta_sq) || !(eta_sq > 0.0) {
            return Merging::OFF;
        }
        Merging { eta_sq, inv_eta_sq: 1.0 / eta_sq, inv_eta: 1.0 / eta }
    }

    /// A pass's merging: under `INTEGRATOR_VCM`, each camera sample merges with the vertices of the
    /// pass's light paths, one per pixel of the window.
    #[inline]
    pub fn of(params: &FrameParams) -> Self {
        if params.integrator != INTEGRATOR_VCM {
            return Merging::OFF;
        }
        Merging::new(params.merge_radius, super::ptracer::light_paths(params), Connections::of(params))
    }
}

/// A sub-path's recursive MIS state at its current vertex (every term squared).
#[derive(Clone, Copy)]
pub struct SubpathMis {
    pub vcm: f32,
    pub vc: f32,
    pub vm: f32,
}

impl SubpathMis {
    pub const ZERO: SubpathMis = SubpathMis { vcm: 0.0, vc: 0.0, vm: 0.0 };

    /// The camera path's first vertex: light tracing reaches it by connecting it to the camera (`a`
    /// as above; 0 where it cannot: outside the film, an orthographic camera).
    #[inline]
    pub fn camera_first_vertex(a: f32, c: Connections) -> Self {
        SubpathMis { vcm: if a > 0.0 { c.inv_sq / (a * a) } else { 0.0 }, vc: 0.0, vm: 0.0 }
    }

    /// The light path's first vertex, met at `|cos|` `cos_in`: next-event estimation from it could have
    /// sampled the emitter point (`inv_nee_sq`: `1/er²` of `emission::nee_ratio` for that light sample,
    /// 0 for an emitter it cannot sample), and a camera path leaving it could have hit that point
    /// (`inv_hit_sq`: `1/E²` of `emission::hit_density`, 0 for point, spot and projector lights).
    #[inline]
    pub fn light_first_vertex(
        inv_nee_sq: f32,
        inv_hit_sq: f32,
        cos_in: f32,
        m: Merging,
        c: Connections,
    ) -> Self {
        let c2 = cos_in * cos_in;
        if !(c2 > 0.0) {
            return SubpathMis::ZERO;
        }
        let vc = c.inv_sq * inv_hit_sq / c2;
        SubpathMis { vcm: c.inv_sq * inv_nee_sq / c2, vc, vm: vc * m.inv_eta_sq }
    }

    /// Arriving at the next vertex along a segment of squared length `dist_sq`, which meets the
    /// surface at `|cos|` `cos_in`.
    #[inline]
    pub fn arrive(self, dist_sq: f32, cos_in: f32) -> Self {
        let c2 = cos_in * cos_in;
        if !(c2 > 0.0) {
            return SubpathMis::ZERO;
        }
        let g = dist_sq / cos_in;
        SubpathMis { vcm: self.vcm * g * g, vc: self.vc / c2, vm: self.vm / c2 }
    }

    /// Leaving a vertex by a direction of solid-angle density `fwd` at `|cos|` `cos_out`; `rev` is the
    /// other side's density of sampling the way back from here. A Dirac lobe has the same probability
    /// both ways: the ratios pass through it, and no strategy connects or merges at it.
    #[inline]
    pub fn scatter(self, delta: bool, fwd: f32, rev: f32, cos_out: f32, m: Merging) -> Self {
        let c2 = cos_out * cos_out;
        if delta {
            return SubpathMis { vcm: 0.0, vc: self.vc * c2, vm: self.vm * c2 };
        }
        if !(fwd > 0.0) {
            return SubpathMis::ZERO;
        }
        let g2 = c2 / (fwd * fwd);
        let r2 = rev * rev;
        SubpathMis {
            vcm: 1.0 / (fwd * fwd),
            vc: g2 * (self.vc * r2 + self.vcm + m.eta_sq),
            vm: g2 * (self.vm * r2 + self.vcm * m.inv_eta_sq + 1.0),
        }
    }

    /// The sum of the other strategies' ratios, squared, where the other side samples this vertex with
    /// area density `other_area` and would leave it back along this sub-path with density `rev`
    /// (merging at this vertex among them).
    #[inline]
    pub fn others(self, other_area: f32, rev: f32, m: Merging) -> f32 {
        other_area * other_area * (m.eta_sq + self.vcm + self.vc * rev * rev)
    }

    /// The other strategies' ratios, squared, relative to merging at this vertex, where the other side
    /// would leave it with density `other` (onwards along this sub-path for the light side's term:
    /// the camera's BSDF towards where the light came from; back along the other sub-path for the
    /// camera side's).
    #[inline]
    pub fn merge_others(self, other: f32, m: Merging) -> f32 {
        self.vcm * m.inv_eta_sq + self.vm * other * other
    }
}

/// The power heuristic's weight from the squared ratios of the other strategies on either side.
#[inline]
pub fn weight(light_side: f32, camera_side: f32) -> f32 {
    let w = 1.0 / (1.0 + light_side + camera_side);
    if is_finite(w) {
        w
    } else {
        0.0
    }
}

/// A solid-angle density at a vertex turned into the area density at a point `dist_sq` away, met at
/// `|cos|` `cos_at`.
#[inline]
pub fn to_area(pdf_w: f32, dist_sq: f32, cos_at: f32) -> f32 {
    if dist_sq > 0.0 {
        pdf_w * cos_at / dist_sq
    } else {
        0.0
    }
}

/// The camera path hits an emitter (not at its first vertex): `direct_area` is next-event estimation's
/// density of that point from the previous vertex, in area, `emission` light tracing's density of
/// starting there and leaving towards the previous vertex (`hit_density · |cos|`; 0 for emitters
/// that start no light path); `camera` the camera path's state at the hit.
#[inline]
pub fn hit_weight(camera: SubpathMis, direct_area: f32, emission: f32, c: Connections) -> f32 {
    weight(0.0, direct_area * direct_area * camera.vcm + c.sq * emission * emission * camera.vc)
}

/// The camera sees an emitter at its first vertex (state `camera`): the other strategy is the light
/// path's emitter point connected to the camera, `point` light tracing's density of that point
/// (`hit_density · |cos|`; 0 where light paths do not connect it), weighed as `ibpt` weighs it
/// (`mis::seen_ratio_sq`, with the pass's `light_paths`).
#[inline]
pub fn seen_weight(camera: SubpathMis, point: f32, light_paths: f32, c: Connections) -> f32 {
    weight(0.0, super::mis::seen_ratio_sq(c.sq * point * point * camera.vcm, light_paths))
}

/// Next-event estimation from a camera vertex: `r_hit` BSDF sampling's density over the light
/// sample's (0 for delta lights), `nee_ratio` the light sample's `emission::nee_ratio`, `cos` the
/// cosine at the vertex towards the light, `rev` light tracing's density of leaving the vertex back
/// along the camera path.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn nee_weight(
    camera: SubpathMis,
    r_hit: f32,
    nee_ratio: f32,
    cos: f32,
    rev: f32,
    m: Merging,
    c: Connections,
) -> f32 {
    weight(r_hit * r_hit, c.sq * camera.others(nee_ratio * cos, rev, m))
}

/// A camera vertex (state `camera`) merged with a light vertex (state `light`) within the radius:
/// `fwd` the camera's BSDF density of leaving towards where the light came from, `rev` its density
/// of the reverse, the light side leaving back along the camera path.
#[inline]
pub fn merge_weight(light: SubpathMis, camera: SubpathMis, fwd: f32, rev: f32, m: Merging) -> f32 {
    weight(light.merge_others(fwd, m), camera.merge_others(rev, m))
}
