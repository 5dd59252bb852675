//! A 1 kHz position loop with friction compensation, then a block simulation of the same model.
//!
//! ```text
//! cargo run -p gms-core --example control_loop
//! ```
//!
//! The plant is a 1 kg mass with viscous damping whose friction is the model itself, with
//! "true" parameters, run as an observer of the plant's position. A PD controller tracks
//! `x_d(t) = A·(1 − cos 2πft)`; the [`Compensator`] (feedforward mode, nominal parameters) adds
//! the friction force predicted along the desired velocity. The loop runs once without and once
//! with compensation and prints the RMS tracking error of each. Then [`Params::simulate`] runs
//! the whole desired-velocity signal in one call: the block form of the same model.
use gms_core::{Compensator, Error, LeuvenParams, MaxwellSlip, Mode, Params, Scheme, Stribeck};

const DT: f64 = 1e-3;
const SAMPLES: usize = 2000;
const MASS: f64 = 1.0;
const DAMPING: f64 = 2.0;
const KP: f64 = 4000.0;
const KD: f64 = 80.0;
const AMPLITUDE: f64 = 2e-4;
const FREQUENCY: f64 = 2.0;

fn params(fc: f64, fs: f64, w: [f64; 4]) -> Result<LeuvenParams<4>, Error> {
    let stribeck = Stribeck::new(fc, fs, 1e-3, 2.0)?;
    let elements = MaxwellSlip::new(w, [1e-6, 2e-6, 4e-6, 8e-6])?;
    Params::new(stribeck, 2.0, 30.0, 0.4, elements)
}

/// Desired position and velocity at sample `k`.
fn desired(k: usize) -> (f64, f64) {
    let phase = 2.0 * core::f64::consts::PI * FREQUENCY * k as f64 * DT;
    let omega = 2.0 * core::f64::consts::PI * FREQUENCY;
    (
        AMPLITUDE * (1.0 - phase.cos()),
        AMPLITUDE * omega * phase.sin(),
    )
}

/// The RMS tracking error [m] of the loop, with or without the compensator.
fn run(compensate: bool) -> Result<f64, Error> {
    let truth = params(1.1, 1.7, [0.7, 0.6, 0.4, 0.3])?;
    let nominal = params(1.0, 1.5, [0.6, 0.5, 0.4, 0.3])?;
    let mut plant_friction = Compensator::new(truth, DT, Mode::Observer)?;
    let mut compensator = Compensator::new(nominal, DT, Mode::Feedforward)?;
    let (mut x, mut v, mut squared) = (0.0, 0.0, 0.0);
    for k in 0..SAMPLES {
        let (x_desired, v_desired) = desired(k);
        squared += (x_desired - x).powi(2);
        // One sample of the controller: no allocation, no panic; an Err keeps the last force.
        let feedforward = if compensate {
            compensator.step(v_desired)?
        } else {
            0.0
        };
        let command = KP * (x_desired - x) + KD * (v_desired - v) + feedforward;
        let friction = plant_friction.step(x)?;
        v += DT * (command - DAMPING * v - friction) / MASS;
        x += DT * v;
    }
    Ok((squared / SAMPLES as f64).sqrt())
}

fn main() -> Result<(), Error> {
    let without = run(false)?;
    let with = run(true)?;
    println!("RMS tracking error without compensation: {without:.3e} m");
    println!("RMS tracking error with compensation:    {with:.3e} m");

    // The block form: the friction force along the whole desired velocity in one call.
    let model = params(1.0, 1.5, [0.6, 0.5, 0.4, 0.3])?;
    let velocity: Vec<f64> = (0..SAMPLES).map(|k| desired(k).1).collect();
    let mut force = vec![0.0; SAMPLES];
    let mut state = model.relaxed_state();
    model.simulate(&mut state, &velocity, DT, Scheme::Implicit, &mut force)?;
    let peak = force.iter().fold(0.0f64, |peak, f| peak.max(f.abs()));
    println!("block simulation: {SAMPLES} samples, peak friction force {peak:.3} N");
    Ok(())
}
