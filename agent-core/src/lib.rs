//! A CLIPS-compatible rule and fact engine in fixed memory (`no_std`, no `alloc`).
#![no_std]
