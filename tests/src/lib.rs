//! Workspace-level tools and tests: the memory-footprint gate and the instruction-set gate
//! for the agent image (rules/image, package `agent-image`).
//!
//! - `footprint` (bin): builds the image for i586 in profile `image`, measures code, RAM
//!   (sections + stack high-water mark from a run under `qemu-i386 -cpu pentium`), the
//!   engine arena's share and heap, and checks them against `footprint-budget.toml`.
//! - `isa-gate` (bin): disassembles the image and rejects SSE, `xmm`, `cmovcc` and `0f 1f`,
//!   and rejects an image that carries the lexer, the parser or float parsing (`contents`).

pub mod budget;
pub mod contents;
pub mod footprint;
pub mod image;
pub mod isa;
pub mod report;
