//! Rule text for the agent image: comments (and constructs' comment strings) gone,
//! whitespace runs collapsed, at compile
//! time (`const fn`). The robot never prints its rule files, and a fifth of their
//! bytes are comments and indentation: some 13 KB of the image's code budget.
//!
//! CLIPS reads the result as it reads the original: `;` starts a comment only outside a
//! string, whitespace only separates tokens, and `(` `)` end a token by themselves, so
//! the whitespace next to them separates nothing. Strings are copied as they are
//! (escapes included). The tests load both forms and compare what the engine built.

/// Whitespace between tokens.
const fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r')
}

/// True if `src[from..to]` is one of the constructs whose name may be followed by a
/// comment string (CLIPS 6.30: defrule, deffunction, deftemplate, deffacts, defmodule,
/// defgeneric).
const fn is_commented_construct(src: &[u8], from: usize, to: usize) -> bool {
    const NAMES: [&[u8]; 6] = [
        b"defrule",
        b"deffunction",
        b"deftemplate",
        b"deffacts",
        b"defmodule",
        b"defgeneric",
    ];
    let mut k = 0;
    while k < NAMES.len() {
        let name = NAMES[k];
        if name.len() == to - from {
            let mut same = true;
            let mut i = 0;
            while i < name.len() {
                if name[i] != src[from + i] {
                    same = false;
                }
                i += 1;
            }
            if same {
                return true;
            }
        }
        k += 1;
    }
    false
}

/// Where a construct's comment string may come: nothing to drop; after a top-level `(`; after the
/// construct keyword (the name comes next); after the name (a string here is the
/// construct's comment, which the engine skips: it is dropped).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Doc {
    None,
    Open,
    Keyword,
    Name,
}

/// Runs the minifier over `src`, writing into `out` as far as it is long; returns the
/// minified length either way (an empty `out` measures).
const fn run(src: &[u8], out: &mut [u8]) -> usize {
    let mut n = 0;
    let mut i = 0;
    // the last byte written, and whether a separating space is owed before the next
    let mut last = b'(';
    let mut space = false;
    let mut doc = Doc::None;
    // parentheses open: a construct starts at depth 0
    let mut depth = 0usize;
    while i < src.len() {
        let b = src[i];
        if is_space(b) {
            space = true;
            i += 1;
            continue;
        }
        if b == b';' {
            while i < src.len() && src[i] != b'\n' {
                i += 1;
            }
            space = true;
            continue;
        }
        // a token: a string whole, escapes and all, up to its closing quote; a
        // parenthesis; or a symbol, number or variable up to the next delimiter
        let end = if b == b'"' {
            let mut j = i + 1;
            while j < src.len() && src[j] != b'"' {
                if src[j] == b'\\' {
                    j += 1;
                }
                j += 1;
            }
            if j < src.len() {
                j + 1
            } else {
                src.len()
            }
        } else if b == b'(' || b == b')' {
            i + 1
        } else {
            let mut j = i + 1;
            while j < src.len() && !is_space(src[j]) && !matches!(src[j], b'(' | b')' | b'"' | b';')
            {
                j += 1;
            }
            j
        };
        // a construct's comment string: the engine skips it, the robot never prints it
        if b == b'"' && matches!(doc, Doc::Name) {
            doc = Doc::None;
            space = true;
            i = end;
            continue;
        }
        doc = match b {
            b'(' if depth == 0 => Doc::Open,
            b'(' => Doc::None,
            b')' | b'"' => Doc::None,
            _ => match doc {
                Doc::Open if is_commented_construct(src, i, end) => Doc::Keyword,
                Doc::Keyword => Doc::Name,
                _ => Doc::None,
            },
        };
        if b == b'(' {
            depth += 1;
        } else if b == b')' {
            depth = depth.saturating_sub(1);
        }
        // a space only between two tokens neither of which is a parenthesis
        if space && b != b'(' && b != b')' && last != b'(' && last != b')' {
            if n < out.len() {
                out[n] = b' ';
            }
            n += 1;
        }
        space = false;
        while i < end {
            if n < out.len() {
                out[n] = src[i];
            }
            last = src[i];
            n += 1;
            i += 1;
        }
    }
    n
}

/// Length of `src` minified.
pub const fn minified_len(src: &str) -> usize {
    run(src.as_bytes(), &mut [])
}

/// `src` minified into exactly `N` bytes (`N` from [`minified_len`]).
pub const fn minify<const N: usize>(src: &str) -> [u8; N] {
    let mut out = [0u8; N];
    let n = run(src.as_bytes(), &mut out);
    assert!(n == N, "minify: length differs from minified_len");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `src` minified, as text.
    fn min(src: &str, out: &mut [u8; 256]) -> usize {
        let n = run(src.as_bytes(), out);
        assert_eq!(n, minified_len(src));
        n
    }

    #[test]
    fn comments_go_and_whitespace_separates_tokens_once() {
        let cases: [(&str, &str); 9] = [
            ("(a b)  ; note\n  (c\t d )", "(a b)(c d)"),
            (
                ";;; head\n(defrule r\n  (x ?y&:(> ?y 1))\n  =>)\n",
                "(defrule r(x ?y&:(> ?y 1))=>)",
            ),
            ("(printout t \"a ; b\" crlf)", "(printout t \"a ; b\" crlf)"),
            (
                "(p \"say \\\"hi\\\"  ; x\" y) ; tail",
                "(p \"say \\\"hi\\\"  ; x\" y)",
            ),
            ("  x   y  ", "x y"),
            ("(f \"doc\nstring\" ?a)", "(f \"doc\nstring\" ?a)"),
            // a construct's comment goes; other strings stay
            (
                "(defrule r \"why\" (a \"x\") => (printout t \"y\"))",
                "(defrule r(a \"x\")=>(printout t \"y\"))",
            ),
            (
                "(deffunction f \"doc\" (?x) ?x)(deftemplate t \"d\" (slot s))",
                "(deffunction f(?x)?x)(deftemplate t(slot s))",
            ),
            (
                "(assert (defrule x \"kept\"))",
                "(assert(defrule x \"kept\"))",
            ),
        ];
        for (src, want) in cases {
            let mut out = [0u8; 256];
            let n = min(src, &mut out);
            assert_eq!(core::str::from_utf8(&out[..n]), Ok(want), "{src:?}");
        }
    }

    #[test]
    fn the_exact_buffer_holds_it_all() {
        const SRC: &str = "(a  b) ; c\n(d)";
        const N: usize = minified_len(SRC);
        const OUT: [u8; N] = minify::<N>(SRC);
        assert_eq!(&OUT, b"(a b)(d)");
    }
}
