//! The host API's text entry points, line by line, on the command line's engine after
//! a small rule base: a line is a fact for `assert_str` (the default), or, by its first
//! byte, `!` an expression for `eval_str`, `>` a command for `exec_command`, `+`
//! constructs for `load_str`, `-` a fact index to `retract`, `.` a bounded `run`,
//! `#` a `reset`. After each: invariants, and every fact and activation read back
//! through the API. Must return, never panic.
#![no_main]

#[path = "common/cli.rs"]
mod cli;

use agent_core::FactId;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    cli::on_engine_stack(move || {
        let h = &mut cli::Budget::default();
        let mut e = cli::with_prelude(h);
        for line in text.split('\n').take(64) {
            h.polls = 0;
            let (what, rest) = match line.as_bytes().first() {
                Some(b'!') => ("eval_str", &line[1..]),
                Some(b'>') => ("exec_command", &line[1..]),
                Some(b'+') => ("load_str", &line[1..]),
                Some(b'-') => ("retract", &line[1..]),
                Some(b'.') => ("run", &line[1..]),
                Some(b'#') => ("reset", &line[1..]),
                _ => ("assert_str", line),
            };
            match what {
                "eval_str" => {
                    let _ = e.eval_str(h, rest);
                }
                "exec_command" => {
                    if !e.exec_command(h, rest, "fuzz") {
                        return;
                    }
                }
                "load_str" => {
                    let _ = e.load_str(h, "fuzz", rest);
                }
                "retract" => {
                    let n = rest.trim().parse::<u32>().unwrap_or(u32::MAX);
                    let _ = e.retract(h, FactId(n));
                }
                "run" => {
                    let n = rest.trim().parse::<u32>().unwrap_or(10).min(1_000);
                    let _ = e.run(h, Some(n));
                }
                "reset" => {
                    let _ = e.reset(h);
                }
                _ => {
                    let _ = e.assert_str(h, rest);
                }
            }
            cli::check(&mut e, what);
            let facts: Vec<FactId> = e.facts().collect();
            for id in facts {
                if let Some(name) = e.fact_template_name(id) {
                    let name = name.to_owned();
                    for slot in ["id", "tag", "parts", "n", "implied"] {
                        let _ = e.fact_slot(id, slot);
                        let _ = e.fact_multislot_item(id, slot, 0);
                    }
                    assert!(
                        e.facts_of(&name).any(|f| f == id),
                        "fact {id:?} not among facts_of({name})"
                    );
                }
            }
            e.for_each_activation(|_, _, _| {});
            let _ = (e.stats(), e.usage(), e.counts(), e.owes());
        }
    });
});
