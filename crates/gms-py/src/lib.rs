//! `leuven_rt._core`: the thin PyO3 layer over gms-core.
//!
//! It turns a Python `Params` into a validated gms-core parameter set, runs the pure-Rust loops
//! with the GIL released, and maps gms-core's error enum onto the Python exception classes.
//! Array shape and dtype checks happen in the Python package before the calls arrive here.

mod bank;
mod compensator;
mod convert;
mod engine;
mod errors;
mod mechanics;
mod model;
mod online;
mod slip;
mod spec;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ParameterError", py.get_type::<errors::ParameterError>())?;
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add("DivergenceError", py.get_type::<errors::DivergenceError>())?;
    m.add("MAX_ELEMENTS", engine::MAX_ELEMENTS)?;
    m.add("MAX_ITERATIONS", gms_core::MAX_ITERATIONS)?;
    m.add_function(wrap_pyfunction!(spec::check_params, m)?)?;
    m.add_function(wrap_pyfunction!(slip::slip_responses, m)?)?;
    m.add_class::<model::Engine>()?;
    m.add_class::<mechanics::MassEngine>()?;
    m.add_class::<compensator::CompensatorEngine>()?;
    m.add_class::<online::OnlineIdentifier>()?;
    Ok(())
}
