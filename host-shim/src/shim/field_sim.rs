//! The simulated field as a pure function of motor commands: robot poses integrated from the
//! commanded wheel speeds, collisions with machines, walls and other robots (bumper), IR ray
//! casting, gyro and odometry with seeded noise, the motor dead-man rule, and the pucks'
//! way through the [`Referee`]. The `robotino-sim` process wraps this in iceoryx2.

use super::config::Config;
use super::referee::{Placement, PuckKind, Referee};
use hal::device::GyroSample;
use hal::field::{
    gate_pose, input_storage_pose_for, machine_approach_pose, recycling_pose, GateId, MachineId,
    RecyclingId, FIELD_SIZE_M, MACHINE_POSITIONS, MACHINE_SIZE_M,
};
use hal::ir::{sensor_angle_rad, IrScan, IR_MAX_RANGE_M, IR_MIN_RANGE_M, IR_SENSOR_COUNT};
use hal::odometry::OdometryIntegrator;
use hal::{wrap_angle, DriveGeometry, LightSignal, Pose2, WheelSpeeds};

/// Deterministic noise: xorshift64* and Box-Muller.
#[derive(Debug, Clone)]
pub struct Noise {
    state: u64,
}

impl Noise {
    pub fn new(seed: u64) -> Self {
        Self {
            state: seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1,
        }
    }

    fn uniform(&mut self) -> f32 {
        self.state ^= self.state >> 12;
        self.state ^= self.state << 25;
        self.state ^= self.state >> 27;
        let x = self.state.wrapping_mul(0x2545_F491_4F6C_DD1D);
        ((x >> 40) as f32 + 0.5) / (1u64 << 24) as f32
    }

    /// A normal sample with standard deviation `sigma` (0 gives exactly 0).
    pub fn gaussian(&mut self, sigma: f32) -> f32 {
        if sigma == 0.0 {
            return 0.0;
        }
        let (u1, u2) = (self.uniform(), self.uniform());
        sigma * (-2.0 * u1.ln()).sqrt() * (2.0 * core::f32::consts::PI * u2).cos()
    }
}

/// How close to a station's pose (position, heading) a robot must be to work it.
const STATION_REACH_M: f32 = 0.1;
const STATION_HEADING_RAD: f32 = 0.3;
/// How far a camera sees a machine's light.
const CAMERA_RANGE_M: f32 = 1.0;

/// Start poses of robots 1..=3, on the free strip below the first machine row.
pub fn start_pose(robot: u8) -> Pose2 {
    let x = [1.0, 2.2, 4.5][usize::from(robot.clamp(1, 3)) - 1];
    Pose2::new(x, 0.8, core::f32::consts::FRAC_PI_2)
}

/// What the drivers of one robot publish after a cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorFrame {
    pub ir: IrScan,
    pub bumper: bool,
    pub gyro: GyroSample,
    pub odometry: Pose2,
    pub measured: WheelSpeeds,
    pub has_puck: bool,
    pub light: Option<(MachineId, LightSignal)>,
}

/// One motor command as the drive driver received it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Command {
    pub seq: u32,
    pub wheels: WheelSpeeds,
    /// Let go of the puck in front of the robot.
    pub release: bool,
    /// Take the puck lying in front of the robot (junk at a machine).
    pub grab: bool,
}

impl Command {
    pub fn drive(seq: u32, wheels: WheelSpeeds) -> Self {
        Self {
            seq,
            wheels,
            release: false,
            grab: false,
        }
    }
}

/// One simulated robot.
#[derive(Debug, Clone)]
pub struct SimRobot {
    pub number: u8,
    pub true_pose: Pose2,
    pub held: Option<PuckKind>,
    applied: WheelSpeeds,
    last_command_seq: Option<u32>,
    cycles_without_command: u32,
    bumper: bool,
    odometry: OdometryIntegrator,
    gyro_angle: f32,
    gyro_rate: f32,
    measured: WheelSpeeds,
    /// What the bumper touches this cycle, if anything.
    pub contact: Option<Contact>,
    /// Bumper contacts so far (each counted when it begins), and those with another robot.
    pub bumps: u32,
    pub robot_contacts: u32,
    /// Metres the robot really drove.
    pub travel_m: f32,
    /// The station where this robot last put or took a puck, until it leaves it: a robot
    /// standing still at a machine must not place the same puck every cycle.
    worked_station: Option<Station>,
    /// Junk this robot handed to a recycling unit: seconds until the unit hands the raw
    /// puck back (to the robot if it still stands there).
    recycling: Option<(f32, RecyclingId)>,
    /// The drive tried to take junk since the grab was asked for (once per asking).
    grab_tried: bool,
    /// The machine whose production the held puck is, while that machine still works on
    /// it: a robot that drives away then leaves the puck there.
    produced_at: Option<MachineId>,
}

/// What a robot's bumper touched.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    Wall,
    /// 0-based machine index.
    Machine(usize),
    /// The other robot's number.
    Robot(u8),
}

impl std::fmt::Display for Contact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Wall => write!(f, "wall"),
            Self::Machine(i) => write!(f, "M{}", i + 1),
            Self::Robot(n) => write!(f, "robot{n}"),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Station {
    Storage,
    Machine(MachineId),
    Gate(GateId),
    Recycling(RecyclingId),
}

impl SimRobot {
    pub fn wheels(&self) -> WheelSpeeds {
        self.applied
    }
    pub fn bumper(&self) -> bool {
        self.bumper
    }
    /// Cycles since the last fresh motor command.
    /// The pose the drive's odometry reports.
    pub fn odometry_pose(&self) -> Pose2 {
        self.odometry.pose()
    }
    pub fn cycles_without_command(&self) -> u32 {
        self.cycles_without_command
    }
}

/// The whole field.
pub struct FieldSim<R: Referee> {
    geometry: DriveGeometry,
    radius_m: f32,
    dt_s: f32,
    motor_deadline_cycles: u32,
    noise_cfg: super::config::NoiseConfig,
    noise: Noise,
    pub robots: Vec<SimRobot>,
    pub referee: R,
    cycle: u64,
    /// Outputs robots left under a working machine (by machine index), until one takes it.
    outputs: [Option<PuckKind>; 10],
}

impl<R: Referee> FieldSim<R> {
    pub fn new(config: &Config, robots: u8, referee: R) -> Self {
        let geometry = config.geometry();
        let robots = (1..=robots.clamp(1, 3))
            .map(|n| {
                let pose = start_pose(n);
                SimRobot {
                    number: n,
                    true_pose: pose,
                    held: None,
                    applied: WheelSpeeds::ZERO,
                    last_command_seq: None,
                    cycles_without_command: 0,
                    bumper: false,
                    odometry: OdometryIntegrator::new(geometry, config.robot.gyro_weight, pose),
                    gyro_angle: pose.phi_rad,
                    gyro_rate: 0.0,
                    measured: WheelSpeeds::ZERO,
                    contact: None,
                    bumps: 0,
                    robot_contacts: 0,
                    travel_m: 0.0,
                    worked_station: None,
                    recycling: None,
                    grab_tried: false,
                    produced_at: None,
                }
            })
            .collect();
        Self {
            geometry,
            radius_m: config.robot.radius_m,
            dt_s: config.cycle_s(),
            motor_deadline_cycles: config.timing.motor_deadline_cycles,
            noise_cfg: config.noise.clone(),
            noise: Noise::new(config.noise.seed),
            robots,
            referee,
            cycle: 0,
            outputs: [None; 10],
        }
    }

    pub fn cycle(&self) -> u64 {
        self.cycle
    }

    /// Advances one cycle. `commands[i]` is robot i+1's newest motor command (`None`: never
    /// received). A command counts as fresh when its sequence number changed; after
    /// `motor_deadline_cycles` cycles without one the wheels stop.
    pub fn step(&mut self, commands: &[Option<Command>]) {
        self.cycle += 1;
        self.referee.tick(self.dt_s);
        for i in 0..self.robots.len() {
            let command = commands.get(i).copied().flatten();
            self.apply_command(i, command);
            if command.is_some_and(|c| c.release) {
                let r = &mut self.robots[i];
                match (r.held.take(), r.produced_at.take()) {
                    // Let go under a machine that still works on it: it stays there.
                    (Some(puck), Some(m)) if self.referee.light(m) == LightSignal::Yellow => {
                        self.outputs[m.index()] = Some(puck);
                    }
                    (Some(puck), _) => self.referee.discard(r.number, puck),
                    (None, _) => {}
                }
            }
            self.move_robot(i);
            self.sense_motion(i);
            self.recycle_tick(i);
            self.work_stations(i, command.is_some_and(|c| c.grab));
        }
    }

    fn apply_command(&mut self, i: usize, command: Option<Command>) {
        let deadline = self.motor_deadline_cycles;
        let r = &mut self.robots[i];
        match command {
            Some(c) if Some(c.seq) != r.last_command_seq => {
                r.last_command_seq = Some(c.seq);
                r.cycles_without_command = 0;
                r.applied = c.wheels;
            }
            _ => {
                r.cycles_without_command = r.cycles_without_command.saturating_add(1);
                if r.cycles_without_command >= deadline {
                    r.applied = WheelSpeeds::ZERO;
                }
            }
        }
    }

    fn move_robot(&mut self, i: usize) {
        let twist = self.geometry.forward(self.robots[i].applied);
        let old = self.robots[i].true_pose;
        let new = old.advanced(twist, twist.omega_rad_s * self.dt_s, self.dt_s);
        // A robot touching something may still back away from it: only a move that does
        // not increase its least gap is blocked (else a robot pressed against a machine
        // could never leave, its first slow cycle still within reach of the edge).
        let contact = self
            .collides(i, new.x_m, new.y_m)
            .filter(|_| self.gap(i, new.x_m, new.y_m) <= self.gap(i, old.x_m, old.y_m));
        let blocked = contact.is_some();
        let r = &mut self.robots[i];
        // Contact stops the robot where it was; the bumper reports contact in this cycle.
        r.bumper = blocked;
        if blocked && r.contact.is_none() {
            r.bumps += 1;
            if matches!(contact, Some(Contact::Robot(_))) {
                r.robot_contacts += 1;
            }
        }
        r.contact = contact;
        if blocked {
            r.true_pose = Pose2::new(old.x_m, old.y_m, old.phi_rad);
        } else {
            r.travel_m += old.distance_to(&new);
            r.true_pose = new;
        }
    }

    fn sense_motion(&mut self, i: usize) {
        let dt = self.dt_s;
        let (rel, gyro_sigma) = (self.noise_cfg.wheel_rel, self.noise_cfg.gyro_rad);
        let moved = !self.robots[i].bumper;
        let applied = self.robots[i].applied;
        let measured = if moved {
            WheelSpeeds {
                rpm: applied.rpm.map(|r| r * (1.0 + self.noise.gaussian(rel))),
            }
        } else {
            WheelSpeeds::ZERO
        };
        let gyro_noise = self.noise.gaussian(gyro_sigma);
        let r = &mut self.robots[i];
        let previous = r.gyro_angle;
        r.gyro_angle = wrap_angle(r.true_pose.phi_rad + gyro_noise);
        r.gyro_rate = wrap_angle(r.gyro_angle - previous) / dt;
        r.measured = measured;
        r.odometry.update(measured, Some(r.gyro_angle), dt);
    }

    /// The recycling unit's time passes; then the raw puck goes to the robot still waiting
    /// there (one that left loses it: it stays in the unit).
    fn recycle_tick(&mut self, i: usize) {
        let dt = self.dt_s;
        let r = &mut self.robots[i];
        let Some((left, unit)) = r.recycling.as_mut() else {
            return;
        };
        *left -= dt;
        if *left > 0.0 {
            return;
        }
        let unit = *unit;
        r.recycling = None;
        if r.worked_station == Some(Station::Recycling(unit)) && r.held.is_none() {
            r.held = Some(PuckKind::S0);
        }
    }

    fn work_stations(&mut self, i: usize, grab: bool) {
        let pose = self.robots[i].true_pose;
        let at = |target: Pose2| {
            pose.distance_to(&target) <= STATION_REACH_M
                && wrap_angle(pose.phi_rad - target.phi_rad).abs() <= STATION_HEADING_RAD
        };
        let station = if at(input_storage_pose_for(self.robots[i].number)) {
            Some(Station::Storage)
        } else if let Some(m) = MachineId::all().find(|&m| at(machine_approach_pose(m))) {
            Some(Station::Machine(m))
        } else {
            (1..=3)
                .filter_map(GateId::new)
                .find(|&g| at(gate_pose(g)))
                .map(Station::Gate)
                .or_else(|| {
                    (1..=2)
                        .filter_map(RecyclingId::new)
                        .find(|&u| at(recycling_pose(u)))
                        .map(Station::Recycling)
                })
        };
        let r = &mut self.robots[i];
        if station.is_none() || station != r.worked_station {
            r.worked_station = None;
        }
        r.grab_tried &= grab;
        // The product under a machine that still works on it stays there when the robot
        // drives away (2012: the machine processes the puck under its light); the robot
        // may come back for it once the light is green.
        if let Some(m) = r.produced_at {
            if self.referee.light(m) != LightSignal::Yellow || r.held.is_none() {
                r.produced_at = None;
            } else if !r.applied.is_zero() {
                self.outputs[m.index()] = r.held.take();
                r.produced_at = None;
            }
        }
        // A puck goes into a station only from a robot that stopped there: one driving
        // past a machine's approach pose on its way elsewhere keeps its puck.
        if !r.applied.is_zero() {
            return;
        }
        // Junk is taken only when asked (the robot drives onto it), once per asking: a
        // robot that merely stops in front of a machine takes nothing, and one that just
        // worked the machine may take the junk its production left.
        if let (Some(Station::Machine(m)), None, true, false) =
            (station, r.held, grab, r.grab_tried)
        {
            r.grab_tried = true;
            // What it took is not put back into the machine it stands at.
            r.worked_station = station;
            // A finished output lies on top: it is what the robot takes first.
            if self.referee.light(m) == LightSignal::Green {
                if let Some(out) = self.outputs[m.index()].take() {
                    r.held = Some(out);
                    return;
                }
            }
            let robot = r.number;
            if self.referee.take_junk(robot, m) {
                self.robots[i].held = Some(PuckKind::Junk);
            }
            return;
        }
        let (Some(station), None) = (station, r.worked_station) else {
            return;
        };
        let robot = r.number;
        match (station, r.held) {
            (Station::Storage, None) => {
                r.held = self.referee.take_from_storage(robot);
                r.worked_station = Some(station);
            }
            (Station::Recycling(u), Some(PuckKind::Junk)) => {
                if let Some(wait_s) = self.referee.recycle(robot, u) {
                    r.held = None;
                    r.recycling = Some((wait_s, u));
                }
                r.worked_station = Some(station);
            }
            // A product still lies under the machine's light: the spot is taken, so a
            // puck the robot brings cannot go under the light (2012: the machine reads
            // the one puck in its place). The robot keeps it. This is what a robot
            // stopping in front of a machine on its way elsewhere met (seed 49: an S1
            // loaded over a finished P turned the light yellow, and the P was lost).
            (Station::Machine(m), Some(_)) if self.outputs[m.index()].is_some() => {
                r.worked_station = Some(station);
            }
            (Station::Machine(m), Some(puck)) => {
                r.held = match self.referee.place_at_machine(robot, m, puck) {
                    Placement::Consumed => None,
                    Placement::Rejected => Some(puck),
                    Placement::Produced(out) => {
                        r.produced_at = Some(m);
                        Some(out)
                    }
                };
                r.worked_station = Some(station);
            }
            (Station::Gate(g), Some(puck)) => {
                if self.referee.deliver(robot, g, puck) {
                    r.held = None;
                }
                r.worked_station = Some(station);
            }
            _ => {}
        }
    }

    /// The least distance from a robot's edge at (x, y) to a wall, a machine or another
    /// robot (negative when overlapping).
    fn gap(&self, i: usize, x: f32, y: f32) -> f32 {
        let rad = self.radius_m;
        let walls = x.min(y).min(FIELD_SIZE_M - x).min(FIELD_SIZE_M - y);
        let half = MACHINE_SIZE_M / 2.0;
        let machines = MACHINE_POSITIONS
            .iter()
            .map(|&(mx, my)| {
                let dx = ((x - mx).abs() - half).max(0.0);
                let dy = ((y - my).abs() - half).max(0.0);
                (dx * dx + dy * dy).sqrt()
            })
            .fold(f32::INFINITY, f32::min);
        let robots = self
            .robots
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, o)| o.true_pose.distance_to(&Pose2::new(x, y, 0.0)) - rad)
            .fold(f32::INFINITY, f32::min);
        walls.min(machines).min(robots) - rad
    }

    /// What a robot of this radius at (x, y) would touch: a wall, a machine or another
    /// robot.
    fn collides(&self, i: usize, x: f32, y: f32) -> Option<Contact> {
        let rad = self.radius_m;
        if x < rad || y < rad || x > FIELD_SIZE_M - rad || y > FIELD_SIZE_M - rad {
            return Some(Contact::Wall);
        }
        let half = MACHINE_SIZE_M / 2.0;
        let machine = MACHINE_POSITIONS.iter().position(|&(mx, my)| {
            // Distance from the circle's centre to the square.
            let dx = ((x - mx).abs() - half).max(0.0);
            let dy = ((y - my).abs() - half).max(0.0);
            dx * dx + dy * dy < rad * rad
        });
        if let Some(m) = machine {
            return Some(Contact::Machine(m));
        }
        self.robots
            .iter()
            .enumerate()
            .find(|&(j, o)| j != i && o.true_pose.distance_to(&Pose2::new(x, y, 0.0)) < 2.0 * rad)
            .map(|(_, o)| Contact::Robot(o.number))
    }

    /// Distance along a ray from (x, y) in direction `angle` to the first obstacle.
    fn ray_distance(&self, i: usize, x: f32, y: f32, angle: f32) -> f32 {
        let (dx, dy) = (angle.cos(), angle.sin());
        let mut best = f32::INFINITY;
        // Walls.
        if dx > 1e-6 {
            best = best.min((FIELD_SIZE_M - x) / dx);
        } else if dx < -1e-6 {
            best = best.min(-x / dx);
        }
        if dy > 1e-6 {
            best = best.min((FIELD_SIZE_M - y) / dy);
        } else if dy < -1e-6 {
            best = best.min(-y / dy);
        }
        // Machines: slab intersection with each square.
        let half = MACHINE_SIZE_M / 2.0;
        for &(mx, my) in MACHINE_POSITIONS.iter() {
            if let Some(t) = ray_box(x, y, dx, dy, mx - half, my - half, mx + half, my + half) {
                best = best.min(t);
            }
        }
        // Other robots as circles.
        for (j, o) in self.robots.iter().enumerate() {
            if j == i {
                continue;
            }
            let (ox, oy) = (o.true_pose.x_m - x, o.true_pose.y_m - y);
            let along = ox * dx + oy * dy;
            let perp2 = ox * ox + oy * oy - along * along;
            let r2 = self.radius_m * self.radius_m;
            if along > 0.0 && perp2 <= r2 {
                best = best.min(along - (r2 - perp2).sqrt());
            }
        }
        best
    }

    /// The sensors of robot `i` after the last step.
    pub fn sense(&mut self, i: usize) -> SensorFrame {
        let pose = self.robots[i].true_pose;
        let mut ir = IrScan::EMPTY;
        for s in 0..IR_SENSOR_COUNT {
            let angle = pose.phi_rad + sensor_angle_rad(s);
            let (sx, sy) = (
                pose.x_m + self.radius_m * angle.cos(),
                pose.y_m + self.radius_m * angle.sin(),
            );
            let d = self.ray_distance(i, sx, sy, angle) + self.noise.gaussian(self.noise_cfg.ir_m);
            ir.distances_m[s] = if d > IR_MAX_RANGE_M {
                0.0
            } else {
                // Nearer than the table reaches reads as the table's end.
                d.max(IR_MIN_RANGE_M)
            };
        }
        let light = MachineId::all().find_map(|m| {
            let (mx, my) = m.position();
            let (lx, ly) = pose.to_local(mx, my);
            (lx > 0.0 && lx <= CAMERA_RANGE_M && ly.abs() <= MACHINE_SIZE_M / 2.0)
                .then(|| (m, self.referee.light(m)))
        });
        let r = &self.robots[i];
        SensorFrame {
            ir,
            bumper: r.bumper,
            gyro: GyroSample {
                angle_rad: r.gyro_angle,
                rate_rad_s: r.gyro_rate,
            },
            odometry: r.odometry.pose(),
            measured: r.measured,
            has_puck: r.held.is_some(),
            light,
        }
    }

    /// Fault injection for tests: presses robot `i`'s bumper for this cycle's sensors.
    pub fn force_bumper(&mut self, i: usize) {
        self.robots[i].bumper = true;
    }
}

/// Ray-box intersection (slab method): distance to the first hit ahead, if any.
#[allow(clippy::too_many_arguments)]
fn ray_box(x: f32, y: f32, dx: f32, dy: f32, x0: f32, y0: f32, x1: f32, y1: f32) -> Option<f32> {
    let (mut tmin, mut tmax) = (f32::NEG_INFINITY, f32::INFINITY);
    for (o, d, lo, hi) in [(x, dx, x0, x1), (y, dy, y0, y1)] {
        if d.abs() < 1e-9 {
            if o < lo || o > hi {
                return None;
            }
        } else {
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            tmin = tmin.max(a.min(b));
            tmax = tmax.min(a.max(b));
        }
    }
    (tmax >= tmin.max(0.0)).then_some(tmin.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::super::referee::ClipsReferee;
    use super::super::rule_engine::with_engine_stack;
    use super::*;
    use hal::Twist;
    use rules::setup::{GameSetup, MachineType};

    fn quiet_config() -> Config {
        let mut c = Config::default();
        c.noise.ir_m = 0.0;
        c.noise.gyro_rad = 0.0;
        c.noise.wheel_rel = 0.0;
        c
    }

    const SEED: u64 = 1;

    /// A field with the CLIPS referee; call on a thread from [`with_engine_stack`].
    fn sim() -> FieldSim<ClipsReferee> {
        let referee =
            ClipsReferee::new(&GameSetup::for_seed(SEED)).unwrap_or_else(|e| panic!("{e}"));
        FieldSim::new(&quiet_config(), 1, referee)
    }

    /// Runs a test body on a thread big enough for the engine.
    fn on_engine_stack(f: impl FnOnce() + Send + 'static) {
        with_engine_stack(f).unwrap_or_else(|e| panic!("{e}"));
    }

    fn forward(speed: f32) -> WheelSpeeds {
        DriveGeometry::ROBOTINO2.inverse(Twist::new(speed, 0.0, 0.0))
    }

    #[test]
    fn commands_move_the_robot_and_odometry_follows() {
        on_engine_stack(|| {
            let mut s = sim();
            for seq in 1..=15 {
                s.step(&[Some(Command::drive(seq, forward(0.3)))]);
            }
            let r = &s.robots[0];
            // Facing +y at 0.3 m/s for one second from (1.0, 0.8).
            assert!((r.true_pose.y_m - 1.1).abs() < 1e-3, "{:?}", r.true_pose);
            let f = s.sense(0);
            assert!((f.odometry.y_m - 1.1).abs() < 1e-3, "{:?}", f.odometry);
            assert!(!f.bumper);
        });
    }

    #[test]
    fn dead_man_stops_the_wheels_after_the_deadline() {
        on_engine_stack(|| {
            let mut s = sim();
            s.step(&[Some(Command::drive(1, forward(0.2)))]);
            // The same command (same sequence number) is not fresh.
            for missed in 1..=3u32 {
                s.step(&[Some(Command::drive(1, forward(0.2)))]);
                assert_eq!(
                    s.robots[0].wheels().is_zero(),
                    missed >= 3,
                    "missed {missed}"
                );
            }
            // A fresh command drives again.
            s.step(&[Some(Command::drive(2, forward(0.2)))]);
            assert!(!s.robots[0].wheels().is_zero());
        });
    }

    #[test]
    fn driving_into_a_machine_presses_the_bumper_and_stops() {
        on_engine_stack(|| {
            let mut s = sim();
            // Robot 1 starts at (1.0, 0.8) facing +y; M3's square spans x 0.26..0.86 and
            // y 2.5..3.1, so driving straight ahead clips its corner.
            let mut bumped_at = None;
            for seq in 1..=100 {
                s.step(&[Some(Command::drive(seq, forward(0.4)))]);
                if s.robots[0].bumper() {
                    bumped_at = Some(seq);
                    break;
                }
            }
            assert!(bumped_at.is_some(), "{:?}", s.robots[0].true_pose);
            let f = s.sense(0);
            assert!(f.bumper);
            // The robot stopped outside the machine and odometry saw no motion in that cycle.
            let p = s.robots[0].true_pose;
            assert!(p.y_m < 2.5 && p.y_m > 2.3, "{p:?}");
            assert!(f.measured.is_zero());
        });
    }

    #[test]
    fn ir_sees_a_wall_at_the_right_distance() {
        on_engine_stack(|| {
            let mut s = sim();
            // Put the robot 0.2 m + radius from the bottom wall, facing it.
            s.robots[0].true_pose = Pose2::new(3.0, 0.185 + 0.2, -core::f32::consts::FRAC_PI_2);
            let f = s.sense(0);
            assert!((f.ir.distances_m[0] - 0.2).abs() < 1e-4, "{:?}", f.ir);
            // Sensor 4 (160 deg) looks into the open field: nothing within range.
            assert_eq!(f.ir.distances_m[4], 0.0);
        });
    }

    #[test]
    fn pucks_flow_through_storage_machine_and_gate() {
        on_engine_stack(|| {
            let mut s = sim();
            s.robots[0].true_pose = input_storage_pose_for(1);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S0));
            // Standing still does not take a second puck.
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S0));
            let setup = GameSetup::for_seed(SEED);
            let t1 = MachineId::all()
                .find(|&m| setup.assignment[m.index()] == MachineType::T1)
                .unwrap_or_else(|| panic!());
            s.robots[0].true_pose = machine_approach_pose(t1);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S1));
            // Processing (5.5 s for T1): yellow while the robot already holds the output.
            let f = s.sense(0);
            assert_eq!(f.light, Some((t1, LightSignal::Yellow)));
            assert!(f.has_puck);
            for _ in 0..15 * 6 {
                s.step(&[None]);
            }
            assert_eq!(s.sense(0).light, Some((t1, LightSignal::Green)));
            assert_eq!(s.robots[0].held, Some(PuckKind::S1));
            // Released on the field: the referee counts it discarded.
            let release = Command {
                seq: 1,
                wheels: WheelSpeeds::ZERO,
                release: true,
                grab: false,
            };
            s.step(&[Some(release)]);
            assert_eq!(s.robots[0].held, None);
            let log = s.referee.take_log();
            assert!(log.last().is_some_and(|l| l.contains("discard")), "{log:?}");
            // The next S0 into the gate: it takes any puck.
            s.robots[0].true_pose = input_storage_pose_for(1);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S0));
            let g = GateId::new(1).unwrap_or_else(|| panic!());
            s.robots[0].true_pose = gate_pose(g);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, None);
        });
    }

    /// 2012 recycling: the junk a T2 production leaves is taken only when asked for, once,
    /// and a recycling unit hands a raw puck back after its 2 s (+3 for the T2's junk).
    #[test]
    fn junk_goes_from_a_machine_to_a_recycling_unit_and_back_as_s0() {
        on_engine_stack(|| {
            let mut s = sim();
            let setup = GameSetup::for_seed(SEED);
            let of = |t| {
                MachineId::all()
                    .find(|&m| setup.assignment[m.index()] == t)
                    .unwrap_or_else(|| panic!("{t:?}"))
            };
            let (t1, t2) = (of(MachineType::T1), of(MachineType::T2));
            let command = |seq, release, grab| Command {
                seq,
                wheels: WheelSpeeds::ZERO,
                release,
                grab,
            };
            for (station, held) in [
                (input_storage_pose_for(1), PuckKind::S0),
                (machine_approach_pose(t1), PuckKind::S1),
            ] {
                s.robots[0].true_pose = station;
                s.step(&[None]);
                assert_eq!(s.robots[0].held, Some(held));
            }
            s.robots[0].true_pose = machine_approach_pose(t2);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, None, "S1 loaded into the T2");
            s.robots[0].true_pose = input_storage_pose_for(1);
            s.step(&[None]);
            s.robots[0].true_pose = machine_approach_pose(t2);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S2));
            s.step(&[Some(command(1, true, false))]);
            assert_eq!(s.robots[0].held, None);
            // Standing there without asking takes nothing; asking takes the one junk.
            s.step(&[Some(command(2, false, false))]);
            assert_eq!(s.robots[0].held, None);
            s.step(&[Some(command(3, false, true))]);
            assert_eq!(s.robots[0].held, Some(PuckKind::Junk));
            // Asked on: nothing more (the T2's one junk is gone, and it asks once).
            s.step(&[Some(command(4, false, true))]);
            assert_eq!(s.robots[0].held, Some(PuckKind::Junk));
            let score_before = s.referee.score();
            let unit = RecyclingId::new(1).unwrap_or_else(|| panic!());
            s.robots[0].true_pose = recycling_pose(unit);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, None, "the unit took the junk");
            assert_eq!(s.referee.score(), score_before + 3);
            for _ in 0..15 * 2 + 1 {
                s.step(&[None]);
            }
            assert_eq!(s.robots[0].held, Some(PuckKind::S0));
            let log = s.referee.take_log();
            assert!(
                log.iter()
                    .any(|l| l.contains("robot=1 recycle R1 JUNK -> ok")),
                "{log:?}"
            );
            // Junk the referee never saw taken from a machine is refused: kept.
            s.robots[0].held = Some(PuckKind::Junk);
            s.robots[0].true_pose = machine_approach_pose(t1);
            s.step(&[None]);
            s.robots[0].true_pose = recycling_pose(unit);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::Junk));
        });
    }

    fn command(seq: u32, wheels: WheelSpeeds, release: bool, grab: bool) -> Option<Command> {
        Some(Command {
            seq,
            wheels,
            release,
            grab,
        })
    }

    /// A field whose robot 1 just put the last input into the T3: it holds the P under the
    /// working machine (light yellow). Returns the field and the T3.
    fn p_under_a_working_t3() -> (FieldSim<ClipsReferee>, MachineId) {
        let mut s = sim();
        let setup = GameSetup::for_seed(SEED);
        let of = |t| {
            MachineId::all()
                .find(|&m| setup.assignment[m.index()] == t)
                .unwrap_or_else(|| panic!("{t:?}"))
        };
        let (t1, t2, t3) = (
            of(MachineType::T1),
            of(MachineType::T2),
            of(MachineType::T3),
        );
        // A fresh S0 from the storage before each chain: S0 into the T3; S1 into the T3;
        // S1 and S0 into the T2 make the S2, the T3's last input.
        let chains: [&[MachineId]; 4] = [&[t3], &[t1, t3], &[t1, t2], &[t2, t3]];
        for chain in chains {
            s.robots[0].true_pose = input_storage_pose_for(1);
            s.step(&[None]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S0));
            for &m in chain {
                for _ in 0..15 * 21 {
                    s.step(&[None]); // the last machine finishes its work
                }
                s.robots[0].true_pose = machine_approach_pose(m);
                s.step(&[None]);
            }
        }
        assert_eq!(s.robots[0].held, Some(PuckKind::P), "held under the light");
        assert_eq!(s.referee.light(t3), LightSignal::Yellow);
        (s, t3)
    }

    /// A T3's product stays under the machine when the robot drives away while the machine
    /// works on it; a grab there takes junk until the light is green, then the product.
    #[test]
    fn a_product_left_at_a_working_machine_is_taken_back_once_green() {
        on_engine_stack(|| {
            let (mut s, t3) = p_under_a_working_t3();
            let back = WheelSpeeds {
                rpm: [-300.0, 0.0, 300.0],
            };
            s.step(&[command(1, back, false, false)]);
            assert_eq!(s.robots[0].held, None);
            // Still working: a grab takes a junk puck, not the product.
            s.robots[0].true_pose = machine_approach_pose(t3);
            s.step(&[command(2, WheelSpeeds::ZERO, false, true)]);
            assert_eq!(s.robots[0].held, Some(PuckKind::Junk));
            s.robots[0].held = None;
            for _ in 0..15 * 51 {
                s.step(&[command(3, WheelSpeeds::ZERO, false, false)]);
            }
            assert_eq!(s.referee.light(t3), LightSignal::Green);
            s.step(&[command(4, WheelSpeeds::ZERO, false, true)]);
            assert_eq!(s.robots[0].held, Some(PuckKind::P));
        });
    }

    /// Letting go of the product under the working machine (no room to back away) leaves
    /// it there too: nothing is discarded, a later grab takes it.
    #[test]
    fn a_product_let_go_at_a_working_machine_stays_there() {
        on_engine_stack(|| {
            let (mut s, _) = p_under_a_working_t3();
            let _ = s.referee.take_log();
            s.step(&[command(1, WheelSpeeds::ZERO, true, false)]);
            assert_eq!(s.robots[0].held, None);
            let log = s.referee.take_log();
            assert!(!log.iter().any(|l| l.contains("discard")), "{log:?}");
            for _ in 0..15 * 51 {
                s.step(&[command(2, WheelSpeeds::ZERO, false, false)]);
            }
            s.step(&[command(3, WheelSpeeds::ZERO, false, true)]);
            assert_eq!(s.robots[0].held, Some(PuckKind::P));
        });
    }

    /// A robot that stops at a machine whose product still lies under the light keeps
    /// the puck it carries: the light and the product stay as they were.
    #[test]
    fn a_machine_with_its_product_under_it_takes_no_puck() {
        on_engine_stack(|| {
            let (mut s, t3) = p_under_a_working_t3();
            s.step(&[command(1, WheelSpeeds::ZERO, true, false)]);
            for _ in 0..15 * 51 {
                s.step(&[command(2, WheelSpeeds::ZERO, false, false)]);
            }
            assert_eq!(s.referee.light(t3), LightSignal::Green);
            // Another robot's stop there, modelled as robot 1 arriving with an S1.
            s.robots[0].true_pose = machine_approach_pose(t3);
            s.robots[0].worked_station = None;
            s.robots[0].held = Some(PuckKind::S1);
            s.step(&[command(3, WheelSpeeds::ZERO, false, false)]);
            assert_eq!(s.robots[0].held, Some(PuckKind::S1), "kept");
            assert_eq!(s.referee.light(t3), LightSignal::Green);
            s.robots[0].held = None;
            s.robots[0].worked_station = None;
            s.step(&[command(4, WheelSpeeds::ZERO, false, true)]);
            assert_eq!(
                s.robots[0].held,
                Some(PuckKind::P),
                "the product is still there"
            );
        });
    }

    #[test]
    fn noise_is_seeded() {
        let mut a = Noise::new(5);
        let mut b = Noise::new(5);
        let xs: Vec<f32> = (0..100).map(|_| a.gaussian(1.0)).collect();
        let ys: Vec<f32> = (0..100).map(|_| b.gaussian(1.0)).collect();
        assert_eq!(xs, ys);
        let mean = xs.iter().sum::<f32>() / 100.0;
        assert!(mean.abs() < 0.3, "{mean}");
    }
}
