//! `robotino-agent game`: one whole LLSF game across processes. Starts `robotino-sim` (the
//! drivers, the field and the CLIPS referee) and one `robotino-agent run` per robot under a
//! fresh service prefix, in lockstep (the sim advances a cycle per agent command, so a
//! 15-minute game takes seconds), waits for the referee's end of game, stops the agents
//! and prints the readable report ([`report`]), the score and the agents' loop statistics;
//! `--svg FILE` draws the timeline ([`svg`]). `game-sweep` ([`sweep`]) plays many seeds.

pub mod record;
pub mod report;
pub mod svg;
pub mod sweep;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitCode, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use rules::Strategy;

use record::GameRecord;

#[derive(clap::Args, Clone)]
pub struct Args {
    /// Seed of the game setup (hidden machine types, active gate).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Production strategy of the agents' rules: naive, paper or travel.
    #[arg(long, default_value = "paper", value_parser = crate::sim::parse_strategy)]
    pub strategy: Strategy,
    /// Game length in simulated seconds.
    #[arg(long, default_value_t = 900.0)]
    pub game_seconds: f32,
    /// Robots on the field (1..=3, as an LLSF team), one agent process each.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub robots: u8,
    /// Directory holding `robotino-sim` (default: next to this program).
    #[arg(long)]
    pub bin_dir: Option<PathBuf>,
    /// Echo every line the processes print.
    #[arg(long)]
    pub verbose: bool,
    /// Give up after this many wall-clock seconds.
    #[arg(long, default_value_t = 600)]
    pub timeout_s: u64,
    /// Also draw the game's timeline as SVG into this file.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Join the robots only over Zenoh: run this program (`robotino-agent-zenoh`, built
    /// in `team-link/`) as each robot's agent, peers on 127.0.0.1 TCP endpoints.
    #[arg(long)]
    pub zenoh_agent: Option<PathBuf>,
    /// Percent of the team's messages the link loses (our proxy, drawn from the seed).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub link_loss_percent: u32,
    /// Longest delay of a team message in game time (seconds).
    #[arg(long, default_value_t = 0.0)]
    pub link_delay_s: f64,
    /// Kill the last robot's agent process at this game time: it ends at that cycle as a
    /// crash would (a team plays on without it; its claims run out).
    #[arg(long)]
    pub kill_at_s: Option<f64>,
}

/// A game time for `game-sweep --kill-one` drawn from the seed: from 60 s to 60 s before
/// the end (60..840 s in a 15-minute game; the middle of a game shorter than 2 minutes).
pub fn kill_time_for_seed(seed: u64, game_seconds: f64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    let span = (game_seconds.floor() as i64 - 119).max(0) as u64;
    if span == 0 {
        return (game_seconds / 2.0).floor();
    }
    60.0 + (z % span) as f64
}

pub fn main(args: Args) -> ExitCode {
    match play(&args, true) {
        Ok(record) => {
            print!("{}", report::render(&record, args.strategy.name()));
            if let Some(path) = &args.svg {
                if let Err(e) = std::fs::write(path, svg::render(&record)) {
                    eprintln!("robotino-agent game: cannot write {}: {e}", path.display());
                    return ExitCode::FAILURE;
                }
                println!("robotino-agent game: timeline in {}", path.display());
            }
            println!("robotino-agent game: score={}", record.score);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("robotino-agent game: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A child process whose stdout lines arrive on a channel.
struct Proc {
    name: String,
    child: Child,
    lines: mpsc::Receiver<String>,
    seen: Vec<String>,
}

impl Proc {
    fn start(name: &str, program: &Path, args: &[String]) -> Result<Proc, String> {
        let mut child = Command::new(program)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(|e| format!("cannot start {}: {e}", program.display()))?;
        let (tx, lines) = mpsc::channel();
        if let Some(out) = child.stdout.take() {
            std::thread::spawn(move || {
                for line in BufReader::new(out).lines().map_while(Result::ok) {
                    if tx.send(line).is_err() {
                        break;
                    }
                }
            });
        }
        Ok(Proc {
            name: name.to_string(),
            child,
            lines,
            seen: Vec::new(),
        })
    }

    /// Takes the lines printed so far, echoing them when asked.
    fn collect(&mut self, verbose: bool) {
        while let Ok(line) = self.lines.try_recv() {
            if verbose {
                println!("[{}] {line}", self.name);
            }
            self.seen.push(line);
        }
    }

    fn line_with(&self, needle: &str) -> Option<&String> {
        self.seen.iter().find(|l| l.contains(needle))
    }

    /// SIGTERM: the process ends its loop and prints its statistics.
    fn terminate(&self) {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
    }

    /// Waits for the exit and the last lines (the reader ends at end of file).
    fn finish(&mut self, timeout: Duration, verbose: bool) -> Option<std::process::ExitStatus> {
        let deadline = Instant::now() + timeout;
        while Instant::now() < deadline {
            if let Ok(Some(status)) = self.child.try_wait() {
                // Drain what is still in the pipe.
                while let Ok(line) = self.lines.recv_timeout(Duration::from_millis(200)) {
                    if verbose {
                        println!("[{}] {line}", self.name);
                    }
                    self.seen.push(line);
                }
                return Some(status);
            }
            self.collect(verbose);
            std::thread::sleep(Duration::from_millis(5));
        }
        None
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Removes a game's iceoryx2 directory when the game is over, however it ended.
struct RootGuard(String);

impl Drop for RootGuard {
    fn drop(&mut self) {
        host_shim::shim::transport::remove_root(&self.0);
    }
}

/// Plays one game; `chatty` prints the processes' summary lines as they come.
pub fn play(args: &Args, chatty: bool) -> Result<GameRecord, String> {
    let me = std::env::current_exe().map_err(|e| format!("where am I: {e}"))?;
    let dir = match &args.bin_dir {
        Some(d) => d.clone(),
        None => me
            .parent()
            .map(Path::to_path_buf)
            .ok_or("this program has no directory")?,
    };
    let sim_path = dir.join("robotino-sim");
    let robots = args.robots;
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    let prefix = format!("game/{}-{nanos}", std::process::id());
    // Declared before the processes, so dropped after they are killed and reaped.
    let _root = RootGuard(prefix.clone());
    let s = |x: &str| x.to_string();
    let mut sim = Proc::start(
        "sim",
        &sim_path,
        &[
            s("--prefix"),
            prefix.clone(),
            s("--lockstep"),
            s("--robots"),
            robots.to_string(),
            s("--seed"),
            args.seed.to_string(),
            s("--game-seconds"),
            args.game_seconds.to_string(),
        ],
    )?;
    // Zenoh ports for this game: from the process and the clock, so parallel games of a
    // sweep do not share them.
    let port_base = 20_000 + (std::process::id().wrapping_mul(7919) ^ (nanos / 1000)) % 40_000;
    let endpoint = |r: u8| format!("tcp/127.0.0.1:{}", port_base + u32::from(r));
    let mut agents = (1..=robots)
        .map(|r| {
            let (program, mut argv) = match &args.zenoh_agent {
                Some(z) => {
                    let mut v = vec![s("--listen"), endpoint(r)];
                    for lower in 1..r {
                        v.extend([s("--connect"), endpoint(lower)]);
                    }
                    v.extend([s("--zenoh-prefix"), prefix.replace('/', "_")]);
                    (z.as_path(), v)
                }
                None => (me.as_path(), vec![s("run")]),
            };
            argv.extend([
                s("--prefix"),
                prefix.clone(),
                s("--lockstep"),
                s("--robot"),
                r.to_string(),
                s("--strategy"),
                s(args.strategy.name()),
                s("--team-size"),
                robots.to_string(),
                s("--link-loss-percent"),
                args.link_loss_percent.to_string(),
                s("--link-delay-s"),
                args.link_delay_s.to_string(),
                s("--link-seed"),
                args.seed.to_string(),
            ]);
            // The victim dies by itself at the kill's cycle, so the game is the same
            // however loaded the machine is.
            if let (Some(t), true) = (args.kill_at_s, r == robots) {
                let at = (t * record::CYCLE_HZ).ceil() as u64;
                argv.extend([s("--exit-at-cycle"), at.to_string()]);
            }
            Proc::start(&format!("agent{r}"), program, &argv)
        })
        .collect::<Result<Vec<_>, _>>()?;
    if chatty {
        println!(
            "robotino-agent game: prefix={prefix} seed={} strategy={} robots={robots} game_seconds={}",
            args.seed,
            args.strategy.name(),
            args.game_seconds
        );
    }
    let started = Instant::now();
    let deadline = started + Duration::from_secs(args.timeout_s);
    let status = loop {
        if let Some(status) = sim.finish(Duration::from_millis(20), args.verbose) {
            break status;
        }
        if Instant::now() >= deadline {
            return Err(format!("no end of game within {} s", args.timeout_s));
        }
    };
    for a in &agents {
        a.terminate();
    }
    for a in &mut agents {
        a.finish(Duration::from_secs(30), args.verbose);
    }
    if !status.success() {
        return Err(format!("robotino-sim failed ({status})"));
    }
    let done = sim
        .line_with("robotino-sim: done")
        .ok_or("robotino-sim ended without its `done` line")?
        .clone();
    if chatty {
        println!("{done}");
        for a in &agents {
            if let Some(killed) = a.line_with(" killed robot ") {
                println!("{killed}");
            }
            let decisions = a.seen.iter().filter(|l| l.contains(" start ")).count();
            println!("robotino-agent game: {} skills={decisions}", a.name);
            if let Some(stats) = a.line_with("robotino-agent run: done") {
                println!("{stats}");
            }
        }
        println!(
            "robotino-agent game: wall_ms={}",
            started.elapsed().as_millis()
        );
    }
    let agent_lines: Vec<Vec<String>> = agents.iter().map(|a| a.seen.clone()).collect();
    Ok(GameRecord::parse(
        args.seed,
        f64::from(args.game_seconds),
        &sim.seen,
        &agent_lines,
    ))
}

#[cfg(test)]
mod tests {
    use super::kill_time_for_seed;

    #[test]
    fn kill_times_fall_inside_the_game() {
        for seed in 0..200 {
            let t = kill_time_for_seed(seed, 900.0);
            assert!((60.0..=840.0).contains(&t), "seed {seed}: {t}");
            let short = kill_time_for_seed(seed, 240.0);
            assert!((60.0..=180.0).contains(&short), "seed {seed}: {short}");
            assert_eq!(kill_time_for_seed(seed, 90.0), 45.0);
        }
        // Drawn from the seed: not all alike.
        assert_ne!(kill_time_for_seed(0, 900.0), kill_time_for_seed(1, 900.0));
    }
}
