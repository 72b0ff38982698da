//! `(save-facts <file> [local | visible [<deftemplate-name>*]])`, as CLIPS 6.30:
//! `local` (the default) saves the facts of the current module's templates, `visible`
//! those of every template the current module sees; names after the scope keep only
//! the facts of those templates (a `local` name is looked up in the current module, or
//! in the module a `MOD::` qualifier names; a `visible` one among the templates the
//! current module sees, unqualified only, as CLIPS finds no qualified name there).
//! Facts are written in fact-list order either way.
//!
//! CLIPS checks the scope keyword before it opens the file, and the names after: an
//! unknown name leaves the file empty and returns FALSE.

use super::{Args, SYM_FALSE, SYM_TRUE};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::Host;
use crate::value::{Ix, TextBuf, Value};
use core::fmt::{self, Write};

const FUNC: &str = "save-facts";

/// Argument types this module's messages name (`commands::TABLE` lists them).
pub(super) const T_FILE_NAME: &str = "file name";
pub(super) const T_SYMBOL: &str = "symbol";
pub(super) const T_SCOPE: &str = "symbol with value local or visible";
pub(super) const T_LOCAL: &str = "local deftemplate name";
pub(super) const T_VISIBLE: &str = "visible deftemplate name";

pub(super) fn save_facts(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let (Value::Sym(p) | Value::Str(p)) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type(FUNC, 1, T_FILE_NAME));
    };
    let mut path: TextBuf<256> = TextBuf::new();
    // a cut name would write another file
    if path.write_str(cx.sym_text(p)).is_err() {
        return Err(EvalError::message(crate::error::Message::PathTooLong));
    }
    let visible = if a.len > 1 {
        let Value::Sym(scope) = cx.arg(a, 1) else {
            return Err(EvalError::wrong_type(FUNC, 2, T_SYMBOL));
        };
        match cx.sym_text(scope) {
            "local" => false,
            "visible" => true,
            _ => {
                cx.write_error_message(EvalError::wrong_type(FUNC, 2, T_SCOPE));
                return Ok(Value::Sym(SYM_FALSE));
            }
        }
    } else {
        false
    };
    // opened (emptied) before the names are looked up, as CLIPS does
    if cx.host.write_file(path.as_str(), b"", false).is_err() {
        cx.report_unopened_file(FUNC, path.as_str());
        return Ok(Value::Sym(SYM_FALSE));
    }
    for i in 2..a.len as usize {
        let found = match cx.arg(a, i) {
            Value::Sym(_) => named_template(cx, a, i, visible).is_some(),
            _ => {
                let e = EvalError::wrong_type(FUNC, crate::error::arg_no(i), T_SYMBOL);
                cx.write_error_message(e);
                return Ok(Value::Sym(SYM_FALSE));
            }
        };
        if !found {
            let expected = if visible { T_VISIBLE } else { T_LOCAL };
            let e = EvalError::wrong_type(FUNC, crate::error::arg_no(i), expected);
            cx.write_error_message(e);
            return Ok(Value::Sym(SYM_FALSE));
        }
    }
    let mut buf: TextBuf<512> = TextBuf::new();
    let mut f = cx.st.facts.fact_head;
    while f != crate::value::NONE {
        let t = cx.facts[f as usize].tmpl;
        // the names were all found above: a fact's template is compared with each
        // (looked up again: save-facts is rare, and no list of them has to be kept)
        if in_scope(cx, t, visible)
            && (a.len <= 2
                || (2..a.len as usize).any(|i| named_template(cx, a, i, visible) == Some(t)))
        {
            let (view, host) = cx.split();
            let mut out = FileOut {
                host,
                path: path.as_str(),
                buf: &mut buf,
            };
            if view.write_fact_escaped(&mut out, f).is_err() || out.write_char('\n').is_err() {
                return Ok(Value::Sym(SYM_FALSE));
            }
        }
        f = cx.facts[f as usize].next;
    }
    let mut out = FileOut {
        host: &mut *cx.host,
        path: path.as_str(),
        buf: &mut buf,
    };
    Ok(Value::Sym(if out.flush().is_ok() {
        SYM_TRUE
    } else {
        SYM_FALSE
    }))
}

/// The file's text on its way to the host: gathered in `buf`, handed over whenever it
/// fills, so a fact of any length is written whole.
struct FileOut<'a> {
    host: &'a mut dyn Host,
    path: &'a str,
    buf: &'a mut TextBuf<512>,
}

impl FileOut<'_> {
    fn flush(&mut self) -> fmt::Result {
        if self.buf.is_empty() {
            return Ok(());
        }
        let written = self
            .host
            .write_file(self.path, self.buf.as_str().as_bytes(), true);
        self.buf.clear();
        written.map_err(|_| fmt::Error)
    }
}

impl Write for FileOut<'_> {
    fn write_str(&mut self, mut s: &str) -> fmt::Result {
        loop {
            let before = self.buf.len();
            if self.buf.write_str(s).is_ok() {
                return Ok(());
            }
            // the buffer took what fitted (whole characters): the rest after a flush
            s = &s[self.buf.len() - before..];
            self.flush()?;
        }
    }
}

/// Whether a fact of template `t` is saved in the scope: with modules, `local` takes
/// the current module's templates and `visible` those it sees; MAIN alone has them all.
fn in_scope(cx: &Core<'_>, t: Ix, visible: bool) -> bool {
    #[cfg(feature = "modules")]
    return if visible {
        cx.template_visible(t)
    } else {
        cx.module_of_template(t) == cx.current_module()
    };
    #[cfg(not(feature = "modules"))]
    {
        let _ = (cx, t, visible);
        true
    }
}

/// The template argument `i` (a symbol) names in the scope, if any.
fn named_template(cx: &mut Core<'_>, a: Args, i: usize, visible: bool) -> Option<Ix> {
    let Value::Sym(name) = cx.arg(a, i) else {
        return None;
    };
    let mut text: TextBuf<256> = TextBuf::new();
    let _ = text.write_str(cx.sym_text(name));
    match crate::module::split_qualified(text.as_str()) {
        // CLIPS's lookup among the visible templates takes no qualified name
        Some(_) if visible => None,
        Some((module, bare)) => {
            let bare = cx.find_sym(bare)?;
            #[cfg(feature = "modules")]
            return defined_in(cx, cx.find_module(module)?, bare);
            // MAIN alone: every template is MAIN's
            #[cfg(not(feature = "modules"))]
            (module == "MAIN").then(|| cx.find_template(bare)).flatten()
        }
        None if visible => cx.find_template(name),
        #[cfg(feature = "modules")]
        None => defined_in(cx, cx.current_module(), name),
        #[cfg(not(feature = "modules"))]
        None => cx.find_template(name),
    }
}

/// The template named `name` that module `m` defines (not one it imports).
#[cfg(feature = "modules")]
fn defined_in(cx: &Core<'_>, m: crate::module::ModId, name: crate::value::SymId) -> Option<Ix> {
    (0..cx.st.pools.ntemplates)
        .find(|&t| cx.templates[t as usize].name == name && cx.module_of_template(t) == m)
}

#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::error::HostIoError;
    use crate::host::Host;
    use std::collections::BTreeMap;
    use std::string::String;

    /// Output and files in memory; `writable` false refuses every file.
    struct Files {
        out: String,
        files: BTreeMap<String, String>,
        writable: bool,
    }

    impl Host for Files {
        fn write_str(&mut self, _router: &str, text: &str) {
            self.out.push_str(text);
        }
        fn write_file(&mut self, path: &str, data: &[u8], append: bool) -> Result<(), HostIoError> {
            if !self.writable {
                return Err(HostIoError::Other);
            }
            let file = self.files.entry(path.into()).or_default();
            if !append {
                file.clear();
            }
            file.push_str(&String::from_utf8_lossy(data));
            Ok(())
        }
    }

    fn run(src: &str, writable: bool) -> Files {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let mut h = Files {
            out: String::new(),
            files: BTreeMap::new(),
            writable,
        };
        e.batch_str(&mut h, src, false);
        h
    }

    /// (The batch reader runs the first command of each line.)
    const FACTS: &str =
        "(deftemplate point (slot x))\n(assert (point (x 1)) (color red) (point (x 2)))\n";

    #[test]
    fn only_the_named_templates_are_written() {
        let h = run(
            &(String::from(FACTS)
                + "(save-facts \"p\" local point)\n(save-facts \"c\" visible color point)\n"
                + "(save-facts \"all\")"),
            true,
        );
        assert_eq!(h.files["p"], "(point (x 1))\n(point (x 2))\n", "{}", h.out);
        assert_eq!(h.files["c"], "(point (x 1))\n(color red)\n(point (x 2))\n");
        // (a fresh engine holds the initial fact, as CLIPS)
        assert_eq!(
            h.files["all"],
            "(initial-fact)\n(point (x 1))\n(color red)\n(point (x 2))\n"
        );
    }

    #[test]
    fn a_wrong_scope_writes_no_file_and_an_unknown_name_an_empty_one() {
        let h = run(
            &(String::from(FACTS)
                + "(save-facts \"s\" everything point)\n(save-facts \"n\" local point nosuch)"),
            true,
        );
        assert!(!h.files.contains_key("s"), "{:?}", h.files);
        assert_eq!(h.files.get("n").map(String::as_str), Some(""));
        assert!(h
            .out
            .contains("argument #2 to be of type symbol with value local or visible"));
        assert!(h
            .out
            .contains("argument #4 to be of type local deftemplate name"));
    }

    #[test]
    fn a_file_that_cannot_be_written_is_reported() {
        let h = run(
            &(String::from(FACTS) + "(save-facts \"x\" local point)"),
            false,
        );
        assert!(
            h.out
                .contains("[ARGACCES2] Function save-facts was unable to open file x."),
            "{}",
            h.out
        );
    }
}
