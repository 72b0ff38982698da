//! Expressions: constants, variables, function calls and the special forms.

use super::{PResult, Parser, Scope, VarKind};
use crate::builtins::{self, Syntax};
use crate::expr::{Expr, FnKind, Op};
use crate::lexer::{Lexer, Tok, Token};
use crate::value::Ix;
use crate::value::{TextBuf, Value, NONE};

/// `length$`, whose call of a multifield variable is a quiet operand (`quiet_operand`).
#[cfg(feature = "host-speedups")]
const LENGTH_ID: Ix = builtins::builtin_id("length$");

/// `aux` of the `Sym` node under a `QSlot` (`?v:slot`): every template of `?v` has the
/// slot, so the read is a quiet operand (`Parser::slot_in_every_template`).
const QSLOT_QUIET: u8 = 1;

impl<'s> Parser<'s, '_, '_> {
    /// Interns a string literal's contents with `\"` and `\\` unescaped.
    pub fn string_const(&mut self, t: Token<'s>, raw: &str) -> PResult<Ix> {
        let mut b: TextBuf<1024> = TextBuf::new();
        let mut esc = false;
        let mut fits = true;
        for ch in raw.chars() {
            if esc || ch != '\\' {
                let mut tmp = [0u8; 4];
                if core::fmt::Write::write_str(&mut b, ch.encode_utf8(&mut tmp)).is_err() {
                    fits = false;
                    break;
                }
                esc = false;
            } else {
                esc = true;
            }
        }
        if !fits {
            // host: a longer literal unescaped into a buffer that grows (CLIPS reads
            // any length); the image's parser, and engines without `grow`, refuse it
            #[cfg(feature = "grow")]
            {
                let _ = t;
                return self.long_string_const(raw);
            }
            #[cfg(not(feature = "grow"))]
            return Err(self.err(t, "a string literal of at most 1024 bytes"));
        }
        let id = self.cx.intern(b.as_str());
        let id = cap!(self, id)?;
        let e = self.cx.push_expr(Expr::new(Op::Str, 0, id));
        cap!(self, e)
    }

    /// `string_const` for a literal past 1024 bytes (host).
    #[cfg(feature = "grow")]
    #[inline(never)]
    fn long_string_const(&mut self, raw: &str) -> PResult<Ix> {
        let mut b = alloc::string::String::new();
        // (a String takes any length)
        let _ = unescape_into(raw, &mut b);
        self.cx
            .st
            .eval
            .past_image
            .get_or_insert("a string literal longer than 1024 bytes (the image's limit)");
        let id = self.cx.intern(&b);
        let id = cap!(self, id)?;
        let e = self.cx.push_expr(Expr::new(Op::Str, 0, id));
        cap!(self, e)
    }

    /// A constant node from a literal token, or None if the token is no literal.
    pub fn literal(&mut self, t: Token<'s>) -> PResult<Option<Ix>> {
        let r = match t.tok {
            Tok::Int(i) => self.cx.push_const(Value::Int(i)),
            Tok::IntOverflow(i) => {
                if self.check_only {
                    self.warned_overflow = true;
                } else {
                    self.cx
                        .write(crate::host::router::WWARNING, super::OVERFLOW_WARNING);
                }
                self.cx.push_const(Value::Int(i))
            }
            Tok::Float(f) => self.cx.push_const(Value::Float(f)),
            Tok::Symbol(s) => match self.cx.intern(s) {
                Ok(id) => self.cx.push_expr(Expr::new(Op::Sym, 0, id)),
                Err(e) => Err(e),
            },
            Tok::Str(s) => return self.string_const(t, s).map(Some),
            _ => return Ok(None),
        };
        cap!(self, r).map(Some)
    }

    /// Reads one expression.
    pub fn parse_expr(&mut self) -> PResult<Ix> {
        self.nested(|p| p.parse_expr_inner())
    }

    fn parse_expr_inner(&mut self) -> PResult<Ix> {
        let t = self.next();
        if let Some(c) = self.literal(t)? {
            return Ok(c);
        }
        match t.tok {
            Tok::SfVar(name) => self.var_ref(t, name, false),
            Tok::MfVar(name) => {
                // with sequence-operator recognition `$?x` expands (`aux` 1), as
                // `(expand$ ?x)` does; else it is `?x`. `$?*g*` (the global's value)
                // always expands in CLIPS 6.30.
                let (v, expands) = match name.strip_prefix('*').and_then(|n| n.strip_suffix('*')) {
                    Some(g) if !g.is_empty() => (self.global_read(t, g)?, true),
                    _ => (self.var_ref(t, name, true)?, self.cx.st.mode.seq_ops),
                };
                let e = self.cx.push_expr(Expr {
                    first: v,
                    ..Expr::new(Op::Expand, u8::from(expands), 0)
                });
                cap!(self, e)
            }
            Tok::Global(name) => self.global_read(t, name),
            Tok::LParen => self.call(),
            Tok::RParen => {
                // CLIPS shows the construct up to the `)`, one space before it
                let mut e = self.err(t, "an expression");
                e.detail = crate::error::LoadDetail::Text {
                    text: "[EXPRNPSR2] Expected a constant, variable, or expression.",
                };
                e.echo_end = t.start as u32;
                e.echo_tail = crate::error::EchoTail::SpaceBefore;
                Err(e)
            }
            _ => Err(self.err(t, "an expression")),
        }
    }

    /// A global the current module sees (what `bind` sets).
    pub fn global_ref(&mut self, t: Token<'s>, name: &str) -> PResult<Ix> {
        let g = self
            .cx
            .find_sym(name)
            .and_then(|id| self.cx.find_global(id));
        match g {
            Some(g) => {
                let e = self.cx.push_expr(Expr::new(Op::Global, 0, g));
                cap!(self, e)
            }
            None => Err(self.undefined_global(t, true)),
        }
    }

    /// CLIPS's `[GLOBLPSR1]` for a global the module does not see, in a rule's or
    /// deffunction's actions or a `bind` at the prompt (elsewhere our syntax error).
    fn undefined_global(&self, t: Token<'s>, bind: bool) -> crate::error::LoadError {
        if self.scope == Scope::Lhs && self.construct == "defrule" {
            return self.unbound_in_lhs(t, true);
        }
        let mut e = self.err(t, "a defined global variable");
        let clips = match self.scope {
            Scope::Frame => matches!(self.construct, "defrule" | "deffunction"),
            Scope::TopLevel => bind,
            Scope::Lhs => false,
        };
        if clips {
            e.detail = crate::error::LoadDetail::UndefinedGlobal { whole: !bind };
        }
        e
    }

    /// A global read in an expression.
    fn global_read(&mut self, t: Token<'s>, name: &str) -> PResult<Ix> {
        let g = self
            .cx
            .find_sym(name)
            .and_then(|id| self.cx.find_global(id));
        match g {
            Some(g) => {
                let e = self.cx.push_expr(Expr::new(Op::Global, 0, g));
                cap!(self, e)
            }
            // at the prompt, in a defglobal's initial value, a slot default and a
            // deffacts CLIPS reads a global the module does not see by its name, looked
            // up when it runs (`[GLOBLDEF1]` if still unseen): a hidden global
            // `?*name*`, never bound (`bind` names only defined ones; see
            // `Core::unbound_global`)
            None if (self.scope == Scope::TopLevel
                || self.evaluated_now
                || self.construct == "deffacts")
                && name.len() < 120 =>
            {
                let mut b: TextBuf<128> = TextBuf::new();
                let _ = core::fmt::Write::write_fmt(&mut b, format_args!("*{name}*"));
                let g = self.toplevel_var(t, b.as_str())?;
                let e = self.cx.push_expr(Expr::new(Op::Global, 0, g));
                cap!(self, e)
            }
            None => self.defer_undefined_global(t),
        }
    }

    /// An undefined global read in a rule's conditions or actions or a deffunction's
    /// body: CLIPS resolves those once the construct is read whole, so an error
    /// found later in the text comes first (`[EXPRNPSR3]` for a missing function
    /// after it, say); the read is nothing meanwhile (the construct is never kept).
    fn defer_undefined_global(&mut self, t: Token<'s>) -> PResult<Ix> {
        let deferrable = match self.scope {
            Scope::Lhs | Scope::Frame => matches!(self.construct, "defrule" | "deffunction"),
            Scope::TopLevel => false,
        };
        if !deferrable || self.evaluated_now {
            return Err(self.undefined_global(t, false));
        }
        let e = self.undefined_global(t, false);
        if self.deferred.is_none() {
            self.deferred = Some(e);
        }
        let e = self.cx.push_expr(Expr::new(Op::Nop, 0, 0));
        cap!(self, e)
    }

    /// A variable reference node.
    pub fn var_ref(&mut self, t: Token<'s>, name: &'s str, _multi: bool) -> PResult<Ix> {
        if let Some((var, slot)) = name.split_once(':') {
            if self.find_var(var).is_some() && !slot.is_empty() {
                return self.query_slot_ref(t, var, slot);
            }
        }
        if let Some(v) = self.find_var(name) {
            let e = match v.kind {
                VarKind::Pat { pat, loc, desc } if v.rebound != NONE => {
                    return self.rebound_ref(v.rebound, pat, loc, desc);
                }
                VarKind::Pat { pat, loc, desc } => Expr {
                    first: desc,
                    ..Expr::new(Op::PatVar, pat, loc)
                },
                VarKind::Local(s) if v.unbound_name != NONE => {
                    return self.checked_local_ref(s, v.unbound_name);
                }
                VarKind::Local(s) => Expr::new(Op::Local, 0, s),
            };
            let e = self.cx.push_expr(e);
            return cap!(self, e);
        }
        match self.scope {
            _ if self.at_prompt() => {
                if self.commands_only {
                    self.prompt_reads = self.prompt_reads.saturating_add(1);
                }
                let g = self.toplevel_var(t, name)?;
                let e = self.cx.push_expr(Expr::new(Op::Global, 0, g));
                cap!(self, e)
            }
            _ if self.construct == "deffacts" => {
                Err(self.deffacts_variable(t, "a constant (deffacts take no variables)"))
            }
            Scope::Lhs if self.construct == "defrule" => {
                // CLIPS's `[ANALYSIS4]` comes from its analysis of the rule read whole
                // (a syntax error later in the rule comes first)
                let e = self.unbound_in_lhs(t, true);
                if self.deferred.is_none() {
                    self.deferred = Some(e);
                }
                let e = self.cx.push_expr(Expr::new(Op::Nop, 0, 0));
                cap!(self, e)
            }
            Scope::Frame if matches!(self.construct, "defrule" | "deffunction") => {
                // CLIPS's `[PRCCODE3]`, echoing the whole construct once it is read
                // (another error found on the way comes first); the variable reads
                // as nothing meanwhile: the construct is never kept
                let mut e = self.err(t, "a bound variable");
                e.detail = crate::error::LoadDetail::UndefinedVariable;
                if self.deferred.is_none() {
                    self.deferred = Some(e);
                }
                let e = self.cx.push_expr(Expr::new(Op::Nop, 0, 0));
                cap!(self, e)
            }
            _ => Err(self.err(t, "a bound variable")),
        }
    }

    /// CLIPS's `[ANALYSIS4]` for variable `t` read in a rule's conditions before a
    /// pattern binds it (a global the module does not see too): where it is read.
    /// `[PRNTUTIL6]`: a variable in a deffacts (CLIPS checks once the deffacts is
    /// read and shows it whole).
    pub(super) fn deffacts_variable(
        &self,
        t: Token<'s>,
        expected: &'static str,
    ) -> crate::error::LoadError {
        let mut e = self.err(t, expected);
        e.detail = crate::error::LoadDetail::Text {
            text: "[PRNTUTIL6] Local variables can not be accessed by a deffacts construct.",
        };
        e.echo_end = u32::MAX;
        e
    }

    pub(super) fn unbound_in_lhs(&self, t: Token<'s>, in_call: bool) -> crate::error::LoadError {
        let mut e = self.err(t, "a bound variable");
        e.detail = crate::error::LoadDetail::UnboundInLhs {
            slot: self.lhs_slot.map_or(NONE, |d| d.name),
            ce: self.ce_count,
            field: self.lhs_field,
            in_call,
        };
        e
    }

    /// A read of an LHS variable the actions `bind` (`VarEntry::rebound`): its frame
    /// slot, `aux` 2, the LHS variable as the child read while the slot is unbound.
    #[inline(never)]
    fn rebound_ref(&mut self, slot: Ix, pat: u8, loc: Ix, desc: Ix) -> PResult<Ix> {
        let lhs = Expr {
            first: desc,
            ..Expr::new(Op::PatVar, pat, loc)
        };
        let lhs = cap!(self, self.cx.push_expr(lhs))?;
        let e = Expr {
            first: lhs,
            ..Expr::new(Op::Local, 2, slot)
        };
        cap!(self, self.cx.push_expr(e))
    }

    /// A read of a local that may be unbound: `aux` 1, its name in the payload node
    /// after it (`Core::local`). Out of line: the reader recurses through `var_ref`.
    #[inline(never)]
    fn checked_local_ref(&mut self, slot: Ix, name: Ix) -> PResult<Ix> {
        let e = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 1, slot)))?;
        cap!(self, self.cx.push_expr(Expr::new(Op::Payload, 0, name)))?;
        Ok(e)
    }

    /// Top-level `?x` lives in a hidden global named `?x`.
    fn toplevel_var(&mut self, t: Token<'s>, name: &str) -> PResult<Ix> {
        // a longer name would be cut in the buffer and share another's global
        if name.len() > 126 {
            return Err(self.err(t, "a variable name of at most 126 bytes"));
        }
        let mut b: TextBuf<128> = TextBuf::new();
        let _ = core::fmt::Write::write_fmt(&mut b, format_args!("?{name}"));
        let id = self.cx.intern(b.as_str());
        let id = cap!(self, id)?;
        if let Some(g) =
            (0..self.cx.st.pools.nglobals).find(|&g| self.cx.globals[g as usize].name == id)
        {
            return Ok(g);
        }
        let n = self.cx.st.pools.nglobals as usize;
        #[cfg(feature = "grow")]
        self.cx.ensure(crate::error::Pool::Globals, n + 1);
        if n >= self.cx.globals.len() {
            let c = crate::engine::cap(crate::error::Pool::Globals, self.cx.globals.len());
            return Err(self.cap_err(t, c));
        }
        self.cx.globals[n] = crate::template::Global {
            name: id,
            // unbound until bound (`eval::unbound_global`)
            value: Value::Void,
            init: NONE,
        };
        self.cx.st.pools.nglobals += 1;
        Ok(n as Ix)
    }

    fn push_call(&mut self, kind: FnKind, id: Ix) -> PResult<Ix> {
        let e = self.cx.push_expr(Expr::new(Op::Call, kind as u8, id));
        cap!(self, e)
    }

    /// Builtin call node by name (for desugaring special forms).
    pub fn builtin_call(&mut self, name: &'static str) -> PResult<Ix> {
        let (id, _) = builtins::lookup(name).unwrap_or((0, &builtins::BUILTINS[0]));
        self.push_call(FnKind::Builtin, id)
    }

    /// Parses arguments until `)`, appending them to `call`; returns their count.
    pub fn args_until_rparen(&mut self, call: Ix) -> PResult<Ix> {
        let mut n = 0;
        // the last child so far (`append_arg`)
        let mut tail = NONE;
        loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => {
                    self.next();
                    return Ok(n);
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                _ => {
                    let a = self.parse_expr()?;
                    self.append_arg(call, &mut tail, a);
                    n += 1;
                }
            }
        }
    }

    /// Appends argument `a` to `call`'s children after `tail`, the last child so far
    /// (`NONE` before the first), and makes `a` the last: appending walks on from the
    /// last child, not from the first (a right-hand side of hundreds of asserts was
    /// quadratic to read).
    #[inline]
    fn append_arg(&mut self, call: Ix, tail: &mut Ix, a: Ix) {
        if *tail == NONE {
            self.cx.append_child(call, a);
        } else {
            while self.cx.exprs[*tail as usize].next != NONE {
                *tail = self.cx.exprs[*tail as usize].next;
            }
            self.cx.exprs[*tail as usize].next = a;
        }
        *tail = a;
    }

    /// [`Parser::args_until_rparen`] of the call of the builtin of id `id`, noting
    /// each variable passed straight to an argument that restricts it
    /// (`rhs_types::RuleNotes`).
    #[cfg(feature = "extras")]
    fn builtin_args(&mut self, call: Ix, id: Ix) -> PResult<Ix> {
        if id == crate::builtins::environment::ID_PROGN {
            return self.args_until_rparen(call);
        }
        let mut n = 0;
        // the last child so far (`append_arg`)
        let mut tail = NONE;
        loop {
            let t = self.peek();
            let var = match t.tok {
                Tok::RParen => {
                    self.next();
                    return Ok(n);
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                // (a global `$?*g*` is none, nor `?x:slot` of a query)
                Tok::SfVar(v) if !v.contains(':') => Some((v, false)),
                Tok::MfVar(v) if !(v.len() > 2 && v.starts_with('*') && v.ends_with('*')) => {
                    Some((v, true))
                }
                _ => None,
            };
            let a = self.parse_expr()?;
            self.append_arg(call, &mut tail, a);
            n += 1;
            if let Some((name, mf)) = var {
                let seq_ops = self.cx.st.mode.seq_ops;
                let letter = super::rhs_types::letter_of(id, n as usize, mf, seq_ops);
                if letter != b'u' {
                    let src = self.lex.source();
                    self.cx.st.rule_notes.note_cand(src, name, letter);
                }
            }
        }
    }

    /// Notes the first value of a `bind` of `name` (about to be read) for
    /// `rhs_types::RuleNotes`.
    #[cfg(feature = "extras")]
    fn note_bind(&mut self, name: &'s str) {
        let first = self.peek().tok;
        let src = self.lex.source();
        let lex = &self.lex;
        let value = super::rhs_types::bind_value(src, first, || lex.clone().next_token().tok);
        self.cx.st.rule_notes.note_bind(src, name, value);
    }

    /// `(name args...)` after the `(`.
    fn call(&mut self) -> PResult<Ix> {
        let nt = self.next();
        let (module, name) = match nt.tok {
            // (an instance name `[x]` is no function name: `[EXPRNPSR1]` below)
            Tok::Symbol(s) if crate::value::instance_name_body(s).is_none() => {
                self.qualified_ref(nt, s)?
            }
            Tok::Eof | Tok::Bad => return Err(self.err(nt, "a function name")),
            // CLIPS's `[EXPRNPSR1]` for anything else there (a literal, a variable,
            // `(`, `)`, `&`...), a construct shown up to it
            _ => {
                let mut e = self.err(nt, "a function name");
                e.detail = crate::error::LoadDetail::Text {
                    text: "[EXPRNPSR1] A function name must be a symbol",
                };
                if self.construct != "command" {
                    e.echo_end = nt.end as u32;
                }
                return Err(e);
            }
        };
        let qualified = module != self.current_module();
        let (form, node) = match name {
            "if" => ("if", self.parse_if()?),
            "while" => ("while", self.parse_while()?),
            "bind" => {
                let node = self.parse_bind()?;
                // `(bind ?x a (expand$ ?y))` binds what `(bind ?x a ?y)` binds
                #[cfg(feature = "extras")]
                self.mark_expansions(node);
                return Ok(node);
            }
            "loop-for-count" => ("loop-for-count", self.parse_loop_for_count()?),
            "progn$" => ("progn$", self.parse_foreach("progn$")?),
            "foreach" => ("foreach", self.parse_foreach("foreach")?),
            "switch" => ("switch", self.parse_switch()?),
            "assert" => ("assert", self.parse_assert()?),
            "modify" => ("modify", self.parse_modify("modify")?),
            "duplicate" => ("duplicate", self.parse_modify("duplicate")?),
            _ => ("", NONE),
        };
        if node != NONE {
            // CLIPS's special forms take no sequence expansion
            #[cfg(feature = "extras")]
            self.refuse_expansions(node, form)?;
            let _ = form;
            return Ok(node);
        }
        // deffunctions shadow nothing builtin in CLIPS; check user functions first
        if let Some(sym) = self.cx.find_sym(name) {
            if let Some(f) = self.function_named(nt, sym, module) {
                let call = self.push_call(FnKind::Deffunction, f)?;
                let n = self.args_until_rparen(call)?;
                #[cfg(feature = "extras")]
                if self.expands(call, None)? {
                    return Ok(call);
                }
                self.check_function_arity(nt, f, n)?;
                return Ok(call);
            }
            if let Some(x) = (0..self.cx.st.pools.nexternals)
                .find(|&x| self.cx.externals[x as usize].name == sym)
            {
                let call = self.push_call(FnKind::External, x)?;
                let n = self.args_until_rparen(call)?;
                #[cfg(feature = "extras")]
                if self.expands(call, None)? {
                    return Ok(call);
                }
                let ext = self.cx.externals[x as usize];
                if crate::eval::check_arity("external", ext.min, ext.max, n).is_err() {
                    return Err(self.err(nt, "the function's number of arguments"));
                }
                return Ok(call);
            }
        }
        if qualified {
            let mut e = self.err(nt, "a deffunction the module sees");
            e.detail = crate::error::LoadDetail::MissingFunction;
            e.echo_end = nt.end as u32;
            return Err(e);
        }
        match builtins::lookup(name) {
            Some((id, b)) => {
                // `break` outside a loop's body and `return` outside a deffunction or a
                // rule's actions: CLIPS refuses them when it reads them
                if (b.name == "break" && self.loop_depth == 0)
                    || (b.name == "return" && self.scope == Scope::TopLevel)
                {
                    let mut e = self.err(nt, "a loop body (break) or actions (return)");
                    e.detail = crate::error::LoadDetail::NotInContext { func: b.name };
                    e.echo_end = nt.end as u32;
                    return Err(e);
                }
                let call = self.push_call(FnKind::Builtin, id)?;
                let args_at = self.save();
                let n = if b.syntax == Syntax::Query {
                    self.loop_depth += 1;
                    let r = self.query_args(call, b.name);
                    self.loop_depth -= 1;
                    r?
                } else if b.name == "progn" {
                    self.args_until_rparen(call).map_err(|mut e| {
                        self.back_up_action(&mut e);
                        e
                    })?
                } else {
                    #[cfg(feature = "extras")]
                    let n = self.builtin_args(call, id)?;
                    #[cfg(not(feature = "extras"))]
                    let n = self.args_until_rparen(call)?;
                    n
                };
                // arguments that expand are counted and typed when the call runs
                #[cfg(feature = "extras")]
                {
                    let takes_none = b.syntax == Syntax::Query
                        || matches!(b.name, "expand$" | "progn" | "return" | "break");
                    if self.expands(call, takes_none.then_some(b.name))? {
                        return Ok(call);
                    }
                }
                // CLIPS reads one value and then wants the `)`
                if b.name == "return" && n > 1 {
                    let resume = self.save();
                    self.restore(args_at);
                    self.skip_balanced()?;
                    let at = self.peek();
                    self.restore(resume);
                    return Err(self.syntax_of(at, "')' after the value", "return function"));
                }
                if crate::eval::check_arity(b.name, b.min, b.max, n).is_err() {
                    let mut e = self.err(nt, arity_text(b.min, b.max));
                    e.detail = crate::error::LoadDetail::Arity {
                        func: b.name,
                        min: b.min,
                        max: b.max,
                        got: n,
                    };
                    // a construct is shown up to the call's `)`
                    if matches!(
                        self.construct,
                        "defrule" | "deffunction" | "deftemplate" | "deffacts" | "defglobal"
                    ) {
                        e.echo_end = self.lex.pos() as u32;
                    }
                    return Err(e);
                }
                // the image leaves this to `watch` itself (a run-time refusal): its
                // code budget is tight
                #[cfg(feature = "extras")]
                if matches!(b.name, "watch" | "unwatch") {
                    self.check_watch_items(b.name, call, args_at)?;
                    return Ok(call);
                }
                if b.syntax == Syntax::Plain {
                    self.check_literal_args(b, id, call, args_at)?;
                }
                Ok(call)
            }
            None if self.defining_fn != NONE && self.is_defining(name) => {
                let f = self.defining_fn;
                let call = self.push_call(FnKind::Deffunction, f)?;
                let n = self.args_until_rparen(call)?;
                #[cfg(feature = "extras")]
                if self.expands(call, None)? {
                    return Ok(call);
                }
                self.check_function_arity(nt, f, n)?;
                Ok(call)
            }
            None => {
                // CLIPS 6.30 functions we leave out on purpose, refused as such
                #[cfg(feature = "extras")]
                if let Some(what) = not_implemented_function(name) {
                    return Err(self.not_implemented(nt, what));
                }
                let mut e = self.err(nt, "a known function name");
                e.detail = crate::error::LoadDetail::MissingFunction;
                // CLIPS shows the construct up to the name
                e.echo_end = nt.end as u32;
                Err(e)
            }
        }
    }

    /// The deffunction a call names. Written `M::f`, CLIPS takes only an `f` that `M`
    /// itself defines, and only if `M` is the current module or exports it (an import
    /// of `M`'s does not count, nor does a module that imports `M`).
    fn function_named(
        &self,
        nt: Token<'s>,
        sym: crate::value::SymId,
        module: crate::module::ModId,
    ) -> Option<Ix> {
        let f = self.cx.find_function(sym, module)?;
        #[cfg(feature = "modules")]
        if let Tok::Symbol(s) = nt.tok {
            if crate::module::split_qualified(s).is_some()
                && (self.cx.module_of_function(f) != module
                    || (module != self.current_module()
                        && !self
                            .cx
                            .exports_own(module, crate::module::class::FUNCTION, sym)))
            {
                return None;
            }
        }
        let _ = nt;
        Some(f)
    }

    /// CLIPS rejects a literal argument of a type the builtin never takes when it
    /// parses the call, and a call whose return type it never takes; the error points
    /// at the argument (`args_at`: where the arguments start, to find it again).
    ///
    /// The types are builtin `b`'s (row `id`, found by its name: the row
    /// `describe::arg_type` would find again for each argument).
    ///
    /// A numeric builtin's call (`id`) whose later argument is more than a constant or
    /// a variable goes on to `order_numeric_args`; one of constants and variables only
    /// is noted (`quiet_numeric`).
    fn check_literal_args(
        &mut self,
        b: &'static builtins::Builtin,
        id: Ix,
        call: Ix,
        args_at: (Lexer<'s>, Option<Token<'s>>),
    ) -> PResult<()> {
        let (func, sig) = (b.name, &b.signature);
        // what the arguments are besides constants and variables (`order_numeric_args`):
        // 1 the first, 2 a later one, 4 a later quiet numeric call (`quiet_numeric`)
        let mut more = 0u8;
        let mut c = self.cx.exprs[call as usize].first;
        let mut k = 0;
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            let ty = sig.get(k);
            let refused = match x.op {
                Op::Int | Op::Float | Op::Sym | Op::Str => !ty.admits(self.cx.const_value(c)),
                // a builtin's result of a type the position never takes
                Op::Call if x.aux == FnKind::Builtin as u8 => {
                    more |= if k == 0 {
                        1
                    } else if c == self.quiet_numeric {
                        4
                    } else {
                        2
                    };
                    !ty.admits_call(builtins::get(x.data).returns)
                }
                Op::Local | Op::PatVar => false,
                _ => {
                    more |= if k == 0 { 1 } else { 2 };
                    false
                }
            };
            if refused {
                let resume = self.save();
                self.restore(args_at);
                for _ in 0..k {
                    self.skip_balanced()?;
                }
                let at = self.peek();
                self.restore(resume);
                let mut e = self.err(at, ty.expected());
                e.detail = crate::error::LoadDetail::ArgType {
                    func,
                    arg: k as Ix + 1,
                    expected: ty.clips_name(),
                };
                // a construct is shown up to the call's `)`
                if matches!(
                    self.construct,
                    "defrule" | "deffunction" | "deftemplate" | "deffacts" | "defglobal"
                ) {
                    e.echo_end = self.lex.pos() as u32;
                }
                return Err(e);
            }
            c = self.cx.exprs[c as usize].next;
            k += 1;
        }
        if more == 0 {
            if builtins::ordered::has_twin(id) {
                self.quiet_numeric = call;
            }
        } else if more & 2 != 0 && builtins::ordered::has_twin(id) {
            self.order_numeric_args(call);
        }
        Ok(())
    }

    #[cfg(feature = "extras")]
    /// `watch`/`unwatch` items given as literals: one CLIPS does not know is its
    /// `[ARGACCES5]`; one we do not trace (`focus`, `globals`, ...; `all` for `watch`)
    /// and classes after a COOL item (`(watch instances USER)`) are refused rather
    /// than accepted and ignored.
    fn check_watch_items(
        &mut self,
        func: &'static str,
        call: Ix,
        args_at: (Lexer<'s>, Option<Token<'s>>),
    ) -> PResult<()> {
        let mut c = self.cx.exprs[call as usize].first;
        let mut k = 0;
        // COOL's items with constructs: we have no classes to name
        let mut classes = false;
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            c = x.next;
            k += 1;
            if x.op != Op::Sym && k == 1 {
                continue;
            }
            // construct names after the item (`(watch facts t)`) are looked up when
            // the command runs, as CLIPS does
            if k == 1 {
                classes = matches!(
                    self.cx.sym_text(x.data),
                    "instances" | "slots" | "message-handlers"
                );
            } else if !classes {
                continue;
            }
            let known = k > 1
                || match crate::builtins::commands::watch_item(self.cx.sym_text(x.data)) {
                    crate::builtins::commands::WatchItem::Traced(_) => continue,
                    crate::builtins::commands::WatchItem::Cool(_) => continue,
                    crate::builtins::commands::WatchItem::All
                        if func == "unwatch" || crate::builtins::commands::ALL_TRACED =>
                    {
                        continue
                    }
                    crate::builtins::commands::WatchItem::Unknown => false,
                    _ => true,
                };
            let resume = self.save();
            self.restore(args_at);
            for _ in 1..k {
                self.skip_balanced()?;
            }
            let at = self.peek();
            self.restore(resume);
            if known {
                return Err(self.not_implemented(at, "watch of this item"));
            }
            let mut e = self.err(at, "a watchable symbol");
            e.detail = crate::error::LoadDetail::ArgType {
                func,
                arg: k as Ix,
                expected: "watchable symbol",
            };
            return Err(e);
        }
        Ok(())
    }

    /// A call of a numeric builtin (`+`, `=`, `div`, ...) whose later argument could
    /// print or change something (not `quiet_operand`) after an argument that could
    /// end CLIPS's evaluation of them (`may_end_numbers`) becomes a call of its twin,
    /// which takes its arguments in CLIPS's order (`builtins::ordered`). Other calls
    /// keep the eager path: their arguments cannot tell.
    #[inline(never)]
    fn order_numeric_args(&mut self, call: Ix) {
        let x = self.cx.exprs[call as usize];
        // host: `+`, `-` or `*` of two operands, one a query's slot read: the twin,
        // whose in-place fold reads query slots (`Core::quick_twin_arith`; the plain
        // call's `quick_arith`, on every rule's path, does not)
        #[cfg(all(feature = "host-speedups", feature = "grow"))]
        if x.data.wrapping_sub(builtins::basic::ARITH_FIRST) < 3 && self.query_slot_pair(x.first) {
            if let Some(twin) = builtins::ordered::twin_of(x.data) {
                self.cx.exprs[call as usize].data = twin;
            }
            return;
        }
        let (mut c, mut at, mut may_end) = (x.first, 0, false);
        while c != NONE {
            if may_end && c != self.quiet_numeric && !self.quiet_operand(c, true) {
                if let Some(twin) = builtins::ordered::twin_of(x.data) {
                    self.cx.exprs[call as usize].data = twin;
                }
                return;
            }
            may_end = may_end || self.may_end_numbers(x.data, c, at);
            at += 1;
            c = self.cx.exprs[c as usize].next;
        }
    }

    /// Host: whether the arguments from `a` are two, one of them `?v:slot`.
    #[cfg(all(feature = "host-speedups", feature = "grow"))]
    fn query_slot_pair(&self, a: Ix) -> bool {
        if a == NONE {
            return false;
        }
        let (p, b) = (self.cx.exprs[a as usize], self.cx.exprs[a as usize].next);
        if b == NONE {
            return false;
        }
        let q = self.cx.exprs[b as usize];
        q.next == NONE && (p.op == Op::QSlot || q.op == Op::QSlot)
    }

    /// Whether argument `at` (node `c`) of numeric builtin `id` may end its arguments
    /// in CLIPS (`eval::ends_numbers`) once evaluated without an error: a constant that
    /// does, a variable, a call of no number (a deffunction, a builtin returning
    /// another type), or any call as a divisor of `/` or `div`.
    fn may_end_numbers(&self, id: Ix, c: Ix, at: Ix) -> bool {
        let y = self.cx.exprs[c as usize];
        match y.op {
            Op::Int | Op::Float | Op::Sym | Op::Str => {
                crate::eval::ends_numbers(id, self.cx.const_value(c), at)
            }
            Op::Call if y.aux == FnKind::Builtin as u8 => {
                use crate::builtins::describe::Returns;
                const SLASH: Ix = builtins::builtin_id("/");
                const DIV: Ix = builtins::builtin_id("div");
                (at > 0 && (id == SLASH || id == DIV))
                    || !matches!(
                        builtins::get(y.data).returns,
                        Returns::Number | Returns::Integer | Returns::Float
                    )
            }
            _ => true,
        }
    }

    /// Whether node `c` prints and changes nothing when it is evaluated, and fails, if
    /// it does, with an error it leaves to its caller: a constant, a local or LHS
    /// variable, a defglobal (not a prompt variable or an undefined `?*g*`, which print
    /// when unbound), and (`call`) a quiet builtin's call of those.
    fn quiet_operand(&self, c: Ix, call: bool) -> bool {
        let y = self.cx.exprs[c as usize];
        match y.op {
            Op::Int | Op::Float | Op::Sym | Op::Str | Op::Local | Op::PatVar => true,
            Op::QSlot => self.cx.exprs[y.first as usize].aux == QSLOT_QUIET,
            Op::Global => !self
                .cx
                .sym_text(self.cx.globals[y.data as usize].name)
                .starts_with('?'),
            // host: `(length$ ?l)` of an LHS multifield variable reads a multifield's
            // length: nothing to fail on or print beyond the variable's own read
            #[cfg(feature = "host-speedups")]
            Op::Call
                if call
                    && y.aux == FnKind::Builtin as u8
                    && y.data == LENGTH_ID
                    && self.multifield_pat_var(y.first) =>
            {
                true
            }
            Op::Call if call && y.aux == FnKind::Builtin as u8 && builtins::is_quiet(y.data) => {
                let mut d = y.first;
                while d != NONE {
                    if !self.quiet_operand(d, false) {
                        return false;
                    }
                    d = self.cx.exprs[d as usize].next;
                }
                true
            }
            _ => false,
        }
    }

    /// Host: whether node `c` reads an LHS multifield variable (`$?l`, as `?l` in
    /// the actions), whose value is always a multifield.
    #[cfg(feature = "host-speedups")]
    fn multifield_pat_var(&self, c: Ix) -> bool {
        if c == NONE {
            return false;
        }
        let y = self.cx.exprs[c as usize];
        if y.op != Op::PatVar || y.next != NONE || y.data == crate::expr::loc::FACT {
            return false;
        }
        let mut found = false;
        for v in &self.vars[..self.nvars] {
            if v.kind
                == (VarKind::Pat {
                    pat: y.aux,
                    loc: y.data,
                    desc: y.first,
                })
            {
                if !v.multi || v.rebound != NONE {
                    return false;
                }
                found = true;
            }
        }
        found
    }

    /// Turns the `(expand$ X)` arguments of call `node` into sequence expansions
    /// (`Op::Expand`, `aux` 1); whether it has any (`$?x` read with recognition too).
    #[cfg(feature = "extras")]
    fn mark_expansions(&mut self, node: Ix) -> bool {
        let mut found = false;
        let mut c = self.cx.exprs[node as usize].first;
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            if x.op == Op::Call
                && x.aux == FnKind::Builtin as u8
                && x.data == crate::builtins::environment::ID_EXPAND
            {
                self.cx.exprs[c as usize] = Expr {
                    first: x.first,
                    next: x.next,
                    ..Expr::new(Op::Expand, 1, 0)
                };
                found = true;
            } else if x.op == Op::Expand && x.aux == 1 {
                found = true;
            }
            c = x.next;
        }
        found
    }

    /// A call whose arguments expand becomes CLIPS's `(expansion-call)` of it (in
    /// place: its parent's links stay), which counts and checks the arguments when it
    /// runs; `refuse` names a function that takes no expansion (`[EXPRNPSR4]`).
    #[cfg(feature = "extras")]
    fn expands(&mut self, call: Ix, refuse: Option<&'static str>) -> PResult<bool> {
        if !self.mark_expansions(call) {
            return Ok(false);
        }
        if let Some(func) = refuse {
            return Err(self.sequence_error(func));
        }
        let x = self.cx.exprs[call as usize];
        let inner = cap!(self, self.cx.push_expr(Expr { next: NONE, ..x }))?;
        self.cx.exprs[call as usize] = Expr {
            first: inner,
            next: x.next,
            ..Expr::new(
                Op::Call,
                FnKind::Builtin as u8,
                crate::builtins::environment::ID_EXPANSION_CALL,
            )
        };
        Ok(true)
    }

    /// `[EXPRNPSR4]` for a sequence expansion among the arguments of `func` (a
    /// special form or action block `node`; calls inside were checked already).
    #[cfg(feature = "extras")]
    pub(super) fn refuse_expansions(&mut self, node: Ix, func: &'static str) -> PResult<()> {
        let mut c = self.cx.exprs[node as usize].first;
        while c != NONE {
            let x = self.cx.exprs[c as usize];
            let expansion = (x.op == Op::Expand && x.aux == 1)
                || (x.op == Op::Call
                    && x.aux == FnKind::Builtin as u8
                    && x.data == crate::builtins::environment::ID_EXPAND);
            if expansion {
                return Err(self.sequence_error(func));
            }
            // switch cases, asserted facts and their slots hold arguments too
            if matches!(x.op, Op::Nop | Op::FactSpec | Op::SlotVal) {
                self.refuse_expansions(c, func)?;
            }
            c = x.next;
        }
        Ok(())
    }

    /// CLIPS's `[EXPRNPSR4]`, the construct shown up to what was read.
    #[cfg(feature = "extras")]
    fn sequence_error(&mut self, func: &'static str) -> crate::error::LoadError {
        let end = match self.peeked {
            Some(t) => t.start,
            None => self.lex.pos(),
        };
        let at = self.peek();
        let mut e = self.err(at, "no sequence expansion among these arguments");
        e.detail = crate::error::LoadDetail::SequenceOperator { func, whole: false };
        e.echo_end = end as u32;
        e
    }

    /// The end of an action block that stops before a keyword or `)`.
    fn end_block(&mut self, p: Ix) -> PResult<Ix> {
        #[cfg(feature = "extras")]
        self.refuse_expansions(p, "progn")?;
        Ok(p)
    }

    /// CLIPS's `[ARGACCES4]` for a call of deffunction `f` with `n` arguments (the
    /// one being defined too: its parameters are read before its body), the
    /// construct shown up to the call's `)`.
    fn check_function_arity(&mut self, nt: Token<'s>, f: Ix, n: Ix) -> PResult<()> {
        let df = self.cx.funcs[f as usize];
        if n >= df.nparams as Ix && (df.rest || n <= df.nparams as Ix) {
            return Ok(());
        }
        let mut e = self.err(nt, "the deffunction's number of arguments");
        e.detail = crate::error::LoadDetail::FunctionArity {
            nparams: df.nparams,
            rest: df.rest,
        };
        if matches!(
            self.construct,
            "defrule" | "deffunction" | "deftemplate" | "deffacts" | "defglobal"
        ) {
            e.echo_end = self.lex.pos() as u32;
        }
        Err(e)
    }

    fn is_defining(&mut self, name: &str) -> bool {
        let f = self.defining_fn;
        self.cx.find_sym(name) == Some(self.cx.funcs[f as usize].name)
    }

    /// Actions until `)`, wrapped in a `progn` node.
    /// A loop's body: `break` is allowed in it (CLIPS refuses it elsewhere).
    fn loop_body(&mut self) -> PResult<Ix> {
        self.loop_depth += 1;
        let r = self.action_block();
        self.loop_depth -= 1;
        r
    }

    pub fn action_block(&mut self) -> PResult<Ix> {
        let p = self.builtin_call("progn")?;
        self.args_until_rparen(p)?;
        #[cfg(feature = "extras")]
        self.refuse_expansions(p, "progn")?;
        Ok(p)
    }

    /// Actions until one of the keywords or `)`; the stopping token is not consumed.
    fn actions_until(&mut self, stop: &[&str]) -> PResult<Ix> {
        let p = self.builtin_call("progn")?;
        loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => return self.end_block(p),
                Tok::Symbol(s) if stop.contains(&s) => return self.end_block(p),
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                _ => {
                    let a = self.parse_expr()?;
                    self.cx.append_child(p, a);
                }
            }
        }
    }

    fn parse_if(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("if")?;
        let cond = self.parse_expr()?;
        self.cx.append_child(node, cond);
        let t = self.next();
        if t.tok != Tok::Symbol("then") {
            return Err(self.syntax_of(t, "keyword 'then'", "if function"));
        }
        let then = self.actions_until(&["else"])?;
        self.cx.append_child(node, then);
        let t = self.next();
        match t.tok {
            Tok::RParen => Ok(node),
            Tok::Symbol("else") => {
                let els = self.action_block()?;
                self.cx.append_child(node, els);
                Ok(node)
            }
            _ => Err(self.err(t, "else or ')'")),
        }
    }

    fn parse_while(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("while")?;
        let cond = self.parse_expr()?;
        self.cx.append_child(node, cond);
        self.loop_do("while function")?;
        let body = self.loop_body()?;
        self.cx.append_child(node, body);
        Ok(node)
    }

    /// After a loop's condition or range CLIPS wants `do` or an action's `(`: a word
    /// (`then`), a constant, a variable or the loop's `)` is a syntax error, shown
    /// glued to the text before it (`(while (> ?n 0)then`).
    fn loop_do(&mut self, part: &'static str) -> PResult<()> {
        let t = self.peek();
        match t.tok {
            Tok::Symbol("do") => {
                self.next();
                Ok(())
            }
            Tok::LParen => Ok(()),
            _ => {
                let mut e = self.syntax_of(t, "'do' or an action", part);
                e.echo_tail = crate::error::EchoTail::Glued;
                Err(e)
            }
        }
    }

    /// Whether variables are the prompt's (hidden globals): at top level, and in a
    /// defglobal's values, which CLIPS evaluates at the prompt (a variable nothing
    /// bound there is `[EVALUATN1]` when the value is computed; one a value binds
    /// stays bound).
    /// (a rule's salience is evaluated as it is read, its variables the prompt's)
    fn at_prompt(&self) -> bool {
        self.scope == Scope::TopLevel
            || (self.scope == Scope::Frame
                && (self.construct == "defglobal"
                    || (self.evaluated_now && self.construct == "defrule")))
    }

    /// Node for assigning to variable `name`: a frame local (created if new) or, at
    /// top level, a hidden global.
    fn assign_target(&mut self, t: Token<'s>, name: &'s str) -> PResult<Ix> {
        if let Some(v) = self.find_var(name) {
            if let VarKind::Local(s) = v.kind {
                let e = self.cx.push_expr(Expr::new(Op::Local, 0, s));
                return cap!(self, e);
            }
            // an LHS variable: as in CLIPS, from here on the name is a local of the
            // RHS holding the new value (a new entry shadows the LHS one)
        }
        match self.scope {
            _ if self.at_prompt() => {
                let g = self.toplevel_var(t, name)?;
                let e = self.cx.push_expr(Expr::new(Op::Global, 0, g));
                cap!(self, e)
            }
            _ => {
                let s = self.new_local(t, name, false)?;
                if self.in_nested_action() {
                    // bound only on some paths: reads check it (`Core::local`)
                    let sym = cap!(self, self.cx.intern(name))?;
                    self.vars[self.nvars - 1].unbound_name = sym;
                }
                let e = self.cx.push_expr(Expr::new(Op::Local, 0, s));
                cap!(self, e)
            }
        }
    }

    fn parse_bind(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("bind")?;
        let name_end = self.consumed_end();
        let t = self.next();
        let name = match t.tok {
            Tok::SfVar(name) | Tok::MfVar(name) => {
                self.binds = self.binds.wrapping_add(1);
                let (lo, hi) = self.query_vars;
                if self.query_rebind.is_none()
                    && self.vars[lo..hi.min(self.nvars)]
                        .iter()
                        .any(|v| v.name == name)
                {
                    self.query_rebind = Some(t);
                }
                name
            }
            Tok::Global(name) => {
                let target = self.global_ref(t, name)?;
                self.cx.append_child(node, target);
                self.args_until_rparen(node)?;
                return Ok(node);
            }
            _ => {
                // CLIPS shows the construct up to the token (`(bind )` for none)
                let mut e = self.syntax_of(t, "a variable", "bind function");
                if t.tok == Tok::RParen {
                    e.echo_end = name_end as u32;
                    e.echo_tail = crate::error::EchoTail::SpaceBefore;
                }
                return Err(e);
            }
        };
        if let Some(v) = self.find_var(name).filter(|v| v.rebound != NONE) {
            // an LHS variable the actions bind: its frame slot (`declare_bound_vars`)
            let target = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 0, v.rebound)))?;
            self.cx.append_child(node, target);
            #[cfg(feature = "extras")]
            self.note_bind(name);
            self.args_until_rparen(node)?;
            return Ok(node);
        }
        if !matches!(self.find_var(name), Some(v) if matches!(v.kind, VarKind::Pat { .. })) {
            // a new or existing local: CLIPS knows it in the value too (unbound there
            // it is a run-time error, as in CLIPS)
            let target = self.assign_target(t, name)?;
            self.cx.append_child(node, target);
            #[cfg(feature = "extras")]
            self.note_bind(name);
            self.args_until_rparen(node)?;
            return Ok(node);
        }
        // rebinding an LHS variable: the value's `?x` is still the LHS one
        // (`(bind ?x (+ ?x 1))`); the RHS local that shadows it starts after
        let values = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        #[cfg(feature = "extras")]
        self.note_bind(name);
        self.args_until_rparen(values)?;
        let target = self.assign_target(t, name)?;
        self.cx.append_child(node, target);
        self.cx.exprs[target as usize].next = self.cx.exprs[values as usize].first;
        Ok(node)
    }

    fn parse_loop_for_count(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("loop-for-count")?;
        let t = self.peek();
        let (var, start, end);
        let range = t.tok == Tok::LParen && {
            self.next();
            matches!(self.peek().tok, Tok::SfVar(_))
        };
        if range {
            let vt = self.next();
            let Tok::SfVar(name) = vt.tok else {
                return Err(self.err(vt, "a loop variable"));
            };
            let s = self.new_local(vt, name, false)?;
            var = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 0, s)))?;
            let at = self.peek();
            let a = self.parse_expr()?;
            self.loop_bound_literal(at, a)?;
            if self.peek().tok == Tok::RParen {
                start = cap!(self, self.cx.push_const(Value::Int(1)))?;
                end = a;
                self.expect_rparen("')' after the loop range")?;
            } else {
                start = a;
                let at = self.peek();
                end = self.parse_expr()?;
                // CLIPS checks the end bound after the range's `)`
                let close = self.peek();
                self.expect_rparen("')' after the loop range")?;
                if let Err(mut e) = self.loop_bound_literal(at, end) {
                    e.echo_end = close.end as u32;
                    return Err(e);
                }
            }
        } else if t.tok == Tok::LParen {
            // `(loop-for-count (+ 1 2) ...)`: the count is a call (its `(` read above);
            // `(1 2)` is neither a range nor a call, and CLIPS refuses it as a bad range
            let head = self.peek();
            if !matches!(head.tok, Tok::Symbol(_)) {
                return Err(self.err(head, "a loop variable"));
            }
            var = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
            start = cap!(self, self.cx.push_const(Value::Int(1)))?;
            end = self.call()?;
        } else {
            var = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
            start = cap!(self, self.cx.push_const(Value::Int(1)))?;
            end = self.parse_expr()?;
            self.loop_bound_literal(t, end)?;
        }
        self.cx.append_child(node, var);
        self.cx.append_child(node, start);
        self.cx.append_child(node, end);
        self.loop_do("loop-for-count function")?;
        let body = self.loop_body()?;
        self.cx.append_child(node, body);
        Ok(node)
    }

    /// A loop count or bound written as a constant must be an integer: CLIPS refuses a
    /// float, symbol or string there while parsing (a computed float is truncated).
    fn loop_bound_literal(&self, at: crate::lexer::Token<'s>, e: Ix) -> PResult<()> {
        match self.cx.exprs[e as usize].op {
            Op::Float | Op::Sym | Op::Str => Err(self.syntax_of(
                at,
                "an integer loop count or bound",
                "loop-for-count function",
            )),
            _ => Ok(()),
        }
    }

    /// `(progn$ (?v list) body)` or `(foreach ?v list body)`; `?v-index` is the next
    /// frame slot. `(progn$ list body)` has no variable: the fields go to two frame
    /// slots no name reaches.
    fn parse_foreach(&mut self, name: &'static str) -> PResult<Ix> {
        let node = self.builtin_call(name)?;
        let paren = self.peek().tok == Tok::LParen;
        if paren {
            self.next();
        }
        let named = matches!(self.peek().tok, Tok::SfVar(_)) && (paren || name == "foreach");
        if name == "progn$" && !named {
            let at = self.peek();
            // the call whose `(` was read above, or any expression
            let list = if paren {
                self.call()?
            } else {
                self.parse_expr()?
            };
            let slot = self.nlocals;
            if slot >= 254 {
                return Err(self.err(at, "at most 255 local variables in one construct"));
            }
            self.nlocals += 2;
            let var = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 0, slot)))?;
            self.cx.append_child(node, var);
            self.cx.append_child(node, list);
            if self.peek().tok == Tok::Symbol("do") {
                self.next();
            }
            let body = self.loop_body().map_err(|mut e| {
                self.back_up_action(&mut e);
                e
            })?;
            self.cx.append_child(node, body);
            return Ok(node);
        }
        let vt = self.next();
        let vname = match vt.tok {
            Tok::SfVar(n) => n,
            _ => return Err(self.err(vt, "a loop variable")),
        };
        let list = self.parse_expr()?;
        if paren {
            self.expect_rparen("')' after the list expression")?;
        }
        let s = self.new_local(vt, vname, false)?;
        // the index variable name is `<name>-index`, which lives in the source only as
        // a reference; register it by matching references later
        let idx_slot = self.nlocals;
        self.nlocals += 1;
        self.index_var(vt, vname, idx_slot)?;
        let var = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 0, s)))?;
        self.cx.append_child(node, var);
        self.cx.append_child(node, list);
        if self.peek().tok == Tok::Symbol("do") {
            self.next();
        }
        let body = self.loop_body().map_err(|mut e| {
            self.back_up_action(&mut e);
            e
        })?;
        self.cx.append_child(node, body);
        Ok(node)
    }

    /// Registers `?name-index` by scanning ahead for its spelling in the source.
    fn index_var(&mut self, at: Token<'s>, vname: &'s str, slot: Ix) -> PResult<()> {
        let src = self.lex.source();
        let pos = self.lex.pos();
        let rest = &src[pos..];
        let mut i = 0;
        while let Some(k) = rest[i..].find(vname) {
            let s = i + k;
            let after = &rest[s + vname.len()..];
            if s > 0 && rest.as_bytes()[s - 1] == b'?' && after.starts_with("-index") {
                let name = &rest[s..s + vname.len() + 6];
                return self.add_var(at, name, VarKind::Local(slot), false);
            }
            i = s + vname.len();
        }
        Ok(())
    }

    fn parse_switch(&mut self) -> PResult<Ix> {
        let node = self.builtin_call("switch")?;
        let e = self.parse_expr()?;
        self.cx.append_child(node, e);
        let mut default_seen = false;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => return Ok(node),
                Tok::LParen => {
                    let kw = self.next();
                    match kw.tok {
                        // the default comes last (CLIPS refuses anything after it)
                        Tok::Symbol("case" | "default") if default_seen => {
                            return Err(self.syntax_of(
                                kw,
                                "')' ending switch (nothing may follow the default)",
                                "switch function",
                            ));
                        }
                        Tok::Symbol("case") => {
                            let case = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
                            let v = self.parse_expr()?;
                            self.cx.append_child(case, v);
                            let th = self.next();
                            if th.tok != Tok::Symbol("then") {
                                return Err(self.syntax_of(
                                    th,
                                    "keyword 'then'",
                                    "switch function",
                                ));
                            }
                            let body = self.action_block()?;
                            self.cx.append_child(case, body);
                            self.cx.append_child(node, case);
                        }
                        Tok::Symbol("default") => {
                            default_seen = true;
                            let case = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 1, 0)))?;
                            let body = self.action_block()?;
                            self.cx.append_child(case, body);
                            self.cx.append_child(node, case);
                        }
                        _ => return Err(self.err(kw, "case or default")),
                    }
                }
                _ => return Err(self.err(t, "a case")),
            }
        }
    }

    /// Fact-set query arguments: `((?v tmpl...)...)` then ordinary expressions, where
    /// `?v:slot` reads a slot of the bound fact. Errors as CLIPS's `factqpsr.c` gives
    /// them: `[PRNTUTIL2] ... fact-set query function.` for the query's own syntax
    /// (and after an error in its actions), `[FACTQPSR1-3]`.
    fn query_args(&mut self, call: Ix, func: &'static str) -> PResult<Ix> {
        let outer = self.query_decl;
        let r = self.query_args_in(call, func);
        self.query_decl = outer;
        r
    }

    /// `query_args` once the enclosing query's declarations are saved: this query's
    /// declarations node becomes the innermost (`query_decl`) when they are read.
    fn query_args_in(&mut self, call: Ix, func: &'static str) -> PResult<Ix> {
        const PART: &str = "fact-set query function";
        let decl = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        self.cx.append_child(call, decl);
        let t = self.next();
        if t.tok != Tok::LParen {
            return Err(self.syntax_of(t, "'(' opening the query variables", PART));
        }
        let saved_vars = self.nvars;
        let mut first = true;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen if !first => break,
                Tok::LParen => {
                    let vt = self.next();
                    let vname = match vt.tok {
                        Tok::SfVar(n) => n,
                        _ => return Err(self.syntax_of(vt, "a query variable", PART)),
                    };
                    if self.vars[saved_vars..self.nvars]
                        .iter()
                        .any(|v| v.name == vname)
                    {
                        let mut e = self.err(vt, "a query variable not declared before");
                        e.detail = crate::error::LoadDetail::Query { what: 1, func };
                        e.echo_end = vt.end as u32;
                        return Err(e);
                    }
                    let slot = self.new_local(vt, vname, false)?;
                    let var = cap!(self, self.cx.push_expr(Expr::new(Op::Local, 0, slot)))?;
                    let mut names = 0;
                    loop {
                        let tt = self.peek();
                        match tt.tok {
                            Tok::RParen if names == 0 => {
                                self.next();
                                return Err(self.syntax_of(tt, "a template name", PART));
                            }
                            Tok::RParen => {
                                self.next();
                                break;
                            }
                            Tok::Symbol(tn) => {
                                self.next();
                                let sym = cap!(self, self.cx.intern(tn))?;
                                if self.cx.find_template(sym).is_none() {
                                    // `[PRNTUTIL1]`, the construct up to the name
                                    let mut e = self.err(tt, "a deftemplate name");
                                    e.detail = crate::error::LoadDetail::NoSuchTemplate;
                                    if self.construct != "command" {
                                        e.echo_end = tt.end as u32;
                                    }
                                    return Err(e);
                                }
                                let te = cap!(self, self.cx.push_expr(Expr::new(Op::Sym, 0, sym)))?;
                                self.cx.append_child(var, te);
                            }
                            Tok::Eof | Tok::Bad => return Err(self.err(tt, "a template name")),
                            _ => {
                                // any other expression names its templates when the
                                // query runs (a symbol or a multifield of them)
                                let te = self.parse_expr()?;
                                self.cx.append_child(var, te);
                                self.cx.exprs[decl as usize].aux = 1;
                            }
                        }
                        names += 1;
                    }
                    self.cx.append_child(decl, var);
                }
                _ => return Err(self.syntax_of(t, "'(' and a query variable", PART)),
            }
            first = false;
        }
        self.cx.exprs[decl as usize].data = self.query_decl;
        self.query_decl = decl;
        // the condition: no `bind` in it (`[FACTQPSR2]`)
        let t = self.peek();
        if matches!(t.tok, Tok::RParen) {
            self.next();
            return Err(self.syntax_of(t, "the query's condition", PART));
        }
        let binds = self.binds;
        let cond = self.parse_expr()?;
        self.cx.append_child(call, cond);
        if self.binds != binds {
            let end = self.consumed_end();
            let at = self.peek();
            let mut e = self.err(at, "a condition without bind");
            e.detail = crate::error::LoadDetail::Query { what: 2, func };
            e.echo_end = end as u32;
            return Err(e);
        }
        let mut n = 2;
        if !func.starts_with("do-for") && !func.starts_with("delayed-do-for") {
            // any-factp, find-first-fact, find-all-facts: the `)` after the condition
            let t = self.next();
            if t.tok != Tok::RParen {
                let mut e = self.syntax_of(t, "')' after the query's condition", PART);
                e.echo_tail = crate::error::EchoTail::Glued;
                return Err(e);
            }
        } else {
            // the actions; an error there is followed by the query's syntax error,
            // the construct shown as CLIPS's pretty-print buffer holds it then
            let outer = (self.query_vars, self.query_rebind.take());
            self.query_vars = (saved_vars, self.nvars);
            let r = self.query_actions(call);
            let rebind = core::mem::replace(&mut self.query_rebind, outer.1);
            self.query_vars = outer.0;
            n += match r {
                Ok(k) => k,
                // (the input ending there is no syntax error: CLIPS waits for more;
                // an undefined global or variable CLIPS finds once the construct is
                // read whole)
                Err(e)
                    if e.expected == super::INPUT_ENDED
                        || matches!(
                            e.detail,
                            crate::error::LoadDetail::UndefinedGlobal { whole: true }
                                | crate::error::LoadDetail::UndefinedVariable
                        ) =>
                {
                    return Err(e)
                }
                Err(mut e) => {
                    e.query_syntax = true;
                    self.back_up_action(&mut e);
                    return Err(e);
                }
            };
            if let Some(vt) = rebind {
                let mut e = self.err(vt, "no bind of a query variable");
                e.detail = crate::error::LoadDetail::Query { what: 3, func };
                e.echo_end = self.consumed_end() as u32;
                return Err(e);
            }
        }
        self.nvars = saved_vars;
        Ok(n)
    }

    /// An error in an action of `progn`, `progn$`, `foreach` or a fact-set query: the
    /// parser holding the actions backs up its pretty-print buffer over the last two
    /// things saved and adds the action's `(`, so CLIPS shows `(modify(` for `(modify
    /// 1`, `(+ 1(` for `(+ 1)`, and a missing function's `(` alone. Once only, at the
    /// innermost such form (CLIPS's backups then undo nothing more).
    fn back_up_action(&self, e: &mut crate::error::LoadError) {
        use crate::error::{EchoTail, LoadDetail};
        if e.echo_end == 0
            || e.echo_tail == EchoTail::OpenParen
            || e.expected == super::INPUT_ENDED
            || matches!(
                e.detail,
                LoadDetail::UndefinedGlobal { whole: true } | LoadDetail::UndefinedVariable
            )
        {
            return;
        }
        let src = self.lex.source();
        let upto = src.get(..e.echo_end as usize).unwrap_or("");
        if e.detail == LoadDetail::MissingFunction {
            e.echo_end = e.echo_end.min(e.start);
        } else if upto.ends_with(')') {
            e.echo_end -= 1;
            e.echo_tail = EchoTail::OpenParen;
        } else if matches!(
            e.detail,
            LoadDetail::FactIndexInRule { .. }
                | LoadDetail::ArgType {
                    expected: "non-void return value",
                    ..
                }
        ) {
            // `modify`/`duplicate` refusing their target: up to the function's name
            let before = src.get(..e.start as usize).unwrap_or("");
            e.echo_end = before.trim_end().len() as u32;
            e.echo_tail = EchoTail::OpenParen;
        }
    }

    /// A fact-set query's actions up to its `)`: their count.
    fn query_actions(&mut self, call: Ix) -> PResult<Ix> {
        self.args_until_rparen(call)
    }

    /// Whether query variable `frame` (a frame slot of a query being read) ranges over
    /// templates named in its declaration, each with slot `slot`: then `?v:slot` finds
    /// its slot in any fact it reads and prints nothing (a missing slot is an error
    /// at run time, `[INSFUN3]`; names given as an expression are known only then).
    fn slot_in_every_template(&self, frame: Ix, slot: Ix) -> bool {
        let mut d = self.query_decl;
        while d != NONE {
            let mut v = self.cx.exprs[d as usize].first;
            while v != NONE {
                let var = self.cx.exprs[v as usize];
                if var.data == frame {
                    let mut t = var.first;
                    let mut any = false;
                    while t != NONE {
                        let name = self.cx.exprs[t as usize];
                        let Some(tmpl) = (name.op == Op::Sym)
                            .then(|| self.cx.find_template(name.data))
                            .flatten()
                        else {
                            return false;
                        };
                        if self.cx.templates[tmpl as usize].implied
                            || self.cx.find_slot(tmpl, slot).is_none()
                        {
                            return false;
                        }
                        any = true;
                        t = name.next;
                    }
                    return any;
                }
                v = var.next;
            }
            d = self.cx.exprs[d as usize].data;
        }
        false
    }

    /// `?v:slot` inside a query: `(fact-slot-value ?v slot)`.
    pub fn query_slot_ref(&mut self, t: Token<'s>, var: &'s str, slot: &'s str) -> PResult<Ix> {
        let v = self.var_ref(t, var, false)?;
        let sym = cap!(self, self.cx.intern(slot))?;
        let vx = self.cx.exprs[v as usize];
        if vx.op == Op::Local {
            // reuse the variable's node: it becomes the slot read
            self.cx.exprs[v as usize] = Expr::new(Op::QSlot, 0, vx.data);
            let quiet = if self.slot_in_every_template(vx.data, sym) {
                QSLOT_QUIET
            } else {
                0
            };
            let s = cap!(self, self.cx.push_expr(Expr::new(Op::Sym, quiet, sym)))?;
            self.cx.append_child(v, s);
            return Ok(v);
        }
        let call = self.builtin_call("fact-slot-value")?;
        self.cx.append_child(call, v);
        let s = cap!(self, self.cx.push_expr(Expr::new(Op::Sym, 0, sym)))?;
        self.cx.append_child(call, s);
        Ok(call)
    }
}

pub fn arity_text(min: u8, max: u8) -> &'static str {
    if min == max {
        "exactly the function's number of arguments"
    } else if max == builtins::ANY {
        "at least the function's minimum number of arguments"
    } else {
        "between the function's minimum and maximum number of arguments"
    }
}

#[allow(dead_code)]
fn _unused(_: Scope) {}

/// What a call of CLIPS 6.30 function `name` that robotino-agent leaves out on purpose
/// would need (`[NOTIMPL1]`, README "Not implemented yet"), or None for any other name.
#[cfg(feature = "extras")]
fn not_implemented_function(name: &str) -> Option<&'static str> {
    match name {
        "join-activity" | "join-activity-reset" => {
            Some("CLIPS's join activity counts, which follow its own hashed beta memories")
        }
        "constructs-to-c" => {
            Some("C code generation (a rule base compiles to Rust: rules-compiled)")
        }
        "bload" | "bsave" => Some(
            "CLIPS's binary images, dumps of its own memory layout (a rule base compiles to Rust: rules-compiled)",
        ),
        // constructs of CLIPS's object system and generic functions: said as such, not
        // as a function nobody declared (programs by others define methods, round 14)
        "defclass" | "definstances" | "defmessage-handler" => Some("objects (COOL)"),
        "defgeneric" | "defmethod" => Some("generic functions"),
        _ => None,
    }
}

/// A string literal's contents `raw` with `\"` and `\\` unescaped, into `out` (the
/// long literals' way: `string_const`'s own loop is the common one's).
#[cfg(feature = "grow")]
fn unescape_into(raw: &str, out: &mut impl core::fmt::Write) -> core::fmt::Result {
    let mut esc = false;
    for ch in raw.chars() {
        if esc || ch != '\\' {
            out.write_char(ch)?;
            esc = false;
        } else {
            esc = true;
        }
    }
    Ok(())
}
