//! Builtin `format`: C-style formatting as CLIPS 6.30 does it.
//!
//! `(format <router> <control> <arg>*)` returns the formatted string and prints it to
//! the router unless the router is `nil`. Directives: `%d %u %o %x %c` (integers; floats
//! are truncated; `%u`, host only, prints a negative's 64-bit two's complement),
//! `%f %e %g` (floats; integers converted), `%s` (symbols and strings), `%n` newline,
//! `%t` tab, `%r` carriage return, `%%`. A directive may carry `-` (left justify), a
//! width (a leading `0` pads with zeros) and `.precision`; CLIPS rejects the other C
//! flags (`+`, space, `#`) and length modifiers with `[IOFUN3]`.

use super::describe::ArgType::{Any, Str as S};
use super::describe::OnError;
use super::describe::Returns as R;
use core::fmt::Write;

use super::math::{c_trunc_to_i64, T_NUMBER};
use super::strings::Text;
use super::{Args, Builtin, ANY, SYM_NIL};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::value::{TextBuf, Value};

pub const FUNCS: &[Builtin] = &[Builtin::lazy("format", 2, ANY, format_in_order)
    .args(&[Any, S], Any)
    .on_error(OnError::EmptyString)
    .returns(R::Str)];
pub const TABLE: super::Table = super::Table::new(FUNCS);

const TOO_LONG: EvalError = EvalError::message(crate::error::Message::FormatTooLong);

/// One parsed `%` directive.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Spec {
    left: bool,
    zero: bool,
    width: usize,
    precision: Option<usize>,
    conv: u8,
}

/// Conversions that consume an argument (`%u` with `extras` only: the agent image,
/// short of code, rejects it as it did before CLIPS's `%u` was known to us).
fn takes_arg(conv: u8) -> bool {
    matches!(conv, b'd' | b'o' | b'x' | b'c' | b'f' | b'e' | b'g' | b's')
        || (cfg!(feature = "extras") && conv == b'u')
}

/// Parses the directive after a `%` at `ctl[at..]`; returns it and the bytes used.
/// `None` when the control string ends inside the directive (CLIPS then prints the
/// rest literally).
fn parse_spec(ctl: &[u8]) -> Option<(Spec, usize)> {
    let mut i = 0;
    let mut spec = Spec {
        left: false,
        zero: false,
        width: 0,
        precision: None,
        conv: 0,
    };
    if ctl.first() == Some(&b'-') {
        spec.left = true;
        i += 1;
    }
    if ctl.get(i) == Some(&b'0') {
        spec.zero = true;
    }
    while let Some(d) = ctl.get(i).filter(|b| b.is_ascii_digit()) {
        spec.width = spec
            .width
            .saturating_mul(10)
            .saturating_add((d - b'0') as usize);
        i += 1;
    }
    if ctl.get(i) == Some(&b'.') {
        i += 1;
        let mut p = 0usize;
        while let Some(d) = ctl.get(i).filter(|b| b.is_ascii_digit()) {
            p = p.saturating_mul(10).saturating_add((d - b'0') as usize);
            i += 1;
        }
        spec.precision = Some(p);
    }
    spec.conv = *ctl.get(i)?;
    Some((spec, i + 1))
}

/// Number of arguments the control string asks for.
fn count_args(ctl: &str) -> usize {
    let b = ctl.as_bytes();
    let (mut i, mut n) = (0, 0);
    while i < b.len() {
        if b[i] == b'%' {
            match parse_spec(&b[i + 1..]) {
                Some((spec, used)) => {
                    // CLIPS counts every directive but %n %t %r %% (even invalid ones)
                    n += usize::from(!matches!(spec.conv, b'n' | b't' | b'r' | b'%'));
                    i += 1 + used;
                    // `%5%`: the second `%` starts the next directive (host only)
                    #[cfg(feature = "extras")]
                    if spec.conv == b'%' && used > 1 {
                        i -= 1;
                    }
                }
                None => break,
            }
        } else {
            i += 1;
        }
    }
    n
}

/// The byte range of the control string's first invalid directive (`%z`, `%+d`,
/// `%5z`), which CLIPS reports while it counts the directives, before it compares
/// their number with the arguments (host only, feature `extras`: the agent image
/// reports it as it renders, after the count).
#[cfg(feature = "extras")]
fn first_bad_flag(ctl: &str) -> Option<(usize, usize)> {
    let b = ctl.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'%' {
            i += 1;
            continue;
        }
        let (spec, used) = parse_spec(&b[i + 1..])?;
        if spec.conv == b'%' && used > 1 {
            // `%5%`: unfinished, text; the second `%` starts the next directive
            i += used;
            continue;
        }
        let ok = matches!(spec.conv, b'n' | b't' | b'r' | b'%') || takes_arg(spec.conv);
        if !ok {
            return Some((i, i + 1 + used));
        }
        i += 1 + used;
    }
    None
}

/// `[IOFUN3]` for the directive at `flag` of `ctl`; the error that ends the call.
fn report_bad_flag(cx: &mut Core<'_>, ctl: &str, flag: (usize, usize)) -> EvalError {
    let mut m: TextBuf<128> = TextBuf::new();
    let _ = writeln!(
        m,
        "[IOFUN3] Invalid format flag \"{}\" specified in format function.",
        ctl.get(flag.0..flag.1).unwrap_or("%")
    );
    cx.write(router::WERROR, m.as_str());
    EvalError::new(EvalErrorKind::Reported)
}

/// CLIPS's arity message names the exact count the control string needs.
fn arity_error(expected: usize) -> EvalError {
    EvalError::message(crate::error::Message::format_arity(expected))
}

/// A `format` call: as CLIPS, the control string is checked against the number of
/// arguments before any directive's argument is evaluated, and each of those is
/// checked against its directive before the next is evaluated.
fn format_in_order(cx: &mut Core<'_>, call: crate::value::Ix) -> Result<Value, EvalError> {
    cx.call_in_order(call, format, format_arg)
}

/// The newest argument of a `format` call (the last of `a`; `total` in the call).
fn format_arg(cx: &mut Core<'_>, a: Args, total: usize) -> Result<(), EvalError> {
    let i = a.len as usize - 1;
    if i < 1 {
        return Ok(());
    }
    let ctl = match cx.arg(a, 1) {
        Value::Str(s) => cx.sym_text(s),
        _ => return Err(EvalError::wrong_type("format", 2, "string")),
    };
    if i == 1 {
        #[cfg(feature = "extras")]
        if let Some(flag) = first_bad_flag(ctl) {
            let mut copy: TextBuf<128> = TextBuf::new();
            let _ = copy.write_str(ctl.get(flag.0..flag.1).unwrap_or("%"));
            return Err(report_bad_flag(cx, copy.as_str(), (0, copy.as_str().len())));
        }
        let needed = count_args(ctl);
        return if needed + 2 == total {
            Ok(())
        } else {
            Err(arity_error(needed + 2))
        };
    }
    let v = cx.arg(a, i);
    let ok = match nth_conversion(ctl, i - 2) {
        Some(b's') => matches!(v, Value::Sym(_) | Value::Str(_)),
        Some(c) if takes_arg(c) => matches!(v, Value::Int(_) | Value::Float(_)),
        // an invalid directive: `render` reports it
        _ => true,
    };
    if ok {
        return Ok(());
    }
    let expected = if nth_conversion(ctl, i - 2) == Some(b's') {
        "symbol or string"
    } else {
        T_NUMBER
    };
    Err(EvalError::wrong_type(
        "format",
        crate::error::arg_no(i),
        expected,
    ))
}

/// The conversion of the `n`th directive of `ctl` that takes an argument (counted as
/// `count_args` counts them).
fn nth_conversion(ctl: &str, n: usize) -> Option<u8> {
    let b = ctl.as_bytes();
    let (mut i, mut k) = (0, 0);
    while i < b.len() {
        if b[i] != b'%' {
            i += 1;
            continue;
        }
        let (spec, used) = parse_spec(&b[i + 1..])?;
        if !matches!(spec.conv, b'n' | b't' | b'r' | b'%') {
            if k == n {
                return Some(spec.conv);
            }
            k += 1;
        }
        i += 1 + used;
        #[cfg(feature = "extras")]
        if spec.conv == b'%' && used > 1 {
            i -= 1;
        }
    }
    None
}

pub(super) fn format(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let ctl = match cx.arg(a, 1) {
        Value::Str(s) => s,
        _ => return Err(EvalError::wrong_type("format", 2, "string")),
    };
    let control = super::strings::copy_text(cx, ctl)?;
    // CLIPS checks the router before the arguments
    let dest = match cx.arg(a, 0) {
        Value::Sym(SYM_NIL) => None,
        name => match super::commands::resolve_router(cx, name, "format") {
            Ok(Some(r)) => Some(r),
            // an illegal name halts; an unknown router is reported and gives ""
            Err(e) if e.reported => return Err(e),
            Ok(None) | Err(_) => return Ok(cx.make_string("")?),
        },
    };
    #[cfg(feature = "extras")]
    if let Some(flag) = first_bad_flag(control.as_str()) {
        return Err(report_bad_flag(cx, control.as_str(), flag));
    }
    let needed = count_args(control.as_str());
    if needed + 2 != a.len as usize {
        return Err(arity_error(needed + 2));
    }
    let mut out = Text::new();
    let done = render(cx, a, control.as_str(), &mut out);
    // host: a result past the buffer is rendered again into one that grows (CLIPS
    // builds any length); the symbol storage, growing too, is then the limit
    #[cfg(feature = "grow")]
    if matches!(done, Err(RenderError::Eval(e)) if e == TOO_LONG) {
        let mut long = alloc::string::String::new();
        let done = render(cx, a, control.as_str(), &mut long);
        cx.st
            .eval
            .past_image
            .get_or_insert(super::strings::PAST_TEXT_MAX);
        return format_done(cx, control.as_str(), dest, done, &long);
    }
    format_done(cx, control.as_str(), dest, done, out.as_str())
}

/// `format`'s result: rendering's error, or `text` written to `dest` and returned.
fn format_done(
    cx: &mut Core<'_>,
    control: &str,
    dest: Option<super::commands::Routed>,
    done: Result<(), RenderError>,
    text: &str,
) -> Result<Value, EvalError> {
    if let Err(bad) = done {
        if let RenderError::BadFlag(flag) = bad {
            return Err(report_bad_flag(cx, control, flag));
        }
        return Err(bad.into());
    }
    if let Some(r) = dest {
        cx.write(r.name(), text);
    }
    Ok(cx.make_string(text)?)
}

/// Why rendering a control string stopped.
enum RenderError {
    Eval(EvalError),
    /// An invalid directive: its byte range in the control string (reported by the caller,
    /// whose message quotes it).
    BadFlag((usize, usize)),
}

impl From<EvalError> for RenderError {
    fn from(e: EvalError) -> Self {
        RenderError::Eval(e)
    }
}

impl From<RenderError> for EvalError {
    fn from(e: RenderError) -> Self {
        match e {
            RenderError::Eval(e) => e,
            RenderError::BadFlag(_) => EvalError::new(EvalErrorKind::Reported),
        }
    }
}

/// Expands `ctl` with the call's arguments (from argument 3 on) into `out`.
fn render<W: Write>(cx: &Core<'_>, a: Args, ctl: &str, out: &mut W) -> Result<(), RenderError> {
    let b = ctl.as_bytes();
    let (mut i, mut lit, mut next_arg) = (0, 0, 2usize);
    while i < b.len() {
        if b[i] != b'%' {
            i += 1;
            continue;
        }
        out.write_str(&ctl[lit..i]).map_err(|_| TOO_LONG)?;
        let (spec, used) = match parse_spec(&b[i + 1..]) {
            Some(p) => p,
            None => {
                lit = i;
                break;
            }
        };
        let start = i;
        i += 1 + used;
        lit = i;
        match spec.conv {
            b'n' => out.write_char('\n'),
            b't' => out.write_char('\t'),
            b'r' => out.write_char('\r'),
            b'%' if used == 1 => out.write_char('%'),
            // `%5%`: CLIPS's directive ends unfinished before the second `%`, which
            // starts the next one; the unfinished one is text (host only)
            #[cfg(feature = "extras")]
            b'%' => {
                lit = start;
                i -= 1;
                Ok(())
            }
            c if takes_arg(c) => {
                let v = cx.arg(a, next_arg);
                let argno = crate::error::arg_no(next_arg);
                next_arg += 1;
                directive(cx, spec, v, argno, out)?;
                Ok(())
            }
            // CLIPS quotes the directive up to the character it rejected
            _ => return Err(RenderError::BadFlag((start, i))),
        }
        .map_err(|_| TOO_LONG)?;
    }
    out.write_str(&ctl[lit..]).map_err(|_| TOO_LONG.into())
}

/// Formats one argument-consuming directive.
fn directive<W: Write>(
    cx: &Core<'_>,
    spec: Spec,
    v: Value,
    argno: u8,
    out: &mut W,
) -> Result<(), EvalError> {
    let mut body: TextBuf<400> = TextBuf::new();
    let numeric = spec.conv != b's' && spec.conv != b'c';
    match spec.conv {
        b's' => {
            let s = match v {
                // an instance name without its brackets, as CLIPS prints it here
                Value::Sym(s) => {
                    let t = cx.sym_text(s);
                    crate::value::instance_name_body(t).unwrap_or(t)
                }
                Value::Str(s) => cx.sym_text(s),
                _ => return Err(EvalError::wrong_type("format", argno, "symbol or string")),
            };
            let s = match spec.precision {
                // C counts bytes; cut at a character boundary so the text stays UTF-8.
                Some(p) if p < s.len() => &s[..floor_boundary(s, p)],
                _ => s,
            };
            // padded straight from the symbol table: `body` is too small for long texts
            return pad(out, spec, s, false).map_err(|_| TOO_LONG);
        }
        b'd' | b'u' | b'o' | b'x' | b'c' => {
            let n = match v {
                Value::Int(i) => i,
                Value::Float(f) => c_trunc_to_i64(f),
                _ => return Err(EvalError::wrong_type("format", argno, T_NUMBER)),
            };
            write_integer(&mut body, spec, n).map_err(|_| TOO_LONG)?;
        }
        _ => {
            let x = match v {
                Value::Int(i) => i as f64,
                Value::Float(f) => f,
                _ => return Err(EvalError::wrong_type("format", argno, T_NUMBER)),
            };
            write_float_spec(&mut body, spec, x).map_err(|_| TOO_LONG)?;
        }
    }
    pad(out, spec, body.as_str(), numeric).map_err(|_| TOO_LONG)
}

fn floor_boundary(s: &str, mut at: usize) -> usize {
    while at > 0 && !s.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// Writes `body` justified in the directive's width (zero padding goes after the sign).
/// The width counts bytes, as C's printf does in CLIPS: `%-6s` of `"año"` (4 bytes) adds 2.
fn pad<W: Write>(out: &mut W, spec: Spec, body: &str, numeric: bool) -> core::fmt::Result {
    let len = body.len();
    let fill = spec.width.saturating_sub(len);
    if spec.left {
        out.write_str(body)?;
        return spaces(out, fill, ' ');
    }
    // (the text searches only for a zero-padded number: most directives have no `0`)
    if spec.zero && numeric && !body.contains("inf") && !body.contains("nan") {
        let (sign, digits) = match body.as_bytes().first() {
            Some(b'-') => body.split_at(1),
            _ => ("", body),
        };
        out.write_str(sign)?;
        spaces(out, fill, '0')?;
        return out.write_str(digits);
    }
    spaces(out, fill, ' ')?;
    out.write_str(body)
}

fn spaces<W: Write>(out: &mut W, n: usize, c: char) -> core::fmt::Result {
    for _ in 0..n {
        out.write_char(c)?;
    }
    Ok(())
}

/// `%d %u %o %x %c` of a 64-bit integer (unsigned, octal and hex of negatives as two's
/// complement).
fn write_integer(out: &mut dyn Write, spec: Spec, n: i64) -> core::fmt::Result {
    let min_digits = spec.precision.unwrap_or(1);
    match spec.conv {
        b'c' => out.write_char(char::from(n as u8)),
        b'o' => write!(out, "{:01$o}", n as u64, min_digits),
        b'x' => write!(out, "{:01$x}", n as u64, min_digits),
        #[cfg(feature = "extras")]
        b'u' => write!(out, "{:01$}", n as u64, min_digits),
        _ => {
            if n < 0 {
                out.write_char('-')?;
            }
            write!(out, "{:01$}", n.unsigned_abs(), min_digits)
        }
    }
}

/// `%f %e %g` of a double with C's rules (default precision 6).
fn write_float_spec(out: &mut dyn Write, spec: Spec, x: f64) -> core::fmt::Result {
    if !x.is_finite() {
        let s = if x.is_nan() { "nan" } else { "inf" };
        if x.is_sign_negative() && !x.is_nan() {
            out.write_char('-')?;
        }
        return out.write_str(s);
    }
    let p = spec.precision.unwrap_or(6);
    match spec.conv {
        b'f' => write!(out, "{x:.p$}"),
        b'e' => write_exp(out, x, p),
        _ => write_general(out, x, p),
    }
}

/// C's `%.pe`: mantissa, `e`, sign, at least two exponent digits.
fn write_exp(out: &mut dyn Write, x: f64, p: usize) -> core::fmt::Result {
    let mut t: TextBuf<400> = TextBuf::new();
    write!(t, "{x:.p$e}")?;
    let (mant, exp) = t.as_str().split_once('e').unwrap_or((t.as_str(), "0"));
    let e: i32 = exp.parse().map_err(|_| core::fmt::Error)?;
    let sign = if e < 0 { '-' } else { '+' };
    write!(out, "{mant}e{sign}{:02}", e.unsigned_abs())
}

/// C's `%.pg`: `%e` or `%f` by the exponent, trailing zeros removed.
pub(super) fn write_general(out: &mut dyn Write, x: f64, p: usize) -> core::fmt::Result {
    let p = p.max(1);
    let mut t: TextBuf<400> = TextBuf::new();
    write!(t, "{x:.0$e}", p - 1)?;
    let exp: i32 = t
        .as_str()
        .split_once('e')
        .map_or(Ok(0), |(_, e)| e.parse())
        .map_err(|_| core::fmt::Error)?;
    t.clear();
    if exp < -4 || exp >= p as i32 {
        write_exp(&mut t, x, p - 1)?;
        let s = t.as_str();
        let (mant, e) = s.split_once('e').unwrap_or((s, ""));
        out.write_str(strip_zeros(mant))?;
        out.write_char('e')?;
        out.write_str(e)
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        write!(t, "{x:.decimals$}")?;
        out.write_str(strip_zeros(t.as_str()))
    }
}

/// Drops trailing fractional zeros and a then-trailing point.
fn strip_zeros(s: &str) -> &str {
    if !s.contains('.') {
        return s;
    }
    s.trim_end_matches('0').trim_end_matches('.')
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::{eval_to_string, run_program};

    /// `(format nil ...)` results, checked against CLIPS 6.30's output (046 and probes).
    #[test]
    fn directives_match_clips() {
        for (e, want) in [
            ("(format nil \"%d-%d\" 1 2)", "\"1-2\""),
            ("(format nil \"no args\")", "\"no args\""),
            (
                "(format nil \"[%5d] [%-5d] [%05d]\" 42 42 42)",
                "\"[   42] [42   ] [00042]\"",
            ),
            (
                "(format nil \"%f %e %g\" 3.14159 31415.9 0.0001)",
                "\"3.141590 3.141590e+04 0.0001\"",
            ),
            (
                "(format nil \"%.2f %8.3f %-8.1f|\" 2.71828 2.71828 2.71828)",
                "\"2.72    2.718 2.7     |\"",
            ),
            ("(format nil \"%s and %s\" abc \"def\")", "\"abc and def\""),
            (
                "(format nil \"[%10s] [%-10s]\" right left)",
                "\"[     right] [left      ]\"",
            ),
            ("(format nil \"100%%\")", "\"100%\""),
            ("(format nil \"%d\" 3.7)", "\"3\""),
            ("(format nil \"%g %g\" 100000000.0 1.5)", "\"1e+08 1.5\""),
            (
                "(format nil \"%g %g %g\" 1e-5 123456789.0 0.5)",
                "\"1e-05 1.23457e+08 0.5\"",
            ),
            ("(format nil \"%10.3e|\" 12345.678)", "\" 1.235e+04|\""),
            ("(format nil \"%c\" 65)", "\"A\""),
            ("(format nil \"%5.1s|\" abc)", "\"    a|\""),
            ("(format nil \"%e\" 0.0)", "\"0.000000e+00\""),
            ("(format nil \"abc%\")", "\"abc%\""),
            ("(format nil \"%5d|%-5s|\" -3 \"ab\")", "\"   -3|ab   |\""),
            (
                "(format nil \"%f\" 1e20)",
                "\"100000000000000000000.000000\"",
            ),
            ("(format nil \"%.0f %.0f %.0f\" 0.5 1.5 2.5)", "\"0 2 2\""),
            (
                "(format nil \"%08.2f|%-8d|%08d|%-08d|%.3d\" -3.14159 5 -42 7 5)",
                "\"-0003.14|5       |-0000042|7       |005\"",
            ),
            (
                "(format nil \"%.0e|%.0g|%.10g\" 12345.0 0.0001234 0.1)",
                "\"1e+04|0.0001|0.1\"",
            ),
            (
                "(format nil \"%5c|%x|%o\" 97 -1 -1)",
                "\"    a|ffffffffffffffff|1777777777777777777777\"",
            ),
            (
                "(format nil \"%f %e %g\" 0.0 -0.0 -0.0)",
                "\"0.000000 -0.000000e+00 -0\"",
            ),
            ("(format nil \"%d\" 1e30)", "\"-9223372036854775808\""),
            ("(format nil \"%.20f\" 0.1)", "\"0.10000000000000000555\""),
            (
                "(format nil \"%g %g %g\" 123456.5 1234567.0 100000.0)",
                "\"123456 1.23457e+06 100000\"",
            ),
            ("(format nil \"%.3g\" 0.00001234)", "\"1.23e-05\""),
            ("(format nil \"%f %e\" 2 2)", "\"2.000000 2.000000e+00\""),
            ("(format nil \"%s\" \"a\\\"b\")", "\"a\"b\""),
        ] {
            assert_eq!(eval_to_string(e), want, "{e}");
        }
    }

    #[test]
    fn escapes_and_errors() {
        assert_eq!(eval_to_string("(format nil \"%t%r|\")"), "\"\t\r|\"");
        let out = eval_to_string("(format nil \"%d %s\" 3.7 12)");
        assert!(
            out.contains("#4") && out.contains("symbol or string"),
            "{out}"
        );
        assert!(
            eval_to_string("(format nil \"%d\" a)").contains("#3 to be of type integer or float")
        );
        assert!(
            eval_to_string("(format nil \"%s%s\" a)").contains("expected exactly 4 argument(s)")
        );
        assert!(
            eval_to_string("(format nil \"%d\" 3 4)").contains("expected exactly 3 argument(s)")
        );
        assert!(eval_to_string("(format nil \"%X\" 3)").contains("[IOFUN3]"));
        assert!(eval_to_string("(format nil \"%+d\" 3)").contains("[IOFUN3]"));
        // a non-ASCII character after % is an invalid flag, not a panic
        assert!(eval_to_string("(format nil \"%\u{e9}x\" 3)").contains("[IOFUN3]"));
        assert_eq!(
            eval_to_string("(format nil \"\u{e9}%d\u{e9}\" 3)"),
            "\"\u{e9}3\u{e9}\""
        );
    }

    #[test]
    fn router_t_prints_and_returns() {
        let out = run_program("(format t \"%d items%n\" 5)\n(format nil \"quiet\")\n");
        // run_program prints results like the CLIPS prompt: the string follows the text
        assert_eq!(out, "5 items\n\"5 items\n\"\n\"quiet\"\n");
        let out = run_program("(defrule fmt (p ?x ?y) => (format t \"point (%d, %d)%n\" ?x ?y))\n(assert (p 1 2))\n(run)\n");
        assert!(out.contains("point (1, 2)\n"), "{out}");
    }
}
