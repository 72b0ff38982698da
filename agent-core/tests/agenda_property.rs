//! Property test: random assert/retract/modify sequences; after every step the
//! engine's agenda equals a naive full re-match of all rules, ordered by the same
//! conflict resolution (salience, then newest first). Activations born in the same
//! step are ordered by network details the naive matcher does not model, so the
//! comparison is: same activations, and the engine's order is sorted by
//! (salience desc, birth step desc).
//!
//! The second property runs the same sequences on an engine whose token and
//! activation pools run out: a failed assert or modify leaves the agenda exactly as it
//! was (same activations, same order), and a retract never loses a match (one it
//! reports as owed appears at the next operation that succeeds).
// without `parser` the tests that evaluate builtins are left out (only `parser` links
// their code: `builtins::BUILTINS`), and helpers only they use are unused
#![cfg_attr(
    not(feature = "parser"),
    allow(dead_code, unused_imports, unused_macros)
)]

use std::collections::{BTreeMap, BTreeSet};

use agent_core::{Engine, EngineError, FactId, Host, SmallEngine};
use proptest::prelude::*;

struct Quiet;
impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

const RULES: &str = "
(deftemplate t (slot k) (slot v))
(defrule r1 (a ?x) (b ?x) =>)
(defrule r2 (declare (salience 5)) (a ?x) (not (c ?x)) =>)
(defrule r3 (b ?y) =>)
(defrule r4 (declare (salience -3)) (a ?x) (exists (b ?x)) =>)
(defrule r5 (a ?x) (c ?y&:(> ?y ?x)) =>)
(defrule r6 (declare (salience 2)) ?f <- (t (k ?k) (v ?v)) (a ?v) =>)
(defrule r7 (t (k p) (v ?v)) (not (b ?v)) =>)
(defrule r8 (a ?x) (not (and (b ?x) (c ?y&:(> ?y ?x)))) =>)
(defrule r9 (declare (salience 1)) (exists (a ?x) (b ?x)) =>)
(defrule r10 (not (and (a ?x) (not (b ?x)))) =>)
(defrule r11 (t (k ?k) (v ?v)) (exists (a ?v) (not (c ?v))) =>)
(defrule r12 (a ?x) (not (not (c ?x))) =>)
(defrule r13 (c ?x) (not (b ?x)) (a ?y) (t (k ?k)) =>)
";

#[derive(Clone, Debug)]
enum Op {
    Assert(u8, i64),
    AssertT(bool, i64),
    Retract(usize),
    Modify(usize, i64),
    /// Fire up to n activations (full-pool property only: refraction).
    Run(u8),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => (0u8..3, 1i64..4).prop_map(|(r, n)| Op::Assert(r, n)),
        1 => (any::<bool>(), 1i64..4).prop_map(|(k, v)| Op::AssertT(k, v)),
        2 => (0usize..16).prop_map(Op::Retract),
        1 => (0usize..16, 1i64..4).prop_map(|(i, v)| Op::Modify(i, v)),
    ]
}

/// A fact of the naive model.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum F {
    Rel(u8, i64),
    T(bool, i64),
}

type Key = (String, Vec<Option<u32>>);

fn naive(facts: &BTreeMap<u32, F>) -> BTreeMap<Key, i32> {
    let mut out = BTreeMap::new();
    let rel = |r: u8| {
        facts.iter().filter_map(move |(n, f)| match f {
            F::Rel(x, v) if *x == r => Some((*n, *v)),
            _ => None,
        })
    };
    let ts = || {
        facts.iter().filter_map(|(n, f)| match f {
            F::T(k, v) => Some((*n, *k, *v)),
            _ => None,
        })
    };
    for (na, x) in rel(0) {
        for (nb, y) in rel(1) {
            if x == y {
                out.insert(("r1".into(), vec![Some(na), Some(nb)]), 0);
            }
        }
        if !rel(2).any(|(_, z)| z == x) {
            out.insert(("r2".into(), vec![Some(na), None]), 5);
        }
        if rel(1).any(|(_, y)| y == x) {
            out.insert(("r4".into(), vec![Some(na), None]), -3);
        }
        for (nc, y) in rel(2) {
            if y > x {
                out.insert(("r5".into(), vec![Some(na), Some(nc)]), 0);
            }
        }
    }
    for (nb, _) in rel(1) {
        out.insert(("r3".into(), vec![Some(nb)]), 0);
    }
    // not/exists over several CEs (joins from the right), nested not, double not
    for (na, x) in rel(0) {
        if !rel(1).any(|(_, y)| y == x && rel(2).any(|(_, z)| z > x)) {
            out.insert(("r8".into(), vec![Some(na), None]), 0);
        }
        if rel(2).any(|(_, z)| z == x) {
            out.insert(("r12".into(), vec![Some(na), None]), 0);
        }
    }
    // a retract of a b fact unblocks a match per a fact (fan-out)
    for (nc, x) in rel(2) {
        if !rel(1).any(|(_, y)| y == x) {
            for (na, _) in rel(0) {
                for (nt, _, _) in ts() {
                    out.insert(("r13".into(), vec![Some(nc), None, Some(na), Some(nt)]), 0);
                }
            }
        }
    }
    if rel(0).any(|(_, x)| rel(1).any(|(_, y)| y == x)) {
        out.insert(("r9".into(), vec![None]), 1);
    }
    if rel(0).all(|(_, x)| rel(1).any(|(_, y)| y == x)) {
        out.insert(("r10".into(), vec![None]), 0);
    }
    for (nt, _, v) in ts() {
        if rel(0).any(|(_, x)| x == v && !rel(2).any(|(_, z)| z == v)) {
            out.insert(("r11".into(), vec![Some(nt), None]), 0);
        }
    }
    for (nt, k, v) in ts() {
        for (na, x) in rel(0) {
            if x == v {
                out.insert(("r6".into(), vec![Some(nt), Some(na)]), 2);
            }
        }
        if k && !rel(1).any(|(_, y)| y == v) {
            out.insert(("r7".into(), vec![Some(nt), None]), 0);
        }
    }
    out
}

fn text(f: &F) -> String {
    match f {
        F::Rel(r, v) => format!("({} {v})", ["a", "b", "c"][*r as usize]),
        F::T(k, v) => format!("(t (k {}) (v {v}))", if *k { "p" } else { "q" }),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]
    #[cfg(feature = "parser")]
    #[test]
    fn agenda_matches_naive_rematch(ops in proptest::collection::vec(op(), 1..40)) {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut Quiet;
        e.load_str(h, "rules", RULES).unwrap();
        let mut facts: BTreeMap<u32, F> = BTreeMap::new();
        let mut next = 1u32;
        let mut birth: BTreeMap<Key, usize> = BTreeMap::new();
        for (step, op) in ops.iter().enumerate() {
            match op {
                Op::Assert(..) | Op::AssertT(..) => {
                    let f = match op { Op::Assert(r, v) => F::Rel(*r, *v), Op::AssertT(k, v) => F::T(*k, *v), _ => unreachable!() };
                    let dup = facts.values().any(|g| *g == f);
                    let r = e.assert_str(h, &text(&f));
                    prop_assert_eq!(r.is_ok(), !dup);
                    if !dup {
                        prop_assert_eq!(r.unwrap(), FactId(next));
                        facts.insert(next, f);
                        next += 1;
                    }
                }
                Op::Retract(i) => {
                    if facts.is_empty() { continue; }
                    let num = *facts.keys().nth(i % facts.len()).unwrap();
                    e.retract(h, FactId(num)).unwrap();
                    facts.remove(&num);
                }
                Op::Run(_) => continue,
                Op::Modify(i, v) => {
                    let tnums: Vec<u32> = facts.iter().filter(|(_, f)| matches!(f, F::T(..))).map(|(n, _)| *n).collect();
                    if tnums.is_empty() { continue; }
                    let num = tnums[i % tnums.len()];
                    let k = match facts[&num] { F::T(k, _) => k, _ => unreachable!() };
                    e.eval_str(h, &format!("(modify {num} (v {v}))")).unwrap();
                    facts.remove(&num);
                    let nf = F::T(k, *v);
                    if !facts.values().any(|g| *g == nf) {
                        facts.insert(next, nf);
                        next += 1;
                    }
                }
            }
            let want = naive(&facts);
            birth.retain(|k, _| want.contains_key(k));
            for k in want.keys() {
                birth.entry(k.clone()).or_insert(step);
            }
            let mut got: Vec<(Key, i32)> = Vec::new();
            e.for_each_activation(|r, s, b| got.push(((r.to_string(), b.to_vec()), s)));
            let got_set: BTreeSet<&Key> = got.iter().map(|(k, _)| k).collect();
            let want_set: BTreeSet<&Key> = want.keys().collect();
            prop_assert_eq!(got_set, want_set, "after {:?}", op);
            for (k, s) in &got {
                prop_assert_eq!(*s, want[k]);
            }
            for w in got.windows(2) {
                let a = (w[0].1, birth[&w[0].0]);
                let b = (w[1].1, birth[&w[1].0]);
                prop_assert!(a >= b, "order {:?} before {:?} after {:?}", w[0], w[1], op);
            }
        }
    }
}

fn op_or_run() -> impl Strategy<Value = Op> {
    prop_oneof![7 => op(), 1 => (1u8..4).prop_map(Op::Run)]
}

agent_core::engine_storage! {
    /// SmallEngine with 64 tokens and 12 activations: the sequences run them out.
    struct TightStorage {
        tokens: 64,
        activations: 12,
        ..agent_core::Capacities::SMALL
    }
}
type TightEngine = Engine<TightStorage>;

fn agenda_of(e: &TightEngine) -> Vec<(Key, i32)> {
    let mut got = Vec::new();
    e.for_each_activation(|r, s, b| got.push(((r.to_string(), b.to_vec()), s)));
    got
}

fn is_full(r: &Result<impl std::fmt::Debug, EngineError>) -> bool {
    matches!(r, Err(EngineError::Capacity(_)))
}

/// Runs `ops` on a `TightEngine` against the naive model (see the module docs).
fn check_full_pools(ops: &[Op]) -> Result<(), TestCaseError> {
    let mut e = Box::new(TightEngine::with_storage(TightStorage::new()));
    let h = &mut Quiet;
    e.load_str(h, "rules", RULES).unwrap();
    let mut facts: BTreeMap<u32, F> = BTreeMap::new();
    let mut next = 1u32;
    let mut birth: BTreeMap<Key, usize> = BTreeMap::new();
    // a retract reported matches it could not build yet
    let mut owed = false;
    // matches whose activation fired: refraction keeps them off the agenda while the
    // match lasts
    let mut done: BTreeSet<Key> = BTreeSet::new();
    for (step, op) in ops.iter().enumerate() {
        let before = agenda_of(&e);
        let mut failed = false;
        match op {
            Op::Assert(..) | Op::AssertT(..) => {
                let f = match op {
                    Op::Assert(r, v) => F::Rel(*r, *v),
                    Op::AssertT(k, v) => F::T(*k, *v),
                    _ => unreachable!(),
                };
                let dup = facts.values().any(|g| *g == f);
                let r = e.assert_str(h, &text(&f));
                if is_full(&r) {
                    failed = true;
                } else {
                    prop_assert_eq!(r.is_ok(), !dup, "{:?}", r);
                    owed = false;
                    if !dup {
                        prop_assert_eq!(r.unwrap(), FactId(next));
                        facts.insert(next, f);
                        next += 1;
                    }
                }
            }
            Op::Retract(i) => {
                if facts.is_empty() {
                    continue;
                }
                let num = *facts.keys().nth(i % facts.len()).unwrap();
                let r = e.retract(h, FactId(num));
                prop_assert!(r.is_ok() || is_full(&r), "{:?}", r);
                owed = r.is_err();
                facts.remove(&num);
            }
            Op::Run(n) => {
                // the model knows the agenda only while nothing is owed
                if owed {
                    continue;
                }
                let fired = e.run(h, Some(u32::from(*n))).unwrap() as usize;
                for (k, _) in &before[..fired] {
                    done.insert(k.clone());
                }
            }
            Op::Modify(i, v) => {
                let tnums: Vec<u32> = facts
                    .iter()
                    .filter(|(_, f)| matches!(f, F::T(..)))
                    .map(|(n, _)| *n)
                    .collect();
                if tnums.is_empty() {
                    continue;
                }
                let num = tnums[i % tnums.len()];
                let k = match facts[&num] {
                    F::T(k, _) => k,
                    _ => unreachable!(),
                };
                let r = e.eval_str(h, &format!("(modify {num} (v {v}))"));
                match r {
                    Err(ref err)
                        if matches!(err.kind(), agent_core::EvalErrorKind::Capacity(_)) =>
                    {
                        failed = true
                    }
                    _ => {
                        prop_assert!(r.is_ok(), "{:?}", r);
                        owed = false;
                        facts.remove(&num);
                        let nf = F::T(k, *v);
                        if !facts.values().any(|g| *g == nf) {
                            facts.insert(next, nf);
                        }
                        // a duplicate new fact takes no number
                        next = e.facts().map(|f| f.0 + 1).max().unwrap_or(next).max(next);
                    }
                }
            }
        }
        if let Err(v) = e.check_invariants() {
            panic!("after {op:?}: {v}");
        }
        let got = agenda_of(&e);
        if failed {
            prop_assert_eq!(&got, &before, "a failed {:?} changed the agenda", op);
            continue;
        }
        let mut want = naive(&facts);
        done.retain(|k| want.contains_key(k));
        want.retain(|k, _| !done.contains(k));
        let got_set: BTreeSet<&Key> = got.iter().map(|(k, _)| k).collect();
        let want_set: BTreeSet<&Key> = want.keys().collect();
        if owed {
            prop_assert!(got_set.is_subset(&want_set), "after {:?}", op);
        } else {
            prop_assert_eq!(got_set, want_set, "after {:?}", op);
        }
        birth.retain(|k, _| got.iter().any(|(g, _)| g == k));
        for (k, _) in &got {
            birth.entry(k.clone()).or_insert(step);
        }
        for (k, s) in &got {
            prop_assert_eq!(*s, want[k]);
        }
        for w in got.windows(2) {
            let a = (w[0].1, birth[&w[0].0]);
            let b = (w[1].1, birth[&w[1].0]);
            prop_assert!(a >= b, "order {:?} before {:?} after {:?}", w[0], w[1], op);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]
    #[cfg(feature = "parser")]
    #[test]
    fn full_pools_lose_no_match_and_keep_the_order(ops in proptest::collection::vec(op_or_run(), 1..60)) {
        check_full_pools(&ops)?;
    }
}

/// Found by the property above: an assert of `(b 1)` blocked rule r8's `not (and ...)`
/// and removed its activation, then ran out of tokens; the undo re-created it, but the
/// journal had noted as its agenda follower an activation the assert itself had
/// created (and the undo removed), so it could not be put back and came back as the
/// newest. Now an activation goes back by its creation number.
#[cfg(feature = "parser")]
#[test]
fn undone_assert_restores_an_activation_whose_follower_was_new() {
    use Op::*;
    let ops = [
        Assert(0, 1),
        Assert(0, 2),
        Assert(1, 1),
        Retract(0),
        Retract(0),
        AssertT(true, 1),
        Assert(0, 2),
        Assert(1, 3),
        Retract(4),
        Assert(0, 1),
        Assert(2, 3),
        Modify(0, 2),
        Retract(5),
        Retract(0),
        Assert(2, 2),
        Assert(1, 1),
    ];
    check_full_pools(&ops).unwrap();
}

/// Found by the property above: a modify whose retract unblocked a `not` (the rebuilt
/// matches taking the room the retract freed) ran out of activations; putting the old
/// fact back then met a full pool before reaching the pattern that blocks the `not`
/// again, and the old fact was lost. Now the matches rebuilt below unblocked outputs
/// are taken back (owed) before the old fact returns.
#[cfg(feature = "parser")]
#[test]
fn undone_modify_keeps_its_fact_when_its_retract_unblocked_a_not() {
    use Op::*;
    let ops = [
        Assert(0, 1),
        Assert(1, 1),
        Retract(6),
        Assert(0, 1),
        Assert(0, 2),
        Retract(1),
        Assert(2, 1),
        AssertT(false, 1),
        Assert(1, 2),
        Retract(1),
        Retract(7),
        Assert(0, 3),
        Modify(0, 3),
        Assert(0, 1),
        AssertT(false, 1),
        Retract(1),
        Retract(7),
        Retract(10),
        Assert(1, 2),
        Modify(0, 1),
        Retract(6),
        Assert(1, 2),
        Assert(0, 2),
        Assert(0, 1),
        Assert(2, 3),
        Assert(2, 1),
        Modify(0, 3),
        Retract(7),
        Modify(0, 2),
    ];
    check_full_pools(&ops).unwrap();
}

/// Found by the property above once it fired rules: an assert of `(b 1)` blocked the
/// inner `not` of r10 (`not (and (a ?x) (not (b ?x)))`), which unblocked r10's output;
/// its activation found the pool full and was owed, but the assert reported success
/// with the match still owed. An assert now completes what it owes or fails (undone).
#[test]
fn an_assert_that_leaves_a_not_owed_fails() {
    use Op::*;
    let ops = [
        Assert(1, 1),
        Assert(0, 1),
        Retract(0),
        Assert(0, 2),
        AssertT(false, 1),
        Assert(0, 3),
        Retract(4),
        Assert(0, 1),
        Retract(1),
        Assert(1, 2),
        Retract(1),
        AssertT(true, 1),
        Retract(9),
        Assert(2, 2),
        Assert(0, 1),
        Run(1),
        Assert(1, 1),
    ];
    check_full_pools(&ops).unwrap();
}
