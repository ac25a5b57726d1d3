//! `dpd sweep`: the JSON results file, CSV and plots, and resuming from the results file.
use super::cli_support;

use cli_support::{dpd, has_keys, refused, two_step_sweep, write, RUN_FIELDS, TINY};
use std::path::Path;
use std::process::Output;

#[test]
fn sweep_writes_points_and_summary_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "tiny.toml",
        &format!("{TINY}runs = 2\n[rdf]\nr_max = 1.5\n"),
    );
    let args = two_step_sweep(&scene, "vv,aboba");
    let out = dpd(dir.path(), &args);
    let v = results(dir.path(), &out);
    // 2 schemes x 2 dt x 2 seeds; the baseline (aboba at dt_min) is one of them.
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 8);
    points.iter().for_each(|p| has_keys(p, &RUN_FIELDS));
    let summary = v["summary"].as_array().unwrap();
    assert_eq!(summary.len(), 2);
    for s in summary {
        has_keys(
            s,
            &[
                "scheme",
                "critical_dt_10",
                "critical_dt_1",
                "stability_dt",
                "ms_per_step",
                "efficiency",
            ],
        );
    }
    assert_eq!(v["complete"], true);
    for file in ["out.csv", "errors.svg", "rdf-vv.svg", "rdf-aboba.svg"] {
        assert!(dir.path().join("plots").join(file).exists(), "{file}");
    }
    // Again: every point is found in the results file and none is recomputed.
    let again = dpd(dir.path(), &args);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        again.status.success() && stderr.contains("8 points, 8 already in"),
        "{stderr}"
    );
    let after: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.json")).unwrap())
            .unwrap();
    assert_eq!(after["points"], v["points"]);
    // A narrower plan counts only its own points as done, and keeps the others.
    let mut narrower = args;
    narrower[4] = "aboba";
    let again = dpd(dir.path(), &narrower);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        again.status.success()
            && stderr.contains("4 points, 4 already in")
            && stderr.contains("(and 4 other points it keeps)"),
        "{stderr}"
    );
    let kept: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.json")).unwrap())
            .unwrap();
    assert_eq!(kept["points"].as_array().map(Vec::len), Some(8));
}

/// The results file `out.json` in `dir`, after checking that `out` succeeded.
#[test]
fn a_results_file_that_cannot_be_saved_is_reported_after_each_point() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let json = dir.path().join("missing-dir").join("out.json");
    let out = aboba_sweep(
        dir.path(),
        &scene,
        ["0.05", "0.05"],
        &["--json", json.to_str().unwrap()],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    // One point (aboba at dt 0.05, one seed), saved after it ran and once more at the end.
    let warnings = stderr.matches("warning: cannot write").count();
    assert_eq!(warnings, 1, "{stderr}");
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("missing-dir"), "{stderr}");
}

fn results(dir: &Path, out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("out.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// `dpd sweep` in `dir` of `scene` with aboba alone from `dt_min` to `dt_max`, then `extra`.
fn aboba_sweep(dir: &Path, scene: &str, [dt_min, dt_max]: [&str; 2], extra: &[&str]) -> Output {
    let base = [
        "sweep",
        "--scene",
        scene,
        "--schemes",
        "aboba",
        "--dt-min",
        dt_min,
        "--dt-max",
        dt_max,
    ];
    dpd(dir, &[&base[..], extra].concat())
}

#[test]
fn a_results_file_of_another_scene_or_bad_flags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let run = |extra: &[&str]| aboba_sweep(dir.path(), &scene, ["0.1", "0.1"], extra);
    assert!(run(&["--reference", "aboba"]).status.success());
    refused(&run(&["--reference", "aboba", "--gamma", "40.5"]), "gamma");
    let factor = ["--reference", "aboba", "--dt-factor", "0.5", "--fresh"];
    refused(&run(&factor), "sweep.dt_factor");
    // Without --reference the one scheme swept is the reference (vv, the default where it
    // is swept, is not: this was refused once).
    let alone = run(&["--fresh"]);
    assert!(
        alone.status.success(),
        "{}",
        String::from_utf8_lossy(&alone.stderr)
    );
    assert!(String::from_utf8_lossy(&alone.stdout).contains("efficiency (vs aboba)"));
    refused(&run(&["--reference", "vv", "--fresh"]), "sweep.reference");
}

#[test]
fn a_viscosity_sweep_reports_its_observable_and_refuses_to_mix() {
    let dir = tempfile::tempdir().unwrap();
    let shear = "n = 100\ngamma = 450.0\nshear_rate = 0.2\ntime = 2.0\n";
    let scene = write(dir.path(), "shear.toml", shear);
    let run = |extra: &[&str]| {
        let args = [
            &[
                "--reference",
                "aboba",
                "--dt-factor",
                "2",
                "--json",
                "out.json",
            ],
            extra,
        ];
        aboba_sweep(dir.path(), &scene, ["0.01", "0.02"], &args.concat())
    };
    let out = run(&["--observable", "viscosity"]);
    let v = results(dir.path(), &out);
    assert_eq!(v["observable"], "viscosity");
    assert_eq!(v["scene"]["sweep"]["observable"], "viscosity");
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for row in rows {
        has_keys(row, &["shear_viscosity", "shear_viscosity_error"]);
        assert!(row["shear_viscosity_relative_error"].is_number(), "{row}");
    }
    // The baseline is the dt_min point itself: no error there.
    assert_eq!(rows[0]["shear_viscosity_relative_error"], 0.0);
    has_keys(&v["summary"][0], &["critical_10", "critical_1"]);
    // Resuming with another observable is refused by name; so is a scene without shear.
    refused(&run(&[]), "sweep.observable");
    let plain = write(dir.path(), "plain.toml", TINY);
    let out = dpd(
        dir.path(),
        &["sweep", "--scene", &plain, "--observable", "viscosity"],
    );
    refused(&out, "shear_rate");
}
