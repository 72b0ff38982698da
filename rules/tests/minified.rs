//! The minified rule files the agent image embeds (`rules::minified`) are the same
//! rule base: every strategy's game loads and plays exactly as from the files as
//! written (same output, same final facts, same number of rules fired), and they are
//! markedly smaller.

use agent_core::{DefaultEngine, Host};
use rules::setup::{fact_lines, GameSetup};
use rules::{game_files, minified, RuleFile, Strategy};

/// Collects everything the engine prints.
#[derive(Default)]
struct Capture(String);

impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

/// Plays seed `seed` with `files`: everything printed, the final facts, rules fired.
fn play(files: &[RuleFile], seed: u64) -> (String, u32) {
    let files: Vec<(String, String)> = files
        .iter()
        .map(|f| (f.name.to_string(), f.text.to_string()))
        .collect();
    // the engine is big: a thread with room for it
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(move || {
            let mut engine = Box::new(DefaultEngine::new());
            let mut host = Capture::default();
            for (name, text) in &files {
                engine
                    .load_str(&mut host, name, text)
                    .unwrap_or_else(|e| panic!("{name} does not load: {e:?}"));
            }
            let mut setup = String::new();
            GameSetup::for_seed(seed)
                .write_clips(&mut setup)
                .expect("setup text");
            engine.reset(&mut host).expect("reset");
            for fact in fact_lines(&setup) {
                engine.assert_str(&mut host, fact).expect("setup fact");
            }
            let fired = engine.run(&mut host, Some(100_000)).expect("run");
            engine.exec_command(&mut host, "(facts)", "test");
            (host.0, fired)
        })
        .expect("thread starts")
        .join()
        .expect("the game does not panic")
}

#[test]
fn minified_files_play_the_same_games() {
    for strategy in Strategy::ALL {
        for seed in [0, 1, 7] {
            let (out, fired) = play(game_files(strategy), seed);
            let (min_out, min_fired) = play(minified::game_files(strategy), seed);
            assert!(fired > 100, "{strategy:?} seed {seed}: {fired} rules fired");
            assert_eq!(fired, min_fired, "{strategy:?} seed {seed}");
            assert_eq!(out, min_out, "{strategy:?} seed {seed}");
        }
    }
}

/// `text` with each string replaced by `S`.
fn outside_strings(text: &str) -> String {
    let (mut out, mut in_string, mut escaped) = (String::new(), false, false);
    for c in text.chars() {
        if in_string {
            in_string = escaped || c != '"';
            escaped = !escaped && c == '\\';
        } else if c == '"' {
            in_string = true;
            out.push('S');
        } else {
            out.push(c);
        }
    }
    out
}

#[test]
fn minified_files_are_smaller_and_keep_strings_whole() {
    let size = |files: &[RuleFile]| files.iter().map(|f| f.text.len()).sum::<usize>();
    for strategy in Strategy::ALL {
        let (full, min) = (game_files(strategy), minified::game_files(strategy));
        assert_eq!(full.len(), min.len());
        assert!(
            size(min) * 100 < size(full) * 80,
            "{strategy:?}: {} of {} bytes",
            size(min),
            size(full)
        );
        for (f, m) in full.iter().zip(min) {
            assert_eq!(f.name, m.name);
            let code = outside_strings(m.text);
            assert!(!code.contains(';'), "{}: a comment is left", m.name);
            assert!(
                !code.contains('\n') && !code.contains("  "),
                "{}: whitespace runs",
                m.name
            );
        }
    }
    // a string keeps its spaces and semicolons
    let sim = minified::game_files(Strategy::Paper)
        .iter()
        .find(|f| f.name == "game-log.clp")
        .expect("game-log.clp");
    assert!(sim.text.contains("\"DEADLOCK at \""), "{}", sim.text);
}
