//! Walking a partial match up to the root: the facts it holds, by pattern position.

use crate::engine::Core;
use crate::fact::Fact;
use crate::handle::{JoinId, SlotsRef, TokenId};
use crate::rete::{Join, JoinKind, Token};
use crate::rom::RomRef;

/// The facts of a partial match, from its last pattern up to the root: per CE its
/// depth (pattern position) and the number of the fact it matched, `None` for a
/// not/exists or test CE. What a watch line prints (`f-1,*`), an activation's identity
/// across a rebuild and the strategies' recency read.
pub(crate) struct Basis<'a> {
    pub(crate) tokens: SlotsRef<'a, TokenId, Token>,
    pub(crate) joins: RomRef<'a, Join, JoinId>,
    pub(crate) facts: &'a [Fact],
    pub(crate) at: TokenId,
}

impl Iterator for Basis<'_> {
    type Item = (usize, Option<u32>);

    // inlined on the host: the agenda hashes every activation's basis with it
    #[cfg_attr(feature = "host-speedups", inline(always))]
    fn next(&mut self) -> Option<Self::Item> {
        if self.at == TokenId::NONE {
            return None;
        }
        let tk = self.tokens[self.at];
        let j = self.joins[tk.owner];
        if j.kind == JoinKind::Root {
            return None;
        }
        self.at = tk.parent;
        let num =
            (tk.am != TokenId::NONE).then(|| self.facts[self.tokens[tk.am].fact as usize].num);
        Some((j.depth as usize, num))
    }
}

impl Core<'_> {
    /// The facts partial match `token` holds (see [`Basis`]).
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn basis(&self, token: TokenId) -> Basis<'_> {
        Basis {
            tokens: SlotsRef::new(self.tokens.as_slice()),
            joins: self.joins.as_ref(),
            facts: &self.facts[..],
            at: token,
        }
    }
}
