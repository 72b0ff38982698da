//! `game-sweep` plays process-level games over seeds in parallel and sums them up; `game`
//! prints the readable report and draws the timeline. Short clocks keep this quick.

mod shim_common;

use shim_common::{Proc, AGENT};
use std::time::Duration;

#[test]
fn sweep_prints_a_row_per_seed_and_the_summary() {
    let mut sweep = Proc::start(
        "game-sweep",
        AGENT,
        &[
            "game-sweep",
            "--from",
            "5",
            "--count",
            "2",
            "--game-seconds",
            "60",
            "--quiet",
        ],
    );
    let status = sweep.wait_exit(Duration::from_secs(240));
    assert!(status.is_some_and(|s| s.success()), "{}", sweep.dump());
    let lines = sweep.lines();
    for seed in ["| 5 |", "| 6 |"] {
        assert!(
            lines.iter().any(|l| l.starts_with(seed)),
            "{}",
            sweep.dump()
        );
    }
    let header = lines
        .iter()
        .position(|l| l.starts_with("| games | mean points"))
        .unwrap_or_else(|| panic!("no summary\n{}", sweep.dump()));
    let summary = &lines[header + 2];
    assert!(summary.starts_with("| 2 | "), "{summary}");
}

#[test]
fn game_prints_the_report_and_draws_the_timeline() {
    let dir = std::env::temp_dir().join(format!("game-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let svg = dir.join("t.svg");
    let svg_arg = svg.to_string_lossy().to_string();
    let mut game = Proc::start(
        "game",
        AGENT,
        &[
            "game",
            "--seed",
            "1",
            "--game-seconds",
            "90",
            "--svg",
            &svg_arg,
        ],
    );
    let status = game.wait_exit(Duration::from_secs(240));
    assert!(status.is_some_and(|s| s.success()), "{}", game.dump());
    for needle in [
        "decisions (game time, robot, skill, outcome):",
        "robot1 get-s0 INS (holding NONE) -> FINAL",
        "beliefs learned:",
        "products:",
        "travel and body:",
        "end: the clock ran out",
        "points: ",
    ] {
        assert!(
            game.line_with(needle).is_some(),
            "{needle}\n{}",
            game.dump()
        );
    }
    let picture = std::fs::read_to_string(&svg).unwrap_or_else(|e| panic!("{e}"));
    assert!(picture.starts_with("<svg") && picture.contains(">robot1</text>"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `game-sweep --kill-one` on a short clock: the last robot dies at a game time drawn
/// from the seed inside the game (here 60 s of 150), the game ends normally, the dead
/// robot's time after its death is no stall, and nobody touches its body or works a
/// machine it held.
#[test]
fn a_short_kill_one_sweep_plays_on_without_the_dead_robot() {
    let mut sweep = Proc::start(
        "game-sweep",
        AGENT,
        &[
            "game-sweep",
            "--robots",
            "3",
            "--kill-one",
            "--from",
            "0",
            "--count",
            "1",
            "--game-seconds",
            "150",
            "--quiet",
        ],
    );
    let status = sweep.wait_exit(Duration::from_secs(240));
    assert!(status.is_some_and(|s| s.success()), "{}", sweep.dump());
    let lines = sweep.lines();
    let header = lines
        .iter()
        .position(|l| l.starts_with("| games | mean points"))
        .unwrap_or_else(|| panic!("no summary\n{}", sweep.dump()));
    // | games | mean points | min | max | collisions | double claims | stalls | ...
    let cells: Vec<&str> = lines[header + 2].split('|').map(str::trim).collect();
    assert_eq!(cells.get(1), Some(&"1"), "{}", sweep.dump());
    assert_eq!(cells.get(5), Some(&"0"), "collisions\n{}", sweep.dump());
    assert_eq!(cells.get(6), Some(&"0"), "double claims\n{}", sweep.dump());
    assert_eq!(cells.get(7), Some(&"0"), "stalls\n{}", sweep.dump());
    let points: f64 = cells.get(2).and_then(|p| p.parse().ok()).unwrap_or(0.0);
    assert!(points > 0.0, "{}", sweep.dump());
}
