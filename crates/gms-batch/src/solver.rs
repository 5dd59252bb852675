//! gms-core's implicit step (its `solver.rs`), for L lanes at once.
//!
//! Each lane walks the linear pieces of its own Fh from z towards the root, exactly as the
//! scalar solver does; a lane that has found its root keeps it while the others walk on, and the
//! walk ends when every lane is done. One trial evaluation serves every lane still walking, so a
//! lane never takes more than the scalar bound of 2N + 1 evaluations (the others' wasted
//! evaluations are discarded).
//!
//! The piece's root is computed for every lane with selects: for n = 1 and n = 2 in closed
//! form, written so that each lane's arithmetic is that of the scalar solver operation for
//! operation (the test `quadratic_matches_the_scalar_form` checks it bit for bit); for other n
//! each lane calls gms-core's own safeguarded Newton iteration ([`PieceEquation::newton_root`]).

use crate::lanes::{LaneKernel, TrialLanes};
use gms_core::PieceEquation;

use crate::math::{lanes, Exponent};

/// The lane-wise inputs of one implicit step: R(y) = (y − z) − dt·v + dt·|v|·φ(Fh(y)/g(v)).
pub(crate) struct Step<const L: usize> {
    /// z at step start.
    pub z: [f64; L],
    /// dt·v.
    pub dt_v: [f64; L],
    /// dt·|v|.
    pub dt_abs_v: [f64; L],
    /// 1/g(v).
    pub inverse_g: [f64; L],
}

/// The root of every lane's R, starting from `first`, the trial at z; `None` if a lane exceeded the scalar bound on trial evaluations
/// (only possible for non-finite values, which the caller hands to gms-core).
#[inline(always)]
pub(crate) fn solve<K: LaneKernel, E: Exponent, const L: usize>(
    kernel: &K,
    memory: &K::Lanes<L>,
    step: &Step<L>,
    first: TrialLanes<L>,
    exponent: E,
) -> Option<[f64; L]> {
    let residual = |y: &[f64; L], trial: &TrialLanes<L>| -> [f64; L] {
        lanes(|l| {
            (y[l] - step.z[l]) - step.dt_v[l]
                + step.dt_abs_v[l] * exponent.phi(trial.force[l] * step.inverse_g[l])
        })
    };
    let mut y = step.z;
    // The trial at y = z, handed over from the previous step's commit.
    let mut trial = first;
    let mut r = residual(&y, &trial);
    let mut root = y;
    let mut walking = [false; L];
    for (walking, r) in walking.iter_mut().zip(&r) {
        *walking = *r != 0.0;
    }
    let explicit: [f64; L] = lanes(|l| y[l] - r[l]);
    let mut lo: [f64; L] = lanes(|l| if r[l] < 0.0 { y[l] } else { explicit[l] });
    let mut hi: [f64; L] = lanes(|l| if r[l] < 0.0 { explicit[l] } else { y[l] });
    let mut evaluations = 1;
    while walking.iter().any(|&walking| walking) {
        // gms-core's `solve_piece` for every lane: on the piece next to y towards the root,
        // Fh(y + s) = Fh(y) + K·s, so u(s) = α + β·s.
        let end: [f64; L] = lanes(|l| {
            if r[l] < 0.0 {
                trial.right[l].min(hi[l])
            } else {
                trial.left[l].max(lo[l])
            }
        });
        let alpha: [f64; L] = lanes(|l| trial.force[l] * step.inverse_g[l]);
        let beta: [f64; L] = lanes(|l| {
            let slope = if r[l] < 0.0 {
                trial.slope_right[l]
            } else {
                trial.slope_left[l]
            };
            slope * step.inverse_g[l]
        });
        let c = &step.dt_abs_v;
        let s_end: [f64; L] = lanes(|l| end[l] - y[l]);
        let q: [f64; L] = lanes(|l| (y[l] - step.z[l]) - step.dt_v[l]);
        let n = exponent.n();
        // Lanes whose root lies beyond the piece by the Newton iteration's own test.
        let mut past = [false; L];
        let s: [f64; L] = if n == 1.0 {
            lanes(|l| -r[l] / (1.0 + c[l] * beta[l]))
        } else if n == 2.0 {
            lanes(|l| quadratic_root(r[l], q[l], alpha[l], beta[l], c[l]))
        } else {
            lanes(|l| {
                if beta[l] == 0.0 || !walking[l] {
                    return -r[l];
                }
                let equation = PieceEquation {
                    r: r[l],
                    q: q[l],
                    alpha: alpha[l],
                    beta: beta[l],
                    c: c[l],
                };
                let root = equation.newton_root(
                    exponent.power(),
                    exponent.power_less_one(),
                    step.z[l],
                    s_end[l],
                );
                past[l] = root.is_none();
                root.unwrap_or(0.0)
            })
        };
        for l in 0..L {
            // Every element saturated: φ is constant and R has slope 1.
            let s = if beta[l] == 0.0 { -r[l] } else { s[l] };
            let rightward = r[l] < 0.0;
            // The extended piece is monotone, so a root past the end means the root is beyond.
            let beyond = past[l] || (rightward && s >= s_end[l]) || (!rightward && s <= s_end[l]);
            let value = if beyond {
                end[l]
            } else {
                clamp(y[l] + s, lo[l], hi[l])
            };
            // Root(value); Beyond(end) at a bracket end: the root is that end (to rounding);
            // Beyond(end) inside the bracket: move there.
            let done = !beyond || value == lo[l] || value == hi[l];
            root[l] = if walking[l] && done { value } else { root[l] };
            y[l] = if walking[l] && !done { value } else { y[l] };
            walking[l] = walking[l] && !done;
        }
        if !walking.iter().any(|&walking| walking) {
            break;
        }
        evaluations += 1;
        if evaluations > K::MAX_TRIALS {
            return None;
        }
        trial = kernel.trial(memory, &y);
        r = residual(&y, &trial);
        for l in 0..L {
            let zero = r[l] == 0.0;
            root[l] = if walking[l] && zero { y[l] } else { root[l] };
            walking[l] = walking[l] && !zero;
            lo[l] = if r[l] < 0.0 { y[l] } else { lo[l] };
            hi[l] = if r[l] < 0.0 { hi[l] } else { y[l] };
        }
    }
    Some(root)
}

/// gms-core's `quadratic_root` (root of s + q + c·φ(α + β·s) for n = 2), written without
/// branches: the four forms of the scalar code (same side of the zero of u or across it, stiff
/// or soft piece) are one form σ-free in shape,
///
/// t = −2R / (A + √max(A² − B·R, 0)),  s = t / D (same side) or (t − α)/β (across),
///
/// with R, A, B, D chosen per lane. Each choice reproduces the scalar operations exactly: the
/// factors 4σ and 2 are powers of two (their products are exact), A² = 1 when A = 1, and a
/// division by D = 1 is exact.
#[inline(always)]
pub(crate) fn quadratic_root(r: f64, q: f64, alpha: f64, beta: f64, c: f64) -> f64 {
    let s_zero = -alpha / beta;
    let p_zero = s_zero + q;
    let sigma = if p_zero <= 0.0 { 1.0 } else { -1.0 };
    let stiff = beta > 1.0;
    let same = sigma * alpha >= 0.0;
    let inverse = 1.0 / beta;
    let two_c_alpha = 2.0 * c * libm::fabs(alpha);
    let four_sigma_c = 4.0 * sigma * c;
    let sigma_c_beta = sigma * c * beta;
    // Same side: stiff A = 1/β + 2c|α|, B = 4σc, D = β; soft A = 1 + 2c|α|β, B = 4σcβ², D = 1.
    // Across: stiff R = P(s_zero), A = 1/β, B = 4σc; soft R = β·P(s_zero), A = 1, B = 4σcβ.
    // Selects, not branches, so that the lanes vectorize.
    let numerator = if same {
        r
    } else if stiff {
        p_zero
    } else {
        beta * p_zero
    };
    let soft_same = 1.0 + two_c_alpha * beta;
    let a = match (same, stiff) {
        (true, true) => inverse + two_c_alpha,
        (true, false) => soft_same,
        (false, true) => inverse,
        (false, false) => 1.0,
    };
    let soft_b = if same {
        sigma_c_beta * beta
    } else {
        sigma_c_beta
    };
    let b = if stiff { four_sigma_c } else { 4.0 * soft_b };
    let discriminant = (a * a - b * numerator).max(0.0);
    let t = -2.0 * numerator / (a + discriminant.sqrt());
    let top = if same { t } else { t - alpha };
    let bottom = if same && !stiff { 1.0 } else { beta };
    top / bottom
}

/// gms-core's solver clamp: a NaN passes through.
#[inline(always)]
fn clamp(value: f64, lo: f64, hi: f64) -> f64 {
    if value < lo {
        lo
    } else if value > hi {
        hi
    } else {
        value
    }
}

#[cfg(test)]
mod tests {
    use super::quadratic_root;
    use proptest::prelude::*;

    /// gms-core's own closed form.
    fn scalar(r: f64, q: f64, alpha: f64, beta: f64, c: f64) -> f64 {
        gms_core::PieceEquation {
            r,
            q,
            alpha,
            beta,
            c,
        }
        .quadratic_root()
    }

    fn magnitude() -> impl Strategy<Value = f64> {
        (-30.0..30.0f64, prop::bool::ANY).prop_map(|(e, negative)| {
            let value = 10f64.powf(e);
            if negative {
                -value
            } else {
                value
            }
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        #[test]
        fn quadratic_matches_the_scalar_form(
            r in magnitude(),
            q in magnitude(),
            alpha in magnitude(),
            beta in (-12.0..12.0f64).prop_map(|e| 10f64.powf(e)),
            c in (-15.0..3.0f64).prop_map(|e| 10f64.powf(e)),
        ) {
            let (ours, theirs) = (quadratic_root(r, q, alpha, beta, c), scalar(r, q, alpha, beta, c));
            prop_assert!(ours.to_bits() == theirs.to_bits() || (ours.is_nan() && theirs.is_nan()),
                "{ours:e} vs {theirs:e}");
        }
    }
}
