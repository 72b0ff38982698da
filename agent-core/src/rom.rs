//! Pools whose first entries a compiled rule base provides in place.
//!
//! With the feature `in-place` an engine that loads a [compiled rule
//! base](crate::compiled) reads its expression nodes, alpha nodes, joins, templates,
//! slot definitions and rules from the rule base's read-only tables instead of copying
//! them into its arena: the agent image's RAM. Its symbols too
//! (`symbols::RomSymbols`, with hash chains the compiler works out,
//! `symbols::SymbolIndex`). What changes at run time (alpha, join and template
//! memories) lives in pools of its own ([`AlphaMem`](crate::rete::AlphaMem),
//! [`JoinMem`](crate::rete::JoinMem), [`TemplateMem`](crate::template::TemplateMem)),
//! indexed like the entries.
//!
//! One index space per pool: entry `i` is compiled when `i < rom_len()`, else arena
//! entry `i - rom_len()`. Without the feature there are no compiled entries and
//! indexing is the arena slice's.
//!
//! Compiled entries are never written. The expression pool only appends after them
//! (templates and slot definitions too, for ordered facts of a new relation); the
//! network and the constructs it hangs off (alpha nodes, joins, templates, slot
//! definitions, rules) are copied into the arena before the first edit of a compiled
//! entry (`Core::network_writable`: a rule defined or removed, a template redefined or
//! removed, a salience evaluated again), so a host that loads a compiled rule base and
//! then defines or removes rules works as without the feature, and an image whose
//! arena has no room for the copy gets a capacity error.

use crate::expr::Expr;
use crate::handle::Handle;
use crate::rete::{AlphaNode, Join};
use crate::rule::Rule;
use crate::symbols::RomSymbols;
use crate::template::{SlotDef, Template};
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
    pub templates: &'static [Template],
    pub slots: &'static [SlotDef],
    pub rules: &'static [Rule],
    pub symbols: RomSymbols,
}

impl Rom {
    pub const EMPTY: Rom = Rom {
        exprs: &[],
        alphas: &[],
        joins: &[],
        templates: &[],
        slots: &[],
        rules: &[],
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

    /// Every addressable entry in index order: the compiled ones, then the arena's.
    pub fn iter(&self) -> impl Iterator<Item = &T> + '_ {
        #[cfg(feature = "in-place")]
        let rom = self.rom.iter();
        #[cfg(not(feature = "in-place"))]
        let rom = [].iter();
        rom.chain(self.ram.iter())
    }

    /// The read-only view of the same entries.
    pub fn as_ref(&self) -> RomRef<'_, T, H> {
        #[cfg(feature = "in-place")]
        return RomRef::new(self.rom, self.ram);
        #[cfg(not(feature = "in-place"))]
        RomRef::new(&[], self.ram)
    }
}

impl<T: Copy + 'static, H> RomPool<'_, T, H> {
    /// Whether [`RomPool::copy_rom_to_ram`] has room with `used` entries in use.
    #[cfg(feature = "in-place")]
    pub fn fits_in_ram(&self, used: usize) -> bool {
        used.max(self.rom.len()) <= self.ram.len()
    }

    /// Copies the compiled entries into the arena, after which every entry is the
    /// arena's (indices unchanged): the arena's entries in use (`used` counts every
    /// entry in use, compiled ones too) move up behind them. Refused, changing
    /// nothing, when the arena is too small for all of them; `Err` holds its size.
    #[cfg(feature = "in-place")]
    pub fn copy_rom_to_ram(&mut self, used: usize) -> Result<(), usize> {
        let n = self.rom.len();
        if n == 0 {
            return Ok(());
        }
        if !self.fits_in_ram(used) {
            return Err(self.ram.len());
        }
        let made = used.saturating_sub(n);
        self.ram.copy_within(..made, n);
        self.ram[..n].copy_from_slice(self.rom);
        self.rom = &[];
        Ok(())
    }
}

impl<T: 'static, H: Handle> core::ops::Index<H> for RomPool<'_, T, H> {
    type Output = T;
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index(&self, h: H) -> &T {
        match self.get(h.ix()) {
            Some(x) => x,
            None => crate::handle::out_of_range(),
        }
    }
}

impl<T: 'static, H: Handle> core::ops::IndexMut<H> for RomPool<'_, T, H> {
    /// Panics for a compiled entry: nothing writes an entry it did not make (the
    /// expression pool's caches check [`RomPool::writable`] first; the network is
    /// copied into the arena before its topology changes).
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index_mut(&mut self, h: H) -> &mut T {
        // a compiled entry's place wraps past the arena's end: the same one check
        match self.ram.get_mut(h.ix().wrapping_sub(self.rom_len())) {
            Some(x) => x,
            None => crate::handle::out_of_range(),
        }
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

    /// Entry `i`, or `None` past the end.
    #[inline(always)]
    pub fn get(&self, i: usize) -> Option<&'a T> {
        #[cfg(feature = "in-place")]
        if i < self.rom.len() {
            return self.rom.get(i);
        }
        self.ram.get(i - self.rom_len())
    }

    /// Every addressable entry in index order: the compiled ones, then the arena's.
    pub fn iter(&self) -> impl Iterator<Item = &'a T> + 'a {
        #[cfg(feature = "in-place")]
        let rom: core::slice::Iter<'a, T> = self.rom.iter();
        #[cfg(not(feature = "in-place"))]
        let rom: core::slice::Iter<'a, T> = [].iter();
        rom.chain(self.ram.iter())
    }
}

impl<T: 'static, H> Clone for RomRef<'_, T, H> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: 'static, H> Copy for RomRef<'_, T, H> {}

impl<T: 'static, H: Handle> core::ops::Index<H> for RomRef<'_, T, H> {
    type Output = T;
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index(&self, h: H) -> &T {
        match self.get(h.ix()) {
            Some(x) => x,
            None => crate::handle::out_of_range(),
        }
    }
}
