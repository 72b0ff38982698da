//! The expression evaluator.

use crate::builtins::{self, Args, Imp, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind, Pool};
use crate::expr::{loc, Expr, FnKind, Op};
use crate::rete::{PatBinding, THIS_PATTERN};
use crate::value::Ix;
use crate::value::{MfSpan, Value, NONE};

/// Deepest nesting of function calls (guards the Rust stack against runaway recursion).
/// With the feature `grow` it is the default of [`DepthLimits`], which a host that runs
/// the engine on a large stack raises.
pub const MAX_EVAL_DEPTH: u16 = 200;

/// How deep function calls may nest on the host (feature `grow`): at most `calls`
/// levels, and (when `stack_bytes` is not 0) within `stack_bytes` of the Rust stack
/// below the outermost call. The host that raises `calls` runs the engine on a thread
/// whose stack holds `stack_bytes` and a margin, so a deep recursion ends in the typed
/// `TooDeep` error wherever the frames of a level are larger (an unoptimised build).
#[cfg(feature = "grow")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthLimits {
    pub calls: u16,
    pub stack_bytes: usize,
    /// Lowest stack address calls may reach: set by the outermost call.
    pub(crate) floor: usize,
    /// One less than the first depth whose calls are checked (`calls`, or
    /// `STACK_CHECK_FROM` with a stack bound, whichever is lower; 0: every call):
    /// a call at depth `d` with `d - 1 < quiet` (wrapping, so not the outermost) is
    /// neither too deep nor near the stack's floor.
    pub(crate) quiet: u16,
}

/// Call depth from which `DepthLimits::stack_bytes` is checked: fewer levels stay far
/// inside any stack the host gives (a level is a few KiB even unoptimised), and the
/// check per call cost the LLSF benchmark 1.6 %.
#[cfg(feature = "grow")]
const STACK_CHECK_FROM: u16 = 128;

#[cfg(feature = "grow")]
impl DepthLimits {
    pub const fn new() -> Self {
        Self::with(MAX_EVAL_DEPTH, 0)
    }

    /// At most `calls` levels, within `stack_bytes` of the stack (0: unchecked).
    pub const fn with(calls: u16, stack_bytes: usize) -> Self {
        let checked = if stack_bytes != 0 && STACK_CHECK_FROM < calls {
            STACK_CHECK_FROM
        } else {
            calls
        };
        DepthLimits {
            calls,
            stack_bytes,
            floor: 0,
            quiet: checked.saturating_sub(1),
        }
    }
}

#[cfg(feature = "grow")]
impl Default for DepthLimits {
    fn default() -> Self {
        Self::new()
    }
}

/// Host: ids of builtins the host decides in place (`compare_lengths`,
/// `quick_join_tests`).
#[cfg(feature = "host-speedups")]
const LENGTH_ID: Ix = builtins::builtin_id("length$");
#[cfg(feature = "host-speedups")]
const MEMBER_ID: Ix = builtins::builtin_id("member$");
#[cfg(feature = "host-speedups")]
const NOT_ID: Ix = builtins::builtin_id("not");

/// An operand `quick_compare` reads without a call.
#[inline(always)]
fn is_leaf(op: Op) -> bool {
    matches!(
        op,
        Op::Sym | Op::Str | Op::Int | Op::Float | Op::Local | Op::Global | Op::PatVar | Op::QSlot
    )
}

/// Where an LHS variable's value lies in the fact cells (`values`): one field, or a
/// segment of `len` fields (a multifield, which reading copies to scratch).
#[derive(Clone, Copy)]
pub(crate) enum Place {
    One(usize),
    Seg(usize, usize),
}

impl Core<'_> {
    /// Evaluates one expression node.
    pub fn eval(&mut self, e: Ix) -> Result<Value, EvalError> {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Int | Op::Float | Op::Sym | Op::Str => Ok(self.const_value(e)),
            Op::Local => self.local(e, x),
            Op::Global => {
                let v = self.globals[x.data as usize].value;
                if matches!(v, Value::Void | Value::BoundVoid) {
                    return self.unbound_global(x.data, v);
                }
                Ok(v)
            }
            Op::PatVar => self.pattern_var_of(x),
            Op::QSlot => self.query_slot(e, x),
            Op::Expand => self.eval(x.first),
            Op::Eq2 => {
                #[cfg(feature = "host-speedups")]
                {
                    let a = self.exprs[x.first as usize];
                    if a.op == Op::PatVar {
                        let b = self.exprs[a.next as usize];
                        if b.op == Op::PatVar {
                            if let Some(same) = self.same_places(a, b) {
                                return Ok(Core::bool_value(same));
                            }
                        }
                    }
                }
                let a = self.eval_operand(x.first)?;
                let b = self.eval_operand(self.exprs[x.first as usize].next)?;
                Ok(Core::bool_value(builtins::basic::values_same(self, a, b)))
            }
            Op::And => {
                let mut c = x.first;
                while c != NONE {
                    if !Core::is_true(self.eval(c)?) {
                        return Ok(Value::Sym(SYM_FALSE));
                    }
                    c = self.exprs[c as usize].next;
                }
                Ok(Value::Sym(SYM_TRUE))
            }
            Op::Or => {
                let mut c = x.first;
                while c != NONE {
                    if Core::is_true(self.eval(c)?) {
                        return Ok(Value::Sym(SYM_TRUE));
                    }
                    c = self.exprs[c as usize].next;
                }
                Ok(Value::Sym(SYM_FALSE))
            }
            Op::Not => Ok(Core::bool_value(!Core::is_true(self.eval(x.first)?))),
            Op::Call => self.call(e, x),
            _ => Ok(Value::Void),
        }
    }

    /// A frame local's value (see `void_local` for one holding none).
    #[inline(always)]
    fn local(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        let v = self.stack[(self.st.frame.bp + x.data) as usize];
        if matches!(v, Value::Void | Value::BoundVoid) {
            return self.void_local(e, x, v);
        }
        Ok(v)
    }

    /// A local holding no value: bound to a void value (`Value::BoundVoid`), that
    /// value; unbound, one the parser proved bound is void as well; one it marked as
    /// maybe unbound (bound only inside a condition or loop: `aux` 1, its name in the
    /// payload node after it) is an error, an LHS variable the actions bind (`aux` 2)
    /// has its LHS value until then (CLIPS's fallback).
    #[cold]
    #[inline(never)]
    fn void_local(&mut self, e: Ix, x: Expr, v: Value) -> Result<Value, EvalError> {
        if x.aux == 0 || matches!(v, Value::BoundVoid) {
            return Ok(Value::Void);
        }
        if x.aux == 2 {
            return self.pattern_var_of(self.exprs[x.first as usize]);
        }
        let name = self.exprs[e as usize + 1].data;
        Err(EvalError::new(EvalErrorKind::UnboundVariable { name }))
    }

    /// A global holding no value `v`: bound to a void value, that value; a prompt
    /// variable (`?x`, hidden global `?x`) never bound is CLIPS's `[EVALUATN1]`; a
    /// defglobal gives its value.
    #[cold]
    #[inline(never)]
    fn unbound_global(&mut self, g: Ix, v: Value) -> Result<Value, EvalError> {
        if matches!(v, Value::BoundVoid) {
            return Ok(Value::Void);
        }
        let name = self.globals[g as usize].name;
        let text = self.sym_text(name);
        if !text.starts_with('?') {
            return Ok(Value::Void);
        }
        // `?*x*` read where no defglobal of the name was seen (at the prompt, in a
        // defglobal's value, a slot default or a deffacts): CLIPS looks the name up
        // when it runs, from the current module
        let global = text
            .strip_prefix("?*")
            .and_then(|t| t.strip_suffix('*'))
            .filter(|t| !t.is_empty());
        let Some(inner) = global else {
            #[cfg(feature = "parser")]
            return Ok(self.unbound_prompt_variable(name));
            #[cfg(not(feature = "parser"))]
            return Err(EvalError::new(EvalErrorKind::UnboundVariable { name }));
        };
        let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
        let _ = core::fmt::Write::write_str(&mut b, inner);
        if let Some(v) = self
            .find_sym(b.as_str())
            .and_then(|id| self.find_global(id))
            .map(|d| self.globals[d as usize].value)
            .filter(|v| !matches!(v, Value::Void))
        {
            if matches!(v, Value::BoundVoid) {
                return Ok(Value::Void);
            }
            return Ok(v);
        }
        // none: `[GLOBLDEF1]`, and the read gives FALSE with CLIPS's evaluation error
        // set, which halts what checks it (see `Core::args_failed`)
        let mut m: crate::value::TextBuf<160> = crate::value::TextBuf::new();
        let _ = core::fmt::Write::write_fmt(
            &mut m,
            format_args!(
                "[GLOBLDEF1] Global variable ?*{}* is unbound.\n",
                b.as_str()
            ),
        );
        self.write(crate::host::router::WERROR, m.as_str());
        self.st.mode.halting = true;
        Ok(Value::Sym(SYM_FALSE))
    }

    /// A prompt variable (`?x`, only the parser makes them) never bound: CLIPS's
    /// `[EVALUATN1]`, and the read gives FALSE with the evaluation error set, so
    /// the function reading it reports its argument's type as well.
    #[cfg(feature = "parser")]
    #[cold]
    #[inline(never)]
    fn unbound_prompt_variable(&mut self, name: crate::value::SymId) -> Value {
        let mut m: crate::value::TextBuf<160> = crate::value::TextBuf::new();
        let text = self.sym_text(name);
        let _ = core::fmt::Write::write_fmt(
            &mut m,
            format_args!(
                "[EVALUATN1] Variable {} is unbound\n",
                text.strip_prefix('?').unwrap_or(text)
            ),
        );
        self.write(crate::host::router::WERROR, m.as_str());
        self.st.mode.halting = true;
        Value::Sym(SYM_FALSE)
    }

    /// CLIPS's message for an error that stopped deffunction `func`: an unbound local
    /// names the deffunction. Out of line: the deffunction call recurses, and its
    /// frame should not carry the text buffer.
    #[cold]
    #[inline(never)]
    fn write_deffunction_error(&mut self, err: EvalError, func: crate::value::SymId) {
        match err.kind() {
            EvalErrorKind::UnboundVariable { name } if !err.reported && name != NONE => {
                let mut b: crate::value::TextBuf<160> = crate::value::TextBuf::new();
                let _ = core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!(
                        "[PRCCODE5] Variable {} unbound in deffunction {}.\n",
                        self.sym_text(name),
                        self.sym_text(func)
                    ),
                );
                self.write(crate::host::router::WERROR, b.as_str());
            }
            _ => self.write_error_message(err),
        }
    }

    /// Evaluates an operand (a call argument, an `Eq2` side, a slot value): leaves (constants,
    /// variables) are read in place, without a recursive `eval` call, which is where
    /// most operands end and most of the evaluator's time went.
    #[inline(always)]
    pub(crate) fn eval_operand(&mut self, e: Ix) -> Result<Value, EvalError> {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Sym => Ok(Value::Sym(x.data)),
            Op::Str => Ok(Value::Str(x.data)),
            Op::Int => Ok(Value::Int(
                Expr::join_bits(x, self.exprs[e as usize + 1]) as i64
            )),
            Op::Local => self.local(e, x),
            Op::PatVar => self.pattern_var_of(x),
            Op::QSlot => self.query_slot(e, x),
            _ => self.eval(e),
        }
    }

    /// Host: `eval_operand` for a value that is stored (`bind`'s, a single-field
    /// slot's), where counters and coordinates are computed (`(bind ?*n* (+ ?*n* 1))`,
    /// `(x (+ ?x 1))`): `+`, `-`, `*` go to `arith_value`, other nodes as operands.
    /// (Only these callers: a test in `eval_operand` itself, inlined at every operand
    /// site, made other rows dearer.)
    /// Host: a rule's top-level action (`eval_actions`). A call of a lazy builtin
    /// past the comparisons and arithmetic (`assert`, `modify`, `bind`, `printout`,
    /// `if`, ...) that needs no depth check goes to its code as `call` sends it,
    /// without the evaluator's frame and dispatch; anything else is evaluated.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(always)]
    pub(crate) fn eval_action(&mut self, e: Ix) -> Result<Value, EvalError> {
        let x = self.exprs[e as usize];
        if matches!(x.op, Op::Call)
            && x.aux == FnKind::Builtin as u8
            && x.data > builtins::basic::CMP_LAST
            && self.st.eval.eval_depth.wrapping_sub(1) < self.st.eval.limits.quiet
        {
            if let Imp::Lazy(f) = builtins::code_of(self, x.data, builtins::get(x.data)) {
                self.st.eval.eval_depth += 1;
                let sp = self.st.frame.sp;
                let r = f(self, e);
                self.st.frame.sp = sp;
                self.st.eval.eval_depth -= 1;
                return r;
            }
        }
        self.eval(e)
    }

    /// `IN`: the in-place arithmetic is in line at this site too (`bind`'s, where a
    /// counter's firing paid two call frames for it), else called (`arith_value`).
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(always)]
    pub(crate) fn eval_value_operand<const IN: bool>(&mut self, e: Ix) -> Result<Value, EvalError> {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Sym => Ok(Value::Sym(x.data)),
            Op::Str => Ok(Value::Str(x.data)),
            Op::Int => Ok(Value::Int(
                Expr::join_bits(x, self.exprs[e as usize + 1]) as i64
            )),
            Op::Local => self.local(e, x),
            Op::PatVar => self.pattern_var_of(x),
            Op::QSlot => self.query_slot(e, x),
            // (two compares for other calls)
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && x.data.wrapping_sub(builtins::basic::ARITH_FIRST) < 3 =>
            {
                // (a call that needs no depth check: `arith_value`'s first case)
                if IN && self.st.eval.eval_depth.wrapping_sub(1) < self.st.eval.limits.quiet {
                    if let Some(v) = self.quick_arith_in(x) {
                        return Ok(v);
                    }
                    return self.arith_call(e, x);
                }
                self.arith_value(e, x)
            }
            // a twin of `+`, `-` or `*` (`builtins::ordered`) that needs no depth check:
            // called as `call` would, without the evaluator's frame
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && x.data.wrapping_sub(builtins::ordered::FIRST) < 3
                    && self.st.eval.eval_depth.wrapping_sub(1) < self.st.eval.limits.quiet =>
            {
                if let Some(v) = self.quick_twin_arith(x) {
                    return Ok(v);
                }
                self.arith_call(e, x)
            }
            _ => self.eval(e),
        }
    }

    /// Host: a twin of `+`, `-` or `*` (call `x`) of two operands that `pure_leaf`
    /// reads as numbers without side effects (`(+ ?*sum* ?f:w)` in a query's action):
    /// both are evaluated in CLIPS as well, so the order cannot show; computed in place
    /// as `quick_arith` does. None (nothing read that could fail or print) otherwise.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(never)]
    fn quick_twin_arith(&mut self, x: Expr) -> Option<Value> {
        let a = x.first;
        if a == NONE {
            return None;
        }
        let xa = self.exprs[a as usize];
        let b = xa.next;
        if b == NONE {
            return None;
        }
        // (both leaves, checked before either is read: `(+ ?s (f ?n))` goes on at once)
        let xb = self.exprs[b as usize];
        if xb.next != NONE || !is_leaf(xa.op) || !is_leaf(xb.op) {
            return None;
        }
        let p = self.pure_leaf(a, NONE)?;
        let q = self.pure_leaf(b, NONE)?;
        if !matches!(p, Value::Int(_) | Value::Float(_))
            || !matches!(q, Value::Int(_) | Value::Float(_))
        {
            return None;
        }
        let sp = self.st.frame.sp as usize + 2;
        if sp > self.stack.len() {
            return None;
        }
        self.note_hw(Pool::EvalStack, sp);
        Some(builtins::basic::num_arith(
            builtins::ordered::original_of(x.data),
            p,
            q,
        ))
    }

    /// Host: the arithmetic call `e` (node `x`) of `eval_value_operand` as `call`
    /// makes it, without the evaluator's frame: computed in place (`quick_arith`)
    /// when the call needs no depth check, else the builtin is called (not asking
    /// `quick_arith` again after it declined).
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(never)]
    fn arith_value(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        if self.st.eval.eval_depth.wrapping_sub(1) >= self.st.eval.limits.quiet {
            return self.eval(e);
        }
        if let Some(v) = self.quick_arith(x) {
            return Ok(v);
        }
        self.arith_call(e, x)
    }

    /// `arith_value`'s call of the builtin, once `quick_arith` declined (not asked
    /// again by `bind`'s site, which took it in line).
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(never)]
    fn arith_call(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        self.st.eval.eval_depth += 1;
        let sp = self.st.frame.sp;
        let r = self.call_builtin(e, x);
        self.st.frame.sp = sp;
        self.st.eval.eval_depth -= 1;
        r
    }

    /// A two-argument comparison (`=` .. `neq`, see `basic::CMP_FIRST`) of leaves
    /// (constants and variables, which call nothing), the commonest calls in query
    /// and `if` conditions: the operands are read in place and numbers or `eq` are
    /// compared here, without the argument stack. It evaluates, reports errors and
    /// records the stack's high-water mark as `push_args` and the builtin would;
    /// None (nothing evaluated yet) when the call has another shape or the stack
    /// is full.
    // out of line in the image: inlined, it would grow `call_inner`'s frame, which
    // every nested call pays in stack
    #[cfg_attr(not(feature = "host-speedups"), inline(never))]
    fn quick_compare(&mut self, x: Expr) -> Option<Result<Value, EvalError>> {
        let a = x.first;
        if a == NONE {
            return None;
        }
        let b = self.exprs[a as usize].next;
        if b == NONE {
            return None;
        }
        // host: three or more arguments are evaluated one at a time, as CLIPS does
        #[cfg(feature = "extras")]
        if self.exprs[b as usize].next != NONE {
            return Some(self.compare_in_order(x));
        }
        if self.exprs[b as usize].next != NONE
            || !is_leaf(self.exprs[a as usize].op)
            || !is_leaf(self.exprs[b as usize].op)
        {
            // host: a `length$` operand (checked here: the call's frame cost the
            // other comparisons of calls 30-80 instructions each)
            #[cfg(feature = "host-speedups")]
            if self.length_call(a) || self.length_call(b) {
                return self.compare_lengths(x, a, b);
            }
            return None;
        }
        let sp = self.st.frame.sp as usize;
        if sp + 2 > self.stack.len() {
            return None;
        }
        let va = match self.eval_operand(a) {
            Ok(v) => v,
            Err(err) => {
                self.note_hw(Pool::EvalStack, sp);
                return Some(Err(err));
            }
        };
        let vb = match self.eval_operand(b) {
            Ok(v) => v,
            Err(err) => {
                self.note_hw(Pool::EvalStack, sp + 1);
                return Some(Err(err));
            }
        };
        self.note_hw(Pool::EvalStack, sp + 2);
        if let Some(r) = builtins::basic::compare(self, x.data, va, vb) {
            return Some(Ok(Core::bool_value(r)));
        }
        // not numbers: the builtin itself reports it, from the argument stack (`call`
        // pops it)
        self.stack[sp] = va;
        self.stack[sp + 1] = vb;
        self.st.frame.sp += 2;
        let args = Args {
            base: sp as Ix,
            len: 2,
        };
        let b = builtins::get(x.data);
        let r = match builtins::code_of(self, x.data, b) {
            Imp::Eager(f) => {
                f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
            }
            Imp::Lazy(_) => Err(EvalError::new(EvalErrorKind::NoSuchFunction)),
        };
        Some(r)
    }

    /// Host: `+`, `-` or `*` of two number leaves (constants, locals, globals, single
    /// fields of flat facts: counters, indexes, coordinates) computed in place, as the
    /// builtin's `fold` would, without the argument stack; it records the stack's
    /// high-water mark as `push_args` would. None (nothing read that could fail or
    /// print) for another call, or an operand of another shape or type: the builtin
    /// then runs as usual. (Out of line: inlined, it grew the evaluator's frame,
    /// which every call paid: llsf-10's run +0.3 %.)
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn quick_arith(&mut self, x: Expr) -> Option<Value> {
        self.quick_arith_in(x)
    }

    /// `quick_arith` in line (`eval_value_operand`'s `bind` site).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn quick_arith_in(&mut self, x: Expr) -> Option<Value> {
        if x.data.wrapping_sub(builtins::basic::ARITH_FIRST) >= 3 || x.first == NONE {
            return None;
        }
        let b = self.exprs[x.first as usize].next;
        if b == NONE || self.exprs[b as usize].next != NONE {
            return None;
        }
        let p = self.num_leaf(x.first)?;
        let q = self.num_leaf(b)?;
        let sp = self.st.frame.sp as usize + 2;
        if sp > self.stack.len() {
            return None;
        }
        self.note_hw(Pool::EvalStack, sp);
        Some(builtins::basic::num_arith(x.data, p, q))
    }

    /// Host: whether node `e` calls `length$`.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn length_call(&self, e: Ix) -> bool {
        let y = self.exprs[e as usize];
        y.op == Op::Call && y.data == LENGTH_ID && y.aux == FnKind::Builtin as u8
    }

    /// Host: `quick_compare` of two operands one or both of which are a `length$`
    /// that `quick_length` computes, the others leaves (`(> (length$ $?l) 0)`,
    /// `(>= (length$ ?a) (length$ $?b))`); None for anything else, or values that
    /// are not numbers (the builtin reports them). The lengths are read first: they
    /// have no side effects and cannot fail.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn compare_lengths(&mut self, x: Expr, a: Ix, b: Ix) -> Option<Result<Value, EvalError>> {
        let length = |cx: &mut Self, e: Ix| -> Option<Option<Value>> {
            let y = cx.exprs[e as usize];
            if is_leaf(y.op) {
                Some(None)
            } else if y.op == Op::Call && y.aux == FnKind::Builtin as u8 && y.data == LENGTH_ID {
                cx.quick_length(y).map(Some)
            } else {
                None
            }
        };
        if self.exprs[b as usize].next != NONE {
            return None;
        }
        let (la, lb) = (length(self, a)?, length(self, b)?);
        let sp = self.st.frame.sp as usize;
        if sp + 2 > self.stack.len() {
            return None;
        }
        let va = match la {
            Some(v) => v,
            None => match self.eval_operand(a) {
                Ok(v) => v,
                Err(err) => {
                    self.note_hw(Pool::EvalStack, sp);
                    return Some(Err(err));
                }
            },
        };
        let vb = match lb {
            Some(v) => v,
            None => match self.eval_operand(b) {
                Ok(v) => v,
                Err(err) => {
                    self.note_hw(Pool::EvalStack, sp + 1);
                    return Some(Err(err));
                }
            },
        };
        let r = builtins::basic::compare(self, x.data, va, vb)?;
        self.note_hw(Pool::EvalStack, sp + 2);
        Some(Ok(Core::bool_value(r)))
    }

    /// Host: a join's tests (chain `tests`, `lhs_pm` bound) decided in order while
    /// each is a `member$` of an atom in an LHS variable's multifield, the `not` of
    /// one, or an `Eq2` of two LHS variables, read where the fields lie (`(member$
    /// ?goal ?top)` of a segment): Err(whether all hold) when decided, else Ok(the
    /// first test left for the evaluator). These tests have no side effects and
    /// cannot fail, so deciding them first changes nothing the evaluator does.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn quick_join_tests(&mut self, tests: Ix) -> Result<Ix, bool> {
        // only a first test of these forms calls (the call's frame, in line, cost
        // the evaluator's other joins a third more)
        let Some(&x) = self.exprs.get(tests as usize) else {
            return Ok(tests);
        };
        let worth =
            x.op == Op::Eq2 || (x.op == Op::Call && (x.data == MEMBER_ID || x.data == NOT_ID));
        if !worth || self.st.mode.halting {
            return Ok(tests);
        }
        self.quick_join_chain(tests)
    }

    /// `quick_join_tests` past its first check.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn quick_join_chain(&mut self, tests: Ix) -> Result<Ix, bool> {
        let pm = core::mem::replace(&mut self.st.net.pm_rhs, false);
        let mut t = tests;
        let r = loop {
            if t == NONE {
                break Err(true);
            }
            let x = self.exprs[t as usize];
            match self.in_place_join_test(x) {
                Some(true) => t = x.next,
                Some(false) => break Err(false),
                None => break Ok(t),
            }
        };
        self.st.net.pm_rhs = pm;
        r
    }

    /// One test of `quick_join_tests`, None when the evaluator must decide it.
    #[cfg(feature = "host-speedups")]
    fn in_place_join_test(&self, x: Expr) -> Option<bool> {
        match x.op {
            Op::Eq2 => {
                let a = self.exprs[x.first as usize];
                let b = self.exprs[a.next as usize];
                if a.op != Op::PatVar || b.op != Op::PatVar {
                    return None;
                }
                self.same_places(a, b)
            }
            Op::Call if x.aux == FnKind::Builtin as u8 && x.data == MEMBER_ID => {
                Some(self.quick_member(x)?.is_some())
            }
            Op::Call if x.aux == FnKind::Builtin as u8 && x.data == NOT_ID => {
                if x.first == NONE {
                    return None;
                }
                let y = self.exprs[x.first as usize];
                if y.next != NONE
                    || y.op != Op::Call
                    || y.aux != FnKind::Builtin as u8
                    || y.data != MEMBER_ID
                {
                    return None;
                }
                Some(self.quick_member(y)?.is_none())
            }
            _ => None,
        }
    }

    /// Host: `member$` (call node `x`) of an atom (an LHS variable's field, a
    /// symbol or string) in an LHS variable's multifield, read in place: Some(the
    /// 0-based position found, or None), or None when the builtin must decide.
    #[cfg(feature = "host-speedups")]
    fn quick_member(&self, x: Expr) -> Option<Option<usize>> {
        if x.first == NONE {
            return None;
        }
        let a = self.exprs[x.first as usize];
        if a.next == NONE {
            return None;
        }
        let needle = match a.op {
            Op::PatVar => match self.pattern_place(a.aux, a.data, a.first)? {
                Place::One(c) => self.values[c],
                Place::Seg(..) => return None,
            },
            Op::Sym => Value::Sym(a.data),
            Op::Str => Value::Str(a.data),
            _ => return None,
        };
        let mut v = self.exprs[a.next as usize];
        if needle.is_multi() || v.next != NONE {
            return None;
        }
        if v.op == Op::Expand && v.aux == 0 && v.first != NONE {
            v = self.exprs[v.first as usize];
        }
        if v.op != Op::PatVar {
            return None;
        }
        let Place::Seg(c, n) = self.pattern_place(v.aux, v.data, v.first)? else {
            return None;
        };
        Some((0..n).find(|&k| self.values[c + k].same(needle)))
    }

    /// Host: `length$` (call node `x`) of an LHS variable's multifield, read where
    /// the multifield lies in its fact, without the copy to scratch the argument's
    /// evaluation makes; None for anything else, which the builtin computes.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn quick_length(&mut self, x: Expr) -> Option<Value> {
        if x.first == NONE || self.st.mode.halting {
            return None;
        }
        let mut v = self.exprs[x.first as usize];
        if v.next != NONE {
            return None;
        }
        if v.op == Op::Expand && v.aux == 0 && v.first != NONE {
            v = self.exprs[v.first as usize];
        }
        if v.op != Op::PatVar {
            return None;
        }
        match self.pattern_place(v.aux, v.data, v.first)? {
            Place::Seg(_, n) => Some(Value::Int(n as i64)),
            Place::One(_) => None,
        }
    }

    /// Host: the number leaf `e` holds (`quick_arith`), read without side effects;
    /// None for anything else (a void variable, which the evaluator reports).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn num_leaf(&self, e: Ix) -> Option<Value> {
        let x = self.exprs[e as usize];
        let v = match x.op {
            Op::Int | Op::Float => return Some(self.const_value_inline(e)),
            Op::Local => self.stack[(self.st.frame.bp + x.data) as usize],
            Op::Global => self.globals[x.data as usize].value,
            Op::PatVar if x.data != loc::FACT && loc::elem(x.data) == loc::SINGLE => {
                let fact = self.binding(x.aux).fact;
                if fact == NONE {
                    return None;
                }
                let f = &self.facts[fact as usize];
                if !f.flat {
                    return None;
                }
                self.values[(f.start + Ix::from(loc::slot(x.data))) as usize]
            }
            _ => return None,
        };
        match v {
            Value::Int(_) | Value::Float(_) => Some(v),
            _ => None,
        }
    }

    /// Host: the value leaf `e` holds, read without side effects: a constant, a bound
    /// local or global, a single field of a flat fact's slot (a rule's variable), or
    /// `?v:slot` of a query variable other than the one in frame slot `own`, read in
    /// place (`cached_query_slot`). None for anything the evaluator must read (and
    /// maybe report). Fact-set queries decide their tests with it
    /// (`queries::QuickTest`).
    #[cfg(feature = "host-speedups")]
    pub(crate) fn pure_leaf(&self, e: Ix, own: Ix) -> Option<Value> {
        let x = self.exprs[e as usize];
        let v = match x.op {
            Op::Int | Op::Float | Op::Sym | Op::Str => return Some(self.const_value_inline(e)),
            Op::Local if x.data != own => self.stack[(self.st.frame.bp + x.data) as usize],
            Op::Global => self.globals[x.data as usize].value,
            Op::PatVar if x.data != loc::FACT && loc::elem(x.data) == loc::SINGLE => {
                let fact = self.binding(x.aux).fact;
                if fact == NONE {
                    return None;
                }
                let f = &self.facts[fact as usize];
                if !f.flat {
                    return None;
                }
                self.values[(f.start + Ix::from(loc::slot(x.data))) as usize]
            }
            Op::QSlot if x.data != own => {
                let fv = self.stack[(self.st.frame.bp + x.data) as usize];
                return self.cached_query_slot(fv, self.exprs[x.first as usize].data, x.aux);
            }
            _ => return None,
        };
        match v {
            Value::Void | Value::BoundVoid | Value::Multi(_) => None,
            v => Some(v),
        }
    }

    /// Evaluates a chain of actions; the value of the last one is the result.
    /// Stops early while a `return`/`break` unwinds.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub fn eval_chain(&mut self, mut e: Ix) -> Result<Value, EvalError> {
        let mut v = Value::Sym(SYM_FALSE);
        // while CLIPS halts (`State::halting`) a progn runs nothing and is FALSE
        while e != NONE && !self.st.mode.halting {
            v = self.eval(e)?;
            if self.st.eval.returning || self.st.eval.breaking || self.st.halt_now() {
                break;
            }
            e = self.exprs[e as usize].next;
        }
        // (host: one that halted on the way, a salience's error in `refresh-agenda`,
        // is FALSE too)
        #[cfg(feature = "extras")]
        if self.st.mode.halting {
            v = Value::Sym(SYM_FALSE);
        }
        Ok(v)
    }

    /// The partial match entry pattern `pat` reads. (Host: in line everywhere, as in
    /// the evaluator; called, it cost `arith_value` and `quick_arith` a frame per
    /// pattern variable.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn binding(&self, pat: u8) -> PatBinding {
        if pat == THIS_PATTERN {
            self.st.net.this_pm
        } else if self.st.net.pm_rhs {
            self.st.net.rhs_pm[pat as usize]
        } else {
            self.st.net.lhs_pm[pat as usize]
        }
    }

    /// `pattern_var` of node `x`, its commonest case (a single-field slot of a flat
    /// fact) read in place on the host, without the call.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn pattern_var_of(&mut self, x: Expr) -> Result<Value, EvalError> {
        #[cfg(feature = "host-speedups")]
        if x.data != loc::FACT {
            let fact = self.binding(x.aux).fact;
            if fact != NONE {
                let f = &self.facts[fact as usize];
                let elem = loc::elem(x.data);
                if elem == loc::SINGLE {
                    if f.flat {
                        let v = self.values[(f.start + Ix::from(loc::slot(x.data))) as usize];
                        if !v.is_multi() {
                            return Ok(v);
                        }
                    }
                } else if loc::slot(x.data) == 0 && x.first != NONE {
                    // slot 0 (an ordered fact's one multislot) is the fact's first cell:
                    // an element with only single-field ones before it is at its index,
                    // read here without `slot_cell` and the call
                    let start = f.start as usize;
                    if let Value::Multi(m) = self.values[start] {
                        let mut c = self.exprs[x.first as usize].first;
                        let mut i = 0u8;
                        while c != NONE {
                            let ex = self.exprs[c as usize];
                            if ex.aux == 1 {
                                break;
                            }
                            if i == elem {
                                if Ix::from(i) < m.len {
                                    return Ok(self.values[start + 1 + i as usize]);
                                }
                                break;
                            }
                            i += 1;
                            c = ex.next;
                        }
                    }
                }
            }
        }
        self.pattern_var(x.aux, x.data, x.first)
    }

    /// Value of an LHS variable: a field of the fact bound to pattern `pat`.
    pub(crate) fn pattern_var(
        &mut self,
        pat: u8,
        locator: Ix,
        desc_slot: Ix,
    ) -> Result<Value, EvalError> {
        let b = self.binding(pat);
        if b.fact == NONE {
            return Err(EvalError::new(EvalErrorKind::UnboundVariable {
                name: NONE,
            }));
        }
        if locator == loc::FACT {
            return Ok(Value::Fact(self.fact_ref(b.fact)));
        }
        let slot = loc::slot(locator) as Ix;
        let elem = loc::elem(locator);
        let f = &self.facts[b.fact as usize];
        if f.flat && elem == loc::SINGLE {
            // one cell per slot: no walk over the slots before it
            let v = self.values[(f.start + slot) as usize];
            if !v.is_multi() {
                return Ok(v);
            }
        }
        let (cell, mlen) = self.slot_cell(b.fact, slot);
        let len = match mlen {
            None => return Ok(self.values[cell]),
            Some(l) => l as usize,
        };
        if elem == loc::SINGLE || desc_slot == NONE {
            return Ok(self.copy_to_scratch(cell + 1, len)?);
        }
        let ps = self.exprs[desc_slot as usize];
        // usual case: only single-field elements up to this one, so its offset is its
        // index (ordered facts like `(state IDLE)` test their fields this way)
        let mut c = ps.first;
        let mut i = 0u8;
        while c != NONE {
            let ex = self.exprs[c as usize];
            if ex.aux == 1 {
                break;
            }
            if i == elem {
                return Ok(self.values[cell + 1 + i as usize]);
            }
            i += 1;
            c = ex.next;
        }
        self.element_after_multi(b, cell, len, ps, elem)
    }

    /// `pattern_var` of element `elem` of a slot (cell `cell`, `len` fields) with a
    /// multifield at or before it (see `place_after_multi`). Out of line, so the
    /// usual case above stays a short call.
    #[inline(never)]
    fn element_after_multi(
        &mut self,
        b: PatBinding,
        cell: usize,
        len: usize,
        ps: Expr,
        elem: u8,
    ) -> Result<Value, EvalError> {
        match self.place_after_multi(b, cell, len, ps, elem) {
            Some(Place::One(c)) => Ok(self.values[c]),
            Some(Place::Seg(c, n)) => Ok(self.copy_to_scratch(c, n)?),
            None => Err(EvalError::new(EvalErrorKind::UnboundVariable {
                name: NONE,
            })),
        }
    }

    /// Where element `elem` of a slot (cell `cell`, `len` fields, pattern
    /// descriptor `ps`) lies, in one walk over the slot's elements up to it: a
    /// multifield but the slot's last takes its mark (`ps.aux` is the slot's first);
    /// the last one's length is what the others and the singles leave, so the
    /// elements after it are counted from the slot's end. None: no such element.
    #[inline(always)]
    fn place_after_multi(
        &self,
        b: PatBinding,
        cell: usize,
        len: usize,
        ps: Expr,
        elem: u8,
    ) -> Option<Place> {
        let (mut pos, mut k, mut i) = (0usize, ps.aux as usize, 0u8);
        let mut c = ps.first;
        while c != NONE {
            let ex = self.exprs[c as usize];
            if ex.aux != 1 {
                if i == elem {
                    return Some(Place::One(cell + 1 + pos));
                }
                pos += 1;
                i += 1;
                c = ex.next;
                continue;
            }
            // the singles after this multifield, up to the next one
            let (mut d, mut after) = (ex.next, 0usize);
            while d != NONE && self.exprs[d as usize].aux != 1 {
                after += 1;
                d = self.exprs[d as usize].next;
            }
            if d == NONE {
                // the slot's last multifield
                let rest = len.saturating_sub(pos + after);
                if i == elem {
                    return Some(Place::Seg(cell + 1 + pos, rest));
                }
                let j = usize::from(elem - i - 1);
                if j >= after {
                    return None;
                }
                return Some(Place::One(cell + 1 + pos + rest + j));
            }
            let m = usize::from(b.marks.get(k).copied().unwrap_or(0));
            if i == elem {
                return Some(Place::Seg(cell + 1 + pos, m));
            }
            let j = usize::from(elem - i - 1);
            if j < after {
                return Some(Place::One(cell + 1 + pos + m + j));
            }
            pos += m + after;
            k += 1;
            i += 1 + after as u8;
            c = d;
        }
        None
    }

    /// Host: where LHS variable (`pattern_var`'s arguments) lies in its fact's
    /// cells; None when its pattern binds no fact or it names the fact itself.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn pattern_place(&self, pat: u8, locator: Ix, desc_slot: Ix) -> Option<Place> {
        let b = self.binding(pat);
        if b.fact == NONE || locator == loc::FACT {
            return None;
        }
        let slot = Ix::from(loc::slot(locator));
        let f = &self.facts[b.fact as usize];
        let (cell, mlen) = if f.flat {
            let c = (f.start + slot) as usize;
            match self.values[c] {
                Value::Multi(m) => (c, Some(m.len)),
                _ => (c, None),
            }
        } else {
            self.slot_cell_inline(b.fact, slot)
        };
        let Some(len) = mlen else {
            return Some(Place::One(cell));
        };
        let elem = loc::elem(locator);
        if elem == loc::SINGLE || desc_slot == NONE {
            return Some(Place::Seg(cell + 1, len as usize));
        }
        let ps = self.exprs[desc_slot as usize];
        self.place_after_multi(b, cell, len as usize, ps, elem)
    }

    /// Host: `Eq2` of two LHS variables (`$?rest` in two patterns, `?g` after a
    /// multifield in both) compared where they lie, a multifield without its copy
    /// to scratch; None when either is not a field of a bound fact.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn same_places(&self, a: Expr, b: Expr) -> Option<bool> {
        let pa = self.pattern_place(a.aux, a.data, a.first)?;
        match (pa, self.pattern_place(b.aux, b.data, b.first)?) {
            (Place::One(p), Place::One(q)) => Some(builtins::basic::values_same(
                self,
                self.values[p],
                self.values[q],
            )),
            (Place::Seg(p, m), Place::Seg(q, n)) => {
                Some(m == n && (0..m).all(|k| self.values[p + k].same(self.values[q + k])))
            }
            _ => None,
        }
    }

    /// `?v:slot` (an `Op::QSlot` node); inlined on the host, where most are read in
    /// place (`cached_query_slot`) and the call cost as much as the read.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn query_slot(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        let fv = self.stack[(self.st.frame.bp + x.data) as usize];
        let name = self.exprs[x.first as usize].data;
        if let Some(v) = self.cached_query_slot(fv, name, x.aux) {
            return Ok(v);
        }
        builtins::facts::slot_value_of(self, fv, name, e)
    }

    /// `?v:slot` in the usual case, read in place: a readable fact, the slot cached in
    /// `aux` (see `slot_value_of`) and one cell per slot; None for anything else.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn cached_query_slot(
        &self,
        fv: Value,
        name: crate::value::SymId,
        aux: u8,
    ) -> Option<Value> {
        let (Value::Fact(r), k) = (fv, Ix::from(aux)) else {
            return None;
        };
        if k == 0 || !self.fact_readable(r) {
            return None;
        }
        let f = &self.facts[r.slot as usize];
        let t = &self.templates[f.tmpl as usize];
        if !f.flat
            || t.implied
            || k > t.nslots
            || self.slots[(t.first_slot + k - 1) as usize].name != name
        {
            return None;
        }
        match self.values[(f.start + k - 1) as usize] {
            Value::Multi(_) => None,
            v => Some(v),
        }
    }

    /// Evaluates a call's arguments onto the stack (inlined into `call` on the host:
    /// most calls have an argument or two, where the call's own cost showed).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn push_args<const GO_ON: bool>(&mut self, mut a: Ix) -> Result<Args, EvalError> {
        let base = self.st.frame.sp;
        while a != NONE {
            // `$?x` is passed as one multifield argument: CLIPS 6.30 does not expand it
            // into separate arguments (`(length$ $?x)` is the length of ?x)
            let v = match self.eval_operand(a) {
                Ok(v) => v,
                // (a builtin's arguments, `GO_ON`: a deffunction that halted gives
                // FALSE with CLIPS's evaluation error set, and the builtin goes on as
                // after an unbound global, `Core::args_failed`)
                #[cfg(not(feature = "extras"))]
                Err(e) if GO_ON && self.deffunction_halted(a, &e) => {
                    self.st.mode.halting = true;
                    Value::Sym(SYM_FALSE)
                }
                // a builtin's call failed, or a deffunction's halted: its value after
                // the error goes on (the builtin called decides how,
                // `Core::builtin_after_failed_arg`)
                #[cfg(feature = "extras")]
                Err(e) if GO_ON => return self.arg_failed(base, a, e),
                Err(e) => {
                    self.note_hw(Pool::EvalStack, self.st.frame.sp as usize);
                    return Err(e);
                }
            };
            // `push_value` without its per-value high-water note (one note per call)
            self.put_value(self.st.frame.sp as usize, v)?;
            self.st.frame.sp += 1;
            a = self.exprs[a as usize].next;
        }
        self.note_hw(Pool::EvalStack, self.st.frame.sp as usize);
        Ok(Args {
            base,
            len: self.st.frame.sp - base,
        })
    }

    /// How many arguments follow from `a` on.
    #[cfg(feature = "extras")]
    fn count_args(&self, mut a: Ix) -> usize {
        let mut n = 0;
        while a != NONE {
            n += 1;
            a = self.exprs[a as usize].next;
        }
        n
    }

    /// A comparison (`=` .. `neq`) of three or more arguments as CLIPS's bodies run it:
    /// each argument is evaluated and checked when its turn comes, and the first pair
    /// that fails the comparison ends the call with FALSE, the arguments after it not
    /// evaluated (`(< 2 1 (bind ?*x* 1))` binds nothing; an unbound global there is not
    /// read). A number argument of another type is `[ARGACCES5]` (FALSE); an argument
    /// that failed goes on with its value after the error, as `push_args` would.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn compare_in_order(&mut self, x: Expr) -> Result<Value, EvalError> {
        let id = x.data;
        let numeric = id - builtins::basic::CMP_FIRST < 6;
        let halting = self.st.mode.halting;
        let was = self.st.eval.arg_error;
        let mut failed: Option<EvalError> = None;
        let (mut first, mut prev) = (Value::Void, Value::Void);
        let mut a = x.first;
        let mut k = 0;
        let r = loop {
            if a == NONE {
                break Ok(true);
            }
            let v = match self.eval_operand(a) {
                Ok(v) => v,
                Err(e) => match self.value_after_error(a, e) {
                    Ok(v) => {
                        let mut e = e;
                        e.reported = true;
                        failed = Some(e);
                        self.st.eval.arg_error = true;
                        v
                    }
                    Err(e) => break Err(e),
                },
            };
            if numeric && !matches!(v, Value::Int(_) | Value::Float(_)) {
                let name = builtins::get(id).name;
                let err = EvalError::wrong_type(name, crate::error::arg_no(k), "integer or float");
                break Err(self.classify_type_error(name, x.first, err));
            }
            if k == 0 {
                first = v;
            } else {
                // `=`, `<>`, `eq`, `neq` compare the first with each other, the
                // orderings each neighbouring pair
                let lhs = if matches!(id - builtins::basic::CMP_FIRST, 2..=5) {
                    prev
                } else {
                    first
                };
                if builtins::basic::compare(self, id, lhs, v) != Some(true) {
                    break Ok(false);
                }
            }
            prev = v;
            k += 1;
            a = self.exprs[a as usize].next;
        };
        self.st.eval.arg_error = was;
        let Some(e) = failed else {
            return r.map(Core::bool_value);
        };
        // an argument failed: the value goes to the caller as this call's fallback
        self.st.mode.halting = halting;
        let v = Core::bool_value(r?);
        self.set_error_fallback(v, None);
        Err(e)
    }

    /// Whether CLIPS's evaluation error is set by an earlier argument of a call under
    /// way (`EvalState::arg_error`).
    #[inline(always)]
    pub(crate) fn arg_error(&self) -> bool {
        #[cfg(feature = "extras")]
        return self.st.eval.arg_error;
        #[cfg(not(feature = "extras"))]
        false
    }

    /// The value call `a` (an argument, a value to bind) gives in CLIPS after failing
    /// with `e`: CLIPS's function prints its message (now), returns its fallback and
    /// sets the evaluation error (`State::halting`, set here), and the function
    /// evaluating it goes on with that value. The fallback is the one the builtin
    /// recorded (`set_error_fallback`, consumed here), else its row's constant, else
    /// FALSE; a deffunction that halted gives FALSE. `e` comes back for what is no
    /// function's error (a full pool, `exit`, an interrupt, too deep a nesting, an
    /// unbound variable) and for other nodes.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    pub(crate) fn value_after_error(&mut self, a: Ix, e: EvalError) -> Result<Value, EvalError> {
        if self.deffunction_halted(a, &e) {
            self.st.mode.halting = true;
            return Ok(Value::Sym(SYM_FALSE));
        }
        let x = self.exprs[a as usize];
        if !gives_value_after_error(&x, &e) {
            return Err(e);
        }
        self.write_error_message(e);
        let depth = self.st.eval.eval_depth + 1;
        let v = match self.st.eval.error_fallback.take() {
            Some(fb) if fb.depth == depth => {
                // `/` went on with 0 for a bad divisor
                if let Some(func) = fb.divide_by_zero {
                    self.write_error_message(EvalError::new(EvalErrorKind::DivideByZero { func }));
                }
                fb.value
            }
            _ => match builtins::get(x.data).on_error.fallback() {
                Some(fb) => self.fallback_value(fb)?,
                None => Value::Sym(SYM_FALSE),
            },
        };
        self.st.mode.halting = true;
        Ok(v)
    }

    /// The constant value call `a` gives after failing with `e`, for the caller's own
    /// fallback (an `if` branch): FALSE for a deffunction that halted, a builtin's
    /// row constant when it recorded none (`set_error_fallback`, left for the caller
    /// to read), None otherwise (no function's error, or no value: nothing printed).
    #[cfg(feature = "extras")]
    pub(crate) fn fallback_after_error(&mut self, a: Ix, e: &EvalError) -> Option<Value> {
        if self.deffunction_halted(a, e) {
            return Some(Value::Sym(SYM_FALSE));
        }
        let x = self.exprs[a as usize];
        let depth = self.st.eval.eval_depth + 1;
        if !gives_value_after_error(&x, e)
            || self
                .st
                .eval
                .error_fallback
                .is_some_and(|fb| fb.depth == depth)
        {
            return None;
        }
        let fb = builtins::get(x.data).on_error.fallback()?;
        self.fallback_value(fb).ok()
    }

    /// Argument `a` (the builtin's arguments from `base`, the ones before it pushed)
    /// failed with `e`: noted (`EvalState::failed_arg`) for `builtin_after_failed_arg`,
    /// which decides whether CLIPS evaluated it at all and what it gives, and `e`
    /// stops `push_args`.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn arg_failed(&mut self, base: Ix, a: Ix, e: EvalError) -> Result<Args, EvalError> {
        self.st.eval.failed_arg = (base, a);
        // (opaque to the optimiser, as the message it printed here made it: what it
        // may change decides how the evaluator's loop around its call is compiled)
        core::hint::black_box(&mut *self);
        Err(e)
    }

    /// Builtin call `x` (body `f`) after an argument failed (`arg_failed`), or after
    /// `push_args` failed otherwise (`e` then comes back): as CLIPS's function, it
    /// evaluates the rest of its arguments and computes its value with the failed
    /// one's (arithmetic, comparisons, `eq`, the type predicates, see
    /// `errors::goes_on_after_error`), or stops with its error value (its row's
    /// constant; `min` and `max` the best so far, 0 for none). The value is recorded
    /// as its fallback (`set_error_fallback`) for the caller, and the call fails with
    /// the reported `e` (or its own error), CLIPS's evaluation error set until the
    /// command, action or test is done. `halting`: the state before the call.
    ///
    /// A numeric builtin (`+`, `/`, `=`, ...) whose earlier argument ends its
    /// arguments in CLIPS (`ends_numbers`) never evaluated this one: its error (an
    /// argument that prints nothing before it fails, else the call is a twin,
    /// `builtins::ordered`) is dropped and the body reports the earlier one.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn builtin_after_failed_arg(
        &mut self,
        x: Expr,
        f: builtins::BuiltinFn,
        halting: bool,
        e: EvalError,
    ) -> Result<Value, EvalError> {
        let (base, a) = core::mem::replace(&mut self.st.eval.failed_arg, (0, NONE));
        if a == NONE {
            return Err(e);
        }
        let at = self.st.frame.sp - base;
        let b = builtins::get(x.data);
        if b.signature.numbers_after_lead() && !stops_all_functions(&e) {
            if let Some(k) = self.numbers_end(x.data, base, at) {
                self.drop_error_fallback();
                self.st.frame.sp = base + k + 1;
                return self.numeric_args_done(x, f, b, halting, base, false);
            }
        }
        let v = match self.value_after_error(a, e) {
            Ok(v) => v,
            Err(e) => {
                self.note_hw(Pool::EvalStack, self.st.frame.sp as usize);
                return Err(e);
            }
        };
        self.push_value(v)?;
        let mut e = e;
        e.reported = true;
        let r = self.value_after_failed_arg(x, f, b, base, at);
        self.st.mode.halting = halting;
        match r {
            Ok(v) => {
                self.set_error_fallback(v, None);
                Err(e)
            }
            Err(err) => Err(err),
        }
    }

    /// The first of the `n` values from `base` (a numeric builtin `id`'s first
    /// arguments) that ends its arguments in CLIPS (`ends_numbers`).
    #[cfg(feature = "extras")]
    fn numbers_end(&self, id: Ix, base: Ix, n: Ix) -> Option<Ix> {
        (0..n).find(|&i| ends_numbers(id, self.stack[(base + i) as usize], i))
    }

    /// Forgets the fallback a call that failed recorded (`set_error_fallback`): CLIPS
    /// never evaluated it.
    #[cfg(feature = "extras")]
    fn drop_error_fallback(&mut self) {
        let depth = self.st.eval.eval_depth + 1;
        if self
            .st
            .eval
            .error_fallback
            .is_some_and(|fb| fb.depth == depth)
        {
            self.st.eval.error_fallback = None;
        }
    }

    /// `builtin_after_failed_arg`'s value of builtin `b` (call `x`, body `f`, its
    /// arguments so far from `base`, argument `at` the failed one).
    #[cfg(feature = "extras")]
    fn value_after_failed_arg(
        &mut self,
        x: Expr,
        f: builtins::BuiltinFn,
        b: &builtins::Builtin,
        base: Ix,
        at: Ix,
    ) -> Result<Value, EvalError> {
        if !builtins::errors::goes_on_after_error(b)
            && !builtins::errors::value_argument(b, at as usize, self.count_args(x.first))
        {
            if let Some(v) = self.args_failed(b)? {
                return Ok(v);
            }
            if matches!(b.name, "min" | "max") {
                if at == 0 {
                    return Ok(Value::Int(0));
                }
                return f(self, Args { base, len: at });
            }
        }
        // the arguments after it; arithmetic and numeric comparisons stop at one
        // that is no number (their body reports it, the last one it sees)
        let numeric = b.signature.numbers_after_lead().then_some(x.data);
        let mut a = x.first;
        for _ in 0..=at {
            a = self.exprs[a as usize].next;
        }
        let was = core::mem::replace(&mut self.st.eval.arg_error, true);
        let r = self.push_rest_after_error(a, base, numeric);
        self.st.eval.arg_error = was;
        let stopped = r?;
        let args = Args {
            base,
            len: self.st.frame.sp - base,
        };
        if !stopped {
            check_arity(b.name, b.min, b.max, args.len)?;
        }
        f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
    }

    /// Evaluates and pushes the arguments from `a` on (of a call whose arguments are
    /// pushed from `base`), CLIPS's evaluation error set: another that fails gives its
    /// value after the error as well. `numeric`: the numeric builtin called, which
    /// takes no argument after one (or the value on top) that is no number or a zero
    /// divisor (`ends_numbers`); whether it stopped early.
    #[cfg(feature = "extras")]
    fn push_rest_after_error(
        &mut self,
        mut a: Ix,
        base: Ix,
        numeric: Option<Ix>,
    ) -> Result<bool, EvalError> {
        while a != NONE {
            let top = self.st.frame.sp - 1;
            if numeric.is_some_and(|id| ends_numbers(id, self.stack[top as usize], top - base)) {
                return Ok(true);
            }
            self.st.eval.arg_error = true;
            let v = match self.eval_operand(a) {
                Ok(v) => v,
                Err(e) => self.value_after_error(a, e)?,
            };
            self.push_value(v)?;
            a = self.exprs[a as usize].next;
        }
        Ok(false)
    }

    /// Whether `e` is the error of deffunction call node `a` that halted (reported
    /// where it happened, with `[PRCCODE4]`).
    #[cold]
    #[inline(never)]
    fn deffunction_halted(&self, a: Ix, e: &EvalError) -> bool {
        let x = self.exprs[a as usize];
        e.reported
            && x.op == Op::Call
            && x.aux == FnKind::Deffunction as u8
            && !stops_all_functions(e)
    }

    /// Calls the function of call node `e` (whose node `x` the caller has read).
    fn call(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        #[cfg(not(feature = "grow"))]
        if self.st.eval.eval_depth >= self.max_eval_depth() {
            return Err(EvalError::new(EvalErrorKind::TooDeep {
                limit: self.max_eval_depth(),
            }));
        }
        // host: one comparison for the calls that need no check (`DepthLimits::quiet`)
        #[cfg(feature = "grow")]
        if self.st.eval.eval_depth.wrapping_sub(1) >= self.st.eval.limits.quiet {
            self.depth_checks()?;
        }
        self.st.eval.eval_depth += 1;
        let sp = self.st.frame.sp;
        let r = self.call_inner(e, x);
        self.st.frame.sp = sp;
        self.st.eval.eval_depth -= 1;
        r
    }

    /// Host: a call's depth checks, for the outermost call and deep ones (see
    /// `DepthLimits::quiet`): too deep a nesting, and the stack (the outermost call
    /// notes the floor; only deep calls can come near it).
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn depth_checks(&mut self) -> Result<(), EvalError> {
        if self.st.eval.eval_depth >= self.max_eval_depth() {
            return Err(EvalError::new(EvalErrorKind::TooDeep {
                limit: self.max_eval_depth(),
            }));
        }
        if self.st.eval.limits.stack_bytes != 0
            && (self.st.eval.eval_depth == 0 || self.st.eval.eval_depth >= STACK_CHECK_FROM)
        {
            self.check_stack()?;
        }
        Ok(())
    }

    /// How deep calls may nest (`MAX_EVAL_DEPTH`, or the host's `DepthLimits`).
    #[inline(always)]
    pub(crate) fn max_eval_depth(&self) -> u16 {
        #[cfg(feature = "grow")]
        return self.st.eval.limits.calls;
        #[cfg(not(feature = "grow"))]
        MAX_EVAL_DEPTH
    }

    /// The Rust stack check of `DepthLimits`: the outermost call notes how low the
    /// stack may go, the others stop there (at the depth reached, as its limit).
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn check_stack(&mut self) -> Result<(), EvalError> {
        let probe = 0u8;
        let here = core::hint::black_box(&probe) as *const u8 as usize;
        let l = &mut self.st.eval.limits;
        if self.st.eval.eval_depth == 0 {
            l.floor = here.saturating_sub(l.stack_bytes);
        } else if here < l.floor {
            return Err(EvalError::new(EvalErrorKind::TooDeep {
                limit: self.st.eval.eval_depth,
            }));
        }
        Ok(())
    }

    /// A call of builtin `f` (call node `call`) whose arguments CLIPS evaluates and
    /// checks one at a time (`str-cat`, `sym-cat`, `format`): `check` looks at each
    /// argument as it comes (the values so far, and how many the call has), and a
    /// wrong one stops the call before later arguments run. Otherwise as an eager call.
    pub(crate) fn call_in_order(
        &mut self,
        call: Ix,
        f: builtins::BuiltinFn,
        check: builtins::ArgCheck,
    ) -> Result<Value, EvalError> {
        let x = self.exprs[call as usize];
        let b = builtins::get(x.data);
        let halting = self.st.mode.halting;
        let base = self.st.frame.sp;
        let mut total = 0;
        let mut a = x.first;
        while a != NONE {
            total += 1;
            a = self.exprs[a as usize].next;
        }
        a = x.first;
        while a != NONE {
            let v = self.eval_operand(a)?;
            self.push_value(v)?;
            let args = Args {
                base,
                len: self.st.frame.sp - base,
            };
            // CLIPS's evaluation error (an unbound global): its error value at once
            if self.st.mode.halting && (!halting || self.arg_error()) {
                if let Some(v) = self.args_failed(b)? {
                    return Ok(v);
                }
            }
            check(self, args, total)
                .map_err(|err| self.classify_type_error(b.name, x.first, err))?;
            a = self.exprs[a as usize].next;
        }
        let args = Args {
            base,
            len: self.st.frame.sp - base,
        };
        check_arity(b.name, b.min, b.max, args.len)?;
        f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
    }

    /// Host: `call_in_order` of `str-cat` or `sym-cat` (builtin `f`, called `name`),
    /// whose check of each argument (an atom: no multifield, fact address or void)
    /// is made here in line, without counting the arguments first.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn cat_in_order(
        &mut self,
        call: Ix,
        f: builtins::BuiltinFn,
        name: &'static str,
        type_name: &'static str,
    ) -> Result<Value, EvalError> {
        let x = self.exprs[call as usize];
        let b = builtins::get(x.data);
        let halting = self.st.mode.halting;
        let base = self.st.frame.sp;
        let mut a = x.first;
        while a != NONE {
            let v = self.eval_operand(a)?;
            self.push_value(v)?;
            // CLIPS's evaluation error (an unbound global): its error value at once
            if self.st.mode.halting && !halting {
                if let Some(v) = self.args_failed(b)? {
                    return Ok(v);
                }
            }
            if matches!(v, Value::Multi(_) | Value::Fact(_) | Value::Void) {
                let i = (self.st.frame.sp - base) as usize - 1;
                let err = EvalError::wrong_type(name, crate::error::arg_no(i), type_name);
                return Err(self.classify_type_error(b.name, x.first, err));
            }
            a = self.exprs[a as usize].next;
        }
        let args = Args {
            base,
            len: self.st.frame.sp - base,
        };
        check_arity(b.name, b.min, b.max, args.len)?;
        f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
    }

    fn call_inner(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        match x.aux {
            k if k == FnKind::Builtin as u8 => {
                // (one compare for the other builtins: `+`, `-`, `*` come before the
                // comparisons; without host speed-ups the outer `if` holds one inner
                // `if` only, kept apart so both builds share this shape)
                #[allow(clippy::collapsible_if)]
                if x.data <= builtins::basic::CMP_LAST {
                    if x.data >= builtins::basic::CMP_FIRST {
                        if let Some(r) = self.quick_compare(x) {
                            return r;
                        }
                    }
                    #[cfg(feature = "host-speedups")]
                    if let Some(v) = self.quick_arith(x) {
                        return Ok(v);
                    }
                }
                self.call_builtin(e, x)
            }
            k if k == FnKind::External as u8 => {
                let args = self.push_args::<false>(x.first)?;
                self.call_values(Callee::External(x.data), args)
            }
            _ => self.call_deffunction(x.data, x.first),
        }
    }

    /// The builtin call `e` (node `x`) past `call_inner`'s quick paths: a lazy builtin
    /// gets the node, an eager one its evaluated arguments. (In line in `call_inner`;
    /// the host's `arith_value` calls it for an arithmetic `quick_arith` declined.)
    #[inline(always)]
    fn call_builtin(&mut self, e: Ix, x: Expr) -> Result<Value, EvalError> {
        let b = builtins::get(x.data);
        match builtins::code_of(self, x.data, b) {
            Imp::Lazy(f) => f(self, e),
            Imp::Eager(f) => {
                let halting = self.st.mode.halting;
                #[cfg(feature = "extras")]
                let args = match self.push_args::<true>(x.first) {
                    Ok(args) => args,
                    Err(err) => return self.builtin_after_failed_arg(x, f, halting, err),
                };
                #[cfg(not(feature = "extras"))]
                let args = self.push_args::<false>(x.first)?;
                // an argument failed with CLIPS's evaluation error (an
                // unbound global): most builtins stop with their error value
                if self.st.mode.halting && (!halting || self.arg_error()) {
                    #[cfg(feature = "extras")]
                    let stops = !builtins::errors::values_failed(self, b, args);
                    #[cfg(not(feature = "extras"))]
                    let stops = true;
                    if stops {
                        if let Some(v) = self.args_failed(b)? {
                            return Ok(v);
                        }
                    }
                }
                check_arity(b.name, b.min, b.max, args.len)?;
                f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
            }
        }
    }

    /// A call of a numeric builtin's twin (`builtins::ordered`: the parser found a
    /// later argument that could print or change something), as CLIPS runs the
    /// original: its arguments one at a time (`call_numeric`; a comparison of three or
    /// more as `compare_in_order`).
    #[inline(never)]
    pub(crate) fn call_ordered(&mut self, call: Ix) -> Result<Value, EvalError> {
        let mut x = self.exprs[call as usize];
        x.data = builtins::ordered::original_of(x.data);
        let b = builtins::get(x.data);
        let Imp::Eager(f) = builtins::code_of(self, x.data, b) else {
            return Err(EvalError::new(EvalErrorKind::NoSuchFunction));
        };
        #[cfg(feature = "extras")]
        if x.data.wrapping_sub(builtins::basic::CMP_FIRST) < 6 && self.count_args(x.first) > 2 {
            return self.compare_in_order(x);
        }
        self.call_numeric(x, f, b)
    }

    /// `call_builtin` of call `x` of numeric builtin `b` (body `f`: `+`, `/`, `=`,
    /// `div`, `mod`, ...), whose arguments CLIPS's body takes one at a time
    /// (`GetNumericArgument`): one that is no number, or a zero divisor of `/` or
    /// `div`, is the last evaluated (`(+ ?s (bind ?*g* 1))` with `?s` a symbol binds
    /// nothing), and the body then reports it. An argument that fails goes on as in
    /// `call_builtin`.
    fn call_numeric(
        &mut self,
        x: Expr,
        f: builtins::BuiltinFn,
        b: &builtins::Builtin,
    ) -> Result<Value, EvalError> {
        let halting = self.st.mode.halting;
        let base = self.st.frame.sp;
        let mut a = x.first;
        while a != NONE {
            // (`eval`, not the operand fast path `eval_operand`: these calls are few,
            // and the image's code budget is tight)
            let v = match self.eval(a) {
                Ok(v) => v,
                #[cfg(feature = "extras")]
                Err(e) => {
                    let err = match self.arg_failed(base, a, e) {
                        Ok(_) => EvalError::already_reported(),
                        Err(err) => err,
                    };
                    return self.builtin_after_failed_arg(x, f, halting, err);
                }
                #[cfg(not(feature = "extras"))]
                Err(e) => {
                    self.note_hw(Pool::EvalStack, self.st.frame.sp as usize);
                    return Err(e);
                }
            };
            let at = self.st.frame.sp - base;
            self.push_value(v)?;
            a = self.exprs[a as usize].next;
            if a != NONE && ends_numbers(x.data, v, at) {
                break;
            }
        }
        self.numeric_args_done(x, f, b, halting, base, a == NONE)
    }

    /// `call_numeric` once its arguments are on the stack from `base` (`all`: every
    /// one, else it stopped at the last): as `call_builtin` after `push_args`, without
    /// the count check for a call that stopped.
    #[inline(never)]
    fn numeric_args_done(
        &mut self,
        x: Expr,
        f: builtins::BuiltinFn,
        b: &builtins::Builtin,
        halting: bool,
        base: Ix,
        all: bool,
    ) -> Result<Value, EvalError> {
        // host: `+`, `-` or `*` of two numbers, neither of which failed: computed here as
        // the builtin's fold would (`quick_arith`'s sum), without its call (this
        // function kept small, the rest out of line: `numeric_args_call`)
        #[cfg(feature = "host-speedups")]
        if all
            && self.st.frame.sp == base + 2
            && x.data.wrapping_sub(builtins::basic::ARITH_FIRST) < 3
            && !self.st.mode.halting
        {
            let (p, q) = (self.stack[base as usize], self.stack[base as usize + 1]);
            if matches!(p, Value::Int(_) | Value::Float(_))
                && matches!(q, Value::Int(_) | Value::Float(_))
            {
                self.note_hw(Pool::EvalStack, base as usize + 2);
                return Ok(builtins::basic::num_arith(x.data, p, q));
            }
        }
        self.numeric_args_call(x, f, b, halting, base, all)
    }

    /// `numeric_args_done`'s call of the builtin's body (in line in the image, where
    /// `numeric_args_done` has nothing before it).
    #[cfg_attr(feature = "host-speedups", inline(never))]
    #[cfg_attr(not(feature = "host-speedups"), inline(always))]
    fn numeric_args_call(
        &mut self,
        x: Expr,
        f: builtins::BuiltinFn,
        b: &builtins::Builtin,
        halting: bool,
        base: Ix,
        all: bool,
    ) -> Result<Value, EvalError> {
        self.note_hw(Pool::EvalStack, self.st.frame.sp as usize);
        let args = Args {
            base,
            len: self.st.frame.sp - base,
        };
        // an argument failed with CLIPS's evaluation error (an unbound global)
        if self.st.mode.halting && (!halting || self.arg_error()) {
            #[cfg(feature = "extras")]
            let stops = !builtins::errors::values_failed(self, b, args);
            #[cfg(not(feature = "extras"))]
            let stops = true;
            if stops {
                if let Some(v) = self.args_failed(b)? {
                    return Ok(v);
                }
            }
        }
        if all {
            check_arity(b.name, b.min, b.max, args.len)?;
        }
        f(self, args).map_err(|err| self.classify_type_error(b.name, x.first, err))
    }

    fn call_deffunction(&mut self, func: Ix, first_arg: Ix) -> Result<Value, EvalError> {
        // while CLIPS halts, a deffunction call evaluates nothing and is FALSE
        if self.st.mode.halting {
            return Ok(Value::Sym(SYM_FALSE));
        }
        // CLIPS counts the call's depth before it evaluates the arguments
        #[cfg(feature = "extras")]
        {
            self.st.eval.dfn_depth += 1;
            // (one test per call for the profiler and the host's poll, their work out
            // of line)
            let r = if self.calls_hooked() {
                self.call_deffunction_hooked(func, first_arg)
            } else {
                self.call_deffunction_args(func, first_arg)
            };
            self.st.eval.dfn_depth -= 1;
            r
        }
        #[cfg(not(feature = "extras"))]
        self.call_deffunction_args(func, first_arg)
    }

    /// A deffunction's call that the host is polled at (`Engine::set_poll_calls`: a
    /// recursion that branches loops without a loop), or timed by the profiler
    /// (`builtins::profile`), or both.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn call_deffunction_hooked(&mut self, func: Ix, first_arg: Ix) -> Result<Value, EvalError> {
        if self.st.profile.polls_calls() {
            self.poll_interrupt()?;
        }
        if !self.profiling(false) {
            return self.call_deffunction_args(func, first_arg);
        }
        self.profile_enter(false, func);
        let r = self.call_deffunction_args(func, first_arg);
        self.profile_leave(false, func);
        r
    }

    #[inline(always)]
    fn call_deffunction_args(&mut self, func: Ix, first_arg: Ix) -> Result<Value, EvalError> {
        let mark = self.st.frame.scratch_top;
        #[cfg(feature = "extras")]
        let args = match self.push_args::<false>(first_arg) {
            Ok(args) => args,
            // an argument's error (printed now if a builtin's, already if a deffunction
            // it called halted): CLIPS adds that it happened in this call's arguments
            Err(mut e) if !stops_all_functions(&e) => {
                if !e.reported {
                    self.write_error_message(e);
                    e.reported = true;
                }
                let _ = self.deffunction_args_failed(func);
                return Err(e);
            }
            Err(e) => return Err(e),
        };
        #[cfg(not(feature = "extras"))]
        let args = self.push_args::<false>(first_arg)?;
        // an argument failed with CLIPS's evaluation error: FALSE, the body not run
        if self.st.mode.halting {
            return self.deffunction_args_failed(func);
        }
        let v = self.apply_deffunction(func, args)?;
        Ok(self.reclaim_call_scratch(mark, v))
    }

    /// Frees what a deffunction call built in scratch above `mark` (its arguments, its
    /// body's temporaries), keeping its value: a multifield there is slid down to
    /// `mark`. Its frame is gone and it could bind nothing of its caller's, so the
    /// value is all that can point there (globals live in their own region), and a
    /// recursion or a loop of calls holds no more than the values in use.
    fn reclaim_call_scratch(&mut self, mark: Ix, v: Value) -> Value {
        let top = self.st.frame.scratch_top;
        if top <= mark {
            return v;
        }
        match v {
            Value::Multi(m) if m.start >= mark && m.start < top => {
                let (s, n) = (m.start as usize, m.len as usize);
                self.scratch.copy_within(s..s + n, mark as usize);
                self.st.frame.scratch_top = mark + m.len;
                Value::Multi(MfSpan {
                    start: mark,
                    len: m.len,
                })
            }
            _ => {
                self.st.frame.scratch_top = mark;
                v
            }
        }
    }

    #[cold]
    #[inline(never)]
    fn deffunction_args_failed(&mut self, func: Ix) -> Result<Value, EvalError> {
        let mut b: crate::value::TextBuf<192> = crate::value::TextBuf::new();
        let _ = core::fmt::Write::write_fmt(
            &mut b,
            format_args!(
                "[PRCCODE6] This error occurred while evaluating arguments for the deffunction {}.\n",
                self.sym_text(self.funcs[func as usize].name)
            ),
        );
        self.write(crate::host::router::WERROR, b.as_str());
        Ok(Value::Sym(SYM_FALSE))
    }

    /// The builtin, host function or deffunction named `name` (`funcall`, `sort`); None
    /// when no function has that name, or it is a special form whose arguments are
    /// expressions.
    pub(crate) fn callee(&mut self, name: &str) -> Option<Callee> {
        if let Some((id, b)) = builtins::lookup(name) {
            return match builtins::code_of(self, id, b) {
                Imp::Eager(f) => Some(Callee::Builtin(b.name, b.min, b.max, f)),
                // called with values, those checked in order are ordinary builtins
                Imp::Lazy(_) => builtins::in_order_body(b.name)
                    .map(|f| Callee::Builtin(b.name, b.min, b.max, f)),
            };
        }
        let sym = self.find_sym(name)?;
        if let Some(f) = self.find_function(sym, self.st_current_module()) {
            return Some(Callee::Deffunction(f));
        }
        let e = (0..self.st.pools.nexternals).find(|&e| self.externals[e as usize].name == sym)?;
        Some(Callee::External(e))
    }

    /// Calls `callee` with the values `args`.
    pub(crate) fn call_values(&mut self, callee: Callee, args: Args) -> Result<Value, EvalError> {
        match callee {
            Callee::Builtin(name, min, max, f) => {
                check_arity(name, min, max, args.len)?;
                f(self, args)
            }
            Callee::Deffunction(f) => {
                if self.st.mode.halting {
                    return Ok(Value::Sym(SYM_FALSE));
                }
                // the deffunction's frame starts at its arguments: copy them to the top
                let base = self.st.frame.sp;
                for i in 0..args.len {
                    self.push_value(self.stack[(args.base + i) as usize])?;
                }
                let args = Args {
                    base,
                    len: args.len,
                };
                let mark = self.st.frame.scratch_top;
                #[cfg(feature = "extras")]
                let r = {
                    if self.st.profile.polls_calls() {
                        self.poll_interrupt()?;
                    }
                    self.st.eval.dfn_depth += 1;
                    let r = self.apply_deffunction(f, args);
                    self.st.eval.dfn_depth -= 1;
                    r
                };
                #[cfg(not(feature = "extras"))]
                let r = self.apply_deffunction(f, args);
                Ok(self.reclaim_call_scratch(mark, r?))
            }
            Callee::External(e) => {
                let ext = self.externals[e as usize];
                check_arity("external", ext.min, ext.max, args.len)?;
                match ext.f {
                    Some(f) => f(&mut crate::host_fn::HostCall::new(self, args)),
                    None => Err(EvalError::new(EvalErrorKind::NoSuchFunction)),
                }
            }
        }
    }

    /// Runs deffunction `func` on the arguments `args`, the top of the stack (its frame).
    fn apply_deffunction(&mut self, func: Ix, args: Args) -> Result<Value, EvalError> {
        #[cfg(feature = "extras")]
        if self.st.mode.watch & crate::engine::watch::DEFFUNCTIONS != 0
            && self.function_traced(func)
        {
            return self.apply_traced(func, args);
        }
        self.apply_untraced(func, args)
    }

    /// Deffunction `func`'s body `body` run in its module, the module current before
    /// it current again after it (`apply_untraced` with more than one module).
    #[cfg(feature = "modules")]
    #[cold]
    #[inline(never)]
    fn eval_body_in_module(&mut self, func: Ix, body: Ix) -> Result<Value, EvalError> {
        let outer_module = self.enter_module(self.module_of_function(func));
        let r = self.eval_chain(body);
        self.leave_module(outer_module);
        r
    }

    /// `apply_deffunction` without its trace.
    pub(crate) fn apply_untraced(&mut self, func: Ix, args: Args) -> Result<Value, EvalError> {
        let df = self.funcs[func as usize];
        let n = args.len as usize;
        let np = df.nparams as usize;
        if n < np || (!df.rest && n > np) {
            return Err(EvalError::new(EvalErrorKind::Arity {
                func: "deffunction",
            }));
        }
        if df.rest {
            // collect the extra arguments (multifields spliced) into the rest parameter
            let start = self.st.frame.scratch_top;
            for k in 0..n - np {
                match self.stack[args.base as usize + np + k] {
                    Value::Multi(m) => {
                        for i in 0..m.len as usize {
                            let s = self.scratch_alloc(1)?;
                            self.scratch[s as usize] = self.scratch[m.start as usize + i];
                        }
                    }
                    v => {
                        let s = self.scratch_alloc(1)?;
                        self.scratch[s as usize] = v;
                    }
                }
            }
            self.st.frame.sp = args.base + np as Ix;
            self.push_value(Value::Multi(MfSpan {
                start,
                len: self.st.frame.scratch_top - start,
            }))?;
        }
        let frame_args = np + usize::from(df.rest);
        self.push_voids((df.nlocals as usize).saturating_sub(frame_args))?;
        let saved_bp = self.st.frame.bp;
        self.st.frame.bp = args.base;
        self.st.eval.in_use += 1;
        let was_halting = self.st.mode.halting;
        // CLIPS runs the body in the deffunction's module and then makes the module
        // current before the call current again (`EvaluateProcActions`): with MAIN
        // alone, nothing to change (out of line, the usual call keeps no module)
        #[cfg(feature = "modules")]
        let mut r = if self.st.modules.nmodules > 1 {
            self.eval_body_in_module(func, df.body)
        } else {
            self.eval_chain(df.body)
        };
        #[cfg(not(feature = "modules"))]
        let mut r = self.eval_chain(df.body);
        // an error that set CLIPS's evaluation error without coming back as one (a
        // slot the fact lacks) halts the deffunction too
        if r.is_ok() && self.st.mode.halting && !was_halting {
            r = Err(EvalError::already_reported());
        }
        self.st.eval.in_use -= 1;
        self.st.frame.bp = saved_bp;
        // CLIPS reports an error inside a deffunction where it happens and adds which
        // deffunction it halted, at every level of nesting.
        let r = match r {
            // a runaway recursion names the function where the limit was hit, once,
            // not once per frame
            Err(err) if matches!(err.kind(), EvalErrorKind::TooDeep { .. }) && err.reported => {
                Err(err)
            }
            Err(mut err)
                if !matches!(err.kind(), EvalErrorKind::Exit | EvalErrorKind::Capacity(_)) =>
            {
                self.write_deffunction_error(err, df.name);
                self.write_halted_in("deffunction", df.name);
                err.reported = true;
                Err(err)
            }
            r => r,
        };
        let v = if self.st.eval.returning {
            self.st.eval.returning = false;
            self.st.eval.return_value
        } else {
            r?
        };
        r.map(|_| v)
    }
}

impl Core<'_> {
    /// An argument type error of a builtin: CLIPS checks literal arguments while parsing
    /// (remembered in `literal_error`) and computed ones in the function body, sometimes
    /// with other type names (`builtins::errors`).
    /// `called` is the builtin the call names: another one's error (a function `funcall`
    /// called) is about values, never literals of this call.
    fn classify_type_error(&mut self, called: &str, first_arg: Ix, err: EvalError) -> EvalError {
        let EvalErrorKind::WrongType {
            func,
            arg,
            expected,
        } = err.kind()
        else {
            return err;
        };
        // reported already (in a deffunction `funcall` called): passed on as it is
        if err.reported {
            return err;
        }
        // find argument `arg` (1-based)
        let mut node = first_arg;
        let mut k = 1;
        while node != NONE && k < arg {
            node = self.exprs[node as usize].next;
            k += 1;
        }
        // `length` runs `length$`'s body, whose messages say `length$`; a literal
        // is refused while parsing, under the name typed
        let old_length = func == "length$" && called == "length";
        // format checks its directives' arguments in its body, literal or not, and
        // funcall and sort the function they call
        let literal = node != NONE
            && (func == called || old_length)
            && !(func == "format" && arg > 2)
            && !(func == "funcall" && expected != "symbol or string")
            && !(func == "sort" && expected != "symbol")
            // set-locale checks its argument in its body (CLIPS: no argument types)
            && !(cfg!(feature = "extras") && func == "set-locale")
            // an unknown item is found in the body, after the symbol passed
            && !(func == "get-watch-item" && expected == "watchable symbol")
            && matches!(
                self.exprs[node as usize].op,
                Op::Int | Op::Float | Op::Sym | Op::Str
            );
        self.st.eval.literal_error = literal;
        if literal && old_length {
            return EvalError::wrong_type("length", arg, expected);
        }
        if literal {
            return err;
        }
        EvalError::wrong_type(
            func,
            arg,
            builtins::describe::runtime_type_name(func, expected),
        )
    }
}

/// A function called by name with values (`Core::callee`).
#[derive(Clone, Copy)]
pub(crate) enum Callee {
    Builtin(&'static str, u8, u8, builtins::BuiltinFn),
    Deffunction(Ix),
    External(Ix),
}

pub(crate) fn check_arity(name: &'static str, min: u8, max: u8, n: Ix) -> Result<(), EvalError> {
    if n < min as Ix || (max != builtins::ANY && n > max as Ix) {
        return Err(EvalError::new(EvalErrorKind::Arity { func: name }));
    }
    Ok(())
}

impl Core<'_> {
    /// Asks the host whether to stop (`Host::interrupt`); the loops and the run loop
    /// call this once per step. A runaway program ends with `Interrupted`, unwinding
    /// as any evaluation error does.
    #[inline]
    pub fn poll_interrupt(&mut self) -> Result<(), EvalError> {
        if self.host.interrupt() {
            Err(EvalError::new(EvalErrorKind::Interrupted))
        } else {
            Ok(())
        }
    }
}

impl crate::engine::State {
    pub fn halt_now(&self) -> bool {
        self.mode.exit
    }
}

/// Whether numeric builtin `id` (`Signature::numbers_after_lead`) takes no argument
/// after `v`, its argument `at` (0-based), as CLIPS's bodies run: they stop at one that
/// is no number (`[ARGACCES5]`), `/` and `div` also at a zero divisor (`div`'s
/// truncated to an integer).
#[inline(always)]
pub(crate) fn ends_numbers(id: Ix, v: Value, at: Ix) -> bool {
    const SLASH: Ix = builtins::builtin_id("/");
    const DIV: Ix = builtins::builtin_id("div");
    match v {
        Value::Int(i) => i == 0 && at > 0 && (id == SLASH || id == DIV),
        Value::Float(f) => {
            at > 0
                && ((id == SLASH && f == 0.0)
                    // (`div` truncates: 0 exactly for -1 < f < 1, never for NaN)
                    || (id == DIV && f > -1.0 && f < 1.0))
        }
        _ => true,
    }
}

/// Whether `e` is no function's error but stops every function it passes through:
/// too deep a nesting, `exit`, a full pool or an interrupt. No call goes on after it
/// with a value, and no deffunction adds a message of its own.
#[inline(always)]
fn stops_all_functions(e: &EvalError) -> bool {
    matches!(
        e.kind(),
        EvalErrorKind::TooDeep { .. }
            | EvalErrorKind::Exit
            | EvalErrorKind::Capacity(_)
            | EvalErrorKind::Interrupted
    )
}

/// Whether call `x`, failing with `e`, goes on with a value after its error message, as
/// CLIPS's builtins do: not for what stops all functions (`stops_all_functions`) or an
/// unbound variable, and never for a deffunction's or a construct's call.
#[cfg(feature = "extras")]
#[inline]
fn gives_value_after_error(x: &Expr, e: &EvalError) -> bool {
    x.op == Op::Call
        && x.aux == FnKind::Builtin as u8
        && !stops_all_functions(e)
        && !matches!(e.kind(), EvalErrorKind::UnboundVariable { .. })
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;

    /// `div`'s zero divisor in `ends_numbers` (a float compared with -1 and 1) is the
    /// one its body finds (`c_trunc_to_i64` of it is 0), NaN and huge values included;
    /// `/` stops at 0.0 and -0.0 only, neither at the first argument.
    #[test]
    fn div_ends_at_a_float_that_truncates_to_zero() {
        use super::{builtins, ends_numbers, Value};
        let (div, slash) = (builtins::builtin_id("div"), builtins::builtin_id("/"));
        for f in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            0.999_999,
            -0.999_999,
            1.0,
            -1.0,
            1.5,
            -1.5,
            1e300,
            -1e300,
            9.3e18,
            -9.3e18,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ] {
            let zero = builtins::math::c_trunc_to_i64(f) == 0;
            assert_eq!(ends_numbers(div, Value::Float(f), 1), zero, "div {f}");
            assert!(!ends_numbers(div, Value::Float(f), 0), "div first {f}");
            assert_eq!(ends_numbers(slash, Value::Float(f), 1), f == 0.0, "/ {f}");
        }
    }

    /// `?f:slot` read in place (flat facts, slot cached) gives what `fact-slot-value`
    /// gives, including where it must not: a multislot, a fact of another template
    /// (the cached index names another slot there), an ordered fact. A retracted fact
    /// reads its old values on both paths (flat: in place; with a multislot: through
    /// `slot_value_of`), where `fact-slot-value` gives FALSE, as in CLIPS 6.30.
    #[test]
    fn query_slots_agree_with_fact_slot_value() {
        let out = run_program(
            "(deftemplate a (slot x) (slot y) (multislot m))
             (deftemplate b (slot y) (slot x))
             (assert (a (x 1) (y p)) (a (x 2) (y q) (m u v)) (b (y 3) (x r)) (o 1 2))
             (do-for-all-facts ((?f a b)) TRUE
               (printout t ?f:x \" \" (fact-slot-value ?f x) \" \"
                           ?f:y \" \" (fact-slot-value ?f y) crlf))
             (do-for-all-facts ((?f a)) TRUE
               (printout t ?f:m \" \" (fact-slot-value ?f m) crlf))
             (do-for-all-facts ((?f o)) TRUE
               (printout t ?f:implied \" \" (fact-slot-value ?f implied) crlf))
             (do-for-all-facts ((?f b)) TRUE (retract ?f)
               (printout t ?f:x \" \" (fact-slot-value ?f x) crlf))
             (do-for-all-facts ((?f a)) TRUE (retract ?f)
               (printout t ?f:x \" \" ?f:m \" \" (fact-slot-value ?f x) crlf))
             (assert (b (y 4) (x s)))
             (do-for-all-facts ((?f b)) TRUE (printout t ?f:x \" \" ?f:m crlf))",
        );
        assert!(out.contains("1 1 p p\n2 2 q q\nr r 3 3\n"), "{out}");
        assert!(out.contains("() ()\n(u v) (u v)\n(1 2) (1 2)\n"), "{out}");
        // b is flat (in place), a has a multislot (the general path)
        assert!(
            out.contains("r FALSE\n1 () FALSE\n2 (u v) FALSE\n"),
            "{out}"
        );
        // a slot the fact lacks: CLIPS's message after what was printed before it,
        // and the actions halt
        assert!(
            out.contains("s [INSFUN3] No such slot m in function fact-set query.\n"),
            "{out}"
        );
    }

    /// A command at the prompt keeps what it retracts readable until it is done, as
    /// CLIPS: `duplicate` and `modify` build from the old values (modify retracting
    /// nothing). The next command sees no such fact.
    #[test]
    fn command_duplicates_and_modifies_a_fact_it_retracted() {
        let out = run_program(
            "(deftemplate t (slot a) (slot b) (multislot m))
             (deffunction rd (?f) (retract ?f) (duplicate ?f (b 2)))
             (bind ?x (assert (t (a one) (m x y))))
             (bind ?d (rd ?x))
             (printout t (fact-slot-value ?d m) crlf)
             (printout t (progn (retract ?d) (fact-slot-value (modify ?d (b 3)) m)) crlf)
             (printout t (duplicate ?x (b 4)) crlf)
             (printout t (find-all-facts ((?f t)) (eq ?f:a one)) crlf)",
        );
        assert!(out.ends_with("(x y)\n(x y)\nFALSE\n(<Fact-3>)\n"), "{out}");
    }

    /// ... but only while there is room: a command retracting and asserting 300 facts
    /// one by one fits the 128 fact slots (an assert that needs them frees them).
    #[test]
    fn command_frees_retracted_facts_when_slots_run_out() {
        let out = run_program(
            "(deftemplate a (slot x))
             (bind ?f (assert (a (x 0))))
             (loop-for-count (?i 1 300) (retract ?f) (bind ?f (assert (a (x ?i)))))
             (printout t (find-all-facts ((?g a)) TRUE) crlf)",
        );
        assert!(out.ends_with("(<Fact-301>)\n"), "{out}");
    }

    /// A top-level query holds a retracted fact only while a variable is bound to it:
    /// retracting all 100 facts and asserting 100 others fits the 128 fact slots.
    #[test]
    fn top_level_query_frees_retracted_facts_per_tuple() {
        let out = run_program(
            "(deftemplate a (slot x))
             (deftemplate b (slot y))
             (loop-for-count (?i 1 100) (assert (a (x ?i))))
             (do-for-all-facts ((?f a)) TRUE (retract ?f) (assert (b (y ?f:x))))
             (printout t (length$ (find-all-facts ((?g b)) (> ?g:y 0))) crlf)
             (printout t (find-all-facts ((?g a)) TRUE) crlf)",
        );
        assert!(out.ends_with("100\n()\n"), "{out}");
    }

    /// The delayed variant frees them when the slots run out: the same 100-for-100
    /// swap fits (each tuple's fact is read after its retraction), twice over.
    #[test]
    fn delayed_query_frees_retracted_facts_when_slots_run_out() {
        let out = run_program(
            "(deftemplate a (slot x))
             (deftemplate b (slot y))
             (loop-for-count (?i 1 100) (assert (a (x ?i))))
             (delayed-do-for-all-facts ((?f a)) TRUE (retract ?f) (assert (b (y ?f:x))))
             (delayed-do-for-all-facts ((?f b)) TRUE (retract ?f) (assert (a (x ?f:y))))
             (printout t (length$ (find-all-facts ((?g a)) (> ?g:x 0))) crlf)
             (printout t (find-all-facts ((?g b)) TRUE) crlf)",
        );
        assert!(out.ends_with("100\n()\n"), "{out}");
    }

    /// A modify inside a top-level query on a full fact pool: the old fact is freed at
    /// once instead of held, so the modify finds a slot (it failed while the query held
    /// it); `?f:slot` then reads FALSE. With room to spare the old values are read.
    #[test]
    fn top_level_query_modify_fits_a_full_fact_pool() {
        let out = run_program(
            "(deftemplate a (slot x))
             (loop-for-count (?i 1 126) (assert (a (x ?i))))
             (do-for-fact ((?f a)) (= ?f:x 1) (modify ?f (x 0)) (printout t ?f:x crlf))
             (assert (a (x 128)))
             (printout t (length$ (find-all-facts ((?g a)) TRUE)) crlf)
             (do-for-fact ((?f a)) (= ?f:x 2) (modify ?f (x -2)) (printout t ?f:x crlf))
             (printout t (length$ (find-all-facts ((?g a)) TRUE)) \" \"
                         (length$ (find-all-facts ((?g a)) (<= ?g:x 0))) crlf)",
        );
        // 126 + (initial-fact) leave one slot: the first modify holds the old fact
        assert!(out.ends_with("1\n<Fact-128>\n127\nFALSE\n127 2\n"), "{out}");
    }

    /// `bind` values and single-field slot values that are `+`, `-`, `*` of two
    /// numbers (on the host `quick_arith`, or any path that computes them in place)
    /// give the builtin's values, integer and float; a global holding no number fails as the
    /// builtin does (CLIPS 6.30's message; `bind` then stores 0, the error value).
    #[test]
    fn arithmetic_bind_and_slot_values_as_the_builtin() {
        let out = run_program(
            "(defglobal ?*i* = 5 ?*f* = 1.5 ?*s* = abc ?*r* = 0)
             (deftemplate p (slot x))
             (defrule step ?p <- (p (x ?x&:(< ?x 3)))
                => (bind ?*r* (* ?*r* 2)) (bind ?y (- ?x ?*f*)) (modify ?p (x (+ ?x 1)))
                   (printout t ?x \" \" ?y crlf))
             (bind ?*r* (+ ?*i* 1))
             (printout t ?*r* crlf)
             (bind ?*r* (- ?*i* ?*f*))
             (printout t ?*r* crlf)
             (printout t ?*r* \" \" (+ ?*r* 1) crlf)
             (assert (p (x (* ?*i* 0))))
             (run)
             (printout t ?*r* crlf)
             (bind ?*r* (+ ?*s* 1))
             (printout t ?*r* crlf)\n",
        );
        assert!(
            out.ends_with(
                "6\n6\n3.5\n3.5\n3.5 4.5\n<Fact-1>\n0 -1.5\n1 -0.5\n2 0.5\n28.0\n[ARGACCES5] Function + expected argument #1 to be of type integer or float\n0\n0\n"
            ),
            "{out}"
        );
    }
}
