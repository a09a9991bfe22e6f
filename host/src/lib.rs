//! caustic's host: scene loading (Mitsuba 3 XML, OBJ/MTL), BVH construction, the GPU (wgpu) and CPU
//! backends, render sessions, progressive rendering, image output, comparison and error-against-time
//! curves. No shading code lives here: all of it is in `caustic-kernel`.
//!
//! The folders follow the pipeline, each using only those before it (`host/tests/layout.rs` checks
//! that no folder reaches back up; docs/host.md draws the graph):
//!
//! - `system`: files, memory and signals, as the process meets the operating system;
//! - `scene`: the renderer-neutral description of a scene;
//! - `load`: scene files (Mitsuba XML, OBJ), meshes and images into a `scene::Scene`;
//! - `prepare`: a scene into the kernel's buffers (`prepare::buffers::SceneBuffers`);
//! - `backend`: the GPU and CPU running the kernel over the buffers, into per-pixel sums;
//! - `output`: sums developed into images, AOVs, image files, comparison, tev;
//! - `render`: sessions, progressive passes, checkpoints, MPI ranks, batches, convergence curves.
pub mod backend;
pub mod load;
pub mod output;
pub mod prepare;
pub mod render;
pub mod scene;
pub mod system;

/// An error and its causes, `: `-separated as anyhow's `{:#}`, leaving out a cause whose message
/// the text already holds (an OS error was printed twice: the exr and image crates put their
/// source's message into their own). What the command line prints and the Python module raises.
pub fn error_chain(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let message = cause.to_string();
        if text.is_empty() {
            text = message;
        } else if !text.contains(&message) {
            text = format!("{text}: {message}");
        }
    }
    text
}
