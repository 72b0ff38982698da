//! `robotino-agent clips`: behaves like the `clips` command line.
//!
//! Options as CLIPS takes them: `-f FILE` (batch with echo), `-f2 FILE` (batch without
//! echo), `-l FILE` (load constructs); several may be given and run in order. After
//! them (or without any) it reads commands from standard input with a `CLIPS> ` prompt.

use std::io::{BufRead, Write};
use std::process::ExitCode;

use agent_core::commands::command_complete;
use agent_core::{DefaultEngine, Host, HostIoError};

#[derive(clap::Args)]
pub struct Args {
    /// CLIPS options: -f FILE | -f2 FILE | -l FILE (in order).
    #[arg(allow_hyphen_values = true, trailing_var_arg = true, num_args = 0..)]
    pub options: Vec<String>,
}

/// What to do with one file given on the command line.
enum Step {
    Batch { path: String, echo: bool },
    Load(String),
}

/// Host for the command line: every router goes to stdout; files via std::fs.
struct CliHost {
    out: std::io::BufWriter<std::io::Stdout>,
}

impl Host for CliHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        let _ = self.out.write_all(text.as_bytes());
    }

    fn read_file(&mut self, path: &str, buf: &mut [u8]) -> Result<usize, HostIoError> {
        let data = std::fs::read(path).map_err(|_| HostIoError::NotFound)?;
        if data.len() > buf.len() {
            return Err(HostIoError::TooLarge);
        }
        buf[..data.len()].copy_from_slice(&data);
        Ok(data.len())
    }

    /// Streams files of any size to the engine, one buffer at a time.
    fn read_file_at(
        &mut self,
        path: &str,
        offset: u64,
        buf: &mut [u8],
    ) -> Result<usize, HostIoError> {
        use std::io::{Read, Seek, SeekFrom};
        let mut f = std::fs::File::open(path).map_err(|_| HostIoError::NotFound)?;
        f.seek(SeekFrom::Start(offset))
            .map_err(|_| HostIoError::Other)?;
        let mut n = 0;
        while n < buf.len() {
            match f.read(&mut buf[n..]) {
                Ok(0) => break,
                Ok(k) => n += k,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(_) => return Err(HostIoError::Other),
            }
        }
        Ok(n)
    }

    fn write_file(&mut self, path: &str, data: &[u8], append: bool) -> Result<(), HostIoError> {
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .write(true)
            .append(append)
            .truncate(!append)
            .open(path)
            .map_err(|_| HostIoError::Other)?;
        f.write_all(data).map_err(|_| HostIoError::Other)
    }

    fn time(&mut self) -> f64 {
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs_f64())
            .unwrap_or(0.0)
    }
}

fn parse_steps(options: &[String]) -> Result<Vec<Step>, String> {
    let mut steps = Vec::new();
    let mut it = options.iter();
    while let Some(o) = it.next() {
        let path = || {
            it.clone()
                .next()
                .cloned()
                .ok_or_else(|| format!("option {o} needs a file name"))
        };
        let step = match o.as_str() {
            "-f" => Step::Batch {
                path: path()?,
                echo: true,
            },
            "-f2" => Step::Batch {
                path: path()?,
                echo: false,
            },
            "-l" => Step::Load(path()?),
            _ => return Err(format!("unknown option {o} (expected -f, -f2 or -l)")),
        };
        it.next();
        steps.push(step);
    }
    Ok(steps)
}

pub fn main(args: Args) -> ExitCode {
    let steps = match parse_steps(&args.options) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("robotino-agent clips: {e}");
            return ExitCode::FAILURE;
        }
    };
    // The default engine is a few MiB of inline arrays: give it a thread stack.
    let worker = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || session(steps));
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => code,
        _ => ExitCode::FAILURE,
    }
}

fn session(steps: Vec<Step>) -> ExitCode {
    let mut engine = DefaultEngine::new();
    let mut host = CliHost {
        out: std::io::BufWriter::new(std::io::stdout()),
    };
    host.write_str(
        "stdout",
        "         CLIPS (6.30 compatible: robotino-agent)\n",
    );
    for step in steps {
        let keep_going = match step {
            Step::Batch { path, echo } => match std::fs::read_to_string(&path) {
                Ok(text) => engine.batch_file(&mut host, &path, &text, echo),
                Err(e) => {
                    let _ = host.out.flush();
                    eprintln!("robotino-agent clips: cannot read {path}: {e}");
                    true
                }
            },
            Step::Load(path) => match std::fs::read_to_string(&path) {
                Ok(text) => {
                    if let Err(e) = engine.load_str(&mut host, &path, &text) {
                        host.write_str(
                            "werror",
                            &format!("\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {}.\n--> {path}:{}:{}: expected {}\n", e.construct, e.line, e.col, e.expected),
                        );
                    }
                    true
                }
                Err(e) => {
                    eprintln!("robotino-agent clips: cannot read {path}: {e}");
                    true
                }
            },
        };
        if !keep_going {
            let _ = host.out.flush();
            return ExitCode::SUCCESS;
        }
    }
    interactive(&mut engine, &mut host);
    let _ = host.out.flush();
    ExitCode::SUCCESS
}

/// The prompt loop on standard input.
fn interactive(engine: &mut DefaultEngine, host: &mut CliHost) {
    let stdin = std::io::stdin();
    let mut lines = stdin.lock();
    let mut buf = String::new();
    loop {
        if buf.trim().is_empty() {
            buf.clear();
            host.write_str("stdout", "CLIPS> ");
        }
        let _ = host.out.flush();
        let mut line = String::new();
        match lines.read_line(&mut line) {
            Ok(0) | Err(_) => return,
            Ok(_) => {}
        }
        buf.push_str(&line);
        if let Some(k) = command_complete(&buf) {
            let cmd: String = buf[..k].to_string();
            buf.clear();
            if !engine.exec_command(host, &cmd, "stdin") {
                return;
            }
        }
    }
}
