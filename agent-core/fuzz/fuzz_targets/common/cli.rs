//! What the targets that run text through the command line's engine share: the engine
//! `robotino-agent clips` makes (a `GrowEngine` with its depth limits, on a thread with
//! a stack of the same shape), a host with a poll budget, and a small rule base.
#![allow(dead_code)]

use agent_core::grow::{GrowEngine, GrowStorage};
use agent_core::{Capacities, Host};

/// How often the host lets the engine poll (one poll per loop iteration, rule firing
/// or deffunction call) before it interrupts: a text that loops forever ends.
pub const POLL_BUDGET: u32 = 100_000;

/// How long (wall time) the host lets the engine work before it interrupts, counted
/// from the host's making or `rearm`: a poll counts a step, not its work, and steps
/// can grow (a loop that copies a multifield one longer each time: 100,000 firings
/// copied 5e9 fields). Well inside libFuzzer's `-timeout=10` for the two phases a
/// target may give it (see `rearm`), on a loaded machine.
pub const TIME_BUDGET: std::time::Duration = std::time::Duration::from_secs(3);

/// Every pool grows to at most this many entries (the CLI's `--pool-limit`): a text
/// that fills a pool gets the capacity error instead of the machine's memory.
pub const POOL_LIMIT: usize = 1 << 18;

/// The engine thread's stack and the part of it the depth check leaves unused: the
/// CLI's margin (`CLI_STACK_MARGIN`, 32 MiB) on a smaller stack, so a deep recursion
/// touches 32 MiB, not the CLI's 224.
pub const STACK: usize = 64 << 20;
pub const STACK_MARGIN: usize = 32 << 20;

/// Drops output (counting it) and interrupts once polled `POLL_BUDGET` times or
/// `TIME_BUDGET` after it was made or rearmed, whichever comes first. Being stopped
/// so is a clean end of an input: the engine reports `Interrupted` and must stay
/// consistent.
pub struct Budget {
    pub polls: u32,
    pub written: usize,
    deadline: std::time::Instant,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            polls: 0,
            written: 0,
            deadline: std::time::Instant::now() + TIME_BUDGET,
        }
    }
}

impl Budget {
    /// A new allowance of polls and time, for a next phase of the same input.
    pub fn rearm(&mut self) {
        self.polls = 0;
        self.deadline = std::time::Instant::now() + TIME_BUDGET;
    }
}

impl Host for Budget {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.written = self.written.saturating_add(text.len());
    }
    fn interrupt(&mut self) -> bool {
        self.polls = self.polls.saturating_add(1);
        self.polls > POLL_BUDGET || std::time::Instant::now() >= self.deadline
    }
}

/// The CLI's engine: pools that start small and grow (to `POOL_LIMIT`), calls nested
/// as deep as the stack allows.
pub fn engine() -> Box<GrowEngine> {
    let storage = GrowStorage::with_limits(GrowStorage::START, Capacities::uniform(POOL_LIMIT));
    let mut e = Box::new(GrowEngine::with_storage(storage));
    e.set_depth_limits(u16::MAX, STACK - STACK_MARGIN);
    // a recursion that branches (`fib` of 45) ends by the budget too
    e.set_poll_calls(true);
    e
}

/// Runs `f` on a thread with the engine stack (as the CLI runs its session).
pub fn on_engine_stack(f: impl FnOnce() + Send + 'static) {
    let t = std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(f)
        .expect("engine thread");
    if t.join().is_err() {
        // the panic was reported by the thread (libFuzzer's hook aborts before this)
        std::process::abort();
    }
}

/// Panics with `what` if the engine's invariants do not hold.
pub fn check(e: &mut GrowEngine, what: &str) {
    if let Err(v) = e.check_invariants() {
        panic!("after {what}: {v}");
    }
}

/// A small valid rule base the command texts run against: templates with defaults and
/// a multislot, rules with not/exists/test and a modify loop that ends, a deffunction,
/// globals and deffacts.
pub const PRELUDE: &str = include_str!("prelude.clp");

/// A fresh CLI engine with [`PRELUDE`] loaded and reset.
pub fn with_prelude(h: &mut Budget) -> Box<GrowEngine> {
    let mut e = engine();
    if let Err(err) = e.load_str(h, "prelude", PRELUDE) {
        panic!("the prelude does not load: {err:?}");
    }
    if let Err(err) = e.reset(h) {
        panic!("the prelude does not reset: {err:?}");
    }
    e
}
