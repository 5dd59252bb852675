//! The C ABI from C: `tests/c/control_loop.c` is compiled with gcc against the static and the
//! shared library that this `cargo test` built, run, and every number it prints is checked
//! against the same control loop computed here with gms-core; every bad argument must come
//! back as the expected status, not a crash.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

use gms_core::{
    Compensator, LeuvenParams, Level, MaxwellSlip, Mode, Params, PositionForce, RippleTerms,
    Stribeck,
};
use gms_ffi::leuven_rt_status::*;

// The loop of control_loop.c, constant for constant.
const DT: f64 = 1e-3;
const SAMPLES: usize = 2000;
const SWAP_AT: usize = 1000;
const NAN_AT: usize = 1500;
const MASS: f64 = 1.0;
const DAMPING: f64 = 2.0;
const KP: f64 = 4000.0;
const KD: f64 = 80.0;
const AMPLITUDE: f64 = 2e-4;
const FREQUENCY: f64 = 2.0;

// The status codes as C sees them, from the crate's own enum.
const OK: i32 = LEUVEN_RT_OK as i32;
const INVALID_POINTER: i32 = LEUVEN_RT_INVALID_POINTER as i32;
const INVALID_PARAMETER: i32 = LEUVEN_RT_INVALID_PARAMETER as i32;
const INVALID_DT: i32 = LEUVEN_RT_INVALID_DT as i32;
const INVALID_MODE: i32 = LEUVEN_RT_INVALID_MODE as i32;
const NOT_FINITE_INPUT: i32 = LEUVEN_RT_NOT_FINITE_INPUT as i32;
const INCOMPATIBLE_PARAMS: i32 = LEUVEN_RT_INCOMPATIBLE_PARAMS as i32;
const INVALID_FILE: i32 = LEUVEN_RT_INVALID_FILE as i32;
const NO_START_POSITION: i32 = LEUVEN_RT_NO_START_POSITION as i32;

fn params(fc: f64, fs: f64, vs: f64, w: [f64; 10], delta: [f64; 10]) -> LeuvenParams<10> {
    let stribeck = Stribeck::new(fc, fs, vs, 2.0).unwrap();
    Params::new(
        stribeck,
        2.0,
        30.0,
        0.4,
        MaxwellSlip::new(w, delta).unwrap(),
    )
    .unwrap()
}

fn nominal() -> LeuvenParams<10> {
    let delta = [1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 7e-6, 8e-6, 9e-6, 1e-5];
    params(1.0, 1.5, 1e-3, [0.2; 10], delta)
}

fn swapped() -> LeuvenParams<10> {
    let w = [0.3, 0.3, 0.25, 0.25, 0.2, 0.2, 0.15, 0.15, 0.1, 0.1];
    let delta = [
        1.5e-6, 3e-6, 4e-6, 5e-6, 6e-6, 8e-6, 9e-6, 1e-5, 1.2e-5, 1.5e-5,
    ];
    params(1.1, 1.7, 1.5e-3, w, delta)
}

/// The loop of one mode, in Rust: (x, force) after each sample.
fn rust_loop(mode: Mode) -> Vec<(f64, f64)> {
    let mut compensator = Compensator::new(nominal(), DT, mode).unwrap();
    let mut friction = Compensator::new(swapped(), DT, Mode::Observer).unwrap();
    let (mut x, mut v) = (0.0, 0.0);
    let mut out = Vec::with_capacity(SAMPLES);
    for k in 0..SAMPLES {
        if k == SWAP_AT {
            compensator.set_params(swapped());
        }
        let t = k as f64 * DT;
        let x_desired = AMPLITUDE * (1.0 - (2.0 * PI * FREQUENCY * t).cos());
        let v_desired = AMPLITUDE * 2.0 * PI * FREQUENCY * (2.0 * PI * FREQUENCY * t).sin();
        let force = if k == NAN_AT {
            assert!(compensator.step(f64::NAN).is_err());
            0.0
        } else {
            let input = match mode {
                Mode::Feedforward => v_desired,
                Mode::Observer => x,
            };
            compensator.step(input).unwrap()
        };
        let command = KP * (x_desired - x) + KD * (v_desired - v) + force;
        let friction = friction.step(x).unwrap();
        v += DT * (command - DAMPING * v - friction) / MASS;
        x += DT * v;
        out.push((x, force));
    }
    out
}

/// The directory of the libraries this test run built: cargo writes the static and shared
/// library of gms-ffi beside the test binary, in `target/<profile>/deps`.
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("path of the test binary");
    let dir = exe.parent().expect("target/<profile>/deps");
    for name in ["libgms_ffi.a", "libgms_ffi.so"] {
        assert!(
            dir.join(name).exists(),
            "{name} not found in {}: cargo test builds it with the library",
            dir.display()
        );
    }
    dir.to_path_buf()
}

/// Compiles `control_loop.c` with gcc, linked statically or dynamically, and returns its output.
fn compile_and_run(shared: bool) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let libraries = library_dir();
    let binary = Path::new(env!("CARGO_TARGET_TMPDIR")).join(if shared {
        "control_loop_shared"
    } else {
        "control_loop_static"
    });
    let mut gcc = Command::new("gcc");
    gcc.args([
        "-std=c11",
        "-O2",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-ffp-contract=off",
    ])
    .arg("-I")
    .arg(root.join("include"))
    .arg(root.join("tests/c/control_loop.c"))
    .arg("-o")
    .arg(&binary);
    if shared {
        gcc.arg(format!("-L{}", libraries.display()))
            .arg("-lgms_ffi")
            .arg(format!("-Wl,-rpath,{}", libraries.display()));
    } else {
        gcc.arg(libraries.join("libgms_ffi.a"));
    }
    // What a Rust static library needs from the system on Linux (`--print native-static-libs`).
    gcc.args(["-lm", "-lpthread", "-ldl", "-lgcc_s", "-lc"]);
    let compiled = gcc
        .output()
        .expect("gcc must be installed to test the C ABI");
    assert!(
        compiled.status.success(),
        "gcc failed:\n{}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    // cargo test puts target/<profile> on LD_LIBRARY_PATH, which the loader searches before
    // the rpath: a libgms_ffi.so left there by an earlier `cargo build` would be run instead of
    // the one this test built.
    let run = Command::new(&binary)
        .env("LD_LIBRARY_PATH", &libraries)
        .arg(env!("CARGO_TARGET_TMPDIR"))
        .output()
        .expect("run the C program");
    assert!(
        run.status.success(),
        "the C program failed ({}):\n{}",
        run.status,
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).expect("UTF-8 output")
}

struct Printed {
    loops: Vec<[f64; 4]>,
    checks: HashMap<String, (i32, String, usize)>,
    values: HashMap<String, f64>,
}

fn parse(output: &str) -> Printed {
    let mut printed = Printed {
        loops: Vec::new(),
        checks: HashMap::new(),
        values: HashMap::new(),
    };
    for line in output.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["loop", k, numbers @ ..] => {
                assert_eq!(k.parse::<usize>().unwrap(), printed.loops.len());
                let numbers: Vec<f64> = numbers.iter().map(|n| n.parse().unwrap()).collect();
                printed.loops.push(numbers.try_into().unwrap());
            }
            ["check", name, status, field, index] => {
                let entry = (
                    status.parse().unwrap(),
                    field.to_string(),
                    index.parse().unwrap(),
                );
                printed.checks.insert(name.to_string(), entry);
            }
            ["value", name, value] => {
                printed
                    .values
                    .insert(name.to_string(), value.parse().unwrap());
            }
            _ => panic!("unexpected line from the C program: {line}"),
        }
    }
    printed
}

/// Bad input: (status, field, index) for each check the C program prints.
const EXPECTED: &[(&str, i32, &str, usize)] = &[
    ("nan_feedforward", NOT_FINITE_INPUT, "-", 0),
    ("nan_observer", NOT_FINITE_INPUT, "-", 0),
    ("create_null_params", INVALID_POINTER, "-", 0),
    ("create_null_out", INVALID_POINTER, "-", 0),
    ("create_dt_zero", INVALID_DT, "dt", 0),
    ("create_dt_negative", INVALID_DT, "dt", 0),
    ("create_dt_nan", INVALID_DT, "dt", 0),
    ("create_bad_mode", INVALID_MODE, "-", 0),
    ("create_fs_below_fc", INVALID_PARAMETER, "Fs", 0),
    ("create_vs_negative", INVALID_PARAMETER, "Vs", 0),
    ("create_sigma2_nan", INVALID_PARAMETER, "sigma2", 0),
    (
        "create_sigma2_neg_negative",
        INVALID_PARAMETER,
        "sigma2_neg",
        0,
    ),
    ("create_sigma2_neg_nan", INVALID_PARAMETER, "sigma2_neg", 0),
    ("create_w3_negative", INVALID_PARAMETER, "W", 3),
    ("create_elements_too_weak", INVALID_PARAMETER, "W", 0),
    ("create_w_null", INVALID_POINTER, "-", 0),
    ("create_too_many_elements", INVALID_PARAMETER, "elements", 0),
    ("create_both_hysteresis", INVALID_PARAMETER, "sigma0", 0),
    ("create_no_hysteresis", INVALID_PARAMETER, "sigma0", 0),
    ("create_misaligned_params", INVALID_POINTER, "-", 0),
    ("step_null_handle", INVALID_POINTER, "-", 0),
    ("set_params_null_handle", INVALID_POINTER, "-", 0),
    ("reset_null_handle", INVALID_POINTER, "-", 0),
    ("output_null_handle", INVALID_POINTER, "-", 0),
    ("create_ok", OK, "-", 0),
    ("step_null_force", INVALID_POINTER, "-", 0),
    ("step_inf", NOT_FINITE_INPUT, "-", 0),
    ("step_nan", NOT_FINITE_INPUT, "-", 0),
    ("step_huge_jump", NOT_FINITE_INPUT, "-", 0),
    ("set_params_fc_negative", INVALID_PARAMETER, "Fc", 0),
    (
        "set_params_other_count",
        INCOMPATIBLE_PARAMS,
        "elements",
        10,
    ),
    ("set_params_other_kind", INCOMPATIBLE_PARAMS, "elements", 10),
    ("json_ok", OK, "-", 0),
    ("json_unknown_key", INVALID_FILE, "-", 0),
    ("json_missing_key", INVALID_FILE, "-", 0),
    ("json_fs_below_fc", INVALID_PARAMETER, "Fs", 0),
    ("json_elements_too_weak", INVALID_PARAMETER, "W", 0),
    ("json_w_without_delta", INVALID_FILE, "-", 0),
    ("json_not_json", INVALID_FILE, "-", 0),
    ("json_null", INVALID_POINTER, "-", 0),
    ("json_bad_mode", INVALID_MODE, "-", 0),
    ("file_ok", OK, "-", 0),
    ("file_missing", INVALID_FILE, "-", 0),
    ("file_null", INVALID_POINTER, "-", 0),
    ("file_folder", INVALID_FILE, "-", 0),
    ("file_device", INVALID_FILE, "-", 0),
    ("model_ok", OK, "-", 0),
    ("model_struct_create", OK, "-", 0),
    ("set_level_ok", OK, "-", 0),
    (
        "level_half_stroke_zero",
        INVALID_PARAMETER,
        "half_stroke",
        0,
    ),
    ("level_middle_inf", INVALID_PARAMETER, "middle", 0),
    ("level_trend1_nan", INVALID_PARAMETER, "trend", 1),
    ("level_three_ripples", INVALID_PARAMETER, "ripple_count", 0),
    ("level_period_negative", INVALID_PARAMETER, "period", 1),
    ("level_nine_harmonics", INVALID_PARAMETER, "harmonics", 1),
    ("level_cos_nan", INVALID_PARAMETER, "cos", 1),
    ("level_too_deep", INVALID_PARAMETER, "level", 0),
    ("level_null_cos", INVALID_POINTER, "-", 0),
    ("level_null_ripples", INVALID_POINTER, "-", 0),
    ("level_null", INVALID_POINTER, "-", 0),
    ("level_null_handle", INVALID_POINTER, "-", 0),
    ("model_feedforward", NO_START_POSITION, "x", 0),
    ("model_feedforward_at_nan", NOT_FINITE_INPUT, "x", 0),
    ("model_feedforward_at", OK, "-", 0),
    ("set_position_nan", NOT_FINITE_INPUT, "-", 0),
    ("set_position_null", INVALID_POINTER, "-", 0),
    ("set_position_ok", OK, "-", 0),
    ("model_no_level", OK, "-", 0),
    ("model_version_4", INVALID_FILE, "-", 0),
    ("model_version_missing", INVALID_FILE, "-", 0),
    ("model_format_other", INVALID_FILE, "-", 0),
    ("model_unknown_key", INVALID_FILE, "-", 0),
    ("model_units_other", INVALID_FILE, "-", 0),
    ("model_units_missing", INVALID_FILE, "-", 0),
    ("model_measurement_string", INVALID_FILE, "-", 0),
    ("model_measurement_unknown", INVALID_FILE, "-", 0),
    ("model_friction_unknown", INVALID_FILE, "-", 0),
    ("model_friction_missing", INVALID_FILE, "-", 0),
    ("model_friction_fs_below_fc", INVALID_PARAMETER, "Fs", 0),
    (
        "model_level_half_stroke",
        INVALID_PARAMETER,
        "half_stroke",
        0,
    ),
    ("model_level_trend_length", INVALID_FILE, "-", 0),
    ("model_level_sin_length", INVALID_PARAMETER, "harmonics", 1),
    ("model_level_too_deep", INVALID_PARAMETER, "level", 0),
    ("model_level_unknown", INVALID_FILE, "-", 0),
    ("model_file_ok", OK, "-", 0),
    ("model_file_at", OK, "-", 0),
    ("terms_create", OK, "-", 0),
    ("level_without_start", NO_START_POSITION, "x", 0),
    ("force_without_start", NO_START_POSITION, "x", 0),
    ("terms_start", OK, "-", 0),
    ("level_with_start", OK, "-", 0),
    ("force_with_start", OK, "-", 0),
    ("trajectory_create", OK, "-", 0),
    ("trajectory_nan_x", NOT_FINITE_INPUT, "-", 0),
    ("trajectory_inf_v", NOT_FINITE_INPUT, "-", 0),
    ("trajectory_null_handle", INVALID_POINTER, "-", 0),
    ("trajectory_null_force", INVALID_POINTER, "-", 0),
    ("force_period_unresolved", INVALID_PARAMETER, "period", 0),
    ("level_period_1e-300", INVALID_PARAMETER, "period", 0),
    (
        "level_half_stroke_1e-300",
        INVALID_PARAMETER,
        "half_stroke",
        0,
    ),
    ("level_middle_1e308", INVALID_PARAMETER, "middle", 0),
    ("force_trend_nan", INVALID_PARAMETER, "trend", 0),
    ("force_null", INVALID_POINTER, "-", 0),
    ("force_null_handle", INVALID_POINTER, "-", 0),
    ("json_sigma2_neg_zero", OK, "-", 0),
];

/// Samples of the level part of the C program.
const LEVEL_SAMPLES: i32 = 300;

/// The level of the C program's model file and struct.
fn screw_level() -> Level {
    Level::new(
        0.002,
        0.01,
        [0.05, -0.02],
        &[
            RippleTerms {
                period: 0.004,
                cos: &[0.03, 0.01, 0.005],
                sin: &[0.0, 0.02, -0.004],
            },
            RippleTerms {
                period: 0.0013,
                cos: &[0.01, -0.006],
                sin: &[0.012, 0.003],
            },
        ],
    )
    .unwrap()
}

/// The C program's trajectory of the level part: (position, velocity) of sample `k`.
fn level_trajectory(k: i32) -> (f64, f64) {
    let k = f64::from(k);
    (0.003 * (0.01 * k).sin() + 1e-5 * k, 8e-3 * (0.01 * k).cos())
}

/// The C program's level forces, computed with gms-core: (observer, feedforward).
fn level_forces() -> (Vec<f64>, Vec<f64>) {
    let mut observer = Compensator::new(nominal(), DT, Mode::Observer)
        .and_then(|c| c.with_level(screw_level()))
        .unwrap();
    let mut feedforward = Compensator::new(nominal(), DT, Mode::Feedforward)
        .and_then(|c| c.with_start_position(-0.0042))
        .and_then(|c| c.with_level(screw_level()))
        .unwrap();
    (0..LEVEL_SAMPLES)
        .map(|k| {
            let (x, v) = level_trajectory(k);
            (observer.step(x).unwrap(), feedforward.step(v).unwrap())
        })
        .unzip()
}

/// The C program's cogging force.
fn cogging() -> PositionForce {
    PositionForce::new(
        0.001,
        0.02,
        [0.8, -0.3],
        &[RippleTerms {
            period: 0.0025,
            cos: &[0.4, 0.1],
            sin: &[-0.3, 0.05],
        }],
    )
    .unwrap()
}

/// The C program's forces of the terms part, computed with gms-core: the feedforward run with
/// `sigma2_neg` = 0.9, the level and the position force; the trajectory run; and the run of
/// the parameter file with `sigma2_neg` = 0.
fn terms_forces() -> [Vec<f64>; 3] {
    let asymmetric = nominal().with_sigma2_neg(0.9).unwrap();
    let placed = |start: f64| {
        Compensator::new(asymmetric, DT, Mode::Feedforward)
            .and_then(|c| c.with_start_position(start))
            .and_then(|c| c.with_level(screw_level()))
            .and_then(|c| c.with_position_force(cogging()))
            .unwrap()
    };
    let mut feedforward = placed(-0.0042);
    let mut trajectory = placed(level_trajectory(0).0);
    let mut zero = Compensator::new(
        nominal().with_sigma2_neg(0.0).unwrap(),
        DT,
        Mode::Feedforward,
    )
    .unwrap();
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    for k in 0..LEVEL_SAMPLES {
        let (x, v) = level_trajectory(k);
        out[0].push(feedforward.step(v).unwrap());
        out[1].push(trajectory.step_trajectory(1.1 * v, x).unwrap());
        out[2].push(zero.step(v).unwrap());
    }
    out
}

#[test]
fn c_control_loop_matches_rust_and_bad_input_gets_a_status() {
    let output = compile_and_run(false);
    assert_eq!(
        output,
        compile_and_run(true),
        "static and shared library disagree"
    );
    let printed = parse(&output);

    // The loops: C through the ABI equals gms-core called from Rust.
    assert_eq!(printed.loops.len(), SAMPLES);
    let feedforward = rust_loop(Mode::Feedforward);
    let observer = rust_loop(Mode::Observer);
    let mut largest = 0.0f64;
    for (k, c) in printed.loops.iter().enumerate() {
        let rust = [
            feedforward[k].0,
            feedforward[k].1,
            observer[k].0,
            observer[k].1,
        ];
        for (a, b) in c.iter().zip(rust) {
            largest = largest.max((a - b).abs() / b.abs().max(1e-6));
            assert!(
                (a - b).abs() <= 1e-12 * b.abs().max(1e-6),
                "sample {k}: C {c:?} vs Rust {rust:?}"
            );
        }
    }
    // The compensator did real work: forces of the order of the friction level.
    let peak = feedforward.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
    assert!(peak > 1.0, "peak feedforward force {peak}");
    eprintln!("largest relative difference C vs Rust: {largest:e}");

    let expected = EXPECTED;
    for &(name, status, field, index) in expected {
        let got = printed
            .checks
            .get(name)
            .unwrap_or_else(|| panic!("no check {name} printed"));
        assert_eq!(
            got,
            &(status, field.to_string(), index),
            "{name}: (status, field, index)"
        );
    }
    assert_eq!(printed.checks.len(), expected.len());
    assert_eq!(printed.values["step_null_handle_force"], 0.0);
    assert_eq!(printed.values["held_force_equal"], 1.0);
    assert_eq!(printed.values["untouched_after_rejections"], 1.0);
    for named in [
        "json_equals_struct",
        "json_unknown_key_named",
        "json_missing_key_named",
        "file_missing_named",
        "level_struct_equals_file",
        "level_cos_nan_named",
        "level_untouched_after_rejections",
        "model_no_level_equals_plain",
        "model_version_named",
        "model_format_named",
        "model_unknown_key_named",
        "model_file_equals_text",
        "model_feedforward_named",
        "model_file_at_equals_text",
        "trajectory_held",
        "force_period_named",
        "terms_untouched_after_rejections",
    ] {
        assert_eq!(printed.values[named], 1.0, "{named}");
    }
    assert_eq!(printed.values["trajectory_null_handle_force"], 0.0);
    // The level through the C ABI is gms-core's (C's sin and cos make the trajectory, hence
    // the loop's tolerance).
    let (observer, feedforward) = level_forces();
    let mut scaled = 0;
    for k in 0..observer.len() {
        for (name, rust) in [("observer", observer[k]), ("feedforward", feedforward[k])] {
            let c = printed.values[&format!("level_{name}_{k}")];
            assert!(
                (c - rust).abs() <= 1e-12 * rust.abs().max(1e-6),
                "{name} sample {k}: C {c} vs Rust {rust}"
            );
        }
        scaled += usize::from(observer[k] != 0.0);
    }
    assert!(scaled > 250, "the level run must produce forces");
    terms_match_rust(&printed);
}

/// The viscous asymmetry, the position force and the trajectory steps through the C ABI are
/// gms-core's.
fn terms_match_rust(printed: &Printed) {
    let [feedforward, trajectory, zero] = terms_forces();
    // The comparison sees sigma2_neg: without it the run of the file differs backwards.
    let mut plain = Compensator::new(nominal(), DT, Mode::Feedforward).unwrap();
    let (mut backward, mut asymmetric) = (0, 0);
    for k in 0..feedforward.len() {
        for (name, rust) in [
            ("terms_feedforward", feedforward[k]),
            ("terms_trajectory", trajectory[k]),
            ("sigma2_neg_zero", zero[k]),
        ] {
            let c = printed.values[&format!("{name}_{k}")];
            assert!(
                (c - rust).abs() <= 1e-12 * rust.abs().max(1e-6),
                "{name} sample {k}: C {c} vs Rust {rust}"
            );
        }
        let (_, v) = level_trajectory(i32::try_from(k).unwrap());
        let symmetric = plain.step(v).unwrap();
        backward += usize::from(v < 0.0);
        asymmetric += usize::from(v < 0.0 && (zero[k] - symmetric + 0.4 * v).abs() < 1e-12);
    }
    assert!(
        backward > 100 && asymmetric == backward,
        "{backward} backward samples, {asymmetric} without the viscous force"
    );
}
