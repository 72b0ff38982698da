//! deftemplate, deffacts, deffunction, defglobal.

use super::{PResult, Parser, Scope};
use crate::engine::cap;
use crate::error::LoadDetail;
use crate::error::Pool;
use crate::expr::Op;
use crate::lexer::{Tok, Token};
use crate::template::{Deffacts, Deffunction, Global, SlotDef, Template, TemplateMem};
use crate::value::Ix;
use crate::value::{Value, NONE};

impl<'s> Parser<'s, '_, '_> {
    /// Whether deffacts `d` is the current module's (a redefinition replaces only
    /// that one).
    pub(super) fn deffacts_here(&self, d: Ix) -> bool {
        #[cfg(feature = "modules")]
        return self.cx.module_of_deffacts(d) == self.cx.current_module();
        #[cfg(not(feature = "modules"))]
        {
            let _ = d;
            true
        }
    }

    /// Whether deffunction `f` is the current module's.
    pub(super) fn function_here(&self, f: Ix) -> bool {
        #[cfg(feature = "modules")]
        return self.cx.module_of_function(f) == self.cx.current_module();
        #[cfg(not(feature = "modules"))]
        {
            let _ = f;
            true
        }
    }

    /// Optional comment string after a construct name; `load`'s line for the construct
    /// starts here, as CLIPS prints it once it has read the name and comment.
    fn skip_comment(&mut self) {
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
        self.announce_head();
    }

    /// The construct's source text from `start` to here, interned for its `ppdef*`
    /// command, unless the host chose to drop pretty-print forms (then NONE).
    pub(super) fn pp_text(&mut self, start: usize) -> Ix {
        if !self.cx.st.mode.keep_pp_forms {
            return NONE;
        }
        let end = self.lex.pos();
        let text = self.lex.source().get(start..end).unwrap_or("");
        self.cx.intern(text).unwrap_or(NONE)
    }

    pub(super) fn deftemplate(&mut self, start: usize) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => self.construct_name(nt, s)?,
            _ => return Err(self.missing_name(nt, "a deftemplate name")),
        };
        // CLIPS keeps the conditional elements' keywords out of pattern heads
        if matches!(
            name,
            "not" | "and" | "or" | "test" | "exists" | "forall" | "logical" | "object"
        ) {
            let mut e = self.err(nt, "a name that is not a conditional element keyword");
            e.detail = LoadDetail::SpecialMeaning;
            // CLIPS shows the deftemplate up to the token after the name
            e.echo_end = self.peek().end as u32;
            return Err(e);
        }
        let sym = cap!(self, self.cx.intern(name))?;
        // CLIPS replaces a deftemplate nothing uses yet, and refuses otherwise
        let replaces = self.cx.find_template(sym);
        // one the module imports cannot be replaced by one of its own
        #[cfg(feature = "modules")]
        if replaces.is_some_and(|t| self.cx.module_of_template(t) != self.cx.current_module())
            || self.cx.import_conflict(
                crate::module::class::TEMPLATE,
                self.cx.current_module(),
                sym,
            )
        {
            return Err(self.import_conflict(nt, "deftemplate"));
        }
        if replaces.is_some_and(|t| self.cx.template_in_use(t)) {
            let mut e = self.err(
                nt,
                "a deftemplate name not in use (a deftemplate with facts or constructs using it cannot be redefined)",
            );
            e.detail = LoadDetail::InUse {
                construct: "deftemplate",
            };
            // CLIPS shows the deftemplate up to its name
            e.echo_end = nt.end as u32;
            return Err(e);
        }
        if replaces.is_some() {
            // the old entry is retired in place: a compiled one is copied first
            if let Err(c) = self.cx.network_writable() {
                return Err(self.cap_err(nt, c));
            }
            // from here a failure drops the old one too, as in CLIPS
            self.replacing = sym;
            #[cfg(feature = "extras")]
            if !self.check_only {
                self.cx
                    .watch_defined_again(crate::engine::watch::FACTS, sym);
            }
        }
        self.skip_comment();
        let n = self.cx.st.pools.ntemplates as usize;
        #[cfg(feature = "grow")]
        {
            self.cx.ensure(Pool::Templates, n + 1);
            self.cx.ensure(Pool::TemplateMemories, n + 1);
        }
        if n >= self.cx.templates.len() {
            let c = cap(Pool::Templates, self.cx.templates.len());
            return Err(self.cap_err(nt, c));
        }
        if n >= self.cx.tmpl_mems.len() {
            let c = cap(Pool::TemplateMemories, self.cx.tmpl_mems.len());
            return Err(self.cap_err(nt, c));
        }
        let first_slot = self.cx.st.pools.nslots;
        let mut nslots = 0 as Ix;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => {
                    let kt = self.next();
                    let multi = match kt.tok {
                        Tok::Symbol("slot") | Tok::Symbol("field") => false,
                        Tok::Symbol("multislot") | Tok::Symbol("multifield") => true,
                        _ => {
                            let mut e = self.err(kt, "slot or multislot");
                            if !matches!(kt.tok, Tok::Eof | Tok::Bad) {
                                e.echo_end = kt.end as u32;
                            }
                            return Err(e);
                        }
                    };
                    let st = self.next();
                    let sname = match st.tok {
                        Tok::Symbol(s) => s,
                        // CLIPS shows the deftemplate up to the token (`(slot )`)
                        _ => {
                            let mut e = self.err(st, "a slot name");
                            if !matches!(st.tok, Tok::Eof | Tok::Bad) {
                                e.echo_end = st.end as u32;
                                if st.tok == Tok::RParen {
                                    e.echo_tail = crate::error::EchoTail::SpaceBefore;
                                }
                            }
                            return Err(e);
                        }
                    };
                    let ssym = cap!(self, self.cx.intern(sname))?;
                    if (first_slot..first_slot + nslots)
                        .any(|i| self.cx.slots[i as usize].name == ssym)
                    {
                        return Err(
                            self.slot_twice(st, "a slot name not used before in this template")
                        );
                    }
                    // a pattern's field locator holds the slot in 8 bits, 255 meaning
                    // the fact itself (`expr::loc`)
                    if nslots >= 255 {
                        return Err(self.err(st, "at most 255 slots in one deftemplate"));
                    }
                    let s = self.cx.st.pools.nslots as usize;
                    #[cfg(feature = "grow")]
                    self.cx.ensure(Pool::SlotDefs, s + 1);
                    if s >= self.cx.slots.len() {
                        let c = cap(Pool::SlotDefs, self.cx.slots.len());
                        return Err(self.cap_err(st, c));
                    }
                    let mut facets = NONE;
                    let def = self.slot_attributes(
                        SlotDef {
                            name: ssym,
                            multi,
                            ..SlotDef::EMPTY
                        },
                        &mut facets,
                    )?;
                    self.cx.slots[s] = def;
                    #[cfg(feature = "extras")]
                    if !self.cx.set_slot_facets(s as Ix, facets) {
                        let c = cap(Pool::SlotDefs, self.cx.slots.len());
                        return Err(self.cap_err(st, c));
                    }
                    self.cx.st.pools.nslots += 1;
                    self.cx.note_hw(Pool::SlotDefs, s + 1);
                    nslots += 1;
                }
                _ => {
                    let mut e = self.err(t, "'(' starting a slot or ')'");
                    if !matches!(t.tok, Tok::Eof | Tok::Bad) {
                        e.echo_end = t.end as u32;
                    }
                    return Err(e);
                }
            }
        }
        if self.check_only {
            return Err(self.checked(nt));
        }
        self.cx.templates[n] = Template {
            name: sym,
            first_slot,
            nslots,
            implied: false,
            alpha_head: NONE,
            text: self.pp_text(start),
        };
        self.cx.tmpl_mems[n] = TemplateMem::EMPTY;
        // (room: the template memories just written)
        #[cfg(feature = "modules")]
        let _ = self
            .cx
            .set_template_module(n as Ix, self.cx.current_module());
        self.cx.st.pools.ntemplates += 1;
        self.cx.note_hw(Pool::Templates, n + 1);
        if let Some(old) = replaces {
            // Nothing refers to the old entry, so it is retired where it is; the new
            // one is listed last, as in CLIPS.
            self.cx.retire_template(old);
        }
        Ok(())
    }

    pub(super) fn deffacts(&mut self, start: usize) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => self.construct_name(nt, s)?,
            _ => return Err(self.missing_name(nt, "a deffacts name")),
        };
        let sym = cap!(self, self.cx.intern(name))?;
        // from here a failure drops the old one too, as in CLIPS
        if (0..self.cx.st.pools.ndeffacts)
            .any(|d| self.cx.deffacts[d as usize].name == sym && self.deffacts_here(d))
        {
            self.replacing = sym;
        }
        self.skip_comment();
        let holder = cap!(
            self,
            self.cx.push_expr(crate::expr::Expr::new(Op::Nop, 0, 0))
        )?;
        self.scope = Scope::Lhs;
        // (appended through the last: a deffacts of many facts stays linear)
        let mut last = NONE;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => {
                    let spec = self.fact_spec()?;
                    last = self.cx.append_after(holder, last, spec);
                }
                _ => return Err(self.syntax_of(t, "'(' starting a fact or ')'", "RHS patterns")),
            }
        }
        if self.check_only {
            return Err(self.checked(nt));
        }
        // a redefinition replaces the old deffacts and, as in CLIPS, moves it last
        // (which orders the facts `reset` asserts)
        let existing = (0..self.cx.st.pools.ndeffacts)
            .find(|&d| self.cx.deffacts[d as usize].name == sym && self.deffacts_here(d));
        let facts = self.cx.exprs[holder as usize].first;
        let text = self.pp_text(start);
        #[cfg(feature = "modules")]
        let module = self.cx.current_module();
        match existing {
            Some(d) => {
                let n = self.cx.st.pools.ndeffacts as usize;
                self.cx.deffacts.copy_within(d as usize + 1..n, d as usize);
                #[cfg(feature = "modules")]
                {
                    self.cx
                        .deffacts_module
                        .copy_within(d as usize + 1..n, d as usize);
                    let _ = self.cx.set_deffacts_module(n as Ix - 1, module);
                }
                self.cx.deffacts[n - 1] = Deffacts {
                    name: sym,
                    facts,
                    text,
                };
            }
            None => {
                let n = self.cx.st.pools.ndeffacts as usize;
                #[cfg(feature = "grow")]
                self.cx.ensure(Pool::Deffacts, n + 1);
                if n >= self.cx.deffacts.len() {
                    let c = cap(Pool::Deffacts, self.cx.deffacts.len());
                    return Err(self.cap_err(nt, c));
                }
                self.cx.deffacts[n] = Deffacts {
                    name: sym,
                    facts,
                    text,
                };
                // (room: the deffacts just written)
                #[cfg(feature = "modules")]
                let _ = self.cx.set_deffacts_module(n as Ix, module);
                self.cx.st.pools.ndeffacts += 1;
                self.cx.note_hw(Pool::Deffacts, n + 1);
            }
        }
        // one named `initial-fact` in MAIN replaces CLIPS's own: `reset` asserts
        // `(initial-fact)` only if it lists it
        #[cfg(feature = "modules")]
        let in_main = module == crate::module::MAIN;
        #[cfg(not(feature = "modules"))]
        let in_main = true;
        if name == "initial-fact" && in_main {
            self.cx.st.mode.initial_deffacts = false;
        }
        Ok(())
    }

    pub(super) fn deffunction(&mut self, start: usize) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) => self.construct_name(nt, s)?,
            _ => return Err(self.missing_name(nt, "a deffunction name")),
        };
        // CLIPS's own functions cannot be replaced; our geometry extensions can, since a
        // CLIPS program may define a deffunction of that name (rules/clips/stubs.clp
        // does), and a deffunction is looked up before a builtin
        if crate::lexer::is_construct_keyword(name) {
            let mut e = self.err(nt, "a name that is not a construct keyword");
            e.detail = LoadDetail::ReplacesConstruct;
            // CLIPS shows the deffunction up to the token after the name
            e.echo_end = self.peek().end as u32;
            return Err(e);
        }
        let extension = crate::builtins::geometry::FUNCS
            .iter()
            .any(|b| b.name == name);
        if (crate::builtins::lookup(name).is_some() && !extension)
            || matches!(name, "if" | "while" | "bind" | "assert" | "modify")
        {
            let mut e = self.err(nt, "a name that is not a builtin function");
            e.detail = LoadDetail::ReplacesBuiltin;
            // CLIPS shows the deffunction up to the token after the name
            e.echo_end = self.peek().end as u32;
            return Err(e);
        }
        let sym = cap!(self, self.cx.intern(name))?;
        #[cfg(feature = "modules")]
        if self.cx.import_conflict(
            crate::module::class::FUNCTION,
            self.cx.current_module(),
            sym,
        ) {
            return Err(self.import_conflict(nt, "deffunction"));
        }
        self.skip_comment();
        // register first so the body can call itself recursively
        let existing = (0..self.cx.st.pools.nfuncs)
            .find(|&f| self.cx.funcs[f as usize].name == sym && self.function_here(f));
        let f = match existing {
            Some(f) => f,
            None => {
                let n = self.cx.st.pools.nfuncs as usize;
                #[cfg(feature = "grow")]
                self.cx.ensure(Pool::Functions, n + 1);
                if n >= self.cx.funcs.len() {
                    let c = cap(Pool::Functions, self.cx.funcs.len());
                    return Err(self.cap_err(nt, c));
                }
                self.cx.st.pools.nfuncs += 1;
                self.cx.note_hw(Pool::Functions, n + 1);
                #[cfg(feature = "extras")]
                self.cx.list_function_last(n as Ix);
                n as Ix
            }
        };
        let old = self.cx.funcs[f as usize];
        // CLIPS's "parameter list" syntax error, the deffunction shown up to the token
        let open = self.next();
        if open.tok != Tok::LParen {
            return Err(self.syntax_of(open, "'(' opening the parameter list", "parameter list"));
        }
        self.scope = Scope::Frame;
        let mut nparams = 0u8;
        let mut rest = false;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::SfVar(v) | Tok::MfVar(v) if self.find_var(v).is_some() => {
                    let mut e = self.err(t, "a parameter name not used twice");
                    e.detail = LoadDetail::ParameterTwice;
                    e.echo_end = t.end as u32;
                    return Err(e);
                }
                Tok::SfVar(_) | Tok::MfVar(_) if rest => {
                    let mut e = self.err(t, "the $? wildcard parameter to be last");
                    e.detail = LoadDetail::ParameterAfterWildcard;
                    e.echo_end = t.end as u32;
                    return Err(e);
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
                    return Err(self.syntax_of(
                        t,
                        if rest {
                            "the $? wildcard parameter to be last"
                        } else {
                            "a parameter"
                        },
                        "parameter list",
                    ))
                }
            }
        }
        if existing.is_some() {
            // from here (the body) a failure drops the old one too, as in CLIPS
            self.replacing = sym;
            #[cfg(feature = "extras")]
            if !self.check_only {
                self.cx
                    .watch_defined_again(crate::engine::watch::DEFFUNCTIONS, sym);
                // CLIPS lists it last from here, even when its actions fail
                self.cx.list_function_last(f);
            }
        }
        self.cx.funcs[f as usize] = Deffunction {
            name: sym,
            nparams,
            rest,
            nlocals: 0,
            body: NONE,
        };
        // (room: the deffunction just written)
        #[cfg(feature = "modules")]
        let _ = self.cx.set_function_module(f, self.cx.current_module());
        self.defining_fn = f;
        let body = self
            .declare_bound_vars()
            .and_then(|()| self.body_block())
            .and_then(|b| self.take_deferred().map(|()| b));
        self.defining_fn = NONE;
        let body = match body {
            Ok(b) if !self.check_only => b,
            r => {
                if existing.is_some() {
                    self.cx.funcs[f as usize] = old;
                }
                return Err(match r {
                    Err(e) => e,
                    Ok(_) => self.checked(nt),
                });
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
        #[cfg(feature = "extras")]
        {
            let text = self.pp_text(start);
            self.cx.set_function_text(f, text);
        }
        #[cfg(not(feature = "extras"))]
        let _ = start;
        Ok(())
    }

    /// Error `e` in the initial value of global `global` (`= at eq`), shown after
    /// `ERROR:` as CLIPS shows it: `(defglobal MODULE ?*name* = value` (`start`..
    /// `echo_end`: the global up to its value's end).
    fn global_echoed(
        &self,
        mut e: crate::error::LoadError,
        global: Token<'s>,
        eq: Token<'s>,
    ) -> crate::error::LoadError {
        let src = self.lex.source();
        let mut lx = crate::lexer::Lexer::new(src.get(eq.end..).unwrap_or(""));
        let mut depth = 0u32;
        let mut end = src.len();
        loop {
            let t = lx.next_token();
            match t.tok {
                Tok::Eof | Tok::Bad => break,
                Tok::LParen => depth += 1,
                Tok::RParen if depth == 0 => break,
                Tok::RParen => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                end = eq.end + t.end;
                break;
            }
        }
        e.start = global.start as u32;
        e.end = end as u32;
        e.echo_end = end as u32;
        e
    }

    pub(super) fn defglobal(&mut self) -> PResult<()> {
        self.scope = Scope::Frame;
        if let Tok::Symbol(m) = self.peek().tok {
            let mt = self.next(); // module name
            #[cfg(feature = "modules")]
            match self.cx.find_module(m) {
                Some(m) => self.cx.set_current_module(m),
                None => {
                    // CLIPS's `[PRNTUTIL1]`, the defglobal shown up to the name
                    let mut e = self.err(mt, "the name of a defined module");
                    e.detail = LoadDetail::NoSuchModule;
                    e.echo_end = mt.end as u32;
                    return Err(e);
                }
            }
            #[cfg(not(feature = "modules"))]
            if m != "MAIN" {
                return Err(self.not_implemented(mt, "defmodule"));
            }
        }
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen if self.check_only => return Err(self.checked(t)),
                Tok::RParen => return Ok(()),
                Tok::Global(name) => {
                    let eq = self.next();
                    if eq.tok != Tok::Symbol("=") {
                        // CLIPS shows the global and the token after it (`?*d* )`)
                        let mut e = self.err(eq, "'=' after the global name");
                        if !matches!(eq.tok, Tok::Eof | Tok::Bad) {
                            e.start = t.start as u32;
                            e.echo_end = eq.end as u32;
                            if eq.tok == Tok::RParen {
                                e.echo_end = t.end as u32;
                                e.echo_tail = crate::error::EchoTail::SpaceBefore;
                            }
                        }
                        return Err(e);
                    }
                    self.evaluated_now = true;
                    let init = self.parse_expr();
                    self.evaluated_now = false;
                    let init = match init {
                        Ok(init) => init,
                        // (a literal argument's type: shown up to its call's `)`)
                        Err(e)
                            if matches!(e.detail, LoadDetail::ArgType { .. })
                                && e.echo_end == 0 =>
                        {
                            return Err(self.global_echoed(e, t, eq))
                        }
                        // no value: `(defglobal MAIN ?*b* = )`
                        Err(mut e)
                            if matches!(e.detail, LoadDetail::Text { .. })
                                && e.echo_end <= e.start =>
                        {
                            e.start = t.start as u32;
                            e.echo_end = eq.end as u32;
                            return Err(e);
                        }
                        // a literal as a function name: from the global
                        Err(mut e) if matches!(e.detail, LoadDetail::Text { .. }) => {
                            e.start = t.start as u32;
                            return Err(e);
                        }
                        Err(e) => return Err(e),
                    };
                    let sym = cap!(self, self.cx.intern(name))?;
                    let here = self.cx.st_current_module();
                    #[cfg(feature = "modules")]
                    if self
                        .cx
                        .import_conflict(crate::module::class::GLOBAL, here, sym)
                    {
                        return Err(self.import_conflict(t, "defglobal"));
                    }
                    // (check-syntax evaluates no value, as CLIPS)
                    if self.check_only {
                        continue;
                    }
                    let existing = self.cx.global_of_module(sym, here);
                    // a full pool fails before the evaluation, whose effects would stay
                    let n = self.cx.st.pools.nglobals as usize;
                    #[cfg(feature = "grow")]
                    if existing.is_none() {
                        self.cx.ensure(Pool::Globals, n + 1);
                    }
                    if existing.is_none() && n >= self.cx.globals.len() {
                        let c = cap(Pool::Globals, self.cx.globals.len());
                        return Err(self.cap_err(t, c));
                    }
                    let v = match self.eval_now(init) {
                        Ok(v) => v,
                        Err(err) if err.is_capacity() => {
                            return Err(self.err(eq, "an initial value that evaluates"))
                        }
                        Err(err) => {
                            // CLIPS prints the error, then the defglobal up to the value
                            self.cx.write_error_message(err);
                            let mut e = self.err(eq, "an initial value that evaluates");
                            e.detail = LoadDetail::DefaultEvaluation;
                            return Err(self.global_echoed(e, t, eq));
                        }
                    };
                    let g = match existing {
                        Some(g) => {
                            #[cfg(feature = "extras")]
                            self.cx
                                .watch_defined_again(crate::engine::watch::GLOBALS, sym);
                            g as usize
                        }
                        None => {
                            self.cx.st.pools.nglobals += 1;
                            self.cx.note_hw(Pool::Globals, n + 1);
                            n
                        }
                    };
                    self.cx.globals[g] = Global {
                        name: sym,
                        value: Value::Void,
                        init,
                    };
                    #[cfg(feature = "modules")]
                    let _ = self.cx.set_global_module(g as Ix, here);
                    if let Err(c) = self.cx.set_global(g as Ix, v) {
                        return Err(self.cap_err(t, c));
                    }
                    #[cfg(feature = "extras")]
                    {
                        let text = self.pp_text(t.start);
                        self.cx.set_global_text(g as Ix, text);
                    }
                    // defined: a later error in the construct keeps it (as CLIPS does;
                    // a redefined global must not keep an init that is rolled back)
                    self.keep = Some(self.cx.checkpoint());
                }
                _ => {
                    // CLIPS shows only the token: `(defglobal MAIN 2`
                    let mut e = self.err(t, "a global variable ?*name*");
                    if !matches!(t.tok, Tok::Eof | Tok::Bad) {
                        e.echo_end = t.end as u32;
                    }
                    return Err(e);
                }
            }
        }
    }
}

#[allow(dead_code)]
fn _v(_: Value) {}
