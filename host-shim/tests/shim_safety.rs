//! Safety across processes: the sim's dead-man rule when the agent dies, and bumper ->
//! zero motor command. Real processes, real iceoryx2, a unique prefix per test.

mod shim_common;

use host_shim::shim::payloads::{MotorCommandPayload, OdometryPayload};
use host_shim::shim::transport::{RobotStream, Transport};
use shim_common::{unique_prefix, wait_until, Proc, AGENT, SIM};
use std::time::Duration;

const WATCHDOG: Duration = Duration::from_secs(60);

#[test]
fn agent_killed_mid_skill_the_sim_stops_the_wheels() {
    let prefix = unique_prefix("deadman");
    // Opening a node first also removes what killed test runs left behind.
    let t = Transport::open(&prefix, "shim-test-deadman").unwrap_or_else(|e| panic!("{e}"));
    let mut odometry = t
        .subscriber::<OdometryPayload>(&t.names.robot(1, RobotStream::Odometry))
        .unwrap_or_else(|e| panic!("{e}"));
    let sim = Proc::start("sim", SIM, &["--prefix", &prefix, "--time-warp", "3"]);
    let mut agent = Proc::start(
        "agent",
        AGENT,
        &["run", "--prefix", &prefix, "--time-warp", "3"],
    );

    let mut moving = || {
        odometry
            .poll()
            .ok()
            .flatten()
            .and_then(|p| p.decode().ok())
            .is_some_and(|r| !r.measured.is_zero())
    };
    wait_until("robot drives", WATCHDOG, &[&sim, &agent], &mut moving);

    // The sim also reports the rule at start-up, before the agent's first command.
    let dead_man_lines = || {
        sim.lines()
            .iter()
            .filter(|l| l.contains("dead-man robot=1"))
            .count()
    };
    let before = dead_man_lines();
    agent.kill();
    wait_until("sim reports the dead-man rule", WATCHDOG, &[&sim], || {
        dead_man_lines() > before
    });
    // Drop samples published before the rule tripped.
    let _ = odometry.poll();
    // From then on the wheels stay still: consecutive odometry samples with zero speed and
    // an unchanged pose.
    let mut last: Option<(u32, hal::Pose2)> = None;
    let mut still_samples = 0;
    wait_until("wheels stay stopped", WATCHDOG, &[&sim], || {
        if let Some(p) = odometry.poll().ok().flatten() {
            if let (Ok(r), Some((seq, pose))) = (p.decode(), last) {
                if p.seq != seq {
                    assert!(
                        r.measured.is_zero(),
                        "wheels turn after the dead-man: {r:?}"
                    );
                    // Position frozen; the heading jitters with the gyro's noise only.
                    assert_eq!(
                        (r.pose.x_m, r.pose.y_m),
                        (pose.x_m, pose.y_m),
                        "robot moved"
                    );
                    assert!((r.pose.phi_rad - pose.phi_rad).abs() < 0.05, "robot turned");
                    still_samples += 1;
                }
            }
            if let Ok(r) = p.decode() {
                last = Some((p.seq, r.pose));
            }
        }
        still_samples >= 10
    });
}

#[test]
fn bumper_hit_gives_a_zero_command_and_fails_the_skill() {
    let prefix = unique_prefix("bumper");
    let t = Transport::open(&prefix, "shim-test-bumper").unwrap_or_else(|e| panic!("{e}"));
    let mut motor = t
        .subscriber::<MotorCommandPayload>(&t.names.robot(1, RobotStream::Motor))
        .unwrap_or_else(|e| panic!("{e}"));
    // Lockstep: one sim cycle per agent cycle, so latencies are exact cycle counts.
    let sim = Proc::start(
        "sim",
        SIM,
        &[
            "--prefix",
            &prefix,
            "--lockstep",
            "--bump-at-cycle",
            "40",
            "--cycles",
            "200",
        ],
    );
    let agent = Proc::start(
        "agent",
        AGENT,
        &["run", "--prefix", &prefix, "--lockstep", "--cycles", "150"],
    );
    let mut commands = 0;
    wait_until(
        "sim measures the bumper latency",
        WATCHDOG,
        &[&sim, &agent],
        || {
            commands += usize::from(motor.poll().ok().flatten().is_some());
            sim.line_with("bumper-latency").is_some()
        },
    );
    assert!(commands > 0, "no motor command seen over iceoryx2");
    let line = sim.line_with("bumper-latency").unwrap_or_default();
    assert!(
        line.contains("was_moving=true"),
        "the robot was not driving: {line}"
    );
    // The first command that answers the pressed sample is zero, and it arrives in the
    // next sim cycle: the agent zeroed in the very cycle it read the sample.
    assert!(line.contains("zero=true"), "{line}");
    assert!(line.contains("cycles=1 "), "{line}");
    wait_until("agent fails the skill", WATCHDOG, &[&sim, &agent], || {
        agent.line_with("end GetS0 Failed(Bumper)").is_some()
    });
    // The agent's own measurement: zero command in the cycle that read the sample.
    wait_until(
        "agent reports its loop counters",
        WATCHDOG,
        &[&agent],
        || agent.line_with("robotino-agent run: done").is_some(),
    );
    let done = agent
        .line_with("robotino-agent run: done")
        .unwrap_or_default();
    assert!(done.contains(" bumper_hits=1 "), "{done}");
    assert!(done.contains(" bumper_latency_cycles_max=0 "), "{done}");
    println!("{line}\n{done}");
}
