//! The instruction-set gate: the image's disassembly (`objdump -d -w`, AT&T syntax) must
//! contain nothing the AMD Geode LX800 lacks or that strict i586 forbids:
//! - SSE/SSE2 instructions, or any `xmm`/`ymm`/`zmm` register;
//! - `cmovcc` (and x87 `fcmovcc`), i686 conditional moves;
//! - the multi-byte NOP `0f 1f` (and the rest of the `0f 19`..`0f 1f` hint-NOP space,
//!   e.g. `endbr32`). qemu does not trap these, so only the disassembly can catch them.

use std::fmt;

/// Why an instruction is forbidden.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Forbidden {
    SseInstruction,
    SseRegister,
    ConditionalMove,
    MultiByteNop,
}

impl Forbidden {
    pub const ALL: [Forbidden; 4] = [
        Forbidden::SseInstruction,
        Forbidden::SseRegister,
        Forbidden::ConditionalMove,
        Forbidden::MultiByteNop,
    ];

    pub fn describe(self) -> &'static str {
        match self {
            Forbidden::SseInstruction => "SSE/SSE2 instruction",
            Forbidden::SseRegister => "xmm/ymm/zmm register",
            Forbidden::ConditionalMove => "cmovcc/fcmovcc (i686)",
            Forbidden::MultiByteNop => "multi-byte NOP (0f 1f / hint-NOP space)",
        }
    }
}

/// Mnemonics of SSE/SSE2 instructions that need no `xmm` operand (MMX-register forms,
/// fences, MXCSR access, prefetch, non-temporal stores).
const SSE_WITHOUT_XMM: &[&str] = &[
    "ldmxcsr",
    "stmxcsr",
    "sfence",
    "lfence",
    "mfence",
    "clflush",
    "movnti",
    "maskmovq",
    "movntq",
    "pshufw",
    "pavgb",
    "pavgw",
    "pextrw",
    "pinsrw",
    "pmaxsw",
    "pmaxub",
    "pminsw",
    "pminub",
    "pmovmskb",
    "pmulhuw",
    "psadbw",
    "prefetchnta",
    "prefetcht0",
    "prefetcht1",
    "prefetcht2",
    "paddq",
    "psubq",
    "pmuludq",
    "movdq2q",
    "movq2dq",
    "cvtpi2ps",
    "cvtps2pi",
    "cvttps2pi",
    "cvtpi2pd",
    "cvtpd2pi",
    "cvttpd2pi",
];

/// Prefix bytes that may precede an opcode (operand/address size, segments, lock, rep).
const PREFIXES: &[&str] = &[
    "66", "67", "f2", "f3", "2e", "36", "3e", "26", "64", "65", "f0",
];

/// Prefix words objdump prints before a mnemonic.
const PREFIX_WORDS: &[&str] = &[
    "lock", "rep", "repz", "repe", "repnz", "repne", "data16", "data32", "addr16", "addr32", "cs",
    "ds", "es", "ss", "fs", "gs", "bnd", "notrack",
];

/// One forbidden instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Finding {
    pub reasons: Vec<Forbidden>,
    pub address: String,
    pub function: String,
    pub bytes: String,
    pub text: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let reasons: Vec<_> = self.reasons.iter().map(|r| r.describe()).collect();
        write!(
            f,
            "{} in <{}>: {}  [{}]  ({})",
            self.address,
            self.function,
            self.text,
            self.bytes,
            reasons.join(", ")
        )
    }
}

/// The result of scanning a disassembly.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Scan {
    pub instructions: usize,
    pub findings: Vec<Finding>,
}

impl Scan {
    pub fn count(&self, reason: Forbidden) -> usize {
        self.findings
            .iter()
            .filter(|f| f.reasons.contains(&reason))
            .count()
    }
}

/// Scans `objdump -d -w` output. Lines that are not instructions (headers, symbol labels,
/// byte-only continuation lines of a non-wide listing) are skipped; labels name the
/// function of later findings.
pub fn scan(disassembly: &str) -> Scan {
    let mut result = Scan::default();
    let mut function = String::from("?");
    for line in disassembly.lines() {
        if let Some(label) = symbol_label(line) {
            function = label.to_owned();
            continue;
        }
        let Some(insn) = parse_instruction(line) else {
            continue;
        };
        result.instructions += 1;
        let reasons = classify(&insn);
        if !reasons.is_empty() {
            result.findings.push(Finding {
                reasons,
                address: insn.address.to_owned(),
                function: function.clone(),
                bytes: insn.bytes.to_owned(),
                text: insn.text.to_owned(),
            });
        }
    }
    result
}

struct Instruction<'a> {
    address: &'a str,
    bytes: &'a str,
    text: &'a str,
}

/// `00401000 <_start>:` -> `_start`.
fn symbol_label(line: &str) -> Option<&str> {
    let (address, rest) = line.split_once(' ')?;
    if !is_hex(address) {
        return None;
    }
    rest.strip_prefix('<')?.strip_suffix(">:")
}

/// `  401000:\t0f 1f 40 00 \tnopl   0x0(%eax)` -> address, bytes, text.
fn parse_instruction(line: &str) -> Option<Instruction<'_>> {
    let mut fields = line.split('\t');
    let address = fields.next()?.trim().strip_suffix(':')?;
    if !is_hex(address) {
        return None;
    }
    let bytes = fields.next()?.trim();
    let text = fields.next()?.trim();
    if text.is_empty() {
        return None;
    }
    Some(Instruction {
        address,
        bytes,
        text,
    })
}

fn is_hex(word: &str) -> bool {
    !word.is_empty() && word.chars().all(|c| c.is_ascii_hexdigit())
}

fn classify(insn: &Instruction<'_>) -> Vec<Forbidden> {
    let mnemonic = mnemonic(insn.text);
    let mut reasons = Vec::new();
    if SSE_WITHOUT_XMM.contains(&mnemonic) {
        reasons.push(Forbidden::SseInstruction);
    }
    if names_vector_register(insn.text) {
        reasons.push(Forbidden::SseRegister);
    }
    if mnemonic.starts_with("cmov") || mnemonic.starts_with("fcmov") {
        reasons.push(Forbidden::ConditionalMove);
    }
    if in_hint_nop_space(insn.bytes) || mnemonic == "nopl" || mnemonic == "nopw" {
        reasons.push(Forbidden::MultiByteNop);
    }
    reasons
}

/// The mnemonic after any prefix words (`lock`, `rep`, `data16`, `cs` ...).
fn mnemonic(text: &str) -> &str {
    text.split_whitespace()
        .find(|word| !PREFIX_WORDS.contains(word))
        .unwrap_or("")
}

/// `xmm0`..`xmm31`, `ymm..`, `zmm..` anywhere in the instruction text.
fn names_vector_register(text: &str) -> bool {
    ["xmm", "ymm", "zmm"].iter().any(|reg| {
        text.match_indices(reg).any(|(at, _)| {
            text[at + reg.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit())
        })
    })
}

/// Opcode `0f 19`..`0f 1f` after any prefixes: the P6 hint-NOP space (`nopl`, `nopw`,
/// `endbr32`...), which the i586 and the LX800 do not decode.
fn in_hint_nop_space(bytes: &str) -> bool {
    let mut opcode = bytes
        .split_whitespace()
        .skip_while(|byte| PREFIXES.contains(byte));
    opcode.next() == Some("0f")
        && opcode
            .next()
            .and_then(|b| u8::from_str_radix(b, 16).ok())
            .is_some_and(|b| (0x19..=0x1f).contains(&b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A listing in the shape `objdump -d -w` prints for a 32-bit ELF file.
    const CLEAN: &str = "
/tmp/agent-image:     file format elf32-i386


Disassembly of section .text:

00401000 <_start>:
  401000:\t31 ed                \txor    %ebp,%ebp
  401002:\t89 e6                \tmov    %esp,%esi
  401004:\tf3 ab                \trep stos %eax,%es:(%edi)
  401006:\t90                   \tnop
  401007:\t66 90                \txchg   %ax,%ax
  401009:\t0f 0b                \tud2

00401010 <memcpy>:
  401010:\tf0 0f b1 0a          \tlock cmpxchg %ecx,(%edx)
  401014:\t0f 6f c1             \tmovq   %mm1,%mm0
  401017:\tc3                   \tret
";

    #[test]
    fn a_clean_listing_passes_and_every_instruction_is_counted() {
        let scan = scan(CLEAN);
        assert_eq!(scan.instructions, 9);
        assert_eq!(scan.findings, vec![]);
    }

    fn findings_of(line: &str) -> Vec<Forbidden> {
        let listing = format!("00401000 <f>:\n{line}\n");
        let scan = scan(&listing);
        assert_eq!(scan.instructions, 1, "not parsed as an instruction: {line}");
        scan.findings
            .first()
            .map(|f| f.reasons.clone())
            .unwrap_or_default()
    }

    #[test]
    fn catches_xmm_registers_and_sse_instructions_without_them() {
        assert_eq!(
            findings_of("  401000:\t0f 28 c1 \tmovaps %xmm1,%xmm0"),
            [Forbidden::SseRegister]
        );
        assert_eq!(
            findings_of("  401000:\tf2 0f 10 44 24 04 \tmovsd  0x4(%esp),%xmm0"),
            [Forbidden::SseRegister]
        );
        assert_eq!(
            findings_of("  401000:\t0f ae 54 24 04 \tldmxcsr 0x4(%esp)"),
            [Forbidden::SseInstruction]
        );
        assert_eq!(
            findings_of("  401000:\t0f ae f0 \tmfence"),
            [Forbidden::SseInstruction]
        );
        assert_eq!(
            findings_of("  401000:\t0f d4 c1 \tpaddq  %mm1,%mm0"),
            [Forbidden::SseInstruction]
        );
        assert_eq!(
            findings_of("  401000:\tc5 fc 28 c1 \tvmovaps %ymm1,%ymm0"),
            [Forbidden::SseRegister]
        );
    }

    #[test]
    fn catches_conditional_moves() {
        assert_eq!(
            findings_of("  401000:\t0f 44 c1 \tcmove  %ecx,%eax"),
            [Forbidden::ConditionalMove]
        );
        assert_eq!(
            findings_of("  401000:\t0f 4f 45 08 \tcmovg  0x8(%ebp),%eax"),
            [Forbidden::ConditionalMove]
        );
        assert_eq!(
            findings_of("  401000:\tda c1 \tfcmovb %st(1),%st"),
            [Forbidden::ConditionalMove]
        );
    }

    #[test]
    fn catches_multi_byte_nops_behind_prefixes() {
        for line in [
            "  401000:\t0f 1f 00 \tnopl   (%eax)",
            "  401000:\t0f 1f 44 00 00 \tnopl   0x0(%eax,%eax,1)",
            "  401000:\t66 0f 1f 44 00 00 \tnopw   0x0(%eax,%eax,1)",
            "  401000:\t66 2e 0f 1f 84 00 00 00 00 00 \tcs nopw 0x0(%eax,%eax,1)",
            "  401000:\t66 66 2e 0f 1f 84 00 00 00 00 00 \tdata16 cs nopw 0x0(%eax,%eax,1)",
            "  401000:\tf3 0f 1e fb \tendbr32",
        ] {
            assert_eq!(findings_of(line), [Forbidden::MultiByteNop], "{line}");
        }
    }

    #[test]
    fn look_alikes_are_not_flagged() {
        // `cmp`, one-byte `nop`, MMX on mm registers, x87 `fcom`, a call to a function
        // whose name contains "xmm_", an immediate holding the bytes 0f 1f, and a `bnd`
        // prefixed return.
        for line in [
            "  401000:\t39 c8 \tcmp    %ecx,%eax",
            "  401000:\t90 \tnop",
            "  401000:\t0f fc c1 \tpaddb  %mm1,%mm0",
            "  401000:\td8 d1 \tfcom   %st(1)",
            "  401000:\te8 00 00 00 00 \tcall   401005 <xmm_helper>",
            "  401000:\tb8 0f 1f 00 00 \tmov    $0x1f0f,%eax",
            "  401000:\tf2 c3 \tbnd ret",
        ] {
            assert_eq!(findings_of(line), [], "{line}");
        }
    }

    #[test]
    fn findings_name_address_function_and_reason() {
        let listing = "00401234 <agent_step>:\n  401240:\t0f 44 c1 \tcmove  %ecx,%eax\n";
        let scan = scan(listing);
        assert_eq!(scan.count(Forbidden::ConditionalMove), 1);
        let text = scan.findings[0].to_string();
        assert!(text.contains("401240 in <agent_step>: cmove"), "{text}");
        assert!(text.contains("cmovcc"), "{text}");
    }

    #[test]
    fn byte_only_continuation_lines_are_not_instructions() {
        let listing = "00401000 <f>:\n  401000:\t66 2e 0f 1f 84 00 00 \tcs nopw 0x0(%eax,%eax,1)\n  401007:\t00 00 00 \n";
        let scan = scan(listing);
        assert_eq!(scan.instructions, 1);
        assert_eq!(scan.count(Forbidden::MultiByteNop), 1);
    }
}
