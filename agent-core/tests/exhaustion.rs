//! Exhaustion matrix: every pool of `Pool::ALL`, filled in each place it can fill — at
//! assert, during `run`, at modify, at load (or reset, for deffacts) — on engines with
//! one shrunken pool. Each case checks that
//! - the error names the pool and its capacity (returned, or printed by `run`, which
//!   reports a failing right-hand side and stops as CLIPS does);
//! - the engine is consistent afterwards (`check_invariants`);
//! - the failed operation left no trace (facts, agenda, construct pools unchanged);
//! - after retracting facts (or clearing) the same kind of operation works again.
//!
//! `capacity.rs` holds the first, per-pool capacity tests; this file completes the
//! matrix and adds the invariant checks. `every_pool_is_covered` keeps the list honest.
// without `parser` the tests that evaluate builtins are left out (only `parser` links
// their code: `builtins::BUILTINS`), and helpers only they use are unused
#![cfg_attr(not(feature = "parser"), allow(unused_imports, unused_macros))]
#![allow(dead_code)]

use agent_core::{
    CapacityError, Engine, EngineError, EvalErrorKind, FactId, Host, LoadError, Pool, Usage,
};

#[derive(Default)]
struct Capture {
    out: String,
}
impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.out.push_str(text);
    }
}

#[macro_use]
mod engine_macro;

/// Facts, agenda and construct usage: what a failed operation must not change.
#[derive(Debug, PartialEq)]
struct Snapshot {
    facts: Vec<FactId>,
    agenda: Vec<String>,
    usage: Usage,
}

/// The engine operations the checks need, for every capacity combination.
trait Probe {
    fn snapshot(&self) -> Snapshot;
    fn consistent(&mut self);
}

impl<S: agent_core::Storage> Probe for Engine<S> {
    fn snapshot(&self) -> Snapshot {
        let mut agenda = Vec::new();
        self.for_each_activation(|r, s, b| agenda.push(format!("{s} {r} {b:?}")));
        Snapshot {
            facts: self.facts().collect(),
            agenda,
            usage: self.usage(),
        }
    }
    fn consistent(&mut self) {
        if let Err(v) = self.check_invariants() {
            panic!("{v}");
        }
    }
}

/// The `(facts)` listing of an engine, for every capacity combination.
trait EvalFacts {
    fn fact_listing(&mut self) -> String;
}

impl<S: agent_core::Storage> EvalFacts for Engine<S> {
    fn fact_listing(&mut self) -> String {
        let mut h = Capture::default();
        self.eval_str(&mut h, "(facts)").unwrap();
        h.out
    }
}

fn cap_of(e: &EngineError) -> CapacityError {
    match e {
        EngineError::Capacity(c) => *c,
        EngineError::Load(l) => l.capacity.expect("a capacity error"),
        EngineError::Eval(v) => match v.kind() {
            EvalErrorKind::Capacity(c) => c,
            k => panic!("not a capacity error: {k:?}"),
        },
        other => panic!("not a capacity error: {other:?}"),
    }
}

fn load_cap(e: &LoadError) -> CapacityError {
    e.capacity
        .unwrap_or_else(|| panic!("not a capacity error: {e:?}"))
}

fn full(pool: Pool, capacity: u32) -> CapacityError {
    CapacityError { pool, capacity }
}

/// The message `run` prints for a right-hand side that ran out of `pool`.
fn run_message(pool: Pool, capacity: u32) -> String {
    format!("{}", full(pool, capacity))
}

/// Asserts facts from `make(i)` until one fails; returns the error, after checking the
/// failure left no trace and the engine is consistent.
fn assert_until_full<E: Probe + ?Sized>(
    e: &mut E,
    mut assert: impl FnMut(&mut E, usize) -> Result<FactId, EngineError>,
) -> CapacityError {
    for i in 0..10_000 {
        let before = e.snapshot();
        match assert(e, i) {
            Ok(_) | Err(EngineError::Duplicate) => e.consistent(),
            Err(err) => {
                let c = cap_of(&err);
                assert_eq!(e.snapshot(), before, "failed assert left a trace: {err}");
                e.consistent();
                return c;
            }
        }
    }
    panic!("never filled");
}

/// Loads constructs from `make(i)` until one fails; the failure leaves no trace.
fn load_until_full<E: Probe + ?Sized>(
    e: &mut E,
    mut load: impl FnMut(&mut E, usize) -> Result<usize, LoadError>,
) -> CapacityError {
    for i in 0..10_000 {
        let before = e.snapshot();
        match load(e, i) {
            Ok(_) => e.consistent(),
            Err(err) => {
                let c = load_cap(&err);
                assert_eq!(e.snapshot(), before, "failed load left a trace: {err}");
                e.consistent();
                return c;
            }
        }
    }
    panic!("never filled");
}

// ---------------------------------------------------------------- facts

#[cfg(feature = "parser")]
#[test]
fn facts_at_assert_run_modify_and_reset() {
    let h = &mut Capture::default();
    // assert
    let mut e = engine!(facts = 6);
    let c = assert_until_full(&mut *e, |e, i| e.assert_str(h, &format!("(a {i})")));
    assert_eq!(c, full(Pool::Facts, 6));
    let first = e.facts().nth(1).unwrap();
    e.retract(h, first).unwrap();
    e.assert_str(h, "(a again)").unwrap();
    e.consistent();

    // run: a rule counting upwards fills the pool; the failed assert adds nothing
    let mut e = engine!(facts = 6);
    let h = &mut Capture::default();
    e.load_str(
        h,
        "t",
        "(defrule up (n ?x&:(< ?x 100)) => (assert (n (+ ?x 1))))",
    )
    .unwrap();
    e.assert_str(h, "(n 0)").unwrap();
    let fired = e.run(h, None).unwrap();
    assert!(h.out.contains(&run_message(Pool::Facts, 6)), "{}", h.out);
    assert_eq!(fired, 5);
    assert_eq!(e.facts().count(), 6);
    e.consistent();
    let _ = e.eval_str(h, "(retract 1 2 3)");
    e.consistent();
    // (n 5)'s activation fired and failed; a new start point fires again
    e.assert_str(h, "(n 50)").unwrap();
    assert!(e.run(h, None).unwrap() > 0);
    e.consistent();

    // modify while the pool is full: the retracted fact stays readable until the
    // firing ends, so the new one has no slot
    let mut e = engine!(facts = 4);
    let h = &mut Capture::default();
    e.load_str(
        h,
        "t",
        "(deftemplate c (slot v)) (defrule bump ?f <- (c (v ?v&:(< ?v 3))) => (modify ?f (v (+ ?v 1))))",
    )
    .unwrap();
    e.assert_str(h, "(c (v 0))").unwrap();
    e.assert_str(h, "(x 1)").unwrap();
    e.assert_str(h, "(x 2)").unwrap();
    let before = e.snapshot();
    let before_listing = listing(&mut *e);
    e.run(h, None).unwrap();
    assert!(h.out.contains(&run_message(Pool::Facts, 4)), "{}", h.out);
    failed_modify_kept_the_facts(&mut *e, &before, &before_listing);
    // the same modify at the prompt: the retract frees the slot the new fact takes
    let before = e.snapshot();
    let r = e.eval_str(h, "(modify 1 (v 1))").unwrap();
    assert_ne!(r, agent_core::Value::Sym(0), "{r:?}");
    assert_eq!(
        e.facts().collect::<Vec<_>>(),
        [FactId(0), FactId(2), FactId(3), FactId(4)]
    );
    assert_eq!(before.facts.len(), 4);
    e.consistent();
    // with a slot free the rule modifies on
    e.retract(h, FactId(2)).unwrap();
    h.out.clear();
    e.run(h, None).unwrap();
    assert!(!h.out.contains("out of"), "{}", h.out);
    assert_eq!(
        e.fact_slot(FactId(6), "v").map(|v| format!("{v:?}")),
        Some("Int(3)".into())
    );
    e.consistent();

    // reset with more deffacts than room
    let mut e = engine!(facts = 4);
    let h = &mut Capture::default();
    e.load_str(h, "t", "(deffacts many (a 1) (a 2) (a 3) (a 4) (a 5))")
        .unwrap();
    let err = e.reset(h).unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Facts, 4));
    e.consistent();
    e.clear(h).unwrap();
    e.load_str(h, "t", "(deffacts few (a 1) (a 2))").unwrap();
    e.reset(h).unwrap();
    assert_eq!(e.facts().count(), 3);
    e.consistent();
}

// ---------------------------------------------------------------- fact values

#[cfg(feature = "parser")]
#[test]
fn fact_values_at_assert_run_modify_and_reset() {
    let h = &mut Capture::default();
    let mut e = engine!(fact_values = 24);
    let c = assert_until_full(&mut *e, |e, i| {
        e.assert_str(h, &format!("(big {i} 1 2 3 4 5 6)"))
    });
    assert_eq!(c, full(Pool::FactValues, 24));
    let second = e.facts().nth(1).unwrap();
    e.retract(h, second).unwrap();
    e.assert_str(h, "(big again 1 2 3 4 5)").unwrap();
    e.consistent();

    // run: growing multifields
    let mut e = engine!(fact_values = 40);
    let h = &mut Capture::default();
    e.load_str(h, "t", "(defrule grow (l $?x) => (assert (l $?x $?x 1)))")
        .unwrap();
    e.assert_str(h, "(l 1)").unwrap();
    e.run(h, None).unwrap();
    assert!(
        h.out.contains(&run_message(Pool::FactValues, 40)),
        "{}",
        h.out
    );
    e.consistent();
    let last = e.facts().last().unwrap();
    e.retract(h, last).unwrap();
    e.assert_str(h, "(l 9 9)").unwrap();
    e.consistent();

    // modify to a longer multislot than fits
    let mut e = engine!(fact_values = 20);
    let h = &mut Capture::default();
    e.load_str(h, "t", "(deftemplate m (multislot xs))")
        .unwrap();
    e.assert_str(h, "(m (xs 1 2))").unwrap();
    e.assert_str(h, "(pad 1 2 3 4 5 6 7 8 9)").unwrap();
    let before = e.snapshot();
    let before_listing = listing(&mut *e);
    let r = e.eval_str(h, "(modify 1 (xs 1 2 3 4 5 6 7 8 9 10 11 12))");
    assert_eq!(
        r.map_err(|e| e.kind()),
        Err(EvalErrorKind::Capacity(full(Pool::FactValues, 20)))
    );
    failed_modify_kept_the_facts(&mut *e, &before, &before_listing);
    assert_eq!(e.snapshot(), before);
    // the retracted fact's cells count: a modify that fills the pool exactly fits
    e.eval_str(h, "(modify 1 (xs 1 2 3 4 5 6 7 8))").unwrap();
    assert_eq!(
        e.facts().collect::<Vec<_>>(),
        [FactId(0), FactId(2), FactId(3)]
    );
    e.consistent();
    e.retract(h, FactId(2)).unwrap();
    e.consistent();

    // reset with big deffacts
    let mut e = engine!(fact_values = 16);
    let h = &mut Capture::default();
    e.load_str(
        h,
        "t",
        "(deffacts big (a 1 2 3 4 5 6) (b 1 2 3 4 5 6 7 8 9))",
    )
    .unwrap();
    let err = e.reset(h).unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::FactValues, 16));
    e.consistent();
    e.clear(h).unwrap();
    e.consistent();
    e.assert_str(h, "(a 1 2 3 4 5 6)").unwrap();
}

/// The fact listing `(facts)` prints: numbers and values.
fn listing<E: EvalFacts + ?Sized>(e: &mut E) -> String {
    e.fact_listing()
}

/// A modify that ran out of room left its facts as they were: the old fact with its
/// number, place and values, no new fact, no fact number used up, the construct pools
/// and tokens unchanged, and the engine consistent. (The agenda is compared by the
/// callers that do not fire a rule on the way.)
fn failed_modify_kept_the_facts<E: Probe + EvalFacts + ?Sized>(
    e: &mut E,
    before: &Snapshot,
    before_listing: &str,
) {
    e.consistent();
    let after = e.snapshot();
    assert_eq!(after.facts, before.facts, "modify lost or added facts");
    assert_eq!(listing(e), before_listing, "modify changed fact values");
    assert_eq!(after.usage, before.usage, "modify left pool usage");
}

// ---------------------------------------------------------------- symbols

#[cfg(feature = "parser")]
#[test]
fn symbols_and_bytes_at_assert_run_modify_and_load() {
    for (pool, cap) in [(Pool::Symbols, 48u32), (Pool::SymbolBytes, 600)] {
        // assert new symbols
        let h = &mut Capture::default();
        let mut e = engine!(symbols = 48, symbol_bytes = 600);
        let long = "s".repeat(if pool == Pool::SymbolBytes { 40 } else { 1 });
        let c = assert_until_full(&mut *e, |e, i| e.assert_str(h, &format!("(s {long}{i})")));
        assert_eq!(c, full(pool, cap));
        // known symbols still work after retracting
        let f = e.facts().nth(1).unwrap();
        e.retract(h, f).unwrap();
        e.assert_str(h, "(s nil)").unwrap();
        e.consistent();

        // load: new template names
        let mut e = engine!(
            symbols = 48,
            symbol_bytes = 600,
            templates = 64,
            template_memories = 64,
            slot_defs = 128
        );
        let c = load_until_full(&mut *e, |e, i| {
            e.load_str(h, "t", &format!("(deftemplate {long}t{i} (slot v))"))
        });
        assert_eq!(c, full(pool, cap));
        e.assert_str(h, &format!("({long}t0 (v 1))")).unwrap();
        e.consistent();

        // run: the right-hand side makes new symbols; modify does too
        let mut e = engine!(symbols = 48, symbol_bytes = 600);
        let h = &mut Capture::default();
        e.load_str(
            h,
            "t",
            &format!(
                "(deftemplate k (slot v) (slot n))
                 (defrule mint ?f <- (k (n ?n&:(< ?n 500))) => (modify ?f (n (+ ?n 1)) (v (sym-cat {long} ?n))))"
            ),
        )
        .unwrap();
        e.assert_str(h, "(k (n 0))").unwrap();
        e.run(h, None).unwrap();
        assert!(h.out.contains(&run_message(pool, cap)), "{}", h.out);
        e.consistent();
        assert_eq!(e.facts().count(), 2, "the modified fact is kept");
    }
}

/// `sym-cat` and `sub-string` build their text at the symbol arena's free end: with
/// the arena full, texts that exist are still found, and a new one is a capacity
/// error; the limit on a text's length stays the same.
#[cfg(feature = "parser")]
#[test]
fn sym_cat_and_sub_string_with_the_symbol_arena_full() {
    let h = &mut Capture::default();
    let mut e = engine!(symbol_bytes = 600);
    e.assert_str(h, "(known abcdef)").unwrap();
    let c = assert_until_full(&mut *e, |e, i| {
        e.assert_str(h, &format!("(s {}{i})", "s".repeat(40)))
    });
    assert_eq!(c, full(Pool::SymbolBytes, 600));
    let found = e
        .eval_str(h, "(sym-cat abc def)")
        .expect("an existing symbol");
    let again = e
        .eval_str(h, "(sym-cat abcdef)")
        .expect("an existing symbol");
    assert_eq!(found, again);
    e.eval_str(h, "(sub-string 1 6 abcdef)")
        .expect("an existing string");
    let err = e
        .eval_str(h, &format!("(sym-cat{})", " abcdef".repeat(8)))
        .unwrap_err();
    assert_eq!(
        cap_of(&EngineError::Eval(err)),
        full(Pool::SymbolBytes, 600)
    );
    e.consistent();

    // the length limit, with room in the arena: 2048 bytes in the image; with `grow`
    // none but the storage's (CLIPS builds any length)
    let mut e = engine!(symbol_bytes = 8192);
    let long = "x".repeat(1100);
    let r = e.eval_str(h, &format!("(sym-cat {long} {long})"));
    #[cfg(not(feature = "grow"))]
    assert!(r.unwrap_err().to_string().contains("longer than 2048"));
    #[cfg(feature = "grow")]
    assert!(matches!(r, Ok(agent_core::Value::Sym(_))));
    let ok = e
        .eval_str(h, &format!("(sym-cat {long} {})", "y".repeat(900)))
        .unwrap();
    assert!(matches!(ok, agent_core::Value::Sym(_)), "{ok:?}");
    e.consistent();
}

// ---------------------------------------------------------------- templates, slots

#[test]
fn templates_and_slot_defs_at_load_and_assert() {
    let h = &mut Capture::default();
    // initial-fact takes one template and one slot
    let mut e = engine!(templates = 4);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(deftemplate t{i} (slot v))"))
    });
    assert_eq!(c, full(Pool::Templates, 4));
    // an ordered fact of a new relation needs an implied template
    let c = assert_until_full(&mut *e, |e, i| e.assert_str(h, &format!("(rel{i} 1)")));
    assert_eq!(c, full(Pool::Templates, 4));
    e.assert_str(h, "(t0 (v 1))").unwrap();
    e.clear(h).unwrap();
    e.assert_str(h, "(rel 1)").unwrap();
    e.consistent();

    // a template's run-time part (its fact count) is an entry of its own pool
    let mut e = engine!(template_memories = 4);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(deftemplate t{i} (slot v))"))
    });
    assert_eq!(c, full(Pool::TemplateMemories, 4));
    let c = assert_until_full(&mut *e, |e, i| e.assert_str(h, &format!("(rel{i} 1)")));
    assert_eq!(c, full(Pool::TemplateMemories, 4));
    e.assert_str(h, "(t0 (v 1))").unwrap();
    e.clear(h).unwrap();
    e.assert_str(h, "(rel 1)").unwrap();
    e.consistent();

    let mut e = engine!(slot_defs = 6);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(deftemplate t{i} (slot a) (slot b))"))
    });
    assert_eq!(c, full(Pool::SlotDefs, 6));
    let c = assert_until_full(&mut *e, |e, i| e.assert_str(h, &format!("(rel{i} 1)")));
    assert_eq!(c, full(Pool::SlotDefs, 6));
    e.clear(h).unwrap();
    e.assert_str(h, "(rel 1)").unwrap();
    e.consistent();
}

// ---------------------------------------------------------------- rules, alpha, joins

/// Fills one construct pool by loading rules against existing facts (so new rules are
/// primed and a rollback has matches to undo), then checks recovery after `clear`.
macro_rules! rule_pool_case {
    ($pool:expr, $cap:expr, $e:expr) => {{
        // Each case is a function of its own: in a debug build one frame would hold
        // every case's engine at once, past a test thread's 2 MB stack.
        #[inline(never)]
        fn case() {
            let (pool, cap) = ($pool, $cap);
            let h = &mut Capture::default();
            let mut e = $e;
            e.load_str(h, "t", "(deftemplate p (slot x) (slot y))")
                .unwrap();
            for i in 0..4 {
                e.assert_str(h, &format!("(p (x {i}) (y {}))", i % 2))
                    .unwrap();
            }
            let c = load_until_full(&mut *e, |e, i| {
                let text = match pool {
                    Pool::Rules => format!("(defrule r{i} (p (x ?x)) =>)"),
                    Pool::AlphaNodes | Pool::AlphaMemories => {
                        format!("(defrule r{i} (p (x {i}) (y ?y)) =>)")
                    }
                    _ => format!("(defrule r{i} (p (x ?x)) (p (y ?x)) (q {i}) =>)"),
                };
                e.load_str(h, "t", &text)
            });
            assert_eq!(c, full(pool, cap));
            // still matches and fires
            e.assert_str(h, "(p (x 0) (y 9))").unwrap();
            e.assert_str(h, "(q 0)").unwrap();
            assert!(e.run(h, None).unwrap() > 0);
            e.consistent();
            // clearing gives the room back
            e.clear(h).unwrap();
            e.load_str(h, "t", "(defrule again (p ?x) =>)").unwrap();
            e.consistent();
        }
        case();
    }};
}

#[test]
fn rules_alpha_nodes_and_joins_at_load() {
    rule_pool_case!(Pool::Rules, 6, engine!(rules = 6));
    rule_pool_case!(Pool::AlphaNodes, 8, engine!(alpha_nodes = 8));
    rule_pool_case!(Pool::Joins, 14, engine!(joins = 14));
    // the run-time parts of alpha nodes and joins, pools of their own (so that a
    // compiled rule base's nodes can be read in place)
    rule_pool_case!(Pool::AlphaMemories, 8, engine!(alpha_memories = 8));
    rule_pool_case!(Pool::JoinMemories, 14, engine!(join_memories = 14));
}

/// Regression (found by the invariant property test): a load that failed after
/// creating an alpha node sorted into the middle of its template's list left the node
/// linked there, pointing at a dropped pool entry.
#[test]
fn failed_load_unlinks_alpha_nodes_from_the_middle_of_a_template_list() {
    let h = &mut Capture::default();
    let mut e = engine!(rules = 2);
    e.load_str(
        h,
        "t",
        "(deftemplate item (slot id) (slot state) (multislot tags))
         (defrule a (item (id ?i) (state seen)) =>)
         (defrule b (item (state done)) =>)",
    )
    .unwrap();
    let before = e.snapshot();
    let err = e
        .load_str(
            h,
            "t",
            "(defrule c (item (id ?i) (tags $?t&:(> (length$ ?t) 1))) =>)",
        )
        .unwrap_err();
    assert_eq!(load_cap(&err), full(Pool::Rules, 2));
    assert_eq!(e.snapshot(), before);
    e.consistent();
    e.assert_str(h, "(item (id 1) (state seen) (tags a b))")
        .unwrap();
    e.consistent();
}

// ---------------------------------------------------------------- tokens, activations

const CROSS: &str = "(defrule cross (a ?x) (b ?y) (not (c ?x ?y)) => (assert (c ?x ?y)))";

/// Tokens and activations fill at assert (a growing cross product), during `run`
/// (right-hand sides asserting), at modify and at load (a new rule primed against
/// existing facts); `$mk` makes an engine with the one pool shrunk.
macro_rules! match_pool_case {
    ($pool:expr, $cap:expr, $mk:expr) => {{
        let (pool, cap): (Pool, u32) = ($pool, $cap);
        // assert: the cross product grows until a pool is full; the failed assert
        // is undone completely
        let h = &mut Capture::default();
        let mut e = $mk;
        e.load_str(h, "t", CROSS).unwrap();
        let c = assert_until_full(&mut *e, |e, i| {
            e.assert_str(h, &format!("({} {i})", if i % 2 == 0 { "a" } else { "b" }))
        });
        assert_eq!(c, full(pool, cap), "assert");
        let f = e.facts().nth(1).unwrap();
        e.retract(h, f).unwrap();
        e.consistent();
        assert!(e.assert_str(h, "(a new)").is_ok());
        e.consistent();

        // run: firing asserts (c x y) facts, each dropping an activation but adding
        // tokens; in the activation case more pairs are asserted from the RHS
        let mut e = $mk;
        let h = &mut Capture::default();
        e.load_str(
            h,
            "t",
            "(defrule spawn (go ?n&:(< ?n 40)) => (assert (a ?n) (b ?n) (go (+ ?n 1))))",
        )
        .unwrap();
        e.load_str(h, "t", CROSS).unwrap();
        e.assert_str(h, "(go 0)").unwrap();
        e.run(h, None).unwrap();
        assert!(h.out.contains(&run_message(pool, cap)), "run: {}", h.out);
        e.consistent();
        let _ = e.eval_str(h, "(retract *)");
        e.consistent();
        h.out.clear();
        e.assert_str(h, "(a 1)").unwrap();
        e.assert_str(h, "(b 1)").unwrap();
        assert_eq!(e.run(h, None).unwrap(), 1);
        e.consistent();

        // modify: changing a fact to one that matches many
        let mut e = $mk;
        let h = &mut Capture::default();
        e.load_str(
            h,
            "t",
            "(deftemplate k (slot v)) (defrule many (k (v 1)) (a ?x) (b ?y) =>)",
        )
        .unwrap();
        for i in 0..6 {
            e.assert_str(h, &format!("(a {i})")).unwrap();
            e.assert_str(h, &format!("(b {i})")).unwrap();
        }
        e.assert_str(h, "(k (v 0))").unwrap();
        let fact = e.facts().last().unwrap();
        let before = e.snapshot();
        let before_listing = listing(&mut *e);
        // (k (v 1)) matches 36 pairs: more activations and tokens than room
        let r = e.eval_str(h, &format!("(modify {} (v 1))", fact.0));
        assert_eq!(
            r.map_err(|e| e.kind()),
            Err(EvalErrorKind::Capacity(full(pool, cap))),
            "modify"
        );
        failed_modify_kept_the_facts(&mut *e, &before, &before_listing);
        assert_eq!(e.snapshot(), before);
        // the old fact still matches, and the next fact gets the next number
        let r = e.eval_str(h, &format!("(modify {} (v 2))", fact.0));
        assert!(r.is_ok(), "{r:?}");
        assert_eq!(e.facts().last(), Some(FactId(fact.0 + 1)));
        e.retract(h, FactId(1)).unwrap();
        e.assert_str(h, "(k (v 3))").unwrap();
        e.consistent();

        // load: a new rule primed against existing facts runs out; rollback
        let mut e = $mk;
        let h = &mut Capture::default();
        for i in 0..5 {
            e.assert_str(h, &format!("(a {i})")).unwrap();
            e.assert_str(h, &format!("(b {i})")).unwrap();
        }
        let before = e.snapshot();
        let err = e
            .load_str(h, "t", "(defrule late (a ?x) (b ?y) =>)")
            .unwrap_err();
        assert_eq!(load_cap(&err), full(pool, cap), "load");
        assert_eq!(e.snapshot(), before);
        e.consistent();
        for i in 0..4 {
            e.retract(h, FactId(1 + 2 * i)).unwrap();
        }
        e.load_str(h, "t", "(defrule late (a ?x) (b ?y) =>)")
            .unwrap();
        e.consistent();
    }};
}

#[cfg(feature = "parser")]
#[test]
fn tokens_and_activations_at_assert_run_modify_and_load() {
    // two expansions of the case macro make a frame too big for a test thread's
    // default stack in a debug build, so the cases run on a thread with room
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            match_pool_case!(Pool::Tokens, 40, engine!(tokens = 40));
            match_pool_case!(Pool::Activations, 6, engine!(activations = 6));
        })
        .expect("thread")
        .join()
        .expect("no panic");
}

// ---------------------------------------------------------------- constructs

#[cfg(feature = "parser")]
#[test]
fn functions_globals_and_deffacts_at_load() {
    let h = &mut Capture::default();
    let mut e = engine!(functions = 2);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(deffunction f{i} (?x) (* ?x {i}))"))
    });
    assert_eq!(c, full(Pool::Functions, 2));
    assert_eq!(e.eval_str(h, "(f1 3)").unwrap(), agent_core::Value::Int(3));
    e.clear(h).unwrap();
    e.load_str(h, "t", "(deffunction g () 1)").unwrap();
    e.consistent();

    let mut e = engine!(globals = 2);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(defglobal ?*g{i}* = (create$ {i} {i}))"))
    });
    assert_eq!(c, full(Pool::Globals, 2));
    e.reset(h).unwrap();
    e.consistent();
    e.clear(h).unwrap();
    e.load_str(h, "t", "(defglobal ?*x* = 1)").unwrap();
    e.consistent();

    let mut e = engine!(deffacts = 2);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(deffacts d{i} (d {i}))"))
    });
    assert_eq!(c, full(Pool::Deffacts, 2));
    e.reset(h).unwrap();
    assert_eq!(e.facts().count(), 3);
    e.consistent();
    e.clear(h).unwrap();
    e.load_str(h, "t", "(deffacts again (d 9))").unwrap();
    e.consistent();
}

#[test]
fn expression_nodes_at_load_and_assert() {
    let h = &mut Capture::default();
    let mut e = engine!(exprs = 200);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(
            h,
            "t",
            &format!("(defrule r{i} (a ?x) => (printout t (+ ?x {i} 1 2 3) crlf))"),
        )
    });
    assert_eq!(c, full(Pool::Exprs, 200));
    // an assert's fact spec is parsed into temporary nodes: a big one does not fit
    let values: Vec<String> = (0..120).map(|i| i.to_string()).collect();
    let before = e.snapshot();
    let err = e
        .assert_str(h, &format!("(big {})", values.join(" ")))
        .unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Exprs, 200));
    assert_eq!(e.snapshot(), before);
    e.consistent();
    e.assert_str(h, "(a 1)").unwrap();
    assert!(e.run(h, None).unwrap() > 0);
    e.clear(h).unwrap();
    e.load_str(h, "t", "(defrule small (a ?x) =>)").unwrap();
    e.consistent();
}

#[cfg(feature = "parser")]
#[test]
fn eval_stack_at_run_assert_and_eval() {
    let h = &mut Capture::default();
    // run: a recursive deffunction on the right-hand side
    let mut e = engine!(eval_stack = 24);
    e.load_str(
        h,
        "t",
        "(deffunction down (?n) (if (> ?n 0) then (+ 1 (down (- ?n 1))) else 0))
         (defrule deep (depth ?n) => (assert (got (down ?n))))",
    )
    .unwrap();
    e.assert_str(h, "(depth 100)").unwrap();
    e.run(h, None).unwrap();
    assert!(
        h.out.contains(&run_message(Pool::EvalStack, 24)),
        "{}",
        h.out
    );
    e.consistent();
    assert!(e.facts().all(|f| e.fact_template_name(f) != Some("got")));
    e.assert_str(h, "(depth 3)").unwrap();
    h.out.clear();
    e.run(h, None).unwrap();
    assert!(h.out.is_empty(), "{}", h.out);
    e.consistent();

    // assert: a template with more slots than the stack holds
    let mut e = engine!(eval_stack = 4);
    e.load_str(
        h,
        "t",
        "(deftemplate wide (slot a) (slot b) (slot c) (slot d) (slot e))",
    )
    .unwrap();
    let before = e.snapshot();
    let err = e.assert_str(h, "(wide (a 1))").unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::EvalStack, 4));
    assert_eq!(e.snapshot(), before);
    e.consistent();
    e.assert_str(h, "(narrow 1)").unwrap();
    e.consistent();
}

#[cfg(feature = "parser")]
#[test]
fn scratch_at_run_assert_and_modify() {
    let h = &mut Capture::default();
    let mut e = engine!(scratch = 12);
    e.load_str(
        h,
        "t",
        "(deftemplate m (multislot xs))
         (defrule dup ?f <- (m (xs $?x&:(< (length$ ?x) 40))) => (modify ?f (xs $?x $?x 1)))",
    )
    .unwrap();
    e.assert_str(h, "(m (xs 1))").unwrap();
    e.run(h, None).unwrap();
    assert!(h.out.contains(&run_message(Pool::Scratch, 12)), "{}", h.out);
    e.consistent();
    assert_eq!(e.facts().count(), 2, "the modified fact is kept");

    // assert: a multislot longer than scratch
    let values: Vec<String> = (0..20).map(|i| i.to_string()).collect();
    let before = e.snapshot();
    let err = e
        .assert_str(h, &format!("(m (xs {}))", values.join(" ")))
        .unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Scratch, 12));
    assert_eq!(e.snapshot(), before);
    e.consistent();
    e.assert_str(h, "(m (xs a b c))").unwrap();
    e.consistent();
}

#[test]
fn external_functions_at_registration() {
    fn one(
        _call: &mut agent_core::HostCall<'_, '_>,
    ) -> Result<agent_core::Value, agent_core::EvalError> {
        Ok(agent_core::Value::Int(1))
    }
    let h = &mut Capture::default();
    let mut e = engine!(external_fns = 2);
    e.register_function("one", 0, Some(0), one).unwrap();
    e.register_function("two", 0, Some(0), one).unwrap();
    let before = e.snapshot();
    let err = e.register_function("three", 0, Some(0), one).unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::ExternalFns, 2));
    assert_eq!(e.snapshot().facts, before.facts);
    e.consistent();
    // replacing an existing one still works, and clear keeps them
    e.register_function("two", 0, Some(0), one).unwrap();
    e.clear(h).unwrap();
    assert_eq!(e.eval_str(h, "(two)").unwrap(), agent_core::Value::Int(1));
    e.consistent();
}

#[cfg(all(feature = "parser", feature = "logical"))]
#[test]
fn logical_supports_at_run_and_assert() {
    let h = &mut Capture::default();
    let mut e = engine!(supports = 2);
    e.load_str(h, "t", "(defrule hold (logical (a ?x)) => (assert (b ?x)))")
        .unwrap();
    for x in 1..=3 {
        e.assert_str(h, &format!("(a {x})")).unwrap();
    }
    // two firings fill the pool; the third one's assert stops the run, creating nothing
    e.run(h, None).unwrap();
    assert!(h.out.contains(&run_message(Pool::Supports, 2)), "{}", h.out);
    e.consistent();
    let listing = e.fact_listing();
    assert_eq!(listing.matches("(b ").count(), 2, "{listing}");
    // retracting a supporting fact frees its support (and retracts what it held)
    h.out.clear();
    e.eval_str(h, "(retract 3)").unwrap();
    let listing = e.fact_listing();
    assert!(
        !listing.contains("(b 3)") && !listing.contains("(a 3)"),
        "{listing}"
    );
    assert_eq!(listing.matches("(b ").count(), 1, "{listing}");
    e.consistent();
    // the failed firing is spent (refraction); a new match finds the room freed
    e.assert_str(h, "(a 4)").unwrap();
    h.out.clear();
    e.run(h, None).unwrap();
    assert!(h.out.is_empty(), "{}", h.out);
    assert!(e.fact_listing().contains("(b 4)"));
    e.consistent();
}

#[cfg(all(feature = "parser", feature = "modules"))]
#[test]
fn modules_ports_and_focus_stack() {
    let h = &mut Capture::default();
    // MAIN is entry 0: two entries leave room for one defmodule
    let mut e = engine!(modules = 2);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(h, "t", &format!("(defmodule M{i})"))
    });
    assert_eq!(c, full(Pool::Modules, 2));
    h.out.clear();
    e.eval_str(h, "(printout t (get-defmodule-list) crlf)")
        .unwrap();
    assert_eq!(h.out, "(MAIN M0)\n");
    e.clear(h).unwrap();
    e.load_str(h, "t", "(defmodule N)").unwrap();
    e.consistent();

    let mut e = engine!(module_ports = 3);
    let c = load_until_full(&mut *e, |e, i| {
        e.load_str(
            h,
            "t",
            &format!("(defmodule P{i} (export ?ALL) (export deftemplate a b))"),
        )
    });
    assert_eq!(c, full(Pool::ModulePorts, 3));
    // P0's three ports fill the pool; P1, whose ports did not fit, is not defined
    h.out.clear();
    e.eval_str(h, "(printout t (get-defmodule-list) crlf)")
        .unwrap();
    assert_eq!(h.out, "(MAIN P0)\n");
    e.load_str(h, "t", "(defmodule Q)").unwrap();
    e.consistent();

    let mut e = engine!(focus_stack = 2);
    e.load_str(h, "t", "(defmodule A) (defmodule B)").unwrap();
    e.eval_str(h, "(focus A)").unwrap();
    // the stack holds MAIN and A: B does not fit
    assert!(e.eval_str(h, "(focus B)").is_err());
    h.out.clear();
    e.eval_str(h, "(printout t (get-focus-stack) crlf)")
        .unwrap();
    assert_eq!(h.out, "(A MAIN)\n");
    e.consistent();
}

/// Every pool has a case above (names listed by hand; a new pool fails this test).
#[test]
fn every_pool_is_covered() {
    let covered = [
        Pool::Facts,
        Pool::FactValues,
        Pool::Symbols,
        Pool::SymbolBytes,
        Pool::Templates,
        Pool::TemplateMemories,
        Pool::SlotDefs,
        Pool::Rules,
        Pool::AlphaNodes,
        Pool::AlphaMemories,
        Pool::Joins,
        Pool::JoinMemories,
        Pool::Tokens,
        Pool::Activations,
        Pool::Functions,
        Pool::Globals,
        Pool::Exprs,
        Pool::EvalStack,
        Pool::Scratch,
        Pool::Deffacts,
        Pool::ExternalFns,
        Pool::Supports,
        Pool::Modules,
        Pool::ModulePorts,
        Pool::FocusStack,
    ];
    for p in Pool::ALL {
        assert!(covered.contains(&p), "no exhaustion case for {p:?}");
    }
}

/// Found by the `engine_commands` fuzz target: an assert that blocks a `not` CE and
/// then runs out of tokens is undone; undoing unblocks the `not` and re-creates its
/// rule's activation, which used to come back as the newest one (an older activation
/// then fired first). The assert now journals the activations it removes and the undo
/// gives the re-created ones their old places and numbers.
#[test]
fn failed_assert_keeps_the_agenda_order_of_blocked_not_rules() {
    let h = &mut Capture::default();
    let mut e = engine!(tokens = 40);
    e.load_str(
        h,
        "t",
        "(defrule use (item ?x) (o ?x) =>)
         (defrule unhit (hit ?x) (not (item ?x)) =>)
         (defrule other (o ?x) =>)
         (defrule pad (pad ?x) =>)",
    )
    .unwrap();
    e.assert_str(h, "(hit 1)").unwrap();
    e.assert_str(h, "(o 1)").unwrap();
    let mut i = 0;
    while e.assert_str(h, &format!("(pad {i})")).is_ok() {
        i += 1;
    }
    let pad = e.facts().last().unwrap();
    e.retract(h, pad).unwrap();
    let before = e.snapshot();
    let err = e.assert_str(h, "(item 1)").unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Tokens, 40));
    e.consistent();
    let mut sorted_before = before.agenda.clone();
    let mut sorted_after = e.snapshot().agenda;
    sorted_before.sort();
    sorted_after.sort();
    assert_eq!(sorted_after, sorted_before, "same activations");
    assert_eq!(e.snapshot(), before, "same order");
}

/// A retract that unblocks a `not` must rebuild the matches below it; with the token
/// pool full there may be no room (the retract freed two tokens, the six matches need
/// six), and `retract` used to drop them silently (`remove_link` ignored the error of
/// `propagate`): the rule never fired for those facts. Now the unblocked output is
/// owed: the retract happens (CLIPS's retract cannot fail) and reports the full pool,
/// nothing fires and nothing can be asserted while the matches are owed, and the first
/// operation with room builds them.
#[test]
fn retract_unblocking_a_not_with_full_tokens_is_not_silent() {
    let h = &mut Capture::default();
    let mut e = engine!(tokens = 40);
    e.load_str(
        h,
        "t",
        "(defrule a (p ?x) (not (r ?x)) (q ?x ?) =>)
         (defrule pad (pad ?x) =>)",
    )
    .unwrap();
    e.assert_str(h, "(p 1)").unwrap();
    for k in 0..6 {
        e.assert_str(h, &format!("(q 1 {k})")).unwrap();
    }
    let blocker = e.assert_str(h, "(r 1)").unwrap();
    let mut i = 0;
    while e.assert_str(h, &format!("(pad {i})")).is_ok() {
        i += 1;
    }
    assert_eq!(e.counts().1, i, "only the pads are activated");
    let err = e.retract(h, blocker).unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Tokens, 40));
    e.consistent();
    assert!(!e.facts().any(|f| f == blocker), "the retract happened");
    // owed matches first: no assert, no firing until they are built
    let before = e.snapshot();
    let err = e.assert_str(h, "(other 1)").unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Tokens, 40));
    assert_eq!(e.snapshot(), before, "the assert left no trace");
    let err = e.run(h, None).unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Tokens, 40));
    assert_eq!(e.snapshot(), before, "nothing fired");
    e.consistent();
    // free room: the retracts build the owed matches of rule a for (p 1) and the q facts
    let pads: Vec<FactId> = e.facts().skip(8).take(6).collect();
    for f in pads {
        let _ = e.retract(h, f);
        e.consistent();
    }
    let mut rules = Vec::new();
    e.for_each_activation(|r, _, _| rules.push(r.to_string()));
    assert_eq!(
        rules.iter().filter(|r| *r == "a").count(),
        6,
        "unblocked matches of rule a were lost: {rules:?}"
    );
    assert!(e.retract(h, e.facts().last().unwrap()).is_ok());
    e.assert_str(h, "(other 1)").unwrap();
    e.consistent();
}

/// Found by the invariant property test: an assert that failed on a full pool kept the
/// symbols (and the implied template) its text had created. Now rolled back.
#[test]
fn failed_assert_keeps_no_new_symbols_or_templates() {
    let h = &mut Capture::default();
    let mut e = engine!(facts = 3);
    e.assert_str(h, "(a 1)").unwrap();
    e.assert_str(h, "(a 2)").unwrap();
    let before = e.snapshot();
    let err = e.assert_str(h, "(brand-new never-seen)").unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Facts, 3));
    assert_eq!(e.snapshot(), before);
    e.consistent();
    e.retract(h, FactId(1)).unwrap();
    e.assert_str(h, "(brand-new never-seen)").unwrap();
    e.consistent();
}

/// A modify whose new fact runs out of tokens or activations in the network puts the
/// old fact back: its number, values and matches, and its activations at their old
/// agenda places (between activations of other facts).
macro_rules! agenda_order_case {
    ($pool:expr, $cap:expr, $mk:expr) => {{
        let (pool, cap): (Pool, u32) = ($pool, $cap);
        let h = &mut Capture::default();
        let mut e = $mk;
        e.load_str(
            h,
            "t",
            "(deftemplate k (slot v))
             (defrule many (k (v 1)) (a ?x) (b ?y) =>)
             (defrule seen (k (v ?v)) =>)
             (defrule pair (k (v ?v)) (o ?x) =>)
             (defrule other (o ?x) =>)
             (defrule late (declare (salience -5)) (k (v ?v)) =>)",
        )
        .unwrap();
        e.assert_str(h, "(o 1)").unwrap();
        let k = e.assert_str(h, "(k (v 0))").unwrap();
        e.assert_str(h, "(o 2)").unwrap();
        for i in 0..3 {
            e.assert_str(h, &format!("(a {i})")).unwrap();
            e.assert_str(h, &format!("(b {i})")).unwrap();
        }
        let before = e.snapshot();
        let before_listing = listing(&mut *e);
        assert_eq!(before.agenda.len(), 6, "{:?}", before.agenda);
        let r = e.eval_str(h, &format!("(modify {} (v 1))", k.0));
        assert_eq!(
            r.map_err(|e| e.kind()),
            Err(EvalErrorKind::Capacity(full(pool, cap))),
            "{pool:?} {:?}",
            e.usage()
        );
        failed_modify_kept_the_facts(&mut *e, &before, &before_listing);
        assert_eq!(e.snapshot(), before, "{pool:?}");
        // the next fact gets the next number; the old fact still modifies
        let r = e.eval_str(h, &format!("(modify {} (v 2))", k.0));
        assert!(r.is_ok(), "{r:?}");
        assert_eq!(e.facts().last(), Some(FactId(10)));
        assert_eq!(e.run(h, None).unwrap(), 6);
        e.consistent();
    }};
}

/// A modify whose new fact runs out of tokens or activations in the network puts the
/// old fact back: its number, values and matches, and its activations at their old
/// agenda places (between activations of other facts, and in another salience).
#[cfg(feature = "parser")]
#[test]
fn failed_modify_keeps_the_agenda_order() {
    agenda_order_case!(Pool::Tokens, 24, engine!(tokens = 24));
    agenda_order_case!(Pool::Activations, 12, engine!(activations = 12));
}

/// The same during a firing: the retracted fact was pending (readable until the
/// firing ends) and comes back from there.
#[cfg(feature = "parser")]
#[test]
fn failed_modify_in_a_firing_keeps_the_old_fact() {
    let h = &mut Capture::default();
    let mut e = engine!(tokens = 40);
    e.load_str(
        h,
        "t",
        "(deftemplate k (slot v))
         (defrule many (k (v 1)) (a ?x) (b ?y) =>)
         (defrule go ?f <- (go) ?k <- (k (v 0)) => (retract ?f) (modify ?k (v 1)))",
    )
    .unwrap();
    for i in 0..6 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
        e.assert_str(h, &format!("(b {i})")).unwrap();
    }
    let k = e.assert_str(h, "(k (v 0))").unwrap();
    e.assert_str(h, "(go)").unwrap();
    let before_listing = listing(&mut *e);
    e.run(h, None).unwrap();
    assert!(h.out.contains(&run_message(Pool::Tokens, 40)), "{}", h.out);
    e.consistent();
    // (go) was retracted before the modify failed; (k (v 0)) is still there
    let expected: String = before_listing
        .lines()
        .filter(|l| !l.contains("(go)") && !l.starts_with("For a total"))
        .map(|l| format!("{l}\n"))
        .collect();
    let after = listing(&mut *e);
    assert!(after.starts_with(&expected), "{after}");
    assert_eq!(
        e.fact_slot(k, "v").map(|v| format!("{v:?}")),
        Some("Int(0)".into())
    );
    // the fact is usable: a modify to a value that matches little works
    e.eval_str(h, &format!("(modify {} (v 2))", k.0)).unwrap();
    e.consistent();
}

/// A modify or assert that runs out of room is undone, so it prints no watch traces:
/// no `<== f-1` for a retract that was taken back, no `==> f-N` for a fact that never
/// came, no activation lines of either (they are held back until the operation
/// cannot fail any more, see `hold.rs`). A successful modify prints CLIPS's lines, in
/// CLIPS's order (checked against `clips -f` 6.30).
#[cfg(feature = "parser")]
#[test]
fn failed_modify_and_assert_print_no_watch_traces() {
    let h = &mut Capture::default();
    let mut e = engine!(tokens = 40);
    e.load_str(
        h,
        "t",
        "(deftemplate k (slot v))
         (defrule zero (k (v 0)) =>)
         (defrule many (k (v 1)) (a ?x) (b ?y) =>)
         (defrule pad (pad ?x) =>)",
    )
    .unwrap();
    for i in 0..3 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
    }
    for i in 0..2 {
        e.assert_str(h, &format!("(b {i})")).unwrap();
    }
    let k = e.assert_str(h, "(k (v 0))").unwrap();
    let mut pads = Vec::new();
    while let Ok(f) = e.assert_str(h, &format!("(pad {})", pads.len())) {
        pads.push(f);
    }
    e.eval_str(h, "(watch facts)").unwrap();
    e.eval_str(h, "(watch activations)").unwrap();
    h.out.clear();
    let before = e.snapshot();
    let err = e
        .eval_str(h, &format!("(modify {} (v 1))", k.0))
        .unwrap_err();
    assert_eq!(cap_of(&err.into()), full(Pool::Tokens, 40));
    assert!(
        !h.out.contains("==>") && !h.out.contains("<=="),
        "a failed modify printed traces: {}",
        h.out
    );
    assert_eq!(e.snapshot(), before);
    e.consistent();
    let err = e.assert_str(h, "(k (v 1))").unwrap_err();
    assert_eq!(cap_of(&err), full(Pool::Tokens, 40));
    assert!(
        !h.out.contains("==>") && !h.out.contains("<=="),
        "a failed assert printed traces: {}",
        h.out
    );
    assert_eq!(e.snapshot(), before);
    e.consistent();
    // with room, the same modify prints what CLIPS prints
    e.eval_str(h, "(unwatch all)").unwrap();
    for f in pads.drain(..) {
        e.retract(h, f).unwrap();
    }
    e.eval_str(h, "(watch facts)").unwrap();
    e.eval_str(h, "(watch activations)").unwrap();
    h.out.clear();
    e.eval_str(h, &format!("(modify {} (v 1))", k.0)).unwrap();
    let n = e.facts().last().unwrap().0;
    let expected = format!(
        "<== f-6     (k (v 0))\n\
         <== Activation 0      zero: f-6\n\
         ==> {:<8}(k (v 1))\n\
         ==> Activation 0      many: f-{n},f-1,f-4\n\
         ==> Activation 0      many: f-{n},f-1,f-5\n\
         ==> Activation 0      many: f-{n},f-2,f-4\n\
         ==> Activation 0      many: f-{n},f-2,f-5\n\
         ==> Activation 0      many: f-{n},f-3,f-4\n\
         ==> Activation 0      many: f-{n},f-3,f-5\n",
        format!("f-{n}")
    );
    assert_eq!(h.out, expected);
    e.consistent();
}

/// A failed modify of a fact that is not the newest puts its cells back where no other
/// fact's are: a later compaction keeps every fact's values. (Found by
/// `engine_commands`: the old fact came back at the top of the value arena, and the
/// next compaction copied it over the cells of the first fact.)
#[cfg(feature = "parser")]
#[test]
fn failed_modify_of_an_old_fact_then_compaction_keeps_every_fact() {
    let h = &mut Capture::default();
    // (initial-fact), (pad) and (k) take one cell each, (a i) and (b i) two: 28
    let mut e = engine!(tokens = 40, fact_values = 28);
    e.load_str(
        h,
        "t",
        "(deftemplate k (slot v)) (defrule many (k (v 1)) (a ?x) (b ?y) =>)",
    )
    .unwrap();
    let pad = e.assert_str(h, "(pad)").unwrap();
    let k = e.assert_str(h, "(k (v 0))").unwrap();
    let mut b5 = k;
    for i in 0..6 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
        b5 = e.assert_str(h, &format!("(b {i})")).unwrap();
    }
    e.retract(h, pad).unwrap();
    e.assert_str(h, "(pad)").unwrap();
    // the new (k (v 1)) compacts away the old one's cell, then runs out of tokens:
    // the restore makes room below the (a)/(b) facts
    let r = e.eval_str(h, &format!("(modify {} (v 1))", k.0));
    assert_eq!(
        r.map_err(|e| e.kind()),
        Err(EvalErrorKind::Capacity(full(Pool::Tokens, 40)))
    );
    e.consistent();
    let before = listing(&mut *e);
    // the arena is full again: this assert compacts the gap (b 5) leaves
    e.retract(h, b5).unwrap();
    e.assert_str(h, "(c 1)").unwrap();
    e.consistent();
    let after = listing(&mut *e);
    let kept: String = before
        .lines()
        .filter(|l| !l.contains("(b 5)") && !l.starts_with("For a total"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(after.starts_with(&kept), "{before}\n{after}");
    assert_eq!(
        e.fact_slot(k, "v").map(|v| format!("{v:?}")),
        Some("Int(0)".into())
    );
}

/// A fact without slots takes no value cells; retracted during a firing (pending) it
/// must not stall the compaction an assert of the same firing runs.
#[cfg(feature = "parser")]
#[test]
fn compaction_in_a_firing_passes_a_retracted_fact_without_slots() {
    let h = &mut Capture::default();
    let mut e = engine!(fact_values = 16);
    e.load_str(
        h,
        "t",
        "(deftemplate e) (defrule r ?f <- (e) => (retract ?f) (assert (b 1 2 3 4 5 6 7)))",
    )
    .unwrap();
    let a = e.assert_str(h, "(a 1 2 3 4 5 6)").unwrap();
    e.assert_str(h, "(pad 1)").unwrap();
    e.retract(h, a).unwrap();
    e.assert_str(h, "(e)").unwrap();
    assert_eq!(e.run(h, None).unwrap(), 1);
    e.consistent();
    assert_eq!(
        listing(&mut *e),
        "f-0     (initial-fact)\nf-2     (pad 1)\nf-4     (b 1 2 3 4 5 6 7)\nFor a total of 3 facts.\n"
    );
}

/// A fact a firing retracts leaves its slot its cells; the next firing's new fact
/// takes both: a rule that retracts one fact and asserts one of the same size per
/// firing keeps the arena top where the first firing left it (no compaction, whose
/// cost grows with the fact base). (initial-fact) takes one cell, each (n x) two.
#[cfg(feature = "parser")]
#[test]
fn firings_reuse_the_cells_of_the_facts_they_retracted() {
    let h = &mut Capture::default();
    let mut e = engine!(fact_values = 8);
    e.load_str(
        h,
        "t",
        "(defrule step ?f <- (n ?x&:(< ?x 50)) => (retract ?f) (assert (n (+ ?x 1))))",
    )
    .unwrap();
    e.assert_str(h, "(n 0)").unwrap();
    assert_eq!(e.run(h, None).unwrap(), 50);
    e.consistent();
    assert_eq!(
        listing(&mut *e),
        "f-0     (initial-fact)\nf-51    (n 50)\nFor a total of 2 facts.\n"
    );
    // the first firing's new fact took cells 3-4 (its retracted one was still
    // readable), every later one the cells the previous firing's retract left
    assert_eq!(e.stats().get(Pool::FactValues).0, 5);
}

/// A new fact in a freed fact's cells sits before older facts in the arena: a later
/// compaction packs the facts by cell position, not by list order, and keeps every
/// fact's values.
#[cfg(feature = "parser")]
#[test]
fn compaction_after_reused_cells_keeps_every_fact() {
    let h = &mut Capture::default();
    // (initial-fact) one cell, (a 1) to (d 1) two each
    let mut e = engine!(fact_values = 16);
    let a = e.assert_str(h, "(a 1)").unwrap();
    let b = e.assert_str(h, "(b 1)").unwrap();
    e.assert_str(h, "(c 1)").unwrap();
    e.retract(h, a).unwrap();
    // (d 1) takes the cells (a 1) left, below (c 1)'s
    e.assert_str(h, "(d 1)").unwrap();
    e.assert_str(h, "(e 1 2 3 4)").unwrap();
    e.consistent();
    // too big for the two cells (b 1) leaves: 12 + 6 cells do not fit, compaction
    // leaves 10
    e.retract(h, b).unwrap();
    e.assert_str(h, "(f 1 2 3 4 5)").unwrap();
    e.consistent();
    assert_eq!(
        listing(&mut *e),
        "f-0     (initial-fact)\nf-3     (c 1)\nf-4     (d 1)\nf-5     (e 1 2 3 4)\n\
         f-6     (f 1 2 3 4 5)\nFor a total of 5 facts.\n"
    );
    // full now: the next fact runs out, and nothing changed
    let r = e.assert_str(h, "(g 1)");
    assert_eq!(cap_of(&r.unwrap_err()), full(Pool::FactValues, 16));
    e.consistent();
}
