//! The rule base's behaviour scenarios (`rules/tests/*.clp`: a belief state and a light in,
//! the next belief and chosen action checked by PASS/FAIL lines) run in our engine and in
//! real CLIPS 6.30 through `rules/tests/run.sh`.

use std::path::Path;
use std::process::Command;

fn run_scenarios(engine: &str) -> (bool, String) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../rules/tests/run.sh");
    let out = Command::new("sh")
        .arg(&script)
        .env("CLIPS", engine)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", script.display()));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    (out.status.success(), text)
}

fn passed_count(report: &str) -> usize {
    report
        .lines()
        .find_map(|l| l.strip_prefix("total passed: "))
        .and_then(|n| n.trim().parse().ok())
        .unwrap_or(0)
}

#[test]
fn scenarios_pass_in_our_engine() {
    let engine = format!("{} clips", env!("CARGO_BIN_EXE_robotino-agent"));
    let (ok, report) = run_scenarios(&engine);
    assert!(ok, "scenario failures in our engine:\n{report}");
    assert!(passed_count(&report) >= 50, "too few checks ran:\n{report}");
}

#[test]
fn scenarios_pass_in_real_clips() {
    let probe = Command::new("sh").args(["-c", "command -v clips"]).output();
    assert!(
        probe.map(|o| o.status.success()).unwrap_or(false),
        "real CLIPS is required: apt-get install -y clips"
    );
    let (ok, report) = run_scenarios("clips");
    assert!(ok, "scenario failures in real CLIPS:\n{report}");
    assert_eq!(
        passed_count(&report),
        passed_count(&run_scenarios(&format!("{} clips", env!("CARGO_BIN_EXE_robotino-agent"))).1),
        "both engines must run the same number of checks"
    );
}
