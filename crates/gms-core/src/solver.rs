//! The root of the implicit (backward-Euler) step, to machine precision with bounded work.
//!
//! The step solves R(y) = 0 with
//!
//! R(y) = (y − z) − dt·v + dt·|v|·φ(Fh(y)/g(v)),   φ(u) = sgn(u)·|u|ⁿ,
//!
//! where Fh(y) is the hysteresis trial at y from the memory at step start. Fh is continuous and
//! non-decreasing, so R is strictly increasing with slope ≥ 1 and has exactly one root. Because
//! the slope is at least 1, the explicit Euler point z − R(z) lies on the other side of the root
//! from z, so the two bracket it from the start.
//!
//! Fh is piecewise linear, with breakpoints where an element starts or stops sticking. The solver
//! walks from z towards the root one linear piece at a time: on a piece, R is a smooth function
//! of one variable that is solved in closed form for n = 1 (linear) and n = 2 (quadratic), and by
//! safeguarded Newton otherwise. If the root of the piece lies beyond the piece's end, the walk
//! moves to that breakpoint. A bank of N elements has at most 2N breakpoints, so a step costs at
//! most 2N + 1 evaluations of Fh; in practice one or two.
//!
//! An evaluation is one pass over the elements for Fh at the iterate and, unless the iterate is
//! the root, one for the piece on the side where R says the root lies ([`Hysteresis::piece`]);
//! the slope and breakpoint on the other side are never needed.
//!
//! The exponent n arrives classified ([`Power`], once per parameter set): integer and
//! half-integer n are products and a square root, and only other n call `pow`. The Newton
//! iteration takes P and its slope at a point from the single power |u|ⁿ⁻¹.

use crate::hysteresis::{Hysteresis, Piece};
use crate::math::Power;

/// Upper bound on the scalar Newton/bisection iterations on one linear piece (used only when
/// n ∉ {1, 2}). The bracket at least halves every two iterations, and 55 halvings shrink any
/// piece to four ulps, so the bound is never the reason the iteration stops.
pub const MAX_ITERATIONS: u32 = 128;

/// The committed deflection of an implicit step and how many evaluations of Fh it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// z at the end of the step.
    pub z: f64,
    /// Evaluations of the hysteresis map (each O(N): Fh at the iterate and the piece toward the
    /// root), the one at z included; at most 2N + 1 for N Maxwell-slip elements, 2 for a linear
    /// spring (1 with n = 1: that step is solved in closed form, without the walk).
    pub iterations: u32,
}

/// R(y) of one step, with everything that does not depend on y evaluated once.
pub(crate) struct Residual<'a, H: Hysteresis> {
    pub hysteresis: &'a H,
    pub memory: &'a H::Memory,
    /// z at step start.
    pub z: f64,
    /// dt·v.
    pub dt_v: f64,
    /// dt·|v|.
    pub dt_abs_v: f64,
    /// 1/g(v).
    pub inverse_g: f64,
    /// Transition exponent n.
    pub n: Power,
    /// n − 1, for the slope of φ in the Newton iteration.
    pub n_less_one: Power,
}

/// φ(u) = sgn(u)·|u|ⁿ.
#[inline]
fn phi(u: f64, n: Power) -> f64 {
    libm::copysign(n.abs(u), u)
}

/// Where the root of R lies relative to one linear piece of Fh.
enum OnPiece {
    /// The root, inside the piece.
    Root(f64),
    /// The root lies beyond this end of the piece.
    Beyond(f64),
}

impl<H: Hysteresis> Residual<'_, H> {
    /// R(y), given Fh(y).
    #[inline]
    fn value(&self, y: f64, force: f64) -> f64 {
        (y - self.z) - self.dt_v + self.dt_abs_v * phi(force * self.inverse_g, self.n)
    }

    /// R(y), evaluating Fh.
    pub fn evaluate(&self, y: f64) -> f64 {
        self.value(y, self.hysteresis.force(self.memory, y))
    }

    /// The unique root of R, bracketed by z and the explicit Euler point.
    ///
    /// Each iterate evaluates Fh (`force`), and then, only if it is not the root, the one piece
    /// of Fh on the side where the root lies (`piece`): the sign of R tells the side, so the
    /// other side's slope and breakpoint are never computed.
    pub fn solve(&self) -> Solution {
        self.solve_from(self.hysteresis.force(self.memory, self.z))
    }

    /// [`Residual::solve`], given Fh(z) at step start (`force`, as
    /// [`Hysteresis::force`] computes it): a block call has it from the previous step's commit
    /// ([`Hysteresis::commit_force`]).
    #[allow(clippy::inline_always)] // see the doc comment
    #[inline(always)]
    pub fn solve_from(&self, force: f64) -> Solution {
        let mut y = self.z;
        let mut force = force;
        let mut r = self.value(y, force);
        let mut iterations = 1;
        if r == 0.0 {
            return Solution { z: y, iterations };
        }
        // A NaN in the memory (a state written from outside without `check_state`) makes Fh
        // and R NaN; no comparison then holds, and a bisection would still return a finite
        // point. Returning NaN lets the step refuse it before anything is committed.
        if r.is_nan() {
            return Solution {
                z: f64::NAN,
                iterations,
            };
        }
        let explicit = y - r;
        let (mut lo, mut hi) = if r < 0.0 {
            (y, explicit)
        } else {
            (explicit, y)
        };
        loop {
            let piece = self.hysteresis.piece(self.memory, y, r < 0.0);
            match self.solve_piece(y, r, force, piece, lo, hi) {
                OnPiece::Root(root) => {
                    return Solution {
                        z: root,
                        iterations,
                    }
                }
                // The bracket ends are on the far side of the root; if the piece's root came out
                // beyond one, the root is that end to rounding. Stopping there also guarantees
                // that every move reaches a new breakpoint strictly inside the bracket.
                OnPiece::Beyond(end) if end == lo || end == hi => {
                    return Solution { z: end, iterations }
                }
                OnPiece::Beyond(end) => {
                    y = end;
                    force = self.hysteresis.force(self.memory, y);
                    r = self.value(y, force);
                    iterations += 1;
                    if r == 0.0 {
                        return Solution { z: y, iterations };
                    }
                    if r < 0.0 {
                        lo = y;
                    } else {
                        hi = y;
                    }
                }
            }
        }
    }

    /// On the piece of Fh next to y in the direction of the root (R(y) = r ≠ 0, Fh(y) =
    /// `force`), within the bracket [lo, hi]: the root, or the end of the piece if the root
    /// lies beyond it.
    #[inline]
    fn solve_piece(&self, y: f64, r: f64, force: f64, piece: Piece, lo: f64, hi: f64) -> OnPiece {
        // On the piece, Fh(y + s) = Fh(y) + K·s, so u(s) = α + β·s.
        let rightward = r < 0.0;
        let end = if rightward {
            piece.end.min(hi)
        } else {
            piece.end.max(lo)
        };
        let alpha = force * self.inverse_g;
        let beta = piece.slope * self.inverse_g;
        let c = self.dt_abs_v;
        let s_end = end - y;
        // R(y + s) = s + q + c·φ(α + β·s). Written with q, not r − c·φ(α): when c·φ(α) is huge
        // (a reversal from fast sliding) that difference would cancel catastrophically.
        let q = (y - self.z) - self.dt_v;
        let s = if beta == 0.0 {
            // Every element saturated: φ is constant and R has slope 1.
            -r
        } else {
            match self.n {
                Power::One => -r / (1.0 + c * beta),
                Power::Two => quadratic_root(r, q, alpha, beta, c),
                _ => match (PieceEquation {
                    r,
                    q,
                    alpha,
                    beta,
                    c,
                })
                .newton_root(self.n, self.n_less_one, self.z, s_end)
                {
                    Some(s) => s,
                    None => return OnPiece::Beyond(end),
                },
            }
        };
        // The extended piece is monotone, so a root past the end means the root is beyond it.
        if (rightward && s >= s_end) || (!rightward && s <= s_end) {
            return OnPiece::Beyond(end);
        }
        OnPiece::Root(clamp(y + s, lo, hi))
    }
}

/// The equation of the implicit step on one linear piece of Fh next to the current point y:
/// P(s) = R(y + s) = s + q + c·φ(α + β·s), with P(0) = r ≠ 0.
///
/// The walk of [`Params::solve_implicit`](crate::Params::solve_implicit) builds one per piece;
/// it is public so that a kernel stepping several channels at once (gms-batch) solves each
/// channel's piece with this very arithmetic, and so agrees with the single-channel step bit
/// for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PieceEquation {
    /// P(0) = R(y), nonzero.
    pub r: f64,
    /// (y − z) − dt·v: written apart from r − c·φ(α), which cancels when c·φ(α) is huge.
    pub q: f64,
    /// Fh(y)/g(v).
    pub alpha: f64,
    /// The piece's slope dFh/dy divided by g(v), ≥ 0.
    pub beta: f64,
    /// dt·|v| ≥ 0.
    pub c: f64,
}

impl PieceEquation {
    /// The root for n = 2 (φ(u) = u·|u|) and β > 0, in closed form.
    #[inline]
    pub fn quadratic_root(&self) -> f64 {
        quadratic_root(self.r, self.q, self.alpha, self.beta, self.c)
    }

    /// The root between 0 and `s_end` for any n > 0, given as its class `n` and n − 1 as
    /// `n_less_one` (`Power::new(n - 1.0)`), with z the deflection at step start (it sets the
    /// tolerance); `None` if P keeps the sign of r over the whole interval (the root lies
    /// beyond the piece).
    ///
    /// Newton inside a bracket, with two safeguards: a Newton step that leaves the bracket is
    /// replaced by a bisection, and so is every second step when the bracket has not halved over
    /// the last two (far from the root, Newton on |u|ⁿ gains only a factor (n − 1)/n per step).
    /// The bracket therefore halves at least every two steps, which bounds the iterations.
    pub fn newton_root(&self, n: Power, n_less_one: Power, z: f64, s_end: f64) -> Option<f64> {
        let Self {
            r,
            q,
            alpha,
            beta,
            c,
        } = *self;
        let n_value = n.exponent();
        let p = |s: f64| (s + q) + c * phi(alpha + beta * s, n);
        // P and its slope at s from one power: |u|ⁿ⁻¹ gives both dφ/du = n·|u|ⁿ⁻¹ and
        // |u|ⁿ = |u|ⁿ⁻¹·|u| (exactly φ's rounding for n = 1.5 and 3, within an ulp or two
        // otherwise). dφ/du is infinite at u = 0 when n < 1: no Newton step there.
        let value_and_slope = |s: f64| {
            let u = alpha + beta * s;
            if u == 0.0 {
                let slope = if n_value > 1.0 { 1.0 } else { f64::INFINITY };
                return ((s + q) + c * u, slope);
            }
            let magnitude = libm::fabs(u);
            let power = n_less_one.of(magnitude);
            if !power.is_finite() {
                // n < 1 at a subnormal |u|: |u|ⁿ⁻¹ overflows while |u|ⁿ is tiny. φ from its
                // own power, and no Newton step (the slope is infinite).
                return ((s + q) + c * phi(u, n), f64::INFINITY);
            }
            let phi = libm::copysign(power * magnitude, u);
            ((s + q) + c * phi, 1.0 + c * beta * n_value * power)
        };
        let p_end = p(s_end);
        if (r < 0.0 && p_end < 0.0) || (r > 0.0 && p_end > 0.0) {
            return None;
        }
        // Bracket [a, b] in s with P(a) ≤ 0 ≤ P(b) (an end is 0 only at s_end).
        let (mut a, mut b) = if r < 0.0 { (0.0, s_end) } else { (s_end, 0.0) };
        let tolerance = 4.0 * f64::EPSILON * (libm::fabs(z) + libm::fabs(s_end));
        // P(0) = r is known; its slope is not.
        let (mut s, mut value, mut slope) = (0.0, r, value_and_slope(0.0).1);
        let mut checkpoint = b - a;
        for iteration in 0..MAX_ITERATIONS {
            if b - a <= tolerance {
                break;
            }
            let newton = s - value / slope;
            if slope.is_finite() && libm::fabs(newton - s) <= tolerance {
                // A tiny step is not proof of a root where the slope is huge: accept it only
                // if P changes sign within the tolerance around it. P is increasing and
                // P(a) ≤ 0 ≤ P(b), so a point at or beyond a bracket end needs no evaluation:
                // usually the last iterate is one end, within the tolerance of the new one.
                let (below, above) = (newton - tolerance, newton + tolerance);
                let p_below = if below <= a {
                    f64::NEG_INFINITY
                } else {
                    p(below)
                };
                let p_above = if above >= b { f64::INFINITY } else { p(above) };
                if p_below <= 0.0 && p_above >= 0.0 {
                    return Some(clamp(newton, a, b));
                }
                if p_below > 0.0 {
                    b = b.min(below);
                } else {
                    a = a.max(above);
                }
            }
            let stalled = iteration % 2 == 1 && b - a > 0.5 * checkpoint;
            if iteration % 2 == 1 {
                checkpoint = b - a;
            }
            s = if slope.is_finite() && newton > a && newton < b && !stalled {
                newton
            } else {
                0.5 * (a + b)
            };
            (value, slope) = value_and_slope(s);
            if value == 0.0 {
                return Some(s);
            }
            if value < 0.0 {
                a = s;
            } else {
                b = s;
            }
        }
        Some(0.5 * (a + b))
    }
}

/// The root of R for Fh(y) = k·y and n = 1: R(y) = (y − z) − dt·v + dt·|v|·k·y/g is linear in
/// y, so y = (z + dt·v)/(1 + dt·|v|·k/g), written as (z + dt·v)·(g/(g + dt·|v|·k)) with the
/// factor from [`linear_factor`]: one division, and none that depends on z, so that a run of
/// steps is a chain of one addition and one multiplication. v = 0 gives z exactly.
#[inline]
pub(crate) fn linear_root(z: f64, dt_v: f64, factor: f64) -> f64 {
    (z + dt_v) * factor
}

/// g/(g + dt·|v|·k), the factor of [`linear_root`]: in (0, 1], and it cancels nothing (g > 0,
/// dt·|v|·k ≥ 0). It depends on the input alone.
#[inline]
pub(crate) fn linear_factor(dt_abs_v: f64, stiffness: f64, g: f64) -> f64 {
    g / (g + dt_abs_v * stiffness)
}

/// Root of P(s) = s + q + c·φ(α + β·s) for n = 2 (φ(u) = u·|u|), β > 0, c ≥ 0, where
/// r = P(0) = q + c·φ(α).
///
/// P is a quadratic on each side of the zero of u; the side is the one where P changes sign.
/// The root is written in the form that does not cancel when c·β is small.
#[inline]
fn quadratic_root(r: f64, q: f64, alpha: f64, beta: f64, c: f64) -> f64 {
    let s_zero = -alpha / beta;
    // P at the zero of u; the root lies right of it (u > 0) iff P(s_zero) ≤ 0.
    let p_zero = s_zero + q;
    let sigma = if p_zero <= 0.0 { 1.0 } else { -1.0 };
    // For a stiff piece (β > 1) the forms are divided through by β, so that β² (which
    // overflows for stiffnesses above about 1e154 N/m) is never formed; for a soft one they are
    // not, so that 1/β is never formed.
    let stiff = beta > 1.0;
    if sigma * alpha >= 0.0 {
        // Same side as s = 0: σ·c·β²·s² + (1 + 2c·|α|·β)·s + r = 0, or in t = β·s,
        // σ·c·t² + (1/β + 2c·|α|)·t + r = 0.
        if stiff {
            let a1 = 1.0 / beta + 2.0 * c * libm::fabs(alpha);
            let discriminant = (a1 * a1 - 4.0 * sigma * c * r).max(0.0);
            return -2.0 * r / (a1 + libm::sqrt(discriminant)) / beta;
        }
        let a2 = sigma * c * beta * beta;
        let a1 = 1.0 + 2.0 * c * libm::fabs(alpha) * beta;
        let discriminant = (a1 * a1 - 4.0 * a2 * r).max(0.0);
        -2.0 * r / (a1 + libm::sqrt(discriminant))
    } else {
        // Across the zero of u: in w = α + β·s, σ·c·β·w² + w + (β·P(s_zero)) = 0, or divided
        // by β, σ·c·w² + w/β + P(s_zero) = 0.
        let w = if stiff {
            let inverse = 1.0 / beta;
            -2.0 * p_zero
                / (inverse + libm::sqrt((inverse * inverse - 4.0 * sigma * c * p_zero).max(0.0)))
        } else {
            let a2 = sigma * c * beta;
            let a0 = beta * p_zero;
            -2.0 * a0 / (1.0 + libm::sqrt((1.0 - 4.0 * a2 * a0).max(0.0)))
        };
        (w - alpha) / beta
    }
}

/// `value` limited to [lo, hi]. Unlike `f64::clamp` it cannot panic: a NaN passes through (the
/// step then reports a non-finite state instead of aborting a control loop).
#[inline]
fn clamp(value: f64, lo: f64, hi: f64) -> f64 {
    if value < lo {
        lo
    } else if value > hi {
        hi
    } else {
        value
    }
}
