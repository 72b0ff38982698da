//! `(watch globals)` and `(watch deffunctions)`, traced as CLIPS 6.30 traces them
//! (agent-core feature `extras`; the agent image traces neither).

#[cfg(feature = "modules")]
use super::extras::{owner_at, Kind};
use super::Args;
use crate::engine::{watch, Core};
use crate::error::EvalError;
use crate::host::{router, RouterWriter};
use crate::print::print_view;
use crate::value::{Ix, Value};
use core::fmt::Write;

impl Core<'_> {
    /// `:== ?*x* ==> NEW <== OLD` before global `g` takes `new` (a `bind`, or `reset`
    /// restoring its initial value; defining it prints nothing, as in CLIPS). A
    /// variable bound at the prompt (a hidden global named `?x`) is not traced.
    pub(crate) fn trace_global(&mut self, g: Ix, new: Value) {
        if self.st.mode.watch & watch::GLOBALS == 0 {
            return;
        }
        let name = self.globals[g as usize].name;
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
