//! Python arguments turned into checked Rust values, shared by every binding class.

use gms_core::Scheme;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat};

use crate::errors::{Class, Kind, Refusal};

/// A Python real number as f64: floats on the fast path (the `step` calls of the control loop),
/// then ints and numpy scalars; bools and everything else are refused with an error of `class`
/// (kind `not_real`) naming `name`.
#[inline]
pub fn real_of(value: &Bound<'_, PyAny>, name: &str, class: Class) -> PyResult<f64> {
    if let Ok(float) = value.cast::<PyFloat>() {
        return Ok(float.value());
    }
    if !value.is_instance_of::<PyBool>() {
        if let Ok(number) = value.extract::<f64>() {
            return Ok(number);
        }
    }
    Err(Refusal::new(
        class,
        Kind::NotReal,
        format!("`{name}` must be a real number, got {}", value.repr()?),
    )
    .field(name)
    .value(value)
    .into())
}

/// [`real_of`] for an input: an `InputError`.
#[inline]
pub fn real(value: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    real_of(value, name, Class::Input)
}

/// A channel count of at least 1.
pub fn channel_count(channels: i64) -> PyResult<usize> {
    let refusal = |kind, message| {
        Refusal::new(Class::Input, kind, message)
            .field("channels")
            .value(channels)
    };
    if channels < 1 {
        return Err(refusal(
            Kind::OutOfRange,
            format!("`channels` must be >= 1, got {channels}"),
        )
        .bound(1_i64)
        .into());
    }
    usize::try_from(channels).map_err(|_| {
        refusal(
            Kind::OutOfMemory,
            format!("`channels` = {channels} does not fit in memory"),
        )
        .into()
    })
}

/// Refuses `method` on an object (a "model", a "system") of other than one channel.
#[inline]
pub fn single_channel(channels: usize, method: &str, owner: &str) -> PyResult<()> {
    if channels == 1 {
        Ok(())
    } else {
        Err(Refusal::new(
            Class::Input,
            Kind::ChannelMismatch,
            format!(
                "`{method}` steps one channel, this {owner} has {channels}: use `step_channels`"
            ),
        )
        .lengths(1_usize, channels)
        .into())
    }
}

/// Refuses an input of `got` channels (rows) for an object of `channels`.
pub fn same_channels(got: usize, channels: usize, input: &str, owner: &str) -> PyResult<()> {
    if got == channels {
        Ok(())
    } else {
        Err(Refusal::new(
            Class::Input,
            Kind::ChannelMismatch,
            format!("{input} has {got} channels, this {owner} has {channels}"),
        )
        .lengths(channels, got)
        .into())
    }
}

/// 'implicit' (also when not given) or 'explicit'.
pub fn parse_scheme(scheme: Option<&Bound<'_, PyAny>>) -> PyResult<Scheme> {
    let Some(scheme) = scheme else {
        return Ok(Scheme::Implicit);
    };
    match scheme.extract::<String>().as_deref() {
        Ok("implicit") => Ok(Scheme::Implicit),
        Ok("explicit") => Ok(Scheme::Explicit),
        _ => Err(Refusal::new(
            Class::Input,
            Kind::InvalidChoice,
            format!(
                "`scheme` must be 'implicit' or 'explicit', got {}",
                scheme.repr()?
            ),
        )
        .field("scheme")
        .value(scheme)
        .into()),
    }
}

/// The name `parse_scheme` takes for `scheme`.
pub fn scheme_name(scheme: Scheme) -> &'static str {
    match scheme {
        Scheme::Implicit => "implicit",
        Scheme::Explicit => "explicit",
    }
}

/// `len` zeros for an output array, or an `InputError` if they do not fit in memory (an
/// infallible allocation would abort the interpreter).
pub fn zeros(len: usize, name: &str) -> PyResult<Vec<f64>> {
    let mut out = Vec::new();
    out.try_reserve_exact(len).map_err(|_| {
        PyErr::from(
            Refusal::new(
                Class::Input,
                Kind::OutOfMemory,
                format!(
                    "`{name}` of {len} samples does not fit in memory ({} bytes of output)",
                    len.saturating_mul(8)
                ),
            )
            .field(name)
            .value(len),
        )
    })?;
    out.resize(len, 0.0);
    Ok(out)
}
