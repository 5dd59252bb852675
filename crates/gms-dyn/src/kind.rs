//! The kind of hysteresis of a parameter set, and its size: what a compensator's parameters
//! may be swapped for, and what an error names when they may not.

use core::fmt;

/// The kind of hysteresis of a parameter set, and its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HysteresisKind {
    /// Linear (LuGre-like) hysteresis `sigma0`.
    Linear,
    /// Maxwell slip with this many elements.
    Maxwell {
        /// Number of elements.
        elements: usize,
    },
}

impl HysteresisKind {
    /// Number of Maxwell-slip elements (0 for linear hysteresis).
    pub fn elements(self) -> usize {
        match self {
            HysteresisKind::Linear => 0,
            HysteresisKind::Maxwell { elements } => elements,
        }
    }
}

impl fmt::Display for HysteresisKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HysteresisKind::Linear => f.write_str("linear hysteresis `sigma0`"),
            HysteresisKind::Maxwell { elements } => write!(f, "{elements} Maxwell-slip elements"),
        }
    }
}
