//! Arithmetic, comparison, equality, boolean connectives and `str-cat`.

use super::describe::ArgType::Number as N;
use super::describe::OnError;
use super::describe::Returns as R;
use super::{Args, Builtin, Num, ANY};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::value::Ix;
use crate::value::{Value, NONE};

/// Function ids of the two-argument comparisons that `eval` and the quick alpha
/// tests decide in place: `=`, `<>`, `<`, `<=`, `>`, `>=`, `eq`, `neq`, in this
/// order (table 0 is this module's).
pub const CMP_FIRST: Ix = 4;
pub const CMP_LAST: Ix = 11;

/// Function ids of `+`, `-`, `*` (in this order, from `ARITH_FIRST`), whose two-number
/// calls `eval` computes in place on the host (`num_arith`); below `CMP_FIRST`.
#[cfg(feature = "host-speedups")]
pub const ARITH_FIRST: Ix = super::builtin_id("+");
#[cfg(feature = "host-speedups")]
const _: () = assert!(
    super::builtin_id("-") == ARITH_FIRST + 1
        && super::builtin_id("*") == ARITH_FIRST + 2
        && ARITH_FIRST + 2 < CMP_FIRST
);

/// `+`, `-` or `*` (`id`, from `ARITH_FIRST`) of two numbers `p`, `q` (Int or Float),
/// as `fold` computes it: integers wrap, a float makes the result a float.
#[cfg(feature = "host-speedups")]
#[inline(always)]
pub(crate) fn num_arith(id: Ix, p: Value, q: Value) -> Value {
    let op = id - ARITH_FIRST;
    if let (Value::Int(p), Value::Int(q)) = (p, q) {
        return Value::Int(match op {
            0 => p.wrapping_add(q),
            1 => p.wrapping_sub(q),
            _ => p.wrapping_mul(q),
        });
    }
    let f = |v: Value| match v {
        Value::Int(i) => i as f64,
        Value::Float(x) => x,
        _ => 0.0,
    };
    let (p, q) = (f(p), f(q));
    Value::Float(match op {
        0 => p + q,
        1 => p - q,
        _ => p * q,
    })
}

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("+", 2, ANY, add).args(&[], N).quiet().returns(R::Number),
    Builtin::eager("-", 2, ANY, sub).args(&[], N).quiet().returns(R::Number),
    Builtin::eager("*", 2, ANY, mul).args(&[], N).quiet().returns(R::Number),
    Builtin::eager("/", 2, ANY, div).args(&[], N).on_error(OnError::FloatOne).quiet().returns(R::Number),
    Builtin::eager("=", 2, ANY, num_eq).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager("<>", 2, ANY, num_ne).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager("<", 2, ANY, lt).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager("<=", 2, ANY, le).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager(">", 2, ANY, gt).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager(">=", 2, ANY, ge).args(&[], N).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager("eq", 2, ANY, eq).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("neq", 2, ANY, neq).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::lazy("and", 2, ANY, and).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::lazy("or", 2, ANY, or).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("not", 1, 1, not).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::lazy("str-cat", 1, ANY, super::strings::str_cat_in_order).on_error(OnError::EmptyString).quiet().returns(R::SymbolOrString),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

fn fold(
    cx: &mut Core<'_>,
    a: Args,
    name: &'static str,
    fi: fn(i64, i64) -> i64,
    ff: fn(f64, f64) -> f64,
) -> Result<Value, EvalError> {
    let mut acc = cx.arg_num(a, 0, name).inspect_err(|_| {
        cx.set_error_fallback(Value::Int(0), None);
    })?;
    for i in 1..a.len as usize {
        // CLIPS returns what it has so far (`*` returns 0)
        let x = cx.arg_num(a, i, name).inspect_err(|_| {
            let v = if name == "*" {
                Value::Int(0)
            } else {
                acc.value()
            };
            cx.set_error_fallback(v, None);
        })?;
        acc = match (acc, x) {
            (Num::Int(p), Num::Int(q)) => Num::Int(fi(p, q)),
            (p, q) => Num::Float(ff(p.as_f64(), q.as_f64())),
        };
    }
    Ok(acc.value())
}

fn add(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    fold(cx, a, "+", i64::wrapping_add, |p, q| p + q)
}
fn sub(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    fold(cx, a, "-", i64::wrapping_sub, |p, q| p - q)
}
fn mul(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    fold(cx, a, "*", i64::wrapping_mul, |p, q| p * q)
}

/// CLIPS 6.30 `/` always yields a float.
fn div(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut acc = cx.arg_num(a, 0, "/")?.as_f64();
    for i in 1..a.len as usize {
        // CLIPS goes on with 0 for a bad divisor and so also divides by zero
        let x = cx
            .arg_num(a, i, "/")
            .inspect_err(|_| cx.set_error_fallback(Value::Float(1.0), Some("/")))?
            .as_f64();
        if x == 0.0 {
            return Err(EvalError::new(EvalErrorKind::DivideByZero { func: "/" }));
        }
        acc /= x;
    }
    Ok(Value::Float(acc))
}

/// Comparison `id` (`CMP_FIRST..=CMP_LAST`) of two values as its builtin decides
/// it; None when a numeric one gets a non-number (the builtin reports that).
#[cfg_attr(feature = "host-speedups", inline(always))]
pub(crate) fn compare(cx: &Core<'_>, id: Ix, a: Value, b: Value) -> Option<bool> {
    let op = id - CMP_FIRST;
    if op >= 6 {
        // `eq`, `neq`
        return Some(values_same(cx, a, b) == (op == 6));
    }
    let num = |v: Value| match v {
        Value::Int(i) => Some(Num::Int(i)),
        Value::Float(f) => Some(Num::Float(f)),
        _ => None,
    };
    let o = cmp_num(num(a)?, num(b)?);
    Some(match op {
        0 => o.is_eq(),
        1 => o.is_ne(),
        2 => o.is_lt(),
        3 => o.is_le(),
        4 => o.is_gt(),
        _ => o.is_ge(),
    })
}

fn cmp_num(p: Num, q: Num) -> core::cmp::Ordering {
    match (p, q) {
        (Num::Int(x), Num::Int(y)) => x.cmp(&y),
        (x, y) => x
            .as_f64()
            .partial_cmp(&y.as_f64())
            .unwrap_or(core::cmp::Ordering::Equal),
    }
}

/// Chained numeric comparison: every neighbouring pair must satisfy `ok`.
fn chain(
    cx: &mut Core<'_>,
    a: Args,
    name: &'static str,
    ok: fn(core::cmp::Ordering) -> bool,
) -> Result<Value, EvalError> {
    let mut prev = cx.arg_num(a, 0, name)?;
    for i in 1..a.len as usize {
        let x = cx.arg_num(a, i, name)?;
        if !ok(cmp_num(prev, x)) {
            return Ok(Core::bool_value(false));
        }
        prev = x;
    }
    Ok(Core::bool_value(true))
}

fn num_eq(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let first = cx.arg_num(a, 0, "=")?;
    for i in 1..a.len as usize {
        if cmp_num(first, cx.arg_num(a, i, "=")?) != core::cmp::Ordering::Equal {
            return Ok(Core::bool_value(false));
        }
    }
    Ok(Core::bool_value(true))
}
/// `<>`: the first differs from every other.
pub(super) fn num_ne(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let first = cx.arg_num(a, 0, "<>")?;
    for i in 1..a.len as usize {
        if cmp_num(first, cx.arg_num(a, i, "<>")?) == core::cmp::Ordering::Equal {
            return Ok(Core::bool_value(false));
        }
    }
    Ok(Core::bool_value(true))
}
fn lt(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    chain(cx, a, "<", |o| o.is_lt())
}
fn le(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    chain(cx, a, "<=", |o| o.is_le())
}
fn gt(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    chain(cx, a, ">", |o| o.is_gt())
}
fn ge(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    chain(cx, a, ">=", |o| o.is_ge())
}

/// Strict equality including multifields element by element. The usual cases,
/// symbols and integers, compare as plain numbers at the call site; the rest is one
/// call away (`values_same_general`).
#[inline(always)]
pub fn values_same(cx: &Core<'_>, x: Value, y: Value) -> bool {
    match (x, y) {
        (Value::Sym(p), Value::Sym(q)) => p == q,
        (Value::Int(p), Value::Int(q)) => p == q,
        _ => values_same_general(cx, x, y),
    }
}

#[inline(never)]
fn values_same_general(cx: &Core<'_>, x: Value, y: Value) -> bool {
    match (x, y) {
        (Value::Multi(p), Value::Multi(q)) => {
            p.len == q.len && (0..p.len as usize).all(|k| cx.mf_item(p, k).same(cx.mf_item(q, k)))
        }
        _ => x.same(y),
    }
}

fn eq(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let first = cx.arg(a, 0);
    Ok(Core::bool_value(
        (1..a.len as usize).all(|i| values_same(cx, first, cx.arg(a, i))),
    ))
}
/// `neq`: the first differs from every other.
fn neq(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let first = cx.arg(a, 0);
    Ok(Core::bool_value(
        (1..a.len as usize).all(|i| !values_same(cx, first, cx.arg(a, i))),
    ))
}

// an operand failing with CLIPS's evaluation error (an unbound global read as FALSE)
// makes `and` and `or` FALSE
fn and(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let halting = cx.st.mode.halting;
    let mut e = cx.exprs[call as usize].first;
    while e != NONE {
        if !Core::is_true(cx.eval(e)?) || (cx.st.mode.halting && !halting) {
            return Ok(Core::bool_value(false));
        }
        e = cx.exprs[e as usize].next;
    }
    Ok(Core::bool_value(true))
}
fn or(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let halting = cx.st.mode.halting;
    let mut e = cx.exprs[call as usize].first;
    while e != NONE {
        let v = cx.eval(e)?;
        if cx.st.mode.halting && !halting {
            return Ok(Core::bool_value(false));
        }
        if Core::is_true(v) {
            return Ok(Core::bool_value(true));
        }
        e = cx.exprs[e as usize].next;
    }
    Ok(Core::bool_value(false))
}
fn not(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(!Core::is_true(cx.arg(a, 0))))
}

#[cfg(test)]
mod tests {
    extern crate std;
    #[cfg(feature = "parser")]
    use crate::testutil::eval_to_string;

    #[cfg(feature = "parser")]
    #[test]
    fn arithmetic_and_comparison() {
        assert_eq!(eval_to_string("(+ 1 2)"), "3");
        assert_eq!(eval_to_string("(* 2.0 3)"), "6.0");
        assert_eq!(eval_to_string("(/ 1 3)"), "0.333333333333333");
        assert_eq!(eval_to_string("(- 10 1 2)"), "7");
        assert_eq!(eval_to_string("(= 1 1.0)"), "TRUE");
        assert_eq!(eval_to_string("(eq 1 1.0)"), "FALSE");
        assert_eq!(eval_to_string("(< 1 2 3)"), "TRUE");
        assert_eq!(eval_to_string("(neq a b c)"), "TRUE");
        assert_eq!(eval_to_string("(str-cat \"a\" b 1.5)"), "\"ab1.5\"");
    }

    /// `CMP_FIRST..=CMP_LAST` are the comparisons `eval` decides in place, all eager.
    #[test]
    fn comparison_ids() {
        let names: std::vec::Vec<_> = (super::CMP_FIRST..=super::CMP_LAST)
            .map(|id| {
                let b = crate::builtins::get(id);
                assert!(matches!(b.imp, crate::builtins::Imp::Eager(_)));
                b.name
            })
            .collect();
        assert_eq!(names, ["=", "<>", "<", "<=", ">", ">=", "eq", "neq"]);
    }

    /// A comparison of two variables (decided in `eval`) gives what the same call
    /// through the general path gives (operands wrapped in `progn`), errors included.
    #[cfg(feature = "parser")]
    #[test]
    fn quick_comparisons_agree_with_calls() {
        use crate::testutil::run_program;
        let vals = [
            "1",
            "2",
            "1.0",
            "2.5",
            "-3",
            "a",
            "b",
            "\"a\"",
            "(create$ 1 2)",
            "(create$)",
        ];
        let mut quick = 0;
        for op in ["=", "<>", "<", "<=", ">", ">=", "eq", "neq"] {
            for x in vals {
                for y in vals {
                    let run = |body: &str| {
                        run_program(&std::format!(
                            "(deffunction f (?a ?b) {body})
                             (printout t (f {x} {y}) crlf)"
                        ))
                    };
                    let direct = run(&std::format!("({op} ?a ?b)"));
                    let general = run(&std::format!("({op} (progn ?a) (progn ?b))"));
                    assert_eq!(direct, general, "({op} {x} {y})");
                    quick += 1;
                }
            }
        }
        assert_eq!(quick, 800);
    }
}
