//! The two Linux syscalls the image needs, through the i386 `int 0x80` gate.

use core::arch::asm;
use core::fmt;

const SYS_EXIT: usize = 1;
const SYS_WRITE: usize = 4;

/// A file descriptor written through `write(2)`.
#[derive(Clone, Copy)]
pub struct Fd(usize);

impl Fd {
    pub const STDOUT: Fd = Fd(1);
    pub const STDERR: Fd = Fd(2);
}

impl fmt::Write for Fd {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        let mut rest = text.as_bytes();
        while !rest.is_empty() {
            let written = write(self.0, rest);
            // A negative result is -errno; zero would loop forever. Both end the write.
            let Ok(count) = usize::try_from(written) else {
                return Err(fmt::Error);
            };
            if count == 0 {
                return Err(fmt::Error);
            }
            rest = &rest[count.min(rest.len())..];
        }
        Ok(())
    }
}

/// `write(fd, bytes)`: bytes written, or `-errno`.
fn write(fd: usize, bytes: &[u8]) -> isize {
    let result: isize;
    // SAFETY: `write` reads `bytes.len()` bytes from `bytes.as_ptr()`, a live slice, and
    // touches no other memory of ours. LLVM reserves `ebx` on i386, so the fd goes in through
    // another register and is swapped into `ebx` around the trap; `ebx` is restored after.
    unsafe {
        asm!(
            "xchg {fd}, ebx",
            "int 0x80",
            "xchg {fd}, ebx",
            fd = inout(reg) fd => _,
            inlateout("eax") SYS_WRITE => result,
            in("ecx") bytes.as_ptr(),
            in("edx") bytes.len(),
            options(nostack, readonly),
        );
    }
    result
}

/// `exit(status)`: ends the process.
pub fn exit(status: usize) -> ! {
    // SAFETY: `exit` does not return and touches no memory of ours; `ebx` is handled as in
    // `write`.
    unsafe {
        asm!(
            "xchg {status}, ebx",
            "int 0x80",
            status = in(reg) status,
            in("eax") SYS_EXIT,
            options(noreturn, nostack),
        );
    }
}
