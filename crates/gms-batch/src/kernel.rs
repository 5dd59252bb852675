//! L channels stepped together through their rows of samples: gms-core's `advance` per lane,
//! then gms-core's position terms on the forces.

use gms_core::{Params, Scheme, State};

use crate::curve::Curve;
use crate::lanes::{BatchHysteresis, LaneKernel};
use crate::math::{all_finite, lanes, Closed, Exponent, One, Other, Two};
use crate::solver::{solve, Step};
use crate::Signal;

/// Samples per block (see `run_with`).
const BLOCK: usize = 64;

/// A lane rejected a sample (a non-finite input, velocity or result): the group's states are
/// untouched and gms-core runs the group again, to report exactly what it reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rejected;

/// What one group runs on: L channels' states and their rows (each `samples` long) of the input
/// and output.
pub(crate) struct Group<'a, H: BatchHysteresis> {
    pub params: &'a Params<H>,
    pub kernel: &'a H::Kernel,
    pub states: &'a mut [State<H::Memory>],
    pub input: &'a [f64],
    pub out: &'a mut [f64],
    pub samples: usize,
    pub dt: f64,
    pub scheme: Scheme,
    pub signal: Signal<'a>,
}

/// Runs the group, choosing the exponent's form once.
#[inline(always)]
pub(crate) fn run<H: BatchHysteresis, const L: usize>(group: Group<'_, H>) -> Result<(), Rejected> {
    let n = group.params.n();
    // gms-core's closed form of LuGre's implicit step (a linear spring with n = 1), as a kernel
    // of its own: tested inside the shared kernel, it slowed LuGre's explicit batch by 12-15 %
    // (one thread, AVX2), although that path never takes it.
    let closed = match group.scheme {
        Scheme::Implicit if n == 1.0 => group.params.hysteresis().linear_stiffness(),
        _ => None,
    };
    if let Some(stiffness) = closed {
        run_with::<H, Closed, L>(group, Closed { stiffness })
    } else if n == 1.0 {
        run_with::<H, One, L>(group, One)
    } else if n == 2.0 {
        run_with::<H, Two, L>(group, Two)
    } else {
        run_with::<H, Other, L>(group, Other::new(n))
    }
}

#[inline(always)]
#[allow(clippy::too_many_lines)] // one pass over the samples, kept in one piece
fn run_with<H: BatchHysteresis, E: Exponent, const L: usize>(
    group: Group<'_, H>,
    exponent: E,
) -> Result<(), Rejected> {
    let Group {
        params,
        kernel,
        states,
        input,
        out,
        samples,
        dt,
        scheme,
        signal,
    } = group;
    debug_assert!(states.len() == L && input.len() == L * samples && out.len() == input.len());
    // The positions of velocity input, and the terms on the output (none when both are none:
    // then the forces are the plain ones, bit for bit).
    let (positions, terms) = match signal {
        Signal::Velocity => (None, None),
        Signal::VelocityAt { x, level, force } => (Some(x), Some((level, force))),
        Signal::Position { level, force } => (None, Some((level, force))),
    };
    let terms = terms.filter(|(level, force)| !(level.is_flat() && force.is_none()));
    // gms-core scans a row for finiteness before it steps it; a row that fails is gms-core's to
    // report.
    if !input
        .iter()
        .chain(positions.unwrap_or(&[]))
        .all(|x| x.is_finite())
    {
        return Err(Rejected);
    }
    let (curve, sigma1) = (Curve::new(params.stribeck()), params.sigma1());
    let inverse_dt = 1.0 / dt;
    let linear = exponent.closed_form();
    let position = matches!(signal, Signal::Position { .. });
    let mut memory = kernel.gather::<L>(states);
    let mut z: [f64; L] = lanes(|l| states[l].z);
    let mut last: [f64; L] = lanes(|l| states[l].last_position.unwrap_or(0.0));
    let mut has_last = [false; L];
    for (has_last, state) in has_last.iter_mut().zip(&*states) {
        *has_last = state.last_position.is_some();
    }
    // The samples go in blocks: what depends only on the input (the velocity, g(v) and its
    // exponential) is computed for a whole block in short loops whose iterations are
    // independent, then the block is stepped sample by sample, then its forces are written out
    // row by row.
    // What the next step starts from: the trial at z (implicit) or Fh(z) (explicit), each
    // computed by the previous step's commit in the same pass.
    let mut first_trial = match scheme {
        Scheme::Implicit => Some(kernel.trial::<L>(&memory, &z)),
        Scheme::Explicit => None,
    };
    let mut force_at_z = match scheme {
        Scheme::Implicit => [0.0; L],
        Scheme::Explicit => kernel.force::<L>(&memory, &z),
    };
    let mut x = [[0.0; L]; BLOCK];
    // The positions of velocity input (position input has them in `x`).
    let mut at = [[0.0; L]; BLOCK];
    let mut v = [[0.0; L]; BLOCK];
    let mut g = [[0.0; L]; BLOCK];
    let mut forces = [[0.0; L]; BLOCK];
    for start in (0..samples).step_by(BLOCK) {
        let len = BLOCK.min(samples - start);
        for l in 0..L {
            let row = &input[l * samples + start..l * samples + start + len];
            for (x, &sample) in x.iter_mut().zip(row) {
                x[l] = sample;
            }
            if let Some(positions) = positions {
                let row = &positions[l * samples + start..l * samples + start + len];
                for (at, &sample) in at.iter_mut().zip(row) {
                    at[l] = sample;
                }
            }
        }
        for t in 0..len {
            v[t] = if position {
                let previous = if t == 0 { last } else { x[t - 1] };
                let v: [f64; L] = lanes(|l| {
                    if has_last[l] || t > 0 {
                        (x[t][l] - previous[l]) / dt
                    } else {
                        0.0
                    }
                });
                if !all_finite(&v) {
                    return Err(Rejected);
                }
                v
            } else {
                x[t]
            };
        }
        for t in 0..len {
            g[t] = match scheme {
                // The closed form uses g(v) itself, through its factor g/(g + dt·|v|·k).
                Scheme::Implicit if linear.is_some() => curve.g(&v[t]),
                // The implicit step's walk uses 1/g(v).
                Scheme::Implicit => {
                    let g = curve.g(&v[t]);
                    lanes(|l| 1.0 / g[l])
                }
                Scheme::Explicit => curve.g(&v[t]),
            };
        }
        for t in 0..len {
            let v = &v[t];
            let z_next = match (scheme, linear) {
                (Scheme::Implicit, Some(stiffness)) => {
                    let g = &g[t];
                    lanes(|l| {
                        (z[l] + dt * v[l]) * (g[l] / (g[l] + dt * libm::fabs(v[l]) * stiffness))
                    })
                }
                (Scheme::Implicit, None) => {
                    let step = Step {
                        z,
                        dt_v: lanes(|l| dt * v[l]),
                        dt_abs_v: lanes(|l| dt * libm::fabs(v[l])),
                        inverse_g: g[t],
                    };
                    let first = first_trial.ok_or(Rejected)?;
                    solve::<H::Kernel, E, L>(kernel, &memory, &step, first, exponent)
                        .ok_or(Rejected)?
                }
                (Scheme::Explicit, _) => {
                    let force = &force_at_z;
                    let g = &g[t];
                    lanes(|l| {
                        let u = force[l] / g[l];
                        z[l] + dt * (v[l] - libm::fabs(v[l]) * exponent.phi(u))
                    })
                }
            };
            if !all_finite(&z_next) {
                return Err(Rejected);
            }
            let hysteresis = match scheme {
                Scheme::Implicit => {
                    let (hysteresis, next) = kernel.commit_trial::<L>(&mut memory, &z_next);
                    first_trial = Some(next);
                    hysteresis
                }
                Scheme::Explicit => {
                    let (hysteresis, next) = kernel.commit_force::<L>(&mut memory, &z_next);
                    force_at_z = next;
                    hysteresis
                }
            };
            let force: [f64; L] = lanes(|l| {
                hysteresis[l]
                    + sigma1 * (z_next[l] - z[l]) * inverse_dt
                    + params.sigma2_at(v[l]) * v[l]
            });
            if !all_finite(&force) {
                return Err(Rejected);
            }
            forces[t] = force;
            z = z_next;
        }
        if let Some((level, force)) = terms {
            // gms-core's `at_position`, in its order.
            let x = if position { &x } else { &at };
            for t in 0..len {
                for l in 0..L {
                    let (x, v) = (x[t][l], v[t][l]);
                    let leveled = level.apply(forces[t][l], x, v, params.sigma2_at(v));
                    forces[t][l] = force.apply(leveled, x);
                }
                if !all_finite(&forces[t]) {
                    return Err(Rejected);
                }
            }
        }
        for l in 0..L {
            let row = &mut out[l * samples + start..l * samples + start + len];
            for (out, force) in row.iter_mut().zip(&forces) {
                *out = force[l];
            }
        }
        if position {
            last = x[len - 1];
            has_last = [true; L];
        }
    }
    kernel.scatter::<L>(&memory, states);
    for (l, state) in states.iter_mut().enumerate() {
        state.z = z[l];
        if position && samples > 0 {
            state.last_position = Some(last[l]);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use gms_core::{Level, MaxwellSlip, Params, PositionForce, RippleTerms, Scheme, Stribeck};

    use super::{run, Group};
    use crate::{BatchHysteresis, Signal, LANES};

    /// Groups with the position terms run in the lanes, not handed back to gms-core (which
    /// would also agree, and so hide a kernel that rejects them): velocity, velocity with
    /// positions, and position input, with an asymmetric viscous coefficient.
    #[test]
    fn the_lanes_run_the_position_terms() {
        let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
        let bank = MaxwellSlip::new([0.8, 0.8], [1e-6, 3e-6]).unwrap();
        let params = Params::new(stribeck, 2.0, 30.0, 0.4, bank)
            .and_then(|params| params.with_sigma2_neg(0.9))
            .unwrap();
        let ripple = RippleTerms {
            period: 2e-3,
            cos: &[0.1],
            sin: &[0.05],
        };
        let level = Level::new(0.0, 1e-2, [0.1, 0.0], &[ripple]).unwrap();
        let force = PositionForce::new(0.0, 1e-2, [0.5, 0.1], &[ripple]).unwrap();
        let samples = 100;
        let input: Vec<f64> = (0..LANES * samples)
            .map(|k| 1e-2 * (0.05 * k as f64).sin())
            .collect();
        let x: Vec<f64> = input.iter().map(|v| v * 0.3).collect();
        let kernel = params.hysteresis().kernel();
        for signal in [
            Signal::Velocity,
            Signal::VelocityAt {
                x: &x,
                level: &level,
                force: &force,
            },
            Signal::Position {
                level: &level,
                force: &force,
            },
        ] {
            let mut states = [params.relaxed_state(); LANES];
            let mut out = vec![0.0; input.len()];
            let group = Group {
                params: &params,
                kernel: &kernel,
                states: &mut states,
                input: &input,
                out: &mut out,
                samples,
                dt: 1e-3,
                scheme: Scheme::Implicit,
                signal,
            };
            assert!(run::<_, LANES>(group).is_ok(), "{signal:?}");
        }
    }
}
