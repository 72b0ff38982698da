//! Unit tests of the embedded files and the setup generation (no alloc:
//! text goes into a fixed buffer).

use crate::setup::*;
use crate::*;
use core::fmt::Write;

/// A fixed-size text sink for `write_clips`.
struct Buffer {
    bytes: [u8; 4096],
    len: usize,
}

impl Buffer {
    fn new() -> Self {
        Buffer {
            bytes: [0; 4096],
            len: 0,
        }
    }
    fn as_str(&self) -> &str {
        core::str::from_utf8(&self.bytes[..self.len]).unwrap_or("<not utf-8>")
    }
}

impl Write for Buffer {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let end = self.len + s.len();
        if end > self.bytes.len() {
            return Err(core::fmt::Error);
        }
        self.bytes[self.len..end].copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

fn counts(a: &Assignment) -> (usize, usize, usize) {
    let n = |t| a.iter().filter(|&&m| m == t).count();
    (n(MachineType::T1), n(MachineType::T2), n(MachineType::T3))
}

#[test]
fn splitmix_matches_reference_sequence() {
    // Published first outputs of SplitMix64 seeded with 0.
    let mut rng = SplitMix64::new(0);
    assert_eq!(rng.next_u64(), 0xE220_A839_7B1D_CDAF);
    assert_eq!(rng.next_u64(), 0x6E78_9E6A_A1B9_65F4);
}

#[test]
fn below_stays_in_bounds_and_hits_every_value() {
    let mut rng = SplitMix64::new(7);
    let mut seen = [false; 7];
    for _ in 0..500 {
        let v = rng.below(7) as usize;
        assert!(v < 7);
        seen[v] = true;
    }
    assert!(seen.iter().all(|&s| s));
    assert_eq!(rng.below(0), 0);
}

#[test]
fn seeded_assignments_have_the_2012_mix_and_repeat() {
    for seed in 0..200 {
        let a = assignment_for_seed(seed);
        assert_eq!(counts(&a), (4, 3, 3), "seed {seed}");
        assert_eq!(a, assignment_for_seed(seed));
    }
}

#[test]
fn seeded_assignments_vary() {
    let mut distinct = [false; ASSIGNMENT_COUNT as usize];
    let mut hits = 0;
    for seed in 0..300 {
        let index = index_of_assignment(&assignment_for_seed(seed));
        let index = index.expect("seeded assignment has the 4/3/3 mix") as usize;
        if !distinct[index] {
            distinct[index] = true;
            hits += 1;
        }
    }
    // 300 draws from 4200 values: collisions are rare.
    assert!(hits > 280, "only {hits} distinct assignments");
}

#[test]
fn enumeration_is_a_bijection_onto_all_4200_assignments() {
    let mut seen = [false; ASSIGNMENT_COUNT as usize];
    for index in 0..ASSIGNMENT_COUNT {
        let a = assignment_by_index(index).expect("index in range");
        assert_eq!(counts(&a), (4, 3, 3));
        let back = index_of_assignment(&a).expect("valid mix");
        assert_eq!(back, index);
        assert!(!seen[back as usize]);
        seen[back as usize] = true;
    }
    assert!(assignment_by_index(ASSIGNMENT_COUNT).is_none());
}

#[test]
fn enumeration_starts_and_ends_in_lexicographic_order() {
    use MachineType::*;
    assert_eq!(
        assignment_by_index(0),
        Some([T1, T1, T1, T1, T2, T2, T2, T3, T3, T3])
    );
    assert_eq!(
        assignment_by_index(ASSIGNMENT_COUNT - 1),
        Some([T3, T3, T3, T2, T2, T2, T1, T1, T1, T1])
    );
}

#[test]
fn index_of_rejects_a_wrong_mix() {
    assert_eq!(index_of_assignment(&[MachineType::T1; MACHINE_COUNT]), None);
}

#[test]
fn seeded_times_stay_in_the_2012_ranges() {
    for seed in 0..100 {
        let t = ProcessingTimes::for_seed(seed);
        assert!((30..=80).contains(&t.t1_tenths));
        assert!((150..=250).contains(&t.t2_tenths));
        assert!((400..=600).contains(&t.t3_tenths));
        assert_eq!(t.per_input_tenths, 20);
    }
}

#[test]
fn seeded_faults_are_distinct_and_bounded() {
    let setup = GameSetup::for_seed(3).with_seeded_faults(3, 5, 40);
    let mut n = 0;
    for (i, f) in setup.faults().enumerate() {
        assert!((1..=40).contains(&f.at_decision));
        assert!(setup
            .faults()
            .skip(i + 1)
            .all(|g| g.at_decision != f.at_decision));
        n += 1;
    }
    assert_eq!(n, 5);
    let mut full = GameSetup::for_seed(3).with_seeded_faults(3, 100, 1000);
    assert_eq!(full.faults().count(), MAX_FAULTS);
    let extra = Fault {
        at_decision: 1,
        kind: FaultKind::LosePuck,
    };
    assert_eq!(full.add_fault(extra), Err(FaultsFull));
}

#[test]
fn setup_text_lists_every_fact() {
    let mut setup = GameSetup::new(assignment_by_index(0).expect("index 0"));
    setup.active_gate = 2;
    setup.clock_limit_s = None;
    setup.times = ProcessingTimes::for_seed(1);
    setup
        .add_fault(Fault {
            at_decision: 4,
            kind: FaultKind::DriveFail,
        })
        .expect("room for a fault");
    let mut buf = Buffer::new();
    setup.write_clips(&mut buf).expect("fits the buffer");
    let text = buf.as_str();
    assert!(text.starts_with("(deffacts game-setup\n"));
    assert!(text.contains("  (rf-machine (name M1) (type T1))\n"));
    assert!(text.contains("  (rf-machine (name M10) (type T3))\n"));
    assert!(text.contains("  (s0-supply 20)\n"));
    assert!(text.contains("  (active-gate D2)\n"));
    assert!(text.contains("(enabled FALSE)"));
    assert!(text.contains("  (fault (at-decision 4) (kind drive-fail))\n"));
    let t = setup.times;
    let mut expect = Buffer::new();
    write!(expect, "(t1 {}.{})", t.t1_tenths / 10, t.t1_tenths % 10).expect("fits");
    assert!(text.contains(expect.as_str()));
    assert!(text.trim_end().ends_with(')'));
    assert_eq!(text.matches("(rf-machine").count(), MACHINE_COUNT);
}

#[test]
fn midpoint_times_print_as_clips_floats() {
    let mut buf = Buffer::new();
    GameSetup::new(assignment_by_index(5).expect("index 5"))
        .write_clips(&mut buf)
        .expect("fits");
    assert!(buf
        .as_str()
        .contains("(rf-times (t1 5.5) (t2 20.0) (t3 50.0) (per-input 2.0))"));
    assert!(buf.as_str().contains("(limit 900.0) (enabled TRUE)"));
}

#[test]
fn seeded_gate_is_one_of_three_and_varies() {
    let mut seen = [false; 4];
    for seed in 0..60 {
        let g = GameSetup::for_seed(seed).active_gate;
        assert!((1..=3).contains(&g));
        seen[g as usize] = true;
    }
    assert!(seen[1] && seen[2] && seen[3]);
}

/// Parentheses balance outside strings and comments: a cheap structural
/// check that an edit did not leave a construct open.
fn balanced(text: &str) -> bool {
    let (mut depth, mut in_string, mut in_comment) = (0i32, false, false);
    let mut prev = ' ';
    for c in text.chars() {
        if in_comment {
            in_comment = c != '\n';
        } else if in_string {
            in_string = !(c == '"' && prev != '\\');
        } else {
            match c {
                ';' => in_comment = true,
                '"' => in_string = true,
                '(' => depth += 1,
                ')' => depth -= 1,
                _ => {}
            }
            if depth < 0 {
                return false;
            }
        }
        prev = c;
    }
    depth == 0 && !in_string
}

#[test]
fn every_rule_file_is_balanced_and_named() {
    for strategy in Strategy::ALL {
        for file in game_files(strategy) {
            assert!(file.name.ends_with(".clp"));
            assert!(file.text.contains("(def"), "{}", file.name);
            assert!(balanced(file.text), "{} is unbalanced", file.name);
        }
    }
    assert!(balanced(CLIPS_STUBS.text));
}

#[test]
fn strategies_load_utilities_first_and_their_own_production() {
    for strategy in Strategy::ALL {
        assert_eq!(Strategy::from_name(strategy.name()), Some(strategy));
        let agent = agent_files(strategy);
        assert_eq!(agent[0], UTILS);
        let game = game_files(strategy);
        assert_eq!(&game[..agent.len()], agent);
        assert_eq!(&game[agent.len()..], &[REFEREE, GAME_LOG, SIM]);
        assert_eq!(&game[agent.len()..agent.len() + 2], &DRIVER_FILES);
    }
    assert!(agent_files(Strategy::Naive).contains(&PRODUCTION_NAIVE));
    assert!(agent_files(Strategy::Paper).contains(&SELECT_PAPER));
    assert!(agent_files(Strategy::Travel).contains(&SELECT_TRAVEL));
    assert_eq!(Strategy::from_name("greedy"), None);
}

#[test]
fn the_paper_example_rules_are_present() {
    assert!(PRODUCTION.text.contains("(defrule prod-s0-t23-s1"));
    assert!(WORLD_MODEL.text.contains("(defrule wm-green-t2"));
    assert!(EXECUTION.text.contains("(defrule exec-failed-abort"));
    assert!(!REFEREE.text.contains("(random"));
    assert!(!SIM.text.contains("(random"));
    assert!(!GAME_LOG.text.contains("(random"));
}

#[test]
fn interface_symbols_round_trip() {
    use crate::facts::*;
    for l in Light::ALL {
        assert_eq!(Light::from_symbol(l.as_str()), Some(*l));
    }
    for s in Skill::ALL {
        assert_eq!(Skill::from_symbol(s.as_str()), Some(*s));
        assert!(EXECUTION.text.contains(s.as_str()), "{}", s.as_str());
    }
    for t in TypeBelief::ALL {
        assert!(WORLD_MODEL.text.contains(t.as_str()));
    }
    for e in GameEnd::ALL {
        assert!(REFEREE.text.contains(e.as_str()));
    }
    assert_eq!(Light::from_symbol("orange"), None);
    for name in [
        names::SKILL_REQUEST,
        names::SKILL_OUTCOME,
        names::DECISION,
        names::GAME_OVER,
    ] {
        let construct = game_files(Strategy::Paper)
            .iter()
            .any(|f| f.text.contains(name));
        assert!(construct, "{name} not defined by the game files");
    }
}

#[test]
fn belief_symbols_parse() {
    use crate::facts::*;
    let b = MachineBelief::parse("T2_3+S0").expect("valid belief");
    assert_eq!(b.mtype, TypeBelief::T2or3);
    assert_eq!(b.loaded(), &[Puck::S0]);
    assert!(!b.mtype.is_known());
    let b = MachineBelief::parse("T3+S2+S0").expect("valid belief");
    assert!(b.mtype.is_known());
    assert_eq!(b.loaded(), &[Puck::S2, Puck::S0]);
    assert_eq!(
        MachineBelief::parse("T1_2_3").map(|b| b.loaded().len()),
        Some(0)
    );
    assert_eq!(MachineBelief::parse("T4"), None);
    assert_eq!(MachineBelief::parse("T3+NONE"), None);
    assert_eq!(MachineBelief::parse("T3+S0+S1+S2+S0"), None);
}

#[test]
fn fact_lines_are_the_facts_of_the_deffacts() {
    let setup = GameSetup::for_seed(3);
    let mut buf = Buffer::new();
    setup.write_clips(&mut buf).expect("fits the buffer");
    let text = buf.as_str();
    let mut n = 0;
    for line in fact_lines(text) {
        n += 1;
        assert!(line.starts_with('(') && line.ends_with(')'), "{line:?}");
        assert!(!line.contains("deffacts"), "{line:?}");
        assert!(balanced(line), "{line:?}");
    }
    // every line of the deffacts but its header and closing parenthesis
    assert_eq!(n, text.lines().count() - 2);
    assert_eq!(
        fact_lines(text)
            .filter(|l| l.starts_with("(rf-machine"))
            .count(),
        MACHINE_COUNT
    );
}
