//! Nothing lost on restart: `sim --snapshot FILE` and `sim --resume FILE`.
//!
//! With a `(snapshot-file "FILE")` fact, rules/snapshot.clp saves the whole
//! fact base with `save-facts` after every logged decision and then prints a
//! `SNAPSHOT n FILE` line. The engine's file callback lands here: the facts
//! are collected in memory and, on the marker line, written to `FILE.tmp` and
//! renamed over `FILE`, so a process killed at any moment leaves the last
//! complete snapshot behind (never a half-written one).
//!
//! In `sim` one engine holds the agent and the referee, so the snapshot holds
//! both: the agent's beliefs (machine types and contents, what it holds, the
//! next skill id) and the referee's ground truth, the simulated robot and the
//! decision log, all at the same decision. A resumed run loads the rules,
//! replaces the facts of `(reset)` with the snapshot's and runs on: the
//! referee resumes from the same snapshot as the agent.

use std::path::{Path, PathBuf};
use std::time::Duration;

use rules::setup::{GameSetup, MachineType, ProcessingTimes, MACHINE_COUNT};
use rules::Strategy;

use super::game::SimError;
use super::replay::parse_type;

/// The line snapshot.clp prints once a snapshot is complete.
pub const MARKER: &str = "SNAPSHOT ";

/// Where snapshots go, and the one being written.
#[derive(Debug)]
pub struct SnapshotSink {
    path: PathBuf,
    /// The path as the rules name it (`save-facts` hands it back to us).
    clips_path: String,
    pending: String,
    /// Wall-clock pause after each snapshot (`--pace-ms`): makes a game last
    /// long enough to be killed in the middle, as a real robot's would.
    pace: Duration,
    /// Snapshots written so far.
    pub saved: u32,
    /// The first write that failed (reported after the run).
    pub error: Option<String>,
}

impl SnapshotSink {
    /// A sink for `path`; fails on paths CLIPS strings cannot hold.
    pub fn new(path: &Path, pace: Duration) -> Result<SnapshotSink, SimError> {
        let clips_path = path
            .to_str()
            .filter(|p| !p.contains(['"', '\\']))
            .ok_or_else(|| {
                SimError::Input(format!(
                    "snapshot path {}: must be UTF-8 without quotes or backslashes",
                    path.display()
                ))
            })?
            .to_string();
        Ok(SnapshotSink {
            path: path.to_path_buf(),
            clips_path,
            pending: String::new(),
            pace,
            saved: 0,
            error: None,
        })
    }

    /// The fact that switches snapshots on.
    pub fn fact(&self) -> String {
        format!("(snapshot-file \"{}\")", self.clips_path)
    }

    /// `save-facts` writing to our path: collect.
    pub fn accepts(&self, path: &str) -> bool {
        path == self.clips_path
    }

    pub fn write(&mut self, data: &[u8], append: bool) {
        if !append {
            self.pending.clear();
        }
        self.pending.push_str(&String::from_utf8_lossy(data));
    }

    /// The marker line arrived: the snapshot is complete; replace the file.
    pub fn commit(&mut self) {
        let tmp = self.path.with_extension("tmp");
        let written =
            std::fs::write(&tmp, &self.pending).and_then(|()| std::fs::rename(&tmp, &self.path));
        match written {
            Ok(()) => self.saved += 1,
            Err(e) => {
                self.error.get_or_insert(format!(
                    "cannot write the snapshot {}: {e}",
                    self.path.display()
                ));
            }
        }
        if !self.pace.is_zero() {
            std::thread::sleep(self.pace);
        }
    }
}

/// A snapshot read back: its facts, one per line, and what the host needs
/// to play on.
#[derive(Clone, Debug)]
pub struct Snapshot {
    pub facts: Vec<String>,
    pub strategy: Strategy,
    /// The setup, rebuilt from the setup facts (for the report; faults are
    /// in the facts but not listed here).
    pub setup: GameSetup,
    /// The last decision saved.
    pub decision: u32,
}

/// `(name X)` inside a fact line.
fn slot_word<'a>(line: &'a str, slot: &str) -> Option<&'a str> {
    let start = line.find(&format!("({slot} "))? + slot.len() + 2;
    let rest = &line[start..];
    Some(rest[..rest.find(')')?].trim())
}

/// The single field of an ordered fact line `(name X)`.
fn ordered_value<'a>(line: &'a str, name: &str) -> Option<&'a str> {
    line.strip_prefix(&format!("({name} "))?
        .strip_suffix(')')
        .map(str::trim)
}

fn tenths(word: Option<&str>) -> Option<u32> {
    let seconds: f64 = word?.parse().ok()?;
    Some((seconds * 10.0).round() as u32)
}

/// Parses a snapshot file written through [`SnapshotSink`].
pub fn parse(text: &str) -> Result<Snapshot, SimError> {
    let bad = |what: &str| SimError::Input(format!("not a usable snapshot: {what}"));
    let facts: Vec<String> = text
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with('('))
        .map(str::to_string)
        .collect();
    let mut strategy = None;
    let mut assignment: [Option<MachineType>; MACHINE_COUNT] = [None; MACHINE_COUNT];
    let mut setup = GameSetup::new([MachineType::T1; MACHINE_COUNT]);
    let mut decision = 0;
    for line in &facts {
        if let Some(name) = ordered_value(line, "agent-strategy") {
            strategy = Some(Strategy::from_name(name).ok_or_else(|| bad("unknown strategy"))?);
        } else if let Some(n) = ordered_value(line, "snapshot-saved") {
            decision = n
                .parse()
                .map_err(|_| bad("snapshot-saved is not a number"))?;
        } else if let Some(n) = ordered_value(line, "s0-supply") {
            setup.s0_supply = n.parse().map_err(|_| bad("s0-supply is not a number"))?;
        } else if let Some(gate) = ordered_value(line, "active-gate") {
            setup.active_gate = gate
                .strip_prefix('D')
                .and_then(|g| g.parse().ok())
                .ok_or_else(|| bad("active-gate is not D1..D3"))?;
        } else if line.starts_with("(rf-machine ") {
            let index: usize = slot_word(line, "name")
                .and_then(|n| n.strip_prefix('M'))
                .and_then(|n| n.parse().ok())
                .filter(|i| (1..=MACHINE_COUNT).contains(i))
                .ok_or_else(|| bad("rf-machine without a name M1..M10"))?;
            assignment[index - 1] = Some(
                slot_word(line, "type")
                    .and_then(parse_type)
                    .ok_or_else(|| bad("rf-machine without a type"))?,
            );
        } else if line.starts_with("(rf-times ") {
            setup.times = ProcessingTimes {
                t1_tenths: tenths(slot_word(line, "t1")).ok_or_else(|| bad("rf-times t1"))?,
                t2_tenths: tenths(slot_word(line, "t2")).ok_or_else(|| bad("rf-times t2"))?,
                t3_tenths: tenths(slot_word(line, "t3")).ok_or_else(|| bad("rf-times t3"))?,
                per_input_tenths: tenths(slot_word(line, "per-input"))
                    .ok_or_else(|| bad("rf-times per-input"))?,
            };
        } else if line.starts_with("(game-clock ") {
            let limit = tenths(slot_word(line, "limit")).ok_or_else(|| bad("game-clock"))?;
            setup.clock_limit_s = match slot_word(line, "enabled") {
                Some("FALSE") => None,
                _ => Some(limit / 10),
            };
        }
    }
    for (slot, found) in setup.assignment.iter_mut().zip(assignment) {
        *slot = found.ok_or_else(|| bad("an rf-machine fact is missing"))?;
    }
    Ok(Snapshot {
        facts,
        strategy: strategy.ok_or_else(|| bad("no (agent-strategy ...) fact"))?,
        setup,
        decision,
    })
}

/// The machine beliefs of snapshot fact lines, M1..M10, as `T2_3+S0`
/// symbols (the decision log's format).
pub fn machine_beliefs(facts: &[String]) -> Vec<String> {
    let mut beliefs = vec![String::new(); MACHINE_COUNT];
    for line in facts.iter().filter(|l| l.starts_with("(machine ")) {
        let Some(index) = slot_word(line, "index").and_then(|i| i.parse::<usize>().ok()) else {
            continue;
        };
        let Some(slot) = index.checked_sub(1).and_then(|i| beliefs.get_mut(i)) else {
            continue;
        };
        let mut belief = slot_word(line, "mtype").unwrap_or("?").to_string();
        for puck in slot_word(line, "loaded-with")
            .unwrap_or("")
            .split_whitespace()
        {
            belief.push('+');
            belief.push_str(puck);
        }
        *slot = belief;
    }
    beliefs
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "(initial-fact)\n\
        (agent-strategy travel)\n\
        (rf-machine (name M1) (type T3) (loaded-with S0) (junk 0) (productions 0))\n\
        (machine (name M1) (index 1) (mtype T2_3) (loaded-with S0 S1) (junk 0) (productions 0))\n\
        (machine (name M2) (index 2) (mtype T1) (loaded-with) (junk 0) (productions 2))\n\
        (snapshot-saved 7)\n";

    #[test]
    fn beliefs_read_like_the_decision_log() {
        let snap_facts: Vec<String> = TEXT.lines().map(str::to_string).collect();
        let b = machine_beliefs(&snap_facts);
        assert_eq!(b[0], "T2_3+S0+S1");
        assert_eq!(b[1], "T1");
        assert_eq!(b[2], "");
    }

    #[test]
    fn a_snapshot_without_every_machine_is_refused() {
        let err = parse(TEXT).expect_err("nine rf-machine facts are missing");
        assert!(err.to_string().contains("rf-machine"), "{err}");
    }

    #[test]
    fn slot_words_and_ordered_values() {
        assert_eq!(slot_word("(a (name M3) (x 1))", "name"), Some("M3"));
        assert_eq!(slot_word("(a (loaded-with) (x 1))", "loaded-with"), None);
        assert_eq!(ordered_value("(s0-supply 20)", "s0-supply"), Some("20"));
        assert_eq!(tenths(Some("5.5")), Some(55));
    }
}
