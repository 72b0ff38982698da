//! What a played game left behind, read from the engine's facts through the
//! public API (the fact interface is documented in rules/README.md).

use agent_core::{DefaultEngine, FactId, ValueRef};
use rules::setup::{GameSetup, MACHINE_COUNT};
use rules::Strategy;

use super::game::SimError;

/// One `(decision ...)` fact: a committed action and what followed.
#[derive(Clone, Debug, PartialEq)]
pub struct Decision {
    pub n: u32,
    /// Game time when the skill ended, seconds.
    pub time: f64,
    pub action: String,
    pub target: String,
    pub puck: String,
    pub status: String,
    pub light: String,
    /// What the robot holds afterwards.
    pub holding: String,
    /// Machine beliefs M1..M10 afterwards, e.g. `T2_3+S0`.
    pub beliefs: Vec<String>,
    pub points: i64,
}

impl Decision {
    /// One line with every field; the game log and replay compare these.
    pub fn log_line(&self) -> String {
        format!(
            "{} {:.1} {} {} {} {} {} {} {} {}",
            self.n,
            self.time,
            self.action,
            self.target,
            self.puck,
            self.status,
            self.light,
            self.holding,
            self.points,
            self.beliefs.join(" ")
        )
    }
}

/// The `(score ...)` fact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Score {
    pub points: i64,
    pub s1: i64,
    pub s2: i64,
    pub p: i64,
    pub delivered: i64,
    pub wrong_gate: i64,
    pub lost: i64,
    pub discarded: i64,
    /// Junk pucks brought to a recycling unit (2012 recycling).
    pub recycled: i64,
}

/// How the game ended (`game-over` reason), or that the engine stopped
/// without a `game-over` fact (counted as a deadlock: nothing was left to fire).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndReason {
    Time,
    Done,
    Deadlock,
    /// The agenda ran empty (or the fire limit was hit) with no `game-over`.
    Stalled,
}

impl EndReason {
    pub fn name(self) -> &'static str {
        match self {
            EndReason::Time => "time",
            EndReason::Done => "done",
            EndReason::Deadlock => "deadlock",
            EndReason::Stalled => "stalled",
        }
    }

    pub fn is_deadlock(self) -> bool {
        matches!(self, EndReason::Deadlock | EndReason::Stalled)
    }
}

/// Everything about one played game.
#[derive(Clone, Debug)]
pub struct GameRecord {
    pub setup: GameSetup,
    pub strategy: Strategy,
    pub decisions: Vec<Decision>,
    pub score: Score,
    pub end: EndReason,
    /// Game time at the end, seconds.
    pub end_time: f64,
    /// Metres the simulated robot drove.
    pub travelled: f64,
    /// Rules fired by `(run)`.
    pub fired: u32,
    /// Everything the engine printed during `(run)` (trace lines included).
    pub output: String,
}

impl GameRecord {
    /// The summary line in the format of rules/clips/report.clp's
    /// `report-game`, so runs in real CLIPS and ours compare as text.
    pub fn result_line(&self) -> String {
        let s = &self.score;
        format!(
            "RESULT points {} s1 {} s2 {} p {} delivered {} lost {} discarded {} recycled {} end {} time {:.1} decisions {} travel {:.1}",
            s.points,
            s.s1,
            s.s2,
            s.p,
            s.delivered,
            s.lost,
            s.discarded,
            s.recycled,
            match self.end {
                EndReason::Stalled => "none",
                other => other.name(),
            },
            self.end_time,
            self.decisions.len(),
            self.travelled
        )
    }
}

fn slot_symbol(engine: &DefaultEngine, id: FactId, slot: &str) -> Result<String, SimError> {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Symbol(s)) | Some(ValueRef::String(s)) => Ok(s.to_string()),
        other => Err(SimError::Facts(format!(
            "slot {slot} of f-{}: expected a symbol, got {other:?}",
            id.0
        ))),
    }
}

fn slot_number(engine: &DefaultEngine, id: FactId, slot: &str) -> Result<f64, SimError> {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Int(i)) => Ok(i as f64),
        Some(ValueRef::Float(x)) => Ok(x),
        other => Err(SimError::Facts(format!(
            "slot {slot} of f-{}: expected a number, got {other:?}",
            id.0
        ))),
    }
}

fn slot_int(engine: &DefaultEngine, id: FactId, slot: &str) -> Result<i64, SimError> {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Int(i)) => Ok(i),
        other => Err(SimError::Facts(format!(
            "slot {slot} of f-{}: expected an integer, got {other:?}",
            id.0
        ))),
    }
}

fn slot_symbols(engine: &DefaultEngine, id: FactId, slot: &str) -> Result<Vec<String>, SimError> {
    let Some(ValueRef::Multi(n)) = engine.fact_slot(id, slot) else {
        return Err(SimError::Facts(format!(
            "slot {slot} of f-{}: expected a multifield",
            id.0
        )));
    };
    (0..n as usize)
        .map(|i| match engine.fact_multislot_item(id, slot, i) {
            Some(ValueRef::Symbol(s)) => Ok(s.to_string()),
            other => Err(SimError::Facts(format!(
                "{slot}[{i}] of f-{}: got {other:?}",
                id.0
            ))),
        })
        .collect()
}

fn read_decision(engine: &DefaultEngine, id: FactId) -> Result<Decision, SimError> {
    let beliefs = slot_symbols(engine, id, "beliefs")?;
    if beliefs.len() != MACHINE_COUNT {
        return Err(SimError::Facts(format!(
            "decision f-{} has {} beliefs",
            id.0,
            beliefs.len()
        )));
    }
    Ok(Decision {
        n: u32::try_from(slot_int(engine, id, "n")?)
            .map_err(|_| SimError::Facts(format!("decision f-{} has a negative n", id.0)))?,
        time: slot_number(engine, id, "time")?,
        action: slot_symbol(engine, id, "action")?,
        target: slot_symbol(engine, id, "target")?,
        puck: slot_symbol(engine, id, "puck")?,
        status: slot_symbol(engine, id, "status")?,
        light: slot_symbol(engine, id, "light")?,
        holding: slot_symbol(engine, id, "holding")?,
        beliefs,
        points: slot_int(engine, id, "points")?,
    })
}

fn read_score(engine: &DefaultEngine, id: FactId) -> Result<Score, SimError> {
    Ok(Score {
        points: slot_int(engine, id, "points")?,
        s1: slot_int(engine, id, "s1")?,
        s2: slot_int(engine, id, "s2")?,
        p: slot_int(engine, id, "p")?,
        delivered: slot_int(engine, id, "delivered")?,
        wrong_gate: slot_int(engine, id, "wrong-gate")?,
        lost: slot_int(engine, id, "lost")?,
        discarded: slot_int(engine, id, "discarded")?,
        recycled: slot_int(engine, id, "recycled")?,
    })
}

/// Reads the decision log (ordered by `n`), score, end of game and travel.
pub fn read_record(
    engine: &DefaultEngine,
    setup: GameSetup,
    strategy: Strategy,
    fired: u32,
    output: String,
) -> Result<GameRecord, SimError> {
    let mut decisions = Vec::new();
    let mut score = None;
    let mut end = None;
    let mut clock_time = 0.0;
    let mut travelled = 0.0;
    for id in engine.facts() {
        match engine.fact_template_name(id) {
            Some("decision") => decisions.push(read_decision(engine, id)?),
            Some("score") => score = Some(read_score(engine, id)?),
            Some("game-over") => {
                let reason = match slot_symbol(engine, id, "reason")?.as_str() {
                    "time" => EndReason::Time,
                    "done" => EndReason::Done,
                    "deadlock" => EndReason::Deadlock,
                    other => return Err(SimError::Facts(format!("game-over reason {other}"))),
                };
                end = Some((reason, slot_number(engine, id, "time")?));
            }
            Some("game-clock") => clock_time = slot_number(engine, id, "time")?,
            Some("sim-robot") => travelled = slot_number(engine, id, "travelled")?,
            _ => {}
        }
    }
    decisions.sort_by_key(|d| d.n);
    let score = score.ok_or_else(|| SimError::Facts("no (score) fact after the game".into()))?;
    let (end, end_time) = end.unwrap_or((EndReason::Stalled, clock_time));
    Ok(GameRecord {
        setup,
        strategy,
        decisions,
        score,
        end,
        end_time,
        travelled,
        fired,
        output,
    })
}
