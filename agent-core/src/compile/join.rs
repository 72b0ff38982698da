//! Join network building: a rule's conditional elements (the `Build` the syntax
//! stage filled) become alpha nodes (`compile::alpha`) and joins, shared with earlier
//! rules' identical prefixes; the new joins are hooked up to their alpha nodes and
//! primed with the facts that exist (CLIPS's incremental reset).

use super::{CompileError, Compiler};
use crate::engine::{cap, Core};
use crate::error::Pool;
use crate::handle::JoinId;
use crate::parser::rule::{Build, CE_ROOT};
use crate::rete::{Join, JoinKind, JoinMem, MAX_PATTERNS};
use crate::rule::Rule;
use crate::value::{Ix, SymId, NONE};

impl Core<'_> {
    /// Hooks the joins from `first_new` on up to their alpha nodes (each new join
    /// first among its node's successors).
    pub(crate) fn hook_new_joins(&mut self, first_new: JoinId) {
        for j in first_new.0..self.st.pools.njoins {
            let j = JoinId(j);
            let a = self.joins[j].alpha;
            if a != NONE {
                self.joins[j].alpha_next = self.alphas[a as usize].succ;
                self.alphas[a as usize].succ = j;
                #[cfg(all(feature = "grow", feature = "host-speedups"))]
                if self.twin_joinable(j) {
                    self.st.prime.set_twin_alpha(a);
                }
                #[cfg(feature = "grow")]
                self.note_placing(j, a);
            }
        }
    }

    /// Host: what a retract needs to place CLIPS's copies of `j`'s partial matches
    /// (`PrimeOrders::join_born`, `rejoins`, `self_joined`): `j`, a join of alpha
    /// node `a`, was just hooked to it (after its older successors), when loaded
    /// from compiled constructs too.
    #[cfg(feature = "grow")]
    pub(crate) fn note_placing(&mut self, j: JoinId, a: Ix) {
        let prime = &mut self.st.prime;
        if prime.join_born.len() <= j.ix() {
            // (in steps, not one join at a time)
            let len = (j.ix() + 1).next_power_of_two().max(64);
            prime.join_born.resize(len, 0);
            prime.rejoins.resize(len, false);
        }
        prime.join_born[j.ix()] = self.st.facts.next_fact_num;
        // (only a positive join's partial matches join an alpha match:
        // not/exists outputs are no children of one; an ancestor taking
        // the node is among its other successors)
        let mut rejoin = false;
        let mut p = if self.joins[j].kind == JoinKind::Positive
            && self.joins[j].alpha_next != JoinId::NONE
        {
            self.joins[j].parent
        } else {
            JoinId::NONE
        };
        while p != JoinId::NONE {
            if self.joins[p].alpha == a {
                rejoin = true;
                break;
            }
            p = self.joins[p].parent;
        }
        // (a join id reused by a later rule gets its own answer)
        let prime = &mut self.st.prime;
        prime.rejoins[j.ix()] = rejoin;
        if rejoin {
            prime.self_joined[a as u8 as usize] = true;
            prime.any_self = true;
            prime.placed = true;
            prime.slow_retract = true;
        }
    }

    /// Matches new rules (from `first_rule` on, their joins from `first_join` and
    /// alpha nodes from `first_alpha` on) against the existing facts, as CLIPS's
    /// incremental reset does: primes the new joins fed by old ones (each rule from
    /// its end upwards), then drives the facts, oldest first, through the new patterns.
    pub(crate) fn prime_new_rules(
        &mut self,
        first_rule: Ix,
        first_join: JoinId,
        first_alpha: Ix,
    ) -> Result<(), crate::error::EvalError> {
        let mut primed = Primed {
            ids: [JoinId::NONE; MAX_PRIMED],
            n: 0,
        };
        // host: the tests the new joins fed by old ones run may assert facts, which
        // meet only the new alpha nodes (CLIPS's incremental reset: outside its join
        // operations then, the network's older part closed); those the facts run
        // through the new patterns run inside them and may not
        #[cfg(feature = "extras")]
        let free = core::mem::replace(&mut self.st.net.matching_free, self.st.net.matching + 1);
        #[cfg(feature = "extras")]
        let ir = core::mem::replace(&mut self.st.net.ir_alpha, first_alpha);
        // (host: a stale discrimination index sends an assert to `network_assert`'s
        // slower path, which asks for `ir_alpha`; it stays stale until that is NONE)
        #[cfg(all(feature = "extras", feature = "host-speedups"))]
        {
            self.st.net.disc.net_gen = None;
        }
        let mut r = Ok(());
        for rule in first_rule..self.st.pools.nrules {
            let t = self.rules[rule as usize].terminal;
            r = self.prime_chain(t, first_join, JoinId::ROOT, &mut primed);
            if r.is_err() {
                break;
            }
        }
        #[cfg(feature = "extras")]
        {
            self.st.net.matching_free = free;
        }
        if r.is_ok() && first_alpha < self.st.pools.nalpha {
            r = self.prime_alphas(first_alpha);
        }
        #[cfg(feature = "extras")]
        {
            self.st.net.ir_alpha = ir;
        }
        r
    }

    /// Primes the new joins of a chain whose left input is an old join, walking
    /// from `j` up to `stop`; a subnetwork is primed after the join taking it.
    fn prime_chain(
        &mut self,
        mut j: JoinId,
        first_new: JoinId,
        stop: JoinId,
        primed: &mut Primed,
    ) -> Result<(), crate::error::EvalError> {
        while j != JoinId::NONE && j != JoinId::ROOT && j != stop {
            let jn = self.joins[j];
            // host: a first pattern of its own is left to the facts' priming (as in
            // CLIPS), which would see again what a test asserted meanwhile
            #[cfg(feature = "extras")]
            let own_first = jn.kind == JoinKind::Positive
                && jn.parent == JoinId::ROOT
                && jn.alpha >= self.st.net.ir_alpha;
            #[cfg(not(feature = "extras"))]
            let own_first = false;
            // host: a new join from the right on an old subnetwork gets CLIPS's copies
            // of its partial matches now (`rete::order`)
            #[cfg(feature = "grow")]
            if j >= first_new && jn.rjoin != JoinId::NONE && jn.rjoin < first_new {
                self.note_right_primed(j);
            }
            if j >= first_new
                && jn.parent < first_new
                && !own_first
                && !primed.ids[..primed.n].contains(&j)
            {
                if primed.n == primed.ids.len() {
                    // priming it unrecorded could prime it twice
                    return Err(cap(Pool::Joins, MAX_PRIMED).into());
                }
                primed.ids[primed.n] = j;
                primed.n += 1;
                self.prime_join(j, first_new)?;
            }
            if jn.rjoin != JoinId::NONE {
                self.prime_chain(jn.rjoin, first_new, jn.parent, primed)?;
            }
            j = jn.parent;
        }
        Ok(())
    }
}

impl Compiler<'_, '_> {
    /// How many references to join `j` the rule this defrule replaces (named `name`,
    /// created before `rule_base`) holds: a join only it uses is not shared, as CLIPS
    /// removes the old rule first and builds (and primes) such joins anew.
    pub(crate) fn replaced_uses(&self, name: SymId, j: JoinId) -> Ix {
        let mut n = 0;
        for r in 0..self.rule_base {
            if self.cx.rule_here(r, name) {
                let mut d = r;
                while d != NONE {
                    n += self.chain_uses(self.cx.rules[d as usize].terminal, JoinId::ROOT, j);
                    d = self.cx.rules[d as usize].next_disjunct;
                }
            }
        }
        n
    }

    /// References to join `j` on the chain from `from` up to `stop` and in the
    /// subnetworks it takes from the right (the walk `Core::remove_rule` releases).
    fn chain_uses(&self, mut from: JoinId, stop: JoinId, j: JoinId) -> Ix {
        let mut n = 0;
        while from != JoinId::NONE && from != JoinId::ROOT && from != stop {
            let jn = &self.cx.joins[from];
            n += Ix::from(from == j);
            if jn.rjoin != JoinId::NONE {
                n += self.chain_uses(jn.rjoin, jn.parent, j);
            }
            from = jn.parent;
        }
        n
    }

    /// Builds one disjunct the syntax stage has read whole: the alpha nodes of its
    /// patterns, its joins and its rule (hooked up to the alpha nodes and primed
    /// later, in `defrule`).
    pub(crate) fn compile_disjunct(
        &mut self,
        name: SymId,
        b: &mut Build,
    ) -> Result<Ix, CompileError> {
        for ce in &mut b.ces[..b.n] {
            if ce.pat.tmpl != NONE {
                ce.alpha = self.find_or_make_alpha(&ce.pat, ce.at)?;
            }
        }
        self.build_rule(name, b)
    }

    /// Creates the rule and its joins.
    fn build_rule(&mut self, name: SymId, b: &Build) -> Result<Ix, CompileError> {
        self.cx.st.net.net_gen = self.cx.st.net.net_gen.wrapping_add(1);
        let nr = self.cx.st.pools.nrules as usize;
        #[cfg(feature = "grow")]
        {
            let joins = self.cx.st.pools.njoins as usize + b.n + 1;
            self.cx.ensure(Pool::Rules, nr + 1);
            self.cx.ensure(Pool::Joins, joins);
            self.cx.ensure(Pool::JoinMemories, joins);
        }
        if nr >= self.cx.rules.len() {
            let c = cap(Pool::Rules, self.cx.rules.len());
            return Err(CompileError {
                capacity: c,
                at: None,
            });
        }
        // a logical rule's join is noted by the rule's index (`logical`)
        #[cfg(feature = "logical")]
        if b.logical != CE_ROOT && nr >= self.cx.rule_logical.len() {
            return Err(CompileError {
                capacity: cap(Pool::Rules, self.cx.rule_logical.len()),
                at: None,
            });
        }
        if let Err(c) = self.cx.network_writable() {
            return Err(CompileError {
                capacity: c,
                at: None,
            });
        }
        let need = self.cx.st.pools.njoins as usize + b.n + 1;
        if need > self.cx.joins.len() {
            let c = cap(Pool::Joins, self.cx.joins.len());
            return Err(CompileError {
                capacity: c,
                at: None,
            });
        }
        if need > self.cx.join_mems.len() {
            let c = cap(Pool::JoinMemories, self.cx.join_mems.len());
            return Err(CompileError {
                capacity: c,
                at: None,
            });
        }
        self.cx.rules[nr] = Rule::EMPTY;
        // the join built for each CE
        let mut jid = [JoinId::ROOT; MAX_PATTERNS];
        // a redefinition: the old rule's joins may not be shared (`replaced_uses`)
        let replacing = (0..self.rule_base).any(|r| self.cx.rule_here(r, name));
        for (i, ce) in b.ces[..b.n].iter().enumerate() {
            let parent = if ce.parent == CE_ROOT {
                JoinId::ROOT
            } else {
                jid[ce.parent as usize]
            };
            let rjoin = if ce.right == CE_ROOT {
                JoinId::NONE
            } else {
                jid[ce.right as usize]
            };
            {
                // share an identical join under the same parent (CLIPS does)
                let mut c = self.cx.joins[parent].first_child;
                let mut found = JoinId::NONE;
                while c != JoinId::NONE {
                    // (read in place, the pattern first: the root's children are
                    // every rule's first join, walked for each new rule)
                    let cj = &self.cx.joins[c];
                    if cj.alpha == ce.alpha
                        && cj.refs > 0
                        && cj.kind == ce.kind
                        && cj.rjoin == rjoin
                        && cj.depth == ce.depth
                        && (!replacing || cj.refs > self.replaced_uses(name, c))
                        && self.chain_eq(cj.tests, ce.jtests)
                        && self.chain_eq(cj.post, ce.post)
                    {
                        found = c;
                        break;
                    }
                    c = cj.next_sibling;
                }
                if found != JoinId::NONE {
                    self.cx.joins[found].refs += 1;
                    // CLIPS shows no `=j` for the join of an empty LHS it shares
                    let empty_lhs = b.n == 1 && ce.kind == JoinKind::Test && ce.jtests == NONE;
                    if !empty_lhs {
                        self.marks.push(true);
                    }
                    jid[i] = found;
                    continue;
                }
            }
            self.marks.push(false);
            let j = JoinId(self.cx.st.pools.njoins);
            self.cx.st.pools.njoins += 1;
            self.cx.joins[j] = Join {
                kind: ce.kind,
                depth: ce.depth,
                rule: NONE,
                parent,
                first_child: JoinId::NONE,
                next_sibling: JoinId::NONE,
                refs: 1,
                alpha: ce.alpha,
                tests: ce.jtests,
                post: ce.post,
                alpha_next: JoinId::NONE,
                rjoin,
                rsucc: JoinId::NONE,
                index_child: JoinId::NONE,
            };
            self.cx.join_mems[j] = JoinMem::EMPTY;
            // a join from the right comes second among the parent's children, right
            // after the newest: its subnetwork's first join when that is new (the
            // subnetwork sees a new left token first), another when it shares an older
            // one (CLIPS then passes a new left token to the join from the right
            // before the subnetwork: a transient activation). Not at the root, whose
            // one token only `reset` passes on: there CLIPS primes the joins newest
            // first (its list of left-primed first joins).
            let after = if rjoin != JoinId::NONE && parent != JoinId::ROOT {
                self.cx.joins[parent].first_child
            } else {
                JoinId::NONE
            };
            if after != JoinId::NONE && self.cx.joins[after].parent == parent {
                self.cx.joins[j].next_sibling = self.cx.joins[after].next_sibling;
                self.cx.joins[after].next_sibling = j;
            } else {
                self.cx.joins[j].next_sibling = self.cx.joins[parent].first_child;
                self.cx.joins[parent].first_child = j;
            }
            self.cx.note_children(parent);
            if rjoin != JoinId::NONE {
                // host: a join that comes to feed one from the right gets its
                // partial matches stamped (`rete::Stamp`: kept only since)
                #[cfg(feature = "grow")]
                if self.cx.joins[rjoin].rsucc == JoinId::NONE {
                    self.cx.restamp_memory(rjoin);
                }
                self.cx.joins[j].alpha_next = self.cx.joins[rjoin].rsucc;
                self.cx.joins[rjoin].rsucc = j;
                #[cfg(feature = "wipe")]
                {
                    self.cx.st.net.from_right = true;
                }
            }
            self.cx.choose_index_child(parent, j);
            jid[i] = j;
        }
        let prev = jid[b.cur as usize];
        // the first CE of the rule's own chain decides whether reset rebuilds it
        let mut first = b.cur;
        while b.ces[first as usize].parent != CE_ROOT {
            first = b.ces[first as usize].parent;
        }
        // the rule's end node
        self.marks.push(false);
        let term = JoinId(self.cx.st.pools.njoins);
        self.cx.st.pools.njoins += 1;
        self.cx.joins[term] = Join {
            kind: JoinKind::Terminal,
            depth: b.depth,
            rule: nr as Ix,
            parent: prev,
            next_sibling: self.cx.joins[prev].first_child,
            refs: 1,
            ..Join::EMPTY
        };
        // a failed load's rollback may have left this slot's memory behind
        self.cx.join_mems[term] = JoinMem::EMPTY;
        self.cx.joins[prev].first_child = term;
        self.cx.note_children(prev);
        let prev = term;
        self.cx
            .note_hw(Pool::Joins, self.cx.st.pools.njoins as usize);
        self.cx
            .note_hw(Pool::JoinMemories, self.cx.st.pools.njoins as usize);
        self.cx.rules[nr] = Rule {
            name,
            // (the parser keeps it in CLIPS's range, -10000..=10000)
            salience: b.sal.0.clamp(-10000, 10000) as i16,
            salience_expr: b.sal.1,
            root: JoinId::ROOT,
            terminal: prev,
            rhs: self.cx.exprs[b.rhs as usize].first,
            npat: b.depth,
            nlocals: b.nlocals,
            next_disjunct: NONE,
            next_at_join: NONE,
            root_sensitive: b.ces[first as usize].kind != JoinKind::Positive,
            deleted: false,
            text: NONE,
            complexity: b.complexity,
        };
        #[cfg(feature = "grow")]
        if b.n > crate::rete::IMAGE_MAX_PATTERNS
            || b.depth as usize > crate::rete::IMAGE_MAX_PATTERNS
        {
            self.cx
                .st
                .eval
                .past_image
                .get_or_insert("a rule of more than 32 conditional elements (the image's limit)");
        }
        // the join where the rule's logical CEs end (`logical`)
        #[cfg(feature = "logical")]
        {
            // the successor of the logical join on the rule's path (CLIPS's copy
            // of the logical partial match that supports the rule's facts)
            let lj = if b.logical == CE_ROOT {
                JoinId::NONE
            } else {
                let logical = jid[b.logical as usize];
                let mut s = term;
                while s != JoinId::NONE && self.cx.joins[s].parent != logical {
                    s = self.cx.joins[s].parent;
                }
                s
            };
            // (room checked above)
            let _ = self.cx.set_rule_logical_join(nr as Ix, lj);
        }
        // (room: the rule just written)
        #[cfg(feature = "modules")]
        let _ = self.cx.set_rule_tag(
            nr as Ix,
            crate::module::RuleTag {
                module: self.cx.current_module(),
                auto_focus: b.auto_focus,
            },
        );
        self.cx.st.pools.nrules += 1;
        self.cx.note_hw(Pool::Rules, nr + 1);
        Ok(nr as Ix)
    }
}

/// New joins fed by older ones that one rule (all its disjuncts) may prime while facts
/// exist; more is a capacity error naming the joins.
pub(crate) const MAX_PRIMED: usize = 64;

/// New joins already primed while defining a rule (disjuncts share joins).
pub(crate) struct Primed {
    pub(crate) ids: [JoinId; MAX_PRIMED],
    pub(crate) n: usize,
}
