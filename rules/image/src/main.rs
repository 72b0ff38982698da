//! The agent image: the engine with its static arena and the agent rule base in one
//! executable for the Robotino's AMD Geode LX800.
//!
//! Built for `i586-unknown-linux-gnu` (cfg `freestanding`, set by `build.rs`) it is
//! `no_std`/`no_main`: no libc, no heap, `panic = "abort"` (profile `image`), its own
//! `_start` that paints the stack, and Linux `int 0x80` syscalls. It runs under
//! `qemu-i386 -cpu pentium`. On the host the same crate is an ordinary std program doing
//! the same work, so `cargo clippy --workspace --all-targets` and unit tests cover it.
//!
//! Output is one `agent-image: key=value ...` line per fact, for people and for the
//! footprint tool (which reads `stack_max_bytes=`). See `report` for the lines.
//!
//! The whole crate is `no_builtins`: its hand-written `memcpy` and friends must not be
//! compiled into calls to themselves.
#![cfg_attr(all(freestanding, not(test)), no_std, no_main)]
#![no_builtins]

// The prebuilt `core` unwinds by default; a freestanding image cannot. Say so plainly
// instead of rustc's "unwinding panics are not supported without std".
#[cfg(all(freestanding, not(test), not(panic = "abort")))]
compile_error!(
    "agent-image for i586 is freestanding and needs panic = \"abort\": build it with `--profile image`"
);

mod game;
mod report;
// Only the freestanding build paints its stack; host tests cover the measuring logic.
#[cfg(any(freestanding, test))]
mod stack_paint;

#[cfg(all(freestanding, not(test)))]
mod freestanding;

/// Host build: the same report, written to stdout; the stack is not painted here.
#[cfg(not(all(freestanding, not(test))))]
fn main() -> std::process::ExitCode {
    use std::io::Write as _;

    let mut text = String::new();
    let outcome = report::run(&mut text, "host-std", game::AGENT_ENGINE.try_take());
    let stack_line =
        "agent-image: stack_max_bytes=unmeasured reason=\"host build does not paint its stack\"";
    let mut stdout = std::io::stdout().lock();
    let written = writeln!(stdout, "{text}{stack_line}");
    match (outcome, written) {
        (Ok(()), Ok(())) => std::process::ExitCode::SUCCESS,
        _ => std::process::ExitCode::FAILURE,
    }
}
