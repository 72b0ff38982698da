//! Modules (`defmodule`), as CLIPS 6.30 has them: which constructs a module sees
//! (its own, and those it imports from modules that export them), the current module
//! (where new constructs go, what `facts`, `agenda` and `list-def*` show) and the focus
//! stack (whose top module's agenda `run` fires from).
//!
//! Entry 0 of the `Modules` pool is MAIN, which always exists; the others come in
//! definition order (a module can import only from modules defined before it, so
//! visibility is computed by following imports down to older modules). Each construct
//! keeps its module in a side array by its index (`tmpl_module`, `rule_module`, ...).
//!
//! Off (feature `modules`) in the agent image: there, everything is MAIN, the side
//! arrays and pools have zero-sized entries, and `defmodule` and `Module::name` are
//! refused as not implemented.

#[cfg(feature = "modules")]
use crate::engine::Core;
#[cfg(feature = "modules")]
use crate::value::{Ix, SymId, NONE};

/// A module's number: its entry in the `Modules` pool (0 is MAIN).
pub type ModId = u8;
pub const MAIN: ModId = 0;

/// Construct classes a port names (`deftemplate`, ...), as bits; `ALL` for `?ALL`.
pub mod class {
    pub const TEMPLATE: u8 = 1;
    pub const FUNCTION: u8 = 2;
    pub const GLOBAL: u8 = 4;
    pub const CLASS: u8 = 8;
    pub const GENERIC: u8 = 16;
    /// Defrules and deffacts: no port names their class, only `?ALL` (imported from a
    /// module exporting `?ALL`) makes another module's visible by its plain name.
    pub const RULES: u8 = 32;
    pub const ALL: u8 = 63;

    /// The keyword of construct class `bit` (one bit).
    pub fn keyword(bit: u8) -> &'static str {
        match bit {
            TEMPLATE => "deftemplate",
            FUNCTION => "deffunction",
            GLOBAL => "defglobal",
            CLASS => "defclass",
            _ => "defgeneric",
        }
    }

    /// The bit of a construct keyword in a port specification.
    pub fn of(keyword: &str) -> Option<u8> {
        Some(match keyword {
            "deftemplate" => TEMPLATE,
            "deffunction" => FUNCTION,
            "defglobal" => GLOBAL,
            "defclass" => CLASS,
            "defgeneric" => GENERIC,
            _ => return None,
        })
    }
}

/// A defmodule: its name, its ports (`ports[first_port..first_port + nports]`) and
/// its text for `ppdefmodule` (NONE for the MAIN made at start-up).
#[cfg(feature = "modules")]
#[derive(Clone, Copy, Debug)]
pub struct Module {
    pub name: SymId,
    pub first_port: Ix,
    pub nports: Ix,
    pub text: Ix,
}

#[cfg(feature = "modules")]
pub const NO_MODULE: Module = Module {
    name: NONE,
    first_port: 0,
    nports: 0,
    text: NONE,
};

/// One `(import M ...)` or `(export ...)` item: which classes (`class` bits) and which
/// name (NONE: every construct of those classes). `from` is the imported module.
#[cfg(feature = "modules")]
#[derive(Clone, Copy, Debug)]
pub struct Port {
    pub import: bool,
    pub from: ModId,
    pub classes: u8,
    pub name: SymId,
}

#[cfg(feature = "modules")]
pub const NO_PORT: Port = Port {
    import: false,
    from: MAIN,
    classes: 0,
    name: NONE,
};

/// A construct's module (side arrays by construct index), a focus stack entry.
#[cfg(feature = "modules")]
pub type ModTag = ModId;
#[cfg(feature = "modules")]
pub const NO_TAG: ModTag = MAIN;

/// A rule's module, and whether its activations focus on it (`auto-focus`).
#[cfg(feature = "modules")]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RuleTag {
    pub module: ModId,
    pub auto_focus: bool,
}
#[cfg(feature = "modules")]
pub const NO_RULE_TAG: RuleTag = RuleTag {
    module: MAIN,
    auto_focus: false,
};
#[cfg(not(feature = "modules"))]
pub type RuleTag = ();
#[cfg(not(feature = "modules"))]
pub const NO_RULE_TAG: RuleTag = ();

/// Without the feature: no bytes (the pool table keeps the arrays, of zero-sized
/// entries).
#[cfg(not(feature = "modules"))]
pub type ModTag = ();
#[cfg(not(feature = "modules"))]
pub const NO_TAG: ModTag = ();
#[cfg(not(feature = "modules"))]
pub type Module = ();
#[cfg(not(feature = "modules"))]
pub const NO_MODULE: Module = ();
#[cfg(not(feature = "modules"))]
pub type Port = ();
#[cfg(not(feature = "modules"))]
pub const NO_PORT: Port = ();

/// The engine's module state.
#[cfg(feature = "modules")]
#[derive(Clone, Copy, Debug)]
pub struct ModuleState {
    /// Modules defined (MAIN included: at least 1) and ports used.
    pub nmodules: Ix,
    pub nports: Ix,
    /// Where new constructs go and whose view commands take.
    pub current: ModId,
    /// Entries of the focus stack (its top is `focus[depth - 1]`).
    pub depth: Ix,
    /// MAIN may be redefined once after start-up or `clear`.
    pub main_redefined: bool,
    /// What a new activation does beyond the agenda (`HOOK_*` bits): nothing
    /// unless some rule was defined with `(auto-focus TRUE)` (since start-up or
    /// `clear`: its rule's tag is looked up only then) or a module's agenda start
    /// is known (`ModuleState::fhead`).
    pub add_hooks: u8,
    /// Where module `fmod`'s agenda begins, so the focused module's next activation is
    /// found without walking past other modules' (`focused_head`): every activation of
    /// `fmod` lies at or after `fhead` in the agenda (NONE: it has none) while the
    /// activation there is the one numbered `fseq`; the first of them when
    /// `focused_head` left it. `fmod` is `NO_FOCUS_CACHE` while nothing is known:
    /// always with one module.
    #[cfg(feature = "host-speedups")]
    pub fhead: Ix,
    #[cfg(feature = "host-speedups")]
    pub fseq: u32,
    #[cfg(feature = "host-speedups")]
    pub fmod: u16,
    /// Host, while `HOOK_COUNT` is set (from the second module on): per module, at
    /// least as many activations as it has on the agenda (every new one counts, one
    /// that fires leaves its count, one a retract takes stays counted until a walk of
    /// `focused_head` finds the module has none). A count of 0 proves the module has
    /// none, so focusing it walks no other module's activations (CLIPS keeps an agenda
    /// per module).
    #[cfg(feature = "host-speedups")]
    pub acts_in: [u32; 256],
    /// Host: the module of the activation `focused_head` gave last.
    #[cfg(feature = "host-speedups")]
    pub head_mod: ModId,
}

/// `ModuleState::add_hooks`: some rule has auto-focus.
#[cfg(feature = "modules")]
pub const HOOK_AUTO_FOCUS: u8 = 1;
/// `ModuleState::add_hooks`: a module's agenda start is known.
#[cfg(all(feature = "modules", feature = "host-speedups"))]
pub const HOOK_FOCUS_CACHE: u8 = 2;
/// `ModuleState::add_hooks`: activations are counted per module (`acts_in`).
#[cfg(all(feature = "modules", feature = "host-speedups"))]
pub const HOOK_COUNT: u8 = 4;

#[cfg(feature = "modules")]
impl ModuleState {
    pub const fn new() -> ModuleState {
        ModuleState {
            nmodules: 1,
            nports: 0,
            current: MAIN,
            depth: 1,
            main_redefined: false,
            add_hooks: 0,
            #[cfg(feature = "host-speedups")]
            fhead: crate::value::NONE,
            #[cfg(feature = "host-speedups")]
            fseq: 0,
            #[cfg(feature = "host-speedups")]
            fmod: crate::agenda::NO_FOCUS_CACHE,
            #[cfg(feature = "host-speedups")]
            acts_in: [0; 256],
            #[cfg(feature = "host-speedups")]
            head_mod: MAIN,
        }
    }
}

#[cfg(feature = "modules")]
impl Default for ModuleState {
    fn default() -> Self {
        Self::new()
    }
}

/// `MOD::name` split at the first `::` (None for a plain name).
pub fn split_qualified(name: &str) -> Option<(&str, &str)> {
    let i = qualifier_end(name)?;
    Some((&name[..i], &name[i + 2..]))
}

/// Where the first `::` in `name` starts. A plain byte loop: every name read goes
/// through it, and `str::find`'s searcher costs more to set up than these short
/// names take to scan. It looks at every other byte: a `::` always has one of its
/// two colons at an odd position, and a colon there is checked against both
/// neighbours (the one before first, so the first `::` is the one found).
#[inline]
pub fn qualifier_end(name: &str) -> Option<usize> {
    let b = name.as_bytes();
    let mut i = 1;
    while i < b.len() {
        if b[i] == b':' {
            if b[i - 1] == b':' {
                return Some(i - 1);
            }
            if b.get(i + 1) == Some(&b':') {
                return Some(i);
            }
        }
        i += 2;
    }
    None
}

/// Reads of the module side arrays and pools, the only ones. An engine may have fewer
/// entries there than constructs: one sized as the agent image reads its rules in
/// place from a compiled rule base (`rules: 0`, so `rule_module` is empty) and may
/// name no module pools at all (`modules: 0`, `focus_stack: 0`). What has no entry is
/// MAIN's (compiled rule bases hold MAIN only, `WriteError::Modules`), so such an
/// engine behaves as the single MAIN module: no auto-focus, every rule here.
#[cfg(feature = "modules")]
impl Core<'_> {
    /// Rule `r`'s module and auto-focus flag.
    #[inline]
    pub fn rule_tag(&self, r: Ix) -> RuleTag {
        self.rule_module
            .get(r as usize)
            .copied()
            .unwrap_or(NO_RULE_TAG)
    }

    /// Template `t`'s module.
    pub fn module_of_template(&self, t: Ix) -> ModId {
        self.tmpl_module.get(t as usize).copied().unwrap_or(MAIN)
    }

    /// Deffunction `f`'s module.
    pub fn module_of_function(&self, f: Ix) -> ModId {
        self.func_module.get(f as usize).copied().unwrap_or(MAIN)
    }

    /// Defglobal `g`'s module.
    pub fn module_of_global(&self, g: Ix) -> ModId {
        self.global_module.get(g as usize).copied().unwrap_or(MAIN)
    }

    /// Deffacts `d`'s module.
    pub fn module_of_deffacts(&self, d: Ix) -> ModId {
        self.deffacts_module
            .get(d as usize)
            .copied()
            .unwrap_or(MAIN)
    }

    /// Module `m`'s entry (MAIN's as made at start-up when the pool has no room for it:
    /// no ports, no text).
    pub fn module_entry(&self, m: ModId) -> Module {
        self.modules.get(m as usize).copied().unwrap_or(NO_MODULE)
    }

    /// Port `p` (one matching nothing past the pool's end: a module's ports are
    /// recorded only once stored).
    fn port_entry(&self, p: Ix) -> Port {
        self.ports.get(p as usize).copied().unwrap_or(NO_PORT)
    }

    /// Entry `k` (bottom first) of the focus stack; an engine without a focus stack
    /// holds MAIN only, in no storage (`push_focus`).
    pub fn focus_entry(&self, k: usize) -> ModId {
        self.focus.get(k).copied().unwrap_or(MAIN)
    }

    /// Records the module of rule `r`; false when the pool has no entry for it and the
    /// tag is not MAIN's (the rule pool's room is checked before a rule is made, so
    /// only the MAIN rules of a compiled rule base read in place have none).
    pub fn set_rule_tag(&mut self, r: Ix, tag: RuleTag) -> bool {
        if tag.auto_focus {
            self.st.modules.add_hooks |= HOOK_AUTO_FOCUS;
        }
        set_tag(self.rule_module, r, tag, NO_RULE_TAG)
    }

    /// Records the module of template `t` (false as [`Core::set_rule_tag`]).
    pub fn set_template_module(&mut self, t: Ix, m: ModId) -> bool {
        set_tag(self.tmpl_module, t, m, MAIN)
    }

    /// Records the module of deffunction `f` (false as [`Core::set_rule_tag`]).
    pub fn set_function_module(&mut self, f: Ix, m: ModId) -> bool {
        set_tag(self.func_module, f, m, MAIN)
    }

    /// Records the module of defglobal `g` (false as [`Core::set_rule_tag`]).
    pub fn set_global_module(&mut self, g: Ix, m: ModId) -> bool {
        set_tag(self.global_module, g, m, MAIN)
    }

    /// Records the module of deffacts `d` (false as [`Core::set_rule_tag`]).
    pub fn set_deffacts_module(&mut self, d: Ix, m: ModId) -> bool {
        set_tag(self.deffacts_module, d, m, MAIN)
    }
}

/// Writes `tag` at `i`; past the end only the default (what reads there) fits.
#[cfg(feature = "modules")]
fn set_tag<T: Copy + PartialEq>(arr: &mut [T], i: Ix, tag: T, default: T) -> bool {
    match arr.get_mut(i as usize) {
        Some(e) => {
            *e = tag;
            true
        }
        None => tag == default,
    }
}

#[cfg(feature = "modules")]
impl Core<'_> {
    /// The module named `name`.
    pub fn find_module(&self, name: &str) -> Option<ModId> {
        (0..self.st.modules.nmodules as usize)
            .find(|&m| self.module_name(m as ModId) == name)
            .map(|m| m as ModId)
    }

    pub fn module_name(&self, m: ModId) -> &str {
        if m == MAIN {
            return "MAIN";
        }
        self.sym_text(self.module_entry(m).name)
    }

    /// `MOD::name`: the module and the plain name's symbol (None for a plain name,
    /// and for an unknown module or name, which then names nothing).
    pub fn resolve_qualified(&mut self, name: SymId) -> Option<(ModId, SymId)> {
        let mut b: crate::value::TextBuf<256> = crate::value::TextBuf::new();
        core::fmt::Write::write_str(&mut b, self.sym_text(name)).ok()?;
        let (m, bare) = split_qualified(b.as_str())?;
        let m = self.find_module(m).unwrap_or(ModId::MAX);
        let bare = self.find_sym(bare).unwrap_or(NONE);
        Some((m, bare))
    }

    pub fn current_module(&self) -> ModId {
        self.st.modules.current
    }

    pub fn set_current_module(&mut self, m: ModId) {
        self.st.modules.current = m;
    }

    /// Makes `m` current for a rule's or deffunction's actions, as CLIPS's
    /// `EvaluateProcActions` does; returns the module to make current again after them
    /// (`leave_module`). With MAIN alone, nothing to change or restore.
    #[cfg(feature = "modules")]
    #[inline]
    pub fn enter_module(&mut self, m: ModId) -> Option<ModId> {
        if self.st.modules.nmodules <= 1 {
            return None;
        }
        let outer = self.st.modules.current;
        self.st.modules.current = m;
        Some(outer)
    }

    /// After the actions `enter_module` began: the module current before them is
    /// current again, whatever they changed it to (a `reset`, `focus` or
    /// `set-current-module` in them).
    #[cfg(feature = "modules")]
    #[inline]
    pub fn leave_module(&mut self, outer: Option<ModId>) {
        if let Some(m) = outer {
            self.st.modules.current = m;
        }
    }

    /// Whether a construct of class `class` named `name` defined in `owner` can be used
    /// in module `from`: its own, or imported from a module exporting it (a module
    /// exports what it sees, its imports too). `depth` bounds the walk (a MAIN
    /// redefined to import a later module could make a loop).
    pub fn visible_in(&self, class: u8, owner: ModId, name: SymId, from: ModId) -> bool {
        self.visible_depth(class, owner, name, from, self.st.modules.nmodules)
    }

    fn visible_depth(&self, class: u8, owner: ModId, name: SymId, from: ModId, depth: Ix) -> bool {
        if owner == from {
            return true;
        }
        if depth == 0 {
            return false;
        }
        let m = self.module_entry(from);
        (m.first_port..m.first_port + m.nports).any(|p| {
            let p = self.port_entry(p);
            p.import
                && p.classes & class != 0
                && (p.name == NONE || p.name == name)
                && self.exports(p.from, class, owner, name, depth - 1)
        })
    }

    fn exports(&self, m: ModId, class: u8, owner: ModId, name: SymId, depth: Ix) -> bool {
        let md = self.module_entry(m);
        (md.first_port..md.first_port + md.nports).any(|p| {
            let p = self.port_entry(p);
            !p.import && p.classes & class != 0 && (p.name == NONE || p.name == name)
        }) && self.visible_depth(class, owner, name, m, depth)
    }

    /// Whether module `m` has an export specification for a class of `classes`.
    pub fn exports_any(&self, m: ModId, classes: u8) -> bool {
        let md = self.module_entry(m);
        (md.first_port..md.first_port + md.nports).any(|p| {
            let p = self.port_entry(p);
            !p.import && p.classes & classes != 0
        })
    }

    /// Whether module `m`'s export list names constructs of `class` called `name`
    /// (`?ALL`, the class's `?ALL`, or the name), whoever defines them: CLIPS's
    /// `ConstructExported`.
    pub fn exports_own(&self, m: ModId, class: u8, name: SymId) -> bool {
        let md = self.module_entry(m);
        (md.first_port..md.first_port + md.nports).any(|p| {
            let p = self.port_entry(p);
            !p.import && p.classes & class != 0 && (p.name == NONE || p.name == name)
        })
    }

    /// Whether module `m` exports a construct of `class` named `name` that it sees
    /// (what `(import m class name)` needs, `[MODULPSR1]` otherwise).
    pub fn module_exports(&self, m: ModId, class: u8, name: SymId) -> bool {
        let n = self.st.modules.nmodules;
        (0..n).any(|owner| {
            let owner = owner as ModId;
            self.constructs_named(class, owner, name) && self.exports(m, class, owner, name, n)
        })
    }

    /// Whether defining a construct of `class` named `name` in module `m` clashes
    /// with the imports and exports (CLIPS's `[CSTRCPSR3]`): `m` sees another
    /// module's construct of that name, or a module that would see `m`'s sees another
    /// one too (its own or one it imports).
    pub fn import_conflict(&self, class: u8, m: ModId, name: SymId) -> bool {
        let n = self.st.modules.nmodules;
        (0..n).map(|o| o as ModId).any(|owner| {
            owner != m
                && self.constructs_named(class, owner, name)
                && (0..n).map(|x| x as ModId).any(|x| {
                    self.visible_in(class, m, name, x) && self.visible_in(class, owner, name, x)
                })
        })
    }

    /// The first construct class (`class` bit) and name of which module `m` sees two,
    /// of different modules (CLIPS's `[CSTRCPSR3]` for a defmodule whose imports
    /// clash).
    pub fn clashing_import(&self, m: ModId) -> Option<(u8, SymId)> {
        let n = self.st.modules.nmodules;
        let names = |class: u8, i: Ix| -> Option<(SymId, ModId)> {
            Some(match class {
                class::TEMPLATE if i < self.st.pools.ntemplates => {
                    (self.templates[i as usize].name, self.module_of_template(i))
                }
                class::FUNCTION if i < self.st.pools.nfuncs => {
                    (self.funcs[i as usize].name, self.module_of_function(i))
                }
                class::GLOBAL if i < self.st.pools.nglobals => {
                    (self.globals[i as usize].name, self.module_of_global(i))
                }
                _ => return None,
            })
        };
        for class in [class::TEMPLATE, class::FUNCTION, class::GLOBAL] {
            let mut i = 0;
            while let Some((name, owner)) = names(class, i) {
                i += 1;
                if name == NONE || owner == m || !self.visible_in(class, owner, name, m) {
                    continue;
                }
                let other = (0..n).map(|o| o as ModId).any(|o| {
                    o != owner
                        && self.constructs_named(class, o, name)
                        && self.visible_in(class, o, name, m)
                });
                if other {
                    return Some((class, name));
                }
            }
        }
        None
    }

    /// The defglobal named `name` that module `from` sees.
    pub fn global_seen_from(&self, name: SymId, from: ModId) -> Option<Ix> {
        // MAIN alone sees every defglobal (each is MAIN's): the name decides
        if self.st.modules.nmodules <= 1 {
            return (0..self.st.pools.nglobals).find(|&g| self.globals[g as usize].name == name);
        }
        (0..self.st.pools.nglobals).find(|&g| {
            self.globals[g as usize].name == name
                && self.visible_in(class::GLOBAL, self.module_of_global(g), name, from)
        })
    }

    /// Whether `owner` defines a construct of `class` named `name`.
    fn constructs_named(&self, class: u8, owner: ModId, name: SymId) -> bool {
        match class {
            class::TEMPLATE => (0..self.st.pools.ntemplates).any(|t| {
                self.templates[t as usize].name == name && self.module_of_template(t) == owner
            }),
            class::FUNCTION => (0..self.st.pools.nfuncs).any(|f| {
                self.funcs[f as usize].name == name && self.module_of_function(f) == owner
            }),
            class::GLOBAL => (0..self.st.pools.nglobals).any(|g| {
                self.globals[g as usize].name == name && self.module_of_global(g) == owner
            }),
            _ => false,
        }
    }

    /// The template named `name` that module `from` sees.
    pub fn template_seen_from(&self, name: SymId, from: ModId) -> Option<Ix> {
        // MAIN alone sees every template (each is MAIN's): the name decides
        if self.st.modules.nmodules <= 1 {
            return (0..self.st.pools.ntemplates)
                .find(|&t| self.templates[t as usize].name == name);
        }
        (0..self.st.pools.ntemplates).find(|&t| {
            self.templates[t as usize].name == name
                && self.visible_in(class::TEMPLATE, self.module_of_template(t), name, from)
        })
    }

    /// Whether the current module sees template `t` (`facts`, `find_template`).
    pub fn template_visible(&self, t: Ix) -> bool {
        let name = self.templates[t as usize].name;
        self.visible_in(
            class::TEMPLATE,
            self.module_of_template(t),
            name,
            self.current_module(),
        )
    }

    /// The focus stack's top (the module whose agenda fires), if any.
    pub fn focus_top(&self) -> Option<ModId> {
        let d = self.st.modules.depth as usize;
        // (a fresh engine's stack holds MAIN, entry 0's empty value)
        (d > 0).then(|| self.focus_entry(d - 1))
    }

    /// Pushes `m` on the focus stack (nothing when it is the top already), as CLIPS's
    /// `focus`: `==> Focus M from N` while focus is watched; the current module
    /// becomes `m`.
    pub fn push_focus(&mut self, m: ModId) -> Result<(), crate::error::CapacityError> {
        let d = self.st.modules.depth as usize;
        let top = self.focus_top();
        self.st.modules.current = m;
        if top == Some(m) {
            return Ok(());
        }
        #[cfg(feature = "grow")]
        self.ensure(crate::error::Pool::FocusStack, d + 1);
        match self.focus.get_mut(d) {
            Some(e) => *e = m,
            // an engine without a focus stack holds MAIN alone, in no storage
            None if d == 0 && m == MAIN => {}
            None => {
                return Err(crate::engine::cap(
                    crate::error::Pool::FocusStack,
                    self.focus.len(),
                ))
            }
        }
        self.st.modules.depth += 1;
        self.note_hw(crate::error::Pool::FocusStack, d + 1);
        if self.st.mode.watch & crate::engine::watch::FOCUS != 0 {
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let _ = match top {
                Some(t) => core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!(
                        "==> Focus {} from {}\n",
                        self.module_name(m),
                        self.module_name(t)
                    ),
                ),
                None => core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!("==> Focus {}\n", self.module_name(m)),
                ),
            };
            self.write(crate::host::router::STDOUT, b.as_str());
        }
        Ok(())
    }

    /// Pops the focus stack's top (`<== Focus M to N` while watched); the new top's
    /// module becomes current.
    pub fn pop_focus(&mut self) -> Option<ModId> {
        let top = self.focus_top()?;
        self.st.modules.depth -= 1;
        // (an empty stack is given MAIN on the run loop's general path)
        self.note_run_slow();
        let next = self.focus_top();
        if self.st.mode.watch & crate::engine::watch::FOCUS != 0 {
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let _ = match next {
                Some(n) => core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!(
                        "<== Focus {} to {}\n",
                        self.module_name(top),
                        self.module_name(n)
                    ),
                ),
                None => core::fmt::Write::write_fmt(
                    &mut b,
                    format_args!("<== Focus {}\n", self.module_name(top)),
                ),
            };
            self.write(crate::host::router::STDOUT, b.as_str());
        }
        // (CLIPS's `RemoveFocus`: the new top's module is current, whatever was; the
        // module a rule's actions made current is restored after them, `leave_module`)
        if let Some(n) = next {
            self.st.modules.current = n;
        }
        Some(top)
    }

    /// Takes the topmost entry of module `m` off the focus stack, as CLIPS's
    /// `RemoveFocus`: the top is popped (`pop_focus`); an entry below it goes with
    /// `<== Focus M` while watched, the top staying.
    pub fn remove_focus(&mut self, m: ModId) {
        let d = self.st.modules.depth as usize;
        let Some(k) = (0..d).rev().find(|&k| self.focus_entry(k) == m) else {
            return;
        };
        if k + 1 == d {
            self.pop_focus();
            return;
        }
        // (an entry below the top is in storage: only a lone MAIN may have none)
        if d > self.focus.len() {
            return;
        }
        self.focus.copy_within(k + 1..d, k);
        self.st.modules.depth -= 1;
        // (an empty stack is given MAIN on the run loop's general path)
        self.note_run_slow();
        if self.st.mode.watch & crate::engine::watch::FOCUS != 0 {
            let mut b: crate::value::TextBuf<128> = crate::value::TextBuf::new();
            let _ = core::fmt::Write::write_fmt(
                &mut b,
                format_args!("<== Focus {}\n", self.module_name(m)),
            );
            self.write(crate::host::router::STDOUT, b.as_str());
        }
    }

    /// Empties the focus stack, top first.
    pub fn clear_focus(&mut self) {
        while self.pop_focus().is_some() {}
    }

    /// `reset` and `clear`: the focus stack holds MAIN only, which is current.
    pub fn reset_focus(&mut self) -> Result<(), crate::error::CapacityError> {
        self.clear_focus();
        self.st.modules.current = MAIN;
        self.push_focus(MAIN)
    }

    /// Whether activation `a` is on the agenda of module `m`.
    pub fn activation_in(&self, a: Ix, m: ModId) -> bool {
        self.rule_tag(self.acts[a as usize].rule).module == m
    }
}

impl crate::engine::Core<'_> {
    /// The current module's name ("MAIN" without the feature).
    pub fn current_module_name(&self) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.st.modules.current);
        #[cfg(not(feature = "modules"))]
        "MAIN"
    }

    /// The name of the module of rule `r`.
    pub fn rule_module_name(&self, r: crate::value::Ix) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.rule_tag(r).module);
        #[cfg(not(feature = "modules"))]
        {
            let _ = r;
            "MAIN"
        }
    }

    /// The name of the module of template `t`.
    pub fn template_module_name(&self, t: crate::value::Ix) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.module_of_template(t));
        #[cfg(not(feature = "modules"))]
        {
            let _ = t;
            "MAIN"
        }
    }

    /// The name of the module of deffunction `f`.
    pub fn function_module_name(&self, f: crate::value::Ix) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.module_of_function(f));
        #[cfg(not(feature = "modules"))]
        {
            let _ = f;
            "MAIN"
        }
    }

    /// The name of the module of defglobal `g`.
    pub fn global_module_name(&self, g: crate::value::Ix) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.module_of_global(g));
        #[cfg(not(feature = "modules"))]
        {
            let _ = g;
            "MAIN"
        }
    }

    /// The name of the module of deffacts `d`.
    pub fn deffacts_module_name(&self, d: crate::value::Ix) -> &str {
        #[cfg(feature = "modules")]
        return self.module_name(self.module_of_deffacts(d));
        #[cfg(not(feature = "modules"))]
        {
            let _ = d;
            "MAIN"
        }
    }
}

impl crate::engine::Core<'_> {
    /// The deffunction named `name` that module `from` sees.
    pub fn find_function(&self, name: SymIdAny, from: ModId) -> Option<crate::value::Ix> {
        #[cfg(feature = "modules")]
        return (0..self.st.pools.nfuncs).find(|&f| {
            self.funcs[f as usize].name == name
                && self.visible_in(class::FUNCTION, self.module_of_function(f), name, from)
        });
        #[cfg(not(feature = "modules"))]
        {
            let _ = from;
            (0..self.st.pools.nfuncs).find(|&f| self.funcs[f as usize].name == name)
        }
    }

    /// The defglobal named `name` that the current module sees (hidden prompt
    /// variables have names of their own, `?x`).
    pub fn find_global(&self, name: SymIdAny) -> Option<crate::value::Ix> {
        #[cfg(feature = "modules")]
        return self.global_seen_from(name, self.st.modules.current);
        #[cfg(not(feature = "modules"))]
        (0..self.st.pools.nglobals).find(|&g| self.globals[g as usize].name == name)
    }

    /// The defglobal named `name` that module `m` defines.
    pub fn global_of_module(&self, name: SymIdAny, m: ModId) -> Option<crate::value::Ix> {
        #[cfg(feature = "modules")]
        return (0..self.st.pools.nglobals)
            .find(|&g| self.globals[g as usize].name == name && self.module_of_global(g) == m);
        #[cfg(not(feature = "modules"))]
        {
            let _ = m;
            (0..self.st.pools.nglobals).find(|&g| self.globals[g as usize].name == name)
        }
    }

    /// The current module (MAIN without the feature).
    pub fn st_current_module(&self) -> ModId {
        #[cfg(feature = "modules")]
        return self.st.modules.current;
        #[cfg(not(feature = "modules"))]
        MAIN
    }
}

type SymIdAny = crate::value::SymId;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{qualifier_end, split_qualified};
    use std::string::String;

    #[test]
    fn qualifier_is_split_at_the_first_double_colon() {
        assert_eq!(qualifier_end(""), None);
        assert_eq!(qualifier_end(":"), None);
        assert_eq!(qualifier_end("a:b"), None);
        assert_eq!(qualifier_end("::"), Some(0));
        assert_eq!(qualifier_end("MAIN::x"), Some(4));
        assert_eq!(qualifier_end("a:::b"), Some(1));
        // the pair at an even or an odd position, at either end, and after lone colons
        assert_eq!(qualifier_end("ab::c"), Some(2));
        assert_eq!(qualifier_end("abc::d"), Some(3));
        assert_eq!(qualifier_end("abc::"), Some(3));
        assert_eq!(qualifier_end("ab::"), Some(2));
        assert_eq!(qualifier_end("a:b:c::d"), Some(5));
        assert_eq!(qualifier_end(":a:b:c:"), None);
        assert_eq!(qualifier_end("::::"), Some(0));
        // every position against the obvious scan
        for n in 0..10 {
            for mask in 0u32..(1 << n) {
                let s: String = (0..n)
                    .map(|k| if mask & (1 << k) != 0 { ':' } else { 'x' })
                    .collect();
                assert_eq!(qualifier_end(&s), s.find("::"), "{s:?}");
            }
        }
        assert_eq!(split_qualified("A::b::c"), Some(("A", "b::c")));
        assert_eq!(split_qualified("x"), None);
    }
}
