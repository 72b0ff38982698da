//! Lockstep between the world simulation and the robots' agents, and how a dead agent is
//! told from a slow one.
//!
//! A cycle of the world: the sim publishes every robot's sensor frame (the sim's heartbeat
//! last, carrying the cycle: the frame is complete once it is seen), each agent answers
//! with one motor command naming the frame's bumper sample, and the sim steps the world
//! once every *live* robot has answered. No wall-clock grace decides when the world moves,
//! so the same seed plays the same game however slow a process is.
//!
//! Liveness is the only wall-clock judgement, and it only ever concerns a process that
//! stopped: every agent sends heartbeats from a thread of its own ([`spawn_heartbeat`]),
//! independent of how long its cycle takes; an agent silent for `heartbeat_timeout_ms` is
//! dead and no longer waited for (its wheels stop by the dead-man rule). One that beats
//! again is waited for again.

use super::payloads::{DriverId, HeartbeatPayload};
use super::transport::{RobotStream, ServiceNames, Sub, Transport, TransportError};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Where a robot's agent stands, as the sim sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AgentLife {
    /// No heartbeat yet: waited for up to the start-up timeout.
    Starting,
    Alive,
    /// Silent past the timeout (or never started): not waited for.
    Dead,
}

/// One robot's agent liveness from its heartbeats. Time is passed in, so the rule is
/// testable without sleeping.
#[derive(Debug, Clone)]
pub struct Liveness {
    opened: Instant,
    last_beat: Option<Instant>,
    timeout: Duration,
    startup_timeout: Duration,
    life: AgentLife,
}

impl Liveness {
    pub fn new(now: Instant, timeout: Duration, startup_timeout: Duration) -> Self {
        Self {
            opened: now,
            last_beat: None,
            timeout,
            startup_timeout,
            life: AgentLife::Starting,
        }
    }

    /// A heartbeat arrived.
    pub fn beat(&mut self, now: Instant) {
        self.last_beat = Some(now);
    }

    /// The state at `now`; `Some(new)` in the second place when it changed.
    pub fn update(&mut self, now: Instant) -> (AgentLife, Option<AgentLife>) {
        let next = match self.last_beat {
            None if now.duration_since(self.opened) >= self.startup_timeout => AgentLife::Dead,
            None => AgentLife::Starting,
            Some(t) if now.duration_since(t) >= self.timeout => AgentLife::Dead,
            Some(_) => AgentLife::Alive,
        };
        let changed = (next != self.life).then_some(next);
        self.life = next;
        (next, changed)
    }

    /// Whether the world waits for this robot's command.
    pub fn waited_for(&self) -> bool {
        self.life != AgentLife::Dead
    }
}

/// The sim's reading of one robot's heartbeat service: only the agent's beats count.
pub struct AgentWatch {
    heartbeat: Sub<HeartbeatPayload>,
    pub liveness: Liveness,
}

impl AgentWatch {
    pub fn open(
        t: &Transport,
        robot: u8,
        timeout: Duration,
        startup_timeout: Duration,
    ) -> Result<Self, TransportError> {
        Ok(Self {
            heartbeat: t.subscriber(&t.names.robot(robot, RobotStream::Heartbeat))?,
            liveness: Liveness::new(Instant::now(), timeout, startup_timeout),
        })
    }

    /// Takes the heartbeats received so far; returns the life state and its change.
    pub fn poll(&mut self) -> Result<(AgentLife, Option<AgentLife>), TransportError> {
        let now = Instant::now();
        let mut beat = false;
        self.heartbeat.drain(|h| {
            beat |= matches!(h.decode(), Ok((DriverId::Agent, _)));
        })?;
        if beat {
            self.liveness.beat(now);
        }
        Ok(self.liveness.update(now))
    }
}

/// The agent's side: tells when the sim's next frame is complete (its heartbeat, sent last,
/// carries a cycle not seen before).
pub struct FrameWatch {
    heartbeat: Sub<HeartbeatPayload>,
    last: Option<u32>,
}

impl FrameWatch {
    pub fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        Ok(Self {
            heartbeat: t.subscriber(&t.names.robot(robot, RobotStream::Heartbeat))?,
            last: None,
        })
    }

    /// The sim's cycle of the newest complete frame seen.
    pub fn cycle(&self) -> Option<u32> {
        self.last
    }

    /// `true` once a new frame is complete.
    pub fn fresh_frame(&mut self) -> Result<bool, TransportError> {
        let mut newest = None;
        self.heartbeat.drain(|h| {
            if let Ok((DriverId::Sim, cycle)) = h.decode() {
                newest = Some(cycle);
            }
        })?;
        match newest {
            Some(c) if Some(c) != self.last => {
                self.last = Some(c);
                Ok(true)
            }
            _ => Ok(false),
        }
    }
}

/// The agent process's heartbeat: a thread with its own iceoryx2 node publishes the loop's
/// cycle count every `period`, however long a cycle takes; it stops when the process does.
pub fn spawn_heartbeat(
    names: &ServiceNames,
    robot: u8,
    period: Duration,
    cycle: Arc<AtomicU64>,
) -> Result<(), TransportError> {
    let prefix = names.prefix().to_string();
    let (ready_tx, ready_rx) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .name(format!("heartbeat-{robot}"))
        .spawn(move || {
            let opened = Transport::open_without_signals(&prefix, &format!("heartbeat-{robot}"))
                .and_then(|t| {
                    let p = t.publisher::<HeartbeatPayload>(
                        &t.names.robot(robot, RobotStream::Heartbeat),
                    )?;
                    Ok((t, p))
                });
            let (t, mut publisher) = match opened {
                Ok(x) => {
                    let _ = ready_tx.send(Ok(()));
                    x
                }
                Err(e) => {
                    let _ = ready_tx.send(Err(e));
                    return;
                }
            };
            loop {
                let c = cycle.load(Ordering::Relaxed) as u32;
                if publisher
                    .send(|s| HeartbeatPayload::encode(s, c, DriverId::Agent))
                    .is_err()
                {
                    return;
                }
                if !t.wait(period) {
                    return;
                }
            }
        })
        .map_err(|e| TransportError {
            context: "start the heartbeat thread".into(),
            detail: e.to_string(),
        })?;
    ready_rx.recv().map_err(|e| TransportError {
        context: "heartbeat thread".into(),
        detail: e.to_string(),
    })?
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIMEOUT: Duration = Duration::from_millis(3000);
    const STARTUP: Duration = Duration::from_millis(10_000);

    #[test]
    fn waits_for_a_starting_agent_then_gives_up() {
        let t0 = Instant::now();
        let mut l = Liveness::new(t0, TIMEOUT, STARTUP);
        assert_eq!(
            l.update(t0 + Duration::from_secs(9)),
            (AgentLife::Starting, None)
        );
        assert!(l.waited_for());
        assert_eq!(
            l.update(t0 + STARTUP),
            (AgentLife::Dead, Some(AgentLife::Dead))
        );
        assert!(!l.waited_for());
    }

    #[test]
    fn a_silent_agent_dies_and_a_beating_one_lives_again() {
        let t0 = Instant::now();
        let mut l = Liveness::new(t0, TIMEOUT, STARTUP);
        l.beat(t0);
        assert_eq!(l.update(t0), (AgentLife::Alive, Some(AgentLife::Alive)));
        // A slow cycle is not a death: beats keep coming from the heartbeat thread.
        let mut t = t0;
        for _ in 0..100 {
            t += Duration::from_millis(100);
            l.beat(t);
            assert_eq!(l.update(t), (AgentLife::Alive, None));
        }
        assert_eq!(
            l.update(t + TIMEOUT - Duration::from_millis(1)).0,
            AgentLife::Alive
        );
        assert_eq!(
            l.update(t + TIMEOUT),
            (AgentLife::Dead, Some(AgentLife::Dead))
        );
        assert!(!l.waited_for());
        l.beat(t + TIMEOUT * 2);
        assert_eq!(
            l.update(t + TIMEOUT * 2),
            (AgentLife::Alive, Some(AgentLife::Alive))
        );
    }
}
