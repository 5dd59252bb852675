//! `_core.OnlineIdentifier`: gms-core's online identification (recursive least squares on
//! F = Σ Wᵢψᵢ + Fc·sgn(v) + sigma2·v + offset), stepped from Python or run over a whole log.
//!
//! gms-core fixes the number of elements N (and of parameters P = N + 3) in the type; `build`
//! monomorphises every N up to [`MAX_ELEMENTS`] behind the object-safe [`Online`] trait.
//! `leuven_rt.OnlineIdentifier` subclasses the class, so that `update` reaches Rust without a
//! Python frame in between; it checks array shapes and dtypes before the calls arrive here.

use gms_core::{Error, Field, OnlineIdentifier as Identifier, RlsSettings};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use seq_macro::seq;

use crate::convert::real;
use crate::engine::MAX_ELEMENTS;
use crate::errors::{show, InputError, ParameterError};

/// One identifier, whatever its N.
trait Online: Send + Sync {
    fn elements(&self) -> usize;
    fn delta(&self) -> Vec<f64>;
    fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, Error>;
    /// `out` has T·P entries: the estimate after each sample, row by row.
    fn run(&mut self, x: &[f64], v: &[f64], f: &[f64], out: &mut Vec<f64>) -> Result<(), Error>;
    fn predict(&self, x: f64, v: f64) -> Result<f64, Error>;
    fn estimate(&self) -> Vec<f64>;
    /// P·P entries, column-major (the matrix is symmetric).
    fn covariance(&self) -> Vec<f64>;
    fn covariance_trace(&self) -> f64;
    fn covariance_resets(&self) -> u64;
    fn reset(&mut self);
}

impl<const N: usize, const P: usize> Online for Identifier<N, P> {
    fn elements(&self) -> usize {
        N
    }
    fn delta(&self) -> Vec<f64> {
        Identifier::elements(self).delta().to_vec()
    }
    fn update(&mut self, x: f64, v: f64, f: f64) -> Result<f64, Error> {
        Identifier::update(self, x, v, f)
    }
    fn run(&mut self, x: &[f64], v: &[f64], f: &[f64], out: &mut Vec<f64>) -> Result<(), Error> {
        let mut estimates = vec![[0.0; P]; x.len()];
        Identifier::run(self, x, v, f, &mut estimates)?;
        *out = estimates.into_flattened();
        Ok(())
    }
    fn predict(&self, x: f64, v: f64) -> Result<f64, Error> {
        Identifier::predict(self, x, v)
    }
    fn estimate(&self) -> Vec<f64> {
        Identifier::estimate(self).to_vec()
    }
    fn covariance(&self) -> Vec<f64> {
        self.rls().covariance().as_slice().to_vec()
    }
    fn covariance_trace(&self) -> f64 {
        self.rls().covariance_trace()
    }
    fn covariance_resets(&self) -> u64 {
        self.rls().covariance_resets()
    }
    fn reset(&mut self) {
        Identifier::reset(self);
    }
}

/// Builds the identifier of N = `delta.len()` elements (1 ≤ N ≤ MAX_ELEMENTS, checked by the
/// caller); `initial` has N + 3 entries.
fn build(delta: &[f64], initial: &[f64], settings: RlsSettings) -> Result<Box<dyn Online>, Error> {
    seq!(K in 1..=32 {
        if delta.len() == K {
            let mut d = [0.0; K];
            d.copy_from_slice(delta);
            let mut start = [0.0; K + 3];
            start.copy_from_slice(initial);
            return Ok(Box::new(Identifier::<K, { K + 3 }>::new(d, start, settings)?));
        }
    });
    Err(Error::NoElements)
}

/// A construction error, with the value that broke the rule.
fn settings_error(error: Error, delta: &[f64], settings: &RlsSettings, parameters: usize) -> PyErr {
    let message = match error {
        Error::NotInUnitInterval(Field::forgetting) => {
            format!(
                "`forgetting` must be in (0, 1], got {}",
                show(settings.forgetting)
            )
        }
        Error::NotPositive(Field::initial_covariance) => format!(
            "`initial_covariance` must be finite and > 0, got {}",
            show(settings.initial_covariance)
        ),
        Error::NotPositive(Field::max_trace) => format!(
            "`max_trace` must be finite and > 0, got {}",
            show(settings.max_trace)
        ),
        Error::TraceBelowInitial => format!(
            "`max_trace` must be >= the trace of the initial covariance, {parameters} × \
             initial_covariance = {}, got {}",
            show(parameters as f64 * settings.initial_covariance),
            show(settings.max_trace)
        ),
        Error::Element { field, index } => format!(
            "`{field}[{index}]` must be finite and > 0, got {}",
            show(delta.get(index).copied().unwrap_or(f64::NAN))
        ),
        other => other.to_string(),
    };
    ParameterError::new_err(message)
}

/// An error of an update or a run, with the offending value where there is one.
fn input_error(error: Error, inputs: [&[f64]; 3]) -> PyErr {
    match error {
        Error::NotFinite { field, index } => {
            let input = match field {
                Field::x => inputs[0],
                Field::v => inputs[1],
                _ => inputs[2],
            };
            let value = show(input.get(index).copied().unwrap_or(f64::NAN));
            InputError::new_err(format!(
                "`{field}` must be finite, got {value} at sample {index}"
            ))
        }
        Error::Overflow { index } => InputError::new_err(format!(
            "the least-squares update overflowed at sample {index}: x = {}, v = {}, f = {} are \
             too large for f64 arithmetic (are they in SI units?)",
            show(inputs[0].get(index).copied().unwrap_or(f64::NAN)),
            show(inputs[1].get(index).copied().unwrap_or(f64::NAN)),
            show(inputs[2].get(index).copied().unwrap_or(f64::NAN)),
        )),
        other => InputError::new_err(other.to_string()),
    }
}

/// Recursive least squares on the friction terms that enter linearly.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct OnlineIdentifier {
    inner: Box<dyn Online>,
}

#[pymethods]
impl OnlineIdentifier {
    /// `delta`: N break deflections; `initial`: N + 3 starting values; the settings of the
    /// least squares. Shapes and types are checked by the Python subclass.
    #[new]
    fn new(
        delta: Vec<f64>,
        initial: Vec<f64>,
        forgetting: f64,
        initial_covariance: f64,
        max_trace: f64,
    ) -> PyResult<Self> {
        if delta.is_empty() || delta.len() > MAX_ELEMENTS {
            return Err(ParameterError::new_err(format!(
                "`Delta` must have 1 to {MAX_ELEMENTS} elements, got {}",
                delta.len()
            )));
        }
        let parameters = delta.len() + gms_core::identification::EXTRA_TERMS;
        if initial.len() != parameters {
            return Err(ParameterError::new_err(format!(
                "`initial` must have {parameters} values (W for each of the {} elements, Fc, \
                 sigma2, offset), got {}",
                delta.len(),
                initial.len()
            )));
        }
        let settings = RlsSettings {
            forgetting,
            initial_covariance,
            max_trace,
        };
        let inner = build(&delta, &initial, settings)
            .map_err(|error| settings_error(error, &delta, &settings, parameters))?;
        Ok(Self { inner })
    }

    /// Number of elements N.
    #[getter]
    fn elements(&self) -> usize {
        self.inner.elements()
    }

    /// The break deflections Δᵢ.
    #[getter(Delta)]
    fn delta(&self) -> Vec<f64> {
        self.inner.delta()
    }

    /// One sample; returns the a priori prediction error f − f̂.
    fn update(
        &mut self,
        x: &Bound<'_, PyAny>,
        v: &Bound<'_, PyAny>,
        f: &Bound<'_, PyAny>,
    ) -> PyResult<f64> {
        let (x, v, f) = (real(x, "x")?, real(v, "v")?, real(f, "f")?);
        self.inner
            .update(x, v, f)
            .map_err(|error| input_error(error, [&[x], &[v], &[f]]))
    }

    /// The estimate after each sample of a log, shape (T, N + 3); the GIL is released.
    fn _run<'py>(
        &mut self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        v: PyReadonlyArray1<'py, f64>,
        f: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (x, v, f) = (x.as_slice()?, v.as_slice()?, f.as_slice()?);
        let inner = &mut self.inner;
        let mut out = Vec::new();
        py.detach(|| inner.run(x, v, f, &mut out))
            .map_err(|error| input_error(error, [x, v, f]))?;
        let shape = [
            x.len(),
            self.inner.elements() + gms_core::identification::EXTRA_TERMS,
        ];
        PyArray1::from_vec(py, out).reshape(shape)
    }

    /// The force the current estimate predicts for (x, v); nothing changes.
    fn predict(&self, x: f64, v: f64) -> PyResult<f64> {
        self.inner
            .predict(x, v)
            .map_err(|error| input_error(error, [&[x], &[v], &[f64::NAN]]))
    }

    /// A copy of the estimate [W₀, …, W_{N−1}, Fc, sigma2, offset].
    fn _estimate<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.estimate())
    }

    /// A copy of the covariance P, shape (N + 3, N + 3).
    fn _covariance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let parameters = self.inner.elements() + gms_core::identification::EXTRA_TERMS;
        // Column-major storage of a symmetric matrix reads the same row-major.
        PyArray1::from_vec(py, self.inner.covariance()).reshape([parameters, parameters])
    }

    /// trace(P).
    #[getter]
    fn covariance_trace(&self) -> f64 {
        self.inner.covariance_trace()
    }

    /// How many times the covariance left its range and was reset since construction or reset.
    #[getter]
    fn covariance_resets(&self) -> u64 {
        self.inner.covariance_resets()
    }

    /// Back to the state of construction.
    fn reset(&mut self) {
        self.inner.reset();
    }
}
