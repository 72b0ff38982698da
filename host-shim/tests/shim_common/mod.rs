//! Helpers for the process-level tests: start the real binaries under a unique service
//! prefix, collect their output, and wait on conditions with a watchdog (never a fixed
//! sleep). Dropping a [`Proc`] kills it.

#![allow(dead_code)] // each test binary uses a different subset

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

pub const AGENT: &str = env!("CARGO_BIN_EXE_robotino-agent");
pub const SIM: &str = env!("CARGO_BIN_EXE_robotino-sim");

/// A service prefix no other test or run shares.
pub fn unique_prefix(test: &str) -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    format!("shimtest/{test}/{}-{nanos}", std::process::id())
}

/// A running child process whose stdout lines are collected.
pub struct Proc {
    pub name: String,
    child: Child,
    lines: Arc<Mutex<Vec<String>>>,
    reader: Option<std::thread::JoinHandle<()>>,
}

impl Proc {
    pub fn start(name: &str, program: &str, args: &[&str]) -> Proc {
        let mut child = Command::new(program)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {program}: {e}"));
        let lines = Arc::new(Mutex::new(Vec::new()));
        let mut reader = None;
        if let Some(out) = child.stdout.take() {
            let sink = Arc::clone(&lines);
            reader = Some(std::thread::spawn(move || {
                for line in BufReader::new(out).lines().map_while(Result::ok) {
                    if let Ok(mut v) = sink.lock() {
                        v.push(line);
                    }
                }
            }));
        }
        Proc {
            name: name.to_string(),
            child,
            lines,
            reader,
        }
    }

    pub fn lines(&self) -> Vec<String> {
        self.lines.lock().map(|v| v.clone()).unwrap_or_default()
    }

    /// The first output line containing `needle`.
    pub fn line_with(&self, needle: &str) -> Option<String> {
        self.lines().into_iter().find(|l| l.contains(needle))
    }

    /// Hard kill, as a crash would: no clean-up runs in the child.
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// Asks the process to stop (SIGTERM), as an operator would.
    pub fn terminate(&mut self) {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
    }

    /// Waits for the process to exit by itself.
    pub fn wait_exit(&mut self, timeout: Duration) -> Option<std::process::ExitStatus> {
        let deadline = Instant::now() + timeout;
        while Instant::now() < deadline {
            if let Ok(Some(status)) = self.child.try_wait() {
                // The last lines may still be in the pipe: let the reader reach its end
                // (bounded, in case a grandchild holds the pipe open).
                let until = Instant::now() + Duration::from_secs(5);
                while self.reader.as_ref().is_some_and(|r| !r.is_finished())
                    && Instant::now() < until
                {
                    std::thread::sleep(Duration::from_millis(5));
                }
                return Some(status);
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        None
    }

    pub fn dump(&self) -> String {
        format!("--- {} ---\n{}", self.name, self.lines().join("\n"))
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        self.kill();
    }
}

/// Polls `condition` until it holds; panics with the processes' output after `timeout`.
pub fn wait_until(
    what: &str,
    timeout: Duration,
    procs: &[&Proc],
    mut condition: impl FnMut() -> bool,
) {
    let deadline = Instant::now() + timeout;
    while Instant::now() < deadline {
        if condition() {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let logs: Vec<String> = procs.iter().map(|p| p.dump()).collect();
    panic!(
        "watchdog: `{what}` not reached within {timeout:?}\n{}",
        logs.join("\n")
    );
}

/// A finished `game-sweep`: a row per seed and the summary, read from its tables by the
/// columns' names.
pub struct Sweep {
    /// (seed, points) per game, in the order printed.
    pub rows: Vec<(u64, i64)>,
    /// The summary row, column name to cell (`games`, `mean points`, `collisions`, ...).
    summary: Vec<(String, String)>,
    /// Everything the sweep printed, for assertion messages.
    pub output: String,
}

impl Sweep {
    /// Runs `robotino-agent game-sweep ARGS` (add `--quiet`) and reads its tables; panics
    /// with the output when it fails, runs past `timeout` or prints no summary.
    pub fn run(args: &[&str], timeout: Duration) -> Sweep {
        let mut argv = vec!["game-sweep"];
        argv.extend_from_slice(args);
        let mut sweep = Proc::start("game-sweep", AGENT, &argv);
        let status = sweep.wait_exit(timeout);
        assert!(status.is_some_and(|s| s.success()), "{}", sweep.dump());
        Sweep::parse(&sweep.lines(), sweep.dump())
    }

    /// Reads the tables from a sweep's output lines.
    pub fn parse(lines: &[String], output: String) -> Sweep {
        let cells = |l: &str| -> Vec<String> {
            let l = l.trim().trim_start_matches('|').trim_end_matches('|');
            l.split('|').map(|c| c.trim().to_string()).collect()
        };
        let rows = lines
            .iter()
            .filter(|l| {
                l.starts_with("| ") && !l.starts_with("| seed") && !l.starts_with("| games")
            })
            .map(|l| cells(l))
            .filter_map(|c| Some((c.first()?.parse().ok()?, c.get(1)?.parse().ok()?)))
            .collect();
        let header = lines
            .iter()
            .position(|l| l.starts_with("| games | mean points"))
            .unwrap_or_else(|| panic!("no summary\n{output}"));
        let values = lines
            .get(header + 2)
            .unwrap_or_else(|| panic!("no summary row\n{output}"));
        let summary = cells(&lines[header])
            .into_iter()
            .zip(cells(values))
            .collect();
        Sweep {
            rows,
            summary,
            output,
        }
    }

    /// The summary's cell in column `name`, as printed.
    pub fn cell(&self, name: &str) -> &str {
        self.summary
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
            .unwrap_or_else(|| panic!("no column `{name}`\n{}", self.output))
    }

    /// The summary's cell in column `name` as a number.
    pub fn number(&self, name: &str) -> f64 {
        let cell = self.cell(name);
        cell.parse()
            .unwrap_or_else(|_| panic!("`{name}` is `{cell}`\n{}", self.output))
    }
}
