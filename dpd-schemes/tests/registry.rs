//! Looking schemes up by name, resolving scheme strings, and the listing.
use dpd_schemes::registry::{entries, lookup, resolve};

#[test]
fn the_issue_names_resolve_ignoring_case_and_aliases() {
    for name in [
        "vv",
        "dpd-s1",
        "dpd-s2",
        "aboba",
        "baoab",
        "baooab",
        "obabo",
        "sas",
        "asa",
        "m-shardlow-1",
        "m-shardlow-2",
        "prk3-ruth",
        "prk3-iwatsu-a",
        "prk3-iwatsu-b",
        "setd",
        "msetd",
    ] {
        assert_eq!(lookup(name).unwrap().name, name);
        assert_eq!(lookup(&name.to_uppercase()).unwrap().name, name);
    }
    assert_eq!(lookup("DPD-Trotter").unwrap().name, "sas");
    assert_eq!(lookup(" Velocity_Verlet ").unwrap().name, "vv");
    for e in entries() {
        assert_eq!(
            e.scheme().name(),
            e.name,
            "a scheme reports its registry name"
        );
    }
}

#[test]
fn unknown_names_list_close_matches() {
    let err = lookup("abobaa").unwrap_err();
    assert_eq!(err.close_matches[0], "aboba");
    assert!(err.to_string().contains("did you mean aboba"), "{err}");
    let err = lookup("iwatsu").unwrap_err();
    assert!(err.close_matches.contains(&"prk3-iwatsu-a"), "{err}");
    let err = lookup("zzzzzzzzzzzz").unwrap_err();
    assert!(err.close_matches.is_empty());
    assert!(
        err.to_string().contains("registered schemes: vv, "),
        "{err}"
    );
}

#[test]
fn resolve_falls_back_to_the_scheme_language() {
    assert_eq!(resolve("BAOAB").unwrap().name(), "baoab");
    let custom = resolve("A B O B A O").unwrap();
    assert_eq!(
        custom.program().unwrap().to_string(),
        "A(1/2) B(1/2) O(1/2) B(1/2) A(1/2) O(1/2)"
    );
    let Err(err) = resolve("abobba") else {
        panic!("abobba is neither a name nor a scheme string")
    };
    let text = err.to_string();
    assert!(
        text.contains("not a registered scheme name either: 'abobba'; did you mean aboba"),
        "{text}"
    );
    assert!(text.contains("not a valid scheme string"), "{text}");
    assert!(!err.diagnostics.is_empty());
}

#[test]
fn listing_rows_serialise_with_the_documented_fields() {
    let rows: Vec<_> = entries().iter().map(|e| e.row()).collect();
    let json = serde_json::to_value(&rows).unwrap();
    let first = &json[0];
    for field in [
        "name",
        "aliases",
        "sequence",
        "force_evaluations_per_step",
        "pair_distance_evaluations_per_step",
        "deterministic_order",
        "invariant_measure_order",
        "symmetric",
        "consistent",
        "source",
    ] {
        assert!(first.get(field).is_some(), "missing {field}");
    }
    assert_eq!(first["sequence"], "F(1/2) A(1) F(1/2)");
    assert!(first["invariant_measure_order"].is_null());
    let aboba = &json[entries().iter().position(|e| e.name == "aboba").unwrap()];
    assert_eq!(aboba["invariant_measure_order"], 2);
    let setd = lookup("setd").unwrap().row();
    assert!(setd.hand_written && setd.invariant_measure_order.is_none());
}
