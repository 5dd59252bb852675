//! # gms-batch: many channels of gms-core at once
//!
//! gms-core steps one channel at a time. A batch of B channels sharing one parameter set (the
//! (B, T) calls of the Python bindings) is run here [`LANES`] channels at a time: their states
//! are laid out structure-of-arrays (z per lane, ζ\[element\]\[lane\]), and every operation of
//! the step is done for all lanes at once, which the compiler turns into SIMD. The instruction
//! set is chosen at run time ([`Path`]): the baseline of the target, or AVX2 and FMA where the
//! CPU has them.
//!
//! **Same results.** Every lane does exactly gms-core's arithmetic, in gms-core's order: the
//! explicit Euler step, and the implicit step's walk over the linear pieces of Fh, with each
//! lane walking its own pieces (a lane that has found its root keeps it while the others walk
//! on; at most 2N + 1 trial evaluations per lane, as in gms-core). The element sums keep
//! gms-core's four partial sums, no multiply and add is fused, and `pow`, `exp` and g(v) are
//! gms-core's (or the same `libm` functions), so the forces and states agree with
//! [`Params::simulate`] to the last bit in practice; the tests require 1e-12 relative.
//!
//! **Same errors.** A group of lanes whose input is not all finite, or in which a lane's step
//! is rejected (a non-finite velocity from positions, a diverging explicit step), is handed
//! back untouched to gms-core's per-channel calls, which report exactly what they always
//! report. Channels left over (B mod [`LANES`]) run through gms-core too.
//!
//! **Why a second copy.** A lane does what any lane might need (a commit and then a full trial,
//! both sides, in two passes; every form of a piece's root, with selects) where gms-core fuses
//! its passes, asks for one side and branches. Run at one lane (`run_one_lane`), the kernel
//! gives gms-core's forces bit for bit but takes 1.3–2.0× its time per implicit Maxwell-slip
//! step of a block and 1.6–5× per single step (`cargo bench -p gms-batch --bench one_lane`,
//! docs/benchmarks.md#one-step-for-lanes-and-channels), so gms-core keeps its own step and the
//! tests keep the two equal.
//!
//! gms-core stays `no_std` and free of `unsafe`; the one `unsafe` call of this crate enters the
//! AVX2 copy of the kernel after the CPU has been asked (src/dispatch.rs).

mod curve;
mod dispatch;
mod kernel;
mod lanes;
mod math;
mod solver;

use gms_core::{Error, Level, Params, PositionForce, Scheme, State};

pub use dispatch::Path;
pub use lanes::{BatchHysteresis, LaneKernel, LinearKernel, MaxwellKernel, TrialLanes};

/// Channels stepped together: two AVX2 registers of f64, four SSE2 registers. Eight rather
/// than four gives the processor independent work to overlap (measured: 5–15 % faster).
pub const LANES: usize = 8;

/// What the rows of a batch are, and the position-dependent terms on their output
/// (docs/model.md#position-dependent-level).
#[derive(Clone, Copy, Debug)]
pub enum Signal<'a> {
    /// Velocities v \[m/s\]: [`Params::simulate`].
    Velocity,
    /// Velocities v \[m/s\] with the position of every sample, `x` (the input's shape), which
    /// places a level and a position force: [`Params::simulate_level`].
    VelocityAt {
        /// The positions \[m\], channels × samples like the input.
        x: &'a [f64],
        /// The level ([`Level::none`] for none).
        level: &'a Level,
        /// The position force ([`PositionForce::none`] for none).
        force: &'a PositionForce,
    },
    /// Positions x \[m\] with a level and a position force: [`Params::simulate_position`], or
    /// [`Params::simulate_position_level`] when either is given.
    Position {
        /// The level ([`Level::none`] for none).
        level: &'a Level,
        /// The position force ([`PositionForce::none`] for none).
        force: &'a PositionForce,
    },
}

impl Signal<'_> {
    /// The signal of the channels whose samples are `rows` of the input (the positions of
    /// [`Signal::VelocityAt`] cut like the input), for running them apart.
    ///
    /// # Panics
    /// If `rows` is beyond the positions.
    #[must_use]
    pub fn rows(self, rows: core::ops::Range<usize>) -> Self {
        match self {
            Signal::VelocityAt { x, level, force } => Signal::VelocityAt {
                x: &x[rows],
                level,
                force,
            },
            other => other,
        }
    }
}

/// Runs every channel over its row of `input` (`states.len()` rows of `samples`, row-major),
/// writing the forces into `out` (same shape), on the fastest [`Path`] of this CPU.
///
/// Each channel behaves as gms-core's block call on its row (see [`Signal`]): on success its
/// state has advanced; on error its own state is as before and the others may have advanced
/// (the caller restores them, all or nothing). Returns the first failing channel (lowest
/// index) and gms-core's error for it.
///
/// # Panics
/// If `input`, `out` or the positions of [`Signal::VelocityAt`] are not `states.len() × samples`
/// long.
#[allow(clippy::too_many_arguments)] // gms-core's block call, plus the shape
pub fn run<H: BatchHysteresis>(
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, Error)> {
    run_on(
        Path::detected(),
        params,
        states,
        input,
        samples,
        dt,
        scheme,
        signal,
        out,
    )
}

/// [`run`] on a chosen [`Path`] (for tests and benchmarks; a path the CPU lacks runs the
/// baseline).
///
/// # Panics
/// If `input`, `out` or the positions of [`Signal::VelocityAt`] are not `states.len() × samples`
/// long.
#[allow(clippy::too_many_arguments)]
pub fn run_on<H: BatchHysteresis>(
    path: Path,
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, Error)> {
    assert!(
        input.len() == states.len() * samples && out.len() == input.len(),
        "input and output must be channels × samples"
    );
    if let Signal::VelocityAt { x, .. } = signal {
        assert!(
            x.len() == input.len(),
            "positions must be channels × samples"
        );
    }
    // No channels: `samples` is then not tied to the input's length (0 × anything), and
    // LANES × samples could overflow; gms-core's calls still check dt.
    if states.is_empty() || samples == 0 || refused(dt) {
        // Nothing to step, or a dt gms-core refuses: its own calls say so.
        return run_scalar(params, states, input, samples, dt, scheme, signal, out);
    }
    let kernel = params.hysteresis().kernel();
    let block = LANES * samples;
    let mut first_error = None;
    let groups = states
        .chunks_mut(LANES)
        .zip(input.chunks(block).zip(out.chunks_mut(block)));
    for (index, (states, (input, out))) in groups.enumerate() {
        let offset = index * LANES;
        let signal = signal.rows(offset * samples..offset * samples + input.len());
        let vectorized = states.len() == LANES
            && dispatch::run_group::<H, LANES>(
                path,
                kernel::Group {
                    params,
                    kernel: &kernel,
                    states,
                    input,
                    out,
                    samples,
                    dt,
                    scheme,
                    signal,
                },
            )
            .is_ok();
        if !vectorized {
            if let Some((channel, error)) =
                run_scalar(params, states, input, samples, dt, scheme, signal, out)
            {
                first_error = Some((offset + channel, error));
                break;
            }
        }
    }
    first_error
}

/// Whether gms-core refuses `dt` (not finite and positive, or subnormal): its own calls report
/// that, so the kernel never runs on it.
fn refused(dt: f64) -> bool {
    !(dt.is_finite() && dt >= f64::MIN_POSITIVE)
}

/// The channels one by one through gms-core's block calls.
#[allow(clippy::too_many_arguments)]
fn run_scalar<H: BatchHysteresis>(
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, Error)> {
    if samples == 0 {
        // No rows to split: dt is checked on a scratch state, as gms-dyn does.
        let error = params
            .simulate(&mut params.relaxed_state(), &[], dt, scheme, &mut [])
            .err()?;
        return (!states.is_empty()).then_some((0, error));
    }
    states
        .iter_mut()
        .zip(input.chunks(samples).zip(out.chunks_mut(samples)))
        .enumerate()
        .find_map(|(channel, (state, (input, out)))| {
            let result = match signal.rows(channel * samples..(channel + 1) * samples) {
                Signal::Velocity => params.simulate(state, input, dt, scheme, out),
                Signal::VelocityAt { x, level, force } => {
                    params.simulate_level(state, input, x, dt, scheme, level, force, out)
                }
                Signal::Position { level, force } if level.is_flat() && force.is_none() => {
                    params.simulate_position(state, input, dt, scheme, out)
                }
                Signal::Position { level, force } => {
                    params.simulate_position_level(state, input, dt, scheme, level, force, out)
                }
            };
            result.err().map(|error| (channel, error))
        })
}

/// One channel through the lane kernel at one lane (L = 1): the step written over lanes with
/// `f64` as a one-lane value, measured against gms-core's own step by `benches/one_lane.rs` (the
/// reason gms-core keeps its scalar step: docs/benchmarks.md#one-step-for-lanes-and-channels).
/// `kernel` is `params.hysteresis().kernel()`. Returns whether the kernel stepped the row; where
/// it hands the row back (a non-finite input or result, no samples, a dt gms-core refuses) the
/// state is as it was, and `out` may hold the forces of the blocks before. Not for users:
/// gms-core's calls and [`run`] are.
///
/// # Panics
/// If `out` is not as long as `input`.
#[doc(hidden)]
#[must_use]
#[allow(clippy::too_many_arguments)]
pub fn run_one_lane<H: BatchHysteresis>(
    path: Path,
    params: &Params<H>,
    kernel: &H::Kernel,
    state: &mut State<H::Memory>,
    input: &[f64],
    dt: f64,
    scheme: Scheme,
    out: &mut [f64],
) -> bool {
    assert!(out.len() == input.len(), "input and output must be as long");
    // What `run_on` leaves to gms-core's calls, handed back.
    if input.is_empty() || refused(dt) {
        return false;
    }
    dispatch::run_group::<H, 1>(
        path,
        kernel::Group {
            params,
            kernel,
            states: core::slice::from_mut(state),
            input,
            out,
            samples: input.len(),
            dt,
            scheme,
            signal: Signal::Velocity,
        },
    )
    .is_ok()
}
