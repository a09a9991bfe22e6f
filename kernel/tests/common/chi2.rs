//! Pearson's χ² goodness-of-fit test of a sampling routine against its density, on a (cos θ, φ) grid
//! of the sphere (in the spirit of Mitsuba's and pbrt's sampling tests), and the adaptive quadrature
//! over the same grids that computes the expected counts (also used for albedos and normalisation).
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

/// One adaptive Simpson step on [a, b] given f at a, the midpoint and b and the whole-interval estimate:
/// splits until the halves agree with the whole to `15·eps` or `depth` runs out (Richardson-corrected).
#[allow(clippy::too_many_arguments)]
fn simpson_refine(
    f: &mut dyn FnMut(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    eps: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    let (flm, frm) = (f(lm), f(rm));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    if depth == 0 || (left + right - whole).abs() <= 15.0 * eps {
        return left + right + (left + right - whole) / 15.0;
    }
    simpson_refine(f, a, m, fa, flm, fm, left, eps * 0.5, depth - 1)
        + simpson_refine(f, m, b, fm, frm, fb, right, eps * 0.5, depth - 1)
}

/// Adaptive Simpson quadrature of `f` over [a, b] (absolute tolerance `eps`, bounded depth).
fn adaptive_simpson(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, eps: f64) -> f64 {
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    simpson_refine(f, a, b, fa, fm, fb, whole, eps, 12)
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
                let mut over_phi =
                    |phi: f64| pdf(Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32));
                adaptive_simpson(&mut over_phi, p0, p0 + d_phi, 1e-7)
            };
            e[i * PHI_BINS + j] = adaptive_simpson(&mut over_z, z0, z0 + d_cos, 1e-6);
        }
    }
    e
}

/// Runs the test. `sample` maps (u_lobe, u) to a direction or `None` (a rejected sample, expected
/// with the probability mass the pdf misses). Returns the p-value.
pub fn chi2_directions(
    name: &str,
    mut sample: impl FnMut(f32, Vec2) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) -> f64 {
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

/// A binning of the sphere for `chi2_grid`: bins in (1 - cos α, φ) around an axis, with arbitrary edges
/// in `1 - cos α` (ascending, from 0 to 2) so that narrow lobes can be resolved around their axis.
/// (`1 - cos α` is computed from the tangential components, which keeps its precision near the axis.)
pub struct Grid {
    pub frame: caustic_kernel::frame::Frame,
    pub omc_edges: Vec<f64>,
    pub phi_bins: usize,
    /// Levels of subdivision the quadrature of each bin makes before it may stop: a lobe narrower than
    /// a bin is then not missed by the first few nodes.
    pub min_depth: u32,
    /// How far above 1 the integrated pdf may come (approximate shadowing terms are allowed a little).
    pub mass_tolerance: f64,
    /// Compare only the shape of the distribution of the directions returned (the expected counts
    /// rescaled to their number), not how often none is returned: for densities whose total is only
    /// known to ~1e-4, which misplaces the expected count of rejections by more than its noise.
    pub conditional: bool,
}

impl Grid {
    /// The whole sphere around +z, bins uniform in cos θ and φ (as `chi2_directions`).
    pub fn sphere() -> Grid {
        Grid::around(Vec3::Z, 1.0)
    }

    /// Bins around `axis` with `1 - cos α = 2 (k/K)^power`: `power` > 1 crowds them near the axis.
    pub fn around(axis: Vec3, power: f64) -> Grid {
        let omc_edges = (0..=THETA_BINS).map(|k| 2.0 * (k as f64 / THETA_BINS as f64).powf(power)).collect();
        Grid {
            frame: caustic_kernel::frame::Frame::from_normal(axis.normalize()),
            omc_edges,
            phi_bins: PHI_BINS,
            min_depth: 3,
            mass_tolerance: 1e-3,
            conditional: false,
        }
    }

    /// A coarser grid (12 × 24 bins), for plain integration.
    pub fn coarse(axis: Vec3) -> Grid {
        let omc_edges = (0..=12).map(|k| 2.0 * k as f64 / 12.0).collect();
        Grid {
            frame: caustic_kernel::frame::Frame::from_normal(axis.normalize()),
            omc_edges,
            phi_bins: 24,
            min_depth: 2,
            mass_tolerance: 1e-3,
            conditional: false,
        }
    }

    fn bins(&self) -> usize {
        (self.omc_edges.len() - 1) * self.phi_bins
    }

    fn bin_of(&self, d: Vec3) -> usize {
        let l = self.frame.to_local(d);
        let (x, y, z) = (l.x as f64, l.y as f64, (l.z as f64).clamp(-1.0, 1.0));
        let omc = if z > 0.0 { (x * x + y * y) / (1.0 + z) } else { 1.0 - z };
        let t = self.omc_edges.partition_point(|&e| e <= omc).clamp(1, self.omc_edges.len() - 1) - 1;
        let mut phi = y.atan2(x);
        if phi < 0.0 {
            phi += 2.0 * std::f64::consts::PI;
        }
        let p = ((phi / (2.0 * std::f64::consts::PI)) * self.phi_bins as f64) as usize;
        t * self.phi_bins + p.min(self.phi_bins - 1)
    }
}

/// Adaptive Simpson quadrature over `2^min_depth` equal pieces (so that a feature narrower than the
/// interval is not missed by the first nodes), to a relative tolerance `rel` of a first composite
/// estimate, or the absolute floor `abs`.
fn simpson_min_depth(
    f: &mut dyn FnMut(f64) -> f64,
    a: f64,
    b: f64,
    rel: f64,
    abs: f64,
    min_depth: u32,
) -> f64 {
    let n = 1usize << min_depth;
    let h = (b - a) / n as f64;
    let nodes: Vec<f64> = (0..=2 * n).map(|k| f(a + 0.5 * h * k as f64)).collect();
    let pieces: Vec<f64> =
        (0..n).map(|k| h / 6.0 * (nodes[2 * k] + 4.0 * nodes[2 * k + 1] + nodes[2 * k + 2])).collect();
    let eps = (rel * pieces.iter().sum::<f64>().abs()).max(abs) / n as f64;
    (0..n)
        .map(|k| {
            simpson_refine(
                f,
                a + h * k as f64,
                a + h * (k + 1) as f64,
                nodes[2 * k],
                nodes[2 * k + 1],
                nodes[2 * k + 2],
                pieces[k],
                eps,
                12,
            )
        })
        .sum()
}

/// Integral of `f` over each bin of `grid` (nested adaptive quadrature in 1 - cos α and φ).
pub fn integrate_grid(grid: &Grid, f: &dyn Fn(Vec3) -> f64) -> Vec<f64> {
    let mut out = vec![0.0; grid.bins()];
    let d_phi = 2.0 * std::f64::consts::PI / grid.phi_bins as f64;
    for t in 0..grid.omc_edges.len() - 1 {
        let (o0, o1) = (grid.omc_edges[t], grid.omc_edges[t + 1]);
        for j in 0..grid.phi_bins {
            let p0 = j as f64 * d_phi;
            let mut over_omc = |omc: f64| {
                let z = 1.0 - omc;
                let r = (omc * (2.0 - omc)).max(0.0).sqrt();
                let mut over_phi = |phi: f64| {
                    let local = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    f(grid.frame.to_world(local))
                };
                simpson_min_depth(&mut over_phi, p0, p0 + d_phi, 1e-4, 1e-12, grid.min_depth)
            };
            out[t * grid.phi_bins + j] =
                simpson_min_depth(&mut over_omc, o0, o1, 1e-4, 1e-10, grid.min_depth);
        }
    }
    out
}

/// χ² test of `sample` against `pdf` on `grid` (see `chi2_directions`); `seed` varies the samples.
/// Returns the p-value.
pub fn chi2_grid(
    name: &str,
    grid: &Grid,
    seed: u32,
    mut sample: impl FnMut(f32, Vec2) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) -> f64 {
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
    let expected: Vec<f64> = exp.iter().map(|e| e * SAMPLES as f64).collect();
    let p = if grid.conditional {
        let returned = SAMPLES as f64 - observed[n];
        let scaled: Vec<f64> = expected[..n].iter().map(|e| e * returned / (mass * SAMPLES as f64)).collect();
        chi2_p_value(&observed[..n], &scaled)
    } else {
        chi2_p_value(&observed, &expected)
    };
    println!("{name}: χ² p-value {p:.4} (pdf mass {mass:.5}, rejected {})", observed[n]);
    if std::env::var_os("CHI2_DEBUG").is_some() {
        for t in 0..grid.omc_edges.len() - 1 {
            let o: f64 = (0..grid.phi_bins).map(|k| observed[t * grid.phi_bins + k]).sum();
            let e: f64 = (0..grid.phi_bins).map(|k| expected[t * grid.phi_bins + k]).sum();
            println!("  1-cos α ≥ {:.3e}: observed {o} expected {e:.1}", grid.omc_edges[t]);
            if std::env::var_os("CHI2_PHI").is_some() && o > 1000.0 {
                for k in 0..grid.phi_bins {
                    let (o, e) = (observed[t * grid.phi_bins + k], expected[t * grid.phi_bins + k]);
                    if o > 0.0 || e > 0.5 {
                        println!("      φ bin {k}: observed {o} expected {e:.1}");
                    }
                }
            }
        }
    }
    assert!(
        p > ALPHA,
        "{name}: samples do not follow the pdf (p = {p:.2e}, pdf mass {mass:.5}, rejected {})",
        observed[n]
    );
    p
}
