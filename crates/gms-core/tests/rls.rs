//! Online identification: recursive least squares and the slip regressor.
//!
//! - On noiseless data from the linear-in-parameters model, the estimate reaches the true
//!   parameters; on noisy data it equals the (exponentially weighted) ridge batch solution.
//! - The covariance stays symmetric positive definite and below its trace bound through long
//!   runs without excitation, where the plain covariance update is known to go wrong.
//! - A covariance that leaves its range is reset; a rejected input leaves the state untouched.

mod common;

use gms_core::{Error, Field, Hysteresis, MaxwellSlip, OnlineIdentifier, Rls, RlsSettings};
use nalgebra::{Cholesky, SMatrix, SVector};
use proptest::prelude::*;

const N: usize = 4;
const P: usize = N + 3;
const DT: f64 = 1e-3;

/// A 5 Hz oscillation at 1 kHz whose amplitude sweeps geometrically from 0.3·Δ₀ to 100·Δ_{N−1}
/// over `samples`: reversals inside every element's range and beyond all of them, so every
/// weight and the Coulomb step are informed. Returns (x, v).
fn excitation(delta: &[f64; N], samples: usize) -> (Vec<f64>, Vec<f64>) {
    let omega = 2.0 * core::f64::consts::PI * 5.0;
    let (low, high) = (0.3 * delta[0], 100.0 * delta[N - 1]);
    let growth = (high / low).ln() / samples as f64;
    (0..samples)
        .map(|k| {
            let t = k as f64 * DT;
            let amplitude = low * (growth * k as f64).exp();
            let x = amplitude * (omega * t).sin();
            let v = amplitude * (growth / DT * (omega * t).sin() + omega * (omega * t).cos());
            (x, v)
        })
        .unzip()
}

/// The linear model's force, with the hysteresis from the model's own Maxwell-slip bank
/// (an independent path from the regressor): Σ Wᵢψᵢ + Fc·sgn(v) + sigma2·v + offset.
fn linear_model_force(delta: &[f64; N], truth: &[f64; P], x: &[f64], v: &[f64]) -> Vec<f64> {
    let mut w = [0.0; N];
    w.copy_from_slice(&truth[..N]);
    let bank = MaxwellSlip::new(w, *delta).expect("valid elements");
    let mut zeta = [x[0]; N];
    x.iter()
        .zip(v)
        .map(|(&x, &v)| {
            let sign = if v > 0.0 {
                1.0
            } else if v < 0.0 {
                -1.0
            } else {
                0.0
            };
            bank.commit(&mut zeta, x) + truth[N] * sign + truth[N + 1] * v + truth[N + 2]
        })
        .collect()
}

fn settings(forgetting: f64, initial_covariance: f64) -> RlsSettings {
    RlsSettings {
        forgetting,
        initial_covariance,
        max_trace: 1e3 * P as f64 * initial_covariance,
    }
}

/// Deterministic noise in [−1, 1] (a linear congruential generator).
fn noise(samples: usize, mut seed: u64) -> Vec<f64> {
    (0..samples)
        .map(|_| {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            2.0 * ((seed >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        })
        .collect()
}

/// Every Dⱼ finite and > 0 (exactly: U·D·Uᵀ is positive definite), the formed covariance
/// symmetric with a Cholesky factor, and its trace within the bound.
fn assert_covariance_healthy<const Q: usize>(rls: &Rls<Q>) {
    let (_, scale) = rls.factors();
    assert!(
        scale.iter().all(|&d| d > 0.0 && d.is_finite()),
        "D = {scale:?}"
    );
    let covariance = rls.covariance();
    assert_eq!(covariance, covariance.transpose());
    assert!(Cholesky::new(covariance).is_some(), "P = {covariance}");
    let bound = rls.settings().max_trace;
    assert!(rls.covariance_trace() <= bound * (1.0 + 1e-12));
}

proptest! {
    #![proptest_config(common::config(16))]

    /// Noiseless data: after 4000 samples every parameter is within 1e-6 of the truth
    /// (relative to max(1, |value|)), for random weights, levels and element spacings.
    #[test]
    fn noiseless_data_give_the_exact_parameters(
        w in proptest::array::uniform4(0.05..1.0f64),
        coulomb in 0.0..1.0f64,
        sigma2 in 0.0..100.0f64,
        offset in -0.5..0.5f64,
        spacing in common::log_uniform(1e-7, 1e-5),
    ) {
        let delta: [f64; N] = core::array::from_fn(|i| spacing * (i + 1) as f64);
        let mut truth = [0.0; P];
        truth[..N].copy_from_slice(&w);
        truth[N..].copy_from_slice(&[coulomb, sigma2, offset]);
        let (x, v) = excitation(&delta, 4000);
        let f = linear_model_force(&delta, &truth, &x, &v);
        let mut identifier =
            OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(1.0, 1e12)).unwrap();
        for k in 0..x.len() {
            identifier.update(x[k], v[k], f[k]).unwrap();
        }
        for (estimate, truth) in identifier.estimate().iter().zip(truth) {
            prop_assert!((estimate - truth).abs() <= 1e-6 * truth.abs().max(1.0),
                "estimate {:?}, truth {:?}", identifier.estimate(), truth);
        }
        prop_assert_eq!(identifier.rls().covariance_resets(), 0);
    }

    /// Long runs of arbitrary motion (sliding plateaus, standstill, random walks, scales from
    /// nm/s to m/s) with forgetting: the covariance stays healthy and bounded at every step.
    #[test]
    fn covariance_stays_healthy_under_any_motion(
        forgetting in 0.9..=1.0f64,
        segments in proptest::collection::vec(
            (0..3u8, common::signed(common::log_uniform(1e-9, 1.0)), 10..400usize), 1..12),
    ) {
        let delta: [f64; N] = core::array::from_fn(|i| 2e-6 * (i + 1) as f64);
        let mut identifier =
            OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(forgetting, 1e4)).unwrap();
        let (mut x, mut k) = (0.0, 0u64);
        for (kind, speed, length) in segments {
            for _ in 0..length {
                k += 1;
                let v = match kind {
                    0 => speed,                                   // sliding plateau
                    1 => 0.0,                                     // standstill
                    _ => speed * ((k as f64) * 0.37).sin(),       // oscillation
                };
                x += v * DT;
                identifier.update(x, v, 0.5 * v.signum() + 3.0 * v).unwrap();
                let (_, scale) = identifier.rls().factors();
                prop_assert!(scale.iter().all(|&d| d > 0.0 && d.is_finite()));
                prop_assert!(identifier.rls().covariance_trace()
                    <= identifier.rls().settings().max_trace * (1.0 + 1e-12));
            }
        }
        assert_covariance_healthy(identifier.rls());
        prop_assert_eq!(identifier.rls().covariance_resets(), 0);
    }
}

/// The batch solution of Σₖ λ^(T−1−k)·(yₖ − φₖᵀθ)² + λ^T·|θ − θ₀|²/p₀, by Cholesky.
fn weighted_ridge(
    rows: &[[f64; P]],
    y: &[f64],
    forgetting: f64,
    initial_covariance: f64,
) -> SVector<f64, P> {
    let samples = i32::try_from(rows.len()).expect("a short log");
    let prior = forgetting.powi(samples) / initial_covariance;
    let mut normal = SMatrix::<f64, P, P>::from_diagonal_element(prior);
    let mut right = SVector::<f64, P>::zeros();
    for (k, (row, &y)) in rows.iter().zip(y).enumerate() {
        let weight = forgetting.powi(samples - 1 - i32::try_from(k).expect("a short log"));
        let phi = SVector::from(*row);
        normal += phi * phi.transpose() * weight;
        right += phi * (y * weight);
    }
    Cholesky::new(normal)
        .expect("positive definite")
        .solve(&right)
}

#[test]
fn recursive_estimate_equals_the_weighted_ridge_batch_solution() {
    let delta = [1e-6, 2e-6, 4e-6, 8e-6];
    let truth = [0.4, 0.3, 0.2, 0.1, 0.25, 30.0, 0.02];
    let (x, v) = excitation(&delta, 3000);
    let clean = linear_model_force(&delta, &truth, &x, &v);
    let f: Vec<f64> = clean
        .iter()
        .zip(noise(x.len(), 7))
        .map(|(f, e)| f + 0.01 * e)
        .collect();
    for forgetting in [1.0, 0.998] {
        let mut identifier =
            OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(forgetting, 1e2)).unwrap();
        let mut rows = Vec::new();
        for k in 0..x.len() {
            rows.push(identifier.regressor(x[k], v[k]).unwrap());
            identifier.update(x[k], v[k], f[k]).unwrap();
        }
        let batch = weighted_ridge(&rows, &f, forgetting, 1e2);
        for (recursive, batch) in identifier.estimate().iter().zip(batch.iter()) {
            assert!(
                (recursive - batch).abs() <= 1e-8 * batch.abs().max(1.0),
                "λ = {forgetting}: recursive {:?}, batch {batch}",
                identifier.estimate()
            );
        }
    }
}

/// The regressors of a long log replayed twice, nearly collinear (three columns that differ by
/// 1e-10), with an enormous prior (p₀ = 1e16) and no forgetting: the conditioning is about 1e36.
fn ill_conditioned_rows() -> Vec<([f64; 3], f64)> {
    noise(2000, 1)
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            let phi = [1.0, 1.0 + 1e-10 * r, 1.0 + 1e-10 * (k % 3) as f64];
            (phi, 1.0 + 1e-3 * r)
        })
        .collect()
}

#[test]
fn factored_update_keeps_positive_definiteness_where_the_plain_update_loses_it() {
    let settings = RlsSettings {
        forgetting: 1.0,
        initial_covariance: 1e16,
        max_trace: 3e16,
    };
    let rows = ill_conditioned_rows();

    // The textbook update P ← P − Pφ(Pφ)ᵀ/(1 + φᵀPφ), symmetrised, on the same data.
    let mut plain = SMatrix::<f64, 3, 3>::from_diagonal_element(1e16);
    let mut plain_lost = 0;
    for (phi, _) in &rows {
        let phi = SVector::from(*phi);
        let p_phi = plain * phi;
        let quadratic = phi.dot(&p_phi);
        if quadratic < 0.0 || plain.diagonal().iter().any(|&d| d <= 0.0) {
            plain_lost += 1;
        }
        plain -= p_phi * p_phi.transpose() / (1.0 + quadratic);
        plain = (plain + plain.transpose()) * 0.5;
    }
    assert!(
        plain_lost > 0 || Cholesky::new(plain).is_none(),
        "the plain update was expected to lose positive definiteness on this data"
    );

    let mut rls = Rls::<3>::new([0.0; 3], settings).unwrap();
    for (phi, y) in &rows {
        rls.update(phi, *y).unwrap();
        let (_, scale) = rls.factors();
        assert!(scale.iter().all(|&d| d > 0.0 && d.is_finite()));
    }
    assert_eq!(rls.covariance_resets(), 0);
    assert!(rls.estimate().iter().all(|value| value.is_finite()));
}

#[test]
fn covariance_leaving_its_range_is_reset_and_counted() {
    // λ = 1e-300 multiplies D by 1e300 per sample without excitation: the second update
    // overflows D, which must reset the covariance to p₀·I and keep the estimate.
    let settings = RlsSettings {
        forgetting: 1e-300,
        initial_covariance: 1.0,
        max_trace: 1e308,
    };
    let mut rls = Rls::<2>::new([0.5, -0.5], settings).unwrap();
    rls.update(&[0.0, 0.0], 0.0).unwrap();
    assert_eq!(rls.covariance_resets(), 0);
    assert_eq!(rls.factors().1.as_slice(), &[1.0 / 1e-300; 2]);
    rls.update(&[0.0, 0.0], 0.0).unwrap();
    assert_eq!(rls.covariance_resets(), 1);
    let (factor, scale) = rls.factors();
    assert_eq!(factor, &SMatrix::<f64, 2, 2>::identity());
    assert_eq!(scale.as_slice(), &[1.0, 1.0]);
    assert_eq!(rls.estimate(), [0.5, -0.5]);
    rls.reset();
    assert_eq!(rls.covariance_resets(), 0);
}

#[test]
fn covariance_stays_bounded_through_a_long_run_without_excitation() {
    // 100 000 samples alternating steady sliding (every ψ saturated: the regressor has rank one
    // per direction) and standstill, with forgetting 0.99: unexcited directions wind up at
    // 1/0.99 per sample and would reach 1e400 without the bound.
    let delta: [f64; N] = core::array::from_fn(|i| 2e-6 * (i + 1) as f64);
    let mut identifier =
        OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(0.99, 1e3)).unwrap();
    let mut x = 0.0;
    let (mut bound_reached, mut largest_late_error) = (false, 0.0f64);
    for k in 0..100_000usize {
        let v = match (k / 5000) % 3 {
            0 => 0.01,
            1 => 0.0,
            _ => -0.01,
        };
        x += v * DT;
        let force = if v == 0.0 {
            0.0
        } else {
            0.8 * v.signum() + 5.0 * v
        };
        let error = identifier.update(x, v, force).unwrap();
        if k >= 90_000 {
            largest_late_error = largest_late_error.max(error.abs());
        }
        bound_reached |=
            identifier.rls().covariance_trace() > 0.999 * identifier.rls().settings().max_trace;
        if k % 1000 == 0 {
            assert_covariance_healthy(identifier.rls());
        }
    }
    assert!(
        bound_reached,
        "the run was meant to press against the trace bound"
    );
    assert_eq!(identifier.rls().covariance_resets(), 0);
    // What the data determine (the force in each of the three regimes) is predicted.
    assert!(largest_late_error < 1e-9, "{largest_late_error}");
}

#[test]
fn rejected_input_leaves_everything_untouched() {
    let delta = [1e-6, 2e-6, 4e-6, 8e-6];
    let mut identifier =
        OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(0.999, 1e3)).unwrap();
    for k in 0..50 {
        let x = 3e-6 * (f64::from(k) * 0.3).sin();
        identifier.update(x, 1e-3, 0.5).unwrap();
    }
    let before = identifier;
    for (x, v, f, field) in [
        (f64::NAN, 0.0, 0.0, Field::x),
        (0.0, f64::INFINITY, 0.0, Field::v),
        (0.0, 0.0, f64::NEG_INFINITY, Field::f),
    ] {
        assert_eq!(
            identifier.update(x, v, f),
            Err(Error::NotFinite {
                field,
                index: 0,
                value: [x, v, f][[Field::x, Field::v, Field::f]
                    .iter()
                    .position(|&named| named == field)
                    .unwrap()]
            })
        );
        assert_eq!(identifier, before);
    }
    // Finite but absurd: 1e300 m/s in the viscous column overflows φᵀPφ.
    assert_eq!(
        identifier.update(0.0, 1e300, 1.0),
        Err(Error::InputsOverflow {
            index: 0,
            x: 0.0,
            v: 1e300,
            f: 1.0
        })
    );
    assert_eq!(identifier, before);

    // Block runs are all or nothing, and name the sample.
    let x = [0.0, 1e-6, 2e-6, 3e-6];
    let mut out = [[0.0; P]; 4];
    let v = [1e-3, 1e-3, f64::NAN, 1e-3];
    assert_eq!(
        identifier.run(&x, &v, &[0.5; 4], &mut out),
        Err(Error::NotFinite {
            field: Field::v,
            index: 2,
            value: f64::NAN
        })
    );
    assert_eq!(
        identifier.run(&x, &[1e-3, 1e-3, 1e300, 1e-3], &[0.5; 4], &mut out),
        Err(Error::InputsOverflow {
            index: 2,
            x: 2e-6,
            v: 1e300,
            f: 0.5
        })
    );
    assert_eq!(identifier, before);
    assert_eq!(
        identifier.run(&x, &[1e-3; 3], &[0.5; 4], &mut out),
        Err(Error::InputLengthMismatch {
            field: Field::v,
            expected: 4,
            got: 3
        })
    );
    assert_eq!(
        identifier.run(&x, &[1e-3; 4], &[0.5; 4], &mut out[..2]),
        Err(Error::LengthMismatch {
            expected: 4,
            got: 2
        })
    );
    assert_eq!(identifier, before);
}

#[test]
fn block_run_equals_sample_by_sample_updates() {
    let delta = [1e-6, 2e-6, 4e-6, 8e-6];
    let truth = [0.4, 0.3, 0.2, 0.1, 0.25, 30.0, 0.02];
    let (x, v) = excitation(&delta, 500);
    let f = linear_model_force(&delta, &truth, &x, &v);
    let start = OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings(0.995, 1e3)).unwrap();
    let mut stepped = start;
    let mut estimates = vec![[0.0; P]; x.len()];
    for k in 0..x.len() {
        stepped.update(x[k], v[k], f[k]).unwrap();
        estimates[k] = stepped.estimate();
    }
    let mut blocked = start;
    let mut out = vec![[0.0; P]; x.len()];
    blocked.run(&x, &v, &f, &mut out).unwrap();
    assert_eq!(out, estimates);
    assert_eq!(blocked, stepped);
    blocked.reset();
    assert_eq!(blocked, start);
}

#[test]
fn construction_rules() {
    let good = settings(0.99, 1e3);
    assert_eq!(
        OnlineIdentifier::<N, P>::new([1e-6, 0.0, 1e-6, 1e-6], [0.0; P], good),
        Err(Error::Element {
            field: Field::Delta,
            index: 1,
            value: 0.0
        })
    );
    assert_eq!(
        OnlineIdentifier::<N, P>::new(
            [1e-6; N],
            [0.0; P],
            RlsSettings {
                max_trace: 1.0,
                ..good
            }
        ),
        Err(Error::TraceBelowInitial {
            parameters: P,
            initial_covariance: 1e3,
            max_trace: 1.0
        })
    );
    assert_eq!(
        Error::NotInUnitInterval {
            field: Field::forgetting,
            value: 1.5
        }
        .to_string(),
        "`forgetting` must be in (0, 1], got 1.5"
    );
}
