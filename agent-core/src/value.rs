//! Runtime values: atoms and multifield spans, plus CLIPS-style number printing.

use core::fmt::{self, Write};
use core::mem::MaybeUninit;

/// Index into an engine pool (and link between pool entries). The agent image keeps
/// `u16`: half the bytes per link, and no pool there comes near 65,535 entries.
#[cfg(not(feature = "wide-index"))]
pub type Ix = u16;
/// `u32` pool indices for host engines with more than 65,535 entries per pool (feature
/// `wide-index`); the agent image keeps `u16`.
#[cfg(feature = "wide-index")]
pub type Ix = u32;

/// Index of a symbol or string in the symbol table.
pub type SymId = Ix;

/// "No entry" marker for all `Ix` pool links.
pub const NONE: Ix = Ix::MAX;

/// A fact address: pool slot plus the fact number, so a stale address (the slot was
/// reused) is detected by comparing numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FactRef {
    pub slot: Ix,
    pub num: u32,
}

impl FactRef {
    /// CLIPS's `<Dummy Fact>`, the derived default of a slot whose one type is
    /// FACT-ADDRESS: no fact's address (like a retracted fact's).
    pub const DUMMY_FACT: FactRef = FactRef {
        slot: NONE,
        num: u32::MAX,
    };
    /// CLIPS's `<Dummy Instance>`, the derived default of an INSTANCE-ADDRESS slot
    /// (no instances here): an address of type INSTANCE-ADDRESS that no fact has.
    pub const DUMMY_INSTANCE: FactRef = FactRef {
        slot: NONE,
        num: u32::MAX - 1,
    };
}

/// A contiguous run of atoms in the multifield scratch area (during evaluation) or,
/// inside fact storage, a header announcing that `len` atoms follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MfSpan {
    pub start: Ix,
    pub len: Ix,
}

/// One CLIPS value. `Multi` points into the scratch area during evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Void,
    /// Only in a variable's storage (a frame local, a global): the variable is bound
    /// to a void value (`(bind ?x (printout ...))`), which CLIPS keeps; reading it
    /// gives `Void`, while a `Void` in storage means unbound. Declared next to `Void`
    /// so that one comparison of the tag tells both apart from every value.
    BoundVoid,
    Int(i64),
    Float(f64),
    Sym(SymId),
    Str(SymId),
    Fact(FactRef),
    Multi(MfSpan),
}

impl Value {
    pub const EMPTY: Value = Value::Void;

    pub fn as_number(self) -> Option<f64> {
        match self {
            Value::Int(i) => Some(i as f64),
            Value::Float(f) => Some(f),
            _ => None,
        }
    }

    pub fn is_multi(self) -> bool {
        matches!(self, Value::Multi(_))
    }

    /// CLIPS's `eq`: same type and same value (1 and 1.0 differ). Floats are the
    /// same when CLIPS's float table would give one entry: equal and of the same
    /// bits, so 0.0 and -0.0 differ (a NaN is never the same).
    pub fn same(self, other: Value) -> bool {
        match (self, other) {
            (Value::Float(a), Value::Float(b)) => a == b && a.to_bits() == b.to_bits(),
            _ => self == other,
        }
    }
}

/// The name inside an instance name's text `[x]`. CLIPS's instance names are a type
/// of their own; here they are symbols spelled with their brackets (the lexer makes
/// them, and `sym-cat` refuses to make such a symbol), so the spelling tells them
/// apart: string functions see the name without brackets, `symbolp` is FALSE.
pub fn instance_name_body(text: &str) -> Option<&str> {
    // (`[]` is a symbol in CLIPS)
    text.strip_prefix('[')?
        .strip_suffix(']')
        .filter(|t| !t.is_empty())
}

/// A public, borrowed view of a value (for hosts reading facts).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ValueRef<'a> {
    Int(i64),
    Float(f64),
    Symbol(&'a str),
    String(&'a str),
    Fact(u32),
    /// A multifield; read elements with `Engine::fact_multislot_item`.
    Multi(Ix),
    Void,
}

/// A fixed-size text buffer implementing `fmt::Write`; output beyond capacity is cut.
///
/// The buffer is left uninitialised: string builtins create 2 KiB ones per call, and
/// zeroing them cost more than the work done in them.
pub struct TextBuf<const N: usize> {
    buf: [MaybeUninit<u8>; N],
    /// Bytes `..len` are initialised and hold whole UTF-8 sequences.
    len: usize,
}

impl<const N: usize> TextBuf<N> {
    pub const fn new() -> Self {
        TextBuf {
            buf: [const { MaybeUninit::uninit() }; N],
            len: 0,
        }
    }
    /// The initialised bytes, `buf[..len]`.
    fn bytes(&self) -> &[u8] {
        // SAFETY: `write_str` initialises `buf[..len]` before it raises `len`, and
        // nothing else raises it (`clear` and `truncate` only lower it), so the first
        // `len` bytes are initialised; `len <= N`, so the slice stays inside `buf`.
        unsafe { core::slice::from_raw_parts(self.buf.as_ptr().cast::<u8>(), self.len) }
    }
    pub fn as_str(&self) -> &str {
        // SAFETY: `buf[..len]` is whole UTF-8 sequences: `write_str` pushes a prefix
        // of a `str` cut at a char boundary, `clear` lowers `len` to 0 and `truncate`
        // to a sequence's start. (Checking them again cost every text built here a
        // pass over its bytes.)
        unsafe { core::str::from_utf8_unchecked(self.bytes()) }
    }
    pub fn clear(&mut self) {
        self.len = 0;
    }
    /// Back to an earlier length (one `len` returned), dropping what came after; a
    /// length inside a character goes back to that character's start.
    pub fn truncate(&mut self, len: usize) {
        let mut len = self.len.min(len);
        let bytes = self.bytes();
        while len > 0 && len < bytes.len() && bytes[len] & 0xC0 == 0x80 {
            len -= 1;
        }
        self.len = len;
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl<const N: usize> Default for TextBuf<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Write for TextBuf<N> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let room = N - self.len;
        let mut take = s.len().min(room);
        while take > 0 && !s.is_char_boundary(take) {
            take -= 1;
        }
        for (d, &b) in self.buf[self.len..self.len + take]
            .iter_mut()
            .zip(&s.as_bytes()[..take])
        {
            *d = MaybeUninit::new(b);
        }
        self.len += take;
        if take < s.len() {
            Err(fmt::Error)
        } else {
            Ok(())
        }
    }
}

/// Writes a float as CLIPS 6.30 does: C's `%.15g`, plus `.0` when the text has no `.`
/// or `e` (so glibc's `inf` and `-nan` print as `inf.0` and `-nan.0`).
pub fn write_float(out: &mut dyn Write, x: f64) -> fmt::Result {
    if !x.is_finite() {
        let sign = if x.is_sign_negative() { "-" } else { "" };
        let name = if x.is_nan() { "nan" } else { "inf" };
        return write!(out, "{sign}{name}.0");
    }
    let mut g: TextBuf<48> = TextBuf::new();
    write_g15(&mut g, x)?;
    let s = g.as_str();
    out.write_str(s)?;
    if !s
        .bytes()
        .any(|b| b == b'.' || b == b'e' || b == b'n' || b == b'i')
    {
        out.write_str(".0")?;
    }
    Ok(())
}

/// C's `%.15g`.
fn write_g15(out: &mut dyn Write, x: f64) -> fmt::Result {
    const P: i32 = 15;
    if x == 0.0 {
        return out.write_str(if x.is_sign_negative() { "-0" } else { "0" });
    }
    // Round to 15 significant digits via scientific formatting; it gives the exponent.
    let mut sci: TextBuf<48> = TextBuf::new();
    write!(sci, "{:.14e}", x)?;
    let s = sci.as_str();
    let (mant, exp) = match s.split_once('e') {
        Some(p) => p,
        None => return out.write_str(s),
    };
    let exp: i32 = exp.parse().map_err(|_| fmt::Error)?;
    let (neg, mant) = match mant.strip_prefix('-') {
        Some(m) => (true, m),
        None => (false, mant),
    };
    // digits without the dot
    let mut digits = [b'0'; 16];
    let mut n = 0;
    for b in mant.bytes() {
        if b.is_ascii_digit() && n < 16 {
            digits[n] = b;
            n += 1;
        }
    }
    // strip trailing zeros
    while n > 1 && digits[n - 1] == b'0' {
        n -= 1;
    }
    if neg {
        out.write_char('-')?;
    }
    if !(-4..P).contains(&exp) {
        out.write_char(digits[0] as char)?;
        if n > 1 {
            out.write_char('.')?;
            for &d in &digits[1..n] {
                out.write_char(d as char)?;
            }
        }
        let (sign, e) = if exp < 0 { ('-', -exp) } else { ('+', exp) };
        write!(out, "e{sign}{e:02}")
    } else if exp >= 0 {
        let int_len = exp as usize + 1;
        for i in 0..int_len {
            let d = if i < n {
                digits.get(i).copied().unwrap_or(b'0')
            } else {
                b'0'
            };
            out.write_char(d as char)?;
        }
        if n > int_len {
            out.write_char('.')?;
            for &d in &digits[int_len..n] {
                out.write_char(d as char)?;
            }
        }
        Ok(())
    } else {
        out.write_str("0.")?;
        for _ in 0..(-exp - 1) {
            out.write_char('0')?;
        }
        for &d in &digits[..n] {
            out.write_char(d as char)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(x: f64) -> TextBuf<64> {
        let mut b = TextBuf::new();
        write_float(&mut b, x).unwrap();
        b
    }

    #[test]
    fn floats_print_like_clips() {
        assert_eq!(f(1.0 / 3.0).as_str(), "0.333333333333333");
        assert_eq!(f(6.0).as_str(), "6.0");
        assert_eq!(f(3.5).as_str(), "3.5");
        assert_eq!(f(2.5e10).as_str(), "25000000000.0");
        assert_eq!(f(1e15).as_str(), "1e+15");
        assert_eq!(f(1.5e-7).as_str(), "1.5e-07");
        assert_eq!(f(3e-5).as_str(), "3e-05");
        assert_eq!(f(-0.0).as_str(), "-0.0");
        assert_eq!(f(123456789012345678.0).as_str(), "1.23456789012346e+17");
        assert_eq!(f(0.001).as_str(), "0.001");
        assert_eq!(f(-2.25).as_str(), "-2.25");
    }

    #[test]
    fn a_text_buffer_holds_whole_characters_only() {
        use core::fmt::Write as _;
        // a write past the end keeps the characters that fit whole
        let mut b: TextBuf<5> = TextBuf::new();
        assert!(b.write_str("ab\u{e9}\u{e9}").is_err());
        assert_eq!(b.as_str(), "ab\u{e9}");
        // a length inside a character goes back to its start
        b.truncate(3);
        assert_eq!((b.as_str(), b.len()), ("ab", 2));
        let mut b: TextBuf<16> = TextBuf::new();
        b.write_str("x\u{20ac}y").unwrap();
        for (cut, want) in [
            (4, "x\u{20ac}"),
            (3, "x"),
            (2, "x"),
            (1, "x"),
            (9, "x\u{20ac}y"),
        ] {
            let mut c: TextBuf<16> = TextBuf::new();
            c.write_str(b.as_str()).unwrap();
            c.truncate(cut);
            assert_eq!(c.as_str(), want, "cut at {cut}");
        }
    }
}
