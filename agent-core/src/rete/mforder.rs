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
//!
//! The order is a lexicographic one over a few small numbers per match, so each match
//! gets it as one integer (`NodeKey`): the node's place among its template's nodes
//! level by level, and at a choice level its length, longer first. Sorting compares
//! integers, and a fact whose matches came in order (often: one node, or nodes whose
//! matches do not interleave) is only checked. `mf_cmp` decides where the integer
//! cannot (a template with more nodes than a level's field holds, or nodes sharing
//! a path level where one chooses a length and the other does not).

use alloc::vec::Vec;
use core::cmp::Ordering;

use super::{MAX_MARKS, PATH_LEN};
use crate::engine::Core;
use crate::error::EvalError;
use crate::expr::loc;
use crate::value::{Ix, NONE};

/// One alpha match waiting to be added: the node and the multifield lengths. (Kept
/// small: every collected match is one; order keys are made only for a sort.)
type Pending = (Ix, [u8; MAX_MARKS]);

/// Bits of one path level in an order key: the node's place among its template's
/// nodes sharing the path up to the level (`PLACE_BITS`, +1: 0 is "no such level",
/// which puts a path before its extensions), then the level's multifield length,
/// inverted (longer first), at a choice level. `PATH_LEN` levels fit in 128 bits.
const PLACE_BITS: u32 = 13;
const LEVEL_BITS: u32 = PLACE_BITS + 8;
const _: () = assert!(PATH_LEN as u32 * LEVEL_BITS <= 128);

/// A node's part of its matches' order keys, for one network generation.
#[derive(Clone, Copy)]
struct NodeKey {
    /// The places, level by level.
    base: u128,
    /// Per choice level: the mark holding its length and the level's shift.
    marks: [(u8, u8); PATH_LEN],
    n: u8,
    /// The node's segmentations come in key order: its choice levels' marks are
    /// its first marks, in order (`enumerate_marks` tries marks in index order,
    /// each longest first, so their lengths fall lexicographically).
    mono: bool,
}

impl NodeKey {
    const EMPTY: NodeKey = NodeKey {
        base: 0,
        marks: [(0, 0); PATH_LEN],
        n: 0,
        mono: true,
    };

    /// The order key of the node's match with `marks`.
    #[inline(always)]
    fn key(&self, marks: &[u8; MAX_MARKS]) -> u128 {
        let mut k = self.base;
        for &(i, shift) in &self.marks[..self.n as usize] {
            k |= u128::from(255 - marks[i as usize & (MAX_MARKS - 1)]) << shift;
        }
        k
    }
}

/// The collected matches and which templates need collecting (`MatchState::mf`).
pub struct MfOrder {
    /// `Some` while a fact's matches are being collected.
    pub pending: Option<Vec<Pending>>,
    /// `pending.is_some()`, kept beside it: the check every alpha match makes
    /// (`match_one`) is then one byte compared.
    pub collecting: bool,
    /// An emptied collection kept for the next fact, so collecting does not
    /// allocate (and regrow) a vector per fact.
    spare: Vec<Pending>,
    /// Per alpha node: the network generation (+1; 0 never) its `choice_levels`
    /// were worked out in, and them (they cost a walk of the pattern's slots).
    levels: Vec<(u32, [Option<u8>; PATH_LEN])>,
    /// Per alpha node: the network generation (+1) `mono` was worked out in and
    /// whether its segmentations come in CLIPS's order (`NodeKey::mono`): a fact
    /// matching one node only (the usual case) then needs neither keys nor a check.
    mono: Vec<(u32, bool)>,
    /// Storage kept for `make_node_keys`' node list and a sort's keyed matches, so
    /// neither allocates per template or fact.
    nodes: Vec<Ix>,
    keyed_got: Vec<(u128, Pending)>,
    /// Per alpha node: the network generation (+1) its `NodeKey` was made in, and it.
    keys: Vec<(u32, NodeKey)>,
    /// Per template: the network generation (+1) its nodes' keys were made in, and
    /// whether they order its matches (else `mf_cmp` does).
    keyed: Vec<(u32, bool)>,
    /// Per template: the network generation last checked (+1; 0 never) and whether
    /// one of its alpha nodes has a multifield choice.
    choice: Vec<(u32, bool)>,
}

impl MfOrder {
    pub const fn new() -> MfOrder {
        MfOrder {
            pending: None,
            collecting: false,
            spare: Vec::new(),
            levels: Vec::new(),
            mono: Vec::new(),
            nodes: Vec::new(),
            keyed_got: Vec::new(),
            keys: Vec::new(),
            keyed: Vec::new(),
            choice: Vec::new(),
        }
    }
}

impl Default for MfOrder {
    fn default() -> Self {
        Self::new()
    }
}

/// Entry `i` of a per-generation cache (`MfOrder`'s per-node and per-template
/// vectors) when it was made in network generation `gen` (+1).
#[inline(always)]
fn gen_cached<T: Copy>(v: &[(u32, T)], i: usize, gen: u32) -> Option<T> {
    match v.get(i) {
        Some(&(g, x)) if g == gen => Some(x),
        _ => None,
    }
}

/// Makes entry `i` of a per-generation cache `x`, made in generation `gen` (+1); the
/// vector grows with entries of no generation (`empty`) to reach it.
fn gen_store<T: Copy>(v: &mut Vec<(u32, T)>, i: usize, gen: u32, x: T, empty: T) {
    if v.len() <= i {
        v.resize(i + 1, (0, empty));
    }
    v[i] = (gen, x);
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
        if let Some(c) = gen_cached(&self.st.net.mf.choice, tmpl as usize, gen) {
            return c;
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
        gen_store(&mut self.st.net.mf.choice, t, gen, c, false);
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
        let fresh = core::mem::take(&mut self.st.net.mf.spare);
        let outer = self.st.net.mf.pending.replace(fresh);
        self.st.net.mf.collecting = true;
        let r = visit(self);
        let mut got = core::mem::replace(&mut self.st.net.mf.pending, outer).unwrap_or_default();
        self.st.net.mf.collecting = self.st.net.mf.pending.is_some();
        r?;
        if got.len() > 1 {
            self.put_in_mf_order(&mut got);
        }
        for &(a, marks) in &got {
            self.add_alpha_match(a, fact, marks)?;
        }
        got.clear();
        self.st.net.mf.spare = got;
        Ok(())
    }

    /// Whether `got` (2 or more matches) are all one node's and already in CLIPS's
    /// order, so sorting would keep them as they are: a node's segmentations come
    /// longer leading multifields first (`enumerate_marks`), the order `mf_cmp` asks
    /// for, so one pattern with several `$?` (the usual case) needs no sort.
    fn one_node_in_order(&self, got: &[Pending]) -> bool {
        let a = got[0].0;
        if got.iter().any(|&(b, _)| b != a) {
            return false;
        }
        // the marks compared, level by level (`mf_cmp` with equal keys)
        let levels = self.st.net.mf.levels[a as usize].1;
        let n = self.alphas[a as usize].key_len as usize;
        got.windows(2).all(|w| {
            for &i in levels[..n].iter().flatten() {
                let (p, q) = (w[0].1[i as usize], w[1].1[i as usize]);
                if p != q {
                    return p > q;
                }
            }
            true
        })
    }

    /// Puts a fact's matches `got` (2 or more) in CLIPS's order. (Out of line: the
    /// loop adding them takes the successor joins' walks in line, whose code is
    /// the hot one and must not pay for this.)
    #[inline(never)]
    fn put_in_mf_order(&mut self, got: &mut [Pending]) {
        // one node's matches only: in order when its choice levels read its first
        // marks in order (no keys needed, so a template whose facts each match one
        // node never makes them)
        // (a node's matches lie together, so several nodes' are told at the ends
        // without a walk over the first node's)
        let a = got[0].0;
        if got[got.len() - 1].0 == a && got.iter().all(|&(b, _)| b == a) && self.node_mono(a) {
            return;
        }
        if self.order_by_keys(got) {
            return;
        }
        // a node's matches come one after another (its segmentations): its choice
        // levels are looked up once for them
        let mut last = NONE;
        for &(a, _) in got.iter() {
            if a != last {
                self.cache_choice_levels(a);
                last = a;
            }
        }
        if !self.one_node_in_order(got) {
            let lv = &self.st.net.mf.levels;
            got.sort_by(|x, y| self.mf_cmp(*x, &lv[x.0 as usize].1, *y, &lv[y.0 as usize].1));
        }
    }

    /// Host: before a pattern test of alpha node `x` fails on `fact` with an error
    /// (`failed_test`, under lengths `mx`) while the fact's matches are collected:
    /// the collected matches CLIPS's network reaches before that test's node enter
    /// now, in its order, as CLIPS reports the error when it gets there; the others
    /// stay collected.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    pub(crate) fn matches_before_error(
        &mut self,
        x: Ix,
        fact: Ix,
        mx: [u8; MAX_MARKS],
    ) -> Result<(), EvalError> {
        if !self.st.net.mf.collecting {
            return Ok(());
        }
        let Some(level) = self.test_level(x, self.st.net.failed_test) else {
            return Ok(());
        };
        let Some(p) = self.st.net.mf.pending.as_mut() else {
            return Ok(());
        };
        if p.is_empty() {
            return Ok(());
        }
        let mut got = core::mem::take(p);
        if got.len() > 1 {
            self.put_in_mf_order(&mut got);
        }
        self.cache_choice_levels(x);
        for &(a, _) in &got {
            self.cache_choice_levels(a);
        }
        let lv = &self.st.net.mf.levels;
        let cx = lv[x as usize].1;
        let k = got
            .iter()
            .position(|&m| !self.mf_before(m, &lv[m.0 as usize].1, x, &mx, &cx, level))
            .unwrap_or(got.len());
        let rest = got.split_off(k);
        if let Some(p) = self.st.net.mf.pending.as_mut() {
            *p = rest;
        }
        for &(a, marks) in &got {
            self.add_alpha_match(a, fact, marks)?;
        }
        Ok(())
    }

    /// Host: whether CLIPS's network reaches alpha match `(a, ma)` (choice levels
    /// `ca`) before it tests level `level` of node `x`'s path with lengths `mx`
    /// (choice levels `cx`): `mf_cmp` up to that level.
    #[cfg(feature = "extras")]
    fn mf_before(
        &self,
        (a, ma): Pending,
        ca: &[Option<u8>; PATH_LEN],
        x: Ix,
        mx: &[u8; MAX_MARKS],
        cx: &[Option<u8>; PATH_LEN],
        level: usize,
    ) -> bool {
        let (p, q) = (&self.alphas[a as usize], &self.alphas[x as usize]);
        for l in 0..=level.min(PATH_LEN - 1) {
            if l >= p.key_len as usize {
                // a's path ends above the level: its match comes at its last node
                return true;
            }
            if l >= q.key_len as usize {
                return false;
            }
            if p.key[l] != q.key[l] {
                // the newer node first
                return p.key[l] > q.key[l];
            }
            if let (Some(i), Some(j)) = (ca[l], cx[l]) {
                let (u, v) = (ma.get(i as usize), mx.get(j as usize));
                if u != v {
                    // the longer multifield first
                    return u > v;
                }
            }
        }
        false
    }

    /// Whether alpha node `a`'s segmentations come in CLIPS's order (`NodeKey::mono`),
    /// cached per network generation.
    fn node_mono(&mut self, a: Ix) -> bool {
        // one mark (the usual `$? x $?`): its only choice level reads mark 0, so
        // no walk of the pattern's slots is needed
        if self.alphas[a as usize].nmarks <= 1 {
            return true;
        }
        let gen = self.st.net.net_gen.wrapping_add(1).max(1);
        if let Some(m) = gen_cached(&self.st.net.mf.mono, a as usize, gen) {
            return m;
        }
        self.find_node_mono(a, gen)
    }

    #[cold]
    #[inline(never)]
    fn find_node_mono(&mut self, a: Ix, gen: u32) -> bool {
        let mut mono = true;
        for (m, n) in self.choice_levels(a).iter().flatten().zip(0u8..) {
            mono &= *m == n;
        }
        gen_store(&mut self.st.net.mf.mono, a as usize, gen, mono, false);
        mono
    }

    /// Puts `got` (2 or more matches of one fact) in CLIPS's order by their order
    /// keys: false, `got` unchanged, where the keys cannot tell (`NodeKey`).
    fn order_by_keys(&mut self, got: &mut [Pending]) -> bool {
        let tmpl = self.alphas[got[0].0 as usize].tmpl;
        let gen = self.st.net.net_gen.wrapping_add(1).max(1);
        let ok = match gen_cached(&self.st.net.mf.keyed, tmpl as usize, gen) {
            Some(ok) => ok,
            None => self.make_node_keys(tmpl, gen),
        };
        if !ok {
            return false;
        }
        // a node's matches come one after another (its segmentations): its key is
        // read once for them; when they come in key order (`NodeKey::mono`) only
        // the ends of its run are compared with the neighbouring runs
        let keys = &self.st.net.mf.keys;
        let (mut prev, mut sorted, mut i) = (0u128, true, 0);
        while sorted && i < got.len() {
            let a = got[i].0;
            let nk = keys[a as usize].1;
            let mut j = i + 1;
            while j < got.len() && got[j].0 == a {
                j += 1;
            }
            if nk.mono {
                let first = nk.key(&got[i].1);
                sorted = prev <= first;
                prev = nk.key(&got[j - 1].1);
            } else {
                for p in &got[i..j] {
                    let k = nk.key(&p.1);
                    sorted &= prev <= k;
                    prev = k;
                }
            }
            i = j;
        }
        if !sorted {
            let mut kg = core::mem::take(&mut self.st.net.mf.keyed_got);
            let keys = &self.st.net.mf.keys;
            let mut last = NONE;
            let mut nk = NodeKey::EMPTY;
            kg.clear();
            for &p in got.iter() {
                if p.0 != last {
                    last = p.0;
                    nk = keys[last as usize].1;
                }
                kg.push((nk.key(&p.1), p));
            }
            // stable: matches of nodes on one CLIPS node keep the order they came in
            kg.sort_by_key(|p| p.0);
            for (g, k) in got.iter_mut().zip(&kg) {
                *g = k.1;
            }
            self.st.net.mf.keyed_got = kg;
        }
        true
    }

    /// Makes the `NodeKey`s of template `tmpl`'s alpha nodes for network generation
    /// `gen`; whether they order its matches. (Once per template and network.)
    #[cold]
    #[inline(never)]
    fn make_node_keys(&mut self, tmpl: Ix, gen: u32) -> bool {
        let mut nodes = core::mem::take(&mut self.st.net.mf.nodes);
        nodes.clear();
        let mut a = self.templates[tmpl as usize].alpha_head;
        while a != NONE {
            nodes.push(a);
            a = self.alphas[a as usize].next_in_tmpl;
        }
        // CLIPS's order of the nodes' paths (`mf_cmp` on equal marks): level by
        // level the newer network node first, a path before its extensions; the
        // nodes sharing a path up to a level then lie together
        nodes.sort_by(|&x, &y| {
            let (x, y) = (&self.alphas[x as usize], &self.alphas[y as usize]);
            let (lx, ly) = (x.key_len as usize, y.key_len as usize);
            for l in 0..lx.min(ly) {
                if x.key[l] != y.key[l] {
                    return y.key[l].cmp(&x.key[l]);
                }
            }
            lx.cmp(&ly)
        });
        let mut ok = nodes.len() < (1 << PLACE_BITS) - 1;
        let mut places = [0u32; PATH_LEN];
        let mut prev: Option<(Ix, [Option<u8>; PATH_LEN])> = None;
        for (i, &a) in nodes.iter().enumerate() {
            if !ok {
                break;
            }
            let node = self.alphas[a as usize];
            // (a node without marks chooses no length: its slots are not walked)
            let choice = if node.nmarks == 0 {
                [None; PATH_LEN]
            } else {
                self.choice_levels(a)
            };
            let mut nk = NodeKey::EMPTY;
            let n = (node.key_len as usize).min(PATH_LEN);
            for l in 0..n {
                // the place of the first node sharing the path up to this level
                let shared = prev.and_then(|(p, pc)| {
                    let o = &self.alphas[p as usize];
                    (o.key_len as usize > l && o.key[..=l] == node.key[..=l]).then_some(pc[l])
                });
                match shared {
                    Some(pc) => {
                        // one CLIPS node: it chooses a length for all or for none
                        ok &= pc.is_some() == choice[l].is_some();
                    }
                    None => places[l] = i as u32 + 1,
                }
                let shift = 128 - LEVEL_BITS * (l as u32 + 1);
                nk.base |= u128::from(places[l]) << (shift + 8);
                if let Some(m) = choice[l] {
                    ok &= (m as usize) < MAX_MARKS;
                    nk.mono &= m == nk.n;
                    nk.marks[nk.n as usize] = (m, shift as u8);
                    nk.n += 1;
                }
            }
            gen_store(
                &mut self.st.net.mf.keys,
                a as usize,
                gen,
                nk,
                NodeKey::EMPTY,
            );
            prev = Some((a, choice));
        }
        gen_store(&mut self.st.net.mf.keyed, tmpl as usize, gen, ok, false);
        self.st.net.mf.nodes = nodes;
        ok
    }

    /// Makes `levels[a]` hold alpha node `a`'s `choice_levels` for this network.
    fn cache_choice_levels(&mut self, a: Ix) {
        let gen = self.st.net.net_gen.wrapping_add(1).max(1);
        let i = a as usize;
        if gen_cached(&self.st.net.mf.levels, i, gen).is_some() {
            return;
        }
        let l = self.choice_levels(a);
        gen_store(&mut self.st.net.mf.levels, i, gen, l, [None; PATH_LEN]);
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

#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use super::*;
    use crate::engine::SmallEngine;
    use crate::host::NullHost;
    use std::boxed::Box;

    /// For every template, the order keys put every node's segmentations (each mark
    /// 0..=3; a node's come together, longest first, as `enumerate_marks` yields
    /// them), the nodes in several orders, where `mf_cmp`'s stable sort does.
    #[test]
    fn order_keys_agree_with_mf_cmp() {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(deftemplate c (slot id) (multislot r) (multislot s))
             (defrule a (c (r $?p ?v $?f)) =>)
             (defrule b (c (id 1) (r $?p ?x $?m ?y $?f)) =>)
             (defrule d (c (r $?p ?x $?m ?y&:(> ?x ?y) $?f)) =>)
             (defrule e (c (r ?h $?m ?l)) =>)
             (defrule f (c (r $? ?x $?) (s $?q ?x $?)) =>)
             (defrule g (c (s $?a ?x $?b) (r $? 3 $? ?y $?)) =>)
             (defrule h (c (r $?a ?x $?b ?y $?c ?z $?d)) =>)
             (defrule i (v $?p ?x $?m ?y $?f) =>)
             (defrule j (v $? a $?) =>)
             (defrule k (v $? b $? ?z) =>)
             (defrule l (v ?k $?p ?x $?f) =>)",
        )
        .unwrap();
        let mut c = e.core(h);
        let (mut checked, mut sorted_by_keys) = (0, 0);
        for tmpl in 0..c.templates.len() as Ix {
            let mut runs: Vec<Vec<Pending>> = Vec::new();
            let mut a = c.templates[tmpl as usize].alpha_head;
            while a != NONE {
                let n = c.alphas[a as usize].nmarks as usize;
                let mut run = Vec::new();
                for code in (0..4u32.pow(n as u32)).rev() {
                    let mut marks = [0u8; MAX_MARKS];
                    for (i, m) in marks.iter_mut().enumerate().take(n) {
                        *m = (code / 4u32.pow((n - 1 - i) as u32) % 4) as u8;
                    }
                    run.push((a, marks));
                }
                runs.push(run);
                a = c.alphas[a as usize].next_in_tmpl;
            }
            if runs.len() < 2 {
                continue;
            }
            // the nodes in list order, reversed, and rotated
            let mut orders = Vec::new();
            for k in 0..4 {
                let mut r = runs.clone();
                match k {
                    0 => {}
                    1 => r.reverse(),
                    _ => r.rotate_left(k - 1),
                }
                orders.push(r.concat());
            }
            for mut got in orders {
                let mut want = got.clone();
                for &(a, _) in &want {
                    c.cache_choice_levels(a);
                }
                let lv = &c.st.net.mf.levels;
                want.sort_by(|x, y| c.mf_cmp(*x, &lv[x.0 as usize].1, *y, &lv[y.0 as usize].1));
                if c.order_by_keys(&mut got) {
                    sorted_by_keys += 1;
                }
                assert_eq!(got, want, "template {tmpl}");
                checked += 1;
            }
        }
        // a node's own segmentations, alone: `node_mono` (which spares the sort and
        // the keys) only where `mf_cmp`'s sort keeps them as they come
        let mut monos = 0;
        for a in 0..c.alphas.len() as Ix {
            let n = c.alphas[a as usize].nmarks as usize;
            if n == 0 {
                continue;
            }
            let mut got: Vec<Pending> = Vec::new();
            for code in (0..4u32.pow(n as u32)).rev() {
                let mut marks = [0u8; MAX_MARKS];
                for (i, m) in marks.iter_mut().enumerate().take(n) {
                    *m = (code / 4u32.pow((n - 1 - i) as u32) % 4) as u8;
                }
                got.push((a, marks));
            }
            c.cache_choice_levels(a);
            let mut want = got.clone();
            let lv = &c.st.net.mf.levels;
            want.sort_by(|x, y| c.mf_cmp(*x, &lv[x.0 as usize].1, *y, &lv[y.0 as usize].1));
            if c.node_mono(a) {
                assert_eq!(got, want, "node {a}");
                monos += 1;
            }
            // the one-mark shortcut agrees with the walk
            let gen = c.st.net.net_gen.wrapping_add(1).max(1);
            assert!(n > 1 || c.find_node_mono(a, gen), "node {a}");
            c.put_in_mf_order(&mut got);
            assert_eq!(got, want, "node {a}");
        }
        assert!(monos >= 8, "{monos}");
        assert!(
            checked >= 6 && sorted_by_keys == checked,
            "{checked} {sorted_by_keys}"
        );
    }
}
