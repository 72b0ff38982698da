//! The freestanding agent image for the LX800 (placeholder until the pipeline lands).
fn main() {}
