//! Nonlocal memory with wiping-out, at the hysteresis level (`MaxwellSlip::trial`/`commit` driven
//! with z directly, in small increments so that every intermediate state is committed).
//!
//! With 0 < A, −A < B < C < A < D:
//!
//! - a minor loop B → C → B is forgotten once it closes: along 0 → A → B → C → B → D, Fh (and
//!   the memory) from the closure at B onwards equals that along 0 → A → B → D;
//! - once z passes the earlier extremum A, that turning point is forgotten too: beyond A, Fh
//!   equals the virgin curve (one commit from the relaxed memory straight to z).
//!
//! Cases in which the minor loop would not make any element slip are discarded, so that the
//! loop always leaves a trace in the memory that has to be wiped out.

mod common;

use common::log_uniform;
use gms_core::{Hysteresis, MaxwellSlip};
use proptest::array::uniform;
use proptest::prelude::*;

/// z from `from` to `to` in `steps` equal increments, landing exactly on `to` (the closure of
/// the minor loop must come back to the same B as the path without it).
fn segment(from: f64, to: f64, steps: usize) -> impl Iterator<Item = f64> {
    (1..=steps).map(move |j| {
        if j == steps {
            to
        } else {
            from + (to - from) * j as f64 / steps as f64
        }
    })
}

/// The piecewise-linear path from 0 through `turns`, each leg in `steps` increments.
fn path(turns: &[f64], steps: usize) -> Vec<f64> {
    let mut points = Vec::new();
    let mut from = 0.0;
    for &to in turns {
        points.extend(segment(from, to, steps));
        from = to;
    }
    points
}

/// Fh and the memory after committing each point of `path`, starting relaxed.
fn drive<const N: usize>(bank: &MaxwellSlip<N>, path: &[f64]) -> Vec<(f64, [f64; N])> {
    let mut memory = bank.relaxed();
    path.iter()
        .map(|&z| {
            bank.commit(&mut memory, z);
            (bank.trial(&memory, z).force, memory)
        })
        .collect()
}

fn minor_loops_are_wiped_out<const N: usize>(
    bank: &MaxwellSlip<N>,
    [a, b, c, d]: [f64; 4],
    steps: usize,
) -> Result<(), TestCaseError> {
    let force_tolerance = 1e-12 * bank.max_force();
    let memory_tolerance = 1e-12 * bank.delta().iter().fold(0.0f64, |x, &y| x.max(y));

    let loop_path = path(&[a, b, c, b, d], steps);
    let with_loop = drive(bank, &loop_path);
    let without_loop = drive(bank, &path(&[a, b, d], steps));

    // The loop must leave a trace: some element slipped on the way up to C.
    let at_b = without_loop[2 * steps - 1].1;
    let at_c = with_loop[3 * steps - 1].1;
    prop_assume!(at_b != at_c, "no element slips inside the minor loop");

    // From the point where the loop closes (back at B) to the end at D.
    let after_closure = &with_loop[4 * steps - 1..];
    let reference = &without_loop[2 * steps - 1..];
    prop_assert_eq!(after_closure.len(), reference.len());
    for (k, ((force, memory), (expected, expected_memory))) in
        after_closure.iter().zip(reference).enumerate()
    {
        prop_assert!(
            (force - expected).abs() <= force_tolerance,
            "{} increments after the closure: Fh = {} with the loop, {} without",
            k,
            force,
            expected
        );
        for (zeta, expected_zeta) in memory.iter().zip(expected_memory) {
            prop_assert!((zeta - expected_zeta).abs() <= memory_tolerance);
        }
    }

    // Beyond A, even the outer turning point A (and B with it) is forgotten.
    for (&z, (force, _)) in loop_path.iter().zip(&with_loop).filter(|(&z, _)| z > a) {
        let mut virgin = bank.relaxed();
        bank.commit(&mut virgin, z);
        let expected = bank.trial(&virgin, z).force;
        prop_assert!(
            (force - expected).abs() <= force_tolerance,
            "at z = {} beyond A = {}: Fh = {}, virgin curve {}",
            z,
            a,
            force,
            expected
        );
    }
    Ok(())
}

/// A bank with break deflections over three decades and the turning points A, B, C, D in units
/// of its largest break deflection.
fn case<const N: usize>() -> impl Strategy<Value = (MaxwellSlip<N>, [f64; 4], usize)> {
    (
        uniform::<_, N>(0.05..2.0),
        uniform::<_, N>(log_uniform(1e-7, 1e-4)),
        (0.2..4.0, -0.95..0.95, 0.05..0.95, 0.01..3.0),
        2..30usize,
    )
        .prop_map(|(w, delta, (a, b, c, d), steps)| {
            let bank = MaxwellSlip::new(w, delta).expect("valid elements");
            let unit = delta.iter().fold(0.0f64, |x, &y| x.max(y));
            let a = a * unit;
            let b = b * a; // −A < B < A
            let c = b + c * (a - b); // B < C < A
            let d = a + d * unit; // D > A
            (bank, [a, b, c, d], steps)
        })
}

proptest! {
    #![proptest_config(common::config(128))]

    #[test]
    fn wiping_out_n4((bank, turns, steps) in case::<4>()) {
        minor_loops_are_wiped_out(&bank, turns, steps)?;
    }

    #[test]
    fn wiping_out_n10((bank, turns, steps) in case::<10>()) {
        minor_loops_are_wiped_out(&bank, turns, steps)?;
    }

    #[test]
    fn wiping_out_n32((bank, turns, steps) in case::<32>()) {
        minor_loops_are_wiped_out(&bank, turns, steps)?;
    }
}
