//! The compensator: it is the model, stepped at a fixed dt; its two modes; parameter swaps that
//! carry the hysteresis force over, so the output has no jump.

mod common;

use common::{config, leuven, velocities};
use gms_core::{
    evaluation_bound, Compensator, Hysteresis, LeuvenParams, MaxwellSlip, Mode, Params, Scheme,
    Stribeck,
};
use proptest::prelude::*;

const DT: f64 = 1e-3;

fn params(fc: f64, fs: f64, vs: f64, w: [f64; 4], delta: [f64; 4], sigma1: f64) -> LeuvenParams<4> {
    let stribeck = Stribeck::new(fc, fs, vs, 2.0).unwrap();
    Params::new(
        stribeck,
        2.0,
        sigma1,
        0.4,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap()
}

/// The compensator's nominal model and a "re-identified" one: every level, the Stribeck
/// velocity and the elements differ by 10–40 %.
fn old_and_new(sigma1: f64) -> (LeuvenParams<4>, LeuvenParams<4>) {
    (
        params(1.0, 1.5, 1e-3, [0.5; 4], [1e-6, 2e-6, 4e-6, 8e-6], sigma1),
        params(
            1.2,
            1.6,
            1.4e-3,
            [0.3, 0.5, 0.6, 0.7],
            [1.5e-6, 2.5e-6, 6e-6, 1.2e-5],
            sigma1,
        ),
    )
}

#[test]
fn modes_are_the_model_stepped_at_the_fixed_dt() {
    let (params, _) = old_and_new(30.0);
    let velocity: Vec<f64> = (0..2000)
        .map(|k| 5e-3 * (2e-3 * core::f64::consts::PI * f64::from(k)).sin())
        .collect();
    let mut feedforward = Compensator::new(params, DT, Mode::Feedforward).unwrap();
    let mut observer = Compensator::new(params, DT, Mode::Observer).unwrap();
    let (mut by_velocity, mut by_position) = (params.relaxed_state(), params.relaxed_state());
    let mut x = 0.0;
    for &v in &velocity {
        x += v * DT;
        let expected = params
            .step(&mut by_velocity, v, DT, Scheme::Implicit)
            .unwrap();
        assert_eq!(feedforward.step(v).unwrap(), expected);
        let expected = params
            .step_position(&mut by_position, x, DT, Scheme::Implicit)
            .unwrap();
        assert_eq!(observer.step(x).unwrap(), expected);
        assert_eq!(observer.output(), expected);
    }
    assert_eq!(feedforward.state(), &by_velocity);
    assert_eq!(observer.state(), &by_position);
}

/// The force jump at a parameter swap, with the compensator's re-initialisation and with the
/// naive swap that keeps (z, ζ) as they are: `|F(first sample after) − F(last sample before)|`.
///
/// The velocity is the smooth v(t) = 5 mm/s·sin(2πt); the swap comes at `t_swap`.
fn jumps(dt: f64, t_swap: f64, sigma1: f64) -> (f64, f64) {
    let (old, new) = old_and_new(sigma1);
    let velocity = |k: usize| 5e-3 * (2.0 * core::f64::consts::PI * k as f64 * dt).sin();
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // a small positive count
    let swap = (t_swap / dt).round() as usize;
    let mut compensator = Compensator::new(old, dt, Mode::Feedforward).unwrap();
    let mut naive = old.relaxed_state();
    let mut before = 0.0;
    for k in 0..swap {
        before = compensator.step(velocity(k)).unwrap();
        old.step(&mut naive, velocity(k), dt, Scheme::Implicit)
            .unwrap();
    }
    compensator.set_params(new);
    let after = compensator.step(velocity(swap)).unwrap();
    let naive_after = new
        .step(&mut naive, velocity(swap), dt, Scheme::Implicit)
        .unwrap();
    ((after - before).abs(), (naive_after - before).abs())
}

/// Without a jump, the change over the sample of the swap is O(dt), like any other sample's:
/// it halves when dt halves. A jump of any size J would keep it above J. The naive swap is the
/// control: its jump does not shrink, which shows the detector can see one.
///
/// σ1 = 0 here: with σ1 > 0 the micro-viscous term σ1·ż changes at once, because ż depends on
/// g(v) of the new parameters (checked in the next test).
#[test]
fn a_swap_has_no_jump_in_sliding_or_presliding() {
    // t = 0.2: sliding at 4.8 mm/s; t = 0.5005: 0.5 ms after a reversal, in presliding.
    for t_swap in [0.2, 0.5005] {
        let coarse = jumps(2e-5, t_swap, 0.0);
        let fine = jumps(5e-6, t_swap, 0.0);
        // O(dt) gives 0.25 once dt is well below the relaxation time of Fh (about 0.4 ms here).
        let ratio = fine.0 / coarse.0;
        assert!(ratio < 0.35, "t = {t_swap}: jumps {coarse:?} -> {fine:?}");
        assert!(
            fine.1 > 0.05 && fine.1 > 0.7 * coarse.1,
            "t = {t_swap}: naive {coarse:?} -> {fine:?}"
        );
        assert!(fine.0 < 0.02 * fine.1, "t = {t_swap}: {fine:?}");
    }
}

/// With σ1 > 0 the only change that does not vanish with dt is σ1·ż: at the swap, ż goes to
/// v·(1 − (Fh/`g_new`(v))ⁿ) with Fh = `g_old`(v) carried over, so the change is at most
/// σ1·|v|·|1 − (`g_old`/`g_new`)²| on top of the O(dt) change measured with σ1 = 0.
#[test]
fn with_micro_viscous_damping_only_sigma1_zdot_changes() {
    let (_, new) = old_and_new(30.0);
    let dt = 5e-6;
    let (reinitialised, naive) = jumps(dt, 0.2, 30.0);
    let continuous = jumps(dt, 0.2, 0.0).0;
    let v = 5e-3 * (2.0 * core::f64::consts::PI * 0.2f64).sin();
    let g_old = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap().g(v);
    let g_new = new.stribeck().g(v);
    let bound = 30.0 * v * (1.0 - (g_old / g_new).powi(2)).abs();
    assert!(
        reinitialised <= 1.01 * bound + continuous,
        "{reinitialised} vs bound {bound} + {continuous}"
    );
    assert!(naive > 4.0 * reinitialised, "{naive} vs {reinitialised}");
}

proptest! {
    #![proptest_config(config(200))]

    /// After any history and any swap: the new Fh equals the old (or the nearest force the new
    /// bank can hold), every element is within its new limits, the next steps are accepted,
    /// and the last position is kept.
    #[test]
    fn swap_carries_the_hysteresis_force_over(
        old in leuven::<4>(),
        new in leuven::<4>(),
        history in velocities(),
        observer in any::<bool>(),
    ) {
        let mode = if observer { Mode::Observer } else { Mode::Feedforward };
        let mut compensator = Compensator::new(old, DT, mode).unwrap();
        let mut x = 0.0;
        for &v in &history {
            x += v * DT;
            compensator.step(if observer { x } else { v }).unwrap();
        }
        let state = *compensator.state();
        let target = old.hysteresis().force(&state.memory, state.z);
        compensator.set_params(new);
        let after = compensator.state();
        let limit = new.hysteresis().max_force();
        let expected = target.clamp(-limit, limit);
        let force = new.hysteresis().force(&after.memory, after.z);
        prop_assert!((force - expected).abs() <= 1e-9 * limit, "{force} vs {expected}");
        for (zeta, delta) in after.memory.iter().zip(new.hysteresis().delta()) {
            prop_assert!((after.z - zeta).abs() <= delta * (1.0 + 1e-12));
        }
        prop_assert_eq!(after.last_position, state.last_position);
        prop_assert_eq!(compensator.params(), &new);
        for k in 0..10 {
            let input = if observer { x + 1e-7 * f64::from(k) } else { 1e-4 };
            prop_assert!(compensator.step(input).unwrap().is_finite());
        }
    }

    /// The implicit step of a compensator never needs more than 2N + 1 evaluations.
    #[test]
    fn steps_stay_within_the_evaluation_bound(params in leuven::<10>(), history in velocities()) {
        let mut compensator = Compensator::new(params, DT, Mode::Feedforward).unwrap();
        for &v in &history {
            let solution = params.solve_implicit(compensator.state(), v, DT);
            prop_assert!(solution.iterations as usize <= evaluation_bound(10));
            compensator.step(v).unwrap();
        }
    }
}
