//! Control forms (lazy builtins): progn, if, while, loop-for-count, progn$/foreach,
//! switch, bind, return, break.

use super::describe::OnError;
use super::{Builtin, ANY, SYM_FALSE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::expr::{FnKind, Op};
use crate::value::Ix;
use crate::value::{MfSpan, Value, NONE};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::lazy("progn", 0, ANY, progn).on_error(OnError::False),
    Builtin::lazy("if", 2, 3, if_),
    Builtin::lazy("while", 2, 2, while_).on_error(OnError::False),
    Builtin::lazy("loop-for-count", 4, 4, loop_for_count).on_error(OnError::False),
    Builtin::lazy("progn$", 3, 3, foreach).on_error(OnError::False),
    Builtin::lazy("foreach", 3, 3, foreach).on_error(OnError::False),
    Builtin::lazy("switch", 1, ANY, switch).on_error(OnError::False),
    Builtin::lazy("bind", 1, ANY, bind),
    Builtin::eager("return", 0, 1, return_),
    Builtin::eager("break", 0, 0, break_),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

fn kids<const N: usize>(cx: &Core<'_>, call: Ix) -> [Ix; N] {
    let mut out = [NONE; N];
    let mut c = cx.exprs[call as usize].first;
    for o in out.iter_mut() {
        if c == NONE {
            break;
        }
        *o = c;
        c = cx.exprs[c as usize].next;
    }
    out
}

fn progn(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let first = cx.exprs[call as usize].first;
    cx.eval_chain(first)
}

fn if_(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let [c, t, e] = kids::<3>(cx, call);
    // CLIPS goes on with a failed condition's error value (its evaluation error set:
    // a lone action still runs, `State::halting`)
    #[cfg(feature = "extras")]
    let cond = match cx.eval(c) {
        Ok(v) => v,
        Err(err) => cx.value_after_error(c, err)?,
    };
    #[cfg(not(feature = "extras"))]
    let cond = cx.eval(c)?;
    let p = if Core::is_true(cond) {
        t
    } else if e != NONE {
        e
    } else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    #[cfg(feature = "extras")]
    return branch(cx, p).map_err(|err| branch_failed(cx, p, err));
    #[cfg(not(feature = "extras"))]
    branch(cx, p)
}

/// An `if` branch `p` failed with `err`: CLIPS's `if` returns the value the branch
/// gave after its error, which the command line prints (`(if TRUE then (str-cat
/// (run)))` prints `""`), so its fallback becomes the `if`'s (`set_error_fallback`).
#[cfg(feature = "extras")]
#[cold]
#[inline(never)]
fn branch_failed(cx: &mut Core<'_>, p: Ix, err: EvalError) -> EvalError {
    let x = cx.exprs[p as usize];
    let progn = x.op == Op::Call && x.aux == FnKind::Builtin as u8 && x.data == super::ID_PROGN;
    let a = if progn && x.first != NONE && cx.exprs[x.first as usize].next == NONE {
        x.first
    } else {
        p
    };
    let depth = cx.st.eval.eval_depth;
    if let Some(v) = cx.fallback_after_error(a, &err) {
        cx.set_error_fallback(v, None);
    } else if let Some(mut fb) = cx.st.eval.error_fallback.filter(|fb| fb.depth == depth + 1) {
        fb.depth = depth;
        cx.st.eval.error_fallback = Some(fb);
    }
    err
}

/// An `if` branch, parsed as a progn of its actions. CLIPS keeps a progn only around
/// two or more, which is seen while it halts (`State::halting`): a lone action still
/// runs there, a progn does not.
fn branch(cx: &mut Core<'_>, p: Ix) -> Result<Value, EvalError> {
    let x = cx.exprs[p as usize];
    let progn = x.op == Op::Call && x.aux == FnKind::Builtin as u8 && x.data == super::ID_PROGN;
    if progn && x.first != NONE && cx.exprs[x.first as usize].next == NONE {
        return cx.eval(x.first);
    }
    cx.eval(p)
}

/// Frees the scratch above `mark` that nothing refers to any more: the multifields
/// the stack's variables (and a `return` value on its way out) still hold there are
/// slid down to `mark`, so a loop that rebinds a variable to a new multifield each time
/// holds one value's worth, not every iteration's. Only values built after `mark` sit
/// above it, and while the caller's code (a loop body, a query test) is done, only the
/// current frame's stack (`live_stack`) and the return value can hold them. Globals
/// need no look: their multifields live in their own region at the top of scratch
/// (`Core::set_global`).
#[cfg_attr(feature = "host-speedups", inline(always))]
pub(super) fn release_scratch(cx: &mut Core<'_>, mark: Ix) {
    // nothing above the mark (the usual loop body or query test): no call
    if cx.st.frame.scratch_top > mark {
        release_scratch_keeping(cx, mark, &mut Value::Void);
    }
}

/// The stack values that may hold multifields built above a mark taken while the
/// current frame runs: the frame's own (from `bp`) and what was pushed above it.
/// The frames below `bp` are its callers', which nothing running now can bind, and
/// whatever they held was built before the mark, below it.
fn live_stack<'a>(cx: &'a Core<'_>) -> &'a [Value] {
    let (bp, sp) = (cx.st.frame.bp as usize, cx.st.frame.sp as usize);
    &cx.stack[bp.min(sp)..sp]
}

/// `release_scratch` that also keeps multifield `keep` (a loop's last value), moved
/// down with the others.
/// Dead scratch cells below a loop's one live value that may stay until they are
/// reclaimed (see `release_scratch_keeping`).
const COMPACT_MIN: Ix = 64;

/// (Host: inlined into each loop, whose every iteration runs it; what moves cells is
/// out of line.)
#[cfg_attr(feature = "host-speedups", inline(always))]
pub(super) fn release_scratch_keeping(cx: &mut Core<'_>, mark: Ix, keep: &mut Value) {
    // nothing above the mark (the usual loop body or query test): nothing to scan for
    if cx.st.frame.scratch_top <= mark {
        return;
    }
    let top = cx.st.frame.scratch_top;
    // the usual cases in one look at the stack: nothing live above the mark (a loop
    // body's temporaries), or one value (a list a loop rebinds each time)
    // (a plain loop: this runs per loop iteration and query candidate)
    let mut one: Option<(Ix, Ix)> = None;
    let mut several = false;
    let mut note = |v: &Value| {
        if let Value::Multi(m) = *v {
            let (s, e) = (m.start, m.start + m.len);
            if m.len > 0 && e > mark && s < top {
                match one {
                    None => one = Some((s, e)),
                    Some(o) if o == (s, e) => {}
                    Some(_) => several = true,
                }
            }
        }
    };
    for v in live_stack(cx) {
        note(v);
    }
    if cx.st.eval.returning {
        note(&cx.st.eval.return_value);
    }
    note(keep);
    match one {
        None => cx.st.frame.scratch_top = mark,
        Some((s, e)) if !several => {
            // slide it down only once the dead cells below it are as many as its
            // own and at least `COMPACT_MIN`: a loop that rebinds a list each time
            // then copies it a bounded number of times per cell, not per iteration
            if s > mark && s - mark >= (e - s).max(COMPACT_MIN) {
                slide_down(cx, keep, (s, e), mark);
            } else {
                // it stays where it is (above the mark: with few dead cells below)
                cx.st.frame.scratch_top = e.max(mark).min(top);
            }
        }
        Some(_) => release_several(cx, mark, keep, top),
    }
}

/// Moves the one live run `s..e` of scratch down to `mark`, the top after it.
#[inline(never)]
fn slide_down(cx: &mut Core<'_>, keep: &mut Value, (s, e): (Ix, Ix), mark: Ix) {
    cx.scratch
        .copy_within(s as usize..e as usize, mark as usize);
    shift_spans(cx, keep, (s, e), s - mark);
    cx.st.frame.scratch_top = mark + (e - s);
}

/// `release_scratch_keeping` with several live values above `mark`: each run of
/// them moved down in turn.
#[inline(never)]
fn release_several(cx: &mut Core<'_>, mark: Ix, keep: &mut Value, top: Ix) {
    let mut dest = mark;
    // one run of overlapping live cells at a time, lowest first (values may share
    // cells: `(bind ?y ?x)`, a `rest$` of another)
    while let Some((s, mut e)) = lowest_live(cx, *keep, dest, top) {
        while let Some(b) = live_spans(cx, *keep)
            .filter(|&(a, b)| a < e && b > e)
            .map(|(_, b)| b)
            .max()
        {
            e = b;
        }
        if s > dest {
            cx.scratch
                .copy_within(s as usize..e as usize, dest as usize);
            shift_spans(cx, keep, (s, e), s - dest);
            dest += e - s;
        } else {
            // a run that starts at or below the mark stays where it is
            dest = dest.max(e);
        }
    }
    cx.st.frame.scratch_top = dest.min(top);
}

/// The multifields that may point into scratch temporaries (start, end): the stack's,
/// the value a `return` carries out and `keep`.
fn live_spans<'a>(cx: &'a Core<'_>, keep: Value) -> impl Iterator<Item = (Ix, Ix)> + 'a {
    let ret = if cx.st.eval.returning {
        Some(cx.st.eval.return_value)
    } else {
        None
    };
    live_stack(cx)
        .iter()
        .copied()
        .chain(ret)
        .chain(Some(keep))
        .filter_map(|v| match v {
            Value::Multi(m) if m.len > 0 => Some((m.start, m.start + m.len)),
            _ => None,
        })
}

/// The live cells starting lowest among those that end above `dest` and start below
/// `top` (the globals' region lies above it).
fn lowest_live(cx: &Core<'_>, keep: Value, dest: Ix, top: Ix) -> Option<(Ix, Ix)> {
    live_spans(cx, keep)
        .filter(|&(s, e)| e > dest && s < top)
        .min_by_key(|&(s, e)| (s, core::cmp::Reverse(e)))
}

/// Moves every multifield lying in cells `s..e` down by `by` (its cells were copied).
fn shift_spans(cx: &mut Core<'_>, keep: &mut Value, (s, e): (Ix, Ix), by: Ix) {
    let moved = |v: &mut Value| {
        if let Value::Multi(m) = v {
            if m.len > 0 && m.start >= s && m.start + m.len <= e {
                m.start -= by;
            }
        }
    };
    let (bp, sp) = (cx.st.frame.bp as usize, cx.st.frame.sp as usize);
    cx.stack[bp.min(sp)..sp].iter_mut().for_each(moved);
    if cx.st.eval.returning {
        moved(&mut cx.st.eval.return_value);
    }
    moved(keep);
}

fn while_(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let [c, body] = kids::<2>(cx, call);
    let mark = cx.st.frame.scratch_top;
    // while CLIPS halts (`State::halting`) loops run no iteration
    while !cx.st.mode.halting && Core::is_true(cx.eval(c)?) {
        cx.poll_interrupt()?;
        cx.eval(body)?;
        release_scratch(cx, mark);
        if cx.st.eval.breaking {
            cx.st.eval.breaking = false;
            break;
        }
        if cx.st.eval.returning || cx.st.mode.exit {
            break;
        }
    }
    Ok(Value::Sym(SYM_FALSE))
}

fn loop_for_count(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let [var, s, e, body] = kids::<4>(cx, call);
    // a limit read from an unbound variable (FALSE, halting) is no type error; a
    // float is truncated as CLIPS's C cast does (out of range: the smallest integer)
    let start = match cx.eval(s)? {
        Value::Int(i) => i,
        Value::Float(f) => super::math::c_trunc_to_i64(f),
        _ if cx.st.mode.halting => return Ok(Value::Sym(SYM_FALSE)),
        _ => return Err(EvalError::wrong_type("loop-for-count", 1, "integer")),
    };
    let end = match cx.eval(e)? {
        Value::Int(i) => i,
        Value::Float(f) => super::math::c_trunc_to_i64(f),
        _ if cx.st.mode.halting => return Ok(Value::Sym(SYM_FALSE)),
        _ => return Err(EvalError::wrong_type("loop-for-count", 2, "integer")),
    };
    let slot = if cx.exprs[var as usize].op == Op::Local {
        Some(cx.exprs[var as usize].data)
    } else {
        None
    };
    let mark = cx.st.frame.scratch_top;
    let mut i = start;
    while i <= end && !cx.st.mode.halting {
        if let Some(sl) = slot {
            let at = (cx.st.frame.bp + sl) as usize;
            cx.stack[at] = Value::Int(i);
        }
        cx.poll_interrupt()?;
        cx.eval(body)?;
        release_scratch(cx, mark);
        if cx.st.eval.breaking {
            cx.st.eval.breaking = false;
            break;
        }
        if cx.st.eval.returning || cx.st.mode.exit || i == end {
            break;
        }
        i += 1;
    }
    Ok(Value::Sym(SYM_FALSE))
}

fn foreach(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let [var, list, body] = kids::<3>(cx, call);
    let m = match cx.eval(list)? {
        Value::Multi(m) => m,
        // CLIPS's evaluation error set (an unbound global): FALSE, no iteration
        _ if cx.st.mode.halting => return Ok(Value::Sym(SYM_FALSE)),
        _ => return Err(EvalError::wrong_type("progn$", 1, "multifield")),
    };
    // a global's multifield is iterated as it was: the body may bind the global, which
    // repacks the globals' region under it (CLIPS keeps the old value alive too); an
    // empty one has no cells to keep (no iteration reads any)
    let m = if m.len > 0 && m.start >= cx.st.frame.scratch_top {
        let t = cx.scratch_alloc(m.len as usize)?;
        let s = m.start as usize;
        cx.scratch.copy_within(s..s + m.len as usize, t as usize);
        MfSpan {
            start: t,
            len: m.len,
        }
    } else {
        m
    };
    let slot = cx.exprs[var as usize].data;
    let mark = cx.st.frame.scratch_top;
    let mut last = Value::Sym(SYM_FALSE);
    for k in 0..m.len as usize {
        if cx.st.mode.halting {
            break;
        }
        let at = (cx.st.frame.bp + slot) as usize;
        cx.stack[at] = cx.scratch[m.start as usize + k];
        cx.stack[at + 1] = Value::Int(k as i64 + 1);
        cx.poll_interrupt()?;
        last = cx.eval(body)?;
        // the last iteration's value is progn$'s (a multifield too, as in CLIPS), so its
        // cells stay; earlier iterations' are freed, so a long loop holds one body's worth
        let done = k + 1 == m.len as usize || cx.st.eval.returning || cx.st.mode.exit;
        if done {
            release_scratch_keeping(cx, mark, &mut last);
        } else {
            release_scratch(cx, mark);
        }
        if cx.st.eval.breaking {
            // CLIPS's progn$ left by break has no value (loop-for-count's is FALSE)
            cx.st.eval.breaking = false;
            last = Value::Void;
            break;
        }
        if cx.st.eval.returning || cx.st.mode.exit {
            break;
        }
    }
    Ok(last)
}

fn switch(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    // while CLIPS halts (`State::halting`) a switch is FALSE
    if cx.st.mode.halting {
        return Ok(Value::Sym(SYM_FALSE));
    }
    let first = cx.exprs[call as usize].first;
    let v = cx.eval(first)?;
    let mut c = cx.exprs[first as usize].next;
    while c != NONE {
        let case = cx.exprs[c as usize];
        if case.aux == 1 {
            return cx.eval(case.first);
        }
        let cv = cx.eval(case.first)?;
        if super::basic::values_same(cx, v, cv) {
            let body = cx.exprs[case.first as usize].next;
            return cx.eval(body);
        }
        c = case.next;
    }
    Ok(Value::Sym(SYM_FALSE))
}

fn bind(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let target = cx.exprs[call as usize].first;
    let mut a = cx.exprs[target as usize].next;
    #[cfg(feature = "host-speedups")]
    if a != NONE && cx.exprs[a as usize].next == NONE {
        return bind_one(cx, target, a);
    }
    // several values (or one multifield expansion) make a multifield
    let mut n = 0;
    let mut only = Value::Void;
    let start = cx.multi_begin();
    let mut spliced = false;
    while a != NONE {
        let pos = cx.st.frame.scratch_top;
        #[cfg(feature = "extras")]
        let mut v = match cx.eval(a) {
            Ok(v) => v,
            Err(e) => {
                let several =
                    cx.exprs[target as usize].next != a || cx.exprs[a as usize].next != NONE;
                return bind_failed(cx, target, start, a, e, several);
            }
        };
        #[cfg(not(feature = "extras"))]
        let mut v = cx.eval(a)?;
        match v {
            // a multifield the argument built in scratch above `pos` (an LHS multifield
            // variable's copy, `create$`) is already in place: slid down over the
            // argument's other temporaries, not copied a second time
            Value::Multi(m) if m.start >= pos && m.start + m.len <= cx.st.frame.scratch_top => {
                let from = m.start as usize;
                cx.scratch
                    .copy_within(from..from + m.len as usize, pos as usize);
                cx.st.frame.scratch_top = pos + m.len;
                v = Value::Multi(MfSpan {
                    start: pos,
                    len: m.len,
                });
                spliced = true;
            }
            Value::Multi(m) => {
                for k in 0..m.len as usize {
                    let item = cx.scratch[m.start as usize + k];
                    cx.multi_push(item)?;
                }
                spliced = true;
            }
            // (a call without a value adds nothing)
            Value::Void => cx.st.frame.scratch_top = pos,
            _ => {
                cx.st.frame.scratch_top = pos;
                cx.multi_push(v)?
            }
        }
        only = v;
        n += 1;
        a = cx.exprs[a as usize].next;
    }
    // one value: bound as it is (a multifield's copies pushed above are not needed)
    let value = if n == 1 && (!only.is_multi() || spliced) {
        keep_bound(cx, start, only)?
    } else if n == 0 {
        // `(bind ?*g*)`: a defglobal goes back to its initial value, which bind returns
        let t = cx.exprs[target as usize];
        let init = if t.op == Op::Global {
            cx.globals[t.data as usize].init
        } else {
            NONE
        };
        if init != NONE {
            let v = cx.eval(init)?;
            let v = keep_bound(cx, start, v)?;
            store_bound(cx, target, bound(v))?;
            return Ok(v);
        }
        Value::Void
    } else {
        cx.multi_finish(start)
    };
    // (no value unbinds a local or prompt variable)
    let stored = if n == 0 { value } else { bound(value) };
    store_bound(cx, target, stored)?;
    Ok(if n == 0 { Value::Sym(SYM_FALSE) } else { value })
}

/// `bind` of one value on the host: what the general path makes of it, without copying
/// the value into scratch and dropping the copy again, and with a constant or variable
/// read in place.
#[cfg(feature = "host-speedups")]
fn bind_one(cx: &mut Core<'_>, target: Ix, a: Ix) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    #[cfg(feature = "grow")]
    let value = cx.eval_value_operand::<true>(a);
    #[cfg(not(feature = "grow"))]
    let value = cx.eval_operand(a);
    let value = match value {
        Ok(v) => v,
        #[cfg(feature = "extras")]
        Err(e) => return bind_failed(cx, target, start, a, e, false),
        #[cfg(not(feature = "extras"))]
        Err(e) => return Err(e),
    };
    let value = keep_bound(cx, start, value)?;
    store_bound(cx, target, bound(value))?;
    Ok(value)
}

/// `bind` whose value `a` (from scratch mark `start`) failed with `e`: CLIPS binds
/// the value the failing call returned (`Core::value_after_error`), the empty
/// multifield when there were `several` values, and `bind` returns it (recorded as
/// its fallback) with the evaluation error set: the command or actions stop.
#[cfg(feature = "extras")]
#[cold]
#[inline(never)]
fn bind_failed(
    cx: &mut Core<'_>,
    target: Ix,
    start: Ix,
    a: Ix,
    e: EvalError,
    several: bool,
) -> Result<Value, EvalError> {
    let halting = cx.st.mode.halting;
    let v = cx.value_after_error(a, e)?;
    cx.st.mode.halting = halting;
    let v = if several {
        cx.st.frame.scratch_top = start;
        cx.multi_finish(start)
    } else {
        keep_bound(cx, start, v)?
    };
    store_bound(cx, target, bound(v))?;
    cx.set_error_fallback(v, None);
    let mut e = e;
    e.reported = true;
    Err(e)
}

/// The value `bind` stores for argument value `v`, evaluated above scratch mark
/// `start`: a multifield the argument built there (e.g. `(bind ?x (create$ a b))`)
/// keeps its cells and the argument's other temporaries are dropped; a global's
/// multifield is copied (its region is repacked on every global store, and a
/// temporary's end there would hold the scratch top inside the region).
fn keep_bound(cx: &mut Core<'_>, start: Ix, v: Value) -> Result<Value, EvalError> {
    let top = cx.st.frame.scratch_top;
    let Value::Multi(m) = v else {
        cx.st.frame.scratch_top = start;
        return Ok(v);
    };
    if m.start >= top {
        cx.st.frame.scratch_top = start;
        for k in 0..m.len as usize {
            let item = cx.scratch[m.start as usize + k];
            cx.multi_push(item)?;
        }
        return Ok(cx.multi_finish(start));
    }
    cx.st.frame.scratch_top = if m.start >= start {
        m.start + m.len
    } else {
        start
    };
    Ok(v)
}

/// What a variable bound to `v` holds: a void value (a `printout`, a deffunction
/// returning nothing) binds it as CLIPS does (`Value::BoundVoid`), as `Void` in
/// storage is "unbound".
#[inline(always)]
fn bound(v: Value) -> Value {
    if matches!(v, Value::Void) {
        Value::BoundVoid
    } else {
        v
    }
}

/// Stores `bind`'s value in its target, a local frame slot or a global.
#[inline(always)]
fn store_bound(cx: &mut Core<'_>, target: Ix, value: Value) -> Result<(), EvalError> {
    let t = cx.exprs[target as usize];
    match t.op {
        Op::Local => {
            let at = (cx.st.frame.bp + t.data) as usize;
            cx.stack[at] = value;
        }
        Op::Global => {
            #[cfg(feature = "extras")]
            cx.set_global_traced(t.data, value)?;
            #[cfg(not(feature = "extras"))]
            cx.set_global(t.data, value)?
        }
        _ => {
            return Err(EvalError::new(EvalErrorKind::UnboundVariable {
                name: NONE,
            }))
        }
    }
    Ok(())
}

fn return_(cx: &mut Core<'_>, a: super::Args) -> Result<Value, EvalError> {
    let v = if a.len > 0 { cx.arg(a, 0) } else { Value::Void };
    cx.st.eval.returning = true;
    cx.st.eval.return_value = v;
    Ok(v)
}

fn break_(cx: &mut Core<'_>, _a: super::Args) -> Result<Value, EvalError> {
    cx.st.eval.breaking = true;
    Ok(Value::Sym(SYM_FALSE))
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::run_program;

    #[test]
    fn bind_of_several_values_splices_each_multifield_once() {
        // an argument's multifield built in scratch (create$, an LHS multifield
        // variable) is taken as it lies, not copied after itself
        let out = run_program(
            "(defrule r (data $?x) => (bind ?b $?x z) (bind ?c (create$ a b) $?x)\n\
             (printout t ?b \" \" ?c crlf))\n\
             (assert (data p q))\n(run)\n",
        );
        assert!(out.contains("(p q z) (a b p q)"), "got {out}");
    }

    #[test]
    fn bound_multifield_survives_later_multifields() {
        let out = run_program(
            "(deffunction f3 () (bind ?out (create$ a b)) (bind ?t (create$ p q r)) ?out)\n\
             (printout t (f3) crlf)\n",
        );
        assert!(out.contains("(a b)"), "got {out}");
        assert!(!out.contains("(p q)"), "got {out}");
    }

    /// A loop frees its body's temporaries without looking at the globals: a global's
    /// multifield, built in the body from temporaries, lives in its own region.
    #[test]
    fn global_multifield_survives_loop_temporaries() {
        let out = run_program(
            "(defglobal ?*g* = (create$ a b))\n\
             (deffunction f () (loop-for-count (?i 1 3) (bind ?t (create$ x y z))\n\
                 (bind ?*g* (create$ ?*g* ?i ?t)) (bind ?u (create$ p q))) ?*g*)\n\
             (printout t (f) crlf)\n\
             (deffunction h () (progn$ (?x (create$ 1 2)) (bind ?*g* (create$ ?*g* ?x))\n\
                 (bind ?v (create$ r s))) ?*g*)\n\
             (printout t (h) crlf)\n",
        );
        assert!(
            out.contains("(a b 1 x y z 2 x y z 3 x y z)\n(a b 1 x y z 2 x y z 3 x y z 1 2)"),
            "got {out}"
        );
    }
}
