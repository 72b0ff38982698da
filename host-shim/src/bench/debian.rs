//! Programs people wrote: the sudoku solver and the zebra puzzle that Debian's
//! `clips-common` package installs with CLIPS (`dpkg -L clips-common`).
//!
//! They are read where the package puts them (most files gzip-compressed) and written,
//! decompressed, into the bench's work directory; the repository holds none of their
//! text. `CLIPS_EXAMPLES` names another folder of the same layout.

use super::workloads::{Kind, Workload};
use super::BenchError;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Where Debian's `clips-common` installs the CLIPS examples.
pub const DEBIAN_EXAMPLES: &str = "/usr/share/doc/clips-common/examples";

/// Printed after the shipped `runbench.bat`, whose output file (`output-none.clp`)
/// prints nothing: the cells still possible, in fact-list order, so engines can be
/// compared on what the runs left behind.
pub const RUNBENCH_RESULT: &str = "(do-for-all-facts ((?p possible)) TRUE \
     (printout t \"cell \" ?p:row \" \" ?p:column \" \" ?p:value crlf))\n";

/// The examples folder: `$CLIPS_EXAMPLES`, else Debian's.
pub fn examples_dir() -> PathBuf {
    std::env::var_os("CLIPS_EXAMPLES")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(DEBIAN_EXAMPLES))
}

/// The text of example file `relative` (as a batch file names it, e.g.
/// `puzzles//grid3x3-p17.clp`), from the file itself or its `.gz`.
pub fn read_example(relative: &str) -> Result<String, BenchError> {
    let path = examples_dir().join(relative.replace("//", "/"));
    if path.is_file() {
        return std::fs::read_to_string(&path)
            .map_err(|e| BenchError::new(format!("reading {}: {e}", path.display())));
    }
    let mut compressed = path.into_os_string();
    compressed.push(".gz");
    let compressed = PathBuf::from(compressed);
    if !compressed.is_file() {
        return Err(BenchError::new(format!(
            "{relative}: not in {} (install Debian's clips-common, or set CLIPS_EXAMPLES)",
            examples_dir().display()
        )));
    }
    let out = Command::new("gzip")
        .arg("-dc")
        .arg(&compressed)
        .output()
        .map_err(|e| BenchError::new(format!("running gzip on {}: {e}", compressed.display())))?;
    if !out.status.success() {
        return Err(BenchError::new(format!(
            "gzip -dc {}: {}",
            compressed.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        )));
    }
    String::from_utf8(out.stdout)
        .map_err(|_| BenchError::new(format!("{}: not UTF-8 text", compressed.display())))
}

/// The sudoku solver's files in the order its `how_to_use.txt` loads them, with the
/// output file that prints the solution cell by cell, then the puzzle.
fn sudoku_files(grid: usize, puzzle: usize) -> [String; 4] {
    [
        "sudoku/sudoku.clp".to_string(),
        "sudoku/solve.clp".to_string(),
        "sudoku/output-simple.clp".to_string(),
        format!("sudoku/puzzles/grid{grid}x{grid}-p{puzzle}.clp"),
    ]
}

/// The constructs of an example workload, one file after another (for engines that
/// load one file: the batches of the CLI columns load the same text).
pub fn program_text(workload: Workload) -> Result<String, BenchError> {
    let files: Vec<String> = match workload.kind {
        Kind::Sudoku => sudoku_files(workload.size / 100, workload.size % 100).to_vec(),
        Kind::Zebra => vec!["zebra.clp".to_string()],
        Kind::SudokuRunbench => runbench_loads(&read_example("sudoku/runbench.bat")?)
            .into_iter()
            .map(|file| format!("sudoku/{file}"))
            .collect(),
        _ => {
            return Err(BenchError::new(format!(
                "{} is not a CLIPS example",
                workload.name()
            )))
        }
    };
    let mut text = String::new();
    for file in files {
        text.push_str(&read_example(&file)?);
        text.push('\n');
    }
    Ok(text)
}

/// The file a batch line `(load "FILE")` loads, if it is one.
fn load_target(line: &str) -> Option<&str> {
    let rest = line.trim().strip_prefix("(load")?;
    let rest = rest.strip_prefix('*').unwrap_or(rest).trim_start();
    let inner = rest.strip_prefix('"')?;
    let (file, tail) = inner.split_once('"')?;
    (tail.trim() == ")").then_some(file)
}

/// The files a batch script loads, in order.
fn runbench_loads(batch: &str) -> Vec<&str> {
    batch.lines().filter_map(load_target).collect()
}

/// The three batch texts of `runbench.bat` as shipped (its files written decompressed
/// under `dir` and loaded from there): full, without its `(run)` commands (the
/// baseline), and full with `(mem-used)` printed at the end.
pub struct RunbenchBatches {
    pub full: String,
    pub norun: String,
    pub mem: String,
}

/// Writes the files `runbench.bat` loads into `dir` and returns its batches.
pub fn write_runbench(dir: &Path) -> Result<RunbenchBatches, BenchError> {
    let shipped = read_example("sudoku/runbench.bat")?;
    let mut body = String::new();
    let mut norun = String::new();
    for line in shipped.lines() {
        let line = match load_target(line) {
            Some(file) => {
                let text = read_example(&format!("sudoku/{file}"))?;
                let path = dir.join(file.replace("//", "/"));
                if let Some(parent) = path.parent() {
                    std::fs::create_dir_all(parent).map_err(|e| {
                        BenchError::new(format!("creating {}: {e}", parent.display()))
                    })?;
                }
                std::fs::write(&path, text)
                    .map_err(|e| BenchError::new(format!("writing {}: {e}", path.display())))?;
                let shown = path
                    .to_str()
                    .filter(|p| !p.contains(['"', '\\']))
                    .ok_or_else(|| {
                        BenchError::new(format!("unusable work path {}", path.display()))
                    })?;
                format!("(load \"{shown}\")")
            }
            None => line.trim_end().to_string(),
        };
        body.push_str(&line);
        body.push('\n');
        if line.trim() != "(run)" {
            norun.push_str(&line);
            norun.push('\n');
        }
    }
    Ok(RunbenchBatches {
        full: format!("{body}{RUNBENCH_RESULT}(exit)\n"),
        norun: format!("{norun}{RUNBENCH_RESULT}(exit)\n"),
        mem: format!("{body}(printout t \"mem-used \" (mem-used) crlf)\n(exit)\n"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_lines_are_recognised() {
        assert_eq!(load_target("(load \"sudoku.clp\")"), Some("sudoku.clp"));
        assert_eq!(
            load_target("  (load* \"puzzles//grid3x3-p17.clp\")  "),
            Some("puzzles//grid3x3-p17.clp")
        );
        assert_eq!(load_target("(reset)"), None);
        assert_eq!(load_target("(load \"a.clp\") (run)"), None);
        let batch = "(clear)\n(load \"a.clp\")\n(reset)\n(load \"b/c.clp\")\n(run)\n";
        assert_eq!(runbench_loads(batch), vec!["a.clp", "b/c.clp"]);
    }

    /// Where Debian's examples are installed: the shipped runbench.bat is rewritten to
    /// load its files from the work folder, and its baseline has no `(run)`.
    #[test]
    fn runbench_batches_load_the_written_files() {
        if read_example("sudoku/runbench.bat").is_err() {
            eprintln!("SKIPPED: clips-common examples not installed");
            return;
        }
        let dir = std::env::temp_dir().join(format!("bench-runbench-{}", std::process::id()));
        let batches = write_runbench(&dir).expect("examples readable, temp dir writable");
        assert!(batches.full.contains("(run)") && !batches.norun.contains("(run)"));
        assert!(batches.full.contains("(assert (stress-test))"));
        for file in runbench_loads(&batches.full) {
            assert!(Path::new(file).is_file(), "{file}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
