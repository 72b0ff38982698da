//! Two robots on one simulated field, each with the team's rules (`run --team-size 2`):
//! what one robot finds out of a machine reaches the other as news over the team
//! service, and the other takes it into its own belief.

mod shim_common;

use host_shim::shim::transport::Transport;
use shim_common::{unique_prefix, wait_until, Proc, AGENT, SIM};
use std::time::Duration;

/// `news from robot R: M3 T2 ...` -> (R, "M3", "T2") when the news names a definite type.
fn typed_news(line: &str) -> Option<(u8, String, String)> {
    let rest = line.split(" news from robot ").nth(1)?;
    let (from, rest) = rest.split_once(": ")?;
    let mut w = rest.split_whitespace();
    let (machine, mtype) = (w.next()?, w.next()?);
    (machine.starts_with('M') && ["T1", "T2", "T3"].contains(&mtype))
        .then(|| (from.parse().ok(), machine.to_string(), mtype.to_string()))
        .and_then(|(f, m, t)| Some((f?, m, t)))
}

#[test]
fn a_type_learned_by_one_robot_reaches_the_other() {
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
    let agent = |r: &str| {
        Proc::start(
            &format!("agent{r}"),
            AGENT,
            &[
                "run",
                "--prefix",
                &prefix,
                "--lockstep",
                "--robot",
                r,
                "--team-size",
                "2",
            ],
        )
    };
    let (a1, a2) = (agent("1"), agent("2"));
    let mut found = None;
    wait_until(
        "a robot takes a type its teammate found",
        Duration::from_secs(240),
        &[&sim, &a1, &a2],
        || {
            for (me, agent) in [(1u8, &a1), (2, &a2)] {
                for line in agent.lines() {
                    if let Some((from, machine, mtype)) = typed_news(&line) {
                        let learned = format!("learned {machine} {mtype}");
                        if from != me && agent.line_with(&learned).is_some() {
                            found = Some((me, from, learned));
                        }
                    }
                }
            }
            found.is_some()
        },
    );
    let (_, from, learned) = found.unwrap_or_default();
    // The sender found it out itself (printed before its news went out; each process's
    // output is read by a thread of its own, so under load the receiver's lines can be
    // read first: wait for the sender's, a teammate's news alone never prints it).
    let sender = if from == 1 { &a1 } else { &a2 };
    wait_until(
        &format!("the sender's own line `{learned}`"),
        Duration::from_secs(30),
        &[sender],
        || sender.line_with(&learned).is_some(),
    );
}
