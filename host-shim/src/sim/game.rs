//! The game driver: one engine loaded with a strategy's rule files, playing
//! setups one after another. The game itself (referee, simulation, decision
//! log) is CLIPS text from the `rules` crate; this module only loads it,
//! asserts the setup, runs the engine and reads the result facts back.

use std::fmt;

use agent_core::{DefaultEngine, Host};
use rules::setup::GameSetup;
use rules::Strategy;

use super::record::{read_record, GameRecord};

/// Most rule firings one game may take; a real game fires about a thousand,
/// so hitting this means the rules loop (reported as a stall).
const FIRE_LIMIT: u32 = 500_000;

/// Stack for threads that own an engine: `DefaultEngine::new()` builds
/// several MiB of inline arrays before they reach the heap.
pub const ENGINE_THREAD_STACK: usize = 256 << 20;

/// What went wrong while setting up or playing a game.
#[derive(Debug)]
pub enum SimError {
    /// A rule or setup text did not load.
    Load { file: String, message: String },
    /// The engine stopped with an error while running or evaluating.
    Engine { during: String, message: String },
    /// The result facts were not what the fact interface promises.
    Facts(String),
    /// Files, command line, log format.
    Input(String),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Load { file, message } => write!(f, "loading {file}: {message}"),
            SimError::Engine { during, message } => {
                write!(f, "engine error during {during}: {message}")
            }
            SimError::Facts(m) => write!(f, "unexpected result facts: {m}"),
            SimError::Input(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for SimError {}

/// Collects what the engine prints: `printout` output and, when tracing,
/// the `(watch rules)` lines, in the order they were written.
#[derive(Default)]
pub struct GameHost {
    pub output: String,
}

impl Host for GameHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.output.push_str(text);
    }
}

/// An engine with a strategy's game files loaded, ready to play setups.
pub struct Player {
    engine: Box<DefaultEngine>,
    host: GameHost,
    strategy: Strategy,
    /// Set when the engine lacked the `distance` builtin and the CLIPS stub
    /// from `rules/clips/stubs.clp` was loaded instead.
    pub distance_stubbed: bool,
}

impl Player {
    /// Creates the engine and loads `rules::game_files(strategy)`. Call from a
    /// thread with [`ENGINE_THREAD_STACK`].
    pub fn new(strategy: Strategy) -> Result<Player, SimError> {
        let mut player = Player {
            engine: Box::new(DefaultEngine::new()),
            host: GameHost::default(),
            strategy,
            distance_stubbed: false,
        };
        // `distance` is a host function the rules call; our engine is meant to
        // have it built in. If it does not (yet), use the CLIPS stub and say so.
        if player
            .engine
            .eval_str(&mut player.host, "(distance 0 0 3 4)")
            .is_err()
        {
            player.load(rules::CLIPS_STUBS.name, rules::CLIPS_STUBS.text)?;
            player.distance_stubbed = true;
        }
        for file in rules::game_files(strategy) {
            player.load(file.name, file.text)?;
        }
        player.host.output.clear();
        Ok(player)
    }

    /// The engine's pool high-water marks and capacities (for the benchmark).
    pub fn stats(&self) -> agent_core::Stats {
        self.engine.stats()
    }

    fn load(&mut self, name: &str, text: &str) -> Result<(), SimError> {
        self.engine
            .load_str(&mut self.host, name, text)
            .map(|_| ())
            .map_err(|e| SimError::Load {
                file: name.to_string(),
                message: format!("{e} (output: {})", self.host.output.trim()),
            })
    }

    fn eval(&mut self, command: &str) -> Result<(), SimError> {
        self.engine
            .eval_str(&mut self.host, command)
            .map(|_| ())
            .map_err(|e| SimError::Engine {
                during: command.to_string(),
                message: e.to_string(),
            })
    }

    /// Plays one game: resets, asserts the setup facts, runs to the end and
    /// reads the decision log, score and end of game. Asserting the setup
    /// right after `(reset)` gives the same facts, fact numbers and agenda as
    /// loading it as the last deffacts (what the CLIPS drivers do), and lets
    /// one engine play many setups without redefining constructs.
    /// With `trace` the record's output holds the `(watch rules)` lines.
    pub fn play(&mut self, setup: &GameSetup, trace: bool) -> Result<GameRecord, SimError> {
        let mut text = String::new();
        setup
            .write_clips(&mut text)
            .map_err(|e| SimError::Input(format!("writing the setup: {e}")))?;
        self.eval(if trace {
            "(watch rules)"
        } else {
            "(unwatch rules)"
        })?;
        self.engine
            .reset(&mut self.host)
            .map_err(|e| SimError::Engine {
                during: "(reset)".into(),
                message: e.to_string(),
            })?;
        for fact in rules::setup::fact_lines(&text) {
            self.engine
                .assert_str(&mut self.host, fact)
                .map_err(|e| SimError::Engine {
                    during: format!("asserting the setup fact {fact}"),
                    message: e.to_string(),
                })?;
        }
        self.host.output.clear();
        let fired = self
            .engine
            .run(&mut self.host, Some(FIRE_LIMIT))
            .map_err(|e| SimError::Engine {
                during: "(run)".into(),
                message: format!("{e} (output so far ends: {})", tail(&self.host.output, 400)),
            })?;
        let output = std::mem::take(&mut self.host.output);
        read_record(&self.engine, setup.clone(), self.strategy, fired, output)
    }
}

/// The last `n` bytes of `s` (on a char boundary), for error context.
fn tail(s: &str, n: usize) -> &str {
    let mut start = s.len().saturating_sub(n);
    while !s.is_char_boundary(start) {
        start += 1;
    }
    &s[start..]
}

/// Runs `f` on a thread with a stack big enough to build an engine.
pub fn with_engine_stack<T: Send + 'static>(
    f: impl FnOnce() -> T + Send + 'static,
) -> Result<T, SimError> {
    std::thread::Builder::new()
        .stack_size(ENGINE_THREAD_STACK)
        .spawn(f)
        .map_err(|e| SimError::Input(format!("cannot start the engine thread: {e}")))?
        .join()
        .map_err(|_| SimError::Input("the engine thread panicked".into()))
}
