//! One small trait per device. Traits only move data; configuration (ports, rates,
//! calibration) belongs to the implementation. Every method is fallible.

use crate::error::ErrorType;
use crate::field::{GateId, MachineId};
use crate::ir::IrScan;
use crate::kinematics::WheelSpeeds;
use crate::light::LightSignal;
use crate::odometry::Pose2;

/// The ring of nine IR distance sensors.
pub trait IrRing: ErrorType {
    /// The latest distances in metres, 0 where a sensor saw nothing.
    fn read_scan(&mut self) -> Result<IrScan, Self::Error>;
}

/// The contact strip around the base.
pub trait Bumper: ErrorType {
    fn is_pressed(&mut self) -> Result<bool, Self::Error>;
}

/// A gyro reading: absolute heading and turn rate, counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GyroSample {
    pub angle_rad: f32,
    pub rate_rad_s: f32,
}

pub trait Gyro: ErrorType {
    fn read(&mut self) -> Result<GyroSample, Self::Error>;
}

/// The three-wheel omni drive: motor speeds in, measured motor speeds out.
pub trait OmniDrive: ErrorType {
    /// Commands the three motors. Implementations keep their own dead-man rule.
    fn set_motor_speeds(&mut self, speeds: WheelSpeeds) -> Result<(), Self::Error>;
    /// The motors' measured speeds.
    fn motor_speeds(&mut self) -> Result<WheelSpeeds, Self::Error>;
}

/// A pose estimate with the driver's sequence number, so readers can tell fresh from stale.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OdometrySample {
    pub pose: Pose2,
    pub sequence: u32,
}

pub trait Odometry: ErrorType {
    fn read_pose(&mut self) -> Result<OdometrySample, Self::Error>;
    /// Sets the pose the driver integrates from.
    fn set_pose(&mut self, pose: Pose2) -> Result<(), Self::Error>;
}

/// The signal light of the machine in front of the robot (the camera).
pub trait MachineLight: ErrorType {
    /// The machine in view and its light; `None` when no light is in view.
    fn read_light(&mut self) -> Result<Option<(MachineId, LightSignal)>, Self::Error>;
}

/// The delivery gate whose light is on (the camera, looking at the gates).
pub trait GateSignal: ErrorType {
    /// `None` until the active gate was seen.
    fn active_gate(&mut self) -> Result<Option<GateId>, Self::Error>;
}

/// Whether a puck sits in the robot's gripper area (the front IR sensor on the 2012 robot).
pub trait PuckSensor: ErrorType {
    fn has_puck(&mut self) -> Result<bool, Self::Error>;
}

/// Letting go of the puck: the 2012 robot has no gripper to open, it backs away from the
/// puck; the drive does it when asked, with its next motor command.
pub trait PuckRelease: ErrorType {
    fn set_release(&mut self, release: bool) -> Result<(), Self::Error>;
}

/// The sensing devices, for telling fresh readings from stale ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Device {
    Ir,
    Bumper,
    Gyro,
    Odometry,
    Puck,
    Camera,
}

/// The sequence number of each device's newest valid reading: a reader that sees it
/// unchanged for too long treats the device as silent (the safety layer's deadline).
pub trait Freshness {
    fn sequence(&self, device: Device) -> Option<u32>;
}

impl<T: IrRing + ?Sized> IrRing for &mut T {
    fn read_scan(&mut self) -> Result<IrScan, Self::Error> {
        T::read_scan(self)
    }
}

impl<T: Bumper + ?Sized> Bumper for &mut T {
    fn is_pressed(&mut self) -> Result<bool, Self::Error> {
        T::is_pressed(self)
    }
}

impl<T: Gyro + ?Sized> Gyro for &mut T {
    fn read(&mut self) -> Result<GyroSample, Self::Error> {
        T::read(self)
    }
}

impl<T: OmniDrive + ?Sized> OmniDrive for &mut T {
    fn set_motor_speeds(&mut self, speeds: WheelSpeeds) -> Result<(), Self::Error> {
        T::set_motor_speeds(self, speeds)
    }
    fn motor_speeds(&mut self) -> Result<WheelSpeeds, Self::Error> {
        T::motor_speeds(self)
    }
}

impl<T: Odometry + ?Sized> Odometry for &mut T {
    fn read_pose(&mut self) -> Result<OdometrySample, Self::Error> {
        T::read_pose(self)
    }
    fn set_pose(&mut self, pose: Pose2) -> Result<(), Self::Error> {
        T::set_pose(self, pose)
    }
}

impl<T: MachineLight + ?Sized> MachineLight for &mut T {
    fn read_light(&mut self) -> Result<Option<(MachineId, LightSignal)>, Self::Error> {
        T::read_light(self)
    }
}

impl<T: GateSignal + ?Sized> GateSignal for &mut T {
    fn active_gate(&mut self) -> Result<Option<GateId>, Self::Error> {
        T::active_gate(self)
    }
}

impl<T: PuckRelease + ?Sized> PuckRelease for &mut T {
    fn set_release(&mut self, release: bool) -> Result<(), Self::Error> {
        T::set_release(self, release)
    }
}

impl<T: PuckGrab + ?Sized> PuckGrab for &mut T {
    fn set_grab(&mut self, grab: bool) -> Result<(), Self::Error> {
        T::set_grab(self, grab)
    }
}

impl<T: PuckSensor + ?Sized> PuckSensor for &mut T {
    fn has_puck(&mut self) -> Result<bool, Self::Error> {
        T::has_puck(self)
    }
}

/// Taking a puck that lies in front of the robot (junk at a machine's output): the 2012
/// robot drives onto it; the drive does it when asked, with its next motor command.
pub trait PuckGrab: ErrorType {
    fn set_grab(&mut self, grab: bool) -> Result<(), Self::Error>;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::{Error, ErrorKind};

    /// A bumper that fails after a number of reads, to show errors flow through `&mut T`.
    struct FlakyBumper {
        reads_left: u8,
    }

    #[derive(Debug)]
    struct SerialTimeout;

    impl Error for SerialTimeout {
        fn kind(&self) -> ErrorKind {
            ErrorKind::Timeout
        }
    }

    impl ErrorType for FlakyBumper {
        type Error = SerialTimeout;
    }

    impl Bumper for FlakyBumper {
        fn is_pressed(&mut self) -> Result<bool, SerialTimeout> {
            if self.reads_left == 0 {
                return Err(SerialTimeout);
            }
            self.reads_left -= 1;
            Ok(self.reads_left == 0)
        }
    }

    fn generic_read<B: Bumper>(mut bumper: B) -> Result<bool, ErrorKind> {
        bumper.is_pressed().map_err(|e| e.kind())
    }

    #[test]
    fn forwarding_impl_reaches_the_device() {
        let mut b = FlakyBumper { reads_left: 2 };
        assert_eq!(generic_read(&mut b), Ok(false));
        assert_eq!(generic_read(&mut b), Ok(true));
        assert_eq!(generic_read(&mut b), Err(ErrorKind::Timeout));
    }
}
