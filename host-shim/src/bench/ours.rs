//! The seam where our engine plugs into the benchmark.
//!
//! Ours is measured two ways:
//! 1. As a process, exactly like CLIPS 6.30: `robotino-agent clips -f2 FILE` on the same
//!    batch files (see `BatchCli::ours_cli`). This gives whole-process wall time and the
//!    callgrind instruction counts (whole and run phase). It switches on by itself once the
//!    `clips` subcommand runs batch files, `(load* "file")`, `(watch statistics)` (printing
//!    the CLIPS line `N rules fired`) and `(mem-used)`.
//! 2. In-process, like clipspy's `run()`: implement [`InProcessEngine`] for a wrapper around
//!    `agent_core::DefaultEngine` and return it from [`new_engine`]. This gives the run-phase
//!    wall time without process start-up, and the arena high-water marks as memory.

use super::measure::{result_lines, Contender, Measurement, Plan, ProgramFiles};
use super::process::median;
use super::workloads::{self, Kind};
use crate::sim::game::Player;
use agent_core::grow::{GrowEngine, GrowStorage};
use agent_core::Host;
use std::path::Path;
use std::time::{Duration, Instant};

/// What an engine offers to be timed in-process. One value runs one program once.
pub trait InProcessEngine {
    /// Loads constructs (deftemplates, defrules, deffacts, defglobals) from source text.
    fn load(&mut self, source_name: &str, text: &str) -> Result<(), String>;
    /// `(reset)`: asserts the deffacts.
    fn reset(&mut self) -> Result<(), String>;
    /// `(run)` to completion or `(halt)`; returns the number of rules fired. Gives up
    /// with an error once `deadline` has passed (checked between chunks of firings).
    fn run(&mut self, deadline: Instant) -> Result<u64, String>;
    /// Everything printed to `t` (stdout) so far, drained.
    fn take_output(&mut self) -> String;
    /// Bytes of engine storage in use at its high-water marks (sum over the pools).
    fn memory_bytes(&self) -> Option<u64>;
}

/// The in-process engine: the CLI's [`GrowEngine`], whose pools start at the host's
/// capacities and double when full, so no workload runs out of a pool (the fixed
/// large-pool engine used before ran out of tokens on sudoku-4x4-p9 and of symbol
/// bytes on join3-8000). It is built before the clock starts; memory is counted from
/// high-water marks, not capacities.
pub type BenchEngine = GrowEngine;

/// Collects what the engine prints to `t`; everything else (warnings, errors) is kept
/// apart so a failing program can say why.
#[derive(Default)]
pub struct CaptureHost {
    pub stdout: String,
    pub other: String,
}

impl Host for CaptureHost {
    fn write_str(&mut self, router: &str, text: &str) {
        if router == agent_core::host::router::STDOUT {
            self.stdout.push_str(text);
        } else {
            self.other.push_str(text);
        }
    }
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
    }
}

/// Our engine in a box, driven through the public API.
pub struct Ours<E> {
    engine: Box<E>,
    host: CaptureHost,
}

/// The engine operations the bench needs, over any capacities.
pub trait EngineOps {
    fn load(&mut self, host: &mut dyn Host, name: &str, text: &str) -> Result<usize, String>;
    fn reset(&mut self, host: &mut dyn Host) -> Result<(), String>;
    fn run(&mut self, host: &mut dyn Host, limit: Option<u32>) -> Result<u32, String>;
    fn stats(&self) -> agent_core::Stats;
}

macro_rules! engine_ops {
    ($ty:ty) => {
        impl EngineOps for $ty {
            fn load(
                &mut self,
                host: &mut dyn Host,
                name: &str,
                text: &str,
            ) -> Result<usize, String> {
                self.load_str(host, name, text).map_err(|e| e.to_string())
            }
            fn reset(&mut self, host: &mut dyn Host) -> Result<(), String> {
                agent_core::Engine::reset(self, host).map_err(|e| e.to_string())
            }
            fn run(&mut self, host: &mut dyn Host, limit: Option<u32>) -> Result<u32, String> {
                agent_core::Engine::run(self, host, limit).map_err(|e| e.to_string())
            }
            fn stats(&self) -> agent_core::Stats {
                agent_core::Engine::stats(self)
            }
        }
    };
}
engine_ops!(BenchEngine);

impl<E: EngineOps> InProcessEngine for Ours<E> {
    fn load(&mut self, source_name: &str, text: &str) -> Result<(), String> {
        self.engine
            .load(&mut self.host, source_name, text)
            .map(|_| ())
            .map_err(|e| format!("{e}{}", context(&self.host)))
    }

    fn reset(&mut self) -> Result<(), String> {
        self.engine
            .reset(&mut self.host)
            .map_err(|e| format!("(reset): {e}{}", context(&self.host)))
    }

    fn run(&mut self, deadline: Instant) -> Result<u64, String> {
        // Chunks of firings so a program that outgrows the deadline is stopped (a thread
        // cannot be killed). A chunk that fires fewer than asked ended the run: the
        // agenda is empty or `(halt)` was called.
        const CHUNK: u32 = 200;
        let mut fired = 0u64;
        loop {
            let now = self
                .engine
                .run(&mut self.host, Some(CHUNK))
                .map_err(|e| format!("(run): {e}{}", context(&self.host)))?;
            fired += u64::from(now);
            // An error inside a rule's actions stops the run with a message, not an
            // Err: a run that reported one did not compute the program's result.
            if let Some(line) = first_error(&self.host.other) {
                if let Some(pool) = capacity_exceeded(line) {
                    return Err(format!("capacity exceeded: {pool} after {fired} firings"));
                }
                return Err(format!("(run) stopped after {fired} firings: {line}"));
            }
            if now < CHUNK {
                return Ok(fired);
            }
            if Instant::now() > deadline {
                return Err(format!("run exceeded the deadline after {fired} firings"));
            }
        }
    }

    fn take_output(&mut self) -> String {
        std::mem::take(&mut self.host.stdout)
    }

    fn memory_bytes(&self) -> Option<u64> {
        Some(arena_bytes(&self.engine.stats()).0)
    }
}

/// `out of POOL (capacity N)` when `text` reports an exhausted pool of our engine.
pub fn capacity_exceeded(text: &str) -> Option<&str> {
    text.lines().find_map(|line| {
        let start = line.find("out of ")?;
        let rest = &line[start..];
        let end = rest.find(')')?;
        rest.contains("(capacity ").then(|| &rest[..=end])
    })
}

/// The first error line an engine printed (`[...]` messages other than the halt notice).
fn first_error(other: &str) -> Option<&str> {
    other
        .lines()
        .find(|l| l.starts_with('[') && !l.contains("Execution halted during the actions"))
}

fn context(host: &CaptureHost) -> String {
    match host.other.lines().find(|l| !l.trim().is_empty()) {
        Some(line) => format!(" (engine said: {line})"),
        None => String::new(),
    }
}

/// Bytes of each pool's entry type, in `Pool` order (fact and symbol entries count
/// their hash bucket too). Used to turn high-water marks into bytes.
pub fn entry_bytes() -> [usize; agent_core::Pool::COUNT] {
    agent_core::Pool::ALL.map(agent_core::entry_bytes)
}

/// (bytes in use at the high-water marks, bytes of all pools at capacity).
pub fn arena_bytes(stats: &agent_core::Stats) -> (u64, u64) {
    let sizes = entry_bytes();
    let mut used = 0u64;
    let mut capacity = 0u64;
    for (i, size) in sizes.iter().enumerate() {
        used += u64::from(stats.used[i]) * *size as u64;
        capacity += u64::from(stats.capacity[i]) * *size as u64;
    }
    (used, capacity)
}

/// A fresh bench engine (its pools on the heap, growing without a limit below the
/// index type's).
pub fn new_engine() -> Option<Box<dyn InProcessEngine>> {
    Some(Box::new(Ours {
        engine: Box::new(BenchEngine::with_storage(GrowStorage::with_limits(
            agent_core::Capacities::HOST,
            GrowStorage::NO_LIMIT,
        ))),
        host: CaptureHost::default(),
    }))
}

/// Ours timed in-process through [`InProcessEngine`].
pub struct OursInProcess {
    factory: fn() -> Option<Box<dyn InProcessEngine>>,
}

impl OursInProcess {
    pub fn new() -> Self {
        Self {
            factory: new_engine,
        }
    }

    /// Any factory: lets tests drive the measuring code with a small fake engine.
    #[cfg(test)]
    pub fn with_factory(factory: fn() -> Option<Box<dyn InProcessEngine>>) -> Self {
        Self { factory }
    }

    /// One repetition: (load, reset, timed run) on a fresh engine.
    fn once(&self, name: &str, text: &str, limit: Duration) -> Result<Sample, String> {
        let mut engine = (self.factory)().ok_or_else(not_built)?;
        let start = Instant::now();
        engine.load(name, text)?;
        engine.reset()?;
        let run_start = Instant::now();
        let fired = engine.run(start + limit)?;
        let run = run_start.elapsed();
        Ok(Sample {
            fired,
            run,
            whole: start.elapsed(),
            output: engine.take_output(),
            memory: engine.memory_bytes(),
        })
    }
}

struct Sample {
    fired: u64,
    run: Duration,
    whole: Duration,
    output: String,
    memory: Option<u64>,
}

fn not_built() -> String {
    "ours is not wired in yet (bench::ours::new_engine)".to_string()
}

impl Contender for OursInProcess {
    fn name(&self) -> String {
        "ours (in-process)".to_string()
    }

    fn probe(&self, _scratch: &Path) -> Result<(), String> {
        (self.factory)().map(|_| ()).ok_or_else(not_built)
    }

    fn measure(&self, program: &ProgramFiles, plan: &Plan) -> Measurement {
        if program.workload.kind == Kind::Llsf {
            return measure_games(program.workload.size, plan);
        }
        if program.workload.kind.is_batch_script() {
            // its commands (clear, load, reset, run twice) are the CLI column's to run
            return Measurement::not_measured("a batch script: see the CLI column");
        }
        let text = match std::fs::read_to_string(&program.constructs) {
            Ok(text) => text,
            Err(e) => return Measurement::failed(&format!("reading program: {e}")),
        };
        let name = program.constructs.display().to_string();
        let mut samples = Vec::new();
        for _ in 0..plan.reps.max(1) {
            match self.once(&name, &text, plan.run_limit) {
                // A run that takes a good part of the deadline is not repeated: the
                // time-box of the whole bench matters more than a median of long runs.
                Ok(sample) if sample.whole > plan.run_limit / 4 => {
                    samples.push(sample);
                    break;
                }
                Ok(sample) => samples.push(sample),
                Err(reason) if reason.starts_with("capacity exceeded") => {
                    return Measurement::failed(&reason)
                }
                Err(reason) => return Measurement::failed(&format!("ours: {reason}")),
            }
        }
        let fired = match samples.as_slice() {
            [first, rest @ ..] if rest.iter().all(|s| s.fired == first.fired) => Ok(first.fired),
            _ => Err("rules fired differ between runs".to_string()),
        };
        let runs: Vec<Duration> = samples.iter().map(|s| s.run).collect();
        let wholes: Vec<Duration> = samples.iter().map(|s| s.whole).collect();
        let last = samples.last();
        let prefix = program.workload.kind.result_prefixes();
        let in_process_only = || Err("not measured: counted by the CLI column".to_string());
        Measurement {
            fired,
            result_lines: Ok(last
                .map(|s| result_lines(&s.output, prefix))
                .unwrap_or_default()),
            wall_whole: median(&wholes).ok_or_else(|| "no run".to_string()),
            wall_run: median(&runs).ok_or_else(|| "no run".to_string()),
            instr_whole: in_process_only(),
            instr_run: in_process_only(),
            mem_bytes: last
                .and_then(|s| s.memory)
                .ok_or_else(|| "engine reported no memory figure".to_string()),
        }
    }
}

/// LLSF games through the sim's [`Player`] (the `DefaultEngine` that `robotino-agent sim`
/// uses): per repetition a fresh player (loading the rule base: *whole*) plays seeds
/// 0..games one after another; *run* is the sum of the `play` calls (reset, setup facts,
/// run, reading the record back).
fn measure_games(games: usize, plan: &Plan) -> Measurement {
    let setups = workloads::llsf_setups(games);
    let mut wholes = Vec::new();
    let mut runs = Vec::new();
    let mut fired_per_rep = Vec::new();
    let mut lines = Vec::new();
    let mut memory = None;
    for _ in 0..plan.reps.max(1) {
        let start = Instant::now();
        let mut player = match Player::new(workloads::LLSF_STRATEGY) {
            Ok(player) => player,
            Err(e) => return Measurement::failed(&format!("ours: {e}")),
        };
        let mut run = Duration::ZERO;
        let mut fired = 0u64;
        lines.clear();
        for (seed, setup) in &setups {
            let play_start = Instant::now();
            let record = match player.play(setup, false) {
                Ok(record) => record,
                Err(e) => return Measurement::failed(&format!("ours, seed {seed}: {e}")),
            };
            run += play_start.elapsed();
            fired += u64::from(record.fired);
            lines.push(format!("GAME {seed} {}", record.result_line()));
        }
        wholes.push(start.elapsed());
        runs.push(run);
        fired_per_rep.push(fired);
        memory = Some(arena_bytes(&player.stats()).0);
    }
    let fired = match fired_per_rep.as_slice() {
        [first, rest @ ..] if rest.iter().all(|f| f == first) => Ok(*first),
        _ => Err("rules fired differ between runs".to_string()),
    };
    let in_process_only = || Err("not measured: counted by the CLI column".to_string());
    Measurement {
        fired,
        result_lines: Ok(lines),
        wall_whole: median(&wholes).ok_or_else(|| "no run".to_string()),
        wall_run: median(&runs).ok_or_else(|| "no run".to_string()),
        instr_whole: in_process_only(),
        instr_run: in_process_only(),
        mem_bytes: memory.ok_or_else(|| "no run".to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::workloads::{Kind, Workload};

    /// Fires one rule per fact line and prints the count: enough to exercise the plumbing.
    struct CountingEngine {
        facts: u64,
        output: String,
    }

    impl InProcessEngine for CountingEngine {
        fn load(&mut self, _name: &str, text: &str) -> Result<(), String> {
            // Generated job facts, not the rule patterns that mention `?variables`.
            let is_job_fact = |l: &&str| l.trim_start().starts_with("(job") && !l.contains('?');
            self.facts = text.lines().filter(is_job_fact).count() as u64;
            Ok(())
        }
        fn reset(&mut self) -> Result<(), String> {
            Ok(())
        }
        fn run(&mut self, _deadline: Instant) -> Result<u64, String> {
            self.output = format!("started {}\n", self.facts);
            Ok(self.facts)
        }
        fn take_output(&mut self) -> String {
            std::mem::take(&mut self.output)
        }
        fn memory_bytes(&self) -> Option<u64> {
            Some(64 * self.facts)
        }
    }

    fn counting() -> Option<Box<dyn InProcessEngine>> {
        Some(Box::new(CountingEngine {
            facts: 0,
            output: String::new(),
        }))
    }

    #[test]
    fn in_process_measurement_uses_what_the_engine_reports() {
        let dir = std::env::temp_dir().join(format!("bench-ours-test-{}", std::process::id()));
        let workload = Workload {
            kind: Kind::Negation,
            size: 40,
        };
        let files = ProgramFiles::write(&dir, workload).expect("temp dir is writable");
        let plan = Plan {
            reps: 3,
            callgrind_limit: None,
            run_limit: Duration::from_secs(10),
        };
        let measured = OursInProcess::with_factory(counting).measure(&files, &plan);
        assert_eq!(measured.fired, Ok(20));
        assert_eq!(measured.result_lines, Ok(vec!["started 20".to_string()]));
        assert_eq!(measured.mem_bytes, Ok(64 * 20));
        assert!(measured.wall_run.is_ok() && measured.instr_run.is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn exhausted_pools_are_recognised() {
        assert_eq!(
            capacity_exceeded("x\n[ERROR] out of tokens (capacity 16384)\n"),
            Some("out of tokens (capacity 16384)")
        );
        assert_eq!(capacity_exceeded("[ERROR] something else"), None);
    }

    #[test]
    fn without_an_engine_ours_is_not_measured() {
        let absent = OursInProcess::with_factory(|| None);
        assert!(absent.probe(Path::new(".")).is_err());
    }
}
