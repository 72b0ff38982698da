//! The command line's exit status (issue 19). `(exit N)` exits with N, as in CLIPS. A
//! batch or `-l` file that hit something the session cannot recover from — a pool ran
//! out, a file could not be read, the input ended inside a construct — makes the process
//! exit 1 even after a bare `(exit)`, so a script can tell; real CLIPS exits 0 there (a
//! deliberate difference, stated in the README). Ordinary errors (a syntax error, an
//! unknown function) keep status 0, as in CLIPS.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("robotino-cli-exit-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// Writes `program` to a file and runs `robotino-agent clips OPTION FILE` on it, stdin
/// empty, under a timeout; returns the exit status.
fn status(name: &str, option: &str, program: &str) -> i32 {
    let dir = scratch(name);
    let file = dir.join("program.clp");
    std::fs::write(&file, program).expect("write program");
    let code = run(&dir, &[option, file.to_str().unwrap_or_default()]);
    let _ = std::fs::remove_dir_all(&dir);
    code
}

fn run(dir: &Path, args: &[&str]) -> i32 {
    let out = Command::new("timeout")
        .arg("60")
        .arg(env!("CARGO_BIN_EXE_robotino-agent"))
        .arg("clips")
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .expect("cannot start timeout/robotino-agent");
    let code = out.code().expect("exited, not killed");
    assert_ne!(code, 124, "robotino-agent clips {args:?} timed out");
    code
}

#[test]
fn exit_n_exits_with_n() {
    assert_eq!(status("exit3", "-f", "(exit 3)\n"), 3);
    assert_eq!(status("exit0", "-f", "(printout t hi crlf)\n(exit 0)\n"), 0);
    assert_eq!(
        status("exit-bare", "-f", "(printout t hi crlf)\n(exit)\n"),
        0
    );
    assert_eq!(status("exit-f2", "-f2", "(exit 7)\n"), 7);
}

#[test]
fn ordinary_errors_keep_status_0() {
    assert_eq!(status("syntax", "-f", "(foo)\n(defrule)\n(exit)\n"), 0);
    assert_eq!(status("no-exit", "-f", "(printout t hi crlf)\n"), 0);
}

/// The CLI's pools grow, so a pool runs out only at `--pool-limit` (or the machine's
/// memory): 20,000 facts (five times the fixed host engine's 4,096) fit without it, and
/// the same program under a limit of 4,096 entries per pool exits 1.
#[test]
fn a_pool_running_out_in_a_batch_exits_1() {
    let program =
        "(loop-for-count (?i 1 20000) (assert (x ?i)))\n(printout t after crlf)\n(exit)\n";
    assert_eq!(status("pool-grows", "-f", program), 0);
    let dir = scratch("pool-limit");
    let file = dir.join("program.clp");
    std::fs::write(&file, program).expect("write program");
    let file = file.to_str().unwrap_or_default();
    assert_eq!(run(&dir, &["--pool-limit", "4096", "-f", file]), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn input_ending_inside_a_construct_exits_1() {
    assert_eq!(status("eof-f", "-f", "(defrule r (a) =>\n"), 1);
    assert_eq!(status("eof-l", "-l", "(deftemplate t (slot x)\n"), 1);
}

#[test]
fn an_unreadable_file_exits_1() {
    let dir = scratch("missing");
    assert_eq!(run(&dir, &["-f", "no-such-file.clp"]), 1);
    assert_eq!(run(&dir, &["-l", "no-such-file.clp"]), 1);
    let _ = std::fs::remove_dir_all(&dir);
}
