//! The one error type of the run-time layer: gms-core's rules, and what only this layer refuses.

use core::fmt;

use gms_core::{Field, InChannel};
use strum::VariantNames;

use crate::kind::HysteresisKind;
use crate::MAX_ELEMENTS;

/// Why a parameter set, an input or a call was refused; [`Display`](fmt::Display) writes the
/// whole message, [`Error::details`] gives its data (kind, field, value) without parsing it.
#[derive(Clone, Copy, Debug, PartialEq, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "snake_case")]
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
pub enum ErrorClass {
    /// A parameter breaks its rule.
    Parameter,
    /// An input signal, step size, option or index is not what the call expects.
    Input,
    /// The explicit scheme blew up: the step is too large for the stiffness.
    Divergence,
}

impl Error {
    /// The exception class the error belongs to.
    pub fn class(&self) -> ErrorClass {
        match self {
            Error::Core(error) | Error::Channel(InChannel { error, .. }) => core_class(error),
            Error::BothHysteresis
            | Error::NeitherHysteresis
            | Error::EmptyElements
            | Error::TooManyElements { .. }
            | Error::ElementLengths { .. }
            | Error::Incompatible { .. }
            | Error::DeflectionCount { .. }
            | Error::InitialLength { .. } => ErrorClass::Parameter,
            Error::OutOfMemory { .. }
            | Error::ChannelIndex { .. }
            | Error::SignalShape { .. }
            | Error::BreakDeflection { .. }
            | Error::State { .. } => ErrorClass::Input,
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

    /// The error's kind: gms-core's variant name for the rules of gms-core (`"not_finite"`,
    /// `"elements_too_weak"`), this layer's variant name otherwise (`"too_many_elements"`), both
    /// in snake case.
    pub fn kind(&self) -> &'static str {
        match self.core() {
            Some(error) => error.kind(),
            None => self.into(),
        }
    }

    /// Every kind an [`Error`] can have: gms-core's, then this layer's own.
    pub fn kinds() -> impl Iterator<Item = &'static str> {
        gms_core::Error::KINDS.iter().copied().chain(
            Self::VARIANTS
                .iter()
                .copied()
                .filter(|kind| !WRAPPERS.contains(kind)),
        )
    }

    /// The data of the error, as the bindings attach it to an exception (docs/errors.md#error-data).
    pub fn details(&self) -> Details {
        let own = Details::new(self.kind());
        match *self {
            Error::Core(error) => core_details(error),
            Error::Channel(InChannel { channel, error }) | Error::State { channel, error } => {
                Details {
                    channel: Some(channel),
                    ..core_details(error)
                }
            }
            Error::BothHysteresis | Error::NeitherHysteresis => own.key("sigma0"),
            Error::EmptyElements => own.key("W"),
            Error::TooManyElements { count } => own
                .key("W")
                .value(Number::Count(count))
                .bound(Number::Count(MAX_ELEMENTS)),
            Error::DeflectionCount { count } => own
                .key("Delta")
                .value(Number::Count(count))
                .bound(Number::Count(MAX_ELEMENTS)),
            Error::ElementLengths { w, delta } => own.key("Delta").lengths(w, delta),
            Error::Incompatible { expected, got } => own
                .key("params")
                .lengths(expected.elements(), got.elements()),
            Error::OutOfMemory { channels, .. } => {
                own.key("channels").value(Number::Count(channels))
            }
            Error::ChannelIndex { channel, channels } => own
                .key("channel")
                .value(Number::Count(channel))
                .bound(Number::Count(channels)),
            Error::SignalShape { len, channels } => {
                own.value(Number::Count(len)).bound(Number::Count(channels))
            }
            Error::InitialLength { elements, got } => own
                .key("initial")
                .lengths(elements + gms_core::identification::EXTRA_TERMS, got),
            Error::BreakDeflection { index, value } => {
                own.element("Delta", index).value(Number::Real(value))
            }
        }
    }
}

/// The variants of [`Error`] that wrap a gms-core error, whose kind is the wrapped one's.
const WRAPPERS: [&str; 3] = ["core", "channel", "state"];

/// A value an error carries: a real number, or a count (of elements, samples, channels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Number {
    /// A real number.
    Real(f64),
    /// A count or an index.
    Count(usize),
}

/// Where an error points, spelled as the user wrote it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// A parameter, an argument or a state member: `"Fs"`, `"dt"`, `"channels"`.
    Key(&'static str),
    /// Element `index` of a sequence: `"W[2]"`.
    Element(&'static str, usize),
    /// Ripple `ripple` of a level, one of its members, and an entry of that member:
    /// `"ripples[0]"`, `"ripples[0].period"`, `"ripples[1].cos[3]"`.
    Ripple {
        /// Index of the ripple.
        ripple: usize,
        /// `period`, `cos` or `sin`, if the error is about one of them.
        member: Option<&'static str>,
        /// Index of the amplitude, if the error is about one.
        index: Option<usize>,
    },
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Location::Key(key) => f.write_str(key),
            Location::Element(key, index) => write!(f, "{key}[{index}]"),
            Location::Ripple {
                ripple,
                member,
                index,
            } => {
                write!(f, "ripples[{ripple}]")?;
                if let Some(member) = member {
                    write!(f, ".{member}")?;
                }
                if let Some(index) = index {
                    write!(f, "[{index}]")?;
                }
                Ok(())
            }
        }
    }
}

/// The data of an [`Error`] (docs/errors.md#error-data): what the Python exception carries as
/// attributes, so that a caller reads them instead of parsing the message. Each is `None`
/// where the error has no such datum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Details {
    /// The error's kind, [`Error::kind`].
    pub kind: &'static str,
    /// The parameter, argument or state member at fault.
    pub field: Option<Location>,
    /// The offending value.
    pub value: Option<Number>,
    /// The limit the value had to reach or stay within (`Fc` for `Fs`, the largest count).
    pub bound: Option<Number>,
    /// The index of the element or entry at fault: the last index that `field` spells.
    pub index: Option<usize>,
    /// The sample of a signal.
    pub sample: Option<usize>,
    /// The channel of a bank.
    pub channel: Option<usize>,
    /// The length or count expected (for a swap of parameters: the compensator's number of
    /// elements, 0 for linear hysteresis).
    pub expected: Option<usize>,
    /// The length or count that came.
    pub got: Option<usize>,
}

impl Details {
    const fn new(kind: &'static str) -> Self {
        Details {
            kind,
            field: None,
            value: None,
            bound: None,
            index: None,
            sample: None,
            channel: None,
            expected: None,
            got: None,
        }
    }

    const fn key(self, key: &'static str) -> Self {
        Details {
            field: Some(Location::Key(key)),
            ..self
        }
    }

    const fn element(self, key: &'static str, index: usize) -> Self {
        Details {
            field: Some(Location::Element(key, index)),
            index: Some(index),
            ..self
        }
    }

    const fn ripple(
        self,
        ripple: usize,
        member: Option<&'static str>,
        index: Option<usize>,
    ) -> Self {
        Details {
            field: Some(Location::Ripple {
                ripple,
                member,
                index,
            }),
            index: match index {
                Some(index) => Some(index),
                None => Some(ripple),
            },
            ..self
        }
    }

    const fn value(self, value: Number) -> Self {
        Details {
            value: Some(value),
            ..self
        }
    }

    const fn real(self, value: f64) -> Self {
        self.value(Number::Real(value))
    }

    const fn bound(self, bound: Number) -> Self {
        Details {
            bound: Some(bound),
            ..self
        }
    }

    const fn sample(self, sample: usize) -> Self {
        Details {
            sample: Some(sample),
            ..self
        }
    }

    const fn lengths(self, expected: usize, got: usize) -> Self {
        Details {
            expected: Some(expected),
            got: Some(got),
            ..self
        }
    }
}

/// The data of a gms-core error (one channel's, or of a single step).
fn core_details(error: gms_core::Error) -> Details {
    use gms_core::Error as Core;
    let details = Details::new(error.kind());
    match error {
        Core::NotPositive { field, value }
        | Core::Negative { field, value }
        | Core::NotFiniteValue { field, value }
        | Core::NotInUnitInterval { field, value } => details.key(field.key()).real(value),
        Core::StaticBelowCoulomb {
            field,
            coulomb,
            value,
        } => details
            .key(field.key())
            .real(value)
            .bound(Number::Real(coulomb)),
        Core::Element {
            field,
            index,
            value,
        } => details.element(field.key(), index).real(value),
        Core::NoElements => details.key("W"),
        Core::ForceSumOverflow { index, largest } => details.element("W", index).real(largest),
        Core::StiffnessOverflow { index, delta, .. } => details.element("Delta", index).real(delta),
        Core::StiffnessSumOverflow => details.key("Delta"),
        Core::DeltaTooNarrow {
            index,
            value,
            widest,
        } => details
            .element("Delta", index)
            .real(value)
            .bound(Number::Real(widest * gms_core::MIN_DELTA_RATIO)),
        Core::StateOutsideWindow {
            index,
            deflection,
            limit,
        } => details
            .element("zeta", index)
            .real(deflection)
            .bound(Number::Real(limit)),
        Core::ElementsTooWeak { sum, peak } => details.key("W").real(sum).bound(Number::Real(peak)),
        Core::NotFinite {
            field,
            index,
            value,
        } => match field {
            // A parameter vector, not a signal: its entries are not samples.
            Field::initial | Field::regressor | Field::trend => {
                details.element(field.key(), index).real(value)
            }
            _ => details.key(field.key()).real(value).sample(index),
        },
        Core::VelocityNotFinite { x, .. } => details.key("x").real(x),
        Core::Diverged { index }
        | Core::Overflow { index }
        | Core::InputsOverflow { index, .. } => details.sample(index),
        Core::TraceBelowInitial {
            parameters,
            initial_covariance,
            max_trace,
        } => details
            .key("max_trace")
            .real(max_trace)
            .bound(Number::Real(parameters as f64 * initial_covariance)),
        Core::InputLengthMismatch {
            field,
            expected,
            got,
        } => details.key(field.key()).lengths(expected, got),
        Core::LengthMismatch { expected, got } => details.lengths(expected, got),
        Core::TooManyRipples { .. }
        | Core::RipplePeriod { .. }
        | Core::HarmonicLengths { .. }
        | Core::TooManyHarmonics { .. }
        | Core::RippleCoefficient { .. }
        | Core::LevelTooDeep { .. }
        | Core::PhaseUnresolved { .. } => series_details(details, error),
        Core::Missing { field } => details.key(field.key()),
    }
}

/// The data of a refused level or position force (`details` holds the kind).
fn series_details(details: Details, error: gms_core::Error) -> Details {
    use gms_core::Error as Core;
    match error {
        Core::TooManyRipples { count } => details
            .key("ripples")
            .value(Number::Count(count))
            .bound(Number::Count(gms_core::MAX_RIPPLES)),
        Core::RipplePeriod { ripple, value } => {
            details.ripple(ripple, Some("period"), None).real(value)
        }
        Core::HarmonicLengths { ripple, cos, sin } => {
            details.ripple(ripple, Some("sin"), None).lengths(cos, sin)
        }
        Core::TooManyHarmonics { ripple, count } => details
            .ripple(ripple, None, None)
            .value(Number::Count(count))
            .bound(Number::Count(gms_core::MAX_HARMONICS)),
        Core::RippleCoefficient {
            field,
            ripple,
            index,
            value,
        } => details
            .ripple(ripple, Some(field.key()), Some(index))
            .real(value),
        Core::LevelTooDeep { sum } => details.real(sum).bound(Number::Real(1.0)),
        Core::PhaseUnresolved {
            field,
            index,
            value,
            extent,
        } => match field {
            Field::period => details
                .ripple(index, Some("period"), None)
                .real(value)
                .bound(Number::Real(gms_core::PositionSeries::finest(extent))),
            // The middle is refused for the half stroke it leaves unresolved: no bound of its own.
            Field::middle => details.key(field.key()).real(value),
            _ => details
                .key(field.key())
                .real(value)
                .bound(Number::Real(gms_core::PositionSeries::finest(extent))),
        },
        _ => details,
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

fn core_class(error: &gms_core::Error) -> ErrorClass {
    use gms_core::Error as Core;
    match *error {
        Core::Diverged { .. } => ErrorClass::Divergence,
        Core::NotPositive { field, .. }
        | Core::Negative { field, .. }
        | Core::NotFiniteValue { field, .. }
        | Core::NotInUnitInterval { field, .. }
        | Core::NotFinite { field, .. }
        | Core::Missing { field } => {
            if is_input(field) {
                ErrorClass::Input
            } else {
                ErrorClass::Parameter
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
        | Core::PhaseUnresolved { .. } => ErrorClass::Parameter,
        Core::VelocityNotFinite { .. }
        | Core::Overflow { .. }
        | Core::InputsOverflow { .. }
        | Core::InputLengthMismatch { .. }
        | Core::StateOutsideWindow { .. }
        | Core::LengthMismatch { .. } => ErrorClass::Input,
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
