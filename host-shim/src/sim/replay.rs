//! Game logs: `sim --log FILE` writes the setup and every decision as text;
//! `sim --replay FILE` plays the setup again and checks that the agent makes
//! the same decisions (the paper's replay of interesting scenarios).

use std::fmt::Write;

use rules::setup::{
    Assignment, Fault, FaultKind, GameSetup, MachineType, ProcessingTimes, MACHINE_COUNT,
};
use rules::Strategy;

use super::game::SimError;
use super::record::GameRecord;

const HEADER: &str = "# robotino-agent game log v1";

/// A parsed game log: what to play and what was decided.
#[derive(Clone, Debug, PartialEq)]
pub struct GameLog {
    pub strategy: Strategy,
    pub setup: GameSetup,
    /// `Decision::log_line` of every decision, in order.
    pub decisions: Vec<String>,
    /// `GameRecord::result_line`.
    pub result: String,
}

/// Writes the log text of a played game.
pub fn write_log(record: &GameRecord) -> String {
    let mut out = String::new();
    let s = &record.setup;
    let _ = writeln!(out, "{HEADER}");
    let _ = writeln!(out, "strategy {}", record.strategy.name());
    let types: Vec<&str> = s.assignment.iter().map(|t| t.as_str()).collect();
    let _ = writeln!(out, "assignment {}", types.join(" "));
    let t = &s.times;
    let _ = writeln!(
        out,
        "times-tenths {} {} {} {}",
        t.t1_tenths, t.t2_tenths, t.t3_tenths, t.per_input_tenths
    );
    let _ = writeln!(out, "s0 {}", s.s0_supply);
    let _ = writeln!(out, "gate {}", s.active_gate);
    match s.clock_limit_s {
        Some(limit) => {
            let _ = writeln!(out, "clock {limit}");
        }
        None => {
            let _ = writeln!(out, "clock off");
        }
    }
    for f in s.faults() {
        let _ = writeln!(
            out,
            "fault {} {} {}",
            f.at_decision,
            f.kind.as_str(),
            f.draw
        );
    }
    if let Some(rate) = s.fault_rate {
        let _ = writeln!(out, "fault-rate {} {}", rate.percent, rate.seed);
    }
    for d in &record.decisions {
        let _ = writeln!(out, "decision {}", d.log_line());
    }
    let _ = writeln!(out, "result {}", record.result_line());
    out
}

fn bad(line_no: usize, what: &str) -> SimError {
    SimError::Input(format!("game log line {line_no}: {what}"))
}

fn number<T: std::str::FromStr>(
    line_no: usize,
    word: Option<&str>,
    what: &str,
) -> Result<T, SimError> {
    word.and_then(|w| w.parse().ok())
        .ok_or_else(|| bad(line_no, &format!("expected {what}")))
}

/// Parses a machine type name (`T1`, `T2`, `T3`).
pub fn parse_type(name: &str) -> Option<MachineType> {
    match name {
        "T1" => Some(MachineType::T1),
        "T2" => Some(MachineType::T2),
        "T3" => Some(MachineType::T3),
        _ => None,
    }
}

/// Parses ten machine types into an assignment.
pub fn parse_assignment<'a>(words: impl Iterator<Item = &'a str>) -> Result<Assignment, String> {
    let types: Vec<&str> = words.collect();
    if types.len() != MACHINE_COUNT {
        return Err(format!(
            "an assignment names {MACHINE_COUNT} machine types, got {}",
            types.len()
        ));
    }
    let mut out = [MachineType::T1; MACHINE_COUNT];
    for (slot, name) in out.iter_mut().zip(types) {
        *slot = parse_type(name)
            .ok_or_else(|| format!("unknown machine type {name:?} (T1, T2 or T3)"))?;
    }
    Ok(out)
}

/// Parses a game log written by [`write_log`].
pub fn parse_log(text: &str) -> Result<GameLog, SimError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    match lines.next() {
        Some((_, HEADER)) => {}
        _ => {
            return Err(SimError::Input(format!(
                "not a game log: the first line must be {HEADER:?}"
            )))
        }
    }
    let mut strategy = None;
    let mut setup: Option<GameSetup> = None;
    let mut times = ProcessingTimes::MIDPOINTS;
    let (mut s0, mut gate, mut clock) = (20, 1, Some(900));
    let mut faults = Vec::new();
    let mut fault_rate: Option<(u32, u64)> = None;
    let mut decisions = Vec::new();
    let mut result = None;
    for (no, line) in lines {
        let (key, rest) = line.split_once(' ').unwrap_or((line, ""));
        let mut words = rest.split_whitespace();
        match key {
            "strategy" => {
                strategy = Some(
                    Strategy::from_name(rest.trim()).ok_or_else(|| bad(no, "unknown strategy"))?,
                )
            }
            "assignment" => {
                setup = Some(GameSetup::new(
                    parse_assignment(words).map_err(|e| bad(no, &e))?,
                ))
            }
            "times-tenths" => {
                times = ProcessingTimes {
                    t1_tenths: number(no, words.next(), "T1 tenths")?,
                    t2_tenths: number(no, words.next(), "T2 tenths")?,
                    t3_tenths: number(no, words.next(), "T3 tenths")?,
                    per_input_tenths: number(no, words.next(), "per-input tenths")?,
                }
            }
            "s0" => s0 = number(no, words.next(), "the S0 supply")?,
            "gate" => gate = number(no, words.next(), "the gate number")?,
            "clock" => {
                clock = if rest.trim() == "off" {
                    None
                } else {
                    Some(number(no, words.next(), "seconds or off")?)
                }
            }
            "fault" => {
                let at_decision = number(no, words.next(), "the decision number")?;
                let kind = words
                    .next()
                    .and_then(FaultKind::from_name)
                    .ok_or_else(|| bad(no, "expected a fault kind (lose-puck, drive-fail, grab-fail, wrong-light, drawn)"))?;
                // Logs before draws existed end here: draw 0.
                let draw = match words.next() {
                    Some(w) => number(no, Some(w), "the fault's draw")?,
                    None => 0,
                };
                faults.push(Fault {
                    at_decision,
                    kind,
                    draw,
                });
            }
            "fault-rate" => {
                fault_rate = Some((
                    number(no, words.next(), "the fault rate in %")?,
                    number(no, words.next(), "the fault seed")?,
                ))
            }
            "decision" => decisions.push(rest.to_string()),
            "result" => result = Some(rest.to_string()),
            "" => {}
            _ if key.starts_with('#') => {}
            other => return Err(bad(no, &format!("unknown entry {other:?}"))),
        }
    }
    let strategy =
        strategy.ok_or_else(|| SimError::Input("game log without a strategy line".into()))?;
    let mut setup =
        setup.ok_or_else(|| SimError::Input("game log without an assignment line".into()))?;
    setup.times = times;
    setup.s0_supply = s0;
    setup.active_gate = gate;
    setup.clock_limit_s = clock;
    for f in faults {
        setup
            .add_fault(f)
            .map_err(|e| SimError::Input(e.to_string()))?;
    }
    if let Some((percent, seed)) = fault_rate {
        setup = setup.with_fault_rate(percent, seed);
    }
    let result = result.ok_or_else(|| SimError::Input("game log without a result line".into()))?;
    Ok(GameLog {
        strategy,
        setup,
        decisions,
        result,
    })
}

/// Compares a replayed game with its log: `Ok(())` when every decision and
/// the result are the same, else the first difference in words.
pub fn verify(log: &GameLog, replayed: &GameRecord) -> Result<(), String> {
    let now: Vec<String> = replayed.decisions.iter().map(|d| d.log_line()).collect();
    for (i, (was, is)) in log.decisions.iter().zip(&now).enumerate() {
        if was != is {
            return Err(format!(
                "decision {} differs:\n  logged:   {was}\n  replayed: {is}",
                i + 1
            ));
        }
    }
    if log.decisions.len() != now.len() {
        return Err(format!(
            "the log has {} decisions, the replay made {}",
            log.decisions.len(),
            now.len()
        ));
    }
    let result = replayed.result_line();
    if log.result != result {
        return Err(format!(
            "the result differs:\n  logged:   {}\n  replayed: {result}",
            log.result
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::record::{Decision, EndReason, Score};

    fn record() -> GameRecord {
        let mut setup = GameSetup::for_seed(3)
            .with_seeded_times(3)
            .with_fault_rate(10, 3);
        setup.clock_limit_s = None;
        setup.active_gate = 3;
        setup
            .add_fault(Fault {
                at_decision: 4,
                kind: FaultKind::DriveFail,
                draw: 0,
            })
            .expect("room for a fault");
        let decision = |n: u32, light: &str| Decision {
            n,
            time: 12.25 * f64::from(n),
            action: "finish-puck-at".into(),
            target: "M3".into(),
            puck: "S0".into(),
            status: "FINAL".into(),
            light: light.into(),
            holding: "NONE".into(),
            beliefs: vec!["T1_2_3".to_string(); MACHINE_COUNT],
            points: 0,
        };
        GameRecord {
            setup,
            strategy: Strategy::Travel,
            decisions: vec![decision(1, "yellow"), decision(2, "green")],
            score: Score {
                points: 4,
                s2: 1,
                ..Score::default()
            },
            end: EndReason::Done,
            end_time: 24.5,
            travelled: 3.0,
            fired: 40,
            output: String::new(),
        }
    }

    #[test]
    fn a_written_log_parses_back_to_the_same_game() {
        let r = record();
        let log = parse_log(&write_log(&r)).expect("our own log parses");
        assert_eq!(log.strategy, Strategy::Travel);
        assert_eq!(log.setup, r.setup);
        assert_eq!(log.decisions.len(), 2);
        assert_eq!(verify(&log, &r), Ok(()));
    }

    #[test]
    fn verify_names_the_first_different_decision() {
        let r = record();
        let log = parse_log(&write_log(&r)).expect("our own log parses");
        let mut other = r.clone();
        other.decisions[1].light = "yellow-flashing".into();
        let diff = verify(&log, &other).expect_err("the light differs");
        assert!(diff.starts_with("decision 2 differs"), "{diff}");
        other.decisions.truncate(1);
        other.decisions[0] = r.decisions[0].clone();
        let diff = verify(&log, &other).expect_err("one decision is missing");
        assert!(
            diff.contains("has 2 decisions, the replay made 1"),
            "{diff}"
        );
    }

    #[test]
    fn malformed_logs_are_errors_with_the_line() {
        let text = write_log(&record()).replace("gate 3", "gate three");
        let err = parse_log(&text)
            .expect_err("the gate is not a number")
            .to_string();
        assert!(err.contains("line") && err.contains("gate number"), "{err}");
        assert!(parse_assignment("T1 T2".split(' ')).is_err());
    }
}
