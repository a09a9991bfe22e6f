//! The BVH2 over the primitives (built by `obvhs`), the primitives reordered into its leaf order,
//! and the scene's bounding sphere.
use anyhow::Result;
use caustic_kernel::bvh::STACK_SIZE;
use caustic_kernel::layout::*;
use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;

fn bounds(p: &Primitive) -> Aabb {
    if p.kind == PRIM_INSTANCE {
        Aabb::new(Vec3A::from(p.p0), Vec3A::from(p.p2))
    } else if p.kind == PRIM_SPHERE {
        let c = Vec3A::from(p.p0);
        let r = Vec3A::splat(p.p1[0]);
        Aabb::new(c - r, c + r)
    } else if p.kind == PRIM_DISK {
        // The ellipse c + a·u + b·v reaches ±sqrt(u_i² + v_i²) along each axis.
        let (c, u, v) = (Vec3A::from(p.p0), Vec3A::from(p.p1), Vec3A::from(p.p2));
        let r = (u * u + v * v).sqrt();
        Aabb::new(c - r, c + r)
    } else {
        let (a, b, c) = (Vec3A::from(p.p0), Vec3A::from(p.p1), Vec3A::from(p.p2));
        Aabb::new(a.min(b).min(c), a.max(b).max(c))
    }
}

/// obvhs's medium preset with more reinsertion work and a collapse cost that keeps leaves small.
/// Measured on the H100 (2026-11-22) against the plain preset: cbox 175 → 239 Msamples/s, material
/// previews +20% (glass 59 → 72, diffuse 113 → 136), the PLY bunny 131 → 165; the build of a
/// 62k-triangle mesh takes ~0.1 s. One H100 call on 2026-11-27 (each setting interleaved) moved the
/// collapse cost from 1 to 0.5 and the reinsertion ratio from 0.2 to 0.6: glass +6.0%, the diamond
/// +5.8%, cbox +4.1%, copper +4.1%, diffuse +2.5%, the bunny +1.6%; the build takes about twice as
/// long, so scenes past `MORE_REINSERTION_UP_TO` primitives keep 0.2. obvhs builds on rayon's threads
/// (its `parallel` feature, same tree): on the H100 machine's 16 cores a 10M-triangle scene's
/// buffers and BVH took 41.4 s single-threaded and 7.6 s so (BENCHMARKS.md, "Large scenes").
fn bvh_build_params(primitives: usize) -> obvhs::BvhBuildParams {
    obvhs::BvhBuildParams {
        reinsertion_batch_ratio: if primitives <= MORE_REINSERTION_UP_TO { 0.6 } else { 0.2 },
        collapse_traversal_cost: 0.5,
        ..obvhs::BvhBuildParams::medium_build()
    }
}

/// The largest scene (in primitives) whose BVH gets the costlier reinsertion: about 1 s of build on
/// the H100 machine's 16 cores, where the 10M-triangle scene's 7.6 s would double.
const MORE_REINSERTION_UP_TO: usize = 1 << 20;

/// Builds the BVH and reorders primitives (and what refers to them) into leaf order.
pub(crate) fn build_bvh(
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    origins: &mut Vec<[u32; 2]>,
    lights: &mut [Light],
) -> Result<Vec<BvhNode>> {
    build_bvh_reordering(prims, attributes, origins, lights).map(|(nodes, _)| nodes)
}

/// `build_bvh`, also returning each primitive's new index (by its index before).
pub(super) fn build_bvh_reordering(
    prims: &mut Vec<Primitive>,
    attributes: &mut Vec<TriangleAttributes>,
    origins: &mut Vec<[u32; 2]>,
    lights: &mut [Light],
) -> Result<(Vec<BvhNode>, Vec<u32>)> {
    let aabbs: Vec<Aabb> = prims.iter().map(bounds).collect();
    let mut build_time = std::time::Duration::ZERO;
    let bvh = obvhs::bvh2::builder::build_bvh2(&aabbs, bvh_build_params(aabbs.len()), &mut build_time);
    let (nodes, order) = if bvh.nodes.is_empty() || bvh.depth(0) < STACK_SIZE {
        let nodes = bvh.nodes.iter().map(|n| node_of(&n.aabb, n.prim_count, n.first_index)).collect();
        (nodes, bvh.primitive_indices.clone())
    } else {
        within_depth(&bvh, STACK_SIZE - 1)
    };
    let order = &order;
    let mut new_index = vec![0u32; prims.len()];
    for (new, &old) in order.iter().enumerate() {
        new_index[old as usize] = new as u32;
    }
    *prims = order.iter().map(|&i| prims[i as usize]).collect();
    *attributes = order.iter().map(|&i| attributes[i as usize]).collect();
    if !origins.is_empty() {
        *origins = order.iter().map(|&i| origins[i as usize]).collect();
    }
    for l in lights.iter_mut().filter(|l| matches!(l.kind, LIGHT_AREA | LIGHT_SPHERE)) {
        l.prim = new_index[l.prim as usize];
    }
    inside_buffers(&nodes, prims.len())?;
    Ok((nodes, new_index))
}

/// Checks that every child index and leaf range of `nodes` lies inside the node and primitive
/// buffers: the kernel's traversals read them without bounds checks (`Accel::trace`).
pub(super) fn inside_buffers(nodes: &[BvhNode], prims: usize) -> Result<()> {
    for (i, n) in nodes.iter().enumerate() {
        let (first, count) = (n.first as usize, n.prim_count as usize);
        let inside = if count > 0 { first + count <= prims } else { first + 1 < nodes.len() };
        anyhow::ensure!(inside, "internal error: BVH node {i} points past the buffers ({first}, {count})");
    }
    Ok(())
}

fn node_of(aabb: &Aabb, prim_count: u32, first: u32) -> BvhNode {
    BvhNode { min: aabb.min.to_array(), prim_count, max: aabb.max.to_array(), first }
}

/// The BVH laid out again, depth first, with every subtree that reaches `levels` deep collapsed
/// into one leaf of all its primitives, and the primitive order that goes with it. Triangles that
/// coincide cannot be told apart by any split: 100 copies of one triangle made obvhs a chain 93
/// levels deep, past the kernel's traversal stack (`STACK_SIZE`); a leaf of them is what such input
/// deserves. Trees within the stack keep obvhs's layout untouched.
fn within_depth(bvh: &obvhs::bvh2::Bvh2, levels: usize) -> (Vec<BvhNode>, Vec<u32>) {
    let mut nodes = vec![BvhNode::default()];
    let mut order = Vec::with_capacity(bvh.primitive_indices.len());
    let mut stack = vec![(0usize, 0usize, 1usize)]; // (node in bvh, node in `nodes`, its level)
    while let Some((old, new, level)) = stack.pop() {
        let n = &bvh.nodes[old];
        if n.is_leaf() || level == levels {
            let first = order.len() as u32;
            let mut subtree = vec![old];
            while let Some(i) = subtree.pop() {
                let m = &bvh.nodes[i];
                if m.is_leaf() {
                    let range = m.first_index as usize..(m.first_index + m.prim_count) as usize;
                    order.extend_from_slice(&bvh.primitive_indices[range]);
                } else {
                    subtree.extend([m.first_index as usize + 1, m.first_index as usize]);
                }
            }
            nodes[new] = node_of(&n.aabb, order.len() as u32 - first, first);
        } else {
            let children = nodes.len();
            nodes.extend([BvhNode::default(); 2]);
            nodes[new] = node_of(&n.aabb, 0, children as u32);
            stack.push((n.first_index as usize + 1, children + 1, level + 1));
            stack.push((n.first_index as usize, children, level + 1));
        }
    }
    (nodes, order)
}

/// The scene's bounding sphere (centre, radius), slightly enlarged as Mitsuba does for emitters at
/// infinity; a unit sphere for an empty scene.
pub(super) fn bounding_sphere(nodes: &[BvhNode], has_prims: bool) -> (Vec3, f32) {
    if !has_prims {
        return (Vec3::ZERO, 1.0);
    }
    let (lo, hi) = (Vec3::from(nodes[0].min), Vec3::from(nodes[0].max));
    let centre = 0.5 * (lo + hi);
    (centre, (0.5 * (hi - lo).length() * (1.0 + 1e-4)).max(1e-4))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaf(first: u32, count: u32) -> BvhNode {
        BvhNode { prim_count: count, first, ..Default::default() }
    }

    #[test]
    fn trees_that_point_past_their_buffers_are_refused() {
        // A root over two leaves of two primitives each.
        let good = [leaf(1, 0), leaf(0, 2), leaf(2, 2)];
        assert!(inside_buffers(&good, 4).is_ok());
        assert!(inside_buffers(&good, 3).is_err(), "a leaf past the primitives");
        let far_child = [leaf(2, 0), leaf(0, 2), leaf(2, 2)];
        assert!(inside_buffers(&far_child, 4).is_err(), "a child past the nodes");
        assert!(inside_buffers(&[], 0).is_ok());
    }

    #[test]
    fn built_trees_lie_inside_their_buffers() {
        // Coincident triangles, whose tree `within_depth` lays out again, and a row of distinct ones.
        for coincident in [true, false] {
            let mut prims: Vec<Primitive> = (0..300)
                .map(|i| {
                    let x = if coincident { 0.0 } else { i as f32 };
                    Primitive {
                        p0: [x, 0.0, 0.0],
                        p1: [x + 1.0, 0.0, 0.0],
                        p2: [x, 1.0, 0.0],
                        ..Default::default()
                    }
                })
                .collect();
            let mut attributes = vec![TriangleAttributes::default(); prims.len()];
            let nodes = build_bvh(&mut prims, &mut attributes, &mut Vec::new(), &mut []).unwrap();
            assert!(inside_buffers(&nodes, prims.len()).is_ok());
        }
    }
}
