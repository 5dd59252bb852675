//! Friction compensation for a control loop: the friction force to add to the command, one
//! sample at a time.
//!
//! A [`Compensator`] is one axis of a control loop running at a fixed sample time: its own
//! parameter set (so that it can be swapped while the loop runs), one channel of model state, the
//! sample time (validated once, at construction) and the last output. Two ways to drive it
//! ([`Mode`]):
//!
//! - **feedforward**: each sample gets the *desired* velocity of the trajectory; the output is
//!   the friction the model predicts along the planned motion. No feedback through the model,
//!   so it cannot destabilise the loop, but it ignores where the axis really is;
//! - **observer**: each sample gets the *measured* position; the model runs on the motion that
//!   really happened (v = Δx/dt, the first sample of a fresh compensator taking v = 0), so its
//!   internal deflection z tracks the real junctions. Any position signal works, so a desired
//!   position gives position-based feedforward.
//!
//! **Position-dependent terms.** [`Compensator::with_level`] gives the compensator a
//! [`Level`] and [`Compensator::with_position_force`] a [`PositionForce`]
//! (docs/model.md#position-dependent-level): the output becomes
//! factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x), with F the plain model's force and v the step's
//! velocity. In observer mode x is the input. In feedforward mode the compensator needs the
//! axis's position: [`Compensator::step_trajectory`] takes it with the desired velocity each
//! sample (a trajectory generator gives both); [`Compensator::step`] integrates the desired
//! velocity, x ← x + v·dt, from the start position ([`Compensator::with_start_position`] or
//! [`Compensator::set_position`]). Without a start position the terms would be evaluated from
//! x = 0, out of phase with the machine, so a feedforward compensator refuses a level or a
//! position force until it has one ([`Error::Missing`] naming `x`). The terms act on the output
//! only; the model state evolves as without them, and [`Level::none`] and
//! [`PositionForce::none`] (the defaults) give the plain output bit for bit.
//!
//! **Bounded work.** A step is one implicit model step: at most 2N + 1 evaluations of the
//! hysteresis trial, each O(N) (see the solver), plus for n ∉ {1, 2} at most
//! [`MAX_ITERATIONS`](crate::MAX_ITERATIONS) safeguarded Newton iterations on each of those
//! pieces; with a level or a position force, one sincos per ripple of each and at most
//! [`MAX_HARMONICS`](crate::MAX_HARMONICS) rotations per ripple. [`Compensator::set_params`]
//! costs at most 2N + 1 trial evaluations and two commits.
//! Nothing allocates and nothing panics.
//!
//! **Parameter swap without a jump.** The hysteresis force Fh carries the model's memory; σ1·ż
//! and σ2(v)·v are memoryless. New parameters, applied to the old state (z, ζ) as they are, would
//! generally give a different Fh at the same z: a jump of up to the whole friction level when,
//! say, the Δᵢ change. So [`Compensator::set_params`] re-initialises the state for the new
//! parameters: the elements are first made consistent with the new Δᵢ at the current z (those
//! stretched beyond them slip), then z is moved along the new bank's trial curve until the new
//! Fh equals the old one (clamped to ±`ΣWᵢ` of the new bank, the only forces it can hold). The
//! next sample then starts from the force the loop has just applied, and the transition to the
//! new model's behaviour follows the model's own dynamics: the change over that sample is O(dt)
//! like any other's (tests/compensator.rs checks that it shrinks with dt, while the naive swap
//! jumps by a fixed amount). What changes at once is the part without memory: σ2(v)·v by Δσ2·v,
//! and σ1·ż because ż = v·(1 − |Fh/g(v)|ⁿ·sgn(Fh)/sgn(v)) now uses the new g(v), by at most
//! σ1·|v|·|1 − |Fh/`g_new`(v)|ⁿ|. Both are zero at rest and are the new model's answer to the same
//! motion, not an artefact of the swap.

use crate::checks::{finite, positive};
use crate::error::{Error, Field};
use crate::hysteresis::Hysteresis;
use crate::level::{Level, PositionForce};
use crate::model::{position_velocity, Params, Scheme, State};

/// What the compensator's input is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Mode {
    /// The desired velocity \[m/s\]: friction feedforward along the planned motion.
    #[default]
    Feedforward,
    /// The measured position \[m\]: the model run as an observer of the real motion.
    Observer,
}

impl Mode {
    /// The input's name: `v` (velocity) or `x` (position), as in the errors.
    pub const fn field(self) -> Field {
        match self {
            Mode::Feedforward => Field::v,
            Mode::Observer => Field::x,
        }
    }
}

/// The most evaluations of the hysteresis trial one implicit step can take with `elements`
/// Maxwell-slip elements: 2N + 1 (each element contributes two breakpoints to walk over).
pub const fn evaluation_bound(elements: usize) -> usize {
    2 * elements + 1
}

/// One axis of friction compensation at a fixed sample time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compensator<H: Hysteresis> {
    params: Params<H>,
    state: State<H::Memory>,
    dt: f64,
    mode: Mode,
    output: f64,
    level: Level,
    position_force: PositionForce,
    /// The feedforward position: the start position, then the desired positions stepped or the
    /// desired velocities integrated since; `None` until a start position is given.
    position: Option<f64>,
}

impl<H: Hysteresis> Compensator<H> {
    /// A compensator at rest (relaxed state, output 0) with sample time `dt` (finite, > 0), no
    /// level, no position force and, in feedforward mode, no start position yet.
    ///
    /// # Errors
    /// [`Error::NotPositive`] naming `dt`.
    pub fn new(params: Params<H>, dt: f64, mode: Mode) -> Result<Self, Error> {
        let dt = positive(dt, Field::dt)?;
        Ok(Self {
            state: params.relaxed_state(),
            params,
            dt,
            mode,
            output: 0.0,
            level: Level::none(),
            position_force: PositionForce::none(),
            position: None,
        })
    }

    /// This compensator with the axis's start position `x` (finite): where feedforward mode
    /// starts placing the level and the position force. Give it before them.
    ///
    /// # Errors
    /// [`Error::NotFiniteValue`] naming `x`.
    pub fn with_start_position(mut self, x: f64) -> Result<Self, Error> {
        self.set_position(x)?;
        Ok(self)
    }

    /// This compensator with a position-dependent level (see the module documentation); the
    /// level was validated when it was built.
    ///
    /// # Errors
    /// [`Error::Missing`] naming `x`: a feedforward compensator without a start position
    /// ([`Compensator::with_start_position`]) refuses a level that is not flat.
    pub fn with_level(mut self, level: Level) -> Result<Self, Error> {
        self.set_level(level)?;
        Ok(self)
    }

    /// This compensator with a force that depends on the position alone, added to its output
    /// in both directions (see the module documentation); validated when it was built.
    ///
    /// # Errors
    /// [`Error::Missing`] naming `x`, as [`Compensator::with_level`].
    pub fn with_position_force(mut self, position_force: PositionForce) -> Result<Self, Error> {
        self.set_position_force(position_force)?;
        Ok(self)
    }

    /// Replaces the level between two samples (it was validated when it was built). The level
    /// has no memory, so the model state carries over; the output follows the new factor from
    /// the next sample on.
    ///
    /// # Errors
    /// [`Error::Missing`] naming `x`, as [`Compensator::with_level`]; nothing changes.
    pub fn set_level(&mut self, level: Level) -> Result<(), Error> {
        self.placed(level.is_flat())?;
        self.level = level;
        Ok(())
    }

    /// Replaces the position force between two samples, as [`Compensator::set_level`].
    ///
    /// # Errors
    /// [`Error::Missing`] naming `x`, as [`Compensator::with_level`]; nothing changes.
    pub fn set_position_force(&mut self, position_force: PositionForce) -> Result<(), Error> {
        self.placed(position_force.is_none())?;
        self.position_force = position_force;
        Ok(())
    }

    /// Refuses a position term (unless `none`) in feedforward mode without a start position.
    fn placed(&self, none: bool) -> Result<(), Error> {
        if none || self.mode == Mode::Observer || self.position.is_some() {
            Ok(())
        } else {
            Err(Error::Missing { field: Field::x })
        }
    }

    /// Sets the position (finite) of the axis: feedforward mode places the level and the
    /// position force from it, at `x + v·dt` on the next [`Compensator::step`]. Observer mode
    /// takes the position from its input and does not read this one. A refused value changes
    /// nothing.
    ///
    /// # Errors
    /// [`Error::NotFiniteValue`] naming `x`.
    pub fn set_position(&mut self, x: f64) -> Result<(), Error> {
        if x.is_finite() {
            self.position = Some(x);
            Ok(())
        } else {
            Err(Error::NotFiniteValue {
                field: Field::x,
                value: x,
            })
        }
    }

    /// The friction force to add to the command for this sample.
    ///
    /// `input` is the desired velocity (feedforward) or the measured position (observer). A
    /// non-finite input, or a position jump so large that Δx/dt overflows, is reported; the
    /// state and [`Compensator::output`] are left as they were, so a loop can keep applying the
    /// last output.
    ///
    /// # Errors
    /// [`Error::NotFinite`] naming the input (or `x`, when the integrated feedforward position
    /// overflows), [`Error::VelocityNotFinite`], or [`Error::Diverged`] for a force that is not
    /// finite.
    #[inline]
    pub fn step(&mut self, input: f64) -> Result<f64, Error> {
        self.restoring(|compensator| compensator.step_unchecked(input))
    }

    /// The friction force for one sample of a planned trajectory: the desired velocity `v` is
    /// the model's input, and the desired position `x` places the level and the position
    /// force, so that a loop that knows its position does not integrate the velocity. In
    /// feedforward mode `x` becomes the compensator's position; in observer mode (a measured
    /// velocity beside the measured position) it becomes the previous position of the next
    /// [`Compensator::step`]. A refused sample changes nothing, as in [`Compensator::step`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] naming `v` or `x`, or [`Error::Diverged`] for a force that is not
    /// finite.
    #[inline]
    pub fn step_trajectory(&mut self, v: f64, x: f64) -> Result<f64, Error> {
        finite(x, Field::x)?;
        self.restoring(|compensator| {
            let force = compensator.params.step(
                &mut compensator.state,
                v,
                compensator.dt,
                Scheme::Implicit,
            )?;
            let force = compensator.finish(force, x, v)?;
            match compensator.mode {
                Mode::Feedforward => compensator.position = Some(x),
                Mode::Observer => compensator.state.last_position = Some(x),
            }
            Ok(force)
        })
    }

    /// Runs `step` and puts the state and output back if it fails.
    #[inline]
    fn restoring(
        &mut self,
        step: impl FnOnce(&mut Self) -> Result<f64, Error>,
    ) -> Result<f64, Error> {
        // Only the position terms can refuse a force the model accepted; without them the step
        // runs in place, exactly as the plain model's, and nothing needs to be put back.
        let saved = self.has_terms().then_some((self.state, self.output));
        let result = step(self);
        if let (Err(_), Some((state, output))) = (&result, saved) {
            self.state = state;
            self.output = output;
        }
        result
    }

    /// Whether a level or a position force acts on the output.
    #[inline]
    fn has_terms(&self) -> bool {
        !(self.level.is_flat() && self.position_force.is_none())
    }

    /// [`Compensator::step`] without putting the state back when the terms refuse the force.
    #[inline]
    fn step_unchecked(&mut self, input: f64) -> Result<f64, Error> {
        match self.mode {
            Mode::Feedforward => {
                let position = self.position.map(|x| x + input * self.dt);
                let x = position.unwrap_or(0.0);
                // Only the position terms read the position (and they are refused without a
                // start): without them, a feedforward step is exactly the plain model's (an
                // overflowing integral of an absurd velocity is harmless).
                if self.has_terms() && input.is_finite() && !x.is_finite() {
                    return Err(Error::NotFinite {
                        field: Field::x,
                        index: 0,
                        value: x,
                    });
                }
                let force = self
                    .params
                    .step(&mut self.state, input, self.dt, Scheme::Implicit)?;
                let force = self.finish(force, x, input)?;
                self.position = position;
                Ok(force)
            }
            Mode::Observer => {
                let previous = self.state.last_position;
                // The velocity of this step, from the position before it (0 on the first).
                let v = position_velocity(&self.state, input, self.dt);
                let force = self
                    .params
                    .step_position(&mut self.state, input, self.dt, Scheme::Implicit)
                    .map_err(|error| match (error, previous) {
                        // A finite position can still jump too far for one sample: say so with
                        // the positions, not with a velocity the caller never gave.
                        (
                            Error::NotFinite {
                                field: Field::v, ..
                            },
                            Some(previous),
                        ) => Error::VelocityNotFinite {
                            x: input,
                            previous,
                            dt: self.dt,
                        },
                        (error, _) => error,
                    })?;
                // The step succeeded, so its velocity was finite.
                self.finish(force, input, v.unwrap_or(0.0))
            }
        }
    }

    /// The plain force `force` with the position terms at `x` and velocity `v`, recorded as
    /// the output.
    #[inline]
    fn finish(&mut self, force: f64, x: f64, v: f64) -> Result<f64, Error> {
        let force = self
            .params
            .at_position(force, x, v, &self.level, &self.position_force)?;
        self.output = force;
        Ok(force)
    }

    /// Swaps in new parameters between two samples, re-initialising the state so that the
    /// hysteresis force carries over (see the module documentation). Never fails: `params` was
    /// validated when it was built.
    pub fn set_params(&mut self, params: Params<H>) {
        let target = self
            .params
            .hysteresis()
            .force(&self.state.memory, self.state.z);
        let bank = params.hysteresis();
        let mut memory = self.state.memory;
        bank.commit(&mut memory, self.state.z);
        let limit = bank.max_force();
        let target = if target > limit {
            limit
        } else if target < -limit {
            -limit
        } else {
            target
        };
        let z = match_force(bank, &memory, self.state.z, target);
        bank.commit(&mut memory, z);
        self.state.z = z;
        self.state.memory = memory;
        self.params = params;
    }

    /// Back to rest: relaxed state, no previous position, output 0. The feedforward position
    /// stays: resetting the model does not move the axis (call [`Compensator::set_position`]
    /// if it has moved).
    pub fn reset(&mut self) {
        self.state = self.params.relaxed_state();
        self.output = 0.0;
    }

    /// The last force returned by [`Compensator::step`] (0 before the first).
    pub fn output(&self) -> f64 {
        self.output
    }

    /// The parameters in use.
    pub fn params(&self) -> &Params<H> {
        &self.params
    }

    /// The model state of the axis.
    pub fn state(&self) -> &State<H::Memory> {
        &self.state
    }

    /// The sample time \[s\].
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// What the input is.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The position-dependent level ([`Level::none`] unless one was given).
    pub fn level(&self) -> &Level {
        &self.level
    }

    /// The position force ([`PositionForce::none`] unless one was given).
    pub fn position_force(&self) -> &PositionForce {
        &self.position_force
    }

    /// The feedforward position: the start position given, then the desired positions stepped
    /// ([`Compensator::step_trajectory`]) or the desired velocities integrated since; `None`
    /// until a start position is given. Observer mode leaves it alone.
    pub fn position(&self) -> Option<f64> {
        self.position
    }
}

/// The z at which the trial force of `bank` from `memory` equals `target`, starting the walk at
/// `start`, where every element is within its limits (the memory was committed there).
///
/// The trial force is continuous, non-decreasing and piecewise linear; the walk follows it one
/// linear piece at a time towards `target`, solving each piece in closed form. A bank has two
/// breakpoints per element, hence at most 2N + 1 pieces; the cap below counts them from the size
/// of the memory (one f64 per element). Starting from committed elements, the trial is flat in
/// the direction of the walk only where every element is saturated, i.e. at ±`ΣWᵢ`, which a
/// clamped `target` never lies beyond.
fn match_force<H: Hysteresis>(bank: &H, memory: &H::Memory, start: f64, target: f64) -> f64 {
    let elements = core::mem::size_of::<H::Memory>() / core::mem::size_of::<f64>();
    let mut y = start;
    for _ in 0..evaluation_bound(elements) {
        let trial = bank.trial(memory, y);
        let gap = target - trial.force;
        let (slope, end) = if gap > 0.0 {
            (trial.slope_right, trial.right)
        } else {
            (trial.slope_left, trial.left)
        };
        if gap == 0.0 || slope <= 0.0 {
            return y;
        }
        let candidate = y + gap / slope;
        let on_piece = if gap > 0.0 {
            candidate <= end
        } else {
            candidate >= end
        };
        if on_piece {
            return candidate;
        }
        y = end;
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LeuvenParams, Linear, LuGreParams, MaxwellSlip, Stribeck};

    fn leuven(w: [f64; 3], delta: [f64; 3], sigma2: f64) -> LeuvenParams<3> {
        let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
        Params::new(
            stribeck,
            2.0,
            30.0,
            sigma2,
            MaxwellSlip::new(w, delta).unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn matches_the_force_on_any_piece() {
        let bank = MaxwellSlip::new([1.0, 2.0, 3.0], [1e-6, 2e-6, 4e-6]).unwrap();
        let memory = [0.0, -1e-6, 2e-6];
        for target in [-5.9, -3.0, -0.1, 0.0, 0.7, 2.5, 5.999] {
            let z = match_force(&bank, &memory, 0.0, target);
            assert!((bank.force(&memory, z) - target).abs() < 1e-12, "{target}");
        }
        // The extremes are reached at the last breakpoint.
        let z = match_force(&bank, &memory, 0.0, 6.0);
        assert!((bank.force(&memory, z) - 6.0).abs() < 1e-12);
    }

    #[test]
    fn linear_spring_is_one_piece() {
        let spring = Linear::new(1e5).unwrap();
        assert_eq!(match_force(&spring, &(), 0.3, 2.0), 0.3 + (2.0 - 3e4) / 1e5);
        let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
        let params = LuGreParams::new(stribeck, 1.0, 316.0, 0.4, spring).unwrap();
        let mut compensator = Compensator::new(params, 1e-3, Mode::Feedforward).unwrap();
        compensator.step(1e-3).unwrap();
        let before = params.hysteresis().force(&(), compensator.state().z);
        let stiffer = LuGreParams::new(stribeck, 1.0, 316.0, 0.4, Linear::new(3e5).unwrap());
        compensator.set_params(stiffer.unwrap());
        let after = stiffer
            .unwrap()
            .hysteresis()
            .force(&(), compensator.state().z);
        assert!((after - before).abs() < 1e-12);
    }

    #[test]
    fn bad_dt_and_inputs_are_errors_that_change_nothing() {
        let params = leuven([0.6, 0.6, 0.6], [1e-6, 2e-6, 4e-6], 0.4);
        for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                Compensator::new(params, dt, Mode::Observer),
                Err(Error::NotPositive { field: Field::dt, value }) if value.to_bits() == dt.to_bits()
            ));
        }
        for mode in [Mode::Feedforward, Mode::Observer] {
            let mut compensator = Compensator::new(params, 1e-3, mode).unwrap();
            for k in 0..20 {
                compensator.step(1e-6 * f64::from(k)).unwrap();
            }
            let before = compensator;
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                assert!(matches!(
                    compensator.step(bad),
                    Err(Error::NotFinite { field, index: 0, value })
                        if field == mode.field() && value.to_bits() == bad.to_bits()
                ));
                assert_eq!(compensator, before);
                assert!(compensator.output().is_finite());
            }
        }
        // A finite position whose difference overflows is a velocity error.
        let mut observer = Compensator::new(params, 1e-3, Mode::Observer).unwrap();
        observer.step(-f64::MAX).unwrap();
        let before = observer;
        assert_eq!(
            observer.step(f64::MAX),
            Err(Error::VelocityNotFinite {
                x: f64::MAX,
                previous: -f64::MAX,
                dt: 1e-3
            })
        );
        assert_eq!(observer, before);
    }

    #[test]
    fn same_parameters_change_nothing() {
        let params = leuven([0.6, 0.6, 0.6], [1e-6, 2e-6, 4e-6], 0.4);
        let mut compensator = Compensator::new(params, 1e-3, Mode::Feedforward).unwrap();
        for k in 0..50 {
            compensator
                .step(2e-3 * libm::sin(0.2 * f64::from(k)))
                .unwrap();
        }
        let before = compensator;
        compensator.set_params(params);
        assert_eq!(compensator, before);
    }

    #[test]
    fn reset_relaxes() {
        let params = leuven([0.6, 0.6, 0.6], [1e-6, 2e-6, 4e-6], 0.4);
        let mut compensator = Compensator::new(params, 1e-3, Mode::Observer).unwrap();
        compensator.step(0.0).unwrap();
        compensator.step(1e-6).unwrap();
        compensator.reset();
        assert_eq!(
            compensator,
            Compensator::new(params, 1e-3, Mode::Observer).unwrap()
        );
    }
}
