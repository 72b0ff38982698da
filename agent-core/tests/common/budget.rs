//! The host the fuzz-finding replays run with: it interrupts after the fuzz targets'
//! poll budget, so an input that loops ends as it ends under the fuzzer.

#![allow(dead_code)]

use agent_core::Host;

/// Polls answered before the host asks the engine to stop.
pub const POLL_BUDGET: u32 = 100_000;

/// Counts the engine's polls; true (stop) once past `POLL_BUDGET`.
pub struct Budget(pub u32);

impl Host for Budget {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    fn interrupt(&mut self) -> bool {
        self.0 = self.0.saturating_add(1);
        self.0 > POLL_BUDGET
    }
}
