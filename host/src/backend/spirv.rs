//! SPIR-V modules as words: the committed kernel's, walking their instructions, and the few facts
//! the host reads or writes in them (which specialization constants a module declares, each entry point's workgroup size).
//! `prune` builds on this walk; `gpu` and `kernel_stats` use both.

/// The kernel compiled by `shaders-build` (committed; CI checks it matches the source).
pub(crate) static KERNEL_SPV: &[u8] = include_bytes!("../../shaders/caustic-kernel.spv");

/// `OpDecorate`, and its `SpecId` decoration.
pub(crate) const OP_DECORATE: u32 = 71;
pub(crate) const DECORATION_SPEC_ID: u32 = 1;
const OP_EXECUTION_MODE: u32 = 16;
const EXECUTION_MODE_LOCAL_SIZE: u32 = 17;
/// A module's first word.
pub(crate) const MAGIC: u32 = 0x0723_0203;

/// Where each instruction of a SPIR-V module starts, with its opcode and word count: five header
/// words, then instructions, each with its word count in the high half-word and its opcode in the
/// low. A zero count (a broken module) ends the walk.
pub(crate) fn instructions(words: &[u32]) -> impl Iterator<Item = (usize, u32, usize)> + '_ {
    let mut at = 5;
    std::iter::from_fn(move || {
        let first = *words.get(at)?;
        let count = (first >> 16) as usize;
        if count == 0 {
            return None;
        }
        let found = (at, first & 0xffff, count);
        at += count;
        Some(found)
    })
}

/// Whether a SPIR-V module decorates a specialization constant with `id` (`OpDecorate %c SpecId id`).
pub(crate) fn declares_spec_constant(words: &[u32], id: u32) -> bool {
    instructions(words).any(|(at, op, _)| {
        op == OP_DECORATE && words.get(at + 2) == Some(&DECORATION_SPEC_ID) && words.get(at + 3) == Some(&id)
    })
}

/// Rewrites every entry point's `LocalSize` execution mode to `size` × 1.
pub(crate) fn set_workgroup_size(words: &mut [u32], size: [u32; 2]) {
    let found: Vec<usize> = instructions(words)
        .filter(|&(at, op, count)| {
            op == OP_EXECUTION_MODE && count == 6 && words.get(at + 2) == Some(&EXECUTION_MODE_LOCAL_SIZE)
        })
        .map(|(at, _, _)| at)
        .collect();
    for at in found {
        words[at + 3..at + 6].copy_from_slice(&[size[0], size[1], 1]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use caustic_kernel::layout::{SPEC_FEATURES, SPEC_REGENERATE, TILE};

    #[test]
    fn the_committed_kernel_declares_its_two_constants() {
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(KERNEL_SPV);
        assert!(declares_spec_constant(&words, SPEC_FEATURES));
        assert!(declares_spec_constant(&words, SPEC_REGENERATE));
        assert!(!declares_spec_constant(&words, 2));
        // A module without decorations (header only) and a truncated one declare nothing.
        assert!(!declares_spec_constant(&words[..5], 0));
        assert!(!declares_spec_constant(&[MAGIC, 0, 0, 0, 0, 0], 0));
    }

    #[test]
    fn every_entry_point_gets_the_workgroup_size() {
        let local_sizes = |words: &[u32]| -> Vec<[u32; 3]> {
            instructions(words)
                .filter(|&(at, op, count)| op == 16 && count == 6 && words[at + 2] == 17)
                .map(|(at, _, _)| [words[at + 3], words[at + 4], words[at + 5]])
                .collect()
        };
        let mut words: Vec<u32> = bytemuck::pod_collect_to_vec(KERNEL_SPV);
        const OP_ENTRY_POINT: u32 = 15;
        let entry_points = instructions(&words).filter(|i| i.1 == OP_ENTRY_POINT).count();
        assert_eq!(entry_points, 6, "render, light, cache_light, grid_link, cache_camera, resolve");
        assert_eq!(local_sizes(&words), vec![[TILE, TILE, 1]; entry_points]);
        let before = words.clone();
        set_workgroup_size(&mut words, [32, 16]);
        assert_eq!(local_sizes(&words), vec![[32, 16, 1]; entry_points]);
        let changed = words.iter().zip(&before).filter(|(a, b)| a != b).count();
        assert_eq!(changed, 2 * entry_points, "the sizes alone change");
    }
}
