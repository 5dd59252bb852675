//! Channels of a mass on the friction model (gms-core's `MassSystem`) that share one parameter
//! set and one set of mechanics, whatever the number of elements.

use gms_core::{Hysteresis, MassSample, MassState, MassSystem, Params, Scheme, Spring, Trajectory};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::channels::{
    all_or_nothing, check_channel, check_output, samples_per_channel, states, Memory,
};
use crate::error::Error;
use crate::params::{with_params, ParameterSet};

/// The mechanical parameters of a mass system, as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mechanics {
    /// Mass m \[kg\], finite and > 0.
    pub mass: f64,
    /// Stiffness k of the spring \[N/m\], finite and ≥ 0 (0: no spring).
    pub stiffness: f64,
    /// Speed of the spring's far end \[m/s\], finite (0: spring to ground).
    pub drive_speed: f64,
}

/// The states of every channel as flat slices: x, v, anchor and z of length B, the element
/// positions ζ of length B × N (row-major).
#[derive(Debug)]
pub struct MassStates<'a> {
    /// Positions.
    pub x: &'a mut [f64],
    /// Velocities.
    pub v: &'a mut [f64],
    /// Positions of the spring's far end.
    pub anchor: &'a mut [f64],
    /// Friction state z.
    pub z: &'a mut [f64],
    /// Element positions ζ.
    pub zeta: &'a mut [f64],
}

/// Channels of one mass system.
pub struct MassBank {
    channels: Box<dyn MassChannels>,
    mechanics: Mechanics,
}

/// The bank for one hysteresis type, behind a trait object so that N is chosen at run time.
trait MassChannels: Send + Sync {
    fn channels(&self) -> usize;
    fn elements(&self) -> usize;
    fn scheme(&self) -> Scheme;
    fn step(&mut self, channel: usize, u: f64, dt: f64) -> Result<MassSample, Error>;
    fn run(&mut self, u: &[f64], dt: f64, out: Trajectory<'_>) -> Result<(), Error>;
    fn place(&mut self, x: &[f64], v: &[f64]);
    fn read_state(&self, out: MassStates<'_>);
    fn write_state(
        &mut self,
        x: &[f64],
        v: &[f64],
        anchor: &[f64],
        z: &[f64],
        zeta: &[f64],
    ) -> Result<(), Error>;
}

struct Channels<H: Hysteresis> {
    system: MassSystem<H>,
    states: Vec<MassState<H::Memory>>,
    scheme: Scheme,
}

impl<H> MassChannels for Channels<H>
where
    H: Hysteresis<Memory: Memory> + Send + Sync,
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

    fn step(&mut self, channel: usize, u: f64, dt: f64) -> Result<MassSample, Error> {
        check_channel(channel, self.states.len())?;
        Ok(self
            .system
            .step(&mut self.states[channel], u, dt, self.scheme)?)
    }

    fn run(&mut self, u: &[f64], dt: f64, out: Trajectory<'_>) -> Result<(), Error> {
        let samples = samples_per_channel(u.len(), self.states.len())?;
        let Trajectory { friction, x, v } = out;
        for got in [friction.len(), x.len(), v.len()] {
            check_output(u.len(), got)?;
        }
        let (system, scheme) = (&self.system, self.scheme);
        if samples == 0 {
            // Nothing to run: dt is checked on a scratch state, no channel is copied or touched.
            let empty = Trajectory {
                friction: &mut [],
                x: &mut [],
                v: &mut [],
            };
            return Ok(system.simulate(&mut system.state_at(0.0, 0.0), &[], dt, scheme, empty)?);
        }
        let run_one = |state: &mut MassState<H::Memory>,
                       u: &[f64],
                       friction: &mut [f64],
                       x: &mut [f64],
                       v: &mut [f64]| {
            system.simulate(state, u, dt, scheme, Trajectory { friction, x, v })
        };
        // Only the first failing channel is kept (see the friction bank).
        all_or_nothing(&mut self.states, |states| {
            #[cfg(feature = "parallel")]
            if states.len() > 1 {
                return states
                    .par_iter_mut()
                    .zip(u.par_chunks(samples))
                    .zip(friction.par_chunks_mut(samples))
                    .zip(x.par_chunks_mut(samples).zip(v.par_chunks_mut(samples)))
                    .enumerate()
                    .filter_map(|(channel, (((state, u), friction), (x, v)))| {
                        run_one(state, u, friction, x, v)
                            .err()
                            .map(|error| (channel, error))
                    })
                    .min_by_key(|(channel, _)| *channel);
            }
            // One channel needs no thread pool; without the `parallel` feature none is used.
            states
                .iter_mut()
                .zip(u.chunks(samples))
                .zip(friction.chunks_mut(samples))
                .zip(x.chunks_mut(samples).zip(v.chunks_mut(samples)))
                .enumerate()
                .find_map(|(channel, (((state, u), friction), (x, v)))| {
                    run_one(state, u, friction, x, v)
                        .err()
                        .map(|error| (channel, error))
                })
        })
    }

    fn place(&mut self, x: &[f64], v: &[f64]) {
        for (channel, state) in self.states.iter_mut().enumerate() {
            *state = self.system.state_at(x[channel], v[channel]);
        }
    }

    fn read_state(&self, out: MassStates<'_>) {
        let n = <H::Memory as Memory>::LEN;
        for (b, state) in self.states.iter().enumerate() {
            out.x[b] = state.x;
            out.v[b] = state.v;
            out.anchor[b] = state.anchor;
            out.z[b] = state.friction.z;
            out.zeta[b * n..(b + 1) * n].copy_from_slice(state.friction.memory.values());
        }
    }

    fn write_state(
        &mut self,
        x: &[f64],
        v: &[f64],
        anchor: &[f64],
        z: &[f64],
        zeta: &[f64],
    ) -> Result<(), Error> {
        let n = <H::Memory as Memory>::LEN;
        let state_of = |b: usize| {
            let mut state = self.system.state_at(x[b], v[b]);
            state.anchor = anchor[b];
            state.friction.z = z[b];
            state.friction.memory.write(&zeta[b * n..(b + 1) * n]);
            state
        };
        // Every channel's friction state is checked before any is written: all or nothing.
        for channel in 0..self.states.len() {
            self.system
                .friction()
                .check_state(&state_of(channel).friction)
                .map_err(|error| Error::State { channel, error })?;
        }
        for channel in 0..self.states.len() {
            self.states[channel] = state_of(channel);
        }
        Ok(())
    }
}

fn boxed<H>(
    friction: Params<H>,
    mechanics: Mechanics,
    channels: usize,
    scheme: Scheme,
) -> Result<Box<dyn MassChannels>, Error>
where
    H: Hysteresis<Memory: Memory> + Send + Sync + 'static,
{
    let spring = Spring::dragged(mechanics.stiffness, mechanics.drive_speed)?;
    let system = MassSystem::new(friction, mechanics.mass, spring)?;
    Ok(Box::new(Channels {
        states: states(system.state_at(0.0, 0.0), channels)?,
        system,
        scheme,
    }))
}

impl MassBank {
    /// `channels` channels of a mass on the friction model `params`, at rest at x = 0.
    ///
    /// # Errors
    /// The first mechanical rule broken (`stiffness`, `drive_speed`, `mass`), or
    /// [`Error::OutOfMemory`].
    pub fn new(
        params: &ParameterSet,
        mechanics: Mechanics,
        channels: usize,
        scheme: Scheme,
    ) -> Result<Self, Error> {
        Ok(Self {
            channels: with_params!(*params, params => boxed(params, mechanics, channels, scheme)?),
            mechanics,
        })
    }

    /// The mechanical parameters.
    pub fn mechanics(&self) -> Mechanics {
        self.mechanics
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

    /// One step of `channel` with applied force `u` held over `dt`.
    ///
    /// # Errors
    /// A channel index beyond the bank, a non-finite `u`, a bad `dt`, or a diverged step; the
    /// state is unchanged.
    pub fn step(&mut self, channel: usize, u: f64, dt: f64) -> Result<MassSample, Error> {
        self.channels.step(channel, u, dt)
    }

    /// Runs channel b over row b of `u` (B × T, row-major) in parallel, writing rows of the
    /// three outputs (each shaped like `u`).
    ///
    /// # Errors
    /// All or nothing: a rejected call changes no state; the error names the sample, and the
    /// channel when there are several.
    pub fn run(&mut self, u: &[f64], dt: f64, out: Trajectory<'_>) -> Result<(), Error> {
        self.channels.run(u, dt, out)
    }

    /// Puts every channel at rest at positions `x` with velocities `v` (B each), the spring's
    /// far end at 0, relaxed friction.
    ///
    /// # Panics
    /// If a slice does not have B values.
    pub fn place(&mut self, x: &[f64], v: &[f64]) {
        let b = self.channels();
        assert!(x.len() == b && v.len() == b, "x and v must have {b} values");
        self.channels.place(x, v);
    }

    /// Copies the states out.
    ///
    /// # Panics
    /// If a slice has another length than [`MassStates`] describes.
    pub fn read_state(&self, out: MassStates<'_>) {
        self.assert_state_lengths(
            [out.x.len(), out.v.len(), out.anchor.len(), out.z.len()],
            out.zeta.len(),
        );
        self.channels.read_state(out);
    }

    /// Copies states in, shaped as [`MassStates`] describes.
    ///
    /// # Errors
    /// [`Error::State`] naming the first channel whose friction state breaks a rule
    /// ([`Params::check_state`]); then no channel is written.
    ///
    /// # Panics
    /// If a slice has another length.
    pub fn write_state(
        &mut self,
        x: &[f64],
        v: &[f64],
        anchor: &[f64],
        z: &[f64],
        zeta: &[f64],
    ) -> Result<(), Error> {
        self.assert_state_lengths([x.len(), v.len(), anchor.len(), z.len()], zeta.len());
        self.channels.write_state(x, v, anchor, z, zeta)
    }

    fn assert_state_lengths(&self, per_channel: [usize; 4], zeta: usize) {
        let (b, n) = (self.channels(), self.elements());
        assert!(
            per_channel == [b; 4] && zeta == b * n,
            "state slices must have lengths {b} and {b}×{n}"
        );
    }
}
