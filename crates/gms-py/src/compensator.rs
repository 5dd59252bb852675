//! `_core.CompensatorEngine`: one axis of friction compensation, stepped from Python.
//! `leuven_rt.Compensator` subclasses it, so that `step` reaches Rust without a Python frame in
//! between (the control-loop fast path).

use gms_core::Mode;
use gms_dyn::{Compensator, Terms};
use pyo3::prelude::*;

use crate::convert::real;
use crate::errors::{raise, InputError};
use crate::level::{optional_level, optional_position_force};
use crate::params::{parameter_set, PythonParams};

fn parse_mode(mode: &str) -> PyResult<Mode> {
    match mode {
        "feedforward" => Ok(Mode::Feedforward),
        "observer" => Ok(Mode::Observer),
        other => Err(InputError::new_err(format!(
            "`mode` must be 'feedforward' or 'observer', got {other:?}"
        ))),
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
    fn step(&mut self, input: &Bound<'_, PyAny>) -> PyResult<f64> {
        let name = match self.compensator.mode() {
            Mode::Feedforward => "v",
            Mode::Observer => "x",
        };
        let value = real(input, name)?;
        self.compensator.step(value).map_err(|error| {
            InputError::new_err(format!("{error}; the state and output are unchanged"))
        })
    }

    /// The friction force for one sample of a planned trajectory: the desired velocity `v`
    /// drives the model, the desired position `x` places the level and the position force.
    fn step_trajectory(&mut self, v: &Bound<'_, PyAny>, x: &Bound<'_, PyAny>) -> PyResult<f64> {
        let (v, x) = (real(v, "v")?, real(x, "x")?);
        self.compensator.step_trajectory(v, x).map_err(|error| {
            InputError::new_err(format!("{error}; the state and output are unchanged"))
        })
    }

    /// Swaps in new parameters (same kind and number of elements); the hysteresis force
    /// carries over, so the output has no jump.
    fn set_params(&mut self, params: &Bound<'_, PyAny>) -> PyResult<()> {
        let given = PythonParams::extract(params)?;
        match given.raw() {
            // Kind and size are compared before the values are checked.
            Some(raw) => self.compensator.set_raw_params(&raw),
            None => self.compensator.set_params(&given.validate()?),
        }
        .map_err(raise)?;
        self.params = params.clone().unbind();
        Ok(())
    }

    /// Sets the position from which feedforward mode integrates the desired velocity to place
    /// the level and the position force (observer mode takes it from its input).
    fn set_position(&mut self, x: &Bound<'_, PyAny>) -> PyResult<()> {
        let x = real(x, "x")?;
        self.compensator
            .set_position(x)
            .map_err(|error| InputError::new_err(format!("{error}; the position is unchanged")))
    }

    /// The feedforward position: the start position, then the desired positions stepped or
    /// the desired velocities integrated since; None until a start position is given.
    #[getter]
    fn position(&self) -> Option<f64> {
        self.compensator.position()
    }

    /// Back to rest: relaxed state, no previous position, output 0 (the position stays).
    fn reset(&mut self) {
        self.compensator.reset();
    }

    /// The last force returned by `step` (0 before the first).
    #[getter]
    fn output(&self) -> f64 {
        self.compensator.output()
    }

    /// The parameters in use.
    #[getter]
    fn params(&self, py: Python<'_>) -> Py<PyAny> {
        self.params.clone_ref(py)
    }

    /// The sample time [s].
    #[getter]
    fn dt(&self) -> f64 {
        self.compensator.dt()
    }

    /// 'feedforward' or 'observer'.
    #[getter]
    fn mode(&self) -> &'static str {
        match self.compensator.mode() {
            Mode::Feedforward => "feedforward",
            Mode::Observer => "observer",
        }
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(&self) -> usize {
        self.compensator.kind().elements()
    }

    /// Copies of (z, zeta, `last_position` or None).
    fn _state(&self) -> (f64, Vec<f64>, Option<f64>) {
        let state = self.compensator.state();
        (state.z, state.zeta, state.last_position)
    }
}
