//! Commands: reset, clear, run, facts, agenda, watch/unwatch, printout, halt, exit,
//! refresh-agenda, set-strategy, list-defrules, ppdefrule, undefrule, matches, load,
//! batch, save-facts, load-facts.

use super::files::{FileItems, FILE_BUF};
use super::{Args, Builtin, ANY, SYM_CRLF, SYM_FALSE, SYM_NIL, SYM_TRUE};
use crate::engine::{watch, Core};
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::value::{TextBuf, Value, NONE};
use core::fmt::Write;

pub const FUNCS: &[Builtin] = &[
    Builtin::eager("reset", 0, 0, reset),
    Builtin::eager("clear", 0, 0, clear),
    Builtin::eager("run", 0, 1, run),
    Builtin::eager("facts", 0, 4, facts),
    Builtin::eager("agenda", 0, 1, agenda),
    Builtin::eager("watch", 1, ANY, watch_),
    Builtin::eager("unwatch", 1, ANY, unwatch),
    Builtin::eager("printout", 1, ANY, printout),
    Builtin::eager("halt", 0, 0, halt),
    Builtin::eager("exit", 0, 1, exit),
    Builtin::eager("refresh-agenda", 0, 1, refresh_agenda),
    Builtin::eager("set-strategy", 1, 1, set_strategy),
    Builtin::eager("get-strategy", 0, 0, get_strategy),
    Builtin::eager("list-defrules", 0, 1, list_defrules),
    Builtin::eager("ppdefrule", 1, 1, ppdefrule),
    Builtin::eager("undefrule", 1, 1, undefrule),
    Builtin::eager("matches", 1, 2, matches),
    Builtin::eager("load", 1, 1, load),
    Builtin::eager("load*", 1, 1, load_quiet),
    Builtin::eager("batch", 1, 1, batch),
    Builtin::eager("batch*", 1, 1, batch_quiet),
    Builtin::eager("save-facts", 1, ANY, save_facts),
    Builtin::eager("load-facts", 1, 1, load_facts),
    Builtin::eager("time", 0, 0, time),
    Builtin::eager("list-deftemplates", 0, 1, list_deftemplates),
    Builtin::eager("list-deffunctions", 0, 1, list_deffunctions),
    Builtin::eager("get-fact-duplication", 0, 0, get_fact_dup),
];

fn reset(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.reset()?;
    Ok(Value::Void)
}

fn clear(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.clear()?;
    Ok(Value::Void)
}

fn run(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let limit = if a.len > 0 {
        cx.arg_int(a, 0, "run")?
    } else {
        -1
    };
    if limit == 0 {
        cx.write(router::STDOUT, "rule firing limit reached\n");
        return Ok(Value::Void);
    }
    let fired = cx.run(limit)?;
    // `(watch statistics)`: the first line CLIPS prints after a run. The run-time and
    // mean-count lines are not kept (no clock or fact averages are tracked).
    if cx.st.watch & watch::STATISTICS != 0 {
        let mut b: TextBuf<48> = TextBuf::new();
        let _ = writeln!(b, "{fired} rules fired");
        cx.write(router::STDOUT, b.as_str());
    }
    Ok(Value::Void)
}

fn facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut nums = [-1i64; 3];
    let mut k = 0;
    for i in 0..a.len as usize {
        if let Value::Int(n) = cx.arg(a, i) {
            if k < 3 {
                nums[k] = n;
                k += 1;
            }
        }
    }
    let start = if k > 0 { nums[0] } else { 0 };
    cx.list_facts(start, nums[1], nums[2]);
    Ok(Value::Void)
}

fn agenda(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.list_agenda();
    Ok(Value::Void)
}

fn watch_bits(cx: &Core<'_>, a: Args) -> Result<u8, EvalError> {
    let mut bits = 0;
    for i in 0..a.len as usize {
        let s = cx.arg_lexeme(a, i, "watch")?;
        bits |= match cx.sym_text(s) {
            "facts" => watch::FACTS,
            "rules" => watch::RULES,
            "activations" => watch::ACTIVATIONS,
            "compilations" => watch::COMPILATIONS,
            "statistics" => watch::STATISTICS,
            "all" => 0xFF,
            // other watch items (focus, globals, deffunctions, ...) are accepted silently
            _ => 0,
        };
    }
    Ok(bits)
}

fn watch_(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let b = watch_bits(cx, a)?;
    cx.st.watch |= b;
    Ok(Value::Void)
}

fn unwatch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let b = watch_bits(cx, a)?;
    cx.st.watch &= !b;
    Ok(Value::Void)
}

fn printout(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if cx.arg(a, 0) == Value::Sym(SYM_NIL) {
        return Ok(Value::Void);
    }
    let routed = match resolve_router(cx, cx.arg(a, 0)) {
        Ok(Some(r)) => r,
        Ok(None) => return Ok(Value::Void),
        // CLIPS's printout reports the name and carries on with nothing printed
        Err(_) => return Ok(Value::Void),
    };
    let mut b: TextBuf<1024> = TextBuf::new();
    for i in 1..a.len as usize {
        let v = cx.arg(a, i);
        match v {
            Value::Sym(s) if s == SYM_CRLF => {
                let _ = b.write_char('\n');
            }
            Value::Sym(s) if cx.sym_text(s) == "tab" => {
                let _ = b.write_char('\t');
            }
            _ => {
                if cx.write_printout(&mut b, v).is_err() || b.len() > 900 {
                    cx.write(routed, b.as_str());
                    b.clear();
                    let _ = cx.write_printout(&mut b, v);
                }
            }
        }
    }
    cx.write(routed, b.as_str());
    Ok(Value::Void)
}

/// Maps a logical name to a router constant (unknown names go to stdout).
/// The engine router for a CLIPS logical name: `Some(router)`, or `None` for `stdin`
/// (output to it is dropped). Any other name is `[ROUTER1]` (printed here), as in the
/// CLIPS command line, which has no other routers.
pub(super) fn resolve_router(
    cx: &mut Core<'_>,
    name: Value,
) -> Result<Option<&'static str>, EvalError> {
    if let Value::Sym(s) | Value::Str(s) = name {
        match cx.sym_text(s) {
            "t" | "stdout" | "wclips" | "wdialog" => return Ok(Some(router::STDOUT)),
            "wdisplay" => return Ok(Some(router::WDISPLAY)),
            "wtrace" => return Ok(Some(router::WTRACE)),
            "werror" => return Ok(Some(router::WERROR)),
            "wwarning" => return Ok(Some(router::WWARNING)),
            "stdin" => return Ok(None),
            _ => {}
        }
    }
    cx.write(router::WERROR, "[ROUTER1] Logical name ");
    cx.print_value(router::WERROR, name, false);
    cx.write(router::WERROR, " was not recognized by any routers\n");
    Err(EvalError::new(EvalErrorKind::Reported))
}

fn halt(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.st.halt = true;
    Ok(Value::Void)
}

fn exit(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.st.exit = true;
    cx.st.halt = true;
    Err(EvalError::new(EvalErrorKind::Exit))
}

fn refresh_agenda(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    cx.reorder_agenda();
    Ok(Value::Void)
}

fn set_strategy(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = cx.arg_lexeme(a, 0, "set-strategy")?;
    if cx.sym_text(s) != "depth" {
        return Err(EvalError::other("only the depth strategy is supported"));
    }
    Ok(Value::Sym(cx.intern("depth")?))
}

fn get_strategy(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(cx.intern("depth")?))
}

fn list_defrules(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let mut n = 0;
    for r in 0..cx.st.nrules {
        let rule = cx.rules[r as usize];
        if rule.deleted || (r > 0 && cx.rules[r as usize - 1].next_disjunct == r) {
            continue;
        }
        let mut b: TextBuf<128> = TextBuf::new();
        let _ = writeln!(b, "{}", cx.sym_text(rule.name));
        cx.write(router::WDISPLAY, b.as_str());
        n += 1;
    }
    if n > 0 {
        let mut b: TextBuf<64> = TextBuf::new();
        let _ = writeln!(
            b,
            "For a total of {n} defrule{}.",
            if n == 1 { "" } else { "s" }
        );
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

fn find_rule(cx: &Core<'_>, name: u16) -> Option<u16> {
    (0..cx.st.nrules).find(|&r| cx.rules[r as usize].name == name && !cx.rules[r as usize].deleted)
}

fn ppdefrule(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = cx.arg_lexeme(a, 0, "ppdefrule")?;
    let r = find_rule(cx, name).ok_or(EvalError::other("no such defrule"))?;
    let text = cx.rules[r as usize].text;
    if text != NONE {
        let mut b: TextBuf<4096> = TextBuf::new();
        let _ = b.write_str(cx.sym_text(text));
        let _ = b.write_char('\n');
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(Value::Void)
}

fn undefrule(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = cx.arg_lexeme(a, 0, "undefrule")?;
    match find_rule(cx, name) {
        Some(r) => {
            cx.remove_rule(r);
            Ok(Value::Void)
        }
        None => {
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(
                b,
                "[PRNTUTIL1] Unable to find defrule {}.",
                cx.sym_text(name)
            );
            cx.write(router::WERROR, b.as_str());
            Ok(Value::Void)
        }
    }
}

/// `(matches rule)`: prints the partial matches per join (a compact form of CLIPS's
/// listing) and the activations.
fn matches(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let name = cx.arg_lexeme(a, 0, "matches")?;
    let r = find_rule(cx, name).ok_or(EvalError::other("no such defrule"))?;
    let rule = cx.rules[r as usize];
    let mut path = [NONE; crate::rete::MAX_PATTERNS];
    let mut n = 0;
    let mut j = rule.terminal;
    while j != NONE && j != 0 && n < path.len() {
        path[n] = j;
        n += 1;
        j = cx.joins[j as usize].parent;
    }
    path[..n].reverse();
    for (i, &j) in path[..n].iter().enumerate() {
        let i = i + 1;
        let mut b: TextBuf<64> = TextBuf::new();
        let _ = writeln!(b, "Partial matches for CEs 1 - {i}");
        cx.write(router::WDISPLAY, b.as_str());
        let mut t = cx.joins[j as usize].mem;
        let mut n = 0;
        while t != NONE {
            let mut b: TextBuf<512> = TextBuf::new();
            let _ = cx.write_basis(&mut b, t);
            let _ = b.write_char('\n');
            cx.write(router::WDISPLAY, b.as_str());
            n += 1;
            t = cx.tokens[t as usize].mem_next;
        }
        if n == 0 {
            cx.write(router::WDISPLAY, " None\n");
        }
    }
    Ok(Value::Void)
}

/// The file-name argument of a file function, copied out of the symbol table.
fn path_arg(cx: &Core<'_>, a: Args, func: &'static str) -> Result<TextBuf<256>, EvalError> {
    let p = cx.arg_lexeme(a, 0, func)?;
    let mut path: TextBuf<256> = TextBuf::new();
    let _ = path.write_str(cx.sym_text(p));
    Ok(path)
}

/// `load`/`load*`: defines the constructs of a file, streamed item by item; a bad
/// construct is reported and the rest still loaded (as CLIPS does), the result is then
/// FALSE.
fn load_impl(cx: &mut Core<'_>, a: Args, quiet: bool) -> Result<Value, EvalError> {
    let func = if quiet { "load*" } else { "load" };
    let path = path_arg(cx, a, func)?;
    let mut buf = [0u8; FILE_BUF];
    let mut file = FileItems::new(path.as_str(), &mut buf);
    if file.open(cx).is_err() {
        cx.report_unopened_file(func, path.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    let mut ok = true;
    let mut progress = false;
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
        if let Err(e) = cx.load_items(item.text, !quiet, &mut progress) {
            cx.st.line_base = item.line_base;
            cx.report_load_error(path.as_str(), item.text, &e);
            cx.st.line_base = 0;
            ok = false;
        }
    }
    if progress {
        cx.write(router::STDOUT, "\n");
    }
    Ok(Value::Sym(if ok { SYM_TRUE } else { SYM_FALSE }))
}

fn load(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    load_impl(cx, a, false)
}
fn load_quiet(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    load_impl(cx, a, true)
}

/// `batch`: CLIPS makes the file its next input source, so its commands run (echoed,
/// with prompts) after the current command has finished and printed its TRUE. The path
/// is remembered here and run by the command loop (`Core::run_pending_batch`).
fn batch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
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
    cx.st.pending_batch.clear();
    let _ = cx.st.pending_batch.write_str(path.as_str());
    Ok(Value::Sym(SYM_TRUE))
}

/// `batch*`: runs the file's commands at once, without prompts, echo or results.
fn batch_quiet(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, "batch")?;
    let ok = cx.batch_file_stream(path.as_str(), false)?;
    Ok(Value::Sym(if ok { SYM_TRUE } else { SYM_FALSE }))
}

fn save_facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let p = cx.arg_lexeme(a, 0, "save-facts")?;
    let mut path: TextBuf<256> = TextBuf::new();
    let _ = path.write_str(cx.sym_text(p));
    let mut first = true;
    let mut f = cx.st.fact_head;
    while f != NONE {
        let mut b: TextBuf<2048> = TextBuf::new();
        {
            let (view, _) = cx.split();
            let _ = view.write_fact(&mut b, f);
        }
        let _ = b.write_char('\n');
        if cx
            .host
            .write_file(path.as_str(), b.as_str().as_bytes(), !first)
            .is_err()
        {
            return Ok(Value::Sym(SYM_FALSE));
        }
        first = false;
        f = cx.facts[f as usize].next;
    }
    if first && cx.host.write_file(path.as_str(), b"", false).is_err() {
        return Ok(Value::Sym(SYM_FALSE));
    }
    Ok(Value::Sym(SYM_TRUE))
}

fn load_facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, "load-facts")?;
    let mut buf = [0u8; FILE_BUF];
    let mut file = FileItems::new(path.as_str(), &mut buf);
    if file.open(cx).is_err() {
        cx.report_unopened_file("load-facts", path.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    loop {
        match file.next_item(cx) {
            Ok(Some(item)) => cx.load_facts_text(item.text)?,
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

fn list_deftemplates(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let mut n = 0;
    for t in 0..cx.st.ntemplates {
        let tm = cx.templates[t as usize];
        if tm.implied {
            continue;
        }
        let mut b: TextBuf<128> = TextBuf::new();
        let _ = writeln!(b, "{}", cx.sym_text(tm.name));
        cx.write(router::WDISPLAY, b.as_str());
        n += 1;
    }
    let mut b: TextBuf<64> = TextBuf::new();
    let _ = writeln!(
        b,
        "For a total of {n} deftemplate{}.",
        if n == 1 { "" } else { "s" }
    );
    cx.write(router::WDISPLAY, b.as_str());
    Ok(Value::Void)
}

fn list_deffunctions(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let n = cx.st.nfuncs;
    for f in 0..n {
        let mut b: TextBuf<128> = TextBuf::new();
        let _ = writeln!(b, "{}", cx.sym_text(cx.funcs[f as usize].name));
        cx.write(router::WDISPLAY, b.as_str());
    }
    let mut b: TextBuf<64> = TextBuf::new();
    let _ = writeln!(
        b,
        "For a total of {n} deffunction{}.",
        if n == 1 { "" } else { "s" }
    );
    cx.write(router::WDISPLAY, b.as_str());
    Ok(Value::Void)
}

fn get_fact_dup(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Sym(SYM_FALSE))
}
