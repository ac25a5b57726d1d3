//! Compile-time behaviour of `dpd_scheme!`: every kind of bad input is one clear error at the
//! right place (`tests/ui/<category>/<what-is-wrong>.rs` with its `.stderr`).
//!
//! Only failing cases: trybuild's generated crate takes the dependencies and dev-dependencies of
//! the crate it tests and, with no passing case, only checks them (`cargo check`). What
//! compiles and runs in a user's crate is `tests/user_crate.rs`.
//!
//! Regenerate the snapshots with `TRYBUILD=overwrite`, then read every `.stderr`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    for category in ["args", "language", "checks", "order"] {
        t.compile_fail(format!("tests/ui/{category}/*.rs"));
    }
}
