//! The freestanding runtime of the i586 image: entry point with stack painting, Linux
//! syscalls through `int 0x80`, the panic handler, and the symbols the prebuilt `core`
//! expects from libc (`mem.rs`) and from an unwinder (`rust_eh_personality`).

mod mem;
mod syscall;

use crate::{game, report, stack_paint};
use core::fmt::Write;
use core::panic::PanicInfo;

// Entry point. The kernel leaves `esp` pointing at argc. Before any Rust code runs, fill
// `PAINT_BYTES` just below that point with the paint (`rep stosl` stores `ecx` words from
// `edi` upwards), then call `image_entry(entry_sp)` on a 16-byte aligned stack as the i386
// System V ABI asks. Writing below `esp` is fine here: the stack mapping extends far below
// it (qemu-user maps the whole guest stack; Linux grows the stack VMA on demand).
core::arch::global_asm!(
    ".globl _start",
    ".type _start, @function",
    "_start:",
    "    xorl %ebp, %ebp",
    "    movl %esp, %esi",
    "    leal -{paint_bytes}(%esi), %edi",
    "    movl ${paint_words}, %ecx",
    "    movl ${paint_word}, %eax",
    "    cld",
    "    rep stosl",
    "    andl $-16, %esp",
    "    subl $12, %esp",
    "    pushl %esi",
    "    call {entry}",
    "    ud2",
    paint_bytes = const stack_paint::PAINT_BYTES,
    paint_words = const stack_paint::PAINT_WORDS,
    paint_word = const stack_paint::PAINT_WORD,
    entry = sym image_entry,
    options(att_syntax)
);

/// Rust side of `_start`: runs the report, measures the stack, exits. Never returns.
extern "C" fn image_entry(entry_sp: usize) -> ! {
    let mut out = syscall::Fd::STDOUT;
    let status = match report::run(&mut out, "i586-freestanding", game::AGENT_ENGINE.try_take()) {
        Ok(()) => 0,
        Err(report::RunError::Output) => 2,
        Err(report::RunError::SelfTest(_)) => 3,
        Err(report::RunError::EngineTaken) => 4,
        Err(report::RunError::Game(_)) => 5,
    };
    let stack = measure_stack(entry_sp);
    let written = writeln!(
        out,
        "agent-image: stack_max_bytes={} stack_painted_bytes={} stack_reached_paint_bottom={}",
        stack.max_bytes,
        stack_paint::PAINT_BYTES,
        stack.reached_paint_bottom
    );
    syscall::exit(if written.is_err() && status == 0 {
        2
    } else {
        status
    })
}

/// Reads back the paint below `entry_sp`.
fn measure_stack(entry_sp: usize) -> stack_paint::StackUse {
    let bottom = entry_sp - stack_paint::PAINT_BYTES;
    stack_paint::measure(stack_paint::PAINT_WORDS, |i| {
        // SAFETY: `[bottom, entry_sp)` was written by `_start`, so it is mapped and stays
        // mapped (the stack is never unmapped); `entry_sp` is word aligned (the kernel aligns
        // it to 16), so every address `bottom + 4 * i` with `i < PAINT_WORDS` is an aligned
        // u32 inside that range. The read is volatile because the words belong to no Rust
        // object: the compiler must neither assume nor cache their contents.
        unsafe { core::ptr::read_volatile((bottom + 4 * i) as *const u32) }
    })
}

#[panic_handler]
fn on_panic(info: &PanicInfo) -> ! {
    let mut err = syscall::Fd::STDERR;
    // Nothing more can be done if stderr is gone: the exit status still tells.
    let _ = writeln!(err, "agent-image: panic: {info}");
    syscall::exit(101)
}

/// The prebuilt `core` for this target was built with unwinding and references this symbol.
/// With `panic = "abort"` it is never called.
#[no_mangle]
pub extern "C" fn rust_eh_personality() {}
