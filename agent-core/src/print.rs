//! Printing values, facts, activations and watch traces exactly as CLIPS 6.30 does.

use crate::handle::TokenId;
use crate::value::Ix;
use core::fmt::{self, Write};

use crate::engine::{watch, Core};
use crate::fact::Fact;
use crate::host::{router, Host, RouterWriter};
use crate::rule::{Activation, Rule};
use crate::template::{SlotDef, Template};
#[cfg(feature = "extras")]
use crate::value::FactRef;
use crate::value::{write_float, SymId, Value, NONE};

/// Read-only view of what printing needs, borrowed next to the host.
pub struct View<'a> {
    pub values: &'a [Value],
    pub scratch: &'a [Value],
    pub syms: crate::symbols::SymTexts<'a>,
    pub templates: crate::rom::RomRef<'a, Template>,
    pub slots: crate::rom::RomRef<'a, SlotDef>,
    pub facts: &'a [Fact],
}

/// The [`View`] of a `Core`'s pools with the symbol texts `syms`, and of the
/// `Core`'s own symbols without it. A macro, not a method: it borrows the fields it
/// names only, so a caller keeps the host (or the symbol arena's free end) mutably
/// borrowed beside it.
macro_rules! print_view {
    ($cx:expr) => {
        $crate::print::print_view!(
            $cx,
            $crate::symbols::SymTexts {
                rom: $cx.st.rom.symbols,
                entries: $cx.sym_entries,
                bytes: $cx.sym_bytes,
            }
        )
    };
    ($cx:expr, $syms:expr) => {
        $crate::print::View {
            values: $cx.values,
            scratch: $cx.scratch,
            syms: $syms,
            templates: $cx.templates.as_ref(),
            slots: $cx.slots.as_ref(),
            facts: $cx.facts,
        }
    };
}
pub(crate) use print_view;

impl View<'_> {
    pub fn sym(&self, id: SymId) -> &str {
        self.syms.text(id)
    }

    /// A value as CLIPS prints results: strings quoted, multifields in parentheses.
    pub fn write_value(&self, out: &mut dyn Write, v: Value, quote: bool) -> fmt::Result {
        match v {
            Value::Void | Value::BoundVoid => Ok(()),
            Value::Int(i) => write!(out, "{i}"),
            Value::Float(f) => write_float(out, f),
            Value::Sym(s) => out.write_str(self.sym(s)),
            Value::Str(s) => {
                if quote {
                    write_quoted(out, self.sym(s))
                } else {
                    out.write_str(self.sym(s))
                }
            }
            #[cfg(feature = "extras")]
            Value::Fact(r) if r.slot == NONE => out.write_str(if r == FactRef::DUMMY_FACT {
                "<Dummy Fact>"
            } else {
                "<Dummy Instance>"
            }),
            Value::Fact(r) => write!(out, "<Fact-{}>", r.num),
            Value::Multi(m) => {
                out.write_char('(')?;
                for i in 0..m.len as usize {
                    if i > 0 {
                        out.write_char(' ')?;
                    }
                    self.write_value(out, self.scratch[m.start as usize + i], quote)?;
                }
                out.write_char(')')
            }
        }
    }

    /// Elements of a multifield separated by spaces, no parentheses (printout style).
    pub fn write_flat(&self, out: &mut dyn Write, v: Value, quote: bool) -> fmt::Result {
        match v {
            Value::Multi(m) => {
                for i in 0..m.len as usize {
                    if i > 0 {
                        out.write_char(' ')?;
                    }
                    self.write_value(out, self.scratch[m.start as usize + i], quote)?;
                }
                Ok(())
            }
            _ => self.write_value(out, v, quote),
        }
    }

    /// `(name v...)` or `(name (slot v) (mslot a b))`.
    pub fn write_fact(&self, out: &mut dyn Write, slot: Ix) -> fmt::Result {
        self.write_fact_as(out, slot, false)
    }

    /// A fact as `save-facts` writes it: strings with `"` and `\` escaped, so that
    /// `load-facts` reads them back unchanged (listings print them bare).
    pub fn write_fact_escaped(&self, out: &mut dyn Write, slot: Ix) -> fmt::Result {
        self.write_fact_as(out, slot, true)
    }

    fn write_atom(&self, out: &mut dyn Write, v: Value, escape: bool) -> fmt::Result {
        match v {
            Value::Str(s) if escape => {
                out.write_char('"')?;
                for c in self.sym(s).chars() {
                    if c == '"' || c == '\\' {
                        out.write_char('\\')?;
                    }
                    out.write_char(c)?;
                }
                out.write_char('"')
            }
            _ => self.write_value(out, v, true),
        }
    }

    fn write_fact_as(&self, out: &mut dyn Write, slot: Ix, escape: bool) -> fmt::Result {
        let f = self.facts[slot as usize];
        let t = self.templates[f.tmpl as usize];
        out.write_char('(')?;
        out.write_str(self.sym(t.name))?;
        let mut c = f.start as usize;
        for s in 0..t.nslots {
            let def = self.slots[(t.first_slot + s) as usize];
            if !t.implied {
                out.write_str(" (")?;
                out.write_str(self.sym(def.name))?;
            }
            match self.values[c] {
                Value::Multi(m) => {
                    for k in 0..m.len as usize {
                        out.write_char(' ')?;
                        self.write_atom(out, self.values[c + 1 + k], escape)?;
                    }
                    c += 1 + m.len as usize;
                }
                v => {
                    out.write_char(' ')?;
                    self.write_atom(out, v, escape)?;
                    c += 1;
                }
            }
            if !t.implied {
                out.write_char(')')?;
            }
        }
        out.write_char(')')
    }
}

fn write_quoted(out: &mut dyn Write, s: &str) -> fmt::Result {
    out.write_char('"')?;
    out.write_str(s)?;
    out.write_char('"')
}

impl Core<'_> {
    /// Splits into a printing view and the host.
    pub fn split(&mut self) -> (View<'_>, &mut dyn Host) {
        (print_view!(self), &mut *self.host)
    }

    pub fn write(&mut self, router: &str, text: &str) {
        #[cfg(feature = "extras")]
        if let Some(c) = self.st.capture.as_mut() {
            if router == router::WERROR || router == router::WWARNING {
                // (a message longer than the buffer is cut: output only)
                let _ = core::fmt::Write::write_str(c, text);
                return;
            }
        }
        self.spill_traces();
        self.host.write_str(router, text);
    }

    /// Writes raw bytes to a router (`put-char`): text when they are UTF-8, else through
    /// [`Host::write_bytes`] (a capture of error output takes each byte as the
    /// character of its code). With `parser`, as its one caller (`builtins::io`).
    #[cfg(feature = "parser")]
    pub(crate) fn write_bytes(&mut self, router: &str, bytes: &[u8]) {
        if let Ok(text) = core::str::from_utf8(bytes) {
            self.write(router, text);
            return;
        }
        #[cfg(feature = "extras")]
        if let Some(c) = self.st.capture.as_mut() {
            if router == router::WERROR || router == router::WWARNING {
                for &b in bytes {
                    let _ = core::fmt::Write::write_char(c, char::from(b));
                }
                return;
            }
        }
        self.spill_traces();
        self.host.write_bytes(router, bytes);
    }

    /// Splits into a printing view and a writer for watch traces (see `hold`).
    fn split_trace(&mut self) -> (View<'_>, crate::hold::TraceWriter<'_>) {
        (
            print_view!(self),
            crate::hold::TraceWriter {
                host: &mut *self.host,
                hold: &mut self.st.net.hold,
            },
        )
    }

    /// Writes a value to a router (`quote`: strings in quotes).
    pub fn print_value(&mut self, router: &'static str, v: Value, quote: bool) {
        let (view, host) = self.split();
        let mut w = RouterWriter { host, router };
        let _ = view.write_value(&mut w, v, quote);
    }

    /// `f-N     ` prefix as CLIPS pads it.
    fn write_fact_id(w: &mut dyn Write, num: u32) -> fmt::Result {
        let mut b: crate::value::TextBuf<16> = crate::value::TextBuf::new();
        write!(b, "f-{num}")?;
        write!(w, "{:<7} ", b.as_str())
    }

    pub(crate) fn print_fact_line(&mut self, arrow: &str, slot: Ix) {
        let num = self.facts[slot as usize].num;
        let (view, mut w) = self.split_trace();
        let _ = w.write_str(arrow);
        let _ = Self::write_fact_id(&mut w, num);
        let _ = view.write_fact(&mut w, slot);
        let _ = w.write_str("\n");
    }

    /// `(facts)` listing line.
    pub(crate) fn print_fact_listing_line(&mut self, slot: Ix) {
        let num = self.facts[slot as usize].num;
        let (view, host) = self.split();
        let mut w = RouterWriter {
            host,
            router: router::WDISPLAY,
        };
        let _ = Self::write_fact_id(&mut w, num);
        let _ = view.write_fact(&mut w, slot);
        let _ = w.write_str("\n");
    }

    /// `f-1,f-3,*` for a partial match.
    pub(crate) fn write_basis(&self, w: &mut dyn Write, token: TokenId) -> fmt::Result {
        let mut ids = [u32::MAX; crate::rete::MAX_PATTERNS];
        let mut n = 0;
        for (depth, num) in self.basis(token) {
            if depth < ids.len() {
                ids[depth] = num.unwrap_or(u32::MAX);
                n = n.max(depth + 1);
            }
        }
        for (i, id) in ids[..n].iter().enumerate() {
            if i > 0 {
                w.write_char(',')?;
            }
            if *id == u32::MAX {
                w.write_char('*')?;
            } else {
                write!(w, "f-{id}")?;
            }
        }
        Ok(())
    }

    fn write_activation(&self, w: &mut dyn Write, a: Activation) -> fmt::Result {
        let r: Rule = self.rules[a.rule as usize];
        write!(w, "{:<6} {}: ", a.salience, self.sym_text(r.name))?;
        self.write_basis(w, a.token)
    }

    pub(crate) fn print_activation_line(&mut self, prefix: &str, a: Ix) {
        let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
        let _ = b.write_str(prefix);
        let _ = self.write_activation(&mut b, self.acts[a as usize]);
        let _ = b.write_str("\n");
        let (_, mut w) = self.split_trace();
        let _ = w.write_str(b.as_str());
    }

    #[inline]
    pub(crate) fn print_fire_line(&mut self, count: u32, rule: Ix, token: TokenId) {
        if self.st.mode.watch & watch::RULES != 0 && self.rule_traced(watch::RULES, rule) {
            self.write_fire_line(count, rule, token);
        }
    }

    /// Not inlined: its line buffer stays off the run loop's stack frame, which every
    /// rule's actions run below.
    #[cold]
    #[inline(never)]
    fn write_fire_line(&mut self, count: u32, rule: Ix, token: TokenId) {
        let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
        let _ = write!(
            b,
            "FIRE {count:>4} {}: ",
            self.sym_text(self.rules[rule as usize].name)
        );
        let _ = self.write_basis(&mut b, token);
        let _ = b.write_str("\n");
        self.host.write_str(router::WTRACE, b.as_str());
    }

    /// `(facts)`: all facts with number >= `start`, then the total.
    pub fn list_facts(&mut self, start: i64, end: i64, max: i64) {
        self.list_facts_of(start, end, max, false);
    }

    /// `(facts)`, of every module (`all`, `(facts *)`) or those whose template the
    /// current module sees.
    pub fn list_facts_of(&mut self, start: i64, end: i64, max: i64, all: bool) {
        let mut f = self.st.facts.fact_head;
        let mut n = 0i64;
        while f != NONE {
            let num = self.facts[f as usize].num as i64;
            #[cfg(feature = "modules")]
            let seen = all || self.template_visible(self.facts[f as usize].tmpl);
            #[cfg(not(feature = "modules"))]
            let seen = {
                let _ = all;
                true
            };
            if seen && num >= start && (end < 0 || num <= end) && (max < 0 || n < max) {
                self.print_fact_listing_line(f);
                n += 1;
            }
            f = self.facts[f as usize].next;
        }
        if n > 0 {
            self.print_total(n as usize, "fact");
        }
    }

    pub(crate) fn print_total(&mut self, n: usize, what: &str) {
        let mut b: crate::value::TextBuf<64> = crate::value::TextBuf::new();
        let _ = writeln!(
            b,
            "For a total of {n} {what}{}.",
            if n == 1 { "" } else { "s" }
        );
        self.host.write_str(router::WDISPLAY, b.as_str());
    }

    /// `(agenda)` listing.
    pub fn list_agenda(&mut self) {
        let n = self.list_agenda_of(self.st_current_module(), "");
        if n > 0 {
            self.print_total(n, "activation");
        }
    }

    /// Lists module `m`'s agenda, each line after `indent`; returns how many.
    pub fn list_agenda_of(&mut self, m: crate::module::ModId, indent: &str) -> usize {
        let mut a = self.st.agenda.agenda_head;
        let mut n = 0;
        while a != NONE {
            #[cfg(feature = "modules")]
            if !self.activation_in(a, m) {
                a = self.acts[a as usize].next;
                continue;
            }
            #[cfg(not(feature = "modules"))]
            let _ = m;
            let mut b: crate::value::TextBuf<512> = crate::value::TextBuf::new();
            let _ = b.write_str(indent);
            let _ = self.write_activation(&mut b, self.acts[a as usize]);
            let _ = b.write_str("\n");
            self.host.write_str(router::WDISPLAY, b.as_str());
            n += 1;
            a = self.acts[a as usize].next;
        }
        n
    }
}
