//! defrule: LHS conditional elements compiled into alpha nodes and joins, RHS actions.

use super::{PResult, Parser, Scope, VarKind};
use crate::engine::cap;
use crate::error::Pool;
use crate::expr::{loc, Expr, Op};
use crate::lexer::{Tok, Token};
use crate::rete::{AlphaNode, Join, JoinKind, MAX_MARKS, MAX_PATTERNS, THIS_PATTERN};
use crate::rule::Rule;
use crate::value::{SymId, Value, NONE};

/// Most `or` CEs in one rule.
const MAX_ORS: usize = 8;

#[derive(Clone, Copy)]
struct Ce {
    kind: JoinKind,
    alpha: u16,
    /// Join tests (chain) and post tests (after not/exists).
    jtests: u16,
    jlast: u16,
    post: u16,
    plast: u16,
}

const CE_EMPTY: Ce = Ce { kind: JoinKind::Test, alpha: NONE, jtests: NONE, jlast: NONE, post: NONE, plast: NONE };

struct Build {
    ces: [Ce; MAX_PATTERNS],
    n: usize,
    /// `or` branch choice per `or` met, and how many branches each had.
    choice: [u8; MAX_ORS],
    counts: [u8; MAX_ORS],
    nor: usize,
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
            Tok::Symbol(s) => s,
            _ => return Err(self.err(nt, "a defrule name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
        let body_lex = self.save();
        let first_new_rule = self.cx.st.nrules;
        let first_new_alpha = self.cx.st.nalpha;
        let first_new_join = self.cx.st.njoins;
        let mut b = Build {
            ces: [CE_EMPTY; MAX_PATTERNS],
            n: 0,
            choice: [0; MAX_ORS],
            counts: [0; MAX_ORS],
            nor: 0,
        };
        let mut prev_rule = NONE;
        loop {
            self.restore(body_lex.clone());
            self.nvars = 0;
            self.nlocals = 0;
            b.n = 0;
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
        // source text for ppdefrule
        let end = self.lex.pos();
        let text = &self.lex.source()[start..end];
        if let Ok(id) = self.cx.intern(text) {
            self.cx.rules[first_new_rule as usize].text = id;
        }
        // a redefinition replaces the old rule
        for r in 0..first_new_rule {
            if self.cx.rules[r as usize].name == sym && !self.cx.rules[r as usize].deleted {
                self.cx.remove_rule(r);
            }
        }
        // match the new rule(s) against existing facts: fill new alpha memories
        // (no successors yet), then hook the new joins up and feed them
        for a in first_new_alpha..self.cx.st.nalpha {
            let r = self.cx.prime_alpha(a);
            self.map_prime_err(r, nt)?;
        }
        for j in first_new_join..self.cx.st.njoins {
            let a = self.cx.joins[j as usize].alpha;
            if a != NONE {
                self.cx.joins[j as usize].alpha_next = self.cx.alphas[a as usize].succ;
                self.cx.alphas[a as usize].succ = j;
            }
        }
        for j in first_new_join..self.cx.st.njoins {
            if self.cx.joins[j as usize].parent < first_new_join {
                let r = self.cx.prime_join(j);
                self.map_prime_err(r, nt)?;
            }
        }

        Ok(())
    }

    fn map_prime_err(&self, r: Result<(), crate::error::EvalError>, at: Token<'s>) -> PResult<()> {
        match r {
            Ok(()) => Ok(()),
            Err(e) => {
                let c = match e.kind {
                    crate::error::EvalErrorKind::Capacity(c) => c,
                    _ => cap(Pool::Tokens, self.cx.tokens.len()),
                };
                Err(self.cap_err(at, c))
            }
        }
    }

    /// One disjunct: LHS (with the current or-choices), RHS, then the network.
    fn rule_body(&mut self, name: SymId, b: &mut Build) -> PResult<u16> {
        let mut salience = 0i32;
        // (declare (salience N))
        if self.peek().tok == Tok::LParen {
            let save = self.save();
            self.next();
            if self.peek().tok == Tok::Symbol("declare") {
                self.next();
                salience = self.declare()?;
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
                Tok::Eof | Tok::Bad | Tok::RParen => return Err(self.err(t, "'=>' or a conditional element")),
                _ => self.ce(b, Ctx::Top)?,
            }
            if self.peek().tok == Tok::LParen {
                // a declare after the first CE is also allowed by CLIPS
                let save = self.save();
                self.next();
                if self.peek().tok == Tok::Symbol("declare") {
                    self.next();
                    salience = self.declare()?;
                } else {
                    self.restore(save);
                }
            }
        }
        if b.n == 0 {
            // empty LHS: a test join with no tests (CLIPS shows it as `*`)
            b.ces[0] = CE_EMPTY;
            b.n = 1;
        }
        self.scope = Scope::Frame;
        let rhs = self.action_block()?;
        self.build_rule(name, salience, b, rhs)
    }

    fn declare(&mut self) -> PResult<i32> {
        let mut sal = 0;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => return Ok(sal),
                Tok::LParen => {
                    let kw = self.next();
                    match kw.tok {
                        Tok::Symbol("salience") => {
                            let save = self.scope;
                            self.scope = Scope::Frame;
                            let e = self.parse_expr()?;
                            self.scope = save;
                            let v = self.cx.eval(e);
                            sal = match v {
                                Ok(Value::Int(i)) if (-10000..=10000).contains(&i) => i as i32,
                                _ => return Err(self.err(kw, "an integer salience between -10000 and 10000")),
                            };
                            self.expect_rparen("')' after the salience")?;
                        }
                        Tok::Symbol("auto-focus") => {
                            self.next();
                            self.expect_rparen("')'")?;
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
        let t = self.next();
        match t.tok {
            Tok::SfVar(fv) => {
                let arrow = self.next();
                if arrow.tok != Tok::Symbol("<-") {
                    return Err(self.err(arrow, "'<-' after a fact-address variable"));
                }
                if ctx != Ctx::Top {
                    return Err(self.err(t, "a pattern (fact addresses cannot be bound inside not/exists)"));
                }
                self.expect_lparen("'(' starting a pattern")?;
                self.pattern(b, ctx, Some((t, fv)))
            }
            Tok::LParen => {
                let h = self.peek();
                match h.tok {
                    Tok::Symbol("not") => {
                        self.next();
                        if ctx != Ctx::Top {
                            return Err(self.err(h, "a pattern (nested not/exists is not supported)"));
                        }
                        let saved = self.nvars;
                        self.ce(b, Ctx::Not)?;
                        self.nvars = saved;
                        self.expect_rparen("')' closing not (one CE only)")
                    }
                    Tok::Symbol("exists") => {
                        self.next();
                        if ctx != Ctx::Top {
                            return Err(self.err(h, "a pattern (nested not/exists is not supported)"));
                        }
                        let saved = self.nvars;
                        self.ce(b, Ctx::Exists)?;
                        self.nvars = saved;
                        self.expect_rparen("')' closing exists (one pattern supported)")
                    }
                    Tok::Symbol("and") | Tok::Symbol("logical") => {
                        self.next();
                        loop {
                            let p = self.peek();
                            match p.tok {
                                Tok::RParen => {
                                    self.next();
                                    return Ok(());
                                }
                                Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                                _ => {
                                    if ctx != Ctx::Top {
                                        // only a single CE inside not/exists
                                        self.ce(b, ctx)?;
                                        let q = self.peek();
                                        if q.tok != Tok::RParen {
                                            return Err(self.err(q, "')' (not/exists over several CEs is not supported)"));
                                        }
                                    } else {
                                        self.ce(b, ctx)?;
                                    }
                                }
                            }
                        }
                    }
                    Tok::Symbol("or") => {
                        self.next();
                        if ctx != Ctx::Top {
                            return Err(self.err(h, "a pattern (or inside not/exists is not supported)"));
                        }
                        let k = b.nor;
                        if k >= MAX_ORS {
                            return Err(self.err(h, "fewer or CEs in one rule"));
                        }
                        b.nor += 1;
                        let mut branch = 0u8;
                        loop {
                            let p = self.peek();
                            match p.tok {
                                Tok::RParen => {
                                    self.next();
                                    break;
                                }
                                Tok::Eof | Tok::Bad => return Err(self.err(p, "')'")),
                                _ => {
                                    if branch == b.choice[k] {
                                        self.ce(b, ctx)?;
                                    } else {
                                        self.skip_balanced()?;
                                    }
                                    branch += 1;
                                }
                            }
                        }
                        if branch == 0 {
                            return Err(self.err(h, "at least one CE inside or"));
                        }
                        b.counts[k] = branch;
                        Ok(())
                    }
                    Tok::Symbol("test") => {
                        self.next();
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

    fn attach_test_ce(&mut self, b: &mut Build, e: u16, at: Token<'s>) -> PResult<()> {
        if b.n == 0 {
            if b.n >= MAX_PATTERNS {
                return Err(self.err(at, "fewer conditional elements"));
            }
            b.ces[0] = CE_EMPTY;
            b.n = 1;
            Self::chain_push(self, &mut b.ces[0].jtests, &mut b.ces[0].jlast, e);
            return Ok(());
        }
        let last = b.n - 1;
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

    fn chain_push(&mut self, head: &mut u16, last: &mut u16, e: u16) {
        if *head == NONE {
            *head = e;
        } else {
            self.cx.exprs[*last as usize].next = e;
        }
        *last = e;
    }

    /// A pattern CE after its `(`.
    fn pattern(&mut self, b: &mut Build, ctx: Ctx, factvar: Option<(Token<'s>, &'s str)>) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) if !matches!(s, "test" | "not" | "and" | "or" | "exists" | "logical") => s,
            _ => return Err(self.err(nt, "a template or relation name")),
        };
        if b.n >= MAX_PATTERNS {
            return Err(self.err(nt, "fewer conditional elements"));
        }
        let p = b.n as u8;
        let sym = cap!(self, self.cx.intern(name))?;
        let tmpl = match self.cx.find_template(sym) {
            Some(t) => t,
            None => cap!(self, self.cx.implied_template(sym))?,
        };
        if let Some((ft, fv)) = factvar {
            self.add_var(ft, fv, VarKind::Pat { pat: p, loc: loc::FACT, desc: NONE }, false)?;
        }
        self.scope = Scope::Lhs;
        let mut pb = PatBuild { desc: NONE, dlast: NONE, atests: NONE, alast: NONE, jtests: NONE, jlast: NONE, marks: 0 };
        if self.cx.templates[tmpl as usize].implied {
            self.multislot_fields(&mut pb, p, 0, nt)?;
        } else {
            loop {
                let t = self.next();
                match t.tok {
                    Tok::RParen => break,
                    Tok::LParen => {
                        let st = self.next();
                        let sname = match st.tok {
                            Tok::Symbol(s) => s,
                            _ => return Err(self.err(st, "a slot name")),
                        };
                        let ssym = cap!(self, self.cx.intern(sname))?;
                        let slot = match self.cx.find_slot(tmpl, ssym) {
                            Some(s) => s,
                            None => return Err(self.err(st, "a slot of the template")),
                        };
                        if self.cx.slot_def(tmpl, slot).multi {
                            self.multislot_fields(&mut pb, p, slot as u8, st)?;
                        } else {
                            let (multi, test) = self.field(p, loc::new(slot as u8, loc::SINGLE), NONE)?;
                            if multi {
                                return Err(self.err(st, "a single-field constraint for a single-field slot"));
                            }
                            if let Some(e) = test {
                                self.classify(&mut pb, p, e);
                            }
                            self.expect_rparen("')' closing the slot (one field in a single-field slot)")?;
                        }
                    }
                    _ => return Err(self.err(t, "'(' and a slot name, or ')'")),
                }
            }
        }
        // share an identical alpha node or make a new one
        let alpha = self.find_or_make_alpha(tmpl, &pb, nt)?;
        let kind = match ctx {
            Ctx::Top => JoinKind::Positive,
            Ctx::Not => JoinKind::Negative,
            Ctx::Exists => JoinKind::Exists,
        };
        b.ces[b.n] = Ce { kind, alpha, jtests: pb.jtests, jlast: pb.jlast, post: NONE, plast: NONE };
        b.n += 1;
        Ok(())
    }

    /// Elements of a multislot (or of an ordered fact) until `)`.
    fn multislot_fields(&mut self, pb: &mut PatBuild, p: u8, slot: u8, at: Token<'s>) -> PResult<()> {
        let ps = cap!(self, self.cx.push_expr(Expr::new(Op::PatSlot, pb.marks, slot as u16)))?;
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
                    let el = cap!(self, self.cx.push_expr(Expr::new(Op::PatElem, u8::from(multi), i as u16)))?;
                    self.cx.append_child(ps, el);
                    if let Some(e) = test {
                        self.classify(pb, p, e);
                    }
                    multis += u8::from(multi);
                    i += 1;
                }
            }
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

    /// Puts a field test in the alpha node (if it needs only this pattern) or the join.
    fn classify(&mut self, pb: &mut PatBuild, p: u8, e: u16) {
        if self.refs_earlier(e, p) {
            let (mut h, mut l) = (pb.jtests, pb.jlast);
            Self::chain_push(self, &mut h, &mut l, e);
            pb.jtests = h;
            pb.jlast = l;
        } else {
            self.retarget(e, p);
            let (mut h, mut l) = (pb.atests, pb.alast);
            Self::chain_push(self, &mut h, &mut l, e);
            pb.atests = h;
            pb.alast = l;
        }
    }

    fn refs_earlier(&self, e: u16, p: u8) -> bool {
        let x = self.cx.exprs[e as usize];
        if x.op == Op::PatVar {
            return x.aux != p && x.aux != THIS_PATTERN;
        }
        let mut c = if matches!(x.op, Op::Int | Op::Float) { NONE } else { x.first };
        while c != NONE {
            if self.refs_earlier(c, p) {
                return true;
            }
            c = self.cx.exprs[c as usize].next;
        }
        false
    }

    fn retarget(&mut self, e: u16, p: u8) {
        let x = self.cx.exprs[e as usize];
        if x.op == Op::PatVar {
            if x.aux == p {
                self.cx.exprs[e as usize].aux = THIS_PATTERN;
            }
            return;
        }
        let mut c = if matches!(x.op, Op::Int | Op::Float) { NONE } else { x.first };
        while c != NONE {
            self.retarget(c, p);
            c = self.cx.exprs[c as usize].next;
        }
    }

    fn this_field(&mut self, p: u8, locv: u16, desc: u16) -> PResult<u16> {
        let e = self.cx.push_expr(Expr { first: desc, ..Expr::new(Op::PatVar, p, locv) });
        cap!(self, e)
    }

    fn node2(&mut self, op: Op, a: u16, b: u16) -> PResult<u16> {
        let n = cap!(self, self.cx.push_expr(Expr::new(op, 0, 0)))?;
        self.cx.exprs[n as usize].first = a;
        if b != NONE {
            self.cx.exprs[a as usize].next = b;
        }
        Ok(n)
    }

    /// One field constraint: returns (is multifield, test expression).
    fn field(&mut self, p: u8, locv: u16, desc: u16) -> PResult<(bool, Option<u16>)> {
        let t = self.peek();
        let mut multi = false;
        let mut bound_first = false;
        match t.tok {
            Tok::SfVar(name) | Tok::MfVar(name) if self.find_var(name).is_none() => {
                self.next();
                multi = matches!(t.tok, Tok::MfVar(_));
                self.add_var(t, name, VarKind::Pat { pat: p, loc: locv, desc }, multi)?;
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

    fn or_constraint(&mut self, p: u8, locv: u16, desc: u16, multi: &mut bool) -> PResult<u16> {
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

    fn and_constraint(&mut self, p: u8, locv: u16, desc: u16, multi: &mut bool) -> PResult<u16> {
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

    fn term(&mut self, p: u8, locv: u16, desc: u16, multi: &mut bool) -> PResult<u16> {
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
                if matches!(t.tok, Tok::MfVar(_)) {
                    *multi = true;
                }
                let v = match self.find_var(name) {
                    Some(_) => self.var_ref(t, name, false)?,
                    None => return Err(self.err(t, "a variable bound before (first use must lead the constraint)")),
                };
                let this = self.this_field(p, locv, desc)?;
                self.node2(Op::Eq2, this, v)
            }
            _ => match self.literal(t)? {
                Some(c) => {
                    let this = self.this_field(p, locv, desc)?;
                    self.node2(Op::Eq2, this, c)
                }
                None => Err(self.err(t, "a constraint (literal, variable, ~, :( ) or =( ))")),
            },
        }
    }

    fn find_or_make_alpha(&mut self, tmpl: u16, pb: &PatBuild, at: Token<'s>) -> PResult<u16> {
        let mut a = self.cx.templates[tmpl as usize].alpha_head;
        while a != NONE {
            let n = self.cx.alphas[a as usize];
            if n.live && self.chain_eq(n.desc, pb.desc) && self.chain_eq(n.tests, pb.atests) {
                return Ok(a);
            }
            a = n.next_in_tmpl;
        }
        let n = self.cx.st.nalpha as usize;
        if n >= self.cx.alphas.len() {
            let c = cap(Pool::AlphaNodes, self.cx.alphas.len());
            return Err(self.cap_err(at, c));
        }
        self.cx.alphas[n] = AlphaNode {
            tmpl,
            desc: pb.desc,
            tests: pb.atests,
            next_in_tmpl: self.cx.templates[tmpl as usize].alpha_head,
            succ: NONE,
            mem: NONE,
            mem_tail: NONE,
            nmarks: pb.marks,
            live: true,
        };
        self.cx.templates[tmpl as usize].alpha_head = n as u16;
        self.cx.st.nalpha += 1;
        self.cx.note_hw(Pool::AlphaNodes, n + 1);
        Ok(n as u16)
    }

    fn chain_eq(&self, mut a: u16, mut b: u16) -> bool {
        while a != NONE && b != NONE {
            if !self.expr_eq(a, b) {
                return false;
            }
            a = self.cx.exprs[a as usize].next;
            b = self.cx.exprs[b as usize].next;
        }
        a == NONE && b == NONE
    }

    fn expr_eq(&self, a: u16, b: u16) -> bool {
        let (x, y) = (self.cx.exprs[a as usize], self.cx.exprs[b as usize]);
        if x.op != y.op || x.aux != y.aux || x.data != y.data {
            return false;
        }
        match x.op {
            Op::Int | Op::Float => self.cx.const_value(a).same(self.cx.const_value(b)),
            Op::PatVar => {
                (x.first == NONE && y.first == NONE)
                    || (x.first != NONE && y.first != NONE && {
                        let (p, q) = (self.cx.exprs[x.first as usize], self.cx.exprs[y.first as usize]);
                        p.aux == q.aux && p.data == q.data && self.chain_eq(p.first, q.first)
                    })
            }
            _ => self.chain_eq(x.first, y.first),
        }
    }

    /// Creates the rule and its joins (the root token comes later, in `defrule`).
    fn build_rule(&mut self, name: SymId, salience: i32, b: &Build, rhs: u16) -> PResult<u16> {
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
        let mut prev = 0u16;
        for (i, ce) in b.ces[..b.n].iter().enumerate() {
            {
                // share an identical join under the same parent (CLIPS does)
                let mut c = self.cx.joins[prev as usize].first_child;
                let mut found = NONE;
                while c != NONE {
                    let cj = self.cx.joins[c as usize];
                    if cj.refs > 0
                        && cj.kind == ce.kind
                        && cj.alpha == ce.alpha
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
                    prev = found;
                    continue;
                }
            }
            let j = self.cx.st.njoins;
            self.cx.st.njoins += 1;
            self.cx.joins[j as usize] = Join {
                kind: ce.kind,
                depth: i as u8,
                rule: NONE,
                parent: prev,
                first_child: NONE,
                next_sibling: self.cx.joins[prev as usize].first_child,
                refs: 1,
                alpha: ce.alpha,
                tests: ce.jtests,
                post: ce.post,
                alpha_next: NONE,
                mem: NONE,
            };
            self.cx.joins[prev as usize].first_child = j;
            prev = j;
        }
        // the rule's end node
        let term = self.cx.st.njoins;
        self.cx.st.njoins += 1;
        self.cx.joins[term as usize] = Join {
            kind: JoinKind::Terminal,
            depth: b.n as u8,
            rule: nr as u16,
            parent: prev,
            next_sibling: self.cx.joins[prev as usize].first_child,
            refs: 1,
            ..Join::EMPTY
        };
        self.cx.joins[prev as usize].first_child = term;
        let prev = term;
        self.cx.note_hw(Pool::Joins, self.cx.st.njoins as usize);
        self.cx.rules[nr] = Rule {
            name,
            salience,
            root: 0,
            terminal: prev,
            rhs: self.cx.exprs[rhs as usize].first,
            npat: b.n as u8,
            nlocals: self.nlocals.min(255) as u8,
            next_disjunct: NONE,
            next_at_join: NONE,
            root_sensitive: b.ces[0].kind != JoinKind::Positive,
            deleted: false,
            text: NONE,
        };
        self.cx.st.nrules += 1;
        self.cx.note_hw(Pool::Rules, nr + 1);
        Ok(nr as u16)
    }
}

struct PatBuild {
    desc: u16,
    dlast: u16,
    atests: u16,
    alast: u16,
    jtests: u16,
    jlast: u16,
    marks: u8,
}
