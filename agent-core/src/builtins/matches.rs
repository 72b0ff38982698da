//! `(matches rule [verbose|succinct|terse])`: CLIPS 6.30's listing of a rule's alpha
//! matches per pattern, its partial matches per join, and its activations.
//!
//! CLIPS walks each disjunct's joins from the last one up: a join from the right (a
//! `not`/`exists`/`forall` over several CEs) is left through its right input, whose
//! subnetwork already starts from the CEs before the group; any other join through its
//! left input. Patterns are numbered in that walk, first join first. Each join's
//! partial matches are then listed (all but the first), headed by the CEs they cover:
//! `1 - 3` for a plain chain, and, once groups are involved, each CE with the patterns
//! it spans, `1 (P1) , 2 (P2 - P4)`.

use super::Args;
use crate::engine::Core;
use crate::error::EvalError;
use crate::handle::{JoinId, TokenId};
use crate::host::router;
use crate::rete::{JoinKind, MAX_PATTERNS};
use crate::value::{Ix, TextBuf, Value, NONE};
use core::fmt::Write;

/// How much `matches` prints (its optional second argument).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Detail {
    Verbose,
    Succinct,
    Terse,
}

/// Most joins one disjunct's walk visits (its CEs and the group joins).
const MAX_WALK: usize = MAX_PATTERNS + 2;

/// One join of the walk: the CE it ends counted along its left inputs, and the
/// patterns that CE spans (one for a pattern's join, several for a group).
#[derive(Clone, Copy)]
struct JoinInfo {
    join: JoinId,
    ce: u16,
    begin: u16,
    end: u16,
}

const NO_INFO: JoinInfo = JoinInfo {
    join: JoinId::NONE,
    ce: 0,
    begin: 0,
    end: 0,
};

fn is_end(cx: &Core<'_>, j: JoinId) -> bool {
    j == JoinId::NONE || cx.joins[j].kind == JoinKind::Root
}

fn from_right(cx: &Core<'_>, j: JoinId) -> bool {
    cx.joins[j].rjoin != JoinId::NONE
}

/// Joins from `j` up its left inputs.
fn chain_len(cx: &Core<'_>, mut j: JoinId) -> u16 {
    let mut n = 0;
    while !is_end(cx, j) && (n as usize) < MAX_WALK * 4 {
        n += 1;
        j = cx.joins[j].parent;
    }
    n
}

/// Patterns up to `j`: into groups (`into_group`) or, for the first step only, past
/// them, counting the group as one; CLIPS's pattern range ends and starts so.
fn count_patterns(cx: &Core<'_>, mut j: JoinId, mut into_group: bool) -> u16 {
    let mut n = 0u16;
    if is_end(cx, j) {
        return 0;
    }
    if from_right(cx, j) && !into_group {
        n += 1;
    }
    let mut steps = 0;
    while !is_end(cx, j) && steps < MAX_WALK * 4 {
        steps += 1;
        if from_right(cx, j) {
            j = if into_group {
                cx.joins[j].rjoin
            } else {
                cx.joins[j].parent
            };
        } else {
            n += 1;
            j = cx.joins[j].parent;
        }
        into_group = true;
    }
    n
}

/// The joins of the walk from `last` (the terminal's input), first join first.
fn walk(cx: &Core<'_>, last: JoinId, out: &mut [JoinId; MAX_WALK]) -> usize {
    let mut n = 0;
    let mut j = last;
    while !is_end(cx, j) && n < out.len() {
        out[n] = j;
        n += 1;
        j = if from_right(cx, j) {
            cx.joins[j].rjoin
        } else {
            cx.joins[j].parent
        };
    }
    out[..n].reverse();
    n
}

/// The pattern joins of the walk (joins from the right are passed through).
fn alpha_joins(cx: &Core<'_>, walked: &[JoinId]) -> ([JoinId; MAX_WALK], usize) {
    let mut out = [JoinId::NONE; MAX_WALK];
    let mut n = 0;
    for &j in walked {
        if !from_right(cx, j) {
            out[n] = j;
            n += 1;
        }
    }
    (out, n)
}

/// CLIPS's heading for the partial matches of `info[at]`: the CEs along its left
/// inputs, runs of single-pattern CEs joined by ` - `, groups apart, with pattern
/// ranges once any CE is a group.
fn header(cx: &Core<'_>, info: &[JoinInfo], at: usize, w: &mut dyn Write) {
    let mut marked = [false; MAX_WALK];
    let mut left = 0usize;
    let mut nested = false;
    let mut j = info[at].join;
    let mut search_from = at as isize;
    while !is_end(cx, j) {
        let mut i = search_from;
        while i >= 0 {
            let k = i as usize;
            if info[k].join == j {
                marked[k] = true;
                left += 1;
                nested |= info[k].begin != info[k].end;
                search_from = i - 1;
                break;
            }
            i -= 1;
        }
        j = cx.joins[j].parent;
    }
    let one = |w: &mut dyn Write, x: &JoinInfo| {
        let _ = write!(w, "{}", x.ce);
        if nested {
            if x.begin == x.end {
                let _ = write!(w, " (P{})", x.begin);
            } else {
                let _ = write!(w, " (P{} - P{})", x.begin, x.end);
            }
        }
    };
    let mut i = 0;
    while i <= at {
        if !marked[i] {
            i += 1;
            continue;
        }
        left -= 1;
        let start = i;
        let mut end = i;
        if info[i].begin == info[i].end {
            let mut k = i + 1;
            while k <= at {
                if marked[k] {
                    if info[k].begin != info[k].end {
                        break;
                    }
                    left -= 1;
                    end = k;
                    i = k;
                }
                k += 1;
            }
        }
        one(w, &info[start]);
        if start != end {
            let _ = w.write_str(" - ");
            one(w, &info[end]);
        }
        if left > 0 {
            let _ = w.write_str(" , ");
        }
        i += 1;
    }
}

fn say(cx: &mut Core<'_>, detail: Detail, text: &str) {
    if detail == Detail::Verbose {
        cx.write(router::WDISPLAY, text);
    }
}

/// Lists the alpha memory of a pattern join (or, for a join without a pattern, `*`
/// once the first join of a chain has let the empty match through); returns how
/// many matches.
fn alpha_matches(cx: &mut Core<'_>, j: JoinId, pattern: usize, detail: Detail) -> i64 {
    let mut b: TextBuf<64> = TextBuf::new();
    let _ = writeln!(b, "Matches for Pattern {pattern}");
    say(cx, detail, b.as_str());
    let alpha = cx.joins[j].alpha;
    let mut count = 0i64;
    if alpha == NONE {
        let first = is_end(cx, cx.joins[j].parent);
        if first && cx.join_mems[j].mem != TokenId::NONE {
            count = 1;
            say(cx, detail, "*\n");
        }
    } else {
        let mut t = cx.alpha_mems[alpha as usize].head;
        while t != TokenId::NONE {
            let fact = cx.tokens[t].fact;
            let mut b: TextBuf<32> = TextBuf::new();
            let _ = writeln!(b, "f-{}", cx.facts[fact as usize].num);
            say(cx, detail, b.as_str());
            count += 1;
            t = cx.tokens[t].mem_next;
        }
    }
    if count == 0 {
        say(cx, detail, " None\n");
    }
    if detail == Detail::Succinct {
        let mut b: TextBuf<64> = TextBuf::new();
        let _ = writeln!(b, "Pattern {pattern}: {count}");
        cx.write(router::WDISPLAY, b.as_str());
    }
    count
}

/// Prints the basis of each partial match in join `j`'s output memory (`f-1,f-3,*`);
/// returns how many. A not/exists join keeps blocked tokens too: only live ones count.
fn partial_matches(cx: &mut Core<'_>, j: JoinId, detail: Detail) -> i64 {
    let kind = cx.joins[j].kind;
    let mut t = cx.join_mems[j].mem;
    let mut count = 0;
    while t != TokenId::NONE {
        let tk = cx.tokens[t];
        let live = match kind {
            JoinKind::Negative => !tk.blocked,
            JoinKind::Exists => tk.blocked,
            _ => true,
        };
        if live {
            if detail == Detail::Verbose {
                let mut b: TextBuf<512> = TextBuf::new();
                let _ = cx.write_basis(&mut b, t);
                let _ = b.write_char('\n');
                cx.write(router::WDISPLAY, b.as_str());
            }
            count += 1;
        }
        t = tk.mem_next;
    }
    count
}

/// One disjunct's alpha and beta listings; adds to the two totals.
fn list_disjunct(cx: &mut Core<'_>, rule: Ix, detail: Detail, totals: &mut [i64; 3]) {
    let last = cx.joins[cx.rules[rule as usize].terminal].parent;
    let mut walked = [JoinId::NONE; MAX_WALK];
    let n = walk(cx, last, &mut walked);
    let (alphas, na) = alpha_joins(cx, &walked[..n]);
    for (i, &j) in alphas[..na].iter().enumerate() {
        totals[0] += alpha_matches(cx, j, i + 1, detail);
    }
    let mut info = [NO_INFO; MAX_WALK];
    for (k, &j) in walked[..n].iter().enumerate() {
        info[k] = JoinInfo {
            join: j,
            ce: chain_len(cx, j),
            begin: count_patterns(cx, j, false),
            end: count_patterns(cx, j, true),
        };
    }
    for at in 1..n {
        let mut head: TextBuf<256> = TextBuf::new();
        header(cx, &info[..n], at, &mut head);
        if detail == Detail::Verbose {
            let mut b: TextBuf<300> = TextBuf::new();
            let _ = writeln!(b, "Partial matches for CEs {}", head.as_str());
            cx.write(router::WDISPLAY, b.as_str());
        }
        let count = partial_matches(cx, info[at].join, detail);
        if count == 0 {
            say(cx, detail, " None\n");
        }
        if detail == Detail::Succinct {
            let mut b: TextBuf<300> = TextBuf::new();
            let _ = writeln!(b, "CEs {}: {count}", head.as_str());
            cx.write(router::WDISPLAY, b.as_str());
        }
        totals[1] += count;
    }
}

/// `(matches rule [verbose|succinct|terse])`; returns the three counts (alpha
/// matches, partial matches, activations) as a multifield.
pub(super) fn matches(cx: &mut Core<'_>, a: Args, first: Ix) -> Result<Value, EvalError> {
    let detail = if a.len > 1 {
        let w = cx.arg_symbol(a, 1, "matches")?;
        match cx.sym_text(w) {
            "verbose" => Detail::Verbose,
            "succinct" => Detail::Succinct,
            "terse" => Detail::Terse,
            _ => {
                // said, and FALSE is the command's value: CLIPS's body sets no
                // evaluation error here (the actions go on)
                cx.write_error_message(EvalError::wrong_type(
                    "matches",
                    2,
                    "symbol with value verbose, succinct, or terse",
                ));
                return Ok(Value::Sym(super::SYM_FALSE));
            }
        }
    } else {
        Detail::Verbose
    };
    let mut totals = [0i64; 3];
    let mut r = first;
    let mut guard = 0;
    while r != NONE && guard < 256 {
        list_disjunct(cx, r, detail, &mut totals);
        r = cx.rules[r as usize].next_disjunct;
        guard += 1;
    }
    say(cx, detail, "Activations\n");
    let name = cx.rules[first as usize].name;
    // CLIPS looks for them on the current module's agenda only (an imported rule's
    // show none), among the activations of the rule's own module
    #[cfg(feature = "modules")]
    let (here, module) = {
        let m = cx.rule_tag(first).module;
        (m == cx.current_module(), m)
    };
    #[cfg(feature = "modules")]
    let ours = |cx: &Core<'_>, r: Ix| here && cx.rule_tag(r).module == module;
    #[cfg(not(feature = "modules"))]
    let ours = |_: &Core<'_>, _: Ix| true;
    let mut act = cx.st.agenda.agenda_head;
    while act != NONE {
        let x = cx.acts[act as usize];
        if cx.rules[x.rule as usize].name == name && ours(cx, x.rule) {
            if detail == Detail::Verbose {
                let mut b: TextBuf<512> = TextBuf::new();
                let _ = cx.write_basis(&mut b, x.token);
                if b.is_empty() {
                    let _ = b.write_char('*');
                }
                let _ = b.write_char('\n');
                cx.write(router::WDISPLAY, b.as_str());
            }
            totals[2] += 1;
        }
        act = x.next;
    }
    if totals[2] == 0 {
        say(cx, detail, " None\n");
    }
    if detail == Detail::Succinct {
        let mut b: TextBuf<64> = TextBuf::new();
        let _ = writeln!(b, "Activations: {}", totals[2]);
        cx.write(router::WDISPLAY, b.as_str());
    }
    Ok(cx.make_multi(&[
        Value::Int(totals[0]),
        Value::Int(totals[1]),
        Value::Int(totals[2]),
    ])?)
}
