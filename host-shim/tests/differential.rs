//! Differential suite: every program in `tests/clips/*.clp` runs in real CLIPS 6.30
//! (`clips -f`) and in our CLI (`robotino-agent clips -f`); their stdout must be identical
//! line by line, CLIPS's banner line aside (and the `--> FILE:LINE:COL: expected ...` lines
//! our CLI adds after parse errors, which `parse_errors.rs` checks).
//!
//! Each program has its own `#[test]` (so `cargo test --test differential 031` runs one),
//! and `all_programs_summary` runs the whole suite and prints "N passed, M failed".
//! Real CLIPS is also checked against the golden transcript `tests/clips/NNN-*.out`
//! (made by `tests/clips/regen.sh`), which catches a different CLIPS version on the machine.
//!
//! Real CLIPS is required: without a `clips` command on PATH the tests fail (CI installs the
//! Debian package `clips`); they never skip silently.

mod clips_runner;
mod known_divergences;

use clips_runner::{
    clips_command, first_difference, our_engine, transcript, without_banner, without_position_lines,
};
use std::path::{Path, PathBuf};

fn programs_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/clips");
    dir.canonicalize().unwrap_or(dir)
}

/// Checks one program: CLIPS against its golden transcript, then our CLI against CLIPS.
fn check_program(name: &str) -> Result<(), String> {
    let clips = clips_command()?;
    let ours = our_engine();
    let file = programs_dir().join(format!("{name}.clp"));
    let golden_file = programs_dir().join(format!("{name}.out"));
    if !file.is_file() {
        return Err(format!("program {} does not exist", file.display()));
    }
    let clips_run = transcript("clips", &clips, name, &file)?;
    let clips_lines = clips_run.lines;
    let golden = std::fs::read_to_string(&golden_file).map_err(|e| {
        format!(
            "golden transcript {} unreadable ({e}); run tests/clips/regen.sh",
            golden_file.display()
        )
    })?;
    // The golden transcripts keep CLIPS's banner: a different banner means a different
    // CLIPS build, which explains any other difference.
    let golden_banner = golden.lines().next().unwrap_or_default();
    let clips_banner = clips_run.raw.lines().next().unwrap_or_default();
    if golden_banner != clips_banner {
        return Err(format!(
            "{name}: the installed CLIPS prints banner {clips_banner:?} but the golden \
             transcripts were made with {golden_banner:?}; the oracle is CLIPS 6.30 (Debian \
             package `clips`)"
        ));
    }
    if let Some(diff) = first_difference(
        "golden .out",
        &without_banner(&golden),
        "clips now",
        &clips_lines,
    ) {
        return Err(format!(
            "{name}: real CLIPS no longer matches {} (different CLIPS version, or the program \
             changed without tests/clips/regen.sh):\n{diff}",
            golden_file.display()
        ));
    }
    let our_run = transcript("robotino-agent", &ours, name, &file)?;
    let our_lines = without_position_lines(&our_run.lines);
    match first_difference("clips", &clips_lines, "ours", &our_lines) {
        None => Ok(()),
        Some(diff) => Err(format!(
            "{name}: our CLI differs from CLIPS:\n{diff}{}",
            our_run.note
        )),
    }
}

fn assert_program(name: &str) {
    if let Err(report) = known_divergences::judge(&programs_dir(), name, check_program(name)) {
        panic!("{report}");
    }
}

/// Names (without `.clp`) of every program in `tests/clips`, sorted.
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

macro_rules! differential_programs {
    ($($test:ident => $name:literal,)*) => {
        $(
            #[test]
            fn $test() {
                assert_program($name);
            }
        )*

        /// Every program on disk has its own test above, and every test has its program.
        #[test]
        fn every_program_has_a_test() {
            let listed: Vec<String> = [$($name),*].iter().map(|s| s.to_string()).collect();
            let on_disk = programs_on_disk();
            let missing: Vec<&String> = on_disk.iter().filter(|n| !listed.contains(n)).collect();
            let stale: Vec<&String> = listed.iter().filter(|n| !on_disk.contains(n)).collect();
            assert!(
                missing.is_empty() && stale.is_empty(),
                "differential_programs! list out of date: add {missing:?}, remove {stale:?}"
            );
        }
    };
}

/// Runs every program on disk and prints one line per program plus "N passed, M failed".
#[test]
fn all_programs_summary() {
    let names = programs_on_disk();
    assert!(
        names.len() >= 60,
        "expected at least 60 differential programs in {}, found {}",
        programs_dir().display(),
        names.len()
    );
    known_divergences::summarize(&programs_dir(), &names, "programs", check_program);
}

#[test]
fn banner_is_the_only_line_ignored() {
    let clips = "         CLIPS (6.30 3/17/15)\nCLIPS> (exit)\n";
    assert_eq!(without_banner(clips), vec!["CLIPS> (exit)".to_string()]);
    assert_eq!(
        without_banner("CLIPS> (exit)\n"),
        vec!["CLIPS> (exit)".to_string()]
    );
    // Anything else before the first prompt is compared.
    assert_eq!(
        without_banner("banner\nstray\nCLIPS> (exit)\n"),
        vec!["stray".to_string(), "CLIPS> (exit)".to_string()]
    );
}

#[test]
fn only_position_lines_are_dropped_from_our_output() {
    let ours: Vec<String> = [
        "CLIPS> (foo)",
        "[EXPRNPSR3] Missing function declaration for foo.",
        "--> /x/prog.clp:3:2: expected a defined function",
        "--> not a position line",
        "CLIPS> (exit)",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let kept = without_position_lines(&ours);
    assert_eq!(kept.len(), 4, "{kept:?}");
    assert!(kept.iter().all(|l| !l.contains("expected a defined")));
}

#[test]
fn difference_report_names_first_differing_line() {
    let a: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
    let b: Vec<String> = ["x", "Y", "z"].iter().map(|s| s.to_string()).collect();
    let report = first_difference("clips", &a, "ours", &b).unwrap_or_default();
    assert!(report.contains("transcript line 2"), "{report}");
    assert!(report.contains("- clips: \"y\""), "{report}");
    assert!(report.contains("+ ours: \"Y\""), "{report}");
    assert!(first_difference("clips", &a, "ours", &a).is_none());
    let short: Vec<String> = vec!["x".to_string()];
    let report = first_difference("clips", &a, "ours", &short).unwrap_or_default();
    assert!(report.contains("<end of output>"), "{report}");
}

differential_programs! {
    p001_assert_basic => "001-assert-basic",
    p002_retract_basic => "002-retract-basic",
    p003_reset_numbering => "003-reset-numbering",
    p004_deffacts_multiple => "004-deffacts-multiple",
    p005_template_defaults => "005-template-defaults",
    p006_allowed_values_assert => "006-allowed-values-assert",
    p007_modify_basic => "007-modify-basic",
    p008_duplicate => "008-duplicate",
    p009_facts_listing_range => "009-facts-listing-range",
    p010_rhs_assert_several => "010-rhs-assert-several",
    p011_agenda_one_fact_many_rules => "011-agenda-one-fact-many-rules",
    p012_agenda_across_asserts => "012-agenda-across-asserts",
    p013_agenda_after_modify => "013-agenda-after-modify",
    p014_agenda_with_not => "014-agenda-with-not",
    p015_agenda_join_order => "015-agenda-join-order",
    p016_salience_ties => "016-salience-ties",
    p017_salience_globals => "017-salience-globals",
    p018_refraction => "018-refraction",
    p019_retract_other_activations => "019-retract-other-activations",
    p020_negation_toggle => "020-negation-toggle",
    p021_exists => "021-exists",
    p022_or_ce => "022-or-ce",
    p023_and_not_nested => "023-and-not-nested",
    p024_test_ce => "024-test-ce",
    p025_connectives => "025-connectives",
    p026_predicate_constraint => "026-predicate-constraint",
    p027_return_value_constraint => "027-return-value-constraint",
    p028_fact_address => "028-fact-address",
    p029_multifield_anywhere => "029-multifield-anywhere",
    p030_empty_multifield => "030-empty-multifield",
    p031_variable_joins => "031-variable-joins",
    p032_wildcards => "032-wildcards",
    p033_modify_matched_by_others => "033-modify-matched-by-others",
    p034_run_limit => "034-run-limit",
    p035_halt => "035-halt",
    p036_deffunction_basic => "036-deffunction-basic",
    p037_deffunction_recursion => "037-deffunction-recursion",
    p038_deffunction_rest => "038-deffunction-rest",
    p039_defglobal => "039-defglobal",
    p040_if_then_else => "040-if-then-else",
    p041_while => "041-while",
    p042_loop_for_count => "042-loop-for-count",
    p043_progn_foreach => "043-progn-foreach",
    p044_switch => "044-switch",
    p045_printout => "045-printout",
    p046_format => "046-format",
    p047_arith_integers => "047-arith-integers",
    p048_arith_floats => "048-arith-floats",
    p049_comparisons => "049-comparisons",
    p050_logic => "050-logic",
    p051_type_predicates => "051-type-predicates",
    p052_string_functions => "052-string-functions",
    p053_multifield_functions_a => "053-multifield-functions-a",
    p054_multifield_functions_b => "054-multifield-functions-b",
    p055_implode_explode => "055-implode-explode",
    p056_fact_queries_a => "056-fact-queries-a",
    p057_fact_queries_b => "057-fact-queries-b",
    p058_agenda_listing => "058-agenda-listing",
    p059_watch_unwatch => "059-watch-unwatch",
    p060_retract_several_rhs => "060-retract-several-rhs",
    p061_clear => "061-clear",
    p062_undefrule => "062-undefrule",
    p063_list_defrules_ppdefrule => "063-list-defrules-ppdefrule",
    p064_matches => "064-matches",
    p065_refresh_agenda_strategy => "065-refresh-agenda-strategy",
    p066_save_load_facts => "066-save-load-facts",
    p067_batch_star => "067-batch-star",
    p068_allowed_values_modify => "068-allowed-values-modify",
    p069_slot_type_violation => "069-slot-type-violation",
    p070_facts_display_values => "070-facts-display-values",
    p071_no_lhs_initial_fact => "071-no-lhs-initial-fact",
    p072_or_bindings_multiple => "072-or-bindings-multiple",
    p073_modify_loop_guard => "073-modify-loop-guard",
    p074_pattern_network_error => "074-pattern-network-error",
    p075_agenda_retract_reassert => "075-agenda-retract-reassert",
    p076_rhs_activation_order => "076-rhs-activation-order",
    p077_negative_salience_chain => "077-negative-salience-chain",
    p078_string_symbol_compare_match => "078-string-symbol-compare-match",
    p079_rule_added_after_facts => "079-rule-added-after-facts",
    p080_modify_with_not_order => "080-modify-with-not-order",
    p081_deffacts_reset_fire_order => "081-deffacts-reset-fire-order",
    p082_exists_modify_toggle => "082-exists-modify-toggle",
    p083_startup_state => "083-startup-state",
    p084_watch_compilations => "084-watch-compilations",
    p085_string_edge => "085-string-edge",
    p086_modify_into_duplicate => "086-modify-into-duplicate",
    p087_return_in_loops => "087-return-in-loops",
    p088_exists_multi_and_double_not => "088-exists-multi-and-double-not",
    p089_rule_retracts_own_other_match => "089-rule-retracts-own-other-match",
    p090_multifield_rhs_and_functions => "090-multifield-rhs-and-functions",
    p091_mini_agent => "091-mini-agent",
    p092_number_symbol_lexing => "092-number-symbol-lexing",
    p093_fact_address_values => "093-fact-address-values",
    p094_salience_mixed_order => "094-salience-mixed-order",
    p095_agenda_mixed_rule_shapes => "095-agenda-mixed-rule-shapes",
    p096_one_retract_unblocks_many => "096-one-retract-unblocks-many",
    p097_shared_patterns_order => "097-shared-patterns-order",
    p098_exists_not_same_fact => "098-exists-not-same-fact",
    p099_alpha_network_order => "099-alpha-network-order",
    p100_hashed_memory_order => "100-hashed-memory-order",
    p101_not_and_outer_vars_toggle => "101-not-and-outer-vars-toggle",
    p102_nested_not_exists => "102-nested-not-exists",
    p103_group_rule_added_later => "103-group-rule-added-later",
    p104_unblocked_not_order => "104-unblocked-not-order",
    p105_notand_unblock_order => "105-notand-unblock-order",
    p115_progn_over_rebound_globals => "115-progn-over-rebound-globals",
    p116_printout_between_modifies => "116-printout-between-modifies",
    p117_asserts_before_control_modify => "117-asserts-before-control-modify",
    p120_printout_multifield_values => "120-printout-multifield-values",
    p121_str_index_substring_edges => "121-str-index-substring-edges",
    p122_format_flags => "122-format-flags",
    p123_watch_activations_modify => "123-watch-activations-modify",
    p124_facts_ranges => "124-facts-ranges",
    p125_agenda_saliences => "125-agenda-saliences",
    p126_undefrule_with_activations => "126-undefrule-with-activations",
    p127_save_load_facts_roundtrip => "127-save-load-facts-roundtrip",
    p128_switch_default => "128-switch-default",
    p129_loop_for_count_ranges => "129-loop-for-count-ranges",
    p130_progn_index => "130-progn-index",
    p131_runtime_errors => "131-runtime-errors",
    p132_matches_ppdefrule_more => "132-matches-ppdefrule-more",
    p133_math_multifield_edges => "133-math-multifield-edges",
    p134_multifield_index_errors => "134-multifield-index-errors",
    p135_fact_functions_listings => "135-fact-functions-listings",
    p136_globals_deffacts_modify_reset => "136-globals-deffacts-modify-reset",
    p137_eval_build_run_limits => "137-eval-build-run-limits",
    p138_rhs_runtime_errors => "138-rhs-runtime-errors",
    p139_watch_statistics => "139-watch-statistics",
    p140_fact_cell_reuse => "140-fact-cell-reuse",
    p141_join_test_partial_plan_tail => "141-join-test-partial-plan-tail",
    p150_bind_lhs_variable => "150-bind-lhs-variable",
    p151_redefinitions => "151-redefinitions",
    p152_halt_watched_or_not => "152-halt-watched-or-not",
    p153_parse_time_side_effects => "153-parse-time-side-effects",
    p154_retracted_query_facts => "154-retracted-query-facts",
    p155_progn_multifield_value => "155-progn-multifield-value",
    p156_bind_global_multifield => "156-bind-global-multifield",
    p157_query_slot_tests => "157-query-slot-tests",
    p158_run_limit_message => "158-run-limit-message",
    p159_modify_retracted_in_firing => "159-modify-retracted-in-firing",
    p160_retract_unblocks_shared_pattern => "160-retract-unblocks-shared-pattern",
    p161_alpha_selector_nodes => "161-alpha-selector-nodes",
    p162_alpha_multifield_nodes => "162-alpha-multifield-nodes",
    p163_deferred_join_test_error => "163-deferred-join-test-error",
    p164_redefine_rule_shared_pattern => "164-redefine-rule-shared-pattern",
    p165_redefine_rule_primes_shared_join => "165-redefine-rule-primes-shared-join",
    p166_network_error_halts => "166-network-error-halts",
    p167_query_test_shares_nodes => "167-query-test-shares-nodes",
    p168_network_error_placement => "168-network-error-placement",
    p169_new_rule_primes_shared_pattern => "169-new-rule-primes-shared-pattern",
    p170_query_after_pattern_error => "170-query-after-pattern-error",
    p171_halting_after_network_error => "171-halting-after-network-error",
    p172_reset_halts_deffacts => "172-reset-halts-deffacts",
    p173_no_changes_while_matching => "173-no-changes-while-matching",
    p174_error_slot_of_test_without_its_variable => "174-error-slot-of-test-without-its-variable",
    p175_introspection_and_late_functions => "175-introspection-and-late-functions",
    p176_retract_order_after_priming => "176-retract-order-after-priming",
    p177_undefine_constructs => "177-undefine-constructs",
    p178_sort => "178-sort",
    p179_redefined_rule_nodes_are_new => "179-redefined-rule-nodes-are-new",
    p180_halts_and_in_use_during_a_command => "180-halts-and-in-use-during-a-command",
    p181_unbound_prompt_variables => "181-unbound-prompt-variables",
    p182_unbound_local_variables => "182-unbound-local-variables",
    p183_template_with_70_slots => "183-template-with-70-slots",
    p184_get_fact_list => "184-get-fact-list",
    p185_unbound_variables_in_queries => "185-unbound-variables-in-queries",
    p186_hyperbolic_and_reciprocal_trig => "186-hyperbolic-and-reciprocal-trig",
    p187_older_function_names => "187-older-function-names",
    p188_setgen_and_engine_settings => "188-setgen-and-engine-settings",
    p189_deftemplate_slot_functions => "189-deftemplate-slot-functions",
    p190_show_defglobals => "190-show-defglobals",
    p191_range_cardinality_defaults => "191-range-cardinality-defaults",
    p192_range_cardinality_literals => "192-range-cardinality-literals",
    p193_range_cardinality_rules => "193-range-cardinality-rules",
    p194_range_cardinality_attribute_errors => "194-range-cardinality-attribute-errors",
    p195_dynamic_constraint_checking => "195-dynamic-constraint-checking",
    p196_several_allowed_lists => "196-several-allowed-lists",
    p197_variable_constraint_conflicts => "197-variable-constraint-conflicts",
    p198_strategy_breadth => "198-strategy-breadth",
    p199_strategy_lex => "199-strategy-lex",
    p200_strategy_mea => "200-strategy-mea",
    p201_strategy_complexity => "201-strategy-complexity",
    p202_strategy_simplicity => "202-strategy-simplicity",
    p203_strategy_random => "203-strategy-random",
    p204_strategy_switching => "204-strategy-switching",
    p205_ppdeftemplate_ppdeffacts => "205-ppdeftemplate-ppdeffacts",
    p206_ppfact => "206-ppfact",
    p215_first_field_of_a_pattern => "215-first-field-of-a-pattern",
    p216_check_syntax_warnings => "216-check-syntax-warnings",
    p217_memory_commands => "217-memory-commands",
    p218_angle_conversions => "218-angle-conversions",
    p219_group_ce_error_echo => "219-group-ce-error-echo",
    p220_logical_ce_order => "220-logical-ce-order",
    p221_bind_void_value => "221-bind-void-value",
    p222_fact_index_floats => "222-fact-index-floats",
    p223_length_of_no_sequence => "223-length-of-no-sequence",
    p224_instance_name_logical_name => "224-instance-name-logical-name",
    p230_alpha_constant_discrimination => "230-alpha-constant-discrimination",
    p231_run_inside_a_call => "231-run-inside-a-call",
    p240_logical_basic => "240-logical-basic",
    p241_logical_self_retract => "241-logical-self-retract",
    p242_logical_not_exists_modify => "242-logical-not-exists-modify",
    p243_logical_strategies => "243-logical-strategies",
    p270_io_read_batch => "270-io-read-batch",
    p271_io_files => "271-io-files",
    p272_fact_value_equals_call => "272-fact-value-equals-call",
    p280_join_tests_compiled => "280-join-tests-compiled",
    p244_logical_shared_partial_matches => "244-logical-shared-partial-matches",
    p245_logical_retraction_order => "245-logical-retraction-order",
    p246_logical_undefrule_reset => "246-logical-undefrule-reset",
    p250_forall_basic => "250-forall-basic",
    p251_forall_not_exists => "251-forall-not-exists",
    p252_forall_logical_strategies => "252-forall-logical-strategies",
    p253_compilations_join_marks => "253-compilations-join-marks",
    p254_batch_get_char_echo => "254-batch-get-char-echo",
    p255_static_default_evaluated => "255-static-default-evaluated",
    p256_ordered_modify_and_unknown_inputs => "256-ordered-modify-and-unknown-inputs",
    p257_ppdeffunction_ppdefglobal => "257-ppdeffunction-ppdefglobal",
    p258_fact_duplication => "258-fact-duplication",
    p259_load_construct_errors => "259-load-construct-errors",
    p260_modules_focus => "260-modules-focus",
    p261_modules_not_exists_salience => "261-modules-not-exists-salience",
    p262_modules_listings => "262-modules-listings",
    p263_dribble_on_off => "263-dribble-on-off",
    p264_engine_settings_os => "264-engine-settings-os",
    p265_missing_function_echo => "265-missing-function-echo",
    p266_list_watch_items => "266-list-watch-items",
    p267_get_function_restrictions => "267-get-function-restrictions",
    p268_sequence_expansion => "268-sequence-expansion",
    p269_timer => "269-timer",
    p320_arity_errors_in_constructs => "320-arity-errors-in-constructs",
    p321_breakpoints => "321-breakpoints",
    p322_save => "322-save",
    p323_format_unsigned => "323-format-unsigned",
    p324_module_restored_after_actions => "324-module-restored-after-actions",
    p325_pp_equals_glued_to_call => "325-pp-equals-glued-to-call",
    p326_matches_hashed_alpha_buckets => "326-matches-hashed-alpha-buckets",
    p327_lone_mf_wildcard_in_single_slot => "327-lone-mf-wildcard-in-single-slot",
    p350_check_syntax => "350-check-syntax",
    p351_parse_time_argument_checks => "351-parse-time-argument-checks",
    p352_long_action_lists => "352-long-action-lists",
    p353_multifield_segment_prune => "353-multifield-segment-prune",
    p354_lex_mea_recency_keys => "354-lex-mea-recency-keys",
    p355_module_agenda_starts => "355-module-agenda-starts",
    p356_join_test_partly_planned => "356-join-test-partly-planned",
    p725_arith_stored_values_declined => "725-arith-stored-values-declined",
    p727_shared_pattern_node_error => "727-shared-pattern-node-error",
    p728_tests_before_multislot_length => "728-tests-before-multislot-length",
    p729_slot_order_own_nodes => "729-slot-order-own-nodes",
    p795_tests_before_length_long_path => "795-tests-before-length-long-path",
    p796_tests_before_multifield_choice => "796-tests-before-multifield-choice",
    p898_sub_string_ascii => "898-sub-string-ascii",
    p357_lex_mea_kept_recency => "357-lex-mea-kept-recency",
    p752_lex_mea_index_large => "752-lex-mea-index-large",
    p753_lex_mea_index_modules => "753-lex-mea-index-modules",
    p754_lex_mea_index_saliences => "754-lex-mea-index-saliences",
    p755_mea_index_first_pattern => "755-mea-index-first-pattern",
    p758_resort_salience_ties => "758-resort-salience-ties",
    p746_query_hoisted_operands => "746-query-hoisted-operands",
    p281_modules_defglobals => "281-modules-defglobals",
    p282_modules_import_conflicts => "282-modules-import-conflicts",
    p283_modules_get_lists => "283-modules-get-lists",
    p284_modules_logical_strategies => "284-modules-logical-strategies",
    p285_modules_unseen_globals => "285-modules-unseen-globals",
    p286_modules_undefine => "286-modules-undefine",
    p287_modules_functions => "287-modules-functions",
    p288_modules_rule_visibility => "288-modules-rule-visibility",
    p289_construct_missing_name => "289-construct-missing-name",
    p310_reset_negated_first_order => "310-reset-negated-first-order",
    p290_shared_join_keys => "290-shared-join-keys",
    p311_lhs_unbound_variables => "311-lhs-unbound-variables",
    p312_globals_unseen_initializers => "312-globals-unseen-initializers",
    p313_modules_return_pop_focus => "313-modules-return-pop-focus",
    p340_unbound_global_reads => "340-unbound-global-reads",
    p341_globals_read_when_run => "341-globals-read-when-run",
    p390_primed_join_order => "390-primed-join-order",
    p391_primed_join_bucket_tests => "391-primed-join-bucket-tests",
    p291_arith_join_tests => "291-arith-join-tests",
    p370_join_test_order => "370-join-test-order",
    p410_or_lookups => "410-or-lookups",
    p411_logical_support_lost_in_actions => "411-logical-support-lost-in-actions",
    p412_logical_reassert_after_support_lost => "412-logical-reassert-after-support-lost",
    p413_join_from_right_after_shared_join => "413-join-from-right-after-shared-join",
    p414_join_from_right_free_subnetwork => "414-join-from-right-free-subnetwork",
    p415_join_from_right_after_another => "415-join-from-right-after-another",
    p450_keyed_or_joins => "450-keyed-or-joins",
    p451_element_join_keys => "451-element-join-keys",
    p452_mf_var_offsets => "452-mf-var-offsets",
    p520_left_operand_tests => "520-left-operand-tests",
    p480_testsuite_odds => "480-testsuite-odds",
    p490_address_and_slot_checks => "490-address-and-slot-checks",
    p540_bind_multifield_args => "540-bind-multifield-args",
    p541_reset_in_actions => "541-reset-in-actions",
    p542_or_fact_address => "542-or-fact-address",
    p543_load_facts_stops => "543-load-facts-stops",
    p590_save_facts_templates => "590-save-facts-templates",
    p591_save_facts_modules => "591-save-facts-modules",
    p592_save_facts_errors => "592-save-facts-errors",
    p560_or_inside_not_forall => "560-or-inside-not-forall",
    p561_set_reset_globals => "561-set-reset-globals",
    p562_pp_nested_control => "562-pp-nested-control",
    p610_undefined_variable_in_actions => "610-undefined-variable-in-actions",
    p611_unbound_prompt_variable => "611-unbound-prompt-variable",
    p612_non_fact_arguments => "612-non-fact-arguments",
    p613_halting_ends_queries_and_loops => "613-halting-ends-queries-and-loops",
    p690_variable_name_starting_with_digit => "690-variable-name-starting-with-digit",
    p691_format_width_counts_bytes => "691-format-width-counts-bytes",
    p692_qualified_call_unexported_deffunction => "692-qualified-call-unexported-deffunction",
    p693_multifield_match_order => "693-multifield-match-order",
    p710_scratch_reclaimed_in_loops => "710-scratch-reclaimed-in-loops",
    p711_deep_recursion => "711-deep-recursion",
    p712_loop_for_count_float_bounds => "712-loop-for-count-float-bounds",
    p713_sort_function_arity => "713-sort-function-arity",
    p714_arguments_checked_in_order => "714-arguments-checked-in-order",
    p715_printout_special_symbols_and_infinity => "715-printout-special-symbols-and-infinity",
    p716_load_progress_and_commands => "716-load-progress-and-commands",
    p717_reset_no_condition_rules_order => "717-reset-no-condition-rules-order",
    p718_messages_names_and_funcall => "718-messages-names-and-funcall",
    p719_twin_blockers => "719-twin-blockers",
    p720_flat_join_comparisons => "720-flat-join-comparisons",
    p721_join_arith_integer_overflow => "721-join-arith-integer-overflow",
    p722_join_arith_float_int_mix => "722-join-arith-float-int-mix",
    p723_join_arith_division => "723-join-arith-division",
    p724_join_arith_connectives => "724-join-arith-connectives",
    p730_deffunction_parameter_list_errors => "730-deffunction-parameter-list-errors",
    p731_if_switch_without_then => "731-if-switch-without-then",
    p732_defglobal_missing_function_echo => "732-defglobal-missing-function-echo",
    p733_return_printout_arity_echo => "733-return-printout-arity-echo",
    p734_parse_time_return_types => "734-parse-time-return-types",
    p735_default_dynamic_return_type => "735-default-dynamic-return-type",
    p736_fact_address_bound_to_a_ce => "736-fact-address-bound-to-a-ce",
    p737_funcall_error_values => "737-funcall-error-values",
    p738_argument_errors_of_deffunction_calls => "738-argument-errors-of-deffunction-calls",
    p739_modify_target_in_constructs => "739-modify-target-in-constructs",
    p740_default_multifield_single_slot => "740-default-multifield-single-slot",
    p741_random_draws_across_modifies => "741-random-draws-across-modifies",
    p742_reset_keeps_caller_multifields => "742-reset-keeps-caller-multifields",
    p747_template_slot_functions_unknown_template => "747-template-slot-functions-unknown-template",
    p748_crlf_batch_echo => "748-crlf-batch-echo",
    p749_arith_in_segmented_tests => "749-arith-in-segmented-tests",
    p768_multifield_vars_in_place => "768-multifield-vars-in-place",
    p764_salience_groups_at_the_head => "764-salience-groups-at-the-head",
    p784_lone_multifield_shares_node => "784-lone-multifield-shares-node",
    p777_bound_var_and_or => "777-bound-var-and-or",
    p778_reset_first_exists => "778-reset-first-exists",
    p779_multislot_length_node_shared => "779-multislot-length-node-shared",
    p765_salience_groups_short_again => "765-salience-groups-short-again",
    p810_twin_arith_at_bind => "810-twin-arith-at-bind",
    p811_length_of_multifield_var_in_order => "811-length-of-multifield-var-in-order",
    p812_chain_under_last_match => "812-chain-under-last-match",
    p743_numeric_arguments_in_order => "743-numeric-arguments-in-order",
    p744_numeric_arguments_in_order_rules => "744-numeric-arguments-in-order-rules",
    p704_numeric_arguments_quiet_later => "704-numeric-arguments-quiet-later",
    p708_numeric_arguments_in_order_checks => "708-numeric-arguments-in-order-checks",
    p745_compat_function_return_types => "745-compat-function-return-types",
    p757_retract_order_shared_rule_end => "757-retract-order-shared-rule-end",
    p763_logical_self_join_retract_order => "763-logical-self-join-retract-order",
    p769_logical_shared_join_copy_support => "769-logical-shared-join-copy-support",
    p726_or_own_ordered_elements => "726-or-own-ordered-elements",
    p750_watch_construct_names => "750-watch-construct-names",
    p751_watch_construct_names_modules => "751-watch-construct-names-modules",
    p766_wipe_join_from_right => "766-wipe-join-from-right",
    p767_rhs_type_loop_variables => "767-rhs-type-loop-variables",
    p762_two_integer_arithmetic => "762-two-integer-arithmetic",
    p761_abs_join_tests => "761-abs-join-tests",
    p770_logical_name_upper_t => "770-logical-name-upper-t",
    p771_assert_syntax_errors => "771-assert-syntax-errors",
    p772_defrule_without_arrow => "772-defrule-without-arrow",
    p773_breadth_long_agenda => "773-breadth-long-agenda",
    p780_substring_join_tests => "780-substring-join-tests",
    p781_logical_unsupported_chains => "781-logical-unsupported-chains",
    p786_not_and_blocker_order => "786-not-and-blocker-order",
    p787_not_and_nested_not_marks => "787-not-and-nested-not-marks",
    p788_not_and_modify => "788-not-and-modify",
    p789_not_and_rule_added_later => "789-not-and-rule-added-later",
    p790_exists_and_many_matches => "790-exists-and-many-matches",
    p870_apropos => "870-apropos",
    p871_text_regions => "871-text-regions",
    p872_set_locale => "872-set-locale",
    p873_profile_settings => "873-profile-settings",
    p897_run_features_switched_on_mid_run => "897-run-features-switched-on-mid-run",
    p880_sequencep_watch_item_beta_memory => "880-sequencep-watch-item-beta-memory",
    p881_get_function_list => "881-get-function-list",
    p882_timetag => "882-timetag",
    p883_funcall_and_or_runtime_counts => "883-funcall-and-or-runtime-counts",
    p884_duplicate_modify_retracted_fact => "884-duplicate-modify-retracted-fact",
    p885_modify_duplicate_target_parse => "885-modify-duplicate-target-parse",
    p800_failed_redefinition_each_construct => "800-failed-redefinition-each-construct",
    p801_redefinition_listing_order => "801-redefinition-listing-order",
    p802_deffacts_syntax_errors => "802-deffacts-syntax-errors",
    p803_deftemplate_syntax_errors => "803-deftemplate-syntax-errors",
    p804_defglobal_syntax_errors => "804-defglobal-syntax-errors",
    p805_fact_syntax_errors => "805-fact-syntax-errors",
    p806_query_slot_operands_in_order => "806-query-slot-operands-in-order",
    p808_mf_order_segments_modify => "808-mf-order-segments-modify",
    p840_pretty_fact_set_queries => "840-pretty-fact-set-queries",
    p841_math_as_the_c_library => "841-math-as-the-c-library",
    p842_funcall_argument_counts => "842-funcall-argument-counts",
    p843_deftemplate_pattern_fields => "843-deftemplate-pattern-fields",
    p844_min_max_stop_at_an_error => "844-min-max-stop-at-an-error",
    p845_comparisons_stop_at_false => "845-comparisons-stop-at-false",
    p846_insert_replace_failed_value => "846-insert-replace-failed-value",
    p910_loop_needs_do => "910-loop-needs-do",
    p911_commline_not_a_command => "911-commline-not-a-command",
    p912_module_qualified_template => "912-module-qualified-template",
    p913_pp_constraint_glue => "913-pp-constraint-glue",
    p914_query_template_expressions => "914-query-template-expressions",
    p915_slot_value_error => "915-slot-value-error",
    p916_file_writes_visible => "916-file-writes-visible",
    p917_function_name_not_symbol => "917-function-name-not-symbol",
    p918_computed_float_as_integer => "918-computed-float-as-integer",
    p919_if_value_after_error => "919-if-value-after-error",
    p920_reset_during_reset => "920-reset-during-reset",
    p921_file_name_not_instance_name => "921-file-name-not-instance-name",
    p922_global_sequence_expansion => "922-global-sequence-expansion",
    p923_float_negative_zero => "923-float-negative-zero",
    p924_put_char_low_byte_computed_args => "924-put-char-low-byte-computed-args",
    p925_variable_through_variable_conflict => "925-variable-through-variable-conflict",
    p926_single_multifield_constraint_mix => "926-single-multifield-constraint-mix",
    p927_field_literal_conflict => "927-field-literal-conflict",
    p928_test_argument_types_later_slots => "928-test-argument-types-later-slots",
    p929_lhs_check_bindings_before => "929-lhs-check-bindings-before",
    p930_late_builtin_restrictions => "930-late-builtin-restrictions",
    p931_not_exists_keep_outer_records => "931-not-exists-keep-outer-records",
    p932_literals_of_bound_variables => "932-literals-of-bound-variables",
    p933_pattern2_before_unbound => "933-pattern2-before-unbound",
    p934_div_in_join_tests => "934-div-in-join-tests",
    p791_printout_long_multifield => "791-printout-long-multifield",
    p792_load_same_name_other_module => "792-load-same-name-other-module",
    p793_eq_of_whole_multislots => "793-eq-of-whole-multislots",
    p794_eq_of_multifield_segments => "794-eq-of-multifield-segments",
    p700_segment_key_groups => "700-segment-key-groups",
    p701_segment_or_tests => "701-segment-or-tests",
    p702_segment_test_edges => "702-segment-test-edges",
    p703_marked_fixed_slots => "703-marked-fixed-slots",
    p705_rule_of_43_patterns => "705-rule-of-43-patterns",
    p706_long_built_strings => "706-long-built-strings",
    p707_long_string_literals => "707-long-string-literals",
    p709_later_unequal_symbol_tests => "709-later-unequal-symbol-tests",
    p759_constructs_of_80_variables => "759-constructs-of-80-variables",
    p760_expressions_nested_300_deep => "760-expressions-nested-300-deep",
    p940_void_value_in_slot => "940-void-value-in-slot",
    p580_keyed_or_index => "580-keyed-or-index",
    p581_keyed_or_not => "581-keyed-or-not",
    p582_keyed_or_growth => "582-keyed-or-growth",
    p620_or_ordered_elements => "620-or-ordered-elements",
    p550_failed_redefinitions => "550-failed-redefinitions",
    p551_construct_keyword_names => "551-construct-keyword-names",
    p552_parse_error_echo => "552-parse-error-echo",
    p640_declare_errors => "640-declare-errors",
    p641_ce_syntax_errors => "641-ce-syntax-errors",
    p642_single_slot_errors => "642-single-slot-errors",
    p643_undefined_variable_reported_last => "643-undefined-variable-reported-last",
    p644_deffacts_initial_fact => "644-deffacts-initial-fact",
    p645_deftemplate_syntax_errors => "645-deftemplate-syntax-errors",
    p646_global_function_syntax_errors => "646-global-function-syntax-errors",
    p470_rhs_rebind_lhs_var => "470-rhs-rebind-lhs-var",
    p472_less_than_delimiter => "472-less-than-delimiter",
    p473_failed_rule_redefinition => "473-failed-rule-redefinition",
    p474_lhs_checks_past_32 => "474-lhs-checks-past-32",
    p430_refresh_basics => "430-refresh-basics",
    p431_refresh_ces => "431-refresh-ces",
    p432_refresh_strategies => "432-refresh-strategies",
    p433_refresh_modules => "433-refresh-modules",
    p434_refresh_primed => "434-refresh-primed",
    p435_appendix_h_names_clips_lacks => "435-appendix-h-names-clips-lacks",
    p436_sin_cos_and_every_logical_name => "436-sin-cos-and-every-logical-name",
    p437_put_char_writes_one_raw_byte => "437-put-char-writes-one-raw-byte",
    p438_open_binary_modes => "438-open-binary-modes",
    p439_matches_verbosity => "439-matches-verbosity",
    p440_eval_variables_and_type_of_instances => "440-eval-variables-and-type-of-instances",
    p441_eval_syntax_messages => "441-eval-syntax-messages",
    p442_read_number_from_file_and_format_flags => "442-read-number-from-file-and-format-flags",
    p443_batch_star_forgets_bound_variables => "443-batch-star-forgets-bound-variables",
    p444_mixed_single_and_multifield_constraints => "444-mixed-single-and-multifield-constraints",
    p445_eval_text_ending_inside_loop_and_progn => "445-eval-text-ending-inside-loop-and-progn",
    p500_retract_unblock_skips_dying => "500-retract-unblock-skips-dying",
    p501_retract_unblock_dying_lhs => "501-retract-unblock-dying-lhs",
    p502_retract_unblock_subnetwork => "502-retract-unblock-subnetwork",
    p503_retract_unblock_test_ce => "503-retract-unblock-test-ce",
    p504_retract_unblock_later_not => "504-retract-unblock-later-not",
    p505_retract_unblock_multifield => "505-retract-unblock-multifield",
    p506_retract_unblock_modify => "506-retract-unblock-modify",
    p507_retract_unblock_logical => "507-retract-unblock-logical",
    p508_undefrule_firing_rule => "508-undefrule-firing-rule",
    p570_slot_eval_order => "570-slot-eval-order",
    p571_reset_prime_order => "571-reset-prime-order",
    p572_halt_pops_empty_focus => "572-halt-pops-empty-focus",
    p600_module_specifier_on_fact_name => "600-module-specifier-on-fact-name",
    p601_type_function => "601-type-function",
    p602_string_limits => "602-string-limits",
    p660_watch_deffunctions => "660-watch-deffunctions",
    p661_watch_globals => "661-watch-globals",
    p662_watch_all => "662-watch-all",
    p663_implied_templates_kept => "663-implied-templates-kept",
    p664_options => "664-options",
    p625_salience_when_activated => "625-salience-when-activated",
    p626_salience_every_cycle => "626-salience-every-cycle",
    p627_salience_errors => "627-salience-errors",
    p628_str_assert => "628-str-assert",
    p629_instance_name_strings => "629-instance-name-strings",
    p820_or_under_exists => "820-or-under-exists",
    p821_or_under_exists_marks => "821-or-under-exists-marks",
    p822_clear_runs_join_tests => "822-clear-runs-join-tests",
    p823_instance_name_slot_types => "823-instance-name-slot-types",
    p824_or_under_exists_logical => "824-or-under-exists-logical",
    p825_or_under_exists_modules => "825-or-under-exists-modules",
    p826_or_under_exists_tests_nested_or => "826-or-under-exists-tests-nested-or",
    p827_mf_segment_orders => "827-mf-segment-orders",
    p828_mf_predicates_segments => "828-mf-predicates-segments",
    p829_mf_predicate_errors => "829-mf-predicate-errors",
    p830_mf_multislots_joins => "830-mf-multislots-joins",
    p831_mf_retract_modify_matches => "831-mf-retract-modify-matches",
    p832_mf_sort_by_swaps_order => "832-mf-sort-by-swaps-order",
    p833_mf_mixed_test_kinds => "833-mf-mixed-test-kinds",
    p834_mf_order_rules_change => "834-mf-order-rules-change",
    p835_mf_order_two_multislots => "835-mf-order-two-multislots",
    p850_arith_bind_slot_values => "850-arith-bind-slot-values",
    p851_undefined_global_held_back => "851-undefined-global-held-back",
    p858_retract_right_primed_subnet => "858-retract-right-primed-subnet",
    p859_retract_right_primed_modify => "859-retract-right-primed-modify",
    p890_or_branch_of_several_ces => "890-or-branch-of-several-ces",
    p891_or_branch_of_several_ces_marks => "891-or-branch-of-several-ces-marks",
    p892_dummy_address_defaults => "892-dummy-address-defaults",
    p893_allowed_instance_names_classes => "893-allowed-instance-names-classes",
    p899_ordered_field_vars_in_tests => "899-ordered-field-vars-in-tests",
    p813_kept_groups_places => "813-kept-groups-places",
    p900_sub_string_cuts_found_or_new => "900-sub-string-cuts-found-or-new",
    p950_batch_file_ends_inside_command => "950-batch-file-ends-inside-command",
    p953_construct_name_arguments => "953-construct-name-arguments",
    p954_clear_keeps_settings => "954-clear-keeps-settings",
    p955_construct_of_unknown_module => "955-construct-of-unknown-module",
    p956_fact_function_checks => "956-fact-function-checks",
    p957_variable_referenced_before_defined => "957-variable-referenced-before-defined",
    p958_sort_function_argument => "958-sort-function-argument",
    p959_undefine_star_current_module => "959-undefine-star-current-module",
    p970_error_inside_expression_values => "970-error-inside-expression-values",
    p971_error_inside_expression_actions => "971-error-inside-expression-actions",
    p972_salience_declare_errors => "972-salience-declare-errors",
    p973_salience_refresh_errors_halt => "973-salience-refresh-errors-halt",
    p974_multislot_cardinality_literals => "974-multislot-cardinality-literals",
    p975_test_ce_side_effects_at_reset => "975-test-ce-side-effects-at-reset",
    p985_check_syntax_salience_errors => "985-check-syntax-salience-errors",
    p986_modify_index_echo_in_progn => "986-modify-index-echo-in-progn",
    p987_salience_kept_as_int => "987-salience-kept-as-int",
    p988_function_restrictions_more => "988-function-restrictions-more",
    p989_build_and_literal_argument_types => "989-build-and-literal-argument-types",
    p976_test_assert_while_defining => "976-test-assert-while-defining",
    p977_test_effects_while_defining => "977-test-effects-while-defining",
    p978_test_assert_while_defining_ces => "978-test-assert-while-defining-ces",
    p980_rhs_bind_argument_types => "980-rhs-bind-argument-types",
    p981_rhs_lhs_variable_types => "981-rhs-lhs-variable-types",
    p982_rhs_expansion_argument_types => "982-rhs-expansion-argument-types",
    p983_rhs_literal_constraint_types => "983-rhs-literal-constraint-types",
    p984_lhs_test_argument_types => "984-lhs-test-argument-types",
    p960_slot_facets => "960-slot-facets",
    p961_slot_facet_errors => "961-slot-facet-errors",
    p962_slot_facet_tokens => "962-slot-facet-tokens",
    p963_error_slot_of_test_several_shapes => "963-error-slot-of-test-several-shapes",
    p964_error_slot_of_test_more_shapes => "964-error-slot-of-test-more-shapes",
    p965_retract_order_after_priming_more => "965-retract-order-after-priming-more",
    p966_retract_order_after_priming_not => "966-retract-order-after-priming-not",
    p990_printout_illegal_logical_name => "990-printout-illegal-logical-name",
    p991_commands_nested_in_expressions => "991-commands-nested-in-expressions",
    p992_fact_set_query_syntax_errors => "992-fact-set-query-syntax-errors",
    p993_modify_duplicate_unknown_slot => "993-modify-duplicate-unknown-slot",
    p994_undeftemplate_initial_fact => "994-undeftemplate-initial-fact",
    p995_incremental_reset_off => "995-incremental-reset-off",
    p996_implied_template_import_conflict => "996-implied-template-import-conflict",
    p997_expand_called_alone => "997-expand-called-alone",
    p998_slot_read_errors_halt => "998-slot-read-errors-halt",
}
