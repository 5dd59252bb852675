//! # gms-ffi: the friction compensator for C
//!
//! A C ABI over gms-core's [`Compensator`](gms_core::Compensator), built as a static library
//! (`libgms_ffi.a`) and a shared one (`libgms_ffi.so`), with the header `include/leuven_rt.h`
//! (generated from this file by cbindgen; `tests/header.rs` fails if the two differ).
//!
//! ```c
//! const double W[4] = {0.5, 0.5, 0.5, 0.5}, Delta[4] = {1e-6, 2e-6, 4e-6, 8e-6};
//! leuven_rt_params p = {.Fc = 1.0, .Fs = 1.5, .Vs = 1e-3, .delta = 2.0, .n = 2.0,
//!                       .sigma1 = 30.0, .sigma2 = 0.4, .W = W, .Delta = Delta, .elements = 4};
//! leuven_rt_compensator *c = NULL;
//! if (leuven_rt_compensator_create(&p, 1e-3, LEUVEN_RT_MODE_OBSERVER, &c, NULL) != LEUVEN_RT_OK) ...
//! double force;
//! leuven_rt_status s = leuven_rt_compensator_step(c, measured_position, &force); // every sample
//! leuven_rt_compensator_destroy(c);
//! ```
//!
//! Every function returns a [`leuven_rt_status`] and never crashes on a pointer it can check:
//! null and misaligned pointers are refused with `LEUVEN_RT_INVALID_POINTER`. (A dangling or
//! foreign pointer cannot be told from a valid one; passing one is undefined behaviour, as
//! everywhere in C.) A rejected call changes nothing. The `create` functions allocate the
//! compensator once (its size depends on the number of elements, chosen at run time; the JSON
//! and file variants also allocate while parsing); `step`, `set_params`, `reset` and `output`
//! never allocate, and gms-core never panics.
//!
//! The compensator itself, with its number of elements chosen at run time, is gms-dyn's
//! [`Compensator`], the same one the Python package uses; this crate only
//! checks pointers and turns errors into status codes.
//!
//! All `unsafe` of the workspace is in this file: dereferencing the caller's pointers, each
//! behind the checks of `checked` and `checked_mut`, and turning the boxed compensator into
//! a handle and back.
#![allow(non_camel_case_types)] // C names: leuven_rt_params, leuven_rt_status, ...
#![allow(non_snake_case)]
// A refusal carries its message in a fixed buffer rather than a Box, so that `set_params`, which
// runs in the control loop, never allocates; the larger Err variant is the price.
#![allow(clippy::result_large_err)]
// the paper's parameter names: Fc, Fs, W, Delta, ...
// The doc comments are also the comments of the C header, where units read [m], [s], [N].
#![allow(rustdoc::broken_intra_doc_links)]

use core::ffi::{c_char, CStr};
use core::fmt::{self, Write as _};

use gms_core::{Error, Field, Mode};
use gms_dyn::{
    Compensator, HysteresisKind, Level, PositionForce, RawElements, RawParams, RippleTerms, Terms,
    MAX_HARMONICS, MAX_RIPPLES,
};
use gms_file::{FileError, ModelFile};

/// The largest number of Maxwell-slip elements `leuven_rt_params.elements` may have.
pub const LEUVEN_RT_MAX_ELEMENTS: usize = 32;

// The header spells the number out; it must be gms-dyn's.
const _: () = assert!(LEUVEN_RT_MAX_ELEMENTS == gms_dyn::MAX_ELEMENTS);

/// The most ripples `leuven_rt_level.ripple_count` may have.
pub const LEUVEN_RT_MAX_RIPPLES: usize = 2;

/// The most harmonics `leuven_rt_ripple.harmonics` may have.
pub const LEUVEN_RT_MAX_HARMONICS: usize = 8;

// The header spells the numbers out; they must be gms-core's.
const _: () = assert!(LEUVEN_RT_MAX_RIPPLES == MAX_RIPPLES);
const _: () = assert!(LEUVEN_RT_MAX_HARMONICS == MAX_HARMONICS);

/// The size of `leuven_rt_error.message`, its terminating NUL included.
pub const LEUVEN_RT_ERROR_MESSAGE_SIZE: usize = 160;

/// `mode` of `leuven_rt_compensator_create`: each sample's input is the desired velocity [m/s]
/// and the output the friction feedforward along the planned motion.
pub const LEUVEN_RT_MODE_FEEDFORWARD: i32 = 0;

/// `mode` of `leuven_rt_compensator_create`: each sample's input is the measured position [m]
/// and the model runs as an observer of the real motion.
pub const LEUVEN_RT_MODE_OBSERVER: i32 = 1;

/// What a call did. Everything but `LEUVEN_RT_OK` means the call changed nothing.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum leuven_rt_status {
    /// Done.
    LEUVEN_RT_OK = 0,
    /// A pointer argument is null or misaligned.
    LEUVEN_RT_INVALID_POINTER = 1,
    /// A parameter breaks its rule; the error detail names it.
    LEUVEN_RT_INVALID_PARAMETER = 2,
    /// `dt` is not finite and > 0.
    LEUVEN_RT_INVALID_DT = 3,
    /// `mode` is neither `LEUVEN_RT_MODE_FEEDFORWARD` nor `LEUVEN_RT_MODE_OBSERVER`.
    LEUVEN_RT_INVALID_MODE = 4,
    /// The input is NaN or infinite, or (observer) the position jump over dt gives a
    /// velocity that is not finite. The output holds the last good force.
    LEUVEN_RT_NOT_FINITE_INPUT = 5,
    /// New parameters have another kind of hysteresis or number of elements than the
    /// compensator's.
    LEUVEN_RT_INCOMPATIBLE_PARAMS = 6,
    /// The step produced a non-finite force (inputs far outside SI magnitudes). The output
    /// holds the last good force.
    LEUVEN_RT_STEP_FAILED = 7,
    /// A parameter file or model file (`_from_json`, `_from_file`) cannot be read, is not JSON,
    /// has a `format` or `version` this library does not read, or has a key given twice, an
    /// unknown or missing key, or a value of the wrong type; the error message names the key
    /// path or the cause (docs/data-and-reports.md#model-file).
    LEUVEN_RT_INVALID_FILE = 8,
    /// A feedforward compensator was given a level or a position force (by a call, or in a
    /// model file) without the axis's start position: they would be placed from x = 0, out of
    /// phase with the machine. Call `leuven_rt_compensator_set_position` first, or create from a
    /// model file with `leuven_rt_compensator_create_from_json_at` / `_from_file_at`. The error
    /// detail names `x`.
    LEUVEN_RT_NO_START_POSITION = 9,
}

use leuven_rt_status::{
    LEUVEN_RT_INCOMPATIBLE_PARAMS, LEUVEN_RT_INVALID_DT, LEUVEN_RT_INVALID_FILE,
    LEUVEN_RT_INVALID_MODE, LEUVEN_RT_INVALID_PARAMETER, LEUVEN_RT_INVALID_POINTER,
    LEUVEN_RT_NOT_FINITE_INPUT, LEUVEN_RT_NO_START_POSITION, LEUVEN_RT_OK, LEUVEN_RT_STEP_FAILED,
};

/// Parameters of the modified Leuven model (docs/parameters.md), SI units.
///
/// Maxwell slip: `elements` (1 to `LEUVEN_RT_MAX_ELEMENTS`) values in each of `W` and `Delta`,
/// and `sigma0 = 0`. Linear (LuGre-like) hysteresis: `elements = 0`, `sigma0 > 0`, `W` and
/// `Delta` ignored. `Fc_neg`, `Fs_neg` and `sigma2_neg` of 0 mean "same as `Fc`, `Fs` and
/// `sigma2`" (so a struct written before `sigma2_neg` existed, zero-filled, keeps its meaning; a
/// viscous coefficient of exactly 0 for v < 0 beside a non-zero `sigma2` is given in a parameter
/// file instead).
///
/// Rules (each broken one gives `LEUVEN_RT_INVALID_PARAMETER` and its member's name in
/// `leuven_rt_error.field`): `Fc`, `Fs`, `Vs`, `delta`, `n` (and `Fc_neg`, `Fs_neg`,
/// `sigma0` when used) finite, > 0 and not subnormal; `Fs >= Fc` and `Fs_neg >= Fc_neg`;
/// `sigma1`, `sigma2` (and `sigma2_neg` when used) finite and >= 0; each `W[i]` finite and > 0 and each `Delta[i]`
/// finite and > 0 with `W[i] / Delta[i]` finite (the offending `i` in `error.index`);
/// `sum(W)` finite (field `W`, the index of the largest); the sum of the stiffnesses
/// `W[i] / Delta[i]` finite (field `Delta`, index 0); each `Delta[i]` at least 2^-26 times the
/// largest `Delta`, since narrower windows are lost in the rounding of z (field `Delta`, that
/// index); and `sum(W) > max(Fs, Fs_neg)`, since the elements must be able to balance the
/// Stribeck curve (breaking it reports field `W`, index 0).
///
/// Ownership: the library copies what it needs while `create` or `set_params` runs; `W` and
/// `Delta` may be freed or changed once the call has returned.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct leuven_rt_params {
    /// Coulomb level [N].
    pub Fc: f64,
    /// Static level [N], >= `Fc`.
    pub Fs: f64,
    /// Coulomb level for v < 0 [N]; 0: `Fc`.
    pub Fc_neg: f64,
    /// Static level for v < 0 [N]; 0: `Fs`.
    pub Fs_neg: f64,
    /// Stribeck velocity [m/s].
    pub Vs: f64,
    /// Stribeck shape exponent.
    pub delta: f64,
    /// Transition-curve exponent.
    pub n: f64,
    /// Micro-viscous coefficient [N·s/m].
    pub sigma1: f64,
    /// Viscous coefficient [N·s/m] (for v >= 0 when `sigma2_neg` is given).
    pub sigma2: f64,
    /// Viscous coefficient for v < 0 [N·s/m]; 0: `sigma2`.
    pub sigma2_neg: f64,
    /// Stiffness of linear hysteresis [N/m]; 0 with Maxwell-slip elements.
    pub sigma0: f64,
    /// Saturation forces of the elements [N], `elements` values.
    pub W: *const f64,
    /// Break deflections of the elements [m], `elements` values.
    pub Delta: *const f64,
    /// Number of Maxwell-slip elements; 0 for linear hysteresis.
    pub elements: usize,
}

/// One periodic part of a position-dependent level (docs/model.md#position-dependent-level):
/// the period and `harmonics` relative amplitudes in each of `cos` and `sin` (harmonic k at
/// index k − 1).
///
/// Rules (`LEUVEN_RT_INVALID_PARAMETER`, with the member's name in `leuven_rt_error.field` and
/// the ripple's index in `leuven_rt_error.index`): `period` finite, > 0 and at least 2^20 ulps
/// of max(|middle| + `half_stroke`, 1), the largest position the level covers (a finer period's
/// phase cannot be resolved there); `harmonics` at most `LEUVEN_RT_MAX_HARMONICS`; every
/// amplitude finite. `cos` and `sin` may be null when `harmonics` is 0.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct leuven_rt_ripple {
    /// The period [m or rad].
    pub period: f64,
    /// Amplitudes of cos(2πk·x/period), `harmonics` values (relative to the friction level).
    pub cos: *const f64,
    /// Amplitudes of sin(2πk·x/period), `harmonics` values.
    pub sin: *const f64,
    /// Number of harmonics, 0 to `LEUVEN_RT_MAX_HARMONICS`.
    pub harmonics: usize,
}

/// A friction level that depends on the position (docs/model.md#position-dependent-level):
/// the contact friction is scaled by
/// factor(x) = 1 + t1·p + t2·(1.5·p² − 0.5) + Σ ripples, with p = clip((x − middle) / half stroke, −1, 1),
/// so that the output is factor(x)·(F − sigma2·v) + sigma2·v.
///
/// Rules (`LEUVEN_RT_INVALID_PARAMETER`, the member's name in `leuven_rt_error.field`):
/// `middle` and `trend` finite (`index` says which `trend` entry); `half_stroke` finite, > 0
/// and at least 2^20 ulps of max(|middle| + `half_stroke`, 1) (field `middle` when the middle is
/// so far from 0 that a half stroke resolved about 0 is not resolved there); `ripple_count` at
/// most `LEUVEN_RT_MAX_RIPPLES`; each ripple as in `leuven_rt_ripple`; and |t1| + |t2| + the sum
/// of every |amplitude| below 1, so that the factor is positive everywhere (field "level").
/// `ripples` may be null when `ripple_count` is 0. A level of zeros with no ripples is the flat
/// level: the plain model's output, bit for bit.
///
/// The same struct describes a position force (`leuven_rt_position_force`).
///
/// Ownership: copied while the call runs.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct leuven_rt_level {
    /// Middle of the stroke [m or rad].
    pub middle: f64,
    /// Half the stroke [m or rad], > 0.
    pub half_stroke: f64,
    /// Legendre coefficients (t1, t2) of the trend along the stroke.
    pub trend: [f64; 2],
    /// The ripples, `ripple_count` of them.
    pub ripples: *const leuven_rt_ripple,
    /// Number of ripples, 0 to `LEUVEN_RT_MAX_RIPPLES`.
    pub ripple_count: usize,
}

/// A force that depends on the position alone (docs/model.md#position-dependent-level):
/// cogging, gear mesh, a gravity-like torque along the stroke, added to the output in both
/// directions of motion and not scaled by the level. Its shape is a level's,
/// r(x) = t1·p + t2·(1.5·p² − 0.5) + Σ ripples, but in force units [N or N·m] (the trend and
/// every amplitude), with any finite values: the rules of `leuven_rt_level` without the one on
/// the sum of amplitudes. Zeros with no ripples is no position force.
pub type leuven_rt_position_force = leuven_rt_level;

/// Why a call that takes one was refused. Every function with an `error` argument writes all of
/// it on every return when `error` is not null, whatever the status: on `LEUVEN_RT_OK`,
/// `field` and `message` are "" and `index` is 0.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct leuven_rt_error {
    /// The parameter the status is about, spelled like the member of `leuven_rt_params` (a
    /// static string, never null; "" when the status is not about one parameter).
    pub field: *const c_char,
    /// For `W` and `Delta`: the offending element, or the expected number of elements when the
    /// status is `LEUVEN_RT_INCOMPATIBLE_PARAMS`. 0 otherwise.
    pub index: usize,
    /// A one-line English description of the refusal with the values involved (for
    /// `LEUVEN_RT_INVALID_FILE`, the key or the cause), NUL-terminated, cut to fit.
    pub message: [c_char; LEUVEN_RT_ERROR_MESSAGE_SIZE],
}

/// One axis of friction compensation (opaque).
///
/// Thread safety: a compensator may be created on one thread and used on another, but calls on
/// the same compensator must not overlap (guard it with a lock if several threads share it).
/// Different compensators are independent; `leuven_rt_status_message` may be called from any
/// thread.
pub struct leuven_rt_compensator {
    compensator: Compensator,
}

/// A short English description of `status` (a static string; never null).
#[no_mangle]
pub extern "C" fn leuven_rt_status_message(status: i32) -> *const c_char {
    let message: &'static CStr = match status {
        0 => c"ok",
        1 => c"a pointer argument is null or misaligned",
        2 => c"a parameter breaks its rule (see the error detail)",
        3 => c"dt must be finite and > 0",
        4 => c"mode must be LEUVEN_RT_MODE_FEEDFORWARD or LEUVEN_RT_MODE_OBSERVER",
        5 => c"the input must be finite (and, in observer mode, give a finite velocity)",
        6 => c"the new parameters have another kind or number of elements",
        7 => c"the step produced a non-finite force",
        8 => c"the parameter or model file cannot be read, is not JSON, has another format or version, or a repeated, unknown, missing or mistyped key",
        9 => c"a feedforward compensator needs the axis's start position before a level or a position force",
        _ => c"unknown status",
    };
    message.as_ptr()
}

/// Creates a compensator at rest with sample time `dt` [s]; writes its handle to `*out`.
///
/// `error` may be null; otherwise it is written on every return (see `leuven_rt_error`). On
/// failure `*out` is left as it was. The parameters are copied.
///
/// # Safety
/// `params`, `out` and `error` must each be null or point to a valid object of their type;
/// `params->W` and `params->Delta` must be null or point to `params->elements` doubles.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_create(
    params: *const leuven_rt_params,
    dt: f64,
    mode: i32,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (out, error) = unsafe { (checked_mut(out), checked_mut(error)) };
    let created = out.ok_or_else(|| Refusal::pointer("out")).and_then(|out| {
        let mode = checked_mode(mode)?;
        // SAFETY: as above, for `params` and the arrays it points to.
        let raw = unsafe { raw_params(params) }.ok_or_else(|| Refusal::pointer("params"))?;
        build(&raw, dt, mode, &Terms::default(), out)
    });
    finish(created, error)
}

/// Creates a compensator from the text of a model file (what `leuven-rt identify` writes,
/// version 1 to 3) or of a parameter file (the JSON that `leuven_rt.Params.save` writes): `len`
/// bytes at `json`, UTF-8, no terminating NUL needed. Otherwise as `leuven_rt_compensator_create`.
///
/// The text is read by the reader the Python package uses (the Rust crate gms-file), so both
/// accept and refuse the same texts; docs/data-and-reports.md#model-file lists every key and
/// every refusal. A JSON object with a `format` key is a model file; the compensator takes its
/// `friction`, `level` and `position_force`; `units`, `measurement`, `reconstruction` and
/// `report` are checked but not the compensator's. A plain parameter file reads as a model file
/// of that friction, its keys named `friction.<key>`. A model file with a level or a position
/// force in feedforward mode needs the axis's start position: it gives
/// `LEUVEN_RT_NO_START_POSITION` here, and is read with
/// `leuven_rt_compensator_create_from_json_at`.
///
/// Text that is not JSON, a `format` or `version` this library does not read (a later version
/// says "upgrade leuven-rt"), a key given twice, an unknown or missing key, a value of the wrong
/// type or beyond the f64 range give `LEUVEN_RT_INVALID_FILE`; a value that breaks a rule of the
/// model gives `LEUVEN_RT_INVALID_PARAMETER` and the field, as with the struct. The message
/// starts with the key path (`` `level.ripples[0].period`: ``), or says "not JSON" with the line
/// and column of a syntax error.
///
/// # Safety
/// `json` must be null or point to `len` readable bytes; `out` and `error` as in
/// `leuven_rt_compensator_create`.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_create_from_json(
    json: *const c_char,
    len: usize,
    dt: f64,
    mode: i32,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller's contract is this function's.
    unsafe { create_from_json(json, len, dt, mode, None, out, error) }
}

/// `leuven_rt_compensator_create_from_json` with the axis's start position `x` [m or rad]:
/// where a feedforward compensator places the model file's level from (it then integrates the
/// desired velocity, or takes the positions of `leuven_rt_compensator_step_trajectory`).
/// Observer mode takes the position from its input. A non-finite `x` gives
/// `LEUVEN_RT_NOT_FINITE_INPUT` (field `x`).
///
/// # Safety
/// As `leuven_rt_compensator_create_from_json`.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_create_from_json_at(
    json: *const c_char,
    len: usize,
    dt: f64,
    mode: i32,
    x: f64,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller's contract is this function's.
    unsafe { create_from_json(json, len, dt, mode, Some(x), out, error) }
}

/// Creates a compensator from a model file or parameter file at `path` (a NUL-terminated file
/// name), as `leuven_rt_compensator_create_from_json` does with its text. A file that cannot be
/// read (missing, not a regular file, larger than 1 MiB, not UTF-8) gives
/// `LEUVEN_RT_INVALID_FILE` with the reason in `error->message`.
///
/// # Safety
/// `path` must be null or a NUL-terminated string; `out` and `error` as in
/// `leuven_rt_compensator_create`.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_create_from_file(
    path: *const c_char,
    dt: f64,
    mode: i32,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller's contract is this function's.
    unsafe { create_from_path(path, dt, mode, None, out, error) }
}

/// `leuven_rt_compensator_create_from_file` with the axis's start position `x`, as
/// `leuven_rt_compensator_create_from_json_at`.
///
/// # Safety
/// As `leuven_rt_compensator_create_from_file`.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_create_from_file_at(
    path: *const c_char,
    dt: f64,
    mode: i32,
    x: f64,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller's contract is this function's.
    unsafe { create_from_path(path, dt, mode, Some(x), out, error) }
}

/// Destroys a compensator made by `leuven_rt_compensator_create`. Null is ignored.
///
/// # Safety
/// `compensator` must be null or a handle from `leuven_rt_compensator_create` that has not
/// been destroyed.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_destroy(compensator: *mut leuven_rt_compensator) {
    if compensator.is_null() || !compensator.is_aligned() {
        return;
    }
    // SAFETY: a live handle is a pointer from Box::into_raw in create, given back once.
    drop(unsafe { Box::from_raw(compensator) });
}

/// One sample: the friction force to add to the command, written to `*force`.
///
/// `input` is the desired velocity [m/s] (feedforward) or the measured position [m]
/// (observer). On `LEUVEN_RT_NOT_FINITE_INPUT` or `LEUVEN_RT_STEP_FAILED`, `*force` receives
/// the last good force (0 before the first), which is finite, and the state is unchanged. On
/// `LEUVEN_RT_INVALID_POINTER` with a valid `force`, `*force` receives 0.
///
/// # Safety
/// `compensator` must be null or a live handle; `force` null or valid.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_step(
    compensator: *mut leuven_rt_compensator,
    input: f64,
    force: *mut f64,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (compensator, force) = unsafe { (checked_mut(compensator), checked_mut(force)) };
    let Some(force) = force else {
        return LEUVEN_RT_INVALID_POINTER;
    };
    let Some(compensator) = compensator else {
        *force = 0.0;
        return LEUVEN_RT_INVALID_POINTER;
    };
    let result = compensator.compensator.step(input);
    stepped(&compensator.compensator, result, force)
}

/// One sample of a planned trajectory: the desired velocity `v` [m/s] drives the model and the
/// desired position `x` [m] places the level and the position force, so that a loop that knows
/// its position does not integrate the velocity; the friction force is written to `*force`. In
/// feedforward mode `x` becomes the compensator's position; in observer mode (a measured
/// velocity beside the measured position) the previous position of the next step. Statuses and
/// `*force` as in `leuven_rt_compensator_step` (a non-finite `v` or `x` gives
/// `LEUVEN_RT_NOT_FINITE_INPUT`).
///
/// # Safety
/// `compensator` must be null or a live handle; `force` null or valid.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_step_trajectory(
    compensator: *mut leuven_rt_compensator,
    v: f64,
    x: f64,
    force: *mut f64,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (compensator, force) = unsafe { (checked_mut(compensator), checked_mut(force)) };
    let Some(force) = force else {
        return LEUVEN_RT_INVALID_POINTER;
    };
    let Some(compensator) = compensator else {
        *force = 0.0;
        return LEUVEN_RT_INVALID_POINTER;
    };
    let result = compensator.compensator.step_trajectory(v, x);
    stepped(&compensator.compensator, result, force)
}

/// The status of a step, with the force (or the last good one) written.
fn stepped(
    compensator: &Compensator,
    result: Result<f64, Error>,
    force: &mut f64,
) -> leuven_rt_status {
    match result {
        Ok(value) => {
            *force = value;
            LEUVEN_RT_OK
        }
        Err(error) => {
            *force = compensator.output();
            match error {
                Error::NotFinite { .. } | Error::VelocityNotFinite { .. } => {
                    LEUVEN_RT_NOT_FINITE_INPUT
                }
                _ => LEUVEN_RT_STEP_FAILED,
            }
        }
    }
}

/// Swaps in new parameters between two samples. The hysteresis force carries over, so the
/// output has no jump. The new set must have the same kind of hysteresis and number of
/// elements (`LEUVEN_RT_INCOMPATIBLE_PARAMS` otherwise, with the expected count in
/// `error->index`). Does not allocate; `error`, if not null, is written on every return.
///
/// # Safety
/// As `leuven_rt_compensator_create` for `params` and `error`; `compensator` null or live.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_set_params(
    compensator: *mut leuven_rt_compensator,
    params: *const leuven_rt_params,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (compensator, error) = unsafe { (checked_mut(compensator), checked_mut(error)) };
    let swapped = compensator
        .ok_or_else(|| Refusal::pointer("compensator"))
        .and_then(|compensator| {
            // SAFETY: as above, for `params` and the arrays it points to.
            let raw = unsafe { raw_params(params) }.ok_or_else(|| Refusal::pointer("params"))?;
            compensator
                .compensator
                .set_raw_params(&raw)
                .map_err(Refusal::from_dyn)
        });
    finish(swapped, error)
}

/// Back to rest: relaxed state, no previous position, output 0.
///
/// # Safety
/// `compensator` must be null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_reset(
    compensator: *mut leuven_rt_compensator,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or a valid pointer (the function's contract).
    match unsafe { checked_mut(compensator) } {
        Some(compensator) => {
            compensator.compensator.reset();
            LEUVEN_RT_OK
        }
        None => LEUVEN_RT_INVALID_POINTER,
    }
}

/// Gives the compensator a position-dependent level (see `leuven_rt_level`), replacing the one it
/// had; the model state carries over and the next step's output uses the new level. In
/// feedforward mode the level is evaluated at the position integrated from the desired
/// velocity (or given to `leuven_rt_compensator_step_trajectory`), from the axis's start
/// position: without one (`leuven_rt_compensator_set_position`) a level that is not flat gives
/// `LEUVEN_RT_NO_START_POSITION`. Does not allocate; `error`, if not null, is written on every
/// return.
///
/// # Safety
/// `compensator` null or live; `level` null or valid, with `level->ripples` null or pointing to
/// `level->ripple_count` ripples, and each ripple's `cos` and `sin` null or pointing to its
/// `harmonics` doubles; `error` null or valid.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_set_level(
    compensator: *mut leuven_rt_compensator,
    level: *const leuven_rt_level,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (compensator, error) = unsafe { (checked_mut(compensator), checked_mut(error)) };
    let set = compensator
        .ok_or_else(|| Refusal::pointer("compensator"))
        .and_then(|compensator| {
            // SAFETY: as above, for `level` and the arrays it points to.
            let level = unsafe { c_series(level, "level", Level::new) }?;
            compensator
                .compensator
                .set_level(&level)
                .map_err(|reason| Refusal::from_dyn(reason.into()))
        });
    finish(set, error)
}

/// Gives the compensator a position force (see `leuven_rt_position_force`), replacing the one it
/// had, as `leuven_rt_compensator_set_level` does with a level: the next step's output adds
/// r(x). Does not allocate; `error`, if not null, is written on every return.
///
/// # Safety
/// As `leuven_rt_compensator_set_level`, for `force`.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_set_position_force(
    compensator: *mut leuven_rt_compensator,
    force: *const leuven_rt_position_force,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (compensator, error) = unsafe { (checked_mut(compensator), checked_mut(error)) };
    let set = compensator
        .ok_or_else(|| Refusal::pointer("compensator"))
        .and_then(|compensator| {
            // SAFETY: as above, for `force` and the arrays it points to.
            let force = unsafe { c_series(force, "force", PositionForce::new) }?;
            compensator
                .compensator
                .set_position_force(&force)
                .map_err(|reason| Refusal::from_dyn(reason.into()))
        });
    finish(set, error)
}

/// Sets the axis's position [m or rad], from which feedforward mode integrates the desired
/// velocity (x ← x + v·dt each step) to place the level and the position force; unknown until
/// set, and needed before either is given. Observer mode takes the position from its input and
/// does not read it. A non-finite `x` gives `LEUVEN_RT_NOT_FINITE_INPUT` and changes nothing.
///
/// # Safety
/// `compensator` must be null or a live handle.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_set_position(
    compensator: *mut leuven_rt_compensator,
    x: f64,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or a valid pointer (the function's contract).
    match unsafe { checked_mut(compensator) } {
        Some(compensator) => match compensator.compensator.set_position(x) {
            Ok(()) => LEUVEN_RT_OK,
            Err(_) => LEUVEN_RT_NOT_FINITE_INPUT,
        },
        None => LEUVEN_RT_INVALID_POINTER,
    }
}

/// The last force returned by a successful step (0 before the first), written to `*force`.
///
/// # Safety
/// `compensator` must be null or a live handle; `force` null or valid.
#[no_mangle]
pub unsafe extern "C" fn leuven_rt_compensator_output(
    compensator: *const leuven_rt_compensator,
    force: *mut f64,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    match unsafe { (checked(compensator), checked_mut(force)) } {
        (Some(compensator), Some(force)) => {
            *force = compensator.compensator.output();
            LEUVEN_RT_OK
        }
        _ => LEUVEN_RT_INVALID_POINTER,
    }
}

/// `pointer` as a reference, or `None` if it is null or misaligned.
///
/// # Safety
/// A non-null, aligned `pointer` must point to a valid `T` that nothing else mutates for `'a`.
unsafe fn checked<'a, T>(pointer: *const T) -> Option<&'a T> {
    if pointer.is_aligned() {
        // SAFETY: aligned here; valid or null by the caller's contract; as_ref maps null to None.
        unsafe { pointer.as_ref() }
    } else {
        None
    }
}

/// `pointer` as a mutable reference, or `None` if it is null or misaligned.
///
/// # Safety
/// A non-null, aligned `pointer` must point to a valid `T` that nothing else accesses for `'a`.
unsafe fn checked_mut<'a, T>(pointer: *mut T) -> Option<&'a mut T> {
    if pointer.is_aligned() {
        // SAFETY: as in `checked`.
        unsafe { pointer.as_mut() }
    } else {
        None
    }
}

/// `count` doubles at `pointer` (count 0: empty, whatever the pointer), or `None` if the
/// pointer is null or misaligned, or the count is too large to be an array.
///
/// # Safety
/// A non-null, aligned `pointer` must point to `count` doubles that nothing mutates for `'a`.
unsafe fn array<'a>(pointer: *const f64, count: usize) -> Option<&'a [f64]> {
    if count == 0 {
        return Some(&[]);
    }
    // More than LEUVEN_RT_MAX_ELEMENTS is refused later with a parameter error; the cap here only keeps
    // the slice within what from_raw_parts allows, whatever count comes.
    let count = count.min(LEUVEN_RT_MAX_ELEMENTS + 1);
    if pointer.is_null() || !pointer.is_aligned() {
        return None;
    }
    // SAFETY: non-null and aligned here; `count` valid doubles by the caller's contract (the
    // cap only shortens the slice); count·8 bytes is far below isize::MAX.
    Some(unsafe { core::slice::from_raw_parts(pointer, count) })
}

/// The caller's level or position force (`name`), validated by gms-core through `build`
/// ([`Level::new`] or [`PositionForce::new`]); a null or misaligned pointer (the struct, its
/// ripples, or a ripple's amplitudes) is refused.
///
/// Counts beyond the maxima are refused before any array is read past them.
///
/// # Safety
/// As [`checked`] for `level`; its `ripples` must point to `ripple_count` ripples and each
/// ripple's `cos` and `sin` to `harmonics` doubles (read only up to the maxima + 1).
unsafe fn c_series<T>(
    level: *const leuven_rt_level,
    name: &str,
    build: impl FnOnce(f64, f64, [f64; 2], &[RippleTerms<'_>]) -> Result<T, Error>,
) -> Result<T, Refusal> {
    // SAFETY: passed on from the caller's contract.
    let level = unsafe { checked(level) }.ok_or_else(|| Refusal::pointer(name))?;
    let count = level.ripple_count.min(MAX_RIPPLES + 1);
    let c_ripples: &[leuven_rt_ripple] = if count == 0 {
        &[]
    } else if level.ripples.is_null() || !level.ripples.is_aligned() {
        return Err(Refusal::pointer(format_args!("{name}->ripples")));
    } else {
        // SAFETY: non-null and aligned; `ripple_count` valid ripples by the caller's contract,
        // of which at most MAX_RIPPLES + 1 are read.
        unsafe { core::slice::from_raw_parts(level.ripples, count) }
    };
    let mut terms = [RippleTerms {
        period: 1.0,
        cos: &[],
        sin: &[],
    }; MAX_RIPPLES + 1];
    for (ripple, slot) in c_ripples.iter().zip(terms.iter_mut()) {
        let harmonics = ripple.harmonics.min(MAX_HARMONICS + 1);
        // SAFETY: passed on from the caller's contract.
        let (cos, sin) = unsafe { (array(ripple.cos, harmonics), array(ripple.sin, harmonics)) };
        let (Some(cos), Some(sin)) = (cos, sin) else {
            return Err(Refusal::pointer(format_args!(
                "{name}->ripples[i].cos or .sin"
            )));
        };
        *slot = RippleTerms {
            period: ripple.period,
            cos,
            sin,
        };
    }
    build(
        level.middle,
        level.half_stroke,
        level.trend,
        &terms[..c_ripples.len()],
    )
    .map_err(|reason| Refusal::from_dyn(reason.into()))
}

/// The caller's parameters as plain values, or `None` for a null or misaligned pointer.
///
/// `elements = 0` means linear hysteresis `sigma0`; otherwise a non-zero `sigma0` is given
/// alongside the elements (and refused by validation). `Fc_neg` and `Fs_neg` of 0 mean "same
/// as `Fc` and `Fs`". With more than `LEUVEN_RT_MAX_ELEMENTS` elements, only
/// `LEUVEN_RT_MAX_ELEMENTS + 1` values are read, which is enough to refuse the count.
///
/// # Safety
/// As [`checked`] for `params`, and as [`array`] for its `W` and `Delta`.
unsafe fn raw_params<'a>(params: *const leuven_rt_params) -> Option<RawParams<'a>> {
    // SAFETY: passed on from the caller's contract.
    let params = unsafe { checked(params) }?;
    // SAFETY: passed on from the caller's contract.
    let (w, delta) = unsafe {
        (
            array(params.W, params.elements)?,
            array(params.Delta, params.elements)?,
        )
    };
    let or = |value: f64, default: f64| if value == 0.0 { default } else { value };
    let linear = params.elements == 0;
    Some(RawParams {
        fc: params.Fc,
        fs: params.Fs,
        vs: params.Vs,
        delta: params.delta,
        n: params.n,
        sigma1: params.sigma1,
        sigma2: params.sigma2,
        fc_neg: or(params.Fc_neg, params.Fc),
        fs_neg: or(params.Fs_neg, params.Fs),
        sigma2_neg: (params.sigma2_neg != 0.0).then_some(params.sigma2_neg),
        sigma0: (linear || params.sigma0 != 0.0).then_some(params.sigma0),
        elements: (!linear).then_some(RawElements { w, delta }),
    })
}

/// A refused call: its status, the field and index of `leuven_rt_error` and the message,
/// formatted into a fixed buffer (no allocation, so that `set_params` stays allocation-free).
struct Refusal {
    status: leuven_rt_status,
    field: &'static CStr,
    index: usize,
    message: Message,
}

impl Refusal {
    fn new(
        status: leuven_rt_status,
        field: &'static CStr,
        index: usize,
        message: fmt::Arguments<'_>,
    ) -> Self {
        let mut buffer = Message::default();
        // Message::write_str never fails; a long message is cut.
        let _ = buffer.write_fmt(message);
        Refusal {
            status,
            field,
            index,
            message: buffer,
        }
    }

    /// A null or misaligned pointer argument.
    fn pointer(argument: impl fmt::Display) -> Self {
        Refusal::new(
            LEUVEN_RT_INVALID_POINTER,
            c"",
            0,
            format_args!("the pointer `{argument}` is null or misaligned"),
        )
    }

    /// A refused parameter set (or `dt`).
    fn from_dyn(reason: gms_dyn::Error) -> Self {
        let (status, field, index) = Refusal::sort(reason);
        Refusal::new(status, field, index, format_args!("{reason}"))
    }

    /// A refused model file or parameter file: a value that breaks a rule of the model gives
    /// the status, field and index of that rule (as the struct's would), anything else
    /// `LEUVEN_RT_INVALID_FILE`; the message names the key path.
    fn from_file(reason: &FileError) -> Self {
        let (status, field, index) = match reason.rule() {
            Some(rule) => Refusal::sort(rule),
            None => (LEUVEN_RT_INVALID_FILE, c"", 0),
        };
        Refusal::new(status, field, index, format_args!("{reason}"))
    }

    /// The status, the field and the index of a refusal of gms-dyn.
    fn sort(reason: gms_dyn::Error) -> (leuven_rt_status, &'static CStr, usize) {
        use gms_dyn::Error as Refused;
        match reason {
            Refused::Core(Error::NotPositive {
                field: Field::dt, ..
            }) => (LEUVEN_RT_INVALID_DT, c"dt", 0),
            Refused::Core(
                Error::Element { field, index, .. } | Error::PhaseUnresolved { field, index, .. },
            ) => (LEUVEN_RT_INVALID_PARAMETER, field_name(field), index),
            Refused::Core(
                Error::NotPositive { field, .. }
                | Error::Negative { field, .. }
                | Error::StaticBelowCoulomb { field, .. },
            ) => (LEUVEN_RT_INVALID_PARAMETER, field_name(field), 0),
            Refused::Core(Error::NotFiniteValue {
                field: Field::middle,
                ..
            }) => (LEUVEN_RT_INVALID_PARAMETER, c"middle", 0),
            Refused::Core(Error::NotFinite {
                field: Field::trend,
                index,
                ..
            }) => (LEUVEN_RT_INVALID_PARAMETER, c"trend", index),
            Refused::Core(Error::TooManyRipples { .. }) => {
                (LEUVEN_RT_INVALID_PARAMETER, c"ripple_count", 0)
            }
            Refused::Core(Error::RipplePeriod { ripple, .. }) => {
                (LEUVEN_RT_INVALID_PARAMETER, c"period", ripple)
            }
            Refused::Core(
                Error::TooManyHarmonics { ripple, .. } | Error::HarmonicLengths { ripple, .. },
            ) => (LEUVEN_RT_INVALID_PARAMETER, c"harmonics", ripple),
            Refused::Core(Error::RippleCoefficient { field, ripple, .. }) => {
                (LEUVEN_RT_INVALID_PARAMETER, field_name(field), ripple)
            }
            Refused::Core(Error::LevelTooDeep { .. }) => (LEUVEN_RT_INVALID_PARAMETER, c"level", 0),
            Refused::Core(Error::Missing { field }) => {
                (LEUVEN_RT_NO_START_POSITION, field_name(field), 0)
            }
            Refused::Core(Error::NotFiniteValue {
                field: Field::x, ..
            }) => (LEUVEN_RT_NOT_FINITE_INPUT, c"x", 0),
            Refused::Core(Error::ForceSumOverflow { index, .. }) => {
                (LEUVEN_RT_INVALID_PARAMETER, c"W", index)
            }
            Refused::Core(
                Error::StiffnessOverflow { index, .. } | Error::DeltaTooNarrow { index, .. },
            ) => (LEUVEN_RT_INVALID_PARAMETER, c"Delta", index),
            Refused::Core(Error::StiffnessSumOverflow) => {
                (LEUVEN_RT_INVALID_PARAMETER, c"Delta", 0)
            }
            // sum(W) <= max(Fs, Fs_neg): the elements are too weak.
            Refused::Core(Error::ElementsTooWeak { .. }) => (LEUVEN_RT_INVALID_PARAMETER, c"W", 0),
            Refused::BothHysteresis | Refused::NeitherHysteresis => {
                (LEUVEN_RT_INVALID_PARAMETER, c"sigma0", 0)
            }
            Refused::EmptyElements
            | Refused::TooManyElements { .. }
            | Refused::ElementLengths { .. } => (LEUVEN_RT_INVALID_PARAMETER, c"elements", 0),
            Refused::Incompatible { expected, .. } => (
                LEUVEN_RT_INCOMPATIBLE_PARAMS,
                c"elements",
                match expected {
                    HysteresisKind::Linear => 0,
                    HysteresisKind::Maxwell { elements } => elements,
                },
            ),
            _ => (LEUVEN_RT_INVALID_PARAMETER, c"", 0),
        }
    }
}

/// A NUL-terminated message of at most `LEUVEN_RT_ERROR_MESSAGE_SIZE` bytes, cut at a character
/// boundary.
struct Message {
    bytes: [u8; LEUVEN_RT_ERROR_MESSAGE_SIZE],
    len: usize,
}

impl Default for Message {
    fn default() -> Self {
        Message {
            bytes: [0; LEUVEN_RT_ERROR_MESSAGE_SIZE],
            len: 0,
        }
    }
}

impl fmt::Write for Message {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        for character in text.chars() {
            let mut utf8 = [0; 4];
            let encoded = character.encode_utf8(&mut utf8).as_bytes();
            // One byte stays for the NUL; an interior NUL would cut the C string, so it is
            // written as a space.
            if self.len + encoded.len() >= LEUVEN_RT_ERROR_MESSAGE_SIZE {
                break;
            }
            for &byte in encoded {
                self.bytes[self.len] = if byte == 0 { b' ' } else { byte };
                self.len += 1;
            }
        }
        Ok(())
    }
}

/// The work of `leuven_rt_compensator_create_from_json` and `_at`: `x` is the start position
/// (`None` without one).
///
/// # Safety
/// As `leuven_rt_compensator_create_from_json`.
unsafe fn create_from_json(
    json: *const c_char,
    len: usize,
    dt: f64,
    mode: i32,
    x: Option<f64>,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (out, error) = unsafe { (checked_mut(out), checked_mut(error)) };
    let created = out.ok_or_else(|| Refusal::pointer("out")).and_then(|out| {
        let mode = checked_mode(mode)?;
        if json.is_null() || len > isize::MAX as usize {
            return Err(Refusal::pointer("json"));
        }
        // SAFETY: non-null, `len` readable bytes by the caller's contract; bytes need no
        // alignment.
        let text = unsafe { core::slice::from_raw_parts(json.cast::<u8>(), len) };
        let file = ModelFile::from_slice(text).map_err(|reason| Refusal::from_file(&reason))?;
        from_file(&file, dt, mode, x, out)
    });
    finish(created, error)
}

/// The work of `leuven_rt_compensator_create_from_file` and `_at`: `x` is the start position
/// (`None` without one).
///
/// # Safety
/// As `leuven_rt_compensator_create_from_file`.
unsafe fn create_from_path(
    path: *const c_char,
    dt: f64,
    mode: i32,
    x: Option<f64>,
    out: *mut *mut leuven_rt_compensator,
    error: *mut leuven_rt_error,
) -> leuven_rt_status {
    // SAFETY: the caller passes null or valid pointers (the function's contract).
    let (out, error) = unsafe { (checked_mut(out), checked_mut(error)) };
    let created = out.ok_or_else(|| Refusal::pointer("out")).and_then(|out| {
        let mode = checked_mode(mode)?;
        if path.is_null() {
            return Err(Refusal::pointer("path"));
        }
        // SAFETY: non-null and NUL-terminated by the caller's contract.
        let path = unsafe { CStr::from_ptr(path) };
        let path = std::path::Path::new(path.to_str().map_err(|_| {
            Refusal::new(
                LEUVEN_RT_INVALID_FILE,
                c"",
                0,
                format_args!("the path is not UTF-8"),
            )
        })?);
        let file = ModelFile::load(path).map_err(|reason| Refusal::from_file(&reason))?;
        from_file(&file, dt, mode, x, out)
    });
    finish(created, error)
}

/// The status of a call, with `error` (if given) written for every status.
fn finish(result: Result<(), Refusal>, error: Option<&mut leuven_rt_error>) -> leuven_rt_status {
    let (status, field, index, message) = match result {
        Ok(()) => (LEUVEN_RT_OK, c"", 0, [0; LEUVEN_RT_ERROR_MESSAGE_SIZE]),
        Err(refusal) => (
            refusal.status,
            refusal.field,
            refusal.index,
            refusal.message.bytes,
        ),
    };
    if let Some(error) = error {
        error.field = field.as_ptr();
        error.index = index;
        for (to, from) in error.message.iter_mut().zip(message) {
            *to = c_char::from_ne_bytes([from]);
        }
    }
    status
}

/// `mode` as gms-core's, or `LEUVEN_RT_INVALID_MODE`.
fn checked_mode(mode: i32) -> Result<Mode, Refusal> {
    match mode {
        LEUVEN_RT_MODE_FEEDFORWARD => Ok(Mode::Feedforward),
        LEUVEN_RT_MODE_OBSERVER => Ok(Mode::Observer),
        _ => Err(Refusal::new(
            LEUVEN_RT_INVALID_MODE,
            c"",
            0,
            format_args!(
                "mode {mode} is neither LEUVEN_RT_MODE_FEEDFORWARD (0) nor LEUVEN_RT_MODE_OBSERVER (1)"
            ),
        )),
    }
}

/// Validates `raw`, builds the compensator with `terms` and writes its handle to `*out`.
fn build(
    raw: &RawParams<'_>,
    dt: f64,
    mode: Mode,
    terms: &Terms,
    out: &mut *mut leuven_rt_compensator,
) -> Result<(), Refusal> {
    let compensator = raw
        .validate()
        .and_then(|set| Compensator::with_terms(&set, dt, mode, terms))
        .map_err(Refusal::from_dyn)?;
    *out = Box::into_raw(Box::new(leuven_rt_compensator { compensator }));
    Ok(())
}

/// Builds the compensator from a read model file (or parameter file), starting at `start` if
/// given: every value validated, each refusal naming its key.
fn from_file(
    file: &ModelFile,
    dt: f64,
    mode: Mode,
    start: Option<f64>,
    out: &mut *mut leuven_rt_compensator,
) -> Result<(), Refusal> {
    let model = file
        .validate()
        .map_err(|reason| Refusal::from_file(&reason))?;
    let terms = Terms {
        start,
        level: model.level,
        position_force: model.position_force,
    };
    let compensator =
        Compensator::with_terms(&model.params, dt, mode, &terms).map_err(Refusal::from_dyn)?;
    *out = Box::into_raw(Box::new(leuven_rt_compensator { compensator }));
    Ok(())
}

/// The member of `leuven_rt_params` that holds `field`.
fn field_name(field: Field) -> &'static CStr {
    match field {
        Field::Fc => c"Fc",
        Field::Fs => c"Fs",
        Field::Vs => c"Vs",
        Field::delta => c"delta",
        Field::n => c"n",
        Field::sigma0 => c"sigma0",
        Field::sigma1 => c"sigma1",
        Field::sigma2 => c"sigma2",
        Field::W => c"W",
        Field::Delta => c"Delta",
        Field::Fc_neg => c"Fc_neg",
        Field::Fs_neg => c"Fs_neg",
        Field::sigma2_neg => c"sigma2_neg",
        Field::dt => c"dt",
        Field::x => c"x",
        Field::period => c"period",
        Field::middle => c"middle",
        Field::half_stroke => c"half_stroke",
        Field::trend => c"trend",
        Field::cos => c"cos",
        Field::sin => c"sin",
        _ => c"",
    }
}
