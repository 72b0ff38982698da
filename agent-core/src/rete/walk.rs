//! Walking the joins below a point of the network (for facts about a subtree that
//! deferred propagation and whole-memory removal need).

use crate::engine::Core;
use crate::handle::JoinId;

/// Deepest join subtree a walk follows (deeper: it gives up).
const WALK_STACK: usize = 64;

impl Core<'_> {
    /// Visits join `first` (and with `chain` the joins linked after it by `alpha_next`,
    /// e.g. an alpha node's successors), their descendants and the joins taking their
    /// partial matches from the right; false as soon as `ok` refuses one, or the walk
    /// is deeper than it can follow.
    pub(super) fn walk_joins(
        &self,
        first: JoinId,
        chain: bool,
        ok: &mut dyn FnMut(&Core<'_>, JoinId) -> bool,
    ) -> bool {
        let mut stack = [JoinId::NONE; WALK_STACK];
        let mut n = 0;
        let mut j = first;
        while j != JoinId::NONE {
            if n == WALK_STACK {
                return false;
            }
            stack[n] = j;
            n += 1;
            j = if chain {
                self.joins[j].alpha_next
            } else {
                JoinId::NONE
            };
        }
        while n > 0 {
            n -= 1;
            let j = stack[n];
            if !ok(self, j) {
                return false;
            }
            let jn = &self.joins[j];
            // children by `next_sibling`, joins from the right by `alpha_next`
            for (mut c, by_sibling) in [(jn.first_child, true), (jn.rsucc, false)] {
                while c != JoinId::NONE {
                    if n == WALK_STACK {
                        return false;
                    }
                    stack[n] = c;
                    n += 1;
                    let cj = &self.joins[c];
                    c = if by_sibling {
                        cj.next_sibling
                    } else {
                        cj.alpha_next
                    };
                }
            }
        }
        true
    }
}
