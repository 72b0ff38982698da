//! The readable report of one game (`robotino-agent sim`).

use std::fmt::Write;

use rules::setup::MachineType;

use super::record::GameRecord;

/// When the agent first believed a machine's exact type.
#[derive(Clone, Debug, PartialEq)]
pub struct Learned {
    /// 0-based machine index (M1 is 0).
    pub machine: usize,
    pub belief: String,
    pub time: f64,
    pub decision: u32,
}

/// The type part of a belief symbol: `T2_3+S0` -> `T2_3`.
fn belief_type(belief: &str) -> &str {
    belief.split('+').next().unwrap_or(belief)
}

/// For every machine, the first decision after which its belief was an exact
/// type (T1, T2 or T3); `None` if the agent never pinned it down.
pub fn types_learned(record: &GameRecord) -> Vec<Option<Learned>> {
    let mut learned: Vec<Option<Learned>> = vec![None; record.setup.assignment.len()];
    for d in &record.decisions {
        for (machine, belief) in d.beliefs.iter().enumerate() {
            let kind = belief_type(belief);
            let exact = matches!(kind, "T1" | "T2" | "T3");
            if let Some(slot) = learned.get_mut(machine) {
                if exact && slot.is_none() {
                    *slot = Some(Learned {
                        machine,
                        belief: kind.to_string(),
                        time: d.time,
                        decision: d.n,
                    });
                }
            }
        }
    }
    learned
}

fn type_name(t: MachineType) -> &'static str {
    t.as_str()
}

/// Writes the whole report; `title` says which game it is (seed, assignment).
pub fn render(record: &GameRecord, title: &str) -> String {
    let mut out = String::new();
    let setup = &record.setup;
    let _ = writeln!(
        out,
        "robotino-agent sim: {title}, strategy {}",
        record.strategy.name()
    );
    let assignment: Vec<String> = setup
        .assignment
        .iter()
        .enumerate()
        .map(|(i, t)| format!("M{} {}", i + 1, type_name(*t)))
        .collect();
    let _ = writeln!(out, "assignment: {}", assignment.join(", "));
    let t = &setup.times;
    let clock = match setup.clock_limit_s {
        Some(s) => format!("{s} s"),
        None => "off".to_string(),
    };
    let _ = writeln!(
        out,
        "field: active gate D{}, {} S0, clock {clock}, processing T1 {:.1} s, T2 {:.1} s, T3 {:.1} s, {:.1} s per input",
        setup.active_gate,
        setup.s0_supply,
        f64::from(t.t1_tenths) / 10.0,
        f64::from(t.t2_tenths) / 10.0,
        f64::from(t.t3_tenths) / 10.0,
        f64::from(t.per_input_tenths) / 10.0
    );
    for fault in setup.faults() {
        let _ = writeln!(
            out,
            "fault: {} at decision {}",
            fault.kind.as_str(),
            fault.at_decision
        );
    }
    if let Some(rate) = setup.fault_rate {
        let hits: Vec<String> = setup
            .all_faults()
            .filter(|f| f.at_decision as usize <= record.decisions.len())
            .map(|f| f.at_decision.to_string())
            .collect();
        let _ = writeln!(
            out,
            "faults: {} % per decision (seed {}); decisions hit: {}",
            rate.percent,
            rate.seed,
            if hits.is_empty() {
                "none".to_string()
            } else {
                hits.join(" ")
            }
        );
    }
    let _ = writeln!(
        out,
        "\ndecisions (time = game seconds when the skill ended; beliefs M1..M10 afterwards):"
    );
    let _ = writeln!(
        out,
        "{:>4} {:>7}  {:<14} {:<6} {:<4} {:<6} {:<15} {:<7} {:>4}  beliefs",
        "n", "time", "action", "target", "puck", "status", "light", "holds", "pts"
    );
    for d in &record.decisions {
        let _ = writeln!(
            out,
            "{:>4} {:>7.1}  {:<14} {:<6} {:<4} {:<6} {:<15} {:<7} {:>4}  {}",
            d.n,
            d.time,
            d.action,
            d.target,
            d.puck,
            d.status,
            d.light,
            d.holding,
            d.points,
            d.beliefs.join(" ")
        );
    }
    let _ = writeln!(out, "\nmachine types learned:");
    for (i, learned) in types_learned(record).iter().enumerate() {
        let truth = setup
            .assignment
            .get(i)
            .map(|t| type_name(*t))
            .unwrap_or("?");
        match learned {
            Some(l) => {
                let verdict = if l.belief == truth {
                    String::new()
                } else {
                    format!("  (WRONG: truth is {truth})")
                };
                let _ = writeln!(
                    out,
                    "  M{:<2} {} at {:>6.1} s (decision {}){verdict}",
                    i + 1,
                    l.belief,
                    l.time,
                    l.decision
                );
            }
            None => {
                let _ = writeln!(out, "  M{:<2} never known exactly (truth {truth})", i + 1);
            }
        }
    }
    let s = &record.score;
    let _ = writeln!(
        out,
        "\nproducts: S1 {}, S2 {}, P {} (delivered {}, at a wrong gate {}); pucks lost {}, discarded {}, junk recycled {}",
        s.s1, s.s2, s.p, s.delivered, s.wrong_gate, s.lost, s.discarded, s.recycled
    );
    let _ = writeln!(out, "travel: {:.1} m", record.travelled);
    let _ = writeln!(
        out,
        "end: {} at {:.1} s after {} decisions ({} rules fired)",
        record.end.name(),
        record.end_time,
        record.decisions.len(),
        record.fired
    );
    let _ = writeln!(out, "points: {}", s.points);
    let _ = writeln!(out, "{}", record.result_line());
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::record::{Decision, EndReason, Score};
    use rules::setup::{assignment_by_index, GameSetup};
    use rules::Strategy;

    fn decision(n: u32, time: f64, beliefs: &[&str]) -> Decision {
        Decision {
            n,
            time,
            action: "finish-puck-at".into(),
            target: "M1".into(),
            puck: "S0".into(),
            status: "FINAL".into(),
            light: "green".into(),
            holding: "S1".into(),
            beliefs: beliefs.iter().map(|b| b.to_string()).collect(),
            points: 0,
        }
    }

    #[test]
    fn a_type_counts_as_learned_at_the_first_exact_belief() {
        let setup = GameSetup::new(assignment_by_index(0).expect("index 0 exists"));
        let mut first = vec!["T1_2_3"; 10];
        first[0] = "T2_3+S0";
        let mut second = first.clone();
        second[0] = "T2";
        second[1] = "T1";
        let record = GameRecord {
            setup,
            strategy: Strategy::Paper,
            decisions: vec![
                decision(1, 10.0, &first),
                decision(2, 30.5, &second),
                decision(3, 50.0, &second),
            ],
            score: Score::default(),
            end: EndReason::Done,
            end_time: 50.0,
            travelled: 0.0,
            fired: 0,
            output: String::new(),
        };
        let learned = types_learned(&record);
        let m1 = learned[0].as_ref().expect("M1 became known");
        assert_eq!((m1.belief.as_str(), m1.decision, m1.time), ("T2", 2, 30.5));
        assert!(learned[2].is_none());
        // Assignment #0 has T1 on M1..M4: the report flags the wrong T2 belief.
        let text = render(&record, "test");
        assert!(
            text.contains("M1  T2 at   30.5 s (decision 2)  (WRONG: truth is T1)"),
            "{text}"
        );
        assert!(text.contains("M2  T1 at   30.5 s (decision 2)\n"), "{text}");
    }
}
