//! The LLSF 2012 field: a 5.625 m square, origin bottom-left, with ten production machines
//! (0.6 m squares), two recycling units, a test station, three delivery gates and the input
//! storage (2012 rulebook table).

use crate::odometry::Pose2;

/// Side length of the square field.
pub const FIELD_SIZE_M: f32 = 5.625;
/// Side length of a machine's square footprint.
pub const MACHINE_SIZE_M: f32 = 0.6;
/// How far from a machine's centre the 2012 team stopped, facing it.
pub const APPROACH_DISTANCE_M: f32 = 0.605;
/// Number of production machine places.
pub const MACHINE_COUNT: usize = 10;

/// A production machine place, M1..M10.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MachineId(u8);

impl MachineId {
    /// `number` is 1-based as in the rulebook; `None` outside 1..=10.
    pub const fn new(number: u8) -> Option<Self> {
        if number >= 1 && number as usize <= MACHINE_COUNT {
            Some(Self(number))
        } else {
            None
        }
    }

    pub const fn number(self) -> u8 {
        self.0
    }

    pub const fn index(self) -> usize {
        self.0 as usize - 1
    }

    /// The machine's centre.
    pub const fn position(self) -> (f32, f32) {
        MACHINE_POSITIONS[self.index()]
    }

    pub fn all() -> impl Iterator<Item = MachineId> {
        (1..=MACHINE_COUNT as u8).map(MachineId)
    }
}

/// Centres of M1..M10 (metres).
pub const MACHINE_POSITIONS: [(f32, f32); MACHINE_COUNT] = [
    (1.68, 1.68),
    (3.92, 1.68),
    (0.56, 2.80),
    (1.68, 2.80),
    (2.80, 2.80),
    (3.92, 2.80),
    (5.04, 2.80),
    (1.68, 3.92),
    (3.92, 3.92),
    (5.04, 3.92),
];

/// Recycling units 1 and 2.
pub const RECYCLING_POSITIONS: [(f32, f32); 2] = [(0.20, 0.20), (5.40, 5.40)];
/// The test station.
pub const TEST_STATION_POSITION: (f32, f32) = (5.40, 0.20);
/// Delivery gates 1..3.
pub const GATE_POSITIONS: [(f32, f32); 3] = [(3.15, 0.26), (2.80, 0.26), (2.45, 0.26)];
/// The team's navigation pose in front of the input storage.
pub const INPUT_STORAGE_POSITION: (f32, f32) = (2.25, 4.90);

/// A recycling unit, 1..=2 (the rules' `R1`, `R2`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecyclingId(u8);

impl RecyclingId {
    pub const fn new(number: u8) -> Option<Self> {
        if number >= 1 && number <= 2 {
            Some(Self(number))
        } else {
            None
        }
    }

    pub const fn number(self) -> u8 {
        self.0
    }

    pub const fn position(self) -> (f32, f32) {
        RECYCLING_POSITIONS[self.0 as usize - 1]
    }
}

/// How far from a recycling unit (in a field corner) a robot stops, facing it.
pub const RECYCLING_APPROACH_M: f32 = 0.55;

/// The pose in front of a recycling unit: on the diagonal towards the field's centre,
/// facing the corner where the unit stands.
pub fn recycling_pose(unit: RecyclingId) -> Pose2 {
    let (x, y) = unit.position();
    let c = FIELD_SIZE_M / 2.0;
    let (dx, dy) = (c - x, c - y);
    let n = libm::hypotf(dx, dy);
    let (ux, uy) = (dx / n, dy / n);
    Pose2::new(
        x + RECYCLING_APPROACH_M * ux,
        y + RECYCLING_APPROACH_M * uy,
        libm::atan2f(-uy, -ux),
    )
}

/// A delivery gate, 1..=3.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GateId(u8);

impl GateId {
    pub const fn new(number: u8) -> Option<Self> {
        if number >= 1 && number <= 3 {
            Some(Self(number))
        } else {
            None
        }
    }

    pub const fn number(self) -> u8 {
        self.0
    }

    pub const fn position(self) -> (f32, f32) {
        GATE_POSITIONS[self.0 as usize - 1]
    }
}

/// Distance from a point to the nearest wall or machine footprint, ignoring machine
/// `except` (the one being approached).
pub fn clearance(x_m: f32, y_m: f32, except: Option<MachineId>) -> f32 {
    let walls = x_m.min(y_m).min(FIELD_SIZE_M - x_m).min(FIELD_SIZE_M - y_m);
    let half = MACHINE_SIZE_M / 2.0;
    MACHINE_POSITIONS
        .iter()
        .enumerate()
        .filter(|&(i, _)| except.is_none_or(|m| m.index() != i))
        .map(|(_, &(mx, my))| {
            let dx = ((x_m - mx).abs() - half).max(0.0);
            let dy = ((y_m - my).abs() - half).max(0.0);
            libm::hypotf(dx, dy)
        })
        .fold(walls, f32::min)
}

/// The pose from which a robot works a machine: [`APPROACH_DISTANCE_M`] from its centre,
/// facing it, on whichever side (below, above, left, right) leaves the most room; several
/// machines have only a few centimetres to spare on the side facing a neighbour.
pub fn machine_approach_pose(machine: MachineId) -> Pose2 {
    use core::f32::consts::{FRAC_PI_2, PI};
    let (x, y) = machine.position();
    let d = APPROACH_DISTANCE_M;
    let candidates = [
        Pose2::new(x, y - d, FRAC_PI_2),
        Pose2::new(x, y + d, -FRAC_PI_2),
        Pose2::new(x - d, y, 0.0),
        Pose2::new(x + d, y, PI),
    ];
    let mut best = candidates[0];
    let mut best_room = f32::NEG_INFINITY;
    for c in candidates {
        let room = clearance(c.x_m, c.y_m, Some(machine));
        // Strictly better only: ties keep the earlier side, so the choice is stable.
        if room > best_room + 1e-4 {
            best = c;
            best_room = room;
        }
    }
    best
}

/// The pose in front of the input storage, facing it (+y, towards the field's top edge).
pub fn input_storage_pose() -> Pose2 {
    let (x, y) = INPUT_STORAGE_POSITION;
    Pose2::new(x, y, core::f32::consts::FRAC_PI_2)
}

/// Where robot `robot` (1..=3) picks raw pucks up: the storage is a strip along the top
/// edge, and each robot uses its own spot so two robots never queue for one point.
pub fn input_storage_pose_for(robot: u8) -> Pose2 {
    let offset = [0.0, -1.2, 1.2][usize::from(robot.clamp(1, 3)) - 1];
    let p = input_storage_pose();
    Pose2::new(p.x_m + offset, p.y_m, p.phi_rad)
}

/// The pose in front of a delivery gate, facing it (-y, towards the bottom edge).
pub fn gate_pose(gate: GateId) -> Pose2 {
    let (x, y) = gate.position();
    Pose2::new(x, y + 0.35, -core::f32::consts::FRAC_PI_2)
}

/// True when the point lies within `margin_m` of a machine's footprint or outside the field
/// (shrunk by `margin_m`).
pub fn is_blocked(x_m: f32, y_m: f32, margin_m: f32) -> bool {
    if x_m < margin_m
        || y_m < margin_m
        || x_m > FIELD_SIZE_M - margin_m
        || y_m > FIELD_SIZE_M - margin_m
    {
        return true;
    }
    let half = MACHINE_SIZE_M / 2.0 + margin_m;
    MACHINE_POSITIONS
        .iter()
        .any(|&(mx, my)| (x_m - mx).abs() < half && (y_m - my).abs() < half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_ids_are_one_based() {
        assert_eq!(MachineId::new(0), None);
        assert_eq!(MachineId::new(11), None);
        assert_eq!(
            MachineId::new(5).map(MachineId::position),
            Some((2.80, 2.80))
        );
        assert_eq!(MachineId::all().count(), 10);
        assert_eq!(GateId::new(4), None);
    }

    #[test]
    fn approach_poses_are_free_and_inside() {
        // A robot's radius is about 0.2 m.
        for m in MachineId::all() {
            let p = machine_approach_pose(m);
            assert!(!is_blocked(p.x_m, p.y_m, 0.2), "{m:?} {p:?}");
        }
        for unit in 1..=2 {
            let r = RecyclingId::new(unit)
                .map(recycling_pose)
                .unwrap_or_default();
            assert!(!is_blocked(r.x_m, r.y_m, 0.2), "R{unit} {r:?}");
        }
        for robot in 1..=3 {
            let s = input_storage_pose_for(robot);
            assert!(!is_blocked(s.x_m, s.y_m, 0.2), "robot {robot} {s:?}");
        }
        for g in 1..=3 {
            let p = GateId::new(g).map(gate_pose).unwrap_or_default();
            assert!(!is_blocked(p.x_m, p.y_m, 0.2), "gate {g} {p:?}");
        }
    }

    #[test]
    fn approach_side_has_the_most_room() {
        // M5 is free below; M4 has equal 3 cm gaps on every side, below wins the tie.
        let m = |n| MachineId::new(n).unwrap_or_else(|| panic!("{n}"));
        let p5 = machine_approach_pose(m(5));
        assert!(
            (p5.x_m - 2.80).abs() < 1e-5 && (p5.y_m - 2.195).abs() < 1e-4,
            "{p5:?}"
        );
        // M8 is approached from above (row M3..M7 lies below it).
        let p8 = machine_approach_pose(m(8));
        assert!(p8.y_m > 3.92, "{p8:?}");
        for machine in MachineId::all() {
            let p = machine_approach_pose(machine);
            assert!(
                clearance(p.x_m, p.y_m, Some(machine)) >= 0.185,
                "{machine:?} {p:?}"
            );
            // Facing the machine.
            let (mx, my) = machine.position();
            let bearing = libm::atan2f(my - p.y_m, mx - p.x_m);
            assert!(crate::wrap_angle(bearing - p.phi_rad).abs() < 1e-4);
        }
    }

    #[test]
    fn machines_and_walls_block() {
        assert!(is_blocked(1.68, 1.68, 0.0));
        assert!(is_blocked(1.68 + 0.35, 1.68, 0.1));
        assert!(!is_blocked(1.68 + 0.45, 1.68, 0.1));
        assert!(is_blocked(-0.1, 1.0, 0.0));
        assert!(is_blocked(5.6, 1.0, 0.1));
    }
}
