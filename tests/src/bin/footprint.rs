//! Footprint gate: builds the agent image for i586 (profile `image`), measures code, RAM
//! (sections + stack high-water mark from a run under `qemu-i386 -cpu pentium`), the engine
//! arena's share and heap, prints a table (or JSON) and fails when a budget is exceeded.
//!
//! Exit status: 0 within budget, 1 over budget, 2 could not measure.

use clap::Parser;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use tests::budget::{Budgets, Violation};
use tests::footprint::{self, Footprint};
use tests::{image, report};

#[derive(Parser)]
#[command(about = "Measure the agent image's memory footprint and check it against the budgets")]
struct Args {
    /// Budget file (RAM, code, heap limits with reasons).
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/footprint-budget.toml"))]
    budget: PathBuf,
    /// Features of `agent-image` to build with (the gate's own test uses `oversize`).
    #[arg(long, value_delimiter = ',')]
    features: Vec<String>,
    /// Build the image in this target dir instead of cargo's default.
    #[arg(long)]
    target_dir: Option<PathBuf>,
    /// Print JSON on stdout instead of the table.
    #[arg(long)]
    json: bool,
    /// Also write the JSON to this file.
    #[arg(long)]
    json_out: Option<PathBuf>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match measure_and_check(&args) {
        Ok(violations) if violations.is_empty() => {
            eprintln!("footprint gate: ok, every budget holds");
            ExitCode::SUCCESS
        }
        Ok(violations) => {
            eprintln!("footprint gate: FAILED ({})", args.budget.display());
            for violation in &violations {
                eprintln!("  {violation}");
            }
            ExitCode::from(1)
        }
        Err(error) => {
            eprintln!("footprint gate: could not measure the image: {error}");
            ExitCode::from(2)
        }
    }
}

fn measure_and_check(args: &Args) -> Result<Vec<Violation>, String> {
    let budget_text = std::fs::read_to_string(&args.budget)
        .map_err(|e| format!("reading budget file {}: {e}", args.budget.display()))?;
    let budgets = Budgets::parse(&budget_text)
        .map_err(|e| format!("budget file {}: {e}", args.budget.display()))?;

    let options = image::BuildOptions {
        features: args.features.clone(),
        target_dir: args.target_dir.clone(),
    };
    let executable = image::build(&options).map_err(|e| e.to_string())?;
    let footprint = measure(&executable)?;
    let violations = footprint.violations(&budgets);

    let json = report::json(&executable, &footprint, &budgets, &violations);
    let json_text = serde_json::to_string_pretty(&json)
        .map_err(|e| format!("formatting the JSON report: {e}"))?;
    if let Some(path) = &args.json_out {
        std::fs::write(path, format!("{json_text}\n"))
            .map_err(|e| format!("writing {}: {e}", path.display()))?;
    }
    if args.json {
        println!("{json_text}");
    } else {
        print!(
            "{}",
            report::table(&executable, &footprint, &budgets, &violations)
        );
    }
    Ok(violations)
}

/// Section sizes and symbols from the file, stack from one run under qemu.
fn measure(executable: &Path) -> Result<Footprint, String> {
    let data =
        std::fs::read(executable).map_err(|e| format!("reading {}: {e}", executable.display()))?;
    let static_part =
        footprint::read_elf(&data).map_err(|e| format!("{}: {e}", executable.display()))?;
    let run = image::run(executable).map_err(|e| e.to_string())?;
    let stack_max_bytes = footprint::parse_stack_line(&run.stdout)
        .map_err(|e| format!("{}: {e}", executable.display()))?;
    Ok(Footprint {
        image: static_part,
        stack_max_bytes,
    })
}
