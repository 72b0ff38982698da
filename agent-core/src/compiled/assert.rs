//! Facts built through the API, without the parser: what a host with a compiled rule
//! base (and no parser) asserts its setup with.

use crate::api::FactId;
use crate::config::Storage;
use crate::engine::{Core, Engine};
use crate::error::{EngineError, LoadError};
use crate::expr::{Expr, Op};
use crate::host::Host;
use crate::template::DefaultKind;
use crate::value::{Ix, Value, ValueRef};

/// Why a fact could not be built (before anything was asserted).
fn refused(expected: &'static str) -> EngineError {
    EngineError::Load(LoadError {
        line: 0,
        col: 0,
        expected,
        construct: "assert",
        capacity: None,
        start: 0,
        end: 0,
        detail: crate::error::LoadDetail::Syntax,
        echo_end: 0,
        echo_tail: crate::error::EchoTail::Normal,
        query_syntax: false,
    })
}

impl<S: Storage> Engine<S> {
    /// Asserts a fact given by its template's name and slot values, as
    /// `(assert (template (slot value...)...))` does, with no parser: `slots` names each
    /// given slot with its values (one for a single-field slot); slots left out take
    /// their defaults. An ordered fact (`(s0-supply 4)`, a template of no deftemplate)
    /// has one entry, its name empty, holding its fields. Values are atoms
    /// (`ValueRef::{Int, Float, Symbol, String}`).
    pub fn assert_fact(
        &mut self,
        host: &mut dyn Host,
        template: &str,
        slots: &[(&str, &[ValueRef<'_>])],
    ) -> Result<FactId, EngineError> {
        let mut cx = self.core(host);
        let before = cx.st.pools.nexprs;
        let cp = cx.checkpoint();
        let r = match cx.fact_spec_of(template, slots) {
            Ok(spec) => cx.assert_spec(spec).map_err(EngineError::from),
            Err(e) => Err(e),
        };
        cx.st.pools.nexprs = before;
        cx.st.frame.scratch_top = 0;
        cx.st.frame.sp = 0;
        match r {
            Ok(Some(f)) => Ok(FactId(cx.facts[f as usize].num)),
            Ok(None) => Err(EngineError::Duplicate),
            Err(e) => {
                // leave no trace: symbols (and an implied template) it made go too
                cx.rollback(cp);
                Err(e)
            }
        }
    }
}

impl Core<'_> {
    /// The `FactSpec` expression the parser would build for the fact.
    fn fact_spec_of(
        &mut self,
        template: &str,
        slots: &[(&str, &[ValueRef<'_>])],
    ) -> Result<Ix, EngineError> {
        let sym = self.intern(template)?;
        let tmpl = match self.find_template(sym) {
            Some(t) => t,
            None => self.implied_template(sym)?,
        };
        let spec = self.push_expr(Expr::new(Op::FactSpec, 0, tmpl))?;
        if self.templates[tmpl as usize].implied {
            let [("", values)] = slots else {
                return Err(refused(
                    "one unnamed entry holding an ordered fact's fields",
                ));
            };
            let sv = self.push_expr(Expr::new(Op::SlotVal, 0, 0))?;
            self.append_child(spec, sv);
            self.push_values(sv, values)?;
            return Ok(spec);
        }
        for (k, (name, values)) in slots.iter().enumerate() {
            let slot_sym = self.intern(name)?;
            let Some(slot) = self.find_slot(tmpl, slot_sym) else {
                return Err(refused("a slot of the template"));
            };
            if slots[..k].iter().any(|(other, _)| other == name) {
                return Err(refused("a slot not given twice"));
            }
            if !self.slot_def(tmpl, slot).multi && values.len() != 1 {
                return Err(refused("one value for a single-field slot"));
            }
            let sv = self.push_expr(Expr::new(Op::SlotVal, 0, slot))?;
            self.insert_slot_val(spec, sv);
            self.push_values(sv, values)?;
        }
        let t = self.templates[tmpl as usize];
        for slot in 0..t.nslots {
            let def = self.slot_def(tmpl, slot);
            let name = self.sym_text(def.name);
            if def.default_kind == DefaultKind::Required && !slots.iter().any(|(n, _)| *n == name) {
                return Err(refused("a value for every slot declared (default ?NONE)"));
            }
        }
        Ok(spec)
    }

    /// Constant nodes for `values`, children of `parent`.
    fn push_values(&mut self, parent: Ix, values: &[ValueRef<'_>]) -> Result<(), EngineError> {
        for v in values {
            let value = match *v {
                ValueRef::Int(i) => Value::Int(i),
                ValueRef::Float(f) => Value::Float(f),
                ValueRef::Symbol(s) => Value::Sym(self.intern(s)?),
                ValueRef::String(s) => Value::Str(self.intern(s)?),
                ValueRef::Fact(_) | ValueRef::Multi(_) | ValueRef::Void => {
                    return Err(refused("an atom (integer, float, symbol or string)"))
                }
            };
            let node = self.push_const(value)?;
            self.append_child(parent, node);
        }
        Ok(())
    }
}
