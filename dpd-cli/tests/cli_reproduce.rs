//! `dpd reproduce`: the list of paper items and the reduced protocol of every item.
use super::cli_support;

use cli_support::{dpd, write};
use std::path::Path;

fn items_dir() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes/papers")
        .display()
        .to_string()
}

#[test]
fn list_names_every_item_and_a_bad_item_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dpd(
        dir.path(),
        &["reproduce", "--list", "--items", &items_dir()],
    );
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.lines().count(), 38, "{text}");
    assert!(
        text.contains("003-table-1      Table 1, p. A1941"),
        "{text}"
    );
    assert!(
        text.contains("001-table-1      Table 1, section 2 [not run]"),
        "{text}"
    );
    let bad = dpd(
        dir.path(),
        &["reproduce", "004-table-9", "--items", &items_dir()],
    );
    assert_eq!(bad.status.code(), Some(2));
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(
        e.contains("no item \"004-table-9\"") && e.contains("003-table-6"),
        "{e}"
    );
}

/// Every item's reduced protocol runs, prints published against measured and writes its
/// report and figures (the numbers are checked by the verdicts, not here: at this length most
/// are unresolved, see docs/papers.md).
#[test]
fn all_quick_runs_every_item() {
    let dir = tempfile::tempdir().unwrap();
    let out = dpd(
        dir.path(),
        &[
            "reproduce",
            "all",
            "--quick",
            "--items",
            &items_dir(),
            "--out",
            "q",
        ],
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("38 items in"), "{text}");
    for id in ["003-table-1", "002-table-4", "001-table-2", "000-table-3"] {
        let report = std::fs::read_to_string(dir.path().join(format!("q/{id}.quick.json")));
        let v: serde_json::Value = serde_json::from_str(&report.unwrap()).unwrap();
        assert!(!v["comparisons"].as_array().unwrap().is_empty(), "{id}");
    }
    assert!(dir
        .path()
        .join("q/003-figure-5.quick/003-table-6/errors.svg")
        .exists());
    assert!(dir
        .path()
        .join("q/002-figure-6.quick/002-figure-6-profile-msetd-dt0.001.svg")
        .exists());
}

/// An item of per-dt rows keeps its finished runs in `<id>.points.json`: a second invocation
/// of the full protocol runs none of them again (their measured ms per step would differ), and
/// a file written for another scene is refused, naming it and the key.
#[test]
fn a_point_item_keeps_its_runs_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let paper = dir.path().join("items/900");
    std::fs::create_dir_all(&paper).unwrap();
    write(&paper, "paper.toml", "reference = '''a test paper'''\n");
    let item = |n: usize| {
        format!(
            "kind = \"table\"\ntitle = \"tiny\"\ncitation = \"Table 1\"\n\
             [scene]\nn = {n}\ntime = 0.5\naverage_fraction = 0.5\nruns = 2\n\
             [[published]]\nscheme = \"vv\"\nmethod = \"VV\"\ndt = 0.05\n\
             kinetic_temperature = \"1.0\"\n\
             [[published]]\nscheme = \"aboba\"\nmethod = \"ABOBA\"\ndt = 0.05\n\
             kinetic_temperature = \"1.0\"\n"
        )
    };
    write(&paper, "table-1.toml", &item(100));
    let args = [
        "reproduce",
        "900-table-1",
        "--items",
        "items",
        "--out",
        "out",
    ];
    let first = dpd(dir.path(), &args);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let file = dir.path().join("out/900-table-1.points.json");
    let stored = std::fs::read_to_string(&file).unwrap();
    let v: serde_json::Value = serde_json::from_str(&stored).unwrap();
    assert_eq!(v["points"].as_array().unwrap().len(), 4, "{stored}");
    let again = dpd(dir.path(), &args);
    assert!(again.status.success());
    assert_eq!(std::fs::read_to_string(&file).unwrap(), stored);
    let measured = |o: &std::process::Output| {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .filter(|l| l.contains("kinetic_temperature"))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    assert_eq!(measured(&again), measured(&first));
    write(&paper, "table-1.toml", &item(120));
    let other = dpd(dir.path(), &args);
    let e = String::from_utf8_lossy(&other.stderr);
    assert!(
        !other.status.success() && e.contains("900-table-1.points.json") && e.contains("n differs"),
        "{e}"
    );
}
