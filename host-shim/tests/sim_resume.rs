//! Nothing lost on restart: `robotino-agent sim --snapshot FILE` is killed
//! (SIGKILL) in the middle of a game, `sim --resume FILE` goes on from the
//! last snapshot with the same machine-type beliefs, and the game ends as the
//! uninterrupted one does (same decisions, same result, no deadlock).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const SEED: &str = "5";
const STRATEGY: &str = "travel";
const FAULT_RATE: &str = "10";
/// Kill once this decision is in the snapshot.
const KILL_AFTER: u32 = 8;
/// Wall-clock pause per decision of the killed run: a game of ~60
/// decisions lasts seconds, so the kill lands in the middle.
const PACE_MS: &str = "60";

fn agent() -> Command {
    Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("robotino-resume-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temp dir is writable");
    dir
}

fn game_args() -> [&'static str; 7] {
    [
        "sim",
        "--seed",
        SEED,
        "--strategy",
        STRATEGY,
        "--fault-rate",
        FAULT_RATE,
    ]
}

/// The decision number in a snapshot's `(snapshot-saved N)` fact.
fn saved_decision(text: &str) -> Option<u32> {
    text.lines()
        .find_map(|l| l.trim().strip_prefix("(snapshot-saved "))
        .and_then(|rest| rest.trim_end_matches(')').trim().parse().ok())
}

/// `name` slot value in a fact line.
fn slot<'a>(line: &'a str, name: &str) -> Option<&'a str> {
    let start = line.find(&format!("({name} "))? + name.len() + 2;
    let rest = &line[start..];
    Some(&rest[..rest.find(')')?])
}

/// The snapshot's machine beliefs M1..M10 as `T2_3+S0`, read from its text.
fn snapshot_beliefs(text: &str) -> Vec<String> {
    let mut beliefs: Vec<(u32, String)> = text
        .lines()
        .filter(|l| l.starts_with("(machine "))
        .map(|l| {
            let index = slot(l, "index")
                .and_then(|i| i.parse().ok())
                .expect("a machine fact has an index");
            let mut belief = slot(l, "mtype").expect("a machine has a type").to_string();
            for puck in slot(l, "loaded-with").unwrap_or("").split_whitespace() {
                belief.push('+');
                belief.push_str(puck);
            }
            (index, belief)
        })
        .collect();
    beliefs.sort();
    beliefs.into_iter().map(|(_, b)| b).collect()
}

fn lines_starting<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    text.lines().filter(|l| l.starts_with(prefix)).collect()
}

/// Starts the game with snapshots, waits (polling the snapshot file) until
/// decision KILL_AFTER is saved, kills the process and returns the snapshot.
fn play_and_kill(snap: &Path) -> String {
    let mut child = agent()
        .args(game_args())
        .arg("--snapshot")
        .arg(snap)
        .args(["--pace-ms", PACE_MS])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("starting robotino-agent sim");
    let started = Instant::now();
    loop {
        let text = std::fs::read_to_string(snap).unwrap_or_default();
        if saved_decision(&text).is_some_and(|n| n >= KILL_AFTER) {
            break;
        }
        if let Ok(Some(status)) = child.try_wait() {
            panic!("the game ended ({status}) before decision {KILL_AFTER} was snapshotted");
        }
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no snapshot of decision {KILL_AFTER} after 120 s"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let still_running = child.try_wait().expect("polling the child").is_none();
    assert!(
        still_running,
        "the game finished before it could be killed: raise PACE_MS"
    );
    child.kill().expect("killing the game");
    let _ = child.wait();
    std::fs::read_to_string(snap).expect("the snapshot survives the kill")
}

#[test]
fn a_killed_game_resumes_from_its_snapshot_and_ends_like_the_uninterrupted_one() {
    let dir = scratch("kill");
    let full_log = dir.join("full.log");
    let full = agent()
        .args(game_args())
        .arg("--log")
        .arg(&full_log)
        .output()
        .expect("playing the uninterrupted game");
    assert!(full.status.success());
    let full_log = std::fs::read_to_string(&full_log).expect("the full game's log");
    let full_decisions = lines_starting(&full_log, "decision ");

    let snap = dir.join("game.snapshot");
    let text = play_and_kill(&snap);
    let at = saved_decision(&text).expect("the snapshot names its decision");
    assert!(
        (at as usize) < full_decisions.len(),
        "killed after decision {at} of {}: not mid-game",
        full_decisions.len()
    );
    // The snapshot is complete (atomic replace): every machine belief is there.
    let saved = snapshot_beliefs(&text);
    assert_eq!(saved.len(), 10, "{text}");
    // It already holds knowledge worth keeping.
    assert!(saved.iter().any(|b| b != "T1_2_3"), "{saved:?}");

    let resumed_log = dir.join("resumed.log");
    let resumed = agent()
        .arg("sim")
        .arg("--resume")
        .arg(&snap)
        .arg("--log")
        .arg(&resumed_log)
        .output()
        .expect("resuming the game");
    let out = String::from_utf8_lossy(&resumed.stdout).into_owned();
    assert!(
        resumed.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    let expected = format!(
        "after decision {at}; machine beliefs M1..M10: {}",
        saved.join(" ")
    );
    assert!(out.contains(&expected), "expected {expected:?} in:\n{out}");

    let resumed_log = std::fs::read_to_string(&resumed_log).expect("the resumed game's log");
    assert_eq!(lines_starting(&resumed_log, "decision "), full_decisions);
    let result = lines_starting(&resumed_log, "result ");
    assert_eq!(result, lines_starting(&full_log, "result "));
    assert!(
        result
            .iter()
            .all(|r| !r.contains("deadlock") && !r.contains("end none")),
        "{result:?}"
    );
    // The resumed run kept snapshotting to the same file, up to the last decision.
    let last = std::fs::read_to_string(&snap).expect("the snapshot after the resumed run");
    assert_eq!(saved_decision(&last), Some(full_decisions.len() as u32));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn resuming_something_that_is_not_a_snapshot_is_an_error() {
    let dir = scratch("bad");
    let bad = dir.join("bad.snapshot");
    std::fs::write(&bad, "(initial-fact)\n(holding NONE)\n").expect("writing");
    let out = agent()
        .arg("sim")
        .arg("--resume")
        .arg(&bad)
        .output()
        .expect("running sim");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("not a usable snapshot"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
