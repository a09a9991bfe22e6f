//! The wide BVH's slab operations (`caustic_kernel::wide_bvh`) drop the NaNs its traversal relies on
//! dropping, on the machine that runs the tests: `less_or(a, b)` is `a` only where `a < b`, and
//! `greater_or(a, b)` only where `a > b` (a NaN on either side yields `b`).
use caustic_kernel::glam::Vec4;
use caustic_kernel::wide_bvh::{greater_or, less_or};

#[test]
fn slab_operations_yield_b_wherever_a_nan_takes_part() {
    let nan = f32::NAN;
    let a = Vec4::new(nan, 1.0, 2.0, f32::NEG_INFINITY);
    let b = Vec4::new(3.0, nan, 1.0, f32::INFINITY);
    let min = less_or(a, b).to_array();
    assert_eq!(min[0], 3.0, "NaN in a: b");
    assert!(min[1].is_nan(), "NaN in b: b");
    assert_eq!(&min[2..], &[1.0, f32::NEG_INFINITY]);
    let max = greater_or(a, b).to_array();
    assert_eq!(max[0], 3.0, "NaN in a: b");
    assert!(max[1].is_nan(), "NaN in b: b");
    assert_eq!(&max[2..], &[2.0, f32::INFINITY]);
}
