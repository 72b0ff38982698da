//! Building the agent image for the LX800 and running it under qemu.
//!
//! The build goes through cargo (profile `image`, target i586) and reads the executable's
//! path from cargo's JSON messages, so it works with any target dir.

use std::fmt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

pub const TARGET: &str = "i586-unknown-linux-gnu";
pub const PROFILE: &str = "image";
pub const PACKAGE: &str = "agent-image";
/// Strict i586 (no CMOV, no SSE): the image must not need more than the LX800 offers.
pub const QEMU: [&str; 3] = ["qemu-i386", "-cpu", "pentium"];

/// How to build the image.
#[derive(Clone, Debug, Default)]
pub struct BuildOptions {
    /// Cargo features of `agent-image` (e.g. `oversize` in the gate's own test).
    pub features: Vec<String>,
    /// A target dir of its own; `None` uses cargo's default (or `CARGO_TARGET_DIR`).
    pub target_dir: Option<PathBuf>,
}

/// A failed step of building or running the image.
#[derive(Debug)]
pub struct ImageError {
    pub step: String,
    pub detail: String,
}

impl ImageError {
    fn new(step: impl Into<String>, detail: impl fmt::Display) -> Self {
        ImageError {
            step: step.into(),
            detail: detail.to_string(),
        }
    }
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.step, self.detail)
    }
}

impl std::error::Error for ImageError {}

/// The workspace's Cargo.toml (this crate lives one level below it).
pub fn workspace_manifest() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap_or(Path::new("."))
        .join("Cargo.toml")
}

/// Builds the image and returns the executable's path. Cargo's progress goes to stderr.
pub fn build(options: &BuildOptions) -> Result<PathBuf, ImageError> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .arg("build")
        .arg("--manifest-path")
        .arg(workspace_manifest())
        .args(["-p", PACKAGE, "--profile", PROFILE, "--target", TARGET])
        .arg("--message-format=json-render-diagnostics");
    if !options.features.is_empty() {
        command.arg("--features").arg(options.features.join(","));
    }
    if let Some(dir) = &options.target_dir {
        command.arg("--target-dir").arg(dir);
    }
    let step = format!("building {PACKAGE} (cargo build --profile {PROFILE} --target {TARGET})");
    let output = command
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| ImageError::new(&step, format!("cannot start cargo: {e}")))?;
    if !output.status.success() {
        return Err(ImageError::new(
            &step,
            format!("cargo failed ({})", output.status),
        ));
    }
    let messages = String::from_utf8_lossy(&output.stdout);
    executable_from_messages(&messages)
        .ok_or_else(|| ImageError::new(&step, "cargo reported no executable for agent-image"))
}

/// Finds the `agent-image` executable in cargo's `--message-format=json` output.
pub fn executable_from_messages(messages: &str) -> Option<PathBuf> {
    messages
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|msg| msg["reason"] == "compiler-artifact" && msg["target"]["name"] == PACKAGE)
        .filter_map(|msg| msg["executable"].as_str().map(PathBuf::from))
        .next_back()
}

/// What one run of the image under qemu printed.
#[derive(Debug)]
pub struct Run {
    pub stdout: String,
    pub stderr: String,
}

/// Runs the image under `qemu-i386 -cpu pentium`; a non-zero exit is an error.
pub fn run(executable: &Path) -> Result<Run, ImageError> {
    let step = format!("running {} {}", QEMU.join(" "), executable.display());
    let output = Command::new(QEMU[0])
        .args(&QEMU[1..])
        .arg(executable)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| ImageError::new(&step, format!("cannot start {}: {e}", QEMU[0])))?;
    let run = Run {
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    };
    if !output.status.success() {
        return Err(ImageError::new(
            &step,
            format!(
                "exited with {}\nstdout:\n{}stderr:\n{}",
                output.status, run.stdout, run.stderr
            ),
        ));
    }
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn takes_the_executable_of_the_image_from_cargo_messages() {
        let messages = concat!(
            r#"{"reason":"compiler-artifact","target":{"name":"agent_core"},"executable":null}"#,
            "\n",
            "not json\n",
            r#"{"reason":"compiler-artifact","target":{"name":"agent-image"},"executable":"/t/i586-unknown-linux-gnu/image/agent-image"}"#,
            "\n",
            r#"{"reason":"build-finished","success":true}"#,
        );
        assert_eq!(
            executable_from_messages(messages),
            Some(PathBuf::from("/t/i586-unknown-linux-gnu/image/agent-image"))
        );
        assert_eq!(
            executable_from_messages(r#"{"reason":"build-finished"}"#),
            None
        );
    }

    #[test]
    fn the_workspace_manifest_lists_the_image_package() {
        let manifest = std::fs::read_to_string(workspace_manifest()).unwrap();
        assert!(manifest.contains("rules/image"));
    }
}
