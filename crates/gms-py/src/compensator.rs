//! `_core.CompensatorEngine`: one axis of friction compensation, stepped from Python.
//! `leuven_rt.Compensator` subclasses it, so that `step` reaches Rust without a Python frame in
//! between (the control-loop fast path).

use gms_core::Mode;
use gms_dyn::{Compensator, Terms};
use pyo3::prelude::*;

use crate::convert::real;
use crate::errors::{lend, lend_mut, raise, raise_as, Class, Kind, Refusal};
use crate::level::{optional_level, optional_position_force};
use crate::params::{parameter_set, PythonParams};

fn parse_mode(mode: &str) -> PyResult<Mode> {
    match mode {
        "feedforward" => Ok(Mode::Feedforward),
        "observer" => Ok(Mode::Observer),
        other => Err(Refusal::new(
            Class::Input,
            Kind::InvalidChoice,
            format!("`mode` must be 'feedforward' or 'observer', got {other:?}"),
        )
        .field("mode")
        .into()),
    }
}

/// One axis of friction compensation at a fixed sample time.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct CompensatorEngine {
    compensator: Compensator,
    params: Py<PyAny>,
}

#[pymethods]
impl CompensatorEngine {
    #[new]
    #[pyo3(signature = (params, dt, mode, level = None, position_force = None, x = None))]
    fn new(
        params: &Bound<'_, PyAny>,
        dt: &Bound<'_, PyAny>,
        mode: &str,
        level: Option<&Bound<'_, PyAny>>,
        position_force: Option<&Bound<'_, PyAny>>,
        x: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let dt = real(dt, "dt")?;
        let mode = parse_mode(mode)?;
        let set = parameter_set(params)?;
        let terms = Terms {
            start: x
                .filter(|x| !x.is_none())
                .map(|x| real(x, "x"))
                .transpose()?,
            level: optional_level(level)?,
            position_force: optional_position_force(position_force)?,
        };
        Ok(Self {
            compensator: Compensator::with_terms(&set, dt, mode, &terms).map_err(raise)?,
            params: params.clone().unbind(),
        })
    }

    /// The friction force to add to the command for this sample; `input` is the desired
    /// velocity (feedforward) or the measured position (observer).
    fn step(slf: &Bound<'_, Self>, input: &Bound<'_, PyAny>) -> PyResult<f64> {
        let mut this = lend_mut(slf)?;
        let name = match this.compensator.mode() {
            Mode::Feedforward => "v",
            Mode::Observer => "x",
        };
        let value = real(input, name)?;
        this.compensator.step(value).map_err(|error| {
            raise_as(
                Class::Input,
                error.into(),
                format!("{error}; the state and output are unchanged"),
            )
        })
    }

    /// The friction force for one sample of a planned trajectory: the desired velocity `v`
    /// drives the model, the desired position `x` places the level and the position force (and
    /// becomes the feedforward `position`; in observer mode, the previous position of the next
    /// `step`). A non-finite `v` or `x` raises `InputError` and changes nothing.
    fn step_trajectory(
        slf: &Bound<'_, Self>,
        v: &Bound<'_, PyAny>,
        x: &Bound<'_, PyAny>,
    ) -> PyResult<f64> {
        // Converted before the borrow: no Python code (a `__float__`) runs while it is held.
        let (v, x) = (real(v, "v")?, real(x, "x")?);
        let mut this = lend_mut(slf)?;
        this.compensator.step_trajectory(v, x).map_err(|error| {
            raise_as(
                Class::Input,
                error.into(),
                format!("{error}; the state and output are unchanged"),
            )
        })
    }

    /// Swaps in new parameters (same kind and number of elements); the hysteresis force
    /// carries over, so the output has no jump.
    fn set_params(slf: &Bound<'_, Self>, params: &Bound<'_, PyAny>) -> PyResult<()> {
        let mut this = lend_mut(slf)?;
        let given = PythonParams::extract(params)?;
        match given.raw() {
            // Kind and size are compared before the values are checked.
            Some(raw) => this.compensator.set_raw_params(&raw),
            None => this.compensator.set_params(&given.validate()?),
        }
        .map_err(raise)?;
        this.params = params.clone().unbind();
        Ok(())
    }

    /// Sets the position from which feedforward mode integrates the desired velocity to place
    /// the level and the position force (observer mode takes it from its input).
    fn set_position(slf: &Bound<'_, Self>, x: &Bound<'_, PyAny>) -> PyResult<()> {
        let mut this = lend_mut(slf)?;
        let x = real(x, "x")?;
        this.compensator.set_position(x).map_err(|error| {
            raise_as(
                Class::Input,
                error.into(),
                format!("{error}; the position is unchanged"),
            )
        })
    }

    /// The feedforward position: the start position, then the desired positions stepped or
    /// the desired velocities integrated since; None until a start position is given.
    #[getter]
    fn position(slf: &Bound<'_, Self>) -> PyResult<Option<f64>> {
        Ok(lend(slf)?.compensator.position())
    }

    /// Back to rest: relaxed state, no previous position, output 0 (the position stays).
    fn reset(slf: &Bound<'_, Self>) -> PyResult<()> {
        lend_mut(slf)?.compensator.reset();
        Ok(())
    }

    /// The last force returned by `step` (0 before the first).
    #[getter]
    fn output(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.compensator.output())
    }

    /// The parameters in use.
    #[getter]
    fn params(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        Ok(lend(slf)?.params.clone_ref(slf.py()))
    }

    /// The sample time [s].
    #[getter]
    fn dt(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.compensator.dt())
    }

    /// 'feedforward' or 'observer'.
    #[getter]
    fn mode(slf: &Bound<'_, Self>) -> PyResult<&'static str> {
        Ok(match lend(slf)?.compensator.mode() {
            Mode::Feedforward => "feedforward",
            Mode::Observer => "observer",
        })
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.compensator.kind().elements())
    }

    /// Copies of (z, zeta, `last_position` or None).
    fn _state(slf: &Bound<'_, Self>) -> PyResult<(f64, Vec<f64>, Option<f64>)> {
        let state = lend(slf)?.compensator.state();
        Ok((state.z, state.zeta, state.last_position))
    }
}
