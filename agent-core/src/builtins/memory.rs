//! `mem-used`, `mem-requests`, `release-mem`, `conserve-mem` for an engine whose memory
//! is a fixed arena.
//!
//! CLIPS reports the bytes its allocator handed out and how many requests are
//! outstanding. This engine never allocates: every construct, fact and match lives in a
//! fixed pool. So `(mem-used)` is the bytes of pool entries in use now (entries in use
//! times their size, summed over all pools; the symbol text counted in bytes), and
//! `(mem-requests)` the number of pool entries in use. Both go up and down with the
//! engine's contents as CLIPS's do; the numbers themselves differ from CLIPS's.
//! `(release-mem)` has nothing to give back and returns 0; `(conserve-mem)` is accepted.

use core::mem::size_of;

use super::{Args, Builtin};
use crate::engine::Core;
use crate::error::EvalError;
use crate::value::{Value, NONE};

pub const FUNCS: &[Builtin] = &[
    Builtin::eager("mem-used", 0, 0, mem_used),
    Builtin::eager("mem-requests", 0, 0, mem_requests),
    Builtin::eager("release-mem", 0, 0, release_mem),
    Builtin::eager("conserve-mem", 1, 1, conserve_mem),
];

impl Core<'_> {
    /// Activations on the agenda.
    pub fn activation_count(&self) -> usize {
        let mut n = 0;
        let mut a = self.st.agenda_head;
        while a != NONE {
            n += 1;
            a = self.acts[a as usize].next;
        }
        n
    }

    /// Pool entries in use and their bytes: `(entries, bytes)`.
    pub fn pool_use(&self) -> (usize, usize) {
        let st = &*self.st;
        let parts = [
            entry_of(&self.facts[..0], self.live_fact_count()),
            entry_of(&self.values[..0], st.values_top as usize),
            entry_of(&self.sym_entries[..0], st.nsyms as usize),
            (0, st.sym_bytes as usize),
            entry_of(&self.templates[..0], st.ntemplates as usize),
            entry_of(&self.slots[..0], st.nslots as usize),
            entry_of(&self.rules[..0], st.nrules as usize),
            entry_of(&self.alphas[..0], st.nalpha as usize),
            entry_of(&self.joins[..0], st.njoins as usize),
            entry_of(&self.tokens[..0], st.tokens_live as usize),
            entry_of(&self.acts[..0], self.activation_count()),
            entry_of(&self.funcs[..0], st.nfuncs as usize),
            entry_of(&self.globals[..0], st.nglobals as usize),
            entry_of(&self.exprs[..0], st.nexprs as usize),
            entry_of(&self.deffacts[..0], st.ndeffacts as usize),
            entry_of(&self.externals[..0], st.nexternals as usize),
        ];
        parts
            .iter()
            .fold((0, 0), |(n, b), &(pn, pb)| (n + pn, b + pb))
    }
}

/// `n` entries of the slice's element type: `(n, bytes)`.
fn entry_of<T>(_pool: &[T], n: usize) -> (usize, usize) {
    (n, n * size_of::<T>())
}

fn mem_used(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(cx.pool_use().1 as i64))
}

fn mem_requests(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(cx.pool_use().0 as i64))
}

fn release_mem(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Int(0))
}

fn conserve_mem(_cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Void)
}

#[cfg(test)]
mod tests {
    use crate::testutil::run_program;

    fn number_after(out: &str, prefix: &str) -> i64 {
        out.lines()
            .find_map(|l| l.strip_prefix(prefix))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .unwrap_or(-1)
    }

    #[test]
    fn memory_use_follows_the_engine_contents() {
        let out = run_program(
            "(printout t \"a \" (mem-used) \" \" (mem-requests) crlf)\n\
             (assert (x 1) (x 2) (x 3))\n\
             (printout t \"b \" (mem-used) \" \" (mem-requests) crlf)\n\
             (retract *)\n\
             (printout t \"c \" (mem-used) crlf)\n(release-mem)\n",
        );
        let (a, b, c) = (
            number_after(&out, "a "),
            number_after(&out, "b "),
            number_after(&out, "c "),
        );
        assert!(a > 0 && b > a && c < b, "{out}");
    }
}
