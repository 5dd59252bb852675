//! The value checks shared by every constructor and step: each failure names the field.

use crate::error::{Error, Field};

/// Checks that `value` is finite and strictly positive, and not subnormal: the model divides by
/// these values, and the reciprocal of a subnormal overflows.
pub(crate) fn positive(value: f64, field: Field) -> Result<f64, Error> {
    if value.is_finite() && value >= f64::MIN_POSITIVE {
        Ok(value)
    } else {
        Err(Error::NotPositive { field, value })
    }
}

/// Checks that `value` is finite and non-negative.
pub(crate) fn non_negative(value: f64, field: Field) -> Result<f64, Error> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::Negative { field, value })
    }
}

/// Checks that one input sample is finite (a single step reports index 0).
pub(crate) fn finite(value: f64, field: Field) -> Result<(), Error> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::NotFinite {
            field,
            index: 0,
            value,
        })
    }
}

/// Checks that every sample of a block input is finite, naming the first one that is not.
pub(crate) fn all_finite(values: &[f64], field: Field) -> Result<(), Error> {
    match values.iter().position(|value| !value.is_finite()) {
        Some(index) => Err(Error::NotFinite {
            field,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}
