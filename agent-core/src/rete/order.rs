//! Host (feature `grow`): the order in which a join primed from an older sibling meets
//! the partial matches that existed when it was added, as CLIPS 6.30 does.
//!
//! CLIPS keeps a left memory per join: a copy of every partial match its parent made,
//! in hash buckets (the values the join compares with earlier variables, `clips_hash`;
//! one bucket for a join without such tests), each bucket a list that a new copy
//! enters at its head. A join added to a parent that already has partial matches is
//! primed from the first of its older siblings (children list, newest first): it
//! copies that sibling's memory bucket by bucket, each copy entering its own memory at
//! the head. Our joins share their parent's memory (newest first), which is CLIPS's
//! order only for a join made before any of its parent's partial matches existed.
//!
//! So a join primed while its parent had partial matches keeps those matches here, in
//! its own order (`Primed::order`, reverse of the order it was primed in); a partial
//! match is told apart from later ones by its stamp (`PrimeOrders::stamps`, by token:
//! while any join keeps such an order, every partial match entering the head of a
//! memory gets the next one, see `Core::stamp`; the others keep an older stamp, or
//! none, which reads as 0, so every stamp a token has is below the clock): the join's
//! right activations visit the later ones first (memory order), then these. An entry
//! whose partial match is gone (or whose id was reused: another stamp) is skipped, and
//! a join whose entries are all gone is dropped. Nothing is stamped while no join
//! keeps an order: programs that define their rules before their facts pay a test of
//! an empty list per partial match, no bytes per token. Not modelled: CLIPS's bucket arrays
//! growing past 187 partial matches (11 times larger), which reorders buckets.

use alloc::vec::Vec;

use super::{JoinKind, TokenKind, MAX_RHASH};
use crate::engine::Core;
use crate::error::EvalError;
use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use crate::value::{Value, NONE};

/// A join primed while its parent had partial matches.
pub struct Primed {
    pub join: JoinId,
    /// Stamps below this one are the partial matches it was primed with.
    pub born: u32,
    /// Those partial matches (and their stamps) in the join's order, first first.
    pub order: Vec<(TokenId, u32)>,
    /// A join from the right primed while its subnetwork's end had partial matches
    /// (`order`: those, unordered): CLIPS's copies of them in its right memory are
    /// younger than every copy their walk made (`take_back_primed`). Such an entry
    /// orders no memory.
    pub right: bool,
}

/// `PrimeOrders::slow`: some join keeps a primed order (`joins` holds an entry that
/// is not `right`).
pub const SLOW_PRIMED: u8 = 1;
/// `PrimeOrders::slow`: the alpha match `twin_am` may have an older twin
/// (`Core::twin_blocks`; the bit may outlive its match: the id is compared).
#[cfg(feature = "host-speedups")]
pub const SLOW_TWIN: u8 = 2;

/// The primed joins and the stamps (`State::prime`).
pub struct PrimeOrders {
    /// The next stamp (above every stamp given; 0 is no stamp).
    pub clock: u32,
    pub joins: Vec<Primed>,
    /// Each token's stamp (by id; missing entries read as 0).
    pub stamps: crate::grow::ZeroedU32,
    /// `SLOW_*` bits: whether a right activation takes the way out of line
    /// (`right_activate_maybe_primed`); one byte, so that programs with neither pay
    /// one test for both.
    pub slow: u8,
    /// Host: the alpha match `SLOW_TWIN` is for, and the last of its node's
    /// successor joins that may skip its walk (`Core::twin_mark`).
    #[cfg(feature = "host-speedups")]
    pub twin: (TokenId, JoinId),
    /// Host: alpha nodes (by id modulo 256) that feed a not/exists join that may
    /// skip walks (`Core::twin_joinable`): only their matches are asked about twins
    /// (a shared bit, or one left by a removed rule, only costs a question).
    #[cfg(feature = "host-speedups")]
    pub twin_alphas: [bool; 256],
    /// Alpha nodes (by id modulo 256) one of whose joins has an earlier join of the
    /// same node among its ancestors: their matches' retracts look for partial
    /// matches built on the same alpha match twice (`Core::take_back_newer_copies`).
    pub self_joined: [bool; 256],
    /// Each join's `next_fact_num` when it was made (by id; 0, or missing: before
    /// every fact there is, as after a reset): a partial match built through a
    /// join made after an ancestor's facts was not built in that ancestor's walk.
    pub join_born: Vec<u32>,
    /// By join id: the join takes matches of an alpha node one of its ancestors
    /// takes too (see `self_joined`).
    pub rejoins: Vec<bool>,
    /// Some alpha node is `self_joined`.
    pub any_self: bool,
    /// A retract places CLIPS's copies among an alpha match's partial matches
    /// (`Core::remove_alpha_children_placed`): `any_self`, or a primed order kept.
    pub placed: bool,
    /// A `logical` rule was defined (`LogicalState::defined`).
    pub logical: bool,
    /// `placed` or `logical`: a retract takes the slow path (`Core::retract_fact_held`).
    pub slow_retract: bool,
}

impl PrimeOrders {
    pub const fn new() -> PrimeOrders {
        PrimeOrders {
            clock: 1,
            joins: Vec::new(),
            stamps: crate::grow::ZeroedU32::new(),
            slow: 0,
            #[cfg(feature = "host-speedups")]
            twin: (TokenId::NONE, JoinId::NONE),
            #[cfg(feature = "host-speedups")]
            twin_alphas: [false; 256],
            self_joined: [false; 256],
            join_born: Vec::new(),
            rejoins: Vec::new(),
            any_self: false,
            placed: false,
            logical: false,
            slow_retract: false,
        }
    }

    /// Keeps `SLOW_PRIMED` with `joins` (after each change of it).
    fn joins_changed(&mut self) {
        // (entries of joins from the right order no memory: stamps only)
        if self.joins.iter().all(|p| p.right) {
            self.slow &= !SLOW_PRIMED;
        } else {
            self.slow |= SLOW_PRIMED;
        }
        self.placed = self.any_self || !self.joins.is_empty();
        self.slow_retract = self.placed || self.logical;
    }

    /// Host: whether alpha node `alpha` may feed a `twin_joinable` join.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub fn twin_alpha(&self, alpha: Ix) -> bool {
        self.twin_alphas[alpha as u8 as usize]
    }

    /// Host: alpha node `alpha` feeds a `twin_joinable` join.
    #[cfg(feature = "host-speedups")]
    pub fn set_twin_alpha(&mut self, alpha: Ix) {
        self.twin_alphas[alpha as u8 as usize] = true;
    }

    /// Whether alpha node `alpha` may be `self_joined`.
    #[inline(always)]
    pub fn self_joined(&self, alpha: Ix) -> bool {
        self.self_joined[alpha as u8 as usize]
    }

    /// Records `join` as primed now with `order` (its left memory's, or for a join
    /// from the right, `right`, its subnetwork end's partial matches), replacing an
    /// entry it had.
    fn set_primed(&mut self, join: JoinId, order: Vec<(TokenId, u32)>, right: bool) {
        let born = self.clock;
        let k = if right {
            self.find_right(join)
        } else {
            self.find(join)
        };
        match k {
            Some(k) => {
                self.joins[k].born = born;
                self.joins[k].order = order;
            }
            None => self.joins.push(Primed {
                join,
                born,
                order,
                right,
            }),
        }
        self.joins_changed();
    }

    /// The left-memory order entry of `join`.
    fn find(&self, join: JoinId) -> Option<usize> {
        self.joins.iter().position(|p| p.join == join && !p.right)
    }

    /// The right-memory entry of join from the right `join`.
    fn find_right(&self, join: JoinId) -> Option<usize> {
        self.joins.iter().position(|p| p.join == join && p.right)
    }
}

impl Default for PrimeOrders {
    fn default() -> Self {
        Self::new()
    }
}

/// CLIPS 6.30's hash table sizes (`symbol.h`) and first beta-memory size (`network.h`).
const SYMBOL_HASH_SIZE: u64 = 63559;
const FLOAT_HASH_SIZE: u64 = 8191;
const INTEGER_HASH_SIZE: u64 = 8191;
const BETA_BUCKETS: u64 = 17;

/// The bucket of a string in CLIPS's symbol table (symbols and strings share it).
fn clips_symbol_bucket(s: &[u8]) -> u64 {
    let mut tally: u64 = 0;
    for &b in s {
        // (CLIPS adds a `char`, signed on the hosts it runs on)
        tally = tally.wrapping_mul(127).wrapping_add(b as i8 as i64 as u64);
    }
    tally % SYMBOL_HASH_SIZE
}

fn clips_float_bucket(f: f64) -> u64 {
    let mut tally: u64 = 0;
    for b in f.to_ne_bytes() {
        tally = tally.wrapping_mul(127).wrapping_add(b as i8 as i64 as u64);
    }
    tally % FLOAT_HASH_SIZE
}

fn clips_integer_bucket(i: i64) -> u64 {
    u64::from(i.unsigned_abs() as u32) % INTEGER_HASH_SIZE
}

impl Core<'_> {
    /// Gives a partial match that enters the head of its memory the next stamp.
    #[inline(never)]
    pub(crate) fn stamp(&mut self, t: TokenId) {
        let p = &mut self.st.prime;
        let i = t.ix();
        if i >= p.stamps.len() {
            // (room for the whole pool at once; a refused allocation loses the
            // orders, which are then CLIPS's no more, never the stamps' meaning)
            let want = self.tokens.len().max(i + 1);
            if !p.stamps.grow_to(want) {
                p.joins.clear();
                return;
            }
        }
        p.stamps[i] = p.clock;
        p.clock = p.clock.wrapping_add(1);
        if p.clock == 0 {
            // (after 2^32 stamps) older stamps would read as newer: all go
            p.joins.clear();
            p.stamps.clear();
            p.clock = 1;
        }
    }

    /// A token's stamp (0: none).
    #[inline(always)]
    pub(super) fn seq_of(&self, t: TokenId) -> u32 {
        self.st.prime.stamps.get(t.ix()).copied().unwrap_or(0)
    }

    /// Drops the primed orders (every partial match went: `clear`, `reset`).
    pub(crate) fn forget_prime_orders(&mut self) {
        self.st.prime.joins.clear();
        self.st.prime.joins_changed();
    }

    /// Whether entry `(t, seq)` of a primed join under `parent` is still its
    /// partial match.
    fn primed_live(&self, t: TokenId, seq: u32, parent: JoinId) -> bool {
        let tk = &self.tokens[t];
        tk.kind == TokenKind::Beta && self.seq_of(t) == seq && tk.owner == parent
    }

    /// When `join` was primed (its entry's `born`) if partial match `t` of its parent
    /// (for a join from the right, `from_right`: of its subnetwork's end) existed then
    /// (its copy in CLIPS's memory of `join` is younger than `t`).
    pub(crate) fn primed_after(&self, join: JoinId, t: TokenId, from_right: bool) -> Option<u32> {
        let k = if from_right {
            self.st.prime.find_right(join)?
        } else {
            self.st.prime.find(join)?
        };
        let born = self.st.prime.joins[k].born;
        (self.seq_of(t) < born).then_some(born)
    }

    /// The primed-order entry of `join`, if it has one.
    #[inline(always)]
    pub(crate) fn primed_entry(&self, join: JoinId) -> Option<usize> {
        if self.st.prime.joins.is_empty() {
            return None;
        }
        self.st.prime.find(join)
    }

    /// A join's left memory in CLIPS's order: `parent`'s active partial matches,
    /// those `join` was primed with (if it was) last, in its own order.
    pub(crate) fn clips_memory_order(&self, join: JoinId, parent: JoinId) -> Vec<TokenId> {
        let entry = self.primed_entry(join).map(|k| &self.st.prime.joins[k]);
        let mut out = Vec::new();
        let mut l = self.join_mems[parent].mem;
        while l != TokenId::NONE {
            if self.token_active(l) && entry.is_none_or(|e| self.seq_of(l) >= e.born) {
                out.push(l);
            }
            l = self.tokens[l].mem_next;
        }
        if let Some(e) = entry {
            for &(t, s) in &e.order {
                if self.primed_live(t, s, parent) && self.token_active(t) {
                    out.push(t);
                }
            }
        }
        out
    }

    /// CLIPS's hash of a partial match in `join`'s left memory (`BetaMemoryHashValue`
    /// of its left hash: the earlier variables its equality tests compare with, each
    /// value's symbol-table bucket, the last field's once, the one before it 509
    /// times, and so on), None for a join without one (CLIPS's memory has a single
    /// bucket then).
    fn clips_left_hash(&mut self, join: JoinId, left: TokenId) -> Option<u64> {
        let j = self.joins[join];
        if j.alpha == NONE
            || j.rjoin != JoinId::NONE
            || !matches!(
                j.kind,
                JoinKind::Positive | JoinKind::Negative | JoinKind::Exists
            )
        {
            return None;
        }
        let nrhash = self.alphas[j.alpha as usize].nrhash;
        if nrhash == 0 {
            return None;
        }
        self.bind_left(left);
        let mut buckets = [0u64; MAX_RHASH];
        let mut k = 0;
        let found = self.each_left_key_value(join, nrhash, |cx, v| {
            buckets[k] = v.map_or(0, |v| cx.clips_bucket(v));
            k += 1;
        });
        // the last compared field counts once, each earlier one 509 times more
        let mut hash = 0u64;
        for &b in &buckets[..found as usize] {
            hash = hash.wrapping_mul(509).wrapping_add(b);
        }
        Some(hash)
    }

    /// The bucket of a value in CLIPS's tables (0 for what has none there).
    fn clips_bucket(&self, v: Value) -> u64 {
        match v {
            Value::Sym(s) | Value::Str(s) => clips_symbol_bucket(self.sym_text(s).as_bytes()),
            Value::Int(i) => clips_integer_bucket(i),
            Value::Float(f) => clips_float_bucket(f),
            _ => 0,
        }
    }

    /// Primes new join `join` (its parent `parent` is old) as CLIPS does when a
    /// rule is added: with the memory of its first older sibling (joins from
    /// `first_new` on are new), bucket by bucket, and notes the order the join
    /// keeps those partial matches in. False if it has no older sibling (then the
    /// caller feeds it the parent's memory).
    pub(crate) fn prime_join_ordered(
        &mut self,
        join: JoinId,
        parent: JoinId,
        first_new: JoinId,
    ) -> Result<bool, EvalError> {
        let mut src = self.joins[parent].first_child;
        while src != JoinId::NONE && (src == join || src >= first_new) {
            src = self.joins[src].next_sibling;
        }
        if src == JoinId::NONE {
            return Ok(false);
        }
        self.prune_prime_orders();
        let mut seq = self.clips_memory_order(src, parent);
        // bucket by bucket (a stable sort keeps each bucket's order)
        let mut keyed: Vec<(u64, TokenId)> = Vec::with_capacity(seq.len());
        let mut hashed = false;
        for &t in &seq {
            let h = self.clips_left_hash(src, t);
            hashed |= h.is_some();
            keyed.push((h.unwrap_or(0) % BETA_BUCKETS, t));
        }
        if hashed {
            keyed.sort_by_key(|&(b, _)| b);
            seq = keyed.iter().map(|&(_, t)| t).collect();
        }
        let order: Vec<(TokenId, u32)> = seq.iter().rev().map(|&t| (t, self.seq_of(t))).collect();
        self.st.prime.set_primed(join, order, false);
        for t in seq {
            // (a token priming took back meanwhile is not fed)
            if self.tokens[t].kind == TokenKind::Beta
                && self.tokens[t].owner == parent
                && self.token_active(t)
            {
                self.left_activate(join, t)?;
            }
        }
        Ok(true)
    }

    /// Notes new join from the right `join` as primed now (CLIPS's
    /// `PrimeJoinFromRightMemory`), if its subnetwork's end (old) has partial
    /// matches: their copies CLIPS makes for it are younger than the others.
    pub(crate) fn note_right_primed(&mut self, join: JoinId) {
        let rjoin = self.joins[join].rjoin;
        let mut order = Vec::new();
        let mut l = self.join_mems[rjoin].mem;
        while l != TokenId::NONE {
            order.push((l, self.seq_of(l)));
            l = self.tokens[l].mem_next;
        }
        if order.is_empty() {
            return;
        }
        self.prune_prime_orders();
        self.st.prime.set_primed(join, order, true);
    }

    /// Drops the entries of joins that are gone and of those whose primed partial
    /// matches all went.
    fn prune_prime_orders(&mut self) {
        let mut k = 0;
        while k < self.st.prime.joins.len() {
            let e = &self.st.prime.joins[k];
            let j = e.join;
            let alive = j.0 < self.st.pools.njoins && self.joins[j].refs > 0 && {
                let parent = if e.right {
                    self.joins[j].rjoin
                } else {
                    self.joins[j].parent
                };
                e.order.iter().any(|&(t, s)| self.primed_live(t, s, parent))
            };
            if alive {
                k += 1;
            } else {
                self.st.prime.joins.swap_remove(k);
            }
        }
        self.st.prime.joins_changed();
    }

    /// `right_activate`'s walk for a primed join (entry `k`): the partial matches
    /// made since it was primed in memory order, then those it was primed with in
    /// its own order (along an index bucket: those the bucket holds); `right_one`
    /// handles each. (Not inlined: `right_activate` stays as small as without it.)
    #[inline(never)]
    pub(crate) fn right_activate_primed(
        &mut self,
        join: JoinId,
        am: TokenId,
        k: usize,
        all_active: bool,
    ) -> Result<(), EvalError> {
        let (parent, kind) = (self.joins[join].parent, self.joins[join].kind);
        let born = self.st.prime.joins[k].born;
        let (mut l, via) = self.first_left(join, am);
        // the primed partial matches a walk along an index bucket meets: only these
        // are candidates (as for any other join), in the join's order below
        let mut met: Vec<TokenId> = Vec::new();
        while l != TokenId::NONE {
            let next = self.next_left(l, via);
            if self.seq_of(l) >= born {
                if all_active || self.token_active(l) {
                    self.right_one(join, kind, l, am)?;
                }
            } else if via != 0 {
                met.push(l);
            }
            l = next;
        }
        met.sort_unstable();
        // (right activations add no primed joins: the entry stays at `k`)
        let mut i = 0;
        let mut live = 0;
        while let Some(&(t, s)) = self.st.prime.joins.get(k).and_then(|e| e.order.get(i)) {
            if self.primed_live(t, s, parent) {
                live += 1;
                if (via == 0 || met.binary_search(&t).is_ok())
                    && (all_active || self.token_active(t))
                {
                    self.right_one(join, kind, t, am)?;
                }
            }
            i += 1;
        }
        if live == 0 && k < self.st.prime.joins.len() {
            self.st.prime.joins.swap_remove(k);
            self.st.prime.joins_changed();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clips_buckets() {
        // "a" is 97; "ab" is 97 * 127 + 98
        assert_eq!(clips_symbol_bucket(b"a"), 97);
        assert_eq!(
            clips_symbol_bucket(b"ab"),
            (97 * 127 + 98) % SYMBOL_HASH_SIZE
        );
        assert_eq!(clips_integer_bucket(-5), 5);
        assert_eq!(clips_integer_bucket(8191 + 3), 3);
    }
}
