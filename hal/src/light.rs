//! The signal light of an LLSF machine, as the robot perceives it.

/// One perceived light state. Symbols match the facts and payloads: `green`, `yellow`,
/// `yellow-flashing`, `red`, `off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum LightSignal {
    /// Idle, or cycle complete (the robot now holds the output).
    Green = 0,
    /// Input consumed, more needed (the robot holds nothing).
    Yellow = 1,
    /// Wrong input: the robot keeps its puck.
    YellowFlashing = 2,
    /// Out of order.
    Red = 3,
    /// Offline.
    Off = 4,
}

impl LightSignal {
    pub const ALL: [LightSignal; 5] = [
        Self::Green,
        Self::Yellow,
        Self::YellowFlashing,
        Self::Red,
        Self::Off,
    ];

    /// The symbol used in facts.
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Green => "green",
            Self::Yellow => "yellow",
            Self::YellowFlashing => "yellow-flashing",
            Self::Red => "red",
            Self::Off => "off",
        }
    }

    /// The wire code (the `repr(u8)` discriminant).
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// Decodes a wire code; `None` for unknown codes.
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            0 => Some(Self::Green),
            1 => Some(Self::Yellow),
            2 => Some(Self::YellowFlashing),
            3 => Some(Self::Red),
            4 => Some(Self::Off),
            _ => None,
        }
    }

    /// Parses a fact symbol.
    pub fn from_symbol(symbol: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|l| l.symbol() == symbol)
    }
}

#[cfg(test)]
mod tests {
    use super::LightSignal;

    #[test]
    fn codes_and_symbols_round_trip() {
        for light in LightSignal::ALL {
            assert_eq!(LightSignal::from_code(light.code()), Some(light));
            assert_eq!(LightSignal::from_symbol(light.symbol()), Some(light));
        }
        assert_eq!(LightSignal::from_code(5), None);
        assert_eq!(LightSignal::from_symbol("orange"), None);
    }
}
