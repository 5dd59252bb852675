//! Recursive least squares with exponential forgetting, for parameters that enter linearly.
//!
//! For y = φᵀθ + noise, each sample updates the estimate θ and its covariance P:
//!
//! ```text
//! e = y − φᵀθ                 (a priori prediction error, returned)
//! K = Pφ / (λ + φᵀPφ)
//! θ ← θ + K·e
//! P ← (P − K·(Pφ)ᵀ) / λ
//! ```
//!
//! With λ = 1 and P₀ = p₀·I, θ after T samples is the ridge-regularised batch solution
//! argmin Σ eₖ² + |θ − θ₀|²/p₀; with λ < 1, sample k counts with weight λ^(T−k), so the estimate
//! tracks parameters that drift, with a memory of about 1/(1 − λ) samples.
//!
//! The covariance is kept in factored form P = U·D·Uᵀ (U unit upper triangular, D diagonal),
//! updated by Bierman's algorithm (G. J. Bierman, *Factorization Methods for Discrete
//! Sequential Estimation*, 1977), in O(P²) per sample like the plain update. Numerical guards:
//! - Positive definiteness is structural and checked exactly in O(P): U·D·Uᵀ is positive
//!   definite if and only if every Dⱼ > 0, and Bierman's update multiplies Dⱼ by ratios of
//!   positive numbers. The plain update P − Pφ(Pφ)ᵀ/(λ + φᵀPφ) subtracts, and with
//!   ill-conditioned data it does lose positive definiteness (the tests show a case). If a Dⱼ
//!   still leaves (0, ∞) or U stops being finite (overflow or underflow at absurd magnitudes),
//!   the covariance is reset to P₀ (the estimate is kept) and counted in
//!   [`Rls::covariance_resets`].
//! - trace(P) ≤ `max_trace`: with λ < 1, directions that the data do not excite grow by 1/λ per
//!   sample ("covariance wind-up"), and one burst of excitation would then move the estimate
//!   violently. Above the bound, D is scaled down, which keeps P positive definite.
//! - A non-finite input is rejected before anything is computed; an update that would overflow
//!   (finite inputs of absurd size) is rejected too. Either way the state is left as it was.

use crate::checks::finite;
use nalgebra::{SMatrix, SVector};

use crate::error::{Error, Field};

/// Settings of an estimator, validated once by [`Rls::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RlsSettings {
    /// Forgetting factor λ ∈ (0, 1]; 1 keeps every sample, 0.995 a memory of about 200 samples.
    pub forgetting: f64,
    /// p₀ > 0: the initial covariance is p₀·I, and p₀ is the prior variance of each parameter
    /// (large: trust the data; small: stay near the initial estimate).
    pub initial_covariance: f64,
    /// Upper bound of trace(P); at least P·p₀ (the trace of the initial covariance).
    pub max_trace: f64,
}

/// A recursive least-squares estimator of `P` parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rls<const P: usize> {
    settings: RlsSettings,
    initial: SVector<f64, P>,
    estimate: SVector<f64, P>,
    /// U of P = U·D·Uᵀ: unit upper triangular (zeros below the diagonal).
    factor: SMatrix<f64, P, P>,
    /// D of P = U·D·Uᵀ: every entry finite and > 0.
    scale: SVector<f64, P>,
    covariance_resets: u64,
}

impl<const P: usize> Rls<P> {
    /// Starts from the estimate `initial` with covariance p₀·I.
    ///
    /// Rules: λ ∈ (0, 1], p₀ finite and > 0, `max_trace` finite and ≥ P·p₀, `initial` finite.
    pub fn new(initial: [f64; P], settings: RlsSettings) -> Result<Self, Error> {
        const { assert!(P > 0, "an estimator needs at least one parameter") };
        let RlsSettings {
            forgetting,
            initial_covariance,
            max_trace,
        } = settings;
        if !(forgetting > 0.0 && forgetting <= 1.0) {
            return Err(Error::NotInUnitInterval {
                field: Field::forgetting,
                value: forgetting,
            });
        }
        if !(initial_covariance.is_finite() && initial_covariance > 0.0) {
            return Err(Error::NotPositive {
                field: Field::initial_covariance,
                value: initial_covariance,
            });
        }
        if !(max_trace.is_finite() && max_trace > 0.0) {
            return Err(Error::NotPositive {
                field: Field::max_trace,
                value: max_trace,
            });
        }
        if max_trace < P as f64 * initial_covariance {
            return Err(Error::TraceBelowInitial {
                parameters: P,
                initial_covariance,
                max_trace,
            });
        }
        if let Some(index) = initial.iter().position(|value| !value.is_finite()) {
            return Err(Error::NotFinite {
                field: Field::initial,
                index,
                value: initial[index],
            });
        }
        let initial = SVector::from(initial);
        Ok(Self {
            settings,
            initial,
            estimate: initial,
            factor: SMatrix::identity(),
            scale: SVector::from_element(initial_covariance),
            covariance_resets: 0,
        })
    }

    /// The settings this estimator was built with.
    pub fn settings(&self) -> &RlsSettings {
        &self.settings
    }

    /// The current estimate θ.
    pub fn estimate(&self) -> [f64; P] {
        self.estimate.into()
    }

    /// The current covariance P = U·D·Uᵀ (symmetric, positive definite), formed from its
    /// factors: O(P³), for diagnostics. Scaled by the noise variance, it is the covariance of
    /// the estimate.
    pub fn covariance(&self) -> SMatrix<f64, P, P> {
        let product = self.factor * SMatrix::from_diagonal(&self.scale) * self.factor.transpose();
        (product + product.transpose()) * 0.5
    }

    /// The factors (U, D) of P = U·D·Uᵀ: U unit upper triangular, D the diagonal of D.
    pub fn factors(&self) -> (&SMatrix<f64, P, P>, &SVector<f64, P>) {
        (&self.factor, &self.scale)
    }

    /// trace(P), in O(P²) from the factors: Σⱼ Dⱼ·|column j of U|².
    pub fn covariance_trace(&self) -> f64 {
        trace(&self.factor, &self.scale)
    }

    /// How many times P lost positive definiteness and was reset to p₀·I since construction or
    /// the last [`Rls::reset`].
    pub fn covariance_resets(&self) -> u64 {
        self.covariance_resets
    }

    /// Back to the state of construction: the initial estimate, P = p₀·I, no resets counted.
    pub fn reset(&mut self) {
        self.estimate = self.initial;
        (self.factor, self.scale) = self.initial_factors();
        self.covariance_resets = 0;
    }

    /// The prediction φᵀθ of the current estimate.
    pub fn predict(&self, regressor: &[f64; P]) -> f64 {
        SVector::from(*regressor).dot(&self.estimate)
    }

    /// One update with regressor φ and measurement y; returns the a priori prediction error
    /// y − φᵀθ (θ before the update).
    ///
    /// A non-finite φ or y, or an update that overflows, is reported and leaves the state
    /// untouched. Never panics, never allocates.
    pub fn update(&mut self, regressor: &[f64; P], measured: f64) -> Result<f64, Error> {
        if let Some(index) = regressor.iter().position(|value| !value.is_finite()) {
            return Err(Error::NotFinite {
                field: Field::regressor,
                index,
                value: regressor[index],
            });
        }
        finite(measured, Field::f)?;
        let phi = SVector::from(*regressor);
        let error = measured - phi.dot(&self.estimate);
        if !error.is_finite() {
            return Err(Error::Overflow { index: 0 });
        }

        let lambda = self.settings.forgetting;
        let mut resets = self.covariance_resets;
        let (mut factor, mut scale) = (self.factor, self.scale);
        let update = bierman(&mut factor, &mut scale, &phi, lambda);
        let sigma = update.sigma;
        if !(sigma.is_finite() && sigma >= lambda) {
            return Err(Error::Overflow { index: 0 });
        }
        let estimate = self.estimate + update.gain * (error / sigma);
        if !estimate.iter().all(|value| value.is_finite()) {
            return Err(Error::Overflow { index: 0 });
        }

        scale /= lambda;
        // trace(P) = Σⱼ Dⱼ·|column j of U|². It is finite only if every entry of U is, so it
        // doubles as the finiteness check of U.
        let mut trace = scale.dot(&update.column_norms);
        let positive = scale.iter().all(|&d| d > 0.0 && d.is_finite());
        if !(positive && trace.is_finite()) {
            (factor, scale) = self.initial_factors();
            trace = self.settings.initial_covariance * P as f64;
            resets += 1;
        }
        if trace > self.settings.max_trace {
            scale *= self.settings.max_trace / trace;
        }

        self.estimate = estimate;
        self.factor = factor;
        self.scale = scale;
        self.covariance_resets = resets;
        Ok(error)
    }

    fn initial_factors(&self) -> (SMatrix<f64, P, P>, SVector<f64, P>) {
        (
            SMatrix::identity(),
            SVector::from_element(self.settings.initial_covariance),
        )
    }
}

/// What Bierman's update leaves besides the new factors.
struct Update<const P: usize> {
    /// P·φ with the covariance before the update (the gain times `sigma`).
    gain: SVector<f64, P>,
    /// λ + φᵀPφ.
    sigma: f64,
    /// |column j of the new U|² for every j.
    column_norms: SVector<f64, P>,
}

/// Bierman's measurement update of P = U·D·Uᵀ for a measurement of variance λ, in place; the
/// caller divides D by λ afterwards (that is the forgetting).
///
/// U is stored by columns; column j above the diagonal is the slice `j·P .. j·P + j`, so the
/// inner loops run over slices (no index checks) and are independent across rows.
#[inline]
fn bierman<const P: usize>(
    factor: &mut SMatrix<f64, P, P>,
    scale: &mut SVector<f64, P>,
    phi: &SVector<f64, P>,
    lambda: f64,
) -> Update<P> {
    let phi = phi.as_slice();
    let entries = factor.as_mut_slice();
    let mut gain = [0.0; P];
    let mut column_norms = [0.0; P];
    let mut sigma = lambda;
    for (j, column) in entries.chunks_exact_mut(P).enumerate() {
        let above = &mut column[..j];
        // f = Uᵀφ, one entry per column (U is unit upper triangular).
        let f = phi[j]
            + above
                .iter()
                .zip(&phi[..j])
                .map(|(u, phi)| u * phi)
                .sum::<f64>();
        let weighted = scale[j] * f;
        let step = f / sigma;
        let mut norm = 1.0;
        for (u, gain) in above.iter_mut().zip(&mut gain[..j]) {
            let old = *u;
            *u = old - step * *gain;
            *gain += old * weighted;
            norm += *u * *u;
        }
        gain[j] = weighted;
        column_norms[j] = norm;
        let next = sigma + f * weighted;
        scale[j] *= sigma / next;
        sigma = next;
    }
    Update {
        gain: SVector::from(gain),
        sigma,
        column_norms: SVector::from(column_norms),
    }
}

/// trace(U·D·Uᵀ) = Σⱼ Dⱼ·|column j of U|².
#[inline]
fn trace<const P: usize>(factor: &SMatrix<f64, P, P>, scale: &SVector<f64, P>) -> f64 {
    factor
        .column_iter()
        .zip(scale.iter())
        .map(|(column, d)| d * column.norm_squared())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SETTINGS: RlsSettings = RlsSettings {
        forgetting: 1.0,
        initial_covariance: 1e6,
        max_trace: 1e9,
    };

    #[test]
    fn settings_are_checked_once() {
        let with = |forgetting, initial_covariance, max_trace| {
            Rls::new(
                [0.0; 2],
                RlsSettings {
                    forgetting,
                    initial_covariance,
                    max_trace,
                },
            )
        };
        assert_eq!(
            with(0.0, 1.0, 10.0),
            Err(Error::NotInUnitInterval {
                field: Field::forgetting,
                value: 0.0
            })
        );
        assert_eq!(
            with(1.5, 1.0, 10.0),
            Err(Error::NotInUnitInterval {
                field: Field::forgetting,
                value: 1.5
            })
        );
        assert_eq!(
            with(f64::NAN, 1.0, 10.0),
            Err(Error::NotInUnitInterval {
                field: Field::forgetting,
                value: f64::NAN
            })
        );
        assert_eq!(
            with(1.0, 0.0, 10.0),
            Err(Error::NotPositive {
                field: Field::initial_covariance,
                value: 0.0
            })
        );
        assert_eq!(
            with(1.0, 1.0, f64::INFINITY),
            Err(Error::NotPositive {
                field: Field::max_trace,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            with(1.0, 1.0, 1.5),
            Err(Error::TraceBelowInitial {
                parameters: 2,
                initial_covariance: 1.0,
                max_trace: 1.5
            })
        );
        assert!(with(1.0, 1.0, 2.0).is_ok());
        assert_eq!(
            Rls::new([0.0, f64::NAN], SETTINGS),
            Err(Error::NotFinite {
                field: Field::initial,
                index: 1,
                value: f64::NAN
            })
        );
    }

    #[test]
    fn one_update_is_the_regularised_solution() {
        // One sample y = 2 on φ = (1, 1) from θ₀ = 0, P₀ = p₀·I: θ = p₀·φ·y/(1 + 2p₀).
        let mut rls = Rls::new([0.0; 2], SETTINGS).unwrap();
        assert_eq!(rls.update(&[1.0, 1.0], 2.0), Ok(2.0));
        let expected = 1e6 * 2.0 / (1.0 + 2e6);
        for value in rls.estimate() {
            assert!((value - expected).abs() < 1e-15);
        }
        let covariance = rls.covariance();
        assert_eq!(covariance, covariance.transpose());
        // P = p₀I − p₀²φφᵀ/(1 + 2p₀): its trace from the factors.
        let expected_trace = 2e6 - 2e12 / (1.0 + 2e6);
        assert!((rls.covariance_trace() - expected_trace).abs() < 1e-9 * expected_trace);
    }
}
