//! Runs a CLIPS batch program in real CLIPS 6.30 (`clips -f FILE`) and in our CLI
//! (`robotino-agent clips -f FILE`, or the `DIFFTEST_ENGINE` override) and compares the
//! transcripts: shared by the differential suite (`differential.rs`) and the random
//! programs (`differential_random.rs`).

#![allow(dead_code)] // each test binary uses a different subset

use std::fmt::Write as _;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Each run of a program (in either engine) gets this long before it is killed: a hang
/// fails with the program's name. Wall time, so it leaves room for a loaded machine
/// (program 140, 0.6 s of CPU, took 16 s at a load of 25 on 2 cores).
pub const RUN_TIMEOUT: Duration = Duration::from_secs(30);
/// Lines shown around the first difference.
pub const DIFF_CONTEXT: usize = 3;

/// Output of one run.
pub struct RunOutput {
    pub stdout: String,
    /// Kept for diagnostics only; never compared.
    pub stderr: String,
    pub timed_out: bool,
    pub status: Option<i32>,
}

/// Runs `program args...` in `cwd` with stdin closed, killing it after `RUN_TIMEOUT`.
pub fn run_with_timeout(program: &Path, args: &[&Path], cwd: &Path) -> Result<RunOutput, String> {
    run_with_input(program, args, cwd, None, RUN_TIMEOUT)
}

/// Runs `program args...` in `cwd`, feeding `input` on stdin (closed when `None`, and after
/// the input), killing it after `timeout`.
pub fn run_with_input(
    program: &Path,
    args: &[&Path],
    cwd: &Path,
    input: Option<&[u8]>,
    timeout: Duration,
) -> Result<RunOutput, String> {
    let mut child = Command::new(program)
        .args(args)
        .current_dir(cwd)
        .stdin(if input.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", program.display()))?;
    if let (Some(bytes), Some(mut stdin)) = (input, child.stdin.take()) {
        let bytes = bytes.to_vec();
        // A writer thread: a program that does not read its input must not block us.
        std::thread::spawn(move || {
            use std::io::Write as _;
            let _ = stdin.write_all(&bytes);
        });
    }
    let mut stdout_pipe = child
        .stdout
        .take()
        .ok_or_else(|| "child has no stdout pipe".to_string())?;
    let mut stderr_pipe = child
        .stderr
        .take()
        .ok_or_else(|| "child has no stderr pipe".to_string())?;
    // Read in threads so a chatty child never blocks on a full pipe while we wait.
    let reader = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = stdout_pipe.read_to_end(&mut bytes);
        bytes
    });
    let err_reader = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = stderr_pipe.read_to_end(&mut bytes);
        bytes
    });
    let deadline = Instant::now() + timeout;
    let mut timed_out = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status.code(),
            Ok(None) if Instant::now() >= deadline => {
                timed_out = true;
                let _ = child.kill();
                break child.wait().ok().and_then(|s| s.code());
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(e) => return Err(format!("waiting for {}: {e}", program.display())),
        }
    };
    let bytes = reader
        .join()
        .map_err(|_| "stdout reader thread panicked".to_string())?;
    let err_bytes = err_reader
        .join()
        .map_err(|_| "stderr reader thread panicked".to_string())?;
    Ok(RunOutput {
        stdout: String::from_utf8_lossy(&bytes).into_owned(),
        stderr: String::from_utf8_lossy(&err_bytes).into_owned(),
        timed_out,
        status,
    })
}

/// A fresh, empty working directory, so programs that write files never see each other's.
pub fn scratch_dir(program: &str, engine: &str) -> Result<PathBuf, String> {
    // Unique per run: a program's own test and the summary test may run it concurrently.
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "robotino-difftest-{}-{}-{program}-{engine}",
        std::process::id(),
        RUNS.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    Ok(dir)
}

pub fn clips_command() -> Result<PathBuf, String> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .map(|dir| dir.join("clips"))
        .find(|candidate| candidate.is_file())
        .ok_or_else(|| {
            "real CLIPS 6.30 is required for the differential suite but `clips` is not on PATH: \
             install it (Debian/Ubuntu: `apt-get install clips`)"
                .to_string()
        })
}

/// A transcript (banner removed), the raw stdout, and a note about the run for reports.
pub struct Transcript {
    pub lines: Vec<String>,
    pub raw: String,
    pub note: String,
}

/// Our CLI, invoked as `EXE clips -f FILE`. `DIFFTEST_ENGINE` may name another executable
/// taking the same arguments (used to check the harness itself, e.g. with a wrapper around
/// real CLIPS, which must pass every program).
pub fn our_engine() -> PathBuf {
    std::env::var_os("DIFFTEST_ENGINE")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_robotino-agent")))
}

/// Runs one engine on one program and returns its transcript without the banner.
pub fn transcript(engine: &str, exe: &Path, name: &str, file: &Path) -> Result<Transcript, String> {
    let cwd = scratch_dir(name, engine)?;
    let out = if engine == "clips" {
        run_with_timeout(exe, &[Path::new("-f"), file], &cwd)?
    } else {
        run_with_timeout(exe, &[Path::new("clips"), Path::new("-f"), file], &cwd)?
    };
    let _ = std::fs::remove_dir_all(&cwd);
    if out.timed_out {
        return Err(format!(
            "{engine} did not finish {name} within {RUN_TIMEOUT:?} (missing (exit)? endless loop?); \
             output so far:\n{}",
            out.stdout
        ));
    }
    let mut note = format!("{engine} exit status: {:?}", out.status);
    if !out.stderr.is_empty() {
        let tail: Vec<&str> = out.stderr.lines().rev().take(10).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        let _ = write!(
            note,
            "\n{engine} stderr (last lines):\n  {}",
            tail.join("\n  ")
        );
    }
    Ok(Transcript {
        lines: without_banner(&out.stdout),
        raw: out.stdout,
        note,
    })
}

/// CLIPS prints one banner line (`         CLIPS (6.30 3/17/15)`) before its first prompt;
/// our CLI may print its own banner line or none. Only that one line is not compared: if the
/// output does not start with a prompt, its first line is dropped.
pub fn without_banner(stdout: &str) -> Vec<String> {
    let mut lines = stdout.lines().map(str::to_string).peekable();
    if lines
        .peek()
        .is_some_and(|first| !first.starts_with("CLIPS>"))
    {
        lines.next();
    }
    lines.collect()
}

/// Our CLI adds one line `--> FILE:LINE:COL: expected WHAT` after CLIPS's own text for a
/// parse error (checked by `parse_errors.rs`); CLIPS never prints it, so it is not compared.
pub fn without_position_lines(lines: &[String]) -> Vec<String> {
    lines
        .iter()
        .filter(|line| !is_position_line(line))
        .cloned()
        .collect()
}

pub fn is_position_line(line: &str) -> bool {
    let Some(rest) = line.strip_prefix("--> ") else {
        return false;
    };
    let Some((location, _what)) = rest.split_once(": expected ") else {
        return false;
    };
    let mut parts = location.rsplitn(3, ':');
    let column = parts.next().map(|c| c.parse::<u32>().is_ok());
    let line_no = parts.next().map(|l| l.parse::<u32>().is_ok());
    column == Some(true) && line_no == Some(true) && parts.next().is_some()
}

/// `None` when equal, else a readable report of the first differing line with context.
pub fn first_difference(
    expected_label: &str,
    expected: &[String],
    actual_label: &str,
    actual: &[String],
) -> Option<String> {
    let at = (0..expected.len().max(actual.len())).find(|&i| expected.get(i) != actual.get(i))?;
    let mut report = String::new();
    let _ = writeln!(
        report,
        "first difference at transcript line {} (banner excluded; {} has {} lines, {} has {})",
        at + 1,
        expected_label,
        expected.len(),
        actual_label,
        actual.len()
    );
    let from = at.saturating_sub(DIFF_CONTEXT);
    for (i, line) in expected.iter().enumerate().take(at).skip(from) {
        let _ = writeln!(report, "  {:>4}   {line}", i + 1);
    }
    let show = |l: Option<&String>| match l {
        Some(l) => format!("{l:?}"),
        None => "<end of output>".to_string(),
    };
    let _ = writeln!(
        report,
        "  {:>4} - {expected_label}: {}",
        at + 1,
        show(expected.get(at))
    );
    let _ = writeln!(
        report,
        "  {:>4} + {actual_label}: {}",
        at + 1,
        show(actual.get(at))
    );
    for i in at + 1..=at + DIFF_CONTEXT {
        match (expected.get(i), actual.get(i)) {
            (None, None) => break,
            (Some(same), Some(other)) if same == other => {
                let _ = writeln!(report, "  {:>4}   {same}", i + 1);
            }
            (e, a) => {
                let _ = writeln!(report, "  {:>4} - {expected_label}: {}", i + 1, show(e));
                let _ = writeln!(report, "  {:>4} + {actual_label}: {}", i + 1, show(a));
            }
        }
    }
    Some(report)
}
