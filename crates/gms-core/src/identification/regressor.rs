//! The responses ψᵢ of Maxwell-slip elements with fixed break deflections, driven by position.
//!
//! This is the paper's presliding identification (section IV-B): with the break deflections Δᵢ
//! pre-assigned, Fh = Σᵢ Wᵢ·ψᵢ is linear in the unknown saturation forces Wᵢ, where ψᵢ ∈ [−1, 1]
//! is the deflection of element i over its break deflection. Here the elements are driven by the
//! measured position x (the paper drives them by z; in presliding z follows x closely); the
//! block call [`SlipRegressor::responses`] drives them along any path, z included.

use crate::checks::all_finite;
use crate::error::{Error, Field};
use crate::hysteresis::{Hysteresis, MaxwellSlip};

/// The element memory of N Maxwell-slip elements with break deflections Δᵢ and unit saturation
/// forces, so that element i's force is its response ψᵢ = clamp(x − ζᵢ, ±Δᵢ)/Δᵢ.
///
/// The slip rule is [`MaxwellSlip`]'s, so the regressor and the model's hysteresis move their
/// elements identically. The first position seen relaxes every element there (ψ = 0), just as a
/// fresh model takes v = 0 on its first position sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipRegressor<const N: usize> {
    elements: MaxwellSlip<N>,
    zeta: [f64; N],
    started: bool,
}

impl<const N: usize> SlipRegressor<N> {
    /// Every `delta[i]` must be finite and > 0, and N ≥ 1.
    pub fn new(delta: [f64; N]) -> Result<Self, Error> {
        let elements = MaxwellSlip::new([1.0; N], delta)?;
        Ok(Self {
            elements,
            zeta: elements.relaxed(),
            started: false,
        })
    }

    /// The break deflections Δᵢ.
    pub fn delta(&self) -> &[f64; N] {
        self.elements.delta()
    }

    /// The element positions ζᵢ (all zero before the first position).
    pub fn zeta(&self) -> &[f64; N] {
        &self.zeta
    }

    /// Moves the elements to the finite position `x` (those stretched beyond Δᵢ slip) and
    /// returns the responses ψᵢ ∈ [−1, 1].
    #[inline]
    pub fn advance(&mut self, x: f64) -> [f64; N] {
        if !self.started {
            self.zeta = [x; N];
            self.started = true;
        }
        // The kept deflection, as the commit computes it; dividing (not multiplying by 1/Δ)
        // makes a saturated element exactly ±1.
        let delta = self.elements.delta();
        let mut responses = [0.0; N];
        for (i, response) in responses.iter_mut().enumerate() {
            *response = (x - self.zeta[i]).max(-delta[i]).min(delta[i]) / delta[i];
        }
        self.elements.commit(&mut self.zeta, x);
        responses
    }

    /// Drives the elements along `x`, writing the responses after every sample into `out`, row
    /// by row (`x.len()` rows of N). All or nothing: a non-finite sample or an `out` of the
    /// wrong length is reported and leaves the elements as they were.
    pub fn responses(&mut self, x: &[f64], out: &mut [f64]) -> Result<(), Error> {
        let expected = x.len().saturating_mul(N);
        if out.len() != expected {
            return Err(Error::LengthMismatch {
                expected,
                got: out.len(),
            });
        }
        all_finite(x, Field::x)?;
        for (&position, row) in x.iter().zip(out.chunks_exact_mut(N)) {
            row.copy_from_slice(&self.advance(position));
        }
        Ok(())
    }

    /// Forgets the history: the next position relaxes every element again.
    pub fn reset(&mut self) {
        self.zeta = self.elements.relaxed();
        self.started = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn responses_follow_the_elements() {
        let mut regressor = SlipRegressor::new([1e-6, 4e-6]).unwrap();
        assert_eq!(regressor.advance(5.0), [0.0, 0.0]);
        let psi = regressor.advance(5.0 + 2e-6);
        assert_eq!(psi[0], 1.0);
        assert!((psi[1] - 0.5).abs() < 1e-9);
        // Back by 1 µm: element 0 (slipped at +Δ) leaves saturation, element 1 still sticks.
        let psi = regressor.advance(5.0 + 1e-6);
        assert!(psi[0].abs() < 1e-9);
        assert!((psi[1] - 0.25).abs() < 1e-9);
        regressor.reset();
        assert_eq!(regressor.advance(-3.0), [0.0, 0.0]);
    }

    #[test]
    fn rules_are_the_elements_rules() {
        assert!(SlipRegressor::new([1e-6, 0.0]).is_err());
        assert!(SlipRegressor::<0>::new([]).is_err());
    }
}
