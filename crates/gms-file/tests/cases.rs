//! The table of model-file cases (`tests/fixtures/model_files/cases.json`), read by gms-file
//! itself: every case accepted or refused as the table says, with the kind and the key path.
//! The Python package (`tests/core/test_model_file_cases.py`) and the C library
//! (`crates/gms-ffi/tests/model_file_cases.rs`) are tested against the same table.

use gms_file::ModelFile;
use serde_json::Value;

/// The cases of the table.
fn cases() -> Vec<Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/fixtures/model_files/cases.json"
    );
    let text = std::fs::read_to_string(path).expect("the table of cases");
    let table: Value = serde_json::from_str(&text).expect("the table is JSON");
    table["cases"].as_array().expect("a list of cases").clone()
}

#[test]
fn every_case_is_read_as_the_table_says() {
    let cases = cases();
    assert!(cases.len() > 50, "{} cases", cases.len());
    let mut wrong = Vec::new();
    for case in &cases {
        let name = case["name"].as_str().unwrap();
        let text = case["text"].as_str().unwrap();
        let read = ModelFile::from_json(text).and_then(|file| file.validate().map(|_| file));
        let (kind, key) = match &read {
            Ok(_) => (Value::Null, Value::Null),
            Err(error) => (
                Value::from(error.kind().name()),
                error.key().map_or(Value::Null, Value::from),
            ),
        };
        // The name the bindings give is listed with the kinds (a rule's is gms-dyn's kind).
        let listed = read
            .as_ref()
            .err()
            .and_then(gms_file::FileError::kind_name)
            .is_none_or(|name| gms_file::FileError::KINDS.contains(&name));
        if read.is_ok() != case["accept"].as_bool().unwrap()
            || !listed
            || kind != case["kind"]
            || key != case["key"]
        {
            wrong.push(format!(
                "{name}: got {kind} {key} ({}), expected {} {}",
                read.as_ref()
                    .err()
                    .map(ToString::to_string)
                    .unwrap_or_default(),
                case["kind"],
                case["key"]
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn every_accepted_case_round_trips_through_the_writer() {
    for case in cases() {
        if !case["accept"].as_bool().unwrap() {
            continue;
        }
        let file = ModelFile::from_json(case["text"].as_str().unwrap()).unwrap();
        let text = file.to_json().unwrap();
        let again = ModelFile::from_json(&text).unwrap();
        assert_eq!(again, file, "{}", case["name"]);
        assert_eq!(again.to_json().unwrap(), text, "{}", case["name"]);
        assert!(text.contains("\"version\": 3"), "{}", case["name"]);
    }
}
