//! The agenda's salience groups (host: kept once an insertion walked past many
//! activations) while activations come and go at the agenda's head: a new first
//! group, the first group's last activation firing, a newer activation first in its
//! group, removals from the middle. The invariants (which name each group's first
//! and last activation) hold after every firing, and the firings are CLIPS 6.30's
//! (tests/clips/764-salience-groups-at-the-head.clp is the same program).

// The steps call `loop-for-count` and read CLIPS text (parser).
#![cfg(all(feature = "extras", feature = "parser"))]

use agent_core::{DefaultEngine, Host, SmallEngine};

/// A host that keeps what is written.
struct Transcript(String);

impl Host for Transcript {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

const RULES: &str = r#"
(defrule lo (declare (salience -5)) (l ?x) => (printout t "l" ?x " "))
(defrule mid (m ?x) =>
  (printout t "m" ?x " ")
  (if (= (mod ?x 3) 0) then (assert (h ?x)))
  (if (and (< ?x 60) (= (mod ?x 4) 0)) then (assert (m (+ ?x 100)))))
(defrule hi (declare (salience 10)) (h ?x) => (printout t "h" ?x " ")
  (if (= (mod ?x 5) 0) then (assert (l (+ ?x 1000)))))
(defrule top (declare (salience 20)) (t ?x) => (printout t "t" ?x " "))
"#;

/// Loads `RULES`, resets and asserts 36 (m) facts then 34 (l) facts: every (l)
/// insertion walks past the 36 (m) activations. The transcript starts empty.
fn fill<S: agent_core::Storage>(e: &mut agent_core::Engine<S>, h: &mut Transcript) {
    e.load_str(h, "rules", RULES).expect("the rules load");
    e.reset(h).expect("reset");
    e.batch_str(
        h,
        "(loop-for-count (?i 1 36) do (assert (m ?i)))\n(loop-for-count (?i 1 34) do (assert (l ?i)))\n",
        false,
    );
    h.0.clear();
}

/// Runs `n` firings one at a time, the invariants checked after each.
fn step<S: agent_core::Storage>(
    e: &mut agent_core::Engine<S>,
    h: &mut Transcript,
    n: u32,
    at: &str,
) {
    for k in 0..n {
        match e.run(h, Some(1)) {
            Ok(1) => {}
            Ok(0) => return,
            r => panic!("{at}: firing {k}: {r:?}"),
        }
        if let Err(v) = e.check_invariants() {
            panic!("{at}: after firing {k}: {v}\n{}", h.0);
        }
    }
}

/// What CLIPS printed at each `(run ...)` of transcript `out`, in order.
fn clips_runs(out: &str) -> Vec<String> {
    out.split("CLIPS> (run")
        .skip(1)
        .map(|s| {
            let s = &s[s.find('\n').map_or(s.len(), |i| i + 1)..];
            s.split("CLIPS>").next().unwrap_or("").to_string()
        })
        .collect()
}

#[test]
fn salience_groups_hold_as_the_head_comes_and_goes() {
    let runs = clips_runs(include_str!(
        "../../tests/clips/764-salience-groups-at-the-head.out"
    ));
    assert_eq!(runs.len(), 4, "the transcript's runs");
    let h = &mut Transcript(String::new());
    let mut e = Box::new(SmallEngine::new());
    fill(&mut e, h);
    step(&mut e, h, 12, "first");
    assert_eq!(h.0, runs[0], "the first firings");
    e.batch_str(h, "(assert (t 1))\n(assert (h 500))\n", false);
    h.0.clear();
    step(&mut e, h, 3, "second");
    assert_eq!(h.0, runs[1], "a new first group, gone again");
    e.batch_str(
        h,
        "(retract 20)\n(retract 69)\n(retract 37)\n(assert (t 2) (l 99))\n",
        false,
    );
    h.0.clear();
    step(&mut e, h, 20, "third");
    assert_eq!(h.0, runs[2], "after removals from the groups");
    h.0.clear();
    step(&mut e, h, 10_000, "rest");
    assert_eq!(h.0, runs[3], "the last firings");
}

/// The groups are given up once the agenda is short again (at a removal other than
/// the quick firing of a first activation) and built again when it grows long:
/// activations of every salience come while it is short and after it is long again,
/// one leaves from the middle of a group.
/// (tests/clips/765-salience-groups-short-again.clp is the same program.)
#[test]
fn salience_groups_go_when_short_and_come_back() {
    // more facts than the small engine holds: the default engine is big, so it
    // lives on a thread with room for it
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(short_again)
        .expect("thread")
        .join()
        .expect("no panic");
}

fn short_again() {
    let runs = clips_runs(include_str!(
        "../../tests/clips/765-salience-groups-short-again.out"
    ));
    assert_eq!(runs.len(), 5, "the transcript's runs");
    let h = &mut Transcript(String::new());
    let mut e = Box::new(DefaultEngine::new());
    fill(&mut e, h);
    // down to 7 activations
    step(&mut e, h, 90, "long");
    assert_eq!(h.0, runs[0], "the long agenda's firings");
    e.batch_str(
        h,
        "(assert (t 1) (h 501) (l 77) (m 78) (h 60) (m 9))\n",
        false,
    );
    h.0.clear();
    step(&mut e, h, 4, "short");
    assert_eq!(h.0, runs[1], "insertions into the short agenda");
    e.batch_str(
        h,
        "(loop-for-count (?i 200 236) do (assert (m ?i)))\n(loop-for-count (?i 300 334) do (assert (l ?i)))\n",
        false,
    );
    h.0.clear();
    step(&mut e, h, 10, "long again");
    assert_eq!(h.0, runs[2], "the agenda long again");
    e.batch_str(h, "(assert (t 2) (h 502) (l 78))\n(retract 130)\n", false);
    h.0.clear();
    step(&mut e, h, 5, "head and middle");
    assert_eq!(h.0, runs[3], "a new first group, a removal from the middle");
    h.0.clear();
    step(&mut e, h, 10_000, "rest");
    assert_eq!(h.0, runs[4], "the last firings");
}
