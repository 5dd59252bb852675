//! # gms-fit: what an output-error fit needs from the model
//!
//! An output-error fit adjusts the parameters of the model file itself until the simulated
//! friction force matches the measured one. Gauss–Newton and Levenberg–Marquardt need, at each
//! iteration, the force along the signal and its derivative by every fitted parameter; line
//! searches and the screening of candidates need the force of many parameter sets along the
//! same signal. This crate gives both:
//!
//! - [`sensitivities`]: the forces of one run (gms-core's step, bit for bit equal to
//!   `Params::simulate`) and the exact derivatives at the chosen rows, propagated along the
//!   same run: gms-core's step plus O(P·N) work per step (the time of a few plain runs, see
//!   `benches/sensitivities.rs`), where finite differences take P + 1 runs;
//! - [`simulate_sets`]: many parameter sets along one signal, in parallel.
//!
//! The columns are always those of the asymmetric parameterisation ([`column_names`]); a
//! symmetric set uses `Fc`, `Fs` and `sigma2` in both directions, so its derivative by one of
//! them is the sum of that column and its `_neg` twin. The equations are in
//! docs/sensitivities.md.
//!
//! The forward values are never computed here: each step is gms-core's own, and the derivatives
//! are taken at the point it reached, from the public state before and after it.

mod bank;
mod columns;
mod curve;
mod error;
mod sensitivity;
mod sets;
mod vector;

use gms_core::Scheme;
use gms_dyn::{Input, ParameterSet};

pub use columns::{column_count, column_names, SHARED_COLUMNS, SHARED_NAMES};
pub use error::{Error, Output};
pub use sets::simulate_sets;

use sensitivity::Differentiable;

/// One signal through the model: its samples, what they are, the step and the scheme. Every run
/// starts from a relaxed channel (z = 0, every element undeflected, no previous position).
#[derive(Clone, Copy, Debug)]
pub struct Simulation<'a> {
    /// The input, one sample per step: velocities, or positions (v = (xₖ − xₖ₋₁)/dt, and
    /// v = 0 on the first sample).
    pub signal: &'a [f64],
    /// What the samples are.
    pub input: Input,
    /// The step length \[s\].
    pub dt: f64,
    /// How the state equation is advanced.
    pub scheme: Scheme,
}

/// The friction force of `set` along the signal of `simulation`, written into `force` (one per
/// sample, equal to gms-core's `Params::simulate` bit for bit), and dF/dθ at the samples `rows`
/// (strictly increasing) written into `jacobian` (rows × [`column_count`], row-major, in the
/// order of [`column_names`]).
///
/// The derivatives are those of the discrete model as stepped: wherever no element changes
/// between sticking and slipping under a small change of θ, they equal the limit of finite
/// differences. The work per step is O(P·N) for P columns and N elements, with no allocation.
///
/// # Errors
/// [`Error::OutputLength`] for a `force` or `jacobian` of the wrong length, [`Error::RowOrder`]
/// and [`Error::RowBeyond`] for `rows` (all checked before any step), and [`Error::Core`] when
/// gms-core refuses a step (a bad `dt`, a non-finite input, a diverging explicit step), naming
/// the sample; `force` and `jacobian` then hold the samples before it.
pub fn sensitivities(
    set: &ParameterSet,
    simulation: Simulation<'_>,
    rows: &[usize],
    force: &mut [f64],
    jacobian: &mut [f64],
) -> Result<(), Error> {
    gms_dyn::with_params!(set, params => Differentiable::track(params, &simulation, rows, force, jacobian))
}
