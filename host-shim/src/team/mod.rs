//! The team's coordination as the rule base does it (`rules/team.clp`): one engine per
//! robot, messages between them carried by the host. [`member`] drives one robot's
//! engine (clock, messages in and out, wants, holds); [`net`] is the message-level fault
//! proxy (loss, delay, duplication in game time) the tests and the simulations put
//! between robots; [`link`] is how `robotino-agent run` carries them between processes. The `team-link` crate (its own workspace, `team-link/`) carries them
//! over Zenoh between processes and machines.

pub mod link;
pub mod member;
pub mod net;

pub use link::{FaultyLink, LinkError, TeamLink};
pub use member::{TeamError, TeamMember, TeamMsg};
pub use net::{FaultyNet, LinkFaults};
