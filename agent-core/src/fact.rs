//! Fact storage: slots in a pool, values in a compacting value arena, a hash index
//! against duplicates, and a creation-ordered list (fact numbers only grow).

use crate::handle::TokenId;
use crate::value::Ix;
use crate::value::NONE;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum FactState {
    Free,
    Live,
    /// Retracted while a rule fires: values stay readable until the firing ends.
    Pending,
}

#[derive(Clone, Copy, Debug)]
pub struct Fact {
    /// The fact index CLIPS prints as `f-N`.
    pub num: u32,
    pub tmpl: Ix,
    /// Cells in the value arena: single slots take one cell, a multislot a `Multi`
    /// header cell followed by its elements.
    pub start: Ix,
    pub len: Ix,
    /// Creation-ordered list of live facts (or free/pending list link).
    pub next: Ix,
    pub prev: Ix,
    pub hash_next: Ix,
    /// First alpha match of this fact (chained through the tokens' `next_sib`).
    pub first_am: TokenId,
    pub state: FactState,
    /// One cell per slot (`len` is the template's slot count): slot `i` is cell
    /// `start + i`. Kept here (in padding) so the join tests need not load the
    /// template.
    pub flat: bool,
    /// Host: `cells_hash` of its cells, so a retract finds its bucket without
    /// hashing them again (4 bytes per fact the image does without).
    #[cfg(feature = "host-speedups")]
    pub hash: u32,
    /// Host: entries of the logical unsupported stack naming this fact (`u16::MAX`:
    /// too many to count, the stack is searched), so that a retract searches the
    /// stack only for a fact on it (a walk per retract grew with the stack). In
    /// padding.
    #[cfg(all(feature = "host-speedups", feature = "logical"))]
    pub unsupported: u16,
}

/// Host speed-up: a fact's next and previous live fact of its template
/// (`TemplateMem::tfirst`), so a fact-set query walks only those. Without the feature, no
/// bytes (the pool table keeps the array, of zero-sized entries).
#[cfg(feature = "host-speedups")]
pub type TemplateLinks = [Ix; 2];
#[cfg(not(feature = "host-speedups"))]
pub type TemplateLinks = ();
/// The links of a fact in no template list.
#[cfg(feature = "host-speedups")]
pub const NO_TEMPLATE_LINKS: TemplateLinks = [crate::value::NONE; 2];
#[cfg(not(feature = "host-speedups"))]
pub const NO_TEMPLATE_LINKS: TemplateLinks = ();

impl Fact {
    pub const EMPTY: Fact = Fact {
        num: 0,
        tmpl: 0,
        start: 0,
        len: 0,
        next: NONE,
        prev: NONE,
        hash_next: NONE,
        first_am: TokenId::NONE,
        state: FactState::Free,
        flat: false,
        #[cfg(feature = "host-speedups")]
        hash: 0,
        #[cfg(all(feature = "host-speedups", feature = "logical"))]
        unsupported: 0,
    };
}

use crate::engine::{cap, Core};
use crate::error::{CapacityError, EvalError, Pool};
use crate::value::{FactRef, MfSpan, Value};

fn mix(h: u32, x: u64) -> u32 {
    let mut h = h ^ (x as u32) ^ ((x >> 32) as u32).rotate_left(13);
    h = h.wrapping_mul(0x9E37_79B1);
    h ^ (h >> 15)
}

pub(crate) fn value_hash(h: u32, v: Value) -> u32 {
    match v {
        Value::Void | Value::BoundVoid => mix(h, 0),
        Value::Int(i) => mix(h ^ 1, i as u64),
        Value::Float(f) => mix(h ^ 2, f.to_bits()),
        Value::Sym(s) => mix(h ^ 3, s as u64),
        Value::Str(s) => mix(h ^ 4, s as u64),
        Value::Fact(r) => mix(h ^ 5, r.num as u64),
        Value::Multi(m) => mix(h ^ 6, m.len as u64),
    }
}

impl Core<'_> {
    /// The template named `name` the current module sees.
    pub fn find_template(&self, name: SymId) -> Option<Ix> {
        #[cfg(feature = "modules")]
        return self.template_seen_from(name, self.current_module());
        #[cfg(not(feature = "modules"))]
        (0..self.st.pools.ntemplates).find(|&t| self.templates[t as usize].name == name)
    }

    /// The implied (ordered-fact) template for `name`, created on first use.
    pub fn implied_template(&mut self, name: SymId) -> Result<Ix, CapacityError> {
        if let Some(t) = self.find_template(name) {
            return Ok(t);
        }
        let n = self.st.pools.ntemplates as usize;
        #[cfg(feature = "grow")]
        {
            self.ensure(Pool::Templates, n + 1);
            self.ensure(Pool::TemplateMemories, n + 1);
            self.ensure(Pool::SlotDefs, self.st.pools.nslots as usize + 1);
        }
        if n >= self.templates.len() {
            return Err(cap(Pool::Templates, self.templates.len()));
        }
        if n >= self.tmpl_mems.len() {
            return Err(cap(Pool::TemplateMemories, self.tmpl_mems.len()));
        }
        let s = self.st.pools.nslots as usize;
        if s >= self.slots.len() {
            return Err(cap(Pool::SlotDefs, self.slots.len()));
        }
        let implied = self.intern("implied")?;
        self.slots[s] = SlotDef {
            name: implied,
            multi: true,
            ..SlotDef::EMPTY
        };
        self.st.pools.nslots += 1;
        self.templates[n] = Template {
            name,
            first_slot: s as Ix,
            nslots: 1,
            implied: true,
            alpha_head: NONE,
            text: NONE,
        };
        self.tmpl_mems[n] = TemplateMem::EMPTY;
        // made in the current module, as CLIPS's implied deftemplates
        // (room: the template memories just written)
        #[cfg(feature = "modules")]
        let _ = self.set_template_module(n as Ix, self.current_module());
        self.st.pools.ntemplates += 1;
        self.note_hw(Pool::Templates, n + 1);
        self.note_hw(Pool::SlotDefs, s + 1);
        Ok(n as Ix)
    }

    pub fn slot_def(&self, tmpl: Ix, slot: Ix) -> SlotDef {
        self.slots[(self.templates[tmpl as usize].first_slot + slot) as usize]
    }

    pub fn find_slot(&self, tmpl: Ix, name: SymId) -> Option<Ix> {
        let t = self.templates[tmpl as usize];
        (0..t.nslots).find(|&i| self.slots[(t.first_slot + i) as usize].name == name)
    }

    /// Cell index of slot `slot` of a fact, and for a multislot its element count.
    pub fn slot_cell(&self, fact: Ix, slot: Ix) -> (usize, Option<Ix>) {
        self.slot_cell_inline(fact, slot)
    }

    /// `slot_cell`, inlined where a hot loop reads cells (the host's planned join
    /// tests: an out-of-line call there cost a benchmark 5.7 %).
    #[inline(always)]
    pub(crate) fn slot_cell_inline(&self, fact: Ix, slot: Ix) -> (usize, Option<Ix>) {
        let f = &self.facts[fact as usize];
        let mut c = f.start as usize;
        for _ in 0..slot {
            match self.values[c] {
                Value::Multi(m) => c += 1 + m.len as usize,
                _ => c += 1,
            }
        }
        match self.values[c] {
            Value::Multi(m) => (c, Some(m.len)),
            _ => (c, None),
        }
    }

    /// Slot value of a fact as an evaluation value (multislots are copied to scratch).
    pub fn fact_slot_value(&mut self, fact: Ix, slot: Ix) -> Result<Value, CapacityError> {
        let f = &self.facts[fact as usize];
        if f.flat {
            // one cell per slot: no walk over the slots before it
            let v = self.values[(f.start + slot) as usize];
            if !v.is_multi() {
                return Ok(v);
            }
        }
        let (c, multi) = self.slot_cell(fact, slot);
        match multi {
            None => Ok(self.values[c]),
            Some(n) => self.copy_to_scratch(c + 1, n as usize),
        }
    }

    /// Copies `n` fact cells starting at `cell` into scratch as a multifield.
    pub fn copy_to_scratch(&mut self, cell: usize, n: usize) -> Result<Value, CapacityError> {
        let s = self.scratch_alloc(n)?;
        for i in 0..n {
            self.scratch[s as usize + i] = self.values[cell + i];
        }
        Ok(Value::Multi(MfSpan {
            start: s,
            len: n as Ix,
        }))
    }

    pub fn fact_ref(&self, slot: Ix) -> FactRef {
        FactRef {
            slot,
            num: self.facts[slot as usize].num,
        }
    }

    /// A fact address is usable if its slot still holds that fact, live.
    pub fn fact_alive(&self, r: FactRef) -> bool {
        self.facts
            .get(r.slot as usize)
            .is_some_and(|f| f.num == r.num && f.state == FactState::Live)
    }

    /// A fact address whose cells are still there: live, or retracted while a firing
    /// or a top-level query holds it (pending). Query slot reads (`?f:x`) use it: CLIPS
    /// reads a retracted query fact's old values there, `fact-slot-value` gives FALSE.
    pub fn fact_readable(&self, r: FactRef) -> bool {
        self.facts
            .get(r.slot as usize)
            .is_some_and(|f| f.num == r.num && f.state != FactState::Free)
    }

    /// Fact slot holding live fact number `num`.
    pub fn find_fact(&self, num: u32) -> Option<Ix> {
        let mut f = self.st.facts.fact_head;
        while f != NONE {
            let x = &self.facts[f as usize];
            if x.num == num {
                return Some(f);
            }
            if x.num > num {
                return None;
            }
            f = x.next;
        }
        None
    }

    pub(crate) fn cells_hash(&self, tmpl: Ix, start: usize, len: usize) -> u32 {
        let mut h = mix(0x1234_5678, tmpl as u64);
        for i in 0..len {
            h = value_hash(h, self.values[start + i]);
        }
        h
    }

    fn cells_equal(&self, a: usize, b: usize, len: usize) -> bool {
        (0..len).all(|i| self.values[a + i].same(self.values[b + i]))
    }

    /// Packs the cells of live and pending facts down to the bottom of the arena, in
    /// cell order, and drops the cells free fact slots kept (see `free_fact_slot`).
    /// Cells are not in list order (a new fact may take a freed fact's cells), so the
    /// facts with cells are first chained through `prev` and, unless already in cell
    /// order, sorted by start (merge sort, no storage); the live list's `prev` links
    /// are rebuilt after.
    fn compact_values(&mut self) {
        self.forget_free_cells();
        // chained in list order: while no fact took another's cells (a load, a run
        // without retracts) that is cell order already, and the sort is skipped
        let (mut chain, mut tail, mut sorted, mut last) = (NONE, NONE, true, 0);
        for list in [self.st.facts.fact_head, self.st.facts.pending] {
            let mut f = list;
            while f != NONE {
                let x = self.facts[f as usize];
                if x.len != 0 {
                    self.facts[f as usize].prev = NONE;
                    if tail == NONE {
                        chain = f;
                    } else {
                        self.facts[tail as usize].prev = f;
                    }
                    tail = f;
                    sorted &= x.start >= last;
                    last = x.start;
                }
                f = x.next;
            }
        }
        let mut f = if sorted {
            chain
        } else {
            sort_by_start(self.facts, chain)
        };
        let mut dst = 0usize;
        while f != NONE {
            let x = self.facts[f as usize];
            let (s, l) = (x.start as usize, x.len as usize);
            if s != dst {
                self.values.copy_within(s..s + l, dst);
                self.facts[f as usize].start = dst as Ix;
            }
            dst += l;
            f = x.prev;
        }
        self.st.facts.values_top = dst as Ix;
        let (mut p, mut f) = (NONE, self.st.facts.fact_head);
        while f != NONE {
            self.facts[f as usize].prev = p;
            p = f;
            f = self.facts[f as usize].next;
        }
    }

    /// The cells of live and pending facts: what a compaction leaves (the rest
    /// below the top, kept by free slots or by none, it reclaims).
    fn held_cells(&self) -> usize {
        let mut held = 0usize;
        for list in [self.st.facts.fact_head, self.st.facts.pending] {
            let mut f = list;
            while f != NONE {
                held += self.facts[f as usize].len as usize;
                f = self.facts[f as usize].next;
            }
        }
        held
    }

    /// At most `held_cells`, in one step per template instead of one per fact: a
    /// fact holds a cell per slot at least (a multislot one more per field), so a
    /// template's live facts hold its slot count times their number or more. Without
    /// multislot fields or pending facts it is `held_cells`.
    #[cfg(feature = "grow")]
    fn held_cells_at_least(&self) -> usize {
        (0..self.st.pools.ntemplates as usize)
            .map(|t| self.templates[t].nslots as usize * self.tmpl_mems[t].nfacts as usize)
            .sum()
    }

    /// Free fact slots give up the cells they kept: the arena below the top is
    /// reused or packed (compaction, `reset`).
    pub(crate) fn forget_free_cells(&mut self) {
        let mut f = self.st.pools.fact_free;
        while f != NONE {
            self.facts[f as usize].len = 0;
            f = self.facts[f as usize].next;
        }
    }

    /// Reserves `n` cells at the top of the value arena (compacting if needed).
    fn reserve_cells(&mut self, n: usize) -> Result<usize, CapacityError> {
        let cap_v = self.values.len().min(NONE as usize);
        if self.st.facts.values_top as usize + n > cap_v {
            // a compaction that would leave the held cells over three quarters full
            // is followed by growth: grow at once and skip its sort and copy (the
            // garbage stays until a later compaction). Counting the held cells here
            // (a walk of the fact lists, rarer than asserts by a quarter of the
            // arena) costs the asserts and retracts nothing. The walk is skipped when
            // the live facts' slots alone show it (after asserts without retracts).
            #[cfg(feature = "grow")]
            {
                let top = self.st.facts.values_top as usize;
                let full = cap_v - cap_v / 4;
                if self.grows()
                    && (self.held_cells_at_least() + n > full || self.held_cells() + n > full)
                    && self
                        .grow(Pool::FactValues, (top + n).max(cap_v + 1))
                        .is_ok()
                    && top + n <= self.values.len().min(NONE as usize)
                {
                    return Ok(top);
                }
            }
            self.compact_values();
            // growing once the live cells fill three quarters keeps compaction rare
            #[cfg(feature = "grow")]
            let cap_v = if self.st.facts.values_top as usize + n > cap_v - cap_v / 4 {
                let need = (self.st.facts.values_top as usize + n).max(cap_v + 1);
                let grown = self.grow(Pool::FactValues, need);
                let cap_v = self.values.len().min(NONE as usize);
                if self.st.facts.values_top as usize + n > cap_v {
                    grown?;
                }
                cap_v
            } else {
                cap_v
            };
            if self.st.facts.values_top as usize + n > cap_v {
                return Err(cap(Pool::FactValues, self.values.len()));
            }
        }
        Ok(self.st.facts.values_top as usize)
    }

    /// The cells a new fact of `need` cells can take without the arena top: those
    /// the free slot it will get kept from its last fact, if enough (they were that
    /// fact's, now garbage: `free_fact_slot`). So the facts a firing retracts make
    /// room for those the next one asserts without compaction, which costs in
    /// proportion to the fact base.
    #[inline]
    fn reusable_cells(&self, need: usize) -> Option<usize> {
        let s = self.st.pools.fact_free;
        if s == NONE || need == 0 {
            return None;
        }
        let f = &self.facts[s as usize];
        (f.len as usize >= need).then_some(f.start as usize)
    }

    /// Value cells a fact made from per-slot values on the stack at `base` takes.
    fn cells_needed(&self, tmpl: Ix, base: usize) -> usize {
        let n = self.templates[tmpl as usize].nslots as usize;
        (0..n)
            .map(|i| match self.stack[base + i] {
                Value::Multi(m) => 1 + m.len as usize,
                _ => 1,
            })
            .sum()
    }

    /// Whether every fact slot has been handed out (the free list aside).
    fn fact_slots_exhausted(&self) -> bool {
        self.st.pools.facts_used as usize >= self.facts.len().min(NONE as usize - 1)
    }

    /// No fact slot is free to take: neither a freed one nor a never-used one.
    pub(crate) fn fact_slots_full(&self) -> bool {
        self.st.pools.fact_free == NONE && self.fact_slots_exhausted()
    }

    /// Writes per-slot values from the stack at `base` into cells from `start`.
    fn write_cells(&mut self, tmpl: Ix, base: usize, start: usize) {
        let mut c = start;
        for i in 0..self.templates[tmpl as usize].nslots as usize {
            match self.stack[base + i] {
                Value::Multi(m) => {
                    self.values[c] = Value::Multi(MfSpan {
                        start: 0,
                        len: m.len,
                    });
                    c += 1;
                    for k in 0..m.len as usize {
                        self.values[c] = self.scratch[m.start as usize + k];
                        c += 1;
                    }
                }
                v => {
                    self.values[c] = v;
                    c += 1;
                }
            }
        }
    }

    /// Checks, before a modify retracts `old`, that the new fact (values on the stack
    /// at `base`) will find a fact slot and value cells, so a full pool fails with
    /// nothing changed. During a firing the retracted fact stays readable (pending):
    /// its slot and cells are not given back until the firing ends. A top-level query
    /// holds it too, but only so that `?f:slot` reads the old values: on a full pool
    /// the modify matters more, so the old fact is freed at once (`?f:slot` then reads
    /// FALSE). Returns whether the retract holds the old fact (`retract_fact_held`).
    pub(crate) fn modify_fits(
        &mut self,
        old: Ix,
        tmpl: Ix,
        base: usize,
    ) -> Result<bool, CapacityError> {
        let slots_full = self.fact_slots_full();
        #[cfg(feature = "grow")]
        let slots_full = slots_full
            && self
                .grow(Pool::Facts, self.st.pools.facts_used as usize + 1)
                .is_err();
        if slots_full && self.st.mode.firing {
            return Err(cap(Pool::Facts, self.facts.len()));
        }
        let hold = self.st.mode.firing || (self.st.eval.query_hold > 0 && !slots_full);
        let need = self.cells_needed(tmpl, base);
        let cap_v = self.values.len().min(NONE as usize);
        // in a firing the retract holds the old fact and frees no slot: the new fact
        // takes the free slot's cells the assert will find (`reusable_cells`)
        if self.st.facts.values_top as usize + need <= cap_v
            || (self.st.mode.firing && self.reusable_cells(need).is_some())
        {
            return Ok(hold);
        }
        // what compaction would leave: the cells of live and pending facts
        let mut used = self.held_cells();
        if !hold {
            used -= self.facts[old as usize].len as usize;
        }
        if used + need > cap_v {
            crate::engine::full_pool!(self, Pool::FactValues, used + need, self.values.len());
        }
        Ok(hold)
    }

    /// Puts back a fact a failed modify retracted: the same slot, number and values,
    /// at its place in the creation-ordered list (its cells too), with its matches
    /// built again. `saved` is the fact as it was; `base` holds its slot values on the
    /// stack (needed when the retract freed its cells, i.e. outside a firing).
    pub(crate) fn restore_fact(
        &mut self,
        slot: Ix,
        saved: Fact,
        base: usize,
    ) -> Result<(), EvalError> {
        // the creation-ordered list: after the last fact with a smaller number
        let mut prev = self.st.facts.fact_tail;
        while prev != NONE && self.facts[prev as usize].num > saved.num {
            prev = self.facts[prev as usize].prev;
        }
        let next = if prev == NONE {
            self.st.facts.fact_head
        } else {
            self.facts[prev as usize].next
        };
        let (start, len) = match self.facts[slot as usize].state {
            FactState::Pending => {
                remove_from_list(self.facts, &mut self.st.facts.pending, slot);
                let f = self.facts[slot as usize];
                // its cells stayed where they were (compaction moves pending facts)
                (f.start, f.len)
            }
            FactState::Free => {
                remove_from_list(self.facts, &mut self.st.pools.fact_free, slot);
                let need = self.cells_needed(saved.tmpl, base);
                // the cells the slot kept, if enough (off the free list, a slot
                // keeps none: compaction would not know them)
                let kept = self.facts[slot as usize];
                self.facts[slot as usize].len = 0;
                let at = if need == 0 {
                    0
                } else if kept.len as usize >= need {
                    kept.start as usize
                } else {
                    match self.reserve_cells(need) {
                        Ok(s) => {
                            self.st.facts.values_top = (s + need) as Ix;
                            s
                        }
                        Err(e) => {
                            self.free_fact_slot(slot);
                            return Err(e.into());
                        }
                    }
                };
                self.write_cells(saved.tmpl, base, at);
                (at as Ix, need as Ix)
            }
            // still there: nothing was retracted
            FactState::Live => return Ok(()),
        };
        let h = self.cells_hash(saved.tmpl, start as usize, len as usize);
        let bucket = h as usize % self.fact_buckets.len();
        self.facts[slot as usize] = Fact {
            start,
            len,
            next,
            prev,
            hash_next: self.fact_buckets[bucket],
            first_am: TokenId::NONE,
            state: FactState::Live,
            flat: len == self.templates[saved.tmpl as usize].nslots,
            #[cfg(feature = "host-speedups")]
            hash: h,
            #[cfg(all(feature = "host-speedups", feature = "logical"))]
            unsupported: 0,
            ..saved
        };
        self.fact_buckets[bucket] = slot;
        self.st.facts.facts_live += 1;
        self.tmpl_mems[saved.tmpl as usize].nfacts += 1;
        if prev == NONE {
            self.st.facts.fact_head = slot;
        } else {
            self.facts[prev as usize].next = slot;
        }
        if next == NONE {
            self.st.facts.fact_tail = slot;
        } else {
            self.facts[next as usize].prev = slot;
        }
        #[cfg(feature = "host-speedups")]
        self.tmpl_link(slot);
        // it needs no more room than its retract freed: what a not output passes on
        // waits until every pattern of the fact is in (see `State::defer_nots`)
        self.st.net.defer_nots = true;
        let r = self.network_assert(slot);
        self.st.net.defer_nots = false;
        if let Err(e) = r {
            self.network_retract_checked(slot);
            self.unlink_fact(slot);
            self.release_fact_values(slot);
            self.free_fact_slot(slot);
            return Err(e);
        }
        Ok(())
    }

    /// Creates a fact from per-slot values on the evaluation stack at `base` (a
    /// multislot's value is a scratch `Multi`). Returns `None` for a duplicate.
    /// Runs the network; on a full pool the fact is removed again and the error returned.
    pub fn assert_slots(&mut self, tmpl: Ix, base: usize) -> Result<Option<Ix>, EvalError> {
        // until a rule with a `logical` CE exists there is no support to add, check or
        // retract: one test here instead of one per step (host; the image has no
        // `logical`)
        #[cfg(feature = "logical")]
        if !self.st.logical.defined {
            return self.assert_slots_in::<false>(tmpl, base);
        }
        self.assert_slots_in::<true>(tmpl, base)
    }

    /// `assert_slots`; `TMS` false: no rule with a `logical` CE exists (feature
    /// `logical`: then the support steps are left out).
    fn assert_slots_in<const TMS: bool>(
        &mut self,
        tmpl: Ix,
        base: usize,
    ) -> Result<Option<Ix>, EvalError> {
        // no pattern matching runs here (asserting during it is refused): the token
        // index may grow now (`grow`), once it has fewer buckets than the token pool
        // has entries (the fixed host engine's ratio, which a seeded start keeps)
        #[cfg(feature = "grow")]
        if self.amem_buckets.len() < self.tokens.len() && self.grows() && self.st.net.matching == 0
        {
            self.grow_token_index();
        }
        let defer = core::mem::take(&mut self.st.net.defer_next);
        // a deferred propagation (`rete::defer`) belongs to an earlier assert: built
        // first, or the assert fails with nothing changed (unless this fact's waits
        // behind it)
        if self.st.net.deferred.fact != NONE && !(defer && self.may_queue(tmpl)) {
            self.flush_deferred()?;
        }
        // matches an earlier removal still owes come first: without room for them
        // the assert fails with nothing changed
        self.pay_owed()?;
        let need = self.cells_needed(tmpl, base);
        // what a command at the prompt retracted is kept readable only while there is
        // room: an assert that needs it frees it (not a rule's, in its firing)
        // (`firing` first: a rule's asserts, most, decide on one test)
        if !self.st.mode.firing
            && self.st.eval.query_hold == crate::engine::COMMAND_HOLD
            && self.st.facts.pending != NONE
            && (self.fact_slots_full()
                || (self.st.facts.values_top as usize + need > self.values.len()
                    && self.reusable_cells(need).is_none()))
        {
            self.free_pending();
        }
        if self.fact_slots_full() {
            crate::engine::full_pool!(
                self,
                Pool::Facts,
                self.st.pools.facts_used as usize + 1,
                self.facts.len()
            );
        }
        // the logical support this assert may add needs an entry
        #[cfg(feature = "logical")]
        if TMS {
            self.support_room()?;
        }
        // the cells the free slot kept, else new ones at the top (none: start 0, so
        // the fact never ends past the top when that comes down)
        let reused = self.reusable_cells(need);
        let start = match reused {
            Some(s) => s,
            None if need == 0 => 0,
            None => self.reserve_cells(need)?,
        };
        self.write_cells(tmpl, base, start);
        let h = self.cells_hash(tmpl, start, need);
        let bucket = h as usize % self.fact_buckets.len();
        // with duplication allowed an equal fact is made again, as in CLIPS (tested
        // only when the bucket holds a fact)
        let mut d = self.fact_buckets[bucket];
        while d != NONE && !self.st.mode.fact_duplication {
            // host: a fact keeps its full hash, so only an equal one is compared cell
            // by cell (a chain's other facts, of the same template and length in most
            // programs, lengthen as the fact base grows); its other fields are read
            // only then, not copied at every step
            #[cfg(feature = "host-speedups")]
            {
                let df = &self.facts[d as usize];
                if df.hash != h {
                    d = df.hash_next;
                    continue;
                }
            }
            let df = self.facts[d as usize];
            if df.tmpl == tmpl
                && df.len as usize == need
                && self.cells_equal(df.start as usize, start, need)
            {
                // no new fact; its support may change (`logical`)
                #[cfg(feature = "logical")]
                if TMS {
                    self.support_existing_fact(d);
                }
                return Ok(None);
            }
            d = df.hash_next;
        }
        // a logical rule whose partial match went creates nothing (as CLIPS)
        #[cfg(feature = "logical")]
        if TMS && !self.logical_may_assert() {
            return Ok(None);
        }
        // allocate the fact slot
        // (the free slot `reusable_cells` looked at: nothing freed one since)
        let slot = if self.st.pools.fact_free != NONE {
            let s = self.st.pools.fact_free;
            self.st.pools.fact_free = self.facts[s as usize].next;
            s
        } else {
            self.st.pools.facts_used += 1;
            self.st.pools.facts_used - 1
        };
        if reused.is_none() && need != 0 {
            self.st.facts.values_top = (start + need) as Ix;
        }
        let num = self.st.facts.next_fact_num;
        self.st.facts.next_fact_num += 1;
        self.st.eval.effects = self.st.eval.effects.wrapping_add(1);
        self.facts[slot as usize] = Fact {
            num,
            tmpl,
            start: start as Ix,
            len: need as Ix,
            next: NONE,
            prev: self.st.facts.fact_tail,
            hash_next: self.fact_buckets[bucket],
            first_am: TokenId::NONE,
            state: FactState::Live,
            flat: need == self.templates[tmpl as usize].nslots as usize,
            #[cfg(feature = "host-speedups")]
            hash: h,
            #[cfg(all(feature = "host-speedups", feature = "logical"))]
            unsupported: 0,
        };
        self.fact_buckets[bucket] = slot;
        self.st.facts.facts_live += 1;
        self.tmpl_mems[tmpl as usize].nfacts += 1;
        if self.st.facts.fact_tail != NONE {
            self.facts[self.st.facts.fact_tail as usize].next = slot;
        } else {
            self.st.facts.fact_head = slot;
        }
        self.st.facts.fact_tail = slot;
        // host: the newest fact, last in its template's list too
        #[cfg(feature = "host-speedups")]
        {
            let t = &mut self.tmpl_mems[tmpl as usize];
            self.fact_tlinks[slot as usize] = [NONE, t.tlast];
            if t.tlast == NONE {
                t.tfirst = slot;
            } else {
                self.fact_tlinks[t.tlast as usize][0] = slot;
            }
            t.tlast = slot;
        }
        let live = self.count_live_facts_hint();
        self.note_hw(Pool::Facts, live);
        self.note_hw(Pool::FactValues, self.st.facts.values_top as usize);
        #[cfg(feature = "logical")]
        if TMS {
            self.support_new_fact(slot);
        }
        // an undone assert prints nothing (see `hold`)
        self.hold_traces();
        if self.st.mode.watch & crate::engine::watch::FACTS != 0 && self.fact_line_traced(slot) {
            self.print_fact_line("==> ", slot);
        }
        // CLIPS checks the new fact (dynamic constraint checking) before matching it
        #[cfg(feature = "extras")]
        let defer = !(self.st.mode.dynamic_checks && self.report_violation(slot)) && defer;
        if defer && self.may_defer(tmpl) {
            // the propagation waits for the next action (`rete::defer`)
            let old = self.st.facts.modify_old.take();
            self.defer_fact(slot, old);
            self.release_traces(true);
            return Ok(Some(slot));
        }
        // the activations the new fact's blockers remove are noted, to put them back
        // in their agenda places should the assert fail
        let mark = self.journal_begin();
        // a `not` the fact unblocked on the way (a blocker of a nested `not` taken
        // back) may have found no room: the assert is complete only once it is built
        let r = self.network_assert(slot).and_then(|()| self.pay_owed());
        self.journal_pause();
        if let Err(e) = r {
            // Undo: remove what the fact built, then the fact itself, silently. The
            // removal rebuilds what the fact had blocked from the tokens it frees
            // (anything that does not fit at once is owed and paid right after).
            self.journal_replay(mark);
            #[cfg(feature = "logical")]
            if TMS {
                self.fact_leaves(slot);
            }
            self.network_retract_checked(slot);
            self.unlink_fact(slot);
            // cells from the top go back to it; reused ones stay the slot's
            if reused.is_none() {
                self.facts[slot as usize].len = 0;
                if need != 0 {
                    self.st.facts.values_top = start as Ix;
                }
            }
            self.free_fact_slot(slot);
            self.st.facts.next_fact_num = num;
            #[cfg(feature = "extras")]
            self.forget_pattern_error();
            let _ = self.pay_owed();
            self.journal_end(mark);
            self.release_traces(false);
            return Err(e);
        }
        self.journal_end(mark);
        self.release_traces(true);
        // the facts whose support the new fact took (blocking a `not`) go now
        #[cfg(feature = "logical")]
        if TMS {
            self.force_logical_retractions();
        }
        Ok(Some(slot))
    }

    /// Host: links a restored fact into its template's list, after the last fact of
    /// the template with a smaller number.
    #[cfg(feature = "host-speedups")]
    fn tmpl_link(&mut self, slot: Ix) {
        let (tmpl, num) = (
            self.facts[slot as usize].tmpl,
            self.facts[slot as usize].num,
        );
        let mut p = self.tmpl_mems[tmpl as usize].tlast;
        while p != NONE && self.facts[p as usize].num > num {
            p = self.fact_tlinks[p as usize][1];
        }
        let n = if p == NONE {
            self.tmpl_mems[tmpl as usize].tfirst
        } else {
            self.fact_tlinks[p as usize][0]
        };
        self.fact_tlinks[slot as usize] = [n, p];
        if p == NONE {
            self.tmpl_mems[tmpl as usize].tfirst = slot;
        } else {
            self.fact_tlinks[p as usize][0] = slot;
        }
        if n == NONE {
            self.tmpl_mems[tmpl as usize].tlast = slot;
        } else {
            self.fact_tlinks[n as usize][1] = slot;
        }
    }

    fn count_live_facts_hint(&self) -> usize {
        // facts_used is the pool high mark; good enough as a high-water figure
        self.st.pools.facts_used as usize
    }

    pub(crate) fn unlink_fact(&mut self, slot: Ix) {
        let f = self.facts[slot as usize];
        self.st.facts.facts_live -= 1;
        let t = &mut self.tmpl_mems[f.tmpl as usize];
        t.nfacts = t.nfacts.saturating_sub(1);
        if f.prev != NONE {
            self.facts[f.prev as usize].next = f.next;
        } else {
            self.st.facts.fact_head = f.next;
        }
        if f.next != NONE {
            self.facts[f.next as usize].prev = f.prev;
        } else {
            self.st.facts.fact_tail = f.prev;
        }
        #[cfg(feature = "host-speedups")]
        {
            let [tnext, tprev] = self.fact_tlinks[slot as usize];
            let t = &mut self.tmpl_mems[f.tmpl as usize];
            if tprev == NONE {
                t.tfirst = tnext;
            } else {
                self.fact_tlinks[tprev as usize][0] = tnext;
            }
            if tnext == NONE {
                t.tlast = tprev;
            } else {
                self.fact_tlinks[tnext as usize][1] = tprev;
            }
        }
        // hash chain
        #[cfg(feature = "host-speedups")]
        let h = f.hash;
        #[cfg(not(feature = "host-speedups"))]
        let h = self.cells_hash(f.tmpl, f.start as usize, f.len as usize);
        let bucket = h as usize % self.fact_buckets.len();
        let mut p = self.fact_buckets[bucket];
        if p == slot {
            self.fact_buckets[bucket] = f.hash_next;
        } else {
            while p != NONE {
                let n = self.facts[p as usize].hash_next;
                if n == slot {
                    self.facts[p as usize].hash_next = f.hash_next;
                    break;
                }
                p = n;
            }
        }
    }

    /// Puts a fact slot on the free list. It keeps `start` and `len`: its cells are
    /// garbage the next fact to take the slot may reuse (`reusable_cells`), until
    /// compaction or a reset drops them (`forget_free_cells`). Cells that are no
    /// longer its own must have been given up (`len` 0) before.
    pub(crate) fn free_fact_slot(&mut self, slot: Ix) {
        self.facts[slot as usize].state = FactState::Free;
        self.facts[slot as usize].next = self.st.pools.fact_free;
        self.st.pools.fact_free = slot;
    }

    /// Retracts a live fact: watch line, network removal, then the slot is freed (or
    /// kept readable until the current firing or top-level query tuple ends).
    pub fn retract_fact(&mut self, slot: Ix) {
        self.retract_fact_held(slot, self.st.mode.firing || self.st.eval.query_hold > 0);
    }

    /// Retracts a live fact; `hold` keeps its slot and cells readable (pending).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn retract_fact_held(&mut self, slot: Ix, hold: bool) {
        // (as `assert_slots`: no support to drop or retract before a `logical` rule;
        // host: one test for that and for CLIPS's copies to place, which also take
        // the slow path, so the plain path's code stays as it is)
        #[cfg(all(feature = "logical", feature = "grow"))]
        if !self.st.prime.slow_retract {
            return self.retract_fact_in::<false>(slot, hold);
        }
        #[cfg(all(feature = "logical", not(feature = "grow")))]
        if !self.st.logical.defined {
            return self.retract_fact_in::<false>(slot, hold);
        }
        self.retract_fact_in::<true>(slot, hold)
    }

    /// `retract_fact_held`; `TMS` as for `assert_slots_in`.
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn retract_fact_in<const TMS: bool>(&mut self, slot: Ix, hold: bool) {
        if self.st.mode.watch & crate::engine::watch::FACTS != 0 && self.fact_line_traced(slot) {
            self.print_fact_line("<== ", slot);
        }
        #[cfg(feature = "logical")]
        if TMS {
            self.fact_leaves(slot);
        }
        self.st.net.dying = slot;
        if TMS {
            self.network_retract_checked(slot);
        } else {
            self.network_retract(slot);
        }
        // one load of the network state for the three accesses (through `self.st`
        // each store made the compiler load the pointer again)
        let net = &mut self.st.net;
        net.dying = NONE;
        net.dying_hidden = false;
        // what the retract unblocked and could not rebuild on a full pool is owed:
        // the tokens the fact itself freed may be enough now
        if net.owed != TokenId::NONE {
            let _ = self.pay_owed();
        }
        self.unlink_fact(slot);
        if hold {
            self.facts[slot as usize].state = FactState::Pending;
            self.facts[slot as usize].next = self.st.facts.pending;
            self.st.facts.pending = slot;
        } else {
            self.release_fact_values(slot);
            self.free_fact_slot(slot);
        }
        // then the facts it alone supported, and theirs (`logical`)
        #[cfg(feature = "logical")]
        if TMS {
            self.force_logical_retractions();
        }
    }

    /// Gives back an unlinked fact's cells when they are the arena's top ones (the
    /// slot then keeps none; else it keeps them for its next fact, `free_fact_slot`).
    /// Facts without cells start at 0, so none ends past the new top.
    pub(crate) fn release_fact_values(&mut self, slot: Ix) {
        let f = &mut self.facts[slot as usize];
        if f.len != 0 && f.start as usize + f.len as usize == self.st.facts.values_top as usize {
            self.st.facts.values_top = f.start;
            f.len = 0;
        }
    }

    /// Frees facts retracted during a firing.
    pub fn free_pending(&mut self) {
        while self.st.facts.pending != NONE {
            let s = self.st.facts.pending;
            self.st.facts.pending = self.facts[s as usize].next;
            self.free_fact_slot(s);
        }
    }

    /// Facts on the live list (kept as a count: `watch statistics` asks per firing).
    pub fn live_fact_count(&self) -> usize {
        self.st.facts.facts_live as usize
    }
}

use crate::template::{SlotDef, Template, TemplateMem};
use crate::value::SymId;

/// Sorts a list of facts chained through `prev` by cell start (bottom-up merge sort
/// of the list, as in S. Tatham's list merge sort: O(n log n), no storage); returns
/// the new head.
fn sort_by_start(facts: &mut [Fact], mut list: Ix) -> Ix {
    let mut k = 1usize;
    loop {
        let (mut p, mut tail, mut merges) = (list, NONE, 0usize);
        list = NONE;
        while p != NONE {
            merges += 1;
            // p: a run of up to k facts; q: the next run
            let (mut q, mut psize) = (p, 0usize);
            while psize < k && q != NONE {
                psize += 1;
                q = facts[q as usize].prev;
            }
            let mut qsize = k;
            while psize > 0 || (qsize > 0 && q != NONE) {
                let take_p = psize > 0
                    && (qsize == 0
                        || q == NONE
                        || facts[p as usize].start <= facts[q as usize].start);
                let e = if take_p {
                    let e = p;
                    p = facts[p as usize].prev;
                    psize -= 1;
                    e
                } else {
                    let e = q;
                    q = facts[q as usize].prev;
                    qsize -= 1;
                    e
                };
                if tail == NONE {
                    list = e;
                } else {
                    facts[tail as usize].prev = e;
                }
                tail = e;
            }
            p = q;
        }
        if tail != NONE {
            facts[tail as usize].prev = NONE;
        }
        if merges <= 1 {
            return list;
        }
        k *= 2;
    }
}

/// Unlinks `slot` from a singly linked list of fact slots chained through `next`
/// (the free list or the pending list).
fn remove_from_list(facts: &mut [Fact], head: &mut Ix, slot: Ix) {
    if *head == slot {
        *head = facts[slot as usize].next;
        return;
    }
    let mut p = *head;
    while p != NONE {
        let n = facts[p as usize].next;
        if n == slot {
            facts[p as usize].next = facts[slot as usize].next;
            return;
        }
        p = n;
    }
}
