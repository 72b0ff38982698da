//! Library part of `host-shim`, shared by the `robotino-agent` and `robotino-sim` binaries and
//! by the integration tests.

pub mod agent_loop;
pub mod shim;
pub mod team;
