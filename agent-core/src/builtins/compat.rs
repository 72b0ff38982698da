//! Builtins CLIPS 6.30 has that the agent image leaves out (agent-core feature `extras`;
//! its rules call none of them): hyperbolic and reciprocal trigonometry, `deg-grad` and
//! `grad-deg`, the older names CLIPS still accepts (`!=`, `member`, `nth`, `mv-append`,
//! `str-explode`, `str-implode`, `mv-subseq`, `mv-delete`, `mv-replace`, `subset`,
//! `wordp`, `sequencep`), `pointerp`, `setgen`, `system` (as Debian builds CLIPS: it runs nothing), `get-`/`set-dynamic-constraint-checking`,
//! `set-fact-duplication`, and the
//! engine settings this engine has one value of (`get-`/`set-auto-float-dividend`,
//! `-salience-evaluation`, `-sequence-operator-recognition`,
//! `-static-constraint-checking`, `-incremental-reset`, `-reset-globals`), and
//! `operating-system` (as Debian builds CLIPS: `UNKNOWN`): setting the value it has
//! is accepted, any other is refused with an error, never accepted and ignored.
//!
//! An older name whose function CLIPS shares with the newer one is a row with the newer
//! one's function: CLIPS names the older one when it checks a literal argument while
//! parsing and the newer one when the body finds a wrong computed argument, and so do
//! these rows (`(nth ?x ...)` with a symbol in `?x` reports `nth$`).
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "extras"), allow(dead_code, unused_imports))]

use super::describe::ArgType::{Any, Integer as I, Multifield as M, Number as N, Str as S};
use super::describe::{BodyNames, OnError};
use super::math::{int_arg, num_arg};
use super::multifield::{index_error, multi_arg, push_flat, push_range, slice};
use super::{Args, Builtin, ANY, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::value::{TextBuf, Value};
use core::f64::consts::FRAC_PI_2;
use core::fmt::Write;

/// A float function of one number: CLIPS's row for it.
const fn trig(name: &'static str, f: super::BuiltinFn) -> Builtin {
    Builtin::eager(name, 1, 1, f)
        .args(&[N], Any)
        .on_error(OnError::FloatZero)
        .body_names(BodyNames::Float)
        .returns(super::describe::Returns::Float)
}

#[cfg(feature = "extras")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    trig("sinh", sinh),
    trig("cosh", cosh),
    trig("tanh", tanh),
    trig("sech", sech),
    trig("csch", csch),
    trig("coth", coth),
    trig("asinh", asinh),
    trig("acosh", acosh),
    trig("atanh", atanh),
    trig("asech", asech),
    trig("acsch", acsch),
    trig("acoth", acoth),
    trig("sec", sec),
    trig("csc", csc),
    trig("cot", cot),
    trig("asec", asec),
    trig("acsc", acsc),
    trig("acot", acot),
    trig("deg-grad", deg_grad),
    trig("grad-deg", grad_deg),
    Builtin::eager("system", 1, ANY, system).args(&[], super::describe::ArgType::SymbolOrString).returns(super::describe::Returns::Void),
    Builtin::eager("!=", 2, ANY, super::basic::num_ne).args(&[], N).on_error(OnError::False).quiet(),
    Builtin::eager("mv-append", 0, ANY, super::multifield::create).on_error(OnError::EmptyMultifield).returns(super::describe::Returns::Multifield),
    Builtin::eager("member", 2, 2, super::multifield::member).args(&[Any, M], Any).on_error(OnError::False),
    Builtin::eager("nth", 2, 2, super::multifield::nth).args(&[I, M], Any).on_error(OnError::Nil),
    Builtin::eager("str-explode", 1, 1, super::multifield::explode).args(&[S], Any).on_error(OnError::EmptyMultifield).returns(super::describe::Returns::Multifield),
    Builtin::eager("str-implode", 1, 1, super::multifield::implode).args(&[M], Any).on_error(OnError::EmptyString).returns(super::describe::Returns::Str),
    Builtin::eager("subset", 2, 2, super::multifield::subsetp).args(&[M, M], Any).on_error(OnError::False).returns(super::describe::Returns::Symbol),
    Builtin::eager("wordp", 1, 1, super::predicates::symbolp).on_error(OnError::False).total().returns(super::describe::Returns::Symbol),
    Builtin::eager("sequencep", 1, 1, super::predicates::multifieldp).on_error(OnError::False).total().returns(super::describe::Returns::Symbol),
    Builtin::eager("mv-subseq", 3, 3, mv_subseq).args(&[I, I, M], Any).on_error(OnError::EmptyMultifield).returns(super::describe::Returns::Multifield),
    Builtin::eager("mv-delete", 2, 2, mv_delete).args(&[I, M], Any).on_error(OnError::EmptyMultifield).returns(super::describe::Returns::Multifield),
    Builtin::eager("mv-replace", 3, 3, mv_replace).args(&[I, M], Any).on_error(OnError::EmptyMultifield).returns(super::describe::Returns::Multifield),
    Builtin::eager("pointerp", 1, 1, pointerp).on_error(OnError::False).total().returns(super::describe::Returns::Symbol),
    Builtin::eager("setgen", 1, 1, setgen).args(&[I], Any),
    Builtin::eager("get-auto-float-dividend", 0, 0, get_auto_float_dividend),
    Builtin::eager("set-auto-float-dividend", 1, 1, set_auto_float_dividend),
    Builtin::eager("get-dynamic-constraint-checking", 0, 0, get_dynamic_constraint_checking),
    Builtin::eager("set-dynamic-constraint-checking", 1, 1, set_dynamic_constraint_checking),
    Builtin::eager("set-fact-duplication", 1, 1, set_fact_duplication),
    Builtin::eager("get-sequence-operator-recognition", 0, 0, get_sequence_operator_recognition),
    Builtin::eager("set-sequence-operator-recognition", 1, 1, set_sequence_operator_recognition)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any),
    Builtin::eager("get-static-constraint-checking", 0, 0, get_static_constraint_checking),
    Builtin::eager("set-static-constraint-checking", 1, 1, set_static_constraint_checking),
    Builtin::eager("get-incremental-reset", 0, 0, get_incremental_reset),
    Builtin::eager("set-incremental-reset", 1, 1, set_incremental_reset),
    Builtin::eager("get-reset-globals", 0, 0, get_reset_globals),
    Builtin::eager("set-reset-globals", 1, 1, set_reset_globals),
    Builtin::eager("operating-system", 0, 0, operating_system),
    Builtin::eager("get-salience-evaluation", 0, 0, get_salience_evaluation),
    Builtin::eager("set-salience-evaluation", 1, 1, set_salience_evaluation).args(&[super::describe::ArgType::Symbol], Any),
];
#[cfg(not(feature = "extras"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

// ---- trigonometry, as CLIPS 6.30's emathfun.c computes it ----

/// CLIPS's bound below which a sine or cosine counts as zero (a singularity).
const SMALLEST_ALLOWED_NUMBER: f64 = 1e-15;

fn float_arg(cx: &Core<'_>, a: Args, func: &'static str) -> Result<f64, EvalError> {
    Ok(num_arg(cx, a, 0, func)?.as_f64())
}

/// `[EMATHFUN1]`/`[EMATHFUN3]`, printed now (CLIPS then returns 0.0).
fn math_error(cx: &mut Core<'_>, code: &str, func: &str) -> EvalError {
    let mut b: TextBuf<96> = TextBuf::new();
    let _ = match code {
        "EMATHFUN3" => writeln!(
            b,
            "[EMATHFUN3] Singularity at asymptote in {func} function."
        ),
        _ => writeln!(b, "[EMATHFUN1] Domain error for {func} function."),
    };
    cx.write(router::WERROR, b.as_str());
    EvalError::new(EvalErrorKind::Reported)
}

fn domain(cx: &mut Core<'_>, func: &str) -> Result<Value, EvalError> {
    Err(math_error(cx, "EMATHFUN1", func))
}

fn singularity(cx: &mut Core<'_>, func: &str) -> Result<Value, EvalError> {
    Err(math_error(cx, "EMATHFUN3", func))
}

fn near_zero(x: f64) -> bool {
    x < SMALLEST_ALLOWED_NUMBER && x > -SMALLEST_ALLOWED_NUMBER
}

fn float(x: f64) -> Result<Value, EvalError> {
    Ok(Value::Float(x))
}

// CLIPS's own inverse hyperbolic formulas (the C library's differ in the last bits)
fn gen_acosh(x: f64) -> f64 {
    super::cmath::log(x + libm::sqrt(x * x - 1.0))
}
fn gen_asinh(x: f64) -> f64 {
    super::cmath::log(x + libm::sqrt(x * x + 1.0))
}
fn gen_atanh(x: f64) -> f64 {
    0.5 * super::cmath::log((1.0 + x) / (1.0 - x))
}
fn gen_asech(x: f64) -> f64 {
    super::cmath::log(1.0 / x + libm::sqrt(1.0 / (x * x) - 1.0))
}
fn gen_acsch(x: f64) -> f64 {
    super::cmath::log(1.0 / x + libm::sqrt(1.0 / (x * x) + 1.0))
}
fn gen_acoth(x: f64) -> f64 {
    0.5 * super::cmath::log((x + 1.0) / (x - 1.0))
}

fn sinh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(super::cmath::sinh(float_arg(cx, a, "sinh")?))
}
fn cosh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(super::cmath::cosh(float_arg(cx, a, "cosh")?))
}
fn tanh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(super::cmath::tanh(float_arg(cx, a, "tanh")?))
}
fn sech(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(1.0 / super::cmath::cosh(float_arg(cx, a, "sech")?))
}
fn csch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "csch")?;
    if x == 0.0 {
        return singularity(cx, "csch");
    }
    float(1.0 / super::cmath::sinh(x))
}
fn coth(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "coth")?;
    if x == 0.0 {
        return singularity(cx, "coth");
    }
    float(1.0 / super::cmath::tanh(x))
}
fn asinh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(gen_asinh(float_arg(cx, a, "asinh")?))
}
fn acosh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "acosh")?;
    if x < 1.0 {
        return domain(cx, "acosh");
    }
    float(gen_acosh(x))
}
fn atanh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "atanh")?;
    if x >= 1.0 || x <= -1.0 {
        return domain(cx, "atanh");
    }
    float(gen_atanh(x))
}
fn asech(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "asech")?;
    if x > 1.0 || x <= 0.0 {
        return domain(cx, "asech");
    }
    float(gen_asech(x))
}
fn acsch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "acsch")?;
    if x == 0.0 {
        return domain(cx, "acsch");
    }
    float(gen_acsch(x))
}
fn acoth(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "acoth")?;
    if (-1.0..=1.0).contains(&x) {
        return domain(cx, "acoth");
    }
    float(gen_acoth(x))
}
fn sec(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let c = super::cmath::cos(float_arg(cx, a, "sec")?);
    if near_zero(c) {
        return singularity(cx, "sec");
    }
    float(1.0 / c)
}
fn csc(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = super::cmath::sin(float_arg(cx, a, "csc")?);
    if near_zero(s) {
        return singularity(cx, "csc");
    }
    float(1.0 / s)
}
fn cot(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "cot")?;
    if near_zero(super::cmath::sin(x)) {
        return singularity(cx, "cot");
    }
    float(1.0 / libm::tan(x))
}
fn asec(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "asec")?;
    if x < 1.0 && x > -1.0 {
        return domain(cx, "asec");
    }
    float(super::cmath::acos(1.0 / x))
}
fn acsc(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "acsc")?;
    if x < 1.0 && x > -1.0 {
        return domain(cx, "acsc");
    }
    float(super::cmath::asin(1.0 / x))
}
fn acot(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_arg(cx, a, "acot")?;
    if x == 0.0 {
        return float(FRAC_PI_2);
    }
    float(super::cmath::atan(1.0 / x))
}
/// 90 degrees are 100 grads.
fn deg_grad(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(float_arg(cx, a, "deg-grad")? / 0.9)
}
fn grad_deg(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    float(float_arg(cx, a, "grad-deg")? * 0.9)
}

// ---- the older multifield functions with their own argument order ----

/// `(mv-subseq s e m)`: `subseq$` with the multifield last; indices clamped.
fn mv_subseq(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = int_arg(cx, a, 0, "mv-subseq")?;
    let e = int_arg(cx, a, 1, "mv-subseq")?;
    let m = multi_arg(cx, a, 2, "mv-subseq")?;
    let (s, e) = (s.max(1), e.min(m.len as i64));
    Ok(if s > e {
        slice(m, 0, 0)
    } else {
        slice(m, s as usize - 1, e as usize)
    })
}

/// The 1-based index `i` of `m`, checked as CLIPS checks it.
fn one_index(
    cx: &mut Core<'_>,
    func: &'static str,
    i: i64,
    len: usize,
) -> Result<usize, EvalError> {
    if i < 1 || i > len as i64 {
        return Err(index_error(cx, func, i, i, len));
    }
    Ok(i as usize - 1)
}

/// `(mv-delete i m)`: `m` without element `i`.
fn mv_delete(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let i = int_arg(cx, a, 0, "mv-delete")?;
    let m = multi_arg(cx, a, 1, "mv-delete")?;
    let at = one_index(cx, "mv-delete", i, m.len as usize)?;
    let start = cx.multi_begin();
    push_range(cx, m, 0, at)?;
    push_range(cx, m, at + 1, m.len as usize)?;
    Ok(cx.multi_finish(start))
}

/// `(mv-replace i m v)`: element `i` of `m` replaced by `v` (a multifield spliced in).
fn mv_replace(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let i = int_arg(cx, a, 0, "mv-replace")?;
    let m = multi_arg(cx, a, 1, "mv-replace")?;
    let at = one_index(cx, "mv-replace", i, m.len as usize)?;
    let start = cx.multi_begin();
    push_range(cx, m, 0, at)?;
    let v = cx.arg(a, 2);
    push_flat(cx, v)?;
    push_range(cx, m, at + 1, m.len as usize)?;
    Ok(cx.multi_finish(start))
}

/// `pointerp` asks for an external address; this engine has none.
fn pointerp(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(SYM_FALSE))
}

/// `(setgen n)`: the next `gensym` is `genN`; n below 1 is an error that leaves it.
fn setgen(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let now = Value::Int(i64::from(cx.st.eval.gensym_next));
    // a computed float is truncated (a literal one is refused while parsing)
    let n = match cx.arg(a, 0) {
        Value::Int(n) => n,
        Value::Float(f) => super::math::c_trunc_to_i64(f),
        _ => {
            cx.set_error_fallback(now, None);
            return Err(EvalError::wrong_type("setgen", 1, super::math::T_INTEGER));
        }
    };
    if n < 1 || n > i64::from(u32::MAX) {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function setgen expected argument #1 to be of type number (greater than or equal to 1)\n",
        );
        cx.set_error_fallback(now, None);
        return Err(EvalError::new(EvalErrorKind::Reported));
    }
    cx.st.eval.gensym_next = n as u32;
    Ok(Value::Int(n))
}

// ---- settings this engine has one value of ----

/// The refusal of a setting this engine does not implement: an error naming the one
/// value it has.
fn refuse(cx: &mut Core<'_>, func: &str, only: &str) -> EvalError {
    let mut b: TextBuf<160> = TextBuf::new();
    let _ = writeln!(
        b,
        "[NOTIMPL1] robotino-agent implements only ({func} {only})"
    );
    cx.write(router::WERROR, b.as_str());
    EvalError::already_reported()
}

fn is_false(v: Value) -> bool {
    matches!(v, Value::Sym(SYM_FALSE))
}

/// `/` of integers always gives a float here (CLIPS's default, TRUE).
fn get_auto_float_dividend(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(SYM_TRUE))
}
fn set_auto_float_dividend(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if is_false(cx.arg(a, 0)) {
        return Err(refuse(cx, "set-auto-float-dividend", "TRUE"));
    }
    Ok(Value::Sym(SYM_TRUE))
}

/// Whether every new fact's slot values are checked (off by default, as in CLIPS:
/// literals are checked when constructs and commands are parsed).
fn get_dynamic_constraint_checking(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(cx.st.mode.dynamic_checks))
}
/// Any value but FALSE turns it on; the old setting is returned.
fn set_dynamic_constraint_checking(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = cx.st.mode.dynamic_checks;
    cx.st.mode.dynamic_checks = !is_false(cx.arg(a, 0));
    Ok(Core::bool_value(old))
}

/// Whether an assert of a fact equal to a live one makes a second fact: any value but
/// FALSE turns it on; the old setting is returned.
fn set_fact_duplication(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = cx.st.mode.fact_duplication;
    let on = !is_false(cx.arg(a, 0));
    cx.st.mode.fact_duplication = on;
    cx.st.mode.twins_made |= on;
    Ok(Core::bool_value(old))
}

/// Whether `$?x` in a function call's arguments is a sequence expansion (`expand$`),
/// read when calls are parsed (CLIPS's default is FALSE: `$?x` is `?x`).
fn get_sequence_operator_recognition(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(cx.st.mode.seq_ops))
}
/// Any value but FALSE turns recognition on; the old setting is returned.
fn set_sequence_operator_recognition(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = cx.st.mode.seq_ops;
    // (a computed value that is no symbol: the setting stays, its value returned)
    if !matches!(cx.arg(a, 0), Value::Sym(_)) {
        cx.set_error_fallback(Core::bool_value(old), None);
        return Err(EvalError::wrong_type(
            "set-sequence-operator-recognition",
            1,
            "symbol",
        ));
    }
    cx.st.mode.seq_ops = !is_false(cx.arg(a, 0));
    Ok(Core::bool_value(old))
}

/// Literal slot values are checked when constructs and commands are read (CLIPS's
/// default, TRUE).
fn get_static_constraint_checking(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(SYM_TRUE))
}
fn set_static_constraint_checking(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if is_false(cx.arg(a, 0)) {
        return Err(refuse(cx, "set-static-constraint-checking", "TRUE"));
    }
    Ok(Value::Sym(SYM_TRUE))
}

/// Whether a rule defined while facts exist is matched against them at once (CLIPS's
/// default, TRUE).
fn get_incremental_reset(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(!no_incremental_reset(cx)))
}

/// `(set-incremental-reset FALSE)` is in force (the image has only CLIPS's default).
fn no_incremental_reset(cx: &Core<'_>) -> bool {
    #[cfg(feature = "extras")]
    return cx.st.mode.no_incremental_reset;
    #[cfg(not(feature = "extras"))]
    {
        let _ = cx;
        false
    }
}
/// Any value but FALSE turns it on; the old setting is returned. With FALSE a new
/// rule starts unmatched: its new joins and alpha nodes see only later facts, until
/// `reset`.
fn set_incremental_reset(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = Core::bool_value(!no_incremental_reset(cx));
    if (0..cx.st.pools.nrules).any(|r| !cx.rules[r as usize].deleted) {
        // CLIPS checks this first, whatever the value, and returns the old one
        cx.write(
            router::WERROR,
            "[INCRRSET1] The incremental reset behavior cannot be changed with rules loaded.\n",
        );
        return Ok(old);
    }
    #[cfg(feature = "extras")]
    {
        cx.st.mode.no_incremental_reset = is_false(cx.arg(a, 0));
    }
    #[cfg(not(feature = "extras"))]
    if is_false(cx.arg(a, 0)) {
        return Err(refuse(cx, "set-incremental-reset", "TRUE"));
    }
    Ok(old)
}

/// Whether `reset` gives every defglobal its initial value back (CLIPS's default,
/// TRUE).
fn get_reset_globals(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(!cx.st.mode.keep_globals))
}
/// Any value but FALSE turns it on; the old setting is returned.
fn set_reset_globals(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = !cx.st.mode.keep_globals;
    cx.st.mode.keep_globals = is_false(cx.arg(a, 0));
    Ok(Core::bool_value(old))
}

/// What Debian's build of CLIPS 6.30 answers: it was compiled without naming its
/// system.
fn operating_system(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(cx.intern("UNKNOWN")?))
}

/// CLIPS's three settings, by `agenda::SALIENCE_*` value.
#[cfg(feature = "extras")]
const SALIENCE_EVALUATIONS: [&str; 3] = ["when-defined", "when-activated", "every-cycle"];

/// When a rule's salience expression is evaluated (`agenda::SALIENCE_*`).
#[cfg(feature = "extras")]
fn get_salience_evaluation(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let i = usize::from(cx.st.mode.salience_eval);
    Ok(Value::Sym(cx.intern(SALIENCE_EVALUATIONS[i % 3])?))
}
/// The setting before; CLIPS's messages for a value that is not one of the three.
#[cfg(feature = "extras")]
fn set_salience_evaluation(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old =
        Value::Sym(cx.intern(SALIENCE_EVALUATIONS[usize::from(cx.st.mode.salience_eval) % 3])?);
    let s = match cx.arg(a, 0) {
        Value::Sym(s) => s,
        _ => {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function set-salience-evaluation expected argument #1 to be of type symbol\n",
            );
            // (the setting's value, as CLIPS returns it)
            cx.set_error_fallback(old, None);
            return Err(EvalError::new(crate::error::EvalErrorKind::Reported));
        }
    };
    match SALIENCE_EVALUATIONS
        .iter()
        .position(|&n| n == cx.sym_text(s))
    {
        Some(i) => {
            // (three settings: the index fits)
            cx.st.mode.salience_eval = i as u8;
            // (the run loop refreshes saliences on its general path)
            cx.note_run_slow();
            Ok(old)
        }
        None => {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function set-salience-evaluation expected argument #1 to be of type symbol with value when-defined, when-activated, or every-cycle\n",
            );
            cx.set_error_fallback(old, None);
            Err(EvalError::new(EvalErrorKind::Reported))
        }
    }
}

#[cfg(all(test, feature = "extras"))]
mod tests {
    extern crate std;
    use crate::testutil::eval_to_string;

    /// A setting this engine has one value of: that value is accepted, any other is
    /// refused with an error naming the one it has (never accepted and ignored).
    #[test]
    fn settings_other_than_the_one_implemented_are_refused() {
        let out = eval_to_string("(set-auto-float-dividend FALSE)");
        assert!(
            out.contains("[NOTIMPL1]") && out.contains("(set-auto-float-dividend TRUE)"),
            "{out}"
        );
        assert_eq!(eval_to_string("(set-auto-float-dividend TRUE)"), "TRUE");
    }

    /// Each of CLIPS's three salience evaluation settings is kept; the call gives the
    /// one before.
    #[test]
    fn salience_evaluation_settings_are_kept() {
        assert_eq!(
            eval_to_string(
                "(create$ (set-salience-evaluation every-cycle) (get-salience-evaluation) \
                 (set-salience-evaluation when-activated) (set-salience-evaluation when-defined) \
                 (get-salience-evaluation))"
            ),
            "(when-defined every-cycle every-cycle when-activated when-defined)"
        );
    }

    #[test]
    fn inverse_functions_undo_their_functions() {
        for x in ["0.3", "1.7", "-2.2"] {
            for (f, g) in [("sinh", "asinh"), ("csch", "acsch"), ("tanh", "atanh")] {
                let got: f64 = eval_to_string(&std::format!("({g} ({f} {x}))"))
                    .parse()
                    .unwrap();
                let want: f64 = x.parse().unwrap();
                assert!((got - want).abs() < 1e-9, "({g} ({f} {x})) = {got}");
            }
        }
        assert_eq!(eval_to_string("(grad-deg (deg-grad 27))"), "27.0");
    }
}

/// `(system ARG...)`: Debian's CLIPS 6.30 is built without a system call; it says so
/// and returns nothing, and so does this one (a host command from a rule base is not
/// something the engine offers).
fn system(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    // (each argument checked first, a computed one too)
    for i in 0..a.len as usize {
        if !matches!(cx.arg(a, i), Value::Sym(_) | Value::Str(_)) {
            return Err(EvalError::wrong_type(
                "system",
                crate::error::arg_no(i),
                "symbol or string",
            ));
        }
    }
    cx.write(
        router::STDOUT,
        "System function not fully defined for this system.\n",
    );
    Ok(Value::Void)
}
