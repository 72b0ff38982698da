//! What a builtin's row says about it besides its name, arity and function: the argument
//! types CLIPS checks literals against at parse time, the value it returns after a
//! run-time error, the type names its body prints, and its purity. Each is set on the
//! row with a `const` builder (`Builtin::eager("sqrt", 1, 1, sqrt).args(&[N], Any)
//! .on_error(OnError::FloatZero).quiet().body_names(BodyNames::Float)`); a row that
//! says nothing takes any argument,
//! prints no value after an error and may have effects. Every entry was compared with
//! CLIPS 6.30.

use super::errors::Fallback;
use super::math::{T_LEXEME, T_NUMBER};
use super::{lookup, Builtin};
use crate::value::Value;

/// What a function accepts in one argument position. Only literals are checked while
/// parsing (`(+ 1 abc)` is `[ARGACCES5]`, a load error); variables and calls are
/// checked when they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgType {
    Any,
    Number,
    Integer,
    /// Symbol, string or instance name (CLIPS's `j`).
    Lexeme,
    /// Symbol or string (CLIPS's `k`: a file name).
    SymbolOrString,
    /// A symbol alone (a construct or slot name).
    Symbol,
    Str,
    /// No literal is a multifield.
    Multifield,
    /// A multifield, symbol or string (CLIPS's `q`: `length$`).
    Sequence,
    /// No literal is a fact address (CLIPS's `y`).
    FactAddress,
    /// A fact address, fact index or symbol (CLIPS's `z`: the fact functions):
    /// integers and symbols among literals.
    FactOrIndex,
    /// A fact or an instance: its address, a fact index, an instance name (CLIPS's `h`,
    /// `timetag`): integers, symbols and instance names among literals.
    FactOrInstance,
}

/// What a builtin returns, as CLIPS's parser knows it (the return-type letter of its
/// definition): a call whose result an argument position never takes is refused while
/// parsing, as a literal is (`(+ 1 (str-cat a))` is `[ARGACCES5]`); a row that says
/// nothing returns anything. (The byte fits the row's padding: the image's table does
/// not grow.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Returns {
    /// Anything (`u`): never refused.
    Any,
    /// Integer or float (`n`).
    Number,
    /// `g`, `i`, `l`.
    Integer,
    /// `d`, `f`.
    Float,
    /// `w`, `b` (a boolean is a symbol).
    Symbol,
    /// `s`.
    Str,
    /// Symbol, string or instance name (`j`).
    Lexeme,
    /// Symbol or string (`k`).
    SymbolOrString,
    /// `m`.
    Multifield,
    /// No value (`v`).
    Void,
}

/// Bits of the value types a call may give or an argument position may take.
mod bits {
    pub const SYMBOL: u16 = 1;
    pub const STRING: u16 = 2;
    pub const INTEGER: u16 = 4;
    pub const FLOAT: u16 = 8;
    pub const INSTANCE_NAME: u16 = 16;
    pub const MULTIFIELD: u16 = 32;
    pub const VOID: u16 = 64;
    pub const FACT_ADDRESS: u16 = 128;
    pub const ALL: u16 = u16::MAX;
}

impl Returns {
    /// The single-field types a call of this type gives, as a slot's `type` bits
    /// (`template::types`) for CLIPS's check of a `default-dynamic` call; None where it
    /// may give anything, a multifield or nothing. CLIPS's check there knows no `g`
    /// (most integer functions: `str-length`, `div`, `round`) and lets them by, so
    /// `Integer` is not checked either.
    pub fn slot_types(self) -> Option<u8> {
        use crate::template::types;
        Some(match self {
            Returns::Number => types::NUMBER,
            Returns::Float => types::FLOAT,
            Returns::Symbol => types::SYMBOL,
            Returns::Str => types::STRING,
            Returns::Lexeme | Returns::SymbolOrString => types::LEXEME,
            Returns::Any | Returns::Integer | Returns::Multifield | Returns::Void => return None,
        })
    }

    fn types(self) -> u16 {
        use bits::*;
        match self {
            Returns::Any => ALL,
            Returns::Number => INTEGER | FLOAT,
            Returns::Integer => INTEGER,
            Returns::Float => FLOAT,
            Returns::Symbol => SYMBOL,
            Returns::Str => STRING,
            Returns::Lexeme => SYMBOL | STRING | INSTANCE_NAME,
            Returns::SymbolOrString => SYMBOL | STRING,
            Returns::Multifield => MULTIFIELD,
            Returns::Void => VOID,
        }
    }
}

/// Most leading argument positions a row types one by one/// Most leading argument positions a row types one by one (then every further argument
/// has the `rest` type).
pub const MAX_TYPED: usize = 3;

/// A builtin's argument types: the leading positions, then the type of every further one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Signature {
    lead: [ArgType; MAX_TYPED],
    nlead: u8,
    rest: ArgType,
}

impl Signature {
    /// Any argument anywhere.
    pub const ANY: Signature = Signature {
        lead: [ArgType::Any; MAX_TYPED],
        nlead: 0,
        rest: ArgType::Any,
    };

    /// `lead` (at most [`MAX_TYPED`]), then `rest` for every further argument.
    pub const fn new(lead: &[ArgType], rest: ArgType) -> Signature {
        assert!(
            lead.len() <= MAX_TYPED,
            "more typed arguments than MAX_TYPED"
        );
        let mut s = Signature {
            lead: [ArgType::Any; MAX_TYPED],
            nlead: lead.len() as u8,
            rest,
        };
        let mut i = 0;
        while i < lead.len() {
            s.lead[i] = lead[i];
            i += 1;
        }
        s
    }

    /// Whether every argument from the lead on is a number (`+`, `/`, `=`, `div`,
    /// `mod`, ...): CLIPS's bodies take such arguments one at a time
    /// (`GetNumericArgument`), see `builtins::ordered`.
    #[inline(always)]
    pub const fn numbers_after_lead(&self) -> bool {
        self.nlead == 0 && matches!(self.rest, ArgType::Number)
    }

    /// The type of argument `index` (0-based).
    pub fn get(&self, index: usize) -> ArgType {
        if index < self.nlead as usize {
            self.lead[index]
        } else {
            self.rest
        }
    }
}

/// The value a builtin returns in CLIPS after a run-time error, when it is a constant
/// (the command line prints it after the message).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnError {
    /// None printed: the value depends on the arguments already seen (`+`, `min`, ...,
    /// recorded by the builtin itself, `Core::set_error_fallback`), or nothing observed.
    Nothing,
    False,
    /// `TRUE` (`check-syntax`; host only).
    #[cfg(feature = "extras")]
    True,
    Nil,
    Zero,
    One,
    MinusOne,
    FloatZero,
    FloatOne,
    EmptyString,
    /// `"*** ERROR ***"` (string-to-field).
    ErrorString,
    EmptyMultifield,
}

impl OnError {
    pub fn fallback(self) -> Option<Fallback> {
        Some(match self {
            OnError::Nothing => return None,
            OnError::False => Fallback::Sym("FALSE"),
            #[cfg(feature = "extras")]
            OnError::True => Fallback::Sym("TRUE"),
            OnError::Nil => Fallback::Sym("nil"),
            OnError::Zero => Fallback::Int(0),
            OnError::One => Fallback::Int(1),
            OnError::MinusOne => Fallback::Int(-1),
            OnError::FloatZero => Fallback::Float(0.0),
            OnError::FloatOne => Fallback::Float(1.0),
            OnError::EmptyString => Fallback::Str(""),
            OnError::ErrorString => Fallback::Str("*** ERROR ***"),
            OnError::EmptyMultifield => Fallback::EmptyMulti,
        })
    }
}

/// What a builtin may do besides computing its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Purity {
    /// Anything (facts, agenda, output, globals ...).
    Effects,
    /// Depends on its arguments alone and prints nothing itself, even on an error (it
    /// returns the error, reported once the actions stop).
    Quiet,
    /// Quiet, changes nothing a retract changes or observes, and cannot fail whatever
    /// its arguments (`rete::defer` needs this of the tests a deferred propagation runs).
    Total,
}

/// The type names a builtin's body prints for a computed argument of the wrong type,
/// where CLIPS's body words them differently from its argument restriction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyNames {
    /// As the restriction.
    Same,
    /// "symbol or string" for "symbol, string, or instance name".
    SymbolOrString,
    /// "float" for "integer or float".
    Float,
    /// "integer" for "integer or float".
    Integer,
    /// "file name" for "symbol or string" (`open`, `remove`, `rename`, `dribble-on`).
    FileName,
}

impl Builtin {
    /// The argument types CLIPS checks literal arguments against while parsing.
    pub const fn args(mut self, lead: &[ArgType], rest: ArgType) -> Builtin {
        self.signature = Signature::new(lead, rest);
        self
    }
    /// The value CLIPS returns after a run-time error.
    pub const fn on_error(mut self, value: OnError) -> Builtin {
        self.on_error = value;
        self
    }
    /// Depends on its arguments alone and prints nothing itself.
    pub const fn quiet(mut self) -> Builtin {
        self.purity = Purity::Quiet;
        self
    }
    /// Quiet and cannot fail.
    pub const fn total(mut self) -> Builtin {
        self.purity = Purity::Total;
        self
    }
    /// What the builtin returns, as CLIPS's parser knows it.
    pub const fn returns(mut self, r: Returns) -> Builtin {
        self.returns = r;
        self
    }
    /// A file name argument as `load`, `batch`, `save` and the others check it: a
    /// symbol or string, a computed one of another type worded "file name", FALSE.
    pub const fn file_name(self) -> Builtin {
        self.args(&[ArgType::SymbolOrString], ArgType::Any)
            .on_error(OnError::False)
            .body_names(BodyNames::FileName)
    }
    /// How the body words a computed argument's wrong type.
    pub const fn body_names(mut self, names: BodyNames) -> Builtin {
        self.body_names = names;
        self
    }

    /// The type name the body prints for a computed argument of the wrong type, given
    /// the name its argument restriction uses for a literal one (`expected`).
    pub fn runtime_type_name(&self, expected: &'static str) -> &'static str {
        match self.body_names {
            BodyNames::SymbolOrString if expected == T_LEXEME => "symbol or string",
            BodyNames::Float if expected == T_NUMBER => "float",
            BodyNames::Integer if expected == T_NUMBER => "integer",
            BodyNames::FileName if expected == "symbol or string" => "file name",
            _ => expected,
        }
    }
}

/// The type builtin `func` takes as its `index`-th (0-based) argument (any for a name
/// that is no builtin).
pub fn arg_type(func: &str, index: usize) -> ArgType {
    match lookup(func) {
        Some((_, b)) => b.signature.get(index),
        None => ArgType::Any,
    }
}

/// [`Builtin::runtime_type_name`] of builtin `func` (`expected` for a name that is no
/// builtin).
pub fn runtime_type_name(func: &str, expected: &'static str) -> &'static str {
    match lookup(func) {
        Some((_, b)) => b.runtime_type_name(expected),
        None => expected,
    }
}

impl ArgType {
    /// Whether a literal value (integer, float, symbol or string) fits.
    pub fn admits(self, v: Value) -> bool {
        match self {
            ArgType::Any => true,
            ArgType::Number => matches!(v, Value::Int(_) | Value::Float(_)),
            ArgType::Integer => matches!(v, Value::Int(_)),
            ArgType::Lexeme | ArgType::SymbolOrString => {
                matches!(v, Value::Sym(_) | Value::Str(_))
            }
            ArgType::Symbol => matches!(v, Value::Sym(_)),
            ArgType::Str => matches!(v, Value::Str(_)),
            ArgType::Sequence => matches!(v, Value::Sym(_) | Value::Str(_) | Value::Multi(_)),
            ArgType::FactOrInstance | ArgType::FactOrIndex => {
                matches!(v, Value::Int(_) | Value::Sym(_))
            }
            ArgType::Multifield | ArgType::FactAddress => false,
        }
    }

    /// Whether a call returning `r` may fit (CLIPS intersects the two types and
    /// refuses the call when nothing is left).
    pub fn admits_call(self, r: Returns) -> bool {
        use bits::*;
        let takes = match self {
            ArgType::Any => ALL,
            // (only calls that may give anything give a fact address)
            ArgType::FactAddress => FACT_ADDRESS,
            ArgType::FactOrIndex => FACT_ADDRESS | INTEGER | SYMBOL,
            ArgType::Number => INTEGER | FLOAT,
            ArgType::Integer => INTEGER,
            ArgType::Lexeme => SYMBOL | STRING | INSTANCE_NAME,
            ArgType::SymbolOrString => SYMBOL | STRING,
            ArgType::Symbol => SYMBOL,
            ArgType::Str => STRING,
            ArgType::Multifield => MULTIFIELD,
            ArgType::Sequence => MULTIFIELD | SYMBOL | STRING,
            ArgType::FactOrInstance => FACT_ADDRESS | INTEGER | SYMBOL | INSTANCE_NAME,
        };
        takes & r.types() != 0
    }

    /// CLIPS's wording in `[ARGACCES5] ... to be of type WORDING`.
    pub fn clips_name(self) -> &'static str {
        match self {
            ArgType::Any => "any",
            ArgType::Number => "integer or float",
            ArgType::Integer => "integer",
            ArgType::Lexeme => "symbol, string, or instance name",
            ArgType::SymbolOrString => "symbol or string",
            ArgType::Symbol => "symbol",
            ArgType::Str => "string",
            ArgType::Multifield => "multifield",
            ArgType::Sequence => "multifield, symbol, or string",
            ArgType::FactAddress => "fact-address",
            ArgType::FactOrIndex => "fact-address, integer, or symbol",
            ArgType::FactOrInstance => {
                "instance address, instance name, fact address, integer, or symbol"
            }
        }
    }

    /// The position line's "expected ..." text.
    pub fn expected(self) -> &'static str {
        match self {
            ArgType::Any => "an argument",
            ArgType::Number => "an argument of type integer or float",
            ArgType::Integer => "an argument of type integer",
            ArgType::Lexeme | ArgType::SymbolOrString => "an argument of type symbol or string",
            ArgType::Symbol => "an argument of type symbol",
            ArgType::Str => "an argument of type string",
            ArgType::Multifield => {
                "an argument of type multifield (a variable or call, not a literal)"
            }
            ArgType::FactAddress => {
                "an argument of type fact-address (a variable or call, not a literal)"
            }
            ArgType::FactOrInstance => "a fact index or an instance name",
            ArgType::FactOrIndex => "a fact index or a fact-address variable",
            ArgType::Sequence => "an argument of type multifield, symbol, or string",
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::builtins::BUILTINS;

    #[test]
    fn positions_past_the_listed_ones_take_the_rest_type() {
        assert_eq!(arg_type("+", 0), ArgType::Number);
        assert_eq!(arg_type("+", 7), ArgType::Number);
        assert_eq!(arg_type("nth$", 0), ArgType::Integer);
        assert_eq!(arg_type("nth$", 1), ArgType::Multifield);
        assert_eq!(arg_type("insert$", 5), ArgType::Any);
        assert_eq!(arg_type("printout", 1), ArgType::Any);
        assert_eq!(arg_type("no-such-function", 0), ArgType::Any);
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

    #[test]
    fn calls_are_judged_by_their_return_type() {
        let r = |name: &str| lookup(name).unwrap().1.returns;
        assert!(!ArgType::Number.admits_call(r("str-cat")));
        assert!(ArgType::Integer.admits_call(r("+")));
        assert!(!ArgType::Integer.admits_call(r("sqrt")));
        assert!(!ArgType::Multifield.admits_call(r("+")));
        assert!(!ArgType::Lexeme.admits_call(r("str-length")));
        assert!(ArgType::Symbol.admits_call(r("str-cat")));
        assert!(ArgType::Any.admits_call(r("printout")));
        assert!(!ArgType::Number.admits_call(r("printout")));
        assert!(ArgType::Number.admits_call(r("nth$")));
        // CLIPS's slot check lets `g` integers by
        assert_eq!(r("str-length").slot_types(), None);
        assert_eq!(r("sqrt").slot_types(), Some(crate::template::types::FLOAT));
    }

    #[test]
    fn runtime_names_differ_only_where_clips_differs() {
        assert_eq!(
            runtime_type_name("str-length", T_LEXEME),
            "symbol or string"
        );
        assert_eq!(runtime_type_name("sqrt", T_NUMBER), "float");
        assert_eq!(runtime_type_name("integer", T_NUMBER), "integer");
        assert_eq!(runtime_type_name("+", T_NUMBER), T_NUMBER);
        assert_eq!(runtime_type_name("sqrt", T_LEXEME), T_LEXEME);
    }

    #[test]
    fn fallbacks_come_from_the_rows() {
        let of = |name: &str| lookup(name).unwrap().1.on_error.fallback();
        assert_eq!(of("+"), None);
        assert_eq!(of("format"), Some(Fallback::Str("")));
        assert_eq!(of("/"), Some(Fallback::Float(1.0)));
        assert_eq!(of("nth$"), Some(Fallback::Sym("nil")));
        assert_eq!(of("find-all-facts"), Some(Fallback::EmptyMulti));
    }

    /// A total builtin is quiet; the quiet ones are the arithmetic, comparison, math,
    /// predicate and geometry functions and nothing that prints, reads or changes facts.
    #[test]
    fn purity_is_consistent() {
        for b in BUILTINS.iter() {
            if b.purity >= Purity::Quiet {
                assert!(
                    !matches!(
                        b.name,
                        "printout" | "assert" | "retract" | "modify" | "bind" | "read"
                    ),
                    "{} cannot be quiet",
                    b.name
                );
            }
        }
        let total: std::vec::Vec<&str> = BUILTINS
            .iter()
            .filter(|b| b.purity == Purity::Total)
            .map(|b| b.name)
            .collect();
        for name in ["eq", "neq", "and", "or", "not", "numberp", "multifieldp"] {
            assert!(total.contains(&name), "{name} is total");
        }
        for name in ["<", "+", "str-cat", "sqrt"] {
            assert!(!total.contains(&name), "{name} can fail");
        }
    }
}
