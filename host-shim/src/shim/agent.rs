//! The deliberative agent inside `robotino-agent run`: the rules issue's agent rule base
//! (`rules::agent_files(strategy)`) in our engine. The shim turns skill outcomes and
//! perceptions into facts (`skill-outcome`, `active-gate`), runs the engine to quiescence,
//! and reads the `skill-request` it chose. The fact interface is `rules/README.md`'s
//! "Agent <-> executor". In a team the same engine also loads `rules/team.clp` and
//! `rules/team-agent.clp` (claims, votes, news; `rules/README.md`'s "Team"): the host
//! moves its clock, hands teammates' messages in and takes its own out.

use super::rule_engine::{Rules, RulesError};
use crate::team::TeamMsg;
use agent_core::{EngineError, ValueRef};
use hal::field::{GateId, MachineId, RecyclingId, MACHINE_COUNT};
use hal::skill::{FailReason, Perception, SkillOutcome, SkillRequest};
use hal::LightSignal;
use rules::Strategy;

use super::payloads::{LOADED_S0, LOADED_S1, LOADED_S2};

/// A skill the rules chose: the `skill-request` fact and what it asks of the behaviour layer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChosenSkill {
    pub id: i64,
    /// The rules' names: `get-s0`, `finish-puck-at`, `deliver`, `discard`, `get-junk`,
    /// `recycle`.
    pub name: String,
    pub target: String,
    /// The puck the agent believes it carries.
    pub puck: String,
    pub request: SkillRequest,
}

/// Shortest drive (seconds) whose stop on the bumper counts as a place not reached: a
/// robot already pressed against something fails every skill at once, wherever it goes.
pub const UNREACHED_BUMPER_MIN_S: f64 = 2.0;

/// Whether a skill that ended with `outcome` after `drove_s` seconds failed to reach its
/// place `target`: a failed drive, or a drive to a machine stopped on the bumper after
/// [`UNREACHED_BUMPER_MIN_S`] (a dead teammate's body at a machine's approach pressed
/// the others against the next machine on every try: kill-one seed 23, 115 bumps, 119
/// points). Bumps on the way to a gate, the storage or a unit do not count: a robot
/// with a product that gave up its gate for 120 s stalled (team seed 66).
pub fn unreached_place(outcome: SkillOutcome, target: &str, drove_s: f64) -> bool {
    let machine = target
        .strip_prefix('M')
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    match outcome {
        SkillOutcome::Failed(FailReason::DriveFailed) => true,
        SkillOutcome::Failed(FailReason::Bumper) => machine && drove_s >= UNREACHED_BUMPER_MIN_S,
        _ => false,
    }
}

/// What the agent knows of one machine: its definite type (1..=3) and the inputs it
/// believes loaded (payload bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MachineView {
    pub machine_type: Option<u8>,
    pub loaded: u8,
}

/// This robot's seat in a team.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TeamSeat {
    /// 1..=robots.
    pub id: u8,
    pub robots: u8,
    /// Raw pucks in the input storage at the start (every robot knows the supply).
    pub s0_supply: u32,
}

/// The agent's rules in our engine.
pub struct EngineAgent {
    rules: Rules,
    /// The request handed to the behaviour layer and not answered yet.
    handed_out: Option<i64>,
    gate_told: bool,
    /// Rules fired by the last run of the engine.
    pub last_fired: u32,
    team: Option<TeamSeat>,
}

impl EngineAgent {
    /// Loads the strategy's agent files and resets (the agent's beliefs are deffacts).
    /// Call on a thread with [`super::rule_engine::ENGINE_THREAD_STACK`].
    pub fn new(strategy: Strategy) -> Result<Self, RulesError> {
        Self::with_team(strategy, None)
    }

    /// The agent with what a robot on the field adds (`rules::COLLECT`: leave a working T3,
    /// collect its product later), and with a seat the team's rules after it
    /// (`rules::TEAM`, `rules::TEAM_AGENT`), its identity, clock at 0 and the raw-puck
    /// supply.
    pub fn with_team(strategy: Strategy, team: Option<TeamSeat>) -> Result<Self, RulesError> {
        let mut files = rules::agent_files(strategy).to_vec();
        files.push(rules::COLLECT);
        if team.is_some() {
            files.extend([rules::TEAM, rules::TEAM_AGENT]);
        }
        let mut rules = Rules::load(&files)?;
        // `distance` is a host function of the rules; our engine has it built in.
        rules
            .eval("(distance 0 0 3 4)")
            .map_err(|e| RulesError::new("checking the `distance` builtin", e.message))?;
        rules.reset()?;
        if let Some(seat) = team {
            rules.assert(&format!(
                "(team-self (id {}) (robots {}))",
                seat.id, seat.robots
            ))?;
            rules.assert("(team-clock (now 0.0))")?;
            rules.assert(&format!("(s0-supply {})", seat.s0_supply))?;
        }
        Ok(Self {
            rules,
            handed_out: None,
            gate_told: false,
            last_fired: 0,
            team,
        })
    }

    pub fn team(&self) -> Option<TeamSeat> {
        self.team
    }

    /// Moves the team clock (game time as this robot reads it).
    pub fn set_team_time(&mut self, now: f64) -> Result<(), RulesError> {
        self.rules.eval(&format!("(team-set-time {now:?})"))
    }

    /// Hands a teammate's message in. A copy of one still pending is one fact already
    /// (CLIPS keeps no duplicate facts): nothing to do.
    pub fn receive_team(&mut self, msg: &TeamMsg) -> Result<(), RulesError> {
        match self
            .rules
            .engine
            .assert_str(&mut self.rules.host, &msg.recv_fact())
        {
            Ok(_) | Err(EngineError::Duplicate) => Ok(()),
            Err(e) => Err(RulesError::new("receiving a team message", e)),
        }
    }

    /// Takes the messages the rules want sent (retracting their `team-send` facts), in
    /// the order the robot numbered them.
    pub fn team_outbox(&mut self) -> Result<Vec<TeamMsg>, RulesError> {
        let Some(seat) = self.team else {
            return Ok(Vec::new());
        };
        let ids: Vec<_> = self.rules.facts_of("team-send").collect();
        let mut out = Vec::with_capacity(ids.len());
        for id in ids {
            let r = &self.rules;
            let n = match r.engine.fact_slot(id, "data") {
                Some(ValueRef::Multi(n)) => n as usize,
                _ => 0,
            };
            let data = (0..n)
                .filter_map(|i| match r.engine.fact_multislot_item(id, "data", i) {
                    Some(ValueRef::Symbol(s)) => Some(s.to_string()),
                    Some(ValueRef::Int(v)) => Some(v.to_string()),
                    _ => None,
                })
                .collect();
            out.push(TeamMsg {
                from: seat.id,
                seq: r.int(id, "seq").unwrap_or(0),
                kind: r.symbol(id, "kind").unwrap_or_default(),
                to: r.int(id, "to").unwrap_or(0),
                resource: r.symbol(id, "resource").unwrap_or_default(),
                rseq: r.int(id, "rseq").unwrap_or(0),
                lease: r.number(id, "lease").unwrap_or(0.0),
                data,
            });
            self.rules.retract(id)?;
        }
        out.sort_by_key(|m| m.seq);
        Ok(out)
    }

    /// The places this robot holds a claim on now (its rules' `team-holds`).
    pub fn team_holds(&self) -> Vec<String> {
        let now = self
            .rules
            .facts_of("team-clock")
            .next()
            .and_then(|id| self.rules.number(id, "now"))
            .unwrap_or(0.0);
        self.rules
            .facts_of("team-claim")
            .filter(|&id| self.rules.number(id, "until").unwrap_or(-1.0) > now)
            .filter_map(|id| self.rules.symbol(id, "resource"))
            .collect()
    }

    /// The agent's `(state ...)`: IDLE, EXEC, GOTO-FINAL or DONE.
    pub fn state(&self) -> Option<String> {
        self.rules.ordered_symbol("state")
    }

    pub fn is_done(&self) -> bool {
        self.state().as_deref() == Some("DONE")
    }

    /// The active gate's light, seen once: `(active-gate Dk)`.
    pub fn see_active_gate(&mut self, gate: GateId) -> Result<(), RulesError> {
        if !self.gate_told {
            self.rules
                .assert(&format!("(active-gate D{})", gate.number()))?;
            self.gate_told = true;
        }
        Ok(())
    }

    pub fn knows_gate(&self) -> bool {
        self.gate_told
    }

    /// Runs the rules to quiescence and returns the skill they chose, if it is new.
    pub fn decide(&mut self) -> Result<Option<ChosenSkill>, RulesError> {
        self.run_rules()?;
        self.take_request()
    }

    /// Runs the rules to quiescence (decisions, and in a team the messages).
    pub fn run_rules(&mut self) -> Result<(), RulesError> {
        self.last_fired = self.rules.run()?;
        Ok(())
    }

    /// The skill the rules chose, if it was not handed out yet.
    pub fn take_request(&mut self) -> Result<Option<ChosenSkill>, RulesError> {
        let Some(f) = self.rules.facts_of("skill-request").next() else {
            return Ok(None);
        };
        let id = self.rules.int(f, "id").unwrap_or(0);
        if self.handed_out == Some(id) {
            return Ok(None);
        }
        let name = self.rules.symbol(f, "name").unwrap_or_default();
        let target = self.rules.symbol(f, "target").unwrap_or_default();
        let puck = self.rules.symbol(f, "puck").unwrap_or_default();
        let request = skill_request(&name, &target).ok_or_else(|| {
            RulesError::new(
                format!("reading skill-request {id}"),
                format!("no skill for ({name} {target})"),
            )
        })?;
        self.handed_out = Some(id);
        Ok(Some(ChosenSkill {
            id,
            name,
            target,
            puck,
            request,
        }))
    }

    /// Whether the rules want skill `id` stopped (`skill-abort`: in a team, the hold on
    /// its place lapsed).
    pub fn abort_requested(&self, id: i64) -> bool {
        self.rules
            .facts_of("skill-abort")
            .any(|f| self.rules.int(f, "id") == Some(id))
    }

    /// Tells the rules how skill `id` ended: asserts its `skill-outcome`.
    pub fn report(&mut self, id: i64, outcome: SkillOutcome) -> Result<(), RulesError> {
        let unreached = outcome == SkillOutcome::Failed(FailReason::DriveFailed);
        self.report_sensed(id, outcome, false, unreached, false)
    }

    /// [`Self::report`] with the puck sensor's reading at the end: a failed skill with a
    /// puck still in the gripper says so (`info puck-held`), and the rules keep the puck
    /// instead of believing it lost. `unreached`: the skill failed because the robot
    /// could not get to its place (see [`unreached_place`]). `output_waits`: the puck was
    /// brought to a machine that stayed green and took nothing (`info output-waits`: an
    /// output lies under its light, rules/collect.clp).
    pub fn report_sensed(
        &mut self,
        id: i64,
        outcome: SkillOutcome,
        puck_present: bool,
        unreached: bool,
        output_waits: bool,
    ) -> Result<(), RulesError> {
        let (status, light, mut info) = outcome_slots(outcome);
        if status == "FAILED" && info == "none" && output_waits {
            info = "output-waits";
        } else if status == "FAILED" && info == "none" && puck_present {
            info = "puck-held";
        }
        // A team member's rules avoid a place it keeps failing to drive to
        // (`team-unreached` in rules/team-agent.clp): told before the outcome.
        if self.team.is_some() && unreached {
            self.rules.assert(&format!("(team-unreached (id {id}))"))?;
        }
        self.rules.assert(&format!(
            "(skill-outcome (id {id}) (status {status}) (light {light}) (info {info}))"
        ))?;
        if self.handed_out == Some(id) {
            self.handed_out = None;
        }
        Ok(())
    }

    /// The rules' beliefs about every machine, M1..M10.
    pub fn machines(&self) -> [MachineView; MACHINE_COUNT] {
        let mut out = [MachineView::default(); MACHINE_COUNT];
        for f in self.rules.facts_of("machine") {
            let Some(i) = self
                .rules
                .int(f, "index")
                .and_then(|i| usize::try_from(i - 1).ok())
                .filter(|&i| i < MACHINE_COUNT)
            else {
                continue;
            };
            let machine_type = match self.rules.symbol(f, "mtype").as_deref() {
                Some("T1") => Some(1),
                Some("T2") => Some(2),
                Some("T3") => Some(3),
                _ => None,
            };
            let loaded = self
                .rules
                .symbols(f, "loaded-with")
                .iter()
                .map(|p| match p.as_str() {
                    "S0" => LOADED_S0,
                    "S1" => LOADED_S1,
                    "S2" => LOADED_S2,
                    _ => 0,
                })
                .fold(0, |a, b| a | b);
            out[i] = MachineView {
                machine_type,
                loaded,
            };
        }
        out
    }

    /// What the rules printed since the last call.
    pub fn take_output(&mut self) -> String {
        self.rules.take_output()
    }

    pub fn engine_stats(&self) -> agent_core::Stats {
        self.rules.engine.stats()
    }
}

/// A strategy by name (command lines).
pub fn parse_strategy(name: &str) -> Result<Strategy, String> {
    Strategy::from_name(name)
        .ok_or_else(|| format!("unknown strategy {name:?} (naive, paper or travel)"))
}

/// The behaviour layer's skill for a rules' `skill-request`.
pub fn skill_request(name: &str, target: &str) -> Option<SkillRequest> {
    let number = |prefix: char| {
        target
            .strip_prefix(prefix)
            .and_then(|n| n.parse::<u8>().ok())
    };
    match name {
        "get-s0" => Some(SkillRequest::GetS0),
        "finish-puck-at" => number('M')
            .and_then(MachineId::new)
            .map(SkillRequest::BringPuckTo),
        "deliver" => number('D')
            .and_then(GateId::new)
            .map(SkillRequest::DeliverTo),
        // The recycling units are where the rules would drive; the robot releases in place.
        "discard" => Some(SkillRequest::Discard),
        "get-junk" => number('M')
            .and_then(MachineId::new)
            .map(SkillRequest::GetJunk),
        "recycle" => number('R')
            .and_then(RecyclingId::new)
            .map(SkillRequest::Recycle),
        "feed" => number('M')
            .and_then(MachineId::new)
            .map(SkillRequest::FeedTo),
        "collect" => number('M')
            .and_then(MachineId::new)
            .map(SkillRequest::Collect),
        _ => None,
    }
}

/// The `skill-outcome` slots (status, light, info) for a skill's end. The rules know
/// FINAL with the light seen at a machine, and FAILED; a light that did not change, or one
/// the world model has no rule for, is a failed step.
pub fn outcome_slots(outcome: SkillOutcome) -> (&'static str, &'static str, &'static str) {
    match outcome {
        SkillOutcome::Final(Perception::LightSeen(
            l @ (LightSignal::Green | LightSignal::Yellow | LightSignal::YellowFlashing),
        )) => ("FINAL", l.symbol(), "none"),
        SkillOutcome::Final(Perception::LightSeen(_) | Perception::LightUnchanged) => {
            ("FAILED", "none", "none")
        }
        SkillOutcome::Final(
            Perception::GotS0
            | Perception::Delivered
            | Perception::Released
            | Perception::GotJunk
            | Perception::Recycled
            | Perception::GotOutput,
        ) => ("FINAL", "none", "none"),
        // The machine works on the last input, left there: its light is yellow until done.
        SkillOutcome::Final(Perception::LeftProcessing) => ("FINAL", "yellow", "processing"),
        SkillOutcome::Failed(FailReason::StorageEmpty) => ("FAILED", "none", "storage-empty"),
        SkillOutcome::Failed(FailReason::NoJunk) => ("FAILED", "none", "no-junk"),
        SkillOutcome::Failed(FailReason::NoOutput) => ("FAILED", "none", "no-output"),
        SkillOutcome::Failed(_) | SkillOutcome::Running => ("FAILED", "none", "none"),
    }
}

#[cfg(test)]
mod tests {
    use super::super::rule_engine::with_engine_stack;
    use super::*;

    fn on_engine_stack(f: impl FnOnce() + Send + 'static) {
        with_engine_stack(f).unwrap_or_else(|e| panic!("{e}"));
    }

    #[test]
    fn a_place_is_unreached_after_a_failed_drive_or_a_bump_on_the_way_to_a_machine() {
        let drive = SkillOutcome::Failed(FailReason::DriveFailed);
        let bump = SkillOutcome::Failed(FailReason::Bumper);
        assert!(unreached_place(drive, "INS", 0.0));
        assert!(unreached_place(bump, "M4", 4.0));
        assert!(unreached_place(bump, "M10", UNREACHED_BUMPER_MIN_S));
        // pressed against something already: every skill fails at once
        assert!(!unreached_place(bump, "M8", 0.4));
        // a gate, the storage, a unit: not for a bump
        for place in ["D1", "INS", "R2", "M", "MX"] {
            assert!(!unreached_place(bump, place, 4.0), "{place}");
        }
        let other = SkillOutcome::Failed(FailReason::Aborted);
        assert!(!unreached_place(other, "M4", 4.0));
        assert!(!unreached_place(SkillOutcome::Running, "M4", 4.0));
    }

    fn m(n: u8) -> MachineId {
        MachineId::new(n).unwrap_or_else(|| panic!("{n}"))
    }

    #[test]
    fn requests_map_to_skills() {
        assert_eq!(skill_request("get-s0", "INS"), Some(SkillRequest::GetS0));
        assert_eq!(
            skill_request("finish-puck-at", "M10"),
            Some(SkillRequest::BringPuckTo(m(10)))
        );
        assert_eq!(
            skill_request("deliver", "D3"),
            GateId::new(3).map(SkillRequest::DeliverTo)
        );
        assert_eq!(skill_request("discard", "R2"), Some(SkillRequest::Discard));
        assert_eq!(
            skill_request("get-junk", "M3"),
            Some(SkillRequest::GetJunk(m(3)))
        );
        assert_eq!(
            skill_request("recycle", "R2"),
            RecyclingId::new(2).map(SkillRequest::Recycle)
        );
        assert_eq!(
            skill_request("feed", "M6"),
            Some(SkillRequest::FeedTo(m(6)))
        );
        assert_eq!(
            skill_request("collect", "M6"),
            Some(SkillRequest::Collect(m(6)))
        );
        assert_eq!(skill_request("collect", "INS"), None);
        assert_eq!(skill_request("recycle", "R3"), None);
        assert_eq!(skill_request("finish-puck-at", "M11"), None);
        assert_eq!(skill_request("fly", "M1"), None);
    }

    #[test]
    fn the_rules_fetch_bring_and_learn_from_the_light() {
        on_engine_stack(|| {
            let mut a = EngineAgent::new(Strategy::Paper).unwrap_or_else(|e| panic!("{e}"));
            a.see_active_gate(GateId::new(2).unwrap_or_else(|| panic!()))
                .unwrap_or_else(|e| panic!("{e}"));
            let first = a.decide().unwrap_or_else(|e| panic!("{e}"));
            let first = first.unwrap_or_else(|| panic!("no first skill"));
            assert_eq!((first.id, first.request), (1, SkillRequest::GetS0));
            // Asked again without an outcome: nothing new.
            assert_eq!(a.decide().unwrap_or_else(|e| panic!("{e}")), None);
            assert_eq!(a.state().as_deref(), Some("EXEC"));
            a.report(1, SkillOutcome::Final(Perception::GotS0))
                .unwrap_or_else(|e| panic!("{e}"));
            let second = a
                .decide()
                .unwrap_or_else(|e| panic!("{e}"))
                .unwrap_or_else(|| panic!("no second skill"));
            assert_eq!(second.name, "finish-puck-at");
            assert_eq!(second.puck, "S0");
            let SkillRequest::BringPuckTo(target) = second.request else {
                panic!("{second:?}");
            };
            // Green on the first S0: a T1, and the robot holds an S1.
            a.report(
                2,
                SkillOutcome::Final(Perception::LightSeen(LightSignal::Green)),
            )
            .unwrap_or_else(|e| panic!("{e}"));
            let third = a
                .decide()
                .unwrap_or_else(|e| panic!("{e}"))
                .unwrap_or_else(|| panic!("no third skill"));
            assert_eq!(third.puck, "S1");
            assert_eq!(a.machines()[target.index()].machine_type, Some(1));
        });
    }

    /// Two robots of a team start at the input storage: each takes its raw pucks at its
    /// own spot there, so neither claims the storage and both fetch at once (claimed as
    /// one place, it kept robots waiting for each other at the start).
    #[test]
    fn team_agents_fetch_raw_pucks_at_once() {
        on_engine_stack(|| {
            let seat = |id| {
                Some(TeamSeat {
                    id,
                    robots: 2,
                    s0_supply: 20,
                })
            };
            let mut robots: Vec<EngineAgent> = [1, 2]
                .iter()
                .map(|&id| {
                    let mut a = EngineAgent::with_team(Strategy::Paper, seat(id))
                        .unwrap_or_else(|e| panic!("{e}"));
                    a.see_active_gate(GateId::new(1).unwrap_or_else(|| panic!()))
                        .unwrap_or_else(|e| panic!("{e}"));
                    a
                })
                .collect();
            let mut in_flight: Vec<TeamMsg> = Vec::new();
            let mut fetches: Vec<(u8, f64)> = Vec::new();
            for step in 0..200 {
                let now = f64::from(step) * 0.1;
                let arriving = std::mem::take(&mut in_flight);
                for (i, a) in robots.iter_mut().enumerate() {
                    let me = i as u8 + 1;
                    a.set_team_time(now).unwrap_or_else(|e| panic!("{e}"));
                    for m in arriving.iter().filter(|m| m.from != me) {
                        a.receive_team(m).unwrap_or_else(|e| panic!("{e}"));
                    }
                    a.run_rules().unwrap_or_else(|e| panic!("{e}"));
                    in_flight.extend(a.team_outbox().unwrap_or_else(|e| panic!("{e}")));
                    let chosen = a.take_request().unwrap_or_else(|e| panic!("{e}"));
                    if let Some(c) = chosen.filter(|c| c.request == SkillRequest::GetS0) {
                        assert!(!a.team_holds().contains(&"INS".to_string()));
                        fetches.push((me, now));
                        a.report(c.id, SkillOutcome::Final(Perception::GotS0))
                            .unwrap_or_else(|e| panic!("{e}"));
                    }
                }
                if fetches.len() >= 2 {
                    break;
                }
            }
            let who: Vec<u8> = fetches.iter().map(|f| f.0).collect();
            assert_eq!(who.len(), 2, "{fetches:?}");
            assert_ne!(who[0], who[1], "{fetches:?}");
            assert!(fetches[1].1 < 0.5, "{fetches:?}");
        });
    }

    /// A puck brought to a machine that stayed green and took nothing (`info
    /// output-waits`: an output lies under its light, perhaps a dead teammate's P): the
    /// robot believes the machine a full T3 with a P to collect, keeps its puck for
    /// other work, brings nothing there again and comes back to collect the P once its
    /// hands are empty.
    #[test]
    fn a_refused_puck_at_a_green_machine_means_an_output_to_collect() {
        on_engine_stack(|| {
            let mut a = EngineAgent::new(Strategy::Paper).unwrap_or_else(|e| panic!("{e}"));
            a.see_active_gate(GateId::new(2).unwrap_or_else(|| panic!()))
                .unwrap_or_else(|e| panic!("{e}"));
            let next = |a: &mut EngineAgent| {
                a.decide()
                    .unwrap_or_else(|e| panic!("{e}"))
                    .unwrap_or_else(|| panic!("no skill chosen"))
            };
            let first = next(&mut a);
            assert_eq!(first.request, SkillRequest::GetS0);
            a.report(first.id, SkillOutcome::Final(Perception::GotS0))
                .unwrap_or_else(|e| panic!("{e}"));
            let bring = next(&mut a);
            let SkillRequest::BringPuckTo(m) = bring.request else {
                panic!("{bring:?}");
            };
            let unchanged = SkillOutcome::Final(Perception::LightUnchanged);
            a.report_sensed(bring.id, unchanged, true, false, true)
                .unwrap_or_else(|e| panic!("{e}"));
            // Kept the S0 for other work; answered as a machine that consumes it.
            let mut collected = false;
            for i in 0..12 {
                let c = next(&mut a);
                if i == 0 {
                    assert_eq!(a.machines()[m.index()].machine_type, Some(3));
                    assert_eq!(c.puck, "S0", "the puck was kept: {c:?}");
                }
                let outcome = match c.request {
                    SkillRequest::Collect(at) if at == m => {
                        collected = true;
                        break;
                    }
                    SkillRequest::GetS0 => SkillOutcome::Final(Perception::GotS0),
                    SkillRequest::BringPuckTo(at) | SkillRequest::FeedTo(at) if at != m => {
                        SkillOutcome::Final(Perception::LightSeen(LightSignal::Yellow))
                    }
                    _ => panic!("skill {i}: {c:?}"),
                };
                a.report(c.id, outcome).unwrap_or_else(|e| panic!("{e}"));
            }
            assert!(collected, "never came back for the output at {m:?}");
        });
    }

    #[test]
    fn failures_and_storage_empty_become_outcome_slots() {
        assert_eq!(
            outcome_slots(SkillOutcome::Failed(FailReason::StorageEmpty)),
            ("FAILED", "none", "storage-empty")
        );
        assert_eq!(
            outcome_slots(SkillOutcome::Final(Perception::LightUnchanged)),
            ("FAILED", "none", "none")
        );
        assert_eq!(
            outcome_slots(SkillOutcome::Final(Perception::LightSeen(
                LightSignal::YellowFlashing
            ))),
            ("FINAL", "yellow-flashing", "none")
        );
    }
}
