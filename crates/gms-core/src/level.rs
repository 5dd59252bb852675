//! Functions of the position alone (docs/model.md#position-dependent-level): a smooth trend along
//! the stroke and periodic ripples (a screw's pitch, a gear's teeth, a motor's poles),
//!
//! ```text
//! r(x) = t1·P1(p) + t2·P2(p) + Σ_r Σ_k (c_rk·cos(2πk·x/P_r) + s_rk·sin(2πk·x/P_r)),
//! p = clip((x − middle)/half_stroke, −1, 1),  P1(p) = p,  P2(p) = 1.5·p² − 0.5.
//! ```
//!
//! One implementation of r(x), [`PositionSeries`], serves two effects:
//!
//! - [`Level`]: the friction level, factor(x) = 1 + r(x), scales the contact part of the force,
//!   F = factor(x)·(`F_plain` − σ2(v)·v) + σ2(v)·v. Its coefficients are relative, and the rule
//!   Σ|t| + Σ|c| + Σ|s| < 1 keeps the factor in (0, 2) everywhere (|P1|, |P2|, |cos|, |sin| ≤ 1
//!   on the clipped p).
//! - [`PositionForce`]: r(x) itself, in force units (N, or N·m for a rotary axis), added in both
//!   directions of motion whatever the friction level: cogging, gear mesh, a gravity-like torque
//!   along the stroke. Any finite coefficients.
//!
//! **Validated once.** [`PositionSeries::new`] checks every value, and refuses a half stroke or a
//! period whose phase cannot be resolved at the positions the series covers (below); afterwards
//! the evaluation cannot fail for a finite x.
//!
//! **Resolution.** A series covers the stroke, positions up to
//! extent = max(|middle| + `half_stroke`, 1) in magnitude (at least the unit interval: positions
//! are in metres or radians). There an f64 position is resolved only to an ulp of the extent, so
//! a period (or half stroke) must span at least 2²⁰ ulps of it, about a millionth of a period per
//! representable step; 2²⁰ ulps of 1 are 2.3e-10 m. A finer one would be sampled by rounding,
//! and two correct formulas disagree at the first digit: at a period of 1e-300, x/P is a whole
//! number in f64 for every |x| above 2^52·1e-300 ≈ 4.5e-285, so the reduced phase here is 0,
//! while numpy's unreduced formula takes the cosine of a rounded angle of up to some 1e300 rad.
//!
//! **Bounded work.** One `sin` and one `cos` per ripple; the harmonics follow by the
//! angle-addition recurrence (a rotation by the first harmonic's angle per harmonic), so an
//! evaluation costs at most [`MAX_RIPPLES`] sincos pairs and [`MAX_RIPPLES`]·[`MAX_HARMONICS`]
//! rotations. The evaluation has no branch: the block calls evaluate the terms of a stretch of
//! positions at once (64, ahead of stepping them), which the compiler runs in SIMD registers,
//! with the same arithmetic, bit for bit, as one position at a time.
//!
//! **Accuracy.** The phase is x/P reduced in cycles, exactly: whole periods, then whole quarter
//! periods are removed, which leaves an angle of at most π/4 (the quarter turns are exact swaps
//! and sign changes). There libm's `sincos` evaluates its two polynomials without a reduction
//! of its own, and this module evaluates the same polynomials (`sincos_small`, equal to libm's
//! bit for bit, tested); what remains is the rounding of the angle, half an ulp, and of the
//! quotient x/P itself, about |x/P|·1.1e-16 cycles, which any formula in f64 has (it is the
//! resolution of x relative to the period). Each rotation of the recurrence adds a few ulps to
//! the harmonic: after [`MAX_HARMONICS`] harmonics the cos and sin are within 1e-15 of libm's
//! `cos(k·θ)`, `sin(k·θ)` at the same θ (tests/level.rs checks 4e-15 on the whole factor up to
//! |x/P| = 1e12). The trend's p is (x − middle) times 1/`half_stroke`, computed once. The numpy
//! formula of `leuven_rt.reference` does not reduce the phase: its `k·2π·x/P` rounds by up to
//! about 3·k·2π·|x/P|·1.1e-16 rad, so the two agree to 1e-12 (relative to the sum of the
//! amplitudes) while that stays below 1e-12 (|x/P| up to about 20 with the eighth harmonic at
//! full amplitude; the tests compare them there, and Rust with the reduced formula beyond).

// The evaluation's parts are `#[inline(always)]`: inlined into the block calls' loop over a
// chunk of positions, their lane loops are vectorized together; left out of line, each would
// be a call per position.
#![allow(clippy::inline_always)]

use crate::checks::positive;
use crate::error::{Error, Field};
use crate::resolution::finest;

/// The most ripples (distinct periods) a series holds.
pub const MAX_RIPPLES: usize = 2;

/// The most harmonics of each ripple.
pub const MAX_HARMONICS: usize = 8;

/// 2^52: every f64 of at least this magnitude is a whole number.
const WHOLE: f64 = 4_503_599_627_370_496.0;

/// 1.5·2^52: adding and subtracting it rounds an |x| ≤ 2^51 to the nearest whole number.
const ROUNDING: f64 = 6_755_399_441_055_744.0;

/// One ripple as a caller gives it: the period and the harmonics' amplitudes (`cos[k-1]`,
/// `sin[k-1]` for harmonic k). Checked by [`PositionSeries::new`].
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

    /// Adds to each `sums[i]` the sum over the harmonics k of `c_k·cos(kθ) + s_k·sin(kθ)` at
    /// θ = 2π·`x[i]`/period (each harmonic summed from 0 first). Lane by lane: every loop is
    /// over the L positions, without branches, so that the compiler runs them in SIMD
    /// registers; L = 1 is the same arithmetic for one position.
    #[inline(always)]
    fn add_to<const L: usize>(&self, x: &[f64; L], sums: &mut [f64; L]) {
        let mut sin1 = [0.0; L];
        let mut cos1 = [0.0; L];
        for i in 0..L {
            (sin1[i], cos1[i]) = sincos_cycles(x[i] / self.period);
        }
        let (mut sin_k, mut cos_k) = (sin1, cos1);
        let mut sum = [0.0; L];
        for (&c, &s) in self.cos.iter().zip(&self.sin).take(self.harmonics) {
            for i in 0..L {
                sum[i] += c * cos_k[i] + s * sin_k[i];
                // Angle addition: (k + 1)θ = kθ + θ.
                let next_cos = cos_k[i] * cos1[i] - sin_k[i] * sin1[i];
                sin_k[i] = sin_k[i] * cos1[i] + cos_k[i] * sin1[i];
                cos_k[i] = next_cos;
            }
        }
        for i in 0..L {
            sums[i] += sum[i];
        }
    }
}

/// `a` if `condition`, else `b`: a select, not a branch.
#[inline(always)]
fn select(condition: bool, a: f64, b: f64) -> f64 {
    if condition {
        a
    } else {
        b
    }
}

/// (sin 2πc, cos 2πc) for a phase of c cycles.
///
/// The phase is reduced in cycles, where the reduction is exact: whole periods are removed
/// (from 2^52 on every f64 is a whole number, and x/P may even overflow for a finite x: the
/// phase is 0 there), then whole quarter periods, which leaves at most an eighth of a period:
/// an angle of at most π/4, where libm's `sincos` evaluates its two polynomials directly
/// ([`sincos_small`]). The quarter turns are then swaps and sign changes, exact too. What
/// remains is the rounding of the angle, (π/2)·(the remaining quarters), half an ulp. No
/// branch: a NaN phase gives NaN.
#[inline(always)]
fn sincos_cycles(cycles: f64) -> (f64, f64) {
    let cycles = select(libm::fabs(cycles) >= WHOLE, 0.0, cycles);
    // Nearest whole numbers by adding and subtracting 2^52 (|cycles| < 2^52) or 1.5·2^52
    // (|quarters| ≤ 2): exact.
    let whole = libm::copysign(WHOLE, cycles);
    let fraction = cycles - ((cycles + whole) - whole);
    let quarters = 4.0 * fraction;
    let turns = (quarters + ROUNDING) - ROUNDING;
    let (sin, cos) = sincos_small(core::f64::consts::FRAC_PI_2 * (quarters - turns));
    // turns ∈ {−2, …, 2}; a quarter turn maps (sin, cos) to (cos, −sin), a half turn to
    // (−sin, −cos). Odd: ±1 quarter; a half turn in it: −2, −1 (three quarters) or 2.
    let odd = libm::fabs(turns) == 1.0;
    let half = !(-0.5..=1.5).contains(&turns);
    let (sin, cos) = (select(odd, cos, sin), select(odd, -sin, cos));
    (select(half, -sin, sin), select(half, -cos, cos))
}

// The polynomials of libm's `k_sin` and `k_cos` (FreeBSD's k_sin.c, k_cos.c), as it writes them.
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
const S: [f64; 6] = [
    -1.66666666666666324348e-01,
    8.33333333332248946124e-03,
    -1.98412698298579493134e-04,
    2.75573137070700676789e-06,
    -2.50507602534068634195e-08,
    1.58969099521155010221e-10,
];
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
const C: [f64; 6] = [
    4.16666666666666019037e-02,
    -1.38888888888741095749e-03,
    2.48015872894767294178e-05,
    -2.75573143513906633035e-07,
    2.08757232129817482790e-09,
    -1.13596475577881948265e-11,
];

/// `libm::sincos(x)` for |x| ≤ π/4, bit for bit: there it evaluates `k_sin(x, 0, 0)` and
/// `k_cos(x, 0)` (below 2^-27·√2 it returns (x, 1), which the polynomials round to as well),
/// here without its branches on the size of x, so that lanes of positions run it in SIMD.
#[inline(always)]
fn sincos_small(x: f64) -> (f64, f64) {
    let z = x * x;
    let w = z * z;
    let r = S[1] + z * (S[2] + z * S[3]) + z * w * (S[4] + z * S[5]);
    let v = z * x;
    let sin = x + v * (S[0] + z * r);
    let r = z * (C[0] + z * (C[1] + z * C[2])) + w * w * (C[3] + z * (C[4] + z * C[5]));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // libm's tail, x·y with y = 0, kept for the sign of a zero.
    let tail = 0.0;
    let cos = w + (((1.0 - w) - hz) + (z * r - x * tail));
    (sin, cos)
}

/// r(x) of the module documentation, validated: `Copy`, fixed size, no allocation. The shape
/// shared by [`Level`] and [`PositionForce`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionSeries {
    middle: f64,
    half_stroke: f64,
    /// 1/`half_stroke`, so that an evaluation multiplies instead of dividing.
    inverse_half_stroke: f64,
    trend: [f64; 2],
    ripple_count: usize,
    ripples: [Ripple; MAX_RIPPLES],
}

impl Default for PositionSeries {
    fn default() -> Self {
        Self::zero()
    }
}

impl PositionSeries {
    /// r ≡ 0: no trend and no ripple.
    pub const fn zero() -> Self {
        Self {
            middle: 0.0,
            half_stroke: 1.0,
            inverse_half_stroke: 1.0,
            trend: [0.0; 2],
            ripple_count: 0,
            ripples: [Ripple::EMPTY; MAX_RIPPLES],
        }
    }

    /// The finest period or half stroke whose phase is resolved at positions up to `extent`
    /// (max(|middle| + `half_stroke`, 1), what [`Error::PhaseUnresolved`] carries): 2²⁰ ulps of
    /// it, and infinite for an infinite extent. The bound a refused period or half stroke had to
    /// reach.
    pub fn finest(extent: f64) -> f64 {
        finest(extent)
    }

    /// Validates once: `middle` finite; `half_stroke` finite and > 0 (not subnormal); `trend`
    /// finite; at most [`MAX_RIPPLES`] ripples, each with a finite period > 0 (not subnormal),
    /// `cos` and `sin` of the same length, at most [`MAX_HARMONICS`], all finite; and the half
    /// stroke and every period at least 2²⁰ ulps of max(|middle| + `half_stroke`, 1), so that
    /// their phase is resolved at the positions the series covers (see the module documentation).
    ///
    /// # Errors
    /// The first rule broken, naming the field and carrying the value:
    /// [`Error::NotFiniteValue`] (`middle`), [`Error::NotPositive`] (`half_stroke`),
    /// [`Error::NotFinite`] (`trend`), [`Error::TooManyRipples`], [`Error::RipplePeriod`],
    /// [`Error::HarmonicLengths`], [`Error::TooManyHarmonics`], [`Error::RippleCoefficient`], or
    /// [`Error::PhaseUnresolved`] (`half_stroke`, `middle` or `period`).
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
        // The largest |x| of the stroke (an overflowing sum is infinite, and nothing resolves it).
        let reach = libm::fabs(middle) + half_stroke;
        let extent = if reach > 1.0 { reach } else { 1.0 };
        let resolved = finest(extent);
        if half_stroke < resolved {
            // A half stroke too fine even about 0 is its own fault; otherwise the middle is too
            // far from 0 for it.
            let (field, value) = if half_stroke < finest(1.0) {
                (Field::half_stroke, half_stroke)
            } else {
                (Field::middle, middle)
            };
            return Err(Error::PhaseUnresolved {
                field,
                index: 0,
                value,
                extent,
            });
        }
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
        let mut series = Self {
            middle,
            half_stroke,
            inverse_half_stroke: 1.0 / half_stroke,
            trend,
            ripple_count: ripples.len(),
            ripples: [Ripple::EMPTY; MAX_RIPPLES],
        };
        for (ripple, (terms, slot)) in ripples.iter().zip(series.ripples.iter_mut()).enumerate() {
            *slot = checked_ripple(ripple, terms)?;
            if slot.period < resolved {
                return Err(Error::PhaseUnresolved {
                    field: Field::period,
                    index: ripple,
                    value: slot.period,
                    extent,
                });
            }
        }
        Ok(series)
    }

    /// r(x); NaN for a non-finite x (never a panic).
    #[inline]
    pub fn value(&self, x: f64) -> f64 {
        self.value_from(0.0, x)
    }

    /// `base` + r(x), summed from `base` (so that the level's 1 + r(x) rounds as one sum).
    #[inline]
    fn value_from(&self, base: f64, x: f64) -> f64 {
        let mut out = [0.0];
        self.values_from(base, &[x], &mut out);
        out[0]
    }

    /// `base` + r(x) of each of L positions into `out`, NaN for a non-finite x. Lane by lane
    /// (see `Ripple::add_to`): the block calls evaluate a stretch of positions at once, and
    /// L = 1, the evaluation of one position, is the same arithmetic, so both agree bit for bit.
    #[inline(always)]
    pub(crate) fn values_from<const L: usize>(&self, base: f64, x: &[f64; L], out: &mut [f64; L]) {
        for (out, &x) in out.iter_mut().zip(x) {
            let scaled = (x - self.middle) * self.inverse_half_stroke;
            // Spelled out, as everywhere in a step (CONTRIBUTING.md#rules: no f64::clamp).
            let p = select(scaled > 1.0, 1.0, select(scaled < -1.0, -1.0, scaled));
            *out = base + self.trend[0] * p + self.trend[1] * (1.5 * p * p - 0.5);
        }
        for ripple in self.ripples.iter().take(self.ripple_count) {
            ripple.add_to(x, out);
        }
        for (out, &x) in out.iter_mut().zip(x) {
            *out = select(x.is_finite(), *out, f64::NAN);
        }
    }

    /// Whether r ≡ 0: no trend and no ripple.
    pub fn is_zero(&self) -> bool {
        self.ripple_count == 0 && self.trend == [0.0; 2]
    }

    /// Σ|trend| + Σ|cos| + Σ|sin|: a bound on |r(x)| (perhaps an overflowed inf).
    pub fn amplitude(&self) -> f64 {
        let mut sum = libm::fabs(self.trend[0]) + libm::fabs(self.trend[1]);
        for ripple in &self.ripples[..self.ripple_count] {
            let harmonics = &ripple.cos[..ripple.harmonics];
            let sines = &ripple.sin[..ripple.harmonics];
            sum += harmonics
                .iter()
                .chain(sines)
                .map(|c| libm::fabs(*c))
                .sum::<f64>();
        }
        sum
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

/// A validated position-dependent friction level, factor(x) = 1 + r(x): `Copy`, fixed size, no
/// allocation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Level {
    series: PositionSeries,
}

impl Level {
    /// The flat level: factor ≡ 1, and a compensator with it gives exactly the plain model's
    /// output.
    pub const fn none() -> Self {
        Self {
            series: PositionSeries::zero(),
        }
    }

    /// Validates once: the rules of [`PositionSeries::new`], and
    /// Σ|trend| + Σ|cos| + Σ|sin| < 1, so that the factor is positive everywhere.
    ///
    /// # Errors
    /// Those of [`PositionSeries::new`], or [`Error::LevelTooDeep`].
    pub fn new(
        middle: f64,
        half_stroke: f64,
        trend: [f64; 2],
        ripples: &[RippleTerms<'_>],
    ) -> Result<Self, Error> {
        let series = PositionSeries::new(middle, half_stroke, trend, ripples)?;
        // Every term is finite, so the sum is a number (perhaps an overflowed inf).
        let depth = series.amplitude();
        if depth >= 1.0 {
            return Err(Error::LevelTooDeep { sum: depth });
        }
        Ok(Self { series })
    }

    /// factor(x) = 1 + r(x); NaN for a non-finite x (never a panic).
    #[inline]
    pub fn factor(&self, x: f64) -> f64 {
        self.series.value_from(1.0, x)
    }

    /// factor(x) of each of L positions, bit for bit [`Level::factor`].
    #[inline]
    pub(crate) fn factors<const L: usize>(&self, x: &[f64; L], out: &mut [f64; L]) {
        self.series.values_from(1.0, x, out);
    }

    /// The force with this level from the plain model's force `force` at position `x` and
    /// velocity `v`, with `sigma2` the viscous coefficient that applies to v
    /// ([`Params::sigma2_at`](crate::Params::sigma2_at)): factor(x)·(force − σ2·v) + σ2·v. The
    /// flat level returns `force` itself, bit for bit.
    #[inline]
    pub fn apply(&self, force: f64, x: f64, v: f64, sigma2: f64) -> f64 {
        self.apply_factor(self.factor(x), force, v, sigma2)
    }

    /// [`Level::apply`] with factor(x) evaluated already (`factor`): the block calls evaluate
    /// the factors of a stretch of positions ahead of stepping them.
    #[inline]
    pub(crate) fn apply_factor(&self, factor: f64, force: f64, v: f64, sigma2: f64) -> f64 {
        if self.is_flat() {
            return force;
        }
        let viscous = sigma2 * v;
        factor * (force - viscous) + viscous
    }

    /// Whether factor ≡ 1: no trend and no ripple ([`Level::none`], or a level given as zeros
    /// with no ripples).
    pub fn is_flat(&self) -> bool {
        self.series.is_zero()
    }

    /// r(x), the level's departure from 1.
    pub fn series(&self) -> &PositionSeries {
        &self.series
    }

    /// The position of the middle of the stroke.
    pub fn middle(&self) -> f64 {
        self.series.middle()
    }

    /// Half the stroke over which the trend varies.
    pub fn half_stroke(&self) -> f64 {
        self.series.half_stroke()
    }

    /// The trend's Legendre coefficients (t1, t2).
    pub fn trend(&self) -> [f64; 2] {
        self.series.trend()
    }

    /// Number of ripples.
    pub fn ripple_count(&self) -> usize {
        self.series.ripple_count()
    }

    /// Ripple `index` as given (its period, cos and sin amplitudes), or `None` beyond the count.
    pub fn ripple(&self, index: usize) -> Option<RippleTerms<'_>> {
        self.series.ripple(index)
    }
}

/// A validated force that depends on the position alone, r(x) in N (or N·m): added to the
/// friction in both directions of motion, not scaled by the level. `Copy`, fixed size, no
/// allocation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PositionForce {
    series: PositionSeries,
}

impl PositionForce {
    /// No position force: r ≡ 0, and the output is the one without it, bit for bit.
    pub const fn none() -> Self {
        Self {
            series: PositionSeries::zero(),
        }
    }

    /// Validates once: the rules of [`PositionSeries::new`]; the trend and the amplitudes are
    /// forces \[N or N·m\], any finite values.
    ///
    /// # Errors
    /// Those of [`PositionSeries::new`].
    pub fn new(
        middle: f64,
        half_stroke: f64,
        trend: [f64; 2],
        ripples: &[RippleTerms<'_>],
    ) -> Result<Self, Error> {
        Ok(Self {
            series: PositionSeries::new(middle, half_stroke, trend, ripples)?,
        })
    }

    /// The force r(x) at position `x`; NaN for a non-finite x (never a panic).
    #[inline]
    pub fn force(&self, x: f64) -> f64 {
        self.series.value(x)
    }

    /// r(x) of each of L positions, bit for bit [`PositionForce::force`].
    #[inline]
    pub(crate) fn forces<const L: usize>(&self, x: &[f64; L], out: &mut [f64; L]) {
        self.series.values_from(0.0, x, out);
    }

    /// `force` + r(x): the output with this position force added. No position force returns
    /// `force` itself, bit for bit.
    #[inline]
    pub fn apply(&self, force: f64, x: f64) -> f64 {
        self.apply_force(self.force(x), force)
    }

    /// [`PositionForce::apply`] with r(x) evaluated already (`added`).
    #[inline]
    pub(crate) fn apply_force(&self, added: f64, force: f64) -> f64 {
        if self.is_none() {
            return force;
        }
        force + added
    }

    /// Whether r ≡ 0: no trend and no ripple.
    pub fn is_none(&self) -> bool {
        self.series.is_zero()
    }

    /// r(x) and its shape.
    pub fn series(&self) -> &PositionSeries {
        &self.series
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
    use proptest::prelude::*;

    proptest! {
        /// The branch-free polynomials are libm's `sincos` on |x| ≤ π/4, to the bit: tiny
        /// angles (where libm returns (x, 1) without them) included.
        #[test]
        fn small_angles_are_libm_sincos(
            t in -1.0..=1.0f64,
            scale in prop_oneof![Just(1.0), Just(1e-3), Just(1e-9), Just(1e-300)],
        ) {
            let x = core::f64::consts::FRAC_PI_4 * t * scale;
            let (sin, cos) = sincos_small(x);
            let (expected_sin, expected_cos) = libm::sincos(x);
            prop_assert_eq!(sin.to_bits(), expected_sin.to_bits(), "sin({:e})", x);
            prop_assert_eq!(cos.to_bits(), expected_cos.to_bits(), "cos({:e})", x);
        }

        /// The reduction in quarter periods gives sin and cos of 2πc to an ulp of 1 (the
        /// rounding of the angle), whole periods of the phase removed exactly.
        #[test]
        fn phases_in_cycles(c in -1e6..1e6f64) {
            let (sin, cos) = sincos_cycles(c);
            let angle = core::f64::consts::TAU * (c - libm::round(c));
            prop_assert!(libm::fabs(sin - libm::sin(angle)) <= 4.0 * f64::EPSILON, "{:e}", c);
            prop_assert!(libm::fabs(cos - libm::cos(angle)) <= 4.0 * f64::EPSILON, "{:e}", c);
        }
    }

    #[test]
    fn quarter_periods_are_exact() {
        for (c, sin, cos) in [
            (0.0, 0.0, 1.0),
            (0.25, 1.0, 0.0),
            (0.5, 0.0, -1.0),
            (-0.5, 0.0, -1.0),
            (0.75, -1.0, 0.0),
            (-0.25, -1.0, 0.0),
            (1.0, 0.0, 1.0),
            (-7.75, 1.0, 0.0),
            (4_503_599_627_370_496.0, 0.0, 1.0),
            (f64::INFINITY, 0.0, 1.0),
        ] {
            let (s, k) = sincos_cycles(c);
            assert_eq!((s, k), (sin, cos), "phase {c}");
        }
        assert!(sincos_cycles(f64::NAN).0.is_nan());
    }

    #[test]
    fn lanes_are_the_single_evaluation() {
        let level = Level::new(
            0.001,
            0.02,
            [0.1, -0.05],
            &[
                RippleTerms {
                    period: 0.003,
                    cos: &[0.1, 0.02, -0.01],
                    sin: &[0.05, 0.0, 0.01],
                },
                RippleTerms {
                    period: 7e-4,
                    cos: &[0.02],
                    sin: &[-0.03],
                },
            ],
        )
        .unwrap();
        let mut x: [f64; 8] = core::array::from_fn(|i| -0.05 + 0.0137 * i as f64);
        x[3] = f64::NAN;
        x[5] = 1e300;
        let mut factors = [0.0; 8];
        level.factors(&x, &mut factors);
        for (&x, &factor) in x.iter().zip(&factors) {
            assert_eq!(factor.to_bits(), level.factor(x).to_bits(), "x = {x}");
        }
    }

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
