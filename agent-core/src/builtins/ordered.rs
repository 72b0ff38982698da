//! Twins of the numeric builtins whose arguments CLIPS 6.30 takes one at a time.
//!
//! CLIPS's `+ - * / div mod **` and `= <> < <= > >=` evaluate each argument and check it
//! before the next (`GetNumericArgument`): the first that is no number (or a zero divisor
//! of `/` or `div`) is the last evaluated. `(= ?p (+ ?x ?y))` with `?p` a symbol prints
//! `=`'s error only, and `(+ ?s (bind ?*g* 1))` binds nothing. Our eager calls evaluate
//! every argument first, which is the same unless a later argument could print or change
//! something: the parser (`Parser::order_numeric_args`) gives such a call the id of its
//! twin here, whose row is the original's but lazy (`Core::call_ordered` takes the
//! arguments in CLIPS's order, then runs the original's body). Other calls keep the
//! eager path; one whose later argument fails without having printed (a quiet builtin of
//! leaves) is told apart when it fails (`Core::builtin_after_failed_arg`).
//!
//! A twin has its original's name, so messages, `get-function-restrictions` and
//! `builtin_id` (the first row of a name: the original) are unchanged; the table is the
//! last, and listings of the functions leave the twins out. A compiled rule base names a
//! twin by its original (`twin_of`) and brings both codes.

use super::{Builtin, Imp};
use crate::engine::Core;
use crate::error::EvalError;
use crate::value::{Ix, Value};

/// The originals, in the twins' order.
const NAMES: [&str; 13] = [
    "+", "-", "*", "/", "=", "<>", "<", "<=", ">", ">=", "div", "mod", "**",
];

/// Row `name` of table `funcs`, lazy with the twins' body.
const fn twin(funcs: &[Builtin], name: &str) -> Builtin {
    let mut i = 0;
    while i < funcs.len() {
        if crate::symbols::same_text(funcs[i].name, name) {
            let mut b = funcs[i];
            b.imp = Imp::Lazy(in_order);
            return b;
        }
        i += 1;
    }
    panic!("no such builtin")
}

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    twin(super::basic::FUNCS, "+"),
    twin(super::basic::FUNCS, "-"),
    twin(super::basic::FUNCS, "*"),
    twin(super::basic::FUNCS, "/"),
    twin(super::basic::FUNCS, "="),
    twin(super::basic::FUNCS, "<>"),
    twin(super::basic::FUNCS, "<"),
    twin(super::basic::FUNCS, "<="),
    twin(super::basic::FUNCS, ">"),
    twin(super::basic::FUNCS, ">="),
    twin(super::math::FUNCS, "div"),
    twin(super::math::FUNCS, "mod"),
    twin(super::math::FUNCS, "**"),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// The first twin's id (the table is the last one).
pub const FIRST: Ix = (super::COUNT - NAMES.len()) as Ix;

/// The originals' ids, in the twins' order.
const ORIGINALS: [Ix; NAMES.len()] = {
    let mut ids = [0; NAMES.len()];
    let mut i = 0;
    while i < NAMES.len() {
        ids[i] = super::builtin_id(NAMES[i]);
        i += 1;
    }
    ids
};

/// The twin of builtin `id`, if it has one.
pub const fn twin_of(id: Ix) -> Option<Ix> {
    let mut i = 0;
    while i < ORIGINALS.len() {
        if ORIGINALS[i] == id {
            return Some(FIRST + i as Ix);
        }
        i += 1;
    }
    None
}

/// The twin of builtin `id` (compiled rule bases name twins so; one without a twin
/// does not compile).
pub const fn ordered_twin(id: Ix) -> Ix {
    match twin_of(id) {
        Some(t) => t,
        None => panic!("no twin"),
    }
}

/// Whether builtin `id` has a twin, in a compare or two (`+` .. `>=` are the first
/// ten ids, `basic`'s).
#[inline(always)]
pub const fn has_twin(id: Ix) -> bool {
    id < 10 || id == ORIGINALS[10] || id == ORIGINALS[11] || id == ORIGINALS[12]
}
const _: () = {
    let mut i = 0;
    while i < 10 {
        assert!(ORIGINALS[i] == i as Ix);
        i += 1;
    }
};

/// The original of twin `id` (another id stays).
pub const fn original_of(id: Ix) -> Ix {
    if id >= FIRST && ((id - FIRST) as usize) < ORIGINALS.len() {
        ORIGINALS[(id - FIRST) as usize]
    } else {
        id
    }
}

/// Whether builtin `id` is a twin.
pub const fn is_twin(id: Ix) -> bool {
    original_of(id) != id
}

fn in_order(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    cx.call_ordered(call)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twins_mirror_their_originals() {
        for (k, name) in NAMES.iter().enumerate() {
            let id = super::super::builtin_id(name);
            let t = twin_of(id).expect("a twin");
            assert_eq!(t, FIRST + k as Ix);
            assert_eq!(original_of(t), id);
            assert!(is_twin(t) && !is_twin(id));
            let (b, c) = (super::super::get(id), super::super::get(t));
            assert_eq!(b.name, c.name);
            assert_eq!(
                (b.min, b.max, b.returns, b.purity),
                (c.min, c.max, c.returns, c.purity)
            );
            assert!(b.signature.numbers_after_lead() && has_twin(id) && !has_twin(t));
        }
        assert_eq!(twin_of(super::super::builtin_id("eq")), None);
        assert_eq!(super::super::COUNT, FIRST as usize + NAMES.len());
    }
}
