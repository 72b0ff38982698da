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
use std::path::Path;
use std::time::{Duration, Instant};

/// What an engine offers to be timed in-process. One value runs one program once.
pub trait InProcessEngine {
    /// Loads constructs (deftemplates, defrules, deffacts, defglobals) from source text.
    fn load(&mut self, source_name: &str, text: &str) -> Result<(), String>;
    /// `(reset)`: asserts the deffacts.
    fn reset(&mut self) -> Result<(), String>;
    /// `(run)` to completion or `(halt)`; returns the number of rules fired.
    fn run(&mut self) -> Result<u64, String>;
    /// Everything printed to `t` (stdout) so far, drained.
    fn take_output(&mut self) -> String;
    /// Bytes of engine storage in use at its high-water marks (sum over the pools).
    fn memory_bytes(&self) -> Option<u64>;
}

/// THE SEAM: return a fresh engine once agent-core can run programs. Until then ours is
/// reported as "not measured" for the in-process column.
///
/// Hint for the implementer: `Engine` keeps all storage inline, so build it straight in a
/// `Box` (or a `static`) rather than on the stack, and give `Host::write_str` a `String`
/// buffer that `take_output` drains.
pub fn new_engine() -> Option<Box<dyn InProcessEngine>> {
    None
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
    fn once(&self, name: &str, text: &str) -> Result<Sample, String> {
        let mut engine = (self.factory)().ok_or_else(not_built)?;
        let start = Instant::now();
        engine.load(name, text)?;
        engine.reset()?;
        let run_start = Instant::now();
        let fired = engine.run()?;
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
        let text = match std::fs::read_to_string(&program.constructs) {
            Ok(text) => text,
            Err(e) => return Measurement::failed(&format!("reading program: {e}")),
        };
        let name = program.constructs.display().to_string();
        let mut samples = Vec::new();
        for _ in 0..plan.reps.max(1) {
            match self.once(&name, &text) {
                Ok(sample) => samples.push(sample),
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
        let prefix = program.workload.kind.result_prefix();
        let in_process_only = || Err("counted by the CLI column".to_string());
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
        fn run(&mut self) -> Result<u64, String> {
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
    fn without_an_engine_ours_is_not_measured() {
        let absent = OursInProcess::with_factory(|| None);
        assert!(absent.probe(Path::new(".")).is_err());
    }
}
