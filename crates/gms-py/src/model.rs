//! `_core.Engine`: channels of one model, stepped from Python. `leuven_rt.LeuvenModel` subclasses
//! it, so that `step` reaches Rust without a Python frame in between.

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::convert::{
    channel_count, check_dt, parse_scheme, real, same_channels, scheme_name, single_channel,
};
use crate::engine::{build, Engine as Channels};
use crate::errors::{block_error, step_error, InputError};
use crate::spec::Spec;

/// z, zeta, last_position and has_last_position of every channel.
type StateArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// The forces and the deflection z of a traced run.
type TraceArrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// Channels of one friction model sharing one parameter set.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct Engine {
    channels: Box<dyn Channels>,
    params: Py<PyAny>,
}

#[pymethods]
impl Engine {
    #[new]
    #[pyo3(signature = (params, channels = 1, scheme = None))]
    fn new(
        params: &Bound<'_, PyAny>,
        channels: i64,
        scheme: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let channels = channel_count(channels)?;
        let scheme = parse_scheme(scheme)?;
        let spec = Spec::extract(params)?;
        let channels = build(&spec, channels, scheme)?;
        Ok(Self {
            channels,
            params: params.clone().unbind(),
        })
    }

    /// The parameters this model was built from.
    #[getter]
    fn params(&self, py: Python<'_>) -> Py<PyAny> {
        self.params.clone_ref(py)
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

    /// One step of a single-channel model with velocity `v` held over `dt`; returns the force.
    fn step(&mut self, v: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<f64> {
        single_channel(self.channels.channels(), "step", "model")?;
        let (v, dt) = (real(v, "v")?, real(dt, "dt")?);
        self.channels
            .step(0, v, dt, false)
            .map_err(|error| step_error(error, v, dt))
    }

    /// One step of a single-channel model with position input `x`; returns the force.
    fn step_position(&mut self, x: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<f64> {
        single_channel(self.channels.channels(), "step_position", "model")?;
        let (x, dt) = (real(x, "x")?, real(dt, "dt")?);
        self.channels
            .step(0, x, dt, true)
            .map_err(|error| step_error(error, x, dt))
    }

    /// Steps every channel once; `input` has shape (B,), already float64 and finite.
    fn _step_channels<'py>(
        &mut self,
        py: Python<'py>,
        input: PyReadonlyArray1<'py, f64>,
        dt: f64,
        position: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let dt = check_dt(dt)?;
        let input = input.as_slice()?;
        let mut out = vec![0.0; input.len()];
        self.channels
            .run(input, dt, position, &mut out)
            .map_err(|(channel, error)| block_error(error, input, channel, Some(channel)))?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// Runs every channel over its row of `input`, shape (B, T), with the GIL released.
    fn _run<'py>(
        &mut self,
        py: Python<'py>,
        input: PyReadonlyArray2<'py, f64>,
        dt: f64,
        position: bool,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let dt = check_dt(dt)?;
        let shape = [input.shape()[0], input.shape()[1]];
        same_channels(shape[0], self.channels.channels(), "input", "model")?;
        let input = input.as_slice()?;
        let mut out = vec![0.0; input.len()];
        let channels = &mut self.channels;
        let multiple = shape[0] > 1;
        py.detach(|| channels.run(input, dt, position, &mut out))
            .map_err(|(channel, error)| {
                let channel = multiple.then_some(channel);
                block_error(error, &input[channel.unwrap_or(0) * shape[1]..], 0, channel)
            })?;
        PyArray1::from_vec(py, out).reshape(shape)
    }

    /// Runs the single channel over positions `x`, shape (T,), with the GIL released; returns
    /// the forces and the deflection z after every sample.
    fn _run_position_deflection<'py>(
        &mut self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        dt: f64,
    ) -> PyResult<TraceArrays<'py>> {
        if self.channels.channels() != 1 {
            return Err(InputError::new_err(format!(
                "`trace_position` runs one channel, this model has {}",
                self.channels.channels()
            )));
        }
        let dt = check_dt(dt)?;
        let x = x.as_slice()?;
        let (mut out, mut z) = (vec![0.0; x.len()], vec![0.0; x.len()]);
        let channels = &mut self.channels;
        py.detach(|| channels.run_position_deflection(x, dt, &mut out, &mut z))
            .map_err(|error| block_error(error, x, 0, None))?;
        Ok((PyArray1::from_vec(py, out), PyArray1::from_vec(py, z)))
    }

    /// Relaxes every channel: z = 0, elements undeflected, no previous position.
    fn reset(&mut self) {
        self.channels.reset();
    }

    /// Copies of (z, zeta, last_position, has_last_position), shapes (B,), (B, N), (B,), (B,).
    fn _get_state<'py>(&self, py: Python<'py>) -> PyResult<StateArrays<'py>> {
        let (b, n) = (self.channels.channels(), self.channels.elements());
        let (mut z, mut memory) = (vec![0.0; b], vec![0.0; b * n]);
        let (mut last, mut has_last) = (vec![0.0; b], vec![false; b]);
        self.channels
            .read_state(&mut z, &mut memory, &mut last, &mut has_last);
        Ok((
            PyArray1::from_vec(py, z),
            PyArray1::from_vec(py, memory).reshape([b, n])?,
            PyArray1::from_vec(py, last),
            PyArray1::from_vec(py, has_last),
        ))
    }

    /// Restores states checked by the Python side (shapes and finiteness).
    fn _set_state(
        &mut self,
        z: PyReadonlyArray1<'_, f64>,
        zeta: PyReadonlyArray2<'_, f64>,
        last: PyReadonlyArray1<'_, f64>,
        has_last: PyReadonlyArray1<'_, bool>,
    ) -> PyResult<()> {
        let (b, n) = (self.channels.channels(), self.channels.elements());
        let (z, zeta) = (z.as_slice()?, zeta.as_slice()?);
        let (last, has_last) = (last.as_slice()?, has_last.as_slice()?);
        if z.len() != b || zeta.len() != b * n || last.len() != b || has_last.len() != b {
            return Err(InputError::new_err(format!(
                "state must have shapes z ({b},), zeta ({b}, {n}), last_position ({b},), \
                 has_last_position ({b},)"
            )));
        }
        self.channels.write_state(z, zeta, last, has_last);
        Ok(())
    }
}
