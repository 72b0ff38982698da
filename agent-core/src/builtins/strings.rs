//! Builtins: string functions (sym-cat str-length sub-string str-index upcase lowcase
//! str-compare string-to-field), plus the field scanner `explode$` shares.
//!
//! Positions count characters (CLIPS 6.30 is UTF-8 aware in `str-length`,
//! `sub-string` and `str-index`); `upcase`/`lowcase` change ASCII letters only, as
//! C's `toupper` in the "C" locale does.

use super::describe::ArgType::{Any, Integer as I, Lexeme as L};
use super::describe::Returns as R;
use super::describe::{BodyNames, OnError};
use super::math::{int_arg, lexeme_arg, T_ATOM};
use super::{Args, Builtin, SYM_FALSE};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::lexer::{Lexer, Tok};
use crate::value::{SymId, TextBuf, Value};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::lazy("sym-cat", 1, super::ANY, sym_cat_in_order).on_error(OnError::Nil).returns(R::SymbolOrString),
    Builtin::eager("str-length", 1, 1, str_length).args(&[L], Any).on_error(OnError::MinusOne).body_names(BodyNames::SymbolOrString).returns(R::Integer),
    Builtin::eager("sub-string", 3, 3, sub_string).args(&[I, I, L], Any).on_error(OnError::EmptyString).body_names(BodyNames::SymbolOrString).returns(R::Str),
    Builtin::eager("str-index", 2, 2, str_index).args(&[L, L], Any).on_error(OnError::False).body_names(BodyNames::SymbolOrString),
    Builtin::eager("upcase", 1, 1, upcase).args(&[L], Any).on_error(OnError::EmptyString).body_names(BodyNames::SymbolOrString).returns(R::Lexeme),
    Builtin::eager("lowcase", 1, 1, lowcase).args(&[L], Any).on_error(OnError::EmptyString).body_names(BodyNames::SymbolOrString).returns(R::Lexeme),
    Builtin::eager("str-compare", 2, 3, str_compare).args(&[L, L, I], Any).on_error(OnError::Zero).body_names(BodyNames::SymbolOrString).returns(R::Integer),
    Builtin::eager("string-to-field", 1, 1, string_to_field).on_error(OnError::ErrorString).body_names(BodyNames::SymbolOrString)
        .args(&[super::describe::ArgType::Lexeme], super::describe::ArgType::Any),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// Longest text a string builtin builds (symbol texts longer than this are an error).
pub(super) const TEXT_MAX: usize = 2048;
pub(super) type Text = TextBuf<TEXT_MAX>;

/// Longest text `str-cat` and `sym-cat` build: `TEXT_MAX` in the image; on hosts any
/// length the symbol storage (which grows there) holds, as CLIPS.
#[cfg(not(feature = "grow"))]
const CAT_MAX: usize = TEXT_MAX;
#[cfg(feature = "grow")]
const CAT_MAX: usize = crate::value::Ix::MAX as usize;

/// What an engine with `grow` went past when it built a string longer than the
/// image's `TEXT_MAX` (see `EvalState::past_image`).
#[cfg(feature = "grow")]
pub(crate) const PAST_TEXT_MAX: &str = "a string built longer than 2048 bytes (the image's limit)";

const TOO_LONG: EvalError = EvalError::message(crate::error::Message::StringTooLong);

/// A symbol's text copied out of the table (`copy_text`): up to `TEXT_MAX` bytes in
/// the image; on hosts a longer one on the heap (CLIPS reads any length).
#[cfg(not(feature = "grow"))]
pub(super) type Copied = Text;

// (the short text stays on the stack, as in the image: no heap for the common case)
#[cfg(feature = "grow")]
#[allow(clippy::large_enum_variant)]
pub(super) enum Copied {
    Short(Text),
    Long(alloc::string::String),
}

#[cfg(feature = "grow")]
impl Copied {
    pub(super) fn as_str(&self) -> &str {
        match self {
            Copied::Short(t) => t.as_str(),
            Copied::Long(s) => s.as_str(),
        }
    }
}

/// Copies a symbol's text out of the table, so the table can be written afterwards.
pub(super) fn copy_text(cx: &Core<'_>, id: SymId) -> Result<Copied, EvalError> {
    let mut b = Text::new();
    let text = cx.sym_text(id);
    #[cfg(feature = "grow")]
    if text.len() > TEXT_MAX {
        return Ok(Copied::Long(alloc::string::String::from(text)));
    }
    core::fmt::Write::write_str(&mut b, text).map_err(|_| TOO_LONG)?;
    #[cfg(feature = "grow")]
    return Ok(Copied::Short(b));
    #[cfg(not(feature = "grow"))]
    Ok(b)
}

fn push_str(b: &mut Text, s: &str) -> Result<(), EvalError> {
    core::fmt::Write::write_str(b, s).map_err(|_| TOO_LONG)
}

/// A value of the same kind (symbol or string) as `like`, with text `s`.
fn same_kind(cx: &mut Core<'_>, like: Value, s: &str) -> Result<Value, EvalError> {
    Ok(match like {
        Value::Sym(_) => cx.make_symbol(s)?,
        _ => cx.make_string(s)?,
    })
}

/// The text a string function sees in lexeme `v` (symbol `s`'s text): an instance
/// name's without its brackets, as CLIPS (`value::instance_name_body`).
fn body<'a>(cx: &'a Core<'_>, v: Value, s: SymId) -> &'a str {
    let t = cx.sym_text(s);
    match v {
        Value::Sym(_) => crate::value::instance_name_body(t).unwrap_or(t),
        _ => t,
    }
}

/// A symbol spelled `[x]` would be an instance name here (CLIPS makes a symbol): refused.
pub(super) fn sym_cat(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cat(cx, a, false)?;
    if let Value::Sym(s) = v {
        // host: `instance_name_body`'s test on the bytes (a symbol's are its text's)
        #[cfg(feature = "host-speedups")]
        let instance_name = matches!(cx.sym_texts().text_bytes(s), [b'[', _, .., b']']);
        #[cfg(not(feature = "host-speedups"))]
        let instance_name = crate::value::instance_name_body(cx.sym_text(s)).is_some();
        if instance_name {
            cx.write(
                router::WERROR,
                "[NOTIMPL1] robotino-agent cannot make a symbol spelled as an instance name [x]\n",
            );
            return Err(EvalError::already_reported());
        }
    }
    Ok(v)
}

pub(super) fn str_cat(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    cat(cx, a, true)
}

/// `sym-cat` and `str-cat` calls: CLIPS checks each argument as it evaluates it, and
/// one that cannot be concatenated stops the call before the next runs.
fn sym_cat_in_order(cx: &mut Core<'_>, call: crate::value::Ix) -> Result<Value, EvalError> {
    #[cfg(feature = "host-speedups")]
    return cx.cat_in_order(call, sym_cat, "sym-cat", T_ATOM);
    #[cfg(not(feature = "host-speedups"))]
    cx.call_in_order(call, sym_cat, |cx, a, _| cat_arg(cx, "sym-cat", a))
}

pub(super) fn str_cat_in_order(
    cx: &mut Core<'_>,
    call: crate::value::Ix,
) -> Result<Value, EvalError> {
    #[cfg(feature = "host-speedups")]
    return cx.cat_in_order(call, str_cat, "str-cat", T_ATOM);
    #[cfg(not(feature = "host-speedups"))]
    cx.call_in_order(call, str_cat, |cx, a, _| cat_arg(cx, "str-cat", a))
}

/// The newest argument of a `str-cat` or `sym-cat` call (the last of `a`), checked as
/// `cat` checks them all.
#[cfg_attr(feature = "host-speedups", allow(dead_code))]
fn cat_arg(cx: &mut Core<'_>, name: &'static str, a: Args) -> Result<(), EvalError> {
    let i = a.len as usize - 1;
    if matches!(cx.arg(a, i), Value::Multi(_) | Value::Fact(_) | Value::Void) {
        return Err(EvalError::wrong_type(name, crate::error::arg_no(i), T_ATOM));
    }
    Ok(())
}

/// `str-cat` (`string`) or `sym-cat`: up to `CAT_MAX` bytes, built in the symbol arena
/// (a `Text` here was the image's deepest stack frame; a 1 KiB one cut str-cat short).
fn cat(cx: &mut Core<'_>, a: Args, string: bool) -> Result<Value, EvalError> {
    let name = if string { "str-cat" } else { "sym-cat" };
    cx.make_lexeme_with(string, a, CAT_MAX, |view, args, out| {
        for (i, &v) in args.iter().enumerate() {
            // CLIPS rejects multifields, fact addresses and no value alike
            if matches!(v, Value::Multi(_) | Value::Fact(_) | Value::Void) {
                return Err(EvalError::wrong_type(name, crate::error::arg_no(i), T_ATOM));
            }
            // an instance name is catenated without its brackets (CLIPS)
            let inner = match v {
                Value::Sym(s) => crate::value::instance_name_body(view.sym(s)),
                _ => None,
            };
            match inner {
                Some(t) => out.write_str(t),
                None => view.write_flat(out, v, false),
            }
            .map_err(|_| TOO_LONG)?;
        }
        Ok(())
    })
}

fn str_length(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = lexeme_arg(cx, a, 0, "str-length")?;
    Ok(Value::Int(body(cx, cx.arg(a, 0), s).chars().count() as i64))
}

/// A symbol's stored bytes `b` when they are all ASCII, without the brackets of an
/// instance name when `inst` (as `instance_name_body`); None otherwise.
#[cfg(feature = "host-speedups")]
#[inline(always)]
fn ascii_body(b: &[u8], inst: bool) -> Option<&[u8]> {
    let b = match b {
        [b'[', body @ .., b']'] if inst && !body.is_empty() => body,
        _ => b,
    };
    b.is_ascii().then_some(b)
}

/// Byte offset of character `k` (0-based) of `s`, or `s.len()` past the end.
fn char_offset(s: &str, k: usize) -> usize {
    s.char_indices().nth(k).map_or(s.len(), |(i, _)| i)
}

/// `(sub-string start end s)`: 1-based inclusive character positions, clamped to the
/// string; an empty range gives `""`.
fn sub_string(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let start = int_arg(cx, a, 0, "sub-string")?;
    let end = int_arg(cx, a, 1, "sub-string")?;
    let s = lexeme_arg(cx, a, 2, "sub-string")?;
    let inst = matches!(cx.arg(a, 2), Value::Sym(_));
    // host: an ASCII cut that is a symbol already (a cut taken again, as a join test
    // does per pair) is found from its bytes where they are, not written out first
    #[cfg(feature = "host-speedups")]
    {
        let syms = cx.syms();
        let texts = crate::symbols::SymTexts {
            rom: syms.rom,
            entries: &*syms.entries,
            bytes: &*syms.bytes,
        };
        if let Some(t) = ascii_body(texts.text_bytes(s), inst) {
            let (from, to) = (start.max(1), end.min(t.len() as i64));
            let part = match from > to {
                true => &t[..0],
                false => &t[from as usize - 1..to as usize],
            };
            // SAFETY: `part` is ASCII (`ascii_body`), and ASCII bytes are UTF-8.
            let part = unsafe { core::str::from_utf8_unchecked(part) };
            if let Some(id) = syms.find(part) {
                return Ok(Value::Str(id));
            }
        }
    }
    // copied within the symbol arena (a `Text` here was the image's deepest stack frame)
    cx.make_lexeme_with(true, a, CAT_MAX, |view, _, out| {
        // host: an ASCII text's characters are its bytes, so the positions index the
        // bytes without reading the text as UTF-8 or counting its characters
        #[cfg(feature = "host-speedups")]
        if let Some(t) = ascii_body(view.syms.text_bytes(s), inst) {
            let (from, to) = (start.max(1), end.min(t.len() as i64));
            if from > to {
                return Ok(());
            }
            let part = &t[from as usize - 1..to as usize];
            // SAFETY: `part` is ASCII (`ascii_body`), and ASCII bytes are UTF-8.
            let part = unsafe { core::str::from_utf8_unchecked(part) };
            return out.write_str(part).map_err(|_| TOO_LONG);
        }
        let t = view.sym(s);
        let t = match inst {
            true => crate::value::instance_name_body(t).unwrap_or(t),
            false => t,
        };
        let nchars = t.chars().count() as i64;
        let (from, to) = (start.max(1), end.min(nchars));
        if from > to {
            return Ok(());
        }
        let (b0, b1) = (
            char_offset(t, from as usize - 1),
            char_offset(t, to as usize),
        );
        out.write_str(&t[b0..b1]).map_err(|_| TOO_LONG)
    })
}

/// `(str-index needle haystack)`: 1-based character position of the first occurrence,
/// or FALSE. CLIPS answers an empty needle with one past the haystack's length.
fn str_index(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let needle = lexeme_arg(cx, a, 0, "str-index")?;
    let hay = lexeme_arg(cx, a, 1, "str-index")?;
    let (n, h) = (body(cx, cx.arg(a, 0), needle), body(cx, cx.arg(a, 1), hay));
    if n.is_empty() {
        return Ok(Value::Int(h.chars().count() as i64 + 1));
    }
    Ok(match h.find(n) {
        Some(at) => Value::Int(h[..at].chars().count() as i64 + 1),
        None => Value::Sym(SYM_FALSE),
    })
}

fn change_case(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    upper: bool,
) -> Result<Value, EvalError> {
    let s = lexeme_arg(cx, a, 0, func)?;
    let text = copy_text(cx, s)?;
    // host: a text past the buffer is changed in a copy that grows (CLIPS any length)
    #[cfg(feature = "grow")]
    if text.as_str().len() > TEXT_MAX {
        let mut out = alloc::string::String::from(text.as_str());
        match upper {
            true => out.make_ascii_uppercase(),
            false => out.make_ascii_lowercase(),
        }
        let like = cx.arg(a, 0);
        return same_kind(cx, like, &out);
    }
    let mut out = Text::new();
    for ch in text.as_str().chars() {
        let c = if upper {
            ch.to_ascii_uppercase()
        } else {
            ch.to_ascii_lowercase()
        };
        let mut tmp = [0u8; 4];
        push_str(&mut out, c.encode_utf8(&mut tmp))?;
    }
    let like = cx.arg(a, 0);
    same_kind(cx, like, out.as_str())
}

fn upcase(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    change_case(cx, a, "upcase", true)
}

fn lowcase(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    change_case(cx, a, "lowcase", false)
}

/// `strcmp`/`strncmp` normalised to -1, 0, 1; a negative length compares everything
/// (C converts it to a huge `size_t`).
fn str_compare(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x = lexeme_arg(cx, a, 0, "str-compare")?;
    let y = lexeme_arg(cx, a, 1, "str-compare")?;
    let limit = if a.len > 2 {
        int_arg(cx, a, 2, "str-compare")?
    } else {
        -1
    };
    let (p, q) = (
        body(cx, cx.arg(a, 0), x).as_bytes(),
        body(cx, cx.arg(a, 1), y).as_bytes(),
    );
    let (p, q) = if limit >= 0 {
        let n = limit as usize;
        (&p[..p.len().min(n)], &q[..q.len().min(n)])
    } else {
        (p, q)
    };
    Ok(Value::Int(match p.cmp(q) {
        core::cmp::Ordering::Less => -1,
        core::cmp::Ordering::Equal => 0,
        core::cmp::Ordering::Greater => 1,
    }))
}

/// The first field of a string as CLIPS's scanner reads it; an empty string gives the
/// symbol `EOF`.
fn string_to_field(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = lexeme_arg(cx, a, 0, "string-to-field")?;
    let text = copy_text(cx, s)?;
    let mut lx = Lexer::new(text.as_str());
    match scan_field(cx, &mut lx)? {
        Some(v) => Ok(v),
        None => Ok(cx.make_symbol("EOF")?),
    }
}

/// Reads the next field from `lx` as `explode$` and `string-to-field` see it: numbers,
/// symbols and strings as themselves, every other token (parentheses, variables,
/// connectives) as a string of its text. `None` at the end of the text. An unterminated
/// string prints CLIPS's `[SCANNER1]` message and yields the rest of the text.
pub(super) fn scan_field(
    cx: &mut Core<'_>,
    lx: &mut Lexer<'_>,
) -> Result<Option<Value>, EvalError> {
    let t = lx.next_token();
    let src = lx.source();
    Ok(Some(match t.tok {
        Tok::Eof => return Ok(None),
        Tok::Int(i) => Value::Int(i),
        Tok::Float(f) => Value::Float(f),
        Tok::Symbol(s) => cx.make_symbol(s)?,
        Tok::Str(raw) => {
            let body = unescape(raw)?;
            cx.make_string(body.as_str())?
        }
        Tok::Bad if src[t.start..].starts_with('"') => {
            cx.write(
                router::WERROR,
                "\n[SCANNER1] Encountered End-Of-File while scanning a string\n",
            );
            let body = unescape(&src[t.start + 1..t.end])?;
            cx.make_string(body.as_str())?
        }
        _ => cx.make_string(&src[t.start..t.end])?,
    }))
}

/// A string literal's contents with `\x` escapes resolved to `x` (on hosts one past
/// `TEXT_MAX` bytes on the heap).
fn unescape(raw: &str) -> Result<Copied, EvalError> {
    #[cfg(feature = "grow")]
    if raw.len() > TEXT_MAX {
        let mut b = alloc::string::String::new();
        unescape_into(raw, &mut b).map_err(|_| TOO_LONG)?;
        return Ok(Copied::Long(b));
    }
    let mut b = Text::new();
    let mut escaped = false;
    for ch in raw.chars() {
        if escaped || ch != '\\' {
            let mut tmp = [0u8; 4];
            push_str(&mut b, ch.encode_utf8(&mut tmp))?;
            escaped = false;
        } else {
            escaped = true;
        }
    }
    #[cfg(feature = "grow")]
    return Ok(Copied::Short(b));
    #[cfg(not(feature = "grow"))]
    Ok(b)
}

/// `unescape` into a text that grows (hosts).
#[cfg(feature = "grow")]
fn unescape_into(raw: &str, b: &mut alloc::string::String) -> core::fmt::Result {
    let mut escaped = false;
    for ch in raw.chars() {
        if escaped || ch != '\\' {
            b.push(ch);
            escaped = false;
        } else {
            escaped = true;
        }
    }
    Ok(())
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::testutil::{eval_to_string, run_program};

    fn check(cases: &[(&str, &str)]) {
        for (e, want) in cases {
            assert_eq!(eval_to_string(e), *want, "{e}");
        }
    }

    #[test]
    fn sym_cat_and_lengths() {
        // expected values as printed by CLIPS 6.30 (tests/clips/052, 085)
        check(&[
            ("(sym-cat a \"b\" 3)", "ab3"),
            ("(sym-cat \"x\" 1.5)", "x1.5"),
            ("(sym-cat 1.0 2)", "1.02"),
            ("(symbolp (sym-cat \"has space\"))", "TRUE"),
            ("(eq (sym-cat a b) ab)", "TRUE"),
            ("(str-length \"hello\")", "5"),
            ("(str-length \"\")", "0"),
            ("(str-length abc)", "3"),
            ("(str-length \"a\\\"b\")", "3"),
            ("(str-length \"\u{e4}b\")", "2"),
        ]);
        let out = run_program("(assert (a))\n(sym-cat (nth$ 1 (find-all-facts ((?x a)) TRUE)))\n");
        assert!(
            out.contains("sym-cat") && out.contains("string, instance name"),
            "{out}"
        );
        let out = eval_to_string("(sym-cat (create$ a))");
        assert!(
            out.contains("sym-cat") && out.contains("#1") && out.contains("string, instance name"),
            "{out}"
        );
        // a computed argument (of a type unknown while parsing) is checked in the body:
        // other type names, fallback -1
        let out =
            crate::testutil::run_program("(deffunction mf () (create$ a))\n(str-length (mf))\n");
        assert_eq!(
            out,
            "[ARGACCES5] Function str-length expected argument #1 to be of type symbol or string\n-1\n"
        );
        // a literal one by the argument restriction at parse time, as in CLIPS: the
        // message (then our position line), and no value
        let out = eval_to_string("(str-length 1)");
        assert!(
            out.starts_with("[ARGACCES5] Function str-length expected argument #1 to be of type symbol, string, or instance name"),
            "{out}"
        );
        assert!(!out.contains("-1"), "{out}");
    }

    #[test]
    #[cfg(not(feature = "grow"))]
    fn str_cat_reaches_the_string_limit_and_names_it() {
        // 2040 bytes fit (a 1 KiB buffer cut them before); 2050 exceed TEXT_MAX, and the
        // message gives that limit
        let lit = "0123456789".repeat(68);
        for f in ["str-cat", "sym-cat"] {
            let out = eval_to_string(&std::format!(
                "(str-length ({f} \"{lit}\" \"{lit}\" \"{lit}\"))"
            ));
            assert_eq!(out, "2040", "{f}");
            let out = eval_to_string(&std::format!(
                "({f} \"{lit}\" \"{lit}\" \"{lit}\" 0123456789)"
            ));
            assert!(out.contains("longer than 2048 bytes"), "{f}: {out}");
        }
    }

    #[test]
    fn sub_string_clamps() {
        check(&[
            ("(sub-string 2 4 \"abcdef\")", "\"bcd\""),
            ("(sub-string 1 1 \"abc\")", "\"a\""),
            ("(sub-string 3 10 \"abcdef\")", "\"cdef\""),
            ("(sub-string 4 2 \"abcdef\")", "\"\""),
            ("(sub-string 0 2 \"abc\")", "\"ab\""),
            ("(sub-string -5 100 \"abc\")", "\"abc\""),
            ("(sub-string 4 4 \"abc\")", "\"\""),
            ("(sub-string 1 1 \"\u{e4}b\")", "\"\u{e4}\""),
            ("(sub-string 1 2 sym)", "\"sy\""),
            // brackets kept in a string, not in an instance name; non-ASCII by characters
            ("(sub-string 1 2 \"[ab]\")", "\"[a\""),
            ("(sub-string 2 3 [abc])", "\"bc\""),
            ("(sub-string 2 2 [])", "\"]\""),
            ("(sub-string 2 4 \"x\u{e4}y\u{e4}z\")", "\"\u{e4}y\u{e4}\""),
            ("(sub-string 5 5 \"x\u{e4}y\u{e4}z\")", "\"z\""),
        ]);
        assert!(eval_to_string("(sub-string (float 1) 2 \"abc\")").contains("type integer"));
    }

    #[test]
    fn str_index_positions() {
        check(&[
            ("(str-index \"cd\" \"abcdef\")", "3"),
            ("(str-index \"z\" \"abcdef\")", "FALSE"),
            ("(str-index \"a\" \"banana\")", "2"),
            ("(str-index \"\" \"abc\")", "4"),
            ("(str-index \"\" \"\")", "1"),
            ("(str-index \"b\" \"\u{e4}b\")", "2"),
        ]);
    }

    #[test]
    fn case_changes_keep_the_type() {
        check(&[
            ("(upcase \"Hello World\")", "\"HELLO WORLD\""),
            ("(upcase abc)", "ABC"),
            ("(lowcase \"MiXeD\")", "\"mixed\""),
            ("(lowcase XYZ)", "xyz"),
            ("(upcase \"123 abc!\")", "\"123 ABC!\""),
            ("(lowcase \"\")", "\"\""),
            ("(upcase \"\u{e4}b\")", "\"\u{e4}B\""),
        ]);
    }

    #[test]
    fn str_compare_signs() {
        check(&[
            ("(str-compare \"a\" \"b\")", "-1"),
            ("(str-compare \"b\" \"a\")", "1"),
            ("(str-compare \"abc\" \"abc\")", "0"),
            ("(str-compare \"a\" \"B\")", "1"),
            ("(str-compare \"ab\" \"abc\")", "-1"),
            ("(str-compare \"abc\" \"abd\" 2)", "0"),
            ("(str-compare \"b\" \"abc\" 0)", "0"),
            ("(str-compare \"b\" \"abc\" -1)", "1"),
        ]);
    }

    #[test]
    fn string_to_field_reads_one_token() {
        check(&[
            ("(string-to-field \"3.5 x\")", "3.5"),
            ("(string-to-field \"abc\")", "abc"),
            ("(string-to-field \"  12  \")", "12"),
            ("(string-to-field \"\\\"q\\\"\")", "\"q\""),
            ("(string-to-field \"\")", "EOF"),
            ("(string-to-field \"(a b)\")", "\"(\""),
            ("(string-to-field \"?x\")", "\"?x\""),
        ]);
        let out = run_program("(printout t (string-to-field \"\\\"open\") crlf)\n");
        assert!(
            out.contains("[SCANNER1] Encountered End-Of-File while scanning a string"),
            "{out}"
        );
        assert!(out.contains("open\n"), "{out}");
    }
}
