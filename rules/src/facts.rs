//! The symbols of the fact interface (README.md), typed for hosts: what a
//! skill outcome's light, a held puck or a machine belief can be, and the
//! parser for the `T2_3+S0` belief symbols of `(decision (beliefs ...))`.

/// Template and fact names hosts assert or read.
pub mod names {
    pub const SKILL_REQUEST: &str = "skill-request";
    pub const SKILL_OUTCOME: &str = "skill-outcome";
    pub const DECISION: &str = "decision";
    pub const GAME_OVER: &str = "game-over";
    pub const SCORE: &str = "score";
    pub const GAME_CLOCK: &str = "game-clock";
    pub const RF_ACTION: &str = "rf-action";
    pub const RF_RESULT: &str = "rf-result";
    pub const MACHINE: &str = "machine";
    pub const STATE: &str = "state";
    pub const HOLDING: &str = "holding";
}

/// Defines a symbol enum with its CLIPS spelling both ways.
macro_rules! symbol_enum {
    ($(#[$doc:meta])* $name:ident { $($variant:ident => $text:literal),+ $(,)? }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $name {
            $($variant),+
        }

        impl $name {
            pub const ALL: &'static [$name] = &[$($name::$variant),+];

            /// The CLIPS symbol.
            pub fn as_str(self) -> &'static str {
                match self {
                    $($name::$variant => $text),+
                }
            }

            /// Parses the CLIPS symbol.
            pub fn from_symbol(symbol: &str) -> Option<$name> {
                match symbol {
                    $($text => Some($name::$variant),)+
                    _ => None,
                }
            }
        }
    };
}

symbol_enum!(
    /// What the robot can hold.
    Puck { None => "NONE", S0 => "S0", S1 => "S1", S2 => "S2", P => "P", Junk => "JUNK" }
);

symbol_enum!(
    /// A machine's signal light as a skill outcome reports it (`none` when
    /// the skill did not read one).
    Light {
        None => "none",
        Green => "green",
        Yellow => "yellow",
        YellowFlashing => "yellow-flashing",
        Red => "red",
        Off => "off",
    }
);

symbol_enum!(
    /// The skills the agent requests.
    Skill {
        GetS0 => "get-s0",
        FinishPuckAt => "finish-puck-at",
        Deliver => "deliver",
        Discard => "discard",
        GetJunk => "get-junk",
        Recycle => "recycle",
    }
);

symbol_enum!(
    /// The agent's belief about a machine's type: the types still possible.
    TypeBelief {
        Unknown => "T1_2_3",
        T1or2 => "T1_2",
        T2or3 => "T2_3",
        T1 => "T1",
        T2 => "T2",
        T3 => "T3",
    }
);

symbol_enum!(
    /// Why a game ended.
    GameEnd { Time => "time", Done => "done", Deadlock => "deadlock" }
);

impl TypeBelief {
    /// True once a single type remains.
    pub fn is_known(self) -> bool {
        matches!(self, TypeBelief::T1 | TypeBelief::T2 | TypeBelief::T3)
    }
}

/// One machine's belief as logged: type class and up to three loaded pucks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MachineBelief {
    pub mtype: TypeBelief,
    loaded: [Puck; 3],
    loaded_len: usize,
}

impl MachineBelief {
    /// The loaded pucks, in loading order.
    pub fn loaded(&self) -> &[Puck] {
        &self.loaded[..self.loaded_len]
    }

    /// Parses a `(decision (beliefs ...))` symbol such as `T2_3+S0`.
    pub fn parse(symbol: &str) -> Option<MachineBelief> {
        let mut parts = symbol.split('+');
        let mtype = TypeBelief::from_symbol(parts.next()?)?;
        let mut belief = MachineBelief {
            mtype,
            loaded: [Puck::None; 3],
            loaded_len: 0,
        };
        for part in parts {
            let puck = Puck::from_symbol(part).filter(|p| *p != Puck::None)?;
            *belief.loaded.get_mut(belief.loaded_len)? = puck;
            belief.loaded_len += 1;
        }
        Some(belief)
    }
}
