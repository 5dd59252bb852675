//! The Maxwell-slip elements keep their deflections inside the break deflections, whatever the
//! model does to them, and the hysteresis map has the shape the implicit step relies on.
//!
//! - After every step of either scheme, for N = 1, 4, 10, 32, random valid parameters, random
//!   time steps and velocity sequences with reversals, plateaus and exact zeros: each element
//!   either kept its ζᵢ or slipped to exactly z ∓ Δᵢ, and |eᵢ| = |z − ζᵢ| ≤ Δᵢ (up to the
//!   rounding of z ∓ Δᵢ, which can put a slipped element one ulp beyond its break).
//! - The hysteresis map around reachable memories: `trial` is non-decreasing in z and linear
//!   up to the breakpoints it reports (the implicit solver walks those pieces), `force` and
//!   `commit` return the trial force, and committing at z does not change Fh(z) (no force jump
//!   when elements slip). `piece` is `trial`'s side, bit for bit, and `trial` agrees with a plain
//!   element-by-element evaluation written here (breakpoints exactly, sums to rounding), also
//!   at z exactly on the breakpoints, where the sticking tests `≤` and `<` differ.
//!
//! All comparisons are exact except where a rounding of one operation is unavoidable; each such
//! tolerance is a few ulps and says which rounding it covers.

mod common;

use common::{dt, leuven, reach, scheme, velocities};
use gms_core::{Error, Hysteresis, LeuvenParams, MaxwellSlip, Piece, Scheme, Trial};
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

/// `trial` as the paper's elements define it, one element at a time in plain loops: element i
/// sticks on [ζᵢ − Δᵢ, ζᵢ + Δᵢ], and contributes its stiffness to the slope on a side when it
/// sticks on that side of z.
fn plain_trial<const N: usize>(bank: &MaxwellSlip<N>, memory: &[f64; N], z: f64) -> Trial {
    let mut trial = Trial {
        force: 0.0,
        slope_left: 0.0,
        slope_right: 0.0,
        left: f64::NEG_INFINITY,
        right: f64::INFINITY,
    };
    for ((&w, &limit), &zeta) in bank.w().iter().zip(bank.delta()).zip(memory) {
        let k = w / limit;
        let (lower, upper) = (zeta - limit, zeta + limit);
        trial.force += k * (z - zeta).max(-limit).min(limit);
        if lower <= z && z < upper {
            trial.slope_right += k;
        }
        if lower < z && z <= upper {
            trial.slope_left += k;
        }
        for breakpoint in [lower, upper] {
            if breakpoint > z {
                trial.right = trial.right.min(breakpoint);
            }
            if breakpoint < z {
                trial.left = trial.left.max(breakpoint);
            }
        }
    }
    trial
}

/// `trial` over a grid of z around a reachable memory: monotone, agreeing with `force` and with
/// what `commit` returns, unchanged by a commit, and linear on the pieces it reports.
fn hysteresis_map_is_consistent<const N: usize>(
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
    // Each element force kᵢ·(z − ζᵢ) carries the rounding of z − ζᵢ, an ulp of z, which is
    // |z|/Δᵢ ulps of the element's range: the allowance grows with |z|/Δᵢ.
    let rounding = |z: f64| -> f64 {
        bank.w()
            .iter()
            .zip(bank.delta())
            .map(|(&w, &limit)| 4.0 * f64::EPSILON * w * (1.0 + 2.0 * z.abs() / limit))
            .sum()
    };

    let mut grid: Vec<f64> = offsets
        .iter()
        .map(|offset| state.z + offset * scale)
        .chain(
            state
                .memory
                .iter()
                .zip(bank.delta())
                .flat_map(|(&zeta, &limit)| [zeta - limit, zeta + limit]),
        )
        .collect();
    grid.sort_by(f64::total_cmp);
    for pair in grid.windows(2) {
        let (low, high) = (
            bank.trial(&state.memory, pair[0]),
            bank.trial(&state.memory, pair[1]),
        );
        prop_assert!(
            low.force <= high.force + rounding(pair[1]),
            "Fh({}) = {} > Fh({}) = {}",
            pair[0],
            low.force,
            pair[1],
            high.force
        );
    }
    for &z in &grid {
        let trial = bank.trial(&state.memory, z);
        prop_assert!(trial.force.abs() <= total * (1.0 + 4.0 * f64::EPSILON));
        prop_assert_eq!(bank.force(&state.memory, z), trial.force);
        let right = Piece {
            slope: trial.slope_right,
            end: trial.right,
        };
        let left = Piece {
            slope: trial.slope_left,
            end: trial.left,
        };
        prop_assert_eq!(bank.piece(&state.memory, z, true), right);
        prop_assert_eq!(bank.piece(&state.memory, z, false), left);

        // The same map, element by element: breakpoints exact, sums to their rounding.
        let plain = plain_trial(bank, &state.memory, z);
        prop_assert_eq!((plain.left, plain.right), (trial.left, trial.right));
        let stiffness: f64 = bank
            .w()
            .iter()
            .zip(bank.delta())
            .map(|(&w, &limit)| w / limit)
            .sum();
        prop_assert!((plain.force - trial.force).abs() <= rounding(z));
        prop_assert!((plain.slope_left - trial.slope_left).abs() <= 1e-14 * stiffness);
        prop_assert!((plain.slope_right - trial.slope_right).abs() <= 1e-14 * stiffness);

        // On each side, up to the reported breakpoint, Fh is the reported straight line.
        prop_assert!(trial.left < z && z < trial.right);
        for (end, slope) in [
            (trial.left, trial.slope_left),
            (trial.right, trial.slope_right),
        ] {
            let end = end.clamp(z - scale, z + scale); // the last piece on a side is unbounded
            for fraction in [0.25, 0.5, 1.0] {
                let y = z + fraction * (end - z);
                let on_piece = trial.force + slope * (y - z);
                let actual = bank.trial(&state.memory, y).force;
                prop_assert!(
                    (actual - on_piece).abs() <= rounding(z) + rounding(y),
                    "Fh({}) = {}, the piece at z = {} says {}",
                    y,
                    actual,
                    z,
                    on_piece
                );
            }
        }

        // Committing returns the trial force and does not change Fh at z.
        let mut memory = state.memory;
        prop_assert_eq!(bank.commit(&mut memory, z), trial.force);
        let after = bank.trial(&memory, z).force;
        prop_assert!(
            (after - trial.force).abs() <= rounding(z),
            "commit at z = {} changed Fh from {} to {}",
            z,
            trial.force,
            after
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::config(128))]

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
    fn hysteresis_map_consistent_n4(
        params in leuven::<4>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        hysteresis_map_is_consistent(&params, &v, dt, &offsets)?;
    }

    #[test]
    fn hysteresis_map_consistent_n1(
        params in leuven::<1>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        hysteresis_map_is_consistent(&params, &v, dt, &offsets)?;
    }

    /// N = 10: two full chunks of four elements and a remainder of two.
    #[test]
    fn hysteresis_map_consistent_n10(
        params in leuven::<10>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        hysteresis_map_is_consistent(&params, &v, dt, &offsets)?;
    }

    #[test]
    fn hysteresis_map_consistent_n32(
        params in leuven::<32>(),
        v in velocities(),
        dt in dt(),
        offsets in prop::collection::vec(-3.0..3.0f64, 2..40),
    ) {
        hysteresis_map_is_consistent(&params, &v, dt, &offsets)?;
    }
}
