//! A channel state written from outside is checked by `Params::check_state`: every state the
//! model reaches (read back as it is) passes, and a state with an element outside its window
//! (|z − ζᵢ| > Δᵢ), a non-finite z or a non-finite previous position is refused, naming it.
//! Before, such a state was accepted, and the next step at v = 0 moved the elements and returned
//! a force that did not match the stored state.

mod common;

use common::{config, dt, leuven, reach, scheme, velocities};
use gms_core::{Error, Field, LeuvenParams, Linear, MaxwellSlip, Params, Scheme, Stribeck};
use proptest::prelude::*;

fn params() -> LeuvenParams<3> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let elements = MaxwellSlip::new([1.0, 1.0, 1.0], [1e-6, 2e-6, 4e-6]).expect("valid bank");
    Params::new(stribeck, 2.0, 30.0, 0.4, elements).expect("valid parameters")
}

proptest! {
    #![proptest_config(config(64))]

    /// Every reachable state passes the check as read, whatever its magnitude.
    #[test]
    fn reachable_states_pass(
        params in leuven::<4>(),
        v in velocities(),
        dt in dt(),
        scheme in scheme(),
        offset in prop_oneof![Just(0.0), Just(1.0), Just(-1e3)],
    ) {
        let mut state = params.relaxed_state();
        // A position far from 0 shifts nothing but where the state lives.
        state.z += offset;
        state.memory = state.memory.map(|zeta| zeta + offset);
        reach(&params, &mut state, &v, dt, scheme);
        prop_assert_eq!(params.check_state(&state), Ok(()));
    }
}

#[test]
fn states_outside_the_windows_are_refused() {
    let params = params();
    let mut state = params.relaxed_state();
    assert_eq!(params.check_state(&state), Ok(()));
    // Element 1 stretched by 3 µm, beyond its Δ = 2 µm.
    state.memory = [0.0, -3e-6, 0.0];
    let refused = params.check_state(&state);
    assert_eq!(
        refused,
        Err(Error::StateOutsideWindow {
            index: 1,
            deflection: 3e-6,
            limit: 2e-6
        })
    );
    assert_eq!(
        refused.unwrap_err().to_string(),
        "`zeta[1]` must be within `Delta[1]` = 2e-6 of z, i.e. |z - zeta[1]| <= 2e-6, got z - \
         zeta[1] = 3e-6"
    );
    // What the state meant: stepping it at v = 0 would move element 1 and change the force.
    let mut moved = state;
    let force = params
        .step(&mut moved, 0.0, 1e-3, Scheme::Implicit)
        .expect("a step");
    assert_ne!(moved.memory, state.memory);
    assert!((force - (1.0 + 0.0 + 0.0)).abs() < 1e-12, "{force}");
    // On the edge of a window, and a few ulps beyond (as a read-back slip gives), is fine.
    state.memory = [0.0, -2e-6, 2e-6];
    assert_eq!(params.check_state(&state), Ok(()));
    state.z = 1.0;
    state.memory = [1.0 - 1e-6, 1.0, 1.0 + 4e-6];
    assert_eq!(params.check_state(&state), Ok(()));
    state.memory[0] = (1.0 - 1e-6_f64).next_down().next_down();
    assert_eq!(params.check_state(&state), Ok(()));
    state.memory[0] = 1.0 - 1.01e-6;
    assert!(params.check_state(&state).is_err());
}

#[test]
fn non_finite_states_are_refused() {
    let params = params();
    let mut state = params.relaxed_state();
    state.memory[2] = f64::NAN;
    assert!(matches!(
        params.check_state(&state),
        Err(Error::StateOutsideWindow { index: 2, .. })
    ));
    let mut state = params.relaxed_state();
    state.z = f64::INFINITY;
    assert_eq!(
        params.check_state(&state),
        Err(Error::NotFiniteValue {
            field: Field::z,
            value: f64::INFINITY
        })
    );
    let mut state = params.relaxed_state();
    state.last_position = Some(f64::NAN);
    assert_eq!(
        params.check_state(&state),
        Err(Error::NotFiniteValue {
            field: Field::x,
            value: f64::NAN
        })
    );
    // A linear spring has no windows: any finite z is a state.
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let lugre = Params::new(stribeck, 1.0, 0.0, 0.0, Linear::new(1e5).expect("valid"))
        .expect("valid parameters");
    let mut state = lugre.relaxed_state();
    state.z = 1e3;
    assert_eq!(lugre.check_state(&state), Ok(()));
}

/// A NaN written into the memory, skipping `check_state`, is refused by the step with the state
/// untouched, for every exponent and scheme. With the in-place commit, only a non-finite z⁺ stops
/// such a memory before it is written: the implicit solver must not bisect a NaN residual to a
/// finite point (it used to, for exponents solved by Newton's iteration).
#[test]
fn a_nan_in_the_memory_is_refused_and_nothing_is_written() {
    for n in [1.0, 2.0, 1.5, 3.0, 0.7] {
        let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
        let elements = MaxwellSlip::new([1.0, 1.0, 1.0], [1e-6, 2e-6, 4e-6]).expect("valid bank");
        let params = Params::new(stribeck, n, 30.0, 0.4, elements).expect("valid parameters");
        for scheme in [Scheme::Implicit, Scheme::Explicit] {
            for v in [1e-3, -2e-4, 0.0] {
                let mut state = params.relaxed_state();
                state.memory[1] = f64::NAN;
                let before = state;
                let result = params.step(&mut state, v, 1e-3, scheme);
                assert_eq!(
                    result,
                    Err(Error::Diverged { index: 0 }),
                    "n = {n}, {scheme:?}, v = {v}"
                );
                assert_eq!(state.z.to_bits(), before.z.to_bits());
                assert!(state.memory[1].is_nan());
                assert_eq!(state.memory[0].to_bits(), before.memory[0].to_bits());
                assert_eq!(state.memory[2].to_bits(), before.memory[2].to_bits());
            }
        }
    }
}
