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
    game_events_with(seed, robots, &[]).0
}

/// As [`game_events`], with more options for `game`; also the game's `team:` line.
fn game_events_with(seed: &str, robots: &str, more: &[&str]) -> ((Vec<String>, String), String) {
    let mut args = vec![
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
    ];
    args.extend_from_slice(more);
    let mut game = Proc::start("game", AGENT, &args);
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
    let team = game.line_with("team: ").unwrap_or_default();
    ((events, score), team)
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

/// A robot killed at a game time (`game --kill-at-s`, as `game-sweep --kill-one`) dies at
/// that cycle by itself, not when a watcher gets round to it: the game plays the same
/// twice, the dead robot does nothing after its death, its claims run out (a lease, 20 s)
/// and the others work on without touching its body.
#[test]
fn a_team_game_with_a_robot_killed_plays_the_same_twice() {
    let kill = ["--kill-at-s", "40"];
    let (first, team) = game_events_with("0", "3", &kill);
    let (second, _) = game_events_with("0", "3", &kill);
    assert_eq!(first.1, second.1);
    assert_eq!(first.0, second.0);
    let cycle = |l: &str| -> u64 {
        l.split_whitespace()
            .find_map(|w| w.strip_prefix("cycle="))
            .and_then(|c| c.parse().ok())
            .unwrap_or(0)
    };
    let death = 40 * 15;
    assert!(
        !first
            .0
            .iter()
            .any(|l| l.starts_with("[agent3]") && cycle(l) > death),
        "robot 3 acted after its death: {:#?}",
        first.0
    );
    let after_lease = death + 20 * 15;
    for r in 1..=2 {
        let tag = format!("[agent{r}]");
        assert!(
            first
                .0
                .iter()
                .any(|l| l.starts_with(&tag) && l.contains(" start ") && cycle(l) > after_lease),
            "robot {r} stopped after robot 3 died: {:#?}",
            first.0
        );
    }
    assert!(team.contains(" 0 robot contacts"), "{team}");
    assert!(team.contains(" 0 double claims"), "{team}");
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
