//! Parameter sets and signals for the tests of gms-fit, and gms-core's runs stepped one sample at
//! a time to see which elements stick and which slip.
#![allow(dead_code)] // each test crate uses its own subset

use gms_core::Scheme;
use gms_dyn::{FrictionBank, Input, ParameterSet, RawElements, RawParams};
use gms_fit::Simulation;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

/// `cases` cases, failures saved beside the test file (as gms-core's tests do).
pub fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::with_cases(cases)
    }
}

/// Values spread evenly over the decades of `[lo, hi]`.
pub fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    (lo.ln()..=hi.ln()).prop_map(move |exponent| exponent.exp().clamp(lo, hi))
}

/// A parameter set as plain values: the asymmetric parameterisation, which is the columns' order
/// (`values[0..10]`: Fc, Fs, Vs, delta, n, sigma1, sigma2, `Fc_neg`, `Fs_neg`, `sigma2_neg`),
/// then the weights, and the break deflections apart (they are not fitted).
#[derive(Clone, Debug)]
pub struct Model {
    /// The values in column order; `None` for Maxwell slip's own columns means linear hysteresis
    /// is not used.
    pub values: Vec<f64>,
    /// Break deflections; empty for a linear spring (then `values[10]` is sigma0).
    pub delta: Vec<f64>,
}

impl Model {
    pub fn linear(&self) -> bool {
        self.delta.is_empty()
    }

    /// The validated set, with column `perturbed` moved by `h`.
    pub fn set(&self, perturbed: Option<(usize, f64)>) -> ParameterSet {
        let mut values = self.values.clone();
        if let Some((column, h)) = perturbed {
            values[column] += h;
        }
        let own = &values[10..];
        RawParams {
            fc: values[0],
            fs: values[1],
            vs: values[2],
            delta: values[3],
            n: values[4],
            sigma1: values[5],
            sigma2: values[6],
            fc_neg: values[7],
            fs_neg: values[8],
            sigma2_neg: Some(values[9]),
            sigma0: self.linear().then_some(own[0]),
            elements: (!self.linear()).then_some(RawElements {
                w: own,
                delta: &self.delta,
            }),
        }
        .validate()
        .expect("the strategies build valid sets")
    }

    pub fn columns(&self) -> usize {
        self.values.len()
    }

    /// The largest slope of Fh: σ0, or every element sticking, ΣWᵢ/Δᵢ.
    pub fn stiffness(&self) -> f64 {
        let own = &self.values[10..];
        if self.linear() {
            own[0]
        } else {
            own.iter().zip(&self.delta).map(|(w, d)| w / d).sum()
        }
    }
}

/// Random models: N elements (0 for a linear spring), transition exponent `n`, symmetric levels
/// (`Fc_neg` = Fc, `Fs_neg` = Fs, `sigma2_neg` = σ2) or not; σ1, σ2 and `sigma2_neg` > 0 so
/// that they can be moved both ways.
pub fn model(elements: usize, n: f64, symmetric: bool) -> impl Strategy<Value = Model> {
    (
        log_uniform(0.5, 2.0),
        1.1..2.0f64,
        log_uniform(0.5, 2.0),
        1.1..2.0f64,
        log_uniform(2e-3, 2e-2),
        prop_oneof![Just(2.0), 0.6..2.5f64],
        log_uniform(1.0, 100.0),
        log_uniform(0.05, 5.0),
        log_uniform(0.05, 5.0),
        prop::collection::vec(0.2..1.0f64, elements.max(1)),
        prop::collection::vec(log_uniform(1e-6, 1e-4), elements),
        1.3..3.0f64,
    )
        .prop_map(
            move |(
                fc,
                ratio,
                fc_neg,
                ratio_neg,
                vs,
                delta,
                sigma1,
                sigma2,
                sigma2_neg,
                weights,
                deltas,
                strength,
            )| {
                let (fc_neg, ratio_neg, sigma2_neg) = if symmetric {
                    (fc, ratio, sigma2)
                } else {
                    (fc_neg, ratio_neg, sigma2_neg)
                };
                let peak = (fc * ratio).max(fc_neg * ratio_neg);
                let total: f64 = weights.iter().sum();
                let own: Vec<f64> = if elements == 0 {
                    // A LuGre-like stiffness: Fs over a presliding range of 10 µm.
                    vec![peak / 1e-5]
                } else {
                    weights
                        .iter()
                        .map(|w| w * strength * peak / total)
                        .collect()
                };
                let mut values = vec![
                    fc,
                    fc * ratio,
                    vs,
                    delta,
                    n,
                    sigma1,
                    sigma2,
                    fc_neg,
                    fc_neg * ratio_neg,
                    sigma2_neg,
                ];
                values.extend(own);
                Model {
                    values,
                    delta: deltas,
                }
            },
        )
}

/// A velocity signal with every regime the derivatives must follow, relative to the model's
/// scales `vs` (Stribeck velocity) and `width` (the widest element): gross sliding both ways
/// through reversals, dwells at exactly v = 0, and presliding loops that stay within the
/// windows of the wider elements.
pub fn signal(vs: f64, width: f64, dt: f64) -> impl Strategy<Value = Vec<f64>> {
    let segment = prop_oneof![
        // Sliding: a sine of 0.3 to 5 Stribeck velocities, one or two reversals.
        (
            log_uniform(0.3, 5.0),
            40..120usize,
            1..3usize,
            any::<bool>()
        )
            .prop_map(move |(amplitude, half, halves, negative)| {
                let sign = if negative { -1.0 } else { 1.0 };
                (0..half * halves)
                    .map(|k| {
                        sign * amplitude
                            * vs
                            * (core::f64::consts::PI * k as f64 / half as f64).sin()
                    })
                    .collect::<Vec<_>>()
            }),
        // A dwell.
        (5..30usize).prop_map(|len| vec![0.0; len]),
        // Presliding: a few loops of 0.1 to 1 times the widest window.
        (log_uniform(0.1, 1.0), 20..60usize, 1..4usize).prop_map(
            move |(amplitude, period, loops)| {
                let omega = 2.0 * core::f64::consts::PI / period as f64;
                (0..period * loops)
                    .map(|k| amplitude * width * omega / dt * (omega * k as f64).cos() * 0.5)
                    .collect::<Vec<_>>()
            }
        ),
    ];
    prop::collection::vec(segment, 2..6).prop_map(|segments| segments.concat())
}

/// Which way an element goes on a step, by gms-core's rule with a rounding margin: an element
/// whose deflection is within a few ulps of its window's edge is `Edge`, which either side may
/// round to without changing the derivatives (it has just slipped, so its ζ moves with z).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Way {
    Stick,
    Slip,
    Edge,
}

/// Whether two runs took different ways anywhere (an `Edge` matches either way).
pub fn ways_differ(a: &[Way], b: &[Way]) -> bool {
    a.iter()
        .zip(b)
        .any(|pair| matches!(pair, (Way::Stick, Way::Slip) | (Way::Slip, Way::Stick)))
}

/// One run of gms-core stepped sample by sample (through gms-dyn): the forces, and for every
/// step and element the way it went at z⁺ and, for the explicit step, at z.
pub struct Run {
    pub force: Vec<f64>,
    pub ways: Vec<Way>,
    /// The largest |z| of the run.
    pub largest_z: f64,
}

pub fn run(set: &ParameterSet, delta: &[f64], simulation: &Simulation<'_>) -> Run {
    let mut bank = FrictionBank::new(set, 1, simulation.scheme).expect("one channel");
    let elements = delta.len();
    let (mut z, mut zeta, mut last, mut has_last) =
        (vec![0.0], vec![0.0; elements], vec![0.0], vec![false]);
    let mut force = Vec::with_capacity(simulation.signal.len());
    let mut ways = Vec::new();
    let mut largest_z = 0.0_f64;
    let way = |deviation: f64, limit: f64, z: f64| {
        let margin = 16.0 * f64::EPSILON * z.abs().max(limit);
        if deviation.abs() < limit - margin {
            Way::Stick
        } else if deviation.abs() > limit + margin {
            Way::Slip
        } else {
            Way::Edge
        }
    };
    for &sample in simulation.signal {
        bank.read_state(&mut z, &mut zeta, &mut last, &mut has_last);
        let (z_before, zeta_before) = (z[0], zeta.clone());
        force.push(
            bank.step(0, sample, simulation.dt, simulation.input)
                .expect("the tests run stable steps"),
        );
        bank.read_state(&mut z, &mut zeta, &mut last, &mut has_last);
        largest_z = largest_z.max(z[0].abs());
        for i in 0..elements {
            ways.push(way(z[0] - zeta_before[i], delta[i], z[0]));
            if simulation.scheme == Scheme::Explicit {
                ways.push(way(z_before - zeta_before[i], delta[i], z_before));
            }
        }
    }
    Run {
        force,
        ways,
        largest_z,
    }
}

/// The signal as the input kind wants it: velocities as they are, positions integrated from
/// them (from an offset, so that the first sample's v = 0 is a real step).
pub fn as_input(velocity: &[f64], dt: f64, input: Input) -> Vec<f64> {
    match input {
        Input::Velocity => velocity.to_vec(),
        Input::Position => velocity
            .iter()
            .scan(0.25, |x, v| {
                *x += v * dt;
                Some(*x)
            })
            .collect(),
    }
}
