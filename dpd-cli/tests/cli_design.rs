//! `dpd design`: order solutions of a family, and `--measure`'s sweep against ABOBA.
use super::cli_support;

use cli_support::{dpd, json, write};

const YOSHIDA: &str = "param x in -2..2; S((1 - x)/2) S(x) S((1 - x)/2) O";
const PALINDROME: &str = "param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O";

#[test]
fn yoshidas_x0_is_the_order_four_solution() {
    let dir = tempfile::tempdir().unwrap();
    let d = json(&dpd(dir.path(), &["design", YOSHIDA, "--json"]));
    let best = &d["solutions"][0];
    assert_eq!(best["deterministic_order"], 4, "{best}");
    let x = best["parameters"][0][1].as_f64().unwrap();
    // x0 = -2^(1/3) / (2 - 2^(1/3)).
    let x0 = -(2f64.cbrt()) / (2.0 - 2f64.cbrt());
    assert!((x - x0).abs() < 1e-9, "x = {x}, expected {x0}");
}

#[test]
fn measure_sweeps_the_best_members_and_aboba_and_ranks_them() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(
        dir.path(),
        "scene.toml",
        "n = 100\ntime = 6.0\naverage_fraction = 0.5\nruns = 2\n[sweep]\ndt_min = 0.04\ndt_max = 0.2\ndt_factor = 1.5\n",
    );
    let args = [
        "design",
        PALINDROME,
        "--measure",
        "--top",
        "2",
        "--scene",
        &scene,
        "--out",
        "d",
        "--json",
    ];
    let d = json(&dpd(dir.path(), &args));
    let rows = d["measured"].as_array().unwrap();
    assert_eq!(rows.len(), 3, "two members and ABOBA: {rows:?}");
    assert_eq!(rows[2]["scheme"], "aboba");
    let mut predicted: Vec<u64> = rows
        .iter()
        .map(|r| r["predicted_rank"].as_u64().unwrap())
        .collect();
    predicted.sort();
    assert_eq!(predicted, [1, 2, 3], "ranks by norm: {rows:?}");
    // The two members have smaller invariant-measure norms than ABOBA (0.0266 and 0.0340
    // against 0.2946): ABOBA is predicted last.
    assert_eq!(rows[2]["predicted_rank"], 3);
    for r in rows {
        for key in [
            "critical_dt_10",
            "critical_dt_1",
            "efficiency",
            "measured_rank",
        ] {
            assert!(r.get(key).is_some(), "missing {key} in {r}");
        }
    }
    if let Some(e) = rows[2]["efficiency"].as_f64() {
        assert_eq!(e, 1.0, "the reference's efficiency");
    }
    // The best solution carries its measurement too.
    let best = &d["solutions"][0];
    assert_eq!(best["program"], rows[0]["scheme"]);
    assert!(best.get("critical_dt_10").is_some(), "{best}");
    let sweep: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("d/design.json")).unwrap()).unwrap();
    // Three schemes at four dt with two seeds; the baseline (ABOBA at dt_min) is one of them.
    assert_eq!(sweep["points"].as_array().unwrap().len(), 3 * 4 * 2);
}

#[test]
fn measure_refuses_top_zero() {
    let dir = tempfile::tempdir().unwrap();
    let out = dpd(
        dir.path(),
        &["design", PALINDROME, "--measure", "--top", "0"],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--top = 0"), "{err}");
}
