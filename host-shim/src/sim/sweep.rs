//! `robotino-agent sweep`: every distinct assignment (4200 for the 2012 mix),
//! one engine per worker thread, with a summary of points, products,
//! deadlocks and speed.

use std::fmt::Write;
use std::process::ExitCode;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rules::setup::{assignment_by_index, GameSetup, ASSIGNMENT_COUNT};
use rules::Strategy;

use super::game::{Player, SimError, ENGINE_THREAD_STACK};
use super::record::{EndReason, GameRecord};

/// Options of `robotino-agent sweep`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Production strategy: naive, paper or travel.
    #[arg(long, default_value = "paper", value_parser = super::parse_strategy)]
    pub strategy: Strategy,
    /// Play without the clock (reports P made per 20 S0).
    #[arg(long)]
    pub clock_off: bool,
    /// Play only the first N assignments.
    #[arg(long)]
    pub limit: Option<u32>,
    /// Worker threads (default: the available cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar (for scripts and tests).
    #[arg(long)]
    pub quiet: bool,
    /// Disturb each decision with probability PCT % (lost puck, failed grab,
    /// failed goto, wrong light); game N's faults are drawn from seed N.
    #[arg(long, value_name = "PCT", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub fault_rate: u32,
    /// Points against fault rate: the paper and travel strategies at 0, 5,
    /// 10 and 20 % faults, one table row each (ignores --strategy and
    /// --fault-rate).
    #[arg(long, conflicts_with = "fault_rate")]
    pub fault_table: bool,
    /// Robots in the team: above 1 plays every assignment with the team (one engine
    /// per robot) and with one robot, and prints a table of both.
    #[arg(long, default_value_t = 1, conflicts_with_all = ["fault_table", "fault_rate"])]
    pub robots: u8,
}

/// What a sweep plays: strategy, clock and faults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SweepConfig {
    pub strategy: Strategy,
    pub clock_off: bool,
    /// Faults per decision in %, seeded by the assignment index.
    pub fault_rate: u32,
}

/// Fault rates of `sweep --fault-table`.
pub const TABLE_FAULT_RATES: [u32; 4] = [0, 5, 10, 20];
/// Strategies of `sweep --fault-table`.
pub const TABLE_STRATEGIES: [Strategy; 2] = [Strategy::Paper, Strategy::Travel];

/// What the sweep keeps of one game.
#[derive(Clone, Debug)]
pub struct GameSummary {
    pub index: u32,
    pub points: i64,
    pub s1: i64,
    pub s2: i64,
    pub p: i64,
    pub decisions: usize,
    pub end: EndReason,
    pub end_time: f64,
    pub travelled: f64,
    pub lost: i64,
    pub discarded: i64,
    /// Junk pucks recycled (2012 recycling).
    pub recycled: i64,
    /// The engine thread panicked during this game (always a bug).
    pub panicked: bool,
}

impl GameSummary {
    fn of(index: u32, r: &GameRecord) -> GameSummary {
        GameSummary {
            index,
            points: r.score.points,
            s1: r.score.s1,
            s2: r.score.s2,
            p: r.score.p,
            decisions: r.decisions.len(),
            end: r.end,
            end_time: r.end_time,
            travelled: r.travelled,
            lost: r.score.lost,
            discarded: r.score.discarded,
            recycled: r.score.recycled,
            panicked: false,
        }
    }

    fn panicked(index: u32) -> GameSummary {
        GameSummary {
            index,
            points: 0,
            s1: 0,
            s2: 0,
            p: 0,
            decisions: 0,
            end: EndReason::Stalled,
            end_time: 0.0,
            travelled: 0.0,
            lost: 0,
            discarded: 0,
            recycled: 0,
            panicked: true,
        }
    }
}

/// The setup of assignment `index` under the sweep's options.
pub fn sweep_setup(index: u32, config: SweepConfig) -> Option<GameSetup> {
    let mut setup = GameSetup::new(assignment_by_index(index)?);
    if config.clock_off {
        setup.clock_limit_s = None;
    }
    if config.fault_rate > 0 {
        setup = setup.with_fault_rate(config.fault_rate, u64::from(index));
    }
    Some(setup)
}

/// Plays assignments `0..count` on `threads` workers; `on_game` is called
/// after every game (for the progress bar). Results are ordered by index.
pub fn play_all(
    config: SweepConfig,
    count: u32,
    threads: usize,
    on_game: &(dyn Fn() + Sync),
) -> Result<Vec<GameSummary>, SimError> {
    let new_player = || Player::new(config.strategy);
    let play = |player: &mut Player, index: u32, setup: &GameSetup| {
        // A panic is counted, not fatal: the sweep must say how
        // many games panic (0 is the requirement).
        let played =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| player.play(setup, false)));
        match played {
            Ok(record) => Ok(GameSummary::of(
                index,
                &record.map_err(|e| SimError::Input(format!("assignment #{index}: {e}")))?,
            )),
            Err(_) => {
                // The engine may be half-way through an operation.
                *player = Player::new(config.strategy)?;
                Ok(GameSummary::panicked(index))
            }
        }
    };
    on_workers(config, count, threads, &new_player, &play, on_game)
}

/// The worker pool of every sweep: `threads` scoped workers, each with its own
/// `new_worker()` state (its engines), take the next assignment index until `count`
/// and call `play` on it; the first error stops all workers at their next game.
/// Results are ordered by index.
pub fn on_workers<W, T: Send>(
    config: SweepConfig,
    count: u32,
    threads: usize,
    new_worker: &(dyn Fn() -> Result<W, SimError> + Sync),
    play: &(dyn Fn(&mut W, u32, &GameSetup) -> Result<T, SimError> + Sync),
    on_game: &(dyn Fn() + Sync),
) -> Result<Vec<T>, SimError> {
    let next = AtomicU32::new(0);
    let results: Mutex<Vec<(u32, T)>> = Mutex::new(Vec::with_capacity(count as usize));
    let first_error: Mutex<Option<SimError>> = Mutex::new(None);
    let (next, results, first_error) = (&next, &results, &first_error);
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1) {
            let worker = || -> Result<(), SimError> {
                let mut state = new_worker()?;
                loop {
                    let index = next.fetch_add(1, Ordering::Relaxed);
                    if index >= count {
                        return Ok(());
                    }
                    let setup = sweep_setup(index, config)
                        .ok_or_else(|| SimError::Input(format!("no assignment #{index}")))?;
                    let result = play(&mut state, index, &setup)?;
                    if let Ok(mut all) = results.lock() {
                        all.push((index, result));
                    }
                    on_game();
                }
            };
            let spawned = std::thread::Builder::new()
                .stack_size(ENGINE_THREAD_STACK)
                .spawn_scoped(scope, move || {
                    if let Err(e) = worker() {
                        // Stop the other workers at their next game.
                        next.store(count, Ordering::Relaxed);
                        if let Ok(mut slot) = first_error.lock() {
                            slot.get_or_insert(e);
                        }
                    }
                });
            if let Err(e) = spawned {
                if let Ok(mut slot) = first_error.lock() {
                    slot.get_or_insert(SimError::Input(format!("cannot start a worker: {e}")));
                }
            }
        }
    });
    if let Some(e) = first_error.lock().ok().and_then(|mut slot| slot.take()) {
        return Err(e);
    }
    let mut all = results
        .lock()
        .map(|mut all| std::mem::take(&mut *all))
        .map_err(|_| SimError::Input("a worker panicked".into()))?;
    all.sort_by_key(|(index, _)| *index);
    Ok(all.into_iter().map(|(_, result)| result).collect())
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0u32), |(s, n), v| (s + v, n + 1));
    if n == 0 {
        0.0
    } else {
        sum / f64::from(n)
    }
}

/// `value:count` pairs of a small integer distribution.
fn distribution(values: impl Iterator<Item = i64>) -> String {
    let mut counts = std::collections::BTreeMap::new();
    for v in values {
        *counts.entry(v).or_insert(0u32) += 1;
    }
    counts
        .iter()
        .map(|(v, n)| format!("{v}:{n}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Points grouped in bins of 10.
fn points_histogram(games: &[GameSummary]) -> String {
    let mut counts = std::collections::BTreeMap::new();
    for g in games {
        *counts.entry(g.points.div_euclid(10) * 10).or_insert(0u32) += 1;
    }
    let widest = counts.values().copied().max().unwrap_or(1).max(1);
    let mut out = String::new();
    for (low, n) in counts {
        let bar = "#".repeat(((n as usize) * 50).div_ceil(widest as usize));
        let _ = writeln!(out, "  {:>4}-{:<4} {:>5} {bar}", low, low + 9, n);
    }
    out
}

/// The summary text of a sweep.
pub fn summarize(config: SweepConfig, games: &[GameSummary], seconds: f64) -> String {
    let SweepConfig {
        strategy,
        clock_off,
        fault_rate,
    } = config;
    let mut out = String::new();
    let n = games.len();
    let count = |f: &dyn Fn(&GameSummary) -> bool| games.iter().filter(|g| f(g)).count();
    let min = games.iter().map(|g| g.points).min().unwrap_or(0);
    let max = games.iter().map(|g| g.points).max().unwrap_or(0);
    let _ = writeln!(
        out,
        "sweep: strategy {}, {} assignments, clock {}, faults {fault_rate} %",
        strategy.name(),
        n,
        if clock_off { "off" } else { "900 s" }
    );
    let worst = games
        .iter()
        .min_by_key(|g| (g.points, g.index))
        .map_or(String::new(), |g| format!(" (assignment #{})", g.index));
    let _ = writeln!(
        out,
        "points: mean {:.2}, min {min}{worst}, max {max}",
        mean(games.iter().map(|g| g.points as f64))
    );
    out.push_str(&points_histogram(games));
    let _ = writeln!(
        out,
        "products per game: S1 {:.2}, S2 {:.2}, P {:.3}",
        mean(games.iter().map(|g| g.s1 as f64)),
        mean(games.iter().map(|g| g.s2 as f64)),
        mean(games.iter().map(|g| g.p as f64))
    );
    let _ = writeln!(
        out,
        "P per game: {}",
        distribution(games.iter().map(|g| g.p))
    );
    let _ = writeln!(
        out,
        "games with no production: {} (no P: {})",
        count(&|g| g.s1 + g.s2 + g.p == 0),
        count(&|g| g.p == 0)
    );
    let _ = writeln!(
        out,
        "deadlocks: {}",
        count(&|g| g.end == EndReason::Deadlock)
    );
    let _ = writeln!(
        out,
        "stalls: {}, panics: {}",
        count(&|g| g.end == EndReason::Stalled && !g.panicked),
        count(&|g| g.panicked)
    );
    if fault_rate > 0 {
        let _ = writeln!(
            out,
            "pucks lost per game {:.2}, discarded {:.2}",
            mean(games.iter().map(|g| g.lost as f64)),
            mean(games.iter().map(|g| g.discarded as f64))
        );
    }
    let _ = writeln!(
        out,
        "junk recycled per game {:.2}",
        mean(games.iter().map(|g| g.recycled as f64))
    );
    let ends = distribution(games.iter().map(|g| match g.end {
        EndReason::Time => 0,
        EndReason::Done => 1,
        EndReason::Deadlock => 2,
        EndReason::Stalled => 3,
    }));
    let _ = writeln!(out, "ends (0 time, 1 done, 2 deadlock, 3 stalled): {ends}");
    let _ = writeln!(
        out,
        "decisions per game: mean {:.1}, min {}, max {}",
        mean(games.iter().map(|g| g.decisions as f64)),
        games.iter().map(|g| g.decisions).min().unwrap_or(0),
        games.iter().map(|g| g.decisions).max().unwrap_or(0)
    );
    let _ = writeln!(
        out,
        "mean game end {:.1} s, mean travel {:.1} m",
        mean(games.iter().map(|g| g.end_time)),
        mean(games.iter().map(|g| g.travelled))
    );
    if clock_off {
        let _ = writeln!(
            out,
            "P made per 20 S0 (clock off, junk recycled): mean {:.3}, games with 5 P or more: {} of {n}",
            mean(games.iter().map(|g| g.p as f64)),
            count(&|g| g.p >= 5)
        );
    }
    let _ = writeln!(
        out,
        "speed: {:.1} games/s ({:.1} s wall)",
        if seconds > 0.0 {
            n as f64 / seconds
        } else {
            0.0
        },
        seconds
    );
    out
}

/// One row of the fault table (markdown).
pub fn table_row(config: SweepConfig, games: &[GameSummary], seconds: f64) -> String {
    let count = |f: &dyn Fn(&GameSummary) -> bool| games.iter().filter(|g| f(g)).count();
    format!(
        "| {} | {} | {} | {:.2} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {:.0} |",
        config.strategy.name(),
        config.fault_rate,
        games.len(),
        mean(games.iter().map(|g| g.points as f64)),
        games.iter().map(|g| g.points).min().unwrap_or(0),
        mean(games.iter().map(|g| g.p as f64)),
        mean(games.iter().map(|g| g.s2 as f64)),
        mean(games.iter().map(|g| g.lost as f64)),
        mean(games.iter().map(|g| g.discarded as f64)),
        count(&|g| g.end == EndReason::Deadlock),
        count(&|g| g.end == EndReason::Stalled && !g.panicked),
        count(&|g| g.panicked),
        seconds
    )
}

/// Header of [`table_row`].
pub const TABLE_HEADER: &str = "| strategy | faults % | games | mean points | min points | P | S2 | lost | discarded | deadlocks | stalls | panics | wall s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|";

/// Games that must not happen: deadlocked, stalled or panicked.
fn bad_games(games: &[GameSummary]) -> Vec<String> {
    games
        .iter()
        .filter(|g| g.end.is_deadlock() || g.panicked)
        .take(10)
        .map(|g| format!("#{}", g.index))
        .collect()
}

/// Entry point of `robotino-agent sweep`.
pub fn main(args: Args) -> ExitCode {
    let count = args.limit.unwrap_or(ASSIGNMENT_COUNT).min(ASSIGNMENT_COUNT);
    let threads = args.threads.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    let configs: Vec<SweepConfig> = if args.fault_table {
        TABLE_STRATEGIES
            .iter()
            .flat_map(|&strategy| {
                TABLE_FAULT_RATES
                    .iter()
                    .map(move |&fault_rate| SweepConfig {
                        strategy,
                        clock_off: args.clock_off,
                        fault_rate,
                    })
            })
            .collect()
    } else {
        vec![SweepConfig {
            strategy: args.strategy,
            clock_off: args.clock_off,
            fault_rate: args.fault_rate,
        }]
    };
    if args.robots != 1 {
        return team_main(&args, count, threads);
    }
    if args.fault_table {
        println!("{TABLE_HEADER}");
    }
    let mut failed = false;
    for config in configs {
        let bar = progress_bar(args.quiet, count);
        let started = Instant::now();
        let result = play_all(config, count, threads, &|| bar.inc(1));
        bar.finish_and_clear();
        let games = match result {
            Ok(games) => games,
            Err(e) => {
                eprintln!("robotino-agent sweep: {e}");
                return ExitCode::FAILURE;
            }
        };
        let seconds = started.elapsed().as_secs_f64();
        if args.fault_table {
            println!("{}", table_row(config, &games, seconds));
        } else {
            print!("{}", summarize(config, &games, seconds));
        }
        let bad = bad_games(&games);
        if !bad.is_empty() {
            eprintln!(
                "robotino-agent sweep: {} faults {} %: deadlocked, stalled or panicked assignments (first 10): {}",
                config.strategy.name(),
                config.fault_rate,
                bad.join(" ")
            );
            failed = true;
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// The bar of a sweep of `count` games (hidden with `--quiet`).
fn progress_bar(quiet: bool, count: u32) -> ProgressBar {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(u64::from(count))
    };
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} games  {per_sec}  eta {eta}")
    {
        bar.set_style(style);
    }
    bar
}

/// `sweep --robots N`.
fn team_main(args: &Args, count: u32, threads: usize) -> ExitCode {
    let config = SweepConfig {
        strategy: args.strategy,
        clock_off: args.clock_off,
        fault_rate: 0,
    };
    let bar = progress_bar(args.quiet, count);
    let started = Instant::now();
    let result = super::team::sweep_team(config, args.robots, count, threads, &|| bar.inc(1));
    bar.finish_and_clear();
    match result {
        Ok(games) => {
            print!(
                "{}",
                super::team::summarize_team(args.robots, &games, started.elapsed().as_secs_f64())
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("robotino-agent sweep: {e}");
            ExitCode::FAILURE
        }
    }
}
