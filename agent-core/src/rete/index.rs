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

use super::{JoinKind, PatBinding, TokenKind, THIS_PATTERN};
use crate::engine::Core;
use crate::expr::Op;
use crate::value::{Value, NONE};

fn mix(h: u32, x: u32) -> u32 {
    (h ^ x).wrapping_mul(0x9E37_79B1).rotate_left(13)
}

impl Core<'_> {
    /// A hash of a value consistent with `values_same` (the join tests' equality).
    fn value_hash(&self, v: Value) -> u32 {
        match v {
            Value::Void => 1,
            Value::Int(i) => mix(2, i as u32 ^ (i >> 32) as u32),
            Value::Float(f) => {
                let bits = if f == 0.0 { 0 } else { f.to_bits() };
                mix(3, bits as u32 ^ (bits >> 32) as u32)
            }
            Value::Sym(s) => mix(4, u32::from(s)),
            Value::Str(s) => mix(5, u32::from(s)),
            Value::Fact(r) => mix(6, r.num),
            Value::Multi(p) => {
                let mut h = mix(7, u32::from(p.len));
                for k in 0..p.len as usize {
                    h = mix(h, self.value_hash(self.mf_item(p, k)));
                }
                h
            }
        }
    }

    fn bucket(&self, alpha: u16, key: u32) -> u16 {
        (mix(key, u32::from(alpha)) as usize % self.amem_buckets.len()) as u16
    }

    /// The bucket of an alpha match of `alpha` (a node with a right hash).
    fn alpha_bucket(&mut self, alpha: u16, b: PatBinding) -> u16 {
        let (scratch, sp) = (self.st.scratch_top, self.st.sp);
        let saved = self.st.this_pm;
        self.st.this_pm = b;
        let n = self.alphas[alpha as usize];
        let mut key = 0x5bd1_e995u32;
        for &e in &n.rhash[..n.nrhash as usize] {
            let x = self.exprs[e as usize];
            // an unreadable field hashes as nothing; the join tests decide anyway
            let v = self
                .pattern_var(THIS_PATTERN, x.data, x.first)
                .unwrap_or(Value::Void);
            key = mix(key, self.value_hash(v));
        }
        self.st.this_pm = saved;
        (self.st.scratch_top, self.st.sp) = (scratch, sp);
        self.bucket(alpha, key)
    }

    /// The bucket a left token of `join` looks in (its alpha node must have a right
    /// hash), from the earlier variables the join's equality tests compare with;
    /// `lhs_pm` must hold the left token's bindings. None when a value cannot be
    /// read: then the whole memory is scanned.
    fn left_bucket(&mut self, join: u16) -> Option<u16> {
        let j = self.joins[join as usize];
        let n = self.alphas[j.alpha as usize];
        let (scratch, sp, pm) = (self.st.scratch_top, self.st.sp, self.st.pm_rhs);
        self.st.pm_rhs = false;
        let mut key = 0x5bd1_e995u32;
        let mut found = 0;
        let mut t = j.tests;
        let mut ok = true;
        while t != NONE && found < n.nrhash {
            let x = self.exprs[t as usize];
            if x.op == Op::Eq2 && x.first != NONE {
                let this = self.exprs[x.first as usize];
                let other = this.next;
                if this.op == Op::PatVar
                    && this.aux == j.depth
                    && other != NONE
                    && self.exprs[other as usize].op == Op::PatVar
                    && self.exprs[other as usize].aux != j.depth
                {
                    match self.eval(other) {
                        Ok(v) => key = mix(key, self.value_hash(v)),
                        Err(_) => ok = false,
                    }
                    found += 1;
                }
            }
            t = x.next;
        }
        (self.st.scratch_top, self.st.sp, self.st.pm_rhs) = (scratch, sp, pm);
        if !ok || found != n.nrhash {
            return None;
        }
        Some(self.bucket(j.alpha, key))
    }

    /// Adds a new alpha match (already in its node's memory) to the index.
    pub(crate) fn index_insert(&mut self, am: u16) {
        let alpha = self.tokens[am as usize].owner;
        if self.alphas[alpha as usize].nrhash == 0 {
            return;
        }
        let tk = self.tokens[am as usize];
        let b = self.alpha_bucket(
            alpha,
            PatBinding {
                fact: tk.fact,
                marks: tk.marks,
            },
        );
        let head = self.amem_buckets[b as usize];
        self.tokens[am as usize].parent = b;
        self.tokens[am as usize].am_next = NONE;
        if head == NONE {
            self.tokens[am as usize].am_prev = am;
            self.amem_buckets[b as usize] = am;
        } else {
            let tail = self.tokens[head as usize].am_prev;
            self.tokens[tail as usize].am_next = am;
            self.tokens[am as usize].am_prev = tail;
            self.tokens[head as usize].am_prev = am;
        }
    }

    /// Takes an alpha match out of the index.
    pub(crate) fn index_remove(&mut self, am: u16) {
        let tk = self.tokens[am as usize];
        if tk.kind != TokenKind::Alpha || self.alphas[tk.owner as usize].nrhash == 0 {
            return;
        }
        let b = tk.parent as usize;
        let head = self.amem_buckets[b];
        if head == am {
            self.amem_buckets[b] = tk.am_next;
            if tk.am_next != NONE {
                self.tokens[tk.am_next as usize].am_prev = tk.am_prev;
            }
        } else {
            self.tokens[tk.am_prev as usize].am_next = tk.am_next;
            if tk.am_next != NONE {
                self.tokens[tk.am_next as usize].am_prev = tk.am_prev;
            } else {
                self.tokens[head as usize].am_prev = tk.am_prev;
            }
        }
        self.tokens[am as usize].am_next = NONE;
        self.tokens[am as usize].am_prev = NONE;
        self.tokens[am as usize].parent = NONE;
    }

    /// Where a left token of alpha-fed `join` starts looking for right partners:
    /// the first match of its bucket (then `next_candidate` with `hashed`), or the
    /// whole memory. Binds the left token into `lhs_pm`.
    pub(crate) fn first_candidate(&mut self, join: u16, left: u16) -> (u16, bool) {
        let j = self.joins[join as usize];
        debug_assert!(j.kind != JoinKind::Root);
        let alpha = j.alpha;
        if self.alphas[alpha as usize].nrhash > 0 {
            self.bind_left(left);
            if let Some(b) = self.left_bucket(join) {
                let a = self.amem_buckets[b as usize];
                return (self.skip_foreign(a, alpha), true);
            }
        }
        (self.alphas[alpha as usize].mem, false)
    }

    /// The candidate after `a` (same chain kind as `first_candidate` gave).
    pub(crate) fn next_candidate(&self, a: u16, hashed: bool) -> u16 {
        if hashed {
            let alpha = self.tokens[a as usize].owner;
            self.skip_foreign(self.tokens[a as usize].am_next, alpha)
        } else {
            self.tokens[a as usize].mem_next
        }
    }

    /// Skips bucket entries of other alpha nodes.
    fn skip_foreign(&self, mut a: u16, alpha: u16) -> u16 {
        while a != NONE && self.tokens[a as usize].owner != alpha {
            a = self.tokens[a as usize].am_next;
        }
        a
    }
}
