//! The one error type of the crate: small, `Copy`, allocation-free, and naming the field at fault.

use core::fmt;

/// A named input of the model.
///
/// The variants are spelled exactly like the keys of a parameter file (DESIGN.md §2) and the
/// arguments of the step functions, so that an error can be traced to the key the user wrote.
#[allow(non_camel_case_types)] // the paper's and the parameter file's spelling wins over Rust's
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// Coulomb friction level.
    Fc,
    /// Static (break-away) friction level.
    Fs,
    /// Stribeck velocity.
    Vs,
    /// Stribeck shape exponent δ.
    delta,
    /// Transition-curve exponent.
    n,
    /// Stiffness of the linear (LuGre) hysteresis.
    sigma0,
    /// Micro-viscous coefficient.
    sigma1,
    /// Viscous coefficient.
    sigma2,
    /// Saturation forces of the Maxwell-slip elements.
    W,
    /// Break deflections of the Maxwell-slip elements.
    Delta,
    /// Coulomb level for negative velocity.
    Fc_neg,
    /// Static level for negative velocity.
    Fs_neg,
    /// Time step.
    dt,
    /// Velocity input.
    v,
    /// Position input.
    x,
    /// Mass of a simulated machine (`MassSystem`).
    mass,
    /// Stiffness of the spring that holds or drags a simulated mass.
    stiffness,
    /// Speed at which the far end of that spring is dragged.
    drive_speed,
    /// Force applied to a simulated mass.
    u,
    /// Measured force (the output of online identification).
    f,
    /// Forgetting factor λ of recursive least squares.
    forgetting,
    /// Initial covariance p0 of recursive least squares (P = p0·I).
    initial_covariance,
    /// Bound on the trace of the covariance of recursive least squares.
    max_trace,
    /// Initial parameter estimate of recursive least squares.
    initial,
    /// Regressor of recursive least squares.
    regressor,
}

impl Field {
    /// The key of the field in a parameter file, or the argument name of a step function.
    pub const fn key(self) -> &'static str {
        match self {
            Field::Fc => "Fc",
            Field::Fs => "Fs",
            Field::Vs => "Vs",
            Field::delta => "delta",
            Field::n => "n",
            Field::sigma0 => "sigma0",
            Field::sigma1 => "sigma1",
            Field::sigma2 => "sigma2",
            Field::W => "W",
            Field::Delta => "Delta",
            Field::Fc_neg => "Fc_neg",
            Field::Fs_neg => "Fs_neg",
            Field::dt => "dt",
            Field::v => "v",
            Field::x => "x",
            Field::mass => "mass",
            Field::stiffness => "stiffness",
            Field::drive_speed => "drive_speed",
            Field::u => "u",
            Field::f => "f",
            Field::forgetting => "forgetting",
            Field::initial_covariance => "initial_covariance",
            Field::max_trace => "max_trace",
            Field::initial => "initial",
            Field::regressor => "regressor",
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// Everything that can be wrong with parameters or inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Error {
    /// The field must be finite and strictly positive.
    NotPositive(Field),
    /// The field must be finite and non-negative.
    Negative(Field),
    /// The field must be finite (any sign).
    NotFiniteValue(Field),
    /// A static level is below its Coulomb level (`Fs < Fc` or `Fs_neg < Fc_neg`).
    StaticBelowCoulomb(Field),
    /// Element `index` of `W` or `Delta` is not finite and strictly positive.
    Element {
        /// `W` or `Delta`.
        field: Field,
        /// Index of the offending element.
        index: usize,
    },
    /// A Maxwell-slip bank needs at least one element.
    NoElements,
    /// `sum(W) <= max(Fs, Fs_neg)`: the hysteresis force can never balance the Stribeck curve.
    ElementsTooWeak,
    /// Input sample `index` of `field` is NaN or infinite (a single step reports index 0).
    NotFinite {
        /// `v`, `x` or `dt`.
        field: Field,
        /// Index of the first offending sample.
        index: usize,
    },
    /// The explicit scheme produced a non-finite state at sample `index`; the step is too
    /// large for the stiffness. The state is left as it was before that sample.
    Diverged {
        /// Index of the sample whose step diverged.
        index: usize,
    },
    /// The field must be in the interval (0, 1].
    NotInUnitInterval(Field),
    /// `max_trace` is below the trace of the initial covariance (parameters × `initial_covariance`).
    TraceBelowInitial,
    /// A least-squares update overflowed although its inputs were finite: they are too large
    /// for f64 arithmetic (inputs far outside SI magnitudes). The state is left as it was
    /// before that sample (a single update reports index 0).
    Overflow {
        /// Index of the sample whose update overflowed.
        index: usize,
    },
    /// An input slice of a block call does not have the length of the first input.
    InputLengthMismatch {
        /// The input whose length is wrong.
        field: Field,
        /// Length of the first input.
        expected: usize,
        /// Length that came.
        got: usize,
    },
    /// A block call's output slice does not have the length of its input.
    LengthMismatch {
        /// Length of the input.
        expected: usize,
        /// Length of the output slice that came.
        got: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NotPositive(field) => write!(f, "`{field}` must be finite and > 0"),
            Error::Negative(field) => write!(f, "`{field}` must be finite and >= 0"),
            Error::NotFiniteValue(field) => write!(f, "`{field}` must be finite"),
            Error::StaticBelowCoulomb(Field::Fs_neg) => f.write_str("`Fs_neg` must be >= `Fc_neg`"),
            Error::StaticBelowCoulomb(field) => write!(f, "`{field}` must be >= `Fc`"),
            Error::Element { field, index } => {
                write!(f, "`{field}[{index}]` must be finite and > 0")
            }
            Error::NoElements => f.write_str("`W` and `Delta` need at least one element"),
            Error::ElementsTooWeak => f.write_str(
                "`sum(W)` must be > max(`Fs`, `Fs_neg`), or steady sliding is unreachable",
            ),
            Error::NotFinite { field, index } => {
                write!(f, "`{field}` must be finite (sample {index} is not)")
            }
            Error::Diverged { index } => write!(
                f,
                "the explicit step diverged at sample {index}: dt is too large for the \
                 stiffness; use the implicit scheme"
            ),
            Error::NotInUnitInterval(field) => write!(f, "`{field}` must be in (0, 1]"),
            Error::TraceBelowInitial => f.write_str(
                "`max_trace` must be >= the trace of the initial covariance \
                 (parameters × `initial_covariance`)",
            ),
            Error::Overflow { index } => write!(
                f,
                "the least-squares update overflowed at sample {index}: the inputs are too \
                 large for f64 arithmetic (are they in SI units?)"
            ),
            Error::InputLengthMismatch {
                field,
                expected,
                got,
            } => write!(f, "`{field}` has length {got}, expected {expected}"),
            Error::LengthMismatch { expected, got } => {
                write!(f, "output has length {got}, expected {expected}")
            }
        }
    }
}

impl core::error::Error for Error {}
