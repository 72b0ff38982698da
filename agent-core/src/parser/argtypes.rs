//! Argument types of builtins, for the check CLIPS makes at parse time: a literal
//! argument of a type the function never takes (`(+ 1 abc)`) is a load error
//! (`[ARGACCES5]`), not a run-time one. Only literals are checked here; variables and
//! calls are checked when they run. Each entry was compared with CLIPS 6.30.

use crate::value::Value;

/// What a function accepts in one argument position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgType {
    Any,
    Number,
    Integer,
    /// Symbol or string.
    Lexeme,
    Str,
    /// No literal is a multifield.
    Multifield,
    /// No literal is a fact address.
    FactAddress,
}

use ArgType::{
    Any, FactAddress as F, Integer as I, Lexeme as L, Multifield as M, Number as N, Str as S,
};

/// One builtin's argument types: the leading positions, then the type of every further
/// argument.
struct Signature {
    name: &'static str,
    args: &'static [ArgType],
    rest: ArgType,
}

const fn sig(name: &'static str, args: &'static [ArgType], rest: ArgType) -> Signature {
    Signature { name, args, rest }
}

const SIGNATURES: &[Signature] = &[
    sig("+", &[], N),
    sig("-", &[], N),
    sig("*", &[], N),
    sig("/", &[], N),
    sig("div", &[], N),
    sig("mod", &[], N),
    sig("=", &[], N),
    sig("<>", &[], N),
    sig("<", &[], N),
    sig("<=", &[], N),
    sig(">", &[], N),
    sig(">=", &[], N),
    sig("min", &[], N),
    sig("max", &[], N),
    sig("**", &[], N),
    sig("abs", &[N], Any),
    sig("integer", &[N], Any),
    sig("float", &[N], Any),
    sig("round", &[N], Any),
    sig("sqrt", &[N], Any),
    sig("exp", &[N], Any),
    sig("log", &[N], Any),
    sig("log10", &[N], Any),
    sig("sin", &[N], Any),
    sig("cos", &[N], Any),
    sig("tan", &[N], Any),
    sig("asin", &[N], Any),
    sig("acos", &[N], Any),
    sig("atan", &[N], Any),
    sig("deg-rad", &[N], Any),
    sig("rad-deg", &[N], Any),
    sig("evenp", &[I], Any),
    sig("oddp", &[I], Any),
    sig("str-length", &[L], Any),
    sig("upcase", &[L], Any),
    sig("lowcase", &[L], Any),
    sig("str-index", &[L, L], Any),
    sig("sub-string", &[I, I, L], Any),
    sig("str-compare", &[L, L, I], Any),
    sig("nth$", &[I, M], Any),
    sig("member$", &[Any, M], Any),
    sig("subsetp", &[M, M], Any),
    sig("insert$", &[M, I], Any),
    sig("delete$", &[M, I, I], Any),
    sig("replace$", &[M, I, I], Any),
    sig("subseq$", &[M, I, I], Any),
    sig("first$", &[M], Any),
    sig("rest$", &[M], Any),
    sig("implode$", &[M], Any),
    sig("explode$", &[S], Any),
    sig("delete-member$", &[M], Any),
    sig("replace-member$", &[M], Any),
    sig("fact-index", &[F], Any),
    sig("format", &[Any, S], Any),
    sig("seed", &[I], Any),
    sig("random", &[], I),
];

/// The type builtin `func` takes as its `index`-th (0-based) argument.
pub fn arg_type(func: &str, index: usize) -> ArgType {
    match SIGNATURES.iter().find(|s| s.name == func) {
        Some(s) => s.args.get(index).copied().unwrap_or(s.rest),
        None => Any,
    }
}

impl ArgType {
    /// Whether a literal value (integer, float, symbol or string) fits.
    pub fn admits(self, v: Value) -> bool {
        match self {
            Any => true,
            N => matches!(v, Value::Int(_) | Value::Float(_)),
            I => matches!(v, Value::Int(_)),
            L => matches!(v, Value::Sym(_) | Value::Str(_)),
            S => matches!(v, Value::Str(_)),
            M | F => false,
        }
    }

    /// CLIPS's wording in `[ARGACCES5] ... to be of type WORDING`.
    pub fn clips_name(self) -> &'static str {
        match self {
            Any => "any",
            N => "integer or float",
            I => "integer",
            L => "symbol, string, or instance name",
            S => "string",
            M => "multifield",
            F => "fact-address",
        }
    }

    /// The position line's "expected ..." text.
    pub fn expected(self) -> &'static str {
        match self {
            Any => "an argument",
            N => "an argument of type integer or float",
            I => "an argument of type integer",
            L => "an argument of type symbol or string",
            S => "an argument of type string",
            M => "an argument of type multifield (a variable or call, not a literal)",
            F => "an argument of type fact-address (a variable or call, not a literal)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_past_the_listed_ones_take_the_rest_type() {
        assert_eq!(arg_type("+", 0), ArgType::Number);
        assert_eq!(arg_type("+", 7), ArgType::Number);
        assert_eq!(arg_type("nth$", 0), ArgType::Integer);
        assert_eq!(arg_type("nth$", 1), ArgType::Multifield);
        assert_eq!(arg_type("insert$", 5), ArgType::Any);
        assert_eq!(arg_type("printout", 1), ArgType::Any);
    }

    #[test]
    fn literals_are_judged_by_their_type() {
        assert!(ArgType::Number.admits(Value::Float(1.5)));
        assert!(!ArgType::Number.admits(Value::Sym(3)));
        assert!(!ArgType::Integer.admits(Value::Float(1.0)));
        assert!(ArgType::Lexeme.admits(Value::Str(3)));
        assert!(!ArgType::Str.admits(Value::Sym(3)));
        assert!(!ArgType::Multifield.admits(Value::Int(1)));
    }
}
