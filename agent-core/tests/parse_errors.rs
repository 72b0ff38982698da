//! Parse-error tests: malformed programs give line, column and what was expected; the
//! constructs before the bad one stay; the bad one leaves nothing behind.

use agent_core::{Host, SmallEngine};

struct Quiet;
impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

/// A good prefix every case starts with (defines templates and a rule).
const GOOD: &str = "(deftemplate good (slot a))\n(defrule keep (good (a ?x)) => (printout t ?x crlf))\n(deftemplate req (slot id (default ?NONE)))\n";

/// (bad construct text, 1-based line, column — relative to the bad text, which
/// follows GOOD's two lines — and a fragment of what was expected)
const CASES: &[(&str, u32, u32, &str)] = &[
    ("(defrule r1 (a ?x) => (printout t ?x crlf)", 1, 43, "')'"),
    ("(defrule r2 (a ?x) =>\n  (foo ?x))", 2, 4, "known function"),
    ("(defrule r3 (a \"unterminated) => )", 1, 16, ""),
    ("(defrule)", 1, 9, "defrule name"),
    ("(deftemplate)", 1, 13, "deftemplate name"),
    ("(deftemplate t1 (slot))", 1, 22, "slot name"),
    (
        "(deftemplate t2 (slot a) (slot a))",
        1,
        32,
        "not used before",
    ),
    ("(deftemplate t3 (slt a))", 1, 18, "slot or multislot"),
    ("(deftemplate t4 (slot a (type FOO)))", 1, 31, "type name"),
    (
        "(deftemplate t5 (slot a (colour red)))",
        1,
        26,
        "slot attribute",
    ),
    (
        "(deftemplate t6 (slot a (default 1 2)))",
        1,
        36,
        "exactly one default value",
    ),
    ("(deftemplate good (slot b))", 1, 14, "not in use"),
    (
        "(defrule r4 (good (b 1)) =>)",
        1,
        20,
        "slot of the template",
    ),
    (
        "(defrule r5 (good (a 1 2)) =>)",
        1,
        24,
        "')' closing the slot",
    ),
    (
        "(defrule r6 (good (a $?x)) =>)",
        1,
        20,
        "single-field constraint",
    ),
    ("(defrule r7 (a ?x) (b ?y&~) =>)", 1, 27, "constraint"),
    (
        "(defrule r8 (a ?x) => (printout t ?y crlf))",
        1,
        35,
        "bound variable",
    ),
    ("(defrule r9 (a ?x) (test (> ?x)) =>)", 1, 27, "argument"),
    (
        "(defrule r10 (not (a) (b)) =>)",
        1,
        23,
        "closing not (one CE only)",
    ),
    (
        "(defrule r11 (declare (salience high)) (a) =>)",
        1,
        33,
        "integer salience",
    ),
    (
        "(defrule r12 (declare (salience 99999)) (a) =>)",
        1,
        33,
        "between -10000 and 10000",
    ),
    ("(defrule r13 ?f (a) =>)", 1, 17, "'<-'"),
    ("(defrule r14 (a) (or) =>)", 1, 21, "CE inside or"),
    ("(defrule r15 (a ?x) => (bind))", 1, 29, "variable"),
    (
        "(defrule r16 (a) => (if (> 1 0) (printout t x)))",
        1,
        33,
        "'then'",
    ),
    ("(deffunction)", 1, 13, "deffunction name"),
    (
        "(deffunction f1 ?x ?x)",
        1,
        17,
        "'(' opening the parameter list",
    ),
    (
        "(deffunction f2 ($?a ?b) ?b)",
        1,
        22,
        "wildcard parameter to be last",
    ),
    ("(deffunction + (?a) ?a)", 1, 14, "not a builtin"),
    ("(defglobal ?*g* 5)", 1, 17, "'='"),
    (
        "(defglobal ?*g* = (/ 1 0))",
        1,
        17,
        "initial value that evaluates",
    ),
    (
        "(defglobal ?*g* = (+ 1 a))",
        1,
        24,
        "argument of type integer or float",
    ),
    (
        "(defrule r20 ?f <- (good) => (modify ?f (zz 1)))",
        1,
        42,
        "slot of the template",
    ),
    (
        "(deftemplate t7 (slot a (type INTEGER) (default x)))",
        1,
        49,
        "slot's type",
    ),
    (
        "(deftemplate t8 (multislot a (default x y z) (allowed-symbols x y)))",
        1,
        43,
        "allowed values",
    ),
    ("(deffacts d3 (req))", 1, 15, "(default ?NONE)"),
    ("(defrule r21 (a $?x) (b ?x) =>)", 1, 25, "not both"),
    (
        "(defrule r22 => (printout t (sub-string 1 x \"abc\") crlf))",
        1,
        43,
        "type integer",
    ),
    ("(deffacts d1 (a 1) b)", 1, 20, "'(' starting a fact"),
    ("(deffacts d2 (good (zz 1)))", 1, 21, "slot of the template"),
    (
        "(defrule r17 (a ?x) => (assert (good (a 1 2))))",
        1,
        43,
        "one value for the single-field slot",
    ),
    (
        "(defrule r18 (a ?x) => (switch ?x (cas 1 then 2)))",
        1,
        36,
        "case or default",
    ),
    (
        "(defrule r19 (a) => (loop-for-count (1 2) (printout t x)))",
        1,
        38,
        "loop variable",
    ),
    // forall takes two CEs or more; what it binds is not seen after it
    (
        "(defrule r23 (forall (good (a ?x))) =>)",
        1,
        15,
        "two conditional",
    ),
    ("(defrule r24 (forall) =>)", 1, 15, "two conditional"),
    (
        "(defrule r25 (forall (good (a ?x)) ?f <- (good (a ?x))) =>)",
        1,
        36,
        "fact addresses",
    ),
    (
        "(defrule r26 (forall (good (a ?x)) (logical (good (a ?x)))) =>)",
        1,
        37,
        // (without the feature `logical` the CE is refused as not implemented)
        "",
    ),
    (
        "(defrule r27 (forall (good (a ?x)) (req (id ?x))) => (printout t ?x))",
        1,
        66,
        "bound variable",
    ),
];

#[test]
fn malformed_programs_report_position_and_leave_nothing() {
    assert!(CASES.len() >= 30);
    let mut problems = Vec::new();
    for &(bad, line, col, expected) in CASES {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut Quiet;
        e.load_str(h, "good", GOOD).unwrap();
        let before = e.usage();
        let err = match e.load_str(h, "bad", bad) {
            Ok(n) => {
                problems.push(format!("{bad:?}: loaded {n} constructs, no error"));
                continue;
            }
            Err(err) => err,
        };
        if (err.line, err.col) != (line, col)
            || !err
                .expected
                .to_lowercase()
                .contains(&expected.to_lowercase())
        {
            problems.push(format!(
                "{bad:?}: got {}:{} {:?}",
                err.line, err.col, err.expected
            ));
            continue;
        }
        assert!(err.capacity.is_none());
        let mut after = e.usage();
        // as in CLIPS, the implied templates of unknown relations the bad text read
        // stay (one slot each, with the symbols read up to their names); nothing else
        // does, and no symbol stays when no template did
        let implied = after.templates - before.templates;
        assert_eq!(after.slot_defs - before.slot_defs, implied, "{bad:?}");
        assert!(implied > 0 || after.symbols == before.symbols, "{bad:?}");
        let mut kept = after;
        (kept.templates, kept.slot_defs, kept.symbols) =
            (before.templates, before.slot_defs, before.symbols);
        assert_eq!(kept, before, "leftovers after {bad:?}");
        after.tokens = 0;
        // what was loaded before still works
        e.assert_str(h, "(good (a 7))").unwrap();
        assert_eq!(e.counts().1, 1, "rule `keep` still active after {bad:?}");
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn constructs_before_an_error_in_the_same_text_stay() {
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Quiet;
    let text = "(deftemplate p (slot x))\n(defrule ok (p (x ?v)) => (printout t ?v crlf))\n(defrule broken (p (x ?v) =>)\n";
    let err = e.load_str(h, "t", text).unwrap_err();
    assert_eq!(err.line, 3);
    assert_eq!(err.construct, "defrule");
    e.assert_str(h, "(p (x 1))").unwrap();
    assert_eq!(e.counts().1, 1);
}

/// What we do not implement yet is refused where it stands, as `NotImplemented`, and
/// leaves nothing behind: never accepted and ignored (issue 19).
#[cfg(feature = "parser")]
#[test]
fn unimplemented_constructs_are_refused() {
    use agent_core::LoadDetail;
    // modules are refused only without the feature `modules`
    #[cfg(not(feature = "modules"))]
    let modules: &[(&str, u32, &str)] = &[
        ("(defmodule SENSE (export ?ALL))", 12, "defmodule"),
        ("(deftemplate MAIN::t (slot x))", 14, "module"),
        ("(defrule MAIN::r (good (a 1)) =>)", 10, "module"),
        (
            "(defrule r (declare (auto-focus TRUE)) (good (a 1)) =>)",
            22,
            "auto-focus",
        ),
    ];
    #[cfg(feature = "modules")]
    let modules: &[(&str, u32, &str)] = &[];
    for &(bad, col, what_has) in modules {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut Quiet;
        e.load_str(h, "good", GOOD).unwrap();
        let before = e.usage();
        let err = e.load_str(h, "bad", bad).unwrap_err();
        assert_eq!((err.line, err.col), (1, col), "{bad}");
        match err.detail {
            LoadDetail::NotImplemented { what } => {
                assert!(what.contains(what_has), "{bad}: {what}")
            }
            d => panic!("{bad}: {d:?}"),
        }
        assert_eq!(e.usage(), before, "leftovers after {bad:?}");
    }
    // a module specifier on a relation name: CLIPS 6.30 refuses it ([MODULDEF1]), with
    // or without modules
    for (bad, col) in [
        ("(defrule r (MAIN::good (a 1)) =>)", 13),
        ("(defrule r (good (a 1)) (not (MAIN::good)) =>)", 31),
        ("(deffacts d (MAIN::good (a 1)))", 14),
        ("(defrule r => (assert (MAIN::good (a 1))))", 24),
    ] {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut Quiet;
        e.load_str(h, "good", GOOD).unwrap();
        let before = e.usage();
        let err = e.load_str(h, "bad", bad).unwrap_err();
        assert_eq!((err.line, err.col), (1, col), "{bad}");
        assert_eq!(err.detail, LoadDetail::ModuleSpecifier, "{bad}");
        assert_eq!(e.usage(), before, "leftovers after {bad:?}");
    }
    // watch of an item we do not trace, literal or in a variable: construct names
    // without `extras` (with it, names of constructs that exist: no template `good`
    // here), class names after COOL's items always; globals, deffunctions and COOL's
    // items without `extras`, focus (and so all) without `modules`
    let mut e = Box::new(SmallEngine::new());
    let h = &mut Quiet;
    #[cfg(not(feature = "modules"))]
    assert!(e.eval_str(h, "(watch focus)").is_err());
    assert!(e.eval_str(h, "(watch facts good)").is_err());
    assert!(e.eval_str(h, "(watch instances USER)").is_err());
    assert_eq!(
        e.eval_str(h, "(watch facts initial-fact)").is_ok(),
        cfg!(feature = "extras")
    );
    let traced = cfg!(feature = "extras");
    let all = cfg!(all(feature = "extras", feature = "modules"));
    for (cmd, ok) in [
        ("(watch all)", all),
        ("(unwatch globals)", traced),
        ("(watch deffunctions)", traced),
        ("(watch instances)", traced),
    ] {
        assert_eq!(e.eval_str(h, cmd).is_ok(), ok, "{cmd}");
    }
    assert!(e.eval_str(h, "(bind ?w globals)").is_ok());
    assert_eq!(e.eval_str(h, "(watch ?w)").is_ok(), traced);
    assert!(e.eval_str(h, "(bind ?w facts)").is_ok());
    assert!(e.eval_str(h, "(watch ?w good)").is_err());
    for cmd in ["(watch facts)", "(unwatch all)", "(watch rules)"] {
        assert!(e.eval_str(h, cmd).is_ok(), "{cmd}");
    }
}
