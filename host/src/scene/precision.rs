//! Where f32 precision ends for a scene: rays leave a surface at least `RAY_EPSILON · max(|p|∞, the
//! primitive's coordinates)` off it (`caustic_kernel::shape::offset_origin`), so a primitive small
//! against its own distance from the origin sits among features the offset jumps: light leaks
//! through gaps and shadows go wrong. The loader warns once, naming the ratio.
use crate::scene::{Geometry, Scene};
use caustic_kernel::shape::RAY_EPSILON;
use glam::Vec3;

/// Primitives at least this many ray offsets across render right: measured on a 2-unit box with a
/// sphere of radius 0.35 and a lamp 0.02 under its ceiling, moved by 1e3 (the sphere 3.9 offsets
/// across) it renders the unit box's image; moved by 1e4 (0.39) or scaled 1e-2 and moved by 1e3
/// (0.04) it does not.
const MIN_OFFSETS_ACROSS: f32 = 2.0;

/// The primitive smallest against its distance from the origin: `(size, magnitude)`, its size (a
/// triangle's longest edge, as a sliver is as wide as it is long to a ray offset; a sphere's radius;
/// a disk's larger semi-axis) and the largest coordinate magnitude it reaches (the scale of its
/// points' rounding). Zero-sized primitives are left out; `None` without any other.
pub fn least_resolved(scene: &Scene) -> Option<(f32, f32)> {
    let mut worst: Option<(f32, f32)> = None;
    let mut consider = |size: f32, magnitude: f32| {
        if size > 0.0 && size.is_finite() && magnitude.is_finite() {
            let ratio = |(s, m): (f32, f32)| s / m.max(f32::MIN_POSITIVE);
            if worst.is_none_or(|w| ratio((size, magnitude)) < ratio(w)) {
                worst = Some((size, magnitude));
            }
        }
    };
    for shape in &scene.shapes {
        match &shape.geometry {
            Geometry::Triangles { triangles, .. } => {
                for t in triangles {
                    if (t[1] - t[0]).cross(t[2] - t[0]).length_squared() > 0.0 {
                        let longest =
                            (t[1] - t[0]).length().max((t[2] - t[0]).length()).max((t[2] - t[1]).length());
                        consider(longest, t[0].abs().max(t[1].abs()).max(t[2].abs()).max_element());
                    }
                }
            }
            Geometry::Sphere { center, radius, .. } => {
                consider(*radius, (center.abs() + Vec3::splat(radius.abs())).max_element());
            }
            Geometry::Disk { center, u, v } => {
                consider(u.length().max(v.length()), (center.abs() + u.abs() + v.abs()).max_element());
            }
        }
    }
    worst
}

/// The warning for a scene with a primitive fewer than `MIN_OFFSETS_ACROSS` ray offsets across at
/// its own distance from the origin, or `None`.
pub fn warning(scene: &Scene) -> Option<String> {
    let (size, magnitude) = least_resolved(scene)?;
    let offset = magnitude * RAY_EPSILON;
    (size < MIN_OFFSETS_ACROSS * offset).then(|| {
        format!(
            "float precision: a shape {size:.3e} across lies {magnitude:.3e} from the origin (ratio \
             {:.2e}, below {:.1e}); rays leave surfaces {offset:.2e} off them there, so features that \
             small may leak light or shadow wrongly (move the scene towards the origin)",
            size / magnitude,
            MIN_OFFSETS_ACROSS * RAY_EPSILON
        )
    })
}
