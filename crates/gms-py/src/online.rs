//! `_core.OnlineIdentifier`: gms-core's online identification (recursive least squares on
//! F = Σ Wᵢψᵢ + Fc·sgn(v) + sigma2·v + offset), stepped from Python or run over a whole log.
//!
//! gms-dyn chooses the number of elements N at run time. `leuven_rt.OnlineIdentifier` subclasses the class, so that `update` reaches Rust without a
//! Python frame in between; it checks array shapes and dtypes before the calls arrive here.

use gms_core::RlsSettings;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::convert::real;
use crate::errors::{input_error, lend, lend_mut, raise_as, Class};

/// Recursive least squares on the friction terms that enter linearly.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct OnlineIdentifier {
    inner: gms_dyn::OnlineIdentifier,
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
        let settings = RlsSettings {
            forgetting,
            initial_covariance,
            max_trace,
        };
        // Every construction error is about the identifier's parameters.
        let inner = gms_dyn::OnlineIdentifier::new(&delta, &initial, settings)
            .map_err(|error| raise_as(Class::Parameter, error, error.to_string()))?;
        Ok(Self { inner })
    }

    /// Number of elements N.
    #[getter]
    fn elements(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.inner.elements())
    }

    /// The break deflections Δᵢ.
    #[getter(Delta)]
    fn delta(slf: &Bound<'_, Self>) -> PyResult<Vec<f64>> {
        Ok(lend(slf)?.inner.delta().to_vec())
    }

    /// One sample; returns the a priori prediction error f − f̂.
    fn update(
        slf: &Bound<'_, Self>,
        x: &Bound<'_, PyAny>,
        v: &Bound<'_, PyAny>,
        f: &Bound<'_, PyAny>,
    ) -> PyResult<f64> {
        let mut this = lend_mut(slf)?;
        let (x, v, f) = (real(x, "x")?, real(v, "v")?, real(f, "f")?);
        this.inner.update(x, v, f).map_err(input_error)
    }

    /// The estimate after each sample of a log, shape (T, N + 3); the GIL is released.
    fn _run<'py>(
        slf: &Bound<'py, Self>,
        x: PyReadonlyArray1<'py, f64>,
        v: PyReadonlyArray1<'py, f64>,
        f: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let py = slf.py();
        let mut this = lend_mut(slf)?;
        let (x, v, f) = (x.as_slice()?, v.as_slice()?, f.as_slice()?);
        let shape = [x.len(), this.inner.parameters()];
        let mut out = vec![0.0; shape[0] * shape[1]];
        let inner = &mut this.inner;
        py.detach(|| inner.run(x, v, f, &mut out))
            .map_err(input_error)?;
        PyArray1::from_vec(py, out).reshape(shape)
    }

    /// The force the current estimate predicts for (x, v); nothing changes.
    fn predict(slf: &Bound<'_, Self>, x: f64, v: f64) -> PyResult<f64> {
        lend(slf)?.inner.predict(x, v).map_err(input_error)
    }

    /// A copy of the estimate [W₀, …, W_{N−1}, Fc, sigma2, offset].
    fn _estimate<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(PyArray1::from_vec(slf.py(), lend(slf)?.inner.estimate()))
    }

    /// A copy of the covariance P, shape (N + 3, N + 3).
    fn _covariance<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let this = lend(slf)?;
        let parameters = this.inner.parameters();
        // Column-major storage of a symmetric matrix reads the same row-major.
        PyArray1::from_vec(slf.py(), this.inner.covariance()).reshape([parameters, parameters])
    }

    /// trace(P).
    #[getter]
    fn covariance_trace(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.inner.covariance_trace())
    }

    /// How many times the covariance left its range and was reset since construction or reset.
    #[getter]
    fn covariance_resets(slf: &Bound<'_, Self>) -> PyResult<u64> {
        Ok(lend(slf)?.inner.covariance_resets())
    }

    /// Back to the state of construction.
    fn reset(slf: &Bound<'_, Self>) -> PyResult<()> {
        lend_mut(slf)?.inner.reset();
        Ok(())
    }
}
