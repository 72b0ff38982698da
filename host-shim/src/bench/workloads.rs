//! The benchmark workloads: rule files from `tests/bench/` plus generated facts.
//!
//! Every generator is deterministic (seeded with the size), so all engines load the same
//! program text. Facts go into `deffacts` so that `(reset)` asserts them: parsing and
//! asserting then belong to the "no run" baseline that the run phase is measured against.

use super::generated;
use super::rng::SplitMix64;
use std::fmt::Write as _;

const MANNERS_RULES: &str = include_str!("../../../tests/bench/manners.clp");
const MANNERS_PUBLISHED_RULES: &str = include_str!("../../../tests/bench/manners-published.clp");
const JOIN_RULES: &str = include_str!("../../../tests/bench/join.clp");
const NEGATION_RULES: &str = include_str!("../../../tests/bench/negation.clp");

/// Facts per `deffacts` construct: keeps each construct small for parsers that buffer one
/// construct at a time.
const FACTS_PER_DEFFACTS: usize = 500;

/// Number of hobbies in the Manners pool. Every guest has 2 or 3 of these 3 hobbies, so any
/// two guests share one (2 + 2 > 3): with as many men as women a seating always exists and
/// the search never dead-ends.
const MANNERS_HOBBIES: u64 = 3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Our Miss Manners (`tests/bench/manners.clp`, size = guests).
    Manners,
    /// The published Miss Manners (`tests/bench/manners-published.clp`, size = guests).
    MannersPublished,
    /// A puzzle of the sudoku solver Debian's `clips-common` ships (`debian.rs`;
    /// size = grid * 100 + puzzle number, e.g. 317 for `grid3x3-p17`).
    Sudoku,
    /// The solver's own `runbench.bat`, as shipped (size 1).
    SudokuRunbench,
    /// The zebra puzzle of Debian's `clips-common` examples (size 1).
    Zebra,
    Join,
    Negation,
    /// Seeded simulated LLSF games of the agent rule base (size = number of games).
    Llsf,
    /// Generated (`generated.rs`): many rules with constant tests (size = rules).
    Discrim,
    /// Generated: joins on two and three variables (size = facts per template).
    Join3,
    /// Generated: assert/retract chains with `not`/`exists` (size = nodes).
    Propagate,
    /// Generated: an agent-like state machine (size = rules).
    Agent,
    /// Generated: a join keyed on a row with `?a|?b` on another slot, and a `not` of
    /// the same shape (size = cells per row).
    KeyedOr,
    /// Generated: as `KeyedOr`, keyed on two slots with `?a|?b|?c` (size = cells per
    /// row).
    Keyed2Or3,
}

impl Kind {
    pub fn label(self) -> &'static str {
        match self {
            Kind::Manners => "manners",
            Kind::MannersPublished => "manners-pub",
            Kind::Sudoku => "sudoku",
            Kind::SudokuRunbench => "sudoku-runbench",
            Kind::Zebra => "zebra",
            Kind::Join => "join",
            Kind::Negation => "negation",
            Kind::Llsf => "llsf",
            Kind::Discrim => "discrim",
            Kind::Join3 => "join3",
            Kind::Propagate => "propagate",
            Kind::Agent => "agent",
            Kind::KeyedOr => "keyed-or",
            Kind::Keyed2Or3 => "keyed2-or3",
        }
    }

    /// The rule text of the single-file workloads from `tests/bench` (LLSF games load
    /// the rule base's files; the generated kinds make their whole text).
    fn rules(self) -> &'static str {
        match self {
            Kind::Manners => MANNERS_RULES,
            Kind::MannersPublished => MANNERS_PUBLISHED_RULES,
            Kind::Join => JOIN_RULES,
            Kind::Negation => NEGATION_RULES,
            _ => "",
        }
    }

    /// The whole program text of a generated kind at `size`, None for the others.
    fn generated_text(self, size: usize) -> Option<String> {
        match self {
            Kind::Discrim => Some(generated::discrim_text(size)),
            Kind::Join3 => Some(generated::join3_text(size)),
            Kind::Propagate => Some(generated::propagate_text(size)),
            Kind::Agent => Some(generated::agent_text(size)),
            Kind::KeyedOr => Some(generated::keyed_or_text(size)),
            Kind::Keyed2Or3 => Some(generated::keyed2_or3_text(size)),
            _ => None,
        }
    }

    /// Whether the program comes from Debian's `clips-common` examples, read where the
    /// package installs them (`debian.rs`), never from the repository.
    pub fn is_debian_example(self) -> bool {
        matches!(self, Kind::Sudoku | Kind::SudokuRunbench | Kind::Zebra)
    }

    /// Whether the program is a batch script with its own `(reset)`/`(run)` commands
    /// (not constructs that the drivers reset and run).
    pub fn is_batch_script(self) -> bool {
        matches!(self, Kind::Llsf | Kind::SudokuRunbench)
    }

    /// Whether the sizes of this kind scale one program (so growth across sizes means
    /// something), rather than naming different programs or puzzles.
    pub fn is_scaled(self) -> bool {
        !matches!(
            self,
            Kind::Llsf | Kind::Sudoku | Kind::SudokuRunbench | Kind::Zebra
        )
    }

    /// How the program's own result lines begin; everything else on stdout (statistics,
    /// banners) is engine chatter and not compared.
    pub fn result_prefixes(self) -> &'static [&'static str] {
        match self {
            Kind::Manners => &["seat "],
            // the trace of find_seating (`seat S NAME1 NAME2`) and the seating
            // (`NAME SEAT`: the generator names guests `n1`, `n2`, ...)
            Kind::MannersPublished => &["seat ", "n"],
            // output-simple.clp's `   row: R column: C value: V` lines
            Kind::Sudoku => &["   row: "],
            // output-none.clp prints nothing: the cells left possible, listed after
            // the run (`debian::RUNBENCH_RESULT`)
            Kind::SudokuRunbench => &["cell "],
            // the solution table's house rows, `  1   | norwegian ...`
            Kind::Zebra => &["  "],
            Kind::Join => &["reach2 "],
            Kind::Negation => &["started "],
            Kind::Llsf => &["GAME "],
            Kind::Discrim => &["discrim "],
            Kind::Join3 => &["join3 "],
            Kind::Propagate => &["propagate "],
            Kind::Agent => &["agent "],
            Kind::KeyedOr => &["keyed-or "],
            Kind::Keyed2Or3 => &["keyed2-or3 "],
        }
    }
}

/// One benchmark program: a workload kind at a size (guests for Manners, facts otherwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Workload {
    pub kind: Kind,
    pub size: usize,
}

impl Workload {
    pub fn name(&self) -> String {
        match self.kind {
            Kind::Sudoku => format!(
                "sudoku-{grid}x{grid}-p{puzzle}",
                grid = self.size / 100,
                puzzle = self.size % 100
            ),
            Kind::SudokuRunbench | Kind::Zebra => self.kind.label().to_string(),
            _ => format!("{}-{}", self.kind.label(), self.size),
        }
    }

    /// Checks the size is one the generator can make a solvable program for.
    pub fn validate(&self) -> Result<(), String> {
        match self.kind {
            Kind::Manners | Kind::MannersPublished
                if self.size < 2 || !self.size.is_multiple_of(2) =>
            {
                Err(format!(
                    "{}: Manners needs an even number of guests, at least 2",
                    self.name()
                ))
            }
            Kind::Llsf if self.size == 0 => Err(format!("{}: at least one game", self.name())),
            Kind::Llsf => Ok(()),
            Kind::Sudoku
                if !(2..=5).contains(&(self.size / 100)) || self.size.is_multiple_of(100) =>
            {
                Err(format!(
                    "sudoku puzzle {}: grids are 2x2 to 5x5, puzzles numbered from 1",
                    self.size
                ))
            }
            Kind::Sudoku => Ok(()),
            Kind::SudokuRunbench | Kind::Zebra if self.size != 1 => {
                Err(format!("{}: one program, size 1", self.kind.label()))
            }
            Kind::SudokuRunbench | Kind::Zebra => Ok(()),
            _ if self.size < 2 => Err(format!("{}: size must be at least 2", self.name())),
            _ => Ok(()),
        }
    }

    /// The generated facts, one fact per string, in assertion order.
    pub fn facts(&self) -> Vec<String> {
        match self.kind {
            Kind::Manners | Kind::MannersPublished => manners_facts(&manners_guests(self.size)),
            Kind::Join => join_facts(self.size),
            Kind::Negation => negation_facts(self.size),
            // Each game's setup is its own deffacts (see `llsf_games_batch`); generated
            // kinds write their facts with their rules.
            _ => Vec::new(),
        }
    }

    /// Constructs only (templates, rules, deffacts): what `(load* ...)` reads.
    pub fn constructs_text(&self) -> String {
        if let Some(text) = self.kind.generated_text(self.size) {
            return text;
        }
        let mut text = String::from(self.kind.rules());
        text.push('\n');
        text.push_str(&deffacts_text(&self.name(), &self.facts()));
        text
    }
}

/// Wraps facts into numbered `deffacts` constructs.
pub fn deffacts_text(prefix: &str, facts: &[String]) -> String {
    let mut text = String::new();
    for (index, chunk) in facts.chunks(FACTS_PER_DEFFACTS).enumerate() {
        // Writing into a String cannot fail.
        let _ = writeln!(text, "(deffacts {prefix}-data-{index}");
        for fact in chunk {
            let _ = writeln!(text, "   {fact}");
        }
        text.push_str(")\n");
    }
    text
}

/// A Manners guest: name, sex (`m` or `f`) and hobby numbers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Guest {
    pub name: String,
    pub sex: char,
    pub hobbies: Vec<u64>,
}

/// `count` guests, half of each sex in shuffled order, each with 2 or 3 hobbies of 3.
pub fn manners_guests(count: usize) -> Vec<Guest> {
    let mut rng = SplitMix64::new(count as u64);
    let mut sexes: Vec<char> = (0..count)
        .map(|i| if i % 2 == 0 { 'm' } else { 'f' })
        .collect();
    // Fisher-Yates shuffle.
    for i in (1..count).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        sexes.swap(i, j);
    }
    sexes
        .into_iter()
        .enumerate()
        .map(|(i, sex)| {
            let mut hobbies: Vec<u64> = (1..=MANNERS_HOBBIES).collect();
            let keep_all = rng.below(2) == 1;
            if !keep_all {
                let dropped = 1 + rng.below(MANNERS_HOBBIES);
                hobbies.retain(|&h| h != dropped);
            }
            Guest {
                name: format!("n{}", i + 1),
                sex,
                hobbies,
            }
        })
        .collect()
}

/// One `guest` fact per guest and hobby, then the seat count and the start facts.
pub fn manners_facts(guests: &[Guest]) -> Vec<String> {
    let mut facts: Vec<String> = guests
        .iter()
        .flat_map(|guest| {
            guest.hobbies.iter().map(move |hobby| {
                format!(
                    "(guest (name {}) (sex {}) (hobby h{hobby}))",
                    guest.name, guest.sex
                )
            })
        })
        .collect();
    facts.push(format!("(last_seat (seat {}))", guests.len()));
    facts.push("(count (c 1))".to_string());
    facts.push("(context (state start))".to_string());
    facts
}

/// About `total` facts: a third nodes in 4 groups, two thirds edges (two distinct edges out
/// of every node, to random nodes).
pub fn join_facts(total: usize) -> Vec<String> {
    let mut rng = SplitMix64::new(total as u64);
    let nodes = (total / 3).max(2) as u64;
    let mut facts = Vec::with_capacity(total);
    for id in 0..nodes {
        facts.push(format!("(node (id {id}) (group {}))", rng.below(4)));
    }
    for from in 0..nodes {
        let first = rng.below(nodes);
        // A different second target, so no duplicate edge fact.
        let second = (first + 1 + rng.below(nodes - 1)) % nodes;
        facts.push(format!("(edge (from {from}) (to {first}))"));
        facts.push(format!("(edge (from {from}) (to {second}))"));
    }
    facts
}

/// `total` facts: half jobs, half `pending` markers. Job i waits for an earlier job (or for
/// nothing, one time in eight) and belongs to one of total/32 crews.
pub fn negation_facts(total: usize) -> Vec<String> {
    let mut rng = SplitMix64::new(total as u64);
    let jobs = (total / 2).max(1) as u64;
    let crews = (jobs / 16).max(1);
    let mut facts = Vec::with_capacity(total);
    for id in 1..=jobs {
        let after = if id == 1 || rng.below(8) == 0 {
            0 // job 0 never exists, so this job waits for nothing
        } else {
            1 + rng.below(id - 1)
        };
        let crew = rng.below(crews);
        facts.push(format!("(job (id {id}) (after {after}) (crew {crew}))"));
    }
    for id in 1..=jobs {
        facts.push(format!("(pending (id {id}))"));
    }
    facts
}

/// The published Manners' seating as `seat S NAME` lines (for [`check_seating`]): its
/// `print_results` prints `NAME SEAT`; the `seat ...` lines of its trace are left out.
pub fn published_seating(result_lines: &[String]) -> Vec<String> {
    result_lines
        .iter()
        .filter(|line| !line.starts_with("seat "))
        .map(|line| match line.split_once(' ') {
            Some((name, seat)) => format!("seat {} {name}", seat.trim()),
            None => line.clone(),
        })
        .collect()
}

/// Checks printed `seat S NAME` lines form a valid Manners seating of `guests`: every seat
/// 1..=n taken once, every guest seated once, neighbours of opposite sex sharing a hobby.
pub fn check_seating(guests: &[Guest], result_lines: &[String]) -> Result<(), String> {
    let mut by_seat: Vec<Option<&Guest>> = vec![None; guests.len()];
    let mut seated = std::collections::HashSet::new();
    for line in result_lines {
        let mut words = line.split_whitespace();
        let (Some("seat"), Some(seat), Some(name), None) =
            (words.next(), words.next(), words.next(), words.next())
        else {
            return Err(format!("not a seating line: {line:?}"));
        };
        let seat: usize = seat
            .parse()
            .map_err(|_| format!("bad seat number in {line:?}"))?;
        let guest = guests
            .iter()
            .find(|g| g.name == name)
            .ok_or_else(|| format!("unknown guest in {line:?}"))?;
        let slot = seat
            .checked_sub(1)
            .and_then(|index| by_seat.get_mut(index))
            .ok_or_else(|| format!("seat out of range in {line:?}"))?;
        if slot.is_some() {
            return Err(format!("seat {seat} given twice"));
        }
        if !seated.insert(name.to_string()) {
            return Err(format!("guest {name} seated twice"));
        }
        *slot = Some(guest);
    }
    let order: Vec<&Guest> = by_seat
        .iter()
        .enumerate()
        .map(|(index, slot)| slot.ok_or_else(|| format!("seat {} is empty", index + 1)))
        .collect::<Result<_, _>>()?;
    for pair in order.windows(2) {
        let (left, right) = (pair[0], pair[1]);
        if left.sex == right.sex {
            return Err(format!(
                "{} and {} have the same sex",
                left.name, right.name
            ));
        }
        if !left.hobbies.iter().any(|h| right.hobbies.contains(h)) {
            return Err(format!("{} and {} share no hobby", left.name, right.name));
        }
    }
    Ok(())
}

/// The strategy the LLSF games row plays (the paper's).
pub const LLSF_STRATEGY: rules::Strategy = rules::Strategy::Paper;

/// CLIPS-only driver helpers (`report-game`), loaded by both engines' batch files.
pub const LLSF_REPORT: rules::RuleFile = rules::RuleFile {
    name: "clips/report.clp",
    text: include_str!("../../../rules/clips/report.clp"),
};

/// The files an LLSF batch loads, in order: the `distance` stub, the game files of
/// [`LLSF_STRATEGY`], the report helpers. Written as-is into the work folder so both
/// engines read identical `.clp` text (as `rules/clips/play.sh` does for CLIPS).
pub fn llsf_files() -> Vec<rules::RuleFile> {
    let mut files = vec![rules::CLIPS_STUBS];
    files.extend_from_slice(rules::game_files(LLSF_STRATEGY));
    files.push(LLSF_REPORT);
    files
}

/// The seeds of the games row: 0..games.
pub fn llsf_setups(games: usize) -> Vec<(u64, rules::setup::GameSetup)> {
    (0..games as u64)
        .map(|seed| (seed, rules::setup::GameSetup::for_seed(seed)))
        .collect()
}

/// The batch commands after loading: per game its setup deffacts, `(reset)`, `(run)`
/// (left out when `with_run` is false: the baseline) and a `GAME seed RESULT ...` line,
/// as `rules/examples/setup.rs --sweep` writes them for `rules/clips/sweep.sh`.
pub fn llsf_games_batch(games: usize, with_run: bool) -> Result<String, String> {
    let mut text = String::new();
    for (seed, setup) in llsf_setups(games) {
        setup
            .write_clips(&mut text)
            .map_err(|e| format!("writing the setup of seed {seed}: {e}"))?;
        text.push_str("(reset)\n");
        if with_run {
            text.push_str("(run)\n");
        }
        let _ = writeln!(text, "(printout t \"GAME {seed} \")\n(report-game)");
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn manners_guests_are_balanced_and_any_two_share_a_hobby() {
        for count in [16, 32, 64, 128] {
            let guests = manners_guests(count);
            assert_eq!(guests.len(), count);
            let men = guests.iter().filter(|g| g.sex == 'm').count();
            assert_eq!(men * 2, count);
            for a in &guests {
                assert!((2..=3).contains(&a.hobbies.len()));
                for b in &guests {
                    assert!(a.hobbies.iter().any(|h| b.hobbies.contains(h)));
                }
            }
        }
    }

    #[test]
    fn generators_are_deterministic_and_sized() {
        assert_eq!(manners_guests(32), manners_guests(32));
        assert_eq!(join_facts(999), join_facts(999));
        assert_eq!(join_facts(999).len(), 999);
        assert_eq!(negation_facts(1000).len(), 1000);
        let facts = manners_facts(&manners_guests(16));
        assert_eq!(
            facts.last().map(String::as_str),
            Some("(context (state start))")
        );
        assert!(facts.contains(&"(last_seat (seat 16))".to_string()));
    }

    #[test]
    fn join_edges_are_distinct_per_node() {
        let facts = join_facts(3000);
        let unique: std::collections::HashSet<&String> = facts.iter().collect();
        assert_eq!(unique.len(), facts.len());
    }

    #[test]
    fn negation_jobs_wait_only_for_earlier_jobs() {
        for fact in negation_facts(400).iter().filter(|f| f.starts_with("(job")) {
            let numbers: Vec<u64> = fact
                .split(|c: char| !c.is_ascii_digit())
                .filter_map(|w| w.parse().ok())
                .collect();
            assert!(numbers[1] < numbers[0], "{fact}");
        }
    }

    #[test]
    fn deffacts_chunks_hold_every_fact_once() {
        let facts: Vec<String> = (0..1201).map(|i| format!("(f {i})")).collect();
        let text = deffacts_text("w", &facts);
        assert_eq!(text.matches("(deffacts ").count(), 3);
        assert_eq!(text.matches("(f ").count(), 1201);
        assert_eq!(text.matches('(').count(), text.matches(')').count());
    }

    fn seating_lines(guests: &[Guest], order: &[usize]) -> Vec<String> {
        order
            .iter()
            .enumerate()
            .map(|(seat, &g)| format!("seat {} {}", seat + 1, guests[g].name))
            .collect()
    }

    #[test]
    fn seating_check_accepts_alternating_and_rejects_bad_tables() {
        let guests = manners_guests(4);
        let men: Vec<usize> = (0..4).filter(|&i| guests[i].sex == 'm').collect();
        let women: Vec<usize> = (0..4).filter(|&i| guests[i].sex == 'f').collect();
        let good = [men[0], women[0], men[1], women[1]];
        assert_eq!(
            check_seating(&guests, &seating_lines(&guests, &good)),
            Ok(())
        );
        let same_sex = [men[0], men[1], women[0], women[1]];
        assert!(check_seating(&guests, &seating_lines(&guests, &same_sex)).is_err());
        let missing = seating_lines(&guests, &good[..3]);
        assert!(check_seating(&guests, &missing).is_err());
        let mut twice = seating_lines(&guests, &good);
        twice[3] = format!("seat 4 {}", guests[men[0]].name);
        assert!(check_seating(&guests, &twice).is_err());
    }

    #[test]
    fn rule_files_contain_the_classic_manners_rules() {
        for rule in [
            "assign_first_seat",
            "find_seating",
            "make_path",
            "path_done",
            "are_we_done",
            "continue",
            "print_results",
            "all_done",
        ] {
            assert!(
                MANNERS_RULES.contains(&format!("(defrule {rule}")),
                "{rule}"
            );
        }
    }
}
