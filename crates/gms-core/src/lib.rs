//! # gms-core
//!
//! The modified Leuven integrated friction model (Lampaert, Swevers, Al-Bender, IEEE TAC 2002)
//! with its hysteresis force as a fixed-memory Maxwell-slip model, for hard real-time loops:
//! `no_std`, no allocation, no panics in a step, no `unsafe`.
//!
//! - [`Stribeck`]: the constant-velocity curve g(v), s(v), optionally direction-dependent.
//! - [`MaxwellSlip`] and [`Linear`]: the hysteresis force Fh(z) ([`Hysteresis`]).
//! - [`OnlineIdentifier`] ([`identification`]): recursive least squares on the terms that
//!   enter linearly, for adaptation in the loop.
//! - [`MassSystem`]: a mass on the friction model, driven by a force, with an optional spring
//!   (to ground, or dragged: the stick-slip rig).
//! - [`Level`]: a friction level that depends on the position (trend along the stroke and
//!   periodic ripples), and [`PositionForce`]: a force of the position alone (cogging, gear
//!   mesh, gravity along the stroke), both of one shape ([`PositionSeries`]); applied by the
//!   [`Compensator`], [`Params::simulate_position_level`] and [`Params::simulate_level`].
//! - [`Params`]: one validated parameter set that drives any number of channels, each a
//!   [`State`]; [`Params::step`] and the block calls [`Params::simulate`] advance them.
//!
//! ```
//! use gms_core::{LeuvenParams, MaxwellSlip, Scheme, Stribeck};
//!
//! let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0)?;
//! let elements = MaxwellSlip::new([0.6, 0.5, 0.4, 0.3], [1e-6, 2e-6, 4e-6, 8e-6])?;
//! let params = LeuvenParams::new(stribeck, 2.0, 30.0, 0.4, elements)?;
//! let mut channel = params.relaxed_state();
//! let force = params.step(&mut channel, 1e-3, 1e-3, Scheme::Implicit)?;
//! assert!(force > 0.0);
//! # Ok::<(), gms_core::Error>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

// Only for the C library's `pow` (the `std` feature, math.rs): nothing else of std is used.
#[cfg(feature = "std")]
extern crate std;

mod checks;
mod compensator;
mod error;
pub mod hysteresis;
pub mod identification;
mod level;
mod math;
mod mechanics;
mod model;
mod resolution;
mod solver;
mod stribeck;

pub use compensator::{evaluation_bound, Compensator, Mode};
pub use error::{Error, Field, InChannel, Shown};
pub use hysteresis::{Hysteresis, Linear, MaxwellSlip, Piece, Trial, MIN_DELTA_RATIO};
pub use identification::{OnlineIdentifier, Rls, RlsSettings, SlipRegressor};
pub use level::{Level, PositionForce, PositionSeries, RippleTerms, MAX_HARMONICS, MAX_RIPPLES};
pub use math::Power;
pub use mechanics::{MassSample, MassState, MassSystem, Spring, Trajectory};
pub use model::{LeuvenParams, LuGreParams, Params, Scheme, State};
pub use solver::{PieceEquation, Solution, MAX_ITERATIONS};
pub use stribeck::Stribeck;

// The crate's own README (the page of the published crate) runs as doctests of this crate, so it
// cannot drift from the API. (The workspace README's Rust snippet reads a model file, so it runs
// in gms-file, whose dependencies it uses.)
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct CrateReadme;
