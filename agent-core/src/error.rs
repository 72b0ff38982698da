//! Error values. Every failure is a value naming what ran out or what was wrong.

use crate::value::Ix;
use core::fmt;

pub use crate::config::Pool;

/// The 1-based number of argument `i` (0-based) in an error: 255 stands for any
/// beyond 254 (the field is a byte; a call may have more arguments).
pub const fn arg_no(i: usize) -> u8 {
    if i >= 254 {
        255
    } else {
        i as u8 + 1
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
    /// A variable read before it was bound: `name` is its symbol (a prompt
    /// variable's hidden global is named `?x`), `NONE` when unknown.
    UnboundVariable {
        name: crate::value::SymId,
    },
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
        reason: Message,
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
    Other(Message),
}

/// An evaluation error, packed into 8 bytes: `Result<Value, EvalError>` is then no
/// larger than a value (16 bytes, returned in two registers on the host, where the
/// evaluator's results used to go through memory at 48). Names and texts are kept as
/// indices (builtin ids, [`Message`]s, [`ERROR_TEXTS`] for type names); [`EvalError::kind`]
/// gives the full description back.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct EvalError {
    /// Which `EvalErrorKind` (`code::*`).
    code: u8,
    /// CLIPS's message for it is printed already (by a deffunction it went through, which
    /// added its `[PRCCODE4]` line); callers only stop.
    pub reported: bool,
    /// The kind's fields (see `EvalError::new`).
    a: u16,
    b: u32,
}

/// `EvalError::code` of each `EvalErrorKind`.
mod code {
    pub const CAPACITY: u8 = 0;
    pub const WRONG_TYPE: u8 = 1;
    pub const ARITY: u8 = 2;
    pub const DIVIDE_BY_ZERO: u8 = 3;
    pub const UNBOUND_VARIABLE: u8 = 4;
    pub const TOO_DEEP: u8 = 5;
    pub const NO_SUCH_FACT: u8 = 6;
    pub const NO_SUCH_FUNCTION: u8 = 7;
    pub const NO_SUCH_TEMPLATE: u8 = 8;
    pub const NO_SUCH_SLOT: u8 = 9;
    pub const BAD_SLOT_VALUE: u8 = 10;
    pub const EXTERNAL: u8 = 11;
    pub const EXIT: u8 = 12;
    pub const INTERRUPTED: u8 = 13;
    pub const REPORTED: u8 = 14;
    pub const OTHER: u8 = 15;
}

/// Declares [`Message`]: every message an [`EvalError`] can carry, each with its text,
/// in one table.
macro_rules! messages {
    ($($(#[$doc:meta])* $variant:ident = $text:literal,)*) => {
        /// A message of an evaluation error ([`EvalErrorKind::Other`], the reason of
        /// [`EvalErrorKind::BadSlotValue`]): named, not looked up by its text. Texts
        /// that start with CLIPS's code (`[EMATHFUN1] ...`) are printed as they are.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Message {
            $($(#[$doc])* $variant,)*
        }

        impl Message {
            /// Every message, in declaration order (`message as usize` indexes it).
            pub const ALL: &'static [Message] = &[$(Message::$variant,)*];

            /// The message as printed.
            pub const fn text(self) -> &'static str {
                match self {
                    $(Message::$variant => $text,)*
                }
            }
        }
    };
}

messages! {
    // slot values that do not fit their slot
    TypeViolated = "type restriction violated",
    AllowedValuesViolated = "allowed-values restriction violated",
    RangeViolated = "range restriction violated",
    /// (`extras` only: `allowed-classes`; `Restriction::Classes` words it)
    ClassesViolated = "allowed-classes",
    CardinalityViolated = "cardinality restriction violated",
    SingleFieldNeedsOneValue = "a single-field slot needs exactly one value",
    NoDefault = "slot has no default and needs a value",
    // refusals and limits
    DepthStrategyOnly = "only the depth strategy is supported",
    NotTraced = "[NOTIMPL1] robotino-agent does not trace it",
    QueryTooManyVariables = "fact-set query: more than 8 query variables",
    QueryIncomplete = "fact-set query: missing query variables or query",
    FormatTooLong = "format: result longer than 2048 bytes",
    StringTooLong = "string result longer than 2048 bytes",
    ImplodeTooLong = "implode$: result longer than 2048 bytes",
    PathTooLong = "file name longer than 256 bytes",
    SyntaxError = "syntax error",
    // CLIPS's math and random messages
    SqrtDomain = "[EMATHFUN1] Domain error for sqrt function.",
    PowDomain = "[EMATHFUN1] Domain error for ** function.",
    LogDomain = "[EMATHFUN1] Domain error for log function.",
    Log10Domain = "[EMATHFUN1] Domain error for log10 function.",
    AsinDomain = "[EMATHFUN1] Domain error for asin function.",
    AcosDomain = "[EMATHFUN1] Domain error for acos function.",
    Domain = "[EMATHFUN1] Domain error.",
    LogOverflow = "[EMATHFUN2] Argument overflow for log function.",
    Log10Overflow = "[EMATHFUN2] Argument overflow for log10 function.",
    RandomRange = "[MISCFUN3] Function random expected argument #1 to be less than argument #2",
    RandomArity = "[MISCFUN2] Function random expected either 0 or 2 arguments",
    // `format`'s arity: CLIPS names the exact count its control string needs (2 to 12
    // arguments), or none beyond that
    FormatArity2 = "[ARGACCES4] Function format expected exactly 2 argument(s)",
    FormatArity3 = "[ARGACCES4] Function format expected exactly 3 argument(s)",
    FormatArity4 = "[ARGACCES4] Function format expected exactly 4 argument(s)",
    FormatArity5 = "[ARGACCES4] Function format expected exactly 5 argument(s)",
    FormatArity6 = "[ARGACCES4] Function format expected exactly 6 argument(s)",
    FormatArity7 = "[ARGACCES4] Function format expected exactly 7 argument(s)",
    FormatArity8 = "[ARGACCES4] Function format expected exactly 8 argument(s)",
    FormatArity9 = "[ARGACCES4] Function format expected exactly 9 argument(s)",
    FormatArity10 = "[ARGACCES4] Function format expected exactly 10 argument(s)",
    FormatArity11 = "[ARGACCES4] Function format expected exactly 11 argument(s)",
    FormatArity12 = "[ARGACCES4] Function format expected exactly 12 argument(s)",
    FormatArity = "[ARGACCES4] Function format called with the wrong number of arguments.",
    TanSingularity = "[EMATHFUN3] Singularity at asymptote in tan function.",
}

impl Message {
    /// `format`'s arity message for a control string that needs `expected` arguments.
    pub fn format_arity(expected: usize) -> Message {
        const EXACT: [Message; 11] = [
            Message::FormatArity2,
            Message::FormatArity3,
            Message::FormatArity4,
            Message::FormatArity5,
            Message::FormatArity6,
            Message::FormatArity7,
            Message::FormatArity8,
            Message::FormatArity9,
            Message::FormatArity10,
            Message::FormatArity11,
            Message::FormatArity12,
        ];
        EXACT
            .get(expected.wrapping_sub(2))
            .copied()
            .unwrap_or(Message::FormatArity)
    }

    /// The message of index `i` (see [`Message::ALL`]).
    fn from_index(i: u16) -> Message {
        Message::ALL
            .get(i as usize)
            .copied()
            .unwrap_or(Message::SyntaxError)
    }
}

impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.text())
    }
}

/// Texts an `EvalError` can name besides the builtins' names and its [`Message`]s:
/// callers that are not builtins and CLIPS's descriptions of argument types; the
/// common ones here, then the wordings each builtin module's `TABLE` adds
/// ([`builtins::Table`](crate::builtins::Table)). Index 0 stands for a text missing here
/// (a debug build panics on it instead).
pub const ERROR_TEXTS: &[&str] = &ALL_TEXTS;

const ALL_TEXTS: [&str; COMMON_TEXTS.len() + crate::builtins::table_text_count()] =
    crate::builtins::error_texts(COMMON_TEXTS);

/// The texts more than one module names.
const COMMON_TEXTS: &[&str] = &[
    "?",
    "deffunction",
    "external",
    // argument types, as CLIPS words them
    "integer or float",
    "integer",
    "float",
    "string",
    "multifield",
    "symbol or string",
    "symbol, string, or instance name",
    "string, instance name, symbol, float, or integer",
    "multifield, symbol, or string",
    "fact-address",
    "deftemplate fact",
    "fact-address, fact-index, or the symbol *",
    "fact-address, integer, or symbol",
    "fact-address or fact-index",
    "non-void return value",
    "symbol or positive number",
    "defmodule name",
    "watchable symbol",
    "function, deffunction, or generic function name",
    "function name, deffunction name, or defgeneric name",
    "positive number",
];

/// The index of text `s` in `ERROR_TEXTS` (0, "?", when it is missing there: a debug
/// build panics).
const fn text_id(s: &str) -> u16 {
    let mut k = 0;
    while k < ERROR_TEXTS.len() {
        if crate::symbols::same_text(ERROR_TEXTS[k], s) {
            return k as u16;
        }
        k += 1;
    }
    debug_assert!(false, "an error text missing from ERROR_TEXTS");
    0
}

/// The text of index `id` of `ERROR_TEXTS`.
fn text(id: u16) -> &'static str {
    ERROR_TEXTS.get(id as usize).copied().unwrap_or("?")
}

/// The index of a function's name: a builtin's id, else `BUILTINS.len()` plus its
/// index in `ERROR_TEXTS` (callers that are not builtins).
fn name_id(s: &str) -> u16 {
    let builtins = &crate::builtins::BUILTINS;
    match builtins.iter().position(|b| b.name == s) {
        Some(i) => i as u16,
        None => (builtins.len() + text_id(s) as usize) as u16,
    }
}

/// The name of index `id` (see `name_id`).
fn name(id: u16) -> &'static str {
    let builtins = &crate::builtins::BUILTINS;
    match builtins.get(id as usize) {
        Some(b) => b.name,
        None => text((id as usize).saturating_sub(builtins.len()) as u16),
    }
}

/// The pools by their index (`Pool as u16`).
fn pool(i: u16) -> Pool {
    Pool::ALL.get(i as usize).copied().unwrap_or(Pool::Tokens)
}

impl EvalError {
    const fn packed(code: u8, a: u16, b: u32) -> Self {
        EvalError {
            code,
            reported: false,
            a,
            b,
        }
    }

    /// An error already printed where it happened (a network error, a refused
    /// operation): evaluation just stops, nothing more is printed.
    pub fn already_reported() -> Self {
        let mut e = Self::new(EvalErrorKind::Reported);
        e.reported = true;
        e
    }

    /// Packs `kind`. Its type names and function names are stored as indices: a type
    /// name must be one of `ERROR_TEXTS` and a function name a builtin's (or listed
    /// there), else it reads
    /// back as "?" (a debug build panics). A host function reports its own failure
    /// with `EvalErrorKind::External`, after printing what it wants to say.
    pub fn new(kind: EvalErrorKind) -> Self {
        use EvalErrorKind as K;
        match kind {
            K::Capacity(c) => Self::packed(code::CAPACITY, c.pool as u16, c.capacity),
            K::WrongType {
                func,
                arg,
                expected,
            } => Self::packed(
                code::WRONG_TYPE,
                name_id(func),
                arg as u32 | (text_id(expected) as u32) << 8,
            ),
            K::Arity { func } => Self::packed(code::ARITY, name_id(func), 0),
            K::DivideByZero { func } => Self::packed(code::DIVIDE_BY_ZERO, name_id(func), 0),
            K::UnboundVariable { name } => Self::packed(code::UNBOUND_VARIABLE, 0, name as u32),
            K::TooDeep { limit } => Self::packed(code::TOO_DEEP, limit, 0),
            // 48 bits of the index: CLIPS prints what was asked for, and nothing
            // beyond that range can name a fact
            K::NoSuchFact(n) => {
                let n = n.clamp(-(1 << 47), (1 << 47) - 1);
                Self::packed(code::NO_SUCH_FACT, (n >> 32) as u16, n as u32)
            }
            K::NoSuchFunction => Self::packed(code::NO_SUCH_FUNCTION, 0, 0),
            K::NoSuchTemplate => Self::packed(code::NO_SUCH_TEMPLATE, 0, 0),
            K::NoSuchSlot => Self::packed(code::NO_SUCH_SLOT, 0, 0),
            K::BadSlotValue { reason } => Self::packed(code::BAD_SLOT_VALUE, reason as u16, 0),
            K::External => Self::packed(code::EXTERNAL, 0, 0),
            K::Exit => Self::packed(code::EXIT, 0, 0),
            K::Interrupted => Self::packed(code::INTERRUPTED, 0, 0),
            K::Reported => Self::packed(code::REPORTED, 0, 0),
            K::Other(msg) => Self::packed(code::OTHER, msg as u16, 0),
        }
    }

    /// What went wrong, with its names and numbers.
    pub fn kind(&self) -> EvalErrorKind {
        use EvalErrorKind as K;
        match self.code {
            code::CAPACITY => K::Capacity(CapacityError {
                pool: pool(self.a),
                capacity: self.b,
            }),
            code::WRONG_TYPE => K::WrongType {
                func: name(self.a),
                arg: self.b as u8,
                expected: text((self.b >> 8) as u16),
            },
            code::ARITY => K::Arity { func: name(self.a) },
            code::DIVIDE_BY_ZERO => K::DivideByZero { func: name(self.a) },
            code::UNBOUND_VARIABLE => K::UnboundVariable {
                name: self.b as crate::value::SymId,
            },
            code::TOO_DEEP => K::TooDeep { limit: self.a },
            code::NO_SUCH_FACT => {
                // the 48 bits back, sign-extended
                let n = (((self.a as u64) << 32 | self.b as u64) << 16) as i64 >> 16;
                K::NoSuchFact(n)
            }
            code::NO_SUCH_FUNCTION => K::NoSuchFunction,
            code::NO_SUCH_TEMPLATE => K::NoSuchTemplate,
            code::NO_SUCH_SLOT => K::NoSuchSlot,
            code::BAD_SLOT_VALUE => K::BadSlotValue {
                reason: Message::from_index(self.a),
            },
            code::EXTERNAL => K::External,
            code::EXIT => K::Exit,
            code::INTERRUPTED => K::Interrupted,
            code::REPORTED => K::Reported,
            _ => K::Other(Message::from_index(self.a)),
        }
    }

    /// Whether this is a full pool (most callers treat those apart), without
    /// unpacking.
    pub fn is_capacity(&self) -> bool {
        self.code == code::CAPACITY
    }

    /// An error carrying `msg` (`EvalErrorKind::Other`).
    pub const fn message(msg: Message) -> Self {
        Self::packed(code::OTHER, msg as u16, 0)
    }
    pub fn wrong_type(func: &'static str, arg: u8, expected: &'static str) -> Self {
        Self::new(EvalErrorKind::WrongType {
            func,
            arg,
            expected,
        })
    }
}

impl fmt::Debug for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EvalError")
            .field("kind", &self.kind())
            .field("reported", &self.reported)
            .finish()
    }
}

impl From<CapacityError> for EvalError {
    fn from(c: CapacityError) -> Self {
        Self::new(EvalErrorKind::Capacity(c))
    }
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind() {
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
            EvalErrorKind::UnboundVariable { .. } => write!(f, "unbound variable"),
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
    /// How far CLIPS shows the construct after `ERROR:` (a byte offset in the parsed
    /// text, the end of the last token it read), and how it joins that last token;
    /// 0 when we do not show it.
    pub echo_end: u32,
    pub echo_tail: EchoTail,
    /// An error in a fact-set query's actions: CLIPS then adds its syntax error for
    /// the query (`[PRNTUTIL2] ... fact-set query function.`).
    pub query_syntax: bool,
}

/// How CLIPS's `ERROR:` text joins the token at which it stopped (its pretty-print
/// buffer saves separators around tokens at fixed places).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EchoTail {
    /// As in a pretty-printed construct.
    Normal,
    /// With a space before it even when it is a `)`: `(range 1 )`.
    SpaceBefore,
    /// Without a space before it: `(range 1 23`.
    Glued,
    /// With a space after it: `(allowed-symbols 1 `.
    SpaceAfter,
    /// Followed by a `(`: a fact-set query's action CLIPS stopped reading (its
    /// pretty-print buffer backs up over the last token and adds the action's `(`).
    OpenParen,
    /// The text from the error's `start` as written, on a line of its own after the
    /// CEs before it: a lone variable where a CE was due (`?x =>`).
    OwnLine,
    /// The text from the error's `start` as written, one space after the text before
    /// it even where a pattern glues it: a constraint's `&` or `|` in a fact (`(a b &`).
    Spaced,
}

/// Which restriction of a slot a value breaks, as `[CSTRNCHK1]` words it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Restriction {
    /// "does not match the allowed types"
    Type,
    /// "does not match the allowed values"
    Values,
    /// "does not fall in the allowed range MIN to MAX"
    Range,
    /// "does not satisfy the cardinality restrictions"
    Cardinality,
    /// "does not match the allowed classes" (an instance name or address where
    /// `allowed-classes` names classes: there are no instances here; `extras`)
    #[cfg(feature = "extras")]
    Classes,
}

impl EvalError {
    /// The restriction a `BadSlotValue` error names (`Values` for any other).
    pub fn restriction(&self) -> Restriction {
        match self.kind() {
            EvalErrorKind::BadSlotValue {
                reason: Message::TypeViolated,
            } => Restriction::Type,
            EvalErrorKind::BadSlotValue {
                reason: Message::RangeViolated,
            } => Restriction::Range,
            EvalErrorKind::BadSlotValue {
                reason: Message::CardinalityViolated,
            } => Restriction::Cardinality,
            #[cfg(feature = "extras")]
            EvalErrorKind::BadSlotValue {
                reason: Message::ClassesViolated,
            } => Restriction::Classes,
            _ => Restriction::Values,
        }
    }
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
    /// A syntax error CLIPS names by the part it was reading ("function calls", "first
    /// field of a RHS pattern") rather than by the construct.
    SyntaxOf {
        part: &'static str,
    },
    /// An error CLIPS words as `text` (its id and message, e.g. `[PRNTUTIL10] Salience
    /// value must be an integer value.`), shown with the construct as a syntax error is.
    Text {
        text: &'static str,
    },
    /// `break` outside a loop's body, `return` at the prompt (`[PRCDRPSR2]`).
    NotInContext {
        func: &'static str,
    },
    /// `[EXPRNPSR4]`: a sequence expansion (`expand$`, or `$?x` with
    /// sequence-operator recognition) among the arguments of `func`, which takes none.
    SequenceOperator {
        func: &'static str,
        /// In the actions of a rule or deffunction: CLIPS shows the whole construct.
        whole: bool,
    },
    /// A static default whose expression failed when the deftemplate was defined: the
    /// evaluation error was printed then, and CLIPS adds no syntax error (only the
    /// construct after `ERROR:`).
    DefaultEvaluation,
    /// `[CSTRNCHK1]`: a literal slot value violates the slot's type (`types`) or
    /// allowed values.
    Constraint {
        slot: Ix,
        /// The slot's range (for `Restriction::Range`'s message).
        range: Ix,
        command: &'static str,
        what: Restriction,
    },
    /// `[TMPLTDEF1]`: a slot name the template does not have (the offending token).
    UnknownSlot {
        template: Ix,
        /// In a rule's `modify`/`duplicate`: CLIPS checks those once the rule is
        /// read, and shows it whole (else up to the slot name).
        whole: bool,
    },
    /// `[CSTRNCHK1]`: a literal in a slot's `default`/`default-dynamic` (`attribute`)
    /// violates the slot's type (`types`) or allowed values; or (`call`) a function
    /// call there returns a type the slot never holds.
    DefaultConstraint {
        slot: Ix,
        range: Ix,
        attribute: &'static str,
        what: Restriction,
        call: bool,
    },
    /// `[CSTRNCHK1]`: a literal in a pattern's slot constraint (CE number `ce`)
    /// violates the slot's type (`types`) or allowed values.
    PatternConstraint {
        slot: Ix,
        range: Ix,
        ce: u8,
        what: Restriction,
    },
    /// `[RULECSTR1]`: a variable whose constraints in CE `ce`, slot `slot`, conflict
    /// with those it has elsewhere in the rule (the offending token is the variable).
    VariableConflict {
        slot: Ix,
        ce: u8,
    },
    /// `[RULECSTR3]`: a variable whose bindings leave it no value argument `arg` of the
    /// call at `call_start..call_end` (of the text) takes, in a rule's actions (the
    /// offending token is the variable); `passes` as `parser::rhs_types::Found` has it.
    /// `[RULECSTR2]`: the same in a test CE or `:`/`=` constraint of CE `ce` (in
    /// template slot `slot`, else field `field` of an ordered pattern, 0 for a test).
    #[cfg(feature = "extras")]
    LhsArgumentType {
        call_start: u32,
        call_end: u32,
        slot: Ix,
        arg: u16,
        ce: u8,
        field: u8,
    },
    #[cfg(feature = "extras")]
    RhsArgumentType {
        call_start: u32,
        call_end: u32,
        arg: u16,
        passes: u8,
    },
    /// `[CSTRNPSR2]`: a range's (or a cardinality's, `cardinality`) minimum above its
    /// maximum.
    MinAboveMax {
        cardinality: bool,
    },
    /// `[CSTRNPSR5]`: `cardinality` on a single-field slot.
    CardinalityOfSingle,
    /// `[CSTRNPSR6]`: a negative minimum cardinality.
    CardinalityBelowZero,
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
    /// `[PRNTUTIL5]`: a slot's facet named twice (at its second name; `multi`: the
    /// second is a `multifacet`).
    FacetTwice {
        multi: bool,
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
    /// `[DEFAULT1]`: a single-field slot's default with no value, several, or a
    /// multifield call.
    DefaultSingle,
    /// `[DFFNXPSR1]`: a deffunction named like a construct keyword.
    ReplacesConstruct,
    /// `[PATTERN1]`: a deftemplate named like a conditional element keyword.
    SpecialMeaning,
    /// `[PATTERN1]`: a fact (asserted, in a deffacts) whose relation name is a
    /// conditional element keyword.
    RelationKeyword,
    /// `[PRCCODE3]`: a variable the actions of a rule or a deffunction's body read
    /// but nothing binds (the offending token); CLIPS shows the whole construct.
    UndefinedVariable,
    /// `[RULEPSR1]` (a logical CE after another CE) or, `gap`, `[RULEPSR2]` (after a
    /// CE that follows logical ones); CLIPS shows the whole rule.
    LogicalOrder {
        gap: bool,
    },
    /// `[PRCCODE7]`: a deffunction parameter named twice (at the second).
    ParameterTwice,
    /// `[PRCCODE8]`: a parameter after the `$?` wildcard parameter (at it).
    ParameterAfterWildcard,
    /// `[ANALYSIS3]`: one LHS variable used both as `?x` and `$?x` (the offending token).
    MixedVariable,
    /// `[PATTERN2]`: a field constraint mixing a `=(...)` of a multifield function
    /// with a variable or literal (host only: the image does not check).
    #[cfg(feature = "extras")]
    MixedConstraint,
    /// `[RULECSTR1]` of one field constraint whose literals conflict (`abc&~abc`,
    /// `abc&def`): in CE `ce`, slot `slot` (NONE: field `field` of an ordered
    /// pattern), on the leading variable when `var` (the offending token), else on the
    /// pattern (host only).
    #[cfg(feature = "extras")]
    LiteralConflict {
        ce: u8,
        slot: Ix,
        field: u8,
        var: bool,
    },
    /// `[ANALYSIS1]` (`earlier_field` false) or `[ANALYSIS2]`: a fact-address variable
    /// (the offending token) bound in CE #`ce` that an earlier CE bound already, to a
    /// fact or to a field.
    AddressBound {
        ce: u8,
        earlier_field: bool,
    },
    /// `[PRNTUTIL5]`: a slot given twice in one pattern or fact (at its second name).
    SlotTwice,
    /// `[MODULDEF1]`: a module specifier on a fact's or pattern's relation name (the
    /// offending token).
    ModuleSpecifier,
    /// `[FACTQPSR1]` (`what` 1: a query variable declared twice), `[FACTQPSR2]` (2: a
    /// `bind` in the query's condition) or `[FACTQPSR3]` (3: a query variable, the
    /// offending token, bound in the actions) in fact-set query function `func`.
    Query {
        what: u8,
        func: &'static str,
    },
    /// `[CSTRCPSR3]`: an ordered fact or pattern (its relation name the offending
    /// token) whose implied deftemplate would clash with the imports and exports.
    ImpliedConflict,
    /// `[CSTRCPSR3]`: a construct (`construct`, named by the offending token) whose
    /// name clashes with the imports and exports of the modules.
    ImportConflict {
        construct: &'static str,
    },
    /// `[MODULPSR1]`: an import of what the module (`module`, its name) does not
    /// export: anything (`class` ""), anything of a class, or construct `name`.
    NotExported {
        module: Ix,
        name: Ix,
        class: &'static str,
    },
    /// `[GLOBLPSR1]`: a global variable the module does not see (the offending
    /// token), read (`whole`: CLIPS shows the whole rule or deffunction) or set by
    /// `bind` (shown up to it).
    UndefinedGlobal {
        whole: bool,
    },
    /// `[CSTRCPSR3]`: a defmodule importing two constructs of one class (`class`, its
    /// keyword) and name (`name`) from different modules.
    ModuleImportConflict {
        name: Ix,
        class: &'static str,
    },
    /// `[ANALYSIS4]`: a variable (the offending token) read in a rule's conditions
    /// before a pattern binds it, in CE #`ce`, at the ordered pattern's `field`
    /// (1-based) or the template's `slot` (NONE and 0 in a test CE).
    UnboundInLhs {
        slot: Ix,
        ce: u8,
        field: u8,
        /// Read in a call (`:(...)`, `=(...)`, a test), which CLIPS names; else a
        /// plain constraint (`?x&~?y`).
        in_call: bool,
    },
    /// `[CSTRCPSR2]`: a construct keyword not followed by a name (the offending
    /// token, `)` when there is nothing).
    MissingName,
    /// `[PRNTUTIL1]`: a defmodule importing from a module that does not exist (the
    /// offending token).
    NoSuchModule,
    /// `[PRNTUTIL1]`: a fact-set query names a template that does not exist (the
    /// offending token).
    NoSuchTemplate,
    /// `[COMMLINE1]`: a token that starts no command at the prompt (`)`, `&`, `|`,
    /// `~`, a lone `?` or `$?`).
    NotACommand,
    /// `[COMMLINE2]`: a command's `(` followed by no function name (a constant, a
    /// variable, another `(`...).
    ExpectedCommand,
    /// `[NOTIMPL1]` (ours, not CLIPS's): something robotino-agent does not implement
    /// yet (`what`, e.g. "defmodule"), refused rather than accepted and ignored.
    NotImplemented {
        what: &'static str,
    },
    /// `[ARGACCES4]` for a call of a deffunction (its name is the offending token):
    /// `nparams` arguments expected, or at least that many (`rest`).
    FunctionArity {
        nparams: u8,
        rest: bool,
    },
    /// Not an error: `check-syntax` read the construct whole and it stops before
    /// defining it (the parser's `check_only` mode); it rolls back as an error does.
    Checked,
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
        match e.kind() {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::value::Value;

    /// The string literals the engine's sources give an error as a text or a function
    /// name (`Other("..")`, `other("..")`, `reason: ".."`, `func: ".."`, the last
    /// argument of `wrong_type(..)`; a `WrongType`'s `expected` is written through
    /// `wrong_type`, the field name is also a `LoadError`'s): each must survive packing,
    /// so a text missing from `ERROR_TEXTS` fails here rather than printing "?". Every
    /// function named in the sources is a builtin with `extras` and `parser` only.
    #[cfg(all(feature = "extras", feature = "parser"))]
    #[test]
    fn every_error_text_in_the_sources_is_listed() {
        extern crate std;
        use std::string::String;
        use std::vec::Vec;
        fn files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
            for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
                let p = entry.path();
                if p.is_dir() {
                    files(&p, out);
                } else if p.extension().is_some_and(|e| e == "rs") {
                    out.push(p);
                }
            }
        }
        /// The literal starting right after `at` (just past its opening quote), unless
        /// it stands in a comment.
        fn literal(text: &str, at: usize) -> Option<&str> {
            let line = &text[text[..at].rfind('\n').map_or(0, |n| n + 1)..at];
            if line.trim_start().starts_with("//") {
                return None;
            }
            text[at..].find('"').map(|end| &text[at..at + end])
        }
        let mut paths = Vec::new();
        files(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
            &mut paths,
        );
        let (mut texts, mut funcs): (Vec<String>, Vec<String>) = (Vec::new(), Vec::new());
        for path in &paths {
            let text = std::fs::read_to_string(path).unwrap_or_default();
            for (i, _) in text.match_indices("func: \"") {
                funcs.extend(literal(&text, i + 7).map(String::from));
            }
            for (i, _) in text.match_indices("wrong_type(") {
                let call = &text[i..];
                let Some(close) = call.find(')') else {
                    continue;
                };
                if literal(&text, i).is_none() {
                    continue;
                }
                let args = call[..close].trim_end().trim_end_matches(',');
                if let Some(body) = args.strip_suffix('"') {
                    if let Some(open) = body.rfind('"') {
                        texts.push(String::from(&body[open + 1..]));
                    }
                }
            }
        }
        assert!(texts.len() > 10 && !funcs.is_empty(), "{texts:?} {funcs:?}");
        for t in texts {
            let leaked: &'static str = std::boxed::Box::leak(t.into_boxed_str());
            assert!(
                ERROR_TEXTS.contains(&leaked),
                "error text {leaked:?} is missing from ERROR_TEXTS"
            );
        }
        for f in funcs {
            let leaked: &'static str = std::boxed::Box::leak(f.into_boxed_str());
            let kind = EvalError::new(EvalErrorKind::Arity { func: leaked }).kind();
            assert_eq!(
                kind,
                EvalErrorKind::Arity { func: leaked },
                "function name {leaked:?}"
            );
        }
    }

    /// Every kind comes back from its 8 bytes as it went in: each builtin's name and
    /// each text of `ERROR_TEXTS` in every field that holds one, numbers at their edges.
    #[test]
    fn errors_keep_their_kind_in_eight_bytes() {
        assert_eq!(core::mem::size_of::<EvalError>(), 8);
        assert_eq!(
            core::mem::size_of::<Result<Value, EvalError>>(),
            core::mem::size_of::<Value>()
        );
        let mut kinds = [EvalErrorKind::Exit; 16];
        let simple = [
            EvalErrorKind::UnboundVariable { name: 7 },
            EvalErrorKind::NoSuchFunction,
            EvalErrorKind::NoSuchTemplate,
            EvalErrorKind::NoSuchSlot,
            EvalErrorKind::External,
            EvalErrorKind::Exit,
            EvalErrorKind::Interrupted,
            EvalErrorKind::Reported,
            EvalErrorKind::TooDeep { limit: u16::MAX },
            EvalErrorKind::NoSuchFact(-7),
            EvalErrorKind::NoSuchFact(0),
            EvalErrorKind::NoSuchFact(5_000_000_000),
            EvalErrorKind::NoSuchFact((1 << 47) - 1),
            EvalErrorKind::NoSuchFact(-(1 << 47)),
            EvalErrorKind::Capacity(CapacityError {
                pool: Pool::ExternalFns,
                capacity: u32::MAX,
            }),
            EvalErrorKind::Capacity(CapacityError {
                pool: Pool::Facts,
                capacity: 0,
            }),
        ];
        kinds.copy_from_slice(&simple);
        for k in kinds {
            assert_eq!(EvalError::new(k).kind(), k);
        }
        let names = crate::builtins::BUILTINS
            .iter()
            .map(|b| b.name)
            .chain(["deffunction", "external"]);
        for func in names {
            for k in [
                EvalErrorKind::Arity { func },
                EvalErrorKind::DivideByZero { func },
                EvalErrorKind::WrongType {
                    func,
                    arg: 255,
                    expected: "integer or float",
                },
            ] {
                assert_eq!(EvalError::new(k).kind(), k);
            }
        }
        for &t in &ERROR_TEXTS[1..] {
            let k = EvalErrorKind::WrongType {
                func: "+",
                arg: 1,
                expected: t,
            };
            assert_eq!(EvalError::new(k).kind(), k);
        }
        for &m in Message::ALL {
            for k in [
                EvalErrorKind::Other(m),
                EvalErrorKind::BadSlotValue { reason: m },
            ] {
                assert_eq!(EvalError::new(k).kind(), k);
            }
        }
        // beyond 48 bits a fact index is clamped (no fact has one)
        assert_eq!(
            EvalError::new(EvalErrorKind::NoSuchFact(i64::MAX)).kind(),
            EvalErrorKind::NoSuchFact((1 << 47) - 1)
        );
        let mut reported = EvalError::message(Message::SyntaxError);
        reported.reported = true;
        assert_eq!(reported.kind(), EvalErrorKind::Other(Message::SyntaxError));
        assert!(EvalError::from(CapacityError {
            pool: Pool::Tokens,
            capacity: 3
        })
        .is_capacity());
    }
}
