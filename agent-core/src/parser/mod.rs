//! The CLIPS reader, the syntax stage: commands and constructs read into expression
//! nodes and construct entries; a rule into its intermediate form, which
//! `crate::compile` builds into the network once it is whole.
//!
//! Every construct is read and built inside a checkpoint; on any error the engine
//! goes back to it, so a bad construct leaves nothing behind (a rule the reader
//! refuses has built nothing in the network, so only the append-only pools go back).

/// Maps a pool error to a load error at the current position (two-step so the
/// parser is not borrowed twice).
macro_rules! cap {
    ($p:ident, $e:expr) => {{
        let r = $e;
        $p.cap_res(r)
    }};
}

mod construct;
mod expr;

/// CLIPS's warning for an integer literal beyond 64 bits (clamped).
pub const OVERFLOW_WARNING: &str = "[SCANNER1] WARNING: Over or underflow of long long integer.\n";
mod facts;
mod in_use;
#[cfg(feature = "modules")]
mod module;
#[cfg(feature = "extras")]
pub(crate) mod rhs_types;
pub(crate) mod rule;
mod slot;

use crate::engine::Core;
use crate::error::{CapacityError, LoadError};
use crate::lexer::{Lexer, Tok, Token};
use crate::rete::MAX_PATTERNS;
use crate::value::Ix;
use crate::value::{SymId, NONE};

/// Whether symbol text `s` holds a module separator `::` (a byte scan: on the short
/// relation names of every fact and pattern cheaper than a substring search).
#[inline]
pub(crate) fn has_module_sep(s: &str) -> bool {
    s.as_bytes().windows(2).any(|w| w == b"::")
}

/// Most variables visible at once while parsing one construct: 64 in the image; on
/// hosts (`grow`) as many as fit in memory (CLIPS has no limit), the tables growing
/// as variables are added ([`VarTable`]).
#[cfg(not(feature = "grow"))]
pub const MAX_VARS: usize = IMAGE_MAX_VARS;
#[cfg(feature = "grow")]
pub const MAX_VARS: usize = usize::MAX;
/// The image's (and every engine's without `grow`) most variables in one construct.
pub const IMAGE_MAX_VARS: usize = 64;

/// A table with an entry per variable (by `vars` index): in the image a fixed array.
#[cfg(not(feature = "grow"))]
pub type VarTable<T> = [T; MAX_VARS];

/// On hosts a vector grown to the entries written, so a parser starts without filling
/// a table and a construct may name any number of variables; an entry never written
/// reads as `fill`, as the array's initial one.
#[cfg(feature = "grow")]
pub struct VarTable<T> {
    v: alloc::vec::Vec<T>,
    fill: T,
}

#[cfg(feature = "grow")]
impl<T: Copy> VarTable<T> {
    pub const fn new(fill: T) -> Self {
        VarTable {
            v: alloc::vec::Vec::new(),
            fill,
        }
    }

    /// Grows to hold entry `i`: room for the image's 64 entries at first, then
    /// doubled, and the next entry pushed (variables are added in order), so a table
    /// is allocated once per construct of up to 64 variables and never filled
    /// (growing by one entry per variable cost zebra's load +0.3 %).
    #[inline(always)]
    fn reach(&mut self, i: usize) {
        if i == self.v.len() && self.v.len() < self.v.capacity() {
            self.v.push(self.fill);
        } else {
            self.reach_slow(i);
        }
    }

    #[cold]
    #[inline(never)]
    fn reach_slow(&mut self, i: usize) {
        let room = (i + 1).max(IMAGE_MAX_VARS).max(self.v.capacity() * 2);
        self.v.reserve(room - self.v.len());
        self.v.resize(i + 1, self.fill);
    }
}

#[cfg(feature = "grow")]
impl<T> core::ops::Deref for VarTable<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.v
    }
}

#[cfg(feature = "grow")]
impl<T> core::ops::Index<usize> for VarTable<T> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        self.v.get(i).unwrap_or(&self.fill)
    }
}

#[cfg(feature = "grow")]
impl<T: Copy> core::ops::IndexMut<usize> for VarTable<T> {
    fn index_mut(&mut self, i: usize) -> &mut T {
        if self.v.len() <= i {
            self.reach(i);
        }
        &mut self.v[i]
    }
}

#[cfg(feature = "grow")]
impl<T> core::ops::Index<core::ops::RangeTo<usize>> for VarTable<T> {
    type Output = [T];
    fn index(&self, r: core::ops::RangeTo<usize>) -> &[T] {
        // entries below a count of variables were all written
        &self.v[..r.end.min(self.v.len())]
    }
}

#[cfg(feature = "grow")]
impl<T> core::ops::Index<core::ops::Range<usize>> for VarTable<T> {
    type Output = [T];
    fn index(&self, r: core::ops::Range<usize>) -> &[T] {
        let end = r.end.min(self.v.len());
        &self.v[r.start.min(end)..end]
    }
}

/// Deepest nesting the reader follows (expressions, conditional elements, `~`
/// chains): the reader recurses per level, so input must not decide how deep. An
/// expression nested deeper than the evaluator's call limit could not run anyway.
/// What a parse error at the end of the input expected.
pub const INPUT_ENDED: &str = "')' (the input ended inside a construct)";

pub const MAX_NESTING: u16 = crate::eval::MAX_EVAL_DEPTH;
const _: () = assert!(MAX_NESTING == 200, "update the text of the nesting error");

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarKind {
    /// Bound by an LHS pattern: pattern index, field locator, multislot descriptor.
    Pat { pat: u8, loc: Ix, desc: Ix },
    /// A frame slot (RHS `bind`, deffunction parameter, loop variable).
    Local(Ix),
}

#[derive(Clone, Copy, Debug)]
pub struct VarEntry<'s> {
    pub name: &'s str,
    pub kind: VarKind,
    pub multi: bool,
    /// A local bound only inside a condition or loop may be read unbound: its name
    /// symbol, for the run-time error (`NONE`: always bound when read).
    pub unbound_name: Ix,
    /// An LHS variable the actions `bind` somewhere: the frame slot that holds its
    /// new value (`NONE`: never bound). As in CLIPS, every read of it in the actions,
    /// before or after the `bind` in the text, reads that slot, and the LHS value
    /// while the slot is unbound (see `Core::local`).
    pub rebound: Ix,
}

impl VarEntry<'_> {
    const EMPTY: Self = VarEntry {
        name: "",
        kind: VarKind::Local(0),
        multi: false,
        unbound_name: NONE,
        rebound: NONE,
    };
}

/// Where expressions are being parsed, which decides how unknown variables resolve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// Top-level command: `?x` is a top-level variable (stored as a hidden global).
    TopLevel,
    /// Rule RHS or deffunction body: `bind` creates frame locals.
    Frame,
    /// LHS constraint expressions: only already bound variables.
    Lhs,
}

pub struct Parser<'s, 'c, 'e> {
    pub lex: Lexer<'s>,
    peeked: Option<Token<'s>>,
    pub cx: &'c mut Core<'e>,
    pub vars: VarTable<VarEntry<'s>>,
    /// What each LHS variable (by `vars` index) can still hold after the slots it
    /// stood in so far: CLIPS refuses a rule where that is nothing (`[RULECSTR1]`).
    pub var_cstr: VarTable<VarCstr>,
    /// The count of `add_var`s so far (`rhs_types::RuleNotes::var_serial`): a check
    /// noted earlier sees only variables older than it (not those of a `not` read after
    /// it in slots its own ones had).
    #[cfg(feature = "extras")]
    pub var_count: u32,
    /// `not`, `exists` and `forall` CEs around the one being read.
    #[cfg(feature = "extras")]
    pub quant_depth: u8,
    /// The field constraint being read has a multifield part so far: a `=(...)` call
    /// giving a multifield, a `$?x` binding it or a `$?y` term (mixed with a single
    /// part, `field_sf`, it is CLIPS's `[PATTERN2]`).
    #[cfg(feature = "extras")]
    pub field_mf_call: bool,
    /// The field constraint being read has a single-field part so far: a literal, a
    /// `?x` binding it or a `?y` term.
    #[cfg(feature = "extras")]
    pub field_sf: bool,
    /// Inside such a CE: the variables bound before the outermost one (`vars` below
    /// this index, whose records its slots do not narrow); 0 outside.
    pub quant_base: usize,
    /// No CE read yet inside the innermost of them: a test CE there still narrows
    /// `var_test` (CLIPS moves it out of the group).
    #[cfg(feature = "extras")]
    pub quant_first: bool,
    /// While a `[RULECSTR2]` check runs: the variables it sees (`vars` below this index,
    /// added before this count) and its candidates, which keep the types their
    /// variables had as it was read (`rhs_types::RuleNotes::keep_types`).
    #[cfg(feature = "extras")]
    pub lhs_limit: Option<(usize, u32, (usize, usize))>,
    pub nvars: usize,
    pub nlocals: Ix,
    pub scope: Scope,
    /// Construct being parsed, for error messages.
    pub construct: &'static str,
    /// Deffunction being defined (for recursive calls), NONE otherwise.
    pub defining_fn: Ix,
    /// `+j`/`=j` per join of the last defrule (new or shared), for `watch compilations`.
    pub(crate) join_marks: crate::compile::JoinMarks,
    /// Deftemplate of each LHS pattern of the rule being parsed (NONE when unknown),
    /// so `modify ?f` on the RHS can check slots at parse time.
    pub pat_tmpl: [Ix; MAX_PATTERNS],
    /// The deftemplate slot whose LHS constraint is being parsed (None for ordered
    /// facts): literals in it must fit its type and allowed values.
    pub lhs_slot: Option<crate::template::SlotDef>,
    /// Current recursion depth of the reader (see `MAX_NESTING`).
    depth: u16,
    /// Host: the lowest stack address the reader may reach (see `deep_nesting`).
    #[cfg(feature = "grow")]
    stack_floor: usize,
    /// `depth` where the actions of the rule or deffunction being read start: a
    /// `bind` deeper than one level below it is conditional (see `VarEntry`).
    pub body_depth: u16,
    /// Conditional elements of the rule so far, numbered as CLIPS numbers them in its
    /// messages (`CE #N`: patterns and tests in text order, all `or` branches).
    pub ce_count: u8,
    /// The field (1-based) of the ordered pattern whose constraint is being parsed
    /// (0 elsewhere), for CLIPS's `CE #N field #M` in messages.
    pub lhs_field: u8,
    /// Parsing a value evaluated once it is read (a slot's static default, a
    /// defglobal's initial value) or when it runs (a dynamic default): a global no
    /// module of the name sees is read by its name (`[GLOBLDEF1]` when still unseen
    /// as it runs), as CLIPS reads it.
    pub evaluated_now: bool,
    /// `eval`: a construct keyword is read as a function name (CLIPS 6.30's
    /// `[EXPRNPSR3] Missing function declaration for defrule.`), nothing is defined.
    pub commands_only: bool,
    /// Reads of the prompt's variables (`?x`, `$?x`, not a loop's or query's own) seen
    /// with `commands_only`: `eval` refuses them, as CLIPS's `[STRNGFUN2]`.
    pub prompt_reads: u16,
    /// Facts read by `load-facts`: their fields are constants (a call is a syntax error).
    pub constant_facts: bool,
    /// Loop bodies around the expression being read: `break` needs one.
    pub loop_depth: u16,
    /// The last numeric call read whose arguments are all constants and variables
    /// (`NONE` for none; set back for each item: a construct that failed frees its
    /// nodes, a part read again is read alike): as a later argument it prints and
    /// changes nothing (`Parser::order_numeric_args`), known without a look at it.
    pub(crate) quiet_numeric: Ix,
    /// The declarations node of the innermost fact-set query being read (`NONE`
    /// outside one); each such node's `data` names the enclosing query's (set back for
    /// each item, as `quiet_numeric`). `?v:slot` looks up `?v`'s templates there.
    pub(crate) query_decl: Ix,
    /// `check-syntax`: a construct read whole stops before it is defined, with a
    /// [`LoadDetail::Checked`](crate::error::LoadDetail::Checked) "error" (rolled
    /// back: nothing stays, no old construct is replaced); a defglobal's values are not
    /// evaluated.
    pub check_only: bool,
    /// `check_only` mode read an integer beyond 64 bits: CLIPS's `[SCANNER1]` warning,
    /// which `check-syntax` returns instead of printing.
    pub warned_overflow: bool,
    /// CLIPS's specificity of the rule (disjunct) being read (see `rule::Complexity`).
    pub complexity: u16,
    /// Where a failure of the current construct rolls back to when not to its start:
    /// past what its parse-time evaluations created (their effects stay, as in CLIPS).
    pub keep: Option<crate::engine::Checkpoint>,
    /// `declare_bound_vars`: where the search for a local `bind` last began and what
    /// it found there (`Lexer::local_bind_candidate`), valid for any later start up to
    /// that find.
    bind_hint: (usize, usize),
    /// `[PRCCODE3]` for a variable nothing binds, held until the construct is read
    /// whole: CLIPS reports any other error of the construct first.
    pub deferred: Option<LoadError>,
    /// Symbols in use (count, bytes) when the current item last made an implied
    /// template: CLIPS keeps those templates when the item fails (`spare_implied`).
    pub implied_mark: Option<(Ix, Ix)>,
    /// The first rule the current defrule creates (see `compile::Compiler`).
    pub rule_base: Ix,
    /// The current defrule's name when it replaces a rule of that name (else NONE),
    /// and the first alpha node it creates (see `compile::Compiler`).
    pub replacing: SymId,
    pub alpha_base: Ix,
    /// Local `bind`s read so far: CLIPS refuses one in a fact-set query's condition
    /// (`[FACTQPSR2]`).
    pub binds: u16,
    /// The variables (`vars` indices) of the fact-set query whose actions are being
    /// read, and the first `bind` of one of them there (`[FACTQPSR3]`).
    pub query_vars: (usize, usize),
    pub query_rebind: Option<Token<'s>>,
}

pub type PResult<T> = Result<T, LoadError>;

/// The values a pattern variable can hold: the types and the numeric range every slot
/// it stood in allows (`lo`/`hi`: the constant node of the highest minimum and the
/// lowest maximum, NONE for no bound).
#[derive(Clone, Copy)]
pub struct VarCstr {
    pub types: u8,
    pub lo: Ix,
    pub hi: Ix,
}

impl VarCstr {
    pub const ANY: VarCstr = VarCstr {
        types: 0xFF,
        lo: NONE,
        hi: NONE,
    };
}

impl<'s, 'c, 'e> Parser<'s, 'c, 'e> {
    pub fn new(cx: &'c mut Core<'e>, src: &'s str) -> Self {
        Parser {
            lex: Lexer::new(src),
            peeked: None,
            cx,
            #[cfg(not(feature = "grow"))]
            vars: [VarEntry::EMPTY; MAX_VARS],
            #[cfg(feature = "grow")]
            vars: VarTable::new(VarEntry::EMPTY),
            #[cfg(not(feature = "grow"))]
            var_cstr: [VarCstr::ANY; MAX_VARS],
            #[cfg(feature = "grow")]
            var_cstr: VarTable::new(VarCstr::ANY),
            #[cfg(feature = "extras")]
            var_count: 0,
            #[cfg(feature = "extras")]
            quant_depth: 0,
            quant_base: 0,
            #[cfg(feature = "extras")]
            field_mf_call: false,
            #[cfg(feature = "extras")]
            field_sf: false,
            #[cfg(feature = "extras")]
            quant_first: false,
            #[cfg(feature = "extras")]
            lhs_limit: None,
            nvars: 0,
            nlocals: 0,
            scope: Scope::TopLevel,
            construct: "",
            defining_fn: NONE,
            join_marks: crate::compile::JoinMarks::new(),
            pat_tmpl: [NONE; MAX_PATTERNS],
            lhs_slot: None,
            depth: 0,
            #[cfg(feature = "grow")]
            stack_floor: 0,
            body_depth: 0,
            ce_count: 0,
            lhs_field: 0,
            evaluated_now: false,
            commands_only: false,
            prompt_reads: 0,
            constant_facts: false,
            loop_depth: 0,
            quiet_numeric: crate::value::NONE,
            query_decl: crate::value::NONE,
            check_only: false,
            warned_overflow: false,
            complexity: 0,
            rule_base: 0,
            replacing: NONE,
            alpha_base: 0,
            keep: None,
            bind_hint: (usize::MAX, usize::MAX),
            deferred: None,
            implied_mark: None,
            binds: 0,
            query_vars: (0, 0),
            query_rebind: None,
        }
    }

    /// Reader position including a peeked token, for backtracking.
    pub fn save(&self) -> (Lexer<'s>, Option<Token<'s>>) {
        (self.lex.clone(), self.peeked)
    }

    pub fn restore(&mut self, st: (Lexer<'s>, Option<Token<'s>>)) {
        self.lex = st.0;
        self.peeked = st.1;
    }

    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> Token<'s> {
        match self.peeked.take() {
            Some(t) => t,
            None => self.lex.next_token(),
        }
    }

    /// Fails with the error held back for the end of the construct, if any.
    pub fn take_deferred(&mut self) -> PResult<()> {
        match self.deferred.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Byte offset just past what was read (a peeked token is not read): where an
    /// `ERROR:` echo of the text so far ends.
    pub fn consumed_end(&self) -> usize {
        match self.peeked {
            Some(t) => t.start,
            None => self.lex.pos(),
        }
    }

    pub fn peek(&mut self) -> Token<'s> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lex.next_token());
        }
        match self.peeked {
            Some(t) => t,
            None => self.lex.next_token(),
        }
    }

    /// Byte offset where the next token starts (after skipping nothing).
    pub fn offset(&mut self) -> usize {
        self.peek().start
    }

    pub fn err(&self, at: Token<'s>, expected: &'static str) -> LoadError {
        let expected = match at.tok {
            Tok::Eof => INPUT_ENDED,
            Tok::Bad => "a closing '\"' of the string",
            _ => expected,
        };
        LoadError {
            line: at.line,
            col: at.col,
            expected,
            construct: self.construct,
            capacity: None,
            start: at.start as u32,
            end: at.end as u32,
            detail: crate::error::LoadDetail::Syntax,
            // the input ended inside a rule or deffunction: CLIPS shows all of it
            echo_end: if at.tok == Tok::Eof && matches!(self.construct, "defrule" | "deffunction") {
                at.end as u32
            } else {
                0
            },
            echo_tail: crate::error::EchoTail::Normal,
            query_syntax: false,
        }
    }

    /// `check_only` mode's end of a construct read without errors (see
    /// [`Parser::check_only`]).
    pub fn checked(&self, at: Token<'s>) -> LoadError {
        LoadError {
            detail: crate::error::LoadDetail::Checked,
            ..self.err(at, "nothing (the syntax was only checked)")
        }
    }

    /// A construct, CE, declaration or name we do not implement yet: refused where it
    /// stands (`[NOTIMPL1]`, our own message), never accepted and ignored.
    pub fn not_implemented(&self, at: Token<'s>, what: &'static str) -> LoadError {
        LoadError {
            detail: crate::error::LoadDetail::NotImplemented { what },
            ..self.err(at, "something robotino-agent implements")
        }
    }

    /// `[CSTRCPSR3]`: construct `construct` named by token `at` cannot be defined in
    /// the current module because of the imports and exports.
    pub fn import_conflict(&self, at: Token<'s>, construct: &'static str) -> LoadError {
        LoadError {
            detail: crate::error::LoadDetail::ImportConflict { construct },
            ..self.err(at, "a name no module's imports or exports clash with")
        }
    }

    /// `[CSTRCPSR3]` when an implied deftemplate named `sym` (the relation name at
    /// `at`) cannot be made in `module` because of the imports and exports.
    #[cfg(feature = "modules")]
    pub fn implied_conflict(
        &self,
        at: Token<'s>,
        module: crate::module::ModId,
        sym: SymId,
    ) -> PResult<()> {
        if !self
            .cx
            .import_conflict(crate::module::class::TEMPLATE, module, sym)
        {
            return Ok(());
        }
        let mut e = self.err(
            at,
            "a relation name no module's imports or exports clash with",
        );
        e.detail = crate::error::LoadDetail::ImpliedConflict;
        if self.construct != "command" {
            e.echo_end = at.end as u32;
        }
        Err(e)
    }

    /// A name token: one with a module specifier (`MAIN::x`) is refused, as modules are
    /// not implemented.
    pub fn plain_name(&self, at: Token<'s>, name: &'s str) -> PResult<&'s str> {
        if crate::module::qualifier_end(name).is_some() {
            return Err(self.not_implemented(at, "module specifiers (Module::name)"));
        }
        Ok(name)
    }

    /// Without modules: a construct's name, refused with a module specifier.
    #[cfg(not(feature = "modules"))]
    pub(super) fn construct_name(&mut self, at: Token<'s>, name: &'s str) -> PResult<&'s str> {
        self.plain_name(at, name)
    }

    /// Without modules: a name referring to a construct, looked up in MAIN.
    #[cfg(not(feature = "modules"))]
    pub(super) fn qualified_ref(
        &mut self,
        at: Token<'s>,
        name: &'s str,
    ) -> PResult<(crate::module::ModId, &'s str)> {
        Ok((crate::module::MAIN, self.plain_name(at, name)?))
    }

    /// The module constructs are being read into.
    pub(super) fn current_module(&self) -> crate::module::ModId {
        #[cfg(feature = "modules")]
        return self.cx.current_module();
        #[cfg(not(feature = "modules"))]
        crate::module::MAIN
    }

    /// The template named `sym` that module `m` sees (`Core::find_template` for the
    /// current module).
    pub(super) fn template_in(&self, m: crate::module::ModId, sym: SymId) -> Option<Ix> {
        #[cfg(feature = "modules")]
        return self.cx.template_seen_from(sym, m);
        #[cfg(not(feature = "modules"))]
        {
            let _ = m;
            self.cx.find_template(sym)
        }
    }

    pub fn cap_err(&self, at: Token<'s>, c: CapacityError) -> LoadError {
        LoadError {
            capacity: Some(c),
            expected: "room in a pool",
            ..self.err(at, "")
        }
    }

    /// Maps a pool error at the current position. (Called for every expression node
    /// the parser makes: the `Ok` case in line, the error out of it.)
    #[inline(always)]
    pub fn cap_res<T>(&mut self, r: Result<T, CapacityError>) -> PResult<T> {
        match r {
            Ok(v) => Ok(v),
            Err(c) => Err(self.cap_here(c)),
        }
    }

    #[cold]
    #[inline(never)]
    fn cap_here(&mut self, c: CapacityError) -> LoadError {
        let at = self.peek();
        self.cap_err(at, c)
    }

    pub fn expect_lparen(&mut self, what: &'static str) -> PResult<Token<'s>> {
        let t = self.next();
        if t.tok == Tok::LParen {
            Ok(t)
        } else {
            Err(self.err(t, what))
        }
    }

    /// `[CSTRCPSR2]` at `at`: the construct keyword is not followed by a name.
    pub(super) fn missing_name(&self, at: Token<'s>, expected: &'static str) -> LoadError {
        let mut e = self.err(at, expected);
        e.detail = crate::error::LoadDetail::MissingName;
        // (no construct to show at the input's end: CSTRCPSR2 shows what it read)
        e.echo_end = 0;
        e
    }

    pub fn expect_rparen(&mut self, what: &'static str) -> PResult<()> {
        let t = self.next();
        if t.tok == Tok::RParen {
            Ok(())
        } else {
            Err(self.err(t, what))
        }
    }

    pub fn expect_symbol(&mut self, what: &'static str) -> PResult<&'s str> {
        let t = self.next();
        match t.tok {
            Tok::Symbol(s) => Ok(s),
            _ => Err(self.err(t, what)),
        }
    }

    /// Skips one balanced expression (used for `or` branches not taken).
    pub fn skip_balanced(&mut self) -> PResult<()> {
        let t = self.next();
        match t.tok {
            Tok::LParen => {
                let mut depth = 1;
                while depth > 0 {
                    let t = self.next();
                    match t.tok {
                        Tok::LParen => depth += 1,
                        Tok::RParen => depth -= 1,
                        Tok::Eof | Tok::Bad => return Err(self.err(t, "a closing parenthesis")),
                        _ => {}
                    }
                }
                Ok(())
            }
            Tok::RParen | Tok::Eof | Tok::Bad => Err(self.err(t, "an expression")),
            _ => Ok(()),
        }
    }

    /// Runs one recursive step of the reader, refusing input nested deeper than
    /// `MAX_NESTING` (an error at the token where the limit is reached).
    pub fn nested<T>(&mut self, step: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        #[cfg(not(feature = "grow"))]
        if self.depth >= MAX_NESTING {
            let at = self.peek();
            return Err(self.err(at, "at most 200 levels of nesting"));
        }
        // host: the checks from the image's depth on (`deep_nesting`)
        #[cfg(feature = "grow")]
        if self.depth >= MAX_NESTING {
            self.deep_nesting()?;
        }
        self.depth += 1;
        let r = step(self);
        self.depth -= 1;
        r
    }

    /// Host: how deep the reader may go past `MAX_NESTING`. As deep as calls may nest
    /// (`DepthLimits::calls`: an expression nested deeper could not run; 200 unless
    /// the host raised it, as the CLI does), and, when the host bounds the stack
    /// (`DepthLimits::stack_bytes`), no lower than its floor: that of the running
    /// evaluation, if one reads this text (`eval`, `build`, `load`), else the stack
    /// bound below where the reader passed the image's depth. CLIPS 6.30 has no limit
    /// and overflows its stack (near 17,000 levels in an 8 MiB stack).
    #[cfg(feature = "grow")]
    #[cold]
    #[inline(never)]
    fn deep_nesting(&mut self) -> PResult<()> {
        let l = self.cx.st.eval.limits;
        if self.depth >= l.calls.max(MAX_NESTING) {
            let at = self.peek();
            return Err(if l.calls > MAX_NESTING {
                self.err(at, "fewer levels of nesting (the evaluator's call limit)")
            } else {
                self.err(at, "at most 200 levels of nesting")
            });
        }
        self.cx
            .st
            .eval
            .past_image
            .get_or_insert("more than 200 levels of nesting (the image's limit)");
        if l.stack_bytes != 0 {
            let probe = 0u8;
            let here = core::hint::black_box(&probe) as *const u8 as usize;
            if self.depth == MAX_NESTING {
                self.stack_floor = if self.cx.st.eval.eval_depth > 0 {
                    l.floor
                } else {
                    here.saturating_sub(l.stack_bytes)
                };
            } else if here < self.stack_floor {
                let at = self.peek();
                return Err(self.err(at, "fewer levels of nesting (the stack's room)"));
            }
        }
        Ok(())
    }

    pub fn find_var(&self, name: &str) -> Option<VarEntry<'s>> {
        self.vars[..self.nvars]
            .iter()
            .rev()
            .find(|v| v.name == name)
            .copied()
    }

    pub fn add_var(
        &mut self,
        at: Token<'s>,
        name: &'s str,
        kind: VarKind,
        multi: bool,
    ) -> PResult<()> {
        // Hosts (`grow`) have no limit: their tables grow.
        #[cfg(not(feature = "grow"))]
        if self.nvars >= MAX_VARS {
            return Err(self.err(at, "fewer variables in one construct"));
        }
        #[cfg(feature = "grow")]
        let _ = at;
        #[cfg(feature = "grow")]
        if self.nvars >= IMAGE_MAX_VARS {
            self.cx
                .st
                .eval
                .past_image
                .get_or_insert("a construct of more than 64 variables (the image's limit)");
        }
        self.vars[self.nvars] = VarEntry {
            name,
            kind,
            multi,
            unbound_name: NONE,
            rebound: NONE,
        };
        self.var_cstr[self.nvars] = VarCstr::ANY;
        #[cfg(feature = "extras")]
        {
            self.cx.st.rule_notes.var_lit[self.nvars] = 0xFF;
            self.cx.st.rule_notes.var_serial[self.nvars] = self.var_count;
            self.cx.st.rule_notes.var_test[self.nvars] = 0xFF;
            self.cx.st.rule_notes.var_val[self.nvars] = None;
            self.var_count = self.var_count.wrapping_add(1);
        }
        self.nvars += 1;
        Ok(())
    }

    /// Reads the actions of a rule or deffunction (`body_depth` is where they start).
    pub fn body_block(&mut self) -> PResult<Ix> {
        self.body_depth = self.depth;
        let p = self.builtin_call("progn")?;
        self.args_until_rparen(p)?;
        // CLIPS checks the actions once all are read, and shows the whole construct
        #[cfg(feature = "extras")]
        if let Err(mut e) = self.refuse_expansions(p, "progn") {
            if let crate::error::LoadDetail::SequenceOperator { func, .. } = e.detail {
                e.detail = crate::error::LoadDetail::SequenceOperator { func, whole: true };
                e.start = e.echo_end.saturating_sub(1);
                e.end = e.echo_end;
                e.echo_end = 0;
            }
            return Err(e);
        }
        Ok(p)
    }

    /// Gives each variable that a `bind` in the actions ahead names its frame slot:
    /// an LHS variable its `VarEntry::rebound`, a new name a local that may be read
    /// unbound. CLIPS decides it from the whole of the actions, so a read earlier in
    /// the text (in a loop body, say) sees the new value. Reads the tokens up to the
    /// construct's closing `)` and goes back.
    pub fn declare_bound_vars(&mut self) -> PResult<()> {
        // most actions bind nothing: a scan of the bytes says so
        let from = self.peeked.map_or(self.lex.pos(), |t| t.start);
        // and most sources have no local `bind` ahead at all: a text search, kept for
        // the constructs after this one, says so without the scan
        let (at, hint) = self.bind_hint;
        let hint = if at <= from && hint >= from {
            hint
        } else {
            let h = self.lex.local_bind_candidate(from);
            self.bind_hint = (from, h);
            h
        };
        if hint == usize::MAX || !self.lex.binds_a_local_before_close(from) {
            return Ok(());
        }
        let save = self.save();
        let mut depth = 0u32;
        // 1 after `(`, 2 after `(bind`
        let mut seen = 0u8;
        loop {
            let t = self.next();
            let prev = seen;
            seen = 0;
            match t.tok {
                Tok::LParen => {
                    depth += 1;
                    seen = 1;
                }
                Tok::RParen if depth == 0 => break,
                Tok::RParen => depth -= 1,
                Tok::Eof | Tok::Bad => break,
                Tok::Symbol("bind") if prev == 1 => seen = 2,
                Tok::SfVar(name) | Tok::MfVar(name) if prev == 2 => {
                    let found = self.vars[..self.nvars].iter().rposition(|v| v.name == name);
                    match found {
                        Some(i) => {
                            let v = self.vars[i];
                            if matches!(v.kind, VarKind::Pat { .. }) && v.rebound == NONE {
                                if self.nlocals >= 255 {
                                    self.restore(save);
                                    let at = self.peek();
                                    return Err(self
                                        .err(at, "at most 255 local variables in one construct"));
                                }
                                self.vars[i].rebound = self.nlocals;
                                self.nlocals += 1;
                            }
                        }
                        // a local the actions bind: known from the start, a read while
                        // unbound (earlier in the text, or in a loop) a run-time error
                        None => {
                            let r = self.new_local(t, name, false).and_then(|_| {
                                let sym = cap!(self, self.cx.intern(name))?;
                                self.vars[self.nvars - 1].unbound_name = sym;
                                Ok(())
                            });
                            if let Err(e) = r {
                                self.restore(save);
                                return Err(e);
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        self.restore(save);
        Ok(())
    }

    /// Whether the reader is inside a condition or loop of the current actions.
    pub fn in_nested_action(&self) -> bool {
        self.depth > self.body_depth + 1
    }

    /// A new frame local for `name`.
    pub fn new_local(&mut self, at: Token<'s>, name: &'s str, multi: bool) -> PResult<Ix> {
        let slot = self.nlocals;
        // a frame's size is a u8 (`Rule::nlocals`, `Deffunction::nlocals`)
        if slot >= 255 {
            return Err(self.err(at, "at most 255 local variables in one construct"));
        }
        self.nlocals += 1;
        self.add_var(at, name, VarKind::Local(slot), multi)?;
        Ok(slot)
    }
}

/// One top-level item read from source text.
pub enum Item {
    /// A construct was defined.
    Construct,
    /// A command/expression to evaluate: its root expression node.
    Command(Ix),
    /// End of input.
    End,
}

impl<'s, 'e> Parser<'s, '_, 'e> {
    /// Reads the next construct or command. Constructs are built right away (rolled
    /// back on error); commands are returned for the caller to evaluate.
    pub fn next_item(&mut self) -> PResult<Item> {
        // (a construct that failed may leave it set)
        self.evaluated_now = false;
        self.loop_depth = 0;
        self.quiet_numeric = NONE;
        self.query_decl = NONE;
        self.implied_mark = None;
        let t = self.peek();
        match t.tok {
            Tok::Eof => Ok(Item::End),
            Tok::LParen => {
                let save_lex = self.save();
                self.next();
                let head = self.peek();
                let kw = match head.tok {
                    Tok::Symbol(s) => s,
                    _ => "",
                };
                let kw: &'static str = match kw {
                    _ if self.commands_only => "",
                    "deftemplate" => "deftemplate",
                    "defrule" => "defrule",
                    "deffacts" => "deffacts",
                    "deffunction" => "deffunction",
                    "defglobal" => "defglobal",
                    "defmodule" => "defmodule",
                    _ => "",
                };
                match kw {
                    "deftemplate" | "defrule" | "deffacts" | "deffunction" | "defglobal"
                    | "defmodule" => {
                        let kt = self.next();
                        if self.cx.st.mode.defining {
                            // CLIPS 6.30 crashes on this one
                            self.construct = kw;
                            return Err(
                                self.err(kt, "a construct outside another one's definition")
                            );
                        }
                        let start = t.start;
                        let cp = self.cx.checkpoint();
                        self.keep = None;
                        self.replacing = NONE;
                        self.cx.st.mode.defining = true;
                        self.deferred = None;
                        let r = self.construct_body(kw, start);
                        // (each construct takes its deferred error before it commits;
                        // one left here means nothing may stay of the construct)
                        let r = match (r, self.deferred.take()) {
                            (Ok(()), Some(e)) => Err(e),
                            (r, _) => r,
                        };
                        self.cx.st.mode.defining = false;
                        if let Err(e) = &r {
                            let cp = self.keep.unwrap_or(cp);
                            let cp = self.spare_implied(cp, e);
                            self.cx.rollback(cp);
                            if self.replacing != NONE && !self.check_only {
                                match kw {
                                    "defrule" => self.drop_replaced_rule(),
                                    _ => self.drop_replaced(kw),
                                }
                            }
                        }
                        r.map(|_| Item::Construct)
                    }
                    _ => {
                        // a command: re-read it as an expression from the '('
                        self.restore(save_lex);
                        self.scope = Scope::TopLevel;
                        self.construct = "command";
                        let instance_name = matches!(head.tok, Tok::Symbol(s)
                            if crate::value::instance_name_body(s).is_some());
                        if instance_name
                            || !matches!(head.tok, Tok::Symbol(_) | Tok::Eof | Tok::Bad)
                        {
                            // CLIPS's command loop: `(` and no function name (an
                            // instance name `[x]` is none)
                            let mut e = self.err(head, "a function name");
                            e.detail = crate::error::LoadDetail::ExpectedCommand;
                            return Err(e);
                        }
                        let cp = self.cx.checkpoint();
                        match self.parse_expr() {
                            Ok(e) => Ok(Item::Command(e)),
                            Err(err) => {
                                let cp = self.spare_implied(cp, &err);
                                self.cx.rollback(cp);
                                Err(err)
                            }
                        }
                    }
                }
            }
            _ => {
                self.scope = Scope::TopLevel;
                self.construct = "command";
                // (`$?*g*` too, though `$?x` is read)
                let mf_global = matches!(t.tok, Tok::MfVar(n)
                    if !self.commands_only && n.len() > 1 && n.starts_with('*') && n.ends_with('*'));
                if mf_global
                    || matches!(
                        t.tok,
                        Tok::RParen | Tok::Amp | Tok::Bar | Tok::Tilde | Tok::SfWild | Tok::MfWild
                    )
                {
                    // CLIPS's command loop takes only a `(`, a constant or a variable
                    self.next();
                    let mut e = self.err(t, "'(', a constant or a variable");
                    e.detail = crate::error::LoadDetail::NotACommand;
                    return Err(e);
                }
                let e = self.parse_expr()?;
                Ok(Item::Command(e))
            }
        }
    }

    /// A defrule that failed after its name was read: CLIPS 6.30 has removed the rule
    /// of that name by then, so it is gone (unless a test in the network is running,
    /// when the network may not change).
    #[inline(never)]
    fn drop_replaced_rule(&mut self) {
        let name = self.replacing;
        if self.cx.st.net.matching > 0 || self.cx.network_writable().is_err() {
            return;
        }
        if let Some(r) = (0..self.cx.st.pools.nrules).find(|&r| self.cx.rule_here(r, name)) {
            #[cfg(feature = "extras")]
            self.cx.watch_forget(crate::engine::watch::RULES, r, name);
            self.cx.remove_rule(r);
            #[cfg(feature = "extras")]
            self.cx.st.breaks.remove(name);
        }
    }

    /// A deftemplate, deffacts or deffunction that failed after its name was read:
    /// CLIPS 6.30 has removed the one of that name by then (a deftemplate in use was
    /// refused before), except a deffunction another construct calls, which stays.
    #[inline(never)]
    fn drop_replaced(&mut self, kw: &str) {
        let name = self.replacing;
        match kw {
            "deftemplate" => {
                let Some(t) = self.cx.find_template(name) else {
                    return;
                };
                if self.cx.template_in_use(t) || self.cx.network_writable().is_err() {
                    return;
                }
                #[cfg(feature = "extras")]
                self.cx.watch_forget(crate::engine::watch::FACTS, t, name);
                self.cx.retire_template(t);
            }
            "deffacts" => {
                let n = self.cx.st.pools.ndeffacts as usize;
                let Some(d) = (0..n)
                    .find(|&d| self.cx.deffacts[d].name == name && self.deffacts_here(d as Ix))
                else {
                    return;
                };
                // the later ones move up: `reset` asserts in definition order
                self.cx.deffacts.copy_within(d + 1..n, d);
                #[cfg(feature = "modules")]
                if n <= self.cx.deffacts_module.len() {
                    self.cx.deffacts_module.copy_within(d + 1..n, d);
                }
                self.cx.st.pools.ndeffacts -= 1;
            }
            _ => {
                let n = self.cx.st.pools.nfuncs;
                let Some(f) = (0..n)
                    .find(|&f| self.cx.funcs[f as usize].name == name && self.function_here(f))
                else {
                    return;
                };
                if self.cx.st.eval.in_use > 0 {
                    return;
                }
                if self.cx.deffunction_in_use(f, false) {
                    // CLIPS keeps it (its parameters) but has freed its actions by
                    // then, and its text: calls return FALSE, `save` leaves it out
                    self.cx.funcs[f as usize].body = NONE;
                    #[cfg(feature = "extras")]
                    self.cx.set_function_text(f, NONE);
                    return;
                }
                #[cfg(feature = "extras")]
                self.cx
                    .watch_forget(crate::engine::watch::DEFFUNCTIONS, f, name);
                self.cx.funcs[f as usize].name = NONE;
            }
        }
    }

    /// Notes that an implied template was just made (see `implied_mark`).
    pub(crate) fn note_implied(&mut self) {
        self.implied_mark = Some((self.cx.st.pools.nsyms, self.cx.st.pools.sym_bytes));
    }

    /// Where a failed item rolls back to instead of `cp`: past the implied templates
    /// it made (the run of them right after `cp`), their slots and names, which CLIPS
    /// keeps (`list-deftemplates` shows them); `check-syntax` keeps nothing, nor an
    /// item that found a pool full (it leaves the engine as it was).
    fn spare_implied(
        &self,
        mut cp: crate::engine::Checkpoint,
        err: &LoadError,
    ) -> crate::engine::Checkpoint {
        let Some((nsyms, sym_bytes)) = self.implied_mark else {
            return cp;
        };
        if self.check_only || err.capacity.is_some() {
            return cp;
        }
        let mut t = cp.ntemplates;
        while t < self.cx.st.pools.ntemplates && self.cx.templates[t as usize].implied {
            let tm = self.cx.templates[t as usize];
            cp.nslots = cp.nslots.max(tm.first_slot + tm.nslots);
            t += 1;
        }
        if t > cp.ntemplates {
            cp.ntemplates = t;
            cp.nsyms = cp.nsyms.max(nsyms);
            cp.sym_bytes = cp.sym_bytes.max(sym_bytes);
        }
        cp
    }

    /// Evaluates a parse-time expression (salience, a global's value). Facts it
    /// asserts and globals it sets stay, as in CLIPS, and may use what the construct
    /// created so far (symbols, the implied template of `(assert (new 1))` made while
    /// parsing the call): should the construct fail, that stays too.
    pub fn eval_now(&mut self, e: Ix) -> Result<crate::value::Value, crate::error::EvalError> {
        let effects = self.cx.st.eval.effects;
        let halting = self.cx.st.mode.halting;
        let mut r = self.cx.eval(e);
        if self.cx.st.eval.effects != effects {
            self.keep = Some(self.cx.checkpoint());
        }
        // CLIPS's evaluation error (an unbound global read as FALSE, already
        // reported) fails the value even where the evaluation went on
        if self.cx.st.mode.halting && !halting {
            self.cx.st.mode.halting = false;
            if r.is_ok() {
                r = Err(crate::error::EvalError::already_reported());
            }
        }
        r
    }

    /// The compile stage for the defrule being read: the pools, and what the reader
    /// knows of the rule it replaces.
    pub(crate) fn compiler(&mut self) -> crate::compile::Compiler<'_, 'e> {
        crate::compile::Compiler {
            cx: &mut *self.cx,
            rule_base: self.rule_base,
            alpha_base: self.alpha_base,
            replacing: self.replacing,
            marks: &mut self.join_marks,
        }
    }

    /// A compile error placed in the text: at the CE it names, else where the reader
    /// stopped.
    pub(crate) fn compile_err(&mut self, e: crate::compile::CompileError) -> LoadError {
        let at = match e.at {
            Some(at) => self.lex.token_at(at as usize),
            None => self.peek(),
        };
        self.cap_err(at, e.capacity)
    }

    fn construct_body(&mut self, kw: &'static str, start: usize) -> PResult<()> {
        self.join_marks.clear();
        self.pat_tmpl = [NONE; MAX_PATTERNS];
        self.nvars = 0;
        self.nlocals = 0;
        self.construct = kw;
        match kw {
            "deftemplate" => self.deftemplate(start),
            "defrule" => self.defrule(start),
            "deffacts" => self.deffacts(start),
            "deffunction" => self.deffunction(start),
            "defglobal" => self.defglobal(),
            #[cfg(feature = "modules")]
            _ => self.defmodule(start),
            #[cfg(not(feature = "modules"))]
            _ => {
                let at = self.peek();
                Err(self.not_implemented(at, "defmodule"))
            }
        }
    }
}
