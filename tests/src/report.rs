//! The footprint as a table for people and as JSON for tools. Both come from the same
//! numbers, so they cannot disagree.

use crate::budget::{BudgetName, Budgets, Usage, Violation};
use crate::footprint::{Arena, Footprint, Region, ENGINE_SYMBOL};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::Path;

fn kib(bytes: u64) -> String {
    format!("{:.1} KiB", bytes as f64 / 1024.0)
}

fn percent(used: u64, max: u64) -> String {
    if max == 0 {
        return if used == 0 { "-".into() } else { "inf".into() };
    }
    format!("{:.1}%", used as f64 * 100.0 / max as f64)
}

fn verdict(name: BudgetName, violations: &[Violation]) -> &'static str {
    if violations.iter().any(|v| v.budget == name) {
        "OVER BUDGET"
    } else {
        "ok"
    }
}

/// The human-readable table.
pub fn table(image: &Path, fp: &Footprint, budgets: &Budgets, violations: &[Violation]) -> String {
    let mut out = String::new();
    let row =
        |out: &mut String, region: &str, item: &str, bytes: &str, budget: &str, note: &str| {
            // Writing to a String cannot fail.
            let _ = writeln!(
                out,
                "{region:<6} {item:<36} {bytes:>10} {budget:>10}  {note}"
            );
        };
    let _ = writeln!(out, "Agent image footprint: {}", image.display());
    let _ = writeln!(
        out,
        "(stack measured by running the image under `{}`)",
        crate::image::QEMU.join(" ")
    );
    row(
        &mut out,
        "region",
        "item",
        "bytes",
        "budget",
        "use / status",
    );
    row(
        &mut out,
        "------",
        "----",
        "-----",
        "------",
        "------------",
    );
    for region in [Region::Code, Region::Ram] {
        let label = match region {
            Region::Code => "code",
            Region::Ram => "RAM",
        };
        for s in fp.image.sections.iter().filter(|s| s.region == region) {
            row(&mut out, label, &s.name, &s.bytes.to_string(), "", "");
        }
        if region == Region::Ram {
            row(
                &mut out,
                label,
                "stack (measured high-water)",
                &fp.stack_max_bytes.to_string(),
                "",
                "painted at start, read at exit",
            );
        }
        let (name, total) = match region {
            Region::Code => (BudgetName::Code, fp.code_bytes()),
            Region::Ram => (BudgetName::Ram, fp.ram_bytes()),
        };
        let max = budgets.get(name).max_bytes;
        row(
            &mut out,
            label,
            "TOTAL",
            &total.to_string(),
            &max.to_string(),
            &format!(
                "{} of {} ({})  {}",
                kib(total),
                kib(max),
                percent(total, max),
                verdict(name, violations)
            ),
        );
    }
    let arena_item = format!("of which engine arena ({ENGINE_SYMBOL})");
    match &fp.image.arena {
        Arena::Absent => row(
            &mut out,
            "RAM",
            &arena_item,
            "absent",
            "",
            "symbol not in the image (engine not exported yet)",
        ),
        Arena::Present { bytes, section } => row(
            &mut out,
            "RAM",
            &arena_item,
            &bytes.to_string(),
            "",
            &format!("in {section}, {} of RAM", percent(*bytes, fp.ram_bytes())),
        ),
    }
    let heap_max = budgets.heap.max_bytes;
    match fp.heap_usage() {
        Usage::Bytes(bytes) => row(
            &mut out,
            "heap",
            "allocator",
            &bytes.to_string(),
            &heap_max.to_string(),
            &format!(
                "no allocator symbol linked  {}",
                verdict(BudgetName::Heap, violations)
            ),
        ),
        Usage::Unbounded { because } => row(
            &mut out,
            "heap",
            "allocator",
            "unbounded",
            &heap_max.to_string(),
            &format!("{because}  {}", verdict(BudgetName::Heap, violations)),
        ),
    }
    out
}

/// The same numbers as JSON.
pub fn json(image: &Path, fp: &Footprint, budgets: &Budgets, violations: &[Violation]) -> Value {
    let sections = |region: Region| -> Value {
        fp.image
            .sections
            .iter()
            .filter(|s| s.region == region)
            .map(|s| json!({ "name": s.name, "bytes": s.bytes }))
            .collect()
    };
    let arena = match &fp.image.arena {
        Arena::Absent => json!({ "symbol": ENGINE_SYMBOL, "present": false, "bytes": null }),
        Arena::Present { bytes, section } => {
            json!({ "symbol": ENGINE_SYMBOL, "present": true, "bytes": bytes, "section": section })
        }
    };
    let heap_bytes = match fp.heap_usage() {
        Usage::Bytes(bytes) => json!(bytes),
        Usage::Unbounded { .. } => Value::Null,
    };
    json!({
        "image": image.display().to_string(),
        "pass": violations.is_empty(),
        "code": {
            "bytes": fp.code_bytes(),
            "budget_bytes": budgets.code.max_bytes,
            "budget_reason": budgets.code.reason,
            "sections": sections(Region::Code),
        },
        "ram": {
            "bytes": fp.ram_bytes(),
            "budget_bytes": budgets.ram.max_bytes,
            "budget_reason": budgets.ram.reason,
            "static_bytes": fp.static_ram_bytes(),
            "stack_max_bytes": fp.stack_max_bytes,
            "sections": sections(Region::Ram),
            "engine_arena": arena,
        },
        "heap": {
            "bytes": heap_bytes,
            "budget_bytes": budgets.heap.max_bytes,
            "budget_reason": budgets.heap.reason,
            "allocator_symbols": fp.image.allocator_symbols,
        },
        "violations": violations.iter().map(|v| json!({
            "budget": v.budget.key(),
            "budget_bytes": v.max_bytes,
            "excess_bytes": v.excess_bytes(),
            "message": v.to_string(),
        })).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::Budget;
    use crate::footprint::{Section, StaticFootprint};

    fn sample(arena: Arena) -> (Footprint, Budgets) {
        let fp = Footprint {
            image: StaticFootprint {
                sections: vec![
                    Section {
                        name: ".text".into(),
                        bytes: 4096,
                        region: Region::Code,
                    },
                    Section {
                        name: ".bss".into(),
                        bytes: 70_000,
                        region: Region::Ram,
                    },
                ],
                arena,
                allocator_symbols: vec![],
            },
            stack_max_bytes: 536,
        };
        let b = |max_bytes| Budget {
            max_bytes,
            reason: "why".into(),
        };
        let budgets = Budgets {
            ram: b(65536),
            code: b(262144),
            heap: b(0),
        };
        (fp, budgets)
    }

    #[test]
    fn table_and_json_show_the_same_totals_and_the_violation() {
        let (fp, budgets) = sample(Arena::Absent);
        let violations = fp.violations(&budgets);
        let text = table(Path::new("img"), &fp, &budgets, &violations);
        let value = json(Path::new("img"), &fp, &budgets, &violations);

        assert!(text.contains("70536"), "{text}");
        assert!(text.contains("OVER BUDGET"), "{text}");
        assert!(text.contains("absent"), "{text}");
        assert_eq!(value["ram"]["bytes"], 70536);
        assert_eq!(value["ram"]["static_bytes"], 70000);
        assert_eq!(value["code"]["bytes"], 4096);
        assert_eq!(value["heap"]["bytes"], 0);
        assert_eq!(value["pass"], false);
        assert_eq!(value["violations"][0]["budget"], "ram");
        assert_eq!(value["violations"][0]["excess_bytes"], 70536 - 65536);
        assert_eq!(value["ram"]["engine_arena"]["present"], false);
    }

    #[test]
    fn a_present_arena_is_shown_with_its_size_and_section() {
        let (fp, budgets) = sample(Arena::Present {
            bytes: 60_000,
            section: ".bss".into(),
        });
        let text = table(Path::new("img"), &fp, &budgets, &[]);
        let value = json(Path::new("img"), &fp, &budgets, &[]);
        assert!(text.contains("60000"), "{text}");
        assert!(text.contains("in .bss"), "{text}");
        assert_eq!(value["ram"]["engine_arena"]["bytes"], 60000);
    }
}
