//! The writer: a loaded engine's constructs as Rust source (a [`RuleBase`] `static`).
//!
//! [`RuleBase`]: super::RuleBase

use crate::config::Storage;
use crate::engine::{Core, Engine};
use crate::expr::{FnKind, Op};
use crate::handle::JoinId;
use crate::host::NullHost;
use crate::value::{Ix, Value, NONE};
use core::fmt::{self, Write};

/// Why a rule base could not be written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteError {
    /// Loading the constructs left facts besides `(initial-fact)` (a parse-time
    /// evaluation asserted them): facts are working memory, not part of a compiled
    /// rule base.
    FactsLeft,
    /// The module name is not a Rust identifier.
    BadName,
    /// The output refused the text.
    Output,
    /// A rule uses `logical`: a compiled rule base keeps no logical joins (the agent
    /// image has no truth maintenance).
    Logical,
    /// A defmodule besides the MAIN made at start-up: a compiled rule base keeps no
    /// modules (its constructs are all MAIN's, as the agent image has them).
    Modules,
    /// An engine with `grow` took a construct past one of the image's fixed limits
    /// (named): the image could not hold the rule base, nor would an engine without
    /// `grow` have loaded the same constructs.
    PastImageLimit(&'static str),
}

impl From<fmt::Error> for WriteError {
    fn from(_: fmt::Error) -> Self {
        WriteError::Output
    }
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::FactsLeft => write!(
                f,
                "loading the constructs left facts besides (initial-fact): a compiled \
                 rule base holds no facts"
            ),
            WriteError::BadName => write!(f, "the module name is not a Rust identifier"),
            WriteError::Output => write!(f, "the output refused the text"),
            WriteError::Logical => write!(
                f,
                "a rule uses the logical CE: compiled rule bases have no truth maintenance"
            ),
            WriteError::Modules => write!(
                f,
                "a defmodule besides MAIN: compiled rule bases hold the MAIN module only"
            ),
            WriteError::PastImageLimit(what) => write!(
                f,
                "{what}: compiled rule bases keep the image's fixed limits"
            ),
        }
    }
}

impl<S: Storage> Engine<S> {
    /// Writes this engine's constructs as Rust source: `pub mod {module} { pub static
    /// BASE: RuleBase = ...; }`, for a crate that depends on `agent_core` (see
    /// [`crate::compiled`]). The engine should hold just what loading the rule files
    /// made: its working memory is not written.
    pub fn write_compiled(
        &mut self,
        module: &str,
        source: &str,
        out: &mut dyn Write,
    ) -> Result<(), WriteError> {
        let mut host = NullHost;
        let cx = self.core(&mut host);
        cx.write_compiled(module, source, out)
    }
}

/// An index, `N` for NONE.
struct I(Ix);

impl fmt::Display for I {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0 == NONE {
            f.write_str("N")
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// 16 bits of a constant, written as they are (`0xFFFF` too, which a narrow build's
/// NONE equals); a wide build's NONE, which no 16 bits equal (a payload node that
/// holds no constant), as `N`, so the text is the same from either width.
struct Bits(Ix);

impl fmt::Display for Bits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if u64::from(self.0) > 0xFFFF {
            f.write_str("N")
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// A join, `j(3)`, or `JN` for none.
struct J(JoinId);

impl fmt::Display for J {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0 == JoinId::NONE {
            f.write_str("JN")
        } else {
            write!(f, "j({})", self.0 .0)
        }
    }
}

/// The first `len` entries of an array of 16-bit values that are not indices (field
/// locators, hashes), written as they are, since in a narrow build `0xFFFF` equals NONE
/// and `N` would load as a wide build's NONE; the unused rest as indices (`N` padding).
struct Raw<'a>(&'a [Ix], usize);

impl fmt::Display for Raw<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (i, &x) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            if i < self.1 {
                write!(f, "{x}")?;
            } else {
                write!(f, "{}", I(x))?;
            }
        }
        f.write_str("]")
    }
}

/// An array of indices.
struct Is<'a>(&'a [Ix]);

impl fmt::Display for Is<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (k, &x) in self.0.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{}", I(x))?;
        }
        f.write_str("]")
    }
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_lowercase() || c == '_')
        && chars.all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

impl Core<'_> {
    /// See [`Engine::write_compiled`].
    pub fn write_compiled(
        &self,
        module: &str,
        source: &str,
        out: &mut dyn Write,
    ) -> Result<(), WriteError> {
        if !is_ident(module) {
            return Err(WriteError::BadName);
        }
        #[cfg(feature = "logical")]
        for r in 0..self.st.pools.nrules {
            if !self.rules[r as usize].deleted && self.rule_logical_join(r).is_some() {
                return Err(WriteError::Logical);
            }
        }
        #[cfg(feature = "modules")]
        if self.st.modules.nmodules > 1 || self.st.modules.nports > 0 {
            return Err(WriteError::Modules);
        }
        #[cfg(feature = "grow")]
        if let Some(what) = self.st.eval.past_image {
            return Err(WriteError::PastImageLimit(what));
        }
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            if self.facts[f as usize].tmpl != self.st.facts.initial_tmpl {
                return Err(WriteError::FactsLeft);
            }
            f = self.facts[f as usize].next;
        }
        writeln!(
            out,
            "/// Rule base `{source}`, compiled ahead of time (generated by \
             `agent_core::Engine::write_compiled`; do not edit)."
        )?;
        writeln!(out, "#[rustfmt::skip]")?;
        writeln!(out, "pub mod {module} {{")?;
        writeln!(out, "#[allow(unused_imports)]")?;
        writeln!(out, "use agent_core::compiled::gen::*;")?;
        self.write_builtin_ids(out)?;
        self.write_symbol_statics(out)?;
        writeln!(out, "pub static BASE: RuleBase = RuleBase {{")?;
        writeln!(out, "name: {source:?},")?;
        self.write_symbols(out)?;
        self.write_templates(out)?;
        self.write_rules(out)?;
        self.write_alphas(out)?;
        self.write_joins(out)?;
        self.write_exprs(out)?;
        self.write_functions(out)?;
        writeln!(out, "externals: &[")?;
        for x in &self.externals[..self.st.pools.nexternals as usize] {
            writeln!(out, "{:?},", self.sym_text(x.name))?;
        }
        writeln!(out, "],")?;
        writeln!(out, "trie_ids: {},", self.st.pools.trie_ids)?;
        writeln!(out, "gensym_next: {},", self.st.eval.gensym_next)?;
        writeln!(out, "code: &CODE,")?;
        writeln!(out, "}};")?;
        // only the builtins called: an image links no other
        write!(out, "static CODE: [Imp; COUNT] = code_for(&[")?;
        for id in 0..crate::builtins::BUILTINS.len() {
            if self.calls_builtin(id) {
                write!(out, "B{id}, ")?;
            }
        }
        writeln!(out, "]);")?;
        writeln!(
            out,
            "pub const SIZES: Sizes = Sizes {{ symbols: {}, symbol_bytes: {}, templates: {}, \
             slots: {}, rules: {}, alphas: {}, joins: {}, exprs: {}, functions: {}, \
             globals: {}, deffacts: {} }};",
            self.st.pools.nsyms,
            self.st.pools.sym_bytes,
            self.st.pools.ntemplates,
            self.st.pools.nslots,
            self.st.pools.nrules,
            self.st.pools.nalpha,
            self.st.pools.njoins,
            self.st.pools.nexprs,
            self.st.pools.nfuncs,
            self.st.pools.nglobals,
            self.st.pools.ndeffacts
        )?;
        writeln!(out, "}}")?;
        Ok(())
    }

    /// Whether some node calls builtin `id`, or its twin (`builtins::ordered`, which
    /// runs the original's code).
    fn calls_builtin(&self, id: usize) -> bool {
        let twin = crate::builtins::ordered::twin_of(id as Ix).map_or(usize::MAX, |t| t as usize);
        (0..self.st.pools.nexprs as usize).any(|e| {
            let x = self.exprs[e];
            x.op == Op::Call
                && x.aux == FnKind::Builtin as u8
                && (x.data as usize == id || x.data as usize == twin)
        })
    }

    /// A constant per builtin called: `const B12: Ix = builtin_id("str-cat");`, a twin
    /// named by its original: `const B201: Ix = ordered_twin(builtin_id("+"));`.
    fn write_builtin_ids(&self, out: &mut dyn Write) -> fmt::Result {
        let n = crate::builtins::BUILTINS.len();
        for id in 0..n {
            if self.calls_builtin(id) {
                let name = crate::builtins::get(id as Ix).name;
                if crate::builtins::ordered::is_twin(id as Ix) {
                    writeln!(out, "const B{id}: Ix = ordered_twin(builtin_id({name:?}));")?;
                } else {
                    writeln!(out, "const B{id}: Ix = builtin_id({name:?});")?;
                }
            }
        }
        Ok(())
    }

    /// The symbols' texts and their hash chains, as statics before the rule base.
    fn write_symbol_statics(&self, out: &mut dyn Write) -> fmt::Result {
        let n = self.st.pools.nsyms;
        writeln!(out, "static SYMBOLS: [&str; {n}] = [")?;
        for id in 0..n {
            writeln!(out, "{:?},", self.sym_text(id))?;
        }
        writeln!(out, "];")?;
        writeln!(
            out,
            "static SYMBOL_INDEX: SymbolIndex<{n}> = SymbolIndex::new(&SYMBOLS);"
        )
    }

    fn write_symbols(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "symbols: &SYMBOLS,")?;
        writeln!(out, "symbol_buckets: &SYMBOL_INDEX.buckets,")?;
        writeln!(out, "symbol_next: &SYMBOL_INDEX.next,")
    }

    fn write_templates(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "templates: &[")?;
        for t in self
            .templates
            .iter()
            .take(self.st.pools.ntemplates as usize)
        {
            writeln!(
                out,
                "Template {{ name: {}, first_slot: {}, nslots: {}, implied: {}, \
                 alpha_head: {}, text: {} }},",
                I(t.name),
                I(t.first_slot),
                t.nslots,
                t.implied,
                I(t.alpha_head),
                I(t.text)
            )?;
        }
        writeln!(out, "],")?;
        writeln!(out, "slots: &[")?;
        for s in self.slots.iter().take(self.st.pools.nslots as usize) {
            writeln!(
                out,
                "SlotDef {{ name: {}, multi: {}, default_kind: DefaultKind::{:?}, \
                 default: {}, types: {}, allowed: {}, allowed_kind: {}, range: {}, \
                 cardinality: {} }},",
                I(s.name),
                s.multi,
                s.default_kind,
                I(s.default),
                s.types,
                I(s.allowed),
                s.allowed_kind,
                I(s.range),
                I(s.cardinality)
            )?;
        }
        writeln!(out, "],")?;
        writeln!(out, "deffacts: &[")?;
        for d in &self.deffacts[..self.st.pools.ndeffacts as usize] {
            writeln!(
                out,
                "Deffacts {{ name: {}, facts: {}, text: {} }},",
                I(d.name),
                I(d.facts),
                I(d.text)
            )?;
        }
        writeln!(out, "],")
    }

    fn write_rules(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "rules: &[")?;
        for r in self.rules.iter().take(self.st.pools.nrules as usize) {
            writeln!(
                out,
                "Rule {{ name: {}, salience: {}, salience_expr: {}, root: {}, terminal: {}, \
                 rhs: {}, npat: {}, nlocals: {}, next_disjunct: {}, next_at_join: {}, \
                 root_sensitive: {}, deleted: {}, text: {}, complexity: {} }},",
                I(r.name),
                r.salience,
                I(r.salience_expr),
                J(r.root),
                J(r.terminal),
                I(r.rhs),
                r.npat,
                r.nlocals,
                I(r.next_disjunct),
                I(r.next_at_join),
                r.root_sensitive,
                r.deleted,
                I(r.text),
                r.complexity
            )?;
        }
        writeln!(out, "],")
    }

    fn write_alphas(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "alphas: &[")?;
        for i in 0..self.st.pools.nalpha as usize {
            let a = &self.alphas[i];
            writeln!(
                out,
                "AlphaNode {{ tmpl: {}, desc: {}, tests: {}, next_in_tmpl: {}, succ: {}, \
                 nmarks: {}, live: {}, path_loc: {}, path_test: {}, \
                 key: {}, key_len: {}, rhash: {}, nrhash: {}, ..AlphaNode::EMPTY }},",
                I(a.tmpl),
                I(a.desc),
                I(a.tests),
                I(a.next_in_tmpl),
                J(a.succ),
                a.nmarks,
                a.live,
                Raw(&a.path_loc, a.key_len as usize),
                Raw(&a.path_test, a.key_len as usize),
                Raw(&a.key, a.key_len as usize),
                a.key_len,
                Is(&a.rhash),
                a.nrhash
            )?;
        }
        writeln!(out, "],")
    }

    fn write_joins(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "joins: &[")?;
        for i in 0..self.st.pools.njoins as usize {
            let j = &self.joins[JoinId::at(i)];
            writeln!(
                out,
                "Join {{ kind: JoinKind::{:?}, depth: {}, rule: {}, parent: {}, \
                 first_child: {}, next_sibling: {}, refs: {}, alpha: {}, tests: {}, \
                 post: {}, alpha_next: {}, rjoin: {}, rsucc: {}, index_child: {} }},",
                j.kind,
                j.depth,
                I(j.rule),
                J(j.parent),
                J(j.first_child),
                J(j.next_sibling),
                I(j.refs),
                I(j.alpha),
                I(j.tests),
                I(j.post),
                J(j.alpha_next),
                J(j.rjoin),
                J(j.rsucc),
                J(j.index_child)
            )?;
        }
        writeln!(out, "],")
    }

    fn write_exprs(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "exprs: &[")?;
        for e in 0..self.st.pools.nexprs as usize {
            let x = self.exprs[e];
            write!(out, "e(Op::{:?}, {}, ", x.op, x.aux)?;
            if x.op == Op::Call && x.aux == FnKind::Builtin as u8 {
                write!(out, "B{}", x.data)?;
            } else if matches!(x.op, Op::Payload | Op::Int | Op::Float | Op::PatVar) {
                // 16 bits of a constant, or a field locator (`loc::FACT` is 0xFFFF in
                // every index width): never an index, so never `N`
                write!(out, "{}", Bits(x.data))?;
            } else {
                write!(out, "{}", I(x.data))?;
            }
            if x.op == Op::Payload {
                // the other 32 bits of the constant
                writeln!(out, ", {}, {}),", Bits(x.first), Bits(x.next))?;
            } else {
                writeln!(out, ", {}, {}),", I(x.first), I(x.next))?;
            }
        }
        writeln!(out, "],")
    }

    fn write_functions(&self, out: &mut dyn Write) -> fmt::Result {
        writeln!(out, "functions: &[")?;
        for d in &self.funcs[..self.st.pools.nfuncs as usize] {
            writeln!(
                out,
                "Deffunction {{ name: {}, nparams: {}, rest: {}, nlocals: {}, body: {} }},",
                I(d.name),
                d.nparams,
                d.rest,
                d.nlocals,
                I(d.body)
            )?;
        }
        writeln!(out, "],")?;
        writeln!(out, "globals: &[")?;
        for g in &self.globals[..self.st.pools.nglobals as usize] {
            write!(out, "Global {{ name: {}, value: ", I(g.name))?;
            match g.value {
                Value::Int(i) => write!(out, "Value::Int({i})")?,
                Value::Float(x) => write!(out, "Value::Float(f64::from_bits({:#x}))", x.to_bits())?,
                Value::Sym(s) => write!(out, "Value::Sym({s})")?,
                Value::Str(s) => write!(out, "Value::Str({s})")?,
                // multifields live in scratch, fact addresses in working memory: the
                // loader evaluates the initial value again
                Value::Multi(_) | Value::Fact(_) | Value::Void | Value::BoundVoid => {
                    write!(out, "Value::Void")?
                }
            }
            writeln!(out, ", init: {} }},", I(g.init))?;
        }
        writeln!(out, "],")?;
        let nfuncs = self.st.pools.nfuncs as Ix;
        let nglobals = self.st.pools.nglobals as Ix;
        self.write_texts(out, "function_texts", nfuncs, |f| self.function_text(f))?;
        self.write_texts(out, "global_texts", nglobals, |g| self.global_text(g))?;
        let nslots = self.st.pools.nslots as Ix;
        self.write_texts(out, "slot_facets", nslots, |s| self.slot_facets(s))?;
        write!(out, "function_order: &[")?;
        if (0..nfuncs).any(|p| self.function_listed(p) != p) {
            for p in 0..nfuncs {
                write!(out, "{}, ", self.function_listed(p))?;
            }
        }
        writeln!(out, "],")
    }

    /// `field: &[...]`, the kept source texts of `n` constructs, or `&[]` when none
    /// is kept (a base without pretty-print forms stores nothing for them).
    fn write_texts(
        &self,
        out: &mut dyn Write,
        field: &str,
        n: Ix,
        text: impl Fn(Ix) -> Ix,
    ) -> fmt::Result {
        write!(out, "{field}: &[")?;
        if (0..n).any(|i| text(i) != NONE) {
            for i in 0..n {
                write!(out, "{}, ", I(text(i)))?;
            }
        }
        writeln!(out, "],")
    }
}
