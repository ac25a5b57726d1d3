//! Every pairwise sub-flow conserves total momentum to rounding error.
mod common;

use dpd_core::{Params, System};

#[test]
fn pairwise_flows_conserve_momentum_over_1e4_steps() {
    for flow in common::pairwise_flows() {
        // A small box with unequal masses and two types, so that nothing cancels by symmetry.
        let sys = common::system(
            120,
            3.0,
            Params::builder()
                .a_matrix(vec![vec![25.0, 40.0], vec![40.0, 25.0]])
                .gamma(4.5),
            0.02,
            11,
        );
        let n = sys.len();
        let masses: Vec<f64> = (0..n).map(|i| 0.5 + (i % 3) as f64).collect();
        let kinds: Vec<u16> = (0..n).map(|i| (i % 2) as u16).collect();
        let momenta: Vec<_> = sys
            .momenta()
            .iter()
            .zip(&masses)
            .map(|(p, m)| p * m.sqrt())
            .collect();
        let mut sys = System::builder(
            sys.params().clone(),
            *sys.boundary(),
            sys.positions().to_vec(),
        )
        .momenta(momenta)
        .masses(masses)
        .kinds(kinds)
        .dt(0.02)
        .seed(5)
        .build()
        .unwrap();
        let p0 = sys.total_momentum();
        sys.advance(&flow, 10_000).unwrap();
        let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
        let drift = (sys.total_momentum() - p0).norm() / scale;
        assert!(
            drift < 1e-12,
            "{}: relative momentum change {drift:e}",
            flow.0
        );
    }
}
