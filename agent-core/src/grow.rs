//! Storage that grows (feature `grow`, hosts only): [`GrowStorage`] holds every array
//! of the pool table in a heap vector that starts small ([`GrowStorage::START`]) and doubles
//! when an allocation finds its pool full, up to a limit (by default the most the index
//! type can address), so one host engine runs small and big programs alike and costs
//! only what it uses. The robot never enables the feature: its storage stays the fixed
//! arrays of [`engine_storage!`](crate::engine_storage), and there a full pool is the
//! [`CapacityError`] at once.
//!
//! Nothing outside the storage holds an address into a pool: entries are reached by
//! index through the slices of [`Core`], and growing replaces the grown pool's slices
//! in that `Core` (it takes `&mut Core`, so no borrow of the old ones is alive). A
//! growth that cannot happen (the limit, or the allocator refusing) is the pool's
//! `CapacityError`, with the storage as it was.
//!
//! A host that wants the fixed host engine's start at no cost makes a [`HostSeed`] a
//! `static` (built at compile time: its entries are the program's initialized data, so
//! starting fills nothing and touches only the pages a program uses) and starts from it
//! ([`GrowStorage::from_seed`]); a pool's first growth copies its seed arrays to the heap
//! (but the token pool's array, the largest, starts in a zeroed reserve there: it
//! grows without a copy). A host that can map zeroed pages and make a mapping longer
//! without copying ([`ZeroPages`], Linux's `mmap` and `mremap`) starts the arrays of
//! zero-free entries in such mappings instead ([`GrowStorage::from_seed_in`]): then no
//! growth of theirs copies or fills, the first included.
//!
//! The hash tables over the pools start at the fixed host engine's length and keep
//! twice as many buckets as their pool has entries: the fact and symbol tables are
//! rebuilt at once (their chains are found again from each entry's hash), the token
//! index (alpha- and beta-memory buckets, whose chains a join may be walking) at the
//! next assert, when no pattern matching runs, once the tokens outnumber its buckets
//! (`grow_token_index`); its tokens keep their hash for that (`rete::index`).

use alloc::vec::Vec;
use core::marker::PhantomData;
use core::ptr::NonNull;

use crate::config::{Capacities, Core, Pool};
use crate::engine::cap;
use crate::error::CapacityError;
use crate::handle::TokenId;
use crate::value::NONE;

/// The most entries any pool can have: every index below [`NONE`] but the last (a fact
/// slot's number and a token's id must stay distinct from `NONE`).
pub const INDEX_LIMIT: usize = NONE as usize - 1;

/// The starting length of an array that is a hash table's bucket heads (`Some`: at
/// least the fixed host engine's, so a small program's chains are no longer there;
/// grown to twice its pool's length by `empty_heads` or `fresh_heads`, not with the
/// pool), or `None` for an array with one entry per pool entry.
macro_rules! heads {
    // (two per fact, as growth keeps them: with one per fact the duplicate check's
    // chains of a program near the host's 4,096 facts were twice as long)
    (fact_buckets) => {
        Some(2 * Capacities::HOST.facts)
    };
    (sym_buckets) => {
        Some(Capacities::HOST.symbols)
    };
    // (two per token, as `grow_token_index` keeps them: with one per token the beta
    // index's group of a program near the host's 32,768 tokens had chains of other
    // joins' partial matches to skip)
    (amem_buckets) => {
        Some(2 * Capacities::HOST.tokens)
    };
    ($other:ident) => {
        None::<usize>
    };
}

/// The length of a [`HostSeed`] array: its bucket heads' start (`heads!`) if longer
/// than its pool's host length, else that.
macro_rules! seed_len {
    ($arr:ident, $cap:ident) => {
        match heads!($arr) {
            Some(h) if h > Capacities::HOST.$cap => h,
            _ => Capacities::HOST.$cap,
        }
    };
}

/// `$zeroed` for the arrays whose entries are [`ZeroFree`] (they grow into zeroed
/// memory), else `$plain`: the token and fact pools, the fact value arena, and (host speed-ups) the side
/// arrays of theirs that the engine writes before it reads (a fact's template list
/// links, a partial match's extra index links).
macro_rules! zeroed_or {
    (tokens, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    (facts, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    (values, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    // the symbol table: its entries and bytes past the used ones are written before
    // they are read, its bucket heads' empty value is all-zero bytes (`Head`)
    (sym_entries, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    (sym_bytes, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    (sym_buckets, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    // (a scratch cell is written before it is read; all-zero bytes are `Void`, the
    // value growth filled new cells with)
    (scratch, $zeroed:expr, $plain:expr) => {
        $zeroed
    };
    (fact_tlinks, $zeroed:expr, $plain:expr) => {
        zeroed_or!(@speedups $zeroed, $plain)
    };
    (token_xlinks, $zeroed:expr, $plain:expr) => {
        zeroed_or!(@speedups $zeroed, $plain)
    };
    (token_deps, $zeroed:expr, $plain:expr) => {
        zeroed_or!(@logical $zeroed, $plain)
    };
    (fact_deps, $zeroed:expr, $plain:expr) => {
        zeroed_or!(@logical $zeroed, $plain)
    };
    (@logical $zeroed:expr, $plain:expr) => {{
        #[cfg(feature = "logical")]
        let r = $zeroed;
        #[cfg(not(feature = "logical"))]
        let r = $plain;
        r
    }};
    (@speedups $zeroed:expr, $plain:expr) => {{
        #[cfg(feature = "host-speedups")]
        let r = $zeroed;
        #[cfg(not(feature = "host-speedups"))]
        let r = $plain;
        r
    }};
    ($other:ident, $zeroed:expr, $plain:expr) => {
        $plain
    };
}

/// Whether the new entries of a side array that grows into zeroed memory get their
/// empty value (`$deps`, for the support list heads: once a rule with `logical`
/// exists), or stay zero (the arrays written before they are read).
macro_rules! fills {
    (token_deps, $deps:expr) => {
        $deps
    };
    (fact_deps, $deps:expr) => {
        $deps
    };
    ($other:ident, $deps:expr) => {
        false
    };
}

/// Bucket heads, all `empty`, doubled from `old` until there are `at_least`; `None` if
/// `old` is enough or the allocator refuses. Filled by a loop of vector stores of a
/// value the compiler does not see (`black_box`): as a `memset` (which `resize` or
/// `fill` of a constant become), a fill of that size is `rep stosb`, an instruction
/// per byte (growforall-800: 0.5 M instructions for its one growth's heads).
fn empty_heads<T: Copy>(old: usize, at_least: usize, empty: T) -> Option<Vec<T>> {
    if old >= at_least {
        return None;
    }
    let mut len = old.max(2);
    while len < at_least {
        len = len.saturating_mul(2);
    }
    let mut v = Vec::new();
    v.try_reserve_exact(len).ok()?;
    let empty = core::hint::black_box(empty);
    for slot in v.spare_capacity_mut().iter_mut().take(len) {
        slot.write(empty);
    }
    // SAFETY: the first `len` entries (within the capacity reserved) were written
    // just now.
    unsafe { v.set_len(len) };
    Some(v)
}

/// Replaces the bucket heads `v` by all-empty ones (all-zero bytes: [`ZeroFree`]),
/// doubled from its length until there are `at_least`, in fresh zeroed memory (a new
/// mapping of the host's pages if `v` is in one, else the allocator's): no head is
/// copied or written, the rehash that follows links only the live entries. The old
/// length if it grew; `None` (`v` as it was) if it was long enough or no memory came.
fn fresh_heads<T: ZeroFree>(v: &mut Buf<T>, at_least: usize) -> Option<usize> {
    let old = v.len();
    if old >= at_least {
        return None;
    }
    let mut len = old.max(2);
    while len < at_least {
        len = len.saturating_mul(2);
    }
    let mapped = match v {
        Buf::Mapped { pages, .. } => Buf::mapped(len, *pages),
        _ => None,
    };
    let fresh = match mapped {
        Some(b) => b,
        None => {
            let mut b = Buf::Zeroed(zeroed_vec(len, &[])?);
            b.extend_zeroed(len);
            b
        }
    };
    *v = fresh;
    Some(old)
}

/// One array of a pool: a [`HostSeed`]'s until it first grows, then a heap vector.
enum Buf<T: 'static> {
    Seed(&'static mut [T]),
    Heap(Vec<T>),
    /// A heap vector whose room past its length (up to its capacity) is all-zero
    /// bytes, never written: the arrays of [`ZeroFree`] entries (the tokens and the
    /// facts, and side arrays of theirs) grow into it without writing or copying
    /// (`extend_zeroed`).
    Zeroed(Vec<T>),
    /// As `Zeroed`, in memory of the host's [`ZeroPages`]: `len` entries in `bytes`
    /// of it, those past `len` all-zero bytes never written. Grows by the host's
    /// `grow` (which moves pages, not bytes) and is unmapped when dropped.
    Mapped {
        p: NonNull<T>,
        len: usize,
        bytes: usize,
        pages: ZeroPages,
    },
}

/// Zero-filled memory a host maps for the arrays of [`ZeroFree`] entries and can make
/// longer without copying them (on Linux: anonymous `mmap`, grown by `mremap`, which
/// moves page table entries, not bytes). A seeded storage given one
/// ([`GrowStorage::from_seed_in`]) starts those arrays there instead of in their seeds:
/// starting touches none of their pages, and a pool's growth past the fixed host
/// engine's length (its first included, which copied the whole seed) neither copies
/// nor fills them.
#[derive(Clone, Copy)]
pub struct ZeroPages {
    map: fn(usize) -> *mut u8,
    grow: unsafe fn(*mut u8, usize, usize) -> *mut u8,
    unmap: unsafe fn(*mut u8, usize),
}

impl ZeroPages {
    /// The host's three calls.
    ///
    /// # Safety
    /// `map(n)` (`n` > 0) returns null or the start of `n` bytes of fresh memory, every
    /// byte zero, readable and writable, aligned to at least 16, that nothing else
    /// uses until `unmap`. `grow(p, old, new)` (`p` of a mapping of `old` bytes made by
    /// `map` or `grow`, `new` > `old`) returns null, the mapping unchanged, or the
    /// start of a mapping of `new` bytes (maybe elsewhere; the old one is then gone),
    /// aligned as `map`'s, whose first `old` bytes are the old mapping's and the rest
    /// zero. `unmap(p, n)`
    /// frees a mapping of `n` bytes made by `map` or `grow`.
    pub const unsafe fn new(
        map: fn(usize) -> *mut u8,
        grow: unsafe fn(*mut u8, usize, usize) -> *mut u8,
        unmap: unsafe fn(*mut u8, usize),
    ) -> Self {
        ZeroPages { map, grow, unmap }
    }
}

impl<T: 'static> Drop for Buf<T> {
    fn drop(&mut self) {
        if let Buf::Mapped {
            p, bytes, pages, ..
        } = *self
        {
            // SAFETY: `p` is a mapping of `bytes` bytes made by `pages` (`Buf::mapped`,
            // `reserve_zeroed`), reached only through this array, whose entries
            // (`ZeroFree`: `Copy`) need no drop.
            unsafe { (pages.unmap)(p.as_ptr().cast(), bytes) }
        }
    }
}

/// Entries whose all-zero bytes are a valid value that their pool reads as an entry
/// never handed out (its kind or state `Free`, as `Token::EMPTY`'s and `Fact::EMPTY`'s,
/// for the invariant checks and `clear`; every allocation writes the whole entry
/// before anything reads it, `alloc_token`'s callers and `assert_slots`), or that a
/// side array of those pools never reads as it is (see each `impl`). Such an array
/// grows into memory the allocator hands out zeroed, reserved ahead
/// ([`ZEROED_RESERVE`] bytes): large zeroed allocations are fresh pages of the
/// operating system, zero without a write and resident only once touched, so a
/// growth neither fills the new entries nor copies the old ones.
///
/// # Safety
/// All-zero bytes must be a valid value of the type, and the type must not be
/// zero-sized.
unsafe trait ZeroFree: Copy {}

// SAFETY: every field of a `Token` is an integer, a `bool`, an array of `u8` or of
// `Ix`, a handle (a tuple struct of one `Ix`) or a `TokenKind` (`repr(u8)`, `Free`
// = 0, checked below): zero bytes are a valid value of each. `zero_free_fields` lists
// the fields without `..`, so a field added later fails to compile until this proof
// is looked at again. Not zero-sized (checked below).
unsafe impl ZeroFree for crate::rete::Token {}
// SAFETY: as for `Token`: integers, `Ix`, a `bool`, a `TokenId` and a `FactState`
// (`repr(u8)`, `Free` = 0, checked below); listed in `zero_free_fields`.
unsafe impl ZeroFree for crate::fact::Fact {}
// SAFETY: all-zero bytes are `Value::Void` (`ZERO_VALUE` below: the compiler rejects a
// constant whose bytes are no valid value, and the assertion names the variant), the
// value a new cell of the fact value arena had when growth filled it; not zero-sized.
// The arena's cells past its top are written before they are read anyway
// (`reserve_cells`, then `write_cells`).
unsafe impl ZeroFree for crate::value::Value {}

// SAFETY: integers (`Ix`, a `u32` hash), not zero-sized. Entries past the symbol
// count are never read (every id in a chain or a value is below it); an entry is
// written whole when its symbol is made (`Symbols::add_entry`).
unsafe impl ZeroFree for crate::symbols::SymEntry {}
// SAFETY: a byte. The arena's bytes past the used ones are written before they are
// read (`Symbols::add_new`, `TailWriter`).
unsafe impl ZeroFree for u8 {}
// SAFETY: an integer, not zero-sized; all-zero is the stamp 0 (`ZeroedU32`). (With
// `logical` and `wide-index`, `Ix` is `u32` and has its impl below.)
#[cfg(not(all(feature = "logical", feature = "wide-index")))]
unsafe impl ZeroFree for u32 {}
// SAFETY: an `Ix` (`repr(transparent)`), not zero-sized; with `grow` all-zero bytes
// are `Head::EMPTY` (the complement of `NONE`), checked below.
unsafe impl ZeroFree for crate::symbols::Head {}
const _: () = assert!(crate::symbols::Head::EMPTY.get() == NONE);
const _: () = assert!({
    // SAFETY: an `Ix` of zero bytes is a valid `Head` (`repr(transparent)`)
    let z = unsafe { core::mem::transmute::<crate::value::Ix, crate::symbols::Head>(0) };
    z.get() == NONE
});

/// A value of all-zero bytes (see `ZeroFree for Value`).
const ZERO_VALUE: crate::value::Value = {
    const N: usize = core::mem::size_of::<crate::value::Value>();
    // SAFETY: const evaluation checks that the bytes are a valid `Value` (an invalid
    // tag fails to compile); they are of the same size.
    unsafe { core::mem::transmute::<[u8; N], crate::value::Value>([0u8; N]) }
};
const _: () = assert!(matches!(ZERO_VALUE, crate::value::Value::Void));

// SAFETY: arrays of `Ix` (integers), not zero-sized. The engine writes an entry
// before it reads it: a fact's links when it is asserted or restored (`assert_slots`,
// `tmpl_link`), a partial match's when it enters its first extra index group (`in_x`),
// an alpha match's when it enters the keyed or-index; a freed entry is reused as it
// was left, so no read relies on the empty value a fill wrote.
#[cfg(feature = "host-speedups")]
unsafe impl ZeroFree for crate::fact::TemplateLinks {}
// SAFETY: as for `TemplateLinks`.
#[cfg(feature = "host-speedups")]
unsafe impl ZeroFree for crate::rete::XLinks {}
// SAFETY: an integer (`Deps`, the support list heads), not zero-sized. Nothing reads
// them before a rule with `logical` exists (every reader checks `defined`, or `live`,
// 0 until then); `set_rule_logical_join` sets each to `NO_DEPS` then, and growth after
// that fills the new ones (`fills`).
#[cfg(feature = "logical")]
unsafe impl ZeroFree for crate::value::Ix {}

const _: () = assert!(
    crate::rete::TokenKind::Free as u8 == 0
        && crate::fact::FactState::Free as u8 == 0
        && core::mem::size_of::<crate::rete::Token>() > 0
        && core::mem::size_of::<crate::fact::Fact>() > 0
        && core::mem::size_of::<crate::value::Value>() > 0
);

/// The address space a pool of [`ZeroFree`] entries reserves when it first grows
/// (or its limit's worth, if less): it grows within it without moving. Untouched,
/// it costs no resident memory.
pub const ZEROED_RESERVE: usize = 1 << 30;

/// A vector of `from`'s entries with room for `room` in all, the room past them
/// zeroed by the allocator; `None` if the allocator refuses (or `room` is 0 or less
/// than `from`).
fn zeroed_vec<T: ZeroFree>(room: usize, from: &[T]) -> Option<Vec<T>> {
    if room == 0 || room < from.len() {
        return None;
    }
    let layout = core::alloc::Layout::array::<T>(room).ok()?;
    // SAFETY: `layout` is not zero-sized (`room` > 0 and `T` is not zero-sized,
    // `ZeroFree`).
    let p = unsafe { alloc::alloc::alloc_zeroed(layout) }.cast::<T>();
    if p.is_null() {
        return None;
    }
    // SAFETY: `p` is a fresh allocation of the global allocator for `room` entries
    // of `T` (the layout `Vec` uses for that capacity), aligned for `T`, and does
    // not overlap `from`; its first `from.len()` (<= `room`) entries are written from
    // `from` (`T: Copy`) before the vector takes them as its length.
    unsafe {
        core::ptr::copy_nonoverlapping(from.as_ptr(), p, from.len());
        Some(Vec::from_raw_parts(p, from.len(), room))
    }
}

/// Host: an array of `u32` entries by token (stamps: `State::stamps`,
/// `PrimeOrders::stamps`) that grows into memory the allocator zeroed, reserved
/// ahead for as many entries as the token pool's zeroed reserve holds tokens
/// (address space, resident once touched): a growth neither fills nor copies
/// (growforall-800: the doubling stamps filled 0.5 M instructions' worth of
/// zeros). Entries past its length are all-zero bytes, never written: it is
/// reached only as a slice of its length, and `clear` drops the vector.
pub struct ZeroedU32 {
    v: Vec<u32>,
}

impl ZeroedU32 {
    /// No entries, nothing allocated.
    pub const fn new() -> Self {
        ZeroedU32 { v: Vec::new() }
    }

    /// Makes it at least `len` entries long, the new ones 0; false (unchanged) if
    /// the allocator refuses.
    #[cold]
    #[inline(never)]
    pub fn grow_to(&mut self, len: usize) -> bool {
        if len <= self.v.len() {
            return true;
        }
        if len > self.v.capacity() {
            let room = (ZEROED_RESERVE / core::mem::size_of::<crate::rete::Token>()).max(len);
            let Some(v) = zeroed_vec(room, &self.v).or_else(|| zeroed_vec(len, &self.v)) else {
                return false;
            };
            self.v = v;
        }
        // SAFETY: the entries from the length to the capacity are all-zero bytes (a
        // valid `u32`): the allocator zeroed them (`zeroed`) and nothing wrote them
        // since (the vector is reached only as a slice of its length; it is never
        // pushed to or shrunk, and `clear` replaces it); `len` is within the capacity.
        unsafe { self.v.set_len(len) };
        true
    }

    /// No entries again (the memory given back).
    pub fn clear(&mut self) {
        self.v = Vec::new();
    }
}

impl Default for ZeroedU32 {
    fn default() -> Self {
        Self::new()
    }
}

impl core::ops::Deref for ZeroedU32 {
    type Target = [u32];
    #[inline(always)]
    fn deref(&self) -> &[u32] {
        &self.v
    }
}

impl core::ops::DerefMut for ZeroedU32 {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [u32] {
        &mut self.v
    }
}

impl<T: ZeroFree> Buf<T> {
    /// `len` all-zero entries in a fresh mapping of `pages` with room for exactly
    /// them, or `None` if the host refuses.
    fn mapped(len: usize, pages: ZeroPages) -> Option<Self> {
        let bytes = len.checked_mul(core::mem::size_of::<T>())?;
        if bytes == 0 {
            return None;
        }
        let raw = (pages.map)(bytes);
        let p = NonNull::new(raw.cast::<T>())?;
        if raw.align_offset(core::mem::align_of::<T>()) != 0 {
            // SAFETY: a mapping of `bytes` just made by `pages`, not used.
            unsafe { (pages.unmap)(raw, bytes) };
            return None;
        }
        Some(Buf::Mapped {
            p,
            len,
            bytes,
            pages,
        })
    }

    /// `len` all-zero entries at the start of a fresh zeroed reserve (as
    /// `reserve_zeroed` makes on a first growth, `limit` capping it), or `None` if
    /// the allocator refuses: a seeded pool of such entries starts here instead of in
    /// its seed, so that growing past the seed copies nothing (its first growth
    /// copied the whole seed, 32,768 tokens, once a program needed one more).
    fn zeroed_start(len: usize, limit: usize) -> Option<Self> {
        let room = (ZEROED_RESERVE / core::mem::size_of::<T>())
            .min(limit)
            .max(len);
        let mut b = Buf::Zeroed(zeroed_vec(room, &[])?);
        b.extend_zeroed(len);
        Some(b)
    }

    /// Makes room for `len` entries in zeroed memory (the reserve, or `limit`
    /// entries if fewer, or `len` if more), the entries unchanged: nothing to do if
    /// there is room, else one copy of the entries to a fresh zeroed allocation.
    fn reserve_zeroed(&mut self, len: usize, limit: usize) -> Result<(), ()> {
        match self {
            Buf::Zeroed(v) if v.capacity() >= len => return Ok(()),
            Buf::Mapped {
                p, bytes, pages, ..
            } => {
                let size = core::mem::size_of::<T>();
                if *bytes / size >= len {
                    return Ok(());
                }
                // made longer by the host, the entries where they are (or moved with
                // their pages); if it refuses, copied as below
                if let Some(new) = len.checked_mul(size) {
                    // SAFETY: `p` is a mapping of `bytes` bytes made by `pages`, and
                    // `new` is more; nothing borrows the array's entries now (`grow`
                    // rebinds the pool's slices after this).
                    let q = unsafe { (pages.grow)(p.as_ptr().cast(), *bytes, new) };
                    if let Some(q) = NonNull::new(q.cast::<T>()) {
                        // (aligned as `map`'s: `ZeroPages::new`, and `mapped` checked
                        // that `T` needs no more)
                        *p = q;
                        *bytes = new;
                        return Ok(());
                    }
                }
            }
            _ => {}
        }
        let room = (ZEROED_RESERVE / core::mem::size_of::<T>())
            .min(limit)
            .max(len);
        let v = zeroed_vec(room, self)
            .or_else(|| zeroed_vec(len, self))
            .ok_or(())?;
        *self = Buf::Zeroed(v);
        Ok(())
    }

    /// `reserve_zeroed` for an array whose entries nothing reads yet (the support
    /// list heads before a rule with `logical` exists, `set_rule_logical_join`): where
    /// it would copy them, fresh zeroed room instead, as many entries as before, each
    /// all-zero bytes (a seed of 4,096 fact heads copied cost deepjoin-800 ~16 K
    /// instructions).
    fn reserve_zeroed_fresh(&mut self, len: usize, limit: usize) -> Result<(), ()> {
        match self {
            Buf::Zeroed(v) if v.capacity() >= len => return Ok(()),
            Buf::Mapped { .. } => return self.reserve_zeroed(len, limit),
            _ => {}
        }
        let room = (ZEROED_RESERVE / core::mem::size_of::<T>())
            .min(limit)
            .max(len);
        let was = self.len();
        let v = zeroed_vec(room, &[])
            .or_else(|| zeroed_vec(len, &[]))
            .ok_or(())?;
        *self = Buf::Zeroed(v);
        // (its length as before: the pool keeps it if a later array cannot grow)
        self.extend_zeroed(was);
        Ok(())
    }

    /// Makes it `len` entries long in the room `reserve_zeroed` made, the new
    /// entries all-zero bytes (as they are); unchanged if there is no such room.
    fn extend_zeroed(&mut self, len: usize) {
        if let Buf::Mapped { len: l, bytes, .. } = self {
            // the entries up to `bytes` are all-zero bytes, never written (`mapped`,
            // `reserve_zeroed`): valid `T`s (`ZeroFree`)
            if *l < len && len <= *bytes / core::mem::size_of::<T>() {
                *l = len;
            }
        }
        if let Buf::Zeroed(v) = self {
            if v.len() < len && len <= v.capacity() {
                // SAFETY: the entries from `v.len()` to the capacity are all-zero
                // bytes: the allocator zeroed them (`zeroed_vec`) and nothing wrote
                // them since (the vector is reached only as a slice of its length:
                // it is never pushed to, extended or shrunk, and `reserve` makes a
                // `Heap` of it before it could reallocate). All-zero bytes are a
                // valid `T` (`ZeroFree`), and `len` is within the capacity.
                unsafe { v.set_len(len) };
            }
        }
    }
}

impl<T: Clone> Buf<T> {
    /// Makes room for `len` entries in a heap vector (a seed's entries copied there
    /// first) without changing the entries.
    fn reserve(&mut self, len: usize) -> Result<(), ()> {
        match self {
            Buf::Zeroed(v) if v.capacity() >= len => Ok(()),
            Buf::Zeroed(v) => {
                // (as a `Heap`: a reallocation's room is not zeroed)
                let mut v = core::mem::take(v);
                let extra = len.saturating_sub(v.len());
                let r = v.try_reserve_exact(extra).map_err(|_| ());
                *self = Buf::Heap(v);
                r
            }
            Buf::Heap(v) => {
                let extra = len.saturating_sub(v.len());
                v.try_reserve_exact(extra).map_err(|_| ())
            }
            Buf::Mapped { bytes, .. } if *bytes / core::mem::size_of::<T>().max(1) >= len => Ok(()),
            Buf::Mapped { .. } => {
                // (as a `Heap`, as a `Zeroed` that outgrows its room)
                let mut v = Vec::new();
                v.try_reserve_exact(len.max(self.len())).map_err(|_| ())?;
                v.extend_from_slice(self);
                *self = Buf::Heap(v);
                Ok(())
            }
            Buf::Seed(seed) => {
                let mut v = Vec::new();
                v.try_reserve_exact(len.max(seed.len())).map_err(|_| ())?;
                v.extend_from_slice(seed);
                *self = Buf::Heap(v);
                Ok(())
            }
        }
    }

    /// Makes it `len` entries long, new ones `empty`; unchanged if the allocator
    /// refuses (callers reserve first, so it does not).
    fn resize(&mut self, len: usize, empty: T) {
        // a `Zeroed` one is resized only by `extend_zeroed`: here it would stay as it
        // is when its room is enough, and turn `Heap` and grow when not
        debug_assert!(
            !matches!(self, Buf::Zeroed(_) | Buf::Mapped { .. }),
            "resize of a Zeroed array"
        );
        if self.reserve(len).is_ok() {
            if let Buf::Heap(v) = self {
                v.resize(len, empty);
            }
        }
    }
}

impl<T> core::ops::Deref for Buf<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        match self {
            Buf::Seed(s) => s,
            Buf::Heap(v) | Buf::Zeroed(v) => v,
            // SAFETY: `p` points at `bytes` >= `len` entries' worth of the array's
            // mapping, aligned for `T` (`mapped`), the first `len` valid `T`s (written,
            // or all-zero bytes: `ZeroFree`), reached only through this array.
            Buf::Mapped { p, len, .. } => unsafe { core::slice::from_raw_parts(p.as_ptr(), *len) },
        }
    }
}

impl<T> core::ops::DerefMut for Buf<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        match self {
            Buf::Seed(s) => s,
            Buf::Heap(v) | Buf::Zeroed(v) => v,
            // SAFETY: as in `deref`; `&mut self` makes this the only view.
            Buf::Mapped { p, len, .. } => unsafe {
                core::slice::from_raw_parts_mut(p.as_ptr(), *len)
            },
        }
    }
}

/// A seeded side array's start (`GrowStorage::seeded`): in a mapping of the host's
/// [`ZeroPages`] if it gives one and the entries are zero-free, else in its seed. (The
/// token pool's extra index links in a zeroed reserve of the allocator saved
/// growforall-800 ~0.9 M instructions, but the second allocation at every start cost
/// join-100's whole run +0.06 %; a mapping costs a system call, a few instructions.)
macro_rules! zero_start {
    // the support list heads keep their seed, whose heads are `NO_DEPS` already: in
    // zeroed pages they would be filled (written) once a rule with `logical` exists
    (token_deps, $pages:expr, $seeded:expr, $n:expr, $side:expr) => {{
        let _ = (&$pages, $n, $side);
        Buf::Seed($seeded)
    }};
    (fact_deps, $pages:expr, $seeded:expr, $n:expr, $side:expr) => {{
        let _ = (&$pages, $n, $side);
        Buf::Seed($seeded)
    }};
    ($arr:ident, $pages:expr, $seeded:expr, $n:expr, $side:expr) => {{
        let _ = $side;
        zeroed_or!(
            $arr,
            match ($pages).and_then(|pg| Buf::mapped($n, pg)) {
                Some(b) => b,
                None => Buf::Seed($seeded),
            },
            {
                let _ = (&$pages, $n);
                Buf::Seed($seeded)
            }
        )
    }};
}

macro_rules! grow_items {
    ($(
        $variant:ident $cap:ident $name:literal $host:literal $small:literal [
            $first:ident : $fty:ty = $fempty:expr
            $(, $arr:ident : $aty:ty = $aempty:expr)* $(,)?
        ]
    ),* $(,)?) => {
        /// Every pool in a heap vector that grows on demand (see the module docs).
        pub struct GrowStorage {
            /// The most entries each pool may grow to, in table order.
            limits: [usize; Pool::COUNT],
            $(
                $first: Buf<$fty>,
                $($arr: Buf<$aty>,)*
            )*
        }

        /// Every array of a [`GrowStorage`] at the fixed host engine's length
        /// ([`Capacities::HOST`]), every entry empty: see the module docs.
        pub struct HostSeed {
            $(
                $first: [$fty; Capacities::HOST.$cap],
                $($arr: [$aty; seed_len!($arr, $cap)],)*
            )*
        }

        impl HostSeed {
            /// Every entry empty; `const` so that the seed can be a `static`.
            #[allow(clippy::new_without_default)]
            pub const fn new() -> Self {
                HostSeed {
                    $(
                        $first: [$fempty; Capacities::HOST.$cap],
                        $($arr: [$aempty; seed_len!($arr, $cap)],)*
                    )*
                }
            }

            /// Writes each array's first entry (with the empty value it holds), so
            /// that the first page of each is copied on that write: a first read of a
            /// page of a seed in the program's initialized data maps it from the file
            /// with its neighbours (fault-around), a first write copies that page only.
            pub fn touch_first(&mut self) {
                // (volatile: the value is the one there, a store the compiler keeps)
                // SAFETY: writes of valid values to entries of the seed's arrays, each
                // one reached through `&mut self` (every array has an entry: the host
                // engine's capacities are not zero).
                unsafe {
                    $(
                        core::ptr::write_volatile(&mut self.$first[0], $fempty);
                        $(core::ptr::write_volatile(&mut self.$arr[0], $aempty);)*
                    )*
                }
            }
        }

        impl GrowStorage {
            /// Pools of `start` entries (every entry empty) that grow up to `limit`
            /// entries each (at most [`INDEX_LIMIT`]). Allocates only `start`: an
            /// allocator that refuses that much aborts, as any allocation of the host
            /// does.
            pub fn with_limits(start: Capacities, limit: Capacities) -> Self {
                let limits = limit.to_array().map(|l| l.min(INDEX_LIMIT));
                let start = start.to_array();
                GrowStorage {
                    limits,
                    $(
                        $first: Buf::Heap(alloc::vec![$fempty; start[Pool::$variant as usize]
                            .min(limits[Pool::$variant as usize])]),
                        $($arr: Buf::Heap(alloc::vec![$aempty; {
                            let n = start[Pool::$variant as usize]
                                .min(limits[Pool::$variant as usize]);
                            heads!($arr).map_or(n, |h| n.max(h))
                        }]),)*
                    )*
                }
            }

            /// Pools that start in `seed` (the fixed host engine's lengths, or `limit`
            /// where that is less) and grow up to `limit` entries each (at most
            /// [`INDEX_LIMIT`]). The token pool's array starts in a zeroed reserve
            /// instead (address space, resident once touched), unless the allocator
            /// refuses; the others allocate nothing until their pool grows. The seed's
            /// entries must be empty ([`HostSeed::new`]): it is used as it is.
            pub fn from_seed(seed: &'static mut HostSeed, limit: Capacities) -> Self {
                Self::seeded(seed, limit, None)
            }

            /// [`from_seed`](Self::from_seed), but the arrays of zero-free entries (the
            /// token, fact and fact value pools, multifield scratch and side arrays of
            /// theirs) start in fresh mappings of `pages` (those the host refuses as
            /// `from_seed` starts them): their growth then copies nothing.
            pub fn from_seed_in(
                seed: &'static mut HostSeed,
                limit: Capacities,
                pages: ZeroPages,
            ) -> Self {
                Self::seeded(seed, limit, Some(pages))
            }

            fn seeded(
                seed: &'static mut HostSeed,
                limit: Capacities,
                pages: Option<ZeroPages>,
            ) -> Self {
                let limits = limit.to_array().map(|l| l.min(INDEX_LIMIT));
                let start = Capacities::HOST.to_array();
                GrowStorage {
                    limits,
                    $(
                        $first: {
                            let n = start[Pool::$variant as usize]
                                .min(limits[Pool::$variant as usize]);
                            let limit = limits[Pool::$variant as usize];
                            // the token pool starts in a zeroed reserve (its first
                            // growth's copy, see `zeroed_start`; an allocation at every
                            // start costs ~800 instructions, so the smaller pools keep
                            // their seeds)
                            zeroed_or!($first,
                                match pages.and_then(|pg| Buf::mapped(n, pg)) {
                                    Some(b) => b,
                                    None if Pool::$variant == Pool::Tokens => {
                                        Buf::zeroed_start(n, limit)
                                            .unwrap_or_else(|| Buf::Seed(&mut seed.$first[..n]))
                                    }
                                    None => Buf::Seed(&mut seed.$first[..n]),
                                },
                                { let _ = limit; Buf::Seed(&mut seed.$first[..n]) })
                        },
                        $($arr: {
                            let n = start[Pool::$variant as usize]
                                .min(limits[Pool::$variant as usize]);
                            let seeded = &mut seed.$arr[..heads!($arr).map_or(n, |h| n.max(h))];
                            let n = seeded.len();
                            zero_start!($arr, pages, seeded, n, limits[Pool::$variant as usize]
                                .min(ZEROED_RESERVE / core::mem::size_of::<$fty>().max(1)))
                        },)*
                    )*
                }
            }

            /// Entries each pool has now, in table order.
            pub fn lens(&self) -> [usize; Pool::COUNT] {
                [$(self.$first.len(),)*]
            }

            /// Makes every array of `pool` `len` entries long (new entries empty, but
            /// those of the support list heads zero unless `fill_deps`, and those of
            /// the arrays written before they are read zero), or changes nothing if
            /// the allocator refuses.
            fn resize(&mut self, pool: Pool, len: usize, fill_deps: bool) -> Result<(), ()> {
                match pool {
                    $(Pool::$variant => {
                        let limit = self.limits[Pool::$variant as usize];
                        // all or nothing: reserve every array before changing one
                        zeroed_or!($first, self.$first.reserve_zeroed(len, limit),
                            { let _ = limit; self.$first.reserve(len) })?;
                        // (a side array reserves as many entries as its pool)
                        let _side = limit
                            .min(ZEROED_RESERVE / core::mem::size_of::<$fty>().max(1));
                        // (the support list heads are not read, nor kept, until a
                        // rule with `logical` exists: fresh zeroed room then, their
                        // seed not copied)
                        $(if heads!($arr).is_none() {
                            zeroed_or!($arr, if fills!($arr, true) && !fill_deps {
                                    self.$arr.reserve_zeroed_fresh(len, _side)
                                } else {
                                    self.$arr.reserve_zeroed(len, _side)
                                },
                                self.$arr.reserve(len))?;
                        })*
                        zeroed_or!($first, self.$first.extend_zeroed(len),
                            self.$first.resize(len, $fempty));
                        $(if heads!($arr).is_none() {
                            zeroed_or!($arr, {
                                let old = self.$arr.len();
                                self.$arr.extend_zeroed(len);
                                if fills!($arr, fill_deps) {
                                    for e in self.$arr[old..].iter_mut() {
                                        *e = $aempty;
                                    }
                                }
                            }, {
                                let _ = fill_deps;
                                self.$arr.resize(len, $aempty)
                            });
                        })*
                    })*
                }
                Ok(())
            }
        }

        impl crate::config::Storage for GrowStorage {
            const CAPACITIES: Capacities = GrowStorage::START;

            fn core<'a>(
                &'a mut self,
                st: &'a mut crate::engine::State,
                host: &'a mut dyn crate::Host,
            ) -> Core<'a> {
                let rom = st.rom;
                let me = NonNull::from(self);
                // SAFETY: `me` comes from `&'a mut self`, so for 'a nothing else reaches
                // the storage; every slice below and the grower are derived from it and
                // live in the one `Core`, which hands them out only through `&mut Core`
                // (growth replaces a pool's slices before anything reads them again).
                let s = unsafe { &mut *me.as_ptr() };
                Core {
                    st,
                    host,
                    grower: Grower { storage: Some(me), life: PhantomData },
                    $(
                        $first: crate::__pool_view!(mut $first, rom, &mut s.$first[..]),
                        $($arr: crate::__pool_view!(mut $arr, rom, &mut s.$arr[..]),)*
                    )*
                }
            }

            fn pools(&self, rom: crate::rom::Rom) -> crate::config::Pools<'_> {
                crate::config::Pools {
                    $(
                        $first: crate::__pool_view!(ref $first, rom, &self.$first[..]),
                        $($arr: crate::__pool_view!(ref $arr, rom, &self.$arr[..]),)*
                    )*
                }
            }

            fn capacities(&self) -> [usize; Pool::COUNT] {
                self.lens()
            }
        }

        impl Core<'_> {
            /// Points `pool`'s slices at the storage's arrays again (after a growth).
            fn rebind(&mut self, pool: Pool, s: NonNull<GrowStorage>) {
                let rom = self.st.rom;
                // SAFETY: `s` is the storage this `Core` was made from (`Grower`); the
                // slices replaced here are the only other views of the grown arrays,
                // and nothing borrows them while `self` is borrowed mutably.
                let s = unsafe { &mut *s.as_ptr() };
                match pool {
                    $(Pool::$variant => {
                        self.$first = crate::__pool_view!(mut $first, rom, &mut s.$first[..]);
                        $(self.$arr = crate::__pool_view!(mut $arr, rom, &mut s.$arr[..]);)*
                    })*
                }
            }
        }
    };
}

crate::__pool_table!(grow_items {});

impl GrowStorage {
    /// Pools that start at [`Self::START`] and grow up to [`INDEX_LIMIT`].
    pub fn new() -> Self {
        Self::with_limits(Self::START, Self::NO_LIMIT)
    }

    /// Where [`GrowStorage::new`] starts: the unit tests' small pools, but the
    /// multifield scratch of the fixed host engine (it grows only while no global holds
    /// a multifield, see `Core::scratch_alloc`).
    pub const START: Capacities = Capacities {
        scratch: Capacities::HOST.scratch,
        ..Capacities::SMALL
    };

    /// Limits no pool reaches before its index type's (every one [`INDEX_LIMIT`]).
    pub const NO_LIMIT: Capacities = Capacities::uniform(INDEX_LIMIT);
}

/// An engine whose pools grow ([`GrowStorage`]).
pub type GrowEngine = crate::Engine<GrowStorage>;

impl Default for GrowStorage {
    fn default() -> Self {
        Self::new()
    }
}

/// How a [`Core`] reaches the [`GrowStorage`] it was made from, to grow it (`None` for
/// fixed storage).
#[derive(Clone, Copy)]
pub struct Grower<'a> {
    storage: Option<NonNull<GrowStorage>>,
    life: PhantomData<&'a mut GrowStorage>,
}

impl Grower<'_> {
    /// Fixed storage: a full pool is full.
    pub const NONE: Self = Grower {
        storage: None,
        life: PhantomData,
    };
}

impl Core<'_> {
    /// Makes `pool` hold at least `need` entries: doubles it (or more, to `need`), up
    /// to its limit. The pool's [`CapacityError`] (its capacity as it was) when the
    /// storage is fixed, `need` is over the limit, or the allocator refuses.
    #[cold]
    #[inline(never)]
    pub(crate) fn grow(&mut self, pool: Pool, need: usize) -> Result<(), CapacityError> {
        let have = self.capacities()[pool as usize];
        let full = cap(pool, have);
        let Some(storage) = self.grower.storage else {
            return Err(full);
        };
        // SAFETY: as in `rebind`: the storage this `Core` was made from, reached only
        // through it; read here for its lengths and limits, resized below.
        let s = unsafe { &mut *storage.as_ptr() };
        let ram = s.lens()[pool as usize];
        // entries of a compiled rule base read in place count in `have`, not in `ram`
        let rom = have - ram;
        let limit = s.limits[pool as usize];
        if need <= have {
            return Ok(());
        }
        if need - rom > limit {
            return Err(full);
        }
        let len = (need - rom).max(ram.saturating_mul(2)).min(limit);
        // the support list heads are read only once a rule with `logical` exists
        // (`set_rule_logical_join` empties them then)
        #[cfg(feature = "logical")]
        let fill_deps = self.st.logical.defined;
        #[cfg(not(feature = "logical"))]
        let fill_deps = false;
        s.resize(pool, len, fill_deps).map_err(|()| full)?;
        // hash tables: twice as many buckets as entries (a table that cannot grow
        // keeps its chains, longer)
        let grown_heads = match pool {
            // all new heads in a fresh vector, the old ones dropped: the rehash links
            // only the live facts (copying the seed's heads, filling the new ones and
            // emptying the old ones again cost deepjoin-800 ~40 K instructions)
            Pool::Facts => empty_heads(s.fact_buckets.len(), 2 * len, NONE).map(|fresh| {
                let was = s.fact_buckets.len();
                s.fact_buckets = Buf::Heap(fresh);
                was
            }),
            Pool::Symbols => fresh_heads(&mut s.sym_buckets, 2 * len),
            _ => None,
        };
        self.rebind(pool, storage);
        match (pool, grown_heads) {
            (Pool::Facts, Some(was)) => self.rehash_facts(was),
            (Pool::Symbols, Some(_)) => self.rehash_symbols(),
            _ => {}
        }
        Ok(())
    }

    /// Whether this `Core`'s storage grows.
    #[inline(always)]
    pub(crate) fn grows(&self) -> bool {
        self.grower.storage.is_some()
    }

    /// Builds the duplicate index again for its length now from the live fact list
    /// (the index holds exactly the live facts; their order in a chain does not
    /// matter): one step per fact, with no copy of the old heads and no walk over
    /// the empty buckets of a table twice as long as its pool.
    /// Every head is empty already (`empty_heads`: the table is a new one, longer
    /// than `was`).
    fn rehash_facts(&mut self, was: usize) {
        debug_assert!(self.fact_buckets.len() > was);
        // grown from the host's length by doubling, the table is a power of two
        // long: the remainder is then the hash's low bits (no division per fact)
        let n = self.fact_buckets.len();
        if n.is_power_of_two() {
            self.link_all_facts(|h| h as usize & (n - 1));
        } else {
            self.link_all_facts(|h| h as usize % n);
        }
    }

    /// Puts every live fact at the head of its duplicate-index bucket, `bucket` of
    /// its hash (the remainder by the table's length).
    #[inline(always)]
    fn link_all_facts(&mut self, bucket: impl Fn(u32) -> usize) {
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            // (the fields read, not a copy of the fact)
            let fact = &self.facts[f as usize];
            let next = fact.next;
            #[cfg(feature = "host-speedups")]
            let h = fact.hash;
            #[cfg(not(feature = "host-speedups"))]
            let h = self.cells_hash(fact.tmpl, fact.start as usize, fact.len as usize);
            let b = bucket(h);
            let head = core::mem::replace(&mut self.fact_buckets[b], f);
            self.facts[f as usize].hash_next = head;
            f = next;
        }
    }

    /// Builds the symbol table's buckets again for its length now, newest symbol at
    /// each bucket's head (as interning leaves them; `Symbols::truncate` needs it);
    /// every head is empty already (`fresh_heads`: fresh zeroed memory, none
    /// written), so only the live entries are visited.
    /// Each entry keeps its text's hash (`SymEntry::hash`): a program that makes new
    /// strings as it runs grows the table often, and hashing every text again at each
    /// doubling cost it as much per firing as some of its builtins.
    fn rehash_symbols(&mut self) {
        let rom = self.st.rom.symbols.len();
        let count = (self.st.pools.nsyms as usize).saturating_sub(rom);
        let n = self.sym_buckets.len();
        for k in 0..count {
            let b = self.sym_entries[k].hash as usize % n;
            self.sym_entries[k].next = self.sym_buckets[b].get();
            self.sym_buckets[b] = crate::symbols::Head::of((rom + k) as crate::value::Ix);
        }
    }

    /// At a point where no pattern matching runs (an assert's start): doubles the token
    /// index until it has two buckets per token, and moves every indexed token to its
    /// bucket there (`rete::index`). Keeps the old table if the allocator refuses
    /// (chains longer, results the same).
    #[cold]
    #[inline(never)]
    pub(crate) fn grow_token_index(&mut self) {
        let Some(storage) = self.grower.storage else {
            return;
        };
        // SAFETY: as in `rebind`: the storage this `Core` was made from.
        let s = unsafe { &mut *storage.as_ptr() };
        // new heads, every one empty, in a new vector; the old ones kept where they
        // are for the relink (growforall-800: copying them out and filling the old
        // ones again cost 0.26 M instructions of its one growth)
        let Some(fresh) = empty_heads(s.amem_buckets.len(), 2 * self.tokens.len(), TokenId::NONE)
        else {
            return;
        };
        let old = core::mem::replace(&mut s.amem_buckets, Buf::Heap(fresh));
        self.rebind(Pool::Tokens, storage);
        self.relink_token_index(&old);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::boxed::Box;
    use std::format;
    use std::string::String;

    use super::*;
    use crate::testutil::CaptureHost;
    use crate::DefaultEngine;

    /// Runs `src` as a batch (no echo) on `engine`; returns all output.
    fn run<S: crate::Storage>(engine: &mut crate::Engine<S>, src: &str) -> String {
        let mut host = CaptureHost::default();
        engine.batch_str(&mut host, src, false);
        host.out
    }

    /// Zeroed pages for the tests from the global allocator: `grow` moves a mapping
    /// (a fresh zeroed one, the old bytes copied in), as `mremap` may.
    const TEST_PAGES: ZeroPages = {
        fn layout(bytes: usize) -> core::alloc::Layout {
            core::alloc::Layout::from_size_align(bytes, 16).unwrap()
        }
        fn map(bytes: usize) -> *mut u8 {
            // SAFETY: `bytes` > 0 (`ZeroPages::new`'s contract)
            unsafe { alloc::alloc::alloc_zeroed(layout(bytes)) }
        }
        unsafe fn grow(p: *mut u8, old: usize, new: usize) -> *mut u8 {
            let q = map(new);
            if !q.is_null() {
                // SAFETY: `p` holds `old` bytes (the contract), `q` `new` > `old`;
                // distinct allocations; `p` was allocated by `map` with that layout
                unsafe {
                    core::ptr::copy_nonoverlapping(p, q, old);
                    alloc::alloc::dealloc(p, layout(old));
                }
            }
            q
        }
        unsafe fn unmap(p: *mut u8, bytes: usize) {
            // SAFETY: allocated by `map` or `grow` with this layout (the contract)
            unsafe { alloc::alloc::dealloc(p, layout(bytes)) }
        }
        // SAFETY: zeroed allocations aligned to 16; `grow` keeps the bytes and zeroes
        // the rest (`alloc_zeroed`), and frees the old one only when it succeeds
        unsafe { ZeroPages::new(map, grow, unmap) }
    };

    /// A program past the fixed host engine's pools: 4,500 `n` facts and as many `m`
    /// ones (of 4,096 facts), 520 rules (of 512), joins on a shared variable (the token
    /// index grows under them) and a `not` per rule, with the agenda printed so the
    /// order of what is left shows.
    fn big_program() -> String {
        let mut p = String::from("(defglobal ?*hits* = 0)\n");
        for r in 0..520 {
            p.push_str(&format!(
                "(defrule r{r} (n ?x {r}) (m ?x) (not (gone ?x)) => (bind ?*hits* (+ ?*hits* 1)))\n"
            ));
        }
        p.push_str(
            "(defrule pair (n ?x ?) (m ?x) (test (= (mod ?x 7) 0)) => (assert (gone (+ ?x 3))))\n",
        );
        for i in 0..4500 {
            p.push_str(&format!("(assert (n {i} {}))\n", i % 520));
        }
        for i in (0..4500).rev() {
            p.push_str(&format!("(assert (m {i}))\n"));
        }
        p.push_str("(run 3000)\n(printout t \"hits \" ?*hits* crlf)\n(agenda)\n");
        p.push_str("(printout t (length$ (find-all-facts ((?f gone)) TRUE)) crlf)\n");
        p
    }

    #[test]
    fn a_program_past_the_host_capacities_runs_as_on_a_roomy_fixed_engine() {
        // the fixed engines are built on the stack on their way into the box
        std::thread::Builder::new()
            .stack_size(1 << 30)
            .spawn(past_the_host_capacities)
            .and_then(|t| t.join().map_err(|_| std::io::Error::other("test failed")))
            .unwrap();
    }

    fn past_the_host_capacities() {
        let program = big_program();
        let mut grown = Box::new(GrowEngine::with_storage(GrowStorage::new()));
        let out = run(&mut grown, &program);
        assert!(
            !out.contains("out of "),
            "the growing engine ran out: {out}"
        );
        // (its hash tables rebuilt as they grew: every entry in its bucket)
        if let Err(v) = grown.check_invariants() {
            panic!("{v}");
        }
        assert!(out.contains("hits "), "{out}");
        // every pool it outgrew grew, and the start was the small one
        let stats = grown.stats();
        for pool in [Pool::Facts, Pool::Rules, Pool::Tokens, Pool::FactValues] {
            let (used, capacity) = stats.get(pool);
            assert!(
                used as usize > Capacities::SMALL.get(pool),
                "{pool:?} {used}"
            );
            assert!(capacity >= used, "{pool:?} {used} of {capacity}");
        }
        assert!(stats.get(Pool::Facts).0 as usize > Capacities::HOST.facts);
        // the same run on a fixed engine roomy enough for it (on the heap)
        crate::engine_storage! {
            struct Roomy { facts: 16_384, fact_values: 65_536, rules: 1024, joins: 4096,
                join_memories: 4096, tokens: 262_144, activations: 16_384, exprs: 65_536,
                ..Capacities::HOST }
        }
        let mut fixed = Box::new(crate::Engine::with_storage(Roomy::new()));
        let expected = run(&mut fixed, &program);
        assert!(!expected.contains("out of "), "the roomy engine ran out");
        if let Some((i, (a, b))) = out
            .lines()
            .zip(expected.lines())
            .enumerate()
            .find(|(_, (a, b))| a != b)
        {
            panic!("line {i}: grown {a:?}, fixed {b:?}");
        }
        assert_eq!(out, expected);
        // started in a seed (the CLI's start), it grows out of it the same way
        let seed = Box::leak(Box::new(HostSeed::new()));
        let seeded = GrowStorage::from_seed(seed, GrowStorage::NO_LIMIT);
        assert_eq!(seeded.lens(), Capacities::HOST.to_array());
        // the tokens start in a zeroed reserve (their growth copies nothing), the
        // facts and the bucket heads in the seed
        assert!(matches!(seeded.tokens, Buf::Zeroed(_)));
        assert!(matches!(seeded.facts, Buf::Seed(_)));
        assert!(matches!(seeded.amem_buckets, Buf::Seed(_)));
        let mut seeded = Box::new(GrowEngine::with_storage(seeded));
        assert_eq!(run(&mut seeded, &program), expected);
        assert!(seeded.stats().get(Pool::Facts).1 as usize > Capacities::HOST.facts);
        // started in mapped pages, the zero-free arrays grow there (no copy, no
        // fill: the test's `grow` moves them, as `mremap` may) and it runs the same
        let seed = Box::leak(Box::new(HostSeed::new()));
        let mapped = GrowStorage::from_seed_in(seed, GrowStorage::NO_LIMIT, TEST_PAGES);
        assert!(matches!(mapped.tokens, Buf::Mapped { .. }));
        assert!(matches!(mapped.facts, Buf::Mapped { .. }));
        assert!(matches!(mapped.scratch, Buf::Mapped { .. }));
        assert!(matches!(mapped.amem_buckets, Buf::Seed(_)));
        let mut mapped = Box::new(GrowEngine::with_storage(mapped));
        assert_eq!(run(&mut mapped, &program), expected);
        assert!(mapped.stats().get(Pool::Facts).1 as usize > Capacities::HOST.facts);
        if let Err(v) = mapped.check_invariants() {
            panic!("{v}");
        }
        drop(mapped);
        // and a default (fixed host) engine runs out on it
        let mut small = Box::new(DefaultEngine::new());
        assert!(run(&mut small, &program).contains("out of "));
    }

    #[test]
    fn a_pool_at_its_limit_is_the_capacity_error_and_the_engine_goes_on() {
        let limit = Capacities {
            facts: 200,
            ..GrowStorage::NO_LIMIT
        };
        let mut e = Box::new(GrowEngine::with_storage(GrowStorage::with_limits(
            Capacities::SMALL,
            limit,
        )));
        let mut host = CaptureHost::default();
        let mut last = Ok(());
        for i in 0..300 {
            let r = e.assert_str(&mut host, &format!("(n {i})"));
            if r.is_err() {
                last = r.map(|_| ());
                break;
            }
        }
        match last {
            Err(crate::EngineError::Capacity(c)) => {
                assert_eq!((c.pool, c.capacity), (Pool::Facts, 200));
            }
            other => panic!("expected the facts' capacity error, got {other:?}"),
        }
        // grown up to the limit (from the small start), and nothing lost
        assert_eq!(e.stats().get(Pool::Facts).1, 200);
        let out = run(
            &mut e,
            "(printout t (length$ (find-all-facts ((?f n)) TRUE)) crlf)",
        );
        assert_eq!(out.trim(), "199");
    }

    #[test]
    fn a_full_value_arena_compacts_if_that_frees_a_quarter_and_else_grows_at_once() {
        let mut e = Box::new(GrowEngine::with_storage(GrowStorage::new()));
        let cells = |e: &GrowEngine| e.stats().get(Pool::FactValues).1 as usize;
        let start = cells(&e);
        assert_eq!(start, Capacities::SMALL.fact_values);
        // (the loops' own results are printed before the line asked for)
        let last = |out: &str| String::from(out.trim().lines().last().unwrap_or(""));
        let ok = |e: &mut GrowEngine| {
            if let Err(v) = e.check_invariants() {
                panic!("{v}");
            }
        };
        // one cell a fact: nearly fill the arena, then retract the oldest nine in
        // ten (their cells are garbage below the top)
        let fill = start as i64 - 24;
        let out = run(
            &mut e,
            &format!(
                "(deftemplate n (slot x))
                 (loop-for-count (?i 1 {fill}) (assert (n (x ?i))))
                 (do-for-all-facts ((?f n)) (<= ?f:x {}) (retract ?f))",
                fill * 9 / 10
            ),
        );
        assert!(!out.contains("out of "), "{out}");
        ok(&mut e);
        // the arena fills again: compaction frees most of it, so it does not grow
        let out = run(
            &mut e,
            "(loop-for-count (?i 1 100) (assert (n (x (+ 100000 ?i)))))
             (printout t (length$ (find-all-facts ((?f n)) TRUE)) crlf)",
        );
        ok(&mut e);
        assert_eq!(last(&out), format!("{}", fill - fill * 9 / 10 + 100));
        assert_eq!(cells(&e), start, "compaction made room");
        // facts never retracted: each time it fills it grows (no compaction could
        // free a quarter), and every fact keeps its values
        let out = run(
            &mut e,
            "(loop-for-count (?i 1 5000) (assert (n (x (- 0 ?i)))))
             (printout t (length$ (find-all-facts ((?f n)) TRUE)) \" \"
                 (+ 0 (fact-slot-value (nth$ 1 (find-fact ((?f n)) (= ?f:x -4321))) x)) crlf)",
        );
        ok(&mut e);
        assert_eq!(
            last(&out),
            format!("{} -4321", fill - fill * 9 / 10 + 100 + 5000)
        );
        assert!(cells(&e) > 5000, "{}", cells(&e));
        // and retracting them all leaves an arena that compaction empties
        let out = run(
            &mut e,
            "(do-for-all-facts ((?f n)) TRUE (retract ?f))
             (loop-for-count (?i 1 10) (assert (n (x ?i))))
             (printout t (length$ (find-all-facts ((?f n)) TRUE)) crlf)",
        );
        ok(&mut e);
        assert_eq!(last(&out), "10");
    }

    #[test]
    fn symbols_made_while_the_table_grows_are_found_again() {
        let mut e = Box::new(GrowEngine::with_storage(GrowStorage::new()));
        let start = e.stats().get(Pool::Symbols).1 as usize;
        // several doublings of the table (each puts the symbols in new buckets by the
        // hash each entry kept), then every text made again must be the same symbol:
        // one in a wrong bucket would be interned a second time, and `eq` say FALSE
        let n = 8 * start;
        let out = run(
            &mut e,
            &format!(
                "(defglobal ?*miss* = 0)
                 (loop-for-count (?i 1 {n}) (sym-cat s ?i) (str-cat \"t\" ?i))
                 (loop-for-count (?i 1 {n})
                   (if (or (neq (sym-cat s ?i) (string-to-field (str-cat \"s\" ?i)))
                           (neq (str-cat \"t\" ?i) (sub-string 2 20 (str-cat \"-t\" ?i))))
                    then (bind ?*miss* (+ ?*miss* 1))))
                 (printout t \"miss \" ?*miss* crlf)"
            ),
        );
        assert_eq!(out.trim().lines().last(), Some("miss 0"), "{out}");
        assert!(e.stats().get(Pool::Symbols).1 as usize >= 2 * n);
        if let Err(v) = e.check_invariants() {
            panic!("{v}");
        }
    }

    #[test]
    fn no_limit_is_the_index_types() {
        let s = GrowStorage::with_limits(Capacities::SMALL, Capacities::uniform(usize::MAX));
        assert!(s.limits.iter().all(|&l| l == INDEX_LIMIT));
        assert_eq!(INDEX_LIMIT, NONE as usize - 1);
        assert_eq!(s.lens(), Capacities::SMALL.to_array());
        assert_eq!(GrowStorage::new().lens(), GrowStorage::START.to_array());
    }

    #[test]
    fn a_seed_under_a_limit_starts_at_the_limit() {
        std::thread::Builder::new()
            .stack_size(1 << 28)
            .spawn(|| {
                let seed = Box::leak(Box::new(HostSeed::new()));
                let s = GrowStorage::from_seed(seed, Capacities::uniform(100));
                let lens = s.lens();
                for pool in Pool::ALL {
                    let want = Capacities::HOST.get(pool).min(100);
                    assert_eq!(lens[pool as usize], want, "{pool:?}");
                }
            })
            .and_then(|t| t.join().map_err(|_| std::io::Error::other("test failed")))
            .unwrap();
    }

    #[test]
    fn zero_free_fields() {
        use crate::fact::{Fact, FactState};
        use crate::handle::JoinId;
        use crate::rete::{Token, TokenKind, MAX_MARKS};
        use crate::value::Ix;
        // every field named with its type (no `..`): a field added or changed fails
        // to compile here until the `ZeroFree` proofs cover it
        let Token {
            kind,
            blocked,
            marks,
            owner,
            fact,
            am,
            parent,
            first_child,
            next_sib,
            prev_sib,
            am_next,
            am_prev,
            mem_next,
            mem_prev,
            extra,
            blocks,
            #[cfg(feature = "wide-index")]
            beta_links,
            #[cfg(feature = "host-speedups")]
            binds,
            #[cfg(feature = "host-speedups")]
            has_key,
            #[cfg(feature = "host-speedups")]
            in_x,
            #[cfg(feature = "host-speedups")]
            key,
        } = Token::EMPTY;
        let _: (TokenKind, bool, [u8; MAX_MARKS], JoinId, Ix, Ix) =
            (kind, blocked, marks, owner, fact, extra);
        let _: [TokenId; 10] = [
            am,
            parent,
            first_child,
            next_sib,
            prev_sib,
            am_next,
            am_prev,
            mem_next,
            mem_prev,
            blocks,
        ];
        #[cfg(feature = "wide-index")]
        let _: [Ix; 2] = beta_links;
        #[cfg(feature = "host-speedups")]
        let _: ([Ix; crate::rete::BIND_W], bool, bool, u32) = (binds, has_key, in_x, key);
        let Fact {
            num,
            tmpl,
            start,
            len,
            next,
            prev,
            hash_next,
            first_am,
            state,
            flat,
            #[cfg(feature = "host-speedups")]
            hash,
            #[cfg(all(feature = "host-speedups", feature = "logical"))]
                unsupported: _,
        } = Fact::EMPTY;
        let _: (u32, [Ix; 6], TokenId, FactState, bool) = (
            num,
            [tmpl, start, len, next, prev, hash_next],
            first_am,
            state,
            flat,
        );
        #[cfg(feature = "host-speedups")]
        let _: u32 = hash;
        // the side arrays that are `ZeroFree` (host speed-ups): arrays of `Ix`
        #[cfg(feature = "host-speedups")]
        let _: ([Ix; 2], [[Ix; 3]; crate::rete::XGROUPS]) =
            (crate::fact::NO_TEMPLATE_LINKS, crate::rete::NO_XLINKS);
    }

    #[test]
    fn the_token_and_fact_pools_grow_in_place_into_free_entries() {
        use crate::fact::FactState;
        use crate::rete::TokenKind;
        let mut s = GrowStorage::new();
        let start = s.tokens.len();
        s.resize(Pool::Tokens, 2 * start, true).unwrap();
        let at = s.tokens.as_ptr();
        s.resize(Pool::Tokens, 8 * start, true).unwrap();
        s.resize(Pool::Facts, 4 * s.facts.len(), true).unwrap();
        // within the reserve: not moved, the new entries free (zero), the old kept
        assert_eq!(s.tokens.as_ptr(), at);
        assert_eq!(s.tokens.len(), 8 * start);
        assert!(s.tokens.iter().all(|t| t.kind == TokenKind::Free));
        assert!(s.tokens[start..].iter().all(|t| t.next_sib.0 == 0));
        assert!(s.tokens[..start]
            .iter()
            .all(|t| t.next_sib == TokenId::NONE));
        assert!(s.facts.iter().all(|f| f.state == FactState::Free));
        // the arrays beside them grow in place too: the support heads with their
        // empty value when told (`fill_deps`, else zero), the arrays written before
        // they are read (host speed-ups) zero
        assert_eq!(s.token_deps.len(), 8 * start);
        assert!(s.token_deps.iter().all(|&d| d == crate::logical::NO_DEPS));
        #[cfg(feature = "host-speedups")]
        {
            assert_eq!(s.token_xlinks.len(), 8 * start);
            assert_eq!(s.fact_tlinks.len(), s.facts.len());
            assert!(matches!(s.token_xlinks, Buf::Zeroed(_)));
            assert!(matches!(s.fact_tlinks, Buf::Zeroed(_)));
            let at = s.token_xlinks.as_ptr();
            s.resize(Pool::Tokens, 16 * start, true).unwrap();
            assert_eq!(s.token_xlinks.as_ptr(), at);
        }
        #[cfg(feature = "logical")]
        {
            let was = s.token_deps.len();
            s.resize(Pool::Tokens, 2 * was, false).unwrap();
            assert!(s.token_deps[..was]
                .iter()
                .all(|&d| d == crate::logical::NO_DEPS));
            assert!(s.token_deps[was..].iter().all(|&d| d == 0));
        }
        // a limit under the reserve bounds it
        let mut s = GrowStorage::with_limits(
            Capacities::SMALL,
            Capacities {
                tokens: 3 * Capacities::SMALL.tokens,
                ..GrowStorage::NO_LIMIT
            },
        );
        s.resize(Pool::Tokens, 2 * Capacities::SMALL.tokens, true)
            .unwrap();
        match &s.tokens {
            Buf::Zeroed(v) => assert_eq!(v.capacity(), 3 * Capacities::SMALL.tokens),
            _ => panic!("not grown into zeroed memory"),
        }
    }

    #[cfg(feature = "logical")]
    #[test]
    fn support_heads_grown_before_a_logical_rule_are_emptied_when_it_comes() {
        let mut e = Box::new(GrowEngine::with_storage(GrowStorage::new()));
        let mut p = String::from("(defrule seen (a ?x) =>)\n");
        for i in 0..2000 {
            p.push_str(&format!("(assert (a {i}))\n"));
        }
        p.push_str("(run)\n(dependencies 1900)\n");
        let out = run(&mut e, &p);
        assert!(out.ends_with("None\n"), "{out}");
        // grown while no logical rule existed (their support heads left zero)
        let stats = e.stats();
        assert!(stats.get(Pool::Facts).1 as usize > Capacities::SMALL.facts);
        assert!(stats.get(Pool::Tokens).1 as usize > Capacities::SMALL.tokens);
        let out = run(
            &mut e,
            "(defrule l (logical (a ?x)) (test (>= ?x 1990)) => (assert (b ?x)))\n\
             (run)\n(printout t (length$ (find-all-facts ((?f b)) TRUE)) crlf)\n\
             (retract 1996)\n\
             (printout t (length$ (find-all-facts ((?f b)) TRUE)) crlf)\n\
             (dependencies 1900)\n",
        );
        assert_eq!(out, "10\n9\nNone\n");
        if let Err(v) = e.check_invariants() {
            panic!("{v}");
        }
    }

    #[test]
    fn a_fixed_storage_does_not_grow() {
        let mut e = Box::new(crate::SmallEngine::new());
        let mut host = crate::NullHost;
        let mut core = e.core(&mut host);
        let have = core.capacities()[Pool::Tokens as usize];
        let err = core.grow(Pool::Tokens, have + 1).unwrap_err();
        assert_eq!((err.pool, err.capacity as usize), (Pool::Tokens, have));
    }
}
