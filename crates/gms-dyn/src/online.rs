//! gms-core's online identification (recursive least squares on
//! F = Σ Wᵢψᵢ + Fc·sgn(v) + sigma2·v + offset) with the number of elements chosen at run time.

use gms_core::identification::EXTRA_TERMS;
use gms_core::RlsSettings;

use crate::error::Error;
use crate::params::with_element_count;

/// Recursive least squares on the friction terms that enter linearly, N + 3 parameters.
pub struct OnlineIdentifier {
    estimator: Box<dyn Estimator>,
}

/// gms-core's identifier for one N, behind a trait object.
trait Estimator: Send + Sync {
    fn elements(&self) -> usize;
    fn delta(&self) -> &[f64];
    fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, gms_core::Error>;
    fn run(
        &mut self,
        x: &[f64],
        v: &[f64],
        f: &[f64],
        out: &mut [f64],
    ) -> Result<(), gms_core::Error>;
    fn predict(&self, x: f64, v: f64) -> Result<f64, gms_core::Error>;
    fn estimate(&self, out: &mut [f64]);
    fn covariance(&self, out: &mut [f64]);
    fn covariance_trace(&self) -> f64;
    fn covariance_resets(&self) -> u64;
    fn reset(&mut self);
}

impl<const N: usize, const P: usize> Estimator for gms_core::OnlineIdentifier<N, P> {
    fn elements(&self) -> usize {
        N
    }

    fn delta(&self) -> &[f64] {
        gms_core::OnlineIdentifier::elements(self).delta()
    }

    fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, gms_core::Error> {
        gms_core::OnlineIdentifier::update(self, x, v, f)
    }

    fn run(
        &mut self,
        x: &[f64],
        v: &[f64],
        f: &[f64],
        out: &mut [f64],
    ) -> Result<(), gms_core::Error> {
        let expected = x.len().saturating_mul(P);
        if out.len() != expected {
            return Err(gms_core::Error::LengthMismatch {
                expected,
                got: out.len(),
            });
        }
        let mut estimates = vec![[0.0; P]; x.len()];
        gms_core::OnlineIdentifier::run(self, x, v, f, &mut estimates)?;
        out.copy_from_slice(estimates.as_flattened());
        Ok(())
    }

    fn predict(&self, x: f64, v: f64) -> Result<f64, gms_core::Error> {
        gms_core::OnlineIdentifier::predict(self, x, v)
    }

    fn estimate(&self, out: &mut [f64]) {
        out.copy_from_slice(&gms_core::OnlineIdentifier::estimate(self));
    }

    fn covariance(&self, out: &mut [f64]) {
        out.copy_from_slice(self.rls().covariance().as_slice());
    }

    fn covariance_trace(&self) -> f64 {
        self.rls().covariance_trace()
    }

    fn covariance_resets(&self) -> u64 {
        self.rls().covariance_resets()
    }

    fn reset(&mut self) {
        gms_core::OnlineIdentifier::reset(self);
    }
}

fn boxed<const N: usize, const P: usize>(
    delta: &[f64],
    initial: &[f64],
    settings: RlsSettings,
) -> Result<Box<dyn Estimator>, Error> {
    let (mut delta_array, mut initial_array) = ([0.0; N], [0.0; P]);
    delta_array.copy_from_slice(delta);
    initial_array.copy_from_slice(initial);
    Ok(Box::new(gms_core::OnlineIdentifier::<N, P>::new(
        delta_array,
        initial_array,
        settings,
    )?))
}

impl OnlineIdentifier {
    /// An identifier of N = `delta.len()` elements with break deflections `delta`, starting
    /// from `initial` (N + 3 values: W for each element, Fc, sigma2, offset).
    ///
    /// # Errors
    /// A count of elements outside 1..=[`MAX_ELEMENTS`](crate::MAX_ELEMENTS), an `initial` of
    /// another length, or the first rule of gms-core broken.
    pub fn new(delta: &[f64], initial: &[f64], settings: RlsSettings) -> Result<Self, Error> {
        let count = delta.len();
        let refused = Error::DeflectionCount { count };
        if count == 0 || count > crate::MAX_ELEMENTS {
            return Err(refused);
        }
        if initial.len() != count + EXTRA_TERMS {
            return Err(Error::InitialLength {
                elements: count,
                got: initial.len(),
            });
        }
        let estimator = with_element_count!(count, N => boxed::<N, { N + EXTRA_TERMS }>(delta, initial, settings)?, _ => return Err(refused));
        Ok(Self { estimator })
    }

    /// Number of elements N.
    pub fn elements(&self) -> usize {
        self.estimator.elements()
    }

    /// Number of estimated parameters, N + 3.
    pub fn parameters(&self) -> usize {
        self.elements() + EXTRA_TERMS
    }

    /// The break deflections Δᵢ.
    pub fn delta(&self) -> &[f64] {
        self.estimator.delta()
    }

    /// One sample; returns the a priori prediction error f − f̂.
    ///
    /// # Errors
    /// A non-finite input, or an update that overflows; nothing changes.
    pub fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, Error> {
        Ok(self.estimator.update(x, v, f)?)
    }

    /// Runs a whole log, writing the estimate after each sample into `out` (T × (N + 3),
    /// row-major).
    ///
    /// # Errors
    /// Inputs of unequal lengths, an `out` of the wrong length, a non-finite sample or an update
    /// that overflows; all or nothing.
    pub fn run(&mut self, x: &[f64], v: &[f64], f: &[f64], out: &mut [f64]) -> Result<(), Error> {
        Ok(self.estimator.run(x, v, f, out)?)
    }

    /// The force the current estimate predicts for (x, v); nothing changes.
    ///
    /// # Errors
    /// A non-finite input, or a prediction that overflows.
    pub fn predict(&self, x: f64, v: f64) -> Result<f64, Error> {
        Ok(self.estimator.predict(x, v)?)
    }

    /// The estimate [W₀, …, W_{N−1}, Fc, sigma2, offset].
    pub fn estimate(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.parameters()];
        self.estimator.estimate(&mut out);
        out
    }

    /// The covariance P, (N + 3) × (N + 3); symmetric, so row- and column-major alike.
    pub fn covariance(&self) -> Vec<f64> {
        let parameters = self.parameters();
        let mut out = vec![0.0; parameters * parameters];
        self.estimator.covariance(&mut out);
        out
    }

    /// trace(P).
    pub fn covariance_trace(&self) -> f64 {
        self.estimator.covariance_trace()
    }

    /// How many times the covariance left its range and was reset since construction or reset.
    pub fn covariance_resets(&self) -> u64 {
        self.estimator.covariance_resets()
    }

    /// Back to the state of construction.
    pub fn reset(&mut self) {
        self.estimator.reset();
    }
}
