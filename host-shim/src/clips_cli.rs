//! `robotino-agent clips`: behaves like the `clips` command line.
//!
//! Options as CLIPS takes them: `-f FILE` (batch with echo), `-f2 FILE` (batch without
//! echo), `-l FILE` (load constructs); several may be given and run in order. After
//! them (or without any) it reads commands from standard input with a `CLIPS> ` prompt.
//! As in CLIPS, `-l` and `-f2` files run at start-up before the banner line (which is
//! CLIPS's own), `-f` files after it through the command loop; `-f2` prints no prompts,
//! echo or command results.
//!
//! The session runs on a [`GrowEngine`]: its pools start at the fixed host engine's
//! capacities, in a static seed ([`CLI_SEED`]), and grow as the program needs
//! (`agent_core::grow`), so no program runs out of a pool before the index type's limit
//! or the machine's memory. `--large-pools`
//! (before the CLIPS options; not a CLIPS option) is still accepted and changes nothing:
//! it chose a larger fixed engine before the pools grew.

use std::collections::HashMap;
use std::io::{BufRead, Read, Write};
use std::process::ExitCode;

use agent_core::commands::command_complete;
use agent_core::grow::{GrowEngine, GrowStorage, HostSeed};
use agent_core::Capacities;
use agent_core::{Host, HostIoError, LoadError, OpenMode};

#[derive(clap::Args)]
pub struct Args {
    /// Accepted for older scripts; changes nothing (the pools grow as needed). Not a
    /// CLIPS option.
    #[arg(long)]
    pub large_pools: bool,
    /// Every pool grows to at most N entries; past that an allocation is the pool's
    /// capacity error, as on the robot, whose pools never grow. Not a CLIPS option.
    #[arg(long, value_name = "N")]
    pub pool_limit: Option<usize>,
    /// CLIPS options: -f FILE | -f2 FILE | -l FILE (in order).
    #[arg(allow_hyphen_values = true, trailing_var_arg = true, num_args = 0..)]
    pub options: Vec<String>,
}

/// Where the CLI's pools start: arrays of the fixed host engine's capacities, which most
/// programs never outgrow, built at compile time. Starting costs no instructions then
/// (the seed is initialized data; only the pages a program uses are touched), where a
/// heap start fills every entry, and a small start that doubles costs mid-sized
/// programs their growth (join-1000 of `bench` ran 6.8 % more instructions).
static CLI_SEED: static_cell::ConstStaticCell<HostSeed> =
    static_cell::ConstStaticCell::new(HostSeed::new());

/// The session's storage: in the seed, or (a second session of the process) on the
/// heap at the same capacities; no pool grows past `limit` entries.
fn cli_storage(limit: Capacities) -> GrowStorage {
    match CLI_SEED.try_take() {
        #[cfg(target_os = "linux")]
        Some(seed) => {
            seed.touch_first();
            GrowStorage::from_seed_in(seed, limit, zero_pages::PAGES)
        }
        #[cfg(not(target_os = "linux"))]
        Some(seed) => {
            seed.touch_first();
            GrowStorage::from_seed(seed, limit)
        }
        None => GrowStorage::with_limits(Capacities::HOST, limit),
    }
}

/// Anonymous mappings for the pools' zero-free arrays (`ZeroPages`): fresh pages are
/// zero and resident only once touched, and `mremap` makes one longer by moving its
/// page table entries, so a pool's growth copies none of its entries.
#[cfg(target_os = "linux")]
mod zero_pages {
    use agent_core::grow::ZeroPages;

    fn map(bytes: usize) -> *mut u8 {
        // SAFETY: a new private anonymous mapping; no memory of ours is touched.
        let p = unsafe {
            libc::mmap(
                core::ptr::null_mut(),
                bytes,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        if p == libc::MAP_FAILED {
            core::ptr::null_mut()
        } else {
            p.cast()
        }
    }

    /// # Safety
    /// `p` is a mapping of `old` bytes made by `map` or `grow`.
    unsafe fn grow(p: *mut u8, old: usize, new: usize) -> *mut u8 {
        // SAFETY: the caller's mapping; on failure it stays as it was.
        let q = unsafe { libc::mremap(p.cast(), old, new, libc::MREMAP_MAYMOVE) };
        if q == libc::MAP_FAILED {
            core::ptr::null_mut()
        } else {
            q.cast()
        }
    }

    /// # Safety
    /// `p` is a mapping of `bytes` bytes made by `map` or `grow`, not used after.
    unsafe fn unmap(p: *mut u8, bytes: usize) {
        // SAFETY: the caller's mapping, which nothing uses any more.
        unsafe { libc::munmap(p.cast(), bytes) };
    }

    // SAFETY: `mmap` of private anonymous memory gives zeroed pages, page-aligned,
    // that nothing else uses; `mremap` with MREMAP_MAYMOVE keeps the contents (moved
    // with their pages), the new part zero, or fails leaving the mapping as it was.
    pub const PAGES: ZeroPages = unsafe { ZeroPages::new(map, grow, unmap) };
}

/// The banner line of the Debian build of CLIPS 6.30 this command line imitates.
pub const BANNER: &str = "         CLIPS (6.30 3/17/15)\n";

/// What to do with one file given on the command line.
enum Step {
    Batch {
        path: String,
        echo: bool,
    },
    Load(String),
    /// The banner line, printed between the start-up files and the command loop.
    Banner,
}

/// A file `open` opened, by its logical name.
enum OpenFile {
    /// Read a byte at a time; `back` is a byte `read` gave back.
    Read {
        file: std::io::BufReader<std::fs::File>,
        back: Option<u8>,
        /// The file's end was read: it stays ended (C's stdio keeps the end-of-file
        /// flag), even if a writer adds to the file after.
        ended: bool,
    },
    Write(std::io::BufWriter<std::fs::File>),
}

/// Standard input, shared by the prompt loop and the read functions.
struct Stdin {
    lines: std::io::StdinLock<'static>,
    back: Option<u8>,
}

impl Stdin {
    fn read_byte(&mut self) -> std::io::Result<Option<u8>> {
        if let Some(b) = self.back.take() {
            return Ok(Some(b));
        }
        let mut b = [0u8; 1];
        loop {
            match self.lines.read(&mut b) {
                Ok(0) => return Ok(None),
                Ok(_) => return Ok(Some(b[0])),
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
    }

    /// The next line (with its newline); empty at the end.
    fn read_line(&mut self, line: &mut String) -> std::io::Result<usize> {
        let mut n = 0;
        if let Some(b) = self.back.take() {
            line.push(char::from(b));
            n = 1;
            if b == b'\n' {
                return Ok(n);
            }
        }
        Ok(n + self.lines.read_line(line)?)
    }
}

/// What `CliHost::out` buffers for: a file on a copy of standard output's descriptor,
/// so that a flushed line is one `write` and nothing more. Through std's `Stdout` it
/// was buffered a second time behind a lock (a `LineWriter`): a flush took a second
/// lock, a search for the last newline and a second flush (join-100's two lines of
/// run-phase output cost 500 instructions more, callgrind). Std's `Stdout` where the
/// descriptor cannot be copied (closed: std's stdout drops what is written to it).
enum StdoutSink {
    #[cfg(unix)]
    Fd(std::fs::File),
    Std(std::io::Stdout),
}

impl StdoutSink {
    fn open() -> Self {
        #[cfg(unix)]
        {
            use std::os::fd::AsFd;
            if let Ok(fd) = std::io::stdout().as_fd().try_clone_to_owned() {
                return StdoutSink::Fd(std::fs::File::from(fd));
            }
        }
        StdoutSink::Std(std::io::stdout())
    }
}

impl Write for StdoutSink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            #[cfg(unix)]
            StdoutSink::Fd(f) => f.write(buf),
            StdoutSink::Std(s) => s.write(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            #[cfg(unix)]
            StdoutSink::Fd(_) => Ok(()),
            StdoutSink::Std(s) => s.flush(),
        }
    }
}

/// Host for the command line: every router goes to stdout (and to the dribble file,
/// with what is typed, while `dribble-on` has one open), but the logical names of files
/// `open` opened; files via std::fs.
struct CliHost {
    started: std::time::Instant,
    out: std::io::BufWriter<StdoutSink>,
    /// A `-f`/`-f2`/`-l` file could not be read, or a `-l` file hit something
    /// unrecoverable: the process exits non-zero (`exit_code`).
    failed: bool,
    files: HashMap<String, OpenFile>,
    stdin: Stdin,
    /// `dribble-on`'s file: a copy of what goes to the screen and of what is typed.
    dribble: Option<std::io::BufWriter<std::fs::File>>,
}

impl CliHost {
    /// Copies text to the dribble file, if one is open.
    fn copy_to_dribble(&mut self, text: &[u8]) {
        if let Some(d) = self.dribble.as_mut() {
            let _ = d.write_all(text);
        }
    }
}

impl CliHost {
    /// Output to a router, bytes as they are (`put-char` writes bytes that are no UTF-8).
    fn write_raw(&mut self, router: &str, text: &[u8]) {
        if !self.files.is_empty() {
            match self.files.get_mut(router) {
                Some(OpenFile::Write(f)) => {
                    // out at once, as CLIPS's file writes are: a reader of the same
                    // file sees them before the file is closed (and after a rule
                    // halted before its close)
                    let _ = f.write_all(text);
                    let _ = f.flush();
                    return;
                }
                // as CLIPS's fprintf to a file opened for reading: nothing written
                Some(OpenFile::Read { .. }) => return,
                None => {}
            }
        }
        let _ = self.out.write_all(text);
        // whole lines go out at once, as CLIPS's output does: a command that never
        // ends (killed by a timeout) leaves what came before it, its echo included
        if text.ends_with(b"\n") {
            let _ = self.out.flush();
        }
        self.copy_to_dribble(text);
    }
}

impl Host for CliHost {
    fn write_str(&mut self, router: &str, text: &str) {
        self.write_raw(router, text.as_bytes());
    }

    fn write_bytes(&mut self, router: &str, bytes: &[u8]) {
        self.write_raw(router, bytes);
    }

    fn dribble_on(&mut self, path: &str) -> Result<(), HostIoError> {
        self.dribble_off();
        let file = std::fs::File::create(path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => HostIoError::NotFound,
            _ => HostIoError::Other,
        })?;
        self.dribble = Some(std::io::BufWriter::new(file));
        Ok(())
    }

    fn dribble_off(&mut self) -> bool {
        match self.dribble.take() {
            Some(mut d) => d.flush().is_ok(),
            None => true,
        }
    }

    fn open_file(&mut self, name: &str, path: &str, mode: OpenMode) -> Result<(), HostIoError> {
        let mut options = std::fs::OpenOptions::new();
        match mode {
            OpenMode::Read => options.read(true),
            OpenMode::Write => options.write(true).create(true).truncate(true),
            OpenMode::Append => options.append(true).create(true),
        };
        let file = options.open(path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => HostIoError::NotFound,
            _ => HostIoError::Other,
        })?;
        let open = match mode {
            OpenMode::Read => OpenFile::Read {
                file: std::io::BufReader::new(file),
                back: None,
                ended: false,
            },
            OpenMode::Write | OpenMode::Append => OpenFile::Write(std::io::BufWriter::new(file)),
        };
        self.files.insert(name.to_string(), open);
        Ok(())
    }

    fn close_file(&mut self, name: &str) -> bool {
        match self.files.remove(name) {
            Some(OpenFile::Write(mut f)) => {
                let _ = f.flush();
                true
            }
            Some(OpenFile::Read { .. }) => true,
            None => false,
        }
    }

    fn close_all_files(&mut self) -> bool {
        let any = !self.files.is_empty();
        let names: Vec<String> = self.files.keys().cloned().collect();
        for name in names {
            self.close_file(&name);
        }
        any
    }

    fn is_open_file(&self, name: &str) -> bool {
        self.files.contains_key(name)
    }

    fn read_byte(&mut self, name: &str) -> Result<Option<u8>, HostIoError> {
        if name == "stdin" {
            // what was asked before the read is on the screen first
            let _ = self.out.flush();
            let fresh = self.stdin.back.is_none();
            let b = self.stdin.read_byte().map_err(|_| HostIoError::Other)?;
            // what is typed goes into the dribble file, as in CLIPS (a byte given
            // back and read again is copied once)
            if let (true, Some(b)) = (fresh, b) {
                self.copy_to_dribble(&[b]);
            }
            return Ok(b);
        }
        match self.files.get_mut(name) {
            Some(OpenFile::Read { file, back, ended }) => {
                if let Some(b) = back.take() {
                    return Ok(Some(b));
                }
                if *ended {
                    return Ok(None);
                }
                let mut b = [0u8; 1];
                match file.read(&mut b) {
                    Ok(0) => {
                        *ended = true;
                        Ok(None)
                    }
                    Ok(_) => Ok(Some(b[0])),
                    Err(_) => Err(HostIoError::Other),
                }
            }
            // a file opened for writing reads as ended, as in CLIPS
            Some(OpenFile::Write(_)) => Ok(None),
            None => Err(HostIoError::NotFound),
        }
    }

    fn unread_byte(&mut self, name: &str, byte: u8) {
        if name == "stdin" {
            self.stdin.back = Some(byte);
        } else if let Some(OpenFile::Read { back, .. }) = self.files.get_mut(name) {
            *back = Some(byte);
        }
    }

    fn remove_file(&mut self, path: &str) -> Result<(), HostIoError> {
        std::fs::remove_file(path).map_err(|_| HostIoError::Other)
    }

    fn rename_file(&mut self, from: &str, to: &str) -> Result<(), HostIoError> {
        std::fs::rename(from, to).map_err(|_| HostIoError::Other)
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

    /// Seconds since the command line started: CLIPS's `(time)` is a clock of the
    /// session too (small numbers), not the date.
    fn time(&mut self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
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

/// The engine thread's stack: deep enough for recursions as deep as CLIPS 6.30 goes
/// (it crashes near 20,000 levels of a one-line recursive deffunction; our limit of
/// 65,535 nested calls is about 21,800 such levels). Only the pages used are touched.
const CLI_STACK: usize = 256 << 20;

/// Stack the engine's depth check leaves unused: the frames above the outermost call
/// and those of one level (a parse of `eval` or `build` nests 200 levels).
const CLI_STACK_MARGIN: usize = 32 << 20;

pub fn main(args: Args) -> ExitCode {
    let steps = match parse_steps(&args.options) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("robotino-agent clips: {e}");
            return ExitCode::FAILURE;
        }
    };
    // (`--large-pools` is the same engine: its pools grow)
    let _ = args.large_pools;
    let limit = match args.pool_limit {
        Some(n) => Capacities::uniform(n),
        None => GrowStorage::NO_LIMIT,
    };
    // (the storage is made on the engine's thread, after the thread's own allocations)
    let worker = std::thread::Builder::new()
        .stack_size(CLI_STACK)
        .spawn(move || {
            let mut engine = GrowEngine::with_storage(cli_storage(limit));
            engine.set_depth_limits(u16::MAX, CLI_STACK - CLI_STACK_MARGIN);
            session(&mut engine, steps)
        });
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => code,
        _ => ExitCode::FAILURE,
    }
}

/// The engine calls the command line makes.
trait CliEngine {
    fn run_pending_batch(&mut self, host: &mut dyn Host) -> bool;
    fn batch_path(&mut self, host: &mut dyn Host, path: &str) -> bool;
    fn batch_file_quiet(&mut self, host: &mut dyn Host, name: &str, text: &str) -> bool;
    fn load_str(&mut self, host: &mut dyn Host, name: &str, text: &str)
        -> Result<usize, LoadError>;
    fn exec_command(&mut self, host: &mut dyn Host, text: &str, source: &str) -> bool;
    fn exit_status(&self) -> i32;
    fn hit_unrecoverable(&self) -> bool;
    fn take_batch_carry(&mut self) -> Option<(String, u64)>;
}

macro_rules! cli_engine {
    ($ty:ty) => {
        impl CliEngine for $ty {
            fn run_pending_batch(&mut self, host: &mut dyn Host) -> bool {
                <$ty>::run_pending_batch(self, host)
            }
            fn batch_path(&mut self, host: &mut dyn Host, path: &str) -> bool {
                <$ty>::batch_path(self, host, path)
            }
            fn batch_file_quiet(&mut self, host: &mut dyn Host, name: &str, text: &str) -> bool {
                <$ty>::batch_file_quiet(self, host, name, text)
            }
            fn load_str(
                &mut self,
                host: &mut dyn Host,
                name: &str,
                text: &str,
            ) -> Result<usize, LoadError> {
                <$ty>::load_str(self, host, name, text)
            }
            fn exec_command(&mut self, host: &mut dyn Host, text: &str, source: &str) -> bool {
                <$ty>::exec_command(self, host, text, source)
            }
            fn exit_status(&self) -> i32 {
                <$ty>::exit_status(self)
            }
            fn hit_unrecoverable(&self) -> bool {
                <$ty>::hit_unrecoverable(self)
            }
            fn take_batch_carry(&mut self) -> Option<(String, u64)> {
                <$ty>::take_batch_carry(self).map(|(p, o)| (p.to_string(), o))
            }
        }
    };
}
cli_engine!(GrowEngine);

fn session(engine: &mut dyn CliEngine, steps: Vec<Step>) -> ExitCode {
    let mut host = CliHost {
        started: std::time::Instant::now(),
        out: std::io::BufWriter::new(StdoutSink::open()),
        failed: false,
        files: HashMap::new(),
        stdin: Stdin {
            lines: std::io::stdin().lock(),
            back: None,
        },
        dribble: None,
    };
    // As CLIPS: `-l` and `-f2` files run at start-up, before the banner; `-f` files are
    // read by the command loop after it, as if typed at the prompt.
    let (startup, batches): (Vec<Step>, Vec<Step>) = steps
        .into_iter()
        .partition(|s| !matches!(s, Step::Batch { echo: true, .. }));
    for step in startup
        .into_iter()
        .chain(std::iter::once(Step::Banner))
        .chain(batches)
    {
        if !run_step(engine, &mut host, step) {
            let _ = host.out.flush();
            host.dribble_off();
            return exit_code(engine, &host, true);
        }
    }
    interactive(engine, &mut host);
    let _ = host.out.flush();
    host.dribble_off();
    exit_code(engine, &host, false)
}

/// The process status: `(exit N)`'s N; else 1 when a file could not be read, a pool ran
/// out or the input ended inside a construct (CLIPS exits 0 then: a deliberate
/// difference, so scripts can tell), else 0.
fn exit_code(engine: &dyn CliEngine, host: &CliHost, exited: bool) -> ExitCode {
    let status = engine.exit_status();
    if exited && status != 0 {
        // as the shell sees it: the low 8 bits
        return ExitCode::from(status as u8);
    }
    if host.failed || engine.hit_unrecoverable() {
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

/// Runs one step; false once `(exit)` ran.
fn run_step(engine: &mut dyn CliEngine, host: &mut CliHost, step: Step) -> bool {
    match step {
        Step::Banner => {
            // CLIPS 6.30's own banner, so transcripts (and tools reading them) match
            host.write_str("stdout", BANNER);
            // a `batch` run by a start-up file is the command loop's first input
            engine.run_pending_batch(host)
        }
        // streamed by the engine, so that reads from stdin take its lines (the items
        // before bytes that are not UTF-8 run, then the engine reports them)
        Step::Batch { path, echo: true } => match std::fs::File::open(&path) {
            Ok(_) => engine.batch_path(host, &path),
            Err(e) => {
                let _ = host.out.flush();
                eprintln!("robotino-agent clips: cannot read {path}: {e}");
                host.failed = true;
                true
            }
        },
        Step::Batch { path, echo: false } => match read_text(&path) {
            Ok(text) => engine.batch_file_quiet(host, &path, &text),
            Err(e) => {
                let _ = host.out.flush();
                eprintln!("robotino-agent clips: {e}");
                host.failed = true;
                true
            }
        },
        Step::Load(path) => match read_text(&path) {
            Ok(text) => {
                if let Err(e) = engine.load_str(host, &path, &text) {
                    if e.capacity.is_some() || e.expected == agent_core::INPUT_ENDED {
                        host.failed = true;
                    }
                    host.write_str(
                        "werror",
                        &format!("\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {}.\n--> {path}:{}:{}: expected {}\n", e.construct, e.line, e.col, e.expected),
                    );
                }
                true
            }
            Err(e) => {
                eprintln!("robotino-agent clips: {e}");
                host.failed = true;
                true
            }
        },
    }
}

/// A file's text; an error names the file, and for bytes that are not UTF-8 (CLIPS
/// reads bytes, we read UTF-8 text) the line and column of the first.
fn read_text(path: &str) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = std::str::from_utf8(&bytes[..at]).unwrap_or("");
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
        format!(
            "{path}:{line}:{col}: byte 0x{:02X} is not UTF-8: robotino-agent reads UTF-8 text only",
            bytes[at]
        )
    })
}

/// What a batch file that ended inside a command left of it (CLIPS reads on in the
/// prompt's input): the file's text from where the command starts.
fn batch_carry(engine: &mut dyn CliEngine) -> String {
    let Some((path, offset)) = engine.take_batch_carry() else {
        return String::new();
    };
    let text = std::fs::read(&path).unwrap_or_default();
    let start = usize::try_from(offset)
        .unwrap_or(usize::MAX)
        .min(text.len());
    String::from_utf8_lossy(&text[start..]).into_owned()
}

/// The prompt loop on standard input.
fn interactive(engine: &mut dyn CliEngine, host: &mut CliHost) {
    let mut buf = batch_carry(engine);
    // a prompt comes at the start and after each command, not after a blank line
    let mut done_command = true;
    loop {
        if buf.trim().is_empty() {
            buf.clear();
            if done_command {
                host.write_str("stdout", "CLIPS> ");
            }
        }
        done_command = false;
        let _ = host.out.flush();
        let mut line = String::new();
        // a byte a read gave back went into the dribble file when it was read
        let given_back = usize::from(host.stdin.back.is_some());
        match host.stdin.read_line(&mut line) {
            Ok(0) | Err(_) => return,
            Ok(_) => {}
        }
        // a typed command goes into the dribble file, as in CLIPS
        host.copy_to_dribble(line.as_bytes().get(given_back..).unwrap_or_default());
        buf.push_str(&line);
        if let Some(k) = command_complete(&buf) {
            let cmd: String = buf[..k].to_string();
            buf.clear();
            if !engine.exec_command(host, &cmd, "stdin") {
                return;
            }
            buf = batch_carry(engine);
            done_command = true;
        }
    }
}
