//! The kernel compiled twice, for the baseline instruction set of the target and, on x86-64,
//! for AVX2 and FMA, chosen at run time: one build is fast on every CPU.
//!
//! The lane loops are plain array code; the compiler vectorizes them for the instruction set of
//! the function they are inlined into. The AVX2 copy is that same generic code inlined into a
//! `#[target_feature(enable = "avx2,fma")]` function. Rust never contracts a multiply and an
//! add into an FMA on its own, so the AVX2 copy rounds exactly as the baseline one (and as
//! gms-core): the feature only widens the registers.

use crate::kernel::{run, Group, Rejected};
use crate::lanes::BatchHysteresis;

/// An instruction-set path of the kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Path {
    /// The target's baseline (SSE2 on x86-64): always available.
    Baseline,
    /// AVX2 and FMA (x86-64 only), where the CPU has them.
    Avx2Fma,
}

impl Path {
    /// The fastest path this CPU runs.
    pub fn detected() -> Path {
        if avx2_fma() {
            Path::Avx2Fma
        } else {
            Path::Baseline
        }
    }

    /// The paths this CPU runs: the baseline, and the detected one where it is another (what the
    /// tests and benchmarks compare).
    pub fn available() -> &'static [Path] {
        match Path::detected() {
            Path::Baseline => &[Path::Baseline],
            Path::Avx2Fma => &[Path::Baseline, Path::Avx2Fma],
        }
    }

    /// The path's name, for benchmark reports: "baseline" or "avx2+fma".
    pub fn name(self) -> &'static str {
        match self {
            Path::Baseline => "baseline",
            Path::Avx2Fma => "avx2+fma",
        }
    }
}

/// Whether the CPU has AVX2 and FMA (the standard library caches the answer).
#[cfg(target_arch = "x86_64")]
fn avx2_fma() -> bool {
    std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
}

#[cfg(not(target_arch = "x86_64"))]
fn avx2_fma() -> bool {
    false
}

/// Runs one group on `path`; a path the CPU lacks runs the baseline instead.
pub(crate) fn run_group<H: BatchHysteresis, const L: usize>(
    path: Path,
    group: Group<'_, H>,
) -> Result<(), Rejected> {
    #[cfg(target_arch = "x86_64")]
    if path == Path::Avx2Fma && avx2_fma() {
        // SAFETY: `run_avx2` only requires the CPU features it is compiled for, AVX2 and FMA,
        // and the CPU has just been found to have both.
        #[allow(unsafe_code)]
        return unsafe { run_avx2::<H, L>(group) };
    }
    let _ = path;
    run_baseline::<H, L>(group)
}

#[inline(never)]
fn run_baseline<H: BatchHysteresis, const L: usize>(group: Group<'_, H>) -> Result<(), Rejected> {
    run::<H, L>(group)
}

/// The kernel inlined into a function compiled for AVX2 and FMA.
///
/// # Safety
/// The CPU must have AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
#[allow(unsafe_code)] // an `unsafe fn` only because of its target features (Rust 1.85)
unsafe fn run_avx2<H: BatchHysteresis, const L: usize>(
    group: Group<'_, H>,
) -> Result<(), Rejected> {
    run::<H, L>(group)
}
