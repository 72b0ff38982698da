//! Priming: the root join made at start-up, and new joins and alpha nodes matched
//! against what exists when a rule is added (CLIPS's incremental reset, `incrrset.c`).

use crate::engine::{cap, Core};
use crate::error::{EvalError, Pool};
use crate::handle::{JoinId, TokenId};
use crate::rete::{Join, JoinKind, Token, TokenKind};
use crate::value::{Ix, NONE};

impl Core<'_> {
    /// The global root join and its empty token (join 0), made at start-up.
    pub(crate) fn make_root(&mut self) -> Result<(), EvalError> {
        if self.st.pools.njoins == 0 {
            if self.joins.is_empty() {
                return Err(cap(Pool::Joins, 0).into());
            }
            self.joins[JoinId::ROOT] = Join {
                kind: JoinKind::Root,
                refs: 1,
                ..Join::EMPTY
            };
            self.st.pools.njoins = 1;
        }
        if self.join_mems[JoinId::ROOT].mem == TokenId::NONE {
            let t = self.alloc_token()?;
            self.tokens[t] = Token {
                kind: TokenKind::Beta,
                owner: JoinId::ROOT,
                ..Token::EMPTY
            };
            self.join_mems[JoinId::ROOT].mem = t;
        }
        Ok(())
    }

    /// Feeds the active tokens of `parent`'s memory into a new child join.
    /// Host: a join under an older one is fed its first older sibling's partial
    /// matches in CLIPS's order (`rete::order`; joins from `first_new` on are new).
    pub(crate) fn prime_join(&mut self, join: JoinId, first_new: JoinId) -> Result<(), EvalError> {
        let parent = self.joins[join].parent;
        #[cfg(feature = "grow")]
        if parent != JoinId::ROOT && self.prime_join_ordered(join, parent, first_new)? {
            return Ok(());
        }
        #[cfg(not(feature = "grow"))]
        let _ = first_new;
        let mut l = self.join_mems[parent].mem;
        while l != TokenId::NONE {
            let next = self.tokens[l].mem_next;
            if self.token_active(l) {
                self.left_activate(join, l)?;
            }
            l = next;
        }
        Ok(())
    }

    /// Drives the existing facts, oldest first, through the alpha nodes numbered
    /// `first` and up (a new rule's patterns), in network order per fact.
    pub(crate) fn prime_alphas(&mut self, first: Ix) -> Result<(), EvalError> {
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            let next = self.facts[f as usize].next;
            self.prime_fact(f, first)?;
            f = next;
        }
        Ok(())
    }

    /// Drives one fact through the alpha nodes numbered `first` and up.
    pub(crate) fn prime_fact(&mut self, f: Ix, first: Ix) -> Result<(), EvalError> {
        // the fact meets the new rule's nodes afresh, shared ones too (CLIPS)
        #[cfg(feature = "extras")]
        self.forget_pattern_error();
        let tmpl = self.facts[f as usize].tmpl;
        let mut a = self.templates[tmpl as usize].alpha_head;
        while a != NONE {
            if a >= first {
                if let Some(tests) = self.quick_tests(self.alphas[a as usize].tests, f) {
                    self.match_alpha::<false>(a, f, tests)?;
                }
            }
            a = self.alphas[a as usize].next_in_tmpl;
        }
        Ok(())
    }
}

#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::run_program;

    /// A test's assert while a rule is primed: the fact meets the new rule's own
    /// patterns only (host), else it is refused as during any pattern-matching.
    #[test]
    fn a_test_asserting_while_a_rule_is_defined() {
        let out = run_program(
            "(defrule old (b ?x) => (printout t \"old \" ?x crlf))\n\
             (defrule old2 (a ?x) => )\n\
             (assert (a 1))\n\
             (defrule new (a ?x) (test (assert (b ?x) (c ?x))) (c ?y) => (printout t \"new \" ?y crlf))\n\
             (run)\n(facts)\n",
        );
        #[cfg(feature = "extras")]
        assert!(
            out.contains("new 1\nnew 1\nf-0")
                && !out.contains("old")
                && out.contains("(b 1)\nf-3     (c 1)\n"),
            "{out}"
        );
        #[cfg(not(feature = "extras"))]
        assert!(
            out.contains("[FACTMNGR2]") && !out.contains("(b 1)"),
            "{out}"
        );
    }
}
