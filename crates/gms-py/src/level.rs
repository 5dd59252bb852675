//! `_core.CoreLevel`: a position-dependent friction level (`leuven_rt.PositionLevel`, or any
//! object with its attributes) read into plain values and validated by gms-core, once; the
//! compensator and the position run take it without checking it again.

use gms_dyn::{Level, RippleTerms};
use pyo3::prelude::*;

use crate::errors::{raise, Class, Kind, Refusal};
use crate::params::not_real;

/// One ripple's attributes, as given.
struct GivenRipple {
    period: f64,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

/// Reads the attributes of a `PositionLevel` and has gms-core validate them.
fn read_level(level: &Bound<'_, PyAny>) -> PyResult<Level> {
    // The Python class coerces the types; these messages are for other objects handed in.
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
    let trend = list(level, "trend", "trend")?;
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
    for (index, ripple) in level.getattr("ripples")?.try_iter()?.enumerate() {
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
    Level::new(
        number(level, "middle", "middle")?,
        number(level, "half_stroke", "half_stroke")?,
        trend,
        &terms,
    )
    .map_err(|error| raise(error.into()))
}

/// The validated level of `level` (a `CoreLevel` or a `PositionLevel`-like object).
pub fn level_of(level: &Bound<'_, PyAny>) -> PyResult<Level> {
    match level.cast::<CoreLevel>() {
        Ok(core) => Ok(core.get().level),
        Err(_) => read_level(level),
    }
}

/// A position-dependent friction level validated once (docs/model.md#position-dependent-level).
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

    /// factor(x) as the Rust core computes it (NaN for a non-finite x).
    fn factor(&self, x: f64) -> f64 {
        self.level.factor(x)
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
