//! The calls of gms-fit apart from the values of the derivatives: rows chosen out of the run,
//! many parameter sets at once, symmetric sets tied by adding columns, and every refusal.

mod common;

use gms_core::{Error as CoreError, Field, Scheme};
use gms_dyn::{
    ErrorClass, FrictionBank, Input, Location, Number, ParameterSet, RawElements, RawParams,
};
use gms_fit::{
    column_count, column_names, sensitivities, simulate_sets, Error, Output, Simulation,
};

const DT: f64 = 1e-3;

/// gms-core's bench model with the elements `w`, `delta`: the one literal of the raw values.
fn raw<'a>(w: &'a [f64], delta: &'a [f64]) -> RawParams<'a> {
    RawParams {
        fc: 1.0,
        fs: 1.5,
        vs: 1e-3,
        delta: 2.0,
        n: 2.0,
        sigma1: 30.0,
        sigma2: 0.4,
        fc_neg: 1.0,
        fs_neg: 1.5,
        sigma2_neg: None,
        sigma0: None,
        elements: Some(RawElements { w, delta }),
    }
}

fn maxwell(w: &[f64], delta: &[f64], fc_neg: f64) -> ParameterSet {
    RawParams {
        fc_neg,
        ..raw(w, delta)
    }
    .validate()
    .unwrap()
}

fn four_elements() -> ParameterSet {
    maxwell(&[0.5; 4], &[2e-6, 4e-6, 8e-6, 1.6e-5], 0.7)
}

fn lugre() -> ParameterSet {
    RawParams {
        sigma0: Some(1e5),
        elements: None,
        n: 1.0,
        sigma1: 316.0,
        ..raw(&[], &[])
    }
    .validate()
    .unwrap()
}

/// 5 Hz, 10 mm/s sine: reversals, presliding and sliding.
fn sine(samples: usize) -> Vec<f64> {
    (0..samples)
        .map(|k| 0.01 * (2.0 * core::f64::consts::PI * 5.0 * k as f64 * DT).sin())
        .collect()
}

fn simulation(signal: &[f64], input: Input, scheme: Scheme) -> Simulation<'_> {
    Simulation {
        signal,
        input,
        dt: DT,
        scheme,
    }
}

/// Force and Jacobian at `rows`.
fn run(set: &ParameterSet, simulation: Simulation<'_>, rows: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let columns = column_count(set.kind());
    let mut force = vec![0.0; simulation.signal.len()];
    let mut jacobian = vec![0.0; rows.len() * columns];
    sensitivities(set, simulation, rows, &mut force, &mut jacobian).unwrap();
    (force, jacobian)
}

/// gms-dyn's run of one channel: gms-core's `Params::simulate` (or `simulate_position`).
fn simulate(set: &ParameterSet, simulation: Simulation<'_>) -> Vec<f64> {
    let mut bank = FrictionBank::new(set, 1, simulation.scheme).unwrap();
    let mut out = vec![0.0; simulation.signal.len()];
    bank.run(simulation.signal, simulation.dt, simulation.input, &mut out)
        .unwrap();
    out
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|value| value.to_bits()).collect()
}

#[test]
fn chosen_rows_are_the_rows_of_the_whole_jacobian() {
    let signal = sine(600);
    for set in [four_elements(), lugre()] {
        for scheme in [Scheme::Implicit, Scheme::Explicit] {
            let simulation = simulation(&signal, Input::Velocity, scheme);
            let columns = column_count(set.kind());
            let every: Vec<usize> = (0..signal.len()).collect();
            let (force, whole) = run(&set, simulation, &every);
            let rows = [0, 1, 57, 58, 200, 599];
            let (force_rows, chosen) = run(&set, simulation, &rows);
            assert_eq!(bits(&force), bits(&force_rows));
            for (r, &row) in rows.iter().enumerate() {
                assert_eq!(
                    bits(&chosen[r * columns..(r + 1) * columns]),
                    bits(&whole[row * columns..(row + 1) * columns]),
                    "row {row}"
                );
            }
            let (force_none, none) = run(&set, simulation, &[]);
            assert!(none.is_empty());
            assert_eq!(bits(&force), bits(&force_none));
            assert_eq!(bits(&force), bits(&simulate(&set, simulation)));
        }
    }
}

#[test]
fn column_names_follow_the_kind() {
    let names = column_names(four_elements().kind());
    assert_eq!(names.len(), column_count(four_elements().kind()));
    assert_eq!(&names[..3], ["Fc", "Fs", "Vs"]);
    assert_eq!(names[9], "sigma2_neg");
    assert_eq!(names[13], "W[3]");
    assert_eq!(column_names(lugre().kind())[10], "sigma0");
}

/// A symmetric set is the asymmetric one with `Fc_neg` = Fc: moving the common Fc moves both,
/// so its derivative is the sum of the two columns.
#[test]
fn a_symmetric_level_is_the_sum_of_its_two_columns() {
    let signal = sine(400);
    let simulation = simulation(&signal, Input::Velocity, Scheme::Implicit);
    let w = [0.5; 4];
    let delta = [2e-6, 4e-6, 8e-6, 1.6e-5];
    let (_, jacobian) = run(
        &maxwell(&w, &delta, 1.0),
        simulation,
        &(0..400).collect::<Vec<_>>(),
    );
    let columns = column_count(four_elements().kind());
    let h = 1e-6;
    let tied = |fc: f64| {
        let set = RawParams {
            fc,
            fc_neg: fc,
            ..raw(&w, &delta)
        }
        .validate()
        .unwrap();
        simulate(&set, simulation)
    };
    let (plus, minus) = (tied(1.0 + h), tied(1.0 - h));
    let sums: Vec<f64> = (0..400)
        .map(|k| jacobian[k * columns] + jacobian[k * columns + 7])
        .collect();
    let largest = sums.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    assert!(largest > 0.1, "the signal must excite Fc");
    for (k, sum) in sums.iter().enumerate() {
        let difference = (plus[k] - minus[k]) / (2.0 * h);
        assert!((sum - difference).abs() <= 1e-6 * largest, "sample {k}");
    }
}

#[test]
fn many_sets_are_each_sets_own_run() {
    let signal = sine(500);
    let position: Vec<f64> = signal
        .iter()
        .scan(0.1, |x, v| {
            *x += v * DT;
            Some(*x)
        })
        .collect();
    let sets = [
        four_elements(),
        lugre(),
        maxwell(&[0.7, 0.6, 0.5], &[1e-6, 3e-6, 9e-6], 0.9),
        maxwell(&[2.0], &[5e-6], 1.2),
    ];
    for (signal, input) in [(&signal, Input::Velocity), (&position, Input::Position)] {
        for scheme in [Scheme::Implicit, Scheme::Explicit] {
            let simulation = simulation(signal, input, scheme);
            let mut forces = vec![0.0; sets.len() * signal.len()];
            simulate_sets(&sets, simulation, &mut forces).unwrap();
            for (set, row) in sets.iter().zip(forces.chunks(signal.len())) {
                assert_eq!(bits(row), bits(&simulate(set, simulation)));
            }
        }
    }
    // No sets, and sets of an empty signal: nothing to write, nothing refused.
    simulate_sets(
        &[],
        simulation(&signal, Input::Velocity, Scheme::Implicit),
        &mut [],
    )
    .unwrap();
    simulate_sets(
        &sets,
        simulation(&[], Input::Velocity, Scheme::Implicit),
        &mut [],
    )
    .unwrap();
}

#[test]
fn refusals_name_what_is_wrong() {
    let set = four_elements();
    let signal = sine(10);
    let columns = column_count(set.kind());
    let simulation = simulation(&signal, Input::Velocity, Scheme::Implicit);
    let call = |rows: &[usize], force: usize, jacobian: usize, simulation: Simulation<'_>| {
        sensitivities(
            &set,
            simulation,
            rows,
            &mut vec![0.0; force],
            &mut vec![0.0; jacobian],
        )
    };
    assert_eq!(
        call(&[1, 3, 3], 10, 3 * columns, simulation),
        Err(Error::RowOrder {
            index: 2,
            row: 3,
            previous: 3
        })
    );
    assert_eq!(
        call(&[4, 2], 10, 2 * columns, simulation),
        Err(Error::RowOrder {
            index: 1,
            row: 2,
            previous: 4
        })
    );
    assert_eq!(
        call(&[2, 10], 10, 2 * columns, simulation),
        Err(Error::RowBeyond {
            index: 1,
            row: 10,
            samples: 10
        })
    );
    assert_eq!(
        call(&[2], 9, columns, simulation),
        Err(Error::OutputLength {
            output: Output::Force,
            expected: 10,
            got: 9
        })
    );
    assert_eq!(
        call(&[2], 10, columns + 1, simulation),
        Err(Error::OutputLength {
            output: Output::Jacobian,
            expected: columns,
            got: columns + 1
        })
    );
    let mut bad = signal.clone();
    bad[6] = f64::NAN;
    let refused = call(
        &[],
        10,
        0,
        Simulation {
            signal: &bad,
            ..simulation
        },
    )
    .unwrap_err();
    assert!(matches!(
        refused,
        Error::Core(CoreError::NotFinite { field: Field::v, index: 6, value }) if value.is_nan()
    ));
    assert_eq!(
        call(
            &[],
            10,
            0,
            Simulation {
                dt: 0.0,
                ..simulation
            }
        ),
        Err(Error::Core(CoreError::NotPositive {
            field: Field::dt,
            value: 0.0
        }))
    );
    // LuGre stepped by forward Euler at 100 Hz: ten times past its stability limit, and a
    // linear spring's force has no bound (a bank's has, ΣW, and never diverges).
    let long = sine(1000);
    let diverging = Simulation {
        signal: &long,
        dt: 1e-2,
        scheme: Scheme::Explicit,
        ..simulation
    };
    let diverged = sensitivities(&lugre(), diverging, &[], &mut [0.0; 1000], &mut []).unwrap_err();
    assert!(
        matches!(diverged, Error::Core(CoreError::Diverged { .. })),
        "{diverged:?}"
    );
    assert_eq!(diverged.class(), ErrorClass::Divergence);
    assert_eq!(diverged.kind(), "diverged");
    assert_eq!(refused.class(), ErrorClass::Input);
    assert_eq!(refused.details().sample, Some(6));
}

#[test]
fn refusals_of_many_sets_name_the_set() {
    let signal = sine(10);
    let simulation = simulation(&signal, Input::Velocity, Scheme::Implicit);
    let mut bad = signal.clone();
    bad[6] = f64::NAN;
    // The output's shape, and the first set that fails, with its sample.
    let sets = [four_elements(), lugre()];
    assert_eq!(
        simulate_sets(&sets, simulation, &mut [0.0; 19]),
        Err(Error::OutputLength {
            output: Output::Forces,
            expected: 20,
            got: 19
        })
    );
    let failing = simulate_sets(
        &sets,
        Simulation {
            signal: &bad,
            ..simulation
        },
        &mut [0.0; 20],
    )
    .unwrap_err();
    assert!(matches!(
        failing,
        Error::Set {
            set: 0,
            error: CoreError::NotFinite {
                field: Field::v,
                index: 6,
                ..
            }
        }
    ));
    assert_eq!(
        simulate_sets(
            &sets,
            Simulation {
                dt: -1.0,
                signal: &[],
                ..simulation
            },
            &mut []
        ),
        Err(Error::Set {
            set: 0,
            error: CoreError::NotPositive {
                field: Field::dt,
                value: -1.0
            }
        })
    );
}

#[test]
fn messages_say_what_was_expected_and_what_came() {
    let messages = [
        (
            Error::RowOrder {
                index: 2,
                row: 3,
                previous: 3,
            },
            "`rows` must be strictly increasing, got rows[2] = 3 after rows[1] = 3",
        ),
        (
            Error::RowBeyond {
                index: 1,
                row: 10,
                samples: 10,
            },
            "`rows` must be samples of the signal, below its length 10, got rows[1] = 10",
        ),
        (
            Error::OutputLength {
                output: Output::Jacobian,
                expected: 14,
                got: 15,
            },
            "`jacobian` must have length 14, got 15",
        ),
        (
            Error::Set {
                set: 3,
                error: CoreError::Diverged { index: 7 },
            },
            "parameter set 3: the explicit step diverged at sample 7",
        ),
    ];
    for (error, message) in messages {
        assert!(error.to_string().starts_with(message), "{error}");
    }
}

/// The data an exception carries (docs/errors.md#error-data), without parsing the message.
#[test]
fn refusals_carry_their_data() {
    let order = Error::RowOrder {
        index: 2,
        row: 3,
        previous: 3,
    }
    .details();
    assert_eq!(order.kind, "not_increasing");
    assert_eq!(order.field, Some(Location::Element("rows", 2)));
    assert_eq!(
        (order.index, order.value, order.bound),
        (Some(2), Some(Number::Count(3)), Some(Number::Count(3)))
    );
    let beyond = Error::RowBeyond {
        index: 1,
        row: 10,
        samples: 10,
    }
    .details();
    assert_eq!(beyond.kind, "out_of_range");
    assert_eq!(
        beyond.field.map(|field| field.to_string()).as_deref(),
        Some("rows[1]")
    );
    assert_eq!(
        (beyond.value, beyond.bound),
        (Some(Number::Count(10)), Some(Number::Count(10)))
    );
    let length = Error::OutputLength {
        output: Output::Jacobian,
        expected: 14,
        got: 15,
    };
    assert_eq!(length.kind(), "length_mismatch");
    assert_eq!(length.class(), ErrorClass::Input);
    let details = length.details();
    assert_eq!(
        (details.field, details.expected, details.got),
        (Some(Location::Key("jacobian")), Some(14), Some(15))
    );
    let set = Error::Set {
        set: 3,
        error: CoreError::Diverged { index: 7 },
    };
    assert_eq!(set.class(), ErrorClass::Divergence);
    let details = set.details();
    assert_eq!(
        (details.kind, details.channel, details.sample),
        ("diverged", Some(3), Some(7))
    );
    for kind in Error::KINDS {
        assert!(
            kind.bytes().all(|b| b == b'_' || b.is_ascii_lowercase()),
            "{kind}"
        );
    }
}
