//! Online identification of the friction terms that enter linearly, sample by sample.

use crate::checks::finite;
use crate::error::{Error, Field};

use super::regressor::SlipRegressor;
use super::rls::{Rls, RlsSettings};

/// Number of terms besides the N element weights: Fc, sigma2, offset.
pub const EXTRA_TERMS: usize = 3;

/// Names of the terms besides the element weights, in the order of the estimate.
pub const EXTRA_TERM_NAMES: [&str; EXTRA_TERMS] = ["Fc", "sigma2", "offset"];

/// Recursive least squares on F = Σᵢ Wᵢ·ψᵢ(x) + Fc·sgn(v) + sigma2·v + offset, with N
/// Maxwell-slip elements of fixed break deflections Δᵢ.
///
/// The estimate is `[W₀, …, W_{N−1}, Fc, sigma2, offset]`, so `P` must be `N + 3` (checked
/// when the program is compiled).
///
/// # The terms, and what the data must contain to separate them
///
/// - `Wᵢ·ψᵢ`: the presliding hysteresis, as in the paper's identification (Δᵢ pre-assigned,
///   equally spaced up to the presliding range). ψᵢ comes from [`SlipRegressor`].
/// - `Fc·sgn(v)`: the part of the friction level that switches at once at a reversal. It is
///   the limit of an element with Δ → 0, and in steady sliding it is exactly collinear with the
///   elements (every ψᵢ = sgn(v)): sliding data identify only `Fc + ΣWᵢ`. The two are told apart
///   only by the samples right after a reversal, while the travel is shorter than the largest
///   Δᵢ, and the Wᵢ among themselves by reversals of different amplitudes. So the excitation
///   must contain reversals (and small oscillations) for the split to mean anything. This is
///   handled, not hidden: the initial covariance p₀·I is a ridge prior, so a split that the data
///   never inform stays where the initial estimate put it instead of wandering; with forgetting
///   the bound on trace(P) stops that direction's covariance from winding up. The sum
///   `Fc + ΣWᵢ` and the prediction are well determined either way.
/// - `sigma2·v`: viscous friction (the paper's σ2). σ1 (micro-viscous) does not enter linearly
///   with the model's z, and is left out. One σ2 serves both directions, as one `Fc` does: the
///   identifier fits the symmetric model, whose columns stay separable from a short window of
///   data. A direction-dependent model (`Fc_neg`, `Fs_neg`, `sigma2_neg`) is identified
///   offline (docs/effects.md, `asymmetry`); a column min(v, 0) for `sigma2_neg` would be
///   collinear with `sigma2·v` on any stretch of motion in one direction.
/// - `offset`: a constant force bias of the measurement. It is separated from `Fc` by motion in
///   both directions.
///
/// sgn(0) = 0. The velocity should be a measured or filtered one: with noisy finite
/// differences, sgn(v) chatters while the machine sticks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnlineIdentifier<const N: usize, const P: usize> {
    regressor: SlipRegressor<N>,
    rls: Rls<P>,
}

impl<const N: usize, const P: usize> OnlineIdentifier<N, P> {
    /// Elements with break deflections `delta`, starting from the estimate `initial`.
    ///
    /// Rules: those of [`SlipRegressor::new`] and [`Rls::new`].
    pub fn new(delta: [f64; N], initial: [f64; P], settings: RlsSettings) -> Result<Self, Error> {
        const {
            assert!(
                P == N + EXTRA_TERMS,
                "P must be N + 3: W (N of them), Fc, sigma2, offset"
            );
        };
        Ok(Self {
            regressor: SlipRegressor::new(delta)?,
            rls: Rls::new(initial, settings)?,
        })
    }

    /// One sample: position `x`, velocity `v`, measured force `f`. Returns the a priori
    /// prediction error f − f̂ (f̂ from the estimate before this sample).
    ///
    /// A non-finite input, or an update that overflows, is reported and leaves everything (the
    /// elements included) as it was. Never panics, never allocates.
    pub fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, Error> {
        for (value, field) in [(x, Field::x), (v, Field::v), (f, Field::f)] {
            finite(value, field)?;
        }
        let mut regressor = self.regressor;
        let phi = regressor_at(&mut regressor, x, v);
        let error = self.rls.update(&phi, f).map_err(|error| match error {
            Error::Overflow { index } => Error::InputsOverflow { index, x, v, f },
            other => other,
        })?;
        self.regressor = regressor;
        Ok(error)
    }

    /// Runs a whole log, writing the estimate after each sample into `estimates`.
    ///
    /// `v`, `f` and `estimates` must have the length of `x`. All or nothing: if a sample is
    /// rejected, the state is left as it was before the call and the error names the sample.
    pub fn run(
        &mut self,
        x: &[f64],
        v: &[f64],
        f: &[f64],
        estimates: &mut [[f64; P]],
    ) -> Result<(), Error> {
        for (input, field) in [(v, Field::v), (f, Field::f)] {
            if input.len() != x.len() {
                return Err(Error::InputLengthMismatch {
                    field,
                    expected: x.len(),
                    got: input.len(),
                });
            }
        }
        if estimates.len() != x.len() {
            return Err(Error::LengthMismatch {
                expected: x.len(),
                got: estimates.len(),
            });
        }
        for (input, field) in [(x, Field::x), (v, Field::v), (f, Field::f)] {
            if let Some(index) = input.iter().position(|value| !value.is_finite()) {
                return Err(Error::NotFinite {
                    field,
                    index,
                    value: input[index],
                });
            }
        }
        let before = *self;
        let samples = x.iter().zip(v).zip(f).zip(estimates.iter_mut());
        for (index, (((&x, &v), &f), estimate)) in samples.enumerate() {
            if let Err(error) = self.update(x, v, f) {
                *self = before;
                return Err(match error {
                    Error::InputsOverflow { x, v, f, .. } => {
                        Error::InputsOverflow { index, x, v, f }
                    }
                    other => other,
                });
            }
            *estimate = self.rls.estimate();
        }
        Ok(())
    }

    /// The current estimate `[W₀, …, W_{N−1}, Fc, sigma2, offset]`.
    pub fn estimate(&self) -> [f64; P] {
        self.rls.estimate()
    }

    /// The regressor φ = [ψ₀, …, ψ_{N−1}, sgn(v), v, 1] that an update with (`x`, `v`) would
    /// use, with the elements moved from where the last update left them; nothing is written.
    pub fn regressor(&self, x: f64, v: f64) -> Result<[f64; P], Error> {
        for (value, field) in [(x, Field::x), (v, Field::v)] {
            finite(value, field)?;
        }
        let mut elements = self.regressor;
        Ok(regressor_at(&mut elements, x, v))
    }

    /// The force φᵀθ that the current estimate predicts for the sample (`x`, `v`); nothing is
    /// written.
    pub fn predict(&self, x: f64, v: f64) -> Result<f64, Error> {
        let force = self.rls.predict(&self.regressor(x, v)?);
        if force.is_finite() {
            Ok(force)
        } else {
            Err(Error::InputsOverflow {
                index: 0,
                x,
                v,
                f: f64::NAN,
            })
        }
    }

    /// Back to the state of construction: initial estimate and covariance, relaxed elements.
    pub fn reset(&mut self) {
        self.regressor.reset();
        self.rls.reset();
    }

    /// The least-squares estimator (covariance, reset count, settings).
    pub fn rls(&self) -> &Rls<P> {
        &self.rls
    }

    /// The element memory that produces the responses ψᵢ.
    pub fn elements(&self) -> &SlipRegressor<N> {
        &self.regressor
    }
}

/// φ = [ψ₀, …, ψ_{N−1}, sgn(v), v, 1], moving the elements to `x`.
#[inline]
fn regressor_at<const N: usize, const P: usize>(
    elements: &mut SlipRegressor<N>,
    x: f64,
    v: f64,
) -> [f64; P] {
    let responses = elements.advance(x);
    let mut phi = [0.0; P];
    phi[..N].copy_from_slice(&responses);
    phi[N] = sign(v);
    phi[N + 1] = v;
    phi[N + 2] = 1.0;
    phi
}

/// sgn(v) with sgn(0) = 0.
#[inline]
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}
