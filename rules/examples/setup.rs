//! Writes a game setup as CLIPS text, for the CLIPS drivers in rules/clips.
//!
//! setup SEED [--index] [--clock-off] [--seeded-times] [--faults N] [--fault-rate PCT] [--s0 N]
//!   SEED is a seed, or with --index an assignment index 0..4200.
//! setup --sweep FROM TO [--seeds] [other options]
//!   A batch for one CLIPS process: for every index (with --seeds: seed)
//!   FROM..TO the setup, then (reset) (run) and a RESULT line via
//!   report.clp's report-game.

use rules::setup::{assignment_by_index, GameSetup, ASSIGNMENT_COUNT};
use std::process::ExitCode;

struct Options {
    by_index: bool,
    clock_off: bool,
    seeded_times: bool,
    faults: usize,
    fault_rate: u32,
    s0: Option<u32>,
    positional: Vec<u64>,
    sweep: bool,
    sweep_seeds: bool,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        by_index: false,
        clock_off: false,
        seeded_times: false,
        faults: 0,
        fault_rate: 0,
        s0: None,
        positional: Vec::new(),
        sweep: false,
        sweep_seeds: false,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = |name: &str| -> Result<u64, String> {
            let v = it.next().ok_or(format!("{name} needs a value"))?;
            v.parse().map_err(|e| format!("{name} {v}: {e}"))
        };
        match arg.as_str() {
            "--index" => o.by_index = true,
            "--clock-off" => o.clock_off = true,
            "--seeded-times" => o.seeded_times = true,
            "--sweep" => o.sweep = true,
            "--seeds" => o.sweep_seeds = true,
            "--faults" => o.faults = value("--faults")? as usize,
            "--fault-rate" => o.fault_rate = value("--fault-rate")? as u32,
            "--s0" => o.s0 = Some(value("--s0")? as u32),
            other => o
                .positional
                .push(other.parse().map_err(|e| format!("{other}: {e}"))?),
        }
    }
    Ok(o)
}

fn build(o: &Options, key: u64, by_index: bool) -> Result<GameSetup, String> {
    let mut setup = if by_index {
        let index = u32::try_from(key).map_err(|_| format!("index {key} too large"))?;
        let a = assignment_by_index(index)
            .ok_or(format!("index {index} not below {ASSIGNMENT_COUNT}"))?;
        GameSetup::new(a)
    } else {
        GameSetup::for_seed(key)
    };
    if o.seeded_times {
        setup = setup.with_seeded_times(key);
    }
    if o.faults > 0 {
        setup = setup.with_seeded_faults(key, o.faults, 40);
    }
    if o.fault_rate > 0 {
        setup = setup.with_fault_rate(o.fault_rate, key);
    }
    if o.clock_off {
        setup.clock_limit_s = None;
    }
    if let Some(n) = o.s0 {
        setup.s0_supply = n;
    }
    Ok(setup)
}

fn run(args: &[String]) -> Result<String, String> {
    let o = parse(args)?;
    let mut out = String::new();
    if o.sweep {
        let [from, to] = o.positional[..] else {
            return Err("--sweep FROM TO".into());
        };
        for index in from..to {
            let setup = build(&o, index, !o.sweep_seeds)?;
            setup.write_clips(&mut out).map_err(|e| e.to_string())?;
            out.push_str(&format!(
                "(reset)\n(run)\n(printout t \"GAME {index} \")\n(report-game)\n"
            ));
        }
    } else {
        let [key] = o.positional[..] else {
            return Err(
                "usage: setup SEED [--index] [--clock-off] [--seeded-times] [--faults N] [--fault-rate PCT] [--s0 N]"
                    .into(),
            );
        };
        build(&o, key, o.by_index)?
            .write_clips(&mut out)
            .map_err(|e| e.to_string())?;
    }
    Ok(out)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("setup: {e}");
            ExitCode::FAILURE
        }
    }
}
