//! `dpd run`: the JSON object, blow-ups reported with exit code 0, bad input refused.
mod cli_support;

use cli_support::{dpd, has_keys, json, refused, write, RUN_FIELDS, TINY};

#[test]
fn run_json_has_the_documented_fields() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let v = json(&dpd(
        dir.path(),
        &["run", "--scene", &scene, "--dt", "0.02", "--json"],
    ));
    has_keys(&v, &RUN_FIELDS);
    assert_eq!(v["scheme"], "aboba");
    assert_eq!(
        (v["dt"].as_f64(), v["steps"].as_u64()),
        (Some(0.02), Some(50))
    );
    assert_eq!(v["stable"], true);
    assert!(v["error"].is_null());
    assert_eq!(v["force_evaluations_per_step"].as_f64(), Some(1.0));
    assert!(v["configurational_temperature"].as_f64().unwrap() > 0.0);
    assert_eq!(v["results"].as_array().unwrap().len(), 1);
}

#[test]
fn a_detected_blow_up_is_reported_with_exit_code_zero() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let args = [
        "run", "--scene", &scene, "--scheme", "vv", "--dt", "1.0", "--json",
    ];
    let v = json(&dpd(dir.path(), &args));
    assert_eq!(v["stable"], false);
    assert!(v["error"].as_str().unwrap().contains("blow-up"), "{v}");
    assert!(v["configurational_temperature"].is_null());
}

#[test]
fn bad_input_is_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let typo = write(dir.path(), "typo.toml", "gamma = 4.5\ndenisty = 3.0\n");
    refused(
        &dpd(dir.path(), &["run", "--scene", &scene, "--gamma=-1"]),
        "gamma",
    );
    refused(&dpd(dir.path(), &["run", "--scene", &typo]), "denisty");
    refused(
        &dpd(dir.path(), &["run", "--scene", "missing.toml"]),
        "missing.toml",
    );
    refused(
        &dpd(dir.path(), &["run", "--scene", &scene, "--scheme", "ABX"]),
        "scheme",
    );
}
