//! Command text as `robotino-agent clips -f` runs it (batch mode, echo and results
//! printed), on the command line's engine (`GrowEngine`, its depth limits, its stack
//! shape) after a small valid rule base: commands, constructs, `run`, `eval`, `build`,
//! whatever the bytes say. Must return, never panic, and leave a consistent engine;
//! then the agenda is run (at most `RUN_LIMIT` firings) and checked again. Runaway
//! loops end by the host's budget (polls and time). Seeds: tests/clips/*.clp.
#![no_main]

#[path = "common/cli.rs"]
mod cli;

use libfuzzer_sys::fuzz_target;

/// Firings of the final `run`.
const RUN_LIMIT: u32 = 1_000;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    cli::on_engine_stack(move || {
        let h = &mut cli::Budget::default();
        let mut e = cli::with_prelude(h);
        e.batch_str(h, &text, true);
        cli::check(&mut e, "batch_str");
        if !e.exited() {
            h.rearm();
            let r = e.run(h, Some(RUN_LIMIT));
            if let Err(v) = e.check_invariants() {
                panic!("after run ({r:?}): {v}");
            }
        }
    });
});
