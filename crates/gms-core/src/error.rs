//! The one error type of the crate: small, `Copy`, allocation-free, and naming the field at fault.

use core::fmt;

/// A named input of the model.
///
/// The variants are spelled exactly like the keys of a parameter file (docs/parameters.md#keys) and the
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
    /// Viscous coefficient for negative velocity.
    sigma2_neg,
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
    /// Deflection z of a channel state written by a caller.
    z,
    /// Element positions ζ of a channel state written by a caller.
    zeta,
    /// Middle of the stroke of a position-dependent level.
    middle,
    /// Half the stroke of a position-dependent level.
    half_stroke,
    /// Legendre coefficients (t1, t2) of a level's trend.
    trend,
    /// Cosine amplitudes of a level's ripple.
    cos,
    /// Sine amplitudes of a level's ripple.
    sin,
    /// Period of a ripple of a level or position force.
    period,
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
            Field::sigma2_neg => "sigma2_neg",
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
            Field::z => "z",
            Field::zeta => "zeta",
            Field::middle => "middle",
            Field::half_stroke => "half_stroke",
            Field::trend => "trend",
            Field::cos => "cos",
            Field::sin => "sin",
            Field::period => "period",
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// Everything that can be wrong with parameters or inputs, with the value that broke the rule.
///
/// Small and `Copy`, so that a real-time step can return it; its [`Display`](fmt::Display)
/// writes the whole message ("`Fc` must be finite and > 0, got -1.0"), with floats spelled as
/// Python prints them (`0.0`, `nan`, `inf`) because the Python package shows these messages.
///
/// Two errors are equal when they are the same variant with bit-identical values, so that an
/// error carrying NaN equals itself (and `Eq` holds).
///
/// [`Error::kind`] names the variant in snake case (`"not_finite"`, `"elements_too_weak"`): the
/// bindings hand it on as the error's `kind` (docs/errors.md#error-data).
#[derive(Clone, Copy, Debug, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "snake_case")]
pub enum Error {
    /// The field must be finite and strictly positive (and not subnormal).
    NotPositive {
        /// The field at fault.
        field: Field,
        /// The value that came.
        value: f64,
    },
    /// The field must be finite and non-negative.
    Negative {
        /// The field at fault.
        field: Field,
        /// The value that came.
        value: f64,
    },
    /// The field must be finite (any sign).
    NotFiniteValue {
        /// The field at fault.
        field: Field,
        /// The value that came.
        value: f64,
    },
    /// A static level is below its Coulomb level (`Fs < Fc` or `Fs_neg < Fc_neg`).
    StaticBelowCoulomb {
        /// `Fs` or `Fs_neg`.
        field: Field,
        /// The Coulomb level it must reach (`Fc` or `Fc_neg`).
        coulomb: f64,
        /// The static level that came.
        value: f64,
    },
    /// Element `index` of `W` or `Delta` is not finite and strictly positive (or W/Δ overflows).
    Element {
        /// `W` or `Delta`.
        field: Field,
        /// Index of the offending element.
        index: usize,
        /// The value that came.
        value: f64,
    },
    /// A Maxwell-slip bank needs at least one element.
    NoElements,
    /// `sum(W)` overflows: the saturation forces are too large for f64 arithmetic.
    ForceSumOverflow {
        /// Index of the largest `W[i]`.
        index: usize,
        /// That largest `W[i]`.
        largest: f64,
    },
    /// The stiffness `W[index]/Delta[index]` of one element overflows.
    StiffnessOverflow {
        /// Index of the element.
        index: usize,
        /// Its `W[index]`.
        w: f64,
        /// Its `Delta[index]`.
        delta: f64,
    },
    /// The total stiffness Σ `W[i]/Delta[i]` of the bank overflows although each term is finite.
    StiffnessSumOverflow,
    /// `Delta[index]` is narrower than [`MIN_DELTA_RATIO`](crate::MIN_DELTA_RATIO) times the
    /// widest `Delta`: below the rounding unit of z, the element's window cannot be resolved.
    DeltaTooNarrow {
        /// Index of the narrow element.
        index: usize,
        /// Its `Delta[index]`.
        value: f64,
        /// The widest `Delta`.
        widest: f64,
    },
    /// A written channel state has element `index` outside its window: |z − ζᵢ| > Δᵢ (beyond a
    /// rounding tolerance), or a non-finite ζᵢ.
    StateOutsideWindow {
        /// Index of the element.
        index: usize,
        /// The deflection z − ζᵢ that came.
        deflection: f64,
        /// The element's `Delta[index]`, the largest |z − ζᵢ| allowed.
        limit: f64,
    },
    /// `sum(W) <= max(Fs, Fs_neg)`: the hysteresis force can never balance the Stribeck curve.
    ElementsTooWeak {
        /// The largest hysteresis force, sum(W).
        sum: f64,
        /// The largest static level, max(`Fs`, `Fs_neg`).
        peak: f64,
    },
    /// Input sample `index` of `field` is NaN or infinite (a single step reports index 0).
    NotFinite {
        /// `v`, `x`, `u`, `f`, or the entries of `initial`.
        field: Field,
        /// Index of the first offending sample.
        index: usize,
        /// The value that came (for a velocity computed from positions, that velocity).
        value: f64,
    },
    /// A finite position `x` after `previous` over `dt` gives a velocity that is not finite.
    VelocityNotFinite {
        /// The position that came.
        x: f64,
        /// The position before it.
        previous: f64,
        /// The time step.
        dt: f64,
    },
    /// The explicit scheme produced a non-finite state at sample `index`; the step is too
    /// large for the stiffness. The state is left as it was before that sample.
    Diverged {
        /// Index of the sample whose step diverged.
        index: usize,
    },
    /// The field must be in the interval (0, 1].
    NotInUnitInterval {
        /// The field at fault.
        field: Field,
        /// The value that came.
        value: f64,
    },
    /// `max_trace` is below the trace of the initial covariance (parameters × `initial_covariance`).
    TraceBelowInitial {
        /// Number of estimated parameters.
        parameters: usize,
        /// The initial covariance p0 of each parameter.
        initial_covariance: f64,
        /// The `max_trace` that came.
        max_trace: f64,
    },
    /// A least-squares update overflowed although its inputs were finite: they are too large
    /// for f64 arithmetic (inputs far outside SI magnitudes). The state is left as it was
    /// before that sample (a single update reports index 0).
    Overflow {
        /// Index of the sample whose update overflowed.
        index: usize,
    },
    /// As [`Error::Overflow`], for an online identifier that knows its inputs x, v and f.
    InputsOverflow {
        /// Index of the sample whose update overflowed.
        index: usize,
        /// The position of that sample.
        x: f64,
        /// The velocity of that sample.
        v: f64,
        /// The measured force of that sample (NaN for a prediction, which has none).
        f: f64,
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
    /// A level with more than [`MAX_RIPPLES`](crate::MAX_RIPPLES) ripples.
    TooManyRipples {
        /// The number that came.
        count: usize,
    },
    /// The period of ripple `ripple` is not finite and > 0 (or is subnormal).
    RipplePeriod {
        /// Index of the ripple.
        ripple: usize,
        /// The value that came.
        value: f64,
    },
    /// Ripple `ripple` has `cos` and `sin` amplitudes of different lengths.
    HarmonicLengths {
        /// Index of the ripple.
        ripple: usize,
        /// Length of `cos`.
        cos: usize,
        /// Length of `sin`.
        sin: usize,
    },
    /// Ripple `ripple` has more than [`MAX_HARMONICS`](crate::MAX_HARMONICS) harmonics.
    TooManyHarmonics {
        /// Index of the ripple.
        ripple: usize,
        /// The number that came.
        count: usize,
    },
    /// Amplitude `index` (harmonic `index + 1`) of `cos` or `sin` of ripple `ripple` is not
    /// finite.
    RippleCoefficient {
        /// `cos` or `sin`.
        field: Field,
        /// Index of the ripple.
        ripple: usize,
        /// Index of the amplitude.
        index: usize,
        /// The value that came.
        value: f64,
    },
    /// Σ|trend| + Σ|cos| + Σ|sin| of a level is not below 1: the factor could reach 0 or less.
    LevelTooDeep {
        /// The sum that came.
        sum: f64,
    },
    /// The half stroke or a ripple's period of a level or position force is below 2²⁰ ulps of
    /// the largest position it covers, max(|middle| + `half_stroke`, 1): its phase cannot be
    /// resolved there (docs/model.md#position-dependent-level).
    PhaseUnresolved {
        /// `half_stroke`; `period` (of ripple `index`); or `middle`, too far from 0 for the
        /// half stroke.
        field: Field,
        /// Index of the ripple for `period`, 0 otherwise.
        index: usize,
        /// The value that came.
        value: f64,
        /// max(|middle| + `half_stroke`, 1): the largest |x| at which the phase must be resolved.
        extent: f64,
    },
    /// A value that must be given was not: `x`, the start position of a feedforward
    /// compensator with a level or a position force.
    Missing {
        /// The field that was not given.
        field: Field,
    },
}

/// A float as the Python package prints it: shortest round-trip digits, `nan`, `inf`, `-inf`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown(pub f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_nan() {
            f.write_str("nan")
        } else {
            // Debug is Rust's shortest round-trip spelling, `inf` and `-inf` included.
            write!(f, "{:?}", self.0)
        }
    }
}

/// Why a positive value was refused although it is > 0: it is subnormal, and its reciprocal
/// overflows.
fn subnormal_note(value: f64) -> &'static str {
    if value > 0.0 && value < f64::MIN_POSITIVE {
        " (a subnormal number: at least 2.2e-308 is needed)"
    } else {
        ""
    }
}

/// An [`Error`] of one channel among several: sample-located messages name the channel too
/// ("at channel 2, sample 7"); the others read as without it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InChannel {
    /// Index of the channel.
    pub channel: usize,
    /// What went wrong there.
    pub error: Error,
}

impl Error {
    /// The [`kind`](Error::kind) of every variant, in their order.
    pub const KINDS: &'static [&'static str] = <Self as strum::VariantNames>::VARIANTS;

    /// The variant's name in snake case, e.g. `"not_finite"` for [`Error::NotFinite`].
    pub fn kind(self) -> &'static str {
        self.into()
    }

    /// This error, located in `channel` of several.
    pub const fn in_channel(self, channel: usize) -> InChannel {
        InChannel {
            channel,
            error: self,
        }
    }

    #[allow(clippy::too_many_lines)] // one arm per variant
    fn write(&self, f: &mut fmt::Formatter<'_>, channel: Option<usize>) -> fmt::Result {
        let at = |f: &mut fmt::Formatter<'_>, index: usize| match channel {
            Some(channel) => write!(f, "channel {channel}, sample {index}"),
            None => write!(f, "sample {index}"),
        };
        match *self {
            Error::NotPositive { field, value } => write!(
                f,
                "`{field}` must be finite and > 0, got {}{}",
                Shown(value),
                subnormal_note(value)
            ),
            Error::Negative { field, value } => {
                write!(f, "`{field}` must be finite and >= 0, got {}", Shown(value))
            }
            Error::NotFiniteValue { field, value } => {
                write!(f, "`{field}` must be finite, got {}", Shown(value))
            }
            Error::StaticBelowCoulomb {
                field,
                coulomb,
                value,
            } => {
                let coulomb_field = if field == Field::Fs_neg {
                    Field::Fc_neg
                } else {
                    Field::Fc
                };
                write!(
                    f,
                    "`{field}` must be >= `{coulomb_field}` = {}, got {}",
                    Shown(coulomb),
                    Shown(value)
                )
            }
            Error::Element {
                field,
                index,
                value,
            } => write!(
                f,
                "`{field}[{index}]` must be finite and > 0, got {}",
                Shown(value)
            ),
            Error::NoElements => f.write_str("`W` and `Delta` need at least one element"),
            Error::ForceSumOverflow { index, largest } => write!(
                f,
                "`sum(W)` must be finite, got elements that add up to more than 1.8e308 \
                 (largest `W[{index}]` = {}): the saturation forces are too large for f64 \
                 arithmetic (are they in SI units?)",
                Shown(largest)
            ),
            Error::StiffnessOverflow { index, w, delta } => write!(
                f,
                "the stiffness `W[{index}]`/`Delta[{index}]` = {}/{} must be finite, got a \
                 quotient that overflows: the element is too stiff for f64 arithmetic",
                Shown(w),
                Shown(delta)
            ),
            Error::StiffnessSumOverflow => f.write_str(
                "the total stiffness sum(W[i]/Delta[i]) must be finite, got a sum that \
                 overflows: the elements are too stiff for f64 arithmetic",
            ),
            Error::DeltaTooNarrow {
                index,
                value,
                widest,
            } => write!(
                f,
                "`Delta[{index}]` must be >= 2^-26 (about 1.5e-8) times the widest Delta = {}, \
                 i.e. >= {}, got {}: z is resolved only to about 2.2e-16 × {}, so a narrower \
                 element's window would be decided by rounding (docs/parameters.md#rules)",
                Shown(widest),
                Shown(widest * crate::MIN_DELTA_RATIO),
                Shown(value),
                Shown(widest)
            ),
            Error::StateOutsideWindow {
                index,
                deflection,
                limit,
            } => write!(
                f,
                "`zeta[{index}]` must be within `Delta[{index}]` = {} of z, i.e. |z - \
                 zeta[{index}]| <= {}, got z - zeta[{index}] = {}",
                Shown(limit),
                Shown(limit),
                Shown(deflection)
            ),
            Error::ElementsTooWeak { sum, peak } => write!(
                f,
                "`sum(W)` must be > max(`Fs`, `Fs_neg`) = {}, got sum(W) = {}: the hysteresis \
                 force could never balance the Stribeck curve",
                Shown(peak),
                Shown(sum)
            ),
            Error::NotFinite {
                field,
                index,
                value,
            } => {
                write!(f, "`{field}` must be finite, got {} at ", Shown(value))?;
                match field {
                    // A parameter vector, not a signal: its entries are not samples.
                    Field::initial | Field::regressor | Field::trend => {
                        write!(f, "entry {index}")
                    }
                    _ => at(f, index),
                }
            }
            Error::VelocityNotFinite { x, previous, dt } => write!(
                f,
                "`x` = {} after {} over dt = {} gives a velocity that is not finite",
                Shown(x),
                Shown(previous),
                Shown(dt)
            ),
            Error::Diverged { index } => {
                f.write_str("the explicit step diverged at ")?;
                at(f, index)?;
                f.write_str(": dt is too large for the stiffness; use the implicit scheme")
            }
            Error::NotInUnitInterval { field, value } => {
                write!(f, "`{field}` must be in (0, 1], got {}", Shown(value))
            }
            Error::TraceBelowInitial {
                parameters,
                initial_covariance,
                max_trace,
            } => {
                // The same product the check compares with.
                #[allow(clippy::cast_precision_loss)] // a parameter count is far below 2^52
                let trace = parameters as f64 * initial_covariance;
                write!(
                    f,
                    "`max_trace` must be >= the trace of the initial covariance, {parameters} × \
                     initial_covariance = {}, got {}",
                    Shown(trace),
                    Shown(max_trace)
                )
            }
            Error::Overflow { index } => {
                f.write_str("the least-squares update overflowed at ")?;
                at(f, index)?;
                f.write_str(": the inputs are too large for f64 arithmetic (are they in SI units?)")
            }
            Error::InputsOverflow {
                index,
                x,
                v,
                f: force,
            } => {
                f.write_str("the least-squares update overflowed at ")?;
                at(f, index)?;
                write!(
                    f,
                    ": x = {}, v = {}, f = {} are too large for f64 arithmetic (are they in SI \
                     units?)",
                    Shown(x),
                    Shown(v),
                    Shown(force)
                )
            }
            Error::InputLengthMismatch {
                field,
                expected,
                got,
            } => write!(f, "`{field}` has length {got}, expected {expected}"),
            Error::LengthMismatch { expected, got } => {
                write!(f, "output has length {got}, expected {expected}")
            }
            Error::TooManyRipples { count } => write!(
                f,
                "`ripples` must have at most {} ripples, got {count}",
                crate::MAX_RIPPLES
            ),
            Error::RipplePeriod { ripple, value } => write!(
                f,
                "`ripples[{ripple}].period` must be finite and > 0, got {}{}",
                Shown(value),
                subnormal_note(value)
            ),
            Error::HarmonicLengths { ripple, cos, sin } => write!(
                f,
                "`ripples[{ripple}].cos` and `ripples[{ripple}].sin` must have the same length, \
                 got {cos} and {sin}"
            ),
            Error::TooManyHarmonics { ripple, count } => write!(
                f,
                "`ripples[{ripple}]` must have at most {} harmonics, got {count}",
                crate::MAX_HARMONICS
            ),
            Error::RippleCoefficient {
                field,
                ripple,
                index,
                value,
            } => write!(
                f,
                "`ripples[{ripple}].{field}[{index}]` must be finite, got {}",
                Shown(value)
            ),
            Error::LevelTooDeep { sum } => write!(
                f,
                "the level's amplitudes must have sum(|trend|) + sum(|cos|) + sum(|sin|) < 1 (so \
                 that the factor stays > 0 everywhere), got {}",
                Shown(sum)
            ),
            Error::PhaseUnresolved {
                field,
                index,
                value,
                extent,
            } => {
                let finest = crate::resolution::finest(extent);
                match field {
                    Field::period => write!(f, "`ripples[{index}].period`")?,
                    Field::middle => write!(
                        f,
                        "`middle` must leave `half_stroke` at least 2^20 ulps of \
                         max(|middle| + half_stroke, 1) = {} (>= {}), got middle = {}: the \
                         position along the stroke cannot be resolved that far from 0",
                        Shown(extent),
                        Shown(finest),
                        Shown(value)
                    )?,
                    _ => write!(f, "`{field}`")?,
                }
                if field == Field::middle {
                    return Ok(());
                }
                let what = if field == Field::period {
                    "its phase"
                } else {
                    "the position along the stroke"
                };
                write!(
                    f,
                    " must be at least 2^20 ulps of the largest position covered, max(|middle| \
                     + half_stroke, 1) = {}, i.e. >= {}, got {}: {what} cannot be resolved there",
                    Shown(extent),
                    Shown(finest),
                    Shown(value)
                )
            }
            Error::Missing { field } => match field {
                Field::x => f.write_str(
                    "`x`, the axis's start position, must be given to a feedforward compensator \
                     with a level or a position force: otherwise they are evaluated from x = 0, \
                     out of phase with the machine",
                ),
                _ => write!(f, "`{field}` must be given"),
            },
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, None)
    }
}

impl fmt::Display for InChannel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.error.write(f, Some(self.channel))
    }
}

impl PartialEq for Error {
    #[allow(clippy::too_many_lines)] // one arm per variant
    fn eq(&self, other: &Self) -> bool {
        // Bit-identical floats: NaN equals itself, 0.0 and -0.0 differ (they print differently).
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        match (*self, *other) {
            (
                Error::NotPositive { field, value },
                Error::NotPositive {
                    field: other,
                    value: v,
                },
            )
            | (
                Error::Negative { field, value },
                Error::Negative {
                    field: other,
                    value: v,
                },
            )
            | (
                Error::NotFiniteValue { field, value },
                Error::NotFiniteValue {
                    field: other,
                    value: v,
                },
            )
            | (
                Error::NotInUnitInterval { field, value },
                Error::NotInUnitInterval {
                    field: other,
                    value: v,
                },
            ) => field == other && same(value, v),
            (
                Error::StaticBelowCoulomb {
                    field,
                    coulomb,
                    value,
                },
                Error::StaticBelowCoulomb {
                    field: other,
                    coulomb: c,
                    value: v,
                },
            ) => field == other && same(coulomb, c) && same(value, v),
            (
                Error::Element {
                    field,
                    index,
                    value,
                },
                Error::Element {
                    field: other,
                    index: i,
                    value: v,
                },
            )
            | (
                Error::NotFinite {
                    field,
                    index,
                    value,
                },
                Error::NotFinite {
                    field: other,
                    index: i,
                    value: v,
                },
            ) => field == other && index == i && same(value, v),
            (Error::NoElements, Error::NoElements)
            | (Error::StiffnessSumOverflow, Error::StiffnessSumOverflow) => true,
            (
                Error::ForceSumOverflow { index, largest },
                Error::ForceSumOverflow {
                    index: i,
                    largest: l,
                },
            ) => index == i && same(largest, l),
            (
                Error::StiffnessOverflow { index, w, delta },
                Error::StiffnessOverflow {
                    index: i,
                    w: w2,
                    delta: d,
                },
            ) => index == i && same(w, w2) && same(delta, d),
            (
                Error::DeltaTooNarrow {
                    index,
                    value,
                    widest,
                },
                Error::DeltaTooNarrow {
                    index: i,
                    value: v,
                    widest: w,
                },
            ) => index == i && same(value, v) && same(widest, w),
            (
                Error::StateOutsideWindow {
                    index,
                    deflection,
                    limit,
                },
                Error::StateOutsideWindow {
                    index: i,
                    deflection: d,
                    limit: l,
                },
            ) => index == i && same(deflection, d) && same(limit, l),
            (Error::ElementsTooWeak { sum, peak }, Error::ElementsTooWeak { sum: s, peak: p }) => {
                same(sum, s) && same(peak, p)
            }
            (
                Error::VelocityNotFinite { x, previous, dt },
                Error::VelocityNotFinite {
                    x: x2,
                    previous: p,
                    dt: d,
                },
            ) => same(x, x2) && same(previous, p) && same(dt, d),
            (Error::TooManyRipples { count }, Error::TooManyRipples { count: c }) => count == c,
            (
                Error::RipplePeriod { ripple, value },
                Error::RipplePeriod {
                    ripple: r,
                    value: v,
                },
            ) => ripple == r && same(value, v),
            (
                Error::HarmonicLengths { ripple, cos, sin },
                Error::HarmonicLengths {
                    ripple: r,
                    cos: c,
                    sin: s,
                },
            ) => ripple == r && cos == c && sin == s,
            (
                Error::TooManyHarmonics { ripple, count },
                Error::TooManyHarmonics {
                    ripple: r,
                    count: c,
                },
            ) => ripple == r && count == c,
            (
                Error::RippleCoefficient {
                    field,
                    ripple,
                    index,
                    value,
                },
                Error::RippleCoefficient {
                    field: other,
                    ripple: r,
                    index: i,
                    value: v,
                },
            ) => field == other && ripple == r && index == i && same(value, v),
            (Error::LevelTooDeep { sum }, Error::LevelTooDeep { sum: s }) => same(sum, s),
            (
                Error::PhaseUnresolved {
                    field,
                    index,
                    value,
                    extent,
                },
                Error::PhaseUnresolved {
                    field: other,
                    index: i,
                    value: v,
                    extent: e,
                },
            ) => field == other && index == i && same(value, v) && same(extent, e),
            (Error::Missing { field }, Error::Missing { field: other }) => field == other,
            (Error::Diverged { index }, Error::Diverged { index: i })
            | (Error::Overflow { index }, Error::Overflow { index: i }) => index == i,
            (
                Error::TraceBelowInitial {
                    parameters,
                    initial_covariance,
                    max_trace,
                },
                Error::TraceBelowInitial {
                    parameters: p,
                    initial_covariance: c,
                    max_trace: m,
                },
            ) => parameters == p && same(initial_covariance, c) && same(max_trace, m),
            (
                Error::InputsOverflow { index, x, v, f },
                Error::InputsOverflow {
                    index: i,
                    x: x2,
                    v: v2,
                    f: f2,
                },
            ) => index == i && same(x, x2) && same(v, v2) && same(f, f2),
            (
                Error::InputLengthMismatch {
                    field,
                    expected,
                    got,
                },
                Error::InputLengthMismatch {
                    field: other,
                    expected: e,
                    got: g,
                },
            ) => field == other && expected == e && got == g,
            (
                Error::LengthMismatch { expected, got },
                Error::LengthMismatch {
                    expected: e,
                    got: g,
                },
            ) => expected == e && got == g,
            _ => false,
        }
    }
}

impl Eq for Error {}

impl core::error::Error for Error {}

impl core::error::Error for InChannel {}
