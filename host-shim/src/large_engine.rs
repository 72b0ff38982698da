//! `LargeEngine`: pools for the big benchmark programs (Manners with 128 guests, the
//! join and negation programs at 10^5 facts), which outgrow `DefaultEngine`. Needs the
//! `wide-index` feature of agent-core (`u32` pool indices; host-shim enables it).
//! The bench's in-process engine uses it (`robotino-agent clips` runs on
//! `agent_core::grow::GrowEngine`, whose pools grow; `--large-pools` is an alias there).

agent_core::engine_storage! {
    /// The pools of [`LargeEngine`] (those not named are the host defaults): the high-water marks of the biggest benchmark programs with about half
    /// again to spare. Measured (facts, fact values, tokens, activations, expression nodes,
    /// deffacts): join-100000 133,617 / 267,233 / 769,816 / 33,618 / 700,255 / 200;
    /// negation-100000 100,002 / 250,001 / 350,003 / 6,247 / 700,256 / 200; manners-128
    /// 8,829 / 28,384 / 82,482 / 7,968 / 2,412 / 1. About 144 MiB (u32 indices; host tokens
    /// of 104 B, which keep their bindings: 1.1 M of them are 109 MiB), so it
    /// lives on the heap.
    pub struct LargeStorage {
        facts: 200_000,
        fact_values: 400_000,
        symbols: 16_384,
        symbol_bytes: 262_144,
        tokens: 1_100_000,
        activations: 131_072,
        exprs: 1_000_000,
        deffacts: 512,
        ..agent_core::Capacities::HOST
    }
}
/// The bench's in-process engine (see [`LargeStorage`]).
pub type LargeEngine = agent_core::Engine<LargeStorage>;

/// Stack for a thread that builds a [`LargeEngine`] before boxing it: room for two
/// copies (an unoptimised build moves the value), plus the usual engine stack.
pub const LARGE_ENGINE_THREAD_STACK: usize =
    2 * std::mem::size_of::<LargeEngine>() + crate::sim::game::ENGINE_THREAD_STACK;
