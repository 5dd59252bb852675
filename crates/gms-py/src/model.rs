//! `_core.Engine`: channels of one model, stepped from Python. `leuven_rt.LeuvenModel` subclasses
//! it, so that `step` reaches Rust without a Python frame in between.

use gms_core::Scheme;
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat};

use crate::engine::{build, Engine as Channels};
use crate::errors::{run_error, InputError};
use crate::spec::Spec;

/// A Python real number as f64: floats on the fast path, then ints and numpy scalars; bools
/// and everything else are refused.
#[inline]
fn real(value: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    if let Ok(float) = value.cast::<PyFloat>() {
        return Ok(float.value());
    }
    if !value.is_instance_of::<PyBool>() {
        if let Ok(number) = value.extract::<f64>() {
            return Ok(number);
        }
    }
    Err(InputError::new_err(format!(
        "`{name}` must be a real number, got {}",
        value.repr()?
    )))
}

/// The error of a single step: the value shown is the offending input or dt.
fn step_error(error: gms_core::Error, input: f64, dt: f64) -> PyErr {
    let value = match error {
        gms_core::Error::NotPositive(_) => dt,
        // A finite position can still give an infinite velocity over a tiny dt.
        _ if input.is_finite() => f64::INFINITY,
        _ => input,
    };
    run_error(error, value, None)
}

/// The error of a block call; `row` is the channel's input, or the (B,) samples of one step
/// with `offset` channels before it.
fn block_error(
    error: gms_core::Error,
    row: &[f64],
    offset: usize,
    channel: Option<usize>,
) -> PyErr {
    let value = match error {
        gms_core::Error::NotFinite { index, .. } => {
            let sample = row.get(index + offset).copied().unwrap_or(f64::NAN);
            if sample.is_finite() {
                f64::INFINITY
            } else {
                sample
            }
        }
        _ => f64::NAN,
    };
    run_error(error, value, channel)
}

fn parse_scheme(scheme: &str) -> PyResult<Scheme> {
    match scheme {
        "implicit" => Ok(Scheme::Implicit),
        "explicit" => Ok(Scheme::Explicit),
        other => Err(InputError::new_err(format!(
            "`scheme` must be 'implicit' or 'explicit', got {other:?}"
        ))),
    }
}

/// z, zeta, last_position and has_last_position of every channel.
type StateArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// Channels of one friction model sharing one parameter set.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct Engine {
    channels: Box<dyn Channels>,
    params: Py<PyAny>,
}

impl Engine {
    fn single_channel(&self, method: &str) -> PyResult<()> {
        if self.channels.channels() == 1 {
            Ok(())
        } else {
            Err(InputError::new_err(format!(
                "`{method}` steps one channel, this model has {}: use `step_channels`",
                self.channels.channels()
            )))
        }
    }

    fn check_dt(dt: f64) -> PyResult<()> {
        if dt.is_finite() && dt > 0.0 {
            Ok(())
        } else {
            Err(InputError::new_err(format!(
                "`dt` must be finite and > 0, got {dt}"
            )))
        }
    }
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
        if channels < 1 {
            return Err(InputError::new_err(format!(
                "`channels` must be >= 1, got {channels}"
            )));
        }
        let scheme = match scheme.map(|scheme| (scheme, scheme.extract::<String>())) {
            None => Scheme::Implicit,
            Some((_, Ok(name))) => parse_scheme(&name)?,
            Some((scheme, Err(_))) => {
                return Err(InputError::new_err(format!(
                    "`scheme` must be 'implicit' or 'explicit', got {}",
                    scheme.repr()?
                )))
            }
        };
        let spec = Spec::extract(params)?;
        let channels = build(&spec, channels as usize, scheme)?;
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
        match self.channels.scheme() {
            Scheme::Implicit => "implicit",
            Scheme::Explicit => "explicit",
        }
    }

    /// One step of a single-channel model with velocity `v` held over `dt`; returns the force.
    fn step(&mut self, v: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<f64> {
        self.single_channel("step")?;
        let (v, dt) = (real(v, "v")?, real(dt, "dt")?);
        self.channels
            .step(0, v, dt, false)
            .map_err(|error| step_error(error, v, dt))
    }

    /// One step of a single-channel model with position input `x`; returns the force.
    fn step_position(&mut self, x: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<f64> {
        self.single_channel("step_position")?;
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
        Self::check_dt(dt)?;
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
        Self::check_dt(dt)?;
        let shape = [input.shape()[0], input.shape()[1]];
        if shape[0] != self.channels.channels() {
            return Err(InputError::new_err(format!(
                "input has {} channels, this model has {}",
                shape[0],
                self.channels.channels()
            )));
        }
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
