//! What can run: sparse conditional constant propagation over one function's blocks from the
//! frozen constants (which blocks can run, which integer and boolean values are constants), and
//! what becomes of each block (`Fate`), as `prune`'s module doc describes.
use super::opcodes::{self as op, body_no_result, body_result, well_formed};
use std::collections::{HashMap, HashSet};

/// What the analysis knows of a value: nothing yet (no path that defines it has been found to run),
/// one constant (integers as their low bits, booleans as 0 and 1), or that it varies. It only moves
/// down that list.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Value {
    Unknown,
    Known(u64),
    Varying,
}

impl Value {
    /// What a phi of the two is.
    pub(super) fn meet(self, other: Value) -> Value {
        match (self, other) {
            (Value::Unknown, v) | (v, Value::Unknown) => v,
            (Value::Known(a), Value::Known(b)) if a == b => self,
            _ => Value::Varying,
        }
    }
}

/// The scalar types the analysis folds; everything else varies.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Scalar {
    Other,
    Bool,
    Int { width: u32, signed: bool },
}

/// One instruction: where it starts, its opcode and its length in words.
#[derive(Clone, Copy)]
pub(super) struct Inst {
    pub(super) at: usize,
    pub(super) op: u32,
    pub(super) len: usize,
}

/// One block of a function: instructions `first..=last` (its label first, its terminator last) and
/// its merge instruction, if it heads a construct.
pub(super) struct Block {
    pub(super) label: u32,
    pub(super) first: usize,
    pub(super) last: usize,
    pub(super) merge: Option<usize>,
    /// Where a selection header whose construct the analysis emptied branches instead (`analyse`).
    pub(super) collapse: Option<u32>,
}

/// What becomes of a block.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Fate {
    Kept,
    Unreachable,
    BranchTo(u32),
    Gone,
}

pub(super) struct Module<'a> {
    pub(super) words: &'a [u32],
    pub(super) insts: Vec<Inst>,
    /// Per id: its type's id (0 where it has none), what is known of its value, its scalar kind
    /// (for type ids).
    pub(super) type_of: Vec<u32>,
    pub(super) value: Vec<Value>,
    pub(super) scalar: Vec<Scalar>,
}

impl Module<'_> {
    pub(super) fn w(&self, i: usize) -> &[u32] {
        let Inst { at, len, .. } = self.insts[i];
        &self.words[at..at + len]
    }

    /// The blocks of the function whose instructions after `OpFunction` are `from..end` (`end`:
    /// its `OpFunctionEnd`); records the types of its results, and marks them unknown.
    pub(super) fn blocks(&mut self, from: usize, end: usize) -> Option<Vec<Block>> {
        let mut blocks = Vec::new();
        let mut current: Option<Block> = None;
        for i in from..end {
            let Inst { op, len, .. } = self.insts[i];
            if !well_formed(op, len) {
                return None;
            }
            let w = self.w(i);
            let (ty, res) = match op {
                op::FUNCTION_PARAMETER if current.is_none() => (w[1], w[2]),
                op::LABEL => {
                    if current.is_some() || w.len() != 2 || w[1] as usize >= self.type_of.len() {
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
                _ if body_result(op) => (w[1], w[2]),
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
    pub(super) fn analyse(&mut self, blocks: &mut [Block]) -> Option<Vec<Fate>> {
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
    pub(super) fn kept_targets(&self, b: &Block) -> Vec<u32> {
        match b.collapse {
            Some(side) => vec![side],
            None => self.targets(b.last),
        }
    }

    /// Every block a terminator names.
    pub(super) fn targets(&self, term: usize) -> Vec<u32> {
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
    pub(super) fn taken(&self, term: usize) -> Vec<u32> {
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
    pub(super) fn literal_words(&self, selector: usize) -> usize {
        match self.scalar.get(*self.type_of.get(selector).unwrap_or(&0) as usize) {
            Some(Scalar::Int { width, .. }) if *width > 32 => 2,
            _ => 1,
        }
    }

    /// What instruction `w` (opcode `op`, with a result type and id) computes from what is known of
    /// its operands.
    pub(super) fn fold(&self, op: u32, w: &[u32]) -> Value {
        // (Ids are below the bound by `blocks`' and the globals' checks; `get` keeps that local.)
        let result = self.scalar.get(w[1] as usize).copied().unwrap_or(Scalar::Other);
        if result == Scalar::Other {
            return Value::Varying;
        }
        let value = |k: usize| {
            w.get(k).and_then(|&id| self.value.get(id as usize)).copied().unwrap_or(Value::Varying)
        };
        let scalar_of =
            |id: u32| self.type_of.get(id as usize).and_then(|&ty| self.scalar.get(ty as usize)).copied();
        let width_of = |k: usize| match w.get(k).and_then(|&id| scalar_of(id)) {
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
}
