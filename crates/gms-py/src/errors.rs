//! Python exception classes, and gms-core errors turned into expected-vs-got messages.

use gms_core::{Error, Field};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

use crate::spec::Spec;

create_exception!(
    leuven_rt,
    ParameterError,
    PyValueError,
    "A friction-model parameter breaks its rule (DESIGN.md §2)."
);
create_exception!(
    leuven_rt,
    InputError,
    PyValueError,
    "An input signal, step size or option is not what the function expects."
);
create_exception!(
    leuven_rt,
    DivergenceError,
    PyValueError,
    "The explicit scheme blew up: the step is too large for the stiffness."
);

/// A parameter error with the value that broke the rule.
pub fn parameter_error(error: Error, spec: &Spec) -> PyErr {
    let message = match error {
        Error::NotPositive(field) => {
            format!(
                "`{field}` must be finite and > 0, got {}{}",
                show(spec.value(field)),
                subnormal_note(spec.value(field))
            )
        }
        Error::Negative(field) => {
            format!(
                "`{field}` must be finite and >= 0, got {}",
                show(spec.value(field))
            )
        }
        Error::StaticBelowCoulomb(Field::Fs_neg) => format!(
            "`Fs_neg` must be >= `Fc_neg` = {}, got {}",
            show(spec.value(Field::Fc_neg)),
            show(spec.value(Field::Fs_neg))
        ),
        Error::StaticBelowCoulomb(_) => format!(
            "`Fs` must be >= `Fc` = {}, got {}",
            show(spec.value(Field::Fc)),
            show(spec.value(Field::Fs))
        ),
        Error::Element { field, index } => {
            format!(
                "`{field}[{index}]` must be finite and > 0, got {}",
                show(spec.element(field, index))
            )
        }
        Error::ElementsTooWeak => format!(
            "`sum(W)` must be > max(`Fs`, `Fs_neg`) = {}, got sum(W) = {}: the hysteresis force \
             could never balance the Stribeck curve",
            show(spec.value(Field::Fs).max(spec.value(Field::Fs_neg))),
            show(spec.w.iter().sum::<f64>())
        ),
        other => other.to_string(),
    };
    ParameterError::new_err(message)
}

/// An error of a step or a block run, with the value that broke the rule where there is one,
/// and the channel where the model has several.
pub fn run_error(error: Error, value: f64, channel: Option<usize>) -> PyErr {
    let at = |index: usize| match channel {
        Some(channel) => format!("channel {channel}, sample {index}"),
        None => format!("sample {index}"),
    };
    match error {
        Error::Diverged { index } => DivergenceError::new_err(format!(
            "the explicit step diverged at {}: dt is too large for the stiffness; use the \
             implicit scheme",
            at(index)
        )),
        Error::NotPositive(Field::dt) => dt_error(value),
        Error::NotFinite { field, index } => InputError::new_err(format!(
            "`{field}` must be finite, got {} at {}",
            show(value),
            at(index)
        )),
        other => InputError::new_err(other.to_string()),
    }
}

/// A step size that is not finite and > 0.
pub fn dt_error(dt: f64) -> PyErr {
    InputError::new_err(format!(
        "`dt` must be finite and > 0, got {}{}",
        show(dt),
        subnormal_note(dt)
    ))
}

/// A float as Python users read it: shortest round-trip digits, `nan`, `inf`.
pub fn show(value: f64) -> String {
    if value.is_nan() {
        "nan".into()
    } else if value.is_infinite() {
        if value > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{value:?}")
    }
}

/// Why a positive value was refused when it is subnormal: its reciprocal overflows.
fn subnormal_note(value: f64) -> &'static str {
    if value > 0.0 && value < f64::MIN_POSITIVE {
        " (a subnormal number: at least 2.2e-308 is needed)"
    } else {
        ""
    }
}

/// The error of a single step of one channel: the value shown is the offending input or dt.
pub fn step_error(error: Error, input: f64, dt: f64) -> PyErr {
    let value = match error {
        Error::NotPositive(_) => dt,
        // A finite position can still give an infinite velocity over a tiny dt.
        _ if input.is_finite() => f64::INFINITY,
        _ => input,
    };
    run_error(error, value, None)
}

/// The error of a block call; `row` is the channel's input, or the (B,) samples of one step
/// with `offset` channels before it.
pub fn block_error(error: Error, row: &[f64], offset: usize, channel: Option<usize>) -> PyErr {
    let value = match error {
        Error::NotFinite { index, .. } => {
            let sample = row.get(index + offset).copied().unwrap_or(f64::NAN);
            if sample.is_finite() {
                f64::INFINITY
            } else {
                sample
            }
        }
        _ => f64::NAN,
    };
    run_error(error, value, channel)
}
