//! `dpd run`: the JSON object, blow-ups reported with exit code 0, bad input refused.
use super::cli_support;

use cli_support::{dpd, has_keys, json, refused, two_step_sweep, write, RUN_FIELDS, TINY};

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

#[test]
fn edge_values_are_refused_naming_the_flag_and_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let run = |extra: &[&str]| {
        let mut args = vec!["run", "--scene", &scene];
        args.extend_from_slice(extra);
        dpd(dir.path(), &args)
    };
    for (args, named) in [
        (
            &["--dt", "-1"][..],
            "invalid dt = -1: must be finite and > 0",
        ),
        (&["--gamma", "-2"], "invalid gamma = -2"),
        (&["--n", "-3"], "'--n <N>'"),
        (
            &["--dt", "1e300"],
            "invalid dt = 1e300: gives round(time / dt) = 0 steps",
        ),
        (&["--time", "0.01", "--dt", "0.05"], "0 steps"),
        (
            &["--time", "0.1", "--dt", "1e-300"],
            "more than the 1e9 steps",
        ),
        (
            &["--threads", "100000"],
            "invalid threads = 100000: must be at most",
        ),
        (&["--density", "1e9"], "invalid density = 1000000000"),
    ] {
        refused(&run(args), named);
    }
}

#[test]
fn a_bad_scheme_string_is_shown_once_with_a_caret_and_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let long = format!("{}Q", "A".repeat(5000));
    for (scheme, caret) in [
        (long.as_str(), "...AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAQ\n"),
        ("AB\u{1b}[2JOBA", "AB\\u{1b}[2JOBA\n    ^^^^^^"),
        ("A(NaN) B", "'NaN' is not a finite number"),
    ] {
        let out = dpd(dir.path(), &["run", "--scene", &scene, "--scheme", scheme]);
        refused(&out, caret);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.len() < 600, "{} bytes: {stderr}", stderr.len());
        assert!(!stderr.contains('\u{1b}') && !stderr.contains("registered"));
    }
}

/// A scheme string the order analysis finds inconsistent is refused with the message naming
/// the flag that accepts it, and `dpd run` and `dpd sweep` run it with that flag (the scene key
/// `allow_inconsistent`, recorded in the results), a sweep resuming the results file of one
/// without it (the key chooses runs, not the physics).
#[test]
fn an_inconsistent_scheme_string_runs_when_allowed_as_the_message_says() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    // B's coefficients sum to 1/2.
    let scheme = "A B(1/2) O";
    let flag = "--allow-inconsistent";
    let run = ["run", "--scene", &scene, "--scheme", scheme, "--json"];
    refused(
        &dpd(dir.path(), &run),
        "--allow-inconsistent of dpd run, dpd sweep",
    );
    let v = json(&dpd(dir.path(), &[&run[..], &[flag]].concat()));
    assert_eq!((&v["scheme"], &v["stable"]), (&scheme.into(), &true.into()));
    assert_eq!(v["scene"]["allow_inconsistent"], true);
    let earlier = dpd(dir.path(), &two_step_sweep(&scene, "aboba"));
    assert!(earlier.status.success(), "{earlier:?}");
    let sweep = two_step_sweep(&scene, scheme);
    refused(
        &dpd(dir.path(), &sweep),
        "--allow-inconsistent of dpd run, dpd sweep",
    );
    let out = dpd(dir.path(), &[&sweep[..], &[flag]].concat());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success()
            && stderr.contains("1 already in out.json (and 1 other points it keeps)"),
        "{stderr}"
    );
    let saved = std::fs::read_to_string(dir.path().join("out.json")).unwrap();
    let points = serde_json::from_str::<serde_json::Value>(&saved).unwrap()["points"].clone();
    let swept = points
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["scheme"] == scheme);
    assert_eq!(swept.count(), 2, "{saved}");
}

/// A run's last state written as a LAMMPS data file starts the next run; a data file LAMMPS
/// would refuse is refused with its line, and one whose pair coefficients the engine cannot
/// hold names the pair.
#[test]
fn a_data_file_written_by_a_run_starts_the_next() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "tiny.toml", TINY);
    let first = [
        "run",
        "--scene",
        &scene,
        "--write-data",
        "end.data",
        "--json",
    ];
    json(&dpd(dir.path(), &first));
    let text = std::fs::read_to_string(dir.path().join("end.data")).unwrap();
    assert!(
        text.contains("\n100 atoms\n") && text.contains("PairIJ Coeffs # dpd\n\n1 1 25 4.5 1\n")
    );
    let next = ["run", "--scene", &scene, "--init", "end.data", "--json"];
    let v = json(&dpd(dir.path(), &next));
    assert_eq!(v["stable"], true);
    // The file's coefficients, which the scene's a and gamma do not show, are in the report.
    assert_eq!(
        v["init_coefficients"],
        serde_json::json!({"PairIJ Coeffs # dpd": ["1 1 25 4.5 1"]}),
        "{v}"
    );
    // Without a scene file (whose n is 100) the file's 100 particles and box are the run's;
    // an `--n` or `--density` the file contradicts is refused, naming both.
    let alone = ["run", "--init", "end.data", "--time", "0.5", "--json"];
    let v = json(&dpd(dir.path(), &alone));
    let edges: Vec<f64> = serde_json::from_value(v["scene"]["box"].clone()).unwrap();
    let density = v["scene"]["density"].as_f64().unwrap();
    assert_eq!(
        (density * edges.iter().product::<f64>()).round(),
        100.0,
        "{v}"
    );
    let out = dpd(dir.path(), &[&alone[..], &["--n", "120"]].concat());
    refused(&out, "the file has 100 particles, the scene 120");
    let out = dpd(dir.path(), &[&alone[..], &["--density", "4"]].concat());
    refused(&out, "the file has 100 particles, the scene 133");
    let bad = write(
        dir.path(),
        "bad.data",
        &text.replace("1 1 25 4.5 1", "1 1 25 x 1"),
    );
    let out = dpd(dir.path(), &["run", "--scene", &scene, "--init", &bad]);
    refused(
        &out,
        "line 19 (section `PairIJ Coeffs`): `x` is not a finite number",
    );
    let hot = write(
        dir.path(),
        "hot.data",
        &text.replace("1 1 25 4.5 1", "1 1 25 9 1"),
    );
    // The file's friction is the system's: written again as it was read.
    let again = [
        "run",
        "--scene",
        &scene,
        "--init",
        &hot,
        "--write-data",
        "again.data",
    ];
    json(&dpd(dir.path(), &[&again[..], &["--json"]].concat()));
    let text = std::fs::read_to_string(dir.path().join("again.data")).unwrap();
    assert!(
        text.contains("PairIJ Coeffs # dpd\n\n1 1 25 9 1\n"),
        "{text}"
    );
    let out = dpd(
        dir.path(),
        &["run", "--scene", &scene, "--write-data", "end.gsd"],
    );
    refused(&out, "write_data");
}

/// A mixture's run prints each species' like-neighbour fraction and writes its species
/// profile as CSV, one column per species.
#[test]
fn a_mixture_prints_its_like_neighbours_and_writes_its_species_profile() {
    let dir = tempfile::tempdir().unwrap();
    let mixture = format!(
        "{TINY}like_neighbours = true\n[profile]\nbins = 3\n[[species]]\nname = \"A\"\n\
         fraction = 0.5\n[[species]]\nname = \"W\"\nfraction = 0.5\n[pairs]\n\
         A-A = {{ a = 25.0 }}\nW-W = {{ a = 25.0 }}\nA-W = {{ a = 40.0 }}\n"
    );
    let scene = write(dir.path(), "mixture.toml", &mixture);
    let out = dpd(
        dir.path(),
        &["run", "--scene", &scene, "--profile-dir", "p"],
    );
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("seed 1: like neighbours within r_c: A 0."),
        "{text}"
    );
    let csv = std::fs::read_to_string(dir.path().join("p/species-profile-seed1.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!((lines[0], lines.len()), ("z,A,W", 4), "{csv}");
}

#[test]
fn observables_are_switched_on_by_flags_as_by_tables() {
    // `--rdf ... --vacf-max-lag` give what the scene's [rdf] and [vacf] tables give, and a
    // flag's key overrides the table's. At n = 100 the box edge is 3.2: r_max must be <= 1.6.
    let dir = tempfile::tempdir().unwrap();
    let plain = write(dir.path(), "tiny.toml", TINY);
    let tables = write(
        dir.path(),
        "tables.toml",
        &format!("{TINY}[rdf]\nr_max = 1.5\nbins = 30\n[vacf]\nmax_lag = 0.2\n"),
    );
    let run = |scene: &str, flags: &[&str]| {
        let mut args = vec!["run", "--scene", scene, "--json"];
        args.extend(flags);
        json(&dpd(dir.path(), &args))
    };
    let flags = [
        "--rdf",
        "--rdf-r-max",
        "1.5",
        "--rdf-bins",
        "20",
        "--vacf-max-lag",
        "0.2",
    ];
    let by_flags = run(&plain, &flags);
    let by_tables = run(&tables, &["--rdf-bins", "20"]);
    let rdf = by_flags["results"][0]["rdf"].as_array().unwrap();
    assert_eq!(rdf.len(), 20);
    assert_eq!(by_flags["scene"]["rdf"], by_tables["scene"]["rdf"]);
    assert_eq!(
        by_flags["results"][0]["rdf"],
        by_tables["results"][0]["rdf"]
    );
    assert!(by_flags["diffusion"].as_f64().unwrap() > 0.0, "{by_flags}");
    assert_eq!(by_flags["diffusion"], by_tables["diffusion"]);
    assert!(run(&plain, &[])["results"][0].get("rdf").is_none());
    let out = dpd(dir.path(), &["run", "--scene", &plain, "--rdf-r-max", "9"]);
    refused(&out, "rdf.r_max");
    let out = dpd(dir.path(), &["run", "--scene", &plain, "--init-reset"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--init"));
}

/// A melt runs a scheme with bonds on an inner step, prints its chains, writes its last state
/// with its bonds, and the next run starts from that file with the same bonds (chains found
/// again); `B[bond]` on a scene without bonds is refused, naming the group.
#[test]
fn a_melt_runs_an_mts_scheme_and_restarts_from_its_data_file() {
    let dir = tempfile::tempdir().unwrap();
    let melt = write(
        dir.path(),
        "melt.toml",
        &format!(
            "{TINY}[[bond_types]]\nname = \"s\"\nstyle = \"harmonic\"\nk = 2.0\n\
             [[molecules]]\nlength = 5\ncount = 12\nbond = \"s\"\n"
        ),
    );
    let mts = "B[pair](1/2) (B[bond](1/4) A(1/2) B[bond](1/4))^2 O B[pair](1/2)";
    let first = [
        "run",
        "--scene",
        &melt,
        "--scheme",
        mts,
        "--write-data",
        "m.data",
    ];
    let out = dpd(dir.path(), &first);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("12 linear chains: <R_ee^2>"), "{text}");
    let data = std::fs::read_to_string(dir.path().join("m.data")).unwrap();
    assert!(data.contains("\n48 bonds\n") && data.contains("Bond Coeffs # harmonic\n\n1 2 0\n"));
    let plain = write(dir.path(), "plain.toml", TINY);
    let next = [
        "run", "--scene", &plain, "--init", "m.data", "--scheme", mts, "--json",
    ];
    let v = json(&dpd(dir.path(), &next));
    assert_eq!(v["results"][0]["chains"]["chains"], 12, "{v}");
    let out = dpd(dir.path(), &["run", "--scene", &plain, "--scheme", mts]);
    refused(
        &out,
        "it applies B[bond], the bonded forces (bonds and angles), which this system",
    );
}

/// A FENE bond stretched to its R0 is a blow-up whose error names the bond, and no other result
/// is lost: a sweep from dt = 0.01 (stable) to 0.3 (where the melt blows up at its first step)
/// keeps both points in its results file, and `dpd run --runs 2 --json` at 0.3 reports each
/// run with its bond.
#[test]
fn a_fene_overstretch_names_the_bond_and_loses_no_other_result() {
    let dir = tempfile::tempdir().unwrap();
    let melt = write(
        dir.path(),
        "fene.toml",
        &format!(
            "{TINY}[[bond_types]]\nname = \"f\"\nstyle = \"fene\"\nk = 30.0\nr_max = 1.5\n\
             [[molecules]]\nlength = 5\ncount = 10\nbond = \"f\"\n"
        ),
    );
    let sweep = [
        "sweep",
        "--scene",
        &melt,
        "--schemes",
        "vv",
        "--dt-min",
        "0.01",
        "--dt-max",
        "0.3",
        "--dt-factor",
        "30",
        "--json",
        "s.json",
    ];
    let out = dpd(dir.path(), &sweep);
    assert!(out.status.success(), "{out:?}");
    let text = std::fs::read_to_string(dir.path().join("s.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let points = v["points"].as_array().unwrap();
    let at = |dt: f64| {
        let found = points.iter().find(|p| p["scheme"] == "vv" && p["dt"] == dt);
        found.unwrap_or_else(|| panic!("no vv point at dt = {dt}: {v}"))
    };
    assert_eq!(at(0.01)["stable"], true);
    assert_eq!(at(0.01)["chains"]["chains"], 10);
    let fene = "reached length";
    let error = at(0.3)["error"].as_str().unwrap();
    assert!(error.contains("bond ") && error.contains(fene), "{error}");
    let run = [
        "run", "--scene", &melt, "--scheme", "vv", "--dt", "0.3", "--runs", "2", "--json",
    ];
    let v = json(&dpd(dir.path(), &run));
    let results = v["results"].as_array().unwrap();
    assert_eq!(results.len(), 2, "{v}");
    for r in results {
        assert!(r["error"].as_str().unwrap().contains(fene), "{r}");
    }
}
