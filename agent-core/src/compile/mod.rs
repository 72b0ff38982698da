//! The compile stage: analysis and network building. What the syntax stage read
//! (`parser::rule`: a rule's conditional elements as a `Build`, each pattern's form as
//! a `PatIr`, tests and actions as expression nodes), once whole, becomes alpha nodes
//! ([`alpha`]: sharing and discrimination) and joins ([`join`]: sharing of identical
//! prefixes, the rule, hooking up new joins), [`prime`] (the root join; new joins and
//! alpha nodes matched against what exists); [`remove`] takes them out
//! again (rule removal, the undo of a build that ran out of room). A defrule is built
//! by a [`Compiler`]: the pools and what the parser knows of the rule, no lexer; its
//! errors ([`CompileError`]) name the CE, which the parser places in the text.

pub(crate) mod alpha;
pub(crate) mod join;
pub(crate) mod prime;
pub(crate) mod remove;

use crate::engine::Core;
use crate::error::CapacityError;
use crate::value::{Ix, SymId};

/// The compile stage at work on one defrule: the pools it edits (the engine's
/// [`Core`]) and what it needs to know of the defrule besides its form (a `Build`
/// the syntax stage read whole, handed to [`Compiler::compile_disjunct`]): where the
/// rules and alpha nodes it creates start, and which rule it replaces. Holds no
/// lexer and no parser: what it reports is a [`CompileError`], placed in the text by
/// the caller.
pub(crate) struct Compiler<'a, 'e> {
    pub(crate) cx: &'a mut Core<'e>,
    /// The first rule this defrule creates: rules before it with its name are the
    /// definition it replaces.
    pub(crate) rule_base: Ix,
    /// The first alpha node it creates, and its name when it replaces a rule of that
    /// name (else NONE): see `Compiler::old_only_alpha`.
    pub(crate) alpha_base: Ix,
    pub(crate) replacing: SymId,
    /// `+j`/`=j` per join built (new or shared), for `watch compilations`.
    pub(crate) marks: &'a mut JoinMarks,
}

/// A build that ran out of room: the pool, and where the CE whose node did not fit
/// starts in the text (`None`: the rule as a whole, placed where the reader stopped).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CompileError {
    pub(crate) capacity: CapacityError,
    pub(crate) at: Option<u32>,
}

/// `+` (new) or `=` (shared) per join of the last defrule, for `watch compilations`,
/// and `\n` between the joins of two disjuncts.
pub struct JoinMarks {
    marks: [u8; 64],
    n: usize,
}

impl JoinMarks {
    pub const fn new() -> JoinMarks {
        JoinMarks {
            marks: [0; 64],
            n: 0,
        }
    }

    pub fn clear(&mut self) {
        self.n = 0;
    }

    /// Notes one join (marks past the 64th are dropped: the trace is a summary).
    pub fn push(&mut self, shared: bool) {
        if self.n < self.marks.len() {
            self.marks[self.n] = if shared { b'=' } else { b'+' };
            self.n += 1;
        }
    }

    /// Notes the start of the next disjunct of an `or` rule: CLIPS prints each
    /// disjunct's marks on a line of its own.
    pub fn push_break(&mut self) {
        if self.n < self.marks.len() {
            self.marks[self.n] = b'\n';
            self.n += 1;
        }
    }

    pub fn as_slice(&self) -> &[u8] {
        &self.marks[..self.n]
    }
}

impl Default for JoinMarks {
    fn default() -> Self {
        JoinMarks::new()
    }
}

impl Core<'_> {
    /// Makes the network's topology and the constructs it hangs off editable: a
    /// compiled rule base's alpha nodes, joins, templates, slot definitions and rules
    /// read in place (feature `in-place`, `rom`) are copied into the arena first (ids
    /// unchanged), so that rules can be added and removed as in an engine that parsed
    /// them. Every write to an entry that may be compiled (a rule built or removed, a
    /// template redefined or removed, a salience evaluated again) calls this first. An
    /// arena without room for the copy is a capacity error and the engine stays as it
    /// was (an image sized for its compiled rule base cannot take new rules).
    pub(crate) fn network_writable(&mut self) -> Result<(), CapacityError> {
        #[cfg(feature = "in-place")]
        {
            use crate::engine::cap;
            use crate::error::Pool;
            // every pool read in place: its field (in `Core` and `Rom`), the pool,
            // its entries in use
            macro_rules! each_in_place_pool {
                ($do:ident) => {
                    $do!(joins, Joins, njoins);
                    $do!(alphas, AlphaNodes, nalpha);
                    $do!(templates, Templates, ntemplates);
                    $do!(slots, SlotDefs, nslots);
                    $do!(rules, Rules, nrules);
                };
            }
            // all or nothing: every copy is checked before the first
            macro_rules! check_room {
                ($field:ident, $pool:ident, $used:ident) => {
                    if !self.$field.fits_in_ram(self.st.pools.$used as usize) {
                        return Err(cap(Pool::$pool, self.$field.ram().len()));
                    }
                };
            }
            each_in_place_pool!(check_room);
            // (each copy has room: checked above; the state follows each one)
            macro_rules! copy_to_ram {
                ($field:ident, $pool:ident, $used:ident) => {
                    self.$field
                        .copy_rom_to_ram(self.st.pools.$used as usize)
                        .map_err(|size| cap(Pool::$pool, size))?;
                    self.st.rom.$field = &[];
                };
            }
            each_in_place_pool!(copy_to_ram);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::host::NullHost;

    /// A rule the syntax stage refuses never reaches the network: not even in an `or`
    /// whose first disjunct is sound (the pattern-network ids a built alpha node
    /// takes are never given back, so they show whether one was built and undone).
    #[test]
    fn a_rule_that_fails_to_read_builds_nothing() {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let h = &mut NullHost;
        e.load_str(
            h,
            "t",
            "(deftemplate p (slot x)) (defrule old (p (x 1)) =>)",
        )
        .unwrap();
        e.assert_str(h, "(p (x 2))").unwrap();
        let before = |e: &mut SmallEngine| {
            let mut h = NullHost;
            let c = e.core(&mut h);
            (
                c.st.pools.nalpha,
                c.st.pools.njoins,
                c.st.pools.nrules,
                c.st.pools.trie_ids,
                c.st.pools.nexprs,
            )
        };
        let b = before(&mut e);
        for bad in [
            "(defrule r (p (x 2)) (or (q ?y) (s ?y (t))) =>)",
            "(defrule r (p (x ?x)) (q ?x) => (printout t ?x) (",
            "(defrule r (or (p (x 3)) (p (x 4))) (q 1) => (bind))",
            "(defrule old (p (x 5)) (r =>)",
        ] {
            assert!(e.load_str(h, "t", bad).is_err(), "{bad}");
            assert_eq!(before(&mut e), b, "{bad}");
        }
        // an `or` rule that reads: every disjunct built and primed
        e.load_str(h, "t", "(defrule r (or (p (x 2)) (p (x 3))) =>)")
            .unwrap();
        assert_eq!(e.run(h, None).unwrap(), 1);
    }

    /// A pool that runs out while the network is built names the place of the pattern
    /// whose node did not fit, as when nodes were built while reading.
    #[test]
    fn a_full_alpha_pool_names_the_pattern() {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let h = &mut NullHost;
        let room = e.stats().get(crate::Pool::AlphaNodes).1 as usize;
        let mut text = std::string::String::new();
        for i in 0..room - 1 {
            if i % 8 == 0 {
                text.push_str(&std::format!("(defrule r{i} "));
            }
            text.push_str(&std::format!("(p {i}) "));
            if i % 8 == 7 || i == room - 2 {
                text.push_str("=>)\n");
            }
        }
        e.load_str(h, "t", &text).unwrap();
        let err = e
            .load_str(h, "t", "(defrule full\n  (p 0)\n  (p x) (q é) (p y)\n =>)")
            .unwrap_err();
        assert_eq!(err.capacity.map(|c| c.pool), Some(crate::Pool::AlphaNodes));
        // `(p 0)` shares a node, `(p x)` takes the last one, `(q é)` finds none
        assert_eq!((err.line, err.col), (3, 10));
        assert_eq!(err.end - err.start, 1);
    }
}
