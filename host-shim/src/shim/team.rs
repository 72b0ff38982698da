//! The team link on one host: every agent publishes its team messages on
//! `P/team/messages` (one [`TeamBatchPayload`] per cycle, more if they do not fit) and
//! reads everybody's. In lockstep a batch is handed to the rules in the cycle after the
//! one it was sent in (the sim moves on only when every live agent answered, so by then
//! every batch of that cycle is there), which makes the team's game reproducible.

use super::payloads::TeamBatchPayload;
use super::transport::{Pub, Queue, Sub, TeamStream, Transport, TransportError};
use crate::team::link::{CycleQueue, LinkError, TeamLink};
use crate::team::TeamMsg;

/// One robot's end of the team service.
pub struct IceoryxTeamLink {
    me: u8,
    out: Pub<TeamBatchPayload>,
    inbox: Sub<TeamBatchPayload>,
    queue: CycleQueue,
    /// Batches that did not decode (a broken or foreign sender): dropped, counted.
    pub rejected: u64,
}

impl IceoryxTeamLink {
    pub fn open(t: &Transport, me: u8) -> Result<Self, TransportError> {
        let name = t.names.team(TeamStream::Messages);
        Ok(Self {
            me,
            out: t.publisher_with(&name, Queue::MESSAGES)?,
            inbox: t.subscriber_with(&name, Queue::MESSAGES)?,
            queue: CycleQueue::default(),
            rejected: 0,
        })
    }

    fn send_batch(&mut self, cycle: u32, msgs: &[TeamMsg]) -> Result<(), LinkError> {
        let me = self.me;
        if let Some(mut batch) = TeamBatchPayload::encode(0, me, cycle, msgs) {
            return self
                .out
                .send(|seq| {
                    batch.seq = seq;
                    batch
                })
                .map(|_| ())
                .map_err(|e| LinkError(e.to_string()));
        }
        if msgs.len() < 2 {
            return Err(LinkError(format!(
                "a message of robot {me} is too long for a batch: {:?}",
                msgs.first()
            )));
        }
        let (a, b) = msgs.split_at(msgs.len() / 2);
        self.send_batch(cycle, a)?;
        self.send_batch(cycle, b)
    }
}

impl TeamLink for IceoryxTeamLink {
    fn send(&mut self, cycle: u64, msgs: &[TeamMsg]) -> Result<(), LinkError> {
        if msgs.is_empty() {
            return Ok(());
        }
        self.send_batch(u32::try_from(cycle).unwrap_or(u32::MAX), msgs)
    }

    fn receive(&mut self, cycle: u64) -> Result<Vec<TeamMsg>, LinkError> {
        let me = self.me;
        let queue = &mut self.queue;
        let mut rejected = 0;
        self.inbox
            .drain(|batch| match batch.decode() {
                Ok((from, _, _)) if from == me => {}
                Ok((_, sent_in, msgs)) => {
                    for m in msgs {
                        queue.push(u64::from(sent_in), m);
                    }
                }
                Err(_) => rejected += 1,
            })
            .map_err(|e| LinkError(e.to_string()))?;
        self.rejected += rejected;
        Ok(self.queue.due(cycle))
    }
}
