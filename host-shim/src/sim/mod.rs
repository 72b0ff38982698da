//! `robotino-agent sim` and `sweep`: whole LLSF games played in-process by our
//! engine. The game (agent, referee, instant simulation, decision log) is the
//! CLIPS text of the `rules` crate; Rust picks the setup, runs the engine and
//! reports. Modules: [`game`] (engine + driver), [`record`] (result facts),
//! [`report`] (readable report), [`replay`] (game logs), [`sweep`].

pub mod game;
pub mod record;
pub mod replay;
pub mod report;
pub mod snapshot;
pub mod sweep;
pub mod team;

use std::process::ExitCode;

use rules::setup::{assignment_by_index, index_of_assignment, GameSetup, ASSIGNMENT_COUNT};
use rules::Strategy;

use game::{with_engine_stack, Player, SimError};

/// Options of `robotino-agent sim`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Seed that draws the hidden assignment and the active gate.
    #[arg(long, conflicts_with_all = ["assignment", "index"])]
    pub seed: Option<u64>,
    /// Explicit machine types M1..M10, e.g. T1,T1,T1,T1,T2,T2,T2,T3,T3,T3 (gate D1).
    #[arg(long, conflicts_with = "index")]
    pub assignment: Option<String>,
    /// The INDEX-th of the 4200 distinct assignments (as `sweep` numbers them).
    #[arg(long)]
    pub index: Option<u32>,
    /// Production strategy: naive, paper or travel.
    #[arg(long, default_value = "paper", value_parser = parse_strategy)]
    pub strategy: Strategy,
    /// Play without the 15-minute clock.
    #[arg(long)]
    pub clock_off: bool,
    /// Draw processing times from the seed instead of the midpoints.
    #[arg(long)]
    pub seeded_times: bool,
    /// Inject N faults among the first 40 decisions (drawn from the seed).
    #[arg(long, default_value_t = 0)]
    pub faults: usize,
    /// Disturb each decision with probability PCT % (lost puck, failed grab,
    /// failed goto, wrong light), drawn from the seed (or the index).
    #[arg(long, value_name = "PCT", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub fault_rate: u32,
    /// Print the engine's `(watch rules)` trace before the report.
    #[arg(long)]
    pub trace: bool,
    /// Write a game log (setup and decisions) to FILE.
    #[arg(long, value_name = "FILE")]
    pub log: Option<std::path::PathBuf>,
    /// Save the whole fact base (agent beliefs, referee, log) to FILE after
    /// every decision; the file is replaced atomically.
    #[arg(long, value_name = "FILE")]
    pub snapshot: Option<std::path::PathBuf>,
    /// Go on with the game saved in FILE by --snapshot (e.g. after the process
    /// was killed); keeps snapshotting into FILE unless --snapshot names another.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["seed", "assignment", "index", "replay", "strategy", "fault_rate", "faults"])]
    pub resume: Option<std::path::PathBuf>,
    /// Pause N ms of wall-clock time after each snapshot (lets a test kill
    /// the process in the middle of a game).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub pace_ms: u64,
    /// Robots in the team (1: the single agent; 2..6: one engine per robot with the
    /// team rules, rules/team.clp and rules/team-agent.clp).
    #[arg(long, default_value_t = 1)]
    pub robots: u8,
    /// Play the game in FILE again and check that the decisions are the same.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["seed", "assignment", "index", "log"])]
    pub replay: Option<std::path::PathBuf>,
}

/// clap value parser for `--strategy`.
pub use host_shim::shim::agent::parse_strategy;

/// The setup the options ask for and a title naming it.
fn setup_from_args(args: &Args) -> Result<(GameSetup, String), SimError> {
    let seed = args.seed.unwrap_or(1);
    let (mut setup, title) = if let Some(text) = &args.assignment {
        let assignment =
            replay::parse_assignment(text.split(',').map(str::trim)).map_err(SimError::Input)?;
        (GameSetup::new(assignment), format!("assignment {text}"))
    } else if let Some(index) = args.index {
        let assignment = assignment_by_index(index).ok_or_else(|| {
            SimError::Input(format!("--index {index}: must be below {ASSIGNMENT_COUNT}"))
        })?;
        (GameSetup::new(assignment), format!("assignment #{index}"))
    } else {
        (GameSetup::for_seed(seed), format!("seed {seed}"))
    };
    if args.seeded_times {
        setup = setup.with_seeded_times(seed);
    }
    if args.faults > 0 {
        setup = setup.with_seeded_faults(seed, args.faults, 40);
    }
    if args.fault_rate > 0 {
        let key = args.index.map(u64::from).unwrap_or(seed);
        setup = setup.with_fault_rate(args.fault_rate, key);
    }
    if args.clock_off {
        setup.clock_limit_s = None;
    }
    let title = match index_of_assignment(&setup.assignment) {
        Some(i) if args.index.is_none() => format!("{title} (assignment #{i})"),
        _ => title,
    };
    Ok((setup, title))
}

fn sink_for(
    args: &Args,
    path: Option<&std::path::Path>,
) -> Result<Option<snapshot::SnapshotSink>, SimError> {
    path.map(|p| snapshot::SnapshotSink::new(p, std::time::Duration::from_millis(args.pace_ms)))
        .transpose()
}

/// `sim --resume FILE`: the snapshot's game, played to its end.
fn resume(args: &Args, path: &std::path::Path) -> Result<String, SimError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SimError::Input(format!("cannot read {}: {e}", path.display())))?;
    let snap = snapshot::parse(&text)?;
    let mut player = Player::new(snap.strategy)?;
    warn_stub(&player);
    player.set_snapshot(sink_for(
        args,
        Some(args.snapshot.as_deref().unwrap_or(path)),
    )?);
    let (record, beliefs) = player.resume(&snap, args.trace)?;
    // The resumed engine must know exactly what the snapshot says.
    let saved = snapshot::machine_beliefs(&snap.facts);
    if beliefs != saved {
        return Err(SimError::Facts(format!(
            "resumed beliefs {beliefs:?} differ from the snapshot's {saved:?}"
        )));
    }
    let mut out = String::new();
    if args.trace || !record.output.is_empty() {
        out.push_str(&record.output);
        if !record.output.ends_with('\n') {
            out.push('\n');
        }
    }
    out.push_str(&format!(
        "resumed from {} after decision {}; machine beliefs M1..M10: {}\n",
        path.display(),
        snap.decision,
        beliefs.join(" ")
    ));
    out.push_str(&report::render(
        &record,
        &format!("resumed {}", path.display()),
    ));
    if let Some(log) = &args.log {
        std::fs::write(log, replay::write_log(&record))
            .map_err(|e| SimError::Input(format!("cannot write {}: {e}", log.display())))?;
        out.push_str(&format!("game log written to {}\n", log.display()));
    }
    Ok(out)
}

fn run(args: Args) -> Result<String, SimError> {
    if let Some(path) = &args.resume {
        return resume(&args, path);
    }
    if let Some(path) = &args.replay {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SimError::Input(format!("cannot read {}: {e}", path.display())))?;
        let log = replay::parse_log(&text)?;
        let mut player = Player::new(log.strategy)?;
        warn_stub(&player);
        let record = player.play(&log.setup, args.trace)?;
        let mut out = String::new();
        if args.trace {
            out.push_str(&record.output);
        }
        return match replay::verify(&log, &record) {
            Ok(()) => {
                out.push_str(&format!(
                    "replay {}: OK, the same {} decisions and result\n{}\n",
                    path.display(),
                    record.decisions.len(),
                    record.result_line()
                ));
                Ok(out)
            }
            Err(diff) => Err(SimError::Input(format!(
                "replay {}: MISMATCH, {diff}",
                path.display()
            ))),
        };
    }
    let (setup, title) = setup_from_args(&args)?;
    if args.robots != 1 {
        return team_game(&args, &setup, &title);
    }
    let mut player = Player::new(args.strategy)?;
    warn_stub(&player);
    player.set_snapshot(sink_for(&args, args.snapshot.as_deref())?);
    let record = player.play(&setup, args.trace)?;
    let mut out = String::new();
    if args.trace || !record.output.is_empty() {
        out.push_str(&record.output);
        if !record.output.ends_with('\n') {
            out.push('\n');
        }
    }
    out.push_str(&report::render(&record, &title));
    if let Some(path) = &args.log {
        std::fs::write(path, replay::write_log(&record))
            .map_err(|e| SimError::Input(format!("cannot write {}: {e}", path.display())))?;
        out.push_str(&format!("game log written to {}\n", path.display()));
    }
    Ok(out)
}

/// `sim --robots N`: the team's game, with what the single game offers that a team
/// game does not (yet) refused rather than ignored.
fn team_game(args: &Args, setup: &GameSetup, title: &str) -> Result<String, SimError> {
    let refused = [
        (args.trace, "--trace"),
        (args.log.is_some(), "--log"),
        (args.snapshot.is_some(), "--snapshot"),
        (args.faults > 0, "--faults"),
        (args.fault_rate > 0, "--fault-rate"),
    ];
    if let Some((_, name)) = refused.iter().find(|(on, _)| *on) {
        return Err(SimError::Input(format!(
            "{name} is for one robot; a team game (--robots {}) does not support it",
            args.robots
        )));
    }
    let mut player = team::TeamPlayer::new(args.strategy, args.robots)?;
    let record = player.play(setup, args.seed.unwrap_or(1))?;
    Ok(team::render(&record, title, usize::from(args.robots)))
}

/// Says on stderr when the engine lacked `distance` and the CLIPS stub stands in.
fn warn_stub(player: &Player) {
    if player.distance_stubbed {
        eprintln!("robotino-agent: note: the engine has no `distance` builtin; using rules/clips/stubs.clp");
    }
}

/// Entry point of `robotino-agent sim`.
pub fn main(args: Args) -> ExitCode {
    match with_engine_stack(move || run(args)).and_then(|r| r) {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("robotino-agent sim: {e}");
            ExitCode::FAILURE
        }
    }
}
