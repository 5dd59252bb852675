//! Nanoseconds per step of one long channel through the block calls, the rows of
//! `benches/peers.py`'s one-channel table without Python around them: LuGre implicit on
//! velocities (`simulate`) and on positions (`simulate_position`), and the modified Leuven model
//! (N = 10, n = 2, implicit) on positions with a position-dependent level
//! (`simulate_position_level`), with and without the level, and the level's factor alone.
//!
//! The parameters, the level and the motion are those of `benches/peers.py`: a 1 kHz, 5 Hz
//! sine of 10 mm/s amplitude, T = 100 000 samples per call (criterion reports the time of one
//! call; divide by T). Run with `cargo bench -p gms-core --bench channel`.

use core::hint::black_box;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use gms_core::{
    Level, Linear, LuGreParams, MaxwellSlip, Params, PositionForce, RippleTerms, Scheme, Stribeck,
};

const DT: f64 = 1e-3;
const SAMPLES: usize = 100_000;

fn velocity() -> Vec<f64> {
    (0..SAMPLES)
        .map(|k| 0.01 * (core::f64::consts::TAU * 5.0 * k as f64 * DT).sin())
        .collect()
}

fn position(velocity: &[f64]) -> Vec<f64> {
    velocity
        .iter()
        .scan(0.0, |x, v| {
            *x += v * DT;
            Some(*x)
        })
        .collect()
}

fn stribeck() -> Stribeck {
    Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve")
}

fn lugre() -> LuGreParams {
    let spring = Linear::new(1e5).expect("valid stiffness");
    Params::new(stribeck(), 1.0, 316.0, 0.4, spring).expect("valid parameters")
}

fn leuven() -> Params<MaxwellSlip<10>> {
    let w = [0.2; 10];
    let delta: [f64; 10] = core::array::from_fn(|i| 1e-6 * (i + 1) as f64);
    let elements = MaxwellSlip::new(w, delta).expect("valid elements");
    Params::new(stribeck(), 2.0, 30.0, 0.4, elements).expect("valid parameters")
}

/// A trend of ±10 % over the stroke and the ripple of a 1 mm screw pitch.
fn level() -> Level {
    Level::new(
        0.0,
        2e-3,
        [0.1, 0.05],
        &[RippleTerms {
            period: 1e-3,
            cos: &[0.05],
            sin: &[0.02],
        }],
    )
    .expect("valid level")
}

fn channel(c: &mut Criterion) {
    let v = velocity();
    let x = position(&v);
    let mut out = vec![0.0; SAMPLES];
    let mut group = c.benchmark_group("channel");
    group.throughput(Throughput::Elements(SAMPLES as u64));
    group.sample_size(30);

    let lugre = lugre();
    group.bench_function("LuGre implicit velocity", |b| {
        b.iter(|| {
            let mut state = lugre.relaxed_state();
            lugre.simulate(&mut state, black_box(&v), DT, Scheme::Implicit, &mut out)
        });
    });
    group.bench_function("LuGre implicit position", |b| {
        b.iter(|| {
            let mut state = lugre.relaxed_state();
            lugre.simulate_position(&mut state, black_box(&x), DT, Scheme::Implicit, &mut out)
        });
    });

    let leuven = leuven();
    let level = level();
    let none = PositionForce::none();
    group.bench_function("Leuven N=10 implicit position level", |b| {
        b.iter(|| {
            let mut state = leuven.relaxed_state();
            leuven.simulate_position_level(
                &mut state,
                black_box(&x),
                DT,
                Scheme::Implicit,
                &level,
                &none,
                &mut out,
            )
        });
    });
    group.bench_function("Leuven N=10 implicit position", |b| {
        b.iter(|| {
            let mut state = leuven.relaxed_state();
            leuven.simulate_position(&mut state, black_box(&x), DT, Scheme::Implicit, &mut out)
        });
    });
    group.bench_function("level factor", |b| {
        b.iter(|| {
            for (out, &x) in out.iter_mut().zip(black_box(&x)) {
                *out = level.factor(x);
            }
        });
    });
    group.finish();
}

criterion_group!(benches, channel);
criterion_main!(benches);
