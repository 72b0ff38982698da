//! The engine: its scalar state and its pools' storage (sized by named capacities, see
//! [`crate::config`]), and `Core`, the non-generic view of that storage that all
//! algorithms run on (one copy of the code for every size).
//!
//! The scalar state ([`State`]) is one small struct per subsystem: pool counters
//! ([`PoolCounts`]), the fact list ([`FactList`]), the agenda ([`AgendaState`]),
//! matching in progress ([`MatchState`]), the evaluator's registers ([`Frame`]) and
//! the rest of its state ([`EvalState`]), batch and prompt I/O ([`BatchIo`]), CLIPS
//! mode flags ([`Mode`]), caches ([`Caches`]) and the random generator ([`Random`]).

pub use crate::config::{entry_bytes, Core};
use crate::config::{HostStorage, SmallStorage, Storage};
use crate::error::{CapacityError, Pool};
use crate::expr::{Expr, Op};
use crate::host::Host;
use crate::rete::{PatBinding, MAX_PATTERNS};
use crate::rule::{Activation, Rule};
use crate::symbols::Symbols;

use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use crate::value::{SymId, Value, NONE};

/// `query_hold`'s mark of a command at the prompt (queries count below it).
pub const COMMAND_HOLD: u16 = 0x8000;

/// A host-registered function.
#[derive(Clone, Copy)]
pub struct ExternalEntry {
    pub name: SymId,
    pub min: u8,
    /// `u8::MAX`: no upper bound.
    pub max: u8,
    pub f: Option<crate::host_fn::ExternalFn>,
}

impl ExternalEntry {
    pub const EMPTY: ExternalEntry = ExternalEntry {
        name: 0,
        min: 0,
        max: 0,
        f: None,
    };
}

/// Watch flags.
pub mod watch {
    pub const FACTS: u8 = 1;
    pub const RULES: u8 = 2;
    pub const ACTIVATIONS: u8 = 4;
    pub const COMPILATIONS: u8 = 8;
    pub const STATISTICS: u8 = 16;
    /// `(watch focus)` (feature `modules`).
    pub const FOCUS: u8 = 32;
    /// `(watch globals)`: `:== ?*x* ==> new <== old` (feature `extras`).
    pub const GLOBALS: u8 = 64;
    /// `(watch deffunctions)`: `DFN >> f ED:1 (args)` (feature `extras`).
    pub const DEFFUNCTIONS: u8 = 128;

    /// COOL's watch items (`Mode::cool_watch`, feature `extras`).
    pub mod cool {
        pub const INSTANCES: u8 = 1;
        pub const SLOTS: u8 = 2;
        pub const MESSAGES: u8 = 4;
        pub const MESSAGE_HANDLERS: u8 = 8;
        pub const GENERIC_FUNCTIONS: u8 = 16;
        pub const METHODS: u8 = 32;
    }
}

/// High-water marks (entries in use at most) of every pool.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub used: [u32; Pool::COUNT],
    pub capacity: [u32; Pool::COUNT],
}

impl Stats {
    pub const fn new() -> Stats {
        Stats {
            used: [0; Pool::COUNT],
            capacity: [0; Pool::COUNT],
        }
    }
    pub fn get(&self, pool: Pool) -> (u32, u32) {
        (self.used[pool as usize], self.capacity[pool as usize])
    }

    /// Bytes the pool's storage takes in the engine (capacity times entry size).
    pub fn bytes(&self, pool: Pool) -> usize {
        self.capacity[pool as usize] as usize * entry_bytes(pool)
    }
}

/// Marks of the append-only pools, to undo a construct that failed halfway.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Checkpoint {
    pub nsyms: Ix,
    pub sym_bytes: Ix,
    pub ntemplates: Ix,
    pub nslots: Ix,
    pub nrules: Ix,
    pub nalpha: Ix,
    pub njoins: Ix,
    pub nexprs: Ix,
    pub nfuncs: Ix,
    pub nglobals: Ix,
    pub ndeffacts: Ix,
}

/// Entries in use, free lists and high-water marks of the pools.
pub struct PoolCounts {
    pub nsyms: Ix,
    pub sym_bytes: Ix,
    pub ntemplates: Ix,
    pub nslots: Ix,
    pub nrules: Ix,
    pub nalpha: Ix,
    pub njoins: Ix,
    pub nexprs: Ix,
    pub nfuncs: Ix,
    pub nglobals: Ix,
    pub ndeffacts: Ix,
    pub nexternals: Ix,
    /// Symbols to keep across `clear` (fixed ones and external function names).
    pub ext_syms: Ix,
    /// Ids of pattern-network nodes (see `AlphaNode::key`).
    pub trie_ids: Ix,
    pub fact_free: Ix,
    pub token_free: TokenId,
    pub act_free: Ix,
    pub facts_used: Ix,
    pub tokens_used: Ix,
    /// Tokens currently allocated (for the high-water mark).
    pub tokens_live: Ix,
    pub acts_used: Ix,
    pub hw: Stats,
}

impl PoolCounts {
    pub const fn new() -> PoolCounts {
        PoolCounts {
            nsyms: 0,
            sym_bytes: 0,
            ntemplates: 0,
            nslots: 0,
            nrules: 0,
            nalpha: 0,
            njoins: 0,
            nexprs: 0,
            nfuncs: 0,
            nglobals: 0,
            ndeffacts: 0,
            nexternals: 0,
            ext_syms: 0,
            trie_ids: 0,
            fact_free: NONE,
            token_free: TokenId::NONE,
            act_free: NONE,
            facts_used: 0,
            tokens_used: 0,
            tokens_live: 0,
            acts_used: 0,
            hw: Stats::new(),
        }
    }
}

/// The live facts: their list, numbering and value arena top.
pub struct FactList {
    /// Top of the fact value arena.
    pub values_top: Ix,
    /// Live facts in creation (= number) order.
    pub fact_head: Ix,
    /// How many facts that list holds (`watch statistics` samples it per firing).
    pub facts_live: Ix,
    pub fact_tail: Ix,
    /// Facts retracted during the current firing, freed when it ends.
    pub pending: Ix,
    pub next_fact_num: u32,
    /// Template of `(initial-fact)`.
    pub initial_tmpl: Ix,
    /// A modify's old fact while its new one is asserted, for a deferral to keep.
    pub modify_old: Option<(Ix, crate::fact::Fact)>,
}

impl FactList {
    pub const fn new() -> FactList {
        FactList {
            values_top: 0,
            fact_head: NONE,
            facts_live: 0,
            fact_tail: NONE,
            pending: NONE,
            next_fact_num: 0,
            initial_tmpl: NONE,
            modify_old: None,
        }
    }
}

/// The agenda: its list and activation numbering, the journal of a failed modify.
pub struct AgendaState {
    pub agenda_head: Ix,
    /// Activations on the agenda: `(watch statistics)` samples it after every firing,
    /// which must not walk the list.
    pub agenda_len: Ix,
    pub act_seq: u32,
    /// Activations the retract of a modify removed, to put back in place if the
    /// modify fails.
    pub act_journal: crate::agenda::ActJournal,
    /// Rule being fired (for messages), NONE outside a firing.
    pub current_rule: Ix,
    /// The conflict resolution strategy (`strategy::Strategy` as u8).
    pub strategy: u8,
    /// Host: where each salience's activations lie on the agenda (see `agenda`).
    #[cfg(feature = "host-speedups")]
    pub groups: crate::agenda::SalienceGroups,
}

impl AgendaState {
    pub const fn new() -> AgendaState {
        AgendaState {
            agenda_head: NONE,
            agenda_len: 0,
            act_seq: 0,
            act_journal: crate::agenda::ActJournal::EMPTY,
            current_rule: NONE,
            strategy: 0,
            #[cfg(feature = "host-speedups")]
            groups: crate::agenda::SalienceGroups::EMPTY,
        }
    }
}

/// Matching in progress: pattern bindings, deferred and owed propagation.
pub struct MatchState {
    /// Not outputs a removal unblocked on a full token pool, waiting for their
    /// propagation (see `Core::pay_owed`); chained through the tokens.
    pub owed: TokenId,
    /// Putting a fact back (a failed modify's old fact): a not output that becomes
    /// active is owed instead of passed on, and paid once the fact is complete. A
    /// fact's assert may pass a `not` on and block it again with a later pattern of
    /// its own; re-asserting into a full pool must not need that room for a moment.
    pub defer_nots: bool,
    /// The fact a retract is taking out of the network (NONE otherwise): what a not
    /// it unblocks passes on never meets it, as in CLIPS (see `Core::unblock`).
    pub dying: Ix,
    /// Whether `dying`'s alpha matches not removed yet are out of their memories.
    pub dying_hidden: bool,
    /// Not outputs a modify's retract unblocked (see `Core::owe_unblocked`).
    pub unblocked: crate::rete::UnblockLog,
    /// Watch traces of an assert/modify held back until it cannot be undone.
    pub hold: crate::hold::TraceHold,
    /// The test `eval_tests` last stopped at with an error (names the field in
    /// `[FACTMCH1]`).
    pub failed_test: Ix,
    /// A pattern test failed with an error during the current assert.
    pub pattern_error: bool,
    /// Host: the fact (and its number) whose test in CLIPS's pattern-network node
    /// `err_alpha`'s path level `err_level` failed with an error: every alpha node
    /// sharing that node is done with the fact, as CLIPS tests a shared node once
    /// (`rete::alpha`, `pattern_error_prunes`). `err_fact` NONE: none.
    #[cfg(feature = "extras")]
    pub err_fact: Ix,
    #[cfg(feature = "extras")]
    pub err_num: u32,
    #[cfg(feature = "extras")]
    pub err_alpha: Ix,
    #[cfg(feature = "extras")]
    pub err_level: u8,
    /// Host: the fact passed the tests up to `err_level` instead (a node whose
    /// multislot length failed tested them, `rete::alpha` `tests_before_length`).
    #[cfg(feature = "extras")]
    pub err_pass: bool,
    /// Pattern or join tests running (nested): CLIPS is pattern-matching, and refuses
    /// to assert, retract, modify or duplicate facts, to build or remove rules, to
    /// `clear` or to `reset` until they are done (the checks sit in those builtins and
    /// in `Core::assert_spec`).
    pub matching: u16,
    /// Host: the `matching` level up to which facts may change all the same: 1 while
    /// `reset` primes the joins fed by no pattern (CLIPS runs a first `test`, and
    /// one after a first `not`/`exists`, outside its join operations then), and
    /// while a new rule's joins fed by older ones are primed (its incremental reset).
    #[cfg(feature = "extras")]
    pub matching_free: u16,
    /// Host: the same for retracts (and modifies): only `reset`'s priming raises it
    /// (to `matching_free`'s level: it is never above `matching_free`).
    #[cfg(feature = "extras")]
    pub retract_free: u16,
    /// Host: while a new rule is primed (CLIPS's incremental reset), its first alpha
    /// node (NONE otherwise): a fact asserted meanwhile meets only the alpha nodes
    /// from there on, the new rule's (`Core::prime_new_rules`).
    #[cfg(feature = "extras")]
    pub ir_alpha: Ix,
    /// Network generation: changes whenever joins are added or unlinked (cached
    /// per-template facts about the network, `rete::defer`, are renewed then).
    pub net_gen: u32,
    /// Whether a join fed from the right (a `not`/`exists` over a subnetwork) may
    /// have been built since the last `clear` (`rete::wipe`: without one, every
    /// subtree may be wiped whole, with no walk per join).
    #[cfg(feature = "wipe")]
    pub from_right: bool,
    /// Host: what the constant-test discrimination index was built for (`rete::discrim`).
    #[cfg(feature = "host-speedups")]
    pub disc: crate::rete::DiscState,
    /// The fact whose propagation waits for a retract to go first (`rete::defer`).
    pub deferred: crate::rete::Deferred,
    /// What `printout` wrote while a propagation waited (`rete::defer`).
    #[cfg(feature = "defer")]
    pub held_print: crate::rete::HeldPrint,
    /// Host: facts whose propagation waits before `deferred`'s, oldest first, and
    /// how much held `printout` text each found (`rete::defer`).
    #[cfg(feature = "defer")]
    pub queued: [crate::rete::Queued; crate::rete::QUEUED_MAX],
    #[cfg(feature = "defer")]
    pub nqueued: u8,
    #[cfg(feature = "defer")]
    pub deferred_held: u16,
    /// The right-hand-side action being evaluated at the top level (NONE outside a
    /// firing), and whether the assert it makes now may be deferred.
    pub top_action: Ix,
    pub defer_next: bool,
    /// Host: `worth_past_printouts`'s last walk (`rete::ScanRun`).
    #[cfg(all(feature = "defer", feature = "host-speedups"))]
    pub scan: crate::rete::ScanRun,
    /// Pattern bindings for network tests (`lhs`) and the firing rule (`rhs`).
    pub lhs_pm: [PatBinding; MAX_PATTERNS],
    /// The partial match whose whole ancestry `lhs_pm` holds (NONE if none): then
    /// binding it again is free and quick join tests read facts from `lhs_pm`.
    pub lhs_of: TokenId,
    pub rhs_pm: [PatBinding; MAX_PATTERNS],
    pub this_pm: PatBinding,
    pub pm_rhs: bool,
    /// Host: one fact's alpha matches put in CLIPS's order (`rete::mforder`).
    #[cfg(feature = "grow")]
    pub mf: crate::rete::MfOrder,
}

impl MatchState {
    /// Whether facts may not be asserted, retracted or modified now: a pattern or join
    /// test runs (CLIPS is pattern-matching), beyond `matching_free`.
    #[inline(always)]
    pub fn changes_refused(&self) -> bool {
        #[cfg(feature = "extras")]
        return self.matching > self.matching_free;
        #[cfg(not(feature = "extras"))]
        return self.matching > 0;
    }

    /// Whether facts may not be retracted (nor modified) now: as `changes_refused`,
    /// beyond `retract_free`, which a new rule's priming does not raise (its tests
    /// may assert, as in CLIPS; a retract then, which CLIPS lets remove matches but
    /// not add those of the `not`s it unblocks in older rules, is refused here).
    #[inline(always)]
    pub fn retracts_refused(&self) -> bool {
        #[cfg(feature = "extras")]
        return self.matching > self.retract_free;
        #[cfg(not(feature = "extras"))]
        return self.changes_refused();
    }

    pub const fn new() -> MatchState {
        MatchState {
            owed: TokenId::NONE,
            defer_nots: false,
            dying: NONE,
            dying_hidden: false,
            unblocked: crate::rete::UnblockLog::EMPTY,
            hold: crate::hold::TraceHold::EMPTY,
            failed_test: NONE,
            pattern_error: false,
            #[cfg(feature = "extras")]
            err_fact: NONE,
            #[cfg(feature = "extras")]
            err_num: 0,
            #[cfg(feature = "extras")]
            err_alpha: NONE,
            #[cfg(feature = "extras")]
            err_level: 0,
            #[cfg(feature = "extras")]
            err_pass: false,
            matching: 0,
            #[cfg(feature = "extras")]
            matching_free: 0,
            #[cfg(feature = "extras")]
            retract_free: 0,
            #[cfg(feature = "extras")]
            ir_alpha: NONE,
            net_gen: 0,
            #[cfg(feature = "wipe")]
            from_right: false,
            #[cfg(feature = "host-speedups")]
            disc: crate::rete::DiscState::EMPTY,
            deferred: crate::rete::Deferred::NONE,
            #[cfg(feature = "defer")]
            held_print: crate::rete::HeldPrint::EMPTY,
            #[cfg(feature = "defer")]
            queued: [crate::rete::Queued::NONE; crate::rete::QUEUED_MAX],
            #[cfg(feature = "defer")]
            nqueued: 0,
            #[cfg(feature = "defer")]
            deferred_held: 0,
            top_action: NONE,
            defer_next: false,
            #[cfg(all(feature = "defer", feature = "host-speedups"))]
            scan: crate::rete::ScanRun::NONE,
            lhs_pm: [PatBinding::EMPTY; MAX_PATTERNS],
            lhs_of: TokenId::NONE,
            rhs_pm: [PatBinding::EMPTY; MAX_PATTERNS],
            this_pm: PatBinding::EMPTY,
            pm_rhs: false,
            #[cfg(feature = "grow")]
            mf: crate::rete::MfOrder::new(),
        }
    }
}

/// The evaluator's registers: stack pointer, frame base, scratch top, saved and
/// restored as one value around a frame (a firing, a deffunction call, a command).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Evaluation stack pointer and current frame base.
    pub sp: Ix,
    pub bp: Ix,
    pub scratch_top: Ix,
}

impl Frame {
    /// Ends a frame opened at `outer`: its stack (locals, arguments) goes; what it
    /// left in scratch stays for the caller to keep or drop.
    #[inline]
    pub fn leave(&mut self, outer: Frame) {
        self.sp = outer.sp;
        self.bp = outer.bp;
    }

    pub const fn new() -> Frame {
        Frame {
            sp: 0,
            bp: 0,
            scratch_top: 0,
        }
    }
}

/// The evaluator: nesting, unwinding, error details of the current call.
pub struct EvalState {
    /// Cells at the top of scratch holding multifield values of globals.
    pub gmf_used: Ix,
    pub eval_depth: u16,
    /// `return` / `break` unwinding in progress.
    pub returning: bool,
    pub breaking: bool,
    pub return_value: Value,
    /// Deffunctions executing: `clear` refuses while any is, as in CLIPS.
    pub in_use: u16,
    /// Facts asserted and globals set (wrapping): a parse-time evaluation that moved
    /// it left values that may use the construct's new symbols and templates.
    pub effects: u32,
    /// The last argument type error was about a literal argument: CLIPS reports those
    /// while parsing, so the command line prints no fallback value after it.
    pub literal_error: bool,
    /// A field of the fact being asserted failed to evaluate: CLIPS reports it, leaves
    /// the field out, asserts the fact and then stops the actions (see `assert`).
    pub field_error: Option<crate::error::EvalError>,
    /// A builtin's fallback value after a run-time error, when it depends on the
    /// arguments (see `builtins::errors::ErrorFallback`).
    pub error_fallback: Option<crate::builtins::errors::ErrorFallback>,
    /// Number of the next `gensym` symbol.
    pub gensym_next: u32,
    /// First expression node of the command being run (at the prompt, or an `eval`
    /// string): what it refers to is in use, as in CLIPS (`undeftemplate` ...).
    pub command_base: Ix,
    /// Top-level fact-set queries running (outside a firing): a fact they retract
    /// stays pending, its cells readable by `?f:slot`, until the tuple is done. A
    /// command at the prompt adds `COMMAND_HOLD`: what it retracts stays readable
    /// (`duplicate`, `modify`) until it is done, as in CLIPS.
    pub query_hold: u16,
    /// Deffunction calls under way, counted from before their arguments are
    /// evaluated: CLIPS's evaluation depth (`ED:` in `(watch deffunctions)`).
    #[cfg(feature = "extras")]
    pub dfn_depth: u16,
    /// An argument of the builtin being called failed (see `Core::arg_failed`; the
    /// ones before it pushed): the arguments' base on the stack and the failed one's
    /// node, `NONE` when none.
    #[cfg(feature = "extras")]
    pub failed_arg: (Ix, Ix),
    /// The arguments after a failed one are being evaluated, CLIPS's evaluation error
    /// set: builtins that check it stop with their error value (`(sqrt 4)` is 0.0).
    #[cfg(feature = "extras")]
    pub arg_error: bool,
    /// How deep calls may nest on the host (kept across `clear`).
    #[cfg(feature = "grow")]
    pub limits: crate::eval::DepthLimits,
    /// The first fixed limit of the image (and of engines without `grow`) that this
    /// engine went past, for `write_compiled` to refuse what the image cannot hold.
    #[cfg(feature = "grow")]
    pub past_image: Option<&'static str>,
}

impl EvalState {
    pub const fn new() -> EvalState {
        EvalState {
            gmf_used: 0,
            eval_depth: 0,
            returning: false,
            breaking: false,
            return_value: Value::Void,
            in_use: 0,
            effects: 0,
            literal_error: false,
            field_error: None,
            error_fallback: None,
            gensym_next: 1,
            command_base: 0,
            query_hold: 0,
            #[cfg(feature = "extras")]
            dfn_depth: 0,
            #[cfg(feature = "extras")]
            failed_arg: (0, NONE),
            #[cfg(feature = "extras")]
            arg_error: false,
            #[cfg(feature = "grow")]
            limits: crate::eval::DepthLimits::new(),
            #[cfg(feature = "grow")]
            past_image: None,
        }
    }
}

/// Batch files and the prompt: where commands come from and what they print.
pub struct BatchIo {
    /// Line of the current batch command's first line minus one (error positions).
    pub line_base: u32,
    /// A file `batch` asked for, run by the command loop after the current command
    /// (`batch` parses its file: only with the feature `parser`).
    #[cfg(feature = "parser")]
    pub pending_batch: crate::value::TextBuf<256>,
    /// The batch file (with echo) whose commands run now: in CLIPS's batch mode
    /// `read`, `readline` and `get-char` from `stdin` take its next lines.
    #[cfg(feature = "parser")]
    pub batch_input: BatchInput,
    /// Bytes `get-char` took from the batch file since its last newline: CLIPS echoes
    /// batch input a line at a time, so they lead the next echoed line.
    #[cfg(feature = "parser")]
    pub unechoed: crate::value::TextBuf<80>,
    /// A batch file (with echo) ended inside a command: its file and the offset where
    /// that command starts (`lines`: the newlines before it). As in CLIPS the command
    /// goes on in the input outside the file (an enclosing batch file, the prompt).
    #[cfg(feature = "parser")]
    pub carry: BatchInput,
    /// How many batch files are running inside each other.
    pub batch_depth: u8,
    /// `batch*`: commands print no results.
    pub quiet_results: bool,
    /// A batch file ended after its prompt was printed; the next command read uses it.
    pub prompt_shown: bool,
    /// `load` of the construct being parsed: its start in the text, whether it
    /// redefines one, and whether the first part of its line is printed
    /// (`Parser::announce_head`, once its name is read); the parser announces the rest
    /// (`Parser::announce`) once it is built, before it is matched against the facts.
    pub announce: Option<(usize, bool, bool)>,
    /// A progress mark (`*`, `%`, ...) was printed by this load.
    pub progress_printed: bool,
}

impl BatchIo {
    pub const fn new() -> BatchIo {
        BatchIo {
            line_base: 0,
            #[cfg(feature = "parser")]
            pending_batch: crate::value::TextBuf::new(),
            #[cfg(feature = "parser")]
            batch_input: BatchInput::new(),
            #[cfg(feature = "parser")]
            unechoed: crate::value::TextBuf::new(),
            #[cfg(feature = "parser")]
            carry: BatchInput::new(),
            batch_depth: 0,
            quiet_results: false,
            prompt_shown: false,
            announce: None,
            progress_printed: false,
        }
    }
}

/// Where standard input comes from while a batch file runs (`BatchIo::batch_input`):
/// the file and the offset of its first byte no command or read has consumed. The
/// batch loop sets it before each command and picks up where reads left it.
#[cfg(feature = "parser")]
pub struct BatchInput {
    /// A batch file is running; false at the prompt, in `batch*` and once the file's
    /// end was read (then input comes from the host's standard input, as in CLIPS).
    pub active: bool,
    pub path: crate::value::TextBuf<256>,
    pub offset: u64,
    /// Newlines reads consumed since the batch loop set `offset` (error positions).
    pub lines: u32,
}

#[cfg(feature = "parser")]
impl BatchInput {
    pub const fn new() -> BatchInput {
        BatchInput {
            active: false,
            path: crate::value::TextBuf::new(),
            offset: 0,
            lines: 0,
        }
    }
}

#[cfg(feature = "parser")]
impl Default for BatchInput {
    fn default() -> Self {
        Self::new()
    }
}

/// CLIPS mode flags: watch, halt and exit, halting after an error, what is running.
pub struct Mode {
    pub watch: u8,
    pub halt: bool,
    pub exit: bool,
    /// `(exit N)`'s N (0 for a bare `(exit)`).
    pub exit_status: i32,
    /// Something the session could not recover from was reported: a pool ran out, or
    /// the input ended inside a construct (a command line exits non-zero for it).
    pub unrecoverable: bool,
    /// CLIPS's halting state: an error was reported in the pattern or join network
    /// during the current command, firing or construct. Until that ends, what CLIPS stops while halting does nothing and
    /// gives FALSE (progn, switch, loops, deffunction calls, fact-set queries; printout
    /// prints nothing) in the rest of the propagation, and `reset` asserts no further
    /// deffacts facts.
    pub halting: bool,
    pub firing: bool,
    /// A construct is being parsed: its parse-time expressions (salience, a global's
    /// value) may not define other constructs or `clear`, which would change the pools
    /// its rollback marks point into.
    pub defining: bool,
    /// `reset` is going on: the deffacts and globals it evaluates may not `clear`,
    /// which would wipe the templates, facts and deffacts under it.
    pub resetting: bool,
    /// An assert, modify or duplicate is evaluating its fact's values: a `clear` among
    /// them would retire the template the fact is being made of (CLIPS refuses it, the
    /// template being in use; the byte fits the struct's padding).
    pub asserting: bool,
    /// The `initial-fact` deffacts is defined (`undeffacts` removes it): `reset`
    /// asserts `(initial-fact)`.
    pub initial_deffacts: bool,
    /// Keep each rule's source text for `ppdefrule` (CLIPS's pretty-print forms). A
    /// robot image that never lists its rules turns this off to save the symbol bytes.
    pub keep_pp_forms: bool,
    /// `(set-dynamic-constraint-checking TRUE)`: every new fact's slot values are
    /// checked against their slots' restrictions (agent-core feature `extras`).
    pub dynamic_checks: bool,
    /// `(set-fact-duplication TRUE)`: an assert of a fact equal to a live one makes a
    /// second fact (agent-core feature `extras` sets it).
    pub fact_duplication: bool,
    /// Duplication was on at some point: equal live facts may exist (the invariant
    /// check then allows them).
    pub twins_made: bool,
    /// `(set-sequence-operator-recognition TRUE)`: `$?x` in a function call's arguments
    /// is read as `(expand$ ?x)` (agent-core feature `extras`; the byte fits the
    /// struct's padding).
    pub seq_ops: bool,
    /// `(set-reset-globals FALSE)`: `reset` leaves the defglobals' values as they
    /// are (set by agent-core feature `extras`; kept across `clear`, as CLIPS keeps
    /// it; the byte fits the struct's padding).
    pub keep_globals: bool,
    /// COOL's watch items (`watch::cool`), accepted where only `initial-object`
    /// can make them trace (agent-core feature `extras`).
    #[cfg(feature = "extras")]
    pub cool_watch: u8,
    /// `(set-incremental-reset FALSE)`: a rule defined while facts exist is not
    /// matched against them (its new joins and alpha nodes start empty) until the
    /// next `reset` (agent-core feature `extras`; kept across `clear`, as CLIPS keeps
    /// it).
    #[cfg(feature = "extras")]
    pub no_incremental_reset: bool,
    /// `set-salience-evaluation`: when a rule's salience expression is evaluated
    /// (`agenda::SALIENCE_*`; agent-core feature `extras`, the image keeps CLIPS's
    /// default, when-defined).
    #[cfg(feature = "extras")]
    pub salience_eval: u8,
    /// The run loop takes its general path (`Core::run_turn`): a feature it checks per
    /// firing may be on (a breakpoint, the profiler, every-cycle salience evaluation,
    /// modules or an empty focus stack, a `logical` CE). Whatever may turn one on sets
    /// it (`Core::note_run_slow`); a turn on the general path and each run recompute
    /// it (`Core::refresh_run_slow`), so the usual firing tests this byte only. (Not
    /// in the agent image, which has none of these features.)
    #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
    pub run_slow: bool,
}

impl Mode {
    pub const fn new() -> Mode {
        Mode {
            // CLIPS starts with compilations watched
            watch: watch::COMPILATIONS,
            halt: false,
            exit: false,
            exit_status: 0,
            unrecoverable: false,
            halting: false,
            firing: false,
            defining: false,
            resetting: false,
            asserting: false,
            initial_deffacts: true,
            keep_pp_forms: true,
            dynamic_checks: false,
            fact_duplication: false,
            twins_made: false,
            seq_ops: false,
            keep_globals: false,
            #[cfg(feature = "extras")]
            cool_watch: 0,
            #[cfg(feature = "extras")]
            no_incremental_reset: false,
            #[cfg(feature = "extras")]
            salience_eval: crate::agenda::SALIENCE_WHEN_DEFINED,
            #[cfg(any(feature = "extras", feature = "modules", feature = "logical"))]
            run_slow: true,
        }
    }
}

/// Caches of facts about the network (renewed when it changes): join keys and test plans.
pub struct Caches {
    /// Last beta-index key computed: (token, index child join, key). The token's
    /// left activation of that child, which follows at once, reuses it.
    pub key_cache: (TokenId, JoinId, u32),
    /// Recently used joins' key plans (`rete::index`), direct-mapped by join.
    pub key_plans: [crate::rete::KeyPlan; crate::rete::KEY_PLANS],
    /// Recently used joins' test plans (`rete::quick`), direct-mapped by join.
    pub test_plans: [crate::rete::TestPlan; crate::rete::TEST_PLANS],
    /// Recently used joins' compiled test plans (`rete::plan`), for the joins whose
    /// tests `test_plans` cannot hold (host only: the image keeps its RAM).
    #[cfg(feature = "host-speedups")]
    pub compiled_plans: crate::rete::TestPlans,
    /// Host: the next memory-order stamp of a match of an alpha node with an
    /// or-lookup field (`rete::index`; saturates, and then or-lookups stop).
    #[cfg(feature = "host-speedups")]
    pub or_stamp: u32,
    /// Host: recently used joins' first `?a | ?b` test after error-free ones and
    /// its reads, direct-mapped by join (`rete::index`).
    #[cfg(feature = "host-speedups")]
    pub or_plans: [crate::rete::OrPlan; crate::rete::KEY_PLANS],
}

impl Caches {
    pub const fn new() -> Caches {
        Caches {
            key_cache: (TokenId::NONE, JoinId::NONE, 0),
            key_plans: [crate::rete::KeyPlan::NONE; crate::rete::KEY_PLANS],
            test_plans: [crate::rete::TestPlan::NONE; crate::rete::TEST_PLANS],
            #[cfg(feature = "host-speedups")]
            compiled_plans: crate::rete::TestPlans::EMPTY,
            #[cfg(feature = "host-speedups")]
            or_stamp: 0,
            #[cfg(feature = "host-speedups")]
            or_plans: [crate::rete::OrPlan::NONE; crate::rete::KEY_PLANS],
        }
    }
}

/// The random generator (`seed`, `random`).
#[derive(Clone, Copy)]
pub struct Random {
    /// Random generator state (`seed`/`random`).
    pub rng: u64,
    pub rng_glibc: [i32; 34],
    pub rng_pos: u8,
    pub rng_seeded: bool,
    /// `random` or `seed` was called: the numbers drawn for activations (one per
    /// activation, as in CLIPS) are seen, so deferred propagation, which skips
    /// activations CLIPS makes and removes, stays off (`rete::defer`).
    pub observed: bool,
}

impl Random {
    pub const fn new() -> Random {
        Random {
            rng: 1,
            rng_glibc: [0; 34],
            rng_pos: 0,
            rng_seeded: false,
            observed: false,
        }
    }
}

/// Scalar engine state, one small struct per subsystem.
pub struct State {
    pub pools: PoolCounts,
    pub facts: FactList,
    pub agenda: AgendaState,
    pub net: MatchState,
    pub frame: Frame,
    pub eval: EvalState,
    pub io: BatchIo,
    pub mode: Mode,
    pub cache: Caches,
    pub random: Random,
    /// Truth maintenance (`logical`).
    #[cfg(feature = "logical")]
    pub logical: crate::logical::LogicalState,
    /// Modules and the focus stack (`modules`).
    #[cfg(feature = "modules")]
    pub modules: crate::module::ModuleState,
    /// Expression nodes, alpha nodes and joins of a compiled rule base read in place
    /// (feature `in-place`, `compiled`, `rom`): ids below their length are these, the
    /// arena's come after.
    pub rom: crate::rom::Rom,
    /// Without the feature `parser`: the code of the builtins the loaded compiled rule
    /// base calls, by id (see `builtins::code_for`); empty otherwise.
    pub builtin_code: &'static [crate::builtins::Imp],
    /// Rules with a breakpoint (`set-break`, feature `extras`).
    #[cfg(feature = "extras")]
    pub breaks: Breaks,
    /// Constructs traced otherwise than their watch item (`(watch rules r1)`,
    /// feature `extras`).
    #[cfg(feature = "extras")]
    pub watch_names: WatchNames,
    /// What the parser notes of the rule it reads for CLIPS's `[RULECSTR3]`/`[RULECSTR2]`
    /// checks (feature `extras`; here, not in the parser, so that a parser starts
    /// without filling it).
    #[cfg(feature = "extras")]
    pub rule_notes: crate::parser::rhs_types::RuleNotes,
    /// The files `fetch` read and their current menus (feature `extras`; kept across
    /// `clear`, as in CLIPS).
    #[cfg(feature = "extras")]
    pub text_regions: crate::builtins::textpro::TextRegions,
    /// `set-locale`'s text and `apropos`'s arguments (feature `extras`; kept across
    /// `clear`).
    #[cfg(feature = "extras")]
    pub tools: crate::builtins::tools::ToolsState,
    /// What `timetag` needs to give a fact CLIPS's time tag (feature `extras`; afresh
    /// at `clear`, rebased at `reset`).
    #[cfg(feature = "extras")]
    pub timetags: crate::builtins::tools::Timetags,
    /// The profiler (feature `extras`; its settings kept across `clear`).
    #[cfg(feature = "extras")]
    pub profile: crate::builtins::profile::Profile,
    /// `check-syntax` (feature `extras`): while it reads its text, what the parser
    /// writes to the error and warning routers (a salience or static default that
    /// fails as it is read) goes here, to be returned in its message as CLIPS does.
    #[cfg(feature = "extras")]
    pub capture: Option<crate::value::TextBuf<2048>>,
    /// Host: joins primed while their parent had partial matches, and their own
    /// order of those (`rete::order`).
    #[cfg(feature = "grow")]
    pub prime: crate::rete::PrimeOrders,
    /// Host: activations' recency lists by activation index, worked out the first
    /// time lex or mea compares them (`strategy::RecencyCache`).
    #[cfg(all(feature = "extras", feature = "grow"))]
    pub recency: core::cell::RefCell<alloc::vec::Vec<Option<crate::strategy::RecencyCache>>>,
    /// Host: partial matches' stamps by token index (`rete::Stamp`), allocated
    /// once a join feeds a join from the right; `stamp` the last one given, and
    /// `stamps_off` set once the allocator refused (blocker searches then walk the
    /// memory).
    #[cfg(feature = "grow")]
    pub stamps: crate::grow::ZeroedU32,
    #[cfg(feature = "grow")]
    pub stamp: crate::rete::Stamp,
    #[cfg(feature = "grow")]
    pub stamps_off: bool,
    /// Host: lex and mea's ordered index of the agenda (`strategy::RecencyIndex`).
    #[cfg(all(feature = "extras", feature = "grow"))]
    pub recency_index: crate::strategy::RecencyIndex,
}

/// The names of the rules with a breakpoint (`set-break`): a run stops before firing
/// one of them, unless it is the run's first firing. A name, not a rule: as in CLIPS,
/// a rule defined again keeps its breakpoint; `undefrule` and `clear` remove it.
#[cfg(feature = "extras")]
#[derive(Clone, Copy)]
pub struct Breaks {
    names: [SymId; Breaks::MAX],
    n: u8,
}

#[cfg(feature = "extras")]
impl Default for Breaks {
    fn default() -> Breaks {
        Breaks::new()
    }
}

#[cfg(feature = "extras")]
impl Breaks {
    /// Most breakpoints at once.
    pub const MAX: usize = 32;

    pub const fn new() -> Breaks {
        Breaks {
            names: [0; Breaks::MAX],
            n: 0,
        }
    }

    pub fn has(&self, name: SymId) -> bool {
        self.names[..usize::from(self.n)].contains(&name)
    }

    /// Sets one; false when `MAX` are set already.
    pub fn add(&mut self, name: SymId) -> bool {
        if self.has(name) {
            return true;
        }
        let n = usize::from(self.n);
        if n == Breaks::MAX {
            return false;
        }
        self.names[n] = name;
        self.n += 1;
        true
    }

    /// Removes one; whether it was set.
    pub fn remove(&mut self, name: SymId) -> bool {
        let n = usize::from(self.n);
        match self.names[..n].iter().position(|&x| x == name) {
            Some(i) => {
                self.names.copy_within(i + 1..n, i);
                self.n -= 1;
                true
            }
            None => false,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.n == 0
    }
}

/// The watch items about constructs (facts, rules, activations, deffunctions,
/// globals) and the constructs traced otherwise than their item. As in CLIPS 6.30
/// each construct has its own trace flag: `(watch ITEM)` or `(unwatch ITEM)` sets
/// the item's and every construct's, `(watch ITEM NAME...)` the ones named; a new
/// construct takes its item's, one defined again keeps its own if its item is off.
/// Kept here as the constructs whose flag differs from their item's (by item bit,
/// module and name; `undef*`, `clear` and the whole item forget them), so that
/// `Mode::watch` has an item's bit while it or any of its constructs is traced: the
/// engine checks that bit first, the construct only when it is set.
#[cfg(feature = "extras")]
#[derive(Clone, Copy)]
pub struct WatchNames {
    /// The items' own states (`watch::FACTS`, ...), as `list-watch-items` shows them.
    pub items: u8,
    keys: [(u8, crate::module::ModId, SymId); WatchNames::MAX],
    n: u8,
}

#[cfg(feature = "extras")]
impl Default for WatchNames {
    fn default() -> WatchNames {
        WatchNames::new()
    }
}

#[cfg(feature = "extras")]
impl WatchNames {
    /// Most constructs traced otherwise than their item at once.
    pub const MAX: usize = 64;
    /// The items about constructs.
    pub const ITEMS: u8 =
        watch::FACTS | watch::RULES | watch::ACTIVATIONS | watch::GLOBALS | watch::DEFFUNCTIONS;

    pub const fn new() -> WatchNames {
        WatchNames {
            items: 0,
            keys: [(0, 0, 0); WatchNames::MAX],
            n: 0,
        }
    }

    fn find(&self, bit: u8, m: crate::module::ModId, name: SymId) -> Option<usize> {
        self.keys[..usize::from(self.n)]
            .iter()
            .position(|&k| k == (bit, m, name))
    }

    /// Whether the construct is traced for item `bit`.
    pub fn traced(&self, bit: u8, m: crate::module::ModId, name: SymId) -> bool {
        (self.items & bit != 0) != (self.n != 0 && self.find(bit, m, name).is_some())
    }

    /// Sets the construct's flag for item `bit`; false when `MAX` differ already.
    pub fn set(&mut self, bit: u8, m: crate::module::ModId, name: SymId, on: bool) -> bool {
        let differs = on != (self.items & bit != 0);
        match self.find(bit, m, name) {
            Some(i) if !differs => self.remove_at(i),
            None if differs => {
                let n = usize::from(self.n);
                if n == WatchNames::MAX {
                    return false;
                }
                self.keys[n] = (bit, m, name);
                self.n += 1;
            }
            _ => {}
        }
        true
    }

    fn remove_at(&mut self, i: usize) {
        let n = usize::from(self.n);
        self.keys.copy_within(i + 1..n, i);
        self.n -= 1;
    }

    /// Forgets the constructs named for the items `bits` (each construct is set to
    /// its item's state).
    pub fn forget_items(&mut self, bits: u8) {
        self.remove_where(|k| k.0 & bits != 0);
    }

    /// Forgets a construct for the items `bits` (it is gone, or defined again while
    /// they are on).
    pub fn forget(&mut self, bits: u8, m: crate::module::ModId, name: SymId) {
        self.remove_where(|k| k.0 & bits != 0 && k.1 == m && k.2 == name);
    }

    /// Removes the keys `gone` picks, keeping the others in order.
    fn remove_where(&mut self, gone: impl Fn((u8, crate::module::ModId, SymId)) -> bool) {
        let mut kept = 0;
        for i in 0..usize::from(self.n) {
            let k = self.keys[i];
            if !gone(k) {
                self.keys[kept] = k;
                kept += 1;
            }
        }
        // (kept <= n <= MAX = 64, so it fits the u8 count)
        self.n = kept as u8;
    }

    /// `Mode::watch`'s construct bits: the items on, and those with a construct
    /// traced otherwise.
    pub fn mode_bits(&self) -> u8 {
        self.keys[..usize::from(self.n)]
            .iter()
            .fold(self.items, |b, k| b | k.0)
    }
}

/// Without `extras` a construct is traced exactly when its item is.
#[cfg(not(feature = "extras"))]
impl Core<'_> {
    #[inline(always)]
    pub(crate) fn fact_line_traced(&self, _fact: Ix) -> bool {
        true
    }

    #[inline(always)]
    pub(crate) fn activation_traced(&self, _a: Ix) -> bool {
        true
    }

    #[inline(always)]
    pub(crate) fn rule_traced(&self, _bit: u8, _r: Ix) -> bool {
        true
    }
}

impl State {
    pub const fn new() -> State {
        State {
            pools: PoolCounts::new(),
            facts: FactList::new(),
            agenda: AgendaState::new(),
            net: MatchState::new(),
            frame: Frame::new(),
            eval: EvalState::new(),
            io: BatchIo::new(),
            mode: Mode::new(),
            cache: Caches::new(),
            random: Random::new(),
            #[cfg(feature = "logical")]
            logical: crate::logical::LogicalState::new(),
            #[cfg(feature = "modules")]
            modules: crate::module::ModuleState::new(),
            rom: crate::rom::Rom::EMPTY,
            builtin_code: &[],
            #[cfg(feature = "extras")]
            breaks: Breaks::new(),
            #[cfg(feature = "extras")]
            watch_names: WatchNames::new(),
            #[cfg(feature = "extras")]
            rule_notes: crate::parser::rhs_types::RuleNotes::new(),
            #[cfg(feature = "extras")]
            text_regions: crate::builtins::textpro::TextRegions::new(),
            #[cfg(feature = "extras")]
            tools: crate::builtins::tools::ToolsState::new(),
            #[cfg(feature = "extras")]
            timetags: crate::builtins::tools::Timetags::new(),
            #[cfg(feature = "extras")]
            profile: crate::builtins::profile::Profile::new(),
            #[cfg(feature = "extras")]
            capture: None,
            #[cfg(feature = "grow")]
            prime: crate::rete::PrimeOrders::new(),
            #[cfg(all(feature = "extras", feature = "grow"))]
            recency: core::cell::RefCell::new(alloc::vec::Vec::new()),
            #[cfg(feature = "grow")]
            stamps: crate::grow::ZeroedU32::new(),
            #[cfg(feature = "grow")]
            stamp: 0,
            #[cfg(feature = "grow")]
            stamps_off: false,
            #[cfg(all(feature = "extras", feature = "grow"))]
            recency_index: crate::strategy::RecencyIndex::new(),
        }
    }
}

/// `Default` is `new()` (the state of an empty engine) for the state and its parts.
macro_rules! default_is_new {
    ($($t:ty),*) => {
        $(impl Default for $t {
            fn default() -> Self {
                Self::new()
            }
        })*
    };
}

default_is_new!(
    State,
    PoolCounts,
    FactList,
    AgendaState,
    MatchState,
    Frame,
    EvalState,
    BatchIo,
    Mode,
    Caches,
    Random
);

/// The CLIPS engine: its state and `S`, the storage of every pool, made by
/// [`engine_storage!`](crate::engine_storage) from named capacities. Every pool is an
/// inline array, so an engine can be a `static` and its size is known at compile time.
pub struct Engine<S: Storage> {
    pub(crate) st: State,
    pools: S,
    started: bool,
}

/// Host defaults ([`Capacities::HOST`](crate::Capacities::HOST)): roomy enough for the
/// differential suite and the benchmarks.
pub type DefaultEngine = Engine<HostStorage>;

/// Small capacities for unit tests ([`Capacities::SMALL`](crate::Capacities::SMALL);
/// fits a thread stack).
pub type SmallEngine = Engine<SmallStorage>;

impl Engine<HostStorage> {
    /// An empty engine with [`Capacities::HOST`](crate::Capacities::HOST).
    pub const fn new() -> Self {
        Engine::with_storage(HostStorage::new())
    }
}

impl Engine<SmallStorage> {
    /// An empty engine with [`Capacities::SMALL`](crate::Capacities::SMALL).
    pub const fn new() -> Self {
        Engine::with_storage(SmallStorage::new())
    }
}

impl<S: Storage> Engine<S> {
    /// An empty engine holding `pools` (a storage's `new()`); `const` so it can
    /// initialise a `static`. The first API call performs CLIPS's start-up
    /// (`(initial-fact)` asserted as f-0).
    ///
    /// A pool larger than the index type [`crate::Ix`] can address does not compile:
    /// ```compile_fail
    /// agent_core::engine_storage! {
    ///     struct Big { symbol_bytes: agent_core::NONE as usize + 1, ..agent_core::Capacities::SMALL }
    /// }
    /// let _ = agent_core::Engine::with_storage(Big::new());
    /// ```
    pub const fn with_storage(pools: S) -> Self {
        // Every pool entry must be addressable by an `Ix` other than `NONE`: a
        // capacity the index type cannot hold fails to compile (enable the
        // `wide-index` feature for pools beyond 65,535 entries).
        const {
            let capacities = S::CAPACITIES.to_array();
            let mut i = 0;
            while i < capacities.len() {
                assert!(
                    capacities[i] <= NONE as usize,
                    "an engine pool is larger than its index type allows (feature wide-index)"
                );
                i += 1;
            }
        }
        Engine {
            st: State::new(),
            pools,
            started: false,
        }
    }

    /// The facts as the host API reads them.
    pub(crate) fn fact_view(&self) -> crate::host_fn::FactView<'_> {
        let p = self.pools.pools(self.st.rom);
        crate::host_fn::FactView {
            facts: p.facts,
            templates: p.templates,
            slots: p.slots,
            values: p.values,
            syms: crate::symbols::SymTexts {
                rom: self.st.rom.symbols,
                entries: p.sym_entries,
                bytes: p.sym_bytes,
            },
            head: self.st.facts.fact_head,
        }
    }

    pub(crate) fn rule_at(&self, r: Ix) -> Rule {
        self.pools.pools(self.st.rom).rules[r as usize]
    }

    /// Fact indices along a token's ancestry, by pattern position.
    pub(crate) fn basis_of(
        &self,
        token: TokenId,
        out: &mut [Option<u32>; crate::rete::MAX_PATTERNS],
    ) -> usize {
        let pools = self.pools.pools(self.st.rom);
        let walk = crate::rete::basis::Basis {
            tokens: pools.tokens,
            joins: pools.joins,
            facts: pools.facts,
            at: token,
        };
        let mut n = 0;
        for (depth, num) in walk {
            if depth < out.len() {
                out[depth] = num;
                n = n.max(depth + 1);
            }
        }
        n
    }

    /// The capacities of the storage now, in table order.
    #[inline(always)]
    pub(crate) fn storage_capacities(&self) -> [usize; Pool::COUNT] {
        self.pools.capacities()
    }

    pub(crate) fn act_at(&self, a: Ix) -> Activation {
        self.pools.pools(self.st.rom).acts[a as usize]
    }
    pub(crate) fn sym_str(&self, id: SymId) -> &str {
        let pools = self.pools.pools(self.st.rom);
        crate::symbols::SymTexts {
            rom: self.st.rom.symbols,
            entries: pools.sym_entries,
            bytes: pools.sym_bytes,
        }
        .text(id)
    }

    /// The non-generic view of this engine, bound to `host` for output.
    pub fn core<'a>(&'a mut self, host: &'a mut dyn Host) -> Core<'a> {
        let mut core = self.pools.core(&mut self.st, host);
        if !self.started {
            self.started = true;
            // Start-up as CLIPS: an empty environment holding (initial-fact) as f-0.
            // Only fails if the pools are too small for one fact; then the first
            // assert reports the capacity error instead.
            let _ = core.startup();
        }
        // every API call is a command of its own: no halting carried over
        core.st.mode.halting = false;
        // invariant mode: every operation starts from a consistent engine
        core.debug_check("at the start of an engine operation");
        core
    }
}

impl Default for Engine<HostStorage> {
    fn default() -> Self {
        Self::new()
    }
}

/// At a full pool, in a function whose error type takes a [`CapacityError`]: with
/// feature `grow`, grows `pool` to at least `need` entries (`Core::grow`: the error
/// only if it cannot); without it, returns the pool's capacity error (capacity `len`).
macro_rules! full_pool {
    ($core:expr, $pool:expr, $need:expr, $len:expr) => {{
        #[cfg(feature = "grow")]
        $core.grow($pool, $need)?;
        #[cfg(not(feature = "grow"))]
        return Err($crate::engine::cap($pool, $len).into());
    }};
}
pub(crate) use full_pool;

pub(crate) fn cap(pool: Pool, capacity: usize) -> CapacityError {
    CapacityError {
        pool,
        capacity: capacity as u32,
    }
}

impl Core<'_> {
    pub fn syms(&mut self) -> Symbols<'_> {
        Symbols {
            rom: self.st.rom.symbols,
            entries: self.sym_entries,
            buckets: self.sym_buckets,
            bytes: self.sym_bytes,
            count: &mut self.st.pools.nsyms,
            bytes_used: &mut self.st.pools.sym_bytes,
        }
    }

    /// With feature `grow`: room for one more symbol of `len` bytes, grown if needed
    /// (the [`Symbols`] view cannot grow; a pool that stays full is its error there).
    #[cfg(feature = "grow")]
    pub(crate) fn symbol_room(&mut self, len: usize) {
        let n = (self.st.pools.nsyms as usize).saturating_sub(self.st.rom.symbols.len());
        if n >= self.sym_entries.len() {
            let _ = self.grow(Pool::Symbols, n + 1);
        }
        let used = self.st.pools.sym_bytes as usize;
        if used + len > self.sym_bytes.len() {
            let _ = self.grow(Pool::SymbolBytes, used + len);
        }
    }

    /// With feature `grow`: makes `pool` hold `need` entries if it can (the check
    /// that follows reports a pool that stays too small).
    #[cfg(feature = "grow")]
    pub(crate) fn ensure(&mut self, pool: Pool, need: usize) {
        if need > self.capacity(pool) {
            let _ = self.grow(pool, need);
        }
    }

    /// Text of a symbol or string.
    pub fn sym_text(&self, id: SymId) -> &str {
        // NONE (a retired construct's name) and any id out of range read as ""
        self.sym_texts().text(id)
    }

    /// Every symbol's text, read-only.
    #[inline]
    pub fn sym_texts(&self) -> crate::symbols::SymTexts<'_> {
        crate::symbols::SymTexts {
            rom: self.st.rom.symbols,
            entries: self.sym_entries,
            bytes: self.sym_bytes,
        }
    }

    /// The id of symbol text `s`, added if new.
    /// (Inlined on the host: most calls find a symbol the table has; only a new one
    /// pays the growth check and the high-water notes.)
    #[cfg_attr(feature = "host-speedups", inline)]
    pub fn intern(&mut self, s: &str) -> Result<SymId, CapacityError> {
        let h = crate::symbols::hash_bytes(s.as_bytes());
        match self.syms().find_hashed(s, h) {
            Some(id) => Ok(id),
            None => self.intern_new(s, h),
        }
    }

    /// `intern` of a text the table does not have yet.
    #[cfg_attr(feature = "host-speedups", inline(never))]
    fn intern_new(&mut self, s: &str, h: u32) -> Result<SymId, CapacityError> {
        #[cfg(feature = "grow")]
        self.symbol_room(s.len());
        let r = self.syms().add_new(s, h);
        self.note_hw(Pool::Symbols, self.st.pools.nsyms as usize);
        self.note_hw(Pool::SymbolBytes, self.st.pools.sym_bytes as usize);
        r
    }

    pub fn find_sym(&mut self, s: &str) -> Option<SymId> {
        self.syms().find(s)
    }

    pub fn note_hw(&mut self, pool: Pool, used: usize) {
        let i = pool as usize;
        if used as u32 > self.st.pools.hw.used[i] {
            self.st.pools.hw.used[i] = used as u32;
        }
    }

    /// Appends an expression node.
    pub fn push_expr(&mut self, e: Expr) -> Result<Ix, CapacityError> {
        let n = self.st.pools.nexprs as usize;
        if n >= self.exprs.len() || n >= NONE as usize {
            full_pool!(self, Pool::Exprs, n + 1, self.exprs.len());
        }
        self.exprs[n] = e;
        self.st.pools.nexprs += 1;
        self.note_hw(Pool::Exprs, n + 1);
        Ok(n as Ix)
    }

    /// Appends a constant node for `v` (atoms only).
    pub fn push_const(&mut self, v: Value) -> Result<Ix, CapacityError> {
        match v {
            Value::Int(i) if (i16::MIN as i64..=i16::MAX as i64).contains(&i) => {
                let (h, t) = Expr::split_bits(Op::Int, i as u64);
                let id = self.push_expr(h)?;
                self.push_expr(t)?;
                Ok(id)
            }
            Value::Int(i) => {
                let (h, t) = Expr::split_bits(Op::Int, i as u64);
                let id = self.push_expr(h)?;
                self.push_expr(t)?;
                Ok(id)
            }
            Value::Float(f) => {
                let (h, t) = Expr::split_bits(Op::Float, f.to_bits());
                let id = self.push_expr(h)?;
                self.push_expr(t)?;
                Ok(id)
            }
            Value::Sym(s) => self.push_expr(Expr::new(Op::Sym, 0, s)),
            Value::Str(s) => self.push_expr(Expr::new(Op::Str, 0, s)),
            _ => self.push_expr(Expr::new(Op::Sym, 0, 0)),
        }
    }

    /// Value of a constant node (Int/Float/Sym/Str).
    pub fn const_value(&self, e: Ix) -> Value {
        self.const_value_inline(e)
    }

    /// `const_value`, inlined on the host where a call costs more than its body (the
    /// alpha tests: agent-40's run 11.10 -> 10.94 M instructions, callgrind; inlined
    /// into `eval` too it made that dearer).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn const_value_inline(&self, e: Ix) -> Value {
        let x = self.exprs[e as usize];
        match x.op {
            Op::Int => Value::Int(Expr::join_bits(x, self.exprs[e as usize + 1]) as i64),
            Op::Float => Value::Float(f64::from_bits(Expr::join_bits(
                x,
                self.exprs[e as usize + 1],
            ))),
            Op::Sym => Value::Sym(x.data),
            Op::Str => Value::Str(x.data),
            _ => Value::Void,
        }
    }

    /// `append_child` given `last`, the last child of `parent` (NONE: none yet), so
    /// that a long list is built without walking it; returns the new last child
    /// (the end of `child`'s own `next` chain).
    pub fn append_after(&mut self, parent: Ix, last: Ix, child: Ix) -> Ix {
        if last == NONE {
            self.append_child(parent, child);
        } else {
            self.exprs[last as usize].next = child;
        }
        let mut c = child;
        while self.exprs[c as usize].next != NONE {
            c = self.exprs[c as usize].next;
        }
        c
    }

    /// Links `child` as the last child of `parent`.
    pub fn append_child(&mut self, parent: Ix, child: Ix) {
        let mut c = self.exprs[parent as usize].first;
        if c == NONE {
            self.exprs[parent as usize].first = child;
            return;
        }
        while self.exprs[c as usize].next != NONE {
            c = self.exprs[c as usize].next;
        }
        self.exprs[c as usize].next = child;
    }

    /// Links `SlotVal` node `sv` among the children of fact spec `spec` in slot order:
    /// CLIPS evaluates a fact's slot values in the template's order, whatever order
    /// they are written in (`assert_spec` walks them with the defaults).
    pub fn insert_slot_val(&mut self, spec: Ix, sv: Ix) {
        let slot = self.exprs[sv as usize].data;
        let mut prev = NONE;
        let mut c = self.exprs[spec as usize].first;
        while c != NONE && self.exprs[c as usize].data < slot {
            prev = c;
            c = self.exprs[c as usize].next;
        }
        self.exprs[sv as usize].next = c;
        if prev == NONE {
            self.exprs[spec as usize].first = sv;
        } else {
            self.exprs[prev as usize].next = sv;
        }
    }

    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            nsyms: self.st.pools.nsyms,
            sym_bytes: self.st.pools.sym_bytes,
            ntemplates: self.st.pools.ntemplates,
            nslots: self.st.pools.nslots,
            nrules: self.st.pools.nrules,
            nalpha: self.st.pools.nalpha,
            njoins: self.st.pools.njoins,
            nexprs: self.st.pools.nexprs,
            nfuncs: self.st.pools.nfuncs,
            nglobals: self.st.pools.nglobals,
            ndeffacts: self.st.pools.ndeffacts,
        }
    }

    /// Pushes a value on the evaluation stack.
    pub fn push_value(&mut self, v: Value) -> Result<(), CapacityError> {
        let sp = self.st.frame.sp as usize;
        self.put_value(sp, v)?;
        self.st.frame.sp += 1;
        self.note_hw(Pool::EvalStack, sp + 1);
        Ok(())
    }

    /// Writes `v` at stack entry `sp`, the stack grown first where it may (`grow`).
    /// The bounds check is the room check: a full stack leaves the write's path at
    /// once (`put_value_full`), so the common path checks once and merges with no
    /// grown stack. Without `grow` a full stack is the error at once.
    #[inline(always)]
    pub(crate) fn put_value(&mut self, sp: usize, v: Value) -> Result<(), CapacityError> {
        match self.stack.get_mut(sp) {
            Some(slot) => {
                *slot = v;
                Ok(())
            }
            #[cfg(feature = "grow")]
            None => self.put_value_full(sp, v),
            #[cfg(not(feature = "grow"))]
            None => Err(cap(Pool::EvalStack, self.stack.len())),
        }
    }

    /// `put_value` past the stack's end (`grow`).
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn put_value_full(&mut self, sp: usize, v: Value) -> Result<(), CapacityError> {
        self.grow(Pool::EvalStack, sp + 1)?;
        match self.stack.get_mut(sp) {
            Some(slot) => {
                *slot = v;
                Ok(())
            }
            None => Err(cap(Pool::EvalStack, self.stack.len())),
        }
    }

    /// Pushes `n` empty values (a frame's locals, a fact's slots) with one room
    /// check; on a full stack as `n` calls of `push_value` (those that fit stay).
    #[inline]
    pub fn push_voids(&mut self, n: usize) -> Result<(), CapacityError> {
        let sp = self.st.frame.sp as usize;
        if sp + n > self.stack.len() {
            return self.push_voids_full(n);
        }
        self.stack[sp..sp + n].fill(Value::Void);
        self.st.frame.sp += n as Ix;
        self.note_hw(Pool::EvalStack, sp + n);
        Ok(())
    }

    /// `push_voids` past the stack's end: one at a time, grown where it may.
    #[cold]
    #[inline(never)]
    fn push_voids_full(&mut self, n: usize) -> Result<(), CapacityError> {
        for _ in 0..n {
            self.push_value(Value::Void)?;
        }
        Ok(())
    }

    /// Allocates `n` cells of multifield scratch, returning the start.
    pub fn scratch_alloc(&mut self, n: usize) -> Result<Ix, CapacityError> {
        let top = self.st.frame.scratch_top as usize;
        let limit = self.scratch.len() - self.st.eval.gmf_used as usize;
        if top + n > limit || top + n > NONE as usize {
            return self.scratch_alloc_full(top, n);
        }
        self.st.frame.scratch_top += n as Ix;
        self.note_hw(Pool::Scratch, top + n);
        Ok(top as Ix)
    }

    /// `scratch_alloc` when scratch has no room for `n` cells at `top`: grown if it
    /// may (out of line, so the allocation that fits stays a few instructions).
    #[cold]
    #[inline(never)]
    fn scratch_alloc_full(&mut self, top: usize, n: usize) -> Result<Ix, CapacityError> {
        // the globals' multifields sit at the top: growing would move them under
        // values that point at them, so scratch grows only while there are none
        #[cfg(feature = "grow")]
        if self.st.eval.gmf_used == 0 {
            self.grow(Pool::Scratch, top + n)?;
            self.st.frame.scratch_top += n as Ix;
            self.note_hw(Pool::Scratch, top + n);
            return Ok(top as Ix);
        }
        let _ = (top, n);
        Err(cap(Pool::Scratch, self.scratch.len()))
    }

    /// Makes `v` the value of global `g`; a multifield is copied into the globals'
    /// region at the top of scratch (compacted on each store) so it outlives the
    /// command that built it.
    pub fn set_global(&mut self, g: Ix, v: Value) -> Result<(), CapacityError> {
        self.set_global_with::<false>(g, v)
    }

    /// `set_global` that first prints the `watch globals` trace of the change (`bind`):
    /// the watch flag is read here, next to the store, so the caller pays one call.
    /// (Host: a single-field value stored while globals are not watched, the usual
    /// counter `bind`, in line in its one caller; the rest out of line.)
    #[cfg(feature = "extras")]
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn set_global_traced(&mut self, g: Ix, v: Value) -> Result<(), CapacityError> {
        #[cfg(feature = "host-speedups")]
        if !matches!(v, Value::Multi(_)) && self.st.mode.watch & watch::GLOBALS == 0 {
            self.st.eval.effects = self.st.eval.effects.wrapping_add(1);
            self.globals[g as usize].value = v;
            return Ok(());
        }
        self.set_global_traced_general(g, v)
    }

    /// `set_global_traced` past its in-line case.
    #[cfg(feature = "extras")]
    #[cfg_attr(feature = "host-speedups", inline(never))]
    fn set_global_traced_general(&mut self, g: Ix, v: Value) -> Result<(), CapacityError> {
        self.set_global_with::<true>(g, v)
    }

    #[inline(always)]
    fn set_global_with<const TRACE: bool>(&mut self, g: Ix, v: Value) -> Result<(), CapacityError> {
        #[cfg(feature = "extras")]
        if TRACE {
            self.trace_global(g, v);
        }
        self.st.eval.effects = self.st.eval.effects.wrapping_add(1);
        let len = self.scratch.len();
        let region = len - self.st.eval.gmf_used as usize;
        let m = match v {
            Value::Multi(m) if (m.start as usize) < region => m,
            Value::Multi(m) => {
                // a global's own cells: copy below the region first
                let t = self.scratch_alloc(m.len as usize)?;
                self.scratch
                    .copy_within(m.start as usize..(m.start + m.len) as usize, t as usize);
                return self.set_global(
                    g,
                    Value::Multi(crate::value::MfSpan {
                        start: t,
                        len: m.len,
                    }),
                );
            }
            _ => {
                self.globals[g as usize].value = v;
                return Ok(());
            }
        };
        // copy the new value to a safe place first: the area just below the region
        let n = m.len as usize;
        let mut others = 0usize;
        for (i, gl) in self.globals[..self.st.pools.nglobals as usize]
            .iter()
            .enumerate()
        {
            if let Value::Multi(x) = gl.value {
                if i != g as usize && x.start as usize >= region {
                    others += x.len as usize;
                }
            }
        }
        if self.st.frame.scratch_top as usize + others + n > len {
            return Err(cap(Pool::Scratch, len));
        }
        self.globals[g as usize].value = Value::Void;
        // pack the other globals' multifields against the top, highest start first
        let mut new_top = len;
        loop {
            let mut best: Option<usize> = None;
            for (i, gl) in self.globals[..self.st.pools.nglobals as usize]
                .iter()
                .enumerate()
            {
                if let Value::Multi(x) = gl.value {
                    let s = x.start as usize;
                    if s >= region && s + (x.len as usize) <= new_top && s < new_top {
                        match best {
                            Some(b) => {
                                if let Value::Multi(y) = self.globals[b].value {
                                    if x.start > y.start {
                                        best = Some(i);
                                    }
                                }
                            }
                            None => best = Some(i),
                        }
                    }
                }
            }
            let Some(b) = best else { break };
            let Value::Multi(x) = self.globals[b].value else {
                break;
            };
            let (s, l) = (x.start as usize, x.len as usize);
            let dst = new_top - l;
            self.scratch.copy_within(s..s + l, dst);
            // mark as packed by moving it out of the search window
            self.globals[b].value = Value::Multi(crate::value::MfSpan {
                start: dst as Ix,
                len: l as Ix,
            });
            new_top = dst;
            if l == 0 {
                // an empty multifield needs no cells; park it out of the search window
                self.globals[b].value = Value::Multi(crate::value::MfSpan {
                    start: len as Ix,
                    len: 0,
                });
            }
        }
        let dst = new_top - n;
        self.scratch
            .copy_within(m.start as usize..m.start as usize + n, dst);
        self.globals[g as usize].value = Value::Multi(crate::value::MfSpan {
            start: dst as Ix,
            len: n as Ix,
        });
        self.st.eval.gmf_used = (len - dst) as Ix;
        self.note_hw(
            Pool::Scratch,
            self.st.frame.scratch_top as usize + self.st.eval.gmf_used as usize,
        );
        Ok(())
    }

    /// Stats: high-water marks and capacities of every pool.
    pub fn stats(&self) -> Stats {
        let mut s = self.st.pools.hw;
        let caps = self.capacities();
        for (i, c) in caps.iter().enumerate() {
            s.capacity[i] = *c as u32;
        }
        s
    }
}

#[cfg(test)]
mod size_tests {
    extern crate std;
    use super::*;
    use crate::fact::Fact;
    use crate::rete::{AlphaNode, Join, Token};
    use crate::symbols::SymEntry;
    use crate::template::{Deffacts, Deffunction, Global};
    use crate::template::{SlotDef, Template};
    use core::mem::size_of;

    /// The pools' bytes as `Stats::bytes` reports them account for the whole engine but
    /// its scalar state (and padding): hosts size their RAM from these figures.
    #[test]
    fn pool_bytes_account_for_the_engine() {
        let engine = std::boxed::Box::new(SmallEngine::new());
        let stats = engine.stats();
        let pools: usize = Pool::ALL.iter().map(|&p| stats.bytes(p)).sum();
        let whole = size_of::<SmallEngine>();
        assert!(pools <= whole, "pools {pools} > engine {whole}");
        assert!(
            whole - pools <= size_of::<State>() + 16,
            "engine {whole} B, pools {pools} B: {} B unaccounted",
            whole - pools - size_of::<State>()
        );
    }

    /// Pins the per-entry sizes that decide the image's RAM (see the crate docs); the
    /// image keeps `u16` indices, so `u32` ones (a host feature) are not pinned.
    #[test]
    #[cfg_attr(
        any(feature = "wide-index", feature = "host-speedups"),
        ignore = "pins the image's sizes: u16 indices, no host speed-ups"
    )]
    fn entry_sizes_stay_small() {
        assert!(size_of::<Token>() <= 32, "token {}", size_of::<Token>());
        assert!(size_of::<Expr>() == 8);
        assert!(size_of::<Fact>() <= 24);
        assert!(size_of::<Activation>() <= 24);
        assert!(size_of::<Value>() <= 16);
        // (the host feature `wipe` adds a word and a flag per join; the image has none)
        let wipe = if cfg!(feature = "wipe") { 8 } else { 0 };
        assert!(size_of::<Join>() <= 32 + wipe, "join {}", size_of::<Join>());
        std::println!(
            "sizes: value {} fact {} sym {} template {} slot {} rule {} alpha {} join {} token {} act {} func {} global {} expr {} deffacts {} ext {} state {} | DefaultEngine {} SmallEngine {}",
            size_of::<Value>(),
            size_of::<Fact>(),
            size_of::<SymEntry>(),
            size_of::<Template>(),
            size_of::<SlotDef>(),
            size_of::<Rule>(),
            size_of::<AlphaNode>(),
            size_of::<Join>(),
            size_of::<Token>(),
            size_of::<Activation>(),
            size_of::<Deffunction>(),
            size_of::<Global>(),
            size_of::<Expr>(),
            size_of::<Deffacts>(),
            size_of::<ExternalEntry>(),
            size_of::<State>(),
            size_of::<DefaultEngine>(),
            size_of::<SmallEngine>(),
        );
    }
}
