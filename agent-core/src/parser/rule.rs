//! defrule, the syntax stage: a rule read into its intermediate form, a `Build` (one
//! `Ce` per join to make, its tests as expression nodes, a pattern's own tests and
//! network path as a `PatIr`) and the RHS's actions. Reading touches no network: the
//! alpha nodes and joins are built from the whole form by `crate::compile`, so a rule
//! that fails to read leaves nothing in the network.

use super::facts::expected;
use super::{PResult, Parser, Scope, VarEntry, VarKind};
use crate::compile::alpha::ZERO_LEN;
use crate::expr::{loc, Expr, Op};
use crate::handle::JoinId;
use crate::lexer::{Lexer, Tok, Token};
use crate::rete::{JoinKind, MAX_MARKS, MAX_PATTERNS, MAX_RHASH, PATH_LEN, THIS_PATTERN};
use crate::value::Ix;
use crate::value::{Value, NONE};

/// Most `or` CEs in one rule.
const MAX_ORS: usize = 8;

/// CE index meaning "the root" (as a parent) or "none" (as a right input).
pub(crate) const CE_ROOT: u8 = 0xFF;

/// One join to build. CEs are listed in creation order; a `not`/`exists` over
/// several CEs lists its subnetwork first, then the join taking the subnetwork's
/// end from the right.
#[derive(Clone, Copy)]
pub(crate) struct Ce {
    pub(crate) kind: JoinKind,
    /// The CE's pattern (`pat.tmpl` NONE for a test CE or a not/exists group) and,
    /// once `compile::alpha` has built it, its alpha node.
    pub(crate) pat: PatIr,
    pub(crate) alpha: Ix,
    /// Where the pattern's name starts in the text (`Lexer::token_at`), for an error
    /// while building its node.
    pub(crate) at: u32,
    /// Join tests (chain) and post tests (after not/exists).
    pub(crate) jtests: Ix,
    pub(crate) jlast: Ix,
    pub(crate) post: Ix,
    pub(crate) plast: Ix,
    /// Pattern index (binding slot) of the CE in its chain.
    pub(crate) depth: u8,
    /// Left input: index of the CE before it in its chain, or CE_ROOT.
    pub(crate) parent: u8,
    /// Join from the right: index of the subnetwork's last CE (else CE_ROOT).
    pub(crate) right: u8,
}

const CE_EMPTY: Ce = Ce {
    kind: JoinKind::Test,
    pat: PatIr::NONE,
    alpha: NONE,
    at: 0,
    jtests: NONE,
    jlast: NONE,
    post: NONE,
    plast: NONE,
    depth: 0,
    parent: CE_ROOT,
    right: CE_ROOT,
};

/// The CEs of a `Build`: in the image a fixed array; on hosts a vector that grows to
/// the slots written, so a rule form does not fill MAX_PATTERNS (64 there) CEs up
/// front (a 64-CE array filled per rule cost 0.7 % of a whole 40-rule load).
#[cfg(not(feature = "grow"))]
type Ces = [Ce; MAX_PATTERNS];

#[cfg(feature = "grow")]
pub(crate) struct Ces(alloc::vec::Vec<Ce>);

#[cfg(feature = "grow")]
impl Ces {
    /// Grows to `n` slots (new ones empty), as the array holds them all.
    fn reach(&mut self, n: usize) {
        if self.0.len() < n {
            self.0.resize(n, CE_EMPTY);
        }
    }
}

#[cfg(feature = "grow")]
impl core::ops::Index<usize> for Ces {
    type Output = Ce;
    fn index(&self, i: usize) -> &Ce {
        // a slot never written reads as the array's initial CE
        self.0.get(i).unwrap_or(&CE_EMPTY)
    }
}

#[cfg(feature = "grow")]
impl core::ops::IndexMut<usize> for Ces {
    #[inline]
    fn index_mut(&mut self, i: usize) -> &mut Ce {
        self.reach(i + 1);
        &mut self.0[i]
    }
}

#[cfg(feature = "grow")]
impl core::ops::Index<core::ops::RangeTo<usize>> for Ces {
    type Output = [Ce];
    fn index(&self, r: core::ops::RangeTo<usize>) -> &[Ce] {
        // every slot below `Build::n` was written; a shorter list only if not
        &self.0[..r.end.min(self.0.len())]
    }
}

#[cfg(feature = "grow")]
impl core::ops::IndexMut<core::ops::RangeTo<usize>> for Ces {
    fn index_mut(&mut self, r: core::ops::RangeTo<usize>) -> &mut [Ce] {
        self.reach(r.end);
        &mut self.0[r]
    }
}

pub(crate) struct Build {
    pub(crate) ces: Ces,
    pub(crate) n: usize,
    /// Last CE of the chain being built (CE_ROOT before the first) and the next
    /// pattern index in it.
    pub(crate) cur: u8,
    pub(crate) depth: u8,
    /// Nesting of not/exists groups, and the first CE of the innermost one.
    pub(crate) groups: u8,
    pub(crate) group_first: u8,
    /// `or` branch choice per `or` met, and how many branches each had.
    pub(crate) choice: [u8; MAX_ORS],
    pub(crate) counts: [u8; MAX_ORS],
    pub(crate) nor: usize,
    /// The salience, once the first disjunct evaluated it (CLIPS evaluates it once).
    pub(crate) salience: Option<i32>,
    /// The disjunct's salience (value, and its expression when not a literal), its
    /// actions and its frame size.
    pub(crate) sal: (i32, Ix),
    pub(crate) rhs: Ix,
    pub(crate) nlocals: u8,
    /// The disjunct's complexity (`Rule::complexity`).
    pub(crate) complexity: u16,
    /// The CE ending the rule's `logical` CEs (its logical join), CE_ROOT if none;
    /// whether a `logical` CE is being read, and whether a CE outside one was met.
    pub(crate) logical: u8,
    pub(crate) in_logical: bool,
    pub(crate) plain_seen: bool,
    /// The next group is one branch's negation of a `(not (or ...))`.
    pub(crate) split_branch: bool,
    /// The body a `GroupBody::Split` group splits.
    split_inner: GroupBody,
    /// `(declare (auto-focus TRUE))` (feature `modules`).
    #[cfg_attr(not(feature = "modules"), allow(dead_code))]
    pub(crate) auto_focus: bool,
    /// The rule's name (for `[PRNTUTIL8]` when its salience fails as it is read).
    pub(crate) name: crate::value::SymId,
}

impl Build {
    /// An empty form. Not inlined: built in place in the caller's slot (an inlined
    /// literal kept a second copy on the stack; a constant, 2 KB of read-only data).
    #[inline(never)]
    fn new() -> Build {
        Build {
            #[cfg(not(feature = "grow"))]
            ces: [CE_EMPTY; MAX_PATTERNS],
            #[cfg(feature = "grow")]
            // room for most rules' CEs at once (no growing step by step)
            ces: Ces(alloc::vec::Vec::with_capacity(8)),
            n: 0,
            cur: CE_ROOT,
            depth: 0,
            groups: 0,
            group_first: CE_ROOT,
            choice: [0; MAX_ORS],
            counts: [0; MAX_ORS],
            nor: 0,
            salience: None,
            sal: (0, NONE),
            rhs: NONE,
            nlocals: 0,
            complexity: 0,
            logical: CE_ROOT,
            in_logical: false,
            plain_seen: false,
            split_branch: false,
            split_inner: GroupBody::One,
            auto_focus: false,
            name: NONE,
        }
    }

    /// Moves to the next combination of `or` branches; false after the last one
    /// (the choices are then all 0 again).
    fn next_choice(&mut self) -> bool {
        self.next_choice_from(0)
    }

    /// The same over the `or` CEs from `base` on (those of one negation's body).
    fn next_choice_from(&mut self, base: usize) -> bool {
        let mut i = self.nor;
        while i > base {
            i -= 1;
            self.choice[i] += 1;
            if self.choice[i] < self.counts[i] {
                return true;
            }
            self.choice[i] = 0;
        }
        false
    }
}

/// A pattern as the syntax stage hands it to `compile::alpha`: its template, the tests
/// it makes of one fact, and its path in CLIPS's pattern network (computed by
/// `Compiler::pattern_form`), which decide which alpha node it shares.
#[derive(Clone, Copy)]
pub(crate) struct PatIr {
    /// NONE: no pattern.
    pub(crate) tmpl: Ix,
    /// Multislot layout (descriptor chain) and alpha tests (chain).
    pub(crate) desc: Ix,
    pub(crate) atests: Ix,
    /// Fields the join compares for equality with earlier variables (right hash).
    pub(crate) rhash: [Ix; MAX_RHASH],
    pub(crate) nrhash: u8,
    /// Multifield lengths each match records.
    pub(crate) marks: u8,
    /// A node CLIPS never shares (an ordered pattern without tests).
    pub(crate) alone: bool,
    pub(crate) path_len: u8,
    pub(crate) path_loc: [Ix; PATH_LEN],
    pub(crate) path_test: [Ix; PATH_LEN],
}

impl PatIr {
    pub(crate) const NONE: PatIr = PatIr {
        tmpl: NONE,
        desc: NONE,
        atests: NONE,
        rhash: [NONE; MAX_RHASH],
        nrhash: 0,
        marks: 0,
        alone: false,
        path_len: 0,
        path_loc: [0; PATH_LEN],
        path_test: [0; PATH_LEN],
    };
}

/// A CE over other CEs that CLIPS reads as negations (`exists` is two, `forall` one
/// around its first CE and one more around the rest).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Quant {
    Not,
    Exists,
    Forall,
}

impl Quant {
    fn of(kw: &str) -> Quant {
        match kw {
            "not" => Quant::Not,
            "exists" => Quant::Exists,
            _ => Quant::Forall,
        }
    }
    fn nots(self) -> u8 {
        match self {
            Quant::Not | Quant::Forall => 1,
            Quant::Exists => 2,
        }
    }
    fn body(self) -> GroupBody {
        match self {
            Quant::Not => GroupBody::One,
            Quant::Exists => GroupBody::Several,
            Quant::Forall => GroupBody::Forall,
        }
    }
    fn closing(self) -> &'static str {
        match self {
            Quant::Not => "')' closing not (one CE only)",
            Quant::Exists => "')' closing exists",
            Quant::Forall => "')' closing forall",
        }
    }
}

/// What a group (a join from the right over a subnetwork) reads.
#[derive(Clone, Copy, PartialEq, Eq)]
enum GroupBody {
    /// `(not CE)`: one CE.
    One,
    /// `(exists CE...)`, or the `(not (and B...))` inside a forall: CEs up to `)`.
    Several,
    /// `(forall A B...)`: A, then `(not (and B...))`.
    Forall,
    /// One negation per combination of the `or` branches of the body
    /// `Build::split_inner` names (`split_negation`).
    Split,
}

/// Where a CE sits: at top level, or inside `not`/`exists`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Ctx {
    Top,
    Not,
    Exists,
}

impl<'s> Parser<'s, '_, '_> {
    pub(super) fn defrule(&mut self, start: usize) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => self.construct_name(nt, s)?,
            _ => return Err(self.missing_name(nt, "a defrule name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
        // `load`'s "Defining defrule: r " (CLIPS prints it here, errors follow it)
        self.announce_head();
        let body_lex = self.save();
        let first_new_rule = self.cx.st.pools.nrules;
        self.rule_base = first_new_rule;
        let first_new_alpha = self.cx.st.pools.nalpha;
        self.alpha_base = first_new_alpha;
        let replaces = (0..first_new_rule).any(|r| self.cx.rule_here(r, sym));
        self.replacing = if replaces { sym } else { NONE };
        #[cfg(feature = "extras")]
        if replaces && !self.check_only {
            use crate::engine::watch;
            self.cx
                .watch_defined_again(watch::RULES | watch::ACTIVATIONS, sym);
        }
        let first_new_join = JoinId(self.cx.st.pools.njoins);
        let mut b = Build::new();
        b.name = sym;
        // The syntax stage reads the whole rule before anything is built: a rule with
        // `or` is one disjunct per combination of branches, each read with its own
        // variables and pattern numbers, so all of them are read once first (their
        // expression nodes are scratch, dropped after), then read again, each built as
        // soon as it is whole. A syntax error anywhere leaves no network behind.
        let exprs_mark = self.cx.st.pools.nexprs;
        self.read_disjunct(&body_lex, &mut b)?;
        self.take_deferred()?;
        let several = b.nor > 0;
        if several {
            while b.next_choice() {
                self.read_disjunct(&body_lex, &mut b)?;
                self.take_deferred()?;
            }
            // (what a parse-time evaluation created stays: see `eval_now`)
            let keep = self.keep.map_or(0, |k| k.nexprs);
            self.cx.st.pools.nexprs = exprs_mark.max(keep);
        }
        let mut prev_rule = NONE;
        loop {
            if several {
                self.read_disjunct(&body_lex, &mut b)?;
                self.take_deferred()?;
            }
            if prev_rule != NONE {
                self.join_marks.push_break();
            }
            let r = match self.compiler().compile_disjunct(sym, &mut b) {
                Ok(r) => r,
                Err(e) => return Err(self.compile_err(e)),
            };
            if prev_rule != NONE {
                self.cx.rules[prev_rule as usize].next_disjunct = r;
            }
            prev_rule = r;
            if !several || !b.next_choice() {
                break;
            }
        }
        if self.check_only {
            return Err(self.checked(nt));
        }
        // source text for ppdefrule, unless the host chose to drop pretty-print forms
        if self.cx.st.mode.keep_pp_forms {
            let end = self.lex.pos();
            let text = &self.lex.source()[start..end];
            if let Ok(id) = self.cx.intern(text) {
                self.cx.rules[first_new_rule as usize].text = id;
            }
        }
        // hook the new joins up to their alpha nodes first: a redefinition's removal of
        // the old rule below empties and retires an alpha node whose successor list it
        // leaves empty, and the new rule may share that node
        self.cx.hook_new_joins(first_new_join);
        // a redefinition replaces the old rule
        for r in 0..first_new_rule {
            if self.cx.rule_here(r, sym) {
                self.cx.remove_rule(r);
            }
        }
        // `load` prints "Defining defrule" before the new activations, as CLIPS does
        self.announce();
        // (CLIPS's incremental reset of the rule takes a time tag)
        #[cfg(feature = "extras")]
        {
            let next = self.cx.st.facts.next_fact_num;
            self.cx.st.timetags.rules_defined(next, 1);
        }
        // without incremental reset the new rule waits for the next `reset`
        #[cfg(feature = "extras")]
        if self.cx.st.mode.no_incremental_reset {
            return Ok(());
        }
        let res = self
            .cx
            .prime_new_rules(first_new_rule, first_new_join, first_new_alpha);
        self.map_prime_err(res, nt)
    }

    /// A priming that ran out of room, as a load error at `at`.
    fn map_prime_err(&self, r: Result<(), crate::error::EvalError>, at: Token<'s>) -> PResult<()> {
        match r {
            Ok(()) => Ok(()),
            Err(e) => {
                let c = match e.kind() {
                    crate::error::EvalErrorKind::Capacity(c) => c,
                    _ => crate::engine::cap(crate::error::Pool::Tokens, self.cx.tokens.len()),
                };
                Err(self.cap_err(at, c))
            }
        }
    }

    /// Reads one disjunct (LHS with the current or-choices, RHS) into `b`.
    fn read_disjunct(
        &mut self,
        body: &(crate::lexer::Lexer<'s>, Option<Token<'s>>),
        b: &mut Build,
    ) -> PResult<()> {
        self.restore(body.clone());
        self.nvars = 0;
        self.nlocals = 0;
        b.n = 0;
        b.cur = CE_ROOT;
        b.depth = 0;
        b.groups = 0;
        b.group_first = CE_ROOT;
        b.nor = 0;
        b.logical = CE_ROOT;
        b.in_logical = false;
        b.plain_seen = false;
        self.rule_body(b)
    }

    /// One disjunct: LHS (with the current or-choices), RHS.
    fn rule_body(&mut self, b: &mut Build) -> PResult<()> {
        self.ce_count = 0;
        #[cfg(feature = "extras")]
        {
            let src = self.lex.source();
            self.cx.st.rule_notes.reset(src);
        }
        self.complexity = 0;
        let mut salience = (0i32, NONE);
        // whether the rule has a declare or a CE before its `=>`
        let mut read_any = false;
        // (declare (salience N))
        if self.peek().tok == Tok::LParen {
            let save = self.save();
            self.next();
            if self.peek().tok == Tok::Symbol("declare") {
                self.next();
                salience = self.declare(b)?;
                read_any = true;
            } else {
                self.restore(save);
            }
        }
        loop {
            let t = self.peek();
            match t.tok {
                Tok::Symbol("=>") => {
                    self.next();
                    break;
                }
                Tok::RParen => {
                    // no `=>`: CLIPS shows the rule read, its `)` on a line of its own
                    // (after the name when there is nothing else)
                    let mut e = self.err(t, "'=>' or a conditional element");
                    e.echo_end = t.end as u32;
                    e.echo_tail = if read_any {
                        crate::error::EchoTail::OwnLine
                    } else {
                        crate::error::EchoTail::Glued
                    };
                    return Err(e);
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "'=>' or a conditional element")),
                // a `(declare ...)` after a CE is an ordinary pattern for CLIPS 6.30, whose
                // nested `(` is then a syntax error: declare comes first or not at all
                _ => {
                    self.ce(b, Ctx::Top)?;
                    read_any = true;
                }
            }
        }
        if b.n == 0 {
            // empty LHS: a test join with no tests (CLIPS shows it as `*`)
            b.ces[0] = CE_EMPTY;
            b.n = 1;
            b.cur = 0;
            b.depth = 1;
        }
        self.scope = Scope::Frame;
        self.declare_bound_vars()?;
        #[cfg(feature = "extras")]
        let (rhs_from, rhs_cands) = {
            self.cx.st.rule_notes.clear_binds();
            (self.consumed_end(), self.cx.st.rule_notes.ncands)
        };
        b.rhs = self.body_block()?;
        #[cfg(feature = "extras")]
        self.check_lhs_types()?;
        #[cfg(feature = "extras")]
        self.check_rhs_types(rhs_from, rhs_cands)?;
        b.sal = salience;
        b.nlocals = self.nlocals.min(255) as u8;
        b.complexity = self.complexity;
        Ok(())
    }

    /// An error in `(declare ...)` as CLIPS reports it: `detail` at token `at`, the rule
    /// shown up to `echo_end` (and ` )` when `at` is a `)` CLIPS read instead).
    #[cold]
    /// The `)` that ends a `declare` item, or CLIPS's error naming what was due.
    fn declare_close(&mut self, expected: &'static str) -> Result<(), crate::error::LoadError> {
        let close = self.next();
        if close.tok != Tok::RParen {
            let detail = crate::error::LoadDetail::SyntaxOf {
                part: "declare statement",
            };
            return Err(self.declare_error(close, close.end, expected, detail));
        }
        Ok(())
    }

    fn declare_error(
        &self,
        at: Token<'s>,
        echo_end: usize,
        expected: &'static str,
        detail: crate::error::LoadDetail,
    ) -> crate::error::LoadError {
        let mut e = self.err(at, expected);
        e.detail = detail;
        e.echo_end = echo_end as u32;
        if at.tok == Tok::RParen && echo_end <= at.start {
            e.echo_tail = crate::error::EchoTail::SpaceBefore;
        }
        e
    }

    /// A salience whose evaluation failed: CLIPS prints the error and `[PRNTUTIL8]`,
    /// then the rule up to the value after `ERROR:`.
    #[cold]
    fn salience_failed(
        &mut self,
        err: crate::error::EvalError,
        rule: crate::value::SymId,
        value_end: usize,
    ) -> crate::error::LoadError {
        use core::fmt::Write;
        self.cx.write_error_message(err);
        let mut b: crate::value::TextBuf<160> = crate::value::TextBuf::new();
        let _ = writeln!(
            b,
            "\n[PRNTUTIL8] This error occurred while evaluating the salience for defrule {}.",
            self.cx.sym_text(rule)
        );
        self.cx.write(crate::host::router::WERROR, b.as_str());
        let at = self.lex.token_at(value_end.saturating_sub(1));
        let mut e = self.err(at, "a salience that evaluates");
        e.detail = crate::error::LoadDetail::DefaultEvaluation;
        e.echo_end = value_end as u32;
        e
    }

    fn declare(&mut self, b: &mut Build) -> PResult<(i32, Ix)> {
        const DECLARE: crate::error::LoadDetail = crate::error::LoadDetail::SyntaxOf {
            part: "declare statement",
        };
        let mut sal = 0;
        let mut sal_expr = NONE;
        let mut seen_salience = false;
        let mut seen_item = false;
        let mut prev = self.consumed_end();
        loop {
            let t = self.next();
            match t.tok {
                // `(declare)` declares nothing: CLIPS refuses it
                Tok::RParen if seen_item => return Ok((sal, sal_expr)),
                Tok::LParen => {
                    seen_item = true;
                    let kw = self.next();
                    match kw.tok {
                        Tok::Symbol("salience") if seen_salience => {
                            return Err(self.declare_error(
                                kw,
                                kw.end,
                                "one salience declaration only",
                                crate::error::LoadDetail::Text {
                                    text: "[PRNTUTIL5] The salience declaration has already been parsed.",
                                },
                            ));
                        }
                        Tok::Symbol("salience") => {
                            seen_salience = true;
                            let vt = self.peek();
                            if vt.tok == Tok::RParen {
                                return Err(self.declare_error(
                                    vt,
                                    kw.end,
                                    "an expression (the salience value)",
                                    crate::error::LoadDetail::Text {
                                        text: "[EXPRNPSR2] Expected a constant, variable, or expression.",
                                    },
                                ));
                            }
                            // evaluated as it is read: globals by name (`[GLOBLDEF1]`
                            // when unseen), variables the prompt's (CLIPS's
                            // `[EVALUATN1]` when unbound)
                            let save = self.scope;
                            self.scope = Scope::Frame;
                            self.evaluated_now = true;
                            let e = self.parse_expr();
                            self.evaluated_now = false;
                            self.scope = save;
                            let e = e?;
                            // (a variable nothing binds is not evaluated)
                            self.take_deferred()?;
                            let value_end = self.consumed_end();
                            if !matches!(self.cx.exprs[e as usize].op, Op::Int | Op::Float) {
                                sal_expr = e;
                            }
                            // evaluated once, while the first disjunct is read (CLIPS
                            // evaluates it once per rule)
                            let v = match b.salience {
                                Some(s) => Ok(Value::Int(s.into())),
                                None => self.eval_now(e),
                            };
                            sal = match v {
                                // CLIPS keeps a C `int` of the value, then checks it
                                // (4294967297 is 1)
                                Ok(Value::Int(i)) if (-10000..=10000).contains(&(i as i32)) => {
                                    i as i32
                                }
                                Err(err) if !err.is_capacity() => {
                                    return Err(self.salience_failed(err, b.name, value_end));
                                }
                                Ok(Value::Int(_)) => {
                                    return Err(self.declare_error(
                                        vt,
                                        value_end,
                                        "a salience between -10000 and 10000",
                                        crate::error::LoadDetail::Text {
                                            text: "[PRNTUTIL9] Salience value out of range -10000 to 10000.",
                                        },
                                    ))
                                }
                                _ => {
                                    return Err(self.declare_error(
                                        vt,
                                        value_end,
                                        "an integer salience",
                                        crate::error::LoadDetail::Text {
                                            text: "[PRNTUTIL10] Salience value must be an integer value.",
                                        },
                                    ));
                                }
                            };
                            b.salience = Some(sal);
                            self.declare_close("')' after the salience")?;
                        }
                        #[cfg(feature = "modules")]
                        Tok::Symbol("auto-focus") => {
                            let vt = self.next();
                            b.auto_focus = match vt.tok {
                                Tok::Symbol("TRUE") => true,
                                Tok::Symbol("FALSE") => false,
                                _ => {
                                    return Err(self.declare_error(
                                        vt,
                                        vt.end,
                                        "TRUE or FALSE for auto-focus",
                                        crate::error::LoadDetail::SyntaxOf {
                                            part: "auto-focus statement",
                                        },
                                    ))
                                }
                            };
                            self.declare_close("')' after the auto-focus value")?;
                        }
                        #[cfg(not(feature = "modules"))]
                        Tok::Symbol("auto-focus") => {
                            return Err(self.not_implemented(kw, "auto-focus"));
                        }
                        _ => {
                            return Err(self.declare_error(
                                kw,
                                kw.end,
                                "salience or auto-focus",
                                DECLARE,
                            ))
                        }
                    }
                }
                _ => {
                    let echo_end = if t.tok == Tok::RParen { prev } else { t.end };
                    let mut e = self.declare_error(t, echo_end, "'(' or ')' in declare", DECLARE);
                    // after an item CLIPS shows the token glued to its `)`
                    if seen_item && t.tok != Tok::RParen {
                        e.echo_tail = crate::error::EchoTail::Glued;
                    }
                    return Err(e);
                }
            }
            prev = self.consumed_end();
        }
    }

    /// `(not A B)`: CLIPS reads the CEs after the first up to the not's `)` and then
    /// refuses them, showing the rule up to there.
    #[cold]
    fn not_with_more_ces(&mut self) -> crate::error::LoadError {
        let at = self.peek();
        let mut e = self.syntax_of(
            at,
            "')' closing not (one CE only)",
            "the not conditional element",
        );
        let mut depth = 1u32;
        loop {
            let t = self.next();
            match t.tok {
                Tok::LParen => depth += 1,
                Tok::RParen => {
                    depth -= 1;
                    if depth == 0 {
                        e.echo_end = t.end as u32;
                        break;
                    }
                }
                Tok::Eof | Tok::Bad => break,
                _ => {}
            }
        }
        e
    }

    /// Whether byte `at` of the source is inside a CE of the rule around it (`and`,
    /// `not`, ...), not at the rule's own level (error path only: lexes the source up
    /// to there).
    fn inside_group_ce(&self, at: usize) -> bool {
        let mut lx = Lexer::new(self.lex.source());
        let mut depth = 0u32;
        loop {
            let t = lx.next_token();
            if t.start >= at || matches!(t.tok, Tok::Eof | Tok::Bad) {
                return depth > 1;
            }
            match t.tok {
                Tok::LParen => depth += 1,
                Tok::RParen => depth = depth.saturating_sub(1),
                _ => {}
            }
        }
    }

    /// One conditional element.
    fn ce(&mut self, b: &mut Build, ctx: Ctx) -> PResult<()> {
        let r = self.nested(|p| p.ce_inner(b, ctx));
        #[cfg(feature = "extras")]
        {
            self.quant_first = false;
        }
        r
    }

    fn ce_inner(&mut self, b: &mut Build, ctx: Ctx) -> PResult<()> {
        let t = self.next();
        match t.tok {
            Tok::SfVar(fv) => {
                let arrow = self.next();
                if arrow.tok != Tok::Symbol("<-") {
                    let mut e = self.syntax_of(
                        arrow,
                        "'<-' after a fact-address variable",
                        "binding patterns",
                    );
                    // CLIPS shows the variable and the token after it on one line
                    // (inside a group CE where its next CE would go, a `)` one space
                    // after it)
                    e.start = t.start as u32;
                    e.echo_tail = crate::error::EchoTail::OwnLine;
                    if arrow.tok == Tok::RParen && self.inside_group_ce(t.start) {
                        e.echo_end = t.end as u32;
                        e.echo_tail = crate::error::EchoTail::SpaceBefore;
                    }
                    return Err(e);
                }
                if ctx != Ctx::Top || b.groups > 0 {
                    return Err(self.err(
                        t,
                        "a pattern (fact addresses cannot be bound inside not/exists)",
                    ));
                }
                if !b.in_logical {
                    b.plain_seen = true;
                }
                let lp = self.next();
                if lp.tok != Tok::LParen {
                    return Err(self.syntax_of(lp, "'(' starting a pattern", "binding patterns"));
                }
                if let Tok::Symbol(
                    "not" | "and" | "or" | "exists" | "forall" | "test" | "logical",
                ) = self.peek().tok
                {
                    // CLIPS reads the keyword and the token after it, and shows the rule
                    // up to there
                    self.next();
                    let after = self.peek();
                    let mut e = self.err(lp, "a pattern after '<-' (not a conditional element)");
                    e.echo_end = after.end as u32;
                    return Err(e);
                }
                self.pattern(b, ctx, Some((t, fv)))
            }
            Tok::LParen => {
                let h = self.peek();
                // a top-level CE outside `logical` ends the rule's logical CEs
                if b.groups == 0
                    && !b.in_logical
                    && !matches!(h.tok, Tok::Symbol("logical" | "and" | "or"))
                {
                    b.plain_seen = true;
                }
                match h.tok {
                    Tok::Symbol(kw @ ("not" | "exists" | "forall")) => {
                        self.next();
                        // variables bound inside are not seen after it
                        let saved = self.nvars;
                        // nor do the slots they stand in narrow the variables bound
                        // before it (CLIPS propagates nothing out of it)
                        let base = self.quant_base;
                        if base == 0 {
                            self.quant_base = saved;
                        }
                        #[cfg(feature = "extras")]
                        {
                            self.quant_depth = self.quant_depth.saturating_add(1);
                            self.quant_first = true;
                        }
                        let r = self.quantified(b, Quant::of(kw), h);
                        #[cfg(feature = "extras")]
                        {
                            self.quant_depth = self.quant_depth.saturating_sub(1);
                        }
                        self.quant_base = base;
                        self.nvars = saved;
                        r?;
                        if kw == "not" && self.peek().tok == Tok::LParen {
                            return Err(self.not_with_more_ces());
                        }
                        self.expect_rparen(Quant::of(kw).closing())
                    }
                    Tok::Symbol("logical") => self.logical_ce(b, ctx, h),
                    Tok::Symbol("and") => {
                        self.next();
                        let p = self.peek();
                        if p.tok == Tok::RParen {
                            return Err(self.syntax_of(
                                p,
                                "a conditional element inside and",
                                "the and conditional element",
                            ));
                        }
                        loop {
                            let p = self.peek();
                            match p.tok {
                                Tok::RParen => {
                                    self.next();
                                    return Ok(());
                                }
                                Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                                _ => self.ce(b, ctx)?,
                            }
                        }
                    }
                    Tok::Symbol("or") => {
                        self.next();
                        let p = self.peek();
                        if p.tok == Tok::RParen {
                            return Err(self.syntax_of(
                                p,
                                "a pattern or other CE inside or",
                                "the or conditional element",
                            ));
                        }
                        // (inside not/exists/forall the enclosing negation reads the
                        // body once per choice: `split_negation`)
                        let k = b.nor;
                        if k >= MAX_ORS {
                            return Err(self.err(h, "fewer or CEs in one rule"));
                        }
                        b.nor += 1;
                        let mut branch = 0u8;
                        let close = loop {
                            let p = self.peek();
                            match p.tok {
                                Tok::RParen => {
                                    self.next();
                                    break p;
                                }
                                Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                                _ => {
                                    if branch == b.choice[k] {
                                        self.ce(b, ctx)?;
                                    } else {
                                        // (a pattern bound to a fact address: `?f <- (..)`)
                                        if let Tok::SfVar(_) = p.tok {
                                            self.next();
                                            if self.peek().tok == Tok::Symbol("<-") {
                                                self.next();
                                            }
                                        }
                                        self.skip_balanced()?;
                                        // CLIPS numbers the CEs of every branch
                                        self.ce_count = self.ce_count.saturating_add(1);
                                    }
                                    branch += 1;
                                }
                            }
                        };
                        if branch == 0 {
                            return Err(self.err(close, "a pattern or CE inside or"));
                        }
                        b.counts[k] = branch;
                        Ok(())
                    }
                    Tok::Symbol("test") => {
                        self.next();
                        self.ce_count = self.ce_count.saturating_add(1);
                        self.scope = Scope::Lhs;
                        let p = self.peek();
                        if p.tok == Tok::RParen {
                            // `(test)`: CLIPS wanted a function call and shows `(test )`
                            let mut e = self.syntax_of(p, "an expression", "function calls");
                            e.echo_end = h.end as u32;
                            e.echo_tail = crate::error::EchoTail::SpaceBefore;
                            return Err(e);
                        }
                        #[cfg(feature = "extras")]
                        let from = self.offset();
                        let e = self.parse_expr()?;
                        #[cfg(feature = "extras")]
                        self.note_lhs_check(from, NONE, 0);
                        let close = self.peek();
                        if close.tok != Tok::RParen && close.tok != Tok::Eof {
                            // a second argument: CLIPS shows the rule up to its first
                            // token, glued to the expression
                            let mut e = self.syntax_of(
                                close,
                                "')' closing test (it takes one expression)",
                                "test conditional element",
                            );
                            e.echo_tail = crate::error::EchoTail::Glued;
                            return Err(e);
                        }
                        self.expect_rparen("')' closing test")?;
                        self.add_complexity(e);
                        self.attach_test_ce(b, e, h)
                    }
                    _ => self.pattern(b, ctx, None),
                }
            }
            _ => {
                let mut e = self.err(t, "a conditional element");
                // CLIPS shows the rule read, the token on a line of its own (inside a
                // `not`, `and`, ...: where the group's next CE would go)
                e.echo_end = t.end as u32;
                if !self.inside_group_ce(t.start) {
                    e.echo_tail = crate::error::EchoTail::OwnLine;
                }
                Err(e)
            }
        }
    }

    /// `(logical CE...)` after its `(`: the rule's first CEs, whose partial match
    /// gives the facts its actions assert their logical support (`crate::logical`).
    #[cfg(feature = "logical")]
    fn logical_ce(&mut self, b: &mut Build, ctx: Ctx, h: Token<'s>) -> PResult<()> {
        if ctx != Ctx::Top || b.groups > 0 || b.in_logical {
            return Err(self.err(
                h,
                "a pattern (the logical CE cannot be used within a not/exists/forall CE)",
            ));
        }
        if b.plain_seen {
            // CLIPS checks the order once the rule is read, and shows it whole
            let gap = b.logical != CE_ROOT;
            let mut e = self.err(
                h,
                if gap {
                    "no logical CE here (gaps may not exist between logical CEs)"
                } else {
                    "no logical CE here (logical CEs must be placed first in a rule)"
                },
            );
            e.detail = crate::error::LoadDetail::LogicalOrder { gap };
            if self.deferred.is_none() {
                self.deferred = Some(e);
            }
        }
        self.next();
        b.in_logical = true;
        let first = b.n;
        let r = loop {
            let p = self.peek();
            match p.tok {
                Tok::RParen => {
                    self.next();
                    break Ok(());
                }
                Tok::Eof | Tok::Bad => break Err(self.err(p, "')'")),
                _ => {
                    if let Err(e) = self.ce(b, ctx) {
                        break Err(e);
                    }
                }
            }
        };
        b.in_logical = false;
        r?;
        if b.n == first && b.logical == CE_ROOT {
            return Err(self.err(h, "a conditional element inside logical"));
        }
        b.logical = b.cur;
        Ok(())
    }

    /// Without truth maintenance (feature `logical`), refused.
    #[cfg(not(feature = "logical"))]
    fn logical_ce(&mut self, _b: &mut Build, _ctx: Ctx, h: Token<'s>) -> PResult<()> {
        Err(self.not_implemented(h, "the logical conditional element"))
    }

    /// Whether the next CE is one pattern closing the enclosing CE.
    fn one_pattern_follows(&mut self) -> PResult<bool> {
        let save = self.save();
        let r =
            self.pattern_starts() && self.skip_balanced().is_ok() && self.peek().tok == Tok::RParen;
        self.restore(save);
        Ok(r)
    }

    /// The keyword of the next CE if it is a `not`, `exists` or `forall` closing the
    /// enclosing CE.
    fn lone_quantifier_follows(&mut self) -> Option<Quant> {
        let save = self.save();
        let mut r = None;
        if self.next().tok == Tok::LParen {
            if let Tok::Symbol(kw @ ("not" | "exists" | "forall")) = self.next().tok {
                let mut depth = 1u32;
                loop {
                    match self.next().tok {
                        Tok::LParen => depth += 1,
                        Tok::RParen => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        Tok::Eof | Tok::Bad => break,
                        _ => {}
                    }
                }
                if depth == 0 && self.peek().tok == Tok::RParen {
                    r = Some(Quant::of(kw));
                }
            }
        }
        self.restore(save);
        r
    }

    /// Whether a pattern CE (not another CE keyword) starts here.
    fn pattern_starts(&mut self) -> bool {
        let save = self.save();
        let r = match self.next().tok {
            Tok::SfVar(_) => true,
            Tok::LParen => !matches!(
                self.next().tok,
                Tok::Symbol("not" | "and" | "or" | "exists" | "forall" | "test" | "logical")
            ),
            _ => false,
        };
        self.restore(save);
        r
    }

    /// CEs up to the `)` closing the enclosing CE (not consumed).
    fn ces_to_rparen(&mut self, b: &mut Build) -> PResult<()> {
        loop {
            let p = self.peek();
            match p.tok {
                Tok::RParen => return Ok(()),
                Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                _ => self.ce(b, Ctx::Top)?,
            }
        }
    }

    /// `not`, `exists` or `forall` after its keyword, under `nots` enclosing
    /// negations already folded into it. CLIPS reads `(exists X...)` as
    /// `(not (not (and X...)))` and `(forall A B...)` as `(not (and A (not (and
    /// B...))))`, and cancels nested negations in pairs: a lone `not`/`exists`/`forall`
    /// inside one is folded into it, and what remains is a not join (odd count) or an
    /// exists join (even), on one pattern or on a subnetwork.
    fn quantified(&mut self, b: &mut Build, q: Quant, at: Token<'s>) -> PResult<()> {
        self.quantified_under(b, q.nots(), q.body(), at)
    }

    /// A quantified CE's body under `nots` negations (its own included).
    fn quantified_under(
        &mut self,
        b: &mut Build,
        nots: u8,
        body: GroupBody,
        at: Token<'s>,
    ) -> PResult<()> {
        if body != GroupBody::Forall {
            let p = self.peek();
            if p.tok == Tok::RParen {
                let part = match at.tok {
                    Tok::Symbol("exists") => "the exists conditional element",
                    _ => "the not conditional element",
                };
                return Err(self.syntax_of(p, "a conditional element inside not/exists", part));
            }
            if let Some(inner) = self.lone_quantifier_follows() {
                self.next();
                let h = self.next();
                self.quantified_under(b, nots.saturating_add(inner.nots()), inner.body(), h)?;
                return self.expect_rparen(inner.closing());
            }
            if self.one_pattern_follows()? {
                // one pattern: a not/exists join on its alpha node
                return self.ce(b, if nots % 2 == 1 { Ctx::Not } else { Ctx::Exists });
            }
        }
        if self.free_or_follows(body)? {
            return self.split_negation(b, nots, body, at);
        }
        self.group(b, body, nots % 2 == 1, at)
    }

    /// A quantified body holding an `or` outside any deeper negation. CLIPS moves
    /// the `or` out of the `and`s around it and turns the innermost negation over it
    /// into one negation per combination of branches, in the order of `or`
    /// disjuncts: `(not (or A B))` is `(not A) (not B)`. More negations stay around
    /// those as one group: `(exists (or A B))`, CLIPS's `(not (not (or A B)))`, is
    /// `(not (and (not A) (not B)))`.
    fn split_negation(
        &mut self,
        b: &mut Build,
        nots: u8,
        body: GroupBody,
        at: Token<'s>,
    ) -> PResult<()> {
        if nots > 1 {
            b.split_inner = body;
            // (a lone branch folds into the outer negations as `(not (not A))` does)
            b.split_branch = true;
            return self.group(b, GroupBody::Split, (nots - 1) % 2 == 1, at);
        }
        self.negations_per_choice(b, body, at)
    }

    /// The body read once per combination of its `or` branches, each a negation.
    fn negations_per_choice(
        &mut self,
        b: &mut Build,
        body: GroupBody,
        at: Token<'s>,
    ) -> PResult<()> {
        let base = b.nor;
        let start = self.save();
        loop {
            self.restore(start.clone());
            // variables one negation binds are not seen by the next
            let saved = self.nvars;
            b.split_branch = true;
            let r = self.group(b, body, true, at);
            self.nvars = saved;
            r?;
            if !b.next_choice_from(base) {
                break;
            }
            b.nor = base;
        }
        b.nor = base;
        Ok(())
    }

    /// Whether the quantified body ahead holds an `or` CE outside any deeper
    /// not/exists/forall (for a forall, in its first CE: the rest is a negation of
    /// its own). Looks ahead only.
    fn free_or_follows(&mut self, body: GroupBody) -> PResult<bool> {
        let save = self.save();
        let r = self.scan_free_or(body == GroupBody::Forall);
        self.restore(save);
        r
    }

    fn scan_free_or(&mut self, first_only: bool) -> PResult<bool> {
        loop {
            let save = self.save();
            let t = self.next();
            match t.tok {
                Tok::RParen | Tok::Eof | Tok::Bad => return Ok(false),
                Tok::SfVar(_) => {
                    if self.peek().tok == Tok::Symbol("<-") {
                        self.next();
                    }
                    self.skip_balanced()?;
                }
                Tok::LParen => match self.next().tok {
                    Tok::Symbol("or") => return Ok(true),
                    Tok::Symbol("and" | "logical") => {
                        if self.nested(|p| p.scan_free_or(false))? {
                            return Ok(true);
                        }
                    }
                    _ => {
                        self.restore(save);
                        self.skip_balanced()?;
                    }
                },
                _ => return Ok(false),
            }
            if first_only {
                return Ok(false);
            }
        }
    }

    /// The CEs after the first of `(forall A B...)`: the inner `(not (and B...))`.
    fn forall_rest(&mut self, b: &mut Build, at: Token<'s>) -> PResult<()> {
        if self.peek().tok == Tok::RParen {
            return Err(self.err(at, "a forall with two conditional elements or more"));
        }
        self.quantified_under(b, 1, GroupBody::Several, at)
    }

    /// `not`/`exists` over several CEs (or a nested CE), or a whole `forall`: the CEs
    /// form a subnetwork starting from the current chain, and a join takes its end
    /// from the right. The group is one pattern slot (`*`) of the enclosing chain.
    /// As in CLIPS, a subnetwork of one pattern (and tests on it) is a plain not/exists
    /// join instead, and one of tests only is a test of the enclosing chain.
    fn group(
        &mut self,
        b: &mut Build,
        body: GroupBody,
        negated: bool,
        at: Token<'s>,
    ) -> PResult<()> {
        let (outer, d, gf) = (b.cur, b.depth, b.group_first);
        let split_branch = core::mem::replace(&mut b.split_branch, false);
        let first = b.n;
        b.groups += 1;
        b.group_first = first as u8;
        let r = match body {
            // exactly one CE: (and ...), (not ...), (exists ...)
            GroupBody::One => self.ce(b, Ctx::Top),
            GroupBody::Several => self.ces_to_rparen(b),
            GroupBody::Split => {
                let inner = b.split_inner;
                self.negations_per_choice(b, inner, at)
            }
            GroupBody::Forall => {
                if self.peek().tok == Tok::RParen {
                    Err(self.err(at, "a forall with two conditional elements or more"))
                } else {
                    self.ce(b, Ctx::Top).and_then(|()| self.forall_rest(b, at))
                }
            }
        };
        b.groups -= 1;
        b.group_first = gf;
        r?;
        if b.n == first {
            return Err(self.err(at, "a conditional element inside not/exists"));
        }
        if b.n == first + 1 && b.ces[first].parent == outer && b.ces[first].right == CE_ROOT {
            let only = b.ces[first];
            if only.kind == JoinKind::Positive && only.pat.tmpl != NONE {
                // one pattern and tests on it: a not/exists join on its alpha node
                b.ces[first].kind = if negated {
                    JoinKind::Negative
                } else {
                    JoinKind::Exists
                };
                return Ok(());
            }
            if split_branch
                && matches!(only.kind, JoinKind::Negative | JoinKind::Exists)
                && only.pat.tmpl != NONE
                && only.post == NONE
            {
                // a branch `(not A)` of `(not (or ...))`: CLIPS folds the two
                // negations as it folds `(not (not A))`
                let inner_negated = only.kind == JoinKind::Negative;
                b.ces[first].kind = if negated != inner_negated {
                    JoinKind::Negative
                } else {
                    JoinKind::Exists
                };
                return Ok(());
            }
            if only.kind == JoinKind::Test && only.pat.tmpl == NONE && only.jtests != NONE {
                // tests only: `(not (test X))` is `(test (not X))` of the enclosing chain
                b.n = first;
                b.cur = outer;
                b.depth = d;
                let mut e = only.jtests;
                if self.cx.exprs[e as usize].next != NONE {
                    let and = cap!(self, self.cx.push_expr(Expr::new(Op::And, 0, 0)))?;
                    self.cx.exprs[and as usize].first = e;
                    e = and;
                }
                if negated {
                    let not = cap!(self, self.cx.push_expr(Expr::new(Op::Not, 0, 0)))?;
                    self.cx.exprs[not as usize].first = e;
                    e = not;
                }
                return self.attach_test_ce(b, e, at);
            }
        }
        let first_of_enclosing = b.groups > 0 && first == gf as usize;
        if !negated && (first_of_enclosing || self.first_in_chain_is_group(b, outer)) {
            // CLIPS makes `(not (not (and ...)))` one exists join only when exactly
            // these two groups begin at its first CE: not when that CE begins a deeper
            // group too, nor when the group is the first CE of an enclosing one.
            // Otherwise two negated groups, the inner one alone in the outer one.
            if b.n + 1 >= MAX_PATTERNS {
                return Err(self.err(at, "fewer conditional elements"));
            }
            b.ces[b.n] = Ce {
                kind: JoinKind::Negative,
                depth: d,
                parent: outer,
                right: b.cur,
                ..CE_EMPTY
            };
            b.cur = b.n as u8;
            b.n += 1;
            return self.group_node(b, true, d, outer, at);
        }
        self.group_node(b, negated, d, outer, at)
    }

    /// Whether the chain ending at `b.cur` starts (after `outer`) with a group.
    fn first_in_chain_is_group(&self, b: &Build, outer: u8) -> bool {
        let mut c = b.cur;
        while c != CE_ROOT && b.ces[c as usize].parent != outer {
            c = b.ces[c as usize].parent;
        }
        c != CE_ROOT && {
            let f = &b.ces[c as usize];
            f.pat.tmpl == NONE && f.right != CE_ROOT
        }
    }

    /// The join from the right closing a group whose subnetwork ends at `b.cur`.
    fn group_node(
        &mut self,
        b: &mut Build,
        negated: bool,
        d: u8,
        outer: u8,
        at: Token<'s>,
    ) -> PResult<()> {
        if b.n >= MAX_PATTERNS {
            return Err(self.err(at, "fewer conditional elements"));
        }
        b.ces[b.n] = Ce {
            kind: if negated {
                JoinKind::Negative
            } else {
                JoinKind::Exists
            },
            depth: d,
            parent: outer,
            right: b.cur,
            ..CE_EMPTY
        };
        b.cur = b.n as u8;
        b.n += 1;
        b.depth = d + 1;
        Ok(())
    }

    fn attach_test_ce(&mut self, b: &mut Build, e: Ix, at: Token<'s>) -> PResult<()> {
        if b.cur == CE_ROOT || (b.groups > 0 && b.n == b.group_first as usize) {
            // a leading test: a test join of its own (a pattern slot shown as `*`),
            // which CLIPS counts as a pattern in the rule's complexity
            self.complexity = self.complexity.saturating_add(1);
            if b.n >= MAX_PATTERNS || b.depth as usize >= MAX_PATTERNS {
                return Err(self.err(at, "fewer conditional elements"));
            }
            let i = b.n;
            b.ces[i] = Ce {
                parent: b.cur,
                depth: b.depth,
                ..CE_EMPTY
            };
            let ce = &mut b.ces[i];
            Self::chain_push(self, &mut ce.jtests, &mut ce.jlast, e);
            b.n += 1;
            b.cur = i as u8;
            b.depth += 1;
            return Ok(());
        }
        let last = b.cur as usize;
        let ce = &mut b.ces[last];
        match ce.kind {
            JoinKind::Negative | JoinKind::Exists => {
                let (mut h, mut l) = (ce.post, ce.plast);
                Self::chain_push(self, &mut h, &mut l, e);
                b.ces[last].post = h;
                b.ces[last].plast = l;
            }
            _ => {
                let (mut h, mut l) = (ce.jtests, ce.jlast);
                Self::chain_push(self, &mut h, &mut l, e);
                b.ces[last].jtests = h;
                b.ces[last].jlast = l;
            }
        }
        Ok(())
    }

    fn chain_push(&mut self, head: &mut Ix, last: &mut Ix, e: Ix) {
        if *head == NONE {
            *head = e;
        } else {
            self.cx.exprs[*last as usize].next = e;
        }
        *last = e;
    }

    /// A pattern CE after its `(`.
    fn pattern(
        &mut self,
        b: &mut Build,
        ctx: Ctx,
        factvar: Option<(Token<'s>, &'s str)>,
    ) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) if super::has_module_sep(s) => return Err(self.module_specifier(nt)),
            Tok::Symbol(s)
                if !matches!(
                    s,
                    "test" | "not" | "and" | "or" | "exists" | "forall" | "logical" | "=" | ":"
                ) && crate::value::instance_name_body(s).is_none() =>
            {
                (self.current_module(), s)
            }
            // `=` and `:` are operators, never a relation name (CLIPS's own wording)
            Tok::Symbol("=" | ":") => {
                return Err(self.syntax_of(
                    nt,
                    "a template or relation name",
                    "the field field of a pattern",
                ))
            }
            Tok::Eof | Tok::Bad => return Err(self.err(nt, "a template or relation name")),
            // a number, string, instance name, variable, wildcard, `(`, `)`, `~`, `&`, `|`
            _ => {
                return Err(self.syntax_of(
                    nt,
                    "a template or relation name",
                    "the first field of a pattern",
                ))
            }
        };
        let (module, name) = name;
        if b.n >= MAX_PATTERNS || b.depth as usize >= MAX_PATTERNS {
            return Err(self.err(nt, "fewer conditional elements"));
        }
        let p = b.depth;
        let sym = cap!(self, self.cx.intern(name))?;
        #[cfg(feature = "modules")]
        if self.template_in(module, sym).is_none() {
            self.implied_conflict(nt, module, sym)?;
        }
        let tmpl = match self.template_in(module, sym) {
            Some(t) => t,
            None if self.peek().tok == Tok::LParen => {
                // CLIPS reads it as an ordered pattern and stops at the `(`: the
                // implied template it made for the name stays
                if self.cx.implied_template(sym).is_ok() {
                    self.note_implied();
                }
                let mut e = self.err(
                    nt,
                    "a deftemplate name (no such template for a slot pattern)",
                );
                e.echo_end = self.peek().end as u32;
                return Err(e);
            }
            None => {
                let t = cap!(self, self.cx.implied_template(sym))?;
                self.note_implied();
                t
            }
        };
        self.pat_tmpl[p as usize] = tmpl;
        self.ce_count = self.ce_count.saturating_add(1);
        // the comparison of the relation or template name
        self.complexity = self.complexity.saturating_add(1);
        if let Some((ft, fv)) = factvar {
            // CLIPS: a fact-address variable an earlier CE bound (ANALYSIS1/2/3)
            if let Some(VarEntry {
                kind: VarKind::Pat { loc: l, .. },
                multi,
                ..
            }) = self.find_var(fv)
            {
                let mut e = self.err(ft, "a fact-address variable not bound before");
                e.detail = if multi {
                    crate::error::LoadDetail::MixedVariable
                } else {
                    crate::error::LoadDetail::AddressBound {
                        ce: self.ce_count,
                        earlier_field: l != loc::FACT,
                    }
                };
                return Err(e);
            }
            self.add_var(
                ft,
                fv,
                VarKind::Pat {
                    pat: p,
                    loc: loc::FACT,
                    desc: NONE,
                },
                false,
            )?;
        }
        self.scope = Scope::Lhs;
        let mut pb = PatBuild {
            desc: NONE,
            dlast: NONE,
            atests: NONE,
            alast: NONE,
            jtests: NONE,
            jlast: NONE,
            marks: 0,
            rhash: [NONE; MAX_RHASH],
            nrhash: 0,
            fields: [(0, NONE, false); MAX_FIELDS],
            nfields: 0,
            aliases: [(0, 0, 0, NONE); 8],
            naliases: 0,
        };
        if self.cx.templates[tmpl as usize].implied {
            self.lhs_slot = None;
            self.multislot_fields(&mut pb, p, 0, nt)?;
        } else {
            // the slots given so far
            let mut given = [0u64; 4];
            loop {
                let t = self.next();
                match t.tok {
                    Tok::RParen => break,
                    Tok::LParen => {
                        let st = self.next();
                        if !matches!(st.tok, Tok::Symbol(_)) {
                            return Err(self.syntax_of(st, "a slot name", "deftemplate patterns"));
                        }
                        let slot = self.slot_of(tmpl, st)?;
                        // (a template has at most 255 slots)
                        let (word, bit) = ((slot as usize / 64) & 3, 1u64 << (slot % 64));
                        if given[word] & bit != 0 {
                            return Err(self.slot_twice(st, "a slot not given twice"));
                        }
                        given[word] |= bit;
                        let def = self.cx.slot_def(tmpl, slot);
                        // literals in this slot's constraints must fit the slot
                        self.lhs_slot = Some(def);
                        if def.multi {
                            self.multislot_fields(&mut pb, p, slot as u8, st)?;
                        } else {
                            let empty = self.peek();
                            if empty.tok == Tok::RParen {
                                // `(a)`: CLIPS wanted a field and shows `(a )`
                                let mut e = self.err(empty, "a field for the single-field slot");
                                e.echo_end = st.end as u32;
                                e.echo_tail = crate::error::EchoTail::SpaceBefore;
                                return Err(e);
                            }
                            if empty.tok == Tok::MfWild {
                                // `(a $?)`: CLIPS reads a lone `$?` in a single-field
                                // slot as `?` (anything after it, `&` too, is refused)
                                self.next();
                                let close = self.peek();
                                if !matches!(close.tok, Tok::RParen | Tok::Eof | Tok::Bad) {
                                    // shown one space after the `$?`: `(v $? &`
                                    let mut e = self.syntax_of(
                                        close,
                                        "')' closing the slot after a lone '$?'",
                                        "deftemplate patterns",
                                    );
                                    e.echo_end = close.end as u32;
                                    e.echo_tail = crate::error::EchoTail::Spaced;
                                    return Err(e);
                                }
                                pb.record(loc::new(slot as u8, loc::SINGLE), NONE, false);
                                self.expect_rparen("')' closing the slot after a lone '$?'")?;
                                continue;
                            }
                            let (multi, test) =
                                self.field(p, loc::new(slot as u8, loc::SINGLE), NONE)?;
                            let close = self.peek();
                            if multi && close.tok == Tok::RParen {
                                // `(a $?y)`: CLIPS read the slot whole, then refused it
                                let mut e = self
                                    .err(st, "a single-field constraint for a single-field slot");
                                e.detail = crate::error::LoadDetail::SingleSlot { slot: def.name };
                                e.echo_end = close.end as u32;
                                return Err(e);
                            }
                            if multi && !matches!(close.tok, Tok::RParen | Tok::Eof | Tok::Bad) {
                                // `(a $?x b)`: CLIPS refuses the multifield variable
                                // once it has read the token after it, glued to it
                                let mut e = self.err(
                                    close,
                                    "a single-field constraint for a single-field slot",
                                );
                                e.detail = crate::error::LoadDetail::SingleSlot { slot: def.name };
                                e.echo_end = close.end as u32;
                                e.echo_tail = crate::error::EchoTail::Glued;
                                return Err(e);
                            }
                            if !matches!(close.tok, Tok::RParen | Tok::Eof | Tok::Bad) {
                                // a second field: CLIPS shows the rule up to it
                                return Err(self.syntax_of(
                                    close,
                                    "')' closing the slot (one field in a single-field slot)",
                                    "deftemplate patterns",
                                ));
                            }
                            if multi {
                                return Err(self
                                    .err(st, "a single-field constraint for a single-field slot"));
                            }
                            let at = match test {
                                Some(e) => {
                                    self.classify(&mut pb, p, e, loc::new(slot as u8, loc::SINGLE))?
                                }
                                None => NONE,
                            };
                            pb.record(loc::new(slot as u8, loc::SINGLE), at, false);
                            self.expect_rparen(
                                "')' closing the slot (one field in a single-field slot)",
                            )?;
                        }
                    }
                    _ => {
                        return Err(self.syntax_of(
                            t,
                            "'(' and a slot name, or ')'",
                            "deftemplate patterns",
                        ))
                    }
                }
            }
        }
        self.lhs_slot = None;
        // the pattern's form; `compile::alpha` shares an identical node or makes one
        let mut compiler = self.compiler();
        compiler.right_hash(&mut pb, p);
        let pat = compiler.pattern_form(tmpl, &pb);
        let kind = match ctx {
            Ctx::Top => JoinKind::Positive,
            Ctx::Not => JoinKind::Negative,
            Ctx::Exists => JoinKind::Exists,
        };
        b.ces[b.n] = Ce {
            kind,
            pat,
            alpha: NONE,
            at: nt.start as u32,
            jtests: pb.jtests,
            jlast: pb.jlast,
            post: NONE,
            plast: NONE,
            depth: b.depth,
            parent: b.cur,
            right: CE_ROOT,
        };
        b.cur = b.n as u8;
        b.n += 1;
        b.depth += 1;
        Ok(())
    }

    /// Elements of a multislot (or of an ordered fact) until `)`.
    fn multislot_fields(
        &mut self,
        pb: &mut PatBuild,
        p: u8,
        slot: u8,
        at: Token<'s>,
    ) -> PResult<()> {
        let ps = cap!(
            self,
            self.cx
                .push_expr(Expr::new(Op::PatSlot, pb.marks, slot as Ix))
        )?;
        let mut i = 0u8;
        let mut multis = 0u8;
        // whether an element has a test of the alpha node's own
        let mut tested = false;
        loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => {
                    self.next();
                    break;
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                _ => {
                    if i == loc::SINGLE - 1 {
                        return Err(self.err(t, "fewer fields in one slot"));
                    }
                    if self.lhs_slot.is_none() {
                        self.lhs_field = i + 1;
                    }
                    let (multi, test) = self.field(p, loc::new(slot, i), ps)?;
                    self.lhs_field = 0;
                    let el = cap!(
                        self,
                        self.cx
                            .push_expr(Expr::new(Op::PatElem, u8::from(multi), i as Ix))
                    )?;
                    self.cx.append_child(ps, el);
                    let at = match test {
                        Some(e) => self.classify(pb, p, e, loc::new(slot, i))?,
                        None => NONE,
                    };
                    pb.record(loc::new(slot, i), at, multi);
                    tested |= at != NONE;
                    multis += u8::from(multi);
                    i += 1;
                }
            }
        }
        if i == 0 {
            // CLIPS tests an empty multislot `(l)` for zero length in a node of its own
            pb.record(loc::new(slot, ZERO_LEN), NONE, false);
        } else if multis == 0 {
            // a slot's fields, all single, must be as many as its cardinality allows
            // (CLIPS lets an empty slot and any with a multifield pass)
            if let Some(def) = self.lhs_slot {
                if def.multi && !self.count_fits(&def, i64::from(i), false) {
                    let mut e = self.err(at, expected(crate::error::Restriction::Cardinality));
                    e.detail = crate::error::LoadDetail::PatternConstraint {
                        ce: self.ce_count,
                        what: crate::error::Restriction::Cardinality,
                        slot: def.name,
                        range: def.range,
                    };
                    return Err(e);
                }
            }
        }
        if multis >= 2 {
            pb.marks += multis - 1;
            if pb.marks as usize > MAX_MARKS {
                return Err(self.err(at, "at most 5 multifield variables in one pattern"));
            }
        }
        if i == 1 && multis == 1 && !tested {
            // one multifield and no test of the node's own (`(l $?x)`, `(l $?)`) matches
            // every value, as a slot the pattern leaves out: CLIPS makes no node for it
            // (`RemoveUnneededSlots`), so the pattern shares its node and joins with
            // patterns that do not name the slot. `$?x` is read through its own
            // descriptor `ps`, which the node does not need.
            return Ok(());
        }
        if pb.desc == NONE {
            pb.desc = ps;
        } else {
            // the alpha node lays out at most 8 (`rete::alpha::MAX_LAYOUTS`)
            let mut n = 0;
            let mut d = pb.desc;
            while d != NONE {
                n += 1;
                d = self.cx.exprs[d as usize].next;
            }
            if n >= crate::rete::alpha::MAX_LAYOUTS {
                return Err(self.err(at, "at most 8 multislots with constraints in one pattern"));
            }
            self.cx.exprs[pb.dlast as usize].next = ps;
        }
        pb.dlast = ps;
        Ok(())
    }

    /// Puts a field test in the alpha node (if it needs only this pattern) or the join;
    /// a `&` chain goes conjunct by conjunct, as CLIPS splits it. A variable bound in an
    /// earlier pattern that this pattern equates with one of its fields (`?x&...`
    /// leading a field) is read from that field by the rest of the pattern, so
    /// `?x&:(> ?x 1)` is tested in the alpha node and only `?x`'s equality in the join.
    /// Returns the alpha node's part of the test, else NONE.
    /// `l`: the field (locator) whose constraint `e` is.
    fn classify(&mut self, pb: &mut PatBuild, p: u8, e: Ix, l: Ix) -> PResult<Ix> {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::And {
            let t = self.classify_one(pb, p, e, false);
            if t == NONE {
                return Ok(NONE);
            }
            let t = self.name_field(t, l)?;
            self.push_alpha_test(pb, t);
            return Ok(t);
        }
        // the conjuncts, detached; the alpha ones regrouped under `e`
        let (mut alpha, mut alast, mut n) = (NONE, NONE, 0);
        let mut c = x.first;
        while c != NONE {
            let next = self.cx.exprs[c as usize].next;
            self.cx.exprs[c as usize].next = NONE;
            if self.classify_one(pb, p, c, false) != NONE {
                Self::chain_push(self, &mut alpha, &mut alast, c);
                n += 1;
            }
            c = next;
        }
        Ok(match n {
            0 => NONE,
            1 => {
                let t = self.name_field(alpha, l)?;
                self.push_alpha_test(pb, t);
                t
            }
            _ => {
                self.cx.exprs[e as usize].first = alpha;
                let t = self.name_field(e, l)?;
                self.push_alpha_test(pb, t);
                t
            }
        })
    }

    /// Alpha test `t` of field `l`, naming that field if `[FACTMCH1]` would not find it:
    /// CLIPS reports a test that errors at the slot (ordered fact: the field) holding
    /// its constraint, the engine at the first field the test reads
    /// (`Core::failed_field`). A test that reads another field first, or none, gets an
    /// `And` root that names `l` (`expr::NAMES_FIELD`): its own (an `&` chain's) or a
    /// new one above it (a full expression pool is the rule's error, as for any node).
    fn name_field(&mut self, t: Ix, l: Ix) -> PResult<Ix> {
        // a template's slot is named whichever of its elements the test reads
        let elem_too = self.lhs_slot.is_none();
        match self.cx.failed_field(t) {
            Some((s, el)) if s == loc::slot(l) && (!elem_too || el == loc::elem(l)) => {
                return Ok(t);
            }
            _ => {}
        }
        let x = self.cx.exprs[t as usize];
        if x.op == Op::And && x.aux == 0 {
            self.cx.exprs[t as usize].aux = crate::expr::NAMES_FIELD;
            self.cx.exprs[t as usize].data = l;
            return Ok(t);
        }
        let root = Expr {
            op: Op::And,
            aux: crate::expr::NAMES_FIELD,
            data: l,
            first: t,
            next: NONE,
        };
        cap!(self, self.cx.push_expr(root))
    }

    /// One conjunct of a field's test: aliases noted and applied (see `classify`), then
    /// to the join or (returned) to the alpha side, where `push` adds it to the tests.
    fn classify_one(&mut self, pb: &mut PatBuild, p: u8, e: Ix, push: bool) -> Ix {
        if !self.note_alias(pb, p, e) {
            self.apply_aliases(pb, p, e);
        }
        if self.refs_earlier(e, p) {
            let (mut h, mut l) = (pb.jtests, pb.jlast);
            Self::chain_push(self, &mut h, &mut l, e);
            pb.jtests = h;
            pb.jlast = l;
            return NONE;
        }
        self.retarget(e, p);
        if push {
            self.push_alpha_test(pb, e);
        }
        e
    }

    fn push_alpha_test(&mut self, pb: &mut PatBuild, e: Ix) {
        let (mut h, mut l) = (pb.atests, pb.alast);
        Self::chain_push(self, &mut h, &mut l, e);
        pb.atests = h;
        pb.alast = l;
    }

    /// Notes `e` as an alias if it is `this field = ?x` with `?x` bound earlier and not
    /// aliased yet in this pattern (the first such field reads it; later ones compare
    /// with that field).
    fn note_alias(&mut self, pb: &mut PatBuild, p: u8, e: Ix) -> bool {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::Eq2 {
            return false;
        }
        let this = self.cx.exprs[x.first as usize];
        let other = self.cx.exprs[this.next as usize];
        if this.op != Op::PatVar
            || this.aux != p
            || other.op != Op::PatVar
            || other.aux == p
            || other.aux == THIS_PATTERN
            || other.data == loc::FACT
            || pb.aliases[..pb.naliases]
                .iter()
                .any(|a| (a.0, a.1) == (other.aux, other.data))
            || pb.naliases == pb.aliases.len()
        {
            return false;
        }
        pb.aliases[pb.naliases] = (other.aux, other.data, this.data, this.first);
        pb.naliases += 1;
        true
    }

    /// Rewrites references in `e` to aliased variables (`note_alias`) into reads of
    /// this pattern's field.
    fn apply_aliases(&mut self, pb: &PatBuild, p: u8, e: Ix) {
        if pb.naliases == 0 {
            return;
        }
        let x = self.cx.exprs[e as usize];
        if x.op == Op::PatVar {
            if let Some(a) = pb.aliases[..pb.naliases]
                .iter()
                .find(|a| (a.0, a.1) == (x.aux, x.data))
            {
                let n = &mut self.cx.exprs[e as usize];
                n.aux = p;
                n.data = a.2;
                n.first = a.3;
            }
            return;
        }
        let mut c = if matches!(x.op, Op::Int | Op::Float) {
            NONE
        } else {
            x.first
        };
        while c != NONE {
            self.apply_aliases(pb, p, c);
            c = self.cx.exprs[c as usize].next;
        }
    }

    fn refs_earlier(&self, e: Ix, p: u8) -> bool {
        let x = self.cx.exprs[e as usize];
        if x.op == Op::PatVar {
            return x.aux != p && x.aux != THIS_PATTERN;
        }
        let mut c = if matches!(x.op, Op::Int | Op::Float) {
            NONE
        } else {
            x.first
        };
        while c != NONE {
            if self.refs_earlier(c, p) {
                return true;
            }
            c = self.cx.exprs[c as usize].next;
        }
        false
    }

    fn retarget(&mut self, e: Ix, p: u8) {
        let x = self.cx.exprs[e as usize];
        if x.op == Op::PatVar {
            if x.aux == p {
                self.cx.exprs[e as usize].aux = THIS_PATTERN;
            }
            return;
        }
        let mut c = if matches!(x.op, Op::Int | Op::Float) {
            NONE
        } else {
            x.first
        };
        while c != NONE {
            self.retarget(c, p);
            c = self.cx.exprs[c as usize].next;
        }
    }

    fn this_field(&mut self, p: u8, locv: Ix, desc: Ix) -> PResult<Ix> {
        let e = self.cx.push_expr(Expr {
            first: desc,
            ..Expr::new(Op::PatVar, p, locv)
        });
        cap!(self, e)
    }

    fn node2(&mut self, op: Op, a: Ix, b: Ix) -> PResult<Ix> {
        let n = cap!(self, self.cx.push_expr(Expr::new(op, 0, 0)))?;
        self.cx.exprs[n as usize].first = a;
        if b != NONE {
            self.cx.exprs[a as usize].next = b;
        }
        Ok(n)
    }

    /// One field constraint: returns (is multifield, test expression).
    fn field(&mut self, p: u8, locv: Ix, desc: Ix) -> PResult<(bool, Option<Ix>)> {
        let t = self.peek();
        #[cfg(feature = "extras")]
        {
            self.field_mf_call = false;
            self.field_sf = false;
        }
        let mut multi = false;
        let mut bound_first = false;
        match t.tok {
            Tok::SfVar(name) | Tok::MfVar(name) if self.find_var(name).is_none() => {
                self.next();
                multi = matches!(t.tok, Tok::MfVar(_));
                self.add_var(
                    t,
                    name,
                    VarKind::Pat {
                        pat: p,
                        loc: locv,
                        desc,
                    },
                    multi,
                )?;
                if !multi {
                    self.narrow_var(t, name)?;
                }
                #[cfg(feature = "extras")]
                {
                    self.field_mf_call = multi;
                    self.field_sf = !multi;
                }
                bound_first = true;
            }
            Tok::SfWild | Tok::MfWild => {
                self.next();
                multi = t.tok == Tok::MfWild;
                bound_first = true;
            }
            _ => {}
        }
        if bound_first {
            if self.peek().tok == Tok::Bar {
                // `?x|...`: CLIPS reports the constraint after the bar
                self.next();
                self.or_constraint(p, locv, desc, &mut multi)?;
                // CLIPS reads the variable as an alternative: `[PATTERN2]` when the
                // field mixes single and multifield parts (`$?x|b`), else
                // `[ANALYSIS4]` as it was bound nowhere before
                #[cfg(feature = "extras")]
                if matches!(t.tok, Tok::SfVar(_) | Tok::MfVar(_)) {
                    self.check_mixed_constraint(NONE, false)?;
                    return Err(self.unbound_in_lhs(t, false));
                }
                return Err(self.err(t, "a constraint ('|' cannot follow a binding variable)"));
            }
            if self.peek().tok != Tok::Amp {
                return Ok((multi, None));
            }
            self.next();
            #[cfg(feature = "extras")]
            let from = self.offset();
            let e = self.or_constraint(p, locv, desc, &mut multi)?;
            self.add_complexity(e);
            #[cfg(feature = "extras")]
            self.check_mixed_constraint(e, !multi)?;
            #[cfg(feature = "extras")]
            self.check_literal_conflict(t, e, matches!(t.tok, Tok::SfVar(_)))?;
            #[cfg(feature = "extras")]
            if let Tok::SfVar(name) = t.tok {
                self.narrow_by_literals(name, e);
                self.note_var_value(name, e);
                if self.has_variable_term(e) {
                    let to = self.offset();
                    self.narrow_through_vars(t, name, from, to)?;
                }
            }
            return Ok((multi, Some(e)));
        }
        let e = self.or_constraint(p, locv, desc, &mut multi)?;
        self.add_complexity(e);
        #[cfg(feature = "extras")]
        self.check_mixed_constraint(e, false)?;
        #[cfg(feature = "extras")]
        if let Tok::SfVar(name) = t.tok {
            // (not `?x|...`: the variable is one alternative)
            let x = self.cx.exprs[e as usize];
            if x.op != Op::Or || (x.first != NONE && self.cx.exprs[x.first as usize].op == Op::And)
            {
                self.check_literals_of_var(t, name, e)?;
            }
        }
        #[cfg(feature = "extras")]
        self.check_literal_conflict(t, e, false)?;
        // a bound variable leading the constraint (not one of `|` alternatives) must
        // fit this slot too
        if let Tok::SfVar(name) = t.tok {
            if self.cx.exprs[e as usize].op != Op::Or {
                self.narrow_var(t, name)?;
                #[cfg(feature = "extras")]
                self.narrow_by_literals(name, e);
                #[cfg(feature = "extras")]
                self.note_var_value(name, e);
            }
        }
        // (regrouped after the checks above, which read the literals as before)
        let e = if matches!(t.tok, Tok::SfVar(_) | Tok::MfVar(_)) {
            self.lead_var_first(e)?
        } else {
            e
        };
        Ok((multi, Some(e)))
    }

    /// Narrows what LHS variable `name` (at token `t`) can hold by the slot being read
    /// (none for an ordered fact): `[RULECSTR1]` when no type is left, or only numbers
    /// and an empty range, as CLIPS checks (it does not intersect allowed values).
    fn narrow_var(&mut self, t: Token<'s>, name: &str) -> PResult<()> {
        let Some(def) = self.lhs_slot else {
            return Ok(());
        };
        let Some(i) = self.vars[..self.nvars].iter().rposition(|v| v.name == name) else {
            return Ok(());
        };
        let mut c = self.var_cstr[i];
        if def.types != 0 {
            c.types &= def.types;
        }
        if def.range != NONE {
            let bound = |cx: &crate::engine::Core<'_>, e: Ix| cx.const_value(e).as_number();
            let lo = def.range;
            let hi = self.cx.exprs[lo as usize].next;
            if let Some(v) = bound(self.cx, lo) {
                if c.lo == NONE || bound(self.cx, c.lo).is_some_and(|old| v > old) {
                    c.lo = lo;
                }
            }
            if let Some(v) = bound(self.cx, hi) {
                if c.hi == NONE || bound(self.cx, c.hi).is_some_and(|old| v < old) {
                    c.hi = hi;
                }
            }
        }
        let old = core::mem::replace(&mut self.var_cstr[i], c);
        let r = self.check_var_cstr(t, i, def.name);
        // (a variable bound before a `not`, `exists` or `forall` it stands in keeps
        // its record after it)
        if i < self.quant_base {
            self.var_cstr[i] = old;
        }
        r
    }

    /// `[RULECSTR1]` when what LHS variable `i` (at token `t`, in slot `slot`) can
    /// hold is nothing: no type left, or only numbers and an empty range.
    fn check_var_cstr(&self, t: Token<'s>, i: usize, slot: Ix) -> PResult<()> {
        #[allow(unused_mut)]
        let mut c = self.var_cstr[i];
        #[cfg(feature = "extras")]
        {
            c.types &= self.cx.st.rule_notes.var_test[i] & self.cx.st.rule_notes.var_lit[i];
        }
        let numbers_only = c.types & !crate::template::types::NUMBER == 0;
        let empty_range = c.lo != NONE
            && c.hi != NONE
            && matches!(
                (self.cx.const_value(c.lo).as_number(), self.cx.const_value(c.hi).as_number()),
                (Some(lo), Some(hi)) if lo > hi
            );
        if c.types == 0 || (numbers_only && empty_range) {
            let mut e = self.err(t, "a variable whose slots can hold a common value");
            e.detail = crate::error::LoadDetail::VariableConflict {
                ce: self.ce_count,
                slot,
            };
            return Err(e);
        }
        Ok(())
    }

    /// `?x&?y` in a slot: CLIPS's record of `?x` takes in that of each variable the
    /// constraint (text `from..to`, no `|`) equates it with, as `&` terms of their own
    /// (not under `~`, not in calls): `[RULECSTR1]` for `?x` when nothing is left.
    #[cfg(feature = "extras")]
    fn narrow_through_vars(
        &mut self,
        t: Token<'s>,
        name: &str,
        from: usize,
        to: usize,
    ) -> PResult<()> {
        // (in an ordered fact's field `?x` takes `?y`'s record, no conflict yet)
        let slot = self.lhs_slot.map(|d| d.name);
        let Some(i) = self.vars[..self.nvars].iter().rposition(|v| v.name == name) else {
            return Ok(());
        };
        let Some(text) = self.lex.source().get(from..to) else {
            return Ok(());
        };
        let mut lx = Lexer::new(text);
        let mut depth = 0u32;
        let mut negated = false;
        loop {
            let tok = lx.next_token().tok;
            match tok {
                Tok::Eof | Tok::Bad => break,
                Tok::LParen => depth += 1,
                Tok::RParen => depth = depth.saturating_sub(1),
                Tok::Bar if depth == 0 => return Ok(()),
                Tok::SfVar(other) if depth == 0 && !negated => {
                    let j = self.vars[..self.nvars]
                        .iter()
                        .rposition(|v| v.name == other);
                    if let Some(j) = j.filter(|&j| j != i && !self.vars[j].multi) {
                        let o = self.var_cstr[j];
                        let mut c = self.var_cstr[i];
                        c.types &= o.types;
                        let num =
                            |cx: &crate::engine::Core<'_>, e: Ix| cx.const_value(e).as_number();
                        if o.lo != NONE
                            && (c.lo == NONE
                                || matches!((num(self.cx, o.lo), num(self.cx, c.lo)), (Some(a), Some(b)) if a > b))
                        {
                            c.lo = o.lo;
                        }
                        if o.hi != NONE
                            && (c.hi == NONE
                                || matches!((num(self.cx, o.hi), num(self.cx, c.hi)), (Some(a), Some(b)) if a < b))
                        {
                            c.hi = o.hi;
                        }
                        let old = core::mem::replace(&mut self.var_cstr[i], c);
                        let test = self.cx.st.rule_notes.var_test[i];
                        self.cx.st.rule_notes.var_test[i] &= self.cx.st.rule_notes.var_test[j];
                        let r = match slot {
                            Some(slot) => self.check_var_cstr(t, i, slot),
                            None => Ok(()),
                        };
                        if i < self.quant_base {
                            self.var_cstr[i] = old;
                            self.cx.st.rule_notes.var_test[i] = test;
                        }
                        r?;
                    }
                }
                _ => {}
            }
            negated = depth == 0 && tok == Tok::Tilde;
        }
        Ok(())
    }

    /// Adds a constraint's or a test CE's share of the rule's complexity.
    fn add_complexity(&mut self, e: Ix) {
        let c = Complexity::of(self.cx, e);
        self.complexity = self.complexity.saturating_add(c);
    }

    /// A bound variable leading a field and followed by `&` is a constraint of its own,
    /// whatever follows: CLIPS reads `?x&a|b` as `?x&(a|b)`, not `(?x&a)|b`. Regroups
    /// `e` as read by precedence (`Or(And(?x, ..), ..)`) into `And(?x, Or(.., ..))`.
    fn lead_var_first(&mut self, e: Ix) -> PResult<Ix> {
        let or = self.cx.exprs[e as usize];
        if or.op != Op::Or || self.cx.exprs[or.first as usize].op != Op::And {
            return Ok(e);
        }
        let and = or.first;
        let var = self.cx.exprs[and as usize].first;
        let rest = self.cx.exprs[var as usize].next;
        // the first alternative without the variable: one term, or an `&` of several
        let alt = if self.cx.exprs[rest as usize].next == NONE {
            rest
        } else {
            let a = cap!(self, self.cx.push_expr(Expr::new(Op::And, 0, 0)))?;
            self.cx.exprs[a as usize].first = rest;
            a
        };
        self.cx.exprs[alt as usize].next = self.cx.exprs[and as usize].next;
        self.cx.exprs[e as usize].first = alt;
        self.cx.exprs[e as usize].next = NONE;
        self.cx.exprs[var as usize].next = e;
        self.cx.exprs[and as usize].next = NONE;
        Ok(and)
    }

    fn or_constraint(&mut self, p: u8, locv: Ix, desc: Ix, multi: &mut bool) -> PResult<Ix> {
        let first = self.and_constraint(p, locv, desc, multi)?;
        if self.peek().tok != Tok::Bar {
            return Ok(first);
        }
        let or = cap!(self, self.cx.push_expr(Expr::new(Op::Or, 0, 0)))?;
        self.cx.append_child(or, first);
        while self.peek().tok == Tok::Bar {
            self.next();
            let e = self.and_constraint(p, locv, desc, multi)?;
            self.cx.append_child(or, e);
        }
        Ok(or)
    }

    fn and_constraint(&mut self, p: u8, locv: Ix, desc: Ix, multi: &mut bool) -> PResult<Ix> {
        let first = self.term(p, locv, desc, multi)?;
        if self.peek().tok != Tok::Amp {
            return Ok(first);
        }
        let and = cap!(self, self.cx.push_expr(Expr::new(Op::And, 0, 0)))?;
        self.cx.append_child(and, first);
        while self.peek().tok == Tok::Amp {
            self.next();
            let e = self.term(p, locv, desc, multi)?;
            self.cx.append_child(and, e);
        }
        Ok(and)
    }

    fn term(&mut self, p: u8, locv: Ix, desc: Ix, multi: &mut bool) -> PResult<Ix> {
        self.nested(|parser| parser.term_inner(p, locv, desc, multi))
    }

    fn term_inner(&mut self, p: u8, locv: Ix, desc: Ix, multi: &mut bool) -> PResult<Ix> {
        let t = self.next();
        match t.tok {
            Tok::Tilde => {
                let inner = self.term(p, locv, desc, multi)?;
                let n = cap!(self, self.cx.push_expr(Expr::new(Op::Not, 0, 0)))?;
                self.cx.exprs[n as usize].first = inner;
                Ok(n)
            }
            Tok::Symbol(":") if self.peek().tok == Tok::LParen => {
                let save = self.scope;
                self.scope = Scope::Lhs;
                #[cfg(feature = "extras")]
                let from = self.offset();
                let e = self.parse_expr()?;
                #[cfg(feature = "extras")]
                self.note_field_check(from);
                self.scope = save;
                Ok(e)
            }
            Tok::Symbol("=") if self.peek().tok == Tok::LParen => {
                #[cfg(feature = "extras")]
                let from = self.offset();
                let e = self.parse_expr()?;
                #[cfg(feature = "extras")]
                {
                    self.note_field_check(from);
                    let y = self.cx.exprs[e as usize];
                    // a builtin giving anything (`nth$`) is neither part
                    let returns = if y.aux == crate::expr::FnKind::Builtin as u8 {
                        crate::builtins::get(y.data).returns
                    } else {
                        crate::builtins::describe::Returns::Symbol
                    };
                    if y.op == Op::Call {
                        use crate::builtins::describe::Returns;
                        self.field_mf_call |= returns == Returns::Multifield;
                        self.field_sf |= !matches!(returns, Returns::Multifield | Returns::Any);
                    }
                }
                let this = self.this_field(p, locv, desc)?;
                self.node2(Op::Eq2, this, e)
            }
            // in a pattern `=` and `:` are operators: a call must follow
            Tok::Symbol(":" | "=") => {
                let at = self.peek();
                Err(self.syntax_of(at, "a function call after '=' or ':'", "function calls"))
            }
            Tok::SfVar(name) | Tok::MfVar(name) => {
                let is_mf = matches!(t.tok, Tok::MfVar(_));
                if is_mf {
                    *multi = true;
                }
                #[cfg(feature = "extras")]
                let mixed = {
                    let (sf, mf) = (self.field_sf || !is_mf, self.field_mf_call || is_mf);
                    let (sf, mf) = self.field_kinds_ahead(sf, mf);
                    self.field_sf |= !is_mf;
                    self.field_mf_call |= is_mf;
                    sf && mf
                };
                let v = match self.find_var(name) {
                    Some(var) if var.multi != is_mf && matches!(var.kind, VarKind::Pat { .. }) => {
                        let mut e = self.err(
                            t,
                            "a variable used as single-field (?x) or multifield ($?x), not both",
                        );
                        e.detail = crate::error::LoadDetail::MixedVariable;
                        return Err(e);
                    }
                    Some(_) => self.var_ref(t, name, false)?,
                    // CLIPS's `[ANALYSIS4]`: referenced before a pattern binds it (its
                    // `[PATTERN2]` first, after a `=(...)` giving a multifield)
                    #[cfg(feature = "extras")]
                    None if mixed => {
                        let at = self.constraint_end();
                        let mut err = self.err(at, "no mix of single and multifield constraints");
                        err.detail = crate::error::LoadDetail::MixedConstraint;
                        err.echo_end = at.end as u32;
                        return Err(err);
                    }
                    // (held back to the end of the rule, as CLIPS's analysis finds
                    // it once the rule is read whole; the field tests nothing here)
                    None => {
                        let e = self.unbound_in_lhs(t, false);
                        if self.deferred.is_none() {
                            self.deferred = Some(e);
                        }
                        cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?
                    }
                };
                let this = self.this_field(p, locv, desc)?;
                self.node2(Op::Eq2, this, v)
            }
            _ => match self.literal(t)? {
                Some(c) => {
                    #[cfg(feature = "extras")]
                    {
                        self.field_sf = true;
                    }
                    if let Some(def) = self.lhs_slot {
                        if let Some(what) = self.literal_violation(&def, c) {
                            let mut e = self.err(t, expected(what));
                            e.detail = crate::error::LoadDetail::PatternConstraint {
                                ce: self.ce_count,
                                what,
                                slot: def.name,
                                range: def.range,
                            };
                            return Err(e);
                        }
                    }
                    let this = self.this_field(p, locv, desc)?;
                    self.node2(Op::Eq2, this, c)
                }
                None => {
                    let mut e = self.err(t, "a constraint (literal, variable, ~, :( ) or =( ))");
                    // CLIPS shows the rule up to the token where a field was due (a
                    // `(`, or the `)` after a dangling `&`, `|` or `~`)
                    if !matches!(t.tok, Tok::Eof | Tok::Bad) {
                        e.echo_end = t.end as u32;
                    }
                    Err(e)
                }
            },
        }
    }
}

/// Fields of one pattern remembered for ordering alpha nodes like CLIPS's pattern
/// network; more are accepted but not used for ordering.
const MAX_FIELDS: usize = 16;

pub(crate) struct PatBuild {
    /// (locator, alpha test or NONE, multifield element) per field, in parse order;
    /// an empty multislot is one entry with element `ZERO_LEN`.
    pub(crate) fields: [(Ix, Ix, bool); MAX_FIELDS],
    pub(crate) nfields: usize,
    pub(crate) desc: Ix,
    pub(crate) dlast: Ix,
    pub(crate) atests: Ix,
    pub(crate) alast: Ix,
    pub(crate) jtests: Ix,
    pub(crate) jlast: Ix,
    pub(crate) marks: u8,
    pub(crate) rhash: [Ix; MAX_RHASH],
    pub(crate) nrhash: usize,
    /// Variables bound earlier that this pattern equates with a field: (pattern,
    /// locator) of the binding, (locator, descriptor) of the field (`classify`).
    pub(crate) aliases: [(u8, Ix, Ix, Ix); 8],
    pub(crate) naliases: usize,
}

impl PatBuild {
    fn record(&mut self, locv: Ix, test: Ix, multi: bool) {
        if self.nfields < MAX_FIELDS {
            self.fields[self.nfields] = (locv, test, multi);
            self.nfields += 1;
        }
    }
}

/// CLIPS's specificity (complexity) of a rule, as its complexity, simplicity, lex and
/// mea strategies use it (Basic Programming Guide 5.3.5, checked with CLIPS 6.30): one
/// per pattern (the comparison of its relation or template name) and per leading test
/// CE, one per comparison of a field with a constant or an earlier variable (`a`, `~a`,
/// `?x` again, `=(...)`), one per function call in `:(...)` and `test` CEs, where
/// `and`, `or` and `not` count their arguments instead and calls nested in calls count
/// nothing.
pub(crate) struct Complexity;

impl Complexity {
    const AND: Ix = crate::builtins::builtin_id("and");
    const OR: Ix = crate::builtins::builtin_id("or");
    const NOT: Ix = crate::builtins::builtin_id("not");

    pub(crate) fn of(cx: &crate::engine::Core<'_>, e: Ix) -> u16 {
        let x = cx.exprs[e as usize];
        let logical = match x.op {
            Op::And | Op::Or | Op::Not => true,
            Op::Call => {
                x.aux == crate::expr::FnKind::Builtin as u8
                    && matches!(x.data, Self::AND | Self::OR | Self::NOT)
            }
            Op::Eq2 => return 1,
            _ => return 0,
        };
        if !logical {
            return 1;
        }
        let mut sum = 0u16;
        let mut c = x.first;
        while c != NONE {
            sum = sum.saturating_add(Self::of(cx, c));
            c = cx.exprs[c as usize].next;
        }
        sum
    }
}

#[cfg(feature = "extras")]
impl Parser<'_, '_, '_> {
    /// The types (`template::types` bits) LHS variable `i` (named `name`) can hold: as
    /// the check of candidates `cands` was read when one of them kept them, else now.
    fn var_types(&self, i: usize, name: &str, cands: (usize, usize)) -> u8 {
        let notes = &self.cx.st.rule_notes;
        let src = self.lex.source();
        match notes.kept_types(src, cands, name) {
            Some(k) => k,
            None => self.var_cstr[i].types & notes.var_lit[i],
        }
    }
}

/// What CLIPS's `[RULECSTR3]` check of the actions needs to know of the rule being read.
#[cfg(feature = "extras")]
impl super::rhs_types::Names for Parser<'_, '_, '_> {
    fn lhs(&self, name: &str) -> Option<super::rhs_types::Rec> {
        use super::rhs_types::Rec;
        let (n, serial, cands) = self.lhs_limit.unwrap_or((self.nvars, u32::MAX, (0, 0)));
        let i = self.vars[..n.min(self.vars.len())]
            .iter()
            .zip(self.cx.st.rule_notes.var_serial.iter())
            .rposition(|(v, &s)| {
                v.name == name && matches!(v.kind, VarKind::Pat { .. }) && s < serial
            })?;
        let v = self.vars[i];
        Some(match v.kind {
            VarKind::Pat { loc: l, .. } if l == loc::FACT => Rec::FACT_ADDRESS,
            _ if v.multi => Rec::MULTIFIELD_VAR,
            _ => match self.var_types(i, name, cands) {
                // (CLIPS refuses such a pattern before: `[RULECSTR1]`, `[CSTRNCHK1]`)
                0 => Rec::ANY,
                k => Rec::slot_types(k),
            },
        })
    }

    fn is_template(&self, name: &str) -> bool {
        (0..self.cx.st.pools.ntemplates).any(|i| {
            let t = &self.cx.templates[i as usize];
            !t.implied && self.cx.sym_text(t.name) == name
        })
    }

    fn seq_ops(&self) -> bool {
        self.cx.st.mode.seq_ops
    }
}

#[cfg(feature = "extras")]
impl<'s> Parser<'s, '_, '_> {
    /// CLIPS's `[PATTERN2]`: field constraint `e` (after a leading single-field
    /// variable when `single`) both compares the field with a `=(...)` call of a
    /// function returning a multifield and with a variable or literal (`?x&=(create$
    /// a)`, `abc|=(create$ a)`); predicates `:(...)` count as neither. Reported at
    /// the token after the constraint, which CLIPS shows.
    fn check_mixed_constraint(&mut self, e: Ix, single: bool) -> PResult<()> {
        let (s, m) = if e == NONE {
            (false, false)
        } else {
            self.constraint_kinds(e)
        };
        if (m && (s || single)) || (self.field_sf && self.field_mf_call) {
            let at = self.peek();
            let mut err = self.err(at, "no mix of single and multifield constraints");
            err.detail = crate::error::LoadDetail::MixedConstraint;
            err.echo_end = at.end as u32;
            return Err(err);
        }
        Ok(())
    }

    /// CLIPS's `[RULECSTR1]` for one field constraint `e` without `|` whose `&` terms
    /// compare the field with two different literals (`abc&def`, `1&1.0`) or with a
    /// literal and its negation (`abc&~abc`): on the leading variable `t` when `var`,
    /// else on the pattern.
    fn check_literal_conflict(&mut self, t: Token<'s>, e: Ix, var: bool) -> PResult<()> {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::And {
            return Ok(());
        }
        // the literal a term compares with, and whether it is negated
        let literal = |p: &Self, c: Ix| -> Option<(Value, bool)> {
            let mut y = p.cx.exprs[c as usize];
            let negated = y.op == Op::Not;
            if negated {
                y = p.cx.exprs[y.first as usize];
            }
            if y.op != Op::Eq2 || y.first == NONE {
                return None;
            }
            let v = p.cx.exprs[y.first as usize].next;
            if v == NONE {
                return None;
            }
            match p.cx.exprs[v as usize].op {
                Op::Int | Op::Float | Op::Sym | Op::Str => Some((p.cx.const_value(v), negated)),
                _ => None,
            }
        };
        let mut conflict = false;
        let mut a = x.first;
        while a != NONE && !conflict {
            if let Some((va, na)) = literal(self, a) {
                let mut b = self.cx.exprs[a as usize].next;
                while b != NONE {
                    if let Some((vb, nb)) = literal(self, b) {
                        let same = va.same(vb);
                        if (!na && !nb && !same) || (na != nb && same) {
                            conflict = true;
                            break;
                        }
                    }
                    b = self.cx.exprs[b as usize].next;
                }
            }
            a = self.cx.exprs[a as usize].next;
        }
        if !conflict {
            return Ok(());
        }
        let mut err = self.err(t, "a field constraint its literals can meet");
        err.detail = crate::error::LoadDetail::LiteralConflict {
            ce: self.ce_count,
            slot: self.lhs_slot.map_or(NONE, |d| d.name),
            field: self.lhs_field,
            var,
        };
        Err(err)
    }

    /// (compares with a variable or literal, with a multifield `=(...)`) in `e`.
    fn constraint_kinds(&self, e: Ix) -> (bool, bool) {
        use crate::builtins::describe::Returns;
        let x = self.cx.exprs[e as usize];
        match x.op {
            Op::Or | Op::And | Op::Not => {
                let (mut s, mut m) = (false, false);
                let mut c = x.first;
                while c != NONE {
                    let (a, b) = self.constraint_kinds(c);
                    s |= a;
                    m |= b;
                    c = self.cx.exprs[c as usize].next;
                }
                (s, m)
            }
            Op::Eq2 => {
                let v = if x.first == NONE {
                    NONE
                } else {
                    self.cx.exprs[x.first as usize].next
                };
                if v == NONE {
                    return (false, false);
                }
                let y = self.cx.exprs[v as usize];
                match y.op {
                    Op::Call => {
                        let multi = y.aux == crate::expr::FnKind::Builtin as u8
                            && crate::builtins::get(y.data).returns == Returns::Multifield;
                        (false, multi)
                    }
                    _ => (true, false),
                }
            }
            _ => (false, false),
        }
    }

    /// Narrows what single-field LHS variable `name` can hold by the literals and
    /// `=(...)` calls of constraint `e` of a field it leads (`?x&abc|1`): CLIPS's
    /// record of the variable, which its `[RULECSTR3]` check reads.
    fn narrow_by_literals(&mut self, name: &str, e: Ix) {
        let Some(i) = self.vars[..self.nvars].iter().rposition(|v| v.name == name) else {
            return;
        };
        if self.vars[i].multi {
            return;
        }
        // (not for a variable bound before the `not`, `exists` or `forall` read)
        if i < self.quant_base {
            return;
        }
        let k = self.literal_types(e);
        self.cx.st.rule_notes.var_lit[i] &= k;
    }

    /// Whether the rest of the field constraint being read (its `&`/`|` terms after
    /// the next token) adds a single-field part (a literal, a `?y`) or a multifield
    /// one (a `$?y`, a `=(...)` call giving a multifield) to `sf` and `mf`: CLIPS
    /// reads the whole field before it looks for unbound variables.
    fn field_kinds_ahead(&mut self, mut sf: bool, mut mf: bool) -> (bool, bool) {
        if !matches!(self.peek().tok, Tok::Amp | Tok::Bar) {
            return (sf, mf);
        }
        let mut lx = self.lex.clone();
        loop {
            let mut t = lx.next_token();
            while t.tok == Tok::Tilde {
                t = lx.next_token();
            }
            match t.tok {
                Tok::Symbol(op @ (":" | "=")) => {
                    if lx.next_token().tok != Tok::LParen {
                        return (sf, mf);
                    }
                    if let Tok::Symbol(f) = lx.next_token().tok {
                        use crate::builtins::describe::Returns;
                        // (not a builtin: a deffunction, a single field)
                        let returns =
                            crate::builtins::lookup(f).map_or(Returns::Symbol, |(_, b)| b.returns);
                        if op == "=" {
                            mf |= returns == Returns::Multifield;
                            sf |= !matches!(returns, Returns::Multifield | Returns::Any);
                        }
                    }
                    let mut depth = 1u32;
                    while depth > 0 {
                        match lx.next_token().tok {
                            Tok::LParen => depth += 1,
                            Tok::RParen => depth -= 1,
                            Tok::Eof | Tok::Bad => return (sf, mf),
                            _ => {}
                        }
                    }
                }
                Tok::MfVar(_) => mf = true,
                Tok::SfVar(_) | Tok::Symbol(_) | Tok::Str(_) | Tok::Int(_) | Tok::Float(_) => {
                    sf = true
                }
                _ => return (sf, mf),
            }
            if !matches!(lx.next_token().tok, Tok::Amp | Tok::Bar) {
                return (sf, mf);
            }
        }
    }

    /// The token after the field constraint being read (the rest of its `&`/`|` terms
    /// skipped), which CLIPS's `[PATTERN2]` shows the rule up to.
    fn constraint_end(&mut self) -> Token<'s> {
        let first = self.peek();
        if !matches!(first.tok, Tok::Amp | Tok::Bar) {
            return first;
        }
        let mut lx = self.lex.clone();
        loop {
            let mut t = lx.next_token();
            while t.tok == Tok::Tilde {
                t = lx.next_token();
            }
            if matches!(t.tok, Tok::Symbol(":" | "=")) {
                let mut depth = 0u32;
                loop {
                    let u = lx.next_token();
                    match u.tok {
                        Tok::LParen => depth += 1,
                        Tok::RParen if depth <= 1 => break,
                        Tok::RParen => depth -= 1,
                        Tok::Eof | Tok::Bad => return u,
                        _ => {}
                    }
                }
            }
            let n = lx.next_token();
            if !matches!(n.tok, Tok::Amp | Tok::Bar) {
                return n;
            }
        }
    }

    /// Whether field constraint `e` (no `|`) has a variable among its `&` terms
    /// (`?y` of `?x&?y`).
    fn has_variable_term(&self, e: Ix) -> bool {
        let var_term = |c: Ix| {
            let y = self.cx.exprs[c as usize];
            y.op == Op::Eq2
                && y.first != NONE
                && matches!(self.cx.exprs[y.first as usize].next, v if v != NONE
                    && self.cx.exprs[v as usize].op == Op::PatVar)
        };
        let x = self.cx.exprs[e as usize];
        match x.op {
            Op::And => {
                let mut c = x.first;
                while c != NONE {
                    if var_term(c) {
                        return true;
                    }
                    c = self.cx.exprs[c as usize].next;
                }
                false
            }
            _ => var_term(e),
        }
    }

    /// Calls `f` with each literal term of field constraint `e` (through `&`, `|`
    /// and `~`) and whether it is negated.
    fn literal_terms(&self, e: Ix, negated: bool, f: &mut impl FnMut(Value, bool)) {
        let x = self.cx.exprs[e as usize];
        match x.op {
            Op::Or | Op::And => {
                let mut c = x.first;
                while c != NONE {
                    self.literal_terms(c, negated, f);
                    c = self.cx.exprs[c as usize].next;
                }
            }
            Op::Not if x.first != NONE => self.literal_terms(x.first, !negated, f),
            Op::Eq2 if x.first != NONE => {
                let v = self.cx.exprs[x.first as usize].next;
                if v != NONE
                    && matches!(
                        self.cx.exprs[v as usize].op,
                        Op::Int | Op::Float | Op::Sym | Op::Str
                    )
                {
                    f(self.cx.const_value(v), negated);
                }
            }
            _ => {}
        }
    }

    /// Notes the literal a constraint `e` (no `|`) led by single-field variable `name`
    /// gives it (`abc` of `?x&abc`), outside `not`, `exists` and `forall` for a
    /// variable bound before it (`RuleNotes::var_val`).
    fn note_var_value(&mut self, name: &str, e: Ix) {
        let Some(i) = self.vars[..self.nvars].iter().rposition(|v| v.name == name) else {
            return;
        };
        if self.vars[i].multi || i < self.quant_base || self.cx.exprs[e as usize].op == Op::Or {
            return;
        }
        if self.cx.st.rule_notes.var_val[i].is_some() {
            return;
        }
        let mut found = None;
        self.literal_terms(e, false, &mut |v, negated| {
            if !negated && found.is_none() {
                found = Some(v);
            }
        });
        self.cx.st.rule_notes.var_val[i] = found;
    }

    /// CLIPS's `[CSTRNCHK1]` of a literal in field constraint `e` led by variable
    /// `name` (at token `t`) bound before: each literal (negated too) must fit the
    /// types the variable has (its slots, literals, tests, and this slot's) and the
    /// value a literal gave it; then `[RULECSTR1]` when `~` takes that value away.
    fn check_literals_of_var(&mut self, t: Token<'s>, name: &str, e: Ix) -> PResult<()> {
        let Some(i) = self.vars[..self.nvars].iter().rposition(|v| v.name == name) else {
            return Ok(());
        };
        if self.vars[i].multi || !matches!(self.vars[i].kind, VarKind::Pat { .. }) {
            return Ok(());
        }
        let notes = &self.cx.st.rule_notes;
        let mut types = self.var_cstr[i].types & notes.var_lit[i] & notes.var_test[i];
        // (a fact-address variable: an address)
        if matches!(self.vars[i].kind, VarKind::Pat { loc: l, .. } if l == loc::FACT) {
            types &=
                crate::template::types::FACT_ADDRESS | crate::template::types::INSTANCE_ADDRESS;
        }
        let def = self.lhs_slot;
        if let Some(d) = def.filter(|d| d.types != 0) {
            types &= d.types;
        }
        let value = notes.var_val[i];
        let mut what = None;
        let mut removed = false;
        self.literal_terms(e, false, &mut |v, negated| {
            if what.is_some() {
                return;
            }
            let k = crate::template::types::of(v, |s| self.cx.sym_text(s));
            if k != 0 && k & types == 0 {
                what = Some(crate::error::Restriction::Type);
            } else if value.is_some_and(|x| {
                !(x.same(v) && k == crate::template::types::of(x, |s| self.cx.sym_text(s)))
            }) {
                what = Some(crate::error::Restriction::Values);
            } else if negated && value.is_some() {
                removed = true;
            }
        });
        if let Some(what) = what {
            let mut err = self.err(t, expected(what));
            err.detail = crate::error::LoadDetail::PatternConstraint {
                ce: self.ce_count,
                what,
                slot: def.map_or(NONE, |d| d.name),
                range: def.map_or(Ix::from(self.lhs_field), |d| d.range),
            };
            return Err(err);
        }
        if removed && self.cx.exprs[e as usize].op != Op::Or {
            let mut err = self.err(t, "a field constraint its literals can meet");
            err.detail = crate::error::LoadDetail::LiteralConflict {
                ce: self.ce_count,
                slot: def.map_or(NONE, |d| d.name),
                field: self.lhs_field,
                var: true,
            };
            return Err(err);
        }
        Ok(())
    }

    /// The types (`template::types` bits, 0xFF for any) constraint `e` allows by its
    /// literals and `=(...)` calls (variables, negations and predicates allow any).
    fn literal_types(&self, e: Ix) -> u8 {
        use crate::builtins::describe::Returns;
        use crate::template::types as t;
        let x = self.cx.exprs[e as usize];
        let children = |all: bool| {
            let mut acc = if all { 0xFF } else { 0 };
            let mut c = x.first;
            while c != NONE {
                let k = self.literal_types(c);
                acc = if all { acc & k } else { acc | k };
                c = self.cx.exprs[c as usize].next;
            }
            acc
        };
        match x.op {
            Op::Or => children(false),
            Op::And => children(true),
            Op::Eq2 => {
                let this = x.first;
                let v = if this == NONE {
                    NONE
                } else {
                    self.cx.exprs[this as usize].next
                };
                if v == NONE {
                    return 0xFF;
                }
                let y = self.cx.exprs[v as usize];
                match y.op {
                    Op::Int | Op::Float | Op::Sym | Op::Str => {
                        match t::of(self.cx.const_value(v), |s| self.cx.sym_text(s)) {
                            0 => 0xFF,
                            k => k,
                        }
                    }
                    Op::Call if y.aux == crate::expr::FnKind::Builtin as u8 => {
                        match crate::builtins::get(y.data).returns {
                            Returns::Number => t::NUMBER,
                            Returns::Integer => t::INTEGER,
                            Returns::Float => t::FLOAT,
                            Returns::Symbol => t::SYMBOL,
                            Returns::Str => t::STRING,
                            Returns::Lexeme => t::LEXEME | t::INSTANCE_NAME,
                            Returns::SymbolOrString => t::LEXEME,
                            Returns::Any | Returns::Multifield | Returns::Void => 0xFF,
                        }
                    }
                    _ => 0xFF,
                }
            }
            _ => 0xFF,
        }
    }
}

#[cfg(feature = "extras")]
impl Parser<'_, '_, '_> {
    /// Notes the expression just read (from `from` on) of CE `ce_count` for CLIPS's
    /// `[RULECSTR2]` check (`slot`: the template slot's name, else `field` of an
    /// ordered pattern, 0 in a test CE).
    fn note_lhs_check(&mut self, from: usize, slot: Ix, field: u8) {
        let end = self.consumed_end();
        // (a test CE first in a `not`, `exists` or `forall` group too: CLIPS moves it
        // out of the group)
        let test_ce = slot == NONE && field == 0;
        let narrow = self.quant_depth == 0 || (test_ce && self.quant_first);
        if narrow && self.cx.st.rule_notes.overflow() {
            self.narrow_by_text(from, end);
        }
        // each candidate: its argument's types narrow `var_test` (see
        // `narrow_by_text`), and it keeps the types its variable has here, which
        // CLIPS's [RULECSTR2] reads
        let src = self.lex.source();
        for k in self.cx.st.rule_notes.checked_cands..self.cx.st.rule_notes.ncands {
            let notes = &self.cx.st.rule_notes;
            let Some(name) = notes.cand_name(src, k) else {
                break;
            };
            let i = self.vars[..self.nvars]
                .iter()
                .rposition(|v| v.name == name && matches!(v.kind, VarKind::Pat { .. }));
            let Some(i) = i else {
                self.cx.st.rule_notes.keep_types(k, 0xFF);
                continue;
            };
            let kept = self.var_cstr[i].types & notes.var_lit[i];
            let arg = notes.cand_arg_types(k);
            let notes = &mut self.cx.st.rule_notes;
            notes.keep_types(k, kept);
            if narrow && !notes.overflow() && !self.vars[i].multi {
                notes.var_test[i] &= arg;
            }
        }
        let notes = &mut self.cx.st.rule_notes;
        notes.checked_cands = notes.ncands;
        if let Some(c) = notes.lhs_checks.get_mut(notes.nlhs_checks) {
            *c = super::rhs_types::LhsCheck {
                start: from as u32,
                end: end as u32,
                slot,
                ce: self.ce_count,
                field,
                nvars: self.nvars as u16,
                serial: self.var_count,
                cands_end: notes.ncands as u8,
            };
        }
        // counted past the capacity too: `check_lhs_types` refuses such a rule
        notes.nlhs_checks = notes.nlhs_checks.saturating_add(1);
    }

    /// Narrows `var_test` of each single-field LHS variable passed straight to a
    /// builtin (at any depth) in the call `from..to` of the text by that argument's
    /// restriction (`(> ?x 1)`: a number), reading the text (when the candidates noted
    /// while it was read did not fit).
    fn narrow_by_text(&mut self, from: usize, to: usize) {
        let src = self.lex.source();
        let mut found: [(&str, u8); 16] = [("", 0xFF); 16];
        let mut n = 0;
        super::rhs_types::argument_types(src, from, to, |name, types| {
            if n < found.len() {
                found[n] = (name, types);
                n += 1;
            }
        });
        for &(name, types) in &found[..n] {
            let i = self.vars[..self.nvars].iter().rposition(|v| v.name == name);
            if let Some(i) = i.filter(|&i| !self.vars[i].multi) {
                self.cx.st.rule_notes.var_test[i] &= types;
            }
        }
    }

    /// [`Parser::note_lhs_check`] of a `:` or `=` constraint of the field being read.
    fn note_field_check(&mut self, from: usize) {
        match self.lhs_slot {
            Some(def) => self.note_lhs_check(from, def.name, 0),
            None => self.note_lhs_check(from, NONE, self.lhs_field),
        }
    }

    /// CLIPS's `[RULECSTR2]` once the LHS is read: a variable passed straight to a
    /// builtin in a test CE or `:`/`=` constraint whose argument takes no value the
    /// variable's patterns let it hold.
    fn check_lhs_types(&mut self) -> PResult<()> {
        let src = self.lex.source();
        let notes = &self.cx.st.rule_notes;
        if notes.nlhs_checks > super::rhs_types::MAX_LHS_CHECKS {
            let last = notes.lhs_checks[super::rhs_types::MAX_LHS_CHECKS - 1];
            let t = self.lex.token_at(last.end as usize);
            return Err(self.err(
                t,
                "at most 256 test CEs and `:` or `=` constraints in one rule",
            ));
        }
        let mut cands_from = 0;
        for k in 0..self.cx.st.rule_notes.nlhs_checks {
            let Some(&c) = self.cx.st.rule_notes.lhs_checks.get(k) else {
                break;
            };
            let cands_to = c.cands_end as usize;
            let cands = cands_from.min(cands_to)..cands_to;
            cands_from = cands_to;
            self.lhs_limit = Some((c.nvars as usize, c.serial, (cands.start, cands.end)));
            // the text is read again only when the notes show a violation
            let may_fail = self.cx.st.rule_notes.may_fail(src, cands, false, &*self);
            let found = if may_fail {
                super::rhs_types::check_lhs(src, c.start as usize, c.end as usize, &*self)
            } else {
                debug_assert!(
                    super::rhs_types::check_lhs(src, c.start as usize, c.end as usize, &*self)
                        .is_none(),
                    "the notes missed a [RULECSTR2]"
                );
                None
            };
            self.lhs_limit = None;
            let Some(f) = found else {
                continue;
            };
            let t = self.lex.token_at(f.var_start);
            let mut e = self.err(t, "a variable whose patterns fit the argument");
            e.end = f.var_end as u32;
            e.detail = crate::error::LoadDetail::LhsArgumentType {
                call_start: f.call_start as u32,
                call_end: f.call_end as u32,
                slot: c.slot,
                arg: f.arg,
                ce: c.ce,
                field: c.field,
            };
            return Err(e);
        }
        Ok(())
    }

    /// CLIPS's `[RULECSTR3]` once the actions (from `from` on) are read: a variable
    /// passed to a builtin that takes no value it can hold (`rhs_types`).
    fn check_rhs_types(&mut self, from: usize, cands_from: usize) -> PResult<()> {
        let src = self.lex.source();
        let to = self.consumed_end();
        let notes = &self.cx.st.rule_notes;
        let cands = cands_from.min(notes.ncands)..notes.ncands;
        // the text is read again only when the notes show a violation
        if !notes.may_fail(src, cands, true, &*self) {
            debug_assert!(
                super::rhs_types::check(src, from, to, &*self).is_none(),
                "the notes missed a [RULECSTR3]"
            );
            return Ok(());
        }
        let Some(f) = super::rhs_types::check(src, from, to, &*self) else {
            return Ok(());
        };
        let t = self.lex.token_at(f.var_start);
        let mut e = self.err(t, "a variable whose bindings fit the argument");
        e.end = f.var_end as u32;
        e.detail = crate::error::LoadDetail::RhsArgumentType {
            call_start: f.call_start as u32,
            call_end: f.call_end as u32,
            arg: f.arg,
            passes: f.passes,
        };
        Err(e)
    }
}
