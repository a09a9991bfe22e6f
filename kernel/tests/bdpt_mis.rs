//! BDPT's and VCM's MIS weights on explicit random paths: for every path, the weights of the
//! strategies that can make it (the camera path hitting the emitter, next-event estimation, each
//! connection of a camera vertex to a light vertex, light tracing's connection to the camera and,
//! under VCM, each merge at a vertex) sum to one, each computed as `integrator::bdpt` computes it, by
//! walking the path with `bdpt_mis`'s recursion from the camera side and from the light side. Dirac
//! vertices anywhere between camera and emitter.
use caustic_kernel::glam::Vec3;
use caustic_kernel::integrator::bdpt_mis::{self, Connections, Merging, SubpathMis};
use caustic_kernel::rng::Sampler;
use std::f32::consts::PI;

/// A path `x0` (pinhole camera) … `xk` (emitter), with the normal at every vertex and which vertices
/// scatter by a Dirac lobe (probability `delta_prob` both ways).
struct TestPath {
    x: Vec<Vec3>,
    n: Vec<Vec3>,
    delta: Vec<bool>,
    delta_prob: f32,
    /// Area of the emitter at `xk` (uniform, pmf 1, cosine-weighted emission); `None`: a point light.
    emitter_area: Option<f32>,
    /// `We·cos/d²` of the camera connection to `x1` (film area at unit distance 1.5).
    importance: f32,
    /// For the negative control: the camera side's (`Some(true)`) or the light side's (`Some(false)`)
    /// recursion takes 1 for every reverse density.
    broken: Option<bool>,
    /// Vertex merging (`Merging::OFF`: BDPT).
    merging: Merging,
    /// How a camera vertex joins light vertices (`Connections::EVERY`, or one drawn).
    connections: Connections,
    /// For the negative control: merges are weighted as connections are, without `vm`.
    merges_unweighted: bool,
    /// For the negative control: light tracing's weight without the connections' `c²`.
    tracing_unscaled: bool,
}

fn random_unit(s: &mut Sampler) -> Vec3 {
    let u = s.next_2d();
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `deltas`: which interior vertices (1 ≤ i < k) scatter by a Dirac lobe, as a bit mask.
fn random_path(k: usize, seed: u32, deltas: u32, point_light: bool) -> TestPath {
    let mut s = Sampler::new(seed, k as u32, deltas * 2 + point_light as u32);
    let mut x = vec![Vec3::ZERO];
    for _ in 1..=k {
        let last = *x.last().unwrap();
        x.push(last + random_unit(&mut s) * (0.5 + 2.0 * s.next_1d()));
    }
    let mut n = vec![Vec3::Z];
    for i in 1..=k {
        let towards = if i < k {
            (x[i - 1] - x[i]).normalize() + (x[i + 1] - x[i]).normalize()
        } else {
            x[i - 1] - x[i]
        };
        n.push((towards.normalize() + random_unit(&mut s) * 0.3).normalize());
    }
    let delta = (0..=k).map(|i| i >= 1 && i < k && deltas & (1 << i) != 0).collect();
    let cos_c = (x[1] - x[0]).normalize().z.abs().max(0.2);
    let d2 = (x[1] - x[0]).length_squared();
    TestPath {
        x,
        n,
        delta,
        delta_prob: 0.7,
        emitter_area: if point_light { None } else { Some(0.05 + s.next_1d()) },
        importance: 1.0 / (1.5 * cos_c * cos_c * cos_c * d2),
        broken: None,
        merging: Merging::OFF,
        connections: Connections::EVERY,
        merges_unweighted: false,
        tracing_unscaled: false,
    }
}

impl TestPath {
    fn k(&self) -> usize {
        self.x.len() - 1
    }

    /// `|cos|` at vertex `i` towards vertex `j`.
    fn cos(&self, i: usize, j: usize) -> f32 {
        (self.x[j] - self.x[i]).normalize().dot(self.n[i]).abs()
    }

    fn dist_sq(&self, i: usize, j: usize) -> f32 {
        (self.x[j] - self.x[i]).length_squared()
    }

    /// Sampling density at `i` towards `j`: Lambert's, or a Dirac vertex's discrete probability.
    fn pdf(&self, i: usize, j: usize) -> f32 {
        if self.delta[i] {
            self.delta_prob
        } else {
            self.cos(i, j) / PI
        }
    }

    /// Next-event estimation's solid-angle density of the emitter point from `x(k-1)` (uniform area).
    fn light_pdf(&self) -> f32 {
        let k = self.k();
        self.dist_sq(k - 1, k) / (self.cos(k, k - 1) * self.emitter_area.unwrap())
    }

    /// `emission::hit_density`.
    fn hit_density(&self) -> f32 {
        self.emitter_area.map_or(0.0, |a| 1.0 / (a * PI))
    }

    /// `emission::nee_ratio` of the light sample at `xk` from `x(k-1)`.
    fn nee_ratio(&self) -> f32 {
        let k = self.k();
        match self.emitter_area {
            Some(_) => self.hit_density() / self.light_pdf(),
            None => 1.0 / (4.0 * PI * self.dist_sq(k - 1, k)),
        }
    }

    /// The camera path's state on arriving at each vertex `x1 … xk` (index = vertex).
    fn camera_states(&self) -> Vec<SubpathMis> {
        let k = self.k();
        let mut states = vec![SubpathMis::ZERO; k + 1];
        let mut m = SubpathMis::camera_first_vertex(self.importance * self.cos(1, 0), self.connections);
        states[1] = m;
        for j in 1..k {
            let rev = if self.broken == Some(true) { 1.0 } else { self.pdf(j, j - 1) };
            m = m.scatter(self.delta[j], self.pdf(j, j + 1), rev, self.cos(j, j + 1), self.merging);
            m = m.arrive(self.dist_sq(j, j + 1), self.cos(j + 1, j));
            states[j + 1] = m;
        }
        states
    }

    /// The light path's state on arriving at each vertex `x(k-1) … x1` (index = vertex).
    fn light_states(&self) -> Vec<SubpathMis> {
        let k = self.k();
        let mut states = vec![SubpathMis::ZERO; k + 1];
        let inv_hit_sq = if self.emitter_area.is_some() { 1.0 / self.hit_density().powi(2) } else { 0.0 };
        // As `trace_light_path`: no next-event estimation from a Dirac first vertex.
        let inv_nee_sq = if self.delta[k - 1] { 0.0 } else { 1.0 / self.nee_ratio().powi(2) };
        let mut m = SubpathMis::light_first_vertex(
            inv_nee_sq,
            inv_hit_sq,
            self.cos(k - 1, k),
            self.merging,
            self.connections,
        );
        states[k - 1] = m;
        for j in (2..k).rev() {
            let rev = if self.broken == Some(false) { 1.0 } else { self.pdf(j, j + 1) };
            m = m.scatter(self.delta[j], self.pdf(j, j - 1), rev, self.cos(j, j - 1), self.merging);
            m = m.arrive(self.dist_sq(j, j - 1), self.cos(j - 1, j));
            states[j - 1] = m;
        }
        states
    }

    /// Every strategy's weight: (name, weight), for those that can make the path.
    fn weights(&self) -> Vec<(String, f32)> {
        let k = self.k();
        let camera = self.camera_states();
        let light = self.light_states();
        let mut w = Vec::new();
        if self.emitter_area.is_some() {
            let direct_area = if self.delta[k - 1] {
                0.0
            } else {
                bdpt_mis::to_area(self.light_pdf(), self.dist_sq(k - 1, k), self.cos(k, k - 1))
            };
            let emission = self.hit_density() * self.cos(k, k - 1);
            w.push(("hit".into(), bdpt_mis::hit_weight(camera[k], direct_area, emission, self.connections)));
        }
        if !self.delta[k - 1] {
            let r_hit = if self.emitter_area.is_some() { self.pdf(k - 1, k) / self.light_pdf() } else { 0.0 };
            let rev = self.pdf(k - 1, k - 2);
            let nee = bdpt_mis::nee_weight(
                camera[k - 1],
                r_hit,
                self.nee_ratio(),
                self.cos(k - 1, k),
                rev,
                self.merging,
                self.connections,
            );
            w.push(("nee".into(), nee));
        }
        // Camera vertex x(t-1) connected to light vertex x(t).
        for t in 2..k {
            if self.delta[t - 1] || self.delta[t] {
                continue;
            }
            let d2 = self.dist_sq(t - 1, t);
            let light_side = light[t].others(
                bdpt_mis::to_area(self.pdf(t - 1, t), d2, self.cos(t, t - 1)),
                self.pdf(t, t + 1),
                self.merging,
            );
            let camera_side = camera[t - 1].others(
                bdpt_mis::to_area(self.pdf(t, t - 1), d2, self.cos(t - 1, t)),
                self.pdf(t - 1, t - 2),
                self.merging,
            );
            w.push((format!("connect x{} x{t}", t - 1), bdpt_mis::weight(light_side, camera_side)));
        }
        if !self.delta[1] {
            let a = self.importance * self.cos(1, 0);
            // Not a connection: the others' terms times c² (`bdpt_mis`).
            let c_sq = if self.tracing_unscaled { 1.0 } else { self.connections.sq };
            let others = c_sq * light[1].others(a, self.pdf(1, 2), self.merging);
            w.push(("light tracing".into(), bdpt_mis::weight(others, 0.0)));
        }
        // Under VCM, the camera path merged at x_t with a light vertex there (t ≥ 1, the light path
        // at least one segment long), where x_t scatters by no Dirac lobe.
        if self.merging.eta_sq > 0.0 {
            for t in 1..k {
                if self.delta[t] {
                    continue;
                }
                let (fwd, rev) = (self.pdf(t, t + 1), if t == 1 { 0.0 } else { self.pdf(t, t - 1) });
                let weight = if self.merges_unweighted {
                    bdpt_mis::weight(light[t].vcm, camera[t].vcm)
                } else {
                    bdpt_mis::merge_weight(light[t], camera[t], fwd, rev, self.merging)
                };
                w.push((format!("merge x{t}"), weight));
            }
        }
        w
    }
}

#[test]
fn strategy_weights_sum_to_one_on_random_paths() {
    // BDPT, then VCM with merges a hundredth of, as likely as, and a hundred times as likely as a
    // connection at a typical vertex (`eta`: π r² L).
    for (radius, light_paths) in [(0.0, 1.0), (0.01, 30.0), (0.1, 30.0), (1.0, 30.0)] {
        let merging = Merging::new(radius, light_paths, Connections::EVERY);
        let mut checked = 0;
        for k in 2..=9 {
            // No Dirac vertex; every other interior vertex; random subsets (x1 and x(k-1) included).
            let masks: Vec<u32> =
                vec![0, 0b1010_1010_1010 & ((1 << k) - 2), 0b10, 1 << (k - 1), 0b1_0110_1100];
            for (m, &deltas) in masks.iter().enumerate() {
                let deltas = deltas & ((1 << k) - 2);
                for point_light in [false, true] {
                    for seed in 0..100 {
                        let mut path = random_path(k, seed * 8 + m as u32, deltas, point_light);
                        path.merging = merging;
                        let weights = path.weights();
                        if weights.is_empty() {
                            // (A point light seen through a Dirac vertex: no strategy makes the path.)
                            continue;
                        }
                        let sum: f32 = weights.iter().map(|w| w.1).sum();
                        assert!(
                            (sum - 1.0).abs() < 1e-4,
                            "r={radius} k={k} deltas={deltas:b} point={point_light} seed={seed}: {weights:?} sum to {sum}"
                        );
                        // Every strategy that can make the path takes part.
                        assert!(weights.iter().all(|w| w.1 > 0.0), "k={k} seed={seed}: {weights:?}");
                        checked += 1;
                    }
                }
            }
        }
        println!("radius {radius}: {checked} paths: weights sum to one");
    }
}

/// The test above can fail: either side's recursion without its reverse densities (a plausible
/// slip) breaks the sum.
#[test]
fn a_wrong_recursion_breaks_the_sum() {
    let mut path = random_path(5, 3, 0, false);
    let sum = |p: &TestPath| p.weights().iter().map(|w| w.1).sum::<f32>();
    assert!((sum(&path) - 1.0).abs() < 1e-4);
    for side in [true, false] {
        path.broken = Some(side);
        let s = sum(&path);
        println!("reverse densities left out on the {} side: sum {s}", if side { "camera" } else { "light" });
        assert!((s - 1.0).abs() > 1e-3, "a recursion without reverse densities went unnoticed");
    }
    // Merges weighted without the recursion's `vm` term (as if merging were one more connection).
    let mut path = random_path(5, 3, 0, false);
    path.merging = Merging::new(0.1, 30.0, Connections::EVERY);
    assert!((sum(&path) - 1.0).abs() < 1e-4);
    path.merges_unweighted = true;
    let s = sum(&path);
    println!("merges weighted without vm: sum {s}");
    assert!((s - 1.0).abs() > 1e-3, "merges weighted without their term went unnoticed");
    // One light vertex drawn (c = 0.3), light tracing weighted as if every vertex were joined.
    let mut path = random_path(5, 3, 0, false);
    path.connections = Connections::new(0.3);
    assert!((sum(&path) - 1.0).abs() < 1e-4);
    path.tracing_unscaled = true;
    let s = sum(&path);
    println!("light tracing without c²: sum {s}");
    assert!((s - 1.0).abs() > 1e-3, "light tracing's weight without the connections' share went unnoticed");
}

/// A camera vertex joining one light vertex drawn at random (`Connections`, share `c`) is MIS with
/// counts: each connection strategy counts `c`, every other one 1 (a merge `eta`). So on every random
/// path each strategy's weight is its weight when every vertex is joined, times its count squared,
/// renormalised: `w_i(c) = n_i² w_i(1) / Σ_j n_j² w_j(1)` (which also makes them sum to one).
#[test]
fn one_drawn_light_vertex_weighs_connections_by_their_share() {
    let mut checked = 0;
    for c in [0.5f32, 0.1] {
        for (radius, light_paths) in [(0.0, 1.0), (0.1, 30.0)] {
            for k in 2..=7 {
                for deltas in [0, 0b1010_1010 & ((1 << k) - 2), 0b10 & ((1 << k) - 2)] {
                    for point_light in [false, true] {
                        for seed in 0..40 {
                            let mut path = random_path(k, seed, deltas, point_light);
                            path.merging = Merging::new(radius, light_paths, Connections::EVERY);
                            let every = path.weights();
                            path.connections = Connections::new(c);
                            path.merging = Merging::new(radius, light_paths, path.connections);
                            let drawn = path.weights();
                            let n_sq = |name: &str| if name.starts_with("connect") { c * c } else { 1.0 };
                            let total: f32 = every.iter().map(|(name, w)| n_sq(name) * w).sum();
                            for ((name, w1), (other, wc)) in every.iter().zip(&drawn) {
                                assert_eq!(name, other);
                                let expected = n_sq(name) * w1 / total;
                                assert!(
                                    (wc - expected).abs() < 1e-4,
                                    "c={c} r={radius} k={k} deltas={deltas:b} seed={seed} {name}: {wc} against {expected}"
                                );
                            }
                            checked += every.len();
                        }
                    }
                }
            }
        }
    }
    println!("{checked} strategies' weights checked");
}

/// What one light path takes in the light vertex cache (`bdpt::LightVertex`, `MAX_LIGHT_VERTICES`
/// slots a path): 208 bytes a vertex, a multiple of 16, of 4-byte members, which Rust and the GPU
/// lay out alike.
#[test]
fn a_light_path_takes_1664_bytes_of_the_cache() {
    use caustic_kernel::integrator::bdpt::{LightVertex, MAX_LIGHT_VERTICES};
    assert_eq!(std::mem::size_of::<LightVertex>(), 208);
    assert_eq!(std::mem::align_of::<LightVertex>(), 4);
    assert_eq!(std::mem::size_of::<LightVertex>() * MAX_LIGHT_VERTICES as usize, 1664);
}

/// A path of one segment, the camera seeing an emitter: its two strategies are the camera path
/// hitting the point and the light path's emitter point connected to the camera. `integrator::bdpt`
/// weighs the first with `bdpt_mis::seen_weight` at the camera's first vertex (light tracing's
/// density of the point, `E·|cos|`, against the camera's `a = x·|cos|`), the second as `ibpt` does
/// (`mis::emitter_connection_weight`, `x` the splat's importance), both tempered by the pass's light
/// paths (`mis::seen_ratio_sq`): they sum to one, at any distance, angle and image size, and the hit
/// alone would count the path twice.
#[test]
fn the_emitter_point_and_the_camera_hit_sum_to_one() {
    use caustic_kernel::integrator::mis;
    let mut s = Sampler::new(7, 0, 0);
    let mut shared = 0;
    for _ in 0..10_000 {
        let u = s.next_2d();
        let v = s.next_2d();
        let x = 10f32.powf(6.0 * u.x - 3.0);
        let e = 10f32.powf(6.0 * u.y - 3.0);
        let cos = v.x.max(1e-4);
        let light_paths = 10f32.powf(1.0 + 6.0 * v.y);
        // Neither is a connection: joining one light vertex drawn at random changes neither weight.
        for c in [Connections::EVERY, Connections::new(0.2)] {
            let hit =
                bdpt_mis::seen_weight(SubpathMis::camera_first_vertex(x * cos, c), e * cos, light_paths, c);
            let splat = mis::emitter_connection_weight(x, 1.0 / (e * e), light_paths);
            assert!(
                (hit + splat - 1.0).abs() < 1e-5,
                "x {x} E {e} cos {cos} N {light_paths}: {hit} + {splat}"
            );
            shared += (hit > 0.01 && hit < 0.99) as u32;
        }
    }
    // Where the point is about as likely by light tracing as by the camera ray, both take part.
    assert!(shared > 1000, "{shared}");
}

/// The seen emitter's ratio (`mis::seen_ratio_sq`) at the densities measured in two shared scenes:
/// the sphere light filling much of `shape_sphere_light_analytic`'s 960×720 view (`r` = 0.6) goes to
/// the camera ray, which the plain power heuristic gave only 0.73; the Cornell box's light of about
/// 490 pixels at 256² (`r` = 13.5) stays with the splats, as the plain heuristic has it; a lamp whose
/// `r` is past `N / SEEN_HIT_GAIN` (a pixel or less) is weighed exactly as before; and the ratio
/// crosses 1 at `r = (N / SEEN_HIT_GAIN)^(1/3)`.
#[test]
fn a_seen_emitter_goes_to_the_camera_when_it_spans_many_pixels() {
    use caustic_kernel::integrator::mis::{self, SEEN_HIT_GAIN};
    let hit = |r: f32, n: f32| 1.0 / (1.0 + mis::seen_ratio_sq(r * r, n));
    let plain = |r: f32| 1.0 / (1.0 + r * r);
    let sphere = 960.0 * 720.0;
    assert!(plain(0.6) < 0.75 && hit(0.6, sphere) > 0.99, "{} {}", plain(0.6), hit(0.6, sphere));
    let cbox = 256.0 * 256.0;
    assert!(hit(13.5, cbox) < 0.02, "{}", hit(13.5, cbox));
    let lamp = 2.0 * cbox / SEEN_HIT_GAIN;
    assert_eq!(hit(lamp, cbox), plain(lamp));
    let crossing = (cbox / SEEN_HIT_GAIN).powf(1.0 / 3.0);
    assert!((hit(crossing, cbox) - 0.5).abs() < 1e-3, "{}", hit(crossing, cbox));
    assert!(plain(crossing) < 0.1, "the negative control: {}", plain(crossing));
}
