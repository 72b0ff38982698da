//! `robotino-agent sim`: the report is deterministic per seed and describes
//! the game it played.

use std::process::Command;

fn sim(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
        .arg("sim")
        .args(args)
        .output()
        .expect("running robotino-agent sim");
    assert!(
        out.status.success(),
        "sim {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("the report is UTF-8")
}

/// The numbers of a `RESULT points .. decisions N ..` line, by key.
fn result_value(report: &str, key: &str) -> i64 {
    let line = report
        .lines()
        .find(|l| l.starts_with("RESULT"))
        .expect("a RESULT line");
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words
        .iter()
        .position(|w| *w == key)
        .expect("the key is in the RESULT line");
    let value = words.get(at + 1).expect("a value after the key");
    value.parse::<f64>().expect("a number") as i64
}

#[test]
fn the_same_seed_gives_the_same_report() {
    for strategy in ["naive", "paper", "travel"] {
        let first = sim(&["--seed", "11", "--strategy", strategy]);
        let second = sim(&["--seed", "11", "--strategy", strategy]);
        assert_eq!(first, second, "strategy {strategy}");
    }
}

#[test]
fn different_seeds_give_different_games() {
    let a = sim(&["--seed", "3"]);
    let b = sim(&["--seed", "4"]);
    let assignment = |r: &str| {
        r.lines()
            .find(|l| l.starts_with("assignment:"))
            .map(str::to_string)
    };
    assert_ne!(assignment(&a), assignment(&b));
}

#[test]
fn the_report_lists_every_decision_and_the_products() {
    let report = sim(&["--assignment", "T1,T1,T1,T1,T2,T2,T2,T3,T3,T3"]);
    assert!(
        report.contains("assignment: M1 T1, M2 T1, M3 T1, M4 T1, M5 T2"),
        "{report}"
    );
    let decisions = result_value(&report, "decisions");
    assert!(
        decisions > 10,
        "a whole game takes many decisions: {report}"
    );
    // One table row per decision: rows start with the decision number.
    let rows = report
        .lines()
        .filter(|l| {
            l.split_whitespace()
                .next()
                .and_then(|w| w.parse::<i64>().ok())
                .is_some()
        })
        .count() as i64;
    assert_eq!(rows, decisions, "{report}");
    let points = result_value(&report, "points");
    let (s2, p, delivered) = (
        result_value(&report, "s2"),
        result_value(&report, "p"),
        result_value(&report, "delivered"),
    );
    assert!(
        p > 0,
        "the paper's agent produces P on the sorted assignment: {report}"
    );
    // Scoring rule from the fact interface (no recycling, one active gate).
    assert!(points >= 4 * s2 + 12 * p, "{report}");
    assert!(delivered <= p);
    assert!(report.contains(&format!("points: {points}")));
    // Every type the agent learned must be the true one on this assignment.
    assert!(!report.contains("WRONG"), "{report}");
}

#[test]
fn tracing_adds_the_rule_firings_but_not_other_changes() {
    let plain = sim(&["--seed", "5"]);
    let traced = sim(&["--seed", "5", "--trace"]);
    let fires = traced.lines().filter(|l| l.starts_with("FIRE")).count();
    assert!(fires > 100, "a traced game shows its rule firings");
    let without_fires: Vec<&str> = traced.lines().filter(|l| !l.starts_with("FIRE")).collect();
    assert_eq!(without_fires, plain.lines().collect::<Vec<_>>());
}

#[test]
fn a_bad_assignment_is_an_error_with_context() {
    let out = Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
        .args(["sim", "--assignment", "T1,T2,T9"])
        .output()
        .expect("running robotino-agent sim");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("10 machine types"), "{err}");
}
