//! The contract between the agent (which chooses what to do) and the behaviour layer (which
//! drives the robot): requests, outcomes and the perceptions an outcome carries. Matches the
//! 2012 Carologistics skills: `get_s0`, `finish_puck_at(machine)`, and delivery to a gate.

use crate::field::{GateId, MachineId, RecyclingId};
use crate::light::LightSignal;

/// What the agent asks the behaviour layer to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkillRequest {
    /// Drive to the input storage, fetch a raw S0 puck, leave.
    GetS0,
    /// Bring the held puck to a machine, put it under the light and read the light.
    BringPuckTo(MachineId),
    /// Deliver the held puck (a product P) to a delivery gate.
    DeliverTo(GateId),
    /// Release the held puck where the robot stands and back away from it: the agent's
    /// `discard`, and how the behaviour layer gets rid of a puck the agent believes lost.
    Discard,
    /// Drive to a machine with empty hands and take a junk puck lying there (the consumed
    /// inputs of a production, 2012 recycling).
    GetJunk(MachineId),
    /// Bring the held junk to a recycling unit and take the raw puck it turns it into.
    Recycle(RecyclingId),
    /// Bring the held puck to a machine as its last input and, once the machine works on
    /// it, leave it there (its output stays at the machine until collected) instead of
    /// waiting for the light to turn green.
    FeedTo(MachineId),
    /// Drive to a machine with empty hands, wait for its light to turn green and take the
    /// output lying there.
    Collect(MachineId),
}

impl SkillRequest {
    /// The 2012 skill name.
    pub const fn name(&self) -> &'static str {
        match self {
            Self::GetS0 => "get_s0",
            Self::BringPuckTo(_) => "finish_puck_at",
            Self::DeliverTo(_) => "deliver",
            Self::Discard => "discard",
            Self::GetJunk(_) => "get_junk",
            Self::Recycle(_) => "recycle",
            Self::FeedTo(_) => "feed",
            Self::Collect(_) => "collect",
        }
    }
}

/// What a skill saw when it ended well; the agent turns these into facts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Perception {
    /// The robot now holds a raw S0 puck.
    GotS0,
    /// The machine's light after the puck was placed.
    LightSeen(LightSignal),
    /// The light did not change while the robot waited.
    LightUnchanged,
    /// The puck was delivered through the gate.
    Delivered,
    /// The robot released its puck and no longer holds one.
    Released,
    /// The robot took a junk puck at a machine.
    GotJunk,
    /// The recycling unit took the junk and handed a raw S0 back.
    Recycled,
    /// The machine took the puck and works on it; the robot left it there (`FeedTo`).
    LeftProcessing,
    /// The robot took the output lying at a machine (`Collect`).
    GotOutput,
}

/// Why a skill failed. Codes are stable for payloads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
#[repr(u8)]
pub enum FailReason {
    /// The bumper touched something.
    Bumper = 1,
    /// A sensor driver fell silent past its deadline.
    SensorTimeout = 2,
    /// The skill reported nothing within its time budget.
    SkillTimeout = 3,
    /// The puck left the gripper area and could not be re-grabbed.
    PuckLost = 4,
    /// The robot could not reach its goal.
    DriveFailed = 5,
    /// The request made no sense in the current state (e.g. bring a puck while holding none).
    InvalidRequest = 6,
    /// The agent cancelled the skill.
    Aborted = 7,
    /// The input storage had no puck to give.
    StorageEmpty = 8,
    /// No junk lay at the machine.
    NoJunk = 9,
    /// No output turned up at the machine (`Collect`).
    NoOutput = 10,
}

impl FailReason {
    pub const fn code(self) -> u8 {
        self as u8
    }

    pub const fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            1 => Self::Bumper,
            2 => Self::SensorTimeout,
            3 => Self::SkillTimeout,
            4 => Self::PuckLost,
            5 => Self::DriveFailed,
            6 => Self::InvalidRequest,
            7 => Self::Aborted,
            8 => Self::StorageEmpty,
            9 => Self::NoJunk,
            10 => Self::NoOutput,
            _ => return None,
        })
    }

    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Bumper => "bumper",
            Self::SensorTimeout => "sensor-timeout",
            Self::SkillTimeout => "skill-timeout",
            Self::PuckLost => "puck-lost",
            Self::DriveFailed => "drive-failed",
            Self::InvalidRequest => "invalid-request",
            Self::Aborted => "aborted",
            Self::StorageEmpty => "storage-empty",
            Self::NoJunk => "no-junk",
            Self::NoOutput => "no-output",
        }
    }
}

/// A skill's state as reported each cycle. Every skill ends FINAL or FAILED.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SkillOutcome {
    Running,
    Final(Perception),
    Failed(FailReason),
}

impl SkillOutcome {
    pub const fn is_terminal(&self) -> bool {
        !matches!(self, Self::Running)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fail_reason_codes_round_trip() {
        for code in 0..=255u8 {
            if let Some(r) = FailReason::from_code(code) {
                assert_eq!(r.code(), code);
            }
        }
        assert_eq!(FailReason::from_code(0), None);
        assert_eq!(FailReason::from_code(2), Some(FailReason::SensorTimeout));
    }

    #[test]
    fn names_match_the_2012_skills() {
        assert_eq!(SkillRequest::GetS0.name(), "get_s0");
        let m = MachineId::new(3).map(SkillRequest::BringPuckTo);
        assert_eq!(m.map(|r| r.name()), Some("finish_puck_at"));
        assert!(!SkillOutcome::Running.is_terminal());
        assert!(SkillOutcome::Failed(FailReason::Bumper).is_terminal());
    }
}
