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

/// Builtins by the constant CLIPS returns after a run-time error (lists, not a `match`
/// on strings: they keep the code of the embedded image small).
const FALSE_FNS: &[&str] = &[
    "=",
    "<>",
    "<",
    "<=",
    ">",
    ">=",
    "eq",
    "neq",
    "and",
    "or",
    "not",
    "str-index",
    "member$",
    "eval",
    "funcall",
    "sort",
    "assert-string",
    "progn",
    "progn$",
    "foreach",
    "while",
    "numberp",
    "integerp",
    "floatp",
    "symbolp",
    "stringp",
    "lexemep",
    "multifieldp",
    "evenp",
    "oddp",
    "subsetp",
    "any-factp",
    "do-for-fact",
    "do-for-all-facts",
    "delayed-do-for-all-facts",
];
const ZERO_FNS: &[&str] = &["mod", "abs", "integer", "round", "str-compare"];
const FLOAT_ZERO_FNS: &[&str] = &[
    "sqrt", "float", "exp", "log", "log10", "**", "sin", "cos", "tan", "asin", "acos", "atan",
    "deg-rad", "rad-deg",
];
const EMPTY_STRING_FNS: &[&str] = &[
    "str-cat",
    "sub-string",
    "upcase",
    "lowcase",
    "implode$",
    "format",
];
const EMPTY_MULTI_FNS: &[&str] = &[
    "create$",
    "subseq$",
    "first$",
    "rest$",
    "explode$",
    "insert$",
    "delete$",
    "replace$",
    "delete-member$",
    "replace-member$",
    "find-fact",
    "find-all-facts",
];
/// Functions whose string arguments CLIPS checks in the body as "symbol or string".
const LEXEME_BODY_FNS: &[&str] = &[
    "str-length",
    "str-index",
    "sub-string",
    "upcase",
    "lowcase",
    "str-compare",
    "string-to-field",
];

/// Fallback value of builtin `func` after a run-time error, when CLIPS's is a constant.
/// `None`: CLIPS's value depends on the arguments already seen (`+`, `min`, ...) or the
/// function is not one of those observed; nothing is printed then.
pub fn fallback(func: &str) -> Option<Fallback> {
    use Fallback::*;
    let is = |list: &[&str]| list.contains(&func);
    Some(match func {
        "/" => Float(1.0),
        "div" => Int(1),
        "str-length" | "fact-index" => Int(-1),
        "string-to-field" => Str("*** ERROR ***"),
        "sym-cat" | "nth$" => Sym("nil"),
        _ if is(FALSE_FNS) => Sym("FALSE"),
        _ if is(ZERO_FNS) => Int(0),
        _ if is(FLOAT_ZERO_FNS) => Float(0.0),
        _ if is(EMPTY_STRING_FNS) => Str(""),
        _ if is(EMPTY_MULTI_FNS) => EmptyMulti,
        _ => return None,
    })
}

/// The type name CLIPS's function body prints for a computed argument of the wrong type,
/// given the name its argument restriction uses for a literal one (`expected`).
pub fn runtime_type_name(func: &str, expected: &'static str) -> &'static str {
    if expected == T_LEXEME && LEXEME_BODY_FNS.contains(&func) {
        "symbol or string"
    } else if expected == T_NUMBER && FLOAT_ZERO_FNS.contains(&func) {
        "float"
    } else if expected == T_NUMBER && func == "integer" {
        "integer"
    } else {
        expected
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
