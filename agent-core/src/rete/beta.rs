//! Beta side: joins combining partial matches (left) with alpha matches (right),
//! negation and existence (one blocker per output, as CLIPS), joins from the right
//! for not/exists over several CEs, token deletion, and handing complete matches to
//! the agenda.
//!
//! Joins with an identical prefix are shared between rules (as CLIPS does), so a
//! token may feed several child joins. A `not`/`exists` join keeps one output token
//! per left token, blocked by the first matching right item (listed in that item's
//! `blocks`, through the output's own alpha-sibling links: no token more); it is
//! *active* (passed on) while unblocked (`not`) or blocked (`exists`). When the
//! blocker goes, the next matching right item takes over before anything changes.

#[cfg(feature = "host-speedups")]
use super::index::OrValues;
use super::{JoinId, JoinKind, PatBinding, Token, TokenId, TokenKind};
use crate::engine::Core;
use crate::error::{CapacityError, EvalError, Pool};
use crate::handle::Slots;
use crate::value::Ix;
use crate::value::NONE;

/// `Core::dying_reach`: a left pattern has the retracted fact's template.
const REACH_LEFT: u8 = 1;
/// `Core::dying_reach`: a pattern below the not join has it.
const REACH_BELOW: u8 = 2;

/// Host: what `unblock` asks of an alpha blocker, when its caller knows it
/// (`unblock_alpha_head`).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy)]
pub(crate) struct AlphaBlocker {
    /// Whether it is its fact's last alpha match (`next_sib == NONE`).
    pub(crate) last: bool,
    /// Its fact.
    pub(crate) fact: Ix,
}

#[cfg(feature = "host-speedups")]
type Known = Option<AlphaBlocker>;
#[cfg(feature = "host-speedups")]
const KNOWN_NONE: Known = None;
#[cfg(not(feature = "host-speedups"))]
type Known = ();
#[cfg(not(feature = "host-speedups"))]
const KNOWN_NONE: Known = ();

impl Core<'_> {
    pub(crate) fn alloc_token(&mut self) -> Result<TokenId, CapacityError> {
        if self.st.pools.token_free != TokenId::NONE {
            let t = self.st.pools.token_free;
            self.st.pools.token_free = self.tokens[t].next_sib;
            // no high-water mark to raise: with a free entry, live + 1 <= used,
            // and the mark reached `used` when the last fresh entry was taken
            // (`clear` keeps the mark)
            self.st.pools.tokens_live += 1;
            return Ok(t);
        }
        let n = self.st.pools.tokens_used as usize;
        if n >= self.tokens.len() || n >= NONE as usize {
            crate::engine::full_pool!(self, Pool::Tokens, n + 1, self.tokens.len());
        }
        self.st.pools.tokens_used += 1;
        self.st.pools.tokens_live += 1;
        self.note_hw(Pool::Tokens, self.st.pools.tokens_live as usize);
        Ok(TokenId::at(n))
    }

    pub(crate) fn free_token(&mut self, t: TokenId) {
        // the facts a partial match supports lose that support (`logical`)
        #[cfg(feature = "logical")]
        if self.logical_in_use() {
            self.token_leaves(t);
        }
        self.release_token(t);
    }

    /// `free_token` for a token no logical support can hang on and that cannot be the
    /// firing rule's logical partial match: an alpha match (supports hang on partial
    /// matches of joins), or any token while truth maintenance is idle
    /// (`logical_in_use` false, as whole-memory removal requires: `wipe`). Saves the
    /// truth-maintenance check on the removal paths every retract runs.
    #[inline(always)]
    pub(crate) fn release_token(&mut self, t: TokenId) {
        if self.st.net.lhs_of == t {
            self.st.net.lhs_of = TokenId::NONE;
        }
        // a reused id must not find this match's key
        if self.st.cache.key_cache.0 == t {
            self.st.cache.key_cache.0 = TokenId::NONE;
        }
        // only the free-list link and the kind: every `alloc_token` caller writes
        // the whole token
        let tk = &mut self.tokens[t];
        tk.kind = TokenKind::Free;
        tk.next_sib = self.st.pools.token_free;
        self.st.pools.token_free = t;
        self.st.pools.tokens_live -= 1;
    }

    /// Whether a partial match is passed on to child joins / the agenda.
    pub(crate) fn token_active(&self, t: TokenId) -> bool {
        let tk = &self.tokens[t];
        match self.joins[tk.owner].kind {
            // an owed output (see `owe`) passes nothing on until it is paid
            JoinKind::Negative => !tk.blocked && tk.am_prev == TokenId::NONE,
            JoinKind::Exists => tk.blocked,
            _ => true,
        }
    }

    /// Host: `token_active` for a token of a join of kind `kind`, known to the caller.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn active_in(&self, t: TokenId, kind: JoinKind) -> bool {
        let tk = &self.tokens[t];
        match kind {
            JoinKind::Negative => !tk.blocked && tk.am_prev == TokenId::NONE,
            JoinKind::Exists => tk.blocked,
            _ => true,
        }
    }

    /// Fills `lhs_pm` with the pattern bindings along a token's ancestry (pattern
    /// depths along an ancestry are contiguous from 0, so every entry up to the
    /// token's depth is written).
    pub(crate) fn bind_left(&mut self, mut t: TokenId) {
        let cur = self.st.net.lhs_of;
        if cur == t {
            return;
        }
        if cur != TokenId::NONE && t != TokenId::NONE && self.bound_by(t, cur) {
            self.st.net.lhs_of = t;
            return;
        }
        self.st.net.lhs_of = t;
        while t != TokenId::NONE {
            let tk = self.tokens[t];
            let j = self.joins[tk.owner];
            if j.kind == JoinKind::Root {
                break;
            }
            self.st.net.lhs_pm[j.depth as usize] = if tk.am != TokenId::NONE {
                let a = self.tokens[tk.am];
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

    /// Whether `lhs_pm`, holding the ancestry of `cur`, holds that of `t` after
    /// at most writing `t`'s own level: `cur` is `t`'s parent (one level added)
    /// or `cur` descends from `t` (its entries up to `t`'s depth are `t`'s).
    fn bound_by(&mut self, t: TokenId, cur: TokenId) -> bool {
        let tk = self.tokens[t];
        let j = self.joins[tk.owner];
        if j.kind == JoinKind::Root {
            return false;
        }
        if tk.parent == cur {
            self.st.net.lhs_pm[j.depth as usize] = if tk.am != TokenId::NONE {
                let a = self.tokens[tk.am];
                PatBinding {
                    fact: a.fact,
                    marks: a.marks,
                }
            } else {
                PatBinding::EMPTY
            };
            return true;
        }
        let mut c = cur;
        loop {
            if c == t {
                return true;
            }
            let ck = &self.tokens[c];
            let cj = &self.joins[ck.owner];
            if cj.kind == JoinKind::Root || cj.depth <= j.depth {
                return false;
            }
            c = ck.parent;
        }
    }

    fn eval_lhs_tests(&mut self, tests: Ix) -> Result<bool, EvalError> {
        let saved = self.st.net.pm_rhs;
        self.st.net.pm_rhs = false;
        let r = self.eval_tests(tests);
        self.st.net.pm_rhs = saved;
        r
    }

    /// Evaluates a join's tests for left token `left` and alpha match `am`.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn join_test(&mut self, join: JoinId, left: TokenId, am: TokenId) -> Result<bool, EvalError> {
        let (tests, depth) = self.join_test_fields(join);
        self.join_test_with(join, tests, depth, left, am, &mut false)
    }

    /// The join's `tests` and `depth`, read once for a loop of `join_test_with`.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn join_test_fields(&self, join: JoinId) -> (Ix, u8) {
        let j = &self.joins[join];
        (j.tests, j.depth)
    }

    /// `join_test` with the join's fields from `join_test_fields`. `planned`: the
    /// join's test plan is known to be cached (set here once the plan answers, so a
    /// loop over candidates checks the cache once; callers clear it after a
    /// propagation, which may evict it).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn join_test_with(
        &mut self,
        join: JoinId,
        tests: Ix,
        depth: u8,
        left: TokenId,
        am: TokenId,
        planned: &mut bool,
    ) -> Result<bool, EvalError> {
        self.join_test_skip(join, tests, depth, left, am, planned, NONE)
    }

    /// Host: `join_test_with` for candidate `am` of an or-lookup, whose or test
    /// (`OrValues::or`) `or_match` answered `known`: a candidate it fails is
    /// rejected unseen (the tests before it report nothing, `or_values`), and one it
    /// passes is tested without it (a compiled plan leaves it out).
    #[cfg(feature = "host-speedups")]
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn or_join_test(
        &mut self,
        join: JoinId,
        (tests, depth): (Ix, u8),
        left: TokenId,
        am: TokenId,
        planned: &mut bool,
        ov: &OrValues,
        known: Option<bool>,
    ) -> Result<bool, EvalError> {
        match known {
            Some(false) => Ok(false),
            Some(true) => self.join_test_skip(join, tests, depth, left, am, planned, ov.or),
            None => self.join_test_with(join, tests, depth, left, am, planned),
        }
    }

    /// `join_test_with`, where the join's test `skip` (host: a top-level test of the
    /// chain, NONE for none) is known to hold for `left` and `am`: only a compiled
    /// plan leaves it out, every other path runs all the tests.
    #[allow(clippy::too_many_arguments)]
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn join_test_skip(
        &mut self,
        join: JoinId,
        tests: Ix,
        depth: u8,
        left: TokenId,
        am: TokenId,
        planned: &mut bool,
        skip: Ix,
    ) -> Result<bool, EvalError> {
        if tests == NONE {
            return Ok(true);
        }
        let right_fact = if am != TokenId::NONE {
            self.tokens[am].fact
        } else {
            NONE
        };
        self.bind_for_quick(left);
        if let Some(r) = self.planned_join_test(join, tests, depth, left, right_fact, planned, skip)
        {
            return Ok(r);
        }
        // the evaluator may do anything to the cache
        *planned = false;
        self.join_test_eval(join, left, am)
    }

    /// `join_test` through the evaluator (kept out of line: the planned test is
    /// inlined into the join loops on the host).
    #[inline(never)]
    fn join_test_eval(
        &mut self,
        join: JoinId,
        left: TokenId,
        am: TokenId,
    ) -> Result<bool, EvalError> {
        // one walk up the ancestry per left token, not one per candidate
        self.bind_left(left);
        let j = self.joins[join];
        // the join's own depth lies below `left`'s ancestry: `left` stays bound
        self.st.net.lhs_pm[j.depth as usize] = if am != TokenId::NONE {
            let a = self.tokens[am];
            PatBinding {
                fact: a.fact,
                marks: a.marks,
            }
        } else {
            PatBinding::EMPTY
        };
        // host: tests of fields bound after multifields, read by the marks just bound
        #[cfg(feature = "host-speedups")]
        if self.st.cache.compiled_plans.marked_any {
            if let Some(r) = self.marked_join_test(join, j.tests, j.depth) {
                return Ok(r);
            }
        }
        // host: `member$` of a segment and equal multifields, read in place; the
        // evaluator takes the tests from the first it must decide
        #[cfg(feature = "host-speedups")]
        let tests = match self.quick_join_tests(j.tests) {
            Ok(rest) => rest,
            Err(r) => return Ok(r),
        };
        #[cfg(not(feature = "host-speedups"))]
        let tests = j.tests;
        match self.eval_lhs_tests(tests) {
            // CLIPS reports a failing join test and takes it as false (a not CE's as
            // true: the fact blocks); the assert goes on, then execution halts
            Err(e) if !e.is_capacity() => {
                self.report_join_error(join, e);
                Ok(j.kind == JoinKind::Negative)
            }
            r => r,
        }
    }

    /// `[DRIVE1]`: an error while testing a join (out of line: errors are rare).
    #[inline(never)]
    fn report_join_error(&mut self, join: JoinId, e: EvalError) {
        use core::fmt::Write;
        self.st.net.pattern_error = true;
        self.st.mode.halting = true;
        self.report_eval_error(e);
        let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
        let _ = b.write_str(
            "\n[DRIVE1] This error occurred in the join network\n   Problem resides in associated join\n",
        );
        self.write(crate::host::router::WERROR, b.as_str());
        self.write_rules_below(join, self.joins[join].depth as usize + 1);
        self.write(crate::host::router::WERROR, "\n");
    }

    /// Whether child token `c` belongs to the front of its parent's child list:
    /// not/exists outputs (at most one per child join), see `link_token`.
    fn in_front_run(&self, c: TokenId) -> bool {
        let tk = &self.tokens[c];
        matches!(
            self.joins[tk.owner].kind,
            JoinKind::Negative | JoinKind::Exists
        )
    }

    /// The output token of a not/exists `join` for left token `left`, if any. Only the
    /// front run of the child list is walked: a left token can have any number of
    /// positive children (the root token one per fact of a rule's first pattern), and
    /// walking them made every right activation of a leading `not` linear.
    fn output_of(&self, left: TokenId, join: JoinId) -> TokenId {
        let mut c = self.tokens[left].first_child;
        while c != TokenId::NONE && self.in_front_run(c) {
            if self.tokens[c].owner == join {
                return c;
            }
            c = self.tokens[c].next_sib;
        }
        TokenId::NONE
    }

    /// The last token of `parent`'s front run of children (NONE if the run is
    /// empty) and the child after it, for a new child of positive `join` (a child
    /// of `join` itself ends the run without looking at its join).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn front_run_end(&self, parent: TokenId, join: JoinId) -> (TokenId, TokenId) {
        let mut last = TokenId::NONE;
        let mut c = self.tokens[parent].first_child;
        while c != TokenId::NONE {
            let tk = &self.tokens[c];
            if tk.owner == join || !self.in_front_run(c) {
                break;
            }
            last = c;
            c = tk.next_sib;
        }
        (last, c)
    }

    /// A new alpha match arrives on the right of `join`. (Host: inlined into
    /// `add_alpha_match`, as when that had one caller: the CLIPS-order path of
    /// `rete::mforder` made it two, and LLVM then called this out of line, +1.5 % on
    /// the LLSF benchmark.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn right_activate(&mut self, join: JoinId, am: TokenId) -> Result<(), EvalError> {
        let j = self.joins[join];
        // host: no partial match on the left (often: a fact of a later pattern came
        // first) meets nothing, before the primed-order check below: a primed join's
        // walk would find none of its partial matches live either (its entry then
        // goes on its next right activation or `prune_prime_orders`, not here)
        #[cfg(feature = "host-speedups")]
        if self.join_mems[j.parent].mem == TokenId::NONE {
            return Ok(());
        }
        // the left tokens are all the parent join's: only not/exists outputs can
        // be inactive
        let all_active = !matches!(
            self.joins[j.parent].kind,
            JoinKind::Negative | JoinKind::Exists
        );
        // host: a join primed while its parent had partial matches meets those in
        // its own order (`rete::order`)
        // (host: or the new alpha match may have an older twin, `twin_blocks`)
        #[cfg(feature = "grow")]
        if self.st.prime.slow != 0 {
            return self.right_activate_maybe_primed(join, am, all_active);
        }
        // host: every left token is the parent join's (`first_left` walks its memory
        // or its bucket, which `next_left_of` skips to its own), so its kind is read
        // once, and the owner is not read again per token
        #[cfg(feature = "host-speedups")]
        let parent_kind = self.joins[j.parent].kind;
        let (mut l, via) = self.first_left(join, am);
        while l != TokenId::NONE {
            #[cfg(feature = "host-speedups")]
            let (next, active) = (
                self.next_left_of(l, via, j.parent),
                all_active || self.active_in(l, parent_kind),
            );
            #[cfg(not(feature = "host-speedups"))]
            let (next, active) = (self.next_left(l, via), all_active || self.token_active(l));
            if active {
                match j.kind {
                    JoinKind::Positive => {
                        if self.join_test(join, l, am)? {
                            let t = self.link_token(join, l, am)?;
                            self.propagate_in(t, join)?;
                        }
                    }
                    JoinKind::Negative | JoinKind::Exists => {
                        let t = self.output_of(l, join);
                        // a blocked output keeps its one blocker (CLIPS's order)
                        if t != TokenId::NONE
                            && !self.tokens[t].blocked
                            && self.join_test(join, l, am)?
                        {
                            self.block(t, am)?;
                        }
                    }
                    JoinKind::Root | JoinKind::Test | JoinKind::Terminal => {}
                }
            }
            l = next;
        }
        Ok(())
    }

    /// Host: `right_activate` while some join keeps a primed order (`rete::order`),
    /// or for an alpha match that may have an older twin (`twin_blocks`): out of
    /// line, so that the usual walk stays as it was without them.
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn right_activate_maybe_primed(
        &mut self,
        join: JoinId,
        am: TokenId,
        all_active: bool,
    ) -> Result<(), EvalError> {
        #[cfg(feature = "host-speedups")]
        if self.st.prime.slow & super::order::SLOW_TWIN != 0 {
            let tw = self.st.prime.twin;
            if tw.0 != am || tw.1 == join {
                // the last join it was marked for, or left from an earlier match
                self.st.prime.slow &= !super::order::SLOW_TWIN;
            }
            if tw.0 == am && self.twin_blocks(join, am) {
                return Ok(());
            }
        }
        if let Some(k) = self.primed_entry(join) {
            return self.right_activate_primed(join, am, k, all_active);
        }
        let kind = self.joins[join].kind;
        let (mut l, via) = self.first_left(join, am);
        while l != TokenId::NONE {
            let next = self.next_left(l, via);
            if all_active || self.token_active(l) {
                self.right_one(join, kind, l, am)?;
            }
            l = next;
        }
        Ok(())
    }

    /// Alpha match `am` on the right of `join` (of `kind`) meets active left token `l`
    /// (the walks of `rete::order`; `right_activate` keeps its own copy inline: calling
    /// this there cost llsf-10's run 186.54 -> 186.98 M instructions, callgrind).
    #[cfg(feature = "grow")]
    #[inline(always)]
    pub(crate) fn right_one(
        &mut self,
        join: JoinId,
        kind: JoinKind,
        l: TokenId,
        am: TokenId,
    ) -> Result<(), EvalError> {
        match kind {
            JoinKind::Positive => {
                if self.join_test(join, l, am)? {
                    let t = self.link_token(join, l, am)?;
                    self.propagate_in(t, join)?;
                }
            }
            JoinKind::Negative | JoinKind::Exists => {
                let t = self.output_of(l, join);
                // a blocked output keeps its one blocker (CLIPS's order)
                if t != TokenId::NONE && !self.tokens[t].blocked && self.join_test(join, l, am)? {
                    self.block(t, am)?;
                }
            }
            JoinKind::Root | JoinKind::Test | JoinKind::Terminal => {}
        }
        Ok(())
    }

    /// A partial match `r` of a subnetwork became active: it blocks the output of
    /// the not/exists join `join` for the left token it extends (host: for every left
    /// token, in memory order, when the subnetwork is free: `sub_is_free`).
    fn right_activate_beta(&mut self, join: JoinId, r: TokenId) -> Result<(), EvalError> {
        let parent = self.joins[join].parent;
        #[cfg(feature = "grow")]
        if self.sub_is_free(join) {
            let mut l = self.join_mems[parent].mem;
            while l != TokenId::NONE {
                let next = self.tokens[l].mem_next;
                let t = self.output_of(l, join);
                if t != TokenId::NONE && !self.tokens[t].blocked {
                    self.block(t, r)?;
                }
                l = next;
            }
            return Ok(());
        }
        let l = self.ancestor_in(r, parent);
        if l == TokenId::NONE {
            return Ok(());
        }
        let t = self.output_of(l, join);
        if t != TokenId::NONE && !self.tokens[t].blocked {
            self.block(t, r)?;
        }
        Ok(())
    }

    /// Links `blocker` to not/exists output `t` and passes on or takes back.
    fn block(&mut self, t: TokenId, blocker: TokenId) -> Result<(), EvalError> {
        if self.joins[self.tokens[t].owner].kind == JoinKind::Negative {
            // blocked again before its propagation was paid: nothing is owed any more
            // (first: the owed list and the blocker list share the links)
            if self.is_owed(t) {
                self.unowe(t);
            }
            self.add_link(t, blocker);
            self.deactivate(t);
            // a blocked not output is no partial match for CLIPS: its support goes
            #[cfg(feature = "logical")]
            if self.logical_in_use() {
                self.token_leaves(t);
            }
            Ok(())
        } else {
            self.add_link(t, blocker);
            self.move_to_front(t);
            self.propagate(t)
        }
    }

    /// A not/exists output that becomes active goes to the front of its memory: CLIPS
    /// copies it into its successors' memories only now, so they meet it as newest.
    /// (Host: inlined up to the check for a token at the front already, most of the
    /// calls in llsf-10, which then cost no call; `move_to_front_rest` out of line.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn move_to_front(&mut self, t: TokenId) {
        // host: it enters its successors' memories now (`rete::order`)
        #[cfg(feature = "grow")]
        if !self.st.prime.joins.is_empty() {
            self.stamp(t);
        }
        let join = self.tokens[t].owner;
        if self.join_mems[join].mem == t {
            // host: in its bucket already, unless the index's build left it out
            #[cfg(feature = "host-speedups")]
            if self.left_out(t, join) {
                self.index_left_out(t, join);
            }
            return;
        }
        self.move_to_front_rest(t, join);
    }

    /// `move_to_front` for `t`, of `join`, not at the front of its memory. (The
    /// image: one function, as before.)
    #[cfg_attr(feature = "host-speedups", inline(never))]
    #[cfg_attr(not(feature = "host-speedups"), inline(always))]
    fn move_to_front_rest(&mut self, t: TokenId, join: JoinId) {
        // host: a partial match whose index is its group-0 bucket alone stays in that
        // bucket (its key, so its tag, is the same): taken out here, put back at the
        // head below, as `beta_index_insert` would (see `index_front_take`)
        #[cfg(all(feature = "host-speedups", feature = "grow"))]
        let kept = self.index_front_take(t, join);
        #[cfg(not(all(feature = "host-speedups", feature = "grow")))]
        self.beta_index_remove(t);
        // one borrow of the pool for the relinking (its address stays in a register
        // across the stores)
        let head = self.join_mems[join].mem;
        let mut tokens = self.tokens.view();
        let (prev, next) = (tokens[t].mem_prev, tokens[t].mem_next);
        if prev != TokenId::NONE {
            tokens[prev].mem_next = next;
        }
        if next != TokenId::NONE {
            tokens[next].mem_prev = prev;
        }
        tokens[t].mem_prev = TokenId::NONE;
        tokens[t].mem_next = head;
        if head != TokenId::NONE {
            tokens[head].mem_prev = t;
        }
        self.join_mems[join].mem = t;
        #[cfg(all(feature = "host-speedups", feature = "grow"))]
        if let Some(b) = kept {
            self.index_front_put(t, join, b);
            return;
        }
        self.beta_index_insert(t);
    }

    /// The ancestor of `t` in the memory of `join` (NONE if it has none there).
    fn ancestor_in(&self, mut t: TokenId, join: JoinId) -> TokenId {
        while t != TokenId::NONE {
            let tk = &self.tokens[t];
            if tk.owner == join {
                return t;
            }
            if tk.owner == JoinId::ROOT {
                break;
            }
            t = tk.parent;
        }
        TokenId::NONE
    }

    /// Host: whether the subnetwork feeding join from the right `join` reads no
    /// variable of the patterns before it, or `join` follows another join from the
    /// right on its left path whose subnetwork does (program 415; out of line: the
    /// walks of plain nots inline its callers). CLIPS's join then has no test, and
    /// `drive.c` checks no descent either: any of the subnetwork's partial matches
    /// blocks every left partial match (which one, and the order of what a group
    /// unblocks, show in the activations). (One whose subnetwork shares variables
    /// blocks those agreeing on them in CLIPS; here only its own: not reproduced.)
    #[cfg(feature = "grow")]
    #[inline(always)]
    fn sub_is_free(&mut self, join: JoinId) -> bool {
        let jm = &self.join_mems[join];
        if jm.free_gen == self.st.net.net_gen {
            return jm.free;
        }
        let free = self.work_out_free(join);
        let jm = &mut self.join_mems[join];
        jm.free = free;
        jm.free_gen = self.st.net.net_gen;
        free
    }

    /// `sub_is_free` for a network generation not seen yet (out of line).
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn work_out_free(&self, join: JoinId) -> bool {
        let j = &self.joins[join];
        let parent = j.parent;
        if parent == JoinId::ROOT || j.rjoin == JoinId::NONE {
            return false;
        }
        // CLIPS 6.30 gives no test either to a join from the right that follows
        // another one on its left path whose subnetwork reads variables of the
        // patterns before it: there any subnetwork match blocks every left match,
        // whatever the variables it shares (program 415)
        let mut s = parent;
        while s != JoinId::ROOT && s != JoinId::NONE {
            let sj = &self.joins[s];
            if sj.rjoin != JoinId::NONE
                && sj.parent != JoinId::ROOT
                && self.sub_reads_outer(sj.rjoin, sj.parent, self.joins[sj.parent].depth)
            {
                return true;
            }
            s = sj.parent;
        }
        !self.sub_reads_outer(j.rjoin, parent, self.joins[parent].depth)
    }

    /// Host: whether a join on the path from `last` up to (not including) `stop`, or
    /// of a subnetwork nested there, reads a pattern variable of pattern `outer` or an
    /// earlier one (true when the path does not reach `stop`).
    #[cfg(feature = "grow")]
    fn sub_reads_outer(&self, last: JoinId, stop: JoinId, outer: u8) -> bool {
        let mut s = last;
        while s != stop {
            if s == JoinId::NONE || s == JoinId::ROOT {
                return true;
            }
            let sj = &self.joins[s];
            if self.reads_outer(sj.tests, outer)
                || self.reads_outer(sj.post, outer)
                || (sj.rjoin != JoinId::NONE && self.sub_reads_outer(sj.rjoin, sj.parent, outer))
            {
                return true;
            }
            s = sj.parent;
        }
        false
    }

    /// Host: whether the expression chain from `e` reads a pattern variable of
    /// pattern `outer` or an earlier one.
    #[cfg(feature = "grow")]
    fn reads_outer(&self, mut e: Ix, outer: u8) -> bool {
        while e != NONE {
            let x = self.exprs[e as usize];
            if x.op == crate::expr::Op::PatVar {
                if x.aux <= outer {
                    return true;
                }
            } else if !matches!(x.op, crate::expr::Op::Int | crate::expr::Op::Float)
                && x.first != NONE
                && self.reads_outer(x.first, outer)
            {
                return true;
            }
            e = x.next;
        }
        false
    }

    /// The first right item blocking the output of not/exists `join` for left token
    /// `left`: alpha matches from `from` on (memory order; `hashed`: along its index
    /// bucket), or active partial matches
    /// of the subnetwork extending `left` (skipping `skip`).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn find_blocker(
        &mut self,
        join: JoinId,
        left: TokenId,
        from: TokenId,
        hashed: bool,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        let rjoin = self.joins[join].rjoin;
        if rjoin == JoinId::NONE {
            return self.find_alpha_blocker(join, left, from, hashed, skip);
        }
        self.find_sub_blocker(join, rjoin, left, skip)
    }

    /// `find_blocker` for a join fed by an alpha node.
    #[inline(always)]
    fn find_alpha_blocker(
        &mut self,
        join: JoinId,
        left: TokenId,
        from: TokenId,
        hashed: bool,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        #[cfg(not(feature = "host-speedups"))]
        let _ = skip;
        // host: a keyed join with a `?a | ?b` test (out of line: most have none;
        // it ends the search either way, so the usual walk reads the join's
        // fields once, not again after a call that may have changed them)
        #[cfg(feature = "host-speedups")]
        if hashed && from != TokenId::NONE {
            let n = &self.alphas[self.joins[join].alpha as usize];
            if n.rhash.get(n.nrhash as usize).is_some_and(|&f| f != NONE) {
                return self.find_blocker_or(join, left, from, skip);
            }
        }
        self.blocker_walk(join, left, from, hashed)
    }

    /// `find_blocker` for a join fed by a subnetwork `rjoin`: its first active
    /// partial match extending `left` (skipping `skip`), in memory order. (Host: out
    /// of line, so the usual alpha-fed search inlined in `left_activate` stays lean.)
    #[cfg_attr(feature = "host-speedups", inline(never))]
    #[cfg_attr(not(feature = "host-speedups"), inline(always))]
    fn find_sub_blocker(
        &mut self,
        join: JoinId,
        rjoin: JoinId,
        left: TokenId,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        self.sub_blocker_walk(join, rjoin, left, skip)
    }

    /// `find_sub_blocker`'s walk (host: inlined into `unblock_in`, where it cost less
    /// than the call).
    #[inline(always)]
    fn sub_blocker_walk(
        &mut self,
        join: JoinId,
        rjoin: JoinId,
        left: TokenId,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        let parent = self.joins[join].parent;
        let mut r = self.join_mems[rjoin].mem;
        // host: a free subnetwork's first active partial match blocks any left token
        // (not one holding the fact being retracted: CLIPS's `PartialMatchWillBeDeleted`)
        // (oldest first: CLIPS's right memory of a join from the right appends)
        #[cfg(feature = "grow")]
        if self.sub_is_free(join) {
            let dying = self.st.net.dying;
            while r != TokenId::NONE && self.tokens[r].mem_next != TokenId::NONE {
                r = self.tokens[r].mem_next;
            }
            while r != TokenId::NONE {
                if r != skip
                    && self.token_active(r)
                    && (dying == NONE || !self.holds_fact(r, dying))
                {
                    return Ok(r);
                }
                r = self.tokens[r].mem_prev;
            }
            return Ok(TokenId::NONE);
        }
        // host: the partial matches extending `left`, found down its child lists
        // (not the whole memory): the first in memory order among the active ones
        // is the one last put at the front (`rete::Stamp`), as CLIPS's walk finds
        #[cfg(all(feature = "host-speedups", feature = "grow"))]
        if left != TokenId::NONE {
            if let Some(r) = self.sub_first_candidate(parent, rjoin, left, skip) {
                return Ok(r);
            }
        }
        // host: a partial match extending `left` binds the facts `left` binds
        // (`Token::binds`: copied from the parent, only deeper patterns added),
        // so one binding another fact there is passed over without its walk up
        #[cfg(feature = "host-speedups")]
        let lb = match left {
            TokenId::NONE => [NONE; super::BIND_W],
            l => self.tokens[l].binds,
        };
        while r != TokenId::NONE {
            #[cfg(feature = "host-speedups")]
            {
                let rb = &self.tokens[r].binds;
                if lb.iter().zip(rb).any(|(&l, &b)| l != NONE && l != b) {
                    r = self.tokens[r].mem_next;
                    continue;
                }
            }
            if r != skip && self.token_active(r) && self.ancestor_in(r, parent) == left {
                return Ok(r);
            }
            r = self.tokens[r].mem_next;
        }
        Ok(TokenId::NONE)
    }

    /// Host: the first in memory order of the active partial matches of subnetwork
    /// join `rjoin` (skipping `skip`) extending `left` of join `parent`, found down
    /// the child lists through the subnetwork's joins: the one with the newest
    /// stamp (NONE when there is none), `None` when the subnetwork is deeper than
    /// 8 joins or the stamps are off.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    #[inline(never)]
    fn sub_first_candidate(
        &self,
        parent: JoinId,
        rjoin: JoinId,
        left: TokenId,
        skip: TokenId,
    ) -> Option<TokenId> {
        if self.st.stamps_off {
            return None;
        }
        let mut path = [JoinId::NONE; 8];
        let mut n = 0;
        let mut s = rjoin;
        while s != parent {
            if s == JoinId::NONE || s == JoinId::ROOT || n == path.len() {
                return None;
            }
            path[n] = s;
            n += 1;
            s = self.joins[s].parent;
        }
        let path = &mut path[..n];
        path.reverse();
        let mut found = (TokenId::NONE, 0);
        self.sub_candidates(path, left, skip, &mut found);
        Some(found.0)
    }

    /// Host: `sub_first_candidate`'s search below `t` along `path` (the joins
    /// still to go down), keeping in `found` the active one with the newest stamp.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    fn sub_candidates(
        &self,
        path: &[JoinId],
        t: TokenId,
        skip: TokenId,
        found: &mut (TokenId, crate::rete::Stamp),
    ) {
        // two joins to go (the usual `not (and A B)`): both levels walked here, the
        // last join's kind read once, without a call per partial match of the first
        if let [j, last] = *path {
            let kind = self.joins[last].kind;
            let mut c = self.tokens[t].first_child;
            while c != TokenId::NONE {
                let tc = &self.tokens[c];
                if tc.owner == j {
                    let mut g = tc.first_child;
                    while g != TokenId::NONE {
                        let tg = &self.tokens[g];
                        if tg.owner == last && g != skip && self.active_in(g, kind) {
                            let s = self.stamp_of(g);
                            if found.0 == TokenId::NONE || s > found.1 {
                                *found = (g, s);
                            }
                        }
                        g = tg.next_sib;
                    }
                }
                c = tc.next_sib;
            }
            return;
        }
        let Some((&j, rest)) = path.split_first() else {
            return;
        };
        let mut c = self.tokens[t].first_child;
        while c != TokenId::NONE {
            if self.tokens[c].owner == j {
                if !rest.is_empty() {
                    self.sub_candidates(rest, c, skip, found);
                } else if c != skip && self.token_active(c) {
                    let s = self.stamp_of(c);
                    if found.0 == TokenId::NONE || s > found.1 {
                        *found = (c, s);
                    }
                }
            }
            c = self.tokens[c].next_sib;
        }
    }

    /// Host: the stamp of `t` (0 if it has none).
    #[cfg(feature = "grow")]
    #[inline(always)]
    fn stamp_of(&self, t: TokenId) -> crate::rete::Stamp {
        self.st.stamps.get(t.ix()).copied().unwrap_or(0)
    }

    /// Host: `t` goes (went just now) to the front of its memory: it gets the next
    /// stamp. (Once the count is used up, the memories feeding joins from the right
    /// are numbered again in their order.)
    #[cfg(feature = "grow")]
    #[inline(always)]
    pub(crate) fn stamp_front(&mut self, t: TokenId) {
        let s = self.st.stamp.wrapping_add(1);
        if s == 0 {
            self.restamp_all();
        } else {
            self.st.stamp = s;
        }
        self.set_stamp(t, self.st.stamp);
    }

    /// Host: sets the stamp of `t`, the array grown to hold it first.
    #[cfg(feature = "grow")]
    #[inline(always)]
    fn set_stamp(&mut self, t: TokenId, s: crate::rete::Stamp) {
        match self.st.stamps.get_mut(t.ix()) {
            Some(x) => *x = s,
            None => self.grow_stamps(t, s),
        }
    }

    /// Host: `set_stamp` past the array's end: doubles it (or switches the stamps
    /// off, for good, if the allocator refuses).
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn grow_stamps(&mut self, t: TokenId, s: crate::rete::Stamp) {
        let stamps = &mut self.st.stamps;
        let want = (t.ix() + 1).max(2 * stamps.len()).max(1024);
        if self.st.stamps_off || !stamps.grow_to(want) {
            self.st.stamps_off = true;
            return;
        }
        stamps[t.ix()] = s;
    }

    /// Host: stamps every memory feeding a join from the right afresh, from 1 up.
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn restamp_all(&mut self) {
        self.st.stamp = 0;
        for j in 0..self.st.pools.njoins {
            let j = JoinId(j);
            if self.joins[j].rsucc != JoinId::NONE {
                self.restamp_memory(j);
            }
        }
    }

    /// Host: stamps the partial matches of `join`'s memory in its order (the last
    /// first), as if each had gone to the front in turn: when the join comes to
    /// feed a join from the right (its matches were not stamped as they came).
    #[cfg(feature = "grow")]
    pub(crate) fn restamp_memory(&mut self, join: JoinId) {
        let mut r = self.join_mems[join].mem;
        while r != TokenId::NONE && self.tokens[r].mem_next != TokenId::NONE {
            r = self.tokens[r].mem_next;
        }
        while r != TokenId::NONE {
            self.st.stamp = self.st.stamp.wrapping_add(1).max(1);
            self.set_stamp(r, self.st.stamp);
            r = self.tokens[r].mem_prev;
        }
    }

    /// `find_blocker`'s walk over the candidates of a join fed by an alpha node,
    /// from `a` (`first_candidate`).
    #[inline(always)]
    fn blocker_walk(
        &mut self,
        join: JoinId,
        left: TokenId,
        mut a: TokenId,
        hashed: bool,
    ) -> Result<TokenId, EvalError> {
        // host: the join's test fields read and its plan cache checked once
        // (the image checks per candidate: less code)
        #[cfg(feature = "host-speedups")]
        let (tests, depth) = self.join_test_fields(join);
        #[cfg(feature = "host-speedups")]
        let mut planned = false;
        // grow: the walk's key tag and node read once (`next_blocker_candidate`)
        #[cfg(feature = "grow")]
        let (tag, alpha) = match a {
            TokenId::NONE => (0, NONE),
            _ => (self.tokens[a].parent.0, self.tokens[a].alpha()),
        };
        while a != TokenId::NONE {
            #[cfg(feature = "host-speedups")]
            let found = self.join_test_with(join, tests, depth, left, a, &mut planned)?;
            #[cfg(not(feature = "host-speedups"))]
            let found = self.join_test(join, left, a)?;
            if found {
                return Ok(a);
            }
            #[cfg(feature = "grow")]
            {
                a = if hashed {
                    self.skip_other_key(self.tokens[a].am_next, alpha, tag)
                } else {
                    self.tokens[a].mem_next
                };
            }
            #[cfg(not(feature = "grow"))]
            {
                a = self.next_candidate(a, hashed);
            }
        }
        Ok(TokenId::NONE)
    }

    /// Host: `find_blocker` along a keyed bucket (from `a`) of `join` whose alpha
    /// node keeps a field for a `?a | ?b` test. When the test reads that field, the
    /// keyed or-index gives one bucket per alternative (`or_keyed_cursor`), merged
    /// in memory order; a search after blocker `skip` (an alpha match going away)
    /// goes on with the matches after it, as along its bucket. Else candidates the
    /// test rejects are skipped unseen (`or_match`); the usual walk when the
    /// test's values cannot be read.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn find_blocker_or(
        &mut self,
        join: JoinId,
        left: TokenId,
        mut a: TokenId,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        let Some(ov) = self.or_values(join, left, NONE) else {
            return self.blocker_walk(join, left, a, true);
        };
        let alpha = self.joins[join].alpha;
        if self.or_keyed_serves(alpha, &ov) {
            if let Some(key) = self.left_bucket_key(join, left) {
                return self.blocker_or_keyed(join, left, alpha, key, &ov, skip);
            }
        }
        let (tests, depth) = self.join_test_fields(join);
        let mut planned = false;
        while a != TokenId::NONE {
            let known = self.or_match(&ov, self.tokens[a].fact);
            if self.or_join_test(join, (tests, depth), left, a, &mut planned, &ov, known)? {
                return Ok(a);
            }
            a = self.next_candidate(a, true);
        }
        Ok(TokenId::NONE)
    }

    /// Host: `find_blocker_or` through the keyed or-index: the first candidate of
    /// the alternatives' buckets in memory order (after `skip`'s stamp when `skip`
    /// is a match of the node, skipping the dying fact's other matches, as the
    /// walk after a blocker does) that passes the join's tests.
    #[cfg(feature = "host-speedups")]
    fn blocker_or_keyed(
        &mut self,
        join: JoinId,
        left: TokenId,
        alpha: Ix,
        key: u32,
        ov: &OrValues,
        skip: TokenId,
    ) -> Result<TokenId, EvalError> {
        let after = (skip != TokenId::NONE
            && self.tokens[skip].kind == TokenKind::Alpha
            && self.tokens[skip].alpha() == alpha)
            .then(|| self.or_stamp_of(skip));
        let dying = self.st.net.dying;
        let mut cur = self.or_keyed_cursor(alpha, key, ov);
        let (tests, depth) = self.join_test_fields(join);
        let mut planned = false;
        loop {
            let a = self.or_next(&mut cur);
            if a == TokenId::NONE {
                return Ok(TokenId::NONE);
            }
            if let Some(s) = after {
                if self.or_stamp_of(a) <= s || (dying != NONE && self.tokens[a].fact == dying) {
                    continue;
                }
            }
            let known = self.or_keyed_match(&cur, ov, a);
            if self.or_join_test(join, (tests, depth), left, a, &mut planned, ov, known)? {
                return Ok(a);
            }
        }
    }

    /// Host: `left_activate` of positive `join` whose alpha node keeps a field for a
    /// `?a | ?b` test (`rhash[nrhash]`). Without a right hash: one index bucket per
    /// alternative (`or_lookup`); with one: its bucket, skipping the candidates the
    /// test rejects (`or_match`). When neither applies it walks the candidates as
    /// for any join: it ends the left activation either way, so that the usual
    /// path's reads of the join and its alpha node are not made again after it.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn or_left_activate(&mut self, join: JoinId, left: TokenId) -> Result<(), EvalError> {
        let nrhash = self.alphas[self.joins[join].alpha as usize].nrhash;
        let (tests, depth) = self.join_test_fields(join);
        let mut planned = false;
        if nrhash == 0 {
            // an empty memory: nothing to look up
            if self.alpha_mems[self.joins[join].alpha as usize].head == TokenId::NONE {
                return Ok(());
            }
            let Some(mut cur) = self.or_lookup(join, left) else {
                let (a, hashed) = self.first_candidate(join, left);
                return self.left_walk(join, left, a, hashed);
            };
            loop {
                let a = self.or_next(&mut cur);
                if a == TokenId::NONE {
                    return Ok(());
                }
                if self.join_test_with(join, tests, depth, left, a, &mut planned)? {
                    let t = self.link_token(join, left, a)?;
                    self.propagate_in(t, join)?;
                    planned = false;
                }
            }
        }
        // keyed: the key's bucket first, the usual walk's start: empty (most often
        // when the memory is small), no alternative can have a match
        let (first, hashed) = self.first_candidate(join, left);
        if first == TokenId::NONE {
            return Ok(());
        }
        // one bucket of the keyed or-index per alternative, when the or test reads
        // the node's field
        let ov = self.or_values(join, left, NONE);
        if let Some(ov) = &ov {
            let alpha = self.joins[join].alpha;
            if self.or_keyed_serves(alpha, ov) {
                if let Some(key) = self.left_bucket_key(join, left) {
                    let mut cur = self.or_keyed_cursor(alpha, key, ov);
                    loop {
                        let a = self.or_next(&mut cur);
                        if a == TokenId::NONE {
                            return Ok(());
                        }
                        let known = self.or_keyed_match(&cur, ov, a);
                        if self.or_join_test(
                            join,
                            (tests, depth),
                            left,
                            a,
                            &mut planned,
                            ov,
                            known,
                        )? {
                            let t = self.link_token(join, left, a)?;
                            self.propagate_in(t, join)?;
                            planned = false;
                        }
                    }
                }
            }
        }
        let mut a = first;
        let Some(ov) = ov else {
            return self.left_walk(join, left, a, hashed);
        };
        while a != TokenId::NONE {
            let next = self.next_candidate(a, hashed);
            let known = self.or_match(&ov, self.tokens[a].fact);
            if self.or_join_test(join, (tests, depth), left, a, &mut planned, &ov, known)? {
                let t = self.link_token(join, left, a)?;
                self.propagate_in(t, join)?;
                planned = false;
            }
            a = next;
        }
        Ok(())
    }

    /// A positive join's walk over its candidates from `a` (`first_candidate`) for
    /// left token `left`: each match passing its tests is propagated.
    #[inline(always)]
    fn left_walk(
        &mut self,
        join: JoinId,
        left: TokenId,
        mut a: TokenId,
        hashed: bool,
    ) -> Result<(), EvalError> {
        // host: see `find_blocker`
        #[cfg(feature = "host-speedups")]
        let (tests, depth) = self.join_test_fields(join);
        #[cfg(feature = "host-speedups")]
        let mut planned = false;
        while a != TokenId::NONE {
            let next = self.next_candidate(a, hashed);
            #[cfg(feature = "host-speedups")]
            let matched = self.join_test_with(join, tests, depth, left, a, &mut planned)?;
            #[cfg(not(feature = "host-speedups"))]
            let matched = self.join_test(join, left, a)?;
            if matched {
                let t = self.link_token(join, left, a)?;
                self.propagate_in(t, join)?;
                #[cfg(feature = "host-speedups")]
                {
                    planned = false;
                }
            }
            a = next;
        }
        Ok(())
    }

    /// A new active partial match `left` arrives on the left of `join`.
    pub(crate) fn left_activate(&mut self, join: JoinId, left: TokenId) -> Result<(), EvalError> {
        // the fields, not a copy of the join (which lived on the stack across calls)
        let kind = self.joins[join].kind;
        match kind {
            JoinKind::Positive => {
                // host: a join with a `?a | ?b` test on a field its alpha node keeps
                // for it (out of line: most joins have none)
                #[cfg(feature = "host-speedups")]
                {
                    let n = &self.alphas[self.joins[join].alpha as usize];
                    if n.rhash.get(n.nrhash as usize).is_some_and(|&f| f != NONE) {
                        return self.or_left_activate(join, left);
                    }
                }
                let (a, hashed) = self.first_candidate(join, left);
                self.left_walk(join, left, a, hashed)?;
            }
            JoinKind::Negative | JoinKind::Exists => {
                let post = self.joins[join].post;
                if post != NONE {
                    self.bind_left(left);
                    // an error is reported as in the join's own tests; the test fails
                    let pass = match self.eval_lhs_tests(post) {
                        Err(e) if !e.is_capacity() => {
                            self.report_join_error(join, e);
                            false
                        }
                        r => r?,
                    };
                    if !pass {
                        return Ok(());
                    }
                }
                // the bucket is looked up before the output token exists: its
                // index insert would evict `left`'s key from the key cache
                let (from, hashed) = if self.joins[join].rjoin == JoinId::NONE {
                    self.first_blocker_candidate(join, left)
                } else {
                    (TokenId::NONE, false)
                };
                let t = self.link_token(join, left, TokenId::NONE)?;
                let b = self.find_blocker(join, left, from, hashed, TokenId::NONE)?;
                if b != TokenId::NONE {
                    self.add_link(t, b);
                }
                // `token_active` of the new output: it is owed nothing yet, so a
                // not output is active unblocked, an exists output blocked
                if (b == TokenId::NONE) == (kind == JoinKind::Negative) {
                    if self.st.net.defer_nots && kind == JoinKind::Negative {
                        // see `defer_nots`: a later pattern of the same fact may block it
                        // (host: stamped as it went to the front, for joins from the right)
                        #[cfg(feature = "grow")]
                        if self.joins[join].rsucc != JoinId::NONE {
                            self.stamp_front(t);
                        }
                        self.owe(t, false);
                    } else {
                        self.propagate_in(t, join)?;
                    }
                }
            }
            JoinKind::Test => {
                if self.join_test(join, left, TokenId::NONE)? {
                    let t = self.link_token(join, left, TokenId::NONE)?;
                    self.propagate_in(t, join)?;
                }
            }
            JoinKind::Terminal => {
                let rule = self.joins[join].rule;
                self.add_activation(rule, left)?;
            }
            JoinKind::Root => {}
        }
        Ok(())
    }

    /// Creates a partial match in `join`'s memory (newest first) and links it under
    /// its parents.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn link_token(
        &mut self,
        join: JoinId,
        parent: TokenId,
        am: TokenId,
    ) -> Result<TokenId, EvalError> {
        let t = self.alloc_token()?;
        let kind = self.joins[join].kind;
        // not/exists outputs stay in front of the parent's other children
        // (see `output_of`); the others keep newest-first order among themselves,
        // which is all that the per-successor walks (`take_back`) rely on
        let (after, psib) = if parent == TokenId::NONE {
            (TokenId::NONE, TokenId::NONE)
        } else if matches!(kind, JoinKind::Negative | JoinKind::Exists) {
            (TokenId::NONE, self.tokens[parent].first_child)
        } else {
            self.front_run_end(parent, join)
        };
        // one borrow of the pool and one of the join for all the links (their
        // addresses stay in registers across the stores)
        let mut tokens = self.tokens.view();
        let jn = &self.joins[join];
        let jm = &mut self.join_mems[join];
        // the index child too, while the join is at hand
        let (head, depth) = (jm.mem, jn.depth);
        #[cfg(feature = "host-speedups")]
        let ichild = if jm.index_built {
            jn.index_child
        } else {
            JoinId::NONE
        };
        #[cfg(not(feature = "host-speedups"))]
        let ichild = JoinId::NONE;
        #[cfg(feature = "host-speedups")]
        let xbuilt = jm.xbuilt;
        #[cfg(not(feature = "host-speedups"))]
        let xbuilt = 0;
        #[cfg(feature = "host-speedups")]
        let own = if am != TokenId::NONE {
            tokens[am].fact
        } else {
            NONE
        };
        let asib = if am != TokenId::NONE {
            tokens[am].first_child
        } else {
            TokenId::NONE
        };
        tokens[t] = Token {
            kind: TokenKind::Beta,
            owner: join,
            am,
            parent,
            mem_next: head,
            next_sib: psib,
            prev_sib: after,
            am_next: asib,
            ..Token::EMPTY
        };
        // the bindings: the parent's, copied after the token is written (read
        // before, they went through the stack), then the own level patched in place
        #[cfg(feature = "host-speedups")]
        if parent != TokenId::NONE {
            tokens[t].binds = tokens[parent].binds;
        }
        #[cfg(feature = "host-speedups")]
        if let Some(x) = tokens[t].binds.get_mut(depth as usize) {
            *x = own;
        }
        #[cfg(not(feature = "host-speedups"))]
        let _ = depth;
        if head != TokenId::NONE {
            tokens[head].mem_prev = t;
        }
        if parent != TokenId::NONE {
            if psib != TokenId::NONE {
                tokens[psib].prev_sib = t;
            }
            if after != TokenId::NONE {
                tokens[after].next_sib = t;
            } else {
                tokens[parent].first_child = t;
            }
        }
        if am != TokenId::NONE {
            if asib != TokenId::NONE {
                tokens[asib].am_prev = t;
            }
            tokens[am].first_child = t;
        }
        jm.mem = t;
        self.beta_index_insert_fresh(t, join, ichild, xbuilt);
        // host: while a join keeps a primed order, partial matches entering a memory
        // are stamped (`rete::order`)
        #[cfg(feature = "grow")]
        if !self.st.prime.joins.is_empty() {
            self.stamp(t);
        }
        Ok(t)
    }

    /// Records that `blocker` (an alpha match or a subnetwork's partial match)
    /// blocks not/exists output token `t`: `t` goes to the front of the blocker's
    /// `blocks` list, chained by its `am_next`/`am_prev` (free: the output has no
    /// alpha match, and a blocked one is never owed); the head's `am_prev` names
    /// the blocker. Allocates nothing, as CLIPS links the partial match itself.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn add_link(&mut self, t: TokenId, blocker: TokenId) {
        let bsib = self.tokens[blocker].blocks;
        let tk = &mut self.tokens[t];
        tk.am_next = bsib;
        tk.am_prev = blocker;
        tk.blocked = true;
        if bsib != TokenId::NONE {
            self.tokens[bsib].am_prev = t;
        }
        self.tokens[blocker].blocks = t;
    }

    /// Takes blocked output `t` off its blocker's list. `am_prev` is the blocker
    /// exactly when `t` heads the blocker's list (a token is on one list only).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(super) fn unlink_blocked(&mut self, t: TokenId) {
        let tk = &mut self.tokens[t];
        let (p, n) = (tk.am_prev, tk.am_next);
        tk.am_next = TokenId::NONE;
        tk.am_prev = TokenId::NONE;
        tk.blocked = false;
        if self.tokens[p].blocks == t {
            self.tokens[p].blocks = n;
        } else {
            self.tokens[p].am_next = n;
        }
        if n != TokenId::NONE {
            self.tokens[n].am_prev = p;
        }
    }

    /// The blocker of blocked output `t`: back along the list to its head.
    #[cfg(not(feature = "host-speedups"))]
    fn blocker_of(&self, t: TokenId) -> TokenId {
        let mut c = t;
        loop {
            let p = self.tokens[c].am_prev;
            if self.tokens[p].blocks == c {
                return p;
            }
            c = p;
        }
    }

    /// Blocked output `t` loses its blocker (`t` from the blocker's `blocks`
    /// list; O(1) for its head, as retracts take them). (Host:
    /// `unblock_alpha_head`.)
    #[cfg(not(feature = "host-speedups"))]
    pub(crate) fn remove_link(&mut self, t: TokenId) {
        let blocker = self.blocker_of(t);
        self.unblock(t, blocker);
    }

    /// Host: `remove_link` for `t`, the head of alpha match `am`'s list while `am`
    /// leaves (`remove_alpha_match`): `am` is its blocker, and what the unblock asks
    /// of it (`AlphaBlocker`) is read once for every output it blocks.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    pub(crate) fn unblock_alpha_head(&mut self, t: TokenId, am: TokenId, known: AlphaBlocker) {
        self.unblock_in(t, am, Some(known));
    }

    /// The blocker of output `t` goes away: `t` gets the next blocker, or is
    /// unblocked (not) or loses its match (exists), as CLIPS does.
    #[inline(always)]
    fn unblock(&mut self, t: TokenId, blocker: TokenId) {
        self.unblock_in(t, blocker, KNOWN_NONE);
    }

    /// `unblock`; host: with `known` what `dying_known` needs of an alpha blocker
    /// (None: `dying_to_check` reads it).
    fn unblock_in(&mut self, t: TokenId, blocker: TokenId, known: Known) {
        #[cfg(not(feature = "host-speedups"))]
        let () = known;
        self.unlink_blocked(t);
        // (the image: the fact read once, its code bytes as they were)
        #[cfg(not(feature = "host-speedups"))]
        let dying = self.st.net.dying;
        let join = self.tokens[t].owner;
        let left = self.tokens[t].parent;
        // an evaluation error while searching counts as no further blocker
        #[cfg(not(feature = "host-speedups"))]
        let next = {
            let (from, hashed) = if self.tokens[blocker].kind == TokenKind::Alpha {
                let hashed = self.alphas[self.tokens[blocker].alpha() as usize].nrhash > 0;
                let mut from = self.next_candidate(blocker, hashed);
                while dying != NONE && from != TokenId::NONE && self.tokens[from].fact == dying {
                    from = self.next_candidate(from, hashed);
                }
                (from, hashed)
            } else {
                (TokenId::NONE, false)
            };
            self.find_blocker(join, left, from, hashed, blocker)
                .unwrap_or(TokenId::NONE)
        };
        #[cfg(feature = "host-speedups")]
        let next = if self.tokens[blocker].kind == TokenKind::Alpha {
            // the blocker is the first match in memory order: search on after it,
            // along its index bucket when its node has one (same key as `left`)
            let hashed = self.alphas[self.tokens[blocker].alpha() as usize].nrhash > 0;
            let mut from = self.next_blocker_candidate(blocker, hashed);
            // (a retract: another match of the fact in the same node may follow it)
            if from != TokenId::NONE {
                let dying = self.dying_after(blocker);
                while dying != NONE && from != TokenId::NONE && self.tokens[from].fact == dying {
                    from = self.next_blocker_candidate(from, hashed);
                }
            }
            // no candidate left: no search (most unblocks; an alpha blocker's join
            // has no subnetwork, so the search is the alpha-fed one)
            if from != TokenId::NONE {
                debug_assert!(self.joins[join].rjoin == JoinId::NONE);
                self.find_alpha_blocker(join, left, from, hashed, blocker)
                    .unwrap_or(TokenId::NONE)
            } else {
                TokenId::NONE
            }
        } else {
            // a partial match of the join's subnetwork
            let rjoin = self.joins[join].rjoin;
            if rjoin != JoinId::NONE {
                self.sub_blocker_walk(join, rjoin, left, blocker)
                    .unwrap_or(TokenId::NONE)
            } else {
                TokenId::NONE
            }
        };
        if next != TokenId::NONE {
            self.add_link(t, next);
            return;
        }
        if self.joins[join].kind == JoinKind::Negative {
            // a retract: CLIPS passes nothing on that holds the fact, and nothing
            // passed on meets it (its matches leave their memories first)
            #[cfg(feature = "host-speedups")]
            let dying = match known {
                Some(k) => self.dying_known(join, k.last, k.fact),
                None => self.dying_to_check(join, blocker),
            };
            if dying != NONE {
                // host: what the fact's template cannot reach is not checked
                #[cfg(feature = "host-speedups")]
                let (reach, depths) = self.dying_reach(join, blocker, dying);
                #[cfg(not(feature = "host-speedups"))]
                let reach = REACH_LEFT | REACH_BELOW;
                // (host: the left patterns of its template kept in the bindings)
                #[cfg(feature = "host-speedups")]
                if depths != 0 && self.binds_fact(left, depths, dying) {
                    return;
                }
                if reach & REACH_LEFT != 0 && self.holds_fact(left, dying) {
                    return;
                }
                if reach & REACH_BELOW != 0 && !self.st.net.dying_hidden {
                    self.hide_dying();
                }
            }
            self.move_to_front(t);
            self.log_unblocked(t);
            self.propagate_or_owe(t);
        } else {
            self.deactivate(t);
            // an exists output without a match is no partial match for CLIPS
            #[cfg(feature = "logical")]
            if self.logical_in_use() {
                self.token_leaves(t);
            }
        }
    }

    /// Host: the fact being retracted, while it may still have matches once
    /// `blocker` went (`dying_may_remain`); else NONE.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn dying_after(&self, blocker: TokenId) -> Ix {
        if !self.dying_may_remain(blocker) {
            return NONE;
        }
        self.st.net.dying
    }

    /// Host: `dying_to_check` for an alpha blocker whose `next_sib == NONE` is `last`
    /// and whose fact is `fact` (`unblock_alpha_head`).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn dying_known(&self, join: JoinId, last: bool, fact: Ix) -> Ix {
        let dying = self.st.net.dying;
        if dying == NONE || last {
            return NONE;
        }
        if fact == dying {
            let jm = &self.join_mems[join];
            if jm.reach_gen == self.st.net.net_gen && jm.reach | jm.reach_depths == 0 {
                return NONE;
            }
        }
        dying
    }

    /// Host: `dying_after` for the unblocked output of not join `join`, NONE also
    /// when `blocker` is the dying fact's alpha match and the join's reach, worked
    /// out for this network generation, is nothing (no pattern left of it or below
    /// it has the fact's template): `dying_reach` would then ask for no check.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn dying_to_check(&self, join: JoinId, blocker: TokenId) -> Ix {
        let dying = self.st.net.dying;
        if dying == NONE {
            return NONE;
        }
        let b = &self.tokens[blocker];
        if b.kind == TokenKind::Alpha {
            // (`dying_may_remain`: the fact's last alpha match)
            if b.next_sib == TokenId::NONE {
                return NONE;
            }
            if b.fact == dying {
                let jm = &self.join_mems[join];
                if jm.reach_gen == self.st.net.net_gen && jm.reach | jm.reach_depths == 0 {
                    return NONE;
                }
            }
        }
        dying
    }

    /// Whether, during a retract, the dying fact may still have partial matches or
    /// alpha matches in memory once `blocker` went. Not when `blocker` is the fact's
    /// last alpha match (most facts have one; an alpha blocker unblocks only in
    /// `remove_alpha_match`, so it is the dying fact's): its partial matches went
    /// before the outputs it blocks are unblocked, it left its memory, and the
    /// fact's earlier matches went whole. A partial-match blocker (not-and) goes
    /// while its fact's matches are still in place.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn dying_may_remain(&self, blocker: TokenId) -> bool {
        let b = &self.tokens[blocker];
        b.kind != TokenKind::Alpha || b.next_sib != TokenId::NONE
    }

    /// Host: where retracted fact `dying`, whose alpha match `blocker` blocked an
    /// output of not join `join`, may still be, as bits and pattern depths. A fact
    /// matches only patterns of its template: a left partial match can hold it
    /// only at a left pattern of the template of the join's alpha node (at the
    /// returned depths, which the partial match's bindings keep, or anywhere with
    /// `REACH_LEFT`), and what the output passes on can meet its other matches only
    /// if a join below it, or taking its partial matches from the right, has one
    /// (`REACH_BELOW`). A subnetwork's blocker: both bits. Worked out once per
    /// network generation (`JoinMem::reach`).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn dying_reach(&mut self, join: JoinId, blocker: TokenId, dying: Ix) -> (u8, u8) {
        let b = &self.tokens[blocker];
        if b.kind != TokenKind::Alpha || b.fact != dying {
            return (REACH_LEFT | REACH_BELOW, 0);
        }
        let jm = &self.join_mems[join];
        if jm.reach_gen == self.st.net.net_gen {
            return (jm.reach, jm.reach_depths);
        }
        self.work_out_reach(join)
    }

    /// `dying_reach` for a network generation not seen yet (out of line).
    #[cfg(feature = "host-speedups")]
    #[cold]
    #[inline(never)]
    fn work_out_reach(&mut self, join: JoinId) -> (u8, u8) {
        let alpha = self.joins[join].alpha;
        let (reach, depths) = if alpha == NONE {
            (REACH_LEFT | REACH_BELOW, 0)
        } else {
            let tmpl = self.alphas[alpha as usize].tmpl;
            let of_tmpl = |cx: &Core<'_>, j: JoinId| {
                let a = cx.joins[j].alpha;
                a != NONE && cx.alphas[a as usize].tmpl == tmpl
            };
            let (mut reach, mut depths) = (0u8, 0u8);
            // upwards: a depth written by a join nearer the left partial match
            // (`seen`) no longer holds an earlier join's fact in the bindings
            let mut seen = 0u64;
            let mut p = self.joins[join].parent;
            while p != JoinId::NONE {
                let d = self.joins[p].depth as usize;
                if of_tmpl(self, p) {
                    if d < super::BIND_W && seen & (1 << d) == 0 {
                        depths |= 1 << d;
                    } else {
                        reach |= REACH_LEFT;
                    }
                }
                seen |= 1u64.checked_shl(d as u32).unwrap_or(0);
                p = self.joins[p].parent;
            }
            // (a walk too deep to follow counts as reaching)
            if !self.walk_joins(join, false, &mut |cx, j| j == join || !of_tmpl(cx, j)) {
                reach |= REACH_BELOW;
            }
            (reach, depths)
        };
        let jm = &mut self.join_mems[join];
        jm.reach = reach;
        jm.reach_depths = depths;
        jm.reach_gen = self.st.net.net_gen;
        (reach, depths)
    }

    /// Host: whether partial match `t` binds `fact` at one of the pattern depths
    /// `depths` (bits below `BIND_W`).
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn binds_fact(&self, t: TokenId, depths: u8, fact: Ix) -> bool {
        if t == TokenId::NONE {
            return false;
        }
        let binds = &self.tokens[t].binds;
        let mut m = depths;
        while m != 0 {
            if binds.get(m.trailing_zeros() as usize) == Some(&fact) {
                return true;
            }
            m &= m - 1;
        }
        false
    }

    /// Whether partial match `t` or one of its ancestors holds a match of `fact`.
    #[cold]
    #[inline(never)]
    fn holds_fact(&self, mut t: TokenId, fact: Ix) -> bool {
        while t != TokenId::NONE && self.tokens[t].kind == TokenKind::Beta {
            let am = self.tokens[t].am;
            if am != TokenId::NONE && self.tokens[am].fact == fact {
                return true;
            }
            t = self.tokens[t].parent;
        }
        false
    }

    /// Passes on a not output that a removal unblocked. Removals (retract, and the
    /// undo of a failed assert) cannot fail, but what unblocking rebuilds is not
    /// bounded by what the removal freed (one retracted blocker can release any
    /// number of matches). So on a full pool the part built is taken back and the
    /// output is *owed*: it passes nothing on (inactive, as if blocked), and
    /// `pay_owed` propagates it once there is room. Every operation pays first
    /// (assert fails unchanged if it cannot; `run` fires nothing; retract reports
    /// the error), so no match is lost and no rule fires on an incomplete agenda.
    fn propagate_or_owe(&mut self, t: TokenId) {
        if self.st.net.defer_nots {
            // (host: stamped as it went to the front, for joins from the right)
            #[cfg(feature = "grow")]
            if self.joins[self.tokens[t].owner].rsucc != JoinId::NONE {
                self.stamp_front(t);
            }
            self.owe(t, false);
            return;
        }
        if let Err(e) = self.propagate(t) {
            // an evaluation error in a join test counts as no match (as before);
            // only a full pool leaves matches to build later
            if e.is_capacity() {
                self.deactivate(t);
                self.owe(t, false);
            }
        }
    }

    /// Whether not output `t` is owed its propagation. Not outputs have no alpha
    /// match, so their alpha-sibling links are free: they chain the owed list (the
    /// head's `am_prev` is the tail), and a non-NONE `am_prev` marks membership.
    pub(crate) fn is_owed(&self, t: TokenId) -> bool {
        let tk = &self.tokens[t];
        tk.kind == TokenKind::Beta
            && tk.am == TokenId::NONE
            && !tk.blocked
            && tk.am_prev != TokenId::NONE
    }

    /// Puts `t` on the owed list: at the end, or at the front (kept its turn).
    fn owe(&mut self, t: TokenId, front: bool) {
        let head = self.st.net.owed;
        if head == TokenId::NONE {
            self.tokens[t].am_next = TokenId::NONE;
            self.tokens[t].am_prev = t;
            self.st.net.owed = t;
            return;
        }
        let tail = self.tokens[head].am_prev;
        if front {
            self.tokens[t].am_next = head;
            self.tokens[t].am_prev = tail;
            self.tokens[head].am_prev = t;
            self.st.net.owed = t;
        } else {
            self.tokens[t].am_next = TokenId::NONE;
            self.tokens[t].am_prev = tail;
            self.tokens[tail].am_next = t;
            self.tokens[head].am_prev = t;
        }
    }

    fn unowe(&mut self, t: TokenId) {
        self.st.net.owed = self.am_chain_remove(self.st.net.owed, t);
    }

    /// Notes a not output a modify's retract unblocked (see `UnblockLog`).
    fn log_unblocked(&mut self, t: TokenId) {
        let log = &mut self.st.net.unblocked;
        if !log.on {
            return;
        }
        if log.len as usize >= log.entries.len() {
            log.overflow = true;
            return;
        }
        let tk = &self.tokens[t];
        log.entries[log.len as usize] = (t, tk.owner, tk.parent);
        log.len += 1;
    }

    /// Before a failed modify re-asserts its old fact: takes back what the modify's
    /// retract rebuilt below the not outputs it unblocked and leaves them owed, so
    /// the re-assert (which blocks them again) needs no more room than the retract
    /// freed. Otherwise the re-assert could meet a full pool before it reaches the
    /// patterns that free that room, and lose the fact. An entry whose token was
    /// deleted since (and maybe reused) is recognised by its join and parent: a left
    /// token has one output per join. Returns false if the log overflowed.
    pub(crate) fn owe_unblocked(&mut self) -> bool {
        let log = self.st.net.unblocked;
        for &(t, owner, parent) in &log.entries[..log.len as usize] {
            let tk = self.tokens[t];
            if tk.kind == TokenKind::Beta
                && tk.owner == owner
                && tk.parent == parent
                && self.joins[owner].kind == JoinKind::Negative
                && self.token_active(t)
            {
                self.deactivate(t);
                self.owe(t, false);
            }
        }
        !log.overflow
    }

    /// Propagates the owed not outputs, oldest first. On a full pool the one that
    /// failed is taken back, keeps its turn and the error is returned: the network
    /// stays complete up to what is still owed.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn pay_owed(&mut self) -> Result<(), EvalError> {
        // most operations owe nothing: no call for them on the host
        if self.st.net.owed == TokenId::NONE {
            return Ok(());
        }
        self.pay_owed_list()
    }

    /// `pay_owed` of a non-empty owed list.
    #[cfg_attr(feature = "host-speedups", inline(never))]
    fn pay_owed_list(&mut self) -> Result<(), EvalError> {
        while self.st.net.owed != TokenId::NONE {
            let t = self.st.net.owed;
            self.unowe(t);
            // host: it went to the front when it was owed (or before), not now
            #[cfg(feature = "grow")]
            let stamp = self.stamp_of(t);
            let r = self.propagate(t);
            #[cfg(feature = "grow")]
            self.set_stamp(t, stamp);
            if let Err(e) = r {
                if e.is_capacity() {
                    self.deactivate(t);
                    self.owe(t, true);
                    return Err(e);
                }
            }
        }
        Ok(())
    }

    /// Passes an active partial match on to its join's successors, newest first as
    /// CLIPS does: child joins and rule ends (left), joins taking it from the right.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn propagate(&mut self, t: TokenId) -> Result<(), EvalError> {
        let join = self.tokens[t].owner;
        self.propagate_in(t, join)
    }

    /// `propagate` of token `t` of `join` (callers that just made it know the join).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn propagate_in(&mut self, t: TokenId, join: JoinId) -> Result<(), EvalError> {
        if self.joins[join].rsucc == JoinId::NONE {
            // the common case: no join takes these tokens from the right, so the
            // successors are the child list as it is
            let mut c = self.joins[join].first_child;
            while c != JoinId::NONE {
                let cj = &self.joins[c];
                let next = cj.next_sibling;
                if cj.kind == JoinKind::Terminal {
                    // a rule end: `left_activate` would only do this, in a big frame
                    let rule = cj.rule;
                    self.add_activation(rule, t)?;
                } else {
                    self.left_activate(c, t)?;
                }
                c = next;
            }
            return Ok(());
        }
        // host: it went to the front of its memory just now (a new partial match,
        // or a not/exists output unblocked/blocked); first, as its successors may
        // search this memory
        #[cfg(feature = "grow")]
        self.stamp_front(t);
        let mut it = Successors::of(self, join);
        while let Some((c, from_right)) = it.next(self) {
            if from_right {
                self.right_activate_beta(c, t)?;
            } else {
                self.left_activate(c, t)?;
            }
        }
        Ok(())
    }

    /// Host: before alpha match child `x` goes (the newest left), for a node some
    /// of whose joins take its matches again further down (`self_joined`): the
    /// copies CLIPS made of `x`'s ancestors on the same alpha match for their
    /// successors walked after the one `x` descends through, when `x` was built in
    /// that same walk. CLIPS copies a partial match for each successor as the walk
    /// reaches it, each copy a child of the alpha match; a retract takes back the
    /// alpha match's children newest first, each with what it passed on. Ours
    /// is one partial match, as old as its first copy, so what its later copies
    /// passed on goes here, newest first (the farthest ancestor's first).
    #[cfg(feature = "grow")]
    #[inline(never)]
    pub(super) fn take_back_newer_copies(&mut self, x: TokenId, am: TokenId) {
        // (only a partial match of a join taking this node again has such ancestors)
        let rejoins = &self.st.prime.rejoins;
        if !rejoins.get(self.tokens[x].owner.ix()).is_some_and(|&r| r) {
            return;
        }
        // up from `x`: the newest fact joined on the right below each ancestor, and
        // the latest join made; an ancestor on the same alpha match whose own facts
        // are none older is one `x` was built in the walk of (nearest first)
        let mut found = [(TokenId::NONE, JoinId::NONE); 8];
        let mut n = 0;
        let (mut below, mut born) = (0u32, 0u32);
        let mut c = x;
        loop {
            let tk = &self.tokens[c];
            if tk.am != TokenId::NONE {
                below = below.max(self.facts[self.tokens[tk.am].fact as usize].num);
            }
            born = born.max(self.join_born(tk.owner));
            let p = tk.parent;
            if p == TokenId::NONE || self.tokens[p].kind != TokenKind::Beta {
                break;
            }
            if self.tokens[p].am == am {
                let own = self.newest_fact_of(p);
                if below <= own && born <= own {
                    if n == found.len() {
                        // (more than kept: the plain order stands)
                        return;
                    }
                    found[n] = (p, tk.owner);
                    n += 1;
                }
            }
            c = p;
        }
        // the farthest ancestor's later copies are the newest
        for &(t, via) in found[..n].iter().rev() {
            let mut succ = [(JoinId::NONE, false); 8];
            let mut k = 0;
            let mut at = None;
            let mut it = Successors::of(self, self.tokens[t].owner);
            while let Some(s) = it.next(self) {
                if k == succ.len() {
                    break;
                }
                if s.0 == via && !s.1 {
                    at = Some(k);
                }
                succ[k] = s;
                k += 1;
            }
            let Some(at) = at else {
                continue;
            };
            for &(s, from_right) in succ[at + 1..k].iter().rev() {
                if self.passed_on_to(t, s, from_right) {
                    self.take_back(t, s, from_right);
                }
            }
        }
    }

    /// Host: `next_fact_num` when `join` was made (0: before every fact there is).
    #[cfg(feature = "grow")]
    #[inline(always)]
    fn join_born(&self, join: JoinId) -> u32 {
        self.st.prime.join_born.get(join.ix()).copied().unwrap_or(0)
    }

    /// The newest fact partial match `t` holds (its number).
    #[cfg(feature = "grow")]
    fn newest_fact_of(&self, t: TokenId) -> u32 {
        let mut newest = 0;
        let mut c = t;
        while c != TokenId::NONE && self.tokens[c].kind == TokenKind::Beta {
            let a = self.tokens[c].am;
            if a != TokenId::NONE {
                newest = newest.max(self.facts[self.tokens[a].fact as usize].num);
            }
            c = self.tokens[c].parent;
        }
        newest
    }

    /// Takes back what a token passed on, successor by successor in the order
    /// CLIPS created its copies (oldest successor first): a rule end loses the
    /// activation, a child join the partial matches built on the token, a join from
    /// the right the output it blocks (which looks for another blocker).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn deactivate(&mut self, t: TokenId) {
        let tk = &self.tokens[t];
        if tk.first_child == TokenId::NONE
            && tk.blocks == TokenId::NONE
            && (tk.kind != TokenKind::Beta || tk.extra == NONE)
        {
            // passed nothing on (no partial matches, activations or blocks)
            return;
        }
        let join = tk.owner;
        let jn = &self.joins[join];
        if jn.rsucc == JoinId::NONE
            && jn.first_child != JoinId::NONE
            && self.joins[jn.first_child].next_sibling == JoinId::NONE
        {
            // the common case: one successor, a child join or rule end, so all
            // the children or activations are its (`take_back` without the
            // per-entry checks)
            if self.joins[jn.first_child].kind != JoinKind::Terminal {
                self.delete_children(t);
            } else if self.tokens[t].kind == TokenKind::Beta {
                while self.tokens[t].extra != NONE {
                    let a = self.tokens[t].extra;
                    self.remove_activation(a);
                }
            }
        } else {
            self.take_back_all(t, join);
        }
        while self.tokens[t].blocks != TokenId::NONE {
            let k = self.tokens[t].blocks;
            self.unblock(k, t);
        }
    }

    /// `deactivate` for every successor of `join`, oldest first. Host: those primed
    /// after `t` was made first, the latest primed first (CLIPS's copies of `t` that
    /// priming made are the newest children of its parents, see `rete::order`).
    fn take_back_all(&mut self, t: TokenId, join: JoinId) {
        // the successors in walking order; the first few kept, as most joins have
        // one or two, the rest walked to again
        let mut first = [(JoinId::NONE, false); 8];
        let mut n = 0;
        let mut it = Successors::of(self, join);
        while let Some(s) = it.next(self) {
            if n < first.len() {
                first[n] = s;
            }
            n += 1;
        }
        #[cfg(feature = "grow")]
        let primed = if self.st.prime.joins.is_empty() {
            0
        } else {
            self.take_back_primed(t, &first[..n.min(first.len())])
        };
        for i in (0..n).rev() {
            #[cfg(feature = "grow")]
            if i < first.len() && primed & (1 << i) != 0 {
                continue;
            }
            let (c, from_right) = if i < first.len() {
                first[i]
            } else {
                let mut it = Successors::of(self, join);
                for _ in 0..i {
                    it.next(self);
                }
                let Some(s) = it.next(self) else {
                    break;
                };
                s
            };
            self.take_back(t, c, from_right);
        }
    }

    /// Host: before alpha match child `c` goes (the newest left), what its older
    /// siblings passed on to successors primed after `c` was made, the latest primed
    /// first: CLIPS's copy of a sibling for such a successor is a child of the alpha
    /// match newer than `c` (see `take_back_newer_copies`).
    #[cfg(feature = "grow")]
    #[inline(never)]
    pub(super) fn take_back_primed_before(&mut self, c: TokenId) {
        let made = self.seq_of(c);
        loop {
            let mut latest: Option<(u32, TokenId, JoinId, bool)> = None;
            let mut t = self.tokens[c].am_next;
            while t != TokenId::NONE {
                let tk = &self.tokens[t];
                if tk.extra != NONE || tk.first_child != TokenId::NONE || tk.blocks != TokenId::NONE
                {
                    let mut it = Successors::of(self, tk.owner);
                    while let Some((s, from_right)) = it.next(self) {
                        if let Some(born) = self.primed_after(s, t, from_right) {
                            if born > made
                                && latest.is_none_or(|(b, ..)| born > b)
                                && self.passed_on_to(t, s, from_right)
                            {
                                latest = Some((born, t, s, from_right));
                            }
                        }
                    }
                }
                t = self.tokens[t].am_next;
            }
            let Some((_, t, s, from_right)) = latest else {
                return;
            };
            self.take_back(t, s, from_right);
        }
    }

    /// Whether partial match `t` passed something on to successor `s` that is still
    /// there: an activation of its rule, or a partial match, or logical support of
    /// its copy for `s`; for a join from the right (`from_right`), an output of `s`
    /// it blocks.
    #[cfg(feature = "grow")]
    fn passed_on_to(&self, t: TokenId, s: JoinId, from_right: bool) -> bool {
        if from_right {
            // (outputs of `s` it blocks)
            let mut k = self.tokens[t].blocks;
            while k != TokenId::NONE {
                if self.tokens[k].owner == s {
                    return true;
                }
                k = self.tokens[k].am_next;
            }
            return false;
        }
        let sj = &self.joins[s];
        if sj.kind == JoinKind::Terminal {
            let mut a = self.tokens[t].extra;
            while a != NONE {
                if self.acts[a as usize].rule == sj.rule {
                    return true;
                }
                a = self.acts[a as usize].next_of_token;
            }
        } else {
            let mut k = self.tokens[t].first_child;
            while k != TokenId::NONE {
                if self.tokens[k].owner == s {
                    return true;
                }
                k = self.tokens[k].next_sib;
            }
        }
        // (the copy itself still holds logical support it gave: a fired rule's, or
        // one whose logical CEs end at `t`'s join)
        #[cfg(feature = "logical")]
        if self.logical_in_use() {
            return self.copy_supports(t, s);
        }
        false
    }

    /// Host: takes back what `t` passed on to those of successors `succ` that were
    /// primed after it was made, the latest primed first; returns them as bits.
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn take_back_primed(&mut self, t: TokenId, succ: &[(JoinId, bool)]) -> u8 {
        let mut done = 0u8;
        loop {
            let mut latest: Option<(u32, usize)> = None;
            for (i, &(c, from_right)) in succ.iter().enumerate() {
                if done & (1 << i) != 0 {
                    continue;
                }
                if let Some(born) = self.primed_after(c, t, from_right) {
                    if latest.is_none_or(|(b, _)| born > b) {
                        latest = Some((born, i));
                    }
                }
            }
            let Some((_, i)) = latest else {
                return done;
            };
            done |= 1 << i;
            self.take_back(t, succ[i].0, succ[i].1);
        }
    }

    /// Takes back what token `t` passed on to successor `c` (see `deactivate`).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn take_back(&mut self, t: TokenId, c: JoinId, from_right: bool) {
        let cj = self.joins[c];
        if from_right {
            let mut k = self.tokens[t].blocks;
            while k != TokenId::NONE {
                let next = self.tokens[k].am_next;
                if self.tokens[k].owner == c {
                    self.unblock(k, t);
                }
                k = next;
            }
        } else if cj.is_terminal() {
            if self.tokens[t].kind == TokenKind::Beta {
                let mut a = self.tokens[t].extra;
                while a != NONE {
                    let next = self.acts[a as usize].next_of_token;
                    if self.acts[a as usize].rule == cj.rule {
                        self.remove_activation(a);
                    }
                    a = next;
                }
            }
        } else {
            let mut k = self.tokens[t].first_child;
            while k != TokenId::NONE {
                let next = self.tokens[k].next_sib;
                if self.tokens[k].owner == c {
                    self.delete_token(k);
                }
                k = next;
            }
        }
        // CLIPS's copy of `t` for `c` goes now, with its logical support
        #[cfg(feature = "logical")]
        if self.logical_in_use() {
            self.copy_leaves(t, c);
        }
    }

    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn delete_children(&mut self, t: TokenId) {
        while self.tokens[t].first_child != TokenId::NONE {
            let c = self.tokens[t].first_child;
            self.delete_token(c);
        }
    }

    /// Deletes a partial match and everything built on it.
    pub(crate) fn delete_token(&mut self, t: TokenId) {
        let tk = &self.tokens[t];
        let (owner, fc, extra) = (tk.owner, tk.first_child, tk.extra);
        // What it passed on decides: nothing (a leaf, like most blocked not
        // outputs); or with one successor in the child list (joins from the right
        // take back only what it blocks), only children, all of that child join,
        // which `delete_children` takes in `deactivate`'s order, or only
        // activations, all of that one rule. Else `deactivate` walks every
        // successor.
        // (`delete_children` only where there may be children: a leaf's list
        // was just read)
        if tk.blocks != TokenId::NONE || (fc != TokenId::NONE && extra != NONE) {
            self.deactivate(t);
            self.delete_children(t);
        } else if fc != TokenId::NONE {
            if self.one_child(owner) {
                // the children from the first, as `delete_children` takes them
                let mut c = fc;
                while c != TokenId::NONE {
                    self.delete_token(c);
                    c = self.tokens[t].first_child;
                }
            } else {
                self.deactivate(t);
                self.delete_children(t);
            }
        } else if extra != NONE {
            if self.one_child(owner) {
                while self.tokens[t].extra != NONE {
                    let a = self.tokens[t].extra;
                    self.remove_activation(a);
                }
            } else {
                self.deactivate(t);
                self.delete_children(t);
            }
        }
        self.unlink_and_free(t);
    }

    /// Whether `join`'s child list (child joins and rule ends) has one entry.
    #[cfg(not(feature = "host-speedups"))]
    fn one_child(&self, join: JoinId) -> bool {
        let c = self.joins[join].first_child;
        c != JoinId::NONE && self.joins[c].next_sibling == JoinId::NONE
    }

    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn one_child(&self, join: JoinId) -> bool {
        self.join_mems[join].one_child
    }

    /// Records whether `join`'s child list has one entry (host: `JoinMem::one_child`),
    /// after every change to the list.
    pub(crate) fn note_children(&mut self, join: JoinId) {
        #[cfg(feature = "host-speedups")]
        {
            let c = self.joins[join].first_child;
            self.join_mems[join].one_child =
                c != JoinId::NONE && self.joins[c].next_sibling == JoinId::NONE;
        }
        #[cfg(not(feature = "host-speedups"))]
        let _ = join;
    }

    /// Unlinks a token from its parent, alpha match (or blocker, or owed list) and
    /// memory lists, then frees it.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn unlink_and_free(&mut self, t: TokenId) {
        // fields read one by one: copying the whole (host: 104-byte) token cost
        // more than the unlinking; one borrow of the pool per stretch keeps its
        // bounds in registers across the stores
        let mut tokens = self.tokens.view();
        let tk = &tokens[t];
        let (am, am_prev, am_next) = (tk.am, tk.am_prev, tk.am_next);
        let (parent, prev_sib, next_sib) = (tk.parent, tk.prev_sib, tk.next_sib);
        // host: only a partial match in a bucket has one (see `beta_index_remove`)
        #[cfg(feature = "wide-index")]
        let in_bucket = tk.beta_links[1] != NONE;
        #[cfg(all(feature = "wide-index", feature = "host-speedups"))]
        let in_bucket = in_bucket || tk.in_x;
        #[cfg(not(feature = "wide-index"))]
        let in_bucket = true;
        if parent != TokenId::NONE {
            leave_parent(&mut tokens, parent, prev_sib, next_sib);
        }
        if am != TokenId::NONE {
            leave_alpha_match(&mut tokens, am, am_prev, am_next);
        } else if am_prev != TokenId::NONE {
            // a not/exists output: blocked, or owed (see `is_owed`)
            if tokens[t].blocked {
                self.unlink_blocked(t);
            } else {
                self.unowe(t);
            }
        }
        if in_bucket {
            self.beta_index_remove(t);
        }
        let mut tokens = self.tokens.view();
        let tk = &tokens[t];
        let (owner, mem_prev, mem_next) = (tk.owner, tk.mem_prev, tk.mem_next);
        if mem_prev != TokenId::NONE {
            tokens[mem_prev].mem_next = mem_next;
        } else {
            let j = &mut self.join_mems[owner];
            j.mem = mem_next;
            // an empty memory is trivially unindexed (see `JoinMem::index_built`)
            #[cfg(feature = "host-speedups")]
            if mem_next == TokenId::NONE {
                j.index_built = false;
                j.xbuilt = 0;
            }
        }
        if mem_next != TokenId::NONE {
            tokens[mem_next].mem_prev = mem_prev;
        }
        self.free_token(t);
    }

    /// Deletes every token in a join's memory.
    pub(crate) fn clear_join_memory(&mut self, join: JoinId) {
        while self.join_mems[join].mem != TokenId::NONE {
            let t = self.join_mems[join].mem;
            self.delete_token(t);
        }
    }
}

/// Takes a partial match (whose sibling links are `prev`, `next`) off the child list
/// of token `parent`.
#[inline(always)]
pub(super) fn leave_parent(
    tokens: &mut Slots<'_, TokenId, Token>,
    parent: TokenId,
    prev: TokenId,
    next: TokenId,
) {
    unlink(
        tokens,
        parent,
        (prev, next),
        |t| &mut t.next_sib,
        |t| &mut t.prev_sib,
    );
}

/// Takes a partial match (whose links under its alpha match are `prev`, `next`) off
/// the list of partial matches built on alpha match `am`.
#[inline(always)]
pub(super) fn leave_alpha_match(
    tokens: &mut Slots<'_, TokenId, Token>,
    am: TokenId,
    prev: TokenId,
    next: TokenId,
) {
    unlink(
        tokens,
        am,
        (prev, next),
        |t| &mut t.am_next,
        |t| &mut t.am_prev,
    );
}

/// Takes an entry whose neighbours are `prev` and `next` off a doubly linked list of
/// tokens that starts at `head`'s `first_child` and is linked by the fields
/// `next_of` and `prev_of` (inlined: the same code as written out for each list).
#[inline(always)]
fn unlink(
    tokens: &mut Slots<'_, TokenId, Token>,
    head: TokenId,
    (prev, next): (TokenId, TokenId),
    next_of: fn(&mut Token) -> &mut TokenId,
    prev_of: fn(&mut Token) -> &mut TokenId,
) {
    if prev != TokenId::NONE {
        *next_of(&mut tokens[prev]) = next;
    } else {
        tokens[head].first_child = next;
    }
    if next != TokenId::NONE {
        *prev_of(&mut tokens[next]) = prev;
    }
}

/// Walks a join's successors newest first: its child list (where a join from the
/// right sits just after its subnetwork's first join) merged with the joins taking
/// its tokens from the right, by creation.
struct Successors {
    left: JoinId,
    right: JoinId,
    /// Key of the last child taken from the child list.
    last_key: u32,
}

impl Successors {
    fn of(cx: &Core<'_>, join: JoinId) -> Successors {
        Successors {
            left: cx.joins[join].first_child,
            right: cx.joins[join].rsucc,
            last_key: u32::MAX,
        }
    }

    fn left_key(&self, cx: &Core<'_>) -> u32 {
        if cx.joins[self.left].rjoin != JoinId::NONE {
            self.last_key.saturating_sub(1)
        } else {
            2 * u32::from(self.left.0)
        }
    }

    fn next(&mut self, cx: &Core<'_>) -> Option<(JoinId, bool)> {
        let take_left = match (self.left != JoinId::NONE, self.right != JoinId::NONE) {
            (false, false) => return None,
            (true, false) => true,
            (false, true) => false,
            (true, true) => self.left_key(cx) > 2 * u32::from(self.right.0),
        };
        if take_left {
            let c = self.left;
            self.last_key = self.left_key(cx);
            self.left = cx.joins[c].next_sibling;
            Some((c, false))
        } else {
            let c = self.right;
            self.right = cx.joins[c].alpha_next;
            Some((c, true))
        }
    }
}

/// (host: the image keeps the plain order, `Core::take_back_newer_copies`)
#[cfg(all(test, feature = "grow"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;
    use std::string::String;
    use std::vec::Vec;

    /// The rules of the `<== Activation` lines of a transcript, in order.
    fn removed(out: &str) -> Vec<String> {
        out.lines()
            .filter_map(|l| l.strip_prefix("<== Activation"))
            .map(|l| l.split_whitespace().take(2).collect::<Vec<_>>().join(" "))
            .collect()
    }

    #[test]
    fn a_retract_takes_back_a_shared_joins_rule_ends_newest_first() {
        // r1 ends at the join r0 goes on from: r0's activation is made first (its
        // join was walked first), so CLIPS takes back r1's first
        let out = run_program(
            "(deftemplate a (slot y))
             (watch activations)
             (defrule r1 (a) =>)
             (defrule r0 (a) (a) =>)
             (assert (a (y 3)))
             (retract 1)",
        );
        assert_eq!(removed(&out), ["0 r1:", "0 r0:"], "{out}");
    }

    #[test]
    fn a_rule_end_primed_later_goes_before_older_partial_matches() {
        // r1 is defined after the fact: its activation is the newest
        let out = run_program(
            "(deftemplate a (slot y))
             (watch activations)
             (defrule r0 (a) (a) =>)
             (assert (a (y 3)))
             (defrule r1 (a) =>)
             (retract 1)",
        );
        assert_eq!(removed(&out), ["0 r1:", "0 r0:"], "{out}");
    }

    #[test]
    fn what_a_shared_join_built_on_other_facts_goes_after_its_own_fact() {
        // r4's second join took f-1 twice (a child of f-1's alpha match, made
        // before r2's activation), then f-2 on later asserts: those go last
        let out = run_program(
            "(deftemplate a (slot k))
             (watch activations)
             (defrule r2 (a) =>)
             (defrule r4 (a) (a) =>)
             (assert (a (k 1)))
             (assert (a (k 2)))
             (retract 1)",
        );
        let got: Vec<&str> = out
            .lines()
            .filter(|l| l.starts_with("<== Activation") && l.contains("f-1"))
            .map(|l| l.rsplit(' ').next().unwrap_or(""))
            .collect();
        assert_eq!(got, ["f-2,f-1", "f-1", "f-1,f-1", "f-1,f-2"], "{out}");
    }
}
