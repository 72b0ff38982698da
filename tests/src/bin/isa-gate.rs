//! Instruction-set gate: disassembles the agent image (`objdump -d -w`) and fails on any
//! SSE/SSE2 instruction or `xmm` register, any `cmovcc`, and any multi-byte NOP `0f 1f`.
//!
//! Also checks the image's symbols (`nm -C`): no lexer, parser or float parsing, which the
//! image, loading its rule base compiled ahead of time, must not carry (`tests::contents`).
//!
//! Exit status: 0 clean, 1 forbidden instructions or symbols found, 2 could not check.

use clap::Parser;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use tests::contents;
use tests::image;
use tests::isa::{self, Forbidden};

/// At most this many findings are listed; the counts always cover all of them.
const LISTED_FINDINGS: usize = 40;

#[derive(Parser)]
#[command(about = "Reject instructions the AMD Geode LX800 (strict i586) does not have")]
struct Args {
    /// Check this `objdump -d -w` listing instead of building and disassembling the image.
    #[arg(long)]
    disassembly: Option<PathBuf>,
    /// Build the image in this target dir instead of cargo's default.
    #[arg(long)]
    target_dir: Option<PathBuf>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let (source, listing, executable) = match listing(&args) {
        Ok(found) => found,
        Err(error) => {
            eprintln!("isa gate: could not disassemble the image: {error}");
            return ExitCode::from(2);
        }
    };
    let scan = isa::scan(&listing);
    println!(
        "isa gate: {source}: {} instructions scanned",
        scan.instructions
    );
    if scan.instructions == 0 {
        eprintln!("isa gate: no instructions found in the listing; refusing to call that clean");
        return ExitCode::from(2);
    }
    for reason in Forbidden::ALL {
        println!("  {:<42} {}", reason.describe(), scan.count(reason));
    }
    let contents_ok = match &executable {
        Some(executable) => match check_contents(executable) {
            Ok(ok) => ok,
            Err(error) => {
                eprintln!("isa gate: could not read the image's symbols: {error}");
                return ExitCode::from(2);
            }
        },
        None => {
            println!("isa gate: a listing was given, the image's symbols are not checked");
            true
        }
    };
    if scan.findings.is_empty() {
        println!("isa gate: ok, nothing the LX800 lacks");
        return if contents_ok {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        };
    }
    for finding in scan.findings.iter().take(LISTED_FINDINGS) {
        println!("  {finding}");
    }
    if scan.findings.len() > LISTED_FINDINGS {
        println!("  ... and {} more", scan.findings.len() - LISTED_FINDINGS);
    }
    eprintln!(
        "isa gate: FAILED: {} forbidden instructions in {source}",
        scan.findings.len()
    );
    ExitCode::from(1)
}

/// Prints what of the text side the image carries; `false` when anything.
fn check_contents(executable: &Path) -> Result<bool, String> {
    let output = Command::new("nm")
        .arg("-C")
        .arg(executable)
        .output()
        .map_err(|e| format!("cannot start nm (Debian package binutils): {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "nm failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let listing = String::from_utf8_lossy(&output.stdout);
    let symbols = contents::symbol_count(&listing);
    if symbols == 0 {
        return Err(format!("{} has no symbols to check", executable.display()));
    }
    let found = contents::scan(&listing);
    if found.is_empty() {
        println!("isa gate: {symbols} symbols, no lexer, parser or float parsing in the image");
        return Ok(true);
    }
    for finding in found.iter().take(LISTED_FINDINGS) {
        println!("  {} ({})", finding.symbol, finding.what);
    }
    eprintln!(
        "isa gate: FAILED: the image carries {} symbols of the text side; it must load its \
         rule base compiled ahead of time and reach no parsing code",
        found.len()
    );
    Ok(false)
}

/// The listing to check, where it came from, and the image it was made from.
fn listing(args: &Args) -> Result<(String, String, Option<PathBuf>), String> {
    if let Some(path) = &args.disassembly {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("reading {}: {e}", path.display()))?;
        return Ok((path.display().to_string(), text, None));
    }
    let options = image::BuildOptions {
        features: Vec::new(),
        target_dir: args.target_dir.clone(),
    };
    let executable = image::build(&options).map_err(|e| e.to_string())?;
    let text = disassemble(&executable)?;
    Ok((
        format!("objdump -d -w {}", executable.display()),
        text,
        Some(executable),
    ))
}

fn disassemble(executable: &Path) -> Result<String, String> {
    let output = Command::new("objdump")
        .args(["-d", "-w"])
        .arg(executable)
        .output()
        .map_err(|e| format!("cannot start objdump (Debian package binutils): {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "objdump failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    String::from_utf8(output.stdout).map_err(|e| format!("objdump printed non-UTF-8 text: {e}"))
}
