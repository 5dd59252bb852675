//! The position-dependent terms through the run-time layer: the bank's block runs and the boxed
//! compensator give gms-core's forces, the viscous coefficient of negative velocity reaches the
//! model, and the refusals are sorted into the right kind.

use gms_core::{Field, Mode, Scheme};
use gms_dyn::{
    Compensator, Error, ErrorClass, FrictionBank, Input, Level, PositionForce, RawElements,
    RawParams, RippleTerms, Terms,
};

const DT: f64 = 1e-3;

fn raw<'a>(w: &'a [f64], delta: &'a [f64], sigma2_neg: Option<f64>) -> RawParams<'a> {
    RawParams {
        fc: 1.0,
        fs: 1.5,
        vs: 1e-3,
        delta: 2.0,
        n: 2.0,
        sigma1: 30.0,
        sigma2: 0.4,
        fc_neg: 1.0,
        fs_neg: 1.5,
        sigma2_neg,
        sigma0: None,
        elements: Some(RawElements { w, delta }),
    }
}

/// σ2 = 0.4, and 0.9 for v < 0.
fn set() -> gms_dyn::ParameterSet {
    raw(&[1.0; 3], &[1e-6, 2e-6, 4e-6], Some(0.9))
        .validate()
        .expect("valid parameters")
}

const RIPPLE: RippleTerms<'static> = RippleTerms {
    period: 0.004,
    cos: &[0.03, 0.01],
    sin: &[0.0, 0.02],
};

fn level() -> Level {
    Level::new(0.0, 0.01, [0.05, -0.02], &[RIPPLE]).expect("a valid level")
}

fn cogging() -> PositionForce {
    PositionForce::new(0.002, 0.01, [0.3, 0.1], &[RIPPLE]).expect("a valid position force")
}

fn positions(channel: usize) -> Vec<f64> {
    (0..400)
        .map(|k| 0.004 * (0.02 * f64::from(k) + channel as f64).sin())
        .collect()
}

fn observer() -> Terms {
    Terms {
        start: None,
        level: level(),
        position_force: cogging(),
    }
}

/// Positions with the terms: each channel is the observer compensator, bit for bit, over more
/// channels than one group of lanes (with the `batch` feature, gms-batch's lanes; without it,
/// gms-core's block calls); a non-finite position is named with its channel in both builds.
#[test]
fn bank_run_with_the_terms_is_the_compensator_per_channel() {
    let set = set();
    let channels = 11;
    let x: Vec<f64> = (0..channels).flat_map(positions).collect();
    let mut bank = FrictionBank::new(&set, channels, Scheme::Implicit).expect("a bank");
    let mut out = vec![0.0; x.len()];
    bank.run_position_level(&x, DT, &level(), &cogging(), &mut out)
        .expect("a run");
    for channel in 0..channels {
        let mut observer =
            Compensator::with_terms(&set, DT, Mode::Observer, &observer()).expect("a compensator");
        for (k, &xk) in positions(channel).iter().enumerate() {
            let force = observer.step(xk).expect("a step");
            assert_eq!(force.to_bits(), out[channel * 400 + k].to_bits());
        }
    }
    let mut bad = x.clone();
    bad[2 * 400 + 5] = f64::INFINITY;
    bad[9 * 400 + 1] = f64::NAN;
    let refused = bank
        .run_position_level(&bad, DT, &level(), &cogging(), &mut out)
        .expect_err("a non-finite position");
    assert_eq!(refused.class(), ErrorClass::Input);
    assert_eq!(
        refused.to_string(),
        "`x` must be finite, got inf at channel 2, sample 5"
    );
    // No terms is the plain run.
    let mut plain = FrictionBank::new(&set, channels, Scheme::Implicit).expect("a bank");
    let mut flat = FrictionBank::new(&set, channels, Scheme::Implicit).expect("a bank");
    let (mut a, mut b) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    plain.run(&x, DT, Input::Position, &mut a).expect("a run");
    flat.run_position_level(&x, DT, &Level::none(), &PositionForce::none(), &mut b)
        .expect("a run");
    assert_eq!(a, b);
    assert_ne!(a, out);
}

/// Velocity input with positions: each channel is the feedforward compensator stepped along
/// the trajectory, bit for bit, over more channels than one group of lanes.
#[test]
fn bank_run_of_velocities_at_positions_is_the_trajectory_step() {
    let set = set();
    let channels = 11;
    let x: Vec<f64> = (0..channels).flat_map(positions).collect();
    let v: Vec<f64> = (0..x.len())
        .map(|k| 6e-3 * (0.031 * k as f64).cos())
        .collect();
    let mut bank = FrictionBank::new(&set, channels, Scheme::Implicit).expect("a bank");
    let mut out = vec![0.0; x.len()];
    bank.run_level(&v, &x, DT, &level(), &cogging(), &mut out)
        .expect("a run");
    for channel in 0..channels {
        let row = channel * 400..(channel + 1) * 400;
        let terms = Terms {
            start: Some(x[row.start]),
            ..observer()
        };
        let mut compensator =
            Compensator::with_terms(&set, DT, Mode::Feedforward, &terms).expect("a compensator");
        for k in row {
            let force = compensator.step_trajectory(v[k], x[k]).expect("a step");
            assert_eq!(force.to_bits(), out[k].to_bits(), "sample {k}");
        }
    }
    // Refusals: positions of another shape, and a non-finite position named with its channel.
    assert_eq!(
        bank.run_level(&v, &x[1..], DT, &level(), &cogging(), &mut out),
        Err(Error::Core(gms_core::Error::InputLengthMismatch {
            field: Field::x,
            expected: v.len(),
            got: v.len() - 1
        }))
    );
    let mut bad = x.clone();
    bad[3 * 400 + 17] = f64::NAN;
    let refused = bank
        .run_level(&v, &bad, DT, &level(), &cogging(), &mut out)
        .expect_err("a NaN position");
    assert_eq!(refused.class(), ErrorClass::Input);
    assert_eq!(
        refused.to_string(),
        "`x` must be finite, got nan at channel 3, sample 17"
    );
}

#[test]
fn compensator_keeps_its_terms_and_position() {
    let set = set();
    let terms = Terms {
        start: Some(0.003),
        ..observer()
    };
    let mut compensator =
        Compensator::with_terms(&set, DT, Mode::Feedforward, &terms).expect("a compensator");
    assert_eq!(compensator.level(), level());
    assert_eq!(compensator.position_force(), cogging());
    compensator.step(2e-3).expect("a step");
    assert_eq!(compensator.position(), Some(0.003 + 2e-3 * DT));
    assert_eq!(
        compensator.set_position(f64::INFINITY),
        Err(gms_core::Error::NotFiniteValue {
            field: Field::x,
            value: f64::INFINITY
        })
    );
    assert_eq!(compensator.position(), Some(0.003 + 2e-3 * DT));
    compensator.step_trajectory(1e-3, -0.001).expect("a step");
    assert_eq!(compensator.position(), Some(-0.001));
    let plain = Compensator::new(&set, DT, Mode::Observer).expect("a compensator");
    assert_eq!(plain.level(), Level::none());
    assert_eq!(plain.position_force(), PositionForce::none());
    assert_eq!(plain.position(), None);
}

/// A feedforward compensator with a term and no start position is refused, naming `x`: the
/// terms would otherwise be evaluated from x = 0, out of phase with the machine.
#[test]
fn feedforward_terms_need_the_start_position() {
    let set = set();
    for terms in [
        observer(),
        Terms {
            position_force: PositionForce::none(),
            ..observer()
        },
        Terms {
            level: Level::none(),
            ..observer()
        },
    ] {
        let refused = Compensator::with_terms(&set, DT, Mode::Feedforward, &terms)
            .map(|_| ())
            .expect_err("no start position");
        assert_eq!(
            refused,
            Error::Core(gms_core::Error::Missing { field: Field::x })
        );
        assert_eq!(refused.class(), ErrorClass::Input);
    }
    let mut bare = Compensator::new(&set, DT, Mode::Feedforward).expect("a compensator");
    assert_eq!(
        bare.set_level(&level()),
        Err(gms_core::Error::Missing { field: Field::x })
    );
    assert_eq!(
        bare.set_position_force(&cogging()),
        Err(gms_core::Error::Missing { field: Field::x })
    );
    assert_eq!(bare.level(), Level::none());
    bare.set_position(0.0).expect("finite");
    bare.set_level(&level()).expect("placed");
    bare.set_position_force(&cogging()).expect("placed");
}

#[test]
fn the_viscous_coefficient_of_negative_velocity_reaches_the_model() {
    let (w, delta) = ([1.0; 3], [1e-6, 2e-6, 4e-6]);
    let refused = raw(&w, &delta, Some(-0.1))
        .validate()
        .expect_err("negative");
    assert_eq!(
        refused,
        Error::Core(gms_core::Error::Negative {
            field: Field::sigma2_neg,
            value: -0.1
        })
    );
    assert_eq!(refused.class(), ErrorClass::Parameter);
    // Given as sigma2, it is the symmetric model; another value changes only v < 0.
    let v: Vec<f64> = (0..300)
        .map(|k| 5e-3 * (0.05 * f64::from(k)).sin())
        .collect();
    let run = |sigma2_neg| {
        let set = raw(&w, &delta, sigma2_neg).validate().expect("valid");
        let mut bank = FrictionBank::new(&set, 1, Scheme::Implicit).expect("a bank");
        let mut out = vec![0.0; v.len()];
        bank.run(&v, DT, Input::Velocity, &mut out).expect("a run");
        out
    };
    assert_eq!(run(None), run(Some(0.4)));
    let (symmetric, asymmetric) = (run(None), run(Some(0.9)));
    for ((&v, a), b) in v.iter().zip(symmetric).zip(asymmetric) {
        let expected = if v < 0.0 { (0.9 - 0.4) * v } else { 0.0 };
        assert!((b - a - expected).abs() <= 1e-12, "{v}: {a} {b}");
    }
}

#[test]
fn term_refusals_are_parameter_errors() {
    let refused = Level::new(0.0, 1.0, [0.6, 0.5], &[]).expect_err("too deep");
    assert_eq!(Error::from(refused).class(), ErrorClass::Parameter);
    let refused = Level::new(0.0, -1.0, [0.0; 2], &[]).expect_err("negative half stroke");
    assert_eq!(Error::from(refused).class(), ErrorClass::Parameter);
    let fine = RippleTerms {
        period: 1e-12,
        cos: &[0.1],
        sin: &[0.0],
    };
    let refused = PositionForce::new(0.0, 1.0, [0.0; 2], &[fine]).expect_err("unresolved");
    assert!(matches!(
        refused,
        gms_core::Error::PhaseUnresolved {
            field: Field::period,
            ..
        }
    ));
    assert_eq!(Error::from(refused).class(), ErrorClass::Parameter);
}
