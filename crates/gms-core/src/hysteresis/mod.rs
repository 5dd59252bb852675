//! The hysteresis force Fh(z) of the model, as a static map with memory.
//!
//! Two implementations: [`MaxwellSlip`], the modified Leuven model's N elasto-slide elements
//! (eq. 5), and [`Linear`], Fh = σ0·z, which turns the same stepper into LuGre.

mod linear;
mod maxwell;

pub use linear::Linear;
pub use maxwell::{MaxwellSlip, MIN_DELTA_RATIO};

/// Fh at a candidate deflection and the linear pieces of Fh on either side of it, evaluated
/// without committing (the memory stays as it was at step start).
///
/// The trial map is piecewise linear; at a breakpoint the slopes to the left and to the right
/// differ, which is why both are given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trial {
    /// Fh(z).
    pub force: f64,
    /// dFh/dz on the piece to the left of z.
    pub slope_left: f64,
    /// dFh/dz on the piece to the right of z.
    pub slope_right: f64,
    /// Start of the piece to the left: the nearest breakpoint below z (−∞ if none).
    pub left: f64,
    /// End of the piece to the right: the nearest breakpoint above z (+∞ if none).
    pub right: f64,
}

/// The linear piece of Fh on one side of a deflection: what the implicit solver needs once it
/// knows in which direction the root lies (see [`Hysteresis::piece`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// dFh/dz on the piece.
    pub slope: f64,
    /// The piece's far end: the nearest breakpoint on that side (±∞ if none).
    pub end: f64,
}

/// A hysteresis force with a fixed-size memory per channel.
///
/// `trial(..).force` must be continuous and non-decreasing in `z` (every element is a spring or saturated), which is what
/// makes the implicit step's equation have a unique root.
pub trait Hysteresis {
    /// The per-channel memory (one ζ per element, or nothing).
    type Memory: Copy + core::fmt::Debug + PartialEq;

    /// The memory of a relaxed channel at z = 0.
    fn relaxed(&self) -> Self::Memory;

    /// Fh at `z`, as if the memory were moved to `z` (nothing is written).
    fn force(&self, memory: &Self::Memory, z: f64) -> f64;

    /// Fh and its pieces at `z`, as if the memory were moved to `z` (nothing is written).
    fn trial(&self, memory: &Self::Memory, z: f64) -> Trial;

    /// The piece of the trial map on one side of `z` (to the right if `rightward`): the
    /// `slope_right` and `right` of [`Hysteresis::trial`], or `slope_left` and `left`, equal to
    /// them bit for bit. The default calls `trial`; an implementation may compute one side
    /// only, which is what the implicit solver needs after it has evaluated `force`.
    #[inline]
    fn piece(&self, memory: &Self::Memory, z: f64, rightward: bool) -> Piece {
        let trial = self.trial(memory, z);
        if rightward {
            Piece {
                slope: trial.slope_right,
                end: trial.right,
            }
        } else {
            Piece {
                slope: trial.slope_left,
                end: trial.left,
            }
        }
    }

    /// Moves the memory to `z` (the elements that would be over-stretched slip) and returns
    /// Fh(z), which equals the trial force at `z`.
    fn commit(&self, memory: &mut Self::Memory, z: f64) -> f64;

    /// [`Hysteresis::commit`], then Fh at the same `z` from the moved memory: the pair that
    /// `commit` and then [`Hysteresis::force`] return, bit for bit. The second is the force the
    /// next step starts from, so that a block call hands it over instead of evaluating it again;
    /// an implementation may compute both in one pass over its elements.
    #[inline]
    fn commit_force(&self, memory: &mut Self::Memory, z: f64) -> (f64, f64) {
        let committed = self.commit(memory, z);
        (committed, self.force(memory, z))
    }

    /// sup |Fh| over all z (infinite for a linear spring).
    fn max_force(&self) -> f64;

    /// `Some(k)` if Fh(z) = k·z for every z and every memory (a spring that never slips), as
    /// `force` and `commit` compute it. With n = 1 the implicit step is then linear in z⁺ and
    /// solved in closed form, without the piece walk (docs/model.md#discrete-step). The
    /// default, `None`, is right for any other hysteresis.
    #[inline]
    fn linear_stiffness(&self) -> Option<f64> {
        None
    }

    /// A bound on |Fh(z)| for every memory a channel can hold at deflection `z`, as `commit`
    /// computes it (rounding included, for bounds below half the f64 range). A memory holding
    /// a NaN has no bound, but never reaches the commit: its Fh is NaN, so is z⁺ (the implicit
    /// solver returns NaN for a NaN residual), and the step refuses a non-finite z⁺ first.
    ///
    /// The step uses it to know, before committing, that the committed force will be finite,
    /// so that it can commit in place and still leave the state untouched on a divergence.
    /// The default, +∞, means "no bound known": the step then commits into a copy of the
    /// memory and checks afterwards.
    fn force_bound(&self, z: f64) -> f64 {
        let _ = z;
        f64::INFINITY
    }

    /// Checks a memory written from outside (not produced by stepping) against deflection `z`:
    /// every element within its window, to a rounding tolerance. The default accepts any
    /// memory, which suits a hysteresis without one.
    ///
    /// # Errors
    /// [`Error::StateOutsideWindow`](crate::Error::StateOutsideWindow) naming the first
    /// element out of its window.
    fn check_memory(&self, memory: &Self::Memory, z: f64) -> Result<(), crate::Error> {
        let _ = (memory, z);
        Ok(())
    }
}
