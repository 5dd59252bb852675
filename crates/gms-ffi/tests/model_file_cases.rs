//! The table of model-file cases (`tests/fixtures/model_files/cases.json`) through the C entry
//! point `leuven_rt_compensator_create_from_json`: each case gets the status the table gives, a
//! refusal's message names the key path (or says "not JSON" with the line and column of a
//! syntax error), and a refused call leaves `*out` as it was. The Python package is tested
//! against the same table (`tests/core/test_model_file_cases.py`).

use core::ffi::{c_char, CStr};

use gms_ffi::leuven_rt_status::{
    LEUVEN_RT_INVALID_FILE, LEUVEN_RT_INVALID_PARAMETER, LEUVEN_RT_OK,
};
use gms_ffi::{
    leuven_rt_compensator, leuven_rt_compensator_create_from_json, leuven_rt_compensator_destroy,
    leuven_rt_error, leuven_rt_status, LEUVEN_RT_MODE_OBSERVER,
};
use serde_json::Value;

fn cases() -> Vec<Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/fixtures/model_files/cases.json"
    );
    let text = std::fs::read_to_string(path).expect("the table of cases");
    let table: Value = serde_json::from_str(&text).expect("the table is JSON");
    table["cases"].as_array().expect("a list of cases").clone()
}

fn status_named(name: &str) -> leuven_rt_status {
    match name {
        "LEUVEN_RT_OK" => LEUVEN_RT_OK,
        "LEUVEN_RT_INVALID_FILE" => LEUVEN_RT_INVALID_FILE,
        "LEUVEN_RT_INVALID_PARAMETER" => LEUVEN_RT_INVALID_PARAMETER,
        other => panic!("no status {other} in the table's vocabulary"),
    }
}

/// The status and the message of `create_from_json` on `text`.
fn create(text: &str) -> (leuven_rt_status, String) {
    let mut out: *mut leuven_rt_compensator = core::ptr::null_mut();
    let mut error = leuven_rt_error {
        field: core::ptr::null(),
        index: 0,
        message: [0; gms_ffi::LEUVEN_RT_ERROR_MESSAGE_SIZE],
    };
    // SAFETY: `text` is `len` readable bytes; `out` and `error` are valid for writes.
    let status = unsafe {
        leuven_rt_compensator_create_from_json(
            text.as_ptr().cast::<c_char>(),
            text.len(),
            1e-3,
            LEUVEN_RT_MODE_OBSERVER,
            &raw mut out,
            &raw mut error,
        )
    };
    assert_eq!(
        status == LEUVEN_RT_OK,
        !out.is_null(),
        "*out is written exactly on success"
    );
    // SAFETY: null or the handle just created.
    unsafe { leuven_rt_compensator_destroy(out) };
    // SAFETY: the library always writes a NUL-terminated message.
    let message = unsafe { CStr::from_ptr(error.message.as_ptr()) };
    (status, message.to_string_lossy().into_owned())
}

#[test]
fn the_c_library_reads_every_case_as_the_table_says() {
    let mut wrong = Vec::new();
    for case in cases() {
        let name = case["name"].as_str().unwrap();
        let (status, message) = create(case["text"].as_str().unwrap());
        let expected = status_named(case["status"].as_str().unwrap());
        let named = match (case["kind"].as_str(), case["key"].as_str()) {
            (None, _) => message.is_empty(),
            (Some("syntax"), _) => message.starts_with("not JSON: ") && message.contains(" line "),
            (Some(_), Some(key)) => message.starts_with(&format!("`{key}`")),
            (Some(_), None) => !message.is_empty(),
        };
        if status != expected || !named {
            wrong.push(format!(
                "{name}: {status:?} {message:?}, expected {expected:?}"
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
