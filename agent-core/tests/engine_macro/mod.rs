//! `engine!`: a boxed engine with roomy pools except the ones a test shrinks, shared
//! by the capacity and exhaustion tests. Pools are named as in `agent_core::Capacities`.

use agent_core::Capacities;

/// The pools a test does not shrink: [`Capacities::SMALL`] with room for 64 facts of
/// 8 fields.
pub const ROOMY: Capacities = Capacities {
    facts: 64,
    fact_values: 512,
    ..Capacities::SMALL
};

/// Engine with all pools roomy ([`ROOMY`]) except the ones a test shrinks, by name:
/// `engine!(tokens = 40, fact_values = 28)`.
macro_rules! engine {
    ($($name:ident = $v:expr),*) => {{
        agent_core::engine_storage! {
            struct TestStorage { $($name: $v,)* ..crate::engine_macro::ROOMY }
        }
        Box::new(agent_core::Engine::with_storage(TestStorage::new()))
    }};
}
