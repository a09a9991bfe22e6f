//! The splatting film (`caustic_kernel::film_splat`): what one sample adds to each pixel, that its
//! image estimates what filter importance sampling (`--film fis`) and Mitsuba estimate at a lower
//! error per sample, and that its variance estimates (per pixel, and of sums of pixels) match the
//! scatter of independent renders; the same for the camera halves of `ibpt`, `bdpt` and `vcm`,
//! which splat into the pixels their filter reaches beside light tracing's connections. Its agreement
//! with Mitsuba per filter is `filters.rs`'s; CPU against GPU is `cross_backend.rs`'s.
use caustic::backend::BackendChoice;
use caustic::output::film::Film;
use caustic::scene::{FilmMode, IntegratorKind};
use caustic_kernel::film::{filter_weight, FilmSample};
use caustic_kernel::film_splat::{add, clear, gather, reach_for_radius, resolved, CellReader, FilmCells};
use caustic_kernel::glam::{Vec2, Vec3};
use caustic_kernel::layout::{FrameParams, PixelAccum};
use caustic_tests::*;

#[test]
fn the_reach_covers_every_pixel_centre_within_the_radius() {
    // A sample at u ∈ [0, 1) of pixel 0 is i + ½ − u from pixel i's centre.
    for (radius, reach) in [(0.5, 0), (0.25, 0), (0.51, 1), (1.0, 1), (1.5, 1), (1.51, 2), (2.0, 2), (3.0, 3)]
    {
        assert_eq!(reach_for_radius(radius), reach, "radius {radius}");
    }
}

/// Every pixel's cells, pixel after pixel (as the CPU backend keeps them).
struct Cells {
    values: Vec<f32>,
    stride: usize,
}

impl CellReader for Cells {
    fn get(&self, _: &FrameParams, pixel: u32, slot: u32) -> f32 {
        self.values[pixel as usize * self.stride + slot as usize]
    }
}

impl FilmCells for Cells {
    fn set(&mut self, _: &FrameParams, pixel: u32, slot: u32, value: f32) {
        self.values[pixel as usize * self.stride + slot as usize] = value;
    }
}

/// The buffers of an empty scene whose `width`×`height` film has the reconstruction filter `filter`
/// and the film's further properties `more` (XML, a crop window's say).
fn film_buffers(
    width: u32,
    height: u32,
    more: &str,
    filter: &str,
    tag: &str,
) -> caustic::prepare::buffers::SceneBuffers {
    let scene = load_xml(
        &format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">\
             <integer name=\"width\" value=\"{width}\"/><integer name=\"height\" value=\"{height}\"/>{more}\
             <rfilter type=\"{filter}\"/></film></sensor></scene>"
        ),
        tag,
    );
    caustic::prepare::buffers::build(&scene).expect("builds")
}

/// One sample of a 7×6 image, splatted from pixel (`px`, `py`) at offset `o` within it: each pixel
/// gathers L·w and w for w the product of the filter's weights at its centre's offsets, and only
/// pixels of the image within the radius get anything.
#[test]
fn one_sample_reaches_each_pixel_with_the_filters_weight() {
    let buffers = film_buffers(7, 6, "", "gaussian", "film-weights");
    let params = buffers.params;
    assert_eq!(params.film_reach, 2, "the gaussian's radius 2 reaches two pixels");
    let stride = caustic_kernel::film_splat::words_per_pixel(&params) as usize;
    assert_eq!(stride, 25 * 4 + 1);
    let l = Vec3::new(1.0, 2.0, 4.0);
    for (px, py, o) in
        [(3u32, 2u32, Vec2::new(0.3, 0.8)), (0, 0, Vec2::new(0.05, 0.9)), (6, 5, Vec2::new(0.99, 0.0))]
    {
        let mut cells = Cells { values: vec![f32::NAN; 42 * stride], stride };
        for pixel in 0..42 {
            // (Clears the pixel's cells: they start as NaN here.)
            clear(&mut cells, &params, pixel);
        }
        let pixel = py * 7 + px;
        let pos = Vec2::new((px as f32 + o.x) / 7.0, (py as f32 + o.y) / 6.0);
        add(&mut cells, &buffers.tables, &params, pixel, FilmSample { pos, weight: 1.0 }, l);
        let nan = Vec3::new(f32::NAN, 0.0, 0.0);
        add(&mut cells, &buffers.tables, &params, pixel, FilmSample { pos, weight: 1.0 }, nan);
        for (qx, qy) in (0..6u32).flat_map(|y| (0..7u32).map(move |x| (x, y))) {
            let g = gather(&cells, &params, qx, qy);
            let dx = qx as f32 + 0.5 - (px as f32 + o.x);
            let dy = qy as f32 + 0.5 - (py as f32 + o.y);
            let w = filter_weight(&buffers.tables, &params, dx) * filter_weight(&buffers.tables, &params, dy);
            let near = dx.abs() < 2.0 && dy.abs() < 2.0;
            assert_eq!(w > 0.0, near, "pixel ({qx}, {qy}) from ({px}, {py})");
            assert!((g.weight - w).abs() <= 1e-6 * w.max(1.0), "({qx}, {qy}): {} against {w}", g.weight);
            assert!((g.sum - l * w).abs().max_element() <= 1e-5 * w.max(1.0), "({qx}, {qy})");
            let invalid = if (qx, qy) == (px, py) { 1.0 } else { 0.0 };
            assert_eq!(g.invalid, invalid, "the NaN sample is counted at its own pixel only");
            // The accumulator develops to L where the pixel got any weight.
            let a = resolved(PixelAccum::default(), &g, 1.0);
            if w > 0.0 {
                assert!((Vec3::from(a.sum) / a.count - l).abs().max_element() < 1e-5);
            }
        }
    }
}

/// An empty scene's buffers, a 16×12 image with a 9×7 crop window at (3, 2), under `filter`.
fn crop_window_buffers(filter: &str) -> caustic::prepare::buffers::SceneBuffers {
    let crop = "<integer name=\"crop_offset_x\" value=\"3\"/><integer name=\"crop_offset_y\" value=\"2\"/>\
                <integer name=\"crop_width\" value=\"9\"/><integer name=\"crop_height\" value=\"7\"/>";
    film_buffers(16, 12, crop, filter, &format!("crop-window-{filter}"))
}

/// `film::pixel_weight` (light tracing's weight for a pixel, which the bidirectional camera halves
/// splat with) is the product of its two axes' filters over the product of their masses
/// (`film::axis_pixel_weight`, how `splat_camera_estimate` evaluates a neighbourhood): the same to the bit,
/// for every filter, inside a crop window and at its edges.
#[test]
fn a_pixels_weight_is_the_product_of_its_axes() {
    for filter in ["gaussian", "tent", "mitchell", "lanczos"] {
        let buffers = crop_window_buffers(filter);
        let (params, tables) = (buffers.params, &buffers.tables);
        let (mut nonzero, mut checked) = (0, 0);
        for k in 0..400 {
            // Points of the window, its edges' pixels included (a golden-ratio lattice).
            let u = ((k as f32 * 0.618_034) % 1.0, (k as f32 * 0.754_878) % 1.0);
            let pos = Vec2::new(3.0 + 9.0 * u.0, 2.0 + 7.0 * u.1);
            for py in 2..9 {
                for px in 3..12 {
                    let w = caustic_kernel::film::pixel_weight(tables, &params, pos, px, py);
                    let (fx, mx) = caustic_kernel::film::axis_pixel_weight(
                        tables,
                        &params,
                        pos.x,
                        px as f32 + 0.5,
                        true,
                    );
                    let (fy, my) = caustic_kernel::film::axis_pixel_weight(
                        tables,
                        &params,
                        pos.y,
                        py as f32 + 0.5,
                        false,
                    );
                    let mass = mx * my;
                    let separable = if fx != 0.0 && fy != 0.0 && mass > 0.0 { fx * fy / mass } else { 0.0 };
                    assert_eq!(w.to_bits(), separable.to_bits(), "{filter}: pixel ({px}, {py}) at {pos}");
                    nonzero += (w != 0.0) as u32;
                    checked += 1;
                }
            }
        }
        assert!(nonzero * 20 > checked, "{filter}: only {nonzero} of {checked} weights were not zero");
    }
}

/// Splats into a footprint (`integrator::splat_footprint`) keep each pixel's expectation: the pixels
/// whose weight is below `FOOTPRINT_FLOOR` of the largest are reached by chance, with the floor's
/// weight. For every filter (negative lobes included), at points of a crop window and its edges, the
/// mean over 4096 rounding numbers of what each pixel got is its weight (`film::pixel_weight`) within
/// five standard errors, and a gaussian's splat reaches 5.5 of the 12.3 pixels its footprint has in
/// the window on average (asserted: under 0.6 of them). (Splatting the floor's weight with probability
/// ½ instead fails it: pixel (1, 0) of the gaussian's first point, 0.0114 against 0.0064.)
#[test]
fn a_footprints_chance_splats_keep_each_pixels_expectation() {
    use caustic_kernel::integrator::{axis_weights, splat_footprint, FOOTPRINT_FLOOR};
    use caustic_kernel::splat::{resolved as resolved_words, OwnWords, SPLAT_STRIDE};
    const TRIALS: u32 = 4096;
    for filter in ["gaussian", "tent", "mitchell", "lanczos"] {
        let buffers = crop_window_buffers(filter);
        let (params, tables) = (buffers.params, &buffers.tables);
        let view = buffers.view();
        let (w, h) = (params.width, params.height);
        let r = params.filter_radius;
        let (mut splats, mut footprint) = (0u64, 0u64);
        for k in 0..24 {
            let u = ((k as f32 * 0.618_034) % 1.0, (k as f32 * 0.754_878) % 1.0);
            let pos = Vec2::new(3.0 + 9.0 * u.0, 2.0 + 7.0 * u.1);
            // The footprint as light tracing takes it (`ptracer::splat_to_camera`), in the window.
            let x0 = ((pos.x - r).floor().max(3.0)) as u32;
            let y0 = ((pos.y - r).floor().max(2.0)) as u32;
            let x1 = ((pos.x + r).floor() as u32).min(3 + w - 1);
            let y1 = ((pos.y + r).floor() as u32).min(2 + h - 1);
            let (columns, rows) = (x1 - x0 + 1, y1 - y0 + 1);
            let first = (x0 as i32 - 3, y0 as i32 - 2);
            let along_x = axis_weights(&view, &params, pos.x, first.0, columns, true);
            let along_y = axis_weights(&view, &params, pos.y, first.1, rows, false);
            let mut sums = vec![0.0f64; (w * h) as usize];
            for t in 0..TRIALS {
                let mut words = vec![0u32; (w * h * SPLAT_STRIDE) as usize];
                let u = (t as f32 + 0.5) / TRIALS as f32;
                splat_footprint(
                    &mut OwnWords(&mut words),
                    w,
                    first,
                    &along_x,
                    &along_y,
                    (columns, rows),
                    Vec3::ONE,
                    u,
                );
                for (pixel, sum) in sums.iter_mut().enumerate() {
                    let base = pixel * SPLAT_STRIDE as usize;
                    let mut cell = [0u32; SPLAT_STRIDE as usize];
                    cell.copy_from_slice(&words[base..base + SPLAT_STRIDE as usize]);
                    let a = resolved_words(PixelAccum::default(), cell, 1, 1.0);
                    *sum += a.sum[0] as f64;
                    splats += (cell[..6].iter().any(|&x| x != 0)) as u64;
                }
            }
            let weights: Vec<f32> = (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| caustic_kernel::film::pixel_weight(tables, &params, pos, x + 3, y + 2))
                .collect();
            let largest = weights.iter().fold(0.0f32, |m, x| m.max(x.abs())) as f64;
            let floor = FOOTPRINT_FLOOR as f64 * largest;
            for (pixel, (&sum, &weight)) in sums.iter().zip(&weights).enumerate() {
                let mean = sum / TRIALS as f64;
                let weight = weight as f64;
                footprint += (weight != 0.0) as u64;
                let se = (floor * weight.abs() / TRIALS as f64).sqrt();
                assert!(
                    (mean - weight).abs() <= 5.0 * se + 1e-5 * largest,
                    "{filter}: pixel ({}, {}) at {pos}: {mean:.6} against {weight:.6}",
                    pixel as u32 % w,
                    pixel as u32 / w
                );
            }
        }
        let per_splat = splats as f64 / TRIALS as f64 / 24.0;
        let per_footprint = footprint as f64 / 24.0;
        println!("{filter}: {per_splat:.2} pixels splatted of {per_footprint:.2} with a weight");
        assert!(per_splat < per_footprint, "{filter}: no pixel was left to chance");
        if filter == "gaussian" {
            assert!(per_splat < 0.6 * per_footprint, "the gaussian's tail still takes most splats");
        }
    }
}

fn render_filters_scene(filter: &str, film: FilmMode, spp: u32, seed: u32) -> Film {
    render_sized(filter, film, spp, seed, "32")
}

fn render_sized(filter: &str, film: FilmMode, spp: u32, seed: u32, res: &str) -> Film {
    render_with(IntegratorKind::Path, filter, film, spp, seed, res)
}

fn render_with(kind: IntegratorKind, filter: &str, film: FilmMode, spp: u32, seed: u32, res: &str) -> Film {
    render_file("filters.xml", kind, filter, film, spp, seed, res)
}

#[allow(clippy::too_many_arguments)]
fn render_file(
    file: &str,
    kind: IntegratorKind,
    filter: &str,
    film: FilmMode,
    spp: u32,
    seed: u32,
    res: &str,
) -> Film {
    let defines = defines(&[("filter", filter), ("res", res)]);
    let mut scene = caustic::load::load_scene(&test_data(file), &defines).expect("loads");
    scene.sensor.film = film;
    scene.integrator.kind = kind;
    render_scene(&scene, BackendChoice::Cpu, spp, seed)
}

fn mse(a: &Film, b: &Film) -> f64 {
    let n = (a.rgb.len() * 3) as f64;
    a.rgb
        .iter()
        .zip(&b.rgb)
        .flat_map(|(x, y)| (0..3).map(move |c| (x[c] - y[c]) as f64))
        .map(|d| d * d)
        .sum::<f64>()
        / n
}

/// At equal samples the splatting film's error against Mitsuba's reference is well below filter
/// importance sampling's: for the default gaussian (measured 7x on the Cornell box) and more for a
/// filter with negative lobes, where filter importance sampling adds signed weights' noise. Both
/// estimate the same image: each agrees with the reference.
#[test]
fn the_splatting_film_has_less_error_per_sample_than_filter_sampling() {
    // (Mitsuba's references of this scene, 16384 spp: filters.py.)
    for (filter, factor) in [("mitchell", 2.0), ("lanczos", 2.0)] {
        let reference = Film::load_exr(&test_data(&format!("filters_{filter}.exr"))).expect("reference");
        let (mut splat, mut fis) = (0.0, 0.0);
        for seed in 0..3 {
            splat += mse(&render_filters_scene(filter, FilmMode::Splat, 16, seed), &reference);
            fis += mse(&render_filters_scene(filter, FilmMode::Fis, 16, seed), &reference);
        }
        println!("{filter}: MSE at 16 spp, splat {:.3e}, fis {:.3e}", splat / 3.0, fis / 3.0);
        assert!(splat * factor < fis, "{filter}: splat {splat:.3e} against fis {fis:.3e}");
        for film in [FilmMode::Splat, FilmMode::Fis] {
            let (pass, z) = against(filter, film);
            println!("{filter}, {film:?}: pass {pass:.4}, z {z:+.2}");
            assert_agrees_with_reference((pass, z), &format!("{filter} {film:?}"));
        }
    }
}

/// The camera halves of the bidirectional integrators splat as `path`'s samples do, and so gain what
/// `path` gains: at equal samples their error against Mitsuba's reference is well below filter
/// importance sampling's, and under both films each agrees with the reference. The scene is
/// `filters_black.xml` with Mitsuba's default gaussian: emitters seen directly, which the camera
/// paths and the emitter points joined to the camera both reach, and a sphere under a point light,
/// which light tracing reaches, so the MIS between camera and light strategies weighs camera samples
/// by the density each film draws them with (`film::camera_density`) at every silhouette: left at
/// the filter's density under the splatting film, `ibpt`'s MSE at 16 spp was 5.9e-2 against 4.3e-3.
#[test]
fn the_bidirectional_camera_halves_have_the_splatting_films_lower_error() {
    let reference = Film::load_exr(&test_data("filters_black_gaussian.exr")).expect("reference");
    let render =
        |kind, film, spp, seed| render_file("filters_black.xml", kind, "gaussian", film, spp, seed, "32");
    for kind in [IntegratorKind::Ibpt, IntegratorKind::Bdpt, IntegratorKind::Vcm] {
        let (mut splat, mut fis) = (0.0, 0.0);
        for seed in 0..3 {
            splat += mse(&render(kind, FilmMode::Splat, 16, seed), &reference);
            fis += mse(&render(kind, FilmMode::Fis, 16, seed), &reference);
        }
        println!("{kind:?}: MSE at 16 spp, splat {:.3e}, fis {:.3e}", splat / 3.0, fis / 3.0);
        assert!(splat * 2.0 < fis, "{kind:?}: splat {splat:.3e} against fis {fis:.3e}");
        for film in [FilmMode::Splat, FilmMode::Fis] {
            let image = render(kind, film, 1024, 9);
            let c =
                caustic::output::compare::compare(&image, &reference, 1024.0 / 65536.0).expect("same size");
            let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
            println!("{kind:?}, {film:?}: pass {pass:.4}, z {z:+.2}");
            assert_agrees_with_reference((pass, z), &format!("{kind:?} {film:?}"));
        }
    }
}

/// The GPU runs the same splatted camera halves: `ibpt` (the `render` entry point's camera paths) and
/// `vcm` (`cache_camera`'s, which `bdpt` shares) with the default gaussian, the same seed, the same
/// image to float rounding.
#[test]
fn the_bidirectional_camera_halves_splat_alike_on_gpu_and_cpu() {
    for kind in [IntegratorKind::Ibpt, IntegratorKind::Vcm] {
        let defines = defines(&[("filter", "gaussian"), ("res", "24")]);
        let mut scene = caustic::load::load_scene(&test_data("filters_black.xml"), &defines).expect("loads");
        scene.integrator.kind = kind;
        let cpu = render_scene(&scene, BackendChoice::Cpu, 2, 5);
        let gpu = render_scene(&scene, BackendChoice::Gpu, 2, 5);
        let max_diff = max_abs_difference(&cpu, &gpu);
        println!("{kind:?} GPU vs CPU, gaussian: max |difference| {max_diff:e}");
        assert!(max_diff < 1e-3, "{kind:?}: GPU and CPU differ by {max_diff}");
    }
}

fn against(filter: &str, film: FilmMode) -> (f64, f64) {
    let image = render_filters_scene(filter, film, 256, 9);
    let reference = Film::load_exr(&test_data(&format!("filters_{filter}.exr"))).expect("reference");
    let c = caustic::output::compare::compare(&image, &reference, 256.0 / 16384.0).expect("same size");
    (c.pass_fraction.unwrap(), c.luminance_z.unwrap())
}

/// The film's variance estimates against the scatter of 128 independent renders (32×32, 16 spp):
/// each pixel's estimated variance (batch means) on average within 25% of the variance of its value
/// across renders, and the variance of the image's sum, which neighbouring pixels' shared samples
/// raise above the sum of their variances, within 35% of `sum_variance_factor` times that sum (the
/// scatter of 128 values has a relative standard error of 13%; the factor holds for pixels away
/// from the border, and at 16×16 the border's share made the estimate 1.34 times the scatter). The
/// negative control: the same sum without the factor falls short of the scatter.
#[test]
fn variance_estimates_match_the_scatter_of_independent_renders() {
    const RENDERS: u32 = 128;
    let films: Vec<Film> =
        (0..RENDERS).map(|seed| render_sized("gaussian", FilmMode::Splat, 16, 100 + seed, "32")).collect();
    let n = films[0].rgb.len();
    let factor = films[0].sum_variance_factor;
    println!("sum_variance_factor {factor:.3}");
    assert!(factor > 1.5 && factor < 4.0, "factor {factor}");
    let (mut estimated, mut scattered) = (0.0f64, 0.0f64);
    let mut sums = Vec::new();
    let mut summed_variance = 0.0f64;
    for f in &films {
        sums.push(f.rgb.iter().map(|p| p[1] as f64).sum::<f64>());
        summed_variance += f.variance.as_ref().unwrap().iter().map(|v| v[1]).sum::<f64>() / RENDERS as f64;
    }
    for i in 0..n {
        let values: Vec<f64> = films.iter().map(|f| f.rgb[i][1] as f64).collect();
        let mean = values.iter().sum::<f64>() / RENDERS as f64;
        scattered += values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (RENDERS - 1) as f64;
        estimated += films.iter().map(|f| f.variance.as_ref().unwrap()[i][1]).sum::<f64>() / RENDERS as f64;
    }
    let ratio = estimated / scattered;
    println!("per pixel: estimated / scattered variance {ratio:.3}");
    assert!((0.75..1.25).contains(&ratio), "per-pixel variance estimated {ratio:.3} times the scatter");
    let mean_sum = sums.iter().sum::<f64>() / RENDERS as f64;
    let sum_scatter = sums.iter().map(|s| (s - mean_sum).powi(2)).sum::<f64>() / (RENDERS - 1) as f64;
    let with_factor = summed_variance * factor / sum_scatter;
    let without = summed_variance / sum_scatter;
    println!("image sum: estimated / scattered variance {with_factor:.3} (without the factor {without:.3})");
    assert!((0.65..1.35).contains(&with_factor), "with the factor {with_factor:.3}");
    assert!(without < 0.75, "without the factor {without:.3}: the negative control passed");
}

/// A crop window's edge pixels: both films truncate the filter at the window's edge, where samples
/// stop (as Mitsuba draws them inside the rendered window). Filter importance sampling (the AOV
/// pass, light tracing, `--film fis`) once truncated it at the whole image's edge instead: random
/// scene 31's depth image had its crop's last row 0.7% apart from Mitsuba's. The negative control:
/// the whole image's pixels, cut to the window, differ from the crop's at its edge.
#[test]
fn a_crop_windows_edge_pixels_are_the_same_under_both_films() {
    let window = caustic::scene::Crop { x: 5, y: 7, width: 20, height: 16 };
    let render = |film: FilmMode, crop: Option<caustic::scene::Crop>, seed: u32| {
        let defines = defines(&[("filter", "gaussian"), ("res", "32")]);
        let mut scene = caustic::load::load_scene(&test_data("filters.xml"), &defines).expect("loads");
        (scene.sensor.film, scene.sensor.crop) = (film, crop);
        render_scene(&scene, BackendChoice::Cpu, 1024, seed)
    };
    let splat = render(FilmMode::Splat, Some(window), 1);
    let fis = render(FilmMode::Fis, Some(window), 2);
    let c = caustic::output::compare::compare(&fis, &splat, 1.0).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!("crop window, fis against splat: pass {pass:.4}, z {z:+.2}");
    assert!(pass >= 0.99 && z.abs() < 4.0, "the films disagree on a crop (pass {pass:.4}, z {z:+.2})");
    let inner = render(FilmMode::Fis, None, 3).crop(window.x, window.y, window.width, window.height);
    let c = caustic::output::compare::compare(&inner, &splat, 1.0).expect("same size");
    let (pass, z) = (c.pass_fraction.unwrap(), c.luminance_z.unwrap());
    println!("the whole image cut to the window, against the crop: pass {pass:.4}, z {z:+.2}");
    assert!(pass < 0.99, "the crop's edge went unnoticed (pass {pass:.4}, z {z:+.2})");
}

/// The control variate of the splatting integrators' camera samples (`film_splat::control_variate`)
/// needs each neighbour's mean weight from a sample drawn uniformly in a pixel: along each axis,
/// `film::axis_pixel_integral` against the mean of the filter over the pixel (midpoints), for every
/// pixel within the gaussian's reach, at the image's edge as inside; and `film::axis_pixel_mean`,
/// that over the truncated mass, summed over the pixels a receiving pixel's samples come from, is 1
/// (as the weights' sum is on average: the control variate's term averages to zero).
#[test]
fn the_control_variate_s_mean_weights_are_the_filter_s_means() {
    let buffers = film_buffers(9, 7, "", "gaussian", "film-means");
    let params = buffers.params;
    let tables = &buffers.tables;
    let n = 4096;
    for c in [0.5f32, 1.5, 4.5, 8.5] {
        let mut total = 0.0;
        let mut mass = 0.0;
        for at in 0..9 {
            let at = at as f32;
            let mut mean = 0.0;
            for k in 0..n {
                let x = at + (k as f32 + 0.5) / n as f32;
                let (f, m) = caustic_kernel::film::axis_pixel_weight(tables, &params, x, c, true);
                mean += f / n as f32;
                if m > 0.0 {
                    mass = m;
                }
            }
            let exact = caustic_kernel::film::axis_pixel_integral(tables, &params, at, c);
            assert!((exact - mean).abs() < 2e-4, "centre {c}, pixel {at}: {exact} against {mean}");
            let normalised = caustic_kernel::film::axis_pixel_mean(tables, &params, at, c, true);
            assert!((normalised * mass - exact).abs() < 1e-6, "centre {c}, pixel {at}");
            total += normalised;
        }
        assert!(mass > 0.0 && (total - 1.0).abs() < 1e-5, "centre {c}: the means sum to {total}");
    }
}

/// The kernel takes the control variate's mean weights a row at a time (`integrator::axis_means`:
/// adjacent pixels' integrals share a running sum); they are `film::axis_pixel_mean`'s to the bit for
/// every pixel of a window and every neighbour, at the window's edges (a crop's too) as inside.
#[test]
fn the_kernel_s_mean_weights_are_axis_pixel_mean_s_to_the_bit() {
    use caustic_kernel::film::{axis_pixel_mean, rendered_axis};
    use caustic_kernel::integrator::{axis_means, SPAN};
    for (name, buffers) in &mean_weight_films() {
        let (params, tables) = (&buffers.params, &buffers.tables[..]);
        let reach = params.film_reach as i32;
        let span = (2 * reach + 1) as u32;
        for x_axis in [true, false] {
            let (crop, size) = rendered_axis(params, x_axis);
            for own in 0..size {
                let first = own as i32 - reach;
                let means = axis_means(tables, params, own, (first, span), x_axis);
                assert!(means[span as usize..SPAN].iter().all(|&m| m == 0.0), "{name}: beyond the span");
                for i in 0..span as i32 {
                    let q = first + i;
                    let expected = if q >= 0 && q < size as i32 {
                        let c = (crop as i32 + q) as f32 + 0.5;
                        axis_pixel_mean(tables, params, (crop + own) as f32, c, x_axis)
                    } else {
                        0.0
                    };
                    let got = means[i as usize];
                    assert_eq!(
                        got.to_bits(),
                        expected.to_bits(),
                        "{name}, x {x_axis}, pixel {own}, {i}: {got} {expected}"
                    );
                }
            }
        }
    }
}

/// A whole image, and a crop window under the gaussian and the tent.
fn mean_weight_films() -> [(&'static str, caustic::prepare::buffers::SceneBuffers); 3] {
    [
        ("whole image", film_buffers(9, 7, "", "gaussian", "film-means-rows")),
        ("crop, gaussian", crop_window_buffers("gaussian")),
        ("crop, tent", crop_window_buffers("tent")),
    ]
}

/// A pixel's filter mass in the rendered window (`film::axis_window_mass`, which every splat's
/// weights divide by) is the frame's whole mass where the filter's radius lies inside the window
/// (`FrameParams::filter_mass`, written by the host from `film::whole_masses`), and the two running
/// sums of the truncated filter elsewhere: either way the same to the bit as those running sums, for
/// every pixel of a window and of a crop, under filters with and without negative lobes, along both
/// axes. Negative control: other whole masses in the frame change the interior pixels' masses and no
/// edge pixel's, so the frame's are the ones taken.
#[test]
fn a_pixel_s_mass_is_the_frame_s_whole_mass_inside_the_window_to_the_bit() {
    use caustic_kernel::film::{axis_running_sum, axis_window_mass, rendered_axis};
    // The mean weights' films, and crops under the filters with negative lobes.
    let mut films = Vec::from(mean_weight_films());
    films.push(("crop, mitchell", crop_window_buffers("mitchell")));
    films.push(("crop, lanczos", crop_window_buffers("lanczos")));
    for (name, buffers) in &films {
        let (params, tables) = (&buffers.params, &buffers.tables[..]);
        let other = FrameParams {
            filter_abs_mass: params.filter_abs_mass * 1.01,
            filter_mass: params.filter_mass * 1.01,
            ..*params
        };
        let r = params.filter_radius;
        let (mut interior, mut edge) = (0, 0);
        for x_axis in [true, false] {
            let (crop, size) = rendered_axis(params, x_axis);
            let (lo, hi) = (crop as f32, (crop + size) as f32);
            for q in 0..size {
                let c = (crop + q) as f32 + 0.5;
                let mass = axis_window_mass(tables, params, c, x_axis);
                let summed = axis_running_sum(tables, params, (hi - c).min(r))
                    - axis_running_sum(tables, params, (lo - c).max(-r));
                assert_eq!(
                    mass.to_bits(),
                    summed.to_bits(),
                    "{name}, x {x_axis}, pixel {q}: {mass} {summed}"
                );
                let changed = axis_window_mass(tables, &other, c, x_axis) != mass;
                let inside = hi - c >= r && lo - c <= -r;
                assert_eq!(
                    changed, inside,
                    "{name}, x {x_axis}, pixel {q}: the frame's mass taken {changed}"
                );
                interior += inside as u32;
                edge += !inside as u32;
            }
        }
        assert!(interior > 0 && edge > 0, "{name}: {interior} interior pixels, {edge} at the edge");
    }
}

/// The splatting integrators' camera samples carry a control variate (`film_splat::control_variate`):
/// a light filling the view, which every camera sample sees at one radiance, comes out of each pass
/// after the first with none of the noise of the samples' filter weights, and without bias. The noise
/// left at 32 samples is then the first pass's over 32: a thirty-second of one sample's, where
/// without the variate (each pass as noisy as the first) it is 1/√32. The light is large enough that
/// the camera hit takes the seen emitter's weight (`mis::seen_ratio_sq`).
#[test]
fn a_light_seen_directly_loses_the_filter_weights_noise_after_one_pass() {
    let scene = load_xml(
        "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>\
         <transform name=\"to_world\"><lookat target=\"0, 0, 0\" origin=\"0, 0, 5\" up=\"0, 1, 0\"/></transform>\
         <film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"30\"/>\
         <rfilter type=\"gaussian\"/></film></sensor>\
         <shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"10\" y=\"10\"/></transform>\
         <emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape></scene>",
        "control-variate",
    );
    // Pixels away from the border (where the truncated filter's weights vary less).
    let spread = |film: &Film| {
        let values: Vec<f64> = (4..26)
            .flat_map(|y| (4..36).map(move |x| (x, y)))
            .map(|(x, y)| film.rgb[y * 40 + x][1] as f64)
            .collect();
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / values.len() as f64;
        (mean, var.sqrt())
    };
    for kind in [IntegratorKind::Ibpt, IntegratorKind::Bdpt, IntegratorKind::Vcm] {
        let mut scene = scene.clone();
        scene.integrator.kind = kind;
        let (_, one) = spread(&render_scene(&scene, BackendChoice::Cpu, 1, 3));
        let (mean, many) = spread(&render_scene(&scene, BackendChoice::Cpu, 32, 3));
        println!(
            "{kind:?}: spread at 1 sample {one:.4}, at 32 {many:.5} (ratio {:.1}), mean {mean:.5}",
            one / many
        );
        assert!(one > 0.02, "{kind:?}: the first pass has the weights' noise ({one})");
        assert!(one / many > 16.0, "{kind:?}: {one} at 1 sample, {many} at 32");
        assert!((mean - 2.0).abs() < 2e-3, "{kind:?}: mean {mean}");
    }
}
