//! Test helpers: a capturing host and one-line evaluation.

extern crate std;
use std::string::String;

use crate::engine::SmallEngine;
use crate::host::Host;

/// Collects all router output into one string.
#[derive(Default)]
pub struct CaptureHost {
    pub out: String,
}

impl Host for CaptureHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.out.push_str(text);
    }
}

/// Evaluates one expression on a fresh small engine and returns what the CLIPS prompt
/// would print for the result.
pub fn eval_to_string(expr: &str) -> String {
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut h = CaptureHost::default();
    e.exec_command(&mut h, expr, "test");
    h.out.trim_end_matches('\n').into()
}

/// Runs a batch program (no echo) on a fresh small engine; returns all output.
pub fn run_program(src: &str) -> String {
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut h = CaptureHost::default();
    e.batch_str(&mut h, src, false);
    h.out
}
