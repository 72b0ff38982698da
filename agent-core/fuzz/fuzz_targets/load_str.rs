//! The CLIPS parser and loader on arbitrary text: `load_str` must return (a value or an
//! error), never panic, and leave a consistent engine (`check_invariants`) whatever it
//! loaded, also after a `reset`. Seeds: tests/clips/*.clp, tests/clips-errors.
#![no_main]

use agent_core::{Host, SmallEngine};
use libfuzzer_sys::fuzz_target;

/// Drops output and interrupts once polled `POLL_BUDGET` times (one poll per loop
/// iteration or rule firing), so a text that loops forever at reset ends.
struct Budget(u32);

const POLL_BUDGET: u32 = 100_000;

impl Host for Budget {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    fn interrupt(&mut self) -> bool {
        self.0 = self.0.saturating_add(1);
        self.0 > POLL_BUDGET
    }
}

fuzz_target!(|data: &[u8]| {
    // invalid UTF-8 is replaced, so byte-level mutations still reach the lexer
    let text = String::from_utf8_lossy(data);
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Budget(0);
    let r = e.load_str(h, "fuzz", &text);
    if let Err(v) = e.check_invariants() {
        panic!("after load_str ({r:?}): {v}");
    }
    // what loaded must survive a reset (deffacts, globals; a looping one is interrupted);
    // running rules is the engine_commands target's job
    let r = e.reset(h);
    if let Err(v) = e.check_invariants() {
        panic!("after reset ({r:?}): {v}");
    }
});
