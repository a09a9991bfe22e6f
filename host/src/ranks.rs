//! One image rendered by several processes (MPI ranks, `--features mpi`: `mpi.rs`): each takes a
//! contiguous share of the sample indices, and the accumulations are summed on rank 0, which writes
//! the image. Random numbers are a function of (seed, pixel, sample, dimension), so the shares add
//! up to exactly the one-process estimator, up to the order of the float sums.
use crate::film::Accumulation;
use anyhow::Result;

/// The processes of one render, as this one sees them.
pub trait Ranks {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// Sums every rank's `accum` on rank 0: `Some(total)` there, `None` on the others. Every rank
    /// must call it (a collective operation).
    fn reduce(&self, accum: &Accumulation) -> Result<Option<Accumulation>>;
}

/// Rank `rank` of `size`'s samples: `[first, end)`, as equal as whole samples allow.
pub fn share(spp: u32, rank: usize, size: usize) -> (u32, u32) {
    let at = |r: usize| (spp as u64 * r as u64 / size as u64) as u32;
    (at(rank), at(rank + 1))
}

/// The hardware GPUs (indices among `candidates`) that rank `local_rank` of `local_size` ranks
/// on one node takes: every `local_size`-th, so that one rank per GPU, or one rank per node with all
/// of them, both work. Empty when there are more ranks than GPUs on the node.
pub fn local_gpus(candidates: &[usize], local_rank: usize, local_size: usize) -> Vec<usize> {
    candidates.iter().copied().skip(local_rank).step_by(local_size.max(1)).collect()
}

/// This process's rank among the ranks on its node, and their number (to spread a node's GPUs).
pub fn local_rank() -> (usize, usize) {
    let read = |names: &[&str]| names.iter().find_map(|n| std::env::var(n).ok()?.parse::<usize>().ok());
    let rank = read(&["OMPI_COMM_WORLD_LOCAL_RANK", "SLURM_LOCALID", "MPI_LOCALRANKID"]).unwrap_or(0);
    let size = read(&["OMPI_COMM_WORLD_LOCAL_SIZE", "SLURM_NTASKS_PER_NODE", "MPI_LOCALNRANKS"]).unwrap_or(1);
    (rank, size.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_cover_every_sample_once() {
        for (spp, size) in [(64, 3), (5, 3), (2, 3), (1, 1), (65536, 64)] {
            let shares: Vec<(u32, u32)> = (0..size).map(|r| share(spp, r, size)).collect();
            assert_eq!(shares[0].0, 0);
            assert_eq!(shares[size - 1].1, spp);
            assert!(shares.windows(2).all(|w| w[0].1 == w[1].0), "{shares:?}");
            let (min, max) =
                shares.iter().fold((u32::MAX, 0), |(lo, hi), s| (lo.min(s.1 - s.0), hi.max(s.1 - s.0)));
            assert!(max - min <= 1, "{spp} over {size}: {shares:?}");
        }
    }

    #[test]
    fn ranks_of_one_node_split_its_gpus() {
        assert_eq!(local_gpus(&[0, 1, 2, 3], 1, 2), vec![1, 3]);
        assert_eq!(local_gpus(&[0, 1, 2, 3], 0, 1), vec![0, 1, 2, 3]);
        assert_eq!(local_gpus(&[0, 1], 2, 3), Vec::<usize>::new());
    }
}
