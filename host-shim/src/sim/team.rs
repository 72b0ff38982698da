//! `sim --robots N` and `sweep --robots N`: a team in the instant simulation. One engine
//! per robot (the agent, `team.clp`, `team-agent.clp`) and one for the world (the
//! referee, `referee.clp`); this module plays the body of each robot (`sim.clp`'s part:
//! travel at the robot's speed, the referee round trip, processing waits) in game time,
//! and carries the team's messages between the engines (`host_shim::team::FaultyNet`,
//! a perfect link unless asked otherwise). Robots act in parallel: each has its own
//! position, puck and busy time; the world's clock is set to each action's time.

use std::fmt::Write;

use agent_core::{DefaultEngine, FactId, Host, ValueRef};
use host_shim::team::member::{slot_float, slot_int, slot_sym};
use host_shim::team::{FaultyNet, LinkFaults, TeamError, TeamMember};
use rules::setup::GameSetup;
use rules::Strategy;

use super::game::SimError;

/// Seconds of game time between two looks at the team when nothing else happens
/// (claims renew every 2 s, back-offs last 0.5 s per robot id).
const TICK: f64 = 0.5;
/// A robot that neither starts nor finishes a skill this long while raw pucks remain
/// stalls (the definition).
const STALL_S: f64 = 60.0;
/// Most robots a team may field (LLSF: three; more are refused, not clamped).
pub const MAX_ROBOTS: u8 = 6;

impl From<TeamError> for SimError {
    fn from(e: TeamError) -> SimError {
        SimError::Engine {
            during: e.during,
            message: format!("robot {}: {}", e.robot, e.message),
        }
    }
}

#[derive(Default)]
struct WorldHost;

impl Host for WorldHost {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
    }
}

/// One skill a robot carried out.
#[derive(Debug, Clone)]
pub struct TeamSkill {
    pub robot: u8,
    pub start: f64,
    pub end: f64,
    pub action: String,
    pub target: String,
    pub puck: String,
    pub status: String,
    pub light: String,
}

/// Per robot: what its body did.
#[derive(Debug, Clone, Default)]
pub struct RobotStats {
    pub travelled: f64,
    /// Seconds spent waiting for a place another robot had.
    pub waited: f64,
    pub skills: u32,
    pub stalls: u32,
}

/// The result of one team game.
#[derive(Debug, Clone, Default)]
pub struct TeamRecord {
    pub points: i64,
    pub s1: i64,
    pub s2: i64,
    pub p: i64,
    pub delivered: i64,
    pub lost: i64,
    pub discarded: i64,
    pub recycled: i64,
    pub end_time: f64,
    /// `done` (every robot done), `time` (the clock), `stuck` (nobody can act: a bug).
    pub end: String,
    pub robots: Vec<RobotStats>,
    pub skills: Vec<TeamSkill>,
    /// Skills at one machine, storage or gate by two robots at the same game time.
    pub double_claims: u32,
}

impl TeamRecord {
    pub fn stalls(&self) -> u32 {
        self.robots.iter().map(|r| r.stalls).sum()
    }
}

#[derive(Debug, Clone)]
enum Phase {
    /// Deciding (or waiting for a place, or done).
    Free,
    Driving {
        id: i64,
        arrive: f64,
    },
    Working {
        id: i64,
        done: f64,
        outcome: String,
    },
    /// Out of the game (its skill would end after the clock).
    Stopped,
}

struct Body {
    at: String,
    puck: String,
    phase: Phase,
    /// Highest skill-request id already taken from this robot's agent.
    taken: i64,
    last_event: f64,
    current: Option<TeamSkill>,
    stats: RobotStats,
}

/// The world's referee in its own engine.
struct World {
    engine: Box<DefaultEngine>,
    host: WorldHost,
    next_action: i64,
}

impl World {
    fn new() -> Result<World, SimError> {
        let mut w = World {
            engine: Box::new(DefaultEngine::new()),
            host: WorldHost,
            next_action: 1,
        };
        w.engine
            .load_str(&mut w.host, rules::REFEREE.name, rules::REFEREE.text)
            .map_err(|e| SimError::Load {
                file: rules::REFEREE.name.into(),
                message: e.to_string(),
            })?;
        Ok(w)
    }

    fn eval(&mut self, command: &str) -> Result<agent_core::Value, SimError> {
        self.engine
            .eval_str(&mut self.host, command)
            .map_err(|e| SimError::Engine {
                during: format!("world: {command}"),
                message: e.to_string(),
            })
    }

    fn assert(&mut self, fact: &str) -> Result<(), SimError> {
        self.engine
            .assert_str(&mut self.host, fact)
            .map(|_| ())
            .map_err(|e| SimError::Engine {
                during: format!("world: asserting {fact}"),
                message: e.to_string(),
            })
    }

    fn run(&mut self) -> Result<(), SimError> {
        self.engine
            .run(&mut self.host, Some(10_000))
            .map(|_| ())
            .map_err(|e| SimError::Engine {
                during: "world: (run)".into(),
                message: e.to_string(),
            })
    }

    fn find(&self, template: &str) -> Option<FactId> {
        self.engine.facts_of(template).next()
    }

    fn int(&self, id: FactId, slot: &str) -> i64 {
        slot_int(&self.engine, id, slot)
    }

    fn num(&self, id: FactId, slot: &str) -> f64 {
        slot_float(&self.engine, id, slot)
    }

    fn sym(&self, id: FactId, slot: &str) -> String {
        slot_sym(&self.engine, id, slot)
    }

    fn s0_left(&self) -> i64 {
        self.find("rf-storage").map_or(0, |id| self.int(id, "s0"))
    }

    fn limit(&self) -> Option<f64> {
        let id = self.find("game-clock")?;
        (self.sym(id, "enabled") == "TRUE").then(|| self.num(id, "limit"))
    }

    /// The referee's answer to one action at game time `t`: (status, light, puck
    /// after, wait).
    fn act(
        &mut self,
        t: f64,
        robot: usize,
        kind: &str,
        target: &str,
        puck: &str,
    ) -> Result<(String, String, String, f64), SimError> {
        let id = self.next_action;
        self.next_action += 1;
        self.eval(&format!(
            "(do-for-fact ((?c game-clock)) TRUE (modify ?c (time {t:?})))"
        ))?;
        self.assert(&format!(
            "(rf-action (id {id}) (kind {kind}) (target {target}) (puck {puck}) (robot {robot}))"
        ))?;
        self.run()?;
        let result = self
            .engine
            .facts_of("rf-result")
            .find(|&f| self.int(f, "id") == id)
            .ok_or_else(|| SimError::Facts(format!("no rf-result for action {id}")))?;
        let answer = (
            self.sym(result, "status"),
            self.sym(result, "light"),
            self.sym(result, "puck"),
            self.num(result, "wait"),
        );
        self.engine
            .retract(&mut self.host, result)
            .map_err(|e| SimError::Engine {
                during: "world: retracting rf-result".into(),
                message: e.to_string(),
            })?;
        Ok(answer)
    }
}

/// A team's engines, ready to play setups one after another.
pub struct TeamPlayer {
    robots: Vec<TeamMember>,
    world: World,
    pub link: LinkFaults,
}

fn sym_of(m: &TeamMember, id: FactId, slot: &str) -> String {
    slot_sym(&m.engine, id, slot)
}

fn int_of(m: &TeamMember, id: FactId, slot: &str) -> i64 {
    slot_int(&m.engine, id, slot)
}

/// The agent's `(state X)`.
fn agent_state(m: &TeamMember) -> String {
    m.engine
        .facts_of("state")
        .next()
        .and_then(|id| match m.engine.fact_multislot_item(id, "implied", 0) {
            Some(ValueRef::Symbol(s)) => Some(s.to_string()),
            _ => None,
        })
        .unwrap_or_default()
}

impl TeamPlayer {
    /// `robots` engines with the strategy's agent and the team rules, and the world.
    /// Call from a thread with [`super::game::ENGINE_THREAD_STACK`].
    pub fn new(strategy: Strategy, robots: u8) -> Result<TeamPlayer, SimError> {
        if robots == 0 || robots > MAX_ROBOTS {
            return Err(SimError::Input(format!(
                "--robots {robots}: a team has 1 to {MAX_ROBOTS} robots"
            )));
        }
        let files: Vec<rules::RuleFile> = rules::agent_files(strategy)
            .iter()
            .copied()
            .chain([rules::TEAM])
            .collect();
        let mut members = Vec::new();
        for _ in 0..robots {
            // team.clp comes with TeamMember; the agent's team rules after it.
            let mut m = TeamMember::new(&files[..files.len() - 1], None)?;
            m.engine
                .load_str(&mut m.host, rules::TEAM_AGENT.name, rules::TEAM_AGENT.text)
                .map_err(|e| SimError::Load {
                    file: rules::TEAM_AGENT.name.into(),
                    message: e.to_string(),
                })?;
            members.push(m);
        }
        Ok(TeamPlayer {
            robots: members,
            world: World::new()?,
            link: LinkFaults::NONE,
        })
    }

    /// Plays one game of the setup; `seed` draws the link's faults.
    pub fn play(&mut self, setup: &GameSetup, seed: u64) -> Result<TeamRecord, SimError> {
        let n = self.robots.len();
        let mut text = String::new();
        setup
            .write_clips(&mut text)
            .map_err(|e| SimError::Input(format!("writing the setup: {e}")))?;
        // The world takes the referee's setup; the robots see the active gate.
        self.world
            .engine
            .reset(&mut self.world.host)
            .map_err(|e| SimError::Engine {
                during: "world: (reset)".into(),
                message: e.to_string(),
            })?;
        self.world.next_action = 1;
        // What every robot knows: the active gate, the number of raw pucks.
        let mut public = Vec::new();
        for fact in rules::setup::fact_lines(&text) {
            let keep = ["(rf-", "(s0-supply", "(active-gate", "(game-clock"];
            if keep.iter().any(|k| fact.starts_with(k)) {
                self.world.assert(fact)?;
            }
            if fact.starts_with("(active-gate") || fact.starts_with("(s0-supply") {
                public.push(fact.to_string());
            }
        }
        self.world.run()?;
        for (i, m) in self.robots.iter_mut().enumerate() {
            m.start(i as u8 + 1, n as u8, 0.0, &[])?;
            for fact in &public {
                m.assert(fact)?;
            }
            if !public.iter().any(|f| f.starts_with("(s0-supply")) {
                m.assert("(s0-supply 20)")?;
            }
        }
        let limit = self.world.limit();
        let mut net = FaultyNet::new(self.link, seed);
        let mut bodies: Vec<Body> = (0..n)
            .map(|_| Body {
                at: "INS".into(),
                puck: "NONE".into(),
                phase: Phase::Free,
                taken: 0,
                last_event: 0.0,
                current: None,
                stats: RobotStats::default(),
            })
            .collect();
        let mut record = TeamRecord::default();
        let mut t = 0.0;
        let mut last_progress = 0.0;
        loop {
            // Outcomes due now go to the agents.
            for (i, b) in bodies.iter_mut().enumerate() {
                if let Phase::Working { id, done, outcome } = &b.phase {
                    if *done <= t {
                        let fact = format!("(skill-outcome (id {id}) {outcome})");
                        self.robots[i].assert(&fact)?;
                        if let Some(mut s) = b.current.take() {
                            s.end = t;
                            record.skills.push(s);
                        }
                        b.phase = Phase::Free;
                        b.last_event = t;
                        last_progress = t;
                    }
                }
            }
            // The team talks until it is quiet at this time.
            for round in 0.. {
                if round > 200 {
                    return Err(SimError::Facts(format!(
                        "the team's messages do not settle at {t} s"
                    )));
                }
                for (to, msg) in net.arrived(t) {
                    self.robots[usize::from(to - 1)].receive(&msg)?;
                }
                let mut sent = 0;
                for m in self.robots.iter_mut() {
                    m.set_time(t)?;
                    m.run()?;
                    for msg in m.outbox()? {
                        net.send(&msg, t, 1..=n as u8);
                        sent += 1;
                    }
                }
                if sent == 0 || self.link != LinkFaults::NONE {
                    break;
                }
            }
            // Bodies: new requests start driving; arrivals act.
            for i in 0..n {
                let b = &mut bodies[i];
                if matches!(b.phase, Phase::Free) {
                    if let Some((id, name, target)) = self.new_request(i, b.taken) {
                        b.taken = id;
                        let d = self.distance(i, &b.at, &target)?;
                        let arrive = t + d / 0.5;
                        b.stats.travelled += d;
                        b.stats.skills += 1;
                        b.last_event = t;
                        last_progress = t;
                        // Double claims: another robot's skill at the same place now (not
                        // at the input storage, where each robot has its own spot, as on
                        // the field: rules/team-agent.clp does not claim it).
                        if !matches!(target.as_str(), "R1" | "R2" | "INS") {
                            let clash = bodies_at(&bodies, &target, i);
                            record.double_claims += clash;
                        }
                        let b = &mut bodies[i];
                        b.current = Some(TeamSkill {
                            robot: i as u8 + 1,
                            start: t,
                            end: t,
                            action: name,
                            target,
                            puck: b.puck.clone(),
                            status: String::new(),
                            light: String::new(),
                        });
                        b.phase = match limit {
                            Some(l) if arrive > l => Phase::Stopped,
                            _ => Phase::Driving { id, arrive },
                        };
                    }
                }
                let b = &mut bodies[i];
                if let Phase::Driving { id, arrive } = b.phase {
                    if arrive <= t {
                        let Some(skill) = b.current.clone() else {
                            continue;
                        };
                        b.at = skill.target.clone();
                        let (phase, status, light) =
                            self.act(b, i + 1, id, t, &skill.action, &skill.target, limit)?;
                        let b = &mut bodies[i];
                        if let Some(s) = b.current.as_mut() {
                            s.status = status;
                            s.light = light;
                        }
                        b.phase = phase;
                    }
                }
            }
            // Every agent's state until the next step (no engine runs before it).
            let states: Vec<String> = self.robots.iter().map(agent_state).collect();
            // Stalls: a robot without skill events for a minute while raw pucks remain.
            let s0_left = self.world.s0_left();
            for (i, b) in bodies.iter_mut().enumerate() {
                let done = states[i] == "DONE";
                if s0_left > 0 && !done && t - b.last_event >= STALL_S {
                    b.stats.stalls += 1;
                    b.last_event = t;
                }
            }
            // The end.
            let all_done = (0..n).all(|i| {
                states[i] == "DONE" && matches!(bodies[i].phase, Phase::Free)
                    || matches!(bodies[i].phase, Phase::Stopped)
            });
            if all_done {
                record.end = "done".into();
                break;
            }
            let next = bodies
                .iter()
                .filter_map(|b| match b.phase {
                    Phase::Driving { arrive, .. } => Some(arrive),
                    Phase::Working { done, .. } => Some(done),
                    _ => None,
                })
                .fold(t + TICK, f64::min);
            if let Some(l) = limit {
                if next > l {
                    t = l;
                    record.end = "time".into();
                    break;
                }
            }
            for (i, b) in bodies.iter_mut().enumerate() {
                if matches!(states[i].as_str(), "TEAM-WAIT" | "TEAM-CLAIM") {
                    b.stats.waited += next - t;
                }
            }
            if next - last_progress > 600.0 {
                t = next;
                record.end = "stuck".into();
                break;
            }
            t = next;
        }
        record.end_time = t;
        record.robots = bodies.into_iter().map(|b| b.stats).collect();
        if let Some(id) = self.world.find("score") {
            let w = &self.world;
            record.points = w.int(id, "points");
            record.s1 = w.int(id, "s1");
            record.s2 = w.int(id, "s2");
            record.p = w.int(id, "p");
            record.delivered = w.int(id, "delivered");
            record.lost = w.int(id, "lost");
            record.discarded = w.int(id, "discarded");
            record.recycled = w.int(id, "recycled");
        }
        Ok(record)
    }

    /// Robot `i`'s newest skill request with an id above `taken`.
    fn new_request(&self, i: usize, taken: i64) -> Option<(i64, String, String)> {
        let m = &self.robots[i];
        m.engine
            .facts_of("skill-request")
            .map(|id| {
                (
                    int_of(m, id, "id"),
                    sym_of(m, id, "name"),
                    sym_of(m, id, "target"),
                )
            })
            .filter(|(id, _, _)| *id > taken)
            .max_by_key(|(id, _, _)| *id)
    }

    fn distance(&mut self, i: usize, from: &str, to: &str) -> Result<f64, SimError> {
        let m = &mut self.robots[i];
        let v = m
            .engine
            .eval_str(&mut m.host, &format!("(place-distance {from} {to})"))
            .map_err(|e| SimError::Engine {
                during: format!("(place-distance {from} {to})"),
                message: e.to_string(),
            })?;
        v.as_number()
            .ok_or_else(|| SimError::Facts(format!("place-distance {from} {to}: not a number")))
    }

    /// Robot at its skill's place: the referee round trip, as `sim.clp` does it.
    /// Returns the next phase, the status and the light.
    #[allow(clippy::too_many_arguments)]
    fn act(
        &mut self,
        b: &mut Body,
        robot: usize,
        id: i64,
        t: f64,
        action: &str,
        target: &str,
        limit: Option<f64>,
    ) -> Result<(Phase, String, String), SimError> {
        let fetch = matches!(action, "get-s0" | "get-junk");
        let kind = match action {
            "get-s0" => "get-s0",
            "finish-puck-at" => "load",
            "deliver" => "deliver",
            "get-junk" => "take-junk",
            "recycle" => "recycle",
            _ => "discard",
        };
        let failed = |b: &mut Body| {
            b.puck = "NONE".into();
            (
                Phase::Working {
                    id,
                    done: t,
                    outcome: "(status FAILED)".into(),
                },
                "FAILED".to_string(),
                "none".to_string(),
            )
        };
        if !fetch && b.puck == "NONE" {
            return Ok(failed(b));
        }
        if fetch && b.puck != "NONE" {
            self.world.act(t, robot, "lose", target, &b.puck)?;
            return Ok(failed(b));
        }
        let (status, light, after, wait) = self.world.act(t, robot, kind, target, &b.puck)?;
        let done = t + wait;
        if status == "late" || limit.is_some_and(|l| done > l) {
            return Ok((Phase::Stopped, "late".into(), light));
        }
        if status == "empty" {
            b.puck = "NONE".into();
            return Ok((
                Phase::Working {
                    id,
                    done,
                    outcome: if action == "get-junk" {
                        "(status FAILED) (info no-junk)".into()
                    } else {
                        "(status FAILED) (info storage-empty)".into()
                    },
                },
                "FAILED".into(),
                "none".into(),
            ));
        }
        b.puck = after;
        let info = if action == "finish-puck-at" {
            if b.puck == "NONE" {
                "no-puck"
            } else {
                "puck-held"
            }
        } else {
            "none"
        };
        let light_fact = if light.is_empty() { "none" } else { &light };
        Ok((
            Phase::Working {
                id,
                done,
                outcome: format!("(status FINAL) (light {light_fact}) (info {info})"),
            },
            "FINAL".into(),
            light_fact.to_string(),
        ))
    }
}

/// How many other robots have a skill under way at `target`.
fn bodies_at(bodies: &[Body], target: &str, me: usize) -> u32 {
    bodies
        .iter()
        .enumerate()
        .filter(|(i, b)| {
            *i != me
                && !matches!(b.phase, Phase::Free | Phase::Stopped)
                && b.current.as_ref().is_some_and(|s| s.target == target)
        })
        .count() as u32
}

/// The readable report of a team game.
pub fn render(r: &TeamRecord, title: &str, robots: usize) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "team game: {title}, {robots} robots (instant simulation)"
    );
    for s in &r.skills {
        let _ = writeln!(
            out,
            "  {:7.1}-{:7.1} s  robot {}  {:<15} {:<4} with {:<4} {:<6} {}",
            s.start, s.end, s.robot, s.action, s.target, s.puck, s.status, s.light
        );
    }
    for (i, rs) in r.robots.iter().enumerate() {
        let _ = writeln!(
            out,
            "robot {}: {} skills, travelled {:.1} m, waited for a place {:.1} s, stalls {}",
            i + 1,
            rs.skills,
            rs.travelled,
            rs.waited,
            rs.stalls
        );
    }
    let _ = writeln!(
        out,
        "RESULT points {} s1 {} s2 {} p {} delivered {} lost {} discarded {} recycled {} end {} time {:.1} double-claims {} stalls {}",
        r.points,
        r.s1,
        r.s2,
        r.p,
        r.delivered,
        r.lost,
        r.discarded,
        r.recycled,
        r.end,
        r.end_time,
        r.double_claims,
        r.stalls()
    );
    out
}

/// One assignment played by the team and by one robot.
#[derive(Debug, Clone)]
pub struct TeamVsOne {
    pub index: u32,
    pub team: TeamRecord,
    pub one_points: i64,
    pub one_end: f64,
}

/// Plays assignments `0..count` with `robots` robots and with one robot, on `threads`
/// workers; ordered by index.
pub fn sweep_team(
    config: super::sweep::SweepConfig,
    robots: u8,
    count: u32,
    threads: usize,
    on_game: &(dyn Fn() + Sync),
) -> Result<Vec<TeamVsOne>, SimError> {
    let new_players = || -> Result<_, SimError> {
        Ok((
            TeamPlayer::new(config.strategy, robots)?,
            super::game::Player::new(config.strategy)?,
        ))
    };
    let play =
        |(team, one): &mut (TeamPlayer, super::game::Player), index: u32, setup: &GameSetup| {
            let record = team
                .play(setup, u64::from(index))
                .map_err(|e| SimError::Input(format!("assignment #{index}: {e}")))?;
            let single = one.play(setup, false)?;
            Ok(TeamVsOne {
                index,
                team: record,
                one_points: single.score.points,
                one_end: single.end_time,
            })
        };
    super::sweep::on_workers(config, count, threads, &new_players, &play, on_game)
}

/// The table of a team sweep against one robot.
pub fn summarize_team(robots: u8, games: &[TeamVsOne], seconds: f64) -> String {
    let n = games.len().max(1) as f64;
    let mean = |f: &dyn Fn(&TeamVsOne) -> f64| games.iter().map(f).sum::<f64>() / n;
    let min_team = games.iter().map(|g| g.team.points).min().unwrap_or(0);
    let min_one = games.iter().map(|g| g.one_points).min().unwrap_or(0);
    let worse: Vec<u32> = games
        .iter()
        .filter(|g| g.team.points < g.one_points)
        .map(|g| g.index)
        .collect();
    let stuck = games.iter().filter(|g| g.team.end == "stuck").count();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "team sweep: {} assignments, {robots} robots against one, {seconds:.0} s",
        games.len()
    );
    let _ = writeln!(
        out,
        "| robots | mean points | min points | mean P | mean end s | stalls | double claims | stuck |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    let _ = writeln!(
        out,
        "| 1 | {:.2} | {} | | {:.0} | | | |",
        mean(&|g| g.one_points as f64),
        min_one,
        mean(&|g| g.one_end)
    );
    let _ = writeln!(
        out,
        "| {robots} | {:.2} | {} | {:.2} | {:.0} | {} | {} | {} |",
        mean(&|g| g.team.points as f64),
        min_team,
        mean(&|g| g.team.p as f64),
        mean(&|g| g.team.end_time),
        games.iter().map(|g| g.team.stalls()).sum::<u32>(),
        games.iter().map(|g| g.team.double_claims).sum::<u32>(),
        stuck
    );
    let first: Vec<String> = worse.iter().take(10).map(|i| i.to_string()).collect();
    let _ = writeln!(
        out,
        "team below one robot: {} assignments{}",
        worse.len(),
        if first.is_empty() {
            String::new()
        } else {
            format!(" (first: {})", first.join(" "))
        }
    );
    out
}
