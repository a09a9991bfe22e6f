//! Splatting (`caustic_kernel::splat`): signed 64-bit fixed-point sums added with 32-bit words, the
//! same whatever the order of the additions, unbiased by their stochastic rounding, and never adding
//! what is not finite or out of range.
use caustic_kernel::glam::Vec3;
use caustic_kernel::layout::PixelAccum;
use caustic_kernel::splat::*;

fn words() -> [u32; SPLAT_STRIDE as usize] {
    [0; SPLAT_STRIDE as usize]
}

fn sum_of(w: &[u32; SPLAT_STRIDE as usize]) -> PixelAccum {
    let zero = PixelAccum { sum: [0.0; 3], count: 0.0, sum_sq: [0.0; 3], invalid: 0.0 };
    resolved(zero, *w, 1, 1.0)
}

#[test]
fn signed_sums_do_not_depend_on_the_order() {
    let values = [3.25f32, -1.5, 1.0e6, -0.125, -1.0e6, 7.0e-3, -2.0e-7, 12.5];
    let mut forward = words();
    for (i, v) in values.iter().enumerate() {
        splat(&mut OwnWords(&mut forward), 0, Vec3::new(*v, -*v, 0.5 * v), (i as f32 * 0.37).fract());
    }
    let mut backward = words();
    for (i, v) in values.iter().enumerate().rev() {
        splat(&mut OwnWords(&mut backward), 0, Vec3::new(*v, -*v, 0.5 * v), (i as f32 * 0.37).fract());
    }
    assert_eq!(forward, backward, "integer sums are order-independent");
    let s = sum_of(&forward).sum;
    let exact: f64 = values.iter().map(|&v| v as f64).sum();
    println!("sum {s:?}, exact {exact}");
    for (c, e) in [(s[0], exact), (s[1], -exact), (s[2], 0.5 * exact)] {
        assert!((c as f64 - e).abs() < 1e-5, "sum {c}, expected {e}");
    }
}

/// A small negative total keeps its precision (the words are negated before converting).
#[test]
fn small_negative_sums_are_exact() {
    let mut w = words();
    splat(&mut OwnWords(&mut w), 0, Vec3::new(-0.25, -1.0e-3, -3.0), 0.0);
    splat(&mut OwnWords(&mut w), 0, Vec3::new(0.125, 0.0, 1.0), 0.0);
    let s = sum_of(&w).sum;
    // With u = 0 the magnitude rounds down to the fixed-point grid (2⁻²⁴).
    let grid = (1u32 << SPLAT_FRACTION_BITS) as f32;
    let thousandth = -(1.0e-3f32 * grid).floor() / grid;
    assert_eq!(s, [-0.125, thousandth, -2.0]);
}

/// Stochastic rounding is unbiased: a value far below the resolution still sums to its expectation.
#[test]
fn stochastic_rounding_is_unbiased() {
    let tiny = 1.0e-9f32; // 1/60 of the resolution 2⁻²⁴
    let n = 200_000;
    for sign in [1.0f32, -1.0] {
        let mut w = words();
        let mut rng = caustic_kernel::rng::Sampler::new(3, 0, 0);
        for _ in 0..n {
            splat(&mut OwnWords(&mut w), 0, Vec3::splat(sign * tiny), rng.next_1d());
        }
        let s = sum_of(&w).sum[0] as f64;
        let expected = sign as f64 * tiny as f64 * n as f64;
        // The count of round-ups is binomial: 5 standard deviations.
        let sd = ((n as f64) * 0.0168).sqrt() * 2f64.powi(-24);
        assert!((s - expected).abs() < 5.0 * sd, "sum {s:e}, expected {expected:e} ± {sd:e}");
    }
}

#[test]
fn invalid_values_are_counted_not_added() {
    let mut w = words();
    for v in [f32::NAN, f32::INFINITY, -f32::INFINITY, SPLAT_MAX, -SPLAT_MAX * 2.0] {
        splat(&mut OwnWords(&mut w), 0, Vec3::new(1.0, v, 1.0), 0.5);
    }
    let a = sum_of(&w);
    assert_eq!(a.sum, [0.0; 3], "nothing of a rejected splat is added");
    assert_eq!(a.invalid, 5.0);
}
