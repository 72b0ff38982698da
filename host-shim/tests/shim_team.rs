//! Two robots on one simulated field share world-model updates and claims over the team
//! services: a machine type found out by one robot is used by the other.

mod shim_common;

use host_shim::shim::transport::Transport;
use shim_common::{unique_prefix, wait_until, Proc, AGENT, SIM};
use std::time::Duration;

#[test]
fn a_type_learned_by_one_robot_is_used_by_the_other() {
    let prefix = unique_prefix("team");
    let _cleanup = Transport::open(&prefix, "shim-test-team").unwrap_or_else(|e| panic!("{e}"));
    let sim = Proc::start(
        "sim",
        SIM,
        &[
            "--prefix",
            &prefix,
            "--robots",
            "2",
            "--lockstep",
            "--game-seconds",
            "900",
        ],
    );
    let a1 = Proc::start(
        "agent1",
        AGENT,
        &["run", "--prefix", &prefix, "--lockstep", "--robot", "1"],
    );
    let a2 = Proc::start(
        "agent2",
        AGENT,
        &["run", "--prefix", &prefix, "--lockstep", "--robot", "2"],
    );
    let mut user = None;
    wait_until(
        "a robot uses a type its teammate found",
        Duration::from_secs(240),
        &[&sim, &a1, &a2],
        || {
            for (me, other, agent) in [(1, 2, &a1), (2, 1, &a2)] {
                if let Some(line) = agent.line_with("shared type") {
                    if line.ends_with(&format!("from robot {other}")) {
                        user = Some((me, line));
                    }
                }
            }
            user.is_some()
        },
    );
    let (me, line) = user.unwrap_or_default();
    // The machine named in the line was learned by the teammate, who logged it first.
    let machine = line
        .split_whitespace()
        .find(|w| w.starts_with('M'))
        .unwrap_or_default()
        .to_string();
    let teammate = if me == 1 { &a2 } else { &a1 };
    assert!(
        teammate.line_with(&format!("learned {machine} ")).is_some(),
        "{line}\n{}",
        teammate.dump()
    );
    let receiver = if me == 1 { &a1 } else { &a2 };
    assert!(receiver
        .line_with(&format!("belief from robot {}: {machine} ", 3 - me))
        .is_some());
}
