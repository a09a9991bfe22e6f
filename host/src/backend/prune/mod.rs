//! The kernel pruned to one scene: its specialization constants (the feature mask, the path loop)
//! frozen to the scene's values, and every block they leave unreachable deleted, before naga and the
//! driver see the module. caustic does this itself, in well under a second, with no tool installed.
//!
//! Why prune: the specialization constant alone lets the driver fold unused paths away, but the
//! kernel's module is 20 MB (everything is inlined into its three entry points) and drivers do not
//! fold it as well as a pruned module: on the H100 a scene ran 15–33% slower specialised than pruned
//! (BENCHMARKS.md, "What blends cost scenes without them, and the pruned kernel"), the NVIDIA driver
//! took 15–108 s to compile the whole module cold, and Mesa's lavapipe about 40 s a pipeline.
//!
//! Why not `spirv-opt`: its passes (freeze, fold, dead branches, aggressive dead code) took 25–30 s a
//! module on the H200's host and 26 s on a 2-core machine, the longest part of a new scene's first
//! render (BENCHMARKS.md, "First render of a new scene: where the time goes"), and it is a system
//! binary a user may not have. The kernel tests every feature as `features & BIT != 0` in its
//! entry points' bodies, so the one analysis needed is sparse conditional constant propagation
//! (Wegman and Zadeck 1991) on the integers and booleans of each function, from the frozen
//! constants: which blocks can run, which values are constants.
//!
//! What is rewritten (`rewrite`): the frozen `OpSpecConstant`s become `OpConstant`s (their
//! `SpecId`s go); a block that cannot run is deleted, or, where a block that runs still names it (a
//! branch target, a merge or continue block), reduced to a label and `OpUnreachable` (a back edge of
//! a loop that runs: a label and a branch to the loop's header); a decided branch tests a constant,
//! and a selection decided for an empty side (its merge block, or a block that only branches
//! there) becomes a branch to it, without the header: no block is left inside that could break out
//! to the merge. Otherwise a kept block's control flow is the kernel's own, so the structured
//! control flow of what remains stays valid. Each `OpPhi` keeps the predecessors that remain
//! (`OpUndef` for a value no longer defined); results that nothing with an effect uses are dropped,
//! and so are debug instructions (names, lines, sources). A module with an instruction this does not
//! know (`opcodes::body_result`, `body_no_result`) is not pruned: the caller then runs it
//! specialised. Every feature's module passes naga's validator and `spirv-val` (the tests).
//!
//! Measured (BENCHMARKS.md, "Pruning without spirv-opt"): 0.1-0.3 s a module on a 2-core machine,
//! the module the same size as `spirv-opt`'s to within a few percent, steady state on the H200
//! within -2% to +9% of `spirv-opt`'s.
use super::spirv::{instructions, DECORATION_SPEC_ID, MAGIC, OP_DECORATE};
use analysis::{Inst, Module, Scalar, Value};
use opcodes::{self as op, body_result, debug};
use rewrite::NewGlobals;
use std::collections::{HashMap, HashSet};

mod analysis;
mod opcodes;
mod rewrite;

/// Whether to prune: unless `CAUSTIC_PRUNE=0` (the tests set it to check that the unpruned kernel
/// renders the same image), on every adapter (hardware for speed, software for compile time).
pub fn wanted() -> bool {
    std::env::var("CAUSTIC_PRUNE").as_deref() != Ok("0")
}

/// `words` with spec constant 0 frozen at `mask` and 1 at `path_loop` (`PathLoop::spec_value`), and
/// the blocks they disable removed; `None` where the module is not one this can prune.
pub fn pruned(words: &[u32], mask: u32, path_loop: u32) -> Option<Vec<u32>> {
    prune(words, &[(0, mask), (1, path_loop)], None)
}

/// `pruned`, keeping only the entry points named in `entries` (those a scene's integrator runs): the
/// others' functions are neither analysed nor written. The kernel's entry points are each one
/// inlined function, and a path-traced scene runs two of six (`render`, `resolve`), about a third
/// of the module's words, so its pruning and naga's reading of the result take that much less.
pub fn pruned_to(words: &[u32], mask: u32, path_loop: u32, entries: &[&str]) -> Option<Vec<u32>> {
    prune(words, &[(0, mask), (1, path_loop)], Some(entries))
}

/// An `OpEntryPoint`'s function id and name (`w`: its words).
fn entry_point(w: &[u32]) -> Option<(u32, String)> {
    let function = *w.get(2)?;
    let bytes: Vec<u8> = w.get(3..)?.iter().flat_map(|x| x.to_le_bytes()).take_while(|&b| b != 0).collect();
    Some((function, String::from_utf8(bytes).ok()?))
}

/// The functions of entry points not in `keep`: what `prune` leaves out (none where `keep` is
/// `None`, and none that a kept entry point or any call names).
fn left_out(m: &Module, first_function: usize, keep: Option<&[&str]>) -> Option<HashSet<u32>> {
    let Some(keep) = keep else { return Some(HashSet::new()) };
    let mut out = HashSet::new();
    let mut kept = HashSet::new();
    for i in &m.insts[..first_function] {
        if i.op == op::ENTRY_POINT {
            let (function, name) = entry_point(&m.words[i.at..i.at + i.len])?;
            if keep.contains(&name.as_str()) {
                kept.insert(function)
            } else {
                out.insert(function)
            };
        }
    }
    for i in m.insts[first_function..].iter().filter(|i| i.op == op::FUNCTION_CALL) {
        kept.insert(*m.words.get(i.at + 3)?);
    }
    out.retain(|f| !kept.contains(f));
    Some(out)
}

/// `words` with spec constants frozen (`(spec id, value)`) and the blocks that cannot run removed;
/// only the entry points in `keep`, where it is given.
fn prune(words: &[u32], frozen: &[(u32, u32)], keep: Option<&[&str]>) -> Option<Vec<u32>> {
    if words.len() < 5 || words[0] != MAGIC {
        return None;
    }
    let insts: Vec<Inst> = instructions(words).map(|(at, op, len)| Inst { at, op, len }).collect();
    let walked = insts.last().map_or(5, |i| i.at + i.len);
    if walked != words.len() || insts.iter().any(|i| i.at + i.len > words.len()) {
        return None;
    }
    let bound = words[3] as usize;
    let mut m = Module {
        words,
        insts,
        type_of: vec![0; bound],
        value: vec![Value::Varying; bound],
        scalar: vec![Scalar::Other; bound],
    };
    let first_function = m.insts.iter().position(|i| i.op == op::FUNCTION).unwrap_or(m.insts.len());

    // Globals: the scalar types, the constants, the spec constants to freeze.
    let mut spec_ids: HashMap<u32, u32> = HashMap::new();
    for i in &m.insts[..first_function] {
        let w = &words[i.at..i.at + i.len];
        match i.op {
            OP_DECORATE if w.len() == 4 && w[2] == DECORATION_SPEC_ID => {
                spec_ids.insert(w[1], w[3]);
            }
            op::DECORATION_GROUP | op::GROUP_DECORATE | op::GROUP_MEMBER_DECORATE => return None,
            _ => {}
        }
    }
    let frozen_value =
        |id: u32| spec_ids.get(&id).and_then(|s| frozen.iter().find(|f| f.0 == *s)).map(|f| f.1);
    let mut frozen_ids = HashSet::new();
    for k in 0..first_function {
        let i = m.insts[k];
        let w = &words[i.at..i.at + i.len];
        let id = |k: usize| w.get(k).map(|&x| x as usize).filter(|&x| x < bound);
        match i.op {
            op::TYPE_BOOL => m.scalar[id(1)?] = Scalar::Bool,
            op::TYPE_INT if w.len() == 4 => m.scalar[id(1)?] = Scalar::Int { width: w[2], signed: w[3] != 0 },
            op::CONSTANT_TRUE | op::CONSTANT_FALSE => {
                m.type_of[id(2)?] = id(1)? as u32;
                m.value[id(2)?] = Value::Known((i.op == op::CONSTANT_TRUE) as u64);
            }
            op::CONSTANT | op::CONSTANT_NULL | op::SPEC_CONSTANT if w.len() >= 3 => {
                let (ty, res) = (id(1)?, id(2)?);
                m.type_of[res] = ty as u32;
                let literal = match (i.op, w.len()) {
                    (op::CONSTANT_NULL, _) => Some(0),
                    (op::SPEC_CONSTANT, 4 | 5) => frozen_value(res as u32).map(u64::from),
                    (op::SPEC_CONSTANT, _) => None,
                    (_, 4) => Some(w[3] as u64),
                    (_, 5) => Some(w[3] as u64 | (w[4] as u64) << 32),
                    _ => None,
                };
                if i.op == op::SPEC_CONSTANT && literal.is_some() {
                    frozen_ids.insert(res as u32);
                }
                if let (Some(v), Scalar::Int { .. } | Scalar::Bool) = (literal, m.scalar[ty]) {
                    m.value[res] = Value::Known(v);
                }
            }
            op::SPEC_CONSTANT_TRUE | op::SPEC_CONSTANT_FALSE => {
                if let Some(v) = frozen_value(id(2)? as u32) {
                    frozen_ids.insert(w[2]);
                    m.value[id(2)?] = Value::Known((v != 0) as u64);
                }
            }
            _ => {}
        }
    }

    // Functions: each one's blocks, analysed, then written; those of entry points left out, gone
    // with every id they define.
    let left_out = left_out(&m, first_function, keep)?;
    let mut bodies: Vec<u32> = Vec::new();
    let mut removed = vec![false; bound];
    let mut globals = NewGlobals { words: Vec::new(), next_id: bound as u32, made: HashMap::new() };
    let mut at = first_function;
    while at < m.insts.len() {
        if m.insts[at].op != op::FUNCTION {
            return None;
        }
        let end = at + m.insts[at..].iter().position(|i| i.op == op::FUNCTION_END)?;
        let function = *words.get(m.insts[at].at + 2)?;
        if left_out.contains(&function) {
            for i in &m.insts[at..end] {
                let result = match i.op {
                    op::LABEL => words.get(i.at + 1),
                    op::FUNCTION | op::FUNCTION_PARAMETER => words.get(i.at + 2),
                    o if body_result(o) => words.get(i.at + 2),
                    _ => None,
                };
                if let Some(slot) = result.and_then(|&r| removed.get_mut(r as usize)) {
                    *slot = true;
                }
            }
            at = end + 1;
            continue;
        }
        let mut blocks = m.blocks(at + 1, end)?;
        let fates = m.analyse(&mut blocks)?;
        m.write(at, end, &blocks, &fates, &mut removed, &mut globals, &mut bodies)?;
        at = end + 1;
    }

    // The module: header with the new bound, globals less debug and what names removed ids, the
    // frozen constants, the globals the rewrite made, then the bodies.
    let mut out = Vec::with_capacity(words.len() / 4);
    out.extend_from_slice(&[words[0], words[1], words[2], globals.next_id, words[4]]);
    for i in &m.insts[..first_function] {
        let w = &words[i.at..i.at + i.len];
        let targets_removed = matches!(i.op, OP_DECORATE | op::DECORATE_ID | op::DECORATE_STRING)
            && w.get(1).is_some_and(|&t| removed.get(t as usize) == Some(&true));
        let frees_spec =
            i.op == OP_DECORATE && w.len() == 4 && w[2] == DECORATION_SPEC_ID && frozen_ids.contains(&w[1]);
        let of_left_out = match i.op {
            op::ENTRY_POINT => w.get(2),
            op::EXECUTION_MODE | op::EXECUTION_MODE_ID => w.get(1),
            _ => None,
        }
        .is_some_and(|f| left_out.contains(f));
        if debug(i.op) || targets_removed || frees_spec || of_left_out {
            continue;
        }
        let start = out.len();
        out.extend_from_slice(w);
        if frozen_ids.contains(&w.get(2).copied().unwrap_or(0)) {
            match i.op {
                op::SPEC_CONSTANT => {
                    out[start] = (w.len() as u32) << 16 | op::CONSTANT;
                    let v = match m.value[w[2] as usize] {
                        Value::Known(v) => v,
                        _ => return None,
                    };
                    out[start + 3] = v as u32;
                    if w.len() == 5 {
                        out[start + 4] = (v >> 32) as u32;
                    }
                }
                op::SPEC_CONSTANT_TRUE | op::SPEC_CONSTANT_FALSE => {
                    let on = m.value[w[2] as usize] == Value::Known(1);
                    out[start] = 3 << 16 | if on { op::CONSTANT_TRUE } else { op::CONSTANT_FALSE };
                }
                _ => {}
            }
        }
    }
    out.extend_from_slice(&globals.words);
    out.extend_from_slice(&bodies);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::spirv::declares_spec_constant;
    use crate::backend::spirv::KERNEL_SPV;

    fn kernel() -> Vec<u32> {
        bytemuck::pod_collect_to_vec(KERNEL_SPV)
    }

    #[test]
    fn the_constants_are_frozen_and_unused_paths_go() {
        let words = kernel();
        let all = pruned(&words, u32::MAX, 1).expect("the kernel prunes");
        let none = pruned(&words, 0, 1).expect("the kernel prunes");
        for module in [&all, &none] {
            assert!(!declares_spec_constant(module, 0) && !declares_spec_constant(module, 1));
        }
        assert!(none.len() * 4 < all.len(), "no features: {} words, all: {}", none.len(), all.len());
        assert!(all.len() < words.len(), "debug instructions go even where every path stays");
    }

    /// Every single feature, none and all, under both path loops: naga (what wgpu reads modules
    /// with) parses and validates the pruned kernel.
    #[test]
    fn naga_accepts_the_pruned_kernel_for_every_feature() {
        let words = kernel();
        let masks = (0..32).map(|bit| 1u32 << bit).chain([0, u32::MAX]);
        for mask in masks {
            for path_loop in [0, 1] {
                let module = pruned(&words, mask, path_loop).expect("the kernel prunes");
                let options = naga::front::spv::Options {
                    adjust_coordinate_space: false,
                    strict_capabilities: true,
                    block_ctx_dump_prefix: None,
                };
                let parsed = naga::front::spv::parse_u8_slice(bytemuck::cast_slice(&module), &options)
                    .unwrap_or_else(|e| panic!("mask {mask:#x}, loop {path_loop}: naga cannot read it: {e}"));
                naga::valid::Validator::new(
                    naga::valid::ValidationFlags::all(),
                    naga::valid::Capabilities::all(),
                )
                .validate(&parsed)
                .unwrap_or_else(|e| panic!("mask {mask:#x}, loop {path_loop}: naga rejects it: {e:?}"));
            }
        }
    }

    /// One instruction's words.
    fn inst(op: u32, operands: &[u32]) -> Vec<u32> {
        let mut words = vec![((operands.len() + 1) as u32) << 16 | op];
        words.extend_from_slice(operands);
        words
    }

    /// A compute module around `body` (ids 1-8 are taken: void, its function type, u32, bool, the
    /// spec constant 0 (SpecId 0), the constants 1 and 0, the entry point; 20 and 21: a workgroup
    /// u32 variable and its pointer type, where a body stores what it computes).
    fn module(body: &[Vec<u32>]) -> Vec<u32> {
        let mut w = vec![MAGIC, 0x0001_0300, 0, 40, 0];
        w.extend(inst(17, &[1])); // OpCapability Shader
        w.extend(inst(14, &[0, 1])); // OpMemoryModel Logical GLSL450
        w.extend(inst(15, &[5, 8, u32::from_le_bytes(*b"main"), 0])); // OpEntryPoint GLCompute %8 "main"
        w.extend(inst(16, &[8, 17, 1, 1, 1])); // OpExecutionMode %8 LocalSize 1 1 1
        w.extend(inst(OP_DECORATE, &[5, DECORATION_SPEC_ID, 0]));
        w.extend(inst(19, &[1])); // OpTypeVoid
        w.extend(inst(33, &[2, 1])); // OpTypeFunction %2 %1
        w.extend(inst(op::TYPE_INT, &[3, 32, 0]));
        w.extend(inst(op::TYPE_BOOL, &[4]));
        w.extend(inst(op::SPEC_CONSTANT, &[3, 5, u32::MAX]));
        w.extend(inst(op::CONSTANT, &[3, 6, 1]));
        w.extend(inst(op::CONSTANT, &[3, 7, 0]));
        w.extend(inst(32, &[20, 4, 3])); // OpTypePointer %20 Workgroup %3
        w.extend(inst(59, &[20, 21, 4])); // OpVariable %20 %21 Workgroup
        w.extend(inst(op::FUNCTION, &[1, 8, 0, 2]));
        for i in body {
            w.extend_from_slice(i);
        }
        w.extend(inst(op::FUNCTION_END, &[]));
        w
    }

    /// Each block of a module's one function: its label and the opcodes after it.
    fn blocks_of(words: &[u32]) -> Vec<(u32, Vec<u32>)> {
        let mut blocks: Vec<(u32, Vec<u32>)> = Vec::new();
        for (at, op, _) in instructions(words) {
            match op {
                op::LABEL => blocks.push((words[at + 1], Vec::new())),
                op::FUNCTION_END => {}
                _ if !blocks.is_empty() => blocks.last_mut().unwrap().1.push(op),
                _ => {}
            }
        }
        blocks
    }

    /// The operands of the one `OpPhi`.
    fn phi_of(words: &[u32]) -> Vec<u32> {
        let (at, _, len) = instructions(words).find(|i| i.1 == op::PHI).expect("a phi");
        words[at + 3..at + len].to_vec()
    }

    /// `x = if features & 1 != 0 { 1 + 1 } else { 0 }`, the else block `1 - 1` where `with_else`,
    /// and x stored after it.
    fn selection(with_else: bool) -> Vec<u32> {
        selection_with(with_else, true)
    }

    /// As `selection`, the else block empty (a branch to the merge, as rust-gpu writes an `if`
    /// without `else`) unless `else_code`.
    fn selection_with(with_else: bool, else_code: bool) -> Vec<u32> {
        let otherwise = if with_else { 16 } else { 13 };
        let mut body = vec![
            inst(op::LABEL, &[9]),
            inst(op::BITWISE_AND, &[3, 10, 5, 6]),
            inst(op::I_NOT_EQUAL, &[4, 11, 10, 7]),
            inst(op::SELECTION_MERGE, &[13, 0]),
            inst(op::BRANCH_CONDITIONAL, &[11, 12, otherwise]),
            inst(op::LABEL, &[12]),
            inst(op::I_ADD, &[3, 14, 6, 6]),
            inst(op::BRANCH, &[13]),
        ];
        if with_else {
            body.push(inst(op::LABEL, &[16]));
            body.extend(else_code.then(|| inst(op::I_SUB, &[3, 17, 6, 6])));
            body.push(inst(op::BRANCH, &[13]));
        }
        let (value, parent) = match (with_else, else_code) {
            (true, true) => (17, 16),
            (true, false) => (7, 16),
            _ => (7, 9),
        };
        body.extend([
            inst(op::LABEL, &[13]),
            inst(op::PHI, &[3, 15, 14, 12, value, parent]),
            inst(62, &[21, 15]), // OpStore %21 %15
            // OpAtomicIAdd %3 %22 %21 (scope: device, semantics: none) %6, its result unused.
            inst(234, &[3, 22, 21, 6, 7, 6]),
            inst(253, &[]), // OpReturn
        ]);
        module(&body)
    }

    #[test]
    fn a_selection_the_mask_empties_goes() {
        let off = pruned(&selection(false), 0, 0).unwrap();
        let blocks = blocks_of(&off);
        assert_eq!(blocks, vec![(9, vec![op::BRANCH]), (13, vec![op::PHI, 62, 234, 253])], "header to merge");
        assert_eq!(phi_of(&off), vec![7, 9], "the phi keeps the predecessor that remains");
        assert!(!declares_spec_constant(&off, 0));
        let on = pruned(&selection(false), 1, 0).unwrap();
        assert_eq!(blocks_of(&on)[1], (12, vec![op::I_ADD, op::BRANCH]), "the enabled side stays whole");
        assert_eq!(phi_of(&on), vec![14, 12, 7, 9]);
        // An empty else block: the header branches to it, and it to the merge.
        let off = pruned(&selection_with(true, false), 0, 0).unwrap();
        let expected = vec![(9, vec![op::BRANCH]), (16, vec![op::BRANCH]), (13, vec![op::PHI, 62, 234, 253])];
        assert_eq!(blocks_of(&off), expected);
        assert_eq!(phi_of(&off), vec![7, 16]);
    }

    #[test]
    fn a_side_the_mask_disables_leaves_a_stub() {
        for (mask, dead, live, value) in [(0, 12, 16, 17), (1, 16, 12, 14)] {
            let pruned = pruned(&selection(true), mask, 0).unwrap();
            let blocks = blocks_of(&pruned);
            let stub = blocks.iter().find(|b| b.0 == dead).unwrap();
            assert_eq!(stub.1, vec![op::UNREACHABLE], "the disabled side: a label and OpUnreachable");
            assert_eq!(phi_of(&pruned), vec![value, live], "the phi keeps the predecessor that remains");
            // The header stays, its branch on a constant; what computed its condition is gone.
            assert_eq!(blocks[0], (9, vec![op::SELECTION_MERGE, op::BRANCH_CONDITIONAL]));
            let (at, _, _) = instructions(&pruned).find(|i| i.1 == op::BRANCH_CONDITIONAL).unwrap();
            let kind = if mask == 0 { op::CONSTANT_FALSE } else { op::CONSTANT_TRUE };
            let constant = instructions(&pruned).find(|i| i.1 == kind).expect("a boolean constant");
            assert_eq!((pruned[constant.0 + 1], pruned[constant.0 + 2]), (4, pruned[at + 1]));
        }
    }

    /// `loop { i = phi(0, i + 1); if features & 1 == 0 { break } }`: the continue block runs only
    /// with the feature.
    fn a_loop() -> Vec<u32> {
        module(&[
            inst(op::LABEL, &[9]),
            inst(op::BRANCH, &[16]),
            inst(op::LABEL, &[16]),
            inst(op::PHI, &[3, 15, 7, 9, 14, 18]),
            inst(op::LOOP_MERGE, &[19, 18, 0]),
            inst(op::BRANCH, &[17]),
            inst(op::LABEL, &[17]),
            inst(62, &[21, 15]), // OpStore %21 %15
            inst(op::BITWISE_AND, &[3, 10, 5, 6]),
            inst(op::I_NOT_EQUAL, &[4, 11, 10, 7]),
            inst(op::BRANCH_CONDITIONAL, &[11, 18, 19]),
            inst(op::LABEL, &[18]),
            inst(op::I_ADD, &[3, 14, 15, 6]),
            inst(op::BRANCH, &[16]),
            inst(op::LABEL, &[19]),
            inst(62, &[21, 15]), // OpStore %21 %15
            inst(253, &[]),      // OpReturn
        ])
    }

    #[test]
    fn a_loop_that_cannot_continue_keeps_its_back_edge() {
        let off = pruned(&a_loop(), 0, 0).unwrap();
        let blocks = blocks_of(&off);
        assert_eq!(blocks[3], (18, vec![op::BRANCH]), "the continue block branches to the header alone");
        let phi = phi_of(&off);
        assert_eq!((phi[0], phi[1], phi[3]), (7, 9, 18));
        let undef = instructions(&off).find(|i| i.1 == op::UNDEF).expect("an OpUndef for the lost value");
        assert_eq!(off[undef.0 + 1..undef.0 + 3], [3, phi[2]]);
        assert!(off[3] > phi[2], "the bound covers the new id");
        // With the feature the loop never leaves: its merge block is a stub.
        let on = pruned(&a_loop(), 1, 0).unwrap();
        assert_eq!(blocks_of(&on)[4], (19, vec![op::UNREACHABLE]));
        assert_eq!(phi_of(&on), vec![7, 9, 14, 18]);
    }

    /// Any word after the header set to an id past the bound, or any instruction one word short:
    /// the pruner refuses the module or prunes it, and never panics.
    #[test]
    fn a_malformed_module_is_refused_not_a_panic() {
        for module in [selection(true), a_loop()] {
            let mut variants: Vec<Vec<u32>> = (5..module.len())
                .map(|at| {
                    let mut words = module.clone();
                    words[at] = u32::MAX;
                    words
                })
                .collect();
            for (at, op, len) in instructions(&module).filter(|i| i.2 > 1) {
                let mut words = module.clone();
                words.remove(at + len - 1);
                words[at] = ((len - 1) as u32) << 16 | op;
                variants.push(words);
            }
            for words in variants {
                let _ = pruned(&words, 0, 0);
                let _ = pruned(&words, 1, 0);
            }
        }
    }

    #[test]
    fn only_modules_it_knows_are_pruned() {
        assert!(pruned(&selection(false), 0, 0).is_some());
        let mut unknown = selection(false);
        // An instruction this does not know, in a body (opcode 9999, three words).
        let at = instructions(&unknown).find(|i| i.1 == op::I_ADD).unwrap().0;
        unknown.splice(at..at, inst(9999, &[3, 30]));
        assert!(pruned(&unknown, 0, 0).is_none(), "an unknown instruction");
        assert!(pruned(&[0, 0, 0, 0, 0], 0, 0).is_none(), "no magic number");
        let mut words = kernel();
        words.truncate(words.len() - 1);
        assert!(pruned(&words, 0, 1).is_none(), "a truncated module");
    }
}
