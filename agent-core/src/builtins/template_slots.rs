//! The `deftemplate-slot-*` functions (agent-core feature `extras`; the agent image
//! calls none of them): what a template says about its slots, as CLIPS 6.30 answers.
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "extras"), allow(dead_code, unused_imports))]

use super::describe::ArgType::{Any, Symbol as Y};
use super::{Args, Builtin, SYM_FALSE};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::host::router;
use crate::template::{types, DefaultKind, SlotDef};
use crate::value::{Ix, SymId, TextBuf, Value, NONE};
use core::fmt::Write;

#[cfg(feature = "extras")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("deftemplate-slot-names", 1, 1, slot_names)
        .args(&[super::describe::ArgType::FactOrIndex], super::describe::ArgType::Any),
    Builtin::eager("deftemplate-slot-existp", 2, 2, slot_existp).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-multip", 2, 2, slot_multip).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-singlep", 2, 2, slot_singlep).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-defaultp", 2, 2, slot_defaultp).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-default-value", 2, 2, slot_default_value).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-types", 2, 2, slot_types).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-allowed-values", 2, 2, slot_allowed_values).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-range", 2, 2, slot_range).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-cardinality", 2, 2, slot_cardinality).args(&[Y, Y], Any),
    Builtin::eager("deftemplate-slot-facet-existp", 3, 3, slot_facet_existp).args(&[Y, Y, Y], Any),
    Builtin::eager("deftemplate-slot-facet-value", 3, 3, slot_facet_value).args(&[Y, Y, Y], Any),
    Builtin::eager("rules", 0, 1, super::commands::list_defrules).returns(super::describe::Returns::Void),
];
#[cfg(not(feature = "extras"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// CLIPS's type names in the order `deftemplate-slot-types` lists them.
const TYPE_NAMES: [(u8, &str); 7] = [
    (types::FLOAT, "FLOAT"),
    (types::INTEGER, "INTEGER"),
    (types::SYMBOL, "SYMBOL"),
    (types::STRING, "STRING"),
    (types::FACT_ADDRESS, "FACT-ADDRESS"),
    (types::INSTANCE_ADDRESS, "INSTANCE-ADDRESS"),
    (types::INSTANCE_NAME, "INSTANCE-NAME"),
];
/// Every type a slot without `(type ...)` takes, as CLIPS lists it.
const ALL_TYPES: [&str; 8] = [
    "FLOAT",
    "INTEGER",
    "SYMBOL",
    "STRING",
    "EXTERNAL-ADDRESS",
    "FACT-ADDRESS",
    "INSTANCE-ADDRESS",
    "INSTANCE-NAME",
];

fn empty_multi(cx: &mut Core<'_>) -> Value {
    let start = cx.multi_begin();
    cx.multi_finish(start)
}

/// An error CLIPS reports with `text` and follows with `fallback` (FALSE, or `()`).
fn reported(cx: &mut Core<'_>, text: &str, fallback: Value) -> EvalError {
    cx.write(router::WERROR, text);
    cx.set_error_fallback(fallback, None);
    EvalError::new(EvalErrorKind::Reported)
}

/// The named template (argument 1), as `func` looks it up: a symbol naming a defined
/// template. An argument of another type is `[ARGACCES5]` and an evaluation error; a
/// template not found is `[PRNTUTIL1]` but no error (`Ok(None)`: the function returns
/// its fallback, FALSE or `()`, and the caller's evaluation goes on, as in CLIPS 6.30).
fn template_arg(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    fallback: Value,
) -> Result<Option<Ix>, EvalError> {
    let name = match cx.arg(a, 0) {
        Value::Sym(s) => s,
        _ => {
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(
                b,
                "[ARGACCES5] Function {func} expected argument #1 to be of type deftemplate name"
            );
            return Err(reported(cx, b.as_str(), fallback));
        }
    };
    match super::environment::find_construct(cx, super::extras::Kind::Deftemplate, name) {
        Some(t) => Ok(Some(t)),
        None => {
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(
                b,
                "[PRNTUTIL1] Unable to find deftemplate {}.",
                cx.sym_text(name)
            );
            cx.write(router::WERROR, b.as_str());
            Ok(None)
        }
    }
}

/// Slot `name` of template `t`; `(initial-fact)` has none, as in CLIPS.
fn find_slot(cx: &Core<'_>, t: Ix, name: Value) -> Option<Ix> {
    match name {
        Value::Sym(s) if t != cx.st.facts.initial_tmpl => cx.find_slot(t, s),
        _ => None,
    }
}

/// The slot name (argument 2), a symbol.
fn slot_name_arg(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    fallback: Value,
) -> Result<Value, EvalError> {
    let name = cx.arg(a, 1);
    if !matches!(name, Value::Sym(_)) {
        let mut b: TextBuf<160> = TextBuf::new();
        let _ = writeln!(
            b,
            "[ARGACCES5] Function {func} expected argument #2 to be of type symbol"
        );
        return Err(reported(cx, b.as_str(), fallback));
    }
    Ok(name)
}

/// Template and slot (arguments 1 and 2); a missing slot is `[TMPLTDEF1]` followed by
/// `fallback`, an evaluation error; a template not found is `Ok(None)` (`template_arg`).
fn slot_arg(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    fallback: Value,
) -> Result<Option<(Ix, Ix)>, EvalError> {
    let Some(t) = template_arg(cx, a, func, fallback)? else {
        return Ok(None);
    };
    let name = slot_name_arg(cx, a, func, fallback)?;
    match find_slot(cx, t, name) {
        Some(s) => Ok(Some((t, s))),
        None => {
            let mut b: TextBuf<200> = TextBuf::new();
            let _ = write!(b, "[TMPLTDEF1] Invalid slot ");
            let _ = cx.write_plain(&mut b, name);
            let tname: SymId = cx.templates[t as usize].name;
            let _ = writeln!(
                b,
                " not defined in corresponding deftemplate {}.",
                cx.sym_text(tname)
            );
            Err(reported(cx, b.as_str(), fallback))
        }
    }
}

fn slot_names(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(t) = template_arg(cx, a, "deftemplate-slot-names", Value::Sym(SYM_FALSE))? else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    let start = cx.multi_begin();
    if t != cx.st.facts.initial_tmpl {
        let tm = cx.templates[t as usize];
        for s in 0..tm.nslots {
            let name = cx.slots[(tm.first_slot + s) as usize].name;
            cx.multi_push(Value::Sym(name))?;
        }
    }
    Ok(cx.multi_finish(start))
}

/// FALSE for a missing slot, without a message.
fn slot_existp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let false_ = Value::Sym(SYM_FALSE);
    let Some(t) = template_arg(cx, a, "deftemplate-slot-existp", false_)? else {
        return Ok(false_);
    };
    let name = slot_name_arg(cx, a, "deftemplate-slot-existp", false_)?;
    Ok(Core::bool_value(find_slot(cx, t, name).is_some()))
}

/// The slot's definition; `Ok(None)` for a template not found (the function then
/// returns its fallback).
fn def_of(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    fallback: Value,
) -> Result<Option<SlotDef>, EvalError> {
    Ok(slot_arg(cx, a, func, fallback)?.map(|(t, s)| cx.slot_def(t, s)))
}

fn slot_multip(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(def) = def_of(cx, a, "deftemplate-slot-multip", Value::Sym(SYM_FALSE))? else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    Ok(Core::bool_value(def.multi))
}

fn slot_singlep(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(def) = def_of(cx, a, "deftemplate-slot-singlep", Value::Sym(SYM_FALSE))? else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    Ok(Core::bool_value(!def.multi))
}

/// `static` (a `default`, or none given), `dynamic`, or FALSE for `?NONE`.
fn slot_defaultp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some(def) = def_of(cx, a, "deftemplate-slot-defaultp", Value::Sym(SYM_FALSE))? else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    Ok(match def.default_kind {
        DefaultKind::Required => Value::Sym(SYM_FALSE),
        DefaultKind::Dynamic => Value::Sym(cx.intern("dynamic")?),
        DefaultKind::Static | DefaultKind::Derived => Value::Sym(cx.intern("static")?),
    })
}

/// The value an assert would give the slot (a dynamic default is evaluated now);
/// `?NONE` for a slot that must be given.
fn slot_default_value(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Some((t, s)) = slot_arg(
        cx,
        a,
        "deftemplate-slot-default-value",
        Value::Sym(SYM_FALSE),
    )?
    else {
        return Ok(Value::Sym(SYM_FALSE));
    };
    if cx.slot_def(t, s).default_kind == DefaultKind::Required {
        return Ok(Value::Sym(cx.intern("?NONE")?));
    }
    let v = cx.default_value(t, s)?;
    if let Value::Multi(m) = v {
        // a derived empty multifield points at the scratch top: make it a real one
        if m.len == 0 {
            return Ok(empty_multi(cx));
        }
    }
    Ok(v)
}

fn slot_types(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fallback = empty_multi(cx);
    let Some(def) = def_of(cx, a, "deftemplate-slot-types", fallback)? else {
        return Ok(fallback);
    };
    let start = cx.multi_begin();
    if def.types == 0 {
        for name in ALL_TYPES {
            let s = cx.intern(name)?;
            cx.multi_push(Value::Sym(s))?;
        }
    } else {
        for (bit, name) in TYPE_NAMES {
            if def.types & bit != 0 {
                let s = cx.intern(name)?;
                cx.multi_push(Value::Sym(s))?;
            }
        }
    }
    Ok(cx.multi_finish(start))
}

/// The `allowed-...` values, or FALSE when the slot has none.
fn slot_allowed_values(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fallback = empty_multi(cx);
    let Some(def) = def_of(cx, a, "deftemplate-slot-allowed-values", fallback)? else {
        return Ok(fallback);
    };
    if def.allowed == NONE {
        return Ok(Value::Sym(SYM_FALSE));
    }
    let start = cx.multi_begin();
    let mut e = def.allowed;
    while e != NONE {
        let v = cx.const_value(e);
        cx.multi_push(v)?;
        e = cx.exprs[e as usize].next;
    }
    Ok(cx.multi_finish(start))
}

/// A `(MIN MAX)` multifield of the two bounds chained at `bounds`, or of
/// `default_min` and `+oo` when the slot has none.
fn bounds_value(cx: &mut Core<'_>, bounds: Ix, default_min: &str) -> Result<Value, EvalError> {
    let (min, max) = if bounds == NONE {
        let min = match default_min {
            "0" => Value::Int(0),
            _ => Value::Sym(cx.intern(default_min)?),
        };
        (min, Value::Sym(cx.intern("+oo")?))
    } else {
        let max = cx.exprs[bounds as usize].next;
        (cx.const_value(bounds), cx.const_value(max))
    };
    let start = cx.multi_begin();
    cx.multi_push(min)?;
    cx.multi_push(max)?;
    Ok(cx.multi_finish(start))
}

/// FALSE for a slot that takes no number, else its range (`-oo`/`+oo` for an
/// unbounded end).
fn slot_range(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fallback = empty_multi(cx);
    let Some(def) = def_of(cx, a, "deftemplate-slot-range", fallback)? else {
        return Ok(fallback);
    };
    if def.types != 0 && def.types & types::NUMBER == 0 {
        return Ok(Value::Sym(SYM_FALSE));
    }
    bounds_value(cx, def.range, "-oo")
}

/// `()` for a single-field slot, else its cardinality (`+oo` for no maximum).
fn slot_cardinality(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fallback = empty_multi(cx);
    let Some(def) = def_of(cx, a, "deftemplate-slot-cardinality", fallback)? else {
        return Ok(fallback);
    };
    if !def.multi {
        return Ok(empty_multi(cx));
    }
    bounds_value(cx, def.cardinality, "0")
}

/// The facet node (`template::facet`) that arguments 1-3 name, as CLIPS 6.30 looks it
/// up for both facet functions: an argument of another type is `[ARGACCES5]` (under
/// `deftemplate-slot-facet-existp`'s name for both, as CLIPS words it) and an evaluation
/// error; a template not found is `[PRNTUTIL1]` but no error; an ordered-fact template,
/// a slot or facet it does not have are none found, without a message.
fn facet_of(cx: &mut Core<'_>, a: Args) -> Result<Ix, EvalError> {
    const FUNC: &str = "deftemplate-slot-facet-existp";
    let false_ = Value::Sym(SYM_FALSE);
    let name = match cx.arg(a, 0) {
        Value::Sym(s) => s,
        _ => {
            return Err(reported(
                cx,
                "[ARGACCES5] Function deftemplate-slot-facet-existp expected argument #1 to be of type deftemplate name\n",
                false_,
            ))
        }
    };
    let Some(t) = super::environment::find_construct(cx, super::extras::Kind::Deftemplate, name)
    else {
        let mut b: TextBuf<160> = TextBuf::new();
        let _ = writeln!(
            b,
            "[PRNTUTIL1] Unable to find deftemplate {}.",
            cx.sym_text(name)
        );
        cx.write(router::WERROR, b.as_str());
        return Ok(NONE);
    };
    for k in 1..3 {
        if !matches!(cx.arg(a, k), Value::Sym(_)) {
            let mut b: TextBuf<160> = TextBuf::new();
            let _ = writeln!(
                b,
                "[ARGACCES5] Function {FUNC} expected argument #{} to be of type symbol",
                k + 1
            );
            return Err(reported(cx, b.as_str(), false_));
        }
    }
    let (Value::Sym(slot), Value::Sym(facet)) = (cx.arg(a, 1), cx.arg(a, 2)) else {
        return Ok(NONE);
    };
    if cx.templates[t as usize].implied {
        return Ok(NONE);
    }
    let Some(s) = cx.find_slot(t, slot) else {
        return Ok(NONE);
    };
    let mut f = cx.slot_facets(cx.templates[t as usize].first_slot + s);
    while f != NONE && cx.exprs[f as usize].data != facet {
        f = cx.exprs[f as usize].next;
    }
    Ok(f)
}

/// Whether the slot has the facet (`facet` or `multifacet`); FALSE after an error.
fn slot_facet_existp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    Ok(Core::bool_value(facet_of(cx, a)? != NONE))
}

/// A facet's value, a multifacet's multifield of values; FALSE for none.
fn slot_facet_value(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let f = facet_of(cx, a)?;
    if f == NONE {
        return Ok(Value::Sym(SYM_FALSE));
    }
    let x = cx.exprs[f as usize];
    if x.aux != crate::template::facet::MULTI {
        return Ok(cx.const_value(x.first));
    }
    let start = cx.multi_begin();
    let mut e = x.first;
    while e != NONE {
        let v = cx.const_value(e);
        cx.multi_push(v)?;
        e = cx.exprs[e as usize].next;
    }
    Ok(cx.multi_finish(start))
}

#[cfg(all(test, feature = "extras"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;

    #[test]
    fn range_and_cardinality_are_the_slots_own() {
        let out = run_program(
            "(deftemplate t (slot a (type INTEGER) (range 2 ?VARIABLE)) (slot b (type SYMBOL)) \
             (multislot c (cardinality 1 3)) (multislot d) (slot e))\n\
             (printout t (deftemplate-slot-range t b) crlf)\n\
             (printout t (deftemplate-slot-cardinality t a) crlf)\n\
             (printout t (deftemplate-slot-range t a) crlf)\n\
             (printout t (deftemplate-slot-range t e) crlf)\n\
             (printout t (deftemplate-slot-cardinality t c) crlf)\n\
             (printout t (deftemplate-slot-cardinality t d) crlf)\n",
        );
        assert_eq!(
            out, "FALSE\n()\n(2 +oo)\n(-oo +oo)\n(1 3)\n(0 +oo)\n",
            "{out}"
        );
    }

    #[test]
    fn facets_are_the_slots_own_and_a_failed_template_leaves_none() {
        let out = run_program(
            "(deftemplate t (slot a (facet f 1)) (multislot b (multifacet f x \"y\") (facet g 2.5)))\n\
             (deftemplate u (slot a (facet h 9)) (slot a))\n\
             (deftemplate x (slot a (facet f 3) (facet f 4)))\n\
             (printout t (deftemplate-slot-facet-value t a f) crlf)\n\
             (printout t (deftemplate-slot-facet-value t b f) crlf)\n\
             (printout t (deftemplate-slot-facet-value t b g) crlf)\n\
             (printout t (deftemplate-slot-facet-existp t a g) crlf)\n\
             (printout t (deftemplate-slot-facet-value t b h) crlf)\n\
             (deftemplate v (slot a) (slot b (facet k 5)))\n\
             (printout t (deftemplate-slot-facet-existp v a h) crlf)\n\
             (printout t (deftemplate-slot-facet-value v b k) crlf)\n",
        );
        assert!(
            out.contains("[PRNTUTIL5] The facet f has already been parsed."),
            "{out}"
        );
        assert!(
            out.ends_with("1\n(x \"y\")\n2.5\nFALSE\nFALSE\nFALSE\n5\n"),
            "{out}"
        );
    }

    #[test]
    fn join_activity_constructs_to_c_bload_and_bsave_are_refused_as_not_implemented() {
        for call in [
            "(join-activity r)\n(printout t ok crlf)\n",
            "(join-activity-reset)\n(printout t ok crlf)\n",
            "(constructs-to-c f 1)\n(printout t ok crlf)\n",
            "(bload \"x.bin\")\n(printout t ok crlf)\n",
            "(bsave \"x.bin\")\n(printout t ok crlf)\n",
        ] {
            let out = run_program(call);
            assert!(
                out.contains("[NOTIMPL1] robotino-agent does not implement")
                    && !out.contains("EXPRNPSR3")
                    && out.ends_with("ok\n"),
                "{call}: {out}"
            );
        }
    }

    #[test]
    fn object_and_generic_function_constructs_are_refused_as_not_implemented() {
        // each refused by its own name, the program going on after it
        for (construct, what) in [
            ("(defclass A (is-a USER))", "objects (COOL): defclass"),
            ("(definstances i (a of A))", "objects (COOL): definstances"),
            (
                "(defmessage-handler A m () 1)",
                "objects (COOL): defmessage-handler",
            ),
            ("(defgeneric g)", "generic functions: defgeneric"),
            (
                "(defmethod g ((?x NUMBER)) (* ?x 2))",
                "generic functions: defmethod",
            ),
        ] {
            let out = run_program(&std::format!("{construct}\n(printout t ok crlf)\n"));
            assert!(
                out.contains(&std::format!(
                    "[NOTIMPL1] robotino-agent does not implement {what}"
                )) && !out.contains("EXPRNPSR3")
                    && out.ends_with("ok\n"),
                "{construct}: {out}"
            );
        }
    }
}
