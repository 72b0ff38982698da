//! Same decisions as real CLIPS: seeded games played by real CLIPS 6.30
//! (`clips`, with rules/clips/stubs.clp for the host functions) and by our
//! engine (`robotino-agent sim --trace`) must fire the same rules on the same
//! facts, in the same order, and end with the same result line.
//!
//! Real CLIPS is required: without it this test fails with an install hint.

use std::path::{Path, PathBuf};
use std::process::Command;

use rules::setup::GameSetup;
use rules::Strategy;

/// Seconds one CLIPS game may take (they take well under one).
const CLIPS_TIMEOUT_S: &str = "60";

fn rules_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rules")
}

fn scratch_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("robotino-parity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temp dir is writable");
    dir
}

/// Fails (not skips) when real CLIPS is missing.
fn require_clips() {
    let probe = Command::new("clips")
        .arg("-f2")
        .arg("/dev/null")
        .stdin(std::process::Stdio::null())
        .output();
    if probe.is_err() {
        panic!(
            "real CLIPS 6.30 (`clips` on PATH) is required for the parity test: install it \
             (e.g. `apt-get install clips`, or build CLIPS 6.30 from source and put `clips` on PATH)"
        );
    }
}

/// One game of the parity set: a seed, a strategy, and whether to draw
/// processing times and faults from the seed too.
#[derive(Clone, Copy, Debug)]
struct Case {
    seed: u64,
    strategy: Strategy,
    /// `--seeded-times --faults 3`: exercises the failure handling.
    hard: bool,
}

fn cases() -> Vec<Case> {
    (1..=24u64)
        .map(|seed| Case {
            seed,
            strategy: Strategy::ALL[(seed % 3) as usize],
            hard: seed % 4 == 0,
        })
        .collect()
}

fn setup_of(case: Case) -> GameSetup {
    let mut setup = GameSetup::for_seed(case.seed);
    if case.hard {
        setup = setup
            .with_seeded_times(case.seed)
            .with_seeded_faults(case.seed, 3, 40);
    }
    setup
}

/// The FIRE lines and the RESULT line of a run's output.
fn trace_and_result(output: &str) -> (Vec<String>, Option<String>) {
    let fires = output
        .lines()
        .filter(|l| l.starts_with("FIRE"))
        .map(|l| l.trim_end().to_string())
        .collect();
    let result = output
        .lines()
        .find(|l| l.starts_with("RESULT"))
        .map(|l| l.trim_end().to_string());
    (fires, result)
}

fn play_in_clips(case: Case, dir: &Path) -> String {
    let rules = rules_dir();
    let setup_path = dir.join(format!("setup-{}.clp", case.seed));
    let mut setup_text = String::new();
    setup_of(case)
        .write_clips(&mut setup_text)
        .expect("formatting into a String");
    std::fs::write(&setup_path, setup_text).expect("writing the setup");
    let mut batch = String::new();
    let load = |batch: &mut String, path: &Path| {
        batch.push_str(&format!("(load* \"{}\")\n", path.display()))
    };
    load(&mut batch, &rules.join(rules::CLIPS_STUBS.name));
    for file in rules::game_files(case.strategy) {
        load(&mut batch, &rules.join(file.name));
    }
    load(&mut batch, &rules.join("clips/report.clp"));
    load(&mut batch, &setup_path);
    batch.push_str("(reset)\n(watch rules)\n(run)\n(report-game)\n(exit)\n");
    let batch_path = dir.join(format!("play-{}.clp", case.seed));
    std::fs::write(&batch_path, batch).expect("writing the batch file");
    let out = Command::new("timeout")
        .args([CLIPS_TIMEOUT_S, "clips", "-f2"])
        .arg(&batch_path)
        .output()
        .expect("running clips under timeout");
    assert!(
        out.status.success(),
        "clips failed on {case:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn play_in_ours(case: Case) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_robotino-agent"));
    cmd.args([
        "sim",
        "--trace",
        "--seed",
        &case.seed.to_string(),
        "--strategy",
        case.strategy.name(),
    ]);
    if case.hard {
        cmd.args(["--seeded-times", "--faults", "3"]);
    }
    let out = cmd.output().expect("running robotino-agent sim");
    assert!(
        out.status.success(),
        "robotino-agent sim failed on {case:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn seeded_games_fire_the_same_rules_as_real_clips() {
    require_clips();
    let dir = scratch_dir();
    let mut failures = Vec::new();
    for case in cases() {
        let (clips_fires, clips_result) = trace_and_result(&play_in_clips(case, &dir));
        let (our_fires, our_result) = trace_and_result(&play_in_ours(case));
        assert!(
            clips_fires.len() > 100,
            "CLIPS played no real game for {case:?}"
        );
        assert!(
            clips_result.is_some(),
            "CLIPS printed no RESULT for {case:?}"
        );
        if let Some(i) = (0..clips_fires.len().max(our_fires.len()))
            .find(|&i| clips_fires.get(i) != our_fires.get(i))
        {
            failures.push(format!(
                "{case:?}: traces differ at firing {} of {} (ours {}):\n  clips: {:?}\n  ours:  {:?}",
                i + 1,
                clips_fires.len(),
                our_fires.len(),
                clips_fires.get(i),
                our_fires.get(i)
            ));
        } else if clips_result != our_result {
            failures.push(format!(
                "{case:?}: results differ:\n  clips: {clips_result:?}\n  ours:  {our_result:?}"
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        failures.is_empty(),
        "{} of {} games differ:\n{}",
        failures.len(),
        cases().len(),
        failures.join("\n")
    );
}

#[test]
fn the_parity_set_covers_every_strategy_and_the_fault_paths() {
    let cases = cases();
    assert!(cases.len() >= 20);
    for strategy in Strategy::ALL {
        assert!(
            cases.iter().filter(|c| c.strategy == strategy).count() >= 6,
            "{strategy:?}"
        );
    }
    assert!(cases
        .iter()
        .any(|c| c.hard && setup_of(*c).faults().count() == 3));
}
