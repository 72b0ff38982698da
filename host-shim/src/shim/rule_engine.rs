//! Running our engine inside the shim's processes: the agent's rule base in
//! `robotino-agent run`, the referee in `robotino-sim`. Shared plumbing: a big-stack thread
//! (the engine's arrays are built inline before they reach the heap), a host that collects
//! `printout` text, loading rule files with context, and reading slots of facts.

use agent_core::{DefaultEngine, FactId, Host, ValueRef};
use rules::RuleFile;
use std::fmt;

/// Stack for a thread that builds a `DefaultEngine` (several MiB of inline arrays on the way
/// to its `Box`). Only touched pages are committed, so the size costs address space only.
pub const ENGINE_THREAD_STACK: usize = 64 << 20;

/// Most rule firings one decision (or one referee answer) may take: a whole game fires about
/// a thousand, so hitting this means the rules loop.
pub const FIRE_LIMIT: u32 = 100_000;

/// Firings watched after a loop to name its rules.
const LOOP_TRACE_FIRINGS: u32 = 12;

/// An engine operation that failed, with what the shim was doing.
#[derive(Debug, Clone, PartialEq)]
pub struct RulesError {
    pub during: String,
    pub message: String,
}

impl fmt::Display for RulesError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "rule engine error during {}: {}",
            self.during, self.message
        )
    }
}

impl std::error::Error for RulesError {}

impl RulesError {
    pub fn new(during: impl Into<String>, message: impl fmt::Display) -> Self {
        Self {
            during: during.into(),
            message: message.to_string(),
        }
    }
}

/// Collects what the rules print (`printout t ...`), for the process's log.
#[derive(Default)]
pub struct TextHost {
    pub output: String,
}

impl Host for TextHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.output.push_str(text);
    }
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
    }
}

/// An engine with its host.
pub struct Rules {
    pub engine: Box<DefaultEngine>,
    pub host: TextHost,
}

impl Rules {
    /// A fresh engine with `files` loaded in order, without pretty-print forms (the
    /// robot's processes never list their rules; a team member's rule base with its
    /// source text would not fit the symbol table). Call on a thread with
    /// [`ENGINE_THREAD_STACK`].
    pub fn load(files: &[RuleFile]) -> Result<Self, RulesError> {
        let mut rules = Self {
            engine: Box::new(DefaultEngine::new()),
            host: TextHost::default(),
        };
        rules.engine.set_pretty_print_forms(false);
        for file in files {
            rules
                .engine
                .load_str(&mut rules.host, file.name, file.text)
                .map_err(|e| {
                    RulesError::new(
                        format!("loading {}", file.name),
                        format!("{e} (output: {})", rules.host.output.trim()),
                    )
                })?;
        }
        rules.host.output.clear();
        Ok(rules)
    }

    pub fn reset(&mut self) -> Result<(), RulesError> {
        self.engine
            .reset(&mut self.host)
            .map_err(|e| RulesError::new("(reset)", e))
    }

    pub fn assert(&mut self, fact: &str) -> Result<FactId, RulesError> {
        self.engine
            .assert_str(&mut self.host, fact)
            .map_err(|e| RulesError::new(format!("asserting {fact}"), e))
    }

    pub fn retract(&mut self, id: FactId) -> Result<(), RulesError> {
        self.engine
            .retract(&mut self.host, id)
            .map_err(|e| RulesError::new(format!("retracting f-{}", id.0), e))
    }

    pub fn eval(&mut self, command: &str) -> Result<(), RulesError> {
        self.engine
            .eval_str(&mut self.host, command)
            .map(|_| ())
            .map_err(|e| RulesError::new(command.to_string(), e))
    }

    /// Runs to quiescence; returns the rules fired.
    pub fn run(&mut self) -> Result<u32, RulesError> {
        let fired = self
            .engine
            .run(&mut self.host, Some(FIRE_LIMIT))
            .map_err(|e| RulesError::new("(run)", e))?;
        if fired >= FIRE_LIMIT {
            return Err(RulesError::new(
                "(run)",
                format!(
                    "{FIRE_LIMIT} rules fired without quiescence (a rule loop: {})",
                    self.loop_trace()
                ),
            ));
        }
        Ok(fired)
    }

    /// The rules a loop fires: a few more firings watched (the engine is stopped
    /// anyway), as their `FIRE` lines.
    fn loop_trace(&mut self) -> String {
        let before = self.host.output.len();
        let watched = match self.engine.eval_str(&mut self.host, "(watch rules)") {
            Ok(_) => self
                .engine
                .run(&mut self.host, Some(LOOP_TRACE_FIRINGS))
                .map(|_| ())
                .map_err(|e| e.to_string()),
            Err(e) => Err(e.to_string()),
        };
        let fires: Vec<&str> = self.host.output[before..]
            .lines()
            .filter(|l| l.trim_start().starts_with("FIRE"))
            .map(str::trim)
            .collect();
        let trace = match watched {
            Ok(_) => fires.join("; "),
            Err(e) => format!("not watched: {e}"),
        };
        self.host.output.truncate(before);
        trace
    }

    /// Takes what the rules printed since the last call.
    pub fn take_output(&mut self) -> String {
        std::mem::take(&mut self.host.output)
    }

    /// The facts of one template.
    pub fn facts_of<'a>(&'a self, template: &'a str) -> impl Iterator<Item = FactId> + 'a {
        self.engine.facts_of(template)
    }

    /// The first ordered fact `(name VALUE)`'s value as a symbol, e.g. `(state IDLE)`.
    pub fn ordered_symbol(&self, name: &str) -> Option<String> {
        self.facts_of(name).next().and_then(|id| {
            match self.engine.fact_multislot_item(id, "implied", 0) {
                Some(ValueRef::Symbol(s)) => Some(s.to_string()),
                _ => None,
            }
        })
    }

    pub fn symbol(&self, id: FactId, slot: &str) -> Option<String> {
        match self.engine.fact_slot(id, slot) {
            Some(ValueRef::Symbol(s)) => Some(s.to_string()),
            _ => None,
        }
    }

    pub fn int(&self, id: FactId, slot: &str) -> Option<i64> {
        match self.engine.fact_slot(id, slot) {
            Some(ValueRef::Int(i)) => Some(i),
            _ => None,
        }
    }

    pub fn number(&self, id: FactId, slot: &str) -> Option<f64> {
        match self.engine.fact_slot(id, slot) {
            Some(ValueRef::Int(i)) => Some(i as f64),
            Some(ValueRef::Float(x)) => Some(x),
            _ => None,
        }
    }

    /// The items of a multislot that are symbols.
    pub fn symbols(&self, id: FactId, slot: &str) -> Vec<String> {
        let Some(ValueRef::Multi(n)) = self.engine.fact_slot(id, slot) else {
            return Vec::new();
        };
        (0..n as usize)
            .filter_map(|i| match self.engine.fact_multislot_item(id, slot, i) {
                Some(ValueRef::Symbol(s)) => Some(s.to_string()),
                _ => None,
            })
            .collect()
    }
}

/// Runs `f` on a thread with [`ENGINE_THREAD_STACK`] and returns its result.
pub fn with_engine_stack<T: Send + 'static>(
    f: impl FnOnce() -> T + Send + 'static,
) -> Result<T, String> {
    std::thread::Builder::new()
        .name("engine".into())
        .stack_size(ENGINE_THREAD_STACK)
        .spawn(f)
        .map_err(|e| format!("cannot start the engine thread: {e}"))?
        .join()
        .map_err(|_| "the engine thread panicked".to_string())
}

/// Runs a process's main work on a thread with [`ENGINE_THREAD_STACK`] and ends the process
/// from that thread with the exit code `f` returns, so the thread's stack is never unmapped
/// while the process lives: under qemu-user (the i586 tests) a process that handled SIGTERM
/// crashed with SIGSEGV right after the big stack of a finished thread was unmapped.
pub fn exit_from_engine_stack(f: impl FnOnce() -> i32 + Send + 'static) -> ! {
    let outcome = with_engine_stack(move || -> () {
        let code = f();
        std::process::exit(code)
    });
    if let Err(e) = outcome {
        eprintln!("{e}");
    }
    std::process::exit(1)
}
