//! A message-level fault proxy in game time: every message from one robot to another
//! is lost, delayed or duplicated independently, drawn from a seed, so a faulty run is
//! reproducible. Delays differ per copy, so messages overtake each other.

use rules::setup::SplitMix64;

use super::member::TeamMsg;

/// What the link does to messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkFaults {
    /// Percent of the copies lost.
    pub loss_percent: u32,
    /// Each copy arrives after a delay drawn uniformly from this range (seconds).
    pub delay_min: f64,
    pub delay_max: f64,
    /// Percent of the messages delivered twice (each copy with its own delay).
    pub dup_percent: u32,
}

impl LinkFaults {
    /// A perfect link: every message arrives once, at once.
    pub const NONE: LinkFaults = LinkFaults {
        loss_percent: 0,
        delay_min: 0.0,
        delay_max: 0.0,
        dup_percent: 0,
    };
}

/// Messages in flight between the robots of one team.
pub struct FaultyNet {
    faults: LinkFaults,
    rng: SplitMix64,
    /// (arrival time, ordinal for a stable order, receiver, message)
    in_flight: Vec<(f64, u64, u8, TeamMsg)>,
    sent: u64,
    /// Copies lost and duplicated so far (for reports).
    pub lost: u64,
    pub duplicated: u64,
}

impl FaultyNet {
    pub fn new(faults: LinkFaults, seed: u64) -> FaultyNet {
        FaultyNet {
            faults,
            rng: SplitMix64::new(seed ^ 0x7EA3_11C0_5EED_0001),
            in_flight: Vec::new(),
            sent: 0,
            lost: 0,
            duplicated: 0,
        }
    }

    fn delay(&mut self) -> f64 {
        let span = (self.faults.delay_max - self.faults.delay_min).max(0.0);
        let unit = (self.rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        self.faults.delay_min + span * unit
    }

    /// Sends `msg` at game time `now` to every robot in `to`.
    pub fn send(&mut self, msg: &TeamMsg, now: f64, to: impl IntoIterator<Item = u8>) {
        for receiver in to {
            if receiver == msg.from {
                continue;
            }
            let copies = if self.rng.below(100) < u64::from(self.faults.dup_percent) {
                self.duplicated += 1;
                2
            } else {
                1
            };
            for _ in 0..copies {
                if self.rng.below(100) < u64::from(self.faults.loss_percent) {
                    self.lost += 1;
                    continue;
                }
                let at = now + self.delay();
                self.sent += 1;
                self.in_flight.push((at, self.sent, receiver, msg.clone()));
            }
        }
    }

    /// Takes the messages that have arrived by `now`, in arrival order.
    pub fn arrived(&mut self, now: f64) -> Vec<(u8, TeamMsg)> {
        let mut due: Vec<(f64, u64, u8, TeamMsg)> = Vec::new();
        let mut i = 0;
        while i < self.in_flight.len() {
            if self.in_flight[i].0 <= now {
                due.push(self.in_flight.swap_remove(i));
            } else {
                i += 1;
            }
        }
        due.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        due.into_iter().map(|(_, _, to, m)| (to, m)).collect()
    }

    /// Messages still on their way.
    pub fn in_flight(&self) -> usize {
        self.in_flight.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(seq: i64) -> TeamMsg {
        TeamMsg {
            from: 1,
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
    fn a_perfect_link_delivers_each_message_once_in_order() {
        let mut net = FaultyNet::new(LinkFaults::NONE, 1);
        for s in 1..=5 {
            net.send(&msg(s), 0.0, [1, 2, 3]);
        }
        let got = net.arrived(0.0);
        assert_eq!(got.len(), 10);
        let to2: Vec<i64> = got
            .iter()
            .filter(|(r, _)| *r == 2)
            .map(|(_, m)| m.seq)
            .collect();
        assert_eq!(to2, vec![1, 2, 3, 4, 5]);
        assert_eq!(net.in_flight(), 0);
    }

    #[test]
    fn faults_lose_duplicate_and_reorder() {
        let faults = LinkFaults {
            loss_percent: 20,
            delay_min: 0.0,
            delay_max: 5.0,
            dup_percent: 20,
        };
        let mut net = FaultyNet::new(faults, 7);
        for s in 1..=500 {
            net.send(&msg(s), f64::from(s as u32) * 0.1, [2]);
        }
        assert!(net.arrived(0.0).len() < 5);
        let got: Vec<i64> = net.arrived(1000.0).iter().map(|(_, m)| m.seq).collect();
        assert!(
            net.lost > 50 && net.duplicated > 50,
            "{} {}",
            net.lost,
            net.duplicated
        );
        assert!(
            got.windows(2).any(|w| w[0] > w[1]),
            "no message overtook another"
        );
        assert_eq!(got.len() as u64, 500 + net.duplicated - net.lost);
    }
}
