//! The Stribeck curve: the constant-velocity friction level g(v) and its signed form s(v) (eq. 3).

use crate::checks::positive;
use crate::error::{Error, Field};
use crate::math::Power;

/// g(v) = Fc + (Fs − Fc)·exp(−|v/Vs|^δ), with separate levels for v < 0 when asymmetric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stribeck {
    fc: f64,
    fs: f64,
    fc_neg: f64,
    fs_neg: f64,
    vs: f64,
    /// 1/Vs (finite: Vs is normal), so that g multiplies instead of dividing.
    inverse_vs: f64,
    /// δ, classified once: g is evaluated on every step, usually at an integer δ.
    delta: Power,
    /// Above these values of |v/Vs|^δ the Stribeck term is below half an ulp of Fc (resp.
    /// `Fc_neg`): adding it cannot change g, so the exponential is skipped.
    negligible: f64,
    negligible_neg: f64,
}

impl Stribeck {
    /// A symmetric curve. `Fc > 0`, `Fs >= Fc`, `Vs > 0`, `delta > 0`, all finite.
    pub fn new(fc: f64, fs: f64, vs: f64, delta: f64) -> Result<Self, Error> {
        Self::asymmetric(fc, fs, fc, fs, vs, delta)
    }

    /// A curve whose levels for v < 0 are `fc_neg`, `fs_neg` (same rules as `fc`, `fs`).
    #[allow(clippy::similar_names)] // the paper's pairs: fc and fs, fc_neg and fs_neg
    pub fn asymmetric(
        fc: f64,
        fs: f64,
        fc_neg: f64,
        fs_neg: f64,
        vs: f64,
        delta: f64,
    ) -> Result<Self, Error> {
        positive(fc, Field::Fc)?;
        positive(fs, Field::Fs)?;
        positive(fc_neg, Field::Fc_neg)?;
        positive(fs_neg, Field::Fs_neg)?;
        positive(vs, Field::Vs)?;
        positive(delta, Field::delta)?;
        if fs < fc {
            return Err(Error::StaticBelowCoulomb {
                field: Field::Fs,
                coulomb: fc,
                value: fs,
            });
        }
        if fs_neg < fc_neg {
            return Err(Error::StaticBelowCoulomb {
                field: Field::Fs_neg,
                coulomb: fc_neg,
                value: fs_neg,
            });
        }
        Ok(Self {
            fc,
            fs,
            fc_neg,
            fs_neg,
            vs,
            inverse_vs: 1.0 / vs,
            delta: Power::new(delta),
            negligible: negligible_above(fc, fs),
            negligible_neg: negligible_above(fc_neg, fs_neg),
        })
    }

    /// Coulomb level for v ≥ 0.
    pub fn fc(&self) -> f64 {
        self.fc
    }
    /// Static level for v ≥ 0.
    pub fn fs(&self) -> f64 {
        self.fs
    }
    /// Coulomb level for v < 0.
    pub fn fc_neg(&self) -> f64 {
        self.fc_neg
    }
    /// Static level for v < 0.
    pub fn fs_neg(&self) -> f64 {
        self.fs_neg
    }
    /// Stribeck velocity.
    pub fn vs(&self) -> f64 {
        self.vs
    }
    /// 1/Vs, the factor [`g`](Self::g) scales the velocity by.
    pub fn inverse_vs(&self) -> f64 {
        self.inverse_vs
    }
    /// Stribeck shape exponent δ.
    pub fn delta(&self) -> f64 {
        self.delta.exponent()
    }

    /// The largest level the curve reaches, max(Fs, `Fs_neg`).
    pub fn peak(&self) -> f64 {
        self.fs.max(self.fs_neg)
    }

    /// The exponent δ, classified ([`Power`]): how g raises |v/Vs|.
    pub fn delta_power(&self) -> Power {
        self.delta
    }

    /// The value of |v/Vs|^δ above which g(v) is exactly the Coulomb level for the direction
    /// of `v` (the Stribeck term is below half an ulp of it), so that g skips the exponential.
    /// Negative when Fs = Fc: g is then Fc everywhere.
    pub fn negligible_above(&self, v: f64) -> f64 {
        if v < 0.0 {
            self.negligible_neg
        } else {
            self.negligible
        }
    }

    /// g(v) > 0, the magnitude of the steady sliding friction at velocity v.
    #[inline]
    pub fn g(&self, v: f64) -> f64 {
        let (fc, fs, negligible) = if v < 0.0 {
            (self.fc_neg, self.fs_neg, self.negligible_neg)
        } else {
            (self.fc, self.fs, self.negligible)
        };
        let exponent = self.delta.abs(v * self.inverse_vs);
        if exponent > negligible {
            return fc;
        }
        fc + (fs - fc) * libm::exp(-exponent)
    }

    /// s(v) = sgn(v)·g(v), with s(0) = 0.
    #[inline]
    pub fn s(&self, v: f64) -> f64 {
        if v == 0.0 {
            0.0
        } else {
            libm::copysign(self.g(v), v)
        }
    }
}

/// The x beyond which (fs − fc)·exp(−x) < fc·2⁻⁵⁴, less than half an ulp of fc, so that
/// fc + (fs − fc)·exp(−x) rounds to fc; one unit of margin covers the error of `exp` and `log`.
fn negligible_above(fc: f64, fs: f64) -> f64 {
    if fs == fc {
        return -1.0;
    }
    libm::log((fs - fc) / fc) + 54.0 * core::f64::consts::LN_2 + 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_at_rest_and_far_away() {
        let curve = Stribeck::asymmetric(1.0, 1.5, 0.8, 1.2, 1e-3, 2.0).unwrap();
        assert_eq!(curve.g(0.0), 1.5);
        assert!((curve.g(1.0) - 1.0).abs() < 1e-12);
        assert!((curve.g(-1e-12) - 1.2).abs() < 1e-12);
        assert!((curve.s(-1.0) + 0.8).abs() < 1e-12);
        assert_eq!(curve.s(0.0), 0.0);
        assert_eq!(curve.peak(), 1.5);
    }

    #[test]
    fn skipping_the_negligible_exponential_changes_nothing() {
        let curve = Stribeck::asymmetric(1.0, 1.5, 0.3, 7.0, 1e-3, 1.7).unwrap();
        for k in 0..4000 {
            let v = (f64::from(k) - 2000.0) * 2e-5;
            let (fc, fs) = if v < 0.0 { (0.3, 7.0) } else { (1.0, 1.5) };
            // g multiplies by 1/Vs, computed once.
            let direct = fc + (fs - fc) * libm::exp(-Power::new(1.7).abs(v * (1.0 / 1e-3)));
            assert_eq!(curve.g(v), direct, "v = {v}");
        }
    }

    #[test]
    fn rules_name_the_field() {
        assert_eq!(
            Stribeck::new(0.0, 1.0, 1.0, 1.0),
            Err(Error::NotPositive {
                field: Field::Fc,
                value: 0.0
            })
        );
        assert_eq!(
            Stribeck::new(2.0, 1.0, 1.0, 1.0),
            Err(Error::StaticBelowCoulomb {
                field: Field::Fs,
                coulomb: 2.0,
                value: 1.0
            })
        );
        assert_eq!(
            Stribeck::new(1.0, 1.0, f64::NAN, 1.0),
            Err(Error::NotPositive {
                field: Field::Vs,
                value: f64::NAN
            })
        );
        assert_eq!(
            Stribeck::new(1.0, 1.0, 1.0, -1.0),
            Err(Error::NotPositive {
                field: Field::delta,
                value: -1.0
            })
        );
        assert_eq!(
            Stribeck::asymmetric(1.0, 1.0, 1.0, 0.5, 1.0, 1.0),
            Err(Error::StaticBelowCoulomb {
                field: Field::Fs_neg,
                coulomb: 1.0,
                value: 0.5
            })
        );
    }
}
