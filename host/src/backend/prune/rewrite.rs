//! The rewrite of one function from its blocks' fates: the results nothing uses removed, decided
//! branches on constants, emptied selections collapsed, stubs written, phis mended, and the global
//! instructions that needs (`NewGlobals`).
use super::analysis::{Block, Fate, Module, Value};
use super::opcodes::{self as op, body_result, has_effect};
use std::collections::HashMap;

/// Global instructions the rewrite adds (undefs for phis, boolean constants for decided branches),
/// with the ids it gives them from the module's bound up.
pub(super) struct NewGlobals {
    pub(super) words: Vec<u32>,
    pub(super) next_id: u32,
    pub(super) made: HashMap<(u32, u32), u32>,
}

impl NewGlobals {
    /// The id of the instruction `op` (`OpUndef` or a boolean constant) of type `ty`, made once.
    pub(super) fn get(&mut self, op: u32, ty: u32) -> u32 {
        let next = &mut self.next_id;
        let words = &mut self.words;
        *self.made.entry((op, ty)).or_insert_with(|| {
            words.extend_from_slice(&[3 << 16 | op, ty, *next]);
            *next += 1;
            *next - 1
        })
    }

    pub(super) fn undef(&mut self, ty: u32) -> u32 {
        self.get(op::UNDEF, ty)
    }

    pub(super) fn boolean(&mut self, ty: u32, value: bool) -> u32 {
        self.get(if value { op::CONSTANT_TRUE } else { op::CONSTANT_FALSE }, ty)
    }
}

impl Module<'_> {
    /// Which results of the kept blocks are used (by index of id), marking the others `removed`:
    /// marked from every instruction with an effect (stores, atomics, calls, merges, terminators),
    /// through every word of a used instruction that names a result of the function (a literal
    /// that happens to equal one only keeps a dead value). A decided branch's condition and a
    /// decided select's condition are not uses: the rewrite replaces them.
    pub(super) fn live(&self, blocks: &[Block], fates: &[Fate], removed: &mut [bool]) -> Vec<bool> {
        let mut defined: HashMap<u32, usize> = HashMap::new();
        let mut live = vec![false; removed.len()];
        let mut work: Vec<usize> = Vec::new();
        for (b, _) in blocks.iter().zip(fates).filter(|(_, f)| **f == Fate::Kept) {
            for i in b.first + 1..=b.last {
                let op = self.insts[i].op;
                if body_result(op) {
                    defined.insert(self.w(i)[2], i);
                }
                if has_effect(op) {
                    // (An atomic's or a call's result may go unused; the instruction stays.)
                    if body_result(op) {
                        live[self.w(i)[2] as usize] = true;
                    }
                    work.push(i);
                }
            }
        }
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
    pub(super) fn write(
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
