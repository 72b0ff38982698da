//! `eval` and `build`: CLIPS source given as a string, parsed and run at run time;
//! and the table of every builtin that parses text at run time (these two, `load`,
//! `load*`, `batch`, `batch*`, `load-facts`): without the feature `parser` (the agent
//! image, whose rule base is compiled ahead of time) the table is empty, nothing
//! reaches the parser, and the linker leaves it out.
#![cfg_attr(not(feature = "parser"), allow(dead_code))]

#[cfg(feature = "parser")]
use super::describe::OnError;
use super::{Args, Builtin, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::eval::Callee;
use crate::host::router;
use crate::lexer::Tok;
use crate::parser::{Item, Parser};
use crate::value::{Ix, Value};
use core::fmt::Write;

#[cfg(feature = "parser")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("eval", 1, 1, eval).on_error(OnError::False)
        .args(&[super::describe::ArgType::SymbolOrString], super::describe::ArgType::Any),
    Builtin::eager("build", 1, 1, build).on_error(OnError::False)
        .args(&[super::describe::ArgType::SymbolOrString], super::describe::ArgType::Any),
    Builtin::eager("load", 1, 1, super::commands::load).file_name(),
    Builtin::eager("load*", 1, 1, super::commands::load_quiet).file_name(),
    Builtin::eager("batch", 1, 1, super::commands::batch).file_name(),
    Builtin::eager("batch*", 1, 1, super::commands::batch_quiet).file_name(),
    Builtin::eager("load-facts", 1, 1, super::commands::load_facts).file_name(),
];

#[cfg(not(feature = "parser"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// The text argument (symbol or string), copied out of the symbol table.
fn source_arg(
    cx: &Core<'_>,
    a: Args,
    func: &'static str,
) -> Result<super::strings::Copied, EvalError> {
    match cx.arg(a, 0) {
        Value::Sym(s) | Value::Str(s) => super::strings::copy_text(cx, s),
        _ => Err(EvalError::wrong_type(func, 1, "symbol or string")),
    }
}

/// `(eval "(+ 1 2)")`: the value of one command; constructs are not allowed (use
/// `build`). Its expression nodes are dropped again afterwards.
fn eval(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let text = source_arg(cx, a, "eval")?;
    let text = text.as_str();
    let cp = cx.checkpoint();
    let mut p = Parser::new(cx, text);
    p.commands_only = true;
    let item = p.next_item();
    let nlocals = p.nlocals;
    let prompt_reads = p.prompt_reads;
    let r = match item {
        // `$?x` alone is CLIPS's `expand$` outside a call: `[MISCFUN1]`
        #[cfg(feature = "extras")]
        Ok(Item::Command(e)) if cx.exprs[e as usize].op == crate::expr::Op::Expand => {
            super::environment::expand_outside_call(cx)
        }
        // a variable the text reads but does not bind itself (a loop's or a query's
        // are its own): CLIPS's eval sees none of the caller's, the prompt's included
        Ok(Item::Command(_)) if prompt_reads > 0 => {
            cx.write(
                crate::host::router::WERROR,
                "[STRNGFUN2] Some variables could not be accessed by the eval function.\n",
            );
            Err(EvalError::already_reported())
        }
        Ok(Item::Command(e)) => {
            // a frame for the command's own loop/query variables
            let outer = cx.st.frame;
            cx.st.frame.bp = cx.st.frame.sp;
            let mut r = Ok(Value::Void);
            for _ in 0..nlocals {
                if let Err(c) = cx.push_value(Value::Void) {
                    r = Err(c.into());
                }
            }
            if r.is_ok() {
                r = cx.eval(e);
            }
            cx.st.frame.leave(outer);
            r
        }
        // nothing to evaluate: CLIPS's parser wants an expression
        #[cfg(feature = "extras")]
        Ok(Item::End) => {
            cx.write(
                crate::host::router::WERROR,
                "\n[EXPRNPSR2] Expected a constant, variable, or expression.\n",
            );
            Err(EvalError::already_reported())
        }
        #[cfg(not(feature = "extras"))]
        Ok(Item::End) => Ok(Value::Sym(SYM_FALSE)),
        Ok(Item::Construct) => Ok(Value::Sym(SYM_FALSE)),
        Err(e) => {
            match eval_syntax_message(cx, text, &e) {
                Some(m) => write_eval_syntax_message(cx, m),
                None => cx.report_load_error("eval", text, &e),
            }
            Err(EvalError::new(EvalErrorKind::Reported))
        }
    };
    // a plain command leaves no expressions behind
    let now = cx.checkpoint();
    if now.nrules == cp.nrules
        && now.nfuncs == cp.nfuncs
        && now.ndeffacts == cp.ndeffacts
        && now.ntemplates == cp.ntemplates
        && now.nglobals == cp.nglobals
    {
        cx.st.pools.nexprs = cp.nexprs;
    }
    r
}

/// What CLIPS's `eval`, which reads an expression and not a command, says where our
/// command reader's message would be the prompt's (`[COMMLINE1]`, `[COMMLINE2]`) or
/// about text that ended inside a call ("for the command"); None to keep ours.
#[derive(Clone, Copy)]
enum EvalSyntax {
    /// `[EXPRNPSR2] Expected a constant, variable, or expression.`
    Expression,
    /// `[EXPRNPSR1] A function name must be a symbol`
    FunctionName,
    /// `[PRNTUTIL2] ... for NAME function.` (`if`, `while`, `switch`, `loop-for-count`)
    Special(&'static str),
    /// `[PRNTUTIL2] ... for RHS patterns.` (`assert`)
    RhsPatterns,
}

fn eval_syntax_message(
    cx: &Core<'_>,
    text: &str,
    e: &crate::error::LoadError,
) -> Option<EvalSyntax> {
    let mut b: crate::value::TextBuf<4096> = crate::value::TextBuf::new();
    cx.format_load_error("eval", text, e, &mut b, false);
    let ours = b.as_str();
    if ours.contains("[COMMLINE1]") {
        return Some(EvalSyntax::Expression);
    }
    if ours.contains("[COMMLINE2]") {
        return Some(EvalSyntax::FunctionName);
    }
    if !ours.contains("Check appropriate syntax for the command.") {
        return None;
    }
    // a connective where an argument is due
    if matches!(
        text.get(e.start as usize..e.end as usize),
        Some("&" | "|" | "~")
    ) {
        return Some(EvalSyntax::Expression);
    }
    // the calls still open where the text ends: the innermost's name, the one around
    // it, whether anything followed the innermost's name, and the last token
    let (mut inner, mut outer, mut after_name, mut last_open) = ("", "", false, false);
    let mut depth = 0usize;
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        match c {
            b';' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'"' => {
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
                after_name = true;
                last_open = false;
                continue;
            }
            b'(' => {
                let start = i + 1;
                let mut end = start;
                while end < bytes.len() && !b" \t\r\n()\";&|~".contains(&bytes[end]) {
                    end += 1;
                }
                outer = inner;
                inner = text.get(start..end).unwrap_or("");
                depth += 1;
                after_name = false;
                last_open = start == end;
                i = end;
                continue;
            }
            b')' => {
                // (the name around a closed call is no longer known: only the
                // innermost open call matters, and a closed one makes its caller the
                // innermost with something after its name)
                depth = depth.saturating_sub(1);
                inner = outer;
                outer = "";
                after_name = true;
                last_open = false;
            }
            b' ' | b'\t' | b'\r' | b'\n' => {}
            _ => {
                after_name = true;
                last_open = false;
                while i < bytes.len() && !b" \t\r\n()\";".contains(&bytes[i]) {
                    i += 1;
                }
                continue;
            }
        }
        i += 1;
    }
    if depth == 0 {
        return None;
    }
    if last_open {
        return Some(EvalSyntax::FunctionName);
    }
    let progn = |name: &str| matches!(name, "progn" | "progn$" | "foreach");
    if progn(inner) {
        // CLIPS's reader of their actions stops at the text's end without a word: the
        // text then runs (not ours, kept), or the call around it reports
        if depth == 1 || progn(outer) {
            return None;
        }
        return eval_syntax_of(outer, true, "");
    }
    eval_syntax_of(inner, after_name, outer)
}

/// `eval_syntax_message` for text that ended in a call of `inner` (inside a call of
/// `outer`), with something after its name when `after_name`.
fn eval_syntax_of(inner: &str, after_name: bool, outer: &str) -> Option<EvalSyntax> {
    Some(match inner {
        "if" | "while" | "switch" if !after_name => EvalSyntax::Expression,
        "if" => EvalSyntax::Special("if"),
        "while" => EvalSyntax::Special("while"),
        "switch" => EvalSyntax::Special("switch"),
        "loop-for-count" => EvalSyntax::Special("loop-for-count"),
        "assert" => EvalSyntax::RhsPatterns,
        _ if outer == "assert" => EvalSyntax::RhsPatterns,
        // (their own reader ends differently in CLIPS: ours is kept)
        "modify" | "duplicate" => return None,
        _ => EvalSyntax::Expression,
    })
}

fn write_eval_syntax_message(cx: &mut Core<'_>, m: EvalSyntax) {
    let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
    let _ = match m {
        EvalSyntax::Expression => {
            b.write_str("\n[EXPRNPSR2] Expected a constant, variable, or expression.\n")
        }
        EvalSyntax::FunctionName => b.write_str("\n[EXPRNPSR1] A function name must be a symbol\n"),
        EvalSyntax::Special(name) => write!(
            b,
            "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {name} function.\n"
        ),
        EvalSyntax::RhsPatterns => {
            b.write_str("\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for RHS patterns.\n")
        }
    };
    cx.write(router::WERROR, b.as_str());
}

/// `(assert-string "(point (x 1))")`: asserts the first fact the string writes (its
/// fields may call functions and read globals, not variables), as `assert` would: the
/// fact, or FALSE (a duplicate, or text that is not a fact).
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
pub(super) fn assert_string(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    assert_string_as(cx, a, "assert-string")
}

/// `str-assert`: CLIPS 6.30's older name of `assert-string` (its messages but the
/// argument check's name `assert-string`'s, as in CLIPS).
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
pub(super) fn str_assert(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    assert_string_as(cx, a, "str-assert")
}

const VARIABLE_IN_ASSERT_STRING: &str =
    "\n[PRNTUTIL6] Local variables can not be accessed by the assert-string function.\n";

/// Whether fact spec `spec` leaves out a slot whose default is `<Dummy Fact>`
/// (CLIPS refuses it as it refuses a variable).
#[cfg(feature = "extras")]
fn dummy_fact_left_out(cx: &Core<'_>, spec: Ix) -> bool {
    let tmpl = cx.exprs[spec as usize].data;
    let nslots = cx.templates[tmpl as usize].nslots;
    (0..nslots).any(|slot| {
        let mut c = cx.exprs[spec as usize].first;
        while c != crate::value::NONE {
            let x = cx.exprs[c as usize];
            if x.op == crate::expr::Op::SlotVal && x.data == slot {
                return false;
            }
            c = x.next;
        }
        cx.derives_dummy_fact(&cx.slot_def(tmpl, slot))
    })
}

fn assert_string_as(cx: &mut Core<'_>, a: Args, func: &'static str) -> Result<Value, EvalError> {
    let Value::Str(s) = cx.arg(a, 0) else {
        // (str-assert runs assert-string's body, which names itself; a literal is
        // refused while read, under the name typed)
        let _ = func;
        return Err(EvalError::wrong_type("assert-string", 1, "string"));
    };
    let text = super::strings::copy_text(cx, s)?;
    // CLIPS refuses a variable (a global is no variable here)
    let mut lex = crate::lexer::Lexer::new(text.as_str());
    loop {
        match lex.next_token().tok {
            Tok::SfVar(_) | Tok::MfVar(_) => {
                cx.write(router::WERROR, VARIABLE_IN_ASSERT_STRING);
                return Ok(Value::Sym(SYM_FALSE));
            }
            Tok::Eof | Tok::Bad => break,
            _ => {}
        }
    }
    let cp = cx.checkpoint();
    let mut p = Parser::new(cx, text.as_str());
    let spec = p.expect_lparen("a fact").and_then(|_| p.fact_spec());
    #[cfg(feature = "extras")]
    if let Ok(spec) = spec {
        if dummy_fact_left_out(cx, spec) {
            cx.st.pools.nexprs = cp.nexprs;
            cx.write(router::WERROR, VARIABLE_IN_ASSERT_STRING);
            return Ok(Value::Sym(SYM_FALSE));
        }
    }
    let r = match spec {
        Ok(spec) => {
            // a one-fact assert: what `assert` does with it (errors, halts, FALSE)
            let call = cx.push_expr(crate::expr::Expr::new(
                crate::expr::Op::Call,
                crate::expr::FnKind::Builtin as u8,
                super::ID_ASSERT,
            ));
            match call {
                Ok(call) => {
                    cx.exprs[call as usize].first = spec;
                    cx.eval(call)
                }
                Err(full) => Err(full.into()),
            }
        }
        Err(e) => {
            cx.report_fact_text_error("assert-string", text.as_str(), &e);
            Ok(Value::Sym(SYM_FALSE))
        }
    };
    // the fact's expression nodes go again (symbols it made stay, as for any assert)
    cx.st.pools.nexprs = cp.nexprs;
    r
}

/// `(funcall name args...)`: calls the function (builtin, deffunction or host
/// function) whose name `name` evaluates to, with the other arguments' values.
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
pub(super) fn funcall(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    const NOT_A_FUNCTION: &str = "function, deffunction, or generic function name";
    let name = match cx.arg(a, 0) {
        Value::Sym(s) | Value::Str(s) => s,
        _ => return Err(EvalError::wrong_type("funcall", 1, "symbol or string")),
    };
    let rest = Args {
        base: a.base + 1,
        len: a.len - 1,
    };
    // `and` and `or` take the values as they are (none: TRUE and FALSE)
    let text = cx.sym_text(name);
    if text == "and" || text == "or" {
        let want = text == "or";
        let hit =
            (0..rest.len as usize).any(|i| (cx.arg(rest, i) != Value::Sym(SYM_FALSE)) == want);
        return Ok(Value::Sym(if hit == want {
            super::SYM_TRUE
        } else {
            SYM_FALSE
        }));
    }
    match callee_named(cx, name) {
        Some(Callee::Builtin(func, min, max, _))
            if (rest.len as usize) < usize::from(min)
                || (max != super::ANY && rest.len as usize > usize::from(max)) =>
        {
            funcall_count(cx, func, min, max, rest)
        }
        Some(c) => {
            let r = cx.call_values(c, rest);
            // a builtin that fails gives funcall its own error value (`""` for
            // `str-cat`, `nil` for `sym-cat`), unless it recorded one already
            if let (Err(_), Callee::Builtin(name, ..)) = (&r, c) {
                let depth = cx.st.eval.eval_depth;
                let recorded = cx.st.eval.error_fallback.is_some_and(|f| f.depth == depth);
                let value = super::lookup(name).and_then(|(_, b)| match b.on_error.fallback() {
                    Some(super::errors::Fallback::Sym("nil")) => Some(Value::Sym(super::SYM_NIL)),

                    Some(super::errors::Fallback::Str("")) => {
                        Some(Value::Str(super::SYM_EMPTY_STR))
                    }
                    Some(super::errors::Fallback::Int(i)) => Some(Value::Int(i)),
                    Some(super::errors::Fallback::Float(f)) => Some(Value::Float(f)),
                    _ => None,
                });
                let empty_multi = super::lookup(name)
                    .is_some_and(|(_, b)| b.on_error == super::describe::OnError::EmptyMultifield);
                let value = match value {
                    None if empty_multi => {
                        let m = cx.multi_begin();
                        Some(cx.multi_finish(m))
                    }
                    v => v,
                };
                if let (false, Some(v)) = (recorded, value) {
                    cx.set_error_fallback(v, None);
                }
            }
            r
        }
        None => Err(EvalError::wrong_type("funcall", 1, NOT_A_FUNCTION)),
    }
}

/// A builtin `funcall` calls with too few or too many arguments. CLIPS checks a call's
/// count when it parses it; one made by `funcall` meets only the function's own check at
/// run time: the variadic arithmetic and comparisons make do with what they get
/// (`(funcall + 1)` is 1, `(funcall =)` TRUE), `min`/`max` need one argument, the others say
/// `expected exactly N argument(s)` (`at least`, `no more than`) under their CLIPS name
/// and give their error value (the getters their usual one).
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
fn funcall_count(
    cx: &mut Core<'_>,
    func: &'static str,
    min: u8,
    max: u8,
    rest: Args,
) -> Result<Value, EvalError> {
    let n = rest.len;
    let number = |cx: &Core<'_>| match cx.arg(rest, 0) {
        v @ (Value::Int(_) | Value::Float(_)) => Ok(v),
        _ => Err(EvalError::wrong_type(func, 1, "integer or float")),
    };
    let truth = |b: bool| Value::Sym(if b { super::SYM_TRUE } else { SYM_FALSE });
    let fallback = |cx: &mut Core<'_>, v: Value| cx.set_error_fallback(v, None);
    match (func, n) {
        // (its body counts and draws a number all the same)
        ("random", _) => return super::random::random(cx, rest),
        ("str-compare", _) => {
            cx.write(
                router::WERROR,
                "[ARGACCES1] Function str-compare expected at least 2 and no more than 3 arguments.\n",
            );
            fallback(cx, Value::Int(0));
            return Err(EvalError::already_reported());
        }
        ("mv-subseq" | "mv-delete" | "mv-replace", _) => return mv_count(cx, func, max, rest),
        ("+" | "-", 0) => return Ok(Value::Int(0)),
        ("*" | "div", 0) => return Ok(Value::Int(1)),
        ("/", 0) => return Ok(Value::Float(1.0)),
        ("+" | "-" | "*" | "min" | "max", 1) => {
            fallback(cx, Value::Int(0));
            return number(cx);
        }
        ("/", 1) => {
            fallback(cx, Value::Float(1.0));
            return number(cx).map(|v| match v {
                Value::Int(i) => Value::Float(i as f64),
                v => v,
            });
        }
        ("div", 1) => {
            fallback(cx, Value::Int(1));
            return number(cx).map(|v| match v {
                Value::Float(f) => Value::Int(c_trunc(f)),
                v => v,
            });
        }
        ("=" | "<>" | "!=" | "<" | "<=" | ">" | ">=", 0) => return Ok(truth(true)),
        ("=" | "<>" | "!=" | "<" | "<=" | ">" | ">=", 1) => {
            fallback(cx, truth(false));
            return number(cx).map(|_| truth(true));
        }
        ("eq" | "neq", _) => return Ok(truth(n > 0)),
        ("not", 0) => return Ok(truth(false)),
        ("not", _) => return Ok(truth(cx.arg(rest, 0) == Value::Sym(SYM_FALSE))),
        ("str-cat", 0) => return Ok(Value::Str(super::SYM_EMPTY_STR)),
        ("sym-cat", 0) => return Ok(Value::Sym(super::SYM_NIL)),
        ("get-sequence-operator-recognition", _) => return Ok(truth(false)),
        _ => {}
    }
    // CLIPS's own name for a function it also knows by another
    let name = match func {
        "member" => "member$",
        "nth" => "nth$",
        "length" => "length$",
        "str-explode" => "explode$",
        "str-implode" => "implode$",
        "subset" => "subsetp",
        "wordp" => "symbolp",
        "sequencep" => "multifieldp",
        "rules" => "list-defrules",
        // (CLIPS 6.30 checks this one under its neighbour's name)
        "deftemplate-slot-defaultp" => "deftemplate-slot-existp",
        f => f,
    };
    let (how, count) = match (func, min, max) {
        ("min" | "max", ..) => ("at least", 1),
        (_, lo, hi) if lo == hi => ("exactly", lo),
        (_, lo, _) if (n as usize) < usize::from(lo) => ("at least", lo),
        (_, _, hi) => ("no more than", hi),
    };
    let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
    let _ = core::fmt::Write::write_fmt(
        &mut b,
        format_args!("[ARGACCES4] Function {name} expected {how} {count} argument(s)\n"),
    );
    cx.write(router::WERROR, b.as_str());
    // a getter still answers; the others give their error value
    if max == 0 && func != "get-function-list" {
        if let Some(c) = cx.callee(func) {
            return cx.call_values(
                c,
                Args {
                    base: rest.base,
                    len: 0,
                },
            );
        }
    }
    use super::errors::Fallback;
    // (values these give only after a count error)
    let value = match func {
        "min" | "max" => Some(Fallback::Int(0)),
        "length$" | "length" => Some(Fallback::Int(-1)),
        "deftemplate-slot-defaultp" => Some(Fallback::Sym("FALSE")),
        "get-function-list" => Some(Fallback::EmptyMulti),
        #[cfg(feature = "extras")]
        "set-beta-memory-resizing" => Some(Fallback::Sym(if super::tools::beta_resizing(cx) {
            "TRUE"
        } else {
            "FALSE"
        })),
        _ => super::lookup(func).and_then(|(_, b)| b.on_error.fallback()),
    };
    let value = match value {
        // (a command that returns nothing shows nothing more)
        None => return Ok(Value::Void),
        Some(Fallback::Int(i)) => Value::Int(i),
        Some(Fallback::Float(f)) => Value::Float(f),
        Some(Fallback::Sym(s)) => Value::Sym(cx.intern(s)?),
        Some(Fallback::Str(s)) => Value::Str(cx.intern(s)?),
        Some(Fallback::EmptyMulti) => {
            let start = cx.multi_begin();
            cx.multi_finish(start)
        }
    };
    // an evaluation error, as CLIPS's count check sets it, with the function's value
    cx.set_error_fallback(value, None);
    Err(EvalError::already_reported())
}

/// `mv-subseq`, `mv-delete` or `mv-replace` called by `funcall` with a count its
/// definition refuses: CLIPS's bodies read their arguments one by one and never count
/// them, so those beyond the last are ignored, a missing one is `[ARGACCES3]` once the
/// ones before it have their types (and `mv-replace`'s missing value is FALSE).
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
fn mv_count(
    cx: &mut Core<'_>,
    func: &'static str,
    max: u8,
    rest: Args,
) -> Result<Value, EvalError> {
    let n = rest.len as usize;
    let Some(c) = cx.callee(func) else {
        return Err(EvalError::wrong_type(
            "funcall",
            1,
            "function, deffunction, or generic function name",
        ));
    };
    let m = cx.multi_begin();
    let empty = cx.multi_finish(m);
    // (a failing body gives the empty multifield)
    let or_empty = |cx: &mut Core<'_>, r: Result<Value, EvalError>| {
        if r.is_err() {
            cx.set_error_fallback(empty, None);
        }
        r
    };
    if n >= usize::from(max) {
        let first = Args {
            base: rest.base,
            len: Ix::from(max),
        };
        let r = cx.call_values(c, first);
        return or_empty(cx, r);
    }
    // the types the body asks for, in order (the value of `mv-replace` is any)
    let types: &[bool] = match func {
        "mv-subseq" => &[false, false, true],
        _ => &[false, true],
    };
    for (i, &multi) in types.iter().enumerate().take(n) {
        let ok = match cx.arg(rest, i) {
            Value::Multi(_) => multi,
            Value::Int(_) => !multi,
            _ => false,
        };
        if !ok {
            cx.set_error_fallback(empty, None);
            let what = if multi { "multifield" } else { "integer" };
            return Err(EvalError::wrong_type(func, i as u8 + 1, what));
        }
    }
    if func == "mv-replace" && n == 2 {
        // (the value CLIPS's body finds in place of the missing third argument)
        let base = cx.st.frame.sp;
        for v in [cx.arg(rest, 0), cx.arg(rest, 1), Value::Sym(SYM_FALSE)] {
            cx.push_value(v)?;
        }
        let r = cx.call_values(c, Args { base, len: 3 });
        cx.st.frame.sp = base;
        return or_empty(cx, r);
    }
    let mut b: crate::value::TextBuf<160> = crate::value::TextBuf::new();
    let _ = core::fmt::Write::write_fmt(
        &mut b,
        format_args!(
            "[ARGACCES3] Function RtnUnknown received a request from function {func} for argument #{} which is non-existent\n",
            n + 1
        ),
    );
    cx.write(router::WERROR, b.as_str());
    cx.set_error_fallback(empty, None);
    Err(EvalError::already_reported())
}

/// A float truncated toward zero, as C's cast does (saturating at the ends).
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
fn c_trunc(f: f64) -> i64 {
    f as i64
}

#[cfg_attr(not(feature = "extras"), allow(dead_code))]
fn callee_named(cx: &mut Core<'_>, name: crate::value::SymId) -> Option<Callee> {
    let mut text = super::strings::Text::new();
    let _ = core::fmt::Write::write_str(&mut text, cx.sym_text(name));
    cx.callee(text.as_str())
}

/// `(sort f values...)`: the values (multifields spliced) in the order of a stable
/// merge sort that puts `b` before `a` where `(f a b)` is not FALSE, comparing as CLIPS
/// does (its comparison function sees the same calls). A failing comparison reports
/// its error; the values then come back unsorted, as in CLIPS.
// listed in `extras` (off in the agent image)
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
pub(super) fn sort(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    const NOT_A_FUNCTION: &str = "function name, deffunction name, or defgeneric name";
    // (CLIPS wants a symbol first: anything else is no name at all)
    let callee = match cx.arg(a, 0) {
        // (an instance name `[x]` is no symbol either)
        Value::Sym(s) if crate::value::instance_name_body(cx.sym_text(s)).is_none() => {
            callee_named(cx, s)
        }
        _ => return Err(EvalError::wrong_type("sort", 1, "symbol")),
    };
    let Some(callee) = callee else {
        return Err(EvalError::wrong_type("sort", 1, NOT_A_FUNCTION));
    };
    // CLIPS refuses a function that cannot take two arguments before sorting, and
    // goes on (no evaluation error) with FALSE
    let (min, max, what) = match callee {
        Callee::Builtin(_, min, max, _) => (min, max, "function name"),
        Callee::Deffunction(f) => {
            let d = cx.funcs[f as usize];
            let max = if d.rest { super::ANY } else { d.nparams };
            (d.nparams, max, "deffunction name")
        }
        Callee::External(e) => {
            let x = cx.externals[e as usize];
            (x.min, x.max, "function name")
        }
    };
    if min > 2 || (max != super::ANY && max < 2) {
        let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
        let _ = core::fmt::Write::write_fmt(
            &mut b,
            format_args!(
                "[ARGACCES5] Function sort expected argument #1 to be of type {what} expecting two arguments\n"
            ),
        );
        cx.write(router::WERROR, b.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    // the values, then as many cells for merging
    let Value::Multi(values) = spliced(cx, a)? else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    let n = values.len;
    let tmp = cx.scratch_alloc(n as usize)?;
    let order = Merge {
        callee,
        at: values.start,
        tmp,
    };
    if let Err(e) = order.sort(cx, 0, n) {
        // CLIPS gives the values as they were
        let unsorted = spliced(cx, a)?;
        cx.set_error_fallback(unsorted, None);
        return Err(e);
    }
    Ok(Value::Multi(values))
}

/// Arguments 2.. as one multifield, multifields spliced.
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
fn spliced(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    for i in 1..a.len as usize {
        match cx.arg(a, i) {
            Value::Multi(m) => {
                for k in 0..m.len as usize {
                    let v = cx.mf_item(m, k);
                    cx.multi_push(v)?;
                }
            }
            v => cx.multi_push(v)?,
        }
    }
    Ok(cx.multi_finish(start))
}

/// A merge sort of scratch cells `at..` through the comparison `callee`, with room for
/// merging at `tmp..`.
#[cfg_attr(not(feature = "extras"), allow(dead_code))]
struct Merge {
    callee: Callee,
    at: Ix,
    tmp: Ix,
}

#[cfg_attr(not(feature = "extras"), allow(dead_code))]
impl Merge {
    /// Sorts cells `lo..hi` (relative to `at`); the left half is the bigger one.
    fn sort(&self, cx: &mut Core<'_>, lo: Ix, hi: Ix) -> Result<(), EvalError> {
        if hi - lo < 2 {
            return Ok(());
        }
        let mid = lo + (hi - lo).div_ceil(2);
        self.sort(cx, lo, mid)?;
        self.sort(cx, mid, hi)?;
        let (mut i, mut j, mut k) = (lo, mid, lo);
        while i < mid || j < hi {
            let take_right = if i == mid {
                true
            } else if j == hi {
                false
            } else {
                let (x, y) = (
                    cx.scratch[(self.at + i) as usize],
                    cx.scratch[(self.at + j) as usize],
                );
                self.after(cx, x, y)?
            };
            let src = if take_right { &mut j } else { &mut i };
            cx.scratch[(self.tmp + k) as usize] = cx.scratch[(self.at + *src) as usize];
            *src += 1;
            k += 1;
        }
        for c in lo..hi {
            cx.scratch[(self.at + c) as usize] = cx.scratch[(self.tmp + c) as usize];
        }
        Ok(())
    }

    /// Whether `x` goes after `y`: `(f x y)` is not FALSE.
    fn after(&self, cx: &mut Core<'_>, x: Value, y: Value) -> Result<bool, EvalError> {
        let base = cx.st.frame.sp;
        cx.push_value(x)?;
        cx.push_value(y)?;
        let mark = cx.st.frame.scratch_top;
        let r = cx.call_values(self.callee, Args { base, len: 2 });
        cx.st.frame.sp = base;
        // only the answer's truth is kept: what the call built goes
        let r = r.map(|v| v != Value::Sym(SYM_FALSE));
        super::control::release_scratch(cx, mark);
        r
    }
}

/// `(build "(defrule ...)")`: defines one construct, silently; TRUE when it was defined.
fn build(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let text = source_arg(cx, a, "build")?;
    // CLIPS defines nothing while a pattern or join test runs (`State::matching`)
    if cx.st.net.matching > 0 {
        return Ok(Value::Sym(SYM_FALSE));
    }
    // CLIPS reads one construct: text that does not start with one is FALSE without
    // a message, and what follows the construct is not read
    let Some(end) = first_construct(text.as_str()) else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    let text = text.as_str().get(..end).unwrap_or(text.as_str());
    match cx.load_text(text, false) {
        Ok(n) if n > 0 => Ok(Value::Sym(SYM_TRUE)),
        Ok(_) => Ok(Value::Sym(SYM_FALSE)),
        Err(e) => {
            cx.report_load_error("build", text, &e);
            Ok(Value::Sym(SYM_FALSE))
        }
    }
}

/// Where the construct `text` starts with ends (the whole text when it does not end),
/// or None when `text` does not start with `(` and a construct keyword.
fn first_construct(text: &str) -> Option<usize> {
    let mut lx = crate::lexer::Lexer::new(text);
    if lx.next_token().tok != Tok::LParen {
        return None;
    }
    let Tok::Symbol(kw) = lx.next_token().tok else {
        return None;
    };
    if !crate::lexer::is_construct_keyword(kw) {
        return None;
    }
    let mut depth = 1u32;
    loop {
        let t = lx.next_token();
        match t.tok {
            Tok::Eof | Tok::Bad => return Some(text.len()),
            Tok::LParen => depth += 1,
            Tok::RParen => {
                depth -= 1;
                if depth == 0 {
                    return Some(t.end);
                }
            }
            _ => {}
        }
    }
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::{eval_to_string, run_program};

    /// `sort` orders like a stable sort by the comparison, for lists of every length
    /// up to 40 with many ties (pseudo-random, fixed seed): by value with `>`, and by
    /// tens only (ties kept in their order) with a deffunction.
    #[test]
    #[cfg(feature = "extras")]
    fn sort_is_a_stable_sort_by_its_comparison() {
        extern crate std;
        use std::string::String;
        use std::vec::Vec;
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        for len in 0..40usize {
            let values: Vec<i64> = (0..len)
                .map(|_| {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    ((seed >> 33) % 50) as i64
                })
                .collect();
            let list: Vec<String> = values.iter().map(|v| std::format!("{v}")).collect();
            let list = list.join(" ");
            let mut by_value = values.clone();
            by_value.sort();
            let mut by_tens = values.clone();
            by_tens.sort_by_key(|v| v / 10);
            let show = |v: &[i64]| {
                let items: Vec<String> = v.iter().map(|x| std::format!("{x}")).collect();
                std::format!("({})", items.join(" "))
            };
            assert_eq!(
                eval_to_string(&std::format!("(sort > {list})")),
                show(&by_value)
            );
            let out = run_program(&std::format!(
                "(deffunction tens (?a ?b) (> (div ?a 10) (div ?b 10)))\n(printout t (sort tens {list}) crlf)\n"
            ));
            assert!(out.contains(&show(&by_tens)), "len {len}: {out}");
        }
    }

    #[test]
    fn eval_runs_a_command_from_a_string() {
        assert_eq!(eval_to_string("(eval \"(+ 1 2)\")"), "3");
        assert_eq!(eval_to_string("(eval \"(create$ a (* 2 3))\")"), "(a 6)");
    }

    #[test]
    fn build_defines_a_rule_that_then_fires() {
        let out = run_program(
            "(build \"(defrule b (z ?x) => (printout t built ?x crlf))\")\n(assert (z 1))\n(run)\n",
        );
        assert!(out.contains("TRUE") && out.contains("built1"), "{out}");
    }
}
