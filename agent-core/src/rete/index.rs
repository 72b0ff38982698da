//! Alpha-memory index: the alpha matches of a node whose joins compare fields for
//! equality with earlier variables (its right hash, as in CLIPS) are also chained in
//! buckets of one engine-wide table, keyed by the node and the values of those
//! fields. A join then visits only the bucket of its left token's values instead of
//! the whole memory. Within a bucket matches keep memory order (oldest first), so the
//! visiting order, and with it every activation order, is that of a full scan; the
//! join tests still run on every candidate, so collisions cost time, never results.
//!
//! Alpha tokens use fields they otherwise leave empty: `am_next`/`am_prev` chain the
//! bucket (the head's `am_prev` is the tail, so appending is O(1)), `parent` keeps the
//! bucket number. No allocation, no extra bytes per token.

use super::{JoinKind, PatBinding, TokenKind, MAX_RHASH, THIS_PATTERN};
#[cfg(feature = "host-speedups")]
use super::{XGROUPS, XMAP, XSCAN};
use crate::engine::Core;
use crate::error::EvalError;
#[cfg(feature = "host-speedups")]
use crate::eval::Place;
use crate::expr::{loc, Op};
use crate::handle::{JoinId, TokenId};
#[cfg(feature = "host-speedups")]
use crate::rete::plan::SegRead;
use crate::value::{Ix, Value, NONE};

/// `Core::value_hash` of a single-field value (no multifield to walk; callers
/// pass multifields to `value_hash`, which hashes their items).
#[inline(always)]
fn atom_hash(v: Value) -> u32 {
    match v {
        Value::Void | Value::BoundVoid | Value::Multi(_) => 1,
        Value::Int(i) => mix(2, i as u32 ^ (i >> 32) as u32),
        Value::Float(f) => {
            let bits = if f == 0.0 { 0 } else { f.to_bits() };
            mix(3, bits as u32 ^ (bits >> 32) as u32)
        }
        Value::Sym(s) => mix(4, u32::from(s)),
        Value::Str(s) => mix(5, u32::from(s)),
        Value::Fact(r) => mix(6, r.num),
    }
}

/// Entries of the key-plan cache (`State::key_plans`, direct-mapped by join): on
/// the host enough for programs of a few dozen joins (a miss rebuilds the plan).
#[cfg(not(feature = "host-speedups"))]
pub const KEY_PLANS: usize = 8;
#[cfg(feature = "host-speedups")]
pub const KEY_PLANS: usize = 32;

/// The fields a join's left key reads, worked out once from its tests: pattern
/// index and slot of each earlier variable its equality tests compare with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KeyPlan {
    pub join: JoinId,
    /// The join's test chain (a reused join id has another one).
    pub tests: Ix,
    /// Number of fields; `KeyPlan::NONE.n` when the evaluator must compute the key.
    pub n: u8,
    pub vars: [(u8, u8); MAX_RHASH],
    /// Host: per field, the element of a multislot it reads (at a fixed offset:
    /// every element before it single-field), or `WHOLE_SLOT`.
    #[cfg(feature = "host-speedups")]
    pub elems: [u8; MAX_RHASH],
    /// Host: some field reads an element (`elems`): `elem_left_key` computes the key.
    #[cfg(feature = "host-speedups")]
    pub elem: bool,
    /// Host, of an unplanned key (`n` is `NONE.n`): 0, or the join's `MarkKey` laid
    /// out by `marks_left_key` (`cache_marks_key`): its fields in `vars` and, as
    /// `SegRead` bytes, `elems`, or `NO_MARKS` when it has none that fits (the
    /// padding holds it: the entry is no larger).
    #[cfg(feature = "host-speedups")]
    pub marks: u8,
}

/// `KeyPlan::marks` of a join whose key not even the marks read.
#[cfg(feature = "host-speedups")]
const NO_MARKS: u8 = u8::MAX;

/// `KeyPlan::elems` of a field that is a whole single-field slot.
#[cfg(feature = "host-speedups")]
const WHOLE_SLOT: u8 = u8::MAX;

impl KeyPlan {
    pub const NONE: KeyPlan = KeyPlan {
        join: JoinId::NONE,
        tests: NONE,
        n: u8::MAX,
        vars: [(0, 0); MAX_RHASH],
        #[cfg(feature = "host-speedups")]
        elems: [WHOLE_SLOT; MAX_RHASH],
        #[cfg(feature = "host-speedups")]
        elem: false,
        #[cfg(feature = "host-speedups")]
        marks: 0,
    };
}

/// How many of an indexed alpha node's `rhash` fields its key hashes: its right
/// hash, or (`nrhash` 0) the one field of its or-lookups.
#[inline(always)]
fn key_fields(n: &super::AlphaNode) -> usize {
    if n.nrhash > 0 {
        n.nrhash as usize
    } else {
        1
    }
}

/// Host: at most this many buckets for one or-lookup (distinct alternatives).
#[cfg(feature = "host-speedups")]
pub const OR_WAYS: usize = 4;

/// Host: the part of the beta half of the bucket table (after the extra groups)
/// whose chains are the keyed or-index: the alpha matches of a node with a right
/// hash and an or-lookup field, keyed on both (`or_index_link`), linked through
/// their `token_xlinks[0]` (an alpha match has no extra beta group).
#[cfg(feature = "host-speedups")]
const OR_GROUP: usize = XGROUPS + 1;

/// Host: whether alpha node `n` has a right hash and an or-lookup field: its
/// matches are also in the keyed or-index.
#[cfg(feature = "host-speedups")]
#[inline(always)]
pub(crate) fn keyed_or(n: &super::AlphaNode) -> bool {
    n.nrhash > 0 && n.rhash.get(n.nrhash as usize).is_some_and(|&f| f != NONE)
}

/// Host: a join's or test worked out once (`Core::or_values`): the join and its
/// test chain (a reused join id has another one), the first `?a | ?b` test after
/// error-free ones (NONE: none, or one `or_values` cannot read), the expression
/// reading the join's field, and where each alternative's value lies: (pattern,
/// slot, element at a fixed offset or `WHOLE_SLOT` for the plain slot).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy, Debug)]
pub struct OrPlan {
    join: JoinId,
    tests: Ix,
    or: Ix,
    field: Ix,
    /// Where the field lies in the join's pattern's fact: its slot, and its element
    /// at a fixed offset or `WHOLE_SLOT`.
    at: (u8, u8),
    alts: [(u8, u8, u8); OR_WAYS],
    n: u8,
}

#[cfg(feature = "host-speedups")]
impl OrPlan {
    pub const NONE: OrPlan = OrPlan {
        join: JoinId::NONE,
        tests: NONE,
        or: NONE,
        field: NONE,
        at: (0, WHOLE_SLOT),
        alts: [(0, 0, WHOLE_SLOT); OR_WAYS],
        n: 0,
    };
}

/// Host: the values an `?a | ?b` join test lets a field take (`Core::or_values`).
#[cfg(feature = "host-speedups")]
pub(crate) struct OrValues {
    /// The or test (in the join's chain of tests).
    pub(crate) or: Ix,
    /// The expression reading the field (of the join's pattern).
    field: Ix,
    /// `OrPlan::at`.
    at: (u8, u8),
    vals: [Value; OR_WAYS],
    n: usize,
}

/// Host: an or-lookup in progress (`Core::or_lookup`): the next match of each of
/// its buckets (NONE when done) and the alpha node they are of.
#[cfg(feature = "host-speedups")]
pub(crate) struct OrCursor {
    heads: [TokenId; OR_WAYS],
    alpha: Ix,
    /// The buckets are the keyed or-index's (links in `token_xlinks`).
    keyed: bool,
    /// Keyed: what a match with the left token's key keeps in its `parent` (its
    /// bucket's tag, or the bucket, `index_insert`).
    kept: Ix,
}

fn mix(h: u32, x: u32) -> u32 {
    (h ^ x).wrapping_mul(0x9E37_79B1).rotate_left(13)
}

/// With feature `grow` a bucket's tokens keep their hash (a tag, never `NONE`) instead
/// of the bucket number, so the table can grow (`grow`: `rehash_token_index`).
#[cfg(feature = "grow")]
const TAG: u32 = 0x7FFF_FFFF;

/// Significant bits of a tag (`alpha_tag`, `beta_tag`).
#[cfg(feature = "grow")]
const TAG_BITS: u32 = 31;
#[cfg(not(feature = "grow"))]
const TAG_BITS: u32 = 32;

/// Tag `tag` mapped onto `0..n` by its high bits (a multiply and a shift, where `%`
/// would divide: the table's length need not be a power of two, and with `grow` the
/// bucket is found again from the tag at every removal). `n` of 0 gives 0.
#[inline(always)]
fn reduce(tag: u32, n: usize) -> usize {
    ((u64::from(tag) * n as u64) >> TAG_BITS) as usize
}

/// The hash an alpha match's bucket is taken from.
#[inline(always)]
fn alpha_tag(alpha: Ix, key: u32) -> u32 {
    let h = mix(key, u32::from(alpha));
    #[cfg(feature = "grow")]
    let h = h & TAG;
    h
}

/// Host: the hash an alpha match's keyed or-index bucket is taken from (`key`:
/// its right-hash key mixed with its or field's hash).
#[cfg(feature = "host-speedups")]
#[inline(always)]
fn or_tag(alpha: Ix, key: u32) -> u32 {
    let h = mix(key, 0x4000_0000 | u32::from(alpha));
    #[cfg(feature = "grow")]
    let h = h & TAG;
    h
}

/// The hash a partial match's bucket is taken from.
#[inline(always)]
fn beta_tag(join: JoinId, key: u32) -> u32 {
    let h = mix(key, 0x8000_0000 | u32::from(join.0));
    #[cfg(feature = "grow")]
    let h = h & TAG;
    h
}

/// The beta buckets of index group `g` in a table of `n` heads: (first, count).
/// Host: group 0 (each memory's `Join::index_child`) has half the table's beta half,
/// the extra groups share the rest; elsewhere group 0 has it all. Group 0's range is
/// shifts alone: every indexed insert and removal of a partial match computes it.
#[inline(always)]
fn group_range(n: usize, g: usize) -> (usize, usize) {
    let half = n / 2;
    let r = n - half;
    #[cfg(feature = "host-speedups")]
    {
        let first = r / 2;
        if g == 0 {
            (half, first.max(1))
        } else {
            // the extra groups and the keyed or-index (`OR_GROUP`) share the rest
            let part = (r - first) / OR_GROUP;
            (half + first + (g - 1) * part, part)
        }
    }
    #[cfg(not(feature = "host-speedups"))]
    {
        let _ = g;
        (half, r.max(1))
    }
}

impl Core<'_> {
    /// A hash of a value consistent with `values_same` (the join tests' equality).
    fn value_hash(&self, v: Value) -> u32 {
        match v {
            Value::Multi(p) => self.items_hash(p.len as usize, |k| self.mf_item(p, k)),
            v => atom_hash(v),
        }
    }

    /// `value_hash` of a multifield of `len` fields, field `k` given by `item`.
    #[inline(always)]
    fn items_hash(&self, len: usize, item: impl Fn(usize) -> Value) -> u32 {
        let mut h = mix(7, len as u32);
        for k in 0..len {
            h = mix(h, self.value_hash(item(k)));
        }
        h
    }

    /// Host: `value_hash` of the value an LHS variable (`pattern_var`'s arguments)
    /// reads, hashed where it lies (a multifield without its copy to scratch); None
    /// when the evaluator must read it.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn place_hash(&self, pat: u8, locator: Ix, desc_slot: Ix) -> Option<u32> {
        Some(match self.pattern_place(pat, locator, desc_slot)? {
            Place::One(c) => self.value_hash(self.values[c]),
            Place::Seg(c, n) => self.items_hash(n, |k| self.values[c + k]),
        })
    }

    /// Alpha buckets are the table's first half, beta buckets the rest, so every
    /// chain holds one kind of token (they link through different fields).
    /// (A table of one bucket has a half of 0, which `reduce` maps to bucket 0 too.)
    fn bucket(&self, alpha: Ix, key: u32) -> Ix {
        reduce(alpha_tag(alpha, key), self.amem_buckets.len() / 2) as Ix
    }

    /// With feature `grow`: the bucket of an alpha match's stored tag (`index_insert`).
    #[cfg(feature = "grow")]
    pub(crate) fn alpha_bucket_of(&self, tag: u32) -> usize {
        reduce(tag, self.amem_buckets.len() / 2)
    }

    /// The key of an alpha match of `alpha` (a node with a right hash): its
    /// right-hash field values.
    fn alpha_key(&mut self, alpha: Ix, b: PatBinding) -> u32 {
        if let Some(key) = self.quick_alpha_key(alpha, b.fact) {
            return key;
        }
        #[cfg(feature = "host-speedups")]
        if self.alphas[alpha as usize].elem_key {
            if let Some(key) = self.elem_alpha_key(alpha, b.fact) {
                return key;
            }
        }
        let (scratch, sp) = (self.st.frame.scratch_top, self.st.frame.sp);
        let saved = self.st.net.this_pm;
        self.st.net.this_pm = b;
        // host: the fields read, not a copy of the node (a call to copy it there)
        #[cfg(not(feature = "extras"))]
        let (rhash, nkey) = {
            let n = self.alphas[alpha as usize];
            (n.rhash, key_fields(&n))
        };
        #[cfg(feature = "extras")]
        let (rhash, nkey) = {
            let n = &self.alphas[alpha as usize];
            (n.rhash, key_fields(n))
        };
        let mut key = 0x5bd1_e995u32;
        for &e in &rhash[..nkey] {
            let x = self.exprs[e as usize];
            #[cfg(feature = "host-speedups")]
            if let Some(h) = self.place_hash(THIS_PATTERN, x.data, x.first) {
                key = mix(key, h);
                continue;
            }
            // an unreadable field hashes as nothing; the join tests decide anyway
            let v = self
                .pattern_var(THIS_PATTERN, x.data, x.first)
                .unwrap_or(Value::Void);
            key = mix(key, self.value_hash(v));
        }
        self.st.net.this_pm = saved;
        (self.st.frame.scratch_top, self.st.frame.sp) = (scratch, sp);
        key
    }

    /// The key of alpha match `am` of node `alpha` (a node with a right hash), as
    /// `alpha_key` computes it. Host: the one kept at its insert (`has_key`), so
    /// the fact's fields are not read again on every right activation.
    #[inline(always)]
    fn kept_alpha_key(&mut self, alpha: Ix, am: TokenId) -> u32 {
        let tk = &self.tokens[am];
        #[cfg(feature = "host-speedups")]
        if tk.has_key {
            return tk.key;
        }
        let b = PatBinding {
            fact: tk.fact,
            marks: tk.marks,
        };
        self.alpha_key(alpha, b)
    }

    /// Host: new alpha match `am` of node `alpha` has an older match of its node and
    /// key just before it in its bucket chain: if a successor not/exists join may
    /// skip its walk (`twin_joinable`, its left memory not empty), marks `am` for
    /// the right activations (`SLOW_TWIN`), up to the last such join (the
    /// successors are visited in list order).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    #[cold]
    #[inline(never)]
    fn twin_mark(&mut self, am: TokenId, alpha: Ix) {
        let mut last = JoinId::NONE;
        let mut j = self.alphas[alpha as usize].succ;
        while j != JoinId::NONE {
            let jn = &self.joins[j];
            if matches!(jn.kind, JoinKind::Negative | JoinKind::Exists)
                && self.join_mems[jn.parent].mem != TokenId::NONE
                && self.twin_joinable(j)
            {
                last = j;
            }
            j = self.joins[j].alpha_next;
        }
        if last != JoinId::NONE {
            self.st.prime.slow |= super::order::SLOW_TWIN;
            self.st.prime.twin = (am, last);
        }
    }

    /// Host: whether `join` is a not/exists join fed by an alpha node with a right
    /// hash whose tests are only equalities of this pattern's fields with earlier
    /// patterns' fields (`twin_blocks`).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    pub(crate) fn twin_joinable(&self, join: JoinId) -> bool {
        let j = self.joins[join];
        if !matches!(j.kind, JoinKind::Negative | JoinKind::Exists)
            || j.tests == NONE
            || j.rjoin != JoinId::NONE
            || j.alpha == NONE
            || self.alphas[j.alpha as usize].nrhash == 0
        {
            return false;
        }
        let mut t = j.tests;
        while t != NONE {
            let x = self.exprs[t as usize];
            if x.op != Op::Eq2 || x.first == NONE {
                return false;
            }
            let this = self.exprs[x.first as usize];
            if this.op != Op::PatVar || this.aux != j.depth || this.next == NONE {
                return false;
            }
            let o = self.exprs[this.next as usize];
            if o.op != Op::PatVar || o.aux >= j.depth || o.next != NONE {
                return false;
            }
            t = x.next;
        }
        true
    }

    /// Host: whether new alpha match `am` on the right of `join` can block nothing
    /// new, so that its walk of the left memory (which would meet only outputs
    /// blocked already, or failing its tests) is not needed: `join` is a not/exists
    /// join fed by `am`'s node whose tests are only equalities of this pattern's
    /// fields with earlier patterns' fields, and `am`'s predecessor in its index
    /// bucket chain is an older match of the node (linked, so right-activated, before
    /// it) with the same values in those fields. Every left partial match `am`
    /// passes, that match passes too, so its output has a blocker already (CLIPS
    /// walks them, skipping each blocked output). Asked only for an alpha match whose
    /// bucket predecessor had its tag when it was linked (`PrimeOrders::twin_am`).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    #[inline(never)]
    pub(crate) fn twin_blocks(&mut self, join: JoinId, am: TokenId) -> bool {
        if !self.twin_joinable(join) {
            return false;
        }
        let j = self.joins[join];
        // the predecessor links back to `am` (a chain head's `am_prev` is the tail)
        let a = self.tokens[am];
        let r = a.am_prev;
        if a.kind != TokenKind::Alpha || r == TokenId::NONE || r == am {
            return false;
        }
        let rk = self.tokens[r];
        rk.kind == TokenKind::Alpha
            && rk.am_next == am
            && rk.parent == a.parent
            && rk.alpha() == j.alpha
            && a.alpha() == j.alpha
            && self.same_test_fields(j.tests, am, r)
    }

    /// Host: whether alpha matches `a` and `b` read the same values in the fields
    /// that equality tests `tests` read from this pattern (`twin_blocks`).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    fn same_test_fields(&mut self, tests: Ix, a: TokenId, b: TokenId) -> bool {
        let (scratch, sp) = (self.st.frame.scratch_top, self.st.frame.sp);
        let saved = self.st.net.this_pm;
        let (ta, tb) = (self.tokens[a], self.tokens[b]);
        let mut same = true;
        let mut t = tests;
        while same && t != NONE {
            let x = self.exprs[t as usize];
            let this = self.exprs[x.first as usize];
            self.st.net.this_pm = PatBinding {
                fact: ta.fact,
                marks: ta.marks,
            };
            let va = self.pattern_var(THIS_PATTERN, this.data, this.first);
            self.st.net.this_pm = PatBinding {
                fact: tb.fact,
                marks: tb.marks,
            };
            let vb = self.pattern_var(THIS_PATTERN, this.data, this.first);
            same = match (va, vb) {
                (Ok(p), Ok(q)) => crate::builtins::basic::values_same(self, p, q),
                _ => false,
            };
            t = x.next;
        }
        self.st.net.this_pm = saved;
        (self.st.frame.scratch_top, self.st.frame.sp) = (scratch, sp);
        same
    }

    /// For join test `x` of the join at `depth`, when it is a key test (`(eq ?own
    /// ?earlier)`: a variable of the join's own pattern against one of another
    /// pattern), the other variable's expression. The one reading of a key test,
    /// shared by the key plans, the evaluator's key and the marks' key.
    #[inline(always)]
    pub(crate) fn key_test_other(&self, x: &crate::expr::Expr, depth: u8) -> Option<Ix> {
        if x.op != Op::Eq2 || x.first == NONE {
            return None;
        }
        let this = self.exprs[x.first as usize];
        let other = this.next;
        (this.op == Op::PatVar
            && this.aux == depth
            && other != NONE
            && self.exprs[other as usize].op == Op::PatVar
            && self.exprs[other as usize].aux != depth)
            .then_some(other)
    }

    /// The values a left token gives `join`'s key, in test order: for each of the
    /// join's equality tests between this pattern's variable and an earlier one (at
    /// most `limit`), the earlier variable's value as `eval` reads it (`lhs_pm` must
    /// hold the left token's bindings), handed to `f`. Returns how many it found.
    /// Shared by `left_key` and CLIPS's left hash (`rete::order`).
    #[inline(always)]
    pub(crate) fn each_left_key_value(
        &mut self,
        join: JoinId,
        limit: u8,
        mut f: impl FnMut(&Self, Result<Value, EvalError>),
    ) -> u8 {
        let j = self.joins[join];
        let (scratch, sp, pm) = (
            self.st.frame.scratch_top,
            self.st.frame.sp,
            self.st.net.pm_rhs,
        );
        self.st.net.pm_rhs = false;
        let mut found = 0;
        let mut t = j.tests;
        while t != NONE && found < limit {
            let x = self.exprs[t as usize];
            if let Some(other) = self.key_test_other(&x, j.depth) {
                let v = self.eval(other);
                f(self, v);
                found += 1;
            }
            t = x.next;
        }
        (
            self.st.frame.scratch_top,
            self.st.frame.sp,
            self.st.net.pm_rhs,
        ) = (scratch, sp, pm);
        found
    }

    /// The key of a left token of `join` (its alpha node must have a right hash):
    /// the earlier variables the join's equality tests compare with; `lhs_pm` must
    /// hold the left token's bindings. None when a value cannot be read: then the
    /// whole memory is scanned.
    fn left_key(&mut self, join: JoinId) -> Option<u32> {
        // host: fields some multifield moves, read by the marks
        #[cfg(feature = "host-speedups")]
        if let Some(k) = self.marks_left_key(join) {
            return Some(k);
        }
        #[cfg(feature = "host-speedups")]
        if let Some(k) = self.place_left_key(join) {
            return Some(k);
        }
        let nrhash = self.alphas[self.joins[join].alpha as usize].nrhash;
        let mut key = 0x5bd1_e995u32;
        let mut ok = true;
        let found = self.each_left_key_value(join, nrhash, |cx, v| match v {
            Ok(v) => key = mix(key, cx.value_hash(v)),
            Err(_) => ok = false,
        });
        if !ok || found != nrhash {
            return None;
        }
        Some(key)
    }

    /// Host: `left_key` with each value hashed where it lies (`place_hash`: a
    /// multifield such as `$?rest` without its copy); None when one needs the
    /// evaluator.
    #[cfg(feature = "host-speedups")]
    fn place_left_key(&mut self, join: JoinId) -> Option<u32> {
        let j = self.joins[join];
        let nrhash = self.alphas[j.alpha as usize].nrhash;
        let pm = core::mem::replace(&mut self.st.net.pm_rhs, false);
        let mut key = 0x5bd1_e995u32;
        let mut found = 0;
        let mut t = j.tests;
        while t != NONE && found < nrhash {
            let x = self.exprs[t as usize];
            if let Some(other) = self.key_test_other(&x, j.depth) {
                let o = self.exprs[other as usize];
                let Some(h) = self.place_hash(o.aux, o.data, o.first) else {
                    self.st.net.pm_rhs = pm;
                    return None;
                };
                key = mix(key, h);
                found += 1;
            }
            t = x.next;
        }
        self.st.net.pm_rhs = pm;
        (found == nrhash).then_some(key)
    }

    /// Host: `left_key` through the join's `MarkKey` (`lhs_pm` bound), None when
    /// the evaluator must compute it (out of line: the evaluator's path).
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn marks_left_key(&mut self, join: JoinId) -> Option<u32> {
        // laid out once in the join's key-plan entry, which `quick_left_key` filled
        // just now with a plan that is `NONE` (a planned key's rare misses, and an
        // entry another join took, go the old way: their code as it was)
        let i = join.ix() % KEY_PLANS;
        let plan = &self.st.cache.key_plans[i];
        if plan.n == KeyPlan::NONE.n && plan.join == join && plan.tests == self.joins[join].tests {
            if plan.marks == 0 {
                self.cache_marks_key(i, join);
            }
            let plan = &self.st.cache.key_plans[i];
            if plan.marks == NO_MARKS {
                // the evaluator's
                return None;
            }
            let mut key = 0x5bd1_e995u32;
            for (&(pat, slot), &r) in plan.vars.iter().zip(&plan.elems).take(plan.marks as usize) {
                let b = self.st.net.lhs_pm.get(pat as usize)?;
                let v = self.seg_field(b, slot, SegRead::of_byte(r))?;
                key = mix(key, atom_hash(v));
            }
            return Some(key);
        }
        // a planned key the plan could not read (a multifield where it expects a
        // single field, a pattern beyond the token's binds): worked out here
        let p = self.mark_key(join)?;
        let mut key = 0x5bd1_e995u32;
        for &(pat, slot, r) in p.reads.get(..p.n as usize)? {
            let v = self.seg_field(self.st.net.lhs_pm.get(pat as usize)?, slot, r)?;
            key = mix(key, atom_hash(v));
        }
        Some(key)
    }

    /// `left_key` without the evaluator, for left token `left` (after
    /// `bind_for_quick`): the compared fields are read straight from the facts, as
    /// the join's key plan says. None when one is not a plain single-field slot.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn quick_left_key(&mut self, join: JoinId, left: TokenId) -> Option<u32> {
        let tests = self.joins[join].tests;
        let i = join.ix() % KEY_PLANS;
        let cached = &self.st.cache.key_plans[i];
        if cached.join != join || cached.tests != tests {
            self.st.cache.key_plans[i] = self.key_plan(join);
        }
        // read in place (a copy of the whole plan costs more than the few fields used)
        let plan = &self.st.cache.key_plans[i];
        if plan.n == KeyPlan::NONE.n {
            return None;
        }
        #[cfg(feature = "host-speedups")]
        if plan.elem {
            return self.elem_left_key(i, left);
        }
        let mut key = 0x5bd1_e995u32;
        for &(pat, slot) in &plan.vars[..plan.n as usize] {
            let fact = self.left_fact(left, pat);
            if fact == NONE {
                // a pattern beyond `Token::binds`: read through `lhs_pm` (rare)
                #[cfg(feature = "host-speedups")]
                if pat as usize >= super::BIND_W {
                    return self.deep_left_key(i, left);
                }
                return None;
            }
            // hashed where it lies (a copy costs more than the hash)
            let v = self.slot_ref(fact, Ix::from(slot));
            if matches!(v, Value::Multi(_)) {
                return None;
            }
            key = mix(key, atom_hash(*v));
        }
        Some(key)
    }

    /// Host: `quick_left_key` for a key plan (cache entry `i`) with a field that is
    /// an element of an ordered fact (or multislot) at a fixed offset.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn elem_left_key(&mut self, i: usize, left: TokenId) -> Option<u32> {
        let plan = self.st.cache.key_plans[i];
        let mut key = 0x5bd1_e995u32;
        for (k, &(pat, slot)) in plan.vars[..plan.n as usize].iter().enumerate() {
            let fact = self.left_fact(left, pat);
            if fact == NONE {
                // a pattern beyond `Token::binds` (see `deep_left_key`)
                return None;
            }
            if plan.elems[k] == WHOLE_SLOT {
                let v = self.slot_ref(fact, Ix::from(slot));
                if matches!(v, Value::Multi(_)) {
                    return None;
                }
                key = mix(key, atom_hash(*v));
                continue;
            }
            let elem = plan.elems[k] as usize;
            let (cell, len) = self.slot_cell(fact, Ix::from(slot));
            match len {
                Some(len) if elem < len as usize => {
                    key = mix(key, self.value_hash(self.values[cell + 1 + elem]));
                }
                _ => return None,
            }
        }
        Some(key)
    }

    /// Host: `join`'s `MarkKey` laid out in its key-plan entry `i`, whose plan leaves
    /// the key to the evaluator (out of line: once per entry).
    #[cfg(feature = "host-speedups")]
    #[cold]
    #[inline(never)]
    fn cache_marks_key(&mut self, i: usize, join: JoinId) {
        let plan = KeyPlan {
            marks: NO_MARKS,
            ..self.st.cache.key_plans[i]
        };
        let marks = match self.mark_key(join) {
            Some(p) if p.n > 0 => p,
            _ => {
                self.st.cache.key_plans[i] = plan;
                return;
            }
        };
        let mut laid = plan;
        for (k, &(pat, slot, r)) in marks.reads.iter().enumerate().take(marks.n as usize) {
            let Some(b) = r.to_byte() else {
                // a read the byte cannot hold: the evaluator's
                self.st.cache.key_plans[i] = plan;
                return;
            };
            laid.vars[k] = (pat, slot);
            laid.elems[k] = b;
        }
        laid.marks = marks.n;
        self.st.cache.key_plans[i] = laid;
    }

    /// `quick_left_key` for a key plan (cache entry `i`) that reads a pattern at or
    /// beyond `BIND_W`: every fact through `lhs_pm`, bound to `left`'s ancestry.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn deep_left_key(&mut self, i: usize, left: TokenId) -> Option<u32> {
        self.bind_left(left);
        let plan = &self.st.cache.key_plans[i];
        let mut key = 0x5bd1_e995u32;
        for &(pat, slot) in &plan.vars[..plan.n as usize] {
            let fact = match self.st.net.lhs_pm.get(pat as usize) {
                Some(b) => b.fact,
                None => NONE,
            };
            if fact == NONE {
                return None;
            }
            let v = self.slot_ref(fact, Ix::from(slot));
            if matches!(v, Value::Multi(_)) {
                return None;
            }
            key = mix(key, atom_hash(*v));
        }
        Some(key)
    }

    /// Which fields `left_key` reads for `join`: the earlier variables its
    /// equality tests compare with, in test order, when all are plain single-field
    /// slot reads (else a plan with `n == KeyPlan::NONE.n`).
    fn key_plan(&self, join: JoinId) -> KeyPlan {
        let j = &self.joins[join];
        let nrhash = self.alphas[j.alpha as usize].nrhash;
        let mut plan = KeyPlan {
            join,
            tests: j.tests,
            n: 0,
            ..KeyPlan::NONE
        };
        let unplanned = KeyPlan {
            join,
            tests: j.tests,
            ..KeyPlan::NONE
        };
        let mut t = j.tests;
        while t != NONE && plan.n < nrhash {
            let x = self.exprs[t as usize];
            if let Some(other) = self.key_test_other(&x, j.depth) {
                let o = self.exprs[other as usize];
                if o.aux > j.depth || o.data == loc::FACT {
                    return unplanned;
                }
                if o.first != NONE {
                    // host: an element at a fixed offset
                    #[cfg(feature = "host-speedups")]
                    match self.fixed_elem(&o) {
                        Some(e) => {
                            plan.elems[plan.n as usize] = e;
                            plan.elem = true;
                        }
                        None => return unplanned,
                    }
                    #[cfg(not(feature = "host-speedups"))]
                    return unplanned;
                }
                plan.vars[plan.n as usize] = (o.aux, loc::slot(o.data));
                plan.n += 1;
            }
            t = x.next;
        }
        if plan.n != nrhash {
            return unplanned;
        }
        plan
    }

    /// Host: the element a pattern variable reads in its multislot (or ordered
    /// fact) when its offset is fixed: every element before it is single-field.
    #[cfg(feature = "host-speedups")]
    pub(super) fn fixed_elem(&self, x: &crate::expr::Expr) -> Option<u8> {
        let elem = loc::elem(x.data);
        if elem == loc::SINGLE {
            return None;
        }
        let desc = self.exprs[x.first as usize];
        if desc.op != Op::PatSlot {
            return None;
        }
        let mut c = desc.first;
        let mut i = 0u8;
        while c != NONE {
            let element = self.exprs[c as usize];
            if element.aux == 1 {
                return None;
            }
            if i == elem {
                return (elem != WHOLE_SLOT).then_some(elem);
            }
            i += 1;
            c = element.next;
        }
        None
    }

    /// `alpha_key` for a match whose right-hash fields are all plain single-field
    /// slots, read straight from the fact.
    fn quick_alpha_key(&self, alpha: Ix, fact: Ix) -> Option<u32> {
        let n = &self.alphas[alpha as usize];
        let mut key = 0x5bd1_e995u32;
        for &e in &n.rhash[..key_fields(n)] {
            let v = self.plain_slot_value(fact, &self.exprs[e as usize])?;
            key = mix(key, atom_hash(v));
        }
        Some(key)
    }

    /// Host: `quick_alpha_key` where a field is an element at a fixed offset (an
    /// ordered fact's), read there too (out of line: the plain slots' path stays
    /// as it is).
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn elem_alpha_key(&self, alpha: Ix, fact: Ix) -> Option<u32> {
        let n = &self.alphas[alpha as usize];
        let mut key = 0x5bd1_e995u32;
        for &e in &n.rhash[..key_fields(n)] {
            let v = self.key_field_value(fact, &self.exprs[e as usize])?;
            key = mix(key, atom_hash(v));
        }
        Some(key)
    }

    /// Host: whether node `alpha`'s key has a field at a fixed offset of a multislot
    /// (an ordered fact's) and every other field plain or so too: only then can
    /// `elem_alpha_key` serve it, when `quick_alpha_key` cannot.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn elem_keyed(&self, alpha: Ix) -> bool {
        let n = &self.alphas[alpha as usize];
        let mut elem = false;
        for &e in &n.rhash[..key_fields(n)] {
            if e == NONE {
                return false;
            }
            let x = &self.exprs[e as usize];
            if x.data == loc::FACT {
                return false;
            }
            if x.first != NONE {
                if self.fixed_elem(x).is_none() {
                    return false;
                }
                elem = true;
            }
        }
        elem
    }

    /// Host: the value a right-hash (or or-lookup) field `x` of a pattern reads in
    /// `fact`, read straight from the fact: a plain single-field slot, or an element
    /// at a fixed offset of a multislot (an ordered fact's field); None for another
    /// field (after a multifield), which `pattern_var` reads.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn key_field_value(&self, fact: Ix, x: &crate::expr::Expr) -> Option<Value> {
        if x.first == NONE {
            return self.plain_slot_value(fact, x);
        }
        if x.data == loc::FACT {
            return None;
        }
        let elem = self.fixed_elem(x)?;
        self.field_at(fact, (loc::slot(x.data), elem))
    }

    /// Whether alpha node `alpha`'s matches are in the index: it has a right hash,
    /// or (host) an or-lookup field (`compile::alpha` `or_field`).
    #[inline(always)]
    pub(crate) fn alpha_indexed(&self, alpha: Ix) -> bool {
        let n = &self.alphas[alpha as usize];
        // (a right hash's fields come first in `rhash`, the or field after them, so
        // this is `nrhash > 0 || rhash[0] != NONE` in one test)
        #[cfg(feature = "host-speedups")]
        let indexed = n.rhash[0] != NONE;
        #[cfg(feature = "host-speedups")]
        debug_assert!(n.nrhash == 0 || indexed);
        #[cfg(not(feature = "host-speedups"))]
        let indexed = n.nrhash > 0;
        indexed
    }

    /// When test `t` of a join at pattern `depth` is `?a | ?b ...`, an or of
    /// equalities of one plain single-field slot of that pattern (host: or an
    /// element at a fixed offset, as an ordered fact's `(rel ?a|?b ?x)`) with plain
    /// slots of earlier patterns (host: or their elements at fixed offsets, as an
    /// ordered fact's `(triple ?a ?b ?c)`): the expression reading that field (its
    /// first member's).
    pub(crate) fn or_of_equalities(&self, t: Ix, depth: u8) -> Option<Ix> {
        let x = self.exprs[t as usize];
        if x.op != Op::Or || x.first == NONE {
            return None;
        }
        let mut field = NONE;
        let mut c = x.first;
        while c != NONE {
            let e = self.exprs[c as usize];
            if e.op != Op::Eq2 || e.first == NONE {
                return None;
            }
            let this = self.exprs[e.first as usize];
            if this.op != Op::PatVar
                || this.aux != depth
                || !self.own_field_read(&this)
                || this.data == loc::FACT
                || this.next == NONE
            {
                return None;
            }
            let o = self.exprs[this.next as usize];
            if o.op != Op::PatVar || o.aux >= depth || o.data == loc::FACT {
                return None;
            }
            // host: also an element of an earlier ordered fact (or multislot) at a
            // fixed offset, which `or_values` reads as the plans do (`Source::Elem`)
            #[cfg(feature = "host-speedups")]
            if o.first != NONE && self.fixed_elem(&o).is_none() {
                return None;
            }
            #[cfg(not(feature = "host-speedups"))]
            if o.first != NONE {
                return None;
            }
            if field == NONE {
                field = e.first;
            } else if self.exprs[field as usize].data != this.data {
                return None;
            }
            c = e.next;
        }
        Some(field)
    }

    /// Whether a join's or-lookup can read field `x` of its own pattern: a plain
    /// slot (host: or an element at a fixed offset, an ordered fact's `(rel ?a|?b
    /// ?x)`, which the index and `or_match` read there).
    #[inline(always)]
    fn own_field_read(&self, x: &crate::expr::Expr) -> bool {
        #[cfg(feature = "host-speedups")]
        let read = x.first == NONE || self.fixed_elem(x).is_some();
        #[cfg(not(feature = "host-speedups"))]
        let read = x.first == NONE;
        read
    }

    /// Whether test `t` reports no error whatever the fact: `eq` of pattern
    /// variables and constants, and `and`/`or`/`not` of such tests.
    #[cfg(feature = "host-speedups")]
    fn error_free(&self, t: Ix) -> bool {
        let x = self.exprs[t as usize];
        match x.op {
            Op::Eq2 | Op::And | Op::Or | Op::Not => {
                let mut c = x.first;
                while c != NONE {
                    let e = self.exprs[c as usize];
                    let ok = match e.op {
                        Op::PatVar | Op::Sym | Op::Str | Op::Int | Op::Float => x.op == Op::Eq2,
                        _ => x.op != Op::Eq2 && self.error_free(c),
                    };
                    if !ok {
                        return false;
                    }
                    c = e.next;
                }
                true
            }
            _ => false,
        }
    }

    /// Host: for a left token `left` of `join`, when the first of the join's tests
    /// that is `?a | ?b ...` (`or_of_equalities`) has only error-free tests before it
    /// (and reads field `want`, unless NONE): the values the field must equal (one per
    /// alternative, read from `left`'s facts). A candidate whose field equals none of
    /// them fails the join's tests, having run only tests that report nothing, so it
    /// may be skipped unseen (CLIPS reports the same errors). None: no such test, or
    /// a value that is not a plain single field, or more than `OR_WAYS` alternatives.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn or_values(&mut self, join: JoinId, left: TokenId, want: Ix) -> Option<OrValues> {
        let (depth, tests) = {
            let j = &self.joins[join];
            (j.depth, j.tests)
        };
        // the test and its alternatives' reads are found once per join
        // (direct-mapped cache, as key plans)
        let i = join.ix() % KEY_PLANS;
        let cached = &self.st.cache.or_plans[i];
        if cached.join != join || cached.tests != tests {
            self.st.cache.or_plans[i] = self.or_plan(join, tests, depth);
        }
        let plan = self.st.cache.or_plans[i];
        if plan.or == NONE {
            return None;
        }
        if want != NONE && self.exprs[plan.field as usize].data != self.exprs[want as usize].data {
            return None;
        }
        self.bind_for_quick(left);
        let mut out = OrValues {
            or: plan.or,
            field: plan.field,
            at: plan.at,
            vals: [Value::Void; OR_WAYS],
            n: 0,
        };
        for &(pat, slot, elem) in &plan.alts[..plan.n as usize] {
            let fact = self.left_fact(left, pat);
            if fact == NONE {
                return None;
            }
            let v = if elem == WHOLE_SLOT {
                *self.slot_ref(fact, Ix::from(slot))
            } else {
                // an element at a fixed offset (`or_of_equalities`)
                match self.slot_cell_inline(fact, Ix::from(slot)) {
                    (cell, Some(len)) if (elem as usize) < len as usize => {
                        self.values[cell + 1 + elem as usize]
                    }
                    _ => return None,
                }
            };
            if matches!(v, Value::Multi(_)) {
                return None;
            }
            out.vals[out.n] = v;
            out.n += 1;
        }
        Some(out)
    }

    /// Host: the `OrPlan` of `join` (at `depth`) with test chain `tests`.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn or_plan(&self, join: JoinId, tests: Ix, depth: u8) -> OrPlan {
        let none = OrPlan {
            join,
            tests,
            ..OrPlan::NONE
        };
        let mut or = NONE;
        let mut t = tests;
        while t != NONE {
            if self.or_of_equalities(t, depth).is_some() {
                or = t;
                break;
            }
            if !self.error_free(t) {
                break;
            }
            t = self.exprs[t as usize].next;
        }
        if or == NONE {
            return none;
        }
        let field = self.exprs[self.exprs[or as usize].first as usize].first;
        let f = self.exprs[field as usize];
        let elem = if f.first == NONE {
            WHOLE_SLOT
        } else {
            // (`or_of_equalities` found it at a fixed offset)
            match self.fixed_elem(&f) {
                Some(e) => e,
                None => return none,
            }
        };
        let mut plan = OrPlan {
            or,
            field,
            at: (loc::slot(f.data), elem),
            ..none
        };
        let mut c = self.exprs[or as usize].first;
        while c != NONE {
            let this = self.exprs[c as usize].first;
            let o = self.exprs[self.exprs[this as usize].next as usize];
            // (`or_of_equalities` found every element at a fixed offset)
            let elem = if o.first == NONE {
                WHOLE_SLOT
            } else {
                match self.fixed_elem(&o) {
                    Some(e) => e,
                    None => return none,
                }
            };
            let Some(alt) = plan.alts.get_mut(plan.n as usize) else {
                // more alternatives than `OrValues` holds
                return none;
            };
            *alt = (o.aux, loc::slot(o.data), elem);
            plan.n += 1;
            c = self.exprs[c as usize].next;
        }
        plan
    }

    /// Host: field `(slot, elem)` of `fact` (`elem` an element at a fixed offset, or
    /// `WHOLE_SLOT` for the slot itself) when it is a single field there; None when
    /// it is not (a multislot read whole, an element beyond its multislot's end).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn field_at(&self, fact: Ix, (slot, elem): (u8, u8)) -> Option<Value> {
        if fact == NONE {
            return None;
        }
        if elem == WHOLE_SLOT {
            return self.plain_slot(fact, Ix::from(slot));
        }
        match self.slot_cell_inline(fact, Ix::from(slot)) {
            (cell, Some(len)) if (elem as usize) < len as usize => {
                match self.values[cell + 1 + elem as usize] {
                    Value::Multi(_) => None,
                    v => Some(v),
                }
            }
            _ => None,
        }
    }

    /// Host: the result of the or test of `or_values` for a candidate (fact
    /// `fact`): its field read plainly and compared with each alternative as the
    /// test's `eq`s compare (`values_same`); None when the field cannot be read
    /// plainly (the tests decide).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn or_match(&self, ov: &OrValues, fact: Ix) -> Option<bool> {
        let v = self.field_at(fact, ov.at)?;
        Some(
            ov.vals[..ov.n]
                .iter()
                .any(|&w| crate::builtins::basic::values_same(self, v, w)),
        )
    }

    /// Host: where a left token of positive `join` finds its right partners when its
    /// alpha node has an or-lookup field that the join's `or_values` test reads: one
    /// bucket per distinct bucket of the alternatives' values, merged in memory order
    /// (`or_next`), so each candidate comes once and in the order of a full scan.
    /// None: scan the memory.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn or_lookup(&mut self, join: JoinId, left: TokenId) -> Option<OrCursor> {
        let alpha = self.joins[join].alpha;
        let field = self.alphas[alpha as usize].rhash[0];
        // stamps saturated: memory order is no longer known
        if field == NONE || self.st.cache.or_stamp == u32::MAX {
            return None;
        }
        let ov = self.or_values(join, left, field)?;
        let mut cur = OrCursor {
            heads: [TokenId::NONE; OR_WAYS],
            alpha,
            keyed: false,
            kept: NONE,
        };
        let mut buckets = [NONE; OR_WAYS];
        let mut n = 0;
        for &v in &ov.vals[..ov.n] {
            let b = self.bucket(alpha, mix(0x5bd1_e995, atom_hash(v)));
            // alternatives in one bucket (equal values, or a collision) visit it once
            if !buckets[..n].contains(&b) {
                buckets[n] = b;
                cur.heads[n] = self.skip_foreign(self.amem_buckets[b as usize], alpha);
                n += 1;
            }
        }
        Some(cur)
    }

    /// Host: the next candidate of an or-lookup: the oldest of its buckets' next
    /// matches (each bucket is in memory order; stamps order them across buckets).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn or_next(&self, cur: &mut OrCursor) -> TokenId {
        let mut best = TokenId::NONE;
        let mut at = 0;
        let mut stamp = 0;
        for (i, &h) in cur.heads.iter().enumerate() {
            if h != TokenId::NONE && (best == TokenId::NONE || self.tokens[h].key < stamp) {
                best = h;
                at = i;
                stamp = self.tokens[h].key;
            }
        }
        if best != TokenId::NONE {
            cur.heads[at] = if cur.keyed {
                self.skip_foreign_or(self.or_link(best, 0), cur.alpha)
            } else {
                self.skip_foreign(self.tokens[best].am_next, cur.alpha)
            };
        }
        best
    }

    /// Host: a cursor over the keyed or-index of `alpha` (a `keyed_or` node) for a
    /// left token whose key (its right-hash values) is `key` and whose or test lets
    /// the field take `ov`'s values: one bucket per distinct bucket of the
    /// alternatives, merged in memory order by `or_next`.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn or_keyed_cursor(&self, alpha: Ix, key: u32, ov: &OrValues) -> OrCursor {
        #[cfg(not(feature = "grow"))]
        let kept = self.bucket(alpha, key);
        #[cfg(feature = "grow")]
        let kept = alpha_tag(alpha, key) as Ix;
        let mut cur = OrCursor {
            heads: [TokenId::NONE; OR_WAYS],
            alpha,
            keyed: true,
            kept,
        };
        let mut buckets = [usize::MAX; OR_WAYS];
        let mut n = 0;
        for &v in &ov.vals[..ov.n] {
            let b = self.or_bucket(or_tag(alpha, mix(key, atom_hash(v))));
            // alternatives in one bucket (equal values, or a collision) visit it once
            if !buckets[..n].contains(&b) {
                buckets[n] = b;
                cur.heads[n] = self.skip_foreign_or(self.amem_buckets[b], alpha);
                n += 1;
            }
        }
        cur
    }

    /// Host: for candidate `a` of keyed cursor `cur`, as `or_match` answers: Some(false)
    /// for a match of another key (a collision in the keyed or-index: its other
    /// bucket differs), which fails the join's key tests, having run only tests that
    /// report nothing (`or_values`), else `or_match` of its fact.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn or_keyed_match(&self, cur: &OrCursor, ov: &OrValues, a: TokenId) -> Option<bool> {
        let tk = &self.tokens[a];
        if tk.parent.0 != cur.kept {
            return Some(false);
        }
        self.or_match(ov, tk.fact)
    }

    /// Host: whether the keyed or-index of `alpha` serves an or test whose values
    /// are `ov`: the node is `keyed_or`, its field is the one the test reads, and
    /// the stamps still order its matches.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn or_keyed_serves(&self, alpha: Ix, ov: &OrValues) -> bool {
        let n = &self.alphas[alpha as usize];
        keyed_or(n)
            && self.st.cache.or_stamp != u32::MAX
            && self.exprs[n.rhash[n.nrhash as usize] as usize].data
                == self.exprs[ov.field as usize].data
    }

    /// Host: the memory-order stamp of alpha match `am` (of a node with an
    /// or-lookup field; `index_insert`).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn or_stamp_of(&self, am: TokenId) -> u32 {
        self.tokens[am].key
    }

    /// Host: link `k` (0 next, 1 previous, 2 tag) of alpha match `t` in the keyed
    /// or-index.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn or_link(&self, t: TokenId, k: usize) -> TokenId {
        TokenId(self.token_xlinks[t.ix()][0][k])
    }

    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn set_or_link(&mut self, t: TokenId, k: usize, v: Ix) {
        self.token_xlinks[t.ix()][0][k] = v;
    }

    /// Host: skips keyed or-index entries of other alpha nodes.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn skip_foreign_or(&self, mut a: TokenId, alpha: Ix) -> TokenId {
        while a != TokenId::NONE && self.tokens[a].alpha() != alpha {
            a = self.or_link(a, 0);
        }
        a
    }

    /// Host: the keyed or-index bucket of tag `tag`.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn or_bucket(&self, tag: u32) -> usize {
        self.group_bucket(tag, OR_GROUP)
    }

    /// Host: the hash of the or-lookup field of alpha match `b` of `alpha` (as
    /// `alpha_key` hashes a field).
    #[cfg(feature = "host-speedups")]
    fn or_field_hash(&mut self, alpha: Ix, b: PatBinding) -> u32 {
        let n = &self.alphas[alpha as usize];
        let e = n.rhash[n.nrhash as usize];
        if let Some(v) = self.key_field_value(b.fact, &self.exprs[e as usize]) {
            return atom_hash(v);
        }
        let (scratch, sp) = (self.st.frame.scratch_top, self.st.frame.sp);
        let saved = self.st.net.this_pm;
        self.st.net.this_pm = b;
        let x = self.exprs[e as usize];
        let v = self
            .pattern_var(THIS_PATTERN, x.data, x.first)
            .unwrap_or(Value::Void);
        let h = self.value_hash(v);
        self.st.net.this_pm = saved;
        (self.st.frame.scratch_top, self.st.frame.sp) = (scratch, sp);
        h
    }

    /// Host: appends alpha match `am` of `keyed_or` node `alpha`, whose right-hash
    /// key is `key`, to its keyed or-index bucket (key and or field), which keeps
    /// memory order as the node's other bucket does.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn or_index_link(&mut self, am: TokenId, alpha: Ix, key: u32) {
        let tk = self.tokens[am];
        let h = self.or_field_hash(
            alpha,
            PatBinding {
                fact: tk.fact,
                marks: tk.marks,
            },
        );
        let tag = or_tag(alpha, mix(key, h));
        let b = self.or_bucket(tag);
        // (with `grow` the tag, else the bucket, as for beta groups)
        #[cfg(feature = "grow")]
        let kept = tag as Ix;
        #[cfg(not(feature = "grow"))]
        let kept = b as Ix;
        self.set_or_link(am, 2, kept);
        self.or_chain_append(b, am);
    }

    /// Host: appends alpha match `am` to bucket `b`'s keyed or-index chain (its head
    /// keeps the tail in link 1, so an append touches no other entry).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn or_chain_append(&mut self, b: usize, am: TokenId) {
        self.set_or_link(am, 0, NONE);
        let head = self.amem_buckets[b];
        if head == TokenId::NONE {
            self.set_or_link(am, 1, am.0);
            self.amem_buckets[b] = am;
        } else {
            let tail = self.or_link(head, 1);
            self.set_or_link(tail, 0, am.0);
            self.set_or_link(am, 1, tail.0);
            self.set_or_link(head, 1, am.0);
        }
    }

    /// Host: the keyed or-index bucket alpha match `am` sits in.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn or_bucket_of(&self, am: TokenId) -> usize {
        let kept = self.token_xlinks[am.ix()][0][2];
        #[cfg(feature = "grow")]
        let b = self.or_bucket(kept as u32);
        #[cfg(not(feature = "grow"))]
        let b = kept as usize;
        b
    }

    /// Host: takes alpha match `am` out of the keyed or-index.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn or_index_unlink(&mut self, am: TokenId) {
        let b = self.or_bucket_of(am);
        let (next, prev) = (self.or_link(am, 0), self.or_link(am, 1));
        let head = self.amem_buckets[b];
        if head == am {
            self.amem_buckets[b] = next;
            if next != TokenId::NONE {
                // the new head keeps the tail
                self.set_or_link(next, 1, prev.0);
            }
        } else {
            self.set_or_link(prev, 0, next.0);
            if next != TokenId::NONE {
                self.set_or_link(next, 1, prev.0);
            } else {
                self.set_or_link(head, 1, prev.0);
            }
        }
        self.set_or_link(am, 0, NONE);
        self.set_or_link(am, 1, NONE);
    }

    /// Host: a node with a right hash takes an or-lookup field (`compile::alpha`):
    /// the matches it holds join the keyed or-index, oldest first, with fresh
    /// memory-order stamps.
    #[cfg(feature = "host-speedups")]
    pub(crate) fn or_index_build(&mut self, alpha: Ix) {
        let mut t = self.alpha_mems[alpha as usize].head;
        while t != TokenId::NONE {
            let s = self.st.cache.or_stamp;
            // (the stamp takes the place of a kept key)
            self.tokens[t].key = s;
            self.tokens[t].has_key = false;
            self.st.cache.or_stamp = s.saturating_add(1);
            let tk = self.tokens[t];
            let key = self.alpha_key(
                alpha,
                PatBinding {
                    fact: tk.fact,
                    marks: tk.marks,
                },
            );
            self.or_index_link(t, alpha, key);
            t = self.tokens[t].mem_next;
        }
    }

    /// Adds a new alpha match (already in its node's memory) to the index. (Host:
    /// inlined into the alpha match and beta paths, as before the or-lookup stamp.)
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn index_insert(&mut self, am: TokenId) {
        let tk = self.tokens[am];
        let b = PatBinding {
            fact: tk.fact,
            marks: tk.marks,
        };
        self.index_insert_as(am, tk.alpha(), b);
    }

    /// Adds a new alpha match (already in its node's memory) to the index. (Image:
    /// without the or-lookup stamp, reading the match's values from its token.)
    #[cfg(not(feature = "host-speedups"))]
    pub(crate) fn index_insert(&mut self, am: TokenId) {
        let alpha = self.tokens[am].alpha();
        if !self.alpha_indexed(alpha) {
            return;
        }
        let tk = self.tokens[am];
        let key = self.alpha_key(
            alpha,
            PatBinding {
                fact: tk.fact,
                marks: tk.marks,
            },
        );
        let _ = self.bucket_link(am, alpha, key);
    }

    /// Links alpha match `am` of node `alpha` into its bucket for `key`, at the end;
    /// returns the chain's tail before (NONE: `am` is the chain's first).
    #[inline(always)]
    fn bucket_link(&mut self, am: TokenId, alpha: Ix, key: u32) -> TokenId {
        let b = self.bucket(alpha, key);
        let head = self.amem_buckets[b as usize];
        // (with `grow` the tag the bucket comes from, see `alpha_tag`)
        #[cfg(not(feature = "grow"))]
        let kept = b;
        #[cfg(feature = "grow")]
        let kept = alpha_tag(alpha, key);
        self.tokens[am].parent = TokenId(kept);
        self.tokens[am].am_next = TokenId::NONE;
        if head == TokenId::NONE {
            self.tokens[am].am_prev = am;
            self.amem_buckets[b as usize] = am;
            TokenId::NONE
        } else {
            let tail = self.tokens[head].am_prev;
            self.tokens[tail].am_next = am;
            self.tokens[am].am_prev = tail;
            self.tokens[head].am_prev = am;
            tail
        }
    }

    /// `index_insert` for alpha match `am` of node `alpha` binding `b` (host: the
    /// caller that has just written the token passes these, not read back from it).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn index_insert_as(&mut self, am: TokenId, alpha: Ix, b: PatBinding) {
        if !self.alpha_indexed(alpha) {
            return;
        }
        // matches of an or-lookup node get their place in memory order
        // (a node without a right hash is indexed for its or field alone, so it has one)
        let (keyed, hashed) = {
            let n = &self.alphas[alpha as usize];
            let with_or = n.rhash.get(n.nrhash as usize).is_some_and(|&f| f != NONE);
            if with_or {
                let s = self.st.cache.or_stamp;
                self.tokens[am].key = s;
                self.st.cache.or_stamp = s.saturating_add(1);
            }
            (with_or && n.nrhash > 0, n.nrhash > 0)
        };
        let key = self.alpha_key(alpha, b);
        // kept for the right activations' bucket lookups (`kept_alpha_key`); an or
        // node's matches keep their memory-order stamp there instead
        if hashed && !keyed {
            let tk = &mut self.tokens[am];
            tk.key = key;
            tk.has_key = true;
        }
        let before = self.bucket_link(am, alpha, key);
        #[cfg(feature = "grow")]
        if hashed && before != TokenId::NONE {
            // (most often the chain's previous tail is of the same bucket, and often
            // it is the memory's previous tail too: nothing to move)
            let (b, a) = (&self.tokens[before], &self.tokens[am]);
            // (`before` the chain's head, whose `am_prev` is the tail, `am` now: it was
            // the chain's only match, of another key, so `am` stays the memory's tail)
            let before_only = b.am_prev == am;
            if b.parent == a.parent && b.owner == a.owner {
                if a.mem_prev != before {
                    self.bucket_move_after(am, alpha, before);
                }
                // host: `before` is an older match of the node with `am`'s key: the
                // right activations ask whether it blocks all `am` could (`twin_blocks`)
                if self.st.prime.twin_alpha(alpha) {
                    self.twin_mark(am, alpha);
                }
            } else if !before_only {
                self.bucket_order(am, alpha, before);
            }
        }
        #[cfg(not(feature = "grow"))]
        let _ = (hashed, before);
        if keyed {
            self.or_index_link(am, alpha, key);
        }
    }

    /// Host: CLIPS 6.30 keeps the memory of a pattern with a right hash as a list of
    /// buckets, one per hash value, in the order the buckets were made (a bucket left
    /// empty is dropped, a later match of its value makes a new one at the end), each
    /// bucket's matches oldest first; `matches` and a join primed from the memory
    /// read it so. New match `t` of node `alpha`, just put at the end of the memory
    /// and of its index bucket, moves to after the last match of its own bucket (the
    /// last one of the chain with its tag), if there is one.
    /// `before`: the chain's tail before `t` joined it (not NONE).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    #[inline(never)]
    fn bucket_order(&mut self, t: TokenId, alpha: Ix, before: TokenId) {
        let tag = self.tokens[t].parent;
        let head = self.amem_buckets[self.alpha_bucket_of(tag.0)];
        let mut p = before;
        let last = loop {
            if p == t || p == TokenId::NONE {
                return;
            }
            let pk = self.tokens[p];
            if pk.parent == tag && pk.alpha() == alpha {
                break p;
            }
            if p == head {
                return;
            }
            p = pk.am_prev;
        };
        if self.tokens[t].mem_prev != last {
            self.bucket_move_after(t, alpha, last);
        }
    }

    /// Host: moves new match `t` of node `alpha` (the memory's tail) to just after
    /// `last`, an earlier match of its memory (`bucket_order`).
    #[cfg(all(feature = "grow", feature = "host-speedups"))]
    #[inline(never)]
    fn bucket_move_after(&mut self, t: TokenId, alpha: Ix, last: TokenId) {
        let prev = self.tokens[t].mem_prev;
        if prev == TokenId::NONE {
            return;
        }
        // out of the memory's end (`t` is its tail)...
        self.tokens[prev].mem_next = TokenId::NONE;
        self.alpha_mems[alpha as usize].tail = prev;
        // ...and in after the bucket's last match
        let next = self.tokens[last].mem_next;
        self.tokens[t].mem_prev = last;
        self.tokens[t].mem_next = next;
        self.tokens[last].mem_next = t;
        if next != TokenId::NONE {
            self.tokens[next].mem_prev = t;
        } else {
            self.alpha_mems[alpha as usize].tail = t;
        }
    }

    /// Takes alpha match `am` of node `alpha` out of the index.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn index_remove(&mut self, am: TokenId, alpha: Ix) {
        debug_assert!(self.tokens[am].kind == TokenKind::Alpha && self.tokens[am].alpha() == alpha);
        if !self.alpha_indexed(alpha) {
            return;
        }
        let b = self.tokens[am].parent.ix();
        #[cfg(feature = "grow")]
        let b = self.alpha_bucket_of(b as u32);
        self.amem_buckets[b] = self.am_chain_remove(self.amem_buckets[b], am);
        // (with `grow` the tag stays: a search for the next blocker after a match
        // going away goes on along its bucket with it, `next_candidate`)
        #[cfg(not(feature = "grow"))]
        {
            self.tokens[am].parent = TokenId::NONE;
        }
        #[cfg(feature = "host-speedups")]
        if keyed_or(&self.alphas[alpha as usize]) {
            self.or_index_unlink(am);
        }
    }

    /// Removes `t` from a chain linked through `am_next`/`am_prev` whose head's
    /// `am_prev` is the tail (a bucket, or the owed list); returns the new head.
    pub(crate) fn am_chain_remove(&mut self, head: TokenId, t: TokenId) -> TokenId {
        let tk = self.tokens[t];
        let mut new_head = head;
        if t == head {
            new_head = tk.am_next;
            if tk.am_next != TokenId::NONE {
                // the new head keeps the tail
                self.tokens[tk.am_next].am_prev = tk.am_prev;
            }
        } else {
            self.tokens[tk.am_prev].am_next = tk.am_next;
            if tk.am_next != TokenId::NONE {
                self.tokens[tk.am_next].am_prev = tk.am_prev;
            } else {
                self.tokens[head].am_prev = tk.am_prev;
            }
        }
        self.tokens[t].am_next = TokenId::NONE;
        self.tokens[t].am_prev = TokenId::NONE;
        new_head
    }

    /// Where a left token of alpha-fed `join` starts looking for right partners:
    /// the first match of its bucket (then `next_candidate` with `hashed`), or the
    /// whole memory.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn first_candidate(&mut self, join: JoinId, left: TokenId) -> (TokenId, bool) {
        self.first_candidate_in::<false>(join, left)
    }

    /// `first_candidate` for the search of a not/exists join's blocker: with
    /// feature `grow` the first match of the left token's key (`skip_other_key`),
    /// then `next_blocker_candidate`. A blocker search stops at its first match,
    /// so every entry of another key it visits costs it a test; a positive join's
    /// walk visits its key's matches (most entries, where the table is not crowded)
    /// and keeps the one check.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn first_blocker_candidate(
        &mut self,
        join: JoinId,
        left: TokenId,
    ) -> (TokenId, bool) {
        self.first_candidate_in::<true>(join, left)
    }

    #[inline(always)]
    fn first_candidate_in<const BY_KEY: bool>(
        &mut self,
        join: JoinId,
        left: TokenId,
    ) -> (TokenId, bool) {
        debug_assert!(self.joins[join].kind != JoinKind::Root);
        let alpha = self.joins[join].alpha;
        if self.alphas[alpha as usize].nrhash > 0 {
            if let Some(key) = self.left_bucket_key(join, left) {
                #[cfg(feature = "grow")]
                if BY_KEY {
                    let tag = alpha_tag(alpha, key);
                    let a = self.amem_buckets[self.alpha_bucket_of(tag)];
                    return (self.skip_other_key(a, alpha, tag), true);
                }
                let b = self.bucket(alpha, key);
                let a = self.amem_buckets[b as usize];
                return (self.skip_foreign(a, alpha), true);
            }
        }
        (self.alpha_mems[alpha as usize].head, false)
    }

    /// The key of left token `left` of keyed `join` (its alpha node has a right
    /// hash), None when a value cannot be read (then the memory is scanned).
    // (inlined everywhere: the image's one caller keeps its code as it was)
    #[inline(always)]
    pub(crate) fn left_bucket_key(&mut self, join: JoinId, left: TokenId) -> Option<u32> {
        let (ct, cj, ck) = self.st.cache.key_cache;
        if ct == left && cj == join {
            return Some(ck);
        }
        self.bind_for_quick(left);
        let key = match self.quick_left_key(join, left) {
            Some(k) => Some(k),
            None => {
                self.bind_left(left);
                self.left_key(join)
            }
        };
        #[cfg(feature = "host-speedups")]
        if let Some(k) = key {
            let owner = self.tokens[left].owner;
            if self.joins[owner].index_child == join {
                let tk = &mut self.tokens[left];
                tk.key = k;
                tk.has_key = true;
            }
        }
        key
    }

    /// The candidate after `a` (same chain kind as `first_candidate` gave).
    pub(crate) fn next_candidate(&self, a: TokenId, hashed: bool) -> TokenId {
        if hashed {
            let alpha = self.tokens[a].alpha();
            self.skip_foreign(self.tokens[a].am_next, alpha)
        } else {
            self.tokens[a].mem_next
        }
    }

    /// `next_candidate` for a blocker search (`first_blocker_candidate`): with
    /// feature `grow` also past matches of other keys than `a`'s (its tag, kept
    /// while it goes away, is the left token's: `a` passed the equality tests, or
    /// is the first of the key).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn next_blocker_candidate(&self, a: TokenId, hashed: bool) -> TokenId {
        #[cfg(feature = "grow")]
        if hashed {
            let tk = &self.tokens[a];
            return self.skip_other_key(tk.am_next, tk.alpha(), tk.parent.0);
        }
        self.next_candidate(a, hashed)
    }

    /// With feature `grow`: skips bucket entries of other alpha nodes and of other
    /// keys (their tag, kept in `parent`, differs from `tag`: a collision in the
    /// bucket, whose equality tests fail, having run only what a larger table would
    /// not have run either).
    #[cfg(feature = "grow")]
    #[inline(always)]
    pub(crate) fn skip_other_key(&self, mut a: TokenId, alpha: Ix, tag: u32) -> TokenId {
        while a != TokenId::NONE {
            let tk = &self.tokens[a];
            if tk.parent.0 == tag && tk.alpha() == alpha {
                break;
            }
            a = tk.am_next;
        }
        a
    }

    /// Skips bucket entries of other alpha nodes.
    fn skip_foreign(&self, mut a: TokenId, alpha: Ix) -> TokenId {
        while a != TokenId::NONE && self.tokens[a].alpha() != alpha {
            a = self.tokens[a].am_next;
        }
        a
    }

    // ---- beta memories ----
    //
    // A join's output memory is indexed for one child join (`Join::index_child`,
    // the first child fed by an alpha node with a right hash, chosen while the
    // memory is empty): each partial match sits in the bucket of the values that
    // child's equality tests read from it, so a new alpha match right-activating
    // the child visits only its bucket (newest first, as the memory). Beta tokens
    // keep the bucket links in fields only alpha matches use: `fact` (next),
    // `marks[0..2]` (previous; the head's is the tail), `marks[2..4]` (bucket).
    //
    // Host: a memory shared by several keyed children (rules with a common prefix)
    // also keeps up to `XGROUPS` extra index groups, each keyed as one child's tests
    // read (links in the token pool's side array `token_xlinks`), taken on a child's first right activation
    // (`JoinMem::xmap`); a child whose key plan reads the same fields as a group's
    // uses that group. Each group has its own part of the beta buckets, as a
    // bucket's chain runs through one group's links.

    fn bnext(&self, t: TokenId) -> TokenId {
        TokenId(self.tokens[t].fact)
    }

    fn set_bnext(&mut self, t: TokenId, n: TokenId) {
        self.tokens[t].fact = n.0;
    }

    #[cfg(not(feature = "wide-index"))]
    fn bprev(&self, t: TokenId) -> TokenId {
        let m = self.tokens[t].marks;
        TokenId(Ix::from_le_bytes([m[0], m[1]]))
    }

    #[cfg(not(feature = "wide-index"))]
    fn set_bprev(&mut self, t: TokenId, p: TokenId) {
        let b = p.0.to_le_bytes();
        self.tokens[t].marks[0] = b[0];
        self.tokens[t].marks[1] = b[1];
    }

    #[cfg(not(feature = "wide-index"))]
    fn bbucket(&self, t: TokenId) -> Ix {
        let m = self.tokens[t].marks;
        Ix::from_le_bytes([m[2], m[3]])
    }

    #[cfg(not(feature = "wide-index"))]
    fn set_bbucket(&mut self, t: TokenId, b: Ix) {
        let x = b.to_le_bytes();
        self.tokens[t].marks[2] = x[0];
        self.tokens[t].marks[3] = x[1];
    }

    // With `u32` indices two links do not fit in `marks`: the token has a field for them.
    #[cfg(feature = "wide-index")]
    fn bprev(&self, t: TokenId) -> TokenId {
        TokenId(self.tokens[t].beta_links[0])
    }

    #[cfg(feature = "wide-index")]
    fn set_bprev(&mut self, t: TokenId, p: TokenId) {
        self.tokens[t].beta_links[0] = p.0;
    }

    #[cfg(feature = "wide-index")]
    fn bbucket(&self, t: TokenId) -> Ix {
        self.tokens[t].beta_links[1]
    }

    #[cfg(feature = "wide-index")]
    fn set_bbucket(&mut self, t: TokenId, b: Ix) {
        self.tokens[t].beta_links[1] = b;
    }

    /// Index group `g`'s next link of partial match `t` (group 0: `bnext`).
    #[inline(always)]
    fn gnext(&self, t: TokenId, g: usize) -> TokenId {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            return TokenId(self.token_xlinks[t.ix()][g - 1][0]);
        }
        let _ = g;
        self.bnext(t)
    }

    #[inline(always)]
    fn set_gnext(&mut self, t: TokenId, n: TokenId, g: usize) {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            self.token_xlinks[t.ix()][g - 1][0] = n.0;
            return;
        }
        let _ = g;
        self.set_bnext(t, n)
    }

    #[inline(always)]
    fn gprev(&self, t: TokenId, g: usize) -> TokenId {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            return TokenId(self.token_xlinks[t.ix()][g - 1][1]);
        }
        let _ = g;
        self.bprev(t)
    }

    #[inline(always)]
    fn set_gprev(&mut self, t: TokenId, p: TokenId, g: usize) {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            self.token_xlinks[t.ix()][g - 1][1] = p.0;
            return;
        }
        let _ = g;
        self.set_bprev(t, p)
    }

    // (with wide indices alone the memory's link is read instead)
    #[cfg(any(
        feature = "host-speedups",
        feature = "grow",
        not(feature = "wide-index")
    ))]
    #[inline(always)]
    fn gbucket(&self, t: TokenId, g: usize) -> Ix {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            return self.token_xlinks[t.ix()][g - 1][2];
        }
        let _ = g;
        self.bbucket(t)
    }

    #[inline(always)]
    fn set_gbucket(&mut self, t: TokenId, b: Ix, g: usize) {
        #[cfg(feature = "host-speedups")]
        if g > 0 {
            self.token_xlinks[t.ix()][g - 1][2] = b;
            return;
        }
        let _ = g;
        self.set_bbucket(t, b)
    }

    /// The bucket of index group `g` that tag `tag` maps to.
    #[inline(always)]
    fn group_bucket(&self, tag: u32, g: usize) -> usize {
        let (first, count) = group_range(self.amem_buckets.len(), g);
        first + reduce(tag, count)
    }

    fn beta_bucket(&self, join: JoinId, key: u32, g: usize) -> Ix {
        self.group_bucket(beta_tag(join, key), g) as Ix
    }

    /// Makes `child` the join whose tests key `parent`'s memory, if the memory is
    /// empty and not indexed yet and `child` is fed by a node with a right hash.
    pub(crate) fn choose_index_child(&mut self, parent: JoinId, child: JoinId) {
        // called for every new join: a reused join id must not keep an old plan (the
        // one entry it can be in; clearing all cost every rule's load a cache fill)
        let k = child.ix() % KEY_PLANS;
        if self.st.cache.key_plans[k].join == child {
            self.st.cache.key_plans[k] = KeyPlan::NONE;
        }
        self.forget_test_plan(child);
        let p = self.joins[parent];
        let c = self.joins[child];
        if parent != JoinId::ROOT
            && p.index_child == JoinId::NONE
            && self.join_mems[parent].mem == TokenId::NONE
            && c.alpha != NONE
            && c.rjoin == JoinId::NONE
            && self.alphas[c.alpha as usize].nrhash > 0
        {
            self.joins[parent].index_child = child;
        }
    }

    /// Adds a new partial match (already at the head of its memory) to the index.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn beta_index_insert(&mut self, t: TokenId) {
        let join = self.tokens[t].owner;
        let child = self.joins[join].index_child;
        #[cfg(feature = "host-speedups")]
        let skip = child == JoinId::NONE || !self.join_mems[join].index_built;
        #[cfg(not(feature = "host-speedups"))]
        let skip = child == JoinId::NONE;
        if skip {
            self.set_bnext(t, TokenId::NONE);
            self.set_bprev(t, TokenId::NONE);
            self.set_bbucket(t, NONE);
        } else {
            self.beta_index_link(t, join, child, 0);
        }
        #[cfg(feature = "host-speedups")]
        if self.join_mems[join].xbuilt != 0 {
            self.link_extra(t, join);
        }
    }

    /// `beta_index_insert` for a token of `join` just written from `Token::EMPTY`: with
    /// `u32` indices its bucket links are NONE already (in the image they live in
    /// `marks`, which EMPTY zeroes, so they are written).
    /// On the host `child` is the join's index child if its index is built (NONE
    /// otherwise) and `xbuilt` its built extra groups (`JoinMem::xbuilt`), read by the
    /// caller with the join's other fields.
    #[cfg(all(feature = "host-speedups", feature = "wide-index"))]
    #[inline(always)]
    pub(crate) fn beta_index_insert_fresh(
        &mut self,
        t: TokenId,
        join: JoinId,
        child: JoinId,
        xbuilt: u8,
    ) {
        if child != JoinId::NONE {
            self.beta_index_link(t, join, child, 0);
        }
        if xbuilt != 0 {
            self.link_extra(t, join);
        }
    }

    #[cfg(not(all(feature = "host-speedups", feature = "wide-index")))]
    pub(crate) fn beta_index_insert_fresh(
        &mut self,
        t: TokenId,
        _join: JoinId,
        _child: JoinId,
        _xbuilt: u8,
    ) {
        self.beta_index_insert(t);
    }

    /// Host: puts partial match `t` of `join` in each built extra index group of its
    /// memory.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn link_extra(&mut self, t: TokenId, join: JoinId) {
        let built = self.join_mems[join].xbuilt;
        for g in 1..=XGROUPS {
            if built & (1 << (g - 1)) != 0 {
                let child = self.join_mems[join].xkey[g - 1];
                self.beta_index_link(t, join, child, g);
            }
        }
    }

    /// Puts partial match `t` of `join` at the head of its bucket of index group `g`,
    /// keyed by `child`'s tests.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn beta_index_link(&mut self, t: TokenId, join: JoinId, child: JoinId, g: usize) {
        #[cfg(feature = "host-speedups")]
        let known = {
            let tk = &self.tokens[t];
            (tk.has_key && g == 0).then_some(tk.key)
        };
        #[cfg(not(feature = "host-speedups"))]
        let known = None;
        // usually one level more than the left token just bound by the join test
        self.bind_for_quick(t);
        let known = match known {
            Some(k) => Some(k),
            None => {
                let k = self.quick_left_key(child, t);
                // host: kept for the next link (`move_to_front`), as `first_candidate`
                // keeps it
                #[cfg(feature = "host-speedups")]
                if let (Some(k), 0) = (k, g) {
                    let tk = &mut self.tokens[t];
                    tk.key = k;
                    tk.has_key = true;
                }
                k
            }
        };
        let key = match known {
            Some(key) => key,
            None => {
                self.bind_left(t);
                let (pm, depth) = (self.st.net.pm_rhs, self.joins[child].depth as usize);
                let saved = self.st.net.lhs_pm[depth];
                // an unreadable value: bucket of key 0 (the child then scans, see below)
                let key = self.left_key(child).unwrap_or(0);
                self.st.net.lhs_pm[depth] = saved;
                self.st.net.pm_rhs = pm;
                key
            }
        };
        self.st.cache.key_cache = (t, child, key);
        // host: a token's extra links are its own only from its first extra group on
        // (`XLinks`): the other groups' must read unlinked
        #[cfg(feature = "host-speedups")]
        if g > 0 && !self.tokens[t].in_x {
            self.tokens[t].in_x = true;
            self.token_xlinks[t.ix()] = crate::rete::NO_XLINKS;
        }
        let b = self.beta_bucket(join, key, g);
        let head = self.amem_buckets[b as usize];
        #[cfg(not(feature = "grow"))]
        self.set_gbucket(t, b, g);
        #[cfg(feature = "grow")]
        self.set_gbucket(t, beta_tag(join, key), g);
        self.set_gnext(t, head, g);
        if head == TokenId::NONE {
            self.set_gprev(t, t, g);
        } else {
            let tail = self.gprev(head, g);
            self.set_gprev(t, tail, g);
            self.set_gprev(head, t, g);
        }
        self.amem_buckets[b as usize] = t;
    }

    /// Takes `t` out of the chain of bucket `b` of index group `g`.
    #[inline(always)]
    fn chain_unlink(&mut self, t: TokenId, b: usize, g: usize) {
        let (next, prev) = (self.gnext(t, g), self.gprev(t, g));
        let head = self.amem_buckets[b];
        if head == t {
            self.amem_buckets[b] = next;
            if next != TokenId::NONE {
                self.set_gprev(next, prev, g);
            }
        } else {
            self.set_gnext(prev, next, g);
            if next != TokenId::NONE {
                self.set_gprev(next, prev, g);
            } else {
                self.set_gprev(head, prev, g);
            }
        }
        self.set_gbucket(t, NONE, g);
    }

    /// The bucket partial match `t` sits in for group `g` (NONE: none).
    #[cfg(any(feature = "host-speedups", not(feature = "wide-index")))]
    #[inline(always)]
    fn bucket_of(&self, t: TokenId, g: usize) -> Ix {
        let b = self.gbucket(t, g);
        #[cfg(feature = "grow")]
        let b = if b == NONE {
            NONE
        } else {
            self.group_bucket(b as u32, g) as Ix
        };
        if b == NONE || b as usize >= self.amem_buckets.len() {
            return NONE;
        }
        b
    }

    /// Host: takes partial match `t` out of its memory's extra index groups.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn unlink_extra(&mut self, t: TokenId) {
        for g in 1..=XGROUPS {
            let b = self.bucket_of(t, g);
            if b != NONE {
                self.chain_unlink(t, b as usize, g);
            }
        }
        self.tokens[t].in_x = false;
    }

    /// Takes a partial match out of its memory's index.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn beta_index_remove(&mut self, t: TokenId) {
        #[cfg(feature = "host-speedups")]
        if self.tokens[t].in_x {
            self.unlink_extra(t);
        }
        // host: only a partial match linked into its indexed memory's buckets has a
        // bucket (alpha matches and links keep `beta_links` NONE; `drop_beta_index`
        // unlinks all before the memory stops being indexed): the link decides
        #[cfg(feature = "wide-index")]
        {
            let tag = self.bbucket(t);
            if tag == NONE {
                return;
            }
            debug_assert!(self.tokens[t].kind == TokenKind::Beta);
            debug_assert!(self.joins[self.tokens[t].owner].index_child != JoinId::NONE);
            #[cfg(feature = "grow")]
            let b = self.group_bucket(tag as u32, 0);
            #[cfg(not(feature = "grow"))]
            let b = tag as usize;
            if b < self.amem_buckets.len() {
                self.chain_unlink(t, b, 0);
            }
        }
        #[cfg(not(feature = "wide-index"))]
        {
            let owner = self.tokens[t].owner;
            if self.tokens[t].kind != TokenKind::Beta
                || self.joins[owner].index_child == JoinId::NONE
            {
                return;
            }
            let b = self.bucket_of(t, 0);
            if b != NONE {
                self.chain_unlink(t, b as usize, 0);
            }
        }
    }

    /// Host (`move_to_front`): takes partial match `t` of `join` out of its index.
    /// When that is its group-0 bucket alone (no extra group built, `t` in none) and
    /// its key is kept in it, returns the bucket: `index_front_put` puts it back at
    /// the head, where `beta_index_insert` would, without recomputing the key.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(always)]
    pub(crate) fn index_front_take(&mut self, t: TokenId, join: JoinId) -> Option<(usize, Ix)> {
        let tk = &self.tokens[t];
        if tk.has_key && !tk.in_x && self.join_mems[join].xbuilt == 0 {
            let tag = self.gbucket(t, 0);
            let b = self.bucket_of(t, 0);
            if b != NONE {
                self.chain_unlink(t, b as usize, 0);
                return Some((b as usize, tag));
            }
        }
        self.beta_index_remove(t);
        None
    }

    /// Host: puts `t` back at the head of its bucket `b` with its tag `tag`
    /// (`index_front_take`), as `beta_index_link` would, its key cached as there.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(always)]
    pub(crate) fn index_front_put(&mut self, t: TokenId, join: JoinId, (b, tag): (usize, Ix)) {
        self.st.cache.key_cache = (t, self.joins[join].index_child, self.tokens[t].key);
        let head = self.amem_buckets[b];
        self.set_gbucket(t, tag, 0);
        self.set_gnext(t, head, 0);
        if head == TokenId::NONE {
            self.set_gprev(t, t, 0);
        } else {
            let tail = self.gprev(head, 0);
            self.set_gprev(t, tail, 0);
            self.set_gprev(head, t, 0);
        }
        self.amem_buckets[b] = t;
    }

    /// Where a new alpha match `am` right-activating `join` starts among the
    /// parent's partial matches: its bucket when the parent's memory is indexed for
    /// `join` (then `next_left` with the group `via` it returns), else the whole
    /// memory (`via` 0). (Host: inlined in both walks, `right_activate` and
    /// `rete::order`'s.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn first_left(&mut self, join: JoinId, am: TokenId) -> (TokenId, u8) {
        let j = self.joins[join];
        let parent_mem = self.join_mems[j.parent].mem;
        // host: an empty memory stays unindexed (its index would only make every
        // partial match that comes pay its bucket until the next right activation)
        #[cfg(feature = "host-speedups")]
        if parent_mem == TokenId::NONE {
            return (TokenId::NONE, 0);
        }
        let group = if self.joins[j.parent].index_child == join {
            #[cfg(feature = "host-speedups")]
            if !self.join_mems[j.parent].index_built && !self.build_beta_index(j.parent, join) {
                return (parent_mem, 0);
            }
            Some(0)
        } else {
            // (a child without a right hash has no key: it scans; so does one without
            // tests, tested first as the join is at hand: `key_plan` finds no key)
            #[cfg(feature = "host-speedups")]
            let g = if j.tests != NONE && self.alphas[j.alpha as usize].nrhash > 0 {
                self.extra_group(j.parent, join)
            } else {
                None
            };
            #[cfg(not(feature = "host-speedups"))]
            let g = None;
            g
        };
        if let Some(g) = group {
            let key = self.kept_alpha_key(j.alpha, am);
            let b = self.beta_bucket(j.parent, key, g);
            let first = self.skip_other_beta(self.amem_buckets[b as usize], j.parent, g);
            return (first, g as u8 + 1);
        }
        (parent_mem, 0)
    }

    /// The partial match after `l` (`via` as `first_left` gave). (The host's right
    /// activations walk with `next_left_in`; the primed walks of `grow` with this.)
    #[cfg(any(not(feature = "host-speedups"), feature = "grow"))]
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn next_left(&self, l: TokenId, via: u8) -> TokenId {
        if via > 0 {
            let g = via as usize - 1;
            let owner = self.tokens[l].owner;
            self.skip_other_beta(self.gnext(l, g), owner, g)
        } else {
            self.tokens[l].mem_next
        }
    }

    /// Host: `next_left` for a left token `l` of `owner`, known to the caller (the
    /// right activation's walk: no owner read per token).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn next_left_of(&self, l: TokenId, via: u8, owner: JoinId) -> TokenId {
        if via == 0 {
            return self.tokens[l].mem_next;
        }
        // group 0 (the index child's, most indexed walks) with a loop of its own:
        // sharing the extra groups' loop set up their links' address per token
        if via == 1 {
            let mut n = self.bnext(l);
            while n != TokenId::NONE && self.tokens[n].owner != owner {
                n = self.bnext(n);
            }
            return n;
        }
        self.next_left_extra(l, via, owner)
    }

    /// Host: `next_left_of` along an extra group (out of line: its loop kept the
    /// right activation's registers busy on every walk).
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn next_left_extra(&self, l: TokenId, via: u8, owner: JoinId) -> TokenId {
        let g = via as usize - 1;
        self.skip_other_beta(self.gnext(l, g), owner, g)
    }

    /// (Host: inlined into the walks of `first_left`/`next_left`, which call it per
    /// partial match.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn skip_other_beta(&self, mut l: TokenId, join: JoinId, g: usize) -> TokenId {
        while l != TokenId::NONE && self.tokens[l].owner != join {
            l = self.gnext(l, g);
        }
        l
    }

    /// Host: the index group of `parent`'s memory that `join` (a child fed by an
    /// alpha node) right-activates through, None to scan the memory.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn extra_group(&mut self, parent: JoinId, join: JoinId) -> Option<usize> {
        let map = &self.join_mems[parent].xmap;
        let mut free = XMAP;
        let mut group = None;
        for (k, &(c, g)) in map.iter().enumerate() {
            if c == join {
                group = Some(g);
                break;
            }
            if c == JoinId::NONE {
                free = k;
                break;
            }
        }
        let g = match group {
            Some(g) => g,
            None => self.claim_group(parent, join, free),
        };
        if g == XSCAN {
            return None;
        }
        // (re)build on use: an empty memory gives its groups' buckets up; one of a
        // single partial match is scanned (see `build_beta_index`)
        if g == 0 {
            if !self.join_mems[parent].index_built {
                let ic = self.joins[parent].index_child;
                if !self.build_beta_index(parent, ic) {
                    return None;
                }
            }
        } else if self.join_mems[parent].xbuilt & (1 << (g - 1)) == 0
            && !self.build_extra_group(parent, g as usize)
        {
            return None;
        }
        Some(g as usize)
    }

    /// Host: whether `join`'s (non-empty) memory holds one partial match.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn single_match(&self, join: JoinId) -> bool {
        let m = self.join_mems[join].mem;
        m != TokenId::NONE && self.tokens[m].mem_next == TokenId::NONE
    }

    /// Host: links every partial match of `parent`'s memory into its extra index
    /// group `g` (out of line: its caller is on every right activation); false, as
    /// `build_beta_index`, for a memory of one partial match.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn build_extra_group(&mut self, parent: JoinId, g: usize) -> bool {
        if self.single_match(parent) {
            return false;
        }
        let child = self.join_mems[parent].xkey[g - 1];
        self.build_group(parent, child, g);
        self.join_mems[parent].xbuilt |= 1 << (g - 1);
        true
    }

    /// Host: finds or takes the index group for `join` in `parent`'s memory (a
    /// group keyed on the same fields, or a new one while there is room; `XSCAN`:
    /// none) and remembers it in `xmap` entry `free` (if below `XMAP`).
    #[cfg(feature = "host-speedups")]
    #[cold]
    #[inline(never)]
    fn claim_group(&mut self, parent: JoinId, join: JoinId, free: usize) -> u8 {
        let j = self.joins[join];
        let plan = self.key_plan(join);
        let mut group = XSCAN;
        if j.rjoin == JoinId::NONE
            && j.alpha != NONE
            && self.alphas[j.alpha as usize].nrhash > 0
            && (plan.n != KeyPlan::NONE.n || self.segment_keyed(join))
        {
            let ic = self.joins[parent].index_child;
            if ic != JoinId::NONE && self.same_key(ic, &plan) {
                group = 0;
            } else {
                let nx = self.join_mems[parent].nx as usize;
                for k in 0..nx {
                    if self.same_key(self.join_mems[parent].xkey[k], &plan) {
                        group = k as u8 + 1;
                        break;
                    }
                }
                if group == XSCAN && nx < XGROUPS && group_range(self.amem_buckets.len(), 1).1 > 0 {
                    let jm = &mut self.join_mems[parent];
                    jm.xkey[nx] = join;
                    jm.nx += 1;
                    group = nx as u8 + 1;
                }
            }
        }
        if let Some(e) = self.join_mems[parent].xmap.get_mut(free) {
            *e = (join, group);
        }
        group
    }

    /// Host: whether `join` has no key plan only because some of the earlier
    /// variables its equality tests compare with are bound inside segments (after a
    /// multifield of their slot, `(rango $? ?v $?)`): `left_key` reads those once per
    /// partial match through its bindings' multifield marks, so an extra index group
    /// keyed on them spares the right activations a scan of the whole memory (each
    /// pair's test re-walking the segments). Such a group is the join's own
    /// (`same_key` shares none without a plan).
    #[cfg(feature = "host-speedups")]
    fn segment_keyed(&self, join: JoinId) -> bool {
        let j = self.joins[join];
        let nrhash = self.alphas[j.alpha as usize].nrhash;
        let (mut n, mut seg) = (0u8, false);
        let mut t = j.tests;
        while t != NONE && n < nrhash {
            let x = self.exprs[t as usize];
            if x.op == Op::Eq2 && x.first != NONE {
                let this = self.exprs[x.first as usize];
                if this.op == Op::PatVar && this.aux == j.depth && this.next != NONE {
                    let o = self.exprs[this.next as usize];
                    if o.op == Op::PatVar && o.aux != j.depth {
                        if o.aux > j.depth || o.data == loc::FACT {
                            return false;
                        }
                        if o.first != NONE && self.fixed_elem(&o).is_none() {
                            if loc::elem(o.data) == loc::SINGLE {
                                return false;
                            }
                            seg = true;
                        }
                        n += 1;
                    }
                }
            }
            t = x.next;
        }
        seg && n == nrhash
    }

    /// Host: whether `join`'s key plan reads the fields (and elements) `plan` reads,
    /// in its order.
    #[cfg(feature = "host-speedups")]
    fn same_key(&self, join: JoinId, plan: &KeyPlan) -> bool {
        let p = self.key_plan(join);
        let n = plan.n as usize;
        p.n == plan.n
            && n <= MAX_RHASH
            && p.vars[..n] == plan.vars[..n]
            && p.elems[..n] == plan.elems[..n]
    }

    /// Links every partial match of `join`'s memory into index group `g`, keyed by
    /// `child`'s tests. Oldest first, each at its bucket's head: the buckets get
    /// memory order, as if every match had been indexed when it came.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn build_group(&mut self, join: JoinId, child: JoinId, g: usize) {
        self.build_group_of::<false>(join, child, g);
    }

    /// `build_group`; `ACTIVE_ONLY`: leaves blocked partial matches out (see
    /// `build_group_active`).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn build_group_of<const ACTIVE_ONLY: bool>(&mut self, join: JoinId, child: JoinId, g: usize) {
        let mut t = self.join_mems[join].mem;
        let mut last = TokenId::NONE;
        while t != TokenId::NONE {
            last = t;
            t = self.tokens[t].mem_next;
        }
        while last != TokenId::NONE {
            if !ACTIVE_ONLY || !self.tokens[last].blocked {
                self.beta_index_link(last, join, child, g);
            }
            last = self.tokens[last].mem_prev;
        }
    }

    /// Host: whether not output `t`, unblocked at the head of `join`'s memory, is
    /// out of the group-0 bucket it belongs in (`build_group_active` left it out).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn left_out(&self, t: TokenId, join: JoinId) -> bool {
        self.join_mems[join].index_built && self.gbucket(t, 0) == NONE
    }

    /// Host: puts `left_out` not output `t` of `join` in its group-0 bucket (out of
    /// line: `move_to_front` stays as it was without it).
    #[cfg(feature = "host-speedups")]
    #[cold]
    #[inline(never)]
    pub(crate) fn index_left_out(&mut self, t: TokenId, join: JoinId) {
        let child = self.joins[join].index_child;
        if child != JoinId::NONE {
            self.beta_index_link(t, join, child, 0);
        }
    }

    /// Host: indexes `join`'s memory for `child` (see `JoinMem::index_built`). False
    /// for a memory of one partial match, left unindexed: the right activation
    /// scans it (its one join test is what the bucket's key would save; out of
    /// line, with the build, so that the check stays off the indexed path).
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn build_beta_index(&mut self, join: JoinId, child: JoinId) -> bool {
        if self.single_match(join) {
            return false;
        }
        if self.joins[join].kind == JoinKind::Negative {
            self.build_group_active(join, child);
        } else {
            self.build_group(join, child, 0);
        }
        self.join_mems[join].index_built = true;
        true
    }

    /// Host: `build_group` for group 0 of not join `join`, leaving its blocked
    /// outputs out: a right activation skips them (they pass nothing on), and the
    /// unblock that activates one puts it in (`move_to_front`, `index_left_out`).
    /// Most outputs of a not join filled before its first right activation are
    /// blocked (negation-1000: 450 of 499). (Out of line: the other joins' build
    /// loop stays as it was.)
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn build_group_active(&mut self, join: JoinId, child: JoinId) {
        self.build_group_of::<true>(join, child, 0);
    }

    /// Host: gives up `join`'s extra index groups (a child goes away; they are
    /// taken again as children right-activate).
    #[cfg(feature = "host-speedups")]
    pub(crate) fn drop_extra_index(&mut self, join: JoinId) {
        if self.join_mems[join].xmap[0].0 == JoinId::NONE {
            return;
        }
        let mut t = self.join_mems[join].mem;
        while t != TokenId::NONE {
            if self.tokens[t].in_x {
                self.unlink_extra(t);
            }
            t = self.tokens[t].mem_next;
        }
        let jm = &mut self.join_mems[join];
        jm.xkey = [JoinId::NONE; XGROUPS];
        jm.nx = 0;
        jm.xmap = [(JoinId::NONE, 0); XMAP];
        jm.xbuilt = 0;
    }

    /// Stops indexing `join`'s memory (its index child goes away).
    pub(crate) fn drop_beta_index(&mut self, join: JoinId) {
        #[cfg(feature = "host-speedups")]
        self.drop_extra_index(join);
        let mut t = self.join_mems[join].mem;
        while t != TokenId::NONE {
            self.beta_index_remove(t);
            t = self.tokens[t].mem_next;
        }
        self.joins[join].index_child = JoinId::NONE;
        #[cfg(feature = "host-speedups")]
        {
            self.join_mems[join].index_built = false;
        }
    }
}

/// With feature `grow`: the token index follows its pool (see `grow`).
#[cfg(feature = "grow")]
impl Core<'_> {
    /// Links every token of the old table `old` (bucket heads, alpha buckets in the
    /// first half) into the table `amem_buckets` is now (every head `NONE`), each by
    /// the tag it keeps. Tokens of one key share a tag, so one old chain holds them and
    /// one new chain gets them, in the old chain's order: they keep their order.
    pub(crate) fn relink_token_index(&mut self, old: &[TokenId]) {
        let old_half = (old.len() / 2).max(1);
        for &head in &old[..old_half.min(old.len())] {
            // alpha matches, oldest first: each appended to its new bucket
            let mut t = head;
            while t != TokenId::NONE {
                let next = self.tokens[t].am_next;
                let b = self.alpha_bucket_of(self.tokens[t].parent.0);
                let first = self.amem_buckets[b];
                self.tokens[t].am_next = TokenId::NONE;
                if first == TokenId::NONE {
                    self.tokens[t].am_prev = t;
                    self.amem_buckets[b] = t;
                } else {
                    let tail = self.tokens[first].am_prev;
                    self.tokens[tail].am_next = t;
                    self.tokens[t].am_prev = tail;
                    self.tokens[first].am_prev = t;
                }
                t = next;
            }
        }
        // group by group, each group's range of the old and the new table read once
        // (not per token: the table's fields may alias the tokens' for the compiler)
        let (n_old, n_new) = (old.len(), self.amem_buckets.len());
        #[cfg(feature = "host-speedups")]
        let groups = OR_GROUP;
        #[cfg(not(feature = "host-speedups"))]
        let groups = 0;
        for g in 0..=groups {
            let (first, count) = group_range(n_old, g);
            let (start, end) = (first.max(old_half), (first + count).min(n_old));
            let (new_first, new_count) = group_range(n_new, g);
            for &head in old.get(start..end).unwrap_or(&[]) {
                if head == TokenId::NONE {
                    continue;
                }
                #[cfg(feature = "host-speedups")]
                if g == OR_GROUP {
                    self.relink_or_chain(head);
                    continue;
                }
                // partial matches, newest first: from the tail, each put at the head
                let mut t = self.gprev(head, g);
                loop {
                    let prev = if t == head {
                        TokenId::NONE
                    } else {
                        self.gprev(t, g)
                    };
                    let b = new_first + reduce(self.gbucket(t, g) as u32, new_count);
                    let first = self.amem_buckets[b];
                    self.set_gnext(t, first, g);
                    if first == TokenId::NONE {
                        self.set_gprev(t, t, g);
                    } else {
                        let tail = self.gprev(first, g);
                        self.set_gprev(t, tail, g);
                        self.set_gprev(first, t, g);
                    }
                    self.amem_buckets[b] = t;
                    if prev == TokenId::NONE {
                        break;
                    }
                    t = prev;
                }
            }
        }
    }

    /// Host: moves the alpha matches of an old keyed or-index chain (from `head`,
    /// oldest first) to their buckets in the new table, each appended by its tag.
    #[cfg(feature = "host-speedups")]
    fn relink_or_chain(&mut self, head: TokenId) {
        let mut t = head;
        while t != TokenId::NONE {
            let next = self.or_link(t, 0);
            let b = self.or_bucket_of(t);
            self.or_chain_append(b, t);
            t = next;
        }
    }
}
