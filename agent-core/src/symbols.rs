//! The symbol table: interned symbol and string texts in one byte arena, found by hash.
//!
//! Symbols and strings share entries (the value's type says which). Entries are only
//! appended; a failed load truncates back to a mark (`truncate`).

use crate::error::{CapacityError, Pool};
use crate::value::Ix;
use crate::value::{SymId, NONE};

/// Whether two texts are equal, usable in constants (`==` on `str` is not `const`):
/// names looked up at compile time (builtins, error texts, rule files).
pub const fn same_text(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

#[derive(Clone, Copy, Debug)]
pub struct SymEntry {
    pub start: Ix,
    pub len: Ix,
    /// Next entry in the same hash bucket.
    pub next: Ix,
    /// With `grow`: the text's [`hash_bytes`], so a table that grows puts its symbols in
    /// their new buckets without reading their texts again (`Core::rehash_symbols`).
    #[cfg(feature = "grow")]
    pub hash: u32,
}

impl SymEntry {
    pub const EMPTY: SymEntry = SymEntry {
        start: 0,
        len: 0,
        next: NONE,
        #[cfg(feature = "grow")]
        hash: 0,
    };
}

/// The head of a symbol hash bucket: the newest symbol's id in the bucket, or none.
/// With `grow` it holds the id's complement, so the empty head is all-zero bytes and a
/// table grows into zeroed memory (fresh pages) without writing one head
/// (`Core::rehash_symbols`); without it, the id itself (the robot's table is fixed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(transparent)]
pub struct Head(Ix);

impl Head {
    /// No symbol in the bucket.
    pub const EMPTY: Head = Head::of(NONE);

    /// The head that names `id` (`NONE`: [`Head::EMPTY`]).
    #[inline(always)]
    pub const fn of(id: Ix) -> Head {
        #[cfg(feature = "grow")]
        let h = Head(!id);
        #[cfg(not(feature = "grow"))]
        let h = Head(id);
        h
    }

    /// The id this head names, `NONE` for an empty bucket.
    #[inline(always)]
    pub const fn get(self) -> Ix {
        #[cfg(feature = "grow")]
        let id = !self.0;
        #[cfg(not(feature = "grow"))]
        let id = self.0;
        id
    }
}

/// FNV-1a over bytes; cheap and good enough for bucket spreading. `const`, so a
/// compiled rule base's hash chains are worked out when it compiles ([`SymbolIndex`]).
pub const fn hash_bytes(b: &[u8]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    let mut i = 0;
    while i < b.len() {
        h ^= b[i] as u32;
        h = h.wrapping_mul(0x0100_0193);
        i += 1;
    }
    h
}

/// The hash chains of a compiled rule base's symbols (one bucket per symbol), built
/// by the compiler from the texts (`SymbolIndex::new` is `const`), so the engine
/// finds them in place without copying them into its arena (feature `in-place`).
pub struct SymbolIndex<const N: usize> {
    /// Newest id first in each bucket, as the engine's own table.
    pub buckets: [Ix; N],
    pub next: [Ix; N],
}

impl<const N: usize> SymbolIndex<N> {
    pub const fn new(texts: &[&str; N]) -> Self {
        let mut buckets = [NONE; N];
        let mut next = [NONE; N];
        let mut id = 0;
        while id < N {
            let b = hash_bytes(texts[id].as_bytes()) as usize % N;
            next[id] = buckets[b];
            buckets[b] = id as Ix;
            id += 1;
        }
        SymbolIndex { buckets, next }
    }
}

/// A compiled rule base's symbols read in place: ids `0..texts.len()`, before the
/// arena's (all empty without `in-place`, or before a compiled rule base loads).
#[derive(Clone, Copy)]
pub struct RomSymbols {
    pub texts: &'static [&'static str],
    pub buckets: &'static [Ix],
    pub next: &'static [Ix],
}

impl RomSymbols {
    pub const EMPTY: RomSymbols = RomSymbols {
        texts: &[],
        buckets: &[],
        next: &[],
    };

    #[inline(always)]
    pub fn len(&self) -> usize {
        self.texts.len()
    }

    pub fn is_empty(&self) -> bool {
        self.texts.is_empty()
    }

    pub(crate) fn find(&self, s: &str) -> Option<SymId> {
        self.find_hashed(s, hash_bytes(s.as_bytes()))
    }

    /// `find` of a text whose `hash_bytes` is `h`.
    pub(crate) fn find_hashed(&self, s: &str, h: u32) -> Option<SymId> {
        self.find_bytes(s.as_bytes(), h)
    }

    /// `find_hashed` of a text given by its bytes.
    #[inline]
    fn find_bytes(&self, s: &[u8], h: u32) -> Option<SymId> {
        if self.buckets.is_empty() {
            return None;
        }
        let b = h as usize % self.buckets.len();
        let mut i = self.buckets[b];
        while i != NONE {
            if self.texts.get(i as usize).map(|t| t.as_bytes()) == Some(s) {
                return Some(i);
            }
            i = self.next.get(i as usize).copied().unwrap_or(NONE);
        }
        None
    }
}

/// Read-only view of every symbol's text: the compiled ones read in place, then the
/// arena's.
#[derive(Clone, Copy)]
pub struct SymTexts<'a> {
    pub rom: RomSymbols,
    pub entries: &'a [SymEntry],
    pub bytes: &'a [u8],
}

impl<'a> SymTexts<'a> {
    /// Text of symbol `id`; "" for NONE (a retired construct's name) or any id out of
    /// range.
    #[inline]
    pub fn text(&self, id: SymId) -> &'a str {
        let rom = self.rom.len();
        if (id as usize) < rom {
            return self.rom.texts[id as usize];
        }
        let Some(e) = self.entries.get(id as usize - rom) else {
            return "";
        };
        self.bytes
            .get(e.start as usize..e.start as usize + e.len as usize)
            .and_then(|b| core::str::from_utf8(b).ok())
            .unwrap_or("")
    }

    /// Symbol `id`'s bytes as stored (its text's, empty where `text` is empty),
    /// without reading them as UTF-8 first.
    #[cfg(feature = "host-speedups")]
    #[inline]
    pub fn text_bytes(&self, id: SymId) -> &'a [u8] {
        let rom = self.rom.len();
        if (id as usize) < rom {
            return self.rom.texts[id as usize].as_bytes();
        }
        let Some(e) = self.entries.get(id as usize - rom) else {
            return &[];
        };
        self.bytes
            .get(e.start as usize..e.start as usize + e.len as usize)
            .unwrap_or(&[])
    }

    /// Whether symbol `id`'s text is `text` (as `text(id) == text`, without checking
    /// the bytes are UTF-8 first: bytes equal to a `str`'s are).
    #[inline]
    pub fn is(&self, id: SymId, text: &str) -> bool {
        let rom = self.rom.len();
        if (id as usize) < rom {
            return self.rom.texts[id as usize] == text;
        }
        let Some(e) = self.entries.get(id as usize - rom) else {
            return text.is_empty();
        };
        match self
            .bytes
            .get(e.start as usize..e.start as usize + e.len as usize)
        {
            Some(b) => b == text.as_bytes(),
            None => text.is_empty(),
        }
    }
}

/// Borrowed view of the symbol storage (see `engine::Core`): ids below `rom.len()`
/// are a compiled rule base's, read in place; the arena's entries come after (entry
/// `k` is id `rom.len() + k`), and its buckets and chains hold ids.
pub struct Symbols<'a> {
    pub rom: RomSymbols,
    pub entries: &'a mut [SymEntry],
    /// Bucket heads; at least as many as `entries`.
    pub buckets: &'a mut [Head],
    pub bytes: &'a mut [u8],
    pub count: &'a mut Ix,
    pub bytes_used: &'a mut Ix,
}

impl Symbols<'_> {
    pub fn text(&self, id: SymId) -> &str {
        SymTexts {
            rom: self.rom,
            entries: self.entries,
            bytes: self.bytes,
        }
        .text(id)
    }

    pub fn find(&self, s: &str) -> Option<SymId> {
        self.find_hashed(s, hash_bytes(s.as_bytes()))
    }

    /// `find` of a text whose `hash_bytes` is `h` (interning hashes it once).
    pub fn find_hashed(&self, s: &str, h: u32) -> Option<SymId> {
        self.find_bytes(s.as_bytes(), h)
    }

    /// `find_hashed` of a text given by its bytes: an entry's bytes are compared as
    /// they are (equal bytes are equal texts), with no UTF-8 check per candidate.
    fn find_bytes(&self, s: &[u8], h: u32) -> Option<SymId> {
        if let Some(i) = self.rom.find_bytes(s, h) {
            return Some(i);
        }
        if self.buckets.is_empty() {
            return None;
        }
        let rom = self.rom.len();
        let b = h as usize % self.buckets.len();
        let mut i = self.buckets[b].get();
        while i != NONE {
            let e = self.entries[i as usize - rom];
            if e.len as usize == s.len()
                && self.bytes.get(e.start as usize..e.start as usize + s.len()) == Some(s)
            {
                return Some(i);
            }
            i = e.next;
        }
        None
    }

    pub fn intern(&mut self, s: &str) -> Result<SymId, CapacityError> {
        let h = hash_bytes(s.as_bytes());
        if let Some(i) = self.find_hashed(s, h) {
            return Ok(i);
        }
        self.add_new(s, h)
    }

    /// Adds `s` (its `hash_bytes` is `h`), which the table does not have (`find`
    /// said so).
    pub fn add_new(&mut self, s: &str, h: u32) -> Result<SymId, CapacityError> {
        let used = *self.bytes_used as usize;
        self.room_for(used + s.len() <= self.bytes.len(), s.len())?;
        self.bytes[used..used + s.len()].copy_from_slice(s.as_bytes());
        Ok(self.add_entry(s.len(), h))
    }

    /// Interns the text already written at the arena's free end (`len` bytes from
    /// `*bytes_used`, see [`TailWriter`]): an existing symbol is found (the bytes stay
    /// free), a new one keeps them.
    pub fn intern_tail(&mut self, len: usize) -> Result<SymId, CapacityError> {
        let used = *self.bytes_used as usize;
        let (found, h) = {
            let s = self
                .bytes
                .get(used..used + len)
                .filter(|b| b.is_ascii() || core::str::from_utf8(b).is_ok())
                .unwrap_or(&[]);
            let h = hash_bytes(s);
            (self.find_bytes(s, h), h)
        };
        if let Some(i) = found {
            return Ok(i);
        }
        // (the bytes are in the arena already)
        self.room_for(true, len)?;
        Ok(self.add_entry(len, h))
    }

    /// Whether a new symbol of `len` bytes fits: an entry (the symbols' capacity
    /// error first), then its bytes (`bytes_fit`, and its end within [`Ix`]).
    fn room_for(&self, bytes_fit: bool, len: usize) -> Result<(), CapacityError> {
        let n = *self.count as usize;
        if n - self.rom.len() >= self.entries.len() || n >= NONE as usize {
            return Err(CapacityError {
                pool: Pool::Symbols,
                capacity: self.entries.len() as u32,
            });
        }
        if !bytes_fit || *self.bytes_used as usize + len > Ix::MAX as usize {
            return Err(CapacityError {
                pool: Pool::SymbolBytes,
                capacity: self.bytes.len() as u32,
            });
        }
        Ok(())
    }

    /// Makes the `len` bytes at the arena's free end (hash `h`) the next symbol
    /// (room checked by `room_for`).
    fn add_entry(&mut self, len: usize, h: u32) -> SymId {
        let n = *self.count as usize;
        let used = *self.bytes_used as usize;
        let b = h as usize % self.buckets.len();
        self.entries[n - self.rom.len()] = SymEntry {
            start: used as Ix,
            len: len as Ix,
            next: self.buckets[b].get(),
            #[cfg(feature = "grow")]
            hash: h,
        };
        self.buckets[b] = Head::of(n as Ix);
        *self.count += 1;
        *self.bytes_used += len as Ix;
        n as SymId
    }

    /// Drops every entry with id >= `count` (newest entries sit at bucket heads;
    /// the compiled ones stay).
    pub fn truncate(&mut self, count: Ix, bytes_used: Ix) {
        if count >= *self.count {
            return;
        }
        let rom = self.rom.len();
        // (the compiled symbols stay)
        let count = count.max(rom as Ix);
        for b in self.buckets.iter_mut() {
            while b.get() != NONE && b.get() >= count {
                *b = Head::of(self.entries[b.get() as usize - rom].next);
            }
        }
        *self.count = count;
        *self.bytes_used = bytes_used;
    }
}

/// Writes a text into the symbol arena's free end, so a builtin that builds a symbol
/// (`sym-cat`, `sub-string`) needs no buffer of the longest text on its stack (the
/// agent image's stack high-water mark); [`Symbols::intern_tail`] then keeps it.
pub struct TailWriter<'a> {
    pub tail: &'a mut [u8],
    pub len: usize,
    /// Longest text allowed (the builtins' limit, `builtins::strings::TEXT_MAX`).
    pub max: usize,
    /// Whether a write failed for want of room in the arena (not the limit).
    pub out_of_room: bool,
}

impl core::fmt::Write for TailWriter<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let end = self.len + s.len();
        if end > self.max {
            return Err(core::fmt::Error);
        }
        let Some(dst) = self.tail.get_mut(self.len..end) else {
            self.out_of_room = true;
            return Err(core::fmt::Error);
        };
        dst.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}
