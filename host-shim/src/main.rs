//! `robotino-agent`: the host program around the fixed-memory engine.
//!
//! Each subcommand lives in its own module; this file only parses the command line.

mod bench;
mod clips_cli;
mod game;
mod sim;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "robotino-agent",
    version,
    about = "CLIPS-compatible deliberative agent for the Robotino"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// A CLIPS-like command line (`-f FILE`, `-f2 FILE`, `-l FILE`, or interactive).
    Clips(clips_cli::Args),
    /// One robot's agent loop over iceoryx2 (sensors, skills, safety, motor command).
    Run(host_shim::agent_loop::Args),
    /// A whole game across processes: robotino-sim and one `run` per robot, in lockstep.
    Game(game::Args),
    /// Process-level games over many seeds in parallel: a table of points, collisions,
    /// double claims and stalls.
    GameSweep(game::sweep::Args),
    /// Benchmarks against CLIPS 6.30 and 6.4: prints ratios, regenerates BENCHMARKS.md.
    Bench(bench::Args),
    /// Plays one simulated LLSF game and prints a readable report.
    Sim(sim::Args),
    /// Plays every distinct machine assignment and summarises the results.
    Sweep(sim::sweep::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Clips(args) => clips_cli::main(args),
        Command::Run(args) => host_shim::agent_loop::main(args),
        Command::Game(args) => game::main(args),
        Command::GameSweep(args) => game::sweep::main(args),
        Command::Bench(args) => bench::main(args),
        Command::Sim(args) => sim::main(args),
        Command::Sweep(args) => sim::sweep::main(args),
    }
}
