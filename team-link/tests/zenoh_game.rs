//! The process-level team game with the robots joined only over Zenoh: the main
//! workspace's `robotino-agent game --zenoh-agent` starts this crate's
//! `robotino-agent-zenoh` for each robot (peers on 127.0.0.1 TCP endpoints) and the sim
//! plays the field. With 10 % loss and up to 2 s delay on the link (our proxy), no two
//! robots ever work one machine, and every robot plays.
//!
//! Needs the main workspace's binaries: `cargo build --release -p host-shim` at the
//! top (or `ROBOTINO_BIN_DIR=...`), then `cd team-link && cargo test --release`.

use std::path::PathBuf;
use std::process::Command;

fn bin_dir() -> PathBuf {
    let dir = std::env::var_os("ROBOTINO_BIN_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/release")
        });
    assert!(
        dir.join("robotino-agent").exists() && dir.join("robotino-sim").exists(),
        "no robotino-agent and robotino-sim in {}: build the main workspace first \
         (cargo build --release -p host-shim) or set ROBOTINO_BIN_DIR",
        dir.display()
    );
    dir
}

/// A few seeds with a short clock (the test command runs this; the 100-seed figures are
/// `game-sweep --zenoh-agent`'s, README).
#[test]
fn a_team_joined_only_over_zenoh_plays_without_double_claims() {
    for seed in ["1", "39"] {
        play_over_zenoh(seed);
    }
}

fn play_over_zenoh(seed: &str) {
    let dir = bin_dir();
    let out = Command::new(dir.join("robotino-agent"))
        .args([
            "game",
            "--robots",
            "3",
            "--seed",
            seed,
            "--game-seconds",
            "300",
            "--link-loss-percent",
            "10",
            "--link-delay-s",
            "2",
            "--timeout-s",
            "300",
            "--zenoh-agent",
            env!("CARGO_BIN_EXE_robotino-agent-zenoh"),
        ])
        .output()
        .expect("starting robotino-agent game");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let team = text
        .lines()
        .find(|l| l.starts_with("team: "))
        .unwrap_or_else(|| panic!("no team line\n{text}"));
    assert!(team.contains(" 0 double claims"), "seed {seed}: {team}\n{text}");
    for r in 1..=3 {
        let skills: usize = text
            .lines()
            .find_map(|l| l.strip_prefix(&format!("robotino-agent game: agent{r} skills=")))
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or(0);
        assert!(skills >= 2, "seed {seed}, robot {r}: {skills} skills\n{text}");
    }
    let score: i64 = text
        .lines()
        .find_map(|l| l.strip_prefix("robotino-agent game: score="))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(-1);
    assert!(score > 0, "seed {seed}: {text}");
    eprintln!("seed {seed} over Zenoh: {score} points, {team}");
}
