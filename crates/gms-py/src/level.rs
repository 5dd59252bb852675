//! `_core.CoreLevel` and `_core.CorePositionForce`: a position-dependent level
//! (`leuven_rt.PositionLevel`) or a position force (`leuven_rt.PositionForce`), or any object with
//! their attributes, read into plain values and validated by gms-core, once; the compensator and
//! the runs take them without checking them again, and their evaluation is gms-core's.

use gms_dyn::{Level, PositionForce, RippleTerms};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors::{raise, Class, Kind, Refusal};
use crate::params::not_real;

/// One ripple's attributes, as given.
struct GivenRipple {
    period: f64,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

/// Reads the attributes shared by a level and a position force (`middle`, `half_stroke`,
/// `trend`, `ripples`) and has gms-core validate them with `build`.
fn read_series<T>(
    series: &Bound<'_, PyAny>,
    build: impl FnOnce(f64, f64, [f64; 2], &[RippleTerms<'_>]) -> Result<T, gms_core::Error>,
) -> PyResult<T> {
    // The Python classes coerce the types; these messages are for other objects handed in.
    let number = |owner: &Bound<'_, PyAny>, key: &str, name: &str| -> PyResult<f64> {
        owner
            .getattr(key)?
            .extract::<f64>()
            .map_err(|_| not_real(name, "a real number"))
    };
    let list = |owner: &Bound<'_, PyAny>, key: &str, name: &str| -> PyResult<Vec<f64>> {
        owner
            .getattr(key)?
            .extract::<Vec<f64>>()
            .map_err(|_| not_real(name, "a sequence of real numbers"))
    };
    let trend = list(series, "trend", "trend")?;
    let trend: [f64; 2] = trend.as_slice().try_into().map_err(|_| {
        PyErr::from(
            Refusal::new(
                Class::Parameter,
                Kind::WrongLength,
                format!(
                    "`trend` must have 2 coefficients (t1, t2), got {}",
                    trend.len()
                ),
            )
            .field("trend")
            .lengths(2_usize, trend.len()),
        )
    })?;
    let mut ripples = Vec::new();
    for (index, ripple) in series.getattr("ripples")?.try_iter()?.enumerate() {
        let ripple = ripple?;
        let name = |key: &str| format!("ripples[{index}].{key}");
        ripples.push(GivenRipple {
            period: number(&ripple, "period", &name("period"))?,
            cos: list(&ripple, "cos", &name("cos"))?,
            sin: list(&ripple, "sin", &name("sin"))?,
        });
    }
    let terms: Vec<RippleTerms<'_>> = ripples
        .iter()
        .map(|ripple| RippleTerms {
            period: ripple.period,
            cos: &ripple.cos,
            sin: &ripple.sin,
        })
        .collect();
    build(
        number(series, "middle", "middle")?,
        number(series, "half_stroke", "half_stroke")?,
        trend,
        &terms,
    )
    .map_err(|error| raise(error.into()))
}

/// The validated level of `level` (a `CoreLevel` or a `PositionLevel`-like object).
pub fn level_of(level: &Bound<'_, PyAny>) -> PyResult<Level> {
    match level.cast::<CoreLevel>() {
        Ok(core) => Ok(core.get().level),
        Err(_) => read_series(level, Level::new),
    }
}

/// The validated level of an optional argument: `None` is the flat level.
pub fn optional_level(level: Option<&Bound<'_, PyAny>>) -> PyResult<Level> {
    match level {
        Some(level) if !level.is_none() => level_of(level),
        _ => Ok(Level::none()),
    }
}

/// The validated position force of `force` (a `CorePositionForce` or a `PositionForce`-like
/// object).
pub fn position_force_of(force: &Bound<'_, PyAny>) -> PyResult<PositionForce> {
    match force.cast::<CorePositionForce>() {
        Ok(core) => Ok(core.get().force),
        Err(_) => read_series(force, PositionForce::new),
    }
}

/// The validated position force of an optional argument: `None` is no position force.
pub fn optional_position_force(force: Option<&Bound<'_, PyAny>>) -> PyResult<PositionForce> {
    match force {
        Some(force) if !force.is_none() => position_force_of(force),
        _ => Ok(PositionForce::none()),
    }
}

/// A position-dependent level validated once (docs/model.md#position-dependent-level).
#[pyclass(frozen, module = "leuven_rt._core")]
pub struct CoreLevel {
    level: Level,
}

#[pymethods]
impl CoreLevel {
    /// Validates any object with the attributes of `leuven_rt.PositionLevel` (`middle`,
    /// `half_stroke`, `trend`, `ripples`, each ripple with `period`, `cos`, `sin`); raises
    /// `ParameterError` naming the first rule broken.
    #[new]
    fn new(level: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Self {
            level: level_of(level)?,
        })
    }

    /// factor(x) at every position of `x` (1-D float64), as gms-core computes it (NaN for a
    /// non-finite x).
    fn factor<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_iter(py, x.as_array().iter().map(|&x| self.level.factor(x)))
    }

    /// Number of ripples.
    #[getter]
    fn ripples(&self) -> usize {
        self.level.ripple_count()
    }

    fn __repr__(&self) -> String {
        format!("CoreLevel(<{} ripples>)", self.level.ripple_count())
    }
}

/// A position force validated once (docs/model.md#position-dependent-level).
#[pyclass(frozen, module = "leuven_rt._core")]
pub struct CorePositionForce {
    force: PositionForce,
}

#[pymethods]
impl CorePositionForce {
    /// Validates any object with the attributes of `leuven_rt.PositionForce` (those of a
    /// level); raises `ParameterError` naming the first rule broken.
    #[new]
    fn new(force: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Self {
            force: position_force_of(force)?,
        })
    }

    /// r(x) at every position of `x` (1-D float64), as gms-core computes it (NaN for a
    /// non-finite x).
    fn force<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_iter(py, x.as_array().iter().map(|&x| self.force.force(x)))
    }

    /// Number of ripples.
    #[getter]
    fn ripples(&self) -> usize {
        self.force.series().ripple_count()
    }

    fn __repr__(&self) -> String {
        format!(
            "CorePositionForce(<{} ripples>)",
            self.force.series().ripple_count()
        )
    }
}
