//! The columns of the Jacobian: which parameter each one differentiates by, and its name.
//!
//! The order is always the asymmetric parameterisation, so that a caller fitting a symmetric
//! model ties the columns it wants: a symmetric set uses `Fc` on v ≥ 0 steps and the same value
//! as `Fc_neg` on v < 0 steps, so d/dFc of the symmetric model is the sum of the `Fc` and
//! `Fc_neg` columns; the same holds for `Fs` and `sigma2`.

use gms_dyn::HysteresisKind;

/// The columns every parameter set has, before those of its hysteresis.
pub const SHARED_COLUMNS: usize = 10;

/// The names of the shared columns, in their order.
pub const SHARED_NAMES: [&str; SHARED_COLUMNS] = [
    "Fc",
    "Fs",
    "Vs",
    "delta",
    "n",
    "sigma1",
    "sigma2",
    "Fc_neg",
    "Fs_neg",
    "sigma2_neg",
];

/// Coulomb level for v ≥ 0.
pub(crate) const FC: usize = 0;
/// Static level for v ≥ 0.
pub(crate) const FS: usize = 1;
/// Stribeck velocity.
pub(crate) const VS: usize = 2;
/// Stribeck shape exponent δ.
pub(crate) const DELTA: usize = 3;
/// Transition exponent n.
pub(crate) const N: usize = 4;
/// Micro-viscous coefficient σ1.
pub(crate) const SIGMA1: usize = 5;
/// Viscous coefficient for v ≥ 0.
pub(crate) const SIGMA2: usize = 6;
/// Coulomb level for v < 0.
pub(crate) const FC_NEG: usize = 7;
/// Static level for v < 0.
pub(crate) const FS_NEG: usize = 8;
/// Viscous coefficient for v < 0.
pub(crate) const SIGMA2_NEG: usize = 9;

/// The number of columns P of a parameter set of this kind: the shared ones, then `W[0]` to
/// `W[N-1]` for Maxwell slip, or `sigma0` for a linear spring.
pub fn column_count(kind: HysteresisKind) -> usize {
    match kind {
        HysteresisKind::Linear => SHARED_COLUMNS + 1,
        HysteresisKind::Maxwell { elements } => SHARED_COLUMNS + elements,
    }
}

/// The name of every column, in order: [`SHARED_NAMES`], then `W[i]` (the i-th weight of the
/// parameter file's `W`) or `sigma0`.
pub fn column_names(kind: HysteresisKind) -> Vec<String> {
    let shared = SHARED_NAMES.iter().map(|name| (*name).to_owned());
    match kind {
        HysteresisKind::Linear => shared.chain(["sigma0".to_owned()]).collect(),
        HysteresisKind::Maxwell { elements } => shared
            .chain((0..elements).map(|index| format!("W[{index}]")))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_counts_agree() {
        let constants = [
            (FC, "Fc"),
            (FS, "Fs"),
            (VS, "Vs"),
            (DELTA, "delta"),
            (N, "n"),
            (SIGMA1, "sigma1"),
            (SIGMA2, "sigma2"),
            (FC_NEG, "Fc_neg"),
            (FS_NEG, "Fs_neg"),
            (SIGMA2_NEG, "sigma2_neg"),
        ];
        for (index, name) in constants {
            assert_eq!(SHARED_NAMES[index], name);
        }
        let maxwell = HysteresisKind::Maxwell { elements: 3 };
        assert_eq!(column_names(maxwell).len(), column_count(maxwell));
        assert_eq!(column_names(maxwell)[12], "W[2]");
        assert_eq!(
            column_names(HysteresisKind::Linear),
            [&SHARED_NAMES[..], &["sigma0"]].concat()
        );
    }
}
