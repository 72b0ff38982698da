//! Workspace-level tools and tests: footprint and instruction-set gates.
