//! The loader: a [`RuleBase`] into a fresh engine.

use super::RuleBase;
use crate::config::Storage;
use crate::engine::{cap, Core, Engine};
use crate::error::{CapacityError, EvalError, Pool};
#[cfg(not(feature = "in-place"))]
use crate::expr::{FnKind, Op};
use crate::handle::JoinId;
use crate::host::Host;
use crate::rete::{JoinKind, KeyPlan, KEY_PLANS};
use crate::value::{Ix, Value, NONE};
use core::fmt;

/// Why a compiled rule base did not load. The engine is as it was before the call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CompiledError {
    /// The engine already holds constructs (a defmodule too, its constructs would be
    /// MAIN's): a compiled rule base loads into an engine fresh from start-up or
    /// `(clear)` only (its indices are the writer's).
    NotFresh,
    /// Symbol `index` of the rule base is not the engine's (host functions registered
    /// in another order than in the writing engine, or a rule base from another
    /// version of the engine).
    SymbolMismatch { index: usize },
    /// The start-up template (`initial-fact`) differs.
    TemplateMismatch,
    /// The rule base calls a host function the engine has not registered.
    MissingExternal { name: &'static str },
    /// A pool of the engine is too small for the rule base.
    Capacity(CapacityError),
    /// Rebuilding the start-up matches failed (the engine was cleared again).
    Eval(EvalError),
}

impl From<CapacityError> for CompiledError {
    fn from(c: CapacityError) -> Self {
        CompiledError::Capacity(c)
    }
}

impl fmt::Display for CompiledError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompiledError::NotFresh => write!(
                f,
                "a compiled rule base loads into an engine without constructs only"
            ),
            CompiledError::SymbolMismatch { index } => write!(
                f,
                "symbol {index} of the compiled rule base differs from the engine's \
                 (host functions registered in another order?)"
            ),
            CompiledError::TemplateMismatch => {
                write!(f, "the compiled rule base's initial-fact template differs")
            }
            CompiledError::MissingExternal { name } => write!(
                f,
                "the compiled rule base calls host function {name}, which is not registered"
            ),
            CompiledError::Capacity(c) => write!(f, "{c}"),
            CompiledError::Eval(e) => write!(f, "{e}"),
        }
    }
}

impl<S: Storage> Engine<S> {
    /// Loads a rule base compiled ahead of time (see [`crate::compiled`]) into this
    /// engine, which must hold no constructs yet (fresh, or after `clear`; host
    /// functions the rule base calls registered). Afterwards the engine is as after
    /// loading the rule base's files, with `(initial-fact)` as f-0; `reset` asserts
    /// its deffacts.
    pub fn load_compiled(
        &mut self,
        host: &mut dyn Host,
        base: &RuleBase,
    ) -> Result<(), CompiledError> {
        let mut cx = self.core(host);
        cx.load_compiled(base)
    }
}

impl Core<'_> {
    /// See [`Engine::load_compiled`].
    pub fn load_compiled(&mut self, base: &RuleBase) -> Result<(), CompiledError> {
        self.check_loadable(base)?;
        #[cfg(feature = "in-place")]
        self.read_symbols_in_place(base);
        #[cfg(not(feature = "in-place"))]
        {
            let cp = self.checkpoint();
            if let Err(e) = self.intern_base_symbols(base) {
                self.syms().truncate(cp.nsyms, cp.sym_bytes);
                return Err(e);
            }
        }
        self.copy_network(base);
        let watch = self.st.mode.watch;
        self.st.mode.watch = 0;
        let r = self.rebuild_working_memory(base);
        self.st.mode.watch = watch;
        if let Err(e) = r {
            // back to a fresh engine (host functions stay)
            let _ = self.clear();
            return Err(CompiledError::Eval(e));
        }
        // each rule took a time tag when its text was defined, after initial-fact
        // (`builtins::tools`)
        #[cfg(feature = "extras")]
        {
            let nrules = self.st.pools.nrules;
            let disjuncts = (0..nrules)
                .filter(|&r| self.rules[r as usize].next_disjunct != crate::value::NONE)
                .count() as u32;
            let next = self.st.facts.next_fact_num;
            self.st
                .timetags
                .rules_defined(next, u32::from(nrules) - disjuncts);
        }
        Ok(())
    }

    /// Everything that can refuse the rule base, checked before anything changes.
    fn check_loadable(&mut self, base: &RuleBase) -> Result<(), CompiledError> {
        let st = &self.st;
        if st.pools.nrules != 0
            || st.pools.ntemplates != 1
            || st.pools.njoins != 1
            || st.pools.nalpha != 0
            || st.pools.nfuncs != 0
            || st.pools.nglobals != 0
            || st.pools.ndeffacts != 0
            || st.mode.firing
            || st.mode.defining
        {
            return Err(CompiledError::NotFresh);
        }
        #[cfg(feature = "modules")]
        if st.modules.nmodules > 1
            || st.modules.nports > 0
            || st.modules.current != crate::module::MAIN
        {
            return Err(CompiledError::NotFresh);
        }
        match (base.templates.first(), base.joins.first()) {
            (Some(t), Some(j))
                if t.name == self.templates[0].name && t.implied && j.kind == JoinKind::Root =>
            {
                // the start-up slot must be the base's first too
                if self.st.pools.nslots != 1 || base.slots.is_empty() {
                    return Err(CompiledError::TemplateMismatch);
                }
            }
            _ => return Err(CompiledError::TemplateMismatch),
        }
        let fits = [
            (
                Pool::TemplateMemories,
                base.templates.len(),
                self.tmpl_mems.len(),
            ),
            (
                Pool::AlphaMemories,
                base.alphas.len(),
                self.alpha_mems.len(),
            ),
            (Pool::JoinMemories, base.joins.len(), self.join_mems.len()),
            // (read in place: the arena needs no room for them)
            #[cfg(not(feature = "in-place"))]
            (Pool::Templates, base.templates.len(), self.templates.len()),
            #[cfg(not(feature = "in-place"))]
            (Pool::SlotDefs, base.slots.len(), self.slots.len()),
            #[cfg(not(feature = "in-place"))]
            (Pool::Rules, base.rules.len(), self.rules.len()),
            #[cfg(not(feature = "in-place"))]
            (Pool::AlphaNodes, base.alphas.len(), self.alphas.len()),
            #[cfg(not(feature = "in-place"))]
            (Pool::Joins, base.joins.len(), self.joins.len()),
            #[cfg(not(feature = "in-place"))]
            (Pool::Exprs, base.exprs.len(), self.exprs.len()),
            (Pool::Functions, base.functions.len(), self.funcs.len()),
            (Pool::Globals, base.globals.len(), self.globals.len()),
            (Pool::Deffacts, base.deffacts.len(), self.deffacts.len()),
        ];
        for (pool, need, capacity) in fits {
            #[cfg(feature = "grow")]
            let capacity = {
                self.ensure(pool, need);
                capacity.max(self.capacities()[pool as usize])
            };
            if need > capacity || need >= NONE as usize {
                return Err(cap(pool, capacity).into());
            }
        }
        if base.symbols.len() >= NONE as usize
            || (cfg!(feature = "in-place")
                && (base.symbol_buckets.len() != base.symbols.len()
                    || base.symbol_next.len() != base.symbols.len()))
        {
            return Err(CompiledError::SymbolMismatch {
                index: base.symbols.len(),
            });
        }
        let have = self.st.pools.nsyms as usize;
        if have > base.symbols.len() {
            return Err(CompiledError::SymbolMismatch {
                index: base.symbols.len(),
            });
        }
        for (i, text) in base.symbols[..have].iter().enumerate() {
            if self.sym_text(i as Ix) != *text {
                return Err(CompiledError::SymbolMismatch { index: i });
            }
        }
        for (i, name) in base.externals.iter().enumerate() {
            match self.external_index(name) {
                None => return Err(CompiledError::MissingExternal { name }),
                // nodes read in place keep the writer's numbering: the host registers
                // its functions in the same order
                Some(x) if cfg!(feature = "in-place") && x as usize != i => {
                    return Err(CompiledError::MissingExternal { name })
                }
                Some(_) => {}
            }
        }
        Ok(())
    }

    fn external_index(&mut self, name: &str) -> Option<Ix> {
        let sym = self.find_sym(name)?;
        (0..self.st.pools.nexternals).find(|&x| self.externals[x as usize].name == sym)
    }

    /// The base's symbols read in place (the engine's own, checked to be its first
    /// ones by `check_loadable`, leave the arena, which keeps only those made later).
    #[cfg(feature = "in-place")]
    fn read_symbols_in_place(&mut self, base: &RuleBase) {
        for b in self.sym_buckets.iter_mut() {
            *b = crate::symbols::Head::EMPTY;
        }
        self.st.rom.symbols = crate::symbols::RomSymbols {
            texts: base.symbols,
            buckets: base.symbol_buckets,
            next: base.symbol_next,
        };
        self.st.pools.nsyms = base.symbols.len() as Ix;
        self.st.pools.sym_bytes = 0;
    }

    /// The base's symbols after the engine's: each must get its id in the base.
    #[cfg(not(feature = "in-place"))]
    fn intern_base_symbols(&mut self, base: &RuleBase) -> Result<(), CompiledError> {
        for (i, text) in base
            .symbols
            .iter()
            .enumerate()
            .skip(self.st.pools.nsyms as usize)
        {
            if self.intern(text)? as usize != i {
                return Err(CompiledError::SymbolMismatch { index: i });
            }
        }
        Ok(())
    }

    /// The construct pools from the base; the root join keeps its root token.
    fn copy_network(&mut self, base: &RuleBase) {
        // working memory empties first: f-0 goes (asserted again through the network)
        while self.st.facts.fact_head != NONE {
            let f = self.st.facts.fact_head;
            self.retract_fact(f);
        }
        self.free_pending();
        self.st.facts.values_top = 0;
        self.forget_free_cells();
        self.st.facts.next_fact_num = 0;
        #[cfg(feature = "extras")]
        self.forget_pattern_error();
        let root_token = self.join_mems[JoinId::ROOT].mem;

        for m in self.tmpl_mems.iter_mut() {
            *m = crate::template::TemplateMem::EMPTY;
        }
        #[cfg(feature = "in-place")]
        {
            self.templates.set_rom(base.templates);
            self.slots.set_rom(base.slots);
            self.rules.set_rom(base.rules);
            self.st.rom.templates = base.templates;
            self.st.rom.slots = base.slots;
            self.st.rom.rules = base.rules;
            self.exprs.set_rom(base.exprs);
            self.alphas.set_rom(base.alphas);
            self.joins.set_rom(base.joins);
            self.st.rom.exprs = base.exprs;
            self.st.rom.alphas = base.alphas;
            self.st.rom.joins = base.joins;
        }
        #[cfg(not(feature = "in-place"))]
        {
            self.templates.ram()[..base.templates.len()].copy_from_slice(base.templates);
            self.slots.ram()[..base.slots.len()].copy_from_slice(base.slots);
            self.rules.ram()[..base.rules.len()].copy_from_slice(base.rules);
            self.exprs.ram()[..base.exprs.len()].copy_from_slice(base.exprs);
            self.alphas.ram()[..base.alphas.len()].copy_from_slice(base.alphas);
            self.joins.ram()[..base.joins.len()].copy_from_slice(base.joins);
        }
        self.funcs[..base.functions.len()].copy_from_slice(base.functions);
        self.globals[..base.globals.len()].copy_from_slice(base.globals);
        self.deffacts[..base.deffacts.len()].copy_from_slice(base.deffacts);
        #[cfg(feature = "extras")]
        {
            for (f, &text) in base.function_texts.iter().enumerate() {
                self.set_function_text(f as Ix, text);
            }
            for (g, &text) in base.global_texts.iter().enumerate() {
                self.set_global_text(g as Ix, text);
            }
            for (s, &first) in base.slot_facets.iter().enumerate() {
                self.set_slot_facets(s as Ix, first);
            }
            // (index order unless the base says otherwise)
            for p in 0..base.functions.len() {
                let f = base.function_order.get(p).copied().unwrap_or(p as Ix);
                self.set_function_listed(p as Ix, f);
            }
        }
        self.join_mems[JoinId::ROOT].mem = root_token;
        // host: which tests are staged (`set_stage`; nodes read in place stage all)
        #[cfg(all(feature = "extras", not(feature = "in-place")))]
        for a in 0..base.alphas.len() {
            self.set_stage(a as Ix);
        }
        #[cfg(not(feature = "in-place"))]
        for e in 0..base.exprs.len() {
            let x = self.exprs[e];
            if x.op == Op::Call && x.aux == FnKind::External as u8 {
                // checked by `check_loadable`: every name is registered
                let name = base.externals.get(x.data as usize).copied().unwrap_or("");
                self.exprs[e].data = self.external_index(name).unwrap_or(NONE);
            }
        }

        let n = |len: usize| len as Ix;
        self.st.pools.ntemplates = n(base.templates.len());
        self.st.pools.nslots = n(base.slots.len());
        self.st.pools.nrules = n(base.rules.len());
        self.st.pools.nalpha = n(base.alphas.len());
        self.st.pools.njoins = n(base.joins.len());
        self.st.pools.nexprs = n(base.exprs.len());
        self.st.pools.nfuncs = n(base.functions.len());
        self.st.pools.nglobals = n(base.globals.len());
        self.st.pools.ndeffacts = n(base.deffacts.len());
        for (pool, used) in [
            (Pool::Templates, base.templates.len()),
            (Pool::TemplateMemories, base.templates.len()),
            (Pool::SlotDefs, base.slots.len()),
            (Pool::Rules, base.rules.len()),
            (Pool::AlphaNodes, base.alphas.len()),
            (Pool::AlphaMemories, base.alphas.len()),
            (Pool::Joins, base.joins.len()),
            (Pool::JoinMemories, base.joins.len()),
            (Pool::Exprs, base.exprs.len()),
            (Pool::Functions, base.functions.len()),
            (Pool::Globals, base.globals.len()),
            (Pool::Deffacts, base.deffacts.len()),
        ] {
            self.note_hw(pool, used);
        }
        self.st.pools.trie_ids = base.trie_ids;
        self.st.eval.gensym_next = base.gensym_next;
        self.st.builtin_code = base.code;
        // caches keyed by join or network generation start over
        self.st.net.net_gen = self.st.net.net_gen.wrapping_add(1).max(1);
        self.st.cache.key_plans = [KeyPlan::NONE; KEY_PLANS];
        self.clear_test_plans();
        for j in 0..self.st.pools.njoins {
            let j = JoinId(j);
            self.note_children(j);
            // (in id order: each join after its node's older successors, as parsed)
            #[cfg(feature = "grow")]
            if self.joins[j].alpha != NONE {
                self.note_placing(j, self.joins[j].alpha);
            }
            #[cfg(feature = "wipe")]
            if self.joins[j].rsucc != JoinId::NONE {
                self.st.net.from_right = true;
            }
        }
    }

    /// Globals' values and the start-up matches: f-0 (the parser's engine had it
    /// before the first rule), then the rules that start with `not`, `exists` or
    /// `test` from the root token; their activations in the parser's order.
    fn rebuild_working_memory(&mut self, base: &RuleBase) -> Result<(), EvalError> {
        for (g, global) in base.globals.iter().enumerate() {
            // values the writer could not keep (multifields) are evaluated again
            if matches!(global.value, Value::Void) && global.init != NONE {
                let v = self.eval(global.init)?;
                self.set_global(g as Ix, v)?;
            }
        }
        self.st.frame.sp = 0;
        self.st.frame.scratch_top = 0;
        // a deffacts named `initial-fact` replaced CLIPS's own when it was parsed:
        // `reset` asserts `(initial-fact)` only if it lists it
        if base
            .deffacts
            .iter()
            .any(|d| d.name == crate::builtins::SYM_INITIAL_FACT)
        {
            self.st.mode.initial_deffacts = false;
        }
        self.assert_initial_fact()?;
        // as the parser primed them: rule by rule, each chain from its end upwards (a
        // subnetwork after the join taking it), a shared join with its first rule; the
        // root token's list of derived tokens then has the parser's order, which is
        // the order `reset` removes their activations in
        let root_token = self.join_mems[JoinId::ROOT].mem;
        for r in 0..self.st.pools.nrules {
            if self.rules[r as usize].deleted {
                continue;
            }
            let terminal = self.rules[r as usize].terminal;
            // (the walk counts `at` down as it passes joins: each call starts afresh)
            let mut k = 0;
            loop {
                let mut at = k;
                let Some(j) = self.nth_root_start(terminal, JoinId::ROOT, &mut at) else {
                    break;
                };
                if !self.earlier_rule_uses(r, j) {
                    self.left_activate(j, root_token)?;
                }
                k += 1;
            }
        }
        self.order_activations_as_parsed();
        Ok(())
    }

    /// The `*at`-th join (in the parser's priming walk: from `from` up to `stop`, a
    /// subnetwork after the join taking it) that starts at the root and is not a
    /// positive join (those meet f-0 from the right). `*at` counts down the joins
    /// passed over; `None` once the walk holds no more.
    fn nth_root_start(&self, mut from: JoinId, stop: JoinId, at: &mut usize) -> Option<JoinId> {
        while from != JoinId::NONE && from != JoinId::ROOT && from != stop {
            let jn = &self.joins[from];
            if jn.parent == JoinId::ROOT && jn.kind != JoinKind::Positive {
                if *at == 0 {
                    return Some(from);
                }
                *at -= 1;
            }
            if jn.rjoin != JoinId::NONE {
                if let Some(j) = self.nth_root_start(jn.rjoin, jn.parent, at) {
                    return Some(j);
                }
            }
            from = jn.parent;
        }
        None
    }

    /// Whether a rule defined before rule `r` holds join `j` (it was primed then).
    fn earlier_rule_uses(&self, r: Ix, j: JoinId) -> bool {
        (0..r).any(|e| {
            let rule = &self.rules[e as usize];
            !rule.deleted && self.chain_holds(rule.terminal, JoinId::ROOT, j)
        })
    }

    /// Whether the chain from `from` up to `stop`, or a subnetwork it takes, holds `j`.
    fn chain_holds(&self, mut from: JoinId, stop: JoinId, j: JoinId) -> bool {
        while from != JoinId::NONE && from != JoinId::ROOT && from != stop {
            let jn = &self.joins[from];
            if from == j || (jn.rjoin != JoinId::NONE && self.chain_holds(jn.rjoin, jn.parent, j)) {
                return true;
            }
            from = jn.parent;
        }
        false
    }

    /// The parser primed each rule as it was defined, so a rule's start-up
    /// activations are newer than those of every rule defined before it; the network
    /// made them in its own order. Puts them in definition order (by rule, then as
    /// made), each taking the next creation number, and back on the agenda in that
    /// order (the newest goes first among equal saliences). Each partial match's list
    /// of activations (rules sharing a terminal join: those with no conditions) is
    /// made again in that order too, newest first as the parser left it: `reset`
    /// takes them back in its order.
    fn order_activations_as_parsed(&mut self) {
        let mut old = self.st.agenda.agenda_head;
        let mut seq = u32::MAX;
        let mut a = old;
        while a != NONE {
            seq = seq.min(self.acts[a as usize].seq);
            self.tokens[self.acts[a as usize].token].extra = NONE;
            a = self.acts[a as usize].next;
        }
        self.st.agenda.agenda_head = NONE;
        self.st.agenda.agenda_len = 0;
        #[cfg(feature = "host-speedups")]
        self.st.agenda.groups.reset();
        #[cfg(all(feature = "modules", feature = "host-speedups"))]
        self.focus_cache_clear();
        let key = |x: &crate::rule::Activation| (x.rule, x.seq);
        while old != NONE {
            let mut best = old;
            let mut a = self.acts[old as usize].next;
            while a != NONE {
                if key(&self.acts[a as usize]) < key(&self.acts[best as usize]) {
                    best = a;
                }
                a = self.acts[a as usize].next;
            }
            let (prev, next) = (self.acts[best as usize].prev, self.acts[best as usize].next);
            if prev != NONE {
                self.acts[prev as usize].next = next;
            } else {
                old = next;
            }
            if next != NONE {
                self.acts[next as usize].prev = prev;
            }
            self.acts[best as usize].seq = seq;
            seq = seq.wrapping_add(1);
            let t = self.acts[best as usize].token;
            self.acts[best as usize].next_of_token = self.tokens[t].extra;
            self.tokens[t].extra = best;
            self.agenda_insert(best);
        }
    }
}
