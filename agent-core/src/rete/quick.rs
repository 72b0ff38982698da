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
use crate::handle::{JoinId, TokenId};
use crate::value::{Ix, Value, NONE};

/// Entries of the join-test plan cache (`State::test_plans`, direct-mapped by join):
/// on the host enough for programs of a few dozen joins (a miss rebuilds the plan).
#[cfg(not(feature = "host-speedups"))]
pub const TEST_PLANS: usize = 8;
#[cfg(feature = "host-speedups")]
pub const TEST_PLANS: usize = 32;
/// Most tests a plan holds; joins with more use `quick_join_test` as it is.
pub const PLAN_TESTS: usize = 4;

/// One planned join test: `?a = ?b` (or `~`, `negated`) between pattern-index /
/// slot pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TestOp {
    pub negated: bool,
    pub a: (u8, u8),
    pub b: (u8, u8),
}

/// A join's tests worked out once into slot comparisons (`n` of `ops`), or
/// `n == TestPlan::NONE.n` when they are not all of that shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TestPlan {
    pub join: JoinId,
    /// The join's test chain (a reused join id has another one).
    pub tests: Ix,
    pub n: u8,
    pub ops: [TestOp; PLAN_TESTS],
}

/// Host: the one op of the `TestPlan` of a join whose compiled plan is a marked
/// one (`marked_test_plan`): it reads pattern `u8::MAX`, which no token binds
/// (`left_fact` answers NONE beyond `Token::binds`), so `planned_join_test` answers
/// None at once and the join's pairs go straight to `join_test_eval`, where
/// `marked_join_test` runs the plan. Decided once per cached test plan: the path of
/// every other join stays as it was, and no pair first walks the plain slots of
/// its tests only to give up at a field after a multifield.
#[cfg(feature = "host-speedups")]
const TO_EVALUATOR: TestOp = TestOp {
    negated: false,
    a: (u8::MAX, 0),
    b: (u8::MAX, 0),
};

/// Host: the `TestPlan` of `join` (chain `tests`) whose compiled plan is a marked
/// one: `TO_EVALUATOR` alone. (Set by `marked_join_test`, off the join loops:
/// their code stays as it was.)
#[cfg(feature = "host-speedups")]
pub(crate) fn marked_test_plan(join: JoinId, tests: Ix) -> TestPlan {
    TestPlan {
        join,
        tests,
        n: 1,
        ops: [TO_EVALUATOR; PLAN_TESTS],
    }
}

impl TestPlan {
    pub const NONE: TestPlan = TestPlan {
        join: JoinId::NONE,
        tests: NONE,
        n: u8::MAX,
        ops: [TestOp {
            negated: false,
            a: (0, 0),
            b: (0, 0),
        }; PLAN_TESTS],
    };
}

/// `Value::same` of two cells, symbols and integers (what join keys mostly hold)
/// compared inline, where they lie (copies of the two values cost more than the
/// test); None if either is a multifield.
#[inline(always)]
pub(super) fn same_cell(a: &Value, b: &Value) -> Option<bool> {
    Some(match (a, b) {
        (Value::Sym(x), Value::Sym(y)) => x == y,
        (Value::Int(x), Value::Int(y)) => x == y,
        (Value::Multi(_), _) | (_, Value::Multi(_)) => return None,
        _ => a.same(*b),
    })
}

impl Core<'_> {
    /// Makes the facts of `left`'s ancestry readable by `left_fact`: with
    /// `Token::binds` (host) they already are, else `lhs_pm` is filled.
    #[inline(always)]
    pub(crate) fn bind_for_quick(&mut self, left: TokenId) {
        #[cfg(not(feature = "host-speedups"))]
        self.bind_left(left);
        #[cfg(feature = "host-speedups")]
        let _ = left;
    }

    /// The fact bound at pattern `pat` of left token `left` (NONE if none or not
    /// kept), after `bind_for_quick(left)`.
    #[inline(always)]
    pub(crate) fn left_fact(&self, left: TokenId, pat: u8) -> Ix {
        #[cfg(feature = "host-speedups")]
        {
            match self.tokens[left].binds.get(pat as usize) {
                Some(&f) => f,
                None => NONE,
            }
        }
        #[cfg(not(feature = "host-speedups"))]
        {
            let _ = left;
            self.st.net.lhs_pm[pat as usize].fact
        }
    }

    /// `quick_join_test` for the tests of `join` through its cached plan.
    /// `tests` and `depth` are the join's (read by the caller with its other fields);
    /// `planned`: the plan is known cached (see `join_test_with`), set once it is;
    /// `skip`: a test known to hold, or NONE (see `join_test_skip`).
    #[allow(clippy::too_many_arguments)]
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn planned_join_test(
        &mut self,
        join: JoinId,
        tests: Ix,
        depth: u8,
        left: TokenId,
        right_fact: Ix,
        planned: &mut bool,
        skip: Ix,
    ) -> Option<bool> {
        let i = join.ix() % TEST_PLANS;
        if !*planned {
            let cached = &self.st.cache.test_plans[i];
            if cached.join != join || cached.tests != tests {
                self.st.cache.test_plans[i] = self.test_plan(join, tests, depth);
            }
            *planned = true;
        }
        // read in place (a copy of the whole plan costs more than the few ops used)
        let plan = &self.st.cache.test_plans[i];
        if plan.n == TestPlan::NONE.n {
            // the host compiles other tests into a plan of its own (`rete::plan`)
            #[cfg(feature = "host-speedups")]
            return if skip == NONE {
                self.compiled_join_test(join, tests, depth, left, right_fact)
            } else {
                self.compiled_join_test_or(join, (tests, depth), left, right_fact, skip)
            };
            #[cfg(not(feature = "host-speedups"))]
            {
                let _ = skip;
                return self.quick_join_test(tests, depth, left, right_fact);
            }
        }
        for op in &plan.ops[..plan.n as usize] {
            let va = self.planned_var(op.a, depth, left, right_fact)?;
            let vb = self.planned_var(op.b, depth, left, right_fact)?;
            if same_cell(va, vb)? == op.negated {
                return Some(false);
            }
        }
        Some(true)
    }

    /// Forgets every cached test plan (the network was replaced).
    pub(crate) fn clear_test_plans(&mut self) {
        self.st.cache.test_plans = [TestPlan::NONE; TEST_PLANS];
        #[cfg(feature = "host-speedups")]
        self.st.cache.compiled_plans.clear();
    }

    /// Forgets the cached test plans of new join `join` (its id may be reused).
    pub(crate) fn forget_test_plan(&mut self, join: JoinId) {
        let i = join.ix() % TEST_PLANS;
        if self.st.cache.test_plans[i].join == join {
            self.st.cache.test_plans[i] = TestPlan::NONE;
        }
        #[cfg(feature = "host-speedups")]
        self.st.cache.compiled_plans.forget(join);
    }

    /// The cell of a planned variable (a multifield is the caller's to refuse).
    #[inline(always)]
    fn planned_var(
        &self,
        (pat, slot): (u8, u8),
        depth: u8,
        left: TokenId,
        right_fact: Ix,
    ) -> Option<&Value> {
        let fact = if pat == depth {
            right_fact
        } else {
            self.left_fact(left, pat)
        };
        if fact == NONE {
            return None;
        }
        Some(self.slot_ref(fact, Ix::from(slot)))
    }

    /// The cell of slot `slot` of `fact` (a multislot's is its `Multi`).
    #[inline(always)]
    pub(crate) fn slot_ref(&self, fact: Ix, slot: Ix) -> &Value {
        let f = &self.facts[fact as usize];
        if f.flat {
            // one cell per slot (no multislot holds elements): index directly
            &self.values[(f.start + slot) as usize]
        } else {
            &self.values[self.slot_cell(fact, slot).0]
        }
    }

    /// The plan of a join's tests (see `TestPlan`).
    fn test_plan(&self, join: JoinId, tests: Ix, depth: u8) -> TestPlan {
        let mut plan = TestPlan {
            join,
            tests,
            n: 0,
            ..TestPlan::NONE
        };
        let unplanned = TestPlan {
            join,
            tests,
            ..TestPlan::NONE
        };
        // a pattern beyond `Token::binds` is left to the host's compiled plan
        #[cfg(feature = "host-speedups")]
        let readable = |pat: u8| pat == depth || (pat as usize) < super::BIND_W;
        #[cfg(not(feature = "host-speedups"))]
        let readable = |_: u8| true;
        let var = |x: &Expr| -> Option<(u8, u8)> {
            (x.op == Op::PatVar
                && x.first == NONE
                && x.data != loc::FACT
                && x.aux <= depth
                && readable(x.aux))
            .then(|| (x.aux, loc::slot(x.data)))
        };
        let mut t = tests;
        while t != NONE {
            let x = self.exprs[t as usize];
            let (eq, negated) = match x.op {
                Op::Eq2 => (x, false),
                Op::Not if x.first != NONE => (self.exprs[x.first as usize], true),
                _ => return unplanned,
            };
            if eq.op != Op::Eq2 || eq.first == NONE || plan.n as usize >= PLAN_TESTS {
                return unplanned;
            }
            let a = self.exprs[eq.first as usize];
            if a.next == NONE {
                return unplanned;
            }
            let b = self.exprs[a.next as usize];
            let (Some(a), Some(b)) = (var(&a), var(&b)) else {
                return unplanned;
            };
            plan.ops[plan.n as usize] = TestOp { negated, a, b };
            plan.n += 1;
            t = x.next;
        }
        plan
    }

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
        match self.slot_ref(fact, slot) {
            Value::Multi(_) => None,
            v => Some(*v),
        }
    }

    /// A pattern variable of a join test of the join at `depth`: the right input's
    /// fact (`right_fact`) for `depth`, else left token `left`'s (`left_fact`).
    fn join_var(&self, x: &Expr, depth: u8, left: TokenId, right_fact: Ix) -> Option<&Value> {
        if x.op != Op::PatVar || x.first != NONE || x.data == loc::FACT {
            return None;
        }
        let fact = if x.aux == depth {
            right_fact
        } else if x.aux < depth {
            self.left_fact(left, x.aux)
        } else {
            return None;
        };
        if fact == NONE {
            return None;
        }
        Some(self.slot_ref(fact, Ix::from(loc::slot(x.data))))
    }

    /// The join tests `tests` of the join at `depth` for left token `left` (after
    /// `bind_for_quick`) and right fact `right_fact`, if every test is `?a = ?b` or
    /// `~` of it over plain single-field slots; None when the evaluator must decide.
    pub(crate) fn quick_join_test(
        &self,
        tests: Ix,
        depth: u8,
        left: TokenId,
        right_fact: Ix,
    ) -> Option<bool> {
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
            let va = self.join_var(&a, depth, left, right_fact)?;
            let vb = self.join_var(&b, depth, left, right_fact)?;
            // single-field values: `values_same` is `same`
            if same_cell(va, vb)? == negated {
                return Some(false);
            }
            t = x.next;
        }
        Some(true)
    }
}
