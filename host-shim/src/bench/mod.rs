//! `robotino-agent bench`: our engine against CLIPS 6.30 (`clips`) and CLIPS 6.4 (clipspy).
//!
//! Writes the workload programs (Miss Manners, join-heavy and negation-heavy scaling), runs
//! every available engine on the same files, checks their results agree, prints a ratio
//! table and regenerates `BENCHMARKS.md`. Where ours plugs in: see [`ours`]. How the LLSF
//! decision time will be measured: `DECISION_TIME.md` in this folder.

mod batch_cli;
mod clipspy;
mod debian;
mod decision;
mod footprint;
mod generated;
mod measure;
mod ours;
mod process;
mod report;
mod rng;
mod workloads;

use batch_cli::BatchCli;
use clipspy::ClipsPy;
use measure::{Contender, Measurement, Plan, ProgramFiles};
use ours::OursInProcess;
use report::{Machine, Report, Row};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use workloads::{Kind, Workload};

/// An error with the context needed to act on it.
#[derive(Debug)]
pub struct BenchError {
    context: String,
}

impl BenchError {
    pub fn new(context: String) -> Self {
        Self { context }
    }
}

impl std::fmt::Display for BenchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.context)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum WorkloadArg {
    /// --games seeded LLSF games of the agent rule base (paper strategy).
    Llsf,
    /// Miss Manners at each --manners-sizes guest count.
    Manners,
    /// Join-heavy scaling program at each --scale-sizes fact count.
    Join,
    /// Negation-heavy scaling program at each --scale-sizes fact count.
    Negation,
    /// Generated: many rules with constant tests on one template (--discrim-sizes rules).
    Discrim,
    /// Generated: joins on two and three shared variables (--join3-sizes facts each).
    Join3,
    /// Generated: assert/retract chains with not/exists (--propagate-sizes nodes).
    Propagate,
    /// Generated: many rules, few facts, like an agent (--agent-sizes rules).
    Agent,
    /// Generated: a join keyed on a row with an or of variables on another slot, and a
    /// not of the same shape (--keyed-or-sizes cells per row).
    KeyedOr,
    /// Generated: as keyed-or, keyed on two slots, an or of three (--keyed-or-sizes).
    Keyed2Or3,
    /// The published Miss Manners (printout between find_seating's modifies) at each
    /// --manners-sizes guest count.
    MannersPub,
    /// The sudoku solver of Debian's clips-common examples, each --sudoku-puzzles puzzle.
    Sudoku,
    /// The sudoku solver's runbench.bat as shipped (a puzzle, then the stress test).
    Runbench,
    /// The zebra puzzle of Debian's clips-common examples.
    Zebra,
}

/// A sudoku puzzle named like its file, `GxG-pN` (e.g. `3x3-p17`), as the workload size
/// `G * 100 + N`.
fn parse_puzzle(text: &str) -> Result<usize, String> {
    let bad = || format!("{text:?}: expected GRIDxGRID-pNUMBER, e.g. 3x3-p17");
    let (grid, puzzle) = text.split_once("-p").ok_or_else(bad)?;
    let (rows, columns) = grid.split_once('x').ok_or_else(bad)?;
    let rows: usize = rows.parse().map_err(|_| bad())?;
    let columns: usize = columns.parse().map_err(|_| bad())?;
    let puzzle: usize = puzzle.parse().map_err(|_| bad())?;
    if rows != columns || !(2..=5).contains(&rows) || !(1..100).contains(&puzzle) {
        return Err(bad());
    }
    Ok(rows * 100 + puzzle)
}

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Workloads to run (comma-separated).
    #[arg(long, value_enum, value_delimiter = ',', default_values = ["llsf", "manners", "join", "negation", "discrim", "join3", "propagate", "agent", "keyed-or", "keyed2-or3", "manners-pub", "sudoku", "runbench", "zebra"])]
    pub workloads: Vec<WorkloadArg>,
    /// Seeded LLSF games (seeds 0..N) played in one process per measurement.
    #[arg(long, default_value_t = 10)]
    pub games: usize,
    /// Guest counts for Miss Manners (even numbers).
    #[arg(long, value_delimiter = ',', default_values_t = [16, 32, 64, 128])]
    pub manners_sizes: Vec<usize>,
    /// Fact counts for the join and negation programs.
    #[arg(long, value_delimiter = ',', default_values_t = [100, 1000, 10000, 100000])]
    pub scale_sizes: Vec<usize>,
    /// Rule counts of the generated discrimination program (multiples of 4).
    #[arg(long, value_delimiter = ',', default_values_t = [40, 80, 160, 320])]
    pub discrim_sizes: Vec<usize>,
    /// Facts per template of the generated two- and three-variable join program.
    #[arg(long, value_delimiter = ',', default_values_t = [1000, 2000, 4000, 8000])]
    pub join3_sizes: Vec<usize>,
    /// Nodes of the generated propagation program.
    #[arg(long, value_delimiter = ',', default_values_t = [500, 1000, 2000, 4000])]
    pub propagate_sizes: Vec<usize>,
    /// Rule counts of the generated agent-like program (2000 firings each).
    #[arg(long, value_delimiter = ',', default_values_t = [40, 80, 160, 320])]
    pub agent_sizes: Vec<usize>,
    /// Cells per row of the generated keyed-or programs (800 probes each).
    #[arg(long, value_delimiter = ',', default_values_t = [25, 100, 400, 1600])]
    pub keyed_or_sizes: Vec<usize>,
    /// Puzzles of the Debian sudoku example (its file names, `GxG-pN`).
    #[arg(long, value_delimiter = ',', value_parser = parse_puzzle,
          default_values = ["3x3-p1", "3x3-p10", "3x3-p17", "4x4-p1", "4x4-p9", "4x4-p17", "5x5-p1"])]
    pub sudoku_puzzles: Vec<usize>,
    /// Cheap run: every selected workload at its smallest size only, one repetition,
    /// no decision time (for a quick look, not for BENCHMARKS.md).
    #[arg(long)]
    pub quick: bool,
    /// Timed repetitions per measurement (wall times are medians).
    #[arg(long, default_value_t = 5)]
    pub reps: usize,
    /// Skip the callgrind instruction counts.
    #[arg(long)]
    pub no_callgrind: bool,
    /// Time-box for one callgrind run, in seconds.
    #[arg(long, default_value_t = 300)]
    pub callgrind_timeout: u64,
    /// Deadline for one plain run, in seconds.
    #[arg(long, default_value_t = 120)]
    pub run_timeout: u64,
    /// Leave out CLIPS 6.4 (clipspy).
    #[arg(long)]
    pub no_clipspy: bool,
    /// Markdown report to regenerate.
    #[arg(long, default_value = "BENCHMARKS.md")]
    pub out: PathBuf,
    /// Where the generated programs and scratch files go (default: a temp folder).
    #[arg(long)]
    pub work_dir: Option<PathBuf>,
    /// Only write the programs into the work directory and list them.
    #[arg(long)]
    pub emit_only: bool,
    /// The footprint tool's JSON for the memory row (default:
    /// `$CARGO_TARGET_DIR/footprint.json`, else `target/footprint.json`).
    #[arg(long)]
    pub footprint_json: Option<PathBuf>,
    /// Leave out the LLSF decision-time measurement.
    #[arg(long)]
    pub no_decision: bool,
    /// Internal: the decision-time child process counted under callgrind (GAMES).
    #[arg(long, hide = true)]
    pub decision_child: Option<usize>,
}

impl Args {
    fn selected_workloads(&self) -> Vec<Workload> {
        let mut selected = Vec::new();
        for arg in &self.workloads {
            let games = [self.games];
            let one = [1];
            let (kind, sizes) = match arg {
                WorkloadArg::Llsf => (Kind::Llsf, &games[..]),
                WorkloadArg::Manners => (Kind::Manners, &self.manners_sizes[..]),
                WorkloadArg::Join => (Kind::Join, &self.scale_sizes[..]),
                WorkloadArg::Negation => (Kind::Negation, &self.scale_sizes[..]),
                WorkloadArg::Discrim => (Kind::Discrim, &self.discrim_sizes[..]),
                WorkloadArg::Join3 => (Kind::Join3, &self.join3_sizes[..]),
                WorkloadArg::Propagate => (Kind::Propagate, &self.propagate_sizes[..]),
                WorkloadArg::Agent => (Kind::Agent, &self.agent_sizes[..]),
                WorkloadArg::KeyedOr => (Kind::KeyedOr, &self.keyed_or_sizes[..]),
                WorkloadArg::Keyed2Or3 => (Kind::Keyed2Or3, &self.keyed_or_sizes[..]),
                WorkloadArg::MannersPub => (Kind::MannersPublished, &self.manners_sizes[..]),
                WorkloadArg::Sudoku => (Kind::Sudoku, &self.sudoku_puzzles[..]),
                WorkloadArg::Runbench => (Kind::SudokuRunbench, &one[..]),
                WorkloadArg::Zebra => (Kind::Zebra, &one[..]),
            };
            // Ascending, so an engine that fails at one size can skip the larger ones.
            let mut sizes = sizes.to_vec();
            sizes.sort_unstable();
            sizes.dedup();
            if self.quick {
                sizes.truncate(1);
            }
            selected.extend(sizes.into_iter().map(|size| Workload { kind, size }));
        }
        selected
    }
}

pub fn main(args: Args) -> ExitCode {
    // The sim's engines keep their storage inline: run on a thread with their stack.
    let worker = std::thread::Builder::new()
        .stack_size(crate::sim::game::ENGINE_THREAD_STACK)
        .spawn(move || run(&args));
    let outcome = match worker.map(|w| w.join()) {
        Ok(Ok(outcome)) => outcome,
        Ok(Err(_)) => Err(BenchError::new("the bench thread panicked".to_string())),
        Err(e) => Err(BenchError::new(format!(
            "cannot start the bench thread: {e}"
        ))),
    };
    match outcome {
        Ok(all_agree) if all_agree => ExitCode::SUCCESS,
        Ok(_) => {
            eprintln!("bench: some engines disagree on results (see the report)");
            ExitCode::FAILURE
        }
        Err(error) => {
            eprintln!("bench: {error}");
            ExitCode::FAILURE
        }
    }
}

/// Runs the benchmark; returns whether every workload's results agree.
fn run(args: &Args) -> Result<bool, BenchError> {
    if let Some(games) = args.decision_child {
        decision::child_main(games).map_err(BenchError::new)?;
        return Ok(true);
    }
    let workloads = args.selected_workloads();
    for workload in &workloads {
        workload.validate().map_err(BenchError::new)?;
    }
    let work_dir = args
        .work_dir
        .clone()
        .unwrap_or_else(|| std::env::temp_dir().join("robotino-bench"));
    let programs = workloads
        .iter()
        .map(|&w| ProgramFiles::write(&work_dir, w))
        .collect::<Result<Vec<_>, _>>()?;
    if args.emit_only {
        for program in &programs {
            println!(
                "{}: {} (constructs {})",
                program.workload.name(),
                program.batch_full.display(),
                program.constructs.display()
            );
        }
        return Ok(true);
    }

    let plan = Plan {
        reps: if args.quick { 1 } else { args.reps.max(1) },
        callgrind_limit: (!args.no_callgrind && process::valgrind_available())
            .then(|| Duration::from_secs(args.callgrind_timeout)),
        run_limit: Duration::from_secs(args.run_timeout),
    };
    if !args.no_callgrind && plan.callgrind_limit.is_none() {
        eprintln!("bench: valgrind not found, instruction counts are skipped");
    }
    if cfg!(debug_assertions) {
        eprintln!("bench: debug build: ours runs unoptimised, use a release build for numbers");
    }
    let contenders = contenders(args)?;
    let probed: Vec<(String, Result<String, String>)> = contenders
        .iter()
        .map(|c| (c.name(), describe(c.as_ref(), &work_dir)))
        .collect();
    for (name, status) in &probed {
        match status {
            Ok(version) => eprintln!("bench: {name}: {version}"),
            Err(reason) => eprintln!("bench: {name}: not measured: {reason}"),
        }
    }

    let started = Instant::now();
    let mut rows = Vec::new();
    let mut all_agree = true;
    // (contender index, workload kind, size) of runs that failed: larger sizes of the same
    // kind are skipped for that engine instead of waiting for another deadline.
    let mut failed_at: Vec<(usize, Kind, usize)> = Vec::new();
    for program in &programs {
        let mut measured = Vec::new();
        for (index, (contender, (name, status))) in contenders.iter().zip(&probed).enumerate() {
            let kind = program.workload.kind;
            let earlier_failure = failed_at
                .iter()
                .find(|(i, k, _)| *i == index && *k == kind)
                .map(|(_, _, size)| *size);
            let measurement = match (status, earlier_failure) {
                (Ok(_), Some(size)) => {
                    Measurement::failed(&format!("skipped: failed at {}-{size}", kind.label()))
                }
                (Ok(_), None) => {
                    eprintln!(
                        "bench: [{:>5.0} s] {} on {}",
                        started.elapsed().as_secs_f64(),
                        name,
                        program.workload.name()
                    );
                    let measurement = contender.measure(program, &plan);
                    if let Err(reason) = &measurement.wall_whole {
                        eprintln!(
                            "bench: {name} failed on {}: {reason}",
                            program.workload.name()
                        );
                        failed_at.push((index, kind, program.workload.size));
                    }
                    measurement
                }
                (Err(reason), _) => Measurement::not_measured(reason),
            };
            measured.push(measurement);
        }
        let names: Vec<&str> = probed.iter().map(|(n, _)| n.as_str()).collect();
        let outcome = agreement(program.workload, &names, &measured);
        all_agree &= outcome.all_agree;
        for (m, name) in measured.iter_mut().zip(&names) {
            if outcome.wrong.iter().any(|w| w == name) {
                m.withdraw_costs("wrong results");
            }
        }
        rows.push(Row {
            workload: program.workload,
            measured,
            agreement: outcome.text,
        });
    }

    let decisions = if args.no_decision || args.quick {
        Err("not measured: --no-decision or --quick".to_string())
    } else {
        eprintln!(
            "bench: [{:>5.0} s] decision time over {} games",
            started.elapsed().as_secs_f64(),
            args.games
        );
        let callgrind = plan
            .callgrind_limit
            .map(|limit| (limit, work_dir.as_path()));
        decision::measure(args.games, plan.reps, callgrind)
    };
    if let Err(reason) = &decisions {
        eprintln!("bench: decision time: {reason}");
    }

    let mut footprints = footprint::clips_630();
    if !args.no_clipspy {
        footprints.extend(footprint::clipspy("python3"));
    }
    let report = Report {
        command_line: std::iter::once("robotino-agent".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" "),
        machine: Machine::detect(),
        plan,
        contenders: probed,
        rows,
        footprints,
        decisions,
        image: footprint::image_footprint(&footprint_json_path(args)),
    };
    print!("{}", report.terminal_table());
    std::fs::write(&args.out, report.markdown())
        .map_err(|e| BenchError::new(format!("writing {}: {e}", args.out.display())))?;
    eprintln!("bench: wrote {}", args.out.display());
    Ok(all_agree)
}

fn footprint_json_path(args: &Args) -> PathBuf {
    args.footprint_json.clone().unwrap_or_else(|| {
        let target = std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("target"));
        target.join("footprint.json")
    })
}

/// The engines under test, in report column order: references first, then ours.
fn contenders(args: &Args) -> Result<Vec<Box<dyn Contender>>, BenchError> {
    let this_binary = std::env::current_exe()
        .map_err(|e| BenchError::new(format!("locating robotino-agent itself: {e}")))?;
    let mut list: Vec<Box<dyn Contender>> = vec![Box::new(BatchCli::clips_630())];
    if !args.no_clipspy {
        list.push(Box::new(ClipsPy::new()));
    }
    list.push(Box::new(BatchCli::ours_cli(this_binary)));
    list.push(Box::new(OursInProcess::new()));
    Ok(list)
}

/// A contender's version text when it runs here, else why not.
fn describe(contender: &dyn Contender, scratch: &std::path::Path) -> Result<String, String> {
    std::fs::create_dir_all(scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    contender.probe(scratch)?;
    Ok(contender.version(scratch))
}

/// Whether the measured engines' results agree, and the text for the report. Manners
/// results are compared as sets of seat lines (print order is not the result) and each is
/// checked to be a valid seating of the generated guests.
/// The outcome of comparing the engines' results on one workload.
struct Agreement {
    all_agree: bool,
    /// For the report's "results" column.
    text: String,
    /// Engines whose results are wrong: their speed and memory readings are withdrawn, since
    /// a run that computed something else (or stopped early) is not comparable.
    wrong: Vec<String>,
}

fn agreement(workload: Workload, names: &[&str], measured: &[Measurement]) -> Agreement {
    let normalise = |lines: &Vec<String>| {
        let mut lines = lines.clone();
        if workload.kind == Kind::Manners {
            lines.sort();
        }
        lines
    };
    let results: Vec<(&str, Vec<String>, Option<u64>)> = names
        .iter()
        .zip(measured)
        .filter_map(|(name, m)| {
            let lines = m.result_lines.as_ref().ok()?;
            Some((*name, normalise(lines), m.fired.clone().ok()))
        })
        .collect();
    let Some((reference, reference_lines, reference_fired)) = results.first() else {
        return Agreement {
            all_agree: false,
            text: "no engine produced results".to_string(),
            wrong: Vec::new(),
        };
    };
    let mut problems = Vec::new();
    let mut wrong = Vec::new();
    if reference_lines.is_empty() {
        problems.push(format!("{reference} printed no result lines"));
    }
    for (name, lines, fired) in &results[1..] {
        if lines != reference_lines {
            // Same firings, other output (e.g. another activation order among equals):
            // the row fails, but the costs stay visible as the work done was comparable.
            // A different number of firings withdraws them (below).
            problems.push(format!("{name} results differ from {reference}"));
        }
        // A count an engine did not report is shown as missing in its own column.
        if let (Some(fired), Some(reference_fired)) = (fired, reference_fired) {
            if fired != reference_fired {
                problems.push(format!(
                    "{name} fired {fired} rules, {reference} {reference_fired}"
                ));
                wrong.push(name.to_string());
            }
        }
    }
    if matches!(workload.kind, Kind::Manners | Kind::MannersPublished) {
        let guests = workloads::manners_guests(workload.size);
        for (name, lines, _) in &results {
            let seating = if workload.kind == Kind::MannersPublished {
                workloads::published_seating(lines)
            } else {
                lines.clone()
            };
            if let Err(why) = workloads::check_seating(&guests, &seating) {
                problems.push(format!("{name} seating invalid: {why}"));
                wrong.push(name.to_string());
            }
        }
    }
    let who: Vec<&str> = results.iter().map(|(n, _, _)| *n).collect();
    if problems.is_empty() {
        let valid = if matches!(workload.kind, Kind::Manners | Kind::MannersPublished) {
            "; valid seating"
        } else {
            ""
        };
        let text = if who.len() == 1 {
            format!("only {} measured{valid}", who[0])
        } else {
            format!("agree: {}{valid}", who.join(" = "))
        };
        Agreement {
            all_agree: true,
            text,
            wrong,
        }
    } else {
        wrong.dedup();
        Agreement {
            all_agree: false,
            text: format!("DIFFER: {}", problems.join("; ")),
            wrong,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_lines(lines: &[&str], fired: u64) -> Measurement {
        let mut m = Measurement::not_measured("test");
        m.result_lines = Ok(lines.iter().map(|l| l.to_string()).collect());
        m.fired = Ok(fired);
        m
    }

    #[test]
    fn scaling_results_must_match_exactly() {
        let workload = Workload {
            kind: Kind::Join,
            size: 100,
        };
        let same = [
            with_lines(&["reach2 4 reach4 2"], 7),
            with_lines(&["reach2 4 reach4 2"], 7),
        ];
        let outcome = agreement(workload, &["a", "b"], &same);
        assert!(
            outcome.all_agree && outcome.wrong.is_empty(),
            "{}",
            outcome.text
        );
        let different = [
            with_lines(&["reach2 4 reach4 2"], 7),
            with_lines(&["reach2 5 reach4 2"], 7),
        ];
        let outcome = agreement(workload, &["a", "b"], &different);
        assert!(!outcome.all_agree);
        assert!(
            outcome.wrong.is_empty(),
            "same firings: costs stay comparable"
        );
        let fired = [
            with_lines(&["reach2 4 reach4 2"], 7),
            with_lines(&["reach2 4 reach4 2"], 8),
        ];
        let outcome = agreement(workload, &["a", "b"], &fired);
        assert!(!outcome.all_agree);
        assert_eq!(outcome.wrong, vec!["b".to_string()]);
        let mut uncounted = with_lines(&["reach2 4 reach4 2"], 7);
        uncounted.fired = Err("no 'N rules fired' line".to_string());
        let counted_once = [with_lines(&["reach2 4 reach4 2"], 7), uncounted];
        assert!(agreement(workload, &["a", "b"], &counted_once).all_agree);
        let absent = [
            with_lines(&["reach2 4 reach4 2"], 7),
            Measurement::not_measured("x"),
        ];
        assert!(agreement(workload, &["a", "b"], &absent).all_agree);
    }

    #[test]
    fn manners_results_compare_as_seatings_and_must_be_valid() {
        let workload = Workload {
            kind: Kind::Manners,
            size: 4,
        };
        let guests = workloads::manners_guests(4);
        let man: Vec<&str> = guests
            .iter()
            .filter(|g| g.sex == 'm')
            .map(|g| g.name.as_str())
            .collect();
        let woman: Vec<&str> = guests
            .iter()
            .filter(|g| g.sex == 'f')
            .map(|g| g.name.as_str())
            .collect();
        let seats = [
            format!("seat 1 {}", man[0]),
            format!("seat 2 {}", woman[0]),
            format!("seat 3 {}", man[1]),
            format!("seat 4 {}", woman[1]),
        ];
        let forward: Vec<&str> = seats.iter().map(String::as_str).collect();
        let backward: Vec<&str> = seats.iter().rev().map(String::as_str).collect();
        let outcome = agreement(
            workload,
            &["a", "b"],
            &[with_lines(&forward, 9), with_lines(&backward, 9)],
        );
        assert!(outcome.all_agree, "{}", outcome.text);
        assert!(outcome.text.contains("valid seating"));
        let broken = [with_lines(&forward[..3], 9)];
        assert!(!agreement(workload, &["a"], &broken).all_agree);
    }

    /// Runs the small programs in the real engines installed here (skips those absent):
    /// Manners must yield a valid seating and the engines must agree.
    #[test]
    fn small_programs_agree_in_the_installed_clips_engines() {
        let dir = std::env::temp_dir().join(format!("bench-clips-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir is writable");
        let engines: Vec<Box<dyn Contender>> =
            vec![Box::new(BatchCli::clips_630()), Box::new(ClipsPy::new())];
        let available: Vec<&Box<dyn Contender>> =
            engines.iter().filter(|e| e.probe(&dir).is_ok()).collect();
        if available.is_empty() {
            eprintln!("neither clips nor clipspy installed: nothing to compare");
            return;
        }
        let plan = Plan {
            reps: 1,
            callgrind_limit: None,
            run_limit: Duration::from_secs(60),
        };
        let mut programs = vec![
            (Kind::Manners, 16),
            (Kind::MannersPublished, 16),
            (Kind::Join, 100),
            (Kind::Negation, 100),
            (Kind::Discrim, 40),
            (Kind::Join3, 1000),
            (Kind::Propagate, 500),
            (Kind::Agent, 40),
            (Kind::KeyedOr, 25),
            (Kind::Keyed2Or3, 25),
        ];
        programs.extend(debian_examples_if_installed());
        for (kind, size) in programs {
            let workload = Workload { kind, size };
            let files = ProgramFiles::write(&dir, workload).expect("temp dir is writable");
            let measured: Vec<Measurement> =
                available.iter().map(|e| e.measure(&files, &plan)).collect();
            let names: Vec<String> = available.iter().map(|e| e.name()).collect();
            let names: Vec<&str> = names.iter().map(String::as_str).collect();
            for m in &measured {
                assert!(
                    m.fired.as_ref().is_ok_and(|&f| f > size as u64 / 2),
                    "{m:?}"
                );
            }
            let outcome = agreement(workload, &names, &measured);
            assert!(outcome.all_agree, "{}: {}", workload.name(), outcome.text);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The small programs of Debian's clips-common examples (zebra, an easy sudoku),
    /// where the package is installed.
    fn debian_examples_if_installed() -> Vec<(Kind, usize)> {
        if debian::read_example("zebra.clp").is_err() {
            eprintln!("clips-common examples not installed: zebra and sudoku not compared");
            return Vec::new();
        }
        vec![(Kind::Zebra, 1), (Kind::Sudoku, 301)]
    }

    /// Ours in-process fires as many rules as CLIPS 6.30 on the small programs and prints
    /// the same results where the activation order is CLIPS's (Manners, join).
    #[test]
    fn ours_in_process_fires_like_clips() {
        let dir = std::env::temp_dir().join(format!("bench-ours-clips-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir is writable");
        let clips = BatchCli::clips_630();
        if let Err(why) = clips.probe(&dir) {
            eprintln!(
                "SKIPPED: CLIPS 6.30 (`clips`) not usable here ({why}): ours is not compared"
            );
            return;
        }
        let plan = Plan {
            reps: 1,
            callgrind_limit: None,
            run_limit: Duration::from_secs(60),
        };
        let examples = debian_examples_if_installed()
            .into_iter()
            .map(|(kind, size)| (kind, size, true));
        for (kind, size, same_output) in [
            (Kind::Manners, 16, true),
            (Kind::MannersPublished, 16, true),
            (Kind::Join, 100, true),
            (Kind::Negation, 100, false),
            // the generated kinds at their smallest default sizes: their result lines
            // do not depend on the order of equal activations
            (Kind::Discrim, 40, true),
            (Kind::Join3, 1000, true),
            (Kind::Propagate, 500, true),
            (Kind::Agent, 40, true),
            (Kind::KeyedOr, 25, true),
            (Kind::Keyed2Or3, 25, true),
        ]
        .into_iter()
        .chain(examples)
        {
            let workload = Workload { kind, size };
            let files = ProgramFiles::write(&dir, workload).expect("temp dir is writable");
            let reference = clips.measure(&files, &plan);
            let in_thread = files.clone();
            let in_plan = plan.clone();
            let ours = std::thread::Builder::new()
                .stack_size(crate::sim::game::ENGINE_THREAD_STACK)
                .spawn(move || OursInProcess::new().measure(&in_thread, &in_plan))
                .expect("engine thread starts")
                .join()
                .expect("engine thread runs");
            assert!(
                reference.fired.is_ok(),
                "{}: {reference:?}",
                workload.name()
            );
            assert_eq!(ours.fired, reference.fired, "{}", workload.name());
            let outcome = agreement(workload, &["clips", "ours"], &[reference, ours]);
            assert!(outcome.wrong.is_empty(), "{}", outcome.text);
            if same_output {
                assert!(outcome.all_agree, "{}: {}", workload.name(), outcome.text);
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn default_arguments_select_all_fifty_programs() {
        use clap::Parser;
        #[derive(clap::Parser)]
        struct Wrapper {
            #[command(flatten)]
            args: Args,
        }
        let parsed = Wrapper::parse_from(["bench"]);
        let names: Vec<String> = parsed
            .args
            .selected_workloads()
            .iter()
            .map(Workload::name)
            .collect();
        assert_eq!(names.len(), 50);
        assert_eq!(names[0], "llsf-10");
        assert_eq!(names[1], "manners-16");
        assert_eq!(names[12], "negation-100000");
        assert_eq!(names[13], "discrim-40");
        assert_eq!(names[28], "agent-320");
        assert_eq!(names[29], "keyed-or-25");
        assert_eq!(names[36], "keyed2-or3-1600");
        assert_eq!(names[37], "manners-pub-16");
        assert_eq!(names[41], "sudoku-3x3-p1");
        assert_eq!(names[47], "sudoku-5x5-p1");
        assert_eq!(names[48], "sudoku-runbench");
        assert_eq!(names[49], "zebra");
        assert!(Wrapper::try_parse_from(["bench", "--sudoku-puzzles", "3x4-p1"]).is_err());
        assert!(Wrapper::try_parse_from(["bench", "--sudoku-puzzles", "4x4"]).is_err());
        let quick = Wrapper::parse_from(["bench", "--quick", "--workloads", "join3,agent"]);
        assert_eq!(
            quick.args.selected_workloads(),
            vec![
                Workload {
                    kind: Kind::Join3,
                    size: 1000
                },
                Workload {
                    kind: Kind::Agent,
                    size: 40
                }
            ]
        );
        let only = Wrapper::parse_from(["bench", "--workloads", "join", "--scale-sizes", "300"]);
        assert_eq!(
            only.args.selected_workloads(),
            vec![Workload {
                kind: Kind::Join,
                size: 300
            }]
        );
    }
}
