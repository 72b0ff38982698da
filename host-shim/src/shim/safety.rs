//! The shim's first duty, as a pure state machine: per cycle it takes the sequence numbers of
//! the latest samples, the bumper state and the skill's desired twist, and decides the motor
//! command. No clocks, no I/O: time is the cycle counter, freshness is "the sequence number
//! changed" (any change, so a restarted driver that counts from zero again is fresh).

use hal::limits::MotionLimits;
use hal::skill::FailReason;
use hal::{DriveGeometry, Twist, WheelSpeeds};

/// The driver streams whose silence stops the robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stream {
    Ir = 0,
    Bumper = 1,
    Gyro = 2,
    Odometry = 3,
    Puck = 4,
}

impl Stream {
    pub const COUNT: usize = 5;
    pub const ALL: [Stream; Stream::COUNT] = [
        Stream::Ir,
        Stream::Bumper,
        Stream::Gyro,
        Stream::Odometry,
        Stream::Puck,
    ];
}

/// What the monitor sees in one cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleInput {
    /// Sequence number of the newest valid sample per stream (`None`: never received).
    pub latest_seq: [Option<u32>; Stream::COUNT],
    /// The newest bumper sample says pressed.
    pub bumper_pressed: bool,
    /// What the skill wants; ignored when no skill runs.
    pub desired: Twist,
    /// A skill is running and has not yet reported FINAL or FAILED.
    pub skill_running: bool,
}

/// Why the motors are held at zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hold {
    Bumper,
    Stale(Stream),
}

/// The monitor's decision for one cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decision {
    /// The clamped twist actually commanded.
    pub twist: Twist,
    pub wheels: WheelSpeeds,
    /// Set when the running skill must be FAILED this cycle.
    pub fail_skill: Option<FailReason>,
    /// Set when the motors are forced to zero.
    pub hold: Option<Hold>,
}

#[derive(Debug, Clone, Copy)]
struct Freshness {
    last_seq: Option<u32>,
    cycles_without_fresh: u32,
}

/// The safety state machine.
#[derive(Debug, Clone)]
pub struct SafetyMonitor {
    geometry: DriveGeometry,
    limits: MotionLimits,
    cycle_s: f32,
    sensor_deadline_cycles: u32,
    skill_timeout_cycles: u32,
    streams: [Freshness; Stream::COUNT],
    previous: Twist,
    skill_cycles: u32,
    cycle: u64,
}

impl SafetyMonitor {
    pub fn new(
        geometry: DriveGeometry,
        limits: MotionLimits,
        cycle_s: f32,
        sensor_deadline_cycles: u32,
        skill_timeout_cycles: u32,
    ) -> Self {
        Self {
            geometry,
            limits,
            cycle_s,
            sensor_deadline_cycles,
            skill_timeout_cycles,
            // Nothing received yet counts as already past the deadline: no motion before
            // every driver has spoken.
            streams: [Freshness {
                last_seq: None,
                cycles_without_fresh: sensor_deadline_cycles,
            }; Stream::COUNT],
            previous: Twist::ZERO,
            skill_cycles: 0,
            cycle: 0,
        }
    }

    /// Cycles decided so far.
    pub fn cycle(&self) -> u64 {
        self.cycle
    }

    /// Call when a new skill starts: its timeout counts from here.
    pub fn skill_started(&mut self) {
        self.skill_cycles = 0;
    }

    /// Cycles since `stream` last delivered a fresh sample.
    pub fn staleness(&self, stream: Stream) -> u32 {
        self.streams[stream as usize].cycles_without_fresh
    }

    fn update_freshness(&mut self, latest: &[Option<u32>; Stream::COUNT]) -> Option<Stream> {
        let deadline = self.sensor_deadline_cycles;
        let mut first_stale = None;
        for (stream, (state, &seq)) in Stream::ALL
            .iter()
            .zip(self.streams.iter_mut().zip(latest.iter()))
        {
            let fresh = seq.is_some() && seq != state.last_seq;
            if fresh {
                state.last_seq = seq;
                state.cycles_without_fresh = 0;
            } else {
                state.cycles_without_fresh = state.cycles_without_fresh.saturating_add(1);
            }
            if state.cycles_without_fresh >= deadline && first_stale.is_none() {
                first_stale = Some(*stream);
            }
        }
        first_stale
    }

    /// Decides one cycle.
    pub fn step(&mut self, input: &CycleInput) -> Decision {
        self.cycle += 1;
        let stale = self.update_freshness(&input.latest_seq);
        let hold = if input.bumper_pressed {
            Some(Hold::Bumper)
        } else {
            stale.map(Hold::Stale)
        };

        let mut fail_skill = None;
        if input.skill_running {
            self.skill_cycles = self.skill_cycles.saturating_add(1);
            fail_skill = match hold {
                Some(Hold::Bumper) => Some(FailReason::Bumper),
                Some(Hold::Stale(_)) => Some(FailReason::SensorTimeout),
                None if self.skill_cycles > self.skill_timeout_cycles => {
                    Some(FailReason::SkillTimeout)
                }
                None => None,
            };
        }

        let desired = if hold.is_some() || fail_skill.is_some() || !input.skill_running {
            Twist::ZERO
        } else {
            input.desired
        };
        let (twist, wheels) =
            self.limits
                .command(&self.geometry, self.previous, desired, self.cycle_s);
        self.previous = twist;
        Decision {
            twist,
            wheels,
            fail_skill,
            hold,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEADLINE: u32 = 3;
    const SKILL_TIMEOUT: u32 = 100;

    fn monitor() -> SafetyMonitor {
        SafetyMonitor::new(
            DriveGeometry::ROBOTINO2,
            MotionLimits::ROBOTINO2,
            1.0 / 15.0,
            DEADLINE,
            SKILL_TIMEOUT,
        )
    }

    /// Drives a scripted sequence of cycles: each stream's sequence number advances by one
    /// per cycle unless frozen.
    struct Script {
        seq: [u32; Stream::COUNT],
    }

    impl Script {
        fn new() -> Self {
            Self {
                seq: [0; Stream::COUNT],
            }
        }

        fn input(&mut self, frozen: &[Stream], bumper: bool, desired: Twist) -> CycleInput {
            for s in Stream::ALL {
                if !frozen.contains(&s) {
                    self.seq[s as usize] += 1;
                }
            }
            CycleInput {
                latest_seq: self.seq.map(Some),
                bumper_pressed: bumper,
                desired,
                skill_running: true,
            }
        }
    }

    const FORWARD: Twist = Twist::new(0.3, 0.0, 0.0);

    #[test]
    fn nothing_moves_before_every_driver_has_spoken() {
        let mut m = monitor();
        let d = m.step(&CycleInput {
            latest_seq: [None; Stream::COUNT],
            bumper_pressed: false,
            desired: FORWARD,
            skill_running: true,
        });
        assert!(d.wheels.is_zero());
        assert_eq!(d.hold, Some(Hold::Stale(Stream::Ir)));
        assert_eq!(d.fail_skill, Some(FailReason::SensorTimeout));
    }

    #[test]
    fn fresh_samples_let_the_skill_drive_within_limits() {
        let mut m = monitor();
        let mut s = Script::new();
        let mut last = Twist::ZERO;
        for _ in 0..30 {
            let d = m.step(&s.input(&[], false, Twist::new(3.0, 0.0, 0.0)));
            assert_eq!(d.hold, None);
            assert_eq!(d.fail_skill, None);
            assert!(d.twist.vx_m_s >= last.vx_m_s - 1e-5);
            assert!(d.twist.linear_speed_m_s() <= 0.5 + 1e-4);
            last = d.twist;
        }
        assert!((last.vx_m_s - 0.5).abs() < 1e-3, "{last:?}");
    }

    #[test]
    fn bumper_zeroes_in_the_same_cycle_and_fails_the_skill() {
        let mut m = monitor();
        let mut s = Script::new();
        for _ in 0..20 {
            assert!(!m.step(&s.input(&[], false, FORWARD)).wheels.is_zero());
        }
        let d = m.step(&s.input(&[], true, FORWARD));
        assert!(d.wheels.is_zero());
        assert_eq!(d.twist, Twist::ZERO);
        assert_eq!(d.fail_skill, Some(FailReason::Bumper));
        assert_eq!(d.hold, Some(Hold::Bumper));
        // Released: motion may resume (no acceleration jump from a stale previous command).
        let d = m.step(&s.input(&[], false, FORWARD));
        assert_eq!(d.hold, None);
        assert!(d.twist.vx_m_s > 0.0 && d.twist.vx_m_s <= 1.0 / 15.0 + 1e-5);
    }

    #[test]
    fn silent_driver_stops_after_exactly_the_deadline_and_resumes() {
        let mut m = monitor();
        let mut s = Script::new();
        for _ in 0..5 {
            m.step(&s.input(&[], false, FORWARD));
        }
        // Gyro silent: cycles 1 and 2 still move, cycle 3 stops.
        for missed in 1..=DEADLINE {
            let d = m.step(&s.input(&[Stream::Gyro], false, FORWARD));
            assert_eq!(m.staleness(Stream::Gyro), missed);
            if missed < DEADLINE {
                assert_eq!(d.hold, None, "cycle {missed}");
                assert!(!d.wheels.is_zero());
            } else {
                assert_eq!(d.hold, Some(Hold::Stale(Stream::Gyro)));
                assert_eq!(d.fail_skill, Some(FailReason::SensorTimeout));
                assert!(d.wheels.is_zero());
            }
        }
        // Still silent: still zero.
        assert!(m
            .step(&s.input(&[Stream::Gyro], false, FORWARD))
            .wheels
            .is_zero());
        // The driver returns: motion resumes at once.
        let d = m.step(&s.input(&[], false, FORWARD));
        assert_eq!(d.hold, None);
        assert!(!d.wheels.is_zero());
    }

    #[test]
    fn restarted_driver_counting_from_zero_is_fresh() {
        let mut m = monitor();
        let mut s = Script::new();
        for _ in 0..5 {
            m.step(&s.input(&[], false, FORWARD));
        }
        s.seq[Stream::Odometry as usize] = 0;
        let d = m.step(&s.input(&[], false, FORWARD));
        assert_eq!(m.staleness(Stream::Odometry), 0);
        assert_eq!(d.hold, None);
    }

    #[test]
    fn skill_timeout_counts_cycles_from_start() {
        let mut m = monitor();
        let mut s = Script::new();
        m.skill_started();
        for c in 1..=SKILL_TIMEOUT {
            let d = m.step(&s.input(&[], false, FORWARD));
            assert_eq!(d.fail_skill, None, "cycle {c}");
        }
        let d = m.step(&s.input(&[], false, FORWARD));
        assert_eq!(d.fail_skill, Some(FailReason::SkillTimeout));
        assert!(d.wheels.is_zero());
        m.skill_started();
        assert_eq!(m.step(&s.input(&[], false, FORWARD)).fail_skill, None);
    }

    #[test]
    fn idle_robot_never_moves() {
        let mut m = monitor();
        let mut s = Script::new();
        let mut input = s.input(&[], false, FORWARD);
        input.skill_running = false;
        let d = m.step(&input);
        assert!(d.wheels.is_zero());
        assert_eq!(d.fail_skill, None);
    }

    #[test]
    fn every_command_is_clamped_including_garbage() {
        let mut m = monitor();
        let mut s = Script::new();
        for desired in [
            Twist::new(f32::NAN, 0.0, 0.0),
            Twist::new(100.0, -100.0, 100.0),
            Twist::new(0.0, 0.0, f32::NEG_INFINITY),
        ] {
            for _ in 0..40 {
                let d = m.step(&s.input(&[], false, desired));
                assert!(d.twist.is_finite());
                assert!(d.twist.linear_speed_m_s() <= 0.5 + 1e-4);
                assert!(d.twist.omega_rad_s.abs() <= 0.78 + 1e-4);
                assert!(d.wheels.max_abs_rpm() <= 3000.0 + 1e-2);
            }
        }
    }
}
