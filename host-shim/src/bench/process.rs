//! Running measured child processes: wall time, output, a deadline, callgrind.

use super::BenchError;
use std::io::Read;
use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::thread;
use std::time::{Duration, Instant};

/// A finished (or killed) child process.
pub struct Finished {
    pub status: ExitStatus,
    pub stdout: String,
    pub stderr: String,
    /// From spawn to exit, measured in this process.
    pub elapsed: Duration,
    pub timed_out: bool,
}

/// Runs `command` with stdin closed, collecting its output; kills it (by its own pid) when
/// it outlives `limit`. The watchdog is a thread waiting on a channel, so the measured wall
/// time is not rounded up to a polling interval.
pub fn run_with_deadline(command: &mut Command, limit: Duration) -> Result<Finished, BenchError> {
    let shown = format!("{command:?}");
    let start = Instant::now();
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| BenchError::new(format!("cannot start {shown}: {e}")))?;
    let pid = child.id();
    let (done_tx, done_rx) = mpsc::channel::<()>();
    let watchdog = thread::spawn(move || match done_rx.recv_timeout(limit) {
        Err(mpsc::RecvTimeoutError::Timeout) => {
            // The child is still ours and still running: kill exactly that pid.
            let _ = Command::new("kill")
                .args(["-KILL", &pid.to_string()])
                .status();
            true
        }
        _ => false,
    });
    let stdout_reader = child.stdout.take().map(spawn_reader);
    let stderr_reader = child.stderr.take().map(spawn_reader);
    let status = child.wait();
    let elapsed = start.elapsed();
    let _ = done_tx.send(());
    let timed_out = watchdog.join().unwrap_or(false);
    let status = status.map_err(|e| BenchError::new(format!("waiting for {shown}: {e}")))?;
    Ok(Finished {
        status,
        stdout: join_reader(stdout_reader),
        stderr: join_reader(stderr_reader),
        elapsed,
        timed_out,
    })
}

fn spawn_reader(mut pipe: impl Read + Send + 'static) -> thread::JoinHandle<String> {
    thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = pipe.read_to_end(&mut bytes);
        String::from_utf8_lossy(&bytes).into_owned()
    })
}

fn join_reader(reader: Option<thread::JoinHandle<String>>) -> String {
    reader.and_then(|r| r.join().ok()).unwrap_or_default()
}

/// The median of a set of durations (mean of the middle two for an even count).
pub fn median(samples: &[Duration]) -> Option<Duration> {
    let mut sorted = samples.to_vec();
    sorted.sort();
    let mid = sorted.len() / 2;
    match sorted.len() {
        0 => None,
        n if !n.is_multiple_of(2) => Some(sorted[mid]),
        _ => Some((sorted[mid - 1] + sorted[mid]) / 2),
    }
}

/// Whether `valgrind` can be started here.
pub fn valgrind_available() -> bool {
    Command::new("valgrind")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .map(|s| s.success())
        .unwrap_or(false)
}

/// Instructions executed by `program args...` under `valgrind --tool=callgrind`, or why
/// there is no count (time-box exceeded, failure). `scratch` receives the profile file.
pub fn callgrind_instructions(
    program: &str,
    args: &[&str],
    scratch: &Path,
    limit: Duration,
) -> Result<u64, String> {
    let profile = scratch.join("callgrind.out");
    let mut command = Command::new("valgrind");
    command
        .arg("--tool=callgrind")
        .arg(format!("--callgrind-out-file={}", profile.display()))
        .arg(program)
        .args(args)
        // Python (the CLIPS 6.4 driver) hashes with a random seed per process, which
        // moves its instruction count by up to 0.7 M between runs: the run phase,
        // a difference of two runs, is only meaningful with one fixed seed.
        .env("PYTHONHASHSEED", "0");
    let finished = run_with_deadline(&mut command, limit).map_err(|e| e.to_string())?;
    let _ = std::fs::remove_file(&profile);
    if finished.timed_out {
        return Err(format!(
            "callgrind time-box of {} s exceeded",
            limit.as_secs()
        ));
    }
    if !finished.status.success() {
        return Err(format!("under callgrind: {}", finished.status));
    }
    parse_collected(&finished.stderr)
        .ok_or_else(|| "callgrind printed no 'Collected' line".to_string())
}

/// Typical slowdown of a program under callgrind; used to skip runs that cannot finish
/// inside the time-box instead of burning the whole box on them.
pub const CALLGRIND_SLOWDOWN: u32 = 50;

/// `Ok` when a run of `native` wall time (plus `startup` under valgrind) should finish
/// inside `limit` under callgrind, else the reason it is skipped.
pub fn callgrind_fits(native: Duration, startup: Duration, limit: Duration) -> Result<(), String> {
    let expected = startup + native * CALLGRIND_SLOWDOWN;
    if expected <= limit {
        Ok(())
    } else {
        Err(format!(
            "skipped: about {} s expected under callgrind ({:.2} s native x {CALLGRIND_SLOWDOWN}), \
             time-box {} s",
            expected.as_secs(),
            native.as_secs_f64(),
            limit.as_secs()
        ))
    }
}

/// Reads the `==PID== Collected : N` summary line callgrind prints on exit.
pub fn parse_collected(stderr: &str) -> Option<u64> {
    stderr.lines().find_map(|line| {
        let (_, rest) = line.split_once("Collected :")?;
        rest.split_whitespace().next()?.parse().ok()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_even_and_empty_sets() {
        let ms = Duration::from_millis;
        assert_eq!(median(&[ms(5), ms(1), ms(3)]), Some(ms(3)));
        assert_eq!(
            median(&[ms(4), ms(1), ms(3), ms(2)]),
            Some(Duration::from_micros(2500))
        );
        assert_eq!(median(&[]), None);
    }

    #[test]
    fn callgrind_runs_that_cannot_fit_the_time_box_are_skipped() {
        let box_ = Duration::from_secs(100);
        assert!(callgrind_fits(Duration::from_secs(1), Duration::ZERO, box_).is_ok());
        let too_long = callgrind_fits(Duration::from_secs(3), Duration::ZERO, box_);
        assert!(too_long.is_err_and(|why| why.contains("150 s expected")));
        assert!(callgrind_fits(Duration::from_secs(1), Duration::from_secs(60), box_).is_err());
    }

    #[test]
    fn collected_line_is_found_among_callgrind_chatter() {
        let stderr = "==41== Callgrind, a call-graph generating cache profiler\n\
                      ==41== Events    : Ir\n==41== Collected : 1234567\n==41==\n\
                      ==41== I   refs:      1,234,567\n";
        assert_eq!(parse_collected(stderr), Some(1_234_567));
        assert_eq!(parse_collected("no summary"), None);
    }

    #[test]
    fn deadline_kills_a_hanging_child_and_output_is_kept() {
        let quick = run_with_deadline(
            Command::new("sh").args(["-c", "echo out; echo err >&2"]),
            Duration::from_secs(20),
        )
        .expect("sh runs");
        assert!(quick.status.success() && !quick.timed_out);
        assert_eq!(
            (quick.stdout.as_str(), quick.stderr.as_str()),
            ("out\n", "err\n")
        );

        let slow = run_with_deadline(Command::new("sleep").arg("30"), Duration::from_millis(200))
            .expect("sleep runs");
        assert!(slow.timed_out);
        assert!(slow.elapsed < Duration::from_secs(10));
    }
}
