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

// `robotino-agent clips ...` alone: the command line of the one subcommand that runs
// CLIPS programs, so that starting one builds no other subcommand's arguments (clap
// builds every subcommand's before it parses: code and text pages an empty program
// touched, and instructions every program ran).
#[derive(Parser)]
#[command(
    name = "robotino-agent clips",
    bin_name = "robotino-agent clips",
    about = "A CLIPS-like command line (`-f FILE`, `-f2 FILE`, `-l FILE`, or interactive)."
)]
struct ClipsCli {
    #[command(flatten)]
    args: clips_cli::Args,
}

fn main() -> ExitCode {
    if std::env::args_os().nth(1).is_some_and(|a| a == "clips") {
        // (the subcommand's name stands where clap expects the program's)
        return clips_cli::main(ClipsCli::parse_from(std::env::args_os().skip(1)).args);
    }
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
