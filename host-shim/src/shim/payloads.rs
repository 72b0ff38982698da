//! Fixed-size `#[repr(C)]` payloads, one per iceoryx2 service, and a pure validating decoder
//! for each. Every payload starts with `seq`, the publisher's sequence number, which readers
//! use to tell a fresh sample from a repeated one. Flags are `u8` (0/1) rather than `bool`
//! so that a corrupt byte is a decode error instead of undefined behaviour.
//!
//! Decoders take the payload by reference and return the hal's types or a [`DecodeError`];
//! they never panic, so they can be fuzzed directly.

use core::fmt;
use hal::device::GyroSample;
use hal::field::{GateId, MachineId, RecyclingId};
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
    UnknownCode {
        field: &'static str,
        code: u8,
    },
    /// Text that does not parse (a team batch's JSON).
    Malformed(&'static str),
    /// A byte buffer of the wrong size for the payload ([`Wire::from_bytes`]).
    Length {
        expected: usize,
        got: usize,
    },
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(field) => write!(f, "field `{field}` is NaN or infinite"),
            Self::OutOfRange(field) => write!(f, "field `{field}` is out of range"),
            Self::UnknownCode { field, code } => {
                write!(f, "field `{field}` has unknown code {code}")
            }
            Self::Malformed(field) => write!(f, "field `{field}` does not parse"),
            Self::Length { expected, got } => {
                write!(f, "payload of {got} bytes, expected {expected}")
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
/// behaviour layer's discard); `grab_puck` = 1 to take one lying in front of it (junk at a
/// machine).
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::MotorCommand")]
#[repr(C)]
pub struct MotorCommandPayload {
    pub seq: u32,
    pub bumper_seq: u32,
    pub rpm: [f32; 3],
    pub release_puck: u8,
    pub grab_puck: u8,
    pub reserved: [u8; 2],
}

impl MotorCommandPayload {
    pub fn encode(seq: u32, bumper_seq: u32, wheels: WheelSpeeds) -> Self {
        Self {
            seq,
            bumper_seq,
            rpm: wheels.rpm,
            release_puck: 0,
            grab_puck: 0,
            reserved: [0; 2],
        }
    }

    /// The same command, asking (or not) to release the puck.
    pub fn with_release(mut self, release: bool) -> Self {
        self.release_puck = u8::from(release);
        self
    }

    /// The same command, asking (or not) to take the puck in front of the robot.
    pub fn with_grab(mut self, grab: bool) -> Self {
        self.grab_puck = u8::from(grab);
        self
    }

    /// The wheel speeds; every field is validated (an unknown release flag is an error too).
    pub fn decode(&self) -> Result<WheelSpeeds, DecodeError> {
        let mut wheels = WheelSpeeds::ZERO;
        for (out, &r) in wheels.rpm.iter_mut().zip(self.rpm.iter()) {
            *out = within(r, -MAX_WIRE_RPM, MAX_WIRE_RPM, "rpm")?;
        }
        flag(self.release_puck, "release_puck")?;
        flag(self.grab_puck, "grab_puck")?;
        Ok(wheels)
    }

    /// Whether the command asks to release the puck.
    pub fn release(&self) -> Result<bool, DecodeError> {
        flag(self.release_puck, "release_puck")
    }

    /// Whether the command asks to take the puck in front of the robot.
    pub fn grab(&self) -> Result<bool, DecodeError> {
        flag(self.grab_puck, "grab_puck")
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
const SKILL_GET_JUNK: u8 = 5;
const SKILL_RECYCLE: u8 = 6;
const SKILL_FEED: u8 = 7;
const SKILL_COLLECT: u8 = 8;

fn encode_request(request: SkillRequest) -> (u8, u8) {
    match request {
        SkillRequest::GetS0 => (SKILL_GET_S0, 0),
        SkillRequest::BringPuckTo(m) => (SKILL_BRING_PUCK, m.number()),
        SkillRequest::DeliverTo(g) => (SKILL_DELIVER, g.number()),
        SkillRequest::Discard => (SKILL_DISCARD, 0),
        SkillRequest::GetJunk(m) => (SKILL_GET_JUNK, m.number()),
        SkillRequest::Recycle(r) => (SKILL_RECYCLE, r.number()),
        SkillRequest::FeedTo(m) => (SKILL_FEED, m.number()),
        SkillRequest::Collect(m) => (SKILL_COLLECT, m.number()),
    }
}

fn decode_request(kind: u8, target: u8) -> Result<SkillRequest, DecodeError> {
    match kind {
        SKILL_GET_S0 => Ok(SkillRequest::GetS0),
        SKILL_DISCARD => Ok(SkillRequest::Discard),
        SKILL_BRING_PUCK => Ok(SkillRequest::BringPuckTo(machine(target)?)),
        SKILL_GET_JUNK => Ok(SkillRequest::GetJunk(machine(target)?)),
        SKILL_FEED => Ok(SkillRequest::FeedTo(machine(target)?)),
        SKILL_COLLECT => Ok(SkillRequest::Collect(machine(target)?)),
        SKILL_RECYCLE => {
            RecyclingId::new(target)
                .map(SkillRequest::Recycle)
                .ok_or(DecodeError::UnknownCode {
                    field: "target",
                    code: target,
                })
        }
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
const PERCEPTION_GOT_JUNK: u8 = 6;
const PERCEPTION_RECYCLED: u8 = 7;
const PERCEPTION_LEFT_PROCESSING: u8 = 8;
const PERCEPTION_GOT_OUTPUT: u8 = 9;

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
                Perception::GotJunk => (STATE_FINAL, PERCEPTION_GOT_JUNK, 0),
                Perception::Recycled => (STATE_FINAL, PERCEPTION_RECYCLED, 0),
                Perception::LeftProcessing => (STATE_FINAL, PERCEPTION_LEFT_PROCESSING, 0),
                Perception::GotOutput => (STATE_FINAL, PERCEPTION_GOT_OUTPUT, 0),
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
                PERCEPTION_GOT_JUNK => Perception::GotJunk,
                PERCEPTION_RECYCLED => Perception::Recycled,
                PERCEPTION_LEFT_PROCESSING => Perception::LeftProcessing,
                PERCEPTION_GOT_OUTPUT => Perception::GotOutput,
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

/// Bytes of team-message text one [`TeamBatchPayload`] carries.
pub const TEAM_BATCH_BYTES: usize = 4000;

/// A robot's team messages (`rules/team.clp`'s `team-send` facts) of one cycle, as JSON
/// text: the same form the Zenoh link carries between machines. A cycle whose messages
/// do not fit is sent as several batches with the same `cycle`.
#[derive(Debug, Clone, Copy, PartialEq, ZeroCopySend)]
#[type_name("robotino::TeamBatch")]
#[repr(C)]
pub struct TeamBatchPayload {
    pub seq: u32,
    /// The sender's cycle (in lockstep the sim frame it answered): a receiver hands the
    /// batch to its rules in the next cycle, so every run of a seed delivers alike.
    pub cycle: u32,
    /// Bytes of `text` in use.
    pub len: u32,
    pub robot: u8,
    pub reserved: [u8; 3],
    pub text: [u8; TEAM_BATCH_BYTES],
}

impl TeamBatchPayload {
    /// `None` when the JSON text of `msgs` does not fit one batch.
    pub fn encode(seq: u32, robot: u8, cycle: u32, msgs: &[crate::team::TeamMsg]) -> Option<Self> {
        let json = serde_json::to_vec(msgs).ok()?;
        if json.len() > TEAM_BATCH_BYTES {
            return None;
        }
        let mut text = [0u8; TEAM_BATCH_BYTES];
        text[..json.len()].copy_from_slice(&json);
        Some(Self {
            seq,
            cycle,
            len: json.len() as u32,
            robot,
            reserved: [0; 3],
            text,
        })
    }

    /// `(robot, cycle, messages)`; every message must name the sending robot.
    pub fn decode(&self) -> Result<(u8, u32, Vec<crate::team::TeamMsg>), DecodeError> {
        let robot = robot(self.robot)?;
        let len = usize::try_from(self.len).map_err(|_| DecodeError::OutOfRange("len"))?;
        let text = self.text.get(..len).ok_or(DecodeError::OutOfRange("len"))?;
        let msgs: Vec<crate::team::TeamMsg> =
            serde_json::from_slice(text).map_err(|_| DecodeError::Malformed("text"))?;
        if msgs.iter().any(|m| m.from != robot) {
            return Err(DecodeError::OutOfRange("text"));
        }
        Ok((robot, self.cycle, msgs))
    }
}

/// The byte-level form of every payload: what a foreign publisher (or a fuzzer) hands over.
/// `from_bytes` reads the fields in declaration order (native endianness, as the shared
/// memory holds them) and validates them with the payload's own decoder; reserved bytes are
/// not checked, so newer senders may use them.
pub trait Wire: Sized {
    /// Bytes of the `#[repr(C)]` layout (no padding: every payload is u32/f32 first, then u8).
    const SIZE: usize;
    fn from_bytes(bytes: &[u8]) -> Result<Self, DecodeError>;
    fn to_bytes(&self) -> Vec<u8>;
}

/// Reads fields one after another from a byte slice.
struct Reader<'a>(&'a [u8]);

trait Field: Sized {
    fn read(r: &mut Reader<'_>) -> Option<Self>;
    fn write(&self, out: &mut Vec<u8>);
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, rest) = self.0.split_first_chunk::<N>()?;
        self.0 = rest;
        Some(*head)
    }
}

impl Field for u8 {
    fn read(r: &mut Reader<'_>) -> Option<Self> {
        r.take::<1>().map(|[b]| b)
    }
    fn write(&self, out: &mut Vec<u8>) {
        out.push(*self);
    }
}

impl Field for u32 {
    fn read(r: &mut Reader<'_>) -> Option<Self> {
        r.take().map(u32::from_ne_bytes)
    }
    fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_ne_bytes());
    }
}

impl Field for f32 {
    fn read(r: &mut Reader<'_>) -> Option<Self> {
        r.take().map(f32::from_ne_bytes)
    }
    fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_ne_bytes());
    }
}

impl<T: Field + Copy + Default, const N: usize> Field for [T; N] {
    fn read(r: &mut Reader<'_>) -> Option<Self> {
        let mut a = [T::default(); N];
        for x in a.iter_mut() {
            *x = T::read(r)?;
        }
        Some(a)
    }
    fn write(&self, out: &mut Vec<u8>) {
        for x in self {
            x.write(out);
        }
    }
}

/// Implements [`Wire`] for a payload from its field list (in declaration order).
macro_rules! wire {
    ($t:ident { $($f:ident),* $(,)? }) => {
        impl Wire for $t {
            const SIZE: usize = core::mem::size_of::<$t>();
            fn from_bytes(bytes: &[u8]) -> Result<Self, DecodeError> {
                let length = DecodeError::Length { expected: Self::SIZE, got: bytes.len() };
                if bytes.len() != Self::SIZE {
                    return Err(length);
                }
                let mut r = Reader(bytes);
                let p = $t { $($f: Field::read(&mut r).ok_or(length)?),* };
                if !r.0.is_empty() {
                    return Err(length);
                }
                p.decode()?;
                Ok(p)
            }
            fn to_bytes(&self) -> Vec<u8> {
                let mut out = Vec::with_capacity(Self::SIZE);
                $(self.$f.write(&mut out);)*
                out
            }
        }
    };
}

wire!(IrScanPayload { seq, distances_m });
wire!(BumperPayload {
    seq,
    pressed,
    reserved
});
wire!(GyroPayload {
    seq,
    angle_rad,
    rate_rad_s
});
wire!(OdometryPayload {
    seq,
    x_m,
    y_m,
    phi_rad,
    measured_rpm
});
wire!(MotorCommandPayload {
    seq,
    bumper_seq,
    rpm,
    release_puck,
    grab_puck,
    reserved
});
wire!(LightPayload {
    seq,
    machine,
    light,
    active_gate,
    reserved
});
wire!(PuckPayload {
    seq,
    present,
    reserved
});
wire!(SkillRequestPayload {
    seq,
    robot,
    kind,
    target,
    reserved
});
wire!(SkillStatusPayload {
    seq,
    request_seq,
    robot,
    kind,
    target,
    state,
    detail,
    light,
    reserved
});
wire!(HeartbeatPayload {
    seq,
    cycle,
    driver,
    reserved
});
wire!(TeamBatchPayload {
    seq,
    cycle,
    len,
    robot,
    reserved,
    text
});

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
        let grab = cmd.with_grab(true);
        assert_eq!((grab.grab(), grab.release()), (Ok(true), Ok(false)));
        let mut bad = grab;
        bad.grab_puck = 2;
        assert!(matches!(
            bad.decode(),
            Err(DecodeError::UnknownCode {
                field: "grab_puck",
                code: 2
            })
        ));
    }

    /// Encodes, goes through bytes and back, and checks that a wrong length and a bad field
    /// are rejected.
    fn wire_round_trip<T: Wire + PartialEq + fmt::Debug>(p: T, corrupt: impl Fn(&mut Vec<u8>)) {
        let bytes = p.to_bytes();
        assert_eq!(bytes.len(), T::SIZE, "{p:?}: padding in the layout?");
        assert_eq!(T::from_bytes(&bytes).as_ref(), Ok(&p));
        assert!(matches!(
            T::from_bytes(&bytes[1..]),
            Err(DecodeError::Length { .. })
        ));
        let mut bad = bytes;
        corrupt(&mut bad);
        assert!(T::from_bytes(&bad).is_err(), "{p:?}: corruption accepted");
    }

    #[test]
    fn junk_recycling_feed_and_collect_skills_round_trip() {
        let r2 = RecyclingId::new(2).unwrap_or_else(|| panic!("R2"));
        for (request, outcome) in [
            (
                SkillRequest::GetJunk(m(7)),
                SkillOutcome::Final(Perception::GotJunk),
            ),
            (
                SkillRequest::GetJunk(m(1)),
                SkillOutcome::Failed(FailReason::NoJunk),
            ),
            (
                SkillRequest::Recycle(r2),
                SkillOutcome::Final(Perception::Recycled),
            ),
            (
                SkillRequest::FeedTo(m(6)),
                SkillOutcome::Final(Perception::LeftProcessing),
            ),
            (
                SkillRequest::Collect(m(6)),
                SkillOutcome::Final(Perception::GotOutput),
            ),
            (
                SkillRequest::Collect(m(10)),
                SkillOutcome::Failed(FailReason::NoOutput),
            ),
        ] {
            let p = SkillRequestPayload::encode(1, 3, request);
            assert_eq!(p.decode(), Ok((3, request)));
            let status = SkillStatus {
                request_seq: 1,
                robot: 3,
                request,
                outcome,
            };
            assert_eq!(SkillStatusPayload::encode(2, &status).decode(), Ok(status));
        }
        let mut bad = SkillRequestPayload::encode(1, 1, SkillRequest::Recycle(r2));
        bad.target = 3;
        assert!(bad.decode().is_err());
    }

    #[test]
    fn every_payload_decodes_from_bytes_with_validation() {
        let gyro = GyroSample {
            angle_rad: 0.5,
            rate_rad_s: 0.1,
        };
        let reading = OdometryReading {
            pose: Pose2::new(1.0, 2.0, 0.5),
            measured: WheelSpeeds::ZERO,
        };
        let nan = |b: &mut Vec<u8>| b[4..8].copy_from_slice(&f32::NAN.to_ne_bytes());
        let byte = |i: usize, v: u8| move |b: &mut Vec<u8>| b[i] = v;
        wire_round_trip(IrScanPayload::encode(1, &IrScan::EMPTY), nan);
        wire_round_trip(BumperPayload::encode(2, true), byte(4, 2));
        wire_round_trip(GyroPayload::encode(3, gyro), nan);
        wire_round_trip(OdometryPayload::encode(4, &reading), nan);
        let motor = MotorCommandPayload::encode(5, 1, WheelSpeeds::ZERO).with_release(true);
        wire_round_trip(motor, byte(20, 7));
        let light =
            LightPayload::encode(6, Some((m(3), LightSignal::Green))).with_gate(GateId::new(1));
        wire_round_trip(light, byte(6, 9));
        wire_round_trip(PuckPayload::encode(7, false), byte(4, 5));
        wire_round_trip(
            SkillRequestPayload::encode(8, 1, SkillRequest::Discard),
            byte(4, 0),
        );
        let status = SkillStatus {
            request_seq: 3,
            robot: 2,
            request: SkillRequest::BringPuckTo(m(4)),
            outcome: SkillOutcome::Final(Perception::Released),
        };
        wire_round_trip(SkillStatusPayload::encode(9, &status), byte(11, 9));
        wire_round_trip(HeartbeatPayload::encode(10, 5, DriverId::Agent), byte(8, 0));
        let batch = TeamBatchPayload::encode(11, 2, 7, &[team_msg(2, "M3")])
            .unwrap_or_else(|| panic!("one message fits"));
        wire_round_trip(batch, byte(12, 9));
    }

    #[test]
    fn heartbeats_and_team_batches() {
        assert_eq!(
            HeartbeatPayload::encode(1, 42, DriverId::Sim).decode(),
            Ok((DriverId::Sim, 42))
        );
        let mut hb = HeartbeatPayload::encode(1, 42, DriverId::Sim);
        hb.driver = 0;
        assert!(hb.decode().is_err());

        let msgs = [team_msg(3, "INS"), team_msg(3, "M10")];
        let batch = TeamBatchPayload::encode(1, 3, 42, &msgs).unwrap_or_else(|| panic!("fits"));
        assert_eq!(batch.decode(), Ok((3, 42, msgs.to_vec())));
        // A message in another robot's name, garbage text, a length past the buffer.
        let mut forged = batch;
        forged.robot = 1;
        assert!(forged.decode().is_err());
        let mut garbage = batch;
        garbage.text[0] = b'x';
        assert_eq!(garbage.decode(), Err(DecodeError::Malformed("text")));
        let mut long = batch;
        long.len = TEAM_BATCH_BYTES as u32 + 1;
        assert_eq!(long.decode(), Err(DecodeError::OutOfRange("len")));
        // Too many messages for one batch: the sender splits them.
        let many: Vec<_> = (0..100).map(|_| team_msg(1, "M1")).collect();
        assert_eq!(TeamBatchPayload::encode(1, 1, 0, &many), None);
    }

    fn team_msg(from: u8, resource: &str) -> crate::team::TeamMsg {
        crate::team::TeamMsg {
            from,
            seq: 4,
            kind: "news".into(),
            to: 0,
            resource: resource.into(),
            rseq: 4,
            lease: 20.0,
            data: vec!["T2_3".into(), "0".into(), "1".into(), "S0".into()],
        }
    }
}
