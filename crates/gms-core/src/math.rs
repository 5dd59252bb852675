//! Powers of magnitudes, |x|^p, with the exponents that occur in practice kept off `pow`.
//!
//! The transition exponent n and the Stribeck shape δ are parameters: fixed while a model runs,
//! and raised to on every evaluation of φ and g (several times per step). `libm::pow` costs
//! a few hundred instructions, while the exponents people choose are almost always integers
//! (1, 2, 3, 4) or half-integers (0.5, 1.5, 2.5): for those, a few products and at most one
//! square root are exact to a few ulps. [`Power`] sorts the exponent into its class once, when
//! the parameters are built, so a step pays neither the test nor `pow`. The other exponents (a
//! fitted n or δ) go to `pow`: the C library's where the `std` feature allows it, `libm`'s in
//! `no_std`.

/// The largest integer part of an exponent evaluated by products rather than `pow`.
///
/// a^k by repeated squaring rounds once per product; the relative error of an intermediate
/// raised to the power j is multiplied by j, so the result is within (k − 1)/2 ulps of the
/// exact power in the worst case (measured: 0.7·k ulps from `pow` at most, see the tests). Eight
/// keeps every class within 6 ulps of `pow` (`MAX_ULPS` in the tests); larger exponents, rare as model parameters,
/// go to `pow` itself.
pub(crate) const MAX_INTEGER: u32 = 8;

/// How far from `libm::pow` the integer and half-integer classes may be, in ulps.
#[cfg(test)]
const MAX_ULPS: u64 = 6;

/// An exponent p > 0, sorted once into the class that decides how |x|^p is computed.
///
/// Public so that code stepping the model outside this crate (gms-batch's lanes) raises to the
/// same powers with the same rounding.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Power {
    /// p = 1: |x|.
    One,
    /// p = 2: x².
    Two,
    /// p = k, an integer 3 ≤ k ≤ 8: repeated squaring (larger integers go to `pow`).
    Integer(u32),
    /// p = k + ½ with 0 ≤ k ≤ 8: |x|^k·√|x|.
    HalfInteger(u32),
    /// Any other p, through `pow` (the C library's with the `std` feature, else `libm`'s).
    General(f64),
}

impl Power {
    /// Classifies `p`. Any value is accepted (a NaN or a negative exponent becomes
    /// [`Power::General`]); the parameter checks decide which exponents a model may have.
    pub fn new(p: f64) -> Self {
        if p == 1.0 {
            return Self::One;
        }
        if p == 2.0 {
            return Self::Two;
        }
        if (0.0..=f64::from(MAX_INTEGER) + 0.5).contains(&p) {
            let whole = libm::floor(p);
            // p ≤ 8.5 here, so the integer part converts exactly; 2p is exact too.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let k = whole as u32;
            if p == whole && k >= 3 {
                return Self::Integer(k);
            }
            if p - whole == 0.5 {
                return Self::HalfInteger(k);
            }
        }
        Self::General(p)
    }

    /// The exponent p.
    pub fn exponent(self) -> f64 {
        match self {
            Self::One => 1.0,
            Self::Two => 2.0,
            Self::Integer(k) => f64::from(k),
            Self::HalfInteger(k) => f64::from(k) + 0.5,
            Self::General(p) => p,
        }
    }

    /// |x|^p.
    #[inline]
    pub fn abs(self, x: f64) -> f64 {
        self.of(libm::fabs(x))
    }

    /// a^p for a magnitude a ≥ 0 (or NaN, which propagates).
    #[inline]
    pub fn of(self, a: f64) -> f64 {
        match self {
            Self::One => a,
            Self::Two => a * a,
            Self::Integer(k) => integer_power(a, k),
            Self::HalfInteger(k) => integer_power(a, k) * libm::sqrt(a),
            Self::General(p) => {
                if a == 0.0 {
                    0.0
                } else {
                    pow(a, p)
                }
            }
        }
    }
}

/// a^p for exponents of no class: the C library's `pow` with the `std` feature, `libm`'s
/// without. glibc's (2.28 and later: table-driven, its error at most about 0.52 ulp) costs about
/// a third of the software one's time and lies within an ulp of it; a fit that raises to a
/// fitted n spends much of its simulation in this call
/// (docs/benchmarks.md#rust-one-channel-one-step).
#[inline]
fn pow(a: f64, p: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        std::primitive::f64::powf(a, p)
    }
    #[cfg(not(feature = "std"))]
    {
        libm::pow(a, p)
    }
}

/// a^k by repeated squaring (a^0 = 1). No intermediate exceeds the result's magnitude range
/// (each is a^j with j ≤ k), so nothing overflows or underflows unless the result does.
#[inline]
fn integer_power(a: f64, k: u32) -> f64 {
    let mut result = 1.0;
    let mut base = a;
    let mut rest = k;
    // The loop runs log2(k) + 1 times for the same k on every call of a given model, so its
    // branches are perfectly predicted.
    while rest > 0 {
        if rest & 1 == 1 {
            result *= base;
        }
        rest >>= 1;
        if rest > 0 {
            base *= base;
        }
    }
    result
}

/// |x|^p for p > 0, classifying p on every call: for the few places that see an exponent only
/// once (the hot paths hold a [`Power`] instead).
#[inline]
pub(crate) fn abs_pow(x: f64, p: f64) -> f64 {
    Power::new(p).abs(x)
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use proptest::prelude::*;

    #[test]
    fn classes() {
        assert_eq!(Power::new(1.0), Power::One);
        assert_eq!(Power::new(2.0), Power::Two);
        assert_eq!(Power::new(3.0), Power::Integer(3));
        assert_eq!(Power::new(8.0), Power::Integer(8));
        assert_eq!(Power::new(9.0), Power::General(9.0));
        assert_eq!(Power::new(0.5), Power::HalfInteger(0));
        assert_eq!(Power::new(1.5), Power::HalfInteger(1));
        assert_eq!(Power::new(8.5), Power::HalfInteger(8));
        assert_eq!(Power::new(9.5), Power::General(9.5));
        assert_eq!(Power::new(0.7), Power::General(0.7));
        assert_eq!(Power::new(-0.5), Power::General(-0.5));
        assert!(matches!(Power::new(f64::NAN), Power::General(p) if p.is_nan()));
        for p in [0.5, 1.0, 1.5, 2.0, 3.0, 3.5, 8.0, 0.7, 9.0, 1e300] {
            assert_eq!(Power::new(p).exponent(), p);
        }
    }

    #[test]
    fn edge_values() {
        for p in [0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 2.5, 0.7] {
            let power = Power::new(p);
            assert_eq!(power.abs(0.0), 0.0, "p = {p}");
            assert_eq!(power.abs(-0.0), 0.0, "p = {p}");
            assert_eq!(power.abs(1.0), 1.0, "p = {p}");
            assert_eq!(power.abs(f64::INFINITY), f64::INFINITY, "p = {p}");
            assert!(power.abs(f64::NAN).is_nan(), "p = {p}");
        }
        assert_eq!(Power::new(3.0).abs(-2.0), 8.0);
        assert_eq!(Power::new(4.0).abs(1e100), f64::INFINITY);
        assert_eq!(Power::new(2.5).abs(4.0), 32.0);
    }

    /// Distance in units in the last place between two positive finite doubles.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    /// The bound the tests hold each class to: a^k rounds k − 1 products, each of whose relative
    /// errors is multiplied by at most k, so it is within about k − 1 ulps of the exact power;
    /// `pow` adds one more, and the square root of a half-integer power two.
    fn tolerance(power: Power) -> u64 {
        match power {
            Power::One | Power::Two => 1,
            Power::Integer(k) => u64::from(k),
            Power::HalfInteger(k) => u64::from(k) + 2,
            // The C library's pow (the `std` feature) within an ulp of libm's; libm's itself.
            Power::General(_) => u64::from(cfg!(feature = "std")),
        }
    }

    /// Integer and half-integer exponents up to the cap, and others.
    fn exponents() -> impl Strategy<Value = f64> {
        prop_oneof![
            (1..=MAX_INTEGER).prop_map(f64::from),
            (0..=MAX_INTEGER).prop_map(|k| f64::from(k) + 0.5),
            0.01..20.0,
        ]
    }

    proptest! {
        /// Every class agrees with `libm::pow` to a few ulps, over magnitudes whose power is a
        /// normal number (so that an ulp is a fixed relative size).
        #[test]
        fn agrees_with_pow(p in exponents(), t in 0.0..=1.0f64, negative in any::<bool>()) {
            let power = Power::new(p);
            prop_assert_eq!(power.exponent(), p);
            let span = 700.0 / p.max(1.0);
            let a = libm::exp(span * (2.0 * t - 1.0));
            let x = if negative { -a } else { a };
            let (fast, reference) = (power.abs(x), libm::pow(a, p));
            prop_assert!(
                ulps(fast, reference) <= tolerance(power).min(MAX_ULPS),
                "{:?} at {:e}: {:e} against pow's {:e}", power, a, fast, reference
            );
        }
    }

    /// The bound documented at [`MAX_INTEGER`], checked on a dense sweep of each class.
    #[test]
    fn worst_case_over_a_sweep() {
        for k in 0..=MAX_INTEGER {
            for p in [f64::from(k), f64::from(k) + 0.5] {
                let power = Power::new(p);
                let span = 700.0 / p.max(1.0);
                let worst = (0..=20_000)
                    .map(|i| {
                        let a = libm::exp(span * (f64::from(i) / 10_000.0 - 1.0));
                        ulps(power.of(a), libm::pow(a, p))
                    })
                    .max()
                    .unwrap_or(0);
                assert!(worst <= MAX_ULPS, "p = {p}: {worst} ulps from pow");
            }
        }
    }
}
