//! `robotino-agent sweep --limit N`: plays the first N assignments on both
//! cores without a deadlock and reports the distribution.

use std::process::Command;

fn sweep(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
        .arg("sweep")
        .args(args)
        .output()
        .expect("running robotino-agent sweep");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn line<'a>(out: &'a str, prefix: &str) -> &'a str {
    out.lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no {prefix:?} line in:\n{out}"))
}

#[test]
fn a_small_sweep_has_no_deadlocks() {
    for strategy in ["naive", "paper", "travel"] {
        let (ok, out, err) = sweep(&[
            "--strategy",
            strategy,
            "--limit",
            "8",
            "--threads",
            "2",
            "--quiet",
        ]);
        assert!(ok, "{strategy}: {err}\n{out}");
        assert!(line(&out, "sweep:").contains("8 assignments"), "{out}");
        assert_eq!(line(&out, "deadlocks:"), "deadlocks: 0");
        // Eight games are counted in the P distribution.
        let p_line = line(&out, "P per game:");
        let games: u32 = p_line
            .split_whitespace()
            .skip(3)
            .filter_map(|pair| {
                pair.split_once(':')
                    .and_then(|(_, n)| n.parse::<u32>().ok())
            })
            .sum();
        assert_eq!(games, 8, "{p_line}");
    }
}

#[test]
fn the_clock_off_sweep_reports_p_per_20_s0() {
    let (ok, out, err) = sweep(&["--clock-off", "--limit", "4", "--quiet"]);
    assert!(ok, "{err}");
    assert!(line(&out, "P made per 20 S0").contains("of 4"), "{out}");
}

#[test]
fn one_thread_and_two_threads_give_the_same_numbers() {
    let strip_speed = |s: String| {
        s.lines()
            .filter(|l| !l.starts_with("speed:"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let (_, one, _) = sweep(&["--limit", "6", "--threads", "1", "--quiet"]);
    let (_, two, _) = sweep(&["--limit", "6", "--threads", "2", "--quiet"]);
    assert_eq!(strip_speed(one), strip_speed(two));
}

#[test]
fn faulty_games_go_on_without_deadlock_stall_or_panic() {
    for strategy in ["naive", "paper", "travel"] {
        let (ok, out, err) = sweep(&[
            "--strategy",
            strategy,
            "--fault-rate",
            "20",
            "--limit",
            "12",
            "--threads",
            "2",
            "--quiet",
        ]);
        assert!(ok, "{strategy}: {err}\n{out}");
        assert!(line(&out, "sweep:").contains("faults 20 %"), "{out}");
        assert_eq!(line(&out, "deadlocks:"), "deadlocks: 0");
        assert_eq!(line(&out, "stalls:"), "stalls: 0, panics: 0");
        // Faults cost pucks: some are lost.
        let lost: f64 = line(&out, "pucks lost per game")
            .split_whitespace()
            .nth(4)
            .and_then(|w| w.trim_end_matches(',').parse().ok())
            .unwrap_or_else(|| panic!("no lost count in {out}"));
        assert!(lost > 0.0, "{out}");
    }
}

#[test]
fn the_fault_table_has_a_row_per_strategy_and_rate() {
    let (ok, out, err) = sweep(&["--fault-table", "--limit", "3", "--threads", "2", "--quiet"]);
    assert!(ok, "{err}\n{out}");
    let rows: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("| paper") || l.starts_with("| travel"))
        .collect();
    assert_eq!(rows.len(), 8, "{out}");
    for row in rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        // deadlocks, stalls, panics
        assert_eq!(&cells[10..13], ["0", "0", "0"], "{row}");
    }
    // Without faults the paper's agent makes at least the 105 points of a game without
    // recycling in each game (20 S0 make 5 P; recycled junk scores and makes more).
    let row = out
        .lines()
        .find(|l| l.starts_with("| paper | 0 | 3 |"))
        .unwrap_or_else(|| panic!("no fault-free paper row:\n{out}"));
    let min: i64 = row
        .split('|')
        .nth(5)
        .and_then(|c| c.trim().parse().ok())
        .unwrap_or(0);
    assert!(min >= 105, "{row}");
}
