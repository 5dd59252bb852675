//! The friction force has no jump when an internal hysteresis loop closes (the paper's first
//! modification: the original Leuven model jumps there, Fig. 1).
//!
//! A fair test needs a velocity that is itself continuous at the closure, since sigma2·v and the
//! micro-viscous term follow v. So the input is the smooth profile
//!
//!   x(t) = ε·(s − k·sin s),  s = ωt − π,  v(t) = ε·ω·(1 − k·cos s),  k = 1.5,
//!
//! which rises, reverses at s = −acos(1/k), makes a small excursion back, reverses again at
//! s = +acos(1/k) and rises past the first turning point: a minor loop closed in presliding.
//! The elements are chosen (and the run checks) so that one of them slips inside the loop, two
//! slipped on the way up but not inside the loop and resume slipping just after the closure,
//! and one never slips: the closure is a real change of the memory's active set.
//!
//! The same continuous-time profile is run at dt, dt/2, dt/4, dt/8. A force that is continuous
//! (Lipschitz) in time changes by O(dt) per step, so the largest step-to-step change in a fixed
//! time window around the closure halves with dt; a jump of any size J would keep that largest
//! change above J and the ratio would go to 1. The detector itself is checked on a synthetic jump.

use gms_core::{Hysteresis, LeuvenParams, MaxwellSlip, Params, Scheme, Stribeck};

const K: f64 = 1.5;
const OMEGA: f64 = 2.0 * core::f64::consts::PI;
/// Scale of the motion: the rise to the first reversal is 3.4·ε = 6.8 µm, the minor loop
/// 0.55·ε = 1.1 µm.
const EPSILON: f64 = 2e-6;
/// The profile runs from s = −π to s = 4.5, well past the closure.
const DURATION: f64 = (core::f64::consts::PI + 4.5) / OMEGA;
/// Saturation forces and break deflections: element 0 slips inside the minor loop, 1 and 2
/// slipped on the rise but not in the loop (they resume slipping after the closure, where the
/// slope of Fh changes), and 3 never slips.
const W: [f64; 4] = [0.3, 0.3, 0.3, 1.0];
const DELTA: [f64; 4] = [0.4e-6, 1e-6, 2e-6, 40e-6];
/// Half-width of the window around the closure [s]: narrow enough to leave out the steep
/// reloading right after the bottom of the loop, whose edge would otherwise decide the maximum.
const WINDOW: f64 = 0.015;
const COARSEST_DT: f64 = 1e-3;

fn velocity(t: f64) -> f64 {
    EPSILON * OMEGA * (1.0 - K * (OMEGA * t - core::f64::consts::PI).cos())
}

/// One run of the profile: the times at the end of each step, and the state and force there.
struct Run {
    t: Vec<f64>,
    z: Vec<f64>,
    memory: Vec<[f64; 4]>,
    hysteresis: Vec<f64>,
    force: Vec<f64>,
}

fn run(params: &LeuvenParams<4>, dt: f64, scheme: Scheme) -> Run {
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // a small positive count
    let steps = (DURATION / dt).round() as usize;
    let mut state = params.relaxed_state();
    let mut run = Run {
        t: Vec::new(),
        z: Vec::new(),
        memory: Vec::new(),
        hysteresis: Vec::new(),
        force: Vec::new(),
    };
    for k in 0..steps {
        // The zero-order hold takes the velocity at the middle of the step.
        let v = velocity((k as f64 + 0.5) * dt);
        let force = params
            .step(&mut state, v, dt, scheme)
            .expect("finite input");
        run.t.push((k + 1) as f64 * dt);
        run.z.push(state.z);
        run.memory.push(state.memory);
        run.hysteresis
            .push(params.hysteresis().trial(&state.memory, state.z).force);
        run.force.push(force);
    }
    run
}

/// The time at which z comes back to its value at the first reversal, after the minor loop,
/// once the run is checked to be the scenario the module describes.
fn closure_time(run: &Run, dt: f64, breakaway: f64) -> f64 {
    // Steps are numbered by their end; step k holds v((k + ½)·dt).
    let sign = |k: usize| velocity((k as f64 + 0.5) * dt) > 0.0;
    let first_reversal = (0..run.t.len())
        .find(|&k| !sign(k))
        .expect("the profile reverses");
    let second_reversal = (first_reversal..run.t.len())
        .find(|&k| sign(k))
        .expect("the profile reverses twice");
    let (top, bottom) = (first_reversal - 1, second_reversal - 1);
    let turning_point = run.z[top];
    // Presliding: at the turning point the force is well below the break-away level (when
    // sliding, z would come back to the turning point only asymptotically).
    assert!(
        run.hysteresis[top] < 0.9 * breakaway,
        "the loop is not in presliding"
    );
    let closure = (second_reversal..run.t.len())
        .find(|&k| run.z[k] >= turning_point)
        .expect("the loop closes");

    let moved = |element: usize, from: usize, to: usize| {
        run.memory[from][element] != run.memory[to][element]
    };
    assert!(
        moved(0, top, bottom),
        "element 0 does not slip inside the loop"
    );
    for element in [1, 2] {
        assert!(
            moved(element, 0, top),
            "element {element} did not slip on the way up"
        );
        assert!(
            !moved(element, top, closure - 1),
            "element {element} slipped inside the loop"
        );
        let soon = (closure..run.t.len()).take_while(|&k| run.t[k] - run.t[closure] <= WINDOW);
        assert!(
            soon.into_iter().any(|k| moved(element, closure - 1, k)),
            "element {element} does not resume slipping after the closure"
        );
    }
    assert!(
        run.memory.iter().all(|memory| memory[3] == 0.0),
        "element 3 slipped"
    );
    run.t[closure]
}

/// The largest |F(k+1) − F(k)| over the steps that end within `WINDOW` of `centre`.
fn largest_change(t: &[f64], force: &[f64], centre: f64) -> f64 {
    t.windows(2)
        .zip(force.windows(2))
        .filter(|(t, _)| (t[1] - centre).abs() <= WINDOW)
        .map(|(_, f)| (f[1] - f[0]).abs())
        .fold(0.0, f64::max)
}

/// The largest force changes near the closure at dt, dt/2, dt/4, dt/8, with `jump` added to
/// the force from the closure on.
///
/// z approaches its turning point slowly, so the moment it passes it shifts by several steps
/// between the runs: all runs are measured over the same window, centred on the closure of
/// the finest run, which contains the closure of every run.
fn changes_near_closure(params: &LeuvenParams<4>, scheme: Scheme, jump: f64) -> Vec<f64> {
    let breakaway = params.stribeck().g(0.0);
    let runs: Vec<(Run, f64)> = (0..4)
        .map(|halvings| {
            let dt = COARSEST_DT / f64::from(1 << halvings);
            let mut run = run(params, dt, scheme);
            let closure = closure_time(&run, dt, breakaway);
            // A synthetic discontinuity at the closure, to check that the detector sees one.
            for (t, force) in run.t.iter().zip(&mut run.force) {
                if *t >= closure {
                    *force += jump;
                }
            }
            (run, closure)
        })
        .collect();
    let centre = runs.last().map_or(f64::NAN, |(_, closure)| *closure);
    runs.iter()
        .map(|(run, closure)| {
            assert!(
                (closure - centre).abs() <= 0.5 * WINDOW,
                "closures at {closure} and {centre}"
            );
            largest_change(&run.t, &run.force, centre)
        })
        .collect()
}

fn ratios(changes: &[f64]) -> Vec<f64> {
    changes.windows(2).map(|pair| pair[1] / pair[0]).collect()
}

fn params(stribeck: Stribeck, n: f64) -> LeuvenParams<4> {
    let elements = MaxwellSlip::new(W, DELTA).expect("valid elements");
    Params::new(stribeck, n, 30.0, 0.4, elements).expect("valid parameters")
}

fn curves() -> [Stribeck; 2] {
    [
        Stribeck::new(1.0, 1.5, 1e-3, 2.0).expect("valid curve"),
        Stribeck::asymmetric(1.0, 1.4, 0.7, 1.1, 2e-4, 0.7).expect("valid curve"),
    ]
}

#[test]
fn force_is_continuous_at_loop_closure() {
    for stribeck in curves() {
        for n in [0.6, 1.0, 2.0, 3.3] {
            for scheme in [Scheme::Implicit, Scheme::Explicit] {
                let changes = changes_near_closure(&params(stribeck, n), scheme, 0.0);
                let ratios = ratios(&changes);
                assert!(
                    ratios.iter().all(|&ratio| ratio <= 0.6),
                    "{scheme:?}, n = {n}, {stribeck:?}: largest |ΔF| near the closure at dt, \
                     dt/2, dt/4, dt/8 = {changes:?}, ratios {ratios:?}"
                );
            }
        }
    }
}

/// The same measurement flags a jump of 0.1 % of the total saturation force at the closure.
#[test]
fn detector_sees_a_jump() {
    let params = params(curves()[0], 2.0);
    let jump = 1e-3 * W.iter().sum::<f64>();
    let changes = changes_near_closure(&params, Scheme::Implicit, jump);
    let ratios = ratios(&changes);
    assert!(
        ratios.iter().any(|&ratio| ratio > 0.6),
        "a jump went unnoticed: largest |ΔF| = {changes:?}, ratios {ratios:?}"
    );
}
