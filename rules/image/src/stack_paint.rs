//! Stack high-water measurement by painting.
//!
//! `_start` fills `PAINT_BYTES` below the entry stack pointer with `PAINT_WORD` before any
//! Rust code runs. At exit, the words still holding the pattern at the low end were never
//! touched; everything above them was. This measures the deepest stack use of the whole
//! run, including frames that have long returned.

/// Bytes painted below the entry stack pointer. Half the RAM budget: a run that reaches the
/// bottom of the paint is reported as such, never as a smaller number.
pub const PAINT_BYTES: usize = 32 * 1024;

/// Words painted.
pub const PAINT_WORDS: usize = PAINT_BYTES / 4;

/// The paint. Not zero and not a small integer, so ordinary stack data rarely equals it.
pub const PAINT_WORD: u32 = 0x5A17_C0DE;

/// Stack use seen at exit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StackUse {
    /// Bytes between the entry stack pointer and the deepest overwritten word.
    pub max_bytes: usize,
    /// True when even the lowest painted word was overwritten: the real use may be larger.
    pub reached_paint_bottom: bool,
}

/// Reads the painted region through `word_at(i)` (index 0 = lowest address, `words - 1` =
/// just below the entry stack pointer) and returns how much of it was used.
pub fn measure(words: usize, word_at: impl Fn(usize) -> u32) -> StackUse {
    let untouched = (0..words).take_while(|&i| word_at(i) == PAINT_WORD).count();
    StackUse {
        max_bytes: (words - untouched) * 4,
        reached_paint_bottom: untouched == 0 && words > 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(untouched: usize, used: usize) -> Vec<u32> {
        let mut words = vec![PAINT_WORD; untouched];
        words.extend((0..used).map(|i| i as u32));
        words
    }

    #[test]
    fn untouched_region_reports_zero() {
        let words = region(16, 0);
        let seen = measure(words.len(), |i| words[i]);
        assert_eq!(
            seen,
            StackUse {
                max_bytes: 0,
                reached_paint_bottom: false
            }
        );
    }

    #[test]
    fn counts_bytes_from_the_deepest_overwritten_word() {
        let mut words = region(10, 6);
        // A word deep in the used part that happens to equal the paint does not shorten
        // the measurement: only the untouched run at the bottom counts.
        words[12] = PAINT_WORD;
        let seen = measure(words.len(), |i| words[i]);
        assert_eq!(
            seen,
            StackUse {
                max_bytes: 24,
                reached_paint_bottom: false
            }
        );
    }

    #[test]
    fn flags_a_run_that_used_the_whole_paint() {
        let words = region(0, 8);
        let seen = measure(words.len(), |i| words[i]);
        assert_eq!(
            seen,
            StackUse {
                max_bytes: 32,
                reached_paint_bottom: true
            }
        );
    }

    #[test]
    fn a_fully_used_paint_measures_exactly_the_painted_bytes() {
        let seen = measure(PAINT_WORDS, |_| 0);
        assert_eq!(seen.max_bytes, PAINT_BYTES);
        assert!(seen.reached_paint_bottom);
    }
}
