//! The Stribeck curve g(v) and the transition φ(u) = sgn(u)·|u|ⁿ, with their derivatives by the
//! parameters (docs/sensitivities.md#curve).

use gms_core::{Power, Stribeck};

use crate::columns::{DELTA, FC, FC_NEG, FS, FS_NEG, SHARED_COLUMNS, VS};

/// The value of a = |v/Vs|^δ beyond which exp(−a) is taken as 0 (see [`level`]).
const NEGLIGIBLE: f64 = 40.0;

/// g at one velocity and dg/dθ for the shared columns (zero outside Fc, Fs, Vs, δ and the
/// levels of the direction of v).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Level {
    /// g(v), gms-core's value.
    pub g: f64,
    /// dg/dθ.
    pub derivative: [f64; SHARED_COLUMNS],
}

/// g(v) = Fc + (Fs − Fc)·e, e = exp(−a), a = |v/Vs|^δ, with `Fc_neg`, `Fs_neg` for v < 0:
/// dg/dFc = 1 − e, dg/dFs = e, dg/dVs = (Fs − Fc)·e·δ·a/Vs, dg/dδ = −(Fs − Fc)·e·a·ln|v/Vs|.
pub(crate) fn level(stribeck: &Stribeck, v: f64) -> Level {
    let (coulomb, stiction, fc, fs) = if v < 0.0 {
        (FC_NEG, FS_NEG, stribeck.fc_neg(), stribeck.fs_neg())
    } else {
        (FC, FS, stribeck.fc(), stribeck.fs())
    };
    let ratio = libm::fabs(v / stribeck.vs());
    let a = stribeck.delta_power().of(ratio);
    // Beyond a = 40, e < 4.3e-18 and a·e < 1.8e-16: below an ulp of every term it enters, so
    // it is taken as 0 without calling `exp` (fast sliding is most of a record), and so are the
    // shape's derivatives (where a·ln|v/Vs| could be infinite).
    let e = if a > NEGLIGIBLE { 0.0 } else { libm::exp(-a) };
    let mut derivative = [0.0; SHARED_COLUMNS];
    derivative[coulomb] = 1.0 - e;
    derivative[stiction] = e;
    if e > 0.0 && a > 0.0 {
        let bump = (fs - fc) * e * a;
        derivative[VS] = bump * stribeck.delta() / stribeck.vs();
        derivative[DELTA] = -bump * libm::log(ratio);
    }
    Level {
        g: stribeck.g(v),
        derivative,
    }
}

/// The transition exponent n, with n − 1 for the slope of φ, classified once.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Transition {
    n: Power,
    n_less_one: Power,
}

/// φ(u), dφ/du = n·|u|ⁿ⁻¹ and dφ/dn = φ(u)·ln|u| at one u.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TransitionAt {
    pub slope: f64,
    pub by_n: f64,
}

impl Transition {
    pub fn new(n: f64) -> Self {
        Self {
            n: Power::new(n),
            n_less_one: Power::new(n - 1.0),
        }
    }

    #[inline]
    pub fn at(&self, u: f64) -> TransitionAt {
        let magnitude = libm::fabs(u);
        let n = self.n.exponent();
        if magnitude == 0.0 {
            // φ'(0) is 0 for n > 1, 1 for n = 1 and unbounded for n < 1; φ·ln|u| → 0.
            let slope = if n > 1.0 {
                0.0
            } else if n == 1.0 {
                1.0
            } else {
                f64::INFINITY
            };
            return TransitionAt { slope, by_n: 0.0 };
        }
        let slope = match self.n {
            Power::One => 1.0,
            _ => n * self.n_less_one.of(magnitude),
        };
        let phi = libm::copysign(self.n.of(magnitude), u);
        TransitionAt {
            slope,
            by_n: phi * libm::log(magnitude),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of g itself, for each parameter of the curve.
    #[test]
    fn level_matches_differences_of_g() {
        let build = |p: [f64; 6]| Stribeck::asymmetric(p[0], p[1], p[2], p[3], p[4], p[5]).unwrap();
        let base = [1.0, 1.5, 0.8, 1.3, 2e-3, 1.7];
        // The columns of Fc, Fs, Fc_neg, Fs_neg, Vs, delta, in the order of `base`.
        let columns = [FC, FS, FC_NEG, FS_NEG, VS, DELTA];
        for v in [3e-4, 2e-3, 7e-3, -5e-4, -4e-3] {
            let terms = level(&build(base), v);
            assert_eq!(terms.g, build(base).g(v));
            for (parameter, &column) in columns.iter().enumerate() {
                let h = 1e-6 * base[parameter];
                let (mut plus, mut minus) = (base, base);
                plus[parameter] += h;
                minus[parameter] -= h;
                let difference = (build(plus).g(v) - build(minus).g(v)) / (2.0 * h);
                let derivative = terms.derivative[column];
                assert!(
                    (derivative - difference).abs() <= 1e-8 * (1.0 + derivative.abs()),
                    "v = {v}, column {column}: {derivative} against {difference}"
                );
            }
        }
    }

    #[test]
    fn transition_matches_differences_of_phi() {
        let phi = |u: f64, n: f64| libm::copysign(libm::pow(u.abs(), n), u);
        for n in [0.7, 1.0, 1.5, 2.0, 3.0] {
            let transition = Transition::new(n);
            for u in [-0.9, -0.2, 0.3, 0.95] {
                let at = transition.at(u);
                let h = 1e-6;
                let by_u = (phi(u + h, n) - phi(u - h, n)) / (2.0 * h);
                let by_n = (phi(u, n + h) - phi(u, n - h)) / (2.0 * h);
                assert!((at.slope - by_u).abs() < 1e-8, "n = {n}, u = {u}");
                assert!((at.by_n - by_n).abs() < 1e-8, "n = {n}, u = {u}");
            }
            let at_zero = transition.at(0.0);
            assert_eq!(at_zero.by_n, 0.0);
        }
        assert_eq!(Transition::new(1.0).at(0.0).slope, 1.0);
        assert_eq!(Transition::new(2.0).at(0.0).slope, 0.0);
        assert_eq!(Transition::new(0.5).at(0.0).slope, f64::INFINITY);
    }
}
