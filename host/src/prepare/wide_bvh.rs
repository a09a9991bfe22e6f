//! The CPU backend's 4-wide BVH (`caustic_kernel::wide_bvh`), collapsed from the scene's BVH2: each
//! inner node's children are opened, the one of largest surface area first, until it has four
//! (pbrt-v3's and Embree's collapse of a binary tree), and the leaves stay as they were, so the
//! primitive buffer serves both.
use caustic_kernel::layout::{BvhNode, NONE};
use caustic_kernel::wide_bvh::{Group, WIDE_DEPTH};

/// Half the surface area of a node's box (enough to compare).
fn half_area(n: &BvhNode) -> f32 {
    let d = [n.max[0] - n.min[0], n.max[1] - n.min[1], n.max[2] - n.min[2]];
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// The up-to-four BVH2 nodes under inner node `n` that become one group's children, and how many.
fn children(nodes: &[BvhNode], n: usize) -> ([usize; 4], usize) {
    let first = nodes[n].first as usize;
    let (mut open, mut len) = ([first, first + 1, 0, 0], 2);
    while len < 4 {
        let inner = (0..len)
            .filter(|&i| nodes[open[i]].prim_count == 0)
            .max_by(|&i, &j| half_area(&nodes[open[i]]).total_cmp(&half_area(&nodes[open[j]])));
        let Some(i) = inner else { break };
        let first = nodes[open[i]].first as usize;
        (open[i], open[len]) = (first, first + 1);
        len += 1;
    }
    (open, len)
}

/// The wide BVH of `nodes` (a BVH2 of the layout `bvh::build_bvh` makes) as the kernel's walk reads it
/// (`collapse`, then `by_lane`), or `None` where `collapse` gives none.
pub fn widen(nodes: &[BvhNode]) -> Option<Vec<BvhNode>> {
    let mut groups = collapse(nodes)?;
    by_lane(&mut groups);
    Some(groups)
}

/// Rewrites each group of four child records in place as the `Group` they occupy: the same children,
/// their bounds in rows of four lanes.
pub fn by_lane(groups: &mut [BvhNode]) {
    for records in groups.chunks_exact_mut(4) {
        let mut g = Group::default();
        for (lane, c) in records.iter().enumerate() {
            for axis in 0..3 {
                g.bounds[axis][lane] = c.min[axis];
                g.bounds[3 + axis][lane] = c.max[axis];
            }
            g.first[lane] = c.first;
            g.prim_count[lane] = c.prim_count;
        }
        bytemuck::cast_slice_mut::<BvhNode, Group>(records)[0] = g;
    }
}

/// The wide BVH of `nodes` in child records (four a group), or `None` when it
/// would nest deeper than the traversal's stack allows (`WIDE_DEPTH`: a child left unopened goes
/// down one BVH2 level per group, so a lopsided BVH2 within its own stack may not fit) or `nodes` is
/// empty.
pub fn collapse(nodes: &[BvhNode]) -> Option<Vec<BvhNode>> {
    let empty = BvhNode { first: NONE, ..Default::default() };
    let root = nodes.first()?;
    let mut out = vec![empty; 4];
    // (group in `out`, its BVH2 children, its depth in groups)
    let mut pending =
        vec![(0usize, if root.prim_count > 0 { ([0; 4], 1) } else { children(nodes, 0) }, 1usize)];
    while let Some((group, (kids, len), depth)) = pending.pop() {
        if depth > WIDE_DEPTH {
            return None;
        }
        for (slot, &c) in kids[..len].iter().enumerate() {
            let n = nodes[c];
            out[4 * group + slot] = if n.prim_count > 0 {
                n
            } else {
                let below = out.len() / 4;
                out.extend([empty; 4]);
                pending.push((below, children(nodes, c), depth + 1));
                BvhNode { first: below as u32, ..n }
            };
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(min: [f32; 3], max: [f32; 3], prim_count: u32, first: u32) -> BvhNode {
        BvhNode { min, prim_count, max, first }
    }

    /// Leaf ranges (first, count), sorted.
    type Ranges = Vec<(u32, u32)>;

    /// The leaf ranges the BVH2 reaches from its root, and those the wide BVH reaches from its.
    fn leaves(nodes: &[BvhNode], wide: &[BvhNode]) -> (Ranges, Ranges) {
        let mut binary = Vec::new();
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = nodes[i];
            if n.prim_count > 0 {
                binary.push((n.first, n.prim_count));
            } else {
                stack.extend([n.first as usize, n.first as usize + 1]);
            }
        }
        let mut four = Vec::new();
        let mut groups = vec![0usize];
        while let Some(g) = groups.pop() {
            for n in &wide[4 * g..4 * g + 4] {
                if n.prim_count > 0 {
                    four.push((n.first, n.prim_count));
                } else if n.first != NONE {
                    groups.push(n.first as usize);
                }
            }
        }
        binary.sort();
        four.sort();
        (binary, four)
    }

    /// A complete BVH2 of `levels` levels over unit boxes along x, leaves of one primitive each.
    fn complete(levels: u32) -> Vec<BvhNode> {
        let mut nodes = vec![node([0.0; 3], [0.0; 3], 0, 0)];
        let mut level = vec![0usize];
        let mut next_prim = 0;
        for l in 0..levels {
            let mut below = Vec::new();
            for &i in &level {
                let first = nodes.len();
                nodes[i].first = first as u32;
                for _ in 0..2 {
                    let leaf = l + 1 == levels;
                    let (count, f) = if leaf { (1, next_prim) } else { (0, 0) };
                    next_prim += leaf as u32;
                    nodes.push(node([0.0; 3], [0.0; 3], count, f));
                    below.push(nodes.len() - 1);
                }
            }
            level = below;
        }
        // Boxes bottom up: leaf k spans [k, k + 1] on x.
        for i in (0..nodes.len()).rev() {
            let n = nodes[i];
            let (min, max) = if n.prim_count > 0 {
                ([n.first as f32, 0.0, 0.0], [n.first as f32 + 1.0, 1.0, 1.0])
            } else {
                let (a, b) = (nodes[n.first as usize], nodes[n.first as usize + 1]);
                ([a.min[0].min(b.min[0]), 0.0, 0.0], [a.max[0].max(b.max[0]), 1.0, 1.0])
            };
            nodes[i].min = min;
            nodes[i].max = max;
        }
        nodes
    }

    #[test]
    fn a_complete_tree_becomes_groups_of_four_over_the_same_leaves() {
        let nodes = complete(6); // 64 leaves: 1 + 4 + 16 groups
        let wide = collapse(&nodes).expect("shallow enough");
        assert_eq!(wide.len(), 4 * 21);
        let (binary, four) = leaves(&nodes, &wide);
        assert_eq!(binary.len(), 64);
        assert_eq!(binary, four);
        assert!(wide.iter().all(|n| n.first != NONE), "a complete tree leaves no slot empty");
    }

    #[test]
    fn a_leaf_root_and_an_odd_tree_leave_empty_slots() {
        let one = [node([0.0; 3], [1.0; 3], 3, 0)];
        let wide = collapse(&one).unwrap();
        assert_eq!(wide[0].prim_count, 3);
        assert!(wide[1..4].iter().all(|n| n.first == NONE && n.prim_count == 0));
        // A root with a leaf and an inner node of two leaves: three children, one empty slot.
        let nodes = [
            node([0.0; 3], [3.0; 3], 0, 1),
            node([0.0; 3], [1.0; 3], 1, 0),
            node([1.0; 3], [3.0; 3], 0, 3),
            node([1.0; 3], [2.0; 3], 1, 1),
            node([2.0; 3], [3.0; 3], 1, 2),
        ];
        let wide = collapse(&nodes).unwrap();
        assert_eq!(wide.len(), 4);
        let (binary, four) = leaves(&nodes, &wide);
        assert_eq!(binary, four);
        assert_eq!(wide.iter().filter(|n| n.first == NONE).count(), 1);
    }

    /// Each inner node: a leaf and the next inner node, `levels` inner nodes in all. Node 0 is the
    /// root, its children at 1 (leaf) and 2 (inner), and so on.
    fn chain(levels: usize) -> Vec<BvhNode> {
        let mut chain = vec![node([0.0; 3], [1.0; 3], 0, 1)];
        for l in 0..levels {
            let last = l + 1 == levels;
            chain.push(node([0.0; 3], [1.0; 3], 1, l as u32));
            let next = chain.len() as u32 + 1;
            chain.push(if last {
                node([0.0; 3], [1.0; 3], 1, levels as u32)
            } else {
                node([0.0; 3], [1.0; 3], 0, next)
            });
        }
        chain
    }

    #[test]
    fn a_chain_too_deep_for_the_stack_stays_binary() {
        // A group opens three of the chain's inner nodes.
        let fits = collapse(&chain(3 * WIDE_DEPTH)).expect("WIDE_DEPTH groups fit");
        assert_eq!(fits.len(), 4 * WIDE_DEPTH);
        assert!(collapse(&chain(3 * WIDE_DEPTH + 1)).is_none());
        assert!(collapse(&[]).is_none());
    }

    #[test]
    fn by_lane_puts_each_child_in_its_lane() {
        let wide = collapse(&complete(2)).unwrap(); // one group of four leaves
        let mut lanes = wide.clone();
        by_lane(&mut lanes);
        let g: &Group = &bytemuck::cast_slice::<BvhNode, Group>(&lanes)[0];
        for (lane, c) in wide.iter().enumerate() {
            let (min, max) = ([0, 1, 2].map(|a| g.bounds[a][lane]), [3, 4, 5].map(|a| g.bounds[a][lane]));
            assert_eq!((min, max, g.first[lane], g.prim_count[lane]), (c.min, c.max, c.first, c.prim_count));
        }
        let widened = widen(&complete(2)).unwrap();
        assert_eq!(
            bytemuck::cast_slice::<BvhNode, u32>(&widened),
            bytemuck::cast_slice::<BvhNode, u32>(&lanes)
        );
    }
}
