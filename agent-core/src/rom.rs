//! Pools whose first entries a compiled rule base provides in place.
//!
//! With the feature `in-place` an engine that loads a [compiled rule
//! base](crate::compiled) reads its expression nodes, alpha nodes and joins from the
//! rule base's read-only tables instead of copying them into its arena: the agent
//! image's RAM. Its symbols too (`symbols::RomSymbols`, with hash chains the compiler
//! works out, `symbols::SymbolIndex`). What changes at run time (alpha and join memories) lives in pools of
//! its own ([`AlphaMem`](crate::rete::AlphaMem), [`JoinMem`](crate::rete::JoinMem)),
//! indexed like the nodes.
//!
//! One index space per pool: entry `i` is compiled when `i < rom_len()`, else arena
//! entry `i - rom_len()`. Without the feature there are no compiled entries and
//! indexing is the arena slice's.
//!
//! Compiled entries are never written. The expression pool only appends after them;
//! the network (alpha nodes and joins) is copied into the arena before the first edit
//! of its topology (`Core::network_writable`), so a host that loads a compiled rule
//! base and then defines or removes rules works as without the feature, and an image
//! whose arena has no room for the copy gets a capacity error.

use crate::expr::Expr;
use crate::handle::Handle;
use crate::rete::{AlphaNode, Join};
use crate::symbols::RomSymbols;
use core::marker::PhantomData;

/// Whether this build reads compiled entries in place (feature `in-place`).
pub const IN_PLACE: bool = cfg!(feature = "in-place");

/// The compiled entries an engine reads in place (all empty without `in-place`, or
/// before a compiled rule base is loaded).
#[derive(Clone, Copy)]
pub struct Rom {
    pub exprs: &'static [Expr],
    pub alphas: &'static [AlphaNode],
    pub joins: &'static [Join],
    pub symbols: RomSymbols,
}

impl Rom {
    pub const EMPTY: Rom = Rom {
        exprs: &[],
        alphas: &[],
        joins: &[],
        symbols: RomSymbols::EMPTY,
    };
}

/// A pool as the engine sees it: compiled entries read in place, then the arena's;
/// indexed by the pool's handle `H` only (see [`crate::handle`]).
pub struct RomPool<'a, T: 'static, H = usize> {
    #[cfg(feature = "in-place")]
    rom: &'static [T],
    ram: &'a mut [T],
    handle: PhantomData<H>,
}

impl<'a, T: 'static, H> RomPool<'a, T, H> {
    /// The pool over `ram`, after the compiled entries `rom` (ignored without
    /// `in-place`).
    #[inline(always)]
    pub fn new(rom: &'static [T], ram: &'a mut [T]) -> Self {
        #[cfg(not(feature = "in-place"))]
        let _ = rom;
        RomPool {
            #[cfg(feature = "in-place")]
            rom,
            ram,
            handle: PhantomData,
        }
    }

    /// Entries addressable: the compiled ones and the arena's.
    #[inline(always)]
    pub fn len(&self) -> usize {
        self.rom_len() + self.ram.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Compiled entries read in place (0 without `in-place`).
    #[inline(always)]
    pub fn rom_len(&self) -> usize {
        #[cfg(feature = "in-place")]
        return self.rom.len();
        #[cfg(not(feature = "in-place"))]
        0
    }

    /// Whether entry `i` may be written (it is in the arena).
    #[inline(always)]
    pub fn writable(&self, i: usize) -> bool {
        i >= self.rom_len() && i < self.len()
    }

    /// Makes `rom` the compiled entries (the engine's `State::rom` says the same).
    #[cfg(feature = "in-place")]
    pub fn set_rom(&mut self, rom: &'static [T]) {
        self.rom = rom;
    }

    /// The arena's entries.
    pub fn ram(&mut self) -> &mut [T] {
        self.ram
    }

    /// Entry `i`, or `None` past the end.
    #[inline(always)]
    pub fn get(&self, i: usize) -> Option<&T> {
        #[cfg(feature = "in-place")]
        if i < self.rom.len() {
            return self.rom.get(i);
        }
        self.ram.get(i - self.rom_len())
    }
}

impl<T: Copy + 'static, H> RomPool<'_, T, H> {
    /// Copies the compiled entries into the arena, after which every entry is the
    /// arena's (indices unchanged). The arena's entries must not be in use yet (the
    /// caller has added none since the compiled ones were set). Refused, changing
    /// nothing, when the arena is smaller than the compiled entries.
    #[cfg(feature = "in-place")]
    pub fn copy_rom_to_ram(&mut self) -> Result<(), usize> {
        let n = self.rom.len();
        if n == 0 {
            return Ok(());
        }
        if n > self.ram.len() {
            return Err(self.ram.len());
        }
        self.ram[..n].copy_from_slice(self.rom);
        self.rom = &[];
        Ok(())
    }
}

impl<T: 'static, H: Handle> core::ops::Index<H> for RomPool<'_, T, H> {
    type Output = T;
    #[inline(always)]
    fn index(&self, h: H) -> &T {
        let i = h.ix();
        #[cfg(feature = "in-place")]
        if i < self.rom.len() {
            return &self.rom[i];
        }
        &self.ram[i - self.rom_len()]
    }
}

impl<T: 'static, H: Handle> core::ops::IndexMut<H> for RomPool<'_, T, H> {
    /// Panics for a compiled entry: nothing writes an entry it did not make (the
    /// expression pool's caches check [`RomPool::writable`] first; the network is
    /// copied into the arena before its topology changes).
    #[inline(always)]
    fn index_mut(&mut self, h: H) -> &mut T {
        let i = h.ix();
        let rom = self.rom_len();
        &mut self.ram[i.checked_sub(rom).expect("compiled entries are read-only")]
    }
}

/// The read-only counterpart of [`RomPool`] (the engine's queries between operations).
pub struct RomRef<'a, T: 'static, H = usize> {
    #[cfg(feature = "in-place")]
    rom: &'static [T],
    ram: &'a [T],
    handle: PhantomData<H>,
}

impl<'a, T: 'static, H> RomRef<'a, T, H> {
    #[inline(always)]
    pub fn new(rom: &'static [T], ram: &'a [T]) -> Self {
        #[cfg(not(feature = "in-place"))]
        let _ = rom;
        RomRef {
            #[cfg(feature = "in-place")]
            rom,
            ram,
            handle: PhantomData,
        }
    }

    #[inline(always)]
    fn rom_len(&self) -> usize {
        #[cfg(feature = "in-place")]
        return self.rom.len();
        #[cfg(not(feature = "in-place"))]
        0
    }

    /// Entries addressable: the compiled ones and the arena's.
    pub fn len(&self) -> usize {
        self.rom_len() + self.ram.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<T: 'static, H: Handle> core::ops::Index<H> for RomRef<'_, T, H> {
    type Output = T;
    #[inline(always)]
    fn index(&self, h: H) -> &T {
        let i = h.ix();
        #[cfg(feature = "in-place")]
        if i < self.rom.len() {
            return &self.rom[i];
        }
        &self.ram[i - self.rom_len()]
    }
}
