//! Every parameter rule of docs/parameters.md#rules is enforced at construction, with the `Error` variant
//! that names the offending key, and valid values on the edge of each rule are accepted:
//!
//! | rule | constructor | error |
//! |---|---|---|
//! | `Fc`, `Fs`, `Vs`, `delta`, `Fc_neg`, `Fs_neg` finite and > 0, not subnormal | `Stribeck::new/asymmetric` | `NotPositive(field)` |
//! | `Fs ≥ Fc`, `Fs_neg ≥ Fc_neg` | `Stribeck::new/asymmetric` | `StaticBelowCoulomb(field)` |
//! | each `W[i]`, `Delta[i]` finite and > 0 | `MaxwellSlip::new` | `Element { field, index }` |
//! | `sum(W)` finite | `MaxwellSlip::new` | `ForceSumOverflow { index }` (the largest `W`) |
//! | each `W[i]/Delta[i]` finite, and their sum | `MaxwellSlip::new` | `StiffnessOverflow { index }`, `StiffnessSumOverflow` |
//! | each `Delta[i] ≥ MIN_DELTA_RATIO · max(Delta)` | `MaxwellSlip::new` | `DeltaTooNarrow { index }` |
//! | at least one element | `MaxwellSlip::new` | `NoElements` |
//! | `sigma0` finite and > 0 | `Linear::new` | `NotPositive(sigma0)` |
//! | `n` finite and > 0 | `Params::new` | `NotPositive(n)` |
//! | `sigma1`, `sigma2` finite and ≥ 0 | `Params::new` | `Negative(field)` |
//! | `sum(W) > max(Fs, Fs_neg)` | `Params::new` | `ElementsTooWeak` |
//!
//! and every message names its key.

mod common;

use common::{log_uniform, saturation_forces, stribeck};
use gms_core::{Error, Field, Hysteresis, Linear, MaxwellSlip, Params, Stribeck, MIN_DELTA_RATIO};
use proptest::array::uniform;
use proptest::prelude::*;

/// Values that break "finite and > 0".
const NOT_POSITIVE: [f64; 8] = [
    0.0,
    -0.0,
    -1.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e-310,
    5e-324,
];
/// Values that break "finite and ≥ 0".
const NEGATIVE: [f64; 5] = [-1e-300, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

const FIELDS: [Field; 16] = [
    Field::Fc,
    Field::Fs,
    Field::Vs,
    Field::delta,
    Field::n,
    Field::sigma0,
    Field::sigma1,
    Field::sigma2,
    Field::W,
    Field::Delta,
    Field::Fc_neg,
    Field::Fs_neg,
    Field::sigma2_neg,
    Field::dt,
    Field::v,
    Field::x,
];

fn curve() -> Stribeck {
    Stribeck::asymmetric(1.0, 1.5, 0.8, 1.2, 1e-3, 2.0).expect("valid curve")
}

fn elements() -> MaxwellSlip<2> {
    MaxwellSlip::new([1.0, 1.0], [1e-6, 2e-6]).expect("valid elements")
}

#[test]
fn stribeck_levels_must_be_positive() {
    for bad in NOT_POSITIVE {
        let cases = [
            (Stribeck::new(bad, 1.5, 1e-3, 2.0), Field::Fc),
            (Stribeck::new(1.0, bad, 1e-3, 2.0), Field::Fs),
            (Stribeck::new(1.0, 1.5, bad, 2.0), Field::Vs),
            (Stribeck::new(1.0, 1.5, 1e-3, bad), Field::delta),
            (
                Stribeck::asymmetric(1.0, 1.5, bad, 1.2, 1e-3, 2.0),
                Field::Fc_neg,
            ),
            (
                Stribeck::asymmetric(1.0, 1.5, 0.8, bad, 1e-3, 2.0),
                Field::Fs_neg,
            ),
        ];
        for (result, field) in cases {
            assert_eq!(
                result,
                Err(Error::NotPositive { field, value: bad }),
                "{field} = {bad}"
            );
        }
    }
}

#[test]
fn static_levels_must_not_be_below_coulomb() {
    let below = 1.0 - f64::EPSILON;
    assert_eq!(
        Stribeck::new(1.0, below, 1e-3, 2.0),
        Err(Error::StaticBelowCoulomb {
            field: Field::Fs,
            coulomb: 1.0,
            value: below
        })
    );
    assert_eq!(
        Stribeck::asymmetric(1.0, 1.5, 1.0, below, 1e-3, 2.0),
        Err(Error::StaticBelowCoulomb {
            field: Field::Fs_neg,
            coulomb: 1.0,
            value: below
        })
    );
    // Equality is allowed: no Stribeck bump.
    let flat = Stribeck::asymmetric(1.0, 1.0, 0.5, 0.5, 1e-3, 2.0).expect("Fs = Fc is valid");
    assert_eq!((flat.g(1e-9), flat.g(-1e-9)), (1.0, 0.5));
}

#[test]
fn elements_must_be_positive_and_present() {
    // A subnormal W is a negligible but usable spring: nothing divides by it.
    for bad in &NOT_POSITIVE[..6] {
        let bad = *bad;
        for index in 0..3 {
            let mut w = [1.0; 3];
            w[index] = bad;
            assert_eq!(
                MaxwellSlip::new(w, [1e-6; 3]),
                Err(Error::Element {
                    field: Field::W,
                    index,
                    value: bad
                }),
                "W[{index}] = {bad}"
            );
            let mut delta = [1e-6; 3];
            delta[index] = bad;
            assert_eq!(
                MaxwellSlip::new([1.0; 3], delta),
                Err(Error::Element {
                    field: Field::Delta,
                    index,
                    value: bad
                }),
                "Delta[{index}] = {bad}"
            );
        }
    }
    assert_eq!(MaxwellSlip::<0>::new([], []), Err(Error::NoElements));
}

/// Finite values whose sum or quotient overflows are refused at construction, naming the real
/// cause: before, `W = [1e308; 4]` was accepted (and every step then failed with a message about
/// the explicit scheme), and `W = [1.7e308; 4]` blamed `Delta[0]`.
#[test]
fn overflowing_sums_and_stiffnesses_are_refused() {
    for w in [1e308, 1.7e308] {
        for delta in [1.0, 1e-6] {
            let refused = MaxwellSlip::new([w; 4], [delta; 4]);
            assert_eq!(
                refused,
                Err(Error::ForceSumOverflow {
                    index: 0,
                    largest: w
                }),
                "W = {w}, Delta = {delta}"
            );
            let message = refused.unwrap_err().to_string();
            assert!(
                message.starts_with("`sum(W)` must be finite") && message.contains("`W[0]`"),
                "{message}"
            );
        }
    }
    // The largest W is named, not the first.
    assert_eq!(
        MaxwellSlip::new([1e300, 1.7e308, 1.0e308], [1.0; 3]),
        Err(Error::ForceSumOverflow {
            index: 1,
            largest: 1.7e308
        })
    );
    // A break deflection so small that the stiffness W/Δ overflows is not a spring either.
    let refused = MaxwellSlip::new([1.0, 2.0], [1e-6, 1e-310]);
    assert_eq!(
        refused,
        Err(Error::StiffnessOverflow {
            index: 1,
            w: 2.0,
            delta: 1e-310
        })
    );
    assert_eq!(
        refused.unwrap_err().to_string(),
        "the stiffness `W[1]`/`Delta[1]` = 2.0/1e-310 must be finite, got a quotient that \
         overflows: the element is too stiff for f64 arithmetic"
    );
    // Each stiffness finite (1e308), their sum not.
    assert_eq!(
        MaxwellSlip::new([1e300; 2], [1e-8; 2]),
        Err(Error::StiffnessSumOverflow)
    );
    assert!(MaxwellSlip::new([1e300; 2], [1e-7; 2]).is_ok());
}

/// An element narrower than 2^-26 of the widest is refused: its window is below the rounding
/// unit of z, the implicit step cannot locate its root, and two correct implementations (this
/// one and the numpy reference) disagreed by up to 25 % at `Delta[0]` = 1e-18 or 1e-22.
#[test]
fn elements_narrower_than_the_rounding_of_z_are_refused() {
    assert_eq!(MIN_DELTA_RATIO, f64::EPSILON.sqrt());
    for narrow in [1e-14, 1e-18, 1e-20, 1e-22, 1e-300] {
        let refused = MaxwellSlip::new([0.5; 4], [narrow, 1e-6, 2e-6, 4e-6]);
        assert_eq!(
            refused,
            Err(Error::DeltaTooNarrow {
                index: 0,
                value: narrow,
                widest: 4e-6
            }),
            "Delta[0] = {narrow}"
        );
        let message = refused.unwrap_err().to_string();
        assert!(
            message.starts_with("`Delta[0]` must be >= 2^-26 (about 1.5e-8) times the widest")
                && message.contains("rounding"),
            "{message}"
        );
    }
    // On the edge: accepted; any relative spread is fine at any absolute scale.
    let widest = 4e-6;
    assert!(MaxwellSlip::new([0.5; 2], [widest * MIN_DELTA_RATIO, widest]).is_ok());
    assert!(MaxwellSlip::new([0.5; 2], [(widest * MIN_DELTA_RATIO).next_down(), widest]).is_err());
    assert!(MaxwellSlip::new([0.5; 2], [1e-300, 2e-300]).is_ok());
}

#[test]
fn linear_stiffness_must_be_positive() {
    for bad in NOT_POSITIVE {
        assert_eq!(
            Linear::new(bad),
            Err(Error::NotPositive {
                field: Field::sigma0,
                value: bad
            }),
            "sigma0 = {bad}"
        );
    }
}

#[test]
fn model_coefficients_follow_their_rules() {
    for bad in NOT_POSITIVE {
        assert_eq!(
            Params::new(curve(), bad, 1.0, 1.0, elements()),
            Err(Error::NotPositive {
                field: Field::n,
                value: bad
            })
        );
    }
    for bad in NEGATIVE {
        assert_eq!(
            Params::new(curve(), 1.0, bad, 1.0, elements()),
            Err(Error::Negative {
                field: Field::sigma1,
                value: bad
            }),
            "sigma1 = {bad}"
        );
        assert_eq!(
            Params::new(curve(), 1.0, 1.0, bad, elements()),
            Err(Error::Negative {
                field: Field::sigma2,
                value: bad
            }),
            "sigma2 = {bad}"
        );
    }
    // Zero damping is allowed (Dahl-like), and so is negative zero.
    for zero in [0.0, -0.0] {
        assert!(Params::new(curve(), 1.0, zero, zero, elements()).is_ok());
    }
}

#[test]
fn the_viscous_coefficient_of_negative_velocity_follows_sigma2s_rule() {
    let params = Params::new(curve(), 1.0, 1.0, 0.4, elements()).unwrap();
    for bad in NEGATIVE {
        assert_eq!(
            params.with_sigma2_neg(bad),
            Err(Error::Negative {
                field: Field::sigma2_neg,
                value: bad
            }),
            "sigma2_neg = {bad}"
        );
    }
    assert_eq!(
        params.with_sigma2_neg(-1.0).unwrap_err().to_string(),
        "`sigma2_neg` must be finite and >= 0, got -1.0"
    );
    // Not given, it is sigma2: the same parameters as given equal to sigma2.
    assert_eq!(params.sigma2_neg(), 0.4);
    assert_eq!(params.with_sigma2_neg(0.4), Ok(params));
    let asymmetric = params.with_sigma2_neg(0.0).unwrap();
    assert_eq!(
        (
            asymmetric.sigma2_at(-1e-9),
            asymmetric.sigma2_at(0.0),
            asymmetric.sigma2_at(-0.0)
        ),
        (0.0, 0.4, 0.4)
    );
}

proptest! {
    #![proptest_config(common::config(128))]

    /// sum(W) must exceed the larger static level, whichever direction it belongs to.
    #[test]
    fn elements_must_balance_the_stribeck_curve(
        stribeck in stribeck(),
        weights in uniform::<_, 5>(0.05..1.0f64),
        delta in uniform::<_, 5>(log_uniform(1e-7, 1e-4)),
        (weak, strong) in (0.05..0.999f64, 1.001..5.0f64),
    ) {
        let peak = stribeck.fs().max(stribeck.fs_neg());
        let too_weak = MaxwellSlip::new(saturation_forces(weights, peak, weak), delta).expect("valid elements");
        prop_assert_eq!(
            Params::new(stribeck, 1.0, 1.0, 1.0, too_weak),
            Err(Error::ElementsTooWeak { sum: too_weak.max_force(), peak })
        );
        let strong_enough = MaxwellSlip::new(saturation_forces(weights, peak, strong), delta).expect("valid elements");
        prop_assert!(Params::new(stribeck, 1.0, 1.0, 1.0, strong_enough).is_ok());
        // A linear spring has no saturation: never too weak.
        prop_assert!(Params::new(stribeck, 1.0, 1.0, 1.0, Linear::new(1e5).expect("valid")).is_ok());
    }
}

#[test]
fn elements_exactly_at_the_static_level_are_too_weak() {
    // sum(W) = 1.5 = Fs exactly, and sum(W) = 1.2 = Fs_neg < Fs with Fs_neg the larger level.
    let at_fs = MaxwellSlip::new([1.0, 0.5], [1e-6, 2e-6]).expect("valid elements");
    assert_eq!(
        Params::new(curve(), 1.0, 0.0, 0.0, at_fs),
        Err(Error::ElementsTooWeak {
            sum: 1.5,
            peak: 1.5
        })
    );
    let reversed = Stribeck::asymmetric(0.8, 1.2, 1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    assert_eq!(
        Params::new(reversed, 1.0, 0.0, 0.0, at_fs),
        Err(Error::ElementsTooWeak {
            sum: 1.5,
            peak: 1.5
        })
    );
    let above = MaxwellSlip::new([1.0, 0.5 + 1e-12], [1e-6, 2e-6]).expect("valid elements");
    assert!(Params::new(reversed, 1.0, 0.0, 0.0, above).is_ok());
}

#[test]
fn messages_name_the_key() {
    for field in FIELDS {
        let key = field.key();
        assert_eq!(field.to_string(), key);
        let errors = [
            Error::NotPositive { field, value: -1.0 },
            Error::Negative { field, value: -1.0 },
            Error::StaticBelowCoulomb {
                field,
                coulomb: 1.0,
                value: 0.5,
            },
            Error::Element {
                field,
                index: 3,
                value: f64::NAN,
            },
            Error::NotFinite {
                field,
                index: 3,
                value: f64::INFINITY,
            },
        ];
        for error in errors {
            let message = error.to_string();
            assert!(
                message.contains(&format!("`{key}")),
                "{error:?} displays as {message:?}"
            );
        }
    }
}

/// The messages carry the value, spelled as Python prints floats, and the channel when given.
#[test]
fn messages_carry_the_value() {
    let cases = [
        (
            Error::NotPositive {
                field: Field::dt,
                value: 0.0,
            },
            "`dt` must be finite and > 0, got 0.0",
        ),
        (
            Error::NotPositive {
                field: Field::Fc,
                value: 1e-310,
            },
            "`Fc` must be finite and > 0, got 1e-310 (a subnormal number: at least 2.2e-308 is \
             needed)",
        ),
        (
            Error::Negative {
                field: Field::sigma1,
                value: f64::NAN,
            },
            "`sigma1` must be finite and >= 0, got nan",
        ),
        (
            Error::StaticBelowCoulomb {
                field: Field::Fs_neg,
                coulomb: 0.8,
                value: 0.5,
            },
            "`Fs_neg` must be >= `Fc_neg` = 0.8, got 0.5",
        ),
        (
            Error::Element {
                field: Field::W,
                index: 2,
                value: f64::NEG_INFINITY,
            },
            "`W[2]` must be finite and > 0, got -inf",
        ),
        (
            Error::ElementsTooWeak {
                sum: 1.0,
                peak: 1.5,
            },
            "`sum(W)` must be > max(`Fs`, `Fs_neg`) = 1.5, got sum(W) = 1.0: the hysteresis force \
             could never balance the Stribeck curve",
        ),
        (
            Error::NotFinite {
                field: Field::v,
                index: 4,
                value: f64::INFINITY,
            },
            "`v` must be finite, got inf at sample 4",
        ),
    ];
    for (error, message) in cases {
        assert_eq!(error.to_string(), message);
    }
    assert_eq!(
        Error::Diverged { index: 5 }.in_channel(1).to_string(),
        "the explicit step diverged at channel 1, sample 5: dt is too large for the stiffness; \
         use the implicit scheme"
    );
    // Not about a sample: the channel adds nothing.
    let dt = Error::NotPositive {
        field: Field::dt,
        value: -1.0,
    };
    assert_eq!(dt.in_channel(3).to_string(), dt.to_string());
}

/// The error is a small value: `Copy`, comparable, and a `core::error::Error`.
#[test]
fn errors_are_plain_values() {
    fn plain<T: Copy + PartialEq + core::error::Error>() {}
    plain::<Error>();
}
