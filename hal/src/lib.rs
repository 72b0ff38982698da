//! Hardware abstraction for the Festo Robotino (`no_std`, no alloc).
//!
//! * [`device`]: one small trait per device (IR ring, bumper, gyro, omni drive, odometry,
//!   machine light, active gate, puck sensor, puck release), embedded-hal style: every
//!   method is fallible and each implementation's error maps to a shared [`ErrorKind`];
//!   `Freshness` tells fresh readings from stale ones.
//! * [`kinematics`], [`limits`], [`odometry`]: the three-wheel omni drive's transforms, the
//!   speed/acceleration limits and pose integration fused with the gyro heading.
//! * [`ir`]: the IR ring's geometry and the sensors' volts-to-metres table.
//! * [`field`]: the LLSF 2012 field and its places.
//! * [`skill`]: the contract between the agent and the behaviour layer.
//!
//! Units are in the names (`_m`, `_rad`, `_rpm`, `_m_s`); angles are counter-clockwise.
#![no_std]

pub mod device;
pub mod error;
pub mod field;
pub mod ir;
pub mod kinematics;
pub mod light;
pub mod limits;
pub mod odometry;
pub mod skill;

pub use error::{Error, ErrorKind, ErrorType};
pub use kinematics::{DriveGeometry, Twist, WheelSpeeds};
pub use light::LightSignal;
pub use odometry::Pose2;

/// Wraps an angle into (-pi, pi].
pub fn wrap_angle(angle_rad: f32) -> f32 {
    use core::f32::consts::PI;
    let mut a = libm::fmodf(angle_rad, 2.0 * PI);
    if a > PI {
        a -= 2.0 * PI;
    } else if a <= -PI {
        a += 2.0 * PI;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::wrap_angle;
    use core::f32::consts::PI;

    #[test]
    fn wrap_angle_maps_into_half_open_interval() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-5);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-5);
        assert!((wrap_angle(0.5) - 0.5).abs() < 1e-6);
        assert!((wrap_angle(2.0 * PI + 0.25) - 0.25).abs() < 1e-5);
        assert!((wrap_angle(-2.0 * PI - 0.25) + 0.25).abs() < 1e-5);
    }
}
