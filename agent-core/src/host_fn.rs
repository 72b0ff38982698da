//! Functions the host registers ([`Engine::register_function`](crate::Engine)): what
//! they see of the engine is a [`HostCall`], their arguments and a few services
//! (symbols, facts, output, building a result), never the engine's pools or state, so
//! the engine's layout can change without touching a host.

use crate::api::FactId;
use crate::builtins::Args;
use crate::engine::{cap, Core};
use crate::error::{CapacityError, EvalError, Pool};
use crate::fact::{Fact, FactState};
use crate::rom::RomRef;
use crate::template::{SlotDef, Template};
use crate::value::{Ix, MfSpan, SymId, Value, ValueRef, NONE};

/// A host-registered function: reads its arguments from the call, returns its value.
pub type ExternalFn = fn(&mut HostCall<'_, '_>) -> Result<Value, EvalError>;

/// One call of a host function: its arguments and what it may use of the engine.
pub struct HostCall<'a, 'c> {
    cx: &'a mut Core<'c>,
    args: Args,
}

impl<'a, 'c> HostCall<'a, 'c> {
    pub(crate) fn new(cx: &'a mut Core<'c>, args: Args) -> Self {
        HostCall { cx, args }
    }

    /// Number of arguments.
    pub fn len(&self) -> usize {
        self.args.len as usize
    }

    pub fn is_empty(&self) -> bool {
        self.args.len == 0
    }

    /// Argument `i` (from 0); `None` past the last. Symbols and strings are ids (read
    /// their text with [`HostCall::text`]), a multifield a span ([`HostCall::item`]).
    pub fn arg(&self, i: usize) -> Option<Value> {
        (i < self.len()).then(|| self.cx.stack[self.args.base as usize + i])
    }

    /// Argument `i` with its text (symbols, strings) or length (multifields).
    pub fn arg_ref(&self, i: usize) -> Option<ValueRef<'_>> {
        let v = self.arg(i)?;
        Some(self.facts().value_ref(v))
    }

    /// Text of a symbol or string value.
    pub fn text(&self, v: Value) -> Option<&str> {
        match v {
            Value::Sym(s) | Value::Str(s) => Some(self.cx.sym_text(s)),
            _ => None,
        }
    }

    /// Element `i` of a multifield value (an argument or one this call built).
    pub fn item(&self, v: Value, i: usize) -> Option<Value> {
        match v {
            Value::Multi(m) if i < m.len as usize => {
                self.cx.scratch.get(m.start as usize + i).copied()
            }
            _ => None,
        }
    }

    /// A symbol with this text, as a result or to compare with arguments.
    pub fn symbol(&mut self, text: &str) -> Result<Value, CapacityError> {
        Ok(Value::Sym(self.cx.intern(text)?))
    }

    /// A string with this text.
    pub fn string(&mut self, text: &str) -> Result<Value, CapacityError> {
        Ok(Value::Str(self.cx.intern(text)?))
    }

    /// A multifield of these atoms (a multifield among them is refused).
    pub fn multifield(&mut self, items: &[Value]) -> Result<Value, CapacityError> {
        if items.iter().any(|v| matches!(v, Value::Multi(_))) || items.len() >= NONE as usize {
            return Err(cap(Pool::Scratch, self.cx.scratch.len()));
        }
        let start = self.cx.scratch_alloc(items.len())?;
        self.cx.scratch[start as usize..start as usize + items.len()].copy_from_slice(items);
        Ok(Value::Multi(MfSpan {
            start,
            len: items.len() as Ix,
        }))
    }

    /// Live facts, oldest first.
    pub fn fact_ids(&self) -> impl Iterator<Item = FactId> + '_ {
        self.facts().ids()
    }

    /// Template (relation) name of a live fact.
    pub fn fact_template_name(&self, id: FactId) -> Option<&str> {
        self.facts().template_name(id)
    }

    /// A slot of a live fact (`implied` for ordered facts); a multislot reads as
    /// `Multi(len)`, its elements through [`HostCall::fact_multislot_item`].
    pub fn fact_slot(&self, id: FactId, slot: &str) -> Option<ValueRef<'_>> {
        self.facts().slot(id, slot)
    }

    pub fn fact_multislot_item(&self, id: FactId, slot: &str, i: usize) -> Option<ValueRef<'_>> {
        self.facts().multislot_item(id, slot, i)
    }

    /// Writes `text` to a router (`t`, `stdout`, `werror`, ...) through the host.
    pub fn write(&mut self, router: &str, text: &str) {
        self.cx.write(router, text);
    }

    fn facts(&self) -> FactView<'_> {
        FactView {
            facts: &self.cx.facts[..],
            templates: self.cx.templates.as_ref(),
            slots: self.cx.slots.as_ref(),
            values: &self.cx.values[..],
            syms: self.cx.sym_texts(),
            head: self.cx.st.facts.fact_head,
        }
    }
}

/// Read-only access to the facts by number and slot name (the host API's and a host
/// function's view).
pub(crate) struct FactView<'a> {
    pub(crate) facts: &'a [Fact],
    pub(crate) templates: RomRef<'a, Template>,
    pub(crate) slots: RomRef<'a, SlotDef>,
    pub(crate) values: &'a [Value],
    pub(crate) syms: crate::symbols::SymTexts<'a>,
    /// First fact of the creation-ordered list.
    pub(crate) head: Ix,
}

impl<'a> FactView<'a> {
    pub(crate) fn text(&self, id: SymId) -> &'a str {
        self.syms.text(id)
    }

    pub(crate) fn value_ref(&self, v: Value) -> ValueRef<'a> {
        match v {
            Value::Int(i) => ValueRef::Int(i),
            Value::Float(f) => ValueRef::Float(f),
            Value::Sym(s) => ValueRef::Symbol(self.text(s)),
            Value::Str(s) => ValueRef::String(self.text(s)),
            Value::Fact(r) => ValueRef::Fact(r.num),
            Value::Multi(m) => ValueRef::Multi(m.len),
            Value::Void | Value::BoundVoid => ValueRef::Void,
        }
    }

    pub(crate) fn ids(&self) -> impl Iterator<Item = FactId> + 'a {
        let (facts, mut f) = (self.facts, self.head);
        core::iter::from_fn(move || {
            if f == NONE {
                return None;
            }
            let x = facts[f as usize];
            f = x.next;
            Some(FactId(x.num))
        })
    }

    /// Live facts of the template named `name`, in index order: one walk of the list
    /// (asking each id's template name walks it once per id).
    pub(crate) fn ids_of(&self, name: &'a str) -> impl Iterator<Item = FactId> + 'a {
        let (facts, templates, syms, mut f) = (self.facts, self.templates, self.syms, self.head);
        // The last template looked at and whether its name is `name`.
        let mut last: Option<(Ix, bool)> = None;
        core::iter::from_fn(move || {
            while f != NONE {
                let x = facts[f as usize];
                f = x.next;
                if x.state != FactState::Live {
                    continue;
                }
                let hit = match last {
                    Some((t, hit)) if t == x.tmpl => hit,
                    _ => {
                        let hit = syms.is(templates[x.tmpl as usize].name, name);
                        last = Some((x.tmpl, hit));
                        hit
                    }
                };
                if hit {
                    return Some(FactId(x.num));
                }
            }
            None
        })
    }

    fn find(&self, id: FactId) -> Option<Ix> {
        let mut f = self.head;
        while f != NONE {
            let x = self.facts[f as usize];
            if x.num == id.0 && x.state == FactState::Live {
                return Some(f);
            }
            f = x.next;
        }
        None
    }

    pub(crate) fn template_name(&self, id: FactId) -> Option<&'a str> {
        let f = self.find(id)?;
        let t = self.templates[self.facts[f as usize].tmpl as usize];
        Some(self.text(t.name))
    }

    /// The cell of a fact's slot, and its length if it is a multislot.
    fn slot_cell(&self, id: FactId, slot: &str) -> Option<(usize, Option<Ix>)> {
        let f = self.find(id)?;
        let fact = self.facts[f as usize];
        let t = self.templates[fact.tmpl as usize];
        let idx = if t.implied {
            0
        } else {
            (0..t.nslots)
                .find(|&i| self.text(self.slots[(t.first_slot + i) as usize].name) == slot)?
        };
        let mut c = fact.start as usize;
        for _ in 0..idx {
            match self.values[c] {
                Value::Multi(m) => c += 1 + m.len as usize,
                _ => c += 1,
            }
        }
        match self.values[c] {
            Value::Multi(m) => Some((c, Some(m.len))),
            _ => Some((c, None)),
        }
    }

    pub(crate) fn slot(&self, id: FactId, slot: &str) -> Option<ValueRef<'a>> {
        let (cell, multi) = self.slot_cell(id, slot)?;
        match multi {
            Some(n) => Some(ValueRef::Multi(n)),
            None => Some(self.value_ref(self.values[cell])),
        }
    }

    pub(crate) fn multislot_item(&self, id: FactId, slot: &str, i: usize) -> Option<ValueRef<'a>> {
        let (cell, multi) = self.slot_cell(id, slot)?;
        if i >= multi? as usize {
            return None;
        }
        Some(self.value_ref(self.values[cell + 1 + i]))
    }
}
