//! A rule base compiled ahead of time: the constructs of a loaded engine as Rust
//! constants, and the loader that puts them into another engine.
//!
//! The compiled form is the network *after* compilation, not the text or the parser's
//! intermediate form: the used part of every construct pool (symbols, templates and
//! their slots, rules, alpha nodes, joins, expression nodes, deffunctions, globals,
//! deffacts) in the engine's own entry types, which hold no working memory (alpha,
//! join and template memories are pools of their own). So the engine that
//! loads it holds exactly the network the parser built, and a robot image that loads
//! it needs no parser and no rule text.
//!
//! ```text
//!  host (build script):  .clp text ──parse──▶ Engine ──write_compiled──▶ Rust source
//!  image / host:         RuleBase (static) ──load_compiled──▶ Engine ──reset, run──▶
//! ```
//!
//! Independent of the engine's features and index width: the writer names every field
//! the network needs (what changes at run time, memories and the host's caches, is in
//! pools of its own: `rete::AlphaMem`, `rete::JoinMem`, `template::TemplateMem`), writes `N` for [`NONE`](crate::NONE)
//! and names builtins, not their table positions (`builtin_id("str-cat")`, worked out
//! when the generated code compiles: a builtin the loading engine lacks does not
//! compile). Host functions are named too and found among the loading engine's
//! registered functions.
//!
//! What loading gives: the state the parser leaves after the same constructs (the
//! loader rebuilds the start-up matches, f-0 and the rules that start with `not`,
//! `exists` or `test`, and orders their activations by rule, as the parser primed
//! them one after another, each partial match's list of them too; a deffacts named
//! `initial-fact` replaces CLIPS's own, as when parsed). A rule base
//! whose parse left facts behind (a global's initial value that asserts) is refused by
//! the writer, since facts are not part of the compiled form.

mod assert;
mod load;
mod write;

pub use load::CompiledError;
pub use write::WriteError;

use crate::expr::Expr;
use crate::rete::{AlphaNode, Join};
use crate::rule::Rule;
use crate::template::{Deffacts, Deffunction, Global, SlotDef, Template};
use crate::value::Ix;

/// A rule base compiled ahead of time (see the [module docs](self)): generated Rust
/// source (`Engine::write_compiled`) defines one as a `static`, and
/// `Engine::load_compiled` puts it into an engine.
#[derive(Clone, Copy)]
pub struct RuleBase {
    /// What it was compiled from (for messages).
    pub name: &'static str,
    /// Every symbol and string, by id (the fixed start-up symbols first).
    pub symbols: &'static [&'static str],
    /// Their hash chains (`symbols::SymbolIndex`, worked out when the generated code
    /// compiles), for reading them in place (feature `in-place`).
    pub symbol_buckets: &'static [Ix],
    pub symbol_next: &'static [Ix],
    pub templates: &'static [Template],
    pub slots: &'static [SlotDef],
    pub rules: &'static [Rule],
    pub alphas: &'static [AlphaNode],
    pub joins: &'static [Join],
    pub exprs: &'static [Expr],
    pub functions: &'static [Deffunction],
    pub globals: &'static [Global],
    /// Each deffunction's and defglobal's source text (a symbol, NONE for none), by
    /// index, for `ppdeffunction` and `ppdefglobal`; empty when no text was kept
    /// (pretty-print forms off, or no `extras`).
    pub function_texts: &'static [Ix],
    pub global_texts: &'static [Ix],
    /// Each slot definition's first facet node (`template::facet`, NONE for none), by
    /// index; empty when no slot has one (or without `extras`).
    pub slot_facets: &'static [Ix],
    /// The deffunctions' indices in listing order (`list-deffunctions`: a redefined
    /// one is listed last); empty when that is index order.
    pub function_order: &'static [Ix],
    pub deffacts: &'static [Deffacts],
    /// Names of the host functions, by the index calls of kind `External` hold.
    pub externals: &'static [&'static str],
    /// Ids given to pattern-network nodes so far (`State::trie_ids`).
    pub trie_ids: Ix,
    /// `gensym`'s next number: a static slot default evaluated while parsing may have
    /// called it, and what loads next must not make the same symbols again.
    pub gensym_next: u32,
    /// The code of the builtins it calls, by id (`builtins::code_for`): an engine
    /// without the feature `parser` runs these and links no other builtin.
    pub code: &'static [crate::builtins::Imp],
}

/// How many entries a compiled rule base fills in each construct pool, as constants
/// (generated next to its `BASE` as `SIZES`): an engine sized for exactly one rule base
/// (the agent image) names its capacities from them plus what the game adds at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sizes {
    pub symbols: usize,
    /// Bytes of symbol text.
    pub symbol_bytes: usize,
    pub templates: usize,
    pub slots: usize,
    pub rules: usize,
    pub alphas: usize,
    pub joins: usize,
    pub exprs: usize,
    pub functions: usize,
    pub globals: usize,
    pub deffacts: usize,
}

/// What generated code uses: `use agent_core::compiled::gen::*;`.
pub mod gen {
    pub use super::{RuleBase, Sizes};
    pub use crate::builtins::ordered::ordered_twin;
    pub use crate::builtins::{builtin_id, code_for, Imp, COUNT};
    pub use crate::expr::{Expr, Op};
    pub use crate::handle::JoinId;
    pub use crate::rete::{AlphaNode, Join, JoinKind};
    pub use crate::rule::Rule;
    pub use crate::symbols::SymbolIndex;
    pub use crate::template::{DefaultKind, Deffacts, Deffunction, Global, SlotDef, Template};
    pub use crate::value::{Ix, Value};

    /// [`NONE`](crate::NONE), short: generated tables hold many.
    pub const N: Ix = crate::value::NONE;
    /// No join, short.
    pub const JN: JoinId = JoinId::NONE;

    /// A join, short.
    pub const fn j(i: Ix) -> JoinId {
        JoinId(i)
    }

    /// An expression node, short.
    pub const fn e(op: Op, aux: u8, data: Ix, first: Ix, next: Ix) -> Expr {
        Expr {
            op,
            aux,
            data,
            first,
            next,
        }
    }
}

#[cfg(test)]
mod tests;
