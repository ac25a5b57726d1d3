//! What a user crate that depends only on `dpd` writes: build a system, run a generated scheme,
//! read the program of a scheme exported with `allow_inconsistent`. An integration test is a
//! crate of its own that sees `dpd` as a dependency, as a user's crate does; these were trybuild
//! pass cases, which made trybuild build every dependency a second time (see `tests/ui.rs`).

use dpd::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd::{Params, Scheme, System};

/// BAOOAB on 100 particles for 200 steps: every piece conserves total momentum, so it changes
/// only by rounding (about 1e-14 per step for momenta of order 1).
#[test]
fn generated_baooab_runs_and_conserves_momentum() {
    let n = 100;
    let params = Params::builder().gamma(4.5).build().unwrap();
    let bx = cubic_box(n, 3.0).unwrap();
    let q = uniform_positions(&bx, n, 1);
    let p = maxwell_momenta(&vec![1.0; n], params.kbt(), 1);
    let mut sys = System::builder(params, bx, q)
        .momenta(p)
        .dt(0.02)
        .seed(1)
        .build()
        .unwrap();
    let scheme = dpd::dpd_scheme!("BAOOAB");
    assert_eq!(scheme.name(), "BAOOAB");
    let before = sys.total_momentum();
    sys.advance(&scheme, 200).unwrap();
    assert_eq!(sys.step(), 200);
    let drift = (sys.total_momentum() - before).norm();
    assert!(drift < 1e-10, "total momentum changed by {drift}");
}

/// M-Shardlow-1 as published by Yamada et al. (x0 = +2^(1/3)/(2 - 2^(1/3)), the wrong sign):
/// its A coefficients sum to about 4.405, and `allow_inconsistent` accepts it so that the
/// published error can be reproduced; the analysis still reports it inconsistent.
#[test]
fn allow_inconsistent_keeps_the_published_m_shardlow_1() {
    let m1 = dpd::dpd_scheme!(
        r"
        let x0 = 2^(1/3)/(2 - 2^(1/3));
        S(x1) S(x0) S(x1) Ob
        ",
        name = "m-shardlow-1",
        allow_inconsistent,
    );
    assert_eq!(m1.name(), "m-shardlow-1");
    let analysis = m1.program().unwrap().analysis();
    assert!(!analysis.consistent);
    assert!((analysis.coefficient_sums.a - 4.405).abs() < 1e-3);
}
