//! At v = 0 nothing moves: from any reachable state (reached by random velocities with either
//! scheme), feeding exact zeros (+0.0 and −0.0) with either scheme leaves z, the memory and the
//! force bitwise identical step after step, and the force is the hysteresis force Fh(z): the
//! micro-viscous and viscous terms vanish with the motion.
//!
//! This is what writing eq. (4) as dz/dt = v − |v|·sgn(Fh)·|Fh/g(v)|ⁿ buys over the paper's
//! v·(1 − sgn(Fh/s)·|Fh/s(v)|ⁿ), which is 0/0 at v = 0: no NaN at rest, and no creep.

mod common;

use common::{dt, leuven, log_uniform, reach, scheme, stribeck, velocities};
use gms_core::{Hysteresis, LeuvenParams, Linear, Params, Scheme, State};
use proptest::prelude::*;

/// The bits of a Maxwell-slip state, so that −0.0 ≠ +0.0 and every ulp counts.
fn bits<const N: usize>(state: &State<[f64; N]>) -> (u64, [u64; N], Option<u64>) {
    (
        state.z.to_bits(),
        state.memory.map(f64::to_bits),
        state.last_position.map(f64::to_bits),
    )
}

/// Exact zeros of either sign.
fn zeros() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(prop_oneof![Just(0.0), Just(-0.0)], 1..200)
}

/// Reaches a state with `history` (velocities, dt, scheme), then feeds `zeros` the same way.
fn nothing_moves<const N: usize>(
    params: &LeuvenParams<N>,
    (history, history_dt, history_scheme): (&[f64], f64, Scheme),
    (zeros, dt, scheme): (&[f64], f64, Scheme),
) -> Result<(), TestCaseError> {
    let mut state = params.relaxed_state();
    reach(params, &mut state, history, history_dt, history_scheme);
    let at_rest = bits(&state);
    let hysteresis_force = params.hysteresis().trial(&state.memory, state.z).force;

    let mut first_force = None;
    for (k, &v) in zeros.iter().enumerate() {
        let force = params
            .step(&mut state, v, dt, scheme)
            .map_err(|error| TestCaseError::fail(format!("zero input {k}: {error}")))?;
        prop_assert_eq!(bits(&state), at_rest, "the state moved at zero input {}", k);
        // Fh(z) + sigma1·0/dt + sigma2·(±0): equal to Fh(z) as a number (a −0.0 may become +0.0).
        prop_assert_eq!(force, hysteresis_force, "zero input {}", k);
        let first = *first_force.get_or_insert(force);
        prop_assert_eq!(
            force.to_bits(),
            first.to_bits(),
            "the force changed at zero input {}",
            k
        );
    }

    // The block call does the same.
    let mut out = vec![f64::NAN; zeros.len()];
    params
        .simulate(&mut state, zeros, dt, scheme, &mut out)
        .map_err(|error| TestCaseError::fail(error.to_string()))?;
    prop_assert_eq!(bits(&state), at_rest);
    prop_assert!(out.iter().all(|&force| force == hysteresis_force));
    Ok(())
}

proptest! {
    #![proptest_config(common::config(96))]

    #[test]
    fn at_rest_n1(
        params in leuven::<1>(),
        (history, history_dt, history_scheme) in (velocities(), dt(), scheme()),
        (zeros, dt, scheme) in (zeros(), dt(), scheme()),
    ) {
        nothing_moves(&params, (&history, history_dt, history_scheme), (&zeros, dt, scheme))?;
    }

    #[test]
    fn at_rest_n4(
        params in leuven::<4>(),
        (history, history_dt, history_scheme) in (velocities(), dt(), scheme()),
        (zeros, dt, scheme) in (zeros(), dt(), scheme()),
    ) {
        nothing_moves(&params, (&history, history_dt, history_scheme), (&zeros, dt, scheme))?;
    }

    #[test]
    fn at_rest_n10(
        params in leuven::<10>(),
        (history, history_dt, history_scheme) in (velocities(), dt(), scheme()),
        (zeros, dt, scheme) in (zeros(), dt(), scheme()),
    ) {
        nothing_moves(&params, (&history, history_dt, history_scheme), (&zeros, dt, scheme))?;
    }

    #[test]
    fn at_rest_n32(
        params in leuven::<32>(),
        (history, history_dt, history_scheme) in (velocities(), dt(), scheme()),
        (zeros, dt, scheme) in (zeros(), dt(), scheme()),
    ) {
        nothing_moves(&params, (&history, history_dt, history_scheme), (&zeros, dt, scheme))?;
    }

    /// LuGre (linear hysteresis) rests the same way: z stays, F = sigma0·z.
    #[test]
    fn at_rest_lugre(
        stribeck in stribeck(),
        sigma0 in log_uniform(1e3, 1e8),
        history in velocities(),
        (history_dt, zeros, dt, scheme) in (dt(), zeros(), dt(), scheme()),
    ) {
        let spring = Linear::new(sigma0).expect("valid stiffness");
        let params = Params::new(stribeck, 1.0, 10.0, 0.5, spring).expect("valid parameters");
        let mut state = params.relaxed_state();
        reach(&params, &mut state, &history, history_dt, Scheme::Implicit);
        let z = state.z;
        for &v in &zeros {
            let force = params.step(&mut state, v, dt, scheme).expect("finite input");
            prop_assert_eq!(state.z.to_bits(), z.to_bits());
            prop_assert_eq!(force, sigma0 * z);
        }
    }
}
