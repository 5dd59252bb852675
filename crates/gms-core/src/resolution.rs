//! How fine a period or half stroke an f64 position resolves: the rule of the position-dependent
//! terms (`level`), which their errors also state. A module of its own, below both, so that the
//! error's message and the check read one rule.

/// 2^20: the ulps of the extent a period or a half stroke must span (see `level`'s module
/// documentation).
const RESOLUTION_ULPS: f64 = 1_048_576.0;

/// The finest period or half stroke resolved at positions up to `extent` (≥ 1): 2^20 ulps of
/// it, and infinite when the extent is (|middle| + `half_stroke` overflowed).
pub(crate) fn finest(extent: f64) -> f64 {
    if extent.is_finite() {
        // The distance to the next f64 up: one ulp (infinite above f64::MAX).
        RESOLUTION_ULPS * (f64::from_bits(extent.to_bits() + 1) - extent)
    } else {
        f64::INFINITY
    }
}
