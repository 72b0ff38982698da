//! Built-in functions: the registry and the calling convention.
//!
//! A builtin is one row of a table (`Builtin`): its name, arity, argument types, purity,
//! the value it returns after a run-time error and its plain `fn` (see [`describe`]:
//! `Builtin::eager("sqrt", 1, 1, sqrt).args(&[N], Any).on_error(OnError::FloatZero)
//! .quiet()`). Eager builtins receive their arguments already evaluated, on the
//! evaluation stack, through an [`Args`] handle; lazy builtins (control forms, fact-set
//! queries) receive their call node and evaluate arguments themselves with
//! [`Core::eval`]. Each module exports its rows (`FUNCS`) as a [`Table`] (`TABLE`), with
//! the CLIPS wordings of argument types its bodies name in wrong-type errors that no
//! other module uses; [`TABLES`] lists the modules. A function is named by its `Ix`
//! index in [`BUILTINS`] (the tables one after another), stored in the call's
//! expression node.
//!
//! Adding a builtin is a change to one module: its row in the module's `FUNCS`, its
//! function, and (only if CLIPS words a wrong argument in a way no module has yet) the
//! wording in the module's `TABLE`; nothing else (`describe` says what a row can say).
//! Messages a body prints itself (`[PRNTUTIL1]`, `[ROUTER1]`) it writes where it finds
//! them and returns [`EvalError::already_reported`](crate::EvalError::already_reported).
//! A new module is one line in [`TABLES`] besides.

pub mod basic;
pub mod cmath;
pub mod commands;
pub mod compat;
pub mod control;
pub mod describe;
pub mod environment;
pub mod errors;
pub mod evaluate;
pub mod extras;
pub mod facts;
pub mod files;
pub mod format;
pub mod geometry;
#[cfg(feature = "parser")]
pub mod io;
pub mod logical;
mod matches;
pub mod math;
pub mod memory;
pub mod modules;
pub mod multifield;
pub mod ordered;
pub mod predicates;
pub mod pretty;
#[cfg(feature = "extras")]
pub mod profile;
pub mod queries;
pub mod random;
mod save_facts;
pub mod strings;
pub mod syntax;
pub mod template_slots;
#[cfg(feature = "extras")]
pub mod textpro;
#[cfg(feature = "extras")]
pub mod tools;
#[cfg(feature = "extras")]
mod trace;

use crate::engine::Core;
use crate::error::{CapacityError, EvalError};
use crate::value::Ix;
use crate::value::{MfSpan, SymId, Value};

/// Fixed symbol ids interned at start-up (and after `clear`) in this order.
pub const SYM_FALSE: SymId = 0;
pub const SYM_TRUE: SymId = 1;
pub const SYM_NIL: SymId = 2;
pub const SYM_INITIAL_FACT: SymId = 3;
pub const SYM_IMPLIED: SymId = 4;
pub const SYM_CRLF: SymId = 5;
pub const SYM_T: SymId = 6;
pub const SYM_EMPTY_STR: SymId = 7;
pub const FIXED_SYMBOLS: [&str; 8] = [
    "FALSE",
    "TRUE",
    "nil",
    "initial-fact",
    "implied",
    "crlf",
    "t",
    "",
];

/// Evaluated arguments of an eager call: `len` values on the stack from `base`.
#[derive(Clone, Copy, Debug)]
pub struct Args {
    pub base: Ix,
    pub len: Ix,
}

/// What a builtin's text writer gives back (`Core::make_lexeme_with`).
type WriteResult = Result<(), EvalError>;
/// A builtin's text writer (`Core::make_lexeme_with`): the printing view, the
/// call's arguments, where to write.
type TextWriter<'w> =
    dyn Fn(&crate::print::View<'_>, &[Value], &mut dyn core::fmt::Write) -> WriteResult + 'w;

/// An eager builtin (also the type of host-registered external functions).
pub type BuiltinFn = fn(cx: &mut Core<'_>, args: Args) -> Result<Value, EvalError>;
/// A lazy builtin: gets the call node; its arguments are the node's children.
pub type LazyFn = fn(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError>;
/// The check of each argument of a builtin CLIPS evaluates one argument at a time
/// (`Core::call_in_order`): the arguments so far (the last is the new one) and how
/// many the call has.
pub type ArgCheck = fn(cx: &mut Core<'_>, args: Args, total: usize) -> Result<(), EvalError>;

/// The body of a builtin whose row is lazy only to check its arguments in order
/// (`Core::call_in_order`), for calls with values (`funcall`, `sort`, `expand$`).
pub fn in_order_body(name: &str) -> Option<BuiltinFn> {
    match name {
        "str-cat" => Some(strings::str_cat),
        "sym-cat" => Some(strings::sym_cat),
        "format" => Some(format::format),
        "min" => Some(math::min),
        "max" => Some(math::max),
        _ => None,
    }
}

#[derive(Clone, Copy)]
pub enum Imp {
    Eager(BuiltinFn),
    Lazy(LazyFn),
}

/// How the parser reads the call's arguments.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Syntax {
    /// Ordinary expressions.
    Plain,
    /// Fact-set query: first argument `((?v tmpl...)...)`; `?v:slot` allowed inside.
    Query,
}

/// Unbounded arity marker for `Builtin::max`.
pub const ANY: u8 = u8::MAX;

/// One builtin, described in one row.
#[derive(Clone, Copy)]
pub struct Builtin {
    pub name: &'static str,
    pub min: u8,
    pub max: u8,
    pub imp: Imp,
    pub syntax: Syntax,
    /// Argument types CLIPS checks literal arguments against while parsing.
    pub signature: describe::Signature,
    /// The value CLIPS returns after a run-time error.
    pub on_error: describe::OnError,
    pub purity: describe::Purity,
    /// How the body words a computed argument's wrong type.
    pub body_names: describe::BodyNames,
    /// What the call returns, as CLIPS's parser knows it (calls as arguments are
    /// checked against it).
    pub returns: describe::Returns,
}

impl Builtin {
    const fn row(name: &'static str, min: u8, max: u8, imp: Imp, syntax: Syntax) -> Builtin {
        Builtin {
            name,
            min,
            max,
            imp,
            syntax,
            signature: describe::Signature::ANY,
            on_error: describe::OnError::Nothing,
            purity: describe::Purity::Effects,
            body_names: describe::BodyNames::Same,
            returns: describe::Returns::Any,
        }
    }
    pub const fn eager(name: &'static str, min: u8, max: u8, f: BuiltinFn) -> Builtin {
        Builtin::row(name, min, max, Imp::Eager(f), Syntax::Plain)
    }
    pub const fn lazy(name: &'static str, min: u8, max: u8, f: LazyFn) -> Builtin {
        Builtin::row(name, min, max, Imp::Lazy(f), Syntax::Plain)
    }
    pub const fn query(name: &'static str, min: u8, max: u8, f: LazyFn) -> Builtin {
        Builtin::row(name, min, max, Imp::Lazy(f), Syntax::Query)
    }
}

/// One module's builtins: its rows, and the wordings of argument types its bodies pass
/// to [`EvalError::wrong_type`] that the common list (`error::ERROR_TEXTS`) does not
/// have, so that such a wording is part of the module that prints it.
#[derive(Clone, Copy)]
pub struct Table {
    pub funcs: &'static [Builtin],
    pub texts: &'static [&'static str],
}

impl Table {
    /// A module's rows, naming no wording of their own.
    pub const fn new(funcs: &'static [Builtin]) -> Table {
        Table { funcs, texts: &[] }
    }
    /// The wordings the module's bodies name in wrong-type errors, beyond the common ones.
    pub const fn texts(mut self, texts: &'static [&'static str]) -> Table {
        self.texts = texts;
        self
    }
}

/// Every builtin table, in id order (`basic` first: its comparisons are the ids
/// `basic::CMP_FIRST..=CMP_LAST`).
pub const TABLES: &[Table] = &[
    basic::TABLE,
    control::TABLE,
    facts::TABLE,
    commands::TABLE,
    math::TABLE,
    strings::TABLE,
    multifield::TABLE,
    predicates::TABLE,
    format::TABLE,
    queries::TABLE,
    random::TABLE,
    geometry::TABLE,
    memory::TABLE,
    evaluate::TABLE,
    extras::TABLE,
    compat::TABLE,
    template_slots::TABLE,
    logical::TABLE,
    modules::TABLE,
    IO_TABLE,
    environment::TABLE,
    syntax::TABLE,
    TOOLS_TABLE,
    TEXTPRO_TABLE,
    PROFILE_TABLE,
    // last: its twins share their originals' names (`builtin_id` finds the originals)
    ordered::TABLE,
];

/// `apropos` and `set-locale` (`tools`): only with the feature `extras`.
#[cfg(feature = "extras")]
const TOOLS_TABLE: Table = tools::TABLE;
#[cfg(not(feature = "extras"))]
const TOOLS_TABLE: Table = Table::new(&[]);

/// External text manipulation (`textpro`: `fetch`, `print-region`, ...): only with
/// the feature `extras`.
#[cfg(feature = "extras")]
const TEXTPRO_TABLE: Table = textpro::TABLE;
#[cfg(not(feature = "extras"))]
const TEXTPRO_TABLE: Table = Table::new(&[]);

/// The profiler (`profile`): only with the feature `extras`.
#[cfg(feature = "extras")]
const PROFILE_TABLE: Table = profile::TABLE;
#[cfg(not(feature = "extras"))]
const PROFILE_TABLE: Table = Table::new(&[]);

/// The I/O functions (`io`): only with the feature `parser`, like the other builtins
/// that lex text at run time.
#[cfg(feature = "parser")]
const IO_TABLE: Table = io::TABLE;
#[cfg(not(feature = "parser"))]
const IO_TABLE: Table = Table::new(&[]);

/// How many rows, and how many wordings of their own, the tables have in all.
const fn table_sizes() -> (usize, usize) {
    let (mut funcs, mut texts, mut t) = (0, 0, 0);
    while t < TABLES.len() {
        funcs += TABLES[t].funcs.len();
        texts += TABLES[t].texts.len();
        t += 1;
    }
    (funcs, texts)
}

const fn builtin_count() -> usize {
    table_sizes().0
}

/// How many wordings the tables add to the common error texts.
pub(crate) const fn table_text_count() -> usize {
    table_sizes().1
}

/// `common`, then every table's wordings in table order (`N` in all): the texts an
/// `EvalError` can name (`error::ERROR_TEXTS`).
pub(crate) const fn error_texts<const N: usize>(common: &[&'static str]) -> [&'static str; N] {
    let mut out = [""; N];
    let mut k = 0;
    while k < common.len() {
        out[k] = common[k];
        k += 1;
    }
    let mut t = 0;
    while t < TABLES.len() {
        let mut i = 0;
        while i < TABLES[t].texts.len() {
            out[k] = TABLES[t].texts[i];
            i += 1;
            k += 1;
        }
        t += 1;
    }
    out
}

pub(crate) const fn flatten<const N: usize>() -> [Builtin; N] {
    let mut out = [basic::FUNCS[0]; N];
    let (mut t, mut k) = (0, 0);
    while t < TABLES.len() {
        let mut i = 0;
        while i < TABLES[t].funcs.len() {
            out[k] = TABLES[t].funcs[i];
            i += 1;
            k += 1;
        }
        t += 1;
    }
    out
}

/// How many builtins there are (the ids are `0..COUNT`).
pub const COUNT: usize = builtin_count();

/// Every builtin, the tables one after another; a function's id is its index: every
/// call reads its builtin with one index, not two.
#[cfg(feature = "parser")]
pub static BUILTINS: [Builtin; COUNT] = flatten();

/// Without `parser` (the agent image) the rows describe the builtins but hold no code:
/// the code of the builtins a compiled rule base calls comes with it
/// ([`code_for`], `RuleBase::code`), so the image links only those.
#[cfg(not(feature = "parser"))]
pub static BUILTINS: [Builtin; COUNT] = {
    let mut rows = flatten::<COUNT>();
    let mut i = 0;
    while i < COUNT {
        rows[i].imp = NOT_LINKED;
        i += 1;
    }
    rows
};

/// The code of a builtin a compiled rule base does not call (see [`code_for`]).
pub const NOT_LINKED: Imp = Imp::Eager(not_linked);

fn not_linked(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Err(EvalError::new(crate::error::EvalErrorKind::NoSuchFunction))
}

/// The code of builtins `ids`, by id, the others [`NOT_LINKED`]: worked out when the
/// generated code of a compiled rule base compiles, so only these functions are
/// referenced (and linked).
pub const fn code_for(ids: &[Ix]) -> [Imp; COUNT] {
    const ALL: [Builtin; COUNT] = flatten();
    let mut out = [NOT_LINKED; COUNT];
    let mut k = 0;
    while k < ids.len() {
        let id = ids[k] as usize;
        out[id] = ALL[id].imp;
        k += 1;
    }
    out
}

/// The code of builtin `id` for an engine: its row's, or without `parser` the code the
/// loaded compiled rule base brought (`State::builtin_code`).
#[inline(always)]
pub fn code_of(cx: &Core<'_>, id: Ix, row: &Builtin) -> Imp {
    #[cfg(feature = "parser")]
    {
        let _ = (cx, id);
        row.imp
    }
    #[cfg(not(feature = "parser"))]
    {
        let _ = row;
        cx.st
            .builtin_code
            .get(id as usize)
            .copied()
            .unwrap_or(NOT_LINKED)
    }
}

/// The id of builtin `name`, worked out at compile time (a missing name does not
/// compile).
pub const fn builtin_id(name: &str) -> Ix {
    const ALL: [Builtin; builtin_count()] = flatten();
    let mut i = 0;
    while i < ALL.len() {
        if crate::symbols::same_text(ALL[i].name, name) {
            return i as Ix;
        }
        i += 1;
    }
    panic!("no such builtin")
}

/// Whether builtin `id` is total ([`describe::Purity::Total`]: `eq`, `neq`, `and`, `or`,
/// `not` and the type predicates): `rete::defer` needs this of the tests a deferred
/// propagation runs: a retract that overtakes it removes combinations those tests would
/// have seen, so a test that could fail (`<` on a symbol) would lose an error CLIPS
/// reports.
pub fn is_total(id: Ix) -> bool {
    BUILTINS
        .get(id as usize)
        .is_some_and(|b| b.purity == describe::Purity::Total)
}

/// Whether builtin `id` depends on its arguments alone and prints nothing itself, even on an
/// error ([`describe::Purity::Quiet`] or total).
pub fn is_quiet(id: Ix) -> bool {
    BUILTINS
        .get(id as usize)
        .is_some_and(|b| b.purity >= describe::Purity::Quiet)
}

/// Ids of `assert` and `modify`: as top-level actions of a firing they may leave a
/// deferred propagation waiting (`rete::defer`).
pub const ID_ASSERT: Ix = builtin_id("assert");
pub const ID_MODIFY: Ix = builtin_id("modify");
/// Id of `printout`: a top-level one of leaves may run while a propagation waits, its
/// text held until the propagation is built (`rete::defer`).
pub const ID_PRINTOUT: Ix = builtin_id("printout");
/// Id of `progn`: an `if` branch is one (see `control::branch`).
pub const ID_PROGN: Ix = builtin_id("progn");

/// Finds a builtin by name.
pub fn lookup(name: &str) -> Option<(Ix, &'static Builtin)> {
    BUILTINS
        .iter()
        .enumerate()
        .find(|(_, b)| b.name == name)
        .map(|(i, b)| (i as Ix, b))
}

pub fn get(id: Ix) -> &'static Builtin {
    &BUILTINS[id as usize]
}

/// Number argument, as CLIPS's arithmetic sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Num {
    Int(i64),
    Float(f64),
}

impl Num {
    pub fn as_f64(self) -> f64 {
        match self {
            Num::Int(i) => i as f64,
            Num::Float(f) => f,
        }
    }
    pub fn value(self) -> Value {
        match self {
            Num::Int(i) => Value::Int(i),
            Num::Float(f) => Value::Float(f),
        }
    }
}

/// Helpers for builtins: argument access and result construction.
impl Core<'_> {
    /// Argument `i` (0-based) of an eager call.
    pub fn arg(&self, a: Args, i: usize) -> Value {
        self.stack[a.base as usize + i]
    }

    pub fn arg_num(&self, a: Args, i: usize, func: &'static str) -> Result<Num, EvalError> {
        match self.arg(a, i) {
            Value::Int(x) => Ok(Num::Int(x)),
            Value::Float(x) => Ok(Num::Float(x)),
            _ => Err(EvalError::wrong_type(
                func,
                crate::error::arg_no(i),
                "integer or float",
            )),
        }
    }

    pub fn arg_int(&self, a: Args, i: usize, func: &'static str) -> Result<i64, EvalError> {
        match self.arg(a, i) {
            Value::Int(x) => Ok(x),
            Value::Float(x) => Ok(x as i64),
            _ => Err(EvalError::wrong_type(
                func,
                crate::error::arg_no(i),
                "integer",
            )),
        }
    }

    /// Symbol or string argument: its symbol-table id.
    pub fn arg_lexeme(&self, a: Args, i: usize, func: &'static str) -> Result<SymId, EvalError> {
        match self.arg(a, i) {
            Value::Sym(s) | Value::Str(s) => Ok(s),
            _ => Err(EvalError::wrong_type(
                func,
                crate::error::arg_no(i),
                "symbol or string",
            )),
        }
    }

    /// A construct, module or keyword name argument: a symbol only, as CLIPS's
    /// commands taking a name want it (a string is `[ARGACCES5]` "symbol").
    pub fn arg_symbol(&self, a: Args, i: usize, func: &'static str) -> Result<SymId, EvalError> {
        match self.arg(a, i) {
            // (an instance name `[x]` is no symbol)
            Value::Sym(s) if crate::value::instance_name_body(self.sym_text(s)).is_none() => Ok(s),
            _ => Err(EvalError::wrong_type(
                func,
                crate::error::arg_no(i),
                "symbol",
            )),
        }
    }

    /// Multifield argument: its span in scratch.
    pub fn arg_multi(&self, a: Args, i: usize, func: &'static str) -> Result<MfSpan, EvalError> {
        match self.arg(a, i) {
            Value::Multi(m) => Ok(m),
            _ => Err(EvalError::wrong_type(
                func,
                crate::error::arg_no(i),
                "multifield",
            )),
        }
    }

    /// Element `k` of a multifield value.
    pub fn mf_item(&self, m: MfSpan, k: usize) -> Value {
        self.scratch[m.start as usize + k]
    }

    pub fn bool_value(b: bool) -> Value {
        Value::Sym(if b { SYM_TRUE } else { SYM_FALSE })
    }

    pub fn is_true(v: Value) -> bool {
        v != Value::Sym(SYM_FALSE)
    }

    pub fn make_symbol(&mut self, s: &str) -> Result<Value, CapacityError> {
        Ok(Value::Sym(self.intern(s)?))
    }

    pub fn make_string(&mut self, s: &str) -> Result<Value, CapacityError> {
        Ok(Value::Str(self.intern(s)?))
    }

    /// A symbol (`string` false) or string of the text `write` writes (at most `max`
    /// bytes, else its error), built in place at the symbol arena's free end: no
    /// buffer for the longest text on the stack. `write` gets the printing view (for
    /// symbol texts and values) and the call's arguments `a`. When the arena's free
    /// end is too short, the text is built on the stack instead (`lexeme_via_stack`),
    /// so a text that exists already is still found with the arena full.
    pub(crate) fn make_lexeme_with(
        &mut self,
        string: bool,
        a: Args,
        max: usize,
        write: impl Fn(&crate::print::View<'_>, &[Value], &mut dyn core::fmt::Write) -> WriteResult,
    ) -> Result<Value, EvalError> {
        let args = &self.stack[a.base as usize..a.base as usize + a.len as usize];
        let used = self.st.pools.sym_bytes as usize;
        let (head, tail) = self.sym_bytes.split_at_mut(used.min(self.sym_bytes.len()));
        let view = crate::print::print_view!(
            self,
            crate::symbols::SymTexts {
                rom: self.st.rom.symbols,
                entries: self.sym_entries,
                bytes: head,
            }
        );
        let mut out = crate::symbols::TailWriter {
            tail,
            len: 0,
            max,
            out_of_room: false,
        };
        let written = write(&view, args, &mut out);
        let (len, out_of_room) = (out.len, out.out_of_room);
        if let Err(e) = written {
            // the arena's free end grows (doubles) until the text fits there
            #[cfg(feature = "grow")]
            if out_of_room
                && self
                    .grow(crate::error::Pool::SymbolBytes, self.sym_bytes.len() + 1)
                    .is_ok()
            {
                return self.make_lexeme_with(string, a, max, write);
            }
            return if out_of_room {
                self.lexeme_via_stack(string, a, &write)
            } else {
                Err(e)
            };
        }
        #[cfg(feature = "grow")]
        self.symbol_room(0);
        let id = self.syms().intern_tail(len)?;
        #[cfg(feature = "grow")]
        if len > strings::TEXT_MAX {
            self.st
                .eval
                .past_image
                .get_or_insert(strings::PAST_TEXT_MAX);
        }
        self.note_hw(crate::error::Pool::Symbols, self.st.pools.nsyms as usize);
        self.note_hw(
            crate::error::Pool::SymbolBytes,
            self.st.pools.sym_bytes as usize,
        );
        Ok(if string {
            Value::Str(id)
        } else {
            Value::Sym(id)
        })
    }

    /// `make_lexeme_with`'s way when the symbol arena is (nearly) full: the text built
    /// in a buffer of the longest text on the stack, then interned (found, or a
    /// capacity error). Not inlined, so the buffer is on the stack only then.
    #[inline(never)]
    fn lexeme_via_stack(
        &mut self,
        string: bool,
        a: Args,
        write: &TextWriter<'_>,
    ) -> Result<Value, EvalError> {
        let mut text = strings::Text::new();
        let args = &self.stack[a.base as usize..a.base as usize + a.len as usize];
        let view = crate::print::print_view!(self);
        write(&view, args, &mut text)?;
        let id = self.intern(text.as_str())?;
        Ok(if string {
            Value::Str(id)
        } else {
            Value::Sym(id)
        })
    }

    /// A new multifield built from `items` (copied into scratch).
    pub fn make_multi(&mut self, items: &[Value]) -> Result<Value, CapacityError> {
        let s = self.scratch_alloc(items.len())?;
        self.scratch[s as usize..s as usize + items.len()].copy_from_slice(items);
        Ok(Value::Multi(MfSpan {
            start: s,
            len: items.len() as Ix,
        }))
    }

    /// Starts building a multifield of unknown length: push elements with
    /// `multi_push`, then `multi_finish(start)`.
    pub fn multi_begin(&self) -> Ix {
        self.st.frame.scratch_top
    }

    pub fn multi_push(&mut self, v: Value) -> Result<(), CapacityError> {
        let s = self.scratch_alloc(1)?;
        self.scratch[s as usize] = v;
        Ok(())
    }

    pub fn multi_finish(&self, start: Ix) -> Value {
        Value::Multi(MfSpan {
            start,
            len: self.st.frame.scratch_top - start,
        })
    }

    /// A value as `printout` writes it: strings unquoted, multifields in parentheses.
    pub fn write_printout(&self, out: &mut dyn core::fmt::Write, v: Value) -> core::fmt::Result {
        let view = crate::print::print_view!(self);
        // a string prints bare, but inside a multifield in quotes: (a "b c")
        view.write_value(out, v, v.is_multi())
    }

    /// Writes a value's printed form (strings without quotes, as str-cat wants them)
    /// into `out`.
    pub fn write_plain(&self, out: &mut dyn core::fmt::Write, v: Value) -> core::fmt::Result {
        let view = crate::print::print_view!(self);
        view.write_flat(out, v, false)
    }
}
