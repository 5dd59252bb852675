//! Builds only if gms-core needs neither `std` nor `alloc`.
//!
//! This static library is `#![no_std]`, defines its own panic handler and no global allocator.
//! If gms-core pulled in `std`, the panic handler would be defined twice; if it allocated, the
//! link would ask for a global allocator that does not exist. Either way the build fails.
#![no_std]

use gms_core::{LeuvenParams, Linear, LuGreParams, MaxwellSlip, Scheme, Stribeck};

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
    let Ok(leuven) = LeuvenParams::new(stribeck, 2.0, 10.0, 0.4, elements) else {
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
    total
}
