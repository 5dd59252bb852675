//! `_core.Engine`: channels of one model, stepped from Python. `leuven_rt.LeuvenModel` subclasses
//! it, so that `step` reaches Rust without a Python frame in between.

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyReadwriteArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use gms_dyn::{FrictionBank, Input};

use crate::convert::{
    channel_count, parse_scheme, real, same_channels, scheme_name, single_channel, zeros,
};
use crate::errors::{lend, lend_mut, raise, Class, Kind, Refusal};
use crate::level::{optional_level, optional_position_force};
use crate::params::parameter_set;

/// z, zeta, `last_position` and `has_last_position` of every channel.
type StateArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// The forces and the deflection z of a traced run.
type TraceArrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The input kind of the block calls, from their `position` flag.
fn kind(position: bool) -> Input {
    if position {
        Input::Position
    } else {
        Input::Velocity
    }
}

/// Channels of one friction model sharing one parameter set.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct Engine {
    bank: FrictionBank,
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
        let set = parameter_set(params)?;
        Ok(Self {
            bank: FrictionBank::new(&set, channels, scheme).map_err(raise)?,
            params: params.clone().unbind(),
        })
    }

    /// The parameters this model was built from.
    #[getter]
    fn params(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        Ok(lend(slf)?.params.clone_ref(slf.py()))
    }

    /// Number of channels B.
    #[getter]
    fn channels(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.bank.channels())
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.bank.elements())
    }

    /// 'implicit' or 'explicit'.
    #[getter]
    fn scheme(slf: &Bound<'_, Self>) -> PyResult<&'static str> {
        Ok(scheme_name(lend(slf)?.bank.scheme()))
    }

    /// One step of a single-channel model with velocity `v` held over `dt`; returns the force.
    fn step(slf: &Bound<'_, Self>, v: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>) -> PyResult<f64> {
        let mut this = lend_mut(slf)?;
        single_channel(this.bank.channels(), "step", "model")?;
        let (v, dt) = (real(v, "v")?, real(dt, "dt")?);
        this.bank.step(0, v, dt, Input::Velocity).map_err(raise)
    }

    /// One step of a single-channel model with position input `x`; returns the force.
    fn step_position(
        slf: &Bound<'_, Self>,
        x: &Bound<'_, PyAny>,
        dt: &Bound<'_, PyAny>,
    ) -> PyResult<f64> {
        let mut this = lend_mut(slf)?;
        single_channel(this.bank.channels(), "step_position", "model")?;
        let (x, dt) = (real(x, "x")?, real(dt, "dt")?);
        this.bank.step(0, x, dt, Input::Position).map_err(raise)
    }

    /// Steps every channel once; `input` has shape (B,), already float64 and finite.
    fn _step_channels<'py>(
        slf: &Bound<'py, Self>,
        input: PyReadonlyArray1<'py, f64>,
        dt: f64,
        position: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut this = lend_mut(slf)?;
        let input = input.as_slice()?;
        let mut out = vec![0.0; input.len()];
        this.bank
            .run(input, dt, kind(position), &mut out)
            .map_err(raise)?;
        Ok(PyArray1::from_vec(slf.py(), out))
    }

    /// Runs every channel over its row of `input`, shape (B, T), with the GIL released, writing
    /// the forces into `out` (the same shape: a new array of the caller's, so that no output is
    /// allocated, zeroed and handed over here).
    fn _run<'py>(
        slf: &Bound<'py, Self>,
        input: PyReadonlyArray2<'py, f64>,
        dt: f64,
        position: bool,
        mut out: PyReadwriteArray2<'py, f64>,
    ) -> PyResult<()> {
        let py = slf.py();
        let mut this = lend_mut(slf)?;
        same_channels(input.shape()[0], this.bank.channels(), "input", "model")?;
        let (input, out) = (input.as_slice()?, out.as_slice_mut()?);
        let bank = &mut this.bank;
        py.detach(|| bank.run(input, dt, kind(position), out))
            .map_err(raise)
    }

    /// Runs every channel over its row of positions `input`, shape (B, T), with the GIL
    /// released, with the position-dependent `level` and `position_force` (either may be None)
    /// on the forces (docs/model.md#position-dependent-level), writing them into `out` as
    /// [`Engine::_run`] does.
    fn _run_position_level<'py>(
        slf: &Bound<'py, Self>,
        input: PyReadonlyArray2<'py, f64>,
        dt: f64,
        level: Option<&Bound<'py, PyAny>>,
        position_force: Option<&Bound<'py, PyAny>>,
        mut out: PyReadwriteArray2<'py, f64>,
    ) -> PyResult<()> {
        let py = slf.py();
        let level = optional_level(level)?;
        let force = optional_position_force(position_force)?;
        let mut this = lend_mut(slf)?;
        same_channels(input.shape()[0], this.bank.channels(), "input", "model")?;
        let (input, out) = (input.as_slice()?, out.as_slice_mut()?);
        let bank = &mut this.bank;
        py.detach(|| bank.run_position_level(input, dt, &level, &force, out))
            .map_err(raise)
    }

    /// Runs every channel over its row of velocities `v`, shape (B, T), with the GIL released,
    /// the level and the position force placed at the positions `x` (the same shape, checked by
    /// the Python side), writing the forces into `out` as [`Engine::_run`] does.
    #[allow(clippy::too_many_arguments)] // the signals, the step, the two terms and the output
    fn _run_level<'py>(
        slf: &Bound<'py, Self>,
        v: PyReadonlyArray2<'py, f64>,
        x: PyReadonlyArray2<'py, f64>,
        dt: f64,
        level: Option<&Bound<'py, PyAny>>,
        position_force: Option<&Bound<'py, PyAny>>,
        mut out: PyReadwriteArray2<'py, f64>,
    ) -> PyResult<()> {
        let py = slf.py();
        let level = optional_level(level)?;
        let force = optional_position_force(position_force)?;
        let mut this = lend_mut(slf)?;
        same_channels(v.shape()[0], this.bank.channels(), "v", "model")?;
        let (v, x, out) = (v.as_slice()?, x.as_slice()?, out.as_slice_mut()?);
        let bank = &mut this.bank;
        py.detach(|| bank.run_level(v, x, dt, &level, &force, out))
            .map_err(raise)
    }

    /// Runs the single channel over positions `x`, shape (T,), with the GIL released; returns
    /// the forces and the deflection z after every sample.
    fn _run_position_deflection<'py>(
        slf: &Bound<'py, Self>,
        x: PyReadonlyArray1<'py, f64>,
        dt: f64,
    ) -> PyResult<TraceArrays<'py>> {
        let py = slf.py();
        let mut this = lend_mut(slf)?;
        let channels = this.bank.channels();
        if channels != 1 {
            return Err(Refusal::new(
                Class::Input,
                Kind::ChannelMismatch,
                format!("`trace_position` runs one channel, this model has {channels}"),
            )
            .lengths(1_usize, channels)
            .into());
        }
        let x = x.as_slice()?;
        let (mut out, mut z) = (zeros(x.len(), "x")?, zeros(x.len(), "x")?);
        let bank = &mut this.bank;
        py.detach(|| bank.trace_position(0, x, dt, &mut out, &mut z))
            .map_err(raise)?;
        Ok((PyArray1::from_vec(py, out), PyArray1::from_vec(py, z)))
    }

    /// Relaxes every channel: z = 0, elements undeflected, no previous position.
    fn reset(slf: &Bound<'_, Self>) -> PyResult<()> {
        lend_mut(slf)?.bank.reset();
        Ok(())
    }

    /// Copies of (z, zeta, `last_position`, `has_last_position`), shapes (B,), (B, N), (B,), (B,).
    fn _get_state<'py>(slf: &Bound<'py, Self>) -> PyResult<StateArrays<'py>> {
        let py = slf.py();
        let this = lend(slf)?;
        let (b, n) = (this.bank.channels(), this.bank.elements());
        let (mut z, mut memory) = (vec![0.0; b], vec![0.0; b * n]);
        let (mut last, mut has_last) = (vec![0.0; b], vec![false; b]);
        this.bank
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
        slf: &Bound<'_, Self>,
        z: PyReadonlyArray1<'_, f64>,
        zeta: PyReadonlyArray2<'_, f64>,
        last: PyReadonlyArray1<'_, f64>,
        has_last: PyReadonlyArray1<'_, bool>,
    ) -> PyResult<()> {
        let mut this = lend_mut(slf)?;
        let (b, n) = (this.bank.channels(), this.bank.elements());
        let (z, zeta) = (z.as_slice()?, zeta.as_slice()?);
        let (last, has_last) = (last.as_slice()?, has_last.as_slice()?);
        if z.len() != b || zeta.len() != b * n || last.len() != b || has_last.len() != b {
            return Err(Refusal::new(
                Class::Input,
                Kind::Shape,
                format!(
                    "state must have shapes z ({b},), zeta ({b}, {n}), last_position ({b},), \
                     has_last_position ({b},)"
                ),
            )
            .field("state")
            .into());
        }
        this.bank
            .write_state(z, zeta, last, has_last)
            .map_err(raise)
    }
}
