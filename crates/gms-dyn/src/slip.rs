//! Maxwell-slip elements with unit weights driven along a path: the regressor columns of
//! identification, for any number of elements.

use gms_core::SlipRegressor;

use crate::error::Error;
use crate::params::with_element_count;
use crate::MAX_ELEMENTS;

fn group<const N: usize>(delta: &[f64], x: &[f64], out: &mut [f64]) -> Result<(), gms_core::Error> {
    let mut delta_array = [0.0; N];
    delta_array.copy_from_slice(delta);
    SlipRegressor::new(delta_array)?.responses(x, out)
}

/// The responses ψᵢ ∈ [−1, 1] of elements with break deflections `delta` driven by `x`, all
/// relaxed at the first sample, written into `out` (T × N, row-major). The elements are
/// independent, so any N is computed in groups of [`MAX_ELEMENTS`].
///
/// # Errors
/// A break deflection not finite and > 0 (or whose reciprocal overflows), a non-finite `x`, or
/// an `out` of the wrong length.
pub fn slip_responses(x: &[f64], delta: &[f64], out: &mut [f64]) -> Result<(), Error> {
    let elements = delta.len();
    let expected = x.len().saturating_mul(elements);
    if out.len() != expected {
        return Err(gms_core::Error::LengthMismatch {
            expected,
            got: out.len(),
        }
        .into());
    }
    // The narrowness rule judges each element against the widest of the whole bank, not of its
    // group, so that the answer does not depend on the order of the elements.
    let widest = delta
        .iter()
        .copied()
        .filter(|value| value.is_finite())
        .fold(0.0_f64, f64::max);
    if let Some((index, &value)) = delta
        .iter()
        .enumerate()
        .find(|(_, &value)| value > 0.0 && value < gms_core::MIN_DELTA_RATIO * widest)
    {
        return Err(Error::Core(gms_core::Error::DeltaTooNarrow {
            index,
            value,
            widest,
        }));
    }
    let mut responses = Vec::new();
    for (first, chunk) in (0..).step_by(MAX_ELEMENTS).zip(delta.chunks(MAX_ELEMENTS)) {
        responses.resize(x.len() * chunk.len(), 0.0);
        let result = with_element_count!(chunk.len(), N => group::<N>(chunk, x, &mut responses), _ => unreachable!("chunks hold 1 to MAX_ELEMENTS elements"));
        result.map_err(|error| match error {
            gms_core::Error::Element { index, value, .. } => Error::BreakDeflection {
                index: first + index,
                value,
            },
            // With unit weights, an overflowing stiffness is an overflowing 1/Delta.
            gms_core::Error::StiffnessOverflow { index, delta, .. } => Error::BreakDeflection {
                index: first + index,
                value: delta,
            },
            gms_core::Error::DeltaTooNarrow {
                index,
                value,
                widest,
            } => Error::Core(gms_core::Error::DeltaTooNarrow {
                index: first + index,
                value,
                widest,
            }),
            other => Error::Core(other),
        })?;
        for (row, values) in out
            .chunks_exact_mut(elements)
            .zip(responses.chunks_exact(chunk.len()))
        {
            row[first..first + chunk.len()].copy_from_slice(values);
        }
    }
    Ok(())
}
