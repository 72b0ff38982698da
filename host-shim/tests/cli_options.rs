//! The command line's options against real CLIPS 6.30: `robotino-agent clips OPTIONS`
//! must print exactly what `clips OPTIONS` prints (banner included) for the same files
//! and standard input. Covers `-f2` (start-up batch without echo or results, before the
//! banner), `-l` (start-up load), `-f` (batch through the command loop) and their order.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "robotino-cli-options-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// Runs `exe args...` in `dir` with `stdin` as input, under a 10 s timeout.
fn run(exe: &[&str], args: &[&str], dir: &Path, stdin: &str) -> String {
    run_within("10", exe, args, dir, stdin)
}

/// `run` under a timeout of `secs` seconds.
fn run_within(secs: &str, exe: &[&str], args: &[&str], dir: &Path, stdin: &str) -> String {
    let mut child = Command::new("timeout")
        .arg(secs)
        .args(exe)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("cannot start timeout/engine");
    if let Some(mut i) = child.stdin.take() {
        let _ = i.write_all(stdin.as_bytes());
    }
    let out = child.wait_with_output().expect("engine output");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn compare(name: &str, files: &[(&str, &str)], args: &[&str], stdin: &str) {
    compare_within("10", name, files, args, stdin);
}

/// `compare` with both runs under a timeout of `secs` seconds.
fn compare_within(secs: &str, name: &str, files: &[(&str, &str)], args: &[&str], stdin: &str) {
    let dir = scratch(name);
    for (f, text) in files {
        std::fs::write(dir.join(f), text).expect("write program");
    }
    let ours = env!("CARGO_BIN_EXE_robotino-agent");
    let has_clips = std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())
        .any(|d| d.join("clips").is_file());
    assert!(
        has_clips,
        "real CLIPS 6.30 is required: apt-get install clips"
    );
    let theirs = run_within(secs, &["clips"], args, &dir, stdin);
    let mine = run_within(secs, &[ours, "clips"], args, &dir, stdin);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        mine, theirs,
        "{name}: our output (left) differs from CLIPS (right)"
    );
}

const PROGRAM: &str = "(printout t \"hello\" crlf)\n(+ 1 2)\n(assert (a 1))\n\
    (defrule r (a ?x) => (printout t \"fired \" ?x crlf))\n(run)\n(facts)\n";

#[test]
fn f2_runs_silently_before_the_banner() {
    compare(
        "f2",
        &[("p.clp", &format!("{PROGRAM}(exit)\n"))],
        &["-f2", "p.clp"],
        "",
    );
}

#[test]
fn f2_without_exit_then_prompts() {
    compare(
        "f2-prompt",
        &[("p.clp", PROGRAM)],
        &["-f2", "p.clp"],
        "(facts)\n(+ 2 3)\n(exit)\n",
    );
}

/// A prompt comes at the start and after each command: a blank line (or one of
/// blanks) typed at the prompt prints none, before a command, inside one or after
/// a constant whose line had more on it.
#[test]
fn blank_lines_at_the_prompt_print_no_prompt() {
    compare(
        "blank-lines",
        &[],
        &[],
        "\n\n1\n\n2\n   \n(+ 1\n\n2)\n\n\"a\" b\n\n(exit)\n",
    );
}

/// A command that never ends, killed by the timeout: what came before it is on
/// stdout, its echo included (CLIPS flushes its output; ours sends whole lines).
#[test]
fn output_before_a_hang_survives_the_kill() {
    compare_within(
        "4",
        "hang",
        &[(
            "hang.clp",
            "(printout t \"before\" crlf)\n(bind ?x 1)\n(while TRUE do (bind ?x 2))\n\
             (printout t \"never\" crlf)\n",
        )],
        &["-f", "hang.clp"],
        "",
    );
}

#[test]
fn options_run_in_clips_order() {
    compare(
        "order",
        &[
            ("f.clp", "(printout t \"in f\" crlf)\n(* 2 3)\n"),
            ("l.clp", "(defrule lr (a) => )\n(deffacts d (a))\n"),
            ("f2.clp", "(printout t \"in f2\" crlf)\n(+ 1 2)\n"),
        ],
        &["-f", "f.clp", "-l", "l.clp", "-f2", "f2.clp"],
        "(list-defrules)\n(exit)\n",
    );
}

#[test]
fn batch_inside_a_batch_file() {
    compare(
        "batch",
        &[
            ("outer.clp", "(batch \"inner.clp\")\n(printout t \"after\" crlf)\n(batch* \"inner.clp\")\n(exit)\n"),
            ("inner.clp", "(printout t \"inner\" crlf)\n(+ 4 5)\n\n"),
        ],
        &["-f", "outer.clp"],
        "",
    );
}

/// `load*` and `batch*` from a rule's RHS: the new rule is matched against existing facts
/// at once, the batch file's asserts land in the running engine; then load messages.
#[test]
fn load_and_batch_from_a_rule() {
    compare(
        "rhs-load",
        &[
            (
                "late.clp",
                "(defrule late (item ?x) => (printout t \"late sees \" ?x crlf))\n(deffacts more (item 9))\n",
            ),
            ("cmds.clp", "(printout t \"from batch\" crlf)\n(assert (item 5))\n"),
            (
                "main.clp",
                "(watch facts)\n(watch rules)\n(watch activations)\n(assert (item 1) (item 2))\n\
                 (defrule loader (go) => (printout t \"loading\" crlf) (load* \"late.clp\") (printout t \"loaded\" crlf))\n\
                 (defrule batcher (go2) => (batch* \"cmds.clp\") (printout t \"batched\" crlf))\n\
                 (assert (go))\n(run)\n(agenda)\n(assert (go2))\n(run)\n(reset)\n(run)\n\
                 (unwatch compilations)\n(load \"late.clp\")\n(load \"missing.clp\")\n(exit)\n",
            ),
        ],
        &["-f", "main.clp"],
        "",
    );
}

/// The command line's pools grow: a program that outgrows the fixed host engine
/// (`Capacities::HOST`: 4,096 facts, 32,768 fact values, 512 rules; here 10,000 facts
/// from 20 `deffacts`, 600 rules and 40,000 tokens) runs as in CLIPS on plain `clips`,
/// and `--large-pools` (ours only, kept for older scripts) gives the same.
#[test]
fn pools_grow_past_the_fixed_host_capacities() {
    let dir = scratch("large-pools");
    let mut program = String::new();
    for chunk in 0..20 {
        program.push_str(&format!("(deffacts d{chunk}"));
        for i in chunk * 500..(chunk + 1) * 500 {
            program.push_str(&format!(" (n {i})"));
        }
        program.push_str(")\n");
    }
    program.push_str(
        "(defglobal ?*sum* = 0 ?*count* = 0 ?*hits* = 0)\n\
         (defrule add (n ?x) => (bind ?*sum* (+ ?*sum* ?x)) (bind ?*count* (+ ?*count* 1)))\n",
    );
    // more rules than the fixed engine holds, each with an alpha memory of 500 facts
    for r in 0..600 {
        program.push_str(&format!(
            "(defrule r{r} (n ?x&:(= (mod ?x 600) {r})) => (bind ?*hits* (+ ?*hits* 1)))\n"
        ));
    }
    std::fs::write(dir.join("big.clp"), program).expect("write program");
    std::fs::write(
        dir.join("cmds.bat"),
        "(reset)\n(run)\n(printout t \"sum \" ?*sum* \" count \" ?*count* \" hits \" ?*hits* crlf)\n(exit)\n",
    )
    .expect("write batch");
    let ours = env!("CARGO_BIN_EXE_robotino-agent");
    let args = ["-l", "big.clp", "-f2", "cmds.bat"];
    // CLIPS needs seconds here; on a loaded machine more than `run`'s 10.
    let theirs = run_within("120", &["clips"], &args, &dir, "");
    assert!(
        theirs.contains("sum 49995000 count 10000 hits 10000"),
        "CLIPS: {theirs}"
    );
    let grown = run_within("120", &[ours, "clips"], &args, &dir, "");
    assert_eq!(grown, theirs, "clips (left) differs from CLIPS (right)");
    let large = run_within("120", &[ours, "clips", "--large-pools"], &args, &dir, "");
    assert_eq!(
        large, theirs,
        "--large-pools (left) differs from CLIPS (right)"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `batch*` from a rule's actions and from a pattern test: the commands of the batch
/// file run there (an assert refused while the test runs), and the rule's own variables
/// and multifields are as they were afterwards.
#[test]
fn batch_star_inside_actions_and_tests_keeps_the_caller_frame() {
    compare(
        "batch-star-nested",
        &[
            (
                "main.clp",
                "(deffunction bf () (batch* \"cmd.clp\") TRUE)\n\
                 (defrule r (a ?x&:(bf)) => (printout t \"r fired\" crlf))\n\
                 (assert (a 1))\n\
                 (facts)\n\
                 (defrule s (s) => (bind ?v (create$ 1 2 3)) (bind ?w 7) \
                 (batch* \"cmd.clp\") (printout t ?v \" \" ?w crlf))\n\
                 (assert (s))\n\
                 (run)\n\
                 (exit)\n",
            ),
            (
                "cmd.clp",
                "(printout t \"in batch\" crlf)\n(assert (c 1))\n",
            ),
        ],
        &["-f2", "main.clp"],
        "",
    );
}

/// A file that is not UTF-8 (CLIPS reads bytes; we refuse, naming where): `-l` runs
/// nothing of it and says line and column on stderr; `-f` runs the items before the
/// first such byte and the engine reports it.
#[test]
fn files_not_utf8_are_refused_at_their_first_such_byte() {
    let dir = scratch("latin1");
    std::fs::write(
        dir.join("l.clp"),
        b"(printout t ok crlf)\n(printout t \"x\xE9y\" crlf)\n(printout t no crlf)\n",
    )
    .expect("write program");
    let ours = env!("CARGO_BIN_EXE_robotino-agent");
    let out = Command::new("timeout")
        .args(["10", ours, "clips", "-l", "l.clp"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .output()
        .expect("engine output");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("l.clp:2:15: byte 0xE9 is not UTF-8"),
        "stderr: {err}"
    );
    assert!(!out.status.success());
    let out = run(&[ours, "clips"], &["-f", "l.clp"], &dir, "");
    assert!(out.contains("\nok\n"), "{out}");
    assert!(
        out.contains("file l.clp: byte 0xE9 at line 2, column 15"),
        "{out}"
    );
    assert!(!out.contains("no\n"), "{out}");
}
