//! Fixed-size `#[repr(C)]` payloads, one per iceoryx2 service, and a pure validating decoder
//! for each. Every payload starts with `seq`, the publisher's sequence number, which readers
//! use to tell a fresh sample from a repeated one. Flags are `u8` (0/1) rather than `bool`
//! so that a corrupt byte is a decode error instead of undefined behaviour.
//!
//! Decoders take the payload by reference and return the hal's types or a [`DecodeError`];
//! they never panic, so they can be fuzzed directly.

use core::fmt;
use hal::device::GyroSample;
use hal::field::{GateId, MachineId};
use hal::ir::{IrScan, IR_MAX_RANGE_M, IR_NO_READING, IR_SENSOR_COUNT};
use hal::skill::{FailReason, Perception, SkillOutcome, SkillRequest};
use hal::{LightSignal, Pose2, WheelSpeeds};
use iceoryx2::prelude::ZeroCopySend;

/// Largest speed any motor command may carry; well above the Robotino's 3000 rpm, so only
/// garbage is rejected here (the safety layer clamps to the configured limit).
pub const MAX_WIRE_RPM: f32 = 10_000.0;
/// Largest angular rate a gyro sample may report (the XG1010 saturates near 100 deg/s).
pub const MAX_GYRO_RATE_RAD_S: f32 = 10.0;
/// Poses outside the field by more than this are rejected.
pub const FIELD_SLACK_M: f32 = 1.0;
/// Largest robot number (up to three robots per team).
pub const MAX_ROBOTS: u8 = 3;

/// Why a payload was rejected: the field and what was wrong with it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DecodeError {
    NotFinite(&'static str),
    OutOfRange(&'static str),
    UnknownCode { field: &'static str, code: u8 },
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(field) => write!(f, "field `{field}` is NaN or infinite"),
            Self::OutOfRange(field) => write!(f, "field `{field}` is out of range"),
            Self::UnknownCode { field, code } => {
                write!(f, "field `{field}` has unknown code {code}")
            }
        }
    }
}

impl std::error::Error for DecodeError {}

fn finite(value: f32, field: &'static str) -> Result<f32, DecodeError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(DecodeError::NotFinite(field))
    }
}

fn within(value: f32, lo: f32, hi: f32, field: &'static str) -> Result<f32, DecodeError> {
    let v = finite(value, field)?;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(DecodeError::OutOfRange(field))
    }
}

fn flag(value: u8, field: &'static str) -> Result<bool, DecodeError> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        code => Err(DecodeError::UnknownCode { field, code }),
    }
}

fn robot(value: u8) -> Result<u8, DecodeError> {
    if (1..=MAX_ROBOTS).contains(&value) {
        Ok(value)
    } else {
        Err(DecodeError::OutOfRange("robot"))
    }
}

fn machine(code: u8) -> Result<MachineId, DecodeError> {
    MachineId::new(code).ok_or(DecodeError::UnknownCode {
        field: "machine",
        code,
    })
}

fn field_coordinate(value: f32, field: &'static str) -> Result<f32, DecodeError> {
    within(
        value,
        -FIELD_SLACK_M,
        hal::field::FIELD_SIZE_M + FIELD_SLACK_M,
        field,
    )
}

/// The IR ring: distances in metres, 0 = no reading.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::IrScan")]
#[repr(C)]
pub struct IrScanPayload {
    pub seq: u32,
    pub distances_m: [f32; IR_SENSOR_COUNT],
}

impl IrScanPayload {
    pub fn encode(seq: u32, scan: &IrScan) -> Self {
        Self {
            seq,
            distances_m: scan.distances_m,
        }
    }

    pub fn decode(&self) -> Result<IrScan, DecodeError> {
        let mut scan = IrScan::EMPTY;
        for (out, &d) in scan.distances_m.iter_mut().zip(self.distances_m.iter()) {
            let d = within(d, 0.0, IR_MAX_RANGE_M, "distances_m")?;
            // Below the sensor's range is physically a reading at the minimum; keep it.
            *out = if d == 0.0 { IR_NO_READING } else { d };
        }
        Ok(scan)
    }
}

/// The bumper: 1 = pressed.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::Bumper")]
#[repr(C)]
pub struct BumperPayload {
    pub seq: u32,
    pub pressed: u8,
    pub reserved: [u8; 3],
}

impl BumperPayload {
    pub fn encode(seq: u32, pressed: bool) -> Self {
        Self {
            seq,
            pressed: pressed as u8,
            reserved: [0; 3],
        }
    }

    pub fn decode(&self) -> Result<bool, DecodeError> {
        flag(self.pressed, "pressed")
    }
}

/// The gyro: absolute angle and rate, counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::Gyro")]
#[repr(C)]
pub struct GyroPayload {
    pub seq: u32,
    pub angle_rad: f32,
    pub rate_rad_s: f32,
}

impl GyroPayload {
    pub fn encode(seq: u32, sample: GyroSample) -> Self {
        Self {
            seq,
            angle_rad: sample.angle_rad,
            rate_rad_s: sample.rate_rad_s,
        }
    }

    pub fn decode(&self) -> Result<GyroSample, DecodeError> {
        let pi = core::f32::consts::PI;
        Ok(GyroSample {
            angle_rad: within(self.angle_rad, -pi - 1e-3, pi + 1e-3, "angle_rad")?,
            rate_rad_s: within(
                self.rate_rad_s,
                -MAX_GYRO_RATE_RAD_S,
                MAX_GYRO_RATE_RAD_S,
                "rate_rad_s",
            )?,
        })
    }
}

/// Odometry: the driver's pose estimate and the measured motor speeds.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::Odometry")]
#[repr(C)]
pub struct OdometryPayload {
    pub seq: u32,
    pub x_m: f32,
    pub y_m: f32,
    pub phi_rad: f32,
    pub measured_rpm: [f32; 3],
}

/// A decoded odometry sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OdometryReading {
    pub pose: Pose2,
    pub measured: WheelSpeeds,
}

impl OdometryPayload {
    pub fn encode(seq: u32, reading: &OdometryReading) -> Self {
        Self {
            seq,
            x_m: reading.pose.x_m,
            y_m: reading.pose.y_m,
            phi_rad: reading.pose.phi_rad,
            measured_rpm: reading.measured.rpm,
        }
    }

    pub fn decode(&self) -> Result<OdometryReading, DecodeError> {
        let pi = core::f32::consts::PI;
        let pose = Pose2::new(
            field_coordinate(self.x_m, "x_m")?,
            field_coordinate(self.y_m, "y_m")?,
            within(self.phi_rad, -pi - 1e-3, pi + 1e-3, "phi_rad")?,
        );
        let mut measured = WheelSpeeds::ZERO;
        for (out, &r) in measured.rpm.iter_mut().zip(self.measured_rpm.iter()) {
            *out = within(r, -MAX_WIRE_RPM, MAX_WIRE_RPM, "measured_rpm")?;
        }
        Ok(OdometryReading { pose, measured })
    }
}

/// The motor command. `bumper_seq` names the newest bumper sample the sender had read when
/// it computed the command, so the driver can measure bumper-to-stop latency in cycles.
/// `release_puck` = 1 asks the drive to let go of the puck in front of the robot (the
/// behaviour layer's discard).
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::MotorCommand")]
#[repr(C)]
pub struct MotorCommandPayload {
    pub seq: u32,
    pub bumper_seq: u32,
    pub rpm: [f32; 3],
    pub release_puck: u8,
    pub reserved: [u8; 3],
}

impl MotorCommandPayload {
    pub fn encode(seq: u32, bumper_seq: u32, wheels: WheelSpeeds) -> Self {
        Self {
            seq,
            bumper_seq,
            rpm: wheels.rpm,
            release_puck: 0,
            reserved: [0; 3],
        }
    }

    /// The same command, asking (or not) to release the puck.
    pub fn with_release(mut self, release: bool) -> Self {
        self.release_puck = u8::from(release);
        self
    }

    /// The wheel speeds; every field is validated (an unknown release flag is an error too).
    pub fn decode(&self) -> Result<WheelSpeeds, DecodeError> {
        let mut wheels = WheelSpeeds::ZERO;
        for (out, &r) in wheels.rpm.iter_mut().zip(self.rpm.iter()) {
            *out = within(r, -MAX_WIRE_RPM, MAX_WIRE_RPM, "rpm")?;
        }
        flag(self.release_puck, "release_puck")?;
        Ok(wheels)
    }

    /// Whether the command asks to release the puck.
    pub fn release(&self) -> Result<bool, DecodeError> {
        flag(self.release_puck, "release_puck")
    }
}

/// The light of the machine in front of the robot; `machine` 0 = none in view.
/// `active_gate` is the delivery gate whose light is on (1..=3; 0 = not known yet): the
/// gate lights are visible from the whole field.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::LightSignal")]
#[repr(C)]
pub struct LightPayload {
    pub seq: u32,
    pub machine: u8,
    pub light: u8,
    pub active_gate: u8,
    pub reserved: u8,
}

impl LightPayload {
    pub fn encode(seq: u32, seen: Option<(MachineId, LightSignal)>) -> Self {
        let (machine, light) = seen.map_or((0, 0), |(m, l)| (m.number(), l.code()));
        Self {
            seq,
            machine,
            light,
            active_gate: 0,
            reserved: 0,
        }
    }

    /// The same sample with the active delivery gate.
    pub fn with_gate(mut self, gate: Option<GateId>) -> Self {
        self.active_gate = gate.map_or(0, GateId::number);
        self
    }

    /// The machine light in view; every field is validated (the gate code too).
    pub fn decode(&self) -> Result<Option<(MachineId, LightSignal)>, DecodeError> {
        self.active_gate()?;
        if self.machine == 0 {
            return Ok(None);
        }
        let light = LightSignal::from_code(self.light).ok_or(DecodeError::UnknownCode {
            field: "light",
            code: self.light,
        })?;
        Ok(Some((machine(self.machine)?, light)))
    }

    /// The active delivery gate, when the sender knows it.
    pub fn active_gate(&self) -> Result<Option<GateId>, DecodeError> {
        match self.active_gate {
            0 => Ok(None),
            code => GateId::new(code).map(Some).ok_or(DecodeError::UnknownCode {
                field: "active_gate",
                code,
            }),
        }
    }
}

/// The puck sensor: 1 = a puck is in the gripper area.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::Puck")]
#[repr(C)]
pub struct PuckPayload {
    pub seq: u32,
    pub present: u8,
    pub reserved: [u8; 3],
}

impl PuckPayload {
    pub fn encode(seq: u32, present: bool) -> Self {
        Self {
            seq,
            present: present as u8,
            reserved: [0; 3],
        }
    }

    pub fn decode(&self) -> Result<bool, DecodeError> {
        flag(self.present, "present")
    }
}

const SKILL_GET_S0: u8 = 1;
const SKILL_BRING_PUCK: u8 = 2;
const SKILL_DELIVER: u8 = 3;
const SKILL_DISCARD: u8 = 4;

fn encode_request(request: SkillRequest) -> (u8, u8) {
    match request {
        SkillRequest::GetS0 => (SKILL_GET_S0, 0),
        SkillRequest::BringPuckTo(m) => (SKILL_BRING_PUCK, m.number()),
        SkillRequest::DeliverTo(g) => (SKILL_DELIVER, g.number()),
        SkillRequest::Discard => (SKILL_DISCARD, 0),
    }
}

fn decode_request(kind: u8, target: u8) -> Result<SkillRequest, DecodeError> {
    match kind {
        SKILL_GET_S0 => Ok(SkillRequest::GetS0),
        SKILL_DISCARD => Ok(SkillRequest::Discard),
        SKILL_BRING_PUCK => Ok(SkillRequest::BringPuckTo(machine(target)?)),
        SKILL_DELIVER => {
            GateId::new(target)
                .map(SkillRequest::DeliverTo)
                .ok_or(DecodeError::UnknownCode {
                    field: "target",
                    code: target,
                })
        }
        code => Err(DecodeError::UnknownCode {
            field: "kind",
            code,
        }),
    }
}

/// A skill request from an agent (published for monitoring and other robots).
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::SkillRequest")]
#[repr(C)]
pub struct SkillRequestPayload {
    pub seq: u32,
    pub robot: u8,
    pub kind: u8,
    pub target: u8,
    pub reserved: u8,
}

impl SkillRequestPayload {
    pub fn encode(seq: u32, robot: u8, request: SkillRequest) -> Self {
        let (kind, target) = encode_request(request);
        Self {
            seq,
            robot,
            kind,
            target,
            reserved: 0,
        }
    }

    pub fn decode(&self) -> Result<(u8, SkillRequest), DecodeError> {
        Ok((robot(self.robot)?, decode_request(self.kind, self.target)?))
    }
}

const STATE_RUNNING: u8 = 0;
const STATE_FINAL: u8 = 1;
const STATE_FAILED: u8 = 2;

const PERCEPTION_GOT_S0: u8 = 1;
const PERCEPTION_LIGHT: u8 = 2;
const PERCEPTION_LIGHT_UNCHANGED: u8 = 3;
const PERCEPTION_DELIVERED: u8 = 4;
const PERCEPTION_RELEASED: u8 = 5;

/// A skill's state for monitoring. `detail` is the perception code (FINAL) or the fail
/// reason (FAILED); `light` carries the seen light for `PERCEPTION_LIGHT`.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::SkillStatus")]
#[repr(C)]
pub struct SkillStatusPayload {
    pub seq: u32,
    /// The `seq` of the request this status answers.
    pub request_seq: u32,
    pub robot: u8,
    pub kind: u8,
    pub target: u8,
    pub state: u8,
    pub detail: u8,
    pub light: u8,
    pub reserved: [u8; 2],
}

/// A decoded skill status.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkillStatus {
    pub request_seq: u32,
    pub robot: u8,
    pub request: SkillRequest,
    pub outcome: SkillOutcome,
}

impl SkillStatusPayload {
    pub fn encode(seq: u32, status: &SkillStatus) -> Self {
        let (kind, target) = encode_request(status.request);
        let (state, detail, light) = match status.outcome {
            SkillOutcome::Running => (STATE_RUNNING, 0, 0),
            SkillOutcome::Failed(r) => (STATE_FAILED, r.code(), 0),
            SkillOutcome::Final(p) => match p {
                Perception::GotS0 => (STATE_FINAL, PERCEPTION_GOT_S0, 0),
                Perception::LightSeen(l) => (STATE_FINAL, PERCEPTION_LIGHT, l.code()),
                Perception::LightUnchanged => (STATE_FINAL, PERCEPTION_LIGHT_UNCHANGED, 0),
                Perception::Delivered => (STATE_FINAL, PERCEPTION_DELIVERED, 0),
                Perception::Released => (STATE_FINAL, PERCEPTION_RELEASED, 0),
            },
        };
        Self {
            seq,
            request_seq: status.request_seq,
            robot: status.robot,
            kind,
            target,
            state,
            detail,
            light,
            reserved: [0; 2],
        }
    }

    pub fn decode(&self) -> Result<SkillStatus, DecodeError> {
        let unknown = |field, code| DecodeError::UnknownCode { field, code };
        let outcome = match self.state {
            STATE_RUNNING => SkillOutcome::Running,
            STATE_FAILED => SkillOutcome::Failed(
                FailReason::from_code(self.detail).ok_or(unknown("detail", self.detail))?,
            ),
            STATE_FINAL => SkillOutcome::Final(match self.detail {
                PERCEPTION_GOT_S0 => Perception::GotS0,
                PERCEPTION_LIGHT => Perception::LightSeen(
                    LightSignal::from_code(self.light).ok_or(unknown("light", self.light))?,
                ),
                PERCEPTION_LIGHT_UNCHANGED => Perception::LightUnchanged,
                PERCEPTION_DELIVERED => Perception::Delivered,
                PERCEPTION_RELEASED => Perception::Released,
                code => return Err(unknown("detail", code)),
            }),
            code => return Err(unknown("state", code)),
        };
        Ok(SkillStatus {
            request_seq: self.request_seq,
            robot: robot(self.robot)?,
            request: decode_request(self.kind, self.target)?,
            outcome,
        })
    }
}

/// Which driver a heartbeat comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum DriverId {
    /// `robotino-sim`, standing for all drivers at once.
    Sim = 1,
    Ir = 2,
    Bumper = 3,
    Gyro = 4,
    Drive = 5,
    Camera = 6,
    Agent = 7,
}

impl DriverId {
    pub fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            1 => Self::Sim,
            2 => Self::Ir,
            3 => Self::Bumper,
            4 => Self::Gyro,
            5 => Self::Drive,
            6 => Self::Camera,
            7 => Self::Agent,
            _ => return None,
        })
    }
}

/// A driver's sign of life, once per driver cycle.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::Heartbeat")]
#[repr(C)]
pub struct HeartbeatPayload {
    pub seq: u32,
    /// The driver's own cycle counter (simulated cycles for the sim).
    pub cycle: u32,
    pub driver: u8,
    pub reserved: [u8; 3],
}

impl HeartbeatPayload {
    pub fn encode(seq: u32, cycle: u32, driver: DriverId) -> Self {
        Self {
            seq,
            cycle,
            driver: driver as u8,
            reserved: [0; 3],
        }
    }

    pub fn decode(&self) -> Result<(DriverId, u32), DecodeError> {
        let driver = DriverId::from_code(self.driver).ok_or(DecodeError::UnknownCode {
            field: "driver",
            code: self.driver,
        })?;
        Ok((driver, self.cycle))
    }
}

/// Machine types as shared between robots; 0 = unknown.
pub const MACHINE_TYPE_UNKNOWN: u8 = 0;
/// Highest machine type code (T3).
pub const MACHINE_TYPE_MAX: u8 = 3;
/// Bits of `loaded`: which inputs the machine currently holds.
pub const LOADED_S0: u8 = 1;
pub const LOADED_S1: u8 = 2;
pub const LOADED_S2: u8 = 4;

/// One robot's belief about one machine, shared with the other robots.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::WorldModelShare")]
#[repr(C)]
pub struct WorldModelPayload {
    pub seq: u32,
    pub robot: u8,
    pub machine: u8,
    /// 0 unknown, 1..=3 for T1..T3.
    pub machine_type: u8,
    /// `LOADED_*` bits.
    pub loaded: u8,
}

/// A decoded world-model update.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MachineBelief {
    pub robot: u8,
    pub machine: MachineId,
    pub machine_type: Option<u8>,
    pub loaded: u8,
}

impl WorldModelPayload {
    pub fn encode(seq: u32, belief: &MachineBelief) -> Self {
        Self {
            seq,
            robot: belief.robot,
            machine: belief.machine.number(),
            machine_type: belief.machine_type.unwrap_or(MACHINE_TYPE_UNKNOWN),
            loaded: belief.loaded,
        }
    }

    pub fn decode(&self) -> Result<MachineBelief, DecodeError> {
        if self.machine_type > MACHINE_TYPE_MAX {
            return Err(DecodeError::UnknownCode {
                field: "machine_type",
                code: self.machine_type,
            });
        }
        if self.loaded & !(LOADED_S0 | LOADED_S1 | LOADED_S2) != 0 {
            return Err(DecodeError::UnknownCode {
                field: "loaded",
                code: self.loaded,
            });
        }
        Ok(MachineBelief {
            robot: robot(self.robot)?,
            machine: machine(self.machine)?,
            machine_type: (self.machine_type != MACHINE_TYPE_UNKNOWN).then_some(self.machine_type),
            loaded: self.loaded,
        })
    }
}

/// A robot claims a machine before driving to it (1) and releases it afterwards (0).
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::MachineClaim")]
#[repr(C)]
pub struct MachineClaimPayload {
    pub seq: u32,
    pub robot: u8,
    pub machine: u8,
    pub claimed: u8,
    pub reserved: u8,
}

impl MachineClaimPayload {
    pub fn encode(seq: u32, robot: u8, machine: MachineId, claimed: bool) -> Self {
        Self {
            seq,
            robot,
            machine: machine.number(),
            claimed: claimed as u8,
            reserved: 0,
        }
    }

    /// `(robot, machine, claimed)`.
    pub fn decode(&self) -> Result<(u8, MachineId, bool), DecodeError> {
        Ok((
            robot(self.robot)?,
            machine(self.machine)?,
            flag(self.claimed, "claimed")?,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(n: u8) -> MachineId {
        MachineId::new(n).unwrap_or_else(|| panic!("machine {n}"))
    }

    #[test]
    fn ir_scan_round_trip_and_rejects() {
        let mut scan = IrScan::EMPTY;
        scan.distances_m[2] = 0.2;
        let p = IrScanPayload::encode(7, &scan);
        assert_eq!(p.decode(), Ok(scan));
        let mut bad = p;
        bad.distances_m[0] = f32::NAN;
        assert_eq!(bad.decode(), Err(DecodeError::NotFinite("distances_m")));
        bad.distances_m[0] = 0.5;
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("distances_m")));
        bad.distances_m[0] = -0.01;
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("distances_m")));
    }

    #[test]
    fn flags_reject_other_bytes() {
        assert_eq!(BumperPayload::encode(1, true).decode(), Ok(true));
        let mut b = BumperPayload::encode(1, false);
        assert_eq!(b.decode(), Ok(false));
        b.pressed = 2;
        assert!(matches!(
            b.decode(),
            Err(DecodeError::UnknownCode { code: 2, .. })
        ));
        let mut p = PuckPayload::encode(1, true);
        p.present = 255;
        assert!(p.decode().is_err());
    }

    #[test]
    fn gyro_rejects_nan_and_range() {
        let ok = GyroPayload::encode(
            3,
            GyroSample {
                angle_rad: 1.0,
                rate_rad_s: -0.5,
            },
        );
        assert!(ok.decode().is_ok());
        let mut bad = ok;
        bad.angle_rad = 4.0;
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("angle_rad")));
        bad = ok;
        bad.rate_rad_s = f32::INFINITY;
        assert_eq!(bad.decode(), Err(DecodeError::NotFinite("rate_rad_s")));
    }

    #[test]
    fn odometry_and_motor_round_trip() {
        let r = OdometryReading {
            pose: Pose2::new(1.0, 2.0, 0.5),
            measured: WheelSpeeds {
                rpm: [100.0, -200.0, 300.0],
            },
        };
        assert_eq!(OdometryPayload::encode(1, &r).decode(), Ok(r));
        let mut bad = OdometryPayload::encode(1, &r);
        bad.x_m = 50.0;
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("x_m")));
        let cmd = MotorCommandPayload::encode(9, 4, r.measured);
        assert_eq!(cmd.decode(), Ok(r.measured));
        let mut bad = cmd;
        bad.rpm[1] = f32::NAN;
        assert_eq!(bad.decode(), Err(DecodeError::NotFinite("rpm")));
        bad.rpm[1] = 1e9;
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("rpm")));
        let release = cmd.with_release(true);
        assert_eq!(release.release(), Ok(true));
        assert_eq!(cmd.release(), Ok(false));
        let mut bad = release;
        bad.release_puck = 3;
        assert!(matches!(
            bad.decode(),
            Err(DecodeError::UnknownCode {
                field: "release_puck",
                code: 3
            })
        ));
    }

    #[test]
    fn light_carries_the_active_gate() {
        let g = GateId::new(2);
        let p = LightPayload::encode(1, None).with_gate(g);
        assert_eq!(p.active_gate(), Ok(g));
        assert_eq!(LightPayload::encode(1, None).active_gate(), Ok(None));
        let mut bad = p;
        bad.active_gate = 4;
        assert!(matches!(
            bad.decode(),
            Err(DecodeError::UnknownCode {
                field: "active_gate",
                code: 4
            })
        ));
    }

    #[test]
    fn light_codes() {
        let seen = Some((m(4), LightSignal::YellowFlashing));
        assert_eq!(LightPayload::encode(1, seen).decode(), Ok(seen));
        assert_eq!(LightPayload::encode(1, None).decode(), Ok(None));
        let mut bad = LightPayload::encode(1, seen);
        bad.light = 9;
        assert!(matches!(
            bad.decode(),
            Err(DecodeError::UnknownCode { field: "light", .. })
        ));
        bad = LightPayload::encode(1, seen);
        bad.machine = 11;
        assert!(matches!(
            bad.decode(),
            Err(DecodeError::UnknownCode {
                field: "machine",
                ..
            })
        ));
    }

    #[test]
    fn skill_request_and_status_round_trip() {
        for req in [
            SkillRequest::GetS0,
            SkillRequest::BringPuckTo(m(10)),
            SkillRequest::DeliverTo(GateId::new(2).unwrap_or_else(|| panic!("gate"))),
            SkillRequest::Discard,
        ] {
            assert_eq!(
                SkillRequestPayload::encode(1, 2, req).decode(),
                Ok((2, req))
            );
            for outcome in [
                SkillOutcome::Running,
                SkillOutcome::Failed(FailReason::Bumper),
                SkillOutcome::Final(Perception::GotS0),
                SkillOutcome::Final(Perception::LightSeen(LightSignal::Yellow)),
                SkillOutcome::Final(Perception::LightUnchanged),
                SkillOutcome::Final(Perception::Delivered),
                SkillOutcome::Final(Perception::Released),
            ] {
                let s = SkillStatus {
                    request_seq: 5,
                    robot: 1,
                    request: req,
                    outcome,
                };
                assert_eq!(SkillStatusPayload::encode(3, &s).decode(), Ok(s));
            }
        }
        let mut bad = SkillRequestPayload::encode(1, 1, SkillRequest::GetS0);
        bad.kind = 0;
        assert!(bad.decode().is_err());
        bad = SkillRequestPayload::encode(1, 4, SkillRequest::GetS0);
        assert_eq!(bad.decode(), Err(DecodeError::OutOfRange("robot")));
        bad = SkillRequestPayload::encode(1, 1, SkillRequest::GetS0);
        bad.kind = SKILL_DELIVER;
        bad.target = 4;
        assert!(bad.decode().is_err());
        let mut st = SkillStatusPayload::encode(
            1,
            &SkillStatus {
                request_seq: 1,
                robot: 1,
                request: SkillRequest::GetS0,
                outcome: SkillOutcome::Running,
            },
        );
        st.state = 3;
        assert!(st.decode().is_err());
        st.state = STATE_FAILED;
        st.detail = 0;
        assert!(st.decode().is_err());
    }

    #[test]
    fn heartbeat_world_model_and_claims() {
        assert_eq!(
            HeartbeatPayload::encode(1, 42, DriverId::Sim).decode(),
            Ok((DriverId::Sim, 42))
        );
        let mut hb = HeartbeatPayload::encode(1, 42, DriverId::Sim);
        hb.driver = 0;
        assert!(hb.decode().is_err());

        let belief = MachineBelief {
            robot: 2,
            machine: m(7),
            machine_type: Some(3),
            loaded: LOADED_S0 | LOADED_S2,
        };
        assert_eq!(WorldModelPayload::encode(1, &belief).decode(), Ok(belief));
        let mut wm = WorldModelPayload::encode(1, &belief);
        wm.machine_type = 4;
        assert!(wm.decode().is_err());
        wm = WorldModelPayload::encode(1, &belief);
        wm.loaded = 8;
        assert!(wm.decode().is_err());

        assert_eq!(
            MachineClaimPayload::encode(1, 3, m(1), true).decode(),
            Ok((3, m(1), true))
        );
        let mut c = MachineClaimPayload::encode(1, 3, m(1), true);
        c.claimed = 7;
        assert!(c.decode().is_err());
    }
}
