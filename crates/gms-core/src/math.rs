//! Powers of magnitudes, with the exponents that occur most often kept off `pow`.

/// |x|^p for p > 0; exact and cheap for p = 1 and p = 2, which are the usual choices of n and δ.
#[inline]
pub(crate) fn abs_pow(x: f64, p: f64) -> f64 {
    let a = libm::fabs(x);
    if p == 1.0 {
        a
    } else if p == 2.0 {
        a * a
    } else if a == 0.0 {
        0.0
    } else {
        libm::pow(a, p)
    }
}
