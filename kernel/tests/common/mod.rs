//! Pearson's χ² goodness-of-fit test of a sampling routine against its density, on a (cos θ, φ) grid
//! of the sphere (in the spirit of Mitsuba's and pbrt's sampling tests).
#![allow(dead_code)]
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::rng::Sampler;
use statrs::distribution::{ChiSquared, ContinuousCDF};

pub const THETA_BINS: usize = 24;
pub const PHI_BINS: usize = 48;
pub const SAMPLES: usize = 400_000;
/// Significance of each test. (Several tests run; each fails by chance with this probability.)
pub const ALPHA: f64 = 1e-3;

fn bin_of(d: Vec3) -> usize {
    let ct = ((d.z.clamp(-1.0, 1.0) + 1.0) * 0.5 * THETA_BINS as f32) as usize;
    let mut phi = d.y.atan2(d.x);
    if phi < 0.0 {
        phi += 2.0 * std::f32::consts::PI;
    }
    let p = (phi / (2.0 * std::f32::consts::PI) * PHI_BINS as f32) as usize;
    ct.min(THETA_BINS - 1) * PHI_BINS + p.min(PHI_BINS - 1)
}

/// Adaptive Simpson quadrature of `f` over [a, b] (absolute tolerance `eps`, bounded depth).
fn adaptive_simpson(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, eps: f64) -> f64 {
    fn recurse(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, fa: f64, fm: f64, fb: f64, whole: f64, eps: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        if depth == 0 || (left + right - whole).abs() <= 15.0 * eps {
            return left + right + (left + right - whole) / 15.0;
        }
        recurse(f, a, m, fa, flm, fm, left, eps * 0.5, depth - 1) + recurse(f, m, b, fm, frm, fb, right, eps * 0.5, depth - 1)
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    recurse(f, a, b, fa, fm, fb, whole, eps, 12)
}

/// Expected probability of each bin: the solid-angle density integrated over the bin by nested
/// adaptive quadrature (in cos θ and φ), which resolves narrow lobes and the sharp rims of cones.
fn expected(pdf: &dyn Fn(Vec3) -> f64) -> Vec<f64> {
    let mut e = vec![0.0; THETA_BINS * PHI_BINS];
    let d_cos = 2.0 / THETA_BINS as f64;
    let d_phi = 2.0 * std::f64::consts::PI / PHI_BINS as f64;
    for i in 0..THETA_BINS {
        for j in 0..PHI_BINS {
            let (z0, p0) = (-1.0 + i as f64 * d_cos, j as f64 * d_phi);
            let mut over_z = |z: f64| {
                let r = (1.0 - z * z).max(0.0).sqrt();
                let mut over_phi = |phi: f64| pdf(Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32));
                adaptive_simpson(&mut over_phi, p0, p0 + d_phi, 1e-7)
            };
            e[i * PHI_BINS + j] = adaptive_simpson(&mut over_z, z0, z0 + d_cos, 1e-6);
        }
    }
    e
}

/// Runs the test. `sample` maps (u_lobe, u) to a direction or `None` (a rejected sample, expected
/// with the probability mass the pdf misses). Returns the p-value.
pub fn chi2_directions(name: &str, mut sample: impl FnMut(f32, Vec2) -> Option<Vec3>, pdf: impl Fn(Vec3) -> f64) -> f64 {
    let mut observed = vec![0.0f64; THETA_BINS * PHI_BINS + 1];
    let mut rng = Sampler::new(0x5eed, name.len() as u32, 0);
    for _ in 0..SAMPLES {
        let u_lobe = rng.next_1d();
        let u = rng.next_2d();
        match sample(u_lobe, u) {
            Some(d) => observed[bin_of(d)] += 1.0,
            None => observed[THETA_BINS * PHI_BINS] += 1.0,
        }
    }
    let mut exp = expected(&pdf);
    let mass: f64 = exp.iter().sum();
    assert!(mass < 1.0 + 1e-3, "{name}: the pdf integrates to {mass} > 1");
    exp.push((1.0 - mass).max(0.0));
    let p = chi2_p_value(&observed, &exp.iter().map(|e| e * SAMPLES as f64).collect::<Vec<_>>());
    println!("{name}: χ² p-value {p:.4}");
    if std::env::var_os("CHI2_DEBUG").is_some() {
        for t in 0..THETA_BINS {
            let o: f64 = (0..PHI_BINS).map(|k| observed[t * PHI_BINS + k]).sum();
            let e: f64 = (0..PHI_BINS).map(|k| exp[t * PHI_BINS + k] * SAMPLES as f64).sum();
            println!("  θ bin {t}: observed {o} expected {e:.1}");
        }
    }
    assert!(p > ALPHA, "{name}: samples do not follow the pdf (p = {p:.2e})");
    p
}

/// χ² test of observed counts against expected counts; bins expecting fewer than 5 are pooled.
pub fn chi2_p_value(observed: &[f64], expected: &[f64]) -> f64 {
    let mut order: Vec<usize> = (0..observed.len()).collect();
    order.sort_by(|&a, &b| expected[a].partial_cmp(&expected[b]).unwrap());
    let (mut chi2, mut dof) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    for &i in &order {
        if expected[i] < 5.0 {
            pool_o += observed[i];
            pool_e += expected[i];
            continue;
        }
        chi2 += (observed[i] - expected[i]).powi(2) / expected[i];
        dof += 1;
    }
    if pool_e > 0.0 {
        if pool_e >= 5.0 {
            chi2 += (pool_o - pool_e).powi(2) / pool_e;
            dof += 1;
        } else {
            // Too little expected mass to test the pooled bins: then they must be (nearly) empty.
            assert!(pool_o <= 5.0 + 3.0 * pool_e, "{pool_o} samples in bins expecting {pool_e}");
        }
    }
    let dist = ChiSquared::new((dof.max(2) - 1) as f64).unwrap();
    1.0 - dist.cdf(chi2)
}

/// A binning of the sphere for `chi2_grid`: bins in (cos α, φ) of a frame, with arbitrary edges in
/// cos α (ascending, from -1 to 1) so that narrow lobes can be resolved around their axis.
pub struct Grid {
    pub frame: caustic_kernel::frame::Frame,
    pub cos_edges: Vec<f64>,
    pub phi_bins: usize,
    /// Levels of subdivision the quadrature of each bin makes before it may stop: a lobe narrower than
    /// a bin is then not missed by the first few nodes.
    pub min_depth: u32,
    /// How far above 1 the integrated pdf may come (approximate shadowing terms are allowed a little).
    pub mass_tolerance: f64,
}

impl Grid {
    /// The whole sphere around +z, bins uniform in cos θ and φ (as `chi2_directions`).
    pub fn sphere() -> Grid {
        Grid::around(Vec3::Z, 1.0)
    }

    /// Bins around `axis` with `1 - cos α = 2 (k/K)^power`: `power` > 1 crowds them near the axis.
    pub fn around(axis: Vec3, power: f64) -> Grid {
        let mut cos_edges: Vec<f64> = (0..=THETA_BINS).map(|k| 1.0 - 2.0 * (k as f64 / THETA_BINS as f64).powf(power)).collect();
        cos_edges.reverse();
        cos_edges[0] = -1.0;
        cos_edges[THETA_BINS] = 1.0;
        Grid { frame: caustic_kernel::frame::Frame::from_normal(axis.normalize()), cos_edges, phi_bins: PHI_BINS, min_depth: 3, mass_tolerance: 1e-3 }
    }

    fn bins(&self) -> usize {
        (self.cos_edges.len() - 1) * self.phi_bins
    }

    fn bin_of(&self, d: Vec3) -> usize {
        let l = self.frame.to_local(d);
        let c = (l.z as f64).clamp(-1.0, 1.0);
        let t = self.cos_edges.partition_point(|&e| e <= c).clamp(1, self.cos_edges.len() - 1) - 1;
        let mut phi = (l.y as f64).atan2(l.x as f64);
        if phi < 0.0 {
            phi += 2.0 * std::f64::consts::PI;
        }
        let p = ((phi / (2.0 * std::f64::consts::PI)) * self.phi_bins as f64) as usize;
        t * self.phi_bins + p.min(self.phi_bins - 1)
    }
}

/// Adaptive Simpson quadrature that subdivides at least `min_depth` times before testing convergence.
fn simpson_min_depth(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, eps: f64, min_depth: u32) -> f64 {
    #[allow(clippy::too_many_arguments)]
    fn recurse(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, fa: f64, fm: f64, fb: f64, whole: f64, eps: f64, depth: u32, min_depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        if depth >= 14 || (depth >= min_depth && (left + right - whole).abs() <= 15.0 * eps) {
            return left + right + (left + right - whole) / 15.0;
        }
        recurse(f, a, m, fa, flm, fm, left, eps * 0.5, depth + 1, min_depth) + recurse(f, m, b, fm, frm, fb, right, eps * 0.5, depth + 1, min_depth)
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    recurse(f, a, b, fa, fm, fb, whole, eps, 0, min_depth)
}

/// Integral of `f` over each bin of `grid` (nested adaptive quadrature in cos α and φ).
pub fn integrate_grid(grid: &Grid, f: &dyn Fn(Vec3) -> f64) -> Vec<f64> {
    let mut out = vec![0.0; grid.bins()];
    let d_phi = 2.0 * std::f64::consts::PI / grid.phi_bins as f64;
    for t in 0..grid.cos_edges.len() - 1 {
        let (z0, z1) = (grid.cos_edges[t], grid.cos_edges[t + 1]);
        for j in 0..grid.phi_bins {
            let p0 = j as f64 * d_phi;
            let mut over_z = |z: f64| {
                let r = (1.0 - z * z).max(0.0).sqrt();
                let mut over_phi = |phi: f64| {
                    let local = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    f(grid.frame.to_world(local))
                };
                simpson_min_depth(&mut over_phi, p0, p0 + d_phi, 1e-8, grid.min_depth)
            };
            out[t * grid.phi_bins + j] = simpson_min_depth(&mut over_z, z0, z1, 1e-7, grid.min_depth);
        }
    }
    out
}

/// χ² test of `sample` against `pdf` on `grid` (see `chi2_directions`); `seed` varies the samples.
/// Returns the p-value.
pub fn chi2_grid(name: &str, grid: &Grid, seed: u32, mut sample: impl FnMut(f32, Vec2) -> Option<Vec3>, pdf: impl Fn(Vec3) -> f64) -> f64 {
    let n = grid.bins();
    let mut observed = vec![0.0f64; n + 1];
    let mut rng = Sampler::new(0xc41, seed, name.len() as u32);
    for _ in 0..SAMPLES {
        let u_lobe = rng.next_1d();
        let u = rng.next_2d();
        match sample(u_lobe, u) {
            Some(d) => observed[grid.bin_of(d)] += 1.0,
            None => observed[n] += 1.0,
        }
    }
    let mut exp = integrate_grid(grid, &pdf);
    exp.push(0.0);
    let mass: f64 = exp.iter().sum();
    assert!(mass < 1.0 + grid.mass_tolerance, "{name}: the pdf integrates to {mass} > 1");
    exp[n] = (1.0 - mass).max(0.0);
    let p = chi2_p_value(&observed, &exp.iter().map(|e| e * SAMPLES as f64).collect::<Vec<_>>());
    println!("{name}: χ² p-value {p:.4} (pdf mass {mass:.5}, rejected {})", observed[n]);
    assert!(p > ALPHA, "{name}: samples do not follow the pdf (p = {p:.2e}, pdf mass {mass:.5}, rejected {})", observed[n]);
    p
}
