//! Whole memories removed at once: when the only match of an alpha memory goes, every
//! partial match of its positive successor joins goes, and with them everything below
//! (a memory's partial matches all extend those of its parent join). A control fact
//! that changes (`(modify ?ctx (state next))`) takes a rule's whole network with it.
//!
//! Deleting them one by one (`delete_token`) unlinks each from its parent's child list
//! and from its memory list, though parents and memories all go too. Here each memory
//! is walked once and emptied; a partial match is only taken off the lists that stay:
//! its alpha match's children (the alpha match may live on), the blocker list of
//! another fact's match (a blocked not output), its index bucket, its activations.
//!
//! The result is the same network and agenda as one by one; only the order in which the
//! activations leave differs, which `(watch activations)` would show, so traced runs
//! delete one by one. A subtree feeding a join from the right (whose partial matches
//! block outputs elsewhere) is deleted one by one too, as is everything while matches
//! are owed.

use super::{JoinKind, TokenKind};
use crate::engine::{watch, Core};
use crate::handle::{JoinId, TokenId};
use crate::value::NONE;

impl Core<'_> {
    /// Before alpha match `am` is removed: if it is its memory's only match, empties the
    /// memories of its positive successor joins and all below them at once.
    pub(crate) fn wipe_successors(&mut self, am: TokenId) {
        // (first what most removals fail: their memory keeps other matches)
        let alpha = self.tokens[am].alpha();
        if self.alpha_mems[alpha as usize].head != am || self.tokens[am].mem_next != TokenId::NONE {
            return;
        }
        // partial matches in a chain (each with one child at most, like a job's match
        // under one rule) go one by one for the same work without a memory walk per
        // join: a wipe pays where memories hold several
        if self.chain_below(am) {
            return;
        }
        if self.st.mode.watch & watch::ACTIVATIONS != 0 || self.st.net.owed != TokenId::NONE {
            return;
        }
        // logical support goes partial match by partial match, in CLIPS's order
        #[cfg(feature = "logical")]
        if self.logical_in_use() {
            return;
        }
        let mut j = self.alphas[alpha as usize].succ;
        while j != JoinId::NONE {
            let jn = &self.joins[j];
            let next = jn.alpha_next;
            if jn.kind == JoinKind::Positive
                && self.join_mems[j].mem != TokenId::NONE
                && self.subtree_plain(j)
            {
                self.wipe_memory(j, true);
            }
            j = next;
        }
    }

    /// Whether the partial matches built on alpha match `am` and all below them form
    /// one chain (none, or one whose every partial match has one child at most).
    #[inline(always)]
    fn chain_below(&self, am: TokenId) -> bool {
        let mut t = self.tokens[am].first_child;
        if t == TokenId::NONE {
            return true;
        }
        if self.tokens[t].am_next != TokenId::NONE {
            return false;
        }
        loop {
            let c = self.tokens[t].first_child;
            if c == TokenId::NONE {
                return true;
            }
            if self.tokens[c].next_sib != TokenId::NONE {
                return false;
            }
            t = c;
        }
    }

    /// Whether no join from `join` down feeds a join from the right (remembered per
    /// network generation). None does while no join from the right was built: then
    /// no walk (it cost each rule's first wipe as much as a firing's matching).
    fn subtree_plain(&mut self, join: JoinId) -> bool {
        if !self.st.net.from_right {
            return true;
        }
        let jn = &self.join_mems[join];
        if jn.plain_gen == self.st.net.net_gen {
            return jn.plain;
        }
        let plain = self.walk_joins(join, false, &mut |cx, j| cx.joins[j].rsucc == JoinId::NONE);
        let jn = &mut self.join_mems[join];
        jn.plain = plain;
        jn.plain_gen = self.st.net.net_gen;
        plain
    }

    /// Empties the memory of `join` and of every join below it; `parents_stay`: the
    /// partial matches' parents are not being removed (the top memory), so they leave
    /// their parents' child lists.
    fn wipe_memory(&mut self, join: JoinId, parents_stay: bool) {
        let t = self.join_mems[join].mem;
        // host: a memory with no index built and no extra group has none of its
        // partial matches in a bucket (`JoinMem::index_built`, `JoinMem::xbuilt`), so
        // its walk skips the index removal. Both walks are out of line: inlined here
        // (the recursion's frame) they cost modify-heavy programs more than the skip
        // saves (manners-16 run +2 %).
        #[cfg(feature = "host-speedups")]
        let indexed = {
            let jm = &self.join_mems[join];
            jm.index_built || jm.xbuilt != 0
        };
        #[cfg(not(feature = "host-speedups"))]
        let indexed = true;
        if !indexed {
            self.wipe_tokens::<false>(t, parents_stay);
        } else if t != TokenId::NONE {
            self.wipe_tokens::<true>(t, parents_stay);
        }
        let jm = &mut self.join_mems[join];
        jm.mem = TokenId::NONE;
        // an empty memory is trivially unindexed (see `JoinMem::index_built`)
        #[cfg(feature = "host-speedups")]
        {
            jm.index_built = false;
            jm.xbuilt = 0;
        }
        let mut c = self.joins[join].first_child;
        while c != JoinId::NONE {
            let cj = &self.joins[c];
            let next = cj.next_sibling;
            // an empty memory has empty ones below it (theirs extend its matches)
            if !cj.is_terminal() && self.join_mems[c].mem != TokenId::NONE {
                self.wipe_memory(c, false);
            }
            c = next;
        }
    }

    /// Frees the partial matches of a memory from `t` on (see `wipe_memory`);
    /// `INDEXED`: the memory may have them in index buckets.
    #[inline(never)]
    fn wipe_tokens<const INDEXED: bool>(&mut self, mut t: TokenId, parents_stay: bool) {
        while t != TokenId::NONE {
            let next = self.tokens[t].mem_next;
            if parents_stay {
                self.leave_parent(t);
            }
            self.wipe_token(t, INDEXED);
            t = next;
        }
    }

    /// Takes partial match `t` off its parent's child list.
    fn leave_parent(&mut self, t: TokenId) {
        let tk = &self.tokens[t];
        let (parent, prev, next) = (tk.parent, tk.prev_sib, tk.next_sib);
        if parent != TokenId::NONE {
            super::beta::leave_parent(&mut self.tokens, parent, prev, next);
        }
    }

    /// Frees partial match `t` of a memory being emptied, taking it off the lists that
    /// stay: its alpha match's children, its blocker's list, its index bucket, and its
    /// activations off the agenda (`indexed`: its memory may have it in a bucket).
    #[inline(always)]
    fn wipe_token(&mut self, t: TokenId, indexed: bool) {
        let tk = &self.tokens[t];
        debug_assert!(tk.kind == TokenKind::Beta && tk.blocks == TokenId::NONE);
        let (am, am_prev, am_next) = (tk.am, tk.am_prev, tk.am_next);
        if am != TokenId::NONE {
            super::beta::leave_alpha_match(&mut self.tokens, am, am_prev, am_next);
        } else if self.tokens[t].blocked {
            // a not/exists output on another match's blocker list (nothing is owed)
            self.unlink_blocked(t);
        }
        while self.tokens[t].extra != NONE {
            let a = self.tokens[t].extra;
            self.remove_activation(a);
        }
        if indexed {
            self.beta_index_remove(t);
        }
        // (a wipe runs only while truth maintenance is idle: `wipe_successors`)
        #[cfg(feature = "logical")]
        debug_assert!(!self.logical_in_use());
        self.release_token(t);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::testutil::run_program;
    use std::string::String;

    /// A control fact's modifies empty whole memories (not/exists outputs blocked by
    /// other facts, shared joins, two rules on the same pattern, activations): the
    /// facts, agenda and firings equal those of the one-by-one deletion that a traced
    /// run takes. (The traced run's own lines are dropped before comparing.)
    #[test]
    fn wiped_memories_leave_what_one_by_one_deletion_leaves() {
        let program = |watch: &str| {
            run_program(&std::format!(
                "(deftemplate ctx (slot s))
                 (deftemplate it (slot id) (slot v))
                 (deftemplate mk (slot id))
                 (deffacts d (ctx (s a)) (it (id 1) (v x)) (it (id 2) (v y)) (it (id 3) (v x))
                   (mk (id 2)))
                 (defrule step-a ?c <- (ctx (s a)) (it (id ?i) (v ?v)) (not (mk (id ?i)))
                   (it (id ?j&~?i) (v ?v)) => (modify ?c (s b)))
                 (defrule also-a (ctx (s a)) (it (id ?i)) (exists (mk (id ?k&:(> ?k ?i)))) =>)
                 (defrule step-b ?c <- (ctx (s b)) (it (id ?i) (v x)) =>
                   (assert (mk (id ?i))) (modify ?c (s a)))
                 (defrule done (declare (salience -5)) (ctx (s a)) (not (it (id ?i&:(> ?i 0)) (v x))) =>)
                 {watch}
                 (reset)
                 (run 12)
                 (printout t \"--\" crlf)
                 (facts)
                 (agenda)"
            ))
        };
        let after = |out: String| {
            let keep = out
                .lines()
                .filter(|l| !l.starts_with("==> Activation") && !l.starts_with("<== Activation"))
                .collect::<std::vec::Vec<_>>()
                .join("\n");
            keep
        };
        let wiped = program("(watch rules)");
        let one_by_one = program("(watch rules)\n(watch activations)");
        assert!(one_by_one.contains("<== Activation"), "{one_by_one}");
        assert!(wiped.contains("FIRE"), "{wiped}");
        assert_eq!(after(wiped), after(one_by_one));
    }

    /// A control fact's match whose memories below feed a `not (and ...)` from the
    /// right: once such a join is built no memory there is emptied whole, and after
    /// a `clear` a program without one wipes again: both leave what one-by-one
    /// deletion (a traced run) leaves.
    #[test]
    fn memories_feeding_a_join_from_the_right_are_not_wiped() {
        let rules = "(deftemplate ctx (slot s))
             (deftemplate it (slot id))
             (deftemplate mk (slot id))
             (deffacts d (ctx (s a)) (it (id 1)) (it (id 2)) (it (id 3)) (mk (id 2)))
             (defrule step-a ?c <- (ctx (s a)) (it (id ?i))
               (not (and (mk (id ?i)) (it (id ?j&:(> ?j ?i)))))
               => (modify ?c (s b)))
             (defrule step-b ?c <- (ctx (s b)) (it (id ?i)) (not (mk (id ?i))) =>
               (assert (mk (id ?i))) (modify ?c (s a)))";
        let plain = "(deftemplate ctx (slot s))
             (deftemplate it (slot id))
             (deffacts d (ctx (s a)) (it (id 1)) (it (id 2)))
             (defrule flip ?c <- (ctx (s ?s)) (it (id ?i)) =>
               (modify ?c (s (if (eq ?s a) then b else a))))";
        let program = |watch: &str| {
            run_program(&std::format!(
                "{rules}
                 {watch}
                 (reset)
                 (run 10)
                 (printout t \"--\" crlf)
                 (facts)
                 (agenda)
                 (clear)
                 {plain}
                 {watch}
                 (reset)
                 (run 7)
                 (printout t \"--\" crlf)
                 (facts)
                 (agenda)"
            ))
        };
        let after = |out: String| {
            out.lines()
                .filter(|l| !l.starts_with("==> Activation") && !l.starts_with("<== Activation"))
                .collect::<std::vec::Vec<_>>()
                .join("\n")
        };
        let wiped = program("(watch rules)");
        let one_by_one = program("(watch rules)\n(watch activations)");
        assert!(wiped.matches("FIRE").count() >= 10, "{wiped}");
        assert!(
            wiped.contains("step-b") && wiped.contains("flip"),
            "{wiped}"
        );
        assert_eq!(after(wiped), after(one_by_one));
    }
}
