//! `engine!`: a boxed engine with roomy pools except the ones a test shrinks, shared
//! by the capacity and exhaustion tests. The caller imports `agent_core::Engine`.

/// Engine with all pools roomy except the ones a test shrinks (positional consts).
macro_rules! engine {
    ($($name:ident = $v:expr),*) => {{
        #[allow(non_snake_case, unused_variables)]
        {
            const FACTS: usize = 64;
            const VALUES: usize = 512;
            const SYMBOLS: usize = 256;
            const SYMBYTES: usize = 4096;
            const TEMPLATES: usize = 16;
            const SLOTS: usize = 64;
            const RULES: usize = 32;
            const ALPHA: usize = 64;
            const JOINS: usize = 128;
            const TOKENS: usize = 512;
            const ACTS: usize = 256;
            const FUNCS: usize = 16;
            const GLOBALS: usize = 16;
            const EXPRS: usize = 2048;
            const STACK: usize = 128;
            const SCRATCH: usize = 256;
            const DEFFACTS: usize = 8;
            const EXTERNALS: usize = 8;
            {
                // inner items shadow the defaults above
                $(const $name: usize = $v;)*
                Box::new(Engine::<FACTS, VALUES, SYMBOLS, SYMBYTES, TEMPLATES, SLOTS, RULES, ALPHA, JOINS,
                    TOKENS, ACTS, FUNCS, GLOBALS, EXPRS, STACK, SCRATCH, DEFFACTS, EXTERNALS>::new())
            }
        }
    }};
}
