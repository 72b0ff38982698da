//! What a process-level game did, read back from the lines its processes print (the sim's
//! referee log, bumps and done line; each agent's decisions, skill ends and findings), and
//! the figures `game-sweep` sums: points, collisions, double claims, stalls.

use std::collections::BTreeMap;

/// Simulated cycles per second (the Robotino's behaviour-layer rate, `timing.cycle_hz`).
pub const CYCLE_HZ: f64 = 15.0;
/// A stall: this much game time in which a robot neither starts nor finishes a skill while
/// raw pucks remain.
pub const STALL_S: f64 = 60.0;

fn seconds(cycle: u64) -> f64 {
    cycle as f64 / CYCLE_HZ
}

/// The value of `key=` in a line.
pub fn field<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
}

fn cycle_of(line: &str) -> Option<u64> {
    field(line, "cycle")?.parse().ok()
}

/// How a skill ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    Final,
    Failed,
    /// Still running when the game ended.
    Cut,
}

/// One skill of one robot.
#[derive(Debug, Clone, PartialEq)]
pub struct SkillRun {
    pub robot: u8,
    pub start_s: f64,
    pub end_s: f64,
    /// The rules' name and target, e.g. `finish-puck-at M3`.
    pub name: String,
    pub target: String,
    pub holding: String,
    pub ending: Ending,
    /// The behaviour layer's outcome, e.g. `Final(LightSeen(Green))`, `Failed(Bumper)`.
    pub outcome: String,
}

/// A referee event: an action of a robot and the referee's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct RefereeEvent {
    pub time_s: f64,
    pub robot: u8,
    pub kind: String,
    pub target: String,
    pub puck: String,
    pub status: String,
    pub light: String,
    pub puck_after: String,
    pub score: i64,
}

/// Why the game ended.
#[derive(Debug, Clone, PartialEq)]
pub enum EndReason {
    /// The referee's clock ran out.
    Clock,
    /// The referee ended it early (every robot done, or the referee's own rule).
    Referee,
}

/// A whole process-level game.
#[derive(Debug, Clone, Default)]
pub struct GameRecord {
    pub seed: u64,
    pub robots: u8,
    pub game_seconds: f64,
    pub score: i64,
    pub game_time_s: f64,
    pub skills: Vec<SkillRun>,
    pub referee: Vec<RefereeEvent>,
    /// (time, robot, machine, type) when a robot first learned a machine's type.
    pub learned: Vec<(f64, u8, String, String)>,
    /// (time, robot) when a robot's rules reached DONE.
    pub done: Vec<(f64, u8)>,
    /// (time, robot, what it touched).
    pub bumps: Vec<(f64, u8, String)>,
    pub robot_contacts: u32,
    /// Metres each robot's body drove (1-based robot number - 1).
    pub travel_m: Vec<f64>,
    /// Lines that explain the rules' doubts (`WARN ...`).
    pub warnings: Vec<(u8, String)>,
    /// (robot, game time) of a robot killed mid-game (`game --kill-at-s`).
    pub killed: Vec<(u8, f64)>,
}

impl GameRecord {
    /// Reads the sim's lines and each robot's agent lines (`agents[i]` is robot i+1).
    pub fn parse(seed: u64, game_seconds: f64, sim: &[String], agents: &[Vec<String>]) -> Self {
        let mut g = GameRecord {
            seed,
            robots: agents.len() as u8,
            game_seconds,
            travel_m: vec![0.0; agents.len()],
            ..GameRecord::default()
        };
        for line in sim {
            if let Some(rest) = line.split(" referee ").nth(1) {
                if let Some(e) = parse_referee(rest) {
                    g.referee.push(e);
                }
            } else if line.contains(" bump robot=") {
                let (Some(c), Some(r)) = (cycle_of(line), field(line, "robot")) else {
                    continue;
                };
                g.bumps.push((
                    seconds(c),
                    r.parse().unwrap_or(0),
                    field(line, "with").unwrap_or("?").to_string(),
                ));
            } else if line.starts_with("robotino-sim: travel ") {
                if let (Some(r), Some(m)) = (
                    field(line, "robot").and_then(|r| r.parse::<usize>().ok()),
                    field(line, "m").and_then(|m| m.parse::<f64>().ok()),
                ) {
                    if let Some(t) = g.travel_m.get_mut(r.wrapping_sub(1)) {
                        *t = m;
                    }
                }
            } else if line.starts_with("robotino-sim: done ") {
                g.score = field(line, "score")
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(0);
                g.game_time_s = field(line, "game_time_s")
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(0.0);
                g.robot_contacts = field(line, "robot_contacts")
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(0);
            }
        }
        for (i, lines) in agents.iter().enumerate() {
            let robot = i as u8 + 1;
            let mut open: Option<SkillRun> = None;
            // A robot killed mid-game (`game --kill-at-s`): its skill ends there.
            let mut killed_at: Option<f64> = None;
            for line in lines {
                let Some(c) = cycle_of(line) else {
                    if let Some(w) = line.strip_prefix("WARN ") {
                        g.warnings.push((robot, w.to_string()));
                    }
                    if line.contains(" killed robot ") {
                        killed_at = line.rsplit("t=").next().and_then(|t| t.parse().ok());
                    }
                    continue;
                };
                let t = seconds(c);
                if let Some(rest) = line.split(" (skill-request ").nth(1) {
                    // `ID NAME TARGET holding PUCK)`
                    let w: Vec<&str> = rest.trim_end_matches(')').split_whitespace().collect();
                    if let Some(s) = open.take() {
                        g.skills.push(s);
                    }
                    open = Some(SkillRun {
                        robot,
                        start_s: t,
                        end_s: t,
                        name: w.get(1).copied().unwrap_or("?").to_string(),
                        target: w.get(2).copied().unwrap_or("?").to_string(),
                        holding: w.get(4).copied().unwrap_or("?").to_string(),
                        ending: Ending::Cut,
                        outcome: String::new(),
                    });
                } else if line.contains(" end ") {
                    if let Some(mut s) = open.take() {
                        let outcome = line
                            .split_whitespace()
                            .skip_while(|w| *w != "end")
                            .nth(2)
                            .unwrap_or("")
                            .to_string();
                        s.end_s = t;
                        s.ending = if outcome.starts_with("Failed") {
                            Ending::Failed
                        } else {
                            Ending::Final
                        };
                        s.outcome = outcome;
                        g.skills.push(s);
                    }
                } else if let Some(rest) = line.split(" learned ").nth(1) {
                    let mut w = rest.split_whitespace();
                    if let (Some(m), Some(ty)) = (w.next(), w.next()) {
                        g.learned.push((t, robot, m.to_string(), ty.to_string()));
                    }
                } else if line.contains(" agent DONE") {
                    g.done.push((t, robot));
                }
            }
            if let Some(mut s) = open.take() {
                s.end_s = killed_at.unwrap_or(g.game_time_s).max(s.start_s);
                g.skills.push(s);
            }
            if let Some(t) = killed_at {
                g.killed.push((robot, t));
            }
        }
        g.skills
            .sort_by(|a, b| a.start_s.total_cmp(&b.start_s).then(a.robot.cmp(&b.robot)));
        g
    }

    /// When the input storage ran out of raw pucks (the referee answered `empty`), if it did.
    pub fn storage_empty_s(&self) -> Option<f64> {
        self.referee
            .iter()
            .find(|e| e.kind == "get-s0" && e.status == "empty")
            .map(|e| e.time_s)
    }

    pub fn end_reason(&self) -> EndReason {
        if self.game_time_s + 1.0 >= self.game_seconds {
            EndReason::Clock
        } else {
            EndReason::Referee
        }
    }

    /// Stalls: for each robot, stretches of [`STALL_S`] or more without a skill starting or
    /// ending while raw pucks remained (each stretch counts once). A killed robot is off
    /// the team from its death: only its time before counts.
    pub fn stalls(&self) -> Vec<(u8, f64, f64)> {
        let game_until = self
            .storage_empty_s()
            .unwrap_or(self.game_time_s)
            .min(self.game_time_s);
        let mut out = Vec::new();
        for robot in 1..=self.robots {
            let until = self
                .killed
                .iter()
                .find(|&&(r, _)| r == robot)
                .map_or(game_until, |&(_, t)| t.min(game_until));
            let mut times: Vec<f64> = self
                .skills
                .iter()
                .filter(|s| s.robot == robot)
                .flat_map(|s| [s.start_s, s.end_s])
                .filter(|&t| t <= until)
                .collect();
            times.push(0.0);
            times.push(until);
            times.sort_by(f64::total_cmp);
            for w in times.windows(2) {
                if w[1] - w[0] >= STALL_S {
                    out.push((robot, w[0], w[1]));
                }
            }
        }
        out
    }

    /// Double claims: two robots carrying to (or working) the same machine at once, from
    /// their `finish-puck-at`, `feed` and `collect` skills.
    pub fn double_claims(&self) -> Vec<(String, u8, u8, f64)> {
        let at_machine: Vec<&SkillRun> = self
            .skills
            .iter()
            .filter(|s| matches!(s.name.as_str(), "finish-puck-at" | "feed" | "collect"))
            .collect();
        let mut out = Vec::new();
        for (i, a) in at_machine.iter().enumerate() {
            for b in &at_machine[i + 1..] {
                if a.robot != b.robot
                    && a.target == b.target
                    && a.start_s < b.end_s
                    && b.start_s < a.end_s
                {
                    out.push((a.target.clone(), a.robot, b.robot, a.start_s.max(b.start_s)));
                }
            }
        }
        out
    }

    /// Products delivered: (time, robot, product, score after).
    pub fn deliveries(&self) -> Vec<&RefereeEvent> {
        self.referee
            .iter()
            .filter(|e| e.kind == "deliver" && e.status == "ok")
            .collect()
    }

    /// Each machine's light over time, from the referee's answers: (time, light).
    pub fn machine_lights(&self) -> BTreeMap<String, Vec<(f64, String)>> {
        let mut out: BTreeMap<String, Vec<(f64, String)>> = BTreeMap::new();
        for e in &self.referee {
            if e.kind == "load" && e.light != "none" {
                out.entry(e.target.clone())
                    .or_default()
                    .push((e.time_s, e.light.clone()));
            }
        }
        out
    }
}

/// `t=10.1 robot=1 get-s0 INS NONE -> ok light=none puck=S0 wait=0.0 score=0`
fn parse_referee(rest: &str) -> Option<RefereeEvent> {
    let w: Vec<&str> = rest.split_whitespace().collect();
    let time_s = w.first()?.strip_prefix("t=")?.parse().ok()?;
    let robot = w.get(1)?.strip_prefix("robot=")?.parse().ok()?;
    Some(RefereeEvent {
        time_s,
        robot,
        kind: w.get(2)?.to_string(),
        target: w.get(3)?.to_string(),
        puck: w.get(4)?.to_string(),
        status: w.get(6)?.to_string(),
        light: field(rest, "light")?.to_string(),
        puck_after: field(rest, "puck")?.to_string(),
        score: field(rest, "score")?.parse().ok()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn reads_skills_stalls_and_claims() {
        let sim = lines(&[
            "robotino-sim: cycle=152 referee t=10.1 robot=1 get-s0 INS NONE -> ok light=none puck=S0 wait=0.0 score=0",
            "robotino-sim: cycle=400 bump robot=2 with=M2 at=(3.50,2.13,1.57)",
            "robotino-sim: travel robot=1 m=12.5",
            "robotino-sim: done cycles=13500 game_time_s=900.0 score=4 bumps=1 robot_contacts=0 wall_ms=1",
        ]);
        let a1 = lines(&[
            "robotino-agent run: cycle=2 start GetS0 (skill-request 1 get-s0 INS holding NONE)",
            "robotino-agent run: cycle=180 end GetS0 Final(GotS0) ",
            "robotino-agent run: cycle=181 start BringPuckTo(MachineId(1)) (skill-request 2 finish-puck-at M1 holding S0)",
            "robotino-agent run: cycle=334 end BringPuckTo(MachineId(1)) Failed(Bumper) bumper",
            "robotino-agent run: cycle=335 learned M1 T2",
        ]);
        let a2 = lines(&[
            "robotino-agent run: cycle=300 start BringPuckTo(MachineId(1)) (skill-request 1 finish-puck-at M1 holding S0)",
        ]);
        let g = GameRecord::parse(3, 900.0, &sim, &[a1, a2]);
        assert_eq!(g.skills.len(), 3);
        assert_eq!(g.skills[1].ending, Ending::Failed);
        assert_eq!(g.skills[1].outcome, "Failed(Bumper)");
        assert_eq!(g.skills[2].ending, Ending::Cut);
        assert_eq!(g.score, 4);
        assert_eq!(g.travel_m, vec![12.5, 0.0]);
        assert_eq!(g.learned, vec![(335.0 / 15.0, 1, "M1".into(), "T2".into())]);
        assert_eq!(g.end_reason(), EndReason::Clock);
        // Robot 1 idles from cycle 334 to the end, robot 2 until cycle 300 and after it
        // (its skill runs to the end of the game: no start or end after cycle 300).
        let stalls = g.stalls();
        assert!(stalls
            .iter()
            .any(|&(r, from, _)| r == 1 && from == 334.0 / 15.0));
        assert!(stalls.iter().any(|&(r, _, _)| r == 2));
        // Both carry to M1 between cycles 300 and 334.
        assert_eq!(g.double_claims().len(), 1);
        assert_eq!(g.bumps.len(), 1);
    }

    /// A robot killed mid-skill (`game --kill-at-s`) works no machine after its death.
    #[test]
    fn a_killed_robots_skill_ends_at_its_death() {
        let sim = lines(&[
            "robotino-sim: done cycles=13500 game_time_s=900.0 score=4 bumps=0 robot_contacts=0 wall_ms=1",
        ]);
        let a1 = lines(&[
            "robotino-agent run: cycle=300 start BringPuckTo(MachineId(1)) (skill-request 1 finish-puck-at M1 holding S0)",
            "robotino-agent game: killed robot 1 at t=25.0",
        ]);
        let a2 = lines(&[
            "robotino-agent run: cycle=900 start BringPuckTo(MachineId(1)) (skill-request 1 finish-puck-at M1 holding S0)",
            "robotino-agent run: cycle=1000 end BringPuckTo(MachineId(1)) Final(LightSeen(Yellow)) ",
        ]);
        let g = GameRecord::parse(3, 900.0, &sim, &[a1, a2]);
        assert_eq!(g.skills[0].ending, Ending::Cut);
        assert_eq!(g.skills[0].end_s, 25.0);
        assert!(g.double_claims().is_empty());
        assert_eq!(g.killed, vec![(1, 25.0)]);
        // Robot 2 idles 60 s and more before its skill and after it; robot 1 is dead
        // from 25 s on, which is not a stall of the team.
        let stalls = g.stalls();
        assert!(stalls.iter().all(|&(r, _, _)| r == 2), "{stalls:?}");
        assert_eq!(stalls.len(), 2, "{stalls:?}");
    }
}
