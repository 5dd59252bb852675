//! Every `Error` variant has a kind, its name in snake case, which the bindings hand on as the
//! error's `kind` (docs/errors.md#kinds); `Error::KINDS` lists them all, once each.

use gms_core::{Error, Field};

#[test]
fn kinds_are_the_variant_names_in_snake_case() {
    let cases = [
        (
            Error::NotFinite {
                field: Field::v,
                index: 3,
                value: f64::NAN,
            },
            "not_finite",
        ),
        (
            Error::NotFiniteValue {
                field: Field::middle,
                value: f64::INFINITY,
            },
            "not_finite_value",
        ),
        (
            Error::ElementsTooWeak {
                sum: 1.0,
                peak: 1.5,
            },
            "elements_too_weak",
        ),
        (
            Error::StaticBelowCoulomb {
                field: Field::Fs,
                coulomb: 1.0,
                value: 0.5,
            },
            "static_below_coulomb",
        ),
        (Error::StiffnessSumOverflow, "stiffness_sum_overflow"),
        (Error::Diverged { index: 7 }, "diverged"),
        (
            Error::PhaseUnresolved {
                field: Field::period,
                index: 0,
                value: 1e-12,
                extent: 1.0,
            },
            "phase_unresolved",
        ),
        (Error::Missing { field: Field::x }, "missing"),
    ];
    for (error, kind) in cases {
        assert_eq!(error.kind(), kind);
        assert!(Error::KINDS.contains(&kind), "{kind}");
    }
}

#[test]
fn every_kind_is_listed_once_and_spelled_in_snake_case() {
    let mut kinds = Error::KINDS.to_vec();
    assert!(kinds.len() >= 29, "{kinds:?}");
    for kind in &kinds {
        assert!(
            kind.chars().all(|c| c.is_ascii_lowercase() || c == '_') && !kind.starts_with('_'),
            "{kind}"
        );
    }
    kinds.sort_unstable();
    kinds.dedup();
    assert_eq!(kinds.len(), Error::KINDS.len());
}
