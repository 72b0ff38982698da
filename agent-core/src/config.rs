//! Capacities by name: the one pool table.
//!
//! Every pool of an engine is one row of [`pool_table!`](crate::__pool_table): its
//! [`Pool`] variant, the name of its capacity, the name a [`CapacityError`] prints, its
//! capacity in the host's [`Capacities::HOST`] and the unit tests' [`Capacities::SMALL`],
//! and the arrays an engine holds per entry (entry type and empty value). Everything
//! that lists the pools is generated from that row: [`Pool`] (`ALL`, `COUNT`, `name`),
//! [`Capacities`], [`entry_bytes`], [`Stats`](crate::Stats)' arrays, the slices of
//! [`Core`], and the storage an [`engine_storage!`](crate::engine_storage) names.
//!
//! An engine's capacities are named, never positional:
//! ```
//! agent_core::engine_storage! {
//!     /// A small robot engine.
//!     pub struct RobotStorage {
//!         facts: 64,
//!         tokens: 256,
//!         // the pools not named take the unit tests' capacities
//!         ..agent_core::Capacities::SMALL
//!     }
//! }
//! type RobotEngine = agent_core::Engine<RobotStorage>;
//! let engine = Box::new(RobotEngine::with_storage(RobotStorage::new()));
//! assert_eq!(engine.stats().get(agent_core::Pool::Tokens).1, 256);
//! ```
//! A name that is no pool, or a pool left out without a `..` base, does not compile:
//! ```compile_fail
//! agent_core::engine_storage! {
//!     pub struct Typo { fatcs: 64, ..agent_core::Capacities::SMALL }
//! }
//! ```
//!
//! Adding a pool: a row here (and the entry type in the module that allocates from it);
//! every engine that names all its capacities (the agent image pins each one to its
//! game's high-water mark) names the new one too.
//!
//! [`CapacityError`]: crate::CapacityError
//! [`Core`]: crate::Core

use crate::host::Host;

/// The pool table: calls `$callback! { $($args)* rows }`, one row per pool:
/// `Variant capacity_name "error name" host small [array: Type = EMPTY, ...]`. The first
/// array of a row is the pool itself (its length is the capacity); the others are
/// indexes with one entry per pool entry.
#[doc(hidden)]
#[macro_export]
macro_rules! __pool_table {
    ($callback:path { $($args:tt)* }) => {
        $callback! { $($args)*
            Facts facts "facts" 4096 128 [
                facts: $crate::fact::Fact = $crate::fact::Fact::EMPTY,
                // duplicate-index bucket heads
                fact_buckets: $crate::value::Ix = $crate::value::NONE,
                // host speed-up: the template list links of each fact
                fact_tlinks: $crate::fact::TemplateLinks = $crate::fact::NO_TEMPLATE_LINKS,
                // truth maintenance: the head of each fact's logical supports
                fact_deps: $crate::logical::Deps = $crate::logical::NO_DEPS,
            ],
            FactValues fact_values "fact values" 32768 1024 [
                values: $crate::value::Value = $crate::value::Value::Void,
            ],
            Symbols symbols "symbols" 4096 256 [
                sym_entries: $crate::symbols::SymEntry = $crate::symbols::SymEntry::EMPTY,
                sym_buckets: $crate::symbols::Head = $crate::symbols::Head::EMPTY,
            ],
            // the host holds the text of deftemplates and deffacts for ppdeftemplate and
            // ppdeffacts here too: the rule scenarios with referee and sim need ~50 KiB;
            // 65,535 is the most a u16 index (no wide-index) can address
            SymbolBytes symbol_bytes "symbol bytes" 65535 4096 [
                sym_bytes: u8 = 0,
            ],
            Templates templates "templates" 256 16 [
                templates: $crate::template::Template = $crate::template::Template::EMPTY,
            ],
            // what changes at run time per template (its facts), by template index:
            // with `in-place`, the templates of a compiled rule base are read in place
            TemplateMemories template_memories "template memories" 256 16 [
                tmpl_mems: $crate::template::TemplateMem = $crate::template::TemplateMem::EMPTY,
                // host speed-up: each template's constant-test discrimination
                tmpl_disc: $crate::rete::TemplateDisc = $crate::rete::NO_TEMPLATE_DISC,
                // modules: the module each template belongs to
                tmpl_module: $crate::module::ModTag = $crate::module::NO_TAG,
            ],
            SlotDefs slot_defs "slot definitions" 1024 64 [
                slots: $crate::template::SlotDef = $crate::template::SlotDef::EMPTY,
                // extras: each slot's `facet`/`multifacet` attributes (a chain of
                // `template::facet` nodes), for `deftemplate-slot-facet-value`
                slot_facets: $crate::template::PpText = $crate::template::NO_PP_TEXT,
            ],
            Rules rules "rules" 512 32 [
                rules: $crate::rule::Rule = $crate::rule::Rule::EMPTY,
                // truth maintenance: each rule's logical join
                rule_logical: $crate::logical::RuleLogical = $crate::logical::NO_RULE_LOGICAL,
                // modules: the module each rule belongs to (its agenda)
                rule_module: $crate::module::RuleTag = $crate::module::NO_RULE_TAG,
            ],
            AlphaNodes alpha_nodes "alpha nodes" 1024 64 [
                alphas: $crate::rete::AlphaNode = $crate::rete::AlphaNode::EMPTY,
            ],
            // what changes at run time per alpha node (its memory), by alpha node id:
            // with `in-place`, the nodes of a compiled rule base are read in place
            AlphaMemories alpha_memories "alpha memories" 1024 64 [
                alpha_mems: $crate::rete::AlphaMem = $crate::rete::AlphaMem::EMPTY,
                // host speed-up: discrimination links by alpha node id, and bucket heads
                alpha_disc: $crate::rete::AlphaDisc = $crate::rete::NO_ALPHA_DISC,
            ],
            Joins joins "joins" 2048 128 [
                joins: $crate::rete::Join = $crate::rete::Join::EMPTY,
            ],
            // what changes at run time per join (its memory), by join id
            JoinMemories join_memories "join memories" 2048 128 [
                join_mems: $crate::rete::JoinMem = $crate::rete::JoinMem::EMPTY,
            ],
            Tokens tokens "tokens" 32768 512 [
                tokens: $crate::rete::Token = $crate::rete::Token::EMPTY,
                // alpha- and beta-memory index bucket heads (see `rete::index`)
                amem_buckets: $crate::handle::TokenId = $crate::handle::TokenId::NONE,
                // truth maintenance: the head of the facts each partial match supports
                token_deps: $crate::logical::Deps = $crate::logical::NO_DEPS,
                // host speed-up: partial matches' links in extra beta index groups
                token_xlinks: $crate::rete::XLinks = $crate::rete::NO_XLINKS,
            ],
            Activations activations "activations" 8192 256 [
                acts: $crate::rule::Activation = $crate::rule::Activation::EMPTY,
            ],
            Functions functions "deffunctions" 256 16 [
                funcs: $crate::template::Deffunction = $crate::template::Deffunction::EMPTY,
                // modules: the module each deffunction belongs to
                func_module: $crate::module::ModTag = $crate::module::NO_TAG,
                // extras: each deffunction's source text, for ppdeffunction, and the
                // deffunctions in listing order (a redefined one goes last)
                func_extras: $crate::template::FnExtras = $crate::template::NO_FN_EXTRAS,
            ],
            Globals globals "globals" 128 16 [
                globals: $crate::template::Global = $crate::template::Global::EMPTY,
                // modules: the module each defglobal belongs to
                global_module: $crate::module::ModTag = $crate::module::NO_TAG,
                // extras: each defglobal's source text from its name, for ppdefglobal
                global_text: $crate::template::PpText = $crate::template::NO_PP_TEXT,
            ],
            Exprs exprs "expression nodes" 32768 2048 [
                exprs: $crate::expr::Expr = $crate::expr::Expr::EMPTY,
            ],
            EvalStack eval_stack "evaluation stack" 1024 128 [
                stack: $crate::value::Value = $crate::value::Value::Void,
            ],
            Scratch scratch "multifield scratch" 4096 256 [
                scratch: $crate::value::Value = $crate::value::Value::Void,
            ],
            Deffacts deffacts "deffacts" 64 8 [
                deffacts: $crate::template::Deffacts = $crate::template::Deffacts::EMPTY,
                // modules: the module each deffacts belongs to
                deffacts_module: $crate::module::ModTag = $crate::module::NO_TAG,
            ],
            ExternalFns external_fns "external functions" 32 8 [
                externals: $crate::engine::ExternalEntry = $crate::engine::ExternalEntry::EMPTY,
            ],
            // truth maintenance (`logical`): one entry per (partial match, fact) support
            Supports supports "logical supports" 8192 64 [
                supports: $crate::logical::Support = $crate::logical::NO_SUPPORT,
            ],
            // modules (`defmodule`): MAIN is entry 0; the agent image has MAIN only
            Modules modules "defmodules" 64 4 [
                modules: $crate::module::Module = $crate::module::NO_MODULE,
            ],
            // modules: the import and export specifications of every defmodule
            ModulePorts module_ports "module ports" 256 16 [
                ports: $crate::module::Port = $crate::module::NO_PORT,
            ],
            // modules: the focus stack, bottom first
            FocusStack focus_stack "focus stack" 128 8 [
                focus: $crate::module::ModTag = $crate::module::NO_TAG,
            ],
        }
    };
}

/// How `Core` holds a pool's array: a slice, but the pools whose views read a compiled
/// rule base's entries in place too ([`RomPool`](crate::rom::RomPool)): expression
/// nodes, alpha nodes, joins, templates, slot definitions and rules.
#[doc(hidden)]
#[macro_export]
macro_rules! __pool_view {
    (mut exprs, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t> };
    (mut templates, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t> };
    (mut slots, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t> };
    (mut rules, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t> };
    (mut alphas, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t> };
    (mut joins, $l:lifetime, $t:ty) => { $crate::rom::RomPool<$l, $t, $crate::handle::JoinId> };
    (mut join_mems, $l:lifetime, $t:ty) => { $crate::handle::Slots<$l, $crate::handle::JoinId, $t> };
    (mut tokens, $l:lifetime, $t:ty) => { $crate::handle::Slots<$l, $crate::handle::TokenId, $t> };
    (mut $name:ident, $l:lifetime, $t:ty) => { &$l mut [$t] };
    (ref exprs, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t> };
    (ref templates, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t> };
    (ref slots, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t> };
    (ref rules, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t> };
    (ref alphas, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t> };
    (ref joins, $l:lifetime, $t:ty) => { $crate::rom::RomRef<$l, $t, $crate::handle::JoinId> };
    (ref join_mems, $l:lifetime, $t:ty) => { $crate::handle::SlotsRef<$l, $crate::handle::JoinId, $t> };
    (ref tokens, $l:lifetime, $t:ty) => { $crate::handle::SlotsRef<$l, $crate::handle::TokenId, $t> };
    (ref $name:ident, $l:lifetime, $t:ty) => { &$l [$t] };
    (mut exprs, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.exprs, $arr) };
    (mut templates, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.templates, $arr) };
    (mut slots, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.slots, $arr) };
    (mut rules, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.rules, $arr) };
    (mut alphas, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.alphas, $arr) };
    (mut joins, $rom:ident, $arr:expr) => { $crate::rom::RomPool::new($rom.joins, $arr) };
    (mut join_mems, $rom:ident, $arr:expr) => { $crate::handle::Slots::new($arr) };
    (mut tokens, $rom:ident, $arr:expr) => { $crate::handle::Slots::new($arr) };
    (mut $name:ident, $rom:ident, $arr:expr) => { $arr };
    (ref exprs, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.exprs, $arr) };
    (ref templates, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.templates, $arr) };
    (ref slots, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.slots, $arr) };
    (ref rules, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.rules, $arr) };
    (ref alphas, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.alphas, $arr) };
    (ref joins, $rom:ident, $arr:expr) => { $crate::rom::RomRef::new($rom.joins, $arr) };
    (ref join_mems, $rom:ident, $arr:expr) => { $crate::handle::SlotsRef::new($arr) };
    (ref tokens, $rom:ident, $arr:expr) => { $crate::handle::SlotsRef::new($arr) };
    (ref $name:ident, $rom:ident, $arr:expr) => { $arr };
}

/// Generates, from the pool table, everything in agent-core that lists the pools.
macro_rules! pool_items {
    ($(
        $variant:ident $cap:ident $name:literal $host:literal $small:literal [
            $first:ident : $fty:ty = $fempty:expr
            $(, $arr:ident : $aty:ty = $aempty:expr)* $(,)?
        ]
    ),* $(,)?) => {
        /// A pool of the engine (named in [`CapacityError`](crate::CapacityError)s and
        /// [`Stats`](crate::Stats)); one row of the pool table each.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Pool {
            $($variant,)*
        }

        impl Pool {
            /// Every pool, in table order (`pool as usize` indexes [`Stats`](crate::Stats)).
            pub const ALL: [Pool; Pool::COUNT] = [$(Pool::$variant,)*];
            /// How many pools an engine has.
            pub const COUNT: usize = [$(stringify!($variant),)*].len();

            /// The pool's name in messages (`out of tokens (capacity 512)`).
            pub const fn name(self) -> &'static str {
                match self {
                    $(Pool::$variant => $name,)*
                }
            }
        }

        /// Every pool's capacity (entries), by name. An engine's storage is made from
        /// one of these by [`engine_storage!`](crate::engine_storage).
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub struct Capacities {
            $(
                #[doc = concat!("Entries of the ", $name, " pool.")]
                pub $cap: usize,
            )*
        }

        impl Capacities {
            /// Host defaults ([`DefaultEngine`](crate::DefaultEngine)): roomy enough for
            /// the differential suite and the benchmarks.
            pub const HOST: Capacities = Capacities { $($cap: $host,)* };
            /// Small capacities for unit tests ([`SmallEngine`](crate::SmallEngine); fits
            /// a thread stack).
            pub const SMALL: Capacities = Capacities { $($cap: $small,)* };

            /// The capacity of `pool`.
            pub const fn get(&self, pool: Pool) -> usize {
                match pool {
                    $(Pool::$variant => self.$cap,)*
                }
            }

            /// Every pool with `n` entries.
            pub const fn uniform(n: usize) -> Capacities {
                Capacities { $($cap: n,)* }
            }

            /// The capacities in table order (as [`Pool::ALL`]).
            pub const fn to_array(&self) -> [usize; Pool::COUNT] {
                [$(self.$cap,)*]
            }
        }

        /// Bytes one entry of `pool` occupies in an engine, its index entries included
        /// (hash-bucket heads, the host's template list links), so hosts can turn
        /// capacities and high-water marks into RAM figures.
        pub const fn entry_bytes(pool: Pool) -> usize {
            match pool {
                $(Pool::$variant => {
                    core::mem::size_of::<$fty>() $(+ core::mem::size_of::<$aty>())*
                })*
            }
        }

        /// The non-generic view every algorithm works on: the engine's scalar state,
        /// the host, and every pool's arrays as slices (one copy of the code whatever
        /// the capacities).
        pub struct Core<'a> {
            pub st: &'a mut crate::engine::State,
            pub host: &'a mut dyn Host,
            /// How a full pool grows (feature `grow`; nothing on fixed storage).
            pub grower: Grower<'a>,
            $(
                pub $first: $crate::__pool_view!(mut $first, 'a, $fty),
                $(pub $arr: &'a mut [$aty],)*
            )*
        }

        /// Read-only slices of every pool (the engine's queries between operations).
        pub struct Pools<'a> {
            $(
                pub $first: $crate::__pool_view!(ref $first, 'a, $fty),
                $(pub $arr: &'a [$aty],)*
            )*
        }

        impl Core<'_> {
            /// Capacities of every pool, in table order.
            pub fn capacities(&self) -> [usize; Pool::COUNT] {
                [$(self.$first.len(),)*]
            }

            /// Capacity of `pool` alone (`capacities()[pool]` without reading every pool).
            #[inline]
            pub fn capacity(&self, pool: Pool) -> usize {
                match pool {
                    $(Pool::$variant => self.$first.len(),)*
                }
            }
        }
    };
}

__pool_table!(pool_items {});

/// Storage for every pool of an engine, sized by named capacities. Implemented only by
/// [`engine_storage!`](crate::engine_storage), which generates the struct from the pool
/// table, with a `const fn new()` (every entry empty) that runs as fill loops when
/// called at run time; an [`Engine`](crate::Engine) holds one
/// ([`Engine::with_storage`](crate::Engine::with_storage)). (Not an associated `EMPTY`
/// constant: a host engine's constant would be copied from a read-only image of its
/// every byte, hundreds of MiB for the large one.)
pub trait Storage {
    /// The capacities this storage was made with.
    const CAPACITIES: Capacities;
    /// The engine's view of the storage, with its state and host.
    fn core<'a>(&'a mut self, st: &'a mut crate::engine::State, host: &'a mut dyn Host)
        -> Core<'a>;
    /// Read-only slices of every pool (`rom`: the compiled entries read in place,
    /// `State::rom`).
    fn pools(&self, rom: crate::rom::Rom) -> Pools<'_>;
    /// The capacities this storage has now, in table order (a growing storage's grow).
    #[inline(always)]
    fn capacities(&self) -> [usize; Pool::COUNT] {
        Self::CAPACITIES.to_array()
    }
}

/// How a `Core` grows its storage: with feature `grow`, a handle on the
/// [`GrowStorage`](crate::grow::GrowStorage) it was made from; without it, nothing
/// (fixed storage never grows).
#[cfg(feature = "grow")]
pub use crate::grow::Grower;

/// How a `Core` grows its storage: without feature `grow`, nothing (fixed storage
/// never grows; the type takes no space).
#[cfg(not(feature = "grow"))]
#[derive(Clone, Copy)]
pub struct Grower<'a>(core::marker::PhantomData<&'a mut ()>);

#[cfg(not(feature = "grow"))]
impl Grower<'_> {
    /// Fixed storage: a full pool is full.
    pub const NONE: Self = Grower(core::marker::PhantomData);
}

/// Defines a struct holding every pool of an engine, sized by named capacities (a
/// [`Capacities`] literal: every pool named, or the rest taken from a base with
/// `..Capacities::SMALL`). `Engine<ThatStruct>` is then an engine. See the [module
/// docs](crate::config).
#[macro_export]
macro_rules! engine_storage {
    ($(#[$meta:meta])* $vis:vis struct $name:ident $caps:tt) => {
        $crate::__pool_table!($crate::__engine_storage { ($(#[$meta])*) ($vis) $name $caps });
    };
}

#[doc(hidden)]
#[macro_export]
macro_rules! __engine_storage {
    (($($meta:tt)*) ($vis:vis) $name:ident $caps:tt $(
        $variant:ident $cap:ident $pname:literal $host:literal $small:literal [
            $($arr:ident : $aty:ty = $aempty:expr),* $(,)?
        ]
    ),* $(,)?) => {
        $($meta)*
        $vis struct $name {
            $($(
                $arr: [$aty; $crate::config::Capacities $caps.$cap],
            )*)*
        }

        impl $name {
            /// Every entry empty; `const` so an engine can be a `static`.
            #[allow(clippy::new_without_default)]
            pub const fn new() -> Self {
                $name {
                    $($(
                        $arr: [$aempty; $crate::config::Capacities $caps.$cap],
                    )*)*
                }
            }
        }

        impl $crate::config::Storage for $name {
            const CAPACITIES: $crate::config::Capacities = $crate::config::Capacities $caps;
            #[inline(always)]
            fn core<'a>(
                &'a mut self,
                st: &'a mut $crate::engine::State,
                host: &'a mut dyn $crate::Host,
            ) -> $crate::Core<'a> {
                let rom = st.rom;
                $crate::Core { st, host, grower: $crate::config::Grower::NONE, $($($arr: $crate::__pool_view!(mut $arr, rom, &mut self.$arr),)*)* }
            }
            #[inline(always)]
            fn pools(&self, rom: $crate::rom::Rom) -> $crate::config::Pools<'_> {
                $crate::config::Pools { $($($arr: $crate::__pool_view!(ref $arr, rom, &self.$arr),)*)* }
            }
        }
    };
}

crate::engine_storage! {
    /// Storage of [`DefaultEngine`](crate::DefaultEngine): [`Capacities::HOST`].
    pub struct HostStorage { ..Capacities::HOST }
}

crate::engine_storage! {
    /// Storage of [`SmallEngine`](crate::SmallEngine): [`Capacities::SMALL`].
    pub struct SmallStorage { ..Capacities::SMALL }
}
