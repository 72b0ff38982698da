//! Deterministic game setups: the hidden machine assignment, processing
//! times, the active gate and injected faults, drawn from a seed by our own
//! PRNG (the rule bases never call `random`), and written as CLIPS facts.

use core::fmt::{self, Write};

/// Machines on the field, in place order M1..M10.
pub const MACHINE_COUNT: usize = 10;
/// Distinct assignments of 4 x T1, 3 x T2, 3 x T3: 10! / (4! 3! 3!).
pub const ASSIGNMENT_COUNT: u32 = 4200;
/// Ways to place the four T1 among ten machines: C(10, 4).
const T1_PLACEMENTS: u32 = 210;
/// Ways to place the three T2 among the remaining six: C(6, 3).
const T2_PLACEMENTS: u32 = 20;
/// Most faults a setup carries.
pub const MAX_FAULTS: usize = 8;

/// A production machine type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum MachineType {
    T1,
    T2,
    T3,
}

impl MachineType {
    pub fn as_str(self) -> &'static str {
        match self {
            MachineType::T1 => "T1",
            MachineType::T2 => "T2",
            MachineType::T3 => "T3",
        }
    }
}

/// One type per machine, index 0 is M1.
pub type Assignment = [MachineType; MACHINE_COUNT];

/// SplitMix64: tiny, well mixed, the same on every target.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..bound` (rejection sampling, no modulo bias).
    /// A zero bound yields 0.
    pub fn below(&mut self, bound: u64) -> u64 {
        if bound == 0 {
            return 0;
        }
        // Largest multiple of bound that fits: draws above it are redrawn.
        let zone = u64::MAX - (u64::MAX % bound);
        loop {
            let draw = self.next_u64();
            if draw < zone {
                return draw % bound;
            }
        }
    }

    /// Uniform in `low..=high`.
    pub fn in_range(&mut self, low: u32, high: u32) -> u32 {
        low + self.below(u64::from(high.saturating_sub(low)) + 1) as u32
    }
}

/// Seeds for independent streams derived from one game seed, so adding a
/// draw to one stream never shifts another.
const STREAM_ASSIGNMENT: u64 = 0x4153_5349_474E; // "ASSIGN"
const STREAM_TIMES: u64 = 0x0054_494D_4553; // "TIMES"
const STREAM_GATE: u64 = 0x4741_5445; // "GATE"
const STREAM_FAULTS: u64 = 0x4641_554C_5453; // "FAULTS"

fn stream(seed: u64, salt: u64) -> SplitMix64 {
    let mut mixer = SplitMix64::new(seed ^ salt.rotate_left(17));
    SplitMix64::new(mixer.next_u64())
}

/// The 2012 mix in place order before shuffling.
const BASE_MIX: Assignment = [
    MachineType::T1,
    MachineType::T1,
    MachineType::T1,
    MachineType::T1,
    MachineType::T2,
    MachineType::T2,
    MachineType::T2,
    MachineType::T3,
    MachineType::T3,
    MachineType::T3,
];

/// The hidden assignment of a seeded game: 4 x T1, 3 x T2, 3 x T3 shuffled
/// (Fisher-Yates).
pub fn assignment_for_seed(seed: u64) -> Assignment {
    let mut rng = stream(seed, STREAM_ASSIGNMENT);
    let mut mix = BASE_MIX;
    for i in (1..MACHINE_COUNT).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        mix.swap(i, j);
    }
    mix
}

/// Binomial coefficient for the small numbers used here.
fn choose(n: u32, k: u32) -> u32 {
    if k > n {
        return 0;
    }
    let mut result: u32 = 1;
    for i in 0..k {
        result = result * (n - i) / (i + 1);
    }
    result
}

/// Writes the `rank`-th (lexicographic) k-subset of `0..n` into `out`.
fn unrank_subset(mut rank: u32, n: u32, k: u32, out: &mut [u32]) {
    let mut next = 0;
    for (slot, chosen) in out.iter_mut().enumerate().take(k as usize) {
        let left = k - slot as u32 - 1;
        loop {
            // Subsets whose element `slot` is `next`.
            let with_next = choose(n - next - 1, left);
            if rank < with_next {
                break;
            }
            rank -= with_next;
            next += 1;
        }
        *chosen = next;
        next += 1;
    }
}

/// Rank of a sorted k-subset of `0..n` (inverse of [`unrank_subset`]).
fn rank_subset(subset: &[u32], n: u32) -> u32 {
    let k = subset.len() as u32;
    let mut rank = 0;
    let mut next = 0;
    for (slot, &chosen) in subset.iter().enumerate() {
        let left = k - slot as u32 - 1;
        while next < chosen {
            rank += choose(n - next - 1, left);
            next += 1;
        }
        next += 1;
    }
    rank
}

/// The `index`-th distinct assignment (0..4200): the T1 places are the
/// `index / 20`-th 4-subset of the ten machines, the T2 places the
/// `index % 20`-th 3-subset of the six left; the rest are T3.
pub fn assignment_by_index(index: u32) -> Option<Assignment> {
    if index >= ASSIGNMENT_COUNT {
        return None;
    }
    let mut t1 = [0u32; 4];
    unrank_subset(index / T2_PLACEMENTS, 10, 4, &mut t1);
    let mut t2 = [0u32; 3];
    unrank_subset(index % T2_PLACEMENTS, 6, 3, &mut t2);
    let mut out = [MachineType::T3; MACHINE_COUNT];
    let mut free_slot = 0u32;
    for (place, machine) in out.iter_mut().enumerate() {
        if t1.contains(&(place as u32)) {
            *machine = MachineType::T1;
        } else {
            if t2.contains(&free_slot) {
                *machine = MachineType::T2;
            }
            free_slot += 1;
        }
    }
    Some(out)
}

/// Inverse of [`assignment_by_index`]; `None` unless the mix is 4/3/3.
pub fn index_of_assignment(assignment: &Assignment) -> Option<u32> {
    let mut t1 = [0u32; 4];
    let mut t2 = [0u32; 3];
    let (mut n1, mut n2, mut free_slot) = (0usize, 0usize, 0u32);
    for (place, machine) in assignment.iter().enumerate() {
        match machine {
            MachineType::T1 => {
                *t1.get_mut(n1)? = place as u32;
                n1 += 1;
                continue;
            }
            MachineType::T2 => {
                *t2.get_mut(n2)? = free_slot;
                n2 += 1;
            }
            MachineType::T3 => {}
        }
        free_slot += 1;
    }
    if n1 != 4 || n2 != 3 {
        return None;
    }
    let index = rank_subset(&t1, 10) * T2_PLACEMENTS + rank_subset(&t2, 6);
    debug_assert!(index < T1_PLACEMENTS * T2_PLACEMENTS);
    Some(index)
}

/// Processing times in tenths of a second (integers keep the text that
/// both engines print identical).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProcessingTimes {
    pub t1_tenths: u32,
    pub t2_tenths: u32,
    pub t3_tenths: u32,
    pub per_input_tenths: u32,
}

impl ProcessingTimes {
    /// Midpoints of the 2012 ranges (3-8 s, 15-25 s, 40-60 s), 2 s per
    /// consumed input.
    pub const MIDPOINTS: ProcessingTimes = ProcessingTimes {
        t1_tenths: 55,
        t2_tenths: 200,
        t3_tenths: 500,
        per_input_tenths: 20,
    };

    /// Times drawn uniformly (0.1 s steps) from the 2012 ranges.
    pub fn for_seed(seed: u64) -> ProcessingTimes {
        let mut rng = stream(seed, STREAM_TIMES);
        ProcessingTimes {
            t1_tenths: rng.in_range(30, 80),
            t2_tenths: rng.in_range(150, 250),
            t3_tenths: rng.in_range(400, 600),
            per_input_tenths: 20,
        }
    }
}

/// How an injected fault makes a skill fail (see sim.clp).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultKind {
    LosePuck,
    DriveFail,
}

impl FaultKind {
    pub fn as_str(self) -> &'static str {
        match self {
            FaultKind::LosePuck => "lose-puck",
            FaultKind::DriveFail => "drive-fail",
        }
    }
}

/// The skill request with id `at_decision` fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fault {
    pub at_decision: u32,
    pub kind: FaultKind,
}

/// Everything the host asserts before a game.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GameSetup {
    pub assignment: Assignment,
    pub times: ProcessingTimes,
    pub s0_supply: u32,
    /// 1..=3: delivery gate D1, D2 or D3.
    pub active_gate: u8,
    /// Game length in seconds; `None` plays with the clock off.
    pub clock_limit_s: Option<u32>,
    faults: [Option<Fault>; MAX_FAULTS],
}

/// Why a fault could not be added.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaultsFull;

impl fmt::Display for FaultsFull {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a game setup holds at most {MAX_FAULTS} faults")
    }
}

impl GameSetup {
    /// The 2012 defaults around an assignment: midpoint times, 20 S0,
    /// gate D1, 15-minute clock, no faults.
    pub fn new(assignment: Assignment) -> GameSetup {
        GameSetup {
            assignment,
            times: ProcessingTimes::MIDPOINTS,
            s0_supply: 20,
            active_gate: 1,
            clock_limit_s: Some(900),
            faults: [None; MAX_FAULTS],
        }
    }

    /// A seeded game: assignment and active gate from the seed, midpoint
    /// times (use [`GameSetup::with_seeded_times`] to draw them too).
    pub fn for_seed(seed: u64) -> GameSetup {
        let mut setup = GameSetup::new(assignment_for_seed(seed));
        setup.active_gate = 1 + stream(seed, STREAM_GATE).below(3) as u8;
        setup
    }

    /// Draw processing times from the seed instead of the midpoints.
    pub fn with_seeded_times(mut self, seed: u64) -> GameSetup {
        self.times = ProcessingTimes::for_seed(seed);
        self
    }

    /// Adds a fault.
    pub fn add_fault(&mut self, fault: Fault) -> Result<(), FaultsFull> {
        let free = self
            .faults
            .iter_mut()
            .find(|f| f.is_none())
            .ok_or(FaultsFull)?;
        *free = Some(fault);
        Ok(())
    }

    /// Schedules `count` faults (at most [`MAX_FAULTS`]) at distinct
    /// decisions among the first `horizon`, kinds alternating by draw.
    pub fn with_seeded_faults(mut self, seed: u64, count: usize, horizon: u32) -> GameSetup {
        let mut rng = stream(seed, STREAM_FAULTS);
        let wanted = count.min(MAX_FAULTS).min(horizon as usize);
        let mut added = 0;
        while added < wanted {
            let at_decision = 1 + rng.below(u64::from(horizon)) as u32;
            if self.faults().any(|f| f.at_decision == at_decision) {
                continue;
            }
            let kind = if rng.below(2) == 0 {
                FaultKind::LosePuck
            } else {
                FaultKind::DriveFail
            };
            if self.add_fault(Fault { at_decision, kind }).is_err() {
                break;
            }
            added += 1;
        }
        self
    }

    pub fn faults(&self) -> impl Iterator<Item = Fault> + '_ {
        self.faults.iter().flatten().copied()
    }

    /// Writes the setup as one CLIPS construct, `(deffacts game-setup ...)`:
    /// load it with the rule files, then `(reset)` and `(run)`.
    pub fn write_clips<W: Write>(&self, out: &mut W) -> fmt::Result {
        writeln!(out, "(deffacts game-setup")?;
        for (i, machine) in self.assignment.iter().enumerate() {
            writeln!(
                out,
                "  (rf-machine (name M{}) (type {}))",
                i + 1,
                machine.as_str()
            )?;
        }
        let t = &self.times;
        writeln!(
            out,
            "  (rf-times (t1 {}) (t2 {}) (t3 {}) (per-input {}))",
            Tenths(t.t1_tenths),
            Tenths(t.t2_tenths),
            Tenths(t.t3_tenths),
            Tenths(t.per_input_tenths)
        )?;
        writeln!(out, "  (s0-supply {})", self.s0_supply)?;
        writeln!(out, "  (active-gate D{})", self.active_gate)?;
        match self.clock_limit_s {
            Some(limit) => writeln!(out, "  (game-clock (limit {limit}.0) (enabled TRUE))")?,
            None => writeln!(out, "  (game-clock (limit 900.0) (enabled FALSE))")?,
        }
        for fault in self.faults() {
            writeln!(
                out,
                "  (fault (at-decision {}) (kind {}))",
                fault.at_decision,
                fault.kind.as_str()
            )?;
        }
        writeln!(out, ")")
    }
}

/// Tenths of a second printed as a CLIPS float (`55` -> `5.5`).
struct Tenths(u32);

impl fmt::Display for Tenths {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{}", self.0 / 10, self.0 % 10)
    }
}

/// The facts of a `(deffacts game-setup ...)` text written by
/// [`GameSetup::write_clips`], one per line. Asserting them right after `(reset)`
/// gives the same facts, fact numbers and agenda as loading the deffacts before the
/// reset, and lets one engine play many setups without redefining constructs.
pub fn fact_lines(deffacts: &str) -> impl Iterator<Item = &str> {
    deffacts
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with('(') && !l.starts_with("(deffacts"))
}
