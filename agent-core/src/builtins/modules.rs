//! Module and focus commands (agent-core feature `modules`, see `crate::module`):
//! `focus`, `get-focus`, `get-focus-stack`, `list-focus-stack`, `pop-focus`,
//! `clear-focus-stack`, `set-current-module`, `get-current-module`, `list-defmodules`,
//! `get-defmodule-list`, `ppdefmodule`, and the module of a construct
//! (`deftemplate-module`, `deffacts-module`, `defrule-module`, `deffunction-module`,
//! `defglobal-module`), as CLIPS 6.30 prints them.
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "modules"), allow(dead_code, unused_imports))]

use super::commands::Unable;
use super::describe::ArgType::{Any, Symbol};
use super::{Args, Builtin, ANY, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::{TextBuf, Value};
use core::fmt::Write;

#[cfg(feature = "modules")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("focus", 1, ANY, focus).on_error(super::describe::OnError::False).args(&[], super::describe::ArgType::Symbol),
    Builtin::eager("get-focus", 0, 0, get_focus),
    Builtin::eager("get-focus-stack", 0, 0, get_focus_stack),
    Builtin::eager("list-focus-stack", 0, 0, list_focus_stack).returns(super::describe::Returns::Void),
    Builtin::eager("pop-focus", 0, 0, pop_focus),
    Builtin::eager("clear-focus-stack", 0, 0, clear_focus_stack).returns(super::describe::Returns::Void),
    Builtin::eager("set-current-module", 1, 1, set_current_module).args(&[Symbol], Any),
    Builtin::eager("get-current-module", 0, 0, get_current_module),
    Builtin::eager("list-defmodules", 0, 0, list_defmodules).returns(super::describe::Returns::Void),
    Builtin::eager("get-defmodule-list", 0, 0, get_defmodule_list),
    Builtin::eager("ppdefmodule", 1, 1, ppdefmodule).args(&[Symbol], Any).returns(super::describe::Returns::Void),
    Builtin::eager("deftemplate-module", 1, 1, deftemplate_module).args(&[Symbol], Any),
    Builtin::eager("deffacts-module", 1, 1, deffacts_module).args(&[Symbol], Any),
    Builtin::eager("defrule-module", 1, 1, defrule_module).args(&[Symbol], Any),
    Builtin::eager("deffunction-module", 1, 1, deffunction_module).args(&[Symbol], Any),
    Builtin::eager("defglobal-module", 1, 1, defglobal_module).args(&[Symbol], Any),
];
#[cfg(not(feature = "modules"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

#[cfg(feature = "modules")]
use crate::module::ModId;

/// The module argument `i` names, or its `[PRNTUTIL1]` message printed.
#[cfg(feature = "modules")]
fn module_arg(
    cx: &mut Core<'_>,
    a: Args,
    i: usize,
    func: &'static str,
) -> Result<Option<ModId>, EvalError> {
    let s = cx.arg_symbol(a, i, func)?;
    match cx.find_module(cx.sym_text(s)) {
        Some(m) => Ok(Some(m)),
        None => {
            super::commands::unable(cx, Unable::Find, "defmodule", s);
            Ok(None)
        }
    }
}

/// The symbol naming module `m`.
#[cfg(feature = "modules")]
fn module_sym(cx: &mut Core<'_>, m: ModId) -> Result<Value, EvalError> {
    let mut b: TextBuf<256> = TextBuf::new();
    let _ = b.write_str(cx.module_name(m));
    Ok(Value::Sym(cx.intern(b.as_str())?))
}

/// `(focus M...)`: pushes the modules, the last first (the first ends on top).
#[cfg(feature = "modules")]
fn focus(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    // every name is checked before anything is pushed
    for i in 0..a.len as usize {
        if module_arg(cx, a, i, "focus")?.is_none() {
            return Ok(Value::Sym(SYM_FALSE));
        }
    }
    for i in (0..a.len as usize).rev() {
        if let Some(m) = module_arg(cx, a, i, "focus")? {
            cx.push_focus(m)?;
        }
    }
    Ok(Value::Sym(SYM_TRUE))
}

#[cfg(feature = "modules")]
fn get_focus(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    match cx.focus_top() {
        Some(m) => module_sym(cx, m),
        None => Ok(Value::Sym(SYM_FALSE)),
    }
}

/// The focus stack, top first.
#[cfg(feature = "modules")]
fn get_focus_stack(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    for k in (0..cx.st.modules.depth as usize).rev() {
        let v = module_sym(cx, cx.focus_entry(k))?;
        cx.multi_push(v)?;
    }
    Ok(cx.multi_finish(start))
}

#[cfg(feature = "modules")]
fn list_focus_stack(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    for k in (0..cx.st.modules.depth as usize).rev() {
        let mut b: TextBuf<256> = TextBuf::new();
        let _ = writeln!(b, "{}", cx.module_name(cx.focus_entry(k)));
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

#[cfg(feature = "modules")]
fn pop_focus(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    match cx.pop_focus() {
        Some(m) => module_sym(cx, m),
        None => Ok(Value::Sym(SYM_FALSE)),
    }
}

#[cfg(feature = "modules")]
fn clear_focus_stack(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.clear_focus();
    Ok(Value::Void)
}

/// `(set-current-module M)`: the module before (unchanged for an unknown one). A
/// computed argument that is no symbol is an error whose value is the current module.
#[cfg(feature = "modules")]
fn set_current_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let old = cx.current_module();
    if !matches!(cx.arg(a, 0), Value::Sym(_)) {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function set-current-module expected argument #1 to be of type symbol\n",
        );
        let current = module_sym(cx, old)?;
        cx.set_error_fallback(current, None);
        return Err(EvalError::already_reported());
    }
    if let Some(m) = module_arg(cx, a, 0, "set-current-module")? {
        cx.set_current_module(m);
    }
    module_sym(cx, old)
}

#[cfg(feature = "modules")]
fn get_current_module(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    module_sym(cx, cx.current_module())
}

#[cfg(feature = "modules")]
fn list_defmodules(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let n = cx.st.modules.nmodules;
    for m in 0..n {
        let mut b: TextBuf<256> = TextBuf::new();
        let _ = writeln!(b, "{}", cx.module_name(m as ModId));
        cx.write(router::WDISPLAY, b.as_str());
    }
    super::commands::write_total(cx, n as usize, "defmodule");
    Ok(Value::Void)
}

#[cfg(feature = "modules")]
fn get_defmodule_list(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    for m in 0..cx.st.modules.nmodules {
        let v = module_sym(cx, m as ModId)?;
        cx.multi_push(v)?;
    }
    Ok(cx.multi_finish(start))
}

/// `(ppdefmodule M)`: `(defmodule M` and each port specification on a line of its
/// own, tokens one space apart (`(defmodule MAIN)` for the MAIN made at start-up).
#[cfg(feature = "modules")]
fn ppdefmodule(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if super::commands::construct_name(cx, a, "ppdefmodule", "defmodule").is_none() {
        return Ok(Value::Void);
    }
    let Some(m) = module_arg(cx, a, 0, "ppdefmodule")? else {
        return Ok(Value::Void);
    };
    // the MAIN made at start-up has no text: nothing is printed
    let text = cx.module_entry(m).text;
    if text != crate::value::NONE {
        let mut b: TextBuf<4096> = TextBuf::new();
        let _ = write_defmodule(cx.sym_text(text), &mut b);
        let _ = b.write_char('\n');
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

/// A construct class whose module `*-module` names.
#[cfg(feature = "modules")]
#[derive(Clone, Copy)]
enum Construct {
    Template,
    Deffacts,
    Rule,
    Function,
    Global,
}

/// `(deftemplate-module NAME)` and the others: the module that defines the construct
/// NAME names for the current module (its own or an imported one), FALSE with
/// `[PRNTUTIL1]` for none. As in CLIPS, `MOD::...` is module MOD whatever follows the
/// `::` (FALSE for an unknown MOD).
#[cfg(feature = "modules")]
fn construct_module(
    cx: &mut Core<'_>,
    a: Args,
    func: &str,
    kind: &str,
    class: Construct,
) -> Result<Value, EvalError> {
    let Some(name) = super::commands::construct_name(cx, a, func, kind) else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    let text = cx.sym_text(name);
    let owner = match crate::module::qualifier_end(text) {
        Some(i) if i > 0 => {
            let m = text.get(..i).unwrap_or("");
            cx.find_module(m)
        }
        _ => {
            let from = cx.current_module();
            match class {
                Construct::Template => cx.find_template(name).map(|t| cx.module_of_template(t)),
                Construct::Deffacts => {
                    if text == "initial-fact" && cx.st.mode.initial_deffacts {
                        let main = crate::module::MAIN;
                        let seen = cx.visible_in(crate::module::class::RULES, main, name, from);
                        seen.then_some(main)
                    } else {
                        super::extras::find_deffacts(cx, name).map(|d| cx.module_of_deffacts(d))
                    }
                }
                Construct::Rule => {
                    super::commands::find_rule(cx, name).map(|r| cx.rule_tag(r).module)
                }
                Construct::Function => cx
                    .find_function(name, from)
                    .map(|f| cx.module_of_function(f)),
                Construct::Global => cx.find_global(name).map(|g| cx.module_of_global(g)),
            }
        }
    };
    match owner {
        Some(m) => module_sym(cx, m),
        None => {
            super::commands::unable(cx, Unable::Find, kind, name);
            Ok(Value::Sym(SYM_FALSE))
        }
    }
}

#[cfg(feature = "modules")]
fn deftemplate_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    construct_module(
        cx,
        a,
        "deftemplate-module",
        "deftemplate",
        Construct::Template,
    )
}

#[cfg(feature = "modules")]
fn deffacts_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    construct_module(cx, a, "deffacts-module", "deffacts", Construct::Deffacts)
}

#[cfg(feature = "modules")]
fn defrule_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    construct_module(cx, a, "defrule-module", "defrule", Construct::Rule)
}

#[cfg(feature = "modules")]
fn deffunction_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    construct_module(
        cx,
        a,
        "deffunction-module",
        "deffunction",
        Construct::Function,
    )
}

#[cfg(feature = "modules")]
fn defglobal_module(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    construct_module(cx, a, "defglobal-module", "defglobal", Construct::Global)
}

/// The pretty-printed form of the defmodule in `src` that byte `at` is in, up to the
/// end of `src` (what CLIPS shows after `ERROR:` for a defmodule it rejected).
pub fn write_defmodule_at(src: &str, at: usize, w: &mut dyn Write) -> core::fmt::Result {
    let start = src
        .get(..at)
        .and_then(|s| s.rfind("(defmodule"))
        .unwrap_or(0);
    write_defmodule(src.get(start..).unwrap_or(""), w)
}

/// The pretty-printed form of the defmodule whose source is `src`.
fn write_defmodule(src: &str, w: &mut dyn Write) -> core::fmt::Result {
    use crate::lexer::{Lexer, Tok};
    let mut lx = Lexer::new(src);
    let mut depth = 0u32;
    let mut first_in_list = false;
    // tokens of the defmodule itself: its keyword, name and comment share its line,
    // anything else (only in text CLIPS rejected) goes on a line of its own
    let mut top = 0u32;
    loop {
        let t = lx.next_token();
        let text = src.get(t.start..t.end).unwrap_or("");
        match t.tok {
            Tok::Eof | Tok::Bad => return Ok(()),
            Tok::LParen => {
                match depth {
                    0 => {}
                    1 => w.write_str("\n   ")?,
                    _ => w.write_char(' ')?,
                }
                w.write_char('(')?;
                depth += 1;
                first_in_list = true;
                continue;
            }
            Tok::RParen => {
                w.write_char(')')?;
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    return Ok(());
                }
            }
            _ => {
                if depth == 1 {
                    top += 1;
                    let comment = top == 3 && matches!(t.tok, Tok::Str(_));
                    if top > 2 && !comment {
                        w.write_str("\n  ")?;
                    }
                }
                if !first_in_list {
                    w.write_char(' ')?;
                }
                w.write_str(text)?;
            }
        }
        first_in_list = false;
    }
}
