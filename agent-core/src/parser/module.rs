//! `defmodule` and module-qualified construct names (feature `modules`, see
//! `crate::module`).

use super::{PResult, Parser};
use crate::error::{LoadDetail, Pool};
use crate::lexer::{Tok, Token};
use crate::module::{class, split_qualified, ModId, Module, Port, MAIN};
use crate::value::{Ix, NONE};

impl<'s> Parser<'s, '_, '_> {
    /// `(defmodule NAME [comment] port-spec*)` after `defmodule`. The module is
    /// entered only once its whole text is read; it becomes the current module.
    pub(super) fn defmodule(&mut self, start: usize) -> PResult<()> {
        let nt = self.next();
        let name = match nt.tok {
            Tok::Symbol(s) if split_qualified(s).is_none() => s,
            // a module specifier in a defmodule's name: CLIPS's "module specifier"
            Tok::Symbol(_) => {
                return Err(self.syntax_of(nt, "a defmodule name", "module specifier"))
            }
            _ => return Err(self.missing_name(nt, "a defmodule name")),
        };
        let slot: ModId = match self.cx.find_module(name) {
            Some(MAIN) if !self.cx.st.modules.main_redefined => MAIN,
            Some(_) => {
                let mut e = self.err(
                    nt,
                    "a defmodule name not in use (modules cannot be redefined)",
                );
                e.detail = LoadDetail::InUse {
                    construct: "defmodule",
                };
                return Err(e);
            }
            None => {
                let n = self.cx.st.modules.nmodules as usize;
                if n > ModId::MAX as usize {
                    let c = crate::engine::cap(Pool::Modules, n);
                    return Err(self.cap_err(nt, c));
                }
                n as ModId
            }
        };
        // MAIN too: an engine without a modules pool has MAIN as made at start-up only
        #[cfg(feature = "grow")]
        self.cx.ensure(Pool::Modules, slot as usize + 1);
        if slot as usize >= self.cx.modules.len() {
            let c = crate::engine::cap(Pool::Modules, self.cx.modules.len());
            return Err(self.cap_err(nt, c));
        }
        let sym = cap!(self, self.cx.intern(name))?;
        if let Tok::Str(_) = self.peek().tok {
            self.next();
        }
        let first_port = self.cx.st.modules.nports;
        let mut nports: Ix = 0;
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => break,
                Tok::LParen => self.port_spec(slot, first_port, &mut nports)?,
                _ => return Err(self.err(t, "'(' opening an import or export specification")),
            }
        }
        if self.check_only {
            return Err(self.checked(nt));
        }
        let text = self.pp_text(start);
        let old = self.cx.modules[slot as usize];
        self.cx.modules[slot as usize] = Module {
            name: sym,
            first_port,
            nports,
            text,
        };
        // two constructs of one name the imports bring in from different modules
        if let Some((class, name)) = self.cx.clashing_import(slot) {
            self.cx.modules[slot as usize] = old;
            let mut e = self.err(nt, "imports that bring in no two constructs of one name");
            e.detail = LoadDetail::ModuleImportConflict {
                name,
                class: class::keyword(class),
            };
            return Err(e);
        }
        self.cx.st.modules.nports = first_port + nports;
        if slot == MAIN {
            self.cx.st.modules.main_redefined = true;
        } else {
            self.cx.st.modules.nmodules += 1;
            #[cfg(feature = "host-speedups")]
            self.cx.start_module_counts();
            // (the run loop looks for activations module by module on its general path)
            self.cx.note_run_slow();
            self.cx
                .note_hw(Pool::Modules, self.cx.st.modules.nmodules as usize);
        }
        self.cx.set_current_module(slot);
        Ok(())
    }

    /// One `(export ...)` or `(import MODULE ...)` after its `(`; its ports go after
    /// the ones this defmodule read so far (`first + *n`).
    fn port_spec(&mut self, this: ModId, first: Ix, n: &mut Ix) -> PResult<()> {
        let kt = self.next();
        let import = match kt.tok {
            Tok::Symbol("import") => true,
            Tok::Symbol("export") => false,
            _ => return Err(self.err(kt, "import or export")),
        };
        let mut from = MAIN;
        if import {
            let mt = self.next();
            from = match mt.tok {
                Tok::Symbol(s) => match self.cx.find_module(s) {
                    Some(m) if m != this => m,
                    _ => {
                        let mut e = self.err(mt, "the name of a defined module to import from");
                        e.detail = LoadDetail::NoSuchModule;
                        return Err(e);
                    }
                },
                _ => return Err(self.port_err(mt, true, "a module name")),
            };
            // a module exporting nothing cannot be imported from
            if !self.cx.exports_any(from, class::ALL) {
                return Err(self.not_exported(mt, from, "", NONE));
            }
        }
        let t = self.next();
        match t.tok {
            // ?ALL or ?NONE for every class
            Tok::SfVar("ALL") => {
                self.add_port(t, first, n, import, from, class::ALL, NONE)?;
                self.port_rparen(import, "')' after ?ALL")
            }
            Tok::SfVar("NONE") => self.port_rparen(import, "')' after ?NONE"),
            Tok::Symbol(kw) => {
                let Some(classes) = class::of(kw) else {
                    return Err(self.port_err(
                        t,
                        import,
                        "deftemplate, deffunction, defglobal, defclass or defgeneric",
                    ));
                };
                let t = self.next();
                match t.tok {
                    Tok::SfVar("ALL") => {
                        self.add_port(t, first, n, import, from, classes, NONE)?;
                        let close = self.next();
                        if close.tok != Tok::RParen {
                            return Err(self.port_err(close, import, "')' after ?ALL"));
                        }
                        if import && !self.cx.exports_any(from, classes) {
                            return Err(self.not_exported(
                                close,
                                from,
                                class::keyword(classes),
                                NONE,
                            ));
                        }
                        return Ok(());
                    }
                    Tok::SfVar("NONE") => return self.port_rparen(import, "')' after ?NONE"),
                    _ => {}
                }
                let mut t = t;
                let mut names = 0;
                let first_name = first + *n;
                loop {
                    match t.tok {
                        Tok::RParen if names > 0 => break,
                        Tok::Symbol(s) => {
                            let sym = cap!(self, self.cx.intern(s))?;
                            self.add_port(t, first, n, import, from, classes, sym)?;
                            names += 1;
                        }
                        _ => return Err(self.port_err(t, import, "a construct name")),
                    }
                    t = self.next();
                }
                // what is imported by name must be exported (and defined) already
                if import {
                    for p in first_name..first + *n {
                        let name = self.cx.ports[p as usize].name;
                        if !self.cx.module_exports(from, classes, name) {
                            return Err(self.not_exported(t, from, class::keyword(classes), name));
                        }
                    }
                }
                Ok(())
            }
            _ => Err(self.port_err(t, import, "?ALL, ?NONE or a construct type")),
        }
    }

    /// A syntax error in an import (`import`) or export specification at `at`, as
    /// CLIPS words it ("Check appropriate syntax for defmodule import specification").
    fn port_err(
        &self,
        at: Token<'s>,
        import: bool,
        expected: &'static str,
    ) -> crate::error::LoadError {
        let mut e = self.err(at, expected);
        e.construct = if import {
            "defmodule import specification"
        } else {
            "defmodule export specification"
        };
        e
    }

    /// The `)` closing a port specification.
    fn port_rparen(&mut self, import: bool, expected: &'static str) -> PResult<()> {
        let t = self.next();
        if t.tok == Tok::RParen {
            Ok(())
        } else {
            Err(self.port_err(t, import, expected))
        }
    }

    /// `[MODULPSR1]` at token `at`: module `from` does not export what is imported.
    fn not_exported(
        &mut self,
        at: Token<'s>,
        from: ModId,
        class: &'static str,
        name: Ix,
    ) -> crate::error::LoadError {
        let module = self.cx.module_entry(from).name;
        let module = if from == MAIN {
            self.cx.intern("MAIN").unwrap_or(NONE)
        } else {
            module
        };
        let mut e = self.err(at, "an import of what the module exports ([MODULPSR1])");
        e.detail = LoadDetail::NotExported {
            module,
            name,
            class,
        };
        e
    }

    #[allow(clippy::too_many_arguments)]
    fn add_port(
        &mut self,
        at: Token<'s>,
        first: Ix,
        n: &mut Ix,
        import: bool,
        from: ModId,
        classes: u8,
        name: Ix,
    ) -> PResult<()> {
        let k = first as usize + *n as usize;
        #[cfg(feature = "grow")]
        self.cx.ensure(Pool::ModulePorts, k + 1);
        if k >= self.cx.ports.len() || k >= NONE as usize {
            let c = crate::engine::cap(Pool::ModulePorts, self.cx.ports.len());
            return Err(self.cap_err(at, c));
        }
        self.cx.ports[k] = Port {
            import,
            from,
            classes,
            name,
        };
        *n += 1;
        self.cx.note_hw(Pool::ModulePorts, k + 1);
        Ok(())
    }

    /// A construct's name as written after its keyword: `MOD::name` defines it in
    /// module MOD, which becomes the current module (as in CLIPS); returns the name
    /// without the module.
    pub(super) fn construct_name(&mut self, at: Token<'s>, name: &'s str) -> PResult<&'s str> {
        match split_qualified(name) {
            None => Ok(name),
            Some((m, bare)) => {
                let Some(found) = self.cx.find_module(m) else {
                    // CLIPS: `[PRNTUTIL1] Unable to find defmodule M.`, the construct
                    // shown up to its name
                    let mut e = self.err(at, "the name of a defined module before '::'");
                    e.detail = LoadDetail::NoSuchModule;
                    e.end = e.start + m.len() as u32;
                    return Err(e);
                };
                let m = found;
                if bare.is_empty() || split_qualified(bare).is_some() {
                    return Err(self.err(at, "a construct name after the module name"));
                }
                self.cx.set_current_module(m);
                Ok(bare)
            }
        }
    }

    /// A name that refers to a construct (`MOD::name` or `name`): the module whose
    /// view to look it up in, and the name without the module.
    pub(super) fn qualified_ref(
        &mut self,
        at: Token<'s>,
        name: &'s str,
    ) -> PResult<(ModId, &'s str)> {
        match split_qualified(name) {
            None => Ok((self.cx.current_module(), name)),
            Some((m, bare)) => match self.cx.find_module(m) {
                Some(m) if !bare.is_empty() && split_qualified(bare).is_none() => Ok((m, bare)),
                Some(_) => Err(self.err(at, "a construct name after the module name")),
                None => Err(self.err(at, "the name of a defined module before '::'")),
            },
        }
    }
}
