//! How CLIPS 6.30 reports a run-time error of a builtin, beyond the message itself.
//!
//! CLIPS checks literal arguments against a function's argument restrictions while
//! parsing (the command is then not run, and nothing is printed after the message), but
//! checks computed arguments inside the function body, with sometimes different type
//! names, and the function then returns a fallback value that the command line prints
//! (`(str-cat (create$ a))` prints its message and then `""`). These tables hold the
//! run-time type names and the fallback values observed in CLIPS 6.30.

use super::math::{T_LEXEME, T_NUMBER};
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
        self.st.error_fallback = Some(ErrorFallback {
            value,
            depth: self.st.eval_depth,
            divide_by_zero,
        });
    }
}

/// The value a builtin returns in CLIPS after a run-time error.
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

/// Fallback value of builtin `func` after a run-time error, when CLIPS's is a constant.
/// `None`: CLIPS's value depends on the arguments already seen (`+`, `min`, ...) or the
/// function is not one of those observed; nothing is printed then.
pub fn fallback(func: &str) -> Option<Fallback> {
    use Fallback::*;
    Some(match func {
        "/" => Float(1.0),
        "div" => Int(1),
        "mod" | "abs" | "integer" | "round" | "str-compare" => Int(0),
        "sqrt" | "float" | "exp" | "log" | "log10" | "**" | "sin" | "cos" | "tan" | "asin"
        | "acos" | "atan" | "deg-rad" | "rad-deg" => Float(0.0),
        "str-length" | "fact-index" => Int(-1),
        "str-cat" | "sub-string" | "upcase" | "lowcase" | "implode$" | "format" => Str(""),
        "string-to-field" => Str("*** ERROR ***"),
        "sym-cat" | "nth$" => Sym("nil"),
        "=" | "<>" | "<" | "<=" | ">" | ">=" | "eq" | "neq" | "and" | "or" | "not"
        | "str-index" | "member$" | "eval" | "progn" | "progn$" | "foreach" | "while"
        | "numberp" | "integerp" | "floatp" | "symbolp" | "stringp" | "lexemep" | "multifieldp"
        | "evenp" | "oddp" | "subsetp" => Sym("FALSE"),
        "create$" | "subseq$" | "first$" | "rest$" | "explode$" | "insert$" | "delete$"
        | "replace$" | "delete-member$" | "replace-member$" => EmptyMulti,
        _ => return None,
    })
}

/// The type name CLIPS's function body prints for a computed argument of the wrong type,
/// given the name its argument restriction uses for a literal one (`expected`).
pub fn runtime_type_name(func: &str, expected: &'static str) -> &'static str {
    match func {
        "str-length" | "str-index" | "sub-string" | "upcase" | "lowcase" | "str-compare"
        | "string-to-field"
            if expected == T_LEXEME =>
        {
            "symbol or string"
        }
        "sqrt" | "float" | "exp" | "log" | "log10" | "**" | "sin" | "cos" | "tan" | "asin"
        | "acos" | "atan" | "deg-rad" | "rad-deg"
            if expected == T_NUMBER =>
        {
            "float"
        }
        "integer" if expected == T_NUMBER => "integer",
        _ => expected,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runtime_names_differ_only_where_clips_differs() {
        assert_eq!(
            runtime_type_name("str-length", T_LEXEME),
            "symbol or string"
        );
        assert_eq!(runtime_type_name("sqrt", T_NUMBER), "float");
        assert_eq!(runtime_type_name("+", T_NUMBER), T_NUMBER);
        assert_eq!(fallback("+"), None);
        assert_eq!(fallback("format"), Some(Fallback::Str("")));
    }
}
