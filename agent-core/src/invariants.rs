//! Invariant mode: a consistency check of the whole engine, meant to run after every
//! operation in tests and fuzzing (`Engine::check_invariants`).
//!
//! The engine links everything through `Ix` indices in fixed pools, so a bug shows up
//! as a broken link long before it shows up as a wrong answer. This module walks every
//! list with a bounded walk (a cycle is a violation, not a hang) and checks:
//! - pool accounting: free list + live entries = entries handed out, for facts, tokens
//!   and activations; the value arena top covers exactly the live and pending facts;
//! - facts: the creation-ordered list, the duplicate hash index, the cell layout of
//!   each fact against its template;
//! - tokens: every alpha match is in its alpha memory and its fact's list, and the fact
//!   is live; every partial match is in its join's memory, under its parent and its
//!   alpha match (no dangling partial match after a retract), and not/exists counts
//!   equal their links;
//! - the agenda: doubly linked, sorted by salience then by the strategy (`strategy`),
//!   every activation belongs to a live rule, sits on an active partial match of that
//!   rule's last join, and all the facts it matched are live;
//! - the symbol table: texts packed in order, hash chains complete, no duplicates;
//! - the construct pools and the evaluation state at rest.
//!
//! It only reads; it costs O(pool sizes) (the fact cell overlap check walks the facts
//! once per 8,192 cells of the value arena, the join checks the join lists once per
//! 8,192 joins), so it is for debugging, not for the robot's control loop.

use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use core::fmt;

use crate::engine::{Core, Engine};
use crate::fact::FactState;
use crate::host::NullHost;
use crate::rete::{Join, JoinKind, TokenKind};
use crate::value::{Value, NONE};

/// A broken invariant: what is wrong and at which pool entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Violation {
    pub what: &'static str,
    /// Index of the offending entry in its pool (or a count), for debugging.
    pub at: u32,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "engine invariant broken: {} (entry {})",
            self.what, self.at
        )
    }
}

fn fail<T>(what: &'static str, at: usize) -> Result<T, Violation> {
    Err(Violation {
        what,
        at: at as u32,
    })
}

/// Entries a window of `MARK_WINDOW` indices wide marks at a time: the checker has no
/// storage of its own, and comparing every pair of entries instead (fact cells that
/// overlap, joins missing from lists) took most of a 9,000-fact test's time.
const MARK_WINDOW: usize = 8192;

/// A bitmap of the indices `low..low + MARK_WINDOW` of a pool.
struct Marks {
    low: usize,
    bits: [u64; MARK_WINDOW / 64],
}

impl Marks {
    fn new(low: usize) -> Marks {
        Marks {
            low,
            bits: [0; MARK_WINDOW / 64],
        }
    }

    /// Marks `i` if it is in the window; whether it was marked before.
    fn mark(&mut self, i: usize) -> bool {
        let Some(k) = i.checked_sub(self.low).filter(|&k| k < MARK_WINDOW) else {
            return false;
        };
        let (word, bit) = (k / 64, 1u64 << (k % 64));
        let was = self.bits[word] & bit != 0;
        self.bits[word] |= bit;
        was
    }

    /// Whether `i` (in the window) is marked.
    fn has(&self, i: usize) -> bool {
        let k = i - self.low;
        self.bits[k / 64] & (1u64 << (k % 64)) != 0
    }
}

/// The entry a violation names: a pool index, typed or not.
trait At {
    fn at(self) -> usize;
}

macro_rules! at_as_usize {
    ($($t:ty),*) => {$(
        impl At for $t {
            fn at(self) -> usize {
                self as usize
            }
        }
    )*};
}
at_as_usize!(u8, u16, u32, usize, i32);

impl At for JoinId {
    fn at(self) -> usize {
        self.ix()
    }
}

impl At for TokenId {
    fn at(self) -> usize {
        self.ix()
    }
}

macro_rules! ensure {
    ($cond:expr, $what:expr, $at:expr) => {
        if !$cond {
            return fail($what, At::at($at));
        }
    };
}

impl<S: crate::config::Storage> Engine<S> {
    /// Checks every engine invariant (see the module docs). Call it between API
    /// operations (not from inside a host function). `&mut` only because the engine's
    /// view is built that way; nothing is changed (a never-used engine is started).
    pub fn check_invariants(&mut self) -> Result<(), Violation> {
        let mut host = NullHost;
        let cx = self.core(&mut host);
        cx.check_invariants()
    }
}

impl Core<'_> {
    /// Invariant mode (feature `check-invariants`): panics with the violation when an
    /// invariant is broken; a no-op without the feature. Only call it between
    /// top-level operations (not while a rule fires or a function evaluates).
    #[inline]
    pub(crate) fn debug_check(&self, when: &str) {
        #[cfg(feature = "check-invariants")]
        if let Err(v) = self.check_invariants() {
            panic!("{v} ({when})");
        }
        let _ = when;
    }

    /// See [`Engine::check_invariants`].
    pub fn check_invariants(&self) -> Result<(), Violation> {
        self.check_rest_state()?;
        self.check_symbols()?;
        self.check_constructs()?;
        self.check_facts()?;
        self.check_values()?;
        self.check_tokens()?;
        self.check_owed()?;
        self.check_dead_alphas()?;
        self.check_agenda()?;
        #[cfg(feature = "logical")]
        self.check_supports()?;
        Ok(())
    }

    /// Truth maintenance between operations: no unsupported fact waits, no logical
    /// rule is firing; every support links a live partial match and a live fact and
    /// is on both their lists; the live count is what the lists hold.
    #[cfg(feature = "logical")]
    fn check_supports(&self) -> Result<(), Violation> {
        let l = &self.st.logical;
        ensure!(
            l.unsupported == NONE,
            "unsupported facts left unretracted",
            l.unsupported
        );
        ensure!(
            l.bind == TokenId::NONE && !l.gone && !l.forcing && !l.detach,
            "logical firing state left set",
            0
        );
        // before a rule with `logical` exists the list heads are not kept (growing
        // storage leaves them zero)
        if !l.defined {
            ensure!(l.live == 0, "support without a logical rule", l.live);
            return Ok(());
        }
        let mut n = 0usize;
        for (f, &head) in self.fact_deps.iter().enumerate() {
            let mut s = head;
            while s != NONE {
                ensure!(
                    (s as usize) < self.supports.len(),
                    "support index past the pool",
                    f
                );
                let e = self.supports[s as usize];
                ensure!(e.fact as usize == f, "support listed by another fact", s);
                ensure!(
                    self.facts[f].state == crate::fact::FactState::Live,
                    "support of a fact not live",
                    f
                );
                ensure!(
                    e.token.ix() < self.tokens.len()
                        && self.tokens[e.token].kind == TokenKind::Beta,
                    "support by a token that is no partial match",
                    s
                );
                let mut t = self.token_deps[e.token.ix()];
                while t != NONE && t != s {
                    t = self.supports[t as usize].next_of_token;
                }
                ensure!(t == s, "support missing from its partial match's list", s);
                n += 1;
                ensure!(n <= self.supports.len(), "support lists loop", s);
                s = e.next_of_fact;
            }
        }
        let mut m = 0usize;
        for &head in self.token_deps.iter() {
            let mut s = head;
            while s != NONE && m <= self.supports.len() {
                m += 1;
                s = self.supports[s as usize].next_of_token;
            }
        }
        ensure!(m == n, "partial matches list supports no fact lists", m);
        ensure!(n == l.live as usize, "live support count off", n);
        Ok(())
    }

    /// An alpha node whose rules are gone keeps no matches (new facts skip it).
    fn check_dead_alphas(&self) -> Result<(), Violation> {
        for i in 0..self.st.pools.nalpha as usize {
            let n = &self.alphas[i];
            ensure!(
                n.live || self.alpha_mems[i].head == TokenId::NONE,
                "removed alpha node holds matches",
                i
            );
        }
        Ok(())
    }

    /// The owed list (see `Core::pay_owed`): unblocked not outputs, each once, their
    /// back links consistent (the head's names the tail), and no other token marked.
    fn check_owed(&self) -> Result<(), Violation> {
        let used = self.st.pools.tokens_used as usize;
        let marked = (0..used).filter(|&t| self.is_owed(TokenId::at(t))).count();
        let (mut n, mut prev, mut t) = (0usize, TokenId::NONE, self.st.net.owed);
        while t != TokenId::NONE {
            ensure!(t.ix() < used, "owed list names a token outside the pool", t);
            let tk = self.tokens[t];
            ensure!(self.is_owed(t), "owed list holds an unmarked token", t);
            ensure!(
                self.joins[tk.owner].kind == JoinKind::Negative && !tk.blocked,
                "owed token is not an unblocked not output",
                t
            );
            if prev != TokenId::NONE {
                ensure!(tk.am_prev == prev, "owed list back link broken", t);
            }
            n += 1;
            ensure!(n <= marked, "owed list has a cycle or misses marks", t);
            prev = t;
            t = tk.am_next;
        }
        ensure!(n == marked, "owed marks outside the owed list", marked);
        if self.st.net.owed != TokenId::NONE {
            ensure!(
                self.tokens[self.st.net.owed].am_prev == prev,
                "owed list head does not name the tail",
                self.st.net.owed
            );
        }
        Ok(())
    }

    /// Between operations nothing is half done.
    fn check_rest_state(&self) -> Result<(), Violation> {
        let st = &self.st;
        ensure!(!st.mode.firing, "firing flag set between operations", 0);
        ensure!(
            st.facts.pending == NONE,
            "retracted facts still pending",
            st.facts.pending
        );
        ensure!(
            st.eval.eval_depth == 0 && st.eval.in_use == 0 && !st.mode.defining,
            "evaluation depth not back to 0",
            st.eval.eval_depth
        );
        ensure!(
            st.net.hold.depth == 0 && st.net.hold.buf.is_empty(),
            "watch traces still held",
            st.net.hold.depth
        );
        ensure!(
            !st.agenda.act_journal.on && !st.net.unblocked.on && !st.net.defer_nots,
            "undo journal still recording",
            0
        );
        ensure!(
            (st.frame.sp as usize) <= self.stack.len(),
            "evaluation stack pointer past the stack",
            st.frame.sp
        );
        ensure!(
            st.frame.scratch_top as usize + st.eval.gmf_used as usize <= self.scratch.len(),
            "scratch and globals' multifields overlap",
            st.frame.scratch_top
        );
        Ok(())
    }

    fn check_symbols(&self) -> Result<(), Violation> {
        // a compiled rule base's symbols read in place come first; the arena's entry
        // `k` is id `rom + k`
        let rom = self.st.rom.symbols.len();
        ensure!(
            self.st.pools.nsyms as usize >= rom,
            "fewer symbols than read in place",
            self.st.pools.nsyms
        );
        let n = self.st.pools.nsyms as usize - rom;
        ensure!(n <= self.sym_entries.len(), "more symbols than capacity", n);
        ensure!(
            self.st.pools.sym_bytes as usize <= self.sym_bytes.len(),
            "symbol bytes past capacity",
            self.st.pools.sym_bytes
        );
        // texts are appended, so entry i starts where entry i-1 ended
        let mut end = 0usize;
        for i in 0..n {
            let e = self.sym_entries[i];
            ensure!(e.start as usize == end, "symbol text not packed", i);
            end += e.len as usize;
            ensure!(
                end <= self.st.pools.sym_bytes as usize,
                "symbol text past the used bytes",
                i
            );
            ensure!(
                core::str::from_utf8(&self.sym_bytes[e.start as usize..end]).is_ok(),
                "symbol text is not UTF-8",
                i
            );
        }
        ensure!(
            end == self.st.pools.sym_bytes as usize,
            "used symbol bytes do not match the entries",
            end
        );
        // every entry is in the chain of its bucket, exactly once overall
        let mut chained = 0usize;
        for (b, &head) in self.sym_buckets.iter().enumerate() {
            let mut i = head.get();
            let mut steps = 0usize;
            while i != NONE {
                ensure!(
                    (i as usize) >= rom && (i as usize) < rom + n,
                    "symbol chain links a dropped entry",
                    b
                );
                let e = self.sym_entries[i as usize - rom];
                let text = &self.sym_bytes[e.start as usize..(e.start + e.len) as usize];
                let h = crate::symbols::hash_bytes(text);
                let home = h as usize % self.sym_buckets.len();
                ensure!(home == b, "symbol in the wrong hash bucket", i);
                #[cfg(feature = "grow")]
                ensure!(e.hash == h, "symbol's kept hash is not its text's", i);
                chained += 1;
                steps += 1;
                ensure!(steps <= n, "symbol hash chain has a cycle", b);
                i = e.next;
            }
        }
        ensure!(
            chained == n,
            "symbols missing from the hash chains",
            chained
        );
        // no text twice: the first match of each text's lookup is the entry itself
        for i in 0..n {
            let e = self.sym_entries[i];
            let text = &self.sym_bytes[e.start as usize..(e.start + e.len) as usize];
            let b = crate::symbols::hash_bytes(text) as usize % self.sym_buckets.len();
            let mut j = self.sym_buckets[b].get();
            while j != NONE {
                let f = self.sym_entries[j as usize - rom];
                if &self.sym_bytes[f.start as usize..(f.start + f.len) as usize] == text {
                    break;
                }
                j = f.next;
            }
            ensure!(j as usize == rom + i, "symbol text interned twice", i);
            ensure!(
                core::str::from_utf8(text).map_or(true, |t| self.st.rom.symbols.find(t).is_none()),
                "symbol text interned twice",
                i
            );
        }
        Ok(())
    }

    fn check_constructs(&self) -> Result<(), Violation> {
        let st = &self.st;
        ensure!(
            (st.pools.ntemplates as usize) <= self.templates.len(),
            "templates past capacity",
            st.pools.ntemplates
        );
        ensure!(
            (st.pools.nslots as usize) <= self.slots.len(),
            "slots past capacity",
            st.pools.nslots
        );
        ensure!(
            (st.pools.nrules as usize) <= self.rules.len(),
            "rules past capacity",
            st.pools.nrules
        );
        ensure!(
            (st.pools.nalpha as usize) <= self.alphas.len(),
            "alpha nodes past capacity",
            st.pools.nalpha
        );
        ensure!(
            (st.pools.njoins as usize) <= self.joins.len(),
            "joins past capacity",
            st.pools.njoins
        );
        ensure!(
            (st.pools.nexprs as usize) <= self.exprs.len(),
            "expressions past capacity",
            st.pools.nexprs
        );
        ensure!(
            (st.pools.nfuncs as usize) <= self.funcs.len(),
            "deffunctions past capacity",
            st.pools.nfuncs
        );
        ensure!(
            (st.pools.nglobals as usize) <= self.globals.len(),
            "globals past capacity",
            st.pools.nglobals
        );
        ensure!(
            (st.pools.ndeffacts as usize) <= self.deffacts.len(),
            "deffacts past capacity",
            st.pools.ndeffacts
        );
        ensure!(
            (st.pools.nexternals as usize) <= self.externals.len(),
            "external functions past capacity",
            st.pools.nexternals
        );
        for t in 0..st.pools.ntemplates as usize {
            let tp = self.templates[t];
            // a redefined template's old entry is retired in place: no name, listed
            // nowhere, matched by nothing (`parser::construct::deftemplate`)
            ensure!(
                (tp.name as usize) < st.pools.nsyms as usize
                    || (tp.name == NONE && tp.implied && tp.alpha_head == NONE),
                "template name is not a symbol",
                t
            );
            ensure!(
                tp.first_slot as usize + tp.nslots as usize <= st.pools.nslots as usize,
                "template slots past the slot pool",
                t
            );
            // its alpha nodes test its facts
            let mut a = tp.alpha_head;
            let mut steps = 0usize;
            while a != NONE {
                ensure!(
                    a < st.pools.nalpha,
                    "template lists a dropped alpha node",
                    t
                );
                ensure!(
                    self.alphas[a as usize].tmpl as usize == t,
                    "alpha node listed under another template",
                    a
                );
                steps += 1;
                ensure!(
                    steps <= st.pools.nalpha as usize,
                    "alpha list has a cycle",
                    t
                );
                a = self.alphas[a as usize].next_in_tmpl;
            }
        }
        // joins: the root, then live joins hang under live parents and their alpha node
        ensure!(
            st.pools.njoins >= 1 && self.joins[JoinId::ROOT].kind == JoinKind::Root,
            "join 0 is not the root",
            0
        );
        #[cfg(feature = "host-speedups")]
        for j in 0..st.pools.njoins {
            let j = JoinId(j);
            let c = self.joins[j].first_child;
            ensure!(
                self.join_mems[j].one_child
                    == (c != JoinId::NONE && self.joins[c].next_sibling == JoinId::NONE),
                "join's one-child flag disagrees with its child list",
                j
            );
        }
        let njoins = st.pools.njoins as usize;
        // the joins listed under their parent and fed by their alpha node, a window
        // of the pool at a time
        for low in (1..njoins).step_by(MARK_WINDOW) {
            let (under_parent, fed) = self.listed_joins(low);
            for j in low..(low + MARK_WINDOW).min(njoins) {
                let j = JoinId::at(j);
                let jn = self.joins[j];
                if jn.refs == 0 {
                    ensure!(
                        self.join_mems[j].mem == TokenId::NONE,
                        "removed join still holds partial matches",
                        j
                    );
                    ensure!(
                        !under_parent.has(j.0 as usize),
                        "removed join still under its parent",
                        j
                    );
                    ensure!(
                        jn.alpha == NONE || !fed.has(j.0 as usize),
                        "removed join still fed by its alpha node",
                        j
                    );
                    continue;
                }
                ensure!(jn.kind != JoinKind::Root, "second root join", j);
                ensure!(
                    jn.parent.0 < st.pools.njoins,
                    "join parent past the pool",
                    j
                );
                ensure!(
                    self.joins[jn.parent].refs > 0,
                    "live join under a removed parent",
                    j
                );
                ensure!(
                    under_parent.has(j.0 as usize),
                    "join missing from its parent's children",
                    j
                );
                match jn.kind {
                    JoinKind::Negative | JoinKind::Exists if jn.rjoin != JoinId::NONE => {
                        // not/exists over several CEs: fed by a subnetwork's last join
                        ensure!(
                            jn.rjoin.0 < st.pools.njoins,
                            "join from the right past the pool",
                            j
                        );
                        let mut r = self.joins[jn.rjoin].rsucc;
                        let mut steps = 0usize;
                        while r != JoinId::NONE && r != j && steps <= st.pools.njoins as usize {
                            r = self.joins[r].alpha_next;
                            steps += 1;
                        }
                        ensure!(r == j, "join missing from its right input's successors", j);
                    }
                    JoinKind::Positive | JoinKind::Negative | JoinKind::Exists => {
                        ensure!(jn.alpha < st.pools.nalpha, "join without its alpha node", j);
                        ensure!(
                            fed.has(j.0 as usize),
                            "join missing from its alpha node's successors",
                            j
                        );
                    }
                    JoinKind::Terminal => {
                        ensure!(
                            self.join_mems[j].mem == TokenId::NONE,
                            "terminal join holds partial matches",
                            j
                        );
                        ensure!(jn.rule < st.pools.nrules, "terminal join without a rule", j);
                    }
                    _ => {}
                }
            }
        }
        for r in 0..st.pools.nrules {
            let rule = self.rules[r as usize];
            if rule.deleted || rule.terminal == JoinId::NONE {
                continue;
            }
            ensure!(
                rule.terminal.0 < st.pools.njoins,
                "rule end past the join pool",
                r
            );
            let t = self.joins[rule.terminal];
            ensure!(
                t.kind == JoinKind::Terminal && t.refs > 0,
                "rule end is not a live terminal join",
                r
            );
        }
        // globals' multifields live in the reserved top of scratch
        let region = self.scratch.len() - st.eval.gmf_used as usize;
        for g in 0..st.pools.nglobals as usize {
            if let Value::Multi(m) = self.globals[g].value {
                if m.len > 0 {
                    ensure!(
                        m.start as usize >= region
                            && m.start as usize + m.len as usize <= self.scratch.len(),
                        "global multifield outside the globals' region",
                        g
                    );
                }
            }
        }
        Ok(())
    }

    /// The joins of the window from `low` listed under their parent (`first_child`,
    /// `next_sibling`), and those listed among their alpha node's successors
    /// (`succ`, `alpha_next`). A list is read for as many steps as there are joins.
    fn listed_joins(&self, low: usize) -> (Marks, Marks) {
        let n = self.st.pools.njoins as usize;
        let walk = |head: JoinId, next: fn(&Join) -> JoinId, on: &mut dyn FnMut(JoinId)| {
            let mut c = head;
            let mut steps = 0usize;
            while c != JoinId::NONE && (c.0 as usize) < n && steps <= n {
                on(c);
                c = next(&self.joins[c]);
                steps += 1;
            }
        };
        let mut under_parent = Marks::new(low);
        for p in 0..n {
            let p = JoinId::at(p);
            walk(self.joins[p].first_child, |x| x.next_sibling, &mut |c| {
                if self.joins[c].parent == p {
                    under_parent.mark(c.0 as usize);
                }
            });
        }
        let mut fed = Marks::new(low);
        for a in 0..self.st.pools.nalpha {
            walk(self.alphas[a as usize].succ, |x| x.alpha_next, &mut |c| {
                if self.joins[c].alpha == a {
                    fed.mark(c.0 as usize);
                }
            });
        }
        (under_parent, fed)
    }

    /// Counts a singly linked list, failing on a cycle (more steps than `bound`).
    fn walk(
        &self,
        head: Ix,
        bound: usize,
        next: impl Fn(Ix) -> Ix,
        what: &'static str,
    ) -> Result<usize, Violation> {
        let mut n = 0usize;
        let mut i = head;
        while i != NONE {
            if (i as usize) >= bound || n >= bound {
                return Err(Violation { what, at: i as u32 });
            }
            n += 1;
            i = next(i);
        }
        Ok(n)
    }

    fn check_facts(&self) -> Result<(), Violation> {
        let used = self.st.pools.facts_used as usize;
        ensure!(
            used <= self.facts.len(),
            "facts handed out past capacity",
            used
        );
        // live list: doubly linked, numbers growing, tail at the end
        let mut prev = NONE;
        let mut f = self.st.facts.fact_head;
        let mut live = 0usize;
        let mut last_num: Option<u32> = None;
        while f != NONE {
            ensure!((f as usize) < used, "live fact list leaves the pool", f);
            let x = self.facts[f as usize];
            ensure!(x.state == FactState::Live, "listed fact is not live", f);
            ensure!(x.prev == prev, "fact list back link broken", f);
            if let Some(n) = last_num {
                ensure!(x.num > n, "fact numbers not increasing", f);
            }
            ensure!(
                x.num < self.st.facts.next_fact_num,
                "fact number not yet handed out",
                f
            );
            last_num = Some(x.num);
            live += 1;
            ensure!(live <= used, "live fact list has a cycle", f);
            prev = f;
            f = x.next;
        }
        ensure!(
            self.st.facts.fact_tail == prev,
            "fact list tail wrong",
            prev
        );
        ensure!(
            live == self.st.facts.facts_live as usize,
            "live fact count wrong",
            self.st.facts.facts_live
        );
        let per_template: usize = (0..self.st.pools.ntemplates as usize)
            .map(|t| self.tmpl_mems[t].nfacts as usize)
            .sum();
        ensure!(
            per_template == live,
            "per-template fact counts wrong",
            per_template
        );
        // host: each template's own list holds its live facts, numbers growing
        #[cfg(feature = "host-speedups")]
        for t in 0..self.st.pools.ntemplates as usize {
            let (mut prev, mut f, mut n) = (NONE, self.tmpl_mems[t].tfirst, 0usize);
            while f != NONE {
                ensure!((f as usize) < used, "template fact list leaves the pool", f);
                let x = self.facts[f as usize];
                ensure!(
                    x.state == FactState::Live && x.tmpl as usize == t,
                    "template fact list holds another fact",
                    f
                );
                let [next, back] = self.fact_tlinks[f as usize];
                ensure!(back == prev, "template fact list back link broken", f);
                ensure!(
                    prev == NONE || self.facts[prev as usize].num < x.num,
                    "template fact numbers not increasing",
                    f
                );
                n += 1;
                ensure!(n <= used, "template fact list has a cycle", f);
                prev = f;
                f = next;
            }
            ensure!(
                self.tmpl_mems[t].tlast == prev,
                "template fact list tail wrong",
                prev
            );
            ensure!(
                n == self.tmpl_mems[t].nfacts as usize,
                "template fact list length wrong",
                n
            );
        }
        let free = self.walk(
            self.st.pools.fact_free,
            used,
            |i| self.facts[i as usize].next,
            "fact free list broken",
        )?;
        let mut states = [0usize; 3];
        for (i, x) in self.facts.iter().enumerate() {
            if i >= used {
                ensure!(x.state == FactState::Free, "fact beyond the used mark", i);
                continue;
            }
            states[x.state as usize] += 1;
            if x.state != FactState::Live {
                ensure!(
                    x.first_am == TokenId::NONE,
                    "dead fact keeps alpha matches",
                    i
                );
            }
        }
        ensure!(
            states[FactState::Live as usize] == live,
            "live facts not all listed",
            live
        );
        ensure!(
            states[FactState::Pending as usize] == 0,
            "fact left pending",
            0
        );
        ensure!(
            states[FactState::Free as usize] == free,
            "free facts not all on the free list",
            free
        );
        ensure!(live + free == used, "fact accounting does not add up", used);
        let mut g = self.st.pools.fact_free;
        while g != NONE {
            ensure!(
                self.facts[g as usize].state == FactState::Free,
                "fact on the free list is in use",
                g
            );
            g = self.facts[g as usize].next;
        }
        // duplicate index: each bucket chain holds live facts hashed there; all listed
        let mut hashed = 0usize;
        for (b, &head) in self.fact_buckets.iter().enumerate() {
            let mut d = head;
            let mut steps = 0usize;
            while d != NONE {
                ensure!((d as usize) < used, "fact hash chain leaves the pool", b);
                let x = self.facts[d as usize];
                ensure!(x.state == FactState::Live, "dead fact in the hash index", d);
                let h = self.cells_hash(x.tmpl, x.start as usize, x.len as usize);
                ensure!(
                    h as usize % self.fact_buckets.len() == b,
                    "fact in the wrong hash bucket",
                    d
                );
                #[cfg(feature = "host-speedups")]
                ensure!(x.hash == h, "fact's stored hash is stale", d);
                hashed += 1;
                steps += 1;
                ensure!(steps <= used, "fact hash chain has a cycle", b);
                d = x.hash_next;
            }
        }
        ensure!(
            hashed == live,
            "live facts missing from the hash index",
            hashed
        );
        // each live fact: template, cell layout, and no equal twin
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            let x = self.facts[f as usize];
            ensure!(
                x.tmpl < self.st.pools.ntemplates,
                "fact of an unknown template",
                f
            );
            let t = self.templates[x.tmpl as usize];
            let mut c = x.start as usize;
            let end = x.start as usize + x.len as usize;
            ensure!(
                end <= self.st.facts.values_top as usize,
                "fact cells past the arena top",
                f
            );
            for s in 0..t.nslots {
                ensure!(c < end, "fact has fewer cells than slots", f);
                let multi = self.slots[(t.first_slot + s) as usize].multi;
                let cells = match self.values[c] {
                    Value::Multi(m) => {
                        ensure!(multi, "multifield in a single-field slot", f);
                        1 + m.len as usize
                    }
                    Value::Void => return fail("fact slot holds no value", f as usize),
                    _ => {
                        ensure!(!multi, "multislot without its header cell", f);
                        1
                    }
                };
                for k in c + usize::from(multi)..c + cells {
                    ensure!(k < end, "multislot runs past the fact", f);
                    match self.values[k] {
                        Value::Sym(id) | Value::Str(id) => {
                            ensure!(id < self.st.pools.nsyms, "fact holds a dropped symbol", f)
                        }
                        // a void element stays (CLIPS keeps the one `insert$` of a
                        // call without a value puts in, and prints nothing for it)
                        Value::Multi(_) => return fail("fact field is not an atom", f as usize),
                        _ => {}
                    }
                }
                c += cells;
            }
            ensure!(c == end, "fact length does not match its slots", f);
            f = x.next;
        }
        // no two live facts are equal. Equal cells hash alike (but 0.0 and -0.0, which
        // CLIPS keeps apart too) and the walk above found each live fact once, in its
        // hash's bucket: only a bucket's facts need comparing (over all pairs of live
        // facts, this took 3/4 of a 9,000-fact test's time). Twins are made on
        // purpose while duplication is allowed, and stay after.
        if !self.st.mode.twins_made {
            for &head in self.fact_buckets.iter() {
                let mut d = head;
                while d != NONE {
                    let x = self.facts[d as usize];
                    let mut other = x.hash_next;
                    while other != NONE {
                        let y = self.facts[other as usize];
                        let same = y.tmpl == x.tmpl
                            && y.len == x.len
                            && (0..x.len as usize).all(|i| {
                                self.values[x.start as usize + i]
                                    .same(self.values[y.start as usize + i])
                            });
                        ensure!(!same, "two equal live facts", other);
                        other = y.hash_next;
                    }
                    d = x.hash_next;
                }
            }
        }
        Ok(())
    }

    /// The cells of live facts, and those free fact slots keep for their next fact
    /// (`free_fact_slot`), lie below the arena top and are disjoint: compaction
    /// moves the one, a new fact overwrites the other.
    fn check_values(&self) -> Result<(), Violation> {
        let top = self.st.facts.values_top as usize;
        ensure!(
            top <= self.values.len(),
            "value arena top past capacity",
            self.st.facts.values_top
        );
        let used = (self.st.pools.facts_used as usize).min(self.facts.len());
        let cells = |i: usize| {
            let x = &self.facts[i];
            (x.len != 0 && x.state != FactState::Pending)
                .then_some((x.start as usize, x.start as usize + x.len as usize))
        };
        for i in 0..used {
            let Some((_, e)) = cells(i) else { continue };
            ensure!(e <= top, "kept fact cells past the arena top", i);
        }
        // disjoint: each fact marks its cells, a window of the arena after the other
        for low in (0..top).step_by(MARK_WINDOW) {
            let high = (low + MARK_WINDOW).min(top);
            let mut marks = Marks::new(low);
            for i in 0..used {
                let Some((s, e)) = cells(i) else { continue };
                for c in s.max(low)..e.min(high) {
                    ensure!(!marks.mark(c), "fact cells overlap another fact's", i);
                }
            }
        }
        Ok(())
    }

    fn check_tokens(&self) -> Result<(), Violation> {
        let used = self.st.pools.tokens_used as usize;
        ensure!(
            used <= self.tokens.len(),
            "tokens handed out past capacity",
            used
        );
        let free = self.walk(
            self.st.pools.token_free.0,
            used,
            |i| self.tokens[TokenId(i)].next_sib.0,
            "token free list broken",
        )?;
        let mut counts = [0usize; 3];
        for (i, t) in self.tokens.iter().enumerate() {
            if i >= used {
                ensure!(t.kind == TokenKind::Free, "token beyond the used mark", i);
                continue;
            }
            counts[t.kind as usize] += 1;
        }
        let (nfree, nalpha, nbeta) = (
            counts[TokenKind::Free as usize],
            counts[TokenKind::Alpha as usize],
            counts[TokenKind::Beta as usize],
        );
        ensure!(nfree == free, "free tokens not all on the free list", free);
        ensure!(
            nalpha + nbeta == self.st.pools.tokens_live as usize,
            "live token count wrong",
            self.st.pools.tokens_live
        );
        ensure!(
            free + self.st.pools.tokens_live as usize == used,
            "token accounting does not add up",
            used
        );

        // alpha memories and each fact's alpha matches hold exactly the alpha tokens
        let mut in_mem = 0usize;
        for a in 0..self.st.pools.nalpha {
            let node = self.alpha_mems[a as usize];
            let mut prev = TokenId::NONE;
            let mut t = node.head;
            while t != TokenId::NONE {
                ensure!(t.ix() < used, "alpha memory leaves the pool", a);
                let tk = self.tokens[t];
                ensure!(
                    tk.kind == TokenKind::Alpha,
                    "non-alpha token in an alpha memory",
                    t
                );
                ensure!(tk.alpha() == a, "alpha match in another node's memory", t);
                ensure!(tk.mem_prev == prev, "alpha memory back link broken", t);
                ensure!(tk.extra == NONE, "alpha match left mid-propagation", t);
                let f = tk.fact;
                ensure!(
                    (f as usize) < self.facts.len()
                        && self.facts[f as usize].state == FactState::Live,
                    "alpha match of a dead fact",
                    t
                );
                ensure!(
                    self.facts[f as usize].tmpl == self.alphas[a as usize].tmpl,
                    "alpha match of another template's fact",
                    t
                );
                in_mem += 1;
                ensure!(in_mem <= nalpha, "alpha memory has a cycle", a);
                prev = t;
                t = tk.mem_next;
            }
            ensure!(node.tail == prev, "alpha memory tail wrong", a);
        }
        ensure!(in_mem == nalpha, "alpha matches outside any memory", in_mem);
        let mut of_facts = 0usize;
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            let mut prev = TokenId::NONE;
            let mut t = self.facts[f as usize].first_am;
            while t != TokenId::NONE {
                let tk = self.tokens[t];
                ensure!(
                    tk.kind == TokenKind::Alpha,
                    "fact lists a non-alpha token",
                    t
                );
                ensure!(tk.fact == f, "fact lists another fact's alpha match", t);
                ensure!(
                    tk.prev_sib == prev,
                    "fact's alpha match back link broken",
                    t
                );
                of_facts += 1;
                ensure!(of_facts <= nalpha, "fact's alpha matches have a cycle", f);
                prev = t;
                t = tk.next_sib;
            }
            f = self.facts[f as usize].next;
        }
        ensure!(
            of_facts == nalpha,
            "alpha matches missing from their facts",
            of_facts
        );

        // join memories hold exactly the partial matches
        let mut in_joins = 0usize;
        for j in 0..self.st.pools.njoins {
            let j = JoinId(j);
            let mut prev = TokenId::NONE;
            let mut t = self.join_mems[j].mem;
            while t != TokenId::NONE {
                ensure!(t.ix() < used, "join memory leaves the pool", j);
                let tk = self.tokens[t];
                ensure!(
                    tk.kind == TokenKind::Beta,
                    "non-partial match in a join memory",
                    t
                );
                ensure!(tk.owner == j, "partial match in another join's memory", t);
                ensure!(tk.mem_prev == prev, "join memory back link broken", t);
                in_joins += 1;
                ensure!(in_joins <= nbeta, "join memory has a cycle", j);
                prev = t;
                t = tk.mem_next;
            }
        }
        ensure!(
            in_joins == nbeta,
            "partial matches outside any join memory",
            in_joins
        );

        // each partial match: parents, alpha match, child lists, counts
        let mut parented = 0usize;
        let mut with_am = 0usize;
        let mut with_blocker = 0usize;
        for (i, tk) in self.tokens.as_slice()[..used].iter().enumerate() {
            if tk.kind == TokenKind::Beta {
                let j = self.joins[tk.owner];
                if j.kind == JoinKind::Root {
                    ensure!(
                        tk.parent == TokenId::NONE && tk.am == TokenId::NONE,
                        "root token with parents",
                        i
                    );
                } else {
                    ensure!(j.refs > 0, "partial match of a removed join", i);
                    self.check_parent(TokenId::at(i), j.parent)?;
                    #[cfg(feature = "host-speedups")]
                    {
                        // the binding copy: the parent's plus the own level
                        let mut want = self.tokens[tk.parent].binds;
                        if let Some(x) = want.get_mut(j.depth as usize) {
                            *x = if tk.am != TokenId::NONE {
                                self.tokens[tk.am].fact
                            } else {
                                NONE
                            };
                        }
                        ensure!(tk.binds == want, "partial match bindings stale", i);
                    }
                    match j.kind {
                        JoinKind::Positive => {
                            self.check_am(TokenId::at(i), j.alpha)?;
                            with_am += 1;
                        }
                        _ => ensure!(tk.am == TokenId::NONE, "unexpected alpha match", i),
                    }
                    if tk.blocked {
                        ensure!(
                            matches!(j.kind, JoinKind::Negative | JoinKind::Exists),
                            "blocked match at a join without not/exists",
                            i
                        );
                        with_blocker += 1;
                    }
                    if !self.token_active(TokenId::at(i)) {
                        ensure!(
                            self.children(TokenId::at(i), TokenKind::Beta)? == 0,
                            "inactive not/exists match has children",
                            i
                        );
                        ensure!(tk.extra == NONE, "inactive match has activations", i);
                    }
                }
                if tk.parent != TokenId::NONE {
                    parented += 1;
                }
                // every activation of this match is on the agenda and points back
                let mut a = tk.extra;
                let mut steps = 0usize;
                while a != NONE {
                    ensure!(
                        (a as usize) < self.st.pools.acts_used as usize,
                        "match lists an activation outside the pool",
                        i
                    );
                    ensure!(
                        self.acts[a as usize].token.ix() == i,
                        "match lists another match's activation",
                        a
                    );
                    steps += 1;
                    ensure!(steps <= self.acts.len(), "activation chain has a cycle", i);
                    a = self.acts[a as usize].next_of_token;
                }
            }
        }
        // blocker lists: every blocked output is listed once under the token that
        // blocks it (an alpha match of the join's pattern, or a partial match of the
        // subnetwork of a not/exists over several CEs); the head's back link names
        // the blocker
        let mut listed_b = 0usize;
        for (i, tk) in self.tokens.as_slice()[..used].iter().enumerate() {
            if !matches!(tk.kind, TokenKind::Alpha | TokenKind::Beta) {
                continue;
            }
            let mut prev = TokenId::at(i);
            let mut k = tk.blocks;
            while k != TokenId::NONE {
                ensure!(k.ix() < used, "blocker list outside the pool", i);
                let lk = self.tokens[k];
                ensure!(
                    lk.kind == TokenKind::Beta && lk.blocked,
                    "blocker list holds an unblocked token",
                    k
                );
                let j = self.joins[lk.owner];
                match tk.kind {
                    TokenKind::Alpha => ensure!(
                        tk.alpha() == j.alpha && j.rjoin == JoinId::NONE,
                        "blocker of another pattern",
                        k
                    ),
                    _ => ensure!(
                        j.rjoin != JoinId::NONE,
                        "partial match blocks an alpha-fed join",
                        k
                    ),
                }
                ensure!(lk.am_prev == prev, "blocker list back link broken", k);
                listed_b += 1;
                ensure!(listed_b <= with_blocker, "blocker list has a cycle", i);
                prev = k;
                k = lk.am_next;
            }
        }
        ensure!(
            listed_b == with_blocker,
            "blocked matches missing from their blockers' lists",
            listed_b
        );
        // child lists: every child points back and every parented token is listed
        let mut listed_p = 0usize;
        let mut listed_a = 0usize;
        for (i, tk) in self.tokens.as_slice()[..used].iter().enumerate() {
            match tk.kind {
                TokenKind::Beta => {
                    let mut prev = TokenId::NONE;
                    let mut c = tk.first_child;
                    while c != TokenId::NONE {
                        let ck = self.tokens[c];
                        ensure!(ck.parent.ix() == i, "child does not point to its parent", c);
                        ensure!(ck.prev_sib == prev, "child list back link broken", c);
                        listed_p += 1;
                        ensure!(listed_p <= parented, "child list has a cycle", i);
                        prev = c;
                        c = ck.next_sib;
                    }
                }
                TokenKind::Alpha => {
                    let mut prev = TokenId::NONE;
                    let mut c = tk.first_child;
                    while c != TokenId::NONE {
                        let ck = self.tokens[c];
                        ensure!(
                            ck.am.ix() == i,
                            "match does not point to its alpha match",
                            c
                        );
                        ensure!(ck.am_prev == prev, "alpha child list back link broken", c);
                        listed_a += 1;
                        ensure!(listed_a <= with_am, "alpha child list has a cycle", i);
                        prev = c;
                        c = ck.am_next;
                    }
                }
                _ => {}
            }
        }
        ensure!(
            listed_p == parented,
            "partial matches missing from parents",
            listed_p
        );
        ensure!(
            listed_a == with_am,
            "partial matches missing from alpha matches",
            listed_a
        );
        Ok(())
    }

    /// A partial match's parent is a live partial match of the parent join.
    fn check_parent(&self, t: TokenId, parent_join: JoinId) -> Result<(), Violation> {
        let p = self.tokens[t].parent;
        ensure!(
            p != TokenId::NONE && p.ix() < self.st.pools.tokens_used as usize,
            "partial match without its parent",
            t
        );
        let pk = self.tokens[p];
        ensure!(
            pk.kind == TokenKind::Beta,
            "parent of a match is not a partial match",
            t
        );
        ensure!(
            pk.owner == parent_join,
            "parent of a match at the wrong join",
            t
        );
        Ok(())
    }

    /// A partial match's alpha match is live and of the join's alpha node.
    fn check_am(&self, t: TokenId, alpha: Ix) -> Result<(), Violation> {
        let am = self.tokens[t].am;
        ensure!(
            am != TokenId::NONE && am.ix() < self.st.pools.tokens_used as usize,
            "partial match without its alpha match (dangling)",
            t
        );
        let ak = self.tokens[am];
        ensure!(
            ak.kind == TokenKind::Alpha,
            "alpha match of a match was freed",
            t
        );
        ensure!(ak.alpha() == alpha, "alpha match of another pattern", t);
        Ok(())
    }

    fn children(&self, t: TokenId, kind: TokenKind) -> Result<usize, Violation> {
        let mut n = 0usize;
        let mut c = self.tokens[t].first_child;
        let mut steps = 0usize;
        while c != TokenId::NONE {
            if self.tokens[c].kind == kind {
                n += 1;
            }
            steps += 1;
            ensure!(steps <= self.tokens.len(), "child list has a cycle", t);
            c = self.tokens[c].next_sib;
        }
        Ok(n)
    }

    fn check_agenda(&self) -> Result<(), Violation> {
        let used = self.st.pools.acts_used as usize;
        ensure!(used <= self.acts.len(), "activations past capacity", used);
        let free = self.walk(
            self.st.pools.act_free,
            used,
            |i| self.acts[i as usize].next,
            "activation free list broken",
        )?;
        let mut prev = NONE;
        let mut a = self.st.agenda.agenda_head;
        let mut on_agenda = 0usize;
        // host: the salience groups name each salience's run of the agenda
        #[cfg(feature = "host-speedups")]
        let groups = self.st.agenda.groups;
        #[cfg(feature = "host-speedups")]
        let mut group = 0usize;
        while a != NONE {
            ensure!((a as usize) < used, "agenda leaves the pool", a);
            let x = self.acts[a as usize];
            ensure!(x.prev == prev, "agenda back link broken", a);
            #[cfg(feature = "host-speedups")]
            if groups.kept {
                if prev == NONE || self.acts[prev as usize].salience != x.salience {
                    let g = groups
                        .groups
                        .get(group)
                        .filter(|_| group < groups.n as usize);
                    ensure!(
                        g.is_some_and(|g| g.first == a && g.salience == x.salience),
                        "salience group does not start its run",
                        a
                    );
                    group += 1;
                }
                if x.next == NONE || self.acts[x.next as usize].salience != x.salience {
                    ensure!(
                        groups.groups[group - 1].last == a,
                        "salience group does not end its run",
                        a
                    );
                }
            }
            if prev != NONE {
                let p = self.acts[prev as usize];
                ensure!(p.salience >= x.salience, "agenda not sorted by salience", a);
                ensure!(
                    !self.goes_before(a, prev),
                    "agenda not in strategy order among equal salience",
                    a
                );
            }
            ensure!(
                x.rule < self.st.pools.nrules,
                "activation of an unknown rule",
                a
            );
            let rule = self.rules[x.rule as usize];
            ensure!(!rule.deleted, "activation of a removed rule", a);
            ensure!(
                x.token.ix() < self.st.pools.tokens_used as usize,
                "activation without its match",
                a
            );
            let tk = self.tokens[x.token];
            ensure!(tk.kind == TokenKind::Beta, "activation of a freed match", a);
            ensure!(
                rule.terminal != JoinId::NONE && self.joins[rule.terminal].parent == tk.owner,
                "activation's match is not at its rule's last join",
                a
            );
            ensure!(
                self.token_active(x.token),
                "activation of an inactive match",
                a
            );
            if rule.salience_expr == NONE {
                ensure!(
                    x.salience == i32::from(rule.salience),
                    "activation salience is stale",
                    a
                );
            }
            // the activation is in its match's list
            let mut k = tk.extra;
            while k != NONE && k != a {
                k = self.acts[k as usize].next_of_token;
            }
            ensure!(k == a, "activation missing from its match's list", a);
            // every fact it matched is live
            let mut t = x.token;
            let mut depth = 0usize;
            while t != TokenId::NONE {
                let tk = self.tokens[t];
                if tk.am != TokenId::NONE {
                    let f = self.tokens[tk.am].fact;
                    ensure!(
                        self.facts[f as usize].state == FactState::Live,
                        "activation of a retracted fact",
                        a
                    );
                }
                depth += 1;
                ensure!(depth <= self.tokens.len(), "match ancestry has a cycle", a);
                t = tk.parent;
            }
            on_agenda += 1;
            ensure!(on_agenda <= used, "agenda has a cycle", a);
            prev = a;
            a = x.next;
        }
        #[cfg(feature = "host-speedups")]
        ensure!(
            !groups.kept || group == groups.n as usize,
            "salience group without activations",
            groups.n
        );
        // host, lex and mea: the ordered index is the agenda reversed, but for fired
        // heads still at its end (`strategy::RecencyIndex`)
        #[cfg(all(feature = "extras", feature = "grow", feature = "host-speedups"))]
        if groups.kept && self.st.recency_index.on {
            let v = &self.st.recency_index.v;
            let live = |e: &(Ix, u32)| {
                let x = &self.acts[e.0 as usize];
                x.rule != NONE && x.seq == e.1
            };
            let n = v.iter().rposition(live).map_or(0, |k| k + 1);
            ensure!(n == on_agenda, "lex/mea index length wrong", n);
            let mut a = self.st.agenda.agenda_head;
            for e in v[..n].iter().rev() {
                ensure!(
                    e.0 == a && live(e),
                    "lex/mea index out of agenda order",
                    e.0
                );
                a = self.acts[a as usize].next;
            }
        }
        ensure!(
            on_agenda + free == used,
            "activation accounting does not add up",
            used
        );
        ensure!(
            self.st.agenda.agenda_len as usize == on_agenda,
            "agenda length wrong",
            self.st.agenda.agenda_len
        );
        // host, several modules: no module has more activations than counted
        #[cfg(all(feature = "modules", feature = "host-speedups"))]
        if self.st.modules.add_hooks & crate::module::HOOK_COUNT != 0 {
            let mut have = [0u32; 256];
            let mut a = self.st.agenda.agenda_head;
            while a != NONE {
                have[usize::from(self.rule_tag(self.acts[a as usize].rule).module)] += 1;
                a = self.acts[a as usize].next;
            }
            for (m, (&h, &c)) in have.iter().zip(self.st.modules.acts_in.iter()).enumerate() {
                ensure!(h <= c, "module has more activations than counted", m as Ix);
            }
        }
        // and every activation listed under a match is on the agenda (counted above)
        let mut listed = 0usize;
        for tk in self.tokens.as_slice()[..self.st.pools.tokens_used as usize].iter() {
            if tk.kind == TokenKind::Beta {
                let mut k = tk.extra;
                while k != NONE {
                    listed += 1;
                    ensure!(listed <= on_agenda, "activations listed off the agenda", k);
                    k = self.acts[k as usize].next_of_token;
                }
            }
        }
        ensure!(
            listed == on_agenda,
            "activations missing from their matches",
            listed
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::handle::TokenId;
    use crate::host::NullHost;
    use crate::rete::TokenKind;
    use crate::value::NONE;
    use std::boxed::Box;

    #[test]
    fn fresh_and_busy_engines_are_consistent() {
        let mut e = Box::new(SmallEngine::new());
        e.check_invariants().unwrap();
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(deftemplate p (slot x) (multislot m))
             (defrule a (p (x ?x) (m $? ?y $?)) (not (q ?x)) => (assert (q ?x)))
             (defrule b (exists (q ?)) (p (x ?x)) => (retract ?x))",
        )
        .unwrap();
        e.check_invariants().unwrap();
        e.assert_str(h, "(p (x 1) (m a b c))").unwrap();
        e.assert_str(h, "(p (x 2) (m))").unwrap();
        e.check_invariants().unwrap();
        e.run(h, Some(2)).unwrap();
        e.check_invariants().unwrap();
        e.reset(h).unwrap();
        e.check_invariants().unwrap();
        e.clear(h).unwrap();
        e.check_invariants().unwrap();
    }

    /// 0.0 and -0.0 hash apart and make two facts, as in CLIPS: not twins to the
    /// checker either, though `same` takes them for equal.
    #[test]
    fn zero_and_negative_zero_make_two_facts() {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        let before = e.core(h).live_fact_count();
        e.assert_str(h, "(a 0.0)").unwrap();
        e.assert_str(h, "(a -0.0)").unwrap();
        // (a twin: refused)
        assert!(e.assert_str(h, "(a 0.0)").is_err());
        assert_eq!(e.core(h).live_fact_count(), before + 2);
        e.check_invariants().unwrap();
    }

    /// A busy engine for the corruption tests: facts, partial matches, not/exists
    /// counts and an agenda of several activations with equal salience.
    fn busy() -> Box<SmallEngine> {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(defrule a (p ?x) (q ?x) (not (r ?x)) =>) (defrule b (exists (q ?)) (p ?x) =>)",
        )
        .unwrap();
        for i in 0..3 {
            e.assert_str(h, &std::format!("(p {i})")).unwrap();
            e.assert_str(h, &std::format!("(q {i})")).unwrap();
        }
        e.assert_str(h, "(r 1)").unwrap();
        e.check_invariants().unwrap();
        e
    }

    /// The checker must see each kind of damage (a checker that never fails proves
    /// nothing): corrupt one link at a time and expect the named violation.
    #[test]
    fn corruption_is_detected() {
        type Damage = fn(&mut crate::engine::Core<'_>);
        let cases: [(&str, Damage); 13] = [
            ("free tokens not all on the free list", |cx| {
                cx.st.pools.tokens_used += 1
            }),
            ("live token count wrong", |cx| cx.st.pools.tokens_live += 1),
            ("fact list tail wrong", |cx| {
                cx.st.facts.fact_tail = cx.st.facts.fact_head
            }),
            ("fact cells overlap another fact's", |cx| {
                // (q 0) reads the cells of (p 0), equal to its own: values and hashes
                // stay right, only (p 0)'s cells are no longer its own
                let a = cx.facts[cx.st.facts.fact_head as usize].next as usize;
                let b = cx.facts[a].next as usize;
                cx.facts[b].start = cx.facts[a].start;
            }),
            ("two equal live facts", |cx| {
                // (p 1) gets the cells of (p 0), and the hash index is built again
                let a = cx.facts[cx.st.facts.fact_head as usize].next as usize;
                let b = cx.facts[cx.facts[a].next as usize].next as usize;
                let (from, to) = (cx.facts[a].start as usize, cx.facts[b].start as usize);
                for i in 0..cx.facts[a].len as usize {
                    cx.values[to + i] = cx.values[from + i];
                }
                for b in cx.fact_buckets.iter_mut() {
                    *b = NONE;
                }
                let mut f = cx.st.facts.fact_head;
                while f != NONE {
                    let x = cx.facts[f as usize];
                    let h = cx.cells_hash(x.tmpl, x.start as usize, x.len as usize);
                    #[cfg(feature = "host-speedups")]
                    {
                        cx.facts[f as usize].hash = h;
                    }
                    let bucket = h as usize % cx.fact_buckets.len();
                    cx.facts[f as usize].hash_next = cx.fact_buckets[bucket];
                    cx.fact_buckets[bucket] = f;
                    f = x.next;
                }
            }),
            ("live facts missing from the hash index", |cx| {
                for b in cx.fact_buckets.iter_mut() {
                    *b = NONE;
                }
            }),
            ("join missing from its parent's children", |cx| {
                let p = cx.joins[crate::handle::JoinId::at(1)].parent;
                cx.joins[p].first_child = crate::handle::JoinId::NONE;
            }),
            ("join missing from its alpha node's successors", |cx| {
                let a = cx.joins[crate::handle::JoinId::at(1)].alpha;
                cx.alphas[a as usize].succ = crate::handle::JoinId::NONE;
            }),
            ("symbols missing from the hash chains", |cx| {
                let empty = crate::symbols::Head::EMPTY;
                let b = cx.sym_buckets.iter().position(|&b| b != empty).unwrap();
                cx.sym_buckets[b] = empty;
            }),
            ("agenda not in strategy order among equal salience", |cx| {
                let a = cx.st.agenda.agenda_head;
                cx.acts[a as usize].seq = 0;
            }),
            ("activation accounting does not add up", |cx| {
                cx.st.pools.acts_used += 1
            }),
            ("alpha match of a match was freed", |cx| {
                // free an alpha match that partial matches are built on (dangling)
                let t = (0..cx.st.pools.tokens_used as usize)
                    .map(TokenId::at)
                    .find(|&t| {
                        cx.tokens[t].kind == TokenKind::Alpha
                            && cx.tokens[t].first_child != TokenId::NONE
                    })
                    .unwrap();
                cx.tokens[t].kind = TokenKind::Free;
                cx.st.pools.tokens_live -= 1;
                let free = cx.st.pools.token_free;
                cx.st.pools.token_free = t;
                // take it out of its fact's and memory's lists as a buggy free would
                let tk = cx.tokens[t];
                let a = tk.alpha() as usize;
                if tk.mem_prev != TokenId::NONE {
                    cx.tokens[tk.mem_prev].mem_next = tk.mem_next;
                } else {
                    cx.alpha_mems[a].head = tk.mem_next;
                }
                if tk.mem_next != TokenId::NONE {
                    cx.tokens[tk.mem_next].mem_prev = tk.mem_prev;
                } else {
                    cx.alpha_mems[a].tail = tk.mem_prev;
                }
                if tk.prev_sib != TokenId::NONE {
                    cx.tokens[tk.prev_sib].next_sib = tk.next_sib;
                } else {
                    cx.facts[tk.fact as usize].first_am = tk.next_sib;
                }
                if tk.next_sib != TokenId::NONE {
                    cx.tokens[tk.next_sib].prev_sib = tk.prev_sib;
                }
                cx.tokens[t].next_sib = free;
            }),
            ("blocked matches missing from their blockers' lists", |cx| {
                let t = (0..cx.st.pools.tokens_used as usize)
                    .map(TokenId::at)
                    .find(|&t| {
                        cx.tokens[t].kind != TokenKind::Free && cx.tokens[t].blocks != TokenId::NONE
                    })
                    .unwrap();
                cx.tokens[t].blocks = TokenId::NONE;
            }),
        ];
        let mut wrong = std::vec::Vec::new();
        for (what, damage) in cases {
            let mut e = busy();
            let h = &mut NullHost;
            let mut cx = e.core(h);
            damage(&mut cx);
            match cx.check_invariants() {
                Err(v) if v.what == what => {}
                other => wrong.push(std::format!("{what}: got {other:?}")),
            }
        }
        assert!(wrong.is_empty(), "{wrong:#?}");
    }
}
