//! Parse-error suite: every malformed program in `tests/clips-errors/*.clp` runs in our CLI
//! (`robotino-agent clips -f FILE`), which must print, after CLIPS's own error text, a line
//!
//! ```text
//! --> FILE:LINE:COL: expected WHAT
//! ```
//!
//! (1-based line and column). Each program states what it expects in its first line:
//!
//! ```text
//! ; expect: 3:14 expected ')'
//! ; keeps: f-1     (good (a 5))
//! ```
//!
//! The position must match exactly and WHAT must contain the text after `expected`
//! (case-insensitive). Each `; keeps:` line names an output line that must appear too: the
//! program defined a good construct before the bad one and uses it afterwards, so the engine
//! must have kept it. Each `; lacks:` line names an output line that must NOT appear: the
//! bad construct must leave nothing of itself behind (e.g. no rule in `(list-defrules)`). What real CLIPS prints for each program is recorded for humans in
//! `NNN-*.clips-out` (`tests/clips-errors/regen.sh`); it is not compared.

mod clips_runner;
mod known_divergences;

use std::path::{Path, PathBuf};

fn programs_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/clips-errors");
    dir.canonicalize().unwrap_or(dir)
}

/// What one malformed program expects of our CLI.
#[derive(Debug, PartialEq)]
struct Expectation {
    line: u32,
    column: u32,
    /// Text that must occur in the `expected ...` part of the position line.
    what: String,
    /// Output lines proving that constructs defined before the error were kept.
    keeps: Vec<String>,
    /// Output lines that must not appear: the bad construct left nothing of itself behind.
    lacks: Vec<String>,
}

/// Reads the `; expect: L:C expected WHAT` header and any `; keeps: LINE` and
/// `; lacks: LINE` lines that follow it.
fn parse_expectation(source: &str) -> Result<Expectation, String> {
    let mut lines = source.lines();
    let first = lines.next().unwrap_or_default();
    let spec = first.strip_prefix("; expect: ").ok_or_else(|| {
        format!("first line must be `; expect: L:C expected WHAT`, got {first:?}")
    })?;
    let (position, rest) = spec
        .split_once(' ')
        .ok_or_else(|| format!("no text after the position in {first:?}"))?;
    let (line, column) = position
        .split_once(':')
        .ok_or_else(|| format!("position must be LINE:COL in {first:?}"))?;
    let line: u32 = line
        .parse()
        .map_err(|e| format!("bad line number in {first:?}: {e}"))?;
    let column: u32 = column
        .parse()
        .map_err(|e| format!("bad column number in {first:?}: {e}"))?;
    let what = rest
        .strip_prefix("expected ")
        .ok_or_else(|| format!("text must start with `expected ` in {first:?}"))?
        .trim()
        .to_string();
    if line == 0 || column == 0 || what.is_empty() {
        return Err(format!(
            "positions are 1-based and WHAT is required in {first:?}"
        ));
    }
    let mut keeps = Vec::new();
    let mut lacks = Vec::new();
    for header in lines.take_while(|l| l.starts_with("; ")) {
        if let Some(kept) = header.strip_prefix("; keeps: ") {
            keeps.push(kept.to_string());
        } else if let Some(lacking) = header.strip_prefix("; lacks: ") {
            lacks.push(lacking.to_string());
        }
    }
    Ok(Expectation {
        line,
        column,
        what,
        keeps,
        lacks,
    })
}

/// A `--> FILE:LINE:COL: expected WHAT` line taken apart.
#[derive(Debug, PartialEq)]
struct PositionLine<'a> {
    file: &'a str,
    line: u32,
    column: u32,
    what: &'a str,
}

fn parse_position_line(text: &str) -> Option<PositionLine<'_>> {
    let rest = text.strip_prefix("--> ")?;
    let (location, what) = rest.split_once(": expected ")?;
    // The file name may itself contain ':', so take LINE and COL from the right.
    let mut parts = location.rsplitn(3, ':');
    let column = parts.next()?.parse().ok()?;
    let line = parts.next()?.parse().ok()?;
    let file = parts.next()?;
    Some(PositionLine {
        file,
        line,
        column,
        what,
    })
}

fn run_our_cli(file: &Path, name: &str) -> Result<String, String> {
    let cwd = clips_runner::scratch_dir(name, "parse-errors")?;
    let run = clips_runner::run_with_timeout(
        &clips_runner::our_engine(),
        &[Path::new("clips"), Path::new("-f"), file],
        &cwd,
    )?;
    let _ = std::fs::remove_dir_all(&cwd);
    // position lines may go to stdout or stderr: both are searched
    let mut output = run.stdout;
    if !output.ends_with('\n') && !output.is_empty() {
        output.push('\n');
    }
    output.push_str(&run.stderr);
    if run.timed_out {
        return Err(format!(
            "our CLI did not finish {name} within {:?}; output so far:\n{output}",
            clips_runner::RUN_TIMEOUT
        ));
    }
    Ok(output)
}

/// Checks one malformed program; the error names what is missing from the output.
fn check_program(name: &str) -> Result<(), String> {
    let file = programs_dir().join(format!("{name}.clp"));
    let source = std::fs::read_to_string(&file)
        .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let expect = parse_expectation(&source).map_err(|e| format!("{name}.clp: {e}"))?;
    let output = run_our_cli(&file, name)?;
    let file_name = format!("{name}.clp");
    let positions: Vec<PositionLine<'_>> = output
        .lines()
        .filter_map(parse_position_line)
        .filter(|p| p.file.ends_with(&file_name))
        .collect();
    let wanted = expect.what.to_lowercase();
    let position_ok = positions.iter().any(|p| {
        p.line == expect.line
            && p.column == expect.column
            && p.what.to_lowercase().contains(&wanted)
    });
    let missing_keeps = missing_lines(&output, &expect.keeps);
    let leftovers = present_lines(&output, &expect.lacks);
    if position_ok && missing_keeps.is_empty() && leftovers.is_empty() {
        return Ok(());
    }
    let mut report = format!("{name}: ");
    if !position_ok {
        report.push_str(&format!(
            "expected a line `--> .../{file_name}:{}:{}: expected ...{}...`; ",
            expect.line, expect.column, expect.what
        ));
        if positions.is_empty() {
            report.push_str("found no position line for this file");
        } else {
            let found: Vec<String> = positions
                .iter()
                .map(|p| format!("{}:{}: expected {}", p.line, p.column, p.what))
                .collect();
            report.push_str(&format!("found {found:?}"));
        }
    }
    if !missing_keeps.is_empty() {
        report.push_str(&format!(
            "\n  constructs before the error were not kept: missing output lines {missing_keeps:?}"
        ));
    }
    if !leftovers.is_empty() {
        report.push_str(&format!(
            "\n  the bad construct left something behind: unexpected output lines {leftovers:?}"
        ));
    }
    report.push_str(&format!(
        "\n  our output:\n    {}",
        output.replace('\n', "\n    ")
    ));
    Err(report)
}

/// Expected lines that do not occur in `output` (trailing blanks ignored).
fn missing_lines<'a>(output: &str, wanted: &'a [String]) -> Vec<&'a String> {
    wanted
        .iter()
        .filter(|w| !output.lines().any(|l| l.trim_end() == w.as_str()))
        .collect()
}

/// Forbidden lines that do occur in `output`.
fn present_lines<'a>(output: &str, forbidden: &'a [String]) -> Vec<&'a String> {
    forbidden
        .iter()
        .filter(|f| output.lines().any(|l| l.trim_end() == f.as_str()))
        .collect()
}

fn programs_on_disk() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(programs_dir())
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .filter_map(|e| {
                    let name = e.file_name().to_string_lossy().into_owned();
                    name.strip_suffix(".clp").map(str::to_string)
                })
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// Runs every malformed program and prints one line each plus "N passed, M failed".
#[test]
fn all_malformed_programs_summary() {
    let names = programs_on_disk();
    assert!(
        names.len() >= 30,
        "expected at least 30 malformed programs in {}, found {}",
        programs_dir().display(),
        names.len()
    );
    known_divergences::summarize(&programs_dir(), &names, "malformed programs", check_program);
}

/// Every program's header is well formed and its position lies inside the file (or just
/// past its end, for errors at end of input).
#[test]
fn every_program_states_a_valid_expectation() {
    for name in programs_on_disk() {
        let file = programs_dir().join(format!("{name}.clp"));
        let source = std::fs::read_to_string(&file).unwrap_or_default();
        let expect = match parse_expectation(&source) {
            Ok(e) => e,
            Err(e) => panic!("{name}.clp: {e}"),
        };
        let lines: Vec<&str> = source.lines().collect();
        let line_count = u32::try_from(lines.len()).unwrap_or(u32::MAX);
        assert!(
            expect.line <= line_count + 1,
            "{name}.clp: line {} is past the end of the file",
            expect.line
        );
        if let Some(text) = lines.get(expect.line as usize - 1) {
            // Positions name the first character of a token: a parenthesis, or a non-blank
            // right after a delimiter (or at the start of the line).
            let chars: Vec<char> = text.chars().collect();
            let at = expect.column as usize - 1;
            let here = chars.get(at).copied();
            let before = at.checked_sub(1).and_then(|i| chars.get(i)).copied();
            assert!(
                here.is_some_and(|c| !c.is_whitespace())
                    && (here.is_some_and(|c| "()".contains(c))
                        || before.is_none_or(|c| c.is_whitespace() || "()&|~:=\"".contains(c))),
                "{name}.clp: {}:{} is not the start of a token in {text:?}",
                expect.line,
                expect.column
            );
        }
    }
}

/// The `keeps`/`lacks` claims hold for real CLIPS too (its transcripts `*.clips-out`, made
/// by `tests/clips-errors/regen.sh`): the suite asks nothing of us that CLIPS does not do.
#[test]
fn keeps_and_lacks_agree_with_clips_transcripts() {
    for name in programs_on_disk() {
        let source =
            std::fs::read_to_string(programs_dir().join(format!("{name}.clp"))).unwrap_or_default();
        let expect = match parse_expectation(&source) {
            Ok(e) => e,
            Err(e) => panic!("{name}.clp: {e}"),
        };
        if expect.keeps.is_empty() && expect.lacks.is_empty() {
            continue;
        }
        let transcript_file = programs_dir().join(format!("{name}.clips-out"));
        let transcript = match std::fs::read_to_string(&transcript_file) {
            Ok(t) => t,
            Err(e) => panic!(
                "{} unreadable ({e}); run tests/clips-errors/regen.sh",
                transcript_file.display()
            ),
        };
        let missing = missing_lines(&transcript, &expect.keeps);
        let present = present_lines(&transcript, &expect.lacks);
        assert!(
            missing.is_empty() && present.is_empty(),
            "{name}: CLIPS itself does not print {missing:?} or does print {present:?}"
        );
    }
}

/// Run-time errors (`tests/clips-errors/runtime/*.clp`): each program's `; prints:` lines
/// must appear in its output in that order (the error, the deffunction frames, the
/// rule), and the program must run to its end: no crash, whatever the recursion.
#[test]
fn runtime_errors_name_the_limit_function_and_rule() {
    let dir = programs_dir().join("runtime");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "clp"))
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    assert!(
        names.len() >= 2,
        "no run-time programs in {}",
        dir.display()
    );
    for file in names {
        let name = file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let source = std::fs::read_to_string(&file).unwrap_or_default();
        let wanted: Vec<&str> = source
            .lines()
            .filter_map(|l| l.strip_prefix("; prints: "))
            .collect();
        assert!(!wanted.is_empty(), "{name}: no `; prints:` lines");
        let output = match run_our_cli(&file, &name) {
            Ok(o) => o,
            Err(e) => panic!("{name}: {e}"),
        };
        let mut lines = output.lines().map(str::trim_end);
        for w in &wanted {
            // a line ending in `...` gives the start only (the host's depth limit
            // depends on the build's stack frames)
            let matches = |l: &str| match w.strip_suffix("...") {
                Some(start) => l.starts_with(start),
                None => l == *w,
            };
            assert!(
                lines.any(matches),
                "{name}: missing (or out of order) {w:?} in:\n{output}"
            );
        }
        assert!(
            output.contains("CLIPS> (exit)"),
            "{name}: did not run to its end:\n{output}"
        );
    }
}

#[test]
fn expectation_header_parses() {
    let source =
        "; expect: 3:14 expected ')'\n; keeps: f-1     (a 1)\n; lacks: bad\n(assert (a 1))\n";
    assert_eq!(
        parse_expectation(source),
        Ok(Expectation {
            line: 3,
            column: 14,
            what: "')'".to_string(),
            keeps: vec!["f-1     (a 1)".to_string()],
            lacks: vec!["bad".to_string()],
        })
    );
    assert!(parse_expectation("(assert (a 1))\n").is_err());
    assert!(parse_expectation("; expect: 0:1 expected x\n").is_err());
    assert!(parse_expectation("; expect: 2:1 wanted x\n").is_err());
}

#[test]
fn position_line_parses_with_colons_in_path() {
    assert_eq!(
        parse_position_line("--> C:/tmp/x.clp:3:14: expected ')'"),
        Some(PositionLine {
            file: "C:/tmp/x.clp",
            line: 3,
            column: 14,
            what: "')'",
        })
    );
    assert_eq!(parse_position_line("[PRNTUTIL2] Syntax Error"), None);
    assert_eq!(parse_position_line("--> x.clp:3: expected y"), None);
}

macro_rules! malformed_programs {
    ($($test:ident => $name:literal,)*) => {
        $(
            #[test]
            fn $test() {
                if let Err(report) = known_divergences::judge(&programs_dir(), $name, check_program($name)) {
                    panic!("{report}");
                }
            }
        )*

        /// Every program on disk has its own test above, and every test has its program.
        #[test]
        fn every_malformed_program_has_a_test() {
            let listed: Vec<String> = [$($name),*].iter().map(|s| s.to_string()).collect();
            let on_disk = programs_on_disk();
            let missing: Vec<&String> = on_disk.iter().filter(|n| !listed.contains(n)).collect();
            let stale: Vec<&String> = listed.iter().filter(|n| !on_disk.contains(n)).collect();
            assert!(
                missing.is_empty() && stale.is_empty(),
                "malformed_programs! list out of date: add {missing:?}, remove {stale:?}"
            );
        }
    };
}

malformed_programs! {
    e001_unclosed_defrule_eof => "001-unclosed-defrule-eof",
    e002_unclosed_assert_eof => "002-unclosed-assert-eof",
    e003_unterminated_string => "003-unterminated-string",
    e004_defrule_missing_name => "004-defrule-missing-name",
    e005_deftemplate_missing_name => "005-deftemplate-missing-name",
    e006_deffacts_missing_name => "006-deffacts-missing-name",
    e007_deffunction_missing_params => "007-deffunction-missing-params",
    e008_deffunction_param_not_variable => "008-deffunction-param-not-variable",
    e009_slot_missing_name => "009-slot-missing-name",
    e010_slot_bad_keyword => "010-slot-bad-keyword",
    e011_slot_bad_attribute => "011-slot-bad-attribute",
    e012_slot_type_unknown => "012-slot-type-unknown",
    e013_defrule_missing_arrow => "013-defrule-missing-arrow",
    e014_constraint_dangling_and => "014-constraint-dangling-and",
    e015_constraint_dangling_not => "015-constraint-dangling-not",
    e016_constraint_bad_connective => "016-constraint-bad-connective",
    e017_salience_not_integer => "017-salience-not-integer",
    e018_declare_unknown_property => "018-declare-unknown-property",
    e019_deffacts_bare_symbol => "019-deffacts-bare-symbol",
    e020_defglobal_missing_equals => "020-defglobal-missing-equals",
    e021_defglobal_bad_name => "021-defglobal-bad-name",
    e022_if_missing_then => "022-if-missing-then",
    e023_not_two_patterns => "023-not-two-patterns",
    e024_test_without_expression => "024-test-without-expression",
    e025_unknown_slot_in_pattern => "025-unknown-slot-in-pattern",
    e026_unknown_slot_in_assert => "026-unknown-slot-in-assert",
    e027_unknown_slot_in_modify => "027-unknown-slot-in-modify",
    e028_unknown_template_pattern => "028-unknown-template-pattern",
    e029_wrong_type_in_slot => "029-wrong-type-in-slot",
    e030_allowed_values_violation => "030-allowed-values-violation",
    e031_allowed_values_default_violation => "031-allowed-values-default-violation",
    e032_allowed_values_in_rhs_modify => "032-allowed-values-in-rhs-modify",
    e033_unbound_variable_rhs => "033-unbound-variable-rhs",
    e034_unbound_variable_from_not => "034-unbound-variable-from-not",
    e035_unbound_variable_in_test => "035-unbound-variable-in-test",
    e036_wrong_arity_builtin => "036-wrong-arity-builtin",
    e037_wrong_arity_deffunction => "037-wrong-arity-deffunction",
    e038_assert_without_fact => "038-assert-without-fact",
    e039_unknown_function_rhs => "039-unknown-function-rhs",
    e040_unknown_function_command => "040-unknown-function-command",
    e041_unknown_construct => "041-unknown-construct",
    e042_wrong_argument_type_literal => "042-wrong-argument-type-literal",
    e043_duplicate_deftemplate_in_use => "043-duplicate-deftemplate-in-use",
    e044_duplicate_slot_in_deftemplate => "044-duplicate-slot-in-deftemplate",
    e045_slot_given_twice => "045-slot-given-twice",
    e046_single_slot_two_values => "046-single-slot-two-values",
    e047_rest_parameter_not_last => "047-rest-parameter-not-last",
    e048_duplicate_parameter => "048-duplicate-parameter",
    e049_salience_out_of_range => "049-salience-out-of-range",
    e050_fact_address_on_not => "050-fact-address-on-not",
    e051_missing_required_slot => "051-missing-required-slot",
    e052_bind_non_variable => "052-bind-non-variable",
    e053_switch_case_missing_then => "053-switch-case-missing-then",
    e054_single_slot_multi_default => "054-single-slot-multi-default",
    e055_duplicate_salience => "055-duplicate-salience",
    e056_retract_without_arguments => "056-retract-without-arguments",
    e057_empty_or => "057-empty-or",
    e058_deffacts_variable => "058-deffacts-variable",
    e059_unbound_variable_rhs_assert => "059-unbound-variable-rhs-assert",
    e060_unknown_global_rhs => "060-unknown-global-rhs",
    e061_bare_question_mark_rhs => "061-bare-question-mark-rhs",
    e062_single_and_multifield_variable => "062-single-and-multifield-variable",
    e063_default_wrong_type => "063-default-wrong-type",
    e064_empty_salience => "064-empty-salience",
    e065_bind_unknown_global => "065-bind-unknown-global",
    e066_pattern_literal_wrong_type => "066-pattern-literal-wrong-type",
    e067_pattern_literal_not_allowed => "067-pattern-literal-not-allowed",
    e068_redefine_deftemplate_used_by_deffunction => "068-redefine-deftemplate-used-by-deffunction",
    e069_modify_single_slot_two_values => "069-modify-single-slot-two-values",
    e070_modify_slot_given_twice => "070-modify-slot-given-twice",
    e071_rhs_assert_wrong_type => "071-rhs-assert-wrong-type",
    e072_deffunction_named_like_builtin => "072-deffunction-named-like-builtin",
    e073_default_dynamic_wrong_type => "073-default-dynamic-wrong-type",
    e074_deffunction_literal_argument_type => "074-deffunction-literal-argument-type",
    e075_slot_attribute_twice => "075-slot-attribute-twice",
    e076_type_conflicts_with_allowed_values => "076-type-conflicts-with-allowed-values",
    e077_allowed_symbols_with_a_number => "077-allowed-symbols-with-a-number",
    e078_allowed_values_combined => "078-allowed-values-combined",
    e079_modify_fact_index_in_rule => "079-modify-fact-index-in-rule",
    e080_declare_after_a_ce => "080-declare-after-a-ce",
    e081_logical_ce_not_first => "081-logical-ce-not-first",
    e082_defmodule_redefined => "082-defmodule-redefined",
    e083_module_specifier_unknown => "083-module-specifier-unknown",
    e084_import_not_exported => "084-import-not-exported",
    e085_watch_untraced_item_refused => "085-watch-untraced-item-refused",
    e086_pattern_of_6_multifield_variables => "086-pattern-of-6-multifield-variables",
    e087_template_of_256_slots => "087-template-of-256-slots",
    e088_rule_of_65_patterns => "088-rule-of-65-patterns",
    e089_deffunction_of_256_locals => "089-deffunction-of-256-locals",
    e095_undefined_global_before_missing_function => "095-undefined-global-before-missing-function",
    e806_defmethod_refused => "806-defmethod-refused",
    e807_defclass_refused => "807-defclass-refused",
}
