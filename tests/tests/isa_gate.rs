//! The instruction-set gate as a program: fed a synthetic listing it passes a clean one and
//! fails, naming each forbidden instruction, on one with SSE, cmov and a multi-byte NOP.

use std::path::PathBuf;
use std::process::{Command, Output};

fn gate_on(name: &str, listing: &str) -> Output {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, listing).expect("listing written");
    Command::new(env!("CARGO_BIN_EXE_isa-gate"))
        .arg("--disassembly")
        .arg(&path)
        .output()
        .expect("the isa gate starts")
}

const HEADER: &str =
    "\nagent-image:     file format elf32-i386\n\n\nDisassembly of section .text:\n\n";

#[test]
fn a_clean_listing_passes() {
    let listing = format!(
        "{HEADER}00401000 <_start>:\n  401000:\t31 ed \txor    %ebp,%ebp\n  401002:\t90 \tnop\n  401003:\tc3 \tret\n"
    );
    let output = gate_on("clean.dis", &listing);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}");
    assert!(stdout.contains("3 instructions scanned"), "{stdout}");
}

#[test]
fn each_forbidden_instruction_fails_the_gate_and_is_named() {
    let listing = format!(
        "{HEADER}00401000 <step>:\n\
         \x20 401000:\t0f 44 c1 \tcmove  %ecx,%eax\n\
         \x20 401003:\t66 0f 1f 44 00 00 \tnopw   0x0(%eax,%eax,1)\n\
         \x20 401009:\t0f 57 c0 \txorps  %xmm0,%xmm0\n\
         \x20 40100c:\t0f ae f8 \tsfence\n\
         \x20 40100f:\tc3 \tret\n"
    );
    let output = gate_on("dirty.dis", &listing);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stdout}{stderr}");
    for expected in [
        "401000 in <step>: cmove",
        "401003 in <step>: nopw",
        "401009 in <step>: xorps",
        "40100c in <step>: sfence",
    ] {
        assert!(stdout.contains(expected), "missing {expected}:\n{stdout}");
    }
    assert!(
        stderr.contains("FAILED: 4 forbidden instructions"),
        "{stderr}"
    );
}

#[test]
fn an_empty_listing_is_an_error_not_a_pass() {
    let output = gate_on("empty.dis", HEADER);
    assert_eq!(output.status.code(), Some(2));
}

/// Real `objdump -d -w` output of real machine code: assembles a few instructions with the
/// system assembler (`cc -m32`, from gcc-multilib) and checks the gate reads objdump's own
/// format, not only the synthetic listings above.
#[test]
fn reads_real_objdump_output_of_assembled_code() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let listing_of = |name: &str, asm: &str| -> String {
        let source = dir.join(format!("{name}.s"));
        let object = dir.join(format!("{name}.o"));
        std::fs::write(&source, format!(".text\n.globl {name}\n{name}:\n{asm}")).unwrap();
        let assembled = Command::new("cc")
            .args(["-m32", "-c"])
            .arg(&source)
            .arg("-o")
            .arg(&object)
            .status()
            .expect("cc starts");
        assert!(assembled.success(), "cc -m32 failed on {name}.s");
        let output = Command::new("objdump")
            .args(["-d", "-w"])
            .arg(&object)
            .output()
            .expect("objdump starts");
        assert!(output.status.success());
        String::from_utf8(output.stdout).unwrap()
    };

    let clean = listing_of("clean_fn", "  xorl %eax, %eax\n  nop\n  ret\n");
    let output = gate_on("real-clean.dis", &clean);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stdout)
    );

    let dirty = listing_of(
        "dirty_fn",
        "  cmovel %ecx, %eax\n  nopl 0(%eax,%eax,1)\n  movaps %xmm0, %xmm1\n  lfence\n  ret\n",
    );
    let output = gate_on("real-dirty.dis", &dirty);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("5 instructions scanned"), "{stdout}");
    for (what, count) in [
        ("SSE/SSE2 instruction", 1),
        ("xmm/ymm/zmm register", 1),
        ("cmovcc/fcmovcc (i686)", 1),
        ("multi-byte NOP (0f 1f / hint-NOP space)", 1),
    ] {
        let line = stdout
            .lines()
            .find(|line| line.trim_start().starts_with(what))
            .unwrap_or_else(|| panic!("no count line for {what}:\n{stdout}"));
        assert!(line.trim_end().ends_with(&format!(" {count}")), "{line}");
    }
    assert!(stdout.contains("in <dirty_fn>: cmove"), "{stdout}");
}
