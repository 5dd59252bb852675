//! Channels of the friction model that share one validated parameter set, whatever its number
//! of elements: stepped one at a time, or run over blocks in parallel, all or nothing.

// The hysteresis types a bank holds and what its rows are: with the `batch` feature those that
// gms-batch steps in lanes (every one gms-core has) and gms-batch's `Signal`, without it any of
// gms-core's and this crate's own `Signal` of the same shape.
#[cfg(feature = "batch")]
use gms_batch::{BatchHysteresis as BankHysteresis, Signal};
#[cfg(not(feature = "batch"))]
use gms_core::Hysteresis as BankHysteresis;
use gms_core::{Hysteresis, Level, Params, PositionForce, Scheme, State};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::channels::{
    all_or_nothing, check_channel, check_output, samples_per_channel, states, Memory,
};
use crate::error::Error;
use crate::params::{with_params, ParameterSet};

/// What the input signal of a friction channel is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Input {
    /// Velocity v \[m/s\].
    Velocity,
    /// Position x \[m\]; the velocity is its difference over dt.
    Position,
}

/// Channels of one friction model sharing one parameter set.
pub struct FrictionBank {
    channels: Box<dyn FrictionChannels>,
}

/// The bank for one hysteresis type, behind a trait object so that N is chosen at run time.
trait FrictionChannels: Send + Sync {
    fn channels(&self) -> usize;
    fn elements(&self) -> usize;
    fn scheme(&self) -> Scheme;
    fn step(&mut self, channel: usize, input: f64, dt: f64, kind: Input) -> Result<f64, Error>;
    fn run(
        &mut self,
        input: &[f64],
        dt: f64,
        signal: Signal<'_>,
        out: &mut [f64],
    ) -> Result<(), Error>;
    fn trace_position(
        &mut self,
        channel: usize,
        x: &[f64],
        dt: f64,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error>;
    fn reset(&mut self);
    fn read_state(
        &self,
        z: &mut [f64],
        memory: &mut [f64],
        last: &mut [f64],
        has_last: &mut [bool],
    );
    fn write_state(
        &mut self,
        z: &[f64],
        memory: &[f64],
        last: &[f64],
        has_last: &[bool],
    ) -> Result<(), Error>;
}

struct Channels<H: Hysteresis> {
    params: Params<H>,
    states: Vec<State<H::Memory>>,
    scheme: Scheme,
}

impl<H> FrictionChannels for Channels<H>
where
    H: BankHysteresis<Memory: Memory> + Send + Sync,
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

    fn step(&mut self, channel: usize, input: f64, dt: f64, kind: Input) -> Result<f64, Error> {
        check_channel(channel, self.states.len())?;
        let state = &mut self.states[channel];
        let result = match kind {
            Input::Velocity => self.params.step(state, input, dt, self.scheme),
            Input::Position => self.params.step_position(state, input, dt, self.scheme),
        };
        Ok(result?)
    }

    fn run(
        &mut self,
        input: &[f64],
        dt: f64,
        signal: Signal<'_>,
        out: &mut [f64],
    ) -> Result<(), Error> {
        let samples = samples_per_channel(input.len(), self.states.len())?;
        check_output(input.len(), out.len())?;
        if let Signal::VelocityAt { x, .. } = signal {
            if x.len() != input.len() {
                return Err(gms_core::Error::InputLengthMismatch {
                    field: gms_core::Field::x,
                    expected: input.len(),
                    got: x.len(),
                }
                .into());
            }
        }
        let (params, scheme) = (&self.params, self.scheme);
        if samples == 0 {
            // Nothing to run: dt is checked on a scratch state, no channel is copied or touched.
            return Ok(params.simulate(&mut params.relaxed_state(), &[], dt, scheme, &mut [])?);
        }
        // Only the first failing channel is kept: a result per channel would be one more
        // allocation the size of the bank, and an infallible one.
        all_or_nothing(&mut self.states, |states| {
            #[cfg(feature = "parallel")]
            if states.len() > 1 {
                // Whole groups (of lanes, with `batch`) go to the threads.
                let block = GROUP * samples;
                return states
                    .par_chunks_mut(GROUP)
                    .zip(input.par_chunks(block).zip(out.par_chunks_mut(block)))
                    .enumerate()
                    .filter_map(|(group, (states, (input, out)))| {
                        let start = group * block;
                        let signal = signal.rows(start..start + input.len());
                        run_rows(params, states, input, samples, dt, scheme, signal, out)
                            .map(|(channel, error)| (group * GROUP + channel, error))
                    })
                    .min_by_key(|(channel, _)| *channel);
            }
            // One channel needs no thread pool; without the `parallel` feature none is used.
            run_rows(params, states, input, samples, dt, scheme, signal, out)
        })
    }

    fn trace_position(
        &mut self,
        channel: usize,
        x: &[f64],
        dt: f64,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error> {
        check_channel(channel, self.states.len())?;
        Ok(self.params.simulate_position_deflection(
            &mut self.states[channel],
            x,
            dt,
            self.scheme,
            out,
            z,
        )?)
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
            memory[channel * n..(channel + 1) * n].copy_from_slice(state.memory.values());
            last[channel] = state.last_position.unwrap_or(0.0);
            has_last[channel] = state.last_position.is_some();
        }
    }

    fn write_state(
        &mut self,
        z: &[f64],
        memory: &[f64],
        last: &[f64],
        has_last: &[bool],
    ) -> Result<(), Error> {
        let n = <H::Memory as Memory>::LEN;
        let state_of = |channel: usize| {
            let mut state = self.params.relaxed_state();
            state.z = z[channel];
            state.memory.write(&memory[channel * n..(channel + 1) * n]);
            state.last_position = has_last[channel].then_some(last[channel]);
            state
        };
        // Every channel is checked before any is written: all or nothing.
        for channel in 0..self.states.len() {
            self.params
                .check_state(&state_of(channel))
                .map_err(|error| Error::State { channel, error })?;
        }
        for channel in 0..self.states.len() {
            self.states[channel] = state_of(channel);
        }
        Ok(())
    }
}

/// What the rows of a run are, and the position-dependent terms on their output
/// (docs/model.md#position-dependent-level): gms-batch's `Signal`, for the build without it.
#[cfg(not(feature = "batch"))]
#[derive(Clone, Copy, Debug)]
enum Signal<'a> {
    /// Velocities v: `Params::simulate`.
    Velocity,
    /// Velocities v with the position of every sample, `x` (the input's shape), which places
    /// the level and the position force: `Params::simulate_level`.
    VelocityAt {
        x: &'a [f64],
        level: &'a Level,
        force: &'a PositionForce,
    },
    /// Positions x with a level and a position force: `Params::simulate_position`, or
    /// `Params::simulate_position_level` when either is given.
    Position {
        level: &'a Level,
        force: &'a PositionForce,
    },
}

#[cfg(not(feature = "batch"))]
impl Signal<'_> {
    /// The signal of the channels whose samples are `rows` of the input (the positions of
    /// [`Signal::VelocityAt`] cut like the input), for running them apart.
    fn rows(self, rows: core::ops::Range<usize>) -> Self {
        match self {
            Signal::VelocityAt { x, level, force } => Signal::VelocityAt {
                x: &x[rows],
                level,
                force,
            },
            other => other,
        }
    }
}

/// The channels the threads take at a time: a group of gms-batch's lanes, or one channel.
#[cfg(all(feature = "parallel", feature = "batch"))]
const GROUP: usize = gms_batch::LANES;
#[cfg(all(feature = "parallel", not(feature = "batch")))]
const GROUP: usize = 1;

/// Runs each of `states` over its row of `samples` (> 0) in `input`, writing the forces into
/// `out`; the first failing channel (lowest index) and gms-core's error for it, whose state is
/// as before (the others may have advanced: the caller restores them).
///
/// gms-batch steps the channels several at a time (LANES of them in SIMD lanes), the level and
/// the position force included, and hands any group with a rejected sample to gms-core's block
/// calls, which check dt and scan each row for finiteness before they step: the one check, and
/// the same errors.
#[cfg(feature = "batch")]
#[allow(clippy::too_many_arguments)] // gms-core's block call, plus the shape
fn run_rows<H: BankHysteresis>(
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, gms_core::Error)> {
    gms_batch::run(params, states, input, samples, dt, scheme, signal, out)
}

/// [`run_rows`] without gms-batch (the C library, which steps one compensator per call and
/// leaves the batch kernels out): the channels one after the other through gms-core's block
/// calls, which check dt and scan each row for finiteness before they step. The forces, states
/// and errors are those of the batch build, which hands its rejected groups to the same calls.
#[cfg(not(feature = "batch"))]
#[allow(clippy::too_many_arguments)] // gms-core's block call, plus the shape
fn run_rows<H: BankHysteresis>(
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, gms_core::Error)> {
    states
        .iter_mut()
        .zip(input.chunks(samples).zip(out.chunks_mut(samples)))
        .enumerate()
        .find_map(|(channel, (state, (input, out)))| {
            let result = match signal.rows(channel * samples..(channel + 1) * samples) {
                Signal::Velocity => params.simulate(state, input, dt, scheme, out),
                Signal::VelocityAt { x, level, force } => {
                    params.simulate_level(state, input, x, dt, scheme, level, force, out)
                }
                Signal::Position { level, force } if level.is_flat() && force.is_none() => {
                    params.simulate_position(state, input, dt, scheme, out)
                }
                Signal::Position { level, force } => {
                    params.simulate_position_level(state, input, dt, scheme, level, force, out)
                }
            };
            result.err().map(|error| (channel, error))
        })
}

fn boxed<H>(
    params: Params<H>,
    channels: usize,
    scheme: Scheme,
) -> Result<Box<dyn FrictionChannels>, Error>
where
    H: BankHysteresis<Memory: Memory> + Send + Sync + 'static,
{
    Ok(Box::new(Channels {
        states: states(params.relaxed_state(), channels)?,
        params,
        scheme,
    }))
}

impl FrictionBank {
    /// `channels` relaxed channels of `params`.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the states do not fit in memory.
    pub fn new(params: &ParameterSet, channels: usize, scheme: Scheme) -> Result<Self, Error> {
        Ok(Self {
            channels: with_params!(*params, params => boxed(params, channels, scheme)?),
        })
    }

    /// Number of channels B.
    pub fn channels(&self) -> usize {
        self.channels.channels()
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    pub fn elements(&self) -> usize {
        self.channels.elements()
    }

    /// The integration scheme of every step.
    pub fn scheme(&self) -> Scheme {
        self.channels.scheme()
    }

    /// One step of `channel` with `input` held over `dt`; returns the force.
    ///
    /// # Errors
    /// A channel index beyond the bank, a non-finite input, a bad `dt`, or a diverged explicit
    /// step; the state is unchanged.
    pub fn step(&mut self, channel: usize, input: f64, dt: f64, kind: Input) -> Result<f64, Error> {
        self.channels.step(channel, input, dt, kind)
    }

    /// Runs every channel over its row of `input` (channels × samples, row-major), in parallel,
    /// writing the forces into `out` (same shape).
    ///
    /// # Errors
    /// All or nothing: a rejected call changes no state; the error names the sample, and the
    /// channel when there are several.
    pub fn run(
        &mut self,
        input: &[f64],
        dt: f64,
        kind: Input,
        out: &mut [f64],
    ) -> Result<(), Error> {
        let signal = match kind {
            Input::Velocity => Signal::Velocity,
            Input::Position => Signal::Position {
                level: &Level::none(),
                force: &PositionForce::none(),
            },
        };
        self.channels.run(input, dt, signal, out)
    }

    /// [`FrictionBank::run`] on positions `x` with a position-dependent level and a position
    /// force (docs/model.md#position-dependent-level): each force is
    /// factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x). The states evolve as without them; none of
    /// either gives the plain forces bit for bit.
    ///
    /// # Errors
    /// As [`FrictionBank::run`]; a force that the terms make non-finite is a divergence.
    pub fn run_position_level(
        &mut self,
        x: &[f64],
        dt: f64,
        level: &Level,
        position_force: &PositionForce,
        out: &mut [f64],
    ) -> Result<(), Error> {
        let signal = Signal::Position {
            level,
            force: position_force,
        };
        self.channels.run(x, dt, signal, out)
    }

    /// [`FrictionBank::run`] on velocities `v` with the position of every sample, `x` (the
    /// same shape), which places the level and the position force: gms-core's
    /// `Params::simulate_level` on every channel, as a log with a measured velocity column
    /// drives the model. The states evolve as on `v` alone.
    ///
    /// # Errors
    /// As [`FrictionBank::run`], and `gms_core::Error::InputLengthMismatch` naming `x` when it
    /// is not the shape of `v`; a non-finite position is refused naming `x`, the sample and
    /// the channel.
    pub fn run_level(
        &mut self,
        v: &[f64],
        x: &[f64],
        dt: f64,
        level: &Level,
        position_force: &PositionForce,
        out: &mut [f64],
    ) -> Result<(), Error> {
        let signal = Signal::VelocityAt {
            x,
            level,
            force: position_force,
        };
        self.channels.run(v, dt, signal, out)
    }

    /// Runs `channel` over positions `x`, writing the forces into `out` and the deflection z
    /// after every sample into `z`.
    ///
    /// # Errors
    /// As [`FrictionBank::run`] for that channel.
    pub fn trace_position(
        &mut self,
        channel: usize,
        x: &[f64],
        dt: f64,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error> {
        self.channels.trace_position(channel, x, dt, out, z)
    }

    /// Relaxes every channel: z = 0, elements undeflected, no previous position.
    pub fn reset(&mut self) {
        self.channels.reset();
    }

    /// Copies the states out: z (B), memory (B × N, row-major), last position (B, 0 where
    /// there is none) and whether there is one (B).
    ///
    /// # Panics
    /// If a slice has another length.
    pub fn read_state(
        &self,
        z: &mut [f64],
        memory: &mut [f64],
        last_position: &mut [f64],
        has_last_position: &mut [bool],
    ) {
        self.assert_state_lengths(
            z.len(),
            memory.len(),
            last_position.len(),
            has_last_position.len(),
        );
        self.channels
            .read_state(z, memory, last_position, has_last_position);
    }

    /// Copies states in; the slices are shaped as for [`FrictionBank::read_state`].
    ///
    /// # Errors
    /// [`Error::State`] naming the first channel whose state breaks a rule
    /// ([`Params::check_state`]: z and the previous position finite, every element within its
    /// window); then no channel is written.
    ///
    /// # Panics
    /// If a slice has another length.
    pub fn write_state(
        &mut self,
        z: &[f64],
        memory: &[f64],
        last_position: &[f64],
        has_last_position: &[bool],
    ) -> Result<(), Error> {
        self.assert_state_lengths(
            z.len(),
            memory.len(),
            last_position.len(),
            has_last_position.len(),
        );
        self.channels
            .write_state(z, memory, last_position, has_last_position)
    }

    fn assert_state_lengths(&self, z: usize, memory: usize, last: usize, has_last: usize) {
        let (b, n) = (self.channels(), self.elements());
        assert!(
            z == b && memory == b * n && last == b && has_last == b,
            "state slices must have lengths {b}, {b}×{n}, {b}, {b}"
        );
    }
}
