//! Whether a deftemplate is in use, which decides whether it may be redefined: CLIPS
//! refuses (`[CSTRCPSR4]`) while a fact of it exists or a construct refers to it (a
//! rule's pattern, an `assert` or fact-set query in a rule, deffunction, deffacts,
//! global or slot default), and otherwise replaces it.

use crate::builtins::{self, Syntax};
use crate::engine::Core;
use crate::expr::{FnKind, Op};
use crate::fact::FactState;
use crate::value::Ix;
use crate::value::{SymId, NONE};

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
        for r in &self.rules[..self.st.nrules as usize] {
            if r.deleted {
                continue;
            }
            if self.chain_uses(r.rhs, tmpl, name) || self.chain_uses(r.salience_expr, tmpl, name) {
                return true;
            }
            // the rule's joins, from its end node up to the root
            let mut j = r.terminal;
            while j != NONE && j != 0 {
                let join = &self.joins[j as usize];
                if join.alpha != NONE {
                    let alpha = &self.alphas[join.alpha as usize];
                    if alpha.tmpl == tmpl || self.chain_uses(alpha.tests, tmpl, name) {
                        return true;
                    }
                }
                if self.chain_uses(join.tests, tmpl, name) || self.chain_uses(join.post, tmpl, name)
                {
                    return true;
                }
                j = join.parent;
            }
        }
        let uses = |e: Ix| self.chain_uses(e, tmpl, name);
        self.funcs[..self.st.nfuncs as usize]
            .iter()
            .any(|f| uses(f.body))
            || self.deffacts[..self.st.ndeffacts as usize]
                .iter()
                .any(|d| uses(d.facts))
            || self.globals[..self.st.nglobals as usize]
                .iter()
                .any(|g| uses(g.init))
            || self.slots[..self.st.nslots as usize]
                .iter()
                .any(|s| uses(s.default))
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
