//! The one error type of the run-time layer: gms-core's rules, and what only this layer refuses.

use core::fmt;

use gms_core::{Field, InChannel};

use crate::kind::HysteresisKind;
use crate::MAX_ELEMENTS;

/// Why a parameter set, an input or a call was refused; [`Display`](fmt::Display) writes the
/// whole message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Error {
    /// A rule of gms-core.
    Core(gms_core::Error),
    /// A rule of gms-core, broken in one channel of several.
    Channel(InChannel),
    /// Both linear hysteresis (`sigma0`) and Maxwell-slip elements were given.
    BothHysteresis,
    /// Neither linear hysteresis (`sigma0`) nor Maxwell-slip elements were given.
    NeitherHysteresis,
    /// `W` and `Delta` were given, but empty.
    EmptyElements,
    /// More than [`MAX_ELEMENTS`] elements.
    TooManyElements {
        /// The number that came.
        count: usize,
    },
    /// `W` and `Delta` have different lengths.
    ElementLengths {
        /// Length of `W`.
        w: usize,
        /// Length of `Delta`.
        delta: usize,
    },
    /// New parameters of another kind or number of elements than the compensator's.
    Incompatible {
        /// The compensator's hysteresis.
        expected: HysteresisKind,
        /// The new parameters' hysteresis.
        got: HysteresisKind,
    },
    /// The states of `channels` channels (or the copy an all-or-nothing run keeps) do not fit
    /// in memory.
    OutOfMemory {
        /// The number of channels asked for.
        channels: usize,
        /// Bytes of state per channel.
        bytes_each: usize,
    },
    /// A channel index beyond the bank.
    ChannelIndex {
        /// The index that came.
        channel: usize,
        /// The number of channels of the bank.
        channels: usize,
    },
    /// An input of `len` samples that does not split into rows of equal length, one a channel.
    SignalShape {
        /// Number of samples that came.
        len: usize,
        /// Number of channels of the bank.
        channels: usize,
    },
    /// An online identifier needs 1 to [`MAX_ELEMENTS`] break deflections.
    DeflectionCount {
        /// The number that came.
        count: usize,
    },
    /// An online identifier's initial estimate needs N + 3 values.
    InitialLength {
        /// Number of elements N.
        elements: usize,
        /// The number of values that came.
        got: usize,
    },
    /// A state written into channel `channel` breaks a rule of gms-core (an element outside its
    /// window, a non-finite value).
    State {
        /// Index of the channel.
        channel: usize,
        /// The rule broken.
        error: gms_core::Error,
    },
    /// A break deflection of [`slip_responses`](crate::slip_responses) is not finite and > 0,
    /// or so small that 1/Delta overflows.
    BreakDeflection {
        /// Index of the element.
        index: usize,
        /// The value that came.
        value: f64,
    },
}

/// What an [`Error`] is about, for the bindings that sort errors into classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// A parameter breaks its rule.
    Parameter,
    /// An input signal, step size, option or index is not what the call expects.
    Input,
    /// The explicit scheme blew up: the step is too large for the stiffness.
    Divergence,
}

impl Error {
    /// What the error is about.
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::Core(error) | Error::Channel(InChannel { error, .. }) => core_kind(error),
            Error::BothHysteresis
            | Error::NeitherHysteresis
            | Error::EmptyElements
            | Error::TooManyElements { .. }
            | Error::ElementLengths { .. }
            | Error::Incompatible { .. }
            | Error::DeflectionCount { .. }
            | Error::InitialLength { .. } => ErrorKind::Parameter,
            Error::OutOfMemory { .. }
            | Error::ChannelIndex { .. }
            | Error::SignalShape { .. }
            | Error::BreakDeflection { .. }
            | Error::State { .. } => ErrorKind::Input,
        }
    }

    /// The gms-core error inside, if there is one.
    pub fn core(&self) -> Option<gms_core::Error> {
        match self {
            Error::Core(error)
            | Error::Channel(InChannel { error, .. })
            | Error::State { error, .. } => Some(*error),
            _ => None,
        }
    }
}

/// Fields that are inputs of a call rather than parameters of a model.
fn is_input(field: Field) -> bool {
    matches!(
        field,
        Field::dt
            | Field::v
            | Field::x
            | Field::u
            | Field::f
            | Field::regressor
            | Field::z
            | Field::zeta
    )
}

fn core_kind(error: &gms_core::Error) -> ErrorKind {
    use gms_core::Error as Core;
    match *error {
        Core::Diverged { .. } => ErrorKind::Divergence,
        Core::NotPositive { field, .. }
        | Core::Negative { field, .. }
        | Core::NotFiniteValue { field, .. }
        | Core::NotInUnitInterval { field, .. }
        | Core::NotFinite { field, .. }
        | Core::Missing { field } => {
            if is_input(field) {
                ErrorKind::Input
            } else {
                ErrorKind::Parameter
            }
        }
        Core::StaticBelowCoulomb { .. }
        | Core::Element { .. }
        | Core::NoElements
        | Core::ElementsTooWeak { .. }
        | Core::ForceSumOverflow { .. }
        | Core::StiffnessOverflow { .. }
        | Core::StiffnessSumOverflow
        | Core::DeltaTooNarrow { .. }
        | Core::TraceBelowInitial { .. }
        | Core::TooManyRipples { .. }
        | Core::RipplePeriod { .. }
        | Core::HarmonicLengths { .. }
        | Core::TooManyHarmonics { .. }
        | Core::RippleCoefficient { .. }
        | Core::LevelTooDeep { .. }
        | Core::PhaseUnresolved { .. } => ErrorKind::Parameter,
        Core::VelocityNotFinite { .. }
        | Core::Overflow { .. }
        | Core::InputsOverflow { .. }
        | Core::InputLengthMismatch { .. }
        | Core::StateOutsideWindow { .. }
        | Core::LengthMismatch { .. } => ErrorKind::Input,
    }
}

impl From<gms_core::Error> for Error {
    fn from(error: gms_core::Error) -> Self {
        Error::Core(error)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::Core(error) => error.fmt(f),
            Error::Channel(error) => error.fmt(f),
            Error::BothHysteresis => f.write_str(
                "give either `sigma0` (linear hysteresis) or `W` + `Delta` (Maxwell slip), got both",
            ),
            Error::NeitherHysteresis => f.write_str(
                "give either `sigma0` (linear hysteresis) or `W` + `Delta` (Maxwell slip), got \
                 neither",
            ),
            Error::EmptyElements => {
                f.write_str("`W` and `Delta` need at least one element, got empty sequences")
            }
            Error::TooManyElements { count } => write!(
                f,
                "`W` and `Delta` may have at most {MAX_ELEMENTS} elements, got {count}"
            ),
            Error::ElementLengths { w, delta } => write!(
                f,
                "`W` and `Delta` must have the same length, got {w} and {delta}"
            ),
            Error::Incompatible { expected, got } => write!(
                f,
                "new parameters must have {expected} like the compensator's, got {got}"
            ),
            Error::OutOfMemory {
                channels,
                bytes_each,
            } => write!(
                f,
                "`channels` = {channels} does not fit in memory ({bytes_each} bytes of state each)"
            ),
            Error::ChannelIndex { channel, channels } => write!(
                f,
                "channel {channel} does not exist: there are {channels}"
            ),
            Error::SignalShape { len, channels } => write!(
                f,
                "an input of {len} samples does not split into {channels} channels of equal length"
            ),
            Error::DeflectionCount { count } => write!(
                f,
                "`Delta` must have 1 to {MAX_ELEMENTS} elements, got {count}"
            ),
            Error::InitialLength { elements, got } => write!(
                f,
                "`initial` must have {} values (W for each of the {elements} elements, Fc, \
                 sigma2, offset), got {got}",
                elements + gms_core::identification::EXTRA_TERMS
            ),
            Error::State { channel, error } => write!(f, "state of channel {channel}: {error}"),
            Error::BreakDeflection { index, value } => write!(
                f,
                "`Delta[{index}]` must be finite and > 0 (and 1/Delta finite), got {}",
                gms_core::Shown(value)
            ),
        }
    }
}

impl std::error::Error for Error {}
