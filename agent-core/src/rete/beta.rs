//! Beta side: joins combining partial matches (left) with alpha matches (right),
//! negation and existence counting, token deletion, and handing complete matches to
//! the agenda.

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
        self.st.hw.used[Pool::Tokens as usize] = self.st.hw.used[Pool::Tokens as usize].max(self.live_tokens_estimate());
        Ok(t)
    }

    fn live_tokens_estimate(&self) -> u32 {
        self.st.tokens_used as u32
    }

    pub(crate) fn free_token(&mut self, t: u16) {
        self.tokens[t as usize] = Token { next_sib: self.st.token_free, ..Token::EMPTY };
        self.st.token_free = t;
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
                PatBinding { fact: a.fact, marks: a.marks }
            } else {
                PatBinding::EMPTY
            };
            t = tk.parent;
        }
    }

    /// Evaluates a join's tests for left token `left` and alpha match `am`.
    fn join_test(&mut self, join: u16, left: u16, am: u16, left_bound: bool) -> Result<bool, EvalError> {
        let j = self.joins[join as usize];
        if j.tests == NONE {
            return Ok(true);
        }
        if !left_bound {
            self.bind_left(left);
        }
        self.st.lhs_pm[j.depth as usize] = if am != NONE {
            let a = self.tokens[am as usize];
            PatBinding { fact: a.fact, marks: a.marks }
        } else {
            PatBinding::EMPTY
        };
        let saved = self.st.pm_rhs;
        self.st.pm_rhs = false;
        let r = self.eval_tests(j.tests);
        self.st.pm_rhs = saved;
        r
    }

    /// A new alpha match arrives on the right of `join`.
    pub(crate) fn right_activate(&mut self, join: u16, am: u16) -> Result<(), EvalError> {
        let j = self.joins[join as usize];
        let mut l = self.joins[j.parent as usize].mem;
        match j.kind {
            JoinKind::Positive => {
                while l != NONE {
                    let next = self.tokens[l as usize].mem_next;
                    if self.join_test(join, l, am, false)? {
                        self.new_token(join, l, am)?;
                    }
                    l = next;
                }
            }
            JoinKind::Negative => {
                while l != NONE {
                    let next = self.tokens[l as usize].mem_next;
                    if self.join_test(join, l, am, false)? {
                        self.tokens[l as usize].extra = self.tokens[l as usize].extra.saturating_add(1);
                        if self.tokens[l as usize].extra == 1 {
                            self.delete_children(l);
                        }
                    }
                    l = next;
                }
            }
            JoinKind::Exists => {
                // count first (cannot fail), then create outputs, so a rollback is exact
                while l != NONE {
                    let next = self.tokens[l as usize].mem_next;
                    if self.join_test(join, l, am, false)? {
                        self.tokens[l as usize].extra = self.tokens[l as usize].extra.saturating_add(1);
                    }
                    l = next;
                }
                let mut l = self.joins[j.parent as usize].mem;
                while l != NONE {
                    let next = self.tokens[l as usize].mem_next;
                    if self.tokens[l as usize].extra >= 1 && self.tokens[l as usize].first_child == NONE {
                        self.emit(join, l)?;
                    }
                    l = next;
                }
            }
            JoinKind::Root | JoinKind::Test => {}
        }
        Ok(())
    }

    /// A new partial match `left` arrives on the left of `join`.
    pub(crate) fn left_activate(&mut self, join: u16, left: u16) -> Result<(), EvalError> {
        let j = self.joins[join as usize];
        match j.kind {
            JoinKind::Positive => {
                let mut a = self.alphas[j.alpha as usize].mem;
                let mut bound = false;
                while a != NONE {
                    let next = self.tokens[a as usize].mem_next;
                    if self.join_test(join, left, a, bound)? {
                        self.new_token(join, left, a)?;
                        bound = false;
                    } else {
                        bound = true;
                    }
                    a = next;
                }
            }
            JoinKind::Negative | JoinKind::Exists => {
                let mut a = self.alphas[j.alpha as usize].mem;
                let mut count: u16 = 0;
                let mut bound = false;
                while a != NONE {
                    if self.join_test(join, left, a, bound)? {
                        count = count.saturating_add(1);
                    }
                    bound = true;
                    a = self.tokens[a as usize].mem_next;
                }
                self.tokens[left as usize].extra = count;
                let pass = if j.kind == JoinKind::Negative { count == 0 } else { count > 0 };
                if pass {
                    self.emit(join, left)?;
                }
            }
            JoinKind::Test => {
                if self.join_test(join, left, NONE, false)? {
                    self.new_token(join, left, NONE)?;
                }
            }
            JoinKind::Root => {}
        }
        Ok(())
    }

    /// Output of a not/exists join for `left`, if its post tests hold.
    fn emit(&mut self, join: u16, left: u16) -> Result<(), EvalError> {
        let post = self.joins[join as usize].post;
        if post != NONE {
            self.bind_left(left);
            let saved = self.st.pm_rhs;
            self.st.pm_rhs = false;
            let ok = self.eval_tests(post);
            self.st.pm_rhs = saved;
            if !ok? {
                return Ok(());
            }
        }
        self.new_token(join, left, NONE).map(|_| ())
    }

    /// Creates a partial match in `join`'s memory and passes it on.
    pub(crate) fn new_token(&mut self, join: u16, parent: u16, am: u16) -> Result<u16, EvalError> {
        let t = self.alloc_token()?;
        let head = self.joins[join as usize].mem;
        let psib = if parent != NONE { self.tokens[parent as usize].first_child } else { NONE };
        let asib = if am != NONE { self.tokens[am as usize].first_child } else { NONE };
        self.tokens[t as usize] = Token {
            kind: TokenKind::Beta,
            owner: join,
            am,
            parent,
            mem_next: head,
            next_sib: psib,
            am_next: asib,
            extra: NONE,
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
        let child = self.joins[join as usize].child;
        if child == NONE {
            let rule = self.joins[join as usize].rule;
            self.add_activation(rule, t)?;
        } else {
            self.tokens[t as usize].extra = 0;
            self.left_activate(child, t)?;
        }
        Ok(t)
    }

    pub(crate) fn delete_children(&mut self, t: u16) {
        while self.tokens[t as usize].first_child != NONE {
            let c = self.tokens[t as usize].first_child;
            self.delete_token(c);
        }
    }

    /// Deletes a partial match and everything built on it.
    pub(crate) fn delete_token(&mut self, t: u16) {
        self.delete_children(t);
        let tk = self.tokens[t as usize];
        let join = self.joins[tk.owner as usize];
        if join.child == NONE && join.kind != JoinKind::Root && tk.extra != NONE {
            self.remove_activation(tk.extra);
        }
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
        if tk.mem_prev != NONE {
            self.tokens[tk.mem_prev as usize].mem_next = tk.mem_next;
        } else {
            self.joins[tk.owner as usize].mem = tk.mem_next;
        }
        if tk.mem_next != NONE {
            self.tokens[tk.mem_next as usize].mem_prev = tk.mem_prev;
        }
        self.free_token(t);
    }

    /// A blocking alpha match leaves a `not` join: unblock left tokens it was counted in.
    pub(crate) fn negative_right_remove(&mut self, join: u16, am: u16) {
        let parent = self.joins[join as usize].parent;
        let mut l = self.joins[parent as usize].mem;
        while l != NONE {
            let next = self.tokens[l as usize].mem_next;
            if self.join_test(join, l, am, false).unwrap_or(false) && self.tokens[l as usize].extra > 0 {
                self.tokens[l as usize].extra -= 1;
                if self.tokens[l as usize].extra == 0 {
                    // Restoring a match that existed before; a full pool here is reported
                    // by the next operation that needs the space.
                    let _ = self.emit(join, l);
                }
            }
            l = next;
        }
    }

    pub(crate) fn exists_right_remove(&mut self, join: u16, am: u16) {
        let parent = self.joins[join as usize].parent;
        let mut l = self.joins[parent as usize].mem;
        while l != NONE {
            let next = self.tokens[l as usize].mem_next;
            if self.join_test(join, l, am, false).unwrap_or(false) && self.tokens[l as usize].extra > 0 {
                self.tokens[l as usize].extra -= 1;
                if self.tokens[l as usize].extra == 0 {
                    self.delete_children(l);
                }
            }
            l = next;
        }
    }

    /// Releases every token of a rule (root token cascade).
    pub(crate) fn remove_rule_matches(&mut self, rule: u16) {
        let root = self.rules[rule as usize].root;
        if root == NONE {
            return;
        }
        while self.joins[root as usize].mem != NONE {
            let t = self.joins[root as usize].mem;
            self.delete_token(t);
        }
    }

    /// Creates the rule's root token and matches the rule against existing facts.
    pub(crate) fn activate_root(&mut self, rule: u16) -> Result<(), EvalError> {
        let root = self.rules[rule as usize].root;
        let t = self.alloc_token()?;
        self.tokens[t as usize] = Token { kind: TokenKind::Beta, owner: root, extra: 0, ..Token::EMPTY };
        self.joins[root as usize].mem = t;
        let child = self.joins[root as usize].child;
        if child != NONE {
            self.left_activate(child, t)?;
        }
        Ok(())
    }
}
