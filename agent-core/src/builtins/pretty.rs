//! CLIPS 6.30's pretty-printed form of a defrule (`ppdefrule`), rebuilt from its source.
//!
//! CLIPS re-spaces the tokens it read: one CE per line indented by 3, connective CEs
//! (`and`/`or`/`not`) with their first CE on the same line and the others aligned below
//! it, `exists`/`logical` with every CE on a new line, one action per line, and the
//! bodies of `if`/`while`/`loop-for-count`/`progn$`/`switch` and the query and actions of
//! fact-set queries (`do-for-all-facts`, ...) indented by 3 more.
//! Comments are dropped and numbers printed as CLIPS prints them (`2.50` -> `2.5`).

use core::fmt::{self, Write};

use crate::lexer::{Lexer, Tok, Token};
use crate::value::write_float;

/// Tokens of one construct with one token of lookahead.
struct Cursor<'a> {
    src: &'a str,
    lx: Lexer<'a>,
    peeked: [Option<Token<'a>>; 2],
    /// Column of the action or CE being written: a control form nested in a call
    /// indents its body from there, as CLIPS does (feature `extras`; the agent image
    /// prints such a form on one line).
    #[cfg(feature = "extras")]
    indent: usize,
}

impl<'a> Cursor<'a> {
    fn new(src: &'a str) -> Self {
        Cursor {
            src,
            lx: Lexer::new(src),
            peeked: [None, None],
            #[cfg(feature = "extras")]
            indent: 3,
        }
    }

    fn fill(&mut self, k: usize) {
        for i in 0..=k {
            if self.peeked[i].is_none() {
                self.peeked[i] = Some(self.lx.next_token());
            }
        }
    }

    /// The token `k` ahead (0 or 1).
    fn peek(&mut self, k: usize) -> Token<'a> {
        self.fill(k);
        self.peeked[k].unwrap_or_else(|| self.lx.next_token())
    }

    fn next(&mut self) -> Token<'a> {
        self.fill(0);
        let t = self.peek(0);
        self.peeked = [self.peeked[1], None];
        t
    }

    fn text(&self, t: Token<'a>) -> &'a str {
        self.src.get(t.start..t.end).unwrap_or("")
    }
}

fn spaces(w: &mut dyn Write, n: usize) -> fmt::Result {
    for _ in 0..n {
        w.write_char(' ')?;
    }
    Ok(())
}

fn is_sym(t: Token<'_>, s: &str) -> bool {
    t.tok == Tok::Symbol(s)
}

/// One token as CLIPS prints it.
fn write_token(c: &Cursor<'_>, w: &mut dyn Write, t: Token<'_>) -> fmt::Result {
    match t.tok {
        Tok::Int(i) | Tok::IntOverflow(i) => write!(w, "{i}"),
        Tok::Float(f) => write_float(w, f),
        _ => w.write_str(c.text(t)),
    }
}

/// One expression (an atom or a parenthesised list, nested lists included) on one line.
fn flat(c: &mut Cursor<'_>, w: &mut dyn Write) -> fmt::Result {
    flat_as(c, w, false)
}

/// [`flat`] for a fact or pattern (`fact`: a CE, a deffacts fact), where CLIPS glues a
/// `=` or `:` to the call after it (`(a =(+ 1 2))`, `?x&:(> ?x 1)`) however it was
/// written; so in the facts of `assert`, `modify` and `duplicate`, but not among a
/// call's arguments (`(printout t = (+ 1 2))`).
fn flat_as(c: &mut Cursor<'_>, w: &mut dyn Write, fact: bool) -> fmt::Result {
    // a fact-set query as an `if`'s condition or a global's value: over lines as well
    #[cfg(feature = "extras")]
    if query_form(c) {
        let col = c.indent;
        return action(c, w, col);
    }
    let first = c.next();
    write_token(c, w, first)?;
    if first.tok != Tok::LParen {
        return Ok(());
    }
    let mut depth = 1;
    let mut prev = first;
    let mut prev2 = first;
    // bit d: the list at depth d is a fact or slot; `makes` bit d: its head is a
    // function whose list arguments are facts (deeper than 63: calls)
    let mut facts: u64 = u64::from(fact) << 1;
    let mut makes: u64 = 0;
    while depth > 0 {
        #[cfg(feature = "extras")]
        if nested_control(c) {
            // (a `=` or `:` glued to it only as a constraint in a fact, as below)
            let after_constraint = matches!(prev.tok, Tok::Symbol(":" | "="))
                && prev2.tok != Tok::LParen
                && facts & 1u64.checked_shl(depth as u32).unwrap_or(0) != 0;
            if !matches!(prev.tok, Tok::LParen | Tok::Amp | Tok::Bar | Tok::Tilde)
                && !after_constraint
            {
                w.write_char(' ')?;
            }
            let col = c.indent;
            action(c, w, col)?;
            prev = Token {
                tok: Tok::RParen,
                ..first
            };
            continue;
        }
        let t = c.next();
        let bit = |d: i32| 1u64.checked_shl(d as u32).unwrap_or(0);
        // a `=` or `:` that is no call's name, in a fact: a constraint or `=(...)`
        let constraint =
            matches!(prev.tok, Tok::Symbol(":") | Tok::Symbol("=")) && prev2.tok != Tok::LParen;
        let in_fact = facts & bit(depth) != 0;
        match t.tok {
            Tok::Eof | Tok::Bad => return Ok(()),
            Tok::LParen => {
                depth += 1;
                let is_fact = !constraint && (facts | makes) & bit(depth - 1) != 0;
                facts = (facts & !bit(depth)) | if is_fact { bit(depth) } else { 0 };
                makes &= !bit(depth);
            }
            Tok::RParen => depth -= 1,
            Tok::Symbol("assert" | "modify" | "duplicate") if prev.tok == Tok::LParen => {
                makes |= bit(depth);
            }
            _ => {}
        }
        // constraint syntax stays glued: ?x&~3|4, ?y&:(> ?y 1), =(+ 1 2); a `=` or `:`
        // glued to a call elsewhere (a call's name, as in `(=(+ 1 1) 2)`, or an argument)
        // is printed with a space after it, as CLIPS prints it
        let glued = matches!(t.tok, Tok::RParen | Tok::Amp | Tok::Bar)
            || matches!(prev.tok, Tok::LParen | Tok::Amp | Tok::Bar | Tok::Tilde)
            || (matches!(prev.tok, Tok::Symbol(":") | Tok::Symbol("="))
                && t.tok == Tok::LParen
                && constraint
                && in_fact);
        if !glued {
            w.write_char(' ')?;
        }
        write_token(c, w, t)?;
        prev2 = prev;
        prev = t;
    }
    Ok(())
}

/// Whether a control form (`if`, `while`, ...) starts here, which CLIPS prints over
/// several lines even as a call's argument.
#[cfg(feature = "extras")]
fn nested_control(c: &mut Cursor<'_>) -> bool {
    c.peek(0).tok == Tok::LParen
        && matches!(
            c.peek(1).tok,
            Tok::Symbol(
                "if" | "while"
                    | "loop-for-count"
                    | "progn$"
                    | "foreach"
                    | "progn"
                    | "switch"
                    | "any-factp"
                    | "find-fact"
                    | "find-all-facts"
                    | "do-for-fact"
                    | "do-for-all-facts"
                    | "delayed-do-for-all-facts"
            )
        )
}

/// Whether a fact-set query call starts here.
#[cfg(feature = "extras")]
fn query_form(c: &mut Cursor<'_>) -> bool {
    c.peek(0).tok == Tok::LParen
        && matches!(
            c.peek(1).tok,
            Tok::Symbol(
                "any-factp"
                    | "find-fact"
                    | "find-all-facts"
                    | "do-for-fact"
                    | "do-for-all-facts"
                    | "delayed-do-for-all-facts"
            )
        )
}

/// A conditional element starting at column `col`.
fn ce(c: &mut Cursor<'_>, w: &mut dyn Write, col: usize) -> fmt::Result {
    #[cfg(feature = "extras")]
    {
        c.indent = col;
    }
    let t0 = c.peek(0);
    if matches!(t0.tok, Tok::SfVar(_)) && is_sym(c.peek(1), "<-") {
        // ?f <- (pattern)
        let v = c.next();
        write_token(c, w, v)?;
        c.next();
        w.write_str(" <- ")?;
        return flat_as(c, w, true);
    }
    let kw = match c.peek(1).tok {
        Tok::Symbol(k) if t0.tok == Tok::LParen => k,
        _ => return flat(c, w),
    };
    let same_line = match kw {
        "and" | "or" | "not" => true,
        "exists" | "logical" | "forall" => false,
        _ => return flat_as(c, w, true),
    };
    c.next();
    c.next();
    write!(w, "({kw}")?;
    let inner = col + 5;
    let mut first = true;
    let mut closed = false;
    loop {
        let t = c.peek(0);
        match t.tok {
            Tok::RParen => {
                c.next();
                closed = true;
                break;
            }
            Tok::Eof | Tok::Bad => break,
            _ => {}
        }
        if first && same_line {
            spaces(w, inner - col - 1 - kw.len())?;
        } else {
            w.write_char('\n')?;
            spaces(w, inner)?;
        }
        first = false;
        ce(c, w, inner)?;
    }
    // a rule shown up to where CLIPS stopped reading it may end inside the CE
    if !closed && c.peek(0).tok == Tok::Eof {
        return Ok(());
    }
    w.write_char(')')
}

/// Actions up to the closing parenthesis of their list (not consumed), one per line at
/// column `col`.
fn action_lines(c: &mut Cursor<'_>, w: &mut dyn Write, col: usize, stop: &[&str]) -> fmt::Result {
    loop {
        let t = c.peek(0);
        if matches!(t.tok, Tok::RParen | Tok::Eof | Tok::Bad) {
            return Ok(());
        }
        if let Tok::Symbol(s) = t.tok {
            if stop.contains(&s) {
                return Ok(());
            }
        }
        w.write_char('\n')?;
        spaces(w, col)?;
        action(c, w, col)?;
    }
}

/// Consumes a `)` if it is next and writes it.
fn close(c: &mut Cursor<'_>, w: &mut dyn Write) -> fmt::Result {
    if c.peek(0).tok == Tok::RParen {
        c.next();
        w.write_char(')')?;
    }
    Ok(())
}

/// One RHS action starting at column `col`.
fn action(c: &mut Cursor<'_>, w: &mut dyn Write, col: usize) -> fmt::Result {
    #[cfg(feature = "extras")]
    let outer = core::mem::replace(&mut c.indent, col);
    let r = action_at(c, w, col);
    #[cfg(feature = "extras")]
    {
        c.indent = outer;
    }
    r
}

fn action_at(c: &mut Cursor<'_>, w: &mut dyn Write, col: usize) -> fmt::Result {
    let kw = match (c.peek(0).tok, c.peek(1).tok) {
        (Tok::LParen, Tok::Symbol(k)) => k,
        _ => return flat(c, w),
    };
    let body = col + 3;
    match kw {
        "if" => {
            c.next();
            c.next();
            w.write_str("(if ")?;
            flat(c, w)?;
            // (an `if` CLIPS stopped reading where `then` was due: the token there on
            // a line of its own; only parse errors show such text)
            #[cfg(feature = "parser")]
            if !matches!(c.peek(0).tok, Tok::RParen | Tok::Eof | Tok::Bad)
                && !is_sym(c.peek(0), "then")
                && !is_sym(c.peek(0), "else")
            {
                action_lines(c, w, body, &[])?;
            }
            for part in ["then", "else"] {
                if is_sym(c.peek(0), part) {
                    c.next();
                    w.write_char('\n')?;
                    spaces(w, body)?;
                    w.write_str(part)?;
                    action_lines(c, w, body, &["else"])?;
                }
            }
            close(c, w)
        }
        "while" | "loop-for-count" | "progn$" | "foreach" => {
            c.next();
            c.next();
            write!(w, "({kw} ")?;
            if kw == "foreach" {
                let v = c.next();
                write_token(c, w, v)?;
                w.write_char(' ')?;
            }
            // a `(?var ...)` range or list spec is followed by a space; an expression
            // is not
            let spec = kw != "while"
                && c.peek(0).tok == Tok::LParen
                && matches!(c.peek(1).tok, Tok::SfVar(_));
            flat(c, w)?;
            if spec {
                w.write_char(' ')?;
            }
            // `while` and `loop-for-count` keep `do` on their line; `progn$` and
            // `foreach` print it as the first line of their body
            if is_sym(c.peek(0), "do") && matches!(kw, "while" | "loop-for-count") {
                c.next();
                w.write_str(" do")?;
            }
            action_lines(c, w, body, &[])?;
            close(c, w)
        }
        // a fact-set query: its restrictions on its line, then the query and each
        // action on a line of its own, indented by 3 (CLIPS's ParseQueryNoAction and
        // ParseQueryAction)
        #[cfg(feature = "extras")]
        "any-factp"
        | "find-fact"
        | "find-all-facts"
        | "do-for-fact"
        | "do-for-all-facts"
        | "delayed-do-for-all-facts" => {
            c.next();
            c.next();
            write!(w, "({kw} ")?;
            flat(c, w)?;
            action_lines(c, w, body, &[])?;
            close(c, w)
        }
        "progn" => {
            c.next();
            c.next();
            w.write_str("(progn")?;
            action_lines(c, w, body, &[])?;
            close(c, w)
        }
        "switch" => {
            c.next();
            c.next();
            w.write_str("(switch ")?;
            flat(c, w)?;
            while c.peek(0).tok == Tok::LParen {
                w.write_char('\n')?;
                spaces(w, body)?;
                c.next();
                let k = c.next();
                write!(w, "(")?;
                write_token(c, w, k)?;
                w.write_char(' ')?;
                if is_sym(k, "case") {
                    flat(c, w)?;
                    if is_sym(c.peek(0), "then") {
                        c.next();
                        w.write_str(" then")?;
                    } else if cfg!(feature = "parser")
                        && !matches!(c.peek(0).tok, Tok::RParen | Tok::Eof | Tok::Bad)
                    {
                        // a case CLIPS stopped reading where `then` was due: on its line
                        w.write_char(' ')?;
                        flat(c, w)?;
                    }
                }
                action_lines(c, w, body + 3, &[])?;
                close(c, w)?;
            }
            close(c, w)
        }
        "assert" => {
            // several facts: one per line, aligned under the first
            c.next();
            c.next();
            w.write_str("(assert")?;
            // (a control form in a fact indents from the facts' column)
            #[cfg(feature = "extras")]
            {
                c.indent = col + 8;
            }
            // (a field that is no fact, which CLIPS stopped reading at, too)
            let mut first = true;
            while !matches!(c.peek(0).tok, Tok::RParen | Tok::Eof | Tok::Bad) {
                if first {
                    w.write_char(' ')?;
                } else {
                    w.write_char('\n')?;
                    spaces(w, col + 8)?;
                }
                first = false;
                flat_as(c, w, true)?;
            }
            close(c, w)
        }
        _ => flat(c, w),
    }
}

/// `(KEYWORD MODULE::name`, for the construct whose source `c` starts at (left after
/// its name): a name written with its module keeps it; another is in `module`, the
/// one the construct was defined in.
fn write_head(c: &mut Cursor<'_>, w: &mut dyn Write, keyword: &str, module: &str) -> fmt::Result {
    c.next(); // (
    c.next(); // the keyword
    let name = c.next();
    let name = c.text(name);
    if crate::module::split_qualified(name).is_some() {
        write!(w, "({keyword} {name}")
    } else {
        write!(w, "({keyword} {module}::{name}")
    }
}

/// `write_head`, and the construct's comment if it has one, on the same line.
fn write_head_comment(
    c: &mut Cursor<'_>,
    w: &mut dyn Write,
    keyword: &str,
    module: &str,
) -> fmt::Result {
    write_head(c, w, keyword, module)?;
    if let Tok::Str(_) = c.peek(0).tok {
        let t = c.next();
        w.write_char(' ')?;
        write_token(c, w, t)?;
    }
    Ok(())
}

/// Writes the pretty-printed form of the defrule whose source is `src`.
pub fn write_defrule(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    write_defrule_upto(src, module, w)?;
    w.write_char(')')
}

/// The pretty-printed form of the defrule whose source `src` holds, without its last
/// `)`: what CLIPS shows after `ERROR:` for a rule it stopped reading where `src` ends.
pub fn write_defrule_upto(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    write_head_comment(&mut c, w, "defrule", module)?;
    loop {
        let t = c.peek(0);
        match t.tok {
            Tok::Eof | Tok::Bad | Tok::RParen => break,
            Tok::Symbol("=>") => break,
            _ => {}
        }
        w.write_str("\n   ")?;
        ce(&mut c, w, 3)?;
    }
    w.write_str("\n   =>")?;
    if is_sym(c.peek(0), "=>") {
        c.next();
    }
    action_lines(&mut c, w, 3, &[])
}

/// Whether a defrule's text holds its `=>` (at the rule's top level).
pub fn has_arrow(src: &str) -> bool {
    let mut c = Cursor::new(src);
    let mut depth = 0u32;
    loop {
        let t = c.next();
        match t.tok {
            Tok::Eof | Tok::Bad => return false,
            Tok::LParen => depth += 1,
            Tok::RParen => depth = depth.saturating_sub(1),
            Tok::Symbol("=>") if depth == 1 => return true,
            _ => {}
        }
    }
}

/// What CLIPS shows after `ERROR:` for a rule it stopped reading in its conditions,
/// where `src` ends (inside a CE): the head, the comment, and the CEs one per line.
pub fn write_defrule_lhs_upto(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    write_head_comment(&mut c, w, "defrule", module)?;
    while !matches!(c.peek(0).tok, Tok::Eof | Tok::Bad | Tok::RParen) {
        w.write_str("\n   ")?;
        ce(&mut c, w, 3)?;
    }
    Ok(())
}

/// Writes the pretty-printed form of the deffunction whose source is `src`
/// (`ppdeffunction`).
pub fn write_deffunction(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    write_deffunction_upto(src, module, w)?;
    w.write_char(')')
}

/// Writes the pretty-printed form of one defglobal variable (`ppdefglobal`) whose
/// source `src` starts at its `?*name*`: `(defglobal MODULE ?*name* = value)`, the
/// value expression on one line.
pub fn write_defglobal(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    let name = c.next();
    write!(w, "(defglobal {module} {} =", c.text(name))?;
    if is_sym(c.peek(0), "=") {
        c.next();
    }
    if !matches!(c.peek(0).tok, Tok::Eof | Tok::Bad | Tok::RParen) {
        w.write_char(' ')?;
        flat(&mut c, w)?;
    }
    w.write_char(')')
}

/// What CLIPS shows after `ERROR:` for a deffunction it stopped reading where `src`
/// ends: `(deffunction MAIN::name`, the parameters on a line, one action per line.
pub fn write_deffunction_upto(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    write_head_comment(&mut c, w, "deffunction", module)?;
    w.write_str("\n   ")?;
    flat(&mut c, w)?;
    action_lines(&mut c, w, 3, &[])
}

/// What CLIPS shows after `ERROR:` for a deffacts it stopped reading where `src`
/// ends: `(deffacts MAIN::name`, then each fact on a line of its own indented by 3.
pub fn write_deffacts_upto(src: &str, module: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    write_head_comment(&mut c, w, "deffacts", module)?;
    while c.peek(0).tok == Tok::LParen {
        w.write_str("\n   ")?;
        flat_as(&mut c, w, true)?;
    }
    // an item that is no fact, where CLIPS stopped (`[PRNTUTIL2]` for RHS patterns)
    if !matches!(c.peek(0).tok, Tok::Eof | Tok::Bad | Tok::RParen) {
        let t = c.next();
        w.write_str("\n   ")?;
        write_token(&c, w, t)?;
    }
    Ok(())
}

/// What CLIPS shows after `ERROR:` of a defglobal whose value it stopped reading
/// where `src` (from the global's name on) ends: `?*x* = (f 1 (`, tokens as its
/// pretty-print buffer joins them, control forms over lines.
#[cfg(feature = "parser")]
pub fn write_defglobal_value_upto(src: &str, w: &mut dyn Write) -> fmt::Result {
    let mut c = Cursor::new(src);
    let name = c.next();
    write_token(&c, w, name)?;
    while !matches!(c.peek(0).tok, Tok::Eof | Tok::Bad) {
        w.write_char(' ')?;
        // (a control form's actions on lines of their own)
        #[cfg(feature = "extras")]
        if nested_control(&mut c) {
            let col = c.indent;
            action(&mut c, w, col)?;
            continue;
        }
        flat(&mut c, w)?;
    }
    Ok(())
}

/// The start of the last global named at the top of the defglobal holding byte `at`
/// of `src` (the global whose value CLIPS was reading there), if any.
#[cfg(feature = "parser")]
pub fn defglobal_name_before(src: &str, at: usize) -> Option<usize> {
    let mut lx = Lexer::new(src);
    let mut depth = 0u32;
    let mut found = None;
    loop {
        let t = lx.next_token();
        if matches!(t.tok, Tok::Eof | Tok::Bad) || t.start >= at {
            return found;
        }
        match t.tok {
            Tok::LParen => {
                if depth == 0 {
                    found = None;
                }
                depth += 1;
            }
            Tok::RParen => depth = depth.saturating_sub(1),
            Tok::Global(_) if depth == 1 => found = Some(t.start),
            _ => {}
        }
    }
}

/// What CLIPS shows after `ERROR:` for a deftemplate it rejected: the construct as
/// its pretty-print buffer held it (`(deftemplate MAIN::name`, each slot on a line of
/// its own indented by 3, tokens one space apart), from the construct that `src`
/// holds up to the token ending at byte `end`, that last token joined by `tail`.
pub fn write_deftemplate_echo(
    src: &str,
    end: usize,
    tail: crate::error::EchoTail,
    module: &str,
    w: &mut dyn Write,
) -> fmt::Result {
    use crate::error::EchoTail;
    let mut c = Cursor::new(src);
    // the construct the error is in: the last top-level `(` before it
    let mut start = 0;
    let mut depth = 0u32;
    loop {
        let t = c.next();
        if matches!(t.tok, Tok::Eof | Tok::Bad) || t.start >= end {
            break;
        }
        match t.tok {
            Tok::LParen => {
                if depth == 0 {
                    start = t.start;
                }
                depth += 1;
            }
            Tok::RParen => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    let mut c = Cursor::new(src.get(start..end).unwrap_or(""));
    write_head(&mut c, w, "deftemplate", module)?;
    let mut depth = 1u32;
    let mut after_open = false;
    // (a comment right after the name stays on its line)
    let mut comment_due = true;
    loop {
        let t = c.next();
        if matches!(t.tok, Tok::Eof | Tok::Bad) {
            break;
        }
        let last = t.end + start >= end;
        let comment = comment_due && matches!(t.tok, Tok::Str(_));
        comment_due = false;
        // a slot, and a second comment or a bare word where a slot is due, start a
        // line of their own
        let own_line = depth == 1 && t.tok != Tok::RParen && !comment;
        match t.tok {
            _ if own_line => w.write_str("\n   ")?,
            Tok::RParen if last && tail == EchoTail::SpaceBefore => w.write_char(' ')?,
            Tok::RParen => {}
            _ if after_open || (last && tail == EchoTail::Glued) => {}
            _ => w.write_char(' ')?,
        }
        write_token(&c, w, t)?;
        if last && tail == EchoTail::SpaceAfter {
            w.write_char(' ')?;
        }
        after_open = t.tok == Tok::LParen;
        match t.tok {
            Tok::LParen => depth += 1,
            Tok::RParen => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::String;

    fn pp(src: &str) -> String {
        let mut s = String::new();
        write_defrule(src, "MAIN", &mut s).unwrap();
        s
    }

    #[test]
    fn patterns_and_actions_one_per_line() {
        assert_eq!(
            pp("(defrule alpha (a ?x) => (printout t ?x crlf))"),
            "(defrule MAIN::alpha\n   (a ?x)\n   =>\n   (printout t ?x crlf))"
        );
        assert_eq!(pp("(defrule r4 => )"), "(defrule MAIN::r4\n   =>)");
    }

    #[test]
    fn connectives_align_their_ces() {
        assert_eq!(
            pp("(defrule g \"c\" (exists (d)) (or (a ?x) (b ?x)) (not (and (e) (f))) => (halt))"),
            "(defrule MAIN::g \"c\"\n   (exists\n        (d))\n   (or  (a ?x)\n        (b ?x))\n   (not (and (e)\n             (f)))\n   =>\n   (halt))"
        );
    }

    #[test]
    fn constraints_stay_glued_and_numbers_reprinted() {
        assert_eq!(
            pp("(defrule r ?f <- (a  ?x&~3|4  $?rest) (c ?y&:(> ?y 1)&~5) => (printout t 2.50 crlf))"),
            "(defrule MAIN::r\n   ?f <- (a ?x&~3|4 $?rest)\n   (c ?y&:(> ?y 1)&~5)\n   =>\n   (printout t 2.5 crlf))"
        );
    }

    /// Transcribed from CLIPS 6.30: a `=` or `:` glued to the call after it stays glued
    /// only as a constraint in a pattern or fact.
    #[test]
    fn equals_glued_to_a_call_is_spaced_outside_facts() {
        assert_eq!(
            pp("(defrule r (test (=(+ 1 1) 2)) (b =(+ 1 1)) => (assert (e =(+ 1 1))) (printout t =(+ 1 2) :(+ 1 2)) (if (=(+ 1 1) 2) then (halt)))"),
            "(defrule MAIN::r
   (test (= (+ 1 1) 2))
   (b =(+ 1 1))
   =>
   (assert (e =(+ 1 1)))
   (printout t = (+ 1 2) : (+ 1 2))
   (if (= (+ 1 1) 2)
      then
      (halt)))"
        );
    }

    /// Transcribed from CLIPS 6.30's `ppdeffunction` and `ppdefglobal`.
    #[test]
    fn deffunctions_and_defglobals_as_clips_prints_them() {
        let mut s = String::new();
        write_deffunction(
            "(deffunction g \"c\" (?x $?r) (bind ?y   2.50) ; note\n ?y)",
            "MAIN",
            &mut s,
        )
        .unwrap();
        assert_eq!(
            s,
            "(deffunction MAIN::g \"c\"\n   (?x $?r)\n   (bind ?y 2.5)\n   ?y)"
        );
        s.clear();
        write_deffunction("(deffunction A::h ())", "B", &mut s).unwrap();
        assert_eq!(s, "(deffunction A::h\n   ())");
        s.clear();
        write_defglobal("?*y* =\n (+ 1   (* 2 3)) ?*z* = 4", "A", &mut s).unwrap();
        assert_eq!(s, "(defglobal A ?*y* = (+ 1 (* 2 3)))");
        s.clear();
        write_defglobal("?*x* = 1.50", "MAIN", &mut s).unwrap();
        assert_eq!(s, "(defglobal MAIN ?*x* = 1.5)");
    }

    /// `do` and list specs in the loops, as CLIPS 6.30 prints them.
    #[test]
    fn loops_print_do_and_specs_as_clips() {
        let src = "(defrule r => (foreach ?v (create$ a b) do (printout t ?v)) (progn$ (?v ?l) do (x)) (progn$ ?l (x)) (loop-for-count 3 do (x)) (loop-for-count (?i 1 3) do (x)) (loop-for-count (+ 1 2) (x)))";
        assert_eq!(
            pp(src),
            "(defrule MAIN::r\n   =>\n   (foreach ?v (create$ a b)\n      do\n      (printout t ?v))\n   (progn$ (?v ?l) \n      do\n      (x))\n   (progn$ ?l\n      (x))\n   (loop-for-count 3 do\n      (x))\n   (loop-for-count (?i 1 3)  do\n      (x))\n   (loop-for-count (+ 1 2)\n      (x)))"
        );
    }

    /// Transcribed from CLIPS 6.30's `ppdefrule` of the same source.
    #[test]
    fn control_actions_indent_their_bodies() {
        let src = "(defrule r1 (or (a ?x) (b ?x)) (and (c) (d)) (not (and (e) (f))) (test (> 1 0)) => (if (> 1 0) then (printout t \"yes\"   crlf) (assert (g)) else (printout t no crlf)) (while (> 0 1) do (bind ?x 1)) (bind ?y (+ 1 2)))";
        assert_eq!(
            pp(src),
            "(defrule MAIN::r1\n   (or  (a ?x)\n        (b ?x))\n   (and (c)\n        (d))\n   (not (and (e)\n             (f)))\n   (test (> 1 0))\n   =>\n   (if (> 1 0)\n      then\n      (printout t \"yes\" crlf)\n      (assert (g))\n      else\n      (printout t no crlf))\n   (while (> 0 1) do\n      (bind ?x 1))\n   (bind ?y (+ 1 2)))"
        );
        let src = "(defrule r2\n  ?f <- (a  ?x&~3|4  $?rest)   ; comment\n  (exists (b ?x) (c ?x))\n  (c ?y&:(> ?y 1)&~5)\n  (not (d))\n=>\n  (modify ?f (a 1))\n  (loop-for-count (?i 1 3) do (printout t ?i crlf))\n  (progn$ (?v $?rest) (printout t ?v))\n  (switch ?x (case 1 then (printout t one)) (default (printout t other))))";
        assert_eq!(
            pp(src),
            "(defrule MAIN::r2\n   ?f <- (a ?x&~3|4 $?rest)\n   (exists\n        (b ?x)\n        (c ?x))\n   (c ?y&:(> ?y 1)&~5)\n   (not (d))\n   =>\n   (modify ?f (a 1))\n   (loop-for-count (?i 1 3)  do\n      (printout t ?i crlf))\n   (progn$ (?v $?rest) \n      (printout t ?v))\n   (switch ?x\n      (case 1 then\n         (printout t one))\n      (default \n         (printout t other))))"
        );
    }
}
