//! gms-core's powers (its `math.rs`), and the transition exponent n as a type, so that the
//! common exponents are decided once per call rather than in every lane of every step.

/// |x|^p for p > 0, exactly as gms-core computes it (p = 1 and p = 2 kept off `pow`).
#[inline(always)]
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

/// The transition exponent n of φ(u) = sgn(u)·|u|ⁿ.
pub(crate) trait Exponent: Copy {
    /// φ(u), as gms-core's `copysign(abs_pow(u, n), u)`.
    fn phi(self, u: f64) -> f64;
    /// n itself.
    fn n(self) -> f64;
}

/// n = 1: φ(u) = u (copysign(|u|, u) is u, NaN included).
#[derive(Clone, Copy)]
pub(crate) struct One;

/// n = 2: φ(u) = u·|u|.
#[derive(Clone, Copy)]
pub(crate) struct Two;

/// Any other n > 0, through `pow`.
#[derive(Clone, Copy)]
pub(crate) struct Other(pub f64);

impl Exponent for One {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        libm::fabs(u).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        1.0
    }
}

impl Exponent for Two {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        let a = libm::fabs(u);
        (a * a).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        2.0
    }
}

impl Exponent for Other {
    #[inline(always)]
    fn phi(self, u: f64) -> f64 {
        abs_pow(u, self.0).copysign(u)
    }
    #[inline(always)]
    fn n(self) -> f64 {
        self.0
    }
}
