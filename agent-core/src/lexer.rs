//! Tokenizer for CLIPS source text, tracking 1-based line and column.

/// A token kind; texts borrow from the source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tok<'a> {
    LParen,
    RParen,
    Symbol(&'a str),
    /// String contents without quotes, escapes still in place.
    Str(&'a str),
    Int(i64),
    /// An integer literal beyond 64 bits: CLIPS warns and clamps it.
    IntOverflow(i64),
    Float(f64),
    /// `?name`
    SfVar(&'a str),
    /// `$?name`
    MfVar(&'a str),
    /// `?*name*`
    Global(&'a str),
    /// `?`
    SfWild,
    /// `$?`
    MfWild,
    Amp,
    Bar,
    Tilde,
    Eof,
    /// An unterminated string or other unreadable input.
    Bad,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Token<'a> {
    pub tok: Tok<'a>,
    pub line: u32,
    pub col: u32,
    /// Byte offsets of the token in the source.
    pub start: usize,
    pub end: usize,
}

#[derive(Clone)]
pub struct Lexer<'a> {
    src: &'a str,
    pos: usize,
    line: u32,
    col: u32,
}

/// The first `bind` in `b` at or after `at`: a skip on the byte under the needle's
/// end (its four letters differ), without `str::find`'s searcher set-up per call.
fn find_bind(b: &[u8], at: usize) -> Option<usize> {
    let mut i = at;
    while let Some(&last) = b.get(i + 3) {
        i += match last {
            b'd' if b[i..i + 3] == *b"bin" => return Some(i),
            b'n' => 1,
            b'i' => 2,
            b'b' => 3,
            _ => 4,
        };
    }
    None
}

/// Whether `text` (after a `(`) starts `bind ?x` or `bind $?x` with `x` no global.
fn binds_a_local(text: &[u8]) -> bool {
    let mut i = 0;
    while matches!(text.get(i), Some(b) if b.is_ascii_whitespace()) {
        i += 1;
    }
    let Some(rest) = text.get(i..).and_then(|t| t.strip_prefix(b"bind")) else {
        return false;
    };
    let mut i = 0;
    while matches!(rest.get(i), Some(b) if b.is_ascii_whitespace()) {
        i += 1;
    }
    if i == 0 {
        return false;
    }
    if rest.get(i) == Some(&b'$') {
        i += 1;
    }
    rest.get(i) == Some(&b'?') && rest.get(i + 1) != Some(&b'*')
}

/// Where the blanks and comments from byte `i` of `b` end, as `Lexer` skips them.
pub fn skip_blanks(b: &[u8], mut i: usize) -> usize {
    loop {
        match b.get(i) {
            Some(c) if c.is_ascii_whitespace() => i += 1,
            Some(b';') => {
                while matches!(b.get(i), Some(&c) if c != b'\n') {
                    i += 1;
                }
            }
            _ => return i,
        }
    }
}

/// Where a word from byte `i` ends (`Lexer::word`).
fn word_end(b: &[u8], mut i: usize) -> usize {
    if matches!(b.get(i), Some(&c) if !is_delim(c)) {
        i += 1;
    }
    while matches!(b.get(i), Some(&c) if !is_delim(c) && c != b'<') {
        i += 1;
    }
    i
}

/// Where a string whose opening quote is at `i` ends (after its closing quote); None
/// when it does not (`Tok::Bad`).
fn string_end(b: &[u8], mut i: usize) -> Option<usize> {
    i += 1;
    loop {
        match b.get(i)? {
            b'\\' => i += 2,
            b'"' => return Some(i + 1),
            _ => i += 1,
        }
    }
}

/// Byte length of the first complete top-level item in the text `b` (a list, or an
/// atom once a character follows it), leading blanks and comments included; None
/// while more input is needed. What reading it with `Lexer` would find, from the
/// bytes alone: inside a list only parentheses, strings and comments matter (the
/// lexer starts a string or a comment at every `"` and `;` outside them).
pub fn item_end(b: &[u8]) -> Option<usize> {
    let mut i = skip_blanks(b, 0);
    let end = match *b.get(i)? {
        b')' => return Some(i + 1),
        b'(' => {
            let mut depth = 0usize;
            loop {
                match *b.get(i)? {
                    b'(' => depth += 1,
                    b')' => {
                        depth -= 1;
                        if depth == 0 {
                            return Some(i + 1);
                        }
                    }
                    b'"' => {
                        i = string_end(b, i)?;
                        continue;
                    }
                    b';' => {
                        i = skip_blanks(b, i);
                        continue;
                    }
                    _ => {}
                }
                i += 1;
            }
        }
        b'"' => string_end(b, i)?,
        b'&' | b'|' | b'~' => i + 1,
        b'?' | b'$' if b[i] == b'?' || b.get(i + 1) == Some(&b'?') => {
            let j = if b[i] == b'?' { i + 1 } else { i + 2 };
            match b.get(j) {
                Some(&c) if c.is_ascii_alphabetic() || c >= 0x80 || c == b'*' => word_end(b, j),
                _ => j,
            }
        }
        _ => word_end(b, i),
    };
    (end < b.len()).then_some(end)
}

/// Host: where `item_end_resumed`'s walk through an unfinished list stopped: the
/// byte it goes on from and the list depth there (`at` 0: nothing walked yet; a walk
/// stops only after the list's opening parenthesis, so never at 0).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ItemScan {
    at: usize,
    depth: usize,
}

#[cfg(feature = "host-speedups")]
impl ItemScan {
    /// A new item: nothing walked yet.
    pub const NEW: ItemScan = ItemScan { at: 0, depth: 0 };
}

/// Host: `item_end` of a text that grows between calls (a file read piece by piece),
/// with the same result. `scan` keeps how far the walk through an unfinished list
/// got (stopping before a string or comment that may go on), so each byte of a long
/// item is walked about once, not once per piece read: `load` of a 100 KB rule
/// walked it once per 4 KB read, quadratic. `b` must be the text of the call that
/// left `scan` with bytes added at its end; `ItemScan::NEW` for another item.
#[cfg(feature = "host-speedups")]
pub fn item_end_resumed(b: &[u8], scan: &mut ItemScan) -> Option<usize> {
    let (mut i, mut depth) = (scan.at, scan.depth);
    if i == 0 {
        i = skip_blanks(b, 0);
        if *b.get(i)? != b'(' {
            // an atom or a stray `)`: short, nothing to keep
            return item_end(b);
        }
    }
    loop {
        let Some(&c) = b.get(i) else {
            *scan = ItemScan { at: i, depth };
            return None;
        };
        match c {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i + 1);
                }
            }
            b'"' => match string_end(b, i) {
                Some(j) => {
                    i = j;
                    continue;
                }
                None => {
                    *scan = ItemScan { at: i, depth };
                    return None;
                }
            },
            b';' => {
                let j = skip_blanks(b, i);
                if j >= b.len() {
                    // the comment (or blanks after it) may go on
                    *scan = ItemScan { at: i, depth };
                    return None;
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
}

/// Characters in UTF-8 bytes `b` (the bytes that start one).
fn chars(b: &[u8]) -> u32 {
    b.iter().filter(|&&c| (c & 0xC0) != 0x80).count() as u32
}

fn is_delim(b: u8) -> bool {
    matches!(
        b,
        b' ' | b'\t' | b'\r' | b'\n' | b'\x0c' | b'(' | b')' | b'"' | b';' | b'&' | b'|' | b'~'
    )
}

impl<'a> Lexer<'a> {
    pub fn new(src: &'a str) -> Self {
        Lexer {
            src,
            pos: 0,
            line: 1,
            col: 1,
        }
    }

    pub fn source(&self) -> &'a str {
        self.src
    }

    pub fn pos(&self) -> usize {
        self.pos
    }

    /// The token starting at byte `start` of the source, with its line and column (for
    /// an error found after the reader has moved on).
    pub fn token_at(&self, start: usize) -> Token<'a> {
        // a byte inside a character (a caller's `end - 1`) reads from its first byte
        let mut start = start.min(self.src.len());
        while !self.src.is_char_boundary(start) {
            start -= 1;
        }
        let before = self.src.as_bytes().get(..start).unwrap_or(&[]);
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let mut at = Lexer {
            src: self.src,
            pos: start,
            line: 1 + before.iter().filter(|&&b| b == b'\n').count() as u32,
            col: 1 + before[line_start..]
                .iter()
                .filter(|&&b| (b & 0xC0) != 0x80)
                .count() as u32,
        };
        at.next_token()
    }

    fn bump(&mut self) -> Option<u8> {
        let b = *self.src.as_bytes().get(self.pos)?;
        self.pos += 1;
        if b == b'\n' {
            self.line += 1;
            self.col = 1;
        } else if (b & 0xC0) != 0x80 {
            self.col += 1;
        }
        Some(b)
    }

    fn peek(&self) -> Option<u8> {
        self.src.as_bytes().get(self.pos).copied()
    }

    fn peek2(&self) -> Option<u8> {
        self.src.as_bytes().get(self.pos + 1).copied()
    }

    /// Skips blanks and comments. Byte by byte as `bump` would, but a comment's
    /// columns are counted only when no newline ends it (a newline sets them anew).
    fn skip_space(&mut self) {
        let b = self.src.as_bytes();
        let mut i = self.pos;
        loop {
            match b.get(i) {
                Some(b'\n') => {
                    self.line += 1;
                    self.col = 1;
                    i += 1;
                }
                Some(b' ' | b'\t' | b'\r' | b'\x0c') => {
                    self.col += 1;
                    i += 1;
                }
                Some(b';') => {
                    let s = i;
                    while matches!(b.get(i), Some(&c) if c != b'\n') {
                        i += 1;
                    }
                    if i == b.len() {
                        self.col += chars(&b[s..]);
                    }
                }
                _ => break,
            }
        }
        self.pos = i;
    }

    /// A symbol or number: up to a delimiter, or a `<` after its first character (as
    /// in CLIPS, `4<56` is `4` and `<56`, `?f<-` is `?f` and `<-`).
    fn word(&mut self) -> &'a str {
        let b = self.src.as_bytes();
        let s = self.pos;
        let mut i = s;
        // (the first character may be `<`: one step before the loop keeps its test
        // as cheap as a delimiter's)
        if matches!(b.get(i), Some(&c) if !is_delim(c)) {
            i += 1;
        }
        // no newline (a delimiter) inside: the column moves by the characters, which
        // are the bytes unless one is not ASCII
        let mut high = 0u8;
        while let Some(&c) = b.get(i) {
            if is_delim(c) || c == b'<' {
                break;
            }
            high |= c;
            i += 1;
        }
        self.col += if (high | b.get(s).copied().unwrap_or(0)) < 0x80 {
            (i - s) as u32
        } else {
            chars(&b[s..i])
        };
        self.pos = i;
        &self.src[s..i]
    }

    /// Whether the text from byte `from` to the `)` closing the list it is in may bind
    /// a local variable: holds `(bind ?x` or `(bind $?x` (not a global `?*x*`) outside
    /// strings and comments. A look far cheaper than reading the tokens, before the
    /// parser reads them twice.
    /// Where the first `bind` from byte `from` on that may bind a local starts (`(`,
    /// spaces, `bind`, spaces, `?x` or `$?x`, `x` no global), by the text alone
    /// (strings and comments not told apart: `binds_a_local_before_close` finds a
    /// subset); `usize::MAX` when there is none. A substring search, far cheaper per
    /// byte than that scan.
    pub fn local_bind_candidate(&self, from: usize) -> usize {
        let b = self.src.as_bytes();
        let mut at = from;
        while let Some(p) = find_bind(b, at) {
            let mut q = p;
            while q > 0 && b[q - 1].is_ascii_whitespace() {
                q -= 1;
            }
            if q > 0 && b[q - 1] == b'(' && binds_a_local(&b[q..]) {
                return p;
            }
            at = p + 4;
        }
        usize::MAX
    }

    pub fn binds_a_local_before_close(&self, from: usize) -> bool {
        let b = self.src.as_bytes();
        let mut i = from;
        let mut depth = 0u32;
        while let Some(&c) = b.get(i) {
            match c {
                b'"' => {
                    i += 1;
                    while let Some(&d) = b.get(i) {
                        if d == b'"' {
                            break;
                        }
                        i += if d == b'\\' { 2 } else { 1 };
                    }
                }
                b';' => {
                    while matches!(b.get(i), Some(&d) if d != b'\n') {
                        i += 1;
                    }
                }
                b'(' => {
                    depth += 1;
                    if binds_a_local(b.get(i + 1..).unwrap_or(&[])) {
                        return true;
                    }
                }
                b')' if depth == 0 => return false,
                b')' => depth -= 1,
                _ => {}
            }
            i += 1;
        }
        false
    }

    pub fn next_token(&mut self) -> Token<'a> {
        self.skip_space();
        let (line, col, start) = (self.line, self.col, self.pos);
        let tok = match self.peek() {
            None => Tok::Eof,
            Some(b'(') => {
                self.bump();
                Tok::LParen
            }
            Some(b')') => {
                self.bump();
                Tok::RParen
            }
            Some(b'&') => {
                self.bump();
                Tok::Amp
            }
            Some(b'|') => {
                self.bump();
                Tok::Bar
            }
            Some(b'~') => {
                self.bump();
                Tok::Tilde
            }
            Some(b'"') => self.string(),
            Some(b'?') => {
                self.bump();
                self.variable(false)
            }
            Some(b'$') if self.peek2() == Some(b'?') => {
                self.bump();
                self.bump();
                self.variable(true)
            }
            Some(_) => {
                let w = self.word();
                classify_word(w)
            }
        };
        Token {
            tok,
            line,
            col,
            start,
            end: self.pos,
        }
    }

    fn string(&mut self) -> Tok<'a> {
        self.bump();
        let s = self.pos;
        loop {
            match self.bump() {
                None => return Tok::Bad,
                Some(b'\\') => {
                    self.bump();
                }
                Some(b'"') => return Tok::Str(&self.src[s..self.pos - 1]),
                Some(_) => {}
            }
        }
    }

    fn variable(&mut self, multi: bool) -> Tok<'a> {
        // CLIPS's scanner starts a variable name only with a letter, a non-ASCII
        // character or `*`: `?1st` is the wildcard `?` and then the symbol `1st`.
        let name = match self.peek() {
            Some(b) if b.is_ascii_alphabetic() || b >= 0x80 || b == b'*' => self.word(),
            _ => "",
        };
        if name.is_empty() {
            return if multi { Tok::MfWild } else { Tok::SfWild };
        }
        if !multi && name.len() >= 2 && name.starts_with('*') && name.ends_with('*') {
            return Tok::Global(&name[1..name.len() - 1]);
        }
        if multi {
            Tok::MfVar(name)
        } else {
            Tok::SfVar(name)
        }
    }
}

/// Numbers as CLIPS reads them; anything else is a symbol.
pub fn classify_word(w: &str) -> Tok<'_> {
    let b = w.as_bytes();
    // (most words start with a letter: no number)
    if matches!(b.first(), Some(c) if c.is_ascii_alphabetic()) {
        return Tok::Symbol(w);
    }
    let digits_start = usize::from(matches!(b.first(), Some(b'+') | Some(b'-')));
    let body = &b[digits_start..];
    if body.is_empty() {
        return Tok::Symbol(w);
    }
    if body.iter().all(|c| c.is_ascii_digit()) {
        return match w.parse::<i64>() {
            Ok(i) => Tok::Int(i),
            Err(_) => Tok::IntOverflow(if w.starts_with('-') {
                i64::MIN
            } else {
                i64::MAX
            }),
        };
    }
    // float: digits with one '.', optional exponent; must contain a digit
    let mut seen_digit = false;
    let mut i = 0;
    while i < body.len() && body[i].is_ascii_digit() {
        seen_digit = true;
        i += 1;
    }
    if i < body.len() && body[i] == b'.' {
        i += 1;
        while i < body.len() && body[i].is_ascii_digit() {
            seen_digit = true;
            i += 1;
        }
    }
    if !seen_digit {
        return Tok::Symbol(w);
    }
    if i < body.len() && (body[i] == b'e' || body[i] == b'E') {
        i += 1;
        if i < body.len() && (body[i] == b'+' || body[i] == b'-') {
            i += 1;
        }
        let s = i;
        while i < body.len() && body[i].is_ascii_digit() {
            i += 1;
        }
        if i == s {
            return Tok::Symbol(w);
        }
    }
    if i != body.len() {
        return Tok::Symbol(w);
    }
    match w.parse::<f64>() {
        Ok(f) => Tok::Float(f),
        Err(_) => Tok::Symbol(w),
    }
}

/// Whether `s` is a construct keyword of CLIPS 6.30 (those of its object system too,
/// which the parser refuses by name): what starts a construct, and no deffunction name.
pub fn is_construct_keyword(s: &str) -> bool {
    matches!(
        s,
        "deftemplate"
            | "defrule"
            | "deffacts"
            | "deffunction"
            | "defglobal"
            | "defmodule"
            | "defgeneric"
            | "defmethod"
            | "defclass"
            | "defmessage-handler"
            | "definstances"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> [Tok<'_>; 8] {
        let mut l = Lexer::new(s);
        let mut out = [Tok::Eof; 8];
        for t in out.iter_mut() {
            *t = l.next_token().tok;
        }
        out
    }

    #[test]
    fn lexes_constraints_and_numbers() {
        let t = toks("(a ?y&~?x $?r 1.5e3 -7 \"s\\\"q\")");
        assert_eq!(t[0], Tok::LParen);
        assert_eq!(t[1], Tok::Symbol("a"));
        assert_eq!(t[2], Tok::SfVar("y"));
        assert_eq!(t[3], Tok::Amp);
        assert_eq!(t[4], Tok::Tilde);
        assert_eq!(t[5], Tok::SfVar("x"));
        assert_eq!(t[6], Tok::MfVar("r"));
        assert_eq!(t[7], Tok::Float(1500.0));
        let t = toks("?*g* ? $? 1. .5 - e5 ;c\n x");
        assert_eq!(t[0], Tok::Global("g"));
        assert_eq!(t[1], Tok::SfWild);
        assert_eq!(t[2], Tok::MfWild);
        assert_eq!(t[3], Tok::Float(1.0));
        assert_eq!(t[4], Tok::Float(0.5));
        assert_eq!(t[5], Tok::Symbol("-"));
        assert_eq!(t[6], Tok::Symbol("e5"));
        assert_eq!(t[7], Tok::Symbol("x"));
    }

    #[test]
    fn a_bind_of_a_local_is_seen_before_the_closing_paren() {
        let sees = |t: &str| Lexer::new(t).binds_a_local_before_close(0);
        assert!(sees("(printout t ?x) (bind ?x 1))"));
        assert!(sees("(while TRUE (bind\n $?y (create$))))"));
        assert!(sees("( bind ?z 2))"));
        // a global, a string, a comment, a longer name, a later construct
        assert!(!sees("(bind ?*g* 1))"));
        assert!(!sees("(printout t \"(bind ?x 1)\"))"));
        assert!(!sees("; (bind ?x 1)\n(printout t 1))"));
        assert!(!sees("(binder ?x))"));
        assert!(!sees("(printout t 1)) (defrule r => (bind ?x 1))"));
    }

    #[test]
    fn find_bind_is_the_first_bind_at_or_after_the_start() {
        let texts = [
            "",
            "bin",
            "bind",
            "bbind",
            "bibind",
            "bnbind x",
            "dbind",
            "xbindbind",
            "(bin d) (bind",
        ];
        for t in texts {
            for at in 0..=t.len() + 1 {
                let want = t.get(at..).and_then(|r| r.find("bind")).map(|k| at + k);
                assert_eq!(find_bind(t.as_bytes(), at), want, "{t:?} from {at}");
            }
        }
    }

    #[test]
    fn a_local_bind_candidate_covers_every_bind_the_scan_sees() {
        let cand = |t: &str, from: usize| Lexer::new(t).local_bind_candidate(from);
        // wherever the scan sees a bind, the search finds one at or after the start
        for t in [
            "(printout t ?x) (bind ?x 1))",
            "(while TRUE (bind\n $?y (create$))))",
            "( bind ?z 2))",
        ] {
            assert!(Lexer::new(t).binds_a_local_before_close(0));
            assert_ne!(cand(t, 0), usize::MAX, "{t}");
        }
        assert_eq!(cand("(printout t ?x) (bind ?x 1))", 0), 17);
        // none: globals, a longer name, no `(`, or all of them before the start
        assert_eq!(cand("(bind ?*g* 1)) (binder ?x) bind ?y", 0), usize::MAX);
        assert_eq!(cand("(bind ?x 1) (printout t 1))", 2), usize::MAX);
        // text alone: a bind in a string counts (the scan then decides)
        assert_eq!(cand("(printout t \"(bind ?x 1)\"))", 0), 14);
    }

    /// `item_end` as the tokens say it: what it replaced.
    fn item_end_by_tokens(s: &str) -> Option<usize> {
        let mut lx = Lexer::new(s);
        let mut depth = 0usize;
        loop {
            let t = lx.next_token();
            match t.tok {
                Tok::Eof | Tok::Bad => return None,
                Tok::LParen => depth += 1,
                Tok::RParen => {
                    if depth <= 1 {
                        return Some(t.end);
                    }
                    depth -= 1;
                }
                _ if depth == 0 => return (t.end < s.len()).then_some(t.end),
                _ => {}
            }
        }
    }

    #[test]
    fn an_item_ends_where_its_tokens_do() {
        let texts = [
            "(a b)",
            "  ; c (\n (x \"(\" ; )\n y) z",
            "(a \"b\\\"c)\" d) e",
            "(a (b) c",
            "(a \"b",
            "atom rest",
            "atom",
            "?x<y",
            "?1 z",
            "$?rest)",
            "$a b",
            "\"str\" x",
            "\"str\"",
            "\"open",
            ") x",
            "& y",
            "~",
            "<<a b",
            "?*g* 1",
            "(é \"ü\") ä",
            "; only a comment",
            "",
            "   ",
            "(a;b)\n c)",
            "(printout t \"\\\\\" crlf)",
        ];
        for t in texts {
            for k in 0..=t.len() {
                if let Some(p) = t.get(..k) {
                    assert_eq!(item_end(p.as_bytes()), item_end_by_tokens(p), "{p:?}");
                }
            }
        }
    }

    /// Host: a text read piece by piece (prefixes growing by 1 to 4 bytes), the
    /// resumed walk gives `item_end` of each prefix, strings, comments and escapes
    /// cut anywhere included.
    #[cfg(feature = "host-speedups")]
    #[test]
    fn a_resumed_item_end_is_item_end_of_each_prefix() {
        let texts = [
            "(a b)",
            "  ; c (\n (x \"(\" ; )\n y) z",
            "(a \"b\\\"c)\" d) e",
            "(a (b) c",
            "(a \"b",
            "atom rest",
            "\"str\" x",
            ") x",
            "(é \"ü\") ä",
            "(a;b)\n c)",
            "(a ; one ( \n ; two )\n (b \"x;y\" (c)) ; ) \n ) tail",
            "(printout t \"\\\\\" crlf)",
            "(defrule r (x ?a) => (assert (y \"))\" ?a)) ; (\n (z))\n",
        ];
        for t in texts {
            let b = t.as_bytes();
            for step in 1..=4 {
                let mut scan = ItemScan::NEW;
                let mut k = 0;
                while k < b.len() {
                    k = (k + step).min(b.len());
                    let want = item_end(&b[..k]);
                    // (and on past the end found: a reader wanting the line's rest)
                    assert_eq!(item_end_resumed(&b[..k], &mut scan), want, "{t:?} to {k}");
                }
            }
        }
    }

    #[test]
    fn columns_count_characters_after_comments_and_words() {
        let mut l = Lexer::new("é ab;x\n  cd ; ü\n\tef ; end");
        for want in [(1, 1), (1, 3), (2, 3), (3, 2)] {
            let t = l.next_token();
            assert_eq!((t.line, t.col), want, "{:?}", t.tok);
        }
        let t = l.next_token();
        assert_eq!((t.tok, t.line, t.col), (Tok::Eof, 3, 10));
    }

    #[test]
    fn a_less_than_sign_ends_a_word() {
        let t = toks("4<56 a<b<c <<a ?f<-(x");
        assert_eq!(t[0], Tok::Int(4));
        assert_eq!(t[1], Tok::Symbol("<56"));
        assert_eq!(t[2], Tok::Symbol("a"));
        assert_eq!(t[3], Tok::Symbol("<b"));
        assert_eq!(t[4], Tok::Symbol("<c"));
        assert_eq!(t[5], Tok::Symbol("<"));
        assert_eq!(t[6], Tok::Symbol("<a"));
        assert_eq!(t[7], Tok::SfVar("f"));
        let t = toks("?f<-(x $?r<y ?<");
        assert_eq!(t[1], Tok::Symbol("<-"));
        assert_eq!(t[2], Tok::LParen);
        assert_eq!(t[4], Tok::MfVar("r"));
        assert_eq!(t[5], Tok::Symbol("<y"));
        assert_eq!(t[6], Tok::SfWild);
        assert_eq!(t[7], Tok::Symbol("<"));
    }

    #[test]
    fn a_variable_name_starts_with_a_letter() {
        let t = toks("?1st $?2x ?_a ?-b ?é $?Ж ?*");
        assert_eq!(t[0], Tok::SfWild);
        assert_eq!(t[1], Tok::Symbol("1st"));
        assert_eq!(t[2], Tok::MfWild);
        assert_eq!(t[3], Tok::Symbol("2x"));
        assert_eq!(t[4], Tok::SfWild);
        assert_eq!(t[5], Tok::Symbol("_a"));
        assert_eq!(t[6], Tok::SfWild);
        assert_eq!(t[7], Tok::Symbol("-b"));
        let t = toks("?é $?Ж ?* ?4");
        assert_eq!(t[0], Tok::SfVar("é"));
        assert_eq!(t[1], Tok::MfVar("Ж"));
        assert_eq!(t[2], Tok::SfVar("*"));
        assert_eq!(t[3], Tok::SfWild);
        assert_eq!(t[4], Tok::Int(4));
    }

    #[test]
    fn positions_are_one_based() {
        let mut l = Lexer::new("(a\n  b)");
        l.next_token();
        l.next_token();
        let b = l.next_token();
        assert_eq!((b.line, b.col), (2, 3));
    }

    #[test]
    fn a_token_is_found_again_by_its_start() {
        let src = "(défrule ä\n  (p (x \"é\n\")) ; c\n\t?x <- (q)\n=> )";
        let mut l = Lexer::new(src);
        loop {
            let t = l.next_token();
            let again = l.token_at(t.start);
            assert_eq!(
                (again.tok, again.line, again.col, again.start, again.end),
                (t.tok, t.line, t.col, t.start, t.end)
            );
            if t.tok == Tok::Eof {
                break;
            }
        }
    }
}
