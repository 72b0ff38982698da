//! Alpha side: matching one fact against the patterns of its template, keeping alpha
//! memories, and telling successor joins about new and removed alpha matches.

#[cfg(feature = "extras")]
use super::STAGE_LENGTH;
use super::{PatBinding, Token, TokenKind, MAX_MARKS, THIS_PATTERN};
use crate::builtins::basic::{CMP_FIRST, CMP_LAST};
use crate::engine::Core;
use crate::error::EvalError;
use crate::expr::{loc, FnKind, Op};
use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use crate::value::{Value, NONE};

/// Segmentation layout of one constrained multislot of a pattern.
#[derive(Clone, Copy)]
struct SlotLayout {
    slot: Ix,
    fixed: Ix,
    multis: u8,
    first_mark: u8,
    /// Host: where each of the slot's first `SEG_ELEMS` pattern elements lies under
    /// the marks (`ElemAt`), worked out once per fact and node rather than by a walk
    /// over the elements per test and segmentation (`mark_operand`).
    #[cfg(feature = "host-speedups")]
    at: [ElemAt; SEG_ELEMS],
    /// Host: the slot's cell in the fact and its length (`match_alpha`).
    #[cfg(feature = "host-speedups")]
    cell: usize,
    #[cfg(feature = "host-speedups")]
    len: Ix,
}

/// Host: pattern elements per slot `SlotLayout::at` places (the rest are walked).
#[cfg(feature = "host-speedups")]
const SEG_ELEMS: usize = 16;

/// Host: where a single-field pattern element lies in its slot: `base` plus the
/// lengths of the slot's first `marks` multifields (their marks), or, after the slot's
/// last multifield, `base` fields before the slot's end (`marks == FROM_END`).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy)]
struct ElemAt {
    base: u8,
    marks: u8,
}

#[cfg(feature = "host-speedups")]
const FROM_END: u8 = 0xFE;
/// Host: `ElemAt::marks` of a multifield element (not a single field's place).
#[cfg(feature = "host-speedups")]
const MULTI_ELEM: u8 = 0xFF;

#[cfg(feature = "host-speedups")]
const NO_ELEM: ElemAt = ElemAt {
    base: 0,
    marks: MULTI_ELEM,
};

impl SlotLayout {
    const EMPTY: SlotLayout = SlotLayout {
        slot: 0,
        fixed: 0,
        multis: 0,
        first_mark: 0,
        #[cfg(feature = "host-speedups")]
        at: [NO_ELEM; SEG_ELEMS],
        #[cfg(feature = "host-speedups")]
        cell: 0,
        #[cfg(feature = "host-speedups")]
        len: 0,
    };
}

/// Multislots with constraints one pattern may have (the parser refuses more).
pub(crate) const MAX_LAYOUTS: usize = 8;

/// Host: an alpha test decided under some of a segmentation's marks (`mark_test`).
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy, PartialEq, Eq)]
enum MarkTest {
    True,
    False,
    /// side-effect free, but reads an element a mark not yet set places
    Later,
    /// not one the quick path reads: the evaluator decides
    Unknown,
}

/// Host: an operand of `mark_test`.
#[cfg(feature = "host-speedups")]
#[derive(Clone, Copy)]
enum MarkOperand {
    Value(Value),
    Later,
    Unknown,
}

impl Core<'_> {
    /// Adds a new fact to every alpha memory it matches and propagates.
    pub(crate) fn network_assert(&mut self, fact: Ix) -> Result<(), EvalError> {
        // host: the discrimination index (`visit_alphas`, `needs_mf_order`) is made
        // current first (`network_assert_stale`, out of line: the usual path only
        // tests that it is; a new rule's priming keeps it stale)
        #[cfg(feature = "host-speedups")]
        if self.st.net.disc.net_gen != Some(self.st.net.net_gen) {
            return self.network_assert_stale(fact);
        }
        #[cfg(all(feature = "extras", not(feature = "host-speedups")))]
        if self.st.net.ir_alpha != NONE {
            return self.prime_fact(fact, self.st.net.ir_alpha);
        }
        // host: patterns sharing a multifield node match in CLIPS's order
        #[cfg(feature = "grow")]
        if self.needs_mf_order(self.facts[fact as usize].tmpl) {
            return self.network_assert_mf_order(fact);
        }
        self.visit_alphas::<false>(fact)
    }

    /// Host: `network_assert` while the discrimination index is stale: a fact a new
    /// rule's test asserts while the rule is primed meets only the rule's new alpha
    /// nodes, as in CLIPS's incremental reset (the index is kept stale meanwhile);
    /// otherwise the index is rebuilt and the fact goes the usual way.
    #[cfg(feature = "host-speedups")]
    #[cold]
    #[inline(never)]
    fn network_assert_stale(&mut self, fact: Ix) -> Result<(), EvalError> {
        #[cfg(feature = "extras")]
        if self.st.net.ir_alpha != NONE {
            return self.prime_fact(fact, self.st.net.ir_alpha);
        }
        self.rebuild_discrimination();
        self.network_assert(fact)
    }

    /// `network_assert` of a fact whose template needs CLIPS's multifield order (out
    /// of line: its collection's frame stays off the usual path).
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn network_assert_mf_order(&mut self, fact: Ix) -> Result<(), EvalError> {
        self.assert_in_mf_order(fact, |cx| cx.visit_alphas::<true>(fact))
    }

    /// Tests a new fact against every alpha node of its template. Inlined into each
    /// caller; `MF` only tells the callers apart (the multifield-order collection is
    /// the other one, on the host), so each has its own per-node closure, which LLVM
    /// inlines into the discrimination walk of its one caller.
    #[inline(always)]
    fn visit_alphas<const MF: bool>(&mut self, fact: Ix) -> Result<(), EvalError> {
        // host: only the nodes whose constant the fact holds, and the others
        #[cfg(feature = "host-speedups")]
        if self.for_discriminated_alphas(fact, |cx, a| cx.visit_alpha::<MF>(a, fact))? {
            return Ok(());
        }
        let tmpl = self.facts[fact as usize].tmpl;
        let mut a = self.templates[tmpl as usize].alpha_head;
        while a != NONE {
            self.visit_alpha::<MF>(a, fact)?;
            a = self.alphas[a as usize].next_in_tmpl;
        }
        Ok(())
    }

    /// Tests a new fact against one alpha node of its template and propagates a match
    /// (`MF`: in the multifield-order collection, see `match_one`).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn visit_alpha<const MF: bool>(&mut self, a: Ix, fact: Ix) -> Result<(), EvalError> {
        // a node whose rules are gone stays listed (ids and order) but is empty
        // and stays so: matches there would take tokens for nothing (and a
        // modify's old fact would need more room to come back than it freed)
        let node = &self.alphas[a as usize];
        if node.live {
            // the tests the quick path decides come first: most nodes a fact
            // visits fail one, and then no segmentation work is done
            if let Some(tests) = self.quick_tests(node.tests, fact) {
                // host: a node without multislot constraints (most) matches in
                // one call
                #[cfg(feature = "host-speedups")]
                if self.alphas[a as usize].desc == NONE && self.alphas[a as usize].nmarks == 0 {
                    return self.match_one::<MF>(a, fact, tests, [0; MAX_MARKS]);
                }
                self.match_alpha::<MF>(a, fact, tests)?;
            }
        }
        Ok(())
    }

    /// Removes everything a fact built in the network.
    /// (host: only where no copies are placed, `PrimeOrders::slow_retract`; else
    /// `network_retract_checked`)
    pub(crate) fn network_retract(&mut self, fact: Ix) {
        while self.facts[fact as usize].first_am != TokenId::NONE {
            let am = self.facts[fact as usize].first_am;
            self.remove_alpha_match(am);
        }
    }

    fn layouts(&self, alpha: Ix, out: &mut [SlotLayout; MAX_LAYOUTS]) -> usize {
        let mut n = 0;
        let mut marks = 0u8;
        let mut s = self.alphas[alpha as usize].desc;
        while s != NONE && n < out.len() {
            let sd = self.exprs[s as usize];
            let (mut fixed, mut multis) = (0 as Ix, 0u8);
            let mut e = sd.first;
            while e != NONE {
                if self.exprs[e as usize].aux == 1 {
                    multis += 1;
                } else {
                    fixed += 1;
                }
                e = self.exprs[e as usize].next;
            }
            // Without host-speedups every field is named here.
            #[allow(clippy::needless_update)]
            let layout = SlotLayout {
                slot: sd.data,
                fixed,
                multis,
                first_mark: marks,
                ..SlotLayout::EMPTY
            };
            out[n] = layout;
            #[cfg(feature = "host-speedups")]
            self.place_elements(&mut out[n], sd.first);
            if multis >= 2 {
                marks += multis - 1;
            }
            n += 1;
            s = sd.next;
        }
        n
    }

    /// Host: `l.at` for the slot's elements from `first` (`l.multis` counted).
    #[cfg(feature = "host-speedups")]
    fn place_elements(&self, l: &mut SlotLayout, first: Ix) {
        let (mut e, mut i, mut fixed, mut seen) = (first, 0usize, 0u8, 0u8);
        let mut after_last = l.fixed as usize;
        while e != NONE && i < SEG_ELEMS {
            let x = &self.exprs[e as usize];
            l.at[i] = if x.aux == 1 {
                seen += 1;
                NO_ELEM
            } else if seen == l.multis && seen > 0 {
                // after the last multifield: counted from the slot's end
                let back = after_last.min(u8::MAX as usize) as u8;
                after_last = after_last.saturating_sub(1);
                fixed += 1;
                ElemAt {
                    base: back,
                    marks: FROM_END,
                }
            } else {
                after_last = after_last.saturating_sub(1);
                fixed += 1;
                ElemAt {
                    base: fixed - 1,
                    marks: seen,
                }
            };
            i += 1;
            e = x.next;
        }
    }

    /// Runs one alpha node over one fact, creating an alpha match per segmentation;
    /// `tests` are the node's tests left for the evaluator (see `quick_tests`).
    /// `MF` as for `match_one`.
    pub(crate) fn match_alpha<const MF: bool>(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
    ) -> Result<(), EvalError> {
        let node = &self.alphas[alpha as usize];
        if node.desc == NONE && node.nmarks == 0 {
            // no multislot constraints (most patterns): one segmentation, nothing to lay out
            let mut marks = [0u8; MAX_MARKS];
            return self.enumerate_marks::<MF, false>(
                alpha,
                fact,
                tests,
                &[],
                &[0; MAX_LAYOUTS],
                &mut marks,
                0,
                0,
            );
        }
        #[cfg(feature = "host-speedups")]
        if node.nmarks == 0 {
            // one segmentation (no multislot has two multifield variables): only the
            // slots' lengths decide, checked as `layouts` lays them out (same slots,
            // same limit), without building the layout
            let mut s = node.desc;
            let mut n = 0;
            while s != NONE && n < 8 {
                let sd = self.exprs[s as usize];
                if self.slot_length_fails(fact, sd) {
                    #[cfg(feature = "extras")]
                    if tests != NONE && self.alphas[alpha as usize].stage & STAGE_LENGTH != 0 {
                        return self.tests_before_length(alpha, fact, tests);
                    }
                    return Ok(());
                }
                n += 1;
                s = sd.next;
            }
            let mut marks = [0u8; MAX_MARKS];
            return self.enumerate_marks::<MF, false>(
                alpha,
                fact,
                tests,
                &[],
                &[0; MAX_LAYOUTS],
                &mut marks,
                0,
                0,
            );
        }
        // host: a node with tests that may fail with an error or act before one of
        // its multifield choices runs them per choice (decided when it is made)
        #[cfg(feature = "extras")]
        if node.stage & !STAGE_LENGTH != 0 {
            return self.match_staged::<MF>(alpha, fact, tests);
        }
        self.match_marks::<MF, false>(alpha, fact, tests)
    }

    /// Host: `match_marks` for a node whose tests are staged (`AlphaNode::stage`),
    /// out of line.
    #[cfg(feature = "extras")]
    #[inline(never)]
    fn match_staged<const MF: bool>(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
    ) -> Result<(), EvalError> {
        self.match_marks::<MF, true>(alpha, fact, tests)
    }

    /// `match_alpha` of a node with multifield choices: the slots laid out, their
    /// lengths checked, every segmentation tried (`STAGE`: as `enumerate_marks`).
    #[inline(always)]
    fn match_marks<const MF: bool, const STAGE: bool>(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
    ) -> Result<(), EvalError> {
        let mut lay = [SlotLayout::EMPTY; MAX_LAYOUTS];
        let n = self.layouts(alpha, &mut lay);
        let mut slack = [0 as Ix; MAX_LAYOUTS];
        for (i, l) in lay[..n].iter_mut().enumerate() {
            let (cell, mlen) = self.slot_cell(fact, l.slot);
            let len = mlen.unwrap_or(1);
            if len < l.fixed || (l.multis == 0 && len != l.fixed) {
                #[cfg(feature = "extras")]
                if tests != NONE && self.alphas[alpha as usize].stage & STAGE_LENGTH != 0 {
                    return self.tests_before_length(alpha, fact, tests);
                }
                return Ok(());
            }
            slack[i] = len - l.fixed;
            #[cfg(feature = "host-speedups")]
            {
                // (a slot that is no multifield is not placed: `len` 0 reads nothing)
                l.cell = cell;
                l.len = mlen.unwrap_or(0);
            }
            #[cfg(not(feature = "host-speedups"))]
            let _ = cell;
        }
        let nmarks = self.alphas[alpha as usize].nmarks as usize;
        let mut marks = [0u8; MAX_MARKS];
        self.enumerate_marks::<MF, STAGE>(
            alpha,
            fact,
            tests,
            &lay[..n],
            &slack,
            &mut marks,
            0,
            nmarks,
        )
    }

    /// Tries every segmentation; CLIPS tries longer leading multifields first.
    #[allow(clippy::too_many_arguments)]
    fn enumerate_marks<const MF: bool, const STAGE: bool>(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        lay: &[SlotLayout],
        slack: &[Ix; MAX_LAYOUTS],
        marks: &mut [u8; MAX_MARKS],
        i: usize,
        nmarks: usize,
    ) -> Result<(), EvalError> {
        if i == nmarks {
            return self.match_one::<MF>(alpha, fact, tests, *marks);
        }
        // host: the tests on the path's levels before mark `i`'s node run now, once
        // for the marks chosen so far, as CLIPS tests them before it chooses there
        // (`STAGE`: the node has tests that may fail with an error or act there)
        #[cfg(feature = "extras")]
        let tests = if STAGE && tests != NONE && self.stage_at(alpha, tests, i) {
            match self.tests_before_mark(alpha, fact, tests, marks, i)? {
                Some(t) => t,
                None => return Ok(()),
            }
        } else {
            tests
        };
        // the slot this mark belongs to, and what earlier marks of it used
        let room = mark_room(lay, slack, marks, i);
        for m in (0..=room).rev() {
            marks[i] = m as u8;
            // host: the tests this mark decides run now, as CLIPS tests element by
            // element, so a constant that fails drops every segmentation after it
            #[cfg(feature = "host-speedups")]
            let tests = match self.mark_tests(tests, fact, lay, marks, i + 1) {
                Some(rest) => rest,
                None => continue,
            };
            self.enumerate_marks::<MF, STAGE>(
                alpha,
                fact,
                tests,
                lay,
                slack,
                marks,
                i + 1,
                nmarks,
            )?;
        }
        marks[i] = 0;
        Ok(())
    }

    /// Host: the node's tests `tests` once marks `..fixed` are set: None when one
    /// decides false (no segmentation with these marks matches), else the tests left
    /// for later, after those decided true. Tests are read in order while each is a
    /// side-effect-free comparison (`mark_test`); one that needs a later mark is
    /// passed over (it cannot fail with an error or write anything, so a false test
    /// after it decides the same), the first the quick path cannot read stops.
    #[cfg(feature = "host-speedups")]
    fn mark_tests(
        &mut self,
        tests: Ix,
        fact: Ix,
        lay: &[SlotLayout],
        marks: &[u8; MAX_MARKS],
        fixed: usize,
    ) -> Option<Ix> {
        let (mut t, mut rest, mut prefix) = (tests, tests, true);
        while t != NONE {
            match self.mark_test(t, fact, lay, marks, fixed) {
                MarkTest::True => {}
                MarkTest::False => return None,
                MarkTest::Later => prefix = false,
                MarkTest::Unknown => break,
            }
            t = self.exprs[t as usize].next;
            if prefix {
                rest = t;
            }
        }
        Some(rest)
    }

    /// Host: alpha test `e` (`Eq2`, a comparison builtin `=` .. `neq` with two
    /// arguments, `Not`, `And`, `Or` of constants, globals and single fields of
    /// `fact`) with marks `..fixed` set, as the evaluator would decide it once every
    /// mark is set. A comparison is decided as soon as the marks placing its fields
    /// are set, as CLIPS tests a field's constraint when the pattern network reaches
    /// it: a failing one drops every segmentation of the marks after it.
    #[cfg(feature = "host-speedups")]
    fn mark_test(
        &mut self,
        e: Ix,
        fact: Ix,
        lay: &[SlotLayout],
        marks: &[u8; MAX_MARKS],
        fixed: usize,
    ) -> MarkTest {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Eq2 => {
                let a = self.mark_operand(x.first, fact, lay, marks, fixed);
                let b =
                    self.mark_operand(self.exprs[x.first as usize].next, fact, lay, marks, fixed);
                match (a, b) {
                    (MarkOperand::Unknown, _) | (_, MarkOperand::Unknown) => MarkTest::Unknown,
                    (MarkOperand::Value(a), MarkOperand::Value(b)) => {
                        // neither is a multifield: `values_same` is `same`
                        if a.same(b) {
                            MarkTest::True
                        } else {
                            MarkTest::False
                        }
                    }
                    _ => MarkTest::Later,
                }
            }
            Op::Not => match self.mark_test(x.first, fact, lay, marks, fixed) {
                MarkTest::True => MarkTest::False,
                MarkTest::False => MarkTest::True,
                r => r,
            },
            Op::And | Op::Or => {
                let (want, hit) = if x.op == Op::Or {
                    (MarkTest::True, true)
                } else {
                    (MarkTest::False, false)
                };
                let mut later = false;
                let mut c = x.first;
                while c != NONE {
                    match self.mark_test(c, fact, lay, marks, fixed) {
                        MarkTest::Unknown => return MarkTest::Unknown,
                        MarkTest::Later => later = true,
                        r if r == want => return want,
                        _ => {}
                    }
                    c = self.exprs[c as usize].next;
                }
                match (later, hit) {
                    (true, _) => MarkTest::Later,
                    (false, true) => MarkTest::False,
                    (false, false) => MarkTest::True,
                }
            }
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && (CMP_FIRST..=CMP_LAST).contains(&x.data)
                    && x.first != NONE =>
            {
                let second = self.exprs[x.first as usize].next;
                if second == NONE || self.exprs[second as usize].next != NONE {
                    return MarkTest::Unknown;
                }
                // what `call` and `push_args` would refuse or record (as
                // `quick_alpha_test`)
                let sp = self.st.frame.sp as usize + 2;
                if self.st.eval.eval_depth >= self.max_eval_depth() || sp > self.stack.len() {
                    return MarkTest::Unknown;
                }
                let a = self.mark_operand(x.first, fact, lay, marks, fixed);
                let b = self.mark_operand(second, fact, lay, marks, fixed);
                match (a, b) {
                    (MarkOperand::Value(a), MarkOperand::Value(b)) => {
                        match crate::builtins::basic::compare(self, x.data, a, b) {
                            Some(r) => {
                                self.note_hw(crate::error::Pool::EvalStack, sp);
                                if r {
                                    MarkTest::True
                                } else {
                                    MarkTest::False
                                }
                            }
                            // a number compared with something else: the evaluator
                            // reports it
                            None => MarkTest::Unknown,
                        }
                    }
                    (MarkOperand::Unknown, _) | (_, MarkOperand::Unknown) => MarkTest::Unknown,
                    // `eq` and `neq` cannot fail, so a later test may be decided
                    // before them; a numeric one may fail once its fields are
                    // placed, and the tests after it wait for it
                    _ if x.data >= CMP_FIRST + 6 => MarkTest::Later,
                    _ => MarkTest::Unknown,
                }
            }
            _ => MarkTest::Unknown,
        }
    }

    /// Host: an operand of `mark_test` that is `+`, `-` or `*` of two operands it
    /// reads as numbers (`(= ?dx (- ?x 1))` on fields of a segmented slot), worked
    /// out as the evaluator's quick path does (`num_arith`); Unknown for any other
    /// call, a non-number (the evaluator reports it) or a call the evaluator's depth
    /// or stack limit would refuse inside the comparison.
    #[cfg(feature = "host-speedups")]
    #[inline(never)]
    fn mark_arith(
        &self,
        x: crate::expr::Expr,
        fact: Ix,
        lay: &[SlotLayout],
        marks: &[u8; MAX_MARKS],
        fixed: usize,
    ) -> MarkOperand {
        use crate::builtins::basic::{num_arith, ARITH_FIRST};
        if x.aux != FnKind::Builtin as u8
            || x.data.wrapping_sub(ARITH_FIRST) >= 3
            || x.first == NONE
        {
            return MarkOperand::Unknown;
        }
        let second = self.exprs[x.first as usize].next;
        if second == NONE || self.exprs[second as usize].next != NONE {
            return MarkOperand::Unknown;
        }
        // inside the comparison: one level deeper, its first argument pushed
        if self.st.eval.eval_depth + 1 >= self.max_eval_depth()
            || self.st.frame.sp as usize + 3 > self.stack.len()
        {
            return MarkOperand::Unknown;
        }
        let num = |o: MarkOperand| match o {
            MarkOperand::Value(v @ (Value::Int(_) | Value::Float(_))) => MarkOperand::Value(v),
            MarkOperand::Value(_) => MarkOperand::Unknown,
            o => o,
        };
        let a = num(self.mark_operand(x.first, fact, lay, marks, fixed));
        let b = num(self.mark_operand(second, fact, lay, marks, fixed));
        match (a, b) {
            (MarkOperand::Value(p), MarkOperand::Value(q)) => {
                MarkOperand::Value(num_arith(x.data, p, q))
            }
            (MarkOperand::Unknown, _) | (_, MarkOperand::Unknown) => MarkOperand::Unknown,
            _ => MarkOperand::Later,
        }
    }

    /// Host: an operand of `mark_test`: a single-field element of a multislot of
    /// `fact` read at its offset under marks `..fixed` (`Later` while a mark it
    /// depends on is not set), else as `quick_alpha_operand` reads it.
    #[cfg(feature = "host-speedups")]
    #[inline(always)]
    fn mark_operand(
        &self,
        e: Ix,
        fact: Ix,
        lay: &[SlotLayout],
        marks: &[u8; MAX_MARKS],
        fixed: usize,
    ) -> MarkOperand {
        let x = self.exprs[e as usize];
        if x.op == Op::Call {
            return self.mark_arith(x, fact, lay, marks, fixed);
        }
        let elem = loc::elem(x.data);
        if x.op != Op::PatVar
            || x.aux != THIS_PATTERN
            || x.data == loc::FACT
            || elem == loc::SINGLE
            || x.first == NONE
        {
            return match self.quick_alpha_operand(e, fact) {
                Some(v) => MarkOperand::Value(v),
                None => MarkOperand::Unknown,
            };
        }
        // the slot's places worked out for this fact (`place_elements`)
        let slot = Ix::from(loc::slot(x.data));
        if let Some(l) = lay.iter().find(|l| l.slot == slot) {
            if let Some(at) = l.at.get(elem as usize) {
                let len = l.len as usize;
                let pos = match at.marks {
                    MULTI_ELEM => return MarkOperand::Unknown,
                    FROM_END => len.wrapping_sub(at.base as usize),
                    0 => at.base as usize,
                    k => {
                        let (f, k) = (l.first_mark as usize, k as usize);
                        if f + k > fixed || f + k > MAX_MARKS {
                            return MarkOperand::Later;
                        }
                        at.base as usize
                            + marks[f..f + k].iter().map(|&m| m as usize).sum::<usize>()
                    }
                };
                if pos >= len {
                    return MarkOperand::Unknown;
                }
                return match self.values[l.cell + 1 + pos] {
                    Value::Multi(_) => MarkOperand::Unknown,
                    v => MarkOperand::Value(v),
                };
            }
        }
        let ps = self.exprs[x.first as usize];
        let (cell, mlen) = self.slot_cell_inline(fact, Ix::from(loc::slot(x.data)));
        let Some(len) = mlen else {
            return MarkOperand::Unknown;
        };
        let len = len as usize;
        // the element's offset, as `pattern_var` lays the slot out: a multifield
        // before it but the slot's last takes its mark (`ps.aux` is the slot's
        // first); the elements after the last one are all single and counted
        // from the slot's end, whatever the marks
        let mut k = ps.aux as usize;
        let (mut pos, mut i) = (0usize, 0u8);
        let mut c = ps.first;
        while c != NONE {
            let ex = &self.exprs[c as usize];
            let is_multi = ex.aux == 1;
            if i == elem {
                if is_multi {
                    return MarkOperand::Unknown;
                }
                break;
            }
            if is_multi {
                let (mut d, mut after) = (ex.next, 0usize);
                while d != NONE && self.exprs[d as usize].aux != 1 {
                    after += 1;
                    d = self.exprs[d as usize].next;
                }
                if d == NONE {
                    // the last multifield: `elem` is one of the `after` fields
                    let back = after - usize::from(elem - i - 1).min(after);
                    pos = match len.checked_sub(back) {
                        Some(p) => p,
                        None => return MarkOperand::Unknown,
                    };
                    break;
                }
                if k >= fixed || k >= MAX_MARKS {
                    return MarkOperand::Later;
                }
                pos += marks[k] as usize;
                k += 1;
            } else {
                pos += 1;
            }
            i += 1;
            c = ex.next;
        }
        if c == NONE || pos >= len {
            return MarkOperand::Unknown;
        }
        match self.values[cell + 1 + pos] {
            Value::Multi(_) => MarkOperand::Unknown,
            v => MarkOperand::Value(v),
        }
    }

    /// One segmentation of `fact` for `alpha`: an alpha match if the tests pass.
    /// `MF`: called from `network_assert_mf_order`'s walk, where the matches are
    /// collected (`rete::mforder`); only that walk collects (a fact cannot come while
    /// a pattern test runs), so the others leave the check out.
    #[cfg_attr(feature = "host-speedups", inline(never))]
    fn match_one<const MF: bool>(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        marks: [u8; MAX_MARKS],
    ) -> Result<(), EvalError> {
        if self.alpha_tests_pass(alpha, fact, tests, marks)? {
            #[cfg(feature = "grow")]
            if MF && self.st.net.mf.collecting {
                if let Some(p) = self.st.net.mf.pending.as_mut() {
                    p.push((alpha, marks));
                    return Ok(());
                }
            }
            self.add_alpha_match(alpha, fact, marks)?;
        }
        Ok(())
    }

    /// (Host: inlined into both `match_one`s, as into the one before `MF`.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn alpha_tests_pass(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        marks: [u8; MAX_MARKS],
    ) -> Result<bool, EvalError> {
        let t = tests;
        if t == NONE {
            return Ok(true);
        }
        // host: a node sharing the CLIPS node whose test failed with an error on
        // this fact is not tested again
        #[cfg(feature = "extras")]
        let t = if self.st.net.err_fact == fact {
            match self.shared_tests_left(alpha, fact, t) {
                Some(NONE) => return Ok(true),
                Some(t) => t,
                None => return Ok(false),
            }
        } else {
            t
        };
        let saved = self.st.net.this_pm;
        self.st.net.this_pm = PatBinding { fact, marks };
        let r = self.eval_tests(t);
        self.st.net.this_pm = saved;
        match r {
            // CLIPS reports a failing pattern test and treats it as not matching
            Err(e) if !e.is_capacity() => {
                #[cfg(all(feature = "grow", feature = "extras"))]
                self.matches_before_error(alpha, fact, marks)?;
                self.report_pattern_error(alpha, fact, e);
                Ok(false)
            }
            r => r,
        }
    }

    /// Whether `fact`'s slot of descriptor `sd` (a `PatSlot`) has a length its
    /// elements cannot take: fewer fields than its single-field elements, or another
    /// number of them when it has no multifield.
    #[cfg(any(feature = "host-speedups", feature = "extras"))]
    #[inline(always)]
    fn slot_length_fails(&self, fact: Ix, sd: crate::expr::Expr) -> bool {
        let (mut fixed, mut multi) = (0 as Ix, false);
        let mut e = sd.first;
        while e != NONE {
            let x = &self.exprs[e as usize];
            if x.aux == 1 {
                multi = true;
            } else {
                fixed += 1;
            }
            e = x.next;
        }
        let len = self.slot_cell(fact, sd.data).1.unwrap_or(1);
        len < fixed || (!multi && len != fixed)
    }

    /// A node's tests `tests` run on `fact` by the quick path, in order, before any
    /// segmentation (they read no marks): None when one is false, else the tests
    /// left for the evaluator, from the first one the quick path cannot decide
    /// (NONE: all passed).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn quick_tests(&mut self, tests: Ix, fact: Ix) -> Option<Ix> {
        let mut t = tests;
        if t == NONE {
            return Some(t);
        }
        // the first test, which most nodes a fact visits fail, with its fast case
        match self.quick_first_test(t, fact) {
            Some(true) => t = self.exprs[t as usize].next,
            Some(false) => return None,
            None => return Some(t),
        }
        while t != NONE {
            match self.quick_alpha_test(t, fact) {
                Some(true) => t = self.exprs[t as usize].next,
                Some(false) => return None,
                None => break,
            }
        }
        Some(t)
    }

    /// `quick_alpha_test` with its commonest case first: a field of the fact equal
    /// to a symbol (`(state IDLE)`, `(x a)`), a couple of loads and no calls.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn quick_first_test(&mut self, e: Ix, fact: Ix) -> Option<bool> {
        let x = self.exprs[e as usize];
        if x.op == Op::Eq2 {
            let a = self.exprs[x.first as usize];
            let b = self.exprs[a.next as usize];
            if b.op == Op::Sym && a.op == Op::PatVar && a.aux == THIS_PATTERN {
                let elem = loc::elem(a.data);
                if elem == loc::SINGLE && a.first == NONE && a.data != loc::FACT {
                    let v = self.plain_slot(fact, Ix::from(loc::slot(a.data)))?;
                    return Some(matches!(v, Value::Sym(s) if s == b.data));
                }
                if elem == 0 && a.first != NONE {
                    // the first element of a multislot (ordered facts: `(state IDLE)`),
                    // when the pattern's first element is single-field
                    let pe = self.exprs[a.first as usize].first;
                    if pe != NONE && self.exprs[pe as usize].aux != 1 {
                        let (cell, mlen) = self.slot_cell(fact, Ix::from(loc::slot(a.data)));
                        let v = match mlen {
                            Some(len) if len > 0 => self.values[cell + 1],
                            _ => return None,
                        };
                        return Some(matches!(v, Value::Sym(s) if s == b.data));
                    }
                }
            }
        }
        self.quick_alpha_test(e, fact)
    }

    /// Alpha test `e` on `fact` decided without the evaluator, when it is a
    /// comparison (`Eq2`, or one of the builtins `=` .. `neq` with two arguments) of
    /// constants, globals and single fields of the fact, or `Not`/`And`/`Or` of
    /// such; None otherwise, and whenever the evaluator would fail or read a
    /// multifield (it then decides, with the same result and errors). Side-effect
    /// free, so a None after partial work loses nothing.
    fn quick_alpha_test(&mut self, e: Ix, fact: Ix) -> Option<bool> {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Eq2 => {
                let a = self.quick_alpha_operand(x.first, fact)?;
                let b = self.quick_alpha_operand(self.exprs[x.first as usize].next, fact)?;
                // neither is a multifield: `values_same` is `same`
                Some(a.same(b))
            }
            // host: a field unequal to a symbol (`~far`) decided in line, without the
            // recursive call (as `And`/`Or` below)
            #[cfg(feature = "host-speedups")]
            Op::Not => Some(!self.quick_first_test(x.first, fact)?),
            #[cfg(not(feature = "host-speedups"))]
            Op::Not => Some(!self.quick_alpha_test(x.first, fact)?),
            Op::And | Op::Or => {
                let want = x.op == Op::Or;
                let mut c = x.first;
                while c != NONE {
                    // host: a field equal to a symbol (`S0|S1|S2`) decided in line
                    #[cfg(feature = "host-speedups")]
                    let r = self.quick_first_test(c, fact)?;
                    #[cfg(not(feature = "host-speedups"))]
                    let r = self.quick_alpha_test(c, fact)?;
                    if r == want {
                        return Some(want);
                    }
                    c = self.exprs[c as usize].next;
                }
                Some(!want)
            }
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && (CMP_FIRST..=CMP_LAST).contains(&x.data)
                    && x.first != NONE =>
            {
                let second = self.exprs[x.first as usize].next;
                if second == NONE || self.exprs[second as usize].next != NONE {
                    return None;
                }
                // what `call` and `push_args` would refuse or record
                let sp = self.st.frame.sp as usize + 2;
                if self.st.eval.eval_depth >= self.max_eval_depth() || sp > self.stack.len() {
                    return None;
                }
                let a = self.quick_alpha_operand(x.first, fact)?;
                let b = self.quick_alpha_operand(second, fact)?;
                self.note_hw(crate::error::Pool::EvalStack, sp);
                crate::builtins::basic::compare(self, x.data, a, b)
            }
            _ => None,
        }
    }

    /// An operand of a quick alpha test: a constant, a global or a single field of
    /// `fact` that `pattern_var` reads without segmentation marks; None for anything
    /// else and for multifield values.
    // inlined on the host only: in the image the copies would cost 2 KB of code
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn quick_alpha_operand(&self, e: Ix, fact: Ix) -> Option<Value> {
        let x = self.exprs[e as usize];
        let v = match x.op {
            Op::Sym => Value::Sym(x.data),
            Op::Str => Value::Str(x.data),
            Op::Int | Op::Float => self.const_value_inline(e),
            Op::Global => self.globals[x.data as usize].value,
            Op::PatVar if x.aux == THIS_PATTERN && x.data != loc::FACT => {
                let slot = Ix::from(loc::slot(x.data));
                let elem = loc::elem(x.data);
                if elem == loc::SINGLE {
                    return self.plain_slot(fact, slot);
                }
                if x.first == NONE {
                    return None;
                }
                let (cell, mlen) = self.slot_cell(fact, slot);
                // as `pattern_var`: only single-field elements up to this one, so its
                // offset is its index (within the slot: this may run before the alpha
                // node checks the slot's length)
                let len = mlen?;
                let mut c = self.exprs[x.first as usize].first;
                let mut i = 0u8;
                loop {
                    if c == NONE || self.exprs[c as usize].aux == 1 {
                        return None;
                    }
                    if i == elem {
                        break;
                    }
                    i += 1;
                    c = self.exprs[c as usize].next;
                }
                if Ix::from(i) >= len {
                    return None;
                }
                self.values[cell + 1 + i as usize]
            }
            _ => return None,
        };
        match v {
            Value::Multi(_) => None,
            v => Some(v),
        }
    }

    /// `[FACTMCH1]`: an error while testing a fact in the pattern network (out of
    /// line: errors are rare, and its buffer stays off the matching's stack frames).
    #[cold]
    #[inline(never)]
    fn report_pattern_error(&mut self, alpha: Ix, fact: Ix, e: EvalError) {
        use core::fmt::Write;
        self.st.net.pattern_error = true;
        self.st.mode.halting = true;
        self.report_eval_error(e);
        let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
        let _ = b.write_str("\n[FACTMCH1] This error occurred in the fact pattern network\n   Currently active fact: ");
        {
            let (view, _) = self.split();
            let _ = view.write_fact(&mut b, fact);
        }
        let tm = self.templates[self.facts[fact as usize].tmpl as usize];
        match self.failed_field(self.st.net.failed_test) {
            Some((slot, _)) if !tm.implied => {
                let name = self.slots[(tm.first_slot + Ix::from(slot)) as usize].name;
                let _ = writeln!(b, "\n   Problem resides in slot {}", self.sym_text(name));
            }
            Some((_, elem)) if elem != loc::SINGLE => {
                let _ = writeln!(b, "\n   Problem resides in field #{}", elem as usize + 1);
            }
            _ => {
                let _ = writeln!(b, "\n   Problem resides in field #1");
            }
        }
        self.write(crate::host::router::WERROR, b.as_str());
        // host: every alpha node sharing the CLIPS node whose test failed (in the
        // template's order, CLIPS's), and the fact is done with them all
        #[cfg(feature = "extras")]
        if let Some(level) = self.error_level(alpha) {
            let num = self.facts[fact as usize].num;
            let n = &mut self.st.net;
            (n.err_fact, n.err_num, n.err_alpha, n.err_level) = (fact, num, alpha, level as u8);
            n.err_pass = false;
            let mut a = self.templates[self.facts[fact as usize].tmpl as usize].alpha_head;
            while a != NONE {
                if self.shares_level(a, alpha, level) && !self.ends_above(a, level) {
                    self.write_alpha_rules(a);
                }
                a = self.alphas[a as usize].next_in_tmpl;
            }
            self.write(crate::host::router::WERROR, "\n");
            return;
        }
        self.write_alpha_rules(alpha);
        self.write(crate::host::router::WERROR, "\n");
    }

    /// Every rule using alpha node `alpha`'s pattern, and the pattern's position in it.
    fn write_alpha_rules(&mut self, alpha: Ix) {
        let mut j = self.alphas[alpha as usize].succ;
        while j != JoinId::NONE {
            self.write_rules_below(j, self.joins[j].depth as usize + 1);
            j = self.joins[j].alpha_next;
        }
    }

    /// Host: the level of alpha node `alpha`'s path (CLIPS's pattern-network node)
    /// whose test `failed_test` is, when CLIPS tests it once per fact: a level
    /// before the path's first multifield choice (a multifield among several in a
    /// slot: CLIPS tests the levels after it per length). None: not known (also a
    /// path cut short, a test naming no field).
    #[cfg(feature = "extras")]
    fn error_level(&self, alpha: Ix) -> Option<usize> {
        let level = self.test_level(alpha, self.st.net.failed_test)?;
        if self.alphas[alpha as usize].nmarks != 0 && level >= self.mark_level(alpha, 0)? {
            return None;
        }
        Some(level)
    }

    /// Host: whether alpha test `e` may fail with an error or act (print, change
    /// anything): all but constants, globals, fields of the fact and their equality
    /// (`Eq2`, `eq`, `neq`), numeric comparisons of numbers, `not`, `and`, `or` of
    /// such. Tests that cannot are not staged (`set_stage`): run any number of times
    /// in any order, they show nothing.
    #[cfg(feature = "extras")]
    fn test_acts(&self, e: Ix) -> bool {
        let x = &self.exprs[e as usize];
        match x.op {
            Op::Int | Op::Float | Op::Sym | Op::Str | Op::Global | Op::PatVar => false,
            Op::Eq2 | Op::And | Op::Or | Op::Not | Op::Expand => self.any_acts(x.first),
            Op::Call
                if x.aux == FnKind::Builtin as u8 && (CMP_FIRST..=CMP_LAST).contains(&x.data) =>
            {
                if x.data >= CMP_FIRST + 6 {
                    // `eq`, `neq`
                    return self.any_acts(x.first);
                }
                // a numeric comparison of numbers
                let mut c = x.first;
                while c != NONE {
                    if !matches!(self.exprs[c as usize].op, Op::Int | Op::Float) {
                        return true;
                    }
                    c = self.exprs[c as usize].next;
                }
                false
            }
            _ => true,
        }
    }

    /// Host: whether any of the arguments from `c` on may act (`test_acts`); the
    /// leaves (most: fields and constants) are told apart here, without a call.
    #[cfg(feature = "extras")]
    #[inline]
    fn any_acts(&self, mut c: Ix) -> bool {
        while c != NONE {
            let y = &self.exprs[c as usize];
            let leaf = matches!(
                y.op,
                Op::Int | Op::Float | Op::Sym | Op::Str | Op::Global | Op::PatVar
            );
            if !leaf && self.test_acts(c) {
                return true;
            }
            c = y.next;
        }
        false
    }

    /// Host: works out alpha node `alpha`'s `stage`, `stage_from` and `stage_end`
    /// (see `AlphaNode`) from its tests and path, when it is made. A node without
    /// multislot constraints (most) has no length test and no choice to stage tests
    /// before: decided here, in line, without looking at its tests.
    #[cfg(feature = "extras")]
    #[inline(always)]
    pub(crate) fn set_stage(&mut self, alpha: Ix) {
        let n = &mut self.alphas[alpha as usize];
        if n.desc == NONE && n.nmarks == 0 {
            // (`stage_from` and `stage_end` are read only for a mark staged)
            n.stage = 0;
            return;
        }
        self.set_stage_tested(alpha);
    }

    /// Host: `set_stage` of a node with multislot constraints: most have no test
    /// that acts, and no level is looked up.
    #[cfg(feature = "extras")]
    #[inline(never)]
    fn set_stage_tested(&mut self, alpha: Ix) {
        let (tests, nmarks) = {
            let n = &self.alphas[alpha as usize];
            (n.tests, n.nmarks as usize)
        };
        if !self.tests_act(tests) {
            self.alphas[alpha as usize].stage = 0;
            return;
        }
        self.work_out_stage(alpha, tests, nmarks);
    }

    /// Host: whether any test of the chain `tests` may act (`test_acts`), with the
    /// commonest, a field's equality to a constant, told without a call.
    #[cfg(feature = "extras")]
    fn tests_act(&self, mut t: Ix) -> bool {
        while t != NONE {
            let x = &self.exprs[t as usize];
            let acts = if x.op == Op::Eq2 {
                self.any_acts(x.first)
            } else {
                self.test_acts(t)
            };
            if acts {
                return true;
            }
            t = x.next;
        }
        false
    }

    /// Host: `set_stage` of a node with a test that may act. Each test's level and
    /// whether it acts are looked up once (the first `STAGE_TESTS` tests; a longer
    /// chain's others as they come).
    #[cfg(feature = "extras")]
    #[inline(never)]
    fn work_out_stage(&mut self, alpha: Ix, tests: Ix, nmarks: usize) {
        const STAGE_TESTS: usize = 16;
        // per test: its level, and the level again if it acts
        let look_up = |cx: &Self, t: Ix| {
            let l = cx.test_level(alpha, t);
            (l, l.filter(|_| cx.test_acts(t)))
        };
        let mut known = [(None, None); STAGE_TESTS];
        let mut stage = 0u8;
        let (mut t, mut k) = (tests, 0);
        while t != NONE {
            let (l, a) = look_up(self, t);
            if k < STAGE_TESTS {
                known[k] = (l, a);
            }
            if a.is_some() {
                stage |= STAGE_LENGTH;
            }
            (t, k) = (self.exprs[t as usize].next, k + 1);
        }
        let look = |cx: &Self, t: Ix, k: usize| match known.get(k) {
            Some(&v) => v,
            None => look_up(cx, t),
        };
        let (mut from, mut end) = ([NONE; MAX_MARKS], [NONE; MAX_MARKS]);
        for i in 0..nmarks.min(MAX_MARKS) {
            let Some(choice) = self.mark_level(alpha, i) else {
                continue;
            };
            // the last acting test on a level before the choice
            let (mut last, mut last_k, mut t, mut k) = (NONE, 0, tests, 0);
            while t != NONE {
                if look(self, t, k).1.is_some_and(|l| l < choice) {
                    (last, last_k) = (t, k);
                }
                (t, k) = (self.exprs[t as usize].next, k + 1);
            }
            if last == NONE {
                continue;
            }
            stage |= 1 << i;
            // the first test after it not on a level before the choice
            let f = self.exprs[last as usize].next;
            let (mut e, mut k) = (f, last_k + 1);
            while e != NONE && look(self, e, k).0.is_some_and(|l| l < choice) {
                (e, k) = (self.exprs[e as usize].next, k + 1);
            }
            (from[i], end[i]) = (f, e);
        }
        let n = &mut self.alphas[alpha as usize];
        (n.stage, n.stage_from, n.stage_end) = (stage, from, end);
    }

    /// Host: whether the tests left `tests` of alpha node `alpha` may hold one
    /// that acts on a level before mark `i`'s node (`stage`): not when they start
    /// after the last such one, before the first test not before the node.
    #[cfg(feature = "extras")]
    #[inline(always)]
    fn stage_at(&self, alpha: Ix, tests: Ix, i: usize) -> bool {
        let n = &self.alphas[alpha as usize];
        if i >= MAX_MARKS || n.stage & (1 << i) == 0 {
            return false;
        }
        let (mut t, end) = (n.stage_from[i], n.stage_end[i]);
        loop {
            if t == tests {
                return false;
            }
            if t == end || t == NONE {
                return true;
            }
            t = self.exprs[t as usize].next;
        }
    }

    /// Host: the level of alpha node `alpha`'s path where CLIPS chooses the length
    /// of mark `i`'s multifield (the node of that element; marks count a pattern's
    /// multislots in the order it names them, as its path does). `PATH_LEN` when
    /// cut off a full path (after every level it keeps); None: no such mark.
    #[cfg(feature = "extras")]
    fn mark_level(&self, alpha: Ix, i: usize) -> Option<usize> {
        let node = &self.alphas[alpha as usize];
        let mut first = 0usize;
        let mut s = node.desc;
        while s != NONE {
            let sd = self.exprs[s as usize];
            let mut multis = 0usize;
            let mut e = sd.first;
            while e != NONE {
                multis += usize::from(self.exprs[e as usize].aux == 1);
                e = self.exprs[e as usize].next;
            }
            if multis >= 2 && i < first + multis - 1 {
                // the slot's (i - first)th multifield element
                let (mut e, mut k, mut seen) = (sd.first, 0u8, 0usize);
                while e != NONE {
                    if self.exprs[e as usize].aux == 1 {
                        if seen == i - first {
                            let at = loc::new(u8::try_from(sd.data).ok()?, k);
                            let n = node.key_len as usize;
                            // (not on a full path: cut off it, after all its levels)
                            return (0..n)
                                .find(|&l| node.path_loc[l] == at)
                                .or((n == crate::rete::PATH_LEN).then_some(crate::rete::PATH_LEN));
                        }
                        seen += 1;
                    }
                    k = k.checked_add(1)?;
                    e = self.exprs[e as usize].next;
                }
                return None;
            }
            if multis >= 2 {
                first += multis - 1;
            }
            s = sd.next;
        }
        None
    }

    /// Host: `tests_before_length` when the multislot whose length fails (its first
    /// level `failing`) comes after multifield choices: the choices of the slots
    /// before it are made as `enumerate_marks` makes them, and the tests on levels
    /// before `failing` run as there (`tests_before_mark`); the fact matches no
    /// segmentation.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn choices_before_length(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        failing: usize,
    ) -> Result<(), EvalError> {
        let mut lay = [SlotLayout::EMPTY; MAX_LAYOUTS];
        let n = self.layouts(alpha, &mut lay);
        let mut slack = [0 as Ix; MAX_LAYOUTS];
        // the marks of the slots before the failing one
        let mut marks_before = 0;
        for (i, l) in lay[..n].iter().enumerate() {
            let len = self.slot_cell(fact, l.slot).1.unwrap_or(1);
            if len < l.fixed || (l.multis == 0 && len != l.fixed) {
                break;
            }
            slack[i] = len - l.fixed;
            if l.multis >= 2 {
                marks_before = l.first_mark as usize + l.multis as usize - 1;
            }
        }
        let mut marks = [0u8; MAX_MARKS];
        self.choices_before(
            alpha,
            fact,
            tests,
            &lay[..n],
            &slack,
            &mut marks,
            0,
            marks_before,
            failing,
        )
    }

    /// Host: `choices_before_length`'s walk over marks `i..k`, then the tests on
    /// levels before `failing`.
    #[cfg(feature = "extras")]
    #[allow(clippy::too_many_arguments)]
    fn choices_before(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        lay: &[SlotLayout],
        slack: &[Ix; MAX_LAYOUTS],
        marks: &mut [u8; MAX_MARKS],
        i: usize,
        k: usize,
        failing: usize,
    ) -> Result<(), EvalError> {
        if tests == NONE {
            return Ok(());
        }
        if i == k {
            self.tests_before_level(alpha, fact, tests, marks, failing, false)?;
            return Ok(());
        }
        let tests = match self.tests_before_mark(alpha, fact, tests, marks, i)? {
            Some(t) => t,
            None => return Ok(()),
        };
        let room = mark_room(lay, slack, marks, i);
        for m in (0..=room).rev() {
            marks[i] = m as u8;
            self.choices_before(alpha, fact, tests, lay, slack, marks, i + 1, k, failing)?;
        }
        marks[i] = 0;
        Ok(())
    }

    /// Host: the tests `tests` of alpha node `alpha` (those left, in the path's
    /// order) on levels before mark `i`'s node, run on `fact` with marks `..i` set,
    /// once for all the choices of the marks after (`enumerate_marks`): CLIPS tests
    /// a pattern's nodes before one where it chooses a multifield's length once per
    /// choice made above them. None: the fact fails the node (an error is
    /// reported); else the tests left. Before the first choice the fact is tested
    /// once (per fact and CLIPS node, `err_fact`, as `tests_before_length`).
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn tests_before_mark(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        marks: &[u8; MAX_MARKS],
        i: usize,
    ) -> Result<Option<Ix>, EvalError> {
        match self.mark_level(alpha, i) {
            Some(choice) => self.tests_before_level(alpha, fact, tests, marks, choice, i == 0),
            None => Ok(Some(tests)),
        }
    }

    /// Host: `tests_before_mark` up to level `choice`; `first`: no choice is made
    /// before it (the fact is tested once, the per-fact memo applies).
    #[cfg(feature = "extras")]
    fn tests_before_level(
        &mut self,
        alpha: Ix,
        fact: Ix,
        tests: Ix,
        marks: &[u8; MAX_MARKS],
        choice: usize,
        first: bool,
    ) -> Result<Option<Ix>, EvalError> {
        let mut end = tests;
        let mut last = 0;
        while end != NONE {
            match self.test_level(alpha, end) {
                Some(l) if l < choice => {
                    last = l;
                    end = self.exprs[end as usize].next;
                }
                _ => break,
            }
        }
        if end == tests {
            return Ok(Some(tests));
        }
        let mut t = tests;
        let num = self.facts[fact as usize].num;
        let memo = first && self.st.net.err_fact == fact && self.st.net.err_num == num;
        if memo && self.memo_applies(alpha, fact) {
            // a node visited before this one tested some of these levels
            if !self.st.net.err_pass {
                return Ok(None);
            }
            let level = self.st.net.err_level as usize;
            while t != end && self.test_level(alpha, t).is_some_and(|l| l <= level) {
                t = self.exprs[t as usize].next;
            }
            if t == end {
                return Ok(Some(end));
            }
        }
        match self.run_tests_to(alpha, fact, *marks, t, end, last) {
            Ok((level, pass)) => {
                if first && !memo {
                    // the nodes after this one sharing those levels are done with them
                    let n = &mut self.st.net;
                    (n.err_fact, n.err_num, n.err_alpha) = (fact, num, alpha);
                    (n.err_level, n.err_pass) = (level as u8, pass);
                }
                Ok(pass.then_some(end))
            }
            Err(e) if !e.is_capacity() => {
                #[cfg(feature = "grow")]
                self.matches_before_error(alpha, fact, *marks)?;
                self.report_pattern_error(alpha, fact, e);
                Ok(None)
            }
            Err(e) => Err(e),
        }
    }

    /// Host: whether another pattern's path ends on alpha node `a`'s path at level
    /// `level` or below it, before `a`'s end: CLIPS traces an error to the rules of
    /// a node where patterns end and not further down (`[FACTMCH1]`).
    #[cfg(feature = "extras")]
    fn ends_above(&self, a: Ix, level: usize) -> bool {
        let x = &self.alphas[a as usize];
        let len = x.key_len as usize;
        let tmpl = x.tmpl;
        let mut b = self.templates[tmpl as usize].alpha_head;
        while b != NONE {
            let y = &self.alphas[b as usize];
            let n = y.key_len as usize;
            if y.live && n > level && n < len && y.key[..n] == x.key[..n] {
                return true;
            }
            b = y.next_in_tmpl;
        }
        false
    }

    /// Host: whether alpha node `a` passes through level `level` of `b`'s path (the
    /// same CLIPS pattern-network node: the same node ids up to there).
    #[cfg(feature = "extras")]
    fn shares_level(&self, a: Ix, b: Ix, level: usize) -> bool {
        let (x, y) = (&self.alphas[a as usize], &self.alphas[b as usize]);
        x.live && x.key_len as usize > level && x.key[..=level] == y.key[..=level]
    }

    /// Host: whether alpha node `alpha` passes through the CLIPS node `err_fact`
    /// (here `fact`) was last tested at.
    #[cfg(feature = "extras")]
    fn memo_applies(&self, alpha: Ix, fact: Ix) -> bool {
        let n = &self.st.net;
        n.err_fact == fact
            && n.err_num == self.facts[fact as usize].num
            && n.err_alpha != NONE
            && (n.err_alpha as usize) < self.alphas.len()
            && self.shares_level(alpha, n.err_alpha, n.err_level as usize)
    }

    /// Host: alpha node `alpha`'s tests `t` left to run on `fact` (`err_fact`):
    /// None when the fact failed (with an error) at a CLIPS node the node passes
    /// through, as CLIPS tested it once and went no further below it; the tests
    /// after that node's level when the fact passed it; else `t`.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn shared_tests_left(&self, alpha: Ix, fact: Ix, mut t: Ix) -> Option<Ix> {
        if !self.memo_applies(alpha, fact) {
            return Some(t);
        }
        if !self.st.net.err_pass {
            return None;
        }
        let level = self.st.net.err_level as usize;
        while t != NONE && self.test_level(alpha, t).is_some_and(|l| l <= level) {
            t = self.exprs[t as usize].next;
        }
        Some(t)
    }

    /// Host: the level of alpha node `alpha`'s path test `t` is on.
    #[cfg(feature = "extras")]
    pub(crate) fn test_level(&self, alpha: Ix, t: Ix) -> Option<usize> {
        let (slot, elem) = self.failed_field(t)?;
        let at = loc::new(slot, elem);
        let node = &self.alphas[alpha as usize];
        (0..node.key_len as usize)
            .rev()
            .find(|&l| node.path_loc[l] == at)
    }

    /// Host: forgets the fact a pattern test failed on (`err_fact`): its number may
    /// be given again (a reset, a failed assert) or its nodes tested again (a new
    /// rule's priming).
    #[cfg(feature = "extras")]
    pub(crate) fn forget_pattern_error(&mut self) {
        self.st.net.err_fact = NONE;
    }

    /// Host: a fact whose multislot is too short or too long for alpha node `alpha`
    /// (`match_alpha`): CLIPS tests the slot's length at the slot's first node of
    /// the pattern's path, so the node's tests `tests` (those the quick path left)
    /// on levels before the first such slot run first, for their errors and
    /// effects; the fact does not match either way.
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn tests_before_length(&mut self, alpha: Ix, fact: Ix, tests: Ix) -> Result<(), EvalError> {
        let node = self.alphas[alpha as usize];
        // the first level of a slot whose length fails
        let mut first = usize::MAX;
        let mut s = node.desc;
        while s != NONE {
            let sd = self.exprs[s as usize];
            if self.slot_length_fails(fact, sd) {
                let l = (0..node.key_len as usize)
                    .find(|&l| Ix::from(loc::slot(node.path_loc[l])) == sd.data);
                match l {
                    Some(l) => first = first.min(l),
                    // cut off a full path: after all its levels
                    None if node.key_len as usize == crate::rete::PATH_LEN => {
                        first = first.min(crate::rete::PATH_LEN)
                    }
                    // not known where
                    None => return Ok(()),
                }
            }
            s = sd.next;
        }
        if first == usize::MAX {
            return Ok(());
        }
        if node.nmarks != 0 {
            // multifield choices before it: the tests after one run per choice
            match self.mark_level(alpha, 0) {
                Some(c) if c < first => {
                    return self.choices_before_length(alpha, fact, tests, first)
                }
                Some(_) => {}
                None => return Ok(()),
            }
        }
        // the tests (in the path's order) on levels before it
        let (mut end, mut last) = (tests, 0);
        while end != NONE {
            match self.test_level(alpha, end) {
                Some(l) if l < first => {
                    last = l;
                    end = self.exprs[end as usize].next;
                }
                _ => break,
            }
        }
        if end == tests || self.memo_applies(alpha, fact) {
            return Ok(());
        }
        // a node visited before this one through the same CLIPS nodes tested them
        let ir = self.st.net.ir_alpha;
        let mut b = self.templates[self.facts[fact as usize].tmpl as usize].alpha_head;
        while b != alpha && b != NONE {
            if (ir == NONE || b >= ir) && self.shares_level(b, alpha, last) {
                return Ok(());
            }
            b = self.alphas[b as usize].next_in_tmpl;
        }
        // the level the fact got to, and whether it passed it
        match self.run_tests_to(alpha, fact, [0; MAX_MARKS], tests, end, last) {
            Ok((level, pass)) => {
                // the nodes after this one sharing those levels are done with them
                let num = self.facts[fact as usize].num;
                let n = &mut self.st.net;
                (n.err_fact, n.err_num, n.err_alpha) = (fact, num, alpha);
                (n.err_level, n.err_pass) = (level as u8, pass);
                Ok(())
            }
            Err(e) if !e.is_capacity() => {
                #[cfg(feature = "grow")]
                self.matches_before_error(alpha, fact, [0; MAX_MARKS])?;
                self.report_pattern_error(alpha, fact, e);
                Ok(())
            }
            Err(e) => Err(e),
        }
    }

    /// Host: runs alpha node `alpha`'s tests from `t` up to `end` on `fact` with
    /// `marks`, as its match would, until one fails or raises an error (kept in
    /// `failed_test`): the level reached (`last` when all pass) and whether all did.
    #[cfg(feature = "extras")]
    fn run_tests_to(
        &mut self,
        alpha: Ix,
        fact: Ix,
        marks: [u8; MAX_MARKS],
        mut t: Ix,
        end: Ix,
        last: usize,
    ) -> Result<(usize, bool), EvalError> {
        let saved = self.st.net.this_pm;
        self.st.net.this_pm = PatBinding { fact, marks };
        let (scratch, sp) = (self.st.frame.scratch_top, self.st.frame.sp);
        self.st.net.matching += 1;
        let mut r = Ok((last, true));
        while t != end {
            let v = self.eval(t);
            self.st.frame.scratch_top = scratch;
            self.st.frame.sp = sp;
            match v {
                Err(e) => {
                    self.st.net.failed_test = t;
                    r = Err(e);
                    break;
                }
                Ok(v) if v == Value::Sym(crate::builtins::SYM_FALSE) => {
                    r = Ok((self.test_level(alpha, t).unwrap_or(last), false));
                    break;
                }
                Ok(_) => {}
            }
            t = self.exprs[t as usize].next;
        }
        self.st.net.matching -= 1;
        self.st.net.this_pm = saved;
        r
    }

    /// `      Of pattern #N in rule R` for every rule whose network passes through
    /// `join` (newest first, as CLIPS traces an error to its rules).
    pub(crate) fn write_rules_below(&mut self, join: JoinId, pattern: usize) {
        use core::fmt::Write;
        let j = self.joins[join];
        if j.is_terminal() {
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let name = self.sym_text(self.rules[j.rule as usize].name);
            let _ = writeln!(b, "      Of pattern #{pattern} in rule {name}");
            self.write(crate::host::router::WERROR, b.as_str());
            return;
        }
        let mut c = j.first_child;
        while c != JoinId::NONE {
            self.write_rules_below(c, pattern);
            c = self.joins[c].next_sibling;
        }
        // the end of a not/exists subnetwork feeds joins from the right
        let mut r = j.rsucc;
        while r != JoinId::NONE {
            self.write_rules_below(r, pattern);
            r = self.joins[r].alpha_next;
        }
    }

    /// The field (slot, element) the failing constraint `e` belongs to, as CLIPS names
    /// it: the one its root names (`expr::NAMES_FIELD`), else the pattern's first
    /// variable in it. (The image, without `extras`, reads no names: the check would
    /// cost its code budget.)
    pub(crate) fn failed_field(&self, e: Ix) -> Option<(u8, u8)> {
        if e == NONE {
            return None;
        }
        let x = self.exprs[e as usize];
        #[cfg(feature = "extras")]
        if x.op == Op::And && x.aux == crate::expr::NAMES_FIELD {
            return Some((loc::slot(x.data), loc::elem(x.data)));
        }
        if x.op == Op::PatVar && x.aux == THIS_PATTERN && x.data != loc::FACT {
            return Some((loc::slot(x.data), loc::elem(x.data)));
        }
        if matches!(x.op, Op::Int | Op::Float) {
            return None;
        }
        let mut c = x.first;
        while c != NONE {
            if let Some(f) = self.failed_field(c) {
                return Some(f);
            }
            c = self.exprs[c as usize].next;
        }
        None
    }

    /// Evaluates a chain of tests; all must be non-FALSE. Scratch and stack are
    /// restored afterwards, so tests leave nothing behind.
    /// While they run, CLIPS is pattern-matching: facts, rules and the environment
    /// may not change (`State::matching`).
    pub(crate) fn eval_tests(&mut self, mut t: Ix) -> Result<bool, EvalError> {
        let (scratch, sp) = (self.st.frame.scratch_top, self.st.frame.sp);
        self.st.net.matching += 1;
        let mut r = Ok(true);
        while t != NONE {
            let v = self.eval(t);
            self.st.frame.scratch_top = scratch;
            self.st.frame.sp = sp;
            match v {
                Err(e) => {
                    self.st.net.failed_test = t;
                    r = Err(e);
                    break;
                }
                Ok(v) if v == Value::Sym(crate::builtins::SYM_FALSE) => {
                    r = Ok(false);
                    break;
                }
                Ok(_) => {}
            }
            t = self.exprs[t as usize].next;
        }
        self.st.net.matching -= 1;
        r
    }

    /// (Host: inlined into `match_one`, its one caller on the assert path.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn add_alpha_match(
        &mut self,
        alpha: Ix,
        fact: Ix,
        marks: [u8; MAX_MARKS],
    ) -> Result<(), EvalError> {
        let t = self.alloc_token()?;
        let tail = self.alpha_mems[alpha as usize].tail;
        let fam = self.facts[fact as usize].first_am;
        self.tokens[t] = Token {
            kind: TokenKind::Alpha,
            marks,
            owner: Token::alpha_owner(alpha),
            fact,
            mem_prev: tail,
            next_sib: fam,
            extra: NONE,
            ..Token::EMPTY
        };
        if tail != TokenId::NONE {
            self.tokens[tail].mem_next = t;
        } else {
            self.alpha_mems[alpha as usize].head = t;
        }
        self.alpha_mems[alpha as usize].tail = t;
        if fam != TokenId::NONE {
            self.tokens[fam].prev_sib = t;
        }
        self.facts[fact as usize].first_am = t;
        #[cfg(feature = "host-speedups")]
        self.index_insert_as(t, alpha, PatBinding { fact, marks });
        #[cfg(not(feature = "host-speedups"))]
        self.index_insert(t);
        let mut j = self.alphas[alpha as usize].succ;
        while j != JoinId::NONE {
            // remember how far propagation got, so a rollback undoes only that
            self.tokens[t].extra = j.0;
            self.right_activate(j, t)?;
            j = self.joins[j].alpha_next;
        }
        self.tokens[t].extra = NONE;
        Ok(())
    }

    /// Removes an alpha match: retracts what successor joins built from it.
    pub(crate) fn remove_alpha_match(&mut self, am: TokenId) {
        // the only match of its memory: its successors' memories go whole
        #[cfg(feature = "wipe")]
        self.wipe_successors(am);
        let alpha = self.tokens[am].alpha();
        // partial matches built on it (newest first), then the not/exists outputs it
        // blocks, which look for another blocker: CLIPS's order
        while self.tokens[am].first_child != TokenId::NONE {
            let c = self.tokens[am].first_child;
            // the firing rule's logical partial match going with its own fact: CLIPS
            // unlinks it from its parents (`PosEntryRetractAlpha`), and the actions
            // assert nothing more (as a descendant, or blocked, they go on unsupported)
            #[cfg(feature = "logical")]
            let cut = self.logical_cut_before(c);
            self.delete_token(c);
            #[cfg(feature = "logical")]
            if cut {
                self.logical_cut_after();
            }
        }
        // out of its memory and bucket before the outputs it blocks are unblocked: a
        // later pattern of their rule may share this node, and what they pass on must
        // not meet the fact that is going (CLIPS builds nothing with it). Its own links
        // stay, so the search for the next blocker goes on after it.
        let tk = &self.tokens[am];
        let (fact, prev_sib, next_sib, blocks) = (tk.fact, tk.prev_sib, tk.next_sib, tk.blocks);
        // (the dying fact's matches may have left their memories already: `hide_dying`)
        let hidden = self.st.net.dying_hidden && fact == self.st.net.dying;
        if !hidden {
            let am_next = self.leave_alpha_memory(am, alpha);
            if blocks != TokenId::NONE {
                self.tokens[am].am_next = am_next;
            }
        }
        if blocks != TokenId::NONE {
            // (host: `am` is the blocker of its list's head, and what the unblocks
            // ask of it is read here once)
            #[cfg(feature = "host-speedups")]
            let known = super::beta::AlphaBlocker {
                last: next_sib == TokenId::NONE,
                fact,
            };
            while self.tokens[am].blocks != TokenId::NONE {
                let k = self.tokens[am].blocks;
                #[cfg(feature = "host-speedups")]
                self.unblock_alpha_head(k, am, known);
                #[cfg(not(feature = "host-speedups"))]
                self.remove_link(k);
            }
        }
        if prev_sib != TokenId::NONE {
            self.tokens[prev_sib].next_sib = next_sib;
        } else {
            self.facts[fact as usize].first_am = next_sib;
        }
        if next_sib != TokenId::NONE {
            self.tokens[next_sib].prev_sib = prev_sib;
        }
        // (an alpha match carries no logical support)
        debug_assert!(self.tokens[am].kind == TokenKind::Alpha);
        self.release_token(am);
    }

    /// `network_retract`, host: placing CLIPS's copies of partial matches where
    /// some are (`PrimeOrders::placed`).
    pub(crate) fn network_retract_checked(&mut self, fact: Ix) {
        #[cfg(feature = "grow")]
        if self.st.prime.placed && self.removal_order_shows() {
            return self.network_retract_placed(fact);
        }
        self.network_retract(fact);
    }

    /// Whether the order in which a retract deletes partial matches can show: in
    /// `watch activations`, in the facts that lose logical support, or in the
    /// outputs unblocked by a join from the right (or paid when owed). Else the
    /// deleted partial matches just go, and any order gives the same run (as for
    /// `wipe_successors`).
    #[cfg(feature = "grow")]
    fn removal_order_shows(&self) -> bool {
        self.st.mode.watch & crate::engine::watch::ACTIVATIONS != 0
            || self.st.net.from_right
            || self.st.net.owed != TokenId::NONE
            || {
                #[cfg(feature = "logical")]
                let l = self.logical_in_use();
                #[cfg(not(feature = "logical"))]
                let l = false;
                l
            }
    }

    /// Host: `network_retract` where CLIPS's copies of partial matches are placed
    /// among an alpha match's children: those go first, then the rest as usual.
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn network_retract_placed(&mut self, fact: Ix) {
        let primed = !self.st.prime.joins.is_empty();
        while self.facts[fact as usize].first_am != TokenId::NONE {
            let am = self.facts[fact as usize].first_am;
            let tk = &self.tokens[am];
            // (nothing to place without partial matches built on it)
            if tk.first_child != TokenId::NONE {
                let self_joined = self.st.prime.self_joined(tk.alpha());
                if primed || self_joined {
                    self.remove_alpha_children_placed(am, primed, self_joined);
                }
            }
            self.remove_alpha_match(am);
        }
    }

    /// Host: `remove_alpha_match`'s deletion of the partial matches built on `am`
    /// (of node `alpha`), each after what CLIPS's newer copies of older ones passed
    /// on (`take_back_primed_before`, `take_back_newer_copies`).
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn remove_alpha_children_placed(&mut self, am: TokenId, primed: bool, self_joined: bool) {
        while self.tokens[am].first_child != TokenId::NONE {
            let c = self.tokens[am].first_child;
            if primed {
                self.take_back_primed_before(c);
            }
            if self_joined {
                self.take_back_newer_copies(c, am);
            }
            if self.tokens[am].first_child != c {
                // (gone with what was taken back)
                continue;
            }
            #[cfg(feature = "logical")]
            let cut = self.logical_cut_before(c);
            self.delete_token(c);
            #[cfg(feature = "logical")]
            if cut {
                self.logical_cut_after();
            }
        }
    }

    /// Takes alpha match `am` of node `alpha` out of its memory and bucket; returns
    /// its bucket successor (`am_next`, cleared by the removal), which a search for
    /// the next blocker after it follows. Its memory links stay.
    #[inline(always)]
    fn leave_alpha_memory(&mut self, am: TokenId, alpha: Ix) -> TokenId {
        let am_next = self.tokens[am].am_next;
        self.index_remove(am, alpha);
        let tk = &self.tokens[am];
        let (mem_prev, mem_next) = (tk.mem_prev, tk.mem_next);
        if mem_prev != TokenId::NONE {
            self.tokens[mem_prev].mem_next = mem_next;
        } else {
            self.alpha_mems[alpha as usize].head = mem_next;
        }
        if mem_next != TokenId::NONE {
            self.tokens[mem_next].mem_prev = mem_prev;
        } else {
            self.alpha_mems[alpha as usize].tail = mem_prev;
        }
        am_next
    }

    /// Before a retract's first unblocked not output passes on: the retracted fact's
    /// alpha matches not removed yet leave their memories and buckets, so the joins
    /// below never meet the fact (CLIPS skips a dying fact's matches there). Each
    /// keeps links to the next match of another fact in its memory and bucket, where
    /// a search for a next blocker after it goes on.
    #[cold]
    #[inline(never)]
    pub(crate) fn hide_dying(&mut self) {
        let dying = self.st.net.dying;
        let mut am = self.facts[dying as usize].first_am;
        while am != TokenId::NONE {
            let tk = &self.tokens[am];
            let alpha = tk.alpha();
            let in_memory = if tk.mem_prev != TokenId::NONE {
                self.tokens[tk.mem_prev].mem_next == am
            } else {
                self.alpha_mems[alpha as usize].head == am
            };
            // (the match being removed has left already)
            if in_memory {
                let am_next = self.leave_alpha_memory(am, alpha);
                self.tokens[am].am_next = am_next;
            }
            am = self.tokens[am].next_sib;
        }
        // (the match being removed, which left as usual, too)
        let mut am = self.facts[dying as usize].first_am;
        while am != TokenId::NONE {
            let mut n = self.tokens[am].mem_next;
            while n != TokenId::NONE && self.tokens[n].fact == dying {
                n = self.tokens[n].mem_next;
            }
            self.tokens[am].mem_next = n;
            if self.alpha_indexed(self.tokens[am].alpha()) {
                let mut n = self.tokens[am].am_next;
                while n != TokenId::NONE && self.tokens[n].fact == dying {
                    n = self.tokens[n].am_next;
                }
                self.tokens[am].am_next = n;
            }
            am = self.tokens[am].next_sib;
        }
        self.st.net.dying_hidden = true;
    }

    /// Empties an alpha memory (used when a rule is removed or a load rolled back).
    pub(crate) fn clear_alpha_memory(&mut self, alpha: Ix) {
        while self.alpha_mems[alpha as usize].head != TokenId::NONE {
            let am = self.alpha_mems[alpha as usize].head;
            self.tokens[am].extra = NONE;
            self.remove_alpha_match(am);
        }
    }
}

/// How many elements mark `i` may take: what its slot's multifields have left
/// (`slack`) after the marks before it in that slot (at most 255; 0 for a mark of
/// no slot's choice).
#[inline(always)]
fn mark_room(
    lay: &[SlotLayout],
    slack: &[Ix; MAX_LAYOUTS],
    marks: &[u8; MAX_MARKS],
    i: usize,
) -> Ix {
    let mut room = 0 as Ix;
    for (k, l) in lay.iter().enumerate() {
        let f = l.first_mark as usize;
        let cnt = if l.multis >= 2 {
            l.multis as usize - 1
        } else {
            0
        };
        if i >= f && i < f + cnt {
            let used: Ix = marks[f..i].iter().map(|&m| m as Ix).sum();
            room = slack[k].saturating_sub(used).min(255);
        }
    }
    room
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use super::*;
    use crate::engine::SmallEngine;
    use crate::host::NullHost;
    use std::boxed::Box;

    /// An engine with `text` loaded and `facts` asserted.
    fn loaded(text: &str, facts: &[&str]) -> Box<SmallEngine> {
        let mut e = Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(h, "t", text).unwrap();
        for f in facts {
            e.assert_str(h, f).unwrap();
        }
        e
    }

    /// For every alpha test and fact of its template that the node's layout admits,
    /// the quick path either declines or agrees with the evaluator; the forms it
    /// must decline (function calls, multifields, type errors) do go to it.
    #[test]
    fn quick_alpha_tests_agree_with_the_evaluator() {
        let mut e = loaded(
            "(defglobal ?*lim* = 3 ?*mf* = (create$ 1 2))
             (deftemplate p (slot x) (slot y) (multislot m))
             (defrule r1 (p (x a) (y ~b)) =>)
             (defrule r2 (p (x a|b|1) (y ?y&:(<= ?y ?*lim*))) =>)
             (defrule r3 (p (y ?y&:(> ?y 2.5)&:(neq ?y 7)) (m $?m&:(> (length$ ?m) 0))) =>)
             (defrule r4 (p (y ?y&:(eq ?y ?*mf*))) =>)
             (defrule r5 (p (m c ?z&:(= ?z 2))) =>)
             (defrule r6 (state IDLE|BUSY) =>)
             (defrule r7 (state ~IDLE) =>)
             (defrule r8 (p (x ?x&:(< ?x 3))) =>)
             (defrule r9 (p (m $? d)) =>)
             (defrule r10 (p (m c ?z&:(eq ?z 2))) =>)",
            &[
                "(p (x a) (y b) (m))",
                "(p (x a) (y 2) (m c 2))",
                "(p (x b) (y 3.0) (m c 3))",
                "(p (x 1) (y 7) (m x))",
                "(p (x 2) (y zz) (m c 2 d))",
                "(state IDLE)",
                "(state BUSY)",
                "(state GONE)",
                "(state)",
                "(p (x a) (y 2) (m c))",
            ],
        );
        let h = &mut NullHost;
        let mut c = e.core(h);
        let (mut decided, mut declined, mut firsts) = (0, 0, 0);
        for a in 0..c.alphas.len() {
            let node = c.alphas[a];
            if !node.live || node.nmarks != 0 {
                continue;
            }
            let mut f = c.st.facts.fact_head;
            while f != NONE {
                let fits = c.facts[f as usize].tmpl == node.tmpl && {
                    let mut lay = [SlotLayout::EMPTY; MAX_LAYOUTS];
                    let n = c.layouts(a as Ix, &mut lay);
                    lay[..n].iter().all(|l| {
                        let len = c.slot_cell(f, l.slot).1.unwrap_or(1);
                        len >= l.fixed && (l.multis > 0 || len == l.fixed)
                    })
                };
                let mut t = node.tests;
                while c.facts[f as usize].tmpl == node.tmpl && t != NONE {
                    // network_assert asks before the layout check: must not fail
                    let quick = c.quick_alpha_test(t, f);
                    let first = (t == node.tests).then(|| c.quick_first_test(t, f));
                    if !fits {
                        t = c.exprs[t as usize].next;
                        continue;
                    }
                    c.st.net.this_pm = PatBinding {
                        fact: f,
                        marks: [0; MAX_MARKS],
                    };
                    let general = c
                        .eval(t)
                        .map(|v| v != Value::Sym(crate::builtins::SYM_FALSE));
                    c.st.net.this_pm = PatBinding::EMPTY;
                    if let Some(Some(q)) = first {
                        assert_eq!(Ok(q), general, "first: alpha {a} test {t} fact {f}");
                        firsts += 1;
                    }
                    match quick {
                        Some(q) => {
                            assert_eq!(Ok(q), general, "alpha {a} test {t} fact {f}");
                            decided += 1;
                        }
                        None => declined += 1,
                    }
                    t = c.exprs[t as usize].next;
                }
                f = c.facts[f as usize].next;
            }
        }
        assert!(
            decided >= 30 && declined >= 10 && firsts >= 10,
            "{decided} {declined} {firsts}"
        );
    }

    /// Host: for every segmentation of every fact a node with multifields admits, and
    /// every number of its marks set, the tests the marks decide (`mark_tests`)
    /// agree with the evaluator: None only where the evaluator says false, and the
    /// tests left give what all of them give, errors included.
    #[cfg(feature = "host-speedups")]
    #[test]
    fn mark_tests_agree_with_the_evaluator() {
        let mut e = loaded(
            "(defglobal ?*lim* = 3)
             (deftemplate p (slot x) (multislot m) (multislot n))
             (defrule r1 (p (m $?a ?x $?b ?y&:(> ?x ?y) $?c)) =>)
             (defrule r2 (p (m $? ?x&:(< ?x ?*lim*) $? ?y&:(eq ?y ?x) $?)) =>)
             (defrule r3 (p (m $? ?x $? ?y&:(<= ?y ?x)|:(= ?y 0) $?) (n $? ?z&:(<> ?z 2) $?)) =>)
             (defrule r4 (p (m $?a ?x ?y&:(>= ?y ?x))) =>)
             (defrule r5 (p (m ?f $? ?l&:(neq ?l ?f)) (n $? a $? ?q&:(> ?q 1))) =>)
             (defrule r6 (p (m $? ?x $? ?y&:(> (+ ?x 0) ?y) $?)) =>)
             (defrule r7 (v $? ?x $? ?y&:(< ?x ?y)&:(> ?y 2) $? ?z&:(neq ?z ?y)) =>)",
            &[
                "(p (x 1) (m 3 1 2 a 2.0) (n a 2 0))",
                "(p (m) (n))",
                "(p (m 1) (n a 5))",
                "(p (m b 2 b 1.5 7) (n 1 a 3 a 0))",
                "(v 1 x 3 0.5 4 4)",
                "(v 2 2)",
            ],
        );
        let h = &mut NullHost;
        let mut c = e.core(h);
        let (mut decided, mut segs) = (0, 0);
        for a in 0..c.alphas.len() {
            let node = c.alphas[a];
            if !node.live || node.desc == NONE {
                continue;
            }
            let nmarks = node.nmarks as usize;
            let mut f = c.st.facts.fact_head;
            while f != NONE {
                let next = c.facts[f as usize].next;
                let Some(tests) = (c.facts[f as usize].tmpl == node.tmpl)
                    .then(|| c.quick_tests(node.tests, f))
                    .flatten()
                else {
                    f = next;
                    continue;
                };
                let mut lay = [SlotLayout::EMPTY; MAX_LAYOUTS];
                let n = c.layouts(a as Ix, &mut lay);
                let mut fits = true;
                for l in lay[..n].iter_mut() {
                    let (cell, mlen) = c.slot_cell(f, l.slot);
                    let len = mlen.unwrap_or(1);
                    fits &= len >= l.fixed && (l.multis > 0 || len == l.fixed);
                    l.cell = cell;
                    l.len = mlen.unwrap_or(0);
                }
                // every marks vector (each mark up to 7) within its slot's slack
                for code in 0..8usize.pow(nmarks as u32) {
                    let mut marks = [0u8; MAX_MARKS];
                    for (i, m) in marks.iter_mut().enumerate().take(nmarks) {
                        *m = (code / 8usize.pow(i as u32) % 8) as u8;
                    }
                    let ok = fits
                        && lay[..n].iter().all(|l| {
                            let f0 = l.first_mark as usize;
                            let k = (l.multis as usize).saturating_sub(1);
                            let used: Ix = marks[f0..f0 + k].iter().map(|&m| m as Ix).sum();
                            used + l.fixed <= l.len.max(l.fixed)
                        });
                    if !ok {
                        continue;
                    }
                    segs += 1;
                    let eval = |c: &mut Core<'_>, t: Ix| {
                        c.st.net.this_pm = PatBinding { fact: f, marks };
                        let r = c.eval_tests(t).map_err(|e| e.is_capacity());
                        c.st.net.this_pm = PatBinding::EMPTY;
                        r
                    };
                    let general = eval(&mut c, tests);
                    for fixed in 0..=nmarks {
                        match c.mark_tests(tests, f, &lay[..n], &marks, fixed) {
                            None => {
                                assert_eq!(
                                    general,
                                    Ok(false),
                                    "alpha {a} fact {f} {marks:?} {fixed}"
                                );
                                decided += 1;
                            }
                            Some(rest) => {
                                decided += usize::from(rest != tests);
                                let r = eval(&mut c, rest);
                                assert_eq!(r, general, "alpha {a} fact {f} {marks:?} {fixed}");
                            }
                        }
                    }
                }
                f = next;
            }
        }
        assert!(decided >= 100 && segs >= 100, "{decided} {segs}");
    }

    /// The forms the quick path leaves to the evaluator.
    #[test]
    fn quick_alpha_tests_decline_what_they_cannot_decide() {
        let mut e = loaded(
            "(defglobal ?*mf* = (create$ 1 2))
             (deftemplate p (slot x) (multislot m))
             (defrule len (p (m $?m&:(> (length$ ?m) 0))) =>)
             (defrule glob (p (x ?x&:(eq ?x ?*mf*))) =>)
             (defrule typ (p (x ?x&:(< ?x 3))) =>)",
            &["(p (x sym) (m 1))"],
        );
        let h = &mut NullHost;
        let mut c = e.core(h);
        let f = c.st.facts.fact_head;
        let mut n = 0;
        for a in 0..c.alphas.len() {
            let node = c.alphas[a];
            if node.live && node.tests != NONE {
                assert_eq!(c.quick_alpha_test(node.tests, f), None, "alpha {a}");
                n += 1;
            }
        }
        assert_eq!(n, 3);
    }

    /// `set_stage`: equality and `eq`/`neq` tests are never staged; a call that may
    /// fail or act is, for the marks whose nodes come after it on the path and for
    /// a slot's length test; the tests left after it need no staging.
    #[cfg(feature = "extras")]
    #[test]
    fn stage_marks_only_tests_that_may_act() {
        let mut e = loaded(
            "(deftemplate t (slot x) (slot y) (multislot m))
             (deffunction p (?v) TRUE)
             (defrule eqs (t (m $? red $? blue $?)) =>)
             (defrule neqs (t (x ?x&~2&:(neq ?x a)) (m $?a ?b $?c)) =>)
             (defrule before (t (y ?y&:(< ?y 3)) (m $?a ?b $?c)) =>)
             (defrule after (t (m $?a ?b $?c) (y ?y&:(< ?y 3))) =>)
             (defrule between (t (m $?a ?b&:(p ?b) $?c ?d $?e)) =>)",
            &[],
        );
        let h = &mut NullHost;
        let c = e.core(h);
        let nodes: std::vec::Vec<_> = (0..c.alphas.len()).filter(|&a| c.alphas[a].live).collect();
        assert_eq!(nodes.len(), 5);
        let stage: std::vec::Vec<_> = nodes.iter().map(|&a| c.alphas[a].stage).collect();
        assert_eq!(
            stage,
            [0, 0, 1 | STAGE_LENGTH, STAGE_LENGTH, 2 | STAGE_LENGTH]
        );
        let b = nodes[4] as Ix;
        let t = c.alphas[b as usize].tests;
        assert!(!c.stage_at(b, t, 0));
        assert!(c.stage_at(b, t, 1));
        assert!(!c.stage_at(b, c.alphas[b as usize].stage_end[1], 1));
        assert!(c.stage_at(nodes[2] as Ix, c.alphas[nodes[2]].tests, 0));
    }
}
