//! `sim --robots N` and `sweep --robots N`: teams in the instant simulation, one engine
//! per robot with rules/team.clp and rules/team-agent.clp.

use std::process::Command;

fn agent(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_robotino-agent"))
        .args(args)
        .output()
        .expect("running robotino-agent");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The value after `name` on a `RESULT name value name value ...` line.
fn field<'a>(result: &'a str, name: &str) -> &'a str {
    let words: Vec<&str> = result.split_whitespace().collect();
    words
        .windows(2)
        .find(|w| w[0] == name)
        .map(|w| w[1])
        .unwrap_or_else(|| panic!("no {name} in {result}"))
}

#[test]
fn three_robots_make_more_than_one_without_double_claims() {
    let (ok, one, err) = agent(&["sim", "--seed", "0"]);
    assert!(ok, "{err}");
    let one_result = one.lines().find(|l| l.starts_with("RESULT")).unwrap_or("");
    let (ok, team, err) = agent(&["sim", "--seed", "0", "--robots", "3"]);
    assert!(ok, "{err}");
    let result = team
        .lines()
        .find(|l| l.starts_with("RESULT"))
        .unwrap_or_else(|| panic!("no RESULT line:\n{team}"));
    assert_eq!(field(result, "double-claims"), "0", "{result}");
    // With 2012 recycling the pucks come back, so the clock ends both games and the
    // team's saved time becomes points: at least 1.3 times one robot's (the issue's
    // target for the team). The team may be done a few seconds early, when nothing it
    // could still start would end before the clock.
    let end_s = field(result, "time").parse::<f64>().unwrap_or(0.0);
    assert!(field(result, "end") == "time" || end_s >= 890.0, "{result}");
    let points = |r: &str| field(r, "points").parse::<f64>().unwrap_or(0.0);
    assert!(
        points(result) >= 1.3 * points(one_result),
        "{result}\n{one_result}"
    );
    assert_ne!(field(result, "recycled"), "0", "{result}");
    // Every robot worked.
    for r in 1..=3 {
        let line = team
            .lines()
            .find(|l| l.starts_with(&format!("robot {r}:")))
            .unwrap_or_else(|| panic!("no robot {r} line:\n{team}"));
        assert!(!line.contains(": 0 skills"), "{line}");
    }
}

#[test]
fn a_small_team_sweep_is_never_below_one_robot() {
    let (ok, out, err) = agent(&[
        "sweep",
        "--robots",
        "3",
        "--limit",
        "4",
        "--threads",
        "2",
        "--quiet",
    ]);
    assert!(ok, "{err}\n{out}");
    assert!(out.contains("team below one robot: 0 assignments"), "{out}");
    let row = out
        .lines()
        .find(|l| l.starts_with("| 3 |"))
        .unwrap_or_else(|| panic!("no team row:\n{out}"));
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    // | robots | mean | min | P | end | stalls | double claims | stuck |
    assert_eq!(cells[7], "0", "double claims: {row}");
    assert_eq!(cells[8], "0", "stuck games: {row}");
}

#[test]
fn team_sizes_and_single_robot_options_are_refused_not_ignored() {
    for bad in [&["sim", "--robots", "0"][..], &["sim", "--robots", "7"]] {
        let (ok, _, err) = agent(bad);
        assert!(
            !ok && err.contains("a team has 1 to 6 robots"),
            "{bad:?}: {err}"
        );
    }
    let (ok, _, err) = agent(&["sim", "--robots", "2", "--fault-rate", "10"]);
    assert!(
        !ok && err.contains("--fault-rate is for one robot"),
        "{err}"
    );
}
