//! Builtins `random` and `seed`, reproducing CLIPS 6.30 on glibc.
//!
//! CLIPS calls the C library's `srand`/`rand`; glibc implements them as `srandom`/
//! `random` with the TYPE_3 additive feedback generator (degree 31, separation 3). The
//! generator here is that algorithm, so `(seed 1) (random)` gives 1804289383 as CLIPS
//! does, and an unseeded engine behaves as seeded with 1 (glibc's initial state).
//!
//! State lives in the fields `engine::State` reserves for it: `rng_glibc[0..31]` is the
//! ring of 31 words, `rng_pos` the index of glibc's "rear" pointer (the "front" pointer
//! is 3 ahead), `rng_seeded` whether the ring was initialised.

use super::describe::ArgType::{Any, Integer as I};
use super::describe::Returns as R;
use super::math::int_arg;
use super::{Args, Builtin};
use crate::engine::{Core, State};
use crate::error::EvalError;
use crate::value::Value;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("random", 0, 2, random).args(&[], I).returns(R::Integer),
    Builtin::eager("seed", 1, 1, seed).args(&[I], Any).returns(R::Void),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// Degree and separation of glibc's TYPE_3 generator.
const DEG: usize = 31;
const SEP: usize = 3;

/// glibc `srandom`: fills the ring with a Lehmer sequence (Schrage's method, exactly as
/// glibc computes it) and discards the first 310 outputs.
fn srandom(st: &mut State, seed: u32) {
    let seed = if seed == 0 { 1 } else { seed };
    st.random.rng_glibc[0] = seed as i32;
    for i in 1..DEG {
        let word = st.random.rng_glibc[i - 1] as i64;
        let (hi, lo) = (word / 127_773, word % 127_773);
        let mut next = 16_807 * lo - 2_836 * hi;
        if next < 0 {
            next += 2_147_483_647;
        }
        st.random.rng_glibc[i] = next as i32;
    }
    st.random.rng_pos = 0;
    st.random.rng_seeded = true;
    for _ in 0..10 * DEG {
        next_random(st);
    }
}

/// glibc `random`: front += rear (mod 2^32); the result is front >> 1. (Out of line
/// on the host: inlined into the agenda's insertion, which draws one per activation,
/// it cost more there than its call.)
#[cfg_attr(feature = "host-speedups", inline(never))]
pub(crate) fn next_random(st: &mut State) -> i64 {
    if !st.random.rng_seeded {
        srandom(st, 1);
    }
    // (`rng_pos` stays below `DEG`: the pointers wrap by a compare, not a division,
    // as every activation draws one)
    let mut rear = st.random.rng_pos as usize;
    if rear >= DEG {
        rear %= DEG;
    }
    let front = if rear + SEP >= DEG {
        rear + SEP - DEG
    } else {
        rear + SEP
    };
    let sum = (st.random.rng_glibc[front] as u32).wrapping_add(st.random.rng_glibc[rear] as u32);
    st.random.rng_glibc[front] = sum as i32;
    st.random.rng_pos = if rear + 1 == DEG { 0 } else { rear as u8 + 1 };
    i64::from(sum >> 1)
}

/// `(random)` or `(random lo hi)`: `lo + r mod (hi - lo + 1)` as CLIPS computes it.
/// CLIPS draws the number before it looks at the arguments: a wrong one still takes a
/// number and gives it (an argument of the wrong type as an evaluation error, a range
/// the wrong way round and a wrong count after their message alone).
pub(super) fn random(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    cx.st.random.observed = true;
    if a.len != 0 && a.len != 2 {
        cx.write_error_message(EvalError::message(crate::error::Message::RandomArity));
    }
    let r = next_random(cx.st);
    if a.len != 2 {
        return Ok(Value::Int(r));
    }
    let bounds = int_arg(cx, a, 0, "random").and_then(|lo| Ok((lo, int_arg(cx, a, 1, "random")?)));
    let (lo, hi) = match bounds {
        Ok(b) => b,
        Err(e) => {
            cx.set_error_fallback(Value::Int(r), None);
            return Err(e);
        }
    };
    if hi < lo {
        cx.write_error_message(EvalError::message(crate::error::Message::RandomRange));
        return Ok(Value::Int(r));
    }
    let span = hi.wrapping_sub(lo).wrapping_add(1);
    Ok(Value::Int(if span <= 0 {
        r
    } else {
        lo.wrapping_add(r % span)
    }))
}

/// `(seed n)`: C's `srand((unsigned) n)`; returns no value, as in CLIPS.
fn seed(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let n = int_arg(cx, a, 0, "seed")?;
    cx.st.random.observed = true;
    srandom(cx.st, n as u32);
    Ok(Value::Void)
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    use crate::testutil::run_program;

    fn outputs(src: &str) -> std::vec::Vec<std::string::String> {
        run_program(src)
            .lines()
            .map(std::string::String::from)
            .collect()
    }
    extern crate std;

    #[test]
    fn glibc_sequence() {
        // CLIPS 6.30 on glibc: unseeded = seed 1; values also printed by C's rand()
        assert_eq!(
            outputs("(random)\n(seed 1)\n(random)\n(random)\n"),
            ["1804289383", "1804289383", "846930886"]
        );
        assert_eq!(outputs("(seed 0)\n(random)\n"), ["1804289383"]);
        assert_eq!(outputs("(seed -5)\n(random)\n"), ["1469203335"]);
        assert_eq!(
            outputs("(seed 42)\n(random)\n(random)\n(random)\n"),
            ["71876166", "708592740", "1483128881"]
        );
    }

    #[test]
    fn ranges() {
        assert_eq!(
            outputs("(seed 42)\n(random 1 6)\n(random 1 6)\n(random 10 100)\n"),
            ["1", "1", "62"]
        );
        assert_eq!(
            outputs("(seed 1)\n(random 0 2147483647)\n(random -10 -5)\n"),
            ["1804289383", "-6"]
        );
        let out = run_program("(random 5 1)\n");
        assert!(out.contains("[MISCFUN3]"), "{out}");
        let out = run_program("(random 1)\n");
        assert!(out.contains("[MISCFUN2]"), "{out}");
        let out = run_program("(seed (float 1))\n");
        assert!(out.contains("integer"), "{out}");
    }

    #[test]
    fn long_run_matches_glibc_recurrence() {
        // o(k) = r(k+344) >> 1 with r(i) = r(i-31) + r(i-3): the 1000th value after
        // seed 1, from glibc's rand() loop.
        let src: std::string::String = core::iter::once("(seed 1)\n")
            .chain(core::iter::repeat_n("(random)\n", 1000))
            .collect();
        let out = outputs(&src);
        assert_eq!(out.len(), 1000);
        assert_eq!(out[999], "1143565421");
    }
}
