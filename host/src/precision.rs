//! Where f32 precision ends for a scene: rays leave surfaces `RAY_EPSILON · |p|` off them
//! (`caustic_kernel::shape::offset_origin`), so a scene far from the origin against the size of
//! its primitives leaks light through, or shadows wrongly across, features smaller than that.
//! The loader warns once, naming the ratio.
use crate::scene::{Geometry, Scene};
use caustic_kernel::shape::RAY_EPSILON;
use glam::Vec3;

/// Primitives at least this many ray offsets across render right: measured on a 2-unit box with
/// a sphere of radius 0.35 and a lamp 0.02 under its ceiling, moved by 1e3 (the sphere 3.9 offsets
/// across) it renders the unit box's image; moved by 1e4 (0.39) or scaled 1e-2 and moved by 1e3
/// (0.04) it does not.
const MIN_OFFSETS_ACROSS: f32 = 2.0;

/// The scene's extent (largest coordinate magnitude of any shape) and its smallest primitive's size
/// (a triangle's longest edge: a sliver is as wide as it is long to a ray offset; a sphere's radius;
/// a disk's larger semi-axis), ignoring zero-sized ones. `None` without shapes.
pub fn extent_and_smallest(scene: &Scene) -> Option<(f32, f32)> {
    let (mut extent, mut smallest) = (0.0f32, f32::INFINITY);
    let mut size = |s: f32| {
        if s > 0.0 && s.is_finite() {
            smallest = smallest.min(s);
        }
    };
    for shape in &scene.shapes {
        match &shape.geometry {
            Geometry::Triangles { triangles, .. } => {
                for t in triangles {
                    extent = extent.max(t[0].abs().max(t[1].abs()).max(t[2].abs()).max_element());
                    let longest =
                        (t[1] - t[0]).length().max((t[2] - t[0]).length()).max((t[2] - t[1]).length());
                    if (t[1] - t[0]).cross(t[2] - t[0]).length_squared() > 0.0 {
                        size(longest);
                    }
                }
            }
            Geometry::Sphere { center, radius } => {
                extent = extent.max((center.abs() + Vec3::splat(radius.abs())).max_element());
                size(*radius);
            }
            Geometry::Disk { center, u, v } => {
                extent = extent.max((center.abs() + u.abs() + v.abs()).max_element());
                size(u.length().max(v.length()));
            }
        }
    }
    smallest.is_finite().then_some((extent, smallest))
}

/// The warning for a scene whose smallest primitive is fewer than `MIN_OFFSETS_ACROSS` ray
/// offsets across at the scene's extent, or `None`.
pub fn warning(scene: &Scene) -> Option<String> {
    let (extent, smallest) = extent_and_smallest(scene)?;
    let offset = extent * RAY_EPSILON;
    (smallest < MIN_OFFSETS_ACROSS * offset).then(|| {
        format!(
            "float precision: the scene reaches {extent:.3e} from the origin and its smallest shape is \
             {smallest:.3e} across (ratio {:.2e}); rays leave surfaces {offset:.2e} off them there, so \
             features that small may leak light or shadow wrongly (move the scene to the origin or \
             scale it down; below a ratio of {:.1e} invariance is lost)",
            smallest / extent,
            MIN_OFFSETS_ACROSS * RAY_EPSILON
        )
    })
}
