//! `check-syntax` (agent-core features `extras` and `parser`): whether a construct or command given
//! as a string reads without errors, defining and running nothing.
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(all(feature = "extras", feature = "parser")), allow(dead_code))]

use super::{Args, Builtin, SYM_FALSE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind, LoadDetail};
use crate::host::router;
use crate::lexer::{Lexer, Tok};
use crate::parser::{Item, Parser};
use crate::value::{TextBuf, Value};

#[cfg(all(feature = "extras", feature = "parser"))]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    // (a computed argument of the wrong type: CLIPS's error, then TRUE)
    Builtin::eager("check-syntax", 1, 1, check_syntax)
        .args(&[super::describe::ArgType::Str], super::describe::ArgType::Any)
        .on_error(super::describe::OnError::True),
];
#[cfg(not(all(feature = "extras", feature = "parser")))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// `(check-syntax "(defrule ...)")`: FALSE when the text is one construct or command
/// that reads without errors; else CLIPS's symbol for text that is not one
/// parenthesized form (`MISSING-LEFT-PARENTHESIS`,
/// `EXPECTED-SYMBOL-AFTER-LEFT-PARENTHESIS`, `EXTRANEOUS-INPUT-AFTER-LAST-PARENTHESIS`),
/// or a multifield of the error text (what `load` would print, without our position
/// line) and FALSE. Nothing read stays defined, no old construct is replaced, and a
/// defglobal's value is not evaluated (as in CLIPS); a salience is (its effects stay,
/// as in CLIPS).
fn check_syntax(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Str(s) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type("check-syntax", 1, "string"));
    };
    let text = super::strings::copy_text(cx, s)?;
    let text = text.as_str();
    let mut lx = Lexer::new(text);
    if lx.next_token().tok != Tok::LParen {
        return Ok(cx.make_symbol("MISSING-LEFT-PARENTHESIS")?);
    }
    let Tok::Symbol(head) = lx.next_token().tok else {
        return Ok(cx.make_symbol("EXPECTED-SYMBOL-AFTER-LEFT-PARENTHESIS")?);
    };
    // a construct is read into the network: not while a pattern or join test runs
    let construct = matches!(
        head,
        "deftemplate" | "defrule" | "deffacts" | "deffunction" | "defglobal" | "defmodule"
    );
    if construct && cx.st.net.matching > 0 {
        cx.write(
            router::WERROR,
            "[CHECKSYN1] robotino-agent's check-syntax cannot read a construct while a pattern is matched.\n",
        );
        return Err(EvalError::new(EvalErrorKind::Reported));
    }
    let cp = cx.checkpoint();
    // what reading it prints as errors (a salience evaluated as it is read) goes
    // into the message, as in CLIPS (a check inside a check keeps the outer's text)
    #[cfg(feature = "extras")]
    let outer = cx.st.capture.replace(TextBuf::new());
    let mut p = Parser::new(cx, text);
    p.check_only = true;
    let item = p.next_item();
    let extraneous = p.peek().tok != Tok::Eof;
    let warned = p.warned_overflow;
    #[cfg(feature = "extras")]
    let printed = core::mem::replace(&mut cx.st.capture, outer).unwrap_or_default();
    // (without `extras` there is no check-syntax to call this)
    #[cfg(not(feature = "extras"))]
    let printed: TextBuf<8> = TextBuf::new();
    // CLIPS returns the warnings reading a construct printed (a command's are lost)
    let mut warning = Value::Sym(SYM_FALSE);
    let failed = match item {
        // read whole (a command's expressions go again; a construct rolled itself back)
        Ok(Item::Command(_)) => {
            cx.rollback(cp);
            None
        }
        Err(e) if e.detail == LoadDetail::Checked => {
            if warned {
                warning = cx.make_string(crate::parser::OVERFLOW_WARNING)?;
            }
            None
        }
        Err(e) => Some(e),
        // (not in check_only mode: every construct stops before it is defined)
        Ok(Item::Construct) | Ok(Item::End) => None,
    };
    let Some(e) = failed else {
        return Ok(if extraneous {
            cx.make_symbol("EXTRANEOUS-INPUT-AFTER-LAST-PARENTHESIS")?
        } else if warned && construct {
            cx.make_multi(&[Value::Sym(SYM_FALSE), warning])?
        } else {
            Value::Sym(SYM_FALSE)
        });
    };
    if warned && construct {
        warning = cx.make_string(crate::parser::OVERFLOW_WARNING)?;
    }
    let mut b: TextBuf<4096> = TextBuf::new();
    let _ = core::fmt::Write::write_str(&mut b, printed.as_str());
    cx.format_load_error("check-syntax", text, &e, &mut b, false);
    let message = cx.make_string(b.as_str())?;
    Ok(cx.make_multi(&[message, warning])?)
}

#[cfg(all(test, feature = "extras", feature = "parser"))]
mod tests {
    use crate::testutil::run_program;

    /// Checking leaves nothing behind: hundreds of checks of rules (with `or`, a
    /// shared pattern, an implied template of their own), deffunctions, deffacts,
    /// deftemplates, defglobals and commands, good and bad, on the small engine (whose
    /// pools a leak would fill), and the rule base still answers as before.
    #[test]
    fn checking_leaves_nothing_behind() {
        let out = run_program(
            "(defrule keep (a ?x) => (printout t kept- ?x crlf))\n\
             (deffunction twice (?x) (* 2 ?x))\n\
             (defglobal ?*n* = 0)\n\
             (loop-for-count 500\n\
               (bind ?*n* (+ ?*n* 1))\n\
               (check-syntax \"(defrule keep (b ?y) (or (c ?y) (d ?y)) => (assert (e (twice ?y))))\")\n\
               (check-syntax \"(defrule other (a ?x) (new-template ?x) => (foo))\")\n\
               (check-syntax \"(deffunction twice (?x $?y) (+ ?x 1))\")\n\
               (check-syntax \"(deffunction thrice (?x) (thrice))\")\n\
               (check-syntax \"(deftemplate point (slot x) (multislot y))\")\n\
               (check-syntax \"(deffacts start (a 1) (a 2))\")\n\
               (check-syntax \"(defglobal ?*n* = (printout t never crlf))\")\n\
               (check-syntax \"(printout t never crlf)\")\n\
               (check-syntax \"(+ 1 a)\"))\n\
             (printout t ?*n* \" \" (twice 4) \" \" (check-syntax \"(deffunction twice (?x) (twice 1 2))\") crlf)\n\
             (assert (a 7))\n\
             (run)\n\
             (rules)\n\
             (list-deftemplates)\n\
             (list-deffacts)\n",
        );
        assert!(!out.contains("never"), "{out}");
        assert!(!out.contains("MEMORY"), "{out}");
        assert!(
            out.contains("500 8 (\"[ARGACCES4] Function twice expected exactly 1 argument(s)"),
            "{out}"
        );
        assert!(out.contains("kept-7\n"), "{out}");
        assert!(out.contains("keep\nFor a total of 1 defrule."), "{out}");
        assert!(
            !out.contains("point") && !out.contains("new-template"),
            "{out}"
        );
        assert!(!out.contains("start"), "{out}");
    }
}
