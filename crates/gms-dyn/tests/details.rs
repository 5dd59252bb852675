//! `Error::details()`: the data of an error (kind, field, value, …) as plain values, which the
//! Python bindings attach to their exceptions without reading the message (docs/errors.md#error-data).

use gms_core::{Field, InChannel};
use gms_dyn::{Details, Error, HysteresisKind, Location, Number, RawElements, RawParams};

fn raw<'a>(w: &'a [f64], delta: &'a [f64]) -> RawParams<'a> {
    RawParams {
        fc: 1.0,
        fs: 1.5,
        vs: 1e-3,
        delta: 2.0,
        n: 2.0,
        sigma1: 0.0,
        sigma2: 0.0,
        sigma2_neg: None,
        fc_neg: 1.0,
        fs_neg: 1.5,
        sigma0: None,
        elements: Some(RawElements { w, delta }),
    }
}

#[test]
fn a_refused_element_names_its_key_index_and_value() {
    let refused = raw(&[1.0, 1.0, -0.5], &[1e-6, 2e-6, 3e-6])
        .validate()
        .unwrap_err();
    let details = refused.details();
    assert_eq!(details.kind, "element");
    assert_eq!(details.field, Some(Location::Element("W", 2)));
    assert_eq!(
        details.field.map(|field| field.to_string()).as_deref(),
        Some("W[2]")
    );
    assert_eq!(details.value, Some(Number::Real(-0.5)));
    assert_eq!(details.index, Some(2));
    assert_eq!(refused.kind(), "element");
}

#[test]
fn this_layers_refusals_have_their_own_kinds() {
    let refused = raw(&[1.0, 1.0], &[1e-6, 2e-6, 3e-6])
        .validate()
        .unwrap_err();
    let details = refused.details();
    assert_eq!(
        (details.kind, details.expected, details.got),
        ("element_lengths", Some(2), Some(3))
    );
    let swap = Error::Incompatible {
        expected: HysteresisKind::Maxwell { elements: 4 },
        got: HysteresisKind::Linear,
    };
    let details = swap.details();
    assert_eq!(
        (details.kind, details.field, details.expected, details.got),
        (
            "incompatible",
            Some(Location::Key("params")),
            Some(4),
            Some(0)
        )
    );
}

#[test]
fn a_channel_error_keeps_the_wrapped_kind_and_adds_the_channel() {
    let inner = gms_core::Error::NotFinite {
        field: Field::x,
        index: 9,
        value: f64::INFINITY,
    };
    let details = Error::Channel(InChannel {
        channel: 2,
        error: inner,
    })
    .details();
    assert_eq!(
        details,
        Details {
            kind: "not_finite",
            field: Some(Location::Key("x")),
            value: Some(Number::Real(f64::INFINITY)),
            bound: None,
            index: None,
            sample: Some(9),
            channel: Some(2),
            expected: None,
            got: None,
        }
    );
}

#[test]
fn ripples_are_located_by_ripple_member_and_entry() {
    let coefficient = Error::Core(gms_core::Error::RippleCoefficient {
        field: Field::cos,
        ripple: 1,
        index: 3,
        value: f64::NAN,
    });
    let details = coefficient.details();
    assert_eq!(
        details.field.map(|field| field.to_string()).as_deref(),
        Some("ripples[1].cos[3]")
    );
    assert_eq!(details.index, Some(3));
    let period = Error::Core(gms_core::Error::RipplePeriod {
        ripple: 0,
        value: 0.0,
    })
    .details();
    assert_eq!(
        period.field.map(|field| field.to_string()).as_deref(),
        Some("ripples[0].period")
    );
}

#[test]
fn the_kinds_are_gms_cores_and_this_layers_without_the_wrappers() {
    let kinds: Vec<&str> = Error::kinds().collect();
    for kind in gms_core::Error::KINDS {
        assert!(kinds.contains(kind), "{kind}");
    }
    for kind in [
        "too_many_elements",
        "both_hysteresis",
        "break_deflection",
        "incompatible",
    ] {
        assert!(kinds.contains(&kind), "{kind}");
    }
    for wrapper in ["core", "channel", "state"] {
        assert!(!kinds.contains(&wrapper), "{wrapper}");
    }
}

/// A period or half stroke whose phase cannot be resolved gives the finest one resolved as its
/// bound; a middle too far from 0 is named without one (the half stroke is what falls short).
#[test]
fn an_unresolved_phase_names_the_term_and_the_finest_resolved() {
    let fine = gms_dyn::RippleTerms {
        period: 1e-12,
        cos: &[0.1],
        sin: &[0.0],
    };
    let refused = gms_dyn::PositionForce::new(0.0, 1.0, [0.0; 2], &[fine, fine]).unwrap_err();
    let details = Error::from(refused).details();
    assert_eq!(details.kind, "phase_unresolved");
    assert_eq!(
        details.field.map(|field| field.to_string()).as_deref(),
        Some("ripples[0].period")
    );
    assert_eq!(details.value, Some(Number::Real(1e-12)));
    // 2^20 ulps of the extent max(|0| + 1, 1) = 1.
    let finest = 1_048_576.0 * f64::EPSILON;
    assert_eq!(details.bound, Some(Number::Real(finest)));
    assert_eq!(details.index, Some(0));

    let refused = gms_dyn::Level::new(0.0, 1e-300, [0.0; 2], &[]).unwrap_err();
    let details = Error::from(refused).details();
    assert_eq!(
        (details.kind, details.field, details.value, details.bound),
        (
            "phase_unresolved",
            Some(Location::Key("half_stroke")),
            Some(Number::Real(1e-300)),
            Some(Number::Real(finest))
        )
    );

    let refused = gms_dyn::Level::new(1e12, 1e-6, [0.0; 2], &[]).unwrap_err();
    let details = Error::from(refused).details();
    assert_eq!(
        (details.kind, details.field, details.value, details.bound),
        (
            "phase_unresolved",
            Some(Location::Key("middle")),
            Some(Number::Real(1e12)),
            None
        )
    );
}

#[test]
fn a_missing_start_position_names_x() {
    let set = raw(&[1.0; 4], &[1e-6, 2e-6, 3e-6, 4e-6])
        .validate()
        .expect("valid");
    let level = gms_dyn::Level::new(0.0, 1.0, [0.1, 0.0], &[]).expect("a level");
    let terms = gms_dyn::Terms {
        level,
        ..gms_dyn::Terms::default()
    };
    let refused = gms_dyn::Compensator::with_terms(&set, 1e-3, gms_core::Mode::Feedforward, &terms)
        .map(|_| ())
        .unwrap_err();
    let details = refused.details();
    assert_eq!(
        (details.kind, details.field, details.value),
        ("missing", Some(Location::Key("x")), None)
    );
    assert_eq!(refused.class(), gms_dyn::ErrorClass::Input);
}
