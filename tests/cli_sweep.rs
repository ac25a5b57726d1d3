//! `dpd sweep`: the JSON results file, CSV and plots, and resuming from the results file.
mod cli_support;

use cli_support::{dpd, has_keys, refused, write, RUN_FIELDS, TINY};

#[test]
fn sweep_writes_points_and_summary_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "tiny.toml",
        &format!("{TINY}runs = 2\n[rdf]\nr_max = 1.5\n"),
    );
    let args = [
        "sweep",
        "--scene",
        &scene,
        "--schemes",
        "vv,aboba",
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
    ];
    let out = dpd(dir.path(), &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.path().join("out.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
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
}

#[test]
fn a_results_file_of_another_scene_or_bad_flags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let base = [
        "sweep",
        "--scene",
        &scene,
        "--schemes",
        "aboba",
        "--dt-min",
        "0.1",
        "--dt-max",
        "0.1",
    ];
    let run = |extra: &[&str]| dpd(dir.path(), &[&base[..], extra].concat());
    assert!(run(&["--reference", "aboba"]).status.success());
    refused(&run(&["--reference", "aboba", "--gamma", "40.5"]), "gamma");
    let factor = ["--reference", "aboba", "--dt-factor", "0.5", "--fresh"];
    refused(&run(&factor), "sweep.dt_factor");
    // The default reference, vv, is not among the schemes.
    refused(&run(&["--fresh"]), "sweep.reference");
}
