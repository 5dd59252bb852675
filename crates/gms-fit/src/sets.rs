//! Many parameter sets along one signal: what a line search or a screening of candidates runs,
//! one set per thread of rayon's pool.

use gms_core::{Hysteresis, Params};
use gms_dyn::{Input, ParameterSet};
use rayon::prelude::*;

use crate::error::{Error, Output};
use crate::Simulation;

/// gms-core's block call for one set, from a relaxed channel.
fn simulate<H: Hysteresis>(
    params: &Params<H>,
    simulation: &Simulation<'_>,
    out: &mut [f64],
) -> Result<(), gms_core::Error> {
    let Simulation {
        signal,
        input,
        dt,
        scheme,
    } = *simulation;
    let mut state = params.relaxed_state();
    match input {
        Input::Velocity => params.simulate(&mut state, signal, dt, scheme, out),
        Input::Position => params.simulate_position(&mut state, signal, dt, scheme, out),
    }
}

/// The friction force of every parameter set in `sets` along one signal, each from a relaxed
/// channel, written into `forces` (sets × samples, row-major); the sets run in parallel.
///
/// Each row is gms-core's [`Params::simulate`] (or `simulate_position`) of its set, bit for bit.
/// The sets may differ in their number of elements and kind of hysteresis.
///
/// # Errors
/// [`Error::OutputLength`] if `forces` is not sets × samples long; [`Error::Set`] naming the
/// first set (lowest index) whose run gms-core refused, and the sample. `forces` is then
/// written only in part.
pub fn simulate_sets(
    sets: &[ParameterSet],
    simulation: Simulation<'_>,
    forces: &mut [f64],
) -> Result<(), Error> {
    let samples = simulation.signal.len();
    let expected = sets.len().saturating_mul(samples);
    if forces.len() != expected {
        return Err(Error::OutputLength {
            output: Output::Forces,
            expected,
            got: forces.len(),
        });
    }
    let run = |set: &ParameterSet, out: &mut [f64]| gms_dyn::with_params!(set, params => simulate(params, &simulation, out));
    let first_failure = if samples == 0 {
        // No rows to split; gms-core still checks dt, as its block calls do on empty input.
        sets.iter()
            .enumerate()
            .find_map(|(set, params)| run(params, &mut []).err().map(|error| (set, error)))
    } else {
        forces
            .par_chunks_mut(samples)
            .zip(sets.par_iter())
            .enumerate()
            .filter_map(|(set, (out, params))| run(params, out).err().map(|error| (set, error)))
            .min_by_key(|(set, _)| *set)
    };
    first_failure.map_or(Ok(()), |(set, error)| Err(Error::Set { set, error }))
}
