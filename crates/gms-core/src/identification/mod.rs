//! Online identification: recursive least squares on the friction terms that enter linearly.
//!
//! - [`Rls`]: recursive least squares with forgetting and numerical guards, for any `P`
//!   parameters (nalgebra fixed-size matrices, no allocation).
//! - [`SlipRegressor`]: the responses ψᵢ of Maxwell-slip elements with fixed break deflections
//!   Δᵢ, in which the element weights Wᵢ enter linearly (the paper's presliding identification).
//! - [`OnlineIdentifier`]: the two together, for F = Σᵢ Wᵢ·ψᵢ + Fc·sgn(v) + sigma2·v + offset.

mod online;
mod regressor;
mod rls;

pub use online::{OnlineIdentifier, EXTRA_TERMS, EXTRA_TERM_NAMES};
pub use regressor::SlipRegressor;
pub use rls::{Rls, RlsSettings};
