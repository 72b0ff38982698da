//! A game setup as facts given field by field, for hosts that assert them through the
//! engine's API without a parser (the agent image, which loads its rules compiled ahead
//! of time). The same facts as [`GameSetup::write_clips`] writes as text (a test shows
//! it for many seeds).

use crate::setup::GameSetup;

/// A field of a setup fact: an atom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field {
    Int(i64),
    Float(f64),
    Symbol(Name),
}

/// A symbol short enough to be kept inline (`M10`, `lose-puck`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Name {
    bytes: [u8; 16],
    len: u8,
}

impl Name {
    /// `text` cut to 16 bytes (every setup symbol is shorter).
    pub fn new(text: &str) -> Name {
        Name::prefixed(text, None)
    }

    /// `prefix` followed by the digits of `n` (`M` and 3 give `M3`).
    pub fn numbered(prefix: &str, n: u32) -> Name {
        Name::prefixed(prefix, Some(n))
    }

    fn prefixed(prefix: &str, n: Option<u32>) -> Name {
        let mut name = Name {
            bytes: [0; 16],
            len: 0,
        };
        for &b in prefix.as_bytes() {
            name.push(b);
        }
        if let Some(n) = n {
            let mut digits = [0u8; 10];
            let (mut k, mut rest) = (0, n);
            loop {
                digits[k] = b'0' + (rest % 10) as u8;
                k += 1;
                rest /= 10;
                if rest == 0 {
                    break;
                }
            }
            for &d in digits[..k].iter().rev() {
                name.push(d);
            }
        }
        name
    }

    fn push(&mut self, b: u8) {
        if (self.len as usize) < self.bytes.len() {
            self.bytes[self.len as usize] = b;
            self.len += 1;
        }
    }

    pub fn as_str(&self) -> &str {
        // only whole ASCII bytes are pushed by the setup's symbols
        core::str::from_utf8(&self.bytes[..self.len as usize]).unwrap_or("")
    }
}

/// One setup fact: its template and its slots' values. An ordered fact (`s0-supply`)
/// has one slot with an empty name holding its fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetupFact {
    pub template: &'static str,
    slots: [(&'static str, Field); 4],
    len: usize,
}

impl SetupFact {
    fn new(template: &'static str) -> SetupFact {
        SetupFact {
            template,
            slots: [("", Field::Int(0)); 4],
            len: 0,
        }
    }

    fn with(mut self, slot: &'static str, value: Field) -> SetupFact {
        if self.len < self.slots.len() {
            self.slots[self.len] = (slot, value);
            self.len += 1;
        }
        self
    }

    /// Slot names and values, in the order `write_clips` writes them.
    pub fn slots(&self) -> &[(&'static str, Field)] {
        &self.slots[..self.len]
    }
}

fn tenths(t: u32) -> Field {
    // correctly rounded, as the text `5.5` reads
    Field::Float(f64::from(t) / 10.0)
}

impl GameSetup {
    /// Calls `f` with every fact of the setup, in the order of `write_clips`.
    pub fn for_each_fact(&self, mut f: impl FnMut(&SetupFact)) {
        for (i, machine) in self.assignment.iter().enumerate() {
            f(&SetupFact::new("rf-machine")
                .with("name", Field::Symbol(Name::numbered("M", i as u32 + 1)))
                .with("type", Field::Symbol(Name::new(machine.as_str()))));
        }
        let t = &self.times;
        f(&SetupFact::new("rf-times")
            .with("t1", tenths(t.t1_tenths))
            .with("t2", tenths(t.t2_tenths))
            .with("t3", tenths(t.t3_tenths))
            .with("per-input", tenths(t.per_input_tenths)));
        f(&SetupFact::new("s0-supply").with("", Field::Int(i64::from(self.s0_supply))));
        f(&SetupFact::new("active-gate").with(
            "",
            Field::Symbol(Name::numbered("D", u32::from(self.active_gate))),
        ));
        let (limit, enabled) = match self.clock_limit_s {
            Some(limit) => (limit, "TRUE"),
            None => (900, "FALSE"),
        };
        f(&SetupFact::new("game-clock")
            .with("limit", Field::Float(f64::from(limit)))
            .with("enabled", Field::Symbol(Name::new(enabled))));
        for fault in self.all_faults() {
            let mut fact = SetupFact::new("fault")
                .with("at-decision", Field::Int(i64::from(fault.at_decision)))
                .with("kind", Field::Symbol(Name::new(fault.kind.as_str())));
            if fault.draw != 0 {
                fact = fact.with("draw", Field::Int(i64::from(fault.draw)));
            }
            f(&fact);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::fact_lines;
    use core::fmt::{self, Write};

    struct Buf<const N: usize> {
        bytes: [u8; N],
        len: usize,
    }

    impl<const N: usize> Buf<N> {
        fn new() -> Self {
            Buf {
                bytes: [0; N],
                len: 0,
            }
        }
        fn as_str(&self) -> &str {
            core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("<not utf-8>")
        }
    }

    impl<const N: usize> Write for Buf<N> {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            let end = self.len + s.len();
            if end > N {
                return Err(fmt::Error);
            }
            self.bytes[self.len..end].copy_from_slice(s.as_bytes());
            self.len = end;
            Ok(())
        }
    }

    fn field(out: &mut impl Write, v: &Field) -> fmt::Result {
        match v {
            Field::Int(i) => write!(out, "{i}"),
            // `{:?}` keeps the `.0` CLIPS writes
            Field::Float(x) => write!(out, "{x:?}"),
            Field::Symbol(s) => write!(out, "{}", s.as_str()),
        }
    }

    fn as_clips(fact: &SetupFact) -> Buf<160> {
        let mut out = Buf::new();
        let _ = write!(out, "({}", fact.template);
        for (slot, v) in fact.slots() {
            if slot.is_empty() {
                let _ = write!(out, " ");
                let _ = field(&mut out, v);
            } else {
                let _ = write!(out, " ({slot} ");
                let _ = field(&mut out, v);
                let _ = write!(out, ")");
            }
        }
        let _ = write!(out, ")");
        out
    }

    #[test]
    fn the_facts_are_those_write_clips_writes() {
        for seed in 0..200 {
            let mut setup = GameSetup::for_seed(seed)
                .with_seeded_times(seed)
                .with_seeded_faults(seed, (seed % 4) as usize, 60);
            if seed % 3 == 0 {
                setup.clock_limit_s = Some(300 + seed as u32);
            }
            if seed % 2 == 0 {
                setup = setup.with_fault_rate(20, seed);
            }
            let mut text = Buf::<8192>::new();
            setup.write_clips(&mut text).unwrap();
            let mut lines = fact_lines(text.as_str());
            let mut n = 0;
            setup.for_each_fact(|fact| {
                n += 1;
                assert_eq!(Some(as_clips(fact).as_str()), lines.next(), "seed {seed}");
            });
            assert_eq!(lines.next(), None, "seed {seed}: {n} facts");
        }
    }

    #[test]
    fn names_hold_numbers() {
        assert_eq!(Name::numbered("M", 10).as_str(), "M10");
        assert_eq!(Name::numbered("D", 0).as_str(), "D0");
        assert_eq!(Name::new("lose-puck").as_str(), "lose-puck");
    }
}
