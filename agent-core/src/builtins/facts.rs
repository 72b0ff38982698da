//! Fact functions: assert, retract, modify, duplicate, fact-slot-value, fact-index.

use super::describe::ArgType::{Any, FactAddress as F, FactOrIndex as Z, Symbol};
use super::describe::OnError;
use super::describe::Returns as R;
use super::{Args, Builtin, ANY, SYM_FALSE, SYM_NIL};
use crate::engine::Core;
use crate::error::{EvalError, EvalErrorKind};
use crate::expr::Op;
use crate::host::router;
use crate::template::{allowed, types, DefaultKind, SlotDef};
use crate::value::Ix;
use crate::value::{FactRef, MfSpan, SymId, Value, NONE};

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::lazy("assert", 1, ANY, assert),
    Builtin::eager("retract", 1, ANY, retract).args(&[], Z).returns(R::Void),
    Builtin::lazy("modify", 1, ANY, modify),
    Builtin::lazy("duplicate", 1, ANY, duplicate),
    Builtin::eager("fact-slot-value", 2, 2, fact_slot_value).args(&[Z, Symbol], Any),
    Builtin::eager("fact-index", 1, 1, fact_index).args(&[F], Any).on_error(OnError::MinusOne).returns(R::Integer),
    Builtin::eager("fact-existp", 1, 1, fact_existp).args(&[Z], Any).returns(R::Symbol),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// `a < b` for two numbers; false when either is not a number (an unbounded end of
/// a range, `-oo`/`+oo`).
fn below(a: Value, b: Value) -> bool {
    match (a.as_number(), b.as_number()) {
        (Some(x), Some(y)) => x < y,
        _ => false,
    }
}

impl Core<'_> {
    /// The type bit of atom `v` (`types::of`).
    pub(crate) fn type_bit(&self, v: Value) -> u8 {
        types::of(v, |s| self.sym_text(s))
    }

    /// Checks one atom against a slot's type and allowed-value restrictions (the
    /// parser's literal checks; also for a slot not yet stored in a template).
    pub(crate) fn check_atom_def(&self, def: &SlotDef, v: Value) -> Result<(), EvalError> {
        if def.types != 0 && def.types & self.type_bit(v) == 0 {
            return Err(EvalError::new(EvalErrorKind::BadSlotValue {
                reason: crate::error::Message::TypeViolated,
            }));
        }
        // (`allowed::CLASSES` has no list: only `extras` makes its bit or an instance
        // address)
        #[cfg(feature = "extras")]
        let restricted =
            def.allowed_kind & !allowed::CLASSES & (allowed::VALUES | self.type_bit(v)) != 0;
        #[cfg(not(feature = "extras"))]
        let restricted = def.allowed_kind & (allowed::VALUES | self.type_bit(v)) != 0;
        if def.allowed != NONE && restricted {
            // CLIPS looks for a value of the same type: 1.0 is not 1
            let mut c = def.allowed;
            while c != NONE {
                let a = self.const_value(c);
                let eq = match (a, v) {
                    (Value::Int(x), Value::Int(y)) => x == y,
                    _ => self.type_bit(a) == self.type_bit(v) && a.same(v),
                };
                if eq {
                    return Ok(());
                }
                c = self.exprs[c as usize].next;
            }
            return Err(EvalError::new(EvalErrorKind::BadSlotValue {
                reason: crate::error::Message::AllowedValuesViolated,
            }));
        }
        // no instance is of a class here: `allowed-classes` refuses every one
        #[cfg(feature = "extras")]
        if def.allowed_kind & allowed::CLASSES != 0 && self.type_bit(v) & types::INSTANCE != 0 {
            return Err(EvalError::new(EvalErrorKind::BadSlotValue {
                reason: crate::error::Message::ClassesViolated,
            }));
        }
        if def.range != NONE && matches!(v, Value::Int(_) | Value::Float(_)) {
            let min = self.const_value(def.range);
            let max = self.const_value(self.exprs[def.range as usize].next);
            if below(v, min) || below(max, v) {
                return Err(EvalError::new(EvalErrorKind::BadSlotValue {
                    reason: crate::error::Message::RangeViolated,
                }));
            }
        }
        Ok(())
    }

    /// Dynamic constraint checking of a new fact: the first slot whose value breaks
    /// its restrictions is reported as CLIPS reports it (`[CSTRNCHK1] Slot value ...
    /// found in fact f-N`), and execution halts as after an error in the pattern
    /// network (the fact stays). Whether one was reported.
    #[cfg(feature = "extras")]
    pub(crate) fn report_violation(&mut self, fact: Ix) -> bool {
        use crate::error::Restriction;
        use core::fmt::Write;
        let tmpl = self.facts[fact as usize].tmpl;
        let nslots = self.templates[tmpl as usize].nslots;
        for s in 0..nslots {
            let def = self.slot_def(tmpl, s);
            let Ok(v) = self.fact_slot_value(fact, s) else {
                return false;
            };
            let what = match v {
                Value::Multi(m) => {
                    let (min, max) = self.cardinality_of(&def);
                    let len = i64::from(m.len);
                    if len < min || len > max {
                        Some(Restriction::Cardinality)
                    } else {
                        (0..m.len as usize).find_map(|k| {
                            let item = self.mf_item(m, k);
                            self.check_atom_def(&def, item)
                                .err()
                                .map(|e| e.restriction())
                        })
                    }
                }
                v => self.check_atom_def(&def, v).err().map(|e| e.restriction()),
            };
            let Some(what) = what else { continue };
            let mut b: crate::value::TextBuf<1024> = crate::value::TextBuf::new();
            let _ = b.write_str("\n[CSTRNCHK1] Slot value ");
            {
                let (view, _) = self.split();
                let _ = view.write_value(&mut b, v, true);
            }
            let mut id: crate::value::TextBuf<16> = crate::value::TextBuf::new();
            let _ = write!(id, "f-{}", self.facts[fact as usize].num);
            let _ = writeln!(b, " found in fact {:<7} ", id.as_str());
            let _ = match what {
                Restriction::Type => b.write_str("does not match the allowed types"),
                Restriction::Values => b.write_str("does not match the allowed values"),
                Restriction::Classes => b.write_str("does not match the allowed classes"),
                Restriction::Cardinality => {
                    b.write_str("does not satisfy the cardinality restrictions")
                }
                Restriction::Range => {
                    let min = self.const_value(def.range);
                    let max = self.const_value(self.exprs[def.range as usize].next);
                    let _ = b.write_str("does not fall in the allowed range ");
                    let _ = self.write_plain(&mut b, min);
                    let _ = b.write_str(" to ");
                    self.write_plain(&mut b, max)
                }
            };
            let _ = writeln!(b, " for slot {}.", self.sym_text(def.name));
            self.write(router::WERROR, b.as_str());
            self.st.net.pattern_error = true;
            self.st.mode.halting = true;
            return true;
        }
        false
    }

    /// Whether a slot left out of a fact gets CLIPS's `<Dummy Fact>` (its one type
    /// FACT-ADDRESS, no default given): CLIPS refuses that in a deffacts and in
    /// `assert-string` (`[PRNTUTIL6]`, as for a variable).
    #[cfg(feature = "extras")]
    pub(crate) fn derives_dummy_fact(&self, def: &SlotDef) -> bool {
        def.default_kind == crate::template::DefaultKind::Derived
            && def.types & types::FACT_ADDRESS != 0
            && def.types & !types::FACT_ADDRESS == 0
            && (!def.multi || self.cardinality_of(def).0 > 0)
    }

    /// A multislot's cardinality: the fewest and most fields it takes.
    pub(crate) fn cardinality_of(&self, def: &SlotDef) -> (i64, i64) {
        if def.cardinality == NONE {
            return (0, i64::MAX);
        }
        let bound = |v: Value, unbounded: i64| match v {
            Value::Int(n) => n,
            _ => unbounded,
        };
        (
            bound(self.const_value(def.cardinality), 0),
            bound(
                self.const_value(self.exprs[def.cardinality as usize].next),
                i64::MAX,
            ),
        )
    }

    /// A value a derived default gives a slot of type `ty` (one type bit): the first
    /// allowed value of that type, else for numbers the range's minimum, else its
    /// maximum (converted to the type), else `standard`, as CLIPS derives it.
    fn derived_atom(&self, def: &SlotDef, ty: u8, standard: Value) -> Value {
        let mut c = def.allowed;
        while c != NONE {
            let v = self.const_value(c);
            if self.type_bit(v) == ty {
                return v;
            }
            c = self.exprs[c as usize].next;
        }
        if def.range != NONE && ty & types::NUMBER != 0 {
            let min = self.const_value(def.range);
            let max = self.const_value(self.exprs[def.range as usize].next);
            for bound in [min, max] {
                match (ty, bound) {
                    (types::INTEGER, Value::Int(_)) | (types::FLOAT, Value::Float(_)) => {
                        return bound
                    }
                    (types::INTEGER, Value::Float(f)) => return Value::Int(f as i64),
                    (types::FLOAT, Value::Int(n)) => return Value::Float(n as f64),
                    _ => {}
                }
            }
        }
        standard
    }

    /// The value of a slot without a default, derived from its restrictions as CLIPS
    /// does: the first type it takes among symbol, string, integer, float, with the
    /// value `derived_atom` picks; a multislot takes its minimum cardinality of them.
    fn derived_default(&mut self, def: &SlotDef) -> Result<Value, EvalError> {
        let t = def.types;
        let atom = if t == 0 || t & types::SYMBOL != 0 {
            self.derived_atom(def, types::SYMBOL, Value::Sym(SYM_NIL))
        } else if t & types::STRING != 0 {
            self.derived_atom(def, types::STRING, Value::Str(super::SYM_EMPTY_STR))
        } else if t & types::INTEGER != 0 {
            self.derived_atom(def, types::INTEGER, Value::Int(0))
        } else if t & types::FLOAT != 0 {
            self.derived_atom(def, types::FLOAT, Value::Float(0.0))
        } else if t & types::INSTANCE_NAME != 0 {
            let nil = self.intern("[nil]")?;
            self.derived_atom(def, types::INSTANCE_NAME, Value::Sym(nil))
        } else if cfg!(feature = "extras") && t & types::INSTANCE_ADDRESS != 0 {
            Value::Fact(crate::value::FactRef::DUMMY_INSTANCE)
        } else if cfg!(feature = "extras") && t & types::FACT_ADDRESS != 0 {
            Value::Fact(crate::value::FactRef::DUMMY_FACT)
        } else {
            Value::Sym(SYM_NIL)
        };
        if !def.multi {
            return Ok(atom);
        }
        let (min, _) = self.cardinality_of(def);
        if min == 0 {
            return Ok(Value::Multi(MfSpan {
                start: self.st.frame.scratch_top,
                len: 0,
            }));
        }
        let start = self.multi_begin();
        for _ in 0..min {
            self.multi_push(atom)?;
        }
        Ok(self.multi_finish(start))
    }

    /// `slot_value_from` with, on the host, a symbol for a single-field slot (the
    /// commonest value `modify` gives) taken as it is, without the call. (Not for
    /// `assert`, whose values are mostly variables: join3-1000 paid 28 a fact.)
    #[inline(always)]
    fn slot_value_quick(
        &mut self,
        tmpl: Ix,
        slot: Ix,
        e: Ix,
        asserting: bool,
    ) -> Result<Value, EvalError> {
        #[cfg(feature = "host-speedups")]
        if let Some(x) = self.exprs.get(e as usize) {
            if x.op == Op::Sym && !self.slot_def(tmpl, slot).multi {
                return Ok(Value::Sym(x.data));
            }
        }
        self.slot_value_from(tmpl, slot, e, asserting)
    }

    /// Evaluates value expressions (a chain) into one slot value: a multifield for a
    /// multislot (all values spliced), else the single value.
    /// (`asserting`: for a fact being asserted, where a failed single-field value is
    /// kept, see `single_field_failed`)
    fn slot_value_from(
        &mut self,
        tmpl: Ix,
        slot: Ix,
        mut e: Ix,
        asserting: bool,
    ) -> Result<Value, EvalError> {
        let multi = self.slot_def(tmpl, slot).multi;
        if !multi {
            // no value at all, `(modify ?f (x))` on a single-field slot whose template
            // the parser could not know: CLIPS's TMPLTFUN2 ("a multifield value into
            // the single field slot"), not an expression to evaluate
            if e == NONE {
                return Err(EvalError::new(EvalErrorKind::BadSlotValue {
                    reason: crate::error::Message::SingleFieldNeedsOneValue,
                }));
            }
            // most slot values are constants or variables: the host reads them in
            // place (the image keeps the 370 B of code that inline copy costs)
            #[cfg(all(feature = "host-speedups", feature = "grow"))]
            let v = self.eval_value_operand::<false>(e);
            #[cfg(all(feature = "host-speedups", not(feature = "grow")))]
            let v = self.eval_operand(e);
            #[cfg(not(feature = "host-speedups"))]
            let v = self.eval(e);
            let v = match v {
                Ok(v) => v,
                Err(err) if asserting => self.single_field_failed(err, e)?,
                Err(err) => return Err(err),
            };
            return match v {
                Value::Multi(m) if m.len == 1 => Ok(self.mf_item(m, 0)),
                Value::Multi(_) => Err(EvalError::new(EvalErrorKind::BadSlotValue {
                    reason: crate::error::Message::SingleFieldNeedsOneValue,
                })),
                // a call with no value (`printout`, `profile`): CLIPS stores `nil`
                Value::Void => Ok(Value::Sym(SYM_NIL)),
                _ => Ok(v),
            };
        }
        // evaluate first (values may build scratch), then gather
        let base = self.st.frame.sp;
        while e != NONE {
            // (host: each field read in place too, an ordered fact's most of all)
            #[cfg(all(feature = "host-speedups", feature = "grow"))]
            let v = self.eval_value_operand::<false>(e);
            #[cfg(not(all(feature = "host-speedups", feature = "grow")))]
            let v = self.eval(e);
            let v = match v {
                Ok(v) => v,
                Err(err)
                    if !matches!(
                        err.kind(),
                        EvalErrorKind::Capacity(_)
                            | EvalErrorKind::Exit
                            | EvalErrorKind::Interrupted
                    ) =>
                {
                    if matches!(err.kind(), EvalErrorKind::UnboundVariable { .. }) {
                        // an unbound variable empties the slot, as in CLIPS:
                        // `(assert (k x ?u y))` makes `(k)`, then the actions stop
                        self.write_error_message(err);
                        self.st.eval.field_error = Some(err);
                        self.st.frame.sp = base;
                        break;
                    }
                    // CLIPS reports it and goes on without this field, its evaluation
                    // error set (fields after it are dropped, `reset` stops)
                    self.write_error_message(err);
                    self.st.eval.field_error = Some(err);
                    self.st.mode.halting = true;
                    e = self.exprs[e as usize].next;
                    continue;
                }
                Err(err) => return Err(err),
            };
            // CLIPS's evaluation error is set (an unbound global read as FALSE): the
            // slot is empty and the actions stop, as for an unbound variable
            if self.st.mode.halting {
                self.st.eval.field_error = Some(EvalError::already_reported());
                self.st.frame.sp = base;
                break;
            }
            self.push_value(v)?;
            e = self.exprs[e as usize].next;
        }
        let start = self.multi_begin();
        for i in base..self.st.frame.sp {
            match self.stack[i as usize] {
                Value::Multi(m) => {
                    for k in 0..m.len as usize {
                        let item = self.mf_item(m, k);
                        self.multi_push(item)?;
                    }
                }
                // a function without a value (`printout`) adds no field, as in CLIPS:
                // `(deffacts d (a x (printout t)))` makes `(a x)`
                Value::Void => {}
                v => self.multi_push(v)?,
            }
        }
        self.st.frame.sp = base;
        Ok(self.multi_finish(start))
    }

    /// The value a slot takes when an assert leaves it out.
    /// A single-field slot's value whose evaluation failed: CLIPS reports the error,
    /// keeps the value the failing function returned (`(+ 1 ?*u*)` is 1), sets its
    /// evaluation error (multislots evaluated after it are empty) and asserts the fact;
    /// the assert then stops (`field_error`).
    #[cold]
    #[inline(never)]
    fn single_field_failed(&mut self, err: EvalError, e: Ix) -> Result<Value, EvalError> {
        if matches!(
            err.kind(),
            EvalErrorKind::Capacity(_) | EvalErrorKind::Exit | EvalErrorKind::Interrupted
        ) {
            return Err(err);
        }
        let depth = self.st.eval.eval_depth + 1;
        #[cfg(not(feature = "extras"))]
        let _ = e;
        let v = match self.st.eval.error_fallback {
            Some(fb) if fb.depth == depth => fb.value,
            // else the constant the failing builtin returns (`sqrt`'s 0.0; the image
            // keeps FALSE)
            #[cfg(feature = "extras")]
            _ => self.builtin_fallback(e).unwrap_or(Value::Sym(SYM_FALSE)),
            #[cfg(not(feature = "extras"))]
            _ => Value::Sym(SYM_FALSE),
        };
        self.write_error_message(err);
        let mut err = err;
        err.reported = true;
        self.st.eval.field_error = Some(err);
        self.st.mode.halting = true;
        Ok(v)
    }

    /// The value builtin call `e` returns after a run-time error, when CLIPS's is a
    /// constant (`builtins::describe::OnError`).
    #[cfg(feature = "extras")]
    fn builtin_fallback(&mut self, e: Ix) -> Option<Value> {
        use crate::builtins::errors::Fallback;
        use crate::expr::FnKind;
        let x = self.exprs[e as usize];
        if x.op != Op::Call || x.aux != FnKind::Builtin as u8 {
            return None;
        }
        Some(match crate::builtins::get(x.data).on_error.fallback()? {
            Fallback::Int(i) => Value::Int(i),
            Fallback::Float(f) => Value::Float(f),
            Fallback::Sym("nil") => Value::Sym(crate::builtins::SYM_NIL),
            Fallback::Sym(_) => Value::Sym(SYM_FALSE),
            Fallback::Str("") => Value::Str(super::SYM_EMPTY_STR),
            Fallback::Str(_) | Fallback::EmptyMulti => return None,
        })
    }

    pub(crate) fn default_value(&mut self, tmpl: Ix, slot: Ix) -> Result<Value, EvalError> {
        self.default_value_for(tmpl, slot, false)
    }

    /// `default_value`; `asserting`: see `slot_value_from`.
    fn default_value_for(
        &mut self,
        tmpl: Ix,
        slot: Ix,
        asserting: bool,
    ) -> Result<Value, EvalError> {
        let def = self.slot_def(tmpl, slot);
        match def.default_kind {
            DefaultKind::Static | DefaultKind::Dynamic if def.default != NONE => {
                self.slot_value_from(tmpl, slot, def.default, asserting)
            }
            DefaultKind::Required => Err(EvalError::new(EvalErrorKind::BadSlotValue {
                reason: crate::error::Message::NoDefault,
            })),
            _ => self.derived_default(&def),
        }
    }

    /// Asserts the fact described by a `FactSpec` node. `Ok(None)`: duplicate.
    pub fn assert_spec(&mut self, spec: Ix) -> Result<Option<Ix>, EvalError> {
        self.assert_spec_deferring(spec, false)
    }

    /// `assert_spec`; `defer`: the fact's propagation may wait (`rete::defer`).
    fn assert_spec_deferring(&mut self, spec: Ix, defer: bool) -> Result<Option<Ix>, EvalError> {
        // no fact may come while a pattern or join test runs (`State::matching`): CLIPS
        // says so and the assert gives FALSE
        if self.st.net.changes_refused() {
            self.write(router::WERROR, NO_ASSERT_WHILE_MATCHING);
            return Ok(None);
        }
        let tmpl = self.exprs[spec as usize].data;
        let nslots = self.templates[tmpl as usize].nslots;
        let base = self.st.frame.sp;
        self.push_voids(nslots as usize)?;
        // the values' calls may not `clear` the template away (`Mode::asserting`)
        let was = core::mem::replace(&mut self.st.mode.asserting, true);
        let r = self.assert_spec_inner(spec, tmpl, base, defer);
        self.st.mode.asserting = was;
        self.st.frame.sp = base;
        r
    }

    fn assert_spec_inner(
        &mut self,
        spec: Ix,
        tmpl: Ix,
        base: Ix,
        defer: bool,
    ) -> Result<Option<Ix>, EvalError> {
        let nslots = self.templates[tmpl as usize].nslots;
        // CLIPS evaluates given values and defaults alike in the template's slot
        // order; the spec's values come in that order (`insert_slot_val`)
        let mut sv = self.exprs[spec as usize].first;
        for s in 0..nslots {
            let v = if sv != NONE && self.exprs[sv as usize].data == s {
                let first = self.exprs[sv as usize].first;
                sv = self.exprs[sv as usize].next;
                self.slot_value_from(tmpl, s, first, true)?
            } else {
                self.default_value_for(tmpl, s, true)?
            };
            self.stack[(base + s) as usize] = v;
        }
        // Values computed at run time are not checked against the slots' restrictions:
        // CLIPS checks literals while parsing and leaves dynamic constraint checking off.
        self.st.net.defer_next = defer;
        self.assert_slots(tmpl, base as usize)
    }

    /// Resolves a fact argument: an address or an index.
    pub fn fact_arg(&self, v: Value) -> Option<Ix> {
        match v {
            Value::Fact(r) if self.fact_alive(r) => Some(r.slot),
            Value::Int(n) if n >= 0 => self.find_fact(n as u32),
            _ => None,
        }
    }

    /// What `modify_or_duplicate`'s two push loops make of the `n` slots of `fact`
    /// when it is flat, no slot holds a multifield and the stack has room: the
    /// values pushed twice from stack slot `sp` (the top); false (nothing pushed)
    /// otherwise.
    #[cfg(feature = "host-speedups")]
    fn copy_flat_slots_twice(&mut self, fact: Ix, n: usize, sp: usize) -> bool {
        let f = &self.facts[fact as usize];
        let start = f.start as usize;
        if !f.flat || sp + 2 * n > self.stack.len() {
            return false;
        }
        for s in 0..n {
            let v = self.values[start + s];
            // an empty multislot's cell: `fact_slot_value` makes a scratch multifield
            if v.is_multi() {
                return false;
            }
            self.stack[sp + s] = v;
            self.stack[sp + n + s] = v;
        }
        self.st.frame.sp = (sp + 2 * n) as Ix;
        self.note_hw(crate::error::Pool::EvalStack, sp + 2 * n);
        true
    }

    /// `[TMPLTDEF1]` for a slot `modify`/`duplicate` names that template `tmpl` lacks:
    /// FALSE, the actions halted.
    #[cold]
    fn bad_slot(&mut self, tmpl: Ix, slot: SymId) -> EvalError {
        #[cfg(feature = "extras")]
        {
            let mut m: crate::value::TextBuf<200> = crate::value::TextBuf::new();
            let _ = core::fmt::Write::write_fmt(
                &mut m,
                format_args!(
                    "\n[TMPLTDEF1] Invalid slot {} not defined in corresponding deftemplate {}.\n",
                    self.sym_text(slot),
                    self.sym_text(self.templates[tmpl as usize].name)
                ),
            );
            self.write(router::WERROR, m.as_str());
            self.set_error_fallback(Value::Sym(SYM_FALSE), None);
            EvalError::already_reported()
        }
        #[cfg(not(feature = "extras"))]
        {
            let _ = (tmpl, slot);
            EvalError::new(EvalErrorKind::NoSuchSlot)
        }
    }

    fn modify_or_duplicate(&mut self, call: Ix, retract_old: bool) -> Result<Value, EvalError> {
        // the values' calls may not `clear` the fact and its template away
        // (`Mode::asserting`)
        let was = core::mem::replace(&mut self.st.mode.asserting, true);
        let r = self.modify_or_duplicate_inner(call, retract_old);
        self.st.mode.asserting = was;
        r
    }

    fn modify_or_duplicate_inner(
        &mut self,
        call: Ix,
        retract_old: bool,
    ) -> Result<Value, EvalError> {
        let first = self.exprs[call as usize].first;
        let fv = self.eval(first)?;
        #[cfg(feature = "extras")]
        {
            self.st.eval.field_error = None;
        }
        // a waiting propagation (`rete::defer`) lets only this modify's retract go
        // first, and only when nothing can tell
        if self.st.net.deferred.fact != NONE
            && !(retract_old
                && self
                    .fact_arg(fv)
                    .is_some_and(|old| self.may_overtake(call, old)))
        {
            self.flush_deferred()?;
        }
        // a fact retracted meanwhile whose values are still held (in this firing, or
        // by a query): CLIPS makes the modified copy without retracting anything, as
        // `duplicate` does
        let held = match fv {
            Value::Fact(r) if self.fact_readable(r) => Some(r.slot),
            _ => None,
        };
        let (old, retract_old) = match (self.fact_arg(fv), held) {
            (Some(f), _) => (f, retract_old),
            (None, Some(f)) => (f, false),
            // a stale fact address: CLIPS says FALSE without a message
            (None, None) if matches!(fv, Value::Fact(_)) => return Ok(Value::Sym(SYM_FALSE)),
            (None, None) => {
                let Value::Int(n @ 0..) = fv else {
                    // neither a fact nor an index: CLIPS's error halts the actions
                    let func = if retract_old { "modify" } else { "duplicate" };
                    // the prompt shows FALSE when a variable or a negative index gave
                    // the value
                    if matches!(fv, Value::Int(_))
                        || matches!(
                            self.exprs[first as usize].op,
                            Op::Global | Op::Local | Op::PatVar
                        )
                    {
                        self.set_error_fallback(Value::Sym(SYM_FALSE), None);
                    }
                    return Err(EvalError::wrong_type(func, 1, "non-void return value"));
                };
                let mut b: crate::value::TextBuf<64> = crate::value::TextBuf::new();
                let _ = core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!("[PRNTUTIL1] Unable to find fact f-{n}.\n"),
                );
                self.write(router::WERROR, b.as_str());
                return Ok(Value::Sym(SYM_FALSE));
            }
        };
        let tmpl = self.facts[old as usize].tmpl;
        if self.templates[tmpl as usize].implied {
            // `initial-fact` is a deftemplate of no slots in CLIPS: any slot is
            // `[TMPLTDEF1]`, none makes a copy (host only: the image's code budget)
            #[cfg(feature = "extras")]
            let initial = self.templates[tmpl as usize].name == super::SYM_INITIAL_FACT;
            #[cfg(not(feature = "extras"))]
            let initial = false;
            if initial {
                let sv = self.exprs[first as usize].next;
                if sv != NONE {
                    return Err(self.bad_slot(tmpl, self.exprs[sv as usize].data));
                }
            } else {
                // an ordered fact has no slots to change: CLIPS gives FALSE, says
                // nothing and evaluates no slot value
                return Ok(Value::Sym(SYM_FALSE));
            }
        }
        // (host: `duplicate` may assert while a rule is primed, `modify` may not; the
        // level `modify` may not pass is the lower one, so the usual path reads one)
        #[cfg(feature = "extras")]
        let refused =
            self.st.net.retracts_refused() && (retract_old || self.st.net.changes_refused());
        #[cfg(feature = "extras")]
        debug_assert!(self.st.net.retract_free <= self.st.net.matching_free);
        #[cfg(not(feature = "extras"))]
        let refused = self.st.net.changes_refused();
        if refused {
            // a modify is a retract, then an assert: CLIPS refuses both
            if retract_old {
                self.write(router::WERROR, NO_RETRACT_WHILE_MATCHING);
            }
            self.write(router::WERROR, NO_ASSERT_WHILE_MATCHING);
            return Ok(Value::Sym(SYM_FALSE));
        }
        let nslots = self.templates[tmpl as usize].nslots;
        // matches an earlier retract owes come first: the retract below must free
        // room for the old fact's return, not for old debts
        self.pay_owed()?;
        // the old values at `saved`, the new fact's built from a copy at `base`: a
        // modify that fails after the retract puts the old fact back from them
        let saved = self.st.frame.sp;
        let base = saved + nslots;
        self.st.net.pattern_error = false;
        let r = (|| {
            // host: a flat fact without multislot values (most) copied in place
            #[cfg(feature = "host-speedups")]
            let copied = self.copy_flat_slots_twice(old, nslots as usize, saved as usize);
            #[cfg(not(feature = "host-speedups"))]
            let copied = false;
            if !copied {
                for s in 0..nslots {
                    let v = self.fact_slot_value(old, s)?;
                    self.push_value(v)?;
                }
                for s in 0..nslots {
                    self.push_value(self.stack[(saved + s) as usize])?;
                }
            }
            let mut sv = self.exprs[first as usize].next;
            while sv != NONE {
                let sym = self.exprs[sv as usize].data;
                let Some(slot) = self.find_slot(tmpl, sym) else {
                    return Err(self.bad_slot(tmpl, sym));
                };
                // unchecked, as in CLIPS (see assert); a failed single-field value is
                // kept on the host, as CLIPS keeps it (see `single_field_failed`)
                let v = self.slot_value_quick(
                    tmpl,
                    slot,
                    self.exprs[sv as usize].first,
                    cfg!(feature = "extras"),
                )?;
                self.stack[(base + slot) as usize] = v;
                sv = self.exprs[sv as usize].next;
            }
            if !retract_old {
                return self.assert_slots(tmpl, base as usize);
            }
            // no room for the new fact: fail before anything changed
            let hold = self.modify_fits(old, tmpl, base as usize)?;
            let old_fact = self.facts[old as usize];
            // a modify that is undone prints nothing (see `hold`); the activations
            // its retract removes are noted, to put them back in their agenda places,
            // and the not outputs it unblocks, to take back what they rebuilt, should
            // the assert fail
            self.hold_traces();
            let mark = self.journal_begin();
            self.st.net.unblocked = crate::rete::UnblockLog {
                on: true,
                ..crate::rete::UnblockLog::EMPTY
            };
            self.retract_fact_held(old, hold);
            self.st.net.unblocked.on = false;
            self.journal_pause();
            // a propagation the retract overtook (`rete::defer`) is built now; if it
            // fails, this modify's journal lacks the activations the overtaken
            // assert's retract removed: its undo rebuilds every one as the newest
            // (host: unless the new fact's waits behind it, `rete::Queued`)
            // the new fact's propagation may wait for the next action's retract
            let defer = self.defer_worth(call);
            let flushed = if defer && self.may_queue(tmpl) {
                Ok(())
            } else {
                self.flush_deferred()
            };
            let r = match flushed {
                Err(e) => {
                    self.st.agenda.act_journal.overflow = true;
                    Err(e)
                }
                Ok(()) => {
                    if defer {
                        self.st.facts.modify_old = Some((old, old_fact));
                    }
                    self.st.net.defer_next = defer;
                    let r = self.assert_slots(tmpl, base as usize);
                    self.st.facts.modify_old = None;
                    r
                }
            };
            if r.is_err() {
                // facts that waited for this retract (`rete::Queued`: the new fact
                // found no room before it could join them) are built first, as the
                // eager order built them before the retract
                #[cfg(feature = "defer")]
                if self.st.net.deferred.fact != NONE {
                    let _ = self.flush_deferred();
                }
                // the network ran out of room (tokens, activations): the new fact is
                // gone again; the old one comes back with the room its retract freed
                // (if that fails too, it stays retracted and the first error is
                // reported; only possible after an unblock log overflow)
                self.owe_unblocked();
                self.journal_replay(mark);
                if self.restore_fact(old, old_fact, saved as usize).is_ok() {
                    let _ = self.pay_owed();
                }
            }
            self.journal_end(mark);
            self.release_traces(r.is_ok());
            r
        })();
        self.st.frame.sp = saved;
        let v = match r? {
            Some(f) => Value::Fact(self.fact_ref(f)),
            None => Value::Sym(SYM_FALSE),
        };
        // a value failed: the fact is changed all the same, then the actions stop
        #[cfg(feature = "extras")]
        if let Some(mut err) = self.st.eval.field_error.take() {
            err.reported = true;
            self.set_error_fallback(v, None);
            return Err(err);
        }
        if self.st.net.pattern_error {
            return halt_after_network_error(self, v);
        }
        Ok(v)
    }
}

fn assert(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    let mut spec = cx.exprs[call as usize].first;
    let mut last = Value::Sym(SYM_FALSE);
    cx.st.net.pattern_error = false;
    // a top-level action's last fact may defer its propagation (`rete::defer`): an
    // earlier one's pattern errors must stop the assert before the next fact
    let top = cx.defer_worth(call);
    while spec != NONE {
        if cx.exprs[spec as usize].op == Op::FactSpec {
            cx.st.eval.field_error = None;
            let defer = top && cx.exprs[spec as usize].next == NONE;
            last = match cx.assert_spec_deferring(spec, defer)? {
                Some(f) => Value::Fact(cx.fact_ref(f)),
                None => Value::Sym(SYM_FALSE),
            };
            // a field failed: the fact stands without it, the actions stop here; the
            // assert gives the fact, FALSE when more facts were to follow (CLIPS)
            if let Some(mut err) = cx.st.eval.field_error.take() {
                err.reported = true;
                if cx.exprs[spec as usize].next != NONE {
                    last = Value::Sym(SYM_FALSE);
                }
                cx.set_error_fallback(last, None);
                return Err(err);
            }
        }
        spec = cx.exprs[spec as usize].next;
        // CLIPS stops a multi-fact assert after a pattern-network error
        if cx.st.net.pattern_error && spec != NONE {
            return halt_after_network_error(cx, Value::Sym(SYM_FALSE));
        }
    }
    if cx.st.net.pattern_error {
        // CLIPS shows a lone fact, but FALSE for a multi-fact assert
        let several = cx.exprs[cx.exprs[call as usize].first as usize].next != NONE;
        let v = if several { Value::Sym(SYM_FALSE) } else { last };
        return halt_after_network_error(cx, v);
    }
    Ok(last)
}

/// After a test in the pattern or join network failed with an error (reported there,
/// the test taken as false, the fact standing), CLIPS halts execution: the rule's or
/// deffunction's remaining actions do not run. The error is already reported; the
/// call's value (the fact, shown by a bare `assert` at the prompt) is the fallback.
fn halt_after_network_error(cx: &mut Core<'_>, value: Value) -> Result<Value, EvalError> {
    cx.st.net.pattern_error = false;
    cx.set_error_fallback(value, None);
    Err(EvalError::already_reported())
}

/// CLIPS's messages for a fact change asked for by a pattern or join test: while
/// matching (`State::matching`) the network may not change under its own feet.
const NO_RETRACT_WHILE_MATCHING: &str =
    "\n[FACTMNGR1] Facts may not be retracted during pattern-matching\n";
const NO_ASSERT_WHILE_MATCHING: &str =
    "\n[FACTMNGR2] Facts may not be asserted during pattern-matching\n";

/// `(retract f ...)`: each fact (address or index) retracted; `*` all of them. An
/// argument of another type is reported and the others still retracted (then the
/// error halts what runs); a negative index is reported and ends the call.
fn retract(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let mut failed = false;
    for i in 0..a.len as usize {
        let v = cx.arg(a, i);
        if let Value::Sym(s) = v {
            if cx.sym_text(s) == "*" {
                if cx.st.net.retracts_refused() {
                    // CLIPS refuses each fact (and, unlike here, tries again forever)
                    let mut f = cx.st.facts.fact_head;
                    while f != NONE {
                        cx.write(router::WERROR, NO_RETRACT_WHILE_MATCHING);
                        f = cx.facts[f as usize].next;
                    }
                    continue;
                }
                while cx.st.facts.fact_head != NONE {
                    let f = cx.st.facts.fact_head;
                    cx.retract_fact(f);
                }
                continue;
            }
        }
        match cx.fact_arg(v) {
            Some(_) if cx.st.net.retracts_refused() => {
                cx.write(router::WERROR, NO_RETRACT_WHILE_MATCHING)
            }
            Some(f) => cx.retract_fact(f),
            // a stale fact address was retracted already: nothing to do (as CLIPS)
            None if matches!(v, Value::Fact(_)) => {}
            None => {
                let Value::Int(n @ 0..) = v else {
                    cx.write_error_message(EvalError::wrong_type(
                        "retract",
                        crate::error::arg_no(i),
                        "fact-address, fact-index, or the symbol *",
                    ));
                    if matches!(v, Value::Int(_)) {
                        break;
                    }
                    failed = true;
                    continue;
                };
                let mut b: crate::value::TextBuf<64> = crate::value::TextBuf::new();
                let _ = core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!("[PRNTUTIL1] Unable to find fact f-{n}.\n"),
                );
                cx.write(router::WERROR, b.as_str());
            }
        }
    }
    // matches the retracts unblocked but found no room for are owed (see
    // `Core::pay_owed`): reported here, as the right-hand side's error
    cx.pay_owed()?;
    if failed {
        return Err(EvalError::already_reported());
    }
    Ok(Value::Void)
}

fn modify(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    cx.modify_or_duplicate(call, true)
}

fn duplicate(cx: &mut Core<'_>, call: Ix) -> Result<Value, EvalError> {
    cx.modify_or_duplicate(call, false)
}

fn fact_slot_value(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let fv = cx.arg(a, 0);
    // (the slot name's type is checked before the fact is looked for)
    let name = cx.arg_symbol(a, 1, "fact-slot-value")?;
    let Some(f) = cx.fact_arg(fv) else {
        return no_such_fact(cx, fv);
    };
    slot_of_fact(cx, f, name, false)
}

/// `?v:slot`: `(fact-slot-value ?v slot)` with its arguments at hand. `node` (the
/// `QSlot` node) keeps in `aux` the slot index found last time plus one: checked by
/// name against the fact's template, it saves the search by name in query loops.
pub(crate) fn slot_value_of(
    cx: &mut Core<'_>,
    fv: Value,
    name: SymId,
    node: Ix,
) -> Result<Value, EvalError> {
    // a retracted fact the firing or query still holds reads its old values, as in CLIPS
    let held = match fv {
        Value::Fact(r) => cx.fact_readable(r).then_some(r.slot),
        _ => cx.fact_arg(fv),
    };
    let Some(f) = held else {
        return no_such_fact(cx, fv);
    };
    let tmpl = cx.facts[f as usize].tmpl;
    let t = cx.templates[tmpl as usize];
    if !t.implied {
        let k = cx.exprs[node as usize].aux as Ix;
        if k != 0 && k <= t.nslots && cx.slots[(t.first_slot + k - 1) as usize].name == name {
            return Ok(cx.fact_slot_value(f, k - 1)?);
        }
        // a miss: search once, remember it, read it (an unknown slot reports below)
        if let Some(s) = cx.find_slot(tmpl, name) {
            // (a compiled rule base's nodes read in place keep no cache)
            if s < u8::MAX as Ix && cx.exprs.writable(node as usize) {
                cx.exprs[node as usize].aux = s as u8 + 1;
            }
            return Ok(cx.fact_slot_value(f, s)?);
        }
    }
    slot_of_fact(cx, f, name, true)
}

/// fact-slot-value of a missing fact: CLIPS prints the missing fact's index, then
/// returns FALSE (nothing printed for a stale address).
fn no_such_fact(cx: &mut Core<'_>, fv: Value) -> Result<Value, EvalError> {
    match fv {
        Value::Int(n @ 0..) => cx.write_error_message(EvalError::new(EvalErrorKind::NoSuchFact(n))),
        Value::Fact(_) => {}
        _ => report_not_a_fact(cx, "fact-slot-value"),
    }
    Ok(Value::Sym(SYM_FALSE))
}

/// Slot `name` of fact `f`; a slot the fact lacks is FALSE after CLIPS's message,
/// `[INSFUN3]` for a query's `?v:slot` (`query`), else `[TMPLTDEF1]`.
fn slot_of_fact(cx: &mut Core<'_>, f: Ix, name: SymId, query: bool) -> Result<Value, EvalError> {
    let tmpl = cx.facts[f as usize].tmpl;
    // an ordered fact's one slot is `implied`; another name is no slot of it
    let slot = if cx.templates[tmpl as usize].implied && cx.sym_text(name) == "implied" {
        0
    } else {
        match cx.find_slot(tmpl, name) {
            Some(s) => s,
            None => {
                report_invalid_slot(cx, tmpl, name, query);
                // FALSE with CLIPS's evaluation error set: it halts what runs
                cx.st.mode.halting = true;
                return Ok(Value::Sym(SYM_FALSE));
            }
        }
    };
    Ok(cx.fact_slot_value(f, slot)?)
}

/// `[TMPLTDEF1]`. Out of line: its buffer stays off the stack frame of every slot
/// read (`?f:slot`).
#[cold]
#[inline(never)]
fn report_invalid_slot(cx: &mut Core<'_>, tmpl: Ix, name: SymId, query: bool) {
    let mut b: crate::value::TextBuf<256> = crate::value::TextBuf::new();
    // (the image, whose code budget is tight, words both as `[TMPLTDEF1]`)
    #[cfg(not(feature = "extras"))]
    let query = {
        let _ = query;
        false
    };
    let _ = if query {
        core::fmt::Write::write_fmt(
            &mut b,
            format_args!(
                "[INSFUN3] No such slot {} in function fact-set query.\n",
                cx.sym_text(name)
            ),
        )
    } else {
        core::fmt::Write::write_fmt(
            &mut b,
            format_args!(
                "[TMPLTDEF1] Invalid slot {} not defined in corresponding deftemplate {}.\n",
                cx.sym_text(name),
                cx.sym_text(cx.templates[tmpl as usize].name)
            ),
        )
    };
    cx.write(router::WERROR, b.as_str());
}

fn fact_index(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    match cx.arg(a, 0) {
        // CLIPS 6.30 gives -1 for a fact that has been retracted since
        Value::Fact(r) if cx.fact_alive(r) => Ok(Value::Int(r.num as i64)),
        Value::Fact(_) => Ok(Value::Int(-1)),
        _ => Err(EvalError::wrong_type("fact-index", 1, "fact-address")),
    }
}

fn fact_existp(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let v = cx.arg(a, 0);
    if !is_fact_or_index(v) {
        report_not_a_fact(cx, "fact-existp");
    }
    Ok(Core::bool_value(cx.fact_arg(v).is_some()))
}

/// A fact address or a fact index (a negative index is none, nor is a float).
pub(crate) fn is_fact_or_index(v: Value) -> bool {
    matches!(v, Value::Fact(_) | Value::Int(0..))
}

/// A value that is no fact where a fact function wants one (`nil` from an empty query,
/// a float, a negative index): CLIPS's message, and the function gives FALSE without
/// halting the actions.
pub(crate) fn report_not_a_fact(cx: &mut Core<'_>, func: &'static str) {
    cx.write_error_message(EvalError::wrong_type(func, 1, "fact-address or fact-index"));
}

#[allow(dead_code)]
fn _r(_: FactRef) {}
