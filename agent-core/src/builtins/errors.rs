//! How CLIPS 6.30 reports a run-time error of a builtin, beyond the message itself.
//!
//! CLIPS checks literal arguments against a function's argument restrictions while
//! parsing (the command is then not run, and nothing is printed after the message), but
//! checks computed arguments inside the function body, with sometimes different type
//! names, and the function then returns a fallback value that the command line prints
//! (`(str-cat (create$ a))` prints its message and then `""`). Each builtin's row
//! holds its constant fallback and its run-time type names (`builtins::describe`).

use crate::engine::Core;
use crate::value::Value;

/// A fallback value that depends on the arguments (`(+ 1 (f))` returns 1 when `(f)` is
/// not a number), recorded by the builtin at call depth `depth`; the command line uses it
/// only for the top-level call (depth 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorFallback {
    pub value: Value,
    pub depth: u16,
    /// `/` and `div` go on with 0 for the bad argument, so CLIPS also reports a division
    /// by zero in this function.
    pub divide_by_zero: Option<&'static str>,
}

impl Core<'_> {
    /// Records the value this builtin returns in CLIPS after a run-time error.
    pub fn set_error_fallback(&mut self, value: Value, divide_by_zero: Option<&'static str>) {
        self.st.eval.error_fallback = Some(ErrorFallback {
            value,
            depth: self.st.eval.eval_depth,
            divide_by_zero,
        });
    }
}

/// The value a builtin returns in CLIPS after a run-time error, as the command line
/// prints it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fallback {
    Int(i64),
    Float(f64),
    /// A symbol, printed as is (`FALSE`, `nil`).
    Sym(&'static str),
    /// A string, printed in quotes.
    Str(&'static str),
    /// The empty multifield `()`.
    EmptyMulti,
}

/// Builtins that take an argument whose evaluation failed (an unbound global read as
/// `FALSE`, CLIPS's evaluation error set) as the value it gave: the type predicates
/// and `length$`, and those that check their argument types themselves and report
/// `[ARGACCES5]` for it (arithmetic, comparisons, fact functions).
const READ_FAILED_ARGUMENTS: &[&str] = &[
    "eq",
    "neq",
    "lexemep",
    "type",
    "multifieldp",
    "numberp",
    "symbolp",
    "stringp",
    "integerp",
    "floatp",
    "pointerp",
    "length$",
    "length",
    "+",
    "-",
    "*",
    "/",
    "div",
    "<",
    ">",
    "<=",
    ">=",
    "=",
    "<>",
    "!=",
    "fact-existp",
    "retract",
    "fact-index",
];

/// Whether builtin `b` evaluates its arguments after one failed (CLIPS's evaluation
/// error set) and computes its value with the failed one's fallback: those of
/// `READ_FAILED_ARGUMENTS`. The others check each argument as it comes and stop.
#[cfg(feature = "extras")]
pub(crate) fn goes_on_after_error(b: &super::Builtin) -> bool {
    READ_FAILED_ARGUMENTS.contains(&b.name)
}

/// Whether argument `at` (0-based) of builtin `b`, called with `n` arguments, is the
/// one value `insert$` or `replace$` puts in (after the multifield and the indices):
/// CLIPS reads a single value without checking its evaluation error, so one that
/// failed (an unbound global, a failing call) goes in as the value it gave
/// (`(insert$ ?m 1 ?*u*)` is `(FALSE a b)`), where a failed multifield or index stops
/// the call. (Of several values, CLIPS's `insert$` then gives the multifield
/// unchanged, which we do not reproduce: both give `()`.)
#[cfg(feature = "extras")]
pub(crate) fn value_argument(b: &super::Builtin, at: usize, n: usize) -> bool {
    match b.name {
        "insert$" => at == 2 && n == 3,
        "replace$" => at == 3 && n == 4,
        _ => false,
    }
}

/// `value_argument` for an argument that set the evaluation error without failing
/// (an unbound global read as FALSE) among arguments `a` all evaluated: the
/// multifield and indices before the values have their types, so the error came
/// from a value (an index call that gave a number with the error set is taken for
/// a value as well).
#[cfg(feature = "extras")]
#[cold]
#[inline(never)]
pub(crate) fn values_failed(cx: &Core<'_>, b: &super::Builtin, a: super::Args) -> bool {
    let first_value = match b.name {
        "insert$" => 2,
        "replace$" => 3,
        _ => return false,
    };
    a.len as usize == first_value + 1
        && matches!(cx.arg(a, 0), Value::Multi(_))
        && (1..first_value).all(|i| matches!(cx.arg(a, i), Value::Int(_) | Value::Float(_)))
}

impl Core<'_> {
    /// What builtin `b` gives when evaluating its arguments set CLIPS's evaluation
    /// error: most check it after each argument and return their constant error value
    /// without a message (`(str-cat x ?*u* y)` is `""`, `(abs ?*u*)` is 0); None when
    /// `b` goes on with the values (see `READ_FAILED_ARGUMENTS`) or has no constant.
    #[cold]
    #[inline(never)]
    pub(crate) fn args_failed(
        &mut self,
        b: &super::Builtin,
    ) -> Result<Option<Value>, crate::error::EvalError> {
        if READ_FAILED_ARGUMENTS.contains(&b.name) {
            return Ok(None);
        }
        Ok(Some(match b.on_error.fallback() {
            None => return Ok(None),
            Some(Fallback::Int(i)) => Value::Int(i),
            Some(Fallback::Float(f)) => Value::Float(f),
            Some(Fallback::Sym(s)) => Value::Sym(self.intern(s)?),
            Some(Fallback::Str(s)) => Value::Str(self.intern(s)?),
            Some(Fallback::EmptyMulti) => {
                let start = self.multi_begin();
                self.multi_finish(start)
            }
        }))
    }

    /// Constant fallback `fb` as a value (as `args_failed` makes it).
    #[cfg(feature = "extras")]
    pub(crate) fn fallback_value(
        &mut self,
        fb: Fallback,
    ) -> Result<Value, crate::error::EvalError> {
        Ok(match fb {
            Fallback::Int(i) => Value::Int(i),
            Fallback::Float(f) => Value::Float(f),
            Fallback::Sym(s) => Value::Sym(self.intern(s)?),
            Fallback::Str(s) => Value::Str(self.intern(s)?),
            Fallback::EmptyMulti => {
                let start = self.multi_begin();
                self.multi_finish(start)
            }
        })
    }
}
