//! The reconstruction filter as the kernel samples it (`caustic_kernel::film`): tabulated over
//! `[-radius, radius]`, with a signed running sum beside the CDF for filters with negative lobes.
use crate::scene::Filter;
use anyhow::{bail, Result};

/// The tabulated 1D filter over [-radius, radius] (`caustic_kernel::film`): the inclusive CDF of |w|,
/// normalised to end at 1, then, for a filter with negative lobes, the running sum of the signed
/// weight w in the same units (so that each bin's signed mass over its absolute mass is the sign, or
/// between -1 and 1 in a bin where w changes sign). Fails if the signed weight sums to zero or less.
pub fn filter_tables(filter: &Filter, bins: u32) -> Result<(Vec<f32>, bool)> {
    const SUB: usize = 32;
    let r = filter.radius();
    let width = 2.0 * r / bins as f32;
    let (mut abs_sum, mut signed_sum) = (0.0f64, 0.0f64);
    let mut cumulative = Vec::with_capacity(bins as usize);
    for b in 0..bins {
        let mut mass = 0.0f64;
        let mut abs_mass = 0.0f64;
        for s in 0..SUB {
            let x = -r + (b as f32 + (s as f32 + 0.5) / SUB as f32) * width;
            let w = filter.weight(x) as f64;
            mass += w;
            abs_mass += w.abs();
        }
        abs_sum += abs_mass;
        signed_sum += mass;
        cumulative.push((abs_sum, signed_sum));
    }
    if signed_sum.is_nan() || signed_sum <= 0.0 {
        bail!("the reconstruction filter {filter:?} has no positive total weight");
    }
    let mut tables: Vec<f32> = cumulative.iter().map(|&(a, _)| (a / abs_sum) as f32).collect();
    let signed = cumulative.iter().any(|&(a, s)| s != a);
    if signed {
        tables.extend(cumulative.iter().map(|&(_, s)| (s / abs_sum) as f32));
    }
    Ok((tables, signed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use caustic_kernel::film::{pixel_density, pixel_weight, sample_position};
    use caustic_kernel::glam::Vec2;
    use caustic_kernel::layout::{FrameParams, SAMPLER_STRATIFIED};
    use caustic_kernel::rng::Sampler;

    const BINS: u32 = 64;
    /// A small image, so that the filters (radius up to 3) are truncated at its border.
    const SIZE: (u32, u32) = (7, 6);
    /// Pixels at a corner, inside, and at the opposite corner.
    const PIXELS: [(u32, u32); 3] = [(0, 0), (3, 2), (6, 5)];

    fn params(filter: &Filter, strata: u32) -> (FrameParams, Vec<f32>) {
        let (tables, signed) = filter_tables(filter, BINS).expect("tabulates");
        let mut params = FrameParams {
            width: SIZE.0,
            height: SIZE.1,
            full_width: SIZE.0,
            full_height: SIZE.1,
            sampler: SAMPLER_STRATIFIED,
            spp_total: strata * strata,
            filter_bins: BINS,
            filter_radius: filter.radius(),
            filter_signed: signed as u32,
            ..Default::default()
        };
        (params.filter_abs_mass, params.filter_mass) = caustic_kernel::film::whole_masses(&tables, &params);
        (params, tables)
    }

    /// ∫w(t)·t^k over the part of the filter centred at `c` inside [0, `full`] (fine midpoint rule on the
    /// exact filter, not the table).
    fn moment(filter: &Filter, c: f64, full: f64, k: i32, abs: bool) -> f64 {
        let r = filter.radius() as f64;
        let (lo, hi) = ((-c).max(-r), (full - c).min(r));
        let n = 200_000;
        let h = (hi - lo) / n as f64;
        (0..n)
            .map(|i| {
                let t = lo + (i as f64 + 0.5) * h;
                let w = filter.weight(t as f32) as f64;
                (if abs { w.abs() } else { w }) * t.powi(k) * h
            })
            .sum()
    }

    /// The filtered mean of g = dx² + dy² (offsets from the pixel centre) for pixel (`px`, `py`).
    fn filtered_second_moment(filter: &Filter, px: u32, py: u32, abs: bool) -> f64 {
        let axis = |p: u32, full: u32| {
            let c = p as f64 + 0.5;
            moment(filter, c, full as f64, 2, abs) / moment(filter, c, full as f64, 0, abs)
        };
        axis(px, SIZE.0) + axis(py, SIZE.1)
    }

    const SIGNED: [Filter; 4] = [
        Filter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 },
        Filter::Mitchell { b: 0.0, c: 0.5 },
        Filter::Lanczos { lobes: 3 },
        Filter::Lanczos { lobes: 2 },
    ];

    #[test]
    fn non_negative_filters_keep_one_table_and_weight_one() {
        for filter in [
            Filter::Box { radius: 0.5 },
            Filter::Tent { radius: 1.0 },
            Filter::Gaussian { stddev: 0.5, radius: 2.0 },
        ] {
            let (params, tables) = params(&filter, 4);
            assert_eq!((params.filter_signed, tables.len()), (0, BINS as usize), "{filter:?}");
            for i in 0..16 {
                let s = sample_position(&params, &tables, 0, 0, i, &mut Sampler::new(1, 0, i));
                assert_eq!(s.weight, 1.0, "{filter:?}");
                let pos = Vec2::new(s.pos.x * SIZE.0 as f32, s.pos.y * SIZE.1 as f32);
                let d = pixel_density(&tables, &params, pos, 0, 0);
                assert_eq!(pixel_weight(&tables, &params, pos, 0, 0).to_bits(), d.to_bits(), "{filter:?}");
            }
        }
    }

    /// Camera samples (drawn ∝ |w| over 256² strata, weighted by sign·∫|w|/∫w) average to the pixel's
    /// filtered mean under the signed filter, truncated at the border, both for g = 1 and for
    /// g = dx² + dy²; the |w| filter's mean of g is far off (so the check can fail).
    #[test]
    fn signed_camera_samples_estimate_the_signed_filter() {
        let strata = 256;
        for filter in SIGNED {
            let (params, tables) = params(&filter, strata);
            assert_eq!(params.filter_signed, 1);
            for (px, py) in PIXELS {
                let pixel = py * SIZE.0 + px;
                let (mut sum_w, mut sum_wg) = (0.0f64, 0.0f64);
                for i in 0..strata * strata {
                    let s = sample_position(&params, &tables, px, py, i, &mut Sampler::new(1, pixel, i));
                    let dx = (s.pos.x * SIZE.0 as f32 - (px as f32 + 0.5)) as f64;
                    let dy = (s.pos.y * SIZE.1 as f32 - (py as f32 + 0.5)) as f64;
                    sum_w += s.weight as f64;
                    sum_wg += s.weight as f64 * (dx * dx + dy * dy);
                }
                let n = (strata * strata) as f64;
                let (mean_w, mean_g) = (sum_w / n, sum_wg / n);
                let expected = filtered_second_moment(&filter, px, py, false);
                let unsigned = filtered_second_moment(&filter, px, py, true);
                println!(
                    "{filter:?} pixel ({px}, {py}): E[weight] {mean_w:.5}, E[weight·g] {mean_g:.5}, exact {expected:.5} (|w|: {unsigned:.5})"
                );
                assert!((mean_w - 1.0).abs() < 2e-3, "{filter:?} ({px}, {py}): mean weight {mean_w}");
                assert!(
                    (mean_g - expected).abs() < 5e-3,
                    "{filter:?} ({px}, {py}): {mean_g} against {expected}"
                );
                assert!((unsigned - expected).abs() > 0.05, "{filter:?}: |w| indistinguishable");
            }
        }
    }

    /// Light tracing's splat weight (`pixel_weight`) integrates over the film to 1 and to the same
    /// filtered mean of g as the camera samples: splats and camera samples estimate one pixel.
    #[test]
    fn splat_weights_integrate_to_the_signed_filter() {
        for filter in SIGNED {
            let (params, tables) = params(&filter, 1);
            for (px, py) in PIXELS {
                let steps = 64; // per pixel and axis
                let h = 1.0 / steps as f64;
                let (mut total, mut total_g) = (0.0f64, 0.0f64);
                for j in 0..SIZE.1 * steps {
                    for i in 0..SIZE.0 * steps {
                        let (x, y) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                        let w = pixel_weight(&tables, &params, Vec2::new(x as f32, y as f32), px, py) as f64;
                        let (dx, dy) = (x - (px as f64 + 0.5), y - (py as f64 + 0.5));
                        total += w * h * h;
                        total_g += w * (dx * dx + dy * dy) * h * h;
                    }
                }
                let expected = filtered_second_moment(&filter, px, py, false);
                assert!((total - 1.0).abs() < 1e-3, "{filter:?} ({px}, {py}): splat weights sum to {total}");
                assert!(
                    (total_g - expected).abs() < 5e-3,
                    "{filter:?} ({px}, {py}): splats' mean of g {total_g} against {expected}"
                );
            }
        }
    }
}
