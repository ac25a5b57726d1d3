//! `dpd design` on the two families of issue 23: Yoshida's triple jump comes out of the
//! order conditions, and the free BABAB family is optimised over its parameter.

use dpd_ir::design::design;
use dpd_ir::lang::compile_family;

#[test]
fn yoshida_x0_is_the_fourth_order_member_of_the_triple_jump_family() {
    let f = compile_family("param x in -2..2; S((1 - x)/2) S(x) S((1 - x)/2) O").unwrap();
    let d = design(&f, &[]).unwrap();
    assert_eq!(d.generic_orders.0, 2);
    let x0 = -(2f64.cbrt()) / (2.0 - 2f64.cbrt());
    let best = &d.solutions[0];
    assert_eq!(best.deterministic_order, 4, "{d:#?}");
    assert_eq!(best.freedom, 0);
    assert!(
        (best.parameters[0].1 - x0).abs() < 1e-9,
        "{:?}",
        best.parameters
    );
    assert_eq!(d.solutions.len(), 1, "the cubic has one real root: {d:#?}");
}

#[test]
fn the_free_babab_family_is_minimised_over_its_parameter() {
    let f = compile_family("param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O").unwrap();
    let d = design(&f, &[vec![0.1932]]).unwrap();
    let best = &d.solutions[0];
    assert!(best.freedom == 1, "{d:#?}");
    let norm = |m: &dpd_ir::design::Member| m.invariant_measure_error_norm.unwrap_or(0.0);
    // the optimum is no worse than any notable point, l = 1/4 and l = 1/6 among them
    assert!(d.notable.iter().any(|m| m.parameters[0].1 == 0.25));
    assert!(d
        .notable
        .iter()
        .any(|m| (m.parameters[0].1 - 1.0 / 6.0).abs() < 1e-15));
    for m in &d.notable {
        assert!(norm(best) <= norm(m) + 1e-12, "{best:?} vs {m:?}");
    }
}
