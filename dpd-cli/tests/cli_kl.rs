//! `dpd kl` and the energy balance of `dpd run`.
use super::cli_support;

use cli_support::{dpd, has_keys, json, refused};

#[test]
fn kl_json_has_the_documented_fields() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "kl",
        "ABOBA",
        "--dt",
        "0.1",
        "--n",
        "100",
        "--samples",
        "20",
        "--protocol-time",
        "0.5",
        "--json",
    ];
    let r = json(&dpd(dir.path(), &args));
    has_keys(
        &r,
        &[
            "kl_divergence",
            "kl_error",
            "protocol_steps",
            "samples",
            "kl_per_particle",
            "forward_work",
            "reverse_work",
            "equilibrium_potential_energy",
        ],
    );
    assert_eq!(r["protocol_steps"], 5);
    assert_eq!(r["samples"], 20);
    assert!(r["kl_error"].as_f64().unwrap() > 0.0, "{r}");
}

#[test]
fn kl_refuses_schemes_it_does_not_apply_to_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    for (scheme, reason) in [
        ("A B O", "not symmetric"),
        ("sas", "T stage"),
        ("vv", "F stage"),
        ("setd", "hand-written"),
    ] {
        refused(&dpd(dir.path(), &["kl", scheme, "--n", "50"]), reason);
    }
    refused(
        &dpd(dir.path(), &["kl", "ABOBA", "--samples", "5"]),
        "samples",
    );
    refused(
        &dpd(dir.path(), &["kl", "ABOBA", "--shear-rate", "0.5"]),
        "shear_rate",
    );
}

/// Over 20 time units the thermostat takes up heat and the deterministic stages do shadow
/// work; on the equilibrium box both are about 0.15 per particle and time unit at dt = 0.1
/// (the energy changes by far less), with opposite signs.
#[test]
fn run_reports_heat_and_shadow_work_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "run",
        "--scheme",
        "ABOBA",
        "--dt",
        "0.1",
        "--n",
        "100",
        "--time",
        "20",
        "--energy-balance",
        "--json",
    ];
    let r = json(&dpd(dir.path(), &args));
    let (q, w) = (
        r["heat"].as_f64().unwrap(),
        r["shadow_work"].as_f64().unwrap(),
    );
    assert!(w > 0.05 && q < -0.05, "heat {q}, work {w}");
    assert!((q + w).abs() < 0.2 * w, "heat {q}, work {w}");
    let plain = json(&dpd(
        dir.path(),
        &[&args[..args.len() - 2], &["--json"]].concat(),
    ));
    assert!(plain.get("heat").is_none() && plain.get("shadow_work").is_none());
    refused(
        &dpd(dir.path(), &["run", "--scheme", "sas", "--energy-balance"]),
        "T stage",
    );
}
