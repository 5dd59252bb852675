//! The hysteresis side of the sensitivities: the trial force Fh(y) from the memory at step start,
//! linearised in y and in the parameters, and the memory's own sensitivities carried through the
//! commit (docs/sensitivities.md#hysteresis).
//!
//! Everything here is computed from the public state before and after gms-core's step: which
//! elements stick at the root, and which slip when the memory is committed, follow from ζ, Δ and
//! the new z by gms-core's own rule (an element slips when clipping its deflection changes it).

use gms_core::{Linear, MaxwellSlip};

use crate::vector::{weighted_sum, Vector};

/// Fh at a trial deflection y and its linearisation, Fh(y + dy) ≈ force + slope·dy + D·dθ.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Linearised {
    /// Fh(y).
    pub force: f64,
    /// dFh/dy: the summed stiffness of the elements that stick at y.
    pub slope: f64,
}

/// A hysteresis model prepared for differentiation, with M columns of its own.
pub(crate) trait Bank<const M: usize>: Copy {
    /// gms-core's memory of a channel.
    type Memory;
    /// dζᵢ/dθ of every element.
    type Carried: Copy;
    /// Per element, its stiffness where it sticks at the trial deflection and 0 where it slips.
    type Sticking: Copy;

    /// The sensitivities of a relaxed memory (zero: the relaxed state depends on no parameter).
    fn relaxed(&self) -> (Self::Carried, Self::Sticking);

    /// Which elements stick at `y`, with `memory` from step start.
    fn sticking(&self, memory: &Self::Memory, y: f64, sticking: &mut Self::Sticking);

    /// Fh(y) with `memory` from step start, its slope in y, and in `d` its derivative by every
    /// column at fixed y: −Σ over sticking elements of kᵢ·dζᵢ/dθ, plus dFh/dθ of the own
    /// columns; `s` is dz/dθ at step start. Also writes `sticking`, as [`Bank::sticking`] does.
    /// `carried` is mutable for what it keeps of the last call's sums, not for the sensitivities.
    fn linearise(
        &self,
        memory: &Self::Memory,
        carried: &mut Self::Carried,
        s: &Vector<M>,
        y: f64,
        sticking: &mut Self::Sticking,
        d: &mut Vector<M>,
    ) -> Linearised;

    /// The commit, with `s` = dz/dθ at step start: every element that slips (0 in `sticking`)
    /// now sits at z⁺ ∓ Δᵢ, whose sensitivity is that of z⁺ (Δ is not a fitted parameter);
    /// every element that sticks keeps its own.
    fn carry(&self, sticking: &Self::Sticking, carried: &mut Self::Carried, s: &Vector<M>);
}

/// `value` limited to [−limit, limit] by the two selects of gms-core's element loops (no panic
/// path, and the same value: this decides, as gms-core decides, whether an element slips).
#[inline]
fn clamp(value: f64, limit: f64) -> f64 {
    let low = if value < -limit { -limit } else { value };
    if low > limit {
        limit
    } else {
        low
    }
}

/// N Maxwell-slip elements, with kᵢ = Wᵢ/Δᵢ computed once, as gms-core computes it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Elements<const N: usize> {
    stiffness: [f64; N],
    delta: [f64; N],
    inverse_delta: [f64; N],
}

impl<const N: usize> Elements<N> {
    pub fn new(elements: &MaxwellSlip<N>) -> Self {
        let (w, delta) = (elements.w(), elements.delta());
        Self {
            stiffness: core::array::from_fn(|i| w[i] / delta[i]),
            delta: *delta,
            inverse_delta: delta.map(|value| 1.0 / value),
        }
    }
}

/// dζᵢ/dθ of N elements. An element that slipped on the last moving step sits at z ∓ Δᵢ and
/// follows z: its sensitivity is dz/dθ itself, kept nowhere else. Only when it sticks again is
/// that value written into its own slot, which then holds while it sticks. In gross sliding,
/// where every element slips on every step, nothing is summed or copied.
///
/// The sum over the elements that stick with a sensitivity of their own, Σ kᵢ·dζᵢ/dθ, changes
/// only when one of them starts or stops sticking or a slot is written: between those events
/// (presliding, where a bank holds for hundreds of steps between slips) it is kept, not summed
/// again. It is the same sum of the same numbers, so the result is the same bit for bit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ElementSensitivities<const N: usize> {
    /// dζᵢ/dθ of the elements that do not follow z.
    own: [Vector<N>; N],
    /// Whether element i follows z (its `own` slot is then stale).
    follows: [bool; N],
    /// The weights of the last sum of `own`: kᵢ where element i sticks with its own slot, else 0.
    summed: [f64; N],
    /// That sum, valid while `fresh` holds.
    sum: Vector<N>,
    /// Whether `sum` is Σ summed[i]·own[i] of the slots as they are now.
    fresh: bool,
}

impl<const N: usize> Bank<N> for Elements<N> {
    type Memory = [f64; N];
    type Carried = ElementSensitivities<N>;
    type Sticking = [f64; N];

    fn relaxed(&self) -> (Self::Carried, Self::Sticking) {
        // A relaxed channel: dz/dθ = dζᵢ/dθ = 0, so every element follows z.
        let carried = ElementSensitivities {
            own: [Vector::ZERO; N],
            follows: [true; N],
            summed: [0.0; N],
            sum: Vector::ZERO,
            fresh: false,
        };
        (carried, [0.0; N])
    }

    #[inline]
    fn sticking(&self, zeta: &[f64; N], y: f64, sticking: &mut [f64; N]) {
        for i in 0..N {
            let deviation = y - zeta[i];
            let kept = clamp(deviation, self.delta[i]);
            sticking[i] = if kept == deviation {
                self.stiffness[i]
            } else {
                0.0
            };
        }
    }

    #[inline]
    fn linearise(
        &self,
        zeta: &[f64; N],
        carried: &mut ElementSensitivities<N>,
        s: &Vector<N>,
        y: f64,
        sticking: &mut [f64; N],
        d: &mut Vector<N>,
    ) -> Linearised {
        let (mut force, mut slope, mut following, mut held) = (0.0, 0.0, 0.0, 0.0);
        let mut by_weight = [0.0; N];
        let mut holding = [0.0; N];
        for i in 0..N {
            let deviation = y - zeta[i];
            let kept = clamp(deviation, self.delta[i]);
            let k = self.stiffness[i];
            let stuck = if kept == deviation { k } else { 0.0 };
            sticking[i] = stuck;
            force += k * kept;
            slope += stuck;
            // A sticking element's force kᵢ·(y − ζᵢ) moves with its ζᵢ: with z's sensitivity
            // if it follows z, with its own otherwise. A slipping one's is ±Wᵢ.
            let follows = carried.follows[i];
            following += if follows { stuck } else { 0.0 };
            holding[i] = if follows { 0.0 } else { stuck };
            held += holding[i];
            // Fhᵢ = Wᵢ·clip(y − ζᵢ, ±Δᵢ)/Δᵢ: by Wᵢ, the clipped deflection over Δᵢ, sticking or not.
            by_weight[i] = kept * self.inverse_delta[i];
        }
        // Gross sliding holds no element (every kᵢ > 0, so the sum is 0 only then): nothing
        // to sum.
        let mut moved = if held == 0.0 {
            Vector::ZERO
        } else if carried.fresh && carried.summed == holding {
            carried.sum
        } else {
            let sum = weighted_sum(&holding, &carried.own);
            (carried.summed, carried.sum, carried.fresh) = (holding, sum, true);
            sum
        };
        moved.add_scaled(following, s);
        for (value, moved) in d.shared.iter_mut().zip(&moved.shared) {
            *value = -moved;
        }
        for ((value, moved), direct) in d.own.iter_mut().zip(&moved.own).zip(&by_weight) {
            *value = direct - moved;
        }
        Linearised { force, slope }
    }

    #[inline]
    fn carry(&self, sticking: &[f64; N], carried: &mut ElementSensitivities<N>, s: &Vector<N>) {
        // Which elements stop following z, found without a branch per element (whether one
        // sticks changes from step to step); an element stops following only at a reversal.
        let mut stops = [false; N];
        let mut any = false;
        for ((&stuck, follows), stop) in sticking.iter().zip(&mut carried.follows).zip(&mut stops) {
            let sticks = stuck != 0.0;
            *stop = sticks && *follows;
            any |= *stop;
            *follows = !sticks;
        }
        if any {
            // It keeps the sensitivity z had at step start.
            for (own, _) in carried.own.iter_mut().zip(stops).filter(|(_, stop)| *stop) {
                *own = *s;
            }
            carried.fresh = false;
        }
    }
}

/// The linear spring Fh = σ0·z of LuGre: no memory, one own column, σ0.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spring {
    sigma0: f64,
}

impl Spring {
    pub fn new(spring: Linear) -> Self {
        Self {
            sigma0: spring.sigma0(),
        }
    }
}

impl Bank<1> for Spring {
    type Memory = ();
    type Carried = ();
    type Sticking = ();

    fn relaxed(&self) -> ((), ()) {
        ((), ())
    }

    #[inline]
    fn sticking(&self, _memory: &(), _y: f64, _sticking: &mut ()) {}

    #[inline]
    fn linearise(
        &self,
        _memory: &(),
        _carried: &mut (),
        _s: &Vector<1>,
        y: f64,
        _sticking: &mut (),
        d: &mut Vector<1>,
    ) -> Linearised {
        *d = Vector::ZERO;
        d.own[0] = y;
        Linearised {
            force: self.sigma0 * y,
            slope: self.sigma0,
        }
    }

    #[inline]
    fn carry(&self, _sticking: &(), _carried: &mut (), _s: &Vector<1>) {}
}
