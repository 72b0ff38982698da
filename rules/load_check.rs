//! Loads rule files into a fresh engine, in order, and reports the first one that does
//! not load: which file, line and column, and what the engine's parser expected there.
//!
//! Shared (`#[path]`) by `build.rs`, which runs it on every load order of
//! `src/order.rs` so a broken rule file fails `cargo build -p rules`, and by
//! `tests/load_check.rs`, which shows that broken texts are caught. It runs on the host
//! with std; the `rules` crate itself stays `no_std` and does not contain it.

use agent_core::{DefaultEngine, EvalError, Host, Value};
use std::fmt;

/// The engine is about 2 MB and `DefaultEngine::new` may build it on the stack before
/// it is boxed (unoptimised build scripts do), so loads run on a thread this big.
const ENGINE_STACK: usize = 64 << 20;

/// A rule file that does not load.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BadRuleFile {
    /// The file's name as given to [`check_load`] (e.g. `rules/utils.clp`).
    pub file: String,
    /// 1-based position of the offending token.
    pub line: u32,
    pub col: u32,
    /// "expected ..." (plus the token found), or the pool that ran out.
    pub message: String,
}

impl fmt::Display for BadRuleFile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.col, self.message
        )
    }
}

/// Drops the engine's output: loading constructs prints nothing we need.
struct Silent;

impl Host for Silent {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

/// A host function the rule files may call: name, least and most arguments (None:
/// any number).
pub type HostFunction = (&'static str, u8, Option<u8>);

/// Loads `files` (name, text) into one fresh engine in the given order, as a host
/// does; the first file that does not load is the error.
pub fn check_load(files: &[(String, String)]) -> Result<(), BadRuleFile> {
    check_load_with(files, &[])
}

/// `check_load` with stand-ins registered for the host's functions first, so calls
/// of them parse (and are checked for their number of arguments).
pub fn check_load_with(
    files: &[(String, String)],
    host_functions: &[HostFunction],
) -> Result<(), BadRuleFile> {
    check_load_as(files, host_functions, PpForms::Keep)
}

/// Whether the engine keeps each construct's source text for `ppdefrule` and the like
/// (`Engine::set_pretty_print_forms`). A robot's agent never lists its rules: the hosts
/// load a robot's engine without them (`robotino-agent run`, a team member), which
/// leaves the symbol table a second copy of the rule base's text short.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PpForms {
    Keep,
    Drop,
}

/// `check_load_with` into an engine that keeps or drops the pretty-print forms, as the
/// host that loads this order does.
pub fn check_load_as(
    files: &[(String, String)],
    host_functions: &[HostFunction],
    pp_forms: PpForms,
) -> Result<(), BadRuleFile> {
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new()
            .stack_size(ENGINE_STACK)
            .spawn_scoped(scope, || load_all(files, host_functions, pp_forms))
            .map_err(|e| no_position(format!("cannot start the checking thread: {e}")))?;
        worker
            .join()
            .map_err(|_| no_position("the engine panicked while loading".to_string()))?
    })
}

fn no_position(message: String) -> BadRuleFile {
    BadRuleFile {
        file: "rules".to_string(),
        line: 0,
        col: 0,
        message,
    }
}

/// What a stand-in returns: loading never calls it.
fn stand_in(_call: &mut agent_core::HostCall<'_, '_>) -> Result<Value, EvalError> {
    Ok(Value::Void)
}

fn load_all(
    files: &[(String, String)],
    host_functions: &[HostFunction],
    pp_forms: PpForms,
) -> Result<(), BadRuleFile> {
    let mut engine = Box::new(DefaultEngine::new());
    engine.set_pretty_print_forms(pp_forms == PpForms::Keep);
    let host = &mut Silent;
    for &(name, min, max) in host_functions {
        engine
            .register_function(name, min, max, stand_in)
            .map_err(|e| no_position(format!("cannot register host function {name}: {e}")))?;
    }
    for (name, text) in files {
        if let Err(e) = engine.load_str(host, name, text) {
            let message = match e.capacity {
                Some(c) => c.to_string(),
                None => {
                    let found = text.get(e.start as usize..e.end as usize).unwrap_or("");
                    if found.is_empty() {
                        format!("expected {}", e.expected)
                    } else {
                        format!("expected {}, found `{found}`", e.expected)
                    }
                }
            };
            return Err(BadRuleFile {
                file: name.clone(),
                line: e.line,
                col: e.col,
                message,
            });
        }
    }
    Ok(())
}
