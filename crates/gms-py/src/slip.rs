//! `_core.slip_responses`: Maxwell-slip elements with unit weights driven along a path, the
//! regressor columns of identification and of the discrepancy workflow.

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors::input_error;

/// The responses ψᵢ ∈ [−1, 1] of elements with break deflections `delta` driven by `x`, all
/// relaxed at the first sample, shape (T, N); computed with the GIL released.
#[pyfunction]
pub fn slip_responses<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    delta: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (x, delta) = (x.as_slice()?, delta.as_slice()?);
    let mut out = vec![0.0; x.len() * delta.len()];
    // Both inputs are the caller's signals here, so every refusal is an input error.
    py.detach(|| gms_dyn::slip_responses(x, delta, &mut out))
        .map_err(input_error)?;
    PyArray1::from_vec(py, out).reshape([x.len(), delta.len()])
}
