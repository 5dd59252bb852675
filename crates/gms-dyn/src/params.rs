//! Parameter sets as callers give them, and validated with their number of elements in the type.
//!
//! This module is the one place where a run-time element count becomes a compile-time one: the
//! table of [`ParameterSet`] variants, and the two macros that dispatch over it
//! ([`with_params`]) and over a bare element count ([`with_element_count`]), all spell out
//! 1..=32, which must be [`MAX_ELEMENTS`].

use gms_core::{Hysteresis, Linear, LuGreParams, MaxwellSlip, Params, Stribeck};
use seq_macro::seq;

use crate::channels::Memory;
use crate::error::Error;
use crate::kind::HysteresisKind;
use crate::MAX_ELEMENTS;

// The macros below and the variants of `ParameterSet` are written for 1..=32 elements.
const _: () = assert!(MAX_ELEMENTS == 32);

/// Runs `$body` with `$params` bound to the gms-core parameters inside the [`ParameterSet`]
/// `$set`, whatever its variant (each arm is compiled for its own hysteresis type).
///
/// Exported so that a crate built on this one (gms-fit) dispatches over the same table rather
/// than spelling out a second one: `gms_dyn::with_params!(set, params => run(params))`, with
/// `run` generic over the hysteresis.
#[macro_export]
macro_rules! with_params {
    ($set:expr, $params:ident => $body:expr) => {
        $crate::__seq!(N in 1..=32 {
            match $set {
                $crate::ParameterSet::Linear($params) => $body,
                #( $crate::ParameterSet::Maxwell~N($params) => $body, )*
            }
        })
    };
}
pub(crate) use crate::with_params;

/// Evaluates `$body` with the const `$n` equal to `$count` when it is in 1..=[`MAX_ELEMENTS`],
/// and `$otherwise` when not.
macro_rules! with_element_count {
    ($count:expr, $n:ident => $body:expr, _ => $otherwise:expr) => {
        seq_macro::seq!($n in 1..=32 {
            match $count {
                #( $n => $body, )*
                _ => $otherwise,
            }
        })
    };
}
pub(crate) use with_element_count;

/// The Maxwell-slip elements of a raw parameter set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawElements<'a> {
    /// Saturation forces Wᵢ.
    pub w: &'a [f64],
    /// Break deflections Δᵢ.
    pub delta: &'a [f64],
}

/// A parameter set as plain values, exactly as a caller gives it, not yet validated.
///
/// The direction-dependent levels are resolved by the caller (Python's `None` and C's 0 both
/// mean "same as `Fc`/`Fs`"); `sigma2_neg` is `None` when not given ("same as `sigma2`").
/// Exactly one of `sigma0` and `elements` should be given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawParams<'a> {
    /// Coulomb level.
    pub fc: f64,
    /// Static level.
    pub fs: f64,
    /// Stribeck velocity.
    pub vs: f64,
    /// Stribeck shape exponent.
    pub delta: f64,
    /// Transition-curve exponent.
    pub n: f64,
    /// Micro-viscous coefficient.
    pub sigma1: f64,
    /// Viscous coefficient.
    pub sigma2: f64,
    /// Coulomb level for negative velocity.
    pub fc_neg: f64,
    /// Static level for negative velocity.
    pub fs_neg: f64,
    /// Viscous coefficient for negative velocity; `None`: `sigma2`.
    pub sigma2_neg: Option<f64>,
    /// Stiffness of linear hysteresis, if that is the kind given.
    pub sigma0: Option<f64>,
    /// Maxwell-slip elements, if that is the kind given (possibly empty).
    pub elements: Option<RawElements<'a>>,
}

impl RawParams<'_> {
    /// The kind of hysteresis given: Maxwell slip whenever elements are given (even alongside
    /// `sigma0`, which validation then refuses), linear otherwise.
    pub fn kind(&self) -> HysteresisKind {
        match self.elements {
            Some(elements) => HysteresisKind::Maxwell {
                elements: elements.w.len(),
            },
            None => HysteresisKind::Linear,
        }
    }

    /// Checks every rule of the model (docs/parameters.md#rules) and returns the validated set.
    ///
    /// # Errors
    /// The first rule broken, with the value that broke it.
    pub fn validate(&self) -> Result<ParameterSet, Error> {
        match (self.sigma0, self.elements) {
            (Some(_), Some(_)) => Err(Error::BothHysteresis),
            (None, None) => Err(Error::NeitherHysteresis),
            (Some(sigma0), None) => {
                let spring = Linear::new(sigma0)?;
                Ok(ParameterSet::Linear(self.params(spring)?))
            }
            (None, Some(RawElements { w, delta })) => {
                if w.len() != delta.len() {
                    return Err(Error::ElementLengths {
                        w: w.len(),
                        delta: delta.len(),
                    });
                }
                with_element_count!(w.len(), N => self.maxwell::<N>(w, delta), _ => Err(if w.is_empty() {
                    Error::EmptyElements
                } else {
                    Error::TooManyElements { count: w.len() }
                }))
            }
        }
    }

    fn maxwell<const N: usize>(&self, w: &[f64], delta: &[f64]) -> Result<ParameterSet, Error>
    where
        ParameterSet: From<Params<MaxwellSlip<N>>>,
    {
        let (mut w_array, mut delta_array) = ([0.0; N], [0.0; N]);
        w_array.copy_from_slice(w);
        delta_array.copy_from_slice(delta);
        let elements = MaxwellSlip::new(w_array, delta_array)?;
        Ok(self.params(elements)?.into())
    }

    fn params<H: Hysteresis>(&self, hysteresis: H) -> Result<Params<H>, gms_core::Error> {
        let stribeck = Stribeck::asymmetric(
            self.fc,
            self.fs,
            self.fc_neg,
            self.fs_neg,
            self.vs,
            self.delta,
        )?;
        let params = Params::new(stribeck, self.n, self.sigma1, self.sigma2, hysteresis)?;
        match self.sigma2_neg {
            Some(sigma2_neg) => params.with_sigma2_neg(sigma2_neg),
            None => Ok(params),
        }
    }
}

/// The hysteresis types a [`ParameterSet`] can hold, and how to find them in one.
pub(crate) trait InParameterSet: Hysteresis + Sized {
    /// The parameters inside `set`, if they are of this type.
    fn find(set: &ParameterSet) -> Option<Params<Self>>;
}

seq!(N in 1..=32 {
    /// A validated parameter set, with its kind of hysteresis and number of elements in the
    /// type of its variant (`Maxwell7` holds 7 elements).
    #[derive(Clone, Copy, Debug, PartialEq)]
    // The variants are the dispatch table itself; boxing the large ones would allocate in the
    // parameter swap of the C API, which promises not to.
    #[allow(clippy::large_enum_variant)]
    pub enum ParameterSet {
        /// Linear (LuGre-like) hysteresis.
        Linear(LuGreParams),
        #(
            /// Maxwell slip with the variant's number of elements.
            Maxwell~N(Params<MaxwellSlip<N>>),
        )*
    }

    #(
        impl From<Params<MaxwellSlip<N>>> for ParameterSet {
            fn from(params: Params<MaxwellSlip<N>>) -> Self {
                ParameterSet::Maxwell~N(params)
            }
        }

        impl InParameterSet for MaxwellSlip<N> {
            fn find(set: &ParameterSet) -> Option<Params<Self>> {
                match set {
                    ParameterSet::Maxwell~N(params) => Some(*params),
                    _ => None,
                }
            }
        }
    )*
});

impl From<LuGreParams> for ParameterSet {
    fn from(params: LuGreParams) -> Self {
        ParameterSet::Linear(params)
    }
}

impl InParameterSet for Linear {
    fn find(set: &ParameterSet) -> Option<Params<Self>> {
        match set {
            ParameterSet::Linear(params) => Some(*params),
            _ => None,
        }
    }
}

impl ParameterSet {
    /// The kind of hysteresis and its number of elements.
    pub fn kind(&self) -> HysteresisKind {
        with_params!(self, params => kind_of(params))
    }

    /// Number of Maxwell-slip elements (0 for linear hysteresis).
    pub fn elements(&self) -> usize {
        self.kind().elements()
    }
}

fn kind_of<H>(_params: &Params<H>) -> HysteresisKind
where
    H: Hysteresis<Memory: Memory>,
{
    match <H::Memory as Memory>::LEN {
        0 => HysteresisKind::Linear,
        elements => HysteresisKind::Maxwell { elements },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw<'a>(w: &'a [f64], delta: &'a [f64]) -> RawParams<'a> {
        RawParams {
            fc: 1.0,
            fs: 1.5,
            vs: 1e-3,
            delta: 2.0,
            n: 2.0,
            sigma1: 30.0,
            sigma2: 0.4,
            fc_neg: 1.0,
            fs_neg: 1.5,
            sigma2_neg: None,
            sigma0: None,
            elements: Some(RawElements { w, delta }),
        }
    }

    #[test]
    fn the_count_chooses_the_variant() {
        for count in 1..=MAX_ELEMENTS {
            let w = vec![2.0 / count as f64; count];
            let delta = vec![1e-6; count];
            let set = raw(&w, &delta).validate().unwrap();
            assert_eq!(set.kind(), HysteresisKind::Maxwell { elements: count });
        }
        let linear = RawParams {
            sigma0: Some(1e5),
            elements: None,
            ..raw(&[], &[])
        };
        assert_eq!(linear.validate().unwrap().kind(), HysteresisKind::Linear);
    }

    #[test]
    fn refusals_of_this_layer() {
        let many = [1.0; MAX_ELEMENTS + 1];
        assert_eq!(
            raw(&many, &many).validate(),
            Err(Error::TooManyElements {
                count: MAX_ELEMENTS + 1
            })
        );
        assert_eq!(
            raw(&[1.0; 3], &[1e-6; 4]).validate(),
            Err(Error::ElementLengths { w: 3, delta: 4 })
        );
        assert_eq!(raw(&[], &[]).validate(), Err(Error::EmptyElements));
        let both = RawParams {
            sigma0: Some(1e5),
            ..raw(&[1.0; 2], &[1e-6; 2])
        };
        assert_eq!(both.validate(), Err(Error::BothHysteresis));
        let neither = RawParams {
            elements: None,
            ..raw(&[], &[])
        };
        assert_eq!(neither.validate(), Err(Error::NeitherHysteresis));
    }
}
