//! Join tests compiled into a test plan (host build, feature `host-speedups`).
//!
//! Joins whose tests are only `eq`/`neq` of slots keep `quick`'s plan (cheapest to
//! run inline in the join loops); the tests of the others go through this one.
//! A join's tests are worked out once into a small tree of direct comparisons over
//! the slots of the facts the partial match binds: variable comparisons (`?x` used
//! again, `~?x`, `?a | ?b`), `eq`/`neq`/`=`/`<>`/`<`/`<=`/`>`/`>=` of variables,
//! constants and `(+ ?x N)`/`(- ?x N)` (of a slot or an ordered fact's field), integer arithmetic (`+`, `-`, `*`, `mod`, `div`, `abs`) of
//! those, `eq`/`neq` of `sub-string` cuts with constant bounds of such variables
//! (compared as bytes, without making the cut a symbol), and `and`/`or`/`not` of
//! those, whether they come from field constraints,
//! `&:(...)` predicates or `(test ...)` CEs. Everything else keeps the evaluator; an
//! `and` member of another shape after one of these is `Node::Evaluator`, which
//! sends the pair to the evaluator only when the members before it all hold.
//! A plan whose slots all lie at fixed offsets in their facts (no multislot before
//! them in their templates) reads them from each fact's first cell (`Bases`).
//!
//! Exactness: the plan runs the tests in the evaluator's order with its
//! short-circuits (except that within an `and`, an error-free `?x | ?y` goes before
//! the error-free tests next to it: see `PlanBuild::selective_first`),
//! and the comparisons are the builtins' own (`basic::compare`,
//! `values_same`, wrapping integer `+`/`-`). Wherever the evaluator could report an
//! error or take another path (an unbound pattern, a multifield, a non-number for a
//! numeric test, a float in arithmetic, a zero divisor), the plan answers None before any result is
//! used and the caller evaluates the tests from the start, which reports as before:
//! the tests have no side effects, so running the first ones twice changes nothing.

use crate::builtins;
use crate::builtins::basic::{CMP_FIRST, CMP_LAST};
use crate::builtins::Num;
use crate::engine::Core;
use crate::expr::{loc, Expr, FnKind, Op};
use crate::handle::{JoinId, TokenId};
use crate::rete::quick::{marked_test_plan, same_cell, TestPlan, TEST_PLANS};
use crate::rete::JoinKind;
use crate::rete::BIND_W;
use crate::rete::{PatBinding, MAX_RHASH};
use crate::value::{Ix, Value, NONE};

/// Joins of the compiled plan cache (`Caches::compiled_plans`, direct-mapped by join),
/// each with two entries: its plan at `join % PLAN_JOINS`, and `PLAN_JOINS` after it
/// its plan without the or test that an or-lookup found to hold
/// (`compiled_join_test`'s `skip`).
const PLAN_JOINS: usize = 64;
/// Entries of the compiled plan cache.
const COMPILED_PLANS: usize = 2 * PLAN_JOINS;
/// Nodes (and child links) the cached plans share. A plan that finds no room empties
/// the cache first: kept small, the cache costs the engine's start little.
const POOL_NODES: usize = 255;
/// Length of the pool arrays: every `u8` index is in bounds, so the plan runner's
/// reads of nodes and kids need no bounds check (the last entry stays unused).
const POOL_LEN: usize = 256;
/// Most nodes one plan holds; joins with more keep the evaluator.
const PLAN_NODES: usize = 64;
/// Deepest nesting of `and`/`or`/`not` a plan holds.
const PLAN_DEPTH: u8 = 4;

/// Builtin ids of table 0 (`builtins::basic::FUNCS`) the plan knows, checked by a test.
const FN_ADD: Ix = builtins::builtin_id("+");
const FN_SUB: Ix = builtins::builtin_id("-");
const FN_MUL: Ix = builtins::builtin_id("*");
const FN_EQ: Ix = CMP_FIRST + 6;
const FN_NEQ: Ix = CMP_FIRST + 7;
const FN_AND: Ix = builtins::builtin_id("and");
const FN_OR: Ix = builtins::builtin_id("or");
const FN_NOT: Ix = builtins::builtin_id("not");
/// `sub-string`, whose cuts `Node::Text` compares where they lie.
const FN_SUB_STRING: Ix = builtins::builtin_id("sub-string");
/// `abs`, an `ArOp::Abs` node (its id compared: no name compared per call planned).
const FN_ABS: Ix = builtins::builtin_id("abs");
/// `/`, `min`, `max`, `float`, `mod`, `div`: `ArOp` nodes.
const FN_SLASH: Ix = builtins::builtin_id("/");
const FN_MIN: Ix = builtins::builtin_id("min");
const FN_MAX: Ix = builtins::builtin_id("max");
const FN_FLOAT: Ix = builtins::builtin_id("float");
const FN_MOD: Ix = builtins::builtin_id("mod");
const FN_DIV: Ix = builtins::builtin_id("div");

/// Where a compared value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Source {
    /// A single-field slot of the fact bound at pattern `pat`.
    Slot { pat: u8, slot: u8 },
    /// The constant at expression node `e` (read with `const_value`).
    Const { e: Ix },
    /// Field `elem` of multislot `slot` (an ordered fact's field), when the pattern
    /// has only single-field elements up to it (so its offset is its index).
    Elem { pat: u8, slot: u8, elem: u8 },
    /// An integer slot plus `delta` (wrapping, as the builtins' `+`/`-`; a delta
    /// beyond 32 bits keeps the evaluator, so the node stays small).
    SlotPlus { pat: u8, slot: u8, delta: i32 },
    /// `SlotPlus` of field `elem` of multislot `slot` (an ordered fact's field, at
    /// a fixed offset as `Elem`'s).
    ElemPlus {
        pat: u8,
        slot: u8,
        elem: u8,
        delta: i32,
    },
    /// The integer result of arithmetic node `node` (`Node::Arith`).
    Arith { node: u8 },
}

/// A single-field cell a plan compares where it lies: slot `slot` of the fact
/// bound at `pat`, or field `elem` of that multislot (`WHOLE`: the slot itself).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Cell {
    pat: u8,
    slot: u8,
    elem: u8,
}

/// `Cell::elem` of a whole single-field slot.
const WHOLE: u8 = u8::MAX;

/// The fields a multifield variable binds (`$?p` of `(puzzle $?p)`, `(a ?x $?r ?y)`),
/// read where they lie: multislot `slot` of the fact bound at `pat` without its first
/// `before` and last `after` fields (the variable is its slot's only multifield, so
/// the singles around it fix its bounds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Seg {
    pat: u8,
    slot: u8,
    before: u8,
    after: u8,
}

/// `Cell::elem` of a `Seg` stored as a `Node::Cut` (an operand of `Text`, whose
/// runner is out of line: a node kind of its own in the plan runner's dispatch made
/// every other plan's tests dearer).
const SEG: u8 = u8::MAX - 1;

impl Seg {
    /// The segment as a `Text` operand node.
    fn node(self) -> Node {
        Node::Cut {
            c: Cell {
                pat: self.pat,
                slot: self.slot,
                elem: SEG,
            },
            from: i16::from(self.before),
            to: i16::from(self.after),
        }
    }

    /// The segment operand node `n` holds (None: another node).
    fn of(n: Node) -> Option<Seg> {
        match n {
            Node::Cut { c, from, to } if c.elem == SEG => Some(Seg {
                pat: c.pat,
                slot: c.slot,
                before: u8::try_from(from).ok()?,
                after: u8::try_from(to).ok()?,
            }),
            _ => None,
        }
    }
}

impl Cell {
    /// The cell a slot or element source names (None for another source).
    fn of(s: Source) -> Option<Cell> {
        match s {
            Source::Slot { pat, slot } => Some(Cell {
                pat,
                slot,
                elem: WHOLE,
            }),
            // an element index of `WHOLE` would read as the slot, one of `SEG` as a
            // segment
            Source::Elem { pat, slot, elem } if elem < SEG => Some(Cell { pat, slot, elem }),
            _ => None,
        }
    }
}

/// An arithmetic operation of a plan, as its builtin folds its arguments: integers
/// wrap, a float operand makes the rest of the fold float (`+`, `-`, `*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ArOp {
    Add,
    Sub,
    Mul,
    /// `mod`: the remainder with C's sign rule (two arguments); of a float,
    /// `a - trunc(a / b) * b`.
    Mod,
    /// `div`: the quotient truncated toward zero, folded left as the builtin does
    /// (a float operand truncated first).
    Div,
    /// `abs` of its one argument (wrapping, as the builtin).
    Abs,
    /// `/`: always a float, folded left.
    Slash,
    /// `min`: the first least argument, with its own type.
    Min,
    /// `max`: the first greatest argument, with its own type.
    Max,
    /// `float` of its one argument.
    Float,
}

/// One node of a plan. Composite nodes name their children through `kids`; all
/// indices are into the pool of `TestPlans`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Node {
    /// Comparison builtin `id` (`CMP_FIRST..=CMP_LAST`; `Eq2` is `eq`) of `a` and `b`.
    Cmp { id: u8, a: Source, b: Source },
    /// `eq` (`neq` when `negated`) of two single-field slots, (pattern, slot) each:
    /// `?x` used again and `~?x`, compared where the values lie.
    SameSlots {
        a: (u8, u8),
        b: (u8, u8),
        negated: bool,
    },
    /// `SameSlots` where one side (or both) is a field of a multislot (an ordered
    /// fact's `(triple ?a ?b ?c)`), compared where it lies.
    SameCells { a: Cell, b: Cell, negated: bool },
    /// All of `kids[first..first + len]` (short-circuit, in order; the planner puts
    /// members that mostly fail first where that changes no result).
    And { first: u8, len: u8 },
    /// Any of `kids[first..first + len]` (short-circuit, in order).
    Or { first: u8, len: u8 },
    /// Not `child`.
    Not { child: u8 },
    /// `op` folded over the numbers of `kids[first..first + len]` (each a `Leaf`
    /// or an `Arith`); a non-number or a zero divisor answers None.
    Arith { op: ArOp, first: u8, len: u8 },
    /// An operand of an `Arith` node.
    Leaf { s: Source },
    /// `eq` (`neq` when `negated`) of text operands `a` and `b` (nodes: each a
    /// `Cut`, or a `Leaf` of a slot, element or constant, equal to a cut only as a
    /// string of its bytes), one of them (or both) a cut: an ASCII cut is compared
    /// as bytes (the builtin's cut of an ASCII text is its bytes, and equal
    /// strings are one symbol); another text, or a non-lexeme, answers None.
    /// (Operands as nodes: a wider `Node` made every plan's reads dearer.)
    Text { a: u8, b: u8, negated: bool },
    /// An operand of `Text`: `(sub-string from to ?x)` of cell `c` (a string,
    /// symbol or instance name), the bounds integer constants.
    Cut { c: Cell, from: i16, to: i16 },
    /// A member of an `and` the plan cannot hold: reached, it answers None (the
    /// evaluator decides, from the start), so that the members before it still
    /// decide without the evaluator when one fails.
    Evaluator,
}

const UNPLANNED: u8 = u8::MAX;

/// How a plan finds the facts it reads (`PlanEntry::mode`).
/// A shallow plan whose reads all lie at fixed offsets: `Bases`.
const MODE_BASES: u8 = 0;
/// Another shallow plan (a slot after a multislot, a pattern of unknown template):
/// `Frame`.
const MODE_FRAME: u8 = 1;
/// A plan reading a left pattern at or beyond `BIND_W`, which only the ancestry
/// walk (`bind_left`) finds: `Ancestry`.
const MODE_DEEP: u8 = 2;
/// A `MODE_BASES` plan that is one numeric comparison of two cells
/// (`?i&:(< ?i ?c)`), run as its `FlatPlan` (`TestPlans::flats`). Its entry's `root`
/// reads `UNPLANNED`, so that the other plans' dispatch stays as it is: only the
/// rare unplanned entries look at this mode.
const MODE_FLAT: u8 = 3;
/// A plan reading a field bound after a multifield of its slot (`$? ?x $?`), found
/// by its pattern's multifield marks, which only `join_test_eval` binds (in
/// `lhs_pm`): it runs there (`marked_join_test`), read by `Marked`. Its root is kept
/// in its `flats` entry's `root` (unused in this mode), the entry's `root` reads
/// `UNPLANNED`: the usual path's dispatch and runners stay as they are (a `Source`
/// variant of its own made every other plan's runner dearer: zebra +0.66 %, r12j),
/// and the cache is no larger (side tables, copied with the engine's state as it
/// starts, cost every program 10 k instructions).
const MODE_MARKS: u8 = 4;

/// `Source::ElemPlus::elem` of a field bound after a multifield, in a `MODE_MARKS`
/// plan only (`plan_elem` leaves the number to it): its `delta` is the field's
/// `SegRead` (`SegRead::packed`).
const SEG_ELEM: u8 = 240;

/// A `MODE_MARKS` plan's slot number with this bit set names a slot at a fixed
/// offset in its fact (`PlanBuild::flag_fixed_slots`): `Marked` reads it at the
/// fact's first cell plus the slot (the bit cleared). The other runners never see
/// it: only `Marked` runs such plans.
const FIXED_SLOT: u8 = 0x80;

/// Where a field lies in its multislot: `base` fields plus the lengths of the
/// pattern's multifields `mark..mark + n` (its marks) from the slot's start (`n` 0:
/// a fixed offset), or (`n` of `FROM_END`) `base` fields before the slot's end
/// (after the slot's last multifield, which has no mark), as `pattern_var` finds it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SegRead {
    base: u8,
    mark: u8,
    n: u8,
}

/// `SegRead::n` of a field after its slot's last multifield.
const FROM_END: u8 = u8::MAX;
/// `SegRead::n` of a whole single-field slot (`MarkKey`).
const WHOLE_READ: u8 = u8::MAX - 1;

impl SegRead {
    const NONE: SegRead = SegRead {
        base: 0,
        mark: 0,
        n: 0,
    };

    /// The read as an `ElemPlus` delta (24 bits, not negative).
    fn packed(self) -> i32 {
        i32::from(self.base) | (i32::from(self.mark) << 8) | (i32::from(self.n) << 16)
    }

    fn unpacked(d: i32) -> SegRead {
        SegRead {
            base: d as u8,
            mark: (d >> 8) as u8,
            n: (d >> 16) as u8,
        }
    }

    /// The read in one byte, as a `KeyPlan` keeps a marked key's field (`base`
    /// in bits 0-2, `mark` in 3-4, `n` coded in 5-7: 0 to `MAX_MARKS`, then
    /// `FROM_END`, `WHOLE_READ`); None if it does not fit.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn to_byte(self) -> Option<u8> {
        let n = match self.n {
            FROM_END => SEG_BYTE_FROM_END,
            WHOLE_READ => SEG_BYTE_WHOLE,
            n if n as usize <= crate::rete::MAX_MARKS => n,
            _ => return None,
        };
        (self.base < 8 && self.mark < 4).then_some(self.base | self.mark << 3 | n << 5)
    }

    /// The read `to_byte` gave `b`.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn of_byte(b: u8) -> SegRead {
        SegRead {
            base: b & 7,
            mark: b >> 3 & 3,
            n: match b >> 5 {
                SEG_BYTE_FROM_END => FROM_END,
                SEG_BYTE_WHOLE => WHOLE_READ,
                n => n,
            },
        }
    }
}

/// `SegRead::to_byte`'s codes of `FROM_END` and `WHOLE_READ`.
#[cfg(feature = "host-speedups")]
const SEG_BYTE_FROM_END: u8 = 5;
#[cfg(feature = "host-speedups")]
const SEG_BYTE_WHOLE: u8 = 6;
#[cfg(feature = "host-speedups")]
const _: () = assert!(crate::rete::MAX_MARKS < SEG_BYTE_FROM_END as usize);

/// A join's left key read by the marks, for a join whose key fields some
/// multifield moves (`$? ?x $?`), which `index`'s `KeyPlan` leaves to the
/// evaluator: `left_key`, after `bind_left`, reads them from `lhs_pm`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct MarkKey {
    /// Fields read.
    pub(crate) n: u8,
    /// Per field: its pattern, slot and place in the slot.
    pub(crate) reads: [(u8, u8, SegRead); MAX_RHASH],
}

const _: () = assert!(SEG_ELEM < SEG);

/// `FlatPlan::test`: the orderings of two integers that pass, bits 0, 1, 2 for
/// `Less`, `Equal`, `Greater` (`(x > y) - (x < y) + 1`).
const FLAT_LT: u8 = 1;
const FLAT_EQ: u8 = 2;
const FLAT_GT: u8 = 4;

/// A `MODE_FLAT` plan: comparison `test` of cells `a` and `b` (the right fact's at
/// `RIGHT`), decided in place for two integers; any other pair (a float, a
/// non-number, a cell not found) goes to its compiled plan at `root`, which
/// decides it as before (and the evaluator reports what it must). A call costs
/// two thirds of the compiled plan's (`growforall`'s `?i&:(< ?i ?c)`). (A form
/// with the left cell first, each read without the side test, saved a tenth
/// more but moved the other plans' registers: zebra +0.3 %.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct FlatPlan {
    test: u8,
    root: u8,
    a: Cell,
    b: Cell,
}

impl FlatPlan {
    const NONE: FlatPlan = FlatPlan {
        test: 0,
        root: UNPLANNED,
        a: Cell {
            pat: 0,
            slot: 0,
            elem: WHOLE,
        },
        b: Cell {
            pat: 0,
            slot: 0,
            elem: WHOLE,
        },
    };

    /// The flat form of plan `b` (its reads of the right fact at `RIGHT`) whose
    /// root is `root` there and `stored` in the pool, if it is one numeric
    /// comparison of two cells.
    fn of(b: &PlanBuild, root: u8, stored: u8) -> Option<FlatPlan> {
        let Some(&Node::Cmp { id, a, b }) = b.nodes.get(root as usize) else {
            return None;
        };
        let test = match Ix::from(id).checked_sub(CMP_FIRST)? {
            0 => FLAT_EQ,
            1 => FLAT_LT | FLAT_GT,
            2 => FLAT_LT,
            3 => FLAT_LT | FLAT_EQ,
            4 => FLAT_GT,
            5 => FLAT_GT | FLAT_EQ,
            // `eq`/`neq`: `run_inline`'s compare of any two values costs no more
            _ => return None,
        };
        Some(FlatPlan {
            test,
            root: stored,
            a: Cell::of(a)?,
            b: Cell::of(b)?,
        })
    }
}

/// A cache entry: the plan of `join` with test chain `tests` (a reused join id has
/// another one), `root` its node (`UNPLANNED` when its tests are not all of a
/// planned shape), `mode` one of the `MODE_` constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PlanEntry {
    join: JoinId,
    tests: Ix,
    root: u8,
    mode: u8,
}

impl PlanEntry {
    const NONE: PlanEntry = PlanEntry {
        join: JoinId::NONE,
        tests: NONE,
        root: UNPLANNED,
        mode: MODE_FRAME,
    };
}

/// The compiled join-test plans of recently tested joins: direct-mapped entries over one
/// shared pool of nodes.
pub struct TestPlans {
    entries: [PlanEntry; COMPILED_PLANS],
    /// The flat form of each usual entry's plan, read while its mode is
    /// `MODE_FLAT`.
    flats: [FlatPlan; PLAN_JOINS],
    nodes: [Node; POOL_LEN],
    kids: [u8; POOL_LEN],
    nodes_used: u8,
    kids_used: u8,
    /// The pool ran out of room since the network was built: partial plans (with a
    /// `Node::Evaluator`) are no longer stored, so that they never make the plans
    /// of a network with many joins be built again and again.
    crowded: bool,
    /// A `MODE_MARKS` plan was stored since the network was built: only then does
    /// `join_test_eval` look for one (a look per test cost llsf's run +0.05 %).
    pub(crate) marked_any: bool,
}

impl TestPlans {
    pub const EMPTY: TestPlans = TestPlans {
        entries: [PlanEntry::NONE; COMPILED_PLANS],
        flats: [FlatPlan::NONE; PLAN_JOINS],
        nodes: [Node::Not { child: 0 }; POOL_LEN],
        kids: [0; POOL_LEN],
        nodes_used: 0,
        kids_used: 0,
        crowded: false,
        marked_any: false,
    };

    /// Forgets every plan (the network was replaced).
    pub fn clear(&mut self) {
        self.empty();
        self.crowded = false;
        self.marked_any = false;
    }

    /// Forgets every plan and frees the pool.
    fn empty(&mut self) {
        self.entries = [PlanEntry::NONE; COMPILED_PLANS];
        self.nodes_used = 0;
        self.kids_used = 0;
    }

    /// Forgets the plan of `join`, a new join that may reuse an old one's id (its
    /// nodes stay used until the pool is emptied).
    pub fn forget(&mut self, join: JoinId) {
        let i = join.ix() % PLAN_JOINS;
        for e in [i, i + PLAN_JOINS] {
            if self.entries[e].join == join {
                self.entries[e] = PlanEntry::NONE;
            }
        }
    }

    /// Stores built plan `b` for entry `i`, emptying the pool first if it lacks room
    /// (a partial plan, one with a `Node::Evaluator`, is stored unplanned instead,
    /// and so is every partial plan once the pool is `crowded`: its join keeps the
    /// evaluator).
    fn store(&mut self, i: usize, mut entry: PlanEntry, b: &PlanBuild) {
        let full = |p: &Self| {
            p.nodes_used as usize + b.used as usize > POOL_NODES
                || p.kids_used as usize + b.kids_used as usize > POOL_NODES
        };
        if entry.root != UNPLANNED && b.partial && (self.crowded || full(self)) {
            entry.root = UNPLANNED;
        }
        if entry.root == UNPLANNED {
            self.entries[i] = entry;
            return;
        }
        let (n, k) = (b.used as usize, b.kids_used as usize);
        if full(self) {
            self.empty();
            self.crowded = true;
        }
        // POOL_NODES <= 256 and the sums fit: every index stays a u8
        let (nb, kb) = (self.nodes_used, self.kids_used);
        for (dst, src) in self.nodes[nb as usize..nb as usize + n]
            .iter_mut()
            .zip(&b.nodes[..n])
        {
            *dst = match *src {
                Node::And { first, len } => Node::And {
                    first: first + kb,
                    len,
                },
                Node::Or { first, len } => Node::Or {
                    first: first + kb,
                    len,
                },
                Node::Not { child } => Node::Not { child: child + nb },
                Node::Arith { op, first, len } => Node::Arith {
                    op,
                    first: first + kb,
                    len,
                },
                Node::Leaf { s } => Node::Leaf { s: s.shifted(nb) },
                Node::Text { a, b, negated } => Node::Text {
                    a: a + nb,
                    b: b + nb,
                    negated,
                },
                Node::Cmp { id, a, b } => Node::Cmp {
                    id,
                    a: a.shifted(nb),
                    b: b.shifted(nb),
                },
                same => same,
            };
        }
        for (dst, src) in self.kids[kb as usize..kb as usize + k]
            .iter_mut()
            .zip(&b.kids[..k])
        {
            *dst = *src + nb;
        }
        self.nodes_used += n as u8;
        self.kids_used += k as u8;
        entry.root += nb;
        self.entries[i] = entry;
    }
}

/// A plan being built (on the stack; `TestPlans::store` moves it into the pool).
struct PlanBuild {
    used: u8,
    kids_used: u8,
    deep: bool,
    /// The plan reads fields bound after multifields (`MODE_MARKS`).
    marks: bool,
    /// The plan holds a `Node::Evaluator`.
    partial: bool,
    nodes: [Node; PLAN_NODES],
    kids: [u8; PLAN_NODES],
}

impl PlanBuild {
    /// Moves a shallow plan's reads of the join's own pattern `depth` to `RIGHT`,
    /// where its `Frame` holds the right fact.
    fn read_right_at(&mut self, depth: u8) {
        let pat = |p: u8| if p == depth { RIGHT } else { p };
        let src = |s: Source| match s {
            Source::Slot { pat: p, slot } => Source::Slot { pat: pat(p), slot },
            Source::Elem { pat: p, slot, elem } => Source::Elem {
                pat: pat(p),
                slot,
                elem,
            },
            Source::SlotPlus {
                pat: p,
                slot,
                delta,
            } => Source::SlotPlus {
                pat: pat(p),
                slot,
                delta,
            },
            Source::ElemPlus {
                pat: p,
                slot,
                elem,
                delta,
            } => Source::ElemPlus {
                pat: pat(p),
                slot,
                elem,
                delta,
            },
            s @ (Source::Const { .. } | Source::Arith { .. }) => s,
        };
        let cell = |c: Cell| Cell {
            pat: pat(c.pat),
            ..c
        };
        for n in &mut self.nodes[..self.used as usize] {
            *n = match *n {
                Node::Cmp { id, a, b } => Node::Cmp {
                    id,
                    a: src(a),
                    b: src(b),
                },
                Node::SameSlots { a, b, negated } => Node::SameSlots {
                    a: (pat(a.0), a.1),
                    b: (pat(b.0), b.1),
                    negated,
                },
                Node::SameCells { a, b, negated } => Node::SameCells {
                    a: cell(a),
                    b: cell(b),
                    negated,
                },
                Node::Leaf { s } => Node::Leaf { s: src(s) },
                Node::Cut { c, from, to } => Node::Cut {
                    c: cell(c),
                    from,
                    to,
                },
                other @ (Node::And { .. }
                | Node::Text { .. }
                | Node::Or { .. }
                | Node::Not { .. }
                | Node::Arith { .. }
                | Node::Evaluator) => other,
            };
        }
    }

    /// A `MODE_MARKS` plan's reads of a slot at a fixed offset in its fact
    /// (`fixed(pat, slot)`: only single-field slots before it in the template of
    /// the facts bound at `pat`) get `FIXED_SLOT` in their slot number, so that
    /// `Marked` reads them at the fact's first cell plus the slot, without a walk
    /// over the slots (the plan's facts hold multifields). False if a read's slot
    /// is `FIXED_SLOT` or beyond (it would read as flagged): the plan is dropped.
    fn flag_fixed_slots(&mut self, fixed: impl Fn(u8, u8) -> bool) -> bool {
        let fits = core::cell::Cell::new(true);
        let flag = |pat: u8, slot: u8| -> u8 {
            if slot >= FIXED_SLOT {
                fits.set(false);
                slot
            } else if fixed(pat, slot) {
                slot | FIXED_SLOT
            } else {
                slot
            }
        };
        let src = |s: Source| match s {
            Source::Slot { pat, slot } => Source::Slot {
                pat,
                slot: flag(pat, slot),
            },
            Source::Elem { pat, slot, elem } => Source::Elem {
                pat,
                slot: flag(pat, slot),
                elem,
            },
            Source::SlotPlus { pat, slot, delta } => Source::SlotPlus {
                pat,
                slot: flag(pat, slot),
                delta,
            },
            Source::ElemPlus {
                pat,
                slot,
                elem,
                delta,
            } => Source::ElemPlus {
                pat,
                slot: flag(pat, slot),
                elem,
                delta,
            },
            s @ (Source::Const { .. } | Source::Arith { .. }) => s,
        };
        for n in &mut self.nodes[..self.used as usize] {
            *n = match *n {
                Node::Cmp { id, a, b } => Node::Cmp {
                    id,
                    a: src(a),
                    b: src(b),
                },
                Node::SameSlots { a, b, negated } => Node::SameSlots {
                    a: (a.0, flag(a.0, a.1)),
                    b: (b.0, flag(b.0, b.1)),
                    negated,
                },
                Node::SameCells { a, b, negated } => Node::SameCells {
                    a: Cell {
                        slot: flag(a.pat, a.slot),
                        ..a
                    },
                    b: Cell {
                        slot: flag(b.pat, b.slot),
                        ..b
                    },
                    negated,
                },
                Node::Leaf { s } => Node::Leaf { s: src(s) },
                Node::Cut { c, from, to } => Node::Cut {
                    c: Cell {
                        slot: flag(c.pat, c.slot),
                        ..c
                    },
                    from,
                    to,
                },
                other @ (Node::And { .. }
                | Node::Text { .. }
                | Node::Or { .. }
                | Node::Not { .. }
                | Node::Arith { .. }
                | Node::Evaluator) => other,
            };
        }
        fits.get()
    }

    fn push(&mut self, node: Node) -> Option<u8> {
        let i = self.used as usize;
        *self.nodes.get_mut(i)? = node;
        self.used += 1;
        Some(i as u8)
    }

    /// Reserves `len` child slots, returns the first.
    fn reserve_kids(&mut self, len: usize) -> Option<u8> {
        let first = self.kids_used as usize;
        if first + len > PLAN_NODES {
            return None;
        }
        self.kids_used += len as u8;
        Some(first as u8)
    }
}

impl PlanBuild {
    /// How node `n` may be reordered among the members of an `and`: None when it
    /// could make the evaluator report an error (a numeric comparison, arithmetic),
    /// else its class: 0 a test that mostly fails (`?x | ?y`: an `or` of
    /// equalities), 1 any other (`~?x` mostly passes; a single equality may be the
    /// join's hash key, which its candidates pass). `eq`/`neq` of single-field
    /// slots, elements and constants never report an error.
    fn order_class(&self, n: u8) -> Option<u8> {
        let plain = |s: Source| {
            !matches!(
                s,
                Source::Arith { .. } | Source::SlotPlus { .. } | Source::ElemPlus { .. }
            )
        };
        match self.nodes[n as usize] {
            Node::SameSlots { .. } | Node::SameCells { .. } => Some(1),
            Node::Cmp { id, a, b } if plain(a) && plain(b) => match Ix::from(id) {
                FN_EQ | FN_NEQ => Some(1),
                _ => None,
            },
            Node::Or { first, len } => {
                let mut all_eq = true;
                for &k in &self.kids[first as usize..(first + len) as usize] {
                    self.order_class(k)?;
                    all_eq &= self.is_equality(k);
                }
                Some(u8::from(!all_eq))
            }
            Node::And { first, len } => {
                for &k in &self.kids[first as usize..(first + len) as usize] {
                    self.order_class(k)?;
                }
                Some(1)
            }
            Node::Not { child } => self.order_class(child).map(|_| 1),
            _ => None,
        }
    }

    /// Node `n` is an `eq` of two operands.
    fn is_equality(&self, n: u8) -> bool {
        match self.nodes[n as usize] {
            Node::SameSlots { negated, .. } | Node::SameCells { negated, .. } => !negated,
            Node::Cmp { id, .. } => Ix::from(id) == FN_EQ,
            _ => false,
        }
    }

    /// Puts the members of an `and` that mostly fail (`order_class` 0) first,
    /// within each run of members that report no error (stable; a member that may
    /// report one keeps every member on its side). The members are side-effect free
    /// and error-free there, so their order changes no result; a member that answers
    /// None sends the whole test to the evaluator, which runs them in source order.
    fn selective_first(&self, members: &mut [u8]) {
        let mut i = 0;
        while i < members.len() {
            let start = i;
            while i < members.len() && self.order_class(members[i]).is_some() {
                i += 1;
            }
            // insertion sort by class (stable): runs are a few members long
            for j in start + 1..i {
                let mut k = j;
                while k > start && self.order_class(members[k - 1]) > self.order_class(members[k]) {
                    members.swap(k - 1, k);
                    k -= 1;
                }
            }
            i += 1;
        }
    }
}

/// Where a plan reads the facts its patterns bind.
trait LeftFacts: Copy {
    /// The cell of slot `slot` of the fact bound at `pat` (the right input's at the
    /// join's own `depth`; a multislot's is its `Multi`); None if unbound.
    fn slot<'c>(
        self,
        core: &'c Core<'_>,
        pat: u8,
        slot: u8,
        depth: u8,
        right_fact: Ix,
    ) -> Option<&'c Value>;

    /// `slot_cell` of slot `slot` of the fact bound at `pat`: its cell and, for a
    /// multislot, its length; None if unbound.
    fn slot_cell(
        self,
        core: &Core<'_>,
        pat: u8,
        slot: u8,
        depth: u8,
        right_fact: Ix,
    ) -> Option<(usize, Option<Ix>)>;

    /// `Marked` alone: its plans read `SEG_ELEM` fields (see `source_value`), the
    /// others' code has no such arm.
    const MARKED: bool = false;
}

/// A `MODE_MARKS` plan's: every pattern's fact and marks as `join_test_eval` bound
/// them in `lhs_pm`, the join's own included.
#[derive(Clone, Copy)]
struct Marked;

impl LeftFacts for Marked {
    #[inline(always)]
    fn slot<'c>(self, core: &'c Core<'_>, pat: u8, slot: u8, _: u8, _: Ix) -> Option<&'c Value> {
        // the walk over the slots in line (`slot_ref` calls `slot_cell`, out of
        // line: a marked plan's facts hold multifields, the walk is the usual case)
        let fact = core.st.net.lhs_pm.get(pat as usize)?.fact;
        if fact == NONE {
            return None;
        }
        let f = core.facts.get(fact as usize)?;
        // (a slot number below `FIXED_SLOT` is the slot itself)
        if f.flat || slot & FIXED_SLOT != 0 {
            return core
                .values
                .get(f.start as usize + (slot & !FIXED_SLOT) as usize);
        }
        core.values
            .get(core.slot_cell_inline(fact, Ix::from(slot)).0)
    }

    #[inline(always)]
    fn slot_cell(
        self,
        core: &Core<'_>,
        pat: u8,
        slot: u8,
        _: u8,
        _: Ix,
    ) -> Option<(usize, Option<Ix>)> {
        let fact = core.st.net.lhs_pm.get(pat as usize)?.fact;
        if slot & FIXED_SLOT != 0 {
            return fixed_slot_cell(core, fact, slot & !FIXED_SLOT);
        }
        fact_slot_cell(core, fact, slot)
    }

    const MARKED: bool = true;
}

/// `LeftFacts::slot` of `fact` (NONE: unbound).
#[inline(always)]
fn fact_slot<'c>(core: &'c Core<'_>, fact: Ix, slot: u8) -> Option<&'c Value> {
    if fact == NONE {
        return None;
    }
    Some(core.slot_ref(fact, Ix::from(slot)))
}

/// `LeftFacts::slot_cell` of `fact` (NONE: unbound) for a slot at a fixed offset
/// in it (`FIXED_SLOT`), read at its first cell plus `slot`, without a walk.
#[inline(always)]
fn fixed_slot_cell(core: &Core<'_>, fact: Ix, slot: u8) -> Option<(usize, Option<Ix>)> {
    if fact == NONE {
        return None;
    }
    let c = core.facts.get(fact as usize)?.start as usize + slot as usize;
    Some(match core.values.get(c)? {
        Value::Multi(m) => (c, Some(m.len)),
        _ => (c, None),
    })
}

/// `LeftFacts::slot_cell` of `fact` (NONE: unbound).
#[inline(always)]
fn fact_slot_cell(core: &Core<'_>, fact: Ix, slot: u8) -> Option<(usize, Option<Ix>)> {
    if fact == NONE {
        return None;
    }
    Some(core.slot_cell_inline(fact, Ix::from(slot)))
}

/// Entries of a shallow plan's `Frame` and `Bases` (a power of two: an index is
/// masked, not checked).
const FRAME: usize = 2 * BIND_W;
/// Where a shallow plan reads the join's own pattern (the right fact) in its `Frame`
/// or `Bases`: the plan's reads of it are moved there when the plan is stored.
const RIGHT: u8 = BIND_W as u8;

/// A shallow plan's (every pattern it reads below `BIND_W` or the join's own): the
/// left token's `binds`, then the right fact (at `RIGHT`, repeated to the end), in
/// one array filled once per test, so a read is one indexed load whichever side it
/// is on.
#[derive(Clone, Copy)]
struct Frame<'a>(&'a [Ix; FRAME]);

impl LeftFacts for Frame<'_> {
    #[inline(always)]
    fn slot<'c>(self, core: &'c Core<'_>, pat: u8, slot: u8, _: u8, _: Ix) -> Option<&'c Value> {
        fact_slot(core, self.0[pat as usize & (FRAME - 1)], slot)
    }

    #[inline(always)]
    fn slot_cell(
        self,
        core: &Core<'_>,
        pat: u8,
        slot: u8,
        _: u8,
        _: Ix,
    ) -> Option<(usize, Option<Ix>)> {
        fact_slot_cell(core, self.0[pat as usize & (FRAME - 1)], slot)
    }
}

/// The first cell of a fact not found: beyond every cell (`Bases::cell` adds at
/// most 2 * 255 + 1 to it without overflow, even with a 32-bit `usize`).
const NO_BASE: u32 = u32::MAX >> 1;

/// A `MODE_BASES` plan's: the left token's `binds` and the first cell
/// (`Fact::start`) of the right fact, found once per test (a fact's cells may move
/// when the arena is compacted: never kept beyond it). Every slot such a plan reads
/// follows single-field slots only (`Core::fixed_reads`), so slot `s` is the cell
/// `s` after the fact's first, whether the fact is flat or not.
#[derive(Clone, Copy)]
struct Bases<'a> {
    binds: &'a [Ix; BIND_W],
    right: u32,
}

impl Bases<'_> {
    /// The first cell of fact `f` (`NO_BASE` if none).
    #[inline(always)]
    fn base(core: &Core<'_>, f: Ix) -> u32 {
        match core.facts.get(f as usize) {
            Some(x) => x.start as u32,
            None => NO_BASE,
        }
    }

    /// The index of cell `slot` of the fact at `pat` (beyond the cells if unbound).
    #[inline(always)]
    fn cell(self, core: &Core<'_>, pat: u8, slot: u8) -> usize {
        let base = if pat == RIGHT {
            self.right
        } else {
            Self::base(core, self.binds[pat as usize & (BIND_W - 1)])
        };
        base as usize + slot as usize
    }
}

impl LeftFacts for Bases<'_> {
    #[inline(always)]
    fn slot<'c>(self, core: &'c Core<'_>, pat: u8, slot: u8, _: u8, _: Ix) -> Option<&'c Value> {
        core.values.get(self.cell(core, pat, slot))
    }

    #[inline(always)]
    fn slot_cell(
        self,
        core: &Core<'_>,
        pat: u8,
        slot: u8,
        _: u8,
        _: Ix,
    ) -> Option<(usize, Option<Ix>)> {
        let c = self.cell(core, pat, slot);
        match core.values.get(c)? {
            Value::Multi(m) => Some((c, Some(m.len))),
            _ => Some((c, None)),
        }
    }
}

/// A deep plan's: found per read, the left ones through `left_fact` (beyond
/// `BIND_W` through `lhs_pm`, which `compiled_join_test` bound).
#[derive(Clone, Copy)]
struct Ancestry(TokenId);

impl Ancestry {
    #[inline(always)]
    fn fact(self, core: &Core<'_>, pat: u8, depth: u8, right_fact: Ix) -> Ix {
        if pat == depth {
            right_fact
        } else if (pat as usize) < BIND_W {
            core.left_fact(self.0, pat)
        } else {
            match core.st.net.lhs_pm.get(pat as usize) {
                Some(b) => b.fact,
                None => NONE,
            }
        }
    }
}

impl LeftFacts for Ancestry {
    #[inline(always)]
    fn slot<'c>(
        self,
        core: &'c Core<'_>,
        pat: u8,
        slot: u8,
        depth: u8,
        right_fact: Ix,
    ) -> Option<&'c Value> {
        fact_slot(core, self.fact(core, pat, depth, right_fact), slot)
    }

    #[inline(always)]
    fn slot_cell(
        self,
        core: &Core<'_>,
        pat: u8,
        slot: u8,
        depth: u8,
        right_fact: Ix,
    ) -> Option<(usize, Option<Ix>)> {
        fact_slot_cell(core, self.fact(core, pat, depth, right_fact), slot)
    }
}

const _: () = assert!(
    POOL_NODES <= UNPLANNED as usize
        && PLAN_NODES <= POOL_NODES
        && POOL_LEN == u8::MAX as usize + 1
        && FRAME > RIGHT as usize
        && FRAME.is_power_of_two()
);

impl Source {
    /// The pattern a source reads (None for a constant or arithmetic, whose
    /// operands are checked as they are planned).
    fn pat(self) -> Option<u8> {
        match self {
            Source::Slot { pat, .. }
            | Source::Elem { pat, .. }
            | Source::SlotPlus { pat, .. }
            | Source::ElemPlus { pat, .. } => Some(pat),
            Source::Const { .. } | Source::Arith { .. } => None,
        }
    }

    /// The source with its node index moved by `nb` (a plan stored at pool offset `nb`).
    fn shifted(self, nb: u8) -> Source {
        match self {
            Source::Arith { node } => Source::Arith { node: node + nb },
            s => s,
        }
    }
}

impl Core<'_> {
    /// The tests of `join` (not all `eq`/`neq` of slots: `quick`'s plan holds those)
    /// decided through its compiled plan: Some(result), or None when the evaluator
    /// must decide (see the module comment). Out of line: one call per test beats
    /// the evaluator, and keeps the join loops small.
    #[inline(never)]
    pub(crate) fn compiled_join_test(
        &mut self,
        join: JoinId,
        tests: Ix,
        depth: u8,
        left: TokenId,
        right_fact: Ix,
    ) -> Option<bool> {
        self.compiled_test_in::<false>(join, tests, depth, left, right_fact, NONE)
    }

    /// `compiled_join_test` where `or`, the join's or test (`OrValues::or`, a test
    /// of the chain itself), is known to hold for this pair: a plan of the other
    /// tests decides (the tests have no side effects, and the evaluator, if it must
    /// decide, runs them all). A function of its own, so that the usual call passes
    /// and computes nothing more.
    #[inline(never)]
    pub(crate) fn compiled_join_test_or(
        &mut self,
        join: JoinId,
        (tests, depth): (Ix, u8),
        left: TokenId,
        right_fact: Ix,
        or: Ix,
    ) -> Option<bool> {
        self.compiled_test_in::<true>(join, tests, depth, left, right_fact, or)
    }

    /// `compiled_join_test` (`SKIP`: `compiled_join_test_or` of test `skip`).
    #[inline(always)]
    fn compiled_test_in<const SKIP: bool>(
        &mut self,
        join: JoinId,
        tests: Ix,
        depth: u8,
        left: TokenId,
        right_fact: Ix,
        skip: Ix,
    ) -> Option<bool> {
        // the join's or test is the same for every left token: one entry holds the
        // plan without it
        let i = join.ix() % PLAN_JOINS + if SKIP { PLAN_JOINS } else { 0 };
        let cached = &self.st.cache.compiled_plans.entries[i];
        if cached.join != join || cached.tests != tests {
            self.cache_test_plan(i, join, tests, depth, skip);
        }
        let entry = self.st.cache.compiled_plans.entries[i];
        if entry.root == UNPLANNED {
            if SKIP {
                // the usual call (its plan is unplanned too): `quick_join_test` stays
                // inlined there alone
                return self.compiled_join_test(join, tests, depth, left, right_fact);
            }
            if entry.mode == MODE_FLAT {
                return self.flat_join_test(i, depth, left, right_fact);
            }
            return self.quick_join_test(tests, depth, left, right_fact);
        }
        // the root's own dispatch inlined here: one call less per test
        match entry.mode {
            MODE_BASES => {
                // the right fact found once per test, not once per slot read (the
                // plan reads it at `RIGHT`)
                let bases = Bases {
                    binds: &self.tokens[left].binds,
                    right: Bases::base(self, right_fact),
                };
                self.run_inline(entry.root, depth, bases, right_fact)
            }
            MODE_FRAME => {
                // the facts found once per test, not once per slot read (the plan
                // reads the right fact at `RIGHT`)
                let mut frame = [right_fact; FRAME];
                frame[..BIND_W].copy_from_slice(&self.tokens[left].binds);
                self.run_inline(entry.root, depth, Frame(&frame), right_fact)
            }
            _ => {
                // free when `left` is bound already (a loop over its candidates)
                self.bind_left(left);
                self.run_inline(entry.root, depth, Ancestry(left), right_fact)
            }
        }
    }

    /// Builds the plan of `join` into cache entry `i` (out of line: once per join
    /// while it stays cached).
    #[inline(never)]
    fn cache_test_plan(&mut self, i: usize, join: JoinId, tests: Ix, depth: u8, skip: Ix) {
        let mut b = PlanBuild {
            used: 0,
            kids_used: 0,
            deep: false,
            marks: false,
            partial: false,
            nodes: [Node::Not { child: 0 }; PLAN_NODES],
            kids: [0; PLAN_NODES],
        };
        let root = self
            .plan_chain(&mut b, tests, depth, Chain::And, 0, skip)
            .unwrap_or(UNPLANNED);
        let mode = if b.marks && root != UNPLANNED {
            MODE_MARKS
        } else if b.deep {
            MODE_DEEP
        } else if root != UNPLANNED && self.fixed_reads(&b, join, depth).is_some() {
            MODE_BASES
        } else {
            MODE_FRAME
        };
        let entry = PlanEntry {
            join,
            tests,
            root,
            mode,
        };
        if mode == MODE_MARKS {
            let mut entry = entry;
            let (left, right) = self.read_templates(join);
            let fixed = |pat: u8, slot: u8| {
                let t = if pat == depth {
                    right
                } else {
                    left.get(pat as usize).copied().unwrap_or(NONE)
                };
                self.slot_at_fixed_offset(t, slot)
            };
            if !b.flag_fixed_slots(fixed) {
                entry.root = UNPLANNED;
            }
            let plans = &mut self.st.cache.compiled_plans;
            plans.store(i, entry, &b);
            // run by `marked_join_test` alone (a skip entry's not at all)
            let root = core::mem::replace(&mut plans.entries[i].root, UNPLANNED);
            if let Some(f) = plans.flats.get_mut(i) {
                f.root = root;
                plans.marked_any = true;
            }
            return;
        }
        if !b.deep {
            b.read_right_at(depth);
        }
        self.st.cache.compiled_plans.store(i, entry, &b);
        // a usual entry's complete plan reading fixed offsets: its flat form, if it
        // has one
        if i < PLAN_JOINS && mode == MODE_BASES && root != UNPLANNED && !b.partial {
            let plans = &mut self.st.cache.compiled_plans;
            let stored = plans.entries[i].root;
            if stored != UNPLANNED {
                if let Some(f) = FlatPlan::of(&b, root, stored) {
                    plans.flats[i] = f;
                    plans.entries[i].root = UNPLANNED;
                    plans.entries[i].mode = MODE_FLAT;
                }
            }
        }
    }

    /// The tests of the join whose usual entry `i` holds a `MODE_FLAT` plan, for
    /// left token `left` and right fact `right_fact` (as `compiled_join_test`).
    #[inline(always)]
    fn flat_join_test(&self, i: usize, depth: u8, left: TokenId, right_fact: Ix) -> Option<bool> {
        // read in place, field by field (a copy of the plan is unpacked by shifts)
        let f = &self.st.cache.compiled_plans.flats[i & (PLAN_JOINS - 1)];
        let binds = &self.tokens[left].binds;
        let a = self.flat_cell(f.a.pat, f.a.slot, f.a.elem, binds, right_fact);
        let b = self.flat_cell(f.b.pat, f.b.slot, f.b.elem, binds, right_fact);
        if let (Some(&Value::Int(x)), Some(&Value::Int(y))) = (a, b) {
            let o = u32::from(x > y) + 1 - u32::from(x < y);
            return Some(f.test >> o & 1 != 0);
        }
        self.flat_undecided(f.root, depth, left, right_fact)
    }

    /// The cell of a `FlatPlan` (`Cell`'s fields; as `Bases` reads it), None if not
    /// found.
    #[inline(always)]
    fn flat_cell(
        &self,
        pat: u8,
        slot: u8,
        elem: u8,
        binds: &[Ix; BIND_W],
        right_fact: Ix,
    ) -> Option<&Value> {
        let fact = if pat == RIGHT {
            right_fact
        } else {
            binds[pat as usize & (BIND_W - 1)]
        };
        let at = self.facts.get(fact as usize)?.start as usize + slot as usize;
        let v = self.values.get(at)?;
        if elem == WHOLE {
            return Some(v);
        }
        match v {
            Value::Multi(m) if (elem as usize) < m.len as usize => {
                self.values.get(at + 1 + elem as usize)
            }
            _ => None,
        }
    }

    /// A `MODE_FLAT` plan's pair its flat form does not decide: its compiled plan
    /// at `root` decides, as a `MODE_BASES` one (out of line: rare).
    #[cold]
    #[inline(never)]
    fn flat_undecided(&self, root: u8, depth: u8, left: TokenId, right_fact: Ix) -> Option<bool> {
        let bases = Bases {
            binds: &self.tokens[left].binds,
            right: Bases::base(self, right_fact),
        };
        self.run_inline(root, depth, bases, right_fact)
    }

    /// The tests of `join` (its chain `tests`, at `depth`) through its compiled
    /// plan when that reads fields bound after multifields (`MODE_MARKS`), once
    /// `join_test_eval` has bound every pattern's fact and marks in `lhs_pm`:
    /// Some(result), or None when the evaluator must decide. Only a plan the usual
    /// path cached runs. (Out of line: the evaluator's path stays as it was.)
    #[inline(never)]
    pub(crate) fn marked_join_test(&mut self, join: JoinId, tests: Ix, depth: u8) -> Option<bool> {
        let i = join.ix() % PLAN_JOINS;
        let entry = &self.st.cache.compiled_plans.entries[i];
        if entry.mode != MODE_MARKS || entry.join != join || entry.tests != tests {
            return None;
        }
        let root = self.st.cache.compiled_plans.flats.get(i)?.root;
        if root == UNPLANNED {
            return None;
        }
        // the join's test plan, if cached as `quick`'s unplanned one, sends its
        // next pairs here at once (`quick`'s walk would read the plain slots only
        // to give up at the first field after a multifield); set here, off the
        // join loops, whose code stays as it was
        let t = &mut self.st.cache.test_plans[join.ix() % TEST_PLANS];
        if t.n == TestPlan::NONE.n && t.join == join && t.tests == tests {
            *t = marked_test_plan(join, tests);
        }
        self.run_inline(root, depth, Marked, NONE)
    }

    /// The field of multislot `slot` of pattern `pat` that a `Marked` plan's
    /// `SEG_ELEM` read of `delta` names (in line in `Marked`'s runner alone, the
    /// only one with the arm: out of line it cost s01b a third of its run).
    #[inline(always)]
    fn seg_elem_value(&self, pat: u8, slot: u8, delta: i32) -> Option<Value> {
        let b = self.st.net.lhs_pm.get(pat as usize)?;
        let r = SegRead::unpacked(delta);
        if slot & FIXED_SLOT == 0 {
            return self.seg_field(b, slot, r);
        }
        // the multislot at a fixed offset: no walk over the slots before it
        let (cell, len) = fixed_slot_cell(self, b.fact, slot & !FIXED_SLOT)?;
        let len = len? as usize;
        // (a plan's read is never `WHOLE_READ`: as another `n`, beyond the marks,
        // it would find no field)
        let at = match r.n {
            FROM_END => len.checked_sub(r.base as usize)?,
            // after one multifield (`$?a ?x`), the usual case
            1 => r.base as usize + *b.marks.get(r.mark as usize)? as usize,
            _ => {
                let lens = b
                    .marks
                    .get(r.mark as usize..r.mark as usize + r.n as usize)?;
                r.base as usize + lens.iter().map(|&m| m as usize).sum::<usize>()
            }
        };
        if at >= len {
            return None;
        }
        self.values.get(cell + 1 + at).copied()
    }

    /// Some when every read of shallow plan `b` (of `join`, at `depth`) is of a slot
    /// at a fixed offset in its fact: the template of the facts bound at its pattern
    /// is known (`read_templates`), and no slot before it there is a multislot
    /// (whose elements would move it).
    fn fixed_reads(&self, b: &PlanBuild, join: JoinId, depth: u8) -> Option<()> {
        let (left, right) = self.read_templates(join);
        let read = |pat: u8, slot: u8| -> Option<()> {
            let t = if pat == depth {
                right
            } else {
                *left.get(pat as usize)?
            };
            self.slot_at_fixed_offset(t, slot).then_some(())
        };
        let src = |s: Source| -> Option<()> {
            match s {
                Source::Slot { pat, slot }
                | Source::Elem { pat, slot, .. }
                | Source::SlotPlus { pat, slot, .. }
                | Source::ElemPlus { pat, slot, .. } => read(pat, slot),
                Source::Const { .. } | Source::Arith { .. } => Some(()),
            }
        };
        for n in &b.nodes[..b.used as usize] {
            match *n {
                Node::Cmp { a, b, .. } => {
                    src(a)?;
                    src(b)?;
                }
                Node::SameSlots { a, b, .. } => {
                    read(a.0, a.1)?;
                    read(b.0, b.1)?;
                }
                Node::SameCells { a, b, .. } => {
                    read(a.pat, a.slot)?;
                    read(b.pat, b.slot)?;
                }
                Node::Leaf { s } => src(s)?,
                Node::Cut { c, .. } => read(c.pat, c.slot)?,
                Node::Text { .. }
                | Node::And { .. }
                | Node::Or { .. }
                | Node::Not { .. }
                | Node::Arith { .. }
                | Node::Evaluator => {}
            }
        }
        Some(())
    }

    /// Slot `slot` of template `t` (NONE: unknown) follows single-field slots only,
    /// so it is the cell `slot` after its fact's first.
    fn slot_at_fixed_offset(&self, t: Ix, slot: u8) -> bool {
        let Some(t) = self.templates.get(t as usize) else {
            return false;
        };
        if Ix::from(slot) >= t.nslots {
            return false;
        }
        let first = t.first_slot as usize;
        (first..first + slot as usize).all(|i| self.slots.get(i).is_some_and(|s| !s.multi))
    }

    /// The templates of the facts a shallow plan of `join` reads (NONE: unknown):
    /// at each left pattern below `BIND_W`, the alpha node's of the nearest join at
    /// that depth on `join`'s path (whose bindings `Token::binds` keeps: a positive
    /// join's; another binds no fact), and `join`'s own for its right input.
    fn read_templates(&self, join: JoinId) -> ([Ix; BIND_W], Ix) {
        let tmpl = |jn: &super::Join| match self.alphas.get(jn.alpha as usize) {
            Some(a) if jn.rjoin == JoinId::NONE && jn.kind != JoinKind::Root => a.tmpl,
            _ => NONE,
        };
        let own = &self.joins[join];
        let right = tmpl(own);
        let mut left = [NONE; BIND_W];
        let mut seen = 0u32;
        let mut j = own.parent;
        while j != JoinId::NONE {
            let jn = &self.joins[j];
            if jn.kind == JoinKind::Root {
                break;
            }
            let d = jn.depth as usize;
            if d < BIND_W && seen & (1 << d) == 0 {
                seen |= 1 << d;
                if jn.kind == JoinKind::Positive {
                    left[d] = tmpl(jn);
                }
            }
            j = jn.parent;
        }
        (left, right)
    }

    /// Node `node`'s result (out of line: the composites below a root or an
    /// `or` member of a root `and`).
    #[inline(never)]
    fn run_node<L: LeftFacts>(
        &self,
        node: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        self.run_inline(node, depth, binds, right_fact)
    }

    /// `run_node` inlined into its caller: comparisons, and the members of an `and`
    /// and of an `or` (also one under an `and`) run without a call; deeper
    /// composites go through `run_node`.
    #[inline(always)]
    fn run_inline<L: LeftFacts>(
        &self,
        node: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let plans = &self.st.cache.compiled_plans;
        match plans.nodes[node as usize] {
            Node::Cmp { id, a, b } => self.run_cmp(id, a, b, depth, binds, right_fact),
            Node::SameSlots { a, b, negated } => {
                self.run_same(a, b, negated, depth, binds, right_fact)
            }
            Node::SameCells { a, b, negated } => {
                self.run_same_cells(a, b, negated, depth, binds, right_fact)
            }
            Node::And { first, len } => {
                for &k in &plans.kids[first as usize..(first + len) as usize] {
                    // the comparisons and an `or` inline, other composites through
                    // the recursion
                    let r = match plans.nodes[k as usize] {
                        Node::Cmp { id, a, b } => {
                            self.run_cmp(id, a, b, depth, binds, right_fact)?
                        }
                        Node::SameSlots { a, b, negated } => {
                            self.run_same(a, b, negated, depth, binds, right_fact)?
                        }
                        Node::SameCells { a, b, negated } => {
                            self.run_same_cells(a, b, negated, depth, binds, right_fact)?
                        }
                        Node::Or { first, len } => {
                            self.run_or(first, len, depth, binds, right_fact)?
                        }
                        _ => self.run_node(k, depth, binds, right_fact)?,
                    };
                    if !r {
                        return Some(false);
                    }
                }
                Some(true)
            }
            Node::Or { first, len } => self.run_or(first, len, depth, binds, right_fact),
            Node::Not { child } => Some(!self.run_node(child, depth, binds, right_fact)?),
            Node::Text { a, b, negated } => self.run_text(a, b, negated, depth, binds, right_fact),
            // operands, reached only through a `Source::Arith`; a member the
            // evaluator decides
            Node::Arith { .. } | Node::Leaf { .. } | Node::Cut { .. } | Node::Evaluator => None,
        }
    }

    /// An `or` of kids `first..first + len` (short-circuit, in order).
    #[inline(always)]
    fn run_or<L: LeftFacts>(
        &self,
        first: u8,
        len: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let plans = &self.st.cache.compiled_plans;
        for &k in &plans.kids[first as usize..(first + len) as usize] {
            let r = match plans.nodes[k as usize] {
                Node::Cmp { id, a, b } => self.run_cmp(id, a, b, depth, binds, right_fact)?,
                Node::SameSlots { a, b, negated } => {
                    self.run_same(a, b, negated, depth, binds, right_fact)?
                }
                Node::SameCells { a, b, negated } => {
                    self.run_same_cells(a, b, negated, depth, binds, right_fact)?
                }
                _ => self.run_node(k, depth, binds, right_fact)?,
            };
            if r {
                return Some(true);
            }
        }
        Some(false)
    }

    /// The value of arithmetic node `node`, as its builtin computes it; None where
    /// the evaluator must decide (a non-number operand, a zero divisor).
    fn run_arith<L: LeftFacts>(
        &self,
        node: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<Num> {
        let plans = &self.st.cache.compiled_plans;
        let Node::Arith { op, first, len } = plans.nodes[node as usize] else {
            return None;
        };
        let kids = &plans.kids[first as usize..(first + len) as usize];
        let (&k0, rest) = kids.split_first()?;
        let mut acc = self.arith_operand(k0, depth, binds, right_fact)?;
        match op {
            ArOp::Abs => {
                return Some(match acc {
                    Num::Int(i) => Num::Int(i.wrapping_abs()),
                    // negated only below zero, so -0.0 stays -0.0
                    Num::Float(f) => Num::Float(if f < 0.0 { -f } else { f }),
                });
            }
            ArOp::Float => return Some(Num::Float(acc.as_f64())),
            ArOp::Slash => acc = Num::Float(acc.as_f64()),
            ArOp::Div => acc = Num::Int(div_operand(acc)),
            _ => {}
        }
        for &k in rest {
            let x = self.arith_operand(k, depth, binds, right_fact)?;
            acc = match (op, acc, x) {
                (ArOp::Add, Num::Int(p), Num::Int(q)) => Num::Int(p.wrapping_add(q)),
                (ArOp::Sub, Num::Int(p), Num::Int(q)) => Num::Int(p.wrapping_sub(q)),
                (ArOp::Mul, Num::Int(p), Num::Int(q)) => Num::Int(p.wrapping_mul(q)),
                (ArOp::Mod, Num::Int(p), Num::Int(q)) if q != 0 => Num::Int(p.wrapping_rem(q)),
                _ => float_step(op, acc, x)?,
            };
        }
        Some(acc)
    }

    /// One operand of an arithmetic node, as a number.
    #[inline(always)]
    fn arith_operand<L: LeftFacts>(
        &self,
        k: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<Num> {
        match self.st.cache.compiled_plans.nodes[k as usize] {
            Node::Leaf { s } => match self.source_value(s, depth, binds, right_fact)? {
                Value::Int(i) => Some(Num::Int(i)),
                Value::Float(f) => Some(Num::Float(f)),
                _ => None,
            },
            Node::Arith { .. } => self.run_arith(k, depth, binds, right_fact),
            _ => None,
        }
    }

    /// One planned `eq`/`neq` of two slots.
    #[inline(always)]
    fn run_same<L: LeftFacts>(
        &self,
        a: (u8, u8),
        b: (u8, u8),
        negated: bool,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let va = self.plan_cell(a, depth, binds, right_fact)?;
        let vb = self.plan_cell(b, depth, binds, right_fact)?;
        Some(same_cell(va, vb)? != negated)
    }

    /// One planned `eq`/`neq` of two cells, one of them (or both) a multislot's field.
    #[inline(always)]
    fn run_same_cells<L: LeftFacts>(
        &self,
        a: Cell,
        b: Cell,
        negated: bool,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let va = self.plan_field(a, depth, binds, right_fact)?;
        let vb = self.plan_field(b, depth, binds, right_fact)?;
        Some(same_cell(va, vb)? != negated)
    }

    /// One planned `eq`/`neq` of two multifield variables (`Seg::node` operands of
    /// a `Text`), as `eq` compares two multifields: the lengths, then field by field.
    #[inline(always)]
    fn run_same_segs<L: LeftFacts>(
        &self,
        a: Seg,
        b: Seg,
        negated: bool,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let xa = self.seg_fields(a, depth, binds, right_fact)?;
        let xb = self.seg_fields(b, depth, binds, right_fact)?;
        let same = xa.len() == xb.len() && xa.iter().zip(xb).all(|(va, vb)| va.same(*vb));
        Some(same != negated)
    }

    /// The fields segment `s` names, where they lie; None if its pattern is unbound
    /// or the slot is not a multislot holding its singles.
    #[inline(always)]
    fn seg_fields<L: LeftFacts>(
        &self,
        s: Seg,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<&[Value]> {
        let (cell, len) = binds.slot_cell(self, s.pat, s.slot, depth, right_fact)?;
        let len = len? as usize;
        let from = cell + 1 + s.before as usize;
        let to = (cell + 1 + len).checked_sub(s.after as usize)?;
        self.values.get(from..to.max(from))
    }

    /// The cell `c` names, where it lies; None if its pattern is unbound or the
    /// multislot has no such field.
    #[inline(always)]
    fn plan_field<L: LeftFacts>(
        &self,
        c: Cell,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<&Value> {
        if c.elem == WHOLE {
            return binds.slot(self, c.pat, c.slot, depth, right_fact);
        }
        match binds.slot_cell(self, c.pat, c.slot, depth, right_fact)? {
            (cell, Some(len)) if (c.elem as usize) < len as usize => {
                self.values.get(cell + 1 + c.elem as usize)
            }
            _ => None,
        }
    }

    /// The cell of single-field slot `slot` of the fact bound at `pat`, where it lies
    /// (a copy of the two values costs more than the comparison); None if unbound.
    #[inline(always)]
    fn plan_cell<L: LeftFacts>(
        &self,
        (pat, slot): (u8, u8),
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<&Value> {
        binds.slot(self, pat, slot, depth, right_fact)
    }

    /// One planned `eq`/`neq` of text operands (`Node::Text`).
    #[inline(never)]
    fn run_text<L: LeftFacts>(
        &self,
        a: u8,
        b: u8,
        negated: bool,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let nodes = &self.st.cache.compiled_plans.nodes;
        if let (Some(sa), Some(sb)) = (Seg::of(nodes[a as usize]), Seg::of(nodes[b as usize])) {
            return self.run_same_segs(sa, sb, negated, depth, binds, right_fact);
        }
        let ta = self.text_operand(a, depth, binds, right_fact)?;
        let tb = self.text_operand(b, depth, binds, right_fact)?;
        let same = matches!((ta, tb), (Some(x), Some(y)) if x == y);
        Some(same != negated)
    }

    /// A text operand's bytes: Some(None) for a value no string equals (not a
    /// string), None where the evaluator must look (an unbound or multifield
    /// variable, a cut of a non-lexeme, which the builtin reports, or of a text
    /// that is not ASCII, whose characters are not its bytes).
    #[inline(always)]
    fn text_operand<L: LeftFacts>(
        &self,
        k: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<Option<&[u8]>> {
        match self.st.cache.compiled_plans.nodes[k as usize] {
            Node::Cut { c, from, to } => {
                // as `sub-string`: an instance name is cut without its brackets
                let (id, inst) = match *self.plan_field(c, depth, binds, right_fact)? {
                    Value::Sym(id) => (id, true),
                    Value::Str(id) => (id, false),
                    _ => return None,
                };
                let b = self.sym_texts().text_bytes(id);
                let b = match b {
                    [b'[', body @ .., b']'] if inst && !body.is_empty() => body,
                    _ => b,
                };
                if !b.is_ascii() {
                    return None;
                }
                let (from, to) = (i64::from(from).max(1), i64::from(to).min(b.len() as i64));
                Some(Some(match from > to {
                    true => &b[..0],
                    false => &b[from as usize - 1..to as usize],
                }))
            }
            Node::Leaf { s } => match self.source_value(s, depth, binds, right_fact)? {
                Value::Str(id) => Some(Some(self.sym_texts().text_bytes(id))),
                _ => Some(None),
            },
            _ => None,
        }
    }

    /// One planned comparison.
    #[inline(always)]
    fn run_cmp<L: LeftFacts>(
        &self,
        id: u8,
        a: Source,
        b: Source,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<bool> {
        let va = self.source_value(a, depth, binds, right_fact)?;
        let vb = self.source_value(b, depth, binds, right_fact)?;
        builtins::basic::compare(self, id as Ix, va, vb)
    }

    /// The single-field value a source names; None where the evaluator must look.
    #[inline(always)]
    fn source_value<L: LeftFacts>(
        &self,
        s: Source,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<Value> {
        match s {
            Source::Slot { pat, slot } => self.plan_slot_value(pat, slot, depth, binds, right_fact),
            Source::Elem { pat, slot, elem } => {
                let (cell, len) = binds.slot_cell(self, pat, slot, depth, right_fact)?;
                match len {
                    Some(len) if (elem as usize) < len as usize => {
                        Some(self.values[cell + 1 + elem as usize])
                    }
                    _ => None,
                }
            }
            Source::Const { e } => Some(self.const_value(e)),
            Source::ElemPlus {
                pat,
                slot,
                elem,
                delta,
            } => {
                // (`Marked` alone: the other runners have no such arm)
                if L::MARKED && elem == SEG_ELEM {
                    return self.seg_elem_value(pat, slot, delta);
                }
                let (cell, len) = binds.slot_cell(self, pat, slot, depth, right_fact)?;
                match (len, self.values.get(cell + 1 + elem as usize)) {
                    (Some(len), Some(&Value::Int(i))) if (elem as usize) < len as usize => {
                        Some(Value::Int(i.wrapping_add(i64::from(delta))))
                    }
                    _ => None,
                }
            }
            Source::SlotPlus { pat, slot, delta } => {
                match self.plan_slot_value(pat, slot, depth, binds, right_fact)? {
                    Value::Int(i) => Some(Value::Int(i.wrapping_add(i64::from(delta)))),
                    _ => None,
                }
            }
            Source::Arith { node } => Some(self.run_arith(node, depth, binds, right_fact)?.value()),
        }
    }

    /// A single-field slot of the fact bound at `pat` (None for a multifield).
    #[inline(always)]
    fn plan_slot_value<L: LeftFacts>(
        &self,
        pat: u8,
        slot: u8,
        depth: u8,
        binds: L,
        right_fact: Ix,
    ) -> Option<Value> {
        match *binds.slot(self, pat, slot, depth, right_fact)? {
            Value::Multi(_) => None,
            v => Some(v),
        }
    }

    /// Plans the sibling chain from `first` as one `and`/`or` node, without its
    /// member `skip` (NONE: every member).
    fn plan_chain(
        &self,
        plan: &mut PlanBuild,
        first: Ix,
        depth: u8,
        chain: Chain,
        level: u8,
        skip: Ix,
    ) -> Option<u8> {
        if level > PLAN_DEPTH {
            return None;
        }
        let mut members = [0u8; PLAN_NODES];
        let mut len = 0usize;
        let mut t = first;
        // (a member the plan cannot hold after one it holds: `Node::Evaluator`, and
        // the chain ends there; a chain that would start with one is not planned, it
        // would never decide)
        let mut planned = false;
        while t != NONE {
            if t != skip {
                let mark = (plan.used, plan.kids_used, plan.deep, plan.marks);
                let m = match self.plan_test(plan, t, depth, level) {
                    Some(m) => {
                        planned = true;
                        m
                    }
                    // (in an `and` only: an `or` whose planned members mostly
                    // fail would send most pairs to the evaluator after them)
                    // (none once the pool is crowded: `store` would drop it)
                    None if planned
                        && matches!(chain, Chain::And)
                        && !self.st.cache.compiled_plans.crowded =>
                    {
                        // reached, it ends the plan: the members after it never
                        // run (the nodes the member left behind are dropped)
                        (plan.used, plan.kids_used, plan.deep, plan.marks) = mark;
                        *members.get_mut(len)? = plan.push(Node::Evaluator)?;
                        plan.partial = true;
                        len += 1;
                        break;
                    }
                    None => return None,
                };
                *members.get_mut(len)? = m;
                len += 1;
            }
            t = self.exprs[t as usize].next;
        }
        if len == 1 {
            return Some(members[0]);
        }
        if let Chain::And = chain {
            plan.selective_first(&mut members[..len]);
        }
        let start = plan.reserve_kids(len)?;
        plan.kids[start as usize..start as usize + len].copy_from_slice(&members[..len]);
        let (first, len) = (start, len as u8);
        plan.push(match chain {
            Chain::And => Node::And { first, len },
            Chain::Or => Node::Or { first, len },
        })
    }

    /// Plans one boolean test expression.
    fn plan_test(&self, plan: &mut PlanBuild, e: Ix, depth: u8, level: u8) -> Option<u8> {
        let x = self.exprs[e as usize];
        let builtin = |id: Ix| x.op == Op::Call && x.aux == FnKind::Builtin as u8 && x.data == id;
        match x.op {
            Op::Eq2 => self.plan_cmp(plan, FN_EQ, x.first, depth),
            Op::Call if builtin(FN_AND) => {
                self.plan_chain(plan, x.first, depth, Chain::And, level + 1, NONE)
            }
            Op::And => self.plan_chain(plan, x.first, depth, Chain::And, level + 1, NONE),
            Op::Call if builtin(FN_OR) => {
                self.plan_chain(plan, x.first, depth, Chain::Or, level + 1, NONE)
            }
            Op::Or => self.plan_chain(plan, x.first, depth, Chain::Or, level + 1, NONE),
            Op::Not => self.plan_not(plan, x.first, depth, level),
            Op::Call if builtin(FN_NOT) => self.plan_not(plan, x.first, depth, level),
            Op::Call
                if x.aux == FnKind::Builtin as u8 && (CMP_FIRST..=CMP_LAST).contains(&x.data) =>
            {
                self.plan_cmp(plan, x.data, x.first, depth)
            }
            _ => None,
        }
    }

    /// `not` of the single test `child`; of an equality (`~?x`), `neq` in one node.
    fn plan_not(&self, plan: &mut PlanBuild, child: Ix, depth: u8, level: u8) -> Option<u8> {
        if child == NONE || self.exprs[child as usize].next != NONE {
            return None;
        }
        let c = self.exprs[child as usize];
        let is_eq = c.op == Op::Eq2
            || (c.op == Op::Call && c.aux == FnKind::Builtin as u8 && c.data == FN_EQ);
        if is_eq {
            return self.plan_cmp(plan, FN_NEQ, c.first, depth);
        }
        let child = self.plan_test(plan, child, depth, level + 1)?;
        plan.push(Node::Not { child })
    }

    /// A two-operand comparison `id` of the chain from `a`.
    fn plan_cmp(&self, plan: &mut PlanBuild, id: Ix, a: Ix, depth: u8) -> Option<u8> {
        if a == NONE {
            return None;
        }
        let b = self.exprs[a as usize].next;
        if b == NONE || self.exprs[b as usize].next != NONE {
            return None;
        }
        if id == FN_EQ || id == FN_NEQ {
            if let (Some(sa), Some(sb)) = (self.plan_seg(a, depth), self.plan_seg(b, depth)) {
                for p in [sa.pat, sb.pat] {
                    if p != depth && p as usize >= BIND_W {
                        plan.deep = true;
                    }
                }
                let a = plan.push(sa.node())?;
                let b = plan.push(sb.node())?;
                return plan.push(Node::Text {
                    a,
                    b,
                    negated: id == FN_NEQ,
                });
            }
            let (ca, cb) = (self.plan_cut(plan, a, depth), self.plan_cut(plan, b, depth));
            if ca.is_some() || cb.is_some() {
                let text = |plan: &mut PlanBuild, cut: Option<Node>, e: Ix| match cut {
                    Some(t) => plan.push(t),
                    None => match self.plan_simple_source(e, depth)? {
                        s @ (Source::Slot { .. } | Source::Elem { .. } | Source::Const { .. }) => {
                            if let Some(p) = s.pat() {
                                if p != depth && p as usize >= BIND_W {
                                    plan.deep = true;
                                }
                            }
                            plan.push(Node::Leaf { s })
                        }
                        _ => None,
                    },
                };
                let ta = text(plan, ca, a)?;
                let tb = text(plan, cb, b)?;
                return plan.push(Node::Text {
                    a: ta,
                    b: tb,
                    negated: id == FN_NEQ,
                });
            }
        }
        let a = self.plan_source(plan, a, depth, 0)?;
        let b = self.plan_source(plan, b, depth, 0)?;
        if id == FN_EQ || id == FN_NEQ {
            let negated = id == FN_NEQ;
            if let (Source::Slot { pat: pa, slot: sa }, Source::Slot { pat: pb, slot: sb }) = (a, b)
            {
                return plan.push(Node::SameSlots {
                    a: (pa, sa),
                    b: (pb, sb),
                    negated,
                });
            }
            if let (Some(a), Some(b)) = (Cell::of(a), Cell::of(b)) {
                return plan.push(Node::SameCells { a, b, negated });
            }
        }
        plan.push(Node::Cmp {
            id: u8::try_from(id).ok()?,
            a,
            b,
        })
    }

    /// The segment of a multifield variable operand (`$?p`, an `Expand` that does
    /// not splice, of a pattern variable), when it is its slot's only multifield
    /// element, of a pattern at or above the join's `depth`.
    fn plan_seg(&self, e: Ix, depth: u8) -> Option<Seg> {
        let mut x = self.exprs[e as usize];
        if x.op == Op::Expand && x.aux == 0 && x.first != NONE {
            x = self.exprs[x.first as usize];
        }
        let elem = loc::elem(x.data);
        if x.op != Op::PatVar
            || x.data == loc::FACT
            || elem == loc::SINGLE
            || x.first == NONE
            || x.aux > depth
        {
            return None;
        }
        // the slot's elements (`aux` 1: a multifield): the variable's must be its
        // only multifield
        let (mut i, mut multis, mut is_multi) = (0u8, 0u8, false);
        let mut c = self.exprs[x.first as usize].first;
        while c != NONE {
            let ex = self.exprs[c as usize];
            if ex.aux == 1 {
                multis += 1;
                is_multi |= i == elem;
            }
            i = i.checked_add(1)?;
            c = ex.next;
        }
        if multis != 1 || !is_multi || elem >= i {
            return None;
        }
        Some(Seg {
            pat: x.aux,
            slot: loc::slot(x.data),
            before: elem,
            after: i - elem - 1,
        })
    }

    /// `(sub-string from to ?x)` with integer constant bounds (within 16 bits) of
    /// a single-field slot or element variable, as a `Node::Cut` (not pushed yet).
    fn plan_cut(&self, plan: &mut PlanBuild, e: Ix, depth: u8) -> Option<Node> {
        let x = self.exprs[e as usize];
        if x.op != Op::Call || x.aux != FnKind::Builtin as u8 || x.data != FN_SUB_STRING {
            return None;
        }
        let bound = |ix: Ix| -> Option<(i16, Ix)> {
            if ix == NONE || self.exprs[ix as usize].op != Op::Int {
                return None;
            }
            let Value::Int(i) = self.const_value(ix) else {
                return None;
            };
            Some((i16::try_from(i).ok()?, self.exprs[ix as usize].next))
        };
        let (from, next) = bound(x.first)?;
        let (to, var) = bound(next)?;
        if var == NONE || self.exprs[var as usize].next != NONE {
            return None;
        }
        let v = self.exprs[var as usize];
        if v.op != Op::PatVar {
            return None;
        }
        let c = Cell::of(self.plan_source(plan, var, depth, 0)?)?;
        Some(Node::Cut { c, from, to })
    }

    /// The source of an operand: a single-field slot variable, a constant, a slot
    /// variable plus or minus an integer constant, or integer arithmetic of those
    /// (nested `level` deep). Marks the plan `deep` for a left pattern at or beyond
    /// `BIND_W`.
    fn plan_source(&self, plan: &mut PlanBuild, e: Ix, depth: u8, level: u8) -> Option<Source> {
        let s = self.plan_simple_source(e, depth);
        if let Some(s) = s {
            if let Some(p) = s.pat() {
                if p != depth && p as usize >= BIND_W {
                    plan.deep = true;
                }
            }
            return Some(s);
        }
        if let Some(s) = self.plan_seg_elem(plan, e, depth) {
            return Some(s);
        }
        self.plan_arith(plan, e, depth, level)
    }

    /// A single-field pattern variable bound after a multifield of its slot (of a
    /// pattern at or above the join's `depth`), as a `SEG_ELEM` read (the plan
    /// becomes `MODE_MARKS`).
    fn plan_seg_elem(&self, plan: &mut PlanBuild, e: Ix, depth: u8) -> Option<Source> {
        let x = self.exprs[e as usize];
        if x.op != Op::PatVar || x.aux > depth {
            return None;
        }
        let r = self.seg_read(&x)?;
        // (a field at a fixed offset is `plan_elem`'s)
        if r.n == 0 {
            return None;
        }
        plan.marks = true;
        Some(Source::ElemPlus {
            pat: x.aux,
            slot: loc::slot(x.data),
            elem: SEG_ELEM,
            delta: r.packed(),
        })
    }

    /// Where single-field pattern variable `x`, an element of a multislot, lies in
    /// it (`SegRead::n` 0: at a fixed offset, no multifield before it), as
    /// `pattern_var` finds it; None for another variable, or one after more
    /// multifields than the marks keep.
    pub(crate) fn seg_read(&self, x: &Expr) -> Option<SegRead> {
        let elem = loc::elem(x.data);
        if x.first == NONE || x.data == loc::FACT || elem == loc::SINGLE {
            return None;
        }
        let desc = self.exprs[x.first as usize];
        if desc.op != Op::PatSlot {
            return None;
        }
        // singles and multifields before the element, and whether one follows it
        let (mut i, mut singles, mut multis, mut after) = (0u8, 0u8, 0u8, false);
        let mut c = desc.first;
        while c != NONE {
            let ex = self.exprs[c as usize];
            let multi = ex.aux == 1;
            match i.cmp(&elem) {
                core::cmp::Ordering::Less if multi => multis += 1,
                core::cmp::Ordering::Less => singles += 1,
                core::cmp::Ordering::Equal if multi => return None,
                core::cmp::Ordering::Equal => {}
                core::cmp::Ordering::Greater => after |= multi,
            }
            i = i.checked_add(1)?;
            c = ex.next;
        }
        if elem >= i {
            return None;
        }
        Some(if multis == 0 {
            SegRead {
                base: singles,
                mark: 0,
                n: 0,
            }
        } else if after {
            // before the slot's last multifield: each one before it has its mark
            if desc.aux as usize + multis as usize > crate::rete::MAX_MARKS {
                return None;
            }
            SegRead {
                base: singles,
                mark: desc.aux,
                n: multis,
            }
        } else {
            // after the last one: counted from the slot's end
            SegRead {
                base: i - elem,
                mark: 0,
                n: FROM_END,
            }
        })
    }

    /// The field `r` names in slot `slot` of the fact `b` binds, with `b`'s marks
    /// (`WHOLE_READ`: the slot itself, a single-field one); None if unbound or not
    /// there.
    #[inline(always)]
    pub(crate) fn seg_field(&self, b: &PatBinding, slot: u8, r: SegRead) -> Option<Value> {
        if r.n == WHOLE_READ {
            return match *fact_slot(self, b.fact, slot)? {
                Value::Multi(_) => None,
                v => Some(v),
            };
        }
        let (cell, len) = fact_slot_cell(self, b.fact, slot)?;
        let len = len? as usize;
        let at = if r.n == FROM_END {
            len.checked_sub(r.base as usize)?
        } else {
            let lens = b
                .marks
                .get(r.mark as usize..r.mark as usize + r.n as usize)?;
            r.base as usize + lens.iter().map(|&m| m as usize).sum::<usize>()
        };
        if at >= len {
            return None;
        }
        self.values.get(cell + 1 + at).copied()
    }

    /// The `MarkKey` of `join`: the fields `each_left_key_value` evaluates, each a
    /// single-field slot or an element `seg_read` finds; None if one is another.
    /// (Worked out per key: a cache of them made the engine's state larger, which
    /// every program pays as it starts; the evaluator's walk costs more. Inlined:
    /// out of line, a planned key's rare misses in `marks_left_key` cost manypat-50
    /// +0.34 %.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn mark_key(&self, join: JoinId) -> Option<MarkKey> {
        let j = &self.joins[join];
        let nrhash = self.alphas[j.alpha as usize].nrhash;
        let mut p = MarkKey {
            n: 0,
            reads: [(0, 0, SegRead::NONE); MAX_RHASH],
        };
        let mut t = j.tests;
        while t != NONE && p.n < nrhash {
            let x = self.exprs[t as usize];
            if let Some(other) = self.key_test_other(&x, j.depth) {
                let o = self.exprs[other as usize];
                if o.aux > j.depth || o.data == loc::FACT {
                    return None;
                }
                let r = if o.first == NONE {
                    if loc::elem(o.data) != loc::SINGLE {
                        return None;
                    }
                    SegRead {
                        n: WHOLE_READ,
                        ..SegRead::NONE
                    }
                } else {
                    self.seg_read(&o)?
                };
                *p.reads.get_mut(p.n as usize)? = (o.aux, loc::slot(o.data), r);
                p.n += 1;
            }
            t = x.next;
        }
        (p.n == nrhash).then_some(p)
    }

    /// Arithmetic `(+ ...)`, `(- ...)`, `(* ...)`, `(/ ...)`, `(mod a b)`, `(div ...)`,
    /// `(min ...)`, `(max ...)`, `(abs a)`, `(float a)` of plannable operands, as an
    /// `Arith` node.
    fn plan_arith(&self, plan: &mut PlanBuild, e: Ix, depth: u8, level: u8) -> Option<Source> {
        if level >= PLAN_DEPTH {
            return None;
        }
        let x = self.exprs[e as usize];
        if x.op != Op::Call || x.aux != FnKind::Builtin as u8 || x.first == NONE {
            return None;
        }
        let op = match x.data {
            FN_ADD => ArOp::Add,
            FN_SUB => ArOp::Sub,
            FN_MUL => ArOp::Mul,
            FN_SLASH => ArOp::Slash,
            FN_MOD => ArOp::Mod,
            FN_DIV => ArOp::Div,
            FN_ABS => ArOp::Abs,
            FN_MIN => ArOp::Min,
            FN_MAX => ArOp::Max,
            FN_FLOAT => ArOp::Float,
            _ => return None,
        };
        let mut members = [0u8; PLAN_NODES];
        let mut len = 0usize;
        let mut a = x.first;
        while a != NONE {
            let s = self.plan_source(plan, a, depth, level + 1)?;
            let node = match s {
                Source::Arith { node } => node,
                s => plan.push(Node::Leaf { s })?,
            };
            *members.get_mut(len)? = node;
            len += 1;
            a = self.exprs[a as usize].next;
        }
        // the builtins' arities (a call of another is the evaluator's to report)
        let one = matches!(op, ArOp::Abs | ArOp::Float);
        if one != (len == 1) || (op == ArOp::Mod && len != 2) {
            return None;
        }
        let first = plan.reserve_kids(len)?;
        plan.kids[first as usize..first as usize + len].copy_from_slice(&members[..len]);
        let node = plan.push(Node::Arith {
            op,
            first,
            len: len as u8,
        })?;
        Some(Source::Arith { node })
    }

    /// `plan_source` without arithmetic nodes: a slot variable, a constant, or a
    /// slot variable plus or minus an integer constant.
    fn plan_simple_source(&self, e: Ix, depth: u8) -> Option<Source> {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Int | Op::Float | Op::Sym | Op::Str => Some(Source::Const { e }),
            Op::PatVar if x.first != NONE => self.plan_elem(&x, depth),
            Op::PatVar => {
                let (pat, slot) = self.plan_slot(&x, depth)?;
                Some(Source::Slot { pat, slot })
            }
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && (x.data == FN_ADD || x.data == FN_SUB)
                    && x.first != NONE =>
            {
                let first = self.exprs[x.first as usize];
                if first.next == NONE || self.exprs[first.next as usize].next != NONE {
                    return None;
                }
                let second_ix = first.next;
                let second = self.exprs[second_ix as usize];
                let int_const = |ix: Ix, ex: &Expr| match ex.op {
                    Op::Int => match self.const_value(ix) {
                        Value::Int(i) => Some(i),
                        _ => None,
                    },
                    _ => None,
                };
                // `(+ ?x N)`, `(+ N ?x)`, `(- ?x N)`
                let (var, delta) = if first.op == Op::PatVar {
                    (first, int_const(second_ix, &second)?)
                } else if x.data == FN_ADD && second.op == Op::PatVar {
                    (second, int_const(x.first, &first)?)
                } else {
                    return None;
                };
                // within 32 bits, so `(- ?x i64::MIN)`, whose negation wraps, is
                // the evaluator's
                let delta = i32::try_from(delta).ok()?;
                let delta = if x.data == FN_SUB {
                    delta.checked_neg()?
                } else {
                    delta
                };
                // (an ordered fact's field: `ElemPlus`)
                if var.first != NONE {
                    let Source::Elem { pat, slot, elem } = self.plan_elem(&var, depth)? else {
                        return None;
                    };
                    return Some(Source::ElemPlus {
                        pat,
                        slot,
                        elem,
                        delta,
                    });
                }
                let (pat, slot) = self.plan_slot(&var, depth)?;
                Some(Source::SlotPlus { pat, slot, delta })
            }
            _ => None,
        }
    }

    /// A pattern variable naming a single-field element of a multislot, at a fixed
    /// offset: every element of the pattern's slot up to it is single-field.
    fn plan_elem(&self, x: &Expr, depth: u8) -> Option<Source> {
        if x.data == loc::FACT || x.aux > depth {
            return None;
        }
        // (`SEG_ELEM` is `plan_seg_elem`'s; fields that far are rare)
        let elem = self.fixed_elem(x).filter(|&e| e < SEG_ELEM)?;
        Some(Source::Elem {
            pat: x.aux,
            slot: loc::slot(x.data),
            elem,
        })
    }

    /// The (pattern, slot) of a pattern variable naming a whole single-field slot of a
    /// pattern at or above the join's `depth`.
    fn plan_slot(&self, x: &Expr, depth: u8) -> Option<(u8, u8)> {
        (x.op == Op::PatVar
            && x.first == NONE
            && x.data != loc::FACT
            && loc::elem(x.data) == loc::SINGLE
            && x.aux <= depth)
            .then(|| (x.aux, loc::slot(x.data)))
    }
}

/// `div`'s reading of an operand: a float truncated as C converts it.
#[inline(always)]
fn div_operand(n: Num) -> i64 {
    match n {
        Num::Int(i) => i,
        Num::Float(f) => builtins::math::c_trunc_to_i64(f),
    }
}

/// One step of `run_arith`'s fold other than two integers added, subtracted or
/// multiplied: `acc` op `x` as the builtin computes it; None for a zero divisor
/// (the builtin reports it). Out of line: the integer steps stay small.
#[inline(never)]
fn float_step(op: ArOp, acc: Num, x: Num) -> Option<Num> {
    Some(match op {
        ArOp::Add => Num::Float(acc.as_f64() + x.as_f64()),
        ArOp::Sub => Num::Float(acc.as_f64() - x.as_f64()),
        ArOp::Mul => Num::Float(acc.as_f64() * x.as_f64()),
        ArOp::Slash => {
            let q = x.as_f64();
            if q == 0.0 {
                return None;
            }
            Num::Float(acc.as_f64() / q)
        }
        ArOp::Mod => {
            if x.as_f64() == 0.0 {
                return None;
            }
            match (acc, x) {
                (Num::Int(p), Num::Int(q)) => Num::Int(p.wrapping_rem(q)),
                (p, q) => {
                    let (p, q) = (p.as_f64(), q.as_f64());
                    Num::Float(p - libm::trunc(p / q) * q)
                }
            }
        }
        ArOp::Div => {
            let d = div_operand(x);
            if d == 0 {
                return None;
            }
            Num::Int(div_operand(acc).wrapping_div(d))
        }
        ArOp::Min => {
            if builtins::math::less(x, acc) {
                x
            } else {
                acc
            }
        }
        ArOp::Max => {
            if builtins::math::less(acc, x) {
                x
            } else {
                acc
            }
        }
        // (one argument: answered before the fold)
        ArOp::Abs | ArOp::Float => return None,
    })
}

/// Which connective a chain of tests is.
#[derive(Clone, Copy)]
enum Chain {
    And,
    Or,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planned_builtin_ids_name_the_builtins() {
        let name = |id: Ix| builtins::get(id).name;
        assert_eq!(name(FN_ADD), "+");
        assert_eq!(name(FN_SUB), "-");
        assert_eq!(name(FN_MUL), "*");
        assert_eq!(name(FN_EQ), "eq");
        assert_eq!(name(FN_NEQ), "neq");
        assert_eq!(name(FN_AND), "and");
        assert_eq!(name(FN_OR), "or");
        assert_eq!(name(FN_NOT), "not");
        assert_eq!(name(FN_ABS), "abs");
        assert_eq!(name(FN_SLASH), "/");
        assert_eq!(name(FN_MIN), "min");
        assert_eq!(name(FN_MAX), "max");
        assert_eq!(name(FN_FLOAT), "float");
        assert_eq!(name(FN_MOD), "mod");
        assert_eq!(name(FN_DIV), "div");
    }

    /// Join tests with `/`, `min`, `max`, `float`, `abs` and float constants are
    /// planned whole (no `Node::Evaluator`, no unplanned entry), and decide as the
    /// evaluator does.
    #[test]
    fn float_arithmetic_tests_are_planned_whole() {
        extern crate std;
        let mut e = std::boxed::Box::new(crate::engine::SmallEngine::new());
        let mut h = crate::testutil::CaptureHost::default();
        e.batch_str(
            &mut h,
            "(deftemplate pt (slot id) (slot x))
             (defrule tri (pt (id ?i) (x ?a)) (w ?i ?k) (pt (id ?j&:(> ?j ?i)) (x ?b))
               (test (= (mod (+ ?a (* ?b ?k) (max ?a ?b)) 13) 0))
               (test (or (> (/ ?a ?k) 2.5) (< (min ?b ?k) 3)))
               (test (> (float (+ ?a ?b)) (* 0.5 (abs (- ?a ?b)))))
               => (printout t tri \" \" ?i \" \" ?j crlf))
             (assert (pt (id 1) (x 5)) (pt (id 2) (x 4)) (pt (id 3) (x 1.5)) (w 1 2) (w 2 1))
             (run)",
            false,
        );
        assert!(h.out.ends_with("tri 1 3\n"), "{}", h.out);
        let core = e.core(&mut h);
        let plans = &core.st.cache.compiled_plans;
        let entries = plans.entries.iter().filter(|x| x.join != JoinId::NONE);
        let mut planned = 0;
        for x in entries {
            assert!(x.root != UNPLANNED || x.mode == MODE_FLAT, "{x:?}");
            planned += 1;
        }
        assert!(planned > 0);
        let used = &plans.nodes[..plans.nodes_used as usize];
        assert!(!used.contains(&Node::Evaluator), "{used:?}");
    }
}
