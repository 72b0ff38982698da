//! A team member that finds its machine busy does not wait for it for ever
//! (`rules/team-agent.clp`, "a robot that waits long takes other work"): robot 2 keeps
//! M3 (it fed the T3 and will collect the P); robot 1, holding an S1 whose best use is
//! M3, waits, and after `?*TEAM_WAIT_OTHER_WORK_S*` (20 s) brings the S1 to the free T2
//! M8 instead, a lower priority. A robot that still holds nothing else keeps waiting
//! when no free machine takes its puck. A robot that fails twice in a row to drive to
//! a machine (a dead teammate's body in its approach) takes other work at once.

use agent_core::ValueRef;
use host_shim::team::member::slot_sym;
use host_shim::team::TeamMember;

const STEP: f64 = 0.25;

fn on_big_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .expect("spawning the test thread")
        .join()
        .expect("the test thread panicked")
}

fn team() -> Vec<TeamMember> {
    let files: Vec<rules::RuleFile> = rules::agent_files(rules::Strategy::Paper).to_vec();
    (1..=3u8)
        .map(|id| {
            let mut m = TeamMember::new(&files, None).unwrap_or_else(|e| panic!("{e}"));
            m.engine
                .load_str(&mut m.host, rules::TEAM_AGENT.name, rules::TEAM_AGENT.text)
                .unwrap_or_else(|e| panic!("team-agent.clp: {e}"));
            m.start(id, 3, 0.0, &[]).unwrap_or_else(|e| panic!("{e}"));
            m
        })
        .collect()
}

fn eval(m: &mut TeamMember, command: &str) {
    m.eval(command).unwrap_or_else(|e| panic!("{e}"));
}

/// Robot `m` believes what the test says: nothing to do (a state no rule acts on) until
/// `begin` puts it to work.
fn believe(m: &mut TeamMember, holding: &str, machines: &[(&str, &str, &str)]) {
    eval(m, "(do-for-all-facts ((?s state)) TRUE (retract ?s))");
    eval(m, "(assert (state TEST-PAUSED))");
    eval(m, "(do-for-all-facts ((?h holding)) TRUE (retract ?h))");
    eval(m, &format!("(assert (holding {holding}))"));
    for (name, mtype, loaded) in machines {
        eval(
            m,
            &format!(
                "(do-for-fact ((?m machine)) (eq ?m:name {name}) \
                 (modify ?m (mtype {mtype}) (loaded-with {loaded})))"
            ),
        );
    }
}

fn begin(m: &mut TeamMember) {
    eval(m, "(do-for-all-facts ((?s state)) TRUE (retract ?s))");
    eval(m, "(assert (state IDLE))");
}

/// One step of game time: clocks, rules, and every message to every robot (the sender
/// too: its own vote comes back to it), until the team is quiet.
fn step(members: &mut [TeamMember], t: f64) {
    for m in members.iter_mut() {
        m.set_time(t).unwrap_or_else(|e| panic!("{e}"));
    }
    for _ in 0..50 {
        let mut mail = Vec::new();
        for m in members.iter_mut() {
            m.run().unwrap_or_else(|e| panic!("{e}"));
            mail.extend(m.outbox().unwrap_or_else(|e| panic!("{e}")));
        }
        if mail.is_empty() {
            return;
        }
        for msg in &mail {
            for m in members.iter_mut() {
                m.receive(msg).unwrap_or_else(|e| panic!("{e}"));
            }
        }
    }
    panic!("the team's messages do not settle at {t} s");
}

fn state(m: &TeamMember) -> String {
    m.engine
        .facts()
        .find(|&id| m.engine.fact_template_name(id) == Some("state"))
        .and_then(|id| match m.engine.fact_multislot_item(id, "implied", 0) {
            Some(ValueRef::Symbol(s)) => Some(s.to_string()),
            _ => None,
        })
        .unwrap_or_default()
}

/// The (name, target) of the robot's skill request, if it made one.
fn request(m: &TeamMember) -> Option<(String, String)> {
    m.engine
        .facts()
        .find(|&id| m.engine.fact_template_name(id) == Some("skill-request"))
        .map(|id| {
            (
                slot_sym(&m.engine, id, "name"),
                slot_sym(&m.engine, id, "target"),
            )
        })
}

/// Robot 1 at one step: (game time, state, skill request).
type Moment = (f64, String, Option<(String, String)>);

/// Robot 2 holds M3 (a T3 with an S2 it fed, its P to collect) all game; every robot
/// believes `beliefs` of the machines; robot 1 gets an S1 at 3 s. Returns robot 1's
/// moments up to `until`.
fn play(beliefs: &[(&str, &str, &str)], until: f64) -> Vec<Moment> {
    let mut members = team();
    believe(&mut members[0], "S1", beliefs);
    believe(&mut members[1], "NONE", beliefs);
    believe(&mut members[2], "NONE", beliefs);
    eval(&mut members[1], "(assert (output-at M3 P))");
    members[1].want("M3").unwrap_or_else(|e| panic!("{e}"));
    let mut seen = Vec::new();
    let mut t = 0.0;
    while t <= until {
        if t == 3.0 {
            assert!(members[1].holds("M3"), "robot 2 got M3 at the start");
            begin(&mut members[0]);
        }
        step(&mut members, t);
        assert!(
            !(members[0].holds("M3") && members[1].holds("M3")),
            "M3 held twice at {t}"
        );
        seen.push((t, state(&members[0]), request(&members[0])));
        t += STEP;
    }
    seen
}

#[test]
fn a_robot_that_waits_long_brings_its_puck_to_a_free_machine() {
    let seen = on_big_stack(|| {
        play(
            &[("M3", "T3", "S2"), ("M8", "T2", ""), ("M1", "T1", "")],
            30.0,
        )
    });
    // It waits for M3 at first (the S1 is of most use there) ...
    let waited = seen
        .iter()
        .filter(|(t, s, r)| *t >= 4.0 && *t < 22.0 && s == "TEAM-WAIT" && r.is_none())
        .count();
    assert!(
        waited as f64 * STEP >= 15.0,
        "robot 1 should wait for M3 first: {seen:?}"
    );
    // ... and then brings it to the free T2 M8 (a lower priority), never to M3.
    let first = seen.iter().find_map(|(t, _, r)| r.clone().map(|r| (*t, r)));
    assert_eq!(
        first.as_ref().map(|(_, r)| r.clone()),
        Some(("finish-puck-at".to_string(), "M8".to_string())),
        "{seen:?}"
    );
    let at = first.map(|(t, _)| t).unwrap_or_default();
    assert!(
        (23.0..=26.0).contains(&at),
        "M8 after 20 s of waiting, not at {at}"
    );
}

/// No free machine takes the S1: the robot waits for M3, and after
/// `?*TEAM_WAIT_PUCK_MAX_S*` (40 s) of waits lets go of the puck (a discard) rather than
/// stand still on (team seeds 72 and 91: 61 s with an S1, a stall).
#[test]
fn a_robot_waits_when_no_free_machine_takes_its_puck_then_lets_go() {
    // Every other machine is a T1: none takes an S1 (unknown ones would, to explore).
    let others = ["M1", "M2", "M4", "M5", "M6", "M7", "M8", "M9", "M10"];
    let mut beliefs = vec![("M3", "T3", "S2")];
    beliefs.extend(others.iter().map(|m| (*m, "T1", "")));
    let seen = on_big_stack(move || play(&beliefs, 50.0));
    let at = |t: f64| seen.iter().find(|m| m.0 == t).cloned();
    assert!(
        matches!(at(40.0), Some((_, s, None)) if s == "TEAM-WAIT"),
        "robot 1 should still wait for M3 at 40 s: {:?}",
        at(40.0)
    );
    let discard = seen
        .iter()
        .find(|(_, _, r)| r.as_ref().is_some_and(|(a, _)| a == "discard"))
        .map(|(t, _, _)| *t);
    assert!(
        discard.is_some_and(|t| (42.0..=45.0).contains(&t)),
        "a discard 40 s after the wait began (3 s): {discard:?} {seen:?}"
    );
    assert!(
        !seen
            .iter()
            .any(|(_, _, r)| r.as_ref().is_some_and(|(_, x)| x == "M3")),
        "never at M3, robot 2's: {seen:?}"
    );
}

fn request_id(m: &TeamMember) -> Option<i64> {
    m.engine
        .facts()
        .find(|&id| m.engine.fact_template_name(id) == Some("skill-request"))
        .and_then(|id| match m.engine.fact_slot(id, "id") {
            Some(ValueRef::Int(v)) => Some(v),
            _ => None,
        })
}

/// The executor's report of a drive that could not reach the place, the puck still
/// held (as `run` reports `FailReason::DriveFailed`).
fn fail_drive(m: &mut TeamMember) {
    let id = request_id(m).unwrap_or_else(|| panic!("no skill running"));
    eval(m, &format!("(assert (team-unreached (id {id})))"));
    eval(
        m,
        &format!("(assert (skill-outcome (id {id}) (status FAILED) (info puck-held)))"),
    );
}

/// Nobody holds M3, but robot 1 cannot drive there: after two failed drives in a row it
/// brings its S1 to the free T2 M8 at once (not after 20 s), and M3 is tried again only
/// once `?*TEAM_BLOCKED_S*` (120 s) have passed.
#[test]
fn a_robot_that_cannot_reach_a_machine_takes_other_work() {
    let seen = on_big_stack(|| {
        let mut members = team();
        let beliefs = [("M3", "T3", "S2"), ("M8", "T2", ""), ("M1", "T1", "")];
        believe(&mut members[0], "S1", &beliefs);
        believe(&mut members[1], "NONE", &beliefs);
        believe(&mut members[2], "NONE", &beliefs);
        begin(&mut members[0]);
        let mut seen: Vec<Moment> = Vec::new();
        let mut failed = 0;
        let mut t = 0.0;
        while t <= 140.0 {
            step(&mut members, t);
            let r = request(&members[0]);
            seen.push((t, state(&members[0]), r.clone()));
            if failed < 2 && r.is_some_and(|(_, x)| x == "M3") {
                fail_drive(&mut members[0]);
                failed += 1;
            }
            // Every 10 s from 20 s robot 1 drops its skill and holds another S1 (as if
            // the last one were in M8): it decides again.
            if t >= 20.0 && t % 10.0 == 0.0 {
                eval(
                    &mut members[0],
                    "(do-for-all-facts ((?r skill-request)) TRUE (retract ?r))",
                );
                believe(&mut members[0], "S1", &beliefs);
                begin(&mut members[0]);
            }
            t += STEP;
        }
        seen
    });
    let at_m3: Vec<f64> = seen
        .iter()
        .filter(|(_, _, r)| r.as_ref().is_some_and(|(_, x)| x == "M3"))
        .map(|(t, _, _)| *t)
        .collect();
    let first_m8 = seen
        .iter()
        .find(|(_, _, r)| r.as_ref().is_some_and(|(_, x)| x == "M8"))
        .map(|(t, _, _)| *t);
    let second_failure = at_m3.iter().copied().find(|&t| t > at_m3[0] + STEP / 2.0);
    let (Some(m8), Some(failed)) = (first_m8, second_failure) else {
        panic!("two drives to M3, then M8: {seen:?}");
    };
    assert!(
        m8 - failed <= 2.0,
        "M8 at {m8}, right after the failure at {failed}"
    );
    // Deciding again every 10 s, it does not go back to M3 while it is blocked ...
    assert!(
        !at_m3.iter().any(|&t| (20.0..failed + 119.0).contains(&t)),
        "{seen:?}"
    );
    // ... but does once the block is over (its best use is still there).
    assert!(
        at_m3.iter().any(|&t| t >= failed + 120.0),
        "M3 again after 120 s: {seen:?}"
    );
}

/// Robot 1 holds junk, its P lies at M6, and it cannot drive to the recycling unit it
/// chose: after two failed drives there it recycles at the other unit at once. Before,
/// the blocked unit was waited for with the hands full and the product out, the wait
/// broke with a discard at that same unit, blocked again: a rule loop that stopped the
/// agent (kill-one seeds 92 and 97, "rules fired without quiescence").
#[test]
fn a_robot_that_cannot_reach_a_recycling_unit_recycles_at_the_other() {
    let seen = on_big_stack(|| {
        let mut members = team();
        let beliefs = [("M6", "T3", ""), ("M8", "T2", ""), ("M1", "T1", "")];
        believe(&mut members[0], "JUNK", &beliefs);
        believe(&mut members[1], "NONE", &beliefs);
        believe(&mut members[2], "NONE", &beliefs);
        eval(&mut members[0], "(assert (output-at M6 P))");
        begin(&mut members[0]);
        let mut seen: Vec<Moment> = Vec::new();
        let mut failed: Vec<String> = Vec::new();
        let mut t = 0.0;
        while t <= 40.0 {
            step(&mut members, t);
            let r = request(&members[0]);
            seen.push((t, state(&members[0]), r.clone()));
            match r {
                Some((a, x)) if a == "recycle" && failed.len() < 2 => {
                    if failed.first().is_some_and(|f| *f != x) {
                        panic!("the first unit once more before it was blocked: {seen:?}");
                    }
                    fail_drive(&mut members[0]);
                    failed.push(x);
                }
                _ => {}
            }
            t += STEP;
        }
        (seen, failed)
    });
    let (seen, failed) = seen;
    let [first, again] = &failed[..] else {
        panic!("two failed drives to a unit: {seen:?}");
    };
    assert_eq!(first, again);
    let other = if first == "R1" { "R2" } else { "R1" };
    let second_failure = seen
        .iter()
        .filter(|(_, _, r)| r.as_ref().is_some_and(|(_, x)| x == first))
        .map(|(t, _, _)| *t)
        .fold(0.0, f64::max);
    let at_other = seen
        .iter()
        .find(|(_, _, r)| {
            r.as_ref()
                .is_some_and(|(a, x)| a == "recycle" && x == other)
        })
        .map(|(t, _, _)| *t);
    assert!(
        at_other.is_some_and(|t| t - second_failure <= 2.0),
        "recycling at {other} right after the second failure at {second_failure}: {seen:?}"
    );
}

/// As above, but no other machine takes the S1 (all the others are T1s) and nobody holds
/// M3: blocked after two failed drives, M3 is the robot's only work. It tries M3 again
/// after `?*TEAM_BLOCKED_RETRY_S*` (20 s) rather than stand still for the block's 120 s
/// (team seed 32: a robot pushed onto M9 twice on its way to M10 stood still 61 s with
/// its S2, a stall).
#[test]
fn a_robot_with_no_other_work_tries_a_blocked_place_again() {
    let seen = on_big_stack(|| {
        let mut members = team();
        let others = ["M1", "M2", "M4", "M5", "M6", "M7", "M8", "M9", "M10"];
        let mut beliefs = vec![("M3", "T3", "S2")];
        beliefs.extend(others.iter().map(|m| (*m, "T1", "")));
        believe(&mut members[0], "S1", &beliefs);
        believe(&mut members[1], "NONE", &beliefs);
        believe(&mut members[2], "NONE", &beliefs);
        begin(&mut members[0]);
        let mut seen: Vec<Moment> = Vec::new();
        // When each skill request at M3 (by its id) was first seen.
        let mut starts: Vec<(i64, f64)> = Vec::new();
        let mut t = 0.0;
        while t <= 60.0 {
            step(&mut members, t);
            let r = request(&members[0]);
            seen.push((t, state(&members[0]), r.clone()));
            if r.is_some_and(|(_, x)| x == "M3") {
                let id = request_id(&members[0]).unwrap_or_else(|| panic!("an id"));
                if starts.iter().all(|&(i, _)| i != id) {
                    starts.push((id, t));
                    if starts.len() <= 2 {
                        fail_drive(&mut members[0]);
                    }
                }
            }
            t += STEP;
        }
        (seen, starts)
    });
    let (seen, starts) = seen;
    let starts: Vec<f64> = starts.iter().map(|&(_, t)| t).collect();
    let [_, second, third, ..] = starts[..] else {
        panic!("three drives to M3: {starts:?} {seen:?}");
    };
    // Between the second failure and the retry it waits (it has no other work) ...
    assert!(
        seen.iter()
            .filter(|(t, _, _)| *t > second + 2.0 && *t < third)
            .all(|(_, s, r)| s == "TEAM-WAIT" && r.is_none()),
        "{seen:?}"
    );
    // ... 20 s, not the block's 120 s.
    assert!(
        (second + 19.0..=second + 24.0).contains(&third),
        "M3 again at {third}, the second failure at {second}: {seen:?}"
    );
}
