//! The host API used the way hosts use it (`eval_str`, `assert_str`, fact reading),
//! outside the command line.

use agent_core::{Host, SmallEngine, ValueRef};

#[derive(Default)]
struct Capture(String);

impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

fn slot_symbol(engine: &SmallEngine, template: &str, slot: &str) -> Vec<String> {
    engine
        .facts()
        .filter(|&f| engine.fact_template_name(f) == Some(template))
        .filter_map(|f| match engine.fact_slot(f, slot) {
            Some(ValueRef::Symbol(s)) => Some(s.to_string()),
            _ => None,
        })
        .collect()
}

/// A query's fact variable lives in a frame of its own: `eval_str` must make one, as the
/// prompt does, or `?f` reads whatever the arguments left on the stack.
#[test]
fn eval_str_runs_fact_set_queries_that_modify_their_fact() {
    let mut engine = Box::new(SmallEngine::new());
    let mut host = Capture::default();
    engine
        .load_str(&mut host, "m.clp", "(deftemplate m (slot name) (slot t))")
        .expect("template loads");
    engine
        .assert_str(&mut host, "(m (name A) (t x))")
        .expect("assert A");
    engine
        .assert_str(&mut host, "(m (name B) (t x))")
        .expect("assert B");

    let result = engine.eval_str(
        &mut host,
        "(do-for-fact ((?f m)) (eq ?f:name A) (modify ?f (t y)))",
    );
    assert!(result.is_ok(), "{result:?}: {}", host.0);
    assert_eq!(host.0, "", "no error output expected");
    let mut ts = slot_symbol(&engine, "m", "t");
    ts.sort();
    assert_eq!(ts, ["x", "y"]);

    // and again with a loop variable beside the query variable
    let result = engine.eval_str(
        &mut host,
        "(loop-for-count (?i 1 2) (do-for-all-facts ((?f m)) (eq ?f:t x) (modify ?f (t z))))",
    );
    assert!(result.is_ok(), "{result:?}: {}", host.0);
    assert_eq!(host.0, "");
    let mut ts = slot_symbol(&engine, "m", "t");
    ts.sort();
    assert_eq!(ts, ["y", "z"]);
}
