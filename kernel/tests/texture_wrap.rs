//! Texel addressing without panic paths (`texture::wrap`, `texture::rem`): the same texels as the
//! `rem_euclid` and `clamp` they replace, for every wrap mode, over negative, large and extreme
//! coordinates.
use caustic_kernel::layout::{
    TEXTURE_WRAP_CLAMP, TEXTURE_WRAP_MIRROR, TEXTURE_WRAP_REPEAT, TEXTURE_WRAP_SHIFT,
};
use caustic_kernel::texture::{rem, wrap};

/// What `wrap` computed before: Mitsuba's modes through `i32::rem_euclid` and `i32::clamp`.
fn reference(i: i32, n: u32, mode: u32) -> u32 {
    let n = n as i32;
    (if mode == TEXTURE_WRAP_CLAMP {
        i.clamp(0, n - 1)
    } else if mode == TEXTURE_WRAP_MIRROR {
        let period = i.rem_euclid(2 * n);
        if period < n {
            period
        } else {
            2 * n - 1 - period
        }
    } else {
        i.rem_euclid(n)
    }) as u32
}

#[test]
fn wrapping_matches_rem_euclid_and_clamp_for_every_mode() {
    let extremes = [i32::MIN, i32::MIN + 1, -(1 << 24), -65537, 65535, 1 << 24, i32::MAX - 1, i32::MAX];
    let mut checked = 0;
    for mode in [TEXTURE_WRAP_REPEAT, TEXTURE_WRAP_MIRROR, TEXTURE_WRAP_CLAMP] {
        for n in (1..=17).chain([255, 256, 4096, 8191]) {
            for i in (-70..70).chain(extremes) {
                let got = wrap(i, n, mode << TEXTURE_WRAP_SHIFT);
                assert_eq!(got, reference(i, n, mode), "i {i}, size {n}, mode {mode}");
                assert!(got < n);
                checked += 1;
            }
        }
    }
    assert!(checked > 3 * 21 * 140);
}

#[test]
fn the_remainder_is_the_operators_and_never_divides_by_zero() {
    for n in 1..40u32 {
        for a in (0..200u32).chain([u32::MAX - 1, u32::MAX]) {
            assert_eq!(rem(a, n), a % n);
        }
    }
    // A zero size (which the host never makes) gives the coordinate back instead of a panic.
    assert_eq!(rem(7, 0), 7);
    assert_eq!(wrap(-3, 0, TEXTURE_WRAP_REPEAT << TEXTURE_WRAP_SHIFT), 0);
}
