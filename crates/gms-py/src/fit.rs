//! `_core.sensitivities` and `_core.simulate_sets`: the two calls of the output-error engine
//! (gms-fit), with the GIL released. `leuven_rt.fitting.sensitivity` coerces the arguments.

use gms_core::Scheme;
use gms_dyn::{Input, ParameterSet};
use gms_fit::Simulation;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::convert::{parse_scheme, zeros};
use crate::errors::{raise_fit, Class, Kind, Refusal};
use crate::params::parameter_set;

/// The forces (T,), the Jacobian at the rows (R, P) and the names of its columns.
type Sensitivities<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Vec<String>,
);

/// Sample indices as numpy gives them: signed (any negative one is refused) or unsigned.
#[derive(FromPyObject)]
pub enum Rows<'py> {
    /// int64.
    Signed(PyReadonlyArray1<'py, i64>),
    /// uint64.
    Unsigned(PyReadonlyArray1<'py, u64>),
}

impl Rows<'_> {
    /// The indices as gms-fit takes them; their order and range are gms-fit's to check.
    fn indices(&self) -> PyResult<Vec<usize>> {
        match self {
            Rows::Signed(rows) => rows
                .as_slice()?
                .iter()
                .enumerate()
                .map(|(index, &row)| {
                    usize::try_from(row).map_err(|_| {
                        Refusal::new(
                            Class::Input,
                            Kind::OutOfRange,
                            format!(
                                "`rows` must be sample indices >= 0, got rows[{index}] = {row}"
                            ),
                        )
                        .field(format!("rows[{index}]"))
                        .index(index)
                        .value(row)
                        .bound(0_i64)
                        .into()
                    })
                })
                .collect(),
            // u64 and usize are one width on the 64-bit targets the wheels are built for; a
            // row beyond usize would be beyond any signal, which gms-fit refuses by its range.
            Rows::Unsigned(rows) => Ok(rows
                .as_slice()?
                .iter()
                .map(|&row| usize::try_from(row).unwrap_or(usize::MAX))
                .collect()),
        }
    }
}

fn simulation(signal: &[f64], dt: f64, position: bool, scheme: Scheme) -> Simulation<'_> {
    Simulation {
        signal,
        input: if position {
            Input::Position
        } else {
            Input::Velocity
        },
        dt,
        scheme,
    }
}

/// The friction force of `params` along `signal` (T,) and its derivatives by every parameter
/// at the samples `rows` (R,), computed with the GIL released.
#[pyfunction]
#[pyo3(signature = (params, signal, dt, position, scheme, rows))]
pub fn sensitivities<'py>(
    py: Python<'py>,
    params: &Bound<'py, PyAny>,
    signal: PyReadonlyArray1<'py, f64>,
    dt: f64,
    position: bool,
    scheme: &Bound<'py, PyAny>,
    rows: Rows<'py>,
) -> PyResult<Sensitivities<'py>> {
    let set = parameter_set(params)?;
    let scheme = parse_scheme(Some(scheme))?;
    let rows = rows.indices()?;
    let signal = signal.as_slice()?;
    let kind = set.kind();
    let columns = gms_fit::column_count(kind);
    let mut force = zeros(signal.len(), "signal")?;
    let mut jacobian = zeros(rows.len().saturating_mul(columns), "rows")?;
    let simulation = simulation(signal, dt, position, scheme);
    py.detach(|| gms_fit::sensitivities(&set, simulation, &rows, &mut force, &mut jacobian))
        .map_err(raise_fit)?;
    Ok((
        PyArray1::from_vec(py, force),
        PyArray1::from_vec(py, jacobian).reshape([rows.len(), columns])?,
        gms_fit::column_names(kind),
    ))
}

/// The friction force of every parameter set in `params` along `signal` (T,), each from a
/// relaxed channel, shape (B, T); the sets run in parallel with the GIL released.
#[pyfunction]
#[pyo3(signature = (params, signal, dt, position, scheme))]
pub fn simulate_sets<'py>(
    py: Python<'py>,
    params: Vec<Bound<'py, PyAny>>,
    signal: PyReadonlyArray1<'py, f64>,
    dt: f64,
    position: bool,
    scheme: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let sets = params
        .iter()
        .map(parameter_set)
        .collect::<PyResult<Vec<ParameterSet>>>()?;
    let scheme = parse_scheme(Some(scheme))?;
    let signal = signal.as_slice()?;
    let mut forces = zeros(sets.len().saturating_mul(signal.len()), "signal")?;
    let simulation = simulation(signal, dt, position, scheme);
    py.detach(|| gms_fit::simulate_sets(&sets, simulation, &mut forces))
        .map_err(raise_fit)?;
    PyArray1::from_vec(py, forces).reshape([sets.len(), signal.len()])
}
