//! Beta side: joins combining partial matches (left) with alpha matches (right),
//! negation and existence counting, token deletion, and handing complete matches to
//! the agenda.
//!
//! Joins with an identical prefix are shared between rules (as CLIPS does), so a
//! token may feed several child joins. A `not`/`exists` join keeps one output token
//! per left token, carrying the count of matching right items; it is *active* (passed
//! on) while the count is zero (`not`) or positive (`exists`).

use super::{JoinKind, PatBinding, Token, TokenKind};
use crate::engine::{cap, Core};
use crate::error::{CapacityError, EvalError, Pool};
use crate::value::NONE;

impl Core<'_> {
    pub(crate) fn alloc_token(&mut self) -> Result<u16, CapacityError> {
        let t = if self.st.token_free != NONE {
            let t = self.st.token_free;
            self.st.token_free = self.tokens[t as usize].next_sib;
            t
        } else {
            let n = self.st.tokens_used as usize;
            if n >= self.tokens.len() || n >= NONE as usize {
                return Err(cap(Pool::Tokens, self.tokens.len()));
            }
            self.st.tokens_used += 1;
            n as u16
        };
        self.st.tokens_live += 1;
        self.note_hw(Pool::Tokens, self.st.tokens_live as usize);
        Ok(t)
    }

    pub(crate) fn free_token(&mut self, t: u16) {
        self.tokens[t as usize] = Token {
            next_sib: self.st.token_free,
            ..Token::EMPTY
        };
        self.st.token_free = t;
        self.st.tokens_live -= 1;
    }

    /// Whether a partial match is passed on to child joins / the agenda.
    pub(crate) fn token_active(&self, t: u16) -> bool {
        let tk = &self.tokens[t as usize];
        match self.joins[tk.owner as usize].kind {
            JoinKind::Negative => tk.count == 0,
            JoinKind::Exists => tk.count > 0,
            _ => true,
        }
    }

    /// Fills `lhs_pm` with the pattern bindings along a token's ancestry.
    pub(crate) fn bind_left(&mut self, mut t: u16) {
        while t != NONE {
            let tk = self.tokens[t as usize];
            let j = self.joins[tk.owner as usize];
            if j.kind == JoinKind::Root {
                break;
            }
            self.st.lhs_pm[j.depth as usize] = if tk.am != NONE {
                let a = self.tokens[tk.am as usize];
                PatBinding {
                    fact: a.fact,
                    marks: a.marks,
                }
            } else {
                PatBinding::EMPTY
            };
            t = tk.parent;
        }
    }

    fn eval_lhs_tests(&mut self, tests: u16) -> Result<bool, EvalError> {
        let saved = self.st.pm_rhs;
        self.st.pm_rhs = false;
        let r = self.eval_tests(tests);
        self.st.pm_rhs = saved;
        r
    }

    /// Evaluates a join's tests for left token `left` and alpha match `am`.
    fn join_test(
        &mut self,
        join: u16,
        left: u16,
        am: u16,
        left_bound: bool,
    ) -> Result<bool, EvalError> {
        let j = self.joins[join as usize];
        if j.tests == NONE {
            return Ok(true);
        }
        if !left_bound {
            self.bind_left(left);
        }
        self.st.lhs_pm[j.depth as usize] = if am != NONE {
            let a = self.tokens[am as usize];
            PatBinding {
                fact: a.fact,
                marks: a.marks,
            }
        } else {
            PatBinding::EMPTY
        };
        self.eval_lhs_tests(j.tests)
    }

    /// The output token of a not/exists `join` for left token `left`, if any.
    fn output_of(&self, left: u16, join: u16) -> u16 {
        let mut c = self.tokens[left as usize].first_child;
        while c != NONE {
            if self.tokens[c as usize].owner == join {
                return c;
            }
            c = self.tokens[c as usize].next_sib;
        }
        NONE
    }

    /// A new alpha match arrives on the right of `join`.
    pub(crate) fn right_activate(&mut self, join: u16, am: u16) -> Result<(), EvalError> {
        let j = self.joins[join as usize];
        let mut l = self.joins[j.parent as usize].mem;
        while l != NONE {
            let next = self.tokens[l as usize].mem_next;
            if self.token_active(l) && self.join_test(join, l, am, false)? {
                match j.kind {
                    JoinKind::Positive => {
                        let t = self.link_token(join, l, am)?;
                        self.propagate(t)?;
                    }
                    JoinKind::Negative => {
                        let t = self.output_of(l, join);
                        if t != NONE {
                            self.add_link(t, am)?;
                            if self.tokens[t as usize].count == 1 {
                                self.deactivate(t);
                            }
                        }
                    }
                    JoinKind::Exists => {
                        let t = self.output_of(l, join);
                        if t != NONE {
                            self.add_link(t, am)?;
                            if self.tokens[t as usize].count == 1 {
                                self.propagate(t)?;
                            }
                        }
                    }
                    JoinKind::Root | JoinKind::Test | JoinKind::Terminal => {}
                }
            }
            l = next;
        }
        Ok(())
    }

    /// A new active partial match `left` arrives on the left of `join`.
    pub(crate) fn left_activate(&mut self, join: u16, left: u16) -> Result<(), EvalError> {
        let j = self.joins[join as usize];
        match j.kind {
            JoinKind::Positive => {
                let mut a = self.alphas[j.alpha as usize].mem;
                let mut bound = false;
                while a != NONE {
                    let next = self.tokens[a as usize].mem_next;
                    if self.join_test(join, left, a, bound)? {
                        let t = self.link_token(join, left, a)?;
                        self.propagate(t)?;
                        bound = false;
                    } else {
                        bound = true;
                    }
                    a = next;
                }
            }
            JoinKind::Negative | JoinKind::Exists => {
                if j.post != NONE {
                    self.bind_left(left);
                    if !self.eval_lhs_tests(j.post)? {
                        return Ok(());
                    }
                }
                let t = self.link_token(join, left, NONE)?;
                let mut a = self.alphas[j.alpha as usize].mem;
                let mut bound = false;
                while a != NONE {
                    if self.join_test(join, left, a, bound)? {
                        self.add_link(t, a)?;
                    }
                    bound = true;
                    a = self.tokens[a as usize].mem_next;
                }
                if self.token_active(t) {
                    self.propagate(t)?;
                }
            }
            JoinKind::Test => {
                if self.join_test(join, left, NONE, false)? {
                    let t = self.link_token(join, left, NONE)?;
                    self.propagate(t)?;
                }
            }
            JoinKind::Terminal => {
                let rule = j.rule;
                self.add_activation(rule, left)?;
            }
            JoinKind::Root => {}
        }
        Ok(())
    }

    /// Creates a partial match in `join`'s memory (newest first) and links it under
    /// its parents.
    fn link_token(&mut self, join: u16, parent: u16, am: u16) -> Result<u16, EvalError> {
        let t = self.alloc_token()?;
        let head = self.joins[join as usize].mem;
        let psib = if parent != NONE {
            self.tokens[parent as usize].first_child
        } else {
            NONE
        };
        let asib = if am != NONE {
            self.tokens[am as usize].first_child
        } else {
            NONE
        };
        self.tokens[t as usize] = Token {
            kind: TokenKind::Beta,
            owner: join,
            am,
            parent,
            mem_next: head,
            next_sib: psib,
            am_next: asib,
            ..Token::EMPTY
        };
        if head != NONE {
            self.tokens[head as usize].mem_prev = t;
        }
        self.joins[join as usize].mem = t;
        if parent != NONE {
            if psib != NONE {
                self.tokens[psib as usize].prev_sib = t;
            }
            self.tokens[parent as usize].first_child = t;
        }
        if am != NONE {
            if asib != NONE {
                self.tokens[asib as usize].am_prev = t;
            }
            self.tokens[am as usize].first_child = t;
        }
        Ok(t)
    }

    /// Records that alpha match `am` counts for not/exists output token `t`.
    fn add_link(&mut self, t: u16, am: u16) -> Result<(), EvalError> {
        let owner = self.tokens[t as usize].owner;
        let k = self.link_token(owner, t, am)?;
        // links are not members of the join's memory
        let head = self.tokens[k as usize].mem_next;
        self.joins[owner as usize].mem = head;
        if head != NONE {
            self.tokens[head as usize].mem_prev = NONE;
        }
        self.tokens[k as usize].mem_next = NONE;
        self.tokens[k as usize].kind = TokenKind::Link;
        self.tokens[t as usize].count = self.tokens[t as usize].count.saturating_add(1);
        Ok(())
    }

    /// Removes a link; the counted token is unblocked (not) or loses its match
    /// (exists) when its count drops to zero.
    pub(crate) fn remove_link(&mut self, k: u16) {
        let t = self.tokens[k as usize].parent;
        self.unlink_and_free(k);
        if self.tokens[t as usize].count > 0 {
            self.tokens[t as usize].count -= 1;
            if self.tokens[t as usize].count == 0 {
                if self.joins[self.tokens[t as usize].owner as usize].kind == JoinKind::Negative {
                    // Restores a match that existed before; a full pool here is
                    // reported by the next operation that needs the space.
                    let _ = self.propagate(t);
                } else {
                    self.deactivate(t);
                }
            }
        }
    }

    /// Passes an active partial match on: an activation or the child joins.
    /// Child joins and rule ends, newest first, as CLIPS does.
    pub(crate) fn propagate(&mut self, t: u16) -> Result<(), EvalError> {
        let join = self.tokens[t as usize].owner;
        let mut c = self.joins[join as usize].first_child;
        while c != NONE {
            self.left_activate(c, t)?;
            c = self.joins[c as usize].next_sibling;
        }
        Ok(())
    }

    /// Takes back what a token passed on: its activations, then its child partial
    /// matches (newest first), as CLIPS orders the removals. Its links stay.
    fn deactivate(&mut self, t: u16) {
        while self.tokens[t as usize].extra != NONE
            && self.tokens[t as usize].kind == TokenKind::Beta
        {
            let a = self.tokens[t as usize].extra;
            self.remove_activation(a);
        }
        loop {
            let mut c = self.tokens[t as usize].first_child;
            while c != NONE && self.tokens[c as usize].kind == TokenKind::Link {
                c = self.tokens[c as usize].next_sib;
            }
            if c == NONE {
                break;
            }
            self.delete_token(c);
        }
    }

    pub(crate) fn delete_children(&mut self, t: u16) {
        while self.tokens[t as usize].first_child != NONE {
            let c = self.tokens[t as usize].first_child;
            self.delete_token(c);
        }
    }

    /// Deletes a partial match and everything built on it (links included).
    pub(crate) fn delete_token(&mut self, t: u16) {
        if self.tokens[t as usize].kind == TokenKind::Link {
            self.unlink_and_free(t);
            return;
        }
        self.deactivate(t);
        self.delete_children(t);
        self.unlink_and_free(t);
    }

    /// Unlinks a token from its parent, alpha match and memory lists, then frees it.
    fn unlink_and_free(&mut self, t: u16) {
        let tk = self.tokens[t as usize];
        if tk.parent != NONE {
            if tk.prev_sib != NONE {
                self.tokens[tk.prev_sib as usize].next_sib = tk.next_sib;
            } else {
                self.tokens[tk.parent as usize].first_child = tk.next_sib;
            }
            if tk.next_sib != NONE {
                self.tokens[tk.next_sib as usize].prev_sib = tk.prev_sib;
            }
        }
        if tk.am != NONE {
            if tk.am_prev != NONE {
                self.tokens[tk.am_prev as usize].am_next = tk.am_next;
            } else {
                self.tokens[tk.am as usize].first_child = tk.am_next;
            }
            if tk.am_next != NONE {
                self.tokens[tk.am_next as usize].am_prev = tk.am_prev;
            }
        }
        if tk.kind != TokenKind::Link {
            if tk.mem_prev != NONE {
                self.tokens[tk.mem_prev as usize].mem_next = tk.mem_next;
            } else {
                self.joins[tk.owner as usize].mem = tk.mem_next;
            }
            if tk.mem_next != NONE {
                self.tokens[tk.mem_next as usize].mem_prev = tk.mem_prev;
            }
        }
        self.free_token(t);
    }

    /// Deletes every token in a join's memory.
    pub(crate) fn clear_join_memory(&mut self, join: u16) {
        while self.joins[join as usize].mem != NONE {
            let t = self.joins[join as usize].mem;
            self.delete_token(t);
        }
    }

    /// The global root join and its empty token (join 0), made at start-up.
    pub(crate) fn make_root(&mut self) -> Result<(), EvalError> {
        if self.st.njoins == 0 {
            if self.joins.is_empty() {
                return Err(cap(Pool::Joins, 0).into());
            }
            self.joins[0] = super::Join {
                kind: JoinKind::Root,
                refs: 1,
                ..super::Join::EMPTY
            };
            self.st.njoins = 1;
        }
        if self.joins[0].mem == NONE {
            let t = self.alloc_token()?;
            self.tokens[t as usize] = Token {
                kind: TokenKind::Beta,
                owner: 0,
                ..Token::EMPTY
            };
            self.joins[0].mem = t;
        }
        Ok(())
    }

    /// Feeds the active tokens of `parent`'s memory into a new child join.
    pub(crate) fn prime_join(&mut self, join: u16) -> Result<(), EvalError> {
        let parent = self.joins[join as usize].parent;
        let mut l = self.joins[parent as usize].mem;
        while l != NONE {
            let next = self.tokens[l as usize].mem_next;
            if self.token_active(l) {
                self.left_activate(join, l)?;
            }
            l = next;
        }
        Ok(())
    }
}
