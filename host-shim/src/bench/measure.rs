//! What a measurement holds and the trait every engine under test implements.

use super::debian;
use super::workloads::{self, Kind, Workload};
use super::BenchError;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// A number, or the reason there is none ("not measured: ..."). Reports print the reason
/// instead of inventing a value.
pub type Reading<T> = Result<T, String>;

/// Everything measured for one engine on one workload.
#[derive(Clone, Debug)]
pub struct Measurement {
    pub fired: Reading<u64>,
    /// The program's own result lines (see `Kind::result_prefixes`), in printed order.
    pub result_lines: Reading<Vec<String>>,
    /// Median wall time of the whole thing (process, or load+reset+run in-process).
    pub wall_whole: Reading<Duration>,
    /// Median wall time of the run phase alone.
    pub wall_run: Reading<Duration>,
    /// Instructions of the whole process under callgrind.
    pub instr_whole: Reading<u64>,
    /// Instructions of the program minus the same program without its `(run)`.
    pub instr_run: Reading<u64>,
    /// CLIPS `(mem-used)` after the run, or our arena bytes in use.
    pub mem_bytes: Reading<u64>,
}

impl Measurement {
    /// A measurement with every reading missing for the same reason.
    pub fn not_measured(reason: &str) -> Self {
        Self::missing(format!("not measured: {reason}"))
    }

    /// A measurement that was attempted and failed (shown as "failed: ..." in reports).
    pub fn failed(reason: &str) -> Self {
        Self::missing(reason.to_string())
    }

    /// Replaces the time, instruction and memory readings with `reason`: used when the run
    /// produced wrong results, so its costs must not enter any ratio.
    pub fn withdraw_costs(&mut self, reason: &str) {
        let why = format!("withdrawn: {reason}");
        self.wall_whole = Err(why.clone());
        self.wall_run = Err(why.clone());
        self.instr_whole = Err(why.clone());
        self.instr_run = Err(why.clone());
        self.mem_bytes = Err(why);
    }

    fn missing(why: String) -> Self {
        Self {
            fired: Err(why.clone()),
            result_lines: Err(why.clone()),
            wall_whole: Err(why.clone()),
            wall_run: Err(why.clone()),
            instr_whole: Err(why.clone()),
            instr_run: Err(why.clone()),
            mem_bytes: Err(why),
        }
    }
}

/// How much measuring to do.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Timed repetitions per variant; wall times are medians over these.
    pub reps: usize,
    /// Time-box per callgrind run; `None` skips callgrind.
    pub callgrind_limit: Option<Duration>,
    /// Deadline for one plain (not callgrind) run.
    pub run_limit: Duration,
}

/// The files written for one workload; every engine reads the same ones.
#[derive(Clone, Debug)]
pub struct ProgramFiles {
    pub workload: Workload,
    /// Constructs only (templates, rules, deffacts).
    pub constructs: PathBuf,
    /// `(load* constructs) (watch statistics) (reset) (run) (exit)`.
    pub batch_full: PathBuf,
    /// The same without `(run)`: the baseline subtracted to get the run phase.
    pub batch_norun: PathBuf,
    /// Like `batch_full`, then prints `mem-used N`.
    pub batch_mem: PathBuf,
    /// Scratch space for profiles.
    pub dir: PathBuf,
}

impl ProgramFiles {
    /// Writes the program files for `workload` into `dir/<workload name>/`.
    pub fn write(dir: &Path, workload: Workload) -> Result<Self, BenchError> {
        let dir = dir.join(workload.name());
        std::fs::create_dir_all(&dir)
            .map_err(|e| BenchError::new(format!("creating {}: {e}", dir.display())))?;
        let constructs = dir.join("program.clp");
        let quoted = clips_string(&constructs)?;
        let load = format!("(load* {quoted})\n");
        let files = Self {
            workload,
            batch_full: dir.join("full.bat.clp"),
            batch_norun: dir.join("norun.bat.clp"),
            batch_mem: dir.join("mem.bat.clp"),
            constructs,
            dir,
        };
        if workload.kind == Kind::Llsf {
            files.write_llsf()?;
            return Ok(files);
        }
        if workload.kind == Kind::SudokuRunbench {
            files.write_runbench()?;
            return Ok(files);
        }
        let text = if workload.kind.is_debian_example() {
            debian::program_text(workload)?
        } else {
            workload.constructs_text()
        };
        write_file(&files.constructs, &text)?;
        let full = format!("{load}(watch statistics)\n(reset)\n(run)\n(exit)\n");
        write_file(&files.batch_full, &full)?;
        let norun = format!("{load}(watch statistics)\n(reset)\n(exit)\n");
        write_file(&files.batch_norun, &norun)?;
        let mem =
            format!("{load}(reset)\n(run)\n(printout t \"mem-used \" (mem-used) crlf)\n(exit)\n");
        write_file(&files.batch_mem, &mem)?;
        Ok(files)
    }

    /// The sudoku solver's `runbench.bat` as shipped, its files written into the folder;
    /// `constructs` is their concatenation (for reading, not loaded by the batches).
    fn write_runbench(&self) -> Result<(), BenchError> {
        let batches = debian::write_runbench(&self.dir)?;
        write_file(&self.constructs, &debian::program_text(self.workload)?)?;
        write_file(&self.batch_full, &batches.full)?;
        write_file(&self.batch_norun, &batches.norun)?;
        write_file(&self.batch_mem, &batches.mem)
    }

    /// LLSF games: the rule base's files copied into the folder and loaded one by one;
    /// `constructs` is their concatenation (for reading, not loaded by the batches).
    fn write_llsf(&self) -> Result<(), BenchError> {
        let games = self.workload.size;
        let mut load = String::new();
        let mut all = String::new();
        for file in workloads::llsf_files() {
            let path = self.dir.join(file.name.replace('/', "-"));
            write_file(&path, file.text)?;
            load.push_str(&format!("(load* {})\n", clips_string(&path)?));
            all.push_str(file.text);
            all.push('\n');
        }
        write_file(&self.constructs, &all)?;
        let games_text =
            |with_run| workloads::llsf_games_batch(games, with_run).map_err(BenchError::new);
        let full = format!("{load}(watch statistics)\n{}(exit)\n", games_text(true)?);
        write_file(&self.batch_full, &full)?;
        let norun = format!("{load}(watch statistics)\n{}(exit)\n", games_text(false)?);
        write_file(&self.batch_norun, &norun)?;
        let mem = format!(
            "{load}{}(printout t \"mem-used \" (mem-used) crlf)\n(exit)\n",
            games_text(true)?
        );
        write_file(&self.batch_mem, &mem)
    }
}

/// A path as a CLIPS string literal; refuses paths CLIPS could not read back.
fn clips_string(path: &Path) -> Result<String, BenchError> {
    let text = path
        .to_str()
        .filter(|t| !t.contains(['"', '\\']))
        .ok_or_else(|| {
            BenchError::new(format!(
                "work path {} must be UTF-8 without quotes or backslashes",
                path.display()
            ))
        })?;
    Ok(format!("\"{text}\""))
}

fn write_file(path: &Path, text: &str) -> Result<(), BenchError> {
    std::fs::write(path, text)
        .map_err(|e| BenchError::new(format!("writing {}: {e}", path.display())))
}

/// An engine under test: CLIPS 6.30, CLIPS 6.4 or ours.
pub trait Contender {
    /// Column name in the report, e.g. "CLIPS 6.30".
    fn name(&self) -> String;
    /// `Ok` when the engine can run here, else the reason it is not measured.
    fn probe(&self, scratch: &Path) -> Result<(), String>;
    /// Version text for the report header (called after a successful probe).
    fn version(&self, _scratch: &Path) -> String {
        self.name()
    }
    /// Measures one workload. Missing readings carry their reason.
    fn measure(&self, program: &ProgramFiles, plan: &Plan) -> Measurement;
}

/// The result lines of a program's stdout: lines starting with one of the workload's
/// prefixes.
pub fn result_lines(stdout: &str, prefixes: &[&str]) -> Vec<String> {
    stdout
        .lines()
        .filter(|line| prefixes.iter().any(|p| line.starts_with(p)))
        .map(|line| line.trim_end().to_string())
        .collect()
}

/// The sum of CLIPS's `(watch statistics)` lines `N rules fired` (one per `(run)`).
pub fn parse_rules_fired(stdout: &str) -> Option<u64> {
    let counts: Vec<u64> = stdout
        .lines()
        .filter_map(|line| {
            let (count, _) = line.trim_start().split_once(" rules fired")?;
            count.trim().parse().ok()
        })
        .collect();
    (!counts.is_empty()).then(|| counts.iter().sum())
}

/// The number after `mem-used ` printed by the memory variant.
pub fn parse_mem_used(stdout: &str) -> Option<u64> {
    stdout
        .lines()
        .find_map(|line| line.strip_prefix("mem-used ")?.trim().parse().ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_and_results_are_parsed_from_clips_output() {
        let stdout = "seat 1 n3\nseat 2 n1\n183 rules fired        Run time is 0.01 seconds.\n\
                      18300 rules per second.\n137 mean number of facts (212 maximum).\n";
        assert_eq!(parse_rules_fired(stdout), Some(183));
        assert_eq!(
            result_lines(stdout, &["seat "]),
            vec!["seat 1 n3", "seat 2 n1"]
        );
        assert_eq!(parse_mem_used("x\nmem-used 2054726\n"), Some(2_054_726));
        assert_eq!(parse_rules_fired("nothing here"), None);
    }

    #[test]
    fn program_files_load_the_constructs_by_absolute_path() {
        let dir = std::env::temp_dir().join(format!("bench-files-test-{}", std::process::id()));
        let workload = Workload {
            kind: Kind::Negation,
            size: 100,
        };
        let files = ProgramFiles::write(&dir, workload).expect("temp dir is writable");
        let full = std::fs::read_to_string(&files.batch_full).expect("written");
        let norun = std::fs::read_to_string(&files.batch_norun).expect("written");
        assert!(full.contains(&format!("(load* \"{}\")", files.constructs.display())));
        assert!(full.contains("(run)") && !norun.contains("(run)"));
        assert_eq!(full.replace("(run)\n", ""), norun);
        let constructs = std::fs::read_to_string(&files.constructs).expect("written");
        assert!(constructs.contains("(defrule start_job"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
