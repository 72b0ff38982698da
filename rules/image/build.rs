//! Link arguments and the `freestanding` cfg for the agent image.
//!
//! They apply only when building for 32-bit x86 Linux (the LX800): there the image provides
//! its own `_start`, memory functions and syscalls, so it links without libc or start files.
//! On the host the same crate is an ordinary std program (for clippy and unit tests). The
//! arguments go to bin targets only (`rustc-link-arg-bins`), never target-wide, so the i586
//! std test binaries of the other crates keep linking against glibc.

use std::env;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(freestanding)");
    println!("cargo::rerun-if-changed=build.rs");

    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if arch == "x86" && os == "linux" {
        println!("cargo::rustc-cfg=freestanding");
        // No crt files, no libc, a fully static non-PIE executable: `_start` is ours and
        // nothing relocates the image at run time. No RELRO either: without a dynamic loader
        // or libc nobody would write-protect it, and its page padding (`.relro_padding`)
        // would only add layout noise to the RAM the footprint gate measures.
        for arg in [
            "-nostartfiles",
            "-nostdlib",
            "-static",
            "-no-pie",
            "-Wl,-z,norelro",
            "-Wl,--no-eh-frame-hdr",
        ] {
            println!("cargo::rustc-link-arg-bins={arg}");
        }
        // The image aborts on panic and never unwinds, but the prebuilt `core` carries
        // unwind tables (`.eh_frame`, 40+ KB): a linker-script fragment, added to the
        // default script, discards them.
        let out_dir = env::var("OUT_DIR").unwrap_or_default();
        let script = std::path::Path::new(&out_dir).join("discard-unwind-tables.ld");
        if let Err(e) = std::fs::write(&script, DISCARD_UNWIND_TABLES) {
            panic!("cannot write {}: {e}", script.display());
        }
        println!("cargo::rustc-link-arg-bins=-Wl,-T,{}", script.display());
    }
}

/// Linker-script fragment: `INSERT` keeps the default script and adds this to it.
const DISCARD_UNWIND_TABLES: &str = "\
SECTIONS
{
  /DISCARD/ : { *(.eh_frame) *(.eh_frame_hdr) }
}
INSERT AFTER .text;
";
