//! One thread, B = 256 channels × T = 10 000 samples: gms-core's per-channel block call in a
//! loop against the batch kernel (baseline and detected instruction-set paths), for the
//! benchmark parameters of benches/bench.py (N = 10, n = 2) and a LuGre spring, both schemes,
//! each on bench.py's input (the same sine in every channel) and on a different sine per channel.
//! Throughput is in element-updates (B·T·N; B·T for LuGre).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use gms_batch::{run_on, BatchHysteresis, Path, Signal};
use gms_core::{Linear, MaxwellSlip, Params, Scheme, Stribeck};

const CHANNELS: usize = 256;
const SAMPLES: usize = 10_000;
const DT: f64 = 1e-3;

/// The input of every channel.
#[derive(Clone, Copy)]
enum Input {
    /// benches/bench.py's input: v = 0.01·sin(2π·5·t), the same in every channel.
    Same,
    /// A different sine per channel (amplitude, frequency and phase vary), so that the lanes
    /// of a group take different sides of every data-dependent choice, as real batches do.
    Varied,
}

fn input(kind: Input) -> Vec<f64> {
    match kind {
        Input::Same => {
            let row: Vec<f64> = (0..SAMPLES)
                .map(|k| 0.01 * (std::f64::consts::TAU * 5.0 * k as f64 * DT).sin())
                .collect();
            row.repeat(CHANNELS)
        }
        Input::Varied => (0..CHANNELS)
            .flat_map(|c| {
                let c = c as f64;
                let amplitude = 0.005 + 0.015 * ((c * 0.618_034) % 1.0);
                let frequency = 2.0 + 6.0 * ((c * 0.414_214) % 1.0);
                let phase = std::f64::consts::TAU * ((c * 0.732_051) % 1.0);
                (0..SAMPLES).map(move |k| {
                    amplitude * (std::f64::consts::TAU * frequency * k as f64 * DT + phase).sin()
                })
            })
            .collect(),
    }
}

fn bench_case<H: BatchHysteresis + Copy>(
    c: &mut Criterion,
    name: &str,
    params: &Params<H>,
    elements: usize,
    kind: Input,
) {
    let v = input(kind);
    let mut out = vec![0.0; v.len()];
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.throughput(Throughput::Elements((CHANNELS * SAMPLES * elements) as u64));
    for scheme in [Scheme::Implicit, Scheme::Explicit] {
        let label = |what: &str| format!("{scheme:?}/{what}").to_lowercase();
        group.bench_function(label("scalar"), |b| {
            b.iter(|| {
                let mut states = [params.relaxed_state(); CHANNELS];
                for (state, (v, out)) in states
                    .iter_mut()
                    .zip(v.chunks(SAMPLES).zip(out.chunks_mut(SAMPLES)))
                {
                    params.simulate(state, v, DT, scheme, out).unwrap();
                }
                black_box(&out);
            });
        });
        for &path in Path::available() {
            group.bench_function(label(path.name()), |b| {
                b.iter(|| {
                    let mut states = vec![params.relaxed_state(); CHANNELS];
                    let error = run_on(
                        path,
                        params,
                        &mut states,
                        &v,
                        SAMPLES,
                        DT,
                        scheme,
                        Signal::Velocity,
                        &mut out,
                    );
                    assert!(error.is_none());
                    black_box(&out);
                });
            });
        }
    }
    group.finish();
}

fn batch(c: &mut Criterion) {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let w = [0.2; 10];
    let delta = core::array::from_fn(|i| 1e-6 * (i + 1) as f64);
    let maxwell = Params::new(
        stribeck,
        2.0,
        30.0,
        0.4,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap();
    bench_case(c, "maxwell10", &maxwell, 10, Input::Same);
    bench_case(c, "maxwell10_varied", &maxwell, 10, Input::Varied);
    let lugre = Params::new(stribeck, 1.0, 30.0, 0.4, Linear::new(1e5).unwrap()).unwrap();
    bench_case(c, "lugre", &lugre, 1, Input::Same);
    bench_case(c, "lugre_varied", &lugre, 1, Input::Varied);
}

criterion_group!(benches, batch);
criterion_main!(benches);
