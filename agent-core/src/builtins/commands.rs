//! Commands: reset, clear, run, facts, agenda, watch/unwatch, printout, halt, exit,
//! refresh-agenda, set-strategy, list-defrules, ppdefrule, undefrule, matches, load,
//! batch, save-facts, load-facts.

use super::describe::Returns as R;
use super::describe::{ArgType, OnError};
use super::files::{file_buffer, FileItems};
use super::save_facts::{self, save_facts};
use super::{Args, Builtin, ANY, SYM_CRLF, SYM_FALSE, SYM_NIL, SYM_TRUE};
use crate::commands::FactsRead;
use crate::engine::{watch, Core};
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::value::Ix;
use crate::value::{TextBuf, Value, NONE};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("reset", 0, 0, reset).returns(super::describe::Returns::Void),
    Builtin::eager("clear", 0, 0, clear).returns(super::describe::Returns::Void),
    Builtin::eager("run", 0, 1, run).args(&[ArgType::Integer], ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("facts", 0, 4, facts).args(&[super::describe::ArgType::Any], super::describe::ArgType::Integer).returns(super::describe::Returns::Void),
    Builtin::eager("agenda", 0, 1, agenda).returns(super::describe::Returns::Void),
    Builtin::eager("watch", 1, ANY, watch_).returns(super::describe::Returns::Void),
    Builtin::eager("unwatch", 1, ANY, unwatch).returns(super::describe::Returns::Void),
    Builtin::lazy("printout", 1, ANY, printout).returns(R::Void),
    Builtin::eager("halt", 0, 0, halt).returns(super::describe::Returns::Void),
    Builtin::eager("exit", 0, 1, exit).returns(R::Void),
    Builtin::eager("refresh-agenda", 0, 1, refresh_agenda).returns(super::describe::Returns::Void),
    Builtin::eager("set-strategy", 1, 1, set_strategy)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any),
    Builtin::eager("get-strategy", 0, 0, get_strategy),
    Builtin::eager("list-defrules", 0, 1, list_defrules).returns(super::describe::Returns::Void),
    Builtin::eager("ppdefrule", 1, 1, ppdefrule).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("undefrule", 1, 1, undefrule).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("matches", 1, 2, matches).on_error(super::describe::OnError::False).args(&[], super::describe::ArgType::Symbol),
    // literal arguments are checked while parsing, as CLIPS's "1*wk"
    Builtin::eager("save-facts", 1, ANY, save_facts)
        .args(&[ArgType::SymbolOrString], ArgType::Symbol)
        .on_error(OnError::False),
    Builtin::eager("time", 0, 0, time).returns(R::Float),
    Builtin::eager("list-deftemplates", 0, 1, list_deftemplates).returns(super::describe::Returns::Void),
    Builtin::eager("list-deffunctions", 0, 1, list_deffunctions).returns(super::describe::Returns::Void),
    Builtin::eager("get-fact-duplication", 0, 0, get_fact_dup),
];
pub const TABLE: super::Table = super::Table::new(FUNCS).texts(&[
    "symbol with value verbose, succinct, or terse",
    save_facts::T_FILE_NAME,
    save_facts::T_SYMBOL,
    save_facts::T_SCOPE,
    save_facts::T_LOCAL,
    save_facts::T_VISIBLE,
]);

fn reset(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    if cx.st.net.matching > 0 {
        // a reset from a pattern or join test would wipe the network it runs in;
        // CLIPS 6.30 fails on deleting its initial object and halts, with these words
        cx.write(
            router::WERROR,
            "[INSMNGR12] Cannot delete instances of reactive classes while\n  pattern-matching is in process.\n[PRCCODE4] Execution halted during the actions of message-handler delete primary in class USER\n",
        );
        return Err(EvalError::already_reported());
    }
    cx.reset()?;
    Ok(Value::Void)
}

fn clear(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    // a firing rule, a running deffunction, a construct being parsed, a reset, a
    // fact being made or a fact-set query's walk would go on with its pools wiped
    // under it
    if cx.st.mode.firing
        || cx.st.eval.in_use > 0
        || (cx.st.eval.query_hold & !crate::engine::COMMAND_HOLD) > 0
        || cx.st.mode.defining
        || cx.st.mode.resetting
        || cx.st.mode.asserting
        || cx.st.net.matching > 0
    {
        cx.write(
            router::WERROR,
            "[CONSTRCT1] Some constructs are still in use. Clear cannot continue.\n",
        );
    } else {
        cx.clear()?;
    }
    Ok(Value::Void)
}

fn run(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let limit = if a.len > 0 {
        cx.arg_int(a, 0, "run")?
    } else {
        -1
    };
    // a run from a rule's actions does nothing in CLIPS: the run going on goes on
    if cx.st.mode.firing {
        return Ok(Value::Void);
    }
    // `(watch statistics)` lines and the limit message are printed by `Core::run`
    // (commands.rs)
    cx.run(limit)?;
    Ok(Value::Void)
}

/// `(facts [module] [start [end [max]]])`: the numbers must be integers >= 0 (after
/// the first, a float is taken truncated, as CLIPS does).
fn facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut nums = [-1i64; 3];
    let mut k = 0;
    #[cfg_attr(not(feature = "modules"), allow(unused_mut))]
    let mut all = false;
    #[cfg(feature = "modules")]
    let current = cx.current_module();
    for i in 0..a.len as usize {
        match cx.arg(a, i) {
            // a module name: the facts it sees; `*` all of them
            #[cfg(feature = "modules")]
            Value::Sym(s) if i == 0 => {
                if cx.sym_text(s) == "*" {
                    all = true;
                } else if let Some(m) = cx.find_module(cx.sym_text(s)) {
                    cx.set_current_module(m);
                } else {
                    super::commands::unable(cx, Unable::Find, "defmodule", s);
                    return Ok(Value::Void);
                }
            }
            #[cfg(not(feature = "modules"))]
            Value::Sym(_) if i == 0 => {} // a module name: there is only MAIN
            Value::Int(n) if n >= 0 && k < 3 => {
                nums[k] = n;
                k += 1;
            }
            Value::Float(f) if i > 0 && k < 3 && super::math::c_trunc_to_i64(f) >= 0 => {
                nums[k] = super::math::c_trunc_to_i64(f);
                k += 1;
            }
            _ => {
                // (a negative integer is no positive number; anything else no integer)
                let expected = if i == 0 {
                    "symbol or positive number"
                } else if matches!(cx.arg(a, i), Value::Int(_) | Value::Float(_)) {
                    "positive number"
                } else {
                    "integer"
                };
                // (the module a first argument named is left)
                #[cfg(feature = "modules")]
                cx.set_current_module(current);
                // an unbound variable read (reported): CLIPS lists nothing, silently
                if i > 0 && cx.st.mode.halting {
                    return Ok(Value::Void);
                }
                return Err(EvalError::wrong_type(
                    "facts",
                    crate::error::arg_no(i),
                    expected,
                ));
            }
        }
    }
    let start = if k > 0 { nums[0] } else { 0 };
    cx.list_facts_of(start, nums[1], nums[2], all);
    #[cfg(feature = "modules")]
    cx.set_current_module(current);
    Ok(Value::Void)
}

/// `(agenda [MODULE | *])`: the current module's agenda, the one named, or every
/// module's under its heading.
fn agenda(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = module_view(cx, a, "agenda")? else {
        return Ok(Value::Void);
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        n += cx.list_agenda_of(m, view.indent());
    }
    if n > 0 {
        cx.print_total(n, "activation");
    }
    Ok(Value::Void)
}

/// What `watch`/`unwatch` make of an item name.
pub(crate) enum WatchItem {
    /// An item we trace: its `watch::*` bit.
    Traced(u8),
    /// A COOL item (`watch::cool` bit): accepted, traced where `initial-object` is.
    #[cfg(feature = "extras")]
    Cool(u8),
    All,
    /// An item CLIPS traces and we do not (refused, see `parser::expr`; none with
    /// `extras` and `modules`).
    #[cfg_attr(all(feature = "extras", feature = "modules"), allow(dead_code))]
    Untraced,
    Unknown,
}

pub(crate) fn watch_item(name: &str) -> WatchItem {
    match name {
        "facts" => WatchItem::Traced(watch::FACTS),
        "rules" => WatchItem::Traced(watch::RULES),
        "activations" => WatchItem::Traced(watch::ACTIVATIONS),
        "compilations" => WatchItem::Traced(watch::COMPILATIONS),
        "statistics" => WatchItem::Traced(watch::STATISTICS),
        "all" => WatchItem::All,
        #[cfg(feature = "modules")]
        "focus" => WatchItem::Traced(watch::FOCUS),
        #[cfg(not(feature = "modules"))]
        "focus" => WatchItem::Untraced,
        #[cfg(feature = "extras")]
        "globals" => WatchItem::Traced(watch::GLOBALS),
        #[cfg(feature = "extras")]
        "deffunctions" => WatchItem::Traced(watch::DEFFUNCTIONS),
        #[cfg(not(feature = "extras"))]
        "globals" | "deffunctions" => WatchItem::Untraced,
        #[cfg(feature = "extras")]
        "instances" => WatchItem::Cool(watch::cool::INSTANCES),
        #[cfg(feature = "extras")]
        "slots" => WatchItem::Cool(watch::cool::SLOTS),
        #[cfg(feature = "extras")]
        "messages" => WatchItem::Cool(watch::cool::MESSAGES),
        #[cfg(feature = "extras")]
        "message-handlers" => WatchItem::Cool(watch::cool::MESSAGE_HANDLERS),
        #[cfg(feature = "extras")]
        "generic-functions" => WatchItem::Cool(watch::cool::GENERIC_FUNCTIONS),
        #[cfg(feature = "extras")]
        "methods" => WatchItem::Cool(watch::cool::METHODS),
        #[cfg(not(feature = "extras"))]
        "generic-functions" | "methods" | "instances" | "slots" | "messages"
        | "message-handlers" => WatchItem::Untraced,
        _ => WatchItem::Unknown,
    }
}

/// The trace bits of `watch`/`unwatch`'s items (COOL's, feature `extras`, in the high
/// byte); the parser refused literal items we do not trace, and one that arrives in a
/// variable is refused here.
fn watch_bits(cx: &Core<'_>, a: Args, func: &'static str) -> Result<u16, EvalError> {
    let mut bits = 0;
    if a.len > 1 {
        // construct names after the item
        return Err(EvalError::message(crate::error::Message::NotTraced));
    }
    for i in 0..a.len as usize {
        let s = cx.arg_symbol(a, i, func)?;
        bits |= match watch_item(cx.sym_text(s)) {
            WatchItem::Traced(b) => u16::from(b),
            #[cfg(feature = "extras")]
            WatchItem::Cool(b) => u16::from(b) << 8,
            WatchItem::All if func == "unwatch" || ALL_TRACED => 0xFFFF,
            WatchItem::Unknown => {
                return Err(EvalError::wrong_type(
                    func,
                    crate::error::arg_no(i),
                    "watchable symbol",
                ))
            }
            _ => return Err(EvalError::message(crate::error::Message::NotTraced)),
        };
    }
    Ok(bits)
}

/// `(watch all)` is taken when every item is (COOL's by `extras`, focus by `modules`).
pub(crate) const ALL_TRACED: bool = cfg!(all(feature = "extras", feature = "modules"));

fn watch_(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    #[cfg(feature = "extras")]
    if a.len > 1 {
        return super::trace::watch_named(cx, a, "watch", true);
    }
    let b = watch_bits(cx, a, "watch")?;
    cx.st.mode.watch |= b as u8;
    #[cfg(feature = "extras")]
    {
        cx.st.mode.cool_watch |= (b >> 8) as u8;
        whole_items(cx, b as u8, true);
    }
    Ok(Value::Void)
}

fn unwatch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    #[cfg(feature = "extras")]
    if a.len > 1 {
        return super::trace::watch_named(cx, a, "unwatch", false);
    }
    let b = watch_bits(cx, a, "unwatch")?;
    cx.st.mode.watch &= !(b as u8);
    #[cfg(feature = "extras")]
    {
        cx.st.mode.cool_watch &= !((b >> 8) as u8);
        whole_items(cx, b as u8, false);
    }
    Ok(Value::Void)
}

/// An item about constructs set as a whole sets every construct's flag too.
#[cfg(feature = "extras")]
fn whole_items(cx: &mut Core<'_>, bits: u8, on: bool) {
    let items = bits & crate::engine::WatchNames::ITEMS;
    cx.st.watch_names.forget_items(items);
    if on {
        cx.st.watch_names.items |= items;
    } else {
        cx.st.watch_names.items &= !items;
    }
    cx.sync_watch();
}

/// `(printout name args...)`, lazy as in CLIPS: nothing is evaluated for `nil` or an
/// unknown router, and each argument is printed before the next one is evaluated (a
/// function called by a later argument prints after it). While CLIPS halts
/// (`State::halting`) it stops after evaluating an argument, printing nothing more.
fn printout(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let first = cx.exprs[call as usize].first;
    let name = cx.eval(first)?;
    if name == Value::Sym(SYM_NIL) || cx.st.mode.halting {
        return Ok(Value::Void);
    }
    // a propagation waiting (`rete::defer`, this printout may wait): a name that is
    // none of the engine's routers builds it first (its report or file come after)
    #[cfg(feature = "defer")]
    if cx.st.net.deferred.fact != NONE && engine_router(cx, name).is_none() {
        cx.flush_deferred()?;
    }
    let routed = match resolve_router(cx, name, "printout") {
        Ok(Some(r)) => r,
        Ok(None) => return Ok(Value::Void),
        // an illegal name halts (`[IOFUN1]`)
        Err(e) if e.reported => return Err(e),
        // CLIPS's printout reports the name and carries on with nothing printed
        Err(_) => return Ok(Value::Void),
    };
    let mark = cx.st.frame.scratch_top;
    let mut b: TextBuf<1024> = TextBuf::new();
    let mut a = cx.exprs[first as usize].next;
    let mut r = Ok(Value::Void);
    while a != NONE {
        // what a call prints must follow what is printed before it (a read of an
        // unbound global prints `[GLOBLDEF1]`, a bound one prints nothing; the image
        // flushes before every global, its code 100 B smaller)
        let x = cx.exprs[a as usize];
        let prints = match x.op {
            crate::expr::Op::Global => {
                !cfg!(feature = "host-speedups")
                    || matches!(cx.globals[x.data as usize].value, Value::Void)
            }
            crate::expr::Op::QSlot => true,
            op => !is_leaf(op),
        };
        if prints && !b.is_empty() {
            if let Err(e) = printout_write(cx, &routed, b.as_str()) {
                r = Err(e);
                b.clear();
                break;
            }
            b.clear();
        }
        let v = match cx.eval(a) {
            Ok(v) => v,
            Err(e) => {
                r = Err(e);
                break;
            }
        };
        if cx.st.mode.halting {
            break;
        }
        // room for a crlf or tab; a value that does not fit goes out alone
        if b.len() > 900 {
            if let Err(e) = printout_write(cx, &routed, b.as_str()) {
                r = Err(e);
                b.clear();
                break;
            }
            b.clear();
        }
        match special_char(cx, v) {
            Some(c) => {
                let _ = b.write_char(c);
            }
            None => {
                let len = b.len();
                if cx.write_printout(&mut b, v).is_err() {
                    // out goes what came before it, then the value
                    b.truncate(len);
                    if let Err(e) = printout_write(cx, &routed, b.as_str()) {
                        r = Err(e);
                        b.clear();
                        break;
                    }
                    b.clear();
                    #[cfg(not(feature = "extras"))]
                    let _ = cx.write_printout(&mut b, v); // cut past 1 KiB
                                                          // in pieces of 1 KiB, each written anew past the last (CLIPS prints
                                                          // a multifield of any length whole)
                    #[cfg(feature = "extras")]
                    if let Err(e) = printout_long(cx, &routed, &mut b, v) {
                        r = Err(e);
                        b.clear();
                        break;
                    }
                }
            }
        }
        a = cx.exprs[a as usize].next;
    }
    if let Err(e) = printout_write(cx, &routed, b.as_str()) {
        r = Err(e);
    }
    // what the arguments built goes, unless a variable bound there holds it
    super::control::release_scratch(cx, mark);
    r
}

/// A value too long for `printout`'s buffer, written to its router in pieces; the last
/// piece is left in `b` (text may follow it).
#[cfg(feature = "extras")]
#[inline(never)]
fn printout_long(
    cx: &mut Core<'_>,
    routed: &Routed,
    b: &mut TextBuf<1024>,
    v: Value,
) -> Result<(), EvalError> {
    let mut done = 0;
    loop {
        let full = cx
            .write_printout(&mut Past { skip: done, out: b }, v)
            .is_err();
        if !full || b.is_empty() {
            return Ok(());
        }
        done += b.len();
        printout_write(cx, routed, b.as_str())?;
        b.clear();
    }
}

/// Writes into `out` the text after its first `skip` bytes. Each piece `TextBuf` took
/// ends on a character boundary of one `write_str`'s text, so `skip` always lands on one.
#[cfg(feature = "extras")]
struct Past<'a> {
    skip: usize,
    out: &'a mut TextBuf<1024>,
}

#[cfg(feature = "extras")]
impl core::fmt::Write for Past<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        if self.skip >= s.len() {
            self.skip -= s.len();
            return Ok(());
        }
        let rest = s.get(self.skip..).unwrap_or("");
        self.skip = 0;
        self.out.write_str(rest)
    }
}

/// `printout`'s text to its router. While a propagation waits (`rete::defer`) text for
/// an engine router is held until it is built; text that does not fit, or goes to a
/// file, builds it first (its error stops the printout with nothing more printed).
#[inline(always)]
fn printout_write(cx: &mut Core<'_>, routed: &Routed, text: &str) -> Result<(), EvalError> {
    #[cfg(feature = "defer")]
    if cx.st.net.deferred.fact != NONE {
        if text.is_empty() {
            return Ok(());
        }
        if let Routed::Engine(router) = *routed {
            if cx.hold_print(router, text) {
                return Ok(());
            }
        }
        cx.flush_deferred()?;
    }
    cx.write(routed.name(), text);
    Ok(())
}

/// The engine router a logical name names (`t`, `stdout`, ...; None for any other
/// name, a file's or an unknown one), as `resolve_router` finds it without a report.
#[cfg(feature = "defer")]
fn engine_router(cx: &Core<'_>, name: Value) -> Option<Option<&'static str>> {
    let (Value::Sym(s) | Value::Str(s)) = name else {
        return None;
    };
    let text = match cx.sym_text(s) {
        "T" => "t",
        t => t,
    };
    ROUTERS.iter().find(|(n, _)| *n == text).map(|&(_, r)| r)
}

/// Expressions whose evaluation calls nothing (so prints nothing).
/// `printout` of values already evaluated (a call whose arguments expand, see
/// `environment`): the first names the router.
/// The character `printout` writes for its special symbols: `crlf`, `tab`, and
/// `vtab` and `ff` (CLIPS's vertical tab and form feed).
fn special_char(cx: &Core<'_>, v: Value) -> Option<char> {
    match v {
        Value::Sym(s) if s == SYM_CRLF => Some('\n'),
        Value::Sym(s) => match cx.sym_text(s) {
            "tab" => Some('\t'),
            "vtab" => Some('\x0b'),
            "ff" => Some('\x0c'),
            _ => None,
        },
        _ => None,
    }
}

pub(super) fn printout_values(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = cx.arg(a, 0);
    if name == Value::Sym(SYM_NIL) || cx.st.mode.halting {
        return Ok(Value::Void);
    }
    let routed = match resolve_router(cx, name, "printout") {
        Ok(Some(r)) => r,
        Err(e) if e.reported => return Err(e),
        _ => return Ok(Value::Void),
    };
    let mut b: TextBuf<1024> = TextBuf::new();
    for i in 1..a.len as usize {
        let v = cx.arg(a, i);
        if b.len() > 900 {
            cx.write(routed.name(), b.as_str());
            b.clear();
        }
        match special_char(cx, v) {
            Some(c) => {
                let _ = b.write_char(c);
            }
            None => {
                let len = b.len();
                if cx.write_printout(&mut b, v).is_err() {
                    b.truncate(len);
                    cx.write(routed.name(), b.as_str());
                    b.clear();
                    let _ = cx.write_printout(&mut b, v);
                }
            }
        }
    }
    cx.write(routed.name(), b.as_str());
    Ok(Value::Void)
}

fn is_leaf(op: crate::expr::Op) -> bool {
    use crate::expr::Op;
    matches!(
        op,
        Op::Int | Op::Float | Op::Sym | Op::Str | Op::Local | Op::Global | Op::PatVar | Op::QSlot
    )
}

/// CLIPS's own logical names and the engine routers they go to (`None`: `stdin`,
/// output to which is dropped). `open` refuses them as names in use.
pub(super) const ROUTERS: [(&str, Option<&str>); 9] = [
    ("t", Some(router::STDOUT)),
    ("stdout", Some(router::STDOUT)),
    ("wclips", Some(router::STDOUT)),
    ("wdialog", Some(router::STDOUT)),
    ("wdisplay", Some(router::WDISPLAY)),
    ("wtrace", Some(router::WTRACE)),
    ("werror", Some(router::WERROR)),
    ("wwarning", Some(router::WWARNING)),
    ("stdin", None),
];

/// Where output to a logical name goes.
// lives on the stack for one call, and there is no heap to box the name into
#[allow(clippy::large_enum_variant)]
pub(super) enum Routed {
    /// One of CLIPS's own routers.
    Engine(&'static str),
    /// A file the host opened under this name (`open`).
    #[cfg(feature = "parser")]
    File(TextBuf<256>),
}

impl Routed {
    /// The router name the host is given.
    pub(super) fn name(&self) -> &str {
        match self {
            Routed::Engine(r) => r,
            #[cfg(feature = "parser")]
            Routed::File(name) => name.as_str(),
        }
    }
}

/// Where output to a CLIPS logical name goes: `Some(router)`, or `None` for `stdin`
/// (output to it is dropped). A name that is no router and no open file is
/// `[ROUTER1]` (printed here), as in the CLIPS command line.
///
/// A value that cannot be a logical name (a multifield, a fact address) is `[IOFUN1]`
/// for `func`, an error that halts what runs (CLIPS's `GetLogicalName` gives NULL).
pub(super) fn resolve_router(
    cx: &mut Core<'_>,
    name: Value,
    func: &str,
) -> Result<Option<Routed>, EvalError> {
    // (host only: the image's code budget is tight; there such a name is `[ROUTER1]`)
    #[cfg(not(feature = "extras"))]
    let _ = func;
    #[cfg(feature = "extras")]
    if matches!(name, Value::Multi(_) | Value::Fact(_) | Value::Void) {
        cx.write(router::WERROR, "[IOFUN1] Illegal logical name used for ");
        cx.write(router::WERROR, func);
        cx.write(router::WERROR, " function.\n");
        return Err(EvalError::already_reported());
    }
    if let Value::Sym(s) | Value::Str(s) = name {
        let text = cx.sym_text(s);
        // an instance name `[t]` names the router `t` (host only)
        #[cfg(feature = "extras")]
        let text = crate::value::instance_name_body(text).unwrap_or(text);
        // (CLIPS takes `T` for `t` wherever it reads a logical name)
        let text = match text {
            "T" => "t",
            t => t,
        };
        if let Some(&(_, r)) = ROUTERS.iter().find(|(n, _)| *n == text) {
            return Ok(r.map(Routed::Engine));
        }
    }
    #[cfg(feature = "parser")]
    if let Some(file) = super::io::open_file_name(cx, name) {
        return Ok(Some(Routed::File(file)));
    }
    report_unknown_router(cx, name);
    Err(EvalError::new(EvalErrorKind::Reported))
}

/// `[ROUTER1]`: no router takes this logical name.
pub(super) fn report_unknown_router(cx: &mut Core<'_>, name: Value) {
    cx.write(router::WERROR, "[ROUTER1] Logical name ");
    // (an instance name without its brackets, host only)
    #[cfg(feature = "extras")]
    if let Value::Sym(s) = name {
        if let Some(inner) = crate::value::instance_name_body(cx.sym_text(s)) {
            let mut b: TextBuf<256> = TextBuf::new();
            let _ = b.write_str(inner);
            cx.write(router::WERROR, b.as_str());
            cx.write(router::WERROR, " was not recognized by any routers\n");
            return;
        }
    }
    cx.print_value(router::WERROR, name, false);
    cx.write(router::WERROR, " was not recognized by any routers\n");
}

fn halt(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.st.mode.halt = true;
    Ok(Value::Void)
}

fn exit(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    cx.st.mode.exit_status = match a.len {
        0 => 0,
        _ => match cx.arg(a, 0) {
            Value::Int(n) => n as i32,
            _ => return Err(EvalError::wrong_type("exit", 1, "integer")),
        },
    };
    cx.st.mode.exit = true;
    cx.st.mode.halt = true;
    Err(EvalError::new(EvalErrorKind::Exit))
}

/// `(refresh-agenda [MODULE])`: the current module's agenda, MODULE's, or every
/// module's for `*`.
fn refresh_agenda(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    // (CLIPS's message: a symbol, not a string)
    if a.len > 0 && !matches!(cx.arg(a, 0), Value::Sym(_)) {
        return Err(EvalError::wrong_type("refresh-agenda", 1, "symbol"));
    }
    let Some(view) = module_view(cx, a, "refresh-agenda")? else {
        return Ok(Value::Void);
    };
    if view.all {
        cx.reorder_agenda(None)?;
    } else {
        cx.reorder_agenda(Some(view.one))?;
    }
    Ok(Value::Void)
}

/// `(set-strategy NAME)`: the strategy before; CLIPS's messages for a bad argument.
#[cfg(feature = "extras")]
fn set_strategy(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    use crate::strategy::Strategy;
    let s = match cx.arg(a, 0) {
        Value::Sym(s) => s,
        _ => {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function set-strategy expected argument #1 to be of type symbol\n",
            );
            // (a computed value: the strategy stays, its name returned; a literal is
            // refused while read)
            let current = Value::Sym(cx.intern(cx.strategy().name())?);
            cx.set_error_fallback(current, None);
            return Err(EvalError::new(EvalErrorKind::Reported));
        }
    };
    match Strategy::from_name(cx.sym_text(s)) {
        Some(new) => {
            let old = cx.set_strategy(new);
            Ok(Value::Sym(cx.intern(old.name())?))
        }
        None => {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function set-strategy expected argument #1 to be of type symbol with value depth, breadth, lex, mea, complexity, simplicity, or random\n",
            );
            let current = Value::Sym(cx.intern(cx.strategy().name())?);
            cx.set_error_fallback(current, None);
            Err(EvalError::new(EvalErrorKind::Reported))
        }
    }
}

/// Without `extras` (the agent image) the agenda has the depth strategy only.
#[cfg(not(feature = "extras"))]
fn set_strategy(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = cx.arg_symbol(a, 0, "set-strategy")?;
    if cx.sym_text(s) != "depth" {
        return Err(EvalError::message(crate::error::Message::DepthStrategyOnly));
    }
    Ok(Value::Sym(cx.intern("depth")?))
}

fn get_strategy(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(cx.intern(cx.strategy().name())?))
}

pub(super) fn list_defrules(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = module_view(cx, a, "list-defrules")? else {
        return Ok(Value::Void);
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        for r in 0..cx.st.pools.nrules {
            let rule = cx.rules[r as usize];
            if rule.deleted || (r > 0 && cx.rules[r as usize - 1].next_disjunct == r) {
                continue;
            }
            #[cfg(feature = "modules")]
            if cx.rule_tag(r).module != m {
                continue;
            }
            let _ = m;
            let mut b: TextBuf<128> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(rule.name));
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
        }
    }
    if n > 0 {
        write_total(cx, n, "defrule");
    }
    Ok(Value::Void)
}

/// The rule `name` names: `MOD::rule`, the current module's, or one of a module it
/// imports `?ALL` from that exports `?ALL` (as CLIPS finds them).
pub(super) fn find_rule(cx: &mut Core<'_>, name: Ix) -> Option<Ix> {
    #[cfg(feature = "modules")]
    {
        if let Some((m, bare)) = cx.resolve_qualified(name) {
            let current = cx.current_module();
            cx.set_current_module(m);
            let r = (0..cx.st.pools.nrules).find(|&r| cx.rule_here(r, bare));
            cx.set_current_module(current);
            return r;
        }
        let own = (0..cx.st.pools.nrules).find(|&r| cx.rule_here(r, name));
        let from = cx.current_module();
        own.or_else(|| {
            (0..cx.st.pools.nrules).find(|&r| {
                let rule = &cx.rules[r as usize];
                rule.name == name
                    && !rule.deleted
                    && cx.visible_in(
                        crate::module::class::RULES,
                        cx.rule_tag(r).module,
                        name,
                        from,
                    )
            })
        })
    }
    #[cfg(not(feature = "modules"))]
    (0..cx.st.pools.nrules).find(|&r| cx.rule_here(r, name))
}

/// What a construct command could not do.
#[derive(Clone, Copy)]
pub(super) enum Unable {
    /// `[PRNTUTIL1]`: no construct of that name.
    Find,
    /// `[PRNTUTIL4]`: it is in use.
    Delete,
}

/// CLIPS's message for a construct `name` of kind `kind` that is not there or cannot go.
pub(super) fn unable(cx: &mut Core<'_>, what: Unable, kind: &str, name: Ix) {
    let mut b: TextBuf<300> = TextBuf::new();
    let _ = match what {
        Unable::Find => writeln!(
            b,
            "[PRNTUTIL1] Unable to find {kind} {}.",
            cx.sym_text(name)
        ),
        Unable::Delete => writeln!(
            b,
            "[PRNTUTIL4] Unable to delete {kind} {}.",
            cx.sym_text(name)
        ),
    };
    cx.write(router::WERROR, b.as_str());
}

fn ppdefrule(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = construct_name(cx, a, "ppdefrule", "defrule") else {
        return Ok(Value::Void);
    };
    let Some(r) = find_rule(cx, name) else {
        unable(cx, Unable::Find, "defrule", name);
        return Ok(Value::Void);
    };
    let text = cx.rules[r as usize].text;
    if text != NONE {
        let mut b: TextBuf<8192> = TextBuf::new();
        let _ = super::pretty::write_defrule(cx.sym_text(text), cx.rule_module_name(r), &mut b);
        let _ = b.write_char('\n');
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

/// A construct name argument as CLIPS's `GetConstructName` checks it: a computed
/// value that is no symbol is reported (`kind` name) but sets no error, so the actions
/// holding the call go on (a literal is refused while read).
pub(super) fn construct_name(
    cx: &mut Core<'_>,
    a: Args,
    func: &str,
    kind: &str,
) -> Option<crate::value::SymId> {
    match cx.arg(a, 0) {
        Value::Sym(s) if crate::value::instance_name_body(cx.sym_text(s)).is_none() => Some(s),
        v => {
            // (an instance name `[x]`, most often typed, as CLIPS's parser words it)
            let symbol = matches!(v, Value::Sym(_));
            let mut b: TextBuf<120> = TextBuf::new();
            let _ = if symbol {
                writeln!(
                    b,
                    "[ARGACCES5] Function {func} expected argument #1 to be of type symbol"
                )
            } else {
                writeln!(
                    b,
                    "[ARGACCES5] Function {func} expected argument #1 to be of type {kind} name"
                )
            };
            cx.write(router::WERROR, b.as_str());
            None
        }
    }
}

fn undefrule(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = construct_name(cx, a, "undefrule", "defrule") else {
        return Ok(Value::Void);
    };
    if cx.st.net.matching > 0 {
        // the network may not change while a test in it runs
        unable(cx, Unable::Delete, "defrule", name);
        return Ok(Value::Void);
    }
    // a compiled rule base's network read in place is copied into the arena first
    cx.network_writable()?;
    // (a rule named `*` goes alone, as in CLIPS; the next `*` takes all)
    if cx.sym_text(name) == "*" && find_rule(cx, name).is_none() {
        // the current module's rules in definition order; `remove_rule` takes a
        // rule's first disjunct
        for r in 0..cx.st.pools.nrules {
            let rule = cx.rules[r as usize];
            let first = (0..cx.st.pools.nrules).find(|&q| cx.rule_here(q, rule.name));
            if !rule.deleted && first == Some(r) {
                if rule_firing(cx, r) {
                    unable(cx, Unable::Delete, "defrule", rule.name);
                    continue;
                }
                #[cfg(feature = "extras")]
                cx.watch_forget(crate::engine::watch::RULES, r, rule.name);
                cx.remove_rule(r);
                #[cfg(feature = "extras")]
                cx.st.breaks.remove(rule.name);
            }
        }
        return Ok(Value::Void);
    }
    match find_rule(cx, name) {
        Some(r) if rule_firing(cx, r) => {
            unable(cx, Unable::Delete, "defrule", name);
            Ok(Value::Void)
        }
        Some(r) => {
            #[cfg(feature = "extras")]
            cx.watch_forget(crate::engine::watch::RULES, r, cx.rules[r as usize].name);
            cx.remove_rule(r);
            #[cfg(feature = "extras")]
            cx.st.breaks.remove(cx.rules[r as usize].name);
            Ok(Value::Void)
        }
        None => {
            unable(cx, Unable::Find, "defrule", name);
            Ok(Value::Void)
        }
    }
}

/// Whether rule `r` (its first disjunct) is the one whose actions run: CLIPS does
/// not delete it (`[PRNTUTIL4]`), and the actions go on.
fn rule_firing(cx: &Core<'_>, mut r: Ix) -> bool {
    let current = cx.st.agenda.current_rule;
    if current == NONE {
        return false;
    }
    while r != NONE {
        if r == current {
            return true;
        }
        r = cx.rules[r as usize].next_disjunct;
    }
    false
}

/// `(matches rule [verbose|succinct|terse])` (`super::matches`).
fn matches(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = cx.arg_symbol(a, 0, "matches")?;
    let Some(r) = find_rule(cx, name) else {
        unable(cx, Unable::Find, "defrule", name);
        return Ok(Value::Sym(SYM_FALSE));
    };
    super::matches::matches(cx, a, r)
}

/// The file-name argument of a file function, copied out of the symbol table.
fn path_arg(cx: &Core<'_>, a: Args, func: &'static str) -> Result<TextBuf<256>, EvalError> {
    let p = cx.arg_lexeme(a, 0, func)?;
    let mut path: TextBuf<256> = TextBuf::new();
    // a cut name would open another file
    if path.write_str(cx.sym_text(p)).is_err() {
        return Err(EvalError::message(crate::error::Message::PathTooLong));
    }
    Ok(path)
}

/// `load`/`load*`: defines the constructs of a file, streamed item by item; a bad
/// construct is reported and the rest still loaded (as CLIPS does), the result is then
/// FALSE.
fn load_impl(cx: &mut Core<'_>, a: Args, quiet: bool) -> Result<Value, EvalError> {
    let func = if quiet { "load*" } else { "load" };
    let path = path_arg(cx, a, func)?;
    let mut file = FileItems::new(path.as_str(), file_buffer());
    if file.open(cx).is_err() {
        cx.report_unopened_file(func, path.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    let mut ok = true;
    let mut progress = false;
    // CLIPS's error correction: after an error it skips to the next construct, and
    // says nothing of what it skips (a bad construct's rest, commands)
    let mut correcting = false;
    loop {
        let item = match file.next_item(cx) {
            Ok(Some(item)) => item,
            Ok(None) => break,
            Err(e) => {
                cx.report_file_error(func, path.as_str(), e);
                ok = false;
                break;
            }
        };
        if only_blank(item.text) {
            continue;
        }
        if !starts_construct(item.text) {
            // a command, a stray symbol or `)`: one message for a run of them
            if !correcting {
                cx.write(
                    router::WERROR,
                    "\n[CSTRCPSR1] Expected the beginning of a construct.\n",
                );
                correcting = true;
            }
            // skipping, CLIPS's scanner meets the file's end inside a string
            if item.last && ends_in_string(item.text) {
                cx.write(
                    router::WERROR,
                    "\n[SCANNER1] Encountered End-Of-File while scanning a string\n",
                );
            }
            ok = false;
            continue;
        }
        correcting = false;
        if let Err(e) = cx.load_items(item.text, !quiet, &mut progress) {
            cx.st.io.line_base = item.line_base;
            cx.report_load_error(path.as_str(), item.text, &e);
            cx.st.io.line_base = 0;
            ok = false;
            correcting = true;
        }
    }
    if progress {
        cx.write(router::STDOUT, "\n");
    }
    Ok(Value::Sym(if ok { SYM_TRUE } else { SYM_FALSE }))
}

/// Whether text ends inside a string (its last token an unterminated string).
fn ends_in_string(text: &str) -> bool {
    let mut lx = crate::lexer::Lexer::new(text);
    loop {
        match lx.next_token().tok {
            crate::lexer::Tok::Eof => return false,
            crate::lexer::Tok::Bad => return true,
            _ => {}
        }
    }
}

/// Whether a file item holds no token (spaces and comments at the end of the file).
fn only_blank(text: &str) -> bool {
    crate::lexer::Lexer::new(text).next_token().tok == crate::lexer::Tok::Eof
}

/// Whether a file item begins as a construct does, `(` and a construct keyword (those
/// of CLIPS's object system too, which the parser refuses by name).
fn starts_construct(text: &str) -> bool {
    let mut lx = crate::lexer::Lexer::new(text);
    if lx.next_token().tok != crate::lexer::Tok::LParen {
        return false;
    }
    matches!(lx.next_token().tok, crate::lexer::Tok::Symbol(s) if crate::lexer::is_construct_keyword(s))
}

#[cfg_attr(not(feature = "parser"), allow(dead_code))]
pub(super) fn load(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    load_impl(cx, a, false)
}
#[cfg_attr(not(feature = "parser"), allow(dead_code))]
pub(super) fn load_quiet(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    load_impl(cx, a, true)
}

/// `batch`: CLIPS makes the file its next input source, so its commands run (echoed,
/// with prompts) after the current command has finished and printed its TRUE. The path
/// is remembered here and run by the command loop (`Core::run_pending_batch`).
#[cfg(feature = "parser")]
pub(super) fn batch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, "batch")?;
    let mut probe = [0u8; 1];
    match cx.host.read_file_at(path.as_str(), 0, &mut probe) {
        // `TooLarge`: a host without read_file_at, and the file exists
        Ok(_) | Err(crate::error::HostIoError::TooLarge) => {}
        Err(_) => {
            cx.report_unopened_file("batch", path.as_str());
            return Ok(Value::Sym(SYM_FALSE));
        }
    }
    cx.st.io.pending_batch.clear();
    let _ = cx.st.io.pending_batch.write_str(path.as_str());
    Ok(Value::Sym(SYM_TRUE))
}

/// `batch*`: runs the file's commands at once, without prompts, echo or results.
#[cfg_attr(not(feature = "parser"), allow(dead_code))]
pub(super) fn batch_quiet(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, "batch*")?;
    let ok = cx.batch_file_stream(path.as_str(), false)?;
    Ok(Value::Sym(if ok { SYM_TRUE } else { SYM_FALSE }))
}

#[cfg_attr(not(feature = "parser"), allow(dead_code))]
pub(super) fn load_facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, "load-facts")?;
    let mut file = FileItems::new(path.as_str(), file_buffer());
    if file.open(cx).is_err() {
        cx.report_unopened_file("load-facts", path.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    loop {
        match file.next_item(cx) {
            Ok(Some(item)) => match cx.load_facts_text(item.text)? {
                FactsRead::All => {}
                FactsRead::Stopped => return Ok(Value::Sym(SYM_TRUE)),
                FactsRead::Failed => {
                    cx.write(router::WERROR, "Function load-facts encountered an error\n");
                    return Ok(Value::Sym(SYM_FALSE));
                }
            },
            Ok(None) => return Ok(Value::Sym(SYM_TRUE)),
            Err(e) => {
                cx.report_file_error("load-facts", path.as_str(), e);
                return Ok(Value::Sym(SYM_FALSE));
            }
        }
    }
}

fn time(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Float(cx.host.time()))
}

fn list_deftemplates(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = module_view(cx, a, "list-deftemplates")? else {
        return Ok(Value::Void);
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        for t in 0..cx.st.pools.ntemplates {
            // implied (ordered-fact) templates are listed too, as CLIPS 6.30 does; a
            // template retired by a redefinition has no name and is gone
            let tm = cx.templates[t as usize];
            if tm.name == NONE {
                continue;
            }
            #[cfg(feature = "modules")]
            if cx.module_of_template(t) != m {
                continue;
            }
            let _ = m;
            let mut b: TextBuf<128> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(tm.name));
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
        }
    }
    // (a module without deftemplates lists nothing)
    if n == 0 {
        return Ok(Value::Void);
    }
    write_total(cx, n, "deftemplate");
    Ok(Value::Void)
}

/// `(list-deffunctions [MODULE | *])`, as `list-defrules`.
fn list_deffunctions(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = module_view(cx, a, "list-deffunctions")? else {
        return Ok(Value::Void);
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        for p in 0..cx.st.pools.nfuncs {
            // (a redefined one is listed last, as in CLIPS)
            let f = cx.function_listed(p);
            // a removed deffunction keeps its entry, without a name
            let name = cx.funcs[f as usize].name;
            if name == NONE {
                continue;
            }
            #[cfg(feature = "modules")]
            if cx.module_of_function(f) != m {
                continue;
            }
            let _ = m;
            let mut b: TextBuf<128> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(name));
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
        }
    }
    if n == 0 {
        return Ok(Value::Void); // CLIPS lists nothing, not even the total
    }
    write_total(cx, n, "deffunction");
    Ok(Value::Void)
}

/// `For a total of N WHATs.` after a listing (`list-defrules` and the like).
pub(crate) fn write_total(cx: &mut Core<'_>, n: usize, what: &str) {
    let mut b: TextBuf<64> = TextBuf::new();
    let _ = writeln!(
        b,
        "For a total of {n} {what}{}.",
        if n == 1 { "" } else { "s" }
    );
    cx.write(router::WDISPLAY, b.as_str());
}

fn get_fact_dup(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(cx.st.mode.fact_duplication))
}

/// Which modules a `list-def*` command (or `agenda`) lists: one (the current, or the
/// one named), or all (`*`, each under a `NAME:` line, empty ones too, names indented
/// by 3).
#[derive(Clone, Copy)]
pub(super) struct ModuleView {
    all: bool,
    one: crate::module::ModId,
}

impl ModuleView {
    /// The modules to list, in definition order.
    pub(super) fn modules(self, cx: &Core<'_>) -> impl Iterator<Item = crate::module::ModId> {
        #[cfg(feature = "modules")]
        let n = cx.st.modules.nmodules as crate::module::ModId;
        #[cfg(not(feature = "modules"))]
        let n = {
            let _ = cx;
            1
        };
        (0..n).filter(move |&m| self.all || m == self.one)
    }

    /// Whether the (one) module listed sees template `t`.
    pub(super) fn sees_template(self, cx: &Core<'_>, t: Ix) -> bool {
        #[cfg(feature = "modules")]
        return cx.visible_in(
            crate::module::class::TEMPLATE,
            cx.module_of_template(t),
            cx.templates[t as usize].name,
            self.one,
        );
        #[cfg(not(feature = "modules"))]
        {
            let _ = (cx, t);
            true
        }
    }

    /// Whether every module is listed (`*`).
    pub(super) fn all(self) -> bool {
        self.all
    }

    pub(super) fn indent(self) -> &'static str {
        if self.all {
            "   "
        } else {
            ""
        }
    }

    /// Prints module `m`'s heading (listing all modules only).
    pub(super) fn head(self, cx: &mut Core<'_>, m: crate::module::ModId) {
        if !self.all {
            return;
        }
        #[cfg(feature = "modules")]
        {
            let mut b: TextBuf<128> = TextBuf::new();
            let _ = writeln!(b, "{}:", cx.module_name(m));
            cx.write(router::WDISPLAY, b.as_str());
        }
        #[cfg(not(feature = "modules"))]
        {
            let _ = m;
            cx.write(router::WDISPLAY, "MAIN:\n");
        }
    }
}

/// The module argument of a `list-def*` command (`*` for all), or CLIPS's
/// `[ARGACCES5]` printed for a name no module has (None).
pub(super) fn module_view(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
) -> Result<Option<ModuleView>, EvalError> {
    #[cfg(feature = "modules")]
    {
        let current = cx.current_module();
        if a.len == 0 {
            return Ok(Some(ModuleView {
                all: false,
                one: current,
            }));
        }
        let s = match cx.arg(a, 0) {
            Value::Sym(s) => s,
            // (CLIPS's deffunction listings take any non-symbol for no module's name)
            _ if !func.contains("deffunction") => {
                return Err(EvalError::wrong_type(func, 1, "symbol"))
            }
            _ => {
                cx.write_error_message(EvalError::wrong_type(func, 1, "defmodule name"));
                return Ok(None);
            }
        };
        if cx.sym_text(s) == "*" {
            return Ok(Some(ModuleView {
                all: true,
                one: current,
            }));
        }
        match cx.find_module(cx.sym_text(s)) {
            Some(m) => Ok(Some(ModuleView { all: false, one: m })),
            None => {
                cx.write_error_message(EvalError::wrong_type(func, 1, "defmodule name"));
                Ok(None)
            }
        }
    }
    // without modules there is MAIN alone: another name is no module's, as in CLIPS
    #[cfg(not(feature = "modules"))]
    {
        let one = crate::module::MAIN;
        if a.len == 0 {
            return Ok(Some(ModuleView { all: false, one }));
        }
        let s = match cx.arg(a, 0) {
            Value::Sym(s) => s,
            _ if !func.contains("deffunction") => {
                return Err(EvalError::wrong_type(func, 1, "symbol"))
            }
            _ => {
                cx.write_error_message(EvalError::wrong_type(func, 1, "defmodule name"));
                return Ok(None);
            }
        };
        match cx.sym_text(s) {
            "*" => Ok(Some(ModuleView { all: true, one })),
            "MAIN" => Ok(Some(ModuleView { all: false, one })),
            _ => {
                cx.write_error_message(EvalError::wrong_type(func, 1, "defmodule name"));
                Ok(None)
            }
        }
    }
}
