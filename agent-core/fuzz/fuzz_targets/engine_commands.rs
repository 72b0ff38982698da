//! The engine fed random command streams (assert/retract/modify/run/reset/rule
//! redefinition/undefrule/clear, decoded from bytes) against a small rule base with
//! not/exists (also over several CEs) and multifield patterns; invariants are checked
//! after every command and a failed assert must leave no trace. Same decoder as the property test in
//! agent-core/tests/invariants_property.rs.
#![no_main]

#[path = "../../tests/common/command_stream.rs"]
mod command_stream;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // the extended rule base: also a `not` over several CEs
    command_stream::run_stream_with(command_stream::RULE_BASE_NOT_AND, data);
});
