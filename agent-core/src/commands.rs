//! Engine-level operations: start-up, reset, clear, run, undefrule, loading text,
//! and CLIPS's batch command loop.

use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use core::fmt::Write;

use crate::builtins::errors::Fallback;
use crate::builtins::files::{file_buffer, FileItems};
use crate::builtins::{FIXED_SYMBOLS, SYM_INITIAL_FACT};
use crate::engine::{watch, Core, Frame, COMMAND_HOLD};
use crate::error::{EvalError, EvalErrorKind, LoadDetail, LoadError, Restriction};
use crate::expr::{FnKind, Op};
use crate::fact::FactState;
use crate::host::router;
use crate::lexer::{Lexer, Tok};
use crate::parser::{Item, Parser};
use crate::rete::{JoinKind, PatBinding, TokenKind};
use crate::value::{SymId, TextBuf, Value, NONE};

/// `(watch statistics)`: facts and activations sampled before the run and after each
/// rule firing, reported after the run as CLIPS 6.30 does. Its Debian build prints no
/// run time (nor rules per second), so neither is printed here.
#[derive(Default)]
struct RunStats {
    samples: u64,
    sum_facts: u64,
    max_facts: u64,
    sum_acts: u64,
    max_acts: u64,
}

impl RunStats {
    fn sample(&mut self, cx: &Core<'_>) {
        let (f, a) = (cx.live_fact_count() as u64, cx.activation_count() as u64);
        self.samples += 1;
        self.sum_facts += f;
        self.max_facts = self.max_facts.max(f);
        self.sum_acts += a;
        self.max_acts = self.max_acts.max(a);
    }

    /// Not inlined: its buffer stays off the run loop's stack frame.
    #[cold]
    #[inline(never)]
    fn print(&self, cx: &mut Core<'_>, fired: u32) {
        // CLIPS rounds the means to the nearest integer
        let mean = |sum: u64| (sum * 2 + self.samples) / (2 * self.samples.max(1));
        let mut b: TextBuf<320> = TextBuf::new();
        let _ = writeln!(b, "{fired} rules fired");
        let _ = writeln!(
            b,
            "{} mean number of facts ({} maximum).",
            mean(self.sum_facts),
            self.max_facts
        );
        // CLIPS counts its one COOL instance (initial-object); this engine has no COOL
        let _ = writeln!(b, "1 mean number of instances (1 maximum).");
        let _ = writeln!(
            b,
            "{} mean number of activations ({} maximum).",
            mean(self.sum_acts),
            self.max_acts
        );
        cx.write(router::WDISPLAY, b.as_str());
    }
}

/// How deep `batch` files may run inside each other (each level holds a file buffer).
const MAX_BATCH_DEPTH: u8 = 8;

/// Where the echo of a batch item `text` (a command of `len` bytes, then the rest of
/// its line) stops until the command ran: the start of the command's last line, when
/// the first line end after the command is a `\r` ending the item's `\r\n` (CLIPS
/// runs the command at the `\r` and echoes that line at the `\n`). None otherwise.
fn crlf_held_line(text: &str, len: usize) -> Option<usize> {
    let tail = text.get(len..)?;
    let r = tail.find(['\r', '\n'])?;
    if &tail[r..] != "\r\n" {
        return None;
    }
    Some(text[..len].rfind('\n').map_or(0, |k| k + 1))
}

/// How much of `rest` (the text after a command) CLIPS's command loop takes with the
/// command: up to its first line end, `\r\n`, `\n` or a lone `\r` (CLIPS tests a
/// command for completeness at either character), or all of it.
fn line_end_after(rest: &str) -> usize {
    match rest.find(['\r', '\n']) {
        Some(r) if rest[r..].starts_with("\r\n") => r + 2,
        Some(r) => r + 1,
        None => rest.len(),
    }
}

/// Whether text holds only blanks and comments.
fn only_blank(s: &str) -> bool {
    Lexer::new(s).next_token().tok == Tok::Eof
}

/// Name of the construct starting at `s` (`(defrule NAME ...`); for defglobal the
/// first variable's name.
/// first variable's name (after its module's name, if any). A name given with its
/// module (`MOD::name`) is the name alone.
fn construct_name(s: &str) -> &str {
    let mut lx = Lexer::new(s);
    lx.next_token();
    let global = lx.next_token().tok == Tok::Symbol("defglobal");
    loop {
        match lx.next_token().tok {
            Tok::Symbol(_) if global => {}
            Tok::Symbol(n) => return crate::module::split_qualified(n).map_or(n, |(_, n)| n),
            Tok::Global(n) => return n,
            Tok::Eof | Tok::Bad => return "",
            _ => {}
        }
    }
}

/// The globals a defglobal's text defines (`?*x* =` at its top level), in order.
fn global_names(s: &str) -> impl Iterator<Item = &str> {
    let mut lx = Lexer::new(s);
    let mut depth = 0u32;
    let mut pending: Option<&str> = None;
    core::iter::from_fn(move || loop {
        let t = lx.next_token();
        match t.tok {
            Tok::Eof | Tok::Bad => return None,
            Tok::LParen => depth += 1,
            Tok::RParen => depth = depth.saturating_sub(1),
            Tok::Global(n) if depth == 1 => {
                pending = Some(n);
                continue;
            }
            Tok::Symbol("=") if depth == 1 => {
                if let Some(n) = pending.take() {
                    return Some(n);
                }
            }
            _ => {}
        }
        pending = None;
    })
}

impl Parser<'_, '_, '_> {
    /// The first part of `load`'s line for the construct being read, printed as CLIPS
    /// prints it once the construct's name and comment are read, so that what its
    /// parsing prints (errors, a default's output) comes after it: "Defining
    /// deftemplate: t" and a newline, "Defining defrule: r " (its join marks follow
    /// once it is built), CLIPS's redefinition warning, or the progress mark. Prints
    /// once; a defglobal's line waits for its globals (`announce`).
    pub(crate) fn announce_head(&mut self) {
        let Some((start, existed, false)) = self.cx.st.io.announce else {
            return;
        };
        let kw = self.construct;
        if kw == "defglobal" {
            return;
        }
        self.cx.st.io.announce = Some((start, existed, true));
        let mut b: TextBuf<256> = TextBuf::new();
        if self.cx.st.mode.watch & watch::COMPILATIONS != 0 {
            let text = self.lex.source().get(start..).unwrap_or("");
            let name = construct_name(text);
            let _ = if existed {
                write!(b, "\n[CSTRCPSR1] WARNING: Redefining {kw}: {name}")
            } else {
                write!(b, "Defining {kw}: {name}")
            };
            let _ = b.write_char(if kw == "defrule" { ' ' } else { '\n' });
        } else {
            // CLIPS's progress marks when compilations are not watched
            let _ = b.write_char(match kw {
                "deftemplate" => '%',
                "defrule" => '*',
                "deffunction" => '!',
                "deffacts" => '$',
                _ => '#',
            });
            self.cx.st.io.progress_printed = true;
        }
        self.cx.write(router::STDOUT, b.as_str());
    }

    /// The rest of `load`'s line for the construct just parsed (`announce_head` first,
    /// if the parser has not called it): a rule's join marks with compilations
    /// watched, and a defglobal's line or marks, one per global. Called by the parser
    /// once a construct is built (a rule before it is matched, as CLIPS prints it
    /// before the activations), and after it by `load_items`; prints once.
    pub(crate) fn announce(&mut self) {
        self.announce_head();
        let Some((start, _, _)) = self.cx.st.io.announce.take() else {
            return;
        };
        let kw = self.construct;
        let watched = self.cx.st.mode.watch & watch::COMPILATIONS != 0;
        let mut b: TextBuf<256> = TextBuf::new();
        if kw == "defglobal" {
            let end = self.lex.pos().max(start);
            let text = self.lex.source().get(start..end).unwrap_or("");
            // a line per global, written as it comes (a defglobal may define any
            // number; one buffer for all of them cut the text)
            for name in global_names(text) {
                if watched {
                    self.cx.write(router::STDOUT, "Defining defglobal: ");
                    self.cx.write(router::STDOUT, name);
                    self.cx.write(router::STDOUT, "\n");
                } else {
                    self.cx.write(router::STDOUT, ":");
                }
            }
            if !watched {
                self.cx.st.io.progress_printed = true;
            }
        } else if kw == "defrule" && watched {
            for &m in self.join_marks.as_slice() {
                let _ = if m == b'\n' {
                    b.write_char('\n')
                } else {
                    write!(b, "{}j", m as char)
                };
            }
            let _ = b.write_char('\n');
        }
        self.cx.write(router::STDOUT, b.as_str());
    }
}

impl Core<'_> {
    /// Whether the construct starting at `s` (`(defrule NAME ...`) redefines one that
    /// exists (CLIPS's load then warns instead of saying "Defining").
    fn construct_exists(&mut self, s: &str) -> bool {
        let mut lx = Lexer::new(s);
        lx.next_token();
        let kw = match lx.next_token().tok {
            Tok::Symbol(k) => k,
            _ => return false,
        };
        let name = construct_name(s);
        #[cfg(feature = "modules")]
        if kw == "defmodule" {
            return self.find_module(name).is_some();
        }
        let Some(id) = self.find_sym(name) else {
            return false;
        };
        match kw {
            "defrule" => (0..self.st.pools.nrules).any(|r| self.rule_here(r, id)),
            // one of that name in another module is another construct (CLIPS says
            // "Defining"); one the module sees by import is a conflict, refused later
            "deffacts" => (0..self.st.pools.ndeffacts)
                .any(|d| self.deffacts[d as usize].name == id && self.deffacts_here(d)),
            "deffunction" => (0..self.st.pools.nfuncs)
                .any(|f| self.funcs[f as usize].name == id && self.function_here(f)),
            "deftemplate" => self.find_template(id).is_some(),
            _ => false,
        }
    }
}

impl Core<'_> {
    /// Whether deffacts `d` is the current module's.
    fn deffacts_here(&self, d: Ix) -> bool {
        #[cfg(feature = "modules")]
        return self.module_of_deffacts(d) == self.current_module();
        #[cfg(not(feature = "modules"))]
        {
            let _ = d;
            true
        }
    }

    /// Whether deffunction `f` is the current module's.
    fn function_here(&self, f: Ix) -> bool {
        #[cfg(feature = "modules")]
        return self.module_of_function(f) == self.current_module();
        #[cfg(not(feature = "modules"))]
        {
            let _ = f;
            true
        }
    }
}

/// Byte length of the first complete top-level item in `s` (construct, call or atom),
/// or None while more input is needed. Leading blanks and comments are included.
pub fn command_complete(s: &str) -> Option<usize> {
    crate::lexer::item_end(s.as_bytes())
}

impl Core<'_> {
    /// CLIPS start-up state: fixed symbols, the initial-fact template, f-0.
    pub fn startup(&mut self) -> Result<(), EvalError> {
        for s in FIXED_SYMBOLS {
            self.intern(s)?;
        }
        let t = self.implied_template(SYM_INITIAL_FACT)?;
        self.st.facts.initial_tmpl = t;
        self.make_root()?;
        self.assert_initial_fact()
    }

    pub(crate) fn assert_initial_fact(&mut self) -> Result<(), EvalError> {
        let base = self.st.frame.sp;
        let m = self.multi_begin();
        self.push_value(self.multi_finish(m))?;
        let r = self.assert_slots(self.st.facts.initial_tmpl, base as usize);
        self.st.frame.sp = base;
        r.map(|_| ())
    }

    /// `(reset)`.
    pub fn reset(&mut self) -> Result<(), EvalError> {
        // a deffacts or global that calls `clear` is refused (builtins/commands.rs);
        // one that calls `reset` does nothing, as CLIPS ignores a reset under way
        if self.st.mode.resetting {
            return Ok(());
        }
        self.st.mode.resetting = true;
        let r = self.reset_inner();
        self.st.mode.resetting = false;
        r
    }

    /// Removes the activations of token `t` from the head of its list (its newest).
    fn remove_activations_newest_first(&mut self, t: TokenId) {
        while self.tokens[t].extra != NONE {
            self.remove_activation(self.tokens[t].extra);
        }
    }

    /// Every fact retracted through the network, as `reset` and `clear` do it (the
    /// join tests of the nots and exists they unblock run again).
    fn retract_all_facts(&mut self) {
        // rules starting with not/test lose their root-based matches first, join by join
        // in the order they are primed again below (CLIPS's list of them); a first
        // `exists` keeps its own until its facts are retracted, which take back the
        // activations fact by fact
        let root_token = self.join_mems[JoinId::ROOT].mem;
        for phase in [false, true] {
            let mut j = self.joins[JoinId::ROOT].first_child;
            while j != JoinId::NONE {
                if self.joins[j].kind.left_primed() == Some(phase)
                    && self.joins[j].kind != JoinKind::Exists
                {
                    loop {
                        let mut c = self.tokens[root_token].first_child;
                        while c != TokenId::NONE && self.tokens[c].owner != j {
                            c = self.tokens[c].next_sib;
                        }
                        if c == TokenId::NONE {
                            break;
                        }
                        // the rules with no conditions share one join: CLIPS takes
                        // back their activations last made first
                        if self.joins[j].kind == JoinKind::Test && self.joins[j].tests == NONE {
                            self.remove_activations_newest_first(c);
                        }
                        self.delete_token(c);
                    }
                }
                j = self.joins[j].next_sibling;
            }
        }
        // (any left over, in token order)
        loop {
            let mut c = self.tokens[root_token].first_child;
            while c != TokenId::NONE
                && matches!(
                    self.joins[self.tokens[c].owner].kind,
                    JoinKind::Positive | JoinKind::Exists
                )
            {
                c = self.tokens[c].next_sib;
            }
            if c == TokenId::NONE {
                break;
            }
            self.delete_token(c);
        }
        // CLIPS deletes its initial-object between the two
        #[cfg(feature = "extras")]
        self.trace_initial_object(false);
        while self.st.facts.fact_head != NONE {
            let f = self.st.facts.fact_head;
            self.retract_fact(f);
        }
        // (the first `exists`' matches, with nothing left under them)
        loop {
            let mut c = self.tokens[root_token].first_child;
            while c != TokenId::NONE && self.joins[self.tokens[c].owner].kind != JoinKind::Exists {
                c = self.tokens[c].next_sib;
            }
            if c == TokenId::NONE {
                break;
            }
            self.delete_token(c);
        }
    }

    /// `reset`'s priming of the joins under the root, in CLIPS's order.
    fn prime_from_root(&mut self, root_token: TokenId) -> Result<(), EvalError> {
        for phase in [false, true] {
            let mut j = self.joins[JoinId::ROOT].first_child;
            while j != JoinId::NONE {
                if self.joins[j].kind.left_primed() == Some(phase) {
                    self.left_activate(j, root_token)?;
                }
                j = self.joins[j].next_sibling;
            }
        }
        Ok(())
    }

    fn reset_inner(&mut self) -> Result<(), EvalError> {
        // what the scratch area held before stays: a reset in a deffunction or a rule's
        // actions returns to a caller (a top-level `foreach`, say) that still reads its
        // multifields there
        let scratch_mark = self.st.frame.scratch_top;
        // the focus stack holds MAIN only, the current module
        #[cfg(feature = "modules")]
        self.reset_focus()?;
        self.retract_all_facts();
        let root_token = self.join_mems[JoinId::ROOT].mem;
        // (the partial matches joins were primed with are gone)
        #[cfg(feature = "grow")]
        self.forget_prime_orders();
        // a reset in a rule's actions (or a query's body) keeps the retracted facts' cells
        // until that ends: its variables still read the facts they matched
        if !self.st.mode.firing && self.st.eval.query_hold & !COMMAND_HOLD == 0 {
            self.free_pending();
            self.st.facts.values_top = 0;
            self.forget_free_cells();
        }
        self.st.facts.next_fact_num = 0;
        // (every join is older than the facts to come)
        #[cfg(feature = "grow")]
        self.st.prime.join_born.iter_mut().for_each(|b| *b = 0);
        #[cfg(feature = "extras")]
        self.forget_pattern_error();
        #[cfg(feature = "extras")]
        self.st.timetags.reset();
        // globals back to their initial values, unless `(set-reset-globals FALSE)`
        #[cfg(feature = "extras")]
        let nglobals = if self.st.mode.keep_globals {
            0
        } else {
            self.st.pools.nglobals
        };
        #[cfg(not(feature = "extras"))]
        let nglobals = self.st.pools.nglobals;
        for g in 0..nglobals {
            let init = self.globals[g as usize].init;
            if init != NONE {
                let v = self.eval(init)?;
                #[cfg(feature = "extras")]
                self.trace_global(g, v);
                self.set_global(g, v)?;
            }
        }
        // variables bound at the prompt (hidden globals `?x`) are unbound again
        #[cfg(feature = "parser")]
        for g in 0..self.st.pools.nglobals {
            let name = self.globals[g as usize].name;
            let prompt_var = name != NONE && {
                let t = self.sym_text(name);
                t.starts_with('?') && !t.starts_with("?*")
            };
            if prompt_var && !matches!(self.globals[g as usize].value, Value::Void) {
                self.set_global(g, Value::Void)?;
            }
        }
        // CLIPS primes the joins fed by no pattern (no CE, a first `test`) first, then
        // those after a first `not`/`exists` (its right- then left-prime joins), so
        // the latter's activations are newer; then comes the initial-fact. Their tests
        // run outside its join operations: they may assert and retract facts, which
        // go through the whole network at once (host)
        #[cfg(feature = "extras")]
        let free = core::mem::replace(&mut self.st.net.matching_free, self.st.net.matching + 1);
        #[cfg(feature = "extras")]
        let rfree = core::mem::replace(&mut self.st.net.retract_free, self.st.net.matching + 1);
        let r = self.prime_from_root(root_token);
        #[cfg(feature = "extras")]
        {
            self.st.net.matching_free = free;
            self.st.net.retract_free = rfree;
        }
        r?;
        // (and makes its initial-object again before its initial-fact)
        #[cfg(feature = "extras")]
        self.trace_initial_object(true);
        if self.st.mode.initial_deffacts {
            self.assert_initial_fact()?;
        }
        // an error in the network halts CLIPS's reset: no further deffacts fact; the
        // deffacts go module by module, in definition order in each
        #[cfg(feature = "modules")]
        let modules = self.st.modules.nmodules;
        #[cfg(not(feature = "modules"))]
        let modules = 1;
        let ndeffacts = self.st.pools.ndeffacts;
        'deffacts: for d in (0..modules).flat_map(|m| (0..ndeffacts).map(move |d| (m, d))) {
            let (m, d) = d;
            #[cfg(feature = "modules")]
            if Ix::from(self.module_of_deffacts(d)) != m {
                continue;
            }
            #[cfg(not(feature = "modules"))]
            let _ = m;
            // its facts are made in its module (a global read by name is looked up
            // from there)
            #[cfg(feature = "modules")]
            if self.st.modules.nmodules > 1 {
                self.set_current_module(m as crate::module::ModId);
            }
            let mut spec = self.deffacts[d as usize].facts;
            while spec != NONE {
                if self.st.mode.halting {
                    break 'deffacts;
                }
                if self.exprs[spec as usize].op == Op::FactSpec {
                    // a multislot's value is built in the scratch area; once asserted
                    // the fact holds its own copy, so a deffacts of any size fits
                    let mark = self.st.frame.scratch_top;
                    self.assert_spec(spec)?;
                    self.st.frame.scratch_top = mark;
                }
                spec = self.exprs[spec as usize].next;
            }
        }
        #[cfg(feature = "modules")]
        if self.st.modules.nmodules > 1 {
            self.set_current_module(crate::module::MAIN);
        }
        self.st.frame.scratch_top = scratch_mark;
        Ok(())
    }

    /// `(clear)`: everything goes; the environment starts afresh (externals stay).
    pub fn clear(&mut self) -> Result<(), EvalError> {
        let w = self.st.mode.watch;
        // CLIPS retracts the facts through the network first, its traces silenced:
        // what the join tests of nots and exists print shows
        self.st.mode.watch = 0;
        #[cfg(feature = "extras")]
        let cool_watch = core::mem::take(&mut self.st.mode.cool_watch);
        self.retract_all_facts();
        #[cfg(feature = "extras")]
        {
            self.st.mode.cool_watch = cool_watch;
        }
        #[cfg(feature = "extras")]
        let (keep_globals, cool_watch, salience_eval, watch_items) = (
            self.st.mode.keep_globals,
            self.st.mode.cool_watch,
            self.st.mode.salience_eval,
            self.st.watch_names.items,
        );
        #[cfg(feature = "extras")]
        let (dynamic_checks, fact_duplication, twins_made, seq_ops, no_incremental_reset) = (
            self.st.mode.dynamic_checks,
            self.st.mode.fact_duplication,
            self.st.mode.twins_made,
            self.st.mode.seq_ops,
            self.st.mode.no_incremental_reset,
        );
        let next = self.st.pools.nexternals;
        let ext_syms = self.st.pools.ext_syms;
        let rom_syms = self.st.rom.symbols;
        for f in self.facts.iter_mut() {
            *f = crate::fact::Fact::EMPTY;
        }
        for b in self.fact_buckets.iter_mut() {
            *b = NONE;
        }
        for t in self.tokens.iter_mut() {
            *t = crate::rete::Token::EMPTY;
        }
        #[cfg(feature = "grow")]
        self.forget_prime_orders();
        for b in self.amem_buckets.iter_mut() {
            *b = TokenId::NONE;
        }
        for a in self.acts.iter_mut() {
            *a = crate::rule::Activation::EMPTY;
        }
        for j in self.joins.ram().iter_mut() {
            *j = crate::rete::Join::EMPTY;
        }
        for j in self.join_mems.iter_mut() {
            *j = crate::rete::JoinMem::EMPTY;
        }
        for a in self.alphas.ram().iter_mut() {
            *a = crate::rete::AlphaNode::EMPTY;
        }
        for a in self.alpha_mems.iter_mut() {
            *a = crate::rete::AlphaMem::EMPTY;
        }
        for t in self.templates.ram().iter_mut() {
            *t = crate::template::Template::EMPTY;
        }
        for t in self.tmpl_mems.iter_mut() {
            *t = crate::template::TemplateMem::EMPTY;
        }
        #[cfg(feature = "logical")]
        self.logical_clear();
        #[cfg(feature = "extras")]
        {
            self.st.breaks = crate::engine::Breaks::new();
            self.func_extras.fill(crate::template::NO_FN_EXTRAS);
            self.global_text.fill(crate::template::NO_PP_TEXT);
            self.slot_facets.fill(crate::template::NO_PP_TEXT);
        }
        #[cfg(feature = "modules")]
        {
            self.focus.fill(crate::module::NO_TAG);
            self.tmpl_module.fill(crate::module::NO_TAG);
            self.rule_module.fill(crate::module::NO_RULE_TAG);
            self.func_module.fill(crate::module::NO_TAG);
            self.global_module.fill(crate::module::NO_TAG);
            self.deffacts_module.fill(crate::module::NO_TAG);
            self.modules.fill(crate::module::NO_MODULE);
        }
        let hw = self.st.pools.hw;
        // a `clear` inside a larger command (`(eq (clear) 1)`, `(progn (clear) (build
        // ...))`, a batch file's run from the prompt) leaves the expression nodes and
        // symbols in place, the running command's and those before them (a compiled
        // rule base's read in place, too): the command goes on reading its own at the
        // same indices, and what it defines next goes after them. A lone `(clear)` at
        // the prompt lets them all go. (Only commands run from text nest a clear: the
        // image, without the parser, has none.)
        let keep_exprs = (cfg!(feature = "parser") && self.st.eval.eval_depth > 1).then_some((
            self.st.pools.nexprs,
            self.st.eval.command_base,
            #[cfg(feature = "in-place")]
            self.st.rom.exprs,
            #[cfg(not(feature = "in-place"))]
            (),
            (self.st.pools.nsyms, self.st.pools.sym_bytes),
        ));
        // what is running goes on: its frame, nesting and firing, and the generator
        let ctx = (
            self.st.frame,
            self.st.eval.eval_depth,
            self.st.mode.firing,
            self.st.net.pm_rhs,
        );
        let random = self.st.random;
        #[cfg(feature = "grow")]
        let limits = self.st.eval.limits;
        // the strategy is a setting: CLIPS keeps it across clear
        let strategy = self.st.agenda.strategy;
        // and so do the batch files running and where their input is
        let io = core::mem::take(&mut self.st.io);
        #[cfg(feature = "extras")]
        let (text_regions, mut tools, mut profile) =
            (self.st.text_regions, self.st.tools, self.st.profile);
        *self.st = crate::engine::State::new();
        self.st.io = io;
        if let Some(kept) = keep_exprs {
            self.st.pools.nexprs = kept.0;
            self.st.eval.command_base = kept.1;
            #[cfg(feature = "in-place")]
            {
                self.st.rom.exprs = kept.2;
            }
        }
        #[cfg(feature = "extras")]
        {
            tools.forget_symbols();
            profile.forget_constructs();
            self.st.text_regions = text_regions;
            self.st.tools = tools;
            self.st.profile = profile;
        }
        // a compiled rule base's nodes read in place go with the rest
        #[cfg(feature = "in-place")]
        {
            self.exprs.set_rom(self.st.rom.exprs);
            self.alphas.set_rom(self.st.rom.alphas);
            self.joins.set_rom(self.st.rom.joins);
            self.templates.set_rom(self.st.rom.templates);
            self.slots.set_rom(self.st.rom.slots);
            self.rules.set_rom(self.st.rom.rules);
        }
        self.st.pools.hw = hw;
        (
            self.st.frame,
            self.st.eval.eval_depth,
            self.st.mode.firing,
            self.st.net.pm_rhs,
        ) = ctx;
        self.st.random = random;
        #[cfg(feature = "grow")]
        {
            self.st.eval.limits = limits;
        }
        self.st.agenda.strategy = strategy;
        self.st.pools.nexternals = next;
        if let Some(kept) = keep_exprs {
            // the running command's symbols stay too (with all the others)
            self.st.rom.symbols = rom_syms;
            (self.st.pools.nsyms, self.st.pools.sym_bytes) = kept.3;
            self.st.pools.ext_syms = ext_syms;
        } else {
            // keep the symbols naming external functions
            for b in self.sym_buckets.iter_mut() {
                *b = crate::symbols::Head::EMPTY;
            }
            let keep = ext_syms;
            if !rom_syms.is_empty() {
                // they were a compiled rule base's, read in place (the engine had them in
                // its arena before it loaded the rule base, so they fit)
                let mut top = 0usize;
                for i in 0..keep as usize {
                    let t = rom_syms.texts.get(i).copied().unwrap_or("").as_bytes();
                    if i >= self.sym_entries.len() {
                        return Err(crate::engine::cap(
                            crate::error::Pool::Symbols,
                            self.sym_entries.len(),
                        )
                        .into());
                    }
                    if top + t.len() > self.sym_bytes.len() {
                        return Err(crate::engine::cap(
                            crate::error::Pool::SymbolBytes,
                            self.sym_bytes.len(),
                        )
                        .into());
                    }
                    self.sym_bytes[top..top + t.len()].copy_from_slice(t);
                    self.sym_entries[i] = crate::symbols::SymEntry {
                        start: top as Ix,
                        len: t.len() as Ix,
                        next: NONE,
                        #[cfg(feature = "grow")]
                        hash: crate::symbols::hash_bytes(t),
                    };
                    top += t.len();
                }
            }
            for i in 0..keep {
                let e = self.sym_entries[i as usize];
                let text_start = e.start as usize;
                let h = crate::symbols::hash_bytes(
                    &self.sym_bytes[text_start..text_start + e.len as usize],
                ) as usize
                    % self.sym_buckets.len();
                self.sym_entries[i as usize].next = self.sym_buckets[h].get();
                self.sym_buckets[h] = crate::symbols::Head::of(i);
            }
            self.st.pools.nsyms = keep;
            self.st.pools.sym_bytes = if keep == 0 {
                0
            } else {
                self.sym_entries[keep as usize - 1].start + self.sym_entries[keep as usize - 1].len
            };
            self.st.pools.ext_syms = ext_syms;
        }
        // CLIPS prints `==> f-0 (initial-fact)` here when facts are watched
        self.st.mode.watch = w;
        #[cfg(feature = "extras")]
        {
            // settings CLIPS keeps across clear
            self.st.mode.keep_globals = keep_globals;
            self.st.mode.cool_watch = cool_watch;
            self.st.mode.salience_eval = salience_eval;
            self.st.mode.dynamic_checks = dynamic_checks;
            self.st.mode.fact_duplication = fact_duplication;
            self.st.mode.twins_made = twins_made;
            self.st.mode.seq_ops = seq_ops;
            self.st.mode.no_incremental_reset = no_incremental_reset;
            // the items stay, the constructs named are gone
            self.st.watch_names.items = watch_items;
            self.sync_watch();
        }
        // CLIPS's clear ends with a reset's focus on MAIN (the stack holds MAIN)
        #[cfg(feature = "modules")]
        self.reset_focus()?;
        #[cfg(feature = "extras")]
        self.trace_initial_object(true);
        if ext_syms == 0 {
            self.startup()
        } else {
            self.startup_after_clear()
        }
    }

    fn startup_after_clear(&mut self) -> Result<(), EvalError> {
        // fixed symbols are already the first entries
        let t = self.implied_template(SYM_INITIAL_FACT)?;
        self.st.facts.initial_tmpl = t;
        self.make_root()?;
        self.assert_initial_fact()
    }

    /// Copies a token's pattern bindings for the RHS. Pattern depths along an
    /// ancestry are contiguous from 0, so every entry up to the rule's last pattern is
    /// written (EMPTY for a `not` or `exists`) and nothing is cleared first: the RHS
    /// reads no deeper entry, as `bind_left`'s callers read none (one write per
    /// pattern, where clearing all `MAX_PATTERNS` entries cost a loop per firing).
    /// (In line on the host: the run loop's two paths call it.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn bind_rhs(&mut self, mut t: TokenId) {
        while t != TokenId::NONE {
            let tk = self.tokens[t];
            if tk.kind != TokenKind::Beta {
                break;
            }
            let j = self.joins[tk.owner];
            if j.kind == JoinKind::Root {
                break;
            }
            self.st.net.rhs_pm[j.depth as usize] = if tk.am != TokenId::NONE {
                let a = self.tokens[tk.am];
                PatBinding {
                    fact: a.fact,
                    marks: a.marks,
                }
            } else {
                PatBinding::EMPTY
            };
            t = tk.parent;
        }
    }

    /// Whether the next activation's rule has a breakpoint (`set-break`): then CLIPS's
    /// message is printed.
    #[cfg(feature = "extras")]
    #[inline(never)]
    fn at_breakpoint(&mut self) -> bool {
        let Some(rule) = self.next_activation_rule() else {
            return false;
        };
        let name = self.rules[rule as usize].name;
        if !self.st.breaks.has(name) {
            return false;
        }
        let mut b: TextBuf<160> = TextBuf::new();
        let _ = writeln!(b, "Breaking on rule {}.", self.sym_text(name));
        self.write(router::STDOUT, b.as_str());
        true
    }

    /// `(run [limit])`: fires activations; returns how many fired.
    pub fn run(&mut self, limit: i64) -> Result<u32, EvalError> {
        let mut stats = RunStats::default();
        if self.st.mode.watch & watch::STATISTICS != 0 {
            stats.sample(self);
        }
        let r = self.run_rules(limit, &mut stats);
        if let Ok(fired) = r {
            // CLIPS 6.30 counts its limit down per firing and prints this when what is
            // left equals what fired: for `(run 0)`, and for a run that fired half its
            // limit (not when the limit is used up)
            if limit >= 0 && limit - i64::from(fired) == i64::from(fired) {
                self.write(router::STDOUT, "rule firing limit reached\n");
            }
            if self.st.mode.watch & watch::STATISTICS != 0 {
                stats.print(self, fired);
            }
        }
        r
    }

    /// Rule `rule`'s actions timed by the profiler (`builtins::profile`).
    #[cfg(feature = "extras")]
    #[cold]
    #[inline(never)]
    fn eval_actions_profiled(&mut self, rule: Ix) -> Result<Value, EvalError> {
        self.profile_enter(true, rule);
        let r = self.eval_actions(self.rules[rule as usize].rhs);
        self.profile_leave(true, rule);
        r
    }

    /// A rule's actions, as `eval_chain`, each marked as the top-level action while it
    /// runs (`State::top_action`, see `rete::defer`). A propagation still deferred at
    /// the end is built here; its error wins, as it happened first. (Inlined into the
    /// run loop, its one caller but for the profiler's.)
    #[cfg_attr(feature = "extras", inline(always))]
    fn eval_actions(&mut self, mut e: Ix) -> Result<Value, EvalError> {
        let saved = self.st.net.top_action;
        let mut r = Ok(Value::Sym(crate::builtins::SYM_FALSE));
        while e != NONE {
            self.st.net.top_action = e;
            // a deferred propagation waits only for an assert or modify whose
            // arguments call nothing (see `rete::defer`)
            if self.st.net.deferred.fact != NONE && !self.may_wait_for(e) {
                if let Err(err) = self.flush_deferred() {
                    r = Err(err);
                    break;
                }
            }
            #[cfg(all(feature = "host-speedups", feature = "grow"))]
            {
                r = self.eval_action(e);
            }
            #[cfg(not(all(feature = "host-speedups", feature = "grow")))]
            {
                r = self.eval(e);
            }
            // a network error that did not come back as one (a retract's join test)
            // halts the actions too
            if r.is_ok() && self.st.mode.halting {
                r = Err(EvalError::already_reported());
            }
            if r.is_err() || self.st.eval.returning || self.st.eval.breaking || self.st.halt_now() {
                break;
            }
            e = self.exprs[e as usize].next;
        }
        self.st.net.top_action = saved;
        if let Err(err) = self.flush_deferred() {
            r = Err(err);
        }
        r
    }

    fn run_rules(&mut self, limit: i64, stats: &mut RunStats) -> Result<u32, EvalError> {
        self.st.mode.halt = false;
        // a run with an empty focus stack focuses on MAIN (as CLIPS 6.30)
        #[cfg(feature = "modules")]
        if self.focus_top().is_none() {
            self.push_focus(crate::module::MAIN)?;
        }
        #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
        self.refresh_run_slow();
        let mut fired: u32 = 0;
        let scratch_mark = self.st.frame.scratch_top;
        // (one compare per firing: no limit is the largest)
        let max = u64::try_from(limit).unwrap_or(u64::MAX);
        // whether the run stops after a firing (its limit, a halt, an error); the
        // loop changes paths when `Mode::run_slow` does
        #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
        let look_next = loop {
            let end = if self.run_slow() {
                self.run_loop::<true>(max, &mut fired, scratch_mark, stats)?
            } else {
                self.run_loop::<false>(max, &mut fired, scratch_mark, stats)?
            };
            if let Some(look_next) = end {
                break look_next;
            }
        };
        // (one path: the run ends where the loop returns)
        #[cfg(not(any(feature = "extras", feature = "modules", feature = "logical")))]
        let look_next = self
            .run_loop::<false>(max, &mut fired, scratch_mark, stats)?
            .unwrap_or(true);
        // CLIPS looks for the next activation after every firing, the last one the
        // limit allows or one that halted or failed too: modules left with an empty
        // agenda leave the focus stack then
        #[cfg(feature = "modules")]
        if look_next && fired > 0 {
            self.pay_owed()?;
            self.pop_empty_focus();
        }
        #[cfg(not(feature = "modules"))]
        let _ = look_next;
        // CLIPS: the current focus's module is current when the run finishes (an empty
        // stack leaves the module the last firing's actions were restored to)
        #[cfg(feature = "modules")]
        if let Some(top) = self.focus_top() {
            self.set_current_module(top);
        }
        self.st.mode.halt = false;
        Ok(fired)
    }

    /// Whether the run loop takes its general path (`Mode::run_slow`).
    #[inline(always)]
    fn run_slow(&self) -> bool {
        #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
        return self.st.mode.run_slow;
        #[cfg(not(any(feature = "extras", feature = "modules", feature = "logical")))]
        false
    }

    /// Something that may turn on a feature the run loop checks per firing happened
    /// (`Mode::run_slow`): the loop takes its general path until it finds none on.
    #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
    #[inline(always)]
    pub(crate) fn note_run_slow(&mut self) {
        self.st.mode.run_slow = true;
    }

    /// `Mode::run_slow` from what is on now: a breakpoint, the profiler timing rules,
    /// every-cycle salience evaluation, a module besides MAIN or an empty focus stack
    /// (the next activation is looked for module by module), a `logical` CE (a firing
    /// may give or keep logical support).
    #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
    #[inline(never)]
    pub(crate) fn refresh_run_slow(&mut self) {
        #[allow(unused_mut)]
        let mut slow = false;
        #[cfg(feature = "extras")]
        {
            slow |= !self.st.breaks.is_empty()
                || self.profiling(true)
                || self.st.mode.salience_eval == crate::agenda::SALIENCE_EVERY_CYCLE;
        }
        #[cfg(feature = "modules")]
        {
            let m = &self.st.modules;
            slow |= m.nmodules != 1 || m.depth == 0;
        }
        #[cfg(feature = "logical")]
        {
            slow |= self.st.logical.defined;
        }
        self.st.mode.run_slow = slow;
    }

    /// The run loop on one path: `SLOW` is the general one (`Mode::run_slow`), the
    /// usual one leaves out what only the features it names need. Returns
    /// `Some(look_next)` when the run ends (whether CLIPS looks for the next activation
    /// then, see `run_rules`), None when `Mode::run_slow` changed (the other path
    /// goes on).
    #[inline(always)]
    fn run_loop<const SLOW: bool>(
        &mut self,
        max: u64,
        fired: &mut u32,
        scratch_mark: Ix,
        stats: &mut RunStats,
    ) -> Result<Option<bool>, EvalError> {
        // (asked once per path: a host that never interrupts costs no call per firing)
        #[cfg(feature = "host-speedups")]
        let poll = !self.host.never_interrupts();
        #[cfg(not(feature = "host-speedups"))]
        let poll = true;
        loop {
            if u64::from(*fired) >= max {
                return Ok(Some(true));
            }
            // the agenda is complete only once owed matches are built: fire nothing
            // before (the error stops the run; retracting facts makes room)
            self.pay_owed()?;
            // the host may stop an endless run between firings (`Host::interrupt`)
            if poll {
                if let Err(e) = self.poll_interrupt() {
                    self.st.mode.halt = false;
                    return Err(e);
                }
            }
            if self.run_slow() != SLOW {
                return Ok(None);
            }
            if let Some(look_next) = self.run_turn::<SLOW>(fired, scratch_mark, stats)? {
                return Ok(Some(look_next));
            }
        }
    }

    /// One turn of the run loop (`run_loop`): the next activation fires.
    /// `Some(look_next)` ends the run.
    #[inline(always)]
    fn run_turn<const SLOW: bool>(
        &mut self,
        fired: &mut u32,
        scratch_mark: Ix,
        stats: &mut RunStats,
    ) -> Result<Option<bool>, EvalError> {
        // a breakpoint stops the run before its rule fires (not as the first)
        #[cfg(feature = "extras")]
        if SLOW && *fired > 0 && !self.st.breaks.is_empty() && self.at_breakpoint() {
            return Ok(Some(false));
        }
        #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
        let next = if SLOW {
            self.pop_activation()
        } else {
            self.pop_head()
        };
        #[cfg(not(any(feature = "extras", feature = "modules", feature = "logical")))]
        let next = self.pop_activation();
        let Some((rule, token)) = next else {
            return Ok(Some(false));
        };
        *fired += 1;
        self.print_fire_line(*fired, rule, token);
        self.bind_rhs(token);
        // (one borrow of the state for its stores: through `self.st` each store
        // made the next field access load the reference again)
        let st = &mut *self.st;
        let saved = (
            st.mode.firing,
            st.net.pm_rhs,
            st.frame,
            st.agenda.current_rule,
        );
        st.mode.firing = true;
        st.net.pm_rhs = true;
        st.agenda.current_rule = rule;
        // a halt ends the run, so one left here came from before it (a top-level
        // command's propagation): the rule's actions run as usual
        st.mode.halting = false;
        st.frame.bp = st.frame.sp;
        // the rule's actions run in its module (with MAIN alone, current already), and
        // the module current before them is current again after them
        #[cfg(feature = "modules")]
        let outer_module = if SLOW {
            self.enter_module(self.rule_tag(rule).module)
        } else {
            None
        };
        let nlocals = self.rules[rule as usize].nlocals;
        // (most rules bind no locals: no room check for them)
        let mut r = match nlocals {
            0 => Ok(Value::Void),
            n => match self.push_voids(usize::from(n)) {
                Ok(()) => Ok(Value::Void),
                Err(e) => Err(e.into()),
            },
        };
        // the logical support its asserts get (`logical`; nothing to set or keep
        // for a rule without a logical CE fired outside any logical firing)
        #[cfg(feature = "logical")]
        let logical = if !SLOW || self.logical_idle_for(rule) {
            None
        } else {
            Some(self.logical_enter(rule, token))
        };
        if r.is_ok() {
            // (one test of the profiler's mode per firing, its work out of line)
            #[cfg(feature = "extras")]
            if SLOW && self.profiling(true) {
                r = self.eval_actions_profiled(rule);
            } else {
                r = self.eval_actions(self.rules[rule as usize].rhs);
            }
            #[cfg(not(feature = "extras"))]
            {
                r = self.eval_actions(self.rules[rule as usize].rhs);
            }
        }
        #[cfg(feature = "logical")]
        if let Some(logical) = logical {
            self.logical_leave(logical);
        }
        #[cfg(feature = "modules")]
        self.leave_module(outer_module);
        // `(return)` in a rule's actions ends the focus on its module (the topmost
        // entry of it, which its actions may have covered with other modules)
        #[cfg(feature = "modules")]
        if self.st.eval.returning {
            self.remove_focus(self.rule_tag(rule).module);
        }
        let st = &mut *self.st;
        st.eval.returning = false;
        st.eval.breaking = false;
        // the rule's frame goes, and what it left in scratch: nothing outside it
        // refers there (a `run` in a rule's actions fires rules one after another
        // too); retracted facts are freed at the top level only
        let frame;
        (st.mode.firing, st.net.pm_rhs, frame, st.agenda.current_rule) = saved;
        st.frame.leave(frame);
        if !st.mode.firing {
            self.free_pending();
        }
        self.st.frame.scratch_top = scratch_mark;
        if self.st.mode.watch & watch::STATISTICS != 0 {
            stats.sample(self);
        }
        if let Err(e) = r {
            if e.kind() == EvalErrorKind::Exit {
                return Err(e);
            }
            self.report_rhs_error(rule, e);
            if e.kind() == EvalErrorKind::Interrupted {
                // the caller learns the run was stopped; the message is out
                self.st.mode.halt = false;
                let mut e = e;
                e.reported = true;
                return Err(e);
            }
            self.every_cycle_after::<SLOW>()?;
            return Ok(Some(true));
        }
        if self.st.mode.halt {
            // CLIPS names the halted rule only while rules are watched
            if self.st.mode.watch & watch::RULES != 0 && self.rule_traced(watch::RULES, rule) {
                self.write_halted_in("defrule", self.rules[rule as usize].name);
            }
            self.every_cycle_after::<SLOW>()?;
            return Ok(Some(true));
        }
        // CLIPS's every-cycle salience evaluation: after each firing (a salience that
        // failed halts the run)
        if self.every_cycle_after::<SLOW>()? {
            return Ok(Some(true));
        }
        // the general path looks again whether the next turn needs it
        #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
        if SLOW {
            self.refresh_run_slow();
        }
        Ok(None)
    }

    /// CLIPS's every-cycle salience evaluation after a firing (`refresh_every_cycle`):
    /// on the usual path only when the actions turned a feature on (`Mode::run_slow`).
    /// Whether a salience's error halted execution.
    #[inline(always)]
    fn every_cycle_after<const SLOW: bool>(&mut self) -> Result<bool, EvalError> {
        #[cfg(feature = "extras")]
        if SLOW || self.run_slow() {
            self.refresh_every_cycle()?;
            return Ok(self.st.mode.halting);
        }
        Ok(false)
    }

    fn report_rhs_error(&mut self, rule: Ix, e: EvalError) {
        self.write_error_message(e);
        self.write_halted_in("defrule", self.rules[rule as usize].name);
    }

    /// `[PRCCODE4]`: which construct's actions an error (or a halt) stopped. Not
    /// inlined: its buffer stays off the run loop's stack frame.
    #[cold]
    #[inline(never)]
    pub(crate) fn write_halted_in(&mut self, construct: &str, name: SymId) {
        let mut b: TextBuf<256> = TextBuf::new();
        let _ = writeln!(
            b,
            "[PRCCODE4] Execution halted during the actions of {construct} {}.",
            self.sym_text(name)
        );
        self.write(router::WERROR, b.as_str());
    }

    /// Prints an evaluation error as CLIPS would report it at the prompt.
    pub fn report_eval_error(&mut self, e: EvalError) {
        self.write_error_message(e);
    }

    /// CLIPS's message for an evaluation error (nothing for one already reported).
    pub fn write_error_message(&mut self, e: EvalError) {
        if e.is_capacity() {
            self.st.mode.unrecoverable = true;
        }
        if e.reported {
            return;
        }
        let mut b: TextBuf<256> = TextBuf::new();
        match e.kind() {
            EvalErrorKind::Reported | EvalErrorKind::Exit => return,
            EvalErrorKind::Arity { func } => {
                let _ = writeln!(
                    b,
                    "[ARGACCES4] Function {func} called with the wrong number of arguments."
                );
            }
            EvalErrorKind::WrongType {
                func,
                arg,
                expected,
            } => {
                let _ = writeln!(
                    b,
                    "[ARGACCES5] Function {func} expected argument #{arg} to be of type {expected}"
                );
                // host: `/` and `div` go on with 0 for the bad divisor, and so divide by
                // zero: the call just failed records it (`set_error_fallback`), told
                // here once (the prompt's fallback and a caller's value after the
                // error tell it otherwise)
                #[cfg(feature = "extras")]
                if let Some(fb) = self.st.eval.error_fallback.as_mut() {
                    if fb.depth == self.st.eval.eval_depth + 1 {
                        if let Some(func) = fb.divide_by_zero.take() {
                            let _ = writeln!(
                                b,
                                "[PRNTUTIL7] Attempt to divide by zero in {func} function."
                            );
                        }
                    }
                }
            }
            EvalErrorKind::DivideByZero { func } => {
                let _ = writeln!(
                    b,
                    "[PRNTUTIL7] Attempt to divide by zero in {func} function."
                );
            }
            EvalErrorKind::NoSuchFact(n) => {
                let _ = writeln!(b, "[PRNTUTIL1] Unable to find fact f-{n}.");
            }
            EvalErrorKind::UnboundVariable { name } if name != crate::value::NONE => {
                // a prompt variable's hidden global is `?x`; a local's name is `x`
                let text = self.sym_text(name);
                let _ = match text.strip_prefix('?') {
                    Some(v) if v.starts_with('*') => {
                        writeln!(b, "[GLOBLDEF1] Global variable ?{v} is unbound.")
                    }
                    Some(v) => writeln!(b, "[EVALUATN1] Variable {v} is unbound"),
                    None => writeln!(b, "[PRCCODE5] Variable {text} unbound."),
                };
            }
            EvalErrorKind::Interrupted => {
                let _ = writeln!(b, "[INTERRUPT] Execution interrupted by the host.");
            }
            // messages that already carry CLIPS's code, e.g. "[MULTIFUN1] ..."
            EvalErrorKind::Other(m) if m.text().starts_with('[') => {
                let _ = writeln!(b, "{m}");
            }
            _ => {
                let _ = writeln!(b, "[ERROR] {e}");
            }
        }
        self.write(router::WERROR, b.as_str());
    }

    /// After a run-time error at the prompt CLIPS prints the value the top-level function
    /// returned: its fallback (`builtins::errors`), `FALSE` for a deffunction.
    #[inline(never)]
    fn print_fallback(&mut self, top: Ix) {
        if self.st.eval.literal_error {
            return;
        }
        if let Some(fb) = self.st.eval.error_fallback.filter(|fb| fb.depth == 1) {
            if let Some(func) = fb.divide_by_zero {
                self.write_error_message(EvalError::new(EvalErrorKind::DivideByZero { func }));
            }
            self.print_value(router::STDOUT, fb.value, true);
            self.write(router::STDOUT, "\n");
            return;
        }
        let x = self.exprs[top as usize];
        // a call whose arguments expand (`expand$`): the function it wraps
        #[cfg(feature = "extras")]
        let x = crate::builtins::environment::expanded_call(self, x);
        // a prompt variable read unbound
        if x.op == Op::Global {
            self.write(router::STDOUT, "FALSE\n");
            return;
        }
        if x.op != Op::Call {
            return;
        }
        let fb = if x.aux == FnKind::Builtin as u8 {
            match crate::builtins::get(x.data).on_error.fallback() {
                Some(f) => f,
                None => return,
            }
        } else if x.aux == FnKind::Deffunction as u8 {
            Fallback::Sym("FALSE")
        } else {
            return;
        };
        let mut text: TextBuf<32> = TextBuf::new();
        let _ = match fb {
            Fallback::Int(i) => write!(text, "{i}"),
            Fallback::Float(f) => write!(text, "{f:.1}"),
            Fallback::Sym(s) => write!(text, "{s}"),
            Fallback::Str(s) => write!(text, "\"{s}\""),
            Fallback::EmptyMulti => write!(text, "()"),
        };
        self.write(router::STDOUT, text.as_str());
        self.write(router::STDOUT, "\n");
    }

    /// `[CSTRNCHK1]`'s second line: the restriction a value breaks, for slot `slot`
    /// (`range`: the slot's range, for its bounds).
    fn write_restriction(&self, b: &mut TextBuf<4096>, what: Restriction, range: Ix, slot: Ix) {
        let _ = match what {
            Restriction::Type => b.write_str("does not match the allowed types"),
            Restriction::Values => b.write_str("does not match the allowed values"),
            #[cfg(feature = "extras")]
            Restriction::Classes => b.write_str("does not match the allowed classes"),
            Restriction::Cardinality => {
                b.write_str("does not satisfy the cardinality restrictions")
            }
            Restriction::Range if range != NONE => {
                let min = self.const_value(range);
                let max = self.const_value(self.exprs[range as usize].next);
                let _ = b.write_str("does not fall in the allowed range ");
                let _ = self.write_plain(b, min);
                let _ = b.write_str(" to ");
                self.write_plain(b, max)
            }
            Restriction::Range => b.write_str("does not fall in the allowed range"),
        };
        // (a field of an ordered pattern: its number in `range`, host only)
        #[cfg(feature = "extras")]
        if slot == NONE {
            let _ = writeln!(b, " for field #{range}.");
            return;
        }
        let _ = writeln!(b, " for slot {}.", self.sym_text(slot));
    }

    /// What CLIPS shows after `ERROR:` for a rule or deffunction naming a global its
    /// module does not see: the whole construct (`whole`) or up to the global.
    fn write_global_echo(
        &self,
        b: &mut TextBuf<4096>,
        text: &str,
        e: &LoadError,
        whole: bool,
        module: &str,
    ) {
        let head = if e.construct == "defrule" {
            "(defrule"
        } else {
            "(deffunction"
        };
        let at = e.start as usize;
        let Some(start) = text.get(..at).and_then(|s| s.rfind(head)) else {
            return;
        };
        let end = if whole {
            // the construct's closing `)` (its end, or the text's)
            let mut lx = Lexer::new(text.get(start..).unwrap_or(""));
            let mut depth = 0u32;
            let mut end = text.len();
            loop {
                let t = lx.next_token();
                match t.tok {
                    Tok::Eof | Tok::Bad => break,
                    Tok::LParen => depth += 1,
                    Tok::RParen => {
                        depth = depth.saturating_sub(1);
                        if depth == 0 {
                            end = start + t.start;
                            break;
                        }
                    }
                    _ => {}
                }
            }
            end
        } else {
            e.end as usize
        };
        let src = text.get(start..end).unwrap_or("");
        let _ = b.write_str("\nERROR:\n");
        let _ = match (e.construct, whole) {
            ("defrule", true) => crate::builtins::pretty::write_defrule(src, module, b),
            ("defrule", false) => crate::builtins::pretty::write_defrule_upto(src, module, b),
            (_, true) => crate::builtins::pretty::write_deffunction_upto(src, module, b)
                .and_then(|()| b.write_str("\n   )")),
            _ => crate::builtins::pretty::write_deffunction_upto(src, module, b),
        };
        let _ = b.write_char('\n');
    }

    /// Prints a load error in CLIPS's style plus the position line.
    pub fn report_load_error(&mut self, source: &str, text: &str, e: &LoadError) {
        let mut b: TextBuf<4096> = TextBuf::new();
        if e.capacity.is_some() || e.expected == crate::parser::INPUT_ENDED {
            self.st.mode.unrecoverable = true;
        }
        self.format_load_error(source, text, e, &mut b, true);
        self.write(router::WERROR, b.as_str());
    }

    /// A load error's text as `report_load_error` prints it: CLIPS's message and
    /// construct echo, then (`position`) our position line naming `source`.
    pub fn format_load_error(
        &self,
        source: &str,
        text: &str,
        e: &LoadError,
        b: &mut TextBuf<4096>,
        position: bool,
    ) {
        // (a construct's echo names the module it was read into)
        let mut module: TextBuf<64> = TextBuf::new();
        let _ = module.write_str(self.current_module_name());
        let module = module.as_str();
        let tok = text.get(e.start as usize..e.end as usize).unwrap_or("");
        if let Some(c) = e.capacity {
            let _ = writeln!(b, "[MEMORY] {c}");
        } else if let LoadDetail::Arity {
            func,
            min,
            max,
            got,
        } = e.detail
        {
            let _ = if min == max {
                writeln!(
                    b,
                    "[ARGACCES4] Function {func} expected exactly {min} argument(s)"
                )
            } else if got < min as Ix {
                writeln!(
                    b,
                    "[ARGACCES4] Function {func} expected at least {min} argument(s)"
                )
            } else {
                writeln!(
                    b,
                    "[ARGACCES4] Function {func} expected no more than {max} argument(s)"
                )
            };
        } else if let LoadDetail::FunctionArity { nparams, rest } = e.detail {
            let how = if rest { "at least" } else { "exactly" };
            let _ = writeln!(
                b,
                "[ARGACCES4] Function {tok} expected {how} {nparams} argument(s)"
            );
        } else if let LoadDetail::UnknownSlot { template, whole } = e.detail {
            let _ = writeln!(
                b,
                "\n[TMPLTDEF1] Invalid slot {tok} not defined in corresponding deftemplate {}.",
                self.sym_text(template)
            );
            if whole && e.construct == "defrule" {
                self.write_global_echo(b, text, e, true, module);
            }
        } else if e.detail == LoadDetail::MissingFunction {
            let _ = writeln!(b, "\n[EXPRNPSR3] Missing function declaration for {tok}.");
        } else if let LoadDetail::NotInContext { func } = e.detail {
            // (CLIPS's two texts differ by an "is")
            let is = if func == "return" { "is " } else { "" };
            let _ = writeln!(
                b,
                "\n[PRCDRPSR2] The {func} function {is}not valid in this context."
            );
        } else if let LoadDetail::SequenceOperator { func, whole } = e.detail {
            let _ = writeln!(
                b,
                "[EXPRNPSR4] $ Sequence operator not a valid argument for {func}."
            );
            // the whole rule or deffunction, its closing `)` on a line of its own
            let head = if e.construct == "defrule" {
                "(defrule"
            } else {
                "(deffunction"
            };
            let upto = text.get(..e.start as usize).unwrap_or("");
            if let (true, Some(start)) = (whole, upto.rfind(head)) {
                let src = upto.get(start..).unwrap_or("");
                let _ = b.write_str("\nERROR:\n");
                let _ = if e.construct == "defrule" {
                    crate::builtins::pretty::write_defrule_upto(src, module, b)
                } else {
                    crate::builtins::pretty::write_deffunction_upto(src, module, b)
                };
                let _ = b.write_str("\n   )\n");
            }
        } else if let LoadDetail::Constraint {
            command,
            what,
            slot,
            range,
        } = e.detail
        {
            let _ = if what == Restriction::Cardinality {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] Literal slot values found in the {command} command"
                )
            } else {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] A literal slot value found in the {command} command"
                )
            };
            self.write_restriction(b, what, range, slot);
        } else if let LoadDetail::DefaultConstraint {
            attribute,
            what,
            slot,
            range,
            call,
        } = e.detail
        {
            // (only the parser finds calls there)
            let _ = if cfg!(feature = "parser") && call {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] The function return value found in the {attribute} attribute"
                )
            } else {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] An expression found in the {attribute} attribute"
                )
            };
            self.write_restriction(b, what, range, slot);
        } else if let LoadDetail::PatternConstraint {
            ce,
            what,
            slot,
            range,
        } = e.detail
        {
            let _ = if what == Restriction::Cardinality {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] The group of restrictions found in CE #{ce}"
                )
            } else {
                writeln!(
                    b,
                    "\n[CSTRNCHK1] A literal restriction value found in CE #{ce}"
                )
            };
            self.write_restriction(b, what, range, slot);
        } else if let LoadDetail::VariableConflict { ce, slot } = e.detail {
            let _ = writeln!(
                b,
                "\n[RULECSTR1] Variable {tok} in CE #{ce} slot {}\nhas constraint conflicts which make the pattern unmatchable.",
                self.sym_text(slot)
            );
        } else if write_argument_type(self, &mut *b, text, tok, e) {
        } else if let LoadDetail::MinAboveMax { cardinality } = e.detail {
            let what = if cardinality { "cardinality" } else { "range" };
            let _ = writeln!(
                b,
                "\n[CSTRNPSR2] Minimum {what} value must be less than\nor equal to the maximum {what} value"
            );
        } else if e.detail == LoadDetail::CardinalityOfSingle {
            let _ = writeln!(
                b,
                "\n[CSTRNPSR5] The cardinality attribute can only be used with multifield slots."
            );
        } else if e.detail == LoadDetail::CardinalityBelowZero {
            let _ = writeln!(
                b,
                "\n[CSTRNPSR6] Minimum cardinality value must be greater than or equal to zero"
            );
        } else if let LoadDetail::SingleSlot { slot } = e.detail {
            let _ = writeln!(
                b,
                "\n[TMPLTDEF2] The single field slot {} can only contain a single field value.",
                self.sym_text(slot)
            );
        } else if let LoadDetail::RequiredSlot { slot } = e.detail {
            let _ = writeln!(
                b,
                "\n[TMPLTRHS1] Slot {} requires a value because of its (default ?NONE) attribute.",
                self.sym_text(slot)
            );
        } else if let LoadDetail::ArgType {
            func,
            arg,
            expected,
        } = e.detail
        {
            let _ = writeln!(
                b,
                "[ARGACCES5] Function {func} expected argument #{arg} to be of type {expected}"
            );
        } else if let LoadDetail::InUse { construct } = e.detail {
            // named without the module it was written with (`MAIN::a` is `a`)
            let name = tok.rsplit_once("::").map_or(tok, |(_, n)| n);
            let _ = writeln!(
                b,
                "\n[CSTRCPSR4] Cannot redefine {construct} {name} while it is in use."
            );
        } else if let LoadDetail::AttributeTwice { attribute } = e.detail {
            let _ = writeln!(
                b,
                "\n[PRNTUTIL5] The {attribute} attribute has already been parsed."
            );
        } else if let LoadDetail::FacetTwice { multi } = e.detail {
            let what = if multi { "multifacet" } else { "facet" };
            let _ = writeln!(b, "\n[PRNTUTIL5] The {what} {tok} has already been parsed.");
        } else if let LoadDetail::AllowedCombined { first, second } = e.detail {
            let _ = writeln!(
                b,
                "\n[CSTRNPSR3] The {second} attribute cannot be used\nin conjunction with the {first} attribute."
            );
        } else if let LoadDetail::AllowedValueType { attribute } = e.detail {
            let _ = writeln!(
                b,
                "\n[CSTRNPSR4] Value does not match the expected type for the {attribute} attribute"
            );
        } else if let LoadDetail::TypeConflict { attribute } = e.detail {
            let _ = writeln!(
                b,
                "\n[CSTRNPSR1] The type attribute conflicts with the {attribute} attribute."
            );
        } else if let LoadDetail::FactIndexInRule { command } = e.detail {
            let _ = writeln!(
                b,
                "\n[TMPLTFUN1] Fact-indexes can only be used by {command} as a top level command."
            );
        } else if e.detail == LoadDetail::DefaultSingle {
            let _ = writeln!(
                b,
                "\n[DEFAULT1] The default value for a single field slot must be a single field value"
            );
        } else if e.detail == LoadDetail::ReplacesConstruct {
            let _ = writeln!(
                b,
                "[DFFNXPSR1] Deffunctions are not allowed to replace constructs."
            );
        } else if matches!(
            e.detail,
            LoadDetail::SpecialMeaning | LoadDetail::RelationKeyword
        ) {
            let what = if e.detail == LoadDetail::SpecialMeaning {
                "deftemplate"
            } else {
                "relation"
            };
            let _ = writeln!(
                b,
                "\n[PATTERN1] The symbol {tok} has special meaning\nand may not be used as a {what} name."
            );
        } else if e.detail == LoadDetail::ParameterTwice {
            let _ = writeln!(b, "[PRCCODE7] Duplicate parameter names not allowed.");
        } else if e.detail == LoadDetail::ParameterAfterWildcard {
            let _ = writeln!(
                b,
                "[PRCCODE8] No parameters allowed after wildcard parameter."
            );
        } else if e.detail == LoadDetail::UndefinedVariable {
            // CLIPS checks the variables once the construct is read, and shows it whole
            let name = tok.trim_start_matches('$').trim_start_matches('?');
            let place = if e.construct == "defrule" {
                "RHS of defrule"
            } else {
                "deffunction"
            };
            let _ = writeln!(
                b,
                "\n[PRCCODE3] Undefined variable {name} referenced in {place}."
            );
            self.write_global_echo(b, text, e, true, module);
        } else if let LoadDetail::LogicalOrder { gap } = e.detail {
            let _ = writeln!(
                b,
                "{}",
                if gap {
                    "\n[RULEPSR2] Gaps may not exist between logical CEs"
                } else {
                    "\n[RULEPSR1] Logical CEs must be placed first in a rule"
                }
            );
            self.write_global_echo(b, text, e, true, module);
        } else if e.detail == LoadDetail::ReplacesBuiltin {
            let _ = writeln!(
                b,
                "[DFFNXPSR2] Deffunctions are not allowed to replace external functions."
            );
        } else if write_literal_conflict(self, &mut *b, tok, e) {
        } else if cfg!(feature = "extras") && is_mixed_constraint(e) {
            let _ = writeln!(
                b,
                "\n[PATTERN2] Single and multifield constraints cannot be mixed in a field constraint"
            );
        } else if e.detail == LoadDetail::MixedVariable {
            let name = tok.trim_start_matches('$').trim_start_matches('?');
            let _ = writeln!(
                b,
                "\n[ANALYSIS3] Variable ?{name} is used as both a single and multifield variable in the LHS"
            );
        } else if let LoadDetail::AddressBound { ce, earlier_field } = e.detail {
            let _ = if earlier_field {
                writeln!(
                    b,
                    "\n[ANALYSIS2] Pattern-address {tok} used in CE #{ce} was previously bound within a pattern CE."
                )
            } else {
                writeln!(
                    b,
                    "\n[ANALYSIS1] Duplicate pattern-address {tok} found in CE #{ce}."
                )
            };
        } else if e.detail == LoadDetail::SlotTwice {
            let _ = writeln!(b, "\n[PRNTUTIL5] The slot {tok} has already been parsed.");
        } else if e.detail == LoadDetail::ModuleSpecifier {
            let _ = writeln!(b, "\n[MODULDEF1] Illegal use of the module specifier.");
        } else if e.detail == LoadDetail::ImpliedConflict {
            let _ = writeln!(
                b,
                "\n[CSTRCPSR3] Cannot define implied deftemplate {tok} because of an import/export conflict."
            );
        } else if let LoadDetail::ImportConflict { construct } = e.detail {
            let name = match construct {
                "defglobal" => tok.trim_start_matches("?*").trim_end_matches('*'),
                _ => crate::module::split_qualified(tok).map_or(tok, |(_, n)| n),
            };
            let _ = writeln!(
                b,
                "\n[CSTRCPSR3] Cannot define {construct} {name} because of an import/export conflict.\n\nERROR:"
            );
            let _ = if construct == "defglobal" {
                writeln!(b, "(defglobal {module} ?*{name}* ")
            } else {
                writeln!(b, "({construct} {module}::{name}")
            };
        } else if let LoadDetail::UndefinedGlobal { whole } = e.detail {
            let _ = writeln!(
                b,
                "\n[GLOBLPSR1] \nGlobal variable {tok} was referenced, but is not defined."
            );
            if matches!(e.construct, "defrule" | "deffunction") {
                self.write_global_echo(b, text, e, whole, module);
            }
        } else if let LoadDetail::NotExported {
            module: m,
            name,
            class,
        } = e.detail
        {
            let m = self.sym_text(m);
            let _ = if class.is_empty() {
                writeln!(
                    b,
                    "\n[MODULPSR1] Module {m} does not export any constructs."
                )
            } else if name == NONE {
                writeln!(
                    b,
                    "\n[MODULPSR1] Module {m} does not export any {class} constructs."
                )
            } else {
                writeln!(
                    b,
                    "\n[MODULPSR1] Module {m} does not export the {class} {}.",
                    self.sym_text(name)
                )
            };
            let _ = b.write_str("\nERROR:\n");
            let upto = text.get(..e.end as usize).unwrap_or(text);
            let _ = crate::builtins::modules::write_defmodule_at(upto, e.start as usize, b);
            let _ = b.write_char('\n');
        } else if let LoadDetail::ModuleImportConflict { class, name } = e.detail {
            let _ = writeln!(
                b,
                "\n[CSTRCPSR3] Cannot define defmodule {tok} because of an import/export conflict caused by the {class} {}.\n\nERROR:",
                self.sym_text(name)
            );
            let _ = crate::builtins::modules::write_defmodule_at(text, e.start as usize, b);
            let _ = b.write_char('\n');
        } else if let LoadDetail::UnboundInLhs {
            slot,
            ce,
            field,
            in_call,
        } = e.detail
        {
            // a global is named as CLIPS read it, a variable without the stars, a
            // multifield one without its `$`
            let _ = match tok.strip_prefix("?*") {
                Some(g) => write!(b, "\n[ANALYSIS4] Variable ?{}", g.trim_end_matches('*')),
                None => write!(b, "\n[ANALYSIS4] Variable {}", tok.trim_start_matches('$')),
            };
            if in_call {
                let _ = b.write_str(" found in the expression ");
                let _ = write_enclosing_call(b, text, e.start as usize);
                let _ = b.write_char('\n');
            } else {
                let _ = b.write_char(' ');
            }
            let _ = write!(b, "was referenced in CE #{ce}");
            let _ = if slot != NONE {
                write!(b, " slot {}", self.sym_text(slot))
            } else if field != 0 {
                write!(b, " field #{field}")
            } else {
                Ok(())
            };
            let _ = writeln!(b, " before being defined.");
            self.write_global_echo(b, text, e, true, module);
        } else if e.detail == LoadDetail::MissingName {
            let _ = writeln!(
                b,
                "\n[CSTRCPSR2] Missing name for {} construct\n\nERROR:\n({} {tok}",
                e.construct, e.construct
            );
        } else if e.detail == LoadDetail::NoSuchModule {
            let _ = writeln!(b, "[PRNTUTIL1] Unable to find defmodule {tok}.");
            // a construct named `MOD::name` of a module not defined: shown up to it
            let rest = text.get(e.end as usize..).unwrap_or("");
            if matches!(
                e.construct,
                "defrule" | "deffacts" | "deftemplate" | "deffunction"
            ) && rest.starts_with("::")
            {
                let end = rest
                    .find(|c: char| c.is_whitespace() || c == '(' || c == ')')
                    .unwrap_or(rest.len());
                let _ = writeln!(b, "\nERROR:\n({} {tok}{}", e.construct, &rest[..end]);
            }
        } else if e.detail == LoadDetail::NoSuchTemplate {
            let _ = writeln!(b, "[PRNTUTIL1] Unable to find deftemplate {tok}.");
        } else if e.detail == LoadDetail::NotACommand {
            let _ = writeln!(b, "[COMMLINE1] Expected a '(', constant, or variable");
        } else if e.detail == LoadDetail::ExpectedCommand {
            let _ = writeln!(b, "[COMMLINE2] Expected a command.");
        } else if let LoadDetail::NotImplemented { what } = e.detail {
            let _ = writeln!(
                b,
                "\n[NOTIMPL1] robotino-agent does not implement {what}: {tok}"
            );
        } else if e.detail == LoadDetail::DefaultEvaluation {
            // the evaluation error is printed; CLIPS adds only the construct
        } else if let LoadDetail::Text { text } = e.detail {
            let _ = writeln!(b, "\n{text}");
        } else if let LoadDetail::SyntaxOf { part } = e.detail {
            let _ = writeln!(
                b,
                "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {part}."
            );
        } else if let LoadDetail::Query { what, func } = e.detail {
            let _ = match what {
                1 => writeln!(
                    b,
                    "[FACTQPSR1] Duplicate fact member variable name in function {func}."
                ),
                2 => writeln!(
                    b,
                    "[FACTQPSR2] Binds are not allowed in fact-set query in function {func}."
                ),
                _ => writeln!(
                    b,
                    "[FACTQPSR3] Cannot rebind fact-set member variable {} in function {func}.",
                    tok.trim_start_matches(['?', '$'])
                ),
            };
        } else if e.construct == "command" {
            {
                let _ = writeln!(
                    b,
                    "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for the command."
                );
            }
        } else {
            let _ = writeln!(
                b,
                "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {}.",
                e.construct
            );
        }
        if e.query_syntax {
            let _ = writeln!(
                b,
                "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for fact-set query function."
            );
        }
        // a defglobal whose initial value failed: from the global to the value's end
        if e.construct == "defglobal" && e.detail == LoadDetail::NoSuchModule {
            // (no module to name: up to the name it did not find)
            let _ = writeln!(b, "\nERROR:\n(defglobal {tok}");
        } else if e.construct == "defglobal" && e.echo_end != 0 {
            let _ = write!(b, "\nERROR:\n(defglobal {module} ");
            // an unknown function: from its global (`?*e* = (+ 1 (foo`)
            #[cfg(feature = "parser")]
            let from = match e.detail {
                LoadDetail::MissingFunction
                | LoadDetail::Arity { .. }
                | LoadDetail::FunctionArity { .. }
                | LoadDetail::ArgType { .. }
                | LoadDetail::FactIndexInRule { .. } => {
                    crate::builtins::pretty::defglobal_name_before(text, e.start as usize)
                }
                _ => None,
            };
            #[cfg(not(feature = "parser"))]
            let from: Option<usize> = None;
            let upto = text.get(..e.echo_end as usize).unwrap_or("");
            let _ = match from {
                // (as CLIPS's pretty-print buffer holds it: `(duplicate (`)
                #[cfg(feature = "parser")]
                Some(from) => crate::builtins::pretty::write_defglobal_value_upto(
                    upto.get(from..).unwrap_or(""),
                    b,
                ),
                _ => b.write_str(upto.get(e.start as usize..).unwrap_or("")),
            };
            if e.echo_tail == crate::error::EchoTail::OpenParen {
                let _ = b.write_char('(');
            }
            if e.echo_tail == crate::error::EchoTail::SpaceBefore {
                let _ = b.write_str(" )");
            }
            let _ = b.write_char('\n');
        }
        // a defmodule CLIPS stopped reading is shown up to the token it stopped at (a
        // `)` one space after the text before it)
        if e.construct.starts_with("defmodule")
            && matches!(
                e.detail,
                LoadDetail::Syntax
                    | LoadDetail::NoSuchModule
                    | LoadDetail::InUse { .. }
                    | LoadDetail::SyntaxOf {
                        part: "module specifier"
                    }
            )
        {
            let _ = b.write_str("\nERROR:\n");
            let rparen = tok == ")";
            let end = if rparen { e.start } else { e.end };
            let upto = text.get(..end as usize).unwrap_or(text);
            let _ = crate::builtins::modules::write_defmodule_at(upto, e.start as usize, b);
            if rparen {
                let _ = b.write_str(" )");
            }
            let _ = b.write_char('\n');
        }
        // CLIPS checks modify/duplicate slot values and the patterns' constraints once
        // the whole rule is read, and then shows the rule it rejected
        if (matches!(
            e.detail,
            LoadDetail::Constraint {
                command: "modify" | "duplicate",
                ..
            } | LoadDetail::PatternConstraint { .. }
                | LoadDetail::VariableConflict { .. }
                | LoadDetail::AddressBound { .. }
                | LoadDetail::MixedVariable
        ) || is_rhs_argument_type(e)
            || is_literal_conflict(e))
            && e.construct == "defrule"
        {
            let _ = b.write_str("\nERROR:\n");
            let _ = crate::builtins::pretty::write_defrule(text, module, b);
            let _ = b.write_char('\n');
        }
        // CLIPS shows the construct it rejected up to where it stopped reading: a
        // deftemplate's slot, a rule's action (a prompt command is not shown)
        let assert_in_rule = matches!(
            e.detail,
            LoadDetail::Constraint {
                command: "assert",
                ..
            }
        ) && e.construct == "defrule";
        if e.construct == "deffacts"
            && (e.echo_end != 0 || matches!(e.detail, LoadDetail::Constraint { .. }))
        {
            let _ = b.write_str("\nERROR:\n");
            let _ = write_echo(
                text,
                e,
                module,
                b,
                crate::builtins::pretty::write_deffacts_upto,
            );
            if e.echo_end == u32::MAX {
                // the whole deffacts (`[PRNTUTIL6]`)
                let _ = b.write_char(')');
            }
            let _ = b.write_char('\n');
        } else if (matches!(
            e.detail,
            LoadDetail::Constraint {
                command: "assert",
                ..
            }
        ) || (matches!(e.detail, LoadDetail::SingleSlot { .. }) && e.echo_end != 0))
            && e.construct == "deffunction"
        {
            let _ = b.write_str("\nERROR:\n");
            let _ = write_echo(
                text,
                e,
                module,
                b,
                crate::builtins::pretty::write_deffunction_upto,
            );
            let _ = b.write_char('\n');
        } else if assert_in_rule {
            let _ = b.write_str("\nERROR:\n");
            let _ = write_echo(
                text,
                e,
                module,
                b,
                crate::builtins::pretty::write_defrule_upto,
            );
            let _ = b.write_char('\n');
        } else if e.echo_end != 0
            && e.construct == "defrule"
            && (is_mixed_constraint(e)
                || matches!(
                    e.detail,
                    LoadDetail::Syntax
                        | LoadDetail::SyntaxOf { .. }
                        | LoadDetail::Text { .. }
                        | LoadDetail::SingleSlot { .. }
                        | LoadDetail::MissingFunction
                        | LoadDetail::NotInContext { .. }
                        | LoadDetail::SequenceOperator { .. }
                        | LoadDetail::Arity { .. }
                        | LoadDetail::FunctionArity { .. }
                        | LoadDetail::ArgType { .. }
                        | LoadDetail::FactIndexInRule { .. }
                        | LoadDetail::SlotTwice
                        | LoadDetail::ModuleSpecifier
                        | LoadDetail::UnknownSlot { .. }
                        | LoadDetail::RelationKeyword
                        | LoadDetail::NoSuchTemplate
                        | LoadDetail::Query { .. }
                        | LoadDetail::ImpliedConflict
                        | LoadDetail::DefaultEvaluation
                ))
        {
            // a rule CLIPS stopped reading, in its conditions or its actions
            let _ = b.write_str("\nERROR:\n");
            // (a glued or own-line last token is no `=>` of the rule)
            let cut = if matches!(
                e.echo_tail,
                crate::error::EchoTail::Glued | crate::error::EchoTail::OwnLine
            ) {
                e.start.min(e.echo_end)
            } else {
                e.echo_end
            };
            let upto = text.get(..cut as usize).unwrap_or(text);
            let _ = if crate::builtins::pretty::has_arrow(upto) {
                write_echo(
                    text,
                    e,
                    module,
                    b,
                    crate::builtins::pretty::write_defrule_upto,
                )
            } else {
                write_echo(
                    text,
                    e,
                    module,
                    b,
                    crate::builtins::pretty::write_defrule_lhs_upto,
                )
            };
            // (an empty `(and)`, `(not)` or `(exists)`: the writer shows the `)` CLIPS
            // read too)
            let _ = b.write_char('\n');
        } else if e.echo_end != 0
            && e.construct == "deffunction"
            && matches!(
                e.detail,
                LoadDetail::MissingFunction
                    | LoadDetail::SyntaxOf { .. }
                    | LoadDetail::Text { .. }
                    | LoadDetail::NotInContext { .. }
                    | LoadDetail::SequenceOperator { .. }
                    | LoadDetail::Arity { .. }
                    | LoadDetail::FunctionArity { .. }
                    | LoadDetail::ArgType { .. }
                    | LoadDetail::FactIndexInRule { .. }
                    | LoadDetail::ReplacesBuiltin
                    | LoadDetail::ReplacesConstruct
                    | LoadDetail::ParameterTwice
                    | LoadDetail::ParameterAfterWildcard
                    | LoadDetail::SlotTwice
                    | LoadDetail::ModuleSpecifier
                    | LoadDetail::UnknownSlot { .. }
                    | LoadDetail::RelationKeyword
                    | LoadDetail::NoSuchTemplate
                    | LoadDetail::Query { .. }
                    | LoadDetail::ImpliedConflict
            )
        {
            let _ = b.write_str("\nERROR:\n");
            let _ = write_echo(
                text,
                e,
                module,
                b,
                crate::builtins::pretty::write_deffunction_upto,
            );
            let _ = b.write_char('\n');
        } else if e.echo_end != 0
            && e.construct != "defglobal"
            && !matches!(e.detail, LoadDetail::Constraint { .. })
            // (an unknown function elsewhere, at the prompt or in a defglobal, is not
            // shown)
            && (!matches!(
                e.detail,
                LoadDetail::MissingFunction
                    | LoadDetail::SingleSlot { .. }
                    | LoadDetail::Text { .. }
                    | LoadDetail::NotInContext { .. }
                    | LoadDetail::SyntaxOf { .. }
                    | LoadDetail::SequenceOperator { .. }
                    | LoadDetail::Query { .. }
                    | LoadDetail::ImpliedConflict
            ) || e.construct == "deftemplate")
        {
            let _ = b.write_str("\nERROR:\n");
            let _ = crate::builtins::pretty::write_deftemplate_echo(
                text,
                e.echo_end as usize,
                e.echo_tail,
                module,
                b,
            );
            let _ = b.write_char('\n');
        }
        if position {
            let _ = writeln!(
                b,
                "--> {}:{}:{}: expected {}",
                source,
                e.line + self.st.io.line_base,
                e.col,
                e.expected
            );
        }
    }

    /// Loads constructs from text (`load`): constructs before a bad one stay.
    /// Returns the number of constructs defined.
    pub fn load_text(&mut self, text: &str, verbose: bool) -> Result<usize, LoadError> {
        let mut progress = false;
        let r = self.load_items(text, verbose, &mut progress);
        if progress {
            self.write(router::STDOUT, "\n");
        }
        r
    }

    /// `load_text` for one piece of a file: `progress` tells whether progress marks
    /// (`*`, `%`, ...) were printed, so the caller ends their line once at the end.
    pub fn load_items(
        &mut self,
        text: &str,
        verbose: bool,
        progress: &mut bool,
    ) -> Result<usize, LoadError> {
        let mut n = 0;
        self.st.io.progress_printed = *progress;
        let mut p = Parser::new(self, text);
        let r = loop {
            let first = p.peek();
            let start = first.start;
            let existed = p.cx.construct_exists(&text[start..]);
            p.cx.st.io.announce = verbose.then_some((start, existed, false));
            // CLIPS ends a halt with the construct whose matching caused it
            p.cx.st.mode.halting = false;
            let cp = p.cx.checkpoint();
            let item = match p.next_item() {
                Ok(Item::Command(_)) => {
                    // not a construct: drop what its parse built, report where it began
                    p.cx.rollback(cp);
                    Err(p.err(first, "a construct (load accepts constructs only)"))
                }
                item => item,
            };
            match item {
                Ok(Item::End) => {
                    break Ok(n);
                }
                Ok(Item::Construct) => {
                    n += 1;
                    // a defrule announced itself before it was matched
                    p.announce();
                }
                Ok(Item::Command(_)) => {}
                Err(e) => break Err(e),
            }
        };
        self.st.io.announce = None;
        *progress = self.st.io.progress_printed;
        r
    }

    /// Runs commands from text as CLIPS's batch mode does: a prompt, the echoed input
    /// lines up to a complete command, its result; the rest of that line is dropped.
    pub fn batch_text(&mut self, text: &str, echo: bool) -> Result<(), EvalError> {
        self.batch_text_named(text, echo, "batch")
    }

    /// `batch_text` naming the source in error positions.
    pub fn batch_text_named(
        &mut self,
        text: &str,
        echo: bool,
        source: &str,
    ) -> Result<(), EvalError> {
        let mut pos = 0;
        let mut line_base = 0u32;
        while pos < text.len() && !self.st.mode.exit {
            if echo && !core::mem::take(&mut self.st.io.prompt_shown) {
                self.write(router::STDOUT, "CLIPS> ");
            }
            // the command is complete at the first line end after its item, a `\r` as
            // well as a `\n` as CLIPS reads lines (one walk from `pos`: testing each
            // longer prefix again walked a construct of n lines n times)
            let found = command_complete(&text[pos..]);
            let end = match found {
                Some(k) => pos + k + line_end_after(&text[pos + k..]),
                None => text.len(),
            };
            if echo {
                self.write(router::STDOUT, &text[pos..end]);
            }
            if let Some(k) = found {
                self.st.io.line_base = line_base;
                self.exec_command(&text[pos..pos + k], source);
                self.st.io.line_base = 0;
                #[cfg(feature = "parser")]
                if self.st.io.quiet_results {
                    self.flush_bind_list();
                }
                if !self.st.mode.firing && self.st.eval.eval_depth == 0 {
                    self.debug_check("after a batch command");
                }
            } else if !only_blank(&text[pos..end]) && !self.st.io.quiet_results {
                // input ends inside a command: report where it is incomplete
                // (`batch*` drops it silently, as CLIPS does)
                self.st.io.line_base = line_base;
                self.exec_command(&text[pos..end], source);
                self.st.io.line_base = 0;
            }
            line_base += text[pos..end].bytes().filter(|&b| b == b'\n').count() as u32;
            pos = end;
        }
        Ok(())
    }

    /// Runs a command file streamed through a fixed buffer (`batch`, `batch*`): with
    /// `echo` as CLIPS's batch mode (prompt, echoed lines, results), without it silently
    /// but for errors and the commands' own output. Returns whether the file was read
    /// to its end.
    pub fn batch_file_stream(&mut self, path: &str, echo: bool) -> Result<bool, EvalError> {
        let mut file = FileItems::new(path, file_buffer());
        if file.open(self).is_err() {
            self.report_unopened_file("batch", path);
            return Ok(false);
        }
        if self.st.io.batch_depth >= MAX_BATCH_DEPTH {
            self.write(
                router::WERROR,
                "[FILEIO] batch files nested too deeply (a file that runs itself?)\n",
            );
            return Ok(false);
        }
        self.st.io.batch_depth += 1;
        let saved_quiet = self.st.io.quiet_results;
        self.st.io.quiet_results = !echo;
        let mut done = true;
        #[cfg(feature = "parser")]
        {
            self.st.io.carry.active = false;
        }
        while !self.st.mode.exit {
            let item = match file.next_command(self) {
                Ok(Some(item)) => item,
                Ok(None) => break,
                Err(e) => {
                    let mut p: TextBuf<256> = TextBuf::new();
                    let _ = p.write_str(file.path());
                    self.report_file_error("batch", p.as_str(), e);
                    done = false;
                    break;
                }
            };
            // a batch file this one ran ended inside a command, which goes on in this
            // file's text (CLIPS reads on in the input outside the inner file)
            #[cfg(feature = "parser")]
            if self.st.io.carry.active {
                let (start, line_base) = (item.end_offset - item.text.len() as u64, item.line_base);
                if let Some((offset, lines)) = self.join_carried(path, start, line_base) {
                    file.seek(offset, lines);
                }
                continue;
            }
            let command = &item.text[..item.len];
            // CLIPS runs a command at the first `\r` or `\n` after it, but echoes the
            // batch file's text only at each `\n`: a line ending in `\r\n` runs before
            // its last line is echoed, which then follows the next prompt
            let held = if echo && !item.last && !only_blank(command) {
                crlf_held_line(item.text, item.len)
            } else {
                None
            };
            if echo {
                // a long comment block comes alone: echoed without a prompt of its own
                let blank = only_blank(command);
                if (!blank || item.last) && !core::mem::take(&mut self.st.io.prompt_shown) {
                    self.write(router::STDOUT, "CLIPS> ");
                }
                #[cfg(feature = "parser")]
                self.flush_unechoed();
                self.write(
                    router::STDOUT,
                    &item.text[..held.unwrap_or(item.text.len())],
                );
                // CLIPS prompted for a command the file's end cut short: the next
                // command read (from the outer input) goes without a prompt
                if blank && item.last {
                    self.st.io.prompt_shown = true;
                }
            }
            if !only_blank(command) && item.last {
                // the file ends inside a command: CLIPS reads on in the input outside
                // the file (`batch*` drops it); nothing is reported
                let start = item.end_offset - item.text.len() as u64;
                let line_base = item.line_base;
                if echo {
                    self.carry_incomplete(path, command, start, line_base);
                }
            } else if !only_blank(command) {
                self.st.io.line_base = item.line_base;
                let moved = self.exec_batch_command(command, path, echo, item.end_offset);
                self.st.io.line_base = 0;
                #[cfg(feature = "parser")]
                if !echo {
                    self.flush_bind_list();
                }
                if let Some(h) = held {
                    // (exit) closes the file before its `\n` is read: echoed without it
                    if self.st.mode.exit {
                        self.write(router::STDOUT, &item.text[h..item.text.len() - 1]);
                    } else {
                        self.write(router::STDOUT, "CLIPS> ");
                        self.st.io.prompt_shown = true;
                        self.write(router::STDOUT, &item.text[h..]);
                    }
                }
                if let Some((offset, lines)) = moved {
                    file.skip_to(offset, lines);
                }
            }
        }
        self.st.io.quiet_results = saved_quiet;
        self.st.io.batch_depth -= 1;
        Ok(done)
    }

    /// The command a batch file left unfinished (`BatchIo::carry`) goes on in the
    /// batch file `path` from offset `start` (`line_base` newlines before it): echoed
    /// without prompts as it is read, run once the text closes it (the rest of that
    /// line dropped, as CLIPS's batch mode does). Returns where `path` goes on after
    /// it; None when the file ended first (the command goes on further out).
    #[cfg(feature = "parser")]
    fn join_carried(&mut self, path: &str, start: u64, line_base: u32) -> Option<(u64, u32)> {
        use crate::builtins::files::FileBuffer;
        let carry = core::mem::take(&mut self.st.io.carry);
        let mut join = file_buffer();
        let mut len = 0usize;
        // the command so far, from the inner file
        loop {
            if len == join.bytes().len() && !join.enlarge() {
                return None;
            }
            let room = &mut join.bytes_mut()[len..];
            match self
                .host
                .read_file_at(carry.path.as_str(), carry.offset + len as u64, room)
            {
                Ok(0) => break,
                Ok(n) => len += n,
                Err(_) => return None,
            }
        }
        let carried = len;
        // this file's text from `start`, read the same way, until the command is whole
        let mut at = start;
        let end = loop {
            if let Some(k) = crate::lexer::item_end(&join.bytes()[..len]) {
                break Some(k);
            }
            if len == join.bytes().len() && !join.enlarge() {
                return None;
            }
            let room = &mut join.bytes_mut()[len..];
            match self.host.read_file_at(path, at, room) {
                Ok(0) => break None,
                Ok(n) => {
                    len += n;
                    at += n as u64;
                }
                Err(_) => return None,
            }
        };
        let text = core::str::from_utf8(&join.bytes()[..len]).ok()?;
        let Some(k) = end else {
            // the file ended too: all of it echoed, the command goes on further out
            self.write(router::STDOUT, &text[carried..]);
            self.st.io.carry = carry;
            // (the outermost file: the command goes on at the prompt, unfinished)
            if self.st.io.batch_depth == 1 {
                self.st.mode.unrecoverable = true;
            }
            return Some((at, line_base + text[carried..].matches('\n').count() as u32));
        };
        // echoed to the end of the line the command ends on, which is dropped
        let upto = match text[k..].find('\n') {
            Some(nl) => k + nl + 1,
            None => len,
        };
        let from = carried.min(upto);
        self.write(router::STDOUT, &text[from..upto]);
        let command = &text[..k];
        self.exec_command(command, path);
        let rest = (upto - carried.min(upto)) as u64;
        Some((
            start + rest,
            line_base + text[from..upto].matches('\n').count() as u32,
        ))
    }

    /// A batch file with echo ended inside `command` (at file offset `start`): it goes
    /// on in the outer input (`BatchIo::carry`). CLIPS prints nothing for it; we print
    /// only our position line (where the command is incomplete), and the command line
    /// exits non-zero.
    fn carry_incomplete(&mut self, path: &str, command: &str, start: u64, line_base: u32) {
        let cp = self.checkpoint();
        let mut p = Parser::new(self, command);
        p.check_only = true;
        let item = p.next_item();
        if let Ok(Item::Command(_)) = item {
            self.rollback(cp);
        }
        // (a batch file run from another: the command goes on in that file, where it
        // may close; only the outermost one's end is reported, where input goes on
        // at the prompt)
        if self.st.io.batch_depth > 1 {
            self.set_carry(path, start, line_base);
            return;
        }
        if let Err(e) = item {
            if e.detail != LoadDetail::Checked {
                let mut b: TextBuf<400> = TextBuf::new();
                if !command.ends_with('\n') {
                    let _ = b.write_char('\n');
                }
                let _ = writeln!(
                    b,
                    "--> {}:{}:{}: expected {}",
                    path,
                    e.line + line_base,
                    e.col,
                    e.expected
                );
                self.write(router::WERROR, b.as_str());
            }
        }
        self.st.mode.unrecoverable = true;
        self.set_carry(path, start, line_base);
    }

    /// Remembers the unfinished command of batch file `path` (`BatchIo::carry`).
    fn set_carry(&mut self, path: &str, start: u64, line_base: u32) {
        #[cfg(feature = "parser")]
        {
            let carry = &mut self.st.io.carry;
            carry.active = true;
            carry.path.clear();
            let _ = carry.path.write_str(path);
            carry.offset = start;
            carry.lines = line_base;
        }
        #[cfg(not(feature = "parser"))]
        let _ = (path, start, line_base);
    }

    /// Runs one command of a batch file (`path`) that ends at byte `end`. With `echo`
    /// (CLIPS's batch mode, not `batch*`) the command's reads from stdin take the
    /// file's next lines (`builtins::io`): then where the file goes on (offset, and
    /// the newlines the reads took) when they took any.
    fn exec_batch_command(
        &mut self,
        command: &str,
        path: &str,
        echo: bool,
        end: u64,
    ) -> Option<(u64, u32)> {
        #[cfg(feature = "parser")]
        if echo {
            let mut input = crate::engine::BatchInput::new();
            input.active = true;
            input.offset = end;
            let _ = input.path.write_str(path);
            let outer = core::mem::replace(&mut self.st.io.batch_input, input);
            self.exec_command(command, path);
            let left = core::mem::replace(&mut self.st.io.batch_input, outer);
            return (left.offset != end).then_some((left.offset, left.lines));
        }
        let _ = (echo, end);
        self.exec_command(command, path);
        None
    }

    /// `batch*` (and `clips -f2`) forgets the variables top-level `bind`s set once each
    /// of its commands ran, those bound at the prompt before it too (CLIPS's
    /// `FlushBindList`); `batch` and the prompt keep them.
    #[cfg(feature = "parser")]
    fn flush_bind_list(&mut self) {
        for g in 0..self.st.pools.nglobals as usize {
            let t = self.sym_text(self.globals[g].name);
            if t.starts_with('?') && !t.starts_with("?*") {
                self.globals[g].value = Value::Void;
            }
        }
    }

    /// Runs the file a `batch` command asked for, as the next input of the command loop.
    pub fn run_pending_batch(&mut self) {
        #[cfg(feature = "parser")]
        while !self.st.io.pending_batch.is_empty() && !self.st.mode.exit {
            let mut path: TextBuf<256> = TextBuf::new();
            let _ = path.write_str(self.st.io.pending_batch.as_str());
            self.st.io.pending_batch.clear();
            let _ = self.batch_file_stream(path.as_str(), true);
        }
    }

    /// Executes one complete top-level item: defines a construct or evaluates a
    /// command and prints its result (nothing for void).
    // one copy of the command loop's body: callers are many, and it matters for the
    // image's code budget
    #[inline(never)]
    pub fn exec_command(&mut self, text: &str, source: &str) {
        self.exec_item(text, source);
        // inside batch* a batch file waits for the command loop, as in CLIPS
        if !self.st.io.quiet_results {
            self.run_pending_batch();
        }
    }

    #[inline(never)]
    fn exec_item(&mut self, text: &str, source: &str) {
        // a halt lasts until the command (or construct) that caused it is done
        self.st.mode.halting = false;
        let exprs_before = self.st.pools.nexprs;
        // a command run from inside another (`batch*` in a rule's actions or a
        // deffunction) leaves the outer one's frame, scratch and command as they were;
        // one at the prompt starts and ends with all three empty
        let outer = if self.st.eval.eval_depth > 0 {
            (self.st.frame, self.st.eval.command_base)
        } else {
            (Frame::new(), 0)
        };
        self.st.eval.command_base = exprs_before;
        let cp = self.checkpoint();
        let mut p = Parser::new(self, text);
        let item = p.next_item();
        let nlocals = p.nlocals;
        match item {
            Ok(Item::Command(e)) => {
                // a frame for loop/query variables of the command
                self.st.frame.bp = self.st.frame.sp;
                let mut r = Ok(Value::Void);
                for _ in 0..nlocals {
                    if let Err(c) = self.push_value(Value::Void) {
                        r = Err(c.into());
                    }
                }
                self.st.eval.literal_error = false;
                self.st.eval.error_fallback = None;
                // what the command retracts stays readable until it is done: CLIPS
                // frees a retracted fact's values between commands only
                let hold = !self.st.mode.firing && self.st.eval.query_hold == 0;
                if hold {
                    self.st.eval.query_hold = COMMAND_HOLD;
                }
                // a variable alone is printed even when it holds a void value (an
                // empty line, as CLIPS's command loop does); read before the command
                // runs, as a `clear` lets its nodes go
                let bare_variable = matches!(self.exprs[e as usize].op, Op::Global | Op::Local);
                if r.is_ok() {
                    r = self.eval(e);
                }
                if hold {
                    self.st.eval.query_hold = 0;
                    self.free_pending();
                }
                match r {
                    Ok(v) => {
                        if (v != Value::Void || bare_variable) && !self.st.io.quiet_results {
                            self.print_value(router::STDOUT, v, true);
                            self.write(router::STDOUT, "\n");
                        }
                    }
                    Err(err) if err.kind() == EvalErrorKind::Exit => {}
                    Err(err) => {
                        self.report_eval_error(err);
                        if !matches!(
                            err.kind(),
                            EvalErrorKind::Capacity(_) | EvalErrorKind::Interrupted
                        ) && !self.st.io.quiet_results
                        {
                            self.print_fallback(e);
                        }
                    }
                }
                self.st.frame = outer.0;
                self.st.eval.returning = false;
                self.st.eval.breaking = false;
                // a plain command leaves no expressions behind
                let now = self.checkpoint();
                if now.nrules == cp.nrules
                    && now.nfuncs == cp.nfuncs
                    && now.ndeffacts == cp.ndeffacts
                    && now.ntemplates == cp.ntemplates
                    && now.nglobals == cp.nglobals
                {
                    self.st.pools.nexprs = exprs_before;
                }
            }
            Ok(_) => {}
            Err(e) => self.report_load_error(source, text, &e),
        }
        self.st.eval.command_base = outer.1;
    }

    /// `load-facts`: each top-level `(fact ...)` is asserted, up to the first item that
    /// is no fact (CLIPS stops there quietly) or a fact CLIPS refuses (reported).
    pub fn load_facts_text(&mut self, text: &str) -> Result<FactsRead, EvalError> {
        let mut pos = 0;
        while let Some(k) = command_complete(&text[pos..]) {
            let chunk = &text[pos..pos + k];
            pos += k;
            let exprs_before = self.st.pools.nexprs;
            let mut p = Parser::new(self, chunk);
            p.scope = crate::parser::Scope::Lhs;
            p.constant_facts = true;
            if p.expect_lparen("a fact").is_err() {
                self.st.pools.nexprs = exprs_before;
                return Ok(FactsRead::Stopped);
            }
            let spec = match p.fact_spec() {
                Ok(s) => s,
                Err(e) => {
                    self.st.pools.nexprs = exprs_before;
                    self.report_fact_text_error("load-facts", chunk, &e);
                    return Ok(FactsRead::Failed);
                }
            };
            let r = self.assert_spec(spec);
            self.st.pools.nexprs = exprs_before;
            r?;
        }
        // what is left is an atom (no fact: CLIPS stops) or a fact the file cuts short
        Ok(match Lexer::new(&text[pos..]).next_token().tok {
            Tok::Eof => FactsRead::All,
            Tok::LParen => {
                self.write(
                    router::WERROR,
                    "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for RHS patterns.\n",
                );
                FactsRead::Failed
            }
            _ => FactsRead::Stopped,
        })
    }

    /// A fact's text `assert-string` or `load-facts` could not read, reported as
    /// CLIPS does: a syntax error names the RHS patterns (or the part it was in).
    pub fn report_fact_text_error(&mut self, source: &str, text: &str, e: &LoadError) {
        match e.detail {
            LoadDetail::Syntax => self.write(
                router::WERROR,
                "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for RHS patterns.\n",
            ),
            LoadDetail::SyntaxOf { part } => {
                let mut m: TextBuf<96> = TextBuf::new();
                let _ = write!(
                    m,
                    "\n[PRNTUTIL2] Syntax Error:  Check appropriate syntax for {part}.\n"
                );
                self.write(router::WERROR, m.as_str());
            }
            _ => self.report_load_error(source, text, e),
        }
    }

    /// Whether a fact slot is in use (live), for hosts.
    pub fn fact_is_live(&self, slot: Ix) -> bool {
        self.facts[slot as usize].state == FactState::Live
    }
}

/// How far `load-facts` read one item of its file.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum FactsRead {
    /// every fact in it was asserted (or a duplicate)
    All,
    /// an item that is no fact: CLIPS reads no further and answers TRUE
    Stopped,
    /// a fact CLIPS refuses, reported: no further, FALSE
    Failed,
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::testutil::run_program;

    #[test]
    fn reset_in_actions_keeps_the_matched_values() {
        // the rule's variables read the fact reset retracted, not what took its cells
        let out = run_program(
            "(deftemplate m (slot max))\n(deffacts d (m (max 0)) (a x) (b y))\n\
             (defrule again (m (max ?d&~0)) => (reset) (printout t \"d=\" ?d crlf))\n\
             (reset)\n(assert (m (max 5)))\n(run)\n",
        );
        assert!(out.contains("d=5"), "got {out}");
    }

    #[test]
    fn reset_in_a_deffunction_keeps_the_callers_multifields() {
        // the loop's list and the multifield argument live in scratch while the
        // command runs: the reset and the asserts after it must not take them
        let out = run_program(
            "(deffunction t ($?m) (reset) (assert (q 1 2 3 4 5 6)) (printout t ?m crlf))\n\
             (foreach ?x (create$ a b c) (t ?x k l))\n",
        );
        assert_eq!(out, "(a k l)\n(b k l)\n(c k l)\n");
    }

    #[test]
    fn globals_keep_multifields_across_commands() {
        let out = run_program(
            "(defglobal ?*l* = (create$ a b) ?*m* = 0)\n(bind ?*m* (create$ x y z))\n(bind ?*l* (create$ ?*l* c))\n(printout t ?*l* \" \" ?*m* crlf)\n(reset)\n(printout t ?*l* crlf)\n",
        );
        assert_eq!(out, "(x y z)\n(a b c)\n(a b c) (x y z)\n(a b)\n");
    }

    #[test]
    fn modify_gives_a_new_index_and_refires() {
        let out = run_program(
            "(deftemplate p (slot n))\n(defrule r ?f <- (p (n ?n&:(< ?n 3))) => (modify ?f (n (+ ?n 1))))\n(watch facts)\n(reset)\n(assert (p (n 1)))\n(run)\n",
        );
        assert!(out.contains("==> f-1     (p (n 1))"), "{out}");
        assert!(
            out.contains("<== f-1     (p (n 1))\n==> f-2     (p (n 2))"),
            "{out}"
        );
        assert!(out.contains("==> f-3     (p (n 3))"), "{out}");
    }

    #[test]
    fn batch_echo_drops_the_rest_of_the_line() {
        let mut e = std::boxed::Box::new(crate::engine::SmallEngine::new());
        let mut h = crate::testutil::CaptureHost::default();
        e.batch_str(&mut h, "(+ 1 2) (+ 3 4)\n; c\n(assert (a))\n", true);
        assert_eq!(
            h.out,
            "CLIPS> (+ 1 2) (+ 3 4)\n3\nCLIPS> ; c\n(assert (a))\n<Fact-1>\n"
        );
    }

    /// CLIPS's command loop ends a line at `\r` too: a file with old Mac line ends (or
    /// a `\r` between two commands) runs every command, as `clips -f2` does; the rest
    /// of a line after a command is dropped up to the `\r` only.
    #[test]
    fn batch_quiet_ends_lines_at_carriage_returns() {
        let mut e = std::boxed::Box::new(crate::engine::SmallEngine::new());
        let mut h = crate::testutil::CaptureHost::default();
        let text = "(deftemplate a\r  (slot x))\r(assert (a (x 1))) (+ 1 2)\r\
                    (printout t \"a\" crlf)\r(printout t \"b\" crlf)\r\n(facts)\r";
        e.batch_file_quiet(&mut h, "t.clp", text);
        assert_eq!(
            h.out,
            "a\nb\nf-0     (initial-fact)\nf-1     (a (x 1))\nFor a total of 2 facts.\n"
        );
    }
}

/// The innermost call around byte `at` of the rule `text` holds there, as CLIPS prints
/// an expression: tokens one space apart, globals as `?name`, floats in CLIPS's form
/// (`[ANALYSIS4]`).
fn write_enclosing_call(w: &mut dyn Write, text: &str, at: usize) -> core::fmt::Result {
    let head = text
        .get(..at)
        .and_then(|s| s.rfind("(defrule"))
        .unwrap_or(0);
    // the `(` of every call open at `at`
    let mut open = [0usize; 64];
    let mut depth = 0usize;
    let mut lx = Lexer::new(text.get(head..).unwrap_or(""));
    loop {
        let t = lx.next_token();
        if head + t.start >= at || matches!(t.tok, Tok::Eof | Tok::Bad) {
            break;
        }
        match t.tok {
            Tok::LParen => {
                if depth < open.len() {
                    open[depth] = head + t.start;
                }
                depth += 1;
            }
            Tok::RParen => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    let start = match depth {
        0 => at,
        d => open[(d - 1).min(open.len() - 1)],
    };
    let src = text.get(start..).unwrap_or("");
    let mut lx = Lexer::new(src);
    let mut depth = 0u32;
    let mut after_open = true;
    loop {
        let t = lx.next_token();
        match t.tok {
            Tok::Eof | Tok::Bad => return Ok(()),
            Tok::LParen => {
                if !after_open {
                    w.write_char(' ')?;
                }
                w.write_char('(')?;
                depth += 1;
                after_open = true;
                continue;
            }
            Tok::RParen => {
                w.write_char(')')?;
                depth = depth.saturating_sub(1);
            }
            tok => {
                if !after_open {
                    w.write_char(' ')?;
                }
                match tok {
                    Tok::Global(g) => write!(w, "?{g}")?,
                    Tok::Float(f) => crate::value::write_float(w, f)?,
                    _ => w.write_str(src.get(t.start..t.end).unwrap_or(""))?,
                }
            }
        }
        after_open = false;
        if depth == 0 {
            return Ok(());
        }
    }
}

/// Writes what CLIPS shows after `ERROR:` for construct text `text` read up to
/// `e.echo_end` by `write_upto`, joining the last token as `e.echo_tail` says: glued to
/// the text before it (a second value of a single-field slot: `(a 12(`), or a `)` CLIPS
/// read where something else was due, one space after the rest (`(declare )`).
fn write_echo(
    text: &str,
    e: &LoadError,
    module: &str,
    b: &mut dyn core::fmt::Write,
    write_upto: fn(&str, &str, &mut dyn core::fmt::Write) -> core::fmt::Result,
) -> core::fmt::Result {
    let glued = e.echo_tail == crate::error::EchoTail::Glued && e.start < e.echo_end;
    let own_line = e.echo_tail == crate::error::EchoTail::OwnLine && e.start < e.echo_end;
    let spaced_tail = e.echo_tail == crate::error::EchoTail::Spaced && e.start < e.echo_end;
    // a rule's own `)` on a line of its own (no `=>`): the writer reads up to it, so a
    // composite CE just before it keeps its `)`
    let rule_close = own_line
        && e.construct == "defrule"
        && text.get(e.start as usize..e.echo_end as usize) == Some(")");
    let cut = if (glued || own_line || spaced_tail) && !rule_close {
        e.start
    } else {
        e.echo_end
    };
    let mut last = LastChar {
        inner: b,
        last: '\0',
    };
    write_upto(text.get(..cut as usize).unwrap_or(text), module, &mut last)?;
    let spaced = last.last == ' ';
    if spaced_tail && !spaced {
        b.write_char(' ')?;
    }
    if glued || spaced_tail {
        b.write_str(
            text.get(e.start as usize..e.echo_end as usize)
                .unwrap_or(""),
        )?;
    }
    if e.echo_tail == crate::error::EchoTail::OwnLine && e.start < e.echo_end {
        b.write_str("\n   ")?;
        b.write_str(
            text.get(e.start as usize..e.echo_end as usize)
                .unwrap_or(""),
        )?;
    }
    if e.echo_tail == crate::error::EchoTail::OpenParen {
        b.write_char('(')?;
    }
    if e.echo_tail == crate::error::EchoTail::SpaceBefore {
        // (the pretty-printer may have written the space already: `(if `)
        b.write_str(if spaced { ")" } else { " )" })?;
    }
    Ok(())
}

/// A writer remembering the last character written through it.
struct LastChar<'a> {
    inner: &'a mut dyn core::fmt::Write,
    last: char,
}

impl core::fmt::Write for LastChar<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        if let Some(c) = s.chars().next_back() {
            self.last = c;
        }
        self.inner.write_str(s)
    }
}

/// Whether load error `e` is a `[RULECSTR3]` (`parser::rhs_types`).
fn is_rhs_argument_type(e: &LoadError) -> bool {
    #[cfg(feature = "extras")]
    return matches!(
        e.detail,
        LoadDetail::RhsArgumentType { .. } | LoadDetail::LhsArgumentType { .. }
    );
    #[cfg(not(feature = "extras"))]
    {
        let _ = e;
        false
    }
}

/// Writes CLIPS's `[RULECSTR3]` (actions) or `[RULECSTR2]` (conditions) message of
/// load error `e` when it is one (`tok`: the variable), and says so.
fn write_argument_type(
    cx: &Core<'_>,
    b: &mut dyn Write,
    text: &str,
    tok: &str,
    e: &LoadError,
) -> bool {
    #[cfg(feature = "extras")]
    {
        // (the call, the argument and the parses around it, as `rhs_types` found them)
        let (code, call_start, call_end, arg, passes) = match e.detail {
            LoadDetail::RhsArgumentType {
                call_start,
                call_end,
                arg,
                passes,
            } => ("RULECSTR3", call_start, call_end, arg, passes),
            LoadDetail::LhsArgumentType {
                call_start,
                call_end,
                arg,
                ..
            } => ("RULECSTR2", call_start, call_end, arg, 0),
            _ => return false,
        };
        let f = crate::parser::rhs_types::Found {
            var_start: e.start as usize,
            var_end: e.end as usize,
            arg,
            call_start: call_start as usize,
            call_end: call_end as usize,
            passes,
        };
        let _ = write!(
            b,
            "\n[{code}] Previous variable bindings of ?{} caused the type restrictions\nfor argument #{arg} of the expression ",
            tok.trim_start_matches('$').trim_start_matches('?'),
        );
        let _ = crate::parser::rhs_types::write_expression(b, text, &f, cx.st.mode.seq_ops);
        if let LoadDetail::LhsArgumentType {
            slot, ce, field, ..
        } = e.detail
        {
            let _ = write!(b, "\nfound in CE #{ce}");
            if slot != crate::value::NONE {
                let _ = write!(b, " slot {}", cx.sym_text(slot));
            } else if field > 0 {
                let _ = write!(b, " field #{field}");
            }
            let _ = b.write_str(" to be violated.\n");
        } else {
            let _ = b.write_str("\nfound in the rule's RHS to be violated.\n");
        }
        true
    }
    #[cfg(not(feature = "extras"))]
    {
        let _ = (cx, b, text, tok, e);
        false
    }
}

/// `[PATTERN2]` (`LoadDetail::MixedConstraint`, host only).
fn is_mixed_constraint(e: &LoadError) -> bool {
    #[cfg(feature = "extras")]
    return e.detail == LoadDetail::MixedConstraint;
    #[cfg(not(feature = "extras"))]
    {
        let _ = e;
        false
    }
}

/// `[RULECSTR1]` of a field's conflicting literals (`LoadDetail::LiteralConflict`,
/// host only): whether it was one.
fn write_literal_conflict(cx: &Core<'_>, b: &mut dyn Write, tok: &str, e: &LoadError) -> bool {
    #[cfg(feature = "extras")]
    if let LoadDetail::LiteralConflict {
        ce,
        slot,
        field,
        var,
    } = e.detail
    {
        let _ = if var {
            write!(b, "\n[RULECSTR1] Variable {tok} in CE #{ce} ")
        } else {
            write!(b, "\n[RULECSTR1] Pattern #{ce} ")
        };
        let _ = if slot == NONE {
            writeln!(b, "field #{field}")
        } else {
            writeln!(b, "slot {}", cx.sym_text(slot))
        };
        let _ = writeln!(
            b,
            "has constraint conflicts which make the pattern unmatchable."
        );
        return true;
    }
    let _ = (cx, b, tok, e);
    false
}

fn is_literal_conflict(e: &LoadError) -> bool {
    #[cfg(feature = "extras")]
    return matches!(e.detail, LoadDetail::LiteralConflict { .. });
    #[cfg(not(feature = "extras"))]
    {
        let _ = e;
        false
    }
}
