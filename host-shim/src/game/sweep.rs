//! `robotino-agent game-sweep`: process-level games over a range of seeds, as many at once
//! as the machine has cores (each game is a sim and its agents in lockstep, about one core's
//! work), with a progress bar, then one row per seed and a summary: mean/min/max points,
//! collisions, double claims and stalls (definitions in [`super::record`]).

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use indicatif::{ProgressBar, ProgressStyle};
use rules::Strategy;

use super::record::GameRecord;

#[derive(clap::Args)]
pub struct Args {
    /// First seed.
    #[arg(long, default_value_t = 0)]
    pub from: u64,
    /// Number of seeds (from, from+1, ...).
    #[arg(long, default_value_t = 100)]
    pub count: u64,
    /// Robots on the field (1..=3).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub robots: u8,
    /// Production strategy of the agents' rules: naive, paper or travel.
    #[arg(long, default_value = "paper", value_parser = crate::sim::parse_strategy)]
    pub strategy: Strategy,
    /// Game length in simulated seconds.
    #[arg(long, default_value_t = 900.0)]
    pub game_seconds: f32,
    /// Games at once (default: the machine's cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Directory holding `robotino-sim` (default: next to this program).
    #[arg(long)]
    pub bin_dir: Option<PathBuf>,
    /// No progress bar (for logs and tests).
    #[arg(long)]
    pub quiet: bool,
    /// Join the robots only over Zenoh (see `game --zenoh-agent`).
    #[arg(long)]
    pub zenoh_agent: Option<PathBuf>,
    /// Team link faults (see `game --link-loss-percent`, `--link-delay-s`).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub link_loss_percent: u32,
    #[arg(long, default_value_t = 0.0)]
    pub link_delay_s: f64,
    /// Kill the last robot's agent in every game, at a game time drawn from the seed
    /// (60 s to 60 s before the end; see `game --kill-at-s`).
    #[arg(long)]
    pub kill_one: bool,
}

/// One seed's figures.
#[derive(Debug, Clone)]
pub struct Row {
    pub seed: u64,
    pub score: i64,
    pub collisions: u32,
    pub double_claims: usize,
    pub stalls: usize,
    pub bumps: usize,
    pub failed_skills: usize,
    pub end: String,
}

impl Row {
    fn of(g: &GameRecord) -> Self {
        Row {
            seed: g.seed,
            score: g.score,
            collisions: g.robot_contacts,
            double_claims: g.double_claims().len(),
            stalls: g.stalls().len(),
            bumps: g.bumps.len(),
            failed_skills: g
                .skills
                .iter()
                .filter(|s| s.ending == super::record::Ending::Failed)
                .count(),
            end: if g.done.is_empty() {
                format!("{:.0}s", g.game_time_s)
            } else {
                format!("{:.0}s, DONE at {:.0}s", g.game_time_s, g.done[0].0)
            },
        }
    }
}

pub fn main(args: Args) -> ExitCode {
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let seeds: Vec<u64> = (args.from..args.from + args.count).collect();
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(seeds.len() as u64)
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} games, {elapsed} ({eta} left) {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Result<Row, String>>> = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(seeds.len()) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(&seed) = seeds.get(i) else { break };
                let game = super::Args {
                    seed,
                    strategy: args.strategy,
                    game_seconds: args.game_seconds,
                    robots: args.robots,
                    bin_dir: args.bin_dir.clone(),
                    verbose: false,
                    timeout_s: 600,
                    svg: None,
                    zenoh_agent: args.zenoh_agent.clone(),
                    link_loss_percent: args.link_loss_percent,
                    link_delay_s: args.link_delay_s,
                    kill_at_s: args
                        .kill_one
                        .then(|| super::kill_time_for_seed(seed, f64::from(args.game_seconds))),
                };
                let row = super::play(&game, false)
                    .map(|g| Row::of(&g))
                    .map_err(|e| format!("seed {seed}: {e}"));
                if let Ok(r) = &row {
                    bar.set_message(format!("seed {} {} points", r.seed, r.score));
                }
                if let Ok(mut v) = results.lock() {
                    v.push(row);
                }
                bar.inc(1);
            });
        }
    });
    bar.finish_and_clear();
    let results = results.into_inner().unwrap_or_default();
    let mut rows: Vec<Row> = Vec::new();
    let mut failures = Vec::new();
    for r in results {
        match r {
            Ok(row) => rows.push(row),
            Err(e) => failures.push(e),
        }
    }
    rows.sort_by_key(|r| r.seed);
    print!("{}", table(&args, &rows));
    for f in &failures {
        eprintln!("robotino-agent game-sweep: {f}");
    }
    if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// One row per seed, then the summary.
pub fn table(args: &Args, rows: &[Row]) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "robotino-agent game-sweep: seeds {}..{}, {} robot(s), strategy {}, clock {} s",
        args.from,
        args.from + args.count.saturating_sub(1),
        args.robots,
        args.strategy.name(),
        args.game_seconds
    );
    let _ = writeln!(
        out,
        "| seed | points | collisions | double claims | stalls | bumps | failed skills | end |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    for r in rows {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            r.seed,
            r.score,
            r.collisions,
            r.double_claims,
            r.stalls,
            r.bumps,
            r.failed_skills,
            r.end
        );
    }
    let n = rows.len().max(1) as f64;
    let mean = rows.iter().map(|r| r.score as f64).sum::<f64>() / n;
    let min = rows.iter().map(|r| r.score).min().unwrap_or(0);
    let max = rows.iter().map(|r| r.score).max().unwrap_or(0);
    let worst: Vec<String> = {
        let mut v: Vec<&Row> = rows.iter().collect();
        v.sort_by_key(|r| (r.score, r.seed));
        v.iter()
            .take(5)
            .map(|r| format!("{}:{}", r.seed, r.score))
            .collect()
    };
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "| games | mean points | min | max | collisions | double claims | stalls | bumps | failed skills |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    let _ = writeln!(
        out,
        "| {} | {mean:.1} | {min} | {max} | {} | {} | {} | {} | {} |",
        rows.len(),
        rows.iter().map(|r| r.collisions).sum::<u32>(),
        rows.iter().map(|r| r.double_claims).sum::<usize>(),
        rows.iter().map(|r| r.stalls).sum::<usize>(),
        rows.iter().map(|r| r.bumps).sum::<usize>(),
        rows.iter().map(|r| r.failed_skills).sum::<usize>()
    );
    let _ = writeln!(out, "lowest (seed:points): {}", worst.join(" "));
    out
}
