//! Builtins the agent image leaves out (agent-core feature `extras`; its rules call none
//! of them): asking the environment about its constructs and facts (`get-defrule-list`,
//! `list-deffacts`, `show-defglobals`, `fact-slot-names`, ...), removing constructs (`undeffacts`,
//! `undeftemplate`, ...), `gensym`, and `sort`, `funcall` and `assert-string` (in
//! `evaluate`).
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "extras"), allow(dead_code))]

use super::commands::Unable;

use super::{Args, Builtin, SYM_FALSE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::fact::FactState;
use crate::host::{router, RouterWriter};
use crate::template::DefaultKind;
use crate::value::SymId;
use crate::value::{Ix, TextBuf, Value, NONE};
use core::fmt::Write;

#[cfg(feature = "extras")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("get-deffacts-list", 0, 1, get_deffacts_list),
    Builtin::eager("get-deftemplate-list", 0, 1, get_deftemplate_list),
    Builtin::eager("get-deffunction-list", 0, 1, get_deffunction_list),
    Builtin::eager("get-defglobal-list", 0, 1, get_defglobal_list),
    Builtin::eager("get-defrule-list", 0, 1, get_defrule_list),
    Builtin::eager("get-fact-list", 0, 1, get_fact_list)
        .on_error(super::describe::OnError::EmptyMultifield),
    Builtin::eager("list-deffacts", 0, 1, list_deffacts).returns(super::describe::Returns::Void),
    Builtin::eager("list-defglobals", 0, 1, list_defglobals).returns(super::describe::Returns::Void),
    Builtin::eager("show-defglobals", 0, 1, show_defglobals).args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("undeffacts", 1, 1, undeffacts).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("ppdeftemplate", 1, 1, ppdeftemplate).args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("ppdeffacts", 1, 1, ppdeffacts).args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("ppdeffunction", 1, 1, ppdeffunction).args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("ppdefglobal", 1, 1, ppdefglobal).args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("undeftemplate", 1, 1, undeftemplate).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("undeffunction", 1, 1, undeffunction).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("undefglobal", 1, 1, undefglobal).returns(super::describe::Returns::Void).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("fact-relation", 1, 1, fact_relation).args(&[super::describe::ArgType::FactOrIndex], super::describe::ArgType::Any).returns(super::describe::Returns::Symbol),
    Builtin::eager("fact-slot-names", 1, 1, fact_slot_names).args(&[super::describe::ArgType::FactOrIndex], super::describe::ArgType::Any),
    Builtin::eager("ppfact", 1, 3, ppfact).args(&[super::describe::ArgType::FactOrIndex], super::describe::ArgType::Any).returns(super::describe::Returns::Void),
    Builtin::eager("type", 1, 1, type_of).on_error(super::describe::OnError::False),
    Builtin::eager("gensym", 0, 0, gensym).returns(super::describe::Returns::Symbol),
    Builtin::eager("gensym*", 0, 0, gensym_star).returns(super::describe::Returns::Symbol),
    Builtin::eager("sort", 1, super::ANY, super::evaluate::sort).on_error(super::describe::OnError::False)
        .args(&[super::describe::ArgType::Symbol], super::describe::ArgType::Any),
    Builtin::eager("funcall", 1, super::ANY, super::evaluate::funcall).on_error(super::describe::OnError::False)
        .args(&[super::describe::ArgType::SymbolOrString], super::describe::ArgType::Any),
    Builtin::eager("assert-string", 1, 1, super::evaluate::assert_string).on_error(super::describe::OnError::False)
        .args(&[super::describe::ArgType::Str], super::describe::ArgType::Any),
    Builtin::eager("str-assert", 1, 1, super::evaluate::str_assert).on_error(super::describe::OnError::False)
        .args(&[super::describe::ArgType::Str], super::describe::ArgType::Any),
];
#[cfg(not(feature = "extras"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS).texts(&[T_FACT_OR_INDEX]);

/// CLIPS's wording for a fact argument that is neither a fact's address nor an index.
const T_FACT_OR_INDEX: &str = "fact-address or fact-index";

/// The kinds of construct these functions list, each with its names in definition
/// order (the `initial-fact` deffacts and template first, as CLIPS has them).
#[derive(Clone, Copy)]
pub(super) enum Kind {
    Deffacts,
    Deftemplate,
    Deffunction,
    Defglobal,
    Defrule,
}

/// Name number `i` of construct kind `kind`: None past the last; Some(None) for an
/// entry that is gone (a retired template, a removed rule, a rule's later disjunct).
pub(super) fn name_at(cx: &Core<'_>, kind: Kind, i: Ix) -> Option<Option<SymId>> {
    match kind {
        Kind::Deffacts => {
            // the `initial-fact` deffacts comes first while it is defined
            let skip = Ix::from(!cx.st.mode.initial_deffacts);
            let i = i + skip;
            if i == 0 {
                // named as its template
                let t = cx.st.facts.initial_tmpl;
                return Some((t != NONE).then(|| cx.templates[t as usize].name));
            }
            (i <= cx.st.pools.ndeffacts).then(|| Some(cx.deffacts[i as usize - 1].name))
        }
        Kind::Deftemplate => (i < cx.st.pools.ntemplates).then(|| {
            let name = cx.templates[i as usize].name;
            (name != NONE).then_some(name)
        }),
        // a removed deffunction or global keeps its entry, without a name
        Kind::Deffunction => (i < cx.st.pools.nfuncs).then(|| {
            let name = cx.funcs[i as usize].name;
            (name != NONE).then_some(name)
        }),
        // a variable bound at the prompt is a hidden global named `?x`: not listed
        Kind::Defglobal => (i < cx.st.pools.nglobals).then(|| {
            let name = cx.globals[i as usize].name;
            (name != NONE && !cx.sym_text(name).starts_with('?')).then_some(name)
        }),
        Kind::Defrule => (i < cx.st.pools.nrules).then(|| {
            let r = cx.rules[i as usize];
            let later_disjunct = i > 0 && cx.rules[i as usize - 1].next_disjunct == i;
            (!r.deleted && !later_disjunct).then_some(r.name)
        }),
    }
}

/// The index of the construct of kind `kind` listed at place `p` (a redefined
/// deffunction is listed last; the others are listed in index order).
pub(super) fn listed_at(cx: &Core<'_>, kind: Kind, p: Ix) -> Ix {
    match kind {
        Kind::Deffunction => cx.function_listed(p),
        _ => p,
    }
}

/// The module of name number `i` of construct kind `kind` (as `name_at` numbers them).
pub(super) fn owner_at(cx: &Core<'_>, kind: Kind, i: Ix) -> crate::module::ModId {
    #[cfg(feature = "modules")]
    return match kind {
        Kind::Deffacts => {
            deffacts_at(cx, i).map_or(crate::module::MAIN, |d| cx.module_of_deffacts(d))
        }
        Kind::Deftemplate => cx.module_of_template(i),
        Kind::Deffunction => cx.module_of_function(i),
        Kind::Defglobal => cx.module_of_global(i),
        Kind::Defrule => cx.rule_tag(i).module,
    };
    #[cfg(not(feature = "modules"))]
    {
        let _ = (cx, kind, i);
        crate::module::MAIN
    }
}

/// `(get-def*-list [MODULE | *])`: the names of the current module's constructs, of
/// the one named, or of every module's as `MOD::name` (modules in definition order).
fn names_list(
    cx: &mut Core<'_>,
    kind: Kind,
    a: Args,
    func: &'static str,
) -> Result<Value, EvalError> {
    // (the deffunction list takes any non-symbol for no module's name: `module_view`)
    if a.len == 1 && !matches!(cx.arg(a, 0), Value::Sym(_)) && !matches!(kind, Kind::Deffunction) {
        let mut b: TextBuf<120> = TextBuf::new();
        let _ = writeln!(
            b,
            "[ARGACCES5] Function {func} expected argument #1 to be of type symbol"
        );
        cx.write(router::WERROR, b.as_str());
        return Err(EvalError::already_reported());
    }
    let Some(view) = super::commands::module_view(cx, a, func)? else {
        return Ok(cx.multi_finish(cx.multi_begin()));
    };
    let start = cx.multi_begin();
    for m in view.modules(cx) {
        let mut p = 0;
        while let Some(name) = name_at(cx, kind, listed_at(cx, kind, p)) {
            let owner = owner_at(cx, kind, listed_at(cx, kind, p));
            p += 1;
            let Some(s) = name else { continue };
            if owner != m {
                continue;
            }
            let s = if view.all() {
                let mut b: TextBuf<256> = TextBuf::new();
                let _ = write!(b, "{}::{}", module_name(cx, m), cx.sym_text(s));
                cx.intern(b.as_str())?
            } else {
                s
            };
            cx.multi_push(Value::Sym(s))?;
        }
    }
    Ok(cx.multi_finish(start))
}

/// Module `m`'s name ("MAIN" without the feature).
fn module_name<'c>(cx: &'c Core<'_>, m: crate::module::ModId) -> &'c str {
    #[cfg(feature = "modules")]
    return cx.module_name(m);
    #[cfg(not(feature = "modules"))]
    {
        let _ = (cx, m);
        "MAIN"
    }
}

/// `(list-def* [MODULE | *])`: the names, one per line (under each module's heading
/// for `*`), and `For a total of N <what>s.`; no total when there are none (as CLIPS
/// lists deffacts and defglobals).
fn list_names(
    cx: &mut Core<'_>,
    kind: Kind,
    a: Args,
    func: &'static str,
    what: &str,
    plural: &str,
) -> Result<(), EvalError> {
    let Some(view) = super::commands::module_view(cx, a, func)? else {
        return Ok(());
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        let mut p = 0;
        while let Some(name) = name_at(cx, kind, listed_at(cx, kind, p)) {
            let owner = owner_at(cx, kind, listed_at(cx, kind, p));
            p += 1;
            let Some(s) = name else { continue };
            if owner != m {
                continue;
            }
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(s));
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
        }
    }
    if n > 0 {
        let mut b: TextBuf<64> = TextBuf::new();
        let plural = if n == 1 { "" } else { plural };
        let _ = writeln!(b, "For a total of {n} {what}{plural}.");
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(())
}

fn get_deffacts_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    names_list(cx, Kind::Deffacts, a, "get-deffacts-list")
}
fn get_deftemplate_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    names_list(cx, Kind::Deftemplate, a, "get-deftemplate-list")
}
fn get_deffunction_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    names_list(cx, Kind::Deffunction, a, "get-deffunction-list")
}
fn get_defglobal_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    names_list(cx, Kind::Defglobal, a, "get-defglobal-list")
}
fn get_defrule_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    names_list(cx, Kind::Defrule, a, "get-defrule-list")
}

/// `(get-fact-list [MODULE | *])`: the addresses of the facts the current module
/// sees, the named one sees, or all, oldest first; a name no module has is CLIPS's
/// `[ARGACCES5]`.
fn get_fact_list(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let ok = a.len == 0 || matches!(cx.arg(a, 0), Value::Sym(_));
    if !ok {
        // checked here even for a literal, so CLIPS's `()` follows (OnError)
        cx.write_error_message(EvalError::wrong_type("get-fact-list", 1, "defmodule name"));
        return Err(EvalError::already_reported());
    }
    let Some(view) = super::commands::module_view(cx, a, "get-fact-list")? else {
        return Err(EvalError::already_reported());
    };
    let start = cx.multi_begin();
    let mut f = cx.st.facts.fact_head;
    while f != NONE {
        let r = cx.fact_ref(f);
        let t = cx.facts[f as usize].tmpl;
        if view.all() || view.sees_template(cx, t) {
            cx.multi_push(Value::Fact(r))?;
        }
        f = cx.facts[f as usize].next;
    }
    Ok(cx.multi_finish(start))
}

/// `(list-deffacts [MODULE | *])`: the deffacts of the current module, of the one
/// named, or of every module under its heading (`initial-fact` is MAIN's).
fn list_deffacts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(view) = super::commands::module_view(cx, a, "list-deffacts")? else {
        return Ok(Value::Void);
    };
    let mut n = 0;
    for m in view.modules(cx) {
        view.head(cx, m);
        let mut i = 0;
        while let Some(name) = name_at(cx, Kind::Deffacts, i) {
            let d = deffacts_at(cx, i);
            i += 1;
            let Some(s) = name else { continue };
            let owner = d.map_or(crate::module::MAIN, |d| deffacts_module(cx, d));
            if owner != m {
                continue;
            }
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(b, "{}{}", view.indent(), cx.sym_text(s));
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
        }
    }
    if n > 0 {
        let mut b: TextBuf<64> = TextBuf::new();
        let _ = writeln!(b, "For a total of {n} deffacts.");
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

/// The deffacts entry name number `i` of `Kind::Deffacts` is (None: `initial-fact`).
fn deffacts_at(cx: &Core<'_>, i: Ix) -> Option<Ix> {
    let i = i + Ix::from(!cx.st.mode.initial_deffacts);
    (i > 0).then(|| i - 1)
}

/// The deffacts `name` names: `MOD::name`, or one the current module sees (its own,
/// or one of a module it imports from, as CLIPS finds them).
pub(super) fn find_deffacts(cx: &mut Core<'_>, name: SymId) -> Option<Ix> {
    #[cfg(feature = "modules")]
    {
        let (from, bare, qualified) = match cx.resolve_qualified(name) {
            Some((m, bare)) => (m, bare, true),
            None => (cx.current_module(), name, false),
        };
        (0..cx.st.pools.ndeffacts).find(|&d| {
            let owner = cx.module_of_deffacts(d);
            cx.deffacts[d as usize].name == bare
                && if qualified {
                    owner == from
                } else {
                    cx.visible_in(crate::module::class::RULES, owner, bare, from)
                }
        })
    }
    #[cfg(not(feature = "modules"))]
    (0..cx.st.pools.ndeffacts).find(|&d| cx.deffacts[d as usize].name == name)
}

fn deffacts_module(cx: &Core<'_>, d: Ix) -> crate::module::ModId {
    #[cfg(feature = "modules")]
    return cx.module_of_deffacts(d);
    #[cfg(not(feature = "modules"))]
    {
        let _ = (cx, d);
        crate::module::MAIN
    }
}

fn list_defglobals(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    list_names(cx, Kind::Defglobal, a, "list-defglobals", "defglobal", "s")?;
    Ok(Value::Void)
}

/// `(show-defglobals [MODULE | *])`: `?*name* = value` per global of the current
/// module, of the one named, or of each module under its heading, in definition
/// order.
fn show_defglobals(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if a.len == 1 && !matches!(cx.arg(a, 0), Value::Sym(_)) {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function show-defglobals expected argument #1 to be of type symbol\n",
        );
        return Err(EvalError::already_reported());
    }
    let Some(view) = super::commands::module_view(cx, a, "show-defglobals")? else {
        return Err(EvalError::already_reported());
    };
    for m in view.modules(cx) {
        view.head(cx, m);
        let mut i = 0;
        while let Some(name) = name_at(cx, Kind::Defglobal, i) {
            let owner = owner_at(cx, Kind::Defglobal, i);
            i += 1;
            let Some(s) = name else { continue };
            if owner != m {
                continue;
            }
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = write!(b, "{}?*{}* = ", view.indent(), cx.sym_text(s));
            cx.write(router::WDISPLAY, b.as_str());
            let v = cx.globals[i as usize - 1].value;
            cx.print_value(router::WDISPLAY, v, true);
            cx.write(router::WDISPLAY, "\n");
        }
    }
    Ok(Value::Void)
}

/// `(undeffacts name)` or `(undeffacts *)`: the deffacts goes; facts it asserted stay.
/// The symbol argument of a `ppdef*` command, or ARGACCES5 as CLIPS words it when the
/// value is known only at run time (a literal is checked while parsing: "symbol").
fn pp_name(cx: &mut Core<'_>, a: Args, func: &str, kind: &str) -> Option<SymId> {
    super::commands::construct_name(cx, a, func, kind)
}

/// Writes a construct's pretty-printed form, made by `pp` from its source text (none
/// when the text was not kept, as for `initial-fact`).
fn write_pp(
    cx: &mut Core<'_>,
    text: Ix,
    pp: impl FnOnce(&str, &mut dyn Write) -> core::fmt::Result,
) {
    if text == NONE {
        return;
    }
    let mut b: TextBuf<8192> = TextBuf::new();
    let _ = pp(cx.sym_text(text), &mut b);
    let _ = b.write_char('\n');
    cx.write(router::WDISPLAY, b.as_str());
}

/// `(ppdeftemplate name)`: the deftemplate as CLIPS pretty-prints it; nothing for an
/// ordered fact's implied template or `initial-fact`.
fn ppdeftemplate(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = pp_name(cx, a, "ppdeftemplate", "deftemplate") else {
        return Ok(Value::Void);
    };
    // (`MOD::name` is module MOD's own, exported or not, as in CLIPS)
    match find_pp_construct(cx, name, PpKind::Template) {
        Some(t) => {
            let text = cx.templates[t as usize].text;
            let mut module: TextBuf<64> = TextBuf::new();
            let _ = module.write_str(cx.template_module_name(t));
            write_pp(cx, text, |src, w| {
                super::pretty::write_deftemplate_echo(
                    src,
                    src.len(),
                    crate::error::EchoTail::Normal,
                    module.as_str(),
                    w,
                )
            });
        }
        None => super::commands::unable(cx, Unable::Find, "deftemplate", name),
    }
    Ok(Value::Void)
}

/// `(ppdeffacts name)`: the deffacts as CLIPS pretty-prints it.
fn ppdeffacts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = pp_name(cx, a, "ppdeffacts", "deffacts") else {
        return Ok(Value::Void);
    };
    // CLIPS's own `initial-fact` (also as `MAIN::initial-fact`) prints nothing
    let bare = match cx.sym_text(name) {
        "MAIN::initial-fact" => "initial-fact",
        t => t,
    };
    if bare == "initial-fact" && cx.st.mode.initial_deffacts {
        return Ok(Value::Void);
    }
    match find_deffacts(cx, name) {
        Some(d) => {
            let text = cx.deffacts[d as usize].text;
            let mut module: TextBuf<64> = TextBuf::new();
            let _ = module.write_str(cx.deffacts_module_name(d));
            write_pp(cx, text, |src, w| {
                super::pretty::write_deffacts_upto(src, module.as_str(), w)?;
                w.write_char(')')
            });
        }
        None => super::commands::unable(cx, Unable::Find, "deffacts", name),
    }
    Ok(Value::Void)
}

/// `(ppdeffunction name)`: the deffunction as CLIPS pretty-prints it.
fn ppdeffunction(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = pp_name(cx, a, "ppdeffunction", "deffunction") else {
        return Ok(Value::Void);
    };
    match find_pp_construct(cx, name, PpKind::Function) {
        Some(f) => {
            let text = cx.function_text(f);
            let mut module: TextBuf<64> = TextBuf::new();
            let _ = module.write_str(cx.function_module_name(f));
            write_pp(cx, text, |src, w| {
                super::pretty::write_deffunction(src, module.as_str(), w)
            });
        }
        None => super::commands::unable(cx, Unable::Find, "deffunction", name),
    }
    Ok(Value::Void)
}

/// `(ppdefglobal name)` (without `?*`..`*`): the variable as CLIPS pretty-prints it,
/// `(defglobal MODULE ?*name* = value)`.
fn ppdefglobal(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = pp_name(cx, a, "ppdefglobal", "defglobal") else {
        return Ok(Value::Void);
    };
    match find_pp_construct(cx, name, PpKind::Global) {
        Some(g) => {
            let text = cx.global_text(g);
            let mut module: TextBuf<64> = TextBuf::new();
            let _ = module.write_str(cx.global_module_name(g));
            write_pp(cx, text, |src, w| {
                super::pretty::write_defglobal(src, module.as_str(), w)
            });
        }
        None => super::commands::unable(cx, Unable::Find, "defglobal", name),
    }
    Ok(Value::Void)
}

#[derive(Clone, Copy, PartialEq)]
pub(super) enum PpKind {
    Function,
    Global,
    Template,
}

/// The deffunction or defglobal `name` names: `MODULE::x` is module MODULE's own `x`
/// (exported or not, as in CLIPS); a plain `x` is the one the current module sees.
pub(super) fn find_pp_construct(cx: &mut Core<'_>, name: SymId, kind: PpKind) -> Option<Ix> {
    let (count, class) = match kind {
        PpKind::Function => (cx.st.pools.nfuncs, crate::module::class::FUNCTION),
        PpKind::Global => (cx.st.pools.nglobals, crate::module::class::GLOBAL),
        PpKind::Template => (cx.st.pools.ntemplates, crate::module::class::TEMPLATE),
    };
    let name_of = |cx: &Core<'_>, i: Ix| match kind {
        PpKind::Function => cx.funcs[i as usize].name,
        PpKind::Global => cx.globals[i as usize].name,
        PpKind::Template => cx.templates[i as usize].name,
    };
    #[cfg(feature = "modules")]
    {
        let module_of = |cx: &Core<'_>, i: Ix| match kind {
            PpKind::Function => cx.module_of_function(i),
            PpKind::Global => cx.module_of_global(i),
            PpKind::Template => cx.module_of_template(i),
        };
        if let Some((m, bare)) = cx.resolve_qualified(name) {
            return (0..count).find(|&i| name_of(cx, i) == bare && module_of(cx, i) == m);
        }
        let from = cx.current_module();
        (0..count)
            .find(|&i| name_of(cx, i) == name && cx.visible_in(class, module_of(cx, i), name, from))
    }
    #[cfg(not(feature = "modules"))]
    {
        let _ = class;
        (0..count).find(|&i| name_of(cx, i) == name)
    }
}

fn undeffacts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(name) = super::commands::construct_name(cx, a, "undeffacts", "deffacts") else {
        return Ok(Value::Void);
    };
    // (a deffacts named `*` goes alone, as in CLIPS; the next `*` takes all)
    let star = cx.sym_text(name) == "*" && find_deffacts(cx, name).is_none();
    match cx.sym_text(name) {
        // the current module's deffacts, as in CLIPS (the others move up)
        #[cfg(feature = "modules")]
        "*" if star => {
            let current = cx.current_module();
            let n = cx.st.pools.ndeffacts as usize;
            let mut kept = 0;
            for d in 0..n {
                if cx.module_of_deffacts(d as Ix) == current {
                    continue;
                }
                cx.deffacts[kept] = cx.deffacts[d];
                if n <= cx.deffacts_module.len() {
                    cx.deffacts_module[kept] = cx.deffacts_module[d];
                }
                kept += 1;
            }
            cx.st.pools.ndeffacts = kept as Ix;
            if current == crate::module::MAIN {
                cx.st.mode.initial_deffacts = false;
            }
        }
        #[cfg(not(feature = "modules"))]
        "*" if star => {
            cx.st.pools.ndeffacts = 0;
            cx.st.mode.initial_deffacts = false;
        }
        "initial-fact" if cx.st.mode.initial_deffacts => cx.st.mode.initial_deffacts = false,
        _ => match find_deffacts(cx, name) {
            Some(d) => {
                // the later ones move up: `reset` asserts in definition order
                let n = cx.st.pools.ndeffacts as usize;
                cx.deffacts.copy_within(d as usize + 1..n, d as usize);
                // their modules move with them
                #[cfg(feature = "modules")]
                if n <= cx.deffacts_module.len() {
                    cx.deffacts_module
                        .copy_within(d as usize + 1..n, d as usize);
                }
                cx.st.pools.ndeffacts -= 1;
            }
            None => super::commands::unable(cx, Unable::Find, "deffacts", name),
        },
    }
    Ok(Value::Void)
}

/// How one kind of construct goes by its `undef...` command.
struct Undefine {
    func: &'static str,
    kind: &'static str,
    count: fn(&Core<'_>) -> Ix,
    /// The name of entry `i` (NONE: removed before).
    name: fn(&Core<'_>, Ix) -> SymId,
    /// Whether entry `i` must stay (in use); the flag: all of its kind go (`*`).
    stays: fn(&Core<'_>, Ix, bool) -> bool,
    remove: fn(&mut Core<'_>, Ix) -> Result<(), EvalError>,
    /// Its module class (`module::class`), to find a name as the current module sees it.
    class: u8,
}

/// The entry a name given to `undef...` names: `MOD::name` is module MOD's own, a
/// plain name the one the current module sees (its own or an imported one).
fn undefine_target(cx: &mut Core<'_>, how: &Undefine, name: SymId) -> Option<Ix> {
    let n = (how.count)(cx);
    #[cfg(feature = "modules")]
    {
        use crate::module::class;
        let (m, bare, qualified) = match cx.resolve_qualified(name) {
            Some((m, bare)) => (m, bare, true),
            None => (cx.current_module(), name, false),
        };
        (0..n).find(|&i| {
            if (how.name)(cx, i) != bare {
                return false;
            }
            let owner = match how.class {
                class::TEMPLATE => cx.module_of_template(i),
                class::FUNCTION => cx.module_of_function(i),
                _ => cx.module_of_global(i),
            };
            if qualified {
                owner == m
            } else {
                cx.visible_in(how.class, owner, bare, m)
            }
        })
    }
    #[cfg(not(feature = "modules"))]
    (0..n).find(|&i| (how.name)(cx, i) == name)
}

/// `(undef... name)` or `*`: what nothing uses goes, the rest stays with CLIPS's
/// `[PRNTUTIL4]`; a name not defined is `[PRNTUTIL1]`. Entries stay where they are,
/// without a name (indices compiled into other constructs stay valid), as a redefined
/// template's does.
fn undefine(cx: &mut Core<'_>, a: Args, how: &Undefine) -> Result<Value, EvalError> {
    let Some(name) = super::commands::construct_name(cx, a, how.func, how.kind) else {
        return Ok(Value::Void);
    };
    // (one named `*` goes alone, as in CLIPS; the next `*` takes all)
    let all = cx.sym_text(name) == "*" && undefine_target(cx, how, name).is_none();
    if !all {
        let Some(i) = undefine_target(cx, how, name) else {
            super::commands::unable(cx, Unable::Find, how.kind, name);
            return Ok(Value::Void);
        };
        if (how.stays)(cx, i, false) {
            // (named as given: `MAIN::x` stays `MAIN::x`)
            super::commands::unable(cx, Unable::Delete, how.kind, name);
        } else {
            forget_watched(cx, how, i);
            (how.remove)(cx, i)?;
        }
        return Ok(Value::Void);
    }
    let n = (how.count)(cx);
    for i in 0..n {
        let this = (how.name)(cx, i);
        if this == NONE {
            continue;
        }
        // `*` is the current module's constructs, as in CLIPS
        #[cfg(feature = "modules")]
        {
            use crate::module::class;
            let owner = match how.class {
                class::TEMPLATE => cx.module_of_template(i),
                class::FUNCTION => cx.module_of_function(i),
                _ => cx.module_of_global(i),
            };
            if owner != cx.current_module() {
                continue;
            }
        }
        if (how.stays)(cx, i, all) {
            super::commands::unable(cx, Unable::Delete, how.kind, this);
        } else {
            forget_watched(cx, how, i);
            (how.remove)(cx, i)?;
        }
    }
    Ok(Value::Void)
}

/// Construct `i` goes: one defined later under its name takes its items' trace flags.
fn forget_watched(cx: &mut Core<'_>, how: &Undefine, i: Ix) {
    #[cfg(feature = "extras")]
    {
        use crate::engine::watch;
        let bit = match how.kind {
            "deftemplate" => watch::FACTS,
            "deffunction" => watch::DEFFUNCTIONS,
            _ => watch::GLOBALS,
        };
        let name = (how.name)(cx, i);
        cx.watch_forget(bit, i, name);
    }
    let _ = (cx, how, i);
}

/// `(undeftemplate name)`: a template no fact and no construct uses goes; the
/// `(initial-fact)` template stays, as in CLIPS.
fn undeftemplate(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let how = Undefine {
        func: "undeftemplate",
        kind: "deftemplate",
        class: crate::module::class::TEMPLATE,
        count: |cx| cx.st.pools.ntemplates,
        name: |cx, t| cx.templates[t as usize].name,
        // `initial-fact` stays while its deffacts does (CLIPS's deffacts of it is a
        // construct using it); without that, a fact or a rule of it
        stays: |cx, t, _| {
            (t == cx.st.facts.initial_tmpl && cx.st.mode.initial_deffacts) || cx.template_in_use(t)
        },
        remove: |cx, t| {
            cx.network_writable()?;
            cx.retire_template(t);
            // (`clear` makes it again; an assert of `(initial-fact)` makes an
            // ordered template of the name)
            if t == cx.st.facts.initial_tmpl {
                cx.st.facts.initial_tmpl = NONE;
            }
            Ok(())
        },
    };
    undefine(cx, a, &how)
}

/// `(undeffunction name)`: a deffunction no other construct calls goes (with `*`,
/// calls among deffunctions do not count: they go together). While a deffunction runs
/// none goes, where CLIPS refuses only the running ones.
fn undeffunction(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let how = Undefine {
        func: "undeffunction",
        kind: "deffunction",
        class: crate::module::class::FUNCTION,
        count: |cx| cx.st.pools.nfuncs,
        name: |cx, f| cx.funcs[f as usize].name,
        stays: |cx, f, all| cx.st.eval.in_use > 0 || cx.deffunction_in_use(f, all),
        remove: |cx, f| {
            cx.funcs[f as usize].name = NONE;
            Ok(())
        },
    };
    undefine(cx, a, &how)
}

/// `(undefglobal name)` (without `?*`..`*`): a global no rule, deffunction, deffacts or
/// slot default uses goes (other globals' initial values do not count, as in CLIPS).
fn undefglobal(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let how = Undefine {
        func: "undefglobal",
        kind: "defglobal",
        class: crate::module::class::GLOBAL,
        count: |cx| cx.st.pools.nglobals,
        name: |cx, g| cx.globals[g as usize].name,
        stays: |cx, g, _| cx.global_in_use(g),
        remove: |cx, g| {
            // its multifield leaves the globals' region of scratch
            cx.set_global(g, Value::Void)?;
            cx.globals[g as usize].name = NONE;
            cx.globals[g as usize].init = NONE;
            Ok(())
        },
    };
    undefine(cx, a, &how)
}

/// `(fact-relation f)`: the template name of a fact (index or address), FALSE when
/// there is no such fact.
fn fact_relation(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cx.arg(a, 0);
    Ok(match cx.fact_arg(v) {
        Some(f) => Value::Sym(cx.templates[cx.facts[f as usize].tmpl as usize].name),
        None => {
            if !super::facts::is_fact_or_index(v) {
                super::facts::report_not_a_fact(cx, "fact-relation");
            }
            Value::Sym(SYM_FALSE)
        }
    })
}

/// `(fact-slot-names f)`: the slot names of a fact's template, `(implied)` for an
/// ordered fact; FALSE (with CLIPS's message for an index) when there is no such fact.
fn fact_slot_names(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fv = cx.arg(a, 0);
    let Some(f) = cx.fact_arg(fv) else {
        match fv {
            Value::Int(n @ 0..) => {
                cx.write_error_message(EvalError::new(EvalErrorKind::NoSuchFact(n)))
            }
            Value::Fact(_) => {}
            _ => super::facts::report_not_a_fact(cx, "fact-slot-names"),
        }
        return Ok(Value::Sym(SYM_FALSE));
    };
    let tm = cx.templates[cx.facts[f as usize].tmpl as usize];
    let start = cx.multi_begin();
    if cx.facts[f as usize].tmpl == cx.st.facts.initial_tmpl {
        // `(initial-fact)`: a template without slots in CLIPS, not an ordered fact
    } else if tm.implied {
        let implied = cx.intern("implied")?;
        cx.multi_push(Value::Sym(implied))?;
    } else {
        for s in 0..tm.nslots {
            let name = cx.slots[(tm.first_slot + s) as usize].name;
            cx.multi_push(Value::Sym(name))?;
        }
    }
    Ok(cx.multi_finish(start))
}

/// `(ppfact fact [logical-name [ignore-defaults]])`: the fact as CLIPS pretty-prints it,
/// each slot of a template fact on a line of its own; with ignore-defaults (any value but
/// FALSE) the slots that hold their static default are left out. Logical name `nil`
/// prints nothing, as `stdin` does.
fn ppfact(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fv = cx.arg(a, 0);
    let Some(f) = cx.fact_arg(fv) else {
        return match fv {
            // a retracted fact's address prints nothing
            Value::Fact(_) => Ok(Value::Void),
            Value::Int(n @ 0..) => {
                cx.write_error_message(EvalError::new(EvalErrorKind::NoSuchFact(n)));
                Ok(Value::Void)
            }
            // (CLIPS's message; the actions go on)
            _ => {
                super::facts::report_not_a_fact(cx, "ppfact");
                Ok(Value::Void)
            }
        };
    };
    let to = if a.len > 1 {
        match cx.arg(a, 1) {
            Value::Multi(_) => {
                cx.write(
                    router::WERROR,
                    "[IOFUN1] Illegal logical name used for ppfact function.\n",
                );
                return Err(EvalError::already_reported());
            }
            Value::Sym(s) | Value::Str(s) if cx.sym_text(s) == "nil" => return Ok(Value::Void),
            name => match super::commands::resolve_router(cx, name, "ppfact")? {
                Some(to) => to,
                None => return Ok(Value::Void),
            },
        }
    } else {
        super::commands::Routed::Engine(router::STDOUT)
    };
    let ignore_defaults = a.len > 2 && cx.arg(a, 2) != Value::Sym(SYM_FALSE);
    let (num, tmpl) = (cx.facts[f as usize].num, cx.facts[f as usize].tmpl);
    let t = cx.templates[tmpl as usize];
    if t.implied || t.nslots == 0 {
        let (view, host) = cx.split();
        let mut w = RouterWriter {
            host,
            router: to.name(),
        };
        let _ = view.write_fact(&mut w, f);
        let _ = w.write_char('\n');
        return Ok(Value::Void);
    }
    {
        let (view, host) = cx.split();
        let _ = write!(
            RouterWriter {
                host,
                router: to.name()
            },
            "({}",
            view.sym(t.name)
        );
    }
    let mut printed = false;
    for s in 0..t.nslots {
        if ignore_defaults && holds_static_default(cx, f, s)? {
            continue;
        }
        // a default's evaluation may have retracted the fact
        let fact = cx.facts[f as usize];
        if fact.num != num || fact.state != FactState::Live {
            break;
        }
        let cell = slot_cell(cx, f, s);
        let name = cx.slots[(t.first_slot + s) as usize].name;
        let (view, host) = cx.split();
        let mut w = RouterWriter {
            host,
            router: to.name(),
        };
        let _ = w.write_str(if printed { "\n   (" } else { " \n   (" });
        printed = true;
        let _ = w.write_str(view.sym(name));
        let n = match view.values[cell] {
            Value::Multi(m) => m.len as usize,
            _ => 0,
        };
        let values = if n == 0 && !view.values[cell].is_multi() {
            cell..cell + 1
        } else {
            cell + 1..cell + 1 + n
        };
        for c in values {
            let _ = w.write_char(' ');
            let _ = view.write_value(&mut w, view.values[c], true);
        }
        let _ = w.write_str(if s + 1 < t.nslots { ") " } else { ")" });
    }
    cx.write(to.name(), ")\n");
    Ok(Value::Void)
}

/// The value cell of slot `slot` of fact `f` (a multislot's `Multi` header).
fn slot_cell(cx: &Core<'_>, f: Ix, slot: Ix) -> usize {
    let mut c = cx.facts[f as usize].start as usize;
    for _ in 0..slot {
        c += match cx.values[c] {
            Value::Multi(m) => 1 + m.len as usize,
            _ => 1,
        };
    }
    c
}

/// Whether slot `slot` of fact `f` holds the value its template gives it when an assert
/// leaves it out: never for a dynamic default or a slot that must be given.
fn holds_static_default(cx: &mut Core<'_>, f: Ix, slot: Ix) -> Result<bool, EvalError> {
    let tmpl = cx.facts[f as usize].tmpl;
    if matches!(
        cx.slot_def(tmpl, slot).default_kind,
        DefaultKind::Dynamic | DefaultKind::Required
    ) {
        return Ok(false);
    }
    let mark = cx.st.frame.scratch_top;
    let default = cx.default_value(tmpl, slot)?;
    let cell = slot_cell(cx, f, slot);
    let same = match (default, cx.values[cell]) {
        (Value::Multi(d), Value::Multi(m)) => {
            d.len == m.len
                && (0..m.len as usize).all(|k| cx.mf_item(d, k) == cx.values[cell + 1 + k])
        }
        (d, v) => d == v,
    };
    cx.st.frame.scratch_top = mark;
    Ok(same)
}

/// The text of the next `genN` symbol.
fn next_gensym(cx: &mut Core<'_>) -> TextBuf<24> {
    let mut b: TextBuf<24> = TextBuf::new();
    let _ = write!(b, "gen{}", cx.st.eval.gensym_next);
    cx.st.eval.gensym_next = cx.st.eval.gensym_next.wrapping_add(1);
    b
}

/// `(type x)`: the CLIPS type name of a value, as CLIPS 6.30 names it. An instance-name
/// literal `[x]` (a symbol here) is `INITIAL-OBJECT` for COOL's `initial-object`, else
/// CLIPS's `[INSFUN2]`, an error that halts: there are no other instances. A void
/// value gets CLIPS's message and FALSE.
fn type_of(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = match cx.arg(a, 0) {
        Value::Int(_) => "INTEGER",
        Value::Float(_) => "FLOAT",
        Value::Str(_) => "STRING",
        Value::Fact(crate::value::FactRef::DUMMY_INSTANCE) => {
            // CLIPS's `<Dummy Instance>` is no instance: an error that halts
            cx.write(
                router::WERROR,
                "[INSFUN4] Invalid instance-address in function type.\n",
            );
            return Err(EvalError::already_reported());
        }
        Value::Fact(_) => "FACT-ADDRESS",
        Value::Multi(_) => "MULTIFIELD",
        Value::Sym(s) => {
            let text = cx.sym_text(s);
            match crate::value::instance_name_body(text) {
                // COOL's `initial-object`, CLIPS's one instance without classes
                Some("initial-object" | "MAIN::initial-object") => "INITIAL-OBJECT",
                Some(inst) => {
                    let mut b: TextBuf<256> = TextBuf::new();
                    let _ = writeln!(b, "[INSFUN2] No such instance {inst} in function type.");
                    cx.write(router::WERROR, b.as_str());
                    // an error that halts; FALSE at the prompt (`on_error`)
                    return Err(EvalError::already_reported());
                }
                None => "SYMBOL",
            }
        }
        Value::Void | Value::BoundVoid => {
            cx.write(
                router::WERROR,
                "[INSCOM1] Undefined type in function type.\n",
            );
            return Ok(Value::Sym(SYM_FALSE));
        }
    };
    Ok(Value::Sym(cx.intern(name)?))
}

/// `(gensym)`: `gen1`, `gen2`, ... whether or not the symbol is in use.
fn gensym(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let b = next_gensym(cx);
    Ok(Value::Sym(cx.intern(b.as_str())?))
}

/// `(gensym*)`: the next `genN` not yet in the symbol table.
fn gensym_star(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    loop {
        let b = next_gensym(cx);
        if cx.find_sym(b.as_str()).is_none() {
            return Ok(Value::Sym(cx.intern(b.as_str())?));
        }
    }
}
