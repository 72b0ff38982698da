//! Builtins: integer and float arithmetic beyond `+ - * /` (div mod abs min max ** sqrt
//! round integer float exp log log10, trigonometry), as CLIPS 6.30 computes them.
//!
//! Also the argument helpers the other builtin modules of this helper share: they
//! produce CLIPS's own `[ARGACCES5]` type names ("integer or float", "symbol, string,
//! or instance name", ...).

use super::describe::ArgType::{Any, Number as N};
use super::describe::Returns as R;
use super::describe::{BodyNames, OnError};
use super::{Args, Builtin, Num, ANY};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::value::{SymId, Value};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("div", 2, ANY, div).args(&[], N).on_error(OnError::One).quiet().returns(R::Integer),
    Builtin::eager("mod", 2, 2, modulo).args(&[], N).on_error(OnError::Zero).quiet().returns(R::Number),
    Builtin::eager("abs", 1, 1, abs).args(&[N], Any).on_error(OnError::Zero).quiet().returns(R::Number),
    Builtin::lazy("min", 2, ANY, min_in_order).args(&[], N).quiet().returns(R::Number),
    Builtin::lazy("max", 2, ANY, max_in_order).args(&[], N).quiet().returns(R::Number),
    Builtin::eager("**", 2, 2, pow).args(&[], N).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("sqrt", 1, 1, sqrt).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("round", 1, 1, round).args(&[N], Any).on_error(OnError::Zero).quiet().returns(R::Integer),
    Builtin::eager("integer", 1, 1, integer).args(&[N], Any).on_error(OnError::Zero).quiet().body_names(BodyNames::Integer).returns(R::Integer),
    Builtin::eager("float", 1, 1, float).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("exp", 1, 1, exp).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("log", 1, 1, log).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("log10", 1, 1, log10).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("pi", 0, 0, pi).quiet().returns(R::Float),
    Builtin::eager("sin", 1, 1, sin).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("cos", 1, 1, cos).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("tan", 1, 1, tan).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("asin", 1, 1, asin).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("acos", 1, 1, acos).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("atan", 1, 1, atan).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("deg-rad", 1, 1, deg_rad).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
    Builtin::eager("rad-deg", 1, 1, rad_deg).args(&[N], Any).on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float).returns(R::Float),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

// ---- argument helpers shared by this helper's modules ----

/// CLIPS's type names in `[ARGACCES5]` messages.
pub(super) const T_NUMBER: &str = "integer or float";
pub(super) const T_INTEGER: &str = "integer";
pub(super) const T_LEXEME: &str = "symbol, string, or instance name";
pub(super) const T_MULTI: &str = "multifield";
pub(super) const T_ATOM: &str = "string, instance name, symbol, float, or integer";

/// A number argument (1-based position `i + 1` in the error).
pub(super) fn num_arg(
    cx: &Core<'_>,
    a: Args,
    i: usize,
    func: &'static str,
) -> Result<Num, EvalError> {
    match cx.arg(a, i) {
        Value::Int(x) => Ok(Num::Int(x)),
        Value::Float(x) => Ok(Num::Float(x)),
        _ => Err(EvalError::wrong_type(
            func,
            crate::error::arg_no(i),
            T_NUMBER,
        )),
    }
}

/// An integer argument. A literal `1.0` where an index is expected is refused when
/// the call is parsed; a float computed at run time is taken truncated, as CLIPS's
/// `ArgTypeCheck(INTEGER)` converts it (`(nth$ ?x ...)` with `?x` 2.0 is the 2nd).
pub(super) fn int_arg(
    cx: &Core<'_>,
    a: Args,
    i: usize,
    func: &'static str,
) -> Result<i64, EvalError> {
    match cx.arg(a, i) {
        Value::Int(x) => Ok(x),
        Value::Float(x) => Ok(x as i64),
        _ => Err(EvalError::wrong_type(
            func,
            crate::error::arg_no(i),
            T_INTEGER,
        )),
    }
}

/// A symbol or string argument.
pub(super) fn lexeme_arg(
    cx: &Core<'_>,
    a: Args,
    i: usize,
    func: &'static str,
) -> Result<SymId, EvalError> {
    match cx.arg(a, i) {
        Value::Sym(s) | Value::Str(s) => Ok(s),
        _ => Err(EvalError::wrong_type(
            func,
            crate::error::arg_no(i),
            T_LEXEME,
        )),
    }
}

/// `[EMATHFUN1]` for the named function.
pub(super) fn domain_error(func: &'static str) -> EvalError {
    use crate::error::Message;
    EvalError::message(match func {
        "sqrt" => Message::SqrtDomain,
        "**" => Message::PowDomain,
        "log" => Message::LogDomain,
        "log10" => Message::Log10Domain,
        "asin" => Message::AsinDomain,
        "acos" => Message::AcosDomain,
        _ => Message::Domain,
    })
}

/// `[EMATHFUN2]`: CLIPS's message for `log`/`log10` of zero.
fn overflow_error(func: &'static str) -> EvalError {
    EvalError::message(match func {
        "log" => crate::error::Message::LogOverflow,
        _ => crate::error::Message::Log10Overflow,
    })
}

fn divide_by_zero(func: &'static str) -> EvalError {
    EvalError::new(EvalErrorKind::DivideByZero { func })
}

/// C's `(long long) x` on x86: out-of-range values and NaN become `i64::MIN` (the
/// "integer indefinite" of both SSE `cvttsd2si` and x87 `fistp`), which is what CLIPS
/// prints for `(integer 1e30)`. Rust's `as` would saturate instead.
pub(crate) fn c_trunc_to_i64(x: f64) -> i64 {
    const LIMIT: f64 = 9_223_372_036_854_775_808.0; // 2^63
    if x.is_nan() || !(-LIMIT..LIMIT).contains(&x) {
        i64::MIN
    } else {
        x as i64
    }
}

fn float_of(cx: &Core<'_>, a: Args, i: usize, func: &'static str) -> Result<f64, EvalError> {
    Ok(num_arg(cx, a, i, func)?.as_f64())
}

// ---- the functions ----

/// Integer division, truncating toward zero; float arguments are truncated first.
fn div(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let as_int = |n: Num| match n {
        Num::Int(i) => i,
        Num::Float(f) => c_trunc_to_i64(f),
    };
    let mut acc = as_int(num_arg(cx, a, 0, "div").inspect_err(|_| {
        cx.set_error_fallback(Value::Int(0), None);
    })?);
    for i in 1..a.len as usize {
        // CLIPS goes on with 0 for a bad divisor and so also divides by zero
        let d = as_int(
            num_arg(cx, a, i, "div")
                .inspect_err(|_| cx.set_error_fallback(Value::Int(1), Some("div")))?,
        );
        if d == 0 {
            return Err(divide_by_zero("div"));
        }
        acc = acc.wrapping_div(d);
    }
    Ok(Value::Int(acc))
}

/// Remainder with C's sign rule (`(mod -7 3)` is -1); with a float argument
/// `a - trunc(a / b) * b`.
fn modulo(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = num_arg(cx, a, 0, "mod")?;
    let y = num_arg(cx, a, 1, "mod")?;
    if y.as_f64() == 0.0 {
        return Err(divide_by_zero("mod"));
    }
    Ok(match (x, y) {
        (Num::Int(p), Num::Int(q)) => Value::Int(p.wrapping_rem(q)),
        (p, q) => {
            let (p, q) = (p.as_f64(), q.as_f64());
            Value::Float(p - libm::trunc(p / q) * q)
        }
    })
}

fn abs(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(match num_arg(cx, a, 0, "abs")? {
        Num::Int(i) => Value::Int(i.wrapping_abs()),
        // CLIPS negates only values below zero, so -0.0 stays -0.0.
        Num::Float(f) => Value::Float(if f < 0.0 { -f } else { f }),
    })
}

/// Numeric order of two CLIPS numbers (ints compared exactly).
pub(crate) fn less(p: Num, q: Num) -> bool {
    match (p, q) {
        (Num::Int(x), Num::Int(y)) => x < y,
        (x, y) => x.as_f64() < y.as_f64(),
    }
}

/// `min`/`max` return the winning argument with its own type; on ties the earlier one.
fn extremum(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    better: fn(Num, Num) -> bool,
) -> Result<Value, EvalError> {
    let mut best = num_arg(cx, a, 0, func).inspect_err(|_| {
        cx.set_error_fallback(Value::Int(0), None);
    })?;
    for i in 1..a.len as usize {
        // CLIPS returns the best so far
        let x = num_arg(cx, a, i, func).inspect_err(|_| {
            cx.set_error_fallback(best.value(), None);
        })?;
        if better(x, best) {
            best = x;
        }
    }
    Ok(best.value())
}

pub(super) fn min(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    extremum(cx, a, "min", less)
}

pub(super) fn max(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    extremum(cx, a, "max", |x, best| less(best, x))
}

fn min_in_order(cx: &mut Core<'_>, call: crate::value::Ix) -> Result<Value, EvalError> {
    extremum_in_order(cx, call, "min", less)
}

fn max_in_order(cx: &mut Core<'_>, call: crate::value::Ix) -> Result<Value, EvalError> {
    extremum_in_order(cx, call, "max", |x, best| less(best, x))
}

/// `min`/`max` of call `call` as CLIPS's bodies run them (`ArgTypeCheck` per
/// argument): each argument is evaluated and checked before the next runs, and one
/// that sets CLIPS's evaluation error (an unbound global, a failing call) stops the
/// call with the best so far (0 for none) and no `[ARGACCES5]`
/// (`(max 4 ?*u* (printout t x))` is 4 and prints nothing).
fn extremum_in_order(
    cx: &mut Core<'_>,
    call: crate::value::Ix,
    func: &'static str,
    better: fn(Num, Num) -> bool,
) -> Result<Value, EvalError> {
    let halting = cx.st.mode.halting;
    let mut best: Option<Num> = None;
    let mut a = cx.exprs[call as usize].first;
    let mut i = 0;
    let so_far = |best: Option<Num>| best.map_or(Value::Int(0), Num::value);
    while a != crate::value::NONE {
        let v = match cx.eval_operand(a) {
            Ok(v) => v,
            #[cfg(feature = "extras")]
            Err(e) => {
                // its message and value (CLIPS's evaluation error set)
                cx.value_after_error(a, e)?;
                cx.st.mode.halting = halting;
                cx.set_error_fallback(so_far(best), None);
                let mut e = e;
                e.reported = true;
                return Err(e);
            }
            #[cfg(not(feature = "extras"))]
            Err(e) => return Err(e),
        };
        if cx.st.mode.halting && (!halting || cx.arg_error()) {
            return Ok(so_far(best));
        }
        let x = match v {
            Value::Int(x) => Num::Int(x),
            Value::Float(x) => Num::Float(x),
            _ => {
                cx.set_error_fallback(so_far(best), None);
                // (a literal of another type was refused as the call was read)
                return Err(EvalError::wrong_type(
                    func,
                    crate::error::arg_no(i),
                    T_NUMBER,
                ));
            }
        };
        if best.is_none_or(|b| better(x, b)) {
            best = Some(x);
        }
        i += 1;
        a = cx.exprs[a as usize].next;
    }
    Ok(so_far(best))
}

/// `**` always yields a float; `0 ** y<=0` and a negative base with a fractional
/// exponent are domain errors in CLIPS.
fn pow(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_of(cx, a, 0, "**")?;
    let y = float_of(cx, a, 1, "**")?;
    if (x == 0.0 && y <= 0.0) || (x < 0.0 && libm::trunc(y) != y) {
        return Err(domain_error("**"));
    }
    Ok(Value::Float(super::cmath::pow(x, y)))
}

fn sqrt(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_of(cx, a, 0, "sqrt")?;
    if x < 0.0 {
        return Err(domain_error("sqrt"));
    }
    Ok(Value::Float(libm::sqrt(x)))
}

/// CLIPS 6.30 rounds halves toward negative infinity: `ceil(x - 0.5)`.
fn round(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(match num_arg(cx, a, 0, "round")? {
        Num::Int(i) => i,
        Num::Float(f) => c_trunc_to_i64(libm::ceil(f - 0.5)),
    }))
}

fn integer(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(match num_arg(cx, a, 0, "integer")? {
        Num::Int(i) => i,
        Num::Float(f) => c_trunc_to_i64(f),
    }))
}

fn float(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Value::Float(float_of(cx, a, 0, "float")?))
}

fn exp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Value::Float(super::cmath::exp(float_of(cx, a, 0, "exp")?)))
}

/// Shared checks of `log`/`log10`: zero overflows, negatives are outside the domain.
fn logarithm(
    cx: &Core<'_>,
    a: Args,
    func: &'static str,
    f: fn(f64) -> f64,
) -> Result<Value, EvalError> {
    let x = float_of(cx, a, 0, func)?;
    if x < 0.0 {
        return Err(domain_error(func));
    }
    if x == 0.0 {
        return Err(overflow_error(func));
    }
    Ok(Value::Float(f(x)))
}

fn log(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    logarithm(cx, a, "log", super::cmath::log)
}

fn log10(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    logarithm(cx, a, "log10", super::cmath::log10)
}

fn pi(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Float(core::f64::consts::PI))
}

fn unary(
    cx: &Core<'_>,
    a: Args,
    func: &'static str,
    f: fn(f64) -> f64,
) -> Result<Value, EvalError> {
    Ok(Value::Float(f(float_of(cx, a, 0, func)?)))
}

fn sin(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    unary(cx, a, "sin", super::cmath::sin)
}
fn cos(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    unary(cx, a, "cos", super::cmath::cos)
}
/// CLIPS refuses a tangent whose cosine is within 1e-15 of zero (`(tan (/ (pi) 2))`),
/// and divides the sine by that cosine (which is not always `tan`'s value to the last
/// digit: `(tan 0.6706148272166867)` is 0.793255396321826, `tan` gives ...825).
fn tan(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = float_of(cx, a, 0, "tan")?;
    let c = super::cmath::cos(x);
    if c < 1e-15 && c > -1e-15 {
        return Err(EvalError::message(crate::error::Message::TanSingularity));
    }
    Ok(Value::Float(super::cmath::sin(x) / c))
}
fn atan(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    unary(cx, a, "atan", super::cmath::atan)
}

/// `asin`/`acos` are defined on [-1, 1] only.
fn arc(cx: &Core<'_>, a: Args, func: &'static str, f: fn(f64) -> f64) -> Result<Value, EvalError> {
    let x = float_of(cx, a, 0, func)?;
    if !(-1.0..=1.0).contains(&x) {
        return Err(domain_error(func));
    }
    Ok(Value::Float(f(x)))
}

fn asin(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    arc(cx, a, "asin", super::cmath::asin)
}
fn acos(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    arc(cx, a, "acos", super::cmath::acos)
}

fn deg_rad(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    unary(cx, a, "deg-rad", |d| d * core::f64::consts::PI / 180.0)
}
fn rad_deg(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    unary(cx, a, "rad-deg", |r| r * 180.0 / core::f64::consts::PI)
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::eval_to_string;

    /// Parses a printed float and checks it against `want` within `tol`.
    fn close(expr: &str, want: f64, tol: f64) {
        let got = eval_to_string(expr);
        let x: f64 = got
            .parse()
            .unwrap_or_else(|_| panic!("{expr} printed {got:?}"));
        assert!((x - want).abs() <= tol, "{expr} printed {got}, want {want}");
    }

    #[test]
    fn div_truncates_toward_zero() {
        // values from CLIPS 6.30 (tests/clips/047)
        assert_eq!(eval_to_string("(div 7 2)"), "3");
        assert_eq!(eval_to_string("(div -7 2)"), "-3");
        assert_eq!(eval_to_string("(div 20 3 2)"), "3");
        assert_eq!(eval_to_string("(div 7 2.5)"), "3");
        assert_eq!(eval_to_string("(div 7.9 2.9)"), "3");
        assert!(
            eval_to_string("(div 7 0)").contains("divide")
                || eval_to_string("(div 7 0)").contains("zero")
        );
        assert!(eval_to_string("(div 7 0.5)").contains("zero"));
    }

    #[test]
    fn mod_follows_c() {
        assert_eq!(eval_to_string("(mod 7 3)"), "1");
        assert_eq!(eval_to_string("(mod -7 3)"), "-1");
        assert_eq!(eval_to_string("(mod 7 -3)"), "1");
        assert_eq!(eval_to_string("(mod 7.5 2)"), "1.5");
        assert_eq!(eval_to_string("(mod 7 2.5)"), "2.0");
        assert_eq!(eval_to_string("(mod -7.5 2)"), "-1.5");
        assert_eq!(eval_to_string("(mod 7.0 2)"), "1.0");
        assert!(eval_to_string("(mod 7 0.0)").contains("zero"));
    }

    #[test]
    fn abs_min_max_keep_types() {
        assert_eq!(eval_to_string("(abs -5)"), "5");
        assert_eq!(eval_to_string("(abs -2.5)"), "2.5");
        assert_eq!(eval_to_string("(abs -0.0)"), "-0.0");
        assert_eq!(eval_to_string("(min 3 1 2)"), "1");
        assert_eq!(eval_to_string("(max 3 1 2)"), "3");
        assert_eq!(eval_to_string("(min 1 2.0)"), "1");
        assert_eq!(eval_to_string("(max 1 2.0)"), "2.0");
        assert_eq!(eval_to_string("(max 3 2.0)"), "3");
        assert_eq!(eval_to_string("(min 2.0 2)"), "2.0");
        assert_eq!(eval_to_string("(max 2 2.0)"), "2");
        assert_eq!(eval_to_string("(max -1 -1.5 3 3.0)"), "3");
    }

    #[test]
    fn wrong_types_name_the_argument() {
        let out = eval_to_string("(max 1 (create$ x))");
        assert!(
            out.contains("max") && out.contains("#2") && out.contains("integer or float"),
            "{out}"
        );
    }

    #[test]
    fn powers_and_roots_are_floats() {
        assert_eq!(eval_to_string("(** 2 10)"), "1024.0");
        assert_eq!(eval_to_string("(** -8 2)"), "64.0");
        assert_eq!(eval_to_string("(** 2.0 -1)"), "0.5");
        close("(** 2 0.5)", core::f64::consts::SQRT_2, 1e-12);
        assert_eq!(eval_to_string("(sqrt 16)"), "4.0");
        assert_eq!(eval_to_string("(sqrt 2.25)"), "1.5");
        close("(sqrt 2)", core::f64::consts::SQRT_2, 1e-12);
        assert!(eval_to_string("(sqrt -1)").contains("Domain error for sqrt"));
        assert!(eval_to_string("(** 0 0)").contains("Domain error for **"));
        assert!(eval_to_string("(** -2 0.5)").contains("Domain error for **"));
    }

    #[test]
    fn round_halves_down_integer_truncates() {
        for (e, want) in [
            ("(round 2.5)", "2"),
            ("(round 3.5)", "3"),
            ("(round -2.5)", "-3"),
            ("(round 0.5)", "0"),
            ("(round -0.5)", "-1"),
            ("(round 2.6)", "3"),
            ("(round -2.6)", "-3"),
            ("(round -0.4)", "0"),
            ("(round 7)", "7"),
            ("(integer 3.9)", "3"),
            ("(integer -3.9)", "-3"),
            ("(integer 1e30)", "-9223372036854775808"),
            ("(float 3)", "3.0"),
            ("(float 2.5)", "2.5"),
        ] {
            assert_eq!(eval_to_string(e), want, "{e}");
        }
    }

    #[test]
    fn exp_log_trig() {
        close("(exp 1)", core::f64::consts::E, 1e-12);
        assert_eq!(eval_to_string("(exp 0)"), "1.0");
        close("(log 10)", core::f64::consts::LN_10, 1e-12);
        assert_eq!(eval_to_string("(log10 1000)"), "3.0");
        assert!(eval_to_string("(log 0)").contains("Argument overflow for log function"));
        assert!(eval_to_string("(log10 -1)").contains("Domain error for log10"));
        close("(pi)", core::f64::consts::PI, 1e-12);
        close("(sin 1)", 0.841470984807897, 1e-12);
        close("(cos 1)", 0.54030230586814, 1e-12);
        close("(atan 1)", core::f64::consts::FRAC_PI_4, 1e-12);
        close("(deg-rad 180)", core::f64::consts::PI, 1e-12);
        close("(rad-deg 1)", 57.2957795130823, 1e-9);
        assert_eq!(eval_to_string("(acos 1)"), "0.0");
        assert!(eval_to_string("(acos 2)").contains("Domain error for acos"));
    }
}
