//! Every pairwise sub-flow conserves total momentum to rounding error.
use super::common;

use dpd_core::params::ParamsBuilder;
use dpd_core::{Params, System};

/// Two types with one friction and cut-off, and with a friction and cut-off per pair of types
/// (whose sweeps read the pair's types).
fn two_types() -> [ParamsBuilder; 2] {
    let a = Params::builder()
        .a_matrix(vec![vec![25.0, 40.0], vec![40.0, 25.0]])
        .gamma(4.5);
    let by_type = a
        .clone()
        .gamma_matrix(vec![vec![4.5, 20.0], vec![20.0, 0.5]])
        .rc_matrix(vec![vec![1.0, 0.8], vec![0.8, 0.9]]);
    [a, by_type]
}

#[test]
fn pairwise_flows_conserve_momentum_over_1e4_steps() {
    for (flow, params) in (common::pairwise_flows().into_iter()).flat_map(|flow| {
        [(flow.0, flow.1), (flow.0, flow.1)]
            .into_iter()
            .zip(two_types())
    }) {
        let flow = common::Steps(flow.0, flow.1);
        // A small box with unequal masses and two types, so that nothing cancels by symmetry.
        let sys = common::system(120, 3.0, params, 0.02, 11);
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
            "{} ({:?}): relative momentum change {drift:e}",
            flow.0,
            sys.params()
        );
    }
}
