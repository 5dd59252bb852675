//! Fh = σ0·z: a single spring that never slips, which makes the model LuGre when n = 1.

use super::{Hysteresis, Trial};
use crate::checks::positive;
use crate::error::{Error, Field};

/// Linear hysteresis force of stiffness `sigma0` \[N/m\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear {
    sigma0: f64,
}

impl Linear {
    /// `sigma0` must be finite and > 0.
    pub fn new(sigma0: f64) -> Result<Self, Error> {
        Ok(Self {
            sigma0: positive(sigma0, Field::sigma0)?,
        })
    }

    /// The stiffness σ0.
    pub fn sigma0(&self) -> f64 {
        self.sigma0
    }
}

impl Hysteresis for Linear {
    type Memory = ();

    fn relaxed(&self) {}

    #[inline]
    fn force(&self, _memory: &(), z: f64) -> f64 {
        self.sigma0 * z
    }

    #[inline]
    fn trial(&self, _memory: &(), z: f64) -> Trial {
        Trial {
            force: self.sigma0 * z,
            slope_left: self.sigma0,
            slope_right: self.sigma0,
            left: f64::NEG_INFINITY,
            right: f64::INFINITY,
        }
    }

    #[inline]
    fn commit(&self, _memory: &mut (), z: f64) -> f64 {
        self.sigma0 * z
    }

    fn max_force(&self) -> f64 {
        f64::INFINITY
    }

    #[inline]
    fn linear_stiffness(&self) -> Option<f64> {
        Some(self.sigma0)
    }

    /// |σ0·z|: the very product `commit` returns.
    #[inline]
    fn force_bound(&self, z: f64) -> f64 {
        libm::fabs(self.sigma0 * z)
    }
}
