//! `LargeEngine`: pools for the big benchmark programs (Manners with 128 guests, the
//! join and negation programs at 10^5 facts), which outgrow `DefaultEngine`. Needs the
//! `wide-pools` feature of agent-core (`u32` pool indices; host-shim enables it).
//! `robotino-agent clips --large-pools` and the bench's in-process engine use it.

/// Capacities: the high-water marks of the biggest benchmark programs with about half
/// again to spare. Measured (facts, fact values, tokens, activations, expression nodes,
/// deffacts): join-100000 133,617 / 267,233 / 769,816 / 33,618 / 700,255 / 200;
/// negation-100000 100,002 / 250,001 / 350,003 / 6,247 / 700,256 / 200; manners-128
/// 8,829 / 28,384 / 82,482 / 7,968 / 2,412 / 1. About 144 MiB (u32 indices; host tokens
/// of 104 B, which keep their bindings: 1.1 M of them are 109 MiB), so it
/// lives on the heap.
pub type LargeEngine = agent_core::Engine<
    200_000,   // facts
    400_000,   // fact values
    16_384,    // symbols
    262_144,   // symbol bytes
    256,       // templates
    1024,      // slot definitions
    512,       // rules
    1024,      // alpha nodes
    2048,      // joins
    1_100_000, // tokens
    131_072,   // activations
    256,       // deffunctions
    128,       // globals
    1_000_000, // expression nodes
    1024,      // evaluation stack
    4096,      // multifield scratch
    512,       // deffacts
    32,        // external functions
>;

/// Stack for a thread that builds a [`LargeEngine`] before boxing it: room for two
/// copies (an unoptimised build moves the value), plus the usual engine stack.
pub const LARGE_ENGINE_THREAD_STACK: usize =
    2 * std::mem::size_of::<LargeEngine>() + crate::sim::game::ENGINE_THREAD_STACK;
