//! Link arguments of the host program `robotino-agent`.
//!
//! On x86-64 Linux with glibc the program's relative relocations are packed
//! (`DT_RELR`, glibc 2.36+, binutils 2.38+): the ~9,400 entries of `.rela.dyn` (224 KB
//! of the file, all read by the dynamic loader at every start, so resident in every
//! process, even an empty program's) become a bitmap of a few KB, and the loader
//! applies them with fewer instructions.
//!
//! The functions an empty CLIPS program runs (`link-order.txt`: the program's own
//! symbols that callgrind saw run `clips -f2` on `(exit)`) are placed together, first in
//! `.text` (lld's `--symbol-ordering-file`; names it does not find are skipped, so a
//! stale list costs only locality): start-up code spread over the 5 MB of code made
//! every program map ~640 pages of it (fault-around maps 64 KB, or a whole large folio,
//! around each page run), the functions themselves are ~230 KB.

use std::env;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let target_env = env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if arch == "x86_64" && os == "linux" && target_env == "gnu" {
        println!("cargo::rustc-link-arg-bin=robotino-agent=-Wl,-z,pack-relative-relocs");
        let dir = env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        println!("cargo::rerun-if-changed=link-order.txt");
        println!(
            "cargo::rustc-link-arg-bin=robotino-agent=-Wl,--symbol-ordering-file={dir}/link-order.txt"
        );
        println!("cargo::rustc-link-arg-bin=robotino-agent=-Wl,--no-warn-symbol-ordering");
    }
}
