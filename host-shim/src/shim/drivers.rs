//! The robot's devices as the agent's loop sees them: the `hal` device traits, implemented
//! here over the simulated drivers' iceoryx2 services (`robotino-sim`). `run` reads sensors
//! and commands the motors only through these traits, so a real Robotino's drivers take
//! this module's place without touching the agent.
//!
//! Each read returns the device's newest valid reading; an invalid sample is
//! `ErrorKind::InvalidData` and no sample yet `ErrorKind::Timeout` (the reader keeps what it
//! had, and [`Freshness`] shows the device as stale); a broken transport is
//! `ErrorKind::Disconnected`. The motor command carries the newest bumper sample's number,
//! which in lockstep tells the sim which frame it answers.

use hal::device::{
    Bumper, Device, Freshness, GateSignal, Gyro, GyroSample, IrRing, MachineLight, Odometry,
    OdometrySample, OmniDrive, PuckGrab, PuckRelease, PuckSensor,
};
use hal::field::{GateId, MachineId};
use hal::ir::IrScan;
use hal::{ErrorKind, ErrorType, LightSignal, Pose2, WheelSpeeds};

use super::payloads::{
    BumperPayload, DecodeError, GyroPayload, IrScanPayload, LightPayload, MotorCommandPayload,
    OdometryPayload, PuckPayload,
};
use super::transport::{Pub, RobotStream, Sub, Transport, TransportError};

/// A driver failure: the device's kind of error and what happened.
#[derive(Debug)]
pub struct DriverError {
    pub kind: ErrorKind,
    pub detail: String,
}

impl hal::Error for DriverError {
    fn kind(&self) -> ErrorKind {
        self.kind
    }
}

impl std::fmt::Display for DriverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.kind, self.detail)
    }
}

impl std::error::Error for DriverError {}

impl From<TransportError> for DriverError {
    fn from(e: TransportError) -> Self {
        Self {
            kind: ErrorKind::Disconnected,
            detail: e.to_string(),
        }
    }
}

impl From<DecodeError> for DriverError {
    fn from(e: DecodeError) -> Self {
        Self {
            kind: ErrorKind::InvalidData,
            detail: format!("{e:?}"),
        }
    }
}

fn no_sample(device: &str) -> DriverError {
    DriverError {
        kind: ErrorKind::Timeout,
        detail: format!("no {device} sample yet"),
    }
}

/// A reading worth using: `Ok(None)` for a missing or invalid sample (the caller keeps what
/// it had), the error only when the device is gone.
pub fn usable<T>(r: Result<T, DriverError>) -> Result<Option<T>, DriverError> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(e) if e.kind == ErrorKind::Disconnected => Err(e),
        Err(_) => Ok(None),
    }
}

/// One robot's simulated drivers, reached over iceoryx2.
pub struct SimDrivers {
    ir: Sub<IrScanPayload>,
    bumper: Sub<BumperPayload>,
    gyro: Sub<GyroPayload>,
    odometry: Sub<OdometryPayload>,
    puck: Sub<PuckPayload>,
    light: Sub<LightPayload>,
    motor: Pub<MotorCommandPayload>,
    /// Sequence numbers of the newest valid reading, by [`Device`].
    seq: [Option<u32>; 6],
    measured: WheelSpeeds,
    release: bool,
    grab: bool,
}

fn slot(d: Device) -> usize {
    match d {
        Device::Ir => 0,
        Device::Bumper => 1,
        Device::Gyro => 2,
        Device::Odometry => 3,
        Device::Puck => 4,
        Device::Camera => 5,
    }
}

impl SimDrivers {
    pub fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        let name = |s| t.names.robot(robot, s);
        Ok(Self {
            ir: t.subscriber(&name(RobotStream::Ir))?,
            bumper: t.subscriber(&name(RobotStream::Bumper))?,
            gyro: t.subscriber(&name(RobotStream::Gyro))?,
            odometry: t.subscriber(&name(RobotStream::Odometry))?,
            puck: t.subscriber(&name(RobotStream::Puck))?,
            light: t.subscriber(&name(RobotStream::Light))?,
            motor: t.publisher(&name(RobotStream::Motor))?,
            seq: [None; 6],
            measured: WheelSpeeds::ZERO,
            release: false,
            grab: false,
        })
    }

    fn fresh(&mut self, d: Device, seq: u32) {
        self.seq[slot(d)] = Some(seq);
    }
}

impl ErrorType for SimDrivers {
    type Error = DriverError;
}

impl Freshness for SimDrivers {
    fn sequence(&self, device: Device) -> Option<u32> {
        self.seq[slot(device)]
    }
}

impl IrRing for SimDrivers {
    fn read_scan(&mut self) -> Result<IrScan, DriverError> {
        let s = self.ir.poll()?.ok_or_else(|| no_sample("IR"))?;
        let scan = s.decode()?;
        self.fresh(Device::Ir, s.seq);
        Ok(scan)
    }
}

impl Bumper for SimDrivers {
    fn is_pressed(&mut self) -> Result<bool, DriverError> {
        let s = self.bumper.poll()?.ok_or_else(|| no_sample("bumper"))?;
        let pressed = s.decode()?;
        self.fresh(Device::Bumper, s.seq);
        Ok(pressed)
    }
}

impl Gyro for SimDrivers {
    fn read(&mut self) -> Result<GyroSample, DriverError> {
        let s = self.gyro.poll()?.ok_or_else(|| no_sample("gyro"))?;
        let g = s.decode()?;
        self.fresh(Device::Gyro, s.seq);
        Ok(g)
    }
}

impl Odometry for SimDrivers {
    fn read_pose(&mut self) -> Result<OdometrySample, DriverError> {
        let s = self.odometry.poll()?.ok_or_else(|| no_sample("odometry"))?;
        // The driver's odometry already fuses wheels and gyro (hal::odometry).
        let r = s.decode()?;
        self.measured = r.measured;
        self.fresh(Device::Odometry, s.seq);
        Ok(OdometrySample {
            pose: r.pose,
            sequence: s.seq,
        })
    }

    fn set_pose(&mut self, _pose: Pose2) -> Result<(), DriverError> {
        Err(DriverError {
            kind: ErrorKind::Other,
            detail: "the simulated drive integrates from its start pose only".into(),
        })
    }
}

impl PuckSensor for SimDrivers {
    fn has_puck(&mut self) -> Result<bool, DriverError> {
        let s = self.puck.poll()?.ok_or_else(|| no_sample("puck"))?;
        let present = s.decode()?;
        self.fresh(Device::Puck, s.seq);
        Ok(present)
    }
}

impl MachineLight for SimDrivers {
    fn read_light(&mut self) -> Result<Option<(MachineId, LightSignal)>, DriverError> {
        let s = self.light.poll()?.ok_or_else(|| no_sample("camera"))?;
        let light = s.decode()?;
        self.fresh(Device::Camera, s.seq);
        Ok(light)
    }
}

impl GateSignal for SimDrivers {
    fn active_gate(&mut self) -> Result<Option<GateId>, DriverError> {
        let s = self.light.poll()?.ok_or_else(|| no_sample("camera"))?;
        Ok(s.active_gate()?)
    }
}

impl PuckRelease for SimDrivers {
    fn set_release(&mut self, release: bool) -> Result<(), DriverError> {
        self.release = release;
        Ok(())
    }
}

impl PuckGrab for SimDrivers {
    fn set_grab(&mut self, grab: bool) -> Result<(), DriverError> {
        self.grab = grab;
        Ok(())
    }
}

impl OmniDrive for SimDrivers {
    fn set_motor_speeds(&mut self, speeds: WheelSpeeds) -> Result<(), DriverError> {
        let bumper_seq = self.seq[slot(Device::Bumper)].unwrap_or(0);
        let (release, grab) = (self.release, self.grab);
        self.motor.send(|s| {
            MotorCommandPayload::encode(s, bumper_seq, speeds)
                .with_release(release)
                .with_grab(grab)
        })?;
        Ok(())
    }

    fn motor_speeds(&mut self) -> Result<WheelSpeeds, DriverError> {
        Ok(self.measured)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The agent's side reads a simulated driver's samples through the `hal` traits: a
    /// valid reading is fresh, an invalid one is `InvalidData` and leaves freshness as it
    /// was, and the motor command carries the newest bumper sample's number and the release.
    #[test]
    fn hal_traits_over_the_simulated_drivers() {
        let prefix = format!("unit/drivers/{}", std::process::id());
        let t = Transport::open(&prefix, "drivers-test").unwrap_or_else(|e| panic!("{e}"));
        let mut bumper = t
            .publisher::<BumperPayload>(&t.names.robot(1, RobotStream::Bumper))
            .unwrap_or_else(|e| panic!("{e}"));
        let mut motor = t
            .subscriber::<MotorCommandPayload>(&t.names.robot(1, RobotStream::Motor))
            .unwrap_or_else(|e| panic!("{e}"));
        let mut d = SimDrivers::open(&t, 1).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            d.is_pressed().map_err(|e| e.kind).err(),
            Some(ErrorKind::Timeout)
        );
        assert_eq!(d.sequence(Device::Bumper), None);
        let seq = bumper
            .send(|s| BumperPayload::encode(s, true))
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(d.is_pressed().unwrap_or_else(|e| panic!("{e}")));
        assert_eq!(d.sequence(Device::Bumper), Some(seq));
        bumper
            .send(|s| {
                let mut p = BumperPayload::encode(s, false);
                p.pressed = 7;
                p
            })
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            d.is_pressed().map_err(|e| e.kind).err(),
            Some(ErrorKind::InvalidData)
        );
        assert_eq!(d.sequence(Device::Bumper), Some(seq));
        assert!(usable(d.is_pressed())
            .unwrap_or_else(|e| panic!("{e}"))
            .is_none());
        d.set_release(true).unwrap_or_else(|e| panic!("{e}"));
        d.set_motor_speeds(WheelSpeeds::ZERO)
            .unwrap_or_else(|e| panic!("{e}"));
        let sent = motor
            .poll()
            .unwrap_or_else(|e| panic!("{e}"))
            .unwrap_or_else(|| panic!("no motor command"));
        assert_eq!(sent.bumper_seq, seq);
        assert_eq!(sent.release(), Ok(true));
    }
}
