//! What the image does, written once for the freestanding and the host build.
//!
//! Each fact is one line `agent-image: key=value ...`. Lines other tools read:
//! - `engine=present symbol=AGENT_ENGINE bytes=<n>` (footprint tool: arena share);
//! - `pool name=... high_water=... capacity=... bytes=...` per engine pool;
//! - `score=<n>` of the seeded game (the test script compares it with
//!   `robotino-agent sim --seed 0`);
//! - `stack_max_bytes=<n>` (printed by the entry point at exit, footprint tool).

use crate::game::{self, ImageEngine, QuietHost};
use core::fmt::{self, Write};
use core::hint::black_box;

/// Name under which the image exports its engine static. The footprint tool reports this
/// symbol's size as the engine arena's share of RAM.
pub const ENGINE_SYMBOL: &str = "AGENT_ENGINE";

/// Why a run failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunError {
    /// The output sink refused a line.
    Output,
    /// The freestanding runtime (memory functions, 64-bit arithmetic) misbehaved.
    SelfTest(&'static str),
    /// The engine was already taken (the image runs its game once).
    EngineTaken,
    /// The game could not be loaded or played; the line before says why.
    Game(&'static str),
}

impl From<fmt::Error> for RunError {
    fn from(_: fmt::Error) -> Self {
        RunError::Output
    }
}

/// Runs the image's work and reports it line by line on `out`. `build` names the build
/// (`i586-freestanding` or `host-std`); `engine` is the image's engine, fresh.
pub fn run(
    out: &mut impl Write,
    build: &str,
    engine: Option<&mut ImageEngine>,
) -> Result<(), RunError> {
    writeln!(out, "agent-image: build={build} heap=none")?;
    match runtime_self_test() {
        Ok(checks) => writeln!(out, "agent-image: runtime_selftest=ok checks={checks}")?,
        Err(step) => {
            writeln!(out, "agent-image: runtime_selftest=failed step={step}")?;
            return Err(RunError::SelfTest(step));
        }
    }
    ballast::report(out)?;
    let Some(engine) = engine else {
        writeln!(out, "agent-image: engine=taken symbol={ENGINE_SYMBOL}")?;
        return Err(RunError::EngineTaken);
    };
    writeln!(
        out,
        "agent-image: engine=present symbol={ENGINE_SYMBOL} bytes={}",
        core::mem::size_of::<ImageEngine>()
    )?;
    rules_line(out)?;
    let (strategy, seeds) = game::SIZED_FOR;
    writeln!(
        out,
        "agent-image: pools_sized_for strategy={} seeds={}..{}",
        strategy.name(),
        seeds.start,
        seeds.end
    )?;
    let mut host = QuietHost::new();
    let played = game::play(engine, &mut host);
    if host.bytes > 0 {
        writeln!(
            out,
            "agent-image: engine_output_bytes={} first={:?}",
            host.bytes,
            host.first.as_str()
        )?;
    }
    game::write_pools(out, &engine.stats())?;
    match played {
        Ok(result) => {
            writeln!(
                out,
                "agent-image: game seed={} strategy={} fired={} decisions={} end={}",
                game::SEED,
                game::STRATEGY.name(),
                result.fired,
                result.decisions,
                result.end.map_or("none", |e| e.as_str())
            )?;
            writeln!(out, "agent-image: score={}", result.score)?;
            Ok(())
        }
        Err(error) => {
            writeln!(out, "agent-image: game=failed error=\"{error}\"")?;
            Err(RunError::Game(error.step))
        }
    }
}

/// The game's rule base, compiled ahead of time (`rules_compiled`): what it holds.
fn rules_line(out: &mut impl Write) -> fmt::Result {
    match rules_compiled::game(game::STRATEGY.name()) {
        Some(base) => writeln!(
            out,
            "agent-image: rules=compiled strategy={} rules={} joins={} alpha_nodes={} exprs={} symbols={}",
            game::STRATEGY.name(),
            base.rules.len(),
            base.joins.len(),
            base.alphas.len(),
            base.exprs.len(),
            base.symbols.len()
        ),
        None => writeln!(out, "agent-image: rules=missing strategy={}", game::STRATEGY.name()),
    }
}

/// Exercises what the freestanding build provides itself: memset, memcpy, memmove,
/// memcmp/bcmp and 64-bit division (from compiler_builtins). Lengths pass through
/// `black_box` so the calls really happen. Returns the number of checks passed.
/// Not inlined: its buffers stay off the stack frame the game runs below.
#[inline(never)]
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
    use std::boxed::Box;
    use std::string::String;

    fn fresh_engine() -> Box<ImageEngine> {
        Box::new(ImageEngine::with_storage(game::ImageStorage::new()))
    }

    #[test]
    fn plays_the_seeded_game_and_reports_it() {
        let mut engine = fresh_engine();
        let mut text = String::new();
        run(&mut text, "host-std", Some(&mut engine)).expect("the game plays");
        assert!(text.starts_with("agent-image: build=host-std heap=none\n"));
        assert!(text.contains("engine=present symbol=AGENT_ENGINE"));
        assert!(text.contains("runtime_selftest=ok checks=6"));
        // every pool reported, none over its capacity
        let pools: std::vec::Vec<&str> = text.lines().filter(|l| l.contains(" pool ")).collect();
        assert_eq!(pools.len(), agent_core::Pool::ALL.len());
        let score = text
            .lines()
            .find_map(|l| l.strip_prefix("agent-image: score="))
            .expect("a score line");
        assert!(score.parse::<i64>().expect("a number") > 0, "{text}");
        assert!(
            text.contains(" end=done") || text.contains(" end=time"),
            "{text}"
        );
        assert!(
            !text.contains("engine_output_bytes"),
            "the game printed: {text}"
        );
        assert!(text.lines().all(|line| line.starts_with("agent-image: ")));
    }

    /// The pools hold every game the image is sized for (`game::SIZED_FOR`): each
    /// plays to its end without an error (running out of a pool is one, printed on
    /// the error router), within the capacities' stated margins of its high-water
    /// marks.
    #[test]
    fn every_game_it_is_sized_for() {
        use agent_core::Pool;
        let (strategy, seeds) = game::SIZED_FOR;
        let mut most = [0u32; Pool::COUNT];
        for seed in seeds {
            let mut engine = fresh_engine();
            let mut host = QuietHost::new();
            let result = game::play_seed(&mut engine, &mut host, strategy, seed)
                .unwrap_or_else(|e| panic!("seed {seed}: {e}: {}", host.first.as_str()));
            assert_eq!(host.bytes, 0, "seed {seed}: {}", host.first.as_str());
            assert!(
                matches!(
                    result.end,
                    Some(game::EndReason::Time | game::EndReason::Done)
                ),
                "seed {seed}: {result:?}"
            );
            let stats = engine.stats();
            for pool in Pool::ALL {
                most[pool as usize] = most[pool as usize].max(stats.get(pool).0);
            }
        }
        // the margins the capacities claim (game.rs): 10 % for facts and tokens
        let stats = fresh_engine().stats();
        for pool in [Pool::Facts, Pool::Tokens] {
            let capacity = stats.get(pool).1;
            assert!(
                most[pool as usize] * 11 <= capacity * 10 + 10,
                "{pool:?}: {} of {capacity}",
                most[pool as usize]
            );
        }
    }

    #[test]
    fn without_the_engine_it_says_so() {
        let mut text = String::new();
        assert_eq!(run(&mut text, "host-std", None), Err(RunError::EngineTaken));
        assert!(text.contains("engine=taken"));
    }

    #[test]
    fn the_static_engine_is_handed_out_once() {
        assert!(game::AGENT_ENGINE.try_take().is_some());
        assert!(game::AGENT_ENGINE.try_take().is_none());
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
        let mut engine = fresh_engine();
        assert_eq!(
            run(&mut FailingSink { left: 3 }, "host-std", Some(&mut engine)),
            Err(RunError::Output)
        );
    }
}
