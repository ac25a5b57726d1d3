//! The exact pairwise O sweep reaches and keeps the stationary variance k_B T / m_ij of the
//! relative normal velocity, across tau*h from 0 to 1e6.
use super::common;

use dpd_core::flow::ou;
use dpd_core::{Params, Scheme, SweepOrder, System};

/// `pairs` isolated pairs at separation `r = 0.5` (lattice spacing 3 r_c, so pairs do not
/// interact with each other), masses 1 and 3 (m_ij = 3/4), zero initial velocities.
fn isolated_pairs(pairs: usize, gamma: f64, dt: f64, seed: u64) -> System {
    let (bx, q) = common::isolated_pairs(pairs);
    let masses = (0..2 * pairs)
        .map(|i| if i % 2 == 0 { 1.0 } else { 3.0 })
        .collect();
    System::builder(Params::builder().gamma(gamma).build().unwrap(), bx, q)
        .masses(masses)
        .dt(dt)
        .seed(seed)
        .build()
        .unwrap()
}

/// Mean square of the relative normal velocity over all pairs (particles `2k` and `2k + 1`
/// by id; the storage order changes at list builds).
fn mean_square_u(sys: &System) -> f64 {
    let (q, p, m) = (sys.positions(), sys.momenta(), sys.masses());
    let mut at = vec![0; sys.len()];
    for (k, &id) in sys.ids().iter().enumerate() {
        at[id as usize] = k;
    }
    let n = sys.len() / 2;
    (0..n)
        .map(|k| {
            let (i, j) = (at[2 * k], at[2 * k + 1]);
            let e = sys.boundary().min_image(q[i] - q[j]).normalize();
            let u = e.dot(&(p[i] / m[i] - p[j] / m[j]));
            u * u
        })
        .sum::<f64>()
        / n as f64
}

/// One exact O sweep of length dt per step, alternating direction.
struct Sweeps;
impl Scheme for Sweeps {
    fn name(&self) -> &str {
        "O"
    }
    fn step(&self, sys: &mut System) {
        let order = if sys.step().is_multiple_of(2) {
            SweepOrder::Forward
        } else {
            SweepOrder::Reverse
        };
        ou(sys, sys.dt(), 0, order);
    }
}

#[test]
fn exact_ou_reaches_stationary_variance() {
    // tau = gamma w_D(r) / m_ij with w_D(0.5) = 0.25 and 1/m_ij = 4/3: tau = gamma / 3.
    let dt = 0.01;
    // k_B T / m_ij
    let target = 4.0 / 3.0;
    // 20000 pairs: the sample variance of 20000 normals has relative standard error
    // sqrt(2/20000) = 1 %, so a 5 % tolerance is five standard errors.
    let pairs = 20_000;
    // tau h = 0 (no friction): the sweep leaves the pairs at rest.
    let mut sys = isolated_pairs(pairs, 0.0, dt, 3);
    sys.advance(&Sweeps, 10).unwrap();
    assert_eq!(mean_square_u(&sys), 0.0);
    for tau_h in [1e-6, 1.0, 1e4, 1e6] {
        let gamma = 3.0 * tau_h / dt;
        let mut sys = isolated_pairs(pairs, gamma, dt, 3);
        // From rest, n steps give variance target (1 - exp(-2 n tau h)) exactly. At
        // tau h = 1e-6 relaxation takes millions of steps: check that transient instead.
        let n = if tau_h < 1e-3 { 1000 } else { 20 };
        sys.advance(&Sweeps, n).unwrap();
        let expected = target * -(-2.0 * n as f64 * tau_h).exp_m1();
        let got = mean_square_u(&sys);
        assert!(
            (got / expected - 1.0).abs() < 0.05,
            "tau h {tau_h}: {got} vs {expected}"
        );
        if tau_h >= 1.0 {
            // Stationarity: further sweeps keep the variance.
            sys.advance(&Sweeps, 5).unwrap();
            let got = mean_square_u(&sys);
            assert!(
                (got / target - 1.0).abs() < 0.05,
                "tau h {tau_h} kept: {got} vs {target}"
            );
        }
    }
}
