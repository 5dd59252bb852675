//! The implicit mass step as one scalar equation in the new deflection y = z⁺.
//!
//! Backward Euler on the mass and on the friction state, with the friction velocity held at the
//! new velocity w (so that x⁺ = x + dt·w, exactly the friction step's contract), is the system
//!
//! - momentum: m·(w − v)/dt = u + k·(a⁺ − x − dt·w) − [Fh(y) + σ1·(y − z)/dt + σ2(w)·w],
//! - friction: y − z = dt·f(y, w),   f(y, w) = w − |w|·φ(Fh(y)/g(w)),
//!
//! with Fh the hysteresis trial from the memory at step start and σ2(w) = `sigma2_neg` for
//! w < 0, σ2 otherwise. The momentum equation is linear in w on each side of 0, and its left
//! side (m/dt + k·dt)·w + σ2(w)·w is increasing and 0 at w = 0, so w has the sign of the
//! forward solution and is a continuous, decreasing function of Fh(y) and y:
//!
//!   w(y) = v + (net − Fh(y) − σ1·(y − z)/dt) / S,   S = m/dt + k·dt + σ2,
//!   net = u + k·(a⁺ − x − dt·v) − σ2·v,
//!
//! with σ2 when that w is ≥ 0, and otherwise the same with `sigma2_neg` (which then gives a
//! w < 0 too, up to rounding at w ≈ 0 where the viscous force is ≈ 0 either way),
//!
//! and the step reduces to the root of R(y) = (y − z) − dt·f(y, w(y)), which costs one
//! evaluation of Fh and one of g per iterate, with no nested solve.
//!
//! R is continuous, and R(y) → ±∞ as y → ±∞, so a root exists. The search starts from z and
//! the point z − R(z) (the step explicit in y, implicit in w), which bracket the root whenever R
//! has slope ≥ 1 there, as it has near stick: dR/dy = 1 + dt·(K + σ1/dt)/S + O(|w|), K the
//! stiffness of the sticking elements. If they do not bracket it (the Stribeck curve makes R
//! non-monotone in sliding), the bracket is doubled until R changes sign. Inside the bracket a
//! regula falsi with the Illinois correction, falling back to bisection whenever the bracket has
//! not halved in two iterations, converges to a few ulps in bounded work.

use crate::hysteresis::Hysteresis;
use crate::math::abs_pow;
use crate::model::Params;

/// Doublings of the initial bracket before giving up (R grows at least linearly for large
/// |y − z|, so a finite problem never needs more than a few).
const MAX_DOUBLINGS: u32 = 64;

/// Iterations inside the bracket. It at least halves every two iterations and stops at a
/// relative width of 4 ulps (or 4 ulps of z for a root at zero): about 110 iterations when the
/// root is not far below the bracket's scale; the bound caps the rest.
const MAX_ITERATIONS: u32 = 256;

/// The momentum equation of one direction of the new velocity, with that direction's σ2.
#[derive(Clone, Copy, Debug)]
pub(super) struct Momentum {
    /// u + k·(a⁺ − x − dt·v) − σ2·v: the force on the mass, except friction's Fh and σ1 terms,
    /// at w = v.
    pub net: f64,
    /// 1/S, S = m/dt + k·dt + σ2.
    pub inverse_s: f64,
}

/// Everything of one implicit mass step that does not depend on y.
pub(super) struct Coupled<'a, H: Hysteresis> {
    pub params: &'a Params<H>,
    pub memory: &'a H::Memory,
    /// z at step start.
    pub z: f64,
    /// v at step start.
    pub v: f64,
    pub dt: f64,
    /// The momentum equation with σ2, for w ≥ 0.
    pub forward: Momentum,
    /// The momentum equation with `sigma2_neg`, for w < 0, when it differs from σ2.
    pub backward: Option<Momentum>,
}

/// The solution of the step: new deflection and new velocity.
#[derive(Clone, Copy, Debug)]
pub(super) struct Root {
    pub y: f64,
    pub w: f64,
}

impl<H: Hysteresis> Coupled<'_, H> {
    /// R(y) and w(y).
    #[inline]
    fn evaluate(&self, y: f64) -> (f64, f64) {
        let params = self.params;
        let force = params.hysteresis().force(self.memory, y);
        let micro_viscous = params.sigma1() * (y - self.z) / self.dt;
        let velocity = |momentum: Momentum| {
            self.v + (momentum.net - force - micro_viscous) * momentum.inverse_s
        };
        let w = match (velocity(self.forward), self.backward) {
            (w, Some(backward)) if w < 0.0 => velocity(backward),
            (w, _) => w,
        };
        let u = force / params.stribeck().g(w);
        let phi = libm::copysign(abs_pow(u, params.n()), u);
        let residual = (y - self.z) - self.dt * w + self.dt * libm::fabs(w) * phi;
        (residual, w)
    }

    /// The root of R, or `None` if R became non-finite (inputs beyond f64 range).
    pub fn solve(&self) -> Option<Root> {
        let z = self.z;
        let (r0, w0) = self.evaluate(z);
        if !(r0.is_finite() && w0.is_finite()) {
            return None;
        }
        if r0 == 0.0 {
            return Some(Root { y: z, w: w0 });
        }
        // Near end (same sign as r0) and far end of the bracket.
        let (mut near, mut r_near) = (z, r0);
        let mut step = -r0;
        let mut doublings = 0;
        let (far, r_far, w_far) = loop {
            let y = z + step;
            let (r, w) = self.evaluate(y);
            if !(r.is_finite() && w.is_finite()) {
                return None;
            }
            if r == 0.0 {
                return Some(Root { y, w });
            }
            if (r < 0.0) != (r0 < 0.0) {
                break (y, r, w);
            }
            (near, r_near) = (y, r);
            doublings += 1;
            if doublings > MAX_DOUBLINGS {
                return None;
            }
            step *= 2.0;
        };
        let (lo, r_lo, hi, r_hi) = if r0 < 0.0 {
            (near, r_near, far, r_far)
        } else {
            (far, r_far, near, r_near)
        };
        Some(self.refine(lo, r_lo, hi, r_hi, w_far))
    }

    /// Illinois regula falsi on [lo, hi] with R(lo) < 0 < R(hi), safeguarded by bisection.
    fn refine(&self, mut lo: f64, mut r_lo: f64, mut hi: f64, mut r_hi: f64, w_hi: f64) -> Root {
        // Relative to the bracket as it shrinks (the first bracket can be far wider than the
        // root when the step is stiff), with a floor at the scale of z for roots near zero.
        let floor = 4.0 * f64::EPSILON * libm::fabs(self.z) + f64::MIN_POSITIVE;
        let mut best = Root { y: hi, w: w_hi };
        let mut best_r = libm::fabs(r_hi);
        // Which end was kept last time: the Illinois correction halves its residual when the
        // same end is kept twice, so that regula falsi cannot stall on one side.
        let mut kept_lo = 0u32;
        let mut kept_hi = 0u32;
        let mut checkpoint = hi - lo;
        for iteration in 0..MAX_ITERATIONS {
            let scale = libm::fmax(libm::fabs(lo), libm::fabs(hi));
            if hi - lo <= 4.0 * f64::EPSILON * scale || hi - lo <= floor {
                break;
            }
            let secant = hi - r_hi * (hi - lo) / (r_hi - r_lo);
            let stalled = iteration % 2 == 1 && hi - lo > 0.5 * checkpoint;
            if iteration % 2 == 1 {
                checkpoint = hi - lo;
            }
            let y = if !stalled && secant > lo && secant < hi {
                secant
            } else {
                0.5 * (lo + hi)
            };
            let (r, w) = self.evaluate(y);
            if libm::fabs(r) < best_r {
                best = Root { y, w };
                best_r = libm::fabs(r);
            }
            if r == 0.0 {
                return best;
            }
            if r < 0.0 {
                (lo, r_lo) = (y, r);
                kept_hi += 1;
                kept_lo = 0;
                if kept_hi >= 2 {
                    r_hi *= 0.5;
                }
            } else {
                (hi, r_hi) = (y, r);
                kept_lo += 1;
                kept_hi = 0;
                if kept_lo >= 2 {
                    r_lo *= 0.5;
                }
            }
        }
        best
    }
}
