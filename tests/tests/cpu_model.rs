//! The premise of running the image under `qemu-i386 -cpu pentium`: that CPU model really
//! rejects i686 instructions, so an image that runs there needs nothing beyond i586. A tiny
//! freestanding program using `cmov` is assembled (`cc -m32`, gcc-multilib) and run under
//! the image's qemu command (must die with SIGILL) and under the test runner's
//! `-cpu pentium2` (must run).

use std::os::unix::process::ExitStatusExt;
use std::path::PathBuf;
use std::process::Command;
use tests::image::QEMU;

const SIGILL: i32 = 4;

fn build_cmov_program() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let source = dir.join("cmov_probe.s");
    let program = dir.join("cmov_probe");
    std::fs::write(
        &source,
        ".text\n.globl _start\n_start:\n  movl $1, %eax\n  movl $2, %ecx\n  cmpl %eax, %ecx\n  \
         cmovel %ecx, %eax\n  movl $1, %eax\n  xorl %ebx, %ebx\n  int $0x80\n",
    )
    .unwrap();
    let status = Command::new("cc")
        .args(["-m32", "-nostdlib", "-static", "-o"])
        .arg(&program)
        .arg(&source)
        .status()
        .expect("cc starts");
    assert!(status.success(), "cc -m32 could not link the probe");
    program
}

#[test]
fn the_image_cpu_model_traps_cmov_and_the_test_runner_model_runs_it() {
    let program = build_cmov_program();

    // Run in the scratch dir: if core dumps are enabled, qemu's core file lands there.
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let strict = Command::new(QEMU[0])
        .args(&QEMU[1..])
        .arg(&program)
        .current_dir(&scratch)
        .output()
        .expect("qemu starts");
    // qemu-user re-raises the guest's SIGILL on itself.
    assert_eq!(
        strict.status.signal(),
        Some(SIGILL),
        "`{}` ran a cmov: {:?}",
        QEMU.join(" "),
        strict.status
    );

    let i686 = Command::new("qemu-i386")
        .args(["-cpu", "pentium2"])
        .arg(&program)
        .status()
        .expect("qemu starts");
    assert!(i686.success(), "pentium2 should run cmov: {i686:?}");
}
