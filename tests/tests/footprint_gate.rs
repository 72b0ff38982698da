//! The footprint gate fails on a real image that does not fit: the image built with the
//! `oversize` feature carries a 96 KiB static array in RAM, and the gate must reject it with
//! a message naming the budget and the excess.
//!
//! This builds the image for i586 in a target dir of its own and runs it under qemu, so it
//! needs what the test command installs (i586 target, gcc-multilib, qemu-user).

use std::path::PathBuf;
use std::process::Command;

#[test]
fn an_oversized_static_array_fails_the_ram_budget_by_the_measured_excess() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let json_path = scratch.join("oversize-footprint.json");
    let _ = std::fs::remove_file(&json_path);

    let output = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["--features", "oversize", "--target-dir"])
        .arg(scratch.join("oversize-image"))
        .arg("--json-out")
        .arg(&json_path)
        .output()
        .expect("the footprint tool starts");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);

    assert_eq!(
        output.status.code(),
        Some(1),
        "expected 'over budget' (1)\nstdout:\n{stdout}\nstderr:\n{stderr}"
    );

    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json_path).expect("JSON report written"))
            .expect("JSON report parses");
    let ram = report["ram"]["bytes"].as_u64().expect("ram.bytes");
    let budget = report["ram"]["budget_bytes"]
        .as_u64()
        .expect("ram.budget_bytes");
    let ballast = 96 * 1024;
    assert!(
        report["ram"]["static_bytes"]
            .as_u64()
            .expect("static bytes")
            >= ballast,
        "the ballast must be counted as RAM: {report}"
    );
    assert!(ram > budget);
    assert_eq!(report["pass"], false);

    // The message names the budget, its size and the excess, consistent with the numbers.
    let message = format!(
        "budget `ram` ({budget} B) exceeded by {} B: uses {ram} B",
        ram - budget
    );
    assert!(
        stderr.contains(&message),
        "missing '{message}' in stderr:\n{stderr}"
    );
    assert!(stderr.contains("footprint gate: FAILED"), "{stderr}");
    // Only RAM is over: code and heap still pass, and the table says which one failed.
    assert_eq!(report["violations"].as_array().map(Vec::len), Some(1));
    assert!(stdout.contains("OVER BUDGET"), "{stdout}");
    assert!(
        stdout.contains("no allocator symbol linked  ok"),
        "{stdout}"
    );
}
