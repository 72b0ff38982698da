//! Checks the rule files at build time with the engine's parser: every load order of
//! `src/order.rs` (each strategy's agent, plus driver and simulation files) is loaded
//! into an engine as the hosts load it. A file that does not load fails the build with
//! `rules/FILE.clp:LINE:COL: expected ...`.

// (`check_load`, without host functions, is for the tests)
#[allow(dead_code)]
#[path = "load_check.rs"]
mod load_check;
#[path = "src/order.rs"]
mod order;

use std::path::Path;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=load_check.rs");
    println!("cargo::rerun-if-changed=src/order.rs");
    let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".to_string());
    let dir = Path::new(&dir);
    // (a new file also needs a line in src/order.rs, which re-runs the check)
    for sub in ["", "clips"] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_some_and(|e| e == "clp") {
                println!("cargo::rerun-if-changed={}", path.display());
            }
        }
    }
    for (strategy, agent) in order::AGENTS {
        let game: Vec<&str> = agent
            .iter()
            .chain(order::DRIVER)
            .chain(order::SIM)
            .copied()
            .collect();
        if let Err(message) = check_as(dir, &game, load_check::PpForms::Keep) {
            fail(&format!("{message} (loading the {strategy} game)"));
        }
        let member: Vec<&str> = agent
            .iter()
            .chain(order::BODY)
            .chain(order::TEAM)
            .chain(order::TEAM_AGENT)
            .copied()
            .collect();
        // a robot's engine: loaded without pretty-print forms, as `run` and the team
        // members load it
        if let Err(message) = check_as(dir, &member, load_check::PpForms::Drop) {
            fail(&format!("{message} (loading the {strategy} team member)"));
        }
    }
}

/// Reads the named files and loads them in order, keeping or dropping the
/// pretty-print forms.
fn check_as(dir: &Path, names: &[&str], pp_forms: load_check::PpForms) -> Result<(), String> {
    let mut files = Vec::new();
    for name in names {
        let text = std::fs::read_to_string(dir.join(name))
            .map_err(|e| format!("rules/{name}: cannot read: {e}"))?;
        files.push((format!("rules/{name}"), text));
    }
    load_check::check_load_as(&files, order::HOST_FUNCTIONS, pp_forms)
        .map_err(|bad| bad.to_string())
}

fn fail(message: &str) -> ! {
    println!("cargo::warning={message}");
    eprintln!("error: {message}");
    std::process::exit(1);
}
