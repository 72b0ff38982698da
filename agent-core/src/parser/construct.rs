//! deftemplate, deffacts, deffunction, defglobal.

use super::facts::Violation;
use super::{PResult, Parser, Scope};
use crate::engine::cap;
use crate::error::LoadDetail;
use crate::error::Pool;
use crate::expr::Op;
use crate::lexer::{Lexer, Tok, Token};
use crate::template::{
    allowed, types, DefaultKind, Deffacts, Deffunction, Global, SlotDef, Template,
};
use crate::value::{Value, NONE};

impl<'s> Parser<'s, '_, '_> {
    /// Optional comment string after a construct name.
    fn skip_comment(&mut self) {
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
    }

    pub(super) fn deftemplate(&mut self) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => s,
            _ => return Err(self.err(nt, "a deftemplate name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        if self.cx.find_template(sym).is_some() {
            return Err(self.err(
                nt,
                "a deftemplate name not yet defined (cannot redefine a deftemplate)",
            ));
        }
        self.skip_comment();
        let n = self.cx.st.ntemplates as usize;
        if n >= self.cx.templates.len() {
            let c = cap(Pool::Templates, self.cx.templates.len());
            return Err(self.cap_err(nt, c));
        }
        let first_slot = self.cx.st.nslots;
        let mut nslots = 0u16;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => {
                    let kt = self.next();
                    let multi = match kt.tok {
                        Tok::Symbol("slot") | Tok::Symbol("field") => false,
                        Tok::Symbol("multislot") | Tok::Symbol("multifield") => true,
                        _ => return Err(self.err(kt, "slot or multislot")),
                    };
                    let st = self.next();
                    let sname = match st.tok {
                        Tok::Symbol(s) => s,
                        _ => return Err(self.err(st, "a slot name")),
                    };
                    let ssym = cap!(self, self.cx.intern(sname))?;
                    if (first_slot..first_slot + nslots)
                        .any(|i| self.cx.slots[i as usize].name == ssym)
                    {
                        return Err(self.err(st, "a slot name not used before in this template"));
                    }
                    let s = self.cx.st.nslots as usize;
                    if s >= self.cx.slots.len() {
                        let c = cap(Pool::SlotDefs, self.cx.slots.len());
                        return Err(self.cap_err(st, c));
                    }
                    let def = self.slot_attributes(SlotDef {
                        name: ssym,
                        multi,
                        ..SlotDef::EMPTY
                    })?;
                    self.cx.slots[s] = def;
                    self.cx.st.nslots += 1;
                    self.cx.note_hw(Pool::SlotDefs, s + 1);
                    nslots += 1;
                }
                _ => return Err(self.err(t, "'(' starting a slot or ')'")),
            }
        }
        self.cx.templates[n] = Template {
            name: sym,
            first_slot,
            nslots,
            implied: false,
            alpha_head: NONE,
        };
        self.cx.st.ntemplates += 1;
        self.cx.note_hw(Pool::Templates, n + 1);
        Ok(())
    }

    fn slot_attributes(&mut self, mut def: SlotDef) -> PResult<SlotDef> {
        // reader position of the default's values and the attribute's name
        let mut default_at = None;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => {
                    if let Some((values_at, attribute)) = default_at {
                        self.check_default(&def, values_at, attribute)?;
                    }
                    return Ok(def);
                }
                Tok::LParen => {
                    let at = self.next();
                    let attr = match at.tok {
                        Tok::Symbol(s) => s,
                        _ => return Err(self.err(at, "a slot attribute")),
                    };
                    match attr {
                        "default" | "default-dynamic" => {
                            let save = self.scope;
                            self.scope = Scope::Frame;
                            let p = self.peek();
                            if let Tok::SfVar(v) = p.tok {
                                if v == "NONE" || v == "DERIVE" {
                                    self.next();
                                    def.default_kind = if v == "NONE" {
                                        DefaultKind::Required
                                    } else {
                                        DefaultKind::Derived
                                    };
                                    self.expect_rparen("')' after the default")?;
                                    self.scope = save;
                                    continue;
                                }
                            }
                            let holder = cap!(
                                self,
                                self.cx.push_expr(crate::expr::Expr::new(Op::Nop, 0, 0))
                            )?;
                            // where the values start, to point at a bad one later
                            let values_at = self.save();
                            let mut n = 0u16;
                            loop {
                                let t = self.peek();
                                match t.tok {
                                    Tok::RParen => {
                                        self.next();
                                        break;
                                    }
                                    Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                                    _ if !def.multi && n == 1 => {
                                        return Err(self.err(
                                            t,
                                            "a single default value for a single-field slot",
                                        ))
                                    }
                                    _ => {
                                        let a = self.parse_expr()?;
                                        self.cx.append_child(holder, a);
                                        n += 1;
                                    }
                                }
                            }
                            self.scope = save;
                            if !def.multi && n != 1 {
                                return Err(self
                                    .err(at, "exactly one default value for a single-field slot"));
                            }
                            default_at = Some((
                                values_at,
                                if attr == "default" {
                                    "default"
                                } else {
                                    "default-dynamic"
                                },
                            ));
                            def.default = self.cx.exprs[holder as usize].first;
                            def.default_kind = if attr == "default" {
                                DefaultKind::Static
                            } else {
                                DefaultKind::Dynamic
                            };
                        }
                        "type" => {
                            let mut mask = 0u8;
                            loop {
                                let tt = self.next();
                                match tt.tok {
                                    Tok::RParen => break,
                                    Tok::Symbol(ty) => {
                                        mask |= match ty {
                                            "SYMBOL" => types::SYMBOL,
                                            "STRING" => types::STRING,
                                            "LEXEME" => types::LEXEME,
                                            "INTEGER" => types::INTEGER,
                                            "FLOAT" => types::FLOAT,
                                            "NUMBER" => types::NUMBER,
                                            "FACT-ADDRESS" => types::FACT_ADDRESS,
                                            "?VARIABLE" => 0xFF,
                                            _ => return Err(self.err(tt, "a type name")),
                                        }
                                    }
                                    Tok::SfVar("VARIABLE") => mask = 0xFF,
                                    _ => return Err(self.err(tt, "a type name")),
                                }
                            }
                            def.types = if mask == 0xFF { 0 } else { mask };
                        }
                        "allowed-values" | "allowed-symbols" | "allowed-strings"
                        | "allowed-numbers" | "allowed-integers" | "allowed-floats"
                        | "allowed-lexemes" => {
                            let holder = cap!(
                                self,
                                self.cx.push_expr(crate::expr::Expr::new(Op::Nop, 0, 0))
                            )?;
                            loop {
                                let tt = self.next();
                                if tt.tok == Tok::RParen {
                                    break;
                                }
                                if tt.tok == Tok::SfVar("VARIABLE") {
                                    continue;
                                }
                                match self.literal(tt)? {
                                    Some(c) => self.cx.append_child(holder, c),
                                    None => return Err(self.err(tt, "a constant allowed value")),
                                }
                            }
                            let first = self.cx.exprs[holder as usize].first;
                            if first != NONE {
                                def.allowed = first;
                                def.allowed_kind = match attr {
                                    "allowed-symbols" => allowed::SYMBOLS,
                                    "allowed-strings" => allowed::STRINGS,
                                    "allowed-lexemes" => allowed::LEXEMES,
                                    "allowed-integers" => allowed::INTEGERS,
                                    "allowed-floats" => allowed::FLOATS,
                                    "allowed-numbers" => allowed::NUMBERS,
                                    _ => allowed::VALUES,
                                };
                            }
                        }
                        "range" | "cardinality" | "visibility" | "storage" | "pattern-match"
                        | "create-accessor" | "override-message" | "access" | "propagation"
                        | "source" => {
                            // accepted, not enforced
                            loop {
                                let tt = self.next();
                                match tt.tok {
                                    Tok::RParen => break,
                                    Tok::Eof | Tok::Bad => return Err(self.err(tt, "')'")),
                                    _ => {}
                                }
                            }
                        }
                        _ => {
                            return Err(self
                                .err(at, "a slot attribute (type, default, allowed-values, ...)"))
                        }
                    }
                }
                _ => return Err(self.err(t, "'(' starting a slot attribute or ')'")),
            }
        }
    }

    /// CLIPS rejects a default whose literal values break the slot's type or allowed
    /// values (whichever attribute came first); the error points at the value.
    fn check_default(
        &mut self,
        def: &SlotDef,
        values_at: (Lexer<'s>, Option<Token<'s>>),
        attribute: &'static str,
    ) -> PResult<()> {
        let mut c = def.default;
        let mut k = 0;
        while c != NONE {
            if let Some(violation) = self.literal_violation(def, c) {
                // re-read the default's values up to the k-th to find its position
                let resume = self.save();
                self.restore(values_at);
                for _ in 0..k {
                    self.skip_balanced()?;
                }
                let at = self.peek();
                self.restore(resume);
                let mut e = self.err(at, violation.expected());
                e.detail = LoadDetail::DefaultConstraint {
                    attribute,
                    types: violation == Violation::Type,
                    slot: def.name,
                };
                return Err(e);
            }
            c = self.cx.exprs[c as usize].next;
            k += 1;
        }
        Ok(())
    }

    pub(super) fn deffacts(&mut self) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => s,
            _ => return Err(self.err(nt, "a deffacts name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        self.skip_comment();
        let holder = cap!(
            self,
            self.cx.push_expr(crate::expr::Expr::new(Op::Nop, 0, 0))
        )?;
        self.scope = Scope::Lhs;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => {
                    let spec = self.fact_spec()?;
                    self.cx.append_child(holder, spec);
                }
                _ => return Err(self.err(t, "'(' starting a fact or ')'")),
            }
        }
        // redefinition replaces
        let existing =
            (0..self.cx.st.ndeffacts).find(|&d| self.cx.deffacts[d as usize].name == sym);
        let facts = self.cx.exprs[holder as usize].first;
        match existing {
            Some(d) => self.cx.deffacts[d as usize].facts = facts,
            None => {
                let n = self.cx.st.ndeffacts as usize;
                if n >= self.cx.deffacts.len() {
                    let c = cap(Pool::Deffacts, self.cx.deffacts.len());
                    return Err(self.cap_err(nt, c));
                }
                self.cx.deffacts[n] = Deffacts { name: sym, facts };
                self.cx.st.ndeffacts += 1;
                self.cx.note_hw(Pool::Deffacts, n + 1);
            }
        }
        Ok(())
    }

    pub(super) fn deffunction(&mut self) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => s,
            _ => return Err(self.err(nt, "a deffunction name")),
        };
        if crate::builtins::lookup(name).is_some()
            || matches!(name, "if" | "while" | "bind" | "assert" | "modify")
        {
            return Err(self.err(nt, "a name that is not a builtin function"));
        }
        let sym = cap!(self, self.cx.intern(name))?;
        self.skip_comment();
        // register first so the body can call itself recursively
        let existing = (0..self.cx.st.nfuncs).find(|&f| self.cx.funcs[f as usize].name == sym);
        let f = match existing {
            Some(f) => f,
            None => {
                let n = self.cx.st.nfuncs as usize;
                if n >= self.cx.funcs.len() {
                    let c = cap(Pool::Functions, self.cx.funcs.len());
                    return Err(self.cap_err(nt, c));
                }
                self.cx.st.nfuncs += 1;
                self.cx.note_hw(Pool::Functions, n + 1);
                n as u16
            }
        };
        let old = self.cx.funcs[f as usize];
        self.expect_lparen("'(' opening the parameter list")?;
        self.scope = Scope::Frame;
        let mut nparams = 0u8;
        let mut rest = false;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::SfVar(v) | Tok::MfVar(v) if self.find_var(v).is_some() => {
                    return Err(self.err(t, "a parameter name not used twice"));
                }
                Tok::SfVar(v) if !rest => {
                    self.new_local(t, v, false)?;
                    nparams += 1;
                }
                Tok::MfVar(v) if !rest => {
                    self.new_local(t, v, true)?;
                    rest = true;
                }
                _ => {
                    return Err(self.err(
                        t,
                        if rest {
                            "the $? wildcard parameter to be last"
                        } else {
                            "a parameter"
                        },
                    ))
                }
            }
        }
        self.cx.funcs[f as usize] = Deffunction {
            name: sym,
            nparams,
            rest,
            nlocals: 0,
            body: NONE,
        };
        self.defining_fn = f;
        let body = self.action_block();
        self.defining_fn = NONE;
        let body = match body {
            Ok(b) => b,
            Err(e) => {
                if existing.is_some() {
                    self.cx.funcs[f as usize] = old;
                }
                return Err(e);
            }
        };
        let nlocals = self.nlocals.min(255) as u8;
        self.cx.funcs[f as usize] = Deffunction {
            name: sym,
            nparams,
            rest,
            nlocals,
            body: self.cx.exprs[body as usize].first,
        };
        Ok(())
    }

    pub(super) fn defglobal(&mut self) -> PResult<()> {
        self.scope = Scope::Frame;
        if let Tok::Symbol(_) = self.peek().tok {
            self.next(); // module name
        }
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => return Ok(()),
                Tok::Global(name) => {
                    let eq = self.next();
                    if eq.tok != Tok::Symbol("=") {
                        return Err(self.err(eq, "'=' after the global name"));
                    }
                    let init = self.parse_expr()?;
                    let sym = cap!(self, self.cx.intern(name))?;
                    let v = match self.cx.eval(init) {
                        Ok(v) => v,
                        Err(_) => return Err(self.err(eq, "an initial value that evaluates")),
                    };
                    let existing =
                        (0..self.cx.st.nglobals).find(|&g| self.cx.globals[g as usize].name == sym);
                    let g = match existing {
                        Some(g) => g as usize,
                        None => {
                            let n = self.cx.st.nglobals as usize;
                            if n >= self.cx.globals.len() {
                                let c = cap(Pool::Globals, self.cx.globals.len());
                                return Err(self.cap_err(t, c));
                            }
                            self.cx.st.nglobals += 1;
                            self.cx.note_hw(Pool::Globals, n + 1);
                            n
                        }
                    };
                    self.cx.globals[g] = Global {
                        name: sym,
                        value: Value::Void,
                        init,
                    };
                    if let Err(c) = self.cx.set_global(g as u16, v) {
                        return Err(self.cap_err(t, c));
                    }
                }
                _ => return Err(self.err(t, "a global variable ?*name*")),
            }
        }
    }
}

#[allow(dead_code)]
fn _v(_: Value) {}
