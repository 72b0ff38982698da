//! The robot's body over iceoryx2: payloads, configuration, transport, the safety layer,
//! the behaviour layer (skills), the agent's rule engine and the simulated field with the
//! CLIPS referee.

pub mod agent;
pub mod behaviour;
pub mod bump;
pub mod config;
pub mod drivers;
pub mod field_sim;
pub mod lockstep;
pub mod payloads;
pub mod planner;
pub mod referee;
pub mod rule_engine;
pub mod safety;
pub mod team;
pub mod traffic;
pub mod transport;
