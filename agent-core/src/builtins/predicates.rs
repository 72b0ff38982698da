//! Builtins: type predicates (numberp integerp floatp symbolp stringp lexemep
//! multifieldp) and the integer predicates evenp / oddp.

use super::describe::ArgType::{Any, Integer as I};
use super::describe::OnError;
use super::describe::Returns as R;
use super::math::int_arg;
use super::{Args, Builtin};
use crate::engine::Core;
use crate::error::EvalError;
use crate::value::Value;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("numberp", 1, 1, numberp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("integerp", 1, 1, integerp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("floatp", 1, 1, floatp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("symbolp", 1, 1, symbolp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("stringp", 1, 1, stringp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("lexemep", 1, 1, lexemep).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("multifieldp", 1, 1, multifieldp).on_error(OnError::False).total().returns(R::Symbol),
    Builtin::eager("evenp", 1, 1, evenp).args(&[I], Any).on_error(OnError::False).quiet().returns(R::Symbol),
    Builtin::eager("oddp", 1, 1, oddp).args(&[I], Any).on_error(OnError::False).quiet().returns(R::Symbol),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

fn test(cx: &Core<'_>, a: Args, pred: fn(Value) -> bool) -> Result<Value, EvalError> {
    Ok(Core::bool_value(pred(cx.arg(a, 0))))
}

fn numberp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    test(cx, a, |v| matches!(v, Value::Int(_) | Value::Float(_)))
}
fn integerp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    test(cx, a, |v| matches!(v, Value::Int(_)))
}
fn floatp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    test(cx, a, |v| matches!(v, Value::Float(_)))
}
/// A symbol, not an instance name (`value::instance_name_body`).
fn plain_symbol(cx: &Core<'_>, v: Value) -> bool {
    match v {
        Value::Sym(s) => crate::value::instance_name_body(cx.sym_text(s)).is_none(),
        _ => false,
    }
}
pub(super) fn symbolp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(plain_symbol(cx, cx.arg(a, 0))))
}
fn stringp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    test(cx, a, |v| matches!(v, Value::Str(_)))
}
fn lexemep(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cx.arg(a, 0);
    Ok(Core::bool_value(
        matches!(v, Value::Str(_)) || plain_symbol(cx, v),
    ))
}
pub(super) fn multifieldp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    test(cx, a, |v| matches!(v, Value::Multi(_)))
}

/// `evenp`/`oddp` take integers only (CLIPS: "expected argument #1 to be of type integer").
fn evenp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(int_arg(cx, a, 0, "evenp")? % 2 == 0))
}
fn oddp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(int_arg(cx, a, 0, "oddp")? % 2 != 0))
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::eval_to_string;

    #[test]
    fn type_predicates_match_clips() {
        // expected values: tests/clips/051 as printed by CLIPS 6.30
        for (e, want) in [
            ("(numberp 1)", "TRUE"),
            ("(numberp 1.5)", "TRUE"),
            ("(numberp a)", "FALSE"),
            ("(numberp \"1\")", "FALSE"),
            ("(integerp 1)", "TRUE"),
            ("(integerp 1.0)", "FALSE"),
            ("(floatp 1.0)", "TRUE"),
            ("(floatp 1)", "FALSE"),
            ("(symbolp abc)", "TRUE"),
            ("(symbolp \"abc\")", "FALSE"),
            ("(symbolp TRUE)", "TRUE"),
            ("(stringp \"abc\")", "TRUE"),
            ("(stringp abc)", "FALSE"),
            ("(lexemep abc)", "TRUE"),
            ("(lexemep \"abc\")", "TRUE"),
            ("(lexemep 3)", "FALSE"),
            ("(multifieldp (create$ a))", "TRUE"),
            ("(multifieldp (create$))", "TRUE"),
            ("(multifieldp a)", "FALSE"),
        ] {
            assert_eq!(eval_to_string(e), want, "{e}");
        }
    }

    #[test]
    fn even_odd() {
        assert_eq!(eval_to_string("(evenp 4)"), "TRUE");
        assert_eq!(eval_to_string("(evenp -3)"), "FALSE");
        assert_eq!(eval_to_string("(oddp -3)"), "TRUE");
        assert_eq!(eval_to_string("(oddp 0)"), "FALSE");
        assert!(eval_to_string("(evenp (float 2))").contains("integer"));
    }
}
