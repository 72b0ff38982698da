//! The engine's window to the outside: output routers, files, time.

use crate::error::HostIoError;

/// Router names the engine writes to.
pub mod router {
    /// `printout t`.
    pub const STDOUT: &str = "stdout";
    /// Watch traces (`==> f-1 ...`, `FIRE ...`).
    pub const WTRACE: &str = "wtrace";
    /// Listings (`facts`, `agenda`) and command results.
    pub const WDISPLAY: &str = "wdisplay";
    /// Error messages.
    pub const WERROR: &str = "werror";
    /// Warnings.
    pub const WWARNING: &str = "wwarning";
}

/// Everything the engine needs from its environment. All methods but `write_str` have
/// defaults so a minimal host is one function.
pub trait Host {
    /// Output to a router (see `router`); `printout` to other logical names passes them
    /// through unchanged.
    fn write_str(&mut self, router: &str, text: &str);
    /// Raw bytes to a router: `put-char`'s byte, which CLIPS writes as it is (a code of
    /// 128-255 is no UTF-8 text on its own). The default, for hosts whose output is
    /// text, writes UTF-8 as text and any other byte as the character of its code.
    /// (With `parser`: its one caller, `put-char`, is in `builtins::io`, which needs
    /// the reader and which the agent image leaves out.)
    #[cfg(feature = "parser")]
    fn write_bytes(&mut self, router: &str, bytes: &[u8]) {
        match core::str::from_utf8(bytes) {
            Ok(text) => self.write_str(router, text),
            Err(_) => {
                for &b in bytes {
                    let mut buf = [0u8; 4];
                    self.write_str(router, char::from(b).encode_utf8(&mut buf));
                }
            }
        }
    }
    /// Reads a whole file into `buf`, returning its length (`TooLarge` when it does not
    /// fit).
    fn read_file(&mut self, _path: &str, _buf: &mut [u8]) -> Result<usize, HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Reads up to `buf.len()` bytes of a file from byte `offset` on, returning how many
    /// (0 at the end). The engine streams files through a fixed buffer with this, so a
    /// host that implements it can have files of any size loaded. The default serves
    /// files that fit the buffer whole through `read_file`.
    fn read_file_at(
        &mut self,
        path: &str,
        offset: u64,
        buf: &mut [u8],
    ) -> Result<usize, HostIoError> {
        if offset == 0 {
            self.read_file(path, buf)
        } else {
            Ok(0)
        }
    }
    fn write_file(&mut self, _path: &str, _data: &[u8], _append: bool) -> Result<(), HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Seconds, for `(time)`.
    fn time(&mut self) -> f64 {
        0.0
    }
    /// Opens file `path` as logical name `name` (`open`): output to the name comes
    /// through [`Host::write_str`] with it as the router, input through
    /// [`Host::read_byte`]. The engine has checked that the name is free; a host
    /// without files (the robot) refuses with `Unsupported`, and `open` says so.
    fn open_file(&mut self, _name: &str, _path: &str, _mode: OpenMode) -> Result<(), HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Closes the file opened as `name`; false when no file has that name.
    fn close_file(&mut self, _name: &str) -> bool {
        false
    }
    /// Closes every open file (`(close)`); false when none was open.
    fn close_all_files(&mut self) -> bool {
        false
    }
    /// Whether `name` is the logical name of a file this host opened.
    fn is_open_file(&self, _name: &str) -> bool {
        false
    }
    /// The next byte of input `name`: standard input for `stdin`, else a file opened
    /// with [`Host::open_file`]; `Ok(None)` at its end. `Unsupported` when the host has
    /// no such input (`read` reports it rather than pretending the input ended).
    fn read_byte(&mut self, _name: &str) -> Result<Option<u8>, HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Gives back the byte [`Host::read_byte`] returned last for `name`: the next read
    /// returns it again (`read` stops at the character after a token, as CLIPS does).
    fn unread_byte(&mut self, _name: &str, _byte: u8) {}
    /// Deletes a file (`remove`).
    fn remove_file(&mut self, _path: &str) -> Result<(), HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Renames a file (`rename`).
    fn rename_file(&mut self, _from: &str, _to: &str) -> Result<(), HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Starts copying everything the engine writes to the screen (every router but the
    /// logical names of files `open` opened) into file `path`, created or emptied
    /// (`dribble-on`); a dribble file already open is closed first, as CLIPS does. A
    /// host without files (the robot) refuses with `Unsupported`, and `dribble-on` says
    /// so; any other error is a file that could not be opened.
    fn dribble_on(&mut self, _path: &str) -> Result<(), HostIoError> {
        Err(HostIoError::Unsupported)
    }
    /// Stops copying and closes the dribble file, if one is open (`dribble-off`); false
    /// when closing it failed.
    fn dribble_off(&mut self) -> bool {
        true
    }
    /// Polled once per iteration of `while`, `loop-for-count`, `progn$`/`foreach`, of a
    /// fact-set query's walk, once per rule firing of `run` and, if the host asked
    /// (`Engine::set_poll_calls`, feature `extras`), once per deffunction call:
    /// returning true stops the current execution (as CLIPS's keyboard interrupt does)
    /// with `EvalErrorKind::Interrupted`. A robot's watchdog or stop button, or a
    /// fuzzer's step or time budget, ends runaway programs with it. The engine stays
    /// consistent; it polls again in the next loop, so a host that keeps returning
    /// true stops every loop until it is rearmed.
    fn interrupt(&mut self) -> bool {
        false
    }
    /// True when `interrupt` always returns false (feature `host-speedups`): `run`
    /// asks once and then leaves out its per-firing poll. A host that may stop a run
    /// keeps the default (false); the loops inside a rule's actions poll either way.
    #[cfg(feature = "host-speedups")]
    fn never_interrupts(&self) -> bool {
        false
    }
}

/// How `open` opens a file: CLIPS's modes `"r"`, `"w"`, `"a"` (and their `b` forms,
/// the same on the hosts we have).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpenMode {
    Read,
    /// Created, or emptied if it exists.
    Write,
    /// Created if missing, written at its end.
    Append,
}

/// A host that drops all output.
pub struct NullHost;

impl Host for NullHost {
    fn write_str(&mut self, _router: &str, _text: &str) {}
}

/// Adapter so `core::fmt::Write` can target a router.
pub struct RouterWriter<'h> {
    pub host: &'h mut dyn Host,
    pub router: &'h str,
}

impl core::fmt::Write for RouterWriter<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        self.host.write_str(self.router, s);
        Ok(())
    }
}
