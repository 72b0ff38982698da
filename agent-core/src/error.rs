//! Error values. Every failure is a value naming what ran out or what was wrong.

use crate::value::Ix;
use core::fmt;

/// A fixed-capacity pool of the engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pool {
    Facts,
    FactValues,
    Symbols,
    SymbolBytes,
    Templates,
    SlotDefs,
    Rules,
    AlphaNodes,
    Joins,
    Tokens,
    Activations,
    Functions,
    Globals,
    Exprs,
    EvalStack,
    Scratch,
    Deffacts,
    ExternalFns,
}

impl Pool {
    pub const ALL: [Pool; 18] = [
        Pool::Facts,
        Pool::FactValues,
        Pool::Symbols,
        Pool::SymbolBytes,
        Pool::Templates,
        Pool::SlotDefs,
        Pool::Rules,
        Pool::AlphaNodes,
        Pool::Joins,
        Pool::Tokens,
        Pool::Activations,
        Pool::Functions,
        Pool::Globals,
        Pool::Exprs,
        Pool::EvalStack,
        Pool::Scratch,
        Pool::Deffacts,
        Pool::ExternalFns,
    ];

    pub const fn name(self) -> &'static str {
        match self {
            Pool::Facts => "facts",
            Pool::FactValues => "fact values",
            Pool::Symbols => "symbols",
            Pool::SymbolBytes => "symbol bytes",
            Pool::Templates => "templates",
            Pool::SlotDefs => "slot definitions",
            Pool::Rules => "rules",
            Pool::AlphaNodes => "alpha nodes",
            Pool::Joins => "joins",
            Pool::Tokens => "tokens",
            Pool::Activations => "activations",
            Pool::Functions => "deffunctions",
            Pool::Globals => "globals",
            Pool::Exprs => "expression nodes",
            Pool::EvalStack => "evaluation stack",
            Pool::Scratch => "multifield scratch",
            Pool::Deffacts => "deffacts",
            Pool::ExternalFns => "external functions",
        }
    }
}

/// A pool ran out: which one, and how big it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CapacityError {
    pub pool: Pool,
    pub capacity: u32,
}

impl fmt::Display for CapacityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "out of {} (capacity {})",
            self.pool.name(),
            self.capacity
        )
    }
}

/// Why an evaluation failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EvalErrorKind {
    Capacity(CapacityError),
    /// A function got an argument of the wrong type; `arg` is 1-based.
    WrongType {
        func: &'static str,
        arg: u8,
        expected: &'static str,
    },
    Arity {
        func: &'static str,
    },
    DivideByZero {
        func: &'static str,
    },
    UnboundVariable,
    /// Function calls nested deeper than the evaluator allows (`limit`, the
    /// `eval::MAX_EVAL_DEPTH`): a runaway recursion, stopped before the Rust stack is.
    TooDeep {
        limit: u16,
    },
    NoSuchFact(i64),
    NoSuchFunction,
    NoSuchTemplate,
    NoSuchSlot,
    BadSlotValue {
        reason: &'static str,
    },
    /// A host-registered function reported failure.
    External,
    /// `(halt)`/`(exit)` requested; not an error for callers of `run`.
    Exit,
    /// The host's `interrupt` returned true: the running loop or rule firing stopped.
    Interrupted,
    /// The message is already printed (a builtin whose CLIPS message names run-time
    /// details, or a deffunction that added its `[PRCCODE4]` line): evaluation just stops.
    Reported,
    Other(&'static str),
}

/// An evaluation error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EvalError {
    pub kind: EvalErrorKind,
    /// CLIPS's message for it is printed already (by a deffunction it went through, which
    /// added its `[PRCCODE4]` line); callers only stop.
    pub reported: bool,
}

impl EvalError {
    pub const fn new(kind: EvalErrorKind) -> Self {
        EvalError {
            kind,
            reported: false,
        }
    }
    pub const fn other(msg: &'static str) -> Self {
        EvalError {
            kind: EvalErrorKind::Other(msg),
            reported: false,
        }
    }
    pub const fn wrong_type(func: &'static str, arg: u8, expected: &'static str) -> Self {
        EvalError {
            kind: EvalErrorKind::WrongType {
                func,
                arg,
                expected,
            },
            reported: false,
        }
    }
}

impl From<CapacityError> for EvalError {
    fn from(c: CapacityError) -> Self {
        EvalError {
            kind: EvalErrorKind::Capacity(c),
            reported: false,
        }
    }
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            EvalErrorKind::Capacity(c) => write!(f, "{c}"),
            EvalErrorKind::WrongType {
                func,
                arg,
                expected,
            } => {
                write!(
                    f,
                    "function {func} expected argument #{arg} to be of type {expected}"
                )
            }
            EvalErrorKind::Arity { func } => {
                write!(f, "function {func}: wrong number of arguments")
            }
            EvalErrorKind::DivideByZero { func } => {
                write!(f, "division by zero in function {func}")
            }
            EvalErrorKind::UnboundVariable => write!(f, "unbound variable"),
            EvalErrorKind::TooDeep { limit } => write!(
                f,
                "function calls nested deeper than the evaluation depth limit ({limit})"
            ),
            EvalErrorKind::NoSuchFact(n) => write!(f, "unable to find fact f-{n}"),
            EvalErrorKind::NoSuchFunction => write!(f, "no such function"),
            EvalErrorKind::NoSuchTemplate => write!(f, "no such template"),
            EvalErrorKind::NoSuchSlot => write!(f, "no such slot"),
            EvalErrorKind::BadSlotValue { reason } => write!(f, "bad slot value: {reason}"),
            EvalErrorKind::External => write!(f, "external function failed"),
            EvalErrorKind::Exit => write!(f, "exit requested"),
            EvalErrorKind::Interrupted => write!(f, "execution interrupted by the host"),
            EvalErrorKind::Reported => write!(f, "error (already reported)"),
            EvalErrorKind::Other(m) => write!(f, "{m}"),
        }
    }
}

/// Where in the source a parse error happened and what the parser wanted there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// 1-based line and column.
    pub line: u32,
    pub col: u32,
    /// What the parser expected (e.g. "a slot name").
    pub expected: &'static str,
    /// The construct kind being parsed ("defrule", "deftemplate", ...), for CLIPS's message.
    pub construct: &'static str,
    /// Set when the error was a full pool rather than bad syntax.
    pub capacity: Option<CapacityError>,
    /// Byte range of the offending token in the parsed text (for quoting it).
    pub start: u32,
    pub end: u32,
    /// Extra detail for CLIPS's message.
    pub detail: LoadDetail,
}

/// Which CLIPS message a load error corresponds to. (`Ix` fields come before the
/// others: derived `PartialEq` compares fields spelled as primitive types first, so
/// this keeps the comparison, and the image's code, as it was with `u16` fields.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadDetail {
    Syntax,
    /// `[ARGACCES4]`: a call with the wrong number of arguments.
    Arity {
        got: Ix,
        func: &'static str,
        min: u8,
        max: u8,
    },
    /// `[EXPRNPSR3]`: unknown function (its name is the offending token).
    MissingFunction,
    /// `[CSTRNCHK1]`: a literal slot value violates the slot's type (`types`) or
    /// allowed values.
    Constraint {
        slot: Ix,
        command: &'static str,
        types: bool,
    },
    /// `[TMPLTDEF1]`: a slot name the template does not have (the offending token).
    UnknownSlot {
        template: Ix,
    },
    /// `[CSTRNCHK1]`: a literal in a slot's `default`/`default-dynamic` (`attribute`)
    /// violates the slot's type (`types`) or allowed values.
    DefaultConstraint {
        slot: Ix,
        attribute: &'static str,
        types: bool,
    },
    /// `[CSTRNCHK1]`: a literal in a pattern's slot constraint (CE number `ce`)
    /// violates the slot's type (`types`) or allowed values.
    PatternConstraint {
        ce: u8,
        types: bool,
        slot: Ix,
    },
    /// `[TMPLTDEF2]`: a single-field slot given no value or several.
    SingleSlot {
        slot: Ix,
    },
    /// `[TMPLTRHS1]`: an assert leaves out a slot declared `(default ?NONE)`.
    RequiredSlot {
        slot: Ix,
    },
    /// `[ARGACCES5]`: a literal argument of a type the function does not take; `arg`
    /// is 1-based, `expected` CLIPS's wording of the types.
    ArgType {
        arg: Ix,
        func: &'static str,
        expected: &'static str,
    },
    /// `[CSTRCPSR4]`: redefining a construct that is in use (its name is the token).
    InUse {
        construct: &'static str,
    },
    /// `[PRNTUTIL5]`: a slot attribute given twice (at its second name).
    AttributeTwice {
        attribute: &'static str,
    },
    /// `[CSTRNPSR3]`: `allowed-values` combined with another `allowed-...` attribute.
    AllowedCombined {
        first: &'static str,
        second: &'static str,
    },
    /// `[CSTRNPSR4]`: a value of another type in an `allowed-...` attribute.
    AllowedValueType {
        attribute: &'static str,
    },
    /// `[CSTRNPSR1]`: the slot's `type` excludes an allowed value (at the value).
    TypeConflict {
        attribute: &'static str,
    },
    /// `[TMPLTFUN1]`: `modify`/`duplicate` (`command`) of a fact index inside a rule or
    /// deffunction.
    FactIndexInRule {
        command: &'static str,
    },
    /// `[DFFNXPSR2]`: a deffunction named like a builtin function.
    ReplacesBuiltin,
    /// `[ANALYSIS3]`: one LHS variable used both as `?x` and `$?x` (the offending token).
    MixedVariable,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(c) = self.capacity {
            write!(f, "{}:{}: {c}", self.line, self.col)
        } else {
            write!(f, "{}:{}: expected {}", self.line, self.col, self.expected)
        }
    }
}

/// Errors of engine-level operations (reset, run, assert from the host).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineError {
    Capacity(CapacityError),
    Eval(EvalError),
    Load(LoadError),
    NoSuchFact(u32),
    Duplicate,
}

impl From<CapacityError> for EngineError {
    fn from(c: CapacityError) -> Self {
        EngineError::Capacity(c)
    }
}
impl From<EvalError> for EngineError {
    fn from(e: EvalError) -> Self {
        match e.kind {
            EvalErrorKind::Capacity(c) => EngineError::Capacity(c),
            _ => EngineError::Eval(e),
        }
    }
}
impl From<LoadError> for EngineError {
    fn from(e: LoadError) -> Self {
        EngineError::Load(e)
    }
}

impl fmt::Display for EngineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EngineError::Capacity(c) => write!(f, "{c}"),
            EngineError::Eval(e) => write!(f, "{e}"),
            EngineError::Load(e) => write!(f, "{e}"),
            EngineError::NoSuchFact(n) => write!(f, "unable to find fact f-{n}"),
            EngineError::Duplicate => write!(f, "fact already exists"),
        }
    }
}

/// A file operation of the host failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HostIoError {
    NotFound,
    TooLarge,
    Unsupported,
    Other,
}
