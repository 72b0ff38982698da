//! Reading command and construct files (`load`, `load*`, `batch`, `batch*`,
//! `load-facts`) through a fixed buffer, one top-level item at a time.
//!
//! The engine has no heap, so a file is streamed through a buffer of [`FILE_BUF`] bytes
//! with [`Host::read_file_at`](crate::host::Host::read_file_at): any file size works as
//! long as each single top-level item (a construct or a command) fits the buffer. An
//! item that does not is an error naming the limit, never silently cut. On the host
//! (`grow`) the buffer doubles instead, up to [`FILE_ITEM_MAX`]: CLIPS's reader has no
//! item limit, and programs by others hold rules of 40 KB and more.

use core::fmt::Write;

use crate::engine::Core;
use crate::error::HostIoError;
use crate::host::router;
use crate::lexer::skip_blanks;
use crate::value::TextBuf;

/// Size of the stack buffer a file is streamed through; also the largest single item
/// where the buffer cannot grow.
pub const FILE_BUF: usize = 32 * 1024;

/// The largest single item a growing buffer takes (`grow`).
pub const FILE_ITEM_MAX: usize = 16 * 1024 * 1024;

/// Storage a file is streamed through.
pub trait FileBuffer {
    fn bytes(&self) -> &[u8];
    fn bytes_mut(&mut self) -> &mut [u8];
    /// Makes room for an item longer than the buffer; false when it cannot.
    fn enlarge(&mut self) -> bool {
        false
    }
}

impl FileBuffer for &mut [u8] {
    fn bytes(&self) -> &[u8] {
        self
    }
    fn bytes_mut(&mut self) -> &mut [u8] {
        self
    }
}

impl<const N: usize> FileBuffer for [u8; N] {
    fn bytes(&self) -> &[u8] {
        self
    }
    fn bytes_mut(&mut self) -> &mut [u8] {
        self
    }
}

#[cfg(feature = "grow")]
impl FileBuffer for alloc::vec::Vec<u8> {
    fn bytes(&self) -> &[u8] {
        self
    }
    fn bytes_mut(&mut self) -> &mut [u8] {
        self
    }
    fn enlarge(&mut self) -> bool {
        let len = self.len();
        if len >= FILE_ITEM_MAX {
            return false;
        }
        self.resize((len * 2).clamp(FILE_BUF, FILE_ITEM_MAX), 0);
        true
    }
}

/// The buffer `load`, `batch` and `load-facts` read through: fixed on the robot,
/// growing on the host.
#[cfg(not(feature = "grow"))]
pub fn file_buffer() -> [u8; FILE_BUF] {
    [0; FILE_BUF]
}

/// The buffer `load`, `batch` and `load-facts` read through: fixed on the robot,
/// growing on the host.
#[cfg(feature = "grow")]
pub fn file_buffer() -> alloc::vec::Vec<u8> {
    alloc::vec![0; FILE_BUF]
}

/// Why a file could not be read to its end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileError {
    /// The host could not open or read it.
    Io(HostIoError),
    /// One item is longer than the buffer: where it starts (byte offset, 1-based line).
    ItemTooLarge {
        offset: u64,
        line: u32,
        limit: usize,
    },
    /// Bytes that are not UTF-8: the first one, its byte offset, 1-based line and
    /// column (in characters).
    NotUtf8 {
        offset: u64,
        line: u32,
        col: u32,
        byte: u8,
    },
}

/// Top-level items of one file, read through `buf`.
pub struct FileItems<B> {
    path: TextBuf<256>,
    buf: B,
    /// Unconsumed bytes are `buf[start..end]`.
    start: usize,
    end: usize,
    /// `buf[start..checked]` is known to be UTF-8 (each byte is checked once).
    checked: usize,
    /// File offset of `buf[end]`.
    offset: u64,
    eof: bool,
    /// Newlines before `buf[start]`.
    lines: u32,
    /// Characters between the last of those newlines and `buf[start]`.
    col: u32,
    /// Host: how far the walk through the item at `buf[start..]` got (positions from
    /// `start`: they stay when the buffer's bytes move to its front).
    #[cfg(feature = "host-speedups")]
    scan: crate::lexer::ItemScan,
}

/// One item: its text, the item's own length in it, and the number of newlines in the
/// file before it.
pub struct Item<'s> {
    pub text: &'s str,
    pub len: usize,
    pub line_base: u32,
    /// The rest of the file, holding no complete item.
    pub last: bool,
    /// File offset of the byte after the item.
    pub end_offset: u64,
}

impl<B: FileBuffer> FileItems<B> {
    pub fn new(path: &str, buf: B) -> Self {
        let mut p = TextBuf::new();
        let _ = p.write_str(path);
        FileItems {
            path: p,
            buf,
            start: 0,
            end: 0,
            checked: 0,
            offset: 0,
            eof: false,
            lines: 0,
            col: 0,
            #[cfg(feature = "host-speedups")]
            scan: crate::lexer::ItemScan::NEW,
        }
    }

    pub fn path(&self) -> &str {
        self.path.as_str()
    }

    /// Goes on from file offset `offset`, `lines` newlines further than `position()`
    /// (bytes read past meanwhile: a command's `read` took batch lines).
    pub fn skip_to(&mut self, offset: u64, lines: u32) {
        self.start = 0;
        self.end = 0;
        self.checked = 0;
        self.offset = offset;
        self.eof = false;
        self.lines += lines;
        self.col = 0;
        #[cfg(feature = "host-speedups")]
        {
            self.scan = crate::lexer::ItemScan::NEW;
        }
    }

    /// Goes on from file offset `offset`, with `lines` newlines before it (a position
    /// before or after the one read to).
    pub fn seek(&mut self, offset: u64, lines: u32) {
        self.skip_to(offset, 0);
        self.lines = lines;
    }

    /// Reads the first bytes, so a missing file is reported before anything runs.
    pub fn open(&mut self, cx: &mut Core<'_>) -> Result<(), FileError> {
        self.fill(cx)
    }

    /// The next complete item (leading blanks and comments included); at the end of the
    /// file whatever is left (possibly an incomplete command), then `None`.
    pub fn next_item(&mut self, cx: &mut Core<'_>) -> Result<Option<Item<'_>>, FileError> {
        self.next(cx, false)
    }

    /// Like `next_item`, but the text runs on to the end of the line the item ends on
    /// (CLIPS's batch mode echoes that rest of the line and ignores it); `Item::len` is
    /// the item's own length.
    pub fn next_command(&mut self, cx: &mut Core<'_>) -> Result<Option<Item<'_>>, FileError> {
        self.next(cx, true)
    }

    fn next(
        &mut self,
        cx: &mut Core<'_>,
        whole_lines: bool,
    ) -> Result<Option<Item<'_>>, FileError> {
        let mut last = false;
        let (a, b, len) = loop {
            // the bytes read since the last look (a whole buffer's each time would
            // check a file's bytes once per item)
            self.checked = self.checked.max(self.start);
            // where bytes that are not UTF-8 start: the items before them still run
            let mut bad = false;
            match core::str::from_utf8(&self.buf.bytes()[self.checked..self.end]) {
                Ok(_) => self.checked = self.end,
                Err(e) => {
                    // (a character cut by the buffer's end: valid prefix only)
                    self.checked += e.valid_up_to();
                    bad = e.error_len().is_some() || self.eof;
                }
            }
            let valid = &self.buf.bytes()[self.start..self.checked];
            // host: a long item's walk goes on where the last read's stopped
            #[cfg(feature = "host-speedups")]
            let found = crate::lexer::item_end_resumed(valid, &mut self.scan);
            #[cfg(not(feature = "host-speedups"))]
            let found = crate::lexer::item_end(valid);
            if let Some(k) = found {
                if !whole_lines {
                    break (self.start, self.start + k, k);
                }
                // a line ends at `\n`, or at a `\r` not followed by one (CLIPS tests a
                // command for completeness at either); `\r\n` stays whole
                match valid[k..].iter().position(|&c| c == b'\n' || c == b'\r') {
                    Some(nl) if valid[k + nl] == b'\n' => {
                        break (self.start, self.start + k + nl + 1, k)
                    }
                    Some(nl) if k + nl + 1 < valid.len() => {
                        let n = usize::from(valid[k + nl + 1] == b'\n');
                        break (self.start, self.start + k + nl + 1 + n, k);
                    }
                    Some(_) | None if self.eof && !bad => break (self.start, self.end, k),
                    _ => {} // read on to the end of the line (or past a final `\r`)
                }
            } else if self.eof && !bad {
                if self.start == self.end {
                    return Ok(None);
                }
                last = true;
                break (self.start, self.end, self.end - self.start);
            }
            if bad {
                return Err(self.not_utf8());
            }
            if self.start > 0 {
                self.buf.bytes_mut().copy_within(self.start..self.end, 0);
                self.end -= self.start;
                self.checked -= self.start;
                self.start = 0;
            }
            if self.end == self.buf.bytes().len() {
                // a long run of comments and blank lines is handed out on its own
                let valid = &self.buf.bytes()[..self.checked];
                let lead = skip_blanks(valid, 0);
                let cut = valid[..lead]
                    .iter()
                    .rposition(|&c| c == b'\n')
                    .map_or(lead, |k| k + 1);
                if cut > 0 {
                    break (0, cut, cut);
                }
                let limit = self.buf.bytes().len();
                if !self.buf.enlarge() {
                    return Err(FileError::ItemTooLarge {
                        offset: self.offset - self.end as u64,
                        line: self.lines + 1,
                        limit,
                    });
                }
            }
            self.fill(cx)?;
        };
        // (the next item's walk starts afresh)
        #[cfg(feature = "host-speedups")]
        {
            self.scan = crate::lexer::ItemScan::NEW;
        }
        self.start = b;
        let line_base = self.lines;
        let text = core::str::from_utf8(&self.buf.bytes()[a..b]).unwrap_or("");
        self.lines += text.bytes().filter(|&c| c == b'\n').count() as u32;
        self.col = match text.rfind('\n') {
            Some(p) => text[p + 1..].chars().count() as u32,
            None => self.col + text.chars().count() as u32,
        };
        let end_offset = self.offset - (self.end - b) as u64;
        Ok(Some(Item {
            text,
            len,
            line_base,
            last,
            end_offset,
        }))
    }

    /// The error for the bytes at `buf[checked]`, which are not UTF-8.
    #[cold]
    fn not_utf8(&self) -> FileError {
        let at = self.checked;
        let before = core::str::from_utf8(&self.buf.bytes()[self.start..at]).unwrap_or("");
        let newlines = before.bytes().filter(|&c| c == b'\n').count() as u32;
        let col = match before.rfind('\n') {
            Some(p) => before[p + 1..].chars().count() as u32,
            None => self.col + before.chars().count() as u32,
        };
        FileError::NotUtf8 {
            offset: self.offset - (self.end - at) as u64,
            line: self.lines + newlines + 1,
            col: col + 1,
            byte: self.buf.bytes().get(at).copied().unwrap_or(0),
        }
    }

    fn fill(&mut self, cx: &mut Core<'_>) -> Result<(), FileError> {
        let n = cx
            .host
            .read_file_at(
                self.path.as_str(),
                self.offset,
                &mut self.buf.bytes_mut()[self.end..],
            )
            .map_err(FileError::Io)?;
        if n == 0 {
            self.eof = true;
        }
        self.end += n;
        self.offset += n as u64;
        Ok(())
    }
}

impl Core<'_> {
    /// `[ARGACCES2]`: CLIPS's message for a file `func` cannot open.
    pub fn report_unopened_file(&mut self, func: &str, path: &str) {
        let mut b: TextBuf<320> = TextBuf::new();
        let _ = writeln!(
            b,
            "[ARGACCES2] Function {func} was unable to open file {path}."
        );
        self.write(router::WERROR, b.as_str());
    }

    /// A file that stopped being readable part way (CLIPS has no such message: its
    /// reader has no size limit).
    #[cold]
    pub fn report_file_error(&mut self, func: &str, path: &str, e: FileError) {
        let mut b: TextBuf<400> = TextBuf::new();
        let _ = write!(b, "[FILEIO] Function {func}: file {path}: ");
        let _ = match e {
            FileError::Io(HostIoError::TooLarge) => {
                writeln!(b, "larger than the host reads at once ({FILE_BUF} bytes).")
            }
            FileError::Io(_) => writeln!(b, "reading failed."),
            FileError::ItemTooLarge {
                offset,
                line,
                limit,
            } => writeln!(
                b,
                "the item at line {line} (byte {offset}) is longer than the {limit}-byte buffer."
            ),
            FileError::NotUtf8 {
                offset,
                line,
                col,
                byte,
            } => writeln!(
                b,
                "byte 0x{byte:02X} at line {line}, column {col} (offset {offset}) is not UTF-8: robotino-agent reads UTF-8 text only."
            ),
        };
        self.write(router::WERROR, b.as_str());
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::engine::SmallEngine;
    use crate::host::Host;
    use std::string::String;

    /// A host whose one file is `text`.
    struct OneFile {
        text: String,
    }

    impl Host for OneFile {
        fn write_str(&mut self, _router: &str, _text: &str) {}
        fn read_file_at(
            &mut self,
            _path: &str,
            offset: u64,
            buf: &mut [u8],
        ) -> Result<usize, HostIoError> {
            let b = self.text.as_bytes();
            let from = (offset as usize).min(b.len());
            let n = buf.len().min(b.len() - from);
            buf[..n].copy_from_slice(&b[from..from + n]);
            Ok(n)
        }
    }

    fn items(text: &str, bufsize: usize) -> Result<std::vec::Vec<(String, u32)>, FileError> {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let mut h = OneFile { text: text.into() };
        let mut cx = e.core(&mut h);
        let mut buf = std::vec![0u8; bufsize];
        let mut f = FileItems::new("x", &mut buf[..]);
        let mut out = std::vec::Vec::new();
        while let Some(it) = f.next_item(&mut cx)? {
            out.push((String::from(it.text), it.line_base));
        }
        Ok(out)
    }

    /// The items without comment-only pieces, trimmed.
    fn commands(got: &[(String, u32)]) -> std::vec::Vec<String> {
        got.iter()
            .map(|(t, _)| {
                let code: std::vec::Vec<&str> = t
                    .lines()
                    .map(str::trim)
                    .filter(|l| !l.is_empty() && !l.starts_with(';'))
                    .collect();
                code.join("\n")
            })
            .filter(|c| !c.is_empty())
            .collect()
    }

    /// A host whose one file is `bytes`.
    struct OneByteFile(&'static [u8]);

    impl Host for OneByteFile {
        fn write_str(&mut self, _router: &str, _text: &str) {}
        fn read_file_at(
            &mut self,
            _path: &str,
            offset: u64,
            buf: &mut [u8],
        ) -> Result<usize, HostIoError> {
            let from = (offset as usize).min(self.0.len());
            let n = buf.len().min(self.0.len() - from);
            buf[..n].copy_from_slice(&self.0[from..from + n]);
            Ok(n)
        }
    }

    #[test]
    fn items_before_bytes_not_utf8_come_then_where_they_are() {
        // a Latin-1 byte 0xE9 in the third item, after a UTF-8 `é` in the second
        let text: &[u8] = b"(a 1)\n(b \"\xC3\xA9\")(c \"x\xE9y\")\n(d)\n";
        for size in [12, 16, 4096] {
            let mut e = std::boxed::Box::new(SmallEngine::new());
            let mut h = OneByteFile(text);
            let mut cx = e.core(&mut h);
            let mut buf = std::vec![0u8; size];
            let mut f = FileItems::new("x", &mut buf[..]);
            let mut got = std::vec::Vec::new();
            let err = loop {
                match f.next_item(&mut cx) {
                    Ok(Some(it)) => got.push(String::from(it.text.trim())),
                    Ok(None) => panic!("buffer {size}: read past the bad byte"),
                    Err(e) => break e,
                }
            };
            assert_eq!(got, ["(a 1)", "(b \"é\")"], "buffer {size}");
            match err {
                FileError::NotUtf8 {
                    offset,
                    line,
                    col,
                    byte,
                } => assert_eq!(
                    (offset, line, col, byte),
                    (19, 2, 13, 0xE9),
                    "buffer {size}"
                ),
                _ => panic!("buffer {size}: another error"),
            }
        }
    }

    #[test]
    fn items_come_whole_across_buffer_refills() {
        let text = "(a 1)\n; c\n(b \"x y\")\n(cé\n d)\n";
        for size in [12, 16, 4096] {
            let got = items(text, size).unwrap();
            let joined: String = got.iter().map(|(t, _)| t.as_str()).collect();
            assert_eq!(joined, text, "buffer {size}");
            assert_eq!(
                commands(&got),
                ["(a 1)", "(b \"x y\")", "(cé\nd)"],
                "buffer {size}"
            );
            let c = got.iter().find(|(t, _)| t.contains("(cé")).unwrap();
            assert_eq!(
                c.1 + c
                    .0
                    .find("(cé")
                    .map_or(0, |k| c.0[..k].matches('\n').count() as u32),
                3
            );
        }
    }

    #[test]
    fn long_comment_runs_come_in_pieces() {
        let mut text = String::new();
        for _ in 0..10 {
            text.push_str("; a comment line\n");
        }
        text.push_str("(a 1)");
        let got = items(&text, 40).unwrap();
        let joined: String = got.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(joined, text);
        assert_eq!(commands(&got), ["(a 1)"]);
    }

    #[test]
    fn an_item_longer_than_the_buffer_is_an_error_with_the_limit() {
        let e = items("(a)\n(bbbbbbbbbbbbbbbbbbbbbbbb)", 10).unwrap_err();
        assert_eq!(
            e,
            FileError::ItemTooLarge {
                offset: 4,
                line: 2,
                limit: 10
            }
        );
    }

    /// On the host the buffer doubles for an item longer than it, as CLIPS reads items
    /// of any length (the sudoku 5x5 puzzles of CLIPS's examples hold a 46 KB rule).
    #[cfg(feature = "grow")]
    #[test]
    fn a_growing_buffer_takes_an_item_longer_than_it() {
        let mut long = String::from("(a");
        while long.len() < 3 * FILE_BUF {
            long.push_str(" xyzzy");
        }
        long.push(')');
        let text = std::format!("(x)\n{long}\n(b 2)\n");
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let mut h = OneFile { text: text.clone() };
        let mut cx = e.core(&mut h);
        let mut f = FileItems::new("x", file_buffer());
        let mut got = std::vec::Vec::new();
        while let Some(it) = f.next_item(&mut cx).unwrap() {
            got.push(String::from(it.text));
        }
        assert_eq!(got.concat(), text);
        assert_eq!(commands_of(&got), ["(x)", long.as_str(), "(b 2)"]);
    }

    #[cfg(feature = "grow")]
    fn commands_of(items: &[String]) -> std::vec::Vec<String> {
        let pairs: std::vec::Vec<(String, u32)> = items.iter().map(|t| (t.clone(), 0)).collect();
        commands(&pairs)
    }
}
