//! Deftemplates and their slot definitions. Ordered facts use an implied template with
//! one multislot.

use crate::value::Ix;
use crate::value::{SymId, NONE};

/// Type restriction bits of a slot (`(type ...)`); 0 means any type.
pub mod types {
    pub const SYMBOL: u8 = 1;
    pub const STRING: u8 = 2;
    pub const INTEGER: u8 = 4;
    pub const FLOAT: u8 = 8;
    pub const FACT_ADDRESS: u8 = 16;
    /// Instance names (`[x]`: symbols spelled with brackets here, `value::
    /// instance_name_body`) and instance addresses (no value of ours has that type).
    pub const INSTANCE_NAME: u8 = 32;
    pub const INSTANCE_ADDRESS: u8 = 64;
    pub const NUMBER: u8 = INTEGER | FLOAT;
    pub const LEXEME: u8 = SYMBOL | STRING;
    pub const INSTANCE: u8 = INSTANCE_NAME | INSTANCE_ADDRESS;

    /// The type bit of atom `v` (0 for a multifield or no value); `text` gives a
    /// symbol's spelling, which tells an instance name from a symbol.
    pub fn of<'a>(v: crate::value::Value, text: impl FnOnce(crate::value::SymId) -> &'a str) -> u8 {
        use crate::value::Value;
        match v {
            Value::Int(_) => INTEGER,
            Value::Float(_) => FLOAT,
            Value::Sym(s) if crate::value::instance_name_body(text(s)).is_some() => INSTANCE_NAME,
            Value::Sym(_) => SYMBOL,
            Value::Str(_) => STRING,
            #[cfg(feature = "extras")]
            Value::Fact(crate::value::FactRef::DUMMY_INSTANCE) => INSTANCE_ADDRESS,
            Value::Fact(_) => FACT_ADDRESS,
            _ => 0,
        }
    }
}

/// How a slot gets its value when an assert leaves it out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum DefaultKind {
    /// No `default`: derived from type/allowed values (`nil`, 0, "", first allowed).
    Derived,
    /// `(default expr...)`: evaluated once, when the template is defined.
    Static,
    /// `(default-dynamic expr...)`: evaluated at each assert.
    Dynamic,
    /// `(default ?NONE)`: the slot must be given.
    Required,
}

#[derive(Clone, Copy, Debug)]
pub struct SlotDef {
    pub name: SymId,
    pub multi: bool,
    pub default_kind: DefaultKind,
    /// Chain of expression nodes giving the default (NONE when derived).
    pub default: Ix,
    pub types: u8,
    /// Chain of constant expression nodes (allowed-values etc.), NONE when unrestricted.
    pub allowed: Ix,
    /// Which values the `allowed-...` lists restrict (`allowed` bits): a value of a
    /// restricted type must be one of `allowed`.
    pub allowed_kind: u8,
    /// `(range MIN MAX)`: two constant nodes (min, then max), an unbounded end
    /// (`?VARIABLE`) being the symbol `-oo`/`+oo` as CLIPS keeps it; NONE without one.
    pub range: Ix,
    /// `(cardinality MIN MAX)` of a multislot: two constant nodes, an integer or
    /// `+oo` for an unbounded maximum (an unbounded minimum is 0); NONE without one.
    pub cardinality: Ix,
}

/// `SlotDef::allowed_kind` bits: the values an `allowed-...` list restricts, by type
/// (as CLIPS keeps a restriction flag per type), `VALUES` for every type.
pub mod allowed {
    use super::types;
    pub const VALUES: u8 = 0x80;
    pub const SYMBOLS: u8 = types::SYMBOL;
    pub const STRINGS: u8 = types::STRING;
    pub const LEXEMES: u8 = types::LEXEME;
    pub const INTEGERS: u8 = types::INTEGER;
    pub const FLOATS: u8 = types::FLOAT;
    pub const NUMBERS: u8 = types::NUMBER;
    pub const INSTANCE_NAMES: u8 = types::INSTANCE_NAME;
    /// `allowed-classes` with class names (no list of its own; no `allowed-...`
    /// attribute restricts instance addresses, whose bit this is).
    pub const CLASSES: u8 = types::INSTANCE_ADDRESS;
}

impl SlotDef {
    pub const EMPTY: SlotDef = SlotDef {
        name: 0,
        multi: false,
        default_kind: DefaultKind::Derived,
        default: NONE,
        types: 0,
        allowed: NONE,
        allowed_kind: 0,
        range: NONE,
        cardinality: NONE,
    };
}

/// A deftemplate as compiled: what only the parser and the network compiler write (a
/// compiled rule base's templates are read in place, `crate::rom`). What changes while
/// facts come and go is its [`TemplateMem`], by the same index.
#[derive(Clone, Copy, Debug)]
pub struct Template {
    pub name: SymId,
    pub first_slot: Ix,
    pub nslots: Ix,
    pub implied: bool,
    /// First alpha node testing facts of this template.
    pub alpha_head: Ix,
    /// Source text of the construct in the symbol table (for `ppdeftemplate`), or NONE.
    pub text: Ix,
}

impl Template {
    pub const EMPTY: Template = Template {
        name: 0,
        first_slot: NONE,
        nslots: 0,
        implied: false,
        alpha_head: NONE,
        text: NONE,
    };
}

/// The run-time part of a template (pool "template memories", by template index): its
/// live facts.
#[derive(Clone, Copy, Debug)]
pub struct TemplateMem {
    /// Live facts of this template: a fact-set query over a template without facts
    /// ends at once instead of walking the whole fact list.
    pub nfacts: Ix,
    /// Whether its facts may take part in deferred propagation (`rete::defer`),
    /// worked out for network generation `flags_gen`.
    #[cfg(feature = "defer")]
    pub defer_flags: u8,
    #[cfg(feature = "defer")]
    pub flags_gen: u32,
    /// Host: first and last live fact of this template, linked through `Core::fact_tlinks`.
    #[cfg(feature = "host-speedups")]
    pub tfirst: Ix,
    #[cfg(feature = "host-speedups")]
    pub tlast: Ix,
}

impl TemplateMem {
    pub const EMPTY: TemplateMem = TemplateMem {
        nfacts: 0,
        #[cfg(feature = "defer")]
        defer_flags: 0,
        #[cfg(feature = "defer")]
        flags_gen: 0,
        #[cfg(feature = "host-speedups")]
        tfirst: NONE,
        #[cfg(feature = "host-speedups")]
        tlast: NONE,
    };
}

/// A `deffacts`: a chain of `FactSpec` expressions.
#[derive(Clone, Copy, Debug)]
pub struct Deffacts {
    pub name: SymId,
    pub facts: Ix,
    /// Source text of the construct in the symbol table (for `ppdeffacts`), or NONE.
    pub text: Ix,
}

impl Deffacts {
    pub const EMPTY: Deffacts = Deffacts {
        name: 0,
        facts: NONE,
        text: NONE,
    };
}

/// A `defglobal` variable.
#[derive(Clone, Copy, Debug)]
pub struct Global {
    pub name: SymId,
    pub value: crate::value::Value,
    /// Initial-value expression, re-evaluated at `reset`.
    pub init: Ix,
}

impl Global {
    pub const EMPTY: Global = Global {
        name: 0,
        value: crate::value::Value::Void,
        init: NONE,
    };
}

/// The source text (a symbol) of a deffunction or defglobal, kept for `ppdeffunction`
/// and `ppdefglobal` in side arrays by construct index: only with `extras`, where those
/// commands are; without it the entries are zero-sized (the agent image).
#[cfg(feature = "extras")]
pub type PpText = Ix;
#[cfg(not(feature = "extras"))]
pub type PpText = ();
/// No text kept (a compiled rule base's constructs, pretty-print forms off).
#[cfg(feature = "extras")]
pub const NO_PP_TEXT: PpText = crate::value::NONE;
#[cfg(not(feature = "extras"))]
pub const NO_PP_TEXT: PpText = ();

/// A deffunction's side data, by index, only with `extras` (zero-sized otherwise, the
/// agent image): its source text (as `PpText`), and the deffunction listed at its
/// place in listing order (`list-deffunctions`, `save`, ...): CLIPS lists a redefined
/// deffunction last, while calls keep its index.
#[cfg(feature = "extras")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FnExtras {
    pub text: Ix,
    pub listed: Ix,
}
#[cfg(not(feature = "extras"))]
pub type FnExtras = ();
#[cfg(feature = "extras")]
pub const NO_FN_EXTRAS: FnExtras = FnExtras {
    text: crate::value::NONE,
    listed: crate::value::NONE,
};
#[cfg(not(feature = "extras"))]
pub const NO_FN_EXTRAS: FnExtras = ();

/// A `deffunction`.
#[derive(Clone, Copy, Debug)]
pub struct Deffunction {
    pub name: SymId,
    /// Number of required parameters.
    pub nparams: u8,
    /// Whether the last parameter is a `$?rest` wildcard.
    pub rest: bool,
    /// Frame size: parameters plus `bind` locals.
    pub nlocals: u8,
    /// Body: chain of actions.
    pub body: Ix,
}

impl Deffunction {
    pub const EMPTY: Deffunction = Deffunction {
        name: 0,
        nparams: 0,
        rest: false,
        nlocals: 0,
        body: NONE,
    };
}

/// Without `extras` no source text is kept (`ppdeffunction` and `ppdefglobal`, which
/// read it, are not in the builtin table then).
#[cfg(not(feature = "extras"))]
impl crate::engine::Core<'_> {
    pub fn function_text(&self, _f: Ix) -> Ix {
        NONE
    }

    pub fn global_text(&self, _g: Ix) -> Ix {
        NONE
    }

    pub fn slot_facets(&self, _s: Ix) -> Ix {
        NONE
    }

    pub fn function_listed(&self, p: Ix) -> Ix {
        p
    }
}

/// The kept source texts of deffunctions and defglobals (`PpText`).
#[cfg(feature = "extras")]
impl crate::engine::Core<'_> {
    /// Deffunction `f`'s source text (NONE when not kept).
    pub fn function_text(&self, f: Ix) -> Ix {
        self.func_extras.get(f as usize).map_or(NONE, |e| e.text)
    }

    /// Records deffunction `f`'s source text (dropped past the side array's end).
    pub fn set_function_text(&mut self, f: Ix, text: Ix) {
        if let Some(e) = self.func_extras.get_mut(f as usize) {
            e.text = text;
        }
    }

    /// The deffunction listed at place `p` (`p` itself past the last place or the
    /// side array's end).
    pub fn function_listed(&self, p: Ix) -> Ix {
        let n = self.st.pools.nfuncs;
        match self.func_extras.get(p as usize) {
            Some(e) if p < n && e.listed < n => e.listed,
            _ => p,
        }
    }

    /// Sets the deffunction listed at place `p` (a compiled rule base's order).
    pub fn set_function_listed(&mut self, p: Ix, f: Ix) {
        if let Some(e) = self.func_extras.get_mut(p as usize) {
            e.listed = f;
        }
    }

    /// Lists deffunction `f` last (a redefinition, as CLIPS moves it), or first
    /// lists new deffunction `f` (`f` is `nfuncs - 1`).
    pub fn list_function_last(&mut self, f: Ix) {
        let n = (self.st.pools.nfuncs as usize).min(self.func_extras.len());
        let Some(last) = n.checked_sub(1) else {
            return;
        };
        let ex = &mut self.func_extras[..n];
        let at = ex[..last]
            .iter()
            .position(|e| e.listed == f)
            .unwrap_or(last);
        for p in at..last {
            ex[p].listed = ex[p + 1].listed;
        }
        ex[last].listed = f;
    }

    /// Drops the deffunctions from `n` on from the listing order (a failed construct's
    /// new ones given back; the order of the others stays).
    pub fn truncate_function_listing(&mut self, from: usize, n: Ix) {
        let from = from.min(self.func_extras.len());
        let mut k = 0;
        for p in 0..from {
            let f = self.func_extras[p].listed;
            if f < n {
                self.func_extras[k].listed = f;
                k += 1;
            }
        }
    }

    /// Defglobal `g`'s source text from its `?*name*` (NONE when not kept).
    pub fn global_text(&self, g: Ix) -> Ix {
        self.global_text.get(g as usize).copied().unwrap_or(NONE)
    }

    /// Records defglobal `g`'s source text (dropped past the side array's end).
    pub fn set_global_text(&mut self, g: Ix, text: Ix) {
        if let Some(e) = self.global_text.get_mut(g as usize) {
            *e = text;
        }
    }

    /// Slot definition `s`'s first facet node ([`facet`]; NONE: none).
    pub fn slot_facets(&self, s: Ix) -> Ix {
        self.slot_facets.get(s as usize).copied().unwrap_or(NONE)
    }

    /// Records slot definition `s`'s facets (false past the side array's end).
    pub fn set_slot_facets(&mut self, s: Ix, first: Ix) -> bool {
        match self.slot_facets.get_mut(s as usize) {
            Some(e) => {
                *e = first;
                true
            }
            None => first == NONE,
        }
    }
}

/// A slot's `(facet NAME VALUE)` and `(multifacet NAME VALUE...)` attributes (agent-core
/// feature `extras`; kept for `deftemplate-slot-facet-existp`/`-value`, which CLIPS 6.30
/// answers from them and nothing else reads): one `Op::Sym` node per facet, `data` its
/// name, `aux` [`facet::MULTI`] for a multifacet, `first` its chain of constant nodes,
/// `next` the slot's next facet.
pub mod facet {
    /// `aux` of a multifacet's node: its value is the multifield of its constants.
    pub const MULTI: u8 = 1;
}
