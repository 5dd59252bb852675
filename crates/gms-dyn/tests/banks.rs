//! Channel banks: a written state is checked before any channel is written (an element outside
//! its window used to be accepted, and the next step at v = 0 moved it); a run of zero samples
//! touches and copies nothing but still checks dt.

use gms_core::{Field, Scheme};
use gms_dyn::{
    Error, ErrorClass, FrictionBank, Input, MassBank, Mechanics, RawElements, RawParams,
};

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
        sigma2_neg: None,
        sigma0: None,
        elements: Some(RawElements {
            w: &w,
            delta: &delta,
        }),
    }
    .validate()
    .expect("valid parameters")
}

#[test]
fn written_friction_states_are_checked_all_or_nothing() {
    let mut bank = FrictionBank::new(&set(), 2, Scheme::Implicit).expect("a bank");
    let mut out = [0.0; 20];
    let v: Vec<f64> = (0..20).map(|k| 1e-3 * f64::from(k).sin()).collect();
    bank.run(&v, 1e-3, Input::Velocity, &mut out)
        .expect("a run");
    // What is read back goes back in.
    let (mut z, mut zeta, mut last, mut has) = ([0.0; 2], [0.0; 6], [0.0; 2], [false; 2]);
    bank.read_state(&mut z, &mut zeta, &mut last, &mut has);
    bank.write_state(&z, &zeta, &last, &has)
        .expect("a read state");
    // Channel 1, element 2 stretched beyond its window: refused, and channel 0 not written.
    let mut bad = zeta;
    bad[0] = z[0] + 0.5e-6;
    bad[5] = z[1] - 5e-6;
    let refused = bank.write_state(&z, &bad, &last, &has).unwrap_err();
    assert!(
        matches!(
            refused,
            Error::State {
                channel: 1,
                error: gms_core::Error::StateOutsideWindow { index: 2, .. }
            }
        ),
        "{refused:?}"
    );
    assert_eq!(refused.class(), ErrorClass::Input);
    let message = refused.to_string();
    assert!(
        message.starts_with("state of channel 1: `zeta[2]` must be within `Delta[2]` = 4e-6"),
        "{message}"
    );
    let mut now = [0.0; 6];
    bank.read_state(&mut [0.0; 2], &mut now, &mut [0.0; 2], &mut [false; 2]);
    assert_eq!(now, zeta);
    // A non-finite z is an input error naming `z`.
    let refused = bank
        .write_state(&[f64::NAN, 0.0], &[0.0; 6], &last, &has)
        .unwrap_err();
    assert_eq!(
        refused,
        Error::State {
            channel: 0,
            error: gms_core::Error::NotFiniteValue {
                field: Field::z,
                value: f64::NAN
            }
        }
    );
    assert_eq!(refused.class(), ErrorClass::Input);
}

#[test]
fn written_mass_states_are_checked() {
    let mechanics = Mechanics {
        mass: 1.0,
        stiffness: 0.0,
        drive_speed: 0.0,
    };
    let mut bank = MassBank::new(&set(), mechanics, 1, Scheme::Implicit).expect("a bank");
    let refused = bank
        .write_state(&[0.0], &[0.0], &[0.0], &[0.0], &[0.0, 3e-6, 0.0])
        .unwrap_err();
    assert!(
        matches!(
            refused,
            Error::State {
                channel: 0,
                error: gms_core::Error::StateOutsideWindow { index: 1, .. }
            }
        ),
        "{refused:?}"
    );
    bank.write_state(&[1.0], &[0.0], &[0.0], &[0.0], &[0.0, 2e-6, -4e-6])
        .expect("on the edges of the windows");
}

#[test]
fn empty_runs_check_dt_and_touch_nothing() {
    let mut bank = FrictionBank::new(&set(), 1000, Scheme::Implicit).expect("a bank");
    bank.run(&[], 1e-3, Input::Velocity, &mut [])
        .expect("nothing to run");
    let refused = bank.run(&[], -1.0, Input::Position, &mut []).unwrap_err();
    assert_eq!(
        refused,
        Error::Core(gms_core::Error::NotPositive {
            field: Field::dt,
            value: -1.0
        })
    );
}

/// The state of every channel, to compare before and after a run.
fn friction_state(bank: &FrictionBank) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<bool>) {
    let (b, n) = (bank.channels(), bank.elements());
    let (mut z, mut memory, mut last, mut has_last) =
        (vec![0.0; b], vec![0.0; b * n], vec![0.0; b], vec![false; b]);
    bank.read_state(&mut z, &mut memory, &mut last, &mut has_last);
    (z, memory, last, has_last)
}

/// Many channels go through gms-batch's lanes (and the leftover ones through gms-core), or, without
/// the `batch` feature (as the C library builds gms-dyn), all through gms-core's block calls: the
/// forces are those of stepping each channel alone, and a rejected sample anywhere names its
/// channel and sample and leaves every channel as it was.
#[test]
fn batched_runs_match_single_steps_and_stay_all_or_nothing() {
    let (channels, samples) = (19, 300);
    let x: Vec<f64> = (0..channels * samples)
        .map(|k| {
            let (channel, t) = (k / samples, (k % samples) as f64);
            2e-5 * (0.05 * t + channel as f64).sin() * (1.0 + 0.1 * channel as f64)
        })
        .collect();
    for (scheme, kind) in [
        (Scheme::Implicit, Input::Position),
        (Scheme::Explicit, Input::Position),
        (Scheme::Implicit, Input::Velocity),
    ] {
        let mut bank = FrictionBank::new(&set(), channels, scheme).expect("a bank");
        let mut single = FrictionBank::new(&set(), channels, scheme).expect("a bank");
        let mut out = vec![0.0; x.len()];
        bank.run(&x, 1e-3, kind, &mut out).expect("finite input");
        for channel in 0..channels {
            for t in 0..samples {
                let k = channel * samples + t;
                let force = single.step(channel, x[k], 1e-3, kind).expect("a step");
                assert_eq!(force.to_bits(), out[k].to_bits(), "{scheme:?} {kind:?} {k}");
            }
        }
        assert_eq!(friction_state(&bank), friction_state(&single));

        for bad in [3 * samples + 17, 9 * samples, 18 * samples + 299] {
            let mut poisoned = x.clone();
            poisoned[bad] = f64::NAN;
            // A later channel, at an earlier sample: the first channel is the one named.
            if bad + samples < poisoned.len() {
                poisoned[bad + samples - 7] = f64::INFINITY;
            }
            let before = friction_state(&bank);
            let error = bank.run(&poisoned, 1e-3, kind, &mut out).unwrap_err();
            let field = if kind == Input::Position {
                Field::x
            } else {
                Field::v
            };
            assert_eq!(
                error,
                Error::Channel(gms_core::InChannel {
                    channel: bad / samples,
                    error: gms_core::Error::NotFinite {
                        field,
                        index: bad % samples,
                        value: f64::NAN,
                    },
                }),
                "{error}"
            );
            assert_eq!(friction_state(&bank), before);
        }
    }
}
