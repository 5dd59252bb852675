//! The transition exponent n as a type, so that the common exponents are decided once per call
//! rather than in every lane of every step; other exponents raise to gms-core's own [`Power`],
//! so every lane rounds exactly as the single-channel step does.

use gms_core::Power;

/// The transition exponent n of φ(u) = sgn(u)·|u|ⁿ.
pub(crate) trait Exponent: Copy {
    /// φ(u), as gms-core's `copysign(|u|ⁿ, u)`.
    fn phi(self, u: f64) -> f64;
    /// n itself.
    fn n(self) -> f64;
    /// n, classified as gms-core classifies it.
    fn power(self) -> Power {
        Power::new(self.n())
    }
    /// n − 1, classified (the exponent of dφ/du in the Newton iteration).
    fn power_less_one(self) -> Power {
        Power::new(self.n() - 1.0)
    }
    /// The spring's stiffness when the implicit step is solved in closed form ([`Closed`]).
    #[inline(always)]
    fn closed_form(self) -> Option<f64> {
        None
    }
}

/// n = 1 with a linear spring, implicit: LuGre's closed form (gms-core's `linear_root`), whose
/// step needs no φ.
#[derive(Clone, Copy)]
pub(crate) struct Closed {
    pub stiffness: f64,
}

impl Exponent for Closed {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        One.phi(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        1.0
    }
    #[inline(always)]
    fn closed_form(self) -> Option<f64> {
        Some(self.stiffness)
    }
}

/// n = 1: φ(u) = u (copysign(|u|, u) is u, NaN included).
#[derive(Clone, Copy)]
pub(crate) struct One;

/// n = 2: φ(u) = u·|u|.
#[derive(Clone, Copy)]
pub(crate) struct Two;

/// Any other n > 0: n and n − 1 classified by gms-core (products, a square root, or `pow`).
#[derive(Clone, Copy)]
pub(crate) struct Other {
    pub n: Power,
    pub n_less_one: Power,
}

impl Other {
    pub(crate) fn new(n: f64) -> Self {
        Self {
            n: Power::new(n),
            n_less_one: Power::new(n - 1.0),
        }
    }
}

impl Exponent for One {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        libm::fabs(u).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        1.0
    }
}

impl Exponent for Two {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        let a = libm::fabs(u);
        (a * a).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        2.0
    }
}

impl Exponent for Other {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        self.n.abs(u).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        self.n.exponent()
    }
    fn power(self) -> Power {
        self.n
    }
    fn power_less_one(self) -> Power {
        self.n_less_one
    }
}

/// `[f(0), …, f(L − 1)]`, as a loop that is always inlined (`core::array::from_fn` may not be,
/// and a call out of the AVX2 copy of the kernel would run baseline code).
#[inline(always)]
pub(crate) fn lanes<const L: usize>(mut f: impl FnMut(usize) -> f64) -> [f64; L] {
    let mut values = [0.0; L];
    for (l, value) in values.iter_mut().enumerate() {
        *value = f(l);
    }
    values
}

/// Whether every lane is finite.
#[inline(always)]
pub(crate) fn all_finite<const L: usize>(values: &[f64; L]) -> bool {
    // One combined test rather than a branch per lane.
    #[allow(clippy::needless_bitwise_bool)]
    values
        .iter()
        .fold(true, |all, value| all & value.is_finite())
}

// libm's `exp` (FreeBSD's e_exp.c), its constants.
#[allow(clippy::excessive_precision)] // as libm writes it
const LN2HI: f64 = 6.931_471_803_691_238_164_90e-1;
#[allow(clippy::excessive_precision)] // as libm writes it
const LN2LO: f64 = 1.908_214_929_270_587_700_02e-10;
#[allow(clippy::excessive_precision, clippy::approx_constant)] // as libm writes it
const INVLN2: f64 = 1.442_695_040_888_963_387_00e0;
#[allow(clippy::excessive_precision)] // as libm writes it
const P1: f64 = 1.666_666_666_666_660_190_37e-1;
#[allow(clippy::excessive_precision)] // as libm writes it
const P2: f64 = -2.777_777_777_701_559_338_42e-3;
#[allow(clippy::excessive_precision)] // as libm writes it
const P3: f64 = 6.613_756_321_437_934_361_17e-5;
#[allow(clippy::excessive_precision)] // as libm writes it
const P4: f64 = -1.653_390_220_546_525_153_90e-6;
#[allow(clippy::excessive_precision)] // as libm writes it
const P5: f64 = 4.138_136_797_057_238_460_39e-8;

/// 2^52 + 2^51: adding and subtracting it rounds an |x| < 2^51 to the nearest whole number.
const ROUNDING: f64 = 6_755_399_441_055_744.0;

/// `a` where `mask` holds, else `b`: arithmetic on the bits, which the compiler keeps as a
/// vector blend instead of turning a lane's choice into a branch.
#[inline(always)]
fn select(mask: bool, a: f64, b: f64) -> f64 {
    let mask = u64::from(mask).wrapping_neg();
    f64::from_bits((mask & a.to_bits()) | (!mask & b.to_bits()))
}

/// x rounded towards zero, for |x| < 2^51, as f64 (what `x as i32 as f64` gives there); plain
/// arithmetic and masks, so that it vectorizes without SSE4.1's `roundpd`: the nearest whole
/// number, less one towards x's sign where rounding went past x.
#[inline(always)]
fn truncate(x: f64) -> f64 {
    const SIGN: u64 = 1 << 63;
    let nearest = (x + ROUNDING) - ROUNDING;
    let past = u64::from(libm::fabs(nearest) > libm::fabs(x)).wrapping_neg();
    // ±1 with x's sign where rounding went past x, +0 elsewhere.
    let step = f64::from_bits(past & (1.0f64.to_bits() | (x.to_bits() & SIGN)));
    nearest - step
}

/// libm branches on the high word of |x|; for x ≥ 0 "high word ≥ h" is "x ≥ the double whose
/// high word is h and low word 0".
const fn high_word(h: u64) -> f64 {
    f64::from_bits(h << 32)
}

/// exp(x) of every lane, bit for bit `libm::exp`: its algorithm without branches for
/// −708.39 ≤ x ≤ 0 (the Stribeck curve's exp(−|v/Vs|^δ)); other lanes call `libm::exp`.
#[inline(always)]
pub(crate) fn exp_lanes<const L: usize>(x: &[f64; L]) -> [f64; L] {
    const LOWEST: f64 = -708.396_418_532_264_1;
    // Short passes over the lanes, each simple enough for the compiler to vectorize.
    #[allow(clippy::needless_bitwise_bool)] // one test for all lanes, not a branch per lane
    let outside = x
        .iter()
        .fold(false, |outside, x| outside | !(LOWEST..=0.0).contains(x));
    // x ≤ 0: libm's k = (INVLN2·x − 0.5) as i32 from 1.5·ln 2 on (high word 0x3ff0a2b2), −1
    // from 0.5·ln 2 on (high word above 0x3fd62e42), 0 below.
    let magnitude: [f64; L] = lanes(|l| libm::fabs(x[l]));
    let far: [f64; L] = lanes(|l| truncate(INVLN2 * x[l] - 0.5));
    let near: [f64; L] = lanes(|l| select(magnitude[l] >= high_word(0x3fd6_2e43), -1.0, 0.0));
    let k: [f64; L] = lanes(|l| select(magnitude[l] >= high_word(0x3ff0_a2b2), far[l], near[l]));
    let hi: [f64; L] = lanes(|l| select(k[l] == 0.0, x[l], x[l] - k[l] * LN2HI));
    let lo: [f64; L] = lanes(|l| select(k[l] == 0.0, 0.0, k[l] * LN2LO));
    let r: [f64; L] = lanes(|l| select(k[l] == 0.0, x[l], hi[l] - lo[l]));
    let c: [f64; L] = lanes(|l| {
        let rr = r[l] * r[l];
        r[l] - rr * (P1 + rr * (P2 + rr * (P3 + rr * (P4 + rr * P5))))
    });
    let y: [f64; L] = lanes(|l| 1.0 + (r[l] * c[l] / (2.0 - c[l]) - lo[l] + hi[l]));
    // scalbn(y, k) for −1022 ≤ k ≤ 0: one multiplication by 2^k, whose exponent field k + 1023
    // is the low bits of k + 1023 + 2^52.
    let scale: [f64; L] =
        lanes(|l| f64::from_bits((k[l] + (1023.0 + 4_503_599_627_370_496.0)).to_bits() << 52));
    // |x| ≤ 2^-28 (high word at most 0x3e300000): libm returns 1 + x.
    let scaled: [f64; L] = lanes(|l| select(k[l] == 0.0, y[l], y[l] * scale[l]));
    let values: [f64; L] = lanes(|l| {
        select(
            magnitude[l] >= high_word(0x3e30_0001),
            scaled[l],
            1.0 + x[l],
        )
    });
    if outside {
        return lanes(|l| {
            if (LOWEST..=0.0).contains(&x[l]) {
                values[l]
            } else {
                libm::exp(x[l])
            }
        });
    }
    values
}

#[cfg(test)]
mod tests {
    use super::truncate;

    #[test]
    fn truncate_is_the_integer_conversion() {
        let mut x: f64 = -1100.0;
        while x <= 1100.0 {
            for x in [x, x.floor(), x.floor() + 0.5, x.ceil() - 0.5] {
                #[allow(clippy::cast_possible_truncation)] // |x| ≤ 1100
                let expected = f64::from(x as i32);
                assert_eq!(truncate(x), expected, "truncate({x:e})");
            }
            x += 0.013_7;
        }
    }
}
