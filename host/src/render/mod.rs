//! Rendering a scene to the end: a session (`session`: scene file in, image file out), the pass
//! loop (`passes`), checkpoints, several processes (`ranks`, `ranked`, `shares`, `mpi`), batches of
//! scenes (`batch`) and error-against-time curves (`convergence`).
//!
//! Uses every other folder, being the last stage: `backend`, `output`, `prepare`, `load`, `scene`
//! and `system`.
pub mod batch;
pub mod checkpoint;
pub mod convergence;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod passes;
pub mod ranked;
pub mod ranks;
pub mod session;
pub mod shares;
