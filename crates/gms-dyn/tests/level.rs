//! The position-dependent level through the run-time layer: the bank's block run and the boxed
//! compensator give gms-core's forces, and a level's refusals are parameter errors.

use gms_core::{Field, Mode, Scheme};
use gms_dyn::{
    Compensator, Error, ErrorClass, FrictionBank, Input, Level, RawElements, RawParams, RippleTerms,
};

const DT: f64 = 1e-3;

fn set() -> gms_dyn::ParameterSet {
    let (w, delta) = ([1.0; 3], [1e-6, 2e-6, 4e-6]);
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
        sigma0: None,
        elements: Some(RawElements {
            w: &w,
            delta: &delta,
        }),
    }
    .validate()
    .expect("valid parameters")
}

fn level() -> Level {
    Level::new(
        0.0,
        0.01,
        [0.05, -0.02],
        &[RippleTerms {
            period: 0.004,
            cos: &[0.03, 0.01],
            sin: &[0.0, 0.02],
        }],
    )
    .expect("a valid level")
}

fn positions(channel: usize) -> Vec<f64> {
    (0..400)
        .map(|k| 0.004 * (0.02 * f64::from(k) + channel as f64).sin())
        .collect()
}

#[test]
fn bank_run_with_a_level_is_the_compensator_per_channel() {
    let (set, level) = (set(), level());
    let x: Vec<f64> = positions(0).into_iter().chain(positions(1)).collect();
    let mut bank = FrictionBank::new(&set, 2, Scheme::Implicit).expect("a bank");
    let mut out = vec![0.0; x.len()];
    bank.run_position_level(&x, DT, &level, &mut out)
        .expect("a run");
    for channel in 0..2 {
        let mut observer =
            Compensator::with_level(&set, DT, Mode::Observer, &level).expect("a compensator");
        for (k, &xk) in positions(channel).iter().enumerate() {
            let force = observer.step(xk).expect("a step");
            assert_eq!(force.to_bits(), out[channel * 400 + k].to_bits());
        }
    }
    // The flat level is the plain run.
    let mut plain = FrictionBank::new(&set, 2, Scheme::Implicit).expect("a bank");
    let mut flat = FrictionBank::new(&set, 2, Scheme::Implicit).expect("a bank");
    let (mut a, mut b) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    plain.run(&x, DT, Input::Position, &mut a).expect("a run");
    flat.run_position_level(&x, DT, &Level::none(), &mut b)
        .expect("a run");
    assert_eq!(a, b);
    assert_ne!(a, out);
}

#[test]
fn compensator_keeps_its_level_and_position() {
    let (set, level) = (set(), level());
    let mut compensator =
        Compensator::with_level(&set, DT, Mode::Feedforward, &level).expect("a compensator");
    assert_eq!(compensator.level(), level);
    compensator.set_position(0.003).expect("finite");
    compensator.step(2e-3).expect("a step");
    assert_eq!(compensator.position(), 0.003 + 2e-3 * DT);
    assert_eq!(
        compensator.set_position(f64::INFINITY),
        Err(gms_core::Error::NotFiniteValue {
            field: Field::x,
            value: f64::INFINITY
        })
    );
    assert_eq!(compensator.position(), 0.003 + 2e-3 * DT);
    assert_eq!(
        Compensator::new(&set, DT, Mode::Observer)
            .expect("a compensator")
            .level(),
        Level::none()
    );
}

#[test]
fn level_refusals_are_parameter_errors() {
    let refused = Level::new(0.0, 1.0, [0.6, 0.5], &[]).expect_err("too deep");
    assert_eq!(Error::from(refused).class(), ErrorClass::Parameter);
    let refused = Level::new(0.0, -1.0, [0.0; 2], &[]).expect_err("negative half stroke");
    assert_eq!(Error::from(refused).class(), ErrorClass::Parameter);
}
