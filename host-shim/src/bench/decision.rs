//! Decision time of the LLSF agent: from asserting a skill outcome to the agent's next
//! skill request (method: `DECISION_TIME.md` in this folder).
//!
//! 1. **Record**: seeded games are played by the whole game (agent, referee, instant sim)
//!    with `(watch facts)`; the trace gives, in order, every `skill-outcome` the sim
//!    asserted and every `skill-request` the agent asserted.
//! 2. **Replay**: a fresh engine holds the agent alone (no referee, no sim, no log). It
//!    is reset, given the setup fact the agent reads (`active-gate`) and run to its first
//!    request; then each recorded outcome is one *decision*: `assert_str(outcome)` and
//!    `run` until the agenda is empty. The agent has nothing to do while it waits in
//!    state EXEC, so the run ends right after the request (firings after it are counted
//!    and reported). Each replayed request must equal the recorded one, or the
//!    measurement fails: then the replay would not be the game's decision.
//!
//! Wall time: `Instant` around [`decision_step`], in this process. Instructions: the
//! same replay in a child process under `callgrind --collect-atstart=no
//! --toggle-collect=*decision_step* --dump-after=<its full name>`, one profile per
//! decision; its `totals:` line is that decision's count.

use super::ours::CaptureHost;
use super::process::{median, run_with_deadline};
use super::workloads;
use agent_core::{DefaultEngine, Host};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// The recorded traffic of one game.
#[derive(Clone, Debug)]
pub struct GameTrace {
    pub seed: u64,
    /// `(active-gate X)` and other setup facts the agent reads.
    pub agent_setup: Vec<String>,
    pub outcomes: Vec<String>,
    pub requests: Vec<String>,
}

/// Setup facts the agent itself reads; the others are the referee's hidden truth.
fn agent_reads(fact: &str) -> bool {
    fact.starts_with("(active-gate")
}

fn engine_error(during: &str, e: impl std::fmt::Display, host: &CaptureHost) -> String {
    let said = host.other.lines().next().unwrap_or("");
    format!("{during}: {e} {said}")
}

/// A boxed engine with `files` loaded (and the CLIPS `distance` stub if the engine lacks
/// the builtin, as the sim's Player does). Needs a big-stack thread.
fn loaded_engine(
    files: &[rules::RuleFile],
    host: &mut CaptureHost,
) -> Result<Box<DefaultEngine>, String> {
    let mut engine = Box::new(DefaultEngine::new());
    if engine.eval_str(host, "(distance 0 0 3 4)").is_err() {
        let stub = rules::CLIPS_STUBS;
        engine
            .load_str(host, stub.name, stub.text)
            .map_err(|e| engine_error(stub.name, e, host))?;
    }
    for file in files {
        engine
            .load_str(host, file.name, file.text)
            .map_err(|e| engine_error(file.name, e, host))?;
    }
    Ok(engine)
}

/// The fact text of a `(watch facts)` assert line `==> f-N     (template ...)`.
fn asserted_fact<'a>(line: &'a str, template: &str) -> Option<&'a str> {
    let rest = line.strip_prefix("==> f-")?;
    let fact = rest.trim_start_matches(|c: char| c.is_ascii_digit()).trim();
    let name = fact.strip_prefix('(')?.split([' ', ')']).next()?;
    (name == template).then_some(fact)
}

/// Plays seeds 0..games in the whole game and records each one's outcomes and requests.
pub fn record(games: usize) -> Result<Vec<GameTrace>, String> {
    let mut host = CaptureHost::default();
    let mut engine = loaded_engine(rules::game_files(workloads::LLSF_STRATEGY), &mut host)?;
    let mut traces = Vec::new();
    for (seed, setup) in workloads::llsf_setups(games) {
        let mut text = String::new();
        setup
            .write_clips(&mut text)
            .map_err(|e| format!("setup of seed {seed}: {e}"))?;
        let facts: Vec<String> = text
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with('(') && !l.starts_with("(deffacts"))
            .map(str::to_string)
            .collect();
        engine
            .reset(&mut host)
            .map_err(|e| engine_error("(reset)", e, &host))?;
        for fact in &facts {
            engine
                .assert_str(&mut host, fact)
                .map_err(|e| engine_error(fact, e, &host))?;
        }
        engine
            .eval_str(&mut host, "(watch facts)")
            .map_err(|e| engine_error("(watch facts)", e, &host))?;
        host.stdout.clear();
        host.other.clear();
        engine
            .run(&mut host, Some(500_000))
            .map_err(|e| engine_error("(run)", e, &host))?;
        engine
            .eval_str(&mut host, "(unwatch facts)")
            .map_err(|e| engine_error("(unwatch facts)", e, &host))?;
        let trace: String = host.stdout.clone() + &host.other;
        let pick = |template: &str| -> Vec<String> {
            trace
                .lines()
                .filter_map(|l| asserted_fact(l, template))
                .map(str::to_string)
                .collect()
        };
        traces.push(GameTrace {
            seed,
            agent_setup: facts.into_iter().filter(|f| agent_reads(f)).collect(),
            outcomes: pick("skill-outcome"),
            requests: pick("skill-request"),
        });
    }
    Ok(traces)
}

/// The agent alone, replaying one game (the check reads the fact list after each
/// decision, outside the timed step).
struct Replay {
    engine: Box<DefaultEngine>,
    host: CaptureHost,
}

/// One decision: the outcome asserted, the agent run until it waits again. Kept out of
/// line so callgrind can count exactly this function (`--toggle-collect`).
#[inline(never)]
pub fn decision_step(
    engine: &mut DefaultEngine,
    host: &mut dyn Host,
    outcome: &str,
) -> Result<u32, String> {
    engine
        .assert_str(host, outcome)
        .map_err(|e| format!("asserting {outcome}: {e}"))?;
    engine
        .run(host, None)
        .map_err(|e| format!("running after {outcome}: {e}"))
}

/// The newest `skill-request` fact as text (the one the last decision made).
fn last_request(engine: &DefaultEngine) -> Option<String> {
    let id = engine
        .facts()
        .filter(|&f| engine.fact_template_name(f) == Some("skill-request"))
        .last()?;
    let slot = |name: &str| match engine.fact_slot(id, name) {
        Some(agent_core::ValueRef::Int(n)) => n.to_string(),
        Some(agent_core::ValueRef::Symbol(s)) => s.to_string(),
        other => format!("{other:?}"),
    };
    Some(format!(
        "(skill-request (id {}) (name {}) (target {}) (puck {}))",
        slot("id"),
        slot("name"),
        slot("target"),
        slot("puck")
    ))
}

/// One decision's measurement.
#[derive(Clone, Copy, Debug)]
pub struct Decision {
    pub wall: Duration,
    pub fired: u32,
}

impl Replay {
    fn start(trace: &GameTrace) -> Result<Replay, String> {
        let mut host = CaptureHost::default();
        let mut engine = loaded_engine(rules::agent_files(workloads::LLSF_STRATEGY), &mut host)?;
        engine
            .reset(&mut host)
            .map_err(|e| engine_error("(reset)", e, &host))?;
        for fact in &trace.agent_setup {
            engine
                .assert_str(&mut host, fact)
                .map_err(|e| engine_error(fact, e, &host))?;
        }
        engine
            .run(&mut host, None)
            .map_err(|e| engine_error("first (run)", e, &host))?;
        Ok(Replay { engine, host })
    }

    /// Replays the game's decisions; with `check`, compares every request with the
    /// recorded one (not timed: it walks the fact list).
    fn decisions(&mut self, trace: &GameTrace, check: bool) -> Result<Vec<Decision>, String> {
        if check {
            self.expect_request(trace, 0)?;
        }
        let mut out = Vec::new();
        for (i, outcome) in trace.outcomes.iter().enumerate() {
            // The last outcome of a game may end it (no request follows): not a decision.
            if i + 1 >= trace.requests.len() {
                break;
            }
            let start = Instant::now();
            let fired = decision_step(&mut self.engine, &mut self.host, outcome)?;
            let wall = start.elapsed();
            if check {
                self.expect_request(trace, i + 1)?;
            }
            out.push(Decision { wall, fired });
        }
        self.host.stdout.clear();
        Ok(out)
    }

    fn expect_request(&self, trace: &GameTrace, index: usize) -> Result<(), String> {
        let want = &trace.requests[index];
        let got = last_request(&self.engine);
        if got.as_deref() == Some(want.as_str()) {
            Ok(())
        } else {
            Err(format!(
                "seed {}: replayed agent requested {got:?}, the game had {want}",
                trace.seed
            ))
        }
    }
}

/// Replays every game once; returns all decisions in order.
pub fn replay_all(traces: &[GameTrace], check: bool) -> Result<Vec<Decision>, String> {
    let mut all = Vec::new();
    for trace in traces {
        let mut replay = Replay::start(trace)?;
        all.extend(replay.decisions(trace, check)?);
    }
    Ok(all)
}

/// What the report shows about decisions.
#[derive(Clone, Debug)]
pub struct DecisionReport {
    pub games: usize,
    pub decisions: usize,
    pub fired_median: u32,
    pub fired_max: u32,
    pub wall_median: Duration,
    pub wall_p90: Duration,
    pub wall_max: Duration,
    pub reps: usize,
    /// Per-decision instruction counts (median, p90, max, mean) or why there are none.
    pub instructions: Result<InstrSummary, String>,
}

#[derive(Clone, Copy, Debug)]
pub struct InstrSummary {
    pub median: u64,
    pub p90: u64,
    pub max: u64,
    pub mean: u64,
}

fn percentile<T: Copy + Ord>(values: &[T], pct: usize) -> Option<T> {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    let last = sorted.len().checked_sub(1)?;
    sorted.get(last * pct / 100).copied()
}

/// Records the games, checks the replay once, then times `reps` replays (the first is a
/// warm-up and not counted) and counts instructions in a child under callgrind.
pub fn measure(
    games: usize,
    reps: usize,
    callgrind: Option<(Duration, &Path)>,
) -> Result<DecisionReport, String> {
    let traces = record(games)?;
    let checked = replay_all(&traces, true)?;
    if checked.is_empty() {
        return Err("the games made no decisions".to_string());
    }
    let mut walls = Vec::new();
    for rep in 0..=reps.max(1) {
        let timed = replay_all(&traces, false)?;
        if rep > 0 {
            walls.extend(timed.iter().map(|d| d.wall));
        }
    }
    let fired: Vec<u32> = checked.iter().map(|d| d.fired).collect();
    let instructions = match callgrind {
        Some((limit, scratch)) => count_instructions(games, limit, scratch),
        None => Err("not measured: --no-callgrind".to_string()),
    };
    Ok(DecisionReport {
        games,
        decisions: checked.len(),
        fired_median: percentile(&fired, 50).unwrap_or(0),
        fired_max: fired.iter().copied().max().unwrap_or(0),
        wall_median: median(&walls).unwrap_or_default(),
        wall_p90: percentile(&walls, 90).unwrap_or_default(),
        wall_max: walls.iter().copied().max().unwrap_or_default(),
        reps: reps.max(1),
        instructions,
    })
}

/// The child's work: record and replay once (checked), so callgrind sees exactly the
/// replayed `decision_step` calls. Prints the number of decisions.
pub fn child_main(games: usize) -> Result<(), String> {
    let traces = record(games)?;
    let decisions = replay_all(&traces, true)?;
    println!("decisions {}", decisions.len());
    Ok(())
}

/// Runs `robotino-agent bench --decision-child GAMES` under callgrind with collection
/// only inside `decision_step`, one dump per call; reads each dump's `totals:`.
fn count_instructions(
    games: usize,
    limit: Duration,
    scratch: &Path,
) -> Result<InstrSummary, String> {
    let dir = scratch.join("decision-callgrind");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let this = std::env::current_exe().map_err(|e| format!("locating robotino-agent: {e}"))?;
    let mut command = Command::new("valgrind");
    command
        .arg("--tool=callgrind")
        .arg("--collect-atstart=no")
        .arg("--toggle-collect=*decision_step*")
        // Dump triggers need the exact name (wildcards only work for the toggle).
        .arg("--dump-after=robotino_agent::bench::decision::decision_step")
        .arg(format!("--callgrind-out-file={}/cg.out", dir.display()))
        .arg(&this)
        .args(["bench", "--decision-child", &games.to_string()]);
    let finished = run_with_deadline(&mut command, limit).map_err(|e| e.to_string())?;
    if finished.timed_out {
        return Err(format!(
            "callgrind time-box of {} s exceeded",
            limit.as_secs()
        ));
    }
    if !finished.status.success() {
        let last = finished.stderr.lines().last().unwrap_or("");
        return Err(format!(
            "decision child under callgrind: {} {last}",
            finished.status
        ));
    }
    let expected: usize = finished
        .stdout
        .lines()
        .find_map(|l| l.strip_prefix("decisions ")?.trim().parse().ok())
        .ok_or_else(|| "decision child printed no count".to_string())?;
    let mut counts = Vec::new();
    let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries.flatten() {
        let text = std::fs::read_to_string(entry.path()).unwrap_or_default();
        // Dumps are triggered by leaving decision_step; the final dump at exit holds
        // nothing collected (collection is off outside the function).
        if let Some(total) = dump_total(&text) {
            if total > 0 {
                counts.push(total);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    if counts.len() != expected {
        return Err(format!(
            "{} callgrind dumps with instructions for {expected} decisions",
            counts.len()
        ));
    }
    let sum: u64 = counts.iter().sum();
    Ok(InstrSummary {
        median: percentile(&counts, 50).unwrap_or(0),
        p90: percentile(&counts, 90).unwrap_or(0),
        max: counts.iter().copied().max().unwrap_or(0),
        mean: sum / counts.len().max(1) as u64,
    })
}

/// The `totals:` (or `summary:`) figure of one callgrind dump.
pub fn dump_total(text: &str) -> Option<u64> {
    text.lines().find_map(|line| {
        let rest = line
            .strip_prefix("totals:")
            .or_else(|| line.strip_prefix("summary:"))?;
        rest.split_whitespace().next()?.parse().ok()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watch_facts_lines_give_the_fact_text() {
        let line = "==> f-57    (skill-outcome (id 3) (status FINAL) (light green) (info none))";
        assert_eq!(
            asserted_fact(line, "skill-outcome"),
            Some("(skill-outcome (id 3) (status FINAL) (light green) (info none))")
        );
        assert_eq!(asserted_fact(line, "skill-request"), None);
        assert_eq!(
            asserted_fact("<== f-57    (skill-outcome (id 3))", "skill-outcome"),
            None
        );
        assert_eq!(dump_total("events: Ir\ntotals: 12345\n"), Some(12345));
        assert_eq!(dump_total("summary: 77\n"), Some(77));
        assert_eq!(percentile(&[5, 1, 3, 2, 4], 50), Some(3));
    }

    /// The agent alone, fed the recorded outcomes, makes the same requests as in the
    /// whole game (the replay checks each one).
    #[test]
    fn replayed_agent_makes_the_recorded_requests() {
        let decisions = crate::sim::game::with_engine_stack(|| {
            let traces = record(2)?;
            replay_all(&traces, true)
        })
        .expect("engine thread runs")
        .expect("replay matches the recorded games");
        assert!(decisions.len() > 20, "{} decisions", decisions.len());
        assert!(decisions.iter().all(|d| d.fired > 0));
    }
}
