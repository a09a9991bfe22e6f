//! MPI (`--features mpi`): `mpirun -n N caustic render …` (or `srun` under Slurm) renders one image
//! with every rank taking a share of the samples (`ranks.rs`), summed on rank 0 by `MPI_Reduce`.
use crate::film::Accumulation;
use crate::ranks::Ranks;
use anyhow::{anyhow, Result};
use mpi::traits::*;

/// The world communicator; MPI is finalised when it is dropped.
pub struct World {
    _universe: mpi::environment::Universe,
    world: mpi::topology::SimpleCommunicator,
}

/// Whether this process was started by an MPI launcher (Open MPI's mpirun, a PMI launcher such as
/// Slurm's srun, MPICH's hydra): only then is MPI initialised, so a plain `caustic render` of an
/// MPI build behaves as any other.
pub fn launched() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

impl World {
    pub fn init() -> Result<World> {
        let universe = mpi::initialize().ok_or_else(|| anyhow!("MPI was already initialised"))?;
        let world = universe.world();
        Ok(World { _universe: universe, world })
    }
}

impl Ranks for World {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn reduce(&self, accum: &Accumulation) -> Result<Option<Accumulation>> {
        use mpi::collective::SystemOperation;
        let root = self.world.process_at_rank(0);
        let sums: &[f64] = bytemuck::cast_slice(&accum.pixels);
        let batches = [accum.batches.unwrap_or(0)];
        if self.world.rank() != 0 {
            root.reduce_into(sums, SystemOperation::sum());
            root.reduce_into(&batches[..], SystemOperation::sum());
            return Ok(None);
        }
        let mut total = vec![0f64; sums.len()];
        let mut total_batches = [0u32];
        root.reduce_into_root(sums, &mut total[..], SystemOperation::sum());
        root.reduce_into_root(&batches[..], &mut total_batches[..], SystemOperation::sum());
        Ok(Some(Accumulation {
            pixels: bytemuck::pod_collect_to_vec(&total),
            batches: accum.batches.map(|_| total_batches[0]),
        }))
    }
}
