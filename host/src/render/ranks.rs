//! One image rendered by several processes (MPI ranks, `--features mpi`: `mpi.rs`): what the render
//! needs from them, kept apart from MPI so that the session (`ranked.rs`) builds without it. Rank 0
//! hands out chunks of the sample indices (`shares.rs`) and the accumulations are summed on rank
//! 0, which writes the image. Random numbers are a function of (seed, pixel, sample, dimension), so
//! the chunks add up to exactly the one-process estimator, up to the order of the float sums.
use crate::backend::accumulation::Accumulation;
use crate::render::shares::Work;
use anyhow::Result;
use std::sync::Arc;
use std::time::Duration;

/// Writes out what rank 0 has summed when the render cannot finish, given why (`Plan::lost`).
pub type Lost = Arc<dyn Fn(&str) + Send + Sync>;

/// What rank 0 hands out.
pub struct Plan {
    /// `[0, start)` is in rank 0's accumulation already (a resumed checkpoint).
    pub start: u32,
    pub spp: u32,
    /// Interval between checkpoints (`None`: none).
    pub every: Option<Duration>,
    /// Follows the samples finished by all ranks.
    pub progress: indicatif::ProgressBar,
    /// Called (on rank 0) when a rank fails or stops responding, or a signal arrives: writes what
    /// was summed and says why the render stopped; the job ends after it.
    pub lost: Lost,
}

/// The processes of one render, as this one sees them.
pub trait Ranks {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// `rank R on HOST`, for messages.
    fn name(&self, rank: usize) -> String;
    /// Sums every rank's `accum` on rank 0: `Some(total)` there, `None` on the others. Every rank
    /// must call it (a collective operation).
    fn reduce(&self, accum: &Accumulation) -> Result<Option<Accumulation>>;
    /// Every rank says whether it is ready (`Some`: rank 0 gives the first sample to render, a
    /// resumed checkpoint's), or could not start (`None`, having said why). Rank 0's start for
    /// all, or an error naming every rank that could not start. Collective.
    fn agree(&self, start: Option<u32>) -> Result<u32>;
    /// Rank 0: starts handing out the samples (a thread of its own answers the other ranks).
    fn dispatch(&self, plan: Plan) -> Result<()>;
    /// What this rank does next, having finished what it had.
    fn next_work(&self) -> Result<Work>;
    /// Rank 0, right after the final sum (it ends the watch for lost ranks, so that nothing
    /// overwrites the image about to be written): samples per pixel each rank rendered.
    fn shares(&self) -> Vec<u64>;
    /// This rank's render failed: rank 0 names it, writes what it had summed and ends the job.
    fn fail(&self, error: &anyhow::Error) -> !;
    /// Waits until every rank gets here.
    fn barrier(&self);
}

/// Whether this process was started by an MPI launcher (Open MPI's mpirun, a PMI launcher such as
/// Slurm's srun, MPICH's hydra): only then is MPI initialised, so a plain `caustic render` of an
/// MPI build behaves as any other.
pub fn launched() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
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
    fn ranks_of_one_node_split_its_gpus() {
        assert_eq!(local_gpus(&[0, 1, 2, 3], 1, 2), vec![1, 3]);
        assert_eq!(local_gpus(&[0, 1, 2, 3], 0, 1), vec![0, 1, 2, 3]);
        assert_eq!(local_gpus(&[0, 1], 2, 3), Vec::<usize>::new());
    }
}
