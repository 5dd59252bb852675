//! The step's formulas of docs/model.md#discrete-step, recomputed from the states before and
//! after every step of random runs:
//!
//! - both schemes output Fₖ = Fh(z⁺) + sigma1·(z⁺ − z)/dt + σ2(vₖ)·vₖ, with Fh(z⁺) the trial from
//!   the memory at step start and σ2(v) = `sigma2_neg` for v < 0, `sigma2` otherwise;
//! - the explicit scheme moves z⁺ = z + dt·f(z, vₖ), f(z, v) = v − |v|·sgn(Fh)·|Fh/g(v)|ⁿ, with
//!   g(v) from the DESIGN formula (not the crate's `Stribeck::g`).
//!
//! (That the implicit z⁺ solves z⁺ = z + dt·f(z⁺, vₖ) is `implicit_solver.rs`.)

mod common;

use common::{dt, leuven, scheme, stribeck_level, velocities};
use gms_core::{Error, Hysteresis, LeuvenParams, Scheme};
use proptest::prelude::*;

fn formulas_hold<const N: usize>(
    params: &LeuvenParams<N>,
    velocities: &[f64],
    dt: f64,
    scheme: Scheme,
) -> Result<(), TestCaseError> {
    let bank = params.hysteresis();
    let mut state = params.relaxed_state();
    for (k, &v) in velocities.iter().enumerate() {
        let before = state;
        let force = match params.step(&mut state, v, dt, scheme) {
            Ok(force) => force,
            Err(Error::Diverged { .. }) => break,
            Err(other) => return Err(TestCaseError::fail(format!("step {k}: {other}"))),
        };

        let hysteresis = bank.trial(&before.memory, state.z).force;
        let micro_viscous = params.sigma1() * (state.z - before.z) / dt;
        let sigma2 = if v < 0.0 {
            params.sigma2_neg()
        } else {
            params.sigma2()
        };
        let viscous = sigma2 * v;
        let expected = hysteresis + micro_viscous + viscous;
        // Three roundings of terms that may partly cancel.
        let rounding =
            4.0 * f64::EPSILON * (hysteresis.abs() + micro_viscous.abs() + viscous.abs());
        prop_assert!(
            (force - expected).abs() <= rounding,
            "step {}: F = {}, Fh + sigma1·Δz/dt + σ2(v)·v = {} + {} + {}",
            k,
            force,
            hysteresis,
            micro_viscous,
            viscous
        );

        if scheme == Scheme::Explicit {
            let u =
                bank.trial(&before.memory, before.z).force / stribeck_level(params.stribeck(), v);
            let rate = v - v.abs() * u.abs().powf(params.n()).copysign(u);
            let z_next = before.z + dt * rate;
            // pow and exp of two libms may differ in the last bits; the increment is what counts.
            let tolerance = 1e-12 * dt * v.abs() * (1.0 + u.abs().powf(params.n()))
                + 2.0 * f64::EPSILON * before.z.abs();
            prop_assert!(
                (state.z - z_next).abs() <= tolerance,
                "step {}: explicit z⁺ = {}, z + dt·f(z, v) = {}",
                k,
                state.z,
                z_next
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(128))]

    #[test]
    fn step_formulas_n1(params in leuven::<1>(), v in velocities(), dt in dt(), scheme in scheme()) {
        formulas_hold(&params, &v, dt, scheme)?;
    }

    #[test]
    fn step_formulas_n4(params in leuven::<4>(), v in velocities(), dt in dt(), scheme in scheme()) {
        formulas_hold(&params, &v, dt, scheme)?;
    }

    #[test]
    fn step_formulas_n10(params in leuven::<10>(), v in velocities(), dt in dt(), scheme in scheme()) {
        formulas_hold(&params, &v, dt, scheme)?;
    }
}
