//! Which rule files each load consists of, by name, in load order.
//!
//! The single source of the load orders: `lib.rs` turns these names into the embedded
//! files ([`crate::agent_files`], [`crate::game_files`]), and `build.rs` includes this
//! module (`#[path]`) to load the same files in the same order into the engine and
//! reject a rule file that does not parse.

/// The agent with the naive baseline strategy.
pub const AGENT_NAIVE: &[&str] = &[
    "utils.clp",
    "worldmodel.clp",
    "execution.clp",
    "production-common.clp",
    "production-naive.clp",
];
/// The agent with the paper's strategy.
pub const AGENT_PAPER: &[&str] = &[
    "utils.clp",
    "worldmodel.clp",
    "execution.clp",
    "production-common.clp",
    "production.clp",
    "select-paper.clp",
];
/// The agent with our travel-aware strategy.
pub const AGENT_TRAVEL: &[&str] = &[
    "utils.clp",
    "worldmodel.clp",
    "execution.clp",
    "production-common.clp",
    "production.clp",
    "select-travel.clp",
];
/// What a host driver loads after the agent: the referee and the decision log.
pub const DRIVER: &[&str] = &["referee.clp", "game-log.clp"];
/// What a simulated game loads after the driver files: the instant simulation and
/// the snapshots after every decision.
pub const SIM: &[&str] = &["sim.clp", "snapshot.clp"];
/// What an agent on the robot's body (`run`) loads after its agent: leaving a working
/// T3 and collecting its product later.
pub const BODY: &[&str] = &["collect.clp"];
/// What a robot of a team loads after its agent: the claims protocol.
pub const TEAM: &[&str] = &["team.clp"];
/// What a team member's agent loads after `TEAM`: claims before commitments, news.
pub const TEAM_AGENT: &[&str] = &["team-agent.clp"];

/// Every agent, by strategy name (as `Strategy::name` spells it).
pub const AGENTS: [(&str, &[&str]); 3] = [
    ("naive", AGENT_NAIVE),
    ("paper", AGENT_PAPER),
    ("travel", AGENT_TRAVEL),
];

/// Functions a host registers (`Engine::register_function`) before loading the rule
/// files, with their least and most number of arguments (None: any number). The rule
/// files may call them; `build.rs` registers stand-ins of these names and arities, so
/// a call with an unknown name or a wrong number of arguments still fails the build.
/// Our engine has the geometry functions (`distance`, ...) built in, so none is needed
/// today.
pub const HOST_FUNCTIONS: &[(&str, u8, Option<u8>)] = &[];
