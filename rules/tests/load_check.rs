//! The build-time check of the rule files (`load_check.rs`, run by `build.rs`): the
//! real load orders pass, and a broken file is rejected with its name, line, column
//! and what the parser expected.

#[path = "../load_check.rs"]
mod load_check;

use load_check::{check_load, check_load_as, check_load_with, BadRuleFile, PpForms};
use rules::{agent_files, game_files, RuleFile, Strategy, COLLECT, DRIVER_FILES, TEAM, TEAM_AGENT};

fn owned(files: &[RuleFile]) -> Vec<(String, String)> {
    files
        .iter()
        .map(|f| (format!("rules/{}", f.name), f.text.to_string()))
        .collect()
}

fn pair(name: &str, text: &str) -> (String, String) {
    (name.to_string(), text.to_string())
}

#[test]
fn every_load_order_of_the_rule_base_loads() {
    for strategy in Strategy::ALL {
        assert_eq!(check_load(&owned(game_files(strategy))), Ok(()));
        let mut driver = owned(agent_files(strategy));
        driver.extend(owned(&DRIVER_FILES));
        assert_eq!(check_load(&driver), Ok(()));
        // a team member on its body, loaded as `run` loads it (no pretty-print forms)
        let mut member = owned(agent_files(strategy));
        member.extend(owned(&[COLLECT, TEAM, TEAM_AGENT]));
        assert_eq!(check_load_as(&member, &[], PpForms::Drop), Ok(()));
    }
}

#[test]
fn a_broken_file_is_named_with_its_position() {
    let files = [
        pair("rules/a.clp", "(deftemplate robot (slot name))\n"),
        pair(
            "rules/b.clp",
            "; a rule about robots\n(defrule r\n  (robot (nmae ?n))\n  =>)\n",
        ),
    ];
    let bad = check_load(&files).unwrap_err();
    assert_eq!(
        bad,
        BadRuleFile {
            file: "rules/b.clp".to_string(),
            line: 3,
            col: 11,
            message: "expected a slot of the template, found `nmae`".to_string(),
        }
    );
    assert_eq!(
        bad.to_string(),
        "rules/b.clp:3:11: expected a slot of the template, found `nmae`"
    );
}

#[test]
fn a_file_using_what_an_earlier_file_should_define_is_rejected() {
    // the order matters: b.clp's rule needs a.clp's template (a pattern with slots
    // needs a deftemplate)
    let a = pair("rules/a.clp", "(deftemplate robot (slot name))\n");
    let b = pair("rules/b.clp", "(defrule r (robot (name ?n)) =>)\n");
    assert_eq!(check_load(&[a.clone(), b.clone()]), Ok(()));
    let bad = check_load(&[b, a]).unwrap_err();
    assert_eq!(
        (bad.file.as_str(), bad.line, bad.col),
        ("rules/b.clp", 1, 13)
    );
}

#[test]
fn a_real_rule_file_cut_short_is_rejected_at_its_end() {
    let mut files = owned(game_files(Strategy::Paper));
    let (name, text) = files
        .iter_mut()
        .find(|(n, _)| n == "rules/production.clp")
        .expect("the paper game loads production.clp");
    // cut inside the last construct: the input ends with a construct still open
    let cut = text.rfind("=>").expect("production.clp has rules");
    text.truncate(cut + 2);
    text.push('\n');
    let lines = text.lines().count() as u32;
    let name = name.clone();
    let bad = check_load(&files).unwrap_err();
    assert_eq!(bad.file, name);
    assert_eq!((bad.line, bad.col), (lines + 1, 1), "{bad}");
    assert!(bad.message.contains("expected ')'"), "{bad}");
}

#[test]
fn a_semantic_error_in_a_real_file_is_rejected_at_the_offending_token() {
    let mut files = owned(game_files(Strategy::Travel));
    let (_, text) = files
        .iter_mut()
        .find(|(n, _)| n == "rules/utils.clp")
        .expect("every game loads utils.clp");
    // a call of an unknown function, appended as a new construct on its own line
    text.push_str("(deffunction broken (?x)\n  (no-such-function ?x))\n");
    let line = text.lines().count() as u32;
    let bad = check_load(&files).unwrap_err();
    assert_eq!(
        (bad.file.as_str(), bad.line, bad.col),
        ("rules/utils.clp", line, 4)
    );
    assert!(bad.message.contains("known function"), "{bad}");
}

#[test]
fn host_functions_need_their_stand_ins_with_the_right_arity() {
    let file = [pair(
        "rules/skills.clp",
        "(defrule go\n  (robot (name ?n))\n  =>\n  (skill-call goto ?n))\n",
    )];
    let template = pair("rules/a.clp", "(deftemplate robot (slot name))\n");
    let files = [template.clone(), file[0].clone()];
    let unknown = check_load(&files).unwrap_err();
    assert_eq!((unknown.line, unknown.col), (4, 4), "{unknown}");
    assert!(unknown.message.contains("known function"), "{unknown}");
    assert_eq!(check_load_with(&files, &[("skill-call", 1, None)]), Ok(()));
    let arity = check_load_with(&files, &[("skill-call", 3, Some(3))]).unwrap_err();
    assert_eq!((arity.line, arity.col), (4, 4), "{arity}");
    assert!(arity.message.contains("number of arguments"), "{arity}");
}
