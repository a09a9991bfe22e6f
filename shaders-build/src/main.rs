//! Compiles `kernel/` to SPIR-V with rust-gpu and writes it where the host embeds it
//! (`host/shaders/caustic-kernel.spv`), or to the path given as the first argument.
//!
//! The generated module is committed so that rendering never waits for the SPIR-V compiler; CI rebuilds
//! it and fails if the committed file differs from what the kernel source compiles to.
use spirv_builder::{Capability, ShaderPanicStrategy, SpirvBuilder, SpirvMetadata};
use std::path::PathBuf;

fn main() {
    // The repository to build comes from the environment (build.sh sets it), never from where this
    // builder was compiled: its binary lives in a cache shared by every clone on the machine.
    let root = match std::env::var_os("CAUSTIC_ROOT") {
        Some(r) => PathBuf::from(r),
        None => std::env::current_dir()
            .expect("current directory")
            .parent()
            .expect("run from shaders-build/")
            .to_path_buf(),
    };
    let root = root.as_path();
    let out = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("host/shaders/caustic-kernel.spv"));
    // The kernel's own build directory lives outside the clone (a cache shared across clones and CI).
    let cache = std::env::var_os("CAUSTIC_CACHE").map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(std::env::var_os("HOME").unwrap_or_default()).join(".cache/caustic")
    });

    let mut builder = SpirvBuilder::new(root.join("kernel"), "spirv-unknown-vulkan1.2")
        .release(true)
        .spirv_metadata(SpirvMetadata::None)
        .capability(Capability::Int8)
        .shader_panic_strategy(ShaderPanicStrategy::SilentExit)
        .target_dir_path(cache.join("kernel-spirv-target"));
    builder.toolchain_overwrite = Some("nightly-2026-08-15".to_string());
    let result = builder.build().unwrap_or_else(|e| {
        eprintln!("error: the kernel did not compile to SPIR-V: {e}");
        std::process::exit(1);
    });
    let module = result.module.unwrap_single();
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).expect("create the output directory");
    }
    std::fs::copy(module, &out).unwrap_or_else(|e| {
        eprintln!("error: cannot write {}: {e}", out.display());
        std::process::exit(1);
    });
    println!("wrote {} ({} bytes)", out.display(), std::fs::metadata(&out).map(|m| m.len()).unwrap_or(0));
}
