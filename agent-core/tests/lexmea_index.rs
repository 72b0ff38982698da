//! The host's ordered index of the agenda under lex and mea (`strategy::RecencyIndex`)
//! against the agenda itself: long agendas (the index is kept once an insertion walks
//! past 32 activations) changed by asserts, retracts in the middle, firings, strategy
//! switches, several saliences, dynamic salience and modules, with the engine's
//! invariants (the agenda sorted by `goes_before`, the index its reverse) checked
//! after every command and every firing.

#![cfg(all(
    feature = "extras",
    feature = "parser",
    feature = "grow",
    feature = "host-speedups",
    feature = "modules"
))]

use agent_core::grow::{GrowEngine, GrowStorage};
use agent_core::{Capacities, Host};

struct Transcript(String);

impl Host for Transcript {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

/// Runs `commands` one by one (a `(run N)` one firing at a time), checking the
/// invariants after each step; returns what was printed.
fn checked(commands: &[&str]) -> String {
    let storage = GrowStorage::with_limits(GrowStorage::START, Capacities::uniform(1 << 18));
    let mut e = Box::new(GrowEngine::with_storage(storage));
    let h = &mut Transcript(String::new());
    for c in commands {
        if let Some(n) = c.strip_prefix("run ") {
            let n: u32 = n.parse().unwrap();
            for i in 0..n {
                let fired = e.run(h, Some(1)).expect("run");
                if let Err(v) = e.check_invariants() {
                    panic!("after firing {i} of {c}: {v}\n{}", h.0);
                }
                if fired == 0 {
                    break;
                }
            }
        } else {
            e.batch_str(h, c, false);
            if let Err(v) = e.check_invariants() {
                panic!("after {c}: {v}\n{}", h.0);
            }
        }
    }
    h.0.clone()
}

const RULES: &str = "
(defglobal ?*s* = 0)
(defrule mk (declare (salience 50)) ?g <- (go ?n) =>
  (retract ?g)
  (loop-for-count (?i 1 ?n) (assert (item ?i (mod (* ?i 7) 5))))
  (assert (kind a) (kind b)))
(defrule pair (item ?i ?w) (item ?j&:(> ?j ?i) ?w) => (printout t \"pair \" ?i \" \" ?j crlf))
(defrule pick (item ?i ?w) (kind ?k) => (printout t \"pick \" ?i \" \" ?k crlf))
(defrule pick2 (item ?i ?w) (kind ?k) => (printout t \"pick2 \" ?i \" \" ?k crlf))
(defrule lead (not (stop)) (item ?i ?w) => (printout t \"lead \" ?i crlf))
(defrule hi (declare (salience 10)) (item ?i 3) (kind b) => (printout t \"hi \" ?i crlf))
(defrule lo (declare (salience -10)) (kind ?k) (item ?i 1) => (printout t \"lo \" ?i crlf))
(defrule drop (declare (salience 5)) ?f <- (item ?i 4) (kind a) (test (= (mod ?i 3) 0)) =>
  (retract ?f) (printout t \"drop \" ?i crlf))
";

#[test]
fn lex_and_mea_index_follows_the_agenda() {
    for first in ["lex", "mea"] {
        let other = if first == "lex" { "mea" } else { "lex" };
        let set = format!("(set-strategy {first})");
        let switch = format!("(set-strategy {other})");
        let out = checked(&[
            RULES,
            &set,
            "(reset)",
            "(assert (go 40))",
            "run 50",
            "(assert (kind c))",
            "(retract 7)",
            "(retract 21)",
            "run 30",
            &switch,
            "run 30",
            "(assert (stop))",
            "(assert (item 100 2) (item 101 3))",
            "run 30",
            "(set-strategy depth)",
            "run 10",
            &set,
            "(assert (go 25))",
            "run 100",
            "(refresh pick)",
            "run 2000",
        ]);
        assert!(out.contains("pair 1 6"), "{out}");
        assert!(out.contains("lo "), "{out}");
    }
}

/// Dynamic saliences (more than the 16 salience groups the agenda indexes, then
/// fewer), refresh-agenda, and two modules' agendas.
#[test]
fn lex_and_mea_index_with_saliences_and_modules() {
    let out = checked(&[
        "(defglobal ?*s* = 0)",
        "(defmodule MAIN (export ?ALL))",
        "(deftemplate item (slot i) (slot w))",
        "(defrule MAIN::a (item (i ?i) (w ?w)) (item (i ?j&:(> ?j ?i)) (w ?w)) => (printout t \"a \" ?i \" \" ?j crlf))",
        "(defrule MAIN::b (declare (salience (mod ?*s* 20))) (item (i ?i)) => (bind ?*s* (+ ?*s* 1)) (printout t \"b \" ?i crlf))",
        "(defmodule W (import MAIN ?ALL))",
        "(defrule W::c (item (i ?i) (w 2)) (item (i ?j&:(< ?j ?i)) (w 2)) => (printout t \"c \" ?i \" \" ?j crlf))",
        "(defrule W::d (declare (auto-focus TRUE)) (item (i ?i&:(= (mod ?i 9) 0))) => (printout t \"d \" ?i crlf))",
        "(set-current-module MAIN)",
        "(set-salience-evaluation when-activated)",
        "(set-strategy mea)",
        "(reset)",
        "(loop-for-count (?i 1 60) (assert (item (i ?i) (w (mod (* ?i 3) 7)))))",
        "run 40",
        "(focus W)",
        "run 20",
        "(set-salience-evaluation when-defined)",
        "(refresh-agenda)",
        "(set-strategy lex)",
        "(loop-for-count (?i 61 90) (assert (item (i ?i) (w 2))))",
        "run 40",
        "(focus W MAIN)",
        "(set-salience-evaluation every-cycle)",
        "run 30",
        "(set-salience-evaluation when-defined)",
        "run 3000",
    ]);
    assert!(out.contains("c "), "{out}");
    assert!(out.contains("d 9"), "{out}");
}
