//! The checked-in header is the one cbindgen generates from the source: a C caller compiles
//! against exactly the functions, structs and constants the library exports.

use std::path::Path;

#[test]
fn header_matches_the_source() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(root.join("src/lib.rs"))
        .generate()
        .expect("cbindgen parses src/lib.rs");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = root.join("include/leuven_rt.h");
    if std::env::var_os("LEUVEN_RT_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/leuven_rt.h");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/leuven_rt.h differs from the header generated from src/lib.rs; if the change \
         to the C API is intended, run `LEUVEN_RT_BLESS=1 cargo test -p gms-ffi --test header`\n\
         --- generated ---\n{generated}"
    );
}
