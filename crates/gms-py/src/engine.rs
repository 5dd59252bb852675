//! Many channels of one validated model, whatever its number of elements.
//!
//! gms-core fixes the number of Maxwell-slip elements in the type; Python picks it at run time.
//! `build` bridges the two by monomorphising the bank for every N up to [`MAX_ELEMENTS`] and
//! handing it back behind the object-safe [`Engine`] trait.

use gms_core::{Error, Hysteresis, Params, Scheme, State};
use pyo3::PyResult;
use rayon::prelude::*;
use seq_macro::seq;

use crate::bank::{all_or_nothing, first_failure, Memory};
use crate::errors::{InputError, ParameterError};
use crate::spec::Spec;

/// The largest number of Maxwell-slip elements the Python package accepts.
pub const MAX_ELEMENTS: usize = 32;

/// A block of channels that share one parameter set.
pub trait Engine: Send + Sync {
    fn channels(&self) -> usize;
    /// Number of hysteresis memory slots per channel (N, or 0 for a linear spring).
    fn elements(&self) -> usize;
    fn scheme(&self) -> Scheme;
    /// One step of one channel; `position` selects position input.
    fn step(&mut self, channel: usize, input: f64, dt: f64, position: bool) -> Result<f64, Error>;
    /// Runs every channel over its row of `input` (channels × samples, row-major), in parallel.
    /// Inputs are checked before any state changes; the error names the channel.
    fn run(
        &mut self,
        input: &[f64],
        dt: f64,
        position: bool,
        out: &mut [f64],
    ) -> Result<(), (usize, Error)>;
    /// Runs channel 0 over positions `x`, also writing the deflection z after every sample.
    fn run_position_deflection(
        &mut self,
        x: &[f64],
        dt: f64,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error>;
    fn reset(&mut self);
    /// Copies the states out: z (B), memory (B × N), last position (B) and whether it exists.
    fn read_state(
        &self,
        z: &mut [f64],
        memory: &mut [f64],
        last: &mut [f64],
        has_last: &mut [bool],
    );
    /// Copies states in; slices have the lengths `read_state` uses.
    fn write_state(&mut self, z: &[f64], memory: &[f64], last: &[f64], has_last: &[bool]);
}

/// One channel's state with its input row and output row.
type ChannelWork<'a, M> = (&'a mut State<M>, (&'a [f64], &'a mut [f64]));

struct Bank<H: Hysteresis> {
    params: Params<H>,
    states: Vec<State<H::Memory>>,
    scheme: Scheme,
}

impl<H> Engine for Bank<H>
where
    H: Hysteresis + Send + Sync,
    H::Memory: Memory,
{
    fn channels(&self) -> usize {
        self.states.len()
    }

    fn elements(&self) -> usize {
        <H::Memory as Memory>::LEN
    }

    fn scheme(&self) -> Scheme {
        self.scheme
    }

    fn step(&mut self, channel: usize, input: f64, dt: f64, position: bool) -> Result<f64, Error> {
        let state = &mut self.states[channel];
        if position {
            self.params.step_position(state, input, dt, self.scheme)
        } else {
            self.params.step(state, input, dt, self.scheme)
        }
    }

    fn run(
        &mut self,
        input: &[f64],
        dt: f64,
        position: bool,
        out: &mut [f64],
    ) -> Result<(), (usize, Error)> {
        let samples = input
            .len()
            .checked_div(self.states.len())
            .unwrap_or(0)
            .max(1);
        if let Some(index) = input.iter().position(|value| !value.is_finite()) {
            let field = if position {
                gms_core::Field::x
            } else {
                gms_core::Field::v
            };
            return Err((
                index / samples,
                Error::NotFinite {
                    field,
                    index: index % samples,
                },
            ));
        }
        let (params, scheme) = (&self.params, self.scheme);
        let run_one = |(state, (input, out)): ChannelWork<'_, H::Memory>| {
            if position {
                params.simulate_position(state, input, dt, scheme, out)
            } else {
                params.simulate(state, input, dt, scheme, out)
            }
        };
        if self.states.len() <= 1 {
            // One channel: gms-core's own all-or-nothing is enough, no copy needed.
            return first_failure(
                self.states
                    .iter_mut()
                    .zip(input.chunks(samples).zip(out.chunks_mut(samples)))
                    .map(run_one),
            );
        }
        all_or_nothing(&mut self.states, |states| {
            states
                .par_iter_mut()
                .zip(input.par_chunks(samples).zip(out.par_chunks_mut(samples)))
                .map(run_one)
                .collect()
        })
    }

    fn run_position_deflection(
        &mut self,
        x: &[f64],
        dt: f64,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error> {
        self.params
            .simulate_position_deflection(&mut self.states[0], x, dt, self.scheme, out, z)
    }

    fn reset(&mut self) {
        let relaxed = self.params.relaxed_state();
        self.states.iter_mut().for_each(|state| *state = relaxed);
    }

    fn read_state(
        &self,
        z: &mut [f64],
        memory: &mut [f64],
        last: &mut [f64],
        has_last: &mut [bool],
    ) {
        let n = <H::Memory as Memory>::LEN;
        for (channel, state) in self.states.iter().enumerate() {
            z[channel] = state.z;
            state
                .memory
                .read(&mut memory[channel * n..(channel + 1) * n]);
            last[channel] = state.last_position.unwrap_or(0.0);
            has_last[channel] = state.last_position.is_some();
        }
    }

    fn write_state(&mut self, z: &[f64], memory: &[f64], last: &[f64], has_last: &[bool]) {
        let n = <H::Memory as Memory>::LEN;
        for (channel, state) in self.states.iter_mut().enumerate() {
            state.z = z[channel];
            state.memory.write(&memory[channel * n..(channel + 1) * n]);
            state.last_position = has_last[channel].then_some(last[channel]);
        }
    }
}

fn bank<H>(params: Params<H>, channels: usize, scheme: Scheme) -> PyResult<Box<dyn Engine>>
where
    H: Hysteresis + Send + Sync + 'static,
    H::Memory: Memory,
{
    // A channel count that does not fit in memory must be an error, not an abort.
    let mut states = Vec::new();
    states.try_reserve_exact(channels).map_err(|_| {
        InputError::new_err(format!(
            "`channels` = {channels} does not fit in memory ({} bytes of state each)",
            core::mem::size_of::<State<H::Memory>>()
        ))
    })?;
    states.resize(channels, params.relaxed_state());
    Ok(Box::new(Bank {
        params,
        states,
        scheme,
    }))
}

/// Validates `spec` and returns `channels` relaxed channels of it.
pub fn build(spec: &Spec, channels: usize, scheme: Scheme) -> PyResult<Box<dyn Engine>> {
    if let Some(sigma0) = spec.sigma0 {
        if spec.maxwell_given {
            return Err(ParameterError::new_err(
                "give either `sigma0` (linear hysteresis) or `W` + `Delta` (Maxwell slip), got both",
            ));
        }
        return bank(spec.lugre(sigma0)?, channels, scheme);
    }
    seq!(N in 1..=32 {
        match spec.w.len() {
            #(N => bank(spec.maxwell::<N>()?, channels, scheme),)*
            0 if spec.maxwell_given => Err(ParameterError::new_err(
                "`W` and `Delta` need at least one element, got empty sequences",
            )),
            0 => Err(ParameterError::new_err(
                "give either `sigma0` (linear hysteresis) or `W` + `Delta` (Maxwell slip), got neither",
            )),
            count => Err(ParameterError::new_err(format!(
                "`W` and `Delta` may have at most {MAX_ELEMENTS} elements, got {count}"
            ))),
        }
    })
}
