//! The ahead-of-time writer on whatever the parser accepted: arbitrary text loaded into
//! a fresh engine (the command line's), then `write_compiled`. Must return a value or
//! an error, never panic; what it writes names the module's `BASE`.
#![no_main]

#[path = "common/cli.rs"]
mod cli;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    cli::on_engine_stack(move || {
        let h = &mut cli::Budget::default();
        let mut e = cli::engine();
        let _ = e.load_str(h, "fuzz", &text);
        let mut out = String::new();
        if e.write_compiled("fuzz_base", "fuzz.clp", &mut out).is_ok() {
            assert!(out.contains("BASE"), "written without a BASE: {out}");
        }
    });
});
