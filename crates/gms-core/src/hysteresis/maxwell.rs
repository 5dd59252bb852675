//! N elasto-slide elements in parallel (the paper's eq. 5): fixed memory, nonlocal memory.

// The element loops' helpers are `#[inline(always)]`: with `#[inline]` LLVM keeps some out of
// line, and their pairs of elements are no longer stepped with packed instructions (callgrind:
// 601 instead of 570 instructions per Leuven N = 10 step of `simulate_position`).
#![allow(clippy::inline_always)]

use super::{Hysteresis, Piece, Trial};
use crate::error::{Error, Field};

/// The narrowest break deflection allowed, relative to the widest: 2⁻²⁶ = √ε ≈ 1.49e-8.
///
/// z lives on the scale of the widest element and is resolved to ε = 2⁻⁵² of it, so element i
/// sees its deflection rounded to ε·max Δ, a fraction ε·max Δ/Δᵢ of its window. The rule keeps
/// that fraction at most √ε: every element's force is resolved to about 8 digits. Narrower
/// elements turn into relays whose switching the rounding of z decides, and the implicit step's
/// root can then no longer be located (two correct implementations disagreed by 25 %).
pub const MIN_DELTA_RATIO: f64 = 1.0 / 67_108_864.0;

/// The position of the largest value and the value (the first on ties).
fn largest(values: &[f64]) -> (usize, f64) {
    values.iter().enumerate().fold(
        (0, f64::NEG_INFINITY),
        |(i, a), (j, &b)| {
            if b > a {
                (j, b)
            } else {
                (i, a)
            }
        },
    )
}

/// The partial sums (or running extremes) of an element loop: four, element i in
/// `[(i / 2) % 2][i % 2]`, that is partial sum i mod 4. One running sum would chain every
/// addition to the latency of the previous one; and the two elements of a pair sit side by side,
/// in the two halves of one SSE2 register, so that a pair is stepped with packed instructions.
type Lanes = [[f64; 2]; 2];

/// The four partial sums, added in the order (0 + 1) + (2 + 3).
#[inline]
fn sum(lanes: Lanes) -> f64 {
    (lanes[0][0] + lanes[0][1]) + (lanes[1][0] + lanes[1][1])
}

/// The lane `(sum, half)` of `lanes`; always `Some` for the indices [`for_each_element`] hands
/// out (sum < 2, half < 2), and the test folds away once the loop is unrolled.
#[inline(always)]
fn lane(lanes: &mut Lanes, (sum, half): (usize, usize)) -> Option<&mut f64> {
    lanes.get_mut(sum).and_then(|pair| pair.get_mut(half))
}

/// `value` limited to [−limit, limit], for limit > 0, as two selects that compile to one
/// `maxsd` and one `minsd`. Unlike `f64::clamp` it has no panic path; a NaN passes through.
#[inline]
fn clamp(value: f64, limit: f64) -> f64 {
    let low = if value < -limit { -limit } else { value };
    if low > limit {
        limit
    } else {
        low
    }
}

/// `a` if `condition`, else `b`, as data rather than control flow: a compare mask and a blend,
/// never a branch to mispredict.
#[inline]
fn select(condition: bool, a: f64, b: f64) -> f64 {
    if condition {
        a
    } else {
        b
    }
}

/// Runs `body(lane, k, Δ, ζ)` over the elements, two at a time (the last alone if N is odd),
/// each with its stiffness, break deflection, position and lane in [`Lanes`]. The pairs come
/// from `chunks_exact`, so no bound is checked per element.
#[inline(always)]
fn for_each_element<const N: usize>(
    stiffness: &[f64; N],
    delta: &[f64; N],
    zeta: &[f64; N],
    mut body: impl FnMut((usize, usize), f64, f64, f64),
) {
    let pairs = stiffness.chunks_exact(2).zip(delta.chunks_exact(2));
    for (pair, ((k, limit), positions)) in pairs.zip(zeta.chunks_exact(2)).enumerate() {
        for half in 0..2 {
            if let (Some(&k), Some(&limit), Some(&position)) =
                (k.get(half), limit.get(half), positions.get(half))
            {
                body((pair % 2, half), k, limit, position);
            }
        }
    }
    let last = ((N / 2) % 2, 0);
    let remainders = stiffness.chunks_exact(2).remainder().iter();
    let remainders = remainders.zip(delta.chunks_exact(2).remainder());
    for ((&k, &limit), &position) in remainders.zip(zeta.chunks_exact(2).remainder()) {
        body(last, k, limit, position);
    }
}

/// [`for_each_element`] that also moves each element: `body` returns the element's new
/// position. A pair's two positions are stored together, after both are computed.
#[inline(always)]
fn move_each_element<const N: usize>(
    stiffness: &[f64; N],
    delta: &[f64; N],
    zeta: &mut [f64; N],
    mut body: impl FnMut((usize, usize), f64, f64, f64) -> f64,
) {
    let pairs = stiffness.chunks_exact(2).zip(delta.chunks_exact(2));
    for (pair, ((k, limit), positions)) in pairs.zip(zeta.chunks_exact_mut(2)).enumerate() {
        let mut moved = [0.0; 2];
        for (half, moved) in moved.iter_mut().enumerate() {
            if let (Some(&k), Some(&limit), Some(&position)) =
                (k.get(half), limit.get(half), positions.get(half))
            {
                *moved = body((pair % 2, half), k, limit, position);
            }
        }
        for (position, moved) in positions.iter_mut().zip(moved) {
            *position = moved;
        }
    }
    let last = ((N / 2) % 2, 0);
    let remainders = stiffness.chunks_exact(2).remainder().iter();
    let remainders = remainders.zip(delta.chunks_exact(2).remainder());
    for ((&k, &limit), position) in remainders.zip(zeta.chunks_exact_mut(2).into_remainder()) {
        *position = body(last, k, limit, *position);
    }
}

/// The smallest of the lanes' running minima (+∞ if all are).
#[inline]
fn smallest_of(lanes: Lanes) -> f64 {
    lanes
        .iter()
        .flatten()
        .fold(f64::INFINITY, |a, &b| select(b < a, b, a))
}

/// The largest of the lanes' running maxima (−∞ if all are).
#[inline]
fn largest_of(lanes: Lanes) -> f64 {
    lanes
        .iter()
        .flatten()
        .fold(f64::NEG_INFINITY, |a, &b| select(b > a, b, a))
}

/// `nearest` lowered to the nearest breakpoint of one element above z, if that is nearer:
/// ζ − Δ if it is above z, else ζ + Δ if that is; a minimum, with +∞ for "none".
#[inline]
fn nearer_above(nearest: f64, lower: f64, upper: f64, z: f64) -> f64 {
    let above = select(lower > z, lower, upper);
    let above = select(above > z, above, f64::INFINITY);
    select(above < nearest, above, nearest)
}

/// `nearest` raised to the nearest breakpoint of one element below z, if that is nearer.
#[inline]
fn nearer_below(nearest: f64, lower: f64, upper: f64, z: f64) -> f64 {
    let below = select(upper < z, upper, lower);
    let below = select(below < z, below, f64::NEG_INFINITY);
    select(below > nearest, below, nearest)
}

/// Maxwell-slip bank of `N` elements with saturation forces `W` and break deflections `Delta`.
///
/// Element i has stiffness kᵢ = Wᵢ/Δᵢ and position ζᵢ; its deflection eᵢ = z − ζᵢ stays in
/// [−Δᵢ, Δᵢ], and its force is kᵢ·eᵢ. The memory is the array of ζᵢ, whatever the history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaxwellSlip<const N: usize> {
    w: [f64; N],
    delta: [f64; N],
    stiffness: [f64; N],
    /// ΣW, the largest |Fh|, summed once here rather than on every step's finiteness check.
    total: f64,
}

impl<const N: usize> MaxwellSlip<N> {
    /// Every `w[i]` and `delta[i]` must be finite and > 0, and N ≥ 1; `sum(W)`, each stiffness
    /// `W[i]/Delta[i]` and their sum must be finite; and every `delta[i]` must be at least
    /// [`MIN_DELTA_RATIO`] times the largest (docs/parameters.md#rules).
    ///
    /// # Errors
    /// The first rule broken, naming the element: [`Error::Element`] (`W` first, then `Delta`),
    /// [`Error::ForceSumOverflow`], [`Error::StiffnessOverflow`],
    /// [`Error::StiffnessSumOverflow`], [`Error::DeltaTooNarrow`].
    pub fn new(w: [f64; N], delta: [f64; N]) -> Result<Self, Error> {
        if N == 0 {
            return Err(Error::NoElements);
        }
        for (index, &value) in w.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::Element {
                    field: Field::W,
                    index,
                    value,
                });
            }
        }
        let total: f64 = w.iter().sum();
        if !total.is_finite() {
            let (index, largest) = largest(&w);
            return Err(Error::ForceSumOverflow { index, largest });
        }
        for (index, &value) in delta.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::Element {
                    field: Field::Delta,
                    index,
                    value,
                });
            }
        }
        let mut stiffness = [0.0; N];
        for index in 0..N {
            stiffness[index] = w[index] / delta[index];
            if !stiffness[index].is_finite() {
                return Err(Error::StiffnessOverflow {
                    index,
                    w: w[index],
                    delta: delta[index],
                });
            }
        }
        if !stiffness.iter().sum::<f64>().is_finite() {
            return Err(Error::StiffnessSumOverflow);
        }
        let (_, widest) = largest(&delta);
        for (index, &value) in delta.iter().enumerate() {
            if value < MIN_DELTA_RATIO * widest {
                return Err(Error::DeltaTooNarrow {
                    index,
                    value,
                    widest,
                });
            }
        }
        Ok(Self {
            w,
            delta,
            stiffness,
            total,
        })
    }

    /// Saturation forces Wᵢ.
    pub fn w(&self) -> &[f64; N] {
        &self.w
    }

    /// Break deflections Δᵢ.
    pub fn delta(&self) -> &[f64; N] {
        &self.delta
    }

    /// [`Hysteresis::piece`] towards +z (`RIGHTWARD`) or −z: one pass for one side, half the
    /// comparisons of `trial`, and no force (the solver has it already). An element counts
    /// towards a side's slope where it sticks on that side of z; the side's end is the nearest
    /// breakpoint beyond z.
    #[inline(always)]
    fn side<const RIGHTWARD: bool>(&self, zeta: &[f64; N], z: f64) -> Piece {
        let mut slope = [[0.0; 2]; 2];
        let none = if RIGHTWARD {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        };
        let mut end = [[none; 2]; 2];
        for_each_element(
            &self.stiffness,
            &self.delta,
            zeta,
            |at, k, limit, position| {
                if let (Some(slope), Some(end)) = (lane(&mut slope, at), lane(&mut end, at)) {
                    let (lower, upper) = (position - limit, position + limit);
                    if RIGHTWARD {
                        *slope += select(lower <= z && z < upper, k, 0.0);
                        *end = nearer_above(*end, lower, upper, z);
                    } else {
                        *slope += select(lower < z && z <= upper, k, 0.0);
                        *end = nearer_below(*end, lower, upper, z);
                    }
                }
            },
        );
        Piece {
            slope: sum(slope),
            end: if RIGHTWARD {
                smallest_of(end)
            } else {
                largest_of(end)
            },
        }
    }
}

impl<const N: usize> Hysteresis for MaxwellSlip<N> {
    type Memory = [f64; N];

    fn relaxed(&self) -> [f64; N] {
        [0.0; N]
    }

    // The element loops are written with selects rather than branches (whether an element
    // sticks changes from sample to sample, and mispredicted branches cost more than the
    // arithmetic), and accumulate into the four partial sums of [`Lanes`], held in registers,
    // a pair of elements at a time. Every expression is the one the branchy form had (the same
    // comparisons on ζ ± Δ, the same order of sums), so the results are the same to the bit.

    #[inline]
    fn force(&self, zeta: &[f64; N], z: f64) -> f64 {
        let mut force = [[0.0; 2]; 2];
        for_each_element(
            &self.stiffness,
            &self.delta,
            zeta,
            |at, k, limit, position| {
                if let Some(force) = lane(&mut force, at) {
                    *force += k * clamp(z - position, limit);
                }
            },
        );
        sum(force)
    }

    #[inline]
    fn trial(&self, zeta: &[f64; N], z: f64) -> Trial {
        let mut force = [[0.0; 2]; 2];
        let mut slope_left = [[0.0; 2]; 2];
        let mut slope_right = [[0.0; 2]; 2];
        let mut left = [[f64::NEG_INFINITY; 2]; 2];
        let mut right = [[f64::INFINITY; 2]; 2];
        for_each_element(
            &self.stiffness,
            &self.delta,
            zeta,
            |at, k, limit, position| {
                let (Some(force), Some(slope_left), Some(slope_right), Some(left), Some(right)) = (
                    lane(&mut force, at),
                    lane(&mut slope_left, at),
                    lane(&mut slope_right, at),
                    lane(&mut left, at),
                    lane(&mut right, at),
                ) else {
                    return;
                };
                // The element sticks while z ∈ [ζ − Δ, ζ + Δ]; those two points are breakpoints.
                let lower = position - limit;
                let upper = position + limit;
                *force += k * clamp(z - position, limit);
                *slope_right += select(lower <= z && z < upper, k, 0.0);
                *slope_left += select(lower < z && z <= upper, k, 0.0);
                *right = nearer_above(*right, lower, upper, z);
                *left = nearer_below(*left, lower, upper, z);
            },
        );
        Trial {
            force: sum(force),
            slope_left: sum(slope_left),
            slope_right: sum(slope_right),
            left: largest_of(left),
            right: smallest_of(right),
        }
    }

    #[inline]
    fn piece(&self, zeta: &[f64; N], z: f64, rightward: bool) -> Piece {
        // The direction is tested once, outside the element loop.
        if rightward {
            self.side::<true>(zeta, z)
        } else {
            self.side::<false>(zeta, z)
        }
    }

    #[inline]
    fn commit(&self, zeta: &mut [f64; N], z: f64) -> f64 {
        // `commit_force` without its force at z, which the compiler drops unused.
        self.commit_force(zeta, z).0
    }

    /// `commit`'s pass, which computes each element's new position anyway, also sums the
    /// element forces at z from it: per element and partial sum the very expressions of
    /// `commit` and `force`, so both results are theirs bit for bit.
    #[inline]
    fn commit_force(&self, zeta: &mut [f64; N], z: f64) -> (f64, f64) {
        let mut committed = [[0.0; 2]; 2];
        let mut force = [[0.0; 2]; 2];
        move_each_element(
            &self.stiffness,
            &self.delta,
            zeta,
            |at, k, limit, position| {
                let deflection = z - position;
                let kept = clamp(deflection, limit);
                let moved = select(kept != deflection, z - kept, position);
                if let (Some(committed), Some(force)) =
                    (lane(&mut committed, at), lane(&mut force, at))
                {
                    *committed += k * kept;
                    *force += k * clamp(z - moved, limit);
                }
                moved
            },
        );
        (sum(committed), sum(force))
    }

    fn max_force(&self) -> f64 {
        self.total
    }

    /// ΣW, whatever z: each element's force kᵢ·eᵢ has |eᵢ| ≤ Δᵢ, so |Fh| ≤ Σ kᵢ·Δᵢ = ΣW up to
    /// rounding of relative order N·ε, which the step's margin (half the f64 range) covers.
    #[inline]
    fn force_bound(&self, _z: f64) -> f64 {
        self.total
    }

    fn check_memory(&self, zeta: &[f64; N], z: f64) -> Result<(), Error> {
        for (index, (&position, &limit)) in zeta.iter().zip(&self.delta).enumerate() {
            let deflection = z - position;
            // What the getter reads back after a slip is z − (z − Δ), a few ulps off Δ.
            let tolerance = 4.0 * f64::EPSILON * libm::fmax(libm::fabs(z), limit);
            if deflection.is_nan() || libm::fabs(deflection) > limit + tolerance {
                return Err(Error::StateOutsideWindow {
                    index,
                    deflection,
                    limit,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bank() -> MaxwellSlip<3> {
        MaxwellSlip::new([1.0, 2.0, 3.0], [1e-6, 2e-6, 4e-6]).unwrap()
    }

    #[test]
    fn saturates_and_slips() {
        let bank = bank();
        let mut zeta = bank.relaxed();
        let trial = bank.trial(&zeta, 1.5e-6);
        assert!((trial.force - (1.0 + 1.5 + 1.125)).abs() < 1e-12);
        assert!((trial.slope_right - (1e6 + 0.75e6)).abs() < 1e-3);
        assert_eq!(trial.slope_left, trial.slope_right);
        assert_eq!((trial.left, trial.right), (1e-6, 2e-6));
        assert_eq!(bank.commit(&mut zeta, 1e-5), 6.0);
        assert_eq!(zeta, [1e-5 - 1e-6, 1e-5 - 2e-6, 1e-5 - 4e-6]);
        assert_eq!(bank.trial(&zeta, 1e-5).force, 6.0);
        // Every element has just slipped: each sticks to the left and saturates to the right.
        let edge = bank.trial(&zeta, 1e-5);
        assert!((edge.slope_left - 2.75e6).abs() < 1e-3);
        assert_eq!(edge.slope_right, 0.0);
        assert_eq!((edge.left, edge.right), (8e-6, f64::INFINITY));
        assert_eq!(bank.max_force(), 6.0);
    }

    #[test]
    fn rules_name_the_element() {
        assert_eq!(
            MaxwellSlip::new([1.0, -1.0], [1.0, 1.0]),
            Err(Error::Element {
                field: Field::W,
                index: 1,
                value: -1.0
            })
        );
        assert_eq!(
            MaxwellSlip::new([1.0, 1.0], [1.0, f64::INFINITY]),
            Err(Error::Element {
                field: Field::Delta,
                index: 1,
                value: f64::INFINITY
            })
        );
        assert_eq!(MaxwellSlip::<0>::new([], []), Err(Error::NoElements));
    }
}
