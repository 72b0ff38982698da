//! Capacity tests: fill every pool; the error names it and its capacity; the failed
//! operation leaves the engine as it was, and the engine keeps working.
// The `engine!` macro's default capacities are shadowed by the overrides.
#![allow(dead_code)]

use agent_core::{CapacityError, Engine, EngineError, EvalErrorKind, FactId, Host, Pool};

struct Quiet;
impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

#[macro_use]
mod engine_macro;

fn cap_of(e: EngineError) -> CapacityError {
    match e {
        EngineError::Capacity(c) => c,
        EngineError::Load(l) => l.capacity.expect("a capacity error"),
        EngineError::Eval(v) => match v.kind() {
            EvalErrorKind::Capacity(c) => c,
            k => panic!("not a capacity error: {k:?}"),
        },
        other => panic!("not a capacity error: {other:?}"),
    }
}

#[test]
fn facts_pool() {
    let mut e = engine!(facts = 4);
    let h = &mut Quiet;
    for i in 1..4 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
    }
    let before: Vec<FactId> = e.facts().collect();
    let err = cap_of(e.assert_str(h, "(a 99)").unwrap_err());
    assert_eq!(
        err,
        CapacityError {
            pool: Pool::Facts,
            capacity: 4
        }
    );
    assert_eq!(e.facts().collect::<Vec<_>>(), before);
    e.retract(h, FactId(1)).unwrap();
    assert_eq!(e.assert_str(h, "(a 99)").unwrap(), FactId(4));
}

#[test]
fn fact_values_pool() {
    let mut e = engine!(fact_values = 24);
    let h = &mut Quiet;
    e.assert_str(h, "(big 1 2 3 4 5 6 7 8 9 10)").unwrap();
    let err = cap_of(
        e.assert_str(h, "(big 11 12 13 14 15 16 17 18 19 20 21 22 23)")
            .unwrap_err(),
    );
    assert_eq!(err.pool, Pool::FactValues);
    assert_eq!(err.capacity, 24);
    assert_eq!(e.facts().count(), 2);
    // retract frees cells (after compaction) for a new fact
    e.retract(h, FactId(1)).unwrap();
    e.assert_str(h, "(big 11 12 13 14 15 16 17 18 19 20 21 22 23)")
        .unwrap();
}

#[test]
fn symbols_pool() {
    let mut e = engine!(symbols = 16);
    let h = &mut Quiet;
    let mut failed = None;
    for i in 0..20 {
        if let Err(err) = e.assert_str(h, &format!("(s sym{i})")) {
            failed = Some(cap_of(err));
            break;
        }
    }
    assert_eq!(
        failed,
        Some(CapacityError {
            pool: Pool::Symbols,
            capacity: 16
        })
    );
    // known symbols still work
    assert!(e.assert_str(h, "(s sym0 sym1)").is_ok());
}

#[test]
fn symbol_bytes_pool() {
    let mut e = engine!(symbol_bytes = 96);
    let h = &mut Quiet;
    let long = "x".repeat(80);
    let err = cap_of(e.assert_str(h, &format!("(s {long})")).unwrap_err());
    assert_eq!(
        err,
        CapacityError {
            pool: Pool::SymbolBytes,
            capacity: 96
        }
    );
    assert!(e.assert_str(h, "(s short)").is_ok());
}

#[test]
fn templates_and_slot_defs_pools() {
    let mut e = engine!(templates = 3);
    let h = &mut Quiet;
    e.load_str(h, "t", "(deftemplate one (slot a))").unwrap();
    let before = e.usage();
    let err = e
        .load_str(
            h,
            "t",
            "(deftemplate two (slot a)) (deftemplate three (slot b))",
        )
        .unwrap_err();
    assert_eq!(err.capacity.map(|c| c.pool), Some(Pool::Templates));
    // `two` fitted and stays; `three` left nothing
    assert_eq!(e.usage().templates, before.templates + 1);
    e.assert_str(h, "(two (a 1))").unwrap();

    let mut e = engine!(slot_defs = 4);
    e.load_str(h, "t", "(deftemplate one (slot a) (slot b))")
        .unwrap();
    let before = e.usage();
    let err = e
        .load_str(h, "t", "(deftemplate two (slot a) (slot b) (slot c))")
        .unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::SlotDefs,
            capacity: 4
        })
    );
    assert_eq!(e.usage(), before);
    e.assert_str(h, "(one (a 1))").unwrap();
}

#[test]
fn rules_alpha_and_joins_pools() {
    let h = &mut Quiet;
    let mut e = engine!(rules = 2);
    e.load_str(h, "t", "(defrule r1 (a) =>) (defrule r2 (b) =>)")
        .unwrap();
    let before = e.usage();
    let err = e.load_str(h, "t", "(defrule r3 (c) =>)").unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::Rules,
            capacity: 2
        })
    );
    assert_eq!(e.usage(), before);
    e.assert_str(h, "(a)").unwrap();
    assert_eq!(e.counts().1, 1);

    let mut e = engine!(alpha_nodes = 2);
    e.load_str(h, "t", "(defrule r1 (a 1) (a 2) =>)").unwrap();
    let before = e.usage();
    let err = e.load_str(h, "t", "(defrule r2 (a 3) =>)").unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::AlphaNodes,
            capacity: 2
        })
    );
    assert_eq!(e.usage(), before);

    // join 0 is the global root; r1 takes 3 (2 CEs + its end node)
    let mut e = engine!(joins = 5);
    e.load_str(h, "t", "(defrule r1 (a ?x) (b ?x) =>)").unwrap();
    let before = e.usage();
    let err = e
        .load_str(h, "t", "(defrule r2 (c ?x) (d ?x) =>)")
        .unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::Joins,
            capacity: 5
        })
    );
    assert_eq!(e.usage(), before);
    e.assert_str(h, "(a 1)").unwrap();
    e.assert_str(h, "(b 1)").unwrap();
    assert_eq!(e.counts().1, 1);
}

#[test]
fn tokens_pool_assert_is_undone() {
    let h = &mut Quiet;
    let mut e = engine!(tokens = 24);
    e.load_str(
        h,
        "t",
        "(defrule cross (a ?x) (b ?y) => ) (defrule lonely (a ?x) (not (c ?x)) =>)",
    )
    .unwrap();
    let mut failed = None;
    for i in 0..20 {
        let before_facts: Vec<FactId> = e.facts().collect();
        let before_agenda = agenda(&e);
        let before_tokens = e.usage().tokens;
        let fact = if i % 2 == 0 {
            format!("(a {i})")
        } else {
            format!("(b {i})")
        };
        match e.assert_str(h, &fact) {
            Ok(_) => {}
            Err(err) => {
                failed = Some(cap_of(err));
                assert_eq!(e.facts().collect::<Vec<_>>(), before_facts);
                assert_eq!(agenda(&e), before_agenda);
                assert_eq!(e.usage().tokens, before_tokens);
                break;
            }
        }
    }
    assert_eq!(
        failed,
        Some(CapacityError {
            pool: Pool::Tokens,
            capacity: 24
        })
    );
    // still works: free some room, then match again
    let first = e.facts().nth(1).unwrap();
    e.retract(h, first).unwrap();
    e.assert_str(h, "(c 0)").unwrap();
    assert!(e.run(h, None).unwrap() > 0);
}

fn agenda<S: agent_core::Storage>(e: &Engine<S>) -> Vec<String> {
    let mut v = Vec::new();
    e.for_each_activation(|r, s, b| v.push(format!("{s} {r} {b:?}")));
    v
}

#[test]
fn activations_pool() {
    let h = &mut Quiet;
    let mut e = engine!(activations = 3);
    e.load_str(h, "t", "(defrule r (a ?x) =>)").unwrap();
    for i in 0..3 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
    }
    let before = agenda(&e);
    let err = cap_of(e.assert_str(h, "(a 3)").unwrap_err());
    assert_eq!(
        err,
        CapacityError {
            pool: Pool::Activations,
            capacity: 3
        }
    );
    assert_eq!(agenda(&e), before);
    assert_eq!(e.run(h, Some(1)).unwrap(), 1);
    e.assert_str(h, "(a 3)").unwrap();
}

#[cfg(feature = "parser")]
#[test]
fn functions_globals_deffacts_pools() {
    let h = &mut Quiet;
    let mut e = engine!(functions = 1);
    e.load_str(h, "t", "(deffunction f (?x) (* ?x 2))").unwrap();
    let before = e.usage();
    let err = e.load_str(h, "t", "(deffunction g (?x) ?x)").unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::Functions,
            capacity: 1
        })
    );
    assert_eq!(e.usage(), before);
    assert_eq!(e.eval_str(h, "(f 21)").unwrap(), agent_core::Value::Int(42));

    let mut e = engine!(globals = 1);
    e.load_str(h, "t", "(defglobal ?*a* = 1)").unwrap();
    let err = e.load_str(h, "t", "(defglobal ?*b* = 2)").unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::Globals,
            capacity: 1
        })
    );
    assert_eq!(e.eval_str(h, "?*a*").unwrap(), agent_core::Value::Int(1));

    let mut e = engine!(deffacts = 1);
    e.load_str(h, "t", "(deffacts one (x 1))").unwrap();
    let err = e.load_str(h, "t", "(deffacts two (x 2))").unwrap_err();
    assert_eq!(
        err.capacity,
        Some(CapacityError {
            pool: Pool::Deffacts,
            capacity: 1
        })
    );
    e.reset(h).unwrap();
    assert_eq!(e.facts().count(), 2);
}

#[test]
fn exprs_pool() {
    let h = &mut Quiet;
    let mut e = engine!(exprs = 40);
    e.load_str(h, "t", "(defrule r (a ?x) => (printout t ?x crlf))")
        .unwrap();
    let before = e.usage();
    let big = "(defrule big (b ?x) => (printout t (+ ?x 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30) crlf))";
    let err = e.load_str(h, "t", big).unwrap_err();
    assert_eq!(err.capacity.map(|c| c.pool), Some(Pool::Exprs));
    assert_eq!(e.usage(), before);
    e.assert_str(h, "(a 1)").unwrap();
    assert_eq!(e.run(h, None).unwrap(), 1);
}

#[cfg(feature = "parser")]
#[test]
fn eval_stack_and_scratch_pools() {
    let h = &mut Quiet;
    let mut e = engine!(eval_stack = 8);
    let err = e.eval_str(h, "(+ 1 2 3 4 5 6 7 8 9 10)").unwrap_err();
    assert_eq!(
        err.kind(),
        EvalErrorKind::Capacity(CapacityError {
            pool: Pool::EvalStack,
            capacity: 8
        })
    );
    assert_eq!(
        e.eval_str(h, "(+ 1 2 3)").unwrap(),
        agent_core::Value::Int(6)
    );

    let mut e = engine!(scratch = 8);
    e.load_str(
        h,
        "t",
        "(deffunction many () (bind ?x a b c d e f g h i j k) ?x)",
    )
    .unwrap();
    let err = e.eval_str(h, "(many)").unwrap_err();
    assert_eq!(
        err.kind(),
        EvalErrorKind::Capacity(CapacityError {
            pool: Pool::Scratch,
            capacity: 8
        })
    );
    assert!(e.eval_str(h, "(+ 1 2)").is_ok());
}

#[test]
fn external_functions_pool() {
    fn one(
        _call: &mut agent_core::HostCall<'_, '_>,
    ) -> Result<agent_core::Value, agent_core::EvalError> {
        Ok(agent_core::Value::Int(1))
    }
    let h = &mut Quiet;
    let mut e = engine!(external_fns = 1);
    e.register_function("one", 0, Some(0), one).unwrap();
    let err = cap_of(e.register_function("two", 0, Some(0), one).unwrap_err());
    assert_eq!(
        err,
        CapacityError {
            pool: Pool::ExternalFns,
            capacity: 1
        }
    );
    assert_eq!(e.eval_str(h, "(one)").unwrap(), agent_core::Value::Int(1));
}

#[test]
fn stats_report_high_water_marks() {
    let h = &mut Quiet;
    let mut e = engine!();
    e.load_str(h, "t", "(defrule r (a ?x) =>)").unwrap();
    for i in 0..5 {
        e.assert_str(h, &format!("(a {i})")).unwrap();
    }
    let s = e.stats();
    assert_eq!(s.get(Pool::Facts).1, 64);
    assert!(s.get(Pool::Facts).0 >= 6);
    assert!(s.get(Pool::Activations).0 >= 5);
    assert!(s.get(Pool::Tokens).0 >= 10);
}

/// `reset` builds each deffacts fact's values in the scratch area and frees them once
/// the fact is asserted: a deffacts larger than the scratch area resets.
#[test]
fn deffacts_larger_than_the_scratch_area_reset() {
    let mut e = engine!(scratch = 16, facts = 256, fact_values = 1024);
    let h = &mut Quiet;
    let facts: String = (0..200).map(|i| format!("(item {i} x)\n")).collect();
    e.load_str(h, "f", &format!("(deffacts many {facts})"))
        .unwrap();
    e.reset(h).unwrap();
    assert_eq!(e.facts().count(), 201);
}
