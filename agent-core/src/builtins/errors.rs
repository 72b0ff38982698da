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
