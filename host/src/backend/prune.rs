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
//! What is rewritten: the frozen `OpSpecConstant`s become `OpConstant`s (their `SpecId`s go); a block
//! that cannot run is deleted, or, where a block that runs still names it (a branch target, a merge
//! or continue block), reduced to a label and `OpUnreachable` (a back edge of a loop that runs: a
//! label and a branch to the loop's header); each `OpPhi` keeps the predecessors that remain
//! (`OpUndef` for a value no longer defined). A block that can run is kept whole, its terminator
//! untouched, so the structured control flow of what remains is the kernel's own. Debug
//! instructions (names, lines, sources) are dropped. A module with an instruction this does not
//! know (`BODY_RESULTS`, `BODY_NO_RESULT`) is not pruned: the caller then runs it specialised.
use super::spirv::{instructions, DECORATION_SPEC_ID, MAGIC, OP_DECORATE};
use std::collections::{HashMap, HashSet};

/// Whether to prune: unless `CAUSTIC_PRUNE=0` (the tests set it to check that the unpruned kernel
/// renders the same image), on every adapter (hardware for speed, software for compile time).
pub fn wanted() -> bool {
    std::env::var("CAUSTIC_PRUNE").as_deref() != Ok("0")
}

/// `words` with spec constant 0 frozen at `mask` and 1 at `path_loop` (`PathLoop::spec_value`), and
/// the blocks they disable removed; `None` where the module is not one this can prune.
pub fn pruned(words: &[u32], mask: u32, path_loop: u32) -> Option<Vec<u32>> {
    prune(words, &[(0, mask), (1, path_loop)])
}

mod op {
    pub const UNDEF: u32 = 1;
    pub const SOURCE_CONTINUED: u32 = 2;
    pub const SOURCE: u32 = 3;
    pub const SOURCE_EXTENSION: u32 = 4;
    pub const NAME: u32 = 5;
    pub const MEMBER_NAME: u32 = 6;
    pub const STRING: u32 = 7;
    pub const LINE: u32 = 8;
    pub const TYPE_BOOL: u32 = 20;
    pub const TYPE_INT: u32 = 21;
    pub const CONSTANT_TRUE: u32 = 41;
    pub const CONSTANT_FALSE: u32 = 42;
    pub const CONSTANT: u32 = 43;
    pub const CONSTANT_NULL: u32 = 46;
    pub const SPEC_CONSTANT_TRUE: u32 = 48;
    pub const SPEC_CONSTANT_FALSE: u32 = 49;
    pub const SPEC_CONSTANT: u32 = 50;
    pub const FUNCTION: u32 = 54;
    pub const FUNCTION_PARAMETER: u32 = 55;
    pub const FUNCTION_END: u32 = 56;
    pub const DECORATION_GROUP: u32 = 73;
    pub const GROUP_DECORATE: u32 = 74;
    pub const GROUP_MEMBER_DECORATE: u32 = 75;
    pub const COPY_OBJECT: u32 = 83;
    pub const U_CONVERT: u32 = 113;
    pub const S_CONVERT: u32 = 114;
    pub const BITCAST: u32 = 124;
    pub const S_NEGATE: u32 = 126;
    pub const I_ADD: u32 = 128;
    pub const I_SUB: u32 = 130;
    pub const I_MUL: u32 = 132;
    pub const U_DIV: u32 = 134;
    pub const U_MOD: u32 = 137;
    pub const LOGICAL_EQUAL: u32 = 164;
    pub const LOGICAL_NOT_EQUAL: u32 = 165;
    pub const LOGICAL_OR: u32 = 166;
    pub const LOGICAL_AND: u32 = 167;
    pub const LOGICAL_NOT: u32 = 168;
    pub const SELECT: u32 = 169;
    pub const I_EQUAL: u32 = 170;
    pub const I_NOT_EQUAL: u32 = 171;
    pub const U_GREATER_THAN: u32 = 172;
    pub const S_GREATER_THAN: u32 = 173;
    pub const U_GREATER_THAN_EQUAL: u32 = 174;
    pub const S_GREATER_THAN_EQUAL: u32 = 175;
    pub const U_LESS_THAN: u32 = 176;
    pub const S_LESS_THAN: u32 = 177;
    pub const U_LESS_THAN_EQUAL: u32 = 178;
    pub const S_LESS_THAN_EQUAL: u32 = 179;
    pub const SHIFT_RIGHT_LOGICAL: u32 = 194;
    pub const SHIFT_RIGHT_ARITHMETIC: u32 = 195;
    pub const SHIFT_LEFT_LOGICAL: u32 = 196;
    pub const BITWISE_OR: u32 = 197;
    pub const BITWISE_XOR: u32 = 198;
    pub const BITWISE_AND: u32 = 199;
    pub const NOT: u32 = 200;
    pub const PHI: u32 = 245;
    pub const LOOP_MERGE: u32 = 246;
    pub const SELECTION_MERGE: u32 = 247;
    pub const LABEL: u32 = 248;
    pub const BRANCH: u32 = 249;
    pub const BRANCH_CONDITIONAL: u32 = 250;
    pub const SWITCH: u32 = 251;
    pub const UNREACHABLE: u32 = 255;
    pub const NO_LINE: u32 = 317;
    pub const MODULE_PROCESSED: u32 = 330;
    pub const DECORATE_ID: u32 = 332;
    pub const DECORATE_STRING: u32 = 5632;
}

/// Instructions in a function body with a result type and a result id (words 1 and 2): the
/// extended instructions, calls, variables, loads, access chains, composites, conversions,
/// arithmetic, relational and logical, bit operations, atomics, `OpPhi`, `OpCopyLogical`.
fn body_result(op: u32) -> bool {
    matches!(op, op::UNDEF | 12 | 57 | 59..=61 | 65..=68 | 70 | 77..=84 | 109..=152 | 154..=159
        | 164..=191 | 194..=205 | 227 | 229..=242 | op::PHI | 400)
}

/// Instructions in a function body without a result: lines, stores and copies, barriers, an
/// atomic store, merges, branches and the other terminators, lifetimes, `OpTerminateInvocation`.
fn body_no_result(op: u32) -> bool {
    matches!(op, 0 | op::LINE | op::NO_LINE | 62..=64 | 224 | 225 | 228 | op::LOOP_MERGE
        | op::SELECTION_MERGE | op::BRANCH..=op::UNREACHABLE | 256 | 257 | 4416)
}

fn debug(op: u32) -> bool {
    matches!(
        op,
        op::SOURCE_CONTINUED
            | op::SOURCE
            | op::SOURCE_EXTENSION
            | op::NAME
            | op::MEMBER_NAME
            | op::STRING
            | op::LINE
            | op::NO_LINE
            | op::MODULE_PROCESSED
    )
}

/// What the analysis knows of a value: nothing yet (no path that defines it has been found to run),
/// one constant (integers as their low bits, booleans as 0 and 1), or that it varies. It only moves
/// down that list.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Value {
    Unknown,
    Known(u64),
    Varying,
}

impl Value {
    /// What a phi of the two is.
    fn meet(self, other: Value) -> Value {
        match (self, other) {
            (Value::Unknown, v) | (v, Value::Unknown) => v,
            (Value::Known(a), Value::Known(b)) if a == b => self,
            _ => Value::Varying,
        }
    }
}

/// The scalar types the analysis folds; everything else varies.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scalar {
    Other,
    Bool,
    Int { width: u32, signed: bool },
}

/// One instruction: where it starts, its opcode and its length in words.
#[derive(Clone, Copy)]
struct Inst {
    at: usize,
    op: u32,
    len: usize,
}

/// One block of a function: instructions `first..=last` (its label first, its terminator last) and
/// its merge instruction, if it heads a construct.
struct Block {
    label: u32,
    first: usize,
    last: usize,
    merge: Option<usize>,
    /// Where a selection header whose construct the analysis emptied branches instead (`analyse`).
    collapse: Option<u32>,
}

/// What becomes of a block.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Fate {
    Kept,
    Unreachable,
    BranchTo(u32),
    Gone,
}

/// Global instructions the rewrite adds (undefs for phis, boolean constants for decided branches),
/// with the ids it gives them from the module's bound up.
struct NewGlobals {
    words: Vec<u32>,
    next_id: u32,
    made: HashMap<(u32, u32, u32), u32>,
}

impl NewGlobals {
    /// The id of `OpUndef` (`op::UNDEF`, `value` 0) or a boolean constant of type `ty`, made once.
    fn get(&mut self, op: u32, ty: u32) -> u32 {
        let next = &mut self.next_id;
        let words = &mut self.words;
        *self.made.entry((op, ty, 0)).or_insert_with(|| {
            words.extend_from_slice(&[3 << 16 | op, ty, *next]);
            *next += 1;
            *next - 1
        })
    }

    fn undef(&mut self, ty: u32) -> u32 {
        self.get(op::UNDEF, ty)
    }

    fn boolean(&mut self, ty: u32, value: bool) -> u32 {
        self.get(if value { op::CONSTANT_TRUE } else { op::CONSTANT_FALSE }, ty)
    }
}

struct Module<'a> {
    words: &'a [u32],
    insts: Vec<Inst>,
    /// Per id: its type's id (0 where it has none), what is known of its value, its scalar kind
    /// (for type ids).
    type_of: Vec<u32>,
    value: Vec<Value>,
    scalar: Vec<Scalar>,
}

/// `words` with spec constants frozen (`(spec id, value)`) and the blocks that cannot run removed.
fn prune(words: &[u32], frozen: &[(u32, u32)]) -> Option<Vec<u32>> {
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
                m.type_of[id(2)?] = w[1];
                m.value[id(2)?] = Value::Known((i.op == op::CONSTANT_TRUE) as u64);
            }
            op::CONSTANT | op::CONSTANT_NULL | op::SPEC_CONSTANT if w.len() >= 3 => {
                let (ty, res) = (id(1)?, id(2)?);
                m.type_of[res] = ty as u32;
                let literal = match (i.op, w.len()) {
                    (op::CONSTANT_NULL, _) => Some(0),
                    (op::SPEC_CONSTANT, _) => frozen_value(res as u32).map(u64::from),
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

    // Functions: each one's blocks, analysed, then written.
    let mut bodies: Vec<u32> = Vec::new();
    let mut removed = vec![false; bound];
    let mut globals = NewGlobals { words: Vec::new(), next_id: bound as u32, made: HashMap::new() };
    let mut at = first_function;
    while at < m.insts.len() {
        if m.insts[at].op != op::FUNCTION {
            return None;
        }
        let end = at + m.insts[at..].iter().position(|i| i.op == op::FUNCTION_END)?;
        let blocks = m.blocks(at + 1, end)?;
        let mut blocks = blocks;
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
        if debug(i.op) || targets_removed || frees_spec {
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

impl Module<'_> {
    fn w(&self, i: usize) -> &[u32] {
        let Inst { at, len, .. } = self.insts[i];
        &self.words[at..at + len]
    }

    /// The blocks of the function whose instructions after `OpFunction` are `from..end` (`end`:
    /// its `OpFunctionEnd`); records the types of its results, and marks them unknown.
    fn blocks(&mut self, from: usize, end: usize) -> Option<Vec<Block>> {
        let mut blocks = Vec::new();
        let mut current: Option<Block> = None;
        for i in from..end {
            let Inst { op, .. } = self.insts[i];
            let w = self.w(i);
            let (ty, res) = match op {
                op::FUNCTION_PARAMETER if current.is_none() => (w[1], w[2]),
                op::LABEL => {
                    if current.is_some() || w.len() != 2 {
                        return None;
                    }
                    current = Some(Block { label: w[1], first: i, last: i, merge: None, collapse: None });
                    continue;
                }
                _ if current.is_none() => return None,
                op::LOOP_MERGE | op::SELECTION_MERGE => {
                    current.as_mut()?.merge = Some(i);
                    continue;
                }
                op::BRANCH..=op::UNREACHABLE | 4416 => {
                    let mut block = current.take()?;
                    block.last = i;
                    blocks.push(block);
                    continue;
                }
                _ if body_no_result(op) => continue,
                _ if body_result(op) && w.len() >= 3 => (w[1], w[2]),
                _ => return None,
            };
            let (ty, res) = (ty as usize, res as usize);
            if ty >= self.type_of.len() || res >= self.type_of.len() {
                return None;
            }
            self.type_of[res] = ty as u32;
            if op != op::FUNCTION_PARAMETER {
                self.value[res] = Value::Unknown;
            }
        }
        (current.is_none() && !blocks.is_empty()).then_some(blocks)
    }

    /// Sparse conditional constant propagation over one function's blocks, to a fixed point; then
    /// what becomes of each block.
    fn analyse(&mut self, blocks: &mut [Block]) -> Option<Vec<Fate>> {
        let index: HashMap<u32, usize> = blocks.iter().enumerate().map(|(k, b)| (b.label, k)).collect();
        let mut runs = vec![false; blocks.len()];
        let mut edges: HashSet<(u32, u32)> = HashSet::new();
        runs[0] = true;
        loop {
            let mut changed = false;
            for (k, b) in blocks.iter().enumerate() {
                if !runs[k] {
                    continue;
                }
                for i in b.first + 1..b.last {
                    let (op, w) = (self.insts[i].op, self.w(i));
                    if !body_result(op) {
                        continue;
                    }
                    let res = w[2] as usize;
                    let computed = if op == op::PHI {
                        w[3..]
                            .chunks(2)
                            .filter(|p| p.len() == 2 && edges.contains(&(p[1], b.label)))
                            .fold(Value::Unknown, |v, p| {
                                v.meet(self.value.get(p[0] as usize).copied().unwrap_or(Value::Varying))
                            })
                    } else {
                        self.fold(op, w)
                    };
                    let old = self.value[res];
                    let new = match computed {
                        Value::Unknown => old,
                        _ => old.meet(computed),
                    };
                    if new != old {
                        self.value[res] = new;
                        changed = true;
                    }
                }
                for target in self.taken(b.last) {
                    let &t = index.get(&target)?;
                    if edges.insert((b.label, target)) {
                        changed = true;
                    }
                    if !runs[t] {
                        runs[t] = true;
                        changed = true;
                    }
                }
            }
            if changed {
                continue;
            }
            // A branch on a value still unknown at the fixed point (none was seen in the kernel):
            // take it as varying, both ways.
            let mut undecided = false;
            for (k, b) in blocks.iter().enumerate() {
                let selector = matches!(self.insts[b.last].op, op::BRANCH_CONDITIONAL | op::SWITCH)
                    .then(|| self.w(b.last)[1] as usize);
                if let Some(s) = selector.filter(|&s| runs[k] && self.value.get(s) == Some(&Value::Unknown)) {
                    self.value[s] = Value::Varying;
                    undecided = true;
                }
            }
            if !undecided {
                break;
            }
        }

        // Selections decided for an empty side: their merge block, or a block that only branches
        // there. Their header then branches to it unconditionally, without the merge: no block is
        // left in the construct that could break out to its merge.
        for k in 0..blocks.len() {
            let b = &blocks[k];
            let Some(merge) = b.merge.filter(|&m| runs[k] && self.insts[m].op == op::SELECTION_MERGE) else {
                continue;
            };
            let w = self.w(b.last);
            let decided = self.insts[b.last].op == op::BRANCH_CONDITIONAL
                && matches!(self.value.get(w[1] as usize), Some(Value::Known(_)));
            let merge_block = self.w(merge)[1];
            let taken = self.taken(b.last);
            let empty = |t: u32| {
                t == merge_block
                    || index.get(&t).is_some_and(|&j| {
                        let side = &blocks[j];
                        side.merge.is_none()
                            && (side.first + 1..side.last)
                                .all(|i| matches!(self.insts[i].op, op::LINE | op::NO_LINE))
                            && self.insts[side.last].op == op::BRANCH
                            && self.w(side.last)[1] == merge_block
                    })
            };
            if decided && taken.len() == 1 && empty(taken[0]) {
                blocks[k].collapse = Some(taken[0]);
            }
        }
        let blocks: &[Block] = blocks;

        // Fates: blocks that run are kept; of the others, those a kept block still names become
        // stubs (back edges of kept loops branch to their header), the rest go.
        let mut fates: Vec<Fate> = runs.iter().map(|&r| if r { Fate::Kept } else { Fate::Gone }).collect();
        let stub = |fates: &mut Vec<Fate>, label: u32, fate: Fate| -> Option<()> {
            let &t = index.get(&label)?;
            if fates[t] == Fate::Gone || (fates[t] == Fate::Unreachable && fate != Fate::Unreachable) {
                fates[t] = fate;
            }
            Some(())
        };
        for (k, b) in blocks.iter().enumerate() {
            let Some(merge) = b.merge.filter(|_| runs[k]) else { continue };
            let w = self.w(merge);
            if self.insts[merge].op == op::LOOP_MERGE && w.len() >= 3 {
                let (header, continue_target) = (b.label, w[2]);
                if !runs[*index.get(&continue_target)?] {
                    stub(&mut fates, continue_target, Fate::BranchTo(header))?;
                } else {
                    // The loop's back-edge blocks that cannot run keep the one back edge.
                    for (j, other) in blocks.iter().enumerate() {
                        if !runs[j] && self.targets(other.last).contains(&header) {
                            stub(&mut fates, other.label, Fate::BranchTo(header))?;
                        }
                    }
                }
            }
        }
        for (k, b) in blocks.iter().enumerate() {
            if !runs[k] {
                continue;
            }
            let mut named = self.kept_targets(b);
            if let Some(merge) = b.merge.filter(|_| b.collapse.is_none()) {
                let w = self.w(merge);
                named.push(*w.get(1)?);
                if self.insts[merge].op == op::LOOP_MERGE {
                    named.push(*w.get(2)?);
                }
            }
            for label in named {
                stub(&mut fates, label, Fate::Unreachable)?;
            }
        }
        Some(fates)
    }

    /// Every block a kept block's terminator names once rewritten.
    fn kept_targets(&self, b: &Block) -> Vec<u32> {
        match b.collapse {
            Some(side) => vec![side],
            None => self.targets(b.last),
        }
    }

    /// Every block a terminator names.
    fn targets(&self, term: usize) -> Vec<u32> {
        let w = self.w(term);
        match self.insts[term].op {
            op::BRANCH => vec![w[1]],
            op::BRANCH_CONDITIONAL => vec![w[2], w[3]],
            op::SWITCH => {
                let step = 1 + self.literal_words(w[1] as usize);
                let mut t = vec![w[2]];
                t.extend(w[3..].chunks(step).filter(|c| c.len() == step).map(|c| c[step - 1]));
                t
            }
            _ => Vec::new(),
        }
    }

    /// The blocks a terminator can reach, given what is known of its condition or selector.
    fn taken(&self, term: usize) -> Vec<u32> {
        let w = self.w(term);
        let value = |id: u32| self.value.get(id as usize).copied().unwrap_or(Value::Varying);
        match (self.insts[term].op, w.get(1).map(|&c| value(c))) {
            (op::BRANCH_CONDITIONAL, Some(Value::Known(c))) => vec![if c != 0 { w[2] } else { w[3] }],
            (op::SWITCH, Some(Value::Known(s))) => {
                let words = self.literal_words(w[1] as usize);
                let step = 1 + words;
                let case = w[3..].chunks(step).filter(|c| c.len() == step).find(|c| {
                    let literal = if words == 2 { c[0] as u64 | (c[1] as u64) << 32 } else { c[0] as u64 };
                    literal == s
                });
                vec![case.map_or(w[2], |c| c[step - 1])]
            }
            (op::BRANCH_CONDITIONAL | op::SWITCH, Some(Value::Unknown)) => Vec::new(),
            _ => self.targets(term),
        }
    }

    /// Words per case literal of a switch on `selector`.
    fn literal_words(&self, selector: usize) -> usize {
        match self.scalar.get(*self.type_of.get(selector).unwrap_or(&0) as usize) {
            Some(Scalar::Int { width, .. }) if *width > 32 => 2,
            _ => 1,
        }
    }

    /// What instruction `w` (opcode `op`, with a result type and id) computes from what is known of
    /// its operands.
    fn fold(&self, op: u32, w: &[u32]) -> Value {
        let result = self.scalar[w[1] as usize];
        if result == Scalar::Other {
            return Value::Varying;
        }
        let value = |k: usize| {
            w.get(k).and_then(|&id| self.value.get(id as usize)).copied().unwrap_or(Value::Varying)
        };
        let width_of = |k: usize| match w.get(k).map(|&id| self.scalar[self.type_of[id as usize] as usize]) {
            Some(Scalar::Int { width, .. }) => width,
            Some(Scalar::Bool) => 1,
            _ => 0,
        };
        let mask = |width: u32| if width >= 64 { u64::MAX } else { (1u64 << width) - 1 };
        let signed = |v: u64, width: u32| {
            if width == 0 || width >= 64 {
                v as i64
            } else {
                ((v << (64 - width)) as i64) >> (64 - width)
            }
        };
        let out_width = match result {
            Scalar::Int { width, .. } => width,
            _ => 1,
        };
        let (a, b) = (value(3), value(4));
        // Operands that decide the result whatever the other is.
        match (op, a, b) {
            (op::BITWISE_AND | op::I_MUL | op::LOGICAL_AND, Value::Known(0), _)
            | (op::BITWISE_AND | op::I_MUL | op::LOGICAL_AND, _, Value::Known(0)) => return Value::Known(0),
            (op::LOGICAL_OR, Value::Known(1), _) | (op::LOGICAL_OR, _, Value::Known(1)) => {
                return Value::Known(1)
            }
            (op::SELECT, Value::Known(c), _) => return value(if c != 0 { 4 } else { 5 }),
            (op::SELECT, Value::Varying, _) => {
                return match (value(4), value(5)) {
                    (Value::Known(x), Value::Known(y)) if x == y => Value::Known(x),
                    (Value::Unknown, _) | (_, Value::Unknown) => Value::Unknown,
                    _ => Value::Varying,
                }
            }
            _ => {}
        }
        let unary = matches!(
            op,
            op::COPY_OBJECT
                | op::U_CONVERT
                | op::S_CONVERT
                | op::BITCAST
                | op::S_NEGATE
                | op::NOT
                | op::LOGICAL_NOT
        );
        let operands = if unary { [a, a] } else { [a, b] };
        if operands.contains(&Value::Varying) {
            return Value::Varying;
        }
        let (Value::Known(x), Value::Known(y)) = (operands[0], operands[1]) else {
            return Value::Unknown;
        };
        let width = width_of(3);
        let (sx, sy) = (signed(x, width), signed(y, width_of(4)));
        let bool_of = |c: bool| Some(c as u64);
        let folded = match op {
            op::COPY_OBJECT => Some(x),
            op::U_CONVERT => Some(x),
            op::S_CONVERT => Some(sx as u64),
            op::BITCAST if width == out_width => Some(x),
            op::S_NEGATE => Some(x.wrapping_neg()),
            op::NOT => Some(!x),
            op::LOGICAL_NOT => Some((x == 0) as u64),
            op::I_ADD => Some(x.wrapping_add(y)),
            op::I_SUB => Some(x.wrapping_sub(y)),
            op::I_MUL => Some(x.wrapping_mul(y)),
            op::U_DIV if y != 0 => Some(x / y),
            op::U_MOD if y != 0 => Some(x % y),
            op::BITWISE_AND => Some(x & y),
            op::BITWISE_OR => Some(x | y),
            op::BITWISE_XOR => Some(x ^ y),
            op::SHIFT_RIGHT_LOGICAL if y < width as u64 => Some(x >> y),
            op::SHIFT_RIGHT_ARITHMETIC if y < width as u64 => Some((sx >> y) as u64),
            op::SHIFT_LEFT_LOGICAL if y < out_width as u64 => Some(x << y),
            op::LOGICAL_AND => bool_of(x != 0 && y != 0),
            op::LOGICAL_OR => bool_of(x != 0 || y != 0),
            op::LOGICAL_EQUAL | op::I_EQUAL => bool_of(x == y),
            op::LOGICAL_NOT_EQUAL | op::I_NOT_EQUAL => bool_of(x != y),
            op::U_GREATER_THAN => bool_of(x > y),
            op::U_GREATER_THAN_EQUAL => bool_of(x >= y),
            op::U_LESS_THAN => bool_of(x < y),
            op::U_LESS_THAN_EQUAL => bool_of(x <= y),
            op::S_GREATER_THAN => bool_of(sx > sy),
            op::S_GREATER_THAN_EQUAL => bool_of(sx >= sy),
            op::S_LESS_THAN => bool_of(sx < sy),
            op::S_LESS_THAN_EQUAL => bool_of(sx <= sy),
            _ => None,
        };
        folded.map_or(Value::Varying, |v| Value::Known(v & mask(out_width)))
    }

    /// Which results of the kept blocks are used (by index of id), marking the others `removed`:
    /// marked from every instruction with an effect (stores, atomics, calls, merges, terminators),
    /// through every word of a used instruction that names a result of the function (a literal
    /// that happens to equal one only keeps a dead value). A decided branch's condition and a
    /// decided select's condition are not uses: the rewrite replaces them.
    fn live(&self, blocks: &[Block], fates: &[Fate], removed: &mut [bool]) -> Vec<bool> {
        let mut defined: HashMap<u32, usize> = HashMap::new();
        let mut work: Vec<usize> = Vec::new();
        for (b, _) in blocks.iter().zip(fates).filter(|(_, f)| **f == Fate::Kept) {
            for i in b.first + 1..=b.last {
                let op = self.insts[i].op;
                if body_result(op) {
                    defined.insert(self.w(i)[2], i);
                }
                let effect = matches!(op, 57 | 227 | 229..=242)
                    || (body_no_result(op) && op != op::LINE && op != op::NO_LINE);
                if effect {
                    work.push(i);
                }
            }
        }
        let mut live = vec![false; removed.len()];
        let decided = |id: u32| matches!(self.value.get(id as usize), Some(Value::Known(_)));
        while let Some(i) = work.pop() {
            let (op, w) = (self.insts[i].op, self.w(i));
            let skip = match op {
                op::BRANCH_CONDITIONAL if decided(w[1]) => 2,
                op::SELECT if decided(w[3]) => 4,
                _ if body_result(op) => 3,
                _ => 1,
            };
            let picked = (op == op::SELECT && skip == 4).then(|| {
                if self.value[w[3] as usize] == Value::Known(0) {
                    w[5]
                } else {
                    w[4]
                }
            });
            let uses: Vec<u32> = match picked {
                Some(p) => vec![p],
                None => w[skip.min(w.len())..].to_vec(),
            };
            for id in uses {
                if let Some(&d) = defined.get(&id) {
                    if !live[id as usize] {
                        live[id as usize] = true;
                        work.push(d);
                    }
                }
            }
        }
        for (&id, _) in defined.iter().filter(|(&id, _)| !live[id as usize]) {
            removed[id as usize] = true;
        }
        live
    }

    /// Writes function `from..=end` (its `OpFunction` to its `OpFunctionEnd`) with the blocks' fates
    /// into `out`: records the ids it no longer defines in `removed`, and the undefs its phis need.
    #[allow(clippy::too_many_arguments)]
    fn write(
        &self,
        from: usize,
        end: usize,
        blocks: &[Block],
        fates: &[Fate],
        removed: &mut [bool],
        globals: &mut NewGlobals,
        out: &mut Vec<u32>,
    ) -> Option<()> {
        // Ids defined in blocks whose contents go (a stub keeps its label alone).
        for (b, fate) in blocks.iter().zip(fates) {
            if *fate == Fate::Kept {
                continue;
            }
            if *fate == Fate::Gone {
                removed[b.label as usize] = true;
            }
            for i in b.first + 1..b.last {
                if body_result(self.insts[i].op) {
                    removed[self.w(i)[2] as usize] = true;
                }
            }
        }
        // Each remaining block's predecessors, in the order their branches appear.
        let mut preds: HashMap<u32, Vec<u32>> = HashMap::new();
        for (b, fate) in blocks.iter().zip(fates) {
            let successors = match fate {
                Fate::Kept => self.kept_targets(b),
                Fate::BranchTo(header) => vec![*header],
                _ => Vec::new(),
            };
            for s in successors {
                let list = preds.entry(s).or_default();
                if !list.contains(&b.label) {
                    list.push(b.label);
                }
            }
        }
        let live = self.live(blocks, fates, removed);
        let known = |id: u32| match self.value.get(id as usize) {
            Some(Value::Known(v)) => Some(*v != 0),
            _ => None,
        };

        for i in from..blocks[0].first {
            if self.insts[i].op != op::LINE && self.insts[i].op != op::NO_LINE {
                out.extend_from_slice(self.w(i));
            }
        }
        for (b, fate) in blocks.iter().zip(fates) {
            match fate {
                Fate::Gone => {}
                Fate::Unreachable => {
                    out.extend_from_slice(&[2 << 16 | op::LABEL, b.label, 1 << 16 | op::UNREACHABLE])
                }
                Fate::BranchTo(header) => {
                    out.extend_from_slice(&[2 << 16 | op::LABEL, b.label, 2 << 16 | op::BRANCH, *header])
                }
                Fate::Kept => {
                    let none = Vec::new();
                    let parents = preds.get(&b.label).unwrap_or(&none);
                    let collapsed = b.collapse;
                    for i in b.first..=b.last {
                        let (op, w) = (self.insts[i].op, self.w(i));
                        if op == op::LINE || op == op::NO_LINE {
                            continue;
                        }
                        if let Some(side) = collapsed.filter(|_| i == b.last || Some(i) == b.merge) {
                            if i == b.last {
                                out.extend_from_slice(&[2 << 16 | op::BRANCH, side]);
                            }
                            continue;
                        }
                        if body_result(op) && !live[w[2] as usize] {
                            continue;
                        }
                        match (op, w.get(1).and_then(|&c| known(c)), w.get(3).and_then(|&c| known(c))) {
                            // A decided branch: on a constant, its condition's computation dead.
                            (op::BRANCH_CONDITIONAL, Some(c), _) => {
                                let ty = self.type_of[w[1] as usize];
                                out.extend_from_slice(w);
                                let at = out.len() - w.len() + 1;
                                out[at] = globals.boolean(ty, c);
                            }
                            // A decided select: a copy of the operand it picks.
                            (op::SELECT, _, Some(c)) => {
                                let picked = if c { w[4] } else { w[5] };
                                out.extend_from_slice(&[4 << 16 | op::COPY_OBJECT, w[1], w[2], picked]);
                            }
                            (op::PHI, _, _) => {}
                            _ => out.extend_from_slice(w),
                        }
                        if op != op::PHI {
                            continue;
                        }
                        let start = out.len();
                        out.extend_from_slice(&[0, w[1], w[2]]);
                        // The phi's own order first, then the predecessors it did not name.
                        let given = w[3..].chunks(2).filter(|e| e.len() == 2).map(|e| (e[0], e[1]));
                        let named = given.clone().map(|e| e.1).collect::<Vec<_>>();
                        let mut entries: Vec<(u32, u32)> = Vec::new();
                        for (value, p) in
                            given.chain(parents.iter().filter(|p| !named.contains(p)).map(|&p| (0, p)))
                        {
                            if !parents.contains(&p) || entries.iter().any(|e| e.1 == p) {
                                continue;
                            }
                            let defined = value != 0 && !removed.get(value as usize).copied().unwrap_or(true);
                            entries.push((if defined { value } else { globals.undef(w[1]) }, p));
                        }
                        for (value, p) in entries {
                            out.extend_from_slice(&[value, p]);
                        }
                        out[start] = ((out.len() - start) as u32) << 16 | op::PHI;
                    }
                }
            }
        }
        out.extend_from_slice(self.w(end));
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::gpu::KERNEL_SPV;
    use crate::backend::spirv::declares_spec_constant;

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
            inst(253, &[]),      // OpReturn
        ]);
        module(&body)
    }

    #[test]
    fn a_selection_the_mask_empties_goes() {
        let off = pruned(&selection(false), 0, 0).unwrap();
        let blocks = blocks_of(&off);
        assert_eq!(blocks, vec![(9, vec![op::BRANCH]), (13, vec![op::PHI, 62, 253])], "header to merge");
        assert_eq!(phi_of(&off), vec![7, 9], "the phi keeps the predecessor that remains");
        assert!(!declares_spec_constant(&off, 0));
        let on = pruned(&selection(false), 1, 0).unwrap();
        assert_eq!(blocks_of(&on)[1], (12, vec![op::I_ADD, op::BRANCH]), "the enabled side stays whole");
        assert_eq!(phi_of(&on), vec![14, 12, 7, 9]);
        // An empty else block: the header branches to it, and it to the merge.
        let off = pruned(&selection_with(true, false), 0, 0).unwrap();
        let expected = vec![(9, vec![op::BRANCH]), (16, vec![op::BRANCH]), (13, vec![op::PHI, 62, 253])];
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
