//! `leuven_rt._core`: the thin `PyO3` layer over gms-dyn, gms-fit and gms-core.
//!
//! It reads Python arguments into plain Rust values, hands them to gms-dyn (which validates
//! them, chooses the number of elements and runs the loops, here with the GIL released), and
//! sorts gms-dyn's errors into the Python exception classes. Array shape and dtype checks
//! happen in the Python package before the calls arrive here.

// PyO3 extracts arguments (arrays, lists) by value; the methods only read them.
#![allow(clippy::needless_pass_by_value)]

mod compensator;
mod convert;
mod errors;
mod file;
mod fit;
mod level;
mod mechanics;
mod model;
mod online;
mod params;
mod slip;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    for class in errors::Class::ALL {
        m.add(class.name(), class.get(py)?)?;
    }
    // Every kind an error raised by the extension can have (docs/errors.md#kinds).
    m.add("ERROR_KINDS", errors::kinds())?;
    // The version of the package: the workspace's, which maturin also gives the wheel.
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_ELEMENTS", gms_dyn::MAX_ELEMENTS)?;
    m.add("MAX_ITERATIONS", gms_core::MAX_ITERATIONS)?;
    // The model file's format and the version it is written in: gms-file's, its one owner.
    m.add("MODEL_FILE_FORMAT", gms_file::FORMAT)?;
    m.add("MODEL_FILE_VERSION", gms_file::VERSION)?;
    m.add_function(wrap_pyfunction!(params::check_params, m)?)?;
    m.add_function(wrap_pyfunction!(slip::slip_responses, m)?)?;
    m.add_function(wrap_pyfunction!(fit::sensitivities, m)?)?;
    m.add_function(wrap_pyfunction!(fit::simulate_sets, m)?)?;
    m.add_function(wrap_pyfunction!(file::model_file_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(file::model_file_from_object, m)?)?;
    m.add_function(wrap_pyfunction!(file::model_file_load, m)?)?;
    m.add_function(wrap_pyfunction!(file::model_file_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(file::parameter_file_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(file::parameter_file_to_json, m)?)?;
    m.add_class::<params::CoreParams>()?;
    m.add_class::<level::CoreLevel>()?;
    m.add_class::<level::CorePositionForce>()?;
    m.add("MAX_RIPPLES", gms_dyn::MAX_RIPPLES)?;
    m.add("MAX_HARMONICS", gms_dyn::MAX_HARMONICS)?;
    m.add_class::<model::Engine>()?;
    m.add_class::<mechanics::MassEngine>()?;
    m.add_class::<compensator::CompensatorEngine>()?;
    m.add_class::<online::OnlineIdentifier>()?;
    Ok(())
}
