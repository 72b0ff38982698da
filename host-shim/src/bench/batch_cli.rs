//! Engines driven as a CLIPS-style command line in batch mode (`PROGRAM -f2 FILE`).
//!
//! Used for the `clips` command (CLIPS 6.30) and for ours (`robotino-agent clips -f2`): the
//! same batch files, the same output parsing, the same callgrind regions.

use super::measure::{
    parse_mem_used, parse_rules_fired, result_lines, Contender, Measurement, Plan, ProgramFiles,
    Reading,
};
use super::process::{callgrind_fits, callgrind_instructions, median, run_with_deadline, Finished};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// A batch-mode CLIPS command line: `program prefix_args... -f2 FILE`.
pub struct BatchCli {
    pub label: String,
    pub program: PathBuf,
    /// Arguments before `-f2`, e.g. `["clips"]` for `robotino-agent clips -f2 FILE`.
    pub prefix_args: Vec<String>,
    /// Ours: the same command line on the large-pool engine, measured instead when a
    /// program exhausts a pool of the default engine.
    pub larger: Option<Box<BatchCli>>,
}

impl BatchCli {
    pub fn clips_630() -> Self {
        Self {
            label: "CLIPS 6.30".to_string(),
            program: PathBuf::from("clips"),
            prefix_args: Vec::new(),
            larger: None,
        }
    }

    /// Ours, through this very binary's `clips` subcommand.
    /// Programs that outgrow the default engine's pools run again with `--large-pools`.
    pub fn ours_cli(this_binary: PathBuf) -> Self {
        let larger = Self {
            label: "ours (CLI)".to_string(),
            program: this_binary.clone(),
            prefix_args: vec!["clips".to_string(), "--large-pools".to_string()],
            larger: None,
        };
        Self {
            label: "ours (CLI)".to_string(),
            program: this_binary,
            prefix_args: vec!["clips".to_string()],
            larger: Some(Box::new(larger)),
        }
    }

    fn args_for<'a>(&'a self, batch: &'a Path) -> Result<Vec<&'a str>, String> {
        let batch = batch
            .to_str()
            .ok_or_else(|| format!("non-UTF-8 path {}", batch.display()))?;
        let mut args: Vec<&str> = self.prefix_args.iter().map(String::as_str).collect();
        args.extend(["-f2", batch]);
        Ok(args)
    }

    fn run_once(&self, batch: &Path, limit: Duration) -> Result<Finished, String> {
        let args = self.args_for(batch)?;
        let finished = run_with_deadline(Command::new(&self.program).args(&args), limit)
            .map_err(|e| e.to_string())?;
        if finished.timed_out {
            return Err(format!("run exceeded {} s", limit.as_secs()));
        }
        // An exhausted pool first: our CLI then also exits non-zero, and the caller
        // measures the program again with `--large-pools` on this reason.
        for text in [&finished.stdout, &finished.stderr] {
            if let Some(pool) = super::ours::capacity_exceeded(text) {
                return Err(format!("capacity exceeded: {pool}"));
            }
        }
        if !finished.status.success() {
            let first_error = finished.stderr.lines().next().unwrap_or("").to_string();
            return Err(format!("{}: {first_error}", finished.status));
        }
        // A program that did not load is not a measurement (ours reads files into a
        // fixed buffer, so a large program fails here).
        if let Some(line) = finished
            .stdout
            .lines()
            .find(|l| l.contains("was unable to open file"))
        {
            return Err(format!("program not loaded: {}", line.trim()));
        }
        Ok(finished)
    }

    fn program_str(&self) -> Result<&str, String> {
        self.program
            .to_str()
            .ok_or_else(|| format!("non-UTF-8 program path {}", self.program.display()))
    }

    fn callgrind(&self, batch: &Path, scratch: &Path, limit: Duration) -> Reading<u64> {
        let args = self.args_for(batch)?;
        callgrind_instructions(self.program_str()?, &args, scratch, limit)
    }
}

impl Contender for BatchCli {
    fn name(&self) -> String {
        self.label.clone()
    }

    fn probe(&self, scratch: &Path) -> Result<(), String> {
        let probe = scratch.join("probe.bat.clp");
        std::fs::write(&probe, "(printout t \"bench-probe-ok\" crlf)\n(exit)\n")
            .map_err(|e| format!("writing {}: {e}", probe.display()))?;
        let finished = self.run_once(&probe, Duration::from_secs(30))?;
        if finished.stdout.contains("bench-probe-ok") {
            Ok(())
        } else {
            Err(format!(
                "{} does not run CLIPS batch files yet",
                self.program.display()
            ))
        }
    }

    /// The banner line (`CLIPS (6.30 3/17/15)`) that echo mode `-f` prints, if any.
    fn version(&self, scratch: &Path) -> String {
        let probe = scratch.join("probe.bat.clp");
        let mut args: Vec<&str> = self.prefix_args.iter().map(String::as_str).collect();
        let banner = probe.to_str().and_then(|probe| {
            args.extend(["-f", probe]);
            let run = run_with_deadline(
                Command::new(&self.program).args(&args),
                Duration::from_secs(30),
            )
            .ok()?;
            run.stdout
                .lines()
                .find(|line| line.contains("CLIPS ("))
                .map(|line| line.trim().to_string())
        });
        let program = self.program.display();
        match banner {
            Some(banner) => format!("`{program}`: {banner}"),
            None => format!("`{program}`"),
        }
    }

    fn measure(&self, program: &ProgramFiles, plan: &Plan) -> Measurement {
        let prefix = program.workload.kind.result_prefixes();
        let mut full_times = Vec::new();
        let mut norun_times = Vec::new();
        let mut fired: Reading<u64> = Err("no run".to_string());
        let mut lines: Reading<Vec<String>> = Err("no run".to_string());
        // Alternate the variants so machine load drifts hit both alike.
        for _ in 0..plan.reps.max(1) {
            match self.run_once(&program.batch_full, plan.run_limit) {
                Ok(run) => {
                    let this_fired = parse_rules_fired(&run.stdout)
                        .ok_or_else(|| "no 'N rules fired' line in output".to_string());
                    if let (Ok(before), Ok(now)) = (&fired, &this_fired) {
                        if before != now {
                            fired = Err(format!(
                                "rules fired differ between runs: {before} vs {now}"
                            ));
                            break;
                        }
                    }
                    fired = this_fired;
                    lines = Ok(result_lines(&run.stdout, prefix));
                    full_times.push(run.elapsed);
                }
                Err(reason) if reason.starts_with("capacity exceeded") => {
                    return match &self.larger {
                        Some(larger) => larger.measure(program, plan),
                        None => Measurement::failed(&reason),
                    };
                }
                Err(reason) => {
                    return Measurement::failed(&format!("{}: {reason}", self.label));
                }
            }
            if let Ok(run) = self.run_once(&program.batch_norun, plan.run_limit) {
                norun_times.push(run.elapsed);
            }
        }
        let wall_whole = median(&full_times).ok_or_else(|| "no timed run".to_string());
        let wall_run = match (&wall_whole, median(&norun_times)) {
            // Tiny programs: the run can vanish in process start-up jitter.
            (Ok(whole), Some(norun)) if *whole <= norun => {
                Err("skipped: below timing noise (whole <= no-run baseline)".to_string())
            }
            (Ok(whole), Some(norun)) => Ok(*whole - norun),
            _ => Err("baseline (no run) failed".to_string()),
        };
        let (instr_whole, instr_run) = match plan.callgrind_limit {
            None => (
                Err("not measured: --no-callgrind".to_string()),
                Err("not measured: --no-callgrind".to_string()),
            ),
            Some(limit) => {
                let whole = wall_whole
                    .clone()
                    .and_then(|native| callgrind_fits(native, Duration::ZERO, limit))
                    .and_then(|()| self.callgrind(&program.batch_full, &program.dir, limit));
                let run = match &whole {
                    Ok(whole) => self
                        .callgrind(&program.batch_norun, &program.dir, limit)
                        .map(|norun| whole.saturating_sub(norun)),
                    Err(reason) => Err(reason.clone()),
                };
                (whole, run)
            }
        };
        // Ours has no `(mem-used)`: its memory is the in-process column's arena figure.
        let mem_bytes = if self.label.starts_with("ours") {
            Err("not measured: see the in-process column".to_string())
        } else {
            self.run_once(&program.batch_mem, plan.run_limit)
                .and_then(|run| {
                    parse_mem_used(&run.stdout).ok_or_else(|| "no 'mem-used' line".to_string())
                })
        };
        Measurement {
            fired,
            result_lines: lines,
            wall_whole,
            wall_run,
            instr_whole,
            instr_run,
            mem_bytes,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A program that runs out of a pool and exits non-zero (as our CLI does when a load
    /// fails) is reported as an exhausted pool, so it is measured again with the large
    /// pools instead of failing.
    #[test]
    fn an_exhausted_pool_is_reported_even_with_a_failing_exit_status() {
        let cli = |script: &str| BatchCli {
            label: "test".to_string(),
            program: PathBuf::from("sh"),
            prefix_args: vec!["-c".to_string(), script.to_string(), "sh".to_string()],
            larger: None,
        };
        let batch = Path::new("unused.clp");
        let limit = Duration::from_secs(30);
        let out_of = cli("echo '[MEMORY] out of expression nodes (capacity 32768)'; exit 1");
        assert_eq!(
            out_of.run_once(batch, limit).err(),
            Some("capacity exceeded: out of expression nodes (capacity 32768)".to_string())
        );
        let plain_failure = cli("echo 'bad thing' >&2; exit 1");
        let reason = plain_failure
            .run_once(batch, limit)
            .err()
            .unwrap_or_default();
        assert!(reason.contains("bad thing"), "{reason}");
        assert!(cli("echo fine").run_once(batch, limit).is_ok());
    }
}
