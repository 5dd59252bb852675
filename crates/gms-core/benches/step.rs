//! Nanoseconds per single-channel step, for N = 1 (LuGre), 4, 10, 32 and both schemes, and for
//! N = 10 at transition exponents other than n = 2: 1.5 (half-integer), 3 and 4 (integer) and
//! 0.7 (general, through `pow`), which take different paths through the power and the solver.
//!
//! Each iteration is one `step` call on one channel, fed from a 1 kHz, 5 Hz sine of 10 mm/s
//! amplitude (reversals, presliding and sliding alike), so the figure is the average over a cycle.
//! Run with `cargo bench -p gms-core --bench step`.

use core::hint::black_box;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use gms_core::{Hysteresis, Linear, LuGreParams, MaxwellSlip, Params, Scheme, Stribeck};

const DT: f64 = 1e-3;

fn velocity() -> Vec<f64> {
    (0..1000)
        .map(|k| 0.01 * (2.0 * core::f64::consts::PI * 5.0 * f64::from(k) * DT).sin())
        .collect()
}

fn stribeck() -> Stribeck {
    Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve")
}

fn maxwell<const N: usize>(n: f64) -> Params<MaxwellSlip<N>> {
    let mut w = [0.0; N];
    let mut delta = [0.0; N];
    for i in 0..N {
        w[i] = 2.0 / N as f64;
        delta[i] = 1e-5 * (i + 1) as f64 / N as f64;
    }
    let elements = MaxwellSlip::new(w, delta).expect("valid elements");
    Params::new(stribeck(), n, 30.0, 0.4, elements).expect("valid parameters")
}

fn lugre() -> LuGreParams {
    let spring = Linear::new(1e5).expect("valid stiffness");
    Params::new(stribeck(), 1.0, 316.0, 0.4, spring).expect("valid parameters")
}

fn bench_params<H: Hysteresis>(c: &mut Criterion, label: &str, params: &Params<H>) {
    let velocity = velocity();
    let mut group = c.benchmark_group("step");
    for (name, scheme) in [
        ("implicit", Scheme::Implicit),
        ("explicit", Scheme::Explicit),
    ] {
        group.bench_with_input(BenchmarkId::new(name, label), &scheme, |b, &scheme| {
            let mut state = params.relaxed_state();
            let mut k = 0;
            b.iter(|| {
                k = if k + 1 == velocity.len() { 0 } else { k + 1 };
                black_box(params.step(&mut state, black_box(velocity[k]), DT, scheme))
            });
        });
    }
    group.finish();
}

fn steps(c: &mut Criterion) {
    bench_params(c, "N=1 LuGre", &lugre());
    bench_params(c, "N=4", &maxwell::<4>(2.0));
    bench_params(c, "N=10", &maxwell::<10>(2.0));
    bench_params(c, "N=32", &maxwell::<32>(2.0));
    bench_params(c, "N=10 n=1.5", &maxwell::<10>(1.5));
    bench_params(c, "N=10 n=3", &maxwell::<10>(3.0));
    bench_params(c, "N=10 n=4", &maxwell::<10>(4.0));
    bench_params(c, "N=10 n=0.7", &maxwell::<10>(0.7));
}

criterion_group!(benches, steps);
criterion_main!(benches);
