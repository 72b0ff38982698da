//! What must not be in the agent image: the image loads its rule base compiled ahead of
//! time and asserts its facts through the API, so the text side of the engine (lexer,
//! parser, the builtins that parse at run time) and the float parsing only they need are
//! dead code there. The linker drops them as long as nothing reaches them; this check
//! keeps it so, from the image's symbol table (`nm -C`).

/// Demangled symbol-name parts that mark the text side of the engine.
pub const FORBIDDEN: [(&str, &str); 4] = [
    ("agent_core::lexer::", "the lexer"),
    ("agent_core::parser::", "the parser"),
    (
        "agent_core::builtins::evaluate::",
        "the builtins that parse text at run time",
    ),
    (
        "core::num::dec2flt::",
        "float parsing (used only by the lexer)",
    ),
];

/// A symbol the image must not carry, and why.
#[derive(Debug, PartialEq, Eq)]
pub struct Finding {
    pub symbol: String,
    pub what: &'static str,
}

/// The forbidden symbols in an `nm -C` listing (`ADDRESS TYPE NAME` lines).
pub fn scan(nm_listing: &str) -> Vec<Finding> {
    nm_listing
        .lines()
        .filter_map(|line| {
            let name = line.splitn(3, ' ').nth(2)?;
            let (_, what) = FORBIDDEN.iter().find(|(part, _)| name.contains(part))?;
            Some(Finding {
                symbol: name.to_string(),
                what,
            })
        })
        .collect()
}

/// How many symbols the listing names: zero means there was nothing to check (a
/// stripped image), which must not pass as clean.
pub fn symbol_count(nm_listing: &str) -> usize {
    nm_listing
        .lines()
        .filter(|line| line.splitn(3, ' ').nth(2).is_some())
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_text_side_and_nothing_else() {
        let listing = "\
0042bd09 t agent_core::lexer::Lexer::next_token
0045cc60 t core::num::dec2flt::lemire::compute_float::<f64>
00401000 T agent_core::rete::beta::left_activate
00402000 t agent_core::parser::rule::Parser::rule
00403000 t <agent_core::builtins::evaluate::Eval>::call
00404000 t core::fmt::write
";
        let found = scan(listing);
        let whats: Vec<&str> = found.iter().map(|f| f.what).collect();
        assert_eq!(
            whats,
            [
                "the lexer",
                "float parsing (used only by the lexer)",
                "the parser",
                "the builtins that parse text at run time"
            ]
        );
        assert_eq!(symbol_count(listing), 6);
        assert_eq!(symbol_count(""), 0);
    }
}
