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
            Error::LengthMismatch { expected, got } => {
                write!(f, "output has length {got}, expected {expected}")
            }
        }
    }
}

impl core::error::Error for Error {}
