//! The forces along a signal and their derivatives by every parameter, carried from step to step
//! (docs/sensitivities.md).
//!
//! The forward values are gms-core's own step: each sample is stepped by [`Params::step`] (or
//! `step_position`), so the forces are [`Params::simulate`]'s bit for bit. The derivatives are
//! then taken at the point that step reached: for the implicit step, by the implicit function
//! theorem at its root; for the explicit one, by the chain rule through z + dt·f(z, v). Each
//! element's memory carries its own sensitivity, which a slip replaces by that of z.

use gms_core::{Hysteresis, Linear, MaxwellSlip, Params, Scheme, State, Stribeck};
use gms_dyn::Input;

use crate::bank::{Bank, Elements, Spring};
use crate::columns::{N, SHARED_COLUMNS, SIGMA1, SIGMA2, SIGMA2_NEG};
use crate::curve::{self, Transition};
use crate::error::{Error, Output};
use crate::vector::Vector;
use crate::Simulation;

/// The hysteresis types whose parameters can be differentiated: Maxwell slip (one column per
/// weight) and the linear spring (one column, σ0).
pub(crate) trait Differentiable: Hysteresis + Sized {
    /// [`crate::sensitivities`] for these parameters.
    fn track(
        params: &Params<Self>,
        simulation: &Simulation<'_>,
        rows: &[usize],
        force: &mut [f64],
        jacobian: &mut [f64],
    ) -> Result<(), Error>;
}

impl<const E: usize> Differentiable for MaxwellSlip<E> {
    fn track(
        params: &Params<Self>,
        simulation: &Simulation<'_>,
        rows: &[usize],
        force: &mut [f64],
        jacobian: &mut [f64],
    ) -> Result<(), Error> {
        let bank = Elements::new(params.hysteresis());
        track::<Self, Elements<E>, E>(params, bank, simulation, rows, force, jacobian)
    }
}

impl Differentiable for Linear {
    fn track(
        params: &Params<Self>,
        simulation: &Simulation<'_>,
        rows: &[usize],
        force: &mut [f64],
        jacobian: &mut [f64],
    ) -> Result<(), Error> {
        let bank = Spring::new(*params.hysteresis());
        track::<Self, Spring, 1>(params, bank, simulation, rows, force, jacobian)
    }
}

/// Refuses outputs of the wrong length and rows that are not strictly increasing samples.
fn check_call(
    samples: usize,
    rows: &[usize],
    columns: usize,
    force: &[f64],
    jacobian: &[f64],
) -> Result<(), Error> {
    if force.len() != samples {
        return Err(Error::OutputLength {
            output: Output::Force,
            expected: samples,
            got: force.len(),
        });
    }
    for (index, pair) in rows.windows(2).enumerate() {
        if pair[1] <= pair[0] {
            return Err(Error::RowOrder {
                index: index + 1,
                row: pair[1],
                previous: pair[0],
            });
        }
    }
    // Increasing, so the last row is the largest.
    if let Some(&row) = rows.last().filter(|&&row| row >= samples) {
        return Err(Error::RowBeyond {
            index: rows.len() - 1,
            row,
            samples,
        });
    }
    let expected = rows.len().saturating_mul(columns);
    if jacobian.len() != expected {
        return Err(Error::OutputLength {
            output: Output::Jacobian,
            expected,
            got: jacobian.len(),
        });
    }
    Ok(())
}

fn track<H, B, const M: usize>(
    params: &Params<H>,
    bank: B,
    simulation: &Simulation<'_>,
    rows: &[usize],
    force: &mut [f64],
    jacobian: &mut [f64],
) -> Result<(), Error>
where
    H: Hysteresis,
    B: Bank<M, Memory = H::Memory>,
{
    let Simulation {
        signal,
        input,
        dt,
        scheme,
    } = *simulation;
    let columns = SHARED_COLUMNS + M;
    check_call(signal.len(), rows, columns, force, jacobian)?;
    let mut state = params.relaxed_state();
    let mut tracker = Tracker::new(params, bank, dt, scheme);
    let mut wanted = rows
        .iter()
        .copied()
        .zip(jacobian.chunks_exact_mut(columns))
        .peekable();
    for (index, (&sample, out)) in signal.iter().zip(force.iter_mut()).enumerate() {
        let before = state;
        let (result, v) = match input {
            Input::Velocity => (params.step(&mut state, sample, dt, scheme), sample),
            // gms-core's velocity of a position step, the same expression (docs/model.md#discrete-step).
            Input::Position => (
                params.step_position(&mut state, sample, dt, scheme),
                before
                    .last_position
                    .map_or(0.0, |previous| (sample - previous) / dt),
            ),
        };
        *out = result.map_err(|error| Error::at_sample(error, index))?;
        let row = wanted
            .next_if(|(row, _)| *row == index)
            .map(|(_, slot)| slot);
        tracker.step(&before, state.z, v, row);
    }
    Ok(())
}

/// dz/dθ and every element's dζᵢ/dθ, carried along one channel.
struct Tracker<B: Bank<M>, const M: usize> {
    bank: B,
    stribeck: Stribeck,
    transition: Transition,
    sigma1: f64,
    dt: f64,
    scheme: Scheme,
    /// dz/dθ.
    s: Vector<M>,
    /// dζᵢ/dθ of every element.
    carried: B::Carried,
    /// Scratch: which elements stick at the latest linearisation.
    sticking: B::Sticking,
    /// Scratch: dFh/dθ at fixed deflection, from the latest linearisation.
    d: Vector<M>,
}

impl<B: Bank<M>, const M: usize> Tracker<B, M> {
    fn new<H: Hysteresis>(params: &Params<H>, bank: B, dt: f64, scheme: Scheme) -> Self {
        let (carried, sticking) = bank.relaxed();
        Self {
            bank,
            stribeck: *params.stribeck(),
            transition: Transition::new(params.n()),
            sigma1: params.sigma1(),
            dt,
            scheme,
            s: Vector::ZERO,
            carried,
            sticking,
            d: Vector::ZERO,
        }
    }

    /// One step from state `before` to deflection `z_next` (gms-core's), with velocity `v`;
    /// writes dF/dθ of the step into `row` when given.
    #[inline]
    fn step(&mut self, before: &State<B::Memory>, z_next: f64, v: f64, row: Option<&mut [f64]>) {
        let c = self.dt * libm::fabs(v);
        // At v = 0 nothing moves: z⁺ = z exactly (gms-core's root is z, and the explicit rate is
        // 0), so dz/dθ stays, and an element that the commit "slips" is one that slipped on the
        // last moving step and sits at its window's edge by rounding: its dζ/dθ is already
        // that step's dz/dθ, which is still the current one. Only an output needs work.
        if c == 0.0 && row.is_none() {
            return;
        }
        let (z, mut next) = (before.z, self.s);
        match self.scheme {
            Scheme::Implicit => {
                // The root's linearisation gives both the step's sensitivity and the output's.
                let root = self.bank.linearise(
                    &before.memory,
                    &mut self.carried,
                    &self.s,
                    z_next,
                    &mut self.sticking,
                    &mut self.d,
                );
                if c != 0.0 {
                    self.implicit(&mut next, root.force, root.slope, v, c);
                }
                if let Some(row) = row {
                    self.output(row, &next, root.slope, z, z_next, v);
                }
            }
            Scheme::Explicit => {
                if c != 0.0 {
                    let start = self.bank.linearise(
                        &before.memory,
                        &mut self.carried,
                        &self.s,
                        z,
                        &mut self.sticking,
                        &mut self.d,
                    );
                    self.explicit(&mut next, start.force, start.slope, v, c);
                }
                // The output's force and the commit are at z⁺, from the memory at step start.
                if let Some(row) = row {
                    let end = self.bank.linearise(
                        &before.memory,
                        &mut self.carried,
                        &self.s,
                        z_next,
                        &mut self.sticking,
                        &mut self.d,
                    );
                    self.output(row, &next, end.slope, z, z_next, v);
                } else {
                    self.bank
                        .sticking(&before.memory, z_next, &mut self.sticking);
                }
            }
        }
        self.bank.carry(&self.sticking, &mut self.carried, &self.s);
        self.s = next;
    }

    /// The implicit step's root z⁺ solves R = (z⁺ − z) − dt·v + c·φ(Fh(z⁺)/g) = 0, c = dt·|v|.
    /// With a = c·φ'(u)/g, K = dFh/dy at the root and D = dFh/dθ at fixed y:
    /// (1 + a·K)·ds⁺ = s − a·(D − u·dg/dθ) − c·φ·ln|u|·dn/dθ.
    #[inline]
    fn implicit(&self, next: &mut Vector<M>, force: f64, slope: f64, v: f64, c: f64) {
        let level = curve::level(&self.stribeck, v);
        let u = force / level.g;
        let transition = self.transition.at(u);
        let a = c * transition.slope / level.g;
        if a.is_finite() {
            next.add_scaled(-a, &self.d);
            for (value, &dg) in next.shared.iter_mut().zip(&level.derivative) {
                *value += a * u * dg;
            }
            next.shared[N] -= c * transition.by_n;
            next.scale(1.0 / (1.0 + a * slope));
        } else {
            // n < 1 at u = 0, where φ' is unbounded: the limit a → ∞, K·ds⁺ = −(D − u·dg/dθ).
            *next = self.d;
            for (value, &dg) in next.shared.iter_mut().zip(&level.derivative) {
                *value -= u * dg;
            }
            next.scale(-1.0 / slope);
        }
    }

    /// The explicit step z⁺ = z + dt·v − c·φ(Fh(z)/g): ds⁺ = s − a·(K·s + D − u·dg/dθ) − c·φ·ln|u|·dn/dθ.
    #[inline]
    fn explicit(&self, next: &mut Vector<M>, force: f64, slope: f64, v: f64, c: f64) {
        let level = curve::level(&self.stribeck, v);
        let u = force / level.g;
        let transition = self.transition.at(u);
        let a = c * transition.slope / level.g;
        next.scale(1.0 - a * slope);
        next.add_scaled(-a, &self.d);
        for (value, &dg) in next.shared.iter_mut().zip(&level.derivative) {
            *value += a * u * dg;
        }
        next.shared[N] -= c * transition.by_n;
    }

    /// dF/dθ of F = Fh(z⁺) + σ1·(z⁺ − z)/dt + σ2·v, with the linearisation at z⁺ in `self.d`
    /// and `slope`: dFh = K·ds⁺ + D.
    #[inline]
    fn output(&self, row: &mut [f64], next: &Vector<M>, slope: f64, z: f64, z_next: f64, v: f64) {
        let mut out = self.d;
        out.add_scaled(slope, next);
        let mut rate = *next;
        rate.add_scaled(-1.0, &self.s);
        out.add_scaled(self.sigma1 / self.dt, &rate);
        out.shared[SIGMA1] += (z_next - z) / self.dt;
        // The viscous term of the step's direction (v = 0 contributes nothing either way).
        out.shared[if v < 0.0 { SIGMA2_NEG } else { SIGMA2 }] += v;
        out.write(row);
    }
}
