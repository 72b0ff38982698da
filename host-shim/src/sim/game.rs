//! The game driver: one engine loaded with a strategy's rule files, playing
//! setups one after another. The game itself (referee, simulation, decision
//! log) is CLIPS text from the `rules` crate; this module only loads it,
//! asserts the setup, runs the engine and reads the result facts back.

use std::fmt;

use agent_core::{DefaultEngine, Host, HostIoError};
use rules::setup::GameSetup;
use rules::Strategy;

use super::record::{read_record, GameRecord};
use super::snapshot::{self, Snapshot, SnapshotSink};

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
/// the `(watch rules)` lines, in the order they were written; with a
/// snapshot sink, takes `save-facts` output and the snapshot marker lines.
#[derive(Default)]
pub struct GameHost {
    pub output: String,
    pub snapshot: Option<SnapshotSink>,
}

impl Host for GameHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.output.push_str(text);
        let Some(sink) = self.snapshot.as_mut() else {
            return;
        };
        if !text.ends_with('\n') {
            return;
        }
        // The line just completed: a snapshot marker is the host's, not output.
        let body = &self.output[..self.output.len() - 1];
        let start = body.rfind('\n').map_or(0, |i| i + 1);
        if self.output[start..].starts_with(snapshot::MARKER) {
            self.output.truncate(start);
            sink.commit();
        }
    }

    fn write_file(&mut self, path: &str, data: &[u8], append: bool) -> Result<(), HostIoError> {
        match self.snapshot.as_mut() {
            Some(sink) if sink.accepts(path) => {
                sink.write(data, append);
                Ok(())
            }
            _ => Err(HostIoError::Other),
        }
    }
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
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

    /// Snapshots after every decision into `sink` (None: no snapshots).
    pub fn set_snapshot(&mut self, sink: Option<SnapshotSink>) {
        self.host.snapshot = sink;
    }

    fn assert_fact(&mut self, fact: &str, what: &str) -> Result<(), SimError> {
        self.engine
            .assert_str(&mut self.host, fact)
            .map(|_| ())
            .map_err(|e| SimError::Engine {
                during: format!("asserting {what} {fact}"),
                message: e.to_string(),
            })
    }

    /// The facts that switch snapshots on, if a sink is set.
    fn assert_snapshot_facts(&mut self) -> Result<(), SimError> {
        if let Some(fact) = self.host.snapshot.as_ref().map(SnapshotSink::fact) {
            let strategy = format!("(agent-strategy {})", self.strategy.name());
            self.assert_fact(&strategy, "the snapshot fact")?;
            self.assert_fact(&fact, "the snapshot fact")?;
        }
        Ok(())
    }

    fn run_to_end(&mut self, setup: GameSetup) -> Result<GameRecord, SimError> {
        self.host.output.clear();
        let fired = self
            .engine
            .run(&mut self.host, Some(FIRE_LIMIT))
            .map_err(|e| SimError::Engine {
                during: "(run)".into(),
                message: format!("{e} (output so far ends: {})", tail(&self.host.output, 400)),
            })?;
        if let Some(e) = self.host.snapshot.as_mut().and_then(|s| s.error.take()) {
            return Err(SimError::Input(e));
        }
        let output = std::mem::take(&mut self.host.output);
        read_record(&self.engine, setup, self.strategy, fired, output)
    }

    /// Resumes a game from a snapshot (see [`snapshot`]): the facts of
    /// `(reset)` are replaced by the snapshot's, in their saved order, so the
    /// agent and the referee go on from the saved decision. The player must
    /// have been created for the snapshot's strategy. Returns the record and
    /// the machine beliefs as the resumed engine holds them before running.
    pub fn resume(
        &mut self,
        snapshot: &Snapshot,
        trace: bool,
    ) -> Result<(GameRecord, Vec<String>), SimError> {
        if snapshot.strategy != self.strategy {
            return Err(SimError::Input(format!(
                "the snapshot is of strategy {}, the player of {}",
                snapshot.strategy.name(),
                self.strategy.name()
            )));
        }
        self.watch_and_reset(trace)?;
        self.eval("(retract *)")?;
        for fact in snapshot
            .facts
            .iter()
            .filter(|f| !f.starts_with("(snapshot-file ") && !f.starts_with("(agent-strategy "))
        {
            self.assert_fact(fact, "the snapshot fact")?;
        }
        self.assert_snapshot_facts()?;
        let beliefs = self.machine_beliefs();
        let record = self.run_to_end(snapshot.setup.clone())?;
        Ok((record, beliefs))
    }

    /// The engine's machine beliefs M1..M10 as `T2_3+S0` symbols.
    pub fn machine_beliefs(&self) -> Vec<String> {
        let mut beliefs = vec![String::new(); rules::setup::MACHINE_COUNT];
        for id in self.engine.facts() {
            if self.engine.fact_template_name(id) != Some("machine") {
                continue;
            }
            let index = match self.engine.fact_slot(id, "index") {
                Some(agent_core::ValueRef::Int(i)) => i,
                _ => continue,
            };
            let Some(slot) = usize::try_from(index - 1)
                .ok()
                .and_then(|i| beliefs.get_mut(i))
            else {
                continue;
            };
            let mut belief = match self.engine.fact_slot(id, "mtype") {
                Some(agent_core::ValueRef::Symbol(s)) => s.to_string(),
                _ => continue,
            };
            let n = match self.engine.fact_slot(id, "loaded-with") {
                Some(agent_core::ValueRef::Multi(n)) => n as usize,
                _ => 0,
            };
            for i in 0..n {
                if let Some(agent_core::ValueRef::Symbol(p)) =
                    self.engine.fact_multislot_item(id, "loaded-with", i)
                {
                    belief.push('+');
                    belief.push_str(p);
                }
            }
            *slot = belief;
        }
        beliefs
    }

    /// Rules watched (`trace`) or not, then `(reset)`: the start of a game.
    fn watch_and_reset(&mut self, trace: bool) -> Result<(), SimError> {
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
        self.watch_and_reset(trace)?;
        for fact in rules::setup::fact_lines(&text) {
            self.assert_fact(fact, "the setup fact")?;
        }
        self.assert_snapshot_facts()?;
        self.run_to_end(setup.clone())
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
