//! The SPIR-V opcodes the pruner reads or writes, and which instructions of a function body have a
//! result (`body_result`), have none (`body_no_result`) or are debug information (`debug`): the one
//! place that knows instructions' shapes.

pub(super) const UNDEF: u32 = 1;
pub(super) const SOURCE_CONTINUED: u32 = 2;
pub(super) const SOURCE: u32 = 3;
pub(super) const SOURCE_EXTENSION: u32 = 4;
pub(super) const NAME: u32 = 5;
pub(super) const MEMBER_NAME: u32 = 6;
pub(super) const STRING: u32 = 7;
pub(super) const LINE: u32 = 8;
pub(super) const ENTRY_POINT: u32 = 15;
pub(super) const EXECUTION_MODE: u32 = 16;
pub(super) const TYPE_BOOL: u32 = 20;
pub(super) const TYPE_INT: u32 = 21;
pub(super) const CONSTANT_TRUE: u32 = 41;
pub(super) const CONSTANT_FALSE: u32 = 42;
pub(super) const CONSTANT: u32 = 43;
pub(super) const CONSTANT_NULL: u32 = 46;
pub(super) const SPEC_CONSTANT_TRUE: u32 = 48;
pub(super) const SPEC_CONSTANT_FALSE: u32 = 49;
pub(super) const SPEC_CONSTANT: u32 = 50;
pub(super) const FUNCTION: u32 = 54;
pub(super) const FUNCTION_PARAMETER: u32 = 55;
pub(super) const FUNCTION_END: u32 = 56;
pub(super) const FUNCTION_CALL: u32 = 57;
pub(super) const DECORATION_GROUP: u32 = 73;
pub(super) const GROUP_DECORATE: u32 = 74;
pub(super) const GROUP_MEMBER_DECORATE: u32 = 75;
pub(super) const COPY_OBJECT: u32 = 83;
pub(super) const U_CONVERT: u32 = 113;
pub(super) const S_CONVERT: u32 = 114;
pub(super) const BITCAST: u32 = 124;
pub(super) const S_NEGATE: u32 = 126;
pub(super) const I_ADD: u32 = 128;
pub(super) const I_SUB: u32 = 130;
pub(super) const I_MUL: u32 = 132;
pub(super) const U_DIV: u32 = 134;
pub(super) const U_MOD: u32 = 137;
pub(super) const LOGICAL_EQUAL: u32 = 164;
pub(super) const LOGICAL_NOT_EQUAL: u32 = 165;
pub(super) const LOGICAL_OR: u32 = 166;
pub(super) const LOGICAL_AND: u32 = 167;
pub(super) const LOGICAL_NOT: u32 = 168;
pub(super) const SELECT: u32 = 169;
pub(super) const I_EQUAL: u32 = 170;
pub(super) const I_NOT_EQUAL: u32 = 171;
pub(super) const U_GREATER_THAN: u32 = 172;
pub(super) const S_GREATER_THAN: u32 = 173;
pub(super) const U_GREATER_THAN_EQUAL: u32 = 174;
pub(super) const S_GREATER_THAN_EQUAL: u32 = 175;
pub(super) const U_LESS_THAN: u32 = 176;
pub(super) const S_LESS_THAN: u32 = 177;
pub(super) const U_LESS_THAN_EQUAL: u32 = 178;
pub(super) const S_LESS_THAN_EQUAL: u32 = 179;
pub(super) const SHIFT_RIGHT_LOGICAL: u32 = 194;
pub(super) const SHIFT_RIGHT_ARITHMETIC: u32 = 195;
pub(super) const SHIFT_LEFT_LOGICAL: u32 = 196;
pub(super) const BITWISE_OR: u32 = 197;
pub(super) const BITWISE_XOR: u32 = 198;
pub(super) const BITWISE_AND: u32 = 199;
pub(super) const NOT: u32 = 200;
pub(super) const PHI: u32 = 245;
pub(super) const LOOP_MERGE: u32 = 246;
pub(super) const SELECTION_MERGE: u32 = 247;
pub(super) const LABEL: u32 = 248;
pub(super) const BRANCH: u32 = 249;
pub(super) const BRANCH_CONDITIONAL: u32 = 250;
pub(super) const SWITCH: u32 = 251;
pub(super) const UNREACHABLE: u32 = 255;
pub(super) const NO_LINE: u32 = 317;
pub(super) const MODULE_PROCESSED: u32 = 330;
pub(super) const EXECUTION_MODE_ID: u32 = 331;
pub(super) const DECORATE_ID: u32 = 332;
pub(super) const DECORATE_STRING: u32 = 5632;

/// Instructions in a function body with a result type and a result id (words 1 and 2): the
/// extended instructions, calls, variables, loads, access chains, composites, conversions,
/// arithmetic, relational and logical, bit operations, atomics, `OpPhi`, `OpCopyLogical`.
pub(super) fn body_result(op: u32) -> bool {
    matches!(op, UNDEF | 12 | 57 | 59..=61 | 65..=68 | 70 | 77..=84 | 109..=152 | 154..=159
        | 164..=191 | 194..=205 | 227 | 229..=242 | PHI | 400)
}

/// Instructions in a function body without a result: lines, stores and copies, barriers, an
/// atomic store, merges, branches and the other terminators, lifetimes, `OpTerminateInvocation`.
pub(super) fn body_no_result(op: u32) -> bool {
    matches!(op, 0 | LINE | NO_LINE | 62..=64 | 224 | 225 | 228 | LOOP_MERGE
        | SELECTION_MERGE | BRANCH..=UNREACHABLE | 256 | 257 | 4416)
}

/// Whether an instruction of a function body has the words the pruner reads in it: its result
/// type and id, a merge's blocks, a branch's condition and targets, a switch's selector and
/// default, a select's three operands, a phi's pairs. (Everything after checks ids against the
/// bound as it reads them.)
pub(super) fn well_formed(op: u32, len: usize) -> bool {
    let least = match op {
        FUNCTION_PARAMETER | SELECTION_MERGE | SWITCH => 3,
        LOOP_MERGE | BRANCH_CONDITIONAL => 4,
        BRANCH => 2,
        SELECT => 6,
        PHI => return len >= 3 && len % 2 == 1,
        _ if body_result(op) => 3,
        _ => 1,
    };
    len >= least
}

/// Instructions whose effect is more than their result: calls, atomics, and every instruction
/// without a result but lines (stores, copies, barriers, merges, terminators).
pub(super) fn has_effect(op: u32) -> bool {
    matches!(op, 57 | 227 | 229..=242) || (body_no_result(op) && op != LINE && op != NO_LINE)
}

pub(super) fn debug(op: u32) -> bool {
    matches!(
        op,
        SOURCE_CONTINUED
            | SOURCE
            | SOURCE_EXTENSION
            | NAME
            | MEMBER_NAME
            | STRING
            | LINE
            | NO_LINE
            | MODULE_PROCESSED
    )
}
