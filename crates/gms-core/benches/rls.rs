//! Nanoseconds per online-identification update, N = 10 elements (13 parameters).
//!
//! Each iteration is one `OnlineIdentifier::update` (regressor, gain, covariance, guards) on a
//! 1 kHz log of a sine with reversals of several amplitudes and a force from the linear model
//! plus a small deterministic disturbance, so the estimate keeps moving. Forgetting 0.999, so
//! the trace bound is exercised too. Run with `cargo bench -p gms-core --bench rls`.

use core::hint::black_box;
use criterion::{criterion_group, criterion_main, Criterion};
use gms_core::{OnlineIdentifier, Rls, RlsSettings};

const N: usize = 10;
const P: usize = N + 3;
const SAMPLES: usize = 4000;

/// (x, v, f) of a 1 kHz log: 2 Hz motion whose amplitude sweeps from 1 µm to 40 µm.
fn log() -> Vec<(f64, f64, f64)> {
    let dt = 1e-3;
    let omega = 2.0 * core::f64::consts::PI * 2.0;
    (0..SAMPLES)
        .map(|k| {
            let t = k as f64 * dt;
            let amplitude = 1e-6 + 4e-5 * (k as f64 / SAMPLES as f64);
            let x = amplitude * (omega * t).sin();
            let v = amplitude * omega * (omega * t).cos();
            let f = 0.8 * (x / 2e-5).clamp(-1.0, 1.0) + 0.3 * v.signum() + 50.0 * v + 0.01;
            (x, v, f + 1e-3 * (k as f64 * 0.7).sin())
        })
        .collect()
}

fn update(c: &mut Criterion) {
    let delta: [f64; N] = core::array::from_fn(|i| 4e-6 * (i + 1) as f64);
    let settings = RlsSettings {
        forgetting: 0.999,
        initial_covariance: 1e3,
        max_trace: 1e5,
    };
    let log = log();
    c.bench_function("rls/update N=10", |b| {
        let mut identifier =
            OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings).expect("valid settings");
        let mut k = 0;
        b.iter(|| {
            k = if k + 1 == log.len() { 0 } else { k + 1 };
            let (x, v, f) = log[k];
            black_box(identifier.update(black_box(x), black_box(v), black_box(f)))
        });
    });
}

/// The least-squares part alone (regressors prepared beforehand), to split the cost.
fn least_squares(c: &mut Criterion) {
    let delta: [f64; N] = core::array::from_fn(|i| 4e-6 * (i + 1) as f64);
    let settings = RlsSettings {
        forgetting: 0.999,
        initial_covariance: 1e3,
        max_trace: 1e5,
    };
    let mut identifier =
        OnlineIdentifier::<N, P>::new(delta, [0.0; P], settings).expect("valid settings");
    let rows: Vec<([f64; P], f64)> = log()
        .into_iter()
        .map(|(x, v, f)| {
            let row = identifier.regressor(x, v).expect("finite input");
            identifier.update(x, v, f).expect("finite input");
            (row, f)
        })
        .collect();
    c.bench_function("rls/Rls::update P=13 (least squares only)", |b| {
        let mut rls = Rls::<P>::new([0.0; P], settings).expect("valid settings");
        let mut k = 0;
        b.iter(|| {
            k = if k + 1 == rows.len() { 0 } else { k + 1 };
            let (row, f) = &rows[k];
            black_box(rls.update(black_box(row), black_box(*f)))
        });
    });
}

criterion_group!(benches, update, least_squares);
criterion_main!(benches);
