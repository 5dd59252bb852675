//! Experiment (the "one model" issue, stage b): gms-core's single-channel step against the lane
//! kernel of this crate run at one lane (L = 1), the step written over lanes with `f64` as a
//! one-lane value. Per tick (one sample a call, as a compensator runs) and per block
//! (T = 10 000 samples a call), the same 5 Hz sine as gms-core's step bench. The two give the
//! same forces bit for bit (tests/agree.rs, `one_lane_is_gms_core`). The numbers and what they
//! decided: docs/benchmarks.md#one-step-for-lanes-and-channels.
//!
//! Run with `cargo bench -p gms-batch --bench one_lane`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use gms_batch::{run_one_lane, BatchHysteresis, Path};
use gms_core::{Linear, MaxwellSlip, Params, Scheme, Stribeck};

const DT: f64 = 1e-3;
const SAMPLES: usize = 10_000;

fn velocity() -> Vec<f64> {
    (0..SAMPLES)
        .map(|k| 0.01 * (std::f64::consts::TAU * 5.0 * k as f64 * DT).sin())
        .collect()
}

fn stribeck() -> Stribeck {
    Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve")
}

fn maxwell<const N: usize>(n: f64) -> Params<MaxwellSlip<N>> {
    let w = [2.0 / N as f64; N];
    let delta = core::array::from_fn(|i| 1e-5 * (i + 1) as f64 / N as f64);
    Params::new(
        stribeck(),
        n,
        30.0,
        0.4,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap()
}

fn lugre() -> Params<Linear> {
    Params::new(stribeck(), 1.0, 316.0, 0.4, Linear::new(1e5).unwrap()).unwrap()
}

fn case<H: BatchHysteresis>(c: &mut Criterion, label: &str, params: &Params<H>) {
    let v = velocity();
    let kernel = params.hysteresis().kernel();
    let mut out = vec![0.0; SAMPLES];
    for (name, scheme) in [
        ("implicit", Scheme::Implicit),
        ("explicit", Scheme::Explicit),
    ] {
        let mut group = c.benchmark_group(format!("one_lane/{label}/{name}"));
        group.bench_function(BenchmarkId::new("tick", "core"), |b| {
            let mut state = params.relaxed_state();
            let mut k = 0;
            b.iter(|| {
                k = if k + 1 == 1000 { 0 } else { k + 1 };
                black_box(params.step(&mut state, black_box(v[k]), DT, scheme))
            });
        });
        for &path in Path::available() {
            group.bench_function(BenchmarkId::new("tick", path.name()), |b| {
                let mut state = params.relaxed_state();
                let mut k = 0;
                let mut force = [0.0];
                b.iter(|| {
                    k = if k + 1 == 1000 { 0 } else { k + 1 };
                    let stepped = run_one_lane(
                        path,
                        params,
                        &kernel,
                        &mut state,
                        black_box(&v[k..=k]),
                        DT,
                        scheme,
                        &mut force,
                    );
                    black_box((stepped, force[0]))
                });
            });
        }
        group.bench_function(BenchmarkId::new("block", "core"), |b| {
            b.iter(|| {
                let mut state = params.relaxed_state();
                params
                    .simulate(&mut state, &v, DT, scheme, &mut out)
                    .unwrap();
                black_box(&out);
            });
        });
        for &path in Path::available() {
            group.bench_function(BenchmarkId::new("block", path.name()), |b| {
                b.iter(|| {
                    let mut state = params.relaxed_state();
                    assert!(run_one_lane(
                        path, params, &kernel, &mut state, &v, DT, scheme, &mut out
                    ));
                    black_box(&out);
                });
            });
        }
        group.finish();
    }
}

fn benches(c: &mut Criterion) {
    case(c, "N=1 LuGre", &lugre());
    case(c, "N=10", &maxwell::<10>(2.0));
    case(c, "N=32", &maxwell::<32>(2.0));
    case(c, "N=10 n=1.5", &maxwell::<10>(1.5));
}

criterion_group! {
    name = group;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2)).sample_size(30);
    targets = benches
}
criterion_main!(group);
