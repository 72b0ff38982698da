//! Host: constant-test discrimination of a template's alpha nodes.
//!
//! Without it a new fact is tested against every alpha node of its template, one by one:
//! a rule base with many patterns that differ only in the constant a slot must equal
//! (`(state IDLE)`, `(state BUSY)`, ...) pays for each of them on every assert. Here the
//! nodes whose first test compares a slot with a constant are kept in hash buckets keyed
//! by (template, slot, constant) when the template's nodes compare that slot with at
//! least [`KEY_MIN`] distinct constants: a fact then visits the template's other ("plain") nodes plus, for each
//! keyed slot, only the nodes whose constant it holds. Skipped nodes are exactly those
//! whose first test would be false, so no alpha match changes; the nodes visited are
//! merged by their position in the template's list, so facts still reach alpha nodes in
//! CLIPS's pattern-network order (which decides the activation order).
//!
//! The index is rebuilt lazily, on the first assert after the network changed
//! (`MatchState::net_gen`) or was cleared, from the templates' alpha lists.

use crate::engine::Core;
use crate::expr::{loc, Op};
use crate::rete::THIS_PATTERN;
use crate::value::{Ix, Value, NONE};

/// Distinct constants the nodes of a template must compare the same slot with before it
/// is keyed: below that, the hash lookup costs more than the tests it saves.
pub const KEY_MIN: usize = 4;
/// Keyed slots per template (further ones are left plain).
pub const MAX_KEYED: usize = 6;
/// Distinct slots counted per template while choosing which to key.
const MAX_COUNTED: usize = 16;
/// A locator of the first field of a multislot (an ordered fact's first field) rather
/// than of a single-field slot; the low bits are the slot index.
const FIRST_OF_MULTI: u16 = 0x8000;
/// No locator: a plain node.
const NO_LOC: u16 = 0xFFFF;

/// Per alpha node (by id): its key, its place in its template's list, its link in its
/// bucket (keyed) or its template's plain chain; and, by bucket number, a bucket's
/// first and last node.
#[derive(Clone, Copy, Debug)]
pub struct AlphaDisc {
    key: Value,
    loc: u16,
    rank: Ix,
    next: Ix,
    head: Ix,
    tail: Ix,
}

impl AlphaDisc {
    pub const EMPTY: AlphaDisc = AlphaDisc {
        key: Value::Void,
        loc: NO_LOC,
        rank: 0,
        next: NONE,
        head: NONE,
        tail: NONE,
    };
}

/// Per template: its first plain node and its keyed slot locators.
#[derive(Clone, Copy, Debug)]
pub struct TemplateDisc {
    plain: Ix,
    nkeyed: u8,
    locs: [u16; MAX_KEYED],
}

impl TemplateDisc {
    pub const EMPTY: TemplateDisc = TemplateDisc {
        plain: NONE,
        nkeyed: 0,
        locs: [NO_LOC; MAX_KEYED],
    };
}

/// What the index was built for, kept in `MatchState` (so `clear` forgets it).
#[derive(Clone, Copy, Debug)]
pub struct DiscState {
    /// The network generation it was built for; None: not built.
    pub net_gen: Option<u32>,
    /// Templates that existed then (younger ones take the unindexed path).
    pub ntemplates: Ix,
    /// Buckets in use (a power of two).
    pub nbuckets: usize,
    /// Whether some alpha node chooses a multifield's length (with feature `grow`
    /// the asserts of its template go in CLIPS's multifield order; when none does,
    /// as in most networks, an assert asks only this).
    pub mf_any: bool,
}

impl DiscState {
    pub const EMPTY: DiscState = DiscState {
        net_gen: None,
        ntemplates: 0,
        nbuckets: 0,
        mf_any: true,
    };
}

/// The bucket of a key.
#[inline(always)]
fn bucket(tmpl: Ix, loc: u16, v: Value, nbuckets: usize) -> usize {
    let bits: u64 = match v {
        Value::Sym(s) => s as u64 | 1 << 40,
        Value::Str(s) => s as u64 | 2 << 40,
        Value::Int(i) => i as u64 ^ 3 << 40,
        _ => 0,
    };
    let mut h = bits
        ^ (tmpl as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (loc as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h ^= h >> 29;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 32;
    h as usize & (nbuckets - 1)
}

impl Core<'_> {
    /// The alpha nodes of `fact`'s template that it can match, in list order, through
    /// `visit`; false when the fact must take the unindexed walk (template not indexed,
    /// or a keyed field it holds that the quick path would not read).
    #[inline(always)]
    pub(crate) fn for_discriminated_alphas<F>(
        &mut self,
        fact: Ix,
        mut visit: F,
    ) -> Result<bool, crate::error::EvalError>
    where
        F: FnMut(&mut Self, Ix) -> Result<(), crate::error::EvalError>,
    {
        // (`network_assert` made the index current)
        debug_assert!(self.st.net.disc.net_gen == Some(self.st.net.net_gen));
        let tmpl = self.facts[fact as usize].tmpl;
        if tmpl >= self.st.net.disc.ntemplates {
            return Ok(false);
        }
        let td = self.tmpl_disc[tmpl as usize];
        if td.nkeyed == 0 {
            return Ok(false);
        }
        let nbuckets = self.st.net.disc.nbuckets;
        // cursor 0: the plain chain; cursor k + 1: keyed slot k's bucket chain
        let mut cur = [NONE; MAX_KEYED + 1];
        let mut keys = [Value::Void; MAX_KEYED + 1];
        cur[0] = td.plain;
        let n = td.nkeyed as usize;
        for k in 0..n {
            let Some(v) = self.disc_field(fact, td.locs[k]) else {
                return Ok(false);
            };
            keys[k + 1] = v;
            let head = self.alpha_disc[bucket(tmpl, td.locs[k], v, nbuckets)].head;
            cur[k + 1] = self.next_keyed(head, tmpl, td.locs[k], v);
        }
        loop {
            let mut best = usize::MAX;
            let mut best_rank = Ix::MAX;
            for (i, &a) in cur[..=n].iter().enumerate() {
                if a != NONE && self.alpha_disc[a as usize].rank < best_rank {
                    best_rank = self.alpha_disc[a as usize].rank;
                    best = i;
                }
            }
            if best == usize::MAX {
                return Ok(true);
            }
            let a = cur[best];
            let next = self.alpha_disc[a as usize].next;
            cur[best] = if best == 0 {
                next
            } else {
                self.next_keyed(next, tmpl, td.locs[best - 1], keys[best])
            };
            visit(self, a)?;
        }
    }

    /// The first node from `a` on in its bucket chain with this key.
    #[inline(always)]
    fn next_keyed(&self, mut a: Ix, tmpl: Ix, loc: u16, v: Value) -> Ix {
        while a != NONE {
            let d = &self.alpha_disc[a as usize];
            if d.loc == loc && self.alphas[a as usize].tmpl == tmpl && d.key.same(v) {
                return a;
            }
            a = d.next;
        }
        NONE
    }

    /// The field a locator names in `fact`, as the quick path reads it (None where it
    /// would leave the test to the evaluator).
    #[inline(always)]
    fn disc_field(&self, fact: Ix, loc: u16) -> Option<Value> {
        let slot = Ix::from(loc & !FIRST_OF_MULTI);
        if loc & FIRST_OF_MULTI == 0 {
            return self.plain_slot(fact, slot);
        }
        match self.slot_cell(fact, slot) {
            (cell, Some(len)) if len > 0 => match self.values[cell + 1] {
                Value::Multi(_) => None,
                v => Some(v),
            },
            _ => None,
        }
    }

    /// The locator and constant of node `a`'s first test when it is a field equal to a
    /// symbol, string or integer that the quick path reads (`quick_first_test`).
    fn disc_key(&self, a: Ix) -> Option<(u16, Value)> {
        let node = &self.alphas[a as usize];
        let t = node.tests;
        if t == NONE || !node.live {
            return None;
        }
        let x = self.exprs[t as usize];
        if x.op != Op::Eq2 || x.first == NONE {
            return None;
        }
        let pv = self.exprs[x.first as usize];
        if pv.next == NONE {
            return None;
        }
        let c = self.exprs[pv.next as usize];
        if c.next != NONE || !matches!(c.op, Op::Sym | Op::Str | Op::Int) {
            return None;
        }
        if pv.op != Op::PatVar || pv.aux != THIS_PATTERN || pv.data == loc::FACT {
            return None;
        }
        let slot = loc::slot(pv.data) as u16;
        if Ix::from(slot) >= self.templates[node.tmpl as usize].nslots || slot >= FIRST_OF_MULTI {
            return None;
        }
        let elem = loc::elem(pv.data);
        let at = if elem == loc::SINGLE && pv.first == NONE {
            slot
        } else if elem == 0 && pv.first != NONE {
            // the multislot's first element, when the pattern's first element is a
            // single field (so it sits at offset 0)
            let pe = self.exprs[pv.first as usize].first;
            if pe == NONE || self.exprs[pe as usize].aux == 1 {
                return None;
            }
            slot | FIRST_OF_MULTI
        } else {
            return None;
        };
        Some((at, self.const_value(pv.next)))
    }

    /// Whether a node before `a` in template `t`'s list has key (`at`, `key`).
    fn earlier_has_key(&self, t: Ix, a: Ix, at: u16, key: Value) -> bool {
        let mut o = self.templates[t as usize].alpha_head;
        while o != a && o != NONE {
            let d = &self.alpha_disc[o as usize];
            if d.loc == at && d.key.same(key) {
                return true;
            }
            o = self.alphas[o as usize].next_in_tmpl;
        }
        false
    }

    /// Builds the index from the templates' alpha lists.
    #[cold]
    #[inline(never)]
    pub(crate) fn rebuild_discrimination(&mut self) {
        let nalpha = self.st.pools.nalpha as usize;
        let mf_any = self.alphas.iter().take(nalpha).any(|a| a.nmarks > 0);
        let ntemplates = self.st.pools.ntemplates;
        let cap = self.alpha_disc.len();
        let mut nbuckets = 1usize;
        while nbuckets * 2 <= cap && nbuckets < (2 * nalpha).max(64) {
            nbuckets *= 2;
        }
        let nbuckets = nbuckets.min(cap);
        self.st.net.disc = DiscState {
            net_gen: Some(self.st.net.net_gen),
            ntemplates: 0,
            nbuckets,
            mf_any,
        };
        if nbuckets == 0 {
            return;
        }
        for d in self.alpha_disc[..nalpha.max(nbuckets).min(cap)].iter_mut() {
            *d = AlphaDisc::EMPTY;
        }
        let ntemplates = ntemplates.min(self.tmpl_disc.len() as Ix);
        for t in 0..ntemplates {
            self.tmpl_disc[t as usize] = self.template_discrimination(t, nbuckets);
        }
        self.st.net.disc.ntemplates = ntemplates;
    }

    /// Ranks template `t`'s alpha nodes, picks its keyed slots and links its nodes into
    /// their buckets and its plain chain.
    fn template_discrimination(&mut self, t: Ix, nbuckets: usize) -> TemplateDisc {
        let mut counted = [(NO_LOC, 0usize); MAX_COUNTED];
        let mut a = self.templates[t as usize].alpha_head;
        let mut rank: Ix = 0;
        while a != NONE {
            self.alpha_disc[a as usize].rank = rank;
            rank = rank.saturating_add(1);
            if let Some((at, key)) = self.disc_key(a) {
                self.alpha_disc[a as usize].loc = at;
                self.alpha_disc[a as usize].key = key;
                // distinct constants count: nodes that all want the same one gain
                // nothing from a lookup
                if let Some(i) = counted.iter().position(|c| c.0 == at || c.0 == NO_LOC) {
                    // (only whether a slot reaches KEY_MIN matters: past it, no walk
                    // over the earlier nodes, which made this quadratic in them)
                    let new_key = counted[i].1 < KEY_MIN && !self.earlier_has_key(t, a, at, key);
                    counted[i] = (at, counted[i].1 + usize::from(new_key));
                }
            }
            a = self.alphas[a as usize].next_in_tmpl;
        }
        let mut td = TemplateDisc::EMPTY;
        for &(at, n) in counted.iter() {
            if at != NO_LOC && n >= KEY_MIN && (td.nkeyed as usize) < MAX_KEYED {
                td.locs[td.nkeyed as usize] = at;
                td.nkeyed += 1;
            }
        }
        let mut plain_tail = NONE;
        let mut a = self.templates[t as usize].alpha_head;
        while a != NONE {
            let at = self.alpha_disc[a as usize].loc;
            let keyed = at != NO_LOC && td.locs[..td.nkeyed as usize].contains(&at);
            if keyed {
                let b = bucket(t, at, self.alpha_disc[a as usize].key, nbuckets);
                match self.alpha_disc[b].tail {
                    NONE => self.alpha_disc[b].head = a,
                    last => self.alpha_disc[last as usize].next = a,
                }
                self.alpha_disc[b].tail = a;
            } else {
                self.alpha_disc[a as usize].loc = NO_LOC;
                match plain_tail {
                    NONE => td.plain = a,
                    last => self.alpha_disc[last as usize].next = a,
                }
                plain_tail = a;
            }
            a = self.alphas[a as usize].next_in_tmpl;
        }
        td
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::host::NullHost;
    use crate::value::Value;
    use std::boxed::Box;

    /// Slots compared with enough distinct constants are keyed, others not; a fact
    /// fires exactly the rules whose constants it holds (and the plain ones), and the
    /// index follows rules added after it was built.
    #[test]
    fn keyed_slots_are_chosen_and_facts_reach_their_rules() {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(defglobal ?*fired* = 0)
             (deftemplate p (slot a) (slot b) (slot c))
             (defrule a1 (p (a 1)) => (bind ?*fired* (+ ?*fired* 1)))
             (defrule a2 (p (a 2)) => (bind ?*fired* (+ ?*fired* 10)))
             (defrule a3 (p (a x)) => (bind ?*fired* (+ ?*fired* 100)))
             (defrule a4 (p (a \"x\")) => (bind ?*fired* (+ ?*fired* 1000)))
             (defrule b1 (p (b same)) => (bind ?*fired* (+ ?*fired* 10000)))
             (defrule b2 (p (b same) (c 1)) => (bind ?*fired* (+ ?*fired* 100000)))
             (defrule b3 (p (b same) (c 2)) =>)
             (defrule b4 (p (b same) (c 3)) =>)
             (defrule any (p (c ?c&:(> ?c 0))) => (bind ?*fired* (+ ?*fired* 1000000)))",
        )
        .unwrap();
        e.assert_str(h, "(p (a x) (b same) (c 1))").unwrap();
        {
            let c = e.core(h);
            // the template of the rules' patterns
            let td = c.tmpl_disc[c.alphas[0].tmpl as usize];
            // slot a: four distinct constants; slot b: four nodes, one constant
            assert_eq!(td.nkeyed, 1);
            assert_eq!(td.locs[0], 0);
        }
        e.run(h, None).unwrap();
        let fired = e.eval_str(h, "?*fired*").unwrap();
        assert_eq!(fired, Value::Int(1_110_100));
        e.load_str(h, "t2", "(defrule a5 (p (a 5)) => (bind ?*fired* 5))")
            .unwrap();
        e.assert_str(h, "(p (a 5) (b other) (c 0))").unwrap();
        e.run(h, None).unwrap();
        assert_eq!(e.eval_str(h, "?*fired*").unwrap(), Value::Int(5));
    }
}
