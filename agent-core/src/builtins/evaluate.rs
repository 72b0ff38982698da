//! `eval` and `build`: CLIPS source given as a string, parsed and run at run time.

use super::{Args, Builtin, ANY, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::parser::{Item, Parser};
use crate::value::Value;

pub const FUNCS: &[Builtin] = &[
    Builtin::eager("eval", 1, 1, eval),
    Builtin::eager("build", 1, 1, build),
    Builtin::eager("assert-string", 1, 1, assert_string),
    Builtin::eager("funcall", 1, ANY, funcall),
];

/// The text argument (symbol or string), copied out of the symbol table.
fn source_arg(
    cx: &Core<'_>,
    a: Args,
    func: &'static str,
) -> Result<super::strings::Text, EvalError> {
    match cx.arg(a, 0) {
        Value::Sym(s) | Value::Str(s) => super::strings::copy_text(cx, s),
        _ => Err(EvalError::wrong_type(func, 1, "symbol or string")),
    }
}

/// `(eval "(+ 1 2)")`: the value of one command; constructs are not allowed (use
/// `build`). Its expression nodes are dropped again afterwards.
fn eval(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let text = source_arg(cx, a, "eval")?;
    eval_text(cx, text.as_str(), "eval", None)
}

/// Parses and evaluates one command of `text` (`func` names it in a parse error,
/// which gives `on_parse_error` when set, else the reported error).
fn eval_text(
    cx: &mut Core<'_>,
    text: &str,
    func: &'static str,
    on_parse_error: Option<Value>,
) -> Result<Value, EvalError> {
    let cp = cx.checkpoint();
    let mut p = Parser::new(cx, text);
    let item = p.next_item();
    let nlocals = p.nlocals;
    let r = match item {
        Ok(Item::Command(e)) => {
            // a frame for the command's own loop/query variables
            let (bp, sp) = (cx.st.bp, cx.st.sp);
            cx.st.bp = cx.st.sp;
            let mut r = Ok(Value::Void);
            for _ in 0..nlocals {
                if let Err(c) = cx.push_value(Value::Void) {
                    r = Err(c.into());
                }
            }
            if r.is_ok() {
                r = cx.eval(e);
            }
            (cx.st.bp, cx.st.sp) = (bp, sp);
            r
        }
        Ok(Item::End) => Ok(Value::Sym(SYM_FALSE)),
        Ok(Item::Construct) => Ok(Value::Sym(SYM_FALSE)),
        Err(e) => {
            cx.report_load_error(func, text, &e);
            on_parse_error.ok_or(EvalError::new(EvalErrorKind::Reported))
        }
    };
    // a plain command leaves no expressions behind
    let now = cx.checkpoint();
    if now.nrules == cp.nrules
        && now.nfuncs == cp.nfuncs
        && now.ndeffacts == cp.ndeffacts
        && now.ntemplates == cp.ntemplates
        && now.nglobals == cp.nglobals
    {
        cx.st.nexprs = cp.nexprs;
    }
    r
}

/// `(assert-string "(point (x 1))")`: asserts the fact the string writes, as `assert`
/// would (the fact, or FALSE: a duplicate, or text that is not a fact).
fn assert_string(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Str(s) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type("assert-string", 1, "string"));
    };
    let mut text = super::strings::Text::new();
    let fits = core::fmt::Write::write_fmt(&mut text, format_args!("(assert {})", cx.sym_text(s)));
    if fits.is_err() {
        return Err(EvalError::other("string result longer than 2048 bytes"));
    }
    eval_text(
        cx,
        text.as_str(),
        "assert-string",
        Some(Value::Sym(SYM_FALSE)),
    )
}

/// `(funcall name args...)`: calls the function (builtin, deffunction or host
/// function) whose name `name` evaluates to, with the other arguments' values.
fn funcall(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    const NOT_A_FUNCTION: &str = "function, deffunction, or generic function name";
    let name = match cx.arg(a, 0) {
        Value::Sym(s) | Value::Str(s) => s,
        _ => return Err(EvalError::wrong_type("funcall", 1, "symbol or string")),
    };
    let rest = Args {
        base: a.base + 1,
        len: a.len - 1,
    };
    let mut text = super::strings::Text::new();
    let _ = core::fmt::Write::write_str(&mut text, cx.sym_text(name));
    cx.call_named(text.as_str(), rest)
        .unwrap_or_else(|| Err(EvalError::wrong_type("funcall", 1, NOT_A_FUNCTION)))
}

/// `(build "(defrule ...)")`: defines one construct, silently; TRUE when it was defined.
fn build(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let text = source_arg(cx, a, "build")?;
    // CLIPS defines nothing while a pattern or join test runs (`State::matching`)
    if cx.st.matching > 0 {
        return Ok(Value::Sym(SYM_FALSE));
    }
    match cx.load_text(text.as_str(), false) {
        Ok(n) if n > 0 => Ok(Value::Sym(SYM_TRUE)),
        Ok(_) => Ok(Value::Sym(SYM_FALSE)),
        Err(e) => {
            cx.report_load_error("build", text.as_str(), &e);
            Ok(Value::Sym(SYM_FALSE))
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::testutil::{eval_to_string, run_program};

    #[test]
    fn eval_runs_a_command_from_a_string() {
        assert_eq!(eval_to_string("(eval \"(+ 1 2)\")"), "3");
        assert_eq!(eval_to_string("(eval \"(create$ a (* 2 3))\")"), "(a 6)");
    }

    #[test]
    fn build_defines_a_rule_that_then_fires() {
        let out = run_program(
            "(build \"(defrule b (z ?x) => (printout t built ?x crlf))\")\n(assert (z 1))\n(run)\n",
        );
        assert!(out.contains("TRUE") && out.contains("built1"), "{out}");
    }
}
