//! IBPT's MIS weights on explicit random paths: for every path, the weights of the strategies that can
//! make it (camera path hitting the emitter, next-event estimation, light path connected to the camera)
//! sum to one, computed by walking the path with the kernel's own recursions (`integrator::mis`) from
//! the camera side and from the light side, as the integrators do.
use caustic_kernel::glam::Vec3;
use caustic_kernel::integrator::mis;
use caustic_kernel::rng::Sampler;
use std::f32::consts::PI;

/// A path `x0` (pinhole camera) … `xk` (emitter), with the normal at every vertex and which vertices
/// scatter by a Dirac lobe (probability `delta_prob` both ways).
struct TestPath {
    x: Vec<Vec3>,
    n: Vec<Vec3>,
    delta: Vec<bool>,
    delta_prob: f32,
    /// Area of the triangle emitter at `xk`; `None`: a point light there.
    emitter_area: Option<f32>,
    /// `We·cos/d²` of the camera connection to `x1` (film area at unit distance 1.5).
    importance: f32,
}

fn random_unit(s: &mut Sampler) -> Vec3 {
    let u = s.next_2d();
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

fn random_path(k: usize, seed: u32, with_delta: bool, point_light: bool) -> TestPath {
    let mut s = Sampler::new(seed, k as u32, with_delta as u32 + 2 * point_light as u32);
    let mut x = vec![Vec3::ZERO];
    for _ in 1..=k {
        let last = *x.last().unwrap();
        x.push(last + random_unit(&mut s) * (0.5 + 2.0 * s.next_1d()));
    }
    // Normals facing both neighbours' average direction, tilted at random (cosines stay non-zero).
    let mut n = vec![Vec3::Z];
    for i in 1..=k {
        let towards = if i < k {
            (x[i - 1] - x[i]).normalize() + (x[i + 1] - x[i]).normalize()
        } else {
            x[i - 1] - x[i]
        };
        n.push((towards.normalize() + random_unit(&mut s) * 0.3).normalize());
    }
    // Dirac vertices only strictly inside the path, never at x1 or x(k-1), where strategies connect.
    let delta = (0..=k).map(|i| with_delta && i >= 2 && i + 2 <= k && i % 2 == 0).collect();
    let cos_c = (x[1] - x[0]).normalize().z.abs().max(0.2);
    let d2 = (x[1] - x[0]).length_squared();
    TestPath {
        x,
        n,
        delta,
        delta_prob: 0.7,
        emitter_area: if point_light { None } else { Some(0.05 + s.next_1d()) },
        importance: 1.0 / (1.5 * cos_c * cos_c * cos_c * d2),
    }
}

impl TestPath {
    fn k(&self) -> usize {
        self.x.len() - 1
    }

    /// Cosine-weighted (Lambert) solid-angle density at vertex `i` of the direction towards vertex `j`.
    fn lambert(&self, i: usize, j: usize) -> f32 {
        (self.x[j] - self.x[i]).normalize().dot(self.n[i]).abs() / PI
    }

    /// Sampling density at `i` towards `j` (a Dirac vertex: its discrete probability).
    fn pdf(&self, i: usize, j: usize) -> f32 {
        if self.delta[i] {
            self.delta_prob
        } else {
            self.lambert(i, j)
        }
    }

    /// Next-event estimation's solid-angle density of the emitter point from `x(k-1)` (uniform area).
    fn light_pdf(&self) -> f32 {
        let k = self.k();
        let d = self.x[k] - self.x[k - 1];
        let cos = d.normalize().dot(self.n[k]).abs();
        d.length_squared() / (cos * self.emitter_area.unwrap())
    }

    /// `emission::hit_density`: pmf 1, uniform area, cosine-weighted directions.
    fn hit_density(&self) -> f32 {
        self.emitter_area.map_or(0.0, |a| 1.0 / (a * PI))
    }

    /// `emission::nee_ratio` of the light sample at `xk` from `x(k-1)`.
    fn nee_ratio(&self) -> f32 {
        let k = self.k();
        match self.emitter_area {
            Some(_) => self.hit_density() / self.light_pdf(),
            None => 1.0 / (4.0 * PI * (self.x[k] - self.x[k - 1]).length_squared()),
        }
    }

    /// The three weights, from the camera side (hit, NEE) and the light side (connection at x1), of a
    /// path of two segments or more (one segment: `the_seen_emitter_s_two_weights_sum_to_one`).
    fn weights(&self) -> (f32, f32, f32) {
        let k = self.k();
        assert!(k >= 2);
        // Camera side: the scalar s at each vertex, updated when leaving it.
        let mut s = mis::camera_scale_at_first_vertex(self.importance, 1.0);
        let mut s_at = vec![0.0; k + 1];
        s_at[1] = s;
        for t in 1..k {
            let first = t == 1;
            let rev = if self.delta[t] { self.delta_prob } else { self.lambert(t, t - 1) };
            s = mis::camera_scale_after(s, first, self.delta[t], self.pdf(t, t + 1), rev);
            s_at[t + 1] = s;
        }
        let w_hit = if self.emitter_area.is_some() {
            let r_nee = if self.delta[k - 1] { 0.0 } else { self.light_pdf() / self.pdf(k - 1, k) };
            mis::hit_weight(r_nee, s_at[k], self.hit_density())
        } else {
            0.0
        };
        let w_nee = if self.delta[k - 1] {
            0.0
        } else {
            let r_hit = if self.emitter_area.is_some() { self.pdf(k - 1, k) / self.light_pdf() } else { 0.0 };
            mis::nee_weight(r_hit, s_at[k - 1], k - 1 == 1, self.lambert(k - 1, k - 2), self.nee_ratio())
        };
        // Light side: the light path x(k), x(k-1), …, x1; its first vertex is x(k-1).
        let inv_hit_sq =
            if self.emitter_area.is_some() { 1.0 / (self.hit_density() * self.hit_density()) } else { 0.0 };
        let inv_nee_sq = if self.delta[k - 1] { 0.0 } else { 1.0 / (self.nee_ratio() * self.nee_ratio()) };
        let mut d = 0.0;
        for m in (2..k).rev() {
            // Leaving x(m) towards x(m-1): light tracing's density there, the camera path's reverse.
            let (fwd, rho) = if self.delta[m] {
                (self.delta_prob, 1.0)
            } else {
                (self.lambert(m, m - 1), self.lambert(m, m + 1))
            };
            d = mis::light_scalar_after(d, m == k - 1, self.delta[m], inv_hit_sq, inv_nee_sq, rho, fwd);
        }
        let rho1 = self.lambert(1, 2.min(k));
        let w_lt = if k == 2 {
            mis::first_vertex_connection_weight(self.importance, rho1, inv_hit_sq, inv_nee_sq)
        } else {
            mis::connection_weight(self.importance, rho1, d)
        };
        (w_hit, w_nee, w_lt)
    }
}

#[test]
fn strategy_weights_sum_to_one_on_random_paths() {
    let mut checked = 0;
    for k in 2..=7 {
        for with_delta in [false, true] {
            for point_light in [false, true] {
                for seed in 0..200 {
                    let path = random_path(k, seed, with_delta, point_light);
                    let (h, n, l) = path.weights();
                    let sum = h + n + l;
                    assert!(
                        (sum - 1.0).abs() < 1e-4,
                        "k={k} delta={with_delta} point={point_light} seed={seed}: hit {h} + nee {n} + lt {l} = {sum}"
                    );
                    // Every strategy that can make the path takes part.
                    assert!(l > 0.0 && n > 0.0 && (point_light || h > 0.0), "k={k} seed={seed}: {h} {n} {l}");
                    checked += 1;
                }
            }
        }
    }
    println!("{checked} paths: weights sum to one");
}

/// The test above can fail: dropping the reverse density at one vertex (a plausible slip in the
/// recursion) breaks the sum.
#[test]
fn a_wrong_recursion_breaks_the_sum() {
    let path = random_path(4, 3, false, false);
    let (h, n, l) = path.weights();
    assert!((h + n + l - 1.0).abs() < 1e-4);
    let wrong = mis::camera_scale_after(1.0, false, false, 0.3, 1.0)
        != mis::camera_scale_after(1.0, false, false, 0.3, 0.5);
    assert!(wrong, "the reverse density must matter");
    // Recompute the light side without the first-vertex special case: the sum must move.
    let k = path.k();
    let inv_hit_sq = 1.0 / (path.hit_density() * path.hit_density());
    let mut d = 0.0;
    for m in (2..k).rev() {
        d = mis::light_scalar_after(
            d,
            false,
            false,
            inv_hit_sq,
            0.0,
            path.lambert(m, m + 1),
            path.lambert(m, m - 1),
        );
    }
    let l_wrong = mis::connection_weight(path.importance, path.lambert(1, 2), d);
    assert!(
        (h + n + l_wrong - 1.0).abs() > 1e-3,
        "a broken light recursion went unnoticed: {}",
        h + n + l_wrong
    );
}

/// A path of one segment, the camera seeing the emitter: the camera hit (`mis::hit_weight` with the
/// first vertex's scalar tempered by `mis::seen_scale`, no light sampling from the camera) and the
/// emitter point's splat (`mis::emitter_connection_weight`) sum to one at any importance, emitter
/// density and image size; without the tempering on one side they do not.
#[test]
fn the_seen_emitter_s_two_weights_sum_to_one() {
    let mut s = Sampler::new(11, 0, 0);
    let mut broken = 0;
    for _ in 0..10_000 {
        let u = s.next_2d();
        let importance = 10f32.powf(6.0 * u.x - 3.0);
        let e = 10f32.powf(6.0 * u.y - 3.0);
        let light_paths = 10f32.powf(1.0 + 6.0 * s.next_1d());
        let scale = mis::camera_scale_at_first_vertex(importance, 1.0);
        let hit = mis::hit_weight(0.0, mis::seen_scale(scale, e, light_paths), e);
        let splat = mis::emitter_connection_weight(importance, 1.0 / (e * e), light_paths);
        assert!((hit + splat - 1.0).abs() < 1e-5, "x {importance} E {e} N {light_paths}: {hit} + {splat}");
        let untempered = mis::hit_weight(0.0, scale, e);
        broken += ((untempered + splat - 1.0).abs() > 1e-3) as u32;
    }
    assert!(broken > 1000, "{broken}");
}
