//! The readable report of a process-level game, in the manner of `robotino-agent sim`'s:
//! every decision with its game time and how the skill ended, what the robots learned,
//! products, travel, points, and why the game ended.

use std::fmt::Write;

use super::record::{EndReason, Ending, GameRecord};

pub fn render(g: &GameRecord, strategy: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "robotino-agent game: seed {}, strategy {strategy}, {} robot(s), clock {} s",
        g.seed, g.robots, g.game_seconds
    );
    let _ = writeln!(out, "decisions (game time, robot, skill, outcome):");
    for s in &g.skills {
        let ending = match s.ending {
            Ending::Final => "FINAL",
            Ending::Failed => "FAILED",
            Ending::Cut => "RUNNING at the end",
        };
        let _ = writeln!(
            out,
            "  t={:6.1} robot{} {} {} (holding {}) -> {ending} {} at t={:.1}",
            s.start_s, s.robot, s.name, s.target, s.holding, s.outcome, s.end_s
        );
    }
    let _ = writeln!(out, "beliefs learned:");
    if g.learned.is_empty() {
        let _ = writeln!(out, "  none");
    }
    for (t, r, m, ty) in &g.learned {
        let _ = writeln!(out, "  t={t:6.1} robot{r} {m} is {ty}");
    }
    for (r, w) in &g.warnings {
        let _ = writeln!(out, "  robot{r} WARN {w}");
    }
    let _ = writeln!(out, "products:");
    let deliveries = g.deliveries();
    if deliveries.is_empty() {
        let _ = writeln!(out, "  none delivered");
    }
    for e in &deliveries {
        let _ = writeln!(
            out,
            "  t={:6.1} robot{} delivered {} at {} (score {})",
            e.time_s, e.robot, e.puck, e.target, e.score
        );
    }
    let produced = g
        .referee
        .iter()
        .filter(|e| e.kind == "load" && e.puck_after != "NONE" && e.puck_after != e.puck)
        .count();
    let discarded = g.referee.iter().filter(|e| e.kind == "discard").count();
    let _ = writeln!(
        out,
        "  {produced} machine outputs taken, {discarded} pucks discarded"
    );
    let _ = writeln!(out, "travel and body:");
    for (i, m) in g.travel_m.iter().enumerate() {
        let robot = i as u8 + 1;
        let bumps: Vec<String> = g
            .bumps
            .iter()
            .filter(|b| b.1 == robot)
            .map(|(t, _, with)| format!("{with}@{t:.0}s"))
            .collect();
        let failed = g
            .skills
            .iter()
            .filter(|s| s.robot == robot && s.ending == Ending::Failed)
            .count();
        let _ = writeln!(
            out,
            "  robot{robot}: {m:.1} m driven, {} skills ({failed} failed), {} bumps{}{}",
            g.skills.iter().filter(|s| s.robot == robot).count(),
            bumps.len(),
            if bumps.is_empty() { "" } else { ": " },
            bumps.join(" ")
        );
    }
    let stalls = g.stalls();
    let claims = g.double_claims();
    let _ = writeln!(
        out,
        "team: {} robot contacts, {} double claims, {} stalls",
        g.robot_contacts,
        claims.len(),
        stalls.len()
    );
    for (r, from, to) in &stalls {
        let _ = writeln!(out, "  stall robot{r} t={from:.1}..{to:.1}");
    }
    for (m, a, b, t) in &claims {
        let _ = writeln!(out, "  double claim {m} robot{a} robot{b} at t={t:.1}");
    }
    let why = match g.end_reason() {
        EndReason::Clock => format!("the clock ran out at {:.1} s", g.game_time_s),
        EndReason::Referee => format!("the referee ended it at {:.1} s", g.game_time_s),
    };
    let done: Vec<String> = g
        .done
        .iter()
        .map(|(t, r)| format!("robot{r} DONE at {t:.1} s"))
        .collect();
    let storage = g
        .storage_empty_s()
        .map(|t| format!(", input storage empty at {t:.1} s"))
        .unwrap_or_default();
    let _ = writeln!(
        out,
        "end: {why}{storage}{}{}",
        if done.is_empty() { "" } else { "; " },
        done.join(", ")
    );
    let _ = writeln!(out, "points: {}", g.score);
    out
}
