//! What the image does, written once for the freestanding and the host build.
//!
//! Each fact is one line `agent-image: key=value ...`. Today the image does not hold the
//! engine yet and so loads no rules; it says so instead of pretending. The hooks below mark
//! where the engine and the game slot in. Lines other tools read:
//! - `engine=absent|present` and the exported symbol's name (footprint tool: arena share);
//! - `rules=embedded loaded=no|yes` with the agent text size per strategy;
//! - `score=<n>` once the image plays the seeded game (test script compares it with
//!   `robotino-agent sim --seed 0`);
//! - `stack_max_bytes=<n>` (printed by the entry point at exit, footprint tool).

use core::fmt::{self, Write};
use core::hint::black_box;

/// Name under which the image exports its engine static. The footprint tool reports this
/// symbol's size as the engine arena's share of RAM, and the arena as absent while the
/// symbol is missing.
pub const ENGINE_SYMBOL: &str = "AGENT_ENGINE";

// ENGINE HOOK: once `agent_core::Engine` exists (a `const fn new()` type that owns its arena),
// export it here under the fixed name, so it lands in .bss/.data and the footprint tool can
// measure it:
//
//     #[no_mangle]
//     static AGENT_ENGINE: agent_core::Engine = agent_core::Engine::new();
//
// (behind whatever interior-mutability wrapper the engine's API needs), then report
// `engine=present bytes=<size_of::<Engine>()>` in `engine_line`.
//
// RULES HOOK: with the engine in place, load `rules::agent_files(strategy)` (or
// `rules::game_files` for the simulated game) into it here and report `loaded=yes`.
//
// SCORE HOOK: once the image plays the seeded game, print `agent-image: score=<n>`; the test
// script then compares it with the score of `robotino-agent sim --seed 0`.

/// Why a run failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunError {
    /// The output sink refused a line.
    Output,
    /// The freestanding runtime (memory functions, 64-bit arithmetic) misbehaved.
    SelfTest(&'static str),
}

impl From<fmt::Error> for RunError {
    fn from(_: fmt::Error) -> Self {
        RunError::Output
    }
}

/// Runs the image's work and reports it line by line on `out`. `build` names the build
/// (`i586-freestanding` or `host-std`).
pub fn run(out: &mut impl Write, build: &str) -> Result<(), RunError> {
    writeln!(out, "agent-image: build={build} heap=none")?;
    writeln!(
        out,
        "agent-image: engine=absent symbol={ENGINE_SYMBOL} reason=\"the image does not instantiate agent_core::Engine yet\""
    )?;
    rules_line(out)?;
    match runtime_self_test() {
        Ok(checks) => writeln!(out, "agent-image: runtime_selftest=ok checks={checks}")?,
        Err(step) => {
            writeln!(out, "agent-image: runtime_selftest=failed step={step}")?;
            return Err(RunError::SelfTest(step));
        }
    }
    ballast::report(out)?;
    writeln!(
        out,
        "agent-image: score=absent reason=\"needs the engine and the rule base\""
    )?;
    Ok(())
}

/// The agent rule base from the `rules` crate: which strategies exist and how much CLIPS
/// text each agent has. Nothing is loaded while the image has no engine.
fn rules_line(out: &mut impl Write) -> fmt::Result {
    write!(
        out,
        "agent-image: rules=embedded loaded=no agent_text_bytes="
    )?;
    for (i, strategy) in rules::Strategy::ALL.iter().enumerate() {
        let files = rules::agent_files(*strategy);
        let bytes: usize = files.iter().map(|file| file.text.len()).sum();
        let separator = if i == 0 { "" } else { "," };
        write!(out, "{separator}{}:{bytes}", strategy.name())?;
    }
    writeln!(
        out,
        " reason=\"no engine in the image to load them into yet\""
    )
}

/// Exercises what the freestanding build provides itself: memset, memcpy, memmove,
/// memcmp/bcmp and 64-bit division (from compiler_builtins). Lengths pass through
/// `black_box` so the calls really happen. Returns the number of checks passed.
fn runtime_self_test() -> Result<u32, &'static str> {
    let len = black_box(64usize);
    let mut a = [0u8; 64];
    let mut b = [0u8; 64];

    a[..len].fill(black_box(0xA5));
    if a.iter().any(|&x| x != 0xA5) {
        return Err("memset");
    }
    for (i, x) in a.iter_mut().enumerate() {
        *x = i as u8;
    }
    b[..len].copy_from_slice(&a[..len]);
    if a[..len] != b[..len] {
        return Err("memcpy-or-memcmp");
    }
    // Overlapping move upwards: the overlap must be copied from the original bytes.
    b.copy_within(0..len - 8, 8);
    if b[8..].iter().enumerate().any(|(i, &x)| x != i as u8) {
        return Err("memmove");
    }
    b[len - 1] ^= 1;
    if a[..len] == b[..len] {
        return Err("memcmp-missed-difference");
    }

    let dividend = black_box(10_000_000_007u64);
    let divisor = black_box(7u64);
    let (quotient, remainder) = (dividend / divisor, dividend % divisor);
    if quotient * divisor + remainder != dividend || remainder >= divisor {
        return Err("u64-division");
    }
    Ok(6)
}

/// The `oversize` test feature: a static array in RAM that the footprint gate must reject.
mod ballast {
    use core::fmt::{self, Write};

    #[cfg(feature = "oversize")]
    pub fn report(out: &mut impl Write) -> fmt::Result {
        use core::sync::atomic::{AtomicU8, Ordering};

        const BYTES: usize = 96 * 1024;
        // Atomics make it writable data (.bss), like an engine arena; touching one element
        // through `black_box` keeps the linker from dropping it.
        static BALLAST: [AtomicU8; BYTES] = [const { AtomicU8::new(0) }; BYTES];
        let cell = &BALLAST[core::hint::black_box(BYTES - 1)];
        cell.store(1, Ordering::Relaxed);
        let touched = cell.load(Ordering::Relaxed);
        writeln!(
            out,
            "agent-image: oversize_ballast_bytes={BYTES} touched={touched} (test feature: the footprint gate must fail)"
        )
    }

    #[cfg(not(feature = "oversize"))]
    pub fn report(_out: &mut impl Write) -> fmt::Result {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_every_component_and_its_state() {
        let mut text = String::new();
        run(&mut text, "host-std").expect("writing to a String cannot fail");
        assert!(text.starts_with("agent-image: build=host-std heap=none\n"));
        assert!(text.contains("engine=absent symbol=AGENT_ENGINE"));
        // The rule base's text sizes come from the `rules` crate, not from this file.
        let travel: usize = rules::agent_files(rules::Strategy::Travel)
            .iter()
            .map(|f| f.text.len())
            .sum();
        assert!(travel > 0);
        assert!(
            text.contains(&format!("travel:{travel} ")),
            "rule base sizes missing: {text}"
        );
        assert!(text.contains("rules=embedded loaded=no"));
        assert!(text.contains("runtime_selftest=ok checks=6"));
        assert!(text.contains("score=absent"));
        assert!(text.lines().all(|line| line.starts_with("agent-image: ")));
    }

    /// A sink that fails after `left` writes, to show errors propagate instead of vanishing.
    struct FailingSink {
        left: u32,
    }

    impl Write for FailingSink {
        fn write_str(&mut self, _: &str) -> fmt::Result {
            if self.left == 0 {
                return Err(fmt::Error);
            }
            self.left -= 1;
            Ok(())
        }
    }

    #[test]
    fn a_refusing_sink_is_an_error() {
        assert_eq!(
            run(&mut FailingSink { left: 3 }, "host-std"),
            Err(RunError::Output)
        );
    }
}
