//! L channels stepped together through their rows of samples: gms-core's `advance` per lane.

use gms_core::{Params, Scheme, State};

use crate::lanes::{BatchHysteresis, LaneKernel};
use crate::math::{Exponent, One, Other, Two};
use crate::solver::{solve, Step};
use crate::Signal;

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
    if n == 1.0 {
        run_with::<H, One, L>(group, One)
    } else if n == 2.0 {
        run_with::<H, Two, L>(group, Two)
    } else {
        run_with::<H, Other, L>(group, Other(n))
    }
}

#[inline(always)]
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
    // gms-core scans a row for finiteness before it steps it; a row that fails is gms-core's to
    // report.
    if !input.iter().all(|x| x.is_finite()) {
        return Err(Rejected);
    }
    let (stribeck, sigma1, sigma2) = (params.stribeck(), params.sigma1(), params.sigma2());
    let level = match signal {
        Signal::Position(level) if !level.is_flat() => Some(level),
        _ => None,
    };
    let position = matches!(signal, Signal::Position(_));
    let mut memory = kernel.gather::<L>(states);
    let mut z: [f64; L] = core::array::from_fn(|l| states[l].z);
    let mut last: [f64; L] = core::array::from_fn(|l| states[l].last_position.unwrap_or(0.0));
    let mut has_last: [bool; L] = core::array::from_fn(|l| states[l].last_position.is_some());
    for t in 0..samples {
        let x: [f64; L] = core::array::from_fn(|l| input[l * samples + t]);
        let v: [f64; L] = if position {
            core::array::from_fn(|l| {
                if has_last[l] {
                    (x[l] - last[l]) / dt
                } else {
                    0.0
                }
            })
        } else {
            x
        };
        if position && !v.iter().all(|v| v.is_finite()) {
            return Err(Rejected);
        }
        let z_next = match scheme {
            Scheme::Implicit => {
                let step = Step {
                    z,
                    dt_v: core::array::from_fn(|l| dt * v[l]),
                    dt_abs_v: core::array::from_fn(|l| dt * libm::fabs(v[l])),
                    inverse_g: core::array::from_fn(|l| 1.0 / stribeck.g(v[l])),
                };
                solve::<H::Kernel, E, L>(kernel, &memory, &step, exponent).ok_or(Rejected)?
            }
            Scheme::Explicit => {
                let force = kernel.force::<L>(&memory, &z);
                let g: [f64; L] = core::array::from_fn(|l| stribeck.g(v[l]));
                core::array::from_fn(|l| {
                    let u = force[l] / g[l];
                    z[l] + dt * (v[l] - libm::fabs(v[l]) * exponent.phi(u))
                })
            }
        };
        if !z_next.iter().all(|z| z.is_finite()) {
            return Err(Rejected);
        }
        let hysteresis = kernel.commit::<L>(&mut memory, &z_next);
        let mut force: [f64; L] = core::array::from_fn(|l| {
            hysteresis[l] + sigma1 * (z_next[l] - z[l]) / dt + sigma2 * v[l]
        });
        if !force.iter().all(|force| force.is_finite()) {
            return Err(Rejected);
        }
        if let Some(level) = level {
            for l in 0..L {
                force[l] = level.apply(force[l], x[l], v[l], sigma2);
            }
            if !force.iter().all(|force| force.is_finite()) {
                return Err(Rejected);
            }
        }
        for l in 0..L {
            out[l * samples + t] = force[l];
        }
        z = z_next;
        if position {
            last = x;
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
