//! The committed kernel (`host/shaders/caustic-kernel.spv`) was compiled from the kernel source in
//! this tree, as far as the module itself can tell: rust-gpu embeds the text of every source file it
//! emits code from (`OpSource`), comments included, and each `kernel/` file embedded must read as the
//! file on disk. A fast check in the test command for what CI's full rebuild (`.ci/run`, 28 min)
//! finds: stop 27 failed there on one changed word in a comment of `kernel/src/shape/triangle.rs`.
//! A kernel file with no code in the module (constants only) is not embedded and not covered here.
use rspirv::dr::Operand;
use std::collections::HashMap;

/// The embedded source text of each file the module names, by its path as the module spells it.
fn embedded_sources(words: &[u32]) -> HashMap<String, String> {
    let module = rspirv::dr::load_words(words).expect("the committed SPIR-V parses");
    let mut names = HashMap::new();
    let mut sources: HashMap<String, String> = HashMap::new();
    // OpSourceContinued extends the text of the OpSource before it.
    let mut last = None;
    for inst in &module.debug_string_source {
        match (inst.class.opcode, inst.operands.as_slice()) {
            (rspirv::spirv::Op::String, [Operand::LiteralString(name)]) => {
                names.insert(inst.result_id.expect("OpString has a result"), name.clone());
            }
            (rspirv::spirv::Op::Source, [_, _, Operand::IdRef(file), Operand::LiteralString(text)]) => {
                let name = names.get(file).expect("OpSource names a declared OpString").clone();
                sources.insert(name.clone(), text.clone());
                last = Some(name);
            }
            (rspirv::spirv::Op::SourceContinued, [Operand::LiteralString(text)]) => {
                let name = last.as_ref().expect("OpSourceContinued follows an OpSource");
                sources.get_mut(name).expect("its OpSource was recorded").push_str(text);
            }
            _ => last = None,
        }
    }
    sources
}

#[test]
fn the_committed_kernel_embeds_the_kernel_source_of_this_tree() {
    let words: Vec<u32> =
        bytemuck::pod_collect_to_vec(include_bytes!("../../host/shaders/caustic-kernel.spv"));
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let sources = embedded_sources(&words);
    let mut checked = 0;
    let mut stale = Vec::new();
    for (name, text) in sources.iter().filter(|(name, _)| name.starts_with("kernel/")) {
        let on_disk = std::fs::read_to_string(root.join(name)).unwrap_or_default();
        checked += 1;
        if on_disk != *text {
            stale.push(name.clone());
        }
    }
    stale.sort();
    println!("{checked} kernel files embedded in the committed SPIR-V");
    // The kernel's shading, sampling and intersection span some 60 files; a parse that found a few
    // would check almost nothing.
    assert!(
        checked >= 40,
        "only {checked} kernel files found embedded: has rust-gpu stopped embedding source?"
    );
    assert!(
        stale.is_empty(),
        "host/shaders/caustic-kernel.spv was compiled from other text of {stale:?}: run shaders-build/build.sh and commit the result"
    );
}

/// The SHA-256 of `path` (relative to the repository root), as `sha256sum` prints it.
fn sha256_hex(root: &std::path::Path, path: &str) -> String {
    use sha2::{Digest, Sha256};
    let bytes = std::fs::read(root.join(path)).unwrap_or_else(|e| panic!("cannot read {path}: {e}"));
    Sha256::digest(&bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// Every `.rs` file under `kernel/src`, relative to the root, sorted.
fn kernel_sources(root: &std::path::Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut dirs = vec![root.join("kernel/src")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("kernel/src is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(root).expect("under the root");
                found.push(relative.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    found.sort();
    found
}

/// The stamp that `shaders-build/build.sh` writes beside the committed module
/// (`host/shaders/caustic-kernel.inputs`: the SHA-256 of every input of the build and of the module)
/// matches this tree: no kernel file, lock file, toolchain or builder changed since the module was
/// built, none was added or removed, and the module is the one built. With the embedded-source test
/// above, this is what lets CI skip its 28-minute rebuild (`.ci/run`); a kernel file with no code in
/// the module, which that test cannot see, is covered here.
#[test]
fn the_committed_kernel_was_built_from_the_inputs_of_this_tree() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let stamp = std::fs::read_to_string(root.join("host/shaders/caustic-kernel.inputs"))
        .expect("host/shaders/caustic-kernel.inputs exists (shaders-build/build.sh writes it)");
    let mut listed = Vec::new();
    let mut stale = Vec::new();
    for line in stamp.lines() {
        let (hash, path) = line.split_once("  ").unwrap_or_else(|| panic!("a damaged stamp line: {line:?}"));
        if sha256_hex(&root, path) != hash {
            stale.push(path.to_string());
        }
        listed.push(path.to_string());
    }
    assert!(
        stale.is_empty(),
        "changed since host/shaders/caustic-kernel.spv was built: {stale:?}; run shaders-build/build.sh and commit the result"
    );
    let listed_sources: Vec<String> =
        listed.iter().filter(|p| p.starts_with("kernel/src/")).cloned().collect();
    assert_eq!(
        listed_sources,
        kernel_sources(&root),
        "kernel/src has other files than the committed SPIR-V was built from; run shaders-build/build.sh"
    );
    for needed in [
        "Cargo.lock",
        "kernel/Cargo.toml",
        "shaders-build/rust-toolchain.toml",
        "host/shaders/caustic-kernel.spv",
    ] {
        assert!(listed.iter().any(|p| p == needed), "the stamp does not cover {needed}");
    }
}
