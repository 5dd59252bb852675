//! The batch kernel against gms-core's per-channel block calls: the same forces and states (to
//! 1e-12 relative; in practice bit for bit) and the same errors, on both instruction-set paths.

use gms_batch::{run_on, BatchHysteresis, Path, Signal, LANES};
use gms_core::{
    Error, Hysteresis, Level, Linear, MaxwellSlip, Params, PositionForce, RippleTerms, Scheme,
    State, Stribeck, MIN_DELTA_RATIO,
};
use proptest::prelude::*;

/// The agreement required. Setting the environment variable `GMS_BATCH_BITWISE` asks for bit
/// for bit instead (what the kernel gives in practice).
const TOLERANCE: f64 = 1e-12;

fn close(a: f64, b: f64) -> bool {
    if a.to_bits() == b.to_bits() {
        return true;
    }
    let difference = (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
    difference <= TOLERANCE && std::env::var_os("GMS_BATCH_BITWISE").is_none()
}

/// Every channel through gms-core, first failing channel reported: what gms-dyn did before.
#[allow(clippy::too_many_arguments)]
fn scalar<H: BatchHysteresis>(
    params: &Params<H>,
    states: &mut [State<H::Memory>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    out: &mut [f64],
) -> Option<(usize, Error)> {
    states
        .iter_mut()
        .zip(input.chunks(samples).zip(out.chunks_mut(samples)))
        .enumerate()
        .find_map(|(channel, (state, (input, out)))| {
            let rows = channel * samples..(channel + 1) * samples;
            let result = match signal {
                Signal::Velocity => params.simulate(state, input, dt, scheme, out),
                Signal::VelocityAt { x, level, force } => {
                    params.simulate_level(state, input, &x[rows], dt, scheme, level, force, out)
                }
                Signal::Position { level, force } => {
                    params.simulate_position_level(state, input, dt, scheme, level, force, out)
                }
            };
            result.err().map(|error| (channel, error))
        })
}

/// Runs the same batch through gms-core and the kernel (each path) and compares everything.
#[allow(clippy::too_many_arguments)]
fn compare<H, M>(
    params: &Params<H>,
    start: &[State<M>],
    input: &[f64],
    samples: usize,
    dt: f64,
    scheme: Scheme,
    signal: Signal<'_>,
    memory: impl Fn(&M) -> Vec<f64>,
) -> Result<(), TestCaseError>
where
    H: BatchHysteresis<Memory = M>,
    M: Copy + std::fmt::Debug + PartialEq,
{
    let mut expected_states = start.to_vec();
    let mut expected = vec![0.0; input.len()];
    let expected_error = scalar(
        params,
        &mut expected_states,
        input,
        samples,
        dt,
        scheme,
        signal,
        &mut expected,
    );
    for &path in Path::available() {
        let mut states = start.to_vec();
        let mut out = vec![0.0; input.len()];
        let error = run_on(
            path,
            params,
            &mut states,
            input,
            samples,
            dt,
            scheme,
            signal,
            &mut out,
        );
        prop_assert_eq!(error, expected_error, "{:?}", path);
        // Channels before the failing one have run; the failing one is as it was; the others
        // are the caller's to restore.
        let compared = error.map_or(states.len(), |(channel, _)| channel + 1);
        let rows = error.map_or(states.len(), |(channel, _)| channel);
        for channel in 0..compared {
            let (ours, theirs) = (&states[channel], &expected_states[channel]);
            prop_assert!(close(ours.z, theirs.z), "{path:?} z {ours:?} {theirs:?}");
            prop_assert_eq!(ours.last_position.is_some(), theirs.last_position.is_some());
            if let (Some(a), Some(b)) = (ours.last_position, theirs.last_position) {
                prop_assert!(close(a, b));
            }
            for (a, b) in memory(&ours.memory).iter().zip(memory(&theirs.memory)) {
                prop_assert!(close(*a, b), "{path:?} channel {channel} zeta {a:e} {b:e}");
            }
        }
        for (index, (a, b)) in out[..rows * samples]
            .iter()
            .zip(&expected[..rows * samples])
            .enumerate()
        {
            prop_assert!(
                close(*a, *b),
                "{path:?} channel {} sample {}: {a:e} vs {b:e}",
                index / samples,
                index % samples
            );
        }
        if let Some((channel, _)) = error {
            prop_assert_eq!(&states[channel], &start[channel]);
        }
    }
    Ok(())
}

/// A Stribeck curve, symmetric or not, and the transition exponent.
#[derive(Clone, Debug)]
struct Curve {
    fc: f64,
    fs: f64,
    fc_neg: f64,
    fs_neg: f64,
    vs: f64,
    delta: f64,
    n: f64,
    sigma1: f64,
    sigma2: f64,
    sigma2_neg: Option<f64>,
}

impl Curve {
    fn params<H: Hysteresis>(&self, hysteresis: H) -> Params<H> {
        let params = Params::new(
            self.stribeck(),
            self.n,
            self.sigma1,
            self.sigma2,
            hysteresis,
        )
        .unwrap();
        match self.sigma2_neg {
            Some(sigma2_neg) => params.with_sigma2_neg(sigma2_neg).unwrap(),
            None => params,
        }
    }
    fn stribeck(&self) -> Stribeck {
        Stribeck::asymmetric(
            self.fc,
            self.fs,
            self.fc_neg,
            self.fs_neg,
            self.vs,
            self.delta,
        )
        .unwrap()
    }
    fn peak(&self) -> f64 {
        self.fs.max(self.fs_neg)
    }
}

#[allow(clippy::similar_names)] // the paper's pairs: fc and fs, fc_neg and fs_neg
fn curve() -> impl Strategy<Value = Curve> {
    (
        (
            0.2..2.0f64,
            1.0..2.0f64,
            prop::bool::ANY,
            0.3..1.5f64,
            1.0..3.0f64,
        ),
        (
            -4.0..-2.0f64,
            prop::sample::select(vec![1.0, 2.0, 0.7, 1.5]),
        ),
        prop::sample::select(vec![1.0, 2.0, 1.5, 3.0, 0.8]),
        (0.0..100.0f64, 0.0..2.0f64, prop::option::of(0.0..2.0f64)),
    )
        .prop_map(
            |(
                (fc, ratio, asymmetric, scale, ratio_neg),
                (vs, delta),
                n,
                (sigma1, sigma2, sigma2_neg),
            )| {
                let (fc_neg, fs_neg) = if asymmetric {
                    (fc * scale, fc * scale * ratio_neg)
                } else {
                    (fc, fc * ratio)
                };
                Curve {
                    fc,
                    fs: fc * ratio,
                    fc_neg,
                    fs_neg,
                    vs: 10f64.powf(vs),
                    delta,
                    n,
                    sigma1,
                    sigma2,
                    sigma2_neg,
                }
            },
        )
}

/// Elements: W summing to 1.05–3 × the peak, Δ spread over 1e-7–1e-4.
fn elements<const N: usize>(peak: f64) -> impl Strategy<Value = MaxwellSlip<N>> {
    (
        prop::array::uniform(0.1..1.0f64),
        prop::array::uniform(-7.0..-4.0f64),
        1.05..3.0f64,
    )
        .prop_map(move |(w, delta, margin): ([f64; N], [f64; N], f64)| {
            let sum: f64 = w.iter().sum();
            let w = w.map(|w| w / sum * peak * margin);
            let delta = delta.map(|e| 10f64.powf(e));
            assert!(delta.iter().all(|&d| d >= MIN_DELTA_RATIO * 1e-4));
            MaxwellSlip::new(w, delta).unwrap()
        })
}

/// B rows of T velocities: a few sines with random phases plus noise, scaled around Vs, with
/// reversals, stops and (sometimes) exact zeros.
fn velocities(vs: f64) -> impl Strategy<Value = (usize, usize, Vec<f64>)> {
    (1usize..=11, 1usize..=120).prop_flat_map(move |(channels, samples)| {
        (
            Just(channels),
            Just(samples),
            prop::collection::vec(
                (
                    -2.0..2.5f64,
                    0.01..0.3f64,
                    0.0..6.3f64,
                    prop::collection::vec(-1.0..1.0f64, samples),
                    prop::bool::weighted(0.2),
                ),
                channels,
            ),
        )
            .prop_map(move |(channels, samples, rows)| {
                let mut input = Vec::with_capacity(channels * samples);
                for (scale, frequency, phase, noise, stops) in rows {
                    let amplitude = vs * 10f64.powf(scale);
                    for (k, e) in noise.iter().enumerate() {
                        let t = k as f64;
                        let v = amplitude
                            * ((frequency * t + phase).sin() + 0.3 * (3.1 * frequency * t).sin())
                            + 0.2 * amplitude * e;
                        input.push(if stops && k % 7 < 2 { 0.0 } else { v });
                    }
                }
                (channels, samples, input)
            })
    })
}

/// Positions from velocities: the running sum times dt, from a random start.
fn positions(velocities: &[f64], samples: usize, dt: f64, start: f64) -> Vec<f64> {
    let mut x = Vec::with_capacity(velocities.len());
    for row in velocities.chunks(samples) {
        let mut position = start;
        for v in row {
            position += v * dt;
            x.push(position);
        }
    }
    x
}

fn scheme() -> impl Strategy<Value = Scheme> {
    prop::sample::select(vec![Scheme::Implicit, Scheme::Explicit])
}

fn dt() -> impl Strategy<Value = f64> {
    prop::sample::select(vec![1e-3, 1e-4, 2.5e-5])
}

/// Non-relaxed starting states: each channel run through a random warm-up by gms-core.
fn warmed<H: BatchHysteresis>(
    params: &Params<H>,
    channels: usize,
    warmup: &[f64],
    dt: f64,
) -> Vec<State<H::Memory>> {
    (0..channels)
        .map(|channel| {
            let mut state = params.relaxed_state();
            let mut out = vec![0.0; warmup.len()];
            let take = (channel * 7) % (warmup.len() + 1);
            // An explicit warm-up may diverge; the relaxed state is then the start.
            let _ = params.simulate(
                &mut state,
                &warmup[..take],
                dt,
                Scheme::Implicit,
                &mut out[..take],
            );
            state
        })
        .collect()
}

fn maxwell_case<const N: usize>() -> impl Strategy<Value = (Curve, MaxwellSlip<N>)> {
    curve().prop_flat_map(|curve| {
        let peak = curve.peak();
        (Just(curve), elements::<N>(peak))
    })
}

/// A level and a position force, each with a trend and a ripple.
fn terms() -> (Level, PositionForce) {
    let ripple = RippleTerms {
        period: 1e-3,
        cos: &[0.1, 0.02],
        sin: &[0.05, 0.0],
    };
    let level = Level::new(0.0, 1e-2, [0.1, -0.05], &[ripple]).unwrap();
    let cogging = RippleTerms {
        period: 7e-4,
        cos: &[0.4],
        sin: &[-0.3],
    };
    let force = PositionForce::new(1e-3, 5e-3, [0.7, 0.2], &[cogging]).unwrap();
    (level, force)
}

macro_rules! maxwell_tests {
    ($($name:ident: $n:expr, $cases:expr;)*) => {$(
        proptest! {
            #![proptest_config(ProptestConfig::with_cases($cases))]
            #[test]
            fn $name(
                ((curve, bank), (channels, samples, v), scheme, dt, start) in maxwell_case::<$n>()
                    .prop_flat_map(|(curve, bank)| {
                        let vs = curve.vs;
                        ((Just(curve), Just(bank)), velocities(vs), scheme(), dt(), -1e-3..1e-3f64)
                    })
            ) {
                let params = curve.params(bank);
                let states = warmed(&params, channels, &v[..samples], dt);
                let memory = |m: &[f64; $n]| m.to_vec();
                compare(&params, &states, &v, samples, dt, scheme, Signal::Velocity, memory)?;
                let x = positions(&v, samples, dt, start);
                let (level, force) = terms();
                let none = (Level::none(), PositionForce::none());
                for (level, force) in [(&none.0, &none.1), (&level, &none.1), (&none.0, &force), (&level, &force)] {
                    let signal = Signal::Position { level, force };
                    compare(&params, &states, &x, samples, dt, scheme, signal, memory)?;
                    let signal = Signal::VelocityAt { x: &x, level, force };
                    compare(&params, &states, &v, samples, dt, scheme, signal, memory)?;
                }
            }
        }
    )*};
}

maxwell_tests! {
    maxwell_1: 1, 96;
    maxwell_3: 3, 96;
    maxwell_10: 10, 96;
    maxwell_32: 32, 48;
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]
    #[test]
    fn linear(
        (curve, sigma0, (channels, samples, v), scheme, dt) in curve().prop_flat_map(|curve| {
            let vs = curve.vs;
            (Just(curve), (2.0..8.0f64).prop_map(|e| 10f64.powf(e)), velocities(vs), scheme(), dt())
        })
    ) {
        let params = curve.params(Linear::new(sigma0).unwrap());
        let states = warmed(&params, channels, &v[..samples], dt);
        compare(&params, &states, &v, samples, dt, scheme, Signal::Velocity, |()| Vec::new())?;
        let x = positions(&v, samples, dt, 0.0);
        let (level, force) = terms();
        compare(&params, &states, &x, samples, dt, scheme,
            Signal::Position { level: &Level::none(), force: &PositionForce::none() }, |()| Vec::new())?;
        compare(&params, &states, &x, samples, dt, scheme,
            Signal::Position { level: &level, force: &force }, |()| Vec::new())?;
        compare(&params, &states, &v, samples, dt, scheme,
            Signal::VelocityAt { x: &x, level: &level, force: &force }, |()| Vec::new())?;
    }

    /// A non-finite sample anywhere: the same channel, sample and error as gms-core, on a
    /// channel inside a full group as well as in the leftover ones.
    #[test]
    fn non_finite_input_is_reported_as_gms_core_reports_it(
        channels in 1usize..=11,
        samples in 1usize..=40,
        bad in (0usize..11, 0usize..40, prop::sample::select(vec![f64::NAN, f64::INFINITY])),
        second in prop::option::of((0usize..11, 0usize..40)),
        signal in 0usize..3,
    ) {
        let params = standard::<4>();
        let mut v: Vec<f64> = (0..channels * samples).map(|k| 1e-3 * (k as f64 * 0.37).sin()).collect();
        let (channel, sample, value) = bad;
        v[(channel % channels) * samples + sample % samples] = value;
        if let Some((channel, sample)) = second {
            v[(channel % channels) * samples + sample % samples] = f64::NAN;
        }
        let states = vec![params.relaxed_state(); channels];
        let (level, force) = terms();
        // Finite positions beside the bad velocities, and the bad samples as positions.
        let x: Vec<f64> = (0..v.len()).map(|k| 1e-4 * k as f64).collect();
        let signal = match signal {
            0 => Signal::Velocity,
            1 => Signal::Position { level: &level, force: &force },
            _ => Signal::VelocityAt { x: &x, level: &level, force: &force },
        };
        compare(&params, &states, &v, samples, 1e-3, Scheme::Implicit, signal, |m: &[f64; 4]| m.to_vec())?;
        if let Signal::VelocityAt { .. } = signal {
            // The bad samples in the positions instead: refused naming `x`.
            let finite: Vec<f64> = v.iter().map(|v| if v.is_finite() { *v } else { 1e-3 }).collect();
            let signal = Signal::VelocityAt { x: &v, level: &level, force: &force };
            compare(&params, &states, &finite, samples, 1e-3, Scheme::Implicit, signal, |m: &[f64; 4]| m.to_vec())?;
        }
    }
}

fn standard<const N: usize>() -> Params<MaxwellSlip<N>> {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let w = [2.0 / N as f64; N];
    let delta = core::array::from_fn(|i| 1e-6 * (i + 1) as f64);
    Params::new(
        stribeck,
        2.0,
        30.0,
        0.4,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap()
}

#[test]
fn diverging_explicit_step_names_the_channel_and_sample() {
    // A stiff spring and a long step: forward Euler overshoots and grows without bound on the
    // channels driven fast enough (gms-core's tests/inputs.rs uses the same case).
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let params = Params::new(stribeck, 2.0, 10.0, 0.4, Linear::new(1e8).unwrap()).unwrap();
    let samples = 300;
    for fast in [0, 3, 5, 8] {
        let v: Vec<f64> = (0..9 * samples)
            .map(|k| {
                let (channel, t) = (k / samples, k % samples);
                // Later fast channels start later, so they diverge at a later sample.
                if channel >= fast && t >= 7 * channel {
                    0.5
                } else {
                    1e-9
                }
            })
            .collect();
        let states = vec![params.relaxed_state(); 9];
        let mut expected_states = states.clone();
        let mut expected = vec![0.0; v.len()];
        let expected_error = scalar(
            &params,
            &mut expected_states,
            &v,
            samples,
            5e-3,
            Scheme::Explicit,
            Signal::Velocity,
            &mut expected,
        );
        assert!(
            matches!(expected_error, Some((channel, Error::Diverged { .. })) if channel == fast),
            "{expected_error:?}"
        );
        compare(
            &params,
            &states,
            &v,
            samples,
            5e-3,
            Scheme::Explicit,
            Signal::Velocity,
            |()| Vec::new(),
        )
        .unwrap();
    }
}

#[test]
fn bad_dt_and_empty_rows_are_gms_core_errors() {
    let params = standard::<3>();
    for dt in [0.0, -1.0, f64::NAN, 1e-310] {
        let mut states = vec![params.relaxed_state(); 5];
        let mut out = vec![0.0; 10];
        let error = run_on(
            Path::detected(),
            &params,
            &mut states,
            &[1e-3; 10],
            2,
            dt,
            Scheme::Implicit,
            Signal::Velocity,
            &mut out,
        );
        assert_eq!(
            error,
            Some((
                0,
                params
                    .simulate(
                        &mut params.relaxed_state(),
                        &[],
                        dt,
                        Scheme::Implicit,
                        &mut []
                    )
                    .unwrap_err()
            ))
        );
    }
    let mut states = vec![params.relaxed_state(); 5];
    let error = run_on(
        Path::detected(),
        &params,
        &mut states,
        &[],
        0,
        1e-3,
        Scheme::Implicit,
        Signal::Position {
            level: &Level::none(),
            force: &PositionForce::none(),
        },
        &mut [],
    );
    assert_eq!(error, None);
    assert!(states.iter().all(|s| s.last_position.is_none()));
}

/// The standard benchmark case for many samples: bit for bit, on both paths.
#[test]
fn bit_for_bit_on_the_benchmark_case() {
    let params = standard::<10>();
    let (channels, samples) = (2 * LANES + 1, 5_000);
    let v: Vec<f64> = (0..channels * samples)
        .map(|k| {
            let (channel, t) = (k / samples, (k % samples) as f64 * 1e-3);
            0.01 * (std::f64::consts::TAU * 5.0 * t + channel as f64).sin()
        })
        .collect();
    for scheme in [Scheme::Implicit, Scheme::Explicit] {
        let mut expected_states = vec![params.relaxed_state(); channels];
        let mut expected = vec![0.0; v.len()];
        assert!(scalar(
            &params,
            &mut expected_states,
            &v,
            samples,
            1e-3,
            scheme,
            Signal::Velocity,
            &mut expected
        )
        .is_none());
        for &path in Path::available() {
            let mut states = vec![params.relaxed_state(); channels];
            let mut out = vec![0.0; v.len()];
            assert!(run_on(
                path,
                &params,
                &mut states,
                &v,
                samples,
                1e-3,
                scheme,
                Signal::Velocity,
                &mut out
            )
            .is_none());
            assert_eq!(states, expected_states, "{path:?} {scheme:?}");
            assert!(
                out.iter()
                    .zip(&expected)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "{path:?} {scheme:?}"
            );
        }
    }
}

/// No channels: whatever `samples` says (0 × anything is the empty input), nothing is stepped
/// and nothing overflows; the largest count once made LANES × samples wrap.
#[test]
fn no_channels_with_any_sample_count() {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let bank = MaxwellSlip::new([1.0, 1.0], [1e-6, 2e-6]).expect("valid bank");
    let params = Params::new(stribeck, 2.0, 30.0, 0.4, bank).expect("valid parameters");
    for &path in Path::available() {
        for samples in [0, 1, 7, usize::MAX] {
            let result = run_on(
                path,
                &params,
                &mut [],
                &[],
                samples,
                1e-3,
                Scheme::Implicit,
                Signal::Velocity,
                &mut [],
            );
            assert!(result.is_none(), "{samples} samples on {path:?}");
        }
    }
}

/// The kernel at one lane (`run_one_lane`, the experiment of `benches/one_lane.rs`): gms-core's
/// forces and states, bit for bit, a block at a time and a sample at a time, on both paths.
#[test]
fn one_lane_is_gms_core() {
    let stribeck = Stribeck::new(1.0, 1.5, 1e-3, 2.0).unwrap();
    let lugre = Params::new(stribeck, 1.0, 316.0, 0.4, Linear::new(1e5).unwrap()).unwrap();
    let v: Vec<f64> = (0..3_000u32)
        .map(|k| 0.01 * (std::f64::consts::TAU * 5.0 * f64::from(k) * 1e-3).sin())
        .collect();
    one_lane(&standard::<10>(), &v);
    one_lane(&standard::<3>(), &v);
    one_lane(&lugre, &v);
    // The other exponents' pieces: n = 1 in closed form, n = 1.5 by Newton's iteration.
    for n in [1.0, 1.5] {
        let bank = *standard::<10>().hysteresis();
        one_lane(&Params::new(stribeck, n, 30.0, 0.4, bank).unwrap(), &v);
    }
}

fn one_lane<H: BatchHysteresis>(params: &Params<H>, v: &[f64])
where
    H::Memory: PartialEq + core::fmt::Debug,
{
    let kernel = params.hysteresis().kernel();
    for scheme in [Scheme::Implicit, Scheme::Explicit] {
        let mut expected_state = params.relaxed_state();
        let mut expected = vec![0.0; v.len()];
        params
            .simulate(&mut expected_state, v, 1e-3, scheme, &mut expected)
            .unwrap();
        for &path in Path::available() {
            let mut block_state = params.relaxed_state();
            let mut block = vec![0.0; v.len()];
            assert!(gms_batch::run_one_lane(
                path,
                params,
                &kernel,
                &mut block_state,
                v,
                1e-3,
                scheme,
                &mut block
            ));
            let mut tick_state = params.relaxed_state();
            let mut ticks = vec![0.0; v.len()];
            for (v, out) in v.chunks(1).zip(ticks.chunks_mut(1)) {
                assert!(gms_batch::run_one_lane(
                    path,
                    params,
                    &kernel,
                    &mut tick_state,
                    v,
                    1e-3,
                    scheme,
                    out
                ));
            }
            assert_eq!(block_state, expected_state, "{path:?} {scheme:?}");
            assert_eq!(tick_state, expected_state, "{path:?} {scheme:?}");
            for (k, ((a, b), c)) in expected.iter().zip(&block).zip(&ticks).enumerate() {
                assert!(
                    a.to_bits() == b.to_bits() && a.to_bits() == c.to_bits(),
                    "{path:?} {scheme:?} sample {k}: {a} {b} {c}"
                );
            }
        }
    }
}

/// What the kernel does not step, `run_one_lane` hands back (false) with the state as it was:
/// no samples, a dt gms-core refuses, a non-finite input.
#[test]
fn one_lane_hands_back_what_it_does_not_step() {
    let params = standard::<3>();
    let kernel = params.hysteresis().kernel();
    let mut warmed = params.relaxed_state();
    let mut out = [0.0; 4];
    assert!(gms_batch::run_one_lane(
        Path::Baseline,
        &params,
        &kernel,
        &mut warmed,
        &[1e-3; 4],
        1e-3,
        Scheme::Implicit,
        &mut out
    ));
    let inputs: [(&[f64], f64); 6] = [
        (&[], 1e-3),
        (&[1e-3], 0.0),
        (&[1e-3], f64::NAN),
        (&[1e-3], f64::MIN_POSITIVE / 2.0),
        (&[1e-3], -1e-3),
        (&[1e-3, f64::NAN], 1e-3),
    ];
    for &path in Path::available() {
        for (input, dt) in inputs {
            let mut state = warmed;
            let mut out = vec![0.0; input.len()];
            let stepped = gms_batch::run_one_lane(
                path,
                &params,
                &kernel,
                &mut state,
                input,
                dt,
                Scheme::Implicit,
                &mut out,
            );
            assert!(!stepped, "{path:?}: {input:?} at dt {dt}");
            assert_eq!(state, warmed, "{path:?}: {input:?} at dt {dt}");
        }
    }
}
