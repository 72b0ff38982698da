//! Taking network out: a rule's removal (its joins no other rule uses, their partial
//! matches and activations; unused alpha nodes emptied) and the undo of a construct
//! that failed halfway (`rollback` to a checkpoint).

use crate::engine::{Checkpoint, Core};
use crate::handle::JoinId;
use crate::rete::{AlphaNode, Join, JoinMem};
use crate::rule::Rule;
use crate::value::{Ix, NONE};

impl Core<'_> {
    /// Removes a rule (all its disjuncts): joins no other rule uses go, with their
    /// partial matches and activations; unused alpha nodes are emptied. The network
    /// must be writable (`network_writable`, done by whoever built the rule or asks
    /// for its removal).
    pub fn remove_rule(&mut self, r: Ix) {
        // the facts its partial matches support stay (`logical`)
        #[cfg(feature = "logical")]
        let detach = self.detach_supports(true);
        let mut rr = r;
        while rr != NONE {
            let rule = self.rules[rr as usize];
            if rule.terminal != JoinId::NONE {
                self.remove_rule_activations(rr);
            }
            #[cfg(feature = "logical")]
            self.detach_rule_supports(rr);
            self.release_chain(rule.terminal, JoinId::ROOT);
            self.rules[rr as usize].deleted = true;
            rr = rule.next_disjunct;
        }
        #[cfg(feature = "logical")]
        self.detach_supports(detach);
    }

    /// Drops one reference to each join from `j` up to `stop` (and to the
    /// subnetworks of joins from the right); unused joins go with their memories.
    fn release_chain(&mut self, mut j: JoinId, stop: JoinId) {
        while j != JoinId::NONE && j != JoinId::ROOT && j != stop {
            let jn = self.joins[j];
            self.joins[j].refs = jn.refs.saturating_sub(1);
            if self.joins[j].refs == 0 {
                if !jn.is_terminal() {
                    self.clear_join_memory(j);
                }
                self.unlink_join(j);
            }
            if jn.rjoin != JoinId::NONE {
                self.release_chain(jn.rjoin, jn.parent);
            }
            j = jn.parent;
        }
    }

    /// Removes the activations of `rule` (one disjunct) in agenda order, as CLIPS
    /// does (`(watch activations)` shows the order, which the strategy decides).
    fn remove_rule_activations(&mut self, rule: Ix) {
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            let next = self.acts[a as usize].next;
            if self.acts[a as usize].rule == rule {
                self.remove_activation(a);
            }
            a = next;
        }
    }

    pub(crate) fn unlink_join(&mut self, j: JoinId) {
        self.st.net.net_gen = self.st.net.net_gen.wrapping_add(1);
        let a = self.joins[j].alpha;
        if a != NONE {
            let head = self.alphas[a as usize].succ;
            self.alphas[a as usize].succ = self.unlink_from_list(head, j, |x| &mut x.alpha_next);
            if self.alphas[a as usize].succ == JoinId::NONE {
                self.clear_alpha_memory(a);
                self.alphas[a as usize].live = false;
            }
        }
        let parent = self.joins[j].parent;
        let head = self.joins[parent].first_child;
        self.joins[parent].first_child = self.unlink_from_list(head, j, |x| &mut x.next_sibling);
        self.note_children(parent);
        if self.joins[parent].index_child == j {
            self.drop_beta_index(parent);
        }
        // host: extra index groups may be keyed by `j` or map it
        #[cfg(feature = "host-speedups")]
        self.drop_extra_index(parent);
        let rj = self.joins[j].rjoin;
        if rj != JoinId::NONE {
            let head = self.joins[rj].rsucc;
            self.joins[rj].rsucc = self.unlink_from_list(head, j, |x| &mut x.alpha_next);
        }
        self.joins[j].alpha = NONE;
        self.joins[j].rjoin = JoinId::NONE;
        self.joins[j].parent = JoinId::ROOT;
    }

    /// Removes join `j` from a singly linked list of joins that starts at `head` and
    /// chains through the field `next` selects; returns the list's new head.
    fn unlink_from_list(
        &mut self,
        head: JoinId,
        j: JoinId,
        next: fn(&mut Join) -> &mut JoinId,
    ) -> JoinId {
        let after = *next(&mut self.joins[j]);
        if head == j {
            return after;
        }
        let mut p = head;
        while p != JoinId::NONE {
            let n = *next(&mut self.joins[p]);
            if n == j {
                *next(&mut self.joins[p]) = after;
                break;
            }
            p = n;
        }
        head
    }

    /// Gives back the references a new rule took on old joins (below `first_new`),
    /// from `j` up to `stop`, subnetworks included.
    fn release_old_refs(&mut self, mut j: JoinId, stop: JoinId, first_new: JoinId) {
        while j != JoinId::NONE && j != JoinId::ROOT && j != stop && j.ix() < self.joins.len() {
            let jn = self.joins[j];
            if j < first_new {
                self.joins[j].refs = jn.refs.saturating_sub(1);
            }
            if jn.rjoin != JoinId::NONE {
                self.release_old_refs(jn.rjoin, jn.parent, first_new);
            }
            j = jn.parent;
        }
    }

    /// Undoes every construct defined after `cp` (used when a construct fails halfway).
    /// Tokens and activations built by new joins are released first; shared old joins
    /// get their reference counts back.
    pub fn rollback(&mut self, cp: Checkpoint) {
        self.st.net.net_gen = self.st.net.net_gen.wrapping_add(1);
        if cp.njoins == self.st.pools.njoins
            && cp.nalpha == self.st.pools.nalpha
            && cp.nrules == self.st.pools.nrules
        {
            // nothing was built (a construct the syntax stage refused, or one without
            // a network): only the append-only pools go back
            self.truncate_to(cp);
            return;
        }
        // the facts the removed partial matches support stay (`logical`)
        #[cfg(feature = "logical")]
        let detach = self.detach_supports(true);
        for j in (cp.njoins..self.st.pools.njoins).rev() {
            let j = JoinId(j);
            if !self.joins[j].is_terminal() {
                self.clear_join_memory(j);
            }
        }
        for a in cp.nalpha..self.st.pools.nalpha {
            self.clear_alpha_memory(a);
        }
        // activations of new rules (their end nodes may hang below old joins)
        for r in cp.nrules..self.st.pools.nrules {
            let t = self.rules[r as usize].terminal;
            if t != JoinId::NONE && t.ix() < self.joins.len() {
                self.remove_rule_activations(r);
            }
        }
        for r in cp.nrules..self.st.pools.nrules {
            let t = self.rules[r as usize].terminal;
            self.release_old_refs(t, JoinId::ROOT, JoinId(cp.njoins));
        }
        // unlink new joins from old alpha nodes and old parent joins (new ones lead)
        for a in 0..cp.nalpha.min(self.st.pools.nalpha) {
            while self.alphas[a as usize].succ != JoinId::NONE
                && self.alphas[a as usize].succ >= JoinId(cp.njoins)
            {
                let j = self.alphas[a as usize].succ;
                self.alphas[a as usize].succ = self.joins[j].alpha_next;
            }
        }
        for p in 0..cp.njoins.min(self.st.pools.njoins) {
            let p = JoinId(p);
            // new children lead the list, except joins from the right (placed after
            // their subnetwork's first join): drop new ones wherever they are
            while self.joins[p].first_child != JoinId::NONE
                && self.joins[p].first_child >= JoinId(cp.njoins)
            {
                let j = self.joins[p].first_child;
                self.joins[p].first_child = self.joins[j].next_sibling;
            }
            let mut c = self.joins[p].first_child;
            while c != JoinId::NONE {
                let mut n = self.joins[c].next_sibling;
                while n != JoinId::NONE && n >= JoinId(cp.njoins) {
                    n = self.joins[n].next_sibling;
                }
                self.joins[c].next_sibling = n;
                c = n;
            }
            self.note_children(p);
            if self.joins[p].index_child != JoinId::NONE
                && self.joins[p].index_child >= JoinId(cp.njoins)
            {
                self.drop_beta_index(p);
            }
            #[cfg(feature = "host-speedups")]
            if self.join_mems[p]
                .xmap
                .iter()
                .any(|&(c, _)| c >= JoinId(cp.njoins) && c != JoinId::NONE)
            {
                self.drop_extra_index(p);
            }
            while self.joins[p].rsucc != JoinId::NONE && self.joins[p].rsucc >= JoinId(cp.njoins) {
                let j = self.joins[p].rsucc;
                self.joins[p].rsucc = self.joins[j].alpha_next;
            }
        }
        // a template's alpha nodes are kept in network order, so new ones can sit
        // anywhere in its list, not only at the head
        for t in 0..cp.ntemplates.min(self.st.pools.ntemplates) {
            while self.templates[t as usize].alpha_head != NONE
                && self.templates[t as usize].alpha_head >= cp.nalpha
            {
                let a = self.templates[t as usize].alpha_head;
                self.templates[t as usize].alpha_head = self.alphas[a as usize].next_in_tmpl;
            }
            let mut a = self.templates[t as usize].alpha_head;
            while a != NONE {
                let mut n = self.alphas[a as usize].next_in_tmpl;
                while n != NONE && n >= cp.nalpha {
                    n = self.alphas[n as usize].next_in_tmpl;
                }
                self.alphas[a as usize].next_in_tmpl = n;
                a = n;
            }
        }
        for a in cp.nalpha..self.st.pools.nalpha {
            self.alphas[a as usize] = AlphaNode::EMPTY;
        }
        for j in cp.njoins..self.st.pools.njoins {
            let j = JoinId(j);
            self.joins[j] = Join::EMPTY;
            self.join_mems[j] = JoinMem::EMPTY;
        }
        for r in cp.nrules..self.st.pools.nrules {
            self.rules[r as usize] = Rule::EMPTY;
        }
        // An old join whose last user was the new rule (its previous users were removed
        // meanwhile, e.g. by a redefinition of the same rule) is now unused: remove it
        // as `remove_rule` would, or it keeps its partial matches and eats tokens.
        for j in 1..cp.njoins.min(self.st.pools.njoins) {
            let j = JoinId(j);
            if self.joins[j].refs == 0 {
                if !self.joins[j].is_terminal() {
                    self.clear_join_memory(j);
                }
                self.unlink_join(j);
            }
        }
        #[cfg(feature = "logical")]
        self.detach_supports(detach);
        self.st.pools.nrules = cp.nrules;
        self.st.pools.nalpha = cp.nalpha;
        self.st.pools.njoins = cp.njoins;
        self.truncate_to(cp);
    }

    /// Gives back the entries of the append-only construct pools made after `cp`.
    fn truncate_to(&mut self, cp: Checkpoint) {
        self.st.pools.nexprs = cp.nexprs;
        self.st.pools.ntemplates = cp.ntemplates;
        self.st.pools.nslots = cp.nslots;
        #[cfg(feature = "extras")]
        self.truncate_function_listing(self.st.pools.nfuncs as usize, cp.nfuncs);
        self.st.pools.nfuncs = cp.nfuncs;
        self.st.pools.nglobals = cp.nglobals;
        self.st.pools.ndeffacts = cp.ndeffacts;
        self.syms().truncate(cp.nsyms, cp.sym_bytes);
    }
}
