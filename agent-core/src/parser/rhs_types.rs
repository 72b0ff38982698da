//! CLIPS 6.30's `[RULECSTR3]`: once a rule is read, each variable passed straight to a
//! builtin in its actions must be able to hold a value of a type that argument takes
//! (host only, feature `extras`).
//!
//! CLIPS keeps for each variable a constraint record: what its LHS binding allows (the
//! slots' types it stands in, a fact address for `?f <- (...)`, a multifield for `$?x`),
//! united with what every `bind` of it in the actions gives (the type of a literal, a
//! builtin's return type, anything for a variable or a deffunction call; only the first
//! value of a `bind` counts, and binds after the call in the text count too). That record
//! is intersected with the argument's restriction (`get-function-restrictions`'s letter
//! for the position); the rule is refused when nothing is left (`(bind ?x abc) (+ ?x 1)`,
//! `(t (s ?v))` with `s` a SYMBOL slot and `(+ ?v 1)`, a multifield variable where a
//! single value goes, a single value where a multifield goes). Loop and fact-set query
//! variables are not checked (CLIPS replaces them by calls), nor arguments of
//! deffunctions, nor values inside `assert`/`modify` facts.
//!
//! `[RULECSTR2]` is the same check, without binds, of the calls in test CEs and `:`/`=`
//! constraints once the LHS is read (multifield variables are not checked there).
//!
//! The check reads the text again (the expression tree has lost the variables' names)
//! with CLIPS's view of its structure, but only for a rule that can fail it: while the
//! parser reads the rule it notes each variable passed straight to a builtin argument
//! that restricts it and the first value of each `bind` ([`RuleNotes`]);
//! [`RuleNotes::may_fail`] runs the constraint logic over those notes, and only when it
//! finds a violation is the text read again (for the message's call, and CLIPS's
//! order). The
//! notes give each variable at most the record the text gives it (a call whose
//! arguments expand counts as its builtin's return type), so a rule they pass passes.

use core::fmt::{self, Write};

use crate::builtins::describe::Returns;
use crate::lexer::{Lexer, Tok, Token};

// the type flags of a constraint record
const SYM: u16 = 1;
const STR: u16 = 2;
const INT: u16 = 4;
const FLT: u16 = 8;
const INAME: u16 = 16;
const IADDR: u16 = 32;
const FADDR: u16 = 64;
const EADDR: u16 = 128;
const VOID: u16 = 256;
const ALL_TYPES: u16 = 511;

/// The part of CLIPS's constraint record its `UnmatchableConstraint` looks at (allowed
/// values, ranges and cardinalities never empty a record here).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rec {
    any: bool,
    types: u16,
    single: bool,
    multi: bool,
}

impl Rec {
    /// CLIPS's fresh record: any single value.
    pub const ANY: Rec = Rec {
        any: true,
        types: 0,
        single: true,
        multi: false,
    };
    /// Anything, a multifield too (a variable's or deffunction's value).
    pub const ANYTHING: Rec = Rec {
        any: true,
        types: 0,
        single: true,
        multi: true,
    };
    /// A multifield LHS variable (`$?x`).
    pub const MULTIFIELD_VAR: Rec = Rec {
        any: false,
        types: 0,
        single: true,
        multi: true,
    };
    /// A fact-address variable (`?f <- (...)`).
    pub const FACT_ADDRESS: Rec = Rec::of(FADDR);

    const fn of(types: u16) -> Rec {
        Rec {
            any: false,
            types,
            single: true,
            multi: false,
        }
    }

    /// A single-field LHS variable whose slots allow `types` (`template::types` bits,
    /// 0xFF for any).
    pub fn slot_types(types: u8) -> Rec {
        use crate::template::types as t;
        if types == 0xFF {
            return Rec::ANY;
        }
        let pairs = [
            (t::SYMBOL, SYM),
            (t::STRING, STR),
            (t::INTEGER, INT),
            (t::FLOAT, FLT),
            (t::FACT_ADDRESS, FADDR),
            (t::INSTANCE_NAME, INAME),
            (t::INSTANCE_ADDRESS, IADDR),
        ];
        let mut r = 0;
        for (from, to) in pairs {
            if types & from != 0 {
                r |= to;
            }
        }
        Rec::of(r)
    }

    /// The `template::types` bits of a record of single values (0xFF: any, or
    /// nothing a slot could hold).
    fn template_types(self) -> u8 {
        use crate::template::types as t;
        if self.any || !self.single {
            return 0xFF;
        }
        let pairs = [
            (SYM, t::SYMBOL),
            (STR, t::STRING),
            (INT, t::INTEGER),
            (FLT, t::FLOAT),
            (FADDR, t::FACT_ADDRESS),
            (INAME, t::INSTANCE_NAME),
            (IADDR, t::INSTANCE_ADDRESS),
        ];
        let mut r = 0;
        for (from, to) in pairs {
            if self.types & from != 0 {
                r |= to;
            }
        }
        if r == 0 {
            0xFF
        } else {
            r
        }
    }

    /// CLIPS's `ArgumentTypeToConstraintRecord` of restriction letter `c`.
    fn of_argument(c: u8) -> Rec {
        let types = match c {
            b'a' => EADDR,
            b'e' => SYM | INAME | IADDR,
            b'd' | b'f' => FLT,
            b'g' => INT | FLT | SYM,
            b'h' => FADDR | INT | SYM | INAME | IADDR,
            b'i' | b'l' => INT,
            b'j' => SYM | STR | INAME,
            b'k' => SYM | STR,
            b'n' => INT | FLT,
            b'o' => INAME,
            b'p' => INAME | SYM,
            b's' => STR,
            b'w' => SYM,
            b'x' => IADDR,
            b'y' => FADDR,
            b'z' => SYM | FADDR | INT,
            b'v' => VOID,
            b'm' => {
                return Rec {
                    any: false,
                    types: 0,
                    single: false,
                    multi: true,
                }
            }
            b'q' => {
                return Rec {
                    multi: true,
                    ..Rec::of(SYM | STR)
                }
            }
            // `u` and anything we do not know
            _ => return Rec::ANYTHING,
        };
        Rec::of(types)
    }

    /// CLIPS's `FunctionCallToConstraintRecord`: what a call of a builtin returning
    /// `r` gives.
    pub fn of_call(r: Returns) -> Rec {
        Rec::of(match r {
            Returns::Any => return Rec::ANYTHING,
            Returns::Number => INT | FLT,
            Returns::Integer => INT,
            Returns::Float => FLT,
            Returns::Symbol => SYM,
            Returns::Str => STR,
            Returns::Lexeme => SYM | STR | INAME,
            Returns::SymbolOrString => SYM | STR,
            Returns::Void => VOID,
            Returns::Multifield => {
                return Rec {
                    any: false,
                    types: 0,
                    single: false,
                    multi: true,
                }
            }
        })
    }

    /// A literal's record (`[x]` is an instance name).
    fn of_literal(t: Tok<'_>) -> Rec {
        Rec::of(match t {
            Tok::Int(_) | Tok::IntOverflow(_) => INT,
            Tok::Float(_) => FLT,
            Tok::Str(_) => STR,
            Tok::Symbol(s) if crate::value::instance_name_body(s).is_some() => INAME,
            _ => SYM,
        })
    }

    /// CLIPS's `UnionConstraints` (None: no record).
    fn union(a: Option<Rec>, b: Option<Rec>) -> Rec {
        match (a, b) {
            (None, None) => Rec::ANY,
            (Some(x), None) | (None, Some(x)) => x,
            (Some(x), Some(y)) => {
                let any = x.any || y.any;
                Rec {
                    any,
                    types: if any { 0 } else { x.types | y.types },
                    single: x.single || y.single,
                    multi: x.multi || y.multi,
                }
            }
        }
    }

    /// CLIPS's `IntersectConstraints`.
    fn intersect(x: Rec, y: Rec) -> Rec {
        if x.multi != y.multi && x.single != y.single {
            return Rec {
                any: false,
                types: 0,
                single: true,
                multi: false,
            };
        }
        let expand = |r: Rec| if r.any { ALL_TYPES } else { r.types };
        let any = x.any && y.any;
        Rec {
            any,
            types: if any { 0 } else { expand(x) & expand(y) },
            single: x.single && y.single,
            multi: x.multi && y.multi,
        }
    }

    /// CLIPS's `UnmatchableConstraint`.
    fn unmatchable(self) -> bool {
        !self.any && self.types == 0 && !self.multi
    }
}

/// CLIPS's `GetNthRestriction`: the letter of argument `n` (1-based) in restriction
/// string `r` (`u`, anything, without one).
fn nth_restriction(r: Option<&str>, n: usize) -> u8 {
    let Some(r) = r.map(str::as_bytes) else {
        return b'u';
    };
    if r.len() < 3 {
        return b'u';
    }
    let c = r.get(n + 2).copied().unwrap_or(r[2]);
    if c == b'*' {
        b'u'
    } else {
        c
    }
}

/// What the check needs to know of the world around the rule.
pub trait Names {
    /// The record of LHS variable `name` (None when the LHS does not bind it).
    fn lhs(&self, name: &str) -> Option<Rec>;
    /// Whether `name` is a deftemplate (its facts have slots).
    fn is_template(&self, name: &str) -> bool;
    /// Sequence-operator recognition: `$?x` in a call is `(expand$ ?x)`.
    fn seq_ops(&self) -> bool;
}

/// A violation: the variable token (as offsets in the text), the argument's number,
/// the call's text and how many parses of CLIPS's enclosed it (see `write_expression`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Found {
    pub var_start: usize,
    pub var_end: usize,
    pub arg: u16,
    pub call_start: usize,
    pub call_end: usize,
    pub passes: u8,
}

impl Found {
    /// The violation with its offsets moved `by` bytes on: from a text's offsets to
    /// those of the source the text was cut from at `by`.
    fn moved_by(self, by: usize) -> Found {
        Found {
            var_start: self.var_start + by,
            var_end: self.var_end + by,
            call_start: self.call_start + by,
            call_end: self.call_end + by,
            ..self
        }
    }
}

/// A test CE or `:`/`=` constraint to check once the LHS is read (`[RULECSTR2]`): its
/// text, its CE, the template slot's name or the field of an ordered pattern.
#[derive(Clone, Copy, Debug)]
pub struct LhsCheck {
    pub start: u32,
    pub end: u32,
    pub slot: crate::value::Ix,
    pub ce: u8,
    pub field: u8,
    /// The variables it sees (see `Parser::lhs_limit`).
    pub nvars: u16,
    pub serial: u32,
    /// The noted candidates (`Parser::cands`) up to its end.
    pub cands_end: u8,
}

impl LhsCheck {
    pub const EMPTY: LhsCheck = LhsCheck {
        start: 0,
        end: 0,
        slot: crate::value::NONE,
        ce: 0,
        field: 0,
        nvars: 0,
        serial: 0,
        cands_end: 0,
    };
}

/// Test CEs and `:`/`=` constraints one rule may hold (host only): a rule with more is
/// refused with an error, never accepted unchecked.
pub const MAX_LHS_CHECKS: usize = 256;

/// A name noted as offsets in the source text being read.
#[derive(Clone, Copy, Debug)]
pub struct Span {
    start: u32,
    len: u32,
}

impl Span {
    const EMPTY: Span = Span { start: 0, len: 0 };

    /// `s`, a slice of `src`, as offsets (None when it is not one).
    fn of(src: &str, s: &str) -> Option<Span> {
        let start = (s.as_ptr() as usize).checked_sub(src.as_ptr() as usize)?;
        if start.checked_add(s.len())? > src.len() {
            return None;
        }
        Some(Span {
            start: u32::try_from(start).ok()?,
            len: u32::try_from(s.len()).ok()?,
        })
    }

    fn text(self, src: &str) -> &str {
        src.get(self.start as usize..(self.start as usize).saturating_add(self.len as usize))
            .unwrap_or("")
    }
}

/// A variable passed straight to a builtin argument of restriction letter `letter`
/// (never `u`), noted while the parser reads it.
#[derive(Clone, Copy, Debug)]
struct Cand {
    name: Span,
    letter: u8,
    /// The types (`template::types` bits) the variable had as the LHS check it is in
    /// was read (`RuleNotes::keep_types`): CLIPS's `[RULECSTR2]` reads the bindings
    /// before the check, not the slots after.
    then: u8,
}

pub const MAX_CANDS: usize = 24;

/// The first value of a `bind` in the actions, noted while the parser reads it: none,
/// a literal's or variable's record, or a call (its name, looked up when needed).
#[derive(Clone, Copy, Debug)]
pub enum BindValue {
    None,
    Rec(Rec),
    Call(Span),
}

#[derive(Clone, Copy, Debug)]
struct BindNote {
    name: Span,
    value: BindValue,
}

pub const MAX_BIND_NOTES: usize = 16;

/// What the checks need of the rule being read, noted while the parser reads it (kept
/// in the engine's state, host only, so that a parser starts without filling it): the
/// test CEs and `:`/`=` constraints to check, the variables passed straight to
/// restricting builtin arguments, the actions' `bind`s, and what the LHS variables'
/// literals leave them and when they were added (by `vars` index).
pub struct RuleNotes {
    pub lhs_checks: [LhsCheck; MAX_LHS_CHECKS],
    pub nlhs_checks: usize,
    cands: [Cand; MAX_CANDS],
    pub ncands: usize,
    binds: [BindNote; MAX_BIND_NOTES],
    nbinds: usize,
    /// A note did not fit (the text is walked then).
    overflow: bool,
    /// The text the offsets are in (its address and length).
    src: (usize, usize),
    /// The types (`template::types` bits) the literal and `=(...)` constraints of each
    /// LHS variable's fields leave it.
    pub var_lit: super::VarTable<u8>,
    /// When each LHS variable was added (a count of `add_var`s).
    pub var_serial: super::VarTable<u32>,
    /// The types (`template::types` bits) the builtins' arguments each LHS variable is
    /// passed to in test CEs and `:`/`=` constraints (outside `not`, `exists`,
    /// `forall`) leave it: CLIPS's `[RULECSTR1]` of a later slot reads them.
    pub var_test: super::VarTable<u8>,
    /// The candidates noted before the last LHS check (those after it are its own).
    pub checked_cands: usize,
    /// The literal each LHS variable's fields gave it (`?x&abc`), if any.
    pub var_val: super::VarTable<Option<crate::value::Value>>,
}

impl Default for RuleNotes {
    fn default() -> RuleNotes {
        RuleNotes::new()
    }
}

impl RuleNotes {
    pub const fn new() -> RuleNotes {
        RuleNotes {
            lhs_checks: [LhsCheck::EMPTY; MAX_LHS_CHECKS],
            nlhs_checks: 0,
            cands: [Cand {
                name: Span::EMPTY,
                letter: 0,
                then: 0xFF,
            }; MAX_CANDS],
            ncands: 0,
            binds: [BindNote {
                name: Span::EMPTY,
                value: BindValue::None,
            }; MAX_BIND_NOTES],
            nbinds: 0,
            overflow: false,
            src: (0, 0),
            #[cfg(not(feature = "grow"))]
            var_lit: [0xFF; super::MAX_VARS],
            #[cfg(feature = "grow")]
            var_lit: super::VarTable::new(0xFF),
            #[cfg(not(feature = "grow"))]
            var_serial: [0; super::MAX_VARS],
            #[cfg(feature = "grow")]
            var_serial: super::VarTable::new(0),
            #[cfg(not(feature = "grow"))]
            var_test: [0xFF; super::MAX_VARS],
            #[cfg(feature = "grow")]
            var_test: super::VarTable::new(0xFF),
            checked_cands: 0,
            #[cfg(not(feature = "grow"))]
            var_val: [None; super::MAX_VARS],
            #[cfg(feature = "grow")]
            var_val: super::VarTable::new(None),
        }
    }

    /// Starts the notes of a rule (disjunct) read from `src`.
    pub fn reset(&mut self, src: &str) {
        self.nlhs_checks = 0;
        self.ncands = 0;
        self.nbinds = 0;
        self.overflow = false;
        self.checked_cands = 0;
        self.src = (src.as_ptr() as usize, src.len());
    }

    /// The name (of `src`) of candidate `k`.
    pub fn cand_name<'a>(&self, src: &'a str, k: usize) -> Option<&'a str> {
        self.cands
            .get(k..self.ncands)?
            .first()
            .map(|c| c.name.text(src))
    }

    /// The types (`template::types` bits, 0xFF for any) candidate `k`'s argument
    /// allows.
    pub fn cand_arg_types(&self, k: usize) -> u8 {
        self.cands
            .get(k)
            .map_or(0xFF, |c| Rec::of_argument(c.letter).template_types())
    }

    /// Keeps in candidate `k` the types (`template::types` bits) its variable has as the
    /// LHS check it is in is noted (that check reads them).
    pub fn keep_types(&mut self, k: usize, types: u8) {
        if let Some(c) = self.cands.get_mut(k) {
            c.then = types;
        }
    }

    /// The types kept (`keep_types`) for variable `name` by the candidates `cands` (of
    /// `src`), None when none is of it.
    pub fn kept_types(&self, src: &str, cands: (usize, usize), name: &str) -> Option<u8> {
        let cands = self.cands.get(cands.0..cands.1.min(self.ncands))?;
        cands
            .iter()
            .find(|c| c.name.text(src) == name)
            .map(|c| c.then)
    }

    /// Whether a note did not fit.
    pub fn overflow(&self) -> bool {
        self.overflow
    }

    /// Forgets the `bind`s noted so far (the actions start).
    pub fn clear_binds(&mut self) {
        self.nbinds = 0;
    }

    /// Notes variable `name` (of `src`) passed to an argument of restriction `letter`.
    pub fn note_cand(&mut self, src: &str, name: &str, letter: u8) {
        match (self.cands.get_mut(self.ncands), Span::of(src, name)) {
            (Some(c), Some(name)) => {
                *c = Cand {
                    name,
                    letter,
                    then: 0xFF,
                };
                self.ncands += 1;
            }
            _ => self.overflow = true,
        }
    }

    /// Notes a `bind` of `name` (of `src`) whose first value is `value`.
    pub fn note_bind(&mut self, src: &str, name: &str, value: Option<BindValue>) {
        match (self.binds.get_mut(self.nbinds), Span::of(src, name), value) {
            (Some(b), Some(name), Some(value)) => {
                *b = BindNote { name, value };
                self.nbinds += 1;
            }
            _ => self.overflow = true,
        }
    }

    /// Whether one of the candidates `cands` (of `src`) violates its argument's
    /// restriction: the actions' (with their `bind`s) or, without `binds`, a
    /// condition's (multifield variables are not checked there). When not, the text
    /// walk would find nothing.
    pub fn may_fail<N: Names>(
        &self,
        src: &str,
        cands: core::ops::Range<usize>,
        with_binds: bool,
        names: &N,
    ) -> bool {
        if self.overflow || self.src != (src.as_ptr() as usize, src.len()) {
            return true;
        }
        if cands.is_empty() {
            return false;
        }
        let Some(cands) = self.cands.get(cands) else {
            return true;
        };
        let binds = self.binds.get(..self.nbinds).unwrap_or(&[]);
        cands.iter().any(|c| {
            let name = c.name.text(src);
            let lhs = names.lhs(name);
            let bound = match with_binds {
                false if lhs == Some(Rec::MULTIFIELD_VAR) => return false,
                false => None,
                true => binds
                    .iter()
                    .filter(|b| b.name.text(src) == name)
                    .fold(None, |acc, b| match b.value {
                        BindValue::None => acc,
                        BindValue::Rec(r) => Some(Rec::union(Some(r), acc)),
                        BindValue::Call(f) => {
                            let r = crate::builtins::lookup(f.text(src))
                                .map_or(Rec::ANYTHING, |(_, b)| Rec::of_call(b.returns));
                            Some(Rec::union(Some(r), acc))
                        }
                    }),
            };
            Rec::intersect(Rec::union(bound, lhs), Rec::of_argument(c.letter)).unmatchable()
        })
    }
}

/// The record of the first value of a `bind` (its token `first`; for a call, `head`
/// reads the token after the `(`): what the text walk's `collect_binds` gives, a call
/// whose arguments expand aside (None: not a slice of `src`).
pub fn bind_value<'s>(
    src: &str,
    first: Tok<'s>,
    head: impl FnOnce() -> Tok<'s>,
) -> Option<BindValue> {
    Some(match first {
        Tok::RParen => BindValue::None,
        Tok::LParen => match head() {
            Tok::Symbol(name) => BindValue::Call(Span::of(src, name)?),
            _ => BindValue::Rec(Rec::ANYTHING),
        },
        Tok::SfVar(_) | Tok::MfVar(_) | Tok::Global(_) => BindValue::Rec(Rec::ANYTHING),
        t => BindValue::Rec(Rec::of_literal(t)),
    })
}

/// The restriction letter of argument `n` (1-based) of the builtin of id `func` for a
/// variable passed there (`mf`: written `$?x`), `u` when it is not checked.
pub fn letter_of(func: crate::value::Ix, n: usize, mf: bool, seq_ops: bool) -> u8 {
    if mf && seq_ops {
        return b'm';
    }
    nth_restriction(crate::builtins::environment::restriction_of_id(func), n)
}

const MAX_BINDS: usize = 64;
const MAX_SHADOW: usize = 32;

struct Walk<'a, 'n, N: Names> {
    lx: Lexer<'a>,
    peeked: Option<Token<'a>>,
    names: &'n N,
    /// Variables bound by `bind` in the actions: CLIPS's `BindInfo` list.
    binds: [(&'a str, Option<Rec>); MAX_BINDS],
    nbinds: usize,
    /// Loop and query variables in scope (not checked).
    shadow: [&'a str; MAX_SHADOW],
    nshadow: usize,
    /// Checking a condition (`[RULECSTR2]`): multifield variables are not checked.
    lhs: bool,
}

/// `Err(Some)`: a violation; `Err(None)`: the text ended or could not be followed
/// (the parser read it already, so nothing is reported).
type Step<T> = Result<T, Option<Found>>;

const QUERIES: &[&str] = &[
    "any-factp",
    "find-fact",
    "find-all-facts",
    "do-for-fact",
    "do-for-all-facts",
    "delayed-do-for-all-facts",
];

impl<'a, 'n, N: Names> Walk<'a, 'n, N> {
    /// A walk of `text` from its start, no `bind` or loop variable seen yet; `lhs`:
    /// checking a condition (`[RULECSTR2]`), else actions (`[RULECSTR3]`).
    fn new(text: &'a str, names: &'n N, lhs: bool) -> Self {
        Walk {
            lx: Lexer::new(text),
            peeked: None,
            names,
            binds: [("", None); MAX_BINDS],
            nbinds: 0,
            shadow: [""; MAX_SHADOW],
            nshadow: 0,
            lhs,
        }
    }

    fn peek(&mut self) -> Token<'a> {
        *self.peeked.get_or_insert_with(|| self.lx.next_token())
    }

    fn next(&mut self) -> Step<Token<'a>> {
        let t = match self.peeked.take() {
            Some(t) => t,
            None => self.lx.next_token(),
        };
        match t.tok {
            Tok::Eof | Tok::Bad => Err(None),
            _ => Ok(t),
        }
    }

    /// Skips the rest of a parenthesised group whose `(` was read.
    fn skip_group(&mut self) -> Step<()> {
        let mut depth = 1u32;
        while depth > 0 {
            match self.next()?.tok {
                Tok::LParen => depth += 1,
                Tok::RParen => depth -= 1,
                _ => {}
            }
        }
        Ok(())
    }

    // ---- pass 1: the binds ----

    fn collect_binds(&mut self) -> Step<()> {
        let mut prev_paren = false;
        loop {
            let t = self.next()?;
            let after_paren = prev_paren;
            prev_paren = t.tok == Tok::LParen;
            if !(after_paren && t.tok == Tok::Symbol("bind")) {
                continue;
            }
            let (Tok::SfVar(name) | Tok::MfVar(name)) = self.next()?.tok else {
                continue;
            };
            let v = self.peek();
            let rec = match v.tok {
                Tok::RParen => None,
                Tok::LParen => {
                    self.next()?;
                    let head = self.peek();
                    Some(self.call_record(head))
                }
                Tok::SfVar(_) | Tok::MfVar(_) | Tok::Global(_) => Some(Rec::ANYTHING),
                t => Some(Rec::of_literal(t)),
            };
            prev_paren = v.tok == Tok::LParen;
            self.add_bind(name, rec);
        }
    }

    /// What a call (its `(` read, `head` its name) gives as a `bind`'s value: a
    /// builtin's return type; anything for a deffunction or a call whose arguments
    /// expand (CLIPS's `(expansion-call)`).
    fn call_record(&self, head: Token<'a>) -> Rec {
        let Tok::Symbol(name) = head.tok else {
            return Rec::ANYTHING;
        };
        let Some((_, b)) = crate::builtins::lookup(name) else {
            return Rec::ANYTHING;
        };
        // its arguments (after the name, peeked already): does one expand?
        let mut lx = self.lx.clone();
        let mut depth = 0u32;
        loop {
            let t = lx.next_token();
            match t.tok {
                Tok::LParen => depth += 1,
                Tok::RParen if depth == 0 => break,
                Tok::RParen => depth -= 1,
                Tok::Eof | Tok::Bad => break,
                Tok::MfVar(n) if depth == 0 && (is_global(n) || self.names.seq_ops()) => {
                    return Rec::ANYTHING;
                }
                _ => {}
            }
        }
        Rec::of_call(b.returns)
    }

    /// CLIPS's `AddBindName`: a new name keeps its record, a known one unites it with
    /// the new record (a `bind` of no value adds nothing).
    fn add_bind(&mut self, name: &'a str, rec: Option<Rec>) {
        if let Some(b) = self.binds[..self.nbinds].iter_mut().find(|b| b.0 == name) {
            if rec.is_some() {
                b.1 = Some(Rec::union(rec, b.1));
            }
            return;
        }
        if self.nbinds < MAX_BINDS {
            self.binds[self.nbinds] = (name, rec);
            self.nbinds += 1;
        }
    }

    // ---- pass 2: the calls ----

    /// Actions up to and with the `)` that ends them.
    fn actions(&mut self, passes: u8) -> Step<()> {
        loop {
            let t = self.next()?;
            match t.tok {
                Tok::RParen => return Ok(()),
                Tok::LParen => self.form(t, passes)?,
                _ => {}
            }
        }
    }

    /// Actions up to a `)` or one of the symbols `stop` (left unread).
    fn block(&mut self, passes: u8, stop: &[&str]) -> Step<()> {
        loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => return Ok(()),
                Tok::Symbol(s) if stop.contains(&s) => return Ok(()),
                _ => {
                    let t = self.next()?;
                    if t.tok == Tok::LParen {
                        self.form(t, passes)?;
                    }
                }
            }
        }
    }

    /// One argument that is no checked variable: a nested form is walked.
    fn arg(&mut self, passes: u8) -> Step<()> {
        let t = self.next()?;
        if t.tok == Tok::LParen {
            self.form(t, passes)?;
        }
        Ok(())
    }

    fn shadowed(&self, name: &str) -> bool {
        name.contains(':') || self.shadow[..self.nshadow].contains(&name)
    }

    fn push_shadow(&mut self, name: &'a str) {
        if self.nshadow < MAX_SHADOW {
            self.shadow[self.nshadow] = name;
            self.nshadow += 1;
        }
    }

    /// The body of `if`, `while` and the loops: an optional `then`/`do` keyword, then
    /// actions up to one of `stop`.
    fn keyword_block(&mut self, keyword: &str, inner: u8, stop: &[&str]) -> Step<()> {
        if self.peek().tok == Tok::Symbol(keyword) {
            self.next()?;
        }
        self.block(inner.saturating_add(1), stop)
    }

    /// A parenthesised form (its `(` is `open`); `passes`: the parses of CLIPS that
    /// enclose it.
    fn form(&mut self, open: Token<'a>, passes: u8) -> Step<()> {
        let head = self.next()?;
        let Tok::Symbol(name) = head.tok else {
            return self.skip_group();
        };
        let inner = passes.saturating_add(1);
        let saved = self.nshadow;
        let r = match name {
            "bind" => {
                self.next()?;
                self.rest_args(inner)
            }
            "if" => {
                self.arg(inner)?;
                self.keyword_block("then", inner, &["else"])?;
                if self.peek().tok == Tok::Symbol("else") {
                    self.next()?;
                    self.block(inner.saturating_add(1), &[])?;
                }
                self.actions(inner)
            }
            "while" => {
                self.arg(inner)?;
                self.keyword_block("do", inner, &[])?;
                self.actions(inner)
            }
            "loop-for-count" | "progn$" | "foreach" => {
                self.loop_head(name, inner)?;
                self.keyword_block("do", inner, &[])?;
                self.actions(inner)
            }
            "switch" => {
                self.arg(inner)?;
                loop {
                    let t = self.next()?;
                    match t.tok {
                        Tok::RParen => break Ok(()),
                        Tok::LParen => {
                            // `(case VALUE then ACTIONS)` or `(default ACTIONS)`
                            if self.next()?.tok == Tok::Symbol("case") {
                                self.arg(inner)?;
                                if self.peek().tok == Tok::Symbol("then") {
                                    self.next()?;
                                }
                            }
                            self.actions(inner.saturating_add(1))?;
                        }
                        _ => {}
                    }
                }
            }
            "assert" => loop {
                let t = self.next()?;
                match t.tok {
                    Tok::RParen => break Ok(()),
                    Tok::LParen => self.fact(inner)?,
                    _ => {}
                }
            },
            "modify" | "duplicate" => {
                self.arg(inner)?;
                self.slots(inner)
            }
            "progn" => self.actions(inner.saturating_add(1)),
            _ if QUERIES.contains(&name) => {
                // `((?f t) (?g u ...) ...)`: the query variables
                if self.next()?.tok == Tok::LParen {
                    loop {
                        let t = self.next()?;
                        match t.tok {
                            Tok::RParen => break,
                            Tok::LParen => {
                                if let Tok::SfVar(v) = self.peek().tok {
                                    self.push_shadow(v);
                                }
                                self.skip_group()?;
                            }
                            _ => {}
                        }
                    }
                }
                self.block(inner, &[])?;
                self.actions(inner)
            }
            _ => match crate::builtins::lookup(name) {
                Some((_, b)) => self.call(open, b.name, inner, passes),
                // a deffunction's arguments are not checked, calls among them are
                None => self.rest_args(inner),
            },
        };
        self.nshadow = saved;
        r
    }

    /// The loop variable part of `loop-for-count`, `progn$` or `foreach`.
    fn loop_head(&mut self, name: &str, passes: u8) -> Step<()> {
        let t = self.peek();
        if name == "foreach" {
            if let Tok::SfVar(v) = t.tok {
                self.next()?;
                self.arg(passes)?;
                self.push_shadow(v);
                return Ok(());
            }
            return self.arg(passes);
        }
        if t.tok != Tok::LParen {
            return self.arg(passes);
        }
        let open = self.next()?;
        match self.peek().tok {
            Tok::SfVar(v) => {
                self.next()?;
                // the range or list is read before the variable is known
                self.block(passes, &[])?;
                self.next()?;
                self.push_shadow(v);
                Ok(())
            }
            _ => self.form(open, passes),
        }
    }

    /// A fact of `assert` (its `(` read): a template's slots or an ordered fact's
    /// fields.
    fn fact(&mut self, passes: u8) -> Step<()> {
        let head = self.next()?;
        match head.tok {
            Tok::Symbol(rel) if self.names.is_template(rel) => self.slots(passes),
            Tok::RParen => Ok(()),
            _ => self.rest_args(passes),
        }
    }

    /// `(slot value...)` groups up to the `)` that ends them.
    fn slots(&mut self, passes: u8) -> Step<()> {
        loop {
            let t = self.next()?;
            match t.tok {
                Tok::RParen => return Ok(()),
                Tok::LParen => {
                    self.next()?;
                    self.rest_args(passes)?;
                }
                _ => {}
            }
        }
    }

    /// Arguments up to the `)`, none of them checked.
    fn rest_args(&mut self, passes: u8) -> Step<()> {
        loop {
            let t = self.next()?;
            match t.tok {
                Tok::RParen => return Ok(()),
                Tok::LParen => self.form(t, passes)?,
                _ => {}
            }
        }
    }

    /// A builtin's arguments, each variable checked against its restriction.
    fn call(&mut self, open: Token<'a>, func: &str, inner: u8, passes: u8) -> Step<()> {
        let restrictions = crate::builtins::environment::restriction_of(func);
        let mut n = 0usize;
        loop {
            let t = self.next()?;
            let (name, letter) = match t.tok {
                Tok::RParen => return Ok(()),
                Tok::LParen => {
                    n += 1;
                    self.form(t, inner)?;
                    continue;
                }
                Tok::SfVar(v) => (v, nth_restriction(restrictions, n + 1)),
                // `$?x` is `?x` here, or with sequence-operator recognition the
                // argument of an `expand$` (`m`)
                Tok::MfVar(v) if !is_global(v) && !self.names.seq_ops() => {
                    (v, nth_restriction(restrictions, n + 1))
                }
                Tok::MfVar(v) if !is_global(v) => (v, b'm'),
                _ => {
                    n += 1;
                    continue;
                }
            };
            n += 1;
            if self.shadowed(name) || (self.lhs && self.is_multifield(name)) {
                continue;
            }
            if !self.violates(name, letter) {
                continue;
            }
            let end = self.call_end()?;
            let expand = matches!(t.tok, Tok::MfVar(_)) && self.names.seq_ops();
            return Err(Some(Found {
                var_start: t.start,
                var_end: t.end,
                arg: if expand { 1 } else { n as u16 },
                call_start: if expand { t.start } else { open.start },
                call_end: if expand { t.end } else { end },
                passes: if expand { inner } else { passes },
            }));
        }
    }

    /// Where the call being read ends (the rest of it read).
    fn call_end(&mut self) -> Step<usize> {
        let mut depth = 1u32;
        loop {
            let t = self.next()?;
            match t.tok {
                Tok::LParen => depth += 1,
                Tok::RParen => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(t.end);
                    }
                }
                _ => {}
            }
        }
    }

    fn is_multifield(&self, name: &str) -> bool {
        self.names.lhs(name) == Some(Rec::MULTIFIELD_VAR)
    }

    /// CLIPS's `CheckArgumentForConstraintError` for variable `name` as an argument
    /// of restriction letter `letter`.
    fn violates(&self, name: &str, letter: u8) -> bool {
        let lhs = self.names.lhs(name);
        let bound = self.binds[..self.nbinds]
            .iter()
            .find(|b| b.0 == name)
            .and_then(|b| b.1);
        let held = Rec::union(bound, lhs);
        Rec::intersect(held, Rec::of_argument(letter)).unmatchable()
    }
}

fn is_global(name: &str) -> bool {
    name.len() > 2 && name.starts_with('*') && name.ends_with('*')
}

/// Checks the actions in `src[from..to]` (the rule's text after `=>`, its closing `)`
/// included).
pub fn check<N: Names>(src: &str, from: usize, to: usize, names: &N) -> Option<Found> {
    let text = src.get(from..to)?;
    let mut w = Walk::new(text, names, false);
    if let Err(Some(f)) = w.collect_binds() {
        return Some(f);
    }
    w.lx = Lexer::new(text);
    w.peeked = None;
    match w.actions(1) {
        Err(Some(f)) => Some(f.moved_by(from)),
        _ => None,
    }
}

/// Calls `f` with each single-field variable (not a global) passed straight to a
/// builtin in the expression `src[from..to]`, at any depth, and the types
/// (`template::types` bits, 0xFF for any) that argument's restriction letter allows.
pub fn argument_types<'a>(src: &'a str, from: usize, to: usize, mut f: impl FnMut(&'a str, u8)) {
    const DEPTH: usize = 32;
    let Some(text) = src.get(from..to) else {
        return;
    };
    let mut lx = Lexer::new(text);
    // per open call: its restriction string and the arguments seen
    let mut calls: [(Option<&'static str>, usize); DEPTH] = [(None, 0); DEPTH];
    let mut depth = 0usize;
    let mut after_open = false;
    loop {
        let t = lx.next_token();
        match t.tok {
            Tok::Eof | Tok::Bad => return,
            Tok::LParen => {
                if depth > 0 && depth <= DEPTH {
                    calls[depth - 1].1 += 1;
                }
                depth += 1;
                if depth <= DEPTH {
                    calls[depth - 1] = (None, 0);
                }
                after_open = true;
                continue;
            }
            Tok::RParen => depth = depth.saturating_sub(1),
            Tok::Symbol(head) if after_open => {
                if depth > 0 && depth <= DEPTH {
                    calls[depth - 1].0 = crate::builtins::environment::restriction_of(head);
                }
            }
            _ if depth == 0 || depth > DEPTH => {}
            Tok::SfVar(v) if !is_global(v) => {
                let c = &mut calls[depth - 1];
                c.1 += 1;
                if c.0.is_some() {
                    f(
                        v,
                        Rec::of_argument(nth_restriction(c.0, c.1)).template_types(),
                    );
                }
            }
            _ => calls[depth - 1].1 += 1,
        }
        after_open = false;
    }
}

/// Checks the condition expression in `src[from..to]` (a test CE's or a `:`/`=`
/// constraint's call) with the LHS records alone.
pub fn check_lhs<N: Names>(src: &str, from: usize, to: usize, names: &N) -> Option<Found> {
    let text = src.get(from..to)?;
    let mut w = Walk::new(text, names, true);
    let open = w.next().ok()?;
    if open.tok != Tok::LParen {
        return None;
    }
    match w.form(open, 0) {
        Err(Some(f)) => Some(f.moved_by(from)),
        _ => None,
    }
}

/// Writes the call of `f` as CLIPS's `PrintExpression` does in the message: tokens
/// one space apart, `$?x` as `?x` (or `(expand$ ?x)` with sequence-operator
/// recognition), a global `?*g*` as `?g`, `$?*g*` as `(expand$ ?g)`, and a call with
/// an expanding argument inside `((expansion-call) ...)` once for each parse of CLIPS
/// around it (its own, each enclosing call's and action block's); a deffunction call
/// as nothing, and a variable of an enclosing loop as the call CLIPS put in its place
/// ([`LoopScope`]).
pub fn write_expression(w: &mut dyn Write, src: &str, f: &Found, seq_ops: bool) -> fmt::Result {
    let Some(text) = src.get(f.call_start..f.call_end) else {
        return Ok(());
    };
    let lx = Lexer::new(text);
    let mut p = Printer {
        lx,
        src: text,
        seq_ops,
        loops: LoopScope::at(src, f.call_start),
    };
    let t = p.lx.next_token();
    p.item(w, t, f.passes, true)
}

/// How many enclosing loops one message's call can name (more are not looked up).
const MAX_LOOPS: usize = 16;

/// The `loop-for-count`, `progn$` and `foreach` groups open at the message's call, outer
/// first: CLIPS has replaced each of their variables by a call, printed as
/// `((get-loop-count) D)`, `((get-progn$-field) D)` or `((get-progn$-index) D)`, D
/// counting the loops of the same kind between the variable's one and the call.
struct LoopScope<'a> {
    /// (progn$-like, the variable's name or "") per enclosing loop
    open: [(bool, &'a str); MAX_LOOPS],
    len: usize,
}

impl<'a> LoopScope<'a> {
    /// The loops open at `at` in the rule (or deffunction) whose text ends there.
    fn at(src: &'a str, at: usize) -> Self {
        let mut sc = LoopScope {
            open: [(false, ""); MAX_LOOPS],
            len: 0,
        };
        let upto = src.get(..at).unwrap_or("");
        let Some(start) = upto.rfind("(defrule") else {
            return sc;
        };
        let text = &upto[start..];
        let mut lx = Lexer::new(text);
        // per open group: whether it is a loop (an entry of `open`)
        let mut groups = [false; 64];
        let mut depth = 0usize;
        loop {
            let t = lx.next_token();
            match t.tok {
                Tok::Eof | Tok::Bad => break,
                Tok::RParen if depth > 0 => {
                    depth -= 1;
                    if depth < groups.len() && groups[depth] {
                        sc.len = sc.len.saturating_sub(1);
                    }
                }
                Tok::LParen => {
                    let mut ahead = lx.clone();
                    let head = ahead.next_token().tok;
                    let kind = match head {
                        Tok::Symbol("loop-for-count") => Some(false),
                        Tok::Symbol("progn$") | Tok::Symbol("foreach") => Some(true),
                        _ => None,
                    };
                    let is_loop = kind.is_some() && sc.len < MAX_LOOPS;
                    if let (true, Some(k)) = (is_loop, kind) {
                        let name = match (head, ahead.next_token().tok) {
                            (Tok::Symbol("foreach"), Tok::SfVar(v)) => v,
                            (_, Tok::LParen) => match ahead.next_token().tok {
                                Tok::SfVar(v) => v,
                                _ => "",
                            },
                            _ => "",
                        };
                        sc.open[sc.len] = (k, name);
                        sc.len += 1;
                    }
                    if depth < groups.len() {
                        groups[depth] = is_loop;
                    }
                    depth += 1;
                }
                _ => {}
            }
        }
        sc
    }

    /// CLIPS's call in place of variable `v` when a loop binds it.
    fn write_var(&self, w: &mut dyn Write, v: &str) -> Option<fmt::Result> {
        for i in (0..self.len).rev() {
            let (progn, name) = self.open[i];
            if name.is_empty() {
                continue;
            }
            let what = if v == name {
                if progn {
                    "get-progn$-field"
                } else {
                    "get-loop-count"
                }
            } else if progn && v.strip_suffix("-index") == Some(name) {
                "get-progn$-index"
            } else {
                continue;
            };
            let d = self.open[i + 1..self.len]
                .iter()
                .filter(|o| o.0 == progn)
                .count();
            return Some(write!(w, "(({what}) {d})"));
        }
        None
    }
}

struct Printer<'a> {
    lx: Lexer<'a>,
    src: &'a str,
    seq_ops: bool,
    loops: LoopScope<'a>,
}

impl<'a> Printer<'a> {
    fn item(&mut self, w: &mut dyn Write, t: Token<'a>, passes: u8, top: bool) -> fmt::Result {
        match t.tok {
            Tok::LParen => self.group(w, passes, top),
            Tok::Int(i) | Tok::IntOverflow(i) => write!(w, "{i}"),
            Tok::Float(x) => crate::value::write_float(w, x),
            Tok::SfVar(v) => match self.loops.write_var(w, v) {
                Some(r) => r,
                None => write!(w, "?{v}"),
            },
            Tok::Global(g) => write!(w, "?{g}"),
            Tok::MfVar(v) if is_global(v) => write!(w, "(expand$ ?{})", &v[1..v.len() - 1]),
            Tok::MfVar(v) if self.seq_ops => write!(w, "(expand$ ?{v})"),
            Tok::MfVar(v) => write!(w, "?{v}"),
            _ => w.write_str(self.src.get(t.start..t.end).unwrap_or("")),
        }
    }

    /// A parenthesised group (its `(` read): a call whose arguments expand is wrapped
    /// (the top call, the one of the message, is not).
    fn group(&mut self, w: &mut dyn Write, passes: u8, top: bool) -> fmt::Result {
        // a deffunction call prints as nothing (CLIPS's `PrintExpression` writes no
        // text for one)
        if let Tok::Symbol(name) = self.lx.clone().next_token().tok {
            if !top && crate::builtins::lookup(name).is_none() {
                let mut depth = 0u32;
                loop {
                    match self.lx.next_token().tok {
                        Tok::LParen => depth += 1,
                        Tok::RParen if depth == 0 => return Ok(()),
                        Tok::RParen => depth -= 1,
                        Tok::Eof | Tok::Bad => return Ok(()),
                        _ => {}
                    }
                }
            }
        }
        // read the group's tokens ahead to see whether one of its arguments expands
        let mut ahead = self.lx.clone();
        let mut depth = 0u32;
        let mut expands = false;
        loop {
            let t = ahead.next_token();
            match t.tok {
                Tok::LParen => depth += 1,
                Tok::RParen if depth == 0 => break,
                Tok::RParen => depth -= 1,
                Tok::Eof | Tok::Bad => break,
                Tok::MfVar(v) if depth == 0 && (is_global(v) || self.seq_ops) => expands = true,
                _ => {}
            }
        }
        let wraps = if expands && !top {
            passes.saturating_add(1)
        } else {
            0
        };
        for _ in 0..wraps {
            w.write_str("((expansion-call) ")?;
        }
        w.write_char('(')?;
        let mut first = true;
        loop {
            let t = self.lx.next_token();
            match t.tok {
                Tok::RParen | Tok::Eof | Tok::Bad => break,
                _ => {
                    if !first {
                        w.write_char(' ')?;
                    }
                    first = false;
                    self.item(w, t, passes.saturating_add(1), false)?;
                }
            }
        }
        w.write_char(')')?;
        for _ in 0..wraps {
            w.write_char(')')?;
        }
        Ok(())
    }
}
