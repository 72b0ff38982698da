//! Alpha network building: a pattern's form (`PatIr`: its tests and its path in CLIPS's
//! pattern network, analysed by `pattern_form` while the syntax stage reads it, which
//! touches no network) becomes an alpha node, shared with identical earlier patterns
//! (sharing and discrimination) and kept in CLIPS's order.

use super::{CompileError, Compiler};
use crate::engine::cap;
use crate::error::Pool;
use crate::expr::{loc, Op};
use crate::handle::JoinId;
use crate::parser::rule::{PatBuild, PatIr};
use crate::rete::{AlphaNode, EMPTY_PATH, MAX_RHASH, PATH_LEN};
use crate::value::{Ix, NONE};

impl Compiler<'_, '_> {
    /// Analysis of a pattern the syntax stage has read (pure: reads expression nodes
    /// and the template only): its path in the pattern network, the right hash folded
    /// into the path's last field.
    pub(crate) fn pattern_form(&self, tmpl: Ix, pb: &PatBuild) -> PatIr {
        let (path, tail) = self.pattern_path(pb);
        // CLIPS never shares the relation-name node an ordered pattern without tests
        // (`(o $?)`) ends in: each such pattern is a new, newest node
        let alone = self.cx.templates[tmpl as usize].implied && path.locs[0] == EMPTY_PATH;
        let (path_loc, mut path_test, plen) = (path.locs, path.tests, path.len);
        if pb.nrhash > 0 {
            // the last field's nodes carry the right hash: nodes of their own
            let mut h: u32 = 0x7f4a_7c15;
            for &e in &pb.rhash[..pb.nrhash] {
                let x = self.cx.exprs[e as usize];
                h = mix16(h, u32::from(x.data));
                if x.first != NONE {
                    let d = self.cx.exprs[x.first as usize];
                    h = mix16(h, u32::from(d.data) | u32::from(d.aux) << 16);
                }
            }
            for t in &mut path_test[plen - tail..plen] {
                *t = (mix16(u32::from(*t), h) & 0xFFFF) as Ix | 1;
            }
        }
        PatIr {
            tmpl,
            desc: pb.desc,
            atests: pb.atests,
            rhash: pb.rhash,
            nrhash: pb.nrhash as u8,
            marks: pb.marks,
            alone,
            path_len: plen as u8,
            path_loc,
            path_test,
        }
    }

    /// The alpha node of a pattern: an identical live one, or a new one. `at`: where
    /// the pattern starts in the text (for the error when the pool is full).
    pub(crate) fn find_or_make_alpha(&mut self, pat: &PatIr, at: u32) -> Result<Ix, CompileError> {
        let tmpl = pat.tmpl;
        let nrhash = pat.nrhash as usize;
        let mut a = self.cx.templates[tmpl as usize].alpha_head;
        #[cfg(feature = "host-speedups")]
        let sig = self.share_sig(pat);
        while a != NONE && !pat.alone {
            // (read in place: a template's nodes are walked for every pattern on it)
            let n = &self.cx.alphas[a as usize];
            #[cfg(feature = "host-speedups")]
            if n.share_sig != sig && n.share_sig != 0 {
                a = n.next_in_tmpl;
                continue;
            }
            if n.live
                && same_path(n, pat)
                && !self.old_only_alpha(a)
                && self.desc_eq(n.desc, pat.desc, nrhash == 0)
                && self.chain_eq(n.tests, pat.atests)
                && n.nrhash == pat.nrhash
                && (0..nrhash).all(|i| self.same_field(n.rhash[i], pat.rhash[i]))
            {
                if nrhash < MAX_RHASH && n.rhash[nrhash] == NONE && pat.rhash[nrhash] != NONE {
                    self.add_or_field(a, nrhash, pat.rhash[nrhash]);
                }
                return Ok(a);
            }
            a = n.next_in_tmpl;
        }
        if let Err(c) = self.cx.network_writable() {
            return Err(CompileError {
                capacity: c,
                at: Some(at),
            });
        }
        let n = self.cx.st.pools.nalpha as usize;
        #[cfg(feature = "grow")]
        {
            self.cx.ensure(Pool::AlphaNodes, n + 1);
            self.cx.ensure(Pool::AlphaMemories, n + 1);
        }
        if n >= self.cx.alphas.len() || n >= self.cx.alpha_mems.len() {
            let c = if n >= self.cx.alphas.len() {
                cap(Pool::AlphaNodes, self.cx.alphas.len())
            } else {
                cap(Pool::AlphaMemories, self.cx.alpha_mems.len())
            };
            return Err(CompileError {
                capacity: c,
                at: Some(at),
            });
        }
        self.cx.alpha_mems[n] = crate::rete::AlphaMem::EMPTY;
        self.cx.alphas[n] = AlphaNode {
            tmpl,
            desc: pat.desc,
            tests: pat.atests,
            next_in_tmpl: NONE,
            succ: JoinId::NONE,
            nmarks: pat.marks,
            live: true,
            path_loc: pat.path_loc,
            path_test: pat.path_test,
            key: [0; PATH_LEN],
            key_len: pat.path_len,
            rhash: pat.rhash,
            nrhash: pat.nrhash,
            #[cfg(feature = "host-speedups")]
            elem_key: false,
            #[cfg(feature = "host-speedups")]
            share_sig: sig,
            #[cfg(feature = "extras")]
            stage: AlphaNode::EMPTY.stage,
            #[cfg(feature = "extras")]
            stage_from: AlphaNode::EMPTY.stage_from,
            #[cfg(feature = "extras")]
            stage_end: AlphaNode::EMPTY.stage_end,
        };
        #[cfg(feature = "host-speedups")]
        {
            self.cx.alphas[n].elem_key = self.cx.elem_keyed(n as Ix);
        }
        #[cfg(feature = "extras")]
        self.cx.set_stage(n as Ix);
        self.assign_trie_key(tmpl, n as Ix, pat.alone);
        self.insert_alpha_sorted(tmpl, n as Ix);
        self.cx.st.pools.nalpha += 1;
        self.cx.st.net.net_gen = self.cx.st.net.net_gen.wrapping_add(1);
        self.cx.note_hw(Pool::AlphaNodes, n + 1);
        self.cx.note_hw(Pool::AlphaMemories, n + 1);
        Ok(n as Ix)
    }

    /// The pattern's path in CLIPS's pattern network (CLIPS 6.30 `factbld.c`), one
    /// level per network node, in the order the pattern names its slots: a field
    /// without a test of its own makes no node wherever it stands; a constant
    /// constraint without `|` makes two, a "selector" node for the field that every
    /// such constant on it shares, then the constant. Multislot elements are nodes of
    /// their own, told apart by their place in the slot's layout (the first carries
    /// the slot's length test). Returns the path and how many of its last levels are
    /// the last field's (they carry the right hash; 0 when the path was cut).
    fn pattern_path(&self, pb: &PatBuild) -> (NetPath, usize) {
        let (f, nf) = (pb.fields, pb.nfields);
        let mut path = NetPath {
            locs: [0; PATH_LEN],
            tests: [0; PATH_LEN],
            len: 0,
            cut: false,
        };
        let mut tail = 0;
        let mut i = 0;
        while i < nf {
            let (l, t, _) = f[i];
            match loc::elem(l) {
                loc::SINGLE => {
                    if t != NONE {
                        let sel = self.selects(t).then_some(SELECTOR);
                        tail = path.field(l, sel, self.expr_hash(t));
                    }
                    i += 1;
                }
                ZERO_LEN => {
                    tail = path.field(l, None, ZERO_LEN as Ix);
                    i += 1;
                }
                _ => {
                    let slot = loc::slot(l);
                    let mut k = i;
                    while k < nf && loc::slot(f[k].0) == slot {
                        k += 1;
                    }
                    if let Some(n) = self.multislot_path(&f[i..k], &mut path) {
                        tail = n;
                    }
                    i = k;
                }
            }
        }
        if path.len == 0 {
            path.locs[0] = EMPTY_PATH;
            path.len = 1;
            tail = 1;
        }
        if path.cut {
            tail = 0;
        }
        (path, tail)
    }

    /// The nodes of one multislot's elements (CLIPS's `RemoveUnneededSlots`): an
    /// element keeps a node if it has a test (the first one always has the slot's
    /// length test unless it is a multifield with no single field after it) or if it
    /// is a multifield among several. Returns the last node's level count, if any.
    fn multislot_path(&self, r: &[(Ix, Ix, bool)], path: &mut NetPath) -> Option<usize> {
        let nmf = r.iter().filter(|x| x.2).count() as u32;
        let nsf = r.len() as u32 - nmf;
        let length_test = if r[0].2 && nsf == 0 {
            0
        } else {
            2 + u32::from(nmf == 0) + (nsf << 1)
        };
        let keeps = |k: usize| {
            let (_, t, m) = r[k];
            t != NONE || (k == 0 && length_test != 0) || (m && nmf > 1)
        };
        let last = (0..r.len()).rev().find(|&k| keeps(k))?;
        let (mut sfb, mut mfb) = (0u32, 0u32);
        let mut tail = 1;
        for (k, &(l, t, m)) in r.iter().enumerate() {
            if keeps(k) {
                // what CLIPS compares: position, kind, end of slot, how the value is
                // found (fields before and after) and the length test
                let mut h = mix16(0x51ed_270b, k as u32);
                if t == NONE && !(m && nmf > 1) {
                    // the first element, kept for the slot's length test alone: a
                    // single-field node (CLIPS makes the slot's only multifield one)
                    // that reads no field, so where the multifield stands is no part
                    // of it (`(o ?x $?)` and `(o $? ?y)` share it)
                    h = mix16(h, u32::from(k == last) << 1);
                    h = mix16(h, length_test);
                    tail = path.field(l, None, ((h ^ (h >> 16)) & 0xFFFF) as Ix);
                    sfb += u32::from(!m);
                    mfb += u32::from(m);
                    continue;
                }
                h = mix16(h, u32::from(m) | u32::from(k == last) << 1);
                if m && t == NONE && nmf > 1 {
                    // a multifield node among several, without a test: CLIPS's
                    // `FindPatternNode` compares its place and the single fields
                    // left after it, not how many multifields follow
                    // (`(p $?a ?x $?b ?y $?c)` and `(p $?a ?x ?x $?c)` share their
                    // first node; a slot's only multifield is no such node)
                    h = mix16(h, nsf - sfb);
                } else {
                    h = mix16(h, sfb | mfb << 8);
                    h = mix16(
                        h,
                        (nsf - sfb - u32::from(!m)) | (nmf - mfb - u32::from(m)) << 8,
                    );
                }
                if k == 0 {
                    h = mix16(h, length_test);
                }
                let fold = |h: u32| ((h ^ (h >> 16)) & 0xFFFF) as Ix;
                tail = if t != NONE && !m && self.selects(t) {
                    let v = mix16(u32::from(self.expr_hash(t)), u32::from(k == last));
                    path.field(l, Some(fold(mix16(h, 0))), fold(v))
                } else {
                    let test = if t == NONE { 1 } else { self.expr_hash(t) };
                    path.field(l, None, fold(mix16(h, u32::from(test))))
                };
            }
            sfb += u32::from(!m);
            mfb += u32::from(m);
        }
        Some(tail)
    }

    /// Whether CLIPS 6.30 hashes this field constraint on a constant (a selector
    /// node): an `&` chain holding a literal that is not negated, and no `|`.
    fn selects(&self, t: Ix) -> bool {
        let x = self.cx.exprs[t as usize];
        if x.op != Op::And {
            return self.is_const_eq(t);
        }
        let mut c = x.first;
        while c != NONE {
            if self.is_const_eq(c) {
                return true;
            }
            c = self.cx.exprs[c as usize].next;
        }
        false
    }

    fn is_const_eq(&self, e: Ix) -> bool {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::Eq2 || x.first == NONE {
            return false;
        }
        let v = self.cx.exprs[x.first as usize].next;
        v != NONE
            && matches!(
                self.cx.exprs[v as usize].op,
                Op::Int | Op::Float | Op::Sym | Op::Str
            )
    }

    /// Gives each level of the new alpha node's path the id of the identical node of
    /// an existing pattern (same prefix), or a new id (always, for a node `alone`).
    fn assign_trie_key(&mut self, tmpl: Ix, n: Ix, alone: bool) {
        let me = self.cx.alphas[n as usize];
        let mut key = [0 as Ix; PATH_LEN];
        // a level given a new id leaves no node with the same prefix below it
        let mut fresh = false;
        for lvl in 0..me.key_len as usize {
            let mut id = 0;
            let mut a = if alone || fresh {
                NONE
            } else {
                self.cx.templates[tmpl as usize].alpha_head
            };
            while a != NONE {
                // (read in place, the level's own test first: every node of the
                // template is walked per level)
                let o = &self.cx.alphas[a as usize];
                if o.key_len as usize > lvl
                    && o.path_test[lvl] == me.path_test[lvl]
                    && o.path_loc[lvl] == me.path_loc[lvl]
                    && o.key[..lvl] == key[..lvl]
                    && !self.old_only_alpha(a)
                {
                    id = o.key[lvl];
                    break;
                }
                a = o.next_in_tmpl;
            }
            if id == 0 {
                self.cx.st.pools.trie_ids = self.cx.st.pools.trie_ids.wrapping_add(1).max(1);
                id = self.cx.st.pools.trie_ids;
                fresh = true;
            }
            key[lvl] = id;
        }
        self.cx.alphas[n as usize].key = key;
    }

    /// Structural hash of an expression tree (orders alpha nodes; never decides
    /// sharing, which compares exactly).
    fn expr_hash(&self, e: Ix) -> Ix {
        let x = self.cx.exprs[e as usize];
        let mut h = mix16(0x9e37, x.op as u32);
        h = mix16(h, shape_aux(x) as u32);
        h = mix16(h, x.data as u32);
        if matches!(x.op, Op::Int | Op::Float) {
            let p = self.cx.exprs[e as usize + 1];
            h = mix16(h, p.data as u32 | (p.first as u32) << 16);
            h = mix16(h, p.next as u32);
        } else if x.op != Op::PatVar {
            let mut c = x.first;
            while c != NONE {
                h = mix16(h, self.expr_hash(c) as u32);
                c = self.cx.exprs[c as usize].next;
            }
        }
        (((h ^ (h >> 16)) & 0xFFFF) as Ix).max(2)
    }

    /// Keeps a template's alpha nodes in pattern-network order: depth first, newer
    /// sibling nodes first, a pattern's own node before longer ones.
    fn insert_alpha_sorted(&mut self, tmpl: Ix, n: Ix) {
        let me = &self.cx.alphas[n as usize];
        let mine = &me.key[..me.key_len as usize];
        let mut prev = NONE;
        let mut a = self.cx.templates[tmpl as usize].alpha_head;
        while a != NONE {
            // (read in place: a template's nodes are walked for each new one)
            let o = &self.cx.alphas[a as usize];
            // an equal path is the same CLIPS node, whose newest joins come first
            if !key_before(&o.key[..o.key_len as usize], mine) {
                break;
            }
            prev = a;
            a = o.next_in_tmpl;
        }
        self.cx.alphas[n as usize].next_in_tmpl = a;
        if prev == NONE {
            self.cx.templates[tmpl as usize].alpha_head = n;
        } else {
            self.cx.alphas[prev as usize].next_in_tmpl = n;
        }
    }

    /// Records the fields of pattern `p` that its join tests compare for equality
    /// with a variable bound earlier (`?x` used again): CLIPS's right hash.
    pub(crate) fn right_hash(&mut self, pb: &mut PatBuild, p: u8) {
        let mut t = pb.jtests;
        while t != NONE && pb.nrhash < MAX_RHASH {
            let x = self.cx.exprs[t as usize];
            if x.op == Op::Eq2 && x.first != NONE {
                let this = self.cx.exprs[x.first as usize];
                let other = this.next;
                if this.op == Op::PatVar
                    && this.aux == p
                    && other != NONE
                    && self.cx.exprs[other as usize].op == Op::PatVar
                    && self.cx.exprs[other as usize].aux != p
                {
                    pb.rhash[pb.nrhash] = x.first;
                    pb.nrhash += 1;
                }
            }
            t = x.next;
        }
        if pb.nrhash < MAX_RHASH {
            pb.rhash[pb.nrhash] = self.or_field(pb.jtests, p);
        }
    }

    /// The field of pattern `p` that a join test `?a | ?b` (an or of equalities of
    /// one plain slot with variables bound earlier) reads, or NONE. Kept in
    /// `rhash[nrhash]`: it makes no node of its own (CLIPS has no such hash). The host
    /// indexes a node without a right hash on it, so such a join looks up one bucket
    /// per alternative (`rete::index`, `or_lookup`); a keyed node's matches are also
    /// indexed on its key and this field, so a keyed join looks up one bucket per
    /// alternative too (`or_keyed_cursor`).
    fn or_field(&self, mut t: Ix, p: u8) -> Ix {
        while t != NONE {
            let x = self.cx.exprs[t as usize];
            if let Some(f) = self.cx.or_of_equalities(t, p) {
                return f;
            }
            t = x.next;
        }
        NONE
    }

    /// A shared node takes a later pattern's or-test field (`or_field`) when it has
    /// none; the host indexes the matches it already holds on it, oldest first
    /// (a node with a right hash: in the keyed or-index, `rete::index`).
    fn add_or_field(&mut self, a: Ix, nrhash: usize, field: Ix) {
        if self.cx.network_writable().is_err() {
            return;
        }
        self.cx.alphas[a as usize].rhash[nrhash] = field;
        #[cfg(feature = "host-speedups")]
        {
            self.cx.alphas[a as usize].elem_key = self.cx.elem_keyed(a);
        }
        #[cfg(feature = "host-speedups")]
        if nrhash == 0 {
            let mut t = self.cx.alpha_mems[a as usize].head;
            while t != crate::handle::TokenId::NONE {
                self.cx.index_insert(t);
                t = self.cx.tokens[t].mem_next;
            }
        } else {
            // keyed: its matches join the keyed or-index too
            self.cx.or_index_build(a);
        }
    }

    /// Whether two pattern-variable expressions name the same field (any pattern).
    fn same_field(&self, a: Ix, b: Ix) -> bool {
        let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
        x.data == y.data
            && ((x.first == NONE && y.first == NONE)
                || (x.first != NONE && y.first != NONE && {
                    let (p, q) = (
                        self.cx.exprs[x.first as usize],
                        self.cx.exprs[y.first as usize],
                    );
                    p.aux == q.aux && p.data == q.data && self.chain_eq(p.first, q.first)
                }))
    }

    /// Host: a hash of what `find_or_make_alpha` compares besides the path (the
    /// descriptor and test chains as `chain_eq` sees them, the right-hash fields as
    /// `same_field` does):
    /// patterns it finds equal hash equal. Never 0.
    #[cfg(feature = "host-speedups")]
    fn share_sig(&self, pat: &PatIr) -> u32 {
        let mut h = mix16(0x2545_f491, u32::from(pat.nrhash));
        if pat.nrhash == 0 {
            // (what `desc_eq` compares loosely: a slot's shape, not its elements)
            let mut d = pat.desc;
            while d != NONE {
                let x = self.cx.exprs[d as usize];
                h = mix16(mix16(h, u32::from(x.data)), u32::from(x.aux));
                match self.slot_shape(d) {
                    Some((f, m)) => h = mix16(h, u32::from(f) | u32::from(m) << 8),
                    None => h = self.chain_sig(h, x.first),
                }
                d = x.next;
            }
        } else {
            h = self.chain_sig(h, pat.desc);
        }
        h = mix16(h, 0x5a5a);
        h = self.chain_sig(h, pat.atests);
        for &e in &pat.rhash[..pat.nrhash as usize] {
            let x = self.cx.exprs[e as usize];
            h = mix16(h, u32::from(x.data));
            if x.first != NONE {
                let p = self.cx.exprs[x.first as usize];
                h = mix16(mix16(h, u32::from(p.aux)), u32::from(p.data));
                h = self.chain_sig(h, p.first);
            }
        }
        h.max(1)
    }

    /// Host: `share_sig` of a chain, what `expr_eq` compares of each member (a
    /// number's value is left out: `expr_eq` compares values, not their cells).
    #[cfg(feature = "host-speedups")]
    fn chain_sig(&self, mut h: u32, mut c: Ix) -> u32 {
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            h = mix16(h, x.op as u32);
            h = mix16(h, u32::from(shape_aux(x)));
            h = mix16(h, u32::from(x.data));
            match x.op {
                Op::Int | Op::Float => {}
                Op::PatVar => {
                    if x.first != NONE {
                        let p = self.cx.exprs[x.first as usize];
                        h = mix16(mix16(h, u32::from(p.aux)), u32::from(p.data));
                        h = self.chain_sig(h, p.first);
                    }
                }
                _ => h = self.chain_sig(h, x.first),
            }
            c = x.next;
        }
        h
    }

    /// Whether two patterns' slot descriptors lay a fact out alike for the node: equal,
    /// or (`loose`: no right hash reads a field through them) slot by slot equal but
    /// for where the elements of a slot with at most one multifield stand. Such a
    /// slot's layout only makes the node's length test (tested elements are placed
    /// by the node's path), and CLIPS's node compares that test alone:
    /// `(o ?x $?)` and `(o $? ?y)` share it. Variables are read through their own
    /// descriptors.
    fn desc_eq(&self, mut a: Ix, mut b: Ix, loose: bool) -> bool {
        if !loose {
            return self.chain_eq(a, b);
        }
        while a != NONE && b != NONE {
            if !self.expr_eq(a, b) {
                let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
                if x.op != y.op || x.aux != y.aux || x.data != y.data {
                    return false;
                }
                match (self.slot_shape(a), self.slot_shape(b)) {
                    (Some(p), Some(q)) if p == q => {}
                    _ => return false,
                }
            }
            a = self.cx.exprs[a as usize].next;
            b = self.cx.exprs[b as usize].next;
        }
        a == NONE && b == NONE
    }

    /// A slot descriptor's single elements and multifields when it has at most one
    /// multifield (the length test its layout makes), else None.
    fn slot_shape(&self, d: Ix) -> Option<(u8, u8)> {
        let (mut fixed, mut multis) = (0u8, 0u8);
        let mut e = self.cx.exprs[d as usize].first;
        while e != NONE {
            let x = self.cx.exprs[e as usize];
            if x.op != Op::PatElem {
                return None;
            }
            if x.aux == 1 {
                multis += 1;
            } else {
                fixed = fixed.wrapping_add(1);
            }
            e = x.next;
        }
        (multis <= 1).then_some((fixed, multis))
    }

    pub(crate) fn chain_eq(&self, mut a: Ix, mut b: Ix) -> bool {
        while a != NONE && b != NONE {
            if !self.expr_eq(a, b) {
                return false;
            }
            a = self.cx.exprs[a as usize].next;
            b = self.cx.exprs[b as usize].next;
        }
        a == NONE && b == NONE
    }

    fn expr_eq(&self, a: Ix, b: Ix) -> bool {
        let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
        // Equal aux bytes (the usual case) need no masking.
        if x.op != y.op || (x.aux != y.aux && shape_aux(x) != shape_aux(y)) || x.data != y.data {
            return false;
        }
        match x.op {
            Op::Int | Op::Float => self.cx.const_value(a).same(self.cx.const_value(b)),
            Op::PatVar => {
                (x.first == NONE && y.first == NONE)
                    || (x.first != NONE && y.first != NONE && {
                        let (p, q) = (
                            self.cx.exprs[x.first as usize],
                            self.cx.exprs[y.first as usize],
                        );
                        p.aux == q.aux && p.data == q.data && self.chain_eq(p.first, q.first)
                    })
            }
            _ => self.chain_eq(x.first, y.first),
        }
    }

    /// Whether alpha node `a` serves only the rule this defrule replaces: CLIPS removes
    /// the old rule first, so such a node (and a path level only it has) is made anew,
    /// as the newest, not shared. Nodes this defrule made itself are shared.
    fn old_only_alpha(&self, a: Ix) -> bool {
        if self.replacing == NONE || a >= self.alpha_base {
            return false;
        }
        let mut j = self.cx.alphas[a as usize].succ;
        while j != JoinId::NONE {
            if self.cx.joins[j].refs > self.replaced_uses(self.replacing, j) {
                return false;
            }
            j = self.cx.joins[j].alpha_next;
        }
        true
    }
}

/// A pattern's levels in CLIPS's pattern network (field locators and test hashes).
struct NetPath {
    locs: [Ix; PATH_LEN],
    tests: [Ix; PATH_LEN],
    len: usize,
    /// Levels past `PATH_LEN` were dropped.
    cut: bool,
}

impl NetPath {
    /// Adds one field's nodes (a selector first, if any); returns how many.
    fn field(&mut self, l: Ix, selector: Option<Ix>, test: Ix) -> usize {
        let before = self.len;
        for t in selector.into_iter().chain(Some(test)) {
            if self.len < PATH_LEN {
                self.locs[self.len] = l;
                self.tests[self.len] = t;
                self.len += 1;
            } else {
                self.cut = true;
            }
        }
        self.len - before
    }
}

/// Element locator of an empty multislot's zero-length node (never a real element).
pub(crate) const ZERO_LEN: u8 = 0xFE;
/// Path test of a selector node on a single-field slot (`expr_hash` is never 1).
const SELECTOR: Ix = 1;

/// Whether alpha node `n` ends where pattern `pat` does in CLIPS's pattern network:
/// the same nodes in the same order (CLIPS builds a pattern's nodes in the order it
/// names its slots, so patterns testing the same fields in another order do not
/// share a node, and facts visit them apart).
/// (Level by level: every rule base has many identical patterns, which all come
/// here; slice comparisons would call `memcmp` twice for each.)
fn same_path(n: &AlphaNode, pat: &PatIr) -> bool {
    let len = pat.path_len as usize;
    n.key_len == pat.path_len
        && (0..len.min(PATH_LEN))
            .all(|l| n.path_test[l] == pat.path_test[l] && n.path_loc[l] == pat.path_loc[l])
}

/// Depth-first order of pattern-network paths: at the first differing level the
/// newer node (higher id) goes first; a path goes before its extensions.
fn key_before(a: &[Ix], b: &[Ix]) -> bool {
    for (x, y) in a.iter().zip(b.iter()) {
        if x != y {
            return x > y;
        }
    }
    a.len() < b.len()
}

/// A node's `aux` as far as it is part of the expression: a query slot read
/// (`slot_value_of`) and a query variable's template name (`queries::template_of`)
/// keep a lookup cache there, which a run fills in and which must not keep an
/// identical pattern or test from sharing the node; so does a query's declarations
/// node (host: the test's shape, `queries::SHAPE_MASK`).
pub(crate) fn shape_aux(x: crate::expr::Expr) -> u8 {
    // One mask, so the common case costs one test (this runs per node compared).
    let keep = match x.op {
        Op::QSlot | Op::Sym => 0,
        #[cfg(feature = "host-speedups")]
        Op::Nop => !crate::builtins::queries::SHAPE_MASK,
        _ => 0xFF,
    };
    x.aux & keep
}

fn mix16(h: u32, x: u32) -> u32 {
    (h ^ x).wrapping_mul(0x0100_0193).rotate_left(7)
}

#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::host::NullHost;
    use crate::value::NONE;
    use std::boxed::Box;

    /// Patterns with the same tests share a node only when they name the slots in
    /// the same order (CLIPS's path); the one naming them in another order has its
    /// own node, which a fact visits first (the newer path).
    #[test]
    fn patterns_naming_slots_in_another_order_have_own_nodes() {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(deftemplate t (slot x) (multislot m))
             (defrule a (t (x ?x&:(> ?x 2)) (m $?p ?q $?r)) =>)
             (defrule b (t (m $?p ?q $?r) (x ?x&:(> ?x 2))) =>)
             (defrule c (t (x ?x&:(> ?x 2)) (m $?p ?q $?r)) =>)",
        )
        .unwrap();
        let c = e.core(h);
        assert_eq!(c.st.pools.nalpha, 2);
        let (a, b) = (&c.alphas[0], &c.alphas[1]);
        assert_ne!(a.path_loc[0], b.path_loc[0]);
        // a and c share node 0, b's node comes first in the template's order
        let head = c.templates[a.tmpl as usize].alpha_head;
        assert_eq!(head, 1);
        assert_eq!(b.next_in_tmpl, 0);
    }
    /// A multislot constrained by one multifield without a test of its own matches
    /// every value, so the pattern shares the node (and the first join) of a pattern
    /// that leaves the slot out, as in CLIPS; with a test on it, it has its own node.
    #[test]
    fn lone_multifield_shares_the_node_of_a_pattern_leaving_the_slot_out() {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(deftemplate t (multislot m) (slot x))
             (defrule a (t (x ?x)) =>)
             (defrule b (t (m $?p) (x ?x)) =>)
             (defrule c (t (m $?) (x ?x)) =>)
             (defrule d (t (m $?p&:(> (length$ ?p) 1))) =>)",
        )
        .unwrap();
        let c = e.core(h);
        assert_eq!(c.st.pools.nalpha, 2);
        assert_eq!(c.alphas[0].desc, NONE);
        assert_ne!(c.alphas[1].desc, NONE);
        // the root; a, b and c share their first join (CLIPS's `+j`, `=j`, `=j`) and
        // have one join of their own each (`+j`); d has two
        assert_eq!(c.st.pools.njoins, 1 + (1 + 3) + 2);
    }
}
