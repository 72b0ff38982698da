//! `sim --log FILE` then `sim --replay FILE`: the same decisions, and a
//! clear first mismatch when the log says otherwise.

use std::path::PathBuf;
use std::process::{Command, Output};

fn agent(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
        .args(args)
        .output()
        .expect("running robotino-agent")
}

fn temp_log(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("robotino-replay-{}-{name}.log", std::process::id()))
}

#[test]
fn a_logged_game_replays_with_the_same_decisions() {
    for (name, args) in [
        ("seed", vec!["--seed", "21", "--strategy", "travel"]),
        (
            "faults",
            vec!["--seed", "8", "--faults", "3", "--seeded-times"],
        ),
        (
            "clock-off",
            vec!["--index", "4199", "--clock-off", "--strategy", "naive"],
        ),
    ] {
        let log = temp_log(name);
        let log_arg = log.to_string_lossy().into_owned();
        let mut write = vec!["sim", "--log", &log_arg];
        write.extend(&args);
        let played = agent(&write);
        assert!(
            played.status.success(),
            "{}",
            String::from_utf8_lossy(&played.stderr)
        );
        let replayed = agent(&["sim", "--replay", &log_arg]);
        let stdout = String::from_utf8_lossy(&replayed.stdout);
        assert!(
            replayed.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&replayed.stderr)
        );
        assert!(stdout.contains(": OK"), "{name}: {stdout}");
        // The replay's result line is the one the original game printed.
        let result = |s: &str| {
            s.lines()
                .find(|l| l.starts_with("RESULT"))
                .map(str::to_string)
        };
        assert_eq!(
            result(&stdout),
            result(&String::from_utf8_lossy(&played.stdout))
        );
        let _ = std::fs::remove_file(&log);
    }
}

#[test]
fn a_tampered_log_reports_the_first_mismatch() {
    let log = temp_log("tampered");
    let log_arg = log.to_string_lossy().into_owned();
    assert!(agent(&["sim", "--seed", "2", "--log", &log_arg])
        .status
        .success());
    let text = std::fs::read_to_string(&log).expect("the log was written");
    // Claim the third decision saw a different light.
    let mut seen = 0;
    let tampered: Vec<String> = text
        .lines()
        .map(|l| {
            if l.starts_with("decision ") {
                seen += 1;
                if seen == 3 {
                    let mut words: Vec<&str> = l.split(' ').collect();
                    words[7] = if words[7] == "green" {
                        "yellow"
                    } else {
                        "green"
                    };
                    return words.join(" ");
                }
            }
            l.to_string()
        })
        .collect();
    std::fs::write(&log, tampered.join("\n") + "\n").expect("rewriting the log");
    let replayed = agent(&["sim", "--replay", &log_arg]);
    let err = String::from_utf8_lossy(&replayed.stderr);
    assert!(!replayed.status.success());
    assert!(
        err.contains("MISMATCH") && err.contains("decision 3 differs"),
        "{err}"
    );
    let _ = std::fs::remove_file(&log);
}

#[test]
fn a_file_that_is_not_a_game_log_is_rejected() {
    let log = temp_log("garbage");
    std::fs::write(&log, "hello\n").expect("writing");
    let out = agent(&["sim", "--replay", &log.to_string_lossy()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a game log"));
    let _ = std::fs::remove_file(&log);
}
