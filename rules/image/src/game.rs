//! The seeded game, played inside the image: the engine in its static arena, the game's
//! rule base compiled ahead of time (agent, referee, instant simulation and decision
//! log: `rules_compiled::game`, the files of `rules::game_files` as read-only tables;
//! no parser, no rule text), the setup of `robotino-agent sim --seed 0` asserted
//! through the engine's API after `(reset)` (`GameSetup::for_each_fact`), run to the
//! end, the result read back from the facts. The same steps as the host's `sim`
//! (host-shim `sim::game`), so the score must be the same; CI compares them.

use agent_core::host::{router, RouterWriter};
use agent_core::value::TextBuf;
use agent_core::{Engine, Host, Pool, Stats, ValueRef};
use core::fmt::{self, Write};
use rules::setup::GameSetup;
use rules::setup_facts::{Field, SetupFact};
use rules::Strategy;
use static_cell::ConstStaticCell;

/// The seed and strategy `robotino-agent sim` plays by default.
pub const SEED: u64 = 0;
pub const STRATEGY: Strategy = Strategy::Paper;

/// Most rule firings a game may take (the host's `sim` uses the same bound): a seeded
/// game fires under a thousand, so reaching it means the rules loop.
const FIRE_LIMIT: u32 = 500_000;

/// The image's engine. The construct pools hold the compiled rule base exactly (its
/// `SIZES`) plus what the game adds at run time; its expression nodes, alpha nodes,
/// joins, templates, slot definitions, rules and symbols are read in place from
/// read-only memory (agent-core's `in-place`), so the arena holds only what the engine
/// makes itself and the alpha, join and template memories.
///
/// Working-memory capacities: the high-water marks over the games the image is sized
/// for, [`SIZED_FOR`] (paper strategy, seeds 0..39; `tests::every_game_it_is_sized_for`
/// plays them all with these pools), plus the margin in each comment. Most of working
/// memory is the decision log (one fact of 20 cells per decision, up to 87 decisions):
/// the fact-value arena compacts when full, so it needs the live cells at the game's
/// peak, not all values ever written (the smallest arena that plays every seed:
/// between 2,337 and 2,368 cells).
pub type ImageEngine = Engine<ImageStorage>;

/// The games the image's pools are sized for (strategy, seeds).
pub const SIZED_FOR: (Strategy, core::ops::Range<u64>) = (Strategy::Paper, 0..40);

/// Entries of the compiled rule base (paper strategy).
const BASE: agent_core::compiled::Sizes = rules_compiled::game_paper::SIZES;

agent_core::engine_storage! {
    /// The pools of [`ImageEngine`], every one named (a pool added to agent-core must
    /// get its capacity here: the image's RAM budget is checked against them). In the
    /// comments: the most any game of [`SIZED_FOR`] used.
    pub struct ImageStorage {
        facts: 256,                                // 233, +10 %
        fact_values: 2464,                         // live peak <= 2,368, +96 (5 decisions)
        symbols: 24,                               // read in place; 12 made at run time
        symbol_bytes: 192,                         // 61 at run time
        templates: 1,                              // read in place; 1: start-up's
        template_memories: BASE.templates + 1,     // +0 made at run time
        slot_defs: 1,                              // read in place; 1: start-up's
        rules: 0,                                  // read in place
        alpha_nodes: 0,                            // read in place
        alpha_memories: BASE.alphas,
        joins: 1,                                  // read in place; 1: the start-up root
        join_memories: BASE.joins,
        tokens: 544,                               // 495, +10 %
        activations: 24,                           // 16
        functions: BASE.functions,
        globals: BASE.globals,
        exprs: 32,                                 // 13 beyond the compiled ones
        eval_stack: 32,                            // 23
        scratch: 96,                               // 72
        deffacts: BASE.deffacts,
        external_fns: 1,                           // 0: `distance` is built in
        supports: 0,                               // no `logical` in the rules
        modules: 1,                                // MAIN only (no `modules`)
        module_ports: 0,
        focus_stack: 1,
    }
}

/// The engine arena, exported under a fixed name (`report::ENGINE_SYMBOL`) so the
/// footprint tool can show its share of RAM. `try_take` hands it out once, as
/// `&'static mut`.
#[no_mangle]
pub static AGENT_ENGINE: ConstStaticCell<ImageEngine> =
    ConstStaticCell::new(ImageEngine::with_storage(ImageStorage::new()));

/// What the engine printed during the game: normally nothing (the game's rules only print
/// on trouble), so the byte count and the first line are enough to diagnose a failure.
pub struct QuietHost {
    pub bytes: usize,
    pub first: TextBuf<160>,
}

impl QuietHost {
    pub const fn new() -> QuietHost {
        QuietHost {
            bytes: 0,
            first: TextBuf::new(),
        }
    }
}

impl Host for QuietHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.bytes += text.len();
        // Cut at the capacity on purpose: the rest only counts.
        let _ = self.first.write_str(text);
    }
}

/// The result of a game, read back from the facts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GameResult {
    pub score: i64,
    pub fired: u32,
    pub decisions: u32,
    /// `reason` of the `(game-over)` fact, if the game ended.
    pub end: Option<EndReason>,
}

/// Why the game ended, as the decision-log rules say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndReason {
    Done,
    /// The game clock ran out.
    Time,
    Deadlock,
    Other,
}

impl EndReason {
    fn from_symbol(s: &str) -> EndReason {
        match s {
            "done" => EndReason::Done,
            "time" => EndReason::Time,
            "deadlock" => EndReason::Deadlock,
            _ => EndReason::Other,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            EndReason::Done => "done",
            EndReason::Time => "time",
            EndReason::Deadlock => "deadlock",
            EndReason::Other => "other",
        }
    }
}

/// A step of the game that failed. The engine's own message went to the host's error
/// router, as CLIPS prints its errors; [`QuietHost`] keeps its start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GameError {
    pub step: &'static str,
    /// The file being loaded, for load errors.
    pub file: &'static str,
}

impl fmt::Display for GameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.step)?;
        if !self.file.is_empty() {
            write!(f, " {}", self.file)?;
        }
        Ok(())
    }
}

/// Reports `cause` on the host's error router and names the failed step. Not
/// inlined: its formatting stays off the stack frame the game runs below.
#[cold]
#[inline(never)]
fn fail(
    host: &mut QuietHost,
    step: &'static str,
    file: &'static str,
    cause: &dyn fmt::Display,
) -> GameError {
    let mut errors = RouterWriter {
        host,
        router: router::WERROR,
    };
    // RouterWriter never fails.
    let _ = writeln!(errors, "{cause}");
    GameError { step, file }
}

/// Plays the seeded game in `engine` (fresh from `ImageStorage::new()`).
pub fn play(engine: &mut ImageEngine, host: &mut QuietHost) -> Result<GameResult, GameError> {
    play_seed(engine, host, STRATEGY, SEED)
}

/// Plays the game of `seed` in `engine` (fresh from `ImageStorage::new()`).
pub fn play_seed(
    engine: &mut ImageEngine,
    host: &mut QuietHost,
    strategy: Strategy,
    seed: u64,
) -> Result<GameResult, GameError> {
    set_up(engine, host, strategy, seed)?;
    let fired = engine
        .run(host, Some(FIRE_LIMIT))
        .map_err(|e| fail(host, "run", "", &e))?;
    Ok(read_result(engine, fired))
}

/// Loads the rule base, resets and asserts the setup of `seed`. Not inlined: the
/// setup's data and the loader's locals are off the stack before the game runs (the
/// run's deepest calls start below this frame; the image's measured stack).
#[inline(never)]
fn set_up(
    engine: &mut ImageEngine,
    host: &mut QuietHost,
    strategy: Strategy,
    seed: u64,
) -> Result<(), GameError> {
    let base = rules_compiled::game(strategy.name())
        .ok_or_else(|| fail(host, "load", "", &"no compiled rule base for the strategy"))?;
    engine
        .load_compiled(host, base)
        .map_err(|e| fail(host, "load", base.name, &e))?;
    engine
        .reset(host)
        .map_err(|e| fail(host, "reset", "", &e))?;
    let mut setup = Ok(());
    GameSetup::for_seed(seed).for_each_fact(|fact| {
        if setup.is_ok() {
            setup = assert_setup_fact(engine, host, fact)
                .map_err(|e| fail(host, "assert setup", fact.template, &e));
        }
    });
    setup
}

/// Asserts one setup fact through the API (the image has no parser).
fn assert_setup_fact(
    engine: &mut ImageEngine,
    host: &mut QuietHost,
    fact: &SetupFact,
) -> Result<(), agent_core::EngineError> {
    let given = fact.slots();
    let mut values = [ValueRef::Void; 4];
    for (value, (_, field)) in values.iter_mut().zip(given) {
        *value = match field {
            Field::Int(i) => ValueRef::Int(*i),
            Field::Float(x) => ValueRef::Float(*x),
            Field::Symbol(name) => ValueRef::Symbol(name.as_str()),
        };
    }
    let mut slots: [(&str, &[ValueRef<'_>]); 4] = [("", &[]); 4];
    for (k, (slot, (name, _))) in slots.iter_mut().zip(given).enumerate() {
        *slot = (*name, core::slice::from_ref(&values[k]));
    }
    engine
        .assert_fact(host, fact.template, &slots[..given.len().min(4)])
        .map(|_| ())
}

fn read_result(engine: &ImageEngine, fired: u32) -> GameResult {
    let mut result = GameResult {
        score: 0,
        fired,
        decisions: 0,
        end: None,
    };
    for fact in engine.facts() {
        match engine.fact_template_name(fact) {
            Some("score") => {
                if let Some(ValueRef::Int(points)) = engine.fact_slot(fact, "points") {
                    result.score = points;
                }
            }
            Some("decision") => result.decisions += 1,
            Some("game-over") => {
                if let Some(ValueRef::Symbol(reason)) = engine.fact_slot(fact, "reason") {
                    result.end = Some(EndReason::from_symbol(reason));
                }
            }
            _ => {}
        }
    }
    result
}

/// One line per pool: high-water mark, capacity and bytes, so capacities can be sized
/// from a run (the fact-value arena compacts, so its high-water mark is its capacity once
/// it has compacted).
pub fn write_pools(out: &mut impl Write, stats: &Stats) -> fmt::Result {
    for pool in Pool::ALL {
        let (used, capacity) = stats.get(pool);
        writeln!(
            out,
            "agent-image: pool name=\"{}\" high_water={used} capacity={capacity} bytes={}",
            pool.name(),
            stats.bytes(pool)
        )?;
    }
    Ok(())
}
