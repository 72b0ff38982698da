//! Host (feature `grow`): the order in which one new fact's alpha matches enter the
//! network when patterns share a multifield node, as CLIPS 6.30 does.
//!
//! CLIPS's pattern network tests a fact field by field, depth first (newer sibling
//! nodes first, `compile::alpha`). At a multifield node (a `$?` among several in a
//! slot) it tries each length, longest first, and for each length runs the whole
//! subtree below it (every pattern sharing the node) before the next length. So
//! `(p $? a $?)` and `(p $? b $?)` on `(p b a)` match with the first `$?` of length 1
//! (`a`'s pattern) before length 0 (`b`'s), whatever order the rules came in. Our
//! alpha nodes are whole patterns, each trying its own segmentations: while a node of
//! the fact's template has such a choice, the fact's matches are collected, sorted
//! into CLIPS's order (path level by level: the newer node first, then at a choice
//! level the longer length first; a path before its extensions), then added.

use alloc::vec::Vec;
use core::cmp::Ordering;

use super::{MAX_MARKS, PATH_LEN};
use crate::engine::Core;
use crate::error::EvalError;
use crate::expr::loc;
use crate::value::{Ix, NONE};

/// One alpha match waiting to be added: the node and the multifield lengths.
type Pending = (Ix, [u8; MAX_MARKS]);

/// The collected matches and which templates need collecting (`MatchState::mf`).
pub struct MfOrder {
    /// `Some` while a fact's matches are being collected.
    pub pending: Option<Vec<Pending>>,
    /// `pending.is_some()`, kept beside it: the check every alpha match makes
    /// (`match_one`) is then one byte compared.
    pub collecting: bool,
    /// Per template: the network generation last checked (+1; 0 never) and whether
    /// one of its alpha nodes has a multifield choice.
    choice: Vec<(u32, bool)>,
}

impl MfOrder {
    pub const fn new() -> MfOrder {
        MfOrder {
            pending: None,
            collecting: false,
            choice: Vec::new(),
        }
    }
}

impl Default for MfOrder {
    fn default() -> Self {
        Self::new()
    }
}

impl Core<'_> {
    /// Whether template `tmpl`'s matches need CLIPS's multifield order (one of its
    /// alpha nodes chooses a multifield's length).
    /// (The cached answer in line: every assert asks.)
    #[inline(always)]
    pub(crate) fn needs_mf_order(&mut self, tmpl: Ix) -> bool {
        // host: no alpha node chooses a multifield's length (most networks): one test
        // (`network_assert` made the discrimination index current)
        #[cfg(feature = "host-speedups")]
        if !self.st.net.disc.mf_any {
            return false;
        }
        let gen = self.st.net.net_gen.wrapping_add(1).max(1);
        if let Some(&(g, c)) = self.st.net.mf.choice.get(tmpl as usize) {
            if g == gen {
                return c;
            }
        }
        self.find_mf_order(tmpl, gen)
    }

    /// `needs_mf_order` once per template and network generation `gen`.
    #[cold]
    #[inline(never)]
    fn find_mf_order(&mut self, tmpl: Ix, gen: u32) -> bool {
        let t = tmpl as usize;
        let mut c = false;
        let mut a = self.templates[t].alpha_head;
        while a != NONE {
            c |= self.alphas[a as usize].nmarks > 0;
            a = self.alphas[a as usize].next_in_tmpl;
        }
        let v = &mut self.st.net.mf.choice;
        if v.len() <= t {
            v.resize(t + 1, (0, false));
        }
        v[t] = (gen, c);
        c
    }

    /// `visit` (which tests the fact against its template's alpha nodes) with the
    /// matches collected, then added in CLIPS's order.
    pub(crate) fn assert_in_mf_order(
        &mut self,
        fact: Ix,
        visit: impl FnOnce(&mut Self) -> Result<(), EvalError>,
    ) -> Result<(), EvalError> {
        // (a pattern test that asserts nests another collection: each keeps its own)
        let outer = self.st.net.mf.pending.replace(Vec::new());
        self.st.net.mf.collecting = true;
        let r = visit(self);
        let mut got = core::mem::replace(&mut self.st.net.mf.pending, outer).unwrap_or_default();
        self.st.net.mf.collecting = self.st.net.mf.pending.is_some();
        r?;
        if got.len() > 1 {
            // a node's matches come one after another (its segmentations): its choice
            // levels are worked out once for them
            let mut keyed: Vec<[Option<u8>; PATH_LEN]> = Vec::with_capacity(got.len());
            let mut last = (NONE, [None; PATH_LEN]);
            for &(a, _) in &got {
                if a != last.0 {
                    last = (a, self.choice_levels(a));
                }
                keyed.push(last.1);
            }
            let mut idx: Vec<usize> = (0..got.len()).collect();
            idx.sort_by(|&i, &j| self.mf_cmp(got[i], &keyed[i], got[j], &keyed[j]));
            let sorted: Vec<Pending> = idx.iter().map(|&i| got[i]).collect();
            got = sorted;
        }
        for (a, marks) in got {
            self.add_alpha_match(a, fact, marks)?;
        }
        Ok(())
    }

    /// CLIPS's order of two alpha matches (see the module docs).
    fn mf_cmp(
        &self,
        (a, ma): Pending,
        ca: &[Option<u8>; PATH_LEN],
        (b, mb): Pending,
        cb: &[Option<u8>; PATH_LEN],
    ) -> Ordering {
        let (x, y) = (&self.alphas[a as usize], &self.alphas[b as usize]);
        let (lx, ly) = (x.key_len as usize, y.key_len as usize);
        for l in 0..lx.min(ly) {
            if x.key[l] != y.key[l] {
                // the newer node (higher id) first
                return y.key[l].cmp(&x.key[l]);
            }
            if let (Some(i), Some(j)) = (ca[l], cb[l]) {
                let (p, q) = (ma[i as usize], mb[j as usize]);
                if p != q {
                    // the longer multifield first
                    return q.cmp(&p);
                }
            }
        }
        lx.cmp(&ly)
    }

    /// For each level of alpha node `a`'s path: the mark holding the length its
    /// multifield node chooses (a `$?` before the last one of its slot), if any.
    fn choice_levels(&self, a: Ix) -> [Option<u8>; PATH_LEN] {
        let node = self.alphas[a as usize];
        let mut out = [None; PATH_LEN];
        for (l, o) in out.iter_mut().enumerate().take(node.key_len as usize) {
            let at = node.path_loc[l];
            let (slot, elem) = (Ix::from(loc::slot(at)), loc::elem(at));
            // marks are given slot by slot, each slot with several multifields
            // taking one less than it has
            let mut first = 0u8;
            let mut s = node.desc;
            while s != NONE {
                let sd = self.exprs[s as usize];
                let (mut multis, mut ord, mut is_multi) = (0u8, None, false);
                let mut e = sd.first;
                let mut k = 0u8;
                while e != NONE {
                    let x = self.exprs[e as usize];
                    if sd.data == slot && k == elem {
                        is_multi = x.aux == 1;
                        ord = Some(multis);
                    }
                    multis += u8::from(x.aux == 1);
                    k = k.wrapping_add(1);
                    e = x.next;
                }
                if let (Some(j), true) = (ord, is_multi) {
                    if j + 1 < multis {
                        *o = Some(first + j);
                    }
                    break;
                }
                if multis >= 2 {
                    first += multis - 1;
                }
                s = sd.next;
            }
        }
        out
    }
}
