//! One compensator axis whatever its number of elements, behind an object-safe trait.
//!
//! gms-core fixes the number of Maxwell-slip elements N in the type; a C caller chooses it at
//! run time. [`build`] monomorphises the compensator for every N up to 32 (and
//! for linear hysteresis) and hands it back boxed. This is the one allocation of the C API, at
//! create time; stepping and swapping parameters never allocate.

use gms_core::{Compensator, Error, Hysteresis, Linear, MaxwellSlip, Mode, Params, Stribeck};
use seq_macro::seq;

use crate::LEUVEN_RT_MAX_ELEMENTS as MAX_ELEMENTS;

// `build` instantiates the compensator for 1..=32 elements.
const _: () = assert!(MAX_ELEMENTS == 32);

/// Parameters as a C caller gives them, before validation (pointers already turned into
/// slices). `fc_neg`/`fs_neg` of 0 mean "same as `fc`/`fs`"; `w` empty means linear
/// hysteresis `sigma0`.
#[derive(Clone, Copy, Debug)]
pub struct Spec<'a> {
    pub fc: f64,
    pub fs: f64,
    pub fc_neg: f64,
    pub fs_neg: f64,
    pub vs: f64,
    pub delta: f64,
    pub n: f64,
    pub sigma1: f64,
    pub sigma2: f64,
    pub sigma0: f64,
    pub w: &'a [f64],
    pub big_delta: &'a [f64],
}

/// Why a parameter set was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecError {
    /// A rule of DESIGN.md §2, as gms-core states it.
    Invalid(Error),
    /// Both `sigma0` and elements were given.
    BothHysteresis,
    /// More than `LEUVEN_RT_MAX_ELEMENTS` elements.
    TooManyElements(usize),
    /// New parameters of another kind or number of elements than the compensator's.
    Incompatible {
        /// Elements of the compensator (0: linear hysteresis).
        expected: usize,
        /// Elements of the new parameters (0: linear hysteresis).
        got: usize,
    },
}

impl From<Error> for SpecError {
    fn from(error: Error) -> Self {
        SpecError::Invalid(error)
    }
}

impl Spec<'_> {
    fn stribeck(&self) -> Result<Stribeck, Error> {
        let or = |value: f64, default: f64| if value == 0.0 { default } else { value };
        Stribeck::asymmetric(
            self.fc,
            self.fs,
            or(self.fc_neg, self.fc),
            or(self.fs_neg, self.fs),
            self.vs,
            self.delta,
        )
    }

    fn params<H>(&self, hysteresis: H) -> Result<Params<H>, Error>
    where
        H: Hysteresis,
    {
        Params::new(
            self.stribeck()?,
            self.n,
            self.sigma1,
            self.sigma2,
            hysteresis,
        )
    }
}

/// A hysteresis whose parameters can be read from a [`Spec`] of the same kind and size.
trait FromSpec: Hysteresis + Sized {
    /// Number of elements (0 for linear hysteresis).
    const ELEMENTS: usize;
    fn from_spec(spec: &Spec<'_>) -> Result<Params<Self>, SpecError>;
}

impl<const N: usize> FromSpec for MaxwellSlip<N> {
    const ELEMENTS: usize = N;
    fn from_spec(spec: &Spec<'_>) -> Result<Params<Self>, SpecError> {
        let (Ok(w), Ok(delta)) = (
            <[f64; N]>::try_from(spec.w),
            <[f64; N]>::try_from(spec.big_delta),
        ) else {
            return Err(SpecError::Incompatible {
                expected: N,
                got: spec.w.len(),
            });
        };
        if spec.sigma0 != 0.0 {
            return Err(SpecError::BothHysteresis);
        }
        Ok(spec.params(MaxwellSlip::new(w, delta)?)?)
    }
}

impl FromSpec for Linear {
    const ELEMENTS: usize = 0;
    fn from_spec(spec: &Spec<'_>) -> Result<Params<Self>, SpecError> {
        if !spec.w.is_empty() {
            return Err(SpecError::Incompatible {
                expected: 0,
                got: spec.w.len(),
            });
        }
        Ok(spec.params(Linear::new(spec.sigma0)?)?)
    }
}

/// One compensator axis, whatever its hysteresis.
pub trait Axis: Send {
    /// [`Compensator::step`].
    fn step(&mut self, input: f64) -> Result<f64, Error>;
    /// Validates `spec` (same kind and number of elements) and swaps it in.
    fn set_params(&mut self, spec: &Spec<'_>) -> Result<(), SpecError>;
    /// [`Compensator::reset`].
    fn reset(&mut self);
    /// [`Compensator::output`].
    fn output(&self) -> f64;
    /// Number of Maxwell-slip elements (0 for linear hysteresis).
    fn elements(&self) -> usize;
}

impl<H> Axis for Compensator<H>
where
    H: FromSpec + Send,
    H::Memory: Send,
{
    #[inline]
    fn step(&mut self, input: f64) -> Result<f64, Error> {
        Compensator::step(self, input)
    }

    fn set_params(&mut self, spec: &Spec<'_>) -> Result<(), SpecError> {
        Compensator::set_params(self, H::from_spec(spec)?);
        Ok(())
    }

    fn reset(&mut self) {
        Compensator::reset(self);
    }

    fn output(&self) -> f64 {
        Compensator::output(self)
    }

    fn elements(&self) -> usize {
        H::ELEMENTS
    }
}

fn boxed<H>(spec: &Spec<'_>, dt: f64, mode: Mode) -> Result<Box<dyn Axis>, SpecError>
where
    H: FromSpec + Send + 'static,
    H::Memory: Send,
{
    Ok(Box::new(Compensator::new(H::from_spec(spec)?, dt, mode)?))
}

/// Validates `spec` and `dt` and builds an axis at rest.
pub fn build(spec: &Spec<'_>, dt: f64, mode: Mode) -> Result<Box<dyn Axis>, SpecError> {
    if spec.w.len() != spec.big_delta.len() {
        // The C API takes one count for both arrays; this only guards the Rust entry point.
        return Err(SpecError::Incompatible {
            expected: spec.w.len(),
            got: spec.big_delta.len(),
        });
    }
    seq!(N in 1..=32 {
        match spec.w.len() {
            0 => boxed::<Linear>(spec, dt, mode),
            #(N => boxed::<MaxwellSlip<N>>(spec, dt, mode),)*
            count => Err(SpecError::TooManyElements(count)),
        }
    })
}
