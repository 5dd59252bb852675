//! Shared strategies and builders for the integration tests.
//!
//! Everything here produces *valid* inputs (the parameter rules have their own tests in
//! `params.rs`): Stribeck curves with and without direction asymmetry, Maxwell-slip banks of any
//! size `N` that are strong enough to balance the curve, time steps, and velocity sequences that
//! mix plateaus, reversals, exact zeros of both signs and noise.
#![allow(dead_code)] // every test crate includes this module and uses its own subset of it

use gms_core::{Error, Hysteresis, LeuvenParams, MaxwellSlip, Params, Scheme, State, Stribeck};
use proptest::array::uniform;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

/// The proptest configuration of every property: `cases` cases, and failures saved beside the
/// test file (`tests/<name>.proptest-regressions`). The default looks for a `lib.rs` above the
/// test file, finds none for an integration test, and warns on every run.
pub fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::with_cases(cases)
    }
}

/// Values spread evenly over the decades of `[lo, hi]` (both > 0): models, inputs and steps span
/// many orders of magnitude, and a uniform draw would almost never visit the small end.
pub fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    (lo.ln()..=hi.ln()).prop_map(move |exponent| exponent.exp().clamp(lo, hi))
}

/// `magnitude` with a random sign.
pub fn signed(magnitude: impl Strategy<Value = f64> + Clone) -> impl Strategy<Value = f64> + Clone {
    (any::<bool>(), magnitude).prop_map(|(negative, m)| if negative { -m } else { m })
}

/// Time steps from 100 kHz down to 100 Hz.
pub fn dt() -> impl Strategy<Value = f64> + Clone {
    log_uniform(1e-5, 1e-2)
}

/// Exponents n (or δ): the closed-form 1 and 2 often, the integers and half-integers that are
/// evaluated without `pow` (0.5, 1.5, 2.5, 3, 3.5, 4) as often, otherwise anything in (0.3, 4).
pub fn exponent() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        Just(1.0),
        Just(2.0),
        prop::sample::select(&[0.5, 1.5, 2.5, 3.0, 3.5, 4.0][..]),
        0.3..4.0
    ]
}

/// Viscous-type coefficients: exactly zero (Dahl-like) or spread over six decades.
pub fn coefficient() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![Just(0.0), log_uniform(1e-3, 1e3)]
}

/// A Coulomb level and the static-to-Coulomb ratio (exactly 1 sometimes: no Stribeck bump).
fn levels() -> impl Strategy<Value = (f64, f64)> + Clone {
    (log_uniform(0.1, 10.0), prop_oneof![Just(1.0), 1.0..3.0])
}

/// A valid Stribeck curve, symmetric about half of the time.
pub fn stribeck() -> impl Strategy<Value = Stribeck> + Clone {
    (
        levels(),
        prop::option::of(levels()),
        log_uniform(1e-5, 1e-1),
        exponent(),
    )
        .prop_map(|((fc, ratio), negative, vs, delta)| {
            match negative {
                None => Stribeck::new(fc, fc * ratio, vs, delta),
                Some((fc_neg, ratio_neg)) => {
                    Stribeck::asymmetric(fc, fc * ratio, fc_neg, fc_neg * ratio_neg, vs, delta)
                }
            }
            .expect("the strategy only builds valid curves")
        })
}

/// A Stribeck curve that is always direction-dependent.
pub fn asymmetric_stribeck() -> impl Strategy<Value = Stribeck> + Clone {
    (levels(), levels(), log_uniform(1e-5, 1e-1), exponent()).prop_map(
        |((fc, ratio), (fc_neg, ratio_neg), vs, delta)| {
            Stribeck::asymmetric(fc, fc * ratio, fc_neg, fc_neg * ratio_neg, vs, delta)
                .expect("the strategy only builds valid curves")
        },
    )
}

/// g(v) as docs/model.md#stribeck-curve writes it, Fc + (Fs − Fc)·exp(−|v/Vs|^δ) with the `_neg` levels for
/// v < 0, computed here from the curve's parameters: an oracle independent of `Stribeck::g`.
pub fn stribeck_level(curve: &Stribeck, v: f64) -> f64 {
    let (fc, fs) = if v < 0.0 {
        (curve.fc_neg(), curve.fs_neg())
    } else {
        (curve.fc(), curve.fs())
    };
    fc + (fs - fc) * (-(v / curve.vs()).abs().powf(curve.delta())).exp()
}

/// Saturation forces proportional to `weights`, scaled so that they add up to `strength` times
/// `peak` (`strength` > 1 keeps `sum(W) > max(Fs, Fs_neg)`).
pub fn saturation_forces<const N: usize>(weights: [f64; N], peak: f64, strength: f64) -> [f64; N] {
    let total: f64 = weights.iter().sum();
    weights.map(|weight| weight * strength * peak / total)
}

/// Random valid modified-Leuven parameters with `N` elements whose break deflections span
/// 0.1 µm to 100 µm, with a viscous coefficient of its own for v < 0 about half of the time.
pub fn leuven<const N: usize>() -> impl Strategy<Value = LeuvenParams<N>> + Clone {
    (
        stribeck(),
        exponent(),
        coefficient(),
        (coefficient(), prop::option::of(coefficient())),
        uniform::<_, N>(0.05..1.0),
        uniform::<_, N>(log_uniform(1e-7, 1e-4)),
        1.05..5.0,
    )
        .prop_map(
            |(stribeck, n, sigma1, (sigma2, sigma2_neg), weights, delta, strength)| {
                let w = saturation_forces(weights, stribeck.peak(), strength);
                let elements = MaxwellSlip::new(w, delta).expect("valid elements");
                let params =
                    Params::new(stribeck, n, sigma1, sigma2, elements).expect("valid parameters");
                match sigma2_neg {
                    Some(sigma2_neg) => params.with_sigma2_neg(sigma2_neg).expect("valid"),
                    None => params,
                }
            },
        )
}

/// A velocity sequence made of segments that exercise every regime of the model: plateaus,
/// ramps through zero (reversals), runs of exact zeros (both signs of zero) and noise, with
/// magnitudes from 1 µm/s (deep presliding) to 1 m/s (gross sliding).
pub fn velocities() -> impl Strategy<Value = Vec<f64>> + Clone {
    let magnitude = || log_uniform(1e-6, 1.0);
    let segment = prop_oneof![
        (signed(magnitude()), 1..40usize).prop_map(|(v, len)| vec![v; len]),
        (any::<bool>(), 1..20usize).prop_map(|(negative, len)| vec![
            if negative {
                -0.0
            } else {
                0.0
            };
            len
        ]),
        (signed(magnitude()), magnitude(), 2..40usize).prop_map(|(from, to, len)| {
            // From `from` to a velocity of the other sign: a reversal in the middle.
            let to = -to.copysign(from);
            (0..len)
                .map(|k| from + (to - from) * k as f64 / (len - 1) as f64)
                .collect()
        }),
        prop::collection::vec(signed(magnitude()), 1..20),
    ];
    prop::collection::vec(segment, 1..8).prop_map(|segments| segments.concat())
}

/// Runs `velocities` through `state` step by step, stopping quietly at an explicit divergence
/// (whose state is left as it was): the result is a state the model can really be in.
pub fn reach<H: Hysteresis>(
    params: &Params<H>,
    state: &mut State<H::Memory>,
    velocities: &[f64],
    dt: f64,
    scheme: Scheme,
) {
    for &v in velocities {
        match params.step(state, v, dt, scheme) {
            Ok(_) => {}
            Err(Error::Diverged { .. }) => break,
            Err(other) => panic!("valid input rejected: {other}"),
        }
    }
}

/// Both schemes, for properties that hold for either.
pub fn scheme() -> impl Strategy<Value = Scheme> + Clone {
    prop_oneof![Just(Scheme::Implicit), Just(Scheme::Explicit)]
}
