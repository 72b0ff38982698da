//! Inputs the `batch` fuzz target (agent-core/fuzz/fuzz_targets/batch.rs) found,
//! replayed the way it runs them: the same small rule base loaded and reset, the text
//! run in batch mode, invariants checked, a bounded `run`, invariants again, with a
//! host that interrupts after the same poll budget. (The target runs the command
//! line's `GrowEngine`; these findings show on the small fixed engine too.)

// The prelude calls `create$` (extras) and the replay reads CLIPS text (parser).
#![cfg(all(feature = "extras", feature = "parser"))]

mod common;

use agent_core::{Host, SmallEngine};
use common::budget::Budget;

/// A host that keeps what is written.
struct Transcript(String);

impl Host for Transcript {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

/// The fuzz target's rule base (agent-core/fuzz/fuzz_targets/common/cli.rs).
const PRELUDE: &str = include_str!("../fuzz/fuzz_targets/common/prelude.clp");

fn replay(name: &str, text: &str) {
    let h = &mut Budget::new();
    let mut e = Box::new(SmallEngine::new());
    e.set_poll_calls(true);
    e.load_str(h, "prelude", PRELUDE)
        .expect("the prelude loads");
    e.reset(h).expect("the prelude resets");
    e.batch_str(h, text, true);
    if let Err(v) = e.check_invariants() {
        panic!("{name}: after batch_str: {v}");
    }
    if !e.exited() {
        h.rearm();
        let r = e.run(h, Some(1_000));
        if let Err(v) = e.check_invariants() {
            panic!("{name}: after run ({r:?}): {v}");
        }
    }
}

/// The seed tests/clips/286-modules-undefine.clp after the rule base: a template
/// whose rule was undefined, then undefined itself, was retired with its alpha nodes
/// still listed (the invariant check found a nameless template with alpha nodes).
#[test]
fn undeftemplate_after_undefrule_after_a_rule_base() {
    replay(
        "286-modules-undefine",
        include_str!("../../tests/clips/286-modules-undefine.clp"),
    );
}

/// The same, minimised: the template's rule goes, then the template.
#[test]
fn undeftemplate_after_its_rule_went() {
    replay(
        "undeftemplate-after-undefrule",
        "(deftemplate t (slot x))\n(defrule r (t (x ?x)) => )\n(undefrule r)\n(undeftemplate t)\n",
    );
}

/// A template redefined after its rule went is retired the same way; the new one's
/// rule and facts match.
#[test]
fn deftemplate_redefined_after_its_rule_went() {
    replay(
        "redefinition-after-undefrule",
        "(deftemplate t (slot x))\n(defrule r (t (x ?x)) => )\n(undefrule r)\n\
         (deftemplate t (slot y))\n(defrule r2 (t (y ?x)) => )\n(assert (t (y 1)))\n",
    );
}

/// Found by the batch target (a mutated 582-keyed-or-growth.clp): a
/// `do-for-all-facts` whose test modifies the facts it walks never ended, since a
/// query's walk did not poll the host; now the poll budget ends it.
#[test]
fn query_that_modifies_its_facts_forever_is_interrupted() {
    replay(
        "query-modifies-forever",
        &String::from_utf8_lossy(include_bytes!(
            "fuzz_regressions/batch-query-modifies-forever.clp"
        )),
    );
}

/// Found by the batch target (crash-495fe404): a fact without cells (a template
/// without slots) asserted after one with cells sits at the arena top; retracting
/// the one with cells gave the top back and left the empty fact starting past it.
/// Minimised: `(f)` is f-4 after the rule base, `(g)` f-5.
#[test]
fn empty_fact_above_a_retracted_top_fact() {
    replay(
        "empty-fact-above-retracted",
        "(deftemplate g)\n(assert(f)(g))\n(retract 4)",
    );
}

/// The same with more cells and two empty facts above them; then the arena grows
/// from the lowered top again, and a rule retracts the new top fact in a firing.
#[test]
fn empty_facts_above_retracted_top_facts() {
    replay(
        "empty-facts-above-retracted",
        "(deftemplate g)\n(deftemplate h)\n(assert (f a b c) (g) (h))\n(retract 4)\n\
         (retract 6)\n(assert (f x) (h))\n(facts)\n\
         (defrule drop ?x <- (f $?) (h) => (retract ?x))\n(run)\n(assert (f y) (i))\n",
    );
}

/// Found by the batch target (crash-1abcf135): `modify` with a single-field slot
/// given no value, `(max)`, on a fact a query bound (so the parser could not know
/// the template) evaluated the slot's empty value chain: an out-of-range expression
/// handle. Now the modify fails with an error (CLIPS 6.30: TMPLTFUN2, "Attempted to
/// assert a multifield value into the single field slot") and the fact stays.
#[test]
fn modify_single_slot_without_value_in_a_query() {
    let text = "(deftemplate m (slot max) (multislot tags))\n(assert (m (max 0)))\n\
                (do-for-fact ((?f m)) TRUE (modify ?f (max) (tags p q)))\n";
    replay("modify-single-slot-without-value", text);
    let h = &mut Transcript(String::new());
    let mut e = Box::new(SmallEngine::new());
    e.batch_str(h, text, true);
    assert!(
        h.0.contains("a single-field slot needs exactly one value"),
        "{}",
        h.0
    );
    let ms: Vec<_> = e.facts_of("m").collect();
    assert_eq!(ms.len(), 1);
    assert_eq!(
        e.fact_slot(ms[0], "max").map(|v| format!("{v:?}")),
        Some("Int(0)".to_string())
    );
}

/// The fuzz target's engine (`cli::engine`: the command line's `GrowEngine`, pools
/// growing to `--pool-limit` 2^18 entries), the rule base and `replay`'s steps.
#[cfg(feature = "grow")]
fn replay_grow(name: &str, text: &str) {
    use agent_core::grow::{GrowEngine, GrowStorage};
    use agent_core::Capacities;
    let storage = GrowStorage::with_limits(GrowStorage::START, Capacities::uniform(1 << 18));
    let mut e = Box::new(GrowEngine::with_storage(storage));
    e.set_poll_calls(true);
    let h = &mut Budget::new();
    e.load_str(h, "prelude", PRELUDE)
        .expect("the prelude loads");
    e.reset(h).expect("the prelude resets");
    e.batch_str(h, text, true);
    if let Err(v) = e.check_invariants() {
        panic!("{name}: after batch_str: {v}");
    }
    if !e.exited() {
        h.rearm();
        let r = e.run(h, Some(1_000));
        if let Err(v) = e.check_invariants() {
            panic!("{name}: after run ({r:?}): {v}");
        }
    }
}

/// Found by the batch target (timeout-332856a4): a rule whose `modify` makes the
/// fact it matched one field longer fires forever (CLIPS 6.30 too: after 3,000
/// firings it is still on the agenda), each firing copying a longer multifield; the
/// 100,000 polls the host allowed were ~5e9 copied fields, minutes past libFuzzer's
/// timeout. The host's time budget now ends it too, as an interrupt. (On the small
/// engine the fact arena fills first.)
#[cfg(feature = "grow")]
#[test]
fn multifield_that_grows_each_firing_ends_by_the_time_budget() {
    let started = std::time::Instant::now();
    replay_grow(
        "multifield-grows-forever",
        &String::from_utf8_lossy(include_bytes!(
            "fuzz_regressions/batch-multifield-grows-forever.clp"
        )),
    );
    // minimised: one fact, one rule
    replay_grow(
        "multifield-grows-forever-min",
        "(deftemplate inv (slot who) (multislot items))\n\
         (defrule give ?b <- (inv (who ?q) (items $?qi)) (give ?q ?thing)\n\
           => (modify ?b (items ?qi ?thing)))\n\
         (assert (inv (who bob)) (give bob apple))\n(run)\n",
    );
    // each replay: at most two time budgets (the text, then the final run)
    let took = started.elapsed();
    assert!(
        took < common::budget::TIME_BUDGET * 8,
        "the replays took {took:?}"
    );
}

/// Found by `batch`: a salience value that fails to evaluate and ends in a character
/// of more than one byte (`?*f*` then U+FFFD from the fuzzer's bytes) made the error
/// report read its token from inside that character (`token_at(end - 1)`), a panic.
/// The report now reads from the character's first byte.
#[test]
fn salience_error_at_a_value_ending_in_a_multibyte_character() {
    let text = "(defrule r7 (declare (salience ?*f*\u{FFFD})) => (printout t r7 crlf))\n\
                (defrule r8 (declare (salience ?*g*é)) =>)\n\
                (printout t \"rules: \" (length$ (get-defrule-list)) crlf)\n";
    replay("salience-multibyte-end", text);
    let h = &mut Transcript(String::new());
    let mut e = Box::new(SmallEngine::new());
    e.batch_str(h, text, true);
    assert!(h.0.contains("[PRNTUTIL8]"), "{}", h.0);
    assert!(
        h.0.contains("rules: 0\n"),
        "a failed rule must not exist: {}",
        h.0
    );
}
