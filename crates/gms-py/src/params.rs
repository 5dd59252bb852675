//! Python parameter sets: `leuven_rt.Params` (or any object with its attributes) read into
//! plain values, and `_core.CoreParams`, a parameter set validated once and reusable by every
//! engine constructor without checking it again.

use gms_dyn::{ParameterSet, RawElements, RawParams};
use pyo3::prelude::*;

use crate::errors::{raise, Class, Kind, Refusal};

/// The `ParameterError` for attribute `key` of a parameter object that is not `what`.
pub fn not_real(key: &str, what: &str) -> PyErr {
    Refusal::new(
        Class::Parameter,
        Kind::NotReal,
        format!("`{key}` must be {what}"),
    )
    .field(key)
    .into()
}

/// The attributes of a Python `Params`, exactly as given (`None` levels resolved).
pub struct GivenParams {
    fc: f64,
    fs: f64,
    vs: f64,
    delta: f64,
    n: f64,
    sigma1: f64,
    sigma2: f64,
    fc_neg: f64,
    fs_neg: f64,
    sigma2_neg: Option<f64>,
    sigma0: Option<f64>,
    w: Option<Vec<f64>>,
    big_delta: Option<Vec<f64>>,
}

impl GivenParams {
    /// Reads the attributes of a `leuven_rt.Params` (or any object with the same attributes).
    fn extract(params: &Bound<'_, PyAny>) -> PyResult<Self> {
        let number = |key: &str| -> PyResult<f64> {
            params
                .getattr(key)?
                .extract::<f64>()
                .map_err(|_| not_real(key, "a real number"))
        };
        let optional = |key: &str| -> PyResult<Option<f64>> {
            let value = params.getattr(key)?;
            if value.is_none() {
                Ok(None)
            } else {
                number(key).map(Some)
            }
        };
        let list = |key: &str| -> PyResult<Option<Vec<f64>>> {
            let value = params.getattr(key)?;
            if value.is_none() {
                return Ok(None);
            }
            value
                .extract::<Vec<f64>>()
                .map(Some)
                .map_err(|_| not_real(key, "a sequence of real numbers"))
        };
        let (fc, fs) = (number("Fc")?, number("Fs")?);
        Ok(Self {
            fc,
            fs,
            vs: number("Vs")?,
            delta: number("delta")?,
            n: number("n")?,
            sigma1: number("sigma1")?,
            sigma2: number("sigma2")?,
            fc_neg: optional("Fc_neg")?.unwrap_or(fc),
            fs_neg: optional("Fs_neg")?.unwrap_or(fs),
            sigma2_neg: optional("sigma2_neg")?,
            sigma0: optional("sigma0")?,
            w: list("W")?,
            big_delta: list("Delta")?,
        })
    }

    /// The values as gms-dyn takes them; `W` without `Delta` (or the reverse) is an empty list.
    fn raw(&self) -> RawParams<'_> {
        let given = self.w.is_some() || self.big_delta.is_some();
        RawParams {
            fc: self.fc,
            fs: self.fs,
            vs: self.vs,
            delta: self.delta,
            n: self.n,
            sigma1: self.sigma1,
            sigma2: self.sigma2,
            fc_neg: self.fc_neg,
            fs_neg: self.fs_neg,
            sigma2_neg: self.sigma2_neg,
            sigma0: self.sigma0,
            elements: given.then(|| RawElements {
                w: self.w.as_deref().unwrap_or_default(),
                delta: self.big_delta.as_deref().unwrap_or_default(),
            }),
        }
    }
}

/// What a Python caller passed as parameters: a validated [`CoreParams`], or a `Params`-like
/// object still to be read and validated.
pub enum PythonParams {
    /// Validated already.
    Validated(Box<ParameterSet>),
    /// Read, not yet validated.
    Given(GivenParams),
}

impl PythonParams {
    /// Reads `params`; a `CoreParams` is taken as it is.
    pub fn extract(params: &Bound<'_, PyAny>) -> PyResult<Self> {
        match params.cast::<CoreParams>() {
            Ok(core) => Ok(Self::Validated(Box::new(core.get().set))),
            Err(_) => GivenParams::extract(params).map(Self::Given),
        }
    }

    /// The validated set; a `ParameterError` names the first rule broken.
    pub fn validate(&self) -> PyResult<ParameterSet> {
        match self {
            Self::Validated(set) => Ok(**set),
            Self::Given(given) => given.raw().validate().map_err(raise),
        }
    }

    /// The values as given, when they were not validated already.
    pub fn raw(&self) -> Option<RawParams<'_>> {
        match self {
            Self::Validated(_) => None,
            Self::Given(given) => Some(given.raw()),
        }
    }
}

/// The validated parameter set of `params` (a `CoreParams` or a `Params`-like object).
pub fn parameter_set(params: &Bound<'_, PyAny>) -> PyResult<ParameterSet> {
    PythonParams::extract(params)?.validate()
}

/// A friction parameter set validated once; every engine constructor also takes one of these
/// in place of a `Params`, without checking it again.
#[pyclass(frozen, module = "leuven_rt._core")]
pub struct CoreParams {
    set: ParameterSet,
}

#[pymethods]
impl CoreParams {
    /// Validates any object with the attributes of `leuven_rt.Params` (`Fc, Fs, Vs, delta, n,
    /// sigma1, sigma2, Fc_neg, Fs_neg, sigma2_neg, sigma0, W, Delta`); raises `ParameterError`
    /// naming the first rule broken.
    #[new]
    fn new(params: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Self {
            set: parameter_set(params)?,
        })
    }

    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(&self) -> usize {
        self.set.elements()
    }

    fn __repr__(&self) -> String {
        format!("CoreParams(<{}>)", self.set.kind())
    }
}

/// Raises `ParameterError` unless `params` satisfies every rule of docs/parameters.md#rules.
#[pyfunction]
pub fn check_params(params: &Bound<'_, PyAny>) -> PyResult<()> {
    parameter_set(params).map(|_| ())
}
