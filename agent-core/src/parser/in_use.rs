//! Whether a deftemplate is in use, which decides whether it may be redefined or
//! removed: CLIPS refuses (`[CSTRCPSR4]`) while a fact of it exists or a construct refers
//! to it (a rule's pattern, an `assert` or fact-set query in a rule, deffunction,
//! deffacts, global or slot default), and otherwise replaces it. Likewise for a
//! deffunction a construct calls and a global a construct uses (`undeffunction`,
//! `undefglobal`).

use crate::builtins::{self, Syntax};
use crate::engine::Core;
use crate::expr::{Expr, FnKind, Op};
use crate::fact::FactState;
use crate::handle::JoinId;
use crate::value::Ix;
use crate::value::{SymId, NONE};

/// Construct expressions a use check leaves out.
#[derive(Clone, Copy)]
struct Skip {
    /// This deffunction's body ([`SKIP_ALL`]: every deffunction's, NONE: none).
    func: Ix,
    /// The globals' initial values.
    global_inits: bool,
}

const SKIP_ALL: Ix = NONE - 1;

impl Core<'_> {
    pub(crate) fn template_in_use(&self, tmpl: Ix) -> bool {
        let name = self.templates[tmpl as usize].name;
        if self
            .facts
            .iter()
            .any(|f| f.state != FactState::Free && f.tmpl == tmpl)
        {
            return true;
        }
        // a rule's pattern of it
        let in_pattern = self
            .rules
            .iter()
            .take(self.st.pools.nrules as usize)
            .any(|r| {
                let mut j = r.terminal;
                while !r.deleted && j != JoinId::ROOT && j != JoinId::NONE {
                    let join = &self.joins[j];
                    if join.alpha != NONE && self.alphas[join.alpha as usize].tmpl == tmpl {
                        return true;
                    }
                    j = join.parent;
                }
                false
            });
        let skip = Skip {
            func: NONE,
            global_inits: false,
        };
        in_pattern
            || self.any_construct_chain(skip, &mut |e| self.chain_uses(e, tmpl, name))
            || self.command_refers(&|x| x.op == Op::FactSpec && x.data == tmpl)
    }

    /// Retires template `t`, which is not in use ([`Self::template_in_use`]), in place
    /// (indices of later templates stay valid): no name finds it, listings skip it as
    /// they skip ordered-fact templates, and it lists no alpha nodes. Those of rules
    /// removed before were emptied and stay unused: only a rule on this template could
    /// share them again, and none can name it now.
    pub(crate) fn retire_template(&mut self, t: Ix) {
        let tm = &mut self.templates[t as usize];
        tm.name = NONE;
        tm.implied = true;
        tm.alpha_head = NONE;
    }

    /// Whether another construct calls deffunction `func` (CLIPS then refuses
    /// `undeffunction`; its own recursive calls do not count, nor, with
    /// `but_functions`, any deffunction's).
    pub(crate) fn deffunction_in_use(&self, func: Ix, but_functions: bool) -> bool {
        let calls =
            |x: &Expr| x.op == Op::Call && x.aux == FnKind::Deffunction as u8 && x.data == func;
        let skip = Skip {
            func: if but_functions { SKIP_ALL } else { func },
            global_inits: false,
        };
        self.any_construct_chain(skip, &mut |e| self.chain_has(e, &calls))
            || self.command_refers(&calls)
    }

    /// Whether a construct reads or sets global `global` (CLIPS then refuses
    /// `undefglobal`; globals' initial values do not count).
    pub(crate) fn global_in_use(&self, global: Ix) -> bool {
        let reads = |x: &Expr| x.op == Op::Global && x.data == global;
        let skip = Skip {
            func: NONE,
            global_inits: true,
        };
        self.any_construct_chain(skip, &mut |e| self.chain_has(e, &reads))
            || self.command_refers(&reads)
    }

    /// Whether the command being run (`State::command_base` on) has a node `is` picks:
    /// what it refers to is in use while it runs.
    fn command_refers(&self, is: &dyn Fn(&Expr) -> bool) -> bool {
        let end = self.st.pools.nexprs;
        (self.st.eval.command_base.min(end)..end).any(|e| is(&self.exprs[e as usize]))
    }

    /// Calls `hit` on every expression chain a construct keeps (rule actions,
    /// salience and tests, deffunction bodies, deffacts, global initial values, slot
    /// defaults) until it says yes.
    fn any_construct_chain(&self, skip: Skip, hit: &mut dyn FnMut(Ix) -> bool) -> bool {
        for r in self.rules.iter().take(self.st.pools.nrules as usize) {
            if r.deleted {
                continue;
            }
            if hit(r.rhs) || hit(r.salience_expr) {
                return true;
            }
            // the rule's joins, from its end node up to the root
            let mut j = r.terminal;
            while j != JoinId::ROOT && j != JoinId::NONE {
                let join = &self.joins[j];
                if join.alpha != NONE && hit(self.alphas[join.alpha as usize].tests) {
                    return true;
                }
                if hit(join.tests) || hit(join.post) {
                    return true;
                }
                j = join.parent;
            }
        }
        let funcs = self.funcs[..self.st.pools.nfuncs as usize]
            .iter()
            .enumerate();
        funcs
            .filter(|&(i, f)| skip.func != SKIP_ALL && skip.func != i as Ix && f.name != NONE)
            .any(|(_, f)| hit(f.body))
            || self.deffacts[..self.st.pools.ndeffacts as usize]
                .iter()
                .any(|d| hit(d.facts))
            || (!skip.global_inits
                && self.globals[..self.st.pools.nglobals as usize]
                    .iter()
                    .any(|g| hit(g.init)))
            || self
                .slots
                .iter()
                .take(self.st.pools.nslots as usize)
                .any(|s| hit(s.default))
    }

    /// Whether a node of an expression chain (or below one) is one `is` picks.
    fn chain_has(&self, mut e: Ix, is: &dyn Fn(&Expr) -> bool) -> bool {
        while e != NONE {
            let x = self.exprs[e as usize];
            if is(&x) {
                return true;
            }
            // constants keep their payload, pattern variables their descriptor, in
            // the places other nodes keep children
            let leaf = matches!(
                x.op,
                Op::Int | Op::Float | Op::Sym | Op::Str | Op::PatVar | Op::Payload
            );
            if !leaf && self.chain_has(x.first, is) {
                return true;
            }
            e = x.next;
        }
        false
    }

    /// Whether an expression chain (a node and its next siblings) refers to the
    /// template: a fact spec of it, or a fact-set query over it.
    fn chain_uses(&self, mut e: Ix, tmpl: Ix, name: SymId) -> bool {
        while e != NONE {
            if self.expr_uses(e, tmpl, name) {
                return true;
            }
            e = self.exprs[e as usize].next;
        }
        false
    }

    fn expr_uses(&self, e: Ix, tmpl: Ix, name: SymId) -> bool {
        let x = self.exprs[e as usize];
        match x.op {
            // constants keep their payload, pattern variables their descriptor, in
            // the places other nodes keep children
            Op::Int | Op::Float | Op::Sym | Op::Str | Op::PatVar | Op::Payload => false,
            Op::FactSpec if x.data == tmpl => true,
            Op::Call
                if x.aux == FnKind::Builtin as u8
                    && builtins::get(x.data).syntax == Syntax::Query =>
            {
                // first argument: query variables, each with its template names
                let decl = x.first;
                let mut var = if decl == NONE {
                    NONE
                } else {
                    self.exprs[decl as usize].first
                };
                while var != NONE {
                    let mut t = self.exprs[var as usize].first;
                    while t != NONE {
                        let tx = self.exprs[t as usize];
                        if tx.op == Op::Sym && tx.data == name {
                            return true;
                        }
                        t = tx.next;
                    }
                    var = self.exprs[var as usize].next;
                }
                decl != NONE && self.chain_uses(self.exprs[decl as usize].next, tmpl, name)
            }
            _ => self.chain_uses(x.first, tmpl, name),
        }
    }
}
