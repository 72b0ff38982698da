//! 2D pose and dead reckoning: wheel speeds integrated into a pose, heading fused with the
//! gyro. Wheels slip when turning, the gyro does not: so the heading follows the gyro's
//! change (weighted by `gyro_weight`) and the wheels give the translation.

use crate::kinematics::{DriveGeometry, Twist, WheelSpeeds};
use crate::wrap_angle;
use nalgebra::{Rotation2, Vector2};

/// A pose on the field: position (m) and heading (rad, counter-clockwise from +x).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose2 {
    pub x_m: f32,
    pub y_m: f32,
    pub phi_rad: f32,
}

impl Pose2 {
    pub const fn new(x_m: f32, y_m: f32, phi_rad: f32) -> Self {
        Self { x_m, y_m, phi_rad }
    }

    pub fn is_finite(&self) -> bool {
        self.x_m.is_finite() && self.y_m.is_finite() && self.phi_rad.is_finite()
    }

    pub fn distance_to(&self, other: &Pose2) -> f32 {
        libm::hypotf(other.x_m - self.x_m, other.y_m - self.y_m)
    }

    /// Expresses a field point in this pose's robot frame (x forward, y left).
    pub fn to_local(&self, x_m: f32, y_m: f32) -> (f32, f32) {
        let v = Rotation2::new(-self.phi_rad) * Vector2::new(x_m - self.x_m, y_m - self.y_m);
        (v.x, v.y)
    }

    /// Advances the pose by a body twist held for `dt_s`, using the mid-cycle heading for the
    /// translation. `heading_change_rad` replaces `omega * dt` (e.g. from the gyro).
    pub fn advanced(&self, twist: Twist, heading_change_rad: f32, dt_s: f32) -> Pose2 {
        let mid = self.phi_rad + heading_change_rad * 0.5;
        let d = Rotation2::new(mid) * Vector2::new(twist.vx_m_s * dt_s, twist.vy_m_s * dt_s);
        Pose2::new(
            self.x_m + d.x,
            self.y_m + d.y,
            wrap_angle(self.phi_rad + heading_change_rad),
        )
    }
}

/// Integrates wheel speeds and gyro angles into a pose.
#[derive(Debug, Clone, Copy)]
pub struct OdometryIntegrator {
    geometry: DriveGeometry,
    /// 1.0: heading from the gyro alone; 0.0: from the wheels alone.
    gyro_weight: f32,
    pose: Pose2,
    last_gyro_rad: Option<f32>,
}

impl OdometryIntegrator {
    pub fn new(geometry: DriveGeometry, gyro_weight: f32, start: Pose2) -> Self {
        Self {
            geometry,
            gyro_weight: gyro_weight.clamp(0.0, 1.0),
            pose: start,
            last_gyro_rad: None,
        }
    }

    pub fn pose(&self) -> Pose2 {
        self.pose
    }

    /// Resets the pose (e.g. after localisation); the next gyro sample re-anchors.
    pub fn reset(&mut self, pose: Pose2) {
        self.pose = pose;
        self.last_gyro_rad = None;
    }

    /// One integration step: the measured wheel speeds held for `dt_s`, and the gyro's
    /// absolute angle at the end of the step if a fresh one is available. Non-finite input
    /// is ignored rather than poisoning the pose.
    pub fn update(&mut self, wheels: WheelSpeeds, gyro_angle_rad: Option<f32>, dt_s: f32) -> Pose2 {
        if !dt_s.is_finite() || dt_s <= 0.0 {
            return self.pose;
        }
        let twist = self.geometry.forward(wheels);
        if !twist.is_finite() {
            return self.pose;
        }
        let wheel_turn = twist.omega_rad_s * dt_s;
        let gyro = gyro_angle_rad.filter(|g| g.is_finite());
        let turn = match (gyro, self.last_gyro_rad) {
            (Some(now), Some(before)) => {
                let gyro_turn = wrap_angle(now - before);
                self.gyro_weight * gyro_turn + (1.0 - self.gyro_weight) * wheel_turn
            }
            _ => wheel_turn,
        };
        if gyro.is_some() {
            self.last_gyro_rad = gyro;
        }
        self.pose = self.pose.advanced(twist, turn, dt_s);
        self.pose
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::PI;

    const G: DriveGeometry = DriveGeometry::ROBOTINO2;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn straight_line_from_wheels() {
        let mut odo = OdometryIntegrator::new(G, 1.0, Pose2::new(1.0, 1.0, PI / 2.0));
        let wheels = G.inverse(Twist::new(0.2, 0.0, 0.0));
        for _ in 0..15 {
            odo.update(wheels, None, 1.0 / 15.0);
        }
        // Facing +y at 0.2 m/s for one second.
        let p = odo.pose();
        assert!(close(p.x_m, 1.0, 1e-4) && close(p.y_m, 1.2, 1e-4), "{p:?}");
    }

    #[test]
    fn heading_follows_gyro_not_slipping_wheels() {
        // The wheels claim a rotation, the gyro says the robot did not turn.
        let mut odo = OdometryIntegrator::new(G, 1.0, Pose2::default());
        let wheels = G.inverse(Twist::new(0.0, 0.0, 1.0));
        odo.update(wheels, Some(0.3), 0.1);
        for _ in 0..10 {
            odo.update(wheels, Some(0.3), 0.1);
        }
        // The first sample only anchors the gyro (wheels give 0.1 rad), then no change.
        assert!(close(odo.pose().phi_rad, 0.1, 1e-4), "{:?}", odo.pose());
    }

    #[test]
    fn gyro_weight_blends() {
        let mut odo = OdometryIntegrator::new(G, 0.5, Pose2::default());
        let wheels = G.inverse(Twist::new(0.0, 0.0, 1.0));
        odo.update(WheelSpeeds::ZERO, Some(0.0), 0.1);
        odo.update(wheels, Some(0.2), 0.1);
        // Half of the gyro's 0.2 plus half of the wheels' 0.1.
        assert!(close(odo.pose().phi_rad, 0.15, 1e-4), "{:?}", odo.pose());
    }

    #[test]
    fn gyro_wraparound_is_a_small_turn() {
        let mut odo = OdometryIntegrator::new(G, 1.0, Pose2::new(0.0, 0.0, PI - 0.05));
        odo.update(WheelSpeeds::ZERO, Some(PI - 0.05), 0.1);
        odo.update(WheelSpeeds::ZERO, Some(-PI + 0.05), 0.1);
        // +0.1 rad across the +-pi seam, not -2pi + 0.1.
        assert!(
            close(odo.pose().phi_rad, -PI + 0.05, 1e-4),
            "{:?}",
            odo.pose()
        );
    }

    #[test]
    fn quarter_circle_arc() {
        // Forward 0.5 m/s while turning pi/2 rad/s for 1 s: an arc of radius 1/pi,
        // ending at (r, r) facing +y.
        let mut odo = OdometryIntegrator::new(G, 0.0, Pose2::default());
        let wheels = G.inverse(Twist::new(0.5, 0.0, PI / 2.0));
        for _ in 0..1000 {
            odo.update(wheels, None, 0.001);
        }
        let r = 0.5 / (PI / 2.0);
        let p = odo.pose();
        assert!(close(p.x_m, r, 1e-3) && close(p.y_m, r, 1e-3), "{p:?}");
        assert!(close(p.phi_rad, PI / 2.0, 1e-3), "{p:?}");
    }

    #[test]
    fn bad_input_leaves_pose_alone() {
        let mut odo = OdometryIntegrator::new(G, 1.0, Pose2::new(2.0, 3.0, 0.5));
        odo.update(
            WheelSpeeds {
                rpm: [f32::NAN, 0.0, 0.0],
            },
            None,
            0.1,
        );
        odo.update(WheelSpeeds::ZERO, None, -1.0);
        assert_eq!(odo.pose(), Pose2::new(2.0, 3.0, 0.5));
    }

    #[test]
    fn to_local_frame() {
        let p = Pose2::new(1.0, 1.0, PI / 2.0);
        let (x, y) = p.to_local(1.0, 2.0);
        assert!(close(x, 1.0, 1e-5) && close(y, 0.0, 1e-5));
        let (x, y) = p.to_local(0.0, 1.0);
        assert!(close(x, 0.0, 1e-5) && close(y, 1.0, 1e-5));
    }
}
