//! Step latency of the compensator in Rust: `cargo run --release -p gms-ffi --example latency`.
//!
//! 10⁶ steps per mode with N = 10 elements, each step timed on its own with `Instant` (the
//! distribution's tail is the point: median, p99.9 and max). The input is the standard one of
//! the benchmarks: 1 kHz samples of v = 10 mm/s·sin(2π·5 Hz·t), so the solver sees sticking,
//! sliding and 10 reversals a second; the observer gets its integral as the position. An
//! untimed pass counts the implicit solver's evaluations of Fh per step against the bound
//! 2N + 1. The cost of reading the clock (timed empty intervals) is reported beside, not
//! subtracted; since it reads at 10 ns granularity on some machines, the median per step over
//! batches of 100 consecutive steps is reported too. `--json` prints one JSON object per mode instead of the table
//! (benches/latency.py reads it).

use std::hint::black_box;
use std::time::Instant;

use gms_core::{evaluation_bound, Compensator, LeuvenParams, MaxwellSlip, Mode, Params, Stribeck};

const STEPS: usize = 1_000_000;
const ELEMENTS: usize = 10;
const DT: f64 = 1e-3;
const BATCH: usize = 100;

fn params() -> LeuvenParams<ELEMENTS> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let delta = core::array::from_fn(|i| 1e-6 * (i + 1) as f64);
    let elements = MaxwellSlip::new([0.2; ELEMENTS], delta).expect("valid elements");
    Params::new(stribeck, 2.0, 30.0, 0.4, elements).expect("valid parameters")
}

/// The inputs of one mode: velocities, or their running sum times dt as positions.
fn inputs(mode: Mode) -> Vec<f64> {
    let velocity = |k: usize| 0.01 * (2.0 * std::f64::consts::PI * 5.0 * k as f64 * DT).sin();
    let mut x = 0.0;
    (0..STEPS)
        .map(|k| match mode {
            Mode::Feedforward => velocity(k),
            Mode::Observer => {
                x += velocity(k) * DT;
                x
            }
        })
        .collect()
}

/// The nanoseconds of every step, sorted.
fn time_steps(mode: Mode, inputs: &[f64]) -> Vec<f64> {
    let mut compensator = Compensator::new(params(), DT, mode).expect("valid dt");
    // Warm-up: caches, branch predictors, page faults of the output.
    for &input in &inputs[..10_000] {
        black_box(compensator.step(black_box(input)).ok());
    }
    compensator.reset();
    let mut times = vec![0.0; inputs.len()];
    for (time, &input) in times.iter_mut().zip(inputs) {
        let start = Instant::now();
        let force = compensator.step(black_box(input));
        let elapsed = start.elapsed();
        black_box(force.ok());
        *time = elapsed.as_nanos() as f64;
    }
    times.sort_by(f64::total_cmp);
    times
}

/// Median over batches of `BATCH` consecutive steps of the time per step: the clock reads at
/// 10 ns granularity on some machines, too coarse for a ~100 ns step timed alone.
fn batched_median(mode: Mode, inputs: &[f64]) -> f64 {
    let mut compensator = Compensator::new(params(), DT, mode).expect("valid dt");
    let mut averages: Vec<f64> = inputs
        .chunks(BATCH)
        .map(|chunk| {
            let start = Instant::now();
            for &input in chunk {
                black_box(compensator.step(black_box(input)).ok());
            }
            start.elapsed().as_nanos() as f64 / chunk.len() as f64
        })
        .collect();
    averages.sort_by(f64::total_cmp);
    averages[averages.len() / 2]
}

/// Median of `STEPS` timed empty intervals: what the clock itself adds to each step's time.
fn clock_overhead() -> f64 {
    let mut times: Vec<f64> = (0..STEPS / 10)
        .map(|_| {
            let start = Instant::now();
            black_box(start.elapsed()).as_nanos() as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// The most evaluations of Fh any step took (untimed pass over the same inputs).
fn most_evaluations(mode: Mode, inputs: &[f64]) -> u32 {
    let params = params();
    let mut compensator = Compensator::new(params, DT, mode).expect("valid dt");
    let mut most = 0;
    for &input in inputs {
        let state = compensator.state();
        let v = match (mode, state.last_position) {
            (Mode::Feedforward, _) => input,
            (Mode::Observer, Some(previous)) => (input - previous) / DT,
            (Mode::Observer, None) => 0.0,
        };
        most = most.max(params.solve_implicit(state, v, DT).iterations);
        compensator.step(input).expect("finite input");
    }
    most
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // an index in 0..len
    let index = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[index]
}

fn main() {
    let json = std::env::args().any(|argument| argument == "--json");
    let overhead = clock_overhead();
    if !json {
        println!("Rust, N = {ELEMENTS}, {STEPS} steps per mode, each timed with Instant");
        println!("(clock overhead, median of empty intervals: {overhead:.0} ns, included)\n");
        println!(
            "| mode | median | p99.9 | max | median, batches of {BATCH} | most Fh evaluations \
             | bound 2N + 1 |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|");
    }
    for (mode, name) in [
        (Mode::Feedforward, "feedforward"),
        (Mode::Observer, "observer"),
    ] {
        let inputs = inputs(mode);
        let times = time_steps(mode, &inputs);
        let evaluations = most_evaluations(mode, &inputs);
        let batched = batched_median(mode, &inputs);
        let (median, p999, max) = (
            quantile(&times, 0.5),
            quantile(&times, 0.999),
            times[times.len() - 1],
        );
        let bound = evaluation_bound(ELEMENTS);
        if json {
            println!(
                "{{\"language\": \"rust\", \"mode\": \"{name}\", \"steps\": {STEPS}, \
                 \"elements\": {ELEMENTS}, \"median_ns\": {median}, \"p999_ns\": {p999}, \
                 \"batched_median_ns\": {batched}, \
                 \"max_ns\": {max}, \"clock_overhead_ns\": {overhead}, \
                 \"most_evaluations\": {evaluations}, \"evaluation_bound\": {bound}}}"
            );
        } else {
            println!(
                "| {name} | {median:.0} ns | {p999:.0} ns | {max:.0} ns | {batched:.1} ns \
                 | {evaluations} | {bound} |"
            );
        }
    }
}
