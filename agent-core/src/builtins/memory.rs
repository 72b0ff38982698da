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

use super::describe::ArgType;
use super::{Args, Builtin};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::Value;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("mem-used", 0, 0, mem_used),
    Builtin::eager("mem-requests", 0, 0, mem_requests),
    Builtin::eager("release-mem", 0, 0, release_mem),
    Builtin::eager("conserve-mem", 1, 1, conserve_mem)
        .args(&[ArgType::Symbol], ArgType::Any)
        .returns(super::describe::Returns::Void),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

impl Core<'_> {
    /// Activations on the agenda.
    pub fn activation_count(&self) -> usize {
        self.st.agenda.agenda_len as usize
    }

    /// Pool entries in use and their bytes: `(entries, bytes)`.
    pub fn pool_use(&self) -> (usize, usize) {
        let st = &*self.st;
        let counts = [
            (self.live_fact_count(), size_of_first(self.facts)),
            (st.facts.values_top as usize, size_of_first(self.values)),
            (st.pools.nsyms as usize, size_of_first(self.sym_entries)),
            // a template and its memory count as one entry
            (
                st.pools.ntemplates as usize,
                size_of::<crate::template::Template>() + size_of_first(self.tmpl_mems),
            ),
            (
                st.pools.nslots as usize,
                size_of::<crate::template::SlotDef>(),
            ),
            (st.pools.nrules as usize, size_of::<crate::rule::Rule>()),
            // a node and its memory count as one entry
            (
                st.pools.nalpha as usize,
                size_of::<crate::rete::AlphaNode>() + size_of_first(self.alpha_mems),
            ),
            (
                st.pools.njoins as usize,
                size_of::<crate::rete::Join>() + size_of_first(self.join_mems.as_slice()),
            ),
            (
                st.pools.tokens_live as usize,
                size_of_first(self.tokens.as_slice()),
            ),
            (self.activation_count(), size_of_first(self.acts)),
            (st.pools.nfuncs as usize, size_of_first(self.funcs)),
            (st.pools.nglobals as usize, size_of_first(self.globals)),
            (
                st.pools.nexprs as usize,
                core::mem::size_of::<crate::expr::Expr>(),
            ),
            (st.pools.ndeffacts as usize, size_of_first(self.deffacts)),
            (st.pools.nexternals as usize, size_of_first(self.externals)),
        ];
        let mut entries = 0;
        let mut bytes = st.pools.sym_bytes as usize;
        for (n, size) in counts {
            entries += n;
            bytes += n * size;
        }
        (entries, bytes)
    }
}

/// Size of one entry of a pool.
fn size_of_first<T>(_pool: &[T]) -> usize {
    size_of::<T>()
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

/// `on` or `off` (nothing to conserve here); CLIPS's messages for anything else: another
/// symbol is reported without an error (a deffunction goes on), another type is an error.
fn conserve_mem(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(s) = cx.arg(a, 0) else {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function conserve-mem expected argument #1 to be of type symbol\n",
        );
        return Err(EvalError::already_reported());
    };
    if !matches!(cx.sym_text(s), "on" | "off") {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function conserve-mem expected argument #1 to be of type symbol with value on or off\n",
        );
    }
    Ok(Value::Void)
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
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
