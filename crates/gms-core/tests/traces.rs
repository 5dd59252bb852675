//! The analysis block calls: a position run that also records the deflection z
//! (`Params::simulate_position_deflection`) and Maxwell-slip responses along a whole path
//! (`SlipRegressor::responses`). Each must equal the per-sample calls it stands for, bit for
//! bit, and be all or nothing.

mod common;

use common::{config, dt, leuven, scheme, velocities};
use gms_core::{Error, Field, MaxwellSlip, Params, Scheme, SlipRegressor, Stribeck};
use proptest::prelude::*;

/// Positions that visit presliding and sliding: the running sum of a velocity sequence.
fn positions(v: &[f64], dt: f64) -> Vec<f64> {
    v.iter()
        .scan(0.0, |x, v| {
            *x += v * dt;
            Some(*x)
        })
        .collect()
}

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn deflection_run_equals_stepping(params in leuven::<4>(), v in velocities(), dt in dt(), scheme in scheme()) {
        let x = positions(&v, dt);
        let mut stepped = params.relaxed_state();
        let mut expected = Vec::with_capacity(x.len());
        let mut expected_z = Vec::with_capacity(x.len());
        for &position in &x {
            match params.step_position(&mut stepped, position, dt, scheme) {
                Ok(force) => {
                    expected.push(force);
                    expected_z.push(stepped.z);
                }
                Err(_) => return Ok(()), // a diverging explicit run is the other tests' subject
            }
        }
        let mut state = params.relaxed_state();
        let (mut force, mut z) = (vec![0.0; x.len()], vec![0.0; x.len()]);
        params.simulate_position_deflection(&mut state, &x, dt, scheme, &mut force, &mut z).unwrap();
        prop_assert_eq!(force.iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
                        expected.iter().map(|f| f.to_bits()).collect::<Vec<_>>());
        prop_assert_eq!(z.iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
                        expected_z.iter().map(|f| f.to_bits()).collect::<Vec<_>>());
        prop_assert_eq!(state, stepped);
    }

    #[test]
    fn responses_equal_advancing(v in velocities(), dt in dt(), delta in prop::array::uniform3(1e-7..1e-4f64)) {
        let x = positions(&v, dt);
        let mut stepped = SlipRegressor::new(delta).unwrap();
        let expected: Vec<f64> = x.iter().flat_map(|&position| stepped.advance(position)).collect();
        let mut block = SlipRegressor::new(delta).unwrap();
        let mut out = vec![0.0; 3 * x.len()];
        block.responses(&x, &mut out).unwrap();
        prop_assert_eq!(out, expected);
        prop_assert_eq!(block, stepped);
    }
}

#[test]
fn deflection_run_is_all_or_nothing() {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let elements = MaxwellSlip::new([0.8, 0.8], [1e-6, 2e-6]).unwrap();
    let params = Params::new(stribeck, 2.0, 0.0, 0.0, elements).unwrap();
    let mut state = params.relaxed_state();
    let (mut force, mut z) = ([0.0; 3], [0.0; 3]);
    params
        .simulate_position_deflection(
            &mut state,
            &[0.0, 1e-6, 2e-6],
            1e-3,
            Scheme::default(),
            &mut force,
            &mut z,
        )
        .unwrap();
    let before = state;
    let error = params
        .simulate_position_deflection(
            &mut state,
            &[3e-6, f64::NAN, 4e-6],
            1e-3,
            Scheme::default(),
            &mut force,
            &mut z,
        )
        .unwrap_err();
    assert_eq!(
        error,
        Error::NotFinite {
            field: Field::x,
            index: 1,
            value: f64::NAN
        }
    );
    assert_eq!(state, before);
    let error = params
        .simulate_position_deflection(
            &mut state,
            &[3e-6, 4e-6],
            1e-3,
            Scheme::default(),
            &mut [0.0; 2],
            &mut z,
        )
        .unwrap_err();
    assert_eq!(
        error,
        Error::LengthMismatch {
            expected: 2,
            got: 3
        }
    );
    assert_eq!(state, before);
}

#[test]
fn responses_are_all_or_nothing() {
    let mut regressor = SlipRegressor::new([1e-6, 2e-6]).unwrap();
    let mut out = [0.0; 4];
    regressor.responses(&[0.0, 1.5e-6], &mut out).unwrap();
    assert_eq!(out, [0.0, 0.0, 1.0, 0.75]);
    let before = regressor;
    assert_eq!(
        regressor.responses(&[1e-6, f64::INFINITY], &mut out),
        Err(Error::NotFinite {
            field: Field::x,
            index: 1,
            value: f64::INFINITY
        })
    );
    assert_eq!(regressor, before);
    assert_eq!(
        regressor.responses(&[1e-6], &mut out),
        Err(Error::LengthMismatch {
            expected: 2,
            got: 4
        })
    );
    assert_eq!(regressor, before);
}
