//! Fact specifications (`assert`, `deffacts`) and `modify`/`duplicate`, with the checks
//! CLIPS makes when it parses them rather than when it runs them: known slots, a slot
//! given once, one value in a single-field slot, literals that fit the slot's type and
//! allowed values, and every `(default ?NONE)` slot given.

use super::{PResult, Parser, Scope};
use crate::error::{LoadDetail, LoadError, Restriction};
use crate::expr::{loc, Expr, Op};
use crate::lexer::{Tok, Token};
use crate::template::{DefaultKind, SlotDef};
use crate::value::Ix;
use crate::value::NONE;

impl<'s> Parser<'s, '_, '_> {
    pub(super) fn parse_assert(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("assert")?;
        let mut n = 0;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen if n > 0 => return Ok(node),
                Tok::LParen => {
                    let spec = self.fact_spec()?;
                    self.cx.append_child(node, spec);
                    n += 1;
                }
                // CLIPS names what it was reading: the command when it has no fact,
                // its facts otherwise
                Tok::RParen => return Err(self.syntax_of(t, "a fact to assert", "assert command")),
                _ => return Err(self.syntax_of(t, "a fact to assert", "RHS patterns")),
            }
        }
    }

    /// CLIPS's syntax error naming the `part` it was reading, at token `t` (out of
    /// line: the fact readers it is called from stay small enough to inline).
    #[cold]
    #[inline(never)]
    pub fn syntax_of(
        &self,
        t: crate::lexer::Token<'s>,
        expected: &'static str,
        part: &'static str,
    ) -> crate::error::LoadError {
        let mut e = self.err(t, expected);
        e.detail = crate::error::LoadDetail::SyntaxOf { part };
        e.echo_end = t.end as u32;
        e
    }

    /// `(name ...)` after the `(`: a `FactSpec` node.
    pub fn fact_spec(&mut self) -> PResult<Ix> {
        let nt = self.next();
        let (module, name) = match nt.tok {
            // `=` and `:` are operators, never a relation name
            Tok::Symbol(s) if super::has_module_sep(s) => return Err(self.module_specifier(nt)),
            // CLIPS keeps the conditional elements' keywords out of relation names
            Tok::Symbol(
                "not" | "and" | "or" | "test" | "exists" | "forall" | "logical" | "object",
            ) => return Err(self.relation_keyword(nt)),
            Tok::Symbol(s)
                if s != "=" && s != ":" && crate::value::instance_name_body(s).is_none() =>
            {
                (self.current_module(), s)
            }
            _ => {
                return Err(self.syntax_of(
                    nt,
                    "a template or relation name",
                    "first field of a RHS pattern",
                ))
            }
        };
        let sym = cap!(self, self.cx.intern(name))?;
        let tmpl = match self.template_in(module, sym) {
            Some(t) => t,
            None => {
                #[cfg(feature = "modules")]
                self.implied_conflict(nt, module, sym)?;
                let t = cap!(self, self.cx.implied_template(sym))?;
                self.note_implied();
                t
            }
        };
        let spec = cap!(self, self.cx.push_expr(Expr::new(Op::FactSpec, 0, tmpl)))?;
        if self.cx.templates[tmpl as usize].implied {
            let sv = cap!(self, self.cx.push_expr(Expr::new(Op::SlotVal, 0, 0)))?;
            self.cx.append_child(spec, sv);
            // the last value linked (appending through it: a long fact stays linear)
            let mut last = NONE;
            loop {
                let t = self.peek();
                match t.tok {
                    Tok::RParen => {
                        self.next();
                        break;
                    }
                    Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                    _ => {
                        let v = self.fact_value("RHS patterns")?;
                        last = self.cx.append_after(sv, last, v);
                    }
                }
            }
            return Ok(spec);
        }
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => {
                    let st = self.next();
                    if !matches!(st.tok, Tok::Symbol(_)) {
                        return Err(self.syntax_of(st, "a slot name", "deftemplate pattern"));
                    }
                    let slot = self.slot_of(tmpl, st)?;
                    if self.slot_given(spec, slot) {
                        return Err(self.slot_twice(st, "a slot not given twice"));
                    }
                    let sv = cap!(self, self.cx.push_expr(Expr::new(Op::SlotVal, 0, slot)))?;
                    let def = self.cx.slot_def(tmpl, slot);
                    self.slot_values(sv, &def, st, "assert")?;
                    self.cx.insert_slot_val(spec, sv);
                }
                _ => return Err(self.syntax_of(t, "'(' and a slot name", "deftemplate pattern")),
            }
        }
        // CLIPS reports a missing required slot at the template name
        let t = self.cx.templates[tmpl as usize];
        #[cfg(feature = "extras")]
        let in_deffacts = self.construct == "deffacts";
        for slot in 0..t.nslots {
            let def = self.cx.slot_def(tmpl, slot);
            if def.default_kind == DefaultKind::Required && !self.slot_given(spec, slot) {
                let mut e = self.err(nt, "a value for every slot declared (default ?NONE)");
                e.detail = LoadDetail::RequiredSlot { slot: def.name };
                return Err(e);
            }
            #[cfg(feature = "extras")]
            if in_deffacts && self.cx.derives_dummy_fact(&def) && !self.slot_given(spec, slot) {
                // CLIPS takes the `<Dummy Fact>` default for a variable there
                return Err(self.deffacts_variable(
                    nt,
                    "a value for each FACT-ADDRESS slot (no <Dummy Fact> in deffacts)",
                ));
            }
        }
        Ok(spec)
    }

    /// `[PATTERN1]` at a fact's relation name that is a conditional element keyword
    /// (CLIPS shows a construct up to it).
    #[cold]
    #[inline(never)]
    fn relation_keyword(&self, nt: Token<'s>) -> LoadError {
        let mut e = self.err(
            nt,
            "a relation name that is not a conditional element keyword",
        );
        e.detail = LoadDetail::RelationKeyword;
        if matches!(self.construct, "defrule" | "deffunction" | "deffacts") {
            e.echo_end = nt.end as u32;
        }
        e
    }

    /// CLIPS's syntax error naming `part` at a constraint's `~`, `&` or `|` (token `t`)
    /// in a fact, shown one space after the value before it.
    #[cold]
    #[inline(never)]
    fn constraint_in_fact(&self, t: Token<'s>, part: &'static str) -> LoadError {
        let mut e = self.syntax_of(t, "a value (a fact has no constraints)", part);
        e.echo_tail = crate::error::EchoTail::Spaced;
        e
    }

    /// One value of a fact: an expression, or `=(call)`, CLIPS's older way of writing
    /// a call's value there (the `=` is dropped; after it only a call may come). A
    /// constraint's `~`, `&` or `|` is CLIPS's syntax error naming `part`.
    #[inline]
    fn fact_value(&mut self, part: &'static str) -> PResult<Ix> {
        let t = self.peek();
        if matches!(
            t.tok,
            Tok::Amp | Tok::Bar | Tok::Tilde | Tok::SfWild | Tok::MfWild
        ) {
            return Err(self.constraint_in_fact(t, part));
        }
        if self.constant_facts {
            let t = self.peek();
            if matches!(t.tok, Tok::LParen | Tok::Symbol("=")) {
                return Err(self.err(t, "a constant (load-facts calls no functions)"));
            }
        }
        if matches!(self.peek().tok, Tok::Symbol("=")) {
            self.next();
            let t = self.peek();
            if t.tok != Tok::LParen {
                // (CLIPS shows the token glued to the `=`)
                let mut e = self.syntax_of(t, "a function call after '='", "function calls");
                e.echo_tail = crate::error::EchoTail::Glued;
                return Err(e);
            }
        }
        self.parse_expr()
    }

    /// The index of the slot named by token `st` in deftemplate `tmpl`.
    pub(super) fn slot_of(&mut self, tmpl: Ix, st: Token<'s>) -> PResult<Ix> {
        let sname = match st.tok {
            Tok::Symbol(s) => s,
            _ => return Err(self.err(st, "a slot name")),
        };
        let ssym = cap!(self, self.cx.intern(sname))?;
        match self.cx.find_slot(tmpl, ssym) {
            Some(s) => Ok(s),
            None => {
                let mut e = self.err(st, "a slot of the template");
                e.detail = LoadDetail::UnknownSlot {
                    template: self.cx.templates[tmpl as usize].name,
                    whole: false,
                };
                // CLIPS shows a construct up to the slot name (not a fact that
                // `assert-string` or `load-facts` reads)
                if matches!(self.construct, "defrule" | "deffunction" | "deffacts") {
                    e.echo_end = st.end as u32;
                }
                Err(e)
            }
        }
    }

    /// `[PRNTUTIL5]` at a slot name given a second time (CLIPS shows a construct up
    /// to it).
    pub(super) fn slot_twice(&self, st: Token<'s>, expected: &'static str) -> LoadError {
        let mut e = self.err(st, expected);
        e.detail = LoadDetail::SlotTwice;
        if self.construct != "command" {
            e.echo_end = st.end as u32;
        }
        e
    }

    /// `[MODULDEF1]` at a fact's or pattern's relation name with a module specifier
    /// (`MAIN::t`): CLIPS 6.30 takes none there, not even the current module's.
    pub(super) fn module_specifier(&self, nt: Token<'s>) -> LoadError {
        let mut e = self.err(nt, "a relation name without a module specifier");
        e.detail = LoadDetail::ModuleSpecifier;
        if self.construct != "command" {
            e.echo_end = nt.end as u32;
        }
        e
    }

    /// Whether a `SlotVal` child of `node` already has `data == key`.
    fn slot_given(&self, node: Ix, key: Ix) -> bool {
        let mut c = self.cx.exprs[node as usize].first;
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            if x.op == Op::SlotVal && x.data == key {
                return true;
            }
            c = x.next;
        }
        false
    }

    /// The values of one slot up to its `)`, appended to `sv`. A single-field slot takes
    /// exactly one (a second is reported where it starts); each literal must fit the
    /// slot's type and allowed values (reported at the literal).
    fn slot_values(
        &mut self,
        sv: Ix,
        def: &SlotDef,
        st: Token<'s>,
        command: &'static str,
    ) -> PResult<()> {
        let mut n = 0 as Ix;
        // values that are literals (one field each), and whether others (variables,
        // calls: any number of fields) came too
        let mut literals = 0i64;
        let mut open = false;
        // CLIPS checks the values once the slot is read (and shows a rule up to there)
        let mut bad = None;
        let close = loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => {
                    self.next();
                    break t;
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                _ if !def.multi && n == 1 => {
                    // CLIPS shows the second value's first token glued to the first
                    let mut e = self.err(t, "one value for the single-field slot");
                    e.detail = LoadDetail::SingleSlot { slot: def.name };
                    e.echo_end = t.end as u32;
                    e.echo_tail = crate::error::EchoTail::Glued;
                    return Err(e);
                }
                _ => {
                    let v = self.fact_value("deftemplate pattern")?;
                    if let Some(what) = self.literal_violation(def, v) {
                        let mut e = self.err(t, expected(what));
                        e.detail = LoadDetail::Constraint {
                            command,
                            what,
                            slot: def.name,
                            range: def.range,
                        };
                        bad = bad.or(Some(e));
                    }
                    if self.is_literal(v) {
                        literals += 1;
                    } else {
                        open = true;
                    }
                    self.cx.append_child(sv, v);
                    n += 1;
                }
            }
        };
        if bad.is_none() && def.multi && !self.count_fits(def, literals, open) {
            let mut e = self.err(st, "as many values as the slot's cardinality allows");
            e.detail = LoadDetail::Constraint {
                command,
                what: Restriction::Cardinality,
                slot: def.name,
                range: def.range,
            };
            bad = Some(e);
        }
        if let Some(mut e) = bad {
            e.echo_end = close.end as u32;
            return Err(e);
        }
        if !def.multi && n != 1 {
            // no value: CLIPS shows the slot as `(a )`
            let mut e = self.err(st, "exactly one value for a single-field slot");
            e.detail = LoadDetail::SingleSlot { slot: def.name };
            e.echo_end = st.end as u32;
            e.echo_tail = crate::error::EchoTail::SpaceBefore;
            return Err(e);
        }
        Ok(())
    }

    /// Whether expression node `e` is a literal constant.
    pub(super) fn is_literal(&self, e: Ix) -> bool {
        matches!(
            self.cx.exprs[e as usize].op,
            Op::Int | Op::Float | Op::Sym | Op::Str
        )
    }

    /// Whether `literals` fields, plus any number more when `open`, can fit a
    /// multislot's cardinality.
    pub(super) fn count_fits(&self, def: &SlotDef, literals: i64, open: bool) -> bool {
        let (min, max) = self.cx.cardinality_of(def);
        literals <= max && (open || literals >= min)
    }

    /// How a literal expression node breaks a slot's restrictions (None for a literal
    /// that fits, and for anything that is not a literal: checked when it runs).
    pub(super) fn literal_violation(&self, def: &SlotDef, e: Ix) -> Option<Restriction> {
        if !self.is_literal(e) {
            return None;
        }
        let v = self.cx.const_value(e);
        self.cx
            .check_atom_def(def, v)
            .err()
            .map(|e| e.restriction())
    }

    /// The deftemplate of the fact a `modify`/`duplicate` target expression names, when
    /// the parser knows it: a fact-address variable bound to a deftemplate pattern.
    fn target_template(&self, target: Ix) -> Option<Ix> {
        let x = self.cx.exprs[target as usize];
        if x.op != Op::PatVar || x.data != loc::FACT {
            return None;
        }
        let tmpl = *self.pat_tmpl.get(x.aux as usize)?;
        if tmpl == NONE || self.cx.templates[tmpl as usize].implied {
            return None;
        }
        Some(tmpl)
    }

    /// `[ARGACCES5]`: CLIPS takes only a variable (or, at top level, a fact index) as
    /// the fact `modify`/`duplicate` (`func`) changes; anything else is refused while
    /// reading, a construct shown up to the target's first token (`at`).
    fn modify_target_error(&self, func: &'static str, at: Token<'s>) -> LoadError {
        let mut e = self.err(at, "a fact-address variable");
        e.detail = LoadDetail::ArgType {
            func,
            arg: 1,
            expected: "non-void return value",
        };
        if self.scope == Scope::TopLevel {
            // a command at the prompt is not shown
            e.echo_end = 0;
        } else if at.tok == Tok::RParen {
            // no argument: CLIPS shows `(modify )`
            e.echo_end = at.start as u32;
            e.echo_tail = crate::error::EchoTail::SpaceBefore;
        } else {
            e.echo_end = at.end as u32;
        }
        e
    }

    /// `(modify ?f (slot v...)...)`: slot values carry the slot *name* symbol (the
    /// template is known only at run time in general). When `?f` is bound to a
    /// deftemplate pattern, slots and literal values are checked now, as CLIPS does.
    pub(super) fn parse_modify(&mut self, name: &'static str) -> PResult<Ix> {
        let node = self.builtin_call(name)?;
        let target_at = self.peek();
        let in_construct = self.scope != Scope::TopLevel;
        // (a call is refused at its `(`: CLIPS reads no further)
        if matches!(target_at.tok, Tok::RParen | Tok::LParen | Tok::MfVar(_)) {
            return Err(self.modify_target_error(name, target_at));
        }
        let f = self.parse_expr()?;
        // a variable (`?h:slot` too) or, at top level, a fact index: anything else (a
        // call, a constant) CLIPS refuses while reading, at the prompt too
        match self.cx.exprs[f as usize].op {
            // `(modify 3 ...)` names a fact by its index: CLIPS allows that only at
            // top level
            Op::Int if in_construct => {
                let mut e = self.err(target_at, "a fact-address (fact indexes only at top level)");
                e.detail = LoadDetail::FactIndexInRule { command: name };
                e.echo_end = target_at.end as u32;
                return Err(e);
            }
            Op::Int | Op::Local | Op::Global | Op::PatVar | Op::QSlot => {}
            // a variable nothing binds: CLIPS's `[PRCCODE3]` once the construct is read
            Op::Nop if matches!(target_at.tok, Tok::SfVar(_)) && self.deferred.is_some() => {}
            _ => return Err(self.modify_target_error(name, target_at)),
        }
        self.cx.append_child(node, f);
        let tmpl = self.target_template(f);
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => return Ok(node),
                Tok::LParen => {
                    let st = self.next();
                    let sname = match st.tok {
                        Tok::Symbol(s) => s,
                        _ => {
                            return Err(self.syntax_of(
                                st,
                                "a slot name",
                                "duplicate/modify function",
                            ))
                        }
                    };
                    let ssym = cap!(self, self.cx.intern(sname))?;
                    if self.slot_given(node, ssym) {
                        return Err(self.slot_twice(st, "a slot not given twice"));
                    }
                    let sv = cap!(self, self.cx.push_expr(Expr::new(Op::SlotVal, 0, ssym)))?;
                    match tmpl {
                        Some(tmpl) => {
                            let slot = self.slot_of(tmpl, st).map_err(|mut e| {
                                if let LoadDetail::UnknownSlot { ref mut whole, .. } = e.detail {
                                    *whole = true;
                                    e.echo_end = 0;
                                }
                                e
                            })?;
                            let def = self.cx.slot_def(tmpl, slot);
                            self.slot_values(sv, &def, st, name)?;
                        }
                        None => loop {
                            let t = self.peek();
                            match t.tok {
                                Tok::RParen => {
                                    self.next();
                                    break;
                                }
                                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                                Tok::Amp | Tok::Bar | Tok::Tilde => {
                                    return Err(self.constraint_in_fact(t, "deftemplate pattern"))
                                }
                                _ => {
                                    let a = self.parse_expr()?;
                                    self.cx.append_child(sv, a);
                                }
                            }
                        },
                    }
                    self.cx.append_child(node, sv);
                }
                _ => {
                    return Err(self.syntax_of(
                        t,
                        "'(' and a slot name",
                        "duplicate/modify function",
                    ))
                }
            }
        }
    }
}

/// The position line's "expected ..." text for a broken restriction.
pub(super) fn expected(what: Restriction) -> &'static str {
    match what {
        Restriction::Type => "a value of the slot's type",
        Restriction::Values => "one of the slot's allowed values",
        #[cfg(feature = "extras")]
        Restriction::Classes => "no instance name or address (allowed-classes names classes)",
        Restriction::Range => "a number in the slot's range",
        Restriction::Cardinality => "as many values as the slot's cardinality allows",
    }
}
