//! Force groups and repetition: the language (spelling, sharing, merging, errors), the cost
//! model, and the order analysis of multiple-time-stepping schemes against known results.

use dpd_ir::analysis::Analysis;
use dpd_ir::lang::{compile, compile_with, Diagnostic, Options};
use dpd_ir::program::Program;
use dpd_ir::{Evaluations, ForceGroup, SweepOrder};

fn ok(src: &str) -> Program {
    compile(src).unwrap_or_else(|e| panic!("{src}: {e:?}"))
}

fn lenient(src: &str) -> Program {
    let options = Options {
        allow_inconsistent: true,
    };
    compile_with(src, &options).unwrap_or_else(|e| panic!("{src}: {e:?}"))
}

/// The errors of `src`, which must not compile.
fn err(src: &str) -> Vec<Diagnostic> {
    match compile(src) {
        Ok(p) => panic!("{src} compiled to {p}"),
        Err(e) => e,
    }
}

/// The single error of `src`, which must contain `needle`; returns the text it points at.
fn one_err<'a>(src: &'a str, needle: &str) -> &'a str {
    let e = err(src);
    assert_eq!(e.len(), 1, "{src}: {e:?}");
    assert!(e[0].message.contains(needle), "{src}: {}", e[0].message);
    &src[e[0].span.clone()]
}

fn analysis(src: &str) -> Analysis {
    ok(src).analysis()
}

/// The example: pair forces on the outer step, bonds and drifts on an inner loop.
const RESPA: &str = "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)";

#[test]
fn a_repeated_inner_loop_expands_and_merges() {
    let p = ok(RESPA);
    assert_eq!(
        p.to_string(),
        "B[pair](1/2) B[bond](1/8) A(1/4) B[bond](1/4) A(1/4) B[bond](1/4) A(1/4) \
         B[bond](1/4) A(1/4) B[bond](1/8) O(1) B[pair](1/2)"
    );
    assert_eq!(p.unmerged_stages.len(), 15);
    // Letters without coefficients share per letter and group.
    assert_eq!(
        ok("B[pair] (B[bond] A B[bond])^4 O B[pair]").stages,
        p.stages
    );
    // The count may be a constant, and a sub-scheme may repeat with its parameters.
    assert_eq!(
        ok("let n = 4; B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^n O B[pair](1/2)").stages,
        p.stages
    );
    let def = "def R(c, n) = (B[bond](c/(2n)) A(c/n) B[bond](c/(2n)))^n;
               B[pair](1/2) R(1, 4) O B[pair](1/2)";
    assert_eq!(ok(def).stages, p.stages);
    // Repetitions nest.
    assert_eq!(
        ok("((B(1/8) A(1/4) B(1/8))^2)^2 O").stages,
        ok("(B(1/8) A(1/4) B(1/8))^4 O").stages
    );
    // The printed program compiles back to the same stages.
    assert_eq!(ok(&p.to_string()).stages, p.stages);
    assert!(
        ok("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 B[pair](1/2) O")
            .is_cyclically_symmetric()
    );
}

#[test]
fn a_parenthesis_after_a_letter_holds_steps_only_when_a_step_starts_it() {
    // `A (B A B)^2`: A with its default share, then the repetition.
    assert_eq!(
        ok("A(1/2) O (B(1/4) A(1/4) B(1/4))^2").to_string(),
        "A(1/2) O(1) B(1/4) A(1/4) B(1/2) A(1/4) B(1/4)"
    );
    assert_eq!(
        ok("A (B(1/2) A(1/4) B(1/2))^1 A(1/4) O").to_string(),
        "A(1/2) B(1/2) A(1/4) B(1/2) A(1/4) O(1)"
    );
    // `A((1/2))`: a coefficient in parentheses.
    assert_eq!(ok("A((1/2)) B O B A((1/2))").stages, ok("ABOBA").stages);
    assert_eq!(
        ok("(prk(b = [1/2, 1/2], bh = [1, 0], kick = B))^1 O")
            .stages
            .len(),
        4
    );
}

#[test]
fn groups_keep_their_kicks_apart() {
    let p = ok("B[pair](1/2) B[bond](1/2) A O A B[bond](1/2) B[pair](1/2)");
    let groups: Vec<Option<ForceGroup>> = p.stages.iter().map(|s| s.group).collect();
    assert_eq!(
        groups,
        [
            Some(ForceGroup::Pair),
            Some(ForceGroup::Bond),
            None,
            None,
            None,
            Some(ForceGroup::Bond),
            Some(ForceGroup::Pair)
        ]
    );
    // `B B[pair]` are two kicks of different forces and do not merge.
    assert_eq!(
        lenient("B(1/2) B[pair](1/2) A O").to_string(),
        "B(1/2) B[pair](1/2) A(1) O(1)"
    );
    assert_eq!(
        p.named_groups(),
        [ForceGroup::Pair, ForceGroup::Bond],
        "the groups a system must have"
    );
    assert!(ok("ABOBA").named_groups().is_empty());
    assert!(ok("ABOBA").applies(ForceGroup::Bond) && !ok("ATA").applies(ForceGroup::Bond));
    assert_eq!(ok("F[pair](1/2) A F[pair](1/2)").stages[0].stream, 0);
    // The group is serialized where a stage names one, and only there.
    let json = serde_json_of(&p);
    assert!(json.contains("\"group\":\"bond\""), "{json}");
    assert!(!serde_json_of(&ok("ABOBA")).contains("group"));
}

fn serde_json_of(p: &Program) -> String {
    serde_json::to_string(p).unwrap()
}

#[test]
fn bonded_evaluations_are_counted_apart_and_need_no_pair_table() {
    let e = ok(RESPA).evaluations_per_step();
    assert_eq!(
        e,
        Evaluations {
            force: 1,
            pair_distance: 1,
            bonded_force: 4,
        }
    );
    // Without groups a kick applies every force: on a system with bonds one evaluation each.
    for (src, bonded) in [
        ("ABOBA", 1),
        ("F(1/2) A F(1/2)", 1),
        ("BAOAB", 1),
        ("ATA", 0),
    ] {
        assert_eq!(ok(src).bonded_force_evaluations_per_step(), bonded, "{src}");
    }
    // Each drift of the inner loop needs a new bonded evaluation, never a new pair table.
    let inner = |n: usize| {
        ok(&format!(
            "B[pair](1/2) (B[bond](1/{}) A(1/{n}) B[bond](1/{}))^{n} B[pair](1/2) O",
            2 * n,
            2 * n
        ))
        .evaluations_per_step()
    };
    for n in 1..=6 {
        assert_eq!(
            inner(n),
            Evaluations {
                force: 1,
                pair_distance: 1,
                bonded_force: n
            }
        );
    }
}

#[test]
fn group_and_repetition_errors_point_at_their_source() {
    assert_eq!(
        one_err(
            "AB[bonds]OBA",
            "unknown force group 'bonds' at position 4; expected one of pair, bond"
        ),
        "bonds"
    );
    assert_eq!(one_err("A[pair] B O B A", "A takes no force group"), "pair");
    assert_eq!(one_err("ABO[pair]BA", "O takes no force group"), "pair");
    assert_eq!(
        one_err("F[bond](1/2) A F(1/2)", "F[bond] is not a sub-flow"),
        "bond"
    );
    assert_eq!(one_err("S[pair](1) O", "not of the sub-scheme S"), "pair");
    assert_eq!(one_err("B[](1) A O", "a force group name"), "]");
    assert_eq!(
        one_err("(A B)^0 O", "whole number from 1 to 10000, found 0"),
        "0"
    );
    assert_eq!(one_err("(A B)^(1/2) O", "found 1/2"), "1/2");
    assert_eq!(one_err("(A B)^x1 O", "whole number"), "x1");
    assert_eq!(one_err("(A B) O", "'^' and a count"), "O");
    assert_eq!(one_err("() A B O", "empty repetition"), "()");
    assert!(one_err("((A B)^100)^101 O", "more than 10000").starts_with("A"));
    // One error for a repeated mistake, not one per pass.
    assert_eq!(
        one_err("(O(-1) A B)^4 O(5)", "cannot run backwards"),
        "O(-1)"
    );
    assert_eq!(
        one_err(
            "(A(1/4) B(1/3))^3 O",
            "the A coefficients (A stages) sum to 3/4"
        ),
        "A(1/4)"
    );
    // A scheme that names groups checks each group's sum.
    let e = err("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^2 O B[pair](1/2)");
    let messages: Vec<&str> = e.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(e.len(), 2, "{messages:?}");
    assert!(messages[1]
        .contains("the B[bond] coefficients (B, B[bond] and F stages) sum to 1/2, not 1"));
    one_err("B[bond] A B[bond] O", "scheme has no conservative force");
    one_err(
        "B[pair](1/2) A B(1/2) O",
        "the B[bond] coefficients (B, B[bond] and F stages) sum to 1/2",
    );
    let e = err("(A let x = 1; B)^2 O");
    assert!(e[0].message.contains("'let' starts a definition"), "{e:?}");
}

/// r-RESPA (impulse multiple time stepping): the outer pair kicks around `n` velocity Verlet
/// steps of the bonded forces is a symmetric composition of exact flows, hence second order,
/// and not more, for every `n`.
#[test]
fn respa_is_deterministic_order_two_for_every_inner_count() {
    for n in 1..=6 {
        let src = format!(
            "B[pair](1/2) (B[bond](1/{}) A(1/{n}) B[bond](1/{}))^{n} B[pair](1/2)",
            2 * n,
            2 * n
        );
        let a = analysis(&src);
        assert!(a.consistent, "{src}");
        assert_eq!(
            (a.deterministic_order, a.deterministic_order_capped),
            (2, false),
            "{src}"
        );
        let sums = &a.coefficient_sums;
        assert_eq!((sums.a, sums.b, sums.bond), (1.0, 1.0, Some(1.0)));
        // With a thermostat in the middle the Hamiltonian part is the same.
        let thermostat = src.replacen("B[pair](1/2)", "B[pair](1/2) O", 1);
        assert_eq!(analysis(&thermostat).deterministic_order, 2, "{thermostat}");
    }
    assert_eq!(analysis(RESPA).deterministic_order, 2);
}

/// ABOBA with each half drift replaced by `n` Strang steps of the drift and the bonded kick,
/// drift-kick-drift or kick-drift-kick (MTS2 of docs/systems.md is the latter with `n = 2`,
/// MTS3 with `n = 1`), keeps ABOBA's invariant-measure order 2 (the inner loop's error enters
/// at degree 3, the outer B O B keeps L_1 in the ideal), and its deterministic order 2.
#[test]
fn an_mts_aboba_keeps_invariant_measure_order_two() {
    for n in 1..=3 {
        let (half, quarter) = (format!("1/{}", 2 * n), format!("1/{}", 4 * n));
        let inners = [
            format!("(A({quarter}) B[bond]({half}) A({quarter}))^{n}"),
            format!("(B[bond]({quarter}) A({half}) B[bond]({quarter}))^{n}"),
        ];
        for inner in inners {
            let src = format!("{inner} B[pair](1/2) O B[pair](1/2) {inner}");
            let a = analysis(&src);
            assert_eq!(a.invariant_measure_order, Some(2), "{src}");
            assert!(!a.invariant_measure_order_capped, "{src}");
            assert_eq!(a.deterministic_order, 2, "{src}");
        }
    }
}

/// Kicks of different groups commute, so a scheme whose groups always appear together
/// (`B[pair](c) B[bond](c)` for every `B(c)`, `F[pair](c) B[bond](c)` for every `F(c)`) is the
/// scheme without groups: the same deterministic and invariant-measure orders, also where
/// the kicks are not placed symmetrically (Ruth's third-order table, DPD-S1).
#[test]
fn groups_that_always_appear_together_give_the_orders_without_groups() {
    let together = |src: &str| {
        let p = ok(src);
        p.unmerged_stages
            .iter()
            .map(|s| {
                let c = s.coeff.to_string();
                match s.flow {
                    dpd_ir::Flow::B => format!("B[pair]({c}) B[bond]({c})"),
                    dpd_ir::Flow::F => format!("F[pair]({c}) B[bond]({c})"),
                    _ => {
                        let order = match s.order {
                            SweepOrder::Forward => ">",
                            SweepOrder::Reverse => "<",
                        };
                        let order = if s.flow.is_successive_sweep() {
                            order
                        } else {
                            ""
                        };
                        let letter = dpd_ir::lang::letters::spelling(s.flow);
                        format!("{letter}{order}({c})")
                    }
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    for src in [
        "ABOBA",
        "BAOAB",
        "ObBAB",
        "OBAB",
        "ABO",
        "BAOOAB",
        "B(7/24) A(2/3) B(3/4) A(-2/3) B(-1/24) A(1) O",
        "S(x1) S(x0) S(x1) O",
        "F(1/2) A F(1/2)",
        "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O",
    ] {
        let grouped = together(src);
        let (plain, split) = (analysis(src), analysis(&grouped));
        assert_eq!(
            (
                plain.consistent,
                plain.deterministic_order,
                plain.invariant_measure_order
            ),
            (
                split.consistent,
                split.deterministic_order,
                split.invariant_measure_order
            ),
            "{src} against {grouped}"
        );
        let bond = split.coefficient_sums.bond.unwrap();
        assert!((bond - 1.0).abs() < 1e-12, "{grouped}");
    }
    // Ruth's table is third order: the grouped form would lose that were the kicks not
    // known to commute.
    assert_eq!(
        analysis(&together("B(7/24) A(2/3) B(3/4) A(-2/3) B(-1/24) A(1)")).deterministic_order,
        3
    );
}

/// A scheme that names only the pair group is the scheme without groups on a system without
/// bonds: the same orders and error norms, every report but the names the same.
#[test]
fn a_pair_only_scheme_is_analysed_as_the_scheme_without_groups() {
    for (plain, pair) in [
        ("ABOBA", "A B[pair] O B[pair] A"),
        ("BAOAB", "B[pair] A O A B[pair]"),
        ("ObBAB", "Ob B[pair] A B[pair]"),
        ("TAT", "T(1/2) A B[pair](0) T(1/2)"),
    ] {
        let (a, b) = (analysis(plain), analysis(pair));
        assert_eq!(a.deterministic_order, b.deterministic_order, "{pair}");
        assert_eq!(
            a.invariant_measure_order, b.invariant_measure_order,
            "{pair}"
        );
        assert_eq!(
            a.invariant_measure_error_norm, b.invariant_measure_error_norm,
            "{pair}"
        );
        assert_eq!(b.coefficient_sums.bond, None);
    }
}
