//! Random command streams for the engine, decoded from bytes: shared by the invariant
//! property test (`tests/invariants_property.rs`) and the `engine_commands` fuzz target
//! (`fuzz/fuzz_targets/engine_commands.rs`, which includes this file by path).
//!
//! The engine is small so pools run out during the stream; after every command the
//! invariants must hold, and a failed assert must leave facts and agenda unchanged.

#![allow(dead_code)]

use agent_core::{Engine, EngineError, FactId, Host};

agent_core::engine_storage! {
    /// Small pools, so random streams reach every "full" path.
    pub struct StreamStorage {
        facts: 24,
        fact_values: 192,
        symbols: 128,
        symbol_bytes: 2048,
        templates: 8,
        template_memories: 8,
        slot_defs: 32,
        rules: 16,
        alpha_nodes: 48,
        alpha_memories: 48,
        joins: 96,
        join_memories: 96,
        tokens: 160,
        activations: 40,
        functions: 4,
        globals: 4,
        exprs: 1400,
        eval_stack: 64,
        scratch: 96,
        deffacts: 2,
        external_fns: 2,
        supports: 8,
        modules: 4,
        module_ports: 8,
        focus_stack: 8,
    }
}
pub type StreamEngine = Engine<StreamStorage>;

/// Rules with not/exists, multifield patterns, shared prefixes, modify and retract on
/// the right-hand side, salience, a `test` CE and a global. (A macro so the extended
/// base below can append to it; the fuzz-found streams replay against this one.)
macro_rules! rule_base {
    () => {
        "
(deftemplate item (slot id) (slot state (allowed-symbols new seen done) (default new))
  (multislot tags))
(deftemplate link (slot from) (slot to))
(defglobal ?*n* = 0)
(defrule take-tag
  ?f <- (item (id ?i) (state new) (tags ?t $?rest))
  (not (link (from ?i)))
  => (modify ?f (state seen) (tags $?rest)))
(defrule pair
  (item (id ?a) (state seen))
  (item (id ?b&~?a) (state seen))
  (not (link (from ?a) (to ?b)))
  => (assert (link (from ?a) (to ?b))))
(defrule drop-links
  (exists (item (state done)))
  ?l <- (link (from ?a))
  => (retract ?l))
(defrule finish
  (declare (salience 5))
  ?f <- (item (id ?i) (state seen) (tags $? x $?))
  => (modify ?f (state done)))
(defrule count
  (declare (salience -5))
  (tick ?n $?)
  (test (> ?n 2))
  => (bind ?*n* (+ ?*n* 1)))
(defrule split
  (tick $?a ?x $?b)
  (item (id ?x))
  (not (hit ?x))
  => (assert (hit ?x (length$ ?a) (length$ ?b))))
(defrule unhit
  ?h <- (hit ?x $?)
  (not (item (id ?x)))
  => (retract ?h))
"
    };
}
pub const RULE_BASE: &str = rule_base!();

/// The rule base plus a `not` over several CEs (a subnetwork joined from the right).
pub const RULE_BASE_NOT_AND: &str = concat!(
    rule_base!(),
    "(defrule lonely
  (item (id ?i))
  (not (and (link (from ?i) (to ?j)) (item (id ?j) (state done))))
  (exists (tick $?))
  =>)
"
);

/// Extra rules loaded (and redefined) during a stream: rule removal paths.
const EXTRA_RULES: [&str; 4] = [
    "(defrule extra-0 (item (id ?i)) (link (from ?i) (to ?j)) =>)",
    "(defrule extra-1 (declare (salience 3)) (exists (link)) (tick $?) => (assert (seen-tick)))",
    "(defrule extra-0 (item (id ?i) (tags $?t&:(> (length$ ?t) 1))) => (assert (long ?i)))",
    "(defrule extra-2 ?f <- (seen-tick) (not (item)) => (retract ?f))",
];

const STATES: [&str; 3] = ["new", "seen", "done"];
const TAGS: [&str; 3] = ["x", "y", "z"];

/// One step of a stream.
#[derive(Clone, Debug)]
pub enum Cmd {
    AssertItem {
        id: u8,
        state: u8,
        tags: Vec<u8>,
    },
    AssertLink {
        from: u8,
        to: u8,
    },
    AssertTick(Vec<u8>),
    /// Retract the n-th live fact (modulo the fact count).
    Retract(u8),
    /// Modify the n-th live fact: a new state and/or id.
    Modify {
        nth: u8,
        state: u8,
        id: u8,
    },
    Run(u8),
    Reset,
    LoadExtra(u8),
    Undefrule(u8),
    Clear,
}

/// Decodes bytes into commands (every byte string is a valid stream).
pub fn decode(data: &[u8]) -> Vec<Cmd> {
    let mut cmds = Vec::new();
    let mut i = 0;
    let take = |i: &mut usize| {
        let b = data.get(*i).copied().unwrap_or(0);
        *i += 1;
        b
    };
    while i < data.len() {
        let op = take(&mut i);
        let cmd = match op % 16 {
            0..=3 => {
                let a = take(&mut i);
                let b = take(&mut i);
                let tags = (0..(b >> 4) % 4).map(|k| (b >> k) % 3).collect();
                Cmd::AssertItem {
                    id: a % 6,
                    state: (a >> 4) % 3,
                    tags,
                }
            }
            4 | 5 => {
                let a = take(&mut i);
                Cmd::AssertLink {
                    from: a % 6,
                    to: (a >> 4) % 6,
                }
            }
            6 => {
                let a = take(&mut i);
                Cmd::AssertTick((0..a % 5).map(|k| (a >> k) % 6).collect())
            }
            7 | 8 => Cmd::Retract(take(&mut i)),
            9 | 10 => {
                let a = take(&mut i);
                Cmd::Modify {
                    nth: a,
                    state: take(&mut i) % 4,
                    id: take(&mut i) % 8,
                }
            }
            11 | 12 => Cmd::Run(take(&mut i) % 24),
            13 => Cmd::Reset,
            14 => {
                let a = take(&mut i);
                if a >= 250 {
                    Cmd::Clear
                } else if a % 2 == 0 {
                    Cmd::LoadExtra(a / 2)
                } else {
                    Cmd::Undefrule(a / 2)
                }
            }
            _ => Cmd::LoadExtra(take(&mut i)),
        };
        cmds.push(cmd);
    }
    cmds
}

/// Drops output and interrupts once polled `POLL_BUDGET` times in one command (one
/// poll per loop iteration or rule firing): a guard, should a rule base or command ever
/// loop forever (the runs are bounded and the rule bases have no loops today).
struct Quiet(u32);

const POLL_BUDGET: u32 = 100_000;

impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    fn interrupt(&mut self) -> bool {
        self.0 = self.0.saturating_add(1);
        self.0 > POLL_BUDGET
    }
}

fn agenda(e: &StreamEngine) -> Vec<String> {
    let mut v = Vec::new();
    e.for_each_activation(|r, s, b| v.push(format!("{s} {r} {b:?}")));
    v
}

/// A fresh engine with the rule base loaded and reset.
pub fn new_engine() -> Box<StreamEngine> {
    new_engine_with(RULE_BASE)
}

pub fn new_engine_with(rules: &str) -> Box<StreamEngine> {
    let mut e = Box::new(StreamEngine::with_storage(StreamStorage::new()));
    setup(&mut e, rules);
    e
}

fn setup(e: &mut StreamEngine, rules: &str) {
    let h = &mut Quiet(0);
    if let Err(err) = e.load_str(h, "rules", rules) {
        panic!("rule base does not load: {err}");
    }
    let _ = e.reset(h);
}

fn nth_fact(e: &StreamEngine, n: u8) -> Option<FactId> {
    let count = e.facts().count();
    if count == 0 {
        return None;
    }
    e.facts().nth(n as usize % count)
}

/// Applies one command; panics when an invariant breaks or a failed assert left a
/// trace. Returns what happened, for debugging.
pub fn apply(e: &mut StreamEngine, cmd: &Cmd) -> String {
    apply_with(e, cmd, RULE_BASE)
}

/// `apply` with the rule base `clear` reloads.
pub fn apply_with(e: &mut StreamEngine, cmd: &Cmd, rules: &str) -> String {
    let h = &mut Quiet(0);
    let outcome = match cmd {
        Cmd::AssertItem { id, state, tags } => {
            let tags: Vec<&str> = tags.iter().map(|&t| TAGS[t as usize]).collect();
            let text = format!(
                "(item (id {id}) (state {}) (tags {}))",
                STATES[*state as usize],
                tags.join(" ")
            );
            assert_leaving_no_trace(e, &text)
        }
        Cmd::AssertLink { from, to } => {
            assert_leaving_no_trace(e, &format!("(link (from {from}) (to {to}))"))
        }
        Cmd::AssertTick(v) => {
            let v: Vec<String> = v.iter().map(|x| x.to_string()).collect();
            assert_leaving_no_trace(e, &format!("(tick {})", v.join(" ")))
        }
        Cmd::Retract(n) => match nth_fact(e, *n) {
            Some(id) => format!("retract {:?}", e.retract(h, id)),
            None => "retract: no facts".into(),
        },
        Cmd::Modify { nth, state, id } => match nth_fact(e, *nth) {
            Some(f) => {
                let text = if *state == 3 {
                    format!("(modify {} (id {id}))", f.0)
                } else {
                    format!("(modify {} (state {}))", f.0, STATES[*state as usize])
                };
                let facts: Vec<FactId> = e.facts().collect();
                let acts = agenda(e);
                let owed = e.owes();
                let r = e.eval_str(h, &text);
                if let Err(ref err) = r {
                    if matches!(err.kind(), agent_core::EvalErrorKind::Capacity(_)) {
                        // a failed modify is undone: same facts, same agenda order
                        assert_eq!(e.facts().collect::<Vec<_>>(), facts, "{text}: {err}");
                        same_agenda_but_owed(&acts, &agenda(e), owed, &text);
                    }
                }
                format!("{text}: {r:?}")
            }
            None => "modify: no facts".into(),
        },
        Cmd::Run(n) => format!("run {n}: {:?}", e.run(h, Some(*n as u32))),
        Cmd::Reset => format!("reset: {:?}", e.reset(h)),
        Cmd::LoadExtra(k) => {
            let text = EXTRA_RULES[*k as usize % EXTRA_RULES.len()];
            format!("load: {:?}", e.load_str(h, "extra", text))
        }
        Cmd::Undefrule(k) => {
            let text = format!("(undefrule extra-{})", k % 3);
            format!("{text}: {:?}", e.eval_str(h, &text))
        }
        Cmd::Clear => {
            let r = e.clear(h);
            setup(e, rules);
            format!("clear: {r:?}")
        }
    };
    if let Err(v) = e.check_invariants() {
        panic!("after {cmd:?} ({outcome}): {v}");
    }
    outcome
}

/// After a failed assert or modify: the same activations in the same order
/// (exhaustion.rs `failed_assert_keeps_the_agenda_order_of_blocked_not_rules`). With
/// matches owed before, the operation built those first (they were due, and stay when
/// it then runs out): the old activations keep their order, owed ones may be added.
fn same_agenda_but_owed(before: &[String], after: &[String], owed: bool, what: &str) {
    if !owed {
        assert_eq!(after, before, "{what}");
        return;
    }
    let mut rest = after.iter();
    for a in before {
        assert!(rest.any(|b| b == a), "{what}: lost or moved {a}: {after:?}");
    }
}

/// Asserts; a failure other than a duplicate must leave facts and agenda as they were
/// (but for owed matches it built first, see `same_agenda_but_owed`).
fn assert_leaving_no_trace(e: &mut StreamEngine, text: &str) -> String {
    let h = &mut Quiet(0);
    let facts: Vec<FactId> = e.facts().collect();
    let acts = agenda(e);
    let mut usage = e.usage();
    let owed = e.owes();
    let r = e.assert_str(h, text);
    match r {
        Ok(_) | Err(EngineError::Duplicate) => {}
        Err(ref err) => {
            assert_eq!(e.facts().collect::<Vec<_>>(), facts, "{text}: {err}");
            same_agenda_but_owed(&acts, &agenda(e), owed, &format!("{text}: {err}"));
            let mut now = e.usage();
            if owed {
                // the owed matches built hold tokens
                (usage.tokens, now.tokens) = (0, 0);
            }
            assert_eq!(now, usage, "{text}: {err}");
        }
    }
    format!("{text}: {r:?}")
}

/// Runs a whole stream on a fresh engine.
pub fn run_stream(data: &[u8]) {
    run_stream_with(RULE_BASE, data)
}

pub fn run_stream_with(rules: &str, data: &[u8]) {
    let mut e = new_engine_with(rules);
    for cmd in decode(data).iter().take(400) {
        apply_with(&mut e, cmd, rules);
    }
}
