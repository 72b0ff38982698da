//! Compiles rule bases ahead of time: the engine (on the host) parses each one and
//! writes its constructs as Rust constants (`Engine::write_compiled`) into
//! `$OUT_DIR/compiled.rs`, which `src/lib.rs` includes:
//! - `game_naive`, `game_paper`, `game_travel`: a simulated game's files (agent of
//!   that strategy, referee, decision log, instant simulation), as `rules::game_files`
//!   lists them, without pretty-print forms (as the image loads them);
//! - `clips_NNN_...`: the constructs of every differential program in
//!   `tests/clips/*.clp`, in `$OUT_DIR/clips.rs`, which the tests include (for the
//!   test that runs each from its compiled form).
//!
//! A rule file that does not load fails the build with the engine's message.

#[path = "src/split.rs"]
mod split;

use agent_core::{DefaultEngine, Host};
use std::fmt::Write as _;
use std::path::Path;

/// `DefaultEngine::new` may build the engine on the stack before boxing it
/// (unoptimised build scripts do): the work runs on a thread this big.
const ENGINE_STACK: usize = 64 << 20;

struct Silent;

impl Host for Silent {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

/// Keeps what the engine printed (to report a rule file that does not load).
struct Keep(String);

impl Host for Keep {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=src/split.rs");
    let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".to_string());
    let clips_dir = Path::new(&dir).join("../../tests/clips");
    println!("cargo::rerun-if-changed={}", clips_dir.display());
    let out_dir = std::env::var("OUT_DIR").unwrap_or_else(|_| ".".to_string());
    let worker = std::thread::Builder::new()
        .stack_size(ENGINE_STACK)
        .spawn(move || generate(&clips_dir))
        .unwrap_or_else(|e| fail(&format!("cannot start the compiling thread: {e}")));
    let text = match worker.join() {
        Ok(Ok(text)) => text,
        Ok(Err(message)) => fail(&message),
        Err(_) => fail("the engine panicked while compiling"),
    };
    let (games, programs) = text;
    for (name, text) in [("compiled.rs", games), ("clips.rs", programs)] {
        let path = Path::new(&out_dir).join(name);
        if let Err(e) = std::fs::write(&path, text) {
            fail(&format!("cannot write {}: {e}", path.display()));
        }
    }
}

/// The game bases (`compiled.rs`, for the crate) and the differential programs'
/// (`clips.rs`, for its tests: they call builtins the image leaves out).
fn generate(clips_dir: &Path) -> Result<(String, String), String> {
    let mut out = String::new();
    for strategy in rules::Strategy::ALL {
        let mut engine = Box::new(DefaultEngine::new());
        let mut host = Keep(String::new());
        engine.set_pretty_print_forms(false);
        for file in rules::game_files(strategy) {
            engine
                .load_str(&mut host, file.name, file.text)
                .map_err(|e| format!("rules/{}: {e} {}", file.name, host.0))?;
        }
        let module = format!("game_{}", strategy.name());
        engine
            .write_compiled(&module, &format!("{} game", strategy.name()), &mut out)
            .map_err(|e| format!("{module}: {e}"))?;
    }

    let mut clips = String::new();
    let mut programs: Vec<_> = std::fs::read_dir(clips_dir)
        .map_err(|e| format!("{}: {e}", clips_dir.display()))?
        .flatten()
        .map(|entry| entry.path())
        .filter(|p| p.extension().is_some_and(|e| e == "clp"))
        .collect();
    programs.sort();
    let mut index = String::from(
        "/// Every differential program (`tests/clips/NAME.clp`) by name: its constructs \
         compiled, or why they could not be.\n\
         pub static CLIPS_PROGRAMS: &[(&str, Result<&agent_core::compiled::RuleBase, &str>)] = &[\n",
    );
    for path in programs {
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .ok_or_else(|| format!("{}: not a UTF-8 name", path.display()))?
            .to_string();
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut engine = Box::new(DefaultEngine::new());
        for form in split::forms(&text)
            .into_iter()
            .filter(|f| split::is_construct(f))
        {
            // a construct that does not load is left out, as it is when parsed
            let _ = engine.load_str(&mut Silent, &name, form);
        }
        let module = format!("clips_{}", name.replace('-', "_"));
        let mut text = String::new();
        match engine.write_compiled(&module, &format!("tests/clips/{name}.clp"), &mut text) {
            Ok(()) => {
                clips.push_str(&text);
                let _ = writeln!(index, "({name:?}, Ok(&{module}::BASE)),");
            }
            Err(e) => {
                let _ = writeln!(index, "({name:?}, Err({:?})),", e.to_string());
            }
        }
    }
    index.push_str("];\n");
    clips.push_str(&index);
    Ok((out, clips))
}

fn fail(message: &str) -> ! {
    println!("cargo::warning={message}");
    eprintln!("error: {message}");
    std::process::exit(1);
}
