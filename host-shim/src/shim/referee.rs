//! Where the game plugs into the simulated field. The real referee is the rules issue's
//! CLIPS program run by our engine; [`Referee`] is the interface it implements.
//! [`StandInReferee`] is a deliberately small placeholder (instant processing, one active
//! gate) so the field can be exercised before that lands.

use hal::field::{GateId, MachineId, MACHINE_COUNT};
use hal::LightSignal;

/// The kinds of puck in the 2012 game.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PuckKind {
    S0,
    S1,
    S2,
    P,
    Junk,
}

/// What happened to a puck put into a machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placement {
    /// Taken as an input; more are needed (light yellow), the robot holds nothing.
    Consumed,
    /// Wrong input (light yellow-flashing): the robot keeps its puck.
    Rejected,
    /// The cycle completed (light green): the robot now holds the output.
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
    /// The light a camera would see at `machine` now.
    fn light(&self, machine: MachineId) -> LightSignal;
    /// Advances the game clock by one cycle.
    fn tick(&mut self, dt_s: f32);
    fn score(&self) -> i32;
    fn game_over(&self) -> bool;
}

/// Machine type T1..T3 and what it needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MachineType {
    T1,
    T2,
    T3,
}

impl MachineType {
    fn inputs(self) -> &'static [PuckKind] {
        match self {
            Self::T1 => &[PuckKind::S0],
            Self::T2 => &[PuckKind::S0, PuckKind::S1],
            Self::T3 => &[PuckKind::S0, PuckKind::S1, PuckKind::S2],
        }
    }

    /// The rulebook's shortest processing time after the last input.
    fn processing_s(self) -> f32 {
        match self {
            Self::T1 => 3.0,
            Self::T2 => 15.0,
            Self::T3 => 40.0,
        }
    }

    fn output(self) -> PuckKind {
        match self {
            Self::T1 => PuckKind::S1,
            Self::T2 => PuckKind::S2,
            Self::T3 => PuckKind::P,
        }
    }

    /// 1..=3, as in the world-model payload.
    pub fn code(self) -> u8 {
        match self {
            Self::T1 => 1,
            Self::T2 => 2,
            Self::T3 => 3,
        }
    }
}

/// The placeholder referee: seeded machine types (4 x T1, 3 x T2, 3 x T3), inputs taken in
/// any order; when the last input arrives the robot holds the output at once and the light
/// stays yellow for the processing time (the rulebook's lower bounds: 3, 15, 40 s), then
/// turns green. Gate 1 is active; 2012 scoring.
#[derive(Debug, Clone)]
pub struct StandInReferee {
    types: [MachineType; MACHINE_COUNT],
    loaded: [Vec<PuckKind>; MACHINE_COUNT],
    lights: [LightSignal; MACHINE_COUNT],
    /// Seconds of processing left per machine; the light turns green at zero.
    processing_left_s: [f32; MACHINE_COUNT],
    storage_left: u32,
    score: i32,
    elapsed_s: f32,
    game_length_s: f32,
}

impl StandInReferee {
    pub fn new(seed: u64, raw_pucks: u32, game_length_s: f32) -> Self {
        use MachineType::*;
        let mut types = [T1, T1, T1, T1, T2, T2, T2, T3, T3, T3];
        // Fisher-Yates with a small LCG: the assignment is a function of the seed.
        let mut state = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        for i in (1..types.len()).rev() {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let j = (state >> 33) as usize % (i + 1);
            types.swap(i, j);
        }
        Self {
            types,
            loaded: Default::default(),
            lights: [LightSignal::Green; MACHINE_COUNT],
            processing_left_s: [0.0; MACHINE_COUNT],
            storage_left: raw_pucks,
            score: 0,
            elapsed_s: 0.0,
            game_length_s,
        }
    }

    pub fn machine_type(&self, machine: MachineId) -> MachineType {
        self.types[machine.index()]
    }
}

impl Referee for StandInReferee {
    fn take_from_storage(&mut self, _robot: u8) -> Option<PuckKind> {
        if self.storage_left == 0 || self.game_over() {
            return None;
        }
        self.storage_left -= 1;
        Some(PuckKind::S0)
    }

    fn place_at_machine(&mut self, _robot: u8, machine: MachineId, puck: PuckKind) -> Placement {
        let i = machine.index();
        let kind = self.types[i];
        let wanted = kind.inputs().contains(&puck) && !self.loaded[i].contains(&puck);
        if !wanted || self.game_over() {
            self.lights[i] = LightSignal::YellowFlashing;
            return Placement::Rejected;
        }
        self.loaded[i].push(puck);
        if self.loaded[i].len() < kind.inputs().len() {
            self.lights[i] = LightSignal::Yellow;
            return Placement::Consumed;
        }
        self.loaded[i].clear();
        self.lights[i] = LightSignal::Yellow;
        self.processing_left_s[i] = kind.processing_s();
        self.score += match kind {
            MachineType::T1 => 0,
            MachineType::T2 => 4,
            MachineType::T3 => 12,
        };
        Placement::Produced(kind.output())
    }

    fn deliver(&mut self, _robot: u8, gate: GateId, puck: PuckKind) -> bool {
        if gate.number() != 1 || self.game_over() {
            return false;
        }
        if puck == PuckKind::P {
            self.score += 5;
        }
        true
    }

    fn light(&self, machine: MachineId) -> LightSignal {
        self.lights[machine.index()]
    }

    fn tick(&mut self, dt_s: f32) {
        self.elapsed_s += dt_s;
        for (left, light) in self
            .processing_left_s
            .iter_mut()
            .zip(self.lights.iter_mut())
        {
            if *left > 0.0 {
                *left -= dt_s;
                if *left <= 0.0 {
                    *left = 0.0;
                    *light = LightSignal::Green;
                }
            }
        }
    }

    fn score(&self) -> i32 {
        self.score
    }

    fn game_over(&self) -> bool {
        self.elapsed_s >= self.game_length_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn machine_of(r: &StandInReferee, t: MachineType) -> MachineId {
        MachineId::all()
            .find(|&m| r.machine_type(m) == t)
            .unwrap_or_else(|| panic!("no {t:?}"))
    }

    #[test]
    fn type_counts_follow_the_rulebook_and_depend_on_the_seed() {
        let a = StandInReferee::new(1, 20, 900.0);
        let b = StandInReferee::new(2, 20, 900.0);
        let count =
            |r: &StandInReferee, t| MachineId::all().filter(|&m| r.machine_type(m) == t).count();
        assert_eq!(count(&a, MachineType::T1), 4);
        assert_eq!(count(&a, MachineType::T2), 3);
        assert_eq!(count(&a, MachineType::T3), 3);
        assert_ne!(a.types, b.types);
    }

    #[test]
    fn production_chain_scores() {
        let mut r = StandInReferee::new(7, 20, 900.0);
        let t1 = machine_of(&r, MachineType::T1);
        let t2 = machine_of(&r, MachineType::T2);
        assert_eq!(r.take_from_storage(1), Some(PuckKind::S0));
        assert_eq!(
            r.place_at_machine(1, t1, PuckKind::S0),
            Placement::Produced(PuckKind::S1)
        );
        assert_eq!(r.light(t1), LightSignal::Yellow);
        r.tick(2.9);
        assert_eq!(r.light(t1), LightSignal::Yellow);
        r.tick(0.2);
        assert_eq!(r.light(t1), LightSignal::Green);
        assert_eq!(r.place_at_machine(1, t2, PuckKind::S1), Placement::Consumed);
        assert_eq!(r.light(t2), LightSignal::Yellow);
        assert_eq!(r.place_at_machine(1, t2, PuckKind::S1), Placement::Rejected);
        assert_eq!(r.light(t2), LightSignal::YellowFlashing);
        assert_eq!(
            r.place_at_machine(1, t2, PuckKind::S0),
            Placement::Produced(PuckKind::S2)
        );
        assert_eq!(r.score(), 4);
        let gate = GateId::new(1).unwrap_or_else(|| panic!());
        assert!(r.deliver(1, gate, PuckKind::P));
        assert_eq!(r.score(), 9);
    }

    #[test]
    fn storage_runs_out_and_the_clock_ends_the_game() {
        let mut r = StandInReferee::new(1, 1, 1.0);
        assert!(r.take_from_storage(1).is_some());
        assert!(r.take_from_storage(1).is_none());
        r.tick(0.6);
        assert!(!r.game_over());
        r.tick(0.6);
        assert!(r.game_over());
    }
}
