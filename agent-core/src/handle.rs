//! Typed handles: one index type per pool, so that one pool's index cannot reach
//! another's entries.
//!
//! A handle is its pool's [`Ix`] in a `#[repr(transparent)]` newtype: the same bytes
//! in every entry that links to it, the same code for every comparison and index. The
//! engine's view of a pool ([`Slots`], the fields of [`Core`](crate::Core)) is indexed
//! only by that pool's handle:
//! ```
//! fn first_child(c: &agent_core::Core, j: agent_core::JoinId) -> agent_core::JoinId {
//!     c.joins[j].first_child
//! }
//! ```
//! A token's index does not index the joins:
//! ```compile_fail
//! fn first_child(c: &agent_core::Core, t: agent_core::TokenId) -> agent_core::JoinId {
//!     c.joins[t].first_child
//! }
//! ```
//! nor does a bare number:
//! ```compile_fail
//! fn first_child(c: &agent_core::Core, j: usize) -> agent_core::JoinId {
//!     c.joins[j].first_child
//! }
//! ```
//! Crossing pools is a visible conversion (`JoinId(x.0)`), made only where one field
//! holds entries of two pools by kind (a token's `owner`: an alpha node or a join).

use crate::value::{Ix, NONE};
use core::marker::PhantomData;
use core::ops::{Index, IndexMut};

/// A pool's typed index.
pub trait Handle: Copy {
    /// The entry's place in its pool's array.
    fn ix(self) -> usize;
}

/// The untyped index of a pool that has no handle of its own yet.
impl Handle for usize {
    #[inline(always)]
    fn ix(self) -> usize {
        self
    }
}

macro_rules! handles {
    ($($(#[$meta:meta])* $name:ident;)*) => {$(
        $(#[$meta])*
        #[repr(transparent)]
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
        pub struct $name(pub Ix);

        impl $name {
            /// No entry (a list's end, a missing link).
            pub const NONE: $name = $name(NONE);

            /// The entry's place in its pool's array.
            #[inline(always)]
            pub const fn ix(self) -> usize {
                self.0 as usize
            }

            /// The handle of the entry at `i` (below the pool's capacity, which fits
            /// [`Ix`]: capacities beyond it do not compile).
            #[inline(always)]
            pub const fn at(i: usize) -> $name {
                $name(i as Ix)
            }

            #[inline(always)]
            pub const fn is_none(self) -> bool {
                self.0 == NONE
            }

            #[inline(always)]
            pub const fn is_some(self) -> bool {
                self.0 != NONE
            }
        }

        impl Handle for $name {
            #[inline(always)]
            fn ix(self) -> usize {
                self.0 as usize
            }
        }
    )*};
}

impl JoinId {
    /// The root join (made at start-up, holding the empty root token).
    pub const ROOT: JoinId = JoinId(0);
}

handles! {
    /// A join of the beta network (`Core::joins`; join 0 is the root).
    JoinId;
    /// A token: an alpha match or a partial match (`Core::tokens`).
    TokenId;
}

/// A pool's entries as the engine sees them: indexed by the pool's handle `H` only.
pub struct Slots<'a, H, T> {
    items: &'a mut [T],
    handle: PhantomData<H>,
}

impl<'a, H: Handle, T> Slots<'a, H, T> {
    #[inline(always)]
    pub fn new(items: &'a mut [T]) -> Self {
        Slots {
            items,
            handle: PhantomData,
        }
    }

    /// The capacity of the pool.
    #[inline(always)]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Every entry, by place (walks over the whole pool: checks, wipes, writers).
    #[inline(always)]
    pub fn as_slice(&self) -> &[T] {
        self.items
    }

    #[inline(always)]
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        self.items
    }

    /// A second view of the same entries, held by value (its address and length stay
    /// in registers across stores to the entries, where a reference to the view
    /// would be read again).
    #[inline(always)]
    pub fn view(&mut self) -> Slots<'_, H, T> {
        Slots::new(self.items)
    }

    #[inline(always)]
    pub fn get(&self, h: H) -> Option<&T> {
        self.items.get(h.ix())
    }

    #[inline(always)]
    pub fn iter(&self) -> core::slice::Iter<'_, T> {
        self.items.iter()
    }

    #[inline(always)]
    pub fn iter_mut(&mut self) -> core::slice::IterMut<'_, T> {
        self.items.iter_mut()
    }
}

impl<H: Handle, T> Index<H> for Slots<'_, H, T> {
    type Output = T;
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index(&self, h: H) -> &T {
        match self.items.get(h.ix()) {
            Some(x) => x,
            None => out_of_range(),
        }
    }
}

impl<H: Handle, T> IndexMut<H> for Slots<'_, H, T> {
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index_mut(&mut self, h: H) -> &mut T {
        match self.items.get_mut(h.ix()) {
            Some(x) => x,
            None => out_of_range(),
        }
    }
}

/// A handle past its pool's end, or a compiled (read-only) entry written: a broken
/// link, never input. One shared call instead of
/// a bounds-check panic per indexing site, whose code and location record (16 bytes of
/// read-only data each, hundreds of sites) the image's code budget cannot spare. Debug
/// builds still report the indexing site (`track_caller`).
#[cold]
#[inline(never)]
#[cfg_attr(debug_assertions, track_caller)]
pub fn out_of_range() -> ! {
    panic!("pool handle out of range, or a compiled entry written")
}

/// A pool's entries, read only (the engine's queries between operations): indexed by
/// the pool's handle `H` only.
pub struct SlotsRef<'a, H, T> {
    items: &'a [T],
    handle: PhantomData<H>,
}

impl<'a, H: Handle, T> SlotsRef<'a, H, T> {
    #[inline(always)]
    pub fn new(items: &'a [T]) -> Self {
        SlotsRef {
            items,
            handle: PhantomData,
        }
    }

    #[inline(always)]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    #[inline(always)]
    pub fn as_slice(&self) -> &'a [T] {
        self.items
    }
}

impl<H: Handle, T> Index<H> for SlotsRef<'_, H, T> {
    type Output = T;
    #[inline(always)]
    #[cfg_attr(debug_assertions, track_caller)]
    fn index(&self, h: H) -> &T {
        match self.items.get(h.ix()) {
            Some(x) => x,
            None => out_of_range(),
        }
    }
}
