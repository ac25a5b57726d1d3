//! The pairwise adaptive Langevin thermostat (letters Oa and Xi, PAdL): its invariant measure
//! (xi Gaussian around 1 with variance k_B T / mu, k_B T_K = k_B T), its claim (the kinetic
//! temperature held at a step where ABOBA's drifts), and what it needs.
mod common;

use dpd_core::observe::{block_mean, kinetic_temperature};
use dpd_core::reference::Aboba;
use dpd_core::{AdvanceError, DynScheme, Params, Scheme, System};

/// PAdL in the ordering of BAOAB, xi updated around the adaptive sweep.
const PADL: &str = "B A Xi(1/2) Oa Xi(1/2) A B";

fn compiled(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

/// `n` particles at density 3 (a = 25, k_B T = 1) at friction `gamma` with thermostat mass
/// `mu`.
fn adaptive_box(n: usize, gamma: f64, mu: f64, dt: f64, seed: u64) -> System {
    let params = Params::builder().gamma(gamma).thermostat_mass(mu);
    common::system(n, 3.0, params, dt, seed)
}

/// After `skip` steps, per step of the next `steps`: xi and k_B T_K.
fn series(sys: &mut System, scheme: &dyn Scheme, skip: u64, steps: u64) -> (Vec<f64>, Vec<f64>) {
    sys.advance(scheme, skip).unwrap();
    let (mut xi, mut tk) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        sys.advance(scheme, 1).unwrap();
        xi.push(sys.xi());
        tk.push(kinetic_temperature(sys));
    }
    (xi, tk)
}

/// The invariant density `exp(-H / kT) exp(-mu (xi - 1)^2 / (2 kT))` (flow/adaptive.rs): xi has
/// mean 1 and variance kT / mu = 0.04, and k_B T_K = k_B T. N = 250, gamma = 4.5, mu = 25, at
/// dt = 0.01 (short against xi's oscillation, whose frequency grows as sqrt(gamma^2 N / mu):
/// mu = 1 at N = 500 blew up at dt = 0.02), 200 time units after 20. Measured over 300 units:
/// xi 1.0006 +- 0.0032, variance 0.0381 +- 0.0013, k_B T_K 0.9989 +- 0.0013; the bounds below
/// are about 3 standard errors of 200 units (0.02, 12 %, 0.5 %). A factor missing from the
/// feedback (gamma, the weight, the reduced mass 2) changes the variance by that factor, a
/// wrong sign sends xi away.
#[test]
fn xi_and_the_kinetic_temperature_sample_their_invariant_measure() {
    let mut sys = adaptive_box(250, 4.5, 25.0, 0.01, 3);
    let (xi, tk) = series(&mut sys, &compiled(PADL), 2000, 20_000);
    let (mean, mean_err) = block_mean(&xi, 20).unwrap();
    let squares: Vec<f64> = xi.iter().map(|x| (x - 1.0) * (x - 1.0)).collect();
    let (var, var_err) = block_mean(&squares, 20).unwrap();
    let (t, t_err) = block_mean(&tk, 20).unwrap();
    assert!((mean - 1.0).abs() < 0.02, "xi {mean} +- {mean_err}");
    assert!((var / 0.04 - 1.0).abs() < 0.12, "var {var} +- {var_err}");
    assert!((t - 1.0).abs() < 0.005, "kT_K {t} +- {t_err}");
}

/// PAdL's claim: the feedback holds the pairs' kinetic temperature where a fixed friction
/// cannot. At dt = 0.12, gamma = 4.5 (N = 250, mu = 200, 150 time units after 30), in the same
/// box: measured k_B T_K 1.66 +- 0.01 for ABOBA, 1.36 for PAdL in ABOBA's ordering, 0.79 in
/// BAOAB's. Both adaptive errors must stay below 3/4 of ABOBA's (a loose bound: the feedback
/// sets the mean of sum gamma w_D (u^2 - kT mu_ij) at the Xi stages, not T_K at the step's end).
#[test]
fn the_kinetic_temperature_stays_closer_to_k_b_t_than_abobas() {
    let dt = 0.12;
    let error = |scheme: &dyn Scheme| {
        let mut sys = adaptive_box(250, 4.5, 200.0, dt, 5);
        let (_, tk) = series(&mut sys, scheme, 250, 1250);
        (tk.iter().sum::<f64>() / tk.len() as f64 - 1.0).abs()
    };
    let aboba = error(&Aboba);
    for padl in [PADL, "A(1/2) B(1/2) Xi(1/2) Oa Xi(1/2) B(1/2) A(1/2)"] {
        let e = error(&compiled(padl));
        assert!(e < 0.75 * aboba, "{padl}: |T_K - 1| {e}, ABOBA's {aboba}");
    }
}

/// A scheme with Xi needs the thermostat mass, and says so by name; Oa at xi = 1 with a
/// frozen xi is not a scheme (the language refuses Oa without Xi).
#[test]
fn a_scheme_with_xi_needs_a_thermostat_mass() {
    let mut sys = common::standard_box(4.5, 0.04, 1);
    match sys.advance(&compiled(PADL), 1) {
        Err(AdvanceError::Scheme(e)) => {
            assert_eq!(e.field, "thermostat_mass", "{e}");
            assert!(e.to_string().contains("has Xi"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    let e = DynScheme::compile("BAOaAB", "BAOaAB", &Default::default()).unwrap_err();
    assert!(format!("{e:?}").contains("Oa needs an Xi stage"), "{e:?}");
}
