//! What the robots of one team share: machine types and loaded inputs (world-model
//! updates), and claims on machines so two robots never work the same machine at once.
//! Pure bookkeeping; `robotino-agent run` moves it over the `team/*` services.

use super::payloads::MachineBelief;
#[cfg(test)]
use super::payloads::LOADED_S0;
use hal::field::{MachineId, MACHINE_COUNT};

/// One machine as the team knows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MachineKnowledge {
    /// 1..=3 for T1..T3, with the robot that found it out.
    pub machine_type: Option<(u8, u8)>,
    pub loaded: u8,
    /// The robot that currently claims the machine.
    pub claimed_by: Option<u8>,
}

/// The team's shared picture, as one robot holds it.
#[derive(Debug, Clone)]
pub struct TeamView {
    pub me: u8,
    machines: [MachineKnowledge; MACHINE_COUNT],
}

impl TeamView {
    pub fn new(me: u8) -> Self {
        Self {
            me,
            machines: [MachineKnowledge::default(); MACHINE_COUNT],
        }
    }

    pub fn machine(&self, m: MachineId) -> MachineKnowledge {
        self.machines[m.index()]
    }

    /// Takes another robot's update; `true` when it taught us a type we did not know.
    pub fn apply_belief(&mut self, b: &MachineBelief) -> bool {
        if b.robot == self.me {
            return false;
        }
        let k = &mut self.machines[b.machine.index()];
        k.loaded = b.loaded;
        match (b.machine_type, k.machine_type) {
            (Some(t), None) => {
                k.machine_type = Some((t, b.robot));
                true
            }
            _ => false,
        }
    }

    pub fn apply_claim(&mut self, robot: u8, m: MachineId, claimed: bool) {
        let k = &mut self.machines[m.index()];
        if claimed {
            k.claimed_by = Some(robot);
        } else if k.claimed_by == Some(robot) {
            k.claimed_by = None;
        }
    }

    pub fn claimed_by_other(&self, m: MachineId) -> bool {
        self.machines[m.index()]
            .claimed_by
            .is_some_and(|r| r != self.me)
    }

    /// Our own belief about a machine, to publish.
    pub fn belief(&self, m: MachineId) -> MachineBelief {
        let k = self.machines[m.index()];
        MachineBelief {
            robot: self.me,
            machine: m,
            machine_type: k.machine_type.map(|(t, _)| t),
            loaded: k.loaded,
        }
    }

    /// Our own agent's view of machine `m` (its rules' definite type, 1..=3, and the inputs
    /// it believes loaded). Returns `true` when the team did not know the type before: the
    /// robot found it out and should tell the others.
    pub fn record_own(&mut self, m: MachineId, machine_type: Option<u8>, loaded: u8) -> bool {
        let me = self.me;
        let k = &mut self.machines[m.index()];
        k.loaded = loaded;
        match (machine_type, k.machine_type) {
            (Some(t), None) => {
                k.machine_type = Some((t, me));
                true
            }
            _ => false,
        }
    }

    /// Machines of a known type, with who found it out.
    pub fn known_of_type(&self, t: u8) -> impl Iterator<Item = (MachineId, u8)> + '_ {
        MachineId::all().filter_map(move |m| match self.machines[m.index()].machine_type {
            Some((kt, by)) if kt == t => Some((m, by)),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(n: u8) -> MachineId {
        MachineId::new(n).unwrap_or_else(|| panic!("{n}"))
    }

    #[test]
    fn own_findings_are_new_once_and_keep_who_found_them() {
        let mut v = TeamView::new(1);
        assert!(!v.record_own(m(2), None, LOADED_S0));
        assert_eq!(v.machine(m(2)).loaded, LOADED_S0);
        assert!(v.record_own(m(2), Some(2), 0));
        assert!(!v.record_own(m(2), Some(2), 0));
        assert_eq!(v.machine(m(2)).machine_type, Some((2, 1)));
        assert_eq!(v.belief(m(2)).machine_type, Some(2));
    }

    #[test]
    fn beliefs_from_others_are_taken_once_and_own_echoes_ignored() {
        let mut v = TeamView::new(2);
        let b = MachineBelief {
            robot: 1,
            machine: m(7),
            machine_type: Some(1),
            loaded: 0,
        };
        assert!(v.apply_belief(&b));
        assert!(!v.apply_belief(&b));
        assert_eq!(v.known_of_type(1).collect::<Vec<_>>(), vec![(m(7), 1)]);
        let echo = MachineBelief { robot: 2, ..b };
        assert!(!v.apply_belief(&echo));
    }

    #[test]
    fn claims_block_other_robots_only() {
        let mut v = TeamView::new(1);
        v.apply_claim(2, m(4), true);
        assert!(v.claimed_by_other(m(4)));
        // Only the claimant can release.
        v.apply_claim(3, m(4), false);
        assert!(v.claimed_by_other(m(4)));
        v.apply_claim(2, m(4), false);
        assert!(!v.claimed_by_other(m(4)));
        v.apply_claim(1, m(5), true);
        assert!(!v.claimed_by_other(m(5)));
    }
}
