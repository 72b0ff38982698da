//! CLIPS 6.4 through PyPI `clipspy`, driven by `tests/bench/clipspy_run.py`.
//!
//! The driver times `run()` in-process, so Python start-up and parsing stay out of the run
//! figure. Under callgrind the whole Python process is counted; the run phase is again the
//! difference to the same driver stopping after `(reset)`.

use super::measure::{result_lines, Contender, Measurement, Plan, ProgramFiles, Reading};
use super::process::{callgrind_fits, callgrind_instructions, median, run_with_deadline};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// The driver script, embedded so the command works from any directory.
const DRIVER: &str = include_str!("../../../tests/bench/clipspy_run.py");

pub struct ClipsPy {
    pub python: String,
}

/// What the driver prints as JSON on its last stdout line.
#[derive(serde::Deserialize, Debug)]
pub struct DriverReport {
    pub version: String,
    pub fired: Vec<u64>,
    pub run_ns: Vec<u64>,
    pub whole_ns: Vec<u64>,
    #[serde(default)]
    pub output: String,
    pub mem_used: Option<u64>,
}

impl DriverReport {
    pub fn parse(stdout: &str) -> Result<Self, String> {
        let last = stdout
            .lines()
            .rev()
            .find(|l| l.starts_with('{'))
            .ok_or_else(|| "driver printed no JSON line".to_string())?;
        serde_json::from_str(last).map_err(|e| format!("driver JSON: {e}"))
    }
}

impl ClipsPy {
    /// Uses the real interpreter behind `python3`: version managers put a shell-script
    /// shim on PATH, and callgrind would count that shell instead of Python.
    pub fn new() -> Self {
        let python = Command::new("python3")
            .args(["-c", "import sys; print(sys.executable)"])
            .output()
            .ok()
            .map(|out| String::from_utf8_lossy(&out.stdout).trim().to_string())
            .filter(|path| !path.is_empty())
            .unwrap_or_else(|| "python3".to_string());
        Self { python }
    }

    fn driver_path(scratch: &Path) -> Result<PathBuf, String> {
        let path = scratch.join("clipspy_run.py");
        std::fs::write(&path, DRIVER).map_err(|e| format!("writing {}: {e}", path.display()))?;
        Ok(path)
    }

    fn driver_args(driver: &Path, program: &Path, reps: usize, phase: &str) -> Vec<String> {
        vec![
            driver.display().to_string(),
            program.display().to_string(),
            "--reps".to_string(),
            reps.to_string(),
            "--phase".to_string(),
            phase.to_string(),
        ]
    }

    /// The driver's arguments for one workload: constructs (the driver does reset and
    /// run), or for batch scripts (LLSF games, runbench) the batch files, `phase` "full" or "norun". `timed` adds
    /// the no-run batch as the baseline the driver subtracts itself.
    fn workload_args(
        driver: &Path,
        program: &ProgramFiles,
        reps: usize,
        phase: &str,
        timed: bool,
    ) -> Vec<String> {
        if !program.workload.kind.is_batch_script() {
            return Self::driver_args(driver, &program.constructs, reps, phase);
        }
        let batch = if phase == "full" {
            &program.batch_full
        } else {
            &program.batch_norun
        };
        let mut args = Self::driver_args(driver, batch, reps, "full");
        args.push("--batch".to_string());
        if timed {
            args.push("--baseline".to_string());
            args.push(program.batch_norun.display().to_string());
        }
        args
    }

    fn run_driver(&self, args: &[String], limit: Duration) -> Result<DriverReport, String> {
        let finished = run_with_deadline(
            Command::new(&self.python)
                .args(args)
                .env("PYTHONHASHSEED", "0"),
            limit,
        )
        .map_err(|e| e.to_string())?;
        if finished.timed_out {
            return Err(format!("run exceeded {} s", limit.as_secs()));
        }
        if !finished.status.success() {
            let last_error = finished.stderr.lines().last().unwrap_or("").to_string();
            return Err(format!("driver {}: {last_error}", finished.status));
        }
        DriverReport::parse(&finished.stdout)
    }

    /// The CLIPS version the driver finds, for the report header.
    pub fn clips_version(&self, scratch: &Path) -> Result<String, String> {
        let driver = Self::driver_path(scratch)?;
        let program = scratch.join("version-probe.clp");
        std::fs::write(
            &program,
            "(defrule probe => (printout t \"bench-probe-ok\" crlf))\n",
        )
        .map_err(|e| format!("writing {}: {e}", program.display()))?;
        let args = Self::driver_args(&driver, &program, 1, "full");
        let report = self.run_driver(&args, Duration::from_secs(60))?;
        if report.output.contains("bench-probe-ok") {
            Ok(report.version)
        } else {
            Err("clipspy ran but the probe rule printed nothing".to_string())
        }
    }

    fn callgrind_run_phase(
        &self,
        driver: &Path,
        program: &ProgramFiles,
        limit: Duration,
    ) -> (Reading<u64>, Reading<u64>) {
        let count = |phase: &str| {
            let args = Self::workload_args(driver, program, 1, phase, false);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            callgrind_instructions(&self.python, &args, &program.dir, limit)
        };
        let whole = count("full");
        let run = match &whole {
            Ok(whole) => count("norun").map(|norun| whole.saturating_sub(norun)),
            Err(reason) => Err(reason.clone()),
        };
        (whole, run)
    }
}

impl Contender for ClipsPy {
    fn name(&self) -> String {
        "CLIPS 6.4".to_string()
    }

    fn probe(&self, scratch: &Path) -> Result<(), String> {
        self.clips_version(scratch).map(|_| ())
    }

    fn version(&self, scratch: &Path) -> String {
        self.clips_version(scratch)
            .unwrap_or_else(|reason| format!("unknown version ({reason})"))
    }

    fn measure(&self, program: &ProgramFiles, plan: &Plan) -> Measurement {
        let driver = match Self::driver_path(&program.dir) {
            Ok(driver) => driver,
            Err(reason) => return Measurement::failed(&reason),
        };
        let args = Self::workload_args(&driver, program, plan.reps.max(1), "full", true);
        // Every repetition loads and runs afresh; allow the plain-run deadline for each.
        let limit = plan.run_limit * plan.reps.max(1) as u32;
        let report = match self.run_driver(&args, limit) {
            Ok(report) => report,
            Err(reason) => return Measurement::failed(&format!("CLIPS 6.4: {reason}")),
        };
        let fired = match report.fired.as_slice() {
            [first, rest @ ..] if rest.iter().all(|f| f == first) => Ok(*first),
            [] => Err("driver reported no run".to_string()),
            other => Err(format!("rules fired differ between runs: {other:?}")),
        };
        let nanos = |samples: &[u64]| -> Vec<Duration> {
            samples.iter().map(|&ns| Duration::from_nanos(ns)).collect()
        };
        let (instr_whole, instr_run) = match plan.callgrind_limit {
            None => (
                Err("not measured: --no-callgrind".to_string()),
                Err("not measured: --no-callgrind".to_string()),
            ),
            Some(limit) => {
                // Python itself takes about this long to start under valgrind.
                let startup = Duration::from_secs(30);
                let fits = median(&nanos(&report.whole_ns))
                    .ok_or_else(|| "no run".to_string())
                    .and_then(|native| callgrind_fits(native, startup, limit));
                match fits {
                    Ok(()) => self.callgrind_run_phase(&driver, program, limit),
                    Err(reason) => (Err(reason.clone()), Err(reason)),
                }
            }
        };
        Measurement {
            fired,
            result_lines: Ok(result_lines(
                &report.output,
                program.workload.kind.result_prefixes(),
            )),
            wall_whole: median(&nanos(&report.whole_ns)).ok_or_else(|| "no run".to_string()),
            wall_run: median(&nanos(&report.run_ns)).ok_or_else(|| "no run".to_string()),
            instr_whole,
            instr_run,
            mem_bytes: report
                .mem_used
                .ok_or_else(|| "driver reported no mem-used".to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn driver_json_is_read_from_the_last_json_line() {
        let stdout = "noise\n{\"version\": \"CLIPS 6.4.2 (clipspy 1.0.6)\", \"fired\": [3, 3], \
                      \"run_ns\": [10, 30], \"whole_ns\": [50, 70], \"output\": \"seat 1 n1\\n\", \
                      \"mem_used\": 99}\n";
        let report = DriverReport::parse(stdout).expect("valid JSON");
        assert_eq!(report.fired, vec![3, 3]);
        assert_eq!(report.output, "seat 1 n1\n");
        assert_eq!(report.mem_used, Some(99));
        assert!(DriverReport::parse("no json").is_err());
    }
}
