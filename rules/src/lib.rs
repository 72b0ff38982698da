//! The LLSF agent rule base, embedded as CLIPS text (`no_std`).
//!
//! The `.clp` files next to this crate are the product: the agent (utilities,
//! world model, execution monitoring, production), the referee (the game
//! model), and the instant simulation.  This crate only embeds them as
//! `&'static str` and says which to load in which order
//! ([`agent_files`], [`game_files`]), plus [`setup`]: the deterministic
//! per-seed game setups the host asserts as facts.  The fact interface
//! between host, agent, referee and simulation is documented in README.md.
#![no_std]

pub mod facts;
mod minify;
pub mod order;
pub mod setup;
pub mod setup_facts;

/// One embedded rule file: its path relative to `rules/` and its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RuleFile {
    pub name: &'static str,
    pub text: &'static str,
}

macro_rules! rule_file {
    ($path:literal) => {
        RuleFile {
            name: $path,
            text: include_str!(concat!("../", $path)),
        }
    };
}

/// A rule file minified at compile time (see `minify`): only the minified bytes are
/// embedded where this is used.
macro_rules! min_rule_file {
    ($path:literal) => {{
        const LEN: usize = crate::minify::minified_len(include_str!(concat!("../", $path)));
        const BYTES: [u8; LEN] = crate::minify::minify::<LEN>(include_str!(concat!("../", $path)));
        RuleFile {
            name: $path,
            text: match core::str::from_utf8(&BYTES) {
                Ok(text) => text,
                Err(_) => panic!("minified rule text is not UTF-8"),
            },
        }
    }};
}

/// Priorities (saliences) and helper functions; load first.
pub const UTILS: RuleFile = rule_file!("utils.clp");
/// Machine beliefs and their updates from perceived lights.
pub const WORLD_MODEL: RuleFile = rule_file!("worldmodel.clp");
/// Skill requests and outcomes, failure handling.
pub const EXECUTION: RuleFile = rule_file!("execution.clp");
/// Production steps all strategies share (fetch, deliver, discard).
pub const PRODUCTION_COMMON: RuleFile = rule_file!("production-common.clp");
/// The paper's candidate rules with machine priorities.
pub const PRODUCTION: RuleFile = rule_file!("production.clp");
/// The paper's commitment: first candidate in machine-name order.
pub const SELECT_PAPER: RuleFile = rule_file!("select-paper.clp");
/// Our commitment: the nearest candidate (ties by machine name).
pub const SELECT_TRAVEL: RuleFile = rule_file!("select-travel.clp");
/// The naive baseline: fixed machine order, no priorities.
pub const PRODUCTION_NAIVE: RuleFile = rule_file!("production-naive.clp");
/// The game model: hidden types, lights, supply, clock, score.
pub const REFEREE: RuleFile = rule_file!("referee.clp");
/// Decision log and end of game, for any executor (sim or robot driver).
pub const GAME_LOG: RuleFile = rule_file!("game-log.clp");
/// Instant skill execution against the referee.
pub const SIM: RuleFile = rule_file!("sim.clp");
/// A snapshot of the fact base after every decision (with a snapshot-file fact).
pub const SNAPSHOT: RuleFile = rule_file!("snapshot.clp");
/// A robot on the field leaves a working T3 and collects the P later (`run` only).
pub const COLLECT: RuleFile = rule_file!("collect.clp");
/// The team's claims on machines, input storage and gates (one engine per robot).
pub const TEAM: RuleFile = rule_file!("team.clp");
/// The agent as a team member: claim before committing, news of worked machines.
pub const TEAM_AGENT: RuleFile = rule_file!("team-agent.clp");
/// Real-CLIPS stand-ins for host functions (`distance`); our engine has
/// them built in, so hosts running our engine do not load this.
pub const CLIPS_STUBS: RuleFile = rule_file!("clips/stubs.clp");

/// Which production strategy the agent plays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// Fixed exploration order, no priorities: the baseline.
    Naive,
    /// The paper's machine priorities, ties by machine name.
    Paper,
    /// The paper's priorities, equal-priority ties by travel distance.
    Travel,
}

impl Strategy {
    pub const ALL: [Strategy; 3] = [Strategy::Naive, Strategy::Paper, Strategy::Travel];

    /// The name hosts use on command lines.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Naive => "naive",
            Strategy::Paper => "paper",
            Strategy::Travel => "travel",
        }
    }

    /// Parses [`Strategy::name`] back.
    pub fn from_name(name: &str) -> Option<Strategy> {
        Strategy::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// Every embedded file, to look the names of [`order`] up.
const ALL: [RuleFile; 13] = [
    UTILS,
    WORLD_MODEL,
    EXECUTION,
    PRODUCTION_COMMON,
    PRODUCTION,
    SELECT_PAPER,
    SELECT_TRAVEL,
    PRODUCTION_NAIVE,
    REFEREE,
    GAME_LOG,
    SIM,
    SNAPSHOT,
    CLIPS_STUBS,
];

// (agent-core has the same helper; this crate stays free of dependencies)
const fn same_text(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The file of `all` called `name`; an unknown name stops the compilation.
const fn by_name(all: &[RuleFile], name: &str) -> RuleFile {
    let mut i = 0;
    while i < all.len() {
        if same_text(all[i].name, name) {
            return all[i];
        }
        i += 1;
    }
    panic!("rules/src/order.rs names a file that lib.rs does not embed")
}

/// The files named by `parts`, one after the other; `N` must be their total count
/// (checked at compile time).
const fn load<const N: usize>(parts: &[&[&str]]) -> [RuleFile; N] {
    load_from(&ALL, parts)
}

/// `load` from the files of `all`.
const fn load_from<const N: usize>(all: &[RuleFile], parts: &[&[&str]]) -> [RuleFile; N] {
    let mut out = [UTILS; N];
    let mut k = 0;
    let mut p = 0;
    while p < parts.len() {
        let mut i = 0;
        while i < parts[p].len() {
            assert!(k < N, "load order longer than its array");
            out[k] = by_name(all, parts[p][i]);
            k += 1;
            i += 1;
        }
        p += 1;
    }
    assert!(k == N, "load order shorter than its array");
    out
}

const AGENT_NAIVE: [RuleFile; 5] = load(&[order::AGENT_NAIVE]);
const AGENT_PAPER: [RuleFile; 6] = load(&[order::AGENT_PAPER]);
const AGENT_TRAVEL: [RuleFile; 6] = load(&[order::AGENT_TRAVEL]);
const GAME_NAIVE: [RuleFile; 9] = load(&[order::AGENT_NAIVE, order::DRIVER, order::SIM]);
const GAME_PAPER: [RuleFile; 10] = load(&[order::AGENT_PAPER, order::DRIVER, order::SIM]);
const GAME_TRAVEL: [RuleFile; 10] = load(&[order::AGENT_TRAVEL, order::DRIVER, order::SIM]);

/// The agent alone (for a robot driver), in load order.
pub fn agent_files(strategy: Strategy) -> &'static [RuleFile] {
    match strategy {
        Strategy::Naive => &AGENT_NAIVE,
        Strategy::Paper => &AGENT_PAPER,
        Strategy::Travel => &AGENT_TRAVEL,
    }
}

/// What a host driver that moves the robot itself loads after
/// [`agent_files`]: the referee and the decision log (not the instant sim).
pub const DRIVER_FILES: [RuleFile; 2] = load(&[order::DRIVER]);

/// Agent, referee, log and simulation: a whole simulated game, in load order.
/// Load these, then the setup text ([`setup::GameSetup::write_clips`]),
/// then `(reset)` and `(run)`.
pub fn game_files(strategy: Strategy) -> &'static [RuleFile] {
    match strategy {
        Strategy::Naive => &GAME_NAIVE,
        Strategy::Paper => &GAME_PAPER,
        Strategy::Travel => &GAME_TRAVEL,
    }
}

/// The rule files as the agent image embeds them: minified (no comments, whitespace
/// runs collapsed; see `minify`), loading into the same constructs.
pub mod minified {
    use super::{load_from, order, RuleFile, Strategy};

    const ALL: [RuleFile; 12] = [
        min_rule_file!("utils.clp"),
        min_rule_file!("worldmodel.clp"),
        min_rule_file!("execution.clp"),
        min_rule_file!("production-common.clp"),
        min_rule_file!("production.clp"),
        min_rule_file!("select-paper.clp"),
        min_rule_file!("select-travel.clp"),
        min_rule_file!("production-naive.clp"),
        min_rule_file!("referee.clp"),
        min_rule_file!("game-log.clp"),
        min_rule_file!("sim.clp"),
        min_rule_file!("snapshot.clp"),
    ];
    const GAME_NAIVE: [RuleFile; 9] =
        load_from(&ALL, &[order::AGENT_NAIVE, order::DRIVER, order::SIM]);
    const GAME_PAPER: [RuleFile; 10] =
        load_from(&ALL, &[order::AGENT_PAPER, order::DRIVER, order::SIM]);
    const GAME_TRAVEL: [RuleFile; 10] =
        load_from(&ALL, &[order::AGENT_TRAVEL, order::DRIVER, order::SIM]);

    /// [`super::game_files`], minified.
    pub fn game_files(strategy: Strategy) -> &'static [RuleFile] {
        match strategy {
            Strategy::Naive => &GAME_NAIVE,
            Strategy::Paper => &GAME_PAPER,
            Strategy::Travel => &GAME_TRAVEL,
        }
    }
}

#[cfg(test)]
mod tests;
