//! Prints every pool of the host's `DefaultEngine` and the tests' `SmallEngine`: capacity,
//! bytes per entry and bytes, so users can size their own capacities.
//!
//!     cargo run -p agent-core --example pools

use agent_core::{entry_bytes, DefaultEngine, Pool, SmallEngine, Stats};

fn print_table(name: &str, stats: &Stats, whole: usize) {
    println!("{name}: {whole} bytes in all");
    println!(
        "  {:<20} {:>9} {:>7} {:>10}",
        "pool", "capacity", "B/entry", "bytes"
    );
    let mut sum = 0;
    for pool in Pool::ALL {
        let (_, capacity) = stats.get(pool);
        let bytes = stats.bytes(pool);
        sum += bytes;
        println!(
            "  {:<20} {capacity:>9} {:>7} {bytes:>10}",
            pool.name(),
            entry_bytes(pool)
        );
    }
    println!(
        "  {:<20} {:>9} {:>7} {:>10}",
        "scalar state",
        "",
        "",
        whole - sum
    );
}

fn main() {
    // Built on the heap: DefaultEngine is larger than a main thread's stack.
    let default = Box::new(DefaultEngine::new());
    print_table(
        "DefaultEngine",
        &default.stats(),
        std::mem::size_of::<DefaultEngine>(),
    );
    let small = Box::new(SmallEngine::new());
    print_table(
        "SmallEngine",
        &small.stats(),
        std::mem::size_of::<SmallEngine>(),
    );
}
