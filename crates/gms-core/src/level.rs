//! A friction level that depends on the position (docs/model.md#position-dependent-level): a
//! smooth trend along the stroke and periodic ripples (a screw's pitch, a gear's teeth, a
//! motor's poles) scale the contact part of the friction,
//!
//! ```text
//! factor(x) = 1 + t1·P1(p) + t2·P2(p) + Σ_r Σ_k (c_rk·cos(2πk·x/P_r) + s_rk·sin(2πk·x/P_r)),
//! p = clip((x − middle)/half_stroke, −1, 1),  P1(p) = p,  P2(p) = 1.5·p² − 0.5,
//! F = factor(x)·(Fh + σ1·dz/dt) + σ2·v = factor(x)·(F_plain − σ2·v) + σ2·v.
//! ```
//!
//! **Validated once.** [`Level::new`] checks every value; afterwards [`Level::factor`] cannot
//! fail for a finite x. Because |P1|, |P2|, |cos|, |sin| ≤ 1 on the clipped p, the rule
//! Σ|t| + Σ|c| + Σ|s| < 1 keeps the factor in (0, 2) everywhere.
//!
//! **Bounded work.** One `sin` and one `cos` per ripple; the harmonics follow by the
//! angle-addition recurrence (a rotation by the first harmonic's angle per harmonic), so a
//! factor costs at most [`MAX_RIPPLES`] sincos pairs and [`MAX_RIPPLES`]·[`MAX_HARMONICS`]
//! rotations.
//!
//! **Accuracy.** The phase is x/P reduced to the nearest whole period before the sincos, so
//! the angle stays in [−π, π] whatever |x|. The reduction is exact; what remains is the
//! rounding of the quotient x/P itself, about |x/P|·1.1e-16 cycles, which any formula in f64
//! has (it is the resolution of x relative to the period). Each rotation of the recurrence adds
//! a few ulps to the harmonic: after [`MAX_HARMONICS`] harmonics the cos and sin are within
//! 1e-15 of libm's `cos(k·θ)`, `sin(k·θ)` at the same θ (tests/level.rs checks 4e-15 on the
//! whole factor up to |x/P| = 1e12). The numpy formula of `leuven_rt.level` does not reduce
//! the phase: its `k·2π·x/P` rounds by up to about 3·k·2π·|x/P|·1.1e-16 rad, so the two agree
//! to 1e-12 while that stays below 1e-12 (|x/P| up to about 20 with the eighth harmonic at
//! full amplitude; the tests compare them there, and Rust with the reduced formula beyond).

use crate::checks::positive;
use crate::error::{Error, Field};

/// The most ripples (distinct periods) a [`Level`] holds.
pub const MAX_RIPPLES: usize = 2;

/// The most harmonics of each ripple.
pub const MAX_HARMONICS: usize = 8;

/// 2^52: every f64 of at least this magnitude is a whole number.
const WHOLE: f64 = 4_503_599_627_370_496.0;

/// One ripple as a caller gives it: the period and the harmonics' relative amplitudes
/// (`cos[k-1]`, `sin[k-1]` for harmonic k). Checked by [`Level::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RippleTerms<'a> {
    /// The period \[m or rad\].
    pub period: f64,
    /// Amplitudes of cos(2πk·x/period), k = 1, 2, …
    pub cos: &'a [f64],
    /// Amplitudes of sin(2πk·x/period), k = 1, 2, …
    pub sin: &'a [f64],
}

/// One validated ripple, in fixed-size storage.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ripple {
    period: f64,
    harmonics: usize,
    cos: [f64; MAX_HARMONICS],
    sin: [f64; MAX_HARMONICS],
}

impl Ripple {
    const EMPTY: Self = Self {
        period: 1.0,
        harmonics: 0,
        cos: [0.0; MAX_HARMONICS],
        sin: [0.0; MAX_HARMONICS],
    };

    /// The sum over the harmonics k of `c_k·cos(kθ) + s_k·sin(kθ)` at θ = 2π·x/period.
    #[inline]
    fn value(&self, x: f64) -> f64 {
        let cycles = x / self.period;
        // Whole periods add nothing; removing them keeps the angle small (see the module
        // documentation). From 2^52 on every f64 is a whole number, and x/P may even overflow
        // for a finite x: the phase is 0 there (a NaN x has been handled by the caller).
        let fraction = if libm::fabs(cycles) >= WHOLE {
            0.0
        } else {
            cycles - libm::round(cycles)
        };
        let angle = core::f64::consts::TAU * fraction;
        let (sin1, cos1) = libm::sincos(angle);
        let (mut sin_k, mut cos_k) = (sin1, cos1);
        let mut sum = 0.0;
        for k in 0..self.harmonics {
            sum += self.cos[k] * cos_k + self.sin[k] * sin_k;
            // Angle addition: (k + 1)θ = kθ + θ.
            let next_cos = cos_k * cos1 - sin_k * sin1;
            sin_k = sin_k * cos1 + cos_k * sin1;
            cos_k = next_cos;
        }
        sum
    }
}

/// A validated position-dependent friction level: `Copy`, fixed size, no allocation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Level {
    middle: f64,
    half_stroke: f64,
    trend: [f64; 2],
    ripple_count: usize,
    ripples: [Ripple; MAX_RIPPLES],
}

impl Default for Level {
    fn default() -> Self {
        Self::none()
    }
}

impl Level {
    /// The flat level: factor ≡ 1, and a compensator with it gives exactly the plain model's
    /// output.
    pub const fn none() -> Self {
        Self {
            middle: 0.0,
            half_stroke: 1.0,
            trend: [0.0; 2],
            ripple_count: 0,
            ripples: [Ripple::EMPTY; MAX_RIPPLES],
        }
    }

    /// Validates once: `middle` finite; `half_stroke` finite and > 0 (not subnormal); `trend`
    /// finite; at most [`MAX_RIPPLES`] ripples, each with a finite period > 0 (not subnormal),
    /// `cos` and `sin` of the same length, at most [`MAX_HARMONICS`], all finite; and
    /// Σ|trend| + Σ|cos| + Σ|sin| < 1, so that the factor is positive everywhere.
    pub fn new(
        middle: f64,
        half_stroke: f64,
        trend: [f64; 2],
        ripples: &[RippleTerms<'_>],
    ) -> Result<Self, Error> {
        if !middle.is_finite() {
            return Err(Error::NotFiniteValue {
                field: Field::middle,
                value: middle,
            });
        }
        let half_stroke = positive(half_stroke, Field::half_stroke)?;
        for (index, &value) in trend.iter().enumerate() {
            if !value.is_finite() {
                return Err(Error::NotFinite {
                    field: Field::trend,
                    index,
                    value,
                });
            }
        }
        if ripples.len() > MAX_RIPPLES {
            return Err(Error::TooManyRipples {
                count: ripples.len(),
            });
        }
        let mut level = Self {
            middle,
            half_stroke,
            trend,
            ripple_count: ripples.len(),
            ripples: [Ripple::EMPTY; MAX_RIPPLES],
        };
        let mut depth = libm::fabs(trend[0]) + libm::fabs(trend[1]);
        for (ripple, (terms, slot)) in ripples.iter().zip(level.ripples.iter_mut()).enumerate() {
            *slot = checked_ripple(ripple, terms)?;
            depth += slot
                .cos
                .iter()
                .chain(&slot.sin)
                .map(|c| libm::fabs(*c))
                .sum::<f64>();
        }
        // Every term is finite, so the sum is a number (perhaps an overflowed inf).
        if depth >= 1.0 {
            return Err(Error::LevelTooDeep { sum: depth });
        }
        Ok(level)
    }

    /// factor(x) of the module documentation; NaN for a non-finite x (never a panic).
    #[inline]
    pub fn factor(&self, x: f64) -> f64 {
        if !x.is_finite() {
            return f64::NAN;
        }
        let scaled = (x - self.middle) / self.half_stroke;
        // Spelled out, as everywhere in a step (CONTRIBUTING.md#rules: no f64::clamp).
        #[allow(clippy::manual_clamp)]
        let p = if scaled > 1.0 {
            1.0
        } else if scaled < -1.0 {
            -1.0
        } else {
            scaled
        };
        let mut factor = 1.0 + self.trend[0] * p + self.trend[1] * (1.5 * p * p - 0.5);
        for ripple in &self.ripples[..self.ripple_count] {
            factor += ripple.value(x);
        }
        factor
    }

    /// The force with this level from the plain model's force `force` at position `x` and
    /// velocity `v`: factor(x)·(force − σ2·v) + σ2·v. The flat level returns `force` itself,
    /// bit for bit.
    #[inline]
    pub fn apply(&self, force: f64, x: f64, v: f64, sigma2: f64) -> f64 {
        if self.is_flat() {
            return force;
        }
        let viscous = sigma2 * v;
        self.factor(x) * (force - viscous) + viscous
    }

    /// Whether factor ≡ 1: no trend and no ripple ([`Level::none`], or a level given as zeros
    /// with no ripples).
    pub fn is_flat(&self) -> bool {
        self.ripple_count == 0 && self.trend == [0.0; 2]
    }

    /// The position of the middle of the stroke.
    pub fn middle(&self) -> f64 {
        self.middle
    }

    /// Half the stroke over which the trend varies.
    pub fn half_stroke(&self) -> f64 {
        self.half_stroke
    }

    /// The trend's Legendre coefficients (t1, t2).
    pub fn trend(&self) -> [f64; 2] {
        self.trend
    }

    /// Number of ripples.
    pub fn ripple_count(&self) -> usize {
        self.ripple_count
    }

    /// Ripple `index` as given (its period, cos and sin amplitudes), or `None` beyond the count.
    pub fn ripple(&self, index: usize) -> Option<RippleTerms<'_>> {
        self.ripples[..self.ripple_count]
            .get(index)
            .map(|ripple| RippleTerms {
                period: ripple.period,
                cos: &ripple.cos[..ripple.harmonics],
                sin: &ripple.sin[..ripple.harmonics],
            })
    }
}

fn checked_ripple(ripple: usize, terms: &RippleTerms<'_>) -> Result<Ripple, Error> {
    if !(terms.period.is_finite() && terms.period >= f64::MIN_POSITIVE) {
        return Err(Error::RipplePeriod {
            ripple,
            value: terms.period,
        });
    }
    if terms.cos.len() != terms.sin.len() {
        return Err(Error::HarmonicLengths {
            ripple,
            cos: terms.cos.len(),
            sin: terms.sin.len(),
        });
    }
    if terms.cos.len() > MAX_HARMONICS {
        return Err(Error::TooManyHarmonics {
            ripple,
            count: terms.cos.len(),
        });
    }
    let mut out = Ripple {
        period: terms.period,
        harmonics: terms.cos.len(),
        ..Ripple::EMPTY
    };
    for (field, given, slots) in [
        (Field::cos, terms.cos, &mut out.cos),
        (Field::sin, terms.sin, &mut out.sin),
    ] {
        for (index, (&value, slot)) in given.iter().zip(slots.iter_mut()).enumerate() {
            if !value.is_finite() {
                return Err(Error::RippleCoefficient {
                    field,
                    ripple,
                    index,
                    value,
                });
            }
            *slot = value;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn none_is_one_everywhere() {
        let level = Level::none();
        for x in [-1e300, -3.0, 0.0, 0.25, 7e9] {
            assert_eq!(level.factor(x), 1.0);
        }
        assert!(level.is_flat());
        assert_eq!(
            level.apply(1.234, 5.0, -0.3, 0.4).to_bits(),
            1.234f64.to_bits()
        );
    }

    #[test]
    fn non_finite_position_gives_nan_not_a_panic() {
        let level = Level::new(
            0.0,
            1.0,
            [0.1, 0.0],
            &[RippleTerms {
                period: 0.5,
                cos: &[0.1],
                sin: &[0.1],
            }],
        )
        .unwrap();
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(level.factor(x).is_nan(), "{x}");
        }
        // A finite x whose x/P overflows is a whole number of periods.
        for x in [f64::MAX, -f64::MAX, 1e300] {
            let factor = level.factor(x);
            assert!(factor > 0.0 && factor.is_finite(), "{x}: {factor}");
        }
    }
}
