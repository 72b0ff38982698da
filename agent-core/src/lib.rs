//! A CLIPS 6.30-compatible rule and fact engine in fixed memory.
//!
//! `#![no_std]`, no `alloc`: every byte lives in an [`Engine`] whose pools are inline
//! arrays sized by named capacities ([`config`]: one table of every pool, and
//! [`engine_storage!`] to size an engine's), so an engine can be a `static` and its size
//! is known at compile time. Running out of a pool is a [`CapacityError`] naming the pool
//! and its capacity; the failed operation is undone.
//!
//! # Three stages
//! A construct goes through three stages, each with its own types; data flows down,
//! nothing reaches back up.
//!
//! ```text
//!  CLIPS text (&str)
//!     │  syntax: lexer::Lexer -> parser::Parser (parser::rule for defrule);
//!     │  reads, touches no network
//!     ▼
//!  a rule's intermediate form, whole (every disjunct of an `or`):
//!    parser::rule::Build    one Ce per join to make (kind, parent and right input
//!                           by CE number, join and post tests as expression chains)
//!    parser::rule::PatIr    per pattern: template, alpha tests, multislot layout,
//!                           right hash, path in CLIPS's pattern network
//!    expression nodes       tests and actions (expr::Expr, the Expr pool)
//!     │  compile: compile::Compiler { the pools (Core), where the rule's entries
//!     │  start, the rule it replaces } ; errors are compile::CompileError (pool,
//!     │  CE), placed in the text by the parser
//!     │    compile::alpha   pattern network: sharing, discrimination, order
//!     │    compile::join    joins: sharing of prefixes, the rule, hooking up
//!     │    compile::prime   the root join; new joins and alpha nodes primed
//!     │    compile::remove  rule removal, rollback of a build out of room
//!     ▼
//!  the network: rules (rule::Rule), alpha nodes (rete::AlphaNode + AlphaMem),
//!  joins (rete::Join + JoinMem, by JoinId), primed with the existing facts
//!     │  (host, at build time: Engine::write_compiled -> compiled::RuleBase, Rust
//!     │   constants; Engine::load_compiled puts one into an engine with no parser)
//!     │  run time: rete (match), agenda, eval, builtins, commands (run loop)
//!     ▼
//!  tokens (rete::Token, by TokenId), activations, facts; firings
//! ```
//!
//! A construct the syntax stage refuses leaves nothing in the network, since nothing
//! is built before its form is whole; its expression nodes, symbols and implied
//! templates (append-only pools) are given back. Only a build that runs out of room
//! (a pool, or tokens while priming) is undone in the network (`Core::rollback`).
//! The compile stage holds no lexer and no parser: the parser calls it with a form
//! that is whole ([`parser::Parser`]'s `compiler()`), and `rete` only matches (and
//! notes a join's one-child flag, `note_children`, after compile changes its child
//! list). Pools are indexed by typed handles ([`handle`]: a token's index cannot
//! index the joins).
//!
//! # Layout
//! - [`value`]: values (`Int`, `Float`, symbols, strings, fact addresses, multifield
//!   spans) and CLIPS number printing; [`symbols`]: interned texts.
//! - [`lexer`] and [`parser`]: the syntax stage, CLIPS source to constructs and
//!   expression trees ([`expr`], 8-byte nodes), a rule into its intermediate form.
//!   Each construct is read and built inside a checkpoint and undone on any error.
//! - `compile`: the network builder (alpha nodes, joins, priming) and remover (rule
//!   removal, rollback), on a rule's intermediate form and the pools it edits.
//! - [`handle`]: typed pool indexes (`JoinId`, `TokenId`) and the pool views they
//!   index.
//! - [`compiled`]: the ahead-of-time form: a loaded engine's constructs, compiled
//!   network included, written as Rust constants (`Engine::write_compiled`, at build
//!   time on the host) and loaded into an engine without the parser
//!   (`Engine::load_compiled`); facts built through the API (`Engine::assert_fact`).
//!   The agent image runs from it (features `parser` off, `in-place` on: [`rom`] reads
//!   its entries in place).
//! - [`fact`], [`template`]: fact storage (a compacting value arena, a duplicate hash
//!   index, a creation-ordered list), deftemplates, deffacts, globals, deffunctions.
//! - [`rete`], [`agenda`] and [`strategy`], [`commands`]: matching, conflict
//!   resolution, run loop; [`logical`]: truth maintenance (logical support of facts).
//! - [`builtins`]: the functions, one row each (name, arity, argument types, purity,
//!   value after an error: [`builtins::describe`]), [`eval`]: evaluator.
//! - [`config`]: the pool table, capacities by name; [`engine`]: state, storage and
//!   `Core`, the non-generic view all algorithms run on, so the code exists once
//!   whatever the capacities; [`api`]: the host API, [`host`] and [`host_fn`]: what a
//!   host provides (routers, files, its own functions); [`print`]: CLIPS's printed
//!   forms; [`invariants`]: the consistency checks tests and fuzzing run.
//!
//! # The Rete network
//! - **Alpha nodes** ([`rete::AlphaNode`]): one per distinct pattern (template +
//!   constant tests + tests between fields of the same fact + multislot layout). Rules
//!   using an identical pattern share the node and its **alpha memory** (a list of
//!   alpha-match tokens, oldest first). A template lists its alpha nodes, so an
//!   asserted fact is only tested against patterns of its own template. A pattern with
//!   several multifield variables in one multislot yields one alpha match per
//!   segmentation; the match records the multifield lengths ("marks").
//!   As in CLIPS, the fields a join compares for equality with earlier variables
//!   (the "right hash") are part of the node's identity: `(a ?x)` as a first pattern
//!   and `(a ?x)` joined on `?x` are different nodes. Nodes of a template are kept in
//!   CLIPS's pattern-network order (newer sibling nodes first), which is the order a
//!   fact visits them; a pattern's path there has one level per field with a test of
//!   its own, two for a constant (CLIPS's selector node, shared by every constant on
//!   that field, then the constant).
//! - **Joins** ([`rete::Join`]): each rule is a chain `Root -> CE1 -> ... -> CEn`.
//!   The root holds one empty token. A join combines each token of its parent's output
//!   memory (left) with the alpha matches of its pattern (right) under the join tests
//!   (variables shared with earlier patterns) and keeps the results in its own output
//!   memory. Kinds: `Positive`; `Negative` (`not`: a left token passes while no right
//!   item blocks it); `Exists` (passes while one does); `Test` (a leading `test` CE or
//!   an empty LHS); `Terminal` (a rule's end: its left tokens become activations).
//!   Tests following a `not`/`exists` are post-tests on its output. Joins are shared
//!   between rules with an identical prefix; a rule's terminal never is.
//! - **Blockers**: a not/exists output token is blocked by at most one right item,
//!   the first that matches (the output is on the blocker's `blocks` list). When the
//!   blocker goes, the next matching item in memory order takes over, and only if
//!   there is none the output changes: CLIPS's order of (de)activations.
//! - **Joins from the right**: `not`/`exists` over several CEs (and nested
//!   `not`/`exists`) compile, as in CLIPS, into a subnetwork that starts from the
//!   same left input, plus a not/exists join whose right input is the subnetwork's
//!   last join (`Join::rjoin`; the subnetwork lists it in `rsucc`). A subnetwork
//!   token blocks the output of the left token it extends. The join from the right
//!   sits after the subnetwork's first join among its parent's children, so a new
//!   left token runs through the subnetwork first. The group is one pattern slot
//!   (`*`); `(not (not P))` is compiled as `(exists P)`.
//! - **Incremental**: an assert only visits the alpha nodes of its template; each new
//!   alpha match right-activates the successor joins (newest rule first, as CLIPS
//!   orders them), each new token left-activates the next join. A retract removes the
//!   fact's alpha matches and, through child links kept in every token (left parent,
//!   right alpha match), exactly the partial matches built on them, successor by
//!   successor, oldest first (the order CLIPS made its per-successor copies); then the
//!   not/exists outputs it blocked look for another blocker.
//! - **Rule added while facts exist** (CLIPS's incremental reset): new joins fed by
//!   old ones are primed from the left (each rule from its end upwards, a subnetwork
//!   after the join taking it), then the existing facts, oldest first, are driven
//!   through the rule's new alpha nodes.
//! - **Indexes** ([`rete`]`::index`): the alpha matches of a node with a right hash
//!   are also chained in buckets of one fixed table (`Engine::amem_buckets`, as many
//!   buckets as tokens), keyed by the node and the right-hash values; a join's output
//!   memory is likewise indexed for one child join fed by such a node (the first one,
//!   chosen while the memory is empty), keyed by the values that child's equality
//!   tests read from the left. A left (right) activation visits only the bucket of
//!   its values. Buckets keep memory order, so orders are those of a full scan; join
//!   tests still run on every candidate. The chains live in token fields the token's
//!   kind leaves unused: no allocation, no extra bytes, nothing that can run out.
//! - **Tokens** ([`rete::Token`]): alpha matches and partial matches share one pool;
//!   each partial match stores only its parent and its alpha match, so a match of n
//!   patterns costs n tokens. A terminal token points to its activation.
//! - **Full pools**: an assert or modify that runs out is undone (its removed
//!   activations are journaled and get their creation numbers, hence their agenda
//!   places, back; its watch traces are held back, see [`hold`]). A retract cannot
//!   fail; what it unblocks and cannot rebuild for lack of room is *owed* (an
//!   inactive not output on a list, `Core::pay_owed`) and built by the first
//!   operation with room; until then run fires nothing, and an assert or modify that
//!   runs out fails with no trace but the owed matches it built first.
//! - **Agenda**: activations sorted by salience, then by the strategy ([`strategy`]:
//!   depth, newest first, by default; breadth, lex, mea, complexity, simplicity and
//!   random with `extras`); a fired activation is gone for good (refraction), so a rule fires again
//!   only for a new partial match (e.g. after `modify`, which retracts and re-asserts).
//!
//! # Not supported yet
//! As the README's "Not implemented yet" lists them: COOL, an `or` branch of several
//! CEs under `exists` or two negations (CLIPS takes it; other `or`s under negations are
//! expanded as CLIPS expands them); modules ([`module`]) without the feature `modules`.
//! Each is refused where it is read, with a clear message, never accepted and ignored.
#![no_std]
// With `u32` indices (`value::Ix`) the widening casts and conversions written for `u16`
// indices (`x as u32`, `u32::from(x)`) become identities; they stay for the `u16` build.
#![cfg_attr(
    feature = "wide-index",
    allow(clippy::unnecessary_cast, clippy::useless_conversion)
)]

// only the host's growing storage allocates (`grow`)
#[cfg(feature = "grow")]
extern crate alloc;

pub mod agenda;
pub mod api;
pub mod builtins;
pub mod commands;
pub(crate) mod compile;
pub mod compiled;
pub mod config;
pub mod engine;
pub mod error;
pub mod eval;
pub mod expr;
pub mod fact;
#[cfg(feature = "grow")]
pub mod grow;
pub mod handle;
pub mod hold;
pub mod host;
pub mod host_fn;
pub mod invariants;
pub mod lexer;
pub mod logical;
pub mod module;
pub mod parser;
pub mod print;
pub mod rete;
pub mod rom;
pub mod rule;
pub mod strategy;
pub mod symbols;
pub mod template;
pub mod value;

#[cfg(test)]
pub mod testutil;

pub use api::{FactId, Usage};
pub use builtins::{Args, BuiltinFn};
pub use config::{Capacities, Storage};
pub use engine::{entry_bytes, Core, DefaultEngine, Engine, SmallEngine, Stats};
pub use error::{
    CapacityError, EngineError, EvalError, EvalErrorKind, HostIoError, LoadDetail, LoadError,
    Message, Pool,
};
pub use handle::{JoinId, TokenId};
pub use host::{Host, NullHost, OpenMode};
pub use host_fn::{ExternalFn, HostCall};
pub use invariants::Violation;
pub use parser::INPUT_ENDED;
pub use value::{Ix, Value, ValueRef, NONE};
