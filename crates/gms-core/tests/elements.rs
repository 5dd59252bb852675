//! The Maxwell-slip elements keep their deflections inside the break deflections, whatever the
//! model does to them, and the hysteresis map has the shape the implicit step relies on.
//!
//! - After every step of either scheme, for N = 1, 4, 10, 32, random valid parameters, random
//!   time steps and velocity sequences with reversals, plateaus and exact zeros: each element
//!   either kept its ζᵢ or slipped to exactly z ∓ Δᵢ, and |eᵢ| = |z − ζᵢ| ≤ Δᵢ.
//! - `trial` is non-decreasing in z, and committing at z does not change Fh(z) (no force jump
//!   when elements slip).
//!
//! All comparisons are exact except where a rounding of one operation is unavoidable; each such
//! tolerance is a few ulps and says which rounding it covers.

mod common;

use common::{dt, leuven, reach, scheme, velocities};
use gms_core::{Error, Hysteresis, LeuvenParams, Scheme};
use proptest::prelude::*;

/// Steps `velocities` through a relaxed channel and checks every element after every step.
fn deflections_stay_within_breaks<const N: usize>(
    params: &LeuvenParams<N>,
    velocities: &[f64],
    dt: f64,
    scheme: Scheme,
) -> Result<(), TestCaseError> {
    let limits = params.hysteresis().delta();
    let mut state = params.relaxed_state();
    for (k, &v) in velocities.iter().enumerate() {
        let before = state;
        match params.step(&mut state, v, dt, scheme) {
            Ok(_) => {}
            // A diverging explicit step is reported and leaves the state as it was: the states
            // checked so far are all the model ever reached.
            Err(Error::Diverged { .. }) => {
                prop_assert_eq!(state, before);
                break;
            }
            Err(other) => return Err(TestCaseError::fail(format!("step {k}: {other}"))),
        }
        let z = state.z;
        for (i, (&zeta, &limit)) in state.memory.iter().zip(limits).enumerate() {
            // Exact: an element moves only by slipping, and then sits at the break.
            prop_assert!(
                zeta == before.memory[i] || zeta == z - limit || zeta == z + limit,
                "step {}: element {} moved from {} to {} at z = {}",
                k,
                i,
                before.memory[i],
                zeta,
                z
            );
            // ζ = z ∓ Δ is rounded to half an ulp of ζ, and z − ζ to half an ulp of the result,
            // so a slipped element can read one ulp beyond its break (z = 1, Δ = 0.3 does).
            let rounding = f64::EPSILON * (zeta.abs() + limit);
            prop_assert!(
                (z - zeta).abs() <= limit + rounding,
                "step {}: |e{}| = {} > Δ = {} (z = {}, ζ = {})",
                k,
                i,
                (z - zeta).abs(),
                limit,
                z,
                zeta
            );
        }
    }
    Ok(())
}

/// `trial` over a grid of z around a reachable memory: monotone, and unchanged by a commit.
fn trial_is_monotone_and_commit_is_continuous<const N: usize>(
    params: &LeuvenParams<N>,
    velocities: &[f64],
    dt: f64,
    offsets: &[f64],
) -> Result<(), TestCaseError> {
    let bank = params.hysteresis();
    let mut state = params.relaxed_state();
    reach(params, &mut state, velocities, dt, Scheme::Implicit);
    let scale = bank.delta().iter().fold(0.0f64, |a, &b| a.max(b));
    let total = bank.max_force();
    // A sticking element at its break gives (W/Δ)·Δ, which can round one ulp above the W of the
    // slipping element just beyond: Fh may dip by about an ulp of each W at a break.
    let rounding = 2.0 * f64::EPSILON * total;

    let mut grid: Vec<f64> = offsets
        .iter()
        .map(|offset| state.z + offset * scale)
        .collect();
    grid.sort_by(f64::total_cmp);
    for pair in grid.windows(2) {
        let (low, high) = (
            bank.trial(&state.memory, pair[0]),
            bank.trial(&state.memory, pair[1]),
        );
        prop_assert!(
            low.force <= high.force + rounding,
            "Fh({}) = {} > Fh({}) = {}",
            pair[0],
            low.force,
            pair[1],
            high.force
        );
    }
    for &z in &grid {
        let before = bank.trial(&state.memory, z);
        let mut memory = state.memory;
        bank.commit(&mut memory, z);
        let after = bank.trial(&memory, z);
        // A slipped element now reads k·(z − ζ) ≈ W instead of W: ζ = z ∓ Δ is rounded to an ulp
        // of z, which is |z|/Δ ulps of the deflection, so the allowance grows with |z|/Δᵢ.
        let commit_rounding: f64 = bank
            .w()
            .iter()
            .zip(bank.delta())
            .map(|(&w, &limit)| 2.0 * f64::EPSILON * w * (1.0 + z.abs() / limit))
            .sum();
        prop_assert!(
            (after.force - before.force).abs() <= commit_rounding,
            "commit at z = {} changed Fh from {} to {}",
            z,
            before.force,
            after.force
        );
        prop_assert!(after.force.abs() <= total * (1.0 + 4.0 * f64::EPSILON));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn deflections_within_breaks_n1(
        params in leuven::<1>(), v in velocities(), dt in dt(), scheme in scheme()
    ) {
        deflections_stay_within_breaks(&params, &v, dt, scheme)?;
    }

    #[test]
    fn deflections_within_breaks_n4(
        params in leuven::<4>(), v in velocities(), dt in dt(), scheme in scheme()
    ) {
        deflections_stay_within_breaks(&params, &v, dt, scheme)?;
    }

    #[test]
    fn deflections_within_breaks_n10(
        params in leuven::<10>(), v in velocities(), dt in dt(), scheme in scheme()
    ) {
        deflections_stay_within_breaks(&params, &v, dt, scheme)?;
    }

    #[test]
    fn deflections_within_breaks_n32(
        params in leuven::<32>(), v in velocities(), dt in dt(), scheme in scheme()
    ) {
        deflections_stay_within_breaks(&params, &v, dt, scheme)?;
    }

    #[test]
    fn trial_monotone_and_commit_continuous_n4(
        params in leuven::<4>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        trial_is_monotone_and_commit_is_continuous(&params, &v, dt, &offsets)?;
    }

    #[test]
    fn trial_monotone_and_commit_continuous_n32(
        params in leuven::<32>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        trial_is_monotone_and_commit_is_continuous(&params, &v, dt, &offsets)?;
    }
}
