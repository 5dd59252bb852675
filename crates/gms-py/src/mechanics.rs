//! `_core.MassEngine`: channels of a force-driven mass on the friction model (gms-core's
//! `MassSystem`), stepped from Python. `leuven_rt.MassSystem` subclasses it.

use gms_core::{
    Error, Hysteresis, MassSample, MassState, MassSystem, Params, Scheme, Spring, Trajectory,
};
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use rayon::prelude::*;
use seq_macro::seq;

use crate::bank::{all_or_nothing, Memory};
use crate::convert::{
    channel_count, check_dt, parse_scheme, real, same_channels, scheme_name, single_channel,
};
use crate::errors::{block_error, show, step_error, InputError, ParameterError};
use crate::spec::Spec;

/// One channel's states as flat values: x, v, anchor, z and the memory.
struct StateSlices<'a> {
    x: &'a mut [f64],
    v: &'a mut [f64],
    anchor: &'a mut [f64],
    z: &'a mut [f64],
    zeta: &'a mut [f64],
}

/// Channels of one mass system, whatever its number of elements.
trait Channels: Send + Sync {
    fn channels(&self) -> usize;
    fn elements(&self) -> usize;
    fn scheme(&self) -> Scheme;
    fn step(&mut self, channel: usize, u: f64, dt: f64) -> Result<MassSample, Error>;
    /// Runs channel b over row b of `u` (B × T), writing rows of the three outputs; all or
    /// nothing across channels; the error names the channel.
    fn run(&mut self, u: &[f64], dt: f64, out: [&mut [f64]; 3]) -> Result<(), (usize, Error)>;
    fn place(&mut self, x: &[f64], v: &[f64]);
    fn read(&self, out: StateSlices<'_>);
    fn write(&mut self, x: &[f64], v: &[f64], anchor: &[f64], z: &[f64], zeta: &[f64]);
}

struct Bank<H: Hysteresis> {
    system: MassSystem<H>,
    states: Vec<MassState<H::Memory>>,
    scheme: Scheme,
}

impl<H> Channels for Bank<H>
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

    fn step(&mut self, channel: usize, u: f64, dt: f64) -> Result<MassSample, Error> {
        self.system
            .step(&mut self.states[channel], u, dt, self.scheme)
    }

    fn run(&mut self, u: &[f64], dt: f64, out: [&mut [f64]; 3]) -> Result<(), (usize, Error)> {
        let samples = u.len().checked_div(self.states.len()).unwrap_or(0).max(1);
        let (system, scheme) = (&self.system, self.scheme);
        let [friction, x, v] = out;
        all_or_nothing(&mut self.states, |states| {
            states
                .par_iter_mut()
                .zip(u.par_chunks(samples))
                .zip(friction.par_chunks_mut(samples))
                .zip(x.par_chunks_mut(samples).zip(v.par_chunks_mut(samples)))
                .map(|(((state, u), friction), (x, v))| {
                    system.simulate(state, u, dt, scheme, Trajectory { friction, x, v })
                })
                .collect()
        })
    }

    fn place(&mut self, x: &[f64], v: &[f64]) {
        for (channel, state) in self.states.iter_mut().enumerate() {
            *state = self.system.state_at(x[channel], v[channel]);
        }
    }

    fn read(&self, out: StateSlices<'_>) {
        let n = <H::Memory as Memory>::LEN;
        for (b, state) in self.states.iter().enumerate() {
            out.x[b] = state.x;
            out.v[b] = state.v;
            out.anchor[b] = state.anchor;
            out.z[b] = state.friction.z;
            state
                .friction
                .memory
                .read(&mut out.zeta[b * n..(b + 1) * n]);
        }
    }

    fn write(&mut self, x: &[f64], v: &[f64], anchor: &[f64], z: &[f64], zeta: &[f64]) {
        let n = <H::Memory as Memory>::LEN;
        for (b, state) in self.states.iter_mut().enumerate() {
            state.x = x[b];
            state.v = v[b];
            state.anchor = anchor[b];
            state.friction.z = z[b];
            state.friction.memory.write(&zeta[b * n..(b + 1) * n]);
        }
    }
}

/// The mechanical parameters, as given (for error messages and the getters).
#[derive(Clone, Copy)]
struct Mechanics {
    mass: f64,
    stiffness: f64,
    drive_speed: f64,
}

impl Mechanics {
    fn error(&self, error: Error) -> PyErr {
        use gms_core::Field;
        match error {
            Error::NotPositive(Field::mass) => ParameterError::new_err(format!(
                "`mass` must be finite and > 0, got {}",
                show(self.mass)
            )),
            Error::Negative(Field::stiffness) => ParameterError::new_err(format!(
                "`stiffness` must be finite and >= 0, got {}",
                show(self.stiffness)
            )),
            Error::NotFiniteValue(Field::drive_speed) => ParameterError::new_err(format!(
                "`drive_speed` must be finite, got {}",
                show(self.drive_speed)
            )),
            other => ParameterError::new_err(other.to_string()),
        }
    }
}

fn bank<H>(
    friction: Params<H>,
    mechanics: Mechanics,
    channels: usize,
    scheme: Scheme,
) -> PyResult<Box<dyn Channels>>
where
    H: Hysteresis + Send + Sync + 'static,
    H::Memory: Memory,
{
    let spring = Spring::dragged(mechanics.stiffness, mechanics.drive_speed)
        .map_err(|error| mechanics.error(error))?;
    let system = MassSystem::new(friction, mechanics.mass, spring)
        .map_err(|error| mechanics.error(error))?;
    let mut states = Vec::new();
    states.try_reserve_exact(channels).map_err(|_| {
        InputError::new_err(format!("`channels` = {channels} does not fit in memory"))
    })?;
    states.resize(channels, system.state_at(0.0, 0.0));
    Ok(Box::new(Bank {
        system,
        states,
        scheme,
    }))
}

fn build(
    spec: &Spec,
    mechanics: Mechanics,
    channels: usize,
    scheme: Scheme,
) -> PyResult<Box<dyn Channels>> {
    // The friction rules (and their messages) are the friction engine's: check them there first.
    crate::engine::build(spec, 1, scheme)?;
    if let Some(sigma0) = spec.sigma0 {
        return bank(spec.lugre(sigma0)?, mechanics, channels, scheme);
    }
    seq!(N in 1..=32 {
        match spec.w.len() {
            #(N => bank(spec.maxwell::<N>()?, mechanics, channels, scheme),)*
            count => Err(ParameterError::new_err(format!(
                "`W` and `Delta` may have at most {} elements, got {count}",
                crate::engine::MAX_ELEMENTS
            ))),
        }
    })
}

/// x, v, anchor, z of every channel (B,) and zeta (B, N).
type StateArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
);

/// Channels of a mass on the friction model, with an optional (dragged) spring.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct MassEngine {
    channels: Box<dyn Channels>,
    mechanics: Mechanics,
    params: Py<PyAny>,
}

#[pymethods]
impl MassEngine {
    #[new]
    #[pyo3(signature = (params, mass, stiffness = None, drive_speed = None, channels = 1, scheme = None))]
    fn new(
        params: &Bound<'_, PyAny>,
        mass: &Bound<'_, PyAny>,
        stiffness: Option<&Bound<'_, PyAny>>,
        drive_speed: Option<&Bound<'_, PyAny>>,
        channels: i64,
        scheme: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let number = |value: &Bound<'_, PyAny>, name: &str| {
            real(value, name).map_err(|_| {
                ParameterError::new_err(format!(
                    "`{name}` must be a real number, got {}",
                    value.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            })
        };
        let mechanics = Mechanics {
            mass: number(mass, "mass")?,
            stiffness: stiffness.map_or(Ok(0.0), |value| number(value, "stiffness"))?,
            drive_speed: drive_speed.map_or(Ok(0.0), |value| number(value, "drive_speed"))?,
        };
        let channels = channel_count(channels)?;
        let scheme = parse_scheme(scheme)?;
        let spec = Spec::extract(params)?;
        let channels = build(&spec, mechanics, channels, scheme)?;
        Ok(Self {
            channels,
            mechanics,
            params: params.clone().unbind(),
        })
    }

    /// The friction parameters.
    #[getter]
    fn params(&self, py: Python<'_>) -> Py<PyAny> {
        self.params.clone_ref(py)
    }
    /// Mass m [kg].
    #[getter]
    fn mass(&self) -> f64 {
        self.mechanics.mass
    }
    /// Spring stiffness k [N/m] (0: no spring).
    #[getter]
    fn stiffness(&self) -> f64 {
        self.mechanics.stiffness
    }
    /// Speed of the spring's far end [m/s] (0: spring to ground).
    #[getter]
    fn drive_speed(&self) -> f64 {
        self.mechanics.drive_speed
    }
    /// Number of channels B.
    #[getter]
    fn channels(&self) -> usize {
        self.channels.channels()
    }
    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(&self) -> usize {
        self.channels.elements()
    }
    /// 'implicit' or 'explicit'.
    #[getter]
    fn scheme(&self) -> &'static str {
        scheme_name(self.channels.scheme())
    }

    /// One step of a single-channel system with applied force `u` held over `dt`; returns
    /// (friction force, position, velocity) at the end of the step.
    fn step(&mut self, u: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<(f64, f64, f64)> {
        single_channel(self.channels.channels(), "step", "system")?;
        let (u, dt) = (real(u, "u")?, real(dt, "dt")?);
        let sample = self
            .channels
            .step(0, u, dt)
            .map_err(|error| step_error(error, u, dt))?;
        Ok((sample.friction, sample.x, sample.v))
    }

    /// Every channel over its row of `u` (B, T), checked finite by the caller, with the GIL
    /// released; returns (3, B, T): friction force, position, velocity.
    fn _run<'py>(
        &mut self,
        py: Python<'py>,
        u: PyReadonlyArray2<'py, f64>,
        dt: f64,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let dt = check_dt(dt)?;
        let shape = [u.shape()[0], u.shape()[1]];
        same_channels(shape[0], self.channels.channels(), "`u`", "system")?;
        let u = u.as_slice()?;
        let size = u.len();
        let mut out = vec![0.0; 3 * size];
        let channels = &mut self.channels;
        let multiple = shape[0] > 1;
        py.detach(|| {
            let (friction, rest) = out.split_at_mut(size);
            let (x, v) = rest.split_at_mut(size);
            channels.run(u, dt, [friction, x, v])
        })
        .map_err(|(channel, error)| {
            block_error(
                error,
                &u[channel * shape[1]..],
                0,
                multiple.then_some(channel),
            )
        })?;
        PyArray1::from_vec(py, out).reshape([3, shape[0], shape[1]])
    }

    /// Puts every channel at rest state: positions `x` and velocities `v` (B,), the spring's
    /// far end at 0, relaxed friction. Arrays are checked finite by the caller.
    fn _place(
        &mut self,
        x: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<()> {
        let (x, v) = (x.as_slice()?, v.as_slice()?);
        let b = self.channels.channels();
        if x.len() != b || v.len() != b {
            return Err(InputError::new_err(format!(
                "`position` and `velocity` must have shape ({b},)"
            )));
        }
        self.channels.place(x, v);
        Ok(())
    }

    /// Copies of (x, v, anchor, z, zeta), shapes (B,) × 4 and (B, N).
    fn _get_state<'py>(&self, py: Python<'py>) -> PyResult<StateArrays<'py>> {
        let (b, n) = (self.channels.channels(), self.channels.elements());
        let (mut x, mut v, mut anchor, mut z) =
            (vec![0.0; b], vec![0.0; b], vec![0.0; b], vec![0.0; b]);
        let mut zeta = vec![0.0; b * n];
        self.channels.read(StateSlices {
            x: &mut x,
            v: &mut v,
            anchor: &mut anchor,
            z: &mut z,
            zeta: &mut zeta,
        });
        Ok((
            PyArray1::from_vec(py, x),
            PyArray1::from_vec(py, v),
            PyArray1::from_vec(py, anchor),
            PyArray1::from_vec(py, z),
            PyArray1::from_vec(py, zeta).reshape([b, n])?,
        ))
    }

    /// Restores states checked by the Python side (shapes and finiteness).
    fn _set_state(
        &mut self,
        x: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
        anchor: PyReadonlyArray1<'_, f64>,
        z: PyReadonlyArray1<'_, f64>,
        zeta: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<()> {
        let (b, n) = (self.channels.channels(), self.channels.elements());
        let (x, v, anchor, z, zeta) = (
            x.as_slice()?,
            v.as_slice()?,
            anchor.as_slice()?,
            z.as_slice()?,
            zeta.as_slice()?,
        );
        if [x.len(), v.len(), anchor.len(), z.len()] != [b; 4] || zeta.len() != b * n {
            return Err(InputError::new_err(format!(
                "state must have shapes x, v, anchor, z ({b},) and zeta ({b}, {n})"
            )));
        }
        self.channels.write(x, v, anchor, z, zeta);
        Ok(())
    }
}
