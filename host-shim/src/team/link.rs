//! How one robot's team messages reach the others: one trait, two carriers. On one host
//! (the lockstep game) iceoryx2 carries them (`shim::team::IceoryxTeamLink`); between
//! machines Zenoh does (the `team-link` crate, its own workspace). The agent loop only
//! sees this trait.

use std::fmt;

use super::member::TeamMsg;

/// A link failure, with what was being done.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LinkError(pub String);

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "team link: {}", self.0)
    }
}

impl std::error::Error for LinkError {}

/// Carries a robot's messages to its teammates and theirs to it.
pub trait TeamLink {
    /// Hands the messages this robot's rules sent in `cycle` to the team.
    fn send(&mut self, cycle: u64, msgs: &[TeamMsg]) -> Result<(), LinkError>;
    /// The teammates' messages to hand to the rules in `cycle`, oldest first. A link
    /// that can keep lockstep returns exactly those sent in earlier cycles (so a message
    /// sent in cycle k is taken in cycle k+1, and a seed plays the same game every
    /// time); one between machines returns whatever has arrived.
    fn receive(&mut self, cycle: u64) -> Result<Vec<TeamMsg>, LinkError>;
}

/// Messages in flight inside a lockstep link: kept until the cycle after the one they
/// were sent in, then handed out ordered by (cycle sent, sender, sender's number), an
/// order no scheduling can change.
#[derive(Debug, Default)]
pub struct CycleQueue {
    pending: Vec<(u64, TeamMsg)>,
}

impl CycleQueue {
    pub fn push(&mut self, sent_in: u64, msg: TeamMsg) {
        self.pending.push((sent_in, msg));
    }

    /// The messages sent before `cycle`, in delivery order.
    pub fn due(&mut self, cycle: u64) -> Vec<TeamMsg> {
        let (mut due, later): (Vec<_>, Vec<_>) =
            self.pending.drain(..).partition(|(c, _)| *c < cycle);
        self.pending = later;
        due.sort_by_key(|(c, m)| (*c, m.from, m.seq));
        due.into_iter().map(|(_, m)| m).collect()
    }

    pub fn len(&self) -> usize {
        self.pending.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pending.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(from: u8, seq: i64) -> TeamMsg {
        TeamMsg {
            from,
            seq,
            kind: "request".into(),
            to: 0,
            resource: "M1".into(),
            rseq: seq,
            lease: 20.0,
            data: Vec::new(),
        }
    }

    #[test]
    fn a_message_is_due_the_cycle_after_it_was_sent_in_a_fixed_order() {
        let mut q = CycleQueue::default();
        // Arrival order differs from the delivery order.
        q.push(5, msg(3, 2));
        q.push(6, msg(1, 9));
        q.push(5, msg(2, 7));
        q.push(5, msg(3, 1));
        assert!(q.due(5).is_empty());
        let got: Vec<(u8, i64)> = q.due(6).iter().map(|m| (m.from, m.seq)).collect();
        assert_eq!(got, vec![(2, 7), (3, 1), (3, 2)]);
        assert_eq!(q.len(), 1);
        assert_eq!(q.due(7).len(), 1);
        assert!(q.is_empty());
    }
}
