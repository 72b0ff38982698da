//! The image's memory footprint: section sizes and symbols from its ELF file, plus the stack
//! high-water mark the image prints at exit.
//!
//! Code = every allocated section that is not writable (.text, .rodata, .eh_frame, notes).
//! RAM = every allocated writable section (.data, .bss, .got...) plus the measured stack.
//! Heap = 0 unless an allocator symbol is linked, which makes heap use unbounded.

use crate::budget::{self, BudgetName, Budgets, Usage, Violation};
use object::{elf, Object, ObjectSection, ObjectSymbol, SectionFlags};
use std::fmt;

/// The symbol under which the image exports its engine static (see rules/image/src/report.rs).
pub const ENGINE_SYMBOL: &str = "AGENT_ENGINE";

/// Symbols that mean an allocator is linked. Rust's allocator shims are matched as
/// substrings because newer compilers mangle them (`..._7___rustc12___rust_alloc`).
const RUST_ALLOCATOR_PARTS: [&str; 5] = [
    "__rust_alloc",
    "__rust_realloc",
    "__rust_dealloc",
    "__rdl_alloc",
    "__rg_alloc",
];
const LIBC_ALLOCATORS: [&str; 7] = [
    "malloc",
    "calloc",
    "realloc",
    "free",
    "aligned_alloc",
    "posix_memalign",
    "memalign",
];

/// Where an allocated section's bytes live on the robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// Read-only: code and constant data.
    Code,
    /// Writable: RAM.
    Ram,
}

/// One allocated section.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    pub name: String,
    pub bytes: u64,
    pub region: Region,
}

/// The engine static's share of RAM.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Arena {
    /// The image exports no `AGENT_ENGINE` symbol (yet).
    Absent,
    Present {
        bytes: u64,
        section: String,
    },
}

/// What the ELF file says, before running the image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StaticFootprint {
    pub sections: Vec<Section>,
    pub arena: Arena,
    /// Names of linked allocator symbols; empty means no heap.
    pub allocator_symbols: Vec<String>,
}

/// The whole footprint: static part plus the measured stack.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Footprint {
    pub image: StaticFootprint,
    pub stack_max_bytes: u64,
}

impl Footprint {
    pub fn code_bytes(&self) -> u64 {
        self.region_bytes(Region::Code)
    }

    pub fn static_ram_bytes(&self) -> u64 {
        self.region_bytes(Region::Ram)
    }

    pub fn ram_bytes(&self) -> u64 {
        self.static_ram_bytes() + self.stack_max_bytes
    }

    fn region_bytes(&self, region: Region) -> u64 {
        self.image
            .sections
            .iter()
            .filter(|s| s.region == region)
            .map(|s| s.bytes)
            .sum()
    }

    pub fn heap_usage(&self) -> Usage {
        if self.image.allocator_symbols.is_empty() {
            Usage::Bytes(0)
        } else {
            Usage::Unbounded {
                because: format!(
                    "allocator linked: {}",
                    self.image.allocator_symbols.join(", ")
                ),
            }
        }
    }

    pub fn usage(&self, name: BudgetName) -> Usage {
        match name {
            BudgetName::Ram => Usage::Bytes(self.ram_bytes()),
            BudgetName::Code => Usage::Bytes(self.code_bytes()),
            BudgetName::Heap => self.heap_usage(),
        }
    }

    /// Every budget this footprint exceeds, in the order ram, code, heap.
    pub fn violations(&self, budgets: &Budgets) -> Vec<Violation> {
        BudgetName::ALL
            .iter()
            .filter_map(|&name| budget::check(name, budgets.get(name), &self.usage(name)))
            .collect()
    }
}

/// Why an ELF file could not be measured.
#[derive(Debug)]
pub enum ElfError {
    Parse(object::Error),
    /// Without symbols the tool cannot prove that no allocator is linked.
    NoSymbolTable,
}

impl fmt::Display for ElfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ElfError::Parse(e) => write!(f, "not a readable ELF file: {e}"),
            ElfError::NoSymbolTable => write!(
                f,
                "the image has no symbol table (stripped?), so the absence of an allocator cannot be checked"
            ),
        }
    }
}

impl std::error::Error for ElfError {}

/// Reads sections and symbols from the image's ELF bytes.
pub fn read_elf(data: &[u8]) -> Result<StaticFootprint, ElfError> {
    let file = object::File::parse(data).map_err(ElfError::Parse)?;
    let mut sections = Vec::new();
    for section in file.sections() {
        let SectionFlags::Elf { sh_flags, .. } = section.flags() else {
            continue;
        };
        let Some(region) = region_of(sh_flags) else {
            continue;
        };
        if section.size() == 0 {
            continue;
        }
        sections.push(Section {
            name: section.name().unwrap_or("<unnamed>").to_owned(),
            bytes: section.size(),
            region,
        });
    }

    if file.symbols().next().is_none() {
        return Err(ElfError::NoSymbolTable);
    }
    let mut arena = Arena::Absent;
    let mut allocator_symbols = Vec::new();
    for symbol in file.symbols() {
        let Ok(name) = symbol.name() else { continue };
        if name == ENGINE_SYMBOL {
            let section = symbol
                .section_index()
                .and_then(|index| file.section_by_index(index).ok())
                .and_then(|s| s.name().ok().map(str::to_owned))
                .unwrap_or_else(|| "<none>".to_owned());
            arena = Arena::Present {
                bytes: symbol.size(),
                section,
            };
        } else if is_allocator_symbol(name) && !allocator_symbols.iter().any(|s| s == name) {
            allocator_symbols.push(name.to_owned());
        }
    }
    allocator_symbols.sort();
    Ok(StaticFootprint {
        sections,
        arena,
        allocator_symbols,
    })
}

/// `SHF_ALLOC` sections occupy memory at run time; `SHF_WRITE` ones are RAM.
fn region_of(sh_flags: elf::SectionFlags) -> Option<Region> {
    match (
        sh_flags.contains(elf::SHF_ALLOC),
        sh_flags.contains(elf::SHF_WRITE),
    ) {
        (false, _) => None,
        (true, false) => Some(Region::Code),
        (true, true) => Some(Region::Ram),
    }
}

pub fn is_allocator_symbol(name: &str) -> bool {
    LIBC_ALLOCATORS.contains(&name) || RUST_ALLOCATOR_PARTS.iter().any(|part| name.contains(part))
}

/// Finds `stack_max_bytes=<n>` in the image's output. A run whose stack reached the bottom
/// of the painted region is an error: its number would only be a lower bound.
pub fn parse_stack_line(output: &str) -> Result<u64, String> {
    let line = output
        .lines()
        .find(|line| line.contains("stack_max_bytes="))
        .ok_or("the image printed no `stack_max_bytes=` line")?;
    let field = |key: &str| {
        line.split_whitespace()
            .find_map(|word| word.strip_prefix(key))
            .map(str::to_owned)
    };
    let bytes = field("stack_max_bytes=")
        .and_then(|n| n.parse::<u64>().ok())
        .ok_or_else(|| format!("unreadable stack line: {line}"))?;
    if field("stack_reached_paint_bottom=").as_deref() == Some("true") {
        return Err(format!(
            "the stack reached the bottom of the painted region ({line}); the real use is larger: raise PAINT_BYTES in rules/image/src/stack_paint.rs"
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::Budget;

    fn section(name: &str, bytes: u64, region: Region) -> Section {
        Section {
            name: name.into(),
            bytes,
            region,
        }
    }

    fn footprint(bss: u64, stack: u64, allocators: &[&str]) -> Footprint {
        Footprint {
            image: StaticFootprint {
                sections: vec![
                    section(".text", 4000, Region::Code),
                    section(".rodata", 1000, Region::Code),
                    section(".data", 100, Region::Ram),
                    section(".bss", bss, Region::Ram),
                ],
                arena: Arena::Absent,
                allocator_symbols: allocators.iter().map(|s| s.to_string()).collect(),
            },
            stack_max_bytes: stack,
        }
    }

    fn budgets(ram: u64, code: u64) -> Budgets {
        let b = |max_bytes| Budget {
            max_bytes,
            reason: "test".into(),
        };
        Budgets {
            ram: b(ram),
            code: b(code),
            heap: b(0),
        }
    }

    #[test]
    fn sums_regions_and_adds_the_stack_to_ram() {
        let fp = footprint(900, 500, &[]);
        assert_eq!(fp.code_bytes(), 5000);
        assert_eq!(fp.static_ram_bytes(), 1000);
        assert_eq!(fp.ram_bytes(), 1500);
        assert_eq!(fp.heap_usage(), Usage::Bytes(0));
    }

    #[test]
    fn a_footprint_inside_its_budgets_has_no_violations() {
        assert!(footprint(900, 500, &[])
            .violations(&budgets(1500, 5000))
            .is_empty());
    }

    #[test]
    fn stack_alone_can_push_ram_over_budget() {
        let violations = footprint(900, 501, &[]).violations(&budgets(1500, 5000));
        assert_eq!(violations.len(), 1);
        assert_eq!(violations[0].budget, BudgetName::Ram);
        assert_eq!(violations[0].excess_bytes(), Some(1));
    }

    #[test]
    fn reports_every_exceeded_budget_including_a_linked_allocator() {
        let fp = footprint(100_000, 0, &["__rust_alloc", "malloc"]);
        let names: Vec<_> = fp
            .violations(&budgets(65536, 4096))
            .iter()
            .map(|v| v.budget)
            .collect();
        assert_eq!(names, [BudgetName::Ram, BudgetName::Code, BudgetName::Heap]);
        assert!(fp.violations(&budgets(1 << 20, 1 << 20))[0]
            .to_string()
            .contains("allocator linked: __rust_alloc, malloc"));
    }

    #[test]
    fn classifies_sections_by_their_elf_flags() {
        let alloc = elf::SHF_ALLOC;
        assert_eq!(
            region_of(alloc.with(elf::SHF_EXECINSTR)),
            Some(Region::Code)
        );
        assert_eq!(region_of(alloc), Some(Region::Code));
        assert_eq!(region_of(alloc.with(elf::SHF_WRITE)), Some(Region::Ram));
        assert_eq!(region_of(elf::SHF_WRITE), None);
    }

    #[test]
    fn recognises_mangled_rust_and_libc_allocator_symbols() {
        assert!(is_allocator_symbol("_RNvCs123_7___rustc12___rust_alloc"));
        assert!(is_allocator_symbol("__rdl_alloc_zeroed"));
        assert!(is_allocator_symbol("malloc"));
        assert!(!is_allocator_symbol("memcpy"));
        assert!(!is_allocator_symbol("mallocate_table"));
    }

    #[test]
    fn reads_the_stack_line_and_refuses_a_saturated_paint() {
        let ok = "agent-image: x=1\nagent-image: stack_max_bytes=532 stack_painted_bytes=32768 stack_reached_paint_bottom=false\n";
        assert_eq!(parse_stack_line(ok), Ok(532));
        let full = ok.replace("=532", "=32768").replace("=false", "=true");
        assert!(parse_stack_line(&full)
            .unwrap_err()
            .contains("bottom of the painted region"));
        assert!(parse_stack_line("agent-image: x=1\n").is_err());
        assert!(parse_stack_line("stack_max_bytes=lots\n").is_err());
    }

    #[test]
    fn reads_a_real_elf_file() {
        // The test binary itself is an ELF file with a symbol table and both regions.
        let exe = std::env::current_exe().unwrap();
        let data = std::fs::read(exe).unwrap();
        let image = read_elf(&data).unwrap();
        assert!(image
            .sections
            .iter()
            .any(|s| s.name == ".text" && s.region == Region::Code));
        assert!(image.sections.iter().any(|s| s.region == Region::Ram));
        assert_eq!(image.arena, Arena::Absent);
        // A std program links an allocator: the heap check must notice.
        assert!(!image.allocator_symbols.is_empty());
        assert!(matches!(read_elf(b"not an elf"), Err(ElfError::Parse(_))));
    }
}
