//! A Python `Params` read into plain Rust values, and validated by gms-core.

use gms_core::{Field, Linear, LuGreParams, MaxwellSlip, Params, Stribeck};
use pyo3::prelude::*;

use crate::errors::{parameter_error, ParameterError};

/// The values of a Python `Params` object, exactly as given (None levels resolved).
#[derive(Clone, Debug)]
pub struct Spec {
    pub fc: f64,
    pub fs: f64,
    pub vs: f64,
    pub delta: f64,
    pub n: f64,
    pub sigma1: f64,
    pub sigma2: f64,
    pub fc_neg: f64,
    pub fs_neg: f64,
    /// `Some` for linear (LuGre) hysteresis, `None` for Maxwell slip.
    pub sigma0: Option<f64>,
    pub w: Vec<f64>,
    pub big_delta: Vec<f64>,
    /// Whether `W` or `Delta` was given at all (possibly empty).
    pub maxwell_given: bool,
}

impl Spec {
    /// Reads the attributes of a `leuven_rt.Params` (or any object with the same attributes).
    pub fn extract(params: &Bound<'_, PyAny>) -> PyResult<Self> {
        let number = |key: &str| -> PyResult<f64> {
            params
                .getattr(key)?
                .extract::<f64>()
                .map_err(|_| ParameterError::new_err(format!("`{key}` must be a real number")))
        };
        let optional = |key: &str| -> PyResult<Option<f64>> {
            let value = params.getattr(key)?;
            if value.is_none() {
                Ok(None)
            } else {
                number(key).map(Some)
            }
        };
        let list = |key: &str| -> PyResult<Vec<f64>> {
            let value = params.getattr(key)?;
            if value.is_none() {
                return Ok(Vec::new());
            }
            value.extract::<Vec<f64>>().map_err(|_| {
                ParameterError::new_err(format!("`{key}` must be a sequence of real numbers"))
            })
        };
        let fc = number("Fc")?;
        let fs = number("Fs")?;
        let spec = Spec {
            fc,
            fs,
            vs: number("Vs")?,
            delta: number("delta")?,
            n: number("n")?,
            sigma1: number("sigma1")?,
            sigma2: number("sigma2")?,
            fc_neg: optional("Fc_neg")?.unwrap_or(fc),
            fs_neg: optional("Fs_neg")?.unwrap_or(fs),
            sigma0: optional("sigma0")?,
            w: list("W")?,
            big_delta: list("Delta")?,
            maxwell_given: !(params.getattr("W")?.is_none() && params.getattr("Delta")?.is_none()),
        };
        if spec.sigma0.is_none() && spec.w.len() != spec.big_delta.len() {
            return Err(ParameterError::new_err(format!(
                "`W` and `Delta` must have the same length, got {} and {}",
                spec.w.len(),
                spec.big_delta.len()
            )));
        }
        Ok(spec)
    }

    /// The value of a scalar field, for error messages.
    pub fn value(&self, field: Field) -> f64 {
        match field {
            Field::Fc => self.fc,
            Field::Fs => self.fs,
            Field::Vs => self.vs,
            Field::delta => self.delta,
            Field::n => self.n,
            Field::sigma0 => self.sigma0.unwrap_or(f64::NAN),
            Field::sigma1 => self.sigma1,
            Field::sigma2 => self.sigma2,
            Field::Fc_neg => self.fc_neg,
            Field::Fs_neg => self.fs_neg,
            _ => f64::NAN,
        }
    }

    /// The value of element `index` of `W` or `Delta`, for error messages.
    pub fn element(&self, field: Field, index: usize) -> f64 {
        let values = if field == Field::W {
            &self.w
        } else {
            &self.big_delta
        };
        values.get(index).copied().unwrap_or(f64::NAN)
    }

    /// The validated Stribeck curve.
    pub fn stribeck(&self) -> PyResult<Stribeck> {
        Stribeck::asymmetric(
            self.fc,
            self.fs,
            self.fc_neg,
            self.fs_neg,
            self.vs,
            self.delta,
        )
        .map_err(|error| parameter_error(error, self))
    }

    /// The validated LuGre parameters, when the hysteresis is linear.
    pub fn lugre(&self, sigma0: f64) -> PyResult<LuGreParams> {
        let spring = Linear::new(sigma0).map_err(|error| parameter_error(error, self))?;
        Params::new(self.stribeck()?, self.n, self.sigma1, self.sigma2, spring)
            .map_err(|error| parameter_error(error, self))
    }

    /// The validated Maxwell-slip parameters; `W` and `Delta` must have N elements (checked by
    /// the caller).
    pub fn maxwell<const N: usize>(&self) -> PyResult<Params<MaxwellSlip<N>>> {
        let (mut w, mut delta) = ([0.0; N], [0.0; N]);
        w.copy_from_slice(&self.w);
        delta.copy_from_slice(&self.big_delta);
        let elements = MaxwellSlip::new(w, delta).map_err(|error| parameter_error(error, self))?;
        Params::new(self.stribeck()?, self.n, self.sigma1, self.sigma2, elements)
            .map_err(|error| parameter_error(error, self))
    }
}

/// Raises `ParameterError` unless `params` satisfies every rule of DESIGN.md §2.
#[pyfunction]
pub fn check_params(params: &Bound<'_, PyAny>) -> PyResult<()> {
    let spec = Spec::extract(params)?;
    crate::engine::build(&spec, 1, gms_core::Scheme::Implicit).map(|_| ())
}
