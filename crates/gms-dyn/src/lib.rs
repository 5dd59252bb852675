//! # gms-dyn: gms-core with the number of elements chosen at run time
//!
//! gms-core fixes the number N of Maxwell-slip elements in its types, so that a step needs no
//! allocation; Python and C callers choose N at run time. This crate is the one bridge between
//! the two, shared by the Python bindings (gms-py) and the C ABI (gms-ffi):
//!
//! - [`RawParams`]: a parameter set as plain values, as Python or C give it;
//!   [`RawParams::validate`] checks it once and dispatches N once, into a [`ParameterSet`].
//! - [`FrictionBank`] and [`MassBank`]: channels of the friction model, or of a mass on it,
//!   that share one parameter set; block runs go over the channels in parallel, all or nothing.
//! - [`Compensator`]: one axis of friction compensation, optionally with a position-dependent
//!   [`Level`] and a [`PositionForce`] (re-exported from gms-core, which validates them).
//! - [`OnlineIdentifier`] and [`slip_responses`]: identification with N chosen at run time.
//! - [`Error`]: gms-core's rules plus the refusals of this layer, each displayed as the whole
//!   message the user reads, with its data ([`Error::details`]: kind, field, value) beside it.
//! - [`with_params!`]: code generic over the hysteresis, run on whichever gms-core parameters a
//!   [`ParameterSet`] holds (the crates built on this one, gms-fit, dispatch through it).
//!
//! The bindings on top only convert arguments and map [`Error`]s to exception classes or
//! status codes.

#![forbid(unsafe_code)]

mod channels;
mod compensator;
mod error;
mod friction;
mod kind;
mod mass;
mod online;
mod params;
mod slip;

pub use compensator::{Compensator, CompensatorState, Terms};
pub use error::{Details, Error, ErrorClass, Location, Number};
pub use friction::{FrictionBank, Input};
pub use gms_core::{Level, PositionForce, PositionSeries, RippleTerms, MAX_HARMONICS, MAX_RIPPLES};
pub use kind::HysteresisKind;
pub use mass::{MassBank, MassStates, Mechanics};
pub use online::OnlineIdentifier;
pub use params::{ParameterSet, RawElements, RawParams};
pub use slip::slip_responses;

/// The `seq!` macro that [`with_params!`] expands to, reachable from the crates that call it.
#[doc(hidden)]
pub use seq_macro::seq as __seq;

/// The largest number of Maxwell-slip elements a run-time parameter set may have.
///
/// Every N from 1 to this is compiled in (see `params.rs`); more would lengthen the build for
/// no model anyone identifies.
pub const MAX_ELEMENTS: usize = 32;
