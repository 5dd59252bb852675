//! The hysteresis force of L channels at once, laid out structure-of-arrays: for Maxwell slip,
//! ζ[element][lane], so that one element of every lane is one contiguous row.
//!
//! Every lane does exactly gms-core's arithmetic, in the same order: the element loops add into
//! four partial sums by element index modulo four and add those as `(s0 + s1) + (s2 + s3)`,
//! as `MaxwellSlip` does, so a lane's force, slopes and breakpoints are bit for bit the scalar
//! ones. The lane loops are plain `for l in 0..L` over arrays, written with selects rather
//! than branches, which the compiler turns into SIMD for whatever instruction set the calling
//! function is compiled for (see `dispatch`).

use gms_core::{Hysteresis, Linear, MaxwellSlip, State};

use crate::math::lanes;

/// Fh of every lane at a candidate deflection and the linear pieces on either side of it:
/// gms-core's [`Trial`](gms_core::Trial), one value per lane.
#[derive(Clone, Copy, Debug)]
pub struct TrialLanes<const L: usize> {
    /// Fh(z).
    pub force: [f64; L],
    /// dFh/dz on the piece to the left of z.
    pub slope_left: [f64; L],
    /// dFh/dz on the piece to the right of z.
    pub slope_right: [f64; L],
    /// The nearest breakpoint below z (−∞ if none).
    pub left: [f64; L],
    /// The nearest breakpoint above z (+∞ if none).
    pub right: [f64; L],
}

/// A hysteresis force that the batch kernel can step: the gms-core types, [`MaxwellSlip`] and
/// [`Linear`].
pub trait BatchHysteresis: Hysteresis {
    /// The constants of the lane loops (stiffnesses and windows), computed once per call.
    type Kernel: LaneKernel<Memory = Self::Memory>;
    /// The kernel of this hysteresis.
    fn kernel(&self) -> Self::Kernel;
}

/// The hysteresis force of L lanes at once (see the module documentation).
pub trait LaneKernel: Copy {
    /// The memory of one channel, as gms-core holds it.
    type Memory: Copy;
    /// The memory of L channels, structure-of-arrays.
    type Lanes<const L: usize>: Copy;
    /// The most evaluations of the trial an implicit step makes (gms-core's bound: 2N + 1 for
    /// N elements, 2 for a linear spring).
    const MAX_TRIALS: u32;

    /// The memories of `states` (L of them), structure-of-arrays.
    fn gather<const L: usize>(&self, states: &[State<Self::Memory>]) -> Self::Lanes<L>;
    /// Writes lane l's memory into `states[l]`.
    fn scatter<const L: usize>(&self, lanes: &Self::Lanes<L>, states: &mut [State<Self::Memory>]);
    /// Fh of each lane at `z`, as if its memory were moved there.
    fn force<const L: usize>(&self, lanes: &Self::Lanes<L>, z: &[f64; L]) -> [f64; L];
    /// Fh of each lane and its pieces at `z`, as if its memory were moved there.
    fn trial<const L: usize>(&self, lanes: &Self::Lanes<L>, z: &[f64; L]) -> TrialLanes<L>;
    /// Moves each lane's memory to `z` and returns Fh(z).
    fn commit<const L: usize>(&self, lanes: &mut Self::Lanes<L>, z: &[f64; L]) -> [f64; L];

    /// [`LaneKernel::commit`], then [`LaneKernel::trial`] at the same `z` from the moved
    /// memory: where the next implicit step starts.
    #[inline(always)]
    fn commit_trial<const L: usize>(
        &self,
        lanes: &mut Self::Lanes<L>,
        z: &[f64; L],
    ) -> ([f64; L], TrialLanes<L>) {
        let force = self.commit(lanes, z);
        (force, self.trial(lanes, z))
    }

    /// [`LaneKernel::commit`], then [`LaneKernel::force`] at the same `z` from the moved
    /// memory: what the next explicit step starts from. One pass over the memory where an
    /// implementation fuses the two.
    #[inline(always)]
    fn commit_force<const L: usize>(
        &self,
        lanes: &mut Self::Lanes<L>,
        z: &[f64; L],
    ) -> ([f64; L], [f64; L]) {
        let force = self.commit(lanes, z);
        (force, self.force(lanes, z))
    }
}

/// Independent partial sums of gms-core's element loops.
const SUMS: usize = 4;

/// Lanes of the trial's element loop at a time (one AVX2 register), where the lane count is a
/// multiple of it; otherwise one lane at a time.
const WIDTH: usize = 4;

/// gms-core's `(s0 + s1) + (s2 + s3)`, per lane.
#[inline(always)]
fn total<const L: usize>(sums: &[[f64; L]; SUMS]) -> [f64; L] {
    lanes(|l| (sums[0][l] + sums[1][l]) + (sums[2][l] + sums[3][l]))
}

/// gms-core's element clamp: `value` limited to [−limit, limit], no NaN handling.
#[inline(always)]
fn clamp(value: f64, limit: f64) -> f64 {
    let low = if value < -limit { -limit } else { value };
    if low > limit {
        limit
    } else {
        low
    }
}

/// [`MaxwellSlip`]'s constants: stiffness Wᵢ/Δᵢ (computed as gms-core does) and window Δᵢ.
#[derive(Clone, Copy, Debug)]
pub struct MaxwellKernel<const N: usize> {
    stiffness: [f64; N],
    delta: [f64; N],
}

impl<const N: usize> BatchHysteresis for MaxwellSlip<N> {
    type Kernel = MaxwellKernel<N>;
    fn kernel(&self) -> MaxwellKernel<N> {
        MaxwellKernel {
            stiffness: core::array::from_fn(|i| self.w()[i] / self.delta()[i]),
            delta: *self.delta(),
        }
    }
}

impl<const N: usize> LaneKernel for MaxwellKernel<N> {
    type Memory = [f64; N];
    type Lanes<const L: usize> = [[f64; L]; N];
    #[allow(clippy::cast_possible_truncation)] // N ≤ a few dozen
    const MAX_TRIALS: u32 = 2 * N as u32 + 1;

    #[inline(always)]
    fn gather<const L: usize>(&self, states: &[State<[f64; N]>]) -> [[f64; L]; N] {
        core::array::from_fn(|i| lanes(|l| states[l].memory[i]))
    }

    #[inline(always)]
    fn scatter<const L: usize>(&self, lanes: &[[f64; L]; N], states: &mut [State<[f64; N]>]) {
        for (l, state) in states.iter_mut().enumerate().take(L) {
            for (i, row) in lanes.iter().enumerate() {
                state.memory[i] = row[l];
            }
        }
    }

    #[inline(always)]
    fn force<const L: usize>(&self, zeta: &[[f64; L]; N], z: &[f64; L]) -> [f64; L] {
        let mut force = [[0.0; L]; SUMS];
        for start in (0..N).step_by(SUMS) {
            for (sum, force) in force.iter_mut().enumerate() {
                let i = start + sum;
                if i < N {
                    let (k, limit) = (self.stiffness[i], self.delta[i]);
                    for l in 0..L {
                        force[l] += k * clamp(z[l] - zeta[i][l], limit);
                    }
                }
            }
        }
        total(&force)
    }

    #[inline(always)]
    fn trial<const L: usize>(&self, zeta: &[[f64; L]; N], z: &[f64; L]) -> TrialLanes<L> {
        // One lane at a time where L is not a multiple of WIDTH (one channel: `run_one_lane`).
        let width = if L % WIDTH == 0 { WIDTH } else { 1 };
        let mut trial = TrialLanes {
            force: [0.0; L],
            slope_left: [0.0; L],
            slope_right: [0.0; L],
            left: [0.0; L],
            right: [0.0; L],
        };
        // WIDTH lanes at a time (or one): their 3 × 4 partial sums and two breakpoints fill the
        // vector registers without spilling.
        for base in (0..L).step_by(width) {
            let mut force = [[0.0; WIDTH]; SUMS];
            let mut slope_left = [[0.0; WIDTH]; SUMS];
            let mut slope_right = [[0.0; WIDTH]; SUMS];
            // The nearest breakpoints are a minimum and a maximum, the same whatever the order
            // in which the elements are visited: one running value per lane.
            let mut left = [f64::NEG_INFINITY; WIDTH];
            let mut right = [f64::INFINITY; WIDTH];
            for start in (0..N).step_by(SUMS) {
                for sum in 0..SUMS {
                    let i = start + sum;
                    if i >= N {
                        break;
                    }
                    let (k, limit) = (self.stiffness[i], self.delta[i]);
                    for j in 0..width {
                        let (z, zeta) = (z[base + j], zeta[i][base + j]);
                        let lower = zeta - limit;
                        let upper = zeta + limit;
                        force[sum][j] += k * clamp(z - zeta, limit);
                        slope_right[sum][j] += if lower <= z && z < upper { k } else { 0.0 };
                        slope_left[sum][j] += if lower < z && z <= upper { k } else { 0.0 };
                        let above = if lower > z { lower } else { upper };
                        let below = if upper < z { upper } else { lower };
                        // Selects, not conditional stores.
                        right[j] = if above > z && above < right[j] {
                            above
                        } else {
                            right[j]
                        };
                        left[j] = if below < z && below > left[j] {
                            below
                        } else {
                            left[j]
                        };
                    }
                }
            }
            for j in 0..width {
                let total = |sums: &[[f64; WIDTH]; SUMS]| {
                    (sums[0][j] + sums[1][j]) + (sums[2][j] + sums[3][j])
                };
                trial.force[base + j] = total(&force);
                trial.slope_left[base + j] = total(&slope_left);
                trial.slope_right[base + j] = total(&slope_right);
                trial.left[base + j] = left[j];
                trial.right[base + j] = right[j];
            }
        }
        trial
    }

    #[inline(always)]
    fn commit<const L: usize>(&self, zeta: &mut [[f64; L]; N], z: &[f64; L]) -> [f64; L] {
        let mut force = [[0.0; L]; SUMS];
        // The new positions go to a new array: a select stored back where it was loaded from
        // is compiled into a masked store, which is slow.
        let mut moved = [[0.0; L]; N];
        for start in (0..N).step_by(SUMS) {
            for (sum, force) in force.iter_mut().enumerate() {
                let i = start + sum;
                if i < N {
                    let (k, limit) = (self.stiffness[i], self.delta[i]);
                    for l in 0..L {
                        let deflection = z[l] - zeta[i][l];
                        let kept = clamp(deflection, limit);
                        // Only slipping elements move, as in gms-core.
                        moved[i][l] = if kept == deflection {
                            zeta[i][l]
                        } else {
                            z[l] - kept
                        };
                        force[l] += k * kept;
                    }
                }
            }
        }
        *zeta = moved;
        total(&force)
    }

    // `commit_trial` stays the default, commit then trial: fused, its 18 running sums per four
    // lanes spill, and it measured slower. The fused `commit_force` does, per element and lane,
    // exactly what `commit` and then `force` do, so its results are theirs bit for bit.

    #[inline(always)]
    fn commit_force<const L: usize>(
        &self,
        zeta: &mut [[f64; L]; N],
        z: &[f64; L],
    ) -> ([f64; L], [f64; L]) {
        let mut committed = [[0.0; L]; SUMS];
        let mut force = [[0.0; L]; SUMS];
        let mut moved = [[0.0; L]; N];
        for start in (0..N).step_by(SUMS) {
            for sum in 0..SUMS {
                let i = start + sum;
                if i < N {
                    let (k, limit) = (self.stiffness[i], self.delta[i]);
                    for l in 0..L {
                        let deflection = z[l] - zeta[i][l];
                        let kept = clamp(deflection, limit);
                        let position = if kept == deflection {
                            zeta[i][l]
                        } else {
                            z[l] - kept
                        };
                        moved[i][l] = position;
                        committed[sum][l] += k * kept;
                        force[sum][l] += k * clamp(z[l] - position, limit);
                    }
                }
            }
        }
        *zeta = moved;
        (total(&committed), total(&force))
    }
}

/// [`Linear`]'s constant: the stiffness σ0.
#[derive(Clone, Copy, Debug)]
pub struct LinearKernel {
    sigma0: f64,
}

impl BatchHysteresis for Linear {
    type Kernel = LinearKernel;
    fn kernel(&self) -> LinearKernel {
        LinearKernel {
            sigma0: self.sigma0(),
        }
    }
}

impl LaneKernel for LinearKernel {
    type Memory = ();
    type Lanes<const L: usize> = ();
    const MAX_TRIALS: u32 = 2;

    #[inline(always)]
    fn gather<const L: usize>(&self, _states: &[State<()>]) {}

    #[inline(always)]
    fn scatter<const L: usize>(&self, _lanes: &(), _states: &mut [State<()>]) {}

    #[inline(always)]
    fn force<const L: usize>(&self, _lanes: &(), z: &[f64; L]) -> [f64; L] {
        lanes(|l| self.sigma0 * z[l])
    }

    #[inline(always)]
    fn trial<const L: usize>(&self, _lanes: &(), z: &[f64; L]) -> TrialLanes<L> {
        TrialLanes {
            force: lanes(|l| self.sigma0 * z[l]),
            slope_left: [self.sigma0; L],
            slope_right: [self.sigma0; L],
            left: [f64::NEG_INFINITY; L],
            right: [f64::INFINITY; L],
        }
    }

    #[inline(always)]
    fn commit<const L: usize>(&self, _lanes: &mut (), z: &[f64; L]) -> [f64; L] {
        lanes(|l| self.sigma0 * z[l])
    }
}
