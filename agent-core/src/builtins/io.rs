//! CLIPS's I/O functions: `read`, `readline`, `read-number`, `get-char`, `put-char`,
//! `open`, `close`, `remove`, `rename`, `dribble-on`, `dribble-off` (output to an opened
//! file is `printout` and `format`, through `commands::resolve_router`; the dribble file
//! is the host's, [`Host::dribble_on`]).
//!
//! Files and standard input belong to the host ([`Host::open_file`],
//! [`Host::read_byte`], ...): the engine keeps no file table, so its memory is the same
//! with files open or not, and a host without files (the robot) refuses `open`, which
//! says so. In CLIPS's batch mode (`clips -f`, `batch`) a read from `stdin` takes the
//! batch file's next lines and echoes them, as CLIPS does (`BatchInput`); after the
//! file's end it reads the host's standard input.
//!
//! Only with the feature `parser`: reading a token is lexing text at run time, and the
//! agent image has neither files nor a console.
//!
//! [`Host::open_file`]: crate::host::Host::open_file
//! [`Host::read_byte`]: crate::host::Host::read_byte
//! [`Host::dribble_on`]: crate::host::Host::dribble_on

use super::describe::Returns as R;
use super::describe::{ArgType, BodyNames, OnError};

/// A file name: a symbol or a string (CLIPS's `k`).
const FILE: ArgType = ArgType::SymbolOrString;
const ANY_ARG: ArgType = ArgType::Any;
use core::fmt::Write;

use super::commands::{report_unknown_router, ROUTERS};
use super::{Args, Builtin, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::{EvalError, HostIoError};
use crate::host::{router, OpenMode};
use crate::lexer::Lexer;
use crate::value::{TextBuf, Value};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("read", 0, 1, read),
    Builtin::eager("readline", 0, 1, readline).returns(R::SymbolOrString),
    Builtin::eager("read-number", 0, 1, read_number),
    Builtin::eager("get-char", 0, 1, get_char).returns(R::Integer),
    Builtin::eager("put-char", 1, 2, put_char).returns(R::Void),
    Builtin::eager("open", 2, 3, open).returns(R::Symbol).args(&[FILE], ANY_ARG).on_error(OnError::False).body_names(BodyNames::FileName),
    Builtin::eager("close", 0, 1, close).returns(R::Symbol),
    Builtin::eager("remove", 1, 1, remove).returns(R::Symbol).args(&[], FILE).on_error(OnError::False).body_names(BodyNames::FileName),
    Builtin::eager("rename", 2, 2, rename).returns(R::Symbol).args(&[], FILE).on_error(OnError::False).body_names(BodyNames::FileName),
    Builtin::eager("dribble-on", 1, 1, dribble_on).returns(R::Symbol).args(&[], FILE).on_error(OnError::False).body_names(BodyNames::FileName),
    Builtin::eager("dribble-off", 0, 0, dribble_off).returns(R::Symbol),
];

pub const TABLE: super::Table = super::Table::new(FUNCS);

/// The longest line (and token) a read function takes; a longer one is an error
/// naming the limit, never cut silently.
const LINE: usize = 4096;

/// What the read functions return when they cannot read.
const READ_ERROR: &str = "*** READ ERROR ***";

/// A logical name's text (symbols, strings and numbers name files in CLIPS).
type Name = TextBuf<256>;

/// Where a read function reads from.
// lives on the stack for one call, and there is no heap to box the name into
#[allow(clippy::large_enum_variant)]
enum Input {
    Stdin,
    File(Name),
}

/// The text a value names a logical name by, or None for values that cannot be one
/// (an instance name's is the name inside its brackets).
fn name_text(cx: &mut Core<'_>, v: Value) -> Option<Name> {
    match v {
        #[cfg(feature = "extras")]
        Value::Sym(s) if crate::value::instance_name_body(cx.sym_text(s)).is_some() => {
            let mut b = Name::new();
            let _ = b.write_str(crate::value::instance_name_body(cx.sym_text(s))?);
            Some(b)
        }
        Value::Sym(_) | Value::Str(_) | Value::Int(_) | Value::Float(_) => {
            let mut b = Name::new();
            cx.write_printout(&mut b, v).ok()?;
            Some(b)
        }
        _ => None,
    }
}

/// The logical name a value names: `name_text`, with `T` read as `t` (CLIPS's
/// `GetLogicalName`).
fn logical_name(cx: &mut Core<'_>, v: Value) -> Option<Name> {
    let mut name = name_text(cx, v)?;
    if name.as_str() == "T" {
        name.clear();
        let _ = name.write_str("t");
    }
    Some(name)
}

/// The file the host opened as `name`, if any (`printout` and `format` to it).
pub(super) fn open_file_name(cx: &mut Core<'_>, name: Value) -> Option<Name> {
    let text = name_text(cx, name)?;
    cx.host.is_open_file(text.as_str()).then_some(text)
}

/// `[IOFUN1]`: a value that cannot be a logical name.
fn report_illegal_name(cx: &mut Core<'_>, func: &str) {
    let mut m: TextBuf<96> = TextBuf::new();
    let _ = writeln!(m, "[IOFUN1] Illegal logical name used for {func} function.");
    cx.write(router::WERROR, m.as_str());
}

/// Why a read could not go on, reported once here; the function then gives its error
/// value.
fn report_input(cx: &mut Core<'_>, func: &str, why: &str) {
    let mut m: TextBuf<160> = TextBuf::new();
    let _ = writeln!(m, "[IOFUN] Function {func}: {why}.");
    cx.write(router::WERROR, m.as_str());
}

fn host_error(cx: &mut Core<'_>, func: &str, e: HostIoError) -> EvalError {
    let why = match e {
        HostIoError::Unsupported => "this host has no such input",
        _ => "the input could not be read",
    };
    report_input(cx, func, why);
    EvalError::already_reported()
}

/// The input a read function's optional argument names; None after reporting a name
/// that is no input (`[ROUTER1]`, `[IOFUN1]`).
fn input_arg(cx: &mut Core<'_>, a: Args, func: &str) -> Option<Input> {
    if a.len == 0 {
        return Some(Input::Stdin);
    }
    let v = cx.arg(a, 0);
    let Some(name) = logical_name(cx, v) else {
        report_illegal_name(cx, func);
        return None;
    };
    if matches!(v, Value::Sym(_) | Value::Str(_)) && matches!(name.as_str(), "t" | "stdin") {
        return Some(Input::Stdin);
    }
    if cx.host.is_open_file(name.as_str()) {
        return Some(Input::File(name));
    }
    report_unknown_router(cx, v);
    None
}

/// The opened file argument `a` names, if it names one (nothing reported otherwise:
/// `input_arg` then says what is wrong).
#[cfg(feature = "extras")]
fn input_arg_peek(cx: &mut Core<'_>, a: Args) -> Option<Input> {
    if a.len == 0 {
        return None;
    }
    let v = cx.arg(a, 0);
    let name = logical_name(cx, v)?;
    if matches!(v, Value::Sym(_) | Value::Str(_)) && matches!(name.as_str(), "t" | "stdin") {
        return None;
    }
    cx.host
        .is_open_file(name.as_str())
        .then_some(Input::File(name))
}

/// After a name that is no input: CLIPS halts the actions running (a deffunction's,
/// a rule's, a `progn`), but at the prompt the read function's value is printed.
fn halted_with(cx: &mut Core<'_>, text: &str) -> Result<Value, EvalError> {
    let v = cx.make_string(text)?;
    cx.set_error_fallback(v, None);
    Err(EvalError::already_reported())
}

/// One line of input and how much of it was handed out.
struct Line {
    buf: [u8; LINE],
    len: usize,
    pos: usize,
}

impl Line {
    fn new() -> Line {
        Line {
            buf: [0; LINE],
            len: 0,
            pos: 0,
        }
    }

    fn push(&mut self, bytes: &[u8]) -> bool {
        let Some(room) = self.buf.get_mut(self.len..self.len + bytes.len()) else {
            return false;
        };
        room.copy_from_slice(bytes);
        self.len += bytes.len();
        true
    }

    fn text(&self) -> &str {
        core::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
    }
}

fn too_long(cx: &mut Core<'_>, func: &str) -> EvalError {
    let mut m: TextBuf<96> = TextBuf::new();
    let _ = write!(m, "a line or token is longer than {LINE} bytes");
    report_input(cx, func, m.as_str());
    EvalError::already_reported()
}

/// The next line of standard input into `line` (without its newline); false at the
/// end. In batch mode the batch file's next line, echoed; after its end the host's.
fn stdin_line(cx: &mut Core<'_>, line: &mut Line, func: &str) -> Result<bool, EvalError> {
    line.len = 0;
    line.pos = 0;
    if cx.st.io.batch_input.active {
        if batch_line(cx, line, func)? {
            return Ok(true);
        }
        // CLIPS goes on with its standard input after the batch file's end
        cx.st.io.batch_input.active = false;
    }
    loop {
        match cx.host.read_byte("stdin") {
            Ok(Some(b'\n')) => return Ok(true),
            Ok(Some(b)) => {
                if !line.push(&[b]) {
                    return Err(too_long(cx, func));
                }
            }
            Ok(None) => return Ok(line.len > 0),
            Err(e) => return Err(host_error(cx, func, e)),
        }
    }
}

/// The running batch file's next line, echoed as CLIPS's batch mode echoes what it
/// reads; false at the file's end.
fn batch_line(cx: &mut Core<'_>, line: &mut Line, func: &str) -> Result<bool, EvalError> {
    let mut path = Name::new();
    let _ = path.write_str(cx.st.io.batch_input.path.as_str());
    let at = cx.st.io.batch_input.offset;
    let mut chunk = [0u8; 256];
    let mut taken = 0u64;
    let mut ended = false;
    while !ended {
        let n = cx
            .host
            .read_file_at(path.as_str(), at + taken, &mut chunk)
            .map_err(|e| host_error(cx, func, e))?;
        if n == 0 {
            break;
        }
        let (piece, newline) = match chunk[..n].iter().position(|&b| b == b'\n') {
            Some(k) => (&chunk[..k], true),
            None => (&chunk[..n], false),
        };
        if !line.push(piece) {
            return Err(too_long(cx, func));
        }
        taken += (piece.len() + usize::from(newline)) as u64;
        ended = newline;
    }
    if taken == 0 {
        return Ok(false);
    }
    cx.st.io.batch_input.offset = at + taken;
    cx.st.io.batch_input.lines += u32::from(ended);
    let mut echo = Line::new();
    let _ = echo.push(&line.buf[..line.len]);
    cx.flush_unechoed();
    cx.write(router::STDOUT, echo.text());
    cx.write(router::STDOUT, "\n");
    Ok(true)
}

/// Bytes a token is scanned from.
trait Bytes {
    fn next(&mut self, cx: &mut Core<'_>) -> Result<Option<u8>, EvalError>;
    /// Gives back the byte `next` returned last.
    fn back(&mut self, cx: &mut Core<'_>, b: u8);
}

/// One line of standard input, its end the input's end: CLIPS's `read` from `stdin`
/// scans a line at a time (a string does not go on into the next line) and drops what
/// is left of the line after the token.
struct LineBytes<'l> {
    line: &'l mut Line,
}

impl Bytes for LineBytes<'_> {
    fn next(&mut self, _cx: &mut Core<'_>) -> Result<Option<u8>, EvalError> {
        let b = self.line.buf[..self.line.len].get(self.line.pos).copied();
        self.line.pos += usize::from(b.is_some());
        Ok(b)
    }

    fn back(&mut self, _cx: &mut Core<'_>, _b: u8) {
        self.line.pos -= 1;
    }
}

/// An opened file, a byte at a time through the host.
struct FileBytes<'n> {
    name: &'n str,
    func: &'static str,
}

impl Bytes for FileBytes<'_> {
    fn next(&mut self, cx: &mut Core<'_>) -> Result<Option<u8>, EvalError> {
        cx.host
            .read_byte(self.name)
            .map_err(|e| host_error(cx, self.func, e))
    }

    fn back(&mut self, cx: &mut Core<'_>, b: u8) {
        cx.host.unread_byte(self.name, b);
    }
}

/// Bytes that end a symbol or number (the first of them is left for the next read).
fn ends_word(b: u8) -> bool {
    b.is_ascii_whitespace() || matches!(b, b'(' | b')' | b'"' | b';' | b'&' | b'|' | b'~' | b'<')
}

/// Scans the next token's text into `tok` (a string with its quotes, escapes kept),
/// skipping blanks and `;` comments as CLIPS's scanner does; false at the input's end.
fn scan_token(
    cx: &mut Core<'_>,
    src: &mut dyn Bytes,
    tok: &mut Line,
    func: &str,
) -> Result<bool, EvalError> {
    let first = loop {
        match src.next(cx)? {
            None => return Ok(false),
            Some(b';') => loop {
                match src.next(cx)? {
                    None => return Ok(false),
                    Some(b'\n') => break,
                    Some(_) => {}
                }
            },
            Some(b) if b.is_ascii_whitespace() => {}
            Some(b) => break b,
        }
    };
    let mut ok = tok.push(&[first]);
    match first {
        b'"' => {
            let mut escaped = false;
            while let Some(b) = src.next(cx)? {
                ok &= tok.push(&[b]);
                if b == b'"' && !escaped {
                    break;
                }
                escaped = b == b'\\' && !escaped;
            }
        }
        b'(' | b')' | b'&' | b'|' | b'~' => {}
        _ => {
            while let Some(b) = src.next(cx)? {
                if ends_word(b) {
                    src.back(cx, b);
                    break;
                }
                ok &= tok.push(&[b]);
            }
        }
    }
    if !ok {
        return Err(too_long(cx, func));
    }
    Ok(true)
}

/// Reads one field as CLIPS's `read` does: a number, symbol or string as itself, any
/// other token as a string of its text; the symbol `EOF` at the input's end.
fn read_field(cx: &mut Core<'_>, src: &mut dyn Bytes, func: &str) -> Result<Value, EvalError> {
    let mut tok = Line::new();
    if !scan_token(cx, src, &mut tok, func)? {
        return Ok(cx.make_symbol("EOF")?);
    }
    field_of(cx, &tok, func)
}

/// The value of a scanned token.
fn field_of(cx: &mut Core<'_>, tok: &Line, func: &str) -> Result<Value, EvalError> {
    let Ok(text) = core::str::from_utf8(&tok.buf[..tok.len]) else {
        report_input(cx, func, "the input is not UTF-8 text");
        return Ok(cx.make_string(READ_ERROR)?);
    };
    let mut lexer = Lexer::new(text);
    match super::strings::scan_field(cx, &mut lexer)? {
        Some(v) => Ok(v),
        None => Ok(cx.make_symbol("EOF")?),
    }
}

/// Reads a field from the input argument `a` names (stdin without one).
fn read_from(cx: &mut Core<'_>, a: Args, func: &'static str) -> Result<Value, EvalError> {
    match input_arg(cx, a, func) {
        None => halted_with(cx, READ_ERROR),
        Some(Input::Stdin) => {
            // lines until one holds a token
            let mut line = Line::new();
            loop {
                if !stdin_line(cx, &mut line, func)? {
                    return Ok(cx.make_symbol("EOF")?);
                }
                let mut tok = Line::new();
                if scan_token(cx, &mut LineBytes { line: &mut line }, &mut tok, func)? {
                    return field_of(cx, &tok, func);
                }
            }
        }
        Some(Input::File(name)) => {
            let mut src = FileBytes {
                name: name.as_str(),
                func,
            };
            read_field(cx, &mut src, func)
        }
    }
}

fn read(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    read_from(cx, a, "read")
}

/// `read-number`: `read`, but anything but a number (or the end) is a read error. From
/// a file, as CLIPS's own scan: the characters up to a blank, which it takes too (no
/// comment, string or parenthesis ends the token: `12)` is no number).
fn read_number(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    #[cfg(feature = "extras")]
    if let Some(Input::File(name)) = input_arg_peek(cx, a) {
        return read_number_from_file(cx, name.as_str());
    }
    let v = read_from(cx, a, "read-number")?;
    match v {
        Value::Int(_) | Value::Float(_) => Ok(v),
        Value::Sym(s) if cx.sym_text(s) == "EOF" => Ok(v),
        _ => Ok(cx.make_string(READ_ERROR)?),
    }
}

/// `read-number` from an opened file: skips blanks, takes the characters up to the
/// next blank (and the blank), and reads them as a number only if they are one whole.
#[cfg(feature = "extras")]
fn read_number_from_file(cx: &mut Core<'_>, name: &str) -> Result<Value, EvalError> {
    let mut tok = Line::new();
    let mut b = loop {
        match cx.host.read_byte(name) {
            Ok(Some(b)) if b.is_ascii_whitespace() => {}
            Ok(b) => break b,
            Err(e) => return Err(host_error(cx, "read-number", e)),
        }
    };
    if b.is_none() {
        return Ok(cx.make_symbol("EOF")?);
    }
    while let Some(c) = b.filter(|c| !c.is_ascii_whitespace()) {
        if !tok.push(&[c]) {
            return Err(too_long(cx, "read-number"));
        }
        b = cx
            .host
            .read_byte(name)
            .map_err(|e| host_error(cx, "read-number", e))?;
    }
    let text = &tok.buf[..tok.len];
    // C's strtod, which CLIPS reads it with, takes hexadecimal too: a float
    let (sign, digits) = match text.split_first() {
        Some((b'-', rest)) => (-1.0, rest),
        Some((b'+', rest)) => (1.0, rest),
        _ => (1.0, text),
    };
    if let Some(hex) = digits
        .strip_prefix(b"0x")
        .or_else(|| digits.strip_prefix(b"0X"))
        .filter(|h| !h.is_empty() && h.iter().all(u8::is_ascii_hexdigit))
    {
        let x = hex.iter().fold(0.0f64, |x, &c| {
            x * 16.0 + f64::from(char::from(c).to_digit(16).unwrap_or(0))
        });
        return Ok(Value::Float(sign * x));
    }
    let numeric = text
        .iter()
        .all(|c| c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.' | b'e' | b'E'));
    match field_of(cx, &tok, "read-number")? {
        v @ (Value::Int(_) | Value::Float(_)) if numeric => Ok(v),
        _ => Ok(cx.make_string(READ_ERROR)?),
    }
}

/// `readline`: the rest of the current line as a string (`EOF` at the end).
fn readline(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut line = Line::new();
    let more = match input_arg(cx, a, "readline") {
        None => return halted_with(cx, READ_ERROR),
        Some(Input::Stdin) => stdin_line(cx, &mut line, "readline")?,
        Some(Input::File(name)) => {
            let mut any = false;
            loop {
                match cx.host.read_byte(name.as_str()) {
                    Ok(Some(b'\n')) => break true,
                    Ok(Some(b)) => {
                        any = true;
                        if !line.push(&[b]) {
                            return Err(too_long(cx, "readline"));
                        }
                    }
                    Ok(None) => break any,
                    Err(e) => return Err(host_error(cx, "readline", e)),
                }
            }
        }
    };
    if !more {
        return Ok(cx.make_symbol("EOF")?);
    }
    let Ok(text) = core::str::from_utf8(&line.buf[..line.len]) else {
        report_input(cx, "readline", "the input is not UTF-8 text");
        return Ok(cx.make_string(READ_ERROR)?);
    };
    Ok(cx.make_string(text)?)
}

/// `get-char`: the next byte's code, -1 at the end (or for a name that is no input).
fn get_char(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let byte = match input_arg(cx, a, "get-char") {
        None => {
            cx.set_error_fallback(Value::Int(-1), None);
            return Err(EvalError::already_reported());
        }
        Some(Input::Stdin) if cx.st.io.batch_input.active => batch_byte(cx)?,
        Some(Input::Stdin) => cx
            .host
            .read_byte("stdin")
            .map_err(|e| host_error(cx, "get-char", e))?,
        Some(Input::File(name)) => cx
            .host
            .read_byte(name.as_str())
            .map_err(|e| host_error(cx, "get-char", e))?,
    };
    Ok(Value::Int(byte.map_or(-1, i64::from)))
}

/// The running batch file's next byte (`get-char` in batch mode).
fn batch_byte(cx: &mut Core<'_>) -> Result<Option<u8>, EvalError> {
    let mut path = Name::new();
    let _ = path.write_str(cx.st.io.batch_input.path.as_str());
    let mut b = [0u8; 1];
    let at = cx.st.io.batch_input.offset;
    let n = cx
        .host
        .read_file_at(path.as_str(), at, &mut b)
        .map_err(|e| host_error(cx, "get-char", e))?;
    if n == 0 {
        cx.st.io.batch_input.active = false;
        return cx
            .host
            .read_byte("stdin")
            .map_err(|e| host_error(cx, "get-char", e));
    }
    cx.st.io.batch_input.offset = at + 1;
    cx.st.io.batch_input.lines += u32::from(b[0] == b'\n');
    // echoed with the rest of its line, as CLIPS echoes batch input by lines
    if b[0] == b'\n' {
        cx.flush_unechoed();
        cx.write(router::STDOUT, "\n");
    } else if b[0].is_ascii() {
        let _ = cx.st.io.unechoed.write_char(char::from(b[0]));
    }
    Ok(Some(b[0]))
}

/// `(put-char [name] code)`: writes the byte with that code.
fn put_char(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let code_at = a.len as usize - 1;
    // (a float is cut to an integer, as C's cast in CLIPS)
    let code = match cx.arg(a, code_at) {
        Value::Int(code) => code,
        Value::Float(f) => f as i64,
        _ => {
            return Err(EvalError::wrong_type(
                "put-char",
                crate::error::arg_no(code_at),
                "integer",
            ))
        }
    };
    let routed = if a.len == 2 {
        match super::commands::resolve_router(cx, cx.arg(a, 0), "put-char") {
            Ok(Some(r)) => r,
            Err(e) if e.reported => return Err(e),
            Ok(None) | Err(_) => return Ok(Value::Void),
        }
    } else {
        super::commands::Routed::Engine(router::STDOUT)
    };
    // one byte, the code's low 8 bits, as CLIPS's `(char)` cast: 128-255 (and -128..-1)
    // are raw bytes, not the UTF-8 of a character; 256 is 0, 321 is `A`
    let byte = code as u8;
    cx.write_bytes(routed.name(), &[byte]);
    Ok(Value::Void)
}

fn truth(ok: bool) -> Value {
    Value::Sym(if ok { SYM_TRUE } else { SYM_FALSE })
}

/// A file name argument (symbol or string), copied out.
fn path_arg(cx: &mut Core<'_>, a: Args, i: usize, func: &'static str) -> Result<Name, EvalError> {
    match cx.arg(a, i) {
        // (an instance name `[x]` is no symbol)
        Value::Sym(s) if crate::value::instance_name_body(cx.sym_text(s)).is_some() => Err(
            EvalError::wrong_type(func, crate::error::arg_no(i), "symbol or string"),
        ),
        v @ (Value::Sym(_) | Value::Str(_)) => name_text(cx, v).ok_or_else(|| {
            EvalError::wrong_type(func, crate::error::arg_no(i), "symbol or string")
        }),
        _ => Err(EvalError::wrong_type(
            func,
            crate::error::arg_no(i),
            "symbol or string",
        )),
    }
}

/// A host without files: said once per call, never taken for a missing file.
fn no_files(cx: &mut Core<'_>, func: &str) -> Value {
    report_input(cx, func, "this host has no files");
    truth(false)
}

/// `(open path name [mode])`: TRUE when the host opened the file.
fn open(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, 0, "open")?;
    let Some(name) = logical_name(cx, cx.arg(a, 1)) else {
        report_illegal_name(cx, "open");
        return Ok(truth(false));
    };
    let mode = if a.len > 2 {
        let Value::Str(m) = cx.arg(a, 2) else {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function open expected argument #3 to be of type string\n",
            );
            return Ok(truth(false));
        };
        match cx.sym_text(m) {
            "r" | "rb" => OpenMode::Read,
            "w" | "wb" => OpenMode::Write,
            "a" | "ab" => OpenMode::Append,
            _ => {
                cx.write(
                    router::WERROR,
                    "[ARGACCES5] Function open expected argument #3 to be of type string with value \"r\", \"w\", \"a\", \"rb\", \"wb\", or \"ab\"\n",
                );
                return Ok(truth(false));
            }
        }
    } else {
        OpenMode::Read
    };
    if name.as_str() == "t" {
        report_illegal_name(cx, "open");
        return Ok(truth(false));
    }
    if ROUTERS.iter().any(|(n, _)| *n == name.as_str()) || cx.host.is_open_file(name.as_str()) {
        let mut m: TextBuf<320> = TextBuf::new();
        let _ = writeln!(m, "[IOFUN2] Logical name {} already in use.", name.as_str());
        cx.write(router::WERROR, m.as_str());
        return Ok(truth(false));
    }
    match cx.host.open_file(name.as_str(), path.as_str(), mode) {
        Ok(()) => Ok(truth(true)),
        Err(HostIoError::Unsupported) => Ok(no_files(cx, "open")),
        // CLIPS says nothing of a file it cannot open
        Err(_) => Ok(truth(false)),
    }
}

/// `(close [name])`: closes one file or all; TRUE when one was open.
fn close(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if a.len == 0 {
        return Ok(truth(cx.host.close_all_files()));
    }
    let name = match logical_name(cx, cx.arg(a, 0)) {
        Some(name) if name.as_str() != "t" => name,
        _ => {
            report_illegal_name(cx, "close");
            return Ok(truth(false));
        }
    };
    Ok(truth(cx.host.close_file(name.as_str())))
}

/// `(remove path)`: TRUE when the host deleted the file.
fn remove(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, 0, "remove")?;
    match cx.host.remove_file(path.as_str()) {
        Ok(()) => Ok(truth(true)),
        Err(HostIoError::Unsupported) => Ok(no_files(cx, "remove")),
        Err(_) => Ok(truth(false)),
    }
}

/// `(rename from to)`: TRUE when the host renamed the file.
fn rename(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let from = path_arg(cx, a, 0, "rename")?;
    let to = path_arg(cx, a, 1, "rename")?;
    match cx.host.rename_file(from.as_str(), to.as_str()) {
        Ok(()) => Ok(truth(true)),
        Err(HostIoError::Unsupported) => Ok(no_files(cx, "rename")),
        Err(_) => Ok(truth(false)),
    }
}

/// `(dribble-on path)`: TRUE when the host opened the file that copies the screen
/// from now on. A dribble file already open is closed first, even when the new one
/// cannot be opened (`[ARGACCES2]`, FALSE), as in CLIPS.
fn dribble_on(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let path = path_arg(cx, a, 0, "dribble-on")?;
    match cx.host.dribble_on(path.as_str()) {
        Ok(()) => Ok(truth(true)),
        Err(HostIoError::Unsupported) => Ok(no_files(cx, "dribble-on")),
        Err(_) => {
            cx.report_unopened_file("dribble-on", path.as_str());
            Ok(truth(false))
        }
    }
}

/// `(dribble-off)`: closes the dribble file; TRUE also when none was open (CLIPS 6.30).
fn dribble_off(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(truth(cx.host.dribble_off()))
}

impl Core<'_> {
    /// Echoes what `get-char` took from the batch file's current line (see
    /// `BatchIo::unechoed`).
    pub(crate) fn flush_unechoed(&mut self) {
        if !self.st.io.unechoed.is_empty() {
            let text = core::mem::take(&mut self.st.io.unechoed);
            self.write(router::STDOUT, text.as_str());
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::error::HostIoError;
    use crate::host::{Host, OpenMode};
    use std::collections::HashMap;
    use std::string::{String, ToString};
    use std::vec::Vec;

    /// Files in memory: `disk` by path, open ones by logical name (bytes, next read).
    #[derive(Default)]
    struct MemHost {
        out: String,
        disk: HashMap<String, Vec<u8>>,
        open: HashMap<String, (String, usize, OpenMode)>,
        stdin: Vec<u8>,
        stdin_at: usize,
    }

    impl Host for MemHost {
        fn write_str(&mut self, router: &str, text: &str) {
            match self.open.get(router) {
                Some((path, _, OpenMode::Write | OpenMode::Append)) => {
                    let path = path.clone();
                    self.disk
                        .entry(path)
                        .or_default()
                        .extend_from_slice(text.as_bytes());
                }
                Some(_) => {}
                None => self.out.push_str(text),
            }
        }
        fn read_file_at(
            &mut self,
            path: &str,
            offset: u64,
            buf: &mut [u8],
        ) -> Result<usize, HostIoError> {
            let data = self.disk.get(path).ok_or(HostIoError::NotFound)?;
            let from = (offset as usize).min(data.len());
            let n = buf.len().min(data.len() - from);
            buf[..n].copy_from_slice(&data[from..from + n]);
            Ok(n)
        }
        fn open_file(&mut self, name: &str, path: &str, mode: OpenMode) -> Result<(), HostIoError> {
            match mode {
                OpenMode::Read if !self.disk.contains_key(path) => {
                    return Err(HostIoError::NotFound)
                }
                OpenMode::Write => {
                    self.disk.insert(path.to_string(), Vec::new());
                }
                _ => {}
            }
            self.open
                .insert(name.to_string(), (path.to_string(), 0, mode));
            Ok(())
        }
        fn close_file(&mut self, name: &str) -> bool {
            self.open.remove(name).is_some()
        }
        fn is_open_file(&self, name: &str) -> bool {
            self.open.contains_key(name)
        }
        fn read_byte(&mut self, name: &str) -> Result<Option<u8>, HostIoError> {
            if name == "stdin" {
                let b = self.stdin.get(self.stdin_at).copied();
                self.stdin_at += usize::from(b.is_some());
                return Ok(b);
            }
            let (path, at, _) = self.open.get_mut(name).ok_or(HostIoError::NotFound)?;
            let b = self
                .disk
                .get(path.as_str())
                .and_then(|d| d.get(*at))
                .copied();
            *at += usize::from(b.is_some());
            Ok(b)
        }
        fn unread_byte(&mut self, name: &str, _byte: u8) {
            if let Some((_, at, _)) = self.open.get_mut(name) {
                *at -= 1;
            }
        }
    }

    fn batch(h: &mut MemHost, text: &str) -> String {
        h.disk
            .insert("cmds.bat".to_string(), text.as_bytes().to_vec());
        let mut e = std::boxed::Box::new(SmallEngine::new());
        e.batch_path(h, "cmds.bat");
        core::mem::take(&mut h.out)
    }

    #[test]
    fn batch_reads_take_the_next_lines_then_standard_input() {
        let mut h = MemHost {
            stdin: b"after the end\n".to_vec(),
            ..MemHost::default()
        };
        let out = batch(
            &mut h,
            "(read)\nfoo bar\n(readline)\n a line \n(+ 1 2)\n(read)\n",
        );
        assert_eq!(
            out,
            "CLIPS> (read)\nfoo bar\nfoo\nCLIPS> (readline)\n a line \n\" a line \"\n\
             CLIPS> (+ 1 2)\n3\nCLIPS> (read)\nafter\n"
        );
        // standard input ended too
        let out = batch(&mut h, "(read)\n");
        assert_eq!(out, "CLIPS> (read)\nEOF\n");
    }

    #[test]
    fn a_token_in_a_file_stops_before_the_next_one() {
        let mut h = MemHost::default();
        let out = batch(
            &mut h,
            "(open \"f\" out \"w\")\n(printout out \"ab(cd \\\"s t\\\" 7\" crlf \"x\")\n(close out)\n\
             (open \"f\" in)\n(read in)\n(read in)\n(read in)\n(read in)\n(read in)\n(readline in)\n(read in)\n(read in)\n",
        );
        let results: Vec<&str> = out.lines().filter(|l| !l.starts_with("CLIPS>")).collect();
        assert_eq!(
            results,
            // the rest of the line after `7` is empty
            ["TRUE", "TRUE", "TRUE", "ab", "\"(\"", "cd", "\"s t\"", "7", "\"\"", "x", "EOF"]
        );
    }

    #[test]
    fn a_host_without_files_or_input_says_so() {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let mut h = crate::testutil::CaptureHost::default();
        e.exec_command(&mut h, "(open \"f\" x \"w\")", "test");
        assert_eq!(
            h.out,
            "[IOFUN] Function open: this host has no files.\nFALSE\n"
        );
        h.out.clear();
        e.exec_command(&mut h, "(read)", "test");
        assert!(
            h.out
                .starts_with("[IOFUN] Function read: this host has no such input.\n"),
            "{}",
            h.out
        );
        h.out.clear();
        e.exec_command(&mut h, "(printout x \"y\")", "test");
        assert!(h.out.starts_with("[ROUTER1] Logical name x"), "{}", h.out);
    }
}
