//! Conflict resolution strategies: the order of activations of equal salience on the
//! agenda, as CLIPS 6.30 orders them (Basic Programming Guide 5.3; the details below
//! were observed in CLIPS 6.30 with `(agenda)` after `set-strategy`).
//!
//! Every strategy is a total order: salience first (higher first), then the strategy's
//! key, then creation order. Depth puts newer activations first among equal keys; every
//! other strategy puts older ones first. So an agenda re-sorted after `set-strategy` or
//! `refresh-agenda` is the same whatever order its activations are re-inserted in.
//!
//! - depth, breadth: creation order only (newest first, oldest first).
//! - lex: the fact numbers an activation matched (a `not`/`exists`/leading `test`
//!   slot counts as 0), sorted from most recent; compared one by one, the more recent
//!   first; when one list is a prefix of the other, the longer first; then the rule's
//!   complexity (higher first).
//! - mea: the fact matched by the first pattern (none ranks lowest), more recent
//!   first, then as lex.
//! - complexity, simplicity: the rule's complexity (see `Rule::complexity`), higher
//!   first or lower first.
//! - random: the number CLIPS draws from the C library's `rand()` for every activation
//!   it creates, whatever the strategy (so `(seed N)` reproduces CLIPS's order
//!   exactly), smaller first.
//!
//! Strategies other than depth need the `extras` feature (the agent image keeps
//! depth only: the random number costs a word per activation).

use crate::engine::Core;
use crate::value::Ix;

/// A conflict resolution strategy (`set-strategy`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Strategy {
    Depth = 0,
    Breadth = 1,
    Lex = 2,
    Mea = 3,
    Complexity = 4,
    Simplicity = 5,
    Random = 6,
}

impl Strategy {
    pub const ALL: [Strategy; 7] = [
        Strategy::Depth,
        Strategy::Breadth,
        Strategy::Lex,
        Strategy::Mea,
        Strategy::Complexity,
        Strategy::Simplicity,
        Strategy::Random,
    ];

    /// The name `get-strategy` returns.
    pub const fn name(self) -> &'static str {
        match self {
            Strategy::Depth => "depth",
            Strategy::Breadth => "breadth",
            Strategy::Lex => "lex",
            Strategy::Mea => "mea",
            Strategy::Complexity => "complexity",
            Strategy::Simplicity => "simplicity",
            Strategy::Random => "random",
        }
    }

    pub fn from_name(name: &str) -> Option<Strategy> {
        Strategy::ALL.into_iter().find(|s| s.name() == name)
    }

    pub fn from_u8(v: u8) -> Strategy {
        Strategy::ALL
            .get(v as usize)
            .copied()
            .unwrap_or(Strategy::Depth)
    }
}

/// Most fact slots an activation's recency list holds (a rule's pattern slots).
const MAX_SLOTS: usize = crate::rete::MAX_PATTERNS;

/// An activation's matched fact numbers for lex and mea: most recent first, a slot
/// without a fact as 0 (below every fact), and the first pattern's fact.
#[derive(Clone, Copy)]
pub(crate) struct Recency {
    sorted: [u32; MAX_SLOTS],
    n: usize,
    first: Option<u32>,
}

/// Host: an activation's `Recency`, kept aside (`State::recency`, by activation
/// index) from the first time lex or mea compares it, as CLIPS keeps an activation's
/// sorted time tags; with the creation number and partial match of the activation it
/// belongs to: an entry whose activation is not the one now at its index is worked
/// out again. (Only an undo's activation takes an old creation number, for a partial
/// match of the same facts: the same list.)
#[cfg(all(feature = "extras", feature = "grow"))]
#[derive(Clone, Copy)]
pub struct RecencyCache {
    seq: u32,
    token: crate::handle::TokenId,
    rec: Recency,
}

/// Host: under lex and mea, while the salience groups are kept (`agenda`), the
/// agenda's activations in reverse order (the head last) with their creation
/// numbers, so a new activation's place is found by a binary search over the kept
/// recency lists instead of a walk (CLIPS walks its salience group; a new
/// activation whose first fact is old walks far under mea). Every agenda change
/// while the groups are kept goes through it, but one: the head that fires is left
/// at the end and dropped the next time the index is used (`rindex_trim`: its entry
/// is no longer the activation there). Anything unexpected turns it off; the walk
/// (`recency_walk`) takes over until the groups are built again.
#[cfg(all(feature = "extras", feature = "grow"))]
pub struct RecencyIndex {
    pub on: bool,
    pub v: alloc::vec::Vec<(Ix, u32)>,
}

#[cfg(all(feature = "extras", feature = "grow"))]
impl RecencyIndex {
    pub const fn new() -> RecencyIndex {
        RecencyIndex {
            on: false,
            v: alloc::vec::Vec::new(),
        }
    }
}

#[cfg(all(feature = "extras", feature = "grow"))]
impl Default for RecencyIndex {
    fn default() -> Self {
        Self::new()
    }
}

/// Host: whether activation `aa` (recency list `ra`, its rule's complexity `ca`)
/// goes before `ac` (`rc`, `cc`) under lex (`mea` false) or mea: `goes_before`'s
/// order over kept lists.
#[cfg(all(feature = "extras", feature = "grow", feature = "host-speedups"))]
#[inline(always)]
fn kept_before(
    mea: bool,
    aa: &crate::rule::Activation,
    ra: &Recency,
    ca: u16,
    ac: &crate::rule::Activation,
    rc: &Recency,
    cc: u16,
) -> bool {
    if aa.salience != ac.salience {
        return aa.salience > ac.salience;
    }
    let mut by_key = if mea && ra.first != rc.first {
        rc.first.cmp(&ra.first)
    } else {
        recency_order(Strategy::Lex, ra, rc)
    };
    if by_key == core::cmp::Ordering::Equal {
        by_key = cc.cmp(&ca);
    }
    match by_key {
        core::cmp::Ordering::Less => true,
        core::cmp::Ordering::Greater => false,
        core::cmp::Ordering::Equal => (aa.seq.wrapping_sub(ac.seq) as i32) < 0,
    }
}

#[cfg(all(feature = "extras", feature = "grow", feature = "host-speedups"))]
impl Core<'_> {
    /// Drops the fired activations left at the index's end (see `RecencyIndex`).
    #[inline(always)]
    fn rindex_trim(&mut self) {
        let v = &mut self.st.recency_index.v;
        while let Some(&(x, seq)) = v.last() {
            let ax = &self.acts[x as usize];
            if ax.rule != crate::value::NONE && ax.seq == seq {
                break;
            }
            v.pop();
        }
    }

    /// How many of the index's entries activation `a` goes before (its place), by
    /// a binary search; None when some entry's list is not kept (`a`'s is worked
    /// out when `fill`: a new activation's; one leaving may be losing its match).
    fn rindex_search(&self, a: Ix, fill: bool) -> Option<usize> {
        let mut cache = self.st.recency.try_borrow_mut().ok()?;
        let need = self.acts.len();
        if cache.len() < need {
            cache.resize(need, None);
        }
        let aa = self.acts[a as usize];
        let ra = match cache.get(a as usize) {
            Some(Some(k)) if k.seq == aa.seq && k.token == aa.token => k.rec,
            _ if fill => self.kept_recency(&mut cache, a, &aa),
            _ => return None,
        };
        let ca = self.rules[aa.rule as usize].complexity;
        let mea = self.strategy() == Strategy::Mea;
        let v = &self.st.recency_index.v;
        let (mut lo, mut hi) = (0usize, v.len());
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            let c = v[mid].0;
            let ac = &self.acts[c as usize];
            let rc = match cache.get(c as usize) {
                Some(Some(k)) if k.seq == ac.seq && k.token == ac.token => &k.rec,
                _ => return None,
            };
            let cc = self.rules[ac.rule as usize].complexity;
            if kept_before(mea, &aa, &ra, ca, ac, rc, cc) {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        Some(lo)
    }

    /// New activation `a`'s place (the activations before and after it) from the
    /// index, which takes it in; None (the index turned off) when it cannot say.
    #[inline(never)]
    pub(crate) fn rindex_insert(&mut self, a: Ix) -> Option<(Ix, Ix)> {
        self.rindex_trim();
        let found = self.rindex_search(a, true);
        let ix = &mut self.st.recency_index;
        let Some(k) = found else {
            ix.on = false;
            return None;
        };
        let cur = if k > 0 {
            ix.v[k - 1].0
        } else {
            crate::value::NONE
        };
        let prev = ix.v.get(k).map_or(crate::value::NONE, |e| e.0);
        // the two must be neighbours on the agenda
        let linked = if prev == crate::value::NONE {
            self.st.agenda.agenda_head == cur
        } else {
            self.acts[prev as usize].next == cur
        };
        if !linked {
            ix.on = false;
            return None;
        }
        ix.v.insert(k, (a, self.acts[a as usize].seq));
        Some((prev, cur))
    }

    /// Activation `a` (`x`, still linked) leaves the index.
    #[inline(never)]
    pub(crate) fn rindex_remove(&mut self, x: &crate::rule::Activation, a: Ix) {
        self.rindex_trim();
        let at = self
            .rindex_search(a, false)
            .filter(|&k| self.st.recency_index.v.get(k) == Some(&(a, x.seq)));
        let ix = &mut self.st.recency_index;
        let at = at.or_else(|| ix.v.iter().rposition(|e| *e == (a, x.seq)));
        match at {
            Some(k) => {
                ix.v.remove(k);
            }
            None => ix.on = false,
        }
    }

    /// Builds the index from the agenda when the strategy is lex or mea (the
    /// salience groups are being built), every list kept.
    pub(crate) fn rindex_build(&mut self) {
        self.st.recency_index.on = false;
        self.st.recency_index.v.clear();
        let s = self.strategy();
        if s != Strategy::Lex && s != Strategy::Mea {
            return;
        }
        {
            let Ok(mut cache) = self.st.recency.try_borrow_mut() else {
                return;
            };
            let need = self.acts.len();
            if cache.len() < need {
                cache.resize(need, None);
            }
            let mut a = self.st.agenda.agenda_head;
            while a != crate::value::NONE {
                let x = self.acts[a as usize];
                self.kept_recency(&mut cache, a, &x);
                a = x.next;
            }
        }
        let mut a = self.st.agenda.agenda_head;
        let ix = &mut self.st.recency_index;
        while a != crate::value::NONE {
            let x = &self.acts[a as usize];
            ix.v.push((a, x.seq));
            a = x.next;
        }
        ix.v.reverse();
        ix.on = true;
    }
}

impl Core<'_> {
    /// The strategy in force.
    pub fn strategy(&self) -> Strategy {
        Strategy::from_u8(self.st.agenda.strategy)
    }

    /// Whether activation `x` goes before activation `y` on the agenda.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn goes_before(&self, x: Ix, y: Ix) -> bool {
        let (ax, ay) = (self.acts[x as usize], self.acts[y as usize]);
        if ax.salience != ay.salience {
            return ax.salience > ay.salience;
        }
        // creation order: positive when x is newer (numbers wrap)
        let newer = ax.seq.wrapping_sub(ay.seq) as i32;
        let strategy = self.strategy();
        // (without `extras` the strategy is always depth: the rest is not linked)
        if !cfg!(feature = "extras") || strategy == Strategy::Depth {
            return newer > 0;
        }
        let by_key = self.compare_keys(strategy, x, y);
        if by_key != core::cmp::Ordering::Equal {
            return by_key == core::cmp::Ordering::Less;
        }
        newer < 0
    }

    /// The strategy's key of `x` against `y`: Less when `x` goes first.
    fn compare_keys(&self, strategy: Strategy, x: Ix, y: Ix) -> core::cmp::Ordering {
        use core::cmp::Ordering::Equal;
        let (ax, ay) = (self.acts[x as usize], self.acts[y as usize]);
        let complexity = |a: &crate::rule::Activation| self.rules[a.rule as usize].complexity;
        match strategy {
            Strategy::Depth | Strategy::Breadth => Equal,
            Strategy::Complexity => complexity(&ay).cmp(&complexity(&ax)),
            Strategy::Simplicity => complexity(&ax).cmp(&complexity(&ay)),
            Strategy::Random => random_key(&ax).cmp(&random_key(&ay)),
            Strategy::Lex | Strategy::Mea => self
                .compare_recency(strategy, x, &ax, y, &ay)
                .then_with(|| complexity(&ay).cmp(&complexity(&ax))),
        }
    }

    /// Lex's or mea's order of the facts `x` and `y` matched: Less when `x` goes
    /// first. Host: the lists kept aside (`RecencyCache`), worked out on first use.
    fn compare_recency(
        &self,
        strategy: Strategy,
        x: Ix,
        ax: &crate::rule::Activation,
        y: Ix,
        ay: &crate::rule::Activation,
    ) -> core::cmp::Ordering {
        #[cfg(all(feature = "extras", feature = "grow"))]
        if let Ok(mut cache) = self.st.recency.try_borrow_mut() {
            let (i, j) = (x as usize, y as usize);
            let need = i.max(j) + 1;
            let len = cache.len();
            if len < need {
                cache.resize(need.max(2 * len), None);
            }
            for (k, a) in [(i, ax), (j, ay)] {
                let kept = matches!(cache[k], Some(c) if c.seq == a.seq && c.token == a.token);
                if !kept {
                    cache[k] = Some(RecencyCache {
                        seq: a.seq,
                        token: a.token,
                        rec: self.recency(a.token),
                    });
                }
            }
            if let (Some(cx), Some(cy)) = (&cache[i], &cache[j]) {
                return recency_order(strategy, &cx.rec, &cy.rec);
            }
        }
        #[cfg(not(all(feature = "extras", feature = "grow")))]
        let _ = (x, y);
        recency_order(strategy, &self.recency(ax.token), &self.recency(ay.token))
    }

    /// Host, lex and mea: `agenda_insert`'s walk for activation `a` from `cur` (`prev`
    /// the one before it), past every activation `a` does not go before
    /// (`goes_before`'s order), the kept lists borrowed once and compared inline.
    /// Returns the steps taken, or None (nothing moved) when the lists are borrowed.
    #[cfg(all(feature = "extras", feature = "grow", feature = "host-speedups"))]
    #[inline(never)]
    pub(crate) fn recency_walk(&self, a: Ix, prev: &mut Ix, cur: &mut Ix) -> Option<u32> {
        let mut cache = self.st.recency.try_borrow_mut().ok()?;
        let mea = self.strategy() == Strategy::Mea;
        let aa = self.acts[a as usize];
        let need = self.acts.len();
        if cache.len() < need {
            cache.resize(need, None);
        }
        let ra = self.kept_recency(&mut cache, a, &aa);
        let ca = self.rules[aa.rule as usize].complexity;
        let mut steps = 0u32;
        while *cur != crate::value::NONE {
            let c = *cur;
            let ac = self.acts[c as usize];
            if ac.salience != aa.salience {
                if aa.salience > ac.salience {
                    break;
                }
            } else {
                let rc = match cache.get(c as usize) {
                    Some(Some(k)) if k.seq == ac.seq && k.token == ac.token => k.rec,
                    _ => self.kept_recency(&mut cache, c, &ac),
                };
                let mut by_key = if mea && ra.first != rc.first {
                    rc.first.cmp(&ra.first)
                } else {
                    recency_order(Strategy::Lex, &ra, &rc)
                };
                if by_key == core::cmp::Ordering::Equal {
                    by_key = self.rules[ac.rule as usize].complexity.cmp(&ca);
                }
                let before = match by_key {
                    core::cmp::Ordering::Less => true,
                    core::cmp::Ordering::Greater => false,
                    core::cmp::Ordering::Equal => (aa.seq.wrapping_sub(ac.seq) as i32) < 0,
                };
                if before {
                    break;
                }
            }
            *prev = c;
            *cur = ac.next;
            steps += 1;
        }
        Some(steps)
    }

    /// Host: activation `k`'s kept recency list, worked out (and kept) when the entry
    /// is not its own.
    #[cfg(all(feature = "extras", feature = "grow", feature = "host-speedups"))]
    #[inline(always)]
    fn kept_recency(
        &self,
        cache: &mut alloc::vec::Vec<Option<RecencyCache>>,
        k: Ix,
        a: &crate::rule::Activation,
    ) -> Recency {
        let k = k as usize;
        if let Some(Some(c)) = cache.get(k) {
            if c.seq == a.seq && c.token == a.token {
                return c.rec;
            }
        }
        let rec = self.recency(a.token);
        if cache.len() <= k {
            cache.resize(k + 1, None);
        }
        cache[k] = Some(RecencyCache {
            seq: a.seq,
            token: a.token,
            rec,
        });
        rec
    }

    /// The recency list of a partial match (see `Recency`).
    fn recency(&self, token: crate::handle::TokenId) -> Recency {
        // fact numbers by pattern slot, walking the partial match up to the root; fact
        // numbers start at 0 (initial-fact), so they are shifted: 0 means "no fact"
        let mut slots = [0u32; MAX_SLOTS];
        let mut n = 0;
        for (depth, num) in self.basis(token) {
            if depth < MAX_SLOTS {
                if let Some(num) = num {
                    slots[depth] = num.saturating_add(1);
                }
                n = n.max(depth + 1);
            }
        }
        let first = if n > 0 && slots[0] != 0 {
            Some(slots[0])
        } else {
            None
        };
        slots[..n].sort_unstable_by(|a, b| b.cmp(a));
        Recency {
            sorted: slots,
            n,
            first,
        }
    }
}

/// Lex's or mea's order of two recency lists: Less when `rx`'s goes first.
fn recency_order(strategy: Strategy, rx: &Recency, ry: &Recency) -> core::cmp::Ordering {
    if strategy == Strategy::Mea && rx.first != ry.first {
        // a fact beats no fact; the more recent fact goes first
        return ry.first.cmp(&rx.first);
    }
    let shared = rx.n.min(ry.n);
    for i in 0..shared {
        if rx.sorted[i] != ry.sorted[i] {
            return ry.sorted[i].cmp(&rx.sorted[i]);
        }
    }
    ry.n.cmp(&rx.n)
}

#[cfg(feature = "extras")]
fn random_key(a: &crate::rule::Activation) -> u32 {
    a.random
}

#[cfg(not(feature = "extras"))]
fn random_key(_a: &crate::rule::Activation) -> u32 {
    0
}

#[cfg(all(test, feature = "extras"))]
mod tests {
    extern crate std;
    use super::Strategy;
    use crate::engine::SmallEngine;
    use crate::testutil::{run_program, CaptureHost};
    use std::string::String;
    use std::vec::Vec;

    #[test]
    fn names_round_trip() {
        for s in Strategy::ALL {
            assert_eq!(Strategy::from_name(s.name()), Some(s));
            assert_eq!(Strategy::from_u8(s as u8), s);
        }
        assert_eq!(Strategy::from_name("fifo"), None);
    }

    /// The complexity of each rule as CLIPS 6.30 ranks it (measured against rules of
    /// 1 to 10 bare patterns under the complexity strategy).
    #[test]
    fn rule_complexity_is_clips_specificity() {
        let cases = [
            ("(item)", 1),
            ("(item a b)", 3),
            ("(item ?x ?x)", 2),
            (
                "(item ?x ?y ?x) (test (and (numberp ?x) (> ?x (+ 10 ?y)) (< ?x 100)))",
                5,
            ),
            ("(item ?x) (other ?x)", 3),
            ("(item ~a)", 2),
            ("(item a|b)", 3),
            ("(item ?x&:(or (> ?x 1) (< ?x 0)))", 3),
            ("(item =(+ 1 1))", 2),
            ("(item ?x) (not (other ?x ?x))", 4),
            ("(item) (exists (other))", 2),
            ("(test (> 2 1)) (item)", 3),
            ("(not (item))", 1),
            ("?f <- (item $? a $?)", 2),
            ("", 0),
        ];
        for (lhs, want) in cases {
            let mut e = std::boxed::Box::new(SmallEngine::new());
            let mut h = CaptureHost::default();
            e.batch_str(&mut h, &std::format!("(defrule r {lhs} =>)"), false);
            let out = h.out.clone();
            let cx = e.core(&mut h);
            assert_eq!(cx.st.pools.nrules, 1, "{lhs}: {out}");
            assert_eq!(cx.rules[0].complexity, want, "{lhs}");
        }
    }

    /// The fired rules' names, in order.
    fn fired(out: &str) -> Vec<String> {
        out.lines()
            .filter_map(|l| l.strip_prefix("FIRE"))
            .filter_map(|l| l.split_whitespace().nth(1))
            .map(|r| r.trim_end_matches(':').into())
            .collect()
    }

    /// Random ordering is a permutation of the same activations that keeps salience
    /// order, and depends on the seed.
    #[test]
    fn random_is_a_salience_respecting_permutation() {
        let rules = "(defrule hi (declare (salience 5)) (a ?x) =>)
(defrule r1 (a ?x) =>)
(defrule r2 (a ?x) =>)
(defrule r3 (a ?x) (b) =>)
(defrule lo (declare (salience -5)) (a ?x) =>)
(watch rules)
";
        let facts = "(assert (a 1) (a 2) (a 3) (b))\n(run)\n";
        let depth = fired(&run_program(&std::format!("{rules}{facts}")));
        assert_eq!(depth.len(), 15, "{depth:?}");
        let mut orders = Vec::new();
        for seed in 1..6 {
            let out = run_program(&std::format!(
                "(seed {seed})\n(set-strategy random)\n{rules}{facts}"
            ));
            let order = fired(&out);
            let mut a = order.clone();
            let mut b = depth.clone();
            a.sort();
            b.sort();
            assert_eq!(a, b, "{out}");
            let hi = order.iter().rposition(|r| r == "hi");
            let lo = order.iter().position(|r| r == "lo");
            let mid = order.iter().position(|r| r.starts_with('r'));
            assert!(hi < mid && mid < lo, "{order:?}");
            orders.push(order);
        }
        assert!(orders.iter().any(|o| *o != orders[0]), "{orders:?}");
    }

    #[test]
    fn set_strategy_returns_the_old_one_and_refuses_other_names() {
        let out = run_program(
            "(printout t (set-strategy lex) crlf)
(printout t (get-strategy) crlf)
(printout t (set-strategy fifo) crlf)
(printout t (get-strategy) crlf)
",
        );
        // (the error ends the printout; the strategy stays)
        assert!(out.starts_with("depth\nlex\n[ARGACCES5]"), "{out}");
        assert!(out.ends_with("or random\nlex\n"), "{out}");
    }

    /// A change of strategy re-sorts what is on the agenda: breadth fires the oldest
    /// activation first, depth the newest.
    #[test]
    fn set_strategy_reorders_the_agenda() {
        let program = "(defrule r (a ?x) => (printout t ?x crlf))
(assert (a 1))
(assert (a 2))
(assert (a 3))
";
        let run = |extra: &str| run_program(&std::format!("{program}{extra}(run)\n"));
        assert!(run("").ends_with("<Fact-3>\n3\n2\n1\n"));
        assert!(run("(set-strategy breadth)\n").ends_with("<Fact-3>\ndepth\n1\n2\n3\n"));
    }
}
