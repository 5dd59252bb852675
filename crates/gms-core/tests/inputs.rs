//! The input side of the step contract (docs/model.md#discrete-step):
//!
//! - non-finite v, x or dt (and dt ≤ 0) are reported with the field (and, for block calls, the
//!   index of the first bad sample) and leave the state bitwise untouched;
//! - a block call with an output slice of the wrong length is a `LengthMismatch`;
//! - position input: a fresh channel takes v = 0 for its first sample, later ones
//!   v = (xₖ − xₖ₋₁)/dt, so `simulate_position` equals `simulate` on the differenced velocities;
//! - a block run split into two chunks equals one run, and one `Params` driving two channels
//!   equals two copies driving one each, bitwise (no hidden state in the parameters);
//! - a diverging explicit step (stiff linear spring, large dt) is an `Error::Diverged` at the
//!   right sample, not a panic; block calls are all or nothing, so the state is left finite, as
//!   it was before the call.

mod common;

use common::{dt, leuven, log_uniform, reach, scheme, signed, stribeck, velocities};
use gms_core::{Error, Field, Hysteresis, LeuvenParams, Linear, Params, Scheme, State};
use proptest::prelude::*;

/// The bits of a 4-element state, so that −0.0 ≠ +0.0 and every ulp counts.
fn bits(state: &State<[f64; 4]>) -> (u64, [u64; 4], Option<u64>) {
    (
        state.z.to_bits(),
        state.memory.map(f64::to_bits),
        state.last_position.map(f64::to_bits),
    )
}

fn non_finite() -> impl Strategy<Value = f64> {
    prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)]
}

/// Every way a time step can be invalid: zero of either sign, negative, non-finite.
fn bad_dt() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        log_uniform(1e-9, 1.0).prop_map(|dt| -dt),
        non_finite()
    ]
}

/// A state reached by some history, with a previous position recorded or not.
fn reachable_state(
    params: &LeuvenParams<4>,
    history: &[f64],
    dt: f64,
    last_position: Option<f64>,
) -> State<[f64; 4]> {
    let mut state = params.relaxed_state();
    reach(params, &mut state, history, dt, Scheme::Implicit);
    state.last_position = last_position;
    state
}

/// A block of finite inputs with non-finite values at `bad` (index, value) positions.
fn spoiled(len: usize, bad: &[(prop::sample::Index, f64)]) -> (Vec<f64>, usize) {
    let mut block: Vec<f64> = (0..len).map(|k| 1e-4 * (k as f64 * 0.7).sin()).collect();
    for (index, value) in bad {
        block[index.index(len)] = *value;
    }
    let first = bad
        .iter()
        .map(|(index, _)| index.index(len))
        .min()
        .expect("at least one bad sample");
    (block, first)
}

proptest! {
    #![proptest_config(common::config(64))]

    #[test]
    fn single_steps_reject_bad_inputs_untouched(
        params in leuven::<4>(),
        history in velocities(),
        (dt, last_position, scheme) in (dt(), prop::option::of(-1e-3..1e-3f64), scheme()),
        (bad, bad_dt, good) in (non_finite(), bad_dt(), signed(log_uniform(1e-6, 1.0))),
    ) {
        let mut state = reachable_state(&params, &history, dt, last_position);
        let before = bits(&state);

        prop_assert_eq!(
            params.step(&mut state, bad, dt, scheme),
            Err(Error::NotFinite { field: Field::v, index: 0, value: bad })
        );
        prop_assert_eq!(params.step(&mut state, good, bad_dt, scheme), Err(Error::NotPositive { field: Field::dt, value: bad_dt }));
        prop_assert_eq!(
            params.step_position(&mut state, bad, dt, scheme),
            Err(Error::NotFinite { field: Field::x, index: 0, value: bad })
        );
        prop_assert_eq!(
            params.step_position(&mut state, good, bad_dt, scheme),
            Err(Error::NotPositive { field: Field::dt, value: bad_dt })
        );
        prop_assert_eq!(bits(&state), before);
    }

    #[test]
    fn block_calls_reject_bad_inputs_untouched(
        params in leuven::<4>(),
        history in velocities(),
        (dt, last_position, scheme) in (dt(), prop::option::of(-1e-3..1e-3f64), scheme()),
        len in 1..50usize,
        bad in prop::collection::vec((any::<prop::sample::Index>(), non_finite()), 1..4),
        (bad_dt, wrong_len) in (bad_dt(), 0..60usize),
    ) {
        let mut state = reachable_state(&params, &history, dt, last_position);
        let before = bits(&state);
        let (block, first) = spoiled(len, &bad);
        let mut out = vec![0.0; len];

        prop_assert_eq!(
            params.simulate(&mut state, &block, dt, scheme, &mut out),
            Err(Error::NotFinite { field: Field::v, index: first, value: block[first] })
        );
        prop_assert_eq!(
            params.simulate_position(&mut state, &block, dt, scheme, &mut out),
            Err(Error::NotFinite { field: Field::x, index: first, value: block[first] })
        );

        let finite: Vec<f64> = block.iter().map(|&x| if x.is_finite() { x } else { 0.0 }).collect();
        prop_assert_eq!(
            params.simulate(&mut state, &finite, bad_dt, scheme, &mut out),
            Err(Error::NotPositive { field: Field::dt, value: bad_dt })
        );
        prop_assert_eq!(
            params.simulate_position(&mut state, &finite, bad_dt, scheme, &mut out),
            Err(Error::NotPositive { field: Field::dt, value: bad_dt })
        );

        if wrong_len != len {
            let mut out = vec![0.0; wrong_len];
            let mismatch = Err(Error::LengthMismatch { expected: len, got: wrong_len });
            prop_assert_eq!(params.simulate(&mut state, &finite, dt, scheme, &mut out), mismatch);
            prop_assert_eq!(params.simulate_position(&mut state, &finite, dt, scheme, &mut out), mismatch);
        }
        prop_assert_eq!(bits(&state), before);
    }

    /// Positions are differenced: the same forces as the velocity path, the first sample of a
    /// fresh channel at rest.
    #[test]
    fn position_input_is_differenced_velocity(
        params in leuven::<4>(),
        velocities in velocities(),
        (x0, dt, scheme) in (-1e-3..1e-3f64, dt(), scheme()),
    ) {
        // Positions from integrating the random velocities, from an arbitrary origin.
        let positions: Vec<f64> = core::iter::once(x0)
            .chain(velocities.iter().scan(x0, |x, v| {
                *x += v * dt;
                Some(*x)
            }))
            .collect();
        let differenced: Vec<f64> = core::iter::once(0.0)
            .chain(positions.windows(2).map(|x| (x[1] - x[0]) / dt))
            .collect();

        let mut by_position = params.relaxed_state();
        let mut from_position = vec![0.0; positions.len()];
        let mut by_velocity = params.relaxed_state();
        let mut from_velocity = vec![0.0; positions.len()];
        let position_run = params.simulate_position(&mut by_position, &positions, dt, scheme, &mut from_position);
        let velocity_run = params.simulate(&mut by_velocity, &differenced, dt, scheme, &mut from_velocity);
        prop_assert_eq!(position_run, velocity_run);
        if position_run.is_err() {
            return Ok(()); // an explicit divergence, reported identically by both
        }

        let scale = params.hysteresis().max_force();
        for (k, (a, b)) in from_position.iter().zip(&from_velocity).enumerate() {
            prop_assert!((a - b).abs() <= 1e-12 * (scale + b.abs()), "sample {}: {} vs {}", k, a, b);
        }
        prop_assert!((by_position.z - by_velocity.z).abs() <= 1e-12 * by_velocity.z.abs());
        prop_assert_eq!(by_position.last_position, positions.last().copied());
        prop_assert_eq!(by_velocity.last_position, None);

        // The first sample of a fresh channel is a step at rest, whatever x is.
        let mut fresh = params.relaxed_state();
        let mut at_rest = params.relaxed_state();
        prop_assert_eq!(
            params.step_position(&mut fresh, x0, dt, scheme),
            params.step(&mut at_rest, 0.0, dt, scheme)
        );
        prop_assert_eq!((fresh.z, fresh.memory), (at_rest.z, at_rest.memory));
    }

    /// Splitting a block (velocity or position) anywhere changes nothing, bitwise.
    #[test]
    fn split_blocks_equal_one_block(
        params in leuven::<4>(),
        velocities in velocities(),
        split in any::<prop::sample::Index>(),
        (dt, scheme) in (dt(), scheme()),
    ) {
        let split = split.index(velocities.len() + 1);
        let positions: Vec<f64> = velocities.iter().scan(0.0, |x, v| {
            *x += v * dt;
            Some(*x)
        }).collect();
        for (input, by_position) in [(&velocities, false), (&positions, true)] {
            let run = |state: &mut State<[f64; 4]>, input: &[f64], out: &mut [f64]| {
                if by_position {
                    params.simulate_position(state, input, dt, scheme, out)
                } else {
                    params.simulate(state, input, dt, scheme, out)
                }
            };
            let mut whole = params.relaxed_state();
            let mut whole_out = vec![0.0; input.len()];
            let whole_result = run(&mut whole, input, &mut whole_out);

            let mut chunked = params.relaxed_state();
            let mut chunked_out = vec![0.0; input.len()];
            let (head, tail) = input.split_at(split);
            let (head_out, tail_out) = chunked_out.split_at_mut(split);
            let chunked_result = run(&mut chunked, head, head_out).and_then(|()| {
                run(&mut chunked, tail, tail_out).map_err(|error| match error {
                    // The second chunk counts its samples from its own start.
                    Error::Diverged { index } => Error::Diverged { index: index + split },
                    other => other,
                })
            });

            prop_assert_eq!(whole_result, chunked_result);
            // After a divergence, a block call rolls back only its own samples: the states of
            // one call and of two differ, by design.
            if whole_result.is_ok() {
                prop_assert_eq!(bits(&whole), bits(&chunked));
                let to_bits = |out: &[f64]| out.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
                prop_assert_eq!(to_bits(&whole_out), to_bits(&chunked_out));
            }
        }
    }

    /// Interleaving two channels on one `Params` equals running each on its own copy.
    #[test]
    fn one_params_drives_independent_channels(
        params in leuven::<4>(),
        (first, second) in (velocities(), velocities()),
        (dt, scheme) in (dt(), scheme()),
    ) {
        let (mut a, mut b) = (params.relaxed_state(), params.relaxed_state());
        let mut shared = Vec::new();
        for k in 0..first.len().max(second.len()) {
            if let Some(&v) = first.get(k) {
                shared.push((0, params.step(&mut a, v, dt, scheme)));
            }
            if let Some(&v) = second.get(k) {
                shared.push((1, params.step(&mut b, v, dt, scheme)));
            }
        }
        for (channel, input, state) in [(0, &first, &a), (1, &second, &b)] {
            let copy = params;
            let mut own = copy.relaxed_state();
            let alone: Vec<_> = input.iter().map(|&v| copy.step(&mut own, v, dt, scheme)).collect();
            let interleaved: Vec<_> =
                shared.iter().filter(|(c, _)| *c == channel).map(|(_, force)| *force).collect();
            prop_assert_eq!(
                alone.iter().map(|f| f.map(f64::to_bits)).collect::<Vec<_>>(),
                interleaved.iter().map(|f| f.map(f64::to_bits)).collect::<Vec<_>>()
            );
            prop_assert_eq!(bits(&own), bits(state));
        }
    }

    /// A stiff spring with a large explicit step diverges: reported at the first sample whose
    /// step diverges, with the state as it was before the call.
    #[test]
    fn explicit_divergence_is_reported(
        stribeck in stribeck(),
        // n ≥ 1: for n < 1 the explicit oscillation grows only like |z|ⁿ and stays bounded.
        (sigma0, n) in (log_uniform(1e7, 1e9), prop_oneof![Just(1.0), Just(2.0), 1.0..3.0]),
        (v, dt) in (signed(log_uniform(0.1, 1.0)), log_uniform(1e-3, 1e-2)),
    ) {
        let spring = Linear::new(sigma0).expect("valid stiffness");
        let params = Params::new(stribeck, n, 10.0, 0.4, spring).expect("valid parameters");
        let input = vec![v; 2000];
        let mut state = params.relaxed_state();
        let mut out = vec![f64::NAN; input.len()];
        let result = params.simulate(&mut state, &input, dt, Scheme::Explicit, &mut out);
        let Err(Error::Diverged { index }) = result else {
            return Err(TestCaseError::fail(format!("no divergence: {result:?}")));
        };
        prop_assert!(index > 0 && index < input.len());
        prop_assert_eq!(state.z.to_bits(), params.relaxed_state().z.to_bits());

        // `index` is right: the samples before it run, and a single step from there diverges,
        // reported and without touching the (finite) state.
        let mut replay = params.relaxed_state();
        let mut replay_out = vec![0.0; index];
        prop_assert_eq!(params.simulate(&mut replay, &input[..index], dt, Scheme::Explicit, &mut replay_out), Ok(()));
        prop_assert!(replay.z.is_finite() && replay_out.iter().all(|f| f.is_finite()));
        let before = replay;
        prop_assert_eq!(params.step(&mut replay, v, dt, Scheme::Explicit), Err(Error::Diverged { index: 0 }));
        prop_assert_eq!(replay.z.to_bits(), before.z.to_bits());

        // The implicit scheme takes the same input in its stride.
        let mut implicit = params.relaxed_state();
        prop_assert_eq!(params.simulate(&mut implicit, &input, dt, Scheme::Implicit, &mut out), Ok(()));
        prop_assert!(out.iter().all(|f| f.is_finite()));
    }
}

/// Differencing two finite positions can overflow: that is a non-finite velocity, reported as
/// such, and the state is left untouched.
#[test]
fn overflowing_position_difference_is_reported() {
    let stribeck = gms_core::Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve");
    let elements = gms_core::MaxwellSlip::new([0.6, 0.5, 0.4, 0.3], [1e-6, 2e-6, 4e-6, 8e-6])
        .expect("valid elements");
    let params = Params::new(stribeck, 2.0, 30.0, 0.4, elements).expect("valid parameters");
    let mut state = params.relaxed_state();
    assert!(params
        .step_position(&mut state, -f64::MAX, 1e-3, Scheme::Implicit)
        .is_ok());
    let before = bits(&state);
    assert_eq!(
        params.step_position(&mut state, f64::MAX, 1e-3, Scheme::Implicit),
        Err(Error::NotFinite {
            field: Field::v,
            index: 0,
            value: f64::INFINITY
        })
    );
    assert_eq!(bits(&state), before);

    let mut fresh = params.relaxed_state();
    let mut out = [0.0; 2];
    assert_eq!(
        params.simulate_position(
            &mut fresh,
            &[-f64::MAX, f64::MAX],
            1e-3,
            Scheme::Implicit,
            &mut out
        ),
        Err(Error::NotFinite {
            field: Field::v,
            index: 1,
            value: f64::INFINITY
        })
    );
    assert_eq!(bits(&fresh), bits(&params.relaxed_state()));
}

/// A step whose z⁺ is finite but whose force overflows (σ1·(z⁺ − z)/dt beyond the f64 range)
/// is `Diverged` and leaves every element where it was, although the commit at z⁺ would have
/// moved them: the step decides finiteness before it writes the memory.
#[test]
fn overflowing_force_leaves_the_elements_in_place() {
    // Fc close to ΣW: at the step's z⁺ (Fh ≈ g = Fc), the narrow elements slip.
    let stribeck = gms_core::Stribeck::new(3.0, 3.5, 1e-3, 2.0).expect("valid curve");
    let elements = gms_core::MaxwellSlip::new([1.0, 1.0, 1.0, 1.0], [1e-6, 2e-6, 3e-6, 4e-6])
        .expect("valid elements");
    let stiff: LeuvenParams<4> =
        Params::new(stribeck, 2.0, 1e300, 0.4, elements).expect("valid parameters");
    let plain: LeuvenParams<4> =
        Params::new(stribeck, 2.0, 0.0, 0.4, elements).expect("valid parameters");
    // dt·v = 10 µm in 1e-20 s: σ1·(z⁺ − z)/dt ≈ 1e300·1e-6/1e-20 overflows.
    let (v, dt) = (1e15, 1e-20);
    for scheme in [Scheme::Implicit, Scheme::Explicit] {
        // From a state with the elements deflected, not relaxed, so that every ζ counts.
        let mut state = plain.relaxed_state();
        plain
            .step(&mut state, -1e-3, 1e-3, scheme)
            .expect("a finite step");
        let before = bits(&state);
        assert_eq!(
            stiff.step(&mut state, v, dt, scheme),
            Err(Error::Diverged { index: 0 }),
            "{scheme:?}"
        );
        assert_eq!(bits(&state), before, "{scheme:?}");
        // The same step with a finite force commits, and moves elements.
        let mut moved = state;
        plain
            .step(&mut moved, v, dt, scheme)
            .expect("a finite step");
        assert_ne!(moved.memory, state.memory, "{scheme:?}");
    }
}
