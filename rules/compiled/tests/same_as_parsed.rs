//! A rule base loaded from its compiled form behaves exactly as its parsed text: the
//! same output (FIRE lines with `(watch rules)` and `(watch facts)`, everything
//! printed) and the same facts at the end.
//! - every strategy's simulated game, over several seeds, set up as the image and
//!   `robotino-agent sim` set it up (reset, then the seed's setup facts);
//! - every differential program (`tests/clips`): its constructs parsed or loaded
//!   compiled, then its commands run on each engine.

#[path = "../src/split.rs"]
mod split;

// (their `SIZES` are for images; the test reads `BASE`)
#[allow(dead_code)]
mod programs {
    include!(concat!(env!("OUT_DIR"), "/clips.rs"));
}

use agent_core::{DefaultEngine, Host, HostIoError};
use rules::setup::{fact_lines, GameSetup};
use rules::Strategy;
use std::collections::HashMap;

/// Output as text; files written by a program stay in memory, files read come from
/// `tests/clips` (both engines see the same).
#[derive(Default)]
struct Capture {
    out: String,
    files: HashMap<String, Vec<u8>>,
}

impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.out.push_str(text);
    }
    fn read_file(&mut self, path: &str, buf: &mut [u8]) -> Result<usize, HostIoError> {
        let data = match self.files.get(path) {
            Some(d) => d.clone(),
            None => std::fs::read(clips_dir().join(path)).map_err(|_| HostIoError::NotFound)?,
        };
        if data.len() > buf.len() {
            return Err(HostIoError::TooLarge);
        }
        buf[..data.len()].copy_from_slice(&data);
        Ok(data.len())
    }
    fn write_file(&mut self, path: &str, data: &[u8], append: bool) -> Result<(), HostIoError> {
        let file = self.files.entry(path.to_string()).or_default();
        if !append {
            file.clear();
        }
        file.extend_from_slice(data);
        Ok(())
    }
}

fn clips_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/clips")
}

/// Runs `f` on a thread with room for engines built on the stack (unoptimised builds).
fn on_big_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn_scoped(s, f)
            .expect("spawn")
            .join()
            .expect("no panic")
    })
}

/// Plays `seed` on an engine holding the game's rules: output with rules and facts
/// watched, then the fact list.
fn play<S: agent_core::Storage>(engine: &mut agent_core::Engine<S>, seed: u64) -> String {
    let mut host = Capture::default();
    engine.exec_command(&mut host, "(watch rules)", "test");
    engine.exec_command(&mut host, "(watch facts)", "test");
    engine.reset(&mut host).expect("reset");
    let mut setup = String::new();
    GameSetup::for_seed(seed)
        .write_clips(&mut setup)
        .expect("setup text");
    for fact in fact_lines(&setup) {
        engine.assert_str(&mut host, fact).expect("setup fact");
    }
    let fired = engine.run(&mut host, Some(500_000)).expect("run");
    host.out.push_str(&format!("fired {fired}\n"));
    engine.exec_command(&mut host, "(facts)", "test");
    host.out
}

/// Two engines with the game of `strategy`: one that parsed its files, one that
/// loaded `base`, its compiled form.
fn parsed_and_compiled(
    strategy: Strategy,
    base: &agent_core::compiled::RuleBase,
) -> (Box<DefaultEngine>, Box<DefaultEngine>) {
    let mut parsed = Box::new(DefaultEngine::new());
    parsed.set_pretty_print_forms(false);
    for file in rules::game_files(strategy) {
        parsed
            .load_str(&mut Capture::default(), file.name, file.text)
            .expect("rule file loads");
    }
    let mut compiled = Box::new(DefaultEngine::new());
    compiled
        .load_compiled(&mut Capture::default(), base)
        .expect("compiled form loads");
    (parsed, compiled)
}

#[test]
fn every_strategys_game_plays_the_same_from_its_compiled_form() {
    for strategy in Strategy::ALL {
        let base = rules_compiled::game(strategy.name()).expect("compiled game");
        for seed in [0, 1, 7] {
            let (parsed, compiled) = on_big_stack(|| {
                let (mut parsed, mut compiled) = parsed_and_compiled(strategy, base);
                (play(&mut parsed, seed), play(&mut compiled, seed))
            });
            assert!(
                parsed.contains("FIRE") && parsed.contains("game-over"),
                "{strategy:?} seed {seed}: the game did not play:\n{parsed}"
            );
            if parsed != compiled {
                let line = parsed
                    .lines()
                    .zip(compiled.lines())
                    .position(|(a, b)| a != b)
                    .unwrap_or(0);
                panic!(
                    "{strategy:?} seed {seed}: compiled form differs from line {}:\nparsed:   {:?}\ncompiled: {:?}",
                    line + 1,
                    parsed.lines().nth(line),
                    compiled.lines().nth(line)
                );
            }
        }
    }
}

/// Runs a program's commands (not its constructs) on `engine`; returns the output.
fn run_commands(engine: &mut DefaultEngine, text: &str, name: &str) -> String {
    let mut host = Capture::default();
    for form in split::forms(text) {
        if split::is_construct(form) {
            continue;
        }
        if !engine.exec_command(&mut host, form, name) {
            break;
        }
    }
    host.out
}

#[test]
fn every_differential_program_runs_the_same_from_its_compiled_constructs() {
    let mut compared = 0;
    let mut differ = Vec::new();
    for (name, base) in programs::CLIPS_PROGRAMS {
        let text = std::fs::read_to_string(clips_dir().join(format!("{name}.clp"))).expect("read");
        let base = match base {
            Ok(base) => *base,
            Err(why) => {
                // only parse-time effects keep a program's constructs from compiling, and
                // the logical CE and defmodules, which compiled rule bases refuse (no
                // truth maintenance or modules in the image: the robot's rules use
                // neither), and what the host (`grow`) takes past the image's fixed
                // limits (a rule of 43 patterns, a global's string of 4 KiB)
                assert!(
                    why.contains("left facts")
                        || why.contains("no truth maintenance")
                        || why.contains("MAIN module only")
                        || why.contains("the image's fixed limits"),
                    "{name}: {why}"
                );
                continue;
            }
        };
        let (parsed, compiled) = on_big_stack(|| {
            let mut parsed = Box::new(DefaultEngine::new());
            for form in split::forms(&text)
                .into_iter()
                .filter(|f| split::is_construct(f))
            {
                let _ = parsed.load_str(&mut Capture::default(), name, form);
            }
            let mut compiled = Box::new(DefaultEngine::new());
            let loaded = compiled.load_compiled(&mut Capture::default(), base);
            assert_eq!(loaded, Ok(()), "{name}: compiled form does not load");
            (
                run_commands(&mut parsed, &text, name),
                run_commands(&mut compiled, &text, name),
            )
        });
        compared += 1;
        if parsed != compiled {
            let line = parsed
                .lines()
                .zip(compiled.lines())
                .position(|(a, b)| a != b)
                // equal as far as both go: the shorter one ends first
                .unwrap_or_else(|| parsed.lines().count().min(compiled.lines().count()));
            differ.push(format!(
                "{name} line {}:\n  parsed:   {:?}\n  compiled: {:?}",
                line + 1,
                parsed.lines().nth(line),
                compiled.lines().nth(line)
            ));
        }
    }
    assert!(compared > 150, "only {compared} programs compared");
    assert!(
        differ.is_empty(),
        "{} of {compared} differ:\n{}",
        differ.len(),
        differ.join("\n")
    );
}

/// Rules added and removed after a compiled rule base loaded work as after parsing it
/// (with `in-place`, which the workspace build has, the network and the templates,
/// slots and rules read in place are copied into the arena before the first edit,
/// the template an ordered fact made after loading moved behind them): one rule of
/// the game removed, one added that shares its first pattern with the game's rules,
/// then seed 0 played.
#[test]
fn rules_added_and_removed_after_a_compiled_load_work_as_parsed() {
    let edits = [
        "(assert (extra-marker 1))",
        "(undefrule exec-get-junk-none)",
        "(defrule extra-points (score (points ?p&:(> ?p 0))) => (printout t \"points \" ?p crlf))",
    ];
    let strategy = Strategy::Paper;
    let base = rules_compiled::game(strategy.name()).expect("compiled game");
    let (listed, parsed, compiled) = on_big_stack(|| {
        let (mut parsed, mut compiled) = parsed_and_compiled(strategy, base);
        let mut listed = [String::new(), String::new()];
        for (engine, listed) in [&mut parsed, &mut compiled].into_iter().zip(&mut listed) {
            for edit in edits {
                assert!(engine.exec_command(&mut Capture::default(), edit, "test"));
            }
            let mut out = Capture::default();
            assert!(engine.exec_command(&mut out, "(facts)", "test"));
            *listed = out.out;
        }
        (listed, play(&mut parsed, 0), play(&mut compiled, 0))
    });
    assert!(listed[0].contains("(extra-marker 1)"), "{}", listed[0]);
    assert_eq!(listed[0], listed[1]);
    assert!(parsed.contains("points "), "{parsed}");
    assert!(!parsed.contains("exec-get-junk-none"));
    assert_eq!(parsed, compiled);
}

agent_core::engine_storage! {
    /// Sized as the agent image: the compiled network's nodes, templates, slots and
    /// rules only read in place.
    struct InPlaceOnly {
        alpha_nodes: 0,
        joins: 1,
        templates: 1,
        slot_defs: 1,
        rules: 0,
        alpha_memories: rules_compiled::game_paper::SIZES.alphas,
        join_memories: rules_compiled::game_paper::SIZES.joins,
        template_memories: rules_compiled::game_paper::SIZES.templates + 1,
        // no module pools: the engine is MAIN alone
        modules: 0,
        module_ports: 0,
        focus_stack: 0,
        ..agent_core::Capacities::HOST
    }
}

/// An engine sized to read its compiled network in place (as the image) has no room to
/// copy it: a new rule, a rule removed or a second ordered-fact relation made at run
/// time is refused with a capacity error naming the pool, and the engine still plays
/// its game.
#[test]
fn an_engine_sized_for_in_place_reading_refuses_new_rules() {
    if !agent_core::rom::IN_PLACE {
        // (without the feature such an engine cannot load the rule base at all)
        return;
    }
    let base = rules_compiled::game("paper").expect("compiled game");
    on_big_stack(|| {
        let mut engine = Box::new(agent_core::Engine::with_storage(InPlaceOnly::new()));
        let host = &mut Capture::default();
        engine.load_compiled(host, base).expect("loads in place");
        // the rules read in place fill the rule pool: a new one has no room
        let err = engine
            .load_str(host, "t", "(defrule extra (score) =>)")
            .expect_err("no room for a rule");
        assert_eq!(
            err.capacity.map(|c| c.pool),
            Some(agent_core::Pool::Rules),
            "{err}"
        );
        let mut undef = Capture::default();
        engine.exec_command(&mut undef, "(undefrule exec-get-junk-none)", "t");
        assert!(undef.out.contains("joins"), "{}", undef.out);
        // an ordered fact of a new relation takes the arena's one template
        let mut more = Capture::default();
        assert!(engine.exec_command(&mut more, "(assert (extra-marker 1))", "t"));
        assert!(!more.out.contains("out of"), "{}", more.out);
        engine.exec_command(&mut more, "(assert (another-marker 1))", "t");
        assert!(more.out.contains("templates"), "{}", more.out);
        engine.reset(host).expect("reset");
        assert!(engine.run(host, Some(500_000)).expect("run") > 0);
    });
}

/// An engine sized to read its compiled network in place, without module pools (as
/// the image: its rules have no module entries, `rules: 0`), plays as the parsed
/// rules do.
#[test]
fn an_engine_sized_for_in_place_reading_plays_as_parsed() {
    if !agent_core::rom::IN_PLACE {
        return;
    }
    let strategy = Strategy::Paper;
    let base = rules_compiled::game(strategy.name()).expect("compiled game");
    for seed in [0, 3] {
        let (parsed, in_place) = on_big_stack(|| {
            let (mut parsed, _) = parsed_and_compiled(strategy, base);
            let mut engine = Box::new(agent_core::Engine::with_storage(InPlaceOnly::new()));
            engine
                .load_compiled(&mut Capture::default(), base)
                .expect("loads in place");
            (play(&mut parsed, seed), play(&mut engine, seed))
        });
        assert!(parsed.contains("game-over"), "seed {seed}:\n{parsed}");
        assert!(
            parsed == in_place,
            "seed {seed}: the in-place engine plays otherwise"
        );
    }
}
