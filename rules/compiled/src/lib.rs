//! The agent's rule bases compiled ahead of time (`no_std`): every construct of a
//! simulated game's rule files (one per strategy) as read-only Rust constants that
//! `agent_core::Engine::load_compiled` puts into an engine, with no parser and no
//! rule text. `build.rs` writes them with the engine's writer
//! (`Engine::write_compiled`); see `agent_core::compiled` for the form.
//!
//! Also the constructs of every differential program (`tests/clips`), for the test
//! that runs each program from its compiled form and from its text
//! (`tests/same_as_parsed.rs`).
#![no_std]
// generated tables: long, and written for every engine configuration
#![allow(clippy::all)]

include!(concat!(env!("OUT_DIR"), "/compiled.rs"));

use agent_core::compiled::RuleBase;

/// The compiled rule base of a simulated game with `strategy`'s agent (the files of
/// `rules::game_files`, in that order).
pub fn game(strategy: &str) -> Option<&'static RuleBase> {
    match strategy {
        "naive" => Some(&game_naive::BASE),
        "paper" => Some(&game_paper::BASE),
        "travel" => Some(&game_travel::BASE),
        _ => None,
    }
}
