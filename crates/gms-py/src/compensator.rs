//! `_core.CompensatorEngine`: one axis of friction compensation, stepped from Python.
//! `leuven_rt.Compensator` subclasses it, so that `step` reaches Rust without a Python frame in
//! between (the control-loop fast path).
//!
//! gms-core fixes the number of elements in the type; the parameters come at run time, so the
//! axis is built for every N up to [`MAX_ELEMENTS`] and kept behind the object-safe [`Axis`].

use gms_core::{Compensator, Error, Field, Hysteresis, Linear, MaxwellSlip, Mode, Params, State};
use pyo3::prelude::*;
use seq_macro::seq;

use crate::bank::Memory;
use crate::convert::real;
use crate::engine::MAX_ELEMENTS;
use crate::errors::{dt_error, show, InputError, ParameterError};
use crate::spec::Spec;

/// A hysteresis whose parameters can be read from a [`Spec`] of the same kind and size.
trait FromSpec: Hysteresis<Memory: Memory> + Sized {
    /// The validated parameters, or a `ParameterError` if `spec` is invalid or of another kind
    /// or size than `Self`.
    fn params(spec: &Spec) -> PyResult<Params<Self>>;
}

impl<const N: usize> FromSpec for MaxwellSlip<N> {
    fn params(spec: &Spec) -> PyResult<Params<Self>> {
        if spec.sigma0.is_some() || spec.w.len() != N {
            return Err(ParameterError::new_err(format!(
                "new parameters must have {N} Maxwell-slip elements like the compensator's, got {}",
                describe(spec)
            )));
        }
        spec.maxwell::<N>()
    }
}

impl FromSpec for Linear {
    fn params(spec: &Spec) -> PyResult<Params<Self>> {
        match spec.sigma0 {
            Some(sigma0) if !spec.maxwell_given => spec.lugre(sigma0),
            _ => Err(ParameterError::new_err(format!(
                "new parameters must have linear hysteresis `sigma0` like the compensator's, \
                 got {}",
                describe(spec)
            ))),
        }
    }
}

fn describe(spec: &Spec) -> String {
    match spec.sigma0 {
        Some(_) => "linear hysteresis `sigma0`".to_owned(),
        None => format!("{} Maxwell-slip elements", spec.w.len()),
    }
}

/// One compensator axis, whatever its hysteresis.
trait Axis: Send + Sync {
    fn step(&mut self, input: f64) -> Result<f64, Error>;
    fn set_params(&mut self, spec: &Spec) -> PyResult<()>;
    fn reset(&mut self);
    fn output(&self) -> f64;
    fn dt(&self) -> f64;
    fn mode(&self) -> Mode;
    fn elements(&self) -> usize;
    /// z, ζ of every element, and the last position (observer mode, after the first sample).
    fn state(&self) -> (f64, Vec<f64>, Option<f64>);
}

impl<H> Axis for Compensator<H>
where
    H: FromSpec + Send + Sync,
{
    #[inline]
    fn step(&mut self, input: f64) -> Result<f64, Error> {
        Compensator::step(self, input)
    }

    fn set_params(&mut self, spec: &Spec) -> PyResult<()> {
        Compensator::set_params(self, H::params(spec)?);
        Ok(())
    }

    fn reset(&mut self) {
        Compensator::reset(self);
    }

    fn output(&self) -> f64 {
        Compensator::output(self)
    }

    fn dt(&self) -> f64 {
        Compensator::dt(self)
    }

    fn mode(&self) -> Mode {
        Compensator::mode(self)
    }

    fn elements(&self) -> usize {
        <H::Memory as Memory>::LEN
    }

    fn state(&self) -> (f64, Vec<f64>, Option<f64>) {
        let State {
            z,
            memory,
            last_position,
        } = self.state();
        (*z, memory.values().to_vec(), *last_position)
    }
}

fn axis<H>(params: Params<H>, dt: f64, mode: Mode) -> PyResult<Box<dyn Axis>>
where
    H: FromSpec + Send + Sync + 'static,
{
    let compensator = Compensator::new(params, dt, mode).map_err(|_| dt_error(dt))?;
    Ok(Box::new(compensator))
}

/// Validates `spec` and builds an axis at rest.
fn build(spec: &Spec, dt: f64, mode: Mode) -> PyResult<Box<dyn Axis>> {
    if spec.sigma0.is_some() {
        return axis(Linear::params(spec)?, dt, mode);
    }
    seq!(N in 1..=32 {
        match spec.w.len() {
            #(N => axis(MaxwellSlip::<N>::params(spec)?, dt, mode),)*
            // Whatever is wrong with the other cases (no hysteresis, too many elements),
            // the model's builder says it the same way as everywhere else.
            _ => {
                crate::engine::build(spec, 1, gms_core::Scheme::Implicit)?;
                Err(ParameterError::new_err(format!(
                    "`W` and `Delta` may have 1 to {MAX_ELEMENTS} elements, got {}",
                    spec.w.len()
                )))
            }
        }
    })
}

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
    axis: Box<dyn Axis>,
    params: Py<PyAny>,
}

#[pymethods]
impl CompensatorEngine {
    #[new]
    fn new(params: &Bound<'_, PyAny>, dt: &Bound<'_, PyAny>, mode: &str) -> PyResult<Self> {
        let dt = real(dt, "dt")?;
        let mode = parse_mode(mode)?;
        let spec = Spec::extract(params)?;
        Ok(Self {
            axis: build(&spec, dt, mode)?,
            params: params.clone().unbind(),
        })
    }

    /// The friction force to add to the command for this sample; `input` is the desired
    /// velocity (feedforward) or the measured position (observer).
    fn step(&mut self, input: &Bound<'_, PyAny>) -> PyResult<f64> {
        let name = match self.axis.mode() {
            Mode::Feedforward => "v",
            Mode::Observer => "x",
        };
        let value = real(input, name)?;
        self.axis
            .step(value)
            .map_err(|error| self.step_error(error, value))
    }

    /// Swaps in new parameters (same kind and number of elements); the hysteresis force
    /// carries over, so the output has no jump.
    fn set_params(&mut self, params: &Bound<'_, PyAny>) -> PyResult<()> {
        let spec = Spec::extract(params)?;
        self.axis.set_params(&spec)?;
        self.params = params.clone().unbind();
        Ok(())
    }

    /// Back to rest: relaxed state, no previous position, output 0.
    fn reset(&mut self) {
        self.axis.reset();
    }

    /// The last force returned by `step` (0 before the first).
    #[getter]
    fn output(&self) -> f64 {
        self.axis.output()
    }

    /// The parameters in use.
    #[getter]
    fn params(&self, py: Python<'_>) -> Py<PyAny> {
        self.params.clone_ref(py)
    }

    /// The sample time [s].
    #[getter]
    fn dt(&self) -> f64 {
        self.axis.dt()
    }

    /// 'feedforward' or 'observer'.
    #[getter]
    fn mode(&self) -> &'static str {
        match self.axis.mode() {
            Mode::Feedforward => "feedforward",
            Mode::Observer => "observer",
        }
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(&self) -> usize {
        self.axis.elements()
    }

    /// Copies of (z, zeta, last_position or None).
    fn _state(&self) -> (f64, Vec<f64>, Option<f64>) {
        self.axis.state()
    }
}

impl CompensatorEngine {
    fn step_error(&self, error: Error, input: f64) -> PyErr {
        match error {
            Error::NotFinite {
                field: Field::v, ..
            } if self.axis.mode() == Mode::Observer => {
                let (_, _, last) = self.axis.state();
                InputError::new_err(format!(
                    "`x` = {} after {} over dt = {} gives a velocity that is not finite; the \
                     state and output are unchanged",
                    show(input),
                    show(last.unwrap_or(f64::NAN)),
                    show(self.axis.dt())
                ))
            }
            Error::NotFinite { field, .. } => InputError::new_err(format!(
                "`{field}` must be finite, got {}; the state and output are unchanged",
                show(input)
            )),
            other => InputError::new_err(format!("{other}; the state and output are unchanged")),
        }
    }
}
