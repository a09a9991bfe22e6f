//! Statistical comparison of a render against a reference image.
//!
//! Besides RMSE, relative MSE and the ratio of mean luminances, a render that carries a variance
//! estimate gets a per-pixel z-test: each channel's difference divided by its standard error must stay
//! under the critical value of a two-sided test at 1% significance, Šidák-corrected for the number of
//! values tested (so that a correct renderer fails any one image with probability ≈ 1%). The standard
//! error combines the render's variance, the reference's (estimated from the render's per-sample variance
//! and the reference's sample count) and the reference's storage precision (half floats).
use crate::output::film::{variance_path, Film};
use anyhow::{bail, Result};
use glam::Vec3;
use statrs::distribution::{ContinuousCDF, Normal};
use std::path::Path;

/// Relative precision of the reference's storage (half float: 2^-11) plus a small absolute floor,
/// added to the standard error so that noise-free pixels are not failed by rounding.
const REFERENCE_RELATIVE_PRECISION: f64 = 1.0 / 2048.0;
const ABSOLUTE_FLOOR: f64 = 1.0e-4;

#[derive(Clone, Debug)]
pub struct Comparison {
    pub rmse: f64,
    pub rel_mse: f64,
    /// Mean luminance of the render over that of the reference.
    pub luminance_ratio: f64,
    /// Fraction of pixels whose three channels all pass the z-test (when a variance is known).
    pub pass_fraction: Option<f64>,
    pub z_critical: f64,
    /// The difference of mean luminances in units of its standard error (when a variance is known):
    /// a global bias shows here long before single pixels fail.
    pub luminance_z: Option<f64>,
    /// Per-pixel largest |z| (or relative error without a variance), for the false-colour image.
    pub error_map: Vec<f32>,
    /// The reference's own noise in `rmse`² and `rel_mse`, from its variance where it has one
    /// (`Film::load_with_variance`): independent noise adds, so the render's error against the
    /// truth is estimated by the difference (`ConvergencePoint::net_mse`).
    pub reference_noise: Option<ReferenceNoise>,
}

/// The reference's expected share of the mean squared error and of the relative MSE: its variance
/// averaged over the values as `Comparison::rmse`² and `rel_mse` average the squared differences.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceNoise {
    pub mse: f64,
    pub rel_mse: f64,
}

/// The kernel's luminance (one set of weights for the renderer and its statistics), summed in f64.
fn luminance(c: [f32; 3]) -> f64 {
    caustic_kernel::spectrum::luminance(Vec3::from(c)) as f64
}

/// The `samples_ratio` of `compare` for a render and a reference of these samples per pixel: 0 (the
/// reference's noise ignored) unless both are known (non-zero).
pub fn samples_ratio(image_spp: u32, reference_spp: u32) -> f64 {
    if image_spp > 0 && reference_spp > 0 {
        image_spp as f64 / reference_spp as f64
    } else {
        0.0
    }
}

/// Compares `image` with `reference`. `samples_ratio` = render spp / reference spp estimates the
/// reference's own variance from the render's (0 ignores it).
pub fn compare(image: &Film, reference: &Film, samples_ratio: f64) -> Result<Comparison> {
    if image.width != reference.width || image.height != reference.height {
        bail!(
            "image is {}×{} but the reference is {}×{}",
            image.width,
            image.height,
            reference.width,
            reference.height
        );
    }
    let n = image.rgb.len();
    let values = (n * 3) as f64;
    let alpha = 1.0 - (1.0f64 - 0.01).powf(1.0 / values);
    let z_critical = Normal::new(0.0, 1.0).unwrap().inverse_cdf(1.0 - alpha / 2.0);
    let (mut se, mut rel, mut lum_a, mut lum_b) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut passed = 0usize;
    let mut lum_var = 0.0f64;
    let mut error_map = Vec::with_capacity(n);
    let (mut noise_se, mut noise_rel) = (0.0f64, 0.0f64);
    let variance = image.variance.as_ref().map(|v| pooled_variance(v, image.width, image.height));
    for i in 0..n {
        let (a, b) = (image.rgb[i], reference.rgb[i]);
        let mut worst = 0.0f64;
        let mut ok = true;
        for c in 0..3 {
            let d = a[c] as f64 - b[c] as f64;
            let weight = 1.0 / ((b[c] as f64).powi(2) + 1e-2);
            se += d * d;
            rel += d * d * weight;
            if let Some(v) = &reference.variance {
                noise_se += v[i][c];
                noise_rel += v[i][c] * weight;
            }
            match &variance {
                Some(v) => {
                    let var = v[i][c] * (1.0 + samples_ratio)
                        + (REFERENCE_RELATIVE_PRECISION * b[c].abs() as f64).powi(2)
                        + ABSOLUTE_FLOOR * ABSOLUTE_FLOOR;
                    let z = d.abs() / var.sqrt();
                    ok &= z <= z_critical;
                    worst = worst.max(z);
                }
                None => worst = worst.max(d.abs() / (b[c].abs() as f64 + 1e-2)),
            }
        }
        passed += ok as usize;
        if let Some(v) = &variance {
            // Channels of one pixel are strongly correlated: bound the luminance's standard error by
            // the sum of the weighted channel errors (exact for perfect correlation, conservative otherwise).
            let sd = luminance(v[i].map(|x| x.sqrt() as f32));
            lum_var += sd * sd * (1.0 + samples_ratio);
        }
        error_map.push(worst as f32);
        lum_a += luminance(a);
        lum_b += luminance(b);
    }
    Ok(Comparison {
        rmse: (se / values).sqrt(),
        rel_mse: rel / values,
        luminance_ratio: if lum_b > 0.0 { lum_a / lum_b } else { f64::NAN },
        pass_fraction: image.variance.as_ref().map(|_| passed as f64 / n as f64),
        luminance_z: image
            .variance
            .as_ref()
            .map(|_| (lum_a - lum_b) / (lum_var * image.sum_variance_factor).sqrt().max(1e-12)),
        z_critical,
        error_map,
        reference_noise: reference
            .variance
            .as_ref()
            .map(|_| ReferenceNoise { mse: noise_se / values, rel_mse: noise_rel / values }),
    })
}

/// Refuses an image (and its variance, if loaded) holding a NaN or infinite value, naming `path` and
/// the first such pixel: a single one would make every statistic NaN, and a NaN compares as neither
/// pass nor fail.
pub fn check_finite(film: &Film, path: &Path) -> Result<()> {
    let first_bad = |values: &mut dyn Iterator<Item = [f64; 3]>| {
        values.enumerate().find(|(_, p)| p.iter().any(|c| !c.is_finite()))
    };
    let bad = |(i, value): (usize, [f64; 3]), what: &str, file: &Path| {
        let (x, y) = (i as u32 % film.width, i as u32 / film.width);
        anyhow::anyhow!(
            "{}: pixel ({x}, {y}) {what} is not finite ({value:?}); compare needs finite images",
            file.display(),
        )
    };
    if let Some(found) = first_bad(&mut film.rgb.iter().map(|p| p.map(f64::from))) {
        return Err(bad(found, "of the image", path));
    }
    if let Some(v) = &film.variance {
        if let Some(found) = first_bad(&mut v.iter().copied()) {
            return Err(bad(found, "of the variance", &variance_path(path)));
        }
    }
    Ok(())
}

/// Per-pixel variance made robust to its own noise: the larger of the pixel's estimate and the mean
/// over its 3×3 neighbourhood. With few samples a pixel's variance estimate is itself very noisy (and
/// heavy-tailed path contributions make it too small more often than too large); pooling with the
/// neighbours steadies it while a genuine bias still stands out by many standard errors.
pub fn pooled_variance(v: &[[f64; 3]], width: u32, height: u32) -> Vec<[f64; 3]> {
    let (w, h) = (width as i64, height as i64);
    let mut out = Vec::with_capacity(v.len());
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0.0f64; 3];
            let mut count = 0.0f64;
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx >= 0 && ny >= 0 && nx < w && ny < h {
                        let p = v[(ny * w + nx) as usize];
                        for c in 0..3 {
                            sum[c] += p[c];
                        }
                        count += 1.0;
                    }
                }
            }
            let own = v[(y * w + x) as usize];
            out.push(std::array::from_fn(|c| own[c].max(sum[c] / count)));
        }
    }
    out
}

/// Writes the error map as a false-colour PNG: black (no error) through blue and red to yellow at
/// `scale` (the z-test's critical value, or 100% relative error).
pub fn save_error_image(path: &Path, width: u32, height: u32, errors: &[f32], scale: f32) -> Result<()> {
    let img = image::RgbImage::from_fn(width, height, |x, y| {
        let t = (errors[(y * width + x) as usize] / scale).clamp(0.0, 1.0);
        let rgb = if t < 0.5 {
            [0.0, 0.0, t * 2.0]
        } else {
            [(t - 0.5) * 2.0, (t - 0.5).max(0.0) * 2.0 * (t - 0.5) * 2.0, 1.0 - (t - 0.5) * 2.0]
        };
        image::Rgb(rgb.map(|c| (c * 255.0) as u8))
    });
    crate::system::files::write(path, &crate::output::film::png_bytes(&img)?)
}
