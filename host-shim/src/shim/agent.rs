//! The deliberative agent inside `robotino-agent run`: the rules issue's agent rule base
//! (`rules::agent_files(strategy)`) in our engine. The shim turns skill outcomes and
//! perceptions into facts (`skill-outcome`, `active-gate`, teammates' machine types), runs
//! the engine to quiescence while the robot is idle, and reads the `skill-request` it chose.
//! The fact interface is `rules/README.md`'s "Agent <-> executor".

use super::rule_engine::{Rules, RulesError};
use hal::field::{GateId, MachineId, MACHINE_COUNT};
use hal::skill::{FailReason, Perception, SkillOutcome, SkillRequest};
use hal::LightSignal;
use rules::Strategy;

use super::payloads::{LOADED_S0, LOADED_S1, LOADED_S2};

/// A skill the rules chose: the `skill-request` fact and what it asks of the behaviour layer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChosenSkill {
    pub id: i64,
    /// The rules' names: `get-s0`, `finish-puck-at`, `deliver`, `discard`.
    pub name: String,
    pub target: String,
    /// The puck the agent believes it carries.
    pub puck: String,
    pub request: SkillRequest,
}

/// What the agent knows of one machine: its definite type (1..=3) and the inputs it
/// believes loaded (payload bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MachineView {
    pub machine_type: Option<u8>,
    pub loaded: u8,
}

/// The agent's rules in our engine.
pub struct EngineAgent {
    rules: Rules,
    /// The request handed to the behaviour layer and not answered yet.
    handed_out: Option<i64>,
    gate_told: bool,
    /// Rules fired by the last [`EngineAgent::decide`].
    pub last_fired: u32,
}

impl EngineAgent {
    /// Loads the strategy's agent files and resets (the agent's beliefs are deffacts).
    /// Call on a thread with [`super::rule_engine::ENGINE_THREAD_STACK`].
    pub fn new(strategy: Strategy) -> Result<Self, RulesError> {
        let mut rules = Rules::load(rules::agent_files(strategy))?;
        // `distance` is a host function of the rules; our engine has it built in.
        rules
            .eval("(distance 0 0 3 4)")
            .map_err(|e| RulesError::new("checking the `distance` builtin", e.message))?;
        rules.reset()?;
        Ok(Self {
            rules,
            handed_out: None,
            gate_told: false,
            last_fired: 0,
        })
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
        self.last_fired = self.rules.run()?;
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

    /// Tells the rules how skill `id` ended: asserts its `skill-outcome`.
    pub fn report(&mut self, id: i64, outcome: SkillOutcome) -> Result<(), RulesError> {
        let (status, light, info) = outcome_slots(outcome);
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

    /// A teammate found out machine `m`'s type: narrow our belief to it when it is one of
    /// the types we still consider possible. Returns whether the belief changed.
    pub fn adopt_type(&mut self, m: MachineId, machine_type: u8) -> Result<bool, RulesError> {
        let t = match machine_type {
            1 => "T1",
            2 => "T2",
            3 => "T3",
            _ => return Ok(false),
        };
        let name = format!("M{}", m.number());
        let Some(f) = self
            .rules
            .facts_of("machine")
            .find(|&f| self.rules.symbol(f, "name").as_deref() == Some(name.as_str()))
        else {
            return Ok(false);
        };
        // T1_2_3, T1_2, T2_3: the digits are the types still possible.
        let current = self.rules.symbol(f, "mtype").unwrap_or_default();
        let digit = char::from(b'0' + machine_type);
        if current == t || !current.contains(digit) {
            return Ok(false);
        }
        // A modify, spelled out: the same fact with the narrowed type, as a new fact.
        let index = self.rules.int(f, "index").unwrap_or(0);
        let loaded = self.rules.symbols(f, "loaded-with").join(" ");
        let junk = self.rules.int(f, "junk").unwrap_or(0);
        let productions = self.rules.int(f, "productions").unwrap_or(0);
        self.rules.retract(f)?;
        self.rules.assert(&format!(
            "(machine (name {name}) (index {index}) (mtype {t}) (loaded-with {loaded}) (junk {junk}) (productions {productions}))"
        ))?;
        Ok(true)
    }

    /// What the rules printed since the last call.
    pub fn take_output(&mut self) -> String {
        self.rules.take_output()
    }

    pub fn engine_stats(&self) -> agent_core::Stats {
        self.rules.engine.stats()
    }
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
        SkillOutcome::Final(Perception::GotS0 | Perception::Delivered | Perception::Released) => {
            ("FINAL", "none", "none")
        }
        SkillOutcome::Failed(FailReason::StorageEmpty) => ("FAILED", "none", "storage-empty"),
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

    #[test]
    fn a_teammates_type_narrows_the_belief_once() {
        on_engine_stack(|| {
            let mut a = EngineAgent::new(Strategy::Travel).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(a.machines()[4].machine_type, None);
            assert_eq!(a.adopt_type(m(5), 3), Ok(true));
            assert_eq!(a.machines()[4].machine_type, Some(3));
            assert_eq!(a.adopt_type(m(5), 3), Ok(false));
            // A type our belief already excludes is not taken.
            assert_eq!(a.adopt_type(m(5), 1), Ok(false));
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
