//! How one robot's team messages reach the others: one trait, two carriers. On one host
//! (the lockstep game) iceoryx2 carries them (`shim::team::IceoryxTeamLink`); between
//! machines Zenoh does (the `team-link` crate, its own workspace). The agent loop only
//! sees this trait.

use std::fmt;

use super::member::TeamMsg;
use super::net::{FaultyNet, LinkFaults};

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

/// A link whose incoming messages pass our fault proxy ([`FaultyNet`]): each is lost,
/// delayed or duplicated in game time, drawn from a seed (so a lockstep game with faults
/// is still reproducible). The clock is the receiver's: one `receive` a cycle.
pub struct FaultyLink<L> {
    inner: L,
    net: FaultyNet,
    me: u8,
    cycle_s: f64,
    cycles: u64,
}

impl<L: TeamLink> FaultyLink<L> {
    pub fn new(inner: L, me: u8, faults: LinkFaults, seed: u64, cycle_s: f64) -> Self {
        Self {
            inner,
            net: FaultyNet::new(faults, seed ^ u64::from(me)),
            me,
            cycle_s,
            cycles: 0,
        }
    }
}

impl<L: TeamLink> TeamLink for FaultyLink<L> {
    fn send(&mut self, cycle: u64, msgs: &[TeamMsg]) -> Result<(), LinkError> {
        self.inner.send(cycle, msgs)
    }

    fn receive(&mut self, cycle: u64) -> Result<Vec<TeamMsg>, LinkError> {
        self.cycles += 1;
        let now = self.cycles as f64 * self.cycle_s;
        for m in self.inner.receive(cycle)? {
            self.net.send(&m, now, [self.me]);
        }
        Ok(self.net.arrived(now).into_iter().map(|(_, m)| m).collect())
    }
}

impl TeamLink for Box<dyn TeamLink> {
    fn send(&mut self, cycle: u64, msgs: &[TeamMsg]) -> Result<(), LinkError> {
        (**self).send(cycle, msgs)
    }

    fn receive(&mut self, cycle: u64) -> Result<Vec<TeamMsg>, LinkError> {
        (**self).receive(cycle)
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

    /// A perfect inner link: what is sent comes back at the next receive.
    #[derive(Default)]
    struct Loopback(Vec<TeamMsg>);

    impl TeamLink for Loopback {
        fn send(&mut self, _cycle: u64, msgs: &[TeamMsg]) -> Result<(), LinkError> {
            self.0.extend_from_slice(msgs);
            Ok(())
        }
        fn receive(&mut self, _cycle: u64) -> Result<Vec<TeamMsg>, LinkError> {
            Ok(std::mem::take(&mut self.0))
        }
    }

    #[test]
    fn a_faulty_link_loses_and_delays_in_game_time() {
        let faults = LinkFaults {
            loss_percent: 10,
            delay_min: 0.0,
            delay_max: 2.0,
            dup_percent: 0,
        };
        let mut link = FaultyLink::new(Loopback::default(), 2, faults, 7, 0.1);
        let mut got = 0;
        for c in 0..1000u64 {
            if c < 500 {
                link.send(c, &[msg(1, c as i64 + 1)])
                    .unwrap_or_else(|e| panic!("{e}"));
            }
            let arrived = link.receive(c).unwrap_or_else(|e| panic!("{e}"));
            // Nothing is due before it was sent; up to 2 s (20 cycles) later.
            assert!(arrived.iter().all(|m| m.seq <= c as i64 + 1));
            got += arrived.len();
        }
        assert!((400..490).contains(&got), "{got} of 500 arrived");
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
