//! Environment and debugging commands the agent image leaves out (agent-core feature
//! `extras`): `list-watch-items`, `get-watch-item`, `get-function-restrictions`, and sequence expansion
//! (`expand$`, `$?x` with `set-sequence-operator-recognition`).
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "extras"), allow(dead_code))]

use super::commands::WatchItem;
use super::extras::{find_pp_construct, listed_at, name_at, owner_at, Kind, PpKind};
use super::{Args, Builtin, ANY};
use crate::engine::{watch, Core};
use crate::error::EvalError;
use crate::expr::{Expr, FnKind, Op};
use crate::host::router;
use crate::value::{Ix, SymId, TextBuf, Value, NONE};
use core::fmt::Write;

#[cfg(feature = "extras")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("list-watch-items", 0, ANY, list_watch_items)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("get-watch-item", 1, 1, get_watch_item)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any)
        .on_error(super::describe::OnError::False)
        .returns(super::describe::Returns::Symbol),
    Builtin::eager("get-function-restrictions", 1, 1, get_function_restrictions)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any)
        .on_error(super::describe::OnError::EmptyString),
    Builtin::lazy("expand$", 1, 1, expand)
        .args(&[super::describe::ArgType::Multifield], super::describe::ArgType::Any)
        .on_error(super::describe::OnError::False),
    Builtin::lazy("timer", 0, ANY, timer),
    Builtin::eager("options", 0, 0, options).returns(super::describe::Returns::Void),
    Builtin::eager("save", 1, 1, save).file_name(),
    Builtin::eager("set-break", 1, 1, set_break)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("remove-break", 0, 1, remove_break)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("show-breaks", 0, 1, show_breaks)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("refresh", 1, 1, refresh)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    // made by the parser only (no text names it): a call whose arguments expand
    Builtin::lazy("(expansion-call)", 1, 1, expansion_call),
];

/// Ids of `expand$` and of the wrapper of calls whose arguments expand (the parser
/// makes both).
#[cfg(feature = "extras")]
pub const ID_EXPAND: Ix = super::builtin_id("expand$");
#[cfg(feature = "extras")]
pub const ID_EXPANSION_CALL: Ix = super::builtin_id("(expansion-call)");
/// Id of `progn` (its arguments are actions, not checked by `parser::rhs_types`).
#[cfg(feature = "extras")]
pub const ID_PROGN: Ix = super::builtin_id("progn");
#[cfg(not(feature = "extras"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// The watch items in the order `(list-watch-items)` prints them.
const WATCH_ITEMS: [&str; 14] = [
    "facts",
    "instances",
    "slots",
    "rules",
    "activations",
    "messages",
    "message-handlers",
    "generic-functions",
    "methods",
    "deffunctions",
    "compilations",
    "statistics",
    "globals",
    "focus",
];

/// Prints `[ARGACCES5]` for argument `arg` of `list-watch-items`.
fn watch_arg_error(cx: &mut Core<'_>, arg: usize, expected: &str) -> EvalError {
    let mut b: TextBuf<128> = TextBuf::new();
    let _ = writeln!(
        b,
        "[ARGACCES5] Function list-watch-items expected argument #{arg} to be of type {expected}"
    );
    cx.write(router::WERROR, b.as_str());
    EvalError::already_reported()
}

/// `on` or `off` for a trace bit (an item's own state).
fn state(cx: &Core<'_>, bit: u8) -> &'static str {
    #[cfg(feature = "extras")]
    let on =
        (cx.st.mode.watch & !crate::engine::WatchNames::ITEMS | cx.st.watch_names.items) & bit != 0;
    #[cfg(not(feature = "extras"))]
    let on = cx.st.mode.watch & bit != 0;
    if on {
        "on"
    } else {
        "off"
    }
}

/// `on` or `off` for a COOL item (`watch::cool`).
fn cool_state(cx: &Core<'_>, bit: u8) -> &'static str {
    #[cfg(feature = "extras")]
    if cx.st.mode.cool_watch & bit != 0 {
        return "on";
    }
    let _ = (cx, bit);
    "off"
}

/// `(list-watch-items [ITEM [NAME...]])`: every item's state; one item's state and,
/// for items about constructs, each construct's own flag (by module, or the ones
/// named; a rule shows its `activations` flag under `rules` too, as CLIPS 6.30 does).
/// COOL's items with constructs (`instances`, `slots`, `message-handlers`: CLIPS
/// lists its system classes and handlers) are refused.
fn list_watch_items(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if a.len == 0 {
        for item in WATCH_ITEMS {
            let on = match super::commands::watch_item(item) {
                WatchItem::Traced(bit) => state(cx, bit),
                #[cfg(feature = "extras")]
                WatchItem::Cool(bit) => cool_state(cx, bit),
                _ => "off",
            };
            let mut b: TextBuf<64> = TextBuf::new();
            let _ = writeln!(b, "{item} = {on}");
            cx.write(router::WDISPLAY, b.as_str());
        }
        return Ok(Value::Void);
    }
    let Value::Sym(item) = cx.arg(a, 0) else {
        return Err(watch_arg_error(cx, 1, "symbol"));
    };
    let mut name: TextBuf<32> = TextBuf::new();
    let _ = name.write_str(cx.sym_text(item));
    let (bit, cool) = match super::commands::watch_item(name.as_str()) {
        WatchItem::Traced(bit) => (bit, 0),
        #[cfg(feature = "extras")]
        WatchItem::Cool(bit) => (0, bit),
        WatchItem::Untraced => (0, 0),
        WatchItem::All | WatchItem::Unknown => {
            return Err(watch_arg_error(cx, 1, "watchable symbol"))
        }
    };
    let item_state = if cool != 0 {
        cool_state(cx, cool)
    } else {
        state(cx, bit)
    };
    // what the item's constructs are, and how CLIPS names their kind
    let kind = match name.as_str() {
        "facts" => Some((Kind::Deftemplate, "deftemplate")),
        "rules" | "activations" => Some((Kind::Defrule, "defrule")),
        "deffunctions" => Some((Kind::Deffunction, "deffunction")),
        "globals" => Some((Kind::Defglobal, "defglobal")),
        // generic functions and methods: we have none to list
        "generic-functions" | "methods" => None,
        "compilations" | "statistics" | "focus" | "messages" => {
            if a.len > 1 {
                cx.write(
                    router::WERROR,
                    "[ARGACCES4] Function list-watch-items expected exactly 1 argument(s)\n",
                );
                return Err(EvalError::already_reported());
            }
            let mut b: TextBuf<64> = TextBuf::new();
            let _ = writeln!(b, "{} = {item_state}", name.as_str());
            cx.write(router::WDISPLAY, b.as_str());
            return Ok(Value::Void);
        }
        // instances, slots, message-handlers: COOL's classes
        _ => {
            cx.write(
                router::WERROR,
                "[NOTIMPL1] robotino-agent does not implement objects (COOL)\n",
            );
            return Err(EvalError::already_reported());
        }
    };
    let mut b: TextBuf<64> = TextBuf::new();
    let _ = writeln!(b, "{} = {item_state}", name.as_str());
    cx.write(router::WDISPLAY, b.as_str());
    let Some((kind, kind_name)) = kind else {
        if a.len > 1 {
            let expected = if name.as_str() == "methods" {
                "generic function name"
            } else {
                "defgeneric"
            };
            return Err(watch_arg_error(cx, 2, expected));
        }
        list_modules(cx, |_, _| {});
        return Ok(Value::Void);
    };
    if a.len > 1 {
        for i in 1..a.len as usize {
            let found = match cx.arg(a, i) {
                Value::Sym(s) => find_construct(cx, kind, s),
                _ => None,
            };
            let Some(c) = found else {
                return Err(watch_arg_error(cx, i + 1, kind_name));
            };
            let s = name_at(cx, kind, c).flatten().unwrap_or(NONE);
            let on = construct_state(cx, bit, kind, c);
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(b, "{} = {on}", cx.sym_text(s));
            cx.write(router::WDISPLAY, b.as_str());
        }
        return Ok(Value::Void);
    }
    list_modules(cx, |cx, m| {
        let mut p = 0;
        while let Some(entry) = name_at(cx, kind, listed_at(cx, kind, p)) {
            let i = listed_at(cx, kind, p);
            let owner = owner_at(cx, kind, i);
            p += 1;
            let Some(s) = entry else { continue };
            if owner != m {
                continue;
            }
            let on = construct_state(cx, bit, kind, i);
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(b, "   {} = {on}", cx.sym_text(s));
            cx.write(router::WDISPLAY, b.as_str());
        }
    });
    Ok(Value::Void)
}

/// `(get-watch-item ITEM)`: whether the item is watched (its own state, whatever its
/// constructs' flags; `all` is FALSE, as in CLIPS 6.30).
fn get_watch_item(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(item) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type("get-watch-item", 1, "symbol"));
    };
    let mut name: TextBuf<32> = TextBuf::new();
    let _ = name.write_str(cx.sym_text(item));
    let on = match super::commands::watch_item(name.as_str()) {
        WatchItem::Traced(bit) => state(cx, bit) == "on",
        #[cfg(feature = "extras")]
        WatchItem::Cool(bit) => cool_state(cx, bit) == "on",
        WatchItem::Untraced | WatchItem::All => false,
        WatchItem::Unknown => {
            return Err(EvalError::wrong_type(
                "get-watch-item",
                1,
                "watchable symbol",
            ))
        }
    };
    Ok(Core::bool_value(on))
}

/// Every module's `NAME:` line, each followed by what `each` prints for it.
fn list_modules(cx: &mut Core<'_>, mut each: impl FnMut(&mut Core<'_>, crate::module::ModId)) {
    #[cfg(feature = "modules")]
    let n = cx.st.modules.nmodules as crate::module::ModId;
    #[cfg(not(feature = "modules"))]
    let n: crate::module::ModId = 1;
    for m in 0..n {
        let mut b: TextBuf<128> = TextBuf::new();
        #[cfg(feature = "modules")]
        let _ = writeln!(b, "{}:", cx.module_name(m));
        #[cfg(not(feature = "modules"))]
        let _ = b.write_str("MAIN:\n");
        cx.write(router::WDISPLAY, b.as_str());
        each(cx, m);
    }
}

/// The construct of kind `kind` that `name` names (`MOD::x` or one the current module
/// sees), by index (a rule's first disjunct).
pub(super) fn find_construct(cx: &mut Core<'_>, kind: Kind, name: SymId) -> Option<Ix> {
    match kind {
        Kind::Deftemplate => {
            #[cfg(feature = "modules")]
            if let Some((m, bare)) = cx.resolve_qualified(name) {
                if m == crate::module::ModId::MAX {
                    return None;
                }
                let current = cx.current_module();
                cx.set_current_module(m);
                let t = cx.find_template(bare);
                cx.set_current_module(current);
                return t;
            }
            cx.find_template(name)
        }
        Kind::Defrule => super::commands::find_rule(cx, name),
        Kind::Deffunction => find_pp_construct(cx, name, PpKind::Function),
        Kind::Defglobal => find_pp_construct(cx, name, PpKind::Global),
        Kind::Deffacts => None,
    }
}

/// `on` or `off` for construct `i` of `kind` under item `bit` (with `extras`, its own
/// flag; CLIPS 6.30 shows a rule's activations flag under `rules` too).
fn construct_state(cx: &Core<'_>, bit: u8, kind: Kind, i: Ix) -> &'static str {
    let bit = if bit == watch::RULES {
        watch::ACTIVATIONS
    } else {
        bit
    };
    #[cfg(feature = "extras")]
    {
        let on = match kind {
            Kind::Deftemplate => cx.fact_traced(i),
            Kind::Defrule => cx.rule_traced(bit, i),
            Kind::Deffunction => cx.function_traced(i),
            _ => cx.global_traced(i),
        };
        if on {
            "on"
        } else {
            "off"
        }
    }
    #[cfg(not(feature = "extras"))]
    {
        let _ = (kind, i);
        state(cx, bit)
    }
}

/// `(get-function-restrictions NAME)`: CLIPS's restriction string of a function (its
/// least and most arguments, `*` for no limit, then the type codes of its arguments);
/// a function of ours CLIPS does not have gets its argument counts alone.
fn get_function_restrictions(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(name) = cx.arg(a, 0) else {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function get-function-restrictions expected argument #1 to be of type symbol\n",
        );
        return Err(EvalError::already_reported());
    };
    let mut text: TextBuf<64> = TextBuf::new();
    let _ = text.write_str(cx.sym_text(name));
    let counts = match super::lookup(text.as_str()) {
        Some((_, b)) => Some((b.min, b.max)),
        None => cx
            .find_sym(text.as_str())
            .and_then(|s| (0..cx.st.pools.nexternals).find(|&x| cx.externals[x as usize].name == s))
            .map(|x| {
                let e = cx.externals[x as usize];
                (e.min, e.max)
            }),
    };
    let Some((min, max)) = counts else {
        super::commands::unable(cx, super::commands::Unable::Find, "function", name);
        return Err(EvalError::already_reported());
    };
    if let Some(&(_, r)) = RESTRICTIONS_AT_RUN
        .iter()
        .find(|(n, _)| *n == text.as_str())
    {
        return Ok(cx.make_string(r)?);
    }
    let mut r: TextBuf<8> = TextBuf::new();
    let _ = write!(r, "{min}");
    if max == ANY {
        let _ = r.write_char('*');
    } else {
        let _ = write!(r, "{max}");
    }
    Ok(cx.make_string(r.as_str())?)
}

/// CLIPS 6.30's restriction string of builtin `name` (None for one CLIPS does not have
/// or gives none).
pub(crate) fn restriction_of(name: &str) -> Option<&'static str> {
    // (the table is sorted by name: a test below holds it so)
    RESTRICTIONS_AT_RUN
        .binary_search_by(|&(n, _)| n.cmp(name))
        .ok()
        .and_then(|i| RESTRICTIONS_AT_RUN.get(i))
        .map(|&(_, r)| r)
}

/// [`restriction_of`] by builtin id, read once at compile time.
#[cfg(feature = "extras")]
pub(crate) fn restriction_of_id(id: crate::value::Ix) -> Option<&'static str> {
    let i = *RESTRICTION_BY_ID.get(id as usize)?;
    RESTRICTIONS_AT_RUN.get(i as usize).map(|&(_, r)| r)
}

/// The index in [`RESTRICTIONS`] of each builtin's restriction string (by id; `u16::MAX`
/// for none).
#[cfg(feature = "extras")]
static RESTRICTION_BY_ID: [u16; super::COUNT] = {
    const fn cmp(a: &str, b: &str) -> core::cmp::Ordering {
        let (a, b) = (a.as_bytes(), b.as_bytes());
        let mut i = 0;
        while i < a.len() && i < b.len() {
            if a[i] != b[i] {
                return if a[i] < b[i] {
                    core::cmp::Ordering::Less
                } else {
                    core::cmp::Ordering::Greater
                };
            }
            i += 1;
        }
        if a.len() < b.len() {
            core::cmp::Ordering::Less
        } else if a.len() > b.len() {
            core::cmp::Ordering::Greater
        } else {
            core::cmp::Ordering::Equal
        }
    }
    let rows = super::flatten::<{ super::COUNT }>();
    let mut out = [u16::MAX; super::COUNT];
    let mut i = 0;
    while i < super::COUNT {
        // a binary search of the sorted table
        let (mut lo, mut hi) = (0, RESTRICTIONS.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            match cmp(RESTRICTIONS[mid].0, rows[i].name) {
                core::cmp::Ordering::Less => lo = mid + 1,
                core::cmp::Ordering::Greater => hi = mid,
                core::cmp::Ordering::Equal => {
                    out[i] = mid as u16;
                    break;
                }
            }
        }
        i += 1;
    }
    out
};

/// CLIPS 6.30's restriction strings of the functions it shares with us (what its
/// `get-function-restrictions` prints for each).
/// [`RESTRICTIONS`] as the code reads it: one copy of the table (each use of a `const`
/// may have its own, each pointer in it a relocation when the program starts).
static RESTRICTIONS_AT_RUN: &[(&str, &str)] = RESTRICTIONS;

const RESTRICTIONS: &[(&str, &str)] = &[
    ("!=", "2*n"),
    ("*", "2*n"),
    ("**", "22n"),
    ("+", "2*n"),
    ("-", "2*n"),
    ("/", "2*n"),
    ("<", "2*n"),
    ("<=", "2*n"),
    ("<>", "2*n"),
    ("=", "2*n"),
    (">", "2*n"),
    (">=", "2*n"),
    ("abs", "11n"),
    ("acos", "11n"),
    ("acosh", "11n"),
    ("acot", "11n"),
    ("acoth", "11n"),
    ("acsc", "11n"),
    ("acsch", "11n"),
    ("agenda", "01w"),
    ("and", "2*"),
    ("any-factp", "0**"),
    ("apropos", "11w"),
    ("asec", "11n"),
    ("asech", "11n"),
    ("asin", "11n"),
    ("asinh", "11n"),
    ("assert", "0**"),
    ("assert-string", "11s"),
    ("atan", "11n"),
    ("atanh", "11n"),
    ("batch", "11k"),
    ("batch*", "11k"),
    ("bind", "0**"),
    ("break", "0**"),
    ("build", "11k"),
    ("check-syntax", "11s"),
    ("clear", "00"),
    ("clear-focus-stack", "00"),
    ("close", "*1"),
    ("conserve-mem", "11w"),
    ("cos", "11n"),
    ("cosh", "11n"),
    ("cot", "11n"),
    ("coth", "11n"),
    ("create$", "0**"),
    ("csc", "11n"),
    ("csch", "11n"),
    ("deffacts-module", "11w"),
    ("deffunction-module", "11w"),
    ("defglobal-module", "11w"),
    ("defrule-module", "11w"),
    ("deftemplate-module", "11w"),
    ("deftemplate-slot-allowed-values", "22w"),
    ("deftemplate-slot-cardinality", "22w"),
    ("deftemplate-slot-default-value", "22w"),
    ("deftemplate-slot-defaultp", "22w"),
    ("deftemplate-slot-existp", "22w"),
    ("deftemplate-slot-facet-existp", "33w"),
    ("deftemplate-slot-facet-value", "33w"),
    ("deftemplate-slot-multip", "22w"),
    ("deftemplate-slot-names", "11z"),
    ("deftemplate-slot-range", "22w"),
    ("deftemplate-slot-singlep", "22w"),
    ("deftemplate-slot-types", "22w"),
    ("deg-grad", "11n"),
    ("deg-rad", "11n"),
    ("delayed-do-for-all-facts", "0**"),
    ("delete$", "33im"),
    ("delete-member$", "2*um"),
    ("dependencies", "11h"),
    ("dependents", "11h"),
    ("div", "2*n"),
    ("do-for-all-facts", "0**"),
    ("do-for-fact", "0**"),
    ("dribble-off", "00"),
    ("dribble-on", "11k"),
    ("duplicate", "0**"),
    ("eq", "2*"),
    ("eval", "11k"),
    ("evenp", "11i"),
    ("exit", "*1i"),
    ("exp", "11n"),
    ("expand$", "11m"),
    ("explode$", "11s"),
    ("fact-existp", "11z"),
    ("fact-index", "11y"),
    ("fact-relation", "11z"),
    ("fact-slot-names", "11z"),
    ("fact-slot-value", "22*zw"),
    ("facts", "*4iu"),
    ("fetch", "11k"),
    ("find-all-facts", "0**"),
    ("find-fact", "0**"),
    ("first$", "11m"),
    ("float", "11n"),
    ("floatp", "11"),
    ("focus", "1*w"),
    ("foreach", "0**"),
    ("format", "2**us"),
    ("funcall", "1**k"),
    ("gensym", "00"),
    ("gensym*", "00"),
    ("get-auto-float-dividend", "00"),
    ("get-beta-memory-resizing", "00"),
    ("get-char", "*1"),
    ("get-current-module", "00"),
    ("get-deffacts-list", "01w"),
    ("get-deffunction-list", "01"),
    ("get-defglobal-list", "01w"),
    ("get-defmodule-list", "00"),
    ("get-defrule-list", "01w"),
    ("get-deftemplate-list", "01w"),
    ("get-dynamic-constraint-checking", "00"),
    ("get-fact-duplication", "00"),
    ("get-fact-list", "01w"),
    ("get-focus", "00"),
    ("get-focus-stack", "00"),
    ("get-function-list", "00"),
    ("get-function-restrictions", "11w"),
    ("get-incremental-reset", "00"),
    ("get-region", "1**k"),
    ("get-reset-globals", "00"),
    ("get-salience-evaluation", "00"),
    ("get-sequence-operator-recognition", "00"),
    ("get-static-constraint-checking", "00"),
    ("get-strategy", "00"),
    ("get-watch-item", "11w"),
    ("grad-deg", "11n"),
    ("halt", "00"),
    ("if", "0**"),
    ("implode$", "11m"),
    ("insert$", "3**mi"),
    ("integer", "11n"),
    ("integerp", "11"),
    ("length", "11q"),
    ("length$", "11q"),
    ("lexemep", "11"),
    ("list-deffacts", "01w"),
    ("list-deffunctions", "01"),
    ("list-defglobals", "01w"),
    ("list-defmodules", "00"),
    ("list-defrules", "01w"),
    ("list-deftemplates", "01w"),
    ("list-focus-stack", "00"),
    ("list-watch-items", "0**w"),
    ("load", "11k"),
    ("load*", "11k"),
    ("load-facts", "11k"),
    ("log", "11n"),
    ("log10", "11n"),
    ("loop-for-count", "0**"),
    ("lowcase", "11j"),
    ("matches", "12w"),
    ("max", "2*n"),
    ("mem-requests", "00"),
    ("mem-used", "00"),
    ("member", "22*um"),
    ("member$", "22*um"),
    ("min", "2*n"),
    ("mod", "22n"),
    ("modify", "0**"),
    ("multifieldp", "11"),
    ("mv-append", "0**"),
    ("mv-delete", "22*im"),
    ("mv-replace", "33*im"),
    ("mv-subseq", "33*iim"),
    ("neq", "2*"),
    ("not", "11"),
    ("nth", "22*im"),
    ("nth$", "22*im"),
    ("numberp", "11"),
    ("oddp", "11i"),
    ("open", "23*k"),
    ("operating-system", "00"),
    ("options", "00"),
    ("or", "2*"),
    ("pi", "00"),
    ("pointerp", "11"),
    ("pop-focus", "00"),
    ("ppdeffacts", "11w"),
    ("ppdeffunction", "11w"),
    ("ppdefglobal", "11w"),
    ("ppdefmodule", "11w"),
    ("ppdefrule", "11w"),
    ("ppdeftemplate", "11w"),
    ("ppfact", "13*z"),
    ("print-region", "2**wk"),
    ("printout", "1*"),
    ("profile", "11w"),
    ("profile-info", "01w"),
    ("progn", "0**"),
    ("progn$", "0**"),
    ("put-char", "12"),
    ("rad-deg", "11n"),
    ("random", "02i"),
    ("read", "*1"),
    ("read-number", "*1"),
    ("readline", "*1"),
    ("refresh", "11w"),
    ("refresh-agenda", "01w"),
    ("release-mem", "00"),
    ("remove", "11k"),
    ("remove-break", "*1w"),
    ("rename", "22k"),
    ("replace$", "4**mii"),
    ("replace-member$", "3*um"),
    ("reset", "00"),
    ("rest$", "11m"),
    ("retract", "1*z"),
    ("return", "0**"),
    ("round", "11n"),
    ("rules", "01w"),
    ("run", "*1i"),
    ("save", "11k"),
    ("save-facts", "1*wk"),
    ("sec", "11n"),
    ("sech", "11n"),
    ("seed", "11i"),
    ("sequencep", "11"),
    ("set-auto-float-dividend", "11"),
    ("set-beta-memory-resizing", "11"),
    ("set-break", "11w"),
    ("set-current-module", "11w"),
    ("set-dynamic-constraint-checking", "11"),
    ("set-fact-duplication", "11"),
    ("set-incremental-reset", "11"),
    ("set-locale", "*1"),
    ("set-profile-percent-threshold", "11n"),
    ("set-reset-globals", "11"),
    ("set-salience-evaluation", "11w"),
    ("set-sequence-operator-recognition", "11w"),
    ("set-static-constraint-checking", "11"),
    ("set-strategy", "11w"),
    ("setgen", "11i"),
    ("show-breaks", "01w"),
    ("show-defglobals", "01w"),
    ("sin", "11n"),
    ("sinh", "11n"),
    ("sort", "1**w"),
    ("sqrt", "11n"),
    ("str-assert", "11s"),
    ("str-cat", "1*"),
    ("str-compare", "23*jji"),
    ("str-explode", "11s"),
    ("str-implode", "11m"),
    ("str-index", "22j"),
    ("str-length", "11j"),
    ("string-to-field", "11j"),
    ("stringp", "11"),
    ("sub-string", "33*iij"),
    ("subseq$", "33im"),
    ("subset", "22*mm"),
    ("subsetp", "22*mm"),
    ("switch", "0**"),
    ("sym-cat", "1*"),
    ("symbolp", "11"),
    ("system", "1*k"),
    ("tan", "11n"),
    ("tanh", "11n"),
    ("time", "00"),
    ("timer", "**"),
    ("timetag", "11h"),
    ("toss", "11k"),
    ("type", "11u"),
    ("undeffacts", "11w"),
    ("undeffunction", "11w"),
    ("undefglobal", "11w"),
    ("undefrule", "11w"),
    ("undeftemplate", "11w"),
    ("unwatch", "1**w"),
    ("upcase", "11j"),
    ("watch", "1**w"),
    ("while", "0**"),
    ("wordp", "11"),
];

/// `expand$` outside the arguments of a function call (the parser turns it into a
/// sequence expansion everywhere else): CLIPS's `[MISCFUN1]`, and FALSE.
/// `expand$` called itself (not among a call's arguments): CLIPS's `[MISCFUN1]`,
/// its argument not evaluated.
fn expand(cx: &mut Core<'_>, _call: Ix) -> Result<Value, EvalError> {
    expand_outside_call(cx)
}

/// CLIPS's `[MISCFUN1]` for an `expand$` (or `$?x`) that is no call's argument.
pub(crate) fn expand_outside_call(cx: &mut Core<'_>) -> Result<Value, EvalError> {
    cx.write(
        router::WERROR,
        "[MISCFUN1] expand$ must be used in the argument list of a function call.\n",
    );
    Err(EvalError::already_reported())
}

/// The call a wrapper `x` (`(expansion-call)`) stands for, else `x`: after an error
/// at the prompt the wrapped function's fallback value is printed.
#[cfg(feature = "extras")]
pub(crate) fn expanded_call(cx: &Core<'_>, x: Expr) -> Expr {
    if x.op == Op::Call && x.aux == FnKind::Builtin as u8 && x.data == ID_EXPANSION_CALL {
        cx.exprs[x.first as usize]
    } else {
        x
    }
}

/// A call whose arguments expand, as CLIPS 6.30 runs it: the expansions are evaluated
/// first (each must be a multifield), then the number of arguments is checked
/// (`[ARGACCES4]`, and FALSE), then the function is called with the expansions'
/// fields in their places and the other arguments evaluated as usual (lazily for
/// `and` and `or`). Type errors are then errors of computed arguments.
fn expansion_call(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let inner = cx.exprs[call as usize].first;
    let x = cx.exprs[inner as usize];
    let halting = cx.st.mode.halting;
    // the expansions' multifields, in order, from `parts`
    let parts = cx.st.frame.sp;
    let mut count: usize = 0;
    let mut c = x.first;
    while c != NONE {
        let e = cx.exprs[c as usize];
        if is_expansion(e) {
            let halting = cx.st.mode.halting;
            match cx.eval(e.first)? {
                Value::Multi(m) if cx.st.mode.halting == halting => {
                    count += m.len as usize;
                    cx.push_value(Value::Multi(m))?;
                }
                // one that failed (an unbound global, reported) or is no multifield
                // stands for one argument that sets the evaluation error when it
                // is read (CLIPS's `(set-evaluation-error)`), as FALSE (Void here)
                _ => {
                    if cx.st.mode.halting == halting {
                        cx.write(
                            router::WERROR,
                            "[ARGACCES5] Function expand$ expected argument #1 to be of type multifield\n",
                        );
                    }
                    cx.st.mode.halting = halting;
                    count += 1;
                    cx.push_value(Value::Void)?;
                }
            }
        } else {
            count += 1;
        }
        c = e.next;
    }
    let mut b: TextBuf<200> = TextBuf::new();
    let _ = b.write_str("[ARGACCES4] Function ");
    let (min, max) = callee_counts(cx, x, &mut b);
    if count < usize::from(min) || (max != ANY && count > usize::from(max)) {
        let _ = b.write_str(" expected ");
        let _ = if min == max {
            writeln!(b, "exactly {min} argument(s)")
        } else if count < usize::from(min) {
            writeln!(b, "at least {min} argument(s)")
        } else {
            writeln!(b, "no more than {max} argument(s)")
        };
        cx.write(router::WERROR, b.as_str());
        cx.set_error_fallback(Value::Sym(super::SYM_FALSE), None);
        return Err(EvalError::already_reported());
    }
    if x.aux == FnKind::Builtin as u8 {
        let b = super::get(x.data);
        if matches!(b.name, "and" | "or") {
            return and_or(cx, x.first, parts, b.name == "and");
        }
    }
    // the arguments, the expansions' fields spliced in
    let base = cx.st.frame.sp;
    let mut part = parts;
    let mut c = x.first;
    while c != NONE {
        let e = cx.exprs[c as usize];
        if is_expansion(e) {
            match cx.stack[part as usize] {
                Value::Multi(m) => {
                    for k in 0..m.len as usize {
                        let v = cx.mf_item(m, k);
                        cx.push_value(v)?;
                    }
                }
                _ => {
                    cx.st.mode.halting = true;
                    cx.push_value(Value::Sym(super::SYM_FALSE))?;
                }
            }
            part += 1;
        } else {
            let v = cx.eval(c)?;
            cx.push_value(v)?;
        }
        c = e.next;
    }
    let args = Args {
        base,
        len: cx.st.frame.sp - base,
    };
    cx.st.eval.literal_error = false;
    match x.aux {
        k if k == FnKind::Builtin as u8 => {
            let b = super::get(x.data);
            // an argument set the evaluation error: most stop with their error value
            if cx.st.mode.halting && !halting {
                if let Some(v) = cx.args_failed(b)? {
                    return Ok(v);
                }
            }
            match super::code_of(cx, x.data, b) {
                super::Imp::Eager(f) => f(cx, args).map_err(computed_type_error),
                super::Imp::Lazy(_) if b.name == "printout" => {
                    super::commands::printout_values(cx, args)
                }
                // (those lazy to check their arguments in order take values too)
                super::Imp::Lazy(_) => match super::in_order_body(b.name) {
                    Some(f) => f(cx, args).map_err(computed_type_error),
                    None => Err(EvalError::new(crate::error::EvalErrorKind::NoSuchFunction)),
                },
            }
        }
        k if k == FnKind::Deffunction as u8 => {
            cx.call_values(crate::eval::Callee::Deffunction(x.data), args)
        }
        _ => cx.call_values(crate::eval::Callee::External(x.data), args),
    }
}

/// Whether argument node `e` is a sequence expansion.
fn is_expansion(e: Expr) -> bool {
    e.op == Op::Expand && e.aux == 1
}

/// The least and most argument counts of the function call `x` calls, and its name
/// written to `name`.
fn callee_counts(cx: &Core<'_>, x: Expr, name: &mut dyn Write) -> (u8, u8) {
    match x.aux {
        k if k == FnKind::Builtin as u8 => {
            let b = super::get(x.data);
            let _ = name.write_str(b.name);
            (b.min, b.max)
        }
        k if k == FnKind::Deffunction as u8 => {
            let f = cx.funcs[x.data as usize];
            let _ = name.write_str(cx.sym_text(f.name));
            let max = if f.rest { ANY } else { f.nparams };
            (f.nparams, max)
        }
        _ => {
            let e = cx.externals[x.data as usize];
            let _ = name.write_str(cx.sym_text(e.name));
            (e.min, e.max)
        }
    }
}

/// `and` (`all`) or `or` of arguments `first..` whose expansions' multifields are on
/// the stack from `parts`: the other arguments are evaluated only until the result
/// is known.
fn and_or(cx: &mut Core<'_>, first: Ix, parts: Ix, all: bool) -> Result<Value, EvalError> {
    let mut part = parts;
    let mut c = first;
    while c != NONE {
        let e = cx.exprs[c as usize];
        if is_expansion(e) {
            if let Value::Multi(m) = cx.stack[part as usize] {
                for k in 0..m.len as usize {
                    if Core::is_true(cx.mf_item(m, k)) != all {
                        return Ok(Core::bool_value(!all));
                    }
                }
            }
            part += 1;
        } else if Core::is_true(cx.eval(c)?) != all {
            return Ok(Core::bool_value(!all));
        }
        c = e.next;
    }
    Ok(Core::bool_value(all))
}

/// A wrong-type error of a function called with expanded arguments: its arguments
/// were all computed, so it is worded as the function's body words it.
fn computed_type_error(err: EvalError) -> EvalError {
    match err.kind() {
        crate::error::EvalErrorKind::WrongType {
            func,
            arg,
            expected,
        } => EvalError::wrong_type(
            func,
            arg,
            super::describe::runtime_type_name(func, expected),
        ),
        _ => err,
    }
}

/// `(timer EXPR...)`: evaluates the expressions in order and returns the seconds they
/// took (the host's clock, `Host::time`).
fn timer(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let start = cx.host.time();
    let mut c = cx.exprs[call as usize].first;
    while c != NONE {
        cx.eval(c)?;
        c = cx.exprs[c as usize].next;
    }
    Ok(Value::Float(cx.host.time() - start))
}

/// The name of the rule `set-break`/`remove-break` name in their argument, or None
/// (CLIPS's "Unable to find defrule" printed when there is no such rule).
#[cfg(feature = "extras")]
fn break_rule(cx: &mut Core<'_>, a: Args) -> Option<crate::value::SymId> {
    let Value::Sym(name) = cx.arg(a, 0) else {
        return None;
    };
    let Some(r) = super::commands::find_rule(cx, name) else {
        super::commands::unable(cx, super::commands::Unable::Find, "defrule", name);
        return None;
    };
    Some(cx.rules[r as usize].name)
}

/// `(set-break RULE)`: a run stops before firing the rule (unless it fires first).
#[cfg(feature = "extras")]
fn set_break(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if !matches!(cx.arg(a, 0), Value::Sym(_)) {
        return Err(EvalError::wrong_type("set-break", 1, "symbol"));
    }
    let Some(rule) = break_rule(cx, a) else {
        return Ok(Value::Void);
    };
    if !cx.st.breaks.add(rule) {
        let mut b: TextBuf<120> = TextBuf::new();
        let _ = writeln!(
            b,
            "[NOTIMPL1] robotino-agent keeps at most {} breakpoints",
            crate::engine::Breaks::MAX
        );
        cx.write(router::WERROR, b.as_str());
        return Err(EvalError::already_reported());
    }
    // (the run loop stops at breakpoints on its general path)
    cx.note_run_slow();
    Ok(Value::Void)
}

/// `(remove-break [RULE])`: the rule's breakpoint, or all of them.
#[cfg(feature = "extras")]
fn remove_break(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if a.len == 0 {
        cx.st.breaks = crate::engine::Breaks::new();
        return Ok(Value::Void);
    }
    let Some(rule) = break_rule(cx, a) else {
        return Ok(Value::Void);
    };
    if !cx.st.breaks.remove(rule) {
        let mut b: TextBuf<160> = TextBuf::new();
        let _ = writeln!(
            b,
            "Rule {} does not have a breakpoint set.",
            cx.sym_text(rule)
        );
        cx.write(router::WERROR, b.as_str());
    }
    Ok(Value::Void)
}

/// `(refresh RULE)`: the rule's fired matches that still hold go back on the agenda
/// (`Core::refresh_rule`).
#[cfg(feature = "extras")]
fn refresh(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(name) = cx.arg(a, 0) else {
        // (a literal is refused while read; the actions go on)
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function refresh expected argument #1 to be of type rule name\n",
        );
        return Ok(Value::Void);
    };
    match super::commands::find_rule(cx, name) {
        Some(r) => cx.refresh_rule(r)?,
        None => super::commands::unable(cx, super::commands::Unable::Find, "defrule", name),
    }
    Ok(Value::Void)
}

/// `(show-breaks [MODULE | *])`: the rules with a breakpoint, in definition order, of
/// the current module, the one named, or each module under its heading.
#[cfg(feature = "extras")]
fn show_breaks(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = super::commands::module_view(cx, a, "show-breaks")? else {
        return Ok(Value::Void);
    };
    for m in view.modules(cx) {
        view.head(cx, m);
        for r in 0..cx.st.pools.nrules {
            let rule = cx.rules[r as usize];
            // a rule's later disjuncts share its name
            if rule.deleted
                || (r > 0 && cx.rules[r as usize - 1].next_disjunct == r)
                || !cx.st.breaks.has(rule.name)
            {
                continue;
            }
            #[cfg(feature = "modules")]
            if cx.rule_tag(r).module != m {
                continue;
            }
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(rule.name));
            cx.write(router::WDISPLAY, b.as_str());
        }
    }
    Ok(Value::Void)
}

/// `(save FILE)`: the constructs, pretty-printed as `pp*` shows them, each followed by
/// an empty line, in CLIPS 6.30's order: a declaration of every deffunction (its
/// parameters numbered, so later ones can call it), the defglobals one a construct,
/// the deftemplates, deffacts, deffunctions and defrules. TRUE, or `[ARGACCES2]` and
/// FALSE when the file cannot be written.
fn save(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let (Value::Sym(s) | Value::Str(s)) = cx.arg(a, 0) else {
        // (a literal is refused while read; a computed one is a "file name", FALSE)
        return Err(EvalError::wrong_type("save", 1, "symbol or string"));
    };
    let mut path: TextBuf<256> = TextBuf::new();
    let _ = path.write_str(cx.sym_text(s));
    if cx.host.write_file(path.as_str(), b"", false).is_err() {
        let mut b: TextBuf<320> = TextBuf::new();
        let _ = writeln!(
            b,
            "[ARGACCES2] Function save was unable to open file {}.",
            path.as_str()
        );
        cx.write(router::WERROR, b.as_str());
        return Err(EvalError::already_reported());
    }
    let mut out = SaveFile {
        path,
        failed: false,
    };
    for p in 0..cx.st.pools.nfuncs {
        let f = cx.function_listed(p);
        let df = cx.funcs[f as usize];
        // (CLIPS declares only the ones it has the text of: not one whose
        // redefinition failed in its actions while another construct calls it)
        if df.name == NONE || cx.function_text(f) == NONE {
            continue;
        }
        out.put(cx, |cx, w| {
            write!(
                w,
                "(deffunction {}::{} (",
                cx.function_module_name(f),
                cx.sym_text(df.name)
            )?;
            for p in 0..df.nparams {
                if p > 0 {
                    w.write_char(' ')?;
                }
                write!(w, "?p{p}")?;
            }
            if df.rest {
                if df.nparams > 0 {
                    w.write_char(' ')?;
                }
                w.write_str("$?wildargs")?;
            }
            w.write_str("))")
        });
    }
    for g in 0..cx.st.pools.nglobals {
        let name = cx.globals[g as usize].name;
        if name == NONE || cx.sym_text(name).starts_with('?') {
            continue;
        }
        let text = cx.global_text(g);
        out.put_pp(cx, text, |cx, src, w| {
            super::pretty::write_defglobal(src, cx.global_module_name(g), w)
        });
    }
    for t in 0..cx.st.pools.ntemplates {
        // (one retired by a redefinition keeps its text, but no name)
        if cx.templates[t as usize].name == NONE {
            continue;
        }
        let text = cx.templates[t as usize].text;
        out.put_pp(cx, text, |cx, src, w| {
            super::pretty::write_deftemplate_echo(
                src,
                src.len(),
                crate::error::EchoTail::Normal,
                cx.template_module_name(t),
                w,
            )
        });
    }
    for d in 0..cx.st.pools.ndeffacts {
        let text = cx.deffacts[d as usize].text;
        out.put_pp(cx, text, |cx, src, w| {
            super::pretty::write_deffacts_upto(src, cx.deffacts_module_name(d), w)?;
            w.write_char(')')
        });
    }
    for p in 0..cx.st.pools.nfuncs {
        let f = cx.function_listed(p);
        if cx.funcs[f as usize].name == NONE {
            continue;
        }
        let text = cx.function_text(f);
        out.put_pp(cx, text, |cx, src, w| {
            super::pretty::write_deffunction(src, cx.function_module_name(f), w)
        });
    }
    for r in 0..cx.st.pools.nrules {
        let rule = cx.rules[r as usize];
        // a rule's later disjuncts share its text
        if rule.deleted || (r > 0 && cx.rules[r as usize - 1].next_disjunct == r) {
            continue;
        }
        out.put_pp(cx, rule.text, |cx, src, w| {
            super::pretty::write_defrule(src, cx.rule_module_name(r), w)
        });
    }
    if out.failed {
        cx.write(
            router::WERROR,
            "[ARGACCES2] Function save could not write the whole file.\n",
        );
        return Err(EvalError::already_reported());
    }
    Ok(Value::Sym(super::SYM_TRUE))
}

/// The file `save` appends constructs to.
struct SaveFile {
    path: TextBuf<256>,
    failed: bool,
}

impl SaveFile {
    /// Appends what `write` writes, then an empty line.
    fn put(
        &mut self,
        cx: &mut Core<'_>,
        write: impl FnOnce(&Core<'_>, &mut dyn Write) -> core::fmt::Result,
    ) {
        let mut b: TextBuf<8192> = TextBuf::new();
        if write(cx, &mut b).is_err() || b.write_str("\n\n").is_err() {
            self.failed = true;
            return;
        }
        if cx
            .host
            .write_file(self.path.as_str(), b.as_str().as_bytes(), true)
            .is_err()
        {
            self.failed = true;
        }
    }

    /// `put` of a construct's pretty-printed source `text` (none when NONE).
    fn put_pp(
        &mut self,
        cx: &mut Core<'_>,
        text: Ix,
        pp: impl FnOnce(&Core<'_>, &str, &mut dyn Write) -> core::fmt::Result,
    ) {
        if text == NONE {
            return;
        }
        self.put(cx, |cx, w| pp(cx, cx.sym_text(text), w));
    }
}

/// `(options)`: the compile-time settings of the CLIPS build robotino-agent answers
/// for, Debian's CLIPS 6.30 (its text, as `operating-system` answers its `UNKNOWN`).
fn options(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.write(router::WDISPLAY, OPTIONS);
    Ok(Value::Void)
}

const OPTIONS: &str = "Machine type: Generic \n\
Defrule construct is ON
Defmodule construct is ON
Deftemplate construct is ON
  Fact-set queries are ON
  Deffacts construct is ON
Defglobal construct is ON
Deffunction construct is ON
Defgeneric/Defmethod constructs are ON
Object System is ON
  Definstances construct is ON
  Instance-set queries are ON
  Binary loading of instances is ON
  Binary saving of instances is ON
Extended math function package is ON
Text processing function package is ON
Bload capability is BLOAD AND BSAVE
Construct compiler is ON
I/O function package is ON
String function package is ON
Multifield function package is ON
Debugging function package is ON
Window Interface flag is OFF
Developer flag is OFF
Run time module is OFF
";

#[cfg(all(test, feature = "extras"))]
mod tests {
    #[test]
    fn restrictions_are_sorted_for_the_binary_search() {
        let t = super::RESTRICTIONS;
        assert!(t.windows(2).all(|w| w[0].0 < w[1].0));
        for &(n, r) in t {
            assert_eq!(super::restriction_of(n), Some(r));
        }
        assert_eq!(super::restriction_of("no-such-function"), None);
        assert!(t.len() < usize::from(u16::MAX));
        for (id, b) in crate::builtins::BUILTINS.iter().enumerate() {
            let id = id as crate::value::Ix;
            assert_eq!(super::restriction_of_id(id), super::restriction_of(b.name));
        }
    }
}
