//! CLIPS 6.30's `apropos` and `set-locale` (agent-core feature `extras`; the agent
//! image has neither).
//!
//! `apropos` lists, as CLIPS does, the entries of the symbol table whose text contains
//! its argument, in the order of CLIPS's own hash table (`HashSymbol`: `h = h * 127 +
//! byte` over the text, modulo 63,559 buckets, each bucket in the order its entries were
//! added, the builtins' names first). The table is not CLIPS's: it holds the names of
//! our builtins and of the host's functions, and every symbol and string interned since
//! the last `clear` (CLIPS frees those no construct, fact or value uses any more, and has
//! COOL's names besides). So the listing matches CLIPS's where the matching names are
//! the program's constructs, slots and values or functions both engines have.

use super::describe::{ArgType, OnError, Returns};
use super::{Args, Builtin, BUILTINS, COUNT};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::{SymId, TextBuf, Value};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("apropos", 1, 1, apropos).args(&[ArgType::Symbol], ArgType::Any).returns(Returns::Void),
    Builtin::eager("set-locale", 0, 1, set_locale).on_error(OnError::False),
];

pub const TABLE: super::Table = super::Table::new(FUNCS);

/// The number of buckets of CLIPS 6.30's symbol table (`SYMBOL_HASH_SIZE`).
const CLIPS_SYMBOL_BUCKETS: u64 = 63_559;

/// The bucket CLIPS 6.30 puts `text` in (`HashSymbol`; `char` is signed there).
pub fn clips_symbol_bucket(text: &str) -> u32 {
    let mut h: u64 = 0;
    for &b in text.as_bytes() {
        h = h.wrapping_mul(127).wrapping_add(b as i8 as i64 as u64);
    }
    (h % CLIPS_SYMBOL_BUCKETS) as u32
}

/// Most names one `apropos` lists.
const MOST_LISTED: usize = 2048;

/// Fixed symbols of ours that CLIPS's table does not start with (`nil`, `implied`,
/// `crlf`, `t`, the empty string).
fn own_fixed(id: SymId) -> bool {
    use super::{SYM_CRLF, SYM_EMPTY_STR, SYM_IMPLIED, SYM_NIL, SYM_T};
    matches!(id, SYM_NIL | SYM_IMPLIED | SYM_CRLF | SYM_T | SYM_EMPTY_STR)
}

/// Whether symbol `id` is the kept source text of a deffunction or defglobal (for
/// `ppdeffunction`, `ppdefglobal`): no symbol of CLIPS's.
fn kept_text(cx: &Core<'_>, id: SymId) -> bool {
    let nfuncs = (cx.st.pools.nfuncs as usize).min(cx.func_extras.len());
    let globals = &cx.global_text[..(cx.st.pools.nglobals as usize).min(cx.global_text.len())];
    cx.func_extras[..nfuncs].iter().any(|e| e.text == id) || globals.contains(&id)
}

/// The text of candidate `origin`: a builtin's name (`0..COUNT`), else symbol
/// `origin - COUNT`.
fn candidate<'c>(cx: &'c Core<'_>, origin: usize) -> &'c str {
    match BUILTINS.get(origin) {
        Some(b) => b.name,
        None => cx.sym_text((origin - COUNT) as SymId),
    }
}

/// `(apropos <symbol>)`: every name containing the argument, one a line, in CLIPS's
/// hash order (see the module's documentation).
fn apropos(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(arg) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type(
            "apropos",
            1,
            super::save_facts::T_SYMBOL,
        ));
    };
    let nsyms = cx.st.pools.nsyms as usize;
    // a symbol first read by this very command is CLIPS's ephemeral one, gone after
    // it: not listed now, nor by a later `apropos` (which CLIPS would list only if
    // something came to use it meanwhile)
    if arg as usize + 1 == nsyms {
        cx.st.tools.forget_symbol(arg);
    }
    let mut keys = [0u64; MOST_LISTED];
    let mut n = 0;
    for origin in 0..COUNT + nsyms {
        if origin >= COUNT {
            let id = (origin - COUNT) as SymId;
            if own_fixed(id) || cx.st.tools.forgotten(id) || kept_text(cx, id) {
                continue;
            }
        }
        let text = candidate(cx, origin);
        let pattern = cx.sym_text(arg);
        if text.starts_with('(') || !text.contains(pattern) {
            continue;
        }
        if n == MOST_LISTED {
            return Err(crate::engine::cap(crate::error::Pool::Scratch, MOST_LISTED).into());
        }
        keys[n] = (u64::from(clips_symbol_bucket(text)) << 32) | origin as u64;
        n += 1;
    }
    let keys = &mut keys[..n];
    keys.sort_unstable();
    cx.spill_traces();
    let (view, host) = cx.split();
    let text_of = |k: u64| match BUILTINS.get((k & 0xffff_ffff) as usize) {
        Some(b) => b.name,
        None => view.sym(((k & 0xffff_ffff) as usize - COUNT) as SymId),
    };
    for (i, &k) in keys.iter().enumerate() {
        let text = text_of(k);
        // a name both a builtin's and a symbol's is one entry (same bucket: adjacent)
        let mut same_bucket = keys[..i].iter().rev().take_while(|o| *o >> 32 == k >> 32);
        if same_bucket.any(|&o| text_of(o) == text) {
            continue;
        }
        host.write_str(router::WDISPLAY, text);
        host.write_str(router::WDISPLAY, "\n");
    }
    Ok(Value::Void)
}

/// The settings and figures of the tools, kept across `clear` as CLIPS keeps them.
#[derive(Clone, Copy)]
pub struct ToolsState {
    /// `set-locale`'s text (CLIPS starts with `C`).
    locale: [u8; MOST_LOCALE],
    locale_len: u8,
    /// Symbols `apropos` was given that no one had used before (the last few): CLIPS
    /// frees them after the command, ours stay (forgotten at `clear`).
    forgotten: [SymId; FORGOTTEN],
    nforgotten: u8,
    next_forgotten: u8,
}

/// How many of `apropos`'s own arguments are remembered (`ToolsState::forgotten`).
const FORGOTTEN: usize = 16;

/// Longest locale name `set-locale` keeps.
const MOST_LOCALE: usize = 64;

impl Default for ToolsState {
    fn default() -> ToolsState {
        ToolsState::new()
    }
}

impl ToolsState {
    pub const fn new() -> ToolsState {
        let mut locale = [0; MOST_LOCALE];
        locale[0] = b'C';
        ToolsState {
            locale,
            locale_len: 1,
            forgotten: [0; FORGOTTEN],
            nforgotten: 0,
            next_forgotten: 0,
        }
    }

    fn forget_symbol(&mut self, id: SymId) {
        if !self.forgotten(id) {
            self.forgotten[usize::from(self.next_forgotten)] = id;
            self.next_forgotten = (self.next_forgotten + 1) % FORGOTTEN as u8;
            self.nforgotten = (self.nforgotten + 1).min(FORGOTTEN as u8);
        }
    }

    fn forgotten(&self, id: SymId) -> bool {
        self.forgotten[..usize::from(self.nforgotten)].contains(&id)
    }

    /// After `clear`: the symbols are interned afresh.
    pub fn forget_symbols(&mut self) {
        self.nforgotten = 0;
        self.next_forgotten = 0;
    }
}

/// `(set-locale [<string>])`: the locale before, as a string. The engine formats
/// numbers as CLIPS does in the C locale whatever it is set to (the no_std core has no
/// C library locale; CLIPS's `format` and float printing follow the one set, which on
/// Debian's machines, lacking other locales, is the C one's output too).
fn set_locale(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let new = match a.len {
        0 => None,
        _ => match cx.arg(a, 0) {
            Value::Str(s) => Some(s),
            _ => return Err(EvalError::wrong_type("set-locale", 1, "string")),
        },
    };
    let t = &cx.st.tools;
    let mut old: TextBuf<MOST_LOCALE> = TextBuf::new();
    let _ =
        old.write_str(core::str::from_utf8(&t.locale[..usize::from(t.locale_len)]).unwrap_or(""));
    if let Some(s) = new {
        let text = cx.sym_text(s);
        if text.len() > MOST_LOCALE {
            return Err(EvalError::wrong_type("set-locale", 1, "string"));
        }
        let n = text.len();
        let mut buf = [0; MOST_LOCALE];
        buf[..n].copy_from_slice(text.as_bytes());
        let t = &mut cx.st.tools;
        t.locale = buf;
        t.locale_len = n as u8;
    }
    Ok(cx.make_string(old.as_str())?)
}

#[cfg(test)]
mod tests {
    #[test]
    fn clips_symbol_buckets_order_the_profile_names_as_clips_lists_them() {
        let names = [
            "set-profile-percent-threshold",
            "progn",
            "progn$",
            "profile-reset",
            "profile",
        ];
        let buckets = names.map(super::clips_symbol_bucket);
        assert_eq!(buckets, [8676, 15238, 28492, 32984, 36844]);
    }
}
