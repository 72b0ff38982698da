//! Programs by others: CLIPS's own example programs, as Debian's `clips-common` package
//! ships them (`/usr/share/doc/clips-common/examples`, installed with `clips`), run in real
//! CLIPS 6.30 and in our CLI and compared line by line (banner aside).
//!
//! The programs are used where the package puts them: each run expands the package's tree
//! (`.gz` files uncompressed) into a scratch directory and never copies it into the repo.
//! What is ours is in `tests/clips/examples/`: one driver per run (`NAME.bat`: the loads,
//! `(reset)`, `(run)`, then the answers an interactive program reads, since in batch mode
//! CLIPS's `(read)` takes the next lines of the batch file) and `MANIFEST`, which gives each
//! driver its directory, its class and whether it must stay identical:
//! - `identical`: the transcripts must be equal; a difference fails the test.
//! - `open`: not yet equal (what is missing is listed in the issue on CLIPS fidelity); the
//!   test reports it, and tells when it becomes identical so that it is marked.
//! - `objects`: uses COOL (classes, instances, generic functions), which we refuse on
//!   purpose; reported only.
//!
//! Either way a run must end: real CLIPS timing out means a broken driver, ours timing out
//! where CLIPS ended is a hang, and both fail the test with the program's name. Drivers
//! marked `heavy` (the large puzzles, `runbench.bat`) run only with
//! `CLIPS_EXAMPLES_HEAVY=1`; the debug build is too slow for them in the test command.
//!
//! `cargo test -p host-shim --test clips_examples -- --nocapture` prints the table.

mod clips_runner;

use clips_runner::{
    clips_command, first_difference, our_engine, run_with_input, without_banner,
    without_position_lines,
};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// Where Debian's `clips-common` puts CLIPS's example programs.
const EXAMPLES: &str = "/usr/share/doc/clips-common/examples";

fn drivers_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/clips/examples");
    dir.canonicalize().unwrap_or(dir)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Identical,
    Open,
    Objects,
}

/// One line of `MANIFEST`: `NAME DIR SECONDS CLASS [heavy]`.
#[derive(Debug)]
struct Entry {
    name: String,
    dir: String,
    timeout: Duration,
    class: Class,
    heavy: bool,
}

fn manifest() -> Result<Vec<Entry>, String> {
    let path = drivers_dir().join("MANIFEST");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut entries = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or_default().trim();
        if line.is_empty() {
            continue;
        }
        let at = || format!("{}:{}", path.display(), number + 1);
        let words: Vec<&str> = line.split_whitespace().collect();
        let [name, dir, seconds, class, rest @ ..] = words.as_slice() else {
            return Err(format!("{}: expected NAME DIR SECONDS CLASS [heavy]", at()));
        };
        let seconds: u64 = seconds
            .parse()
            .map_err(|_| format!("{}: {seconds:?} is not a number of seconds", at()))?;
        let class = match *class {
            "identical" => Class::Identical,
            "open" => Class::Open,
            "objects" => Class::Objects,
            other => return Err(format!("{}: unknown class {other:?}", at())),
        };
        let heavy = match rest {
            [] => false,
            ["heavy"] => true,
            _ => return Err(format!("{}: only `heavy` may follow the class", at())),
        };
        if !drivers_dir().join(format!("{name}.bat")).is_file() {
            return Err(format!("{}: no driver {name}.bat", at()));
        }
        entries.push(Entry {
            name: name.to_string(),
            dir: dir.to_string(),
            timeout: Duration::from_secs(seconds),
            class,
            heavy,
        });
    }
    Ok(entries)
}

/// Copies the package's example tree into `to`, uncompressing `.gz` files.
fn expand(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| {
        format!(
            "{}: {e} (the example programs come with Debian's clips-common, installed with \
             `apt-get install clips`)",
            from.display()
        )
    })?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", from.display()))?;
        let source = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if source.is_dir() {
            expand(&source, &to.join(&name))?;
        } else if let Some(plain) = name.strip_suffix(".gz") {
            let out = Command::new("gzip")
                .arg("-dc")
                .arg(&source)
                .output()
                .map_err(|e| format!("gzip -dc {}: {e}", source.display()))?;
            if !out.status.success() {
                return Err(format!("gzip -dc {} failed", source.display()));
            }
            std::fs::write(to.join(plain), out.stdout)
                .map_err(|e| format!("{}: {e}", to.join(plain).display()))?;
        } else {
            std::fs::copy(&source, to.join(&name))
                .map_err(|e| format!("{}: {e}", source.display()))?;
        }
    }
    Ok(())
}

/// CLIPS's `(watch compilations)` join markers (`+j`, `=j`) after `Defining defrule: NAME`;
/// a transcript without them shows whether a program behaves alike apart from how the
/// network was shared (the issue on CLIPS fidelity lists the marker differences).
fn without_join_markers(lines: &[String]) -> Vec<String> {
    lines
        .iter()
        .map(|line| match line.strip_prefix("Defining defrule: ") {
            Some(rest) => format!(
                "Defining defrule: {}",
                rest.split_whitespace().next().unwrap_or_default()
            ),
            None => line.clone(),
        })
        .collect()
}

enum Outcome {
    Identical,
    /// Equal once join markers are removed.
    MarkersOnly(String),
    Differs(String),
    /// A run that did not end: CLIPS (broken driver) or ours (a hang).
    Hung(String),
}

fn run_one(entry: &Entry, tree: &Path) -> Result<Outcome, String> {
    let driver = drivers_dir().join(format!("{}.bat", entry.name));
    let cwd = tree.join(&entry.dir);
    let clips = run_with_input(
        &clips_command()?,
        &[Path::new("-f"), &driver],
        &cwd,
        None,
        entry.timeout,
    )?;
    if clips.timed_out {
        return Ok(Outcome::Hung(format!(
            "real CLIPS did not end {} within {:?}: the driver must answer every question",
            entry.name, entry.timeout
        )));
    }
    let ours = run_with_input(
        &our_engine(),
        &[Path::new("clips"), Path::new("-f"), &driver],
        &cwd,
        None,
        entry.timeout,
    )?;
    if ours.timed_out {
        return Ok(Outcome::Hung(format!(
            "our CLI did not end {} within {:?}, where CLIPS did",
            entry.name, entry.timeout
        )));
    }
    let expected = without_banner(&clips.stdout);
    let actual = without_position_lines(&without_banner(&ours.stdout));
    let Some(diff) = first_difference("clips", &expected, "ours", &actual) else {
        return Ok(Outcome::Identical);
    };
    Ok(
        match first_difference(
            "clips",
            &without_join_markers(&expected),
            "ours",
            &without_join_markers(&actual),
        ) {
            None => Outcome::MarkersOnly(diff),
            Some(diff) => Outcome::Differs(diff),
        },
    )
}

/// Runs every driver (the heavy ones when asked), prints the table, and fails on a
/// difference in an `identical` program or on any run that does not end.
#[test]
fn clips_example_programs_against_clips() {
    let entries = manifest().unwrap_or_else(|e| panic!("{e}"));
    let heavy = std::env::var_os("CLIPS_EXAMPLES_HEAVY").is_some_and(|v| v == "1");
    let tree = std::env::temp_dir().join(format!("robotino-clips-examples-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tree);
    expand(Path::new(EXAMPLES), &tree).unwrap_or_else(|e| panic!("{e}"));

    let mut failures = Vec::new();
    let mut newly_identical = Vec::new();
    let (mut ran, mut same, mut markers) = (0, 0, 0);
    println!("| program | class | result |");
    println!("|---|---|---|");
    for entry in entries.iter().filter(|e| heavy || !e.heavy) {
        let outcome = run_one(entry, &tree).unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        if entry.class != Class::Objects {
            ran += 1;
        }
        let result = match &outcome {
            Outcome::Identical => "identical",
            Outcome::MarkersOnly(_) => "identical apart from join markers",
            Outcome::Differs(_) => "differs",
            Outcome::Hung(_) => "did not end",
        };
        println!("| {} | {:?} | {result} |", entry.name, entry.class);
        match (&outcome, entry.class) {
            (Outcome::Hung(why), _) => failures.push(why.clone()),
            (Outcome::Identical, Class::Objects) => {}
            (Outcome::Identical, _) => {
                same += 1;
                if entry.class == Class::Open {
                    newly_identical.push(entry.name.clone());
                }
            }
            (Outcome::MarkersOnly(diff) | Outcome::Differs(diff), Class::Identical) => {
                failures.push(format!(
                    "{} is marked identical but differs:\n{diff}",
                    entry.name
                ));
            }
            (Outcome::MarkersOnly(_), Class::Open) => markers += 1,
            _ => {}
        }
    }
    let _ = std::fs::remove_dir_all(&tree);
    println!(
        "{same} of {ran} example runs without objects identical to CLIPS 6.30; {markers} more \
         identical apart from join markers"
    );
    if !newly_identical.is_empty() {
        println!(
            "now identical, mark them `identical` in tests/clips/examples/MANIFEST: {}",
            newly_identical.join(", ")
        );
    }
    assert!(
        same > 0,
        "no example program matched: is the harness broken?"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The manifest names every driver once, and every driver is in the manifest.
#[test]
fn every_driver_is_in_the_manifest() {
    let entries = manifest().unwrap_or_else(|e| panic!("{e}"));
    let mut names: Vec<&str> = entries.iter().map(|e| e.name.as_str()).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(before, names.len(), "a driver is listed twice");
    let dir = std::fs::read_dir(drivers_dir()).unwrap_or_else(|e| panic!("{e}"));
    for file in dir.flatten() {
        let file_name = file.file_name().to_string_lossy().into_owned();
        if let Some(name) = file_name.strip_suffix(".bat") {
            assert!(
                names.contains(&name),
                "{file_name} is not in tests/clips/examples/MANIFEST"
            );
        }
    }
}
