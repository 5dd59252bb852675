//! The position-dependent level (docs/model.md#position-dependent-level): its rules, its factor
//! against the plain formula, and the compensator and block run that apply it.

mod common;

use common::config;
use core::f64::consts::TAU;
use gms_core::{
    Compensator, Error, Field, LeuvenParams, Level, MaxwellSlip, Mode, Params, RippleTerms, Scheme,
    Stribeck, MAX_HARMONICS,
};
use proptest::prelude::*;

const DT: f64 = 1e-3;

fn params() -> LeuvenParams<3> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let bank = MaxwellSlip::new([0.6, 0.6, 0.6], [1e-6, 2e-6, 4e-6]).unwrap();
    Params::new(stribeck, 2.0, 30.0, 0.4, bank).unwrap()
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

#[test]
fn observer_with_a_level_is_the_formula() {
    let (params, level) = (params(), screw_level());
    let mut plain = Compensator::new(params, DT, Mode::Observer).unwrap();
    let mut leveled = Compensator::new(params, DT, Mode::Observer)
        .unwrap()
        .with_level(level);
    let mut previous: Option<f64> = None;
    let mut changed = 0;
    for x in trajectory(3000) {
        let force = plain.step(x).unwrap();
        let v = previous.map_or(0.0, |p| (x - p) / DT);
        let want = level.factor(x) * (force - 0.4 * v) + 0.4 * v;
        let got = leveled.step(x).unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
        assert_eq!(leveled.output(), got);
        assert_eq!(
            leveled.state(),
            plain.state(),
            "the level only scales the output"
        );
        changed += usize::from(got != force);
        previous = Some(x);
    }
    assert!(changed > 2900, "the level must change the output");
}

#[test]
fn feedforward_integrates_from_the_start_position() {
    let (params, level) = (params(), screw_level());
    let start = -0.0042;
    let mut plain = Compensator::new(params, DT, Mode::Feedforward).unwrap();
    let mut leveled = Compensator::new(params, DT, Mode::Feedforward)
        .unwrap()
        .with_level(level);
    assert_eq!(
        leveled.set_position(f64::NAN),
        Err(Error::NotFiniteValue {
            field: Field::x,
            value: f64::NAN
        })
    );
    assert_eq!(leveled.position(), 0.0);
    leveled.set_position(start).unwrap();
    let mut x = start;
    for k in 0..2000 {
        let v = 8e-3 * libm::cos(f64::from(k) * 0.01);
        x += v * DT;
        let force = plain.step(v).unwrap();
        let want = level.factor(x) * (force - 0.4 * v) + 0.4 * v;
        let got = leveled.step(v).unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
    }
    assert_eq!(leveled.position(), x);
    // Swapping the level leaves the state; a flat level gives the plain output again.
    leveled.set_level(Level::none());
    assert_eq!(leveled.state(), plain.state());
    assert_eq!(leveled.step(1e-3).unwrap(), plain.step(1e-3).unwrap());
    x += 1e-3 * DT;
    // Resetting the model does not move the axis.
    leveled.reset();
    assert_eq!(leveled.position(), x);
}

#[test]
fn no_level_is_bit_identical_to_the_plain_model() {
    let params = params();
    for mode in [Mode::Feedforward, Mode::Observer] {
        let mut compensator = Compensator::new(params, DT, mode)
            .unwrap()
            .with_level(Level::none());
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
fn block_run_with_a_level_is_the_observer() {
    let (params, level) = (params(), screw_level());
    let x = trajectory(2500);
    let mut out = vec![0.0; x.len()];
    let mut state = params.relaxed_state();
    params
        .simulate_position_level(&mut state, &x, DT, Scheme::Implicit, &level, &mut out)
        .unwrap();
    let mut observer = Compensator::new(params, DT, Mode::Observer)
        .unwrap()
        .with_level(level);
    for (&x, &force) in x.iter().zip(&out) {
        assert_eq!(observer.step(x).unwrap().to_bits(), force.to_bits());
    }
    // A flat level is the plain run, bit for bit.
    let (mut flat, mut plain) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    let (mut a, mut b) = (params.relaxed_state(), params.relaxed_state());
    params
        .simulate_position_level(&mut a, &x, DT, Scheme::Implicit, &Level::none(), &mut flat)
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
        params.simulate_position_level(&mut state, &bad, DT, Scheme::Implicit, &level, &mut out),
        Err(Error::NotFinite {
            field: Field::x,
            index: 100,
            value: f64::NAN
        })
    );
    assert_eq!(state, before);
}

#[test]
fn refused_steps_change_nothing_with_a_level() {
    let (params, level) = (params(), screw_level());
    let mut feedforward = Compensator::new(params, DT, Mode::Feedforward)
        .unwrap()
        .with_level(level);
    feedforward.set_position(f64::MAX).unwrap();
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
        .unwrap()
        .with_level(level);
    observer.step(0.001).unwrap();
    let before = observer;
    assert!(observer.step(f64::NAN).is_err());
    assert_eq!(observer, before);
}
