//! The three-wheel omni drive: body twist <-> motor speeds.
//!
//! Inverse kinematics (REC OpenRobotino API), with k = 60 * gear / (2 * pi * rw):
//!
//! ```text
//! m1 = k * (-cos30 * vx + 0.5 * vy + rb * omega)
//! m2 = k * (            - 1.0 * vy + rb * omega)
//! m3 = k * ( cos30 * vx + 0.5 * vy + rb * omega)
//! ```
//!
//! The forward transform is the matrix inverse, which has a closed form: the wheels' sum
//! isolates omega, m3 - m1 isolates vx, and m1 + m3 - 2 m2 isolates vy.

use core::f32::consts::PI;
use nalgebra::{Matrix3, Vector3};

/// cos(30 deg): the vendor's headers round it to 0.866.
const COS_30: f32 = 0.866_025_4;

/// A body velocity: forward `vx`, leftward `vy` (m/s), counter-clockwise `omega` (rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Twist {
    pub vx_m_s: f32,
    pub vy_m_s: f32,
    pub omega_rad_s: f32,
}

impl Twist {
    pub const ZERO: Twist = Twist {
        vx_m_s: 0.0,
        vy_m_s: 0.0,
        omega_rad_s: 0.0,
    };

    pub const fn new(vx_m_s: f32, vy_m_s: f32, omega_rad_s: f32) -> Self {
        Self {
            vx_m_s,
            vy_m_s,
            omega_rad_s,
        }
    }

    pub fn is_finite(&self) -> bool {
        self.vx_m_s.is_finite() && self.vy_m_s.is_finite() && self.omega_rad_s.is_finite()
    }

    pub fn linear_speed_m_s(&self) -> f32 {
        libm::hypotf(self.vx_m_s, self.vy_m_s)
    }

    fn to_vector(self) -> Vector3<f32> {
        Vector3::new(self.vx_m_s, self.vy_m_s, self.omega_rad_s)
    }

    fn from_vector(v: Vector3<f32>) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

/// Motor speeds of the three wheels in rpm (motor side, before the gear).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelSpeeds {
    pub rpm: [f32; 3],
}

impl WheelSpeeds {
    pub const ZERO: WheelSpeeds = WheelSpeeds { rpm: [0.0; 3] };

    pub fn is_zero(&self) -> bool {
        self.rpm.iter().all(|&r| r == 0.0)
    }

    pub fn max_abs_rpm(&self) -> f32 {
        self.rpm.iter().fold(0.0, |m, r| m.max(r.abs()))
    }
}

/// The drive's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveGeometry {
    /// Wheel radius.
    pub wheel_radius_m: f32,
    /// Gear ratio motor : wheel.
    pub gear: f32,
    /// Distance from the robot's centre to each wheel.
    pub centre_to_wheel_m: f32,
}

impl DriveGeometry {
    /// Robotino 2 with the OpenRobotino API2 default rb = 0.132 m.
    pub const ROBOTINO2: DriveGeometry = DriveGeometry {
        wheel_radius_m: 0.040,
        gear: 16.0,
        centre_to_wheel_m: 0.132,
    };
    /// Robotino 2 with the API1 value rb = 0.125 m.
    pub const ROBOTINO2_API1: DriveGeometry = DriveGeometry {
        wheel_radius_m: 0.040,
        gear: 16.0,
        centre_to_wheel_m: 0.125,
    };
    /// Robotino 3.
    pub const ROBOTINO3: DriveGeometry = DriveGeometry {
        wheel_radius_m: 0.060,
        gear: 32.0,
        centre_to_wheel_m: 0.175,
    };

    /// Motor rpm per m/s of wheel rim speed: k = 60 * gear / (2 * pi * rw).
    pub fn rpm_per_m_s(&self) -> f32 {
        60.0 * self.gear / (2.0 * PI * self.wheel_radius_m)
    }

    /// True when the constants are positive and finite, so both transforms are defined.
    pub fn is_valid(&self) -> bool {
        [self.wheel_radius_m, self.gear, self.centre_to_wheel_m]
            .iter()
            .all(|v| v.is_finite() && *v > 0.0)
    }

    /// The matrix M with `rpm = M * (vx, vy, omega)`.
    pub fn inverse_matrix(&self) -> Matrix3<f32> {
        let rb = self.centre_to_wheel_m;
        #[rustfmt::skip]
        let m = Matrix3::new(
            -COS_30,  0.5, rb,
             0.0,    -1.0, rb,
             COS_30,  0.5, rb,
        );
        m * self.rpm_per_m_s()
    }

    /// The matrix with `(vx, vy, omega) = F * rpm`, the closed-form inverse of
    /// [`Self::inverse_matrix`].
    pub fn forward_matrix(&self) -> Matrix3<f32> {
        let k = self.rpm_per_m_s();
        let rb = self.centre_to_wheel_m;
        let a = 1.0 / (2.0 * COS_30);
        let b = 1.0 / 3.0;
        let c = 1.0 / (3.0 * rb);
        #[rustfmt::skip]
        let f = Matrix3::new(
            -a,   0.0,      a,
             b,  -2.0 * b,  b,
             c,   c,        c,
        );
        f / k
    }

    /// Body twist -> motor speeds.
    pub fn inverse(&self, twist: Twist) -> WheelSpeeds {
        let m = self.inverse_matrix() * twist.to_vector();
        WheelSpeeds {
            rpm: [m.x, m.y, m.z],
        }
    }

    /// Motor speeds -> body twist.
    pub fn forward(&self, wheels: WheelSpeeds) -> Twist {
        let [m1, m2, m3] = wheels.rpm;
        Twist::from_vector(self.forward_matrix() * Vector3::new(m1, m2, m3))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn robotino2_k_is_about_3820() {
        // 60 * 16 / (2 * pi * 0.04) = 960 / 0.251327 = 3819.72
        assert!(close(DriveGeometry::ROBOTINO2.rpm_per_m_s(), 3819.72, 0.01));
        // Robotino 3: 60 * 32 / (2 * pi * 0.06) = 1920 / 0.376991 = 5092.96
        assert!(close(DriveGeometry::ROBOTINO3.rpm_per_m_s(), 5092.96, 0.01));
    }

    #[test]
    fn forward_motion_by_hand() {
        // vx = 0.1 m/s: m1 = -k * 0.0866025 = -330.80, m2 = 0, m3 = +330.80.
        let w = DriveGeometry::ROBOTINO2.inverse(Twist::new(0.1, 0.0, 0.0));
        assert!(close(w.rpm[0], -330.80, 0.02), "{w:?}");
        assert!(close(w.rpm[1], 0.0, 1e-3), "{w:?}");
        assert!(close(w.rpm[2], 330.80, 0.02), "{w:?}");
    }

    #[test]
    fn sideways_motion_by_hand() {
        // vy = 0.2 m/s: m1 = m3 = k * 0.1 = 381.97, m2 = -k * 0.2 = -763.94.
        let w = DriveGeometry::ROBOTINO2.inverse(Twist::new(0.0, 0.2, 0.0));
        assert!(close(w.rpm[0], 381.97, 0.02), "{w:?}");
        assert!(close(w.rpm[1], -763.94, 0.03), "{w:?}");
        assert!(close(w.rpm[2], 381.97, 0.02), "{w:?}");
    }

    #[test]
    fn rotation_by_hand_depends_on_rb() {
        // omega = 1 rad/s: every motor k * rb; API2 3819.72 * 0.132 = 504.20,
        // API1 3819.72 * 0.125 = 477.47.
        let w2 = DriveGeometry::ROBOTINO2.inverse(Twist::new(0.0, 0.0, 1.0));
        let w1 = DriveGeometry::ROBOTINO2_API1.inverse(Twist::new(0.0, 0.0, 1.0));
        for r in w2.rpm {
            assert!(close(r, 504.20, 0.02), "{w2:?}");
        }
        for r in w1.rpm {
            assert!(close(r, 477.47, 0.02), "{w1:?}");
        }
    }

    #[test]
    fn mixed_twist_by_hand() {
        // vx 0.3, vy -0.1, omega 0.5 on Robotino 3 (k 5092.96, rb 0.175):
        // m1 = k * (-0.259808 - 0.05 + 0.0875) = k * -0.222308 = -1132.19
        // m2 = k * (0.1 + 0.0875) = k * 0.1875 = 954.93
        // m3 = k * (0.259808 - 0.05 + 0.0875) = k * 0.297308 = 1514.16
        let w = DriveGeometry::ROBOTINO3.inverse(Twist::new(0.3, -0.1, 0.5));
        assert!(close(w.rpm[0], -1132.19, 0.05), "{w:?}");
        assert!(close(w.rpm[1], 954.93, 0.05), "{w:?}");
        assert!(close(w.rpm[2], 1514.16, 0.05), "{w:?}");
    }

    #[test]
    fn forward_by_hand() {
        // All motors equal at k * rb rpm is a pure rotation of 1 rad/s.
        let g = DriveGeometry::ROBOTINO2;
        let r = g.rpm_per_m_s() * g.centre_to_wheel_m;
        let t = g.forward(WheelSpeeds { rpm: [r, r, r] });
        assert!(
            close(t.vx_m_s, 0.0, 1e-5) && close(t.vy_m_s, 0.0, 1e-5),
            "{t:?}"
        );
        assert!(close(t.omega_rad_s, 1.0, 1e-5), "{t:?}");
    }

    #[test]
    fn forward_matrix_is_the_inverse() {
        for g in [
            DriveGeometry::ROBOTINO2,
            DriveGeometry::ROBOTINO2_API1,
            DriveGeometry::ROBOTINO3,
        ] {
            let id = g.forward_matrix() * g.inverse_matrix();
            for r in 0..3 {
                for c in 0..3 {
                    let want = if r == c { 1.0 } else { 0.0 };
                    assert!(close(id[(r, c)], want, 1e-5), "{g:?} {id}");
                }
            }
        }
    }

    /// Property: forward(inverse(t)) == t over a deterministic pseudo-random sample of twists
    /// (a small LCG keeps the test dependency-free and identical on x86_64 and i586).
    #[test]
    fn inverse_then_forward_is_identity() {
        let mut state: u32 = 0x1234_5678;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        for g in [DriveGeometry::ROBOTINO2, DriveGeometry::ROBOTINO3] {
            for _ in 0..2000 {
                let t = Twist::new(next() * 2.0, next() * 2.0, next() * 4.0);
                let back = g.forward(g.inverse(t));
                assert!(close(back.vx_m_s, t.vx_m_s, 1e-4), "{t:?} -> {back:?}");
                assert!(close(back.vy_m_s, t.vy_m_s, 1e-4), "{t:?} -> {back:?}");
                assert!(
                    close(back.omega_rad_s, t.omega_rad_s, 1e-4),
                    "{t:?} -> {back:?}"
                );
            }
        }
    }

    #[test]
    fn geometry_validity() {
        assert!(DriveGeometry::ROBOTINO2.is_valid());
        let bad = DriveGeometry {
            wheel_radius_m: 0.0,
            ..DriveGeometry::ROBOTINO2
        };
        assert!(!bad.is_valid());
        let nan = DriveGeometry {
            gear: f32::NAN,
            ..DriveGeometry::ROBOTINO2
        };
        assert!(!nan.is_valid());
    }
}
