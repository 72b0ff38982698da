//! The terminal table and the regenerated `BENCHMARKS.md`.

use super::decision::DecisionReport;
use super::footprint::{Footprint, ImageFootprint};
use super::measure::{Measurement, Plan, Reading};
use super::workloads::Kind;
use super::workloads::Workload;
use std::fmt::Write as _;
use std::process::Command;
use std::time::Duration;

/// The machine the numbers come from.
#[derive(Clone, Debug)]
pub struct Machine {
    pub hostname: String,
    pub cpu: String,
    pub cores: usize,
    pub date: String,
}

impl Machine {
    pub fn detect() -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let (cpu, cores) = parse_cpuinfo(&cpuinfo);
        let hostname = std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map(|h| h.trim().to_string())
            .unwrap_or_else(|_| "unknown".to_string());
        let date = Command::new("date")
            .args(["-u", "+%Y-%m-%d %H:%M UTC"])
            .output()
            .ok()
            .map(|out| String::from_utf8_lossy(&out.stdout).trim().to_string())
            .filter(|d| !d.is_empty())
            .unwrap_or_else(|| "unknown date".to_string());
        Self {
            hostname,
            cpu,
            cores,
            date,
        }
    }
}

/// CPU model name and the number of logical processors in `/proc/cpuinfo` text.
pub fn parse_cpuinfo(text: &str) -> (String, usize) {
    let field = |line: &str, key: &str| -> Option<String> {
        let (name, value) = line.split_once(':')?;
        (name.trim() == key).then(|| value.trim().to_string())
    };
    let model = text
        .lines()
        .find_map(|line| field(line, "model name"))
        .unwrap_or_else(|| "unknown CPU".to_string());
    let cores = text
        .lines()
        .filter(|line| field(line, "processor").is_some())
        .count();
    (model, cores)
}

/// All engines' measurements of one workload.
pub struct Row {
    pub workload: Workload,
    /// In contender order; the same order for every row.
    pub measured: Vec<Measurement>,
    /// Whether the engines' results agree (and how that was decided).
    pub agreement: String,
}

pub struct Report {
    pub command_line: String,
    pub machine: Machine,
    pub plan: Plan,
    /// Contender names, then their version or the reason they were not measured.
    pub contenders: Vec<(String, Result<String, String>)>,
    pub rows: Vec<Row>,
    pub footprints: Vec<Footprint>,
    pub decisions: Result<DecisionReport, String>,
    /// The footprint tool's JSON for the agent image, or why it is missing.
    pub image: Result<ImageFootprint, String>,
}

/// Index of the contenders that count as "ours" and as the CLIPS references.
fn is_ours(name: &str) -> bool {
    name.starts_with("ours")
}

fn best<T: Copy + Ord>(values: impl Iterator<Item = Option<T>>) -> Option<T> {
    values.flatten().min()
}

/// Reads one figure of a measurement.
type Pick<T> = fn(&Measurement) -> Reading<T>;

/// `reference ÷ ours` to two decimals, i.e. how many times fewer ours needs.
pub fn ratio_text(reference: Option<f64>, ours: Option<f64>) -> String {
    match (reference, ours) {
        (Some(r), Some(o)) if o > 0.0 => format!("{:.2}x", r / o),
        (_, None) => "not measured".to_string(),
        _ => "n/a".to_string(),
    }
}

pub fn millions(count: u64) -> String {
    format!("{:.2} M", count as f64 / 1e6)
}

pub fn duration_text(d: Duration) -> String {
    let micros = d.as_secs_f64() * 1e6;
    if micros < 1000.0 {
        format!("{micros:.0} µs")
    } else if micros < 1e6 {
        format!("{:.2} ms", micros / 1e3)
    } else {
        format!("{:.3} s", micros / 1e6)
    }
}

/// At most `limit` characters of `text`, marked when cut.
fn shorten(text: &str, limit: usize) -> String {
    match text.char_indices().nth(limit) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

/// A reading as table text: the value, or the reason it is missing.
fn cell<T>(reading: &Reading<T>, show: impl Fn(&T) -> String) -> String {
    match reading {
        Ok(value) => show(value),
        // The full reason for a missing engine is listed once under "Machine".
        Err(reason) if reason.starts_with("not measured") => "not measured".to_string(),
        Err(reason)
            if reason.starts_with("skipped")
                || reason.starts_with("withdrawn")
                || reason.starts_with("capacity exceeded") =>
        {
            shorten(reason, 80)
        }
        Err(reason) => format!("failed: {}", shorten(reason, 60)),
    }
}

impl Report {
    fn names(&self) -> Vec<&str> {
        self.contenders.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// Best (lowest) CLIPS value and best ours value of one reading in a row.
    fn best_pair<T: Copy + Ord>(
        &self,
        row: &Row,
        pick: impl Fn(&Measurement) -> Option<T>,
    ) -> (Option<T>, Option<T>) {
        let names = self.names();
        let of = |want_ours: bool| {
            best(
                row.measured
                    .iter()
                    .zip(&names)
                    .filter(|(_, name)| is_ours(name) == want_ours)
                    .map(|(m, _)| pick(m)),
            )
        };
        (of(false), of(true))
    }

    fn ratio_row(&self, row: &Row) -> (String, String) {
        let (clips_instr, ours_instr) = self.best_pair(row, |m| m.instr_run.clone().ok());
        let (clips_wall, ours_wall) = self.best_pair(row, |m| m.wall_run.clone().ok());
        (
            ratio_text(clips_instr.map(|v| v as f64), ours_instr.map(|v| v as f64)),
            ratio_text(
                clips_wall.map(|d| d.as_secs_f64()),
                ours_wall.map(|d| d.as_secs_f64()),
            ),
        )
    }

    /// The summary printed on the terminal.
    pub fn terminal_table(&self) -> String {
        let mut out = String::new();
        let names = self.names();
        let _ = write!(out, "{:<16} {:>7}", "workload", "fired");
        for name in &names {
            let _ = write!(out, " | {name:>18}");
        }
        let _ = writeln!(out, " | {:>12} | {:>12}", "instr ratio", "wall ratio");
        out.push_str(
            "(per engine, run phase: instructions / median wall time; ratio = best CLIPS ÷ ours)\n",
        );
        for row in &self.rows {
            let fired = row
                .measured
                .first()
                .and_then(|m| m.fired.clone().ok())
                .map(|f| f.to_string())
                .unwrap_or_else(|| "-".to_string());
            let _ = write!(out, "{:<16} {:>7}", row.workload.name(), fired);
            for m in &row.measured {
                let instr = m.instr_run.clone().ok().map(millions);
                let wall = m.wall_run.clone().ok().map(duration_text);
                let text = match (instr, wall) {
                    (None, None) => "-".to_string(),
                    (i, w) => format!(
                        "{} / {}",
                        i.unwrap_or_else(|| "-".into()),
                        w.unwrap_or_else(|| "-".into())
                    ),
                };
                let _ = write!(out, " | {text:>18}");
            }
            let (instr_ratio, wall_ratio) = self.ratio_row(row);
            let _ = writeln!(out, " | {instr_ratio:>12} | {wall_ratio:>12}");
        }
        match &self.decisions {
            Ok(d) => {
                let instr = match &d.instructions {
                    Ok(i) => format!(
                        "{} instr median (LX800 {} at IPC 1, {} at IPC 0.5)",
                        i.median,
                        duration_text(lx800_time(i.median, 1.0)),
                        duration_text(lx800_time(i.median, 0.5))
                    ),
                    Err(reason) => format!("instructions {reason}"),
                };
                let _ = writeln!(
                    out,
                    "decision time: {} decisions, median {} (p90 {}), {instr}",
                    d.decisions,
                    duration_text(d.wall_median),
                    duration_text(d.wall_p90)
                );
            }
            Err(reason) => {
                let _ = writeln!(out, "decision time: {reason}");
            }
        }
        out
    }

    fn table_header(out: &mut String, first: &[&str], names: &[&str], last: &[&str]) {
        let columns: Vec<&str> = first.iter().chain(names).chain(last).copied().collect();
        let _ = writeln!(out, "| {} |", columns.join(" | "));
        let _ = writeln!(out, "|{}", "---|".repeat(columns.len()));
    }

    /// The agent program's memory: CLIPS `(mem-used)` after the LLSF games against our
    /// image RAM (when the image holds the engine) and our arena high-water marks.
    fn agent_memory_markdown(&self) -> String {
        let mut md = String::new();
        let names = self.names();
        let Some(row) = self.rows.iter().find(|r| r.workload.kind == Kind::Llsf) else {
            return "Agent memory: not measured (the LLSF games row was not run).\n\n".to_string();
        };
        let mem_of = |want: &str| {
            names
                .iter()
                .zip(&row.measured)
                .find(|(n, _)| **n == want)
                .and_then(|(_, m)| m.mem_bytes.clone().ok())
        };
        let clips = mem_of("CLIPS 6.30");
        let clips64 = mem_of("CLIPS 6.4");
        let ours_hw = mem_of("ours (in-process)");
        let _ = writeln!(
            md,
            "Agent program ({}, the same `.clp` files): memory after the games.\n",
            row.workload.name()
        );
        let _ = writeln!(md, "| engine | bytes | CLIPS 6.30 ÷ this |\n|---|---|---|");
        let show = |v: Option<u64>| {
            v.map(|b| b.to_string())
                .unwrap_or_else(|| "not measured".into())
        };
        let ratio = |v: Option<u64>| ratio_text(clips.map(|c| c as f64), v.map(|b| b as f64));
        let _ = writeln!(md, "| CLIPS 6.30 `(mem-used)` | {} | 1.00x |", show(clips));
        let _ = writeln!(
            md,
            "| CLIPS 6.4 `(mem-used)` | {} | {} |",
            show(clips64),
            ratio(clips64)
        );
        let _ = writeln!(
            md,
            "| ours: `DefaultEngine` pools at their high-water marks (host, same games) | {} | {} |",
            show(ours_hw),
            ratio(ours_hw)
        );
        match &self.image {
            Ok(image) => match image.arena_bytes {
                Some(arena) => {
                    let ram = image.ram_bytes;
                    let _ = writeln!(
                        md,
                        "| ours: agent image RAM (statics incl. the engine arena of {arena} B, plus stack) | {ram} | {} |",
                        ratio(Some(ram))
                    );
                }
                None => {
                    let _ = writeln!(
                        md,
                        "| ours: agent image RAM | {} (engine not in the image yet: not comparable) | n/a |",
                        image.ram_bytes
                    );
                }
            },
            Err(reason) => {
                let _ = writeln!(md, "| ours: agent image RAM | {reason} | n/a |");
            }
        }
        md.push_str(
            "\nTarget: agent image RAM at least 10x below CLIPS's memory for the same agent.\n\n",
        );
        md
    }

    /// Run-phase instructions per rule fired, per workload, and how they grow from the
    /// smallest to the largest size of each kind (a cost per firing that stays flat
    /// means total cost grows with the work, not faster).
    fn per_firing_markdown(&self) -> String {
        let names = self.names();
        let mut md = String::from("\n## Instructions per firing (run phase)\n\n");
        md.push_str(
            "Run-phase instructions ÷ the engine's own rules fired. *Growth* is the largest \
             size's value ÷ the smallest size's, per kind.\n\n",
        );
        Self::table_header(&mut md, &["workload"], &names, &[]);
        let mut kinds: Vec<Kind> = Vec::new();
        for row in &self.rows {
            if !kinds.contains(&row.workload.kind) {
                kinds.push(row.workload.kind);
            }
            let cells: Vec<String> = row
                .measured
                .iter()
                .map(|m| match per_firing(m) {
                    Some(v) => format!("{v:.0}"),
                    None => "–".to_string(),
                })
                .collect();
            let _ = writeln!(md, "| {} | {} |", row.workload.name(), cells.join(" | "));
        }
        // growth only where the sizes scale one program (not across puzzles)
        for kind in kinds.into_iter().filter(|k| k.is_scaled()) {
            let rows: Vec<&Row> = self
                .rows
                .iter()
                .filter(|r| r.workload.kind == kind)
                .collect();
            let (Some(first), Some(last)) = (rows.first(), rows.last()) else {
                continue;
            };
            if rows.len() < 2 {
                continue;
            }
            let cells: Vec<String> = (0..names.len())
                .map(|i| {
                    let small = first.measured.get(i).and_then(per_firing);
                    let large = last.measured.get(i).and_then(per_firing);
                    match (small, large) {
                        (Some(s), Some(l)) if s > 0.0 => format!("{:.2}x", l / s),
                        _ => "–".to_string(),
                    }
                })
                .collect();
            let _ = writeln!(
                md,
                "| growth {} → {} | {} |",
                first.workload.name(),
                last.workload.name(),
                cells.join(" | ")
            );
        }
        md
    }

    /// A table of each workload's two regions (`run`, `whole`, read by `regions`): each
    /// engine's reading (`show`) and the best CLIPS's over ours (as `f64`).
    fn region_table<T: Copy + Ord>(
        &self,
        md: &mut String,
        regions: [(&str, Pick<T>); 2],
        show: impl Fn(&T) -> String,
        as_f64: impl Fn(T) -> f64,
    ) {
        Self::table_header(
            md,
            &["workload", "region"],
            &self.names(),
            &["best CLIPS ÷ ours"],
        );
        for row in &self.rows {
            for (region, pick) in regions {
                let cells: Vec<String> =
                    row.measured.iter().map(|m| cell(&pick(m), &show)).collect();
                let (clips, ours) = self.best_pair(row, |m| pick(m).ok());
                let ratio = ratio_text(clips.map(&as_f64), ours.map(&as_f64));
                let _ = writeln!(
                    md,
                    "| {} | {region} | {} | {ratio} |",
                    row.workload.name(),
                    cells.join(" | ")
                );
            }
        }
    }

    /// The whole `BENCHMARKS.md`.
    pub fn markdown(&self) -> String {
        let names = self.names();
        let mut md = String::new();
        let _ = writeln!(md, "# Benchmarks: robotino-agent engine against CLIPS\n");
        let _ = writeln!(
            md,
            "Regenerated by `{}`; do not edit by hand. Numbers that could not be measured say \
             why instead of showing a value.\n",
            self.command_line
        );
        let _ = writeln!(md, "## Machine\n");
        let m = &self.machine;
        let _ = writeln!(md, "- Host: `{}`; run at {}", m.hostname, m.date);
        let _ = writeln!(md, "- CPU: {} ({} logical processors)", m.cpu, m.cores);
        if cfg!(debug_assertions) {
            let _ = writeln!(
                md,
                "- **Debug build**: ours ran unoptimised; rerun from `cargo build --release`."
            );
        }
        for (name, version) in &self.contenders {
            let text = match version {
                Ok(v) => v.clone(),
                Err(reason) => format!("not measured: {reason}"),
            };
            let _ = writeln!(md, "- {name}: {text}");
        }
        let callgrind = match self.plan.callgrind_limit {
            Some(limit) => format!("on, time-boxed at {} s per run", limit.as_secs()),
            None => "off (--no-callgrind)".to_string(),
        };
        let _ = writeln!(
            md,
            "- Repetitions per timing: {} (median); callgrind: {callgrind}\n",
            self.plan.reps
        );
        md.push_str(METHOD);

        let _ = writeln!(md, "## Rules fired and agreement\n");
        Self::table_header(&mut md, &["workload"], &names, &["results"]);
        for row in &self.rows {
            let cells: Vec<String> = row
                .measured
                .iter()
                .map(|m| cell(&m.fired, |f| f.to_string()))
                .collect();
            let _ = writeln!(
                md,
                "| {} | {} | {} |",
                row.workload.name(),
                cells.join(" | "),
                row.agreement
            );
        }

        let _ = writeln!(md, "\n## Instructions (callgrind)\n");
        self.region_table(
            &mut md,
            [
                ("run", |m| m.instr_run.clone()),
                ("whole", |m| m.instr_whole.clone()),
            ],
            |&v| millions(v),
            |v| v as f64,
        );

        md.push_str(&self.per_firing_markdown());

        let _ = writeln!(md, "\n## Wall time (median of {})\n", self.plan.reps);
        self.region_table(
            &mut md,
            [
                ("run", |m| m.wall_run.clone()),
                ("whole", |m| m.wall_whole.clone()),
            ],
            |&d| duration_text(d),
            |d| d.as_secs_f64(),
        );

        let _ = writeln!(md, "\n## Memory\n");
        let _ = writeln!(md, "Engine code and static data:\n");
        let _ = writeln!(
            md,
            "| file | bytes on disk | text | data | bss |\n|---|---|---|---|---|"
        );
        for f in &self.footprints {
            let (text, data, bss) = match f.sections {
                Some(s) => (s.text.to_string(), s.data.to_string(), s.bss.to_string()),
                None => ("?".into(), "?".into(), "?".into()),
            };
            let _ = writeln!(
                md,
                "| {} (`{}`) | {} | {text} | {data} | {bss} |",
                f.label,
                f.path.display(),
                f.file_bytes
            );
        }
        md.push_str(&image_markdown(&self.image));
        md.push_str(&self.agent_memory_markdown());
        let _ = writeln!(
            md,
            "Dynamic memory after the run: CLIPS `(mem-used)` in bytes; ours: arena \
             high-water marks.\n"
        );
        Self::table_header(&mut md, &["workload"], &names, &[]);
        for row in &self.rows {
            let cells: Vec<String> = row
                .measured
                .iter()
                .map(|m| cell(&m.mem_bytes, |b| b.to_string()))
                .collect();
            let _ = writeln!(md, "| {} | {} |", row.workload.name(), cells.join(" | "));
        }
        md.push_str(&decision_markdown(&self.decisions, &self.machine.cpu));
        md
    }
}

const METHOD: &str = "## Method\n
Every engine loads the same generated files (written by `robotino-agent bench`, kept in the \
work directory): `program.clp` holds the constructs and facts as `deffacts`; the batch file \
does `(load* program.clp)`, `(watch statistics)`, `(reset)`, `(run)`, `(exit)`. \
*Run* is the whole program minus the same program without its `(run)`, so start-up, parsing \
and `(reset)` are out; *whole* is the complete process. CLIPS 6.30 is the Debian `clips` \
command (`clips -f2 FILE`). CLIPS 6.4 is PyPI `clipspy`, driven by \
`tests/bench/clipspy_run.py`: its wall times are `run()` and load+reset+run timed inside \
Python, its instruction counts are of the whole Python process (so *whole* includes the \
interpreter). Ours runs as `robotino-agent clips -f2 FILE` (CLI column; its pools grow, so \
no program runs out of one; `--large-pools` is an alias of the same engine) and \
in-process through `bench::ours::InProcessEngine` (the CLI's growing engine, built \
before the clock starts; CLIPS 6.4's callgrind runs use one fixed Python hash seed, \
so that its run phase, a difference of two processes, is not noise). Both are host builds with `u32` pool indices (feature \
`wide-index`, with `host-speedups`), so in-process memory counts 4-byte links; the agent image keeps 2-byte \
ones. Rules fired come from `(watch statistics)` (CLI) or \
the `run()` return value. Results agree when the programs' result lines are equal (Manners: \
the same set of seat assignments, also checked to be a valid seating).\n\n";

/// Run-phase instructions per rule fired, when both were measured.
pub fn per_firing(m: &Measurement) -> Option<f64> {
    let instr = m.instr_run.as_ref().ok()?;
    let fired = m.fired.as_ref().ok().filter(|&&f| f > 0)?;
    Some(*instr as f64 / *fired as f64)
}

/// The agent image line(s) from the footprint tool's JSON.
pub fn image_markdown(image: &Result<ImageFootprint, String>) -> String {
    match image {
        Ok(i) => {
            let arena = match i.arena_bytes {
                Some(b) => format!("engine arena `AGENT_ENGINE` {b} B"),
                None => "engine arena absent (the engine is not in the image yet)".to_string(),
            };
            format!(
                "| ours: agent image i586 (`{}`; footprint tool) | – | code {} | RAM statics {} | stack high-water {} |\n\n\
                 Agent image: code {} B, RAM {} B ({arena}).\n\n",
                i.path, i.code_bytes, i.static_bytes, i.stack_bytes, i.code_bytes, i.ram_bytes
            )
        }
        Err(reason) => format!("| ours: agent image | {reason} | | | |\n\n"),
    }
}

/// Time on the 500 MHz AMD Geode LX800 for `instructions` at `ipc` instructions per cycle.
pub fn lx800_time(instructions: u64, ipc: f64) -> Duration {
    Duration::from_secs_f64(instructions as f64 / (ipc * 500e6))
}

/// The decision-time section (markdown) or the reason it is missing.
pub fn decision_markdown(decisions: &Result<DecisionReport, String>, cpu: &str) -> String {
    let mut md = String::from("\n## Decision time of the LLSF agent\n\n");
    let d = match decisions {
        Ok(d) => d,
        Err(reason) => {
            let _ = writeln!(md, "{reason}");
            return md;
        }
    };
    let _ = writeln!(
        md,
        "From asserting a skill outcome (e.g. the light seen at a machine) to the agent's next \
         skill request: {} decisions of {} seeded games (seeds 0..{}, paper strategy), the \
         agent alone in a `DefaultEngine` replaying the outcomes recorded from the whole game \
         (every replayed request checked against the game's). One decision fires {} rules \
         (median; at most {}). Method: `host-shim/src/bench/DECISION_TIME.md`.\n",
        d.decisions, d.games, d.games, d.fired_median, d.fired_max
    );
    let _ = writeln!(
        md,
        "| measure | median | p90 | max | target |\n|---|---|---|---|---|"
    );
    let target_met = if d.wall_median < Duration::from_micros(50) {
        "< 50 µs: met"
    } else {
        "< 50 µs: MISSED"
    };
    let _ = writeln!(
        md,
        "| wall time on this host ({cpu}; {} timed replays after a warm-up) | {} | {} | {} | {target_met} |",
        d.reps,
        duration_text(d.wall_median),
        duration_text(d.wall_p90),
        duration_text(d.wall_max)
    );
    match &d.instructions {
        Ok(i) => {
            let _ = writeln!(
                md,
                "| instructions (x86_64, callgrind; mean {}) | {} | {} | {} | |",
                i.mean, i.median, i.p90, i.max
            );
            for ipc in [1.0, 0.5] {
                let _ = writeln!(
                    md,
                    "| LX800 500 MHz at IPC {ipc} (estimate) | {} | {} | {} | |",
                    duration_text(lx800_time(i.median, ipc)),
                    duration_text(lx800_time(i.p90, ipc)),
                    duration_text(lx800_time(i.max, ipc))
                );
            }
            md.push_str(
                "\nThe LX800 estimate is instructions ÷ (IPC × 500 MHz) from the x86_64 count; \
                 an i586 build executes somewhat different instructions (32-bit pointers, no \
                 CMOV), so it is an estimate, not a measurement.\n",
            );
        }
        Err(reason) => {
            let _ = writeln!(md, "| instructions | {reason} | | | |");
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpuinfo_gives_model_and_processor_count() {
        let text = "processor\t: 0\nmodel name\t: AMD EPYC 7B13\nprocessor\t: 1\nmodel name\t: AMD EPYC 7B13\n";
        assert_eq!(parse_cpuinfo(text), ("AMD EPYC 7B13".to_string(), 2));
        assert_eq!(parse_cpuinfo(""), ("unknown CPU".to_string(), 0));
    }

    #[test]
    fn ratios_and_units_are_formatted() {
        assert_eq!(ratio_text(Some(10.0), Some(4.0)), "2.50x");
        assert_eq!(ratio_text(Some(10.0), None), "not measured");
        assert_eq!(ratio_text(None, Some(1.0)), "n/a");
        assert_eq!(millions(12_345_678), "12.35 M");
        assert_eq!(duration_text(Duration::from_micros(250)), "250 µs");
        assert_eq!(duration_text(Duration::from_micros(2500)), "2.50 ms");
        assert_eq!(duration_text(Duration::from_millis(3480)), "3.480 s");
    }

    #[test]
    fn per_firing_needs_both_readings() {
        let mut m = Measurement::not_measured("x");
        assert_eq!(per_firing(&m), None);
        m.instr_run = Ok(5000);
        assert_eq!(per_firing(&m), None);
        m.fired = Ok(0);
        assert_eq!(per_firing(&m), None);
        m.fired = Ok(20);
        assert_eq!(per_firing(&m), Some(250.0));
    }

    #[test]
    fn missing_readings_show_their_reason_not_a_number() {
        let missing: Reading<u64> = Err("not measured: engine absent".to_string());
        assert_eq!(cell(&missing, |v| v.to_string()), "not measured");
        let failed: Reading<u64> = Err("exit status 1".to_string());
        assert_eq!(cell(&failed, |v| v.to_string()), "failed: exit status 1");
    }
}
