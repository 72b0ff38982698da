//! The robot-to-robot link over Zenoh: each robot's agent
//! publishes its team messages on `PREFIX/team/ROBOT` and subscribes to `PREFIX/team/*`.
//! Peers meet on explicit endpoints (`tcp/HOST:PORT`), never by scouting (multicast
//! does not cross containers or most WiFi setups). Zenoh with default features off and
//! TCP only. Messages travel as JSON; a robot ignores its own.

use std::time::Duration;

use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::Subscriber;
use zenoh::sample::Sample;
use zenoh::{Session, Wait};

use host_shim::team::{TeamLink, TeamMsg};

/// What went wrong on the link.
#[derive(Debug)]
pub struct LinkError(pub String);

impl std::fmt::Display for LinkError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "team link: {}", self.0)
    }
}

impl std::error::Error for LinkError {}

fn err(what: &str, e: impl std::fmt::Display) -> LinkError {
    LinkError(format!("{what}: {e}"))
}

/// One robot's end of the team link.
pub struct ZenohLink {
    robot: u8,
    session: Session,
    key: String,
    subscriber: Subscriber<FifoChannelHandler<Sample>>,
}

impl ZenohLink {
    /// Opens a peer session listening on `listen` and connecting to `connect` (endpoints
    /// like `tcp/127.0.0.1:7447`), scouting off, and subscribes to the team's messages
    /// under `prefix`.
    pub fn open(
        robot: u8,
        prefix: &str,
        listen: &[String],
        connect: &[String],
    ) -> Result<ZenohLink, LinkError> {
        let mut config = zenoh::Config::default();
        let json = |v: &[String]| serde_json::to_string(v).unwrap_or_else(|_| "[]".into());
        for (key, value) in [
            ("mode", "\"peer\"".to_string()),
            ("scouting/multicast/enabled", "false".to_string()),
            ("scouting/gossip/enabled", "false".to_string()),
            ("listen/endpoints", json(listen)),
            ("connect/endpoints", json(connect)),
        ] {
            config
                .insert_json5(key, &value)
                .map_err(|e| err(&format!("config {key}={value}"), e))?;
        }
        let session = zenoh::open(config).wait().map_err(|e| err("opening", e))?;
        let subscriber = session
            .declare_subscriber(format!("{prefix}/team/*"))
            .wait()
            .map_err(|e| err("subscribing", e))?;
        Ok(ZenohLink {
            robot,
            session,
            key: format!("{prefix}/team/{robot}"),
            subscriber,
        })
    }

    /// Sends one of this robot's messages to the team.
    pub fn send(&self, msg: &TeamMsg) -> Result<(), LinkError> {
        let text = serde_json::to_string(msg).map_err(|e| err("encoding", e))?;
        self.session
            .put(&self.key, text)
            .wait()
            .map_err(|e| err("publishing", e))
    }

    /// The teammates' messages that have arrived, waiting up to `wait` for the first.
    pub fn receive(&self, wait: Duration) -> Result<Vec<TeamMsg>, LinkError> {
        let mut out = Vec::new();
        let first = self
            .subscriber
            .recv_timeout(wait)
            .map_err(|e| err("receiving", e))?;
        let mut next = first;
        while let Some(sample) = next {
            let bytes = sample.payload().to_bytes();
            let msg: TeamMsg = serde_json::from_slice(&bytes).map_err(|e| err("decoding", e))?;
            if msg.from != self.robot {
                out.push(msg);
            }
            next = self
                .subscriber
                .try_recv()
                .map_err(|e| err("receiving", e))?;
        }
        Ok(out)
    }
}

/// The agent loop's team link over Zenoh (`robotino-agent-zenoh`): no lockstep between
/// machines, so the cycle is ignored and whatever has arrived is handed in; the team's
/// rules stay correct under the delays, losses and reordering that brings.
impl TeamLink for ZenohLink {
    fn send(&mut self, _cycle: u64, msgs: &[TeamMsg]) -> Result<(), host_shim::team::LinkError> {
        for m in msgs {
            ZenohLink::send(self, m).map_err(|e| host_shim::team::LinkError(e.to_string()))?;
        }
        Ok(())
    }

    fn receive(&mut self, _cycle: u64) -> Result<Vec<TeamMsg>, host_shim::team::LinkError> {
        ZenohLink::receive(self, Duration::ZERO)
            .map_err(|e| host_shim::team::LinkError(e.to_string()))
    }
}
