//! Whole runs across processes: a whole game between `robotino-agent run` and
//! `robotino-sim`, and the sim driver killed mid-game and restarted.

mod shim_common;

use host_shim::shim::payloads::MotorCommandPayload;
use host_shim::shim::transport::{RobotStream, Transport};
use shim_common::{unique_prefix, wait_until, Proc, AGENT, SIM};
use std::time::Duration;

const WATCHDOG: Duration = Duration::from_secs(120);

/// The README's command: `robotino-agent game` starts `robotino-sim` (CLIPS referee) and
/// `robotino-agent run` (the agent's rules in our engine) as separate processes in lockstep
/// and plays the whole 15 minutes.
#[test]
fn whole_game_between_the_processes_scores() {
    let mut game = Proc::start(
        "game",
        AGENT,
        &["game", "--seed", "0", "--timeout-s", "240"],
    );
    let status = game.wait_exit(Duration::from_secs(300));
    assert!(
        status.is_some_and(|s| s.success()),
        "{status:?}\n{}",
        game.dump()
    );
    let done = game.line_with("robotino-sim: done").unwrap_or_default();
    // The referee's clock ran the whole game: to 900 s, or to a last processing step that
    // would have ended after it (the referee's `late`).
    let game_time: f64 = done
        .split_whitespace()
        .find_map(|w| w.strip_prefix("game_time_s="))
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0);
    assert!(game_time >= 800.0, "{}", game.dump());
    let score: i64 = game
        .line_with("robotino-agent game: score=")
        .and_then(|l| l.rsplit('=').next().and_then(|v| v.parse().ok()))
        .unwrap_or_else(|| panic!("no score\n{}", game.dump()));
    assert!(score > 0, "{}", game.dump());
    // The agent's rules decided every skill and counted its cycles.
    let stats = game
        .line_with("robotino-agent run: done")
        .unwrap_or_default();
    assert!(stats.contains(" decision_cycles="), "{}", game.dump());
    let skills: usize = game
        .line_with("agent1 skills=")
        .and_then(|l| l.rsplit('=').next().and_then(|v| v.parse().ok()))
        .unwrap_or(0);
    assert!(skills >= 20, "{}", game.dump());
    println!("{done}\n{stats}\nscore={score}");
}

#[test]
fn sim_killed_mid_game_stops_the_motors_and_the_game_resumes_with_a_new_driver() {
    let prefix = unique_prefix("restart");
    let t = Transport::open(&prefix, "shim-test-restart").unwrap_or_else(|e| panic!("{e}"));
    let mut motor = t
        .subscriber::<MotorCommandPayload>(&t.names.robot(1, RobotStream::Motor))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Proc::start("sim", SIM, &["--prefix", &prefix, "--time-warp", "3"]);
    let agent = Proc::start(
        "agent",
        AGENT,
        &["run", "--prefix", &prefix, "--time-warp", "3"],
    );

    let mut moving = false;
    wait_until("robot drives", WATCHDOG, &[&sim, &agent], || {
        let _ = motor.drain(|p| moving |= p.decode().is_ok_and(|w| !w.is_zero()));
        moving
    });

    sim.kill();
    // Every command the agent sends from now on: it may still drive while the last samples
    // are fresh, then at most the 3-cycle deadline, then zero for good.
    let mut after_kill: Vec<bool> = Vec::new();
    wait_until(
        "motors zero after the deadline",
        WATCHDOG,
        &[&agent],
        || {
            let _ = motor.drain(|p| after_kill.push(p.decode().is_ok_and(|w| w.is_zero())));
            after_kill.len() >= 20
        },
    );
    let first_zero = after_kill.iter().position(|&z| z);
    assert!(
        first_zero.is_some_and(|i| i <= 3),
        "zero command came too late: {after_kill:?}"
    );
    let from = first_zero.unwrap_or(0);
    assert!(
        after_kill[from..].iter().all(|&z| z),
        "motion resumed without a driver: {after_kill:?}"
    );
    wait_until(
        "skill failed on the sensor deadline",
        WATCHDOG,
        &[&agent],
        || agent.line_with("Failed(SensorTimeout)").is_some(),
    );

    let starts_before = agent
        .lines()
        .iter()
        .filter(|l| l.contains(" start "))
        .count();
    let sim2 = Proc::start("sim2", SIM, &["--prefix", &prefix, "--time-warp", "3"]);
    let mut moving_again = false;
    wait_until(
        "robot drives with the new driver",
        WATCHDOG,
        &[&sim2, &agent],
        || {
            let _ = motor.drain(|p| moving_again |= p.decode().is_ok_and(|w| !w.is_zero()));
            moving_again
        },
    );
    // The motor command can overtake the agent's `start` line (a pipe and a reader
    // thread): wait for the line rather than count at once.
    wait_until(
        "a skill starts with the new driver",
        WATCHDOG,
        &[&agent],
        || {
            agent
                .lines()
                .iter()
                .filter(|l| l.contains(" start "))
                .count()
                > starts_before
        },
    );
}
