//! The derivatives against central finite differences of gms-core's own runs, on random
//! parameter sets, wherever no element changes between sticking and slipping between the two
//! runs of a difference: the implicit scheme, and the explicit one where it is stable;
//! n = 1, 1.5, 2, 3; N = 1, 3, 10, 20 and a linear spring; velocity and position input;
//! symmetric and asymmetric levels; signals with reversals, dwells at v = 0 and presliding loops.
//! The forces must equal gms-core's bit for bit.

mod common;

use common::{as_input, config, model, run, signal, ways_differ, Model};
use gms_core::Scheme;
use gms_dyn::Input;
use gms_fit::{column_count, sensitivities, Simulation};
use proptest::prelude::*;

/// How far the derivatives may be from the differences, relative to the largest derivative of
/// the column over the run.
const TOLERANCE: f64 = 1e-6;

/// The step of a difference, relative to the parameter.
const STEP: f64 = 1e-6;

/// On top of [`TOLERANCE`], a difference is no more accurate than the forces it divides by 2h:
/// gms-core rounds z⁺ to an ulp of |z|, which moves Fh by up to its stiffness K times that, and
/// rounds the sum F to an ulp of |F|. The difference's error from rounding is therefore at most
/// a few ε·(max|F| + K·max|z|)/h; this many of them are allowed.
const ROUNDING: f64 = 8.0;

/// The columns of `sigma2` and `sigma2_neg`, which are also checked exactly.
const SIGMA2: usize = 6;
const SIGMA2_NEG: usize = 9;

/// Which case a failure message names.
struct Case<'a> {
    model: &'a Model,
    simulation: Simulation<'a>,
}

/// Checks every column of the Jacobian against central differences; returns how many columns
/// were compared (a column whose ± runs went different ways somewhere is not).
fn check(case: &Case<'_>) -> Result<usize, TestCaseError> {
    let Case { model, simulation } = case;
    let set = model.set(None);
    let samples = simulation.signal.len();
    let columns = column_count(set.kind());
    prop_assert_eq!(columns, model.columns());
    let rows: Vec<usize> = (0..samples).collect();
    let (mut force, mut jacobian) = (vec![0.0; samples], vec![0.0; samples * columns]);
    sensitivities(&set, *simulation, &rows, &mut force, &mut jacobian)
        .map_err(|error| TestCaseError::fail(error.to_string()))?;
    let base = run(&set, &model.delta, simulation);
    for (k, (got, expected)) in force.iter().zip(&base.force).enumerate() {
        prop_assert_eq!(got.to_bits(), expected.to_bits(), "force at sample {}", k);
    }
    let column =
        |j: usize| -> Vec<f64> { jacobian.iter().skip(j).step_by(columns).copied().collect() };
    // The viscous columns, exactly: v·[v ≥ 0] and v·[v < 0] with v the step's velocity.
    let velocity = velocities(simulation);
    for (k, &v) in velocity.iter().enumerate() {
        prop_assert_eq!(column(SIGMA2)[k], if v < 0.0 { 0.0 } else { v });
        prop_assert_eq!(column(SIGMA2_NEG)[k], if v < 0.0 { v } else { 0.0 });
    }
    let mut compared = 0;
    for j in 0..columns {
        let derivative = column(j);
        let h = STEP * model.values[j].abs();
        let moved = |sign: f64| {
            let mut perturbed = Model::clone(model);
            perturbed.values[j] += sign * h;
            run(&perturbed.set(None), &model.delta, simulation)
        };
        let (plus, minus) = (moved(1.0), moved(-1.0));
        if ways_differ(&plus.ways, &minus.ways) || ways_differ(&plus.ways, &base.ways) {
            continue;
        }
        let largest = derivative.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
        let scale = base.force.iter().fold(0.0_f64, |a, b| a.max(b.abs()))
            + model.stiffness() * base.largest_z;
        let allowed = TOLERANCE * largest + ROUNDING * f64::EPSILON * scale / h;
        for (k, &d) in derivative.iter().enumerate() {
            let difference = (plus.force[k] - minus.force[k]) / (2.0 * h);
            prop_assert!(
                (d - difference).abs() <= allowed,
                "column {} at sample {}: {:e} against the difference {:e} (largest {:e}, allowed {:e}), {:?} {:?}",
                j, k, d, difference, largest, allowed, simulation.scheme, simulation.input
            );
        }
        compared += 1;
    }
    Ok(compared)
}

/// The velocity of every step, as gms-core computes it from the input.
fn velocities(simulation: &Simulation<'_>) -> Vec<f64> {
    match simulation.input {
        Input::Velocity => simulation.signal.to_vec(),
        Input::Position => {
            let mut previous: Option<f64> = None;
            simulation
                .signal
                .iter()
                .map(|&x| {
                    let v = previous.map_or(0.0, |p| (x - p) / simulation.dt);
                    previous = Some(x);
                    v
                })
                .collect()
        }
    }
}

/// A model, a signal for it and the input kind, for `elements` elements (0: linear spring).
fn cases(
    elements: usize,
    n: f64,
    scheme: Scheme,
) -> impl Strategy<Value = (Model, Vec<f64>, f64, Input)> {
    (any::<bool>(), log_uniform_dt())
        .prop_flat_map(move |(symmetric, dt)| {
            model(elements, n, symmetric).prop_flat_map(move |model| {
                let width = model.delta.iter().copied().fold(1e-5, f64::max);
                let vs = model.values[2];
                (
                    Just(model),
                    signal(vs, width, dt),
                    Just(dt),
                    prop_oneof![Just(Input::Velocity), Just(Input::Position)],
                )
            })
        })
        .prop_map(move |(model, velocity, dt, input)| match scheme {
            Scheme::Implicit => (model, velocity, dt, input),
            Scheme::Explicit => explicit_stable(model, &velocity, dt, input),
        })
}

fn log_uniform_dt() -> impl Strategy<Value = f64> {
    common::log_uniform(1e-4, 1e-3)
}

/// The same motion on a step fine enough for forward Euler: dt·|v|·(stiffness)/g ≤ 0.5 at every
/// sample, each sample repeated on the finer grid.
fn explicit_stable(
    model: Model,
    velocity: &[f64],
    dt: f64,
    input: Input,
) -> (Model, Vec<f64>, f64, Input) {
    let own = &model.values[10..];
    let stiffness: f64 = if model.linear() {
        own[0]
    } else {
        own.iter().zip(&model.delta).map(|(w, d)| w / d).sum()
    };
    let lowest = model.values[0].min(model.values[7]);
    let fastest = velocity.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let number = dt * fastest * stiffness / lowest;
    // At most 8 times finer: a model that needs more is drawn again (an empty signal).
    let repeats = (1..=8_u32)
        .find(|&m| number / f64::from(m) <= 0.5)
        .unwrap_or(0);
    let velocity = velocity
        .iter()
        .flat_map(|&v| core::iter::repeat_n(v, repeats as usize))
        .collect();
    (model, velocity, dt / f64::from(repeats.max(1)), input)
}

fn property(
    elements: usize,
    n: f64,
    scheme: Scheme,
) -> impl Fn((Model, Vec<f64>, f64, Input)) -> Result<(), TestCaseError> {
    move |(model, velocity, dt, input)| {
        prop_assume!(!velocity.is_empty(), "no explicit step fine enough");
        let signal = as_input(&velocity, dt, input);
        let simulation = Simulation {
            signal: &signal,
            input,
            dt,
            scheme,
        };
        let compared = check(&Case {
            model: &model,
            simulation,
        })?;
        // Most columns must be comparable, or the property says little.
        prop_assert!(
            compared * 2 >= model.columns(),
            "only {} of {} columns kept their ways under ±h (N = {}, n = {})",
            compared,
            model.columns(),
            elements,
            n
        );
        Ok(())
    }
}

macro_rules! properties {
    ($($name:ident: $elements:expr, $n:expr, $scheme:expr, $cases:expr;)*) => {$(
        proptest! {
            #![proptest_config(config($cases))]
            #[test]
            fn $name(case in cases($elements, $n, $scheme)) {
                property($elements, $n, $scheme)(case)?;
            }
        }
    )*};
}

properties! {
    implicit_n1_one_element: 1, 1.0, Scheme::Implicit, 12;
    implicit_n2_three_elements: 3, 2.0, Scheme::Implicit, 12;
    implicit_n1_5_ten_elements: 10, 1.5, Scheme::Implicit, 8;
    implicit_n3_twenty_elements: 20, 3.0, Scheme::Implicit, 6;
    implicit_n1_twenty_elements: 20, 1.0, Scheme::Implicit, 4;
    implicit_n2_linear_spring: 0, 2.0, Scheme::Implicit, 8;
    implicit_n1_linear_spring: 0, 1.0, Scheme::Implicit, 8;
    explicit_n1_one_element: 1, 1.0, Scheme::Explicit, 8;
    explicit_n2_three_elements: 3, 2.0, Scheme::Explicit, 8;
    explicit_n1_5_ten_elements: 10, 1.5, Scheme::Explicit, 4;
    explicit_n3_three_elements: 3, 3.0, Scheme::Explicit, 6;
    explicit_n1_linear_spring: 0, 1.0, Scheme::Explicit, 6;
}
