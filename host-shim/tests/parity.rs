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

/// A scratch folder of its own per call: the tests run in parallel and each removes its
/// folder when done.
fn scratch_dir() -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("robotino-parity-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temp dir is writable");
    dir
}

/// Fails (not skips) when real CLIPS is missing. The probe batch ends with
/// `(exit)`: CLIPS spins at end of input otherwise.
fn require_clips(dir: &Path) {
    let probe = dir.join("probe.clp");
    std::fs::write(&probe, "(printout t \"clips-ok\" crlf)\n(exit)\n").expect("writing the probe");
    let found = Command::new("timeout")
        .args([CLIPS_TIMEOUT_S, "clips", "-f2"])
        .arg(&probe)
        .stdin(std::process::Stdio::null())
        .output()
        .map(|out| String::from_utf8_lossy(&out.stdout).contains("clips-ok"))
        .unwrap_or(false);
    if !found {
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
    /// `--fault-rate PCT`: lost pucks, failed grabs and gotos, wrong lights.
    fault_rate: u32,
}

/// Fault rates of the faulty games, in turn.
const PARITY_FAULT_RATES: [u32; 3] = [10, 20, 30];

fn cases() -> Vec<Case> {
    let clean = (1..=24u64).map(|seed| Case {
        seed,
        strategy: Strategy::ALL[(seed % 3) as usize],
        hard: seed % 4 == 0,
        fault_rate: 0,
    });
    let faulty = (25..=36u64).map(|seed| Case {
        seed,
        strategy: Strategy::ALL[(seed % 3) as usize],
        hard: false,
        fault_rate: PARITY_FAULT_RATES[(seed % 3) as usize],
    });
    clean.chain(faulty).collect()
}

fn setup_of(case: Case) -> GameSetup {
    let mut setup = GameSetup::for_seed(case.seed);
    if case.hard {
        setup = setup
            .with_seeded_times(case.seed)
            .with_seeded_faults(case.seed, 3, 40);
    }
    setup.with_fault_rate(case.fault_rate, case.seed)
}

/// Prints the decision log in the format of the game log's `decision` lines
/// (`sim --log`), so both engines' beliefs after every decision compare too.
const CLIPS_DECISION_PRINTER: &str = r#"
(deffunction parity-decisions ()
  (bind ?n (length$ (find-all-facts ((?d decision)) TRUE)))
  (loop-for-count (?i 1 ?n)
    (do-for-fact ((?d decision)) (= ?d:n ?i)
      (format t "decision %d %.1f %s %s %s %s %s %s %d %s%n"
        ?d:n ?d:time ?d:action ?d:target ?d:puck ?d:status ?d:light
        ?d:holding ?d:points (implode$ ?d:beliefs)))))
"#;

/// The `decision ...` lines of CLIPS output or of a game log.
fn decision_lines(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with("decision "))
        .map(|l| l.trim_end().to_string())
        .collect()
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
    let printer_path = dir.join("parity-decisions.clp");
    std::fs::write(&printer_path, CLIPS_DECISION_PRINTER).expect("writing the printer");
    load(&mut batch, &printer_path);
    load(&mut batch, &setup_path);
    batch.push_str("(reset)\n(watch rules)\n(run)\n(unwatch rules)\n(report-game)\n(parity-decisions)\n(exit)\n");
    let batch_path = dir.join(format!("play-{}.clp", case.seed));
    std::fs::write(&batch_path, batch).expect("writing the batch file");
    let out = Command::new("timeout")
        .args([CLIPS_TIMEOUT_S, "clips", "-f2"])
        .arg(&batch_path)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("running clips under timeout");
    assert!(
        out.status.success(),
        "clips failed on {case:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Our run's output and its game log.
fn play_in_ours(case: Case, dir: &Path) -> (String, String) {
    let log = dir.join(format!("ours-{}.log", case.seed));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_robotino-agent"));
    cmd.args([
        "sim",
        "--trace",
        "--seed",
        &case.seed.to_string(),
        "--strategy",
        case.strategy.name(),
    ]);
    cmd.arg("--log").arg(&log);
    if case.hard {
        cmd.args(["--seeded-times", "--faults", "3"]);
    }
    cmd.args(["--fault-rate", &case.fault_rate.to_string()]);
    let out = cmd.output().expect("running robotino-agent sim");
    assert!(
        out.status.success(),
        "robotino-agent sim failed on {case:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let log_text = std::fs::read_to_string(&log).expect("sim --log wrote the game log");
    (String::from_utf8_lossy(&out.stdout).into_owned(), log_text)
}

/// Both engines' traces, results and decision logs for one game.
struct Played {
    clips_fires: Vec<String>,
    our_fires: Vec<String>,
    clips_result: Option<String>,
    our_result: Option<String>,
    clips_decisions: Vec<String>,
    our_decisions: Vec<String>,
}

fn play_both(case: Case, dir: &Path) -> Played {
    let clips_out = play_in_clips(case, dir);
    let (clips_fires, clips_result) = trace_and_result(&clips_out);
    let (our_out, our_log) = play_in_ours(case, dir);
    let (our_fires, our_result) = trace_and_result(&our_out);
    assert!(
        clips_fires.len() > 100,
        "CLIPS played no real game for {case:?}"
    );
    assert!(
        clips_result.is_some(),
        "CLIPS printed no RESULT for {case:?}"
    );
    Played {
        clips_fires,
        our_fires,
        clips_result,
        our_result,
        clips_decisions: decision_lines(&clips_out),
        our_decisions: decision_lines(&our_log),
    }
}

/// Index of the first entry where two lists differ.
fn first_difference(a: &[String], b: &[String]) -> Option<usize> {
    (0..a.len().max(b.len())).find(|&i| a.get(i) != b.get(i))
}

/// Plays every case in both engines and collects what `check` finds.
fn check_all(check: impl Fn(Case, &Played) -> Option<String>) {
    let dir = scratch_dir();
    require_clips(&dir);
    let failures: Vec<String> = cases()
        .into_iter()
        .filter_map(|case| check(case, &play_both(case, &dir)))
        .collect();
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
fn seeded_games_fire_the_same_rules_as_real_clips() {
    check_all(|case, p| {
        if let Some(i) = first_difference(&p.clips_fires, &p.our_fires) {
            Some(format!(
                "{case:?}: traces differ at firing {} of {} (ours {}):\n  clips: {:?}\n  ours:  {:?}",
                i + 1,
                p.clips_fires.len(),
                p.our_fires.len(),
                p.clips_fires.get(i),
                p.our_fires.get(i)
            ))
        } else if p.clips_result != p.our_result {
            Some(format!(
                "{case:?}: results differ:\n  clips: {:?}\n  ours:  {:?}",
                p.clips_result, p.our_result
            ))
        } else {
            None
        }
    });
}

/// The decision log also holds the beliefs after every decision, built by
/// `log-beliefs` (game-log.clp) as a multifield in a deffunction loop.
#[test]
fn seeded_games_log_the_same_decisions_as_real_clips() {
    check_all(|case, p| {
        first_difference(&p.clips_decisions, &p.our_decisions).map(|i| {
            format!(
                "{case:?}: decision log differs at entry {}:\n  clips: {:?}\n  ours:  {:?}",
                i + 1,
                p.clips_decisions.get(i),
                p.our_decisions.get(i)
            )
        })
    });
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
    for strategy in Strategy::ALL {
        assert!(
            cases
                .iter()
                .any(|c| c.strategy == strategy && c.fault_rate >= 10),
            "{strategy:?} in a faulty game"
        );
    }
}
