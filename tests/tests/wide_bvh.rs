//! The CPU's 4-wide BVH (`caustic::prepare::wide_bvh`, `caustic_kernel::wide_bvh`) finds what the scene's
//! BVH2 finds: the same closest hit (distance, primitive, barycentrics; of two primitives at one
//! distance, either) and the same answer to shadow queries, ray for ray, on real scenes' trees.
//! Random rays, and the hostile ones: rays exactly parallel to an axis in the plane of a box's face,
//! whose slab distance is `0 · ∞`. There the two differ by design, and only one way: BVH2 enters
//! such a box through its upper face but not its lower one, the wide BVH through both (a closed box,
//! as pbrt-v4's), so it may find a hit BVH2 missed, never miss one BVH2 found.
use caustic_kernel::bvh::Accel;
use caustic_kernel::camera::Ray;
use caustic_kernel::layout::NONE;
use caustic_tests::*;
use glam::Vec3;

/// A fixed stream of rays' numbers.
struct Stream(Xorshift);

impl Stream {
    fn next(&mut self) -> f32 {
        self.0.uniform()
    }

    fn in_box(&mut self, min: Vec3, max: Vec3) -> Vec3 {
        min + (max - min) * Vec3::new(self.next(), self.next(), self.next())
    }

    fn direction(&mut self) -> Vec3 {
        let (z, phi) = (1.0 - 2.0 * self.next(), std::f32::consts::TAU * self.next());
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

fn show(ray: &Ray) -> String {
    format!("from {} along {} to {}", ray.origin, ray.dir, ray.t_max)
}

fn compare_on(file: &str) {
    let scene = caustic::load::load_scene(&mitsuba_scene(file), &defines(&[])).expect("scene loads");
    let buffers = caustic::prepare::buffers::build(&scene).expect("scene builds");
    let wide = caustic::prepare::wide_bvh::widen(&buffers.nodes).expect("shallow enough to widen");
    let binary_view = buffers.view();
    let wide_view = caustic_kernel::layout::SceneView { nodes: &wide, wide_bvh: true, ..buffers.view() };
    let (binary, four) = (Accel::of(&binary_view), Accel::of(&wide_view));
    let root = buffers.nodes[0];
    let (lo, hi) = (Vec3::from(root.min), Vec3::from(root.max));
    let mut s = Stream(Xorshift(0x9e37_79b9_7f4a_7c15));
    let (mut rays, mut hits, mut on_faces, mut ties, mut near_ties, mut found_more) = (0, 0, 0, 0, 0, 0);
    for i in 0..40_000 {
        let ray = if i % 4 == 3 {
            // In the plane of some node's face, parallel to one axis.
            let n = buffers.nodes[(s.next() * buffers.nodes.len() as f32) as usize];
            let (axis, along) = ((s.next() * 3.0) as usize % 3, (s.next() * 2.0) as usize % 2);
            let mut origin =
                s.in_box(Vec3::from(n.min) - 0.1 * (hi - lo), Vec3::from(n.max) + 0.1 * (hi - lo));
            origin[axis] = if s.next() < 0.5 { n.min[axis] } else { n.max[axis] };
            // Both zeros: -0.0's inverse is -∞, which the wide walk turns into +∞.
            let mut dir = Vec3::splat(if s.next() < 0.5 { 0.0 } else { -0.0 });
            dir[(axis + 1 + along) % 3] = if s.next() < 0.5 { 1.0 } else { -1.0 };
            on_faces += 1;
            Ray { origin, dir, t_min: 0.0, t_max: f32::MAX }
        } else {
            let origin = s.in_box(lo - 0.2 * (hi - lo), hi + 0.2 * (hi - lo));
            let t_max = if i % 2 == 0 { f32::MAX } else { s.next() * (hi - lo).length() };
            Ray { origin, dir: s.direction(), t_min: 0.0, t_max }
        };
        let skip = if i % 5 == 0 { (s.next() * buffers.prims.len() as f32) as u32 } else { NONE };
        let in_plane = i % 4 == 3;
        let (a, b) = (binary.trace(&ray, false, skip), four.trace(&ray, false, skip));
        rays += 1;
        // The wide BVH's hit is a real hit of its primitive at its distance, and not the skipped one.
        let real = |h: &caustic_kernel::shape::Hit| {
            h.prim != skip && {
                let shear = caustic_kernel::shape::triangle::RayShear::of(&ray);
                let prim = &buffers.prims[h.prim as usize];
                caustic_kernel::shape::intersect(prim, &ray, &shear, f32::MAX).map(|(t, _)| t) == Some(h.t)
            }
        };
        match (a, b) {
            (None, None) => {}
            (Some(a), Some(b)) if a.t.to_bits() == b.t.to_bits() => {
                hits += 1;
                // Two primitives at one distance (a shared edge): which is tested first wins.
                ties += (a.prim != b.prim) as u32;
                assert!(
                    a.prim == b.prim && a.uv == b.uv || real(&b),
                    "{file}: ray {i} {}: a false tie",
                    show(&ray)
                );
            }
            // Coplanar surfaces (cbox's floor under the short box's base): the triangle test's
            // distances for the two differ by some ulps, a box's entry distance may fall between them,
            // and which one a walk reports depends on which it met first.
            (Some(a), Some(b)) if (a.t - b.t).abs() <= 1e-5 * a.t && real(&b) => {
                hits += 1;
                near_ties += 1;
            }
            // A ray in a face's plane: BVH2's slab of 0 · ∞ = NaN shuts the box at its lower face
            // (`bvh::intersect_aabb`), the wide BVH's does not, so it may find a nearer hit.
            (a, Some(b)) if in_plane && a.is_none_or(|a| b.t < a.t) && real(&b) => {
                hits += 1;
                found_more += 1;
            }
            (a, b) => panic!(
                "{file}: ray {i} {}: BVH2 found {:?}, the wide BVH {:?}",
                show(&ray),
                a.map(|h| (h.t, h.prim)),
                b.map(|h| (h.t, h.prim))
            ),
        }
        let (a, b) = (binary.occluded(&ray, skip), four.occluded(&ray, skip));
        assert!(a == b || in_plane && b, "{file}: shadow ray {i} {}: BVH2 {a}, wide BVH {b}", show(&ray));
    }
    println!(
        "{file}: {rays} rays ({on_faces} in faces' planes), {hits} hits, {ties} ties between primitives, \
         {near_ties} within rounding, {found_more} in-plane hits BVH2 missed"
    );
    // Not a vacuous comparison: most random rays through the scene's box hit something.
    assert!(hits > rays / 4, "{file}: only {hits} hits of {rays} rays");
}

#[test]
fn the_wide_bvh_finds_what_bvh2_finds_on_the_bunny() {
    compare_on("docs/scenes/shape_ply_bunny.xml");
}

#[test]
fn the_wide_bvh_finds_what_bvh2_finds_on_the_material_preview() {
    compare_on("docs/scenes/bsdf_dielectric_glass.xml");
}

#[test]
fn the_wide_bvh_finds_what_bvh2_finds_in_the_cornell_box() {
    // Axis-aligned walls: the face-plane rays graze them.
    compare_on("scenes/cbox/cbox.xml");
}
