//! The force-driven mass (`MassSystem`): the step solves the equations it claims to, holds a stiff
//! stick at any dt where the explicit coupling blows up, reaches the right steady states, and
//! rejects bad input without touching the state.

mod common;

use common::{config, leuven, log_uniform, signed};
use gms_core::{
    Error, Field, Hysteresis, LeuvenParams, MassSystem, MaxwellSlip, Params, Scheme, Spring,
    Stribeck, Trajectory,
};
use proptest::prelude::*;

fn friction(w: [f64; 2], delta: [f64; 2], sigma1: f64, sigma2: f64) -> LeuvenParams<2> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    Params::new(
        stribeck,
        2.0,
        sigma1,
        sigma2,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap()
}

/// Presliding stiffness K = 2/2e-8 = 1e8 N/m on m = 1 kg: at dt = 1 ms, dt²·K/m = 100, fifty
/// times the explicit coupling's limit of 2.
fn stiff() -> MassSystem<MaxwellSlip<2>> {
    MassSystem::new(
        friction([1.0, 1.0], [2e-8, 2e-8], 0.0, 0.0),
        1.0,
        Spring::NONE,
    )
    .unwrap()
}

#[test]
fn implicit_holds_a_stiff_stick_without_chatter() {
    let system = stiff();
    let (u, dt) = (0.5, 1e-3);
    let mut state = system.state_at(0.0, 0.0);
    let mut velocities = Vec::new();
    let mut last = None;
    for _ in 0..200 {
        let sample = system.step(&mut state, u, dt, Scheme::Implicit).unwrap();
        velocities.push(sample.v);
        last = Some(sample);
    }
    let last = last.unwrap();
    // Below break-away: the mass comes to rest where the elements carry u, within nanometres.
    assert!(
        (last.friction - u).abs() < 1e-12,
        "friction {}",
        last.friction
    );
    assert!(last.v.abs() < 1e-15, "velocity {}", last.v);
    assert!(last.x > 0.0 && last.x < 2e-8, "position {}", last.x);
    // No chatter: the velocity left by the first push at least halves at every step.
    for pair in velocities.windows(2).skip(1).take(10) {
        assert!(pair[1].abs() <= 0.5 * pair[0].abs(), "{pair:?}");
    }
}

#[test]
fn explicit_coupling_chatters_and_slides_at_the_same_stiff_stick() {
    // u = 0.5 N is a third of the break-away force, yet the explicit coupling overshoots the
    // stick at every sample: the friction force flips between ±sum(W) and the mass drifts off.
    let system = stiff();
    let mut state = system.state_at(0.0, 0.0);
    let mut flips = 0;
    let mut previous = 0.0;
    for _ in 0..200 {
        let sample = system
            .step(&mut state, 0.5, 1e-3, Scheme::Explicit)
            .unwrap();
        if sample.friction * previous < 0.0 {
            flips += 1;
        }
        previous = sample.friction;
    }
    assert!(flips > 50, "{flips} sign flips of the friction force");
    assert!(
        state.x > 1e-3,
        "x = {} m after 0.2 s below break-away",
        state.x
    );
}

#[test]
fn explicit_agrees_with_implicit_where_both_are_stable() {
    // Soft contact (K = 2e4 N/m, dt²K/m = 2e-4): both schemes are first order and close.
    let params = friction([1.0, 1.0], [1e-4, 1e-4], 50.0, 1.0);
    let system = MassSystem::new(params, 1.0, Spring::ground(100.0).unwrap()).unwrap();
    let (mut a, mut b) = (system.state_at(0.01, 0.0), system.state_at(0.01, 0.0));
    for _ in 0..2000 {
        let implicit = system.step(&mut a, 0.0, 1e-4, Scheme::Implicit).unwrap();
        let explicit = system.step(&mut b, 0.0, 1e-4, Scheme::Explicit).unwrap();
        assert!(
            (implicit.x - explicit.x).abs() < 2e-5,
            "{implicit:?} {explicit:?}"
        );
    }
}

#[test]
fn a_constant_force_slides_the_mass_at_the_steady_velocity() {
    // u = Fc + sigma2·v∞ + Stribeck remainder: v∞ solves u = g(v) + σ2·v; far above Vs, g = Fc.
    let params = friction([1.0, 1.0], [1e-6, 2e-6], 100.0, 10.0);
    let system = MassSystem::new(params, 0.1, Spring::NONE).unwrap();
    let mut state = system.state_at(0.0, 0.0);
    let mut sample = None;
    for _ in 0..20_000 {
        sample = Some(
            system
                .step(&mut state, 2.0, 1e-3, Scheme::Implicit)
                .unwrap(),
        );
    }
    let sample = sample.unwrap();
    assert!((sample.v - 0.1).abs() < 1e-12, "v = {}", sample.v);
    assert!(
        (sample.friction - 2.0).abs() < 1e-9,
        "F = {}",
        sample.friction
    );
}

/// Pushed backwards, the mass slides at the velocity where u = −`Fc_neg` + `sigma2_neg`·v∞: the
/// implicit step solves the momentum equation with the viscous coefficient of the new
/// velocity's direction.
#[test]
fn a_constant_backward_force_slides_at_the_negative_directions_velocity() {
    let stribeck = Stribeck::asymmetric(1.0, 1.5, 0.8, 1.2, 1e-3, 2.0).unwrap();
    let bank = MaxwellSlip::new([1.0, 1.0], [1e-6, 2e-6]).unwrap();
    let params = Params::new(stribeck, 2.0, 100.0, 10.0, bank)
        .and_then(|params| params.with_sigma2_neg(4.0))
        .unwrap();
    let system = MassSystem::new(params, 0.1, Spring::NONE).unwrap();
    let mut state = system.state_at(0.0, 0.0);
    let mut sample = None;
    for _ in 0..20_000 {
        sample = Some(
            system
                .step(&mut state, -1.2, 1e-3, Scheme::Implicit)
                .unwrap(),
        );
    }
    let sample = sample.unwrap();
    // −1.2 = −0.8 + 4·v∞: v∞ = −0.1 (with sigma2 = 10 it would be −0.04).
    assert!((sample.v + 0.1).abs() < 1e-12, "v = {}", sample.v);
    assert!(
        (sample.friction + 1.2).abs() < 1e-9,
        "F = {}",
        sample.friction
    );
    // The same sigma2 in both directions is the symmetric model, bit for bit.
    let symmetric = MassSystem::new(
        friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4)
            .with_sigma2_neg(0.4)
            .unwrap(),
        1.0,
        Spring::ground(50.0).unwrap(),
    )
    .unwrap();
    let plain = MassSystem::new(
        friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4),
        1.0,
        Spring::ground(50.0).unwrap(),
    )
    .unwrap();
    let (mut a, mut b) = (symmetric.state_at(0.01, 0.0), plain.state_at(0.01, 0.0));
    for k in 0..500 {
        let u = 3.0 * (0.05 * f64::from(k)).sin();
        assert_eq!(
            symmetric.step(&mut a, u, 1e-3, Scheme::Implicit).unwrap(),
            plain.step(&mut b, u, 1e-3, Scheme::Implicit).unwrap()
        );
    }
}

#[test]
fn the_dragged_spring_end_moves_at_the_drive_speed() {
    let params = friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4);
    let system = MassSystem::new(params, 1.0, Spring::dragged(1e3, 0.02).unwrap()).unwrap();
    let mut state = system.state_at(0.0, 0.0);
    for _ in 0..1000 {
        system
            .step(&mut state, 0.0, 1e-3, Scheme::Implicit)
            .unwrap();
    }
    assert!((state.anchor - 0.02).abs() < 1e-15);
    // The mass follows: the spring never stretches beyond what friction can hold (Fs + σ2·v).
    let stretch = state.anchor - state.x;
    assert!(stretch.abs() < 2.0e-3, "stretch {stretch} m");
}

#[test]
fn the_friction_output_is_not_monotone_in_the_held_velocity() {
    // Why the mass step cannot assume it: in steady sliding on the falling Stribeck curve, a
    // faster held velocity gives a smaller force (σ2 = 0 here).
    let params = friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.0);
    let mut state = params.relaxed_state();
    for _ in 0..5000 {
        params
            .step(&mut state, 7e-4, 1e-4, Scheme::Implicit)
            .unwrap();
    }
    let at = |w: f64| {
        let mut copy = state;
        params.step(&mut copy, w, 1e-4, Scheme::Implicit).unwrap()
    };
    let (slow, fast) = (at(7e-4), at(8e-4));
    assert!(
        fast < slow - 1e-3,
        "F(0.7 mm/s) = {slow}, F(0.8 mm/s) = {fast}"
    );
}

/// Everything the step must satisfy, checked from outside with the public friction step.
fn check_step<const N: usize>(
    system: &MassSystem<MaxwellSlip<N>>,
    state: &mut gms_core::MassState<[f64; N]>,
    u: f64,
    dt: f64,
) -> Result<(), TestCaseError> {
    let before = *state;
    let sample = system.step(state, u, dt, Scheme::Implicit).unwrap();
    let (m, k) = (system.mass(), system.spring().stiffness());
    // The friction step's own output with the new velocity held, from the old friction state.
    let mut friction = before.friction;
    let own = system
        .friction()
        .step(&mut friction, sample.v, dt, Scheme::Implicit)
        .unwrap();
    // Force scale, times the sensitivity of the state equation: |Fh/g| can reach
    // sum(W)/min(Fc, Fc_neg), and the rate dz/dt carries it to the power n.
    let params = system.friction();
    let strength = params.hysteresis().max_force();
    let weakest = params.stribeck().fc().min(params.stribeck().fc_neg());
    let sensitivity = 1.0 + (strength / weakest).powf(params.n());
    let scale = (1.0 + u.abs() + strength) * sensitivity;
    prop_assert!(
        (own - sample.friction).abs() <= 1e-9 * scale,
        "{own} vs {}",
        sample.friction
    );
    // The two solvers stop within a few ulps of their own brackets; a stiff, light system
    // amplifies that (largest seen without the sensitivity factor: 1.1e-12 of z).
    let smallest = system
        .friction()
        .hysteresis()
        .delta()
        .iter()
        .fold(f64::INFINITY, |a, &b| a.min(b));
    let dz = (friction.z - state.friction.z).abs();
    prop_assert!(
        dz <= 1e-10 * (smallest + state.friction.z.abs()) * sensitivity,
        "z {} vs {}: {dz:e}",
        friction.z,
        state.friction.z
    );
    // Momentum balance of backward Euler, and x⁺ = x + dt·v⁺.
    let spring = k * (state.anchor - sample.x);
    let imbalance = m * (sample.v - before.v) / dt - (u + spring - sample.friction);
    prop_assert!(
        imbalance.abs() <= 1e-9 * (scale + m * before.v.abs() / dt),
        "{imbalance}"
    );
    prop_assert_eq!(sample.x, before.x + dt * sample.v);
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn every_step_solves_momentum_and_friction_together(
        params in leuven::<4>(),
        mass in log_uniform(1e-3, 1e2),
        stiffness in prop_oneof![Just(0.0), log_uniform(1.0, 1e6)],
        drive_speed in prop_oneof![Just(0.0), signed(log_uniform(1e-5, 1e-1))],
        dt in log_uniform(1e-5, 1e-3),
        forces in prop::collection::vec(signed(log_uniform(1e-3, 10.0)), 1..60),
    ) {
        let spring = Spring::dragged(stiffness, drive_speed).unwrap();
        let system = MassSystem::new(params, mass, spring).unwrap();
        let mut state = system.state_at(0.0, 0.0);
        for u in forces {
            check_step(&system, &mut state, u, dt)?;
        }
    }
}

#[test]
fn bad_parameters_name_the_field() {
    let params = friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4);
    for mass in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            MassSystem::new(params, mass, Spring::NONE),
            Err(Error::NotPositive {
                field: Field::mass,
                value: mass
            })
        );
    }
    for stiffness in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            Spring::ground(stiffness),
            Err(Error::Negative {
                field: Field::stiffness,
                value: stiffness
            })
        );
    }
    assert_eq!(
        Spring::dragged(1.0, f64::NAN),
        Err(Error::NotFiniteValue {
            field: Field::drive_speed,
            value: f64::NAN
        })
    );
    assert_eq!(
        Error::NotFiniteValue {
            field: Field::drive_speed,
            value: f64::NAN
        }
        .to_string(),
        "`drive_speed` must be finite, got nan"
    );
}

#[test]
fn bad_inputs_are_reported_and_leave_the_state_untouched() {
    let system = MassSystem::new(
        friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4),
        1.0,
        Spring::ground(10.0).unwrap(),
    )
    .unwrap();
    let mut state = system.state_at(1e-3, 0.0);
    system
        .step(&mut state, 0.3, 1e-3, Scheme::Implicit)
        .unwrap();
    let before = state;
    for dt in [0.0, -1e-3, f64::NAN] {
        assert_eq!(
            system.step(&mut state, 0.1, dt, Scheme::Implicit),
            Err(Error::NotPositive {
                field: Field::dt,
                value: dt
            })
        );
    }
    assert_eq!(
        system.step(&mut state, f64::NAN, 1e-3, Scheme::Implicit),
        Err(Error::NotFinite {
            field: Field::u,
            index: 0,
            value: f64::NAN
        })
    );
    let u = [0.1, 0.2, 0.3, f64::INFINITY, 0.5];
    let (mut f, mut x, mut v) = ([0.0; 5], [0.0; 5], [0.0; 5]);
    let result = system.simulate(
        &mut state,
        &u,
        1e-3,
        Scheme::Implicit,
        Trajectory {
            friction: &mut f,
            x: &mut x,
            v: &mut v,
        },
    );
    assert_eq!(
        result,
        Err(Error::NotFinite {
            field: Field::u,
            index: 3,
            value: f64::INFINITY
        })
    );
    let mut short = [0.0; 4];
    let result = system.simulate(
        &mut state,
        &u[..2],
        1e-3,
        Scheme::Implicit,
        Trajectory {
            friction: &mut short,
            x: &mut x,
            v: &mut v,
        },
    );
    assert_eq!(
        result,
        Err(Error::LengthMismatch {
            expected: 2,
            got: 4
        })
    );
    assert_eq!(state, before);
}

#[test]
fn a_block_run_equals_single_steps() {
    let system = MassSystem::new(
        friction([1.0, 1.0], [1e-6, 2e-6], 30.0, 0.4),
        0.5,
        Spring::dragged(200.0, 1e-3).unwrap(),
    )
    .unwrap();
    let u: Vec<f64> = (0..500)
        .map(|k| 2.0 * (f64::from(k) * 0.02).sin())
        .collect();
    let (mut f, mut x, mut v) = (vec![0.0; 500], vec![0.0; 500], vec![0.0; 500]);
    let mut block = system.state_at(0.0, 0.0);
    system
        .simulate(
            &mut block,
            &u,
            1e-3,
            Scheme::Implicit,
            Trajectory {
                friction: &mut f,
                x: &mut x,
                v: &mut v,
            },
        )
        .unwrap();
    let mut single = system.state_at(0.0, 0.0);
    for (k, &force) in u.iter().enumerate() {
        let sample = system
            .step(&mut single, force, 1e-3, Scheme::Implicit)
            .unwrap();
        assert_eq!((sample.friction, sample.x, sample.v), (f[k], x[k], v[k]));
    }
    assert_eq!(block, single);
    // The friction memory is the bank's: never more than N numbers, whatever the history.
    assert_eq!(single.friction.memory.len(), 2);
    let _ = system.friction().hysteresis().max_force();
}
