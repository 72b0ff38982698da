//! Bad input (issue 8): rule files with each kind of syntax and semantic error are
//! rejected with the line and column of the offending token and leave the engine
//! exactly as it was — templates, rules, functions, globals, facts, agenda and the
//! usage of every append-only pool — so it goes on exactly like a twin engine that
//! never saw the bad file. Run-time errors (a runaway recursion, an error inside a
//! deffunction) name the limit or pool and the function and rule, and the engine
//! keeps working.
//!
//! The CLI side of the same errors (CLIPS's messages, `--> FILE:LINE:COL`) is
//! `tests/clips-errors` with `host-shim/tests/parse_errors.rs`.
// without `parser` the tests that evaluate builtins are left out (only `parser` links
// their code: `builtins::BUILTINS`), and helpers only they use are unused
#![cfg_attr(
    not(feature = "parser"),
    allow(dead_code, unused_imports, unused_macros)
)]

use agent_core::{DefaultEngine, EvalErrorKind, Host, LoadError, SmallEngine};

/// Collects everything the engine writes.
#[derive(Default)]
struct Capture(String);

impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

/// The program every case starts from: typed and restricted slots, a required slot,
/// a deffunction, a global, deffacts and rules, so each kind of error has something
/// to get wrong.
const BASE: &str = "\
(defglobal ?*limit* = 3)
(deftemplate robot
  (slot name (type SYMBOL) (default ?NONE))
  (slot speed (type INTEGER) (default 0))
  (slot light (allowed-symbols green yellow red) (default green))
  (multislot load))
(deffunction faster (?s) (+ ?s 1))
(deffacts team
  (robot (name r1))
  (robot (name r2) (speed 2)))
(defrule accelerate
  ?r <- (robot (name ?n) (speed ?s&:(< ?s ?*limit*)))
  =>
  (modify ?r (speed (faster ?s))))
(defrule report
  (robot (name ?n) (speed ?s&:(>= ?s ?*limit*)))
  =>
  (printout t ?n \" at \" ?s crlf))
";

/// (what is wrong, the bad file, line, column, text the "expected" part contains)
const CASES: &[(&str, &str, u32, u32, &str)] = &[
    // syntax
    (
        "unclosed construct",
        "(defrule stop\n  (robot (name ?n))\n  =>\n  (printout t ?n crlf)\n",
        5,
        1,
        "')'",
    ),
    (
        "unterminated string",
        "(defrule shout\n  (robot)\n  =>\n  (printout t \"hello crlf))\n",
        4,
        15,
        "closing '\"'",
    ),
    (
        "missing =>",
        // the second CE is a pattern too, so `)` is the error (an action there, as
        // `(printout t ?n crlf)`, would be an ordered pattern whose implied template
        // stays, as in CLIPS: see differential program 663)
        "(defrule no-arrow\n  (robot (name ?n))\n  (robot (speed ?s)))\n",
        3,
        21,
        "'=>'",
    ),
    (
        "bad slot attribute",
        "(deftemplate box\n  (slot size (colour red)))\n",
        2,
        15,
        "slot attribute",
    ),
    (
        "nesting deeper than the reader follows",
        // 250 nested `~` in one constraint
        concat!(
            "(defrule deep\n  (robot (light ",
            "~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~",
            "red))\n  =>)\n"
        ),
        // the pattern CE is one level, the 200th `~` the first one too many
        2,
        216,
        "at most 200 levels of nesting",
    ),
    (
        "a command where a construct belongs",
        "; robots to start with\n(assert (robot (name r9)))\n",
        2,
        1,
        "a construct",
    ),
    // unknown template or slot
    (
        "unknown template",
        "(defrule lost\n  (robto (name ?n))\n  =>)\n",
        2,
        4,
        "deftemplate name",
    ),
    (
        "unknown slot in a pattern",
        "(defrule lost\n  (robot (nmae ?n))\n  =>)\n",
        2,
        11,
        "slot of the template",
    ),
    (
        "unknown slot in an assert",
        "(defrule spawn\n  (robot (name r1))\n  =>\n  (assert (robot (name r3) (colour red))))\n",
        4,
        29,
        "slot of the template",
    ),
    (
        "unknown slot in a modify",
        "(defrule stop\n  ?r <- (robot)\n  =>\n  (modify ?r (sped 0)))\n",
        4,
        15,
        "slot of the template",
    ),
    (
        "unknown slot in deffacts",
        "(deffacts more\n  (robot (name r3) (colour red)))\n",
        2,
        21,
        "slot of the template",
    ),
    // wrong type
    (
        "wrong type in an assert",
        "(defrule spawn\n  (robot (name r1))\n  =>\n  (assert (robot (name r3) (speed fast))))\n",
        4,
        35,
        "slot's type",
    ),
    (
        "wrong type in a pattern",
        "(defrule slow\n  (robot (speed slow))\n  =>)\n",
        2,
        17,
        "slot's type",
    ),
    (
        "wrong type of a default",
        "(deftemplate box\n  (slot size (type INTEGER) (default 1.5)))\n",
        2,
        38,
        "slot's type",
    ),
    (
        "wrong type of a literal argument",
        "(deffunction slower (?s)\n  (- ?s one))\n",
        2,
        9,
        "type integer or float",
    ),
    // value outside allowed-values
    (
        "value outside allowed-values in a modify",
        "(defrule paint\n  ?r <- (robot)\n  =>\n  (modify ?r (light blue)))\n",
        4,
        21,
        "allowed values",
    ),
    (
        "value outside allowed-values in a pattern",
        "(defrule blue\n  (robot (light blue))\n  =>)\n",
        2,
        17,
        "allowed values",
    ),
    (
        "default outside allowed-values",
        "(deftemplate lamp\n  (slot color (allowed-symbols on off) (default dim)))\n",
        2,
        49,
        "allowed values",
    ),
    // unbound variables, ?x and $?x
    (
        "unbound variable on the RHS",
        "(defrule tell\n  (robot (name ?n))\n  =>\n  (printout t ?m crlf))\n",
        4,
        15,
        "bound variable",
    ),
    (
        "variable bound only inside not",
        "(defrule alone\n  (not (robot (name ?n)))\n  =>\n  (printout t ?n crlf))\n",
        4,
        15,
        "bound variable",
    ),
    (
        "single and multifield use of one variable",
        "(defrule mixed\n  (robot (load $?l))\n  (robot (name ?l))\n  =>)\n",
        3,
        16,
        "not both",
    ),
    // arity and unknown functions
    (
        "wrong arity of a builtin",
        "(defrule half\n  (robot (speed ?s))\n  =>\n  (printout t (div ?s) crlf))\n",
        4,
        16,
        "argument",
    ),
    (
        "wrong arity of a deffunction",
        "(defrule boost\n  (robot (speed ?s))\n  =>\n  (printout t (faster ?s 2) crlf))\n",
        4,
        16,
        "number of arguments",
    ),
    (
        "unknown function",
        "(defrule beep\n  (robot)\n  =>\n  (beep 3))\n",
        4,
        4,
        "known function",
    ),
    (
        "missing required slot",
        "(defrule spawn\n  (robot (name r1))\n  =>\n  (assert (robot (speed 1))))\n",
        4,
        12,
        "(default ?NONE)",
    ),
    // duplicates
    (
        "redefinition of a deftemplate in use",
        "(deftemplate robot\n  (slot id))\n",
        1,
        14,
        "not in use",
    ),
    (
        "duplicate slot",
        "(deftemplate box\n  (slot size)\n  (slot size))\n",
        3,
        9,
        "not used before",
    ),
    (
        "duplicate parameter",
        "(deffunction add (?a ?a)\n  (+ ?a ?a))\n",
        1,
        22,
        "not used twice",
    ),
    (
        "deffunction named like a builtin",
        "(deffunction max (?a ?b)\n  ?a)\n",
        1,
        14,
        "not a builtin",
    ),
    (
        "slot given twice",
        "(deffacts more\n  (robot (name r3) (name r4)))\n",
        2,
        21,
        "not given twice",
    ),
];

/// Everything observable about the engine's constructs and state.
#[derive(Debug, PartialEq)]
struct Snapshot {
    usage: agent_core::Usage,
    counts: (usize, usize),
    listings: String,
}

fn snapshot(e: &mut SmallEngine) -> Snapshot {
    let mut h = Capture::default();
    for command in [
        "(facts)",
        "(agenda)",
        "(list-deftemplates)",
        "(list-defrules)",
        "(list-deffunctions)",
        "(printout t ?*limit* crlf)",
        "(printout t (faster 1) crlf)",
    ] {
        e.exec_command(&mut h, command, "snapshot");
    }
    Snapshot {
        usage: e.usage(),
        counts: e.counts(),
        listings: h.0,
    }
}

/// The base program loaded, reset and one rule fired, so facts, an agenda and
/// partial matches exist when the bad file comes.
fn started() -> Box<SmallEngine> {
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Capture::default();
    e.load_str(h, "base.clp", BASE)
        .expect("the base program loads");
    e.reset(h).expect("reset");
    assert_eq!(e.run(h, Some(1)).expect("run"), 1);
    assert!(e.counts().1 > 0, "activations are pending");
    e
}

/// `after` less the implied templates it has and `before` lacks: as in CLIPS, a
/// bad construct leaves the implied deftemplates of the unknown relations it read
/// (one slot each, their names' symbols; differential program 219), and nothing else.
fn without_implied_templates(after: &Snapshot, before: &Snapshot) -> Snapshot {
    let known: Vec<&str> = before.listings.lines().collect();
    let mut listings = String::new();
    let mut implied = 0;
    let mut in_templates = false;
    for line in after.listings.lines() {
        if line == "initial-fact" {
            in_templates = true;
        } else if line.starts_with("For a total of") {
            in_templates = false;
        }
        if in_templates && !known.contains(&line) {
            implied += 1;
            continue;
        }
        let line = if line.ends_with(" deftemplates.") && implied > 0 {
            match line
                .trim_start_matches("For a total of ")
                .trim_end_matches(" deftemplates.")
                .parse::<usize>()
            {
                Ok(n) => format!("For a total of {} deftemplates.", n - implied),
                Err(_) => line.to_string(),
            }
        } else {
            line.to_string()
        };
        listings.push_str(&line);
        listings.push('\n');
    }
    // (counted from the pools: builds without the listing commands list nothing)
    let mut usage = after.usage;
    let k = usage.templates.saturating_sub(before.usage.templates);
    if k > 0
        && (implied == 0 || implied as agent_core::Ix == k)
        && usage.slot_defs == before.usage.slot_defs + k
        && usage.symbols >= before.usage.symbols + k
    {
        usage.templates -= k;
        usage.slot_defs -= k;
        usage.symbols = before.usage.symbols;
    }
    Snapshot {
        usage,
        counts: after.counts,
        listings,
    }
}

fn check_case(what: &str, bad: &str, line: u32, col: u32, expected: &str) -> Result<(), String> {
    let mut e = started();
    let mut twin = started();
    let before = snapshot(&mut e);
    let h = &mut Capture::default();
    let err: LoadError = match e.load_str(h, "bad.clp", bad) {
        Ok(n) => return Err(format!("{what}: loaded {n} constructs, no error")),
        Err(err) => err,
    };
    if (err.line, err.col) != (line, col)
        || !err
            .expected
            .to_lowercase()
            .contains(&expected.to_lowercase())
    {
        return Err(format!(
            "{what}: got {}:{}: expected {}",
            err.line, err.col, err.expected
        ));
    }
    if err.capacity.is_some() {
        return Err(format!("{what}: reported as a full pool: {err}"));
    }
    let after = snapshot(&mut e);
    if without_implied_templates(&after, &before) != before {
        return Err(format!(
            "{what}: the engine changed\n before {before:?}\n after  {after:?}"
        ));
    }
    // and it goes on exactly as an engine that never saw the bad file
    let (mut out, mut twin_out) = (Capture::default(), Capture::default());
    let fired = e.run(&mut out, None).map_err(|x| format!("{what}: {x}"))?;
    let twin_fired = twin
        .run(&mut twin_out, None)
        .map_err(|x| format!("{what}: {x}"))?;
    let (now, twin_now) = (snapshot(&mut e), snapshot(&mut twin));
    if (fired, &out.0) != (twin_fired, &twin_out.0)
        || without_implied_templates(&now, &twin_now) != twin_now
    {
        return Err(format!(
            "{what}: behaves differently from its twin afterwards ({fired} vs {twin_fired} rules fired)"
        ));
    }
    Ok(())
}

#[test]
fn every_kind_of_bad_file_is_rejected_and_leaves_nothing_behind() {
    let problems: Vec<String> = CASES
        .iter()
        .filter_map(|&(what, bad, line, col, expected)| {
            check_case(what, bad, line, col, expected).err()
        })
        .collect();
    assert!(
        problems.is_empty(),
        "{} of {} cases failed:\n{}",
        problems.len(),
        CASES.len(),
        problems.join("\n")
    );
}

#[cfg(feature = "parser")]
#[test]
fn the_base_program_runs_to_the_end() {
    let mut e = started();
    let h = &mut Capture::default();
    e.run(h, None).expect("run");
    assert!(
        h.0.contains("r1 at 3") && h.0.contains("r2 at 3"),
        "{}",
        h.0
    );
}

#[cfg(feature = "parser")]
#[test]
fn a_redefinition_clips_accepts_replaces_the_construct() {
    let mut e = started();
    let h = &mut Capture::default();
    // nothing uses `box`: CLIPS replaces it, and so do we
    e.load_str(h, "a.clp", "(deftemplate box (slot size))")
        .expect("first definition");
    e.load_str(h, "b.clp", "(deftemplate box (slot width) (slot height))")
        .expect("a deftemplate nothing uses may be redefined");
    e.assert_str(h, "(box (width 2) (height 3))")
        .expect("the new slots are in force");
    assert!(e.assert_str(h, "(box (size 1))").is_err());
    // now `box` has a fact: redefining it is refused and changes nothing
    let before = snapshot(&mut e);
    let err = e
        .load_str(h, "c.clp", "(deftemplate box (slot size))")
        .unwrap_err();
    assert_eq!((err.line, err.col), (1, 14));
    assert_eq!(snapshot(&mut e), before);
    // rules and deffunctions are replaced, as in CLIPS
    e.load_str(h, "d.clp", "(deffunction faster (?s) (+ ?s 2))")
        .expect("deffunction redefinition");
    assert_eq!(
        e.eval_str(h, "(faster 1)").expect("eval"),
        agent_core::Value::Int(3)
    );
}

/// A deffunction that recurses forever stops at the evaluation depth limit, with an
/// error naming the limit and the function (and the rule it ran in); no crash, and the
/// engine works on.
#[cfg(feature = "parser")]
#[test]
fn runaway_recursion_names_the_depth_limit_and_the_function() {
    // the default engine's evaluation stack outlasts the depth limit; it is big, so
    // it lives on a thread with room for it
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(runaway_recursion)
        .expect("thread")
        .join()
        .expect("no panic");
}

fn runaway_recursion() {
    let mut e = Box::new(DefaultEngine::new());
    let h = &mut Capture::default();
    e.load_str(h, "base.clp", BASE)
        .expect("the base program loads");
    e.reset(h).expect("reset");
    let h = &mut Capture::default();
    e.load_str(
        h,
        "forever.clp",
        "(deffunction forever (?n) (+ 1 (forever (+ ?n 1))))\n\
         (deftemplate go (slot n))\n\
         (defrule spin (go (n ?n)) => (printout t (forever ?n) crlf))\n",
    )
    .expect("loads: the recursion is only a run-time error");
    let err = e.eval_str(h, "(forever 1)").unwrap_err();
    assert_eq!(err.kind(), EvalErrorKind::TooDeep { limit: 200 });
    assert!(
        h.0.contains("evaluation depth limit (200)")
            && h.0
                .contains("[PRCCODE4] Execution halted during the actions of deffunction forever."),
        "{}",
        h.0
    );
    // from a rule: the rule is named too
    h.0.clear();
    let before = e.usage();
    e.assert_str(h, "(go (n 1))").expect("assert");
    e.run(h, None)
        .expect("a rule's run-time error does not fail the run");
    assert!(
        h.0.contains("deffunction forever.")
            && h.0
                .contains("[PRCCODE4] Execution halted during the actions of defrule spin."),
        "{}",
        h.0
    );
    assert_eq!(
        h.0.matches("deffunction forever").count(),
        1,
        "named once, not once per frame: {}",
        h.0
    );
    // as in CLIPS the error halted the run; the next run goes on with the others
    assert!(!h.0.contains(" at 3"), "{}", h.0);
    h.0.clear();
    e.run(h, None).expect("run");
    assert!(
        h.0.contains("r1 at 3") && h.0.contains("r2 at 3"),
        "{}",
        h.0
    );
    assert_eq!(e.usage().exprs, before.exprs);
    assert_eq!(
        e.eval_str(h, "(faster 41)").expect("still evaluates"),
        agent_core::Value::Int(42)
    );
}

/// Recursion that fills the evaluation stack before the depth limit names the pool.
#[cfg(feature = "parser")]
#[test]
fn recursion_that_fills_the_evaluation_stack_names_the_pool() {
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Capture::default();
    // each call keeps 20 arguments on the stack: 128 values last 6 calls
    e.load_str(
        h,
        "wide.clp",
        "(deffunction wide (?a ?b ?c ?d ?e ?f ?g ?h ?i ?j ?k ?l ?m ?n ?o ?p ?q ?r ?s ?t)\n\
         (wide ?a ?b ?c ?d ?e ?f ?g ?h ?i ?j ?k ?l ?m ?n ?o ?p ?q ?r ?s ?t))\n",
    )
    .expect("loads");
    let err = e
        .eval_str(
            h,
            "(wide 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20)",
        )
        .unwrap_err();
    match err.kind() {
        EvalErrorKind::Capacity(c) => {
            assert_eq!(c.pool, agent_core::Pool::EvalStack, "{c}");
        }
        other => panic!("expected the evaluation stack to run out, got {other:?}"),
    }
    // at the prompt the report names the pool and its capacity
    h.0.clear();
    e.exec_command(
        h,
        "(wide 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20)",
        "cmd",
    );
    assert!(
        h.0.contains("evaluation stack") && h.0.contains("128"),
        "{}",
        h.0
    );
    assert_eq!(
        e.eval_str(h, "(+ 1 2)").expect("still evaluates"),
        agent_core::Value::Int(3)
    );
}

/// A host with one file, for `(load ...)`.
struct OneFile {
    name: &'static str,
    text: &'static str,
    out: String,
}

impl Host for OneFile {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.out.push_str(text);
    }
    fn read_file(&mut self, path: &str, buf: &mut [u8]) -> Result<usize, agent_core::HostIoError> {
        if path != self.name || self.text.len() > buf.len() {
            return Err(agent_core::HostIoError::NotFound);
        }
        buf[..self.text.len()].copy_from_slice(self.text.as_bytes());
        Ok(self.text.len())
    }
}

/// `(load FILE)` as in CLIPS: every bad construct is reported with the file, line and
/// column, leaves nothing behind, and loading goes on with the next construct.
#[cfg(feature = "parser")]
#[test]
fn load_reports_every_bad_construct_and_goes_on() {
    let mut e = Box::new(SmallEngine::new());
    let h = &mut OneFile {
        name: "robots.clp",
        text: "(deftemplate robot (slot speed (type INTEGER)))\n\
               (defrule ok => )\n\
               (defrule bad\n  (robot (speed fast))\n  =>)\n\
               (defrule after => )\n\
               (defrule bad2 (robot (sped 1)) =>)\n\
               (deffunction twice (?x) (* 2 ?x))\n",
        out: String::new(),
    };
    e.exec_command(h, "(load robots.clp)", "cmd");
    assert!(
        h.out
            .contains("--> robots.clp:4:17: expected a value of the slot's type")
            && h.out
                .contains("--> robots.clp:7:23: expected a slot of the template"),
        "{}",
        h.out
    );
    assert!(h.out.trim_end().ends_with("FALSE"), "{}", h.out);
    h.out.clear();
    e.exec_command(h, "(list-defrules)", "cmd");
    assert_eq!(h.out, "ok\nafter\nFor a total of 2 defrules.\n");
    assert_eq!(
        e.eval_str(h, "(twice 21)")
            .expect("the construct after the errors loaded"),
        agent_core::Value::Int(42)
    );
}

/// Our geometry builtins go beyond CLIPS, so a CLIPS program may define a deffunction
/// of the same name (`rules/clips/stubs.clp` does); CLIPS's own functions stay
/// reserved.
#[test]
fn a_deffunction_may_take_the_name_of_an_extension_but_not_of_a_clips_function() {
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Capture::default();
    e.load_str(h, "stub.clp", "(deffunction distance (?a ?b ?c ?d) 7)")
        .expect("distance is not a CLIPS function");
    assert_eq!(
        e.eval_str(h, "(distance 0 0 3 4)").expect("eval"),
        agent_core::Value::Int(7)
    );
    let err = e
        .load_str(h, "max.clp", "(deffunction max (?a ?b) ?a)")
        .unwrap_err();
    assert_eq!((err.line, err.col), (1, 14));
}
