extern crate std;
use super::*;
use crate::SmallEngine;
use std::string::String;

#[test]
fn writes_every_construct_pool() {
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut host = crate::NullHost;
    e.load_str(
        &mut host,
        "t",
        "(deftemplate p (slot x (default 1))) (defglobal ?*g* = 2.5) \
         (deffunction f (?a) (+ ?a 1)) (deffacts d (p (x 3))) \
         (defrule r (p (x ?x&:(> ?x 0))) (not (q)) => (printout t (f ?x) crlf))",
    )
    .unwrap();
    let mut out = String::new();
    e.write_compiled("demo", "demo.clp", &mut out).unwrap();
    assert!(out.starts_with("/// Rule base `demo.clp`"), "{out}");
    assert!(out.contains("pub mod demo {"));
    assert!(out.contains("builtin_id(\">\")"));
    assert!(out.contains("builtin_id(\"printout\")"));
    assert!(out.contains("\"initial-fact\","));
    assert!(out.contains("JoinKind::Negative"));
    assert!(out.contains("Value::Float(f64::from_bits(0x4004000000000000))"));
    // working memory is not written
    assert!(!out.contains("mem: 0") && !out.contains("nfacts"));
}

#[cfg(feature = "parser")]
#[test]
fn refuses_facts_left_by_parsing_and_bad_names() {
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut host = crate::NullHost;
    e.load_str(
        &mut host,
        "t",
        "(defglobal ?*g* = (assert (made-while-parsing)))",
    )
    .unwrap();
    let mut out = String::new();
    assert_eq!(
        e.write_compiled("m", "t", &mut out),
        Err(WriteError::FactsLeft)
    );
    let mut fresh = std::boxed::Box::new(SmallEngine::new());
    assert_eq!(
        fresh.write_compiled("Not-ident", "t", &mut out),
        Err(WriteError::BadName)
    );
}

#[cfg(feature = "logical")]
#[test]
fn refuses_logical_rules() {
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut host = crate::NullHost;
    e.load_str(&mut host, "t", "(defrule r (logical (a)) => (assert (b)))")
        .unwrap();
    let mut out = String::new();
    assert_eq!(
        e.write_compiled("m", "t", &mut out),
        Err(WriteError::Logical)
    );
    // once the rule is gone the rest is written
    e.load_str(&mut host, "t", "(defrule r (a) => (assert (b)))")
        .unwrap();
    assert_eq!(e.write_compiled("m", "t", &mut out), Ok(()));
}

/// What an engine with `grow` takes past the image's fixed limits is refused, naming
/// the limit: a rule of 33 CEs (32 are written), a string built past 2048 bytes, a
/// string literal past 1024.
#[cfg(all(feature = "grow", feature = "parser"))]
#[test]
fn refuses_what_went_past_the_images_limits() {
    // (the engine is built on the stack before it is boxed, in unoptimised builds)
    let written = |text: &str| {
        let text = String::from(text);
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn(move || {
                let mut e = std::boxed::Box::new(crate::DefaultEngine::new());
                e.load_str(&mut crate::NullHost, "t", &text).unwrap();
                e.write_compiled("m", "t", &mut String::new())
            })
            .unwrap()
            .join()
            .unwrap()
    };
    let rule = |n: usize| {
        let lhs: String = (0..n).map(|i| std::format!("(c {i} ?v{i}) ")).collect();
        std::format!("(defrule r {lhs} => (printout t ?v0 crlf))")
    };
    assert_eq!(written(&rule(32)), Ok(()));
    assert!(
        matches!(written(&rule(33)), Err(WriteError::PastImageLimit(w)) if w.contains("32 conditional")),
        "{:?}",
        written(&rule(33))
    );
    let long = "x".repeat(1100);
    assert_eq!(
        written(&std::format!("(defglobal ?*g* = \"{long}\")")).map_err(|_| ()),
        Err(())
    );
    assert_eq!(written(&std::format!("(defglobal ?*g* = (str-cat {long} {long}))"))
        .map_err(|e| std::format!("{e}")), Err(String::from(
        "a string built longer than 2048 bytes (the image's limit): compiled rule bases keep the image's fixed limits")));
    let short = "x".repeat(1000);
    assert_eq!(
        written(&std::format!(
            "(defglobal ?*g* = (str-cat \"{short}\" {short}))"
        )),
        Ok(())
    );
}

#[test]
fn loader_refuses_an_engine_with_constructs() {
    static EMPTY: RuleBase = RuleBase {
        name: "empty",
        symbols: &[],
        symbol_buckets: &[],
        symbol_next: &[],
        templates: &[],
        slots: &[],
        rules: &[],
        alphas: &[],
        joins: &[],
        exprs: &[],
        functions: &[],
        globals: &[],
        function_texts: &[],
        function_order: &[],
        global_texts: &[],
        slot_facets: &[],
        deffacts: &[],
        externals: &[],
        trie_ids: 0,
        gensym_next: 1,
        code: &[],
    };
    let mut e = std::boxed::Box::new(SmallEngine::new());
    let mut host = crate::NullHost;
    e.load_str(&mut host, "t", "(defrule r (a) =>)").unwrap();
    assert_eq!(
        e.load_compiled(&mut host, &EMPTY),
        Err(CompiledError::NotFresh)
    );
    let mut fresh = std::boxed::Box::new(SmallEngine::new());
    assert_eq!(
        fresh.load_compiled(&mut host, &EMPTY),
        Err(CompiledError::TemplateMismatch)
    );
}

#[test]
fn facts_built_through_the_api_are_the_parsed_ones() {
    use crate::ValueRef::{Float, Int, Symbol};
    let rules = "(deftemplate m (slot name) (slot kind (default T1)) (multislot xs)) \
                 (deftemplate need (slot id (default ?NONE)))";
    let mut host = crate::NullHost;
    let mut parsed = std::boxed::Box::new(SmallEngine::new());
    let mut built = std::boxed::Box::new(SmallEngine::new());
    for e in [&mut parsed, &mut built] {
        e.load_str(&mut host, "t", rules).unwrap();
    }
    parsed
        .assert_str(&mut host, "(m (name M1) (xs 1 2.5 a))")
        .unwrap();
    parsed.assert_str(&mut host, "(supply 4 D2)").unwrap();
    built
        .assert_fact(
            &mut host,
            "m",
            &[
                ("name", &[Symbol("M1")]),
                ("xs", &[Int(1), Float(2.5), Symbol("a")]),
            ],
        )
        .unwrap();
    built
        .assert_fact(&mut host, "supply", &[("", &[Int(4), Symbol("D2")])])
        .unwrap();
    let facts = |e: &mut SmallEngine| {
        let mut out = crate::testutil::CaptureHost::default();
        e.exec_command(&mut out, "(facts)", "t");
        out.out
    };
    assert_eq!(facts(&mut parsed), facts(&mut built));
    // refused before anything changes
    let symbols = built.usage().symbols;
    for bad in [
        built.assert_fact(&mut host, "m", &[("nope", &[Int(1)])]),
        built.assert_fact(&mut host, "m", &[("name", &[Int(1), Int(2)])]),
        built.assert_fact(&mut host, "need", &[]),
        built.assert_fact(&mut host, "supply", &[("x", &[Int(1)]), ("y", &[])]),
    ] {
        assert!(matches!(bad, Err(crate::EngineError::Load(_))), "{bad:?}");
    }
    assert_eq!(built.usage().symbols, symbols);
    assert_eq!(
        built.assert_fact(&mut host, "supply", &[("", &[Int(4), Symbol("D2")])]),
        Err(crate::EngineError::Duplicate)
    );
}

#[cfg(feature = "parser")]
#[test]
fn a_rule_base_brings_the_code_of_the_builtins_it_calls_only() {
    use crate::builtins::{builtin_id, code_for, Imp, BUILTINS, NOT_LINKED};
    let same = |a: Imp, b: Imp| match (a, b) {
        (Imp::Eager(f), Imp::Eager(g)) => f as usize == g as usize,
        (Imp::Lazy(f), Imp::Lazy(g)) => f as usize == g as usize,
        _ => false,
    };
    let plus = builtin_id("+");
    let printout = builtin_id("printout");
    let code = code_for(&[plus, printout]);
    assert_eq!(code.len(), BUILTINS.len());
    for (id, imp) in code.iter().enumerate() {
        if id == plus as usize || id == printout as usize {
            assert!(same(*imp, BUILTINS[id].imp), "{}", BUILTINS[id].name);
        } else {
            assert!(same(*imp, NOT_LINKED), "{}", BUILTINS[id].name);
        }
    }
}
