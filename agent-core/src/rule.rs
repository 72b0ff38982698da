//! Rules and agenda activations.

use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use crate::value::{SymId, NONE};

#[derive(Clone, Copy, Debug)]
pub struct Rule {
    pub name: SymId,
    /// -10000..=10000 (CLIPS's range): 16 bits keep the rule table's size with
    /// `complexity` added (the image copies its rules into RAM).
    pub salience: i16,
    /// Salience expression when not a constant (re-evaluated per activation and by
    /// `refresh-agenda`, as CLIPS does for global-based saliences), else NONE.
    pub salience_expr: Ix,
    /// Root join (holds the rule's empty root token) and terminal join.
    pub root: JoinId,
    pub terminal: JoinId,
    /// RHS: chain of actions.
    pub rhs: Ix,
    /// Pattern-level CEs (joins below the root).
    pub npat: u8,
    /// Frame size for RHS `bind` locals.
    pub nlocals: u8,
    /// Next disjunct of the same rule (an `or` LHS yields several).
    pub next_disjunct: Ix,
    /// Next rule ending at the same (shared) terminal join, newest first.
    pub next_at_join: Ix,
    /// First CE is `not`/`exists`/`test`: the root token is rebuilt at `reset`.
    pub root_sensitive: bool,
    pub deleted: bool,
    /// Source text of the construct in the symbol table (for `ppdefrule`), or NONE.
    pub text: Ix,
    /// CLIPS's specificity of the LHS, for the complexity, simplicity, lex and mea
    /// strategies (see `parser::rule`'s `Complexity`).
    pub complexity: u16,
}

impl Rule {
    pub const EMPTY: Rule = Rule {
        name: 0,
        salience: 0,
        salience_expr: NONE,
        root: JoinId::NONE,
        terminal: JoinId::NONE,
        rhs: NONE,
        npat: 0,
        nlocals: 0,
        next_disjunct: NONE,
        next_at_join: NONE,
        root_sensitive: false,
        deleted: false,
        text: NONE,
        complexity: 0,
    };
}

impl crate::engine::Core<'_> {
    /// Whether rule `r` is the live rule `name` of the current module (the one a
    /// definition of that name replaces).
    pub fn rule_here(&self, r: Ix, name: SymId) -> bool {
        let rule = &self.rules[r as usize];
        // the name first: most rules a definition is checked against differ there
        if rule.name != name || rule.deleted {
            return false;
        }
        #[cfg(feature = "modules")]
        if self.rule_tag(r).module != self.current_module() {
            return false;
        }
        true
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Activation {
    pub rule: Ix,
    pub token: TokenId,
    pub salience: i32,
    /// Creation order; the depth strategy puts newer activations first, the others
    /// older ones among equal keys.
    pub seq: u32,
    pub next: Ix,
    pub prev: Ix,
    /// Next activation of the same partial match (rules sharing a terminal join).
    pub next_of_token: Ix,
    /// The C library `rand()` value CLIPS draws for every activation (the random
    /// strategy's key, see `strategy`).
    #[cfg(feature = "extras")]
    pub random: u32,
}

impl Activation {
    pub const EMPTY: Activation = Activation {
        rule: NONE,
        token: TokenId::NONE,
        salience: 0,
        seq: 0,
        next: NONE,
        prev: NONE,
        next_of_token: NONE,
        #[cfg(feature = "extras")]
        random: 0,
    };
}
