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
}

impl SymEntry {
    pub const EMPTY: SymEntry = SymEntry {
        start: 0,
        len: 0,
        next: NONE,
    };
}

/// FNV-1a over bytes; cheap and good enough for bucket spreading.
pub fn hash_bytes(b: &[u8]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for &x in b {
        h ^= x as u32;
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// Borrowed view of the symbol storage (see `engine::Core`).
pub struct Symbols<'a> {
    pub entries: &'a mut [SymEntry],
    /// Bucket heads; same length as `entries`.
    pub buckets: &'a mut [Ix],
    pub bytes: &'a mut [u8],
    pub count: &'a mut Ix,
    pub bytes_used: &'a mut Ix,
}

impl Symbols<'_> {
    pub fn text(&self, id: SymId) -> &str {
        let e = self.entries[id as usize];
        core::str::from_utf8(&self.bytes[e.start as usize..(e.start + e.len) as usize])
            .unwrap_or("")
    }

    pub fn find(&self, s: &str) -> Option<SymId> {
        if self.buckets.is_empty() {
            return None;
        }
        let b = hash_bytes(s.as_bytes()) as usize % self.buckets.len();
        let mut i = self.buckets[b];
        while i != NONE {
            if self.text(i) == s {
                return Some(i);
            }
            i = self.entries[i as usize].next;
        }
        None
    }

    pub fn intern(&mut self, s: &str) -> Result<SymId, CapacityError> {
        if let Some(i) = self.find(s) {
            return Ok(i);
        }
        let n = *self.count as usize;
        if n >= self.entries.len() || n >= NONE as usize {
            return Err(CapacityError {
                pool: Pool::Symbols,
                capacity: self.entries.len() as u32,
            });
        }
        let used = *self.bytes_used as usize;
        if used + s.len() > self.bytes.len() || used + s.len() > Ix::MAX as usize {
            return Err(CapacityError {
                pool: Pool::SymbolBytes,
                capacity: self.bytes.len() as u32,
            });
        }
        self.bytes[used..used + s.len()].copy_from_slice(s.as_bytes());
        let b = hash_bytes(s.as_bytes()) as usize % self.buckets.len();
        self.entries[n] = SymEntry {
            start: used as Ix,
            len: s.len() as Ix,
            next: self.buckets[b],
        };
        self.buckets[b] = n as Ix;
        *self.count += 1;
        *self.bytes_used += s.len() as Ix;
        Ok(n as SymId)
    }

    /// Drops every entry with id >= `count` (newest entries sit at bucket heads).
    pub fn truncate(&mut self, count: Ix, bytes_used: Ix) {
        if count >= *self.count {
            return;
        }
        for b in self.buckets.iter_mut() {
            while *b != NONE && *b >= count {
                *b = self.entries[*b as usize].next;
            }
        }
        *self.count = count;
        *self.bytes_used = bytes_used;
    }
}
