//! Pools beyond 65,535 entries: with the feature `wide-index` indices are `u32`
//! (`agent_core::Ix`), so facts, tokens, activations and expression nodes go past the
//! `u16` limit, and a full pool is still a typed error naming its real capacity.
// Invariant mode walks every pool at every operation: tens of thousands of asserts
// into pools this size would take hours, so these tests run without it.
#![cfg(all(feature = "wide-index", not(feature = "check-invariants")))]
// The `engine!` macro's default capacities are shadowed by the overrides.
#![allow(dead_code)]

use agent_core::{CapacityError, EngineError, FactId, Host, Ix, Pool, Value};

#[macro_use]
mod engine_macro;

struct Quiet;
impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

/// More entries than a `u16` index can address.
const BIG: usize = 70_000;

/// Runs `f` on a thread whose stack holds a tens-of-MiB engine while it is boxed.
fn on_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("test thread");
}

#[test]
fn the_index_type_is_wide() {
    assert_eq!(Ix::MAX, u32::MAX);
    assert_eq!(agent_core::NONE, u32::MAX);
}

/// 70,000 facts, each an alpha match, a partial match and an activation: every one
/// of those pools passes 65,535; all fire, and the last fact is still addressable.
#[test]
fn facts_tokens_and_activations_pass_65535() {
    on_big_stack(|| {
        let mut e = engine!(
            facts = BIG + 16,
            fact_values = 3 * BIG,
            tokens = 2 * BIG + 64,
            activations = BIG + 16
        );
        let h = &mut Quiet;
        e.load_str(h, "rules", "(defrule count (item ?n) => (bind ?x ?n))")
            .unwrap();
        let mut last = FactId(0);
        for i in 0..BIG {
            last = e.assert_str(h, &format!("(item {i})")).unwrap();
        }
        assert_eq!(last, FactId(BIG as u32));
        assert_eq!(e.facts().count(), BIG + 1); // and (initial-fact)
        let stats = e.stats();
        assert!(stats.get(Pool::Tokens).0 as usize >= 2 * BIG);
        assert!(stats.get(Pool::Activations).0 as usize >= BIG);
        assert_eq!(e.run(h, None).unwrap() as usize, BIG);
        e.retract(h, last).unwrap();
        assert_eq!(e.facts().count(), BIG);
        assert_eq!(
            e.assert_str(h, "(item -1)").unwrap(),
            FactId(BIG as u32 + 1)
        );
    });
}

/// A full pool larger than 65,535 reports its own capacity and leaves the engine as
/// it was.
#[test]
fn a_full_wide_pool_is_a_typed_error() {
    on_big_stack(|| {
        let mut e = engine!(facts = BIG, fact_values = 2 * BIG);
        let h = &mut Quiet;
        // (initial-fact) takes one entry
        for i in 1..BIG {
            e.assert_str(h, &format!("(item {i})")).unwrap();
        }
        let err = e.assert_str(h, "(item 0)").unwrap_err();
        let expected = CapacityError {
            pool: Pool::Facts,
            capacity: BIG as u32,
        };
        match err {
            EngineError::Capacity(c) => assert_eq!(c, expected),
            other => panic!("not a capacity error: {other:?}"),
        }
        assert_eq!(e.facts().count(), BIG);
        e.retract(h, FactId(5)).unwrap();
        assert!(e.assert_str(h, "(item 0)").is_ok());
    });
}

/// A `deffacts` of 25,000 facts compiles to more than 65,535 expression nodes (the
/// join and negation benchmarks at 10^4 and 10^5 facts need this), and `reset`
/// asserts them all with their values intact (summed by a rule).
#[test]
#[allow(non_upper_case_globals)]
fn a_deffacts_beyond_65535_expression_nodes_loads_and_resets() {
    on_big_stack(|| {
        const N: i64 = 25_000;
        const n: usize = N as usize;
        let mut e = engine!(
            facts = n + 16,
            fact_values = 4 * n,
            exprs = 8 * n,
            tokens = 2 * n + 64,
            activations = n + 16
        );
        let h = &mut Quiet;
        let mut text = String::from("(deffacts many\n");
        for i in 0..N {
            // an integer beyond 16 bits and a float: 64-bit constants round-trip
            text.push_str(&format!("  (item {} {i}.5)\n", i * 1_000_003));
        }
        text.push_str(")\n(defglobal ?*sum* = 0 ?*halves* = 0.0)\n");
        text.push_str(
            "(defrule sum (item ?n ?x) => \
               (bind ?*sum* (+ ?*sum* ?n)) (bind ?*halves* (+ ?*halves* ?x)))",
        );
        e.load_str(h, "facts", &text).unwrap();
        assert!(e.stats().get(Pool::Exprs).0 as usize > 65_535);
        e.reset(h).unwrap();
        assert_eq!(e.facts().count(), n + 1);
        assert_eq!(e.run(h, None).unwrap() as usize, n);
        let triangle = (N - 1) * N / 2;
        assert_eq!(
            e.eval_str(h, "?*sum*").unwrap(),
            Value::Int(triangle * 1_000_003)
        );
        assert_eq!(
            e.eval_str(h, "?*halves*").unwrap(),
            Value::Float(triangle as f64 + 0.5 * N as f64)
        );
    });
}
