//! The LLSF agent rule base, embedded as CLIPS text (`no_std`).
#![no_std]
