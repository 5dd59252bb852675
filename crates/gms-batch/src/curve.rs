//! gms-core's Stribeck curve g(v) for L lanes, operation for operation (its `stribeck.rs`),
//! with libm's `exp` done for all lanes at once.

use gms_core::{Power, Stribeck};

use crate::math::{exp_lanes, lanes};

/// The curve's values as gms-core holds them, the threshold above which the exponential is
/// skipped included.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Curve {
    fc: f64,
    fs: f64,
    fc_neg: f64,
    fs_neg: f64,
    /// 1/Vs, gms-core's.
    inverse_vs: f64,
    delta: Power,
    negligible: f64,
    negligible_neg: f64,
}

impl Curve {
    pub(crate) fn new(stribeck: &Stribeck) -> Curve {
        Curve {
            fc: stribeck.fc(),
            fs: stribeck.fs(),
            fc_neg: stribeck.fc_neg(),
            fs_neg: stribeck.fs_neg(),
            inverse_vs: stribeck.inverse_vs(),
            delta: stribeck.delta_power(),
            negligible: stribeck.negligible_above(1.0),
            negligible_neg: stribeck.negligible_above(-1.0),
        }
    }

    /// g(v) of every lane.
    #[inline(always)]
    pub(crate) fn g<const L: usize>(&self, v: &[f64; L]) -> [f64; L] {
        let ratio: [f64; L] = lanes(|l| v[l] * self.inverse_vs);
        // The usual shapes as their own loops, which vectorize; the class is the same for
        // every lane.
        let exponent: [f64; L] = match self.delta {
            Power::One => lanes(|l| libm::fabs(ratio[l])),
            Power::Two => lanes(|l| libm::fabs(ratio[l]) * libm::fabs(ratio[l])),
            delta => lanes(|l| delta.abs(ratio[l])),
        };
        let negative = |l: usize| v[l] < 0.0;
        let fc: [f64; L] = lanes(|l| if negative(l) { self.fc_neg } else { self.fc });
        let negligible: [f64; L] = lanes(|l| {
            if negative(l) {
                self.negligible_neg
            } else {
                self.negligible
            }
        });
        // Sliding fast in every lane: g is Fc, and no exponential is needed.
        #[allow(clippy::needless_bitwise_bool)] // one test for all lanes, not a branch per lane
        let needed = (0..L).fold(false, |needed, l| needed | (exponent[l] <= negligible[l]));
        if !needed {
            return fc;
        }
        let e: [f64; L] = exp_lanes(&lanes(|l| -exponent[l]));
        lanes(|l| {
            let fs = if negative(l) { self.fs_neg } else { self.fs };
            if exponent[l] > negligible[l] {
                fc[l]
            } else {
                fc[l] + (fs - fc[l]) * e[l]
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Curve;
    use crate::math::exp_lanes;
    use gms_core::Stribeck;
    use proptest::prelude::*;

    #[test]
    fn exp_is_libm_exp() {
        let mut x: f64 = -750.0;
        while x <= 1.0 {
            let values = [x, -x.abs() * 1e-9, -x.abs() * 1e-3, x / 7.0];
            let ours = exp_lanes(&values);
            for (value, ours) in values.iter().zip(ours) {
                assert_eq!(
                    ours.to_bits(),
                    libm::exp(*value).to_bits(),
                    "exp({value:e})"
                );
            }
            x += 0.000_37;
        }
        for special in [f64::NAN, f64::NEG_INFINITY, -0.0, 0.0, -1e-300, -2e-9] {
            let ours = exp_lanes(&[special; 4]);
            let theirs = libm::exp(special);
            assert!(ours[0].to_bits() == theirs.to_bits() || (ours[0].is_nan() && theirs.is_nan()));
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn g_is_gms_core_g(
            (fc, ratio, fc_neg, ratio_neg) in (0.1..3.0f64, 1.0..1e3f64, 0.1..3.0f64, 1.0..5.0f64),
            vs in 1e-5..1e-1f64,
            delta in prop::sample::select(vec![1.0, 2.0, 0.5, 1.7, 3.0]),
            v in prop::array::uniform4(-1.0..1.0f64),
            scale in -6.0..1.0f64,
        ) {
            let stribeck = Stribeck::asymmetric(fc, fc * ratio, fc_neg, fc_neg * ratio_neg, vs, delta).unwrap();
            let v = v.map(|v| v * 10f64.powf(scale));
            let ours = Curve::new(&stribeck).g(&v);
            for (v, ours) in v.iter().zip(ours) {
                prop_assert_eq!(ours.to_bits(), stribeck.g(*v).to_bits());
            }
        }
    }
}
