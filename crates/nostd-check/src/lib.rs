//! Builds only if gms-core needs neither `std` nor `alloc`.
//!
//! This static library is `#![no_std]`, defines its own panic handler and no global allocator.
//! If gms-core pulled in `std`, the panic handler would be defined twice; if it allocated, the
//! link would ask for a global allocator that does not exist. Either way the build fails.
#![no_std]

use gms_core::{
    Compensator, LeuvenParams, Level, Linear, LuGreParams, MaxwellSlip, Mode, PositionForce,
    RippleTerms, Scheme, Stribeck,
};

#[panic_handler]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

/// Runs a 10-element Leuven model and a LuGre model over a short velocity ramp and returns the
/// sum of their forces, or NaN if the parameters were rejected.
#[no_mangle]
pub extern "C" fn nostd_check_run(dt: f64) -> f64 {
    let Ok(stribeck) = Stribeck::new(1.0, 1.5, 1e-3, 2.0) else {
        return f64::NAN;
    };
    let Ok(elements) = MaxwellSlip::new(
        [0.2; 10],
        [1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 7e-6, 8e-6, 9e-6, 1e-5],
    ) else {
        return f64::NAN;
    };
    let Ok(leuven) =
        LeuvenParams::new(stribeck, 2.0, 10.0, 0.4, elements).and_then(|p| p.with_sigma2_neg(0.6))
    else {
        return f64::NAN;
    };
    let Ok(spring) = Linear::new(1e5) else {
        return f64::NAN;
    };
    let Ok(lugre) = LuGreParams::new(stribeck, 1.0, 316.0, 0.4, spring) else {
        return f64::NAN;
    };

    let velocities = [0.0, 1e-4, 1e-3, 1e-2, -1e-3, 0.0];
    let mut forces = [0.0; 6];
    let mut total = 0.0;
    let mut channel = leuven.relaxed_state();
    if leuven
        .simulate(&mut channel, &velocities, dt, Scheme::Implicit, &mut forces)
        .is_ok()
    {
        total += forces.iter().sum::<f64>();
    }
    let mut channel = lugre.relaxed_state();
    for &v in &velocities {
        total += lugre
            .step(&mut channel, v, dt, Scheme::Explicit)
            .unwrap_or(f64::NAN);
    }
    // A position-dependent level: a trend and one ripple of two harmonics.
    let ripple = RippleTerms {
        period: 0.004,
        cos: &[0.03, 0.01],
        sin: &[0.0, 0.02],
    };
    let Ok(level) = Level::new(0.0, 0.01, [0.05, -0.02], &[ripple]) else {
        return f64::NAN;
    };
    // A position force of the same shape, in newtons.
    let Ok(force) = PositionForce::new(0.0, 0.01, [0.5, 0.0], &[ripple]) else {
        return f64::NAN;
    };
    if leuven
        .simulate_position_level(
            &mut leuven.relaxed_state(),
            &velocities,
            dt,
            Scheme::Implicit,
            &level,
            &force,
            &mut forces,
        )
        .is_ok()
    {
        total += forces.iter().sum::<f64>();
    }
    // Velocity input with positions for the two terms.
    if leuven
        .simulate_level(
            &mut leuven.relaxed_state(),
            &velocities,
            &velocities,
            dt,
            Scheme::Implicit,
            &level,
            &force,
            &mut forces,
        )
        .is_ok()
    {
        total += forces.iter().sum::<f64>();
    }
    // The compensator in both modes, with the terms, a parameter swap between two samples and
    // trajectory steps.
    for mode in [Mode::Feedforward, Mode::Observer] {
        let Ok(mut compensator) = Compensator::new(leuven, dt, mode)
            .and_then(|c| c.with_start_position(1e-3))
            .and_then(|c| c.with_level(level))
            .and_then(|c| c.with_position_force(force))
        else {
            return f64::NAN;
        };
        for (k, &v) in velocities.iter().enumerate() {
            if k == 3 {
                compensator.set_params(leuven);
            }
            total += compensator.step(v).unwrap_or(f64::NAN);
            total += compensator.step_trajectory(v, 1e-3 + v).unwrap_or(f64::NAN);
        }
    }
    total
}

/// Runs online identification (recursive least squares, nalgebra fixed-size matrices) with 10
/// elements over a short log and returns the sum of its estimate, or NaN if it was rejected.
#[no_mangle]
pub extern "C" fn nostd_check_identify(dt: f64) -> f64 {
    let settings = gms_core::RlsSettings {
        forgetting: 0.999,
        initial_covariance: 1e3,
        max_trace: 1e5,
    };
    let delta = [1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 7e-6, 8e-6, 9e-6, 1e-5];
    let Ok(mut identifier) = gms_core::OnlineIdentifier::<10, 13>::new(delta, [0.0; 13], settings)
    else {
        return f64::NAN;
    };
    let velocities = [0.0, 1e-4, 1e-3, 1e-2, -1e-3, 0.0];
    let mut x = 0.0;
    for &v in &velocities {
        x += v * dt;
        if identifier.update(x, v, 0.3 * v + 0.1).is_err() {
            return f64::NAN;
        }
    }
    identifier.estimate().iter().sum()
}

/// Runs a mass on a 10-element Leuven model, dragged through a spring (the stick-slip rig), one
/// sample at a time and as a block, in both schemes; returns the final position, or NaN if
/// anything was rejected.
#[no_mangle]
pub extern "C" fn nostd_check_mass(dt: f64) -> f64 {
    let Ok(stribeck) = Stribeck::new(1.0, 1.5, 1e-3, 2.0) else {
        return f64::NAN;
    };
    let Ok(elements) = MaxwellSlip::new([0.2; 10], [2e-6; 10]) else {
        return f64::NAN;
    };
    let Ok(friction) = LeuvenParams::new(stribeck, 2.0, 10.0, 0.4, elements) else {
        return f64::NAN;
    };
    let Ok(spring) = gms_core::Spring::dragged(1e3, 1e-3) else {
        return f64::NAN;
    };
    let Ok(system) = gms_core::MassSystem::new(friction, 1.0, spring) else {
        return f64::NAN;
    };
    let mut state = system.state_at(0.0, 0.0);
    let forces = [0.0, 0.5, 1.0, 2.0, -1.0, 0.0];
    let (mut friction, mut x, mut v) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    let out = gms_core::Trajectory {
        friction: &mut friction,
        x: &mut x,
        v: &mut v,
    };
    if system
        .simulate(&mut state, &forces, dt, Scheme::Implicit, out)
        .is_err()
    {
        return f64::NAN;
    }
    for &u in &forces {
        if system.step(&mut state, u, dt, Scheme::Explicit).is_err() {
            return f64::NAN;
        }
    }
    state.x
}

/// The analysis block calls: a position run that records z, and Maxwell-slip responses along a
/// path; returns the sum of everything they wrote, or NaN if anything was rejected.
#[no_mangle]
pub extern "C" fn nostd_check_traces(dt: f64) -> f64 {
    let Ok(stribeck) = Stribeck::new(1.0, 1.5, 1e-3, 2.0) else {
        return f64::NAN;
    };
    let Ok(elements) = MaxwellSlip::new([0.8, 0.8], [1e-6, 2e-6]) else {
        return f64::NAN;
    };
    let Ok(params) = LeuvenParams::new(stribeck, 2.0, 0.0, 0.0, elements) else {
        return f64::NAN;
    };
    let x = [0.0, 1e-6, 3e-6, 2e-6, -1e-6, 0.0];
    let (mut force, mut z, mut responses) = ([0.0; 6], [0.0; 6], [0.0; 12]);
    let mut state = params.relaxed_state();
    let Ok(()) = params.simulate_position_deflection(
        &mut state,
        &x,
        dt,
        Scheme::Implicit,
        &mut force,
        &mut z,
    ) else {
        return f64::NAN;
    };
    let Ok(mut regressor) = gms_core::SlipRegressor::new([1e-6, 2e-6]) else {
        return f64::NAN;
    };
    if regressor.responses(&x, &mut responses).is_err() {
        return f64::NAN;
    }
    force.iter().chain(&z).chain(&responses).sum()
}
