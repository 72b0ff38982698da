//! The robot's body over iceoryx2: payloads, configuration, transport, the safety layer,
//! the behaviour layer (skills) and the simulated field.

pub mod behaviour;
pub mod config;
pub mod field_sim;
pub mod payloads;
pub mod planner;
pub mod referee;
pub mod safety;
pub mod scripted;
pub mod team;
pub mod transport;
