//! iceoryx2 plumbing: one publish-subscribe service per stream, named under a configurable
//! prefix, with thin publisher/subscriber wrappers that count sequence numbers and keep the
//! latest sample.
//!
//! Service names (`P` = prefix, `N` = robot number 1..=3):
//!
//! | service | payload | publisher | readers |
//! |---|---|---|---|
//! | `P/robotN/ir` | [`IrScanPayload`] | IR driver (sim) | agent |
//! | `P/robotN/bumper` | [`BumperPayload`] | bumper driver (sim) | agent |
//! | `P/robotN/gyro` | [`GyroPayload`] | gyro driver (sim) | agent |
//! | `P/robotN/odometry` | [`OdometryPayload`] | drive driver (sim) | agent |
//! | `P/robotN/puck` | [`PuckPayload`] | puck sensor (sim) | agent |
//! | `P/robotN/light` | [`LightPayload`] | camera (sim) | agent |
//! | `P/robotN/motor` | [`MotorCommandPayload`] | agent | drive driver (sim) |
//! | `P/robotN/skill-request` | [`SkillRequestPayload`] | agent | monitors, other robots |
//! | `P/robotN/skill-status` | [`SkillStatusPayload`] | agent | monitors, other robots |
//! | `P/robotN/heartbeat` | [`HeartbeatPayload`] | every driver, agent | agent, sim |
//! | `P/team/messages` | [`TeamBatchPayload`] | every agent | every agent |
//!
//! [`IrScanPayload`]: super::payloads::IrScanPayload
//! [`BumperPayload`]: super::payloads::BumperPayload
//! [`GyroPayload`]: super::payloads::GyroPayload
//! [`OdometryPayload`]: super::payloads::OdometryPayload
//! [`PuckPayload`]: super::payloads::PuckPayload
//! [`LightPayload`]: super::payloads::LightPayload
//! [`MotorCommandPayload`]: super::payloads::MotorCommandPayload
//! [`SkillRequestPayload`]: super::payloads::SkillRequestPayload
//! [`SkillStatusPayload`]: super::payloads::SkillStatusPayload
//! [`HeartbeatPayload`]: super::payloads::HeartbeatPayload
//! [`TeamBatchPayload`]: super::payloads::TeamBatchPayload

use iceoryx2::port::publisher::Publisher;
use iceoryx2::port::subscriber::Subscriber;
use iceoryx2::port::update_connections::UpdateConnections;
use iceoryx2::prelude::*;
use iceoryx2::service::builder::publish_subscribe::{
    PublishSubscribeCreateError, PublishSubscribeOpenError, PublishSubscribeOpenOrCreateError,
};
use std::fmt::{self, Debug};

/// Where every prefix keeps its iceoryx2 nodes and services.
const ROOT_BASE: &str = "/tmp/iceoryx2/robotino";

/// The iceoryx2 root directory of one service prefix. Processes of one prefix (one game, one
/// robot) never see the nodes of another: a killed test game's dead nodes, or those of the
/// 32-bit robot build, whose shared-memory layout a 64-bit process misreads when it cleans
/// them up (iceoryx2 0.10 aborts on a misaligned pointer there).
pub fn root_dir(prefix: &str) -> std::path::PathBuf {
    let mut dir = std::path::PathBuf::from(ROOT_BASE);
    for part in prefix.split('/').filter(|p| !p.is_empty()) {
        // Only characters that are safe in any file name; `.` would allow `..`.
        let clean: String = part
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        dir.push(clean);
    }
    dir
}

/// Removes a prefix's iceoryx2 directory once every process of it has ended.
pub fn remove_root(prefix: &str) {
    let _ = std::fs::remove_dir_all(root_dir(prefix));
}

/// One stream of one robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RobotStream {
    Ir,
    Bumper,
    Gyro,
    Odometry,
    Puck,
    Light,
    Motor,
    SkillRequest,
    SkillStatus,
    Heartbeat,
}

impl RobotStream {
    pub const fn leaf(self) -> &'static str {
        match self {
            Self::Ir => "ir",
            Self::Bumper => "bumper",
            Self::Gyro => "gyro",
            Self::Odometry => "odometry",
            Self::Puck => "puck",
            Self::Light => "light",
            Self::Motor => "motor",
            Self::SkillRequest => "skill-request",
            Self::SkillStatus => "skill-status",
            Self::Heartbeat => "heartbeat",
        }
    }
}

/// A stream shared by the whole team.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TeamStream {
    /// The team's messages (`rules/team.clp`): claims, votes, releases, news.
    Messages,
}

/// Builds service names under a prefix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ServiceNames {
    prefix: String,
}

impl ServiceNames {
    pub fn new(prefix: &str) -> Self {
        Self {
            prefix: prefix.trim_end_matches('/').to_string(),
        }
    }

    pub fn prefix(&self) -> &str {
        &self.prefix
    }

    pub fn robot(&self, robot: u8, stream: RobotStream) -> String {
        format!("{}/robot{robot}/{}", self.prefix, stream.leaf())
    }

    pub fn team(&self, stream: TeamStream) -> String {
        let leaf = match stream {
            TeamStream::Messages => "messages",
        };
        format!("{}/team/{leaf}", self.prefix)
    }
}

/// A transport failure with what was being done.
#[derive(Debug)]
pub struct TransportError {
    pub context: String,
    pub detail: String,
}

impl fmt::Display for TransportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.context, self.detail)
    }
}

impl std::error::Error for TransportError {}

fn err(context: impl Into<String>, detail: impl Debug) -> TransportError {
    TransportError {
        context: context.into(),
        detail: format!("{detail:?}"),
    }
}

/// How often a service is tried before its open error is given up on.
const OPEN_ATTEMPTS: u32 = 10;

/// Open errors that another process's creating or removing the same service at that moment
/// explains: they pass, so trying again is worth it.
fn open_error_passes(e: &PublishSubscribeOpenOrCreateError) -> bool {
    use PublishSubscribeOpenError as O;
    match e {
        PublishSubscribeOpenOrCreateError::SystemInFlux => true,
        PublishSubscribeOpenOrCreateError::PublishSubscribeOpenError(o) => matches!(
            o,
            O::DoesNotExist | O::HangsInCreation | O::IsMarkedForDestruction | O::Interrupt
        ),
        PublishSubscribeOpenOrCreateError::PublishSubscribeCreateError(c) => matches!(
            c,
            PublishSubscribeCreateError::AlreadyExists
                | PublishSubscribeCreateError::IsBeingCreatedByAnotherInstance
        ),
    }
}

/// How a service queues samples for each subscriber.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Queue {
    /// Samples a subscriber holds before the oldest is overwritten.
    pub buffer: usize,
    /// Samples a subscriber that joins late receives.
    pub history: usize,
}

impl Queue {
    /// Sensor and command streams: only the newest sample matters, and a late reader
    /// gets it.
    pub const LATEST: Queue = Queue {
        buffer: 4,
        history: 1,
    };
    /// Team messages: every one counts (a reader drains each cycle; three robots send a
    /// batch or two a cycle), and a late joiner gets none of the past.
    pub const MESSAGES: Queue = Queue {
        buffer: 64,
        history: 0,
    };
}

/// The process's iceoryx2 node.
pub struct Transport {
    node: Node<ipc::Service>,
    pub names: ServiceNames,
}

impl Transport {
    /// Creates the node and removes what killed processes left behind, so a restarted
    /// driver can take over its services.
    pub fn open(prefix: &str, node_name: &str) -> Result<Self, TransportError> {
        // Ctrl-C and SIGTERM end the loops through `Node::wait`; processes exit cleanly.
        let t = Self::open_with(
            prefix,
            node_name,
            SignalHandlingMode::HandleTerminationRequests,
        )?;
        t.node.try_cleanup_dead_nodes();
        Ok(t)
    }

    /// A second node of the process (a helper thread's): signals stay with the main one.
    pub fn open_without_signals(prefix: &str, node_name: &str) -> Result<Self, TransportError> {
        Self::open_with(prefix, node_name, SignalHandlingMode::Disabled)
    }

    fn open_with(
        prefix: &str,
        node_name: &str,
        signals: SignalHandlingMode,
    ) -> Result<Self, TransportError> {
        set_log_level(LogLevel::Error);
        let name = NodeName::new(node_name).map_err(|e| err("node name", e))?;
        let mut root = root_dir(prefix)
            .into_os_string()
            .into_string()
            .map_err(|p| err("iceoryx2 root", p))?;
        root.push('/');
        let mut config = Config::global_config().clone();
        config.global.set_root_path(
            &iceoryx2_bb_system_types::path::Path::new(root.as_bytes())
                .map_err(|e| err(format!("iceoryx2 root {root}"), e))?,
        );
        let node = NodeBuilder::new()
            .name(&name)
            .config(&config)
            .signal_handling_mode(signals)
            .create::<ipc::Service>()
            .map_err(|e| err("create iceoryx2 node", e))?;
        Ok(Self {
            node,
            names: ServiceNames::new(prefix),
        })
    }

    /// Sleeps for `d`; `false` when a termination signal arrived.
    pub fn wait(&self, d: std::time::Duration) -> bool {
        self.node.wait(d).is_ok()
    }

    fn service<T: Debug + ZeroCopySend + 'static>(
        &self,
        name: &str,
        queue: Queue,
    ) -> Result<
        iceoryx2::service::port_factory::publish_subscribe::PortFactory<ipc::Service, T, ()>,
        TransportError,
    > {
        let service_name =
            ServiceName::new(name).map_err(|e| err(format!("service name {name}"), e))?;
        // Every process asks for the same settings, so whoever comes first creates the
        // service and the others open it. Under load a process can find the service half
        // made by another (iceoryx2 then says `DoesNotExist` or `SystemInFlux`): that passes,
        // so those are tried again after a growing pause (about 2.5 s in all) before giving up.
        let mut pause = std::time::Duration::from_millis(5);
        let mut attempt = 1u32;
        loop {
            let result = self
                .node
                .service_builder(&service_name)
                .publish_subscribe::<T>()
                .max_publishers(4)
                .max_subscribers(8)
                .subscriber_max_buffer_size(queue.buffer)
                .history_size(queue.history)
                .enable_safe_overflow(true)
                .open_or_create();
            match result {
                Ok(factory) => return Ok(factory),
                Err(e) if attempt < OPEN_ATTEMPTS && open_error_passes(&e) => {
                    std::thread::sleep(pause);
                    pause = (pause * 2).min(std::time::Duration::from_millis(500));
                    attempt += 1;
                }
                Err(e) => {
                    return Err(err(
                        format!("open service {name} (attempt {attempt} of {OPEN_ATTEMPTS})"),
                        e,
                    ))
                }
            }
        }
    }

    pub fn publisher<T: Debug + ZeroCopySend + Copy + 'static>(
        &self,
        name: &str,
    ) -> Result<Pub<T>, TransportError> {
        self.publisher_with(name, Queue::LATEST)
    }

    /// A publisher on a service with the given queue (every opener must ask for the same).
    pub fn publisher_with<T: Debug + ZeroCopySend + Copy + 'static>(
        &self,
        name: &str,
        queue: Queue,
    ) -> Result<Pub<T>, TransportError> {
        let publisher = self
            .service::<T>(name, queue)?
            .publisher_builder()
            .create()
            .map_err(|e| err(format!("publisher on {name}"), e))?;
        Ok(Pub {
            publisher,
            next_seq: 1,
            name: name.to_string(),
        })
    }

    pub fn subscriber<T: Debug + ZeroCopySend + Copy + 'static>(
        &self,
        name: &str,
    ) -> Result<Sub<T>, TransportError> {
        self.subscriber_with(name, Queue::LATEST)
    }

    /// A subscriber on a service with the given queue (every opener must ask for the same).
    pub fn subscriber_with<T: Debug + ZeroCopySend + Copy + 'static>(
        &self,
        name: &str,
        queue: Queue,
    ) -> Result<Sub<T>, TransportError> {
        let subscriber = self
            .service::<T>(name, queue)?
            .subscriber_builder()
            .create()
            .map_err(|e| err(format!("subscriber on {name}"), e))?;
        Ok(Sub {
            subscriber,
            latest: None,
            name: name.to_string(),
        })
    }
}

/// A publisher that numbers its samples 1, 2, 3, ...
pub struct Pub<T: Debug + ZeroCopySend + 'static> {
    publisher: Publisher<ipc::Service, T, ()>,
    next_seq: u32,
    name: String,
}

impl<T: Debug + ZeroCopySend + Copy + 'static> Pub<T> {
    /// Builds the payload with the next sequence number and sends it; returns that number.
    pub fn send(&mut self, build: impl FnOnce(u32) -> T) -> Result<u32, TransportError> {
        let seq = self.next_seq;
        self.publisher
            .send_copy(build(seq))
            .map_err(|e| err(format!("send on {}", self.name), e))?;
        self.next_seq = self.next_seq.wrapping_add(1);
        Ok(seq)
    }

    /// Connects subscribers that came since the last send and hands them the latest sample
    /// (a lockstep publisher that waits for an answer would otherwise never reach a
    /// subscriber that joined after its last send).
    pub fn update_connections(&self) -> Result<(), TransportError> {
        self.publisher
            .update_connections()
            .map_err(|e| err(format!("connect subscribers of {}", self.name), e))
    }
}

/// A subscriber that keeps the newest sample.
pub struct Sub<T: Debug + ZeroCopySend + 'static> {
    subscriber: Subscriber<ipc::Service, T, ()>,
    latest: Option<T>,
    name: String,
}

impl<T: Debug + ZeroCopySend + Copy + 'static> Sub<T> {
    /// Drains everything received and returns the newest sample ever seen.
    pub fn poll(&mut self) -> Result<Option<T>, TransportError> {
        while let Some(sample) = self
            .subscriber
            .receive()
            .map_err(|e| err(format!("receive on {}", self.name), e))?
        {
            self.latest = Some(*sample);
        }
        Ok(self.latest)
    }

    /// Drains and hands every received sample to `each` (for streams where every message
    /// counts, such as claims).
    pub fn drain(&mut self, mut each: impl FnMut(T)) -> Result<(), TransportError> {
        while let Some(sample) = self
            .subscriber
            .receive()
            .map_err(|e| err(format!("receive on {}", self.name), e))?
        {
            self.latest = Some(*sample);
            each(*sample);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A service another process is making or removing at that moment is tried again; a
    /// service whose settings differ, or that no one may open, is not.
    #[test]
    fn only_passing_open_errors_are_tried_again() {
        use PublishSubscribeOpenOrCreateError as E;
        assert!(open_error_passes(&E::SystemInFlux));
        assert!(open_error_passes(&E::PublishSubscribeOpenError(
            PublishSubscribeOpenError::DoesNotExist
        )));
        assert!(open_error_passes(&E::PublishSubscribeCreateError(
            PublishSubscribeCreateError::AlreadyExists
        )));
        assert!(!open_error_passes(&E::PublishSubscribeOpenError(
            PublishSubscribeOpenError::IncompatibleTypes
        )));
        assert!(!open_error_passes(&E::PublishSubscribeOpenError(
            PublishSubscribeOpenError::InsufficientPermissions
        )));
        assert!(!open_error_passes(&E::PublishSubscribeCreateError(
            PublishSubscribeCreateError::InsufficientPermissions
        )));
    }

    /// Two processes opening the same services at once both get them (whoever comes
    /// second opens what the first made, or waits until it is made).
    #[test]
    fn two_threads_open_the_same_services_at_once() {
        let prefix = format!("test/open-race-{}", std::process::id());
        let run = |node: &'static str| {
            let prefix = prefix.clone();
            std::thread::spawn(move || -> Result<(), TransportError> {
                let t = Transport::open_without_signals(&prefix, node)?;
                for i in 0..8 {
                    let _p = t.publisher::<u64>(&format!("{prefix}/s{i}"))?;
                    let _s = t.subscriber::<u64>(&format!("{prefix}/s{i}"))?;
                }
                Ok(())
            })
        };
        let (a, b) = (run("race-a"), run("race-b"));
        for h in [a, b] {
            match h.join() {
                Ok(r) => assert!(r.is_ok(), "{r:?}"),
                Err(_) => panic!("opening thread panicked"),
            }
        }
        let _ = std::fs::remove_dir_all(root_dir(&prefix));
    }

    /// Each prefix has a root of its own, and no prefix reaches outside the base.
    #[test]
    fn every_prefix_has_its_own_root_below_the_base() {
        let a = root_dir("game/1-2");
        assert_eq!(a, std::path::Path::new("/tmp/iceoryx2/robotino/game/1-2"));
        assert_ne!(a, root_dir("game/1-3"));
        let odd = root_dir("/../x y/.");
        assert_eq!(odd, std::path::Path::new("/tmp/iceoryx2/robotino/__/x_y/_"));
    }

    #[test]
    fn names_live_under_the_prefix() {
        let n = ServiceNames::new("test/x/");
        assert_eq!(n.robot(2, RobotStream::Motor), "test/x/robot2/motor");
        assert_eq!(n.team(TeamStream::Messages), "test/x/team/messages");
    }
}
