//! The modified Leuven model (eqs. 1, 3, 4, 5): parameters, per-channel state, the discrete step.
//!
//! The discrete step is the contract of docs/model.md#discrete-step. The velocity vₖ is held over the step;
//! the state equation dz/dt = f(z, v) = v − |v|·sgn(Fh)·|Fh/g(v)|ⁿ is advanced by backward Euler
//! (`Implicit`, the default) or forward Euler (`Explicit`); the memory of the hysteresis is
//! committed at the new z; the output is Fₖ = Fh(z⁺) + σ1·(z⁺ − z)/dt + σ2(vₖ)·vₖ, with
//! σ2(v) = `sigma2_neg` for v < 0 and `sigma2` otherwise.

// The step's parts are `#[inline(always)]`: inlined into each block call's loop, compiled once per
// scheme, they keep the channel in registers; with `#[inline]` LLVM leaves them out of line
// (callgrind: 151 instead of 104 instructions per LuGre step of `simulate`).
#![allow(clippy::inline_always)]

use crate::checks::{all_finite, finite, non_negative, positive};
use crate::error::{Error, Field};
use crate::hysteresis::{Hysteresis, Linear, MaxwellSlip};
use crate::level::{Level, PositionForce};
use crate::math::Power;
use crate::solver::{linear_factor, linear_root, Residual, Solution};
use crate::stribeck::Stribeck;

/// `$body` with `$scheme` bound to the scheme as a constant, written out once per scheme: each
/// block call's loop is then compiled for its scheme, without the test of the scheme inside it.
macro_rules! per_scheme {
    ($scheme:expr, |$bound:ident| $body:expr) => {
        match $scheme {
            Scheme::Implicit => {
                let $bound = Scheme::Implicit;
                $body
            }
            Scheme::Explicit => {
                let $bound = Scheme::Explicit;
                $body
            }
        }
    };
}

/// `$body` with `$bound` bound to the exponents (n, n − 1) of `$params` ([`Exponents`]): to
/// the constants (`Power::Two`, `Power::One`) when n = 2, so that the block call's loop for the
/// common exponent is compiled with φ(u) = u·|u| and the solver's quadratic, without a test of
/// n's class in every evaluation of φ; otherwise to the parameters' own.
macro_rules! per_power {
    ($params:expr, |$bound:ident| $body:expr) => {
        if $params.n == Power::Two {
            let $bound = Exponents {
                n: Power::Two,
                n_less_one: Power::One,
            };
            $body
        } else {
            let $bound = $params.exponents();
            $body
        }
    };
}

/// The transition exponent n and n − 1 (for the slope of φ in the solver's Newton iteration),
/// classified: what a step raises to.
#[derive(Clone, Copy)]
struct Exponents {
    n: Power,
    n_less_one: Power,
}

/// Samples of a block call whose values that depend on the input alone are computed ahead of
/// stepping them ([`run_ahead`]), in a buffer on the stack: LuGre's implicit factor
/// g/(g + dt·|v|·k) (512 bytes; 1 KiB with position input, whose velocities are kept too), and
/// the level's factor and the position force at the positions (1 KiB, and 4 KiB more while
/// they are evaluated lane by lane).
const AHEAD: usize = 64;

/// How the state equation is advanced over one step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// Backward Euler: stable at any step with any stiffness.
    #[default]
    Implicit,
    /// Forward Euler: kept for comparison; unstable when dt·|v|·stiffness/g(v) exceeds 2.
    Explicit,
}

/// Parameters of one friction model, shared by any number of channels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params<H> {
    stribeck: Stribeck,
    /// n, classified once (integer and half-integer exponents are evaluated without `pow`).
    n: Power,
    /// n − 1, the exponent of dφ/du = n·|u|ⁿ⁻¹ in the implicit solver's Newton iteration.
    n_less_one: Power,
    sigma1: f64,
    sigma2: f64,
    /// σ2 for v < 0 (σ2 unless [`Params::with_sigma2_neg`] gave another).
    sigma2_neg: f64,
    hysteresis: H,
}

/// The modified Leuven model with an `N`-element Maxwell-slip hysteresis.
pub type LeuvenParams<const N: usize> = Params<MaxwellSlip<N>>;

/// The LuGre model: linear hysteresis (and n = 1 for the classic form).
pub type LuGreParams = Params<Linear>;

/// The state of one channel: deflection z, hysteresis memory, last position (for position input).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<M> {
    /// Average deflection of the asperity junctions z \[m\].
    pub z: f64,
    /// Memory of the hysteresis (ζ of each Maxwell-slip element).
    pub memory: M,
    /// The position of the previous position-input step; `None` on a fresh channel.
    pub last_position: Option<f64>,
}

impl<H: Hysteresis> Params<H> {
    /// Validates once: `n > 0`, `sigma1 >= 0`, `sigma2 >= 0`, and a hysteresis strong enough to
    /// balance the Stribeck curve (`sum(W) > max(Fs, Fs_neg)`).
    pub fn new(
        stribeck: Stribeck,
        n: f64,
        sigma1: f64,
        sigma2: f64,
        hysteresis: H,
    ) -> Result<Self, Error> {
        positive(n, Field::n)?;
        non_negative(sigma1, Field::sigma1)?;
        non_negative(sigma2, Field::sigma2)?;
        if hysteresis.max_force() <= stribeck.peak() {
            return Err(Error::ElementsTooWeak {
                sum: hysteresis.max_force(),
                peak: stribeck.peak(),
            });
        }
        Ok(Self {
            stribeck,
            n: Power::new(n),
            n_less_one: Power::new(n - 1.0),
            sigma1,
            sigma2,
            sigma2_neg: sigma2,
            hysteresis,
        })
    }

    /// These parameters with the viscous coefficient `sigma2_neg` (finite, ≥ 0) for v < 0:
    /// the viscous force becomes σ2(v)·v, σ2(v) = `sigma2_neg` for v < 0 and `sigma2` for v ≥ 0
    /// (docs/model.md#friction-force). Without it, σ2 applies in both directions.
    ///
    /// # Errors
    /// [`Error::Negative`] naming `sigma2_neg`.
    pub fn with_sigma2_neg(self, sigma2_neg: f64) -> Result<Self, Error> {
        let sigma2_neg = non_negative(sigma2_neg, Field::sigma2_neg)?;
        Ok(Self { sigma2_neg, ..self })
    }

    /// The Stribeck curve.
    pub fn stribeck(&self) -> &Stribeck {
        &self.stribeck
    }
    /// Transition-curve exponent n.
    pub fn n(&self) -> f64 {
        self.n.exponent()
    }
    /// Micro-viscous coefficient σ1.
    pub fn sigma1(&self) -> f64 {
        self.sigma1
    }
    /// Viscous coefficient σ2 (for v ≥ 0).
    pub fn sigma2(&self) -> f64 {
        self.sigma2
    }
    /// Viscous coefficient for v < 0 (σ2 unless [`Params::with_sigma2_neg`] gave another).
    pub fn sigma2_neg(&self) -> f64 {
        self.sigma2_neg
    }
    /// The viscous coefficient that applies to the velocity `v`: `sigma2_neg` for v < 0,
    /// `sigma2` otherwise.
    #[inline]
    pub fn sigma2_at(&self, v: f64) -> f64 {
        if v < 0.0 {
            self.sigma2_neg
        } else {
            self.sigma2
        }
    }
    /// The hysteresis force.
    pub fn hysteresis(&self) -> &H {
        &self.hysteresis
    }

    /// A relaxed channel: z = 0, every element undeflected, no previous position.
    pub fn relaxed_state(&self) -> State<H::Memory> {
        State {
            z: 0.0,
            memory: self.hysteresis.relaxed(),
            last_position: None,
        }
    }

    /// Checks a channel state written from outside (not produced by stepping): z finite, the
    /// previous position finite if there is one, and every element within its window,
    /// |z − ζᵢ| ≤ Δᵢ up to a rounding tolerance of 4 ulps of max(|z|, Δᵢ), so that any state
    /// read from a channel passes. A state outside its windows would move the elements at
    /// v = 0 and give a force that does not match it.
    ///
    /// # Errors
    /// [`Error::NotFiniteValue`] for `z` or `x` (the previous position), or
    /// [`Error::StateOutsideWindow`] naming the first element out of its window.
    pub fn check_state(&self, state: &State<H::Memory>) -> Result<(), Error> {
        let not_finite = |field, value: f64| Error::NotFiniteValue { field, value };
        if !state.z.is_finite() {
            return Err(not_finite(Field::z, state.z));
        }
        if let Some(previous) = state.last_position.filter(|x| !x.is_finite()) {
            return Err(not_finite(Field::x, previous));
        }
        self.hysteresis.check_memory(&state.memory, state.z)
    }

    /// dz/dt = f(z, v) with the hysteresis trial at z from the state's memory.
    pub fn state_derivative(&self, state: &State<H::Memory>, z: f64, v: f64) -> f64 {
        Self::derivative(
            self.hysteresis.force(&state.memory, z),
            v,
            self.stribeck.g(v),
            self.n,
        )
    }

    /// f(z, v) given Fh(z) (`force`) and g(v) (`g`), with n as `n`.
    #[inline(always)]
    fn derivative(force: f64, v: f64, g: f64, n: Power) -> f64 {
        let u = force / g;
        v - libm::fabs(v) * libm::copysign(n.abs(u), u)
    }

    /// n and n − 1, as classified at construction.
    #[inline(always)]
    fn exponents(&self) -> Exponents {
        Exponents {
            n: self.n,
            n_less_one: self.n_less_one,
        }
    }

    /// One step with velocity input `v` held over `dt`; returns the friction force.
    ///
    /// A non-finite `v`, a `dt` that is not finite and > 0, or a diverging explicit step is
    /// reported and leaves the state untouched. Never panics, never allocates.
    pub fn step(
        &self,
        state: &mut State<H::Memory>,
        v: f64,
        dt: f64,
        scheme: Scheme,
    ) -> Result<f64, Error> {
        check_dt(dt)?;
        let inverse_dt = 1.0 / dt;
        finite(v, Field::v)?;
        self.advance(state, v, dt, inverse_dt, scheme)
    }

    /// One step with position input `x`: v = (x − `x_prev`)/dt, and v = 0 on a fresh channel.
    pub fn step_position(
        &self,
        state: &mut State<H::Memory>,
        x: f64,
        dt: f64,
        scheme: Scheme,
    ) -> Result<f64, Error> {
        check_dt(dt)?;
        let inverse_dt = 1.0 / dt;
        finite(x, Field::x)?;
        self.advance_position(state, x, dt, inverse_dt, scheme)
    }

    /// Runs `v` through one channel, writing the forces into `out` (same length).
    ///
    /// All or nothing: if any sample is rejected (non-finite input, a diverging explicit step),
    /// the state is left as it was before the call and the error names the sample.
    pub fn simulate(
        &self,
        state: &mut State<H::Memory>,
        v: &[f64],
        dt: f64,
        scheme: Scheme,
        out: &mut [f64],
    ) -> Result<(), Error> {
        check_block(v, Field::v, dt, out)?;
        let inverse_dt = 1.0 / dt;
        if let Some(stiffness) = self.closed_form(scheme) {
            return self.run_linear(state, v, dt, stiffness, out, |force, _| Ok(force));
        }
        let mut at_z = self.force_at(state);
        per_scheme!(scheme, |scheme| per_power!(self, |exponents| {
            run_ahead(
                state,
                v,
                out,
                |_, v, levels| self.levels(v, levels),
                |state, v, g| {
                    let step = (v, g, dt, inverse_dt);
                    self.advance_from::<true>(state, step, scheme, exponents, &mut at_z)
                },
            )
        }))
    }

    /// Runs positions `x` through one channel, writing the forces into `out` (same length);
    /// all or nothing, like [`Params::simulate`].
    pub fn simulate_position(
        &self,
        state: &mut State<H::Memory>,
        x: &[f64],
        dt: f64,
        scheme: Scheme,
        out: &mut [f64],
    ) -> Result<(), Error> {
        check_block(x, Field::x, dt, out)?;
        let inverse_dt = 1.0 / dt;
        if let Some(stiffness) = self.closed_form(scheme) {
            return self.run_linear_position(state, x, dt, stiffness, out, |force, _, _| Ok(force));
        }
        let mut at_z = self.force_at(state);
        per_scheme!(scheme, |scheme| per_power!(self, |exponents| {
            run_ahead(
                state,
                x,
                out,
                |state, x, values| self.velocities_and_levels(state, x, dt, values),
                |state, x, (v, g)| {
                    let v = finite_velocity(v)?;
                    let step = (v, g, dt, inverse_dt);
                    let force =
                        self.advance_from::<true>(state, step, scheme, exponents, &mut at_z)?;
                    state.last_position = Some(x);
                    // run_ahead puts the state back on this error, like on any other.
                    Ok(force)
                },
            )
        }))
    }

    /// [`Params::simulate_position`] with a position-dependent level and a position force
    /// (docs/model.md#position-dependent-level): each force is
    /// `position_force.apply(level.apply(F, x, v, σ2(v)), x)`, that is
    /// factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x), with vₖ the step's velocity (0 on a fresh
    /// channel). The state evolves exactly as without them (they act on the output only), and
    /// [`Level::none`] with [`PositionForce::none`] give [`Params::simulate_position`]'s forces
    /// bit for bit. All or nothing; a force they make non-finite is [`Error::Diverged`].
    #[allow(clippy::too_many_arguments)] // the block call, plus the two position terms
    pub fn simulate_position_level(
        &self,
        state: &mut State<H::Memory>,
        x: &[f64],
        dt: f64,
        scheme: Scheme,
        level: &Level,
        position_force: &PositionForce,
        out: &mut [f64],
    ) -> Result<(), Error> {
        check_block(x, Field::x, dt, out)?;
        let inverse_dt = 1.0 / dt;
        if let Some(stiffness) = self.closed_form(scheme) {
            return self.run_linear_position(state, x, dt, stiffness, out, |force, x, v| {
                self.at_position(force, x, v, level, position_force)
            });
        }
        // The terms depend on the position alone: a chunk's are evaluated ahead of stepping it.
        let mut at_z = self.force_at(state);
        per_scheme!(scheme, |scheme| per_power!(self, |exponents| {
            run_ahead(
                state,
                x,
                out,
                |state, x, values| {
                    let mut steps = [(0.0, 0.0); AHEAD];
                    self.velocities_and_levels(state, x, dt, &mut steps);
                    let mut terms = [(0.0, 0.0); AHEAD];
                    position_terms(level, position_force, x, &mut terms);
                    for (value, (step, terms)) in
                        values.iter_mut().zip(steps.into_iter().zip(terms))
                    {
                        *value = (step, terms);
                    }
                },
                |state, x, ((v, g), terms)| {
                    let v = finite_velocity(v)?;
                    let step = (v, g, dt, inverse_dt);
                    let force =
                        self.advance_from::<true>(state, step, scheme, exponents, &mut at_z)?;
                    state.last_position = Some(x);
                    // run_ahead puts the state back on this error, like on any other.
                    self.with_terms(force, v, terms, level, position_force)
                },
            )
        }))
    }

    /// [`Params::simulate`] with a position-dependent level and a position force evaluated at
    /// the positions `x` (same length as `v`): the velocity `v` is the model's input, as a log
    /// with a measured velocity column drives it, and each force is
    /// `position_force.apply(level.apply(F, xₖ, vₖ, σ2(vₖ)), xₖ)`. The positions only place
    /// the two terms: the state evolves as in [`Params::simulate`] (the previous position of
    /// position input is not touched), and [`Level::none`] with [`PositionForce::none`] give its
    /// forces bit for bit. All or nothing, like the other block calls.
    ///
    /// # Errors
    /// [`Error::InputLengthMismatch`] naming `x`, [`Error::LengthMismatch`] for `out`, a bad
    /// `dt`, [`Error::NotFinite`] naming `v` or `x` and the sample, or [`Error::Diverged`].
    #[allow(clippy::too_many_arguments)] // the block call, plus the positions and the two terms
    pub fn simulate_level(
        &self,
        state: &mut State<H::Memory>,
        v: &[f64],
        x: &[f64],
        dt: f64,
        scheme: Scheme,
        level: &Level,
        position_force: &PositionForce,
        out: &mut [f64],
    ) -> Result<(), Error> {
        if x.len() != v.len() {
            return Err(Error::InputLengthMismatch {
                field: Field::x,
                expected: v.len(),
                got: x.len(),
            });
        }
        check_block(v, Field::v, dt, out)?;
        let inverse_dt = 1.0 / dt;
        all_finite(x, Field::x)?;
        if let Some(stiffness) = self.closed_form(scheme) {
            let mut positions = x.iter();
            return self.run_linear(state, v, dt, stiffness, out, |force, v| {
                // The lengths are equal, so there is always a position.
                let x = positions.next().copied().unwrap_or(f64::NAN);
                self.at_position(force, x, v, level, position_force)
            });
        }
        let mut at_z = self.force_at(state);
        per_scheme!(scheme, |scheme| per_power!(self, |exponents| {
            // The chunks of x are those of v (the lengths are equal), their terms evaluated
            // ahead of stepping them.
            let mut positions = x.chunks(AHEAD);
            run_ahead(
                state,
                v,
                out,
                |_, v, values| {
                    let x = positions.next().unwrap_or(&[]);
                    let mut levels = [0.0; AHEAD];
                    self.levels(v, &mut levels);
                    let mut terms = [(0.0, 0.0); AHEAD];
                    position_terms(level, position_force, x, &mut terms);
                    for (value, (g, terms)) in values.iter_mut().zip(levels.into_iter().zip(terms))
                    {
                        *value = (g, terms);
                    }
                },
                |state, v, (g, terms)| {
                    let step = (v, g, dt, inverse_dt);
                    let force =
                        self.advance_from::<true>(state, step, scheme, exponents, &mut at_z)?;
                    self.with_terms(force, v, terms, level, position_force)
                },
            )
        }))
    }

    /// [`Params::at_position`] with the terms at the step's position evaluated already
    /// ([`position_terms`]): the level's factor and the position force.
    #[inline(always)]
    fn with_terms(
        &self,
        force: f64,
        v: f64,
        (factor, added): (f64, f64),
        level: &Level,
        position_force: &PositionForce,
    ) -> Result<f64, Error> {
        let force = level.apply_factor(factor, force, v, self.sigma2_at(v));
        finite_force(position_force.apply_force(added, force))
    }

    /// The plain force `force` of a step at position `x` and velocity `v` with the level and
    /// the position force: refused as a divergence if they make it non-finite.
    #[inline]
    pub(crate) fn at_position(
        &self,
        force: f64,
        x: f64,
        v: f64,
        level: &Level,
        position_force: &PositionForce,
    ) -> Result<f64, Error> {
        finite_force(position_force.apply(level.apply(force, x, v, self.sigma2_at(v)), x))
    }

    /// [`Params::simulate_position`], also writing the deflection z after every sample into
    /// `z` (same length): the state the hysteresis elements are driven by, for analysis.
    ///
    /// As with the other block calls, a rejected sample leaves the state as it was; `out` and
    /// `z` then hold the samples before it.
    pub fn simulate_position_deflection(
        &self,
        state: &mut State<H::Memory>,
        x: &[f64],
        dt: f64,
        scheme: Scheme,
        out: &mut [f64],
        z: &mut [f64],
    ) -> Result<(), Error> {
        check_block(x, Field::x, dt, out)?;
        let inverse_dt = 1.0 / dt;
        if z.len() != x.len() {
            return Err(Error::LengthMismatch {
                expected: x.len(),
                got: z.len(),
            });
        }
        let mut deflections = z.iter_mut();
        let mut at_z = self.force_at(state);
        run_block(state, x, out, |state, x| {
            let v = position_velocity(state, x, dt)?;
            let step = (v, self.stribeck.g(v), dt, inverse_dt);
            let force =
                self.advance_from::<true>(state, step, scheme, self.exponents(), &mut at_z)?;
            state.last_position = Some(x);
            if let Some(slot) = deflections.next() {
                *slot = state.z;
            }
            Ok(force)
        })
    }

    /// The implicit step's root for this state and input, without committing anything.
    ///
    /// Exposed so that the solver's accuracy and iteration count can be checked from outside.
    pub fn solve_implicit(&self, state: &State<H::Memory>, v: f64, dt: f64) -> Solution {
        match self.linear_root(state, v, dt) {
            Some(z) => Solution { z, iterations: 1 },
            None => self.residual(state, v, dt).solve(),
        }
    }

    /// LuGre's implicit step (a linear spring, n = 1): R is linear in y, so the root is one
    /// closed form and no Fh is evaluated; `None` for any other model.
    #[inline(always)]
    fn linear_root(&self, state: &State<H::Memory>, v: f64, dt: f64) -> Option<f64> {
        self.closed_form(Scheme::Implicit)
            .map(|stiffness| linear_root(state.z, dt * v, self.linear_factor(v, dt, stiffness)))
    }

    /// The spring's stiffness k when `scheme`'s step is solved in closed form (implicit, a linear
    /// spring, n = 1).
    #[inline(always)]
    fn closed_form(&self, scheme: Scheme) -> Option<f64> {
        match (scheme, self.n) {
            (Scheme::Implicit, Power::One) => self.hysteresis.linear_stiffness(),
            _ => None,
        }
    }

    /// g(v)/(g(v) + dt·|v|·k): the factor of the closed form, from the input alone.
    #[inline(always)]
    fn linear_factor(&self, v: f64, dt: f64, stiffness: f64) -> f64 {
        linear_factor(dt * libm::fabs(v), stiffness, self.stribeck.g(v))
    }

    /// LuGre's implicit block on velocities `v`, `then` applied to each force (with its
    /// velocity). The factors of [`AHEAD`] samples are computed first: they depend on the input
    /// alone, so their evaluations of g (an `exp`, and the division by `Vs`) overlap, instead of
    /// each step waiting for its own; each step then adds and multiplies. The same operations as
    /// [`Params::advance`], so the same forces bit for bit.
    #[inline(always)]
    fn run_linear(
        &self,
        state: &mut State<H::Memory>,
        v: &[f64],
        dt: f64,
        stiffness: f64,
        out: &mut [f64],
        mut then: impl FnMut(f64, f64) -> Result<f64, Error>,
    ) -> Result<(), Error> {
        let inverse_dt = 1.0 / dt;
        run_ahead(
            state,
            v,
            out,
            |_, v, factors| {
                for (factor, &v) in factors.iter_mut().zip(v) {
                    *factor = self.linear_factor(v, dt, stiffness);
                }
            },
            |state, v, factor| {
                let z_next = linear_root(state.z, dt * v, factor);
                let force = self.advance_to::<false>(state, v, inverse_dt, z_next, &mut 0.0)?;
                then(force, v)
            },
        )
    }

    /// [`Params::run_linear`] on positions `x`, `then` applied to each force (with its position
    /// and velocity): the velocities of a chunk are computed ahead too, as
    /// [`position_velocity`] computes them.
    #[inline(always)]
    fn run_linear_position(
        &self,
        state: &mut State<H::Memory>,
        x: &[f64],
        dt: f64,
        stiffness: f64,
        out: &mut [f64],
        mut then: impl FnMut(f64, f64, f64) -> Result<f64, Error>,
    ) -> Result<(), Error> {
        let inverse_dt = 1.0 / dt;
        run_ahead(
            state,
            x,
            out,
            |state, x, values| {
                let mut previous = state.last_position;
                for (value, &x) in values.iter_mut().zip(x) {
                    let v = velocity_between(previous, x, dt);
                    previous = Some(x);
                    // A non-finite v gives a non-finite factor, never used: the step refuses v.
                    *value = (v, self.linear_factor(v, dt, stiffness));
                }
            },
            |state, x, (v, factor)| {
                let v = finite_velocity(v)?;
                let z_next = linear_root(state.z, dt * v, factor);
                let force = self.advance_to::<false>(state, v, inverse_dt, z_next, &mut 0.0)?;
                state.last_position = Some(x);
                // run_ahead puts the state back on this error, like on any other.
                then(force, x, v)
            },
        )
    }

    /// R(y) of the implicit step from this state (zero at the step's solution).
    pub fn implicit_residual(&self, state: &State<H::Memory>, v: f64, dt: f64, y: f64) -> f64 {
        self.residual(state, v, dt).evaluate(y)
    }

    fn residual<'a>(&'a self, state: &'a State<H::Memory>, v: f64, dt: f64) -> Residual<'a, H> {
        self.residual_with(state, v, self.stribeck.g(v), dt, self.exponents())
    }

    /// [`Params::residual`] with the exponents `exponents` (constants in a block call's loop
    /// for n = 2, see [`per_power`]).
    #[inline(always)]
    fn residual_with<'a>(
        &'a self,
        state: &'a State<H::Memory>,
        v: f64,
        g: f64,
        dt: f64,
        Exponents { n, n_less_one }: Exponents,
    ) -> Residual<'a, H> {
        Residual {
            hysteresis: &self.hysteresis,
            memory: &state.memory,
            z: state.z,
            dt_v: dt * v,
            dt_abs_v: dt * libm::fabs(v),
            inverse_g: 1.0 / g,
            n,
            n_less_one,
        }
    }

    /// The step proper, for inputs already checked.
    ///
    /// A diverging step (non-finite z⁺ or force) must leave the state untouched. Committing
    /// into a copy of the memory and storing it back costs two copies of the memory per step
    /// (2 × 256 bytes at N = 32), so the force's finiteness is decided before committing
    /// instead: |Fh(z⁺)| ≤ B (`force_bound`), hence |F| ≤ B + |σ1·(z⁺ − z)/dt| + |σ2(v)·v|, and
    /// when that sum is below half the f64 range, rounding in the sum of Fh cannot carry F to
    /// infinity either, so the memory is committed in place. Only forces near the f64 range
    /// (or a hysteresis without a bound) take the copying path.
    ///
    /// Always inlined, so that each block call's loop is compiled for its scheme ([`per_scheme`])
    /// and keeps the state in registers.
    #[inline(always)]
    fn advance(
        &self,
        state: &mut State<H::Memory>,
        v: f64,
        dt: f64,
        inverse_dt: f64,
        scheme: Scheme,
    ) -> Result<f64, Error> {
        let step = (v, self.stribeck.g(v), dt, inverse_dt);
        self.advance_from::<false>(state, step, scheme, self.exponents(), &mut 0.0)
    }

    /// [`Params::advance`] with Fh(z) at step start handed over when `CARRY`: `at_z` holds it on
    /// entry and, after a step that succeeded, Fh(z⁺) from the moved memory, which the next step
    /// starts from ([`Hysteresis::commit_force`]). The block calls carry it from step to step,
    /// which saves a pass over the elements per step; without `CARRY` it is evaluated here and
    /// `at_z` is neither read nor written. The same values either way, bit for bit.
    #[inline(always)]
    fn advance_from<const CARRY: bool>(
        &self,
        state: &mut State<H::Memory>,
        (v, g, dt, inverse_dt): (f64, f64, f64, f64),
        scheme: Scheme,
        exponents: Exponents,
        at_z: &mut f64,
    ) -> Result<f64, Error> {
        let z = state.z;
        let force_at_z = |state: &State<H::Memory>| {
            if CARRY {
                *at_z
            } else {
                self.hysteresis.force(&state.memory, z)
            }
        };
        let z_next = match scheme {
            Scheme::Implicit => {
                if let Some(z_next) = self.linear_root(state, v, dt) {
                    z_next
                } else {
                    let residual = self.residual_with(state, v, g, dt, exponents);
                    residual.solve_from(force_at_z(state)).z
                }
            }
            Scheme::Explicit => z + dt * Self::derivative(force_at_z(state), v, g, exponents.n),
        };
        self.advance_to::<CARRY>(state, v, inverse_dt, z_next, at_z)
    }

    /// Fh(z) at the start of a block call's first step, for [`Params::advance_from`]: evaluated
    /// only where a step uses it (not by the closed form of [`Params::closed_form`]).
    #[inline(always)]
    fn force_at(&self, state: &State<H::Memory>) -> f64 {
        self.hysteresis.force(&state.memory, state.z)
    }

    /// g(v) at each of the velocities `v` (at most [`AHEAD`]) into `levels`: a chunk's are
    /// computed ahead of stepping it, so that their exponentials overlap instead of each step
    /// waiting for its own. The same g as a step computes, so the same forces bit for bit.
    #[inline(always)]
    fn levels(&self, v: &[f64], levels: &mut [f64; AHEAD]) {
        for (level, &v) in levels.iter_mut().zip(v) {
            *level = self.stribeck.g(v);
        }
    }

    /// The velocity at each of the positions `x` (at most [`AHEAD`]; as [`position_velocity`]
    /// computes it, from the state's last position on) and g at it, into `values`, ahead of
    /// stepping them as in [`Params::levels`]. A non-finite velocity gets a level that is never
    /// used: the step refuses the velocity.
    #[inline(always)]
    fn velocities_and_levels(
        &self,
        state: &State<H::Memory>,
        x: &[f64],
        dt: f64,
        values: &mut [(f64, f64); AHEAD],
    ) {
        let mut previous = state.last_position;
        for (value, &x) in values.iter_mut().zip(x) {
            let v = velocity_between(previous, x, dt);
            previous = Some(x);
            *value = (v, self.stribeck.g(v));
        }
    }

    /// The step to the new deflection `z_next` (refused if not finite): the force and the
    /// commit of [`Params::advance`].
    /// With `CARRY`, also writes Fh(z⁺) from the moved memory into `at_z` ([`Params::advance_from`]).
    #[inline(always)]
    fn advance_to<const CARRY: bool>(
        &self,
        state: &mut State<H::Memory>,
        v: f64,
        inverse_dt: f64,
        z_next: f64,
        at_z: &mut f64,
    ) -> Result<f64, Error> {
        let z = state.z;
        if !z_next.is_finite() {
            return Err(Error::Diverged { index: 0 });
        }
        let micro_viscous = self.sigma1 * (z_next - z) * inverse_dt;
        let viscous = self.sigma2_at(v) * v;
        let bound =
            self.hysteresis.force_bound(z_next) + libm::fabs(micro_viscous) + libm::fabs(viscous);
        let hysteresis = if bound < 0.5 * f64::MAX {
            if CARRY {
                let (committed, next) = self.hysteresis.commit_force(&mut state.memory, z_next);
                *at_z = next;
                committed
            } else {
                self.hysteresis.commit(&mut state.memory, z_next)
            }
        } else {
            let (committed, next) =
                self.commit_copy::<CARRY>(&mut state.memory, z_next, micro_viscous, viscous)?;
            if CARRY {
                *at_z = next;
            }
            committed
        };
        state.z = z_next;
        Ok(hysteresis + micro_viscous + viscous)
    }

    /// The commit of a step whose force may not be finite: into a copy of the memory, stored
    /// back only if the force is finite. Out of line, so that the in-place path keeps its own
    /// inlined commit.
    /// Returns Fh(z⁺) as committed and, with `CARRY`, Fh(z⁺) from the moved memory (else NaN).
    #[cold]
    #[inline(never)]
    fn commit_copy<const CARRY: bool>(
        &self,
        memory: &mut H::Memory,
        z_next: f64,
        micro_viscous: f64,
        viscous: f64,
    ) -> Result<(f64, f64), Error> {
        let mut copy = *memory;
        let (committed, next) = if CARRY {
            self.hysteresis.commit_force(&mut copy, z_next)
        } else {
            (self.hysteresis.commit(&mut copy, z_next), f64::NAN)
        };
        if !(committed + micro_viscous + viscous).is_finite() {
            return Err(Error::Diverged { index: 0 });
        }
        *memory = copy;
        Ok((committed, next))
    }

    #[inline(always)]
    fn advance_position(
        &self,
        state: &mut State<H::Memory>,
        x: f64,
        dt: f64,
        inverse_dt: f64,
        scheme: Scheme,
    ) -> Result<f64, Error> {
        let v = position_velocity(state, x, dt)?;
        let force = self.advance(state, v, dt, inverse_dt, scheme)?;
        state.last_position = Some(x);
        Ok(force)
    }
}

/// The velocity of a position step: (x − `x_prev`)/dt, and 0 on a fresh channel.
#[inline]
pub(crate) fn position_velocity<M>(state: &State<M>, x: f64, dt: f64) -> Result<f64, Error> {
    finite_velocity(velocity_between(state.last_position, x, dt))
}

/// (x − `previous`)/dt, and 0 without a previous position.
#[inline(always)]
fn velocity_between(previous: Option<f64>, x: f64, dt: f64) -> f64 {
    match previous {
        Some(previous) => (x - previous) / dt,
        None => 0.0,
    }
}

/// `v`, or the refusal of a non-finite velocity (a position step too large for dt).
#[inline(always)]
fn finite_velocity(v: f64) -> Result<f64, Error> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::NotFinite {
            field: Field::v,
            index: 0,
            value: v,
        })
    }
}

/// The level's factor and the position force at each of the positions `x` (at most [`AHEAD`])
/// into `terms`: a whole chunk at a time (a short one padded with zeros), lane by lane, the
/// same arithmetic as [`Level::factor`] and [`PositionForce::force`] at one position.
#[inline(always)]
fn position_terms(
    level: &Level,
    position_force: &PositionForce,
    x: &[f64],
    terms: &mut [(f64, f64); AHEAD],
) {
    let mut positions = [0.0; AHEAD];
    for (position, &x) in positions.iter_mut().zip(x) {
        *position = x;
    }
    let (mut factors, mut added) = ([1.0; AHEAD], [0.0; AHEAD]);
    if !level.is_flat() {
        level.factors(&positions, &mut factors);
    }
    if !position_force.is_none() {
        position_force.forces(&positions, &mut added);
    }
    for (terms, (&factor, &added)) in terms.iter_mut().zip(factors.iter().zip(&added)) {
        *terms = (factor, added);
    }
}

/// `force`, or a divergence if the position terms made it non-finite.
#[inline(always)]
fn finite_force(force: f64) -> Result<f64, Error> {
    if force.is_finite() {
        Ok(force)
    } else {
        Err(Error::Diverged { index: 0 })
    }
}

fn check_dt(dt: f64) -> Result<(), Error> {
    positive(dt, Field::dt).map(|_| ())
}

fn check_block(input: &[f64], field: Field, dt: f64, out: &[f64]) -> Result<(), Error> {
    if out.len() != input.len() {
        return Err(Error::LengthMismatch {
            expected: input.len(),
            got: out.len(),
        });
    }
    check_dt(dt)?;
    all_finite(input, field)
}

/// Steps through `input`; on the first error, puts the state back as it was and names the sample.
#[inline(always)]
fn run_block<M: Copy>(
    state: &mut State<M>,
    input: &[f64],
    out: &mut [f64],
    mut step: impl FnMut(&mut State<M>, f64) -> Result<f64, Error>,
) -> Result<(), Error> {
    let before = *state;
    for (index, (&sample, out)) in input.iter().zip(out.iter_mut()).enumerate() {
        match step(state, sample) {
            Ok(force) => *out = force,
            Err(error) => {
                *state = before;
                return Err(at_sample(error, index));
            }
        }
    }
    Ok(())
}

/// [`run_block`] a chunk of [`AHEAD`] samples at a time: `ahead` fills a value per sample of the
/// chunk from the state before it and the chunk's input, then `step` steps each sample with its
/// value. On the first error, puts the state back as it was before the block and names the sample.
#[inline(always)]
fn run_ahead<M: Copy, T: Copy + Default>(
    state: &mut State<M>,
    input: &[f64],
    out: &mut [f64],
    mut ahead: impl FnMut(&State<M>, &[f64], &mut [T; AHEAD]),
    mut step: impl FnMut(&mut State<M>, f64, T) -> Result<f64, Error>,
) -> Result<(), Error> {
    let before = *state;
    let mut values = [T::default(); AHEAD];
    let chunks = input.chunks(AHEAD).zip(out.chunks_mut(AHEAD));
    for (chunk, (input, out)) in chunks.enumerate() {
        ahead(state, input, &mut values);
        for (index, ((&sample, out), &value)) in
            input.iter().zip(out.iter_mut()).zip(&values).enumerate()
        {
            match step(state, sample, value) {
                Ok(force) => *out = force,
                Err(error) => {
                    *state = before;
                    return Err(at_sample(error, chunk * AHEAD + index));
                }
            }
        }
    }
    Ok(())
}

fn at_sample(error: Error, index: usize) -> Error {
    match error {
        Error::NotFinite { field, value, .. } => Error::NotFinite {
            field,
            index,
            value,
        },
        Error::Diverged { .. } => Error::Diverged { index },
        other => other,
    }
}
