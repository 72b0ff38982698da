//! defrule: LHS conditional elements compiled into alpha nodes and joins, RHS actions.

use super::facts::Violation;
use super::{PResult, Parser, Scope, VarKind};
use crate::engine::cap;
use crate::error::Pool;
use crate::expr::{loc, Expr, Op};
use crate::lexer::{Tok, Token};
use crate::rete::{
    AlphaNode, Join, JoinKind, EMPTY_PATH, MAX_MARKS, MAX_PATTERNS, MAX_RHASH, PATH_LEN,
    THIS_PATTERN,
};
use crate::rule::Rule;
use crate::value::Ix;
use crate::value::{SymId, Value, NONE};

/// Most `or` CEs in one rule.
const MAX_ORS: usize = 8;

/// CE index meaning "the root" (as a parent) or "none" (as a right input).
const CE_ROOT: u8 = 0xFF;

/// One join to build. CEs are listed in creation order; a `not`/`exists` over
/// several CEs lists its subnetwork first, then the join taking the subnetwork's
/// end from the right.
#[derive(Clone, Copy)]
struct Ce {
    kind: JoinKind,
    alpha: Ix,
    /// Join tests (chain) and post tests (after not/exists).
    jtests: Ix,
    jlast: Ix,
    post: Ix,
    plast: Ix,
    /// Pattern index (binding slot) of the CE in its chain.
    depth: u8,
    /// Left input: index of the CE before it in its chain, or CE_ROOT.
    parent: u8,
    /// Join from the right: index of the subnetwork's last CE (else CE_ROOT) and
    /// of its first one.
    right: u8,
    first_sub: u8,
}

const CE_EMPTY: Ce = Ce {
    kind: JoinKind::Test,
    alpha: NONE,
    jtests: NONE,
    jlast: NONE,
    post: NONE,
    plast: NONE,
    depth: 0,
    parent: CE_ROOT,
    right: CE_ROOT,
    first_sub: CE_ROOT,
};

struct Build {
    ces: [Ce; MAX_PATTERNS],
    n: usize,
    /// Last CE of the chain being built (CE_ROOT before the first) and the next
    /// pattern index in it.
    cur: u8,
    depth: u8,
    /// Nesting of not/exists groups, and the first CE of the innermost one.
    groups: u8,
    group_first: u8,
    /// `or` branch choice per `or` met, and how many branches each had.
    choice: [u8; MAX_ORS],
    counts: [u8; MAX_ORS],
    nor: usize,
    /// The salience, once the first disjunct evaluated it (CLIPS evaluates it once).
    salience: Option<i32>,
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
            Tok::Symbol(s) => self.plain_name(nt, s)?,
            _ => return Err(self.err(nt, "a defrule name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
        let body_lex = self.save();
        let first_new_rule = self.cx.st.nrules;
        self.rule_base = first_new_rule;
        let first_new_alpha = self.cx.st.nalpha;
        self.alpha_base = first_new_alpha;
        let replaces = (0..first_new_rule).any(|r| {
            let rule = &self.cx.rules[r as usize];
            rule.name == sym && !rule.deleted
        });
        self.replacing = if replaces { sym } else { NONE };
        let first_new_join = self.cx.st.njoins;
        let mut b = Build {
            ces: [CE_EMPTY; MAX_PATTERNS],
            n: 0,
            cur: CE_ROOT,
            depth: 0,
            groups: 0,
            group_first: CE_ROOT,
            choice: [0; MAX_ORS],
            counts: [0; MAX_ORS],
            nor: 0,
            salience: None,
        };
        let mut prev_rule = NONE;
        loop {
            self.restore(body_lex.clone());
            self.nvars = 0;
            self.nlocals = 0;
            b.n = 0;
            b.cur = CE_ROOT;
            b.depth = 0;
            b.groups = 0;
            b.group_first = CE_ROOT;
            b.nor = 0;
            let r = self.rule_body(sym, &mut b)?;
            if prev_rule != NONE {
                self.cx.rules[prev_rule as usize].next_disjunct = r;
            }
            prev_rule = r;
            // next combination of or-branches
            let mut i = b.nor;
            loop {
                if i == 0 {
                    break;
                }
                i -= 1;
                b.choice[i] += 1;
                if b.choice[i] < b.counts[i] {
                    break;
                }
                b.choice[i] = 0;
            }
            if b.choice[..b.nor].iter().all(|&c| c == 0) {
                break;
            }
        }
        // source text for ppdefrule, unless the host chose to drop pretty-print forms
        if self.cx.st.keep_pp_forms {
            let end = self.lex.pos();
            let text = &self.lex.source()[start..end];
            if let Ok(id) = self.cx.intern(text) {
                self.cx.rules[first_new_rule as usize].text = id;
            }
        }
        // hook the new joins up to their alpha nodes first: a redefinition's removal of
        // the old rule below empties and retires an alpha node whose successor list it
        // leaves empty, and the new rule may share that node
        for j in first_new_join..self.cx.st.njoins {
            let a = self.cx.joins[j as usize].alpha;
            if a != NONE {
                self.cx.joins[j as usize].alpha_next = self.cx.alphas[a as usize].succ;
                self.cx.alphas[a as usize].succ = j;
            }
        }
        // a redefinition replaces the old rule
        for r in 0..first_new_rule {
            if self.cx.rules[r as usize].name == sym && !self.cx.rules[r as usize].deleted {
                self.cx.remove_rule(r);
            }
        }
        // `load` prints "Defining defrule" before the new activations, as CLIPS does
        self.announce();
        // match the new rule(s) against existing facts as CLIPS's incremental reset
        // does (the new joins are hooked up above): prime those fed by old joins (each rule from its
        // end upwards), then drive the facts, oldest first, through the new patterns
        let mut primed = Primed {
            ids: [NONE; 64],
            n: 0,
        };
        for r in first_new_rule..self.cx.st.nrules {
            let t = self.cx.rules[r as usize].terminal;
            let res = self.prime_chain(t, first_new_join, 0, &mut primed);
            self.map_prime_err(res, nt)?;
        }
        if first_new_alpha < self.cx.st.nalpha {
            let res = self.cx.prime_alphas(first_new_alpha);
            self.map_prime_err(res, nt)?;
        }

        Ok(())
    }

    /// Primes the new joins of a chain whose left input is an old join, walking
    /// from `j` up to `stop`; a subnetwork is primed after the join taking it.
    fn prime_chain(
        &mut self,
        mut j: Ix,
        first_new: Ix,
        stop: Ix,
        primed: &mut Primed,
    ) -> Result<(), crate::error::EvalError> {
        while j != NONE && j != 0 && j != stop {
            let jn = self.cx.joins[j as usize];
            if j >= first_new && jn.parent < first_new && !primed.ids[..primed.n].contains(&j) {
                if primed.n < primed.ids.len() {
                    primed.ids[primed.n] = j;
                    primed.n += 1;
                }
                self.cx.prime_join(j)?;
            }
            if jn.rjoin != NONE {
                self.prime_chain(jn.rjoin, first_new, jn.parent, primed)?;
            }
            j = jn.parent;
        }
        Ok(())
    }

    fn map_prime_err(&self, r: Result<(), crate::error::EvalError>, at: Token<'s>) -> PResult<()> {
        match r {
            Ok(()) => Ok(()),
            Err(e) => {
                let c = match e.kind() {
                    crate::error::EvalErrorKind::Capacity(c) => c,
                    _ => cap(Pool::Tokens, self.cx.tokens.len()),
                };
                Err(self.cap_err(at, c))
            }
        }
    }

    /// One disjunct: LHS (with the current or-choices), RHS, then the network.
    fn rule_body(&mut self, name: SymId, b: &mut Build) -> PResult<Ix> {
        self.ce_count = 0;
        let mut salience = (0i32, NONE);
        // (declare (salience N))
        if self.peek().tok == Tok::LParen {
            let save = self.save();
            self.next();
            if self.peek().tok == Tok::Symbol("declare") {
                self.next();
                salience = self.declare(b)?;
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
                Tok::Eof | Tok::Bad | Tok::RParen => {
                    return Err(self.err(t, "'=>' or a conditional element"))
                }
                // a `(declare ...)` after a CE is an ordinary pattern for CLIPS 6.30, whose
                // nested `(` is then a syntax error: declare comes first or not at all
                _ => self.ce(b, Ctx::Top)?,
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
        let rhs = self.body_block()?;
        self.build_rule(name, salience, b, rhs)
    }

    fn declare(&mut self, b: &mut Build) -> PResult<(i32, Ix)> {
        let mut sal = 0;
        let mut sal_expr = NONE;
        let mut seen_salience = false;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => return Ok((sal, sal_expr)),
                Tok::LParen => {
                    let kw = self.next();
                    match kw.tok {
                        Tok::Symbol("salience") if seen_salience => {
                            return Err(self.err(kw, "one salience declaration only"));
                        }
                        Tok::Symbol("salience") => {
                            seen_salience = true;
                            let save = self.scope;
                            self.scope = Scope::Frame;
                            let vt = self.peek();
                            let e = self.parse_expr()?;
                            self.scope = save;
                            if !matches!(self.cx.exprs[e as usize].op, Op::Int | Op::Float) {
                                sal_expr = e;
                            }
                            // later disjuncts are built after the first one's network:
                            // their failure must not be kept (see `eval_now`)
                            let v = match b.salience {
                                Some(s) => Ok(Value::Int(s.into())),
                                None => self.eval_now(e),
                            };
                            sal = match v {
                                Ok(Value::Int(i)) if (-10000..=10000).contains(&i) => i as i32,
                                _ => {
                                    return Err(self
                                        .err(vt, "an integer salience between -10000 and 10000"))
                                }
                            };
                            b.salience = Some(sal);
                            self.expect_rparen("')' after the salience")?;
                        }
                        Tok::Symbol("auto-focus") => {
                            return Err(self.not_implemented(kw, "auto-focus"));
                        }
                        _ => return Err(self.err(kw, "salience or auto-focus")),
                    }
                }
                _ => return Err(self.err(t, "'(' or ')' in declare")),
            }
        }
    }

    /// One conditional element.
    fn ce(&mut self, b: &mut Build, ctx: Ctx) -> PResult<()> {
        self.nested(|p| p.ce_inner(b, ctx))
    }

    fn ce_inner(&mut self, b: &mut Build, ctx: Ctx) -> PResult<()> {
        let t = self.next();
        match t.tok {
            Tok::SfVar(fv) => {
                let arrow = self.next();
                if arrow.tok != Tok::Symbol("<-") {
                    return Err(self.err(arrow, "'<-' after a fact-address variable"));
                }
                if ctx != Ctx::Top || b.groups > 0 {
                    return Err(self.err(
                        t,
                        "a pattern (fact addresses cannot be bound inside not/exists)",
                    ));
                }
                let lp = self.expect_lparen("'(' starting a pattern")?;
                if let Tok::Symbol("not" | "and" | "or" | "exists" | "test" | "logical") =
                    self.peek().tok
                {
                    return Err(self.err(lp, "a pattern after '<-' (not a conditional element)"));
                }
                self.pattern(b, ctx, Some((t, fv)))
            }
            Tok::LParen => {
                let h = self.peek();
                match h.tok {
                    Tok::Symbol(kw @ ("not" | "exists")) => {
                        self.next();
                        let negated = kw == "not";
                        let saved = self.nvars;
                        let r = if self.one_pattern_follows()? {
                            // one pattern: a not/exists join on its alpha node
                            let inner = if negated { Ctx::Not } else { Ctx::Exists };
                            self.ce(b, inner)
                        } else if negated && self.not_of_one_pattern_follows()? {
                            // (not (not P)) is (exists P), as CLIPS compiles it
                            self.next();
                            self.next();
                            self.ce(b, Ctx::Exists)
                                .and_then(|()| self.expect_rparen("')' closing not (one CE only)"))
                        } else {
                            self.group(b, negated, h)
                        };
                        self.nvars = saved;
                        r?;
                        self.expect_rparen(if negated {
                            "')' closing not (one CE only)"
                        } else {
                            "')' closing exists"
                        })
                    }
                    Tok::Symbol("logical") => {
                        Err(self.not_implemented(h, "the logical conditional element"))
                    }
                    Tok::Symbol("and") => {
                        self.next();
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
                        if ctx != Ctx::Top || b.groups > 0 {
                            return Err(
                                self.err(h, "a pattern (or inside not/exists is not supported)")
                            );
                        }
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
                        let e = self.parse_expr()?;
                        self.expect_rparen("')' closing test")?;
                        self.attach_test_ce(b, e, h)
                    }
                    _ => self.pattern(b, ctx, None),
                }
            }
            _ => Err(self.err(t, "a conditional element")),
        }
    }

    /// Whether the next CE is one pattern closing the enclosing CE.
    fn one_pattern_follows(&mut self) -> PResult<bool> {
        let save = self.save();
        let r =
            self.pattern_starts() && self.skip_balanced().is_ok() && self.peek().tok == Tok::RParen;
        self.restore(save);
        Ok(r)
    }

    /// Whether the next CE is `(not PATTERN)` closing the enclosing CE.
    fn not_of_one_pattern_follows(&mut self) -> PResult<bool> {
        let save = self.save();
        let mut r = false;
        if self.next().tok == Tok::LParen && self.next().tok == Tok::Symbol("not") {
            r = self.pattern_starts()
                && self.skip_balanced().is_ok()
                && self.next().tok == Tok::RParen
                && self.peek().tok == Tok::RParen;
        }
        self.restore(save);
        Ok(r)
    }

    /// Whether a pattern CE (not another CE keyword) starts here.
    fn pattern_starts(&mut self) -> bool {
        let save = self.save();
        let r = match self.next().tok {
            Tok::SfVar(_) => true,
            Tok::LParen => !matches!(
                self.next().tok,
                Tok::Symbol("not" | "and" | "or" | "exists" | "test" | "logical")
            ),
            _ => false,
        };
        self.restore(save);
        r
    }

    /// `not`/`exists` over several CEs (or a nested CE): the CEs form a subnetwork
    /// starting from the current chain, and a join takes its end from the right.
    /// The group is one pattern slot (`*`) of the enclosing chain.
    fn group(&mut self, b: &mut Build, negated: bool, at: Token<'s>) -> PResult<()> {
        let (outer, d, gf) = (b.cur, b.depth, b.group_first);
        let first = b.n;
        b.groups += 1;
        b.group_first = first as u8;
        let r = (|| {
            if negated {
                // exactly one CE: (and ...), (not ...), (exists ...)
                self.ce(b, Ctx::Top)
            } else {
                loop {
                    let p = self.peek();
                    match p.tok {
                        Tok::RParen => return Ok(()),
                        Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                        _ => self.ce(b, Ctx::Top)?,
                    }
                }
            }
        })();
        b.groups -= 1;
        b.group_first = gf;
        r?;
        if b.n == first {
            return Err(self.err(at, "a conditional element inside not/exists"));
        }
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
            first_sub: first as u8,
            ..CE_EMPTY
        };
        b.cur = b.n as u8;
        b.n += 1;
        b.depth = d + 1;
        Ok(())
    }

    fn attach_test_ce(&mut self, b: &mut Build, e: Ix, at: Token<'s>) -> PResult<()> {
        if b.cur == CE_ROOT || (b.groups > 0 && b.n == b.group_first as usize) {
            // a leading test: a test join of its own (a pattern slot shown as `*`)
            if b.n >= MAX_PATTERNS || b.depth as usize >= MAX_PATTERNS {
                return Err(self.err(at, "fewer conditional elements"));
            }
            let i = b.n;
            b.ces[i] = Ce {
                parent: b.cur,
                depth: b.depth,
                ..CE_EMPTY
            };
            Self::chain_push(self, &mut b.ces[i].jtests, &mut b.ces[i].jlast, e);
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
            Tok::Symbol(s)
                if !matches!(s, "test" | "not" | "and" | "or" | "exists" | "logical") =>
            {
                self.plain_name(nt, s)?
            }
            _ => return Err(self.err(nt, "a template or relation name")),
        };
        if b.n >= MAX_PATTERNS || b.depth as usize >= MAX_PATTERNS {
            return Err(self.err(nt, "fewer conditional elements"));
        }
        let p = b.depth;
        let sym = cap!(self, self.cx.intern(name))?;
        let tmpl = match self.cx.find_template(sym) {
            Some(t) => t,
            None if self.peek().tok == Tok::LParen => {
                return Err(self.err(
                    nt,
                    "a deftemplate name (no such template for a slot pattern)",
                ));
            }
            None => cap!(self, self.cx.implied_template(sym))?,
        };
        self.pat_tmpl[p as usize] = tmpl;
        self.ce_count = self.ce_count.saturating_add(1);
        if let Some((ft, fv)) = factvar {
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
            loop {
                let t = self.next();
                match t.tok {
                    Tok::RParen => break,
                    Tok::LParen => {
                        let st = self.next();
                        let slot = self.slot_of(tmpl, st)?;
                        let def = self.cx.slot_def(tmpl, slot);
                        // literals in this slot's constraints must fit the slot
                        self.lhs_slot = Some(def);
                        if def.multi {
                            self.multislot_fields(&mut pb, p, slot as u8, st)?;
                        } else {
                            let (multi, test) =
                                self.field(p, loc::new(slot as u8, loc::SINGLE), NONE)?;
                            if multi {
                                return Err(self
                                    .err(st, "a single-field constraint for a single-field slot"));
                            }
                            let at = match test {
                                Some(e) => self.classify(&mut pb, p, e),
                                None => NONE,
                            };
                            pb.record(loc::new(slot as u8, loc::SINGLE), at, false);
                            self.expect_rparen(
                                "')' closing the slot (one field in a single-field slot)",
                            )?;
                        }
                    }
                    _ => return Err(self.err(t, "'(' and a slot name, or ')'")),
                }
            }
        }
        self.lhs_slot = None;
        // share an identical alpha node or make a new one
        self.right_hash(&mut pb, p);
        let alpha = self.find_or_make_alpha(tmpl, &pb, nt)?;
        let kind = match ctx {
            Ctx::Top => JoinKind::Positive,
            Ctx::Not => JoinKind::Negative,
            Ctx::Exists => JoinKind::Exists,
        };
        b.ces[b.n] = Ce {
            kind,
            alpha,
            jtests: pb.jtests,
            jlast: pb.jlast,
            post: NONE,
            plast: NONE,
            depth: b.depth,
            parent: b.cur,
            right: CE_ROOT,
            first_sub: CE_ROOT,
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
                    let (multi, test) = self.field(p, loc::new(slot, i), ps)?;
                    let el = cap!(
                        self,
                        self.cx
                            .push_expr(Expr::new(Op::PatElem, u8::from(multi), i as Ix))
                    )?;
                    self.cx.append_child(ps, el);
                    let at = match test {
                        Some(e) => self.classify(pb, p, e),
                        None => NONE,
                    };
                    pb.record(loc::new(slot, i), at, multi);
                    multis += u8::from(multi);
                    i += 1;
                }
            }
        }
        if i == 0 {
            // CLIPS tests an empty multislot `(l)` for zero length in a node of its own
            pb.record(loc::new(slot, ZERO_LEN), NONE, false);
        }
        if multis >= 2 {
            pb.marks += multis - 1;
            if pb.marks as usize > MAX_MARKS {
                return Err(self.err(at, "at most 5 multifield variables in one pattern"));
            }
        }
        if pb.desc == NONE {
            pb.desc = ps;
        } else {
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
    fn classify(&mut self, pb: &mut PatBuild, p: u8, e: Ix) -> Ix {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::And {
            return self.classify_one(pb, p, e, true);
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
        match n {
            0 => NONE,
            1 => {
                self.push_alpha_test(pb, alpha);
                alpha
            }
            _ => {
                self.cx.exprs[e as usize].first = alpha;
                self.push_alpha_test(pb, e);
                e
            }
        }
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
                return Err(self.err(t, "a constraint ('|' cannot follow a binding variable)"));
            }
            if self.peek().tok != Tok::Amp {
                return Ok((multi, None));
            }
            self.next();
            let e = self.or_constraint(p, locv, desc, &mut multi)?;
            return Ok((multi, Some(e)));
        }
        let e = self.or_constraint(p, locv, desc, &mut multi)?;
        Ok((multi, Some(e)))
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
                let e = self.parse_expr()?;
                self.scope = save;
                Ok(e)
            }
            Tok::Symbol("=") if self.peek().tok == Tok::LParen => {
                let e = self.parse_expr()?;
                let this = self.this_field(p, locv, desc)?;
                self.node2(Op::Eq2, this, e)
            }
            Tok::SfVar(name) | Tok::MfVar(name) => {
                let is_mf = matches!(t.tok, Tok::MfVar(_));
                if is_mf {
                    *multi = true;
                }
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
                    None => {
                        return Err(self.err(
                            t,
                            "a variable bound before (first use must lead the constraint)",
                        ))
                    }
                };
                let this = self.this_field(p, locv, desc)?;
                self.node2(Op::Eq2, this, v)
            }
            _ => match self.literal(t)? {
                Some(c) => {
                    if let Some(def) = self.lhs_slot {
                        if let Some(violation) = self.literal_violation(&def, c) {
                            let mut e = self.err(t, violation.expected());
                            e.detail = crate::error::LoadDetail::PatternConstraint {
                                ce: self.ce_count,
                                types: violation == Violation::Type,
                                slot: def.name,
                            };
                            return Err(e);
                        }
                    }
                    let this = self.this_field(p, locv, desc)?;
                    self.node2(Op::Eq2, this, c)
                }
                None => Err(self.err(t, "a constraint (literal, variable, ~, :( ) or =( ))")),
            },
        }
    }

    fn find_or_make_alpha(&mut self, tmpl: Ix, pb: &PatBuild, at: Token<'s>) -> PResult<Ix> {
        let (path, tail) = self.pattern_path(pb);
        // CLIPS never shares the relation-name node an ordered pattern without tests
        // (`(o $?)`) ends in: each such pattern is a new, newest node
        let alone = self.cx.templates[tmpl as usize].implied && path.locs[0] == EMPTY_PATH;
        let mut a = self.cx.templates[tmpl as usize].alpha_head;
        while a != NONE && !alone {
            let n = self.cx.alphas[a as usize];
            if n.live
                && !self.old_only_alpha(a)
                && self.chain_eq(n.desc, pb.desc)
                && self.chain_eq(n.tests, pb.atests)
                && n.nrhash as usize == pb.nrhash
                && (0..pb.nrhash).all(|i| self.same_field(n.rhash[i], pb.rhash[i]))
            {
                return Ok(a);
            }
            a = n.next_in_tmpl;
        }
        let n = self.cx.st.nalpha as usize;
        if n >= self.cx.alphas.len() {
            let c = cap(Pool::AlphaNodes, self.cx.alphas.len());
            return Err(self.cap_err(at, c));
        }
        let (path_loc, mut path_test, plen) = (path.locs, path.tests, path.len);
        if pb.nrhash > 0 {
            // the last field's nodes carry the right hash: nodes of their own
            let mut h: u32 = 0x7f4a_7c15;
            for &e in &pb.rhash[..pb.nrhash] {
                let x = self.cx.exprs[e as usize];
                h = mix16(h, u32::from(x.data));
                if x.first != NONE {
                    let d = self.cx.exprs[x.first as usize];
                    h = mix16(h, u32::from(d.data) | u32::from(d.aux) << 16);
                }
            }
            for t in &mut path_test[plen - tail..plen] {
                *t = (mix16(u32::from(*t), h) & 0xFFFF) as Ix | 1;
            }
        }
        self.cx.alphas[n] = AlphaNode {
            tmpl,
            desc: pb.desc,
            tests: pb.atests,
            next_in_tmpl: NONE,
            succ: NONE,
            mem: NONE,
            mem_tail: NONE,
            nmarks: pb.marks,
            live: true,
            path_loc,
            path_test,
            key: [0; PATH_LEN],
            key_len: plen as u8,
            rhash: pb.rhash,
            nrhash: pb.nrhash as u8,
        };
        self.assign_trie_key(tmpl, n as Ix, alone);
        self.insert_alpha_sorted(tmpl, n as Ix);
        self.cx.st.nalpha += 1;
        self.cx.st.net_gen = self.cx.st.net_gen.wrapping_add(1);
        self.cx.note_hw(Pool::AlphaNodes, n + 1);
        Ok(n as Ix)
    }

    /// The pattern's path in CLIPS's pattern network (CLIPS 6.30 `factbld.c`), one
    /// level per network node, in the order the pattern names its slots: a field
    /// without a test of its own makes no node wherever it stands; a constant
    /// constraint without `|` makes two, a "selector" node for the field that every
    /// such constant on it shares, then the constant. Multislot elements are nodes of
    /// their own, told apart by their place in the slot's layout (the first carries
    /// the slot's length test). Returns the path and how many of its last levels are
    /// the last field's (they carry the right hash; 0 when the path was cut).
    fn pattern_path(&self, pb: &PatBuild) -> (NetPath, usize) {
        let (f, nf) = (pb.fields, pb.nfields);
        let mut path = NetPath {
            locs: [0; PATH_LEN],
            tests: [0; PATH_LEN],
            len: 0,
            cut: false,
        };
        let mut tail = 0;
        let mut i = 0;
        while i < nf {
            let (l, t, _) = f[i];
            match loc::elem(l) {
                loc::SINGLE => {
                    if t != NONE {
                        let sel = self.selects(t).then_some(SELECTOR);
                        tail = path.field(l, sel, self.expr_hash(t));
                    }
                    i += 1;
                }
                ZERO_LEN => {
                    tail = path.field(l, None, ZERO_LEN as Ix);
                    i += 1;
                }
                _ => {
                    let slot = loc::slot(l);
                    let mut k = i;
                    while k < nf && loc::slot(f[k].0) == slot {
                        k += 1;
                    }
                    if let Some(n) = self.multislot_path(&f[i..k], &mut path) {
                        tail = n;
                    }
                    i = k;
                }
            }
        }
        if path.len == 0 {
            path.locs[0] = EMPTY_PATH;
            path.len = 1;
            tail = 1;
        }
        if path.cut {
            tail = 0;
        }
        (path, tail)
    }

    /// The nodes of one multislot's elements (CLIPS's `RemoveUnneededSlots`): an
    /// element keeps a node if it has a test (the first one always has the slot's
    /// length test unless it is a multifield with no single field after it) or if it
    /// is a multifield among several. Returns the last node's level count, if any.
    fn multislot_path(&self, r: &[(Ix, Ix, bool)], path: &mut NetPath) -> Option<usize> {
        let nmf = r.iter().filter(|x| x.2).count() as u32;
        let nsf = r.len() as u32 - nmf;
        let length_test = if r[0].2 && nsf == 0 {
            0
        } else {
            2 + u32::from(nmf == 0) + (nsf << 1)
        };
        let keeps = |k: usize| {
            let (_, t, m) = r[k];
            t != NONE || (k == 0 && length_test != 0) || (m && nmf > 1)
        };
        let last = (0..r.len()).rev().find(|&k| keeps(k))?;
        let (mut sfb, mut mfb) = (0u32, 0u32);
        let mut tail = 1;
        for (k, &(l, t, m)) in r.iter().enumerate() {
            if keeps(k) {
                // what CLIPS compares: position, kind, end of slot, how the value is
                // found (fields before and after) and the length test
                let mut h = mix16(0x51ed_270b, k as u32);
                h = mix16(h, u32::from(m) | u32::from(k == last) << 1);
                h = mix16(h, sfb | mfb << 8);
                h = mix16(
                    h,
                    (nsf - sfb - u32::from(!m)) | (nmf - mfb - u32::from(m)) << 8,
                );
                if k == 0 {
                    h = mix16(h, length_test);
                }
                let fold = |h: u32| ((h ^ (h >> 16)) & 0xFFFF) as Ix;
                tail = if t != NONE && !m && self.selects(t) {
                    let v = mix16(u32::from(self.expr_hash(t)), u32::from(k == last));
                    path.field(l, Some(fold(mix16(h, 0))), fold(v))
                } else {
                    let test = if t == NONE { 1 } else { self.expr_hash(t) };
                    path.field(l, None, fold(mix16(h, u32::from(test))))
                };
            }
            sfb += u32::from(!m);
            mfb += u32::from(m);
        }
        Some(tail)
    }

    /// Whether CLIPS 6.30 hashes this field constraint on a constant (a selector
    /// node): an `&` chain holding a literal that is not negated, and no `|`.
    fn selects(&self, t: Ix) -> bool {
        let x = self.cx.exprs[t as usize];
        if x.op != Op::And {
            return self.is_const_eq(t);
        }
        let mut c = x.first;
        while c != NONE {
            if self.is_const_eq(c) {
                return true;
            }
            c = self.cx.exprs[c as usize].next;
        }
        false
    }

    fn is_const_eq(&self, e: Ix) -> bool {
        let x = self.cx.exprs[e as usize];
        if x.op != Op::Eq2 || x.first == NONE {
            return false;
        }
        let v = self.cx.exprs[x.first as usize].next;
        v != NONE
            && matches!(
                self.cx.exprs[v as usize].op,
                Op::Int | Op::Float | Op::Sym | Op::Str
            )
    }

    /// Gives each level of the new alpha node's path the id of the identical node of
    /// an existing pattern (same prefix), or a new id (always, for a node `alone`).
    fn assign_trie_key(&mut self, tmpl: Ix, n: Ix, alone: bool) {
        let me = self.cx.alphas[n as usize];
        let mut key = [0 as Ix; PATH_LEN];
        for lvl in 0..me.key_len as usize {
            let mut id = 0;
            let mut a = if alone {
                NONE
            } else {
                self.cx.templates[tmpl as usize].alpha_head
            };
            while a != NONE {
                let o = self.cx.alphas[a as usize];
                if o.key_len as usize > lvl
                    && !self.old_only_alpha(a)
                    && o.key[..lvl] == key[..lvl]
                    && o.path_loc[lvl] == me.path_loc[lvl]
                    && o.path_test[lvl] == me.path_test[lvl]
                {
                    id = o.key[lvl];
                    break;
                }
                a = o.next_in_tmpl;
            }
            if id == 0 {
                self.cx.st.trie_ids = self.cx.st.trie_ids.wrapping_add(1).max(1);
                id = self.cx.st.trie_ids;
            }
            key[lvl] = id;
        }
        self.cx.alphas[n as usize].key = key;
    }

    /// Structural hash of an expression tree (orders alpha nodes; never decides
    /// sharing, which compares exactly).
    fn expr_hash(&self, e: Ix) -> Ix {
        let x = self.cx.exprs[e as usize];
        let mut h = mix16(0x9e37, x.op as u32);
        h = mix16(h, shape_aux(x) as u32);
        h = mix16(h, x.data as u32);
        if matches!(x.op, Op::Int | Op::Float) {
            let p = self.cx.exprs[e as usize + 1];
            h = mix16(h, p.data as u32 | (p.first as u32) << 16);
            h = mix16(h, p.next as u32);
        } else if x.op != Op::PatVar {
            let mut c = x.first;
            while c != NONE {
                h = mix16(h, self.expr_hash(c) as u32);
                c = self.cx.exprs[c as usize].next;
            }
        }
        (((h ^ (h >> 16)) & 0xFFFF) as Ix).max(2)
    }

    /// Keeps a template's alpha nodes in pattern-network order: depth first, newer
    /// sibling nodes first, a pattern's own node before longer ones.
    fn insert_alpha_sorted(&mut self, tmpl: Ix, n: Ix) {
        let me = self.cx.alphas[n as usize];
        let mut prev = NONE;
        let mut a = self.cx.templates[tmpl as usize].alpha_head;
        while a != NONE {
            let o = self.cx.alphas[a as usize];
            // an equal path is the same CLIPS node, whose newest joins come first
            if !key_before(&o.key[..o.key_len as usize], &me.key[..me.key_len as usize]) {
                break;
            }
            prev = a;
            a = o.next_in_tmpl;
        }
        self.cx.alphas[n as usize].next_in_tmpl = a;
        if prev == NONE {
            self.cx.templates[tmpl as usize].alpha_head = n;
        } else {
            self.cx.alphas[prev as usize].next_in_tmpl = n;
        }
    }

    /// Records the fields of pattern `p` that its join tests compare for equality
    /// with a variable bound earlier (`?x` used again): CLIPS's right hash.
    fn right_hash(&mut self, pb: &mut PatBuild, p: u8) {
        let mut t = pb.jtests;
        while t != NONE && pb.nrhash < MAX_RHASH {
            let x = self.cx.exprs[t as usize];
            if x.op == Op::Eq2 && x.first != NONE {
                let this = self.cx.exprs[x.first as usize];
                let other = this.next;
                if this.op == Op::PatVar
                    && this.aux == p
                    && other != NONE
                    && self.cx.exprs[other as usize].op == Op::PatVar
                    && self.cx.exprs[other as usize].aux != p
                {
                    pb.rhash[pb.nrhash] = x.first;
                    pb.nrhash += 1;
                }
            }
            t = x.next;
        }
    }

    /// Whether two pattern-variable expressions name the same field (any pattern).
    fn same_field(&self, a: Ix, b: Ix) -> bool {
        let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
        x.data == y.data
            && ((x.first == NONE && y.first == NONE)
                || (x.first != NONE && y.first != NONE && {
                    let (p, q) = (
                        self.cx.exprs[x.first as usize],
                        self.cx.exprs[y.first as usize],
                    );
                    p.aux == q.aux && p.data == q.data && self.chain_eq(p.first, q.first)
                }))
    }

    fn chain_eq(&self, mut a: Ix, mut b: Ix) -> bool {
        while a != NONE && b != NONE {
            if !self.expr_eq(a, b) {
                return false;
            }
            a = self.cx.exprs[a as usize].next;
            b = self.cx.exprs[b as usize].next;
        }
        a == NONE && b == NONE
    }

    fn expr_eq(&self, a: Ix, b: Ix) -> bool {
        let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
        if x.op != y.op || shape_aux(x) != shape_aux(y) || x.data != y.data {
            return false;
        }
        match x.op {
            Op::Int | Op::Float => self.cx.const_value(a).same(self.cx.const_value(b)),
            Op::PatVar => {
                (x.first == NONE && y.first == NONE)
                    || (x.first != NONE && y.first != NONE && {
                        let (p, q) = (
                            self.cx.exprs[x.first as usize],
                            self.cx.exprs[y.first as usize],
                        );
                        p.aux == q.aux && p.data == q.data && self.chain_eq(p.first, q.first)
                    })
            }
            _ => self.chain_eq(x.first, y.first),
        }
    }

    /// Whether alpha node `a` serves only the rule this defrule replaces: CLIPS removes
    /// the old rule first, so such a node (and a path level only it has) is made anew,
    /// as the newest, not shared. Nodes this defrule made itself are shared.
    fn old_only_alpha(&self, a: Ix) -> bool {
        if self.replacing == NONE || a >= self.alpha_base {
            return false;
        }
        let mut j = self.cx.alphas[a as usize].succ;
        while j != NONE {
            if self.cx.joins[j as usize].refs > self.replaced_uses(self.replacing, j) {
                return false;
            }
            j = self.cx.joins[j as usize].alpha_next;
        }
        true
    }

    /// How many references to join `j` the rule this defrule replaces (named `name`,
    /// created before `rule_base`) holds: a join only it uses is not shared, as CLIPS
    /// removes the old rule first and builds (and primes) such joins anew.
    fn replaced_uses(&self, name: SymId, j: Ix) -> Ix {
        let mut n = 0;
        for r in 0..self.rule_base {
            let rule = &self.cx.rules[r as usize];
            if rule.name == name && !rule.deleted {
                let mut d = r;
                while d != NONE {
                    n += self.chain_uses(self.cx.rules[d as usize].terminal, 0, j);
                    d = self.cx.rules[d as usize].next_disjunct;
                }
            }
        }
        n
    }

    /// References to join `j` on the chain from `from` up to `stop` and in the
    /// subnetworks it takes from the right (the walk `Core::remove_rule` releases).
    fn chain_uses(&self, mut from: Ix, stop: Ix, j: Ix) -> Ix {
        let mut n = 0;
        while from != NONE && from != 0 && from != stop {
            let jn = &self.cx.joins[from as usize];
            n += Ix::from(from == j);
            if jn.rjoin != NONE {
                n += self.chain_uses(jn.rjoin, jn.parent, j);
            }
            from = jn.parent;
        }
        n
    }

    /// Creates the rule and its joins (the root token comes later, in `defrule`).
    fn build_rule(&mut self, name: SymId, salience: (i32, Ix), b: &Build, rhs: Ix) -> PResult<Ix> {
        self.cx.st.net_gen = self.cx.st.net_gen.wrapping_add(1);
        let at = self.peek();
        let nr = self.cx.st.nrules as usize;
        if nr >= self.cx.rules.len() {
            let c = cap(Pool::Rules, self.cx.rules.len());
            return Err(self.cap_err(at, c));
        }
        if self.cx.st.njoins as usize + b.n + 1 > self.cx.joins.len() {
            let c = cap(Pool::Joins, self.cx.joins.len());
            return Err(self.cap_err(at, c));
        }
        self.cx.rules[nr] = Rule::EMPTY;
        // the join built for each CE
        let mut jid = [0 as Ix; MAX_PATTERNS];
        // a redefinition: the old rule's joins may not be shared (`replaced_uses`)
        let replacing = (0..self.rule_base).any(|r| {
            let rule = &self.cx.rules[r as usize];
            rule.name == name && !rule.deleted
        });
        for (i, ce) in b.ces[..b.n].iter().enumerate() {
            let parent = if ce.parent == CE_ROOT {
                0
            } else {
                jid[ce.parent as usize]
            };
            let rjoin = if ce.right == CE_ROOT {
                NONE
            } else {
                jid[ce.right as usize]
            };
            {
                // share an identical join under the same parent (CLIPS does)
                let mut c = self.cx.joins[parent as usize].first_child;
                let mut found = NONE;
                while c != NONE {
                    let cj = self.cx.joins[c as usize];
                    if cj.refs > 0
                        && (!replacing || cj.refs > self.replaced_uses(name, c))
                        && cj.kind == ce.kind
                        && cj.alpha == ce.alpha
                        && cj.rjoin == rjoin
                        && cj.depth == ce.depth
                        && self.chain_eq(cj.tests, ce.jtests)
                        && self.chain_eq(cj.post, ce.post)
                    {
                        found = c;
                        break;
                    }
                    c = cj.next_sibling;
                }
                if found != NONE {
                    self.cx.joins[found as usize].refs += 1;
                    self.push_join_mark(true);
                    jid[i] = found;
                    continue;
                }
            }
            self.push_join_mark(false);
            let j = self.cx.st.njoins;
            self.cx.st.njoins += 1;
            self.cx.joins[j as usize] = Join {
                kind: ce.kind,
                depth: ce.depth,
                rule: NONE,
                parent,
                first_child: NONE,
                next_sibling: NONE,
                refs: 1,
                alpha: ce.alpha,
                tests: ce.jtests,
                post: ce.post,
                alpha_next: NONE,
                mem: NONE,
                rjoin,
                rsucc: NONE,
                index_child: NONE,
                #[cfg(feature = "host-speedups")]
                index_built: false,
                #[cfg(feature = "host-speedups")]
                one_child: false,
                #[cfg(feature = "wipe")]
                plain: false,
                #[cfg(feature = "wipe")]
                plain_gen: u32::MAX,
            };
            // a join from the right comes right after its subnetwork's first join
            // among the parent's children: the subnetwork sees a new left token first
            let after = if rjoin != NONE {
                jid[ce.first_sub as usize]
            } else {
                NONE
            };
            if after != NONE && self.cx.joins[after as usize].parent == parent {
                self.cx.joins[j as usize].next_sibling = self.cx.joins[after as usize].next_sibling;
                self.cx.joins[after as usize].next_sibling = j;
            } else {
                self.cx.joins[j as usize].next_sibling = self.cx.joins[parent as usize].first_child;
                self.cx.joins[parent as usize].first_child = j;
            }
            self.cx.note_children(parent);
            if rjoin != NONE {
                self.cx.joins[j as usize].alpha_next = self.cx.joins[rjoin as usize].rsucc;
                self.cx.joins[rjoin as usize].rsucc = j;
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
        self.push_join_mark(false);
        let term = self.cx.st.njoins;
        self.cx.st.njoins += 1;
        self.cx.joins[term as usize] = Join {
            kind: JoinKind::Terminal,
            depth: b.depth,
            rule: nr as Ix,
            parent: prev,
            next_sibling: self.cx.joins[prev as usize].first_child,
            refs: 1,
            ..Join::EMPTY
        };
        self.cx.joins[prev as usize].first_child = term;
        self.cx.note_children(prev);
        let prev = term;
        self.cx.note_hw(Pool::Joins, self.cx.st.njoins as usize);
        self.cx.rules[nr] = Rule {
            name,
            salience: salience.0,
            salience_expr: salience.1,
            root: 0,
            terminal: prev,
            rhs: self.cx.exprs[rhs as usize].first,
            npat: b.depth,
            nlocals: self.nlocals.min(255) as u8,
            next_disjunct: NONE,
            next_at_join: NONE,
            root_sensitive: b.ces[first as usize].kind != JoinKind::Positive,
            deleted: false,
            text: NONE,
        };
        self.cx.st.nrules += 1;
        self.cx.note_hw(Pool::Rules, nr + 1);
        Ok(nr as Ix)
    }
}

/// New joins already primed while defining a rule (disjuncts share joins).
struct Primed {
    ids: [Ix; 64],
    n: usize,
}

/// Fields of one pattern remembered for ordering alpha nodes like CLIPS's pattern
/// network; more are accepted but not used for ordering.
const MAX_FIELDS: usize = 16;

struct PatBuild {
    /// (locator, alpha test or NONE, multifield element) per field, in parse order;
    /// an empty multislot is one entry with element `ZERO_LEN`.
    fields: [(Ix, Ix, bool); MAX_FIELDS],
    nfields: usize,
    desc: Ix,
    dlast: Ix,
    atests: Ix,
    alast: Ix,
    jtests: Ix,
    jlast: Ix,
    marks: u8,
    rhash: [Ix; MAX_RHASH],
    nrhash: usize,
    /// Variables bound earlier that this pattern equates with a field: (pattern,
    /// locator) of the binding, (locator, descriptor) of the field (`classify`).
    aliases: [(u8, Ix, Ix, Ix); 8],
    naliases: usize,
}

impl PatBuild {
    fn record(&mut self, locv: Ix, test: Ix, multi: bool) {
        if self.nfields < MAX_FIELDS {
            self.fields[self.nfields] = (locv, test, multi);
            self.nfields += 1;
        }
    }
}

/// A pattern's levels in CLIPS's pattern network (field locators and test hashes).
struct NetPath {
    locs: [Ix; PATH_LEN],
    tests: [Ix; PATH_LEN],
    len: usize,
    /// Levels past `PATH_LEN` were dropped.
    cut: bool,
}

impl NetPath {
    /// Adds one field's nodes (a selector first, if any); returns how many.
    fn field(&mut self, l: Ix, selector: Option<Ix>, test: Ix) -> usize {
        let before = self.len;
        for t in selector.into_iter().chain(Some(test)) {
            if self.len < PATH_LEN {
                self.locs[self.len] = l;
                self.tests[self.len] = t;
                self.len += 1;
            } else {
                self.cut = true;
            }
        }
        self.len - before
    }
}

/// Element locator of an empty multislot's zero-length node (never a real element).
const ZERO_LEN: u8 = 0xFE;
/// Path test of a selector node on a single-field slot (`expr_hash` is never 1).
const SELECTOR: Ix = 1;

/// Depth-first order of pattern-network paths: at the first differing level the
/// newer node (higher id) goes first; a path goes before its extensions.
fn key_before(a: &[Ix], b: &[Ix]) -> bool {
    for (x, y) in a.iter().zip(b.iter()) {
        if x != y {
            return x > y;
        }
    }
    a.len() < b.len()
}

/// A node's `aux` as far as it is part of the expression: a query slot read
/// (`slot_value_of`) and a query variable's template name (`queries::template_of`)
/// keep a lookup cache there, which a run fills in and which must not keep an
/// identical pattern or test from sharing the node.
fn shape_aux(x: crate::expr::Expr) -> u8 {
    if matches!(x.op, Op::QSlot | Op::Sym) {
        0
    } else {
        x.aux
    }
}

fn mix16(h: u32, x: u32) -> u32 {
    (h ^ x).wrapping_mul(0x0100_0193).rotate_left(7)
}
