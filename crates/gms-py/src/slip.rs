//! `_core.slip_responses`: Maxwell-slip elements with unit weights driven along a path, the
//! regressor columns of identification and of the discrepancy workflow.

use gms_core::{Error, Field, SlipRegressor};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use seq_macro::seq;

use crate::engine::MAX_ELEMENTS;
use crate::errors::{block_error, show, InputError};

fn responses<const N: usize>(delta: &[f64], x: &[f64], out: &mut [f64]) -> Result<(), Error> {
    let mut delta_array = [0.0; N];
    delta_array.copy_from_slice(delta);
    SlipRegressor::new(delta_array)?.responses(x, out)
}

/// One group of at most MAX_ELEMENTS elements, rows of `delta.len()` in `out`.
fn group_responses(delta: &[f64], x: &[f64], out: &mut [f64]) -> Result<(), Error> {
    seq!(N in 1..=32 {
        match delta.len() {
            #(N => responses::<N>(delta, x, out),)*
            _ => unreachable!("groups hold 1 to MAX_ELEMENTS elements"),
        }
    })
}

/// The responses ψᵢ ∈ [−1, 1] of elements with break deflections `delta` driven by `x`, all
/// relaxed at the first sample, shape (T, N); computed with the GIL released. The elements are
/// independent: they run in groups of MAX_ELEMENTS, whatever N is.
#[pyfunction]
pub fn slip_responses<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    delta: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (x, delta) = (x.as_slice()?, delta.as_slice()?);
    let elements = delta.len();
    let mut out = vec![0.0; x.len() * elements];
    let result = py.detach(|| {
        let mut group = Vec::new();
        for (first, chunk) in (0..).step_by(MAX_ELEMENTS).zip(delta.chunks(MAX_ELEMENTS)) {
            group.resize(x.len() * chunk.len(), 0.0);
            group_responses(chunk, x, &mut group).map_err(|error| match error {
                Error::Element { field, index } => Error::Element {
                    field,
                    index: first + index,
                },
                other => other,
            })?;
            for (row, values) in out
                .chunks_exact_mut(elements)
                .zip(group.chunks_exact(chunk.len()))
            {
                row[first..first + chunk.len()].copy_from_slice(values);
            }
        }
        Ok(())
    });
    result.map_err(|error| match error {
        Error::Element { index, .. } => InputError::new_err(format!(
            "`Delta[{index}]` must be finite and > 0 (and 1/Delta finite), got {}",
            show(delta[index])
        )),
        Error::NotFinite {
            field: Field::x, ..
        } => block_error(error, x, 0, None),
        other => InputError::new_err(other.to_string()),
    })?;
    PyArray1::from_vec(py, out).reshape([x.len(), elements])
}
