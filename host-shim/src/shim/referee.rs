//! Where the game plugs into the simulated field. [`Referee`] is what the field asks when a
//! robot works a station; [`ClipsReferee`] answers with the rules issue's CLIPS referee
//! (`rules/referee.clp`: hidden types, inputs, outputs, supply, clock, score) run by our
//! engine. Rust moves the robots; it does not re-implement the game: the referee's
//! `rf-result` facts decide what a robot holds afterwards and which light it sees.
//!
//! The one thing Rust adds is time on the field: the referee answers at once and names the
//! processing time (`wait`); the field shows the machine yellow for that long before it
//! shows the referee's light (green), as a real machine would.

use super::rule_engine::{Rules, RulesError};
use hal::field::{GateId, MachineId, RecyclingId, MACHINE_COUNT};
use hal::LightSignal;
use rules::setup::GameSetup;

/// The kinds of puck in the 2012 game.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PuckKind {
    S0,
    S1,
    S2,
    P,
    /// A consumed input left at a machine (2012 recycling).
    Junk,
}

impl PuckKind {
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::S0 => "S0",
            Self::S1 => "S1",
            Self::S2 => "S2",
            Self::P => "P",
            Self::Junk => "JUNK",
        }
    }

    pub fn from_symbol(s: &str) -> Option<Self> {
        [Self::S0, Self::S1, Self::S2, Self::P, Self::Junk]
            .into_iter()
            .find(|k| k.symbol() == s)
    }
}

/// What happened to a puck put into a machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placement {
    /// Taken as an input; more are needed (light yellow), the robot holds nothing.
    Consumed,
    /// Wrong input (light yellow-flashing) or too late: the robot keeps its puck.
    Rejected,
    /// The cycle completed (light green once processed): the robot holds the output.
    Produced(PuckKind),
}

/// The game as the field sees it. Robot numbers are 1..=3.
pub trait Referee {
    /// A robot at the input storage asks for a raw puck.
    fn take_from_storage(&mut self, robot: u8) -> Option<PuckKind>;
    /// A robot puts `puck` under machine `machine`'s light.
    fn place_at_machine(&mut self, robot: u8, machine: MachineId, puck: PuckKind) -> Placement;
    /// A robot drives `puck` into a delivery gate; `true` when the gate took it.
    fn deliver(&mut self, robot: u8, gate: GateId, puck: PuckKind) -> bool;
    /// A robot lets go of `puck` on the field (the agent's discard).
    fn discard(&mut self, robot: u8, puck: PuckKind);
    /// A robot with empty hands takes a junk puck lying at `machine`; `false`: none there.
    fn take_junk(&mut self, robot: u8, machine: MachineId) -> bool;
    /// A robot hands the junk it carries to a recycling unit: the seconds until the unit
    /// hands a raw puck back, or `None` when it refuses (no junk of a machine, too late).
    fn recycle(&mut self, robot: u8, unit: RecyclingId) -> Option<f32>;
    /// The light a camera would see at `machine` now.
    fn light(&self, machine: MachineId) -> LightSignal;
    /// The delivery gate whose light is on.
    fn active_gate(&self) -> Option<GateId>;
    /// Advances the game clock by one cycle.
    fn tick(&mut self, dt_s: f32);
    fn score(&self) -> i32;
    fn game_over(&self) -> bool;
}

/// One answer of the CLIPS referee.
#[derive(Debug, Clone, PartialEq)]
struct RfResult {
    status: String,
    light: Option<LightSignal>,
    puck: Option<PuckKind>,
    wait_s: f64,
}

/// The CLIPS referee in our engine. Build it on a thread with
/// [`super::rule_engine::ENGINE_THREAD_STACK`].
pub struct ClipsReferee {
    rules: Rules,
    clock_s: f64,
    limit_s: Option<f64>,
    next_action: u32,
    lights: [LightSignal; MACHINE_COUNT],
    /// Seconds of processing left per machine and the light shown when it ends.
    processing: [Option<(f32, LightSignal)>; MACHINE_COUNT],
    gate: Option<GateId>,
    score: i32,
    over: bool,
    /// The first engine error: the game stops there (reported by the sim).
    pub fault: Option<RulesError>,
    log: Vec<String>,
}

impl ClipsReferee {
    /// Loads `referee.clp`, asserts the setup's facts (hidden types, times, supply, gate,
    /// clock) and lets the referee fill its defaults.
    pub fn new(setup: &GameSetup) -> Result<Self, RulesError> {
        let mut rules = Rules::load(&[rules::REFEREE])?;
        rules.reset()?;
        let mut text = String::new();
        setup
            .write_clips(&mut text)
            .map_err(|e| RulesError::new("writing the setup", e))?;
        for fact in text
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with('(') && !l.starts_with("(deffacts"))
        {
            rules.assert(fact)?;
        }
        rules.run()?;
        let gate = rules
            .ordered_symbol("active-gate")
            .and_then(|g| g.strip_prefix('D').and_then(|n| n.parse().ok()))
            .and_then(GateId::new);
        let mut referee = Self {
            rules,
            clock_s: 0.0,
            limit_s: setup.clock_limit_s.map(f64::from),
            next_action: 1,
            lights: [LightSignal::Green; MACHINE_COUNT],
            processing: [None; MACHINE_COUNT],
            gate,
            score: 0,
            over: false,
            fault: None,
            log: Vec::new(),
        };
        referee.read_score();
        Ok(referee)
    }

    /// What the referee did since the last call, one line per action.
    pub fn take_log(&mut self) -> Vec<String> {
        std::mem::take(&mut self.log)
    }

    /// The game time in seconds.
    pub fn clock_s(&self) -> f64 {
        self.clock_s
    }

    /// The engine's pool statistics (high-water marks), for the sim's closing report.
    pub fn engine_stats(&self) -> agent_core::Stats {
        self.rules.engine.stats()
    }

    fn read_score(&mut self) {
        if let Some(id) = self.rules.facts_of("score").next() {
            self.score = self
                .rules
                .int(id, "points")
                .and_then(|p| i32::try_from(p).ok())
                .unwrap_or(self.score);
        }
        if self.rules.facts_of("game-over").next().is_some() {
            self.over = true;
        }
    }

    /// Sets the referee's clock to the field's time, asserts the action, runs the referee
    /// and takes its answer.
    fn act(&mut self, robot: u8, kind: &str, target: &str, puck: &str) -> Option<RfResult> {
        if self.over {
            return None;
        }
        match self.try_act(robot, kind, target, puck) {
            Ok(r) => {
                self.log.push(format!(
                    "referee t={:.1} robot={robot} {kind} {target} {puck} -> {} light={} puck={} wait={:.1} score={}",
                    self.clock_s,
                    r.status,
                    r.light.map_or("none", LightSignal::symbol),
                    r.puck.map_or("NONE", PuckKind::symbol),
                    r.wait_s,
                    self.score
                ));
                Some(r)
            }
            Err(e) => {
                self.fault = Some(e);
                self.over = true;
                None
            }
        }
    }

    fn try_act(
        &mut self,
        robot: u8,
        kind: &str,
        target: &str,
        puck: &str,
    ) -> Result<RfResult, RulesError> {
        let id = self.next_action;
        self.next_action += 1;
        // The field's clock is the game's: the referee judges lateness against it.
        let clock: Vec<_> = self.rules.facts_of("game-clock").collect();
        for c in clock {
            let limit = self.rules.number(c, "limit").unwrap_or(900.0);
            let enabled = self
                .rules
                .symbol(c, "enabled")
                .unwrap_or_else(|| "TRUE".into());
            self.rules.retract(c)?;
            self.rules.assert(&format!(
                "(game-clock (time {:.3}) (limit {limit:.3}) (enabled {enabled}))",
                self.clock_s
            ))?;
        }
        self.rules.assert(&format!(
            "(rf-action (id {id}) (kind {kind}) (target {target}) (puck {puck}) (robot {robot}))"
        ))?;
        self.rules.run()?;
        let answer = self
            .rules
            .facts_of("rf-result")
            .find(|&f| self.rules.int(f, "id") == Some(i64::from(id)))
            .ok_or_else(|| {
                RulesError::new(
                    format!("rf-action {id} {kind} {target} {puck}"),
                    "the referee gave no rf-result",
                )
            })?;
        let result = RfResult {
            status: self.rules.symbol(answer, "status").unwrap_or_default(),
            light: self
                .rules
                .symbol(answer, "light")
                .and_then(|l| LightSignal::from_symbol(&l)),
            puck: self
                .rules
                .symbol(answer, "puck")
                .and_then(|p| PuckKind::from_symbol(&p)),
            wait_s: self.rules.number(answer, "wait").unwrap_or(0.0),
        };
        self.rules.retract(answer)?;
        self.read_score();
        Ok(result)
    }
}

impl Referee for ClipsReferee {
    fn take_from_storage(&mut self, robot: u8) -> Option<PuckKind> {
        let r = self.act(robot, "get-s0", "INS", "NONE")?;
        (r.status == "ok").then_some(r.puck).flatten()
    }

    fn place_at_machine(&mut self, robot: u8, machine: MachineId, puck: PuckKind) -> Placement {
        let name = format!("M{}", machine.number());
        let Some(r) = self.act(robot, "load", &name, puck.symbol()) else {
            return Placement::Rejected;
        };
        let i = machine.index();
        match (r.status.as_str(), r.light) {
            ("ok", Some(LightSignal::Green)) => {
                // Processing: yellow, then the referee's green.
                self.lights[i] = LightSignal::Yellow;
                self.processing[i] = Some((r.wait_s as f32, LightSignal::Green));
                r.puck.map_or(Placement::Consumed, Placement::Produced)
            }
            // A machine that still works on its last input goes on with it (its light
            // stays yellow until the referee's green): a puck a robot puts down there
            // meanwhile, e.g. junk it carries while it stops in front of the machine,
            // must not cancel the product (it did: the P under the light never turned
            // green, and the robot that came to collect it waited in vain).
            ("ok", Some(LightSignal::Yellow)) => {
                if self.processing[i].is_none() {
                    self.lights[i] = LightSignal::Yellow;
                }
                Placement::Consumed
            }
            ("ok", Some(light)) => {
                if self.processing[i].is_none() {
                    self.lights[i] = light;
                }
                Placement::Rejected
            }
            // `late`: the processing would end after the clock; the game is over.
            _ => Placement::Rejected,
        }
    }

    fn deliver(&mut self, robot: u8, gate: GateId, puck: PuckKind) -> bool {
        let name = format!("D{}", gate.number());
        self.act(robot, "deliver", &name, puck.symbol())
            .is_some_and(|r| r.status == "ok")
    }

    fn discard(&mut self, robot: u8, puck: PuckKind) {
        let _ = self.act(robot, "discard", "FIELD", puck.symbol());
    }

    fn take_junk(&mut self, robot: u8, machine: MachineId) -> bool {
        let name = format!("M{}", machine.number());
        self.act(robot, "take-junk", &name, "NONE")
            .is_some_and(|r| r.status == "ok")
    }

    fn recycle(&mut self, robot: u8, unit: RecyclingId) -> Option<f32> {
        let name = format!("R{}", unit.number());
        let r = self.act(robot, "recycle", &name, PuckKind::Junk.symbol())?;
        (r.status == "ok").then_some(r.wait_s as f32)
    }

    fn light(&self, machine: MachineId) -> LightSignal {
        self.lights[machine.index()]
    }

    fn active_gate(&self) -> Option<GateId> {
        self.gate
    }

    fn tick(&mut self, dt_s: f32) {
        self.clock_s += f64::from(dt_s);
        for (p, light) in self.processing.iter_mut().zip(self.lights.iter_mut()) {
            if let Some((left, after)) = p {
                *left -= dt_s;
                if *left <= 0.0 {
                    *light = *after;
                    *p = None;
                }
            }
        }
        if self.limit_s.is_some_and(|l| self.clock_s >= l) {
            self.over = true;
        }
    }

    fn score(&self) -> i32 {
        self.score
    }

    fn game_over(&self) -> bool {
        self.over
    }
}

#[cfg(test)]
mod tests {
    use super::super::rule_engine::with_engine_stack;
    use super::*;
    use rules::setup::MachineType;

    fn machine_of(setup: &GameSetup, t: MachineType) -> MachineId {
        (1..=10u8)
            .filter_map(MachineId::new)
            .find(|m| setup.assignment[m.index()] == t)
            .unwrap_or_else(|| panic!("no {t:?}"))
    }

    #[test]
    fn the_clips_referee_plays_a_production_chain() {
        let out = with_engine_stack(|| {
            let setup = GameSetup::for_seed(7);
            let mut r = ClipsReferee::new(&setup).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(r.active_gate().map(|g| g.number()), Some(setup.active_gate));
            let t1 = machine_of(&setup, MachineType::T1);
            let t2 = machine_of(&setup, MachineType::T2);
            assert_eq!(r.take_from_storage(1), Some(PuckKind::S0));
            // A T1 turns S0 into S1: yellow while processing, then green.
            assert_eq!(
                r.place_at_machine(1, t1, PuckKind::S0),
                Placement::Produced(PuckKind::S1)
            );
            assert_eq!(r.light(t1), LightSignal::Yellow);
            for _ in 0..15 * 10 {
                r.tick(1.0 / 15.0);
            }
            assert_eq!(r.light(t1), LightSignal::Green);
            // An S1 is no input of a T1: flashing, the robot keeps it.
            assert_eq!(r.place_at_machine(1, t1, PuckKind::S1), Placement::Rejected);
            assert_eq!(r.light(t1), LightSignal::YellowFlashing);
            // T2: S1 consumed, then S0 completes an S2 (+4).
            assert_eq!(r.place_at_machine(1, t2, PuckKind::S1), Placement::Consumed);
            assert_eq!(r.take_from_storage(1), Some(PuckKind::S0));
            assert_eq!(
                r.place_at_machine(1, t2, PuckKind::S0),
                Placement::Produced(PuckKind::S2)
            );
            assert_eq!(r.score(), 4);
            assert!(r.fault.is_none());
            assert!(!r.game_over());
            r.take_log().len()
        })
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(out, 6);
    }

    #[test]
    fn a_refused_puck_does_not_cancel_a_machine_at_work() {
        with_engine_stack(|| {
            let setup = GameSetup::for_seed(7);
            let mut r = ClipsReferee::new(&setup).unwrap_or_else(|e| panic!("{e}"));
            let t1 = machine_of(&setup, MachineType::T1);
            assert_eq!(r.take_from_storage(1), Some(PuckKind::S0));
            assert_eq!(
                r.place_at_machine(1, t1, PuckKind::S0),
                Placement::Produced(PuckKind::S1)
            );
            // Junk put down while the T1 works: refused, and the machine works on.
            assert_eq!(
                r.place_at_machine(2, t1, PuckKind::Junk),
                Placement::Rejected
            );
            assert_eq!(r.light(t1), LightSignal::Yellow);
            for _ in 0..15 * 10 {
                r.tick(1.0 / 15.0);
            }
            assert_eq!(r.light(t1), LightSignal::Green);
        })
        .unwrap_or_else(|e| panic!("{e}"));
    }

    #[test]
    fn the_storage_runs_empty_and_the_clock_ends_the_game() {
        with_engine_stack(|| {
            let mut setup = GameSetup::for_seed(3);
            setup.s0_supply = 1;
            setup.clock_limit_s = Some(2);
            let mut r = ClipsReferee::new(&setup).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(r.take_from_storage(1), Some(PuckKind::S0));
            assert_eq!(r.take_from_storage(1), None);
            for _ in 0..29 {
                r.tick(1.0 / 15.0);
            }
            assert!(!r.game_over());
            for _ in 0..2 {
                r.tick(1.0 / 15.0);
            }
            assert!(r.game_over());
        })
        .unwrap_or_else(|e| panic!("{e}"));
    }
}
