//! The public engine API (see `/work/brief/engine-api.md`).

use crate::builtins::ANY;
use crate::config::Storage;
use crate::engine::{cap, Engine, ExternalEntry, Stats};
use crate::error::{EngineError, EvalError, EvalErrorKind, LoadError, Pool};
use crate::handle::TokenId;
use crate::host::Host;
use crate::host_fn::ExternalFn;
use crate::parser::{Item, Parser};
use crate::value::Ix;
use crate::value::{Value, ValueRef, NONE};

/// Construct-pool usage (see `Engine::usage`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Usage {
    pub symbols: Ix,
    pub templates: Ix,
    pub slot_defs: Ix,
    pub rules: Ix,
    pub alpha_nodes: Ix,
    pub joins: Ix,
    pub exprs: Ix,
    pub functions: Ix,
    pub globals: Ix,
    pub deffacts: Ix,
    /// Tokens (alpha and partial matches) currently allocated.
    pub tokens: Ix,
}

/// A fact's index (`f-N`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FactId(pub u32);

macro_rules! engine_impl {
    ($($body:tt)*) => {
        impl<S: Storage> Engine<S> { $($body)* }
    };
}

engine_impl! {
    /// Loads constructs from text. Constructs before an error stay defined; the bad
    /// one leaves nothing behind. Returns the number of constructs defined.
    pub fn load_str(&mut self, host: &mut dyn Host, _source_name: &str, text: &str) -> Result<usize, LoadError> {
        let mut cx = self.core(host);
        cx.load_text(text, false)
    }

    /// Whether rules, deftemplates and deffacts loaded from now on keep their source text
    /// for `ppdefrule`, `ppdeftemplate` and `ppdeffacts` (default: yes, as CLIPS does).
    /// Without it those print nothing for them, and the
    /// symbol table does not hold a second copy of the rule base's text: a robot image
    /// that never lists its rules saves that RAM (CLIPS's run-time images drop their
    /// pretty-print forms the same way).
    pub fn set_pretty_print_forms(&mut self, keep: bool) {
        self.st.mode.keep_pp_forms = keep;
    }

    /// How deep function calls may nest (default [`crate::eval::MAX_EVAL_DEPTH`] calls,
    /// no stack check): a host running the engine on a thread with a large stack lets
    /// recursions go as deep as CLIPS's (thousands of levels), with `stack_bytes` of
    /// that stack (less a margin for one level's frames) as a second bound.
    #[cfg(feature = "grow")]
    pub fn set_depth_limits(&mut self, calls: u16, stack_bytes: usize) {
        self.st.eval.limits = crate::eval::DepthLimits::with(calls, stack_bytes);
    }

    /// Polls the host (`Host::interrupt`) at each deffunction call too, not only at
    /// each loop iteration and rule firing: a host that stops runaway programs then
    /// stops a recursion that branches (`fib` of 45: billions of calls, no loop). Off
    /// by default (a host whose `interrupt` never stops saves the call); `clear` keeps
    /// it.
    #[cfg(feature = "extras")]
    pub fn set_poll_calls(&mut self, on: bool) {
        self.st.profile.set_poll_calls(on);
    }

    /// Parses and evaluates one expression/command. A multifield result points into
    /// scratch and is valid until the next call.
    pub fn eval_str(&mut self, host: &mut dyn Host, command: &str) -> Result<Value, EvalError> {
        let mut cx = self.core(host);
        cx.st.frame.scratch_top = 0;
        cx.st.frame.sp = 0;
        cx.st.frame.bp = 0;
        let before = cx.st.pools.nexprs;
        cx.st.eval.command_base = before;
        let cp = cx.checkpoint();
        let mut p = Parser::new(&mut cx, command);
        let item = p.next_item();
        let nlocals = p.nlocals;
        let r = match item {
            // a frame for the command's loop and query variables, as the prompt makes
            Ok(Item::Command(e)) => match (0..nlocals).try_for_each(|_| cx.push_value(Value::Void)) {
                Ok(()) => cx.eval(e),
                Err(full) => Err(full.into()),
            },
            Ok(Item::Construct) => Ok(Value::Void),
            Ok(Item::End) => Ok(Value::Void),
            Err(_) => Err(EvalError::message(crate::error::Message::SyntaxError)),
        };
        let now = cx.checkpoint();
        if now.nrules == cp.nrules && now.nfuncs == cp.nfuncs && now.ntemplates == cp.ntemplates && now.nglobals == cp.nglobals && now.ndeffacts == cp.ndeffacts {
            cx.st.pools.nexprs = before;
        }
        cx.st.frame.sp = 0;
        r
    }

    /// Executes one complete command text as the CLIPS prompt does (prints results
    /// and errors to the host). Returns false once `(exit)` was called.
    pub fn exec_command(&mut self, host: &mut dyn Host, text: &str, source: &str) -> bool {
        let mut cx = self.core(host);
        cx.exec_command(text, source);
        !cx.st.mode.exit
    }

    /// Runs text as CLIPS's batch mode (`clips -f`): prompts and echo when `echo`.
    /// Returns false once `(exit)` was called.
    pub fn batch_str(&mut self, host: &mut dyn Host, text: &str, echo: bool) -> bool {
        self.batch_file(host, "batch", text, echo)
    }

    /// `batch_str` with the file name used in error positions (`--> FILE:LINE:COL`).
    pub fn batch_file(&mut self, host: &mut dyn Host, source_name: &str, text: &str, echo: bool) -> bool {
        let mut cx = self.core(host);
        let _ = cx.batch_text_named(text, echo, source_name);
        !cx.st.mode.exit
    }

    /// Runs a command file as CLIPS's batch mode does (`clips -f FILE`): prompts, echo
    /// and results, the file streamed through [`Host::read_file_at`]. As in CLIPS,
    /// `read`, `readline` and `get-char` from `stdin` in its commands take the file's
    /// next lines (then the host's standard input after its end). Returns false once
    /// `(exit)` ran.
    pub fn batch_path(&mut self, host: &mut dyn Host, path: &str) -> bool {
        let mut cx = self.core(host);
        let _ = cx.batch_file_stream(path, true);
        !cx.st.mode.exit
    }

    /// A batch file run last (`batch_path`, or `batch` from a command) ended inside a
    /// command: its file and the offset where that command starts. As in CLIPS the
    /// command goes on in what is read next (the prompt's input); taken once.
    #[cfg(feature = "parser")]
    pub fn take_batch_carry(&mut self) -> Option<(&str, u64)> {
        let carry = &mut self.st.io.carry;
        if !carry.active {
            return None;
        }
        carry.active = false;
        Some((carry.path.as_str(), carry.offset))
    }

    /// `batch*` of a text: runs its commands without prompts, echo or results (what
    /// `clips -f2 FILE` does). Returns false once `(exit)` ran.
    pub fn batch_file_quiet(&mut self, host: &mut dyn Host, source_name: &str, text: &str) -> bool {
        let mut cx = self.core(host);
        let saved = cx.st.io.quiet_results;
        cx.st.io.quiet_results = true;
        let _ = cx.batch_text_named(text, false, source_name);
        cx.st.io.quiet_results = saved;
        !cx.st.mode.exit
    }

    /// Runs a file a `batch` command left for the command loop (a `batch` inside
    /// `batch*` or `-f2`). Returns false once `(exit)` ran.
    pub fn run_pending_batch(&mut self, host: &mut dyn Host) -> bool {
        let mut cx = self.core(host);
        cx.run_pending_batch();
        !cx.st.mode.exit
    }

    pub fn exited(&self) -> bool {
        self.st.mode.exit
    }

    /// The status `(exit N)` asked for (0 for a bare `(exit)`).
    pub fn exit_status(&self) -> i32 {
        self.st.mode.exit_status
    }

    /// Whether a pool ran out or the input ended inside a construct since the engine
    /// was made: the command line exits non-zero then (CLIPS exits 0).
    pub fn hit_unrecoverable(&self) -> bool {
        self.st.mode.unrecoverable
    }

    pub fn reset(&mut self, host: &mut dyn Host) -> Result<(), EngineError> {
        let mut cx = self.core(host);
        cx.reset().map_err(EngineError::from)
    }

    pub fn clear(&mut self, host: &mut dyn Host) -> Result<(), EngineError> {
        let mut cx = self.core(host);
        cx.clear().map_err(EngineError::from)
    }

    /// Fires up to `limit` activations (all when None); returns how many fired.
    pub fn run(&mut self, host: &mut dyn Host, limit: Option<u32>) -> Result<u32, EngineError> {
        let mut cx = self.core(host);
        let r = cx.run(limit.map(|l| l as i64).unwrap_or(-1));
        cx.st.frame.scratch_top = 0;
        match r {
            Err(e) if e.kind() == EvalErrorKind::Exit => Ok(0),
            r => r.map_err(EngineError::from),
        }
    }

    /// Asserts one fact written in CLIPS syntax, e.g. `(pos (x 1) (y 2))`.
    pub fn assert_str(&mut self, host: &mut dyn Host, fact: &str) -> Result<FactId, EngineError> {
        let mut cx = self.core(host);
        let before = cx.st.pools.nexprs;
        let cp = cx.checkpoint();
        let mut p = Parser::new(&mut cx, fact);
        p.scope = crate::parser::Scope::Lhs;
        let spec = p.expect_lparen("'(' starting a fact").and_then(|_| p.fact_spec());
        let spec = match spec {
            Ok(s) => s,
            Err(e) => {
                cx.rollback(cp);
                return Err(EngineError::Load(e));
            }
        };
        // the text's values may be calls (and the template's defaults run some): what
        // they did stays, as in CLIPS, and may use what the text created
        let parsed = cx.checkpoint();
        let num = cx.st.facts.next_fact_num;
        let calls =
            (before..parsed.nexprs).any(|x| cx.exprs[x as usize].op == crate::expr::Op::Call);
        let r = cx.assert_spec(spec);
        let now = cx.checkpoint();
        let built = now.nrules != parsed.nrules
            || now.nfuncs != parsed.nfuncs
            || now.ntemplates != parsed.ntemplates
            || now.nglobals != parsed.nglobals
            || now.ndeffacts != parsed.ndeffacts;
        // the fact's expressions go, unless a construct `build` made sits above them
        if !built {
            cx.st.pools.nexprs = before;
        }
        cx.st.frame.scratch_top = 0;
        cx.st.frame.sp = 0;
        match r {
            Ok(Some(f)) => Ok(FactId(cx.facts[f as usize].num)),
            Ok(None) => Err(EngineError::Duplicate),
            Err(e) => {
                // leave no trace: symbols (and an implied template) the failed
                // fact's text created go too, if nothing ran that could keep them (a
                // fact of that template, a global bound to a symbol, a construct)
                if !calls && now == parsed && cx.st.facts.next_fact_num == num {
                    cx.rollback(cp);
                }
                Err(e.into())
            }
        }
    }

    pub fn retract(&mut self, host: &mut dyn Host, id: FactId) -> Result<(), EngineError> {
        let mut cx = self.core(host);
        match cx.find_fact(id.0) {
            Some(f) => {
                cx.retract_fact(f);
                // The fact is gone either way (CLIPS's retract cannot fail), but
                // matches it unblocked that found no room are owed, not lost: say so.
                // They are built once room is made; until then assert and run fail.
                cx.pay_owed().map_err(EngineError::from)
            }
            None => Err(EngineError::NoSuchFact(id.0)),
        }
    }

    /// Registers a host function callable from CLIPS code as `(name args...)`.
    /// `max_args` None means unbounded. Registering a name again replaces it.
    pub fn register_function(&mut self, name: &str, min_args: u8, max_args: Option<u8>, f: ExternalFn) -> Result<(), EngineError> {
        let mut host = crate::host::NullHost;
        let mut cx = self.core(&mut host);
        let sym = cx.intern(name)?;
        let existing = (0..cx.st.pools.nexternals).find(|&x| cx.externals[x as usize].name == sym);
        let i = match existing {
            Some(i) => i as usize,
            None => {
                let n = cx.st.pools.nexternals as usize;
                #[cfg(feature = "grow")]
                cx.ensure(Pool::ExternalFns, n + 1);
                if n >= cx.externals.len() {
                    return Err(cap(Pool::ExternalFns, cx.externals.len()).into());
                }
                cx.st.pools.nexternals += 1;
                cx.note_hw(Pool::ExternalFns, n + 1);
                n
            }
        };
        cx.externals[i] = ExternalEntry { name: sym, min: min_args, max: max_args.unwrap_or(ANY), f: Some(f) };
        cx.st.pools.ext_syms = cx.st.pools.nsyms;
        Ok(())
    }

    /// Live facts in index order.
    pub fn facts(&self) -> impl Iterator<Item = FactId> + '_ {
        self.fact_view().ids()
    }

    /// Live facts of template `name` in index order (the same as filtering `facts()` by
    /// `fact_template_name`, in one walk of the facts instead of one per fact).
    pub fn facts_of<'s>(&'s self, name: &'s str) -> impl Iterator<Item = FactId> + 's {
        self.fact_view().ids_of(name)
    }

    pub fn fact_template_name(&self, id: FactId) -> Option<&str> {
        self.fact_view().template_name(id)
    }

    /// A slot of a fact (`implied` for ordered facts). Multislots read as `Multi(len)`;
    /// elements via `fact_multislot_item`.
    pub fn fact_slot(&self, id: FactId, slot: &str) -> Option<ValueRef<'_>> {
        self.fact_view().slot(id, slot)
    }

    pub fn fact_multislot_item(&self, id: FactId, slot: &str, i: usize) -> Option<ValueRef<'_>> {
        self.fact_view().multislot_item(id, slot, i)
    }

    /// High-water marks and capacities of every pool.
    pub fn stats(&self) -> Stats {
        let mut s = self.st.pools.hw;
        let caps = self.storage_capacities();
        for (i, c) in caps.iter().enumerate() {
            s.capacity[i] = *c as u32;
        }
        s
    }

    /// Whether matches a retract unblocked wait for room (they are *owed*): until they
    /// are built, assert and modify build them first and `run` fires nothing.
    pub fn owes(&self) -> bool {
        self.st.net.owed != TokenId::NONE
    }

    /// Entries in use of the append-only pools (constructs and what they built):
    /// a construct that fails to load leaves these unchanged.
    pub fn usage(&self) -> Usage {
        Usage {
            symbols: self.st.pools.nsyms,
            templates: self.st.pools.ntemplates,
            slot_defs: self.st.pools.nslots,
            rules: self.st.pools.nrules,
            alpha_nodes: self.st.pools.nalpha,
            joins: self.st.pools.njoins,
            exprs: self.st.pools.nexprs,
            functions: self.st.pools.nfuncs,
            globals: self.st.pools.nglobals,
            deffacts: self.st.pools.ndeffacts,
            tokens: self.st.pools.tokens_live,
        }
    }

    /// Calls `f(rule, salience, basis)` for each activation in agenda order; `basis`
    /// holds each pattern CE's fact index (None for not/exists/test CEs).
    pub fn for_each_activation(&self, mut f: impl FnMut(&str, i32, &[Option<u32>])) {
        let mut a = self.st.agenda.agenda_head;
        while a != NONE {
            let act = self.act_at(a);
            let mut basis = [None; crate::rete::MAX_PATTERNS];
            let n = self.basis_of(act.token, &mut basis);
            let rule = self.rule_at(act.rule);
            f(self.sym_str(rule.name), act.salience, &basis[..n]);
            a = act.next;
        }
    }

    /// Number of live facts and pending activations.
    pub fn counts(&self) -> (usize, usize) {
        (self.facts().count(), {
            let mut n = 0;
            let mut a = self.st.agenda.agenda_head;
            while a != NONE {
                n += 1;
                a = self.act_at(a).next;
            }
            n
        })
    }
}
