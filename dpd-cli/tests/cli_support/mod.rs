//! Running the built `dpd` binary in the command-line tests.

use std::path::Path;
use std::process::{Command, Output};

/// A scene small enough for tests: 100 particles, 1 time unit, half of it averaged.
pub const TINY: &str = "n = 100\ntime = 1.0\naverage_fraction = 0.5\n";

/// The arguments of `dpd sweep` over `schemes` on `scene` at dt = 0.05 and 0.1, its results
/// file `out.json` and its plots in `plots/`.
pub fn two_step_sweep<'a>(scene: &'a str, schemes: &'a str) -> [&'a str; 15] {
    [
        "sweep",
        "--scene",
        scene,
        "--schemes",
        schemes,
        "--dt-min",
        "0.05",
        "--dt-max",
        "0.1",
        "--dt-factor",
        "2",
        "--json",
        "out.json",
        "--out",
        "plots",
    ]
}

/// Write `text` as `name` into `dir`; returns the path as a string.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Run `dpd args...` in `dir`.
pub fn dpd(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dpd"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// stdout parsed as JSON, after checking the exit code is 0.
pub fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "exit {:?}, stderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Assert that `value` has every key of `keys`.
pub fn has_keys(value: &serde_json::Value, keys: &[&str]) {
    for key in keys {
        assert!(value.get(key).is_some(), "missing {key} in {value}");
    }
}

/// Assert exit code 2 and a message on stderr that names `key`.
pub fn refused(out: &Output, key: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains(key), "{key} not named in: {stderr}");
}

/// The fields every run result has (`dpd run --json`, sweep points).
pub const RUN_FIELDS: [&str; 11] = [
    "scheme",
    "dt",
    "steps",
    "kinetic_temperature",
    "configurational_temperature",
    "potential_energy",
    "pressure",
    "ms_per_step",
    "force_evaluations_per_step",
    "stable",
    "error",
];
