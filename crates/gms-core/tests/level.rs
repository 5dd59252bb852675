//! The position-dependent terms (docs/model.md#position-dependent-level): the rules of their
//! shape (the level's and the position force's), the factor and the force against the plain
//! formula, and the compensator and block runs that apply them.

mod common;

use common::config;
use core::f64::consts::TAU;
use gms_core::{
    Compensator, Error, Field, LeuvenParams, Level, Linear, MaxwellSlip, Mode, Params,
    PositionForce, PositionSeries, RippleTerms, Scheme, State, Stribeck, MAX_HARMONICS,
};
use proptest::prelude::*;

const DT: f64 = 1e-3;

/// σ2 = 0.4 for v ≥ 0 and 0.7 for v < 0.
fn params() -> LeuvenParams<3> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let bank = MaxwellSlip::new([0.6, 0.6, 0.6], [1e-6, 2e-6, 4e-6]).unwrap();
    Params::new(stribeck, 2.0, 30.0, 0.4, bank)
        .and_then(|params| params.with_sigma2_neg(0.7))
        .unwrap()
}

/// σ2(v) of `params()`.
fn sigma2(v: f64) -> f64 {
    if v < 0.0 {
        0.7
    } else {
        0.4
    }
}

/// A cogging force: a gravity-like trend and a ripple of large, unbounded amplitudes [N].
fn cogging() -> PositionForce {
    PositionForce::new(
        0.001,
        0.02,
        [0.8, -0.3],
        &[RippleTerms {
            period: 0.0025,
            cos: &[0.9, 0.4],
            sin: &[-0.6, 0.25],
        }],
    )
    .unwrap()
}

/// r(x) of a position force as written: the trend and cos(k·2π·x/P) per harmonic.
fn force_formula(force: &PositionForce, x: f64) -> f64 {
    let series = force.series();
    let p = ((x - series.middle()) / series.half_stroke()).clamp(-1.0, 1.0);
    let [t1, t2] = series.trend();
    let mut out = t1 * p + t2 * (1.5 * p * p - 0.5);
    for r in 0..series.ripple_count() {
        let ripple = series.ripple(r).unwrap();
        for (k, (c, s)) in ripple.cos.iter().zip(ripple.sin).enumerate() {
            let angle = (k + 1) as f64 * TAU * x / ripple.period;
            out += c * libm::cos(angle) + s * libm::sin(angle);
        }
    }
    out
}

/// A trend and two ripples with several harmonics, as identified on a screw axis.
fn screw_level() -> Level {
    Level::new(
        0.002,
        0.01,
        [0.05, -0.02],
        &[
            RippleTerms {
                period: 0.004,
                cos: &[0.03, 0.01, 0.005],
                sin: &[0.0, 0.02, -0.004],
            },
            RippleTerms {
                period: 0.0013,
                cos: &[0.01, -0.006],
                sin: &[0.012, 0.003],
            },
        ],
    )
    .unwrap()
}

/// The formula as written (and as numpy evaluates it): cos(k·2π·x/P) per harmonic, no reduction.
fn formula(level: &Level, x: f64) -> f64 {
    let scaled = (x - level.middle()) / level.half_stroke();
    let p = scaled.clamp(-1.0, 1.0); // a test helper: the bounds are constants
    let [t1, t2] = level.trend();
    let mut out = 1.0 + t1 * p + t2 * (1.5 * p * p - 0.5);
    for r in 0..level.ripple_count() {
        let ripple = level.ripple(r).unwrap();
        let phase = TAU * x / ripple.period;
        for (k, (c, s)) in ripple.cos.iter().zip(ripple.sin).enumerate() {
            let angle = (k + 1) as f64 * phase;
            out += c * libm::cos(angle) + s * libm::sin(angle);
        }
    }
    out
}

/// The same with the phase reduced to one period first, each harmonic from libm directly: what
/// the recurrence approximates, at any |x|.
fn reduced_formula(level: &Level, x: f64) -> f64 {
    let flat = Level::new(level.middle(), level.half_stroke(), level.trend(), &[]).unwrap();
    let mut out = flat.factor(x);
    for r in 0..level.ripple_count() {
        let ripple = level.ripple(r).unwrap();
        let cycles = x / ripple.period;
        let angle = TAU * (cycles - libm::round(cycles));
        for (k, (c, s)) in ripple.cos.iter().zip(ripple.sin).enumerate() {
            let angle = (k + 1) as f64 * angle;
            out += c * libm::cos(angle) + s * libm::sin(angle);
        }
    }
    out
}

fn terms(period: f64, cos: &'static [f64], sin: &'static [f64]) -> RippleTerms<'static> {
    RippleTerms { period, cos, sin }
}

#[test]
#[allow(clippy::too_many_lines)] // one case per rule
fn every_rule_names_its_field_and_value() {
    let ok = terms(0.004, &[0.1], &[0.1]);
    let cases: [(Result<Level, Error>, Error, &str); 12] = [
        (
            Level::new(f64::NAN, 1.0, [0.0; 2], &[]),
            Error::NotFiniteValue {
                field: Field::middle,
                value: f64::NAN,
            },
            "`middle` must be finite, got nan",
        ),
        (
            Level::new(0.0, 0.0, [0.0; 2], &[]),
            Error::NotPositive {
                field: Field::half_stroke,
                value: 0.0,
            },
            "`half_stroke` must be finite and > 0, got 0.0",
        ),
        (
            Level::new(0.0, 1e-310, [0.0; 2], &[]),
            Error::NotPositive {
                field: Field::half_stroke,
                value: 1e-310,
            },
            "subnormal",
        ),
        (
            Level::new(0.0, 1.0, [0.1, f64::INFINITY], &[]),
            Error::NotFinite {
                field: Field::trend,
                index: 1,
                value: f64::INFINITY,
            },
            "`trend` must be finite, got inf at entry 1",
        ),
        (
            Level::new(0.0, 1.0, [0.0; 2], &[ok, ok, ok]),
            Error::TooManyRipples { count: 3 },
            "`ripples` must have at most 2 ripples, got 3",
        ),
        (
            Level::new(0.0, 1.0, [0.0; 2], &[ok, terms(-0.5, &[], &[])]),
            Error::RipplePeriod {
                ripple: 1,
                value: -0.5,
            },
            "`ripples[1].period` must be finite and > 0, got -0.5",
        ),
        (
            Level::new(0.0, 1.0, [0.0; 2], &[terms(5e-324, &[], &[])]),
            Error::RipplePeriod {
                ripple: 0,
                value: 5e-324,
            },
            "subnormal",
        ),
        (
            Level::new(0.0, 1.0, [0.0; 2], &[terms(1.0, &[0.1, 0.1], &[0.1])]),
            Error::HarmonicLengths {
                ripple: 0,
                cos: 2,
                sin: 1,
            },
            "`ripples[0].cos` and `ripples[0].sin` must have the same length, got 2 and 1",
        ),
        (
            Level::new(0.0, 1.0, [0.0; 2], &[terms(1.0, &[0.0; 9], &[0.0; 9])]),
            Error::TooManyHarmonics {
                ripple: 0,
                count: 9,
            },
            "`ripples[0]` must have at most 8 harmonics, got 9",
        ),
        (
            Level::new(
                0.0,
                1.0,
                [0.0; 2],
                &[ok, terms(1.0, &[0.0, 0.0], &[0.0, f64::NAN])],
            ),
            Error::RippleCoefficient {
                field: Field::sin,
                ripple: 1,
                index: 1,
                value: f64::NAN,
            },
            "`ripples[1].sin[1]` must be finite, got nan",
        ),
        (
            Level::new(0.0, 1.0, [0.5, -0.25], &[terms(1.0, &[0.125], &[-0.125])]),
            Error::LevelTooDeep { sum: 1.0 },
            "< 1 (so that the factor stays > 0 everywhere), got 1.0",
        ),
        (
            Level::new(0.0, 1.0, [f64::MAX, 0.0], &[]),
            Error::LevelTooDeep { sum: f64::MAX },
            "got 1.7976931348623157e308",
        ),
    ];
    for (got, expected, message) in cases {
        assert_eq!(got, Err(expected));
        let shown = expected.to_string();
        assert!(shown.contains(message), "{shown:?} lacks {message:?}");
    }
    // Just below the bound is a level.
    let deep = Level::new(0.0, 1.0, [0.5, -0.25], &[terms(1.0, &[0.125], &[-0.124])]).unwrap();
    assert!(deep.factor(0.0) > 0.0);
}

/// 2^20 ulps of `extent`: the finest period or half stroke resolved at positions up to it.
fn finest(extent: f64) -> f64 {
    1_048_576.0 * (f64::from_bits(extent.to_bits() + 1) - extent)
}

/// A period or half stroke whose phase cannot be resolved at the positions the series covers
/// is refused, naming the field (and the ripple) and carrying the value and the extent; the
/// level and the position force share the rule. (Python and C accepted periods of 1e-12 and
/// 1e-300, where the factor was decided by rounding.)
#[test]
#[allow(clippy::too_many_lines)] // one case per rule
fn unresolvable_phases_are_refused() {
    let period = |value| [terms(value, &[0.1], &[0.1])];
    let cases: [(f64, f64, [RippleTerms<'static>; 1], Error); 7] = [
        (
            0.0,
            1.0,
            period(1e-12),
            Error::PhaseUnresolved {
                field: Field::period,
                index: 0,
                value: 1e-12,
                extent: 1.0,
            },
        ),
        (
            0.0,
            1.0,
            period(1e-300),
            Error::PhaseUnresolved {
                field: Field::period,
                index: 0,
                value: 1e-300,
                extent: 1.0,
            },
        ),
        // 2^20 ulps of 1 are 2^-32: just below is refused.
        (
            0.0,
            1.0,
            period(0.999 * 2f64.powi(-32)),
            Error::PhaseUnresolved {
                field: Field::period,
                index: 0,
                value: 0.999 * 2f64.powi(-32),
                extent: 1.0,
            },
        ),
        // Far along the stroke a coarser period is needed: 2^20 ulps of 1000 + 1 are 2.4e-7.
        (
            1000.0,
            1.0,
            period(1e-7),
            Error::PhaseUnresolved {
                field: Field::period,
                index: 0,
                value: 1e-7,
                extent: 1001.0,
            },
        ),
        (
            0.0,
            1e-300,
            period(0.01),
            Error::PhaseUnresolved {
                field: Field::half_stroke,
                index: 0,
                value: 1e-300,
                extent: 1.0,
            },
        ),
        // A middle so far from 0 that the half stroke is below its rounding.
        (
            1e308,
            1.0,
            period(0.01),
            Error::PhaseUnresolved {
                field: Field::middle,
                index: 0,
                value: 1e308,
                extent: 1e308,
            },
        ),
        // |middle| + half_stroke overflows: nothing is resolved there.
        (
            -1e308,
            1e308,
            period(0.01),
            Error::PhaseUnresolved {
                field: Field::middle,
                index: 0,
                value: -1e308,
                extent: f64::INFINITY,
            },
        ),
    ];
    for (middle, half_stroke, ripples, expected) in cases {
        assert_eq!(
            Level::new(middle, half_stroke, [0.0; 2], &ripples),
            Err(expected),
            "{middle} {half_stroke}"
        );
        assert_eq!(
            PositionForce::new(middle, half_stroke, [0.0; 2], &ripples),
            Err(expected)
        );
        let shown = expected.to_string();
        let named = match expected {
            Error::PhaseUnresolved {
                field: Field::period,
                ..
            } => "`ripples[0].period` must be at least 2^20 ulps",
            Error::PhaseUnresolved {
                field: Field::middle,
                ..
            } => "`middle` must leave `half_stroke` at least 2^20 ulps",
            _ => "`half_stroke` must be at least 2^20 ulps",
        };
        assert!(shown.contains(named), "{shown}");
    }
    // The second ripple is named by its index; the rule reads the stroke, not the position.
    assert!(matches!(
        Level::new(
            0.0,
            1.0,
            [0.0; 2],
            &[terms(0.5, &[], &[]), terms(1e-11, &[], &[])]
        ),
        Err(Error::PhaseUnresolved {
            field: Field::period,
            index: 1,
            ..
        })
    ));
    // At the bound itself the series is accepted, and so is a tiny stroke about 0 that is
    // still resolved.
    for extent in [1.0, 1001.0, 3.7e5] {
        let middle = extent - 1.0;
        let ok = [terms(finest(extent), &[0.1], &[0.1])];
        assert!(Level::new(middle, 1.0, [0.0; 2], &ok).is_ok(), "{extent}");
        let below = [terms(finest(extent) * (1.0 - f64::EPSILON), &[0.1], &[0.1])];
        assert!(
            Level::new(middle, 1.0, [0.0; 2], &below).is_err(),
            "{extent}"
        );
    }
    assert!(PositionSeries::new(0.0, 2f64.powi(-32), [0.1, 0.0], &[]).is_ok());
}

#[test]
fn a_position_force_has_any_finite_amplitudes() {
    // Far beyond the level's rule of a sum below 1: forces in N.
    let force = cogging();
    assert!(force.series().amplitude() > 1.0);
    for k in -3000..=3000 {
        let x = f64::from(k) * 1.3e-5;
        let (got, want) = (force.force(x), force_formula(&force, x));
        assert!(
            (got - want).abs() <= 1e-12 * force.series().amplitude(),
            "x = {x}: {got} vs {want}"
        );
    }
    // The level of the same shape is its factor minus one: one implementation.
    let level = Level::new(0.0, 0.5, [0.2, 0.1], &[terms(0.01, &[0.05], &[0.1])]).unwrap();
    let same = PositionForce::new(0.0, 0.5, [0.2, 0.1], &[terms(0.01, &[0.05], &[0.1])]).unwrap();
    for x in [-0.7, -0.1, 0.0, 0.013, 0.4, 3.0] {
        assert!((level.factor(x) - 1.0 - same.force(x)).abs() <= 4.0 * f64::EPSILON);
        assert_eq!(same.force(x), level.series().value(x));
    }
    // Non-finite amplitudes are refused as for a level; a non-finite x gives NaN.
    assert_eq!(
        PositionForce::new(0.0, 1.0, [f64::NAN, 0.0], &[]),
        Err(Error::NotFinite {
            field: Field::trend,
            index: 0,
            value: f64::NAN
        })
    );
    assert!(force.force(f64::NAN).is_nan());
    // No position force leaves a force as it is, bit for bit (-0.0 included).
    assert_eq!(
        PositionForce::none().apply(-0.0, 3.0).to_bits(),
        (-0.0f64).to_bits()
    );
    assert!(PositionForce::none().is_none() && !force.is_none());
}

#[test]
fn factor_matches_the_formula() {
    let level = screw_level();
    for k in -4000..=4000 {
        let x = f64::from(k) * 7.3e-6;
        let (got, want) = (level.factor(x), formula(&level, x));
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "x = {x}: {got} vs {want}"
        );
    }
}

#[test]
fn the_trend_is_clipped_beyond_the_stroke() {
    let level = Level::new(0.0, 0.5, [0.2, 0.1], &[]).unwrap();
    assert_eq!(level.factor(0.5), level.factor(7.0));
    assert_eq!(level.factor(-0.5), level.factor(-1e300));
    assert_eq!(level.factor(0.5), 1.0 + 0.2 + 0.1);
    assert_eq!(level.factor(-0.5), 1.0 - 0.2 + 0.1);
    assert_eq!(level.factor(0.0), 1.0 - 0.05);
}

/// The recurrence drifts by a few ulps per harmonic at most: against libm at the same reduced
/// angle it stays within 4e-15 on the factor with all eight harmonics, at any |x/P|.
#[test]
fn recurrence_drift_is_bounded_at_large_positions() {
    const FULL: [f64; MAX_HARMONICS] = [0.06; MAX_HARMONICS];
    let level = Level::new(
        0.0,
        1.0,
        [0.0; 2],
        &[
            terms(1.0, &FULL, &[0.0; MAX_HARMONICS]),
            terms(0.37, &[0.0; 8], &[0.05; 8]),
        ],
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for exponent in 0..=12 {
        for k in 1..500 {
            let x = 10f64.powi(exponent) * (1.0 + f64::from(k) * 0.0137);
            for x in [x, -x] {
                worst = worst.max((level.factor(x) - reduced_formula(&level, x)).abs());
            }
        }
    }
    assert!(worst <= 4e-15, "drift {worst:e}");
    assert!(
        worst > 0.0,
        "the check must see the recurrence, not the same numbers"
    );
}

proptest! {
    #![proptest_config(config(256))]

    /// Any valid level is positive everywhere and agrees with the plain formula to 1e-12
    /// relative for |x/P| up to 20 for every ripple (the plain formula's own phase rounding,
    /// about 3·k·2π·|x/P|·1.1e-16 rad, is 3e-13 there with k = 8).
    #[test]
    fn factor_is_positive_and_matches(
        middle in -1.0f64..1.0,
        half_stroke in 1e-3f64..2.0,
        raw in prop::collection::vec(-1.0f64..1.0, 2 + 4 * MAX_HARMONICS),
        harmonics in (0usize..=MAX_HARMONICS, 0usize..=MAX_HARMONICS),
        periods in (1e-3f64..1.0, 1e-3f64..1.0),
        depth in 0.0f64..0.999,
        cycles in -20.0f64..20.0,
    ) {
        let total: f64 = raw.iter().map(|c| c.abs()).sum();
        let scale = if total > 0.0 { depth / total } else { 0.0 };
        let c: Vec<f64> = raw.iter().map(|c| c * scale).collect();
        let (h0, h1) = harmonics;
        let m = MAX_HARMONICS;
        let ripples = [
            RippleTerms { period: periods.0, cos: &c[2..2 + h0], sin: &c[2 + m..2 + m + h0] },
            RippleTerms { period: periods.1, cos: &c[2 + 2 * m..2 + 2 * m + h1], sin: &c[2 + 3 * m..2 + 3 * m + h1] },
        ];
        let level = Level::new(middle, half_stroke, [c[0], c[1]], &ripples).unwrap();
        let x = cycles * periods.0.min(periods.1);
        let (got, want) = (level.factor(x), formula(&level, x));
        prop_assert!(got > 0.0);
        prop_assert!((got - want).abs() <= 1e-12 * want.abs(), "{} vs {}", got, want);
    }
}

fn trajectory(samples: usize) -> Vec<f64> {
    (0..samples)
        .map(|k| 0.003 * libm::sin(2.0 * k as f64 / samples as f64 * TAU) + 1e-4 * k as f64 / 10.0)
        .collect()
}

/// The output with both terms as docs/model.md#position-dependent-level writes it.
fn with_terms(level: &Level, force: &PositionForce, plain: f64, x: f64, v: f64) -> f64 {
    let viscous = sigma2(v) * v;
    level.factor(x) * (plain - viscous) + viscous + force.force(x)
}

#[test]
fn observer_with_a_level_and_a_position_force_is_the_formula() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let mut plain = Compensator::new(params, DT, Mode::Observer).unwrap();
    let mut leveled = Compensator::new(params, DT, Mode::Observer)
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    let mut previous: Option<f64> = None;
    let (mut changed, mut backward) = (0, 0);
    for x in trajectory(3000) {
        let plain_force = plain.step(x).unwrap();
        let v = previous.map_or(0.0, |p| (x - p) / DT);
        let want = with_terms(&level, &force, plain_force, x, v);
        let got = leveled.step(x).unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
        assert_eq!(leveled.output(), got);
        assert_eq!(
            leveled.state(),
            plain.state(),
            "the terms only act on the output"
        );
        changed += usize::from(got != plain_force);
        backward += usize::from(v < 0.0);
        previous = Some(x);
    }
    assert!(changed > 2900, "the terms must change the output");
    assert!(
        backward > 300,
        "the motion must use sigma2_neg: {backward} samples"
    );
}

#[test]
fn feedforward_refuses_position_terms_without_a_start_position() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let error = Error::Missing { field: Field::x };
    let missing = Err(error);
    let bare = Compensator::new(params, DT, Mode::Feedforward).unwrap();
    assert_eq!(bare.position(), None);
    assert_eq!(bare.with_level(level).map(|_| ()), missing);
    assert_eq!(bare.with_position_force(force).map(|_| ()), missing);
    let mut compensator = bare;
    assert_eq!(compensator.set_level(level), missing);
    assert_eq!(compensator.set_position_force(force), missing);
    assert_eq!(compensator, bare, "a refusal changes nothing");
    assert!(error
        .to_string()
        .starts_with("`x`, the axis's start position"));
    // Flat terms need no position; observer mode takes it from its input; a start position
    // (not NaN) opens the way.
    assert!(bare.with_level(Level::none()).is_ok());
    assert!(bare.with_position_force(PositionForce::none()).is_ok());
    let observer = Compensator::new(params, DT, Mode::Observer).unwrap();
    assert!(observer
        .with_level(level)
        .and_then(|c| c.with_position_force(force))
        .is_ok());
    assert_eq!(
        bare.with_start_position(f64::NAN),
        Err(Error::NotFiniteValue {
            field: Field::x,
            value: f64::NAN
        })
    );
    let started = bare
        .with_start_position(-0.004)
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    assert_eq!(started.position(), Some(-0.004));
}

#[test]
fn feedforward_integrates_from_the_start_position() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let start = -0.0042;
    let mut plain = Compensator::new(params, DT, Mode::Feedforward).unwrap();
    let mut leveled = Compensator::new(params, DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(start))
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    assert_eq!(
        leveled.set_position(f64::NAN),
        Err(Error::NotFiniteValue {
            field: Field::x,
            value: f64::NAN
        })
    );
    assert_eq!(leveled.position(), Some(start));
    let mut x = start;
    for k in 0..2000 {
        let v = 8e-3 * libm::cos(f64::from(k) * 0.01);
        x += v * DT;
        let plain_force = plain.step(v).unwrap();
        let want = with_terms(&level, &force, plain_force, x, v);
        let got = leveled.step(v).unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
    }
    assert_eq!(leveled.position(), Some(x));
    // Swapping the terms leaves the state; flat ones give the plain output again.
    leveled.set_level(Level::none()).unwrap();
    leveled.set_position_force(PositionForce::none()).unwrap();
    assert_eq!(leveled.state(), plain.state());
    assert_eq!(leveled.step(1e-3).unwrap(), plain.step(1e-3).unwrap());
    x += 1e-3 * DT;
    // Resetting the model does not move the axis.
    leveled.reset();
    assert_eq!(leveled.position(), Some(x));
}

/// A trajectory generator gives the position with the velocity: the compensator places the
/// terms there instead of integrating, and its model runs on the velocity exactly as `step`.
#[test]
fn step_trajectory_places_the_terms_at_the_given_position() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let positions = trajectory(2000);
    let mut plain = Compensator::new(params, DT, Mode::Feedforward).unwrap();
    let mut compensator = Compensator::new(params, DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(positions[0]))
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    let mut previous = positions[0];
    for &x in &positions {
        // A velocity that is not the positions' difference: the two are independent inputs.
        let v = 1.1 * (x - previous) / DT;
        let plain_force = plain.step(v).unwrap();
        let got = compensator.step_trajectory(v, x).unwrap();
        assert_eq!(
            got.to_bits(),
            force
                .apply(level.apply(plain_force, x, v, sigma2(v)), x)
                .to_bits()
        );
        assert_eq!(compensator.position(), Some(x));
        assert_eq!(compensator.state(), plain.state());
        previous = x;
    }
    // Refusals change nothing.
    let before = compensator;
    for (v, x, field, value) in [
        (f64::NAN, 0.0, Field::v, f64::NAN),
        (1e-3, f64::INFINITY, Field::x, f64::INFINITY),
    ] {
        assert_eq!(
            compensator.step_trajectory(v, x),
            Err(Error::NotFinite {
                field,
                index: 0,
                value
            })
        );
        assert_eq!(compensator, before);
    }
    // A force the terms make non-finite is refused, and nothing changes.
    let huge = PositionForce::new(0.0, 1.0, [f64::MAX, f64::MAX], &[]).unwrap();
    compensator.set_position_force(huge).unwrap();
    let before = compensator;
    assert_eq!(
        compensator.step_trajectory(1e-3, 0.9),
        Err(Error::Diverged { index: 0 })
    );
    assert_eq!(compensator, before);
    // In observer mode the position becomes the previous one of the next step.
    let mut observer = Compensator::new(params, DT, Mode::Observer).unwrap();
    observer.step_trajectory(2e-3, 0.01).unwrap();
    assert_eq!(observer.state().last_position, Some(0.01));
    let mut state = params.relaxed_state();
    params.step(&mut state, 2e-3, DT, Scheme::Implicit).unwrap();
    state.last_position = Some(0.01);
    let want = params
        .step_position(&mut state, 0.0105, DT, Scheme::Implicit)
        .unwrap();
    assert_eq!(observer.step(0.0105).unwrap(), want);
}

#[test]
fn no_terms_are_bit_identical_to_the_plain_model() {
    let params = params();
    for mode in [Mode::Feedforward, Mode::Observer] {
        let mut compensator = Compensator::new(params, DT, mode)
            .and_then(|c| c.with_level(Level::none()))
            .and_then(|c| c.with_position_force(PositionForce::none()))
            .unwrap();
        let mut state = params.relaxed_state();
        for x in trajectory(1500) {
            let want = match mode {
                Mode::Feedforward => params.step(&mut state, x, DT, Scheme::Implicit),
                Mode::Observer => params.step_position(&mut state, x, DT, Scheme::Implicit),
            }
            .unwrap();
            assert_eq!(compensator.step(x).unwrap().to_bits(), want.to_bits());
        }
    }
}

#[test]
fn block_run_with_the_terms_is_the_observer() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let x = trajectory(2500);
    let mut out = vec![0.0; x.len()];
    let mut state = params.relaxed_state();
    params
        .simulate_position_level(
            &mut state,
            &x,
            DT,
            Scheme::Implicit,
            &level,
            &force,
            &mut out,
        )
        .unwrap();
    let mut observer = Compensator::new(params, DT, Mode::Observer)
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    for (&x, &force) in x.iter().zip(&out) {
        assert_eq!(observer.step(x).unwrap().to_bits(), force.to_bits());
    }
    // No terms is the plain run, bit for bit.
    let (mut flat, mut plain) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    let (mut a, mut b) = (params.relaxed_state(), params.relaxed_state());
    params
        .simulate_position_level(
            &mut a,
            &x,
            DT,
            Scheme::Implicit,
            &Level::none(),
            &PositionForce::none(),
            &mut flat,
        )
        .unwrap();
    params
        .simulate_position(&mut b, &x, DT, Scheme::Implicit, &mut plain)
        .unwrap();
    assert_eq!(flat, plain);
    assert_ne!(flat, out);
    // All or nothing: a bad sample leaves the state as it was.
    let mut bad = x.clone();
    bad[100] = f64::NAN;
    let before = state;
    assert_eq!(
        params.simulate_position_level(
            &mut state,
            &bad,
            DT,
            Scheme::Implicit,
            &level,
            &force,
            &mut out
        ),
        Err(Error::NotFinite {
            field: Field::x,
            index: 100,
            value: f64::NAN
        })
    );
    assert_eq!(state, before);
}

/// A block call of one LuGre channel from a state, writing the forces.
type BlockCall<'a> = dyn Fn(&mut State<()>, &mut [f64]) -> Result<(), Error> + 'a;

/// LuGre's implicit block calls compute the factor of the closed form 64 samples ahead; over
/// many such chunks they are still the single steps bit for bit (the compensator's, with and
/// without the terms), and a refused sample past the first chunk is named, the state left as it
/// was.
#[test]
fn lugre_block_runs_are_the_single_steps() {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let params = Params::new(stribeck, 1.0, 316.0, 0.4, Linear::new(1e5).unwrap())
        .and_then(|params| params.with_sigma2_neg(0.7))
        .unwrap();
    let (level, force) = (screw_level(), cogging());
    let x = trajectory(2500);
    let v: Vec<f64> = (0..x.len())
        .map(|k| 1.5e-2 * libm::sin(0.013 * k as f64))
        .collect();
    let run = |call: &BlockCall| {
        let (mut state, mut out) = (params.relaxed_state(), vec![0.0; x.len()]);
        call(&mut state, &mut out).unwrap();
        (state, out)
    };
    let (_, out) = run(&|state, out| params.simulate(state, &v, DT, Scheme::Implicit, out));
    let mut state = params.relaxed_state();
    for (&v, &force) in v.iter().zip(&out) {
        let want = params.step(&mut state, v, DT, Scheme::Implicit).unwrap();
        assert_eq!(want.to_bits(), force.to_bits());
    }

    let (_, out) =
        run(&|state, out| params.simulate_position(state, &x, DT, Scheme::Implicit, out));
    let mut state = params.relaxed_state();
    for (&x, &force) in x.iter().zip(&out) {
        let want = params
            .step_position(&mut state, x, DT, Scheme::Implicit)
            .unwrap();
        assert_eq!(want.to_bits(), force.to_bits());
    }

    let (_, out) = run(&|state, out| {
        params.simulate_position_level(state, &x, DT, Scheme::Implicit, &level, &force, out)
    });
    let mut observer = Compensator::new(params, DT, Mode::Observer)
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    for (&x, &force) in x.iter().zip(&out) {
        assert_eq!(observer.step(x).unwrap().to_bits(), force.to_bits());
    }

    let (state, out) = run(&|state, out| {
        params.simulate_level(state, &v, &x, DT, Scheme::Implicit, &level, &force, out)
    });
    let mut compensator = Compensator::new(params, DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(x[0]))
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    for ((&v, &x), &want) in v.iter().zip(&x).zip(&out) {
        assert_eq!(
            compensator.step_trajectory(v, x).unwrap().to_bits(),
            want.to_bits()
        );
    }
    assert_eq!(state, *compensator.state());

    // Refusals past the first chunk: a NaN position, and a position step whose velocity
    // overflows (found while stepping, after the factors of its chunk were computed).
    let (mut state, mut out) = (params.relaxed_state(), vec![0.0; x.len()]);
    params
        .simulate_position(&mut state, &x[..70], DT, Scheme::Implicit, &mut out[..70])
        .unwrap();
    let before = state;
    let mut bad = x.clone();
    bad[130] = f64::NAN;
    assert_eq!(
        params.simulate_position(&mut state, &bad, DT, Scheme::Implicit, &mut out),
        Err(Error::NotFinite {
            field: Field::x,
            index: 130,
            value: f64::NAN
        })
    );
    assert_eq!(state, before);
    let mut far = x.clone();
    far[200] = 1e306;
    assert_eq!(
        params.simulate_position(&mut state, &far, DT, Scheme::Implicit, &mut out),
        Err(Error::NotFinite {
            field: Field::v,
            index: 200,
            value: f64::INFINITY
        })
    );
    assert_eq!(state, before);
}

/// Velocity input with a position, as a log with a measured velocity column drives the model:
/// the feedforward compensator stepped along the same trajectory, bit for bit.
#[test]
fn velocity_block_run_at_positions_is_the_trajectory_step() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let x = trajectory(2500);
    let v: Vec<f64> = (0..x.len())
        .map(|k| 4e-3 * libm::sin(0.013 * k as f64))
        .collect();
    let mut out = vec![0.0; x.len()];
    let mut state = params.relaxed_state();
    params
        .simulate_level(
            &mut state,
            &v,
            &x,
            DT,
            Scheme::Implicit,
            &level,
            &force,
            &mut out,
        )
        .unwrap();
    let mut compensator = Compensator::new(params, DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(x[0]))
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    for ((&v, &x), &want) in v.iter().zip(&x).zip(&out) {
        assert_eq!(
            compensator.step_trajectory(v, x).unwrap().to_bits(),
            want.to_bits()
        );
    }
    assert_eq!(state, *compensator.state());
    assert_eq!(
        state.last_position, None,
        "velocity input leaves the previous position"
    );
    // No terms: Params::simulate's forces, bit for bit.
    let (mut with, mut without) = (vec![0.0; v.len()], vec![0.0; v.len()]);
    let (mut a, mut b) = (params.relaxed_state(), params.relaxed_state());
    let none = (Level::none(), PositionForce::none());
    params
        .simulate_level(
            &mut a,
            &v,
            &x,
            DT,
            Scheme::Explicit,
            &none.0,
            &none.1,
            &mut with,
        )
        .unwrap();
    params
        .simulate(&mut b, &v, DT, Scheme::Explicit, &mut without)
        .unwrap();
    assert_eq!(with, without);
    // Refusals name the input and the sample, and change nothing.
    let before = state;
    let mut bad = x.clone();
    bad[7] = f64::INFINITY;
    let run = |state: &mut _, v: &[f64], x: &[f64], out: &mut [f64]| {
        params.simulate_level(state, v, x, DT, Scheme::Implicit, &level, &force, out)
    };
    assert_eq!(
        run(&mut state, &v, &bad, &mut out),
        Err(Error::NotFinite {
            field: Field::x,
            index: 7,
            value: f64::INFINITY
        })
    );
    assert_eq!(
        run(&mut state, &v, &x[1..], &mut out),
        Err(Error::InputLengthMismatch {
            field: Field::x,
            expected: v.len(),
            got: v.len() - 1
        })
    );
    let mut bad = v.clone();
    bad[3] = f64::NAN;
    assert!(matches!(
        run(&mut state, &bad, &x, &mut out),
        Err(Error::NotFinite {
            field: Field::v,
            index: 3,
            ..
        })
    ));
    assert_eq!(state, before);
}

#[test]
fn refused_steps_change_nothing_with_the_terms() {
    let (params, level, force) = (params(), screw_level(), cogging());
    let mut feedforward = Compensator::new(params, DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(f64::MAX))
        .and_then(|c| c.with_level(level))
        .and_then(|c| c.with_position_force(force))
        .unwrap();
    feedforward.step(0.0).unwrap();
    let before = feedforward;
    // The integrated position overflows: reported as the position, nothing changes.
    assert_eq!(
        feedforward.step(1e300),
        Err(Error::NotFinite {
            field: Field::x,
            index: 0,
            value: f64::INFINITY
        })
    );
    assert_eq!(feedforward, before);
    for bad in [f64::NAN, f64::INFINITY] {
        assert!(feedforward.step(bad).is_err());
        assert_eq!(feedforward, before);
    }
    let mut observer = Compensator::new(params, DT, Mode::Observer)
        .and_then(|c| c.with_level(level))
        .unwrap();
    observer.step(0.001).unwrap();
    let before = observer;
    assert!(observer.step(f64::NAN).is_err());
    assert_eq!(observer, before);
}

/// Any f64, finite or not, tiny or huge.
fn any_float() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>(),
        prop::sample::select(
            &[
                0.0,
                -0.0,
                1e-300,
                5e-324,
                1e300,
                f64::MAX,
                f64::INFINITY,
                f64::NAN
            ][..]
        ),
        -1.0f64..1.0,
    ]
}

proptest! {
    #![proptest_config(config(256))]

    /// Whatever values come, building a series answers (a series or an error), never panics;
    /// a series built evaluates at any position without panicking, finite at a finite one when
    /// its amplitudes' sum is; and a compensator with the terms, fed any inputs, either steps or
    /// refuses without changing anything.
    #[test]
    fn nothing_panics_and_refusals_change_nothing(
        middle in any_float(),
        half_stroke in any_float(),
        trend in (any_float(), any_float()),
        period in any_float(),
        amplitudes in prop::collection::vec(any_float(), 0..=2 * MAX_HARMONICS + 2),
        positions in prop::collection::vec(any_float(), 1..8),
        inputs in prop::collection::vec((any_float(), any_float()), 1..24),
    ) {
        let half = amplitudes.len() / 2;
        let ripple = [RippleTerms { period, cos: &amplitudes[..half], sin: &amplitudes[half..2 * half] }];
        let built = PositionSeries::new(middle, half_stroke, [trend.0, trend.1], &ripple);
        let Ok(series) = built else {
            // The level and the position force refuse what the series refuses.
            prop_assert!(PositionForce::new(middle, half_stroke, [trend.0, trend.1], &ripple).is_err());
            return Ok(());
        };
        for &x in &positions {
            let value = series.value(x);
            if x.is_finite() && series.amplitude() < 1e300 {
                prop_assert!(value.is_finite(), "r({}) = {}", x, value);
            }
        }
        let force = PositionForce::new(middle, half_stroke, [trend.0, trend.1], &ripple).unwrap();
        for mode in [Mode::Feedforward, Mode::Observer] {
            let mut compensator = Compensator::new(params(), DT, mode)
                .and_then(|c| c.with_start_position(positions[0]))
                .and_then(|c| c.with_level(screw_level()))
                .and_then(|c| c.with_position_force(force));
            let Ok(compensator) = compensator.as_mut() else {
                // Only a start position that is not finite is refused.
                prop_assert!(!positions[0].is_finite());
                continue;
            };
            for &(v, x) in &inputs {
                for trajectory in [false, true] {
                    let before = *compensator;
                    let result = if trajectory {
                        compensator.step_trajectory(v, x)
                    } else {
                        compensator.step(v)
                    };
                    if let Ok(output) = result {
                        prop_assert!(output.is_finite());
                    } else {
                        prop_assert_eq!(*compensator, before);
                    }
                }
            }
        }
    }
}
