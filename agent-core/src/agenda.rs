//! The agenda: activations ordered by salience, then by the conflict resolution
//! strategy (`strategy`; depth by default: newer activations first). Refraction comes
//! from the network: a fired activation is gone, and only a new partial match can
//! activate the rule again.

use crate::engine::{watch, Core};
use crate::error::{CapacityError, Pool};
use crate::handle::TokenId;
use crate::rule::Activation;
use crate::value::Ix;
use crate::value::NONE;

/// How many removed activations one assert or modify can put back in place.
pub const JOURNAL_LEN: usize = 24;

/// `ModuleState::fmod` while no module's agenda start is known.
#[cfg(all(feature = "modules", feature = "host-speedups"))]
pub const NO_FOCUS_CACHE: u16 = u16::MAX;

/// `set-salience-evaluation`'s settings (`Mode::salience_eval`): a rule's salience
/// expression is evaluated when the rule is defined (and by `refresh-agenda`), also
/// when each activation is made, or also before each firing (CLIPS's three).
pub const SALIENCE_WHEN_DEFINED: u8 = 0;
pub const SALIENCE_WHEN_ACTIVATED: u8 = 1;
pub const SALIENCE_EVERY_CYCLE: u8 = 2;

/// An activation an assert or modify removed (one that existed before it began): its
/// rule, what it matched and its creation number, which is its agenda place.
#[derive(Clone, Copy, Debug)]
pub struct JournalEntry {
    pub rule: Ix,
    /// Hash of the fact numbers the activation matched.
    pub basis: u32,
    pub seq: u32,
    /// Its random-strategy number (an undo draws no new one).
    #[cfg(feature = "extras")]
    pub random: u32,
}

/// Where a (possibly nested) journal recording began: the journal as it was then,
/// and the last activation number then (later ones are the operation's own).
#[derive(Clone, Copy, Debug)]
pub struct JournalMark {
    pub len: u8,
    pub on: bool,
    pub overflow: bool,
    /// The journal's `base` then.
    pub base: u32,
    pub seq: u32,
}

/// The activations removed while `on` (see `JournalEntry`); `overflow` once more than
/// `JOURNAL_LEN` were. Activations numbered after `base` (the start of the innermost
/// recording) are the operation's own: the undo removes them for good, so they are
/// not recorded.
#[derive(Clone, Copy, Debug)]
pub struct ActJournal {
    pub on: bool,
    pub overflow: bool,
    pub len: u8,
    pub base: u32,
    /// An undo is rebuilding what the operation removed: new activations take their
    /// recorded numbers from the entries from `replay_from` on (see `add_activation`).
    pub replay: bool,
    pub replay_from: u8,
    pub entries: [JournalEntry; JOURNAL_LEN],
}

impl ActJournal {
    pub const EMPTY: ActJournal = ActJournal {
        on: false,
        overflow: false,
        len: 0,
        base: 0,
        replay: false,
        replay_from: 0,
        entries: [JournalEntry {
            rule: NONE,
            basis: 0,
            seq: 0,
            #[cfg(feature = "extras")]
            random: 0,
        }; JOURNAL_LEN],
    };
}

impl Core<'_> {
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn add_activation(&mut self, rule: Ix, token: TokenId) -> Result<(), CapacityError> {
        let mut replayed = None;
        if self.st.agenda.act_journal.replay && !self.st.agenda.act_journal.overflow {
            match self.journal_take(rule, token) {
                Some(seq) => replayed = Some(seq),
                // not on the agenda before the operation: the rule had fired for this
                // match (refraction), so the undo must not bring it back
                None => return Ok(()),
            }
        }
        let a = if self.st.pools.act_free != NONE {
            let a = self.st.pools.act_free;
            self.st.pools.act_free = self.acts[a as usize].next;
            a
        } else {
            let n = self.st.pools.acts_used as usize;
            if n >= self.acts.len() || n >= NONE as usize {
                crate::engine::full_pool!(self, Pool::Activations, n + 1, self.acts.len());
            }
            self.st.pools.acts_used += 1;
            // the mark follows `acts_used`, which only a fresh entry raises
            self.note_hw(Pool::Activations, self.st.pools.acts_used as usize);
            n as Ix
        };
        let seq = match replayed {
            Some((seq, _)) => seq,
            None => {
                self.st.agenda.act_seq = self.st.agenda.act_seq.wrapping_add(1);
                self.st.agenda.act_seq
            }
        };
        // CLIPS draws a random number for every activation, whatever the strategy:
        // `(random)` after activations gives what it gives in CLIPS
        #[cfg(feature = "extras")]
        let random = match replayed {
            Some((_, random)) => random,
            None => crate::builtins::random::next_random(self.st) as u32,
        };
        // CLIPS evaluates a dynamic salience for each new activation unless it is
        // evaluated when defined only; asserts are refused meanwhile (it is matching)
        #[cfg(feature = "extras")]
        let salience = if self.st.mode.salience_eval != SALIENCE_WHEN_DEFINED {
            self.st.net.matching += 1;
            let s = self.evaluate_salience(rule, true);
            self.st.net.matching -= 1;
            s?
        } else {
            i32::from(self.rules[rule as usize].salience)
        };
        #[cfg(not(feature = "extras"))]
        let salience = i32::from(self.rules[rule as usize].salience);
        let next_of_token = self.tokens[token].extra;
        self.acts[a as usize] = Activation {
            rule,
            token,
            salience,
            seq,
            next: NONE,
            prev: NONE,
            next_of_token,
            #[cfg(feature = "extras")]
            random,
        };
        self.tokens[token].extra = a;
        // a replayed activation has its old number back, hence its old place
        self.agenda_insert(a);
        // an auto-focus rule's module is focused first (CLIPS prints it first)
        // (the tag is looked up only once some rule has auto-focus); a module's
        // known agenda start kept
        #[cfg(feature = "modules")]
        if self.st.modules.add_hooks != 0 {
            self.activation_module_hooks(rule, a)?;
        }
        if self.st.mode.watch & watch::ACTIVATIONS != 0
            && self.rule_traced(watch::ACTIVATIONS, rule)
        {
            self.print_activation_line("==> Activation ", a);
        }
        Ok(())
    }

    /// `(refresh RULE)`: every complete match of rule `r` (each of its disjuncts) that
    /// has no activation of it, because it fired, goes back on the agenda. A rule's
    /// complete matches are its terminal join's parent's memory, newest first: the
    /// order of CLIPS's terminal join's one unhashed bucket, entered at its head. A
    /// running-out pool is the capacity error (activations added so far stay).
    #[cfg(feature = "extras")]
    pub(crate) fn refresh_rule(&mut self, r: Ix) -> Result<(), CapacityError> {
        let mut d = r;
        while d != NONE {
            let terminal = self.rules[d as usize].terminal;
            let parent = self.joins[terminal].parent;
            // host: a rule end primed from an older sibling keeps its own order of
            // the partial matches it was primed with (`rete::order`)
            #[cfg(feature = "grow")]
            if self.primed_entry(terminal).is_some() {
                for t in self.clips_memory_order(terminal, parent) {
                    if !self.has_activation(d, t) {
                        self.add_activation(d, t)?;
                    }
                }
                d = self.rules[d as usize].next_disjunct;
                continue;
            }
            let mut t = self.join_mems[parent].mem;
            while t != TokenId::NONE {
                let next = self.tokens[t].mem_next;
                if self.token_active(t) && !self.has_activation(d, t) {
                    self.add_activation(d, t)?;
                }
                t = next;
            }
            d = self.rules[d as usize].next_disjunct;
        }
        Ok(())
    }

    /// Whether partial match `t` has an activation of rule `r`.
    #[cfg(feature = "extras")]
    fn has_activation(&self, r: Ix, t: TokenId) -> bool {
        let mut a = self.tokens[t].extra;
        while a != NONE {
            if self.acts[a as usize].rule == r {
                return true;
            }
            a = self.acts[a as usize].next_of_token;
        }
        false
    }

    /// CLIPS's EvaluateSalience: rule `rule`'s salience expression (if it has one)
    /// evaluated now; the value becomes the rule's salience. An error, a value that
    /// is not an integer or one out of -10000..=10000 is reported with `[PRNTUTIL8]`
    /// and the rule's last salience stays; execution halts as CLIPS's evaluation
    /// error makes it (a refresh goes on, a deffunction in a later salience is FALSE;
    /// a run stops after the refresh); when `halt` (an activation being made), as after
    /// a pattern error (a multi-fact assert stops).
    /// A rule read in place whose salience changes is copied first
    /// (`network_writable`): no room for the copy is a capacity error.
    pub(crate) fn evaluate_salience(&mut self, rule: Ix, halt: bool) -> Result<i32, CapacityError> {
        let last = i32::from(self.rules[rule as usize].salience);
        let e = self.rules[rule as usize].salience_expr;
        if e == NONE {
            return Ok(last);
        }
        let (scratch, sp, pm) = (
            self.st.frame.scratch_top,
            self.st.frame.sp,
            self.st.net.pm_rhs,
        );
        let v = self.eval(e);
        (
            self.st.frame.scratch_top,
            self.st.frame.sp,
            self.st.net.pm_rhs,
        ) = (scratch, sp, pm);
        let s = match v {
            // (CLIPS keeps a C `int` of the value, then checks it)
            Ok(crate::value::Value::Int(i)) if (-10000..=10000).contains(&(i as i32)) => i as i32,
            Err(e) => {
                if let crate::error::EvalErrorKind::Capacity(c) = e.kind() {
                    return Err(c);
                }
                self.report_eval_error(e);
                self.salience_error(rule, halt);
                return Ok(last);
            }
            Ok(crate::value::Value::Int(_)) => {
                self.write(
                    crate::host::router::WERROR,
                    "\n[PRNTUTIL9] Salience value out of range -10000 to 10000.\n",
                );
                self.salience_error(rule, halt);
                return Ok(last);
            }
            Ok(_) => {
                self.write(
                    crate::host::router::WERROR,
                    "\n[PRNTUTIL10] Salience value must be an integer value.\n",
                );
                self.salience_error(rule, halt);
                return Ok(last);
            }
        };
        if s != last {
            self.network_writable()?;
            // (in CLIPS's range, checked above)
            self.rules[rule as usize].salience = s as i16;
        }
        Ok(s)
    }

    /// `[PRNTUTIL8]`: which rule's salience failed (out of line: errors are rare).
    #[cold]
    #[inline(never)]
    fn salience_error(&mut self, rule: Ix, halt: bool) {
        use core::fmt::Write;
        let mut b: crate::value::TextBuf<160> = crate::value::TextBuf::new();
        let _ = writeln!(
            b,
            "\n[PRNTUTIL8] This error occurred while evaluating the salience for defrule {}.",
            self.sym_text(self.rules[rule as usize].name)
        );
        self.write(crate::host::router::WERROR, b.as_str());
        // CLIPS's evaluation error halts execution (a deffunction called in a later
        // salience is FALSE); while an activation is made, as a pattern error
        if halt {
            self.st.net.pattern_error = true;
        }
        self.st.mode.halting = true;
    }

    /// Inserts before the first activation it goes before (`goes_before`).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn agenda_insert(&mut self, a: Ix) {
        // host: kept salience groups are a walk of their own (out of line: long
        // agendas only), the short agenda's walk counts its steps only
        #[cfg(feature = "host-speedups")]
        if self.st.agenda.groups.kept {
            self.agenda_insert_grouped(a);
            return;
        }
        let mut prev = NONE;
        let mut cur = self.st.agenda.agenda_head;
        #[cfg(feature = "host-speedups")]
        let mut steps = 0u32;
        while cur != NONE && !self.goes_before(a, cur) {
            prev = cur;
            cur = self.acts[cur as usize].next;
            #[cfg(feature = "host-speedups")]
            {
                steps += 1;
            }
        }
        self.agenda_link(a, prev, cur);
        #[cfg(feature = "host-speedups")]
        if steps > GROUP_WALK {
            self.build_groups();
        }
    }

    /// `agenda_insert` while the salience groups are kept.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn agenda_insert_grouped(&mut self, a: Ix) {
        // the two places found at once come first (the lex/mea index, when on,
        // records every insertion: the general way)
        #[cfg(all(feature = "extras", feature = "grow"))]
        let indexed = self.st.recency_index.on && is_recency(self.st.agenda.strategy);
        #[cfg(not(all(feature = "extras", feature = "grow")))]
        let indexed = false;
        if !indexed && self.group_insert_quick(a) {
            return;
        }
        let mut prev = NONE;
        let mut cur = self.st.agenda.agenda_head;
        // from the first activation of no higher salience (those before it all go
        // first), found through the salience groups
        let group = self.group_start(a, &mut prev, &mut cur);
        // lex and mea: the place from the ordered index when it is on
        #[cfg(all(feature = "extras", feature = "grow"))]
        if self.st.recency_index.on && is_recency(self.st.agenda.strategy) {
            if let Some((p, c)) = self.rindex_insert(a) {
                self.group_insert(group, a, p, c);
                self.agenda_link(a, p, c);
                return;
            }
        }
        let mut steps = 0u32;
        // a place at either end of its own salience group is found at once
        let placed = group != usize::MAX && self.group_place(group, a, &mut prev, &mut cur);
        // lex and mea walk with the kept recency lists (`recency_walk`)
        #[cfg(all(feature = "extras", feature = "grow"))]
        let placed = placed
            || (is_recency(self.st.agenda.strategy)
                && match self.recency_walk(a, &mut prev, &mut cur) {
                    Some(n) => {
                        steps = n;
                        true
                    }
                    None => false,
                });
        // a re-sort inserts the activations in their old order, so one after another
        // of a group often goes a little after the one before (a group whose old
        // saliences differed: two rules' activations by recency): the walk starts at
        // that one when it goes first (the group is in `goes_before` order)
        let h = self.st.agenda.groups.hint;
        if !placed
            && h != NONE
            && group != usize::MAX
            && self.acts[h as usize].salience == self.acts[a as usize].salience
            && self.goes_before(h, a)
        {
            prev = h;
            cur = self.acts[h as usize].next;
        }
        while !placed && cur != NONE && !self.goes_before(a, cur) {
            prev = cur;
            cur = self.acts[cur as usize].next;
            steps += 1;
        }
        self.group_insert(group, a, prev, cur);
        self.agenda_link(a, prev, cur);
        if steps > GROUP_WALK && group == usize::MAX {
            self.build_groups();
        }
    }

    /// Links activation `a` into the agenda between `prev` and `cur`.
    #[inline(always)]
    fn agenda_link(&mut self, a: Ix, prev: Ix, cur: Ix) {
        self.acts[a as usize].prev = prev;
        self.acts[a as usize].next = cur;
        if cur != NONE {
            self.acts[cur as usize].prev = a;
        }
        if prev != NONE {
            self.acts[prev as usize].next = a;
        } else {
            self.st.agenda.agenda_head = a;
        }
        self.st.agenda.agenda_len += 1;
    }

    /// `add_activation`'s module work, out of line (`ModuleState::add_hooks`): a
    /// module's known agenda start kept, an auto-focus rule's module focused.
    #[cfg(feature = "modules")]
    #[cold]
    #[inline(never)]
    fn activation_module_hooks(&mut self, rule: Ix, a: Ix) -> Result<(), CapacityError> {
        #[cfg(not(feature = "host-speedups"))]
        let _ = a;
        // (every hook needs the rule's module: looked up once)
        let tag = self.rule_tag(rule);
        #[cfg(feature = "host-speedups")]
        {
            let hooks = self.st.modules.add_hooks;
            if hooks & crate::module::HOOK_FOCUS_CACHE != 0 {
                self.focus_cache_add(a, tag.module);
            }
            if hooks & crate::module::HOOK_COUNT != 0 {
                let n = &mut self.st.modules.acts_in[usize::from(tag.module)];
                *n = n.saturating_add(1);
            }
        }
        if self.st.modules.add_hooks & crate::module::HOOK_AUTO_FOCUS != 0 && tag.auto_focus {
            self.push_focus(tag.module)?;
        }
        Ok(())
    }

    /// New activation `a` (of module `of`) while a module's agenda start is known:
    /// one of that module's that goes before the start is its first now.
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    fn focus_cache_add(&mut self, a: Ix, of: crate::module::ModId) {
        if u16::from(of) == self.st.modules.fmod {
            // (a start a retract took stays as it is: `focused_head` walks then)
            let h = self.st.modules.fhead;
            if h == NONE || (self.focus_cache_live(h) && self.goes_before(a, h)) {
                self.focus_cache_set(a);
            }
        }
    }

    /// From the second module on: activations are counted per module
    /// (`ModuleState::acts_in`), those on the agenda now first.
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    pub(crate) fn start_module_counts(&mut self) {
        if self.st.modules.add_hooks & crate::module::HOOK_COUNT != 0 {
            return;
        }
        self.st.modules.acts_in = [0; 256];
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            let m = self.rule_tag(self.acts[a as usize].rule).module;
            let n = &mut self.st.modules.acts_in[usize::from(m)];
            *n = n.saturating_add(1);
            a = self.acts[a as usize].next;
        }
        self.st.modules.add_hooks |= crate::module::HOOK_COUNT;
    }

    /// Whether the known agenda start `h` (not NONE) is still the activation it was.
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    #[inline(always)]
    fn focus_cache_live(&self, h: Ix) -> bool {
        let x = &self.acts[h as usize];
        x.rule != NONE && x.seq == self.st.modules.fseq
    }

    /// The known agenda start becomes `a` (NONE: the module has no activation).
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    #[inline(always)]
    fn focus_cache_set(&mut self, a: Ix) {
        self.st.modules.fhead = a;
        if a != NONE {
            self.st.modules.fseq = self.acts[a as usize].seq;
        }
    }

    /// Forgets the known agenda start (the agenda is rebuilt).
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    pub(crate) fn focus_cache_clear(&mut self) {
        self.st.modules.fmod = NO_FOCUS_CACHE;
        self.st.modules.fhead = NONE;
        self.st.modules.add_hooks &= !crate::module::HOOK_FOCUS_CACHE;
    }

    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn agenda_unlink(&mut self, a: Ix) {
        let x = self.acts[a as usize];
        #[cfg(feature = "host-speedups")]
        self.group_unlink(&x, a);
        self.agenda_unlink_links(&x);
    }

    /// `agenda_unlink` of activation `x` once its salience group knows.
    #[inline(always)]
    fn agenda_unlink_links(&mut self, x: &crate::rule::Activation) {
        self.st.agenda.agenda_len -= 1;
        if x.prev != NONE {
            self.acts[x.prev as usize].next = x.next;
        } else {
            self.st.agenda.agenda_head = x.next;
        }
        if x.next != NONE {
            self.acts[x.next as usize].prev = x.prev;
        }
    }

    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn remove_activation(&mut self, a: Ix) {
        if self.st.agenda.act_journal.on {
            self.journal_activation(a);
        }
        if self.st.mode.watch & watch::ACTIVATIONS != 0 && self.activation_traced(a) {
            self.print_activation_line("<== Activation ", a);
        }
        self.agenda_unlink(a);
        self.free_activation(a);
    }

    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn free_activation(&mut self, a: Ix) {
        // unlink from the token's activation chain
        let t = self.acts[a as usize].token;
        if t != TokenId::NONE {
            let mut p = self.tokens[t].extra;
            if p == a {
                self.tokens[t].extra = self.acts[a as usize].next_of_token;
            } else {
                while p != NONE {
                    let n = self.acts[p as usize].next_of_token;
                    if n == a {
                        self.acts[p as usize].next_of_token = self.acts[a as usize].next_of_token;
                        break;
                    }
                    p = n;
                }
            }
        }
        self.acts[a as usize] = Activation {
            next: self.st.pools.act_free,
            ..Activation::EMPTY
        };
        self.st.pools.act_free = a;
    }

    /// Pops the focus stack's modules whose agendas are empty, down to one with an
    /// activation (or none left).
    #[cfg(feature = "modules")]
    pub(crate) fn pop_empty_focus(&mut self) {
        let _ = self.focused_head();
    }

    /// The activation that fires next, if any: the first of the focused module's
    /// agenda (the agenda is one list in CLIPS's order: each module's agenda is its
    /// activations in that order); a module with none leaves the focus stack.
    #[inline]
    fn next_activation(&mut self) -> Option<Ix> {
        #[cfg(feature = "modules")]
        let a = match self.single_module_head() {
            Some(a) => a,
            None => self.focused_head()?,
        };
        #[cfg(not(feature = "modules"))]
        let a = self.st.agenda.agenda_head;
        (a != NONE).then_some(a)
    }

    /// Takes the top activation off the agenda (it fires; refraction keeps it gone).
    pub(crate) fn pop_activation(&mut self) -> Option<(Ix, TokenId)> {
        #[cfg(all(feature = "modules", feature = "host-speedups"))]
        let a = match self.single_module_head() {
            Some(a) => a,
            None => self.focused_pop_head()?,
        };
        #[cfg(not(all(feature = "modules", feature = "host-speedups")))]
        let a = self.next_activation()?;
        Some(self.take_activation(a))
    }

    /// `focused_head` for `pop_activation`: the focused module's known agenda start
    /// fires, so its others lie after it (out of line: the one-module way stays as
    /// it was).
    #[cfg(all(feature = "modules", feature = "host-speedups"))]
    #[inline(never)]
    fn focused_pop_head(&mut self) -> Option<Ix> {
        let a = self.focused_head()?;
        if a == self.st.modules.fhead {
            let next = self.acts[a as usize].next;
            self.focus_cache_set(next);
        }
        // (it fires: its module's count leaves it; `focused_head` found it there)
        if self.st.modules.add_hooks & crate::module::HOOK_COUNT != 0 {
            let n = &mut self.st.modules.acts_in[usize::from(self.st.modules.head_mod)];
            *n = n.saturating_sub(1);
        }
        Some(a)
    }

    /// `pop_activation` while the run loop's general path is off (`Mode::run_slow`):
    /// MAIN is the one module and focused, so the agenda's head fires (an empty
    /// agenda takes the general way, which pops the focus).
    #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
    #[inline(always)]
    pub(crate) fn pop_head(&mut self) -> Option<(Ix, TokenId)> {
        let a = self.st.agenda.agenda_head;
        if a == NONE {
            return self.pop_activation();
        }
        Some(self.take_activation(a))
    }

    /// Takes activation `a` off the agenda: its rule and partial match.
    #[inline(always)]
    fn take_activation(&mut self, a: Ix) -> (Ix, TokenId) {
        let x = self.acts[a as usize];
        #[cfg(not(feature = "host-speedups"))]
        self.agenda_unlink(a);
        // host: the one that fires is most often the first of the first salience
        // group, which then keeps others (in line here, the other removals call)
        #[cfg(feature = "host-speedups")]
        {
            // (one test when no groups are kept, as `group_unlink`)
            let g = &mut self.st.agenda.groups;
            if g.kept | g.overflow {
                let e = &mut g.groups[0];
                if g.kept && g.n > 0 && e.first == a && e.count > 1 {
                    e.first = x.next;
                    e.count -= 1;
                } else {
                    self.group_unlink_kept(&x, a);
                }
            }
            self.agenda_unlink_links(&x);
        }
        self.free_activation(a);
        (x.rule, x.token)
    }

    /// The rule of the activation `pop_activation` would take next (a module with
    /// none leaves the focus stack, as there).
    #[cfg(feature = "extras")]
    pub(crate) fn next_activation_rule(&mut self) -> Option<Ix> {
        let a = self.next_activation()?;
        Some(self.acts[a as usize].rule)
    }

    /// The agenda's head when MAIN is the only module and focused: every activation is
    /// MAIN's then, so the general walk (`focused_head`) would stop at the head. None
    /// sends the caller to that walk (an empty agenda pops the focus there).
    #[cfg(feature = "modules")]
    #[inline(always)]
    fn single_module_head(&self) -> Option<Ix> {
        let m = &self.st.modules;
        let a = self.st.agenda.agenda_head;
        (m.nmodules == 1 && m.depth != 0 && a != NONE).then_some(a)
    }

    /// The first activation of the focused module's agenda, popping modules with none
    /// off the focus stack; None when the stack runs empty. An empty stack is given
    /// MAIN first: CLIPS focuses MAIN whenever it looks for the next activation with
    /// nothing focused (a rule's `pop-focus` emptied it, say).
    #[cfg(feature = "modules")]
    #[inline(never)]
    fn focused_head(&mut self) -> Option<Ix> {
        if self.focus_top().is_none() {
            self.push_focus(crate::module::MAIN).ok()?;
        }
        loop {
            let m = self.focus_top()?;
            // a module counted with none has none: no walk past the others'
            #[cfg(feature = "host-speedups")]
            if self.st.modules.add_hooks & crate::module::HOOK_COUNT != 0
                && self.st.modules.acts_in[usize::from(m)] == 0
            {
                self.pop_focus();
                continue;
            }
            // from the module's known agenda start while it is still on the agenda
            // (a retract may have taken it: its entry is free, or made again with
            // another number), else from the agenda's head
            #[cfg(feature = "host-speedups")]
            let h = self.st.modules.fhead;
            #[cfg(feature = "host-speedups")]
            let mut a = if self.st.modules.fmod == u16::from(m)
                && (h == NONE || self.focus_cache_live(h))
            {
                h
            } else {
                self.st.agenda.agenda_head
            };
            #[cfg(not(feature = "host-speedups"))]
            let mut a = self.st.agenda.agenda_head;
            while a != NONE && !self.activation_in(a, m) {
                a = self.acts[a as usize].next;
            }
            // known from now on (kept by `add_activation` and `pop_activation`), with
            // more modules than MAIN only: MAIN alone never walks
            #[cfg(feature = "host-speedups")]
            if self.st.modules.nmodules > 1 {
                self.st.modules.fmod = u16::from(m);
                self.focus_cache_set(a);
                self.st.modules.add_hooks |= crate::module::HOOK_FOCUS_CACHE;
            }
            if a != NONE {
                #[cfg(feature = "host-speedups")]
                {
                    self.st.modules.head_mod = m;
                }
                return Some(a);
            }
            // (the walk began at the agenda's head or where all of `m`'s lie: it has
            // none, whatever retracts left its count at)
            #[cfg(feature = "host-speedups")]
            {
                self.st.modules.acts_in[usize::from(m)] = 0;
            }
            self.pop_focus();
        }
    }

    /// `refresh-agenda`: the salience of each activation (of module `m`, all when
    /// None) is evaluated again, in agenda order, whatever the salience evaluation
    /// setting (CLIPS's RefreshAgenda; a rule without activations keeps its last
    /// salience), then the agenda is re-sorted. A full arena when a rule read in place
    /// must be copied is a capacity error (saliences set so far stay, sorted).
    pub fn reorder_agenda(&mut self, m: Option<crate::module::ModId>) -> Result<(), CapacityError> {
        #[cfg(not(feature = "modules"))]
        let _ = m;
        let mut r = Ok(());
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            let x = self.acts[a as usize];
            #[cfg(feature = "modules")]
            let here = m.is_none_or(|m| self.activation_in(a, m));
            // (MAIN is the one module)
            #[cfg(not(feature = "modules"))]
            let here = true;
            if here {
                match self.evaluate_salience(x.rule, false) {
                    Ok(s) => self.acts[a as usize].salience = s,
                    Err(e) => {
                        r = Err(e);
                        break;
                    }
                }
            }
            a = x.next;
        }
        self.resort_agenda();
        r
    }

    /// `every-cycle` salience evaluation: after each firing every module's agenda is
    /// refreshed, module by module (CLIPS's DefmoduleRefreshAgenda).
    /// Owed matches are built first: the refresh sees the whole agenda.
    /// (The mode check in line: the run loop asks after every firing.)
    #[cfg(feature = "extras")]
    #[inline(always)]
    pub(crate) fn refresh_every_cycle(&mut self) -> Result<(), crate::error::EvalError> {
        if self.st.mode.salience_eval != SALIENCE_EVERY_CYCLE {
            return Ok(());
        }
        self.refresh_saliences()
    }

    /// `refresh_every_cycle` in CLIPS's every-cycle mode.
    #[cfg(feature = "extras")]
    #[inline(never)]
    fn refresh_saliences(&mut self) -> Result<(), crate::error::EvalError> {
        self.pay_owed()?;
        #[cfg(feature = "modules")]
        for m in 0..self.st.modules.nmodules as crate::module::ModId {
            self.reorder_agenda(Some(m))?;
        }
        #[cfg(not(feature = "modules"))]
        self.reorder_agenda(None)?;
        Ok(())
    }

    /// Sorts the agenda again (saliences or the strategy changed): every activation
    /// is inserted again, which puts it where `goes_before` says whatever the order.
    pub(crate) fn resort_agenda(&mut self) {
        let mut list = self.st.agenda.agenda_head;
        self.st.agenda.agenda_head = NONE;
        self.st.agenda.agenda_len = 0;
        #[cfg(all(feature = "modules", feature = "host-speedups"))]
        self.focus_cache_clear();
        #[cfg(feature = "host-speedups")]
        self.st.agenda.groups.reset();
        while list != NONE {
            let next = self.acts[list as usize].next;
            self.agenda_insert(list);
            #[cfg(feature = "host-speedups")]
            {
                self.st.agenda.groups.hint = list;
            }
            list = next;
        }
        #[cfg(feature = "host-speedups")]
        {
            self.st.agenda.groups.hint = NONE;
        }
    }

    /// `set-strategy`: the agenda is re-sorted when the strategy changes; returns
    /// the strategy before.
    pub fn set_strategy(&mut self, s: crate::strategy::Strategy) -> crate::strategy::Strategy {
        let old = self.strategy();
        self.st.agenda.strategy = s as u8;
        if old != s {
            self.resort_agenda();
        }
        old
    }

    pub fn agenda_len(&self) -> usize {
        let mut n = 0;
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            n += 1;
            a = self.acts[a as usize].next;
        }
        n
    }

    /// Hash of the fact numbers a partial match holds (an activation's identity across
    /// a rebuild).
    fn token_basis(&self, token: TokenId) -> u32 {
        let mut h = 0x9E37_79B9u32;
        // host: the facts per depth are the partial match's `binds` (NONE at a
        // not/exists/test level, as the walk's `None`): the same hash without the walk
        // up its ancestry, which every activation a modify's retract removes pays
        // (the journal)
        #[cfg(feature = "host-speedups")]
        {
            let tk = &self.tokens[token];
            let j = &self.joins[tk.owner];
            let depth = j.depth as usize;
            if j.kind != crate::rete::JoinKind::Root && depth < crate::rete::BIND_W {
                for d in (0..=depth).rev() {
                    let f = tk.binds[d];
                    let num = if f == NONE {
                        u32::MAX
                    } else {
                        self.facts[f as usize].num
                    };
                    h = (h ^ d as u32).wrapping_mul(0x0100_0193);
                    h = (h ^ num).wrapping_mul(0x0100_0193).rotate_left(5);
                }
                return h;
            }
        }
        for (depth, num) in self.basis(token) {
            h = (h ^ depth as u32).wrapping_mul(0x0100_0193);
            h = (h ^ num.unwrap_or(u32::MAX))
                .wrapping_mul(0x0100_0193)
                .rotate_left(5);
        }
        h
    }

    fn journal_activation(&mut self, a: Ix) {
        let j = &self.st.agenda.act_journal;
        if self.acts[a as usize].seq.wrapping_sub(j.base) as i32 > 0 {
            return;
        }
        if j.len as usize >= JOURNAL_LEN {
            self.st.agenda.act_journal.overflow = true;
            return;
        }
        let x = self.acts[a as usize];
        let entry = JournalEntry {
            rule: x.rule,
            basis: self.token_basis(x.token),
            seq: x.seq,
            #[cfg(feature = "extras")]
            random: x.random,
        };
        let j = &mut self.st.agenda.act_journal;
        j.entries[j.len as usize] = entry;
        j.len += 1;
    }

    /// Starts (or nests) recording the activations removed from now on (see
    /// `JournalEntry`): an assert inside a modify records after the modify's entries.
    pub(crate) fn journal_begin(&mut self) -> JournalMark {
        let j = &mut self.st.agenda.act_journal;
        let m = JournalMark {
            len: j.len,
            on: j.on,
            overflow: j.overflow,
            base: j.base,
            seq: self.st.agenda.act_seq,
        };
        j.on = true;
        j.base = self.st.agenda.act_seq;
        m
    }

    /// Stops recording; the entries stay for `journal_replay`.
    pub(crate) fn journal_pause(&mut self) {
        self.st.agenda.act_journal.on = false;
    }

    /// Drops the entries recorded since `m` and recording goes back to what it was.
    pub(crate) fn journal_end(&mut self, m: JournalMark) {
        let j = &mut self.st.agenda.act_journal;
        j.len = m.len;
        j.on = m.on;
        j.overflow = m.overflow;
        j.base = m.base;
        j.replay = false;
    }

    /// An undo of the operation begun at `m` starts: until `journal_end`, each
    /// activation it rebuilds takes the number (hence the agenda place) the journal
    /// recorded for it since `m`, and one the journal does not know is not made (its
    /// rule had fired for that match). After a journal overflow nothing is known:
    /// rebuilt activations come back as the newest.
    pub(crate) fn journal_replay(&mut self, m: JournalMark) {
        let j = &mut self.st.agenda.act_journal;
        j.on = false;
        j.replay = true;
        j.replay_from = m.len;
    }

    /// The recorded number (and random number) of the activation of `rule` for
    /// partial match `token`, used up (each entry is one activation), or None if none
    /// was recorded.
    fn journal_take(&mut self, rule: Ix, token: TokenId) -> Option<(u32, u32)> {
        let basis = self.token_basis(token);
        let j = &mut self.st.agenda.act_journal;
        let recorded = j
            .entries
            .get_mut(j.replay_from as usize..j.len as usize)
            .unwrap_or(&mut []);
        let e = recorded
            .iter_mut()
            .find(|e| e.rule == rule && e.basis == basis)?;
        e.rule = NONE;
        #[cfg(feature = "extras")]
        let random = e.random;
        #[cfg(not(feature = "extras"))]
        let random = 0;
        Some((e.seq, random))
    }
}

/// Host: most distinct saliences the agenda indexes at once; with more it is walked
/// from its head until it empties.
#[cfg(feature = "host-speedups")]
pub const SALIENCE_GROUPS: usize = 16;

/// Host: an insertion that walks past more activations than this starts keeping the
/// salience groups (until the agenda empties): a short agenda is walked, free of upkeep.
#[cfg(feature = "host-speedups")]
const GROUP_WALK: u32 = 32;

/// Host: a removal (one that is not the quick firing of the first group's first
/// activation, `take_activation`) that leaves at most this many activations stops
/// keeping the salience groups: their upkeep costs more than a walk of a short
/// agenda, and an agenda kept non-empty by a low-salience activation would keep them
/// for good. Below `GROUP_WALK`: they come back only once the agenda is long again,
/// and are then kept until it empties (`SalienceGroups::short`).
#[cfg(feature = "host-speedups")]
const GROUP_SHORT: Ix = 16;

/// Whether strategy number `s` is lex or mea (`Core::recency_walk`'s).
#[cfg(all(feature = "host-speedups", feature = "extras", feature = "grow"))]
#[inline(always)]
fn is_recency(s: u8) -> bool {
    s == crate::strategy::Strategy::Lex as u8 || s == crate::strategy::Strategy::Mea as u8
}

/// One salience's run of activations on the agenda (which is sorted by salience).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SalienceGroup {
    pub salience: i32,
    pub first: Ix,
    pub last: Ix,
    pub count: Ix,
}

#[cfg(feature = "host-speedups")]
impl SalienceGroup {
    /// The group of one activation `a` of salience `salience`.
    #[inline(always)]
    const fn one(salience: i32, a: Ix) -> Self {
        SalienceGroup {
            salience,
            first: a,
            last: a,
            count: 1,
        }
    }
}

/// Host: the agenda's salience groups, highest salience first, so an activation is
/// inserted by a walk of its own salience's run only (as CLIPS's salience groups),
/// not of every activation of a higher salience before it. Kept only once an
/// insertion walked far (`GROUP_WALK`), until the agenda is short again (`GROUP_SHORT`).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy, Debug)]
pub struct SalienceGroups {
    pub groups: [SalienceGroup; SALIENCE_GROUPS],
    pub n: u8,
    /// The groups describe the agenda (else they are not looked at).
    pub kept: bool,
    /// More saliences than entries: not tried again until the agenda empties.
    pub overflow: bool,
    /// While `resort_agenda` inserts again: the activation it inserted last (else
    /// NONE), where a walk in its salience group may start (`agenda_insert_grouped`).
    pub hint: Ix,
    /// A removal that leaves fewer activations than this gives the groups up:
    /// `GROUP_SHORT + 1`, or 1 (only once the agenda empties) after they were given
    /// up for a short agenda once (an agenda that swings between short and long
    /// would build them again and again).
    pub short: Ix,
}

#[cfg(feature = "host-speedups")]
impl SalienceGroups {
    pub const EMPTY: SalienceGroups = SalienceGroups {
        groups: [SalienceGroup {
            salience: 0,
            first: NONE,
            last: NONE,
            count: 0,
        }; SALIENCE_GROUPS],
        n: 0,
        kept: false,
        overflow: false,
        hint: NONE,
        short: GROUP_SHORT + 1,
    };

    /// Stops keeping the groups (the agenda emptied or was rebuilt).
    #[inline(always)]
    pub fn reset(&mut self) {
        self.kept = false;
        self.overflow = false;
        self.n = 0;
        self.short = GROUP_SHORT + 1;
    }

    /// The first group of salience at most `s` (`n` if none).
    #[inline(always)]
    fn position(&self, s: i32) -> usize {
        let n = self.n as usize;
        self.groups[..n]
            .iter()
            .position(|g| g.salience <= s)
            .unwrap_or(n)
    }
}

#[cfg(feature = "host-speedups")]
impl Core<'_> {
    /// Where `agenda_insert` starts walking for activation `a`: `cur` the first
    /// activation of `a`'s salience or lower, `prev` the one before it. Returns the
    /// group position (`usize::MAX` when the groups are not kept).
    #[inline(always)]
    fn group_start(&self, a: Ix, prev: &mut Ix, cur: &mut Ix) -> usize {
        let g = &self.st.agenda.groups;
        if !g.kept {
            return usize::MAX;
        }
        let k = g.position(self.acts[a as usize].salience);
        if k < g.n as usize {
            *cur = g.groups[k].first;
            *prev = self.acts[*cur as usize].prev;
        } else {
            *cur = NONE;
            *prev = if k > 0 { g.groups[k - 1].last } else { NONE };
        }
        k
    }

    /// Where activation `a` goes when it goes before the first activation of its
    /// salience group `k` (`cur`, `group_start`'s) or after its last one (the
    /// breadth strategy's new activations): true when `prev` and `cur` are then its
    /// place, false when the walk goes on from them. The group is in the order
    /// `goes_before` gives, so nothing in it is passed over.
    #[inline(always)]
    fn group_place(&self, k: usize, a: Ix, prev: &mut Ix, cur: &mut Ix) -> bool {
        let g = &self.st.agenda.groups;
        if k >= g.n as usize || g.groups[k].salience != self.acts[a as usize].salience {
            return false;
        }
        if *cur == NONE || self.goes_before(a, *cur) {
            return true;
        }
        let last = g.groups[k].last;
        if !self.goes_before(a, last) {
            *prev = last;
            *cur = self.acts[last as usize].next;
            return true;
        }
        *prev = *cur;
        *cur = self.acts[*cur as usize].next;
        false
    }

    /// `agenda_insert_grouped`'s places found at once, whatever the strategy: first
    /// in its salience group (depth's new activations), or as a group of its own
    /// between the higher and lower ones. Links `a` there and returns true, else
    /// (or with no room for a group) changes nothing. Short and straight: a long
    /// agenda's insertions should cost what a short one's cost.
    #[inline(always)]
    fn group_insert_quick(&mut self, a: Ix) -> bool {
        let s = self.acts[a as usize].salience;
        let g = &self.st.agenda.groups;
        let n = g.n as usize;
        let k = g.position(s);
        let (prev, cur);
        if k < n && g.groups[k].salience == s {
            let (first, last) = (g.groups[k].first, g.groups[k].last);
            let at_first = self.goes_before(a, first);
            if at_first {
                (prev, cur) = (self.acts[first as usize].prev, first);
            } else if !self.goes_before(a, last) {
                // after its last: breadth's new activations, and a re-sort's
                // insertions in their old order
                (prev, cur) = (last, self.acts[last as usize].next);
            } else {
                return false;
            }
            let e = &mut self.st.agenda.groups.groups[k];
            if at_first {
                e.first = a;
            } else {
                e.last = a;
            }
            e.count += 1;
        } else {
            if n >= SALIENCE_GROUPS {
                return false;
            }
            prev = if k > 0 { g.groups[k - 1].last } else { NONE };
            cur = if k < n { g.groups[k].first } else { NONE };
            let g = &mut self.st.agenda.groups;
            // (few groups: moved one by one, no call)
            let mut i = n;
            while i > k {
                g.groups[i] = g.groups[i - 1];
                i -= 1;
            }
            g.groups[k] = SalienceGroup::one(s, a);
            g.n += 1;
        }
        self.agenda_link(a, prev, cur);
        true
    }

    /// Records activation `a`, just linked between `prev` and `cur`, in the group
    /// at position `k` (`group_start`'s).
    #[inline(always)]
    fn group_insert(&mut self, k: usize, a: Ix, prev: Ix, cur: Ix) {
        if k != usize::MAX {
            self.group_insert_kept(k, a, prev, cur);
        }
    }

    /// `group_insert` while the groups are kept (out of line).
    #[inline(never)]
    fn group_insert_kept(&mut self, k: usize, a: Ix, prev: Ix, cur: Ix) {
        let s = self.acts[a as usize].salience;
        let g = &mut self.st.agenda.groups;
        let n = g.n as usize;
        if k < n && g.groups[k].salience == s {
            let e = &mut g.groups[k];
            if cur == e.first {
                e.first = a;
            }
            if prev == e.last {
                e.last = a;
            }
            e.count += 1;
            return;
        }
        if n == SALIENCE_GROUPS {
            g.kept = false;
            g.overflow = true;
            return;
        }
        g.groups.copy_within(k..n, k + 1);
        g.groups[k] = SalienceGroup::one(s, a);
        g.n += 1;
    }

    /// Starts keeping the groups: one walk of the agenda (out of line: once per
    /// long agenda).
    #[inline(never)]
    fn build_groups(&mut self) {
        let g = &mut self.st.agenda.groups;
        if g.overflow {
            return;
        }
        g.n = 0;
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            let x = &self.acts[a as usize];
            let n = g.n as usize;
            if n > 0 && g.groups[n - 1].salience == x.salience {
                let e = &mut g.groups[n - 1];
                e.last = a;
                e.count += 1;
            } else if n == SALIENCE_GROUPS {
                g.n = 0;
                g.overflow = true;
                return;
            } else {
                g.groups[n] = SalienceGroup::one(x.salience, a);
                g.n += 1;
            }
            a = x.next;
        }
        g.kept = true;
        #[cfg(all(feature = "extras", feature = "grow"))]
        self.rindex_build();
    }

    /// Takes activation `x` (`a`, still linked) out of its group.
    #[inline(always)]
    fn group_unlink(&mut self, x: &crate::rule::Activation, a: Ix) {
        let g = &self.st.agenda.groups;
        if g.kept | g.overflow {
            self.group_unlink_kept(x, a);
        }
    }

    /// `group_unlink` while the groups are kept or given up (out of line: a short
    /// agenda never comes here).
    #[inline(never)]
    fn group_unlink_kept(&mut self, x: &crate::rule::Activation, a: Ix) {
        #[cfg(all(feature = "extras", feature = "grow"))]
        if self.st.recency_index.on && self.st.agenda.groups.kept {
            self.rindex_remove(x, a);
        }
        // short again (`a` still counted): walked as a short agenda is
        let g = &mut self.st.agenda.groups;
        let len = self.st.agenda.agenda_len;
        if len <= g.short {
            // (once given up for a short agenda, groups built again are kept until
            // the agenda empties; so is an overflow)
            let short = if len == 1 { GROUP_SHORT + 1 } else { 1 };
            g.reset();
            g.short = short;
            return;
        }
        if !g.kept {
            return;
        }
        let n = g.n as usize;
        let Some(k) = g.groups[..n].iter().position(|e| e.salience == x.salience) else {
            return;
        };
        let e = &mut g.groups[k];
        e.count = e.count.saturating_sub(1);
        if e.count == 0 {
            // (few groups: moved one by one, no call)
            for i in k + 1..n {
                g.groups[i - 1] = g.groups[i];
            }
            g.n -= 1;
            return;
        }
        if e.first == a {
            e.first = x.next;
        }
        if e.last == a {
            e.last = x.prev;
        }
    }
}
