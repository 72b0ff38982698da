//! `game-sweep` plays process-level games over seeds in parallel and sums them up; `game`
//! prints the readable report and draws the timeline. Short clocks keep this quick.

mod shim_common;

use shim_common::{Proc, Sweep, AGENT};
use std::time::Duration;

#[test]
fn sweep_prints_a_row_per_seed_and_the_summary() {
    let sweep = Sweep::run(
        &[
            "--from",
            "5",
            "--count",
            "2",
            "--game-seconds",
            "60",
            "--quiet",
        ],
        Duration::from_secs(240),
    );
    let seeds: Vec<u64> = sweep.rows.iter().map(|&(seed, _)| seed).collect();
    assert_eq!(seeds, [5, 6], "{}", sweep.output);
    assert_eq!(sweep.cell("games"), "2", "{}", sweep.output);
}

#[test]
fn a_sweep_table_is_read_by_column_name() {
    let lines: Vec<String> = [
        "robotino-agent game-sweep: seeds 4..5",
        "| seed | points | collisions | double claims | stalls | bumps | failed skills | end |",
        "|---|---|---|---|---|---|---|---|",
        "| 4 | 121 | 0 | 0 | 2 | 1 | 1 | 900s |",
        "| 5 | 77 | 1 | 0 | 0 | 0 | 0 | 900s |",
        "",
        "| games | mean points | min | max | collisions | double claims | stalls | bumps | failed skills |",
        "|---|---|---|---|---|---|---|---|---|",
        "| 2 | 99.0 | 77 | 121 | 1 | 0 | 2 | 1 | 1 |",
    ]
    .map(String::from)
    .to_vec();
    let s = Sweep::parse(&lines, String::new());
    assert_eq!(s.rows, vec![(4, 121), (5, 77)]);
    assert_eq!(s.cell("games"), "2");
    assert_eq!(s.number("mean points"), 99.0);
    assert_eq!(s.number("collisions"), 1.0);
    assert_eq!(s.number("double claims"), 0.0);
    assert_eq!(s.number("stalls"), 2.0);
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
    let sweep = Sweep::run(
        &[
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
        Duration::from_secs(240),
    );
    let out = &sweep.output;
    assert_eq!(sweep.cell("games"), "1", "{out}");
    assert_eq!(sweep.number("collisions"), 0.0, "{out}");
    assert_eq!(sweep.number("double claims"), 0.0, "{out}");
    assert_eq!(sweep.number("stalls"), 0.0, "{out}");
    assert!(sweep.number("mean points") > 0.0, "{out}");
}
