//! Compile-time behaviour of `dpd_scheme!`: every kind of bad input is one clear error at the
//! right place (`tests/ui/<category>/<what-is-wrong>.rs` with its `.stderr`), and user crates
//! depending only on `dpd` compile and run generated schemes (`tests/ui/pass`).
//!
//! Regenerate the snapshots with `TRYBUILD=overwrite`, then read every `.stderr`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    for category in ["args", "language", "checks", "order"] {
        t.compile_fail(format!("tests/ui/{category}/*.rs"));
    }
    t.pass("tests/ui/pass/*.rs");
}
