//! Light-traced images judged against path-traced ones: a light path splats into several pixels, so
//! neighbouring pixels are correlated and a light-traced image's standard error comes from independent
//! replicas rather than from its per-pixel variances.
use crate::render_scene;
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::Scene;

/// A light-traced (or IBPT) image rendered as `REPLICAS` independent renders of `spp / REPLICAS`
/// samples each: a light path splats into several pixels, so neighbouring pixels are correlated and
/// their variances do not add up to the whole image's; the replicas' image means give its standard
/// error instead.
pub struct Replicated {
    /// The replicas' average, with the variance of that average per pixel.
    pub film: Film,
    pub mean: f64,
    /// Standard error of `mean`, from the spread of the replicas' image means.
    pub se: f64,
}

/// 16 replicas: the image z-score is t-distributed with 15 degrees of freedom, so |z| < 4.5 fails by chance
/// with probability 4e-4 per comparison.
pub const REPLICAS: u32 = 16;

pub fn image_mean(f: &Film) -> f64 {
    f.rgb.iter().flatten().map(|&c| c as f64).sum::<f64>() / (3 * f.rgb.len()) as f64
}

pub fn render_replicated(scene: &Scene, spp: u32, seed: u32) -> Replicated {
    let films: Vec<Film> = (0..REPLICAS)
        .map(|r| render_scene(scene, BackendChoice::Cpu, spp / REPLICAS, seed * 1000 + r))
        .collect();
    let n = REPLICAS as f64;
    let means: Vec<f64> = films.iter().map(image_mean).collect();
    let mean = means.iter().sum::<f64>() / n;
    let se = (means.iter().map(|m| (m - mean) * (m - mean)).sum::<f64>() / (n - 1.0) / n).sqrt();
    let mut film = films[0].clone();
    for i in 0..film.rgb.len() {
        for c in 0..3 {
            film.rgb[i][c] = films.iter().map(|f| f.rgb[i][c]).sum::<f32>() / REPLICAS as f32;
            film.variance.as_mut().unwrap()[i][c] =
                films.iter().map(|f| f.variance.as_ref().unwrap()[i][c]).sum::<f64>()
                    / (REPLICAS * REPLICAS) as f64;
        }
    }
    film.invalid_samples = films.iter().map(|f| f.invalid_samples).sum();
    Replicated { film, mean, se }
}

/// The whole-image z-score of `a`'s mean against path-traced `b` (whose pixels are independent) and the
/// worst per-pixel |z| (each image's variance pooled over neighbours).
pub fn agreement(a: &Replicated, b: &Film) -> (f64, f64) {
    let pooled =
        |f: &Film| caustic::output::compare::pooled_variance(f.variance.as_ref().unwrap(), f.width, f.height);
    let (va, vb) = (pooled(&a.film), pooled(b));
    let mut worst = 0.0f64;
    let mut var_b = 0.0f64;
    for i in 0..a.film.rgb.len() {
        for c in 0..3 {
            let d = a.film.rgb[i][c] as f64 - b.rgb[i][c] as f64;
            let v = va[i][c] + vb[i][c];
            var_b += b.variance.as_ref().unwrap()[i][c];
            worst = worst.max(d.abs() / (v.sqrt() + 1e-6));
        }
    }
    let count = (3 * b.rgb.len()) as f64;
    let z = (a.mean - image_mean(b)) / (a.se * a.se + var_b / (count * count)).sqrt();
    (z, worst)
}
