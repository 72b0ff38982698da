//! Fixed local limits of the core that input can reach (issue 19): each one beyond
//! what the pools bound is a typed load error naming the limit, leaving the engine as
//! it was; none drops data silently. The list of limits and what each does is in
//! tests/clips/NOTES.md ("Fixed limits").
// without `parser` the tests that evaluate builtins are left out (only `parser` links
// their code: `builtins::BUILTINS`), and helpers only they use are unused
#![cfg_attr(
    not(feature = "parser"),
    allow(dead_code, unused_imports, unused_macros)
)]

use agent_core::{DefaultEngine, Host};

struct Quiet;
impl Host for Quiet {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

fn engine() -> Box<DefaultEngine> {
    Box::new(DefaultEngine::new())
}

/// Loads `text` and expects a load error whose `expected` names `limit`; the usage
/// figures stay as they were.
fn refused(text: &str, limit: &str) {
    let mut e = engine();
    let h = &mut Quiet;
    // the first load sets the engine up (initial-fact): measure after it
    e.load_str(h, "setup", "").unwrap();
    let before = e.usage();
    let err = e.load_str(h, "limit", text).unwrap_err();
    assert!(err.expected.contains(limit), "{limit}: {err:?}");
    assert!(err.capacity.is_none(), "{err:?}");
    assert_eq!(e.usage(), before);
}

#[test]
fn a_template_holds_255_slots_and_refuses_the_256th() {
    with_big_stack(|| {
        let slots = |n: usize| (0..n).map(|i| format!("(slot s{i})")).collect::<String>();
        let mut e = engine();
        let h = &mut Quiet;
        e.load_str(h, "t", &format!("(deftemplate t {})", slots(255)))
            .unwrap();
        refused(
            &format!("(deftemplate u {})", slots(256)),
            "at most 255 slots",
        );
    });
}

#[cfg(feature = "parser")]
#[test]
fn values_of_slots_past_64_are_kept() {
    with_big_stack(|| {
        let slots: String = (0..100)
            .map(|i| format!("(slot s{i} (default d))"))
            .collect();
        let mut e = engine();
        let h = &mut Quiet;
        e.load_str(h, "t", &format!("(deftemplate t {slots})"))
            .unwrap();
        e.eval_str(h, "(assert (t (s3 a) (s64 b) (s65 c) (s99 z)))")
            .unwrap();
        for (slot, want) in [
            ("s3", "a"),
            ("s64", "b"),
            ("s65", "c"),
            ("s66", "d"),
            ("s99", "z"),
        ] {
            let v = e
                .eval_str(h, &format!("(eq (fact-slot-value 1 {slot}) {want})"))
                .unwrap();
            assert_eq!(
                e.eval_str(h, "TRUE").unwrap(),
                v,
                "slot {slot} should hold {want}"
            );
        }
    });
}

/// Runs `f` on a thread with room for the debug build's deep parser frames.
fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(f)
        .unwrap()
        .join()
        .unwrap();
}

#[cfg(feature = "parser")]
#[test]
fn a_construct_names_at_most_64_variables() {
    // the variable table (64) bounds the frame's locals (255, a u8) first; with
    // `grow` (hosts) the table grows and the frame's 255 locals are the limit
    with_big_stack(|| {
        let binds = |n: usize| {
            (0..n)
                .map(|i| format!("(bind ?v{i} {i})"))
                .collect::<String>()
        };
        let mut e = engine();
        let h = &mut Quiet;
        e.load_str(h, "f", &format!("(deffunction f () {} ?v63)", binds(64)))
            .unwrap();
        assert_eq!(e.eval_str(h, "(f)").unwrap(), agent_core::Value::Int(63));
        #[cfg(not(feature = "grow"))]
        {
            refused(
                &format!("(deffunction g () {})", binds(65)),
                "fewer variables",
            );
            refused(&format!("(defrule r => {})", binds(65)), "fewer variables");
        }
        #[cfg(feature = "grow")]
        {
            e.load_str(h, "g", &format!("(deffunction g () {} ?v254)", binds(255)))
                .unwrap();
            assert_eq!(e.eval_str(h, "(g)").unwrap(), agent_core::Value::Int(254));
            let pats: String = (0..40).map(|i| format!("(p{i} ?x{i} ?y{i})")).collect();
            e.load_str(
                h,
                "r",
                &format!("(defrule r (a) => {} (bind ?z ?v0))", binds(120)),
            )
            .unwrap();
            e.load_str(h, "s", &format!("(defrule s {pats} =>)"))
                .unwrap();
            refused(
                &format!("(deffunction h () {})", binds(256)),
                "at most 255 local variables",
            );
        }
    });
}

#[test]
fn a_pattern_constrains_at_most_8_multislots() {
    with_big_stack(|| {
        let template = (0..9)
            .map(|i| format!("(multislot m{i})"))
            .collect::<String>();
        let constraints = |n: usize| (0..n).map(|i| format!("(m{i} $? x)")).collect::<String>();
        let mut e = engine();
        let h = &mut Quiet;
        let text = format!(
            "(deftemplate t {template}) (defrule ok (t {}) =>)",
            constraints(8)
        );
        e.load_str(h, "ok", &text).unwrap();
        let mut e = engine();
        e.load_str(h, "t", &format!("(deftemplate t {template})"))
            .unwrap();
        let before = e.usage();
        let err = e
            .load_str(h, "r", &format!("(defrule r (t {}) =>)", constraints(9)))
            .unwrap_err();
        assert!(err.expected.contains("at most 8 multislots"), "{err:?}");
        assert_eq!(e.usage(), before);
    });
}

#[cfg(feature = "parser")]
#[test]
fn an_argument_past_the_255th_is_numbered_255() {
    with_big_stack(|| {
        let mut e = engine();
        let h = &mut Quiet;
        e.eval_str(h, "(bind ?s a)").unwrap();
        let call = format!("(+ {} ?s)", "1 ".repeat(255));
        let err = e.eval_str(h, &call).unwrap_err();
        match err.kind() {
            agent_core::EvalErrorKind::WrongType { arg, .. } => assert_eq!(arg, 255),
            k => panic!("{k:?}"),
        }
    });
}

#[cfg(feature = "parser")]
#[test]
fn a_prompt_variable_name_is_at_most_126_bytes() {
    with_big_stack(|| {
        let mut e = engine();
        let h = &mut Quiet;
        let ok = "v".repeat(126);
        e.eval_str(h, &format!("(bind ?{ok} 1)")).unwrap();
        // two long names differing after the cut would share one global
        let long = "v".repeat(200);
        assert!(e.eval_str(h, &format!("(bind ?{long}a 1)")).is_err());
        assert!(e.eval_str(h, &format!("(bind ?{long}b 2)")).is_err());
    });
}

/// Serves one file under a 256-byte name (a longer name cut to 256 bytes would be it).
struct OneFile(String);
impl Host for OneFile {
    fn write_str(&mut self, _router: &str, _text: &str) {}
    fn read_file(&mut self, path: &str, buf: &mut [u8]) -> Result<usize, agent_core::HostIoError> {
        if path != self.0 {
            return Err(agent_core::HostIoError::NotFound);
        }
        let text = b"(defglobal ?*loaded* = yes)";
        buf[..text.len()].copy_from_slice(text);
        Ok(text.len())
    }
}

#[cfg(feature = "parser")]
#[test]
fn a_file_name_over_256_bytes_is_an_error_not_another_file() {
    with_big_stack(|| {
        let mut e = engine();
        let name = "f".repeat(256);
        let h = &mut OneFile(name.clone());
        // exactly 256 bytes: loaded
        e.eval_str(h, &format!("(load \"{name}\")")).unwrap();
        e.eval_str(h, "(bind ?*loaded* no)").unwrap();
        for f in ["load", "load*", "batch", "batch*", "load-facts"] {
            let err = e.eval_str(h, &format!("({f} \"{name}x\")")).unwrap_err();
            assert!(err.to_string().contains("longer than 256"), "{f}: {err}");
        }
        let v = e.eval_str(h, "(eq ?*loaded* no)").unwrap();
        assert_eq!(v, e.eval_str(h, "TRUE").unwrap());
    });
}

struct Capture(String);
impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

#[test]
fn a_string_literal_is_at_most_1024_bytes() {
    // (with `grow`, as on hosts, any length: CLIPS reads any)
    with_big_stack(|| {
        let mut e = engine();
        let h = &mut Capture(String::new());
        let s = "x".repeat(1025);
        let loaded = e.load_str(h, "s", &format!("(defglobal ?*s* = \"{s}\")"));
        #[cfg(not(feature = "grow"))]
        {
            let err = loaded.unwrap_err();
            assert!(err.expected.contains("at most 1024 bytes"), "{err:?}");
            assert!(e.eval_str(h, &format!("(printout t \"{s}\")")).is_err());
        }
        #[cfg(feature = "grow")]
        {
            loaded.unwrap();
            let long = "\\\"y".repeat(3000);
            e.eval_str(h, &format!("(printout t \"{long}\" (str-length ?*s*))"))
                .unwrap();
            assert_eq!(h.0, format!("{}1025", "\"y".repeat(3000)));
        }
    });
}

#[cfg(feature = "parser")]
#[test]
fn printout_prints_each_value_once_and_whole() {
    with_big_stack(|| {
        let mut e = engine();
        let cases = [(500, 600), (0, 950), (10, 1024), (1000, 1000), (1024, 1024)];
        for (a, b) in cases {
            let h = &mut Capture(String::new());
            let (a, b) = ("a".repeat(a), "b".repeat(b));
            let tail = "crlf tab crlf ".repeat(200);
            e.eval_str(h, &format!("(printout t \"{a}\" \"{b}\" {tail})"))
                .unwrap();
            let tail = "\n\t\n".repeat(200);
            assert_eq!(h.0, format!("{a}{b}{tail}"), "{} {}", a.len(), b.len());
        }
    });
}

/// The static type checks of a rule (CLIPS's `[RULECSTR2]`) note each test CE and
/// `:`/`=` constraint; past the 256 noted, the rule is refused, not loaded unchecked.
#[cfg(feature = "extras")]
#[test]
fn a_rule_holds_256_constraint_checks_and_refuses_the_257th() {
    with_big_stack(|| {
        let rule = |n: usize| {
            let checks: String = (0..n).map(|i| format!("&:(neq ?x {i})")).collect();
            format!("(defrule r{n} (a ?x{checks}) =>)")
        };
        let mut e = engine();
        let h = &mut Quiet;
        e.load_str(h, "r", &rule(256)).unwrap();
        let before = e.usage();
        let err = e.load_str(h, "r", &rule(257)).unwrap_err();
        assert!(err.expected.contains("at most 256 test CEs"), "{err:?}");
        assert_eq!(e.usage(), before);
    });
}

/// Hosts (`grow`) read expressions as deep as calls may nest (`set_depth_limits`),
/// and stop at the stack bound the host gives, with an error, not an overflow.
#[cfg(all(feature = "parser", feature = "grow"))]
#[test]
fn hosts_read_expressions_as_deep_as_calls_may_nest() {
    with_big_stack(|| {
        let nest = |n: usize| format!("{}0{}", "(+ 1 ".repeat(n), ")".repeat(n));
        let mut e = engine();
        let h = &mut Quiet;
        // the default: the image's 200 levels
        let def = |n: usize| format!("(deffunction g () {})", nest(n));
        let err = e.load_str(h, "g", &def(300)).unwrap_err();
        assert!(err.expected.contains("200 levels of nesting"), "{err:?}");
        assert!(e.eval_str(h, &nest(300)).is_err());
        e.set_depth_limits(1000, 0);
        assert_eq!(
            e.eval_str(h, &nest(990)).unwrap(),
            agent_core::Value::Int(990)
        );
        e.load_str(h, "f", &format!("(deffunction f () {})", nest(900)))
            .unwrap();
        assert_eq!(e.eval_str(h, "(f)").unwrap(), agent_core::Value::Int(900));
        let err = e.load_str(h, "g", &def(1001)).unwrap_err();
        assert!(err.expected.contains("call limit"), "{err:?}");
        assert!(e.eval_str(h, &nest(1001)).is_err());
        // a stack bound of 4 MiB (of the thread's 64) ends a deeper text in an error
        e.set_depth_limits(u16::MAX, 4 << 20);
        let err = e.load_str(h, "g", &def(60_000)).unwrap_err();
        assert!(err.expected.contains("stack's room"), "{err:?}");
        assert!(e.eval_str(h, &nest(60_000)).is_err());
        assert_eq!(
            e.eval_str(h, &nest(250)).unwrap(),
            agent_core::Value::Int(250)
        );
    });
}
