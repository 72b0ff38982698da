//! The host the fuzz-finding replays run with: it interrupts after the fuzz targets'
//! poll budget or time budget (agent-core/fuzz/fuzz_targets/common/cli.rs), so an
//! input that loops ends as it ends under the fuzzer.

#![allow(dead_code)]

use std::time::{Duration, Instant};

use agent_core::Host;

/// Polls answered before the host asks the engine to stop.
pub const POLL_BUDGET: u32 = 100_000;

/// Wall time after which the host asks the engine to stop (the fuzz targets': a
/// poll is a step, and steps can grow).
pub const TIME_BUDGET: Duration = Duration::from_secs(3);

/// Counts the engine's polls; true (stop) once past `POLL_BUDGET` or `TIME_BUDGET`
/// after it was made or rearmed.
pub struct Budget {
    pub polls: u32,
    deadline: Instant,
}

impl Budget {
    pub fn new() -> Self {
        Budget {
            polls: 0,
            deadline: Instant::now() + TIME_BUDGET,
        }
    }

    /// A new allowance of polls and time (the fuzz target's final `run`).
    pub fn rearm(&mut self) {
        *self = Budget::new();
    }
}

impl Host for Budget {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    fn interrupt(&mut self) -> bool {
        self.polls = self.polls.saturating_add(1);
        self.polls > POLL_BUDGET || Instant::now() >= self.deadline
    }
}
