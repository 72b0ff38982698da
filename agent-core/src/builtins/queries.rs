//! Fact-set queries: any-factp find-fact find-all-facts do-for-fact do-for-all-facts.
//!
//! The parser hands over `((?v tmpl...)...)` as a `Nop` node whose children are one
//! `Local` node per variable, each with `Sym` children naming its templates; then the
//! query expression, then the actions. Tuples are visited as CLIPS 6.30 does: the first
//! variable varies slowest; each variable walks its templates in the order written and,
//! within one template, the facts in fact-index order. Facts retracted by the actions
//! are skipped; facts asserted by them join the iteration as CLIPS's template lists
//! let them (see `next_of_template`).

use super::control::{release_scratch, release_scratch_keeping};
use super::describe::OnError;
use super::{Builtin, ANY, SYM_FALSE};
use crate::engine::Core;
use crate::error::EvalError;
use crate::value::Ix;
use crate::value::{FactRef, Value, NONE};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::query("any-factp", 2, 2, any_factp).on_error(OnError::False),
    Builtin::query("find-fact", 2, 2, find_fact).on_error(OnError::EmptyMultifield),
    Builtin::query("find-all-facts", 2, 2, find_all_facts).on_error(OnError::EmptyMultifield),
    Builtin::query("do-for-fact", 2, ANY, do_for_fact).on_error(OnError::False),
    Builtin::query("do-for-all-facts", 2, ANY, do_for_all_facts).on_error(OnError::False),
    Builtin::query("delayed-do-for-all-facts", 2, ANY, delayed_do_for_all_facts).on_error(OnError::False),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// Most query variables in one fact-set query.
const MAX_VARS: usize = 8;

/// The parsed shape of one query call.
struct Query {
    /// `Local` nodes of the variables, in order.
    vars: [Ix; MAX_VARS],
    nvars: usize,
    /// The query expression and the first action (NONE when there are none).
    test: Ix,
    actions: Ix,
}

/// What to do with each tuple that satisfies the query.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Stop at the first tuple (any-factp, find-fact, do-for-fact).
    First,
    /// Visit every tuple.
    All,
}

/// Per-call iteration state: the current fact of each variable and the collector.
struct Walk {
    q: Query,
    mode: Mode,
    cursor: [FactRef; MAX_VARS],
    /// find-all-facts/find-fact: append matching tuples to the multifield being built.
    collect: bool,
    /// do-for-*: evaluate the actions for matching tuples.
    act: bool,
    found: bool,
    last: Value,
    /// The scratch top when the walk began: in do-for-all-facts each tuple's value
    /// supersedes the one before, whose cells are freed down to here.
    base: Ix,
    /// The outermost query outside a firing: it frees the facts its tuples retracted
    /// (see `Core::query_hold`) once no variable is bound to them.
    hold_top: bool,
    /// Host: the shape of the query test (`classify_test`).
    #[cfg(feature = "host-speedups")]
    shape: u8,
}

fn parse(cx: &Core<'_>, call: Ix) -> Result<Query, EvalError> {
    let decl = cx.exprs[call as usize].first;
    let test = cx.exprs[decl as usize].next;
    let actions = if test == NONE {
        NONE
    } else {
        cx.exprs[test as usize].next
    };
    let mut q = Query {
        vars: [NONE; MAX_VARS],
        nvars: 0,
        test,
        actions,
    };
    let mut v = cx.exprs[decl as usize].first;
    while v != NONE {
        if q.nvars == MAX_VARS {
            return Err(EvalError::message(
                crate::error::Message::QueryTooManyVariables,
            ));
        }
        q.vars[q.nvars] = v;
        q.nvars += 1;
        v = cx.exprs[v as usize].next;
    }
    if test == NONE || q.nvars == 0 {
        return Err(EvalError::message(crate::error::Message::QueryIncomplete));
    }
    Ok(q)
}

/// Does fact slot `f` belong to one of the templates listed under variable node `var`?
fn fact_fits(cx: &Core<'_>, var: Ix, f: Ix) -> bool {
    let tmpl = cx.facts[f as usize].tmpl;
    let mut t = cx.exprs[var as usize].first;
    while t != NONE {
        if cx.find_template(cx.exprs[t as usize].data) == Some(tmpl) {
            return true;
        }
        t = cx.exprs[t as usize].next;
    }
    false
}

/// Where the walk over one template stands: the fact just visited and the fact
/// counter before its actions ran.
#[derive(Clone, Copy)]
struct Resume {
    fact: FactRef,
    counter: u32,
}

/// The next live fact of template `tmpl` (the first one when `after` is `None`).
///
/// CLIPS follows the visited fact's template-list link. If the actions retracted that
/// fact, its link stays frozen as it was at the retraction, so facts the actions
/// asserted after it (e.g. by `modify`) are not reached through it; we approximate the
/// retraction time by the start of the actions (`counter`). A fact that is still live
/// continues through its current link, so new facts join the iteration.
#[cfg_attr(feature = "host-speedups", inline(always))]
fn next_of_template(cx: &Core<'_>, tmpl: Ix, after: Option<Resume>) -> Option<Ix> {
    if cx.tmpl_mems[tmpl as usize].nfacts == 0 {
        return None;
    }
    // the host walks the template's own list (`TemplateMem::tfirst`), the image the list
    // of all facts
    #[cfg(feature = "host-speedups")]
    let (head, link) = (cx.tmpl_mems[tmpl as usize].tfirst, |f: Ix| {
        cx.fact_tlinks[f as usize][0]
    });
    #[cfg(not(feature = "host-speedups"))]
    let (head, link) = (cx.st.facts.fact_head, |f: Ix| cx.facts[f as usize].next);
    let (mut f, lo, hi) = match after {
        None => (head, None, u32::MAX),
        // fast path: still linked, continue from its successor
        Some(r) if cx.fact_alive(r.fact) => (link(r.fact.slot), None, u32::MAX),
        Some(r) => (head, Some(r.fact.num), r.counter),
    };
    if lo.is_none() && hi == u32::MAX {
        // the usual case: the next fact of the template, no number bounds to check
        while f != NONE {
            let fact = &cx.facts[f as usize];
            if fact.tmpl == tmpl {
                return Some(f);
            }
            f = link(f);
        }
        return None;
    }
    while f != NONE {
        let fact = &cx.facts[f as usize];
        if fact.num >= hi {
            return None;
        }
        if lo.is_none_or(|n| fact.num > n) && fact.tmpl == tmpl {
            return Some(f);
        }
        f = link(f);
    }
    None
}

/// Sets the frame slot of query variable `k` to fact slot `f`.
#[cfg_attr(feature = "host-speedups", inline(always))]
fn bind(cx: &mut Core<'_>, w: &mut Walk, k: usize, f: Ix) {
    let r = cx.fact_ref(f);
    w.cursor[k] = r;
    let at = (cx.st.frame.bp + cx.exprs[w.q.vars[k] as usize].data) as usize;
    cx.stack[at] = Value::Fact(r);
}

/// Re-binds variables `0..k` (actions of an inner tuple may have bound other values
/// to the same frame slots through nested queries).
#[cfg_attr(feature = "host-speedups", inline(always))]
fn rebind_outer(cx: &mut Core<'_>, w: &Walk, k: usize) {
    for (i, &var) in w.q.vars[..k].iter().enumerate() {
        let at = (cx.st.frame.bp + cx.exprs[var as usize].data) as usize;
        cx.stack[at] = Value::Fact(w.cursor[i]);
    }
}

/// The template a query variable's template-name node `tnode` names, remembered in
/// the node's `aux` (index + 1) and checked against the name on every use, so a
/// redefinition or `clear` cannot make it stale.
fn template_of(cx: &mut Core<'_>, tnode: Ix) -> Option<Ix> {
    let x = cx.exprs[tnode as usize];
    let cached = Ix::from(x.aux);
    if cached != 0
        && cached <= cx.st.pools.ntemplates
        && cx.templates[cached as usize - 1].name == x.data
    {
        return Some(cached - 1);
    }
    let t = cx.find_template(x.data)?;
    // (a compiled rule base's nodes read in place keep no cache)
    if t < Ix::from(u8::MAX) && cx.exprs.writable(tnode as usize) {
        cx.exprs[tnode as usize].aux = t as u8 + 1;
    }
    Some(t)
}

/// Template `at` (0-based) of a restriction written as an expression, which CLIPS
/// evaluates each time the query runs: a symbol, or a multifield of symbols, each
/// naming a deftemplate; `None` past the last. Anything else is CLIPS's `[PRNTUTIL2]`
/// (after `[PRNTUTIL1]` for a symbol naming none), which ends the query with an error.
/// Host only (`extras`): the image's rules name their templates.
#[cfg(feature = "extras")]
fn dynamic_template_at(
    cx: &mut Core<'_>,
    tnode: Ix,
    at: usize,
    func: &str,
) -> Result<Option<Ix>, EvalError> {
    let mark = cx.st.frame.scratch_top;
    let v = cx.eval(tnode);
    let item = match v {
        Err(e) => {
            release_scratch(cx, mark);
            return Err(e);
        }
        Ok(Value::Multi(m)) if at < m.len as usize => cx.mf_item(m, at),
        Ok(Value::Multi(m))
            if (0..m.len as usize).all(
                |i| matches!(cx.mf_item(m, i), Value::Sym(s) if cx.find_template(s).is_some()),
            ) =>
        {
            release_scratch(cx, mark);
            return Ok(None);
        }
        Ok(Value::Multi(m)) => (0..m.len as usize)
            .map(|i| cx.mf_item(m, i))
            .find(|v| !matches!(*v, Value::Sym(s) if cx.find_template(s).is_some()))
            .unwrap_or(Value::Void),
        Ok(v) if at == 0 => v,
        Ok(_) => {
            release_scratch(cx, mark);
            return Ok(None);
        }
    };
    release_scratch(cx, mark);
    let bad = match item {
        Value::Sym(s) => match cx.find_template(s) {
            Some(t) => return Ok(Some(t)),
            None => Some(s),
        },
        _ => None,
    };
    let mut b: crate::value::TextBuf<200> = crate::value::TextBuf::new();
    if let Some(s) = bad {
        let _ = core::fmt::Write::write_fmt(
            &mut b,
            format_args!(
                "[PRNTUTIL1] Unable to find deftemplate {} in function {func}.\n",
                cx.sym_text(s)
            ),
        );
    }
    let _ = core::fmt::Write::write_str(
        &mut b,
        "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for fact-set query class restrictions.\n",
    );
    cx.write(crate::host::router::WERROR, b.as_str());
    Err(EvalError::already_reported())
}

/// The query function a walk runs, for its error messages (told apart by what it does
/// with the tuples; delayed-do-for-all-facts walks as find-all-facts does).
#[cfg(feature = "extras")]
fn walk_func(w: &Walk) -> &'static str {
    match (w.mode, w.collect, w.act) {
        (Mode::First, false, false) => "any-factp",
        (Mode::First, true, _) => "find-fact",
        (Mode::First, false, true) => "do-for-fact",
        (Mode::All, true, _) => "find-all-facts",
        (Mode::All, false, _) => "do-for-all-facts",
    }
}

/// Checks the restrictions written as expressions before any tuple is visited, as
/// CLIPS does (each name of each one); `call` is the query's call node, which names
/// the function for the error messages.
#[cfg(feature = "extras")]
#[cold]
fn check_dynamic(cx: &mut Core<'_>, q: &Query, call: Ix) -> Result<(), EvalError> {
    let func = super::get(cx.exprs[call as usize].data).name;
    for &var in &q.vars[..q.nvars] {
        let mut t = cx.exprs[var as usize].first;
        while t != NONE {
            if cx.exprs[t as usize].op != crate::expr::Op::Sym {
                let mut at = 0;
                while dynamic_template_at(cx, t, at, func)?.is_some() {
                    at += 1;
                }
            }
            t = cx.exprs[t as usize].next;
        }
    }
    Ok(())
}

/// A query test that compares one slot of the innermost variable's fact with a
/// constant, a local or a global (`(= ?m:index ?i)`, `(eq ?p:name ?from)`): such a
/// test has no side effects, so the walk decides it in place for each fact and
/// binds only the facts that pass. A fact it cannot decide (a multifield value, a
/// non-number for `=`, which the builtin reports) goes to the evaluator.
#[derive(Clone, Copy)]
struct SlotTest {
    /// Comparison builtin id (`basic::CMP_FIRST..=CMP_LAST`).
    cmp: Ix,
    /// The name of the slot the `QSlot` operand reads.
    name: crate::value::SymId,
    /// The other operand (a leaf node), and whether the slot is the first argument.
    other: Ix,
    slot_first: bool,
}

impl SlotTest {
    /// The slot test of query test `test` on the variable in frame slot `frame`, if
    /// the test has that shape. (Inlined into both copies of `walk` on the host, as it
    /// was into the one: the call costs more than the inlined code.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn of(cx: &Core<'_>, test: Ix, frame: Ix) -> Option<SlotTest> {
        use super::basic::{CMP_FIRST, CMP_LAST};
        use crate::expr::{FnKind, Op};
        let x = cx.exprs[test as usize];
        if x.op != Op::Call
            || x.aux != FnKind::Builtin as u8
            || !(CMP_FIRST..=CMP_LAST).contains(&x.data)
        {
            return None;
        }
        let a = x.first;
        let b = if a == NONE {
            return None;
        } else {
            cx.exprs[a as usize].next
        };
        if b == NONE || cx.exprs[b as usize].next != NONE {
            return None;
        }
        let is_own_slot = |e: Ix| {
            let n = cx.exprs[e as usize];
            n.op == Op::QSlot && n.data == frame
        };
        let is_leaf = |e: Ix| {
            let n = cx.exprs[e as usize];
            match n.op {
                Op::Sym | Op::Str | Op::Int | Op::Float | Op::Global => true,
                // another frame slot: a local, or an outer query variable
                Op::Local => n.data != frame,
                _ => false,
            }
        };
        let (qslot, other, slot_first) = if is_own_slot(a) && is_leaf(b) {
            (a, b, true)
        } else if is_own_slot(b) && is_leaf(a) {
            (b, a, false)
        } else {
            return None;
        };
        Some(SlotTest {
            cmp: x.data,
            name: cx.exprs[cx.exprs[qslot as usize].first as usize].data,
            other,
            slot_first,
        })
    }

    /// Host: the slot test of query test `test`, known to have that shape
    /// (`classify_test`): of the two operands, the slot is the one `QSlot` node (the
    /// other, a leaf, is none).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn of_known(cx: &Core<'_>, test: Ix) -> SlotTest {
        let x = cx.exprs[test as usize];
        let a = x.first;
        let b = cx.exprs[a as usize].next;
        let slot_first = cx.exprs[a as usize].op == crate::expr::Op::QSlot;
        let (qslot, other) = if slot_first { (a, b) } else { (b, a) };
        SlotTest {
            cmp: x.data,
            name: cx.exprs[cx.exprs[qslot as usize].first as usize].data,
            other,
            slot_first,
        }
    }

    /// The test's result for live fact `f` of template `tmpl` whose slot `slot`
    /// it reads; None when the evaluator must decide.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn decide(&self, cx: &Core<'_>, f: Ix, slot: Ix) -> Option<bool> {
        let fact = &cx.facts[f as usize];
        if !fact.flat {
            return None;
        }
        let v = cx.values[(fact.start + slot) as usize];
        if v.is_multi() {
            return None;
        }
        let o = cx.exprs[self.other as usize];
        let w = match o.op {
            crate::expr::Op::Local => cx.stack[(cx.st.frame.bp + o.data) as usize],
            crate::expr::Op::Global => cx.globals[o.data as usize].value,
            _ => cx.const_value(self.other),
        };
        // an unbound variable: the evaluator reports it
        if matches!(w, Value::Void | Value::BoundVoid) {
            return None;
        }
        let (a, b) = if self.slot_first { (v, w) } else { (w, v) };
        super::basic::compare(cx, self.cmp, a, b)
    }
}

/// Host: most comparisons in one quick test (the conjuncts of an `and`).
#[cfg(feature = "host-speedups")]
const MAX_CONJ: usize = 4;

/// Host: how deep a hoisted operand's calls nest (`pure_value`).
#[cfg(feature = "host-speedups")]
const PURE_DEPTH: u8 = 4;

/// Host: a query test the walk decides in place for each fact of the innermost
/// variable, binding only the facts that pass: a two-argument comparison, or an `and`
/// of them, whose operands are the variable's own slots (read from the fact) or
/// operands without side effects that do not depend on the fact (`pure_value`:
/// constants, variables, other query variables' slots, `+ - * mod` of them). Such an
/// operand has the same value for every fact until something runs (the test's own
/// evaluation, or the actions): it is computed once and kept until then, where the
/// evaluator computed it for every fact. `and` stops at the first comparison that
/// fails, as the evaluator's does; anything the comparisons cannot decide (a
/// multifield, a non-number for `>`, an unbound variable, an error the evaluator
/// reports) goes to the evaluator for that fact.
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy)]
struct QuickTest {
    conj: [Cmp; MAX_CONJ],
    n: usize,
    /// The variable's frame slot.
    frame: Ix,
}

/// Host: one comparison of a `QuickTest`: builtin `cmp` of operand nodes `opnd`,
/// each the own variable's slot (`own`, by the name in the `QSlot` node) or not.
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy)]
struct Cmp {
    cmp: Ix,
    opnd: [Ix; 2],
    own: [bool; 2],
}

/// Host: a `QuickTest`'s slot indexes in one template, per comparison and operand.
#[cfg(feature = "host-speedups")]
type QuickSlots = [[Ix; 2]; MAX_CONJ];

/// Host: the operands a `QuickTest` computed (`Value::Void`: not yet, or again).
#[cfg(feature = "host-speedups")]
type QuickCache = [[Value; 2]; MAX_CONJ];

#[cfg(feature = "host-speedups")]
const AND_ID: Ix = super::builtin_id("and");
#[cfg(feature = "host-speedups")]
const MOD_ID: Ix = super::builtin_id("mod");

/// Host: does operand `e` have a shape `pure_value` can compute (for variable frame
/// slot `own`, which it must not read)?
#[cfg(feature = "host-speedups")]
fn pure_shape(cx: &Core<'_>, e: Ix, own: Ix, depth: u8) -> bool {
    use crate::expr::{FnKind, Op};
    let x = cx.exprs[e as usize];
    match x.op {
        Op::Int | Op::Float | Op::Sym | Op::Str | Op::Global | Op::PatVar => true,
        Op::Local | Op::QSlot => x.data != own,
        Op::Call if depth > 0 && x.aux == FnKind::Builtin as u8 => {
            if x.data.wrapping_sub(super::basic::ARITH_FIRST) >= 3 && x.data != MOD_ID {
                return false;
            }
            let a = x.first;
            if a == NONE {
                return false;
            }
            let b = cx.exprs[a as usize].next;
            b != NONE
                && cx.exprs[b as usize].next == NONE
                && pure_shape(cx, a, own, depth - 1)
                && pure_shape(cx, b, own, depth - 1)
        }
        _ => false,
    }
}

/// Host: the value of operand `e` of `pure_shape`, computed without side effects as
/// the evaluator would compute it; None where the evaluator could fail or report
/// (an unbound variable, a non-number for arithmetic, `mod` by zero) or has work
/// this does not do (a multifield, floats for `mod`).
#[cfg(feature = "host-speedups")]
fn pure_value(cx: &Core<'_>, e: Ix, own: Ix) -> Option<Value> {
    let x = cx.exprs[e as usize];
    if x.op != crate::expr::Op::Call {
        return cx.pure_leaf(e, own);
    }
    let a = x.first;
    let p = pure_value(cx, a, own)?;
    let q = pure_value(cx, cx.exprs[a as usize].next, own)?;
    if x.data == MOD_ID {
        return match (p, q) {
            (Value::Int(p), Value::Int(q)) if q != 0 => Some(Value::Int(p.wrapping_rem(q))),
            _ => None,
        };
    }
    match (p, q) {
        (Value::Int(_) | Value::Float(_), Value::Int(_) | Value::Float(_)) => {
            Some(super::basic::num_arith(x.data, p, q))
        }
        _ => None,
    }
}

#[cfg(feature = "host-speedups")]
impl QuickTest {
    /// The quick test of query test `test` on the variable in frame slot `frame`, if
    /// the test has that shape.
    fn of(cx: &Core<'_>, test: Ix, frame: Ix) -> Option<QuickTest> {
        use crate::expr::{FnKind, Op};
        let x = cx.exprs[test as usize];
        // (most tests of other shapes end here, before the work below)
        if x.op != Op::Call && x.op != Op::And {
            return None;
        }
        let mut q = QuickTest {
            conj: [Cmp {
                cmp: 0,
                opnd: [NONE; 2],
                own: [false; 2],
            }; MAX_CONJ],
            n: 0,
            frame,
        };
        let is_and = x.op == Op::And
            || (x.op == Op::Call && x.aux == FnKind::Builtin as u8 && x.data == AND_ID);
        let mut c = if is_and { x.first } else { test };
        while c != NONE {
            if q.n == MAX_CONJ {
                return None;
            }
            q.conj[q.n] = Self::comparison(cx, c, frame)?;
            q.n += 1;
            c = if is_and {
                cx.exprs[c as usize].next
            } else {
                NONE
            };
        }
        (q.n > 0).then_some(q)
    }

    /// Comparison `c` as a `Cmp`, if it has that shape.
    fn comparison(cx: &Core<'_>, c: Ix, frame: Ix) -> Option<Cmp> {
        use super::basic::{CMP_FIRST, CMP_LAST};
        use crate::expr::{FnKind, Op};
        let x = cx.exprs[c as usize];
        if x.op != Op::Call
            || x.aux != FnKind::Builtin as u8
            || !(CMP_FIRST..=CMP_LAST).contains(&x.data)
            || x.first == NONE
        {
            return None;
        }
        let a = x.first;
        let b = cx.exprs[a as usize].next;
        if b == NONE || cx.exprs[b as usize].next != NONE {
            return None;
        }
        let mut out = Cmp {
            cmp: x.data,
            opnd: [a, b],
            own: [false; 2],
        };
        for j in 0..2 {
            let n = cx.exprs[out.opnd[j] as usize];
            out.own[j] = n.op == Op::QSlot && n.data == frame;
            if !out.own[j] && !pure_shape(cx, out.opnd[j], frame, PURE_DEPTH) {
                return None;
            }
        }
        Some(out)
    }

    /// The slots the test reads in template `tmpl`; None (the evaluator decides, and
    /// reports an unknown slot) for one it lacks or an implied template.
    fn slots_in(&self, cx: &Core<'_>, tmpl: Ix) -> Option<QuickSlots> {
        if cx.templates[tmpl as usize].implied {
            return None;
        }
        let mut s = [[0; 2]; MAX_CONJ];
        for (c, si) in self.conj[..self.n].iter().zip(s.iter_mut()) {
            for (j, slot) in si.iter_mut().enumerate() {
                if c.own[j] {
                    let name = cx.exprs[cx.exprs[c.opnd[j] as usize].first as usize].data;
                    *slot = cx.find_slot(tmpl, name)?;
                }
            }
        }
        Some(s)
    }

    /// The test's result for live fact `f` (slots `slots` of its template); None when
    /// the evaluator must decide. Computes the operands not yet in `cache`.
    #[inline(always)]
    fn decide(
        &self,
        cx: &Core<'_>,
        f: Ix,
        slots: &QuickSlots,
        cache: &mut QuickCache,
    ) -> Option<bool> {
        let fact = &cx.facts[f as usize];
        if !fact.flat {
            return None;
        }
        for (i, c) in self.conj[..self.n].iter().enumerate() {
            let mut v = [Value::Void; 2];
            for j in 0..2 {
                v[j] = if c.own[j] {
                    let x = cx.values[(fact.start + slots[i][j]) as usize];
                    if x.is_multi() {
                        return None;
                    }
                    x
                } else {
                    if matches!(cache[i][j], Value::Void) {
                        cache[i][j] = pure_value(cx, c.opnd[j], self.frame)?;
                    }
                    cache[i][j]
                };
            }
            if !super::basic::compare(cx, c.cmp, v[0], v[1])? {
                return Some(false);
            }
        }
        Some(true)
    }
}

/// The parser's mark on a query's declarations node (`aux`): a restriction is written
/// as an expression.
#[cfg(feature = "extras")]
const DYNAMIC_MARK: u8 = 1;

/// Host: the shape of a query's test for its innermost variable, kept in bits 1-2
/// of the declarations node's `aux` once known (0: not yet), so that a call node
/// classifies its test once, not on every call: a `SlotTest`, another `QuickTest`,
/// or neither.
#[cfg(feature = "host-speedups")]
const SHAPE_SLOT: u8 = 1 << 1;
#[cfg(feature = "host-speedups")]
const SHAPE_QUICK: u8 = 2 << 1;
#[cfg(feature = "host-speedups")]
const SHAPE_NONE: u8 = 3 << 1;
#[cfg(feature = "host-speedups")]
pub(crate) const SHAPE_MASK: u8 = 3 << 1;

/// Host: the shape of query `q`'s test (call node `call`), classified on its first
/// call. The nodes a shape depends on (the test's, the variables' frame slots) do
/// not change while the call node lives; a reused node starts again from 0.
#[cfg(feature = "host-speedups")]
#[inline(never)]
fn classify_test(cx: &mut Core<'_>, call: Ix, q: &Query) -> u8 {
    let decl = cx.exprs[call as usize].first;
    let frame = cx.exprs[q.vars[q.nvars - 1] as usize].data;
    let s = if SlotTest::of(cx, q.test, frame).is_some() {
        SHAPE_SLOT
    } else if QuickTest::of(cx, q.test, frame).is_some() {
        SHAPE_QUICK
    } else {
        SHAPE_NONE
    };
    // (a compiled rule base's nodes read in place keep no shape: classified per call)
    if cx.exprs.writable(decl as usize) {
        cx.exprs[decl as usize].aux |= s;
    }
    s
}

/// Walks the tuples of variables `k..`; returns true to stop the whole walk.
/// `DYNAMIC`: a restriction of the query is an expression (only then does the walk
/// look for one; the copy for queries that name their templates has no such test).
/// `MULTI` (host): the innermost variable's walk with a `QuickTest` (a copy of its
/// own, so that the others' loop pays nothing for it).
fn walk<const DYNAMIC: bool, const MULTI: bool>(
    cx: &mut Core<'_>,
    w: &mut Walk,
    k: usize,
) -> Result<bool, EvalError> {
    let var = w.q.vars[k];
    // the innermost variable's facts that fail a slot test are skipped in place
    let quick = if !MULTI && k + 1 == w.q.nvars {
        // host: a test of another shape the walk can decide goes to the copy of
        // `walk` with a `QuickTest` (the slot test, the commonest, keeps its own
        // cheaper path); the shape is known once per call node (`classify_test`)
        #[cfg(feature = "host-speedups")]
        match w.shape {
            SHAPE_SLOT => Some(SlotTest::of_known(cx, w.q.test)),
            SHAPE_QUICK => return walk::<DYNAMIC, true>(cx, w, k),
            _ => None,
        }
        #[cfg(not(feature = "host-speedups"))]
        SlotTest::of(cx, w.q.test, cx.exprs[var as usize].data)
    } else {
        None
    };
    #[cfg(feature = "host-speedups")]
    let quick_multi = if MULTI {
        QuickTest::of(cx, w.q.test, cx.exprs[var as usize].data)
    } else {
        None
    };
    // the quick test's operands computed so far (none after a visit: the test's
    // evaluation or the actions may have changed what they read)
    #[cfg(feature = "host-speedups")]
    let mut cache: QuickCache = [[Value::Void; 2]; MAX_CONJ];
    let mut tnode = cx.exprs[var as usize].first;
    // the next template of a restriction written as an expression
    #[cfg(feature = "extras")]
    let mut dyn_at = 0usize;
    while tnode != NONE {
        #[cfg(feature = "extras")]
        let tmpl = if DYNAMIC && cx.exprs[tnode as usize].op != crate::expr::Op::Sym {
            match dynamic_template_at(cx, tnode, dyn_at, walk_func(w))? {
                Some(t) => {
                    dyn_at += 1;
                    Some(t)
                }
                None => {
                    dyn_at = 0;
                    tnode = cx.exprs[tnode as usize].next;
                    continue;
                }
            }
        } else {
            let t = template_of(cx, tnode);
            tnode = cx.exprs[tnode as usize].next;
            t
        };
        #[cfg(not(feature = "extras"))]
        let tmpl = {
            let t = template_of(cx, tnode);
            tnode = cx.exprs[tnode as usize].next;
            t
        };
        let Some(tmpl) = tmpl else { continue };
        // the slot the quick test reads in this template (none: the evaluator
        // reports the unknown slot)
        let quick_slot = match quick {
            Some(q) if !cx.templates[tmpl as usize].implied => {
                cx.find_slot(tmpl, q.name).map(|s| (q, s))
            }
            _ => None,
        };
        #[cfg(feature = "host-speedups")]
        let multi_slots = match &quick_multi {
            Some(q) => q.slots_in(cx, tmpl),
            None => None,
        };
        let mut prev: Option<Resume> = None;
        while let Some(f) = next_of_template(cx, tmpl, prev) {
            debug_assert!(DYNAMIC || fact_fits(cx, var, f));
            // (an outer variable the test may read is bound again first)
            rebind_outer(cx, w, k);
            let decided = quick_slot.and_then(|(q, slot)| q.decide(cx, f, slot));
            #[cfg(feature = "host-speedups")]
            let decided = match (&quick_multi, &multi_slots) {
                (Some(q), Some(slots)) => q.decide(cx, f, slots, &mut cache),
                _ => decided,
            };
            if decided == Some(false) {
                // as after a visit whose test failed: nothing ran, nothing to stop for
                prev = Some(Resume {
                    fact: cx.fact_ref(f),
                    counter: cx.st.facts.next_fact_num,
                });
                continue;
            }
            bind(cx, w, k, f);
            // (a tuple the quick test passed, without actions, runs nothing)
            #[cfg(feature = "host-speedups")]
            if quick_multi.is_some() && (decided != Some(true) || (w.act && w.q.actions != NONE)) {
                cache = [[Value::Void; 2]; MAX_CONJ];
            }
            prev = Some(Resume {
                fact: w.cursor[k],
                counter: cx.st.facts.next_fact_num,
            });
            let stop = if k + 1 < w.q.nvars {
                walk::<DYNAMIC, false>(cx, w, k + 1)?
            } else {
                let stop = visit(cx, w, decided == Some(true))?;
                if w.hold_top && cx.st.facts.pending != NONE {
                    release_held(cx, &w.cursor[..w.q.nvars], 0..0);
                }
                stop
            };
            if stop || cx.st.eval.returning || cx.st.eval.breaking || cx.st.halt_now() {
                return Ok(true);
            }
        }
    }
    Ok(false)
}

/// Tests the query for the bound tuple (unless `passed`: a slot test decided it) and
/// acts on a match; true to stop.
#[cfg_attr(feature = "host-speedups", inline(always))]
fn visit(cx: &mut Core<'_>, w: &mut Walk, passed: bool) -> Result<bool, EvalError> {
    // a test or actions that modify the facts walked can make the walk endless (each
    // modify puts a fact at the end): the host may stop it, as it stops loops
    if !passed || (w.act && w.q.actions != NONE) {
        cx.poll_interrupt()?;
    }
    if !passed {
        let mark = cx.st.frame.scratch_top;
        let ok = Core::is_true(cx.eval(w.q.test)?);
        // the query's temporaries are dead; keep a collected result contiguous
        release_scratch(cx, mark);
        if !ok {
            // an error in the test (an unbound variable read as FALSE) ends the query
            return Ok(cx.st.mode.halting);
        }
    }
    w.found = true;
    if w.collect {
        for i in 0..w.q.nvars {
            cx.multi_push(Value::Fact(w.cursor[i]))?;
        }
    }
    if w.act {
        if w.mode == Mode::All && matches!(w.last, Value::Multi(_)) {
            w.last = Value::Sym(SYM_FALSE);
            release_scratch(cx, w.base);
        }
        let mark = cx.st.frame.scratch_top;
        w.last = if w.q.actions == NONE {
            Value::Sym(SYM_FALSE)
        } else {
            cx.eval_chain(w.q.actions)?
        };
        // an error in the actions (CLIPS's evaluation error) makes the query FALSE
        if cx.st.mode.halting {
            w.last = Value::Sym(SYM_FALSE);
        }
        if w.mode == Mode::All {
            release_scratch_keeping(cx, mark, &mut w.last);
        }
    }
    Ok(w.mode == Mode::First)
}

/// Frees the pending facts (all retracted by the running top-level query) but those
/// in `keep` or among the values in scratch cells `vals`: CLIPS keeps a retracted fact readable
/// while a query variable is bound to it, and only that long, so a query retracting
/// many facts holds no more cells than a few tuples take.
fn release_held(cx: &mut Core<'_>, keep: &[FactRef], vals: core::ops::Range<usize>) {
    let mut p = core::mem::replace(&mut cx.st.facts.pending, NONE);
    while p != NONE {
        let f = cx.facts[p as usize];
        let named = |v: &Value| matches!(*v, Value::Fact(x) if x.slot == p);
        if keep.iter().any(|k| k.slot == p) || cx.scratch[vals.clone()].iter().any(named) {
            cx.facts[p as usize].next = cx.st.facts.pending;
            cx.st.facts.pending = p;
        } else {
            cx.free_fact_slot(p);
        }
        p = f.next;
    }
}

/// Starts holding retracted facts (see `Core::query_hold`): the value to restore,
/// and whether this is the outermost query outside a firing (it frees what is still
/// held at the end).
fn hold_begin(cx: &mut Core<'_>) -> (u16, bool) {
    let saved = cx.st.eval.query_hold;
    if cx.st.mode.firing {
        return (saved, false);
    }
    cx.st.eval.query_hold = saved.saturating_add(1);
    // (a command at the prompt holds what it retracts too: the query frees it)
    (saved, saved & !crate::engine::COMMAND_HOLD == 0)
}

fn hold_end(cx: &mut Core<'_>, (saved, top): (u16, bool)) {
    // restored, not decremented
    cx.st.eval.query_hold = saved;
    if top {
        cx.free_pending();
    }
}

fn run(
    cx: &mut Core<'_>,
    call: Ix,
    mode: Mode,
    collect: bool,
    act: bool,
) -> Result<Walk, EvalError> {
    let q = parse(cx, call)?;
    let mut w = Walk {
        q,
        mode,
        cursor: [FactRef { slot: NONE, num: 0 }; MAX_VARS],
        collect,
        act,
        found: false,
        last: Value::Sym(SYM_FALSE),
        base: cx.st.frame.scratch_top,
        hold_top: false,
        #[cfg(feature = "host-speedups")]
        shape: SHAPE_NONE,
    };
    // while CLIPS halts, a query tests no fact set: nothing found, no action run
    if cx.st.mode.halting {
        return Ok(w);
    }
    // a restriction written as an expression (the parser marks the declarations)
    #[cfg(any(feature = "extras", feature = "host-speedups"))]
    let flags = cx.exprs[cx.exprs[call as usize].first as usize].aux;
    #[cfg(feature = "extras")]
    let dynamic = flags & DYNAMIC_MARK != 0;
    #[cfg(feature = "host-speedups")]
    {
        w.shape = flags & SHAPE_MASK;
        if w.shape == 0 {
            w.shape = classify_test(cx, call, &w.q);
        }
    }
    #[cfg(feature = "extras")]
    if dynamic {
        check_dynamic(cx, &w.q, call)?;
    }
    // outside a firing, retracted facts stay readable (`hold_begin`)
    let hold = hold_begin(cx);
    w.hold_top = hold.1;
    #[cfg(feature = "extras")]
    let r = if dynamic {
        walk::<true, false>(cx, &mut w, 0)
    } else {
        walk::<false, false>(cx, &mut w, 0)
    };
    #[cfg(not(feature = "extras"))]
    let r = walk::<false, false>(cx, &mut w, 0);
    hold_end(cx, hold);
    r.map(|_| w)
}

fn any_factp(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let w = run(cx, call, Mode::First, false, false)?;
    Ok(Core::bool_value(w.found))
}

fn find_fact(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    run(cx, call, Mode::First, true, false)?;
    Ok(cx.multi_finish(start))
}

/// All matching tuples, flattened: `(<Fact-1> <Fact-2> <Fact-3> <Fact-2>)`.
fn find_all_facts(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    run(cx, call, Mode::All, true, false)?;
    Ok(cx.multi_finish(start))
}

/// The value of the last action for the first matching tuple, FALSE without a match.
fn do_for_fact(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    Ok(run(cx, call, Mode::First, false, true)?.last)
}

/// The value of the last action of the last matching tuple, FALSE without a match.
fn do_for_all_facts(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    Ok(run(cx, call, Mode::All, false, true)?.last)
}

/// Finds every matching tuple first, then runs the actions for each of them, even for
/// facts the actions retracted meanwhile (as CLIPS 6.30 does). The value of the last
/// action of the last tuple, FALSE without a match.
fn delayed_do_for_all_facts(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let hold = hold_begin(cx);
    let r = delayed(cx, call, hold.1);
    hold_end(cx, hold);
    r
}

fn delayed(cx: &mut Core<'_>, call: Ix, top: bool) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    let w = run(cx, call, Mode::All, true, false)?;
    let tuples = match cx.multi_finish(start) {
        Value::Multi(m) => m,
        _ => return Ok(Value::Sym(SYM_FALSE)),
    };
    let n = w.q.nvars;
    let mut last = Value::Sym(SYM_FALSE);
    // each tuple's value supersedes the one before: its cells go down to here
    let base = cx.st.frame.scratch_top;
    let mut t = 0;
    while t + n <= tuples.len as usize {
        for k in 0..n {
            let at = (cx.st.frame.bp + cx.exprs[w.q.vars[k] as usize].data) as usize;
            cx.stack[at] = cx.mf_item(tuples, t + k);
        }
        if matches!(last, Value::Multi(_)) {
            release_scratch(cx, base);
        }
        let mark = cx.st.frame.scratch_top;
        last = if w.q.actions == NONE {
            Value::Sym(SYM_FALSE)
        } else {
            cx.eval_chain(w.q.actions)?
        };
        release_scratch_keeping(cx, mark, &mut last);
        if top && cx.st.facts.pending != NONE && cx.fact_slots_full() {
            // the tuples still to come may name a fact retracted now; freed only when
            // the slots are needed, as the check scans those tuples (per tuple, it
            // made a query retracting all its facts quadratic)
            let (s, e) = (tuples.start as usize, (tuples.start + tuples.len) as usize);
            release_held(cx, &[], (s + t + n).min(e)..e);
        }
        if cx.st.eval.returning || cx.st.eval.breaking || cx.st.halt_now() {
            break;
        }
        t += n;
    }
    Ok(last)
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;

    const MACHINES: &str = "(deftemplate machine (slot name) (slot state) (slot load (default 0)))
(assert (machine (name m1) (state idle) (load 3)))
(assert (machine (name m2) (state busy) (load 7)))
(assert (machine (name m3) (state idle) (load 1)))
";

    /// Output lines of `queries` run after MACHINES (skipping the three assert results).
    fn lines_after_setup(queries: &str) -> std::vec::Vec<std::string::String> {
        let out = run_program(&std::format!("{MACHINES}{queries}"));
        out.lines().skip(3).map(std::string::String::from).collect()
    }

    #[test]
    fn any_find_and_find_all() {
        // tests/clips/056 as printed by CLIPS 6.30
        let got = lines_after_setup(
            "(any-factp ((?m machine)) (eq ?m:state busy))
(any-factp ((?m machine)) (eq ?m:state broken))
(find-fact ((?m machine)) (eq ?m:state idle))
(find-fact ((?m machine)) (> ?m:load 100))
(find-all-facts ((?m machine)) (eq ?m:state idle))
(find-all-facts ((?m machine)) TRUE)
(length$ (find-all-facts ((?m machine)) (< ?m:load 5)))
(any-factp ((?a machine) (?b machine)) (and (neq ?a ?b) (eq ?a:state ?b:state)))
(find-all-facts ((?a machine) (?b machine)) (and (eq ?a:state idle) (eq ?b:state busy)))
",
        );
        assert_eq!(
            got,
            [
                "TRUE",
                "FALSE",
                "(<Fact-1>)",
                "()",
                "(<Fact-1> <Fact-3>)",
                "(<Fact-1> <Fact-2> <Fact-3>)",
                "2",
                "TRUE",
                "(<Fact-1> <Fact-2> <Fact-3> <Fact-2>)",
            ]
        );
    }

    #[test]
    fn order_first_variable_slowest_templates_as_written() {
        let out = run_program(
            "(deftemplate a (slot x))
(deftemplate b (slot y))
(assert (a (x 1)) (b (y 2)) (a (x 3)) (b (y 4)))
(do-for-all-facts ((?f b a)) TRUE (printout t ?f crlf) 8)
(find-all-facts ((?f a) (?g b)) TRUE)
(do-for-fact ((?f a b)) TRUE 7)
(do-for-fact ((?f b a)) FALSE 8)
(do-for-all-facts ((?f a)) TRUE)
",
        );
        let want = "<Fact-4>
<Fact-2>
<Fact-4>
<Fact-1>
<Fact-3>
8
(<Fact-1> <Fact-2> <Fact-1> <Fact-4> <Fact-3> <Fact-2> <Fact-3> <Fact-4>)
7
FALSE
FALSE
";
        assert_eq!(out, want);
    }

    #[test]
    fn actions_may_retract_and_modify() {
        // tests/clips/057: modify inside do-for-fact, retract inside do-for-all-facts
        let out = run_program(
            "(deftemplate task (slot id) (slot prio) (slot done (default no)))
(assert (task (id t1) (prio 2)))
(assert (task (id t2) (prio 5)))
(assert (task (id t3) (prio 1)))
(do-for-fact ((?t task)) (> ?t:prio 1) (printout t \"first match \" ?t:id crlf))
(do-for-fact ((?t task)) (> ?t:prio 4) (modify ?t (done yes)))
(do-for-all-facts ((?t task)) (eq ?t:done no) (retract ?t))
(find-all-facts ((?t task)) TRUE)
(do-for-all-facts ((?t task)) TRUE (printout t ?t:id \" \" ?t:done crlf))
",
        );
        assert!(out.contains("first match t1\n"), "{out}");
        assert!(out.contains("(<Fact-4>)\n"), "{out}");
        assert!(out.ends_with("t2 yes\n"), "{out}");
    }

    #[test]
    fn modify_during_do_for_all_facts_follows_clips_links() {
        // CLIPS 6.30: the modified copy of the LAST fact is not reached any more, so the
        // walk ends with f-10 = (c 1) instead of counting every value down to 0.
        let out = run_program(
            "(deftemplate p (slot n) (slot v))
(deftemplate q (slot n))
(assert (p (n a) (v 1)) (q (n x)) (p (n b) (v 2)) (q (n y)) (p (n c) (v 3)))
(do-for-all-facts ((?x p)) (= ?x:v 1) (retract 3))
(do-for-all-facts ((?x p)) TRUE (assert (q (n ?x:n))))
(do-for-all-facts ((?x p)) (> ?x:v 0) (modify ?x (v (- ?x:v 1))))
(find-all-facts ((?x p)) TRUE)
",
        );
        assert!(out.ends_with("<Fact-10>\n(<Fact-8> <Fact-10>)\n"), "{out}");
    }

    #[test]
    fn delayed_variant_collects_first() {
        // assertions made by the actions do not join the iteration
        let out = run_program(
            "(deftemplate p (slot v))
(assert (p (v 1)) (p (v 2)) (p (v 3)))
(delayed-do-for-all-facts ((?x p)) (> ?x:v 1) (printout t ?x crlf) (assert (p (v (+ ?x:v 10)))))
(delayed-do-for-all-facts ((?x p)) FALSE 1)
(delayed-do-for-all-facts ((?x p)) (= ?x:v 1) 5)
",
        );
        assert_eq!(out, "<Fact-3>\n<Fact-2>\n<Fact-3>\n<Fact-5>\nFALSE\n5\n");
    }

    #[test]
    fn queries_in_rules_collect_multislots() {
        let out = run_program(
            "(deftemplate bag (multislot items))
(assert (bag (items a b)) (bag (items c)))
(defrule count => (bind ?n 0)
  (do-for-all-facts ((?b bag)) (> (length$ ?b:items) 0) (bind ?n (+ ?n (length$ ?b:items))))
  (printout t \"items \" ?n \" \" (find-all-facts ((?b bag)) (member$ c ?b:items)) crlf))
(run)
",
        );
        assert!(out.contains("items 3 (<Fact-2>)\n"), "{out}");
    }

    /// Each tuple's multifield value supersedes the one before, whose cells are freed:
    /// 60 tuples of 41 cells each would not fit the small engine's scratch at once.
    #[test]
    fn do_for_all_facts_frees_superseded_multifield_values() {
        let out = run_program(
            "(deftemplate p (slot v))
(defglobal ?*big* = (create$ 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20
                             21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 37 38 39 40))
(loop-for-count (?i 1 60) (assert (p (v ?i))))
(bind ?r (do-for-all-facts ((?x p)) TRUE (create$ ?*big* ?x:v)))
(printout t (length$ ?r) \" \" (nth$ 41 ?r) crlf)
(bind ?r (delayed-do-for-all-facts ((?x p)) TRUE (create$ ?*big* (* 2 ?x:v))))
(printout t (length$ ?r) \" \" (nth$ 41 ?r) crlf)
",
        );
        assert!(out.contains("\n41 60\n"), "{out}");
        assert!(out.ends_with("\n41 120\n"), "{out}");
    }
}
