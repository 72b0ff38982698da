//! Programs where our engine is known to differ from CLIPS, listed with a reason in a
//! `KNOWN-DIVERGENCES` file beside the programs (`name  reason`, `#` comments).
//!
//! A listed program must still differ: once the engine is fixed its test fails until
//! the line is removed, so the list can only shrink and never hides a regression
//! elsewhere.

use std::path::Path;

/// The reason given for `name`, if it is listed.
pub fn reason(dir: &Path, name: &str) -> Option<String> {
    let text = std::fs::read_to_string(dir.join("KNOWN-DIVERGENCES")).ok()?;
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .find_map(|l| {
            let (listed, why) = l.split_once(char::is_whitespace).unwrap_or((l, ""));
            (listed == name).then(|| why.trim().to_string())
        })
}

/// Turns a program's check result into the verdict, honouring the list.
pub fn judge(dir: &Path, name: &str, result: Result<(), String>) -> Result<(), String> {
    match (reason(dir, name), result) {
        (None, r) => r,
        (Some(why), Err(_)) => {
            println!("known divergence {name}: {why}");
            Ok(())
        }
        (Some(_), Ok(())) => Err(format!(
            "{name} is listed in {}/KNOWN-DIVERGENCES but now matches: remove its line",
            dir.display()
        )),
    }
}

/// Checks every program, prints one line each and "N passed, M failed (of N <what>)",
/// and fails when any program fails (known divergences count as passed, printed as such).
pub fn summarize(
    dir: &Path,
    names: &[String],
    what: &str,
    check: impl Fn(&str) -> Result<(), String>,
) {
    let mut failed = Vec::new();
    for name in names {
        match judge(dir, name, check(name)) {
            Ok(()) => println!("ok      {name}"),
            Err(report) => {
                println!("FAILED  {name}");
                failed.push((name.clone(), report));
            }
        }
    }
    for (_, report) in &failed {
        println!("\n{report}");
    }
    let summary = format!(
        "{} passed, {} failed (of {} {what})",
        names.len() - failed.len(),
        failed.len(),
        names.len()
    );
    println!("\n{summary}");
    assert!(
        failed.is_empty(),
        "{summary}; failing: {:?}",
        failed.iter().map(|(n, _)| n).collect::<Vec<_>>()
    );
}
