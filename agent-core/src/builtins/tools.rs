//! CLIPS 6.30's `apropos`, `set-locale`, `get-function-list`, `timetag` and
//! `get-`/`set-beta-memory-resizing` (agent-core feature `extras`; the agent image has
//! none of them).
//!
//! `apropos` lists, as CLIPS does, the entries of the symbol table whose text contains
//! its argument, in the order of CLIPS's own hash table (`HashSymbol`: `h = h * 127 +
//! byte` over the text, modulo 63,559 buckets, each bucket in the order its entries were
//! added, the builtins' names first). The table is not CLIPS's: it holds the names of
//! our builtins and of the host's functions, and every symbol and string interned since
//! the last `clear` (CLIPS frees those no construct, fact or value uses any more, and has
//! COOL's names besides). So the listing matches CLIPS's where the matching names are
//! the program's constructs, slots and values or functions both engines have.

use super::describe::{ArgType, OnError, Returns};
use super::{Args, Builtin, BUILTINS, COUNT};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::{SymId, TextBuf, Value};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("apropos", 1, 1, apropos).args(&[ArgType::Symbol], ArgType::Any).returns(Returns::Void),
    Builtin::eager("set-locale", 0, 1, set_locale).on_error(OnError::False),
    Builtin::eager("get-function-list", 0, 0, get_function_list).returns(Returns::Multifield),
    Builtin::eager("timetag", 1, 1, timetag).args(&[ArgType::FactOrInstance], ArgType::Any).on_error(OnError::MinusOne).returns(Returns::Integer),
    Builtin::eager("get-beta-memory-resizing", 0, 0, get_beta_memory_resizing).returns(Returns::Symbol),
    Builtin::eager("set-beta-memory-resizing", 1, 1, set_beta_memory_resizing).returns(Returns::Symbol),
];

/// CLIPS's wording of `timetag`'s argument type.
const T_TIMETAG: &str = "instance address, instance name, fact address, integer, or symbol";

pub const TABLE: super::Table = super::Table::new(FUNCS).texts(&[T_TIMETAG]);

/// The number of buckets of CLIPS 6.30's symbol table (`SYMBOL_HASH_SIZE`).
const CLIPS_SYMBOL_BUCKETS: u64 = 63_559;

/// The bucket CLIPS 6.30 puts `text` in (`HashSymbol`; `char` is signed there).
pub fn clips_symbol_bucket(text: &str) -> u32 {
    let mut h: u64 = 0;
    for &b in text.as_bytes() {
        h = h.wrapping_mul(127).wrapping_add(b as i8 as i64 as u64);
    }
    (h % CLIPS_SYMBOL_BUCKETS) as u32
}

/// Most names one `apropos` lists.
const MOST_LISTED: usize = 2048;

/// Fixed symbols of ours that CLIPS's table does not start with (`nil`, `implied`,
/// `crlf`, `t`, the empty string).
fn own_fixed(id: SymId) -> bool {
    use super::{SYM_CRLF, SYM_EMPTY_STR, SYM_IMPLIED, SYM_NIL, SYM_T};
    matches!(id, SYM_NIL | SYM_IMPLIED | SYM_CRLF | SYM_T | SYM_EMPTY_STR)
}

/// Whether symbol `id` is the kept source text of a deffunction or defglobal (for
/// `ppdeffunction`, `ppdefglobal`): no symbol of CLIPS's.
fn kept_text(cx: &Core<'_>, id: SymId) -> bool {
    let nfuncs = (cx.st.pools.nfuncs as usize).min(cx.func_extras.len());
    let globals = &cx.global_text[..(cx.st.pools.nglobals as usize).min(cx.global_text.len())];
    cx.func_extras[..nfuncs].iter().any(|e| e.text == id) || globals.contains(&id)
}

/// The text of candidate `origin`: a builtin's name (`0..COUNT`), else symbol
/// `origin - COUNT`.
fn candidate<'c>(cx: &'c Core<'_>, origin: usize) -> &'c str {
    match BUILTINS.get(origin) {
        Some(b) => b.name,
        None => cx.sym_text((origin - COUNT) as SymId),
    }
}

/// `(apropos <symbol>)`: every name containing the argument, one a line, in CLIPS's
/// hash order (see the module's documentation).
fn apropos(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(arg) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type(
            "apropos",
            1,
            super::save_facts::T_SYMBOL,
        ));
    };
    let nsyms = cx.st.pools.nsyms as usize;
    // a symbol first read by this very command is CLIPS's ephemeral one, gone after
    // it: not listed now, nor by a later `apropos` (which CLIPS would list only if
    // something came to use it meanwhile)
    if arg as usize + 1 == nsyms {
        cx.st.tools.forget_symbol(arg);
    }
    let mut keys = [0u64; MOST_LISTED];
    let mut n = 0;
    for origin in 0..COUNT + nsyms {
        if origin >= COUNT {
            let id = (origin - COUNT) as SymId;
            if own_fixed(id) || cx.st.tools.forgotten(id) || kept_text(cx, id) {
                continue;
            }
        }
        let text = candidate(cx, origin);
        let pattern = cx.sym_text(arg);
        if text.starts_with('(') || !text.contains(pattern) {
            continue;
        }
        if n == MOST_LISTED {
            return Err(crate::engine::cap(crate::error::Pool::Scratch, MOST_LISTED).into());
        }
        keys[n] = (u64::from(clips_symbol_bucket(text)) << 32) | origin as u64;
        n += 1;
    }
    let keys = &mut keys[..n];
    keys.sort_unstable();
    cx.spill_traces();
    let (view, host) = cx.split();
    let text_of = |k: u64| match BUILTINS.get((k & 0xffff_ffff) as usize) {
        Some(b) => b.name,
        None => view.sym(((k & 0xffff_ffff) as usize - COUNT) as SymId),
    };
    for (i, &k) in keys.iter().enumerate() {
        let text = text_of(k);
        // a name both a builtin's and a symbol's is one entry (same bucket: adjacent)
        let mut same_bucket = keys[..i].iter().rev().take_while(|o| *o >> 32 == k >> 32);
        if same_bucket.any(|&o| text_of(o) == text) {
            continue;
        }
        host.write_str(router::WDISPLAY, text);
        host.write_str(router::WDISPLAY, "\n");
    }
    Ok(Value::Void)
}

/// The settings and figures of the tools, kept across `clear` as CLIPS keeps them.
#[derive(Clone, Copy)]
pub struct ToolsState {
    /// `set-locale`'s text (CLIPS starts with `C`).
    locale: [u8; MOST_LOCALE],
    locale_len: u8,
    /// Symbols `apropos` was given that no one had used before (the last few): CLIPS
    /// frees them after the command, ours stay (forgotten at `clear`).
    forgotten: [SymId; FORGOTTEN],
    nforgotten: u8,
    next_forgotten: u8,
    /// `set-beta-memory-resizing`'s setting (CLIPS starts with TRUE; it sizes CLIPS's
    /// hash tables of partial matches, which this engine does not have).
    beta_resizing: bool,
}

/// How many of `apropos`'s own arguments are remembered (`ToolsState::forgotten`).
const FORGOTTEN: usize = 16;

/// Longest locale name `set-locale` keeps.
const MOST_LOCALE: usize = 64;

impl Default for ToolsState {
    fn default() -> ToolsState {
        ToolsState::new()
    }
}

impl ToolsState {
    pub const fn new() -> ToolsState {
        let mut locale = [0; MOST_LOCALE];
        locale[0] = b'C';
        ToolsState {
            locale,
            locale_len: 1,
            forgotten: [0; FORGOTTEN],
            nforgotten: 0,
            next_forgotten: 0,
            beta_resizing: true,
        }
    }

    fn forget_symbol(&mut self, id: SymId) {
        if !self.forgotten(id) {
            self.forgotten[usize::from(self.next_forgotten)] = id;
            self.next_forgotten = (self.next_forgotten + 1) % FORGOTTEN as u8;
            self.nforgotten = (self.nforgotten + 1).min(FORGOTTEN as u8);
        }
    }

    fn forgotten(&self, id: SymId) -> bool {
        self.forgotten[..usize::from(self.nforgotten)].contains(&id)
    }

    /// After `clear`: the symbols are interned afresh.
    pub fn forget_symbols(&mut self) {
        self.nforgotten = 0;
        self.next_forgotten = 0;
    }
}

/// `(set-locale [<string>])`: the locale before, as a string. The engine formats
/// numbers as CLIPS does in the C locale whatever it is set to (the no_std core has no
/// C library locale; CLIPS's `format` and float printing follow the one set, which on
/// Debian's machines, lacking other locales, is the C one's output too).
fn set_locale(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let new = match a.len {
        0 => None,
        _ => match cx.arg(a, 0) {
            Value::Str(s) => Some(s),
            _ => return Err(EvalError::wrong_type("set-locale", 1, "string")),
        },
    };
    let t = &cx.st.tools;
    let mut old: TextBuf<MOST_LOCALE> = TextBuf::new();
    let _ =
        old.write_str(core::str::from_utf8(&t.locale[..usize::from(t.locale_len)]).unwrap_or(""));
    if let Some(s) = new {
        let text = cx.sym_text(s);
        if text.len() > MOST_LOCALE {
            return Err(EvalError::wrong_type("set-locale", 1, "string"));
        }
        let n = text.len();
        let mut buf = [0; MOST_LOCALE];
        buf[..n].copy_from_slice(text.as_bytes());
        let t = &mut cx.st.tools;
        t.locale = buf;
        t.locale_len = n as u8;
    }
    Ok(cx.make_string(old.as_str())?)
}

/// `(get-beta-memory-resizing)`: the setting, kept across `clear`.
fn get_beta_memory_resizing(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(cx.st.tools.beta_resizing))
}

/// `(set-beta-memory-resizing VALUE)`: any value but FALSE is TRUE; the setting before.
fn set_beta_memory_resizing(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = cx.st.tools.beta_resizing;
    cx.st.tools.beta_resizing = cx.arg(a, 0) != Value::Sym(super::SYM_FALSE);
    Ok(Core::bool_value(old))
}

/// Whether `set-beta-memory-resizing` is on (what a call with the wrong number of
/// arguments gives back).
pub(crate) fn beta_resizing(cx: &Core<'_>) -> bool {
    cx.st.tools.beta_resizing
}

/// `(get-function-list)`: the names of every function, no deffunction, as symbols, in
/// CLIPS 6.30's order (the newest definition first): the host's functions (the newest
/// first), our own builtins CLIPS lacks, then the functions we share with CLIPS in the
/// order CLIPS lists them (its COOL and generic functions left out).
fn get_function_list(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    for e in (0..cx.st.pools.nexternals).rev() {
        let name = cx.externals[e as usize].name;
        cx.multi_push(Value::Sym(name))?;
    }
    for b in BUILTINS.iter() {
        if !b.name.starts_with('(') && !CLIPS_FUNCTIONS.split(' ').any(|n| n == b.name) {
            let s = cx.intern(b.name)?;
            cx.multi_push(Value::Sym(s))?;
        }
    }
    for name in CLIPS_FUNCTIONS.split(' ') {
        if super::lookup(name).is_some() {
            let s = cx.intern(name)?;
            cx.multi_push(Value::Sym(s))?;
        }
    }
    Ok(cx.multi_finish(start))
}

/// CLIPS 6.30's `(get-function-list)` as Debian's build prints it (its list of
/// functions, the last defined first).
#[rustfmt::skip]
const CLIPS_FUNCTIONS: &str = "\
set-current-module get-current-module ppdefmodule list-defmodules get-defmodule-list \
object-pattern-match-delay delayed-do-for-all-instances do-for-all-instances \
do-for-instance find-all-instances find-instance any-instancep (query-instance-slot) \
(query-instance) definstances-module get-definstances-list list-definstances \
ppdefinstances undefinstances put get dynamic-put dynamic-get override-next-handler \
call-next-handler next-handlerp list-defmessage-handlers ppdefmessage-handler \
preview-send send undefmessage-handler bload-instances bsave-instances \
restore-instances load-instances save-instances slot-delete$ slot-insert$ \
slot-replace$ slot-direct-delete$ slot-direct-insert$ slot-direct-replace$ \
mv-slot-delete mv-slot-insert mv-slot-replace direct-mv-delete direct-mv-insert \
direct-mv-replace (message-duplicate) (direct-duplicate) (message-modify) \
(direct-modify) active-message-duplicate-instance message-duplicate-instance \
active-duplicate-instance duplicate-instance active-message-modify-instance \
message-modify-instance active-modify-instance modify-instance class instance-existp \
instancep instance-name instance-namep instance-addressp instance-address \
instance-name-to-symbol symbol-to-instance-name ppinstance instances unmake-instance \
(create-instance) delete-instance init-slots active-make-instance make-instance \
active-initialize-instance initialize-instance set-class-defaults-mode \
get-class-defaults-mode defclass-module slot-default-value slot-direct-accessp \
slot-publicp slot-initablep slot-writablep slot-cardinality slot-range \
slot-allowed-classes slot-allowed-values slot-types slot-sources slot-facets \
slot-existp get-defmessage-handler-list class-subclasses class-superclasses \
class-slots class-reactivep class-abstractp message-handler-existp class-existp \
subclassp superclassp get-defclass-list browse-classes describe-class ppdefclass \
list-defclasses undefclass deftemplate-slot-facet-value \
deftemplate-slot-facet-existp deftemplate-slot-defaultp deftemplate-slot-existp \
deftemplate-slot-singlep deftemplate-slot-multip deftemplate-slot-types \
deftemplate-slot-range deftemplate-slot-allowed-values deftemplate-slot-cardinality \
deftemplate-slot-default-value deftemplate-slot-names duplicate modify ppdeftemplate \
list-deftemplates deftemplate-module undeftemplate get-deftemplate-list \
delayed-do-for-all-facts do-for-all-facts do-for-fact find-all-facts find-fact \
any-factp (query-fact-slot) (query-fact) ppfact get-fact-list fact-slot-names \
fact-slot-value fact-relation fact-existp fact-index load-facts save-facts \
set-fact-duplication get-fact-duplication str-assert assert-string retract assert \
facts show-defglobals get-reset-globals set-reset-globals ppdefglobal \
list-defglobals defglobal-module undefglobal get-defglobal-list deffunction-module \
get-deffunction-list ppdeffunction list-deffunctions undeffunction type \
defgeneric-module get-method-restrictions get-defmethod-list get-defgeneric-list \
preview-generic list-defmethods ppdefmethod list-defgenerics ppdefgeneric \
(gnrc-current-arg) next-methodp override-next-method call-specific-method \
call-next-method undefmethod undefgeneric ppdeffacts list-deffacts deffacts-module \
undeffacts get-deffacts-list set-strategy get-strategy set-beta-memory-resizing \
get-beta-memory-resizing set-incremental-reset get-incremental-reset timetag \
dependents dependencies list-focus-stack join-activity-reset join-activity matches \
show-breaks remove-break set-break get-focus pop-focus get-focus-stack \
clear-focus-stack focus halt run ppdefrule list-defrules rules defrule-module \
undefrule get-defrule-list agenda set-salience-evaluation get-salience-evaluation \
refresh-agenda refresh reset clear set-static-constraint-checking \
get-static-constraint-checking set-dynamic-constraint-checking \
get-dynamic-constraint-checking check-syntax get-profile-percent-threshold \
set-profile-percent-threshold profile-reset profile-info profile constructs-to-c \
get-region print-region toss fetch round ** grad-deg deg-grad rad-deg deg-rad pi \
sqrt log10 log exp mod acoth acsch asech atanh asinh acosh coth csch sech tanh sinh \
cosh acot acsc asec atan asin acos cot csc sec tan sin cos string-to-field build \
eval str-index sub-string lowcase upcase str-compare str-length sym-cat str-cat \
(get-progn$-index) (get-progn$-field) mv-delete mv-subseq member mv-replace nth \
subset str-explode str-implode foreach progn$ subsetp member$ nth$ implode$ explode$ \
insert$ replace$ delete$ replace-member$ delete-member$ subseq$ rest$ first$ \
list-watch-items get-watch-item unwatch watch sort bload bsave load* load save \
dribble-off dribble-on batch* batch max min abs float integer \
get-auto-float-dividend set-auto-float-dividend div / - * + pointerp sequencep \
multifieldp evenp oddp floatp integerp numberp lexemep stringp wordp symbolp != <> = \
> < >= <= neq eq or and not read-number set-locale readline format rename remove \
put-char get-char close open read printout timer call new funcall get-function-list \
apropos mv-append create$ get-function-restrictions \
get-sequence-operator-recognition set-sequence-operator-recognition \
(set-evaluation-error) expand$ (expansion-call) operating-system options \
mem-requests mem-used release-mem conserve-mem seed random time length$ length \
system setgen gensym* gensym switch break return progn bind (get-loop-count) \
loop-for-count while if exit";
/// `(timetag FACT-OR-INSTANCE)`: a fact's time tag as CLIPS 6.30 numbers it (see
/// [`Timetags`]); a fact index that is no live fact, and any instance but CLIPS's
/// `initial-object`, is `[PRNTUTIL1]` and -1, a value of another type `[ARGACCES5]`
/// and -1.
fn timetag(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut b: TextBuf<160> = TextBuf::new();
    let tag = match cx.arg(a, 0) {
        Value::Fact(r) => cx.st.timetags.tag(r.num),
        Value::Int(n) => match u32::try_from(n).ok().filter(|&n| cx.find_fact(n).is_some()) {
            Some(num) => cx.st.timetags.tag(num),
            None => {
                let _ = writeln!(b, "[PRNTUTIL1] Unable to find fact f-{n}.");
                None
            }
        },
        Value::Sym(s) => {
            let text = cx.sym_text(s);
            let name = crate::value::instance_name_body(text).unwrap_or(text);
            if name == "initial-object" {
                return Ok(Value::Int(cx.st.timetags.initial_object()));
            }
            let _ = writeln!(b, "[PRNTUTIL1] Unable to find instance {name}.");
            None
        }
        // (CLIPS's message alone: no evaluation error, the caller goes on with -1)
        _ => {
            cx.write_error_message(EvalError::wrong_type("timetag", 1, T_TIMETAG));
            return Ok(Value::Int(-1));
        }
    };
    if !b.as_str().is_empty() {
        cx.write(router::WERROR, b.as_str());
        return Ok(Value::Int(-1));
    }
    match tag {
        Some(t) => Ok(Value::Int(t)),
        None => Err(crate::engine::cap(crate::error::Pool::Scratch, MOST_MARKS).into()),
    }
}

/// Most runs of rule definitions between asserts whose effect on time tags is kept.
const MOST_MARKS: usize = 32;

/// CLIPS 6.30 numbers facts (and instances) with one counter, its time tags: `clear`
/// sets it so that `initial-fact` (f-0) is 3 (the `initial-object` instance is 2),
/// `reset` so that it is 4 (`initial-object` 3), every fact asserted takes the next
/// tag (as its index does: a duplicate refused takes neither), and so does every rule
/// defined (CLIPS's incremental reset of it), even one replacing another. So a fact's
/// tag is its index, the base of the epoch, and how many rules were defined before it:
/// `marks` keeps, for each run of definitions, the first fact index after it and the
/// number of rules defined so far.
#[derive(Clone, Copy)]
pub struct Timetags {
    base: u8,
    marks: [(u32, u32); MOST_MARKS],
    nmarks: u8,
    /// A run of definitions that found `marks` full: facts from this index on have
    /// no known tag (refused as a capacity error).
    lost_from: u32,
}

impl Default for Timetags {
    fn default() -> Timetags {
        Timetags::new()
    }
}

impl Timetags {
    /// As after `clear` (and at start-up).
    pub const fn new() -> Timetags {
        Timetags {
            base: 3,
            marks: [(0, 0); MOST_MARKS],
            nmarks: 0,
            lost_from: u32::MAX,
        }
    }

    /// A `reset` starts numbering afresh.
    pub fn reset(&mut self) {
        *self = Timetags::new();
        self.base = 4;
    }

    /// `n` rules were defined while `next_fact` is the index the next fact gets.
    pub fn rules_defined(&mut self, next_fact: u32, n: u32) {
        let k = usize::from(self.nmarks);
        match k.checked_sub(1).map(|l| self.marks[l]) {
            Some((at, count)) if at == next_fact => self.marks[k - 1] = (at, count + n),
            last => {
                let before = last.map_or(0, |(_, c)| c);
                if k == MOST_MARKS {
                    self.lost_from = self.lost_from.min(next_fact);
                } else {
                    self.marks[k] = (next_fact, before + n);
                    self.nmarks += 1;
                }
            }
        }
    }

    /// The tag of the fact of index `num` (None past a run of definitions not kept).
    pub fn tag(&self, num: u32) -> Option<i64> {
        if num >= self.lost_from {
            return None;
        }
        let rules = self.marks[..usize::from(self.nmarks)]
            .iter()
            .take_while(|(at, _)| *at <= num)
            .last()
            .map_or(0, |&(_, c)| c);
        Some(i64::from(num) + i64::from(self.base) + i64::from(rules))
    }

    /// The tag of CLIPS's `initial-object` instance (made just before `initial-fact`).
    pub fn initial_object(&self) -> i64 {
        i64::from(self.base) - 1
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn clips_symbol_buckets_order_the_profile_names_as_clips_lists_them() {
        let names = [
            "set-profile-percent-threshold",
            "progn",
            "progn$",
            "profile-reset",
            "profile",
        ];
        let buckets = names.map(super::clips_symbol_bucket);
        assert_eq!(buckets, [8676, 15238, 28492, 32984, 36844]);
    }
}
