//! Deferred propagation: a rule's actions `(modify ?a ...) (modify ?b ...)` let the
//! second modify's retract go before the first modify's new fact is propagated.
//!
//! Why: a modify that changes a control fact (`(modify ?ctx (state next))`) after one
//! that changes a counter (`(modify ?cnt (c (+ ?c 1)))`) removes every partial match
//! below the control fact, including the ones the counter's new fact had just built.
//! Built after that retract, the new fact meets empty memories instead (Miss Manners
//! spends a third of its time on such matches).
//!
//! When it is exact: the network's final state after "propagate f, retract g" and after
//! "retract g, propagate f" is the same set of partial matches, and the matches f
//! builds are made in the same relative order (the memories they iterate only lack
//! g's matches), so the activations keep their agenda order. That needs a retract that
//! only deletes: g's template feeds no not/exists join and no join from the right
//! (whose removal would unblock and build matches), no owed matches are waiting, and
//! nothing is traced (`watch facts`, `watch activations`). And it needs tests on f's
//! side that cannot see the retract: only total builtins (`builtins::is_total`: no
//! deffunction, no fact or agenda query, nothing that can fail, as `<` on a symbol
//! would: the retract would remove the combination that reports it) in the alpha
//! tests of f's template and the join tests below them.
//!
//! Everything else keeps the eager order: an assert's propagation is deferred only for
//! a top-level action of a rule's right-hand side (an `assert` or `modify` there), and
//! any other function call, the next assert, a retract that may not overtake, and the
//! end of the actions build it first (`flush_deferred`). So between an assert and its
//! propagation only leaves are read, at most one overtaking retract runs, and
//! `printout`s of leaves write (people put one between the two modifies).
//!
//! Host: several facts may wait at once (`Queued`, at most `QUEUED_MAX` before the
//! newest): an assert whose next actions, past asserts and printouts that may wait,
//! reach a modify that may wait, joins the facts already waiting instead of building
//! them (Miss Manners' `find_seating` asserts a seating, a path and a chosen fact
//! before its two modifies). They are built oldest first, so each meets the ones
//! before it as in the eager order; a retract that may overtake one may overtake all
//! (it names none of them, and each had total tests when it was deferred).
//!
//! Such a `printout` (its router and arguments constants, variables and bound
//! globals, so it reads no fact and prints nothing but its text) writes into a held
//! buffer (`HeldPrint`): the text goes out once the propagation is built, and is
//! dropped when building it fails, as the eager order would have failed before the
//! printout ran. Text that does not fit, or goes to a file, builds the propagation
//! first and is written at once.
//!
//! A full pool found while building the deferred matches undoes that assert (a
//! modify's old fact comes back), and the error stops the actions where it was found,
//! as it would have stopped them at the assert; the overtaking retract is part of a
//! modify whose own failure path puts its old fact back. The facts that waited behind
//! the failing one go as if never asserted (their numbers are the next ones again,
//! their modifies' old facts come back), and only the text held before the failing
//! assert is written.

#[cfg(feature = "defer")]
use super::JoinKind;
#[cfg(feature = "defer")]
use crate::engine::watch;
use crate::engine::Core;
use crate::error::EvalError;
#[cfg(feature = "defer")]
use crate::expr::{FnKind, Op};
use crate::fact::Fact;
#[cfg(feature = "defer")]
use crate::handle::{JoinId, TokenId};
use crate::value::{Ix, NONE};

/// Flags of a template (see `Core::defer_flags`).
#[cfg(feature = "defer")]
const FLAGS_KNOWN: u8 = 1;
/// Its facts' propagation runs only total tests: it may be overtaken by a retract.
#[cfg(feature = "defer")]
const TOTAL_TESTS: u8 = 2;
/// Retracting one of its facts only deletes partial matches: it may overtake.
#[cfg(feature = "defer")]
const DELETE_ONLY: u8 = 4;

/// The fact whose propagation waits, and for a modify its old fact.
#[derive(Clone, Copy, Debug)]
pub struct Deferred {
    pub fact: Ix,
    pub old: Option<(Ix, Fact)>,
}

impl Deferred {
    pub const NONE: Deferred = Deferred {
        fact: NONE,
        old: None,
    };
}

/// Host: how many facts may wait before the newest (`State::deferred`): a rule's
/// asserts ahead of its modifies (Miss Manners' `find_seating` makes three).
#[cfg(feature = "defer")]
pub const QUEUED_MAX: usize = 4;

/// Host: what `worth_past_printouts`'s last walk by the builtins' ids found: the
/// `len` actions from `from` on, up to `end`, are all asserts or printouts. The
/// next assert's walk (from the action after `from`) starts at `end`: an action
/// list of asserts (an init rule's hundreds) then costs a step per assert, not
/// `SCAN_MAX`.
#[cfg(all(feature = "defer", feature = "host-speedups"))]
#[derive(Clone, Copy, Debug)]
pub struct ScanRun {
    pub from: Ix,
    pub end: Ix,
    pub len: u8,
}

#[cfg(all(feature = "defer", feature = "host-speedups"))]
impl ScanRun {
    pub const NONE: ScanRun = ScanRun {
        from: NONE,
        end: NONE,
        len: 0,
    };
}

/// A fact waiting before the newest, with the length of the held `printout` text
/// when it was asserted (what the eager order printed before that assert).
#[cfg(feature = "defer")]
#[derive(Clone, Copy, Debug)]
pub struct Queued {
    pub d: Deferred,
    pub held: u16,
}

#[cfg(feature = "defer")]
impl Queued {
    pub const NONE: Queued = Queued {
        d: Deferred::NONE,
        held: 0,
    };
}

/// Bytes of `printout` text held while a propagation waits (a few lines).
#[cfg(feature = "defer")]
pub const HELD_PRINT_BYTES: usize = 256;

/// `printout` text written while a propagation waits, to one of the engine's routers.
#[cfg(feature = "defer")]
pub struct HeldPrint {
    pub router: &'static str,
    pub text: crate::value::TextBuf<HELD_PRINT_BYTES>,
}

#[cfg(feature = "defer")]
impl HeldPrint {
    pub const EMPTY: HeldPrint = HeldPrint {
        router: "",
        text: crate::value::TextBuf::new(),
    };
}

#[cfg(feature = "defer")]
impl Core<'_> {
    /// `TOTAL_TESTS` and `DELETE_ONLY` of template `tmpl`, worked out once per network
    /// generation (`State::net_gen`).
    fn defer_flags(&mut self, tmpl: Ix) -> u8 {
        let t = self.tmpl_mems[tmpl as usize];
        if t.flags_gen == self.st.net.net_gen && t.defer_flags & FLAGS_KNOWN != 0 {
            return t.defer_flags;
        }
        let (mut total, mut delete_only) = (true, true);
        let mut a = self.templates[tmpl as usize].alpha_head;
        while a != NONE {
            let node = &self.alphas[a as usize];
            if node.live {
                total = total && self.calls_only(node.tests, crate::builtins::is_total);
                // a not/exists join on this pattern: its matches are blockers
                let mut j = node.succ;
                while j != JoinId::NONE {
                    let jn = &self.joins[j];
                    if matches!(jn.kind, JoinKind::Negative | JoinKind::Exists) {
                        delete_only = false;
                    }
                    j = jn.alpha_next;
                }
                let mut below_total = true;
                let mut below_no_rsucc = true;
                let walked = self.walk_joins(node.succ, true, &mut |cx, j| {
                    let jn = &cx.joins[j];
                    below_total = below_total
                        && cx.calls_only(jn.tests, crate::builtins::is_total)
                        && cx.calls_only(jn.post, crate::builtins::is_total);
                    // partial matches there block the outputs of a join from the right
                    below_no_rsucc = below_no_rsucc && jn.rsucc == JoinId::NONE;
                    true
                });
                total = total && walked && below_total;
                delete_only = delete_only && walked && below_no_rsucc;
            }
            a = self.alphas[a as usize].next_in_tmpl;
        }
        let flags = FLAGS_KNOWN
            | if total { TOTAL_TESTS } else { 0 }
            | if delete_only { DELETE_ONLY } else { 0 };
        let t = &mut self.tmpl_mems[tmpl as usize];
        t.defer_flags = flags;
        t.flags_gen = self.st.net.net_gen;
        flags
    }

    /// Whether a waiting propagation may stay waiting while action `e` runs: an
    /// assert or modify whose arguments call only quiet builtins (arithmetic and
    /// comparisons on leaves, `builtins::is_quiet`), so nothing runs before it decides
    /// that could see the propagation missing or print before what it prints
    /// (`assert_slots` builds it first, a modify's retract may overtake it; an error
    /// of the arguments is reported after the actions, once it is built).
    ///
    /// Or a `printout` of leaves (`printout_may_wait`), whose text is held.
    pub(crate) fn may_wait_for(&self, e: Ix) -> bool {
        let x = self.exprs[e as usize];
        if x.op != Op::Call || x.aux != FnKind::Builtin as u8 {
            return false;
        }
        if x.data == crate::builtins::ID_ASSERT || x.data == crate::builtins::ID_MODIFY {
            return self.calls_only(x.first, crate::builtins::is_quiet);
        }
        x.data == crate::builtins::ID_PRINTOUT && self.printout_may_wait(x.first)
    }

    /// Whether a `printout` with router and arguments from `e` on reads only leaves
    /// that print nothing and cannot fail but as values: constants, variables, and
    /// globals holding a value (an unbound one prints `[GLOBLDEF1]`).
    fn printout_may_wait(&self, mut e: Ix) -> bool {
        while e != NONE {
            let x = self.exprs[e as usize];
            let leaf = match x.op {
                Op::Int | Op::Float | Op::Sym | Op::Str | Op::Local | Op::PatVar => true,
                Op::Global => !matches!(
                    self.globals[x.data as usize].value,
                    crate::value::Value::Void
                ),
                _ => false,
            };
            if !leaf {
                return false;
            }
            e = x.next;
        }
        true
    }

    /// `printout` text for engine router `router` while a propagation waits: held
    /// (true) when it fits after what is held already (for the same router).
    pub(crate) fn hold_print(&mut self, router: &'static str, text: &str) -> bool {
        let h = &mut self.st.net.held_print;
        if !h.text.is_empty() && h.router != router {
            return false;
        }
        if h.text.len() + text.len() > HELD_PRINT_BYTES {
            return false;
        }
        h.router = router;
        core::fmt::Write::write_str(&mut h.text, text).is_ok()
    }

    /// The held `printout` text goes out up to byte `keep` (what the eager order
    /// printed before the propagation that failed; all of it when every one was
    /// built), the rest is dropped.
    fn release_print(&mut self, keep: usize) {
        if self.st.net.held_print.text.is_empty() {
            return;
        }
        let mut h = core::mem::replace(&mut self.st.net.held_print, HeldPrint::EMPTY);
        h.text.truncate(keep);
        if !h.text.is_empty() {
            self.write(h.router, h.text.as_str());
        }
    }

    /// Whether the expression chain from `e` (and everything below it) calls only
    /// builtins that `allowed` accepts.
    fn calls_only(&self, mut e: Ix, allowed: fn(Ix) -> bool) -> bool {
        while e != NONE {
            let x = self.exprs[e as usize];
            if x.op == Op::Call && (x.aux != FnKind::Builtin as u8 || !allowed(x.data)) {
                return false;
            }
            // a 64-bit constant's payload node (after its header) is data, not a child
            if !matches!(x.op, Op::Int | Op::Float) && !self.calls_only(x.first, allowed) {
                return false;
            }
            e = x.next;
        }
        true
    }

    /// Whether the assert or modify `call` should defer its propagation: it is the
    /// top-level action and the next action (past `printout`s that may wait) is a
    /// modify that may wait for it, whose retract may go first (anything else would
    /// build it at once, so deferring would only cost).
    // (inlined into `assert` and `modify`, as when it was smaller: out of line it
    // cost propagate-500 +0.15 %; the walk past printouts is out of line)
    #[inline(always)]
    pub(crate) fn defer_worth(&mut self, call: Ix) -> bool {
        if call != self.st.net.top_action {
            return false;
        }
        let n = self.exprs[call as usize].next;
        if n == NONE {
            return false;
        }
        let data = self.exprs[n as usize].data;
        if data == crate::builtins::ID_MODIFY {
            return self.may_wait_for(n);
        }
        if data == crate::builtins::ID_ASSERT {
            // most asserts followed by an assert are followed by neither after that
            // (`(assert ...) (assert ...) (bind ...)`): no call for them
            let m = self.exprs[n as usize].next;
            return m != NONE
                && matches!(
                    self.exprs[m as usize].data,
                    crate::builtins::ID_MODIFY
                        | crate::builtins::ID_ASSERT
                        | crate::builtins::ID_PRINTOUT
                )
                && self.worth_past_printouts(n);
        }
        data == crate::builtins::ID_PRINTOUT && self.worth_past_printouts(n)
    }

    /// `defer_worth` from action `n` on, a `printout` or an `assert`: past the
    /// printouts and asserts that may wait (the asserts' facts wait too, `Queued`),
    /// a modify that may wait.
    #[inline(never)]
    fn worth_past_printouts(&mut self, mut n: Ix) -> bool {
        // first by the builtins' ids alone: most action lists (`(assert ...)
        // (assert ...) (bind ...)`) reach no modify, and need no closer look. The walk
        // stops after `SCAN_MAX` actions: past more than `QUEUED_MAX` asserts the fact
        // could not wait until the modify anyway (the queue is full there and builds
        // it), and held printouts are few. So a long list of asserts (an init rule
        // asserting hundreds of facts) costs each of them a few steps, not the rest of
        // the list (quadratic).
        const SCAN_MAX: usize = 2 * QUEUED_MAX;
        let mut m = n;
        let mut budget = SCAN_MAX;
        // host: the last walk's run, when `n` is the action after its start, is
        // known (a stale run, of actions made again since, can only answer false:
        // no deferral, what the image always answers; the walk past the ids below
        // checks every action from `n` itself)
        #[cfg(feature = "host-speedups")]
        let mut len = 0u8;
        #[cfg(feature = "host-speedups")]
        {
            let r = self.st.net.scan;
            let made = self.st.pools.nexprs as usize;
            if r.len > 1
                && (r.from as usize) < made
                && (r.end == NONE || (r.end as usize) < made)
                && self.exprs[r.from as usize].next == n
            {
                len = r.len - 1;
                m = r.end;
                budget -= len as usize;
            }
        }
        loop {
            if m == NONE {
                return false;
            }
            let x = &self.exprs[m as usize];
            if x.op != Op::Call || x.aux != FnKind::Builtin as u8 {
                return false;
            }
            if x.data == crate::builtins::ID_MODIFY {
                break;
            }
            if x.data != crate::builtins::ID_PRINTOUT && x.data != crate::builtins::ID_ASSERT {
                return false;
            }
            budget -= 1;
            let next = x.next;
            #[cfg(feature = "host-speedups")]
            {
                len += 1;
            }
            if budget == 0 {
                #[cfg(feature = "host-speedups")]
                {
                    self.st.net.scan = ScanRun {
                        from: n,
                        end: next,
                        len,
                    };
                }
                return false;
            }
            m = next;
        }
        while n != NONE {
            let x = self.exprs[n as usize];
            if x.data == crate::builtins::ID_MODIFY {
                return self.may_wait_for(n);
            }
            if !(x.op == Op::Call
                && x.aux == FnKind::Builtin as u8
                && ((x.data == crate::builtins::ID_PRINTOUT && self.printout_may_wait(x.first))
                    || (x.data == crate::builtins::ID_ASSERT
                        && self.calls_only(x.first, crate::builtins::is_quiet))))
            {
                return false;
            }
            n = x.next;
        }
        false
    }

    /// Whether the assert of a top-level action, a fact of template `tmpl` whose
    /// propagation may wait (`defer_worth`), may join the ones already waiting
    /// (`Queued`) rather than build them first: one is waiting, there is room, and
    /// `may_defer`. (Not with dynamic constraint checking, which may refuse the
    /// deferral only once the fact is made.)
    #[inline(never)]
    pub(crate) fn may_queue(&mut self, tmpl: Ix) -> bool {
        #[cfg(feature = "extras")]
        if self.st.mode.dynamic_checks {
            return false;
        }
        self.st.net.deferred.fact != NONE
            && (self.st.net.nqueued as usize) < QUEUED_MAX
            && self.may_defer(tmpl)
    }

    /// The fact of a top-level assert or modify waits (`may_defer` held): behind the
    /// ones waiting already (`may_queue` held then).
    #[inline(never)]
    pub(crate) fn defer_fact(&mut self, fact: Ix, old: Option<(Ix, Fact)>) {
        let held = self.st.net.held_print.text.len() as u16;
        if self.st.net.deferred.fact != NONE {
            let n = self.st.net.nqueued as usize;
            self.st.net.queued[n] = Queued {
                d: self.st.net.deferred,
                held: self.st.net.deferred_held,
            };
            self.st.net.nqueued += 1;
        }
        self.st.net.deferred = Deferred { fact, old };
        self.st.net.deferred_held = held;
    }

    /// Whether the assert of a top-level action, a fact of template `tmpl`, may leave
    /// its propagation for later: in a firing, nothing traced, nothing owed, no undo
    /// replaying, and the template's tests total (else no retract could overtake it,
    /// and deferring would only cost). Nor when the random numbers CLIPS draws for
    /// every activation are seen (the random strategy, `random`, `seed`): activations
    /// never made would draw none.
    pub(crate) fn may_defer(&mut self, tmpl: Ix) -> bool {
        self.st.mode.firing
            && self.st.mode.watch & (watch::FACTS | watch::ACTIVATIONS) == 0
            && !self.st.random.observed
            && self.st.agenda.strategy != crate::strategy::Strategy::Random as u8
            && self.st.net.owed == TokenId::NONE
            && !self.st.agenda.act_journal.replay
            && !self.logical_busy()
            && self.defer_flags(tmpl) & TOTAL_TESTS != 0
    }

    /// Whether truth maintenance is at work: its retractions follow each operation,
    /// which a deferred propagation would reorder.
    #[inline(always)]
    fn logical_busy(&self) -> bool {
        #[cfg(feature = "logical")]
        return self.logical_in_use();
        #[cfg(not(feature = "logical"))]
        false
    }

    /// Whether the retract of live fact `old` (by the top-level modify `call`) may
    /// run before the waiting propagation (see the module docs).
    pub(crate) fn may_overtake(&mut self, call: Ix, old: Ix) -> bool {
        let waiting = self.st.net.deferred.fact;
        // the waiting fact itself is never retracted before it was propagated: a
        // literal index (`(modify 5 ...)` naming the new f-5) reaches it, so the
        // `waiting == old` check builds it first
        if waiting == NONE
            || waiting == old
            || self.st.net.queued[..self.st.net.nqueued as usize]
                .iter()
                .any(|q| q.d.fact == old)
            || call != self.st.net.top_action
            || self.st.mode.watch & (watch::FACTS | watch::ACTIVATIONS) != 0
            || self.st.net.owed != TokenId::NONE
            || self.st.agenda.act_journal.replay
            || self.logical_busy()
        {
            return false;
        }
        let (wt, ot) = (
            self.facts[waiting as usize].tmpl,
            self.facts[old as usize].tmpl,
        );
        self.defer_flags(wt) & TOTAL_TESTS != 0 && self.defer_flags(ot) & DELETE_ONLY != 0
    }

    /// Builds the waiting propagation, if any. On a full pool it is undone with its
    /// fact (a modify's old fact comes back) and the error returned.
    #[inline(always)]
    pub(crate) fn flush_deferred(&mut self) -> Result<(), EvalError> {
        // most callers find nothing waiting: no call for them
        if self.st.net.deferred.fact == NONE {
            return Ok(());
        }
        self.flush_waiting()
    }

    /// `flush_deferred` of waiting propagations, oldest first.
    #[inline(never)]
    fn flush_waiting(&mut self) -> Result<(), EvalError> {
        let n = self.st.net.nqueued as usize;
        let queued = self.st.net.queued;
        let last = Queued {
            d: self.st.net.deferred,
            held: self.st.net.deferred_held,
        };
        self.st.net.deferred = Deferred::NONE;
        self.st.net.nqueued = 0;
        let at = |i: usize| if i < n { queued[i] } else { last };
        for i in 0..=n {
            let f = at(i).d.fact;
            self.hold_traces();
            let mark = self.journal_begin();
            let r = self.network_assert(f).and_then(|()| self.pay_owed());
            self.journal_pause();
            if let Err(e) = r {
                self.undo_waiting(i, n, &at, mark);
                self.release_traces(false);
                // the eager order failed before the later printouts ran
                self.release_print(at(i).held as usize);
                return Err(e);
            }
            self.journal_end(mark);
            self.release_traces(true);
        }
        self.release_print(usize::MAX);
        Ok(())
    }

    /// The propagation of waiting fact `i` (of `0..=n`, `at`) failed: undone as a
    /// failed assert, with the facts after it, never propagated, as if never made
    /// (the eager order stopped at its assert); the old facts of their modifies come
    /// back.
    #[inline(never)]
    fn undo_waiting(
        &mut self,
        i: usize,
        n: usize,
        at: &dyn Fn(usize) -> Queued,
        mark: crate::agenda::JournalMark,
    ) {
        // as a failed assert: what the fact built goes, then the facts themselves,
        // newest first
        let f = at(i).d.fact;
        self.journal_replay(mark);
        self.network_retract_checked(f);
        for j in (i..=n).rev() {
            let g = at(j).d.fact;
            let fact = self.facts[g as usize];
            self.unlink_fact(g);
            self.release_fact_values(g);
            self.free_fact_slot(g);
            // nothing else was asserted since: its number is the next one again
            if fact.num.wrapping_add(1) == self.st.facts.next_fact_num {
                self.st.facts.next_fact_num = fact.num;
                #[cfg(feature = "extras")]
                self.forget_pattern_error();
            }
        }
        let _ = self.pay_owed();
        // the old facts' removed activations were journaled by their own modifies,
        // which are over: they come back as the newest (replay off)
        self.journal_end(mark);
        for j in (i..=n).rev() {
            if let Some((old, saved)) = at(j).d.old {
                // held since its retract (a firing holds retracted facts): its cells
                // are there, so no stacked values are needed
                if self.restore_fact(old, saved, 0).is_ok() {
                    let _ = self.pay_owed();
                }
            }
        }
    }
}

/// Without the `defer` feature (the agent image) nothing is deferred: these answer so,
/// and the callers' branches compile away.
#[cfg(not(feature = "defer"))]
impl Core<'_> {
    #[inline(always)]
    pub(crate) fn defer_worth(&self, _call: Ix) -> bool {
        false
    }

    #[inline(always)]
    pub(crate) fn may_defer(&mut self, _tmpl: Ix) -> bool {
        false
    }

    #[inline(always)]
    pub(crate) fn may_overtake(&mut self, _call: Ix, _old: Ix) -> bool {
        false
    }

    #[inline(always)]
    pub(crate) fn may_wait_for(&self, _e: Ix) -> bool {
        false
    }

    #[inline(always)]
    pub(crate) fn may_queue(&mut self, _tmpl: Ix) -> bool {
        false
    }

    #[inline(always)]
    pub(crate) fn defer_fact(&mut self, fact: Ix, old: Option<(Ix, Fact)>) {
        self.st.net.deferred = Deferred { fact, old };
    }

    #[inline(always)]
    pub(crate) fn flush_deferred(&mut self) -> Result<(), EvalError> {
        Ok(())
    }
}

#[cfg(all(test, feature = "defer"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;
    use std::string::String;

    /// `(item (id 0)) ... (item (id n-1))`.
    fn item_facts(n: usize) -> String {
        (0..n).map(|i| std::format!("(item (id {i})) ")).collect()
    }

    /// An action between two modifies that builds a waiting propagation first (a
    /// function call), giving the eager order.
    const EAGER: &str = "(bind ?z (+ 0 0))";

    /// A counter's modify followed by a control fact's modify: the counter's new fact
    /// meets the partial matches only after the control fact's retract removed them,
    /// with the agenda and facts of the eager order (`EAGER` between the two actions
    /// keeps that order).
    fn counter_program(between: &str, items: usize, watch: &str) -> String {
        let facts = item_facts(items);
        run_program(&std::format!(
            "(deftemplate cnt (slot c))
             (deftemplate ctx (slot s))
             (deftemplate item (slot id))
             (deffacts d (cnt (c 0)) (ctx (s go)) {facts})
             (defrule step ?x <- (ctx (s go)) (item (id ?i)) ?n <- (cnt (c ?c&~3))
               => (modify ?n (c (+ ?c 1))) {between} (modify ?x (s back)))
             (defrule back ?x <- (ctx (s back)) => (modify ?x (s go)))
             (defrule wide (cnt (c 2)) (item (id ?i)) (item (id ?j)) =>)
             (defrule count (declare (salience -5)) (cnt (c ?c)) (item (id ?i)) =>
               (printout t c ?c i ?i crlf))
             {watch}
             (reset)
             (run)
             (facts)
             (agenda)"
        ))
    }

    #[test]
    fn overtaking_retract_keeps_the_eager_result() {
        let deferred = counter_program("", 3, "");
        let eager = counter_program(EAGER, 3, "");
        assert_eq!(deferred, eager);
        assert!(deferred.contains("(cnt (c 3))"), "{deferred}");
        // and with every activation traced (no deferral at all)
        let traced = counter_program("", 3, "(watch activations)");
        assert!(traced.contains("==> Activation"), "{traced}");
    }

    /// The deferred matches do not fit (`wide` needs 20 x 20 tokens and activations
    /// for the counter at 2): the counter's modify is undone with the control fact's
    /// retract that overtook it, as the eager order fails at the counter's modify. The
    /// same facts and activations come back; the rebuilt activations' order is the
    /// journal's (both orders overflow its 24 entries here: they come back newest).
    #[test]
    fn full_pool_at_the_deferred_propagation_undoes_both_modifies() {
        let deferred = counter_program("", 20, "");
        let eager = counter_program(EAGER, 20, "");
        assert!(deferred.contains("[ERROR] out of "), "{deferred}");
        let split = |out: &str| {
            let (facts, agenda) = out
                .split_once("For a total of 23 facts.\n")
                .unwrap_or((out, ""));
            let mut acts: std::vec::Vec<String> = agenda.lines().map(String::from).collect();
            acts.sort();
            (String::from(facts), acts)
        };
        assert_eq!(split(&deferred), split(&eager));
        assert!(
            deferred.contains("(cnt (c 1))") && deferred.contains("(ctx (s go))"),
            "{deferred}"
        );
        assert!(
            deferred.contains("For a total of 40 activations."),
            "{deferred}"
        );
    }

    /// The control fact's retract goes first, so the counter's new fact meets no
    /// partial matches under it: 20 x 20 matches of `big` that the eager order builds
    /// (and runs out of room for) are never made.
    #[test]
    fn overtaking_retract_saves_the_matches_it_would_remove() {
        let program = |between: &str| {
            let items = item_facts(20);
            run_program(&std::format!(
                "(deftemplate cnt (slot c))
                 (deftemplate ctx (slot s))
                 (deftemplate item (slot id))
                 (deffacts d (cnt (c 0)) (ctx (s go)) {items})
                 (defrule step ?x <- (ctx (s go)) ?n <- (cnt (c ?c))
                   => (modify ?n (c (+ ?c 1))) {between} (modify ?x (s end)))
                 (defrule big (ctx (s go)) (cnt (c ?c&~0)) (item (id ?i)) (item (id ?j)) =>)
                 (reset)
                 (run)
                 (facts)"
            ))
        };
        let deferred = program("");
        assert!(!deferred.contains("[ERROR]"), "{deferred}");
        assert!(
            deferred.contains("(cnt (c 1))") && deferred.contains("(ctx (s end))"),
            "{deferred}"
        );
        let eager = program(EAGER);
        assert!(eager.contains("[ERROR] out of "), "{eager}");
    }

    /// A `printout` of leaves between the two modifies waits with the propagation: its
    /// text is held and goes out once the propagation is built, so the output is the
    /// eager order's; so is that of one holding too much text (it builds the
    /// propagation first) and of one to a router that is none of the engine's (its
    /// report comes after the propagation, as in the eager order).
    #[test]
    fn printout_between_the_modifies_prints_in_the_eager_order() {
        let long = "x".repeat(300);
        for between in [
            "(printout t \"between \" ?c \" \" ?i crlf)",
            "(printout t \"a \" ?c) (printout t \" b\" crlf)",
            "(printout t a crlf) (printout wdisplay b crlf)",
            &std::format!("(printout t \"{long}\" crlf)"),
            "(printout nosuch ?c crlf)",
        ] {
            let deferred = counter_program(between, 3, "");
            let eager = counter_program(&std::format!("{EAGER} {between}"), 3, "");
            assert_eq!(deferred, eager, "{between}");
            assert!(deferred.contains("c3i0"), "{deferred}");
        }
        let out = counter_program("(printout t \"between \" ?c \" \" ?i crlf)", 3, "");
        assert!(out.contains("between 2 "), "{out}");
    }

    /// The deferred matches do not fit: the text of the `printout` that waited with
    /// them is dropped, as the eager order stops at the counter's modify before the
    /// printout runs; the earlier firings' text stands.
    #[test]
    fn full_pool_drops_the_held_printout() {
        let between = "(printout t \"between \" ?c crlf)";
        let deferred = counter_program(between, 20, "");
        let eager = counter_program(&std::format!("{EAGER} {between}"), 20, "");
        assert!(deferred.contains("[ERROR] out of "), "{deferred}");
        let head = |out: &str| String::from(out.split_once("For a total of").map_or(out, |p| p.0));
        assert_eq!(head(&deferred), head(&eager));
        assert!(deferred.contains("between 0\n"), "{deferred}");
        assert!(!deferred.contains("between 1\n"), "{deferred}");
    }

    /// A `printout` between the modifies lets the retract overtake as well: the
    /// 20 x 20 matches of `big` are never made, and its text is printed.
    #[test]
    fn overtaking_retract_past_a_printout_saves_the_matches() {
        let items = item_facts(20);
        let out = run_program(&std::format!(
            "(defglobal ?*out* = t)
             (deftemplate cnt (slot c))
             (deftemplate ctx (slot s))
             (deftemplate item (slot id))
             (deffacts d (cnt (c 0)) (ctx (s go)) {items})
             (defrule step ?x <- (ctx (s go)) ?n <- (cnt (c ?c))
               => (modify ?n (c (+ ?c 1))) (printout ?*out* step \" \" ?c crlf)
                  (modify ?x (s end)))
             (defrule big (ctx (s go)) (cnt (c ?c&~0)) (item (id ?i)) (item (id ?j)) =>)
             (reset)
             (run)
             (facts)"
        ));
        assert!(!out.contains("[ERROR]"), "{out}");
        assert!(out.contains("step 0\n"), "{out}");
        assert!(
            out.contains("(cnt (c 1))") && out.contains("(ctx (s end))"),
            "{out}"
        );
    }

    /// `marks_program` with a `printout` after each action but the last, as is
    /// (deferred) and with `EAGER` before each `printout` (eager).
    fn printing_marks_programs(items: usize) -> (String, String) {
        let prints = [
            "(printout t p1 crlf)",
            "(printout t p2 crlf)",
            "(printout t p3 crlf)",
        ];
        let deferred = marks_program(prints, items);
        let eager = marks_program(
            prints
                .map(|p| std::format!("{EAGER} {p}"))
                .each_ref()
                .map(|s| s.as_str()),
            items,
        );
        (deferred, eager)
    }

    /// Two asserts, a counter's modify and a control fact's modify, with `printout`s
    /// between (`between` after each action but the last): the asserts' facts wait
    /// too (`Queued`). `wide` needs 20 x 20 matches for the second mark at 2.
    fn marks_program(between: [&str; 3], items: usize) -> String {
        let facts = item_facts(items);
        let [b1, b2, b3] = between;
        run_program(&std::format!(
            "(deftemplate cnt (slot c))
             (deftemplate ctx (slot s))
             (deftemplate item (slot id))
             (deftemplate mark (slot c) (slot k))
             (deffacts d (cnt (c 0)) (ctx (s go)) {facts})
             (defrule step ?x <- (ctx (s go)) ?n <- (cnt (c ?c&~3))
               => (assert (mark (c ?c) (k a))) {b1} (assert (mark (c ?c) (k b)))
                  (assert (mark (c ?c) (k a))) {b2} (modify ?n (c (+ ?c 1))) {b3}
                  (modify ?x (s back)))
             (defrule back ?x <- (ctx (s back)) => (modify ?x (s go)))
             (defrule wide (mark (c 2) (k b)) (item (id ?i)) (item (id ?j)) =>)
             (defrule under (ctx (s go)) (mark (c ?c) (k ?k)) (item (id ?i)) =>)
             (defrule count (declare (salience -5)) (mark (c ?c) (k ?k)) (item (id ?i)) =>
               (printout t c ?c k ?k i ?i crlf))
             (reset)
             (run)
             (facts)
             (agenda)"
        ))
    }

    /// The asserts' facts wait with the counter's for the control fact's retract:
    /// the output (fact numbers, a repeated assert making none, the printouts, the
    /// firing order, the agenda) is the eager order's.
    #[test]
    fn asserts_before_the_modifies_wait_with_the_eager_result() {
        let (deferred, eager) = printing_marks_programs(3);
        assert_eq!(deferred, eager);
        assert!(deferred.contains("(mark (c 2) (k b))"), "{deferred}");
        assert!(deferred.contains("c2kbi0"), "{deferred}");
        let plain = marks_program(["", "", ""], 3);
        let plain_eager = marks_program([EAGER, EAGER, EAGER], 3);
        assert_eq!(plain, plain_eager);
    }

    /// The asserts ahead of the modifies wait too: the control fact's retract goes
    /// first, so the first mark meets no partial matches under it; the eager order
    /// (an action between the asserts builds the first) runs out of room for the
    /// 20 x 20 matches of `big`.
    #[test]
    fn queued_asserts_save_the_matches_the_retract_would_remove() {
        let program = |between: &str| {
            let items = item_facts(20);
            run_program(&std::format!(
                "(deftemplate cnt (slot c))
                 (deftemplate ctx (slot s))
                 (deftemplate item (slot id))
                 (deftemplate mark (slot c) (slot k))
                 (deffacts d (cnt (c 0)) (ctx (s go)) {items})
                 (defrule step ?x <- (ctx (s go)) ?n <- (cnt (c ?c))
                   => (assert (mark (c ?c) (k a))) {between} (assert (mark (c ?c) (k b)))
                      (modify ?n (c (+ ?c 1))) (modify ?x (s end)))
                 (defrule big (ctx (s go)) (mark (k a)) (item (id ?i)) (item (id ?j)) =>)
                 (reset)
                 (run)
                 (facts)"
            ))
        };
        let deferred = program("");
        assert!(!deferred.contains("[ERROR]"), "{deferred}");
        assert!(
            deferred.contains("(mark (c 0) (k b))") && deferred.contains("(ctx (s end))"),
            "{deferred}"
        );
        let eager = program(EAGER);
        assert!(eager.contains("[ERROR] out of "), "{eager}");
    }

    /// The second waiting fact's matches do not fit: it and the facts after it are
    /// undone (the counter's old fact comes back, the control fact's modify is
    /// undone), the first mark stays, and only the text printed before the failing
    /// assert is written, as in the eager order. The activations are the eager
    /// order's, but for the firing rule's own match: the eager order never retracted
    /// the counter and the control fact; brought back here, they come back as after
    /// a journal overflow, all newest, the firing match too.
    #[test]
    fn full_pool_at_a_queued_fact_undoes_the_rest() {
        let (deferred, eager) = printing_marks_programs(20);
        assert!(deferred.contains("[ERROR] out of "), "{deferred}");
        let split = |out: &str| {
            let (facts, agenda) = out.split_once("For a total of").unwrap_or((out, ""));
            let mut acts: std::vec::Vec<String> = agenda
                .lines()
                .filter(|l| !l.contains("activations.") && !l.contains("step: f-32,f-30"))
                .map(String::from)
                .collect();
            acts.sort();
            (String::from(facts), acts)
        };
        assert_eq!(split(&deferred), split(&eager));
        assert!(deferred.contains("step: f-32,f-30"), "{deferred}");
        assert!(
            deferred.contains("(mark (c 2) (k a))")
                && !deferred.contains("(mark (c 2) (k b))")
                && deferred.contains("(cnt (c 2))")
                && deferred.contains("(ctx (s go))"),
            "{deferred}"
        );
        assert_eq!(deferred.matches("p1\n").count(), 3, "{deferred}");
        assert_eq!(deferred.matches("p2\n").count(), 2, "{deferred}");
    }

    /// A join test that can fail (`>` of a symbol) keeps the eager order: the counter's
    /// new fact meets the control fact before the second modify retracts it, so the
    /// error is reported and the actions stop, as in CLIPS; with `eq`, which cannot
    /// fail, the retract overtakes and both modifies complete.
    #[test]
    fn fallible_join_test_keeps_its_error() {
        let program = |test: &str| {
            run_program(&std::format!(
                "(deftemplate cnt (slot c))
                 (deftemplate ctx (slot s))
                 (deffacts d (cnt (c 0)) (ctx (s go)))
                 (defrule step ?x <- (ctx (s go)) ?n <- (cnt (c 0))
                   => (modify ?n (c 1)) (modify ?x (s stop)))
                 (defrule chk (cnt (c ?c)) (ctx (s ?s)) (test (or (neq ?s go) {test})) =>)
                 (reset)
                 (run)
                 (facts)"
            ))
        };
        let fallible = program("(< ?c 1) (> ?s ?c)");
        assert!(fallible.contains("[ARGACCES5]"), "{fallible}");
        assert!(fallible.contains("(ctx (s go))"), "{fallible}");
        let total = program("(eq ?c 0)");
        assert!(!total.contains("[ARGACCES5]"), "{total}");
        assert!(total.contains("(ctx (s stop))"), "{total}");
    }
}
