//! CLIPS 6.30's external text manipulation: `fetch`, `toss`, `print-region` and
//! `get-region` (agent-core feature `extras`; the agent image has none of them).
//!
//! A fetched file holds entries between a `<level><M|I>BEGIN-ENTRY-<name>` line and an
//! `END-ENTRY` line (`$$` at a line's start hides the line from the markers, and prints
//! as two blanks); entries of a higher level under a menu entry (`M`) are its topics.
//! `print-region` and `get-region` walk the tree from the file's current menu, which
//! persists between calls (`^` goes up, `?` last names the current menu, no topic goes
//! up once), and print or return the last entry's lines, as CLIPS's `textpro.c` does:
//! a name matches the first sibling whose upper-cased name starts with it, lines are
//! read as `fgets` reads them (at most 255 bytes at a time), and a tree made when a
//! level goes up puts the entry first among its siblings.
//!
//! The engine keeps only the names of the fetched files and each one's current menu
//! ([`TextRegions`], kept across `clear` as in CLIPS); the tree is read again from the
//! file (through [`Host::read_file_at`]) at each call, into the stack, so a file
//! changed after `fetch` is seen as it is now (CLIPS keeps the tree and the offsets
//! it had). At most [`MOST_FILES`] files are fetched at once and a file has at most
//! [`MOST_ENTRIES`] entries, each limit an error naming it.
//!
//! [`Host::read_file_at`]: crate::host::Host::read_file_at

use super::describe::{ArgType, Returns};
use super::{Args, Builtin, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, HostIoError};
use crate::host::{router, Host};
use crate::value::{TextBuf, Value};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("fetch", 1, 1, fetch).args(&[ArgType::SymbolOrString], ArgType::Any).on_error(super::describe::OnError::False),
    Builtin::eager("toss", 1, 1, toss).args(&[ArgType::SymbolOrString], ArgType::Any).returns(Returns::Symbol).on_error(super::describe::OnError::False),
    Builtin::eager("print-region", 2, super::ANY, print_region).args(&[ArgType::Symbol, ArgType::SymbolOrString], ArgType::Any).returns(Returns::Symbol),
    Builtin::eager("get-region", 1, super::ANY, get_region).args(&[ArgType::SymbolOrString], ArgType::Any).returns(Returns::Str),
];

pub const TABLE: super::Table = super::Table::new(FUNCS);

/// CLIPS's `NAMESIZE`: file and entry names are shorter.
const NAMESIZE: usize = 80;
/// Most files fetched at once.
pub const MOST_FILES: usize = 8;
/// Most entries in one fetched file.
pub const MOST_ENTRIES: usize = 512;
/// Most bytes of entry names in one fetched file.
const NAME_BYTES: usize = 8192;
/// Most bytes `get-region` returns.
const MOST_REGION: usize = 16384;
/// No entry.
const NIL: u16 = u16::MAX;

/// One fetched file: its name as `fetch` was given it, and its current menu (the
/// entry's number in file order, or `NIL`).
#[derive(Clone, Copy)]
struct Fetched {
    name: [u8; NAMESIZE],
    len: u8,
    menu: u16,
}

/// The fetched files, in the order they were fetched.
#[derive(Clone, Copy)]
pub struct TextRegions {
    files: [Fetched; MOST_FILES],
    n: u8,
}

impl Default for TextRegions {
    fn default() -> TextRegions {
        TextRegions::new()
    }
}

impl TextRegions {
    pub const fn new() -> TextRegions {
        TextRegions {
            files: [Fetched {
                name: [0; NAMESIZE],
                len: 0,
                menu: NIL,
            }; MOST_FILES],
            n: 0,
        }
    }

    fn find(&self, name: &str) -> Option<usize> {
        self.files[..usize::from(self.n)]
            .iter()
            .position(|f| &f.name[..usize::from(f.len)] == name.as_bytes())
    }

    fn remove(&mut self, i: usize) {
        let n = usize::from(self.n);
        self.files.copy_within(i + 1..n, i);
        self.n -= 1;
    }
}

/// One entry of a file's tree.
#[derive(Clone, Copy)]
struct Entry {
    level: i32,
    menu: bool,
    name: u16,
    name_len: u8,
    /// Where its text starts: the line after its `BEGIN-ENTRY` line.
    offset: u64,
    child: u16,
    parent: u16,
    next: u16,
}

/// A fetched file's entries, read into the stack for one call.
struct Tree {
    e: [Entry; MOST_ENTRIES],
    n: usize,
    topics: u16,
    names: [u8; NAME_BYTES],
    used: usize,
}

impl Tree {
    fn new() -> Tree {
        Tree {
            e: [Entry {
                level: 0,
                menu: false,
                name: 0,
                name_len: 0,
                offset: 0,
                child: NIL,
                parent: NIL,
                next: NIL,
            }; MOST_ENTRIES],
            n: 0,
            topics: NIL,
            names: [0; NAME_BYTES],
            used: 0,
        }
    }

    fn name(&self, i: u16) -> &[u8] {
        let e = &self.e[usize::from(i)];
        &self.names[usize::from(e.name)..usize::from(e.name) + usize::from(e.name_len)]
    }
}

/// A file read as CLIPS's `fgets(buf, 256, fp)` reads it: at most 255 bytes a time,
/// up to and with a newline.
struct Lines<'p> {
    path: &'p str,
    buf: [u8; 1024],
    at: u64,
    len: usize,
    pos: usize,
}

impl<'p> Lines<'p> {
    fn new(path: &'p str, offset: u64) -> Lines<'p> {
        Lines {
            path,
            buf: [0; 1024],
            at: offset,
            len: 0,
            pos: 0,
        }
    }

    /// Where the next chunk starts in the file.
    fn offset(&self) -> u64 {
        self.at + self.pos as u64
    }

    fn byte(&mut self, host: &mut dyn Host) -> Result<Option<u8>, HostIoError> {
        if self.pos == self.len {
            self.at += self.len as u64;
            self.pos = 0;
            self.len = host.read_file_at(self.path, self.at, &mut self.buf)?;
            if self.len == 0 {
                return Ok(None);
            }
        }
        let b = self.buf[self.pos];
        self.pos += 1;
        Ok(Some(b))
    }

    /// The next chunk into `out`: its length, None at the file's end.
    fn chunk(
        &mut self,
        host: &mut dyn Host,
        out: &mut [u8; 256],
    ) -> Result<Option<usize>, HostIoError> {
        let mut n = 0;
        while n < 255 {
            let Some(b) = self.byte(host)? else { break };
            out[n] = b;
            n += 1;
            if b == b'\n' {
                break;
            }
        }
        Ok((n > 0).then_some(n))
    }
}

/// CLIPS's `findstr`: where `t` first starts in `s` (an empty `t` is never found).
fn findstr(s: &[u8], t: &[u8]) -> Option<usize> {
    if t.is_empty() {
        return None;
    }
    s.windows(t.len()).position(|w| w == t)
}

const BDELIM: &[u8] = b"BEGIN-ENTRY-";
const EDELIM: &[u8] = b"END-ENTRY";

/// Why a file could not be fetched (`[TEXTPROn]`, with its line where CLIPS gives one).
enum Bad {
    Open,
    Line(u8, u32, &'static str),
    /// One of our limits.
    Full(&'static str),
}

/// `%d%1s%12s%s` as `sscanf` reads them: the level, the type letter, the marker, the name.
fn scan_header(line: &[u8]) -> Option<(i32, u8, &[u8], &[u8])> {
    let mut i = 0;
    let skip = |i: &mut usize| {
        while *i < line.len() && line[*i].is_ascii_whitespace() {
            *i += 1;
        }
    };
    skip(&mut i);
    let start = i;
    if i < line.len() && (line[i] == b'-' || line[i] == b'+') {
        i += 1;
    }
    let digits = i;
    let mut level: i64 = 0;
    while i < line.len() && line[i].is_ascii_digit() {
        level = (level * 10 + i64::from(line[i] - b'0')).min(i64::from(i32::MAX) + 1);
        i += 1;
    }
    if i == digits {
        return None;
    }
    let level = if line[start] == b'-' { -level } else { level };
    let word = |i: &mut usize, most: usize| -> Option<(usize, usize)> {
        skip(i);
        let s = *i;
        while *i < line.len() && !line[*i].is_ascii_whitespace() && *i - s < most {
            *i += 1;
        }
        (*i > s).then_some((s, *i))
    };
    let (t, _) = word(&mut i, 1)?;
    let (m0, m1) = word(&mut i, 12)?;
    let (n0, n1) = word(&mut i, usize::MAX)?;
    Some((level as i32, line[t], &line[m0..m1], &line[n0..n1]))
}

/// Reads `path`'s entries into `tree` as CLIPS's `TextLookupFetch` does; the number
/// of entries.
fn read_tree(host: &mut dyn Host, path: &str, tree: &mut Tree) -> Result<usize, Bad> {
    let mut lines = Lines::new(path, 0);
    let mut line = [0u8; 256];
    let (mut line_ct, mut entries) = (0u32, 0usize);
    let mut inside = false;
    let mut parent = NIL;
    loop {
        let n = match lines.chunk(host, &mut line) {
            Ok(Some(n)) => n,
            Ok(None) => break,
            Err(_) if line_ct == 0 => return Err(Bad::Open),
            Err(_) => break,
        };
        line_ct += 1;
        let s = &line[..n];
        if s.starts_with(b"$$") {
            continue;
        }
        if findstr(s, EDELIM).is_some() {
            if !inside {
                return Err(Bad::Line(8, line_ct, "Unmatched end marker."));
            }
            inside = false;
            entries += 1;
        } else if findstr(s, BDELIM).is_some() {
            if inside {
                return Err(Bad::Line(4, line_ct, "Previous entry not closed."));
            }
            inside = true;
            let Some((level, code, marker, name)) = scan_header(s) else {
                return Err(Bad::Line(5, line_ct, "Invalid delimeter string."));
            };
            let menu = match code {
                b'M' => true,
                b'I' => false,
                _ => return Err(Bad::Line(6, line_ct, "Invalid entry type.")),
            };
            if marker != BDELIM {
                return Err(Bad::Line(5, line_ct, "Invalid delimeter string."));
            }
            if tree.n == MOST_ENTRIES {
                return Err(Bad::Full("entries in a file"));
            }
            let name = &name[..name.len().min(NAMESIZE - 1)];
            if tree.used + name.len() > NAME_BYTES {
                return Err(Bad::Full("bytes of entry names in a file"));
            }
            let at = tree.used;
            for (d, b) in tree.names[at..at + name.len()].iter_mut().zip(name) {
                *d = b.to_ascii_uppercase();
            }
            tree.used += name.len();
            let me = tree.n as u16;
            tree.e[tree.n] = Entry {
                level,
                menu,
                name: at as u16,
                name_len: name.len() as u8,
                offset: lines.offset(),
                child: NIL,
                parent: NIL,
                next: NIL,
            };
            tree.n += 1;
            attach(tree, me, &mut parent)
                .map_err(|()| Bad::Line(7, line_ct, "Non-menu entries cannot have subtopics."))?;
        }
    }
    if inside {
        return Err(Bad::Line(4, line_ct, "Previous entry not closed."));
    }
    Ok(entries)
}

/// CLIPS's `AttachLeaf`: entry `me` goes into the tree after entry `*parent`.
fn attach(t: &mut Tree, me: u16, parent: &mut u16) -> Result<(), ()> {
    let m = usize::from(me);
    let level = t.e[m].level;
    if t.topics == NIL {
        t.topics = me;
    } else if level > t.e[usize::from(*parent)].level {
        let p = usize::from(*parent);
        if !t.e[p].menu {
            return Err(());
        }
        t.e[m].parent = *parent;
        t.e[p].child = me;
    } else if level == t.e[usize::from(*parent)].level {
        let p = usize::from(*parent);
        t.e[m].parent = t.e[p].parent;
        t.e[m].next = t.e[p].next;
        t.e[p].next = me;
    } else {
        let mut p = *parent;
        loop {
            p = t.e[usize::from(p)].parent;
            if p == NIL || level >= t.e[usize::from(p)].level {
                break;
            }
        }
        if p == NIL {
            t.e[m].next = t.topics;
            t.topics = me;
        } else if t.e[usize::from(p)].level < level {
            let pi = usize::from(p);
            t.e[m].parent = p;
            t.e[m].next = t.e[pi].child;
            t.e[pi].child = me;
        } else {
            let pi = usize::from(p);
            t.e[m].parent = t.e[pi].parent;
            t.e[m].next = t.e[pi].next;
            t.e[pi].next = me;
        }
    }
    *parent = me;
    Ok(())
}

/// The text of a value as a file or topic name (CLIPS's `GetCommandLineTopics`).
fn name_of(cx: &mut Core<'_>, v: Value) -> TextBuf<NAMESIZE> {
    let mut b = TextBuf::new();
    match v {
        Value::Sym(_) | Value::Str(_) | Value::Int(_) | Value::Float(_) => {
            let mut full: TextBuf<512> = TextBuf::new();
            let _ = cx.write_printout(&mut full, v);
            let mut end = full.len().min(NAMESIZE - 1);
            while !full.as_str().is_char_boundary(end) {
                end -= 1;
            }
            let _ = b.write_str(&full.as_str()[..end]);
        }
        _ => {
            let _ = b.write_str("***ERROR***");
        }
    }
    b
}

fn print_textpro_error(cx: &mut Core<'_>, file: &str, bad: Bad) {
    let mut b: TextBuf<256> = TextBuf::new();
    let _ = match bad {
        Bad::Open => writeln!(b, "[TEXTPRO1] Could not open file \"{file}\"."),
        Bad::Line(id, line, text) => writeln!(b, "[TEXTPRO{id}] Line {line} : {text}"),
        Bad::Full(what) => writeln!(
            b,
            "[TEXTPRO9] robotino-agent holds at most {} {what}.",
            if what.starts_with("entries") {
                MOST_ENTRIES
            } else {
                NAME_BYTES
            }
        ),
    };
    cx.write(router::WERROR, b.as_str());
}

/// `(fetch <file>)`: the number of entries, or FALSE.
fn fetch(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cx.arg(a, 0);
    if !matches!(v, Value::Sym(_) | Value::Str(_)) {
        return Err(EvalError::wrong_type("fetch", 1, "symbol or string"));
    }
    let file = name_of(cx, v);
    let file = file.as_str();
    let mut tree = Tree::new();
    let read = read_tree(cx.host, file, &mut tree);
    if let Err(Bad::Open) = read {
        print_textpro_error(cx, file, Bad::Open);
        return Ok(Value::Sym(SYM_FALSE));
    }
    if cx.st.text_regions.find(file).is_some() {
        let mut b: TextBuf<160> = TextBuf::new();
        let _ = writeln!(b, "[TEXTPRO2] File \"{file}\" already loaded.");
        cx.write(router::WERROR, b.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    match read {
        Ok(0) => {
            cx.write(router::WERROR, "[TEXTPRO3] No entries found.\n");
            Ok(Value::Sym(SYM_FALSE))
        }
        Ok(n) => {
            let r = &mut cx.st.text_regions;
            if usize::from(r.n) == MOST_FILES {
                print_textpro_error(cx, file, Bad::Full("files fetched at once"));
                return Ok(Value::Sym(SYM_FALSE));
            }
            let f = &mut r.files[usize::from(r.n)];
            f.name[..file.len()].copy_from_slice(file.as_bytes());
            f.len = file.len() as u8;
            f.menu = NIL;
            r.n += 1;
            Ok(Value::Int(n as i64))
        }
        Err(bad) => {
            print_textpro_error(cx, file, bad);
            Ok(Value::Sym(SYM_FALSE))
        }
    }
}

/// `(toss <file>)`: TRUE when the file was fetched.
fn toss(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cx.arg(a, 0);
    if !matches!(v, Value::Sym(_) | Value::Str(_)) {
        return Err(EvalError::wrong_type("toss", 1, "symbol or string"));
    }
    let file = name_of(cx, v);
    Ok(Value::Sym(match cx.st.text_regions.find(file.as_str()) {
        Some(i) => {
            cx.st.text_regions.remove(i);
            SYM_TRUE
        }
        None => SYM_FALSE,
    }))
}

/// The outcome of a walk through a file's tree (CLIPS's lookup status codes).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Status {
    NoFile,
    NoTopic,
    Exit,
    Found,
}

/// CLIPS's `FindTopicInEntries` for file `file` (index `fi`) and the call's topics
/// (arguments `first..`): where the entry to print starts.
fn find_topic(cx: &mut Core<'_>, fi: usize, tree: &Tree, a: Args, first: usize) -> (Status, u64) {
    let n = a.len as usize;
    if first == n {
        return lookup(cx, fi, tree, None);
    }
    let mut out = (Status::NoFile, 0);
    for i in first..n {
        let v = cx.arg(a, i);
        let topic = name_of(cx, v);
        out = match topic.as_str() {
            "^" => lookup(cx, fi, tree, None),
            "?" if i + 1 == n => match cx.st.text_regions.files[fi].menu {
                NIL => (Status::NoTopic, 0),
                m => (Status::Found, tree.e[usize::from(m)].offset),
            },
            t => lookup(cx, fi, tree, Some(t.as_bytes())),
        };
        if matches!(out.0, Status::NoFile | Status::NoTopic) {
            break;
        }
    }
    out
}

/// CLIPS's `LookupEntry`: `name` among the current menu's topics (None: up one level).
fn lookup(cx: &mut Core<'_>, fi: usize, tree: &Tree, name: Option<&[u8]>) -> (Status, u64) {
    let menu = &mut cx.st.text_regions.files[fi].menu;
    let Some(name) = name else {
        if *menu == NIL {
            return (Status::Exit, 0);
        }
        let up = tree.e[usize::from(*menu)].parent;
        *menu = up;
        return match up {
            NIL => (Status::Exit, 0),
            p => (Status::Found, tree.e[usize::from(p)].offset),
        };
    };
    let mut upper = [0u8; NAMESIZE];
    let upper = &mut upper[..name.len()];
    for (d, b) in upper.iter_mut().zip(name) {
        *d = b.to_ascii_uppercase();
    }
    let mut e = match *menu {
        NIL => tree.topics,
        m => tree.e[usize::from(m)].child,
    };
    while e != NIL && findstr(tree.name(e), upper) != Some(0) {
        e = tree.e[usize::from(e)].next;
    }
    if e == NIL {
        return (Status::NoTopic, 0);
    }
    if tree.e[usize::from(e)].menu {
        *menu = e;
    }
    (Status::Found, tree.e[usize::from(e)].offset)
}

/// The entry `file`'s topics name: its lines start at the offset returned.
fn region(cx: &mut Core<'_>, a: Args, file_arg: usize, tree: &mut Tree) -> Option<u64> {
    let v = cx.arg(a, file_arg);
    let file = name_of(cx, v);
    let fi = cx.st.text_regions.find(file.as_str())?;
    // a file that cannot be read now is CLIPS's NO_FILE
    read_tree(cx.host, file.as_str(), tree).ok()?;
    let (status, offset) = find_topic(cx, fi, tree, a, file_arg + 1);
    (status == Status::Found).then_some(offset)
}

/// Calls `each` with the entry's lines from `offset` on, as CLIPS's `grab_string`
/// gives them (`$$` as two blanks; up to the `END-ENTRY` line).
fn each_line(
    host: &mut dyn Host,
    file: &str,
    offset: u64,
    mut each: impl FnMut(&mut dyn Host, &str),
) {
    let mut lines = Lines::new(file, offset);
    let mut line = [0u8; 256];
    while let Ok(Some(n)) = lines.chunk(host, &mut line) {
        if line.starts_with(b"$$") {
            line[0] = b' ';
            line[1] = b' ';
        } else if findstr(&line[..n], EDELIM).is_some() {
            break;
        }
        let mut rest = &line[..n];
        while !rest.is_empty() {
            match core::str::from_utf8(rest) {
                Ok(s) => {
                    each(host, s);
                    rest = &[];
                }
                Err(e) => {
                    let (ok, bad) = rest.split_at(e.valid_up_to());
                    each(host, core::str::from_utf8(ok).unwrap_or(""));
                    each(host, "\u{fffd}");
                    rest = &bad[e.error_len().unwrap_or(bad.len()).min(bad.len())..];
                }
            }
        }
    }
}

/// `(print-region <logical-name> <file> <topic>*)`: TRUE when an entry was printed.
fn print_region(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let out = cx.arg(a, 0);
    if !matches!(out, Value::Sym(_)) {
        return Err(EvalError::wrong_type(
            "print-region",
            1,
            super::save_facts::T_SYMBOL,
        ));
    }
    if !matches!(cx.arg(a, 1), Value::Sym(_) | Value::Str(_)) {
        return Err(EvalError::wrong_type("print-region", 2, "symbol or string"));
    }
    let mut tree = Tree::new();
    let Some(offset) = region(cx, a, 1, &mut tree) else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    let v = cx.arg(a, 1);
    let file = name_of(cx, v);
    let name = name_of(cx, out);
    // CLIPS prints to the name as given (`t` is `stdout`; `T` is no router here): a
    // name no router takes is `[ROUTER1]` at each line
    let known = super::commands::ROUTERS
        .iter()
        .find(|(n, _)| *n == name.as_str());
    let to: Option<TextBuf<NAMESIZE>> = match known {
        Some((_, r)) => r.map(|r| {
            let mut b = TextBuf::new();
            let _ = b.write_str(r);
            b
        }),
        None if cx.host.is_open_file(name.as_str()) => Some(name),
        None => {
            let mut lines = 1;
            each_line(cx.host, file.as_str(), offset, |_, _| lines += 1);
            for _ in 0..lines {
                super::commands::report_unknown_router(cx, out);
            }
            return Ok(Value::Sym(SYM_TRUE));
        }
    };
    let Some(to) = to else {
        return Ok(Value::Sym(SYM_TRUE));
    };
    let to = to.as_str();
    cx.spill_traces();
    cx.host.write_str(to, "\n");
    each_line(cx.host, file.as_str(), offset, |h, s| h.write_str(to, s));
    Ok(Value::Sym(SYM_TRUE))
}

/// `(get-region <file> <topic>*)`: the entry's lines as one string ("" when none).
fn get_region(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    // a computed file name of another type: "" and no message, as CLIPS (a literal
    // one is refused as the call is read)
    if !matches!(cx.arg(a, 0), Value::Sym(_) | Value::Str(_)) {
        return Ok(cx.make_string("")?);
    }
    let mut tree = Tree::new();
    let mut text: TextBuf<MOST_REGION> = TextBuf::new();
    if let Some(offset) = region(cx, a, 0, &mut tree) {
        let v = cx.arg(a, 0);
        let file = name_of(cx, v);
        let mut full = false;
        each_line(cx.host, file.as_str(), offset, |_, s| {
            full |= text.write_str(s).is_err();
        });
        if full {
            return Err(crate::engine::cap(crate::error::Pool::SymbolBytes, MOST_REGION).into());
        }
    }
    let s = text.as_str();
    let b = s.as_bytes();
    let s = if b.len() >= 2 && matches!(&b[b.len() - 2..], b"\r\n" | b"\n\r") {
        &s[..s.len() - 2]
    } else {
        s
    };
    Ok(cx.make_string(s)?)
}
