//! At a constant velocity v ≠ 0 the friction force settles on the Stribeck curve plus viscous
//! friction, F → s(v) + σ2(v)·v, to a relative 1e-9: in both directions, with asymmetric
//! levels and viscous coefficients (`sigma2_neg` for v < 0), for the implicit scheme and for
//! the explicit one where its step is stable.
//!
//! "Enough steps" is computed, not guessed. The element stiffnesses are drawn through the
//! dimensionless step ρᵢ = dt·|v|·kᵢ/g(v) (kᵢ = Wᵢ/Δᵢ), which bounds the rate at which the state
//! approaches its fixed point:
//!
//! - implicit: the distance to the fixed point shrinks at least by 1/(1 + min(1, n)·min ρᵢ) per
//!   step, whatever the stiffness (backward Euler never overshoots a monotone equation);
//! - explicit: by (1 − min(1, n)·min ρᵢ), as long as max(1, n)·Σρᵢ < 1 (then no step
//!   overshoots the fixed point, so the scheme is stable and monotone).
//!
//! The run lasts until that bound, applied to the largest possible initial error, is below
//! 1e-11 of the force; the assertion then checks the model, with 100× headroom.

mod common;

use common::{
    asymmetric_stribeck, coefficient, dt, exponent, log_uniform, saturation_forces, signed,
    stribeck_level,
};
use gms_core::{LeuvenParams, MaxwellSlip, Params, Scheme, Stribeck};
use proptest::array::uniform;
use proptest::prelude::*;

/// One constant-velocity run: parameters, input, step and how many steps the bound asks for.
#[derive(Clone, Debug)]
struct Case<const N: usize> {
    params: LeuvenParams<N>,
    v: f64,
    dt: f64,
    steps: usize,
}

/// The number of steps after which an error shrinking by `contraction` per step, starting from
/// the largest possible one, is below 1e-11·g(v).
fn steps_to_settle<const N: usize>(
    params: &LeuvenParams<N>,
    v: f64,
    dt: f64,
    contraction: f64,
) -> usize {
    let bank = params.hysteresis();
    let stiffness: f64 = bank
        .w()
        .iter()
        .zip(bank.delta())
        .map(|(w, delta)| w / delta)
        .sum();
    let reach = bank.delta().iter().fold(0.0f64, |a, &b| a.max(b));
    // The fixed point lies within the largest break deflection of the start, and the force error
    // is the hysteresis error plus the micro-viscous term sigma1·Δz/dt.
    let g = params.stribeck().g(v);
    let initial = (stiffness + params.sigma1() / dt) * reach + g;
    let steps = ((initial / (1e-11 * g)).ln() / -contraction.ln()).ceil();
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // a small positive count
    let steps = steps as usize;
    steps + 2
}

/// The Stribeck curve, n, sigma1, sigma2 and `sigma2_neg` of a case.
type Model = (Stribeck, f64, f64, f64, f64);

/// Parameters whose elements have saturation forces in proportion to `weights` (adding up to
/// `strength` times the peak level) and the dimensionless steps `rho` at velocity `v` and `dt`.
fn build<const N: usize>(
    (stribeck, n, sigma1, sigma2, sigma2_neg): Model,
    (weights, strength, rho): ([f64; N], f64, [f64; N]),
    v: f64,
    dt: f64,
) -> LeuvenParams<N> {
    let g = stribeck.g(v);
    let w = saturation_forces(weights, stribeck.peak(), strength);
    let delta = core::array::from_fn(|i| w[i] * dt * v.abs() / (rho[i] * g));
    let elements = MaxwellSlip::new(w, delta).expect("valid elements");
    Params::new(stribeck, n, sigma1, sigma2, elements)
        .and_then(|params| params.with_sigma2_neg(sigma2_neg))
        .expect("valid parameters")
}

/// A Stribeck curve with asymmetric levels, n, sigma1, and sigma2 and `sigma2_neg`.
fn model() -> impl Strategy<Value = Model> {
    (
        asymmetric_stribeck(),
        exponent(),
        coefficient(),
        coefficient(),
        coefficient(),
    )
}

/// Any stiffness: ρᵢ from 0.1 (soft, slow) to 1000 (stiff, one-step).
fn implicit_case<const N: usize>() -> impl Strategy<Value = Case<N>> {
    let elements = (
        uniform::<_, N>(0.05..1.0),
        1.05..5.0,
        uniform::<_, N>(log_uniform(0.1, 1e3)),
    );
    (model(), elements, signed(log_uniform(1e-6, 1.0)), dt()).prop_map(
        |(model, (weights, strength, rho), v, dt)| {
            let params = build(model, (weights, strength, rho), v, dt);
            let slowest = rho.iter().fold(f64::INFINITY, |a, &b| a.min(b));
            let contraction = 1.0 / (1.0 + params.n().min(1.0) * slowest);
            let steps = steps_to_settle(&params, v, dt, contraction);
            Case {
                params,
                v,
                dt,
                steps,
            }
        },
    )
}

/// Stable and monotone explicit steps: max(1, n)·Σρᵢ from 0.1 to 0.9.
fn explicit_case<const N: usize>() -> impl Strategy<Value = Case<N>> {
    let elements = (
        uniform::<_, N>(0.05..1.0),
        1.05..5.0,
        uniform::<_, N>(0.5..1.0),
        0.1..0.9,
    );
    (model(), elements, signed(log_uniform(1e-6, 1.0)), dt()).prop_map(
        |(model, (weights, strength, shares, total), v, dt)| {
            let n = model.1;
            let sum: f64 = shares.iter().sum();
            let rho = shares.map(|share| total * share / (sum * n.max(1.0)));
            let params = build(model, (weights, strength, rho), v, dt);
            let slowest = rho.iter().fold(f64::INFINITY, |a, &b| a.min(b));
            let contraction = 1.0 - n.min(1.0) * slowest;
            let steps = steps_to_settle(&params, v, dt, contraction);
            Case {
                params,
                v,
                dt,
                steps,
            }
        },
    )
}

fn settles_on_the_stribeck_curve<const N: usize>(
    case: &Case<N>,
    scheme: Scheme,
) -> Result<(), TestCaseError> {
    let Case {
        params,
        v,
        dt,
        steps,
    } = case;
    let mut state = params.relaxed_state();
    let mut force = f64::NAN;
    for _ in 0..*steps {
        force = params
            .step(&mut state, *v, *dt, scheme)
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
    }
    // The Stribeck level from the DESIGN formula, not from the crate's own `s(v)`: a curve that
    // mixed up the direction levels would otherwise agree with itself.
    let level = stribeck_level(params.stribeck(), *v);
    // Likewise the viscous coefficient of the direction, from its definition.
    let sigma2 = if *v < 0.0 {
        params.sigma2_neg()
    } else {
        params.sigma2()
    };
    let expected = level.copysign(*v) + sigma2 * v;
    let scale = level + sigma2 * v.abs();
    prop_assert!(
        (force - expected).abs() <= 1e-9 * scale,
        "after {} steps F = {}, expected s(v) + σ2(v)·v = {} (relative error {:e})",
        steps,
        force,
        expected,
        (force - expected).abs() / scale
    );
    Ok(())
}

proptest! {
    #![proptest_config(common::config(96))]

    #[test]
    fn implicit_settles_n1(case in implicit_case::<1>()) {
        settles_on_the_stribeck_curve(&case, Scheme::Implicit)?;
    }

    #[test]
    fn implicit_settles_n4(case in implicit_case::<4>()) {
        settles_on_the_stribeck_curve(&case, Scheme::Implicit)?;
    }

    #[test]
    fn implicit_settles_n10(case in implicit_case::<10>()) {
        settles_on_the_stribeck_curve(&case, Scheme::Implicit)?;
    }

    #[test]
    fn explicit_settles_n1(case in explicit_case::<1>()) {
        settles_on_the_stribeck_curve(&case, Scheme::Explicit)?;
    }

    #[test]
    fn explicit_settles_n4(case in explicit_case::<4>()) {
        settles_on_the_stribeck_curve(&case, Scheme::Explicit)?;
    }
}
