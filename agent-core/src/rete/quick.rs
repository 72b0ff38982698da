//! Direct reads for the common join tests and index keys.
//!
//! Most join tests compare a field of the new pattern with a variable bound by an
//! earlier one: `?x` used again (`Eq2` of two pattern variables) or `~?x` (`Not`
//! of that). For those, reading the two single-field slots straight from the facts
//! is enough: no `lhs_pm` binding of the whole ancestry, no evaluator, no value
//! copies through `Result`. Anything else (multislot fields, fact addresses,
//! function calls, unbound patterns) answers `None` and the caller takes the
//! general path, which gives the same results and reports the same errors, so the
//! quick path never changes behaviour, only cost.

use crate::engine::Core;
use crate::expr::{loc, Expr, Op};
use crate::value::{Ix, Value, NONE};

impl Core<'_> {
    /// The value of pattern variable `x` read from `fact`, when it is a plain
    /// single-field slot (no multislot element, not the fact address).
    #[inline(always)]
    pub(crate) fn plain_slot_value(&self, fact: Ix, x: &Expr) -> Option<Value> {
        if fact == NONE || x.first != NONE || x.data == loc::FACT {
            return None;
        }
        self.plain_slot(fact, Ix::from(loc::slot(x.data)))
    }

    /// Slot `slot` of `fact` when it holds a single field (not a multislot).
    #[inline(always)]
    pub(crate) fn plain_slot(&self, fact: Ix, slot: Ix) -> Option<Value> {
        let f = &self.facts[fact as usize];
        let v = if f.len == self.templates[f.tmpl as usize].nslots {
            // one cell per slot (no multislot holds elements): index directly
            self.values[(f.start + slot) as usize]
        } else {
            self.values[self.slot_cell(fact, slot).0]
        };
        match v {
            Value::Multi(_) => None,
            v => Some(v),
        }
    }

    /// A pattern variable of a join test of the join at `depth`: the right input's
    /// fact (`right_fact`) for `depth`, else the bound left token's (`lhs_pm`).
    fn join_var(&self, x: &Expr, depth: u8, right_fact: Ix) -> Option<Value> {
        if x.op != Op::PatVar {
            return None;
        }
        let fact = if x.aux == depth {
            right_fact
        } else if x.aux < depth {
            self.st.lhs_pm[x.aux as usize].fact
        } else {
            return None;
        };
        self.plain_slot_value(fact, x)
    }

    /// The join tests `tests` of the join at `depth` for the left token bound in
    /// `lhs_pm` and right fact `right_fact`, if every test is `?a = ?b` or `~` of
    /// it over plain single-field slots; None when the evaluator must decide.
    pub(crate) fn quick_join_test(&self, tests: Ix, depth: u8, right_fact: Ix) -> Option<bool> {
        let mut t = tests;
        while t != NONE {
            let x = self.exprs[t as usize];
            let (eq, negated) = match x.op {
                Op::Eq2 => (x, false),
                Op::Not if x.first != NONE => (self.exprs[x.first as usize], true),
                _ => return None,
            };
            if eq.op != Op::Eq2 || eq.first == NONE {
                return None;
            }
            let a = self.exprs[eq.first as usize];
            if a.next == NONE {
                return None;
            }
            let b = self.exprs[a.next as usize];
            let va = self.join_var(&a, depth, right_fact)?;
            let vb = self.join_var(&b, depth, right_fact)?;
            // single-field values: `values_same` is `same`
            if va.same(vb) == negated {
                return Some(false);
            }
            t = x.next;
        }
        Some(true)
    }
}
