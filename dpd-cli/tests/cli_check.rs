//! `dpd check` and `dpd orderings`: the JSON they print and the published results they
//! reproduce.
use super::cli_support;

use cli_support::{dpd, has_keys, json, refused};

fn check(scheme: &str) -> serde_json::Value {
    let v = json(&dpd(
        std::env::temp_dir().as_path(),
        &["check", scheme, "--json"],
    ));
    has_keys(
        &v,
        &[
            "consistent",
            "coefficient_sums",
            "deterministic_order",
            "invariant_measure_order",
            "symmetric",
            "force_evaluations_per_step",
        ],
    );
    v
}

#[test]
fn aboba_is_second_order_symmetric_with_one_force_evaluation() {
    let v = check("aboba");
    assert_eq!(v["consistent"], true);
    assert_eq!(v["deterministic_order"], 2);
    assert_eq!(v["invariant_measure_order"], 2);
    assert_eq!(v["symmetric"], true);
    assert_eq!(v["force_evaluations_per_step"], 1);
    assert_eq!(v["coefficient_sums"]["a"], 1.0);
}

#[test]
fn abo_is_first_order_and_not_symmetric() {
    let v = check("ABO");
    assert_eq!(v["consistent"], true);
    assert_eq!(v["invariant_measure_order"], 1);
    assert_eq!(v["symmetric"], false);
}

#[test]
fn velocity_verlet_has_no_invariant_measure_bound() {
    let v = check("vv");
    assert_eq!(v["consistent"], true);
    assert!(v["invariant_measure_order"].is_null());
    assert_eq!(v["force_evaluations_per_step"], 1);
}

#[test]
fn m_shardlow_1_is_reported_inconsistent_not_refused() {
    // As published: x0 = +2^(1/3)/(2 - 2^(1/3)), the negative of the Yoshida constant; by
    // registry name and as a string.
    for scheme in ["m-shardlow-1", "S(x1) S(-x0) S(x1) Ob"] {
        let v = check(scheme);
        assert_eq!(v["consistent"], false);
        assert_eq!(v["deterministic_order"], 0);
        let a = v["coefficient_sums"]["a"].as_f64().unwrap();
        assert!((a - 4.405).abs() < 1e-3, "{a}");
        assert_eq!(v["force_evaluations_per_step"], 3);
    }
}

#[test]
fn a_scheme_that_does_not_parse_is_bad_input() {
    refused(
        &dpd(std::env::temp_dir().as_path(), &["check", "ABX"]),
        "ABX",
    );
}

#[test]
fn orderings_of_length_three_are_the_six_permutations() {
    let v = json(&dpd(
        std::env::temp_dir().as_path(),
        &["orderings", "--max-len", "3", "--json"],
    ));
    let list = v.as_array().unwrap();
    assert_eq!(list.len(), 6);
    for o in list {
        has_keys(
            o,
            &[
                "scheme",
                "deterministic_order",
                "invariant_measure_order",
                "force_evaluations_per_step",
                "pair_distance_evaluations_per_step",
                "symmetric",
            ],
        );
    }
    refused(
        &dpd(
            std::env::temp_dir().as_path(),
            &["orderings", "--max-len", "0"],
        ),
        "max-len",
    );
}
