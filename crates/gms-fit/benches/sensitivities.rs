//! One run with its sensitivities against one plain run, and many parameter sets along one signal.
//!
//! `run`: T = 30 000 samples (a 1 kHz, 5 Hz sine of 10 mm/s: reversals, presliding and sliding)
//! through N = 10 and 20 elements (P = 10 + N columns): gms-core's `Params::simulate`, then
//! `gms_fit::sensitivities` with the Jacobian at every row, at every 10th row, and at none. The
//! case `presliding` is what a fit of a presliding log runs: N = 20 with a fitted n = 2.15 (no
//! class: `pow`) along a 1 Hz sine of 12 µm with a 7 Hz one of 4 µm on it, within the bank's
//! widest element for most of the cycle.
//!
//! `sets`: 8 parameter sets of N = 10 along the same signal: `gms_fit::simulate_sets` (one set
//! per thread), the 8 sets one after the other through gms-core, and, for comparison, one set on
//! 8 channels through gms-dyn's bank, which steps them in gms-batch's SIMD lanes (lanes share one
//! parameter set). Run with `RAYON_NUM_THREADS=1` to compare the work on one thread.
//!
//! Run with `cargo bench -p gms-fit --bench sensitivities`.

use core::hint::black_box;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use gms_core::{MaxwellSlip, Params, Scheme, Stribeck};
use gms_dyn::{FrictionBank, Input, ParameterSet};
use gms_fit::{column_count, sensitivities, simulate_sets, Simulation};

const DT: f64 = 1e-3;
const SAMPLES: usize = 30_000;

fn velocity() -> Vec<f64> {
    (0..SAMPLES)
        .map(|k| 0.01 * (2.0 * core::f64::consts::PI * 5.0 * k as f64 * DT).sin())
        .collect()
}

/// Velocities of x = 12 µm·sin(2π·1 Hz·t) + 4 µm·sin(2π·7 Hz·t).
fn presliding() -> Vec<f64> {
    let tau = 2.0 * core::f64::consts::PI;
    (0..SAMPLES)
        .map(|k| {
            let t = k as f64 * DT;
            12e-6 * tau * (tau * t).cos() + 4e-6 * 7.0 * tau * (7.0 * tau * t).cos()
        })
        .collect()
}

/// gms-core's bench model: N equal weights adding up to 2 N, break deflections up to 10 µm;
/// `scale` varies the weights from set to set.
fn maxwell<const N: usize>(scale: f64) -> Params<MaxwellSlip<N>> {
    maxwell_n(scale, 2.0)
}

/// [`maxwell`] with transition exponent `n`.
fn maxwell_n<const N: usize>(scale: f64, n: f64) -> Params<MaxwellSlip<N>> {
    let w = core::array::from_fn(|i| scale * 2.0 / N as f64 * (1.0 + 0.01 * i as f64));
    let delta = core::array::from_fn(|i| 1e-5 * (i + 1) as f64 / N as f64);
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let elements = MaxwellSlip::new(w, delta).expect("valid elements");
    Params::new(stribeck, n, 30.0, 0.4, elements).expect("valid parameters")
}

fn run<const N: usize>(c: &mut Criterion, case: &str, signal: &[f64], n: f64)
where
    ParameterSet: From<Params<MaxwellSlip<N>>>,
{
    let params = maxwell_n::<N>(1.0, n);
    let set = ParameterSet::from(params);
    let simulation = Simulation {
        signal,
        input: Input::Velocity,
        dt: DT,
        scheme: Scheme::Implicit,
    };
    let columns = column_count(set.kind());
    let label = format!("{case} N={N} P={columns}");
    let mut group = c.benchmark_group("run");
    group.sample_size(20);
    let mut force = vec![0.0; SAMPLES];
    group.bench_function(BenchmarkId::new("simulate", &label), |b| {
        b.iter(|| {
            let mut state = params.relaxed_state();
            params
                .simulate(
                    &mut state,
                    black_box(signal),
                    DT,
                    Scheme::Implicit,
                    &mut force,
                )
                .expect("valid run");
            black_box(&force);
        });
    });
    for (name, stride) in [("every row", 1), ("every 10th row", 10), ("no row", 0)] {
        let rows: Vec<usize> = if stride == 0 {
            Vec::new()
        } else {
            (0..SAMPLES).step_by(stride).collect()
        };
        let mut jacobian = vec![0.0; rows.len() * columns];
        group.bench_function(
            BenchmarkId::new(format!("sensitivities, {name}"), &label),
            |b| {
                b.iter(|| {
                    sensitivities(
                        &set,
                        black_box(simulation),
                        &rows,
                        &mut force,
                        &mut jacobian,
                    )
                    .expect("valid run");
                    black_box(&jacobian);
                });
            },
        );
    }
    group.finish();
}

fn sets(c: &mut Criterion) {
    const SETS: usize = 8;
    let params: Vec<_> = (0..SETS)
        .map(|b| maxwell::<10>(1.0 + 0.05 * b as f64))
        .collect();
    let sets: Vec<ParameterSet> = params.iter().copied().map(ParameterSet::from).collect();
    let signal = velocity();
    let simulation = Simulation {
        signal: &signal,
        input: Input::Velocity,
        dt: DT,
        scheme: Scheme::Implicit,
    };
    let mut forces = vec![0.0; SETS * SAMPLES];
    let mut group = c.benchmark_group("sets");
    group.sample_size(10);
    group.bench_function("8 sets N=10, simulate_sets", |b| {
        b.iter(|| {
            simulate_sets(&sets, black_box(simulation), &mut forces).expect("valid runs");
            black_box(&forces);
        });
    });
    group.bench_function("8 sets N=10, one after the other", |b| {
        b.iter(|| {
            for (params, out) in params.iter().zip(forces.chunks_mut(SAMPLES)) {
                let mut state = params.relaxed_state();
                params
                    .simulate(&mut state, black_box(&signal), DT, Scheme::Implicit, out)
                    .expect("valid run");
            }
            black_box(&forces);
        });
    });
    let signals: Vec<f64> = (0..SETS).flat_map(|_| signal.iter().copied()).collect();
    let mut bank = FrictionBank::new(&sets[0], SETS, Scheme::Implicit).expect("8 channels");
    group.bench_function("1 set N=10 on 8 channels, gms-batch lanes", |b| {
        b.iter(|| {
            bank.reset();
            bank.run(black_box(&signals), DT, Input::Velocity, &mut forces)
                .expect("valid run");
            black_box(&forces);
        });
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    let (sine, small) = (velocity(), presliding());
    run::<10>(c, "sine", &sine, 2.0);
    run::<20>(c, "sine", &sine, 2.0);
    run::<20>(c, "presliding", &small, 2.15);
    sets(c);
}

criterion_group!(group, benches);
criterion_main!(group);
