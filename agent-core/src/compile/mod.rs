//! The compile stage: analysis and network building. What the syntax stage read
//! (`parser::rule`: a rule's conditional elements as a `Build`, each pattern as a
//! `PatBuild`, tests and actions as expression nodes) becomes alpha nodes ([`alpha`]:
//! sharing and discrimination) and joins ([`join`]: sharing of identical prefixes,
//! the rule, priming of new joins); [`remove`] takes them out again (rule removal, the
//! undo of a construct that failed halfway). Still to move here: the syntax stage's
//! calls of `find_or_make_alpha` while it reads a pattern (the alpha nodes are built
//! before the rule's form is whole).

pub(crate) mod alpha;
pub(crate) mod join;
pub(crate) mod remove;
