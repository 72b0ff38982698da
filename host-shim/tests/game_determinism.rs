//! The process-level game is reproducible: in lockstep the world advances only when the
//! robot answered, so the same seed plays the same game (every decision at the same cycle,
//! every referee event, the same score), however the processes are scheduled. A team of
//! three too: each agent runs the team's rules (`rules/team.clp`) and their messages go
//! over iceoryx2, taken in the cycle after the one they were sent in. And a team larger
//! than the league's three robots is refused, not clamped.

mod shim_common;

use shim_common::{Proc, AGENT, SIM};
use std::time::Duration;

/// What two runs of one seed must agree on: the agent's decisions and skill ends and the
/// referee's log, each with its cycle (timings and service prefixes left out).
fn game_events(seed: &str, robots: &str) -> (Vec<String>, String) {
    let mut game = Proc::start(
        "game",
        AGENT,
        &[
            "game",
            "--seed",
            seed,
            "--robots",
            robots,
            "--game-seconds",
            "150",
            "--verbose",
            "--timeout-s",
            "200",
        ],
    );
    let status = game.wait_exit(Duration::from_secs(240));
    assert!(
        status.is_some_and(|s| s.success()),
        "{status:?}\n{}",
        game.dump()
    );
    let events: Vec<String> = game
        .lines()
        .into_iter()
        .filter(|l| {
            (l.contains(" start ")
                || l.contains(" end ")
                || l.contains(" referee t=")
                || l.contains(" news from ")
                || l.contains(" learned "))
                && l.contains("cycle=")
        })
        .collect();
    let score = game
        .line_with("robotino-agent game: score=")
        .unwrap_or_else(|| panic!("no score\n{}", game.dump()));
    assert!(events.len() >= 4, "too few events\n{}", game.dump());
    (events, score)
}

#[test]
fn the_same_seed_plays_the_same_process_level_game() {
    let first = game_events("3", "1");
    let second = game_events("3", "1");
    assert_eq!(first.1, second.1);
    assert_eq!(first.0, second.0);
}

#[test]
fn the_same_seed_plays_the_same_team_game() {
    let first = game_events("3", "3");
    let second = game_events("3", "3");
    // The team talked: every robot started skills, and news of places reached the others.
    for r in 1..=3 {
        let tag = format!("[agent{r}]");
        assert!(
            first
                .0
                .iter()
                .any(|l| l.starts_with(&tag) && l.contains(" start ")),
            "robot {r} never started a skill: {:#?}",
            first.0
        );
    }
    assert!(
        first.0.iter().any(|l| l.contains(" news from robot ")),
        "no team news: {:#?}",
        first.0
    );
    assert_eq!(first.1, second.1);
    assert_eq!(first.0, second.0);
}

#[test]
fn more_than_three_robots_is_refused() {
    for (program, args) in [
        (AGENT, vec!["game", "--robots", "4"]),
        (SIM, vec!["--robots", "4"]),
    ] {
        let out = std::process::Command::new(program)
            .args(&args)
            .output()
            .unwrap_or_else(|e| panic!("{program}: {e}"));
        assert!(
            !out.status.success(),
            "{program} {args:?} accepted 4 robots"
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("1..=3") || err.contains("1..4"), "{err}");
    }
}
