//! Truth maintenance commands (agent-core feature `logical`, see `crate::logical`):
//! `dependencies` and `dependents`, as CLIPS 6.30 prints them.
// without the feature the table is empty and the functions unused (and not linked)
#![cfg_attr(not(feature = "logical"), allow(dead_code, unused_imports))]

use super::{Args, Builtin};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::{Ix, TextBuf, Value};
use core::fmt::Write;

#[cfg(feature = "logical")]
#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("dependencies", 1, 1, dependencies).returns(super::describe::Returns::Void),
    Builtin::eager("dependents", 1, 1, dependents).returns(super::describe::Returns::Void),
];
#[cfg(not(feature = "logical"))]
pub const FUNCS: &[Builtin] = &[];
pub const TABLE: super::Table = super::Table::new(FUNCS).texts(&[T_SUPPORTED]);

/// CLIPS's wording for what `dependencies` and `dependents` take.
const T_SUPPORTED: &str = "instance address, instance name, fact address, integer, or symbol";

/// The fact a command names (an address or an index), or its message printed.
fn fact_named(cx: &mut Core<'_>, func: &'static str, v: Value) -> Result<Option<Ix>, EvalError> {
    let mut b: TextBuf<128> = TextBuf::new();
    match v {
        Value::Fact(r) if cx.fact_alive(r) => return Ok(Some(r.slot)),
        Value::Fact(r) => {
            let _ = writeln!(b, "[PRNTUTIL1] Unable to find fact f-{}.", r.num);
        }
        Value::Int(n) => match cx.fact_arg(v) {
            Some(f) => return Ok(Some(f)),
            None => {
                let _ = writeln!(b, "[PRNTUTIL1] Unable to find fact f-{n}.");
            }
        },
        // CLIPS takes a symbol for an instance name
        Value::Sym(s) => {
            let _ = writeln!(b, "[PRNTUTIL1] Unable to find instance {}.", cx.sym_text(s));
        }
        _ => return Err(EvalError::wrong_type(func, 1, T_SUPPORTED)),
    }
    cx.write(router::WERROR, b.as_str());
    Ok(None)
}

/// `(dependencies fact)`: the partial matches giving the fact logical support.
#[cfg(feature = "logical")]
fn dependencies(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if let Some(f) = fact_named(cx, "dependencies", cx.arg(a, 0))? {
        cx.print_dependencies(f);
    }
    Ok(Value::Void)
}

/// `(dependents fact)`: the facts the fact gives logical support.
#[cfg(feature = "logical")]
fn dependents(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if let Some(f) = fact_named(cx, "dependents", cx.arg(a, 0))? {
        cx.print_dependents(f);
    }
    Ok(Value::Void)
}
