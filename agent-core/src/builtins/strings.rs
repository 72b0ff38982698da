//! Builtins: strings (owned by the builtins helper; see /work/brief/engine-interfaces.md).

use super::Builtin;

pub const FUNCS: &[Builtin] = &[];
