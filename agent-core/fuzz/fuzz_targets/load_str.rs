//! The CLIPS parser and loader on arbitrary text: `load_str` must return (a value or an
//! error), never panic, and leave a consistent engine (`check_invariants`) whatever it
//! loaded, also after a `reset`. Seeds: tests/clips/*.clp, tests/clips-errors.
#![no_main]

use agent_core::{NullHost, SmallEngine};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // invalid UTF-8 is replaced, so byte-level mutations still reach the lexer
    let text = String::from_utf8_lossy(data);
    let mut e = Box::new(SmallEngine::new());
    let h = &mut NullHost;
    let r = e.load_str(h, "fuzz", &text);
    if let Err(v) = e.check_invariants() {
        panic!("after load_str ({r:?}): {v}");
    }
    // what loaded must survive a reset (deffacts, globals); running rules is the
    // engine_commands target's job (arbitrary right-hand sides may loop forever)
    let r = e.reset(h);
    if let Err(v) = e.check_invariants() {
        panic!("after reset ({r:?}): {v}");
    }
});
