//! Hardware abstraction for the Festo Robotino (`no_std`).
#![no_std]
