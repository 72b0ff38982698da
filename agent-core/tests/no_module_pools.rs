//! An engine that names no module pools (`modules`, `module_ports` and `focus_stack` of
//! zero entries, as engines sized for the agent image can) is the single MAIN module:
//! it runs a program of auto-focus-free rules as an engine with roomy pools does, with
//! the `modules` feature on or off. (Stage 3 of test-all.sh once panicked here: the
//! module side arrays were indexed past their end.)
#![cfg(feature = "parser")]
#![allow(dead_code)]

use agent_core::{Host, Pool};

#[macro_use]
mod engine_macro;

#[derive(Default)]
struct Capture {
    out: String,
}
impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.out.push_str(text);
    }
}

const CONSTRUCTS: &str = r#"
(deftemplate item (slot n))
(deffacts start (item (n 1)) (item (n 2)) (item (n 3)))
(deffunction double (?x) (* 2 ?x))
(defrule high (declare (salience 10)) (item (n ?n&:(> ?n 2)))
  => (printout t "high " (double ?n) crlf))
(defrule each (item (n ?n)) (not (done ?n))
  => (assert (done ?n)) (printout t "each " ?n crlf))
"#;

/// Commands every build has.
const COMMANDS: &[&str] = &[
    "(watch rules)",
    "(reset)",
    "(run)",
    "(facts)",
    "(list-defrules)",
    "(assert (item (n 7)))",
    "(run)",
    "(reset)",
    "(run 2)",
];

/// The module commands, on an engine with the feature.
#[cfg(feature = "modules")]
const MODULE_COMMANDS: &[&str] = &[
    "(watch focus)",
    "(reset)",
    "(printout t (get-focus-stack) \" \" (get-current-module) crlf)",
    "(run 1)",
    "(focus MAIN)",
    "(printout t (get-focus-stack) crlf)",
    "(pop-focus)",
    "(printout t (get-focus-stack) crlf)",
    "(run)",
    "(ppdefmodule MAIN)",
    "(list-defmodules)",
    "(clear-focus-stack)",
    "(reset)",
    "(printout t (get-focus-stack) crlf)",
];
#[cfg(not(feature = "modules"))]
const MODULE_COMMANDS: &[&str] = &[];

fn run_program<S: agent_core::Storage>(e: &mut agent_core::Engine<S>) -> String {
    let mut h = Capture::default();
    e.load_str(&mut h, "t", CONSTRUCTS)
        .expect("constructs load");
    for c in COMMANDS.iter().chain(MODULE_COMMANDS) {
        h.out.push_str(&format!("> {c}\n"));
        assert!(e.exec_command(&mut h, c, "t"), "{c}: {}", h.out);
    }
    if let Err(v) = e.check_invariants() {
        panic!("{v}");
    }
    h.out
}

#[test]
fn an_engine_without_module_pools_runs_as_main_alone() {
    let mut bare = engine!(modules = 0, module_ports = 0, focus_stack = 0);
    let mut roomy = engine!();
    let out = run_program(&mut *bare);
    assert_eq!(out, run_program(&mut *roomy));
    // the salience order, the `not` and the deffunction all held
    let first = out.find("FIRE    1 high: f-3").expect(&out);
    assert!(out[first..].contains("high 6\n"), "{out}");
    assert!(out.contains("FIRE    2 each: f-3,*"), "{out}");
    assert!(out.contains("each 1\n"), "{out}");
    assert!(out.contains("high 14\n"), "{out}");
    assert!(!out.contains("out of"), "{out}");
}

/// Defining a module needs an entry in the modules pool: with none, even MAIN's
/// redefinition is a capacity error, and the engine stays MAIN alone.
#[cfg(feature = "modules")]
#[test]
fn a_defmodule_without_module_pools_is_a_capacity_error() {
    let mut e = engine!(modules = 0, module_ports = 0, focus_stack = 0);
    let h = &mut Capture::default();
    for text in ["(defmodule A)", "(defmodule MAIN (export ?ALL))"] {
        let err = e.load_str(h, "t", text).expect_err(text);
        assert_eq!(err.capacity.map(|c| c.pool), Some(Pool::Modules), "{err}");
    }
    // the focus stack has MAIN's implicit entry only
    e.load_str(h, "t", "(defrule r =>)").unwrap();
    e.reset(h).unwrap();
    assert_eq!(e.run(h, None).unwrap(), 1);
    h.out.clear();
    e.exec_command(
        h,
        "(printout t (get-defmodule-list) (get-focus-stack) crlf)",
        "t",
    );
    assert!(h.out.starts_with("(MAIN)("), "{}", h.out);
    if let Err(v) = e.check_invariants() {
        panic!("{v}");
    }
}
