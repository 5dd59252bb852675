//! A simulated machine: a mass on the friction model, driven by a force.
//!
//! m·ẍ = u(t) − Ff + k·(a(t) − x), where Ff is the modified Leuven friction force and the spring
//! k is optional: k = 0 is a free mass, a spring to ground has its far end a fixed at 0, and the
//! stick-slip rig drags a at constant speed (a(t) = `drive_speed`·t).
//! [`MassSystem`] holds the parameters, [`MassState`] one channel's x, v, a and friction state;
//! [`MassSystem::step`] advances one sample with an external force (the closed-loop path: a
//! controller computes u from the returned position and velocity), [`MassSystem::simulate`] a
//! whole signal into slices the caller owns.
//!
//! # How the mechanical state is integrated, and why it is stable
//!
//! Same dt contract as the friction step: the friction sees, over step k, the velocity held over
//! that step, wₖ = (xₖ₊₁ − xₖ)/dt.
//!
//! - [`Scheme::Implicit`] (default): backward Euler on the whole state (x, v, z). The new
//!   velocity w and the friction state's new deflection y solve together
//!   m·(w − v)/dt = u + k·(a⁺ − x − dt·w) − Ff(y, w) and the friction's backward-Euler equation
//!   with w held; then x⁺ = x + dt·w. The momentum equation is linear in w on each side of
//!   w = 0 (the viscous force σ2(w)·w takes `sigma2_neg` for w < 0), which reduces the pair to
//!   one scalar root in y, solved with a bracket to a few ulps (see `coupled.rs`).
//! - [`Scheme::Explicit`]: the friction's forward-Euler step with the current velocity held,
//!   then v⁺ = v + dt·(u + k·(a − x) − Ff)/m and x⁺ = x + dt·v. Kept for comparison.
//!
//! Why implicit is stable at any dt: at stick the friction acts on the mass as the spring
//! K = Σ Wᵢ/Δᵢ of the sticking elements in parallel with the damper σ1 + σ2. A coupling that takes
//! the friction force from the previous velocity integrates m·ẍ + (σ1 + σ2)·ẋ + (K + k)·x = 0
//! explicitly, which diverges (or chatters, each sample overshooting the stick) once
//! dt·√((K + k)/m) or dt·(σ1 + σ2)/m approaches 2: with K = 1e8 N/m and m = 1 kg that is
//! dt > 0.2 ms. Backward Euler maps each eigenvalue λ of that linear system (Re λ < 0) to
//! 1/(1 − dt·λ), of modulus < 1 for every dt > 0, so the stick is held without oscillation
//! whatever the stiffness; `tests/mechanics.rs` shows it at dt²·K/m = 100.
//!
//! The friction's output is not monotone in the held velocity (the Stribeck curve falls, and
//! after a speed-up Fh can exceed g(v)), so the scalar equation need not be monotone either. It
//! always has a root (it is continuous and changes sign), and the bracketed search finds one. It
//! is the only one when m/dt exceeds the negative slope of the friction force in w: near stick
//! that slope is positive (the sticking springs), in steady sliding it is g'(w) + σ2, so there
//! dt < m/max(−g'(w) − σ2) suffices (2.3 ms for m = 1 kg, Fs − Fc = 0.5 N, Vs = 1 mm/s, δ = 2,
//! σ2 = 0). Python's `leuven_rt.reference_mechanics` solves the same equation independently.

mod coupled;

use crate::checks::{all_finite, finite, non_negative, positive};
use crate::error::{Error, Field};
use crate::hysteresis::Hysteresis;
use crate::model::{Params, Scheme, State};
use coupled::{Coupled, Momentum};

/// The spring between the mass and its far end a(t) = a₀ + `drive_speed`·t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    stiffness: f64,
    drive_speed: f64,
}

impl Spring {
    /// No spring: a free mass.
    pub const NONE: Spring = Spring {
        stiffness: 0.0,
        drive_speed: 0.0,
    };

    /// A spring of `stiffness` \[N/m\] (finite, ≥ 0) to a fixed point.
    pub fn ground(stiffness: f64) -> Result<Self, Error> {
        Self::dragged(stiffness, 0.0)
    }

    /// A spring of `stiffness` \[N/m\] (finite, ≥ 0) whose far end moves at `drive_speed` \[m/s\]
    /// (finite, any sign): the stick-slip rig.
    pub fn dragged(stiffness: f64, drive_speed: f64) -> Result<Self, Error> {
        non_negative(stiffness, Field::stiffness)?;
        if !drive_speed.is_finite() {
            return Err(Error::NotFiniteValue {
                field: Field::drive_speed,
                value: drive_speed,
            });
        }
        Ok(Self {
            stiffness,
            drive_speed,
        })
    }

    /// Stiffness k \[N/m\].
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// Speed of the far end \[m/s\].
    pub fn drive_speed(&self) -> f64 {
        self.drive_speed
    }
}

/// A mass on the friction model `Params<H>`, with an optional spring: the parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassSystem<H> {
    friction: Params<H>,
    mass: f64,
    spring: Spring,
}

/// One channel of a [`MassSystem`]: the mechanical state and the friction state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassState<M> {
    /// Position x \[m\].
    pub x: f64,
    /// Velocity v \[m/s\].
    pub v: f64,
    /// Position of the spring's far end a \[m\].
    pub anchor: f64,
    /// The friction model's state (z and the hysteresis memory).
    pub friction: State<M>,
}

/// What one step returns: the friction force over the step, and the state at its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassSample {
    /// Friction force Ff over the step \[N\] (acting against the motion).
    pub friction: f64,
    /// Position at the end of the step \[m\].
    pub x: f64,
    /// Velocity at the end of the step \[m/s\] (also the velocity held over it).
    pub v: f64,
}

/// Caller-owned output slices of [`MassSystem::simulate`], one value per input sample.
#[derive(Debug)]
pub struct Trajectory<'a> {
    /// Friction force over each step \[N\].
    pub friction: &'a mut [f64],
    /// Position at the end of each step \[m\].
    pub x: &'a mut [f64],
    /// Velocity at the end of each step \[m/s\].
    pub v: &'a mut [f64],
}

impl<H: Hysteresis> MassSystem<H> {
    /// Validates once: `mass` finite and > 0 (the spring and friction are validated already).
    pub fn new(friction: Params<H>, mass: f64, spring: Spring) -> Result<Self, Error> {
        positive(mass, Field::mass)?;
        Ok(Self {
            friction,
            mass,
            spring,
        })
    }

    /// The friction model.
    pub fn friction(&self) -> &Params<H> {
        &self.friction
    }
    /// Mass m \[kg\].
    pub fn mass(&self) -> f64 {
        self.mass
    }
    /// The spring.
    pub fn spring(&self) -> &Spring {
        &self.spring
    }

    /// At rest at `x`, with the spring's far end at 0 and relaxed friction.
    pub fn state_at(&self, x: f64, v: f64) -> MassState<H::Memory> {
        MassState {
            x,
            v,
            anchor: 0.0,
            friction: self.friction.relaxed_state(),
        }
    }

    /// One step with the applied force `u` held over `dt`.
    ///
    /// A non-finite `u`, a `dt` that is not finite and > 0, or a step whose result is not finite
    /// is reported and leaves the state untouched. Never panics, never allocates.
    pub fn step(
        &self,
        state: &mut MassState<H::Memory>,
        u: f64,
        dt: f64,
        scheme: Scheme,
    ) -> Result<MassSample, Error> {
        positive(dt, Field::dt)?;
        finite(u, Field::u)?;
        self.advance(state, u, dt, scheme)
    }

    /// Runs the applied force `u` through one channel, writing friction force, position and
    /// velocity into `out` (each slice the length of `u`).
    ///
    /// All or nothing: if a sample is rejected, the state is left as it was before the call and
    /// the error names the sample.
    pub fn simulate(
        &self,
        state: &mut MassState<H::Memory>,
        u: &[f64],
        dt: f64,
        scheme: Scheme,
        out: Trajectory<'_>,
    ) -> Result<(), Error> {
        let Trajectory { friction, x, v } = out;
        for got in [friction.len(), x.len(), v.len()] {
            if got != u.len() {
                return Err(Error::LengthMismatch {
                    expected: u.len(),
                    got,
                });
            }
        }
        positive(dt, Field::dt)?;
        all_finite(u, Field::u)?;
        let before = *state;
        for (index, &force) in u.iter().enumerate() {
            let Ok(sample) = self.advance(state, force, dt, scheme) else {
                *state = before;
                return Err(Error::Diverged { index });
            };
            friction[index] = sample.friction;
            x[index] = sample.x;
            v[index] = sample.v;
        }
        Ok(())
    }

    /// The step proper, for inputs already checked.
    #[inline]
    fn advance(
        &self,
        state: &mut MassState<H::Memory>,
        u: f64,
        dt: f64,
        scheme: Scheme,
    ) -> Result<MassSample, Error> {
        let (k, m) = (self.spring.stiffness, self.mass);
        let anchor = state.anchor + dt * self.spring.drive_speed;
        let mut friction_state = state.friction;
        let (force, v_next, x_next) = match scheme {
            Scheme::Implicit => {
                // The momentum equation for each sign of the new velocity w, with the σ2 of that
                // direction (coupled.rs); one form when both directions have the same σ2.
                let momentum = |sigma2: f64| Momentum {
                    net: u + k * (anchor - state.x - dt * state.v) - sigma2 * state.v,
                    inverse_s: 1.0 / (m / dt + k * dt + sigma2),
                };
                let (sigma2, sigma2_neg) = (self.friction.sigma2(), self.friction.sigma2_neg());
                let coupled = Coupled {
                    params: &self.friction,
                    memory: &state.friction.memory,
                    z: state.friction.z,
                    v: state.v,
                    dt,
                    forward: momentum(sigma2),
                    backward: (sigma2_neg != sigma2).then(|| momentum(sigma2_neg)),
                };
                let root = coupled.solve().ok_or(Error::Diverged { index: 0 })?;
                let z = friction_state.z;
                // Commit the memory at y: the friction step's own z⁺ for the held velocity w.
                let hysteresis = self
                    .friction
                    .hysteresis()
                    .commit(&mut friction_state.memory, root.y);
                friction_state.z = root.y;
                let force = hysteresis
                    + self.friction.sigma1() * (root.y - z) / dt
                    + self.friction.sigma2_at(root.w) * root.w;
                (force, root.w, state.x + dt * root.w)
            }
            Scheme::Explicit => {
                let force =
                    self.friction
                        .step(&mut friction_state, state.v, dt, Scheme::Explicit)?;
                let acceleration = (u + k * (state.anchor - state.x) - force) / m;
                (force, state.v + dt * acceleration, state.x + dt * state.v)
            }
        };
        if !(force.is_finite() && v_next.is_finite() && x_next.is_finite()) {
            return Err(Error::Diverged { index: 0 });
        }
        *state = MassState {
            x: x_next,
            v: v_next,
            anchor,
            friction: friction_state,
        };
        Ok(MassSample {
            friction: force,
            x: x_next,
            v: v_next,
        })
    }
}
