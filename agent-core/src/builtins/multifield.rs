//! Builtins: multifield functions (create$ length$ nth$ member$ subsetp insert$ delete$
//! replace$ first$ rest$ subseq$ implode$ explode$).
//!
//! Results are new multifields in scratch; inputs are read before the result is built
//! (their elements stay below the result, so copying element by element is safe).

use super::describe::ArgType::{Any, Integer as I, Multifield as M, Str as S};
use super::describe::OnError;
use super::describe::Returns as R;
use super::math::{int_arg, T_MULTI};
use super::strings::{scan_field, Text};
use super::{Args, Builtin, ANY, SYM_FALSE, SYM_NIL};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::lexer::Lexer;
use crate::value::Ix;
use crate::value::{MfSpan, TextBuf, Value};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("create$", 0, ANY, create).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("length$", 1, 1, length).args(&[super::describe::ArgType::Sequence], super::describe::ArgType::Any).on_error(OnError::MinusOne).returns(R::Integer),
    // CLIPS 6.30 still accepts the old name (its body's messages say `length$`)
    Builtin::eager("length", 1, 1, length).args(&[super::describe::ArgType::Sequence], super::describe::ArgType::Any).on_error(OnError::MinusOne).returns(R::Integer),
    Builtin::eager("nth$", 2, 2, nth).args(&[I, M], Any).on_error(OnError::Nil),
    Builtin::eager("member$", 2, 2, member).args(&[Any, M], Any).on_error(OnError::False),
    Builtin::eager("subsetp", 2, 2, subsetp).args(&[M, M], Any).on_error(OnError::False).returns(R::Symbol),
    Builtin::eager("insert$", 3, ANY, insert).args(&[M, I], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("delete$", 3, 3, delete).args(&[M, I, I], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("replace$", 4, ANY, replace).args(&[M, I, I], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("first$", 1, 1, first).args(&[M], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("rest$", 1, 1, rest).args(&[M], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("subseq$", 3, 3, subseq).args(&[M, I, I], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("implode$", 1, 1, implode).args(&[M], Any).on_error(OnError::EmptyString).returns(R::Str),
    Builtin::eager("delete-member$", 2, ANY, delete_member).args(&[M], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("replace-member$", 3, ANY, replace_member).args(&[M], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
    Builtin::eager("explode$", 1, 1, explode).args(&[S], Any).on_error(OnError::EmptyMultifield).returns(R::Multifield),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

pub(super) fn multi_arg(
    cx: &Core<'_>,
    a: Args,
    i: usize,
    func: &'static str,
) -> Result<MfSpan, EvalError> {
    match cx.arg(a, i) {
        Value::Multi(m) => Ok(m),
        _ => Err(EvalError::wrong_type(
            func,
            crate::error::arg_no(i),
            T_MULTI,
        )),
    }
}

/// Appends `v` to the multifield being built, splicing a multifield's elements.
/// (Host: in line in its callers, `create$` above all: out of line it cost a
/// benchmark 0.35 %.)
#[cfg_attr(feature = "host-speedups", inline(always))]
pub(super) fn push_flat(cx: &mut Core<'_>, v: Value) -> Result<(), EvalError> {
    match v {
        Value::Multi(m) => {
            for k in 0..m.len as usize {
                let item = cx.mf_item(m, k);
                cx.multi_push(item)?;
            }
        }
        _ => cx.multi_push(v)?,
    }
    Ok(())
}

/// Appends elements `from..to` (0-based, exclusive) of `m`.
pub(super) fn push_range(
    cx: &mut Core<'_>,
    m: MfSpan,
    from: usize,
    to: usize,
) -> Result<(), EvalError> {
    for k in from..to {
        let item = cx.mf_item(m, k);
        cx.multi_push(item)?;
    }
    Ok(())
}

/// A multifield holding elements `from..to` of `m` (a sub-span: no copy needed).
pub(super) fn slice(m: MfSpan, from: usize, to: usize) -> Value {
    Value::Multi(MfSpan {
        start: m.start + from as Ix,
        len: to.saturating_sub(from) as Ix,
    })
}

pub(super) fn create(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    for i in 0..a.len as usize {
        // a call without a value adds nothing (CLIPS; insert$ and replace$ keep it)
        let v = cx.arg(a, i);
        if !matches!(v, Value::Void) {
            push_flat(cx, v)?;
        }
    }
    Ok(cx.multi_finish(start))
}

/// Elements of a multifield; for a symbol or string CLIPS answers its length in bytes;
/// -1 after the error for another value.
fn length(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(match cx.arg(a, 0) {
        Value::Multi(m) => m.len as i64,
        // an instance name is none of the three (CLIPS)
        Value::Sym(s) if crate::value::instance_name_body(cx.sym_text(s)).is_none() => {
            cx.sym_text(s).len() as i64
        }
        Value::Str(s) => cx.sym_text(s).len() as i64,
        _ => {
            return Err(EvalError::wrong_type(
                "length$",
                1,
                "multifield, symbol, or string",
            ))
        }
    }))
}

/// `(nth$ i m)`: element `i` (1-based) or `nil` when out of range.
pub(super) fn nth(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let i = int_arg(cx, a, 0, "nth$")?;
    let m = multi_arg(cx, a, 1, "nth$")?;
    Ok(if i >= 1 && i <= m.len as i64 {
        cx.mf_item(m, i as usize - 1)
    } else {
        Value::Sym(SYM_NIL)
    })
}

/// Position of `needle`'s elements as a contiguous run inside `hay`, 0-based.
fn find_run(cx: &Core<'_>, needle: MfSpan, hay: MfSpan) -> Option<usize> {
    let (n, h) = (needle.len as usize, hay.len as usize);
    (0..=h.checked_sub(n)?)
        .find(|&at| (0..n).all(|k| cx.mf_item(needle, k).same(cx.mf_item(hay, at + k))))
}

/// `(member$ x m)`: 1-based index of the first element `eq` to `x`, or FALSE. A
/// multifield `x` of two or more elements is searched as a run and answered with its
/// `(start end)`; CLIPS answers an empty one with `(1 0)`.
pub(super) fn member(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let hay = multi_arg(cx, a, 1, "member$")?;
    let found = match cx.arg(a, 0) {
        Value::Multi(n) if n.len == 1 => find_run(cx, n, hay).map(|at| (at, 1)),
        Value::Multi(n) => find_run(cx, n, hay).map(|at| (at, n.len as usize)),
        x => (0..hay.len as usize)
            .find(|&k| cx.mf_item(hay, k).same(x))
            .map(|at| (at, 1)),
    };
    let single = !matches!(cx.arg(a, 0), Value::Multi(n) if n.len != 1);
    Ok(match found {
        None => Value::Sym(SYM_FALSE),
        Some((at, _)) if single => Value::Int(at as i64 + 1),
        Some((at, n)) => {
            cx.make_multi(&[Value::Int(at as i64 + 1), Value::Int((at + n) as i64)])?
        }
    })
}

/// `(subsetp a b)`: every element of `a` occurs in `b` (`eq` comparison).
pub(super) fn subsetp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let sub = multi_arg(cx, a, 0, "subsetp")?;
    let sup = multi_arg(cx, a, 1, "subsetp")?;
    let all = (0..sub.len as usize)
        .all(|i| (0..sup.len as usize).any(|k| cx.mf_item(sub, i).same(cx.mf_item(sup, k))));
    Ok(Core::bool_value(all))
}

/// Length of the first of `members` (atoms, or multifields as runs) found at position
/// `at` of `m`; empty multifields never match.
fn member_at(
    cx: &Core<'_>,
    m: MfSpan,
    at: usize,
    a: Args,
    members: core::ops::Range<usize>,
) -> Option<usize> {
    let rest = m.len as usize - at;
    members.map(|i| cx.arg(a, i)).find_map(|x| match x {
        Value::Multi(n) => {
            let len = n.len as usize;
            let hit = len > 0
                && len <= rest
                && (0..len).all(|k| cx.mf_item(n, k).same(cx.mf_item(m, at + k)));
            hit.then_some(len)
        }
        x => cx.mf_item(m, at).same(x).then_some(1),
    })
}

/// Copies `m` with every occurrence of the arguments from `first_member` on replaced
/// by argument `with` (spliced), or dropped when `with` is `None`.
fn substitute(
    cx: &mut Core<'_>,
    a: Args,
    m: MfSpan,
    with: Option<usize>,
    first_member: usize,
) -> Result<Value, EvalError> {
    let start = cx.multi_begin();
    let mut at = 0;
    while at < m.len as usize {
        match member_at(cx, m, at, a, first_member..a.len as usize) {
            Some(len) => {
                if let Some(w) = with {
                    let v = cx.arg(a, w);
                    push_flat(cx, v)?;
                }
                at += len;
            }
            None => {
                let item = cx.mf_item(m, at);
                cx.multi_push(item)?;
                at += 1;
            }
        }
    }
    Ok(cx.multi_finish(start))
}

/// `(delete-member$ m x...)`: `m` without any occurrence of the `x`s (a multifield `x`
/// is a run of elements).
fn delete_member(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "delete-member$")?;
    substitute(cx, a, m, None, 1)
}

/// `(replace-member$ m new x...)`: every occurrence of the `x`s replaced by `new`.
fn replace_member(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "replace-member$")?;
    substitute(cx, a, m, Some(1), 2)
}

/// `[MULTIFUN1]`: CLIPS names the bad index (or range) and the valid one, 1..`max`.
pub(super) fn index_error(
    cx: &mut Core<'_>,
    func: &'static str,
    s: i64,
    e: i64,
    max: usize,
) -> EvalError {
    let mut b: TextBuf<160> = TextBuf::new();
    let _ = if s == e {
        writeln!(
            b,
            "[MULTIFUN1] Multifield index {s} out of range 1..{max} in function {func}."
        )
    } else {
        writeln!(
            b,
            "[MULTIFUN1] Multifield index range {s}..{e} out of range 1..{max} in function {func}."
        )
    };
    cx.write(router::WERROR, b.as_str());
    EvalError::new(EvalErrorKind::Reported)
}

/// Checks a `delete$`/`replace$` range `s..e` (1-based, inclusive) against `len`.
fn checked_range(
    cx: &mut Core<'_>,
    func: &'static str,
    s: i64,
    e: i64,
    len: usize,
) -> Result<(usize, usize), EvalError> {
    if s < 1 || e > len as i64 || s > e {
        return Err(index_error(cx, func, s, e, len));
    }
    Ok((s as usize - 1, e as usize))
}

/// `(insert$ m i v...)`: values (multifields spliced) before position `i`; an index past
/// the end appends, below 1 is an error.
fn insert(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "insert$")?;
    let i = int_arg(cx, a, 1, "insert$")?;
    if i < 1 {
        return Err(index_error(cx, "insert$", i, i, m.len as usize + 1));
    }
    let at = (i as usize - 1).min(m.len as usize);
    let start = cx.multi_begin();
    push_range(cx, m, 0, at)?;
    for k in 2..a.len as usize {
        let v = cx.arg(a, k);
        push_flat(cx, v)?;
    }
    push_range(cx, m, at, m.len as usize)?;
    Ok(cx.multi_finish(start))
}

fn delete(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "delete$")?;
    let s = int_arg(cx, a, 1, "delete$")?;
    let e = int_arg(cx, a, 2, "delete$")?;
    let (from, to) = checked_range(cx, "delete$", s, e, m.len as usize)?;
    let start = cx.multi_begin();
    push_range(cx, m, 0, from)?;
    push_range(cx, m, to, m.len as usize)?;
    Ok(cx.multi_finish(start))
}

fn replace(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "replace$")?;
    let s = int_arg(cx, a, 1, "replace$")?;
    let e = int_arg(cx, a, 2, "replace$")?;
    let (from, to) = checked_range(cx, "replace$", s, e, m.len as usize)?;
    let start = cx.multi_begin();
    push_range(cx, m, 0, from)?;
    for k in 3..a.len as usize {
        let v = cx.arg(a, k);
        push_flat(cx, v)?;
    }
    push_range(cx, m, to, m.len as usize)?;
    Ok(cx.multi_finish(start))
}

fn first(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "first$")?;
    Ok(slice(m, 0, (m.len as usize).min(1)))
}

fn rest(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "rest$")?;
    let from = (m.len as usize).min(1);
    Ok(slice(m, from, m.len as usize))
}

/// `(subseq$ m s e)`: indices clamped to the multifield; an empty range gives `()`.
fn subseq(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "subseq$")?;
    let s = int_arg(cx, a, 1, "subseq$")?.max(1);
    let e = int_arg(cx, a, 2, "subseq$")?.min(m.len as i64);
    Ok(if s > e {
        slice(m, 0, 0)
    } else {
        slice(m, s as usize - 1, e as usize)
    })
}

/// `(implode$ m)`: elements as CLIPS prints them, separated by single spaces, as one
/// string. Strings are written in quotes with inner `"` and `\\` escaped (CLIPS 6.30:
/// `(implode$ (create$ "a\\b"))` has 6 characters).
pub(super) fn implode(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let m = multi_arg(cx, a, 0, "implode$")?;
    let mut b = Text::new();
    let done = write_implode(cx, m, &mut b);
    // host: a result past the buffer is written again into one that grows (CLIPS
    // builds any length); the symbol storage, growing too, is then the limit
    #[cfg(feature = "grow")]
    if done.is_err() {
        let mut long = alloc::string::String::new();
        write_implode(cx, m, &mut long)
            .map_err(|_| EvalError::message(crate::error::Message::ImplodeTooLong))?;
        cx.st
            .eval
            .past_image
            .get_or_insert(super::strings::PAST_TEXT_MAX);
        return Ok(cx.make_string(&long)?);
    }
    done.map_err(|_| EvalError::message(crate::error::Message::ImplodeTooLong))?;
    Ok(cx.make_string(b.as_str())?)
}

fn write_implode<W: core::fmt::Write>(cx: &Core<'_>, m: MfSpan, b: &mut W) -> core::fmt::Result {
    for k in 0..m.len as usize {
        if k > 0 {
            b.write_char(' ')?;
        }
        match cx.mf_item(m, k) {
            Value::Str(s) => {
                b.write_char('"')?;
                for ch in cx.sym_text(s).chars() {
                    if ch == '"' || ch == '\\' {
                        b.write_char('\\')?;
                    }
                    b.write_char(ch)?;
                }
                b.write_char('"')?;
            }
            v => cx.write_plain(b, v)?,
        }
    }
    Ok(())
}

/// `(explode$ s)`: the fields of a string as CLIPS's scanner reads them.
pub(super) fn explode(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let s = match cx.arg(a, 0) {
        Value::Str(s) => s,
        _ => return Err(EvalError::wrong_type("explode$", 1, "string")),
    };
    let text = super::strings::copy_text(cx, s)?;
    let mut lx = Lexer::new(text.as_str());
    let start = cx.multi_begin();
    while let Some(v) = scan_field(cx, &mut lx)? {
        cx.multi_push(v)?;
    }
    Ok(cx.multi_finish(start))
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::{eval_to_string, run_program};

    fn check(cases: &[(&str, &str)]) {
        for (e, want) in cases {
            assert_eq!(eval_to_string(e), *want, "{e}");
        }
    }

    #[test]
    fn create_length_nth() {
        // expected values as printed by CLIPS 6.30 (tests/clips/053 and probes)
        check(&[
            ("(create$ a b c)", "(a b c)"),
            ("(create$ 1 (create$ 2 3) 4)", "(1 2 3 4)"),
            ("(create$)", "()"),
            ("(create$ (create$))", "()"),
            ("(create$ a \"b\" 1.0)", "(a \"b\" 1.0)"),
            ("(length$ (create$ a b c))", "3"),
            ("(length$ (create$))", "0"),
            ("(length (create$ a b))", "2"),
            ("(length$ a)", "1"),
            ("(length$ \"abc\")", "3"),
            ("(length$ \"\u{e4}b\")", "3"),
            ("(nth$ 2 (create$ a b c))", "b"),
            ("(nth$ 1 (create$ a))", "a"),
            ("(nth$ 5 (create$ a b c))", "nil"),
            ("(nth$ 0 (create$ a))", "nil"),
            ("(nth$ -1 (create$ a))", "nil"),
        ]);
        assert!(eval_to_string("(length$ 5)").contains("multifield, symbol, or string"));
        assert!(eval_to_string("(nth$ (float 1) (create$ a))").contains("#1 to be of type integer"));
    }

    #[test]
    fn member_and_subsetp() {
        check(&[
            ("(member$ b (create$ a b c))", "2"),
            ("(member$ z (create$ a b c))", "FALSE"),
            ("(member$ 1 (create$ 1.0 1))", "2"),
            ("(member$ (create$ b c) (create$ a b c d))", "(2 3)"),
            ("(member$ (create$ c b) (create$ a b c d))", "FALSE"),
            ("(member$ (create$ a) (create$ a))", "1"),
            ("(member$ (create$) (create$ a))", "(1 0)"),
            ("(subsetp (create$ a c) (create$ a b c))", "TRUE"),
            ("(subsetp (create$ a d) (create$ a b c))", "FALSE"),
            ("(subsetp (create$) (create$ a))", "TRUE"),
            ("(subsetp (create$ a a) (create$ a))", "TRUE"),
            ("(subsetp (create$ 1) (create$ 1.0))", "FALSE"),
        ]);
        assert!(eval_to_string("(member$ a (sym-cat b))").contains("#2 to be of type multifield"));
    }

    #[test]
    fn insert_delete_replace() {
        // tests/clips/054 and probes
        check(&[
            ("(insert$ (create$ a b c) 2 x)", "(a x b c)"),
            ("(insert$ (create$ a b c) 1 x y)", "(x y a b c)"),
            ("(insert$ (create$ a b c) 4 (create$ x y))", "(a b c x y)"),
            ("(insert$ (create$) 1 a)", "(a)"),
            ("(insert$ (create$ a b) 4 x)", "(a b x)"),
            ("(insert$ (create$ a b) 2 (create$ x y) z)", "(a x y z b)"),
            ("(delete$ (create$ a b c d) 2 3)", "(a d)"),
            ("(delete$ (create$ a b c) 1 1)", "(b c)"),
            ("(delete$ (create$ a b c) 1 3)", "()"),
            ("(replace$ (create$ a b c d) 2 3 x)", "(a x d)"),
            ("(replace$ (create$ a b c) 1 1 x y z)", "(x y z b c)"),
            ("(replace$ (create$ a b c) 3 3 (create$))", "(a b)"),
            (
                "(replace$ (create$ a b c) 2 2 (create$ x y) z)",
                "(a x y z c)",
            ),
        ]);
        assert!(eval_to_string("(insert$ (create$ a b) 0 x)").contains("[MULTIFUN1]"));
        assert!(eval_to_string("(delete$ (create$ a b) 3 3)").contains("[MULTIFUN1]"));
        assert!(eval_to_string("(delete$ (create$ a b) 2 1)").contains("[MULTIFUN1]"));
        assert!(eval_to_string("(replace$ (create$ a b) 0 1 x)").contains("[MULTIFUN1]"));
    }

    #[test]
    fn delete_and_replace_members() {
        check(&[
            ("(delete-member$ (create$ a b a c) a)", "(b c)"),
            ("(delete-member$ (create$ a b a c) a c)", "(b)"),
            ("(delete-member$ (create$ a b c d) (create$ b c))", "(a d)"),
            ("(delete-member$ (create$ a b c) z)", "(a b c)"),
            ("(replace-member$ (create$ a b a c) x a)", "(x b x c)"),
            (
                "(replace-member$ (create$ a b a c) (create$ x y) a c)",
                "(x y b x y x y)",
            ),
            (
                "(replace-member$ (create$ a b c d b c) z (create$ b c))",
                "(a z d z)",
            ),
            ("(delete-member$ (create$ a b) (create$))", "(a b)"),
        ]);
        assert!(eval_to_string("(delete-member$ (sym-cat a) b)")
            .contains("#1 to be of type multifield"));
    }

    #[test]
    fn first_rest_subseq() {
        check(&[
            ("(first$ (create$ x y z))", "(x)"),
            ("(first$ (create$))", "()"),
            ("(rest$ (create$ x y z))", "(y z)"),
            ("(rest$ (create$ x))", "()"),
            ("(rest$ (create$))", "()"),
            ("(subseq$ (create$ a b c d e) 2 4)", "(b c d)"),
            ("(subseq$ (create$ a b c) 3 1)", "()"),
            ("(subseq$ (create$ a b c) 2 9)", "(b c)"),
            ("(subseq$ (create$ a b c) 0 2)", "(a b)"),
            ("(subseq$ (create$ a b c) -1 2)", "(a b)"),
            ("(subseq$ (create$ a b c) 2 2)", "(b)"),
        ]);
    }

    #[test]
    fn implode_explode() {
        // tests/clips/055, 085
        check(&[
            ("(implode$ (create$ a b c))", "\"a b c\""),
            (
                "(implode$ (create$ \"str\" 1 2.5 sym))",
                "\"\"str\" 1 2.5 sym\"",
            ),
            ("(implode$ (create$))", "\"\""),
            ("(implode$ (create$ 1.0 \"a b\"))", "\"1.0 \"a b\"\""),
            ("(implode$ (create$ \"a\\\"b\"))", "\"\"a\\\"b\"\""),
            ("(str-length (implode$ (create$ \"a\\\\b\")))", "6"),
            ("(explode$ \"a b c\")", "(a b c)"),
            (
                "(explode$ \"1 2.5 \\\"quoted text\\\" sym\")",
                "(1 2.5 \"quoted text\" sym)",
            ),
            ("(explode$ \"\")", "()"),
            ("(explode$ \"   spaced    out   \")", "(spaced out)"),
            ("(length$ (explode$ \"x y z\"))", "3"),
            ("(nth$ 2 (explode$ \"10 20 30\"))", "20"),
            ("(integerp (nth$ 1 (explode$ \"7 eight\")))", "TRUE"),
            ("(explode$ \"a (b) c\")", "(a \"(\" b \")\" c)"),
            ("(explode$ \"a ?x $?y c\")", "(a \"?x\" \"$?y\" c)"),
            ("(explode$ \"a & b | ~c\")", "(a \"&\" b \"|\" \"~\" c)"),
            ("(explode$ \"1e3 +5 .5\")", "(1000.0 5 0.5)"),
            ("(explode$ \"a;comment b\")", "(a)"),
        ]);
        assert!(eval_to_string("(explode$ abc)").contains("#1 to be of type string"));
        let out = run_program("(printout t (explode$ \"x \\\"open\") crlf)\n");
        // as CLIPS 6.30 prints it: the string inside the multifield in quotes
        assert!(
            out.contains("[SCANNER1]") && out.contains("(x \"open\")"),
            "{out}"
        );
    }
}
