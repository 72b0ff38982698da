//! The Rete network. See the crate docs for the design.

pub(crate) mod alpha;
pub(crate) mod basis;
mod beta;
mod index;
#[cfg(feature = "host-speedups")]
pub use index::OrPlan;
pub use index::{KeyPlan, KEY_PLANS};
mod defer;
pub use defer::Deferred;
#[cfg(all(feature = "defer", feature = "host-speedups"))]
pub use defer::ScanRun;
#[cfg(feature = "defer")]
pub use defer::{HeldPrint, Queued, QUEUED_MAX};
#[cfg(feature = "host-speedups")]
pub(crate) mod discrim;
#[cfg(feature = "host-speedups")]
pub use discrim::{AlphaDisc, DiscState, TemplateDisc};
/// Host speed-up: constant-test discrimination (`discrim`); without the feature, no
/// bytes (the pool table keeps the arrays, of zero-sized entries).
#[cfg(not(feature = "host-speedups"))]
pub type AlphaDisc = ();
#[cfg(not(feature = "host-speedups"))]
pub type TemplateDisc = ();
#[cfg(feature = "host-speedups")]
pub const NO_ALPHA_DISC: AlphaDisc = AlphaDisc::EMPTY;
#[cfg(not(feature = "host-speedups"))]
pub const NO_ALPHA_DISC: AlphaDisc = ();
#[cfg(feature = "host-speedups")]
pub const NO_TEMPLATE_DISC: TemplateDisc = TemplateDisc::EMPTY;
#[cfg(not(feature = "host-speedups"))]
pub const NO_TEMPLATE_DISC: TemplateDisc = ();
#[cfg(feature = "grow")]
pub(crate) mod mforder;
#[cfg(feature = "grow")]
pub use mforder::MfOrder;
#[cfg(feature = "grow")]
pub(crate) mod order;
#[cfg(feature = "host-speedups")]
mod plan;
mod quick;
#[cfg(feature = "grow")]
pub use order::PrimeOrders;
#[cfg(any(feature = "defer", feature = "wipe"))]
mod walk;
#[cfg(feature = "wipe")]
mod wipe;
#[cfg(feature = "host-speedups")]
pub use plan::TestPlans;
pub use quick::{TestOp, TestPlan, PLAN_TESTS, TEST_PLANS};

pub use crate::handle::{JoinId, TokenId};
use crate::value::Ix;
use crate::value::NONE;

/// Pattern index marking "the fact under test" in alpha tests (shared between rules).
pub const THIS_PATTERN: u8 = 0xFE;
/// Most multifield lengths an alpha match records (ambiguous segmentations).
pub const MAX_MARKS: usize = 4;
/// Levels of a pattern's network path used to order alpha nodes as CLIPS does.
pub const PATH_LEN: usize = 6;
/// Path locator of the placeholder node of a pattern without tested fields.
pub const EMPTY_PATH: Ix = 0xFFFE;
/// Most pattern-level CEs in one rule. Hosts allow 64 (a connect-four board shown by
/// one rule of 43 patterns, lu1smgb/UGR-IC 4enraya.clp); the image keeps 32, its RAM.
#[cfg(feature = "grow")]
pub const MAX_PATTERNS: usize = 64;
#[cfg(not(feature = "grow"))]
pub const MAX_PATTERNS: usize = IMAGE_MAX_PATTERNS;
/// The image's (and every engine's without `grow`) most CEs in one rule: a compiled
/// rule base, written on the host, holds no rule past it.
pub const IMAGE_MAX_PATTERNS: usize = 32;
/// Pattern depths whose facts a partial match keeps a copy of on the host
/// (`Token::binds`); deeper ones are read by walking the ancestry.
#[cfg(feature = "host-speedups")]
pub const BIND_W: usize = 8;
/// Most fields of one pattern compared for equality with earlier variables that
/// key its alpha node (CLIPS's "right hash"); further ones are plain join tests.
pub const MAX_RHASH: usize = 4;
/// Host: index groups a join's output memory keeps besides its `Join::index_child`'s
/// (see `rete::index`), each for the keyed children that read the same fields.
#[cfg(feature = "host-speedups")]
pub const XGROUPS: usize = 3;
/// Host: children of one join whose index group is remembered (`JoinMem::xmap`).
#[cfg(feature = "host-speedups")]
pub const XMAP: usize = 8;
/// Host: an `xmap` entry of a child that scans the memory (no group fits it).
#[cfg(feature = "host-speedups")]
pub const XSCAN: u8 = u8::MAX;

/// One distinct pattern: a template plus the tests that need only the fact itself.
/// Shared by every rule that uses an identical pattern.
#[derive(Clone, Copy, Debug)]
pub struct AlphaNode {
    pub tmpl: Ix,
    /// Chain of `PatSlot` descriptor nodes (multislot segmentation), NONE if none.
    pub desc: Ix,
    /// Chain of boolean tests, all must hold.
    pub tests: Ix,
    pub next_in_tmpl: Ix,
    /// First successor join (chained by `Join::alpha_next`, newest first).
    pub succ: JoinId,
    pub nmarks: u8,
    pub live: bool,
    /// The pattern's path in CLIPS's pattern network (field locators and their alpha
    /// tests) and the ids of those network nodes; they order the template's alpha
    /// nodes so facts visit patterns in CLIPS's order.
    pub path_loc: [Ix; PATH_LEN],
    pub path_test: [Ix; PATH_LEN],
    pub key: [Ix; PATH_LEN],
    pub key_len: u8,
    /// Fields of this pattern that joins compare for equality with variables bound
    /// earlier (expressions of the defining pattern). CLIPS keeps patterns that differ
    /// only here apart, which decides the order facts visit them.
    pub rhash: [Ix; MAX_RHASH],
    pub nrhash: u8,
    /// Host: whether `alpha_key` may read the key in place when a field is an
    /// element at a fixed offset (`index::elem_keyed`, decided when the fields are):
    /// a key with a field no in-place read serves (a `$?rest`) goes to the
    /// evaluator without trying.
    #[cfg(feature = "host-speedups")]
    pub elem_key: bool,
    /// Host: a hash of what sharing compares (`compile::alpha` `share_sig`), never 0
    /// for a node the compiler made (0: unknown, compared in full), so finding an
    /// identical node passes the others over at one comparison each.
    #[cfg(feature = "host-speedups")]
    pub share_sig: u32,
    /// Host: bit `i` (a segmentation mark): a test that may fail with an error or
    /// act (`alpha::test_acts`) lies on a level of the path before mark `i`'s node,
    /// so `enumerate_marks` runs the tests before that node once per earlier choice
    /// (`tests_before_mark`); bit [`STAGE_LENGTH`]: one lies on a known level
    /// (`tests_before_length`). Worked out when the node is made (`set_stage`); all
    /// set until then (a compiled rule base's nodes).
    #[cfg(feature = "extras")]
    pub stage: u8,
    /// Host: per mark `i` of `stage`: the tests after the last acting one before
    /// mark `i`'s node and the first test not before it: tests left that start from
    /// one of those up to that one have none left to stage there (`stage_at`).
    #[cfg(feature = "extras")]
    pub stage_from: [Ix; MAX_MARKS],
    #[cfg(feature = "extras")]
    pub stage_end: [Ix; MAX_MARKS],
}

/// Host: `AlphaNode::stage`'s bit for tests before a slot's length test.
#[cfg(feature = "extras")]
pub const STAGE_LENGTH: u8 = 0x80;

impl AlphaNode {
    pub const EMPTY: AlphaNode = AlphaNode {
        tmpl: 0,
        desc: NONE,
        tests: NONE,
        next_in_tmpl: NONE,
        succ: JoinId::NONE,
        nmarks: 0,
        live: false,
        path_loc: [0; PATH_LEN],
        path_test: [NONE; PATH_LEN],
        key: [0; PATH_LEN],
        key_len: 0,
        rhash: [NONE; MAX_RHASH],
        nrhash: 0,
        #[cfg(feature = "host-speedups")]
        elem_key: false,
        #[cfg(feature = "host-speedups")]
        share_sig: 0,
        #[cfg(feature = "extras")]
        stage: 0xFF,
        #[cfg(feature = "extras")]
        stage_from: [NONE; MAX_MARKS],
        #[cfg(feature = "extras")]
        stage_end: [NONE; MAX_MARKS],
    };
}

/// What changes at run time per alpha node: its memory (an own pool, so that a
/// compiled rule base's alpha nodes can be read in place, `rom`).
#[derive(Clone, Copy, Debug)]
pub struct AlphaMem {
    /// Alpha-match tokens, oldest first (CLIPS iterates them so).
    pub head: TokenId,
    pub tail: TokenId,
}

impl AlphaMem {
    pub const EMPTY: AlphaMem = AlphaMem {
        head: TokenId::NONE,
        tail: TokenId::NONE,
    };
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum JoinKind {
    /// The one global root (join 0), holding the empty root token.
    Root,
    Positive,
    Negative,
    Exists,
    /// A `test` CE with no pattern before it.
    Test,
    /// Where a rule ends: partial matches arriving here become its activations.
    /// Listed among its parent's children, so rule activations and child joins are
    /// visited in one newest-first order, as CLIPS does.
    Terminal,
}

impl JoinKind {
    /// For a child of the root, primed at `reset`: Some(false) when fed by no
    /// pattern (a rule's terminal, a first `test`: CLIPS's right-prime joins),
    /// Some(true) after a first `not`/`exists` (left-prime joins), None for a pattern.
    #[inline]
    pub fn left_primed(self) -> Option<bool> {
        match self {
            JoinKind::Negative | JoinKind::Exists => Some(true),
            JoinKind::Test | JoinKind::Terminal => Some(false),
            _ => None,
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Join {
    pub kind: JoinKind,
    /// Pattern index of the right input (the root has none).
    pub depth: u8,
    /// Terminal node: its rule (NONE for other joins).
    pub rule: Ix,
    pub parent: JoinId,
    /// Child joins (newest first), chained by `next_sibling`.
    pub first_child: JoinId,
    pub next_sibling: JoinId,
    /// Rules using this join (joins with the same prefix are shared).
    pub refs: Ix,
    pub alpha: Ix,
    /// Chain of boolean tests needing earlier patterns.
    pub tests: Ix,
    /// `test` CEs after a `not`/`exists`: checked on the left token before output.
    pub post: Ix,
    /// Next join in the alpha node's successor list.
    pub alpha_next: JoinId,
    /// `not`/`exists` over several CEs: the join ending the subnetwork whose partial
    /// matches are this join's right input ("join from the right"), NONE otherwise.
    pub rjoin: JoinId,
    /// First join having this one as its right input (chained by `alpha_next`).
    pub rsucc: JoinId,
    /// The child join whose equality tests key the index of this join's output
    /// memory (see `rete::index`), NONE if the memory is not indexed.
    pub index_child: JoinId,
}

impl Join {
    pub fn is_terminal(&self) -> bool {
        self.kind == JoinKind::Terminal
    }
}

impl Join {
    pub const EMPTY: Join = Join {
        kind: JoinKind::Root,
        depth: 0,
        rule: NONE,
        parent: JoinId::NONE,
        first_child: JoinId::NONE,
        next_sibling: JoinId::NONE,
        refs: 0,
        alpha: NONE,
        tests: NONE,
        post: NONE,
        alpha_next: JoinId::NONE,
        rjoin: JoinId::NONE,
        rsucc: JoinId::NONE,
        index_child: JoinId::NONE,
    };
}

/// What changes at run time per join: its output memory and the caches about it (an
/// own pool, so that a compiled rule base's joins can be read in place, `rom`).
#[derive(Clone, Copy, Debug)]
pub struct JoinMem {
    /// Output memory: first token (newest first).
    pub mem: TokenId,
    /// Host: whether the output memory's partial matches are in their index buckets.
    /// The index is built on the first right activation that uses it and dropped
    /// when the memory empties, so memories that are filled and emptied again
    /// without one (most, in Manners) never pay for it.
    #[cfg(feature = "host-speedups")]
    pub index_built: bool,
    /// Host: whether the child list has exactly one entry (read for every deleted
    /// partial match; two loads less than walking the list), kept by
    /// `Core::note_children`.
    #[cfg(feature = "host-speedups")]
    pub one_child: bool,
    /// Host: the child join whose key defines extra index group `g + 1` (NONE:
    /// unused); groups are taken on a child's first right activation and kept until
    /// a child goes away (see `rete::index`).
    #[cfg(feature = "host-speedups")]
    pub xkey: [JoinId; XGROUPS],
    /// Host: number of extra groups in use (the first `nx` of `xkey`).
    #[cfg(feature = "host-speedups")]
    pub nx: u8,
    /// Host: the index group of each child met so far (0: `Join::index_child`'s,
    /// `XSCAN`: none, the child scans the memory).
    #[cfg(feature = "host-speedups")]
    pub xmap: [(JoinId, u8); XMAP],
    /// Host: the extra groups whose buckets hold the memory's partial matches (bit
    /// `g - 1`), built as `index_built` is and likewise cleared when it empties.
    #[cfg(feature = "host-speedups")]
    pub xbuilt: u8,
    /// Whether no join from this one down feeds a join from the right (its memories
    /// may then be emptied whole, `rete::wipe`), worked out for network generation
    /// `plain_gen`.
    #[cfg(feature = "wipe")]
    pub plain: bool,
    #[cfg(feature = "wipe")]
    pub plain_gen: u32,
    /// Host: for a not join fed by an alpha node, what a retract of a fact of that
    /// node's template can reach (`Core::dying_reach`): bit `REACH_LEFT`, a pattern
    /// of the template on the left whose fact is not in `Token::binds`; bit
    /// `REACH_BELOW`, one below the join. Worked out for network generation
    /// `reach_gen`.
    #[cfg(feature = "host-speedups")]
    pub reach: u8,
    /// Host: the pattern depths left of the join whose facts its left partial
    /// matches keep in `Token::binds` and that have that template (with `reach`).
    #[cfg(feature = "host-speedups")]
    pub reach_depths: u8,
    #[cfg(feature = "host-speedups")]
    pub reach_gen: u32,
    /// Host: `Core::sub_is_free` of the join, worked out for network generation
    /// `free_gen` (read on every subnetwork match made active and every blocker
    /// search; it walks the subnetwork's tests).
    #[cfg(feature = "grow")]
    pub free: bool,
    #[cfg(feature = "grow")]
    pub free_gen: u32,
}

impl JoinMem {
    pub const EMPTY: JoinMem = JoinMem {
        mem: TokenId::NONE,
        #[cfg(feature = "host-speedups")]
        index_built: false,
        #[cfg(feature = "host-speedups")]
        one_child: false,
        #[cfg(feature = "host-speedups")]
        xkey: [JoinId::NONE; XGROUPS],
        #[cfg(feature = "host-speedups")]
        nx: 0,
        #[cfg(feature = "host-speedups")]
        xmap: [(JoinId::NONE, 0); XMAP],
        #[cfg(feature = "host-speedups")]
        xbuilt: 0,
        #[cfg(feature = "wipe")]
        plain: false,
        #[cfg(feature = "wipe")]
        plain_gen: u32::MAX,
        #[cfg(feature = "host-speedups")]
        reach: 0,
        #[cfg(feature = "host-speedups")]
        reach_depths: 0,
        #[cfg(feature = "host-speedups")]
        reach_gen: u32::MAX,
        #[cfg(feature = "grow")]
        free: false,
        #[cfg(feature = "grow")]
        free_gen: u32::MAX,
    };
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum TokenKind {
    Free,
    /// An entry of an alpha memory.
    Alpha,
    /// A partial match in a join's output memory.
    Beta,
}

/// Alpha matches and partial matches share this pool.
#[derive(Clone, Copy, Debug)]
pub struct Token {
    pub kind: TokenKind,
    /// Output of a not/exists join: a right item (its one blocker, as in CLIPS)
    /// matches.
    pub blocked: bool,
    pub marks: [u8; MAX_MARKS],
    /// Partial match: its join. Alpha match: its alpha node, read by
    /// [`Token::alpha`] (one field for both, as a token is one or the other).
    pub owner: JoinId,
    /// Alpha match: the fact slot.
    pub fact: Ix,
    /// Partial match: the alpha match joined on the right (NONE for not/exists/test/root).
    pub am: TokenId,
    pub parent: TokenId,
    /// Alpha match: first partial match built on it; partial match: first left child.
    pub first_child: TokenId,
    /// Partial match: siblings under `parent`; alpha match: other matches of the same fact.
    pub next_sib: TokenId,
    pub prev_sib: TokenId,
    /// Partial match: siblings under `am`. Not/exists output: the owed list (see
    /// `Core::is_owed`), or while blocked its blocker's `blocks` list (the head's
    /// `am_prev` is the blocker).
    pub am_next: TokenId,
    pub am_prev: TokenId,
    pub mem_next: TokenId,
    pub mem_prev: TokenId,
    /// Partial match: its first activation. Alpha match: propagation progress.
    pub extra: Ix,
    /// The not/exists outputs this token blocks (chained by their `am_next`), so
    /// removing it visits exactly the outputs it decided.
    pub blocks: TokenId,
    /// Beta-memory index links of a partial match (previous, bucket), kept in `marks`
    /// when indices are `u16` (see `rete::index`).
    #[cfg(feature = "wide-index")]
    pub beta_links: [Ix; 2],
    /// Partial match: the fact bound at each pattern depth below `BIND_W` (NONE for
    /// not/exists/test levels), copied from the parent when linked, so the quick
    /// join tests and index keys read them without walking the ancestry. Host
    /// only: it would cost the image 16 bytes per token.
    #[cfg(feature = "host-speedups")]
    pub binds: [Ix; BIND_W],
    /// Partial match: its key for its join's index child, once computed (by a left
    /// activation of that child), for when the index is built (`JoinMem::index_built`).
    #[cfg(feature = "host-speedups")]
    pub has_key: bool,
    /// Host: whether the partial match is in a bucket of an extra index group.
    #[cfg(feature = "host-speedups")]
    pub in_x: bool,
    #[cfg(feature = "host-speedups")]
    pub key: u32,
}

impl Token {
    /// An alpha match's alpha node.
    #[inline(always)]
    pub fn alpha(&self) -> Ix {
        self.owner.0
    }

    /// The `owner` of an alpha match of alpha node `a`.
    #[inline(always)]
    pub const fn alpha_owner(a: Ix) -> JoinId {
        JoinId(a)
    }

    pub const EMPTY: Token = Token {
        kind: TokenKind::Free,
        blocked: false,
        marks: [0; MAX_MARKS],
        owner: JoinId::NONE,
        fact: NONE,
        am: TokenId::NONE,
        parent: TokenId::NONE,
        first_child: TokenId::NONE,
        next_sib: TokenId::NONE,
        prev_sib: TokenId::NONE,
        am_next: TokenId::NONE,
        am_prev: TokenId::NONE,
        mem_next: TokenId::NONE,
        mem_prev: TokenId::NONE,
        extra: NONE,
        blocks: TokenId::NONE,
        #[cfg(feature = "wide-index")]
        beta_links: [NONE; 2],
        #[cfg(feature = "host-speedups")]
        binds: [NONE; BIND_W],
        #[cfg(feature = "host-speedups")]
        has_key: false,
        #[cfg(feature = "host-speedups")]
        in_x: false,
        #[cfg(feature = "host-speedups")]
        key: 0,
    };
}

/// Host: when a partial match of a join feeding joins from the right was last put at
/// the front of its memory (a count, `State::stamp`; 0: never): among the active
/// ones, memory order is newest stamp first, so a blocker search picks the first in
/// memory order among the few extending its left partial match without walking the
/// memory (`Core::sub_first_candidate`). Kept in `State::stamps`, not in the token
/// pool, so that programs without such joins do not carry them.
#[cfg(feature = "grow")]
pub type Stamp = u32;

/// Host: a partial match's links in its memory's extra index groups (next, previous,
/// bucket; as `beta_links` for the first group), in a side array of the token pool
/// (`Core::token_xlinks`) so that the tokens of memories without extra groups (most)
/// do not carry them: meaningful only while the token's `in_x` is set (the first link
/// into a group clears them). Zero-sized without `host-speedups`.
#[cfg(feature = "host-speedups")]
pub type XLinks = [[Ix; 3]; XGROUPS];
#[cfg(feature = "host-speedups")]
pub const NO_XLINKS: XLinks = [[NONE; 3]; XGROUPS];
#[cfg(not(feature = "host-speedups"))]
pub type XLinks = ();
#[cfg(not(feature = "host-speedups"))]
pub const NO_XLINKS: XLinks = ();

/// What a pattern variable resolves against: a fact slot plus its segmentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatBinding {
    pub fact: Ix,
    pub marks: [u8; MAX_MARKS],
}

impl PatBinding {
    pub const EMPTY: PatBinding = PatBinding {
        fact: NONE,
        marks: [0; MAX_MARKS],
    };
}

/// How many unblocked not outputs one modify can take back before re-asserting its
/// old fact (see `Core::owe_unblocked`).
pub const UNBLOCK_LOG_LEN: usize = 16;

/// The not outputs a modify's retract unblocked, as (token, join, left parent).
#[derive(Clone, Copy, Debug)]
pub struct UnblockLog {
    pub on: bool,
    pub overflow: bool,
    pub len: u8,
    pub entries: [(TokenId, JoinId, TokenId); UNBLOCK_LOG_LEN],
}

impl UnblockLog {
    pub const EMPTY: UnblockLog = UnblockLog {
        on: false,
        overflow: false,
        len: 0,
        entries: [(TokenId::NONE, JoinId::NONE, TokenId::NONE); UNBLOCK_LOG_LEN],
    };
}
