//! Expression trees, stored as 8-byte nodes in the expression pool.
//!
//! A node has a first child and a next sibling, so argument lists are chains. 64-bit
//! constants (`Int`, `Float`) keep their payload in the node right after them.

use crate::value::Ix;
use crate::value::NONE;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Op {
    /// Payload in the next node.
    Int,
    Float,
    /// `data` is a symbol id.
    Sym,
    Str,
    /// Function call: `aux` is a `FnKind`, `data` its index; args are children.
    Call,
    /// Local variable (rule RHS `bind`, deffunction parameter): `data` is the frame slot;
    /// `aux` 1: maybe unbound (its name in the payload node after it); `aux` 2: an LHS
    /// variable the actions bind, `first` the `PatVar` read while unbound.
    Local,
    /// `data` is the global index.
    Global,
    /// LHS variable: `aux` pattern index, `data` a field locator (`loc`), `first` the
    /// pattern's `PatSlot` node when the field is inside a multislot.
    PatVar,
    /// Strict equality of the two children (literal and variable constraints).
    Eq2,
    /// All children hold. `aux` [`NAMES_FIELD`] in an alpha test's root: `data` is the
    /// locator (`loc`) of the field whose constraint the test is (else `aux` 0).
    And,
    Or,
    Not,
    /// Pattern descriptor: one constrained multislot; `data` slot index, `aux` the index
    /// of its first segmentation mark; children are `PatElem`s.
    PatSlot,
    /// Pattern descriptor: one element of a multislot; `aux` 1 when multifield.
    PatElem,
    /// `(tmpl (slot v...))` in assert: `data` template; children are `SlotVal`s.
    FactSpec,
    /// `data` slot index; children are the values (several for a multislot).
    SlotVal,
    /// `$?x` in a function call: the child's multifield is spliced into the arguments.
    Expand,
    /// Second half of a 64-bit constant (never evaluated).
    Payload,
    /// `?v:slot` of a local (query) variable: `data` its frame slot, `first` a `Sym`
    /// node naming the slot (its `aux` 1: every template of `?v` has it, the parser's
    /// mark of a quiet operand), `aux` a cache (see `builtins::facts::slot_value_of`).
    /// Same result as `(fact-slot-value ?v slot)` without the call's argument stack and
    /// dispatch (queries read slots in their inner loop).
    QSlot,
    /// A query variable of fact-set functions or a free node.
    Nop,
}

/// `aux` of an alpha test's `And` root that names the field of its constraint, which
/// `[FACTMCH1]` reports (the parser's `name_field`: tests that read another field
/// first, or none; read with feature `extras`, which the image leaves out).
pub const NAMES_FIELD: u8 = 1;

/// What a `Call` node calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum FnKind {
    Builtin = 0,
    Deffunction = 1,
    External = 2,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Expr {
    pub op: Op,
    pub aux: u8,
    pub data: Ix,
    pub first: Ix,
    pub next: Ix,
}

impl Expr {
    pub const EMPTY: Expr = Expr {
        op: Op::Nop,
        aux: 0,
        data: 0,
        first: NONE,
        next: NONE,
    };

    pub const fn new(op: Op, aux: u8, data: Ix) -> Expr {
        Expr {
            op,
            aux,
            data,
            first: NONE,
            next: NONE,
        }
    }

    /// Splits 64 bits between a constant's header node (low 16 bits in `data`) and
    /// the payload node after it (upper 48 bits), 16 bits per field whatever `Ix` is.
    pub fn split_bits(op: Op, bits: u64) -> (Expr, Expr) {
        let chunk = |shift: u32| ((bits >> shift) & 0xFFFF) as Ix;
        let head = Expr::new(op, 0, chunk(0));
        let tail = Expr {
            op: Op::Payload,
            aux: 0,
            data: chunk(16),
            first: chunk(32),
            next: chunk(48),
        };
        (head, tail)
    }

    /// Inverse of `split_bits`.
    pub fn join_bits(head: Expr, tail: Expr) -> u64 {
        head.data as u64
            | (tail.data as u64) << 16
            | (tail.first as u64) << 32
            | (tail.next as u64) << 48
    }
}

/// A field locator inside a pattern: slot index and element index within a multislot.
pub mod loc {
    use crate::value::Ix;

    /// The fact address itself (`?f <- (...)`).
    pub const FACT: Ix = 0xFFFF;
    /// Element index for a single-field slot.
    pub const SINGLE: u8 = 0xFF;

    pub const fn new(slot: u8, elem: u8) -> Ix {
        ((slot as Ix) << 8) | elem as Ix
    }
    pub const fn slot(l: Ix) -> u8 {
        (l >> 8) as u8
    }
    pub const fn elem(l: Ix) -> u8 {
        l as u8
    }
}

/// The expression pool as the engine sees it: the nodes of a rule base compiled ahead of
/// time read in place from read-only memory (feature `in-place`, see [`crate::rom`]),
/// then the engine's own nodes in its arena.
pub type ExprPool<'a> = crate::rom::RomPool<'a, Expr>;
