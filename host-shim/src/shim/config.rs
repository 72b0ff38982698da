//! The robot's configuration file (TOML). Every field has a Robotino 2 default, so an empty
//! file, or none at all, is a valid configuration.

use hal::limits::MotionLimits;
use hal::DriveGeometry;
use serde::Deserialize;
use std::fmt;
use std::path::{Path, PathBuf};

/// The whole configuration.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    pub robot: RobotConfig,
    pub limits: LimitsConfig,
    pub timing: TimingConfig,
    pub noise: NoiseConfig,
    pub services: ServicesConfig,
}

/// Drive geometry: wheel radius, gear, centre-to-wheel distance.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobotConfig {
    /// 1..=3: which robot of the team this is.
    pub number: u8,
    pub wheel_radius_m: f32,
    pub gear: f32,
    /// 0.132 (API2 default) or 0.125 (API1) on a Robotino 2.
    pub centre_to_wheel_m: f32,
    /// Footprint radius used for collisions.
    pub radius_m: f32,
    /// Weight of the gyro in the heading (1 = gyro only).
    pub gyro_weight: f32,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LimitsConfig {
    pub max_linear_m_s: f32,
    pub max_angular_rad_s: f32,
    pub max_linear_acc_m_s2: f32,
    pub max_angular_acc_rad_s2: f32,
    pub max_motor_rpm: f32,
}

/// Cycle rate, deadlines and how simulated time relates to wall-clock time.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TimingConfig {
    /// Behaviour-layer and driver cycle rate.
    pub cycle_hz: f32,
    /// Cycles without a fresh sample before a driver counts as silent.
    pub sensor_deadline_cycles: u32,
    /// Cycles without a fresh motor command before the drive stops (dead-man).
    pub motor_deadline_cycles: u32,
    /// Cycles a skill may run before it is FAILED with a timeout.
    pub skill_timeout_cycles: u32,
    /// Simulated seconds per wall-clock second (1 = real time).
    pub time_warp: f32,
    /// Lockstep: the sim advances one cycle once every live robot's agent answered the
    /// cycle's sensor frame with its motor command; nothing else decides when, so the same
    /// seed plays the same game.
    pub lockstep: bool,
    /// Wall-clock time without a heartbeat after which an agent process counts as dead
    /// (lockstep no longer waits for it; its wheels stop by the dead-man rule). Agents
    /// send heartbeats from a thread of their own every `heartbeat_period_ms`, so a slow
    /// cycle never looks like a death.
    pub heartbeat_timeout_ms: u64,
    pub heartbeat_period_ms: u64,
    /// How long lockstep waits for an agent's first heartbeat before playing without it.
    pub startup_timeout_ms: u64,
}

/// Sensor noise in the simulation (standard deviations) and the generator's seed.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NoiseConfig {
    pub seed: u64,
    pub ir_m: f32,
    pub gyro_rad: f32,
    /// Relative error of the measured wheel speeds.
    pub wheel_rel: f32,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ServicesConfig {
    /// Every service name starts with this, so tests and robots never collide.
    pub prefix: String,
}

impl Default for RobotConfig {
    fn default() -> Self {
        let g = DriveGeometry::ROBOTINO2;
        Self {
            number: 1,
            wheel_radius_m: g.wheel_radius_m,
            gear: g.gear,
            centre_to_wheel_m: g.centre_to_wheel_m,
            radius_m: 0.185,
            gyro_weight: 1.0,
        }
    }
}

impl Default for LimitsConfig {
    fn default() -> Self {
        let l = MotionLimits::ROBOTINO2;
        Self {
            max_linear_m_s: l.max_linear_m_s,
            max_angular_rad_s: l.max_angular_rad_s,
            max_linear_acc_m_s2: l.max_linear_acc_m_s2,
            max_angular_acc_rad_s2: l.max_angular_acc_rad_s2,
            max_motor_rpm: l.max_motor_rpm,
        }
    }
}

impl Default for TimingConfig {
    fn default() -> Self {
        Self {
            cycle_hz: 15.0,
            sensor_deadline_cycles: 3,
            motor_deadline_cycles: 3,
            skill_timeout_cycles: 15 * 120,
            time_warp: 1.0,
            lockstep: false,
            heartbeat_timeout_ms: 3000,
            heartbeat_period_ms: 100,
            startup_timeout_ms: 120_000,
        }
    }
}

impl Default for NoiseConfig {
    fn default() -> Self {
        Self {
            seed: 1,
            ir_m: 0.005,
            gyro_rad: 0.002,
            wheel_rel: 0.01,
        }
    }
}

impl Default for ServicesConfig {
    fn default() -> Self {
        Self {
            prefix: "robotino".to_string(),
        }
    }
}

/// A configuration that could not be used, with the file it came from.
#[derive(Debug)]
pub enum ConfigError {
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    Parse {
        path: PathBuf,
        source: toml::de::Error,
    },
    Invalid {
        what: &'static str,
    },
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { path, source } => write!(f, "cannot read {}: {source}", path.display()),
            Self::Parse { path, source } => write!(f, "cannot parse {}: {source}", path.display()),
            Self::Invalid { what } => write!(f, "invalid configuration: {what}"),
        }
    }
}

impl std::error::Error for ConfigError {}

impl Config {
    /// Parses TOML text and validates it.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self, ConfigError> {
        let config: Config = toml::from_str(text).map_err(|source| ConfigError::Parse {
            path: origin.to_path_buf(),
            source,
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Reads a file; `None` gives the defaults.
    pub fn load(path: Option<&Path>) -> Result<Self, ConfigError> {
        match path {
            None => Ok(Self::default()),
            Some(p) => {
                let text = std::fs::read_to_string(p).map_err(|source| ConfigError::Read {
                    path: p.to_path_buf(),
                    source,
                })?;
                Self::from_toml(&text, p)
            }
        }
    }

    pub fn geometry(&self) -> DriveGeometry {
        DriveGeometry {
            wheel_radius_m: self.robot.wheel_radius_m,
            gear: self.robot.gear,
            centre_to_wheel_m: self.robot.centre_to_wheel_m,
        }
    }

    pub fn limits(&self) -> MotionLimits {
        MotionLimits {
            max_linear_m_s: self.limits.max_linear_m_s,
            max_angular_rad_s: self.limits.max_angular_rad_s,
            max_linear_acc_m_s2: self.limits.max_linear_acc_m_s2,
            max_angular_acc_rad_s2: self.limits.max_angular_acc_rad_s2,
            max_motor_rpm: self.limits.max_motor_rpm,
        }
    }

    /// Simulated seconds per cycle.
    pub fn cycle_s(&self) -> f32 {
        1.0 / self.timing.cycle_hz
    }

    /// Wall-clock time per cycle after the time warp.
    pub fn wall_cycle(&self) -> std::time::Duration {
        std::time::Duration::from_secs_f64(
            1.0 / (f64::from(self.timing.cycle_hz) * f64::from(self.timing.time_warp)),
        )
    }

    fn validate(&self) -> Result<(), ConfigError> {
        let invalid = |what| Err(ConfigError::Invalid { what });
        if !self.geometry().is_valid() {
            return invalid("wheel radius, gear and centre-to-wheel must be positive");
        }
        if !self.limits().is_valid() {
            return invalid("limits must be positive");
        }
        let t = &self.timing;
        if !(t.cycle_hz.is_finite() && t.cycle_hz > 0.0 && t.cycle_hz <= 1000.0) {
            return invalid("cycle_hz must lie in (0, 1000]");
        }
        if !(t.time_warp.is_finite() && t.time_warp > 0.0) {
            return invalid("time_warp must be positive");
        }
        if t.sensor_deadline_cycles == 0 || t.motor_deadline_cycles == 0 {
            return invalid("deadlines must be at least one cycle");
        }
        if !(1..=super::payloads::MAX_ROBOTS).contains(&self.robot.number) {
            return invalid("robot.number must be 1..=3");
        }
        let n = &self.noise;
        if [n.ir_m, n.gyro_rad, n.wheel_rel]
            .iter()
            .any(|v| !v.is_finite() || *v < 0.0)
        {
            return invalid("noise must be finite and not negative");
        }
        let p = &self.services.prefix;
        if p.is_empty()
            || !p
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_/".contains(c))
        {
            return invalid("services.prefix: letters, digits, '-', '_', '/' only");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_file_gives_robotino2_defaults() {
        let c = Config::from_toml("", Path::new("x.toml")).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(c, Config::default());
        assert_eq!(c.geometry(), DriveGeometry::ROBOTINO2);
        assert_eq!(c.timing.sensor_deadline_cycles, 3);
        assert_eq!(c.timing.cycle_hz, 15.0);
    }

    #[test]
    fn partial_file_overrides_fields() {
        let text = "[robot]\ncentre_to_wheel_m = 0.125\n[timing]\ntime_warp = 20.0\nlockstep = true\n[services]\nprefix = \"test/abc\"\n";
        let c = Config::from_toml(text, Path::new("x.toml")).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(c.geometry(), DriveGeometry::ROBOTINO2_API1);
        assert!(c.timing.lockstep);
        assert_eq!(c.services.prefix, "test/abc");
        assert_eq!(c.robot.gear, 16.0);
    }

    #[test]
    fn rejects_bad_values_and_unknown_keys() {
        for text in [
            "[robot]\nwheel_radius_m = 0.0\n",
            "[timing]\ncycle_hz = -1.0\n",
            "[timing]\nsensor_deadline_cycles = 0\n",
            "[services]\nprefix = \"a b\"\n",
            "[robot]\nnumber = 4\n",
            "[noise]\nir_m = -0.1\n",
        ] {
            assert!(
                matches!(
                    Config::from_toml(text, Path::new("x.toml")),
                    Err(ConfigError::Invalid { .. })
                ),
                "{text}"
            );
        }
        assert!(matches!(
            Config::from_toml("[robot]\nwheels = 4\n", Path::new("x.toml")),
            Err(ConfigError::Parse { .. })
        ));
    }

    #[test]
    fn shipped_config_file_parses() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("robotino.toml");
        let c = Config::load(Some(&path)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(c.geometry(), DriveGeometry::ROBOTINO2);
    }
}
