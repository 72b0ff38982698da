//! `(watch globals)` and `(watch deffunctions)`, traced as CLIPS 6.30 traces them
//! (agent-core feature `extras`; the agent image traces neither).

#[cfg(feature = "modules")]
use super::extras::{owner_at, Kind};
use super::Args;
use crate::engine::{watch, Core, WatchNames};
use crate::error::EvalError;
use crate::host::{router, RouterWriter};
use crate::print::print_view;
use crate::value::{Ix, SymId, Value};
use core::fmt::Write;

impl Core<'_> {
    /// The module of construct `i` of item `bit`'s kind (a template for facts, a
    /// deffunction, a global, a rule).
    fn watched_module(&self, bit: u8, i: Ix) -> crate::module::ModId {
        #[cfg(feature = "modules")]
        return match bit {
            watch::FACTS => self.module_of_template(i),
            watch::DEFFUNCTIONS => self.module_of_function(i),
            watch::GLOBALS => self.module_of_global(i),
            _ => self.rule_tag(i).module,
        };
        #[cfg(not(feature = "modules"))]
        {
            let _ = (bit, i);
            crate::module::MAIN
        }
    }

    /// Whether facts of template `t` are traced (once `watch::FACTS` is set).
    pub(crate) fn fact_traced(&self, t: Ix) -> bool {
        let name = self.templates[t as usize].name;
        self.st
            .watch_names
            .traced(watch::FACTS, self.watched_module(watch::FACTS, t), name)
    }

    /// Whether fact `f`'s lines are traced (once `watch::FACTS` is set).
    pub(crate) fn fact_line_traced(&self, f: Ix) -> bool {
        self.fact_traced(self.facts[f as usize].tmpl)
    }

    /// Whether activation `a`'s lines are traced (once `watch::ACTIVATIONS` is set).
    pub(crate) fn activation_traced(&self, a: Ix) -> bool {
        self.rule_traced(watch::ACTIVATIONS, self.acts[a as usize].rule)
    }

    /// Whether rule `r` is traced for item `bit` (`watch::RULES`: its firings,
    /// `watch::ACTIVATIONS`: its activations), once the item's bit is set.
    pub(crate) fn rule_traced(&self, bit: u8, r: Ix) -> bool {
        let name = self.rules[r as usize].name;
        self.st
            .watch_names
            .traced(bit, self.watched_module(watch::RULES, r), name)
    }

    /// Whether deffunction `f`'s calls are traced, once `watch::DEFFUNCTIONS` is set.
    pub(crate) fn function_traced(&self, f: Ix) -> bool {
        let name = self.funcs[f as usize].name;
        let m = self.watched_module(watch::DEFFUNCTIONS, f);
        self.st.watch_names.traced(watch::DEFFUNCTIONS, m, name)
    }

    /// Whether global `g`'s changes are traced, once `watch::GLOBALS` is set.
    pub(crate) fn global_traced(&self, g: Ix) -> bool {
        let name = self.globals[g as usize].name;
        let m = self.watched_module(watch::GLOBALS, g);
        self.st.watch_names.traced(watch::GLOBALS, m, name)
    }

    /// `Mode::watch`'s construct bits again, after `WatchNames` changed.
    pub(crate) fn sync_watch(&mut self) {
        let rest = self.st.mode.watch & !WatchNames::ITEMS;
        self.st.mode.watch = rest | self.st.watch_names.mode_bits();
    }

    /// A construct named `name` of the current module is defined again: with its
    /// items (`bits`) on it is traced, else it keeps its own flag (CLIPS 6.30).
    pub(crate) fn watch_defined_again(&mut self, bits: u8, name: SymId) {
        let on = self.st.watch_names.items & bits;
        if on != 0 {
            let m = self.st_current_module();
            self.st.watch_names.forget(on, m, name);
            self.sync_watch();
        }
    }

    /// Construct `i` of item `bit`'s kind goes (`undef*`, a failed redefinition): a
    /// later one of its name takes its items' flags.
    pub(crate) fn watch_forget(&mut self, bit: u8, i: Ix, name: SymId) {
        let bits = if bit == watch::RULES {
            watch::RULES | watch::ACTIVATIONS
        } else {
            bit
        };
        let m = self.watched_module(bit, i);
        self.st.watch_names.forget(bits, m, name);
        self.sync_watch();
    }

    /// `:== ?*x* ==> NEW <== OLD` before global `g` takes `new` (a `bind`, or `reset`
    /// restoring its initial value; defining it prints nothing, as in CLIPS). A
    /// variable bound at the prompt (a hidden global named `?x`) is not traced.
    /// (The watch check in line: every `bind` of a global asks.)
    #[inline(always)]
    pub(crate) fn trace_global(&mut self, g: Ix, new: Value) {
        if self.st.mode.watch & watch::GLOBALS != 0 {
            self.print_global_trace(g, new);
        }
    }

    /// `trace_global` while globals are watched.
    #[cold]
    #[inline(never)]
    fn print_global_trace(&mut self, g: Ix, new: Value) {
        let name = self.globals[g as usize].name;
        if !self.global_traced(g) {
            return;
        }
        if self.sym_text(name).starts_with('?') {
            return;
        }
        let old = self.globals[g as usize].value;
        self.spill_traces();
        let view = print_view!(self);
        let mut w = RouterWriter {
            host: &mut *self.host,
            router: router::WTRACE,
        };
        let _ = write!(w, ":== ?*{}* ==> ", view.sym(name));
        let _ = view.write_value(&mut w, new, true);
        let _ = w.write_str(" <== ");
        let _ = view.write_value(&mut w, old, true);
        let _ = w.write_str("\n");
    }

    /// Runs deffunction `func` between its `DFN >>` and `DFN <<` lines. Both show the
    /// arguments as passed (a multifield in parentheses, the rest parameter's values
    /// one by one), so the body runs on a copy of them: binding a parameter changes
    /// the copy. A call refused for its argument count is not traced, nor the end of
    /// one that exits.
    pub(crate) fn apply_traced(&mut self, func: Ix, args: Args) -> Result<Value, EvalError> {
        let df = self.funcs[func as usize];
        let (n, np) = (args.len as usize, df.nparams as usize);
        if n < np || (!df.rest && n > np) {
            return self.apply_untraced(func, args);
        }
        self.trace_deffunction(func, args, ">> ");
        let base = self.st.frame.sp;
        for i in 0..args.len {
            self.push_value(self.stack[(args.base + i) as usize])?;
        }
        let r = self.apply_untraced(
            func,
            Args {
                base,
                len: args.len,
            },
        );
        if !matches!(&r, Err(e) if matches!(e.kind(), crate::error::EvalErrorKind::Exit)) {
            self.trace_deffunction(func, args, "<< ");
        }
        r
    }

    /// `DFN >> [MOD::]name ED:depth (args)`: the module is named when it is not the
    /// current one; the depth counts the deffunction calls under way (this one
    /// included) and a rule's actions.
    fn trace_deffunction(&mut self, func: Ix, args: Args, arrow: &str) {
        let depth = u32::from(self.st.eval.dfn_depth) + u32::from(self.st.mode.firing);
        self.spill_traces();
        let mut module: crate::value::TextBuf<64> = crate::value::TextBuf::new();
        #[cfg(feature = "modules")]
        {
            let owner = owner_at(self, Kind::Deffunction, func);
            if owner != self.st_current_module() {
                let _ = write!(module, "{}::", self.module_name(owner));
            }
        }
        let name = self.funcs[func as usize].name;
        let view = print_view!(self);
        let mut w = RouterWriter {
            host: &mut *self.host,
            router: router::WTRACE,
        };
        let _ = write!(
            w,
            "DFN {arrow}{}{} ED:{depth} (",
            module.as_str(),
            view.sym(name)
        );
        for i in 0..args.len {
            if i > 0 {
                let _ = w.write_char(' ');
            }
            let _ = view.write_value(&mut w, self.stack[(args.base + i) as usize], true);
        }
        let _ = w.write_str(")\n");
    }
}

/// `(watch ITEM NAME...)` and `(unwatch ITEM NAME...)`: the constructs named (`MOD::x`
/// or one the current module sees) are traced or not, one after another; the item's
/// own state stays. As CLIPS 6.30: an item without constructs takes no names
/// (`[ARGACCES4]`), a name that is no construct of the item's kind stops there
/// (`[ARGACCES5]`, naming `watch` for `unwatch` too; the ones before it are set).
/// COOL's items with constructs (instances, slots, message-handlers) are refused:
/// this engine has no classes.
pub(super) fn watch_named(
    cx: &mut Core<'_>,
    a: Args,
    func: &'static str,
    on: bool,
) -> Result<Value, EvalError> {
    use super::commands::{watch_item, WatchItem};
    use super::environment::find_construct;
    use super::extras::Kind;
    let item = cx.arg_lexeme(a, 0, func)?;
    let mut text: crate::value::TextBuf<32> = crate::value::TextBuf::new();
    let _ = text.write_str(cx.sym_text(item));
    if let WatchItem::Unknown = watch_item(text.as_str()) {
        return Err(EvalError::wrong_type(func, 1, "watchable symbol"));
    }
    let (bit, kind, kind_name) = match text.as_str() {
        "facts" => (watch::FACTS, Kind::Deftemplate, "deftemplate"),
        "rules" => (watch::RULES, Kind::Defrule, "defrule"),
        "activations" => (watch::ACTIVATIONS, Kind::Defrule, "defrule"),
        "deffunctions" => (watch::DEFFUNCTIONS, Kind::Deffunction, "deffunction"),
        "globals" => (watch::GLOBALS, Kind::Defglobal, "defglobal"),
        // (no generic function exists here: no name is one)
        "generic-functions" => (0, Kind::Deffacts, "defgeneric"),
        "methods" => (0, Kind::Deffacts, "generic function name"),
        "instances" | "slots" | "message-handlers" => {
            return Err(EvalError::message(crate::error::Message::NotTraced))
        }
        _ => {
            let mut b: crate::value::TextBuf<80> = crate::value::TextBuf::new();
            let _ = writeln!(
                b,
                "[ARGACCES4] Function {func} expected exactly 1 argument(s)"
            );
            cx.write(router::WERROR, b.as_str());
            return Err(EvalError::already_reported());
        }
    };
    for i in 1..a.len as usize {
        let found = match cx.arg(a, i) {
            Value::Sym(s) if bit != 0 => find_construct(cx, kind, s),
            _ => None,
        };
        let Some(c) = found else {
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let _ = writeln!(
                b,
                "[ARGACCES5] Function watch expected argument #{} to be of type {kind_name}",
                i + 1
            );
            cx.write(router::WERROR, b.as_str());
            cx.sync_watch();
            return Err(EvalError::already_reported());
        };
        let (m, name) = match kind {
            Kind::Deftemplate => (
                cx.watched_module(watch::FACTS, c),
                cx.templates[c as usize].name,
            ),
            Kind::Defrule => (
                cx.watched_module(watch::RULES, c),
                cx.rules[c as usize].name,
            ),
            Kind::Deffunction => (
                cx.watched_module(watch::DEFFUNCTIONS, c),
                cx.funcs[c as usize].name,
            ),
            _ => (
                cx.watched_module(watch::GLOBALS, c),
                cx.globals[c as usize].name,
            ),
        };
        if !cx.st.watch_names.set(bit, m, name, on) {
            cx.sync_watch();
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let _ = writeln!(
                b,
                "[NOTIMPL1] robotino-agent traces at most {} constructs otherwise than their watch item",
                WatchNames::MAX
            );
            cx.write(router::WERROR, b.as_str());
            return Err(EvalError::already_reported());
        }
    }
    cx.sync_watch();
    Ok(Value::Void)
}

/// What COOL's `initial-object` traces at `reset` and `clear` (this engine has no
/// other instance, so no other COOL trace): its `delete` message, and its
/// `create` and `init` ones, each handler's lines inside its message's.
const OBJECT: &str = "(<Instance-initial-object>)";
const STALE: &str = "(<Stale Instance-initial-object>)";

impl Core<'_> {
    /// `(watch instances)`, `messages` and `message-handlers` lines of `reset`
    /// deleting `initial-object` (`create`: false) or of `reset` and `clear` making it
    /// again.
    pub(crate) fn trace_initial_object(&mut self, create: bool) {
        use watch::cool::{INSTANCES, MESSAGES, MESSAGE_HANDLERS};
        let bits = self.st.mode.cool_watch;
        if bits & (INSTANCES | MESSAGES | MESSAGE_HANDLERS) == 0 {
            return;
        }
        let depth = u32::from(self.st.eval.dfn_depth) + u32::from(self.st.mode.firing) + 1;
        self.spill_traces();
        let mut w = RouterWriter {
            host: &mut *self.host,
            router: router::WTRACE,
        };
        let message = |w: &mut RouterWriter<'_>, msg: &str, inner: &str, after: &str| {
            if bits & MESSAGES != 0 {
                let _ = writeln!(w, "MSG >> {msg} ED:{depth} {OBJECT}");
            }
            if bits & MESSAGE_HANDLERS != 0 {
                let _ = writeln!(
                    w,
                    "HND >> {msg} primary in class USER\n       ED:{depth} {OBJECT}"
                );
            }
            let _ = w.write_str(inner);
            if bits & MESSAGE_HANDLERS != 0 {
                let _ = writeln!(
                    w,
                    "HND << {msg} primary in class USER\n       ED:{depth} {after}"
                );
            }
            if bits & MESSAGES != 0 {
                let _ = writeln!(w, "MSG << {msg} ED:{depth} {after}");
            }
        };
        let line = if bits & INSTANCES == 0 {
            ""
        } else if create {
            "==> instance [initial-object] of INITIAL-OBJECT\n"
        } else {
            "<== instance [initial-object] of INITIAL-OBJECT\n"
        };
        if create {
            let _ = w.write_str(line);
            message(&mut w, "create", "", OBJECT);
            message(&mut w, "init", "", OBJECT);
        } else {
            message(&mut w, "delete", line, STALE);
        }
    }
}
