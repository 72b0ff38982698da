//! Speed and acceleration limits. Every motor command passes through [`MotionLimits::clamp`].

use crate::kinematics::{DriveGeometry, Twist, WheelSpeeds};

/// The limits a command must respect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionLimits {
    /// Largest linear speed (magnitude of vx, vy).
    pub max_linear_m_s: f32,
    /// Largest rotation speed.
    pub max_angular_rad_s: f32,
    /// Largest change of linear velocity per second.
    pub max_linear_acc_m_s2: f32,
    /// Largest change of rotation speed per second.
    pub max_angular_acc_rad_s2: f32,
    /// Largest motor speed.
    pub max_motor_rpm: f32,
}

impl MotionLimits {
    /// What the 2012 team drove at (0.5 m/s, 0.78 rad/s); Robotino 2 motors reach about
    /// 3000 rpm.
    pub const ROBOTINO2: MotionLimits = MotionLimits {
        max_linear_m_s: 0.5,
        max_angular_rad_s: 0.78,
        max_linear_acc_m_s2: 1.0,
        max_angular_acc_rad_s2: 2.0,
        max_motor_rpm: 3000.0,
    };

    /// True when all limits are positive and finite.
    pub fn is_valid(&self) -> bool {
        [
            self.max_linear_m_s,
            self.max_angular_rad_s,
            self.max_linear_acc_m_s2,
            self.max_angular_acc_rad_s2,
            self.max_motor_rpm,
        ]
        .iter()
        .all(|v| v.is_finite() && *v > 0.0)
    }

    /// Clamps a speed: the linear part is scaled down keeping its direction, omega is clipped.
    /// A twist with any non-finite component becomes zero: better stop than guess.
    pub fn clamp_speed(&self, desired: Twist) -> Twist {
        if !desired.is_finite() {
            return Twist::ZERO;
        }
        let speed = desired.linear_speed_m_s();
        let scale = if speed > self.max_linear_m_s {
            self.max_linear_m_s / speed
        } else {
            1.0
        };
        Twist::new(
            desired.vx_m_s * scale,
            desired.vy_m_s * scale,
            desired
                .omega_rad_s
                .clamp(-self.max_angular_rad_s, self.max_angular_rad_s),
        )
    }

    /// Limits the change from `previous` to `desired` over `dt_s` to the accelerations.
    pub fn clamp_acceleration(&self, previous: Twist, desired: Twist, dt_s: f32) -> Twist {
        if !desired.is_finite() || !previous.is_finite() || !dt_s.is_finite() || dt_s <= 0.0 {
            return Twist::ZERO;
        }
        let dvx = desired.vx_m_s - previous.vx_m_s;
        let dvy = desired.vy_m_s - previous.vy_m_s;
        let dv = libm::hypotf(dvx, dvy);
        let max_dv = self.max_linear_acc_m_s2 * dt_s;
        let scale = if dv > max_dv { max_dv / dv } else { 1.0 };
        let max_dw = self.max_angular_acc_rad_s2 * dt_s;
        let dw = (desired.omega_rad_s - previous.omega_rad_s).clamp(-max_dw, max_dw);
        Twist::new(
            previous.vx_m_s + dvx * scale,
            previous.vy_m_s + dvy * scale,
            previous.omega_rad_s + dw,
        )
    }

    /// Speed limits, then acceleration limits relative to the previous command. Stopping is
    /// exempt from the acceleration limit: a zero request always yields zero.
    pub fn clamp(&self, previous: Twist, desired: Twist, dt_s: f32) -> Twist {
        let speed_limited = self.clamp_speed(desired);
        if speed_limited == Twist::ZERO {
            return Twist::ZERO;
        }
        self.clamp_speed(self.clamp_acceleration(previous, speed_limited, dt_s))
    }

    /// Scales motor speeds down together so none exceeds `max_motor_rpm` (which keeps the
    /// direction of motion); non-finite speeds become zero.
    pub fn clamp_wheels(&self, wheels: WheelSpeeds) -> WheelSpeeds {
        if wheels.rpm.iter().any(|r| !r.is_finite()) {
            return WheelSpeeds::ZERO;
        }
        let peak = wheels.max_abs_rpm();
        if peak <= self.max_motor_rpm {
            return wheels;
        }
        let s = self.max_motor_rpm / peak;
        WheelSpeeds {
            rpm: wheels.rpm.map(|r| r * s),
        }
    }

    /// The full path from a desired twist to motor speeds within every limit.
    pub fn command(
        &self,
        geometry: &DriveGeometry,
        previous: Twist,
        desired: Twist,
        dt_s: f32,
    ) -> (Twist, WheelSpeeds) {
        let twist = self.clamp(previous, desired, dt_s);
        let wheels = self.clamp_wheels(geometry.inverse(twist));
        (geometry.forward(wheels), wheels)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: MotionLimits = MotionLimits::ROBOTINO2;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 1e-5
    }

    #[test]
    fn speed_within_limits_is_unchanged() {
        let t = Twist::new(0.3, -0.2, 0.5);
        assert_eq!(L.clamp_speed(t), t);
    }

    #[test]
    fn linear_speed_scales_keeping_direction() {
        // (0.6, 0.8) has speed 1.0; limit 0.5 -> (0.3, 0.4).
        let t = L.clamp_speed(Twist::new(0.6, 0.8, 0.0));
        assert!(close(t.vx_m_s, 0.3) && close(t.vy_m_s, 0.4), "{t:?}");
    }

    #[test]
    fn omega_is_clipped_both_ways() {
        assert!(close(
            L.clamp_speed(Twist::new(0.0, 0.0, 5.0)).omega_rad_s,
            0.78
        ));
        assert!(close(
            L.clamp_speed(Twist::new(0.0, 0.0, -5.0)).omega_rad_s,
            -0.78
        ));
    }

    #[test]
    fn non_finite_requests_stop() {
        assert_eq!(L.clamp_speed(Twist::new(f32::NAN, 0.0, 0.0)), Twist::ZERO);
        assert_eq!(
            L.clamp(Twist::ZERO, Twist::new(0.1, f32::INFINITY, 0.0), 0.1),
            Twist::ZERO
        );
    }

    #[test]
    fn acceleration_is_limited_per_cycle() {
        // 1 m/s^2 over 1/15 s allows 0.0667 m/s of change.
        let dt = 1.0 / 15.0;
        let t = L.clamp(Twist::ZERO, Twist::new(0.5, 0.0, 0.78), dt);
        assert!(close(t.vx_m_s, dt), "{t:?}");
        assert!(close(t.omega_rad_s, 2.0 * dt), "{t:?}");
        // Ramping up reaches the limit after enough cycles and stays there.
        let mut cmd = Twist::ZERO;
        for _ in 0..30 {
            cmd = L.clamp(cmd, Twist::new(2.0, 0.0, 0.0), dt);
        }
        assert!(close(cmd.vx_m_s, 0.5), "{cmd:?}");
    }

    #[test]
    fn stopping_is_immediate() {
        let moving = Twist::new(0.5, 0.0, 0.5);
        assert_eq!(L.clamp(moving, Twist::ZERO, 1.0 / 15.0), Twist::ZERO);
    }

    #[test]
    fn wheels_scale_together() {
        let w = L.clamp_wheels(WheelSpeeds {
            rpm: [6000.0, -3000.0, 1500.0],
        });
        assert!(close(w.rpm[0], 3000.0) && close(w.rpm[1], -1500.0) && close(w.rpm[2], 750.0));
        let nan = L.clamp_wheels(WheelSpeeds {
            rpm: [f32::NAN, 0.0, 0.0],
        });
        assert!(nan.is_zero());
    }

    #[test]
    fn command_respects_every_limit() {
        let g = DriveGeometry::ROBOTINO2;
        let (t, w) = L.command(
            &g,
            Twist::new(0.5, 0.0, 0.0),
            Twist::new(5.0, 5.0, 5.0),
            1.0,
        );
        assert!(t.linear_speed_m_s() <= L.max_linear_m_s + 1e-4, "{t:?}");
        assert!(t.omega_rad_s.abs() <= L.max_angular_rad_s + 1e-4, "{t:?}");
        assert!(w.max_abs_rpm() <= L.max_motor_rpm + 1e-2, "{w:?}");
    }
}
