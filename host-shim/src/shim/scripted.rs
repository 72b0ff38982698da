//! STAND-IN for the engine: chooses the next skill while the CLIPS agent is not yet wired in.
//! `robotino-agent run` asks it whenever the robot is idle; the engine will replace it by
//! running the rules to quiescence and reading the skill they chose.

use super::team::{Carried, TeamView};
use hal::field::{GateId, MachineId};
use hal::skill::{SkillOutcome, SkillRequest};

/// The chosen skill, and the teammate's finding it relied on, if any: (machine, type,
/// robot that found the type out).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Choice {
    pub request: SkillRequest,
    pub shared_type: Option<(MachineId, u8, u8)>,
}

/// Either a fixed list of requests, or a loop that fetches S0 whenever the robot holds
/// nothing, delivers a P, and otherwise takes the puck to a machine of the type that needs it
/// when the team knows one, else to the next unclaimed machine in turn.
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

    /// The next skill for an idle robot, or `None` when there is nothing to do now.
    pub fn next(&mut self, carried: Option<Carried>, team: &TeamView) -> Option<Choice> {
        let plain = |request| Choice {
            request,
            shared_type: None,
        };
        match self {
            Self::Fixed { requests, next } => {
                let r = requests.get(*next).copied();
                *next += 1;
                r.map(plain)
            }
            Self::RoundRobin { next_machine } => {
                let Some(carried) = carried else {
                    return Some(plain(SkillRequest::GetS0));
                };
                // The type that takes this puck, and the types it is of no use to.
                let (wanted, useless): (Option<u8>, &[u8]) = match carried {
                    Carried::P => return GateId::new(1).map(SkillRequest::DeliverTo).map(plain),
                    Carried::S0 => (Some(1), &[]),
                    Carried::S1 => (Some(2), &[1]),
                    Carried::S2 => (Some(3), &[1, 2]),
                    Carried::Unknown => (None, &[]),
                };
                if let Some(t) = wanted {
                    if let Some((m, by)) = team
                        .known_of_type(t)
                        .find(|&(m, _)| !team.claimed_by_other(m))
                    {
                        return Some(Choice {
                            request: SkillRequest::BringPuckTo(m),
                            shared_type: (by != team.me).then_some((m, t, by)),
                        });
                    }
                }
                for _ in 0..10 {
                    let m = MachineId::new(*next_machine)?;
                    *next_machine = *next_machine % 10 + 1;
                    let k = team.machine(m);
                    let no_use = k.machine_type.is_some_and(|(t, _)| useless.contains(&t));
                    if !team.claimed_by_other(m) && !no_use {
                        return Some(plain(SkillRequest::BringPuckTo(m)));
                    }
                }
                None
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
        let team = TeamView::new(1);
        let mut a =
            ScriptedAgent::parse("get_s0, bring:4,deliver:1").unwrap_or_else(|e| panic!("{e}"));
        let mut next = || a.next(None, &team).map(|c| c.request);
        assert_eq!(next(), Some(SkillRequest::GetS0));
        assert_eq!(next(), MachineId::new(4).map(SkillRequest::BringPuckTo));
        assert_eq!(next(), GateId::new(1).map(SkillRequest::DeliverTo));
        assert_eq!(next(), None);
        assert!(ScriptedAgent::parse("bring:11").is_err());
        assert!(ScriptedAgent::parse("fly").is_err());
    }

    #[test]
    fn round_robin_fetches_then_visits_unclaimed_machines_in_turn() {
        let mut team = TeamView::new(1);
        let mut a = ScriptedAgent::parse("").unwrap_or_else(|e| panic!("{e}"));
        let req = |c: Option<Choice>| c.map(|c| c.request);
        assert_eq!(req(a.next(None, &team)), Some(SkillRequest::GetS0));
        assert_eq!(
            req(a.next(Some(Carried::S0), &team)),
            MachineId::new(1).map(SkillRequest::BringPuckTo)
        );
        team.apply_claim(2, MachineId::new(2).unwrap_or_else(|| panic!()), true);
        assert_eq!(
            req(a.next(Some(Carried::S0), &team)),
            MachineId::new(3).map(SkillRequest::BringPuckTo)
        );
        assert_eq!(
            req(a.next(Some(Carried::P), &team)),
            GateId::new(1).map(SkillRequest::DeliverTo)
        );
    }

    #[test]
    fn a_type_learned_by_a_teammate_is_used() {
        let mut team = TeamView::new(2);
        let m7 = MachineId::new(7).unwrap_or_else(|| panic!());
        team.apply_belief(&crate::shim::payloads::MachineBelief {
            robot: 1,
            machine: m7,
            machine_type: Some(1),
            loaded: 0,
        });
        let mut a = ScriptedAgent::parse("").unwrap_or_else(|e| panic!("{e}"));
        let c = a.next(Some(Carried::S0), &team);
        assert_eq!(
            c,
            Some(Choice {
                request: SkillRequest::BringPuckTo(m7),
                shared_type: Some((m7, 1, 1)),
            })
        );
        // Claimed by the teammate: fall back to the round.
        team.apply_claim(1, m7, true);
        let c = a.next(Some(Carried::S0), &team);
        assert_eq!(
            c.map(|c| c.request),
            MachineId::new(1).map(SkillRequest::BringPuckTo)
        );
    }
}
