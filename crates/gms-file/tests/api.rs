//! gms-file's API beyond the table of cases: the data its errors carry, the writer refusing what
//! the reader would refuse, values read from a JSON value as from text, files, and exact numbers.

use gms_core::{Error as Core, Field};
use gms_file::{ErrorKind, FileError, Friction, Measurement, ModelFile, Reconstruction, Source};
use serde_json::json;

fn friction() -> Friction {
    Friction::from_json(
        r#"{"Fc": 1.0, "Fs": 1.5, "Vs": 0.001, "delta": 2.0, "n": 2.0, "sigma1": 30.0,
            "sigma2": 0.4, "W": [0.6, 0.5, 0.4, 0.3], "Delta": [1e-6, 2e-6, 4e-6, 8e-6]}"#,
    )
    .unwrap()
}

#[test]
fn a_rule_broken_carries_gms_core_s_error_and_the_key() {
    let mut file = ModelFile::new(friction());
    file.friction.Fs = 0.5;
    let error = file.validate().unwrap_err();
    assert_eq!(error.kind(), ErrorKind::Value);
    assert_eq!(error.key(), Some("friction.Fs"));
    assert!(matches!(
        error.rule(),
        Some(gms_dyn::Error::Core(Core::StaticBelowCoulomb {
            field: Field::Fs,
            ..
        }))
    ));
    // The parameter file alone names the key as the file has it.
    let alone = file.friction.validate().unwrap_err();
    assert_eq!(alone.key(), Some("Fs"));
    assert_eq!(alone.under("friction"), error);
}

#[test]
fn the_writer_refuses_what_the_reader_would_refuse() {
    let mut file = ModelFile::new(friction());
    file.measurement = Measurement {
        offset: f64::NAN,
        inertia: 0.0,
    };
    let error = file.to_json().unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Value, Some("measurement.offset"))
    );
    file.measurement = Measurement::default();
    file.reconstruction = Some(Reconstruction {
        source: Source::Position,
        cutoff: Some(f64::INFINITY),
        acceleration_cutoff: None,
    });
    let error = file.to_value().unwrap_err();
    assert_eq!(error.key(), Some("reconstruction.cutoff"));
    file.reconstruction = Some(Reconstruction {
        source: Source::Position,
        cutoff: None,
        acceleration_cutoff: Some(0.0),
    });
    let error = file.to_value().unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Value, Some("reconstruction.acceleration_cutoff"))
    );
    file.reconstruction = None;
    file.friction.W = None;
    let error = file.to_json().unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Shape, Some("friction.W"))
    );
}

#[test]
fn a_value_reads_as_its_text() {
    let value = json!({"format": "leuven-rt model", "version": 2, "units": "rotary",
        "friction": {"Fc": 1, "Fs": 2, "Vs": 1, "delta": 2, "n": 2, "sigma0": 1e5},
        "reconstruction": {"source": "velocity", "cutoff": null}});
    let from_value = ModelFile::from_value(value.clone()).unwrap();
    assert_eq!(
        from_value,
        ModelFile::from_json(&value.to_string()).unwrap()
    );
    let mut wrong = value;
    wrong["friction"] = json!([1, 2, 1, 2, 2]);
    let error = ModelFile::from_value(wrong).unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Shape, Some("friction"))
    );
    assert!(matches!(
        ModelFile::from_value(json!(3)),
        Err(FileError::NotAnObject { .. })
    ));
}

#[test]
fn numbers_read_back_exactly() {
    let values = [0.1 + 0.2, 1e-300, 5e-324, f64::MAX, 2.0_f64.sqrt()];
    let mut file = ModelFile::new(friction());
    for value in values {
        file.measurement.offset = value;
        file.measurement.inertia = -value;
        let again = ModelFile::from_json(&file.to_json().unwrap()).unwrap();
        assert_eq!(again.measurement.offset.to_bits(), value.to_bits());
        assert_eq!(again.measurement.inertia.to_bits(), (-value).to_bits());
    }
}

#[test]
fn files_are_read_whole_or_refused() {
    let folder = std::env::temp_dir().join(format!("gms-file-test-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let path = folder.join("model.json");
    let file = ModelFile::new(friction());
    std::fs::write(&path, file.to_json().unwrap()).unwrap();
    assert_eq!(ModelFile::load(&path).unwrap(), file);
    for (target, said) in [
        (folder.join("missing.json"), "cannot read"),
        (folder.clone(), "not a regular file"),
    ] {
        let error = ModelFile::load(&target).unwrap_err();
        assert_eq!(error.kind(), ErrorKind::Read);
        assert!(error.to_string().contains(said), "{error}");
    }
    let large = folder.join("large.json");
    let padding = " ".repeat(usize::try_from(gms_file::MAX_FILE_BYTES).unwrap());
    std::fs::write(&large, format!("{}{padding}", file.to_json().unwrap())).unwrap();
    let error = ModelFile::load(&large).unwrap_err();
    assert!(error.to_string().contains("larger than"), "{error}");
    std::fs::write(&large, b"{\"Fc\": \"\xff\"}").unwrap();
    assert!(ModelFile::load(&large)
        .unwrap_err()
        .to_string()
        .contains("not UTF-8"));
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn every_refusal_of_the_reader_is_named() {
    let text = ModelFile::new(friction()).to_json().unwrap();
    for (edited, kind, problem) in [
        (
            text.replace("\"units\"", "\"units\": 1, \"units\""),
            "repeated",
            Some(gms_file::Problem::Repeated),
        ),
        (
            text.replace("\"units\": \"linear\",", ""),
            "missing_key",
            Some(gms_file::Problem::MissingKey),
        ),
        (
            text.replace("\"units\"", "\"colour\": 1, \"units\""),
            "unknown_key",
            Some(gms_file::Problem::UnknownKey),
        ),
        (
            text.replace("\"measurement\": {", "\"measurement\": null, \"x\": {"),
            "wrong_type",
            Some(gms_file::Problem::WrongType),
        ),
        (
            text.replace("\"Fc\": 1.0", "\"Fc\": 1e400"),
            "out_of_range",
            Some(gms_file::Problem::OutOfRange),
        ),
        (
            text.replace("\"version\": 3", "\"version\": 9"),
            "invalid_choice",
            None,
        ),
        (text.replace("\"version\": 3,", ""), "missing_key", None),
        (text.replace("\"Fc\": 1.0", "\"Fc\": NaN"), "not_json", None),
    ] {
        let error = ModelFile::from_json(&edited).unwrap_err();
        assert_eq!(error.kind_name(), Some(kind), "{error}");
        assert!(FileError::KINDS.contains(&kind), "{kind} is not listed");
        if let Some(problem) = problem {
            assert!(
                matches!(error, FileError::Shape { problem: p, .. } if p == problem),
                "{error}"
            );
        }
    }
    let mut file = ModelFile::new(friction());
    file.friction.Fs = 0.5;
    assert_eq!(file.validate().unwrap_err().kind_name(), None);
}

#[test]
fn the_acceleration_cutoff_came_with_version_3() {
    let value = json!({"format": "leuven-rt model", "version": 3, "units": "linear",
        "friction": {"Fc": 1, "Fs": 2, "Vs": 1, "delta": 2, "n": 2, "sigma0": 1e5},
        "reconstruction": {"source": "position", "cutoff": null, "acceleration_cutoff": 400.0}});
    let file = ModelFile::from_value(value.clone()).unwrap();
    assert_eq!(
        file.reconstruction.and_then(|r| r.acceleration_cutoff),
        Some(400.0)
    );
    // Written back as read, and without the key where there is none (so a default stays one).
    assert_eq!(
        file.to_value().unwrap()["reconstruction"],
        value["reconstruction"]
    );
    let mut without = value.clone();
    without["reconstruction"] = json!({"source": "position", "cutoff": null});
    let read = ModelFile::from_value(without.clone()).unwrap();
    assert_eq!(
        read.to_value().unwrap()["reconstruction"],
        without["reconstruction"]
    );

    let mut older = value.clone();
    older["version"] = json!(2);
    let error = ModelFile::from_value(older).unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Shape, Some("reconstruction.acceleration_cutoff"))
    );
    assert!(
        error.to_string().contains("it came with version 3"),
        "{error}"
    );
    let mut null = value;
    null["reconstruction"]["acceleration_cutoff"] = json!(null);
    let error = ModelFile::from_value(null).unwrap_err();
    assert_eq!(
        (error.kind(), error.key()),
        (ErrorKind::Shape, Some("reconstruction.acceleration_cutoff"))
    );
}
