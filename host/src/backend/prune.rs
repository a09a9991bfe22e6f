//! The kernel pruned to one scene: the SPIR-V with the scene's feature mask (and its path loop,
//! `path_loop`) frozen into its specialization constants and every path they disable deleted, by SPIRV-Tools' `spirv-opt`
//! (the optimiser rust-gpu itself uses), before the driver sees it.
//!
//! Why: the specialization constant alone lets the driver fold unused paths away, and with the
//! earlier 4.2 MB kernel (BENCHMARKS.md, "Specialised against pruned") that reached a pruned kernel's
//! speed. The kernel has grown since (blends, normal maps, three more models), and on the H100 the
//! driver no longer folds it as well: the same scene ran 15–33% slower specialised than pruned
//! (`bsdf_diffuse_plain` 120 against 164 Msamples/s, `shape_rectangle` 187 against 254; BENCHMARKS.md,
//! "What blends cost scenes without them, and the pruned kernel"). Pruning returns every scene to the
//! speed of a kernel that never had the paths it does not use.
//!
//! On a software adapter (lavapipe) it buys compile time rather than speed: Mesa translates and
//! inlines the whole 13.7 MB module before its spec constants fold anything, about 40 s per pipeline
//! on a 2-core machine, every time; the pruned module (1.8 MB for a plastic sphere) compiles in
//! about 9 s once and then comes from Mesa's own shader cache, 0.4 s for the whole render
//! (2026-11-24, a 16×16 render at 4 spp). That is what keeps the test suite within CI's time.
//!
//! When: wherever `spirv-opt` is on the `PATH` (Debian's `spirv-tools`), unless `CAUSTIC_PRUNE=0`
//! (the tests set it to check that the unpruned kernel renders the same image). The pruned module is
//! cached per kernel and mask (`$XDG_CACHE_HOME/caustic/pruned`, else `~/.cache/caustic/pruned`), so
//! only a scene's first render pays the optimiser's seconds. Without `spirv-opt`, or if it fails,
//! the kernel runs specialised as before: slower, never wrong.
use std::path::{Path, PathBuf};
use std::process::Command;

/// spirv-opt's passes: freeze the mask, fold what depends on it, drop the dead branches and the
/// functions only they called. (The `-O` recipe was measured 5–20% slower than this on 21 of the 23
/// shared scenes, 2026-11-24.)
const PASSES: &[&str] = &[
    "--freeze-spec-const",
    "--fold-spec-const-op-composite",
    "--ccp",
    "--eliminate-dead-branches",
    "--eliminate-dead-code-aggressive",
    "--eliminate-dead-functions",
    "--merge-blocks",
];

/// Whether to prune: unless `CAUSTIC_PRUNE=0`, on every adapter (hardware for speed, software for
/// compile time).
pub fn wanted() -> bool {
    std::env::var("CAUSTIC_PRUNE").as_deref() != Ok("0")
}

/// `words` with spec constant 0 frozen at `mask`, 1 at `path_loop` (`PathLoop::spec_value`) and the
/// dead paths removed, from the cache or from `spirv-opt`; `None` (with the reason on stderr) where
/// neither can give it. `validated`: the module is known valid (the built-in kernel: rust-gpu's build
/// validates it), so spirv-opt skips validating its input, which took 17 of its 27 s on the 14 MB
/// kernel (2-core machine, 2026-11-24; the output is the same to the byte).
pub fn pruned(words: &[u32], mask: u32, path_loop: u32, validated: bool) -> Option<Vec<u32>> {
    let bytes: &[u8] = bytemuck::cast_slice(words);
    let cached = cache_dir().map(|dir| dir.join(format!("{:016x}-{mask:08x}-{path_loop}.spv", key(bytes))));
    if let Some(words) = cached.as_deref().and_then(read_module) {
        return Some(words);
    }
    let dir = tempdir()?;
    let (input, output) = (dir.join("kernel.spv"), dir.join("pruned.spv"));
    let result = std::fs::write(&input, bytes).ok().and_then(|_| {
        eprintln!("pruning the kernel to this scene's paths (spirv-opt; once per feature mask)");
        let status = Command::new("spirv-opt")
            .arg(format!("--set-spec-const-default-value=0:{mask} 1:{path_loop}"))
            .args(validated.then_some("--skip-validation"))
            .args(PASSES)
            .arg(&input)
            .arg("-o")
            .arg(&output)
            .status();
        match status {
            Ok(s) if s.success() => read_module(&output),
            Ok(s) => {
                eprintln!("warning: spirv-opt failed ({s}); the kernel runs specialised, unpruned");
                None
            }
            // Not installed: the documented fallback, said once per render.
            Err(_) => {
                eprintln!(
                    "note: spirv-opt not found; the kernel runs specialised, unpruned (slower on some GPUs)"
                );
                None
            }
        }
    });
    let _ = std::fs::remove_dir_all(&dir);
    let words = result?;
    if let Some(path) = cached {
        store(&path, bytemuck::cast_slice(&words));
    }
    Some(words)
}

/// A SPIR-V module's words, if `path` holds one (its magic number first).
fn read_module(path: &Path) -> Option<Vec<u32>> {
    let bytes = std::fs::read(path).ok()?;
    if bytes.len() < 20 || bytes.len() % 4 != 0 || bytes[..4] != 0x0723_0203u32.to_le_bytes() {
        return None;
    }
    Some(bytemuck::pod_collect_to_vec(&bytes))
}

/// Writes the cache entry through a temporary name, so that a render running beside this one reads a
/// whole module or none. A cache that cannot be written costs the next render the optimiser again.
fn store(path: &Path, bytes: &[u8]) {
    let Some(dir) = path.parent() else { return };
    if std::fs::create_dir_all(dir).is_err() {
        return;
    }
    let temporary = path.with_extension(format!("{}.tmp", std::process::id()));
    if std::fs::write(&temporary, bytes).is_ok() && std::fs::rename(&temporary, path).is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
}

fn cache_dir() -> Option<PathBuf> {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .filter(|p| p.is_absolute())
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache")))?;
    Some(base.join("caustic").join("pruned"))
}

/// A private scratch directory for spirv-opt's input and output.
fn tempdir() -> Option<PathBuf> {
    let dir = std::env::temp_dir().join(format!(
        "caustic-prune-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&dir).ok()?;
    Some(dir)
}

/// The cache key of a kernel build: a rebuilt kernel gets new entries, equal kernels share them.
/// (std's hasher may change between Rust releases; that only costs a rebuilt cache.)
fn key(bytes: &[u8]) -> u64 {
    use std::hash::Hasher;
    let mut h = std::hash::DefaultHasher::new();
    h.write(bytes);
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_changes_with_the_kernel() {
        assert_ne!(key(b"kernel a"), key(b"kernel b"));
        assert_eq!(key(b"kernel a"), key(b"kernel a"));
    }

    #[test]
    fn only_spirv_is_read_back() {
        let dir = tempdir().unwrap();
        let path = dir.join("x.spv");
        std::fs::write(&path, b"not spir-v at all!!!").unwrap();
        assert!(read_module(&path).is_none());
        let mut module = 0x0723_0203u32.to_le_bytes().to_vec();
        module.extend_from_slice(&[0; 16]);
        std::fs::write(&path, &module).unwrap();
        assert_eq!(read_module(&path).unwrap().len(), 5);
        std::fs::remove_dir_all(dir).unwrap();
    }
}
