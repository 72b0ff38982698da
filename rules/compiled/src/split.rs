//! Splits a CLIPS program into its top-level forms and tells constructs from commands.
//! Shared (`#[path]`) by `build.rs`, which compiles a program's constructs, and the
//! tests, which parse the same constructs and run the same commands.

/// The top-level forms of `text` (comments and blanks before each dropped), in order.
pub fn forms(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(n) = agent_core::commands::command_complete(rest) {
        let mut form = &rest[..n];
        loop {
            form = form.trim_start();
            match form.strip_prefix(';') {
                Some(comment) => form = comment.split_once('\n').map_or("", |(_, r)| r),
                None => break,
            }
        }
        if !form.is_empty() {
            out.push(form);
        }
        rest = &rest[n..];
    }
    out
}

/// Whether a form defines a construct (`(deftemplate ...`, `(defrule ...`, ...).
pub fn is_construct(form: &str) -> bool {
    form.strip_prefix('(')
        .is_some_and(|f| f.trim_start().starts_with("def"))
}
