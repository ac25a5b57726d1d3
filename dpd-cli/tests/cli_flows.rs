//! `dpd run` on non-equilibrium scenes: the shear viscosity in the JSON (null with too few
//! samples), the profile CSV header and SVG of a wall-bounded channel, bad keys refused.
use super::cli_support;

use cli_support::{dpd, json, refused, write};

const SHEAR: &str = "n = 100\ngamma = 450.0\nshear_rate = 0.2\ndt = 0.01\naverage_fraction = 0.8\n";

const CHANNEL: &str = "box = [5.0, 5.0, 10.0]\ndensity = 4.0\na = 18.5\nmass = 0.1\n\
    weight_exponent = 0.5\nscheme = \"msetd\"\ndt = 0.005\ntime = 0.5\nbody_force = 0.1\n\
    [walls]\nlower = 1.0\nupper = 9.0\n[profile]\nbins = 10\n";

#[test]
fn sheared_run_reports_the_viscosity_or_null() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "shear.toml", SHEAR);
    let v = json(&dpd(
        dir.path(),
        &["run", "--scene", &scene, "--time", "2", "--json"],
    ));
    assert!(v["shear_viscosity"].as_f64().unwrap().is_finite(), "{v}");
    assert!(v["shear_viscosity_error"].as_f64().unwrap() > 0.0, "{v}");
    assert!(v["results"][0]["viscosity"]["shear_viscosity"].is_number());
    // 0.2 time units: 2 samples, fewer than the 10 blocks.
    let v = json(&dpd(
        dir.path(),
        &["run", "--scene", &scene, "--time", "0.2", "--json"],
    ));
    assert!(
        v["shear_viscosity"].is_null() && v["shear_viscosity_error"].is_null(),
        "{v}"
    );
    // The plain box has no viscosity fields.
    let v = json(&dpd(
        dir.path(),
        &["run", "--n", "100", "--time", "0.2", "--json"],
    ));
    assert!(v.get("shear_viscosity").is_none(), "{v}");
}

#[test]
fn channel_profile_is_written_as_csv_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "channel.toml", CHANNEL);
    let out = dpd(
        dir.path(),
        &["run", "--scene", &scene, "--profile-dir", "prof", "--json"],
    );
    let v = json(&out);
    assert_eq!(v["results"][0]["profile"].as_array().unwrap().len(), 10);
    // Between walls T_C and the pressure are not bulk quantities: null.
    assert!(v["configurational_temperature"].is_null() && v["pressure"].is_null());
    assert!(v["kinetic_temperature"].is_number());
    // The header leaves out the n that `box` overrides and gives the particle count.
    let header = String::from_utf8_lossy(&out.stderr);
    assert!(header.contains("# 1000 particles"), "{header}");
    assert!(!header.lines().any(|l| l.starts_with("n = ")), "{header}");
    let csv = std::fs::read_to_string(dir.path().join("prof/profile-seed1.csv")).unwrap();
    assert!(
        csv.starts_with("z,density,vx,vy,vz,temperature,count\n"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 11);
    assert!(dir.path().join("prof/profile-seed1.svg").exists());
}

#[test]
fn bad_flow_keys_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "shear.toml", SHEAR);
    refused(
        &dpd(
            dir.path(),
            &["run", "--scene", &scene, "--shear-rate", "nan"],
        ),
        "shear_rate",
    );
    let walls = write(
        dir.path(),
        "w.toml",
        &CHANNEL.replace("upper = 9.0", "upper = 0.5"),
    );
    refused(&dpd(dir.path(), &["run", "--scene", &walls]), "walls");
    let both = write(dir.path(), "b.toml", CHANNEL);
    refused(
        &dpd(
            dir.path(),
            &["run", "--scene", &both, "--shear-rate", "0.1"],
        ),
        "shear_rate",
    );
}
