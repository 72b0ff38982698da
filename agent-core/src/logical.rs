//! Truth maintenance: the `logical` conditional element, as CLIPS 6.30 does it.
//!
//! A rule whose first CEs are `(logical ...)` has a *logical join*: the join of its
//! chain where those CEs end. A fact its actions assert gets *logical support* from
//! the partial match of that join the activation extends (a link from the partial
//! match to the fact, one entry of the `Supports` pool, listed both by the partial
//! match and by the fact). When such a partial match goes (a fact it holds is
//! retracted, a `not` among its CEs is blocked, an `exists` loses its last match), its
//! facts lose that support; a fact left with none goes on the *unsupported* stack, and
//! the operation that caused it retracts the stack's facts, newest first, before it
//! returns (their retractions may push more: the cascade is depth first, as CLIPS's).
//!
//! A fact asserted with no logical support in force (at the top level, or by a rule
//! without `logical`) is unconditional: asserting it again that way drops the support
//! it had; a logical rule re-asserting an unconditional fact adds none. A logical rule
//! whose partial match went during its own actions gives no support any more: when the
//! match went with the fact of the logical group's last pattern (CLIPS unlinks that
//! partial match from its parents) its actions assert nothing more, else (it went as a
//! descendant of a partial match that went, or a `not` was blocked, an `exists` lost
//! its last match: CLIPS keeps its parent links) they assert new facts without support,
//! unconditional ones.
//!
//! Off (feature `logical`, and capacity 0) in the agent image: its rules use no
//! `logical`, and the per-token and per-fact list heads cost a word each.

#[cfg(feature = "logical")]
use crate::engine::Core;
#[cfg(feature = "logical")]
use crate::error::{CapacityError, Pool};
#[cfg(feature = "logical")]
use crate::handle::{JoinId, TokenId};
#[cfg(feature = "logical")]
use crate::value::{Ix, NONE};

/// One logical support: partial match `token`, as passed on to successor `succ` (the
/// next join or rule end on the supporting rule's path), supports fact `fact`. CLIPS
/// copies a partial match for every successor, and each copy has its own supports:
/// rules sharing a partial match support their facts apart, and a copy's support goes
/// right after what it passed on (CLIPS's order of retractions). On the unsupported
/// stack (`token` NONE): fact `fact` lost its last support and is to be retracted.
#[cfg(feature = "logical")]
#[derive(Clone, Copy, Debug)]
pub struct Support {
    pub token: TokenId,
    pub succ: JoinId,
    pub fact: Ix,
    /// Next support of the same partial match (newest first), or next free entry, or
    /// next entry of the unsupported stack.
    pub next_of_token: Ix,
    /// Next support of the same fact (newest first).
    pub next_of_fact: Ix,
}

#[cfg(feature = "logical")]
impl Support {
    pub const EMPTY: Support = Support {
        token: TokenId::NONE,
        succ: JoinId::NONE,
        fact: NONE,
        next_of_token: NONE,
        next_of_fact: NONE,
    };
}

/// Without the feature: no bytes (the pool table keeps the arrays, of zero-sized
/// entries).
#[cfg(not(feature = "logical"))]
pub type Support = ();
#[cfg(not(feature = "logical"))]
pub const NO_SUPPORT: Support = ();
#[cfg(feature = "logical")]
pub const NO_SUPPORT: Support = Support::EMPTY;

/// Head of a partial match's or a fact's support list.
#[cfg(feature = "logical")]
pub type Deps = Ix;
#[cfg(feature = "logical")]
pub const NO_DEPS: Deps = NONE;
#[cfg(not(feature = "logical"))]
pub type Deps = ();
#[cfg(not(feature = "logical"))]
pub const NO_DEPS: Deps = ();

/// The successor of a rule's logical join on the rule's path (a join or the rule's end;
/// NONE: the rule has no `logical` CE).
#[cfg(feature = "logical")]
pub type RuleLogical = JoinId;
#[cfg(feature = "logical")]
pub const NO_RULE_LOGICAL: RuleLogical = JoinId::NONE;
#[cfg(not(feature = "logical"))]
pub type RuleLogical = ();
#[cfg(not(feature = "logical"))]
pub const NO_RULE_LOGICAL: RuleLogical = ();

/// How many facts `LogicalState::held` keeps.
#[cfg(feature = "logical")]
pub const HELD: usize = 8;

/// The engine's truth-maintenance state.
#[cfg(feature = "logical")]
#[derive(Clone, Copy, Debug)]
pub struct LogicalState {
    /// Free supports (chained by `next_of_token`), entries ever used, live ones.
    pub free: Ix,
    pub used: Ix,
    pub live: Ix,
    /// Facts that lost their last support, to retract (newest first).
    pub unsupported: Ix,
    /// The firing rule's logical partial match (NONE: no logical rule firing) and the
    /// successor whose copy of it gives the support.
    pub bind: TokenId,
    pub bind_succ: JoinId,
    /// That partial match went during the rule's actions: they give no support.
    pub gone: bool,
    /// It went with the fact its logical join matched (`remove_alpha_match`; CLIPS's
    /// `AddLogicalDependencies` finds its parent links cut): the actions assert no new
    /// fact. Without it, after `gone`, new facts are asserted unsupported.
    pub cut: bool,
    /// Supported facts asserted again after `gone` (not `cut`): CLIPS links them to the
    /// dead partial match until the firing ends (`FlushGarbagePartialMatches`), so one
    /// losing its other supports meanwhile stays, unconditional (`held`, up to
    /// `HELD` facts; `nheld` of them).
    pub held: [Ix; HELD],
    pub nheld: u8,
    /// The unsupported stack is being retracted (nested operations leave it to that).
    pub forcing: bool,
    /// Partial matches go with their rule (`undefrule`, a redefinition): the facts
    /// they support keep only their other supports, or none (unconditional), and
    /// stay, as in CLIPS.
    pub detach: bool,
    /// A rule with a `logical` CE was defined in this engine (never reset): until
    /// then there is no support, no logical firing, nothing to retract, and the checks
    /// on the hot paths (`logical_in_use`, `logical_idle_for`) read this flag alone.
    pub defined: bool,
}

#[cfg(feature = "logical")]
impl LogicalState {
    pub const fn new() -> LogicalState {
        LogicalState {
            free: NONE,
            used: 0,
            live: 0,
            unsupported: NONE,
            bind: TokenId::NONE,
            bind_succ: JoinId::NONE,
            gone: false,
            cut: false,
            held: [NONE; HELD],
            nheld: 0,
            forcing: false,
            detach: false,
            defined: false,
        }
    }
}

#[cfg(feature = "logical")]
impl Default for LogicalState {
    fn default() -> Self {
        Self::new()
    }
}

/// What `Core::logical_enter` saves for `logical_leave` (a rule fired from a rule's
/// actions by a nested `run`).
#[cfg(feature = "logical")]
#[derive(Clone, Copy)]
pub struct LogicalFrame {
    bind: TokenId,
    bind_succ: JoinId,
    gone: bool,
    cut: bool,
}

#[cfg(feature = "logical")]
impl Core<'_> {
    /// Whether truth maintenance has anything to do (a support, a fact to retract, or
    /// a logical rule firing): deferred propagation and whole-memory removal, which
    /// reorder removals, stay off then. On the hot paths of matching: one load for a
    /// program without `logical` (`defined`), two more for one with it; the facts to
    /// retract are entries of the unsupported stack, which count in `live` until
    /// retracted.
    #[inline(always)]
    pub(crate) fn logical_in_use(&self) -> bool {
        let l = &self.st.logical;
        debug_assert!(l.unsupported == NONE || l.live != 0);
        debug_assert!(l.defined || (l.live == 0 && l.bind == TokenId::NONE));
        l.defined && (l.live != 0 || l.bind != TokenId::NONE)
    }

    /// The successor of rule `rule`'s logical join on its path (NONE: no logical CE).
    pub(crate) fn rule_logical_join(&self, rule: Ix) -> JoinId {
        self.rule_logical
            .get(rule as usize)
            .copied()
            .unwrap_or(JoinId::NONE)
    }

    /// Records the successor of rule `rule`'s logical join; false if the rule is beyond
    /// the table.
    pub(crate) fn set_rule_logical_join(&mut self, rule: Ix, join: JoinId) -> bool {
        if join != JoinId::NONE {
            // growing storage leaves the support list heads of grown entries zero
            // until now (nothing reads them before): empty them, once (`defined` is
            // never reset). Unwritten till then, each array is its first entries'
            // `NO_DEPS` (a seed's or `clear`'s), then the zero ones it grew by.
            #[cfg(feature = "grow")]
            if !self.st.logical.defined && self.grows() {
                let from = self.token_deps.partition_point(|&d| d == NO_DEPS);
                // (the split holds only if nothing wrote a head before: check it)
                debug_assert!(self.token_deps[from..].iter().all(|&d| d == 0));
                self.token_deps[from..].fill(NO_DEPS);
                let from = self.fact_deps.partition_point(|&d| d == NO_DEPS);
                // (the split holds only if nothing wrote a head before: check it)
                debug_assert!(self.fact_deps[from..].iter().all(|&d| d == 0));
                self.fact_deps[from..].fill(NO_DEPS);
            }
            self.st.logical.defined = true;
            #[cfg(feature = "grow")]
            {
                self.st.prime.logical = true;
                self.st.prime.slow_retract = true;
            }
            // (a firing gives logical support on the run loop's general path)
            self.note_run_slow();
        }
        match self.rule_logical.get_mut(rule as usize) {
            Some(e) => {
                *e = join;
                true
            }
            None => join == JoinId::NONE,
        }
    }

    /// Whether firing rule `rule` leaves the logical firing state as it is: the rule
    /// has no logical CE and no logical firing is under way (`logical_enter` would set
    /// what is there and `logical_leave` put it back).
    #[inline(always)]
    pub(crate) fn logical_idle_for(&self, rule: Ix) -> bool {
        let l = &self.st.logical;
        if !l.defined {
            return true;
        }
        l.bind == TokenId::NONE
            && !l.gone
            && l.bind_succ == JoinId::NONE
            && self.rule_logical_join(rule) == JoinId::NONE
    }

    /// Before rule `rule` fires on partial match `token`: the logical support its
    /// asserts get (the ancestor of `token` in the rule's logical join).
    pub(crate) fn logical_enter(&mut self, rule: Ix, token: TokenId) -> LogicalFrame {
        let saved = LogicalFrame {
            bind: self.st.logical.bind,
            bind_succ: self.st.logical.bind_succ,
            gone: self.st.logical.gone,
            cut: self.st.logical.cut,
        };
        let succ = self.rule_logical_join(rule);
        let join = if succ == JoinId::NONE {
            JoinId::NONE
        } else {
            self.joins[succ].parent
        };
        let mut t = token;
        if join != JoinId::NONE {
            while t != TokenId::NONE && self.tokens[t].owner != join {
                t = if self.tokens[t].owner == JoinId::ROOT {
                    TokenId::NONE
                } else {
                    self.tokens[t].parent
                };
            }
        } else {
            t = TokenId::NONE;
        }
        self.st.logical.bind = t;
        self.st.logical.bind_succ = succ;
        // a logical rule whose partial match cannot be found supports nothing
        self.st.logical.gone = join != JoinId::NONE && t == TokenId::NONE;
        self.st.logical.cut = self.st.logical.gone;
        saved
    }

    /// After the actions: the outer firing's logical support again.
    pub(crate) fn logical_leave(&mut self, saved: LogicalFrame) {
        self.st.logical.bind = saved.bind;
        self.st.logical.bind_succ = saved.bind_succ;
        self.st.logical.gone = saved.gone;
        self.st.logical.cut = saved.cut;
        // the firing's dead partial match is flushed: its links go, retracting nothing
        self.st.logical.nheld = 0;
    }

    fn is_held(&self, fact: Ix) -> bool {
        let l = &self.st.logical;
        l.held[..l.nheld as usize].contains(&fact)
    }

    /// Whether an assert may create a fact: not when the firing rule's logical partial
    /// match went with its own fact during the actions (`LogicalState::cut`; CLIPS
    /// creates nothing then).
    #[inline(always)]
    pub(crate) fn logical_may_assert(&self) -> bool {
        !self.st.logical.cut
    }

    /// Alpha match `am`'s partial match `c` is deleted with it (`remove_alpha_match`):
    /// whether it is the firing rule's logical partial match, which then goes `cut`
    /// (`logical_cut_after`).
    #[inline(always)]
    pub(crate) fn logical_cut_before(&self, c: TokenId) -> bool {
        self.st.logical.bind == c && c != TokenId::NONE
    }

    /// After deleting a partial match `logical_cut_before` named.
    #[inline(always)]
    pub(crate) fn logical_cut_after(&mut self) {
        self.st.logical.cut = true;
    }

    /// Whether there is room for the support an assert may add now.
    #[inline(always)]
    pub(crate) fn support_room(&mut self) -> Result<(), CapacityError> {
        let l = &self.st.logical;
        if l.bind == TokenId::NONE || l.free != NONE || (l.used as usize) < self.supports.len() {
            return Ok(());
        }
        // with feature `grow` the pool grows (or that is its capacity error)
        #[cfg(feature = "grow")]
        return self.grow(Pool::Supports, self.st.logical.used as usize + 1);
        #[cfg(not(feature = "grow"))]
        Err(crate::engine::cap(Pool::Supports, self.supports.len()))
    }

    /// Support for a fact just created (before its watch line): the firing rule's
    /// logical partial match, if any. Room was checked (`support_room`).
    pub(crate) fn support_new_fact(&mut self, fact: Ix) {
        let t = self.st.logical.bind;
        if t != TokenId::NONE && !self.st.logical.gone {
            self.link_support(t, fact);
        }
    }

    /// An assert found `fact` already there: without logical support in force it
    /// becomes unconditional; with it, a supported fact gains that support (an
    /// unconditional one stays so). Room was checked (`support_room`).
    pub(crate) fn support_existing_fact(&mut self, fact: Ix) {
        let t = self.st.logical.bind;
        if t == TokenId::NONE {
            let l = &mut self.st.logical;
            if !l.gone {
                self.drop_fact_supports(fact);
            } else if !l.cut
                && self.fact_deps[fact as usize] != NONE
                && (l.nheld as usize) < HELD
                && !l.held[..l.nheld as usize].contains(&fact)
            {
                // linked to the dead partial match until the firing ends
                l.held[l.nheld as usize] = fact;
                l.nheld += 1;
            }
            return;
        }
        if self.fact_deps[fact as usize] != NONE {
            self.link_support(t, fact);
        }
    }

    fn link_support(&mut self, t: TokenId, fact: Ix) {
        let s = match self.alloc_support() {
            Some(s) => s,
            // `support_room` said there was room
            None => return,
        };
        self.supports[s as usize] = crate::logical::Support {
            token: t,
            succ: self.st.logical.bind_succ,
            fact,
            next_of_token: self.token_deps[t.ix()],
            next_of_fact: self.fact_deps[fact as usize],
        };
        self.token_deps[t.ix()] = s;
        self.fact_deps[fact as usize] = s;
    }

    fn alloc_support(&mut self) -> Option<Ix> {
        let l = &mut self.st.logical;
        let s = if l.free != NONE {
            let s = l.free;
            l.free = self.supports[s as usize].next_of_token;
            s
        } else if (l.used as usize) < self.supports.len() && l.used != NONE {
            l.used += 1;
            l.used - 1
        } else {
            return None;
        };
        l.live += 1;
        let live = l.live as usize;
        self.note_hw(Pool::Supports, live);
        Some(s)
    }

    fn free_support(&mut self, s: Ix) {
        self.supports[s as usize] = crate::logical::Support {
            next_of_token: self.st.logical.free,
            ..crate::logical::Support::EMPTY
        };
        self.st.logical.free = s;
        self.st.logical.live -= 1;
    }

    /// A fact is retracted (after its watch line, before the network forgets it): it
    /// leaves the lists of the partial matches supporting it, and the unsupported
    /// stack.
    #[inline(always)]
    pub(crate) fn fact_leaves(&mut self, fact: Ix) {
        if self.st.logical.nheld != 0 {
            let l = &mut self.st.logical;
            if let Some(i) = l.held[..l.nheld as usize].iter().position(|&f| f == fact) {
                l.nheld -= 1;
                l.held[i] = l.held[l.nheld as usize];
            }
        }
        if self.st.logical.live == 0 {
            return;
        }
        self.drop_fact_supports(fact);
        // (only its own retraction takes a fact off the stack early)
        #[cfg(feature = "host-speedups")]
        {
            let on = &mut self.facts[fact as usize].unsupported;
            if *on == 0 {
                return;
            }
            *on = 0;
        }
        let mut p = NONE;
        let mut s = self.st.logical.unsupported;
        while s != NONE {
            let next = self.supports[s as usize].next_of_token;
            if self.supports[s as usize].fact == fact {
                if p == NONE {
                    self.st.logical.unsupported = next;
                } else {
                    self.supports[p as usize].next_of_token = next;
                }
                self.free_support(s);
            } else {
                p = s;
            }
            s = next;
        }
    }

    /// Takes `fact` off the support lists of every partial match supporting it.
    fn drop_fact_supports(&mut self, fact: Ix) {
        let mut s = self.fact_deps[fact as usize];
        self.fact_deps[fact as usize] = NONE;
        while s != NONE {
            let e = self.supports[s as usize];
            let head = &mut self.token_deps[e.token.ix()];
            if *head == s {
                *head = e.next_of_token;
            } else {
                let mut p = *head;
                while p != NONE {
                    let n = self.supports[p as usize].next_of_token;
                    if n == s {
                        self.supports[p as usize].next_of_token = e.next_of_token;
                        break;
                    }
                    p = n;
                }
            }
            self.free_support(s);
            s = e.next_of_fact;
        }
    }

    /// Partial match `t` goes (deleted, or a not/exists output no longer passing
    /// on): the facts it supports lose that support, and those left with none are
    /// pushed on the unsupported stack, in the order of its list. Out of line, as
    /// `copy_leaves`: the callers test `logical_in_use` first, and a program without
    /// `logical` keeps them small (`free_token` inlined in the join loops).
    #[cold]
    #[inline(never)]
    pub(crate) fn token_leaves(&mut self, t: TokenId) {
        self.copy_leaves(t, JoinId::NONE);
    }

    /// Partial match `t`'s copy passed on to successor `succ` goes (all its copies
    /// for NONE): see `token_leaves`. Called once what the copy passed on is taken
    /// back (CLIPS's order).
    #[cold]
    #[inline(never)]
    pub(crate) fn copy_leaves(&mut self, t: TokenId, succ: JoinId) {
        if t == self.st.logical.bind && (succ == JoinId::NONE || succ == self.st.logical.bind_succ)
        {
            self.st.logical.gone = true;
            self.st.logical.bind = TokenId::NONE;
        }
        if self.st.logical.live == 0 || self.token_deps[t.ix()] == NONE {
            return;
        }
        if succ == JoinId::NONE {
            self.drop_all_copies(t);
        } else {
            self.drop_copy_supports(t, succ);
        }
    }

    /// Whether partial match `t`'s copy for successor `succ` supports a fact.
    #[cfg(feature = "grow")]
    pub(crate) fn copy_supports(&self, t: TokenId, succ: JoinId) -> bool {
        let mut s = self.token_deps.get(t.ix()).copied().unwrap_or(NONE);
        while s != NONE {
            let e = &self.supports[s as usize];
            if e.succ == succ {
                return true;
            }
            s = e.next_of_token;
        }
        false
    }

    /// Every copy of `t` goes: their supports in the order CLIPS made the copies (the
    /// oldest successor first, as `deactivate` takes back what they passed on).
    #[inline(never)]
    fn drop_all_copies(&mut self, t: TokenId) {
        let owner = self.tokens[t].owner;
        let mut n = 0usize;
        let mut c = self.joins[owner].first_child;
        while c != JoinId::NONE {
            n += 1;
            c = self.joins[c].next_sibling;
        }
        // the child list is newest first: walk it to the i-th entry, from the last
        for i in (0..n).rev() {
            let mut c = self.joins[owner].first_child;
            for _ in 0..i {
                c = self.joins[c].next_sibling;
            }
            self.drop_copy_supports(t, c);
        }
        // (a support whose successor went with a removed rule)
        if self.token_deps[t.ix()] != NONE {
            self.drop_copy_supports(t, JoinId::NONE);
        }
    }

    #[inline(never)]
    fn drop_copy_supports(&mut self, t: TokenId, succ: JoinId) {
        let mut s = self.token_deps[t.ix()];
        let mut kept_last = NONE;
        while s != NONE {
            let e = self.supports[s as usize];
            if succ != JoinId::NONE && e.succ != succ {
                // another copy's support stays on the list
                kept_last = s;
                s = e.next_of_token;
                continue;
            }
            if kept_last == NONE {
                self.token_deps[t.ix()] = e.next_of_token;
            } else {
                self.supports[kept_last as usize].next_of_token = e.next_of_token;
            }
            let fact = e.fact;
            // off the fact's list
            let head = self.fact_deps[fact as usize];
            if head == s {
                self.fact_deps[fact as usize] = e.next_of_fact;
            } else {
                let mut p = head;
                while p != NONE {
                    let n = self.supports[p as usize].next_of_fact;
                    if n == s {
                        self.supports[p as usize].next_of_fact = e.next_of_fact;
                        break;
                    }
                    p = n;
                }
            }
            if self.fact_deps[fact as usize] == NONE
                && !self.st.logical.detach
                && !self.is_held(fact)
            {
                // the entry itself goes on the unsupported stack
                self.supports[s as usize] = crate::logical::Support {
                    token: TokenId::NONE,
                    succ: JoinId::NONE,
                    fact,
                    next_of_token: self.st.logical.unsupported,
                    next_of_fact: NONE,
                };
                self.st.logical.unsupported = s;
                #[cfg(feature = "host-speedups")]
                {
                    let on = &mut self.facts[fact as usize].unsupported;
                    *on = on.saturating_add(1);
                }
            } else {
                self.free_support(s);
            }
            s = e.next_of_token;
        }
    }

    /// Retracts the facts that lost their last support, newest first, and those
    /// their retraction leaves unsupported (CLIPS's `ForceLogicalRetractions`). Called
    /// at the end of every retract and assert; nested ones leave it to the outer.
    #[inline(always)]
    pub(crate) fn force_logical_retractions(&mut self) {
        if self.st.logical.unsupported == NONE || self.st.logical.forcing {
            return;
        }
        self.retract_unsupported();
    }

    #[inline(never)]
    fn retract_unsupported(&mut self) {
        self.st.logical.forcing = true;
        while self.st.logical.unsupported != NONE {
            let s = self.st.logical.unsupported;
            let fact = self.supports[s as usize].fact;
            self.st.logical.unsupported = self.supports[s as usize].next_of_token;
            self.free_support(s);
            #[cfg(feature = "host-speedups")]
            {
                let on = &mut self.facts[fact as usize].unsupported;
                if *on != u16::MAX {
                    *on = on.saturating_sub(1);
                }
            }
            if self.facts[fact as usize].state == crate::fact::FactState::Live {
                self.retract_fact(fact);
            }
        }
        self.st.logical.forcing = false;
    }

    /// While `on`, partial matches that go take their supports along without
    /// retracting anything (`LogicalState::detach`); returns the previous setting.
    pub(crate) fn detach_supports(&mut self, on: bool) -> bool {
        core::mem::replace(&mut self.st.logical.detach, on)
    }

    /// Rule `rule` is removed: the copies of its logical partial matches go with its
    /// joins unless another rule shares that path, and the facts they support keep
    /// only their other supports (CLIPS retracts nothing then).
    pub(crate) fn detach_rule_supports(&mut self, rule: Ix) {
        let succ = self.rule_logical_join(rule);
        if succ == JoinId::NONE || self.st.logical.live == 0 || self.joins[succ].refs > 1 {
            return;
        }
        let detach = self.detach_supports(true);
        let mut t = self.join_mems[self.joins[succ].parent].mem;
        while t != TokenId::NONE {
            if self.token_deps[t.ix()] != NONE {
                self.drop_copy_supports(t, succ);
            }
            t = self.tokens[t].mem_next;
        }
        self.detach_supports(detach);
    }

    /// Forgets every support (`clear`; tokens and facts are wiped with them).
    pub(crate) fn logical_clear(&mut self) {
        for s in self.supports.iter_mut() {
            *s = crate::logical::Support::EMPTY;
        }
        for d in self.token_deps.iter_mut() {
            *d = NONE;
        }
        for d in self.fact_deps.iter_mut() {
            *d = NONE;
        }
        for r in self.rule_logical.iter_mut() {
            *r = JoinId::NONE;
        }
    }

    /// `(dependencies fact)`: the partial matches supporting the fact, one per line,
    /// or `None`.
    pub(crate) fn print_dependencies(&mut self, fact: Ix) {
        // (no support before a rule with `logical` exists: the heads are not kept)
        let mut s = if self.st.logical.defined {
            self.fact_deps[fact as usize]
        } else {
            NONE
        };
        if s == NONE {
            self.write(crate::host::router::WDISPLAY, "None\n");
            return;
        }
        while s != NONE {
            let e = self.supports[s as usize];
            let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
            let _ = self.write_basis(&mut b, e.token);
            let _ = core::fmt::Write::write_str(&mut b, "\n");
            self.write(crate::host::router::WDISPLAY, b.as_str());
            s = e.next_of_fact;
        }
    }

    /// `(dependents fact)`: the facts (in fact-list order) one of whose supporting
    /// partial matches holds the fact, on one line, or `None`.
    pub(crate) fn print_dependents(&mut self, fact: Ix) {
        let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
        let mut found = false;
        // (no support before a rule with `logical` exists: the heads are not kept)
        let mut f = if self.st.logical.defined {
            self.st.facts.fact_head
        } else {
            NONE
        };
        while f != NONE {
            let mut s = self.fact_deps[f as usize];
            while s != NONE {
                let e = self.supports[s as usize];
                if self.token_holds(e.token, fact) {
                    if found {
                        self.flush_if_full(&mut b);
                        let _ = core::fmt::Write::write_str(&mut b, ",");
                    }
                    let _ = core::fmt::Write::write_fmt(
                        &mut b,
                        format_args!("f-{}", self.facts[f as usize].num),
                    );
                    found = true;
                    break;
                }
                s = e.next_of_fact;
            }
            f = self.facts[f as usize].next;
        }
        let _ = core::fmt::Write::write_str(&mut b, if found { "\n" } else { "None\n" });
        self.write(crate::host::router::WDISPLAY, b.as_str());
    }

    /// Writes out a nearly full line buffer (long dependents lists).
    fn flush_if_full(&mut self, b: &mut crate::value::TextBuf<512>) {
        if b.as_str().len() > 480 {
            self.write(crate::host::router::WDISPLAY, b.as_str());
            *b = crate::value::TextBuf::new();
        }
    }

    /// Whether partial match `t` binds fact `fact` at one of its patterns.
    fn token_holds(&self, mut t: TokenId, fact: Ix) -> bool {
        while t != TokenId::NONE && self.tokens[t].owner != JoinId::ROOT {
            let tk = &self.tokens[t];
            if tk.am != TokenId::NONE && self.tokens[tk.am].fact == fact {
                return true;
            }
            t = tk.parent;
        }
        false
    }
}

#[cfg(all(test, feature = "logical", feature = "parser"))]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::testutil::CaptureHost;
    use std::boxed::Box;
    use std::string::String;

    /// Runs `src` as a batch on a fresh engine, checks its invariants, and returns the
    /// `(facts)` listing after it.
    fn facts_after(src: &str) -> String {
        let mut e = Box::new(SmallEngine::new());
        let mut h = CaptureHost::default();
        e.batch_str(&mut h, src, false);
        if let Err(v) = e.check_invariants() {
            panic!("{v}\n{}", h.out);
        }
        h.out.clear();
        e.batch_str(&mut h, "(facts)", false);
        h.out
    }

    #[test]
    fn retract_cascades_and_unconditional_facts_stay() {
        let rules = "(defrule r1 (logical (a ?x)) => (assert (b ?x)) (assert (c ?x)))
                     (defrule r2 (logical (b ?x)) => (assert (d ?x)))
                     (reset)
(assert (a 1) (a 2))
(run)
";
        let all = facts_after(rules);
        for f in ["(b 1)", "(c 1)", "(d 1)", "(b 2)", "(d 2)"] {
            assert!(all.contains(f), "{f} missing:\n{all}");
        }
        // (c 1) asserted again at the top level loses its logical support
        let after = facts_after(&std::format!("{rules}(assert (c 1))\n(retract 1)\n"));
        assert!(after.contains("(c 1)"), "{after}");
        for f in ["(a 1)", "(b 1)", "(d 1)"] {
            assert!(!after.contains(f), "{f} stayed:\n{after}");
        }
        assert!(after.contains("(d 2)"), "{after}");
    }

    #[test]
    fn a_blocked_not_takes_its_support_and_several_supports_hold() {
        let rules = "(defrule r (logical (a ?x) (not (z))) => (assert (e)))
                     (reset)
(assert (a 1) (a 2))
(run)
";
        assert!(facts_after(rules).contains("(e)"));
        // one of two supports gone: (e) stays
        assert!(facts_after(&std::format!("{rules}(retract 1)\n")).contains("(e)"));
        // both gone by blocking the not
        assert!(!facts_after(&std::format!("{rules}(assert (z))\n")).contains("(e)"));
    }

    #[test]
    fn a_rule_losing_its_own_support_asserts_nothing_more() {
        let out = facts_after(
            "(defrule r (logical ?f <- (k)) => (retract ?f) (assert (after)))
             (reset)
(assert (k))
(run)
",
        );
        assert!(!out.contains("(after)"), "{out}");
    }

    #[test]
    fn misplaced_logical_ces_are_refused() {
        for bad in [
            "(defrule x (a) (logical (b)) => (assert (c)))",
            "(defrule x (logical (a)) (b) (logical (c)) => (assert (d)))",
            "(defrule x (not (logical (a))) =>)",
            "(defrule x (logical) =>)",
        ] {
            let mut e = Box::new(SmallEngine::new());
            let mut h = CaptureHost::default();
            e.batch_str(&mut h, bad, false);
            h.out.clear();
            e.batch_str(&mut h, "(rules)", false);
            assert!(!h.out.contains('x'), "{bad} was defined: {}", h.out);
        }
    }
}
