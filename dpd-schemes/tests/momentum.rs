//! Pairwise schemes conserve total momentum to rounding error; the per-particle exponential
//! schemes do not, and their drift is reported.
use super::common;

use dpd_core::{Params, Scheme, System};
use dpd_schemes::registry::entries;
use dpd_schemes::stability::with_thermostat_friction;

/// 120 particles with unequal masses and two types, so that nothing cancels by symmetry.
fn mixed_box(scheme: &dyn Scheme) -> System {
    let sys = common::system(
        120,
        3.0,
        1.0,
        with_thermostat_friction(
            Params::builder()
                .a_matrix(vec![vec![25.0, 40.0], vec![40.0, 25.0]])
                .gamma(4.5)
                .collision_rate(common::COLLISION_RATE)
                .thermostat_mass(common::THERMOSTAT_MASS),
            scheme,
        ),
        0.01,
        11,
    );
    let n = sys.len();
    let masses: Vec<f64> = (0..n).map(|i| 0.5 + (i % 3) as f64).collect();
    let momenta = sys
        .momenta()
        .iter()
        .zip(&masses)
        .map(|(p, m)| p * m.sqrt())
        .collect();
    System::builder(
        sys.params().clone(),
        *sys.boundary(),
        sys.positions().to_vec(),
    )
    .momenta(momenta)
    .masses(masses)
    .kinds((0..n).map(|i| (i % 2) as u16).collect())
    .dt(0.01)
    .seed(5)
    .build()
    .unwrap()
}

#[test]
fn pairwise_schemes_conserve_total_momentum() {
    for e in entries() {
        let scheme = e.scheme();
        let mut sys = mixed_box(&*scheme);
        let p0 = sys.total_momentum();
        sys.advance(&*scheme, 1000).unwrap();
        let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
        let drift = (sys.total_momentum() - p0).norm() / scale;
        println!("{:>14}: relative momentum change {drift:.2e}", e.name);
        if e.claims().momentum_conserving {
            assert!(drift < 1e-12, "{}: {drift:e}", e.name);
        }
    }
}
