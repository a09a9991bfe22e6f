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
