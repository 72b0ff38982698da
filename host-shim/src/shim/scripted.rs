//! STAND-IN for the engine: chooses the next skill while the CLIPS agent is not yet wired in.
//! `robotino-agent run` asks it whenever the robot is idle; the engine will replace it by
//! running the rules to quiescence and reading the skill they chose.

use hal::field::{GateId, MachineId};
use hal::skill::{SkillOutcome, SkillRequest};

/// Either a fixed list of requests, or a loop that fetches S0 whenever the robot holds
/// nothing and otherwise takes the puck to the next machine in turn.
#[derive(Debug, Clone)]
pub enum ScriptedAgent {
    Fixed {
        requests: Vec<SkillRequest>,
        next: usize,
    },
    RoundRobin {
        next_machine: u8,
    },
}

/// A `--script` entry that could not be parsed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScriptError(pub String);

impl std::fmt::Display for ScriptError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "bad script entry `{}` (use get_s0, bring:N, deliver:G)",
            self.0
        )
    }
}

impl std::error::Error for ScriptError {}

impl ScriptedAgent {
    /// Parses `get_s0,bring:4,deliver:1`; an empty text gives the round-robin loop.
    pub fn parse(text: &str) -> Result<Self, ScriptError> {
        if text.trim().is_empty() {
            return Ok(Self::RoundRobin { next_machine: 1 });
        }
        let requests = text
            .split(',')
            .map(|item| {
                let item = item.trim();
                let bad = || ScriptError(item.to_string());
                let number = |s: &str| s.parse::<u8>().map_err(|_| bad());
                match item.split_once(':') {
                    None if item == "get_s0" => Ok(SkillRequest::GetS0),
                    Some(("bring", n)) => MachineId::new(number(n)?)
                        .map(SkillRequest::BringPuckTo)
                        .ok_or_else(bad),
                    Some(("deliver", g)) => GateId::new(number(g)?)
                        .map(SkillRequest::DeliverTo)
                        .ok_or_else(bad),
                    _ => Err(bad()),
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::Fixed { requests, next: 0 })
    }

    /// The next skill for an idle robot, or `None` when the script is done.
    pub fn next(&mut self, has_puck: bool) -> Option<SkillRequest> {
        match self {
            Self::Fixed { requests, next } => {
                let r = requests.get(*next).copied();
                *next += 1;
                r
            }
            Self::RoundRobin { next_machine } => {
                if !has_puck {
                    return Some(SkillRequest::GetS0);
                }
                let m = MachineId::new(*next_machine)?;
                *next_machine = *next_machine % 10 + 1;
                Some(SkillRequest::BringPuckTo(m))
            }
        }
    }

    /// Told every skill's end (the engine will assert facts here).
    pub fn finished(&mut self, _request: SkillRequest, _outcome: SkillOutcome) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_fixed_scripts() {
        let mut a =
            ScriptedAgent::parse("get_s0, bring:4,deliver:1").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.next(false), Some(SkillRequest::GetS0));
        assert_eq!(
            a.next(true),
            MachineId::new(4).map(SkillRequest::BringPuckTo)
        );
        assert_eq!(a.next(true), GateId::new(1).map(SkillRequest::DeliverTo));
        assert_eq!(a.next(true), None);
        assert!(ScriptedAgent::parse("bring:11").is_err());
        assert!(ScriptedAgent::parse("fly").is_err());
    }

    #[test]
    fn round_robin_fetches_then_visits_machines_in_turn() {
        let mut a = ScriptedAgent::parse("").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.next(false), Some(SkillRequest::GetS0));
        assert_eq!(
            a.next(true),
            MachineId::new(1).map(SkillRequest::BringPuckTo)
        );
        assert_eq!(
            a.next(true),
            MachineId::new(2).map(SkillRequest::BringPuckTo)
        );
    }
}
